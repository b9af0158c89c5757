// The storage of a voxel set: one bit per voxel, rows of 64-bit words along x, rows ordered
// by (y, z), the last word of a row padded with zeros so that word-wide operations (the XORs
// of EVM extraction, the surfel scans) need no masks. Counting is a popcount per word.

#include "BitVolume.h"

#include "Geometry.h"

#include <stdexcept>

namespace vbr
{

BitVolume::BitVolume(std::int32_t nx, std::int32_t ny, std::int32_t nz)
  : Dims{ nx, ny, nz }
{
  if (nx < 0 || ny < 0 || nz < 0)
    throw std::invalid_argument("BitVolume: negative dimension");
  this->RowWords = (static_cast<std::size_t>(nx) + 63) / 64;
  this->Words.assign(this->RowWords * static_cast<std::size_t>(ny) * nz, 0);
}

std::size_t BitVolume::count() const
{
  std::size_t n = 0;
  for (Word w : this->Words)
    n += static_cast<std::size_t>(popCount(w));
  return n;
}

} // namespace vbr
