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
/// keep their order.
template<typename Record, typename Key>
void radixSortBy(std::vector<Record>& records, Key key)
{
  if (records.size() < 2)
    return;
  std::uint64_t differing = 0;
  const std::uint64_t first = key(records[0]);
  for (const Record& r : records)
    differing |= key(r) ^ first;
  constexpr int Bits = 11;
  constexpr std::uint64_t Mask = (1u << Bits) - 1;
  std::vector<Record> scratch(records.size());
  std::array<std::size_t, (1u << Bits) + 1> count;
  for (int shift = 0; shift < 64; shift += Bits)
  {
    if (((differing >> shift) & Mask) == 0)
      continue; // every key has the same digit here
    count.fill(0);
    for (const Record& r : records)
      ++count[((key(r) >> shift) & Mask) + 1];
    for (std::size_t i = 1; i < count.size(); ++i)
      count[i] += count[i - 1];
    for (const Record& r : records)
      scratch[count[(key(r) >> shift) & Mask]++] = r;
    records.swap(scratch);
  }
}

} // namespace vbr

#endif
