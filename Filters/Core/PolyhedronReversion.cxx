// The voxel set rebuilt from H and its marks, and the separation check (PolyhedronReversion.h).
#include "PolyhedronReversion.h"

#include "HullPointRuns.h"
#include "HullShells.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

/// Sets the bits lo..hi of a row of words, a word at a time; any lo > hi sets none.
void setRun(Word* row, std::int64_t lo, std::int64_t hi)
{
  for (std::int64_t w = lo >> 6; lo <= hi && w <= hi >> 6; ++w)
    row[w] |= runMask(w, lo, hi);
}

/// A ray's crossing with a triangle: its row z * ny + y, and ceil(xc) - 1 for its x xc.
using RowCrossing = std::pair<std::uint32_t, std::int64_t>;

/// Appends the crossings of the rays (x -> +infinity, y + delta, z + delta^2) of the grid's rows
/// with the triangle abc (its plane `plane`, whose normal's x component is not 0).
template<typename Wide>
void appendCrossings(const LatticePoint& a,
  const LatticePoint& b,
  const LatticePoint& c,
  const FacePlane& plane,
  const Dims& dims,
  std::vector<RowCrossing>& crossings)
{
  const std::int64_t nx = plane.normal[0];
  const int s = nx > 0 ? 1 : -1;
  for (std::int64_t z = std::max<std::int64_t>(0, std::min({ a[2], b[2], c[2] }));
       z <= std::min<std::int64_t>(dims[2] - 1, std::max({ a[2], b[2], c[2] }));
       ++z)
    for (std::int64_t y = std::max<std::int64_t>(0, std::min({ a[1], b[1], c[1] }));
         y <= std::min<std::int64_t>(dims[1] - 1, std::max({ a[1], b[1], c[1] }));
         ++y)
    {
      if (!rayMeetsTriangle<Wide>(a, b, c, y, z, s))
        continue;
      const std::int64_t r = plane.offset - plane.normal[1] * y - plane.normal[2] * z;
      crossings.emplace_back(static_cast<std::uint32_t>(z * dims[1] + y), ceilDiv(r, nx) - 1);
    }
}

/// The crossings of the rays of the grid's rows with the surface's triangles, in no order: the
/// crossings as (row, x) pairs, grouped by row later (one vector per row of a large grid cost
/// an allocation for each row the surface crosses).
std::vector<RowCrossing> rayCrossings(const LatticeMesh& surface, const Dims& dims)
{
  // Corners below 2^30 in magnitude (H's are voxel centres, below 2^20 as convexHull's; but
  // revertModifiedHull takes any mesh, so the 128-bit products stay for the others, within what
  // planeThrough's 64-bit normals allow): the rows (y, z) tried lie within the triangle's
  // bounds, so every difference in an orientation is at most 2^31 - 2 in magnitude, each
  // product at most (2^31 - 2)^2 < 2^62, and the difference of two products below 2^63.
  const bool productsFit64 = std::all_of(surface.points.begin(),
    surface.points.end(),
    [](const LatticePoint& p)
    {
      return std::all_of(p.begin(),
        p.end(),
        [](std::int64_t c) { return c > -(std::int64_t(1) << 30) && c < (std::int64_t(1) << 30); });
    });
  std::vector<RowCrossing> crossings;
  for (const auto& tri : surface.triangles)
  {
    const LatticePoint &a = surface.points[tri[0]], &b = surface.points[tri[1]],
                       &c = surface.points[tri[2]];
    const FacePlane plane = planeThrough(a, b, c);
    if (plane.normal[0] == 0)
      continue;
    if (productsFit64)
      appendCrossings<std::int64_t>(a, b, c, plane, dims, crossings);
    else
      appendCrossings<__int128>(a, b, c, plane, dims, crossings);
  }
  return crossings;
}

/// Sets in `out` the centres with an odd number of crossings beyond them in their row.
void fillInsideRuns(const std::vector<RowCrossing>& crossings, BitVolume& out)
{
  const Dims& dims = out.dims();
  // Grouped by row by a counting sort.
  const std::size_t rowCount = static_cast<std::size_t>(dims[1]) * dims[2];
  std::vector<std::uint32_t> rowStart(rowCount + 1, 0);
  for (const auto& c : crossings)
    ++rowStart[c.first + 1];
  for (std::size_t n = 0; n < rowCount; ++n)
    rowStart[n + 1] += rowStart[n];
  std::vector<std::int64_t> xs(crossings.size());
  {
    std::vector<std::uint32_t> next(rowStart.begin(), rowStart.end() - 1);
    for (const auto& c : crossings)
      xs[next[c.first]++] = c.second;
  }
  // Centre x of a row is inside when an odd number of its crossings have an index >= x: with
  // the indices in decreasing order c_1 >= c_2 >= ..., the centres in (c_{j+1}, c_j] for odd j
  // (c_{m+1} = -1), only the runs inside visited.
  for (std::int32_t z = 0; z < dims[2]; ++z)
    for (std::int32_t y = 0; y < dims[1]; ++y)
    {
      const std::size_t row = static_cast<std::size_t>(z) * dims[1] + y;
      if (rowStart[row] == rowStart[row + 1])
        continue; // no crossing: the row is outside (most rows of a large grid)
      const auto first = xs.begin() + rowStart[row], last = xs.begin() + rowStart[row + 1];
      std::sort(first, last, std::greater<>());
      bool parity = false;
      for (auto c = first; c != last && *c >= 0; ++c)
      {
        parity = !parity;
        if (!parity)
          continue;
        const std::int64_t hi = std::min<std::int64_t>(*c, dims[0] - 1);
        const std::int64_t lo = c + 1 != last ? std::max<std::int64_t>(*(c + 1), -1) + 1 : 0;
        setRun(out.row(y, z), lo, hi);
      }
    }
}

/// Whether the centres inside or on the closed surface, less the background centres on it, are
/// the object (for a closed embedded surface: the voxel set reverts exactly).
bool revertsToObjects(const BitVolume& objects, const LatticeMesh& surface)
{
  const std::vector<LatticePoint> on = latticePointsOnSurface(surface, objects.dims());
  std::vector<LatticePoint> background;
  for (const auto& p : on)
    if (!voxelClass(objects, p))
      background.push_back(p);
  return revertWithPointsOn(surface, on, background, objects.dims()) == objects;
}

/// Whether the mesh is a closed, consistently oriented 2-manifold: every directed edge once and
/// its reverse once (each edge in two triangles, oriented alike), and the triangles about every
/// point one fan (no point where two pieces touch), what boundsAVolume asks of the mesh before
/// its self-intersection test.
bool isClosedManifold(const LatticeMesh& m)
{
  std::vector<std::pair<Index, Index>> edges;
  edges.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles)
  {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      return false;
    for (int k = 0; k < 3; ++k)
      edges.emplace_back(t[k], t[(k + 1) % 3]);
  }
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end())
    return false;
  for (const auto& [a, b] : edges)
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a)))
      return false;
  // About point v each triangle (v, x, y) leads from x to y: a permutation of v's neighbours
  // (each edge vx in two triangles), which must be one cycle.
  std::vector<std::vector<std::pair<Index, Index>>> around(m.points.size());
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      around[t[k]].emplace_back(t[(k + 1) % 3], t[(k + 2) % 3]);
  for (auto& fan : around)
  {
    if (fan.empty())
      continue;
    std::sort(fan.begin(), fan.end());
    std::size_t length = 0;
    Index x = fan[0].first;
    do
    {
      x = std::lower_bound(fan.begin(), fan.end(), std::make_pair(x, Index(0)))->second;
      ++length;
    } while (x != fan[0].first && length <= fan.size());
    if (length != fan.size())
      return false;
  }
  return true;
}

} // namespace

std::vector<LatticePoint> latticePointsOnSurface(const LatticeMesh& surface, const Dims& dims)
{
  // The points lie in the grid, so (x * ny + y) * nz + z numbers them in the lexicographic
  // order of (x, y, z): sorting these integers (the corners and edges shared by triangles come
  // several times) is much cheaper than sorting the triples, and gives the same list.
  const std::uint64_t ny = static_cast<std::uint64_t>(dims[1]);
  const std::uint64_t nz = static_cast<std::uint64_t>(dims[2]);
  std::vector<std::uint64_t> keys;
  keys.reserve(2 * surface.triangles.size());
  const LatticeBox grid{ LatticePoint{ 0, 0, 0 },
    LatticePoint{ dims[0] - 1, dims[1] - 1, dims[2] - 1 } };
  for (const auto& tri : surface.triangles)
    forEachPointOnTriangle(
      { surface.points[tri[0]], surface.points[tri[1]], surface.points[tri[2]] },
      grid,
      [&](const LatticePoint& p)
      {
        keys.push_back(
          (static_cast<std::uint64_t>(p[0]) * ny + static_cast<std::uint64_t>(p[1])) * nz +
          static_cast<std::uint64_t>(p[2]));
      });
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<LatticePoint> found(keys.size());
  for (std::size_t n = 0; n < keys.size(); ++n)
  {
    const std::uint64_t yz = keys[n] % (ny * nz);
    found[n] = { static_cast<std::int64_t>(keys[n] / (ny * nz)),
      static_cast<std::int64_t>(yz / nz),
      static_cast<std::int64_t>(yz % nz) };
  }
  return found;
}

BitVolume revertModifiedHull(const LatticeMesh& surface,
  const std::vector<LatticePoint>& backgroundOnSurface,
  const Dims& dims)
{
  return revertWithPointsOn(
    surface, latticePointsOnSurface(surface, dims), backgroundOnSurface, dims);
}

namespace detail
{

BitVolume revertWithPointsOn(const LatticeMesh& surface,
  const std::vector<LatticePoint>& on,
  const std::vector<LatticePoint>& backgroundOnSurface,
  const Dims& dims)
{
  BitVolume out(dims[0], dims[1], dims[2]);
  fillInsideRuns(rayCrossings(surface, dims), out);
  for (const auto& p : on)
    out.set(static_cast<std::int32_t>(p[0]),
      static_cast<std::int32_t>(p[1]),
      static_cast<std::int32_t>(p[2]),
      !std::binary_search(backgroundOnSurface.begin(), backgroundOnSurface.end(), p));
  return out;
}

ShellInBox shellInItsBox(const LatticeMesh& shell)
{
  ShellInBox s;
  s.lo = shell.points[0];
  LatticePoint hi = s.lo;
  for (const auto& p : shell.points)
    for (int k = 0; k < 3; ++k)
    {
      s.lo[k] = std::min(s.lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  LatticeMesh local = shell;
  for (auto& p : local.points)
    p = sub(p, s.lo);
  s.box = { static_cast<std::int32_t>(hi[0] - s.lo[0] + 1),
    static_cast<std::int32_t>(hi[1] - s.lo[1] + 1),
    static_cast<std::int32_t>(hi[2] - s.lo[2] + 1) };
  s.on = latticePointsOnSurface(local, s.box);
  s.inside = revertWithPointsOn(local, s.on, s.on, s.box);
  return s;
}

void markShell(const LatticeMesh& shell,
  const Dims& d,
  std::uint8_t flag,
  std::uint8_t onFlag,
  std::vector<std::uint8_t>& out)
{
  const ShellInBox s = shellInItsBox(shell);
  const LatticePoint& lo = s.lo;
  const Dims& box = s.box;
  const std::vector<LatticePoint>& on = s.on;
  const BitVolume& inside = s.inside;
  // The inside's words scanned for their set bits: most of a large shell's box is outside it.
  // All wordsPerRow() words of a row: their padding bits (x >= box[0]) are 0, as
  // revertWithPointsOn sets bits only of centres in the box.
  for (std::int32_t z = 0; z < box[2]; ++z)
    for (std::int32_t y = 0; y < box[1]; ++y)
    {
      const Word* row = inside.row(y, z);
      for (std::size_t w = 0; w < inside.wordsPerRow(); ++w)
        for (Word bits = row[w]; bits != 0; bits &= bits - 1)
        {
          const auto x = static_cast<std::int64_t>(64 * w) + __builtin_ctzll(bits);
          const LatticePoint p{ x + lo[0], y + lo[1], z + lo[2] };
          if (inGrid(d, p))
            out[gridIndex(d, p)] = flag;
        }
    }
  for (const auto& q : on)
  {
    const LatticePoint p{ q[0] + lo[0], q[1] + lo[1], q[2] + lo[2] };
    if (onFlag && inGrid(d, p))
      out[gridIndex(d, p)] = onFlag;
  }
}

bool separates(const BitVolume& objects, const LatticeMesh& surface)
{
  return isClosedEmbeddedManifold(surface) && shellsFaceOutward(shellsOf(surface)) &&
    revertsToObjects(objects, surface);
}

bool separatesAfterLocalChecks(const BitVolume& objects, const LatticeMesh& surface)
{
  return isClosedManifold(surface) && shellsFaceOutward(shellsOf(surface)) &&
    revertsToObjects(objects, surface);
}

} // namespace detail

} // namespace vbr
