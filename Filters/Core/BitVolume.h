// A set of voxels of a box-shaped grid, one bit per voxel, rows of 64-bit words along x.
#ifndef vbr_BitVolume_h
#define vbr_BitVolume_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

using Word = std::uint64_t;

class BitVolume
{
public:
  BitVolume() = default;
  /// An empty set of nx * ny * nz voxels (nz = 1 for a 2D image).
  BitVolume(std::int32_t nx, std::int32_t ny, std::int32_t nz);

  std::int32_t size(int axis) const { return this->Dims[axis]; }
  const std::array<std::int32_t, 3>& dims() const { return this->Dims; }
  std::size_t wordsPerRow() const { return this->RowWords; }
  std::size_t voxelCount() const
  {
    return static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  }

  Word* row(std::int32_t y, std::int32_t z)
  {
    return this->Words.data() + (static_cast<std::size_t>(z) * this->Dims[1] + y) * this->RowWords;
  }
  const Word* row(std::int32_t y, std::int32_t z) const
  {
    return this->Words.data() + (static_cast<std::size_t>(z) * this->Dims[1] + y) * this->RowWords;
  }

  bool get(std::int32_t x, std::int32_t y, std::int32_t z) const
  {
    return (this->row(y, z)[x >> 6] >> (x & 63)) & 1u;
  }
  /// get(x, y, z), and false outside the grid (the background around the volume).
  bool getOrBackground(std::int32_t x, std::int32_t y, std::int32_t z) const
  {
    return x >= 0 && y >= 0 && z >= 0 && x < this->Dims[0] && y < this->Dims[1] &&
      z < this->Dims[2] && this->get(x, y, z);
  }
  void set(std::int32_t x, std::int32_t y, std::int32_t z, bool value = true)
  {
    Word& w = this->row(y, z)[x >> 6];
    const Word bit = Word(1) << (x & 63);
    w = value ? (w | bit) : (w & ~bit);
  }

  /// Number of voxels in the set.
  std::size_t count() const;
  bool empty() const { return this->count() == 0; }

  bool operator==(const BitVolume& other) const
  {
    return this->Dims == other.Dims && this->Words == other.Words;
  }
  bool operator!=(const BitVolume& other) const { return !(*this == other); }

private:
  std::array<std::int32_t, 3> Dims{ 0, 0, 0 };
  std::size_t RowWords = 0;
  std::vector<Word> Words;
};

} // namespace vbr

#endif
