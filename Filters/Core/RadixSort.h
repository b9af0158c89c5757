// Sorting of vertices as packed 64-bit keys: grid coordinates are non-negative and below
// 2^21, so three of them fit in one key whose integer order is the lexicographic order.
#ifndef vbr_RadixSort_h
#define vbr_RadixSort_h

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace vbr
{

constexpr std::int32_t PackedCoordinateLimit = 1 << 21;

/// Packs three non-negative coordinates below 2^bits into one key, the first one highest.
/// The fewer the bits, the fewer radix passes.
struct KeyPacker
{
  int bits = 21;

  /// The narrowest packer for coordinates in [0, maxCoordinate].
  static KeyPacker forMaximum(std::int32_t maxCoordinate)
  {
    KeyPacker p;
    p.bits = 1;
    while (p.bits < 21 && (std::int64_t(1) << p.bits) <= maxCoordinate)
      ++p.bits;
    return p;
  }
  std::uint64_t pack(std::int32_t a, std::int32_t b, std::int32_t c) const
  {
    return (static_cast<std::uint64_t>(a) << (2 * this->bits)) |
      (static_cast<std::uint64_t>(b) << this->bits) | static_cast<std::uint64_t>(c);
  }
  std::array<std::int32_t, 3> unpack(std::uint64_t k) const
  {
    const std::uint64_t mask = (std::uint64_t(1) << this->bits) - 1;
    return { static_cast<std::int32_t>(k >> (2 * this->bits)),
      static_cast<std::int32_t>((k >> this->bits) & mask),
      static_cast<std::int32_t>(k & mask) };
  }
  /// Third coordinate of a key.
  std::int32_t last(std::uint64_t k) const
  {
    return static_cast<std::int32_t>(k & ((std::uint64_t(1) << this->bits) - 1));
  }
};

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

} // namespace vbr

#endif
