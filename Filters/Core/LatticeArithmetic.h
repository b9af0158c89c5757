// Exact integer arithmetic on lattice points for the convex hull modifier's files (the products
// in 128 bits where they can leave 64): floor and ceiling division (differences, dot and cross
// products are ConvexHull.h's), the grid's bounds, the class of a voxel centre (everything off the
// grid is background), points strictly inside a hull or on a triangle, and the lattice points of a
// triangle. Internal to the modifier's files, like HullModifierContext.h, which includes it.
#ifndef vbr_LatticeArithmetic_h
#define vbr_LatticeArithmetic_h

#include "BitVolume.h"
#include "ConvexHull.h"
#include "LatticeMesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>

namespace vbr
{
namespace detail
{

using Index = std::uint32_t;
using Dims = std::array<std::int32_t, 3>;

inline std::int64_t floorDiv(std::int64_t a, std::int64_t b)
{
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0)))
  {
    --q;
  }
  return q;
}

inline std::int64_t ceilDiv(std::int64_t a, std::int64_t b)
{
  return -floorDiv(-a, b);
}

inline bool inGrid(const Dims& d, const LatticePoint& p)
{
  return p[0] >= 0 && p[1] >= 0 && p[2] >= 0 && p[0] < d[0] && p[1] < d[1] && p[2] < d[2];
}

/// 1 for an object centre, 0 for a background one (everything outside the grid).
inline bool voxelClass(const BitVolume& v, const LatticePoint& p)
{
  return inGrid(v.dims(), p) &&
    v.get(static_cast<std::int32_t>(p[0]),
      static_cast<std::int32_t>(p[1]),
      static_cast<std::int32_t>(p[2]));
}

inline bool strictlyInside(const CellList& c, const LatticePoint& p)
{
  return std::all_of(c.planes.begin(),
    c.planes.end(),
    [&](const FacePlane& plane) { return plane.evaluate(p) < 0; });
}

/// Whether p lies on the closed triangle abc (exactly).
inline bool onTriangle(const LatticePoint& a,
  const LatticePoint& b,
  const LatticePoint& c,
  const FacePlane& plane,
  const LatticePoint& p)
{
  if (plane.evaluate(p) != 0)
    return false;
  return dot(plane.normal, cross(sub(b, a), sub(p, a))) >= 0 &&
    dot(plane.normal, cross(sub(c, b), sub(p, b))) >= 0 &&
    dot(plane.normal, cross(sub(a, c), sub(p, c))) >= 0;
}

/// Calls f(p) for every lattice point p of the closed triangle t within the box (each once: the
/// points of the triangle's plane are one per point of its projection along its largest normal
/// component).
template<typename F>
void forEachPointOnTriangle(const std::array<LatticePoint, 3>& t, const LatticeBox& box, F&& f)
{
  const LatticePoint &a = t[0], &b = t[1], &c = t[2];
  const FacePlane plane = planeThrough(a, b, c);
  int k = 0;
  for (int q = 1; q < 3; ++q)
    if (std::abs(plane.normal[q]) > std::abs(plane.normal[k]))
      k = q;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const bool unitK = plane.normal[k] == 1 || plane.normal[k] == -1;
  const std::int64_t loI = std::max(box[0][i], std::min({ a[i], b[i], c[i] }));
  const std::int64_t hiI = std::min(box[1][i], std::max({ a[i], b[i], c[i] }));
  const std::int64_t loJ = std::max(box[0][j], std::min({ a[j], b[j], c[j] }));
  const std::int64_t hiJ = std::min(box[1][j], std::max({ a[j], b[j], c[j] }));
  // p lies in the plane, so each cross product of onTriangle is a multiple of the normal, with
  // the sign of its k-th component times that of n_k: the same test on the projection.
  const std::int64_t sk = plane.normal[k] > 0 ? 1 : -1;
  auto leftOf = [&](const LatticePoint& e0, const LatticePoint& e1, std::int64_t u, std::int64_t v)
  { return sk * ((e1[i] - e0[i]) * (v - e0[j]) - (e1[j] - e0[j]) * (u - e0[i])) >= 0; };
  for (std::int64_t u = loI; u <= hiI; ++u)
    for (std::int64_t v = loJ; v <= hiJ; ++v)
    {
      const std::int64_t r = plane.offset - plane.normal[i] * u - plane.normal[j] * v;
      // A unit component (the faces of a voxel surface, mostly) divides every r: no division.
      if (!unitK && r % plane.normal[k] != 0)
        continue;
      LatticePoint p;
      p[i] = u;
      p[j] = v;
      p[k] = unitK ? r * plane.normal[k] : r / plane.normal[k];
      if (p[k] >= box[0][k] && p[k] <= box[1][k] && leftOf(a, b, u, v) && leftOf(b, c, u, v) &&
        leftOf(c, a, u, v))
        f(p);
    }
}

} // namespace detail
} // namespace vbr

#endif
