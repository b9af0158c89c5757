// Independent references for the core tests: everything here works voxel by voxel or pixel
// by pixel (flood fills, parity counts, scanline rasterization) and shares no code with the
// algorithms under test.
#ifndef vbr_test_BruteForce_h
#define vbr_test_BruteForce_h

#include "BRep.h"
#include "BitVolume.h"

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <vector>

namespace bf
{

using Int3 = std::array<std::int32_t, 3>;

/// Random voxel set with the given density; seeds give reproducible volumes.
vbr::BitVolume randomVolume(const Int3& dims, double density, unsigned seed);

/// Voxel value with everything outside the grid empty.
bool voxel(const vbr::BitVolume& v, std::int32_t x, std::int32_t y, std::int32_t z);

/// Grid vertices incident to an odd number of set voxels (x, y, z), counting the 8 voxels.
std::set<Int3> extremeVertices(const vbr::BitVolume& v);

/// Same for a 2D image (nz == 1): the 4 pixels around each vertex; vertices (x, y, 0).
std::set<Int3> extremeVertices2D(const vbr::BitVolume& v);

/// A 2D pixel set in a plane: pixels (u, v) as a sorted set.
using PixelSet = std::set<std::pair<std::int32_t, std::int32_t>>;

/// Connected components of a pixel set, 4- or 8-connected.
std::vector<PixelSet> components(const PixelSet& pixels, bool eightConnected);

/// Number of bounded 4-connected components of the complement of `face` (its holes).
int holeCount(const PixelSet& face);

/// Faces one would expect: for each axis, plane and normal sign, the connected components
/// of the surfels of that plane (4-connected, or 8 when `merged`).
struct PlaneKey
{
  int axis, sign, position;
  bool operator<(const PlaneKey& o) const
  {
    return std::tie(axis, sign, position) < std::tie(o.axis, o.sign, o.position);
  }
  bool operator==(const PlaneKey& o) const
  {
    return axis == o.axis && sign == o.sign && position == o.position;
  }
};
std::map<PlaneKey, std::vector<PixelSet>> expectedFaces(const vbr::BitVolume& v, bool merged);

/// Pixels enclosed by a face's loops (even-odd rule over all its loops), in its plane's
/// (u, v) = ((axis + 1) % 3, (axis + 2) % 3) coordinates, by scanline crossing counts.
PixelSet rasterize(const vbr::BRep& brep, int face);

/// Twice the signed area of a loop projected on its face's (u, v) plane.
long long doubledSignedArea(const vbr::BRep& brep, int loop);

} // namespace bf

#endif
