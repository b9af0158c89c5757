// Sorting of vertices as packed 64-bit keys (KeyPacker, Geometry.h): grid coordinates are
// non-negative and below 2^21, so three of them fit in one key whose integer order is the
// lexicographic order.
#ifndef vbr_RadixSort_h
#define vbr_RadixSort_h

#include "Geometry.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace vbr
{

/// LSD radix sort on 11-bit digits (a small count table that stays in cache); passes whose
/// digit is the same for all keys are skipped.
inline void radixSort(std::vector<std::uint64_t>& keys)
{
  if (keys.size() < 2)
    return;
  std::uint64_t differing = 0;
  for (std::uint64_t k : keys)
    differing |= k ^ keys[0];
  constexpr int Bits = 11;
  constexpr std::uint64_t Mask = (1u << Bits) - 1;
  // Scratch space without zero-filling: every slot is written before it is read.
  std::unique_ptr<std::uint64_t[]> scratch(new std::uint64_t[keys.size()]);
  std::uint64_t* from = keys.data();
  std::uint64_t* to = scratch.get();
  std::array<std::size_t, (1u << Bits) + 1> count;
  for (int shift = 0; shift < 64; shift += Bits)
  {
    if (((differing >> shift) & Mask) == 0)
      continue; // every key has the same digit here
    count.fill(0);
    for (std::size_t i = 0; i < keys.size(); ++i)
      ++count[((from[i] >> shift) & Mask) + 1];
    for (std::size_t i = 1; i < count.size(); ++i)
      count[i] += count[i - 1];
    for (std::size_t i = 0; i < keys.size(); ++i)
      to[count[(from[i] >> shift) & Mask]++] = from[i];
    std::swap(from, to);
  }
  if (from != keys.data())
    std::copy(from, from + keys.size(), keys.data());
}

/// The same sort of records by a 64-bit key, `key(record)`: stable, so records of equal keys
/// keep their order. Only the bits where keys differ are sorted, in as few passes of at most
/// 12-bit digits as they need (grid keys of 24 bits take two passes, not three).
template<typename Record, typename Key>
void radixSortBy(std::vector<Record>& records, Key key)
{
  if (records.size() < 2)
    return;
  std::uint64_t differing = 0;
  const std::uint64_t first = key(records[0]);
  for (const Record& r : records)
    differing |= key(r) ^ first;
  if (differing == 0)
    return;
  int low = countTrailingZeros(differing), high = 64;
  while (((differing >> (high - 1)) & 1) == 0)
    --high;
  const int passes = (high - low + 11) / 12;
  const int bits = (high - low + passes - 1) / passes;
  const std::uint64_t mask = (std::uint64_t(1) << bits) - 1;
  std::vector<Record> scratch(records.size());
  std::vector<std::size_t> count((std::size_t(1) << bits) + 1);
  for (int shift = low; shift < high; shift += bits)
  {
    std::fill(count.begin(), count.end(), 0);
    for (const Record& r : records)
      ++count[((key(r) >> shift) & mask) + 1];
    for (std::size_t i = 1; i < count.size(); ++i)
      count[i] += count[i - 1];
    for (const Record& r : records)
      scratch[count[(key(r) >> shift) & mask]++] = r;
    records.swap(scratch);
  }
}

} // namespace vbr

#endif
