// Surfels: the unit faces between a selected voxel and an unselected one (or the outside).
#ifndef vbr_Surfels_h
#define vbr_Surfels_h

#include "BitVolume.h"
#include "EVM.h"

#include <cstddef>
#include <vector>

namespace vbr
{

struct Surfel
{
  int axis;       ///< world axis of the normal
  int normalSign; ///< +1 when the normal points to +axis
  Vertex corner;  ///< lowest grid vertex of the unit square (world axes)
};

/// Number of surfels, by word-wide XOR of neighbouring rows.
std::size_t countSurfels(const BitVolume& voxels);

/// Every surfel, in axis then z, y, x order. For a 2D image (nz == 1) only the x and y
/// normals are listed when `planar` is true.
std::vector<Surfel> extractSurfels(const BitVolume& voxels, bool planar = false);

} // namespace vbr

#endif
