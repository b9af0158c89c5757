// The modifier's driver (ConvexHullModifier.h explains the method): the vertex candidates and
// their convex hull, the dispatch to flat objects, the pressing-in passes with their checks
// and topology repair, the object's parts solved apart, and H's faces and marks. The steps
// live in HullPointRuns, HullIntersection, PressingIn, BackgroundComponents, PolyhedronReversion,
// TopologyRepair, FlatObjects and HullFaces.
#include "ConvexHullModifier.h"

#include "BackgroundComponents.h"
#include "FlatObjects.h"
#include "HullFaces.h"
#include "HullPointRuns.h"
#include "HullShells.h"
#include "PolyhedronReversion.h"
#include "PressingIn.h"
#include "TopologyRepair.h"
#include "UnionFind.h"

#include <algorithm>
#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

/// The contribution to the Euler characteristic of the union of the closed voxel cubes of the
/// cells whose lowest corner is a grid corner, from the 8 voxels about that corner (bit
/// dx + 2 dy + 4 dz for the voxel at corner - 1 + (dx, dy, dz)): the corner itself (any voxel),
/// its edges towards +x, +y, +z (the 4 voxels on that side), its faces (the 2 voxels on both
/// sides) and its cube (the one voxel on all three).
int cornerEuler(unsigned config)
{
  auto any = [&](unsigned mask, unsigned value)
  {
    for (unsigned b = 0; b < 8; ++b)
      if ((b & mask) == value && (config >> b & 1))
        return 1;
    return 0;
  };
  return any(0, 0) - any(1, 1) - any(2, 2) - any(4, 4) + any(3, 3) + any(5, 5) + any(6, 6) -
    any(7, 7);
}

/// Whether the 8 voxels about a grid corner (bits as in cornerEuler) are not well-composed:
/// two diagonally opposite voxels alone (of either class), or a face of the block whose two
/// diagonals hold different classes (its low faces; every face is the low face of some block).
bool criticalCorner(unsigned config)
{
  const std::size_t count = std::bitset<8>(config).count();
  for (unsigned k = 0; k < 4; ++k)
  {
    const bool a = config >> k & 1, b = config >> (7 - k) & 1;
    if ((count == 2 && a && b) || (count == 6 && !a && !b))
      return true;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    // u and w: the indices of the voxels one step along the face's two axes from voxel 0.
    const unsigned u = 1u << ((axis + 1) % 3), w = 1u << ((axis + 2) % 3);
    const bool s0 = config & 1, s1 = config >> u & 1, s2 = config >> (u | w) & 1,
               s3 = config >> w & 1;
    if (s0 == s2 && s1 == s3 && s0 != s1)
      return true;
  }
  return false;
}

/// One pass of the levels, with pits or with every level kept apart: true when H separates
/// (checked, see the header), its shells then joined and its missing handles cut.
bool solvePass(Context& ctx, ModifiedHull& r, bool pits)
{
  ctx.pits = pits;
  ctx.keptApart = 0;
  ctx.planeLevel.clear();
  try
  {
    r.surface = solveLevel(ctx, r.hull, nullptr, true, false, 0, r.degreeOfNonConvexity).mesh;
  }
  catch (const Unresolved& e)
  {
    r.failure = e.what();
    return false;
  }
  if (!separates(ctx.objects, r.surface))
  {
    r.failure = "the surface does not separate";
    return false;
  }
  r.complete = true;
  r.failure.clear();
  r.withoutPits = !pits;
  r.keptApart = ctx.keptApart;
  r.joinedShells = joinShells(ctx, r.surface);
  r.cutHandles = cutMissingHandles(ctx, r.surface);
  r.discardedChanges = ctx.discardedChanges;
  return true;
}

/// Whether H has the topology of the well-composed object's boundary: its Euler characteristic
/// and number of surfaces (one shell per surface).
bool hasTopology(Context& ctx, const LatticeMesh& surface)
{
  return eulerCharacteristic(surface) == *objectEuler(ctx) &&
    static_cast<long>(shellsOf(surface).size()) == objectSurfaces(ctx);
}

/// Topology of the second pass (see the header): when H from the pits, its shells joined and
/// its missing handles cut, has not the topology of the well-composed object's boundary (a
/// spurious handle, or a shell no prism joined), H with every level kept apart is made as well
/// and kept when it has. A ring of object voxels about a wide tunnel that a pit cut off comes
/// back as a torus of its own that one tube joins; kept apart, the ring stays part of its
/// level's solid.
void keepTheObjectsTopology(Context& ctx, ModifiedHull& r)
{
  if (!objectEuler(ctx) || hasTopology(ctx, r.surface))
    return;
  ModifiedHull apart = r;
  const auto planes = ctx.planeLevel;
  if (solvePass(ctx, apart, false) && hasTopology(ctx, apart.surface))
  {
    r = std::move(apart);
    r.handlePass = ModifiedHull::HandlePass::Kept;
    return;
  }
  ctx.planeLevel = planes;
  r.handlePass = ModifiedHull::HandlePass::Rejected;
}

/// The levels solved with pits and, when that leaves something unresolved or the result does
/// not separate, again with every level kept apart.
void solveAndCheck(Context& ctx, ModifiedHull& r)
{
  r.complete = false;
  if (solvePass(ctx, r, true))
  {
    keepTheObjectsTopology(ctx, r);
    return;
  }
  if (!solvePass(ctx, r, false))
    r.surface = triangulateHull(r.hull);
}

/// The component in its own box, whose corner is `lo` in the grid: its H lies in the hull of
/// its centres, so many small components do not each pay for the whole grid.
BitVolume inItsBox(const std::vector<LatticePoint>& component, LatticePoint& lo)
{
  lo = component[0];
  LatticePoint hi = component[0];
  for (const auto& p : component)
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  BitVolume part(static_cast<std::int32_t>(hi[0] - lo[0] + 1),
    static_cast<std::int32_t>(hi[1] - lo[1] + 1),
    static_cast<std::int32_t>(hi[2] - lo[2] + 1));
  for (const auto& p : component)
    part.set(static_cast<std::int32_t>(p[0] - lo[0]),
      static_cast<std::int32_t>(p[1] - lo[1]),
      static_cast<std::int32_t>(p[2] - lo[2]));
  return part;
}

/// One part of the object solved on its own (components first): its centres and the box that
/// holds its H (its hull's box, one voxel wider unless the hull is solid: a flat H is a prism
/// one step off its plane, a segment's a tetrahedron one step off its line).
struct ObjectPart
{
  std::vector<LatticePoint> points;
  BoxedHull extent;
};

ObjectPart partOf(std::vector<LatticePoint> points, CoplanarFaces coplanar)
{
  ObjectPart part;
  part.points = std::move(points);
  part.extent = BoxedHull(convexHull(rowEnds(part.points), coplanar));
  if (part.extent.hull.dimension < 3)
    for (int k = 0; k < 3; ++k)
      --part.extent.box[2 * k], ++part.extent.box[2 * k + 1];
  return part;
}

/// Whether the H of two parts may meet, or one hold a centre of the other: H of a solid part
/// lies in its hull (pits and handles are cut out of it, cavities and joins lie inside), so two
/// solid parts whose hulls share no point cannot; parts that are not solid are compared by
/// their boxes only.
bool partsMayMeet(const ObjectPart& a, const ObjectPart& b)
{
  const BoxedHull& p = a.extent;
  const BoxedHull& q = b.extent;
  for (int k = 0; k < 3; ++k)
    if (p.box[2 * k + 1] < q.box[2 * k] || q.box[2 * k + 1] < p.box[2 * k])
      return false;
  return p.hull.dimension < 3 || q.hull.dimension < 3 || hullsIntersect(p.hull, q.hull);
}

/// Parts that may meet, merged into one; false when none may.
bool mergeMeetingParts(std::vector<ObjectPart>& parts, CoplanarFaces coplanar)
{
  // sorted by the boxes' lower x, so that only boxes overlapping in x are compared
  std::sort(parts.begin(),
    parts.end(),
    [](const ObjectPart& a, const ObjectPart& b) { return a.extent.box[0] < b.extent.box[0]; });
  UnionFind classes(parts.size());
  bool merged = false;
  for (std::size_t i = 0; i < parts.size(); ++i)
    for (std::size_t j = i + 1;
         j < parts.size() && parts[j].extent.box[0] <= parts[i].extent.box[1];
         ++j)
      if (partsMayMeet(parts[i], parts[j]))
      {
        classes.unite(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
        merged = true;
      }
  if (!merged)
    return false;
  std::map<std::uint32_t, std::vector<LatticePoint>> unions;
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    auto& u = unions[classes.find(static_cast<std::uint32_t>(i))];
    u.insert(u.end(), parts[i].points.begin(), parts[i].points.end());
  }
  parts.clear();
  for (auto& [root, u] : unions)
    parts.push_back(partOf(std::move(u), coplanar));
  return true;
}

/// The object's components (vertex-connected, so that voxels touching at an edge or a corner
/// stay in one part and the touching rule decides there), merged until no two parts may meet
/// (when `mergeMeeting`); none for an object of one component.
std::vector<ObjectPart> separateParts(const std::vector<LatticePoint>& points,
  CoplanarFaces coplanar,
  bool mergeMeeting)
{
  std::vector<std::vector<LatticePoint>> components = componentsOf(points, false, true);
  if (components.size() < 2)
    return {}; // no parts to make
  std::vector<ObjectPart> parts;
  for (auto& c : components)
    parts.push_back(partOf(std::move(c), coplanar));
  while (mergeMeeting && parts.size() > 1 && mergeMeetingParts(parts, coplanar))
    continue;
  return parts;
}

ModifiedHull modifyHull(const BitVolume& objects,
  CoplanarFaces coplanar,
  const Execution& exec,
  bool componentsFirst);

/// For a segment off the axes' planes (no component of ab zero), an axis along which its
/// primitive direction ab / gcd has a component +-1; -1 when there is none or the segment lies
/// in an axis plane (the flat path's).
int unitStepAxis(const LatticePoint& ab)
{
  std::int64_t m = 0;
  for (int k = 0; k < 3; ++k)
    m = std::gcd(m, std::abs(ab[k]));
  int unit = -1;
  for (int k = 0; k < 3 && m > 0; ++k)
    if (ab[k] == 0)
      return -1;
    else if (std::abs(ab[k]) == m)
      unit = k;
  return unit;
}

/// Whether the part can have an H of its own: not a flat set in no plane of the grid's axes
/// nor a segment with no direction component +-1 (the corners their pyramids add may lie
/// beyond the part's box grown by one voxel, where another part may be).
bool partHasH(const ObjectPart& part)
{
  const CellList& hull = part.extent.hull;
  if (hull.dimension == 2)
    return gridPlaneAxis(part.points) >= 0;
  if (hull.dimension != 1)
    return true;
  return unitStepAxis(sub(hull.vertices[1], hull.vertices[0])) >= 0 ||
    gridPlaneAxis(part.points) >= 0;
}

/// Whether the part's H stays in the grid: a flat part's prism (or a segment's tetrahedron)
/// near the grid's side would put centres off the grid on H, which only a flat object's H may
/// (the whole object is then solved as one).
bool partInGrid(const ObjectPart& part, const Dims& d)
{
  for (int k = 0; k < 3; ++k)
    if (part.extent.box[2 * k] < 0 || part.extent.box[2 * k + 1] >= d[k])
      return false;
  return true;
}

/// H of one part alone (in the box of its centres, the rest of the object its background, not
/// split into parts again) appended to `together`, moved back into the grid, with the level
/// of each of its triangles (those of its own faces). False when that H is incomplete.
bool appendPartH(Context& ctx,
  const ObjectPart& part,
  const Execution& exec,
  ModifiedHull& r,
  LatticeMesh& together,
  std::vector<int>& levels)
{
  LatticePoint lo;
  ModifiedHull h = modifyHull(inItsBox(part.points, lo), ctx.coplanar, exec, false);
  if (!h.complete || h.surface.triangles.empty())
    return false;
  for (auto& p : h.surface.points)
    for (int k = 0; k < 3; ++k)
      p[k] += lo[k];
  const std::size_t base = levels.size();
  levels.resize(base + h.surface.triangles.size(), -1);
  for (const auto& f : h.faces)
    for (const Index t : f.triangles)
      levels[base + t] = f.level;
  together.append(h.surface, false);
  if (!h.failure.empty())
    r.failure += (r.failure.empty() ? "" : "; ") + h.failure; // a part's note stays
  r.joinedShells += h.joinedShells;
  r.cutHandles += h.cutHandles;
  r.discardedChanges += h.discardedChanges;
  r.keptApart += h.keptApart;
  r.degreeOfNonConvexity = std::max(r.degreeOfNonConvexity, h.degreeOfNonConvexity);
  return true;
}

/// Components first (see the header): when the object's components fall into several parts
/// that cannot meet, H is the union of the H of each part alone, kept when it separates (with
/// the object's topology when the object is well-composed); only otherwise is the object
/// solved as one, from the hull of all its components, which presses in every gap between
/// them level after level (the lobster at v >= 128: its 130 smaller components took 15.5 s of
/// CPU as one object, 3.2 s one by one). Each face keeps the level it has in its part's H (a
/// plane can hold a face of one part's hull and a pit's bottom in another). The parts share
/// [from, to] of the progress.
bool solveComponentsFirst(Context& ctx,
  ModifiedHull& r,
  double from,
  double to,
  bool mergeMeeting = true)
{
  const Dims d = ctx.objects.dims();
  std::vector<LatticePoint> points;
  for (std::int32_t z = 0; z < d[2]; ++z)
    for (std::int32_t y = 0; y < d[1]; ++y)
      for (std::int32_t x = 0; x < d[0]; ++x)
        if (ctx.objects.get(x, y, z))
          points.push_back({ x, y, z });
  const std::vector<ObjectPart> parts = separateParts(points, ctx.coplanar, mergeMeeting);
  if (parts.size() < 2 ||
    !std::all_of(parts.begin(),
      parts.end(),
      [&](const ObjectPart& p) { return partInGrid(p, d) && partHasH(p); }))
    return false;
  ModifiedHull apart;
  LatticeMesh together;
  std::vector<int> levels;
  const double step = (to - from) / static_cast<double>(parts.size());
  for (std::size_t c = 0; c < parts.size(); ++c)
  {
    const Execution exec = ctx.exec.within(from + step * c, from + step * (c + 1));
    if (!appendPartH(ctx, parts[c], exec, apart, together, levels))
      return false;
  }
  if (!separates(ctx.objects, together) || (objectEuler(ctx) && !hasTopology(ctx, together)))
    return false;
  r.surface = std::move(together);
  ctx.triangleLevel = std::move(levels);
  r.joinedShells = apart.joinedShells;
  r.cutHandles = apart.cutHandles;
  r.discardedChanges = apart.discardedChanges;
  r.keptApart = apart.keptApart;
  r.degreeOfNonConvexity = apart.degreeOfNonConvexity;
  r.componentsApart = true;
  r.complete = true;
  r.failure = apart.failure;
  return true;
}

ModifiedHull modifyHull(const BitVolume& objects,
  CoplanarFaces coplanar,
  const Execution& exec,
  bool componentsFirst)
{
  ModifiedHull r;
  const std::vector<LatticePoint> candidates = vertexCandidates(objects);
  if (candidates.empty())
    return r;
  r.hull = convexHull(candidates, coplanar);
  if (!exec.report(0.2))
    throw std::runtime_error("aborted");
  const int flat = r.hull.dimension < 3 ? gridPlaneAxis(candidates) : -1;
  if (flat >= 0)
    solveFlatObject(objects, flat, candidates.front()[flat], exec.within(0.2, 0.8), r);
  else if (r.hull.dimension == 1 || r.hull.dimension == 2)
  {
    // A segment or a flat set in no plane of the grid's axes (never face-connected): its parts
    // apart when they cannot meet (voxels apart keep their own shells), else the tetrahedron or
    // pyramid of the header, every object centre on it.
    Context ctx{ objects, coplanar, exec, {}, 0 };
    if (componentsFirst && solveComponentsFirst(ctx, r, 0.2, 0.8))
      mergeIntoFaces(ctx.planeLevel, ctx.triangleLevel, r);
    else
    {
      r.surface = r.hull.dimension == 1 ? segmentTetrahedron(r.hull, objects.dims())
                                        : flatSetPyramid(r.hull, objects.dims());
      r.complete = true;
      mergeIntoFaces({}, std::vector<int>(r.surface.triangles.size(), 0), r);
      // voxels apart that could not be solved apart share the one solid: said, not silent
      if (objectEuler(ctx) && !hasTopology(ctx, r.surface))
        r.failure = "voxels apart in a plane or on a line off the grid's axes share one solid "
                    "(one shell for several components)";
    }
  }
  else if (r.hull.dimension < 3)
  {
    r.complete = false; // unreachable: a point lies in a plane of the grid's axes
    r.failure = "the object spans no solid";
  }
  else
  {
    classifyBackgroundComponents(objects, r.hull, r);
    Context ctx{ objects, coplanar, exec, {}, 0 };
    if (!componentsFirst || !solveComponentsFirst(ctx, r, 0.2, 0.8))
    {
      solveAndCheck(ctx, r);
      // When H of the object as one misses its topology (a ball in a torus's hole: their hulls
      // meet, so they were one part), each component alone, as a last resort.
      if (r.complete && objectEuler(ctx) && !hasTopology(ctx, r.surface))
        solveComponentsFirst(ctx, r, 0.2, 0.8, false);
    }
    if (!exec.report(0.8))
      throw std::runtime_error("aborted");
    mergeIntoFaces(ctx.planeLevel, ctx.triangleLevel, r);
  }
  for (const auto& p : r.surface.points)
    r.vertexMark.push_back(voxelClass(objects, p) ? 1 : 0);
  for (const auto& p : latticePointsOnSurface(r.surface, objects.dims()))
    if (!voxelClass(objects, p))
      r.backgroundOnSurface.push_back(p);
  return r;
}

} // namespace

std::optional<long> wellComposedBoundaryEuler(const BitVolume& objects, const Execution& exec)
{
  std::array<int, 256> euler;
  std::array<bool, 256> critical;
  for (unsigned c = 0; c < 256; ++c)
  {
    euler[c] = cornerEuler(c);
    critical[c] = criticalCorner(c);
  }
  const Dims d = objects.dims();
  long chi = 0;
  for (std::int32_t z = 0; z <= d[2]; ++z)
  {
    if (exec.stopRequested())
      throw std::runtime_error("aborted");
    for (std::int32_t y = 0; y <= d[1]; ++y)
      for (std::int32_t x = 0; x <= d[0]; ++x)
      {
        unsigned config = 0;
        for (unsigned b = 0; b < 8; ++b)
          config |= static_cast<unsigned>(voxelClass(
                      objects, { x - 1 + (b & 1), y - 1 + (b >> 1 & 1), z - 1 + (b >> 2) }))
            << b;
        if (critical[config])
          return std::nullopt;
        chi += euler[config];
      }
  }
  return 2 * chi;
}

ModifiedHull modifyConvexHull(const BitVolume& objects,
  CoplanarFaces coplanar,
  const Execution& exec)
{
  return modifyHull(objects, coplanar, exec, true);
}

} // namespace vbr
