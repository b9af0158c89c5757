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

struct Surfel
{
  Point3 voxel;           ///< the selected voxel it bounds
  std::uint8_t direction; ///< its outward direction

  /// World axis of the normal.
  int axis() const { return this->direction >> 1; }
  /// +1 when the normal points to +axis.
  int sign() const { return (this->direction & 1) ? 1 : -1; }
  /// Corner k (0..3) counter-clockwise seen from outside; corner 0 is the lowest one.
  Point3 corner(int k) const;
};

/// Number of surfels, by word-wide XOR of neighbouring rows.
std::size_t countSurfels(const BitVolume& voxels);

/// Every surfel, in axis then z, y, x order (the -axis surfel of a voxel first). For a 2D image (nz
/// == 1) only the x and y normals are listed when `planar` is true.
std::vector<Surfel> extractSurfels(const BitVolume& voxels, bool planar = false);

} // namespace vbr

#endif
