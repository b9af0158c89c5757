// Section 4.1's classification of the background components in CH(S) (BackgroundComponents.h).
#include "BackgroundComponents.h"

#include "CUDB.h"
#include "HullPointRuns.h"
#include "UnionFind.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

/// Whether a neighbour (26) of p lies outside the closed (solid) hull (only then can a corner
/// of the voxel of p lie outside or on the hull), along a row: the x for which none does are
/// the interval [lo, hi] returned (empty when lo > hi). Over the offsets d in {-1, 0, 1}^3 the
/// largest n.d is |n|_1 (d the signs of n), so the neighbours all lie inside exactly when every
/// plane keeps n.p - d + |n|_1 <= 0: one bound on x per plane and row instead of a pass over
/// the planes per point.
std::array<__int128, 2> farFromHullBoundary(const CellList& c, std::int64_t y, std::int64_t z)
{
  // The floor of a / b for b != 0 in 128 bits (a ceiling is minus the floor of -a / b).
  const auto floorOf = [](__int128 a, __int128 b)
  {
    __int128 q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
  };
  std::array<__int128, 2> range{ std::numeric_limits<std::int64_t>::min(),
    std::numeric_limits<std::int64_t>::max() };
  if (c.dimension < 3)
    return { 1, 0 };
  for (const FacePlane& plane : c.planes)
  {
    const __int128 reach =
      std::abs(plane.normal[0]) + std::abs(plane.normal[1]) + std::abs(plane.normal[2]);
    // n.p - d + reach <= 0  <=>  nx x <= bound
    const __int128 bound = __int128(plane.offset) - reach - __int128(plane.normal[1]) * y -
      __int128(plane.normal[2]) * z;
    const __int128 nx = plane.normal[0];
    if (nx == 0)
    {
      if (bound < 0)
        return { 1, 0 };
    }
    else if (nx > 0)
      range[1] = std::min(range[1], floorOf(bound, nx));
    else
      range[0] = std::max(range[0], -floorOf(bound, -nx)); // ceil(bound / nx), nx < 0
  }
  return range;
}

/// Number of edge-connected sets among the marked faces of the hull.
int connectedFaceSets(const CellList& hull, const std::vector<bool>& marked)
{
  UnionFind sets(hull.faces.size());
  for (const auto& ef : hull.edgeFaces)
    if (ef[0] != Index(-1) && ef[1] != Index(-1) && marked[ef[0]] && marked[ef[1]])
      sets.unite(ef[0], ef[1]);
  int count = 0;
  for (std::size_t f = 0; f < marked.size(); ++f)
    count += marked[f] && sets.find(static_cast<std::uint32_t>(f)) == f;
  return count;
}

} // namespace

namespace detail
{

void classifyBackgroundComponents(const BitVolume& objects, const CellList& hull, ModifiedHull& r)
{
  const std::vector<LatticePoint> background = pointsOfClass(hull, objects, false, false).points();
  if (background.empty())
  {
    return;
  }
  const Dims d = objects.dims();
  BitVolume inside(d[0], d[1], d[2]);
  for (const auto& p : background)
  {
    inside.set(static_cast<std::int32_t>(p[0]),
      static_cast<std::int32_t>(p[1]),
      static_cast<std::int32_t>(p[2]));
  }
  const CUDB cudb = buildCUDB(d[2] == 1 ? extractEVM2D(inside) : extractEVM(inside));
  const Components comps = labelComponents(cudb, Connectivity::Face);
  std::vector<std::int32_t> value(comps.boxLabel.begin(), comps.boxLabel.end());
  std::vector<std::int32_t> labels(inside.voxelCount(), 0);
  paintBoxes(cudb.boxes, value, { 0, 0, 0 }, { 0, 1, 2 }, d, labels.data());
  std::vector<std::vector<bool>> seen(comps.count + 1, std::vector<bool>(hull.faces.size()));
  // A face is seen from (or coplanar with) a corner 2p + s (s in {-1, 1}^3, doubled
  // coordinates) of the voxel of a background point p near the hull's boundary when
  // n.(2p + s) - 2d >= 0; the largest n.s is |n|_1, so when 2(n.p - d) + |n|_1 >= 0. Along a
  // row that is linear in x, so over a component's near points of the row it holds for one of
  // them exactly when it holds for the one of least or greatest x (by the sign of n_x): each
  // row costs one test per face and component there instead of one per face and point. The
  // background points come row by row (pointsOfClass).
  struct Span
  {
    std::int32_t label;
    std::int64_t lo, hi;
  };
  std::vector<Span> spans;
  for (std::size_t i = 0; i < background.size();)
  {
    const std::int64_t y = background[i][1], z = background[i][2];
    const std::array<__int128, 2> far = farFromHullBoundary(hull, y, z);
    spans.clear();
    for (; i < background.size() && background[i][1] == y && background[i][2] == z; ++i)
    {
      const LatticePoint& p = background[i];
      if (far[0] <= p[0] && p[0] <= far[1])
        continue; // no neighbour outside the hull
      const std::int32_t label = labels[(p[2] * d[1] + p[1]) * d[0] + p[0]];
      auto span =
        std::find_if(spans.begin(), spans.end(), [&](const Span& s) { return s.label == label; });
      if (span == spans.end())
        spans.push_back({ label, p[0], p[0] });
      else
      {
        span->lo = std::min(span->lo, p[0]);
        span->hi = std::max(span->hi, p[0]);
      }
    }
    if (spans.empty())
      continue;
    for (std::size_t f = 0; f < hull.faces.size(); ++f)
    {
      const FacePlane& plane = hull.planes[f];
      const __int128 reach =
        std::abs(plane.normal[0]) + std::abs(plane.normal[1]) + std::abs(plane.normal[2]);
      const __int128 rest = 2 *
          (__int128(plane.normal[1]) * y + __int128(plane.normal[2]) * z - __int128(plane.offset)) +
        reach;
      for (const Span& span : spans)
      {
        const std::int64_t x = plane.normal[0] > 0 ? span.hi : span.lo;
        if (2 * __int128(plane.normal[0]) * x + rest >= 0)
          seen[span.label][f] = true;
      }
    }
  }
  for (std::uint32_t l = 1; l <= comps.count; ++l)
  {
    const int sets = connectedFaceSets(hull, seen[l]);
    (sets == 0 ? r.cavities : sets == 1 ? r.concavities : r.tunnels)++;
  }
}

} // namespace detail

} // namespace vbr
