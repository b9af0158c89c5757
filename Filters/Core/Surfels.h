// Surfels: the unit faces between a selected voxel and an unselected one (or the outside).
//
// A surfel is named by the selected voxel it bounds and its outward direction (Geometry.h:
// 2 * axis + 1 when it faces +axis). Its corners are listed counter-clockwise seen from
// outside, starting at its lowest corner.
#ifndef vbr_Surfels_h
#define vbr_Surfels_h

#include "BitVolume.h"
#include "EVM.h"
#include "Geometry.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

namespace detail
{
/// The corners of the surfels of each direction at the voxel (0, 0, 0) (Surfel::corner).
struct SurfelCornerTable
{
  Point3 offset[6][4];
  constexpr SurfelCornerTable()
    : offset{}
  {
    for (int d = 0; d < 6; ++d)
      for (int k = 0; k < 4; ++k)
      {
        const int a = d >> 1, u = a == 2 ? 0 : a + 1, v = a == 0 ? 2 : a - 1;
        // Counter-clockwise about +e_a is base, +e_u, +e_u+e_v, +e_v (e_u x e_v = e_a);
        // about -e_a the reverse.
        const int du[4] = { 0, 1, 1, 0 };
        const int dv[4] = { 0, 0, 1, 1 };
        const int j = (d & 1) ? k : (4 - k) & 3;
        Point3 p{ 0, 0, 0 };
        p[a] += d & 1;
        p[u] += du[j];
        p[v] += dv[j];
        this->offset[d][k] = p;
      }
  }
};
inline constexpr SurfelCornerTable SurfelCorners{};
} // namespace detail

struct Surfel
{
  Point3 voxel;           ///< the selected voxel it bounds
  std::uint8_t direction; ///< its outward direction

  /// World axis of the normal.
  int axis() const { return this->direction >> 1; }
  /// +1 when the normal points to +axis.
  int sign() const { return (this->direction & 1) ? 1 : -1; }
  /// Corner k (0..3) counter-clockwise seen from outside; corner 0 is the lowest one.
  /// Inline: the surfel graph computes corners whenever asked rather than store them. Each
  /// coordinate is the voxel's plus a constant of the table: adding into one coordinate picked
  /// by index went through memory, and reading the point back whole stalled on that store.
  Point3 corner(int k) const
  {
    const Point3& offset = detail::SurfelCorners.offset[this->direction][k];
    return { this->voxel[0] + offset[0], this->voxel[1] + offset[1], this->voxel[2] + offset[2] };
  }
};

/// Number of surfels, by word-wide XOR of neighbouring rows.
std::size_t countSurfels(const BitVolume& voxels);

/// Every surfel, in axis then z, y, x order (the -axis surfel of a voxel first). For a 2D image (nz
/// == 1) only the x and y normals are listed when `planar` is true.
std::vector<Surfel> extractSurfels(const BitVolume& voxels, bool planar = false);

} // namespace vbr

#endif
