// Independent references for the core tests: everything here works voxel by voxel or pixel
// by pixel (flood fills, parity counts, scanline rasterization) and shares no code with the
// algorithms under test.
#ifndef vbr_test_BruteForce_h
#define vbr_test_BruteForce_h

#include "BRep.h"
#include "BitVolume.h"
#include "Execution.h"
#include "Geometry.h"
#include "PixelTopology.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <vector>

namespace bf
{

/// Not a reference but the tests' thread pool: a parallel loop on real threads, one per
/// sub-range, as vtkSMPTools would run it.
vbr::Execution threadedExecution(int threads);

/// Random voxel set with the given density; seeds give reproducible volumes.
vbr::BitVolume randomVolume(const vbr::Point3& dims, double density, unsigned seed);

/// The dimensions of a random volume of trial `trial` in a series: each edge `least` or more,
/// cycling through 11 x 9 x 8 combinations so that a series meets thin plates and cubes alike.
inline vbr::Point3 trialDims(int trial, int least)
{
  return { least + (trial * 5) % 11, least + (trial * 3) % 9, least + (trial * 7) % 8 };
}

/// Voxel value with everything outside the grid empty.
bool voxel(const vbr::BitVolume& v, std::int32_t x, std::int32_t y, std::int32_t z);

/// Connected components by flood fill: label per voxel (x fastest; 0 = not set), numbered
/// 1..n in scan order. Neighbours share a face (6; 4 in 2D) or, when `vertexConnected`,
/// also an edge or a vertex (26; 8 in 2D). A volume with nz == 1 is a 2D image.
std::vector<int> floodFillLabels(const vbr::BitVolume& v, bool vertexConnected, int& count);

/// Grid vertices incident to an odd number of set voxels (x, y, z), counting the 8 voxels.
std::set<vbr::Point3> extremeVertices(const vbr::BitVolume& v);

/// Same for a 2D image (nz == 1): the 4 pixels around each vertex; vertices (x, y, 0).
std::set<vbr::Point3> extremeVertices2D(const vbr::BitVolume& v);

/// Faces one would expect: for each axis, plane and normal sign, the connected components
/// of the surfels of that plane (4-connected, or 8 when `merged`).
std::map<PlaneKey, std::vector<PixelSet>> expectedFaces(const vbr::BitVolume& v, bool merged);

/// Pixels enclosed by a face's loops (even-odd rule over all its loops), in its plane's
/// (u, v) = ((axis + 1) % 3, (axis + 2) % 3) coordinates, by scanline crossing counts.
PixelSet rasterize(const vbr::BRep& brep, int face);

/// Twice the signed area of a loop projected on its face's (u, v) plane.
long long doubledSignedArea(const vbr::BRep& brep, int loop);

/// Bounding box {xmin, xmax, ymin, ymax} of 2D integer points (at least one).
inline std::array<std::int64_t, 4> bounds2D(const std::vector<std::array<std::int64_t, 2>>& p)
{
  std::array<std::int64_t, 4> b{ p[0][0], p[0][0], p[0][1], p[0][1] };
  for (const auto& q : p)
  {
    b[0] = std::min(b[0], q[0]);
    b[1] = std::max(b[1], q[0]);
    b[2] = std::min(b[2], q[1]);
    b[3] = std::max(b[3], q[1]);
  }
  return b;
}

} // namespace bf

#endif
