// The shells of H and the sides of points (HullShells.h).
#include "HullShells.h"

#include "UnionFind.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

/// Whether the triangle's box (scaled by k) misses the row of p across y or z, or ends before p
/// along x.
bool behindOrBeside(const LatticeMesh& surface,
  const std::array<Index, 3>& tri,
  const LatticePoint& p,
  std::int64_t k)
{
  const LatticePoint& a = surface.points[tri[0]];
  const LatticePoint& b = surface.points[tri[1]];
  const LatticePoint& c = surface.points[tri[2]];
  for (int axis = 0; axis < 3; ++axis)
  {
    const std::int64_t hi = k * std::max({ a[axis], b[axis], c[axis] });
    if (p[axis] > hi)
      return true;
    if (axis > 0 && p[axis] < k * std::min({ a[axis], b[axis], c[axis] }))
      return true;
  }
  return false;
}

/// sideOf's step for one triangle: false when p / k lies on it, else flips `parity` when the
/// ray from p crosses it.
bool crossesBeyond(const LatticeMesh& surface,
  const std::array<Index, 3>& tri,
  const LatticePoint& p,
  std::int64_t k,
  int& parity)
{
  // A triangle whose box misses p's row across y and z, or lies wholly before p along x,
  // neither holds p nor crosses the ray beyond it (the ray's perturbation stays in the row):
  // integer comparisons spare most triangles of a large H their plane.
  if (behindOrBeside(surface, tri, p, k))
    return true;
  LatticePoint q[3];
  for (int v = 0; v < 3; ++v)
    for (int a = 0; a < 3; ++a)
      q[v][a] = surface.points[tri[v]][a] * k;
  const FacePlane plane = planeThrough(q[0], q[1], q[2]);
  if (plane.evaluate(p) == 0 && onTriangle(q[0], q[1], q[2], plane, p))
    return false;
  const std::int64_t nx = plane.normal[0];
  if (nx == 0)
    return true;
  const int s = nx > 0 ? 1 : -1;
  if (!rayMeetsTriangle<__int128>(q[0], q[1], q[2], p[1], p[2], s))
    return true;
  // The crossing lies beyond p when n.p < d along +x for an outward normal with nx > 0.
  const __int128 e = plane.evaluate(p);
  parity ^= (nx > 0) == (e < 0);
  return true;
}

/// The entries of the z-row index with rows grouped by 2^shift: each triangle is listed
/// once per group its z-range meets.
std::size_t zIndexEntries(const Shell& shell, int shift)
{
  const LatticeMesh& m = shell.mesh;
  const std::int64_t z0 = shell.box[0][2];
  std::size_t entries = 0;
  for (const auto& t : m.triangles)
  {
    const auto [lo, hi] = std::minmax({ m.points[t[0]][2], m.points[t[1]][2], m.points[t[2]][2] });
    entries += static_cast<std::size_t>(((hi - z0) >> shift) - ((lo - z0) >> shift) + 1);
  }
  return entries;
}

/// Entries per triangle the z-row index may hold before rows are grouped (the aneurism's
/// shells reach 17, so real objects keep one row per group); a group's scan still reads a
/// small part of a tall shell, and the index stays linear in the triangles.
constexpr std::size_t kZIndexEntriesPerTriangle = 64;

/// The triangles of the shell by the groups of integer z-rows they span (Shell::byZ).
void indexByZ(const Shell& shell)
{
  const LatticeMesh& m = shell.mesh;
  const std::int64_t z0 = shell.box[0][2];
  const auto rows = static_cast<std::size_t>(shell.box[1][2] - z0 + 1);
  const std::size_t budget = kZIndexEntriesPerTriangle * m.triangles.size() + rows;
  int shift = 0;
  while ((rows >> shift) > 1 && zIndexEntries(shell, shift) > budget)
    ++shift;
  shell.zShift = shift;
  const std::size_t groups = ((rows - 1) >> shift) + 1;
  auto groupRange = [&](const std::array<Index, 3>& t)
  {
    const auto [lo, hi] = std::minmax({ m.points[t[0]][2], m.points[t[1]][2], m.points[t[2]][2] });
    return std::make_pair(
      static_cast<std::size_t>((lo - z0) >> shift), static_cast<std::size_t>((hi - z0) >> shift));
  };
  shell.zStart.assign(groups + 1, 0);
  for (const auto& t : m.triangles)
  {
    const auto [lo, hi] = groupRange(t);
    for (std::size_t g = lo; g <= hi; ++g)
      ++shell.zStart[g + 1];
  }
  for (std::size_t n = 0; n < groups; ++n)
    shell.zStart[n + 1] += shell.zStart[n];
  shell.byZ.resize(shell.zStart[groups]);
  std::vector<std::size_t> next(shell.zStart.begin(), shell.zStart.end() - 1);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
  {
    const auto [lo, hi] = groupRange(m.triangles[t]);
    for (std::size_t g = lo; g <= hi; ++g)
      shell.byZ[next[g]++] = static_cast<Index>(t);
  }
}

constexpr std::uint32_t kSideQueriesBeforeIndex = 4;
} // namespace

bool shellsFaceOutward(const LatticeMesh& surface)
{
  return shellsFaceOutward(shellsOf(surface));
}

namespace detail
{

std::vector<Shell> shellsOf(const LatticeMesh& m)
{
  UnionFind sets(m.points.size());
  for (const auto& t : m.triangles)
  {
    sets.unite(t[0], t[1]);
    sets.unite(t[0], t[2]);
  }
  // Flat tables, not maps: the joins split a large H into its shells after every Boolean. A
  // point lies in one shell, so one local index per point does.
  constexpr Index none = std::numeric_limits<Index>::max();
  std::vector<Index> shellOfRoot(m.points.size(), none), local(m.points.size(), none);
  std::vector<Shell> shells;
  for (const auto& t : m.triangles)
  {
    Index& shell = shellOfRoot[sets.find(t[0])];
    if (shell == none)
    {
      shell = static_cast<Index>(shells.size());
      shells.emplace_back();
    }
    Shell& s = shells[shell];
    std::array<Index, 3> tri;
    for (int k = 0; k < 3; ++k)
    {
      if (local[t[k]] == none)
      {
        local[t[k]] = static_cast<Index>(s.mesh.points.size());
        s.mesh.points.push_back(m.points[t[k]]);
      }
      tri[k] = local[t[k]];
    }
    s.mesh.triangles.push_back(tri);
    s.volume += dot(m.points[t[0]], cross(m.points[t[1]], m.points[t[2]]));
  }
  for (Shell& s : shells)
  {
    s.box = { s.mesh.points[0], s.mesh.points[0] };
    for (const auto& p : s.mesh.points)
      for (int k = 0; k < 3; ++k)
      {
        s.box[0][k] = std::min(s.box[0][k], p[k]);
        s.box[1][k] = std::max(s.box[1][k], p[k]);
      }
  }
  return shells;
}
int sideOf(const LatticeMesh& surface,
  const std::vector<std::array<Index, 3>>& triangles,
  const LatticePoint& p,
  std::int64_t k)
{
  int parity = 0;
  for (const auto& tri : triangles)
    if (!crossesBeyond(surface, tri, p, k, parity))
      return 0;
  return parity ? 1 : -1;
}

int sideOf(const LatticeMesh& surface, const LatticePoint& p, std::int64_t k)
{
  return sideOf(surface, surface.triangles, p, k);
}
/// sideOf for one shell whose box holds p's row (sideOf for H checks): the triangles scanned
/// are, once the shell is asked often, only those spanning the group of the integer z-row
/// floor(p_z / k), a superset of those behindOrBeside keeps (a triangle whose z-range meets
/// p_z / k holds floor(p_z / k) in it, its corners being integers). The same exact tests
/// decide.
int sideOf(const Shell& shell, const LatticePoint& p, std::int64_t k)
{
  if (shell.sideQueries < kSideQueriesBeforeIndex && ++shell.sideQueries == kSideQueriesBeforeIndex)
    indexByZ(shell);
  if (shell.sideQueries < kSideQueriesBeforeIndex)
    return sideOf(shell.mesh, p, k);
  const std::int64_t row = floorDiv(p[2], k) - shell.box[0][2];
  if (row < 0 || row > shell.box[1][2] - shell.box[0][2])
    return sideOf(shell.mesh, p, k);
  const auto group = static_cast<std::size_t>(row >> shell.zShift);
  int parity = 0;
  for (std::size_t n = shell.zStart[group]; n < shell.zStart[group + 1]; ++n)
    if (!crossesBeyond(shell.mesh, shell.mesh.triangles[shell.byZ[n]], p, k, parity))
      return 0;
  return parity ? 1 : -1;
}
/// The surface's triangles in their order, without those that behindOrBeside(., p, 1) skips for
/// every lattice point p of the box: box[0] <= p <= box[1] makes max_x < lo_x imply max_x < p_x,
/// and likewise max_y < lo_y, min_y > hi_y and the same along z, so sideOf(., p, 1) on the rest
/// gives the same answer for every point of the box as on the whole surface. Locating each of a
/// prism's points against every triangle of the part of H the join changed (on the aneurism
/// mostly the vessels' main shell, tens of thousands of triangles) was most of the check.
std::vector<std::array<Index, 3>> trianglesAheadOf(const LatticeMesh& surface,
  const std::array<LatticePoint, 2>& box)
{
  std::vector<std::array<Index, 3>> near;
  for (const auto& tri : surface.triangles)
  {
    const LatticePoint& a = surface.points[tri[0]];
    const LatticePoint& b = surface.points[tri[1]];
    const LatticePoint& c = surface.points[tri[2]];
    bool skipped = std::max({ a[0], b[0], c[0] }) < box[0][0];
    for (int axis = 1; axis < 3 && !skipped; ++axis)
      skipped = std::max({ a[axis], b[axis], c[axis] }) < box[0][axis] ||
        std::min({ a[axis], b[axis], c[axis] }) > box[1][axis];
    if (!skipped)
      near.push_back(tri);
  }
  return near;
}
bool shellsFaceOutward(const std::vector<Shell>& shells)
{
  for (std::size_t i = 0; i < shells.size(); ++i)
  {
    if (shells[i].volume == 0)
      return false;
    const LatticePoint& p = shells[i].mesh.points[0];
    bool nestedOddly = false;
    for (std::size_t j = 0; j < shells.size(); ++j)
    {
      const LatticeBox& b = shells[j].box;
      if (j == i || p[0] < b[0][0] || p[0] > b[1][0] || p[1] < b[0][1] || p[1] > b[1][1] ||
        p[2] < b[0][2] || p[2] > b[1][2])
        continue;
      const int side = sideOf(shells[j], p, 1);
      if (side == 0)
        return false; // shells that touch: not embedded
      nestedOddly = nestedOddly != (side > 0);
    }
    if ((shells[i].volume > 0) == nestedOddly)
      return false;
  }
  return true;
}
std::vector<int> sidesInBox(const LatticeMesh& surface,
  const LatticePoint& lo,
  const LatticePoint& hi)
{
  const std::vector<std::array<Index, 3>> near = trianglesAheadOf(surface, { lo, hi });
  std::vector<int> sides;
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        sides.push_back(sideOf(surface, near, { x, y, z }, 1));
  return sides;
}

} // namespace detail

} // namespace vbr
