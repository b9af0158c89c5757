// Surfels of a voxel set. countSurfels counts the transitions between neighbouring voxels a
// word at a time (popcount of the XOR of a row with its shifted self, and with the rows
// before it along y and z, plus the rows at the grid's ends). extractSurfels lists them voxel
// by voxel.

#include "Surfels.h"

namespace vbr
{

namespace
{

std::size_t popcount(Word w)
{
  return static_cast<std::size_t>(popCount(w));
}

} // namespace

std::size_t countSurfels(const BitVolume& voxels)
{
  const std::int32_t ny = voxels.size(1), nz = voxels.size(2);
  const std::size_t words = voxels.wordsPerRow();
  std::size_t n = 0;
  for (std::int32_t z = 0; z < nz; ++z)
  {
    for (std::int32_t y = 0; y < ny; ++y)
    {
      const Word* r = voxels.row(y, z);
      Word carry = 0;
      for (std::size_t w = 0; w < words; ++w)
      {
        // x faces: transitions between neighbouring bits, including both row ends.
        n += popcount(transitions(r[w], carry));
        carry = r[w] >> 63;
      }
      n += popcount(carry);
      // y and z faces: transitions between this row and the previous row (or nothing).
      const Word* py = y > 0 ? voxels.row(y - 1, z) : nullptr;
      const Word* pz = z > 0 ? voxels.row(y, z - 1) : nullptr;
      for (std::size_t w = 0; w < words; ++w)
      {
        n += popcount(r[w] ^ (py ? py[w] : 0));
        n += popcount(r[w] ^ (pz ? pz[w] : 0));
      }
      if (y == ny - 1)
        for (std::size_t w = 0; w < words; ++w)
          n += popcount(r[w]);
      if (z == nz - 1)
        for (std::size_t w = 0; w < words; ++w)
          n += popcount(r[w]);
    }
  }
  return n;
}

std::vector<Surfel> extractSurfels(const BitVolume& voxels, bool planar)
{
  std::vector<Surfel> out;
  const auto& d = voxels.dims();
  auto inside = [&](std::int32_t x, std::int32_t y, std::int32_t z)
  { return x >= 0 && y >= 0 && z >= 0 && x < d[0] && y < d[1] && z < d[2] && voxels.get(x, y, z); };
  for (int axis = 0; axis < (planar ? 2 : 3); ++axis)
  {
    for (std::int32_t z = 0; z < d[2]; ++z)
      for (std::int32_t y = 0; y < d[1]; ++y)
        for (std::int32_t x = 0; x < d[0]; ++x)
        {
          if (!voxels.get(x, y, z))
            continue;
          const Point3 c{ x, y, z };
          Point3 n = c;
          --n[axis];
          if (!inside(n[0], n[1], n[2]))
            out.push_back({ c, static_cast<std::uint8_t>(2 * axis) });
          n[axis] += 2;
          if (!inside(n[0], n[1], n[2]))
            out.push_back({ c, static_cast<std::uint8_t>(2 * axis + 1) });
        }
  }
  return out;
}

} // namespace vbr
