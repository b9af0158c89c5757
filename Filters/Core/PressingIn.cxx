// The pressing-in, Algorithm 1 of FZD-514 (PressingIn.h).
#include "PressingIn.h"

#include "Geometry.h"
#include "HullIntersection.h"
#include "HullPointRuns.h"
#include "UnionFind.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

bool hullsMeet(const BoxedHull& a, const BoxedHull& b)
{
  for (int k = 0; k < 3; ++k)
    if (a.box[2 * k + 1] < b.box[2 * k] || b.box[2 * k + 1] < a.box[2 * k])
      return false;
  return hullsIntersect(a.hull, b.hull);
}

/// Whether p lies on a face plane of the (solid) hull.
bool onSurface(const CellList& c, const LatticePoint& p)
{
  return std::any_of(c.planes.begin(),
    c.planes.end(),
    [&](const FacePlane& plane) { return plane.evaluate(p) == 0; });
}

/// strictlyInside and onSurface of one hull for many points, answered from the x ranges of
/// their rows (RowScan), the last row kept: the points of a group come row by row, and testing
/// each of them against every plane of C and of its parent was a tenth of the time on large
/// objects. A point in the closed range but not in the open one lies on a plane (each plane
/// keeps it inside, one not strictly); only points outside the closed range are tested plane by
/// plane for lying on one.
class RowSides
{
public:
  explicit RowSides(const CellList& c)
    : Hull(c)
    , Closed(c, false)
    , Open(c, true)
  {
  }

  bool strictlyInside(const LatticePoint& p)
  {
    this->row(p);
    return this->OpenRow && p[0] >= this->OpenLo && p[0] <= this->OpenHi;
  }

  /// The points [lo, hi] of the run strictly inside (one range: the open interior is convex);
  /// false when none is.
  bool strictRange(const Run& r, std::int64_t& lo, std::int64_t& hi)
  {
    this->row({ r.lo, r.y, r.z });
    lo = std::max(r.lo, this->OpenLo);
    hi = std::min(r.hi, this->OpenHi);
    return this->OpenRow && lo <= hi;
  }

  bool onSurface(const LatticePoint& p)
  {
    this->row(p);
    if (!this->ClosedRow || p[0] < this->ClosedLo || p[0] > this->ClosedHi)
      return vbr::onSurface(this->Hull, p);
    return !(this->OpenRow && p[0] >= this->OpenLo && p[0] <= this->OpenHi);
  }

private:
  void row(const LatticePoint& p)
  {
    if (this->Known && p[1] == this->Y && p[2] == this->Z)
      return;
    if (!this->Known || p[2] != this->Z)
    {
      this->Closed.setSlice(p[2]);
      this->Open.setSlice(p[2]);
    }
    this->Known = true;
    this->Y = p[1];
    this->Z = p[2];
    this->ClosedRow = this->Closed.range(this->Y, this->ClosedLo, this->ClosedHi);
    this->OpenRow = this->Open.range(this->Y, this->OpenLo, this->OpenHi);
  }

  const CellList& Hull;
  RowScan Closed, Open;
  bool Known = false, ClosedRow = false, OpenRow = false;
  std::int64_t Y = 0, Z = 0, ClosedLo = 0, ClosedHi = 0, OpenLo = 0, OpenHi = 0;
};

/// A group of points of the other class: its points, the hull of the points (any dimension)
/// and a solid hull holding them (solidHull; dimension below 3 when no thickening fits). The
/// hull of two merged groups is the hull of their hulls' corners, so a merge costs the
/// corners, not the points.
struct PointGroup
{
  PointRuns points;
  CellList shape;
  BoxedHull solid;
};

/// The solid hull of the group (its shape when that is solid, else its points thickened inside
/// C, in C's open interior when `strict`).
BoxedHull solidOf(const PointGroup& g, const CellList& c, bool strict, CoplanarFaces coplanar)
{
  if (g.shape.dimension == 3)
    return BoxedHull(g.shape);
  CellList out;
  solidHull(g.points.points(), c, strict, coplanar, out);
  return BoxedHull(std::move(out));
}

/// The hull of the points (see makeGroup).
CellList shapeOf(const PointRuns& points, CoplanarFaces coplanar)
{
  const std::vector<LatticePoint> ends = rowEnds(points);
  CellList shape = convexHull(sliceCorners(ends), coplanar);
  if (shape.dimension < 3)
    shape = convexHull(ends, coplanar);
  return shape;
}

/// A group with its hulls. The shape is the hull of the slices' corners (sliceCorners: the same
/// polytope, and a solid hull's cell list depends only on its polytope, faces in the order of
/// their planes, each polygon from its least corner), which spares the hull most row ends of a
/// large group (most of making a group's hull on the aneurism); a flat one is made from the
/// row ends as before, since a flat hull's polygon is not given in such an order.
PointGroup makeGroup(PointRuns points, const CellList& c, bool strict, CoplanarFaces coplanar)
{
  PointGroup g;
  g.points = std::move(points);
  g.shape = shapeOf(g.points, coplanar);
  g.solid = solidOf(g, c, strict, coplanar);
  return g;
}

/// Whether every corner of the groups' shapes lies in the closed solid shape of `into`.
bool shapesWithin(const PointGroup& into, const std::vector<PointGroup*>& from)
{
  if (into.shape.dimension != 3)
    return false;
  for (const PointGroup* g : from)
    for (const auto& p : g->shape.vertices)
      if (!hullContains(into.shape, p))
        return false;
  return true;
}

/// Moves the points of the groups `from` into `into` (the largest list kept, so a growing group
/// is not copied again and again) and finds the hulls of the union from the shapes' corners;
/// true when they are those of `into` already. When those corners all lie in the solid shape of
/// `into` its hulls stay as they are: a merged hull (convexHull merges coplanar faces) depends only
/// on the polytope, faces in the order of their planes and each polygon from its least corner, so
/// computing it again gives the same cell list. Most merges of the groups kept apart are of that
/// kind (8,204 of 9,268 on the full aneurism): a small group whose region met the region of a large
/// one that already holds it.
bool mergeGroups(PointGroup& into,
  const std::vector<PointGroup*>& from,
  const CellList& c,
  bool strict,
  CoplanarFaces coplanar)
{
  const bool within = shapesWithin(into, from);
  std::vector<LatticePoint> corners;
  if (!within)
    corners = into.shape.vertices;
  for (PointGroup* g : from)
  {
    if (into.points.count < g->points.count)
      std::swap(into.points, g->points);
    into.points.append(g->points);
    if (!within)
      corners.insert(corners.end(), g->shape.vertices.begin(), g->shape.vertices.end());
    *g = PointGroup();
  }
  if (within)
    return true; // a solid shape is its own solid hull (solidOf), unchanged too
  into.shape = convexHull(corners, coplanar);
  into.solid = solidOf(into, c, strict, coplanar);
  return false;
}

/// Merges groups while two of them meet, until they are pairwise apart: a group takes every
/// group it meets at once (they all end up with it: a hull holding it meets them), and having
/// grown is tested again. Two groups found apart stay apart until one of them grows, so no
/// pair is tested twice at the same size. The survivors keep their order.
template<typename Meet>
void mergeWhileMeeting(std::vector<PointGroup>& groups,
  const CellList& c,
  bool strict,
  CoplanarFaces coplanar,
  Meet&& meet)
{
  std::vector<bool> alive(groups.size(), true);
  std::vector<std::size_t> todo(groups.size());
  std::iota(todo.rbegin(), todo.rend(), std::size_t(0));
  while (!todo.empty())
  {
    const std::size_t i = todo.back();
    todo.pop_back();
    if (!alive[i])
      continue;
    std::vector<PointGroup*> meeting;
    for (std::size_t j = 0; j < groups.size(); ++j)
      if (j != i && alive[j] && meet(groups[i], groups[j]))
      {
        meeting.push_back(&groups[j]);
        alive[j] = false;
      }
    if (meeting.empty())
      continue;
    mergeGroups(groups[i], meeting, c, strict, coplanar);
    todo.push_back(i);
  }
  std::vector<PointGroup> kept;
  for (std::size_t i = 0; i < groups.size(); ++i)
    if (alive[i])
      kept.push_back(std::move(groups[i]));
  groups = std::move(kept);
}

/// The groups of points of the other class to press in: the components (face-connected: two
/// groups meeting only along an edge or at a corner stay two, and their hulls apart) in the
/// closed hull that reach its open interior, merged while their hulls meet (a group without a
/// solid hull meets every other), each with its hull.
std::vector<PointGroup> pressingInGroups(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls)
{
  std::vector<PointGroup> groups;
  RowSides sides(c);
  std::optional<RowSides> parentSides;
  if (parent)
    parentSides.emplace(*parent);
  for (auto& g :
    componentsOf(pointsOfClass(c, ctx.objects, !cls, false), ctx.objects.dims()[2] == 1, false))
    if (anyPoint(g,
          [&](const LatticePoint& p)
          { return sides.strictlyInside(p) || (parentSides && parentSides->onSurface(p)); }))
      groups.push_back(makeGroup(std::move(g), c, false, ctx.coplanar));
  mergeWhileMeeting(groups,
    c,
    false,
    ctx.coplanar,
    [](const PointGroup& a, const PointGroup& b)
    {
      return a.solid.hull.dimension < 3 || b.solid.hull.dimension < 3 ||
        hullsMeet(a.solid, b.solid);
    });
  return groups;
}

/// Whether the open interior of a region holds no centre of class `cls`: such a region is
/// final one level down (nothing in it is pressed in again).
bool holdsNoCentreOf(const CellList& region, const BitVolume& objects, bool cls)
{
  bool none = true;
  forEachPointIn(region,
    true,
    [&](const LatticePoint& p)
    {
      if (none && voxelClass(objects, p) == cls)
        none = false;
    });
  return none;
}

/// Whether an empty lattice triangle of the region's surface has every corner in the open
/// interior of C: only from such a triangle can a group strictly inside the region be pressed
/// in one level down (C is then its parent). A region with a centre of C's class inside and no
/// such triangle (a tetrahedron from a point of the group and T: each of its faces holds two
/// corners of T, on C's surface) leaves that centre nowhere to be pressed in from.
bool hasInnerTriangle(const CellList& region, const CellList& c)
{
  EmptyFaceTriangles triangles(region, PointRuns());
  std::array<LatticePoint, 3> t;
  while (triangles.next(t))
    if (std::all_of(
          t.begin(), t.end(), [&](const LatticePoint& p) { return strictlyInside(c, p); }))
      return true;
  return false;
}

/// Definition PR with an empty triangle: the hull of the group and an empty triangle T on the
/// surface of C whose corners lie in the open interior of the parent (so T keeps off every piece
/// of surface C shares with it), the nearest T whose hull keeps off the other regions and holds
/// no centre of C's class `cls` in its open interior, else the nearest that keeps off the other
/// regions, or when every candidate meets one, the nearest (its group is then merged with that
/// region's group). The hull of the group and T is the hull of the group's corners and T.
///
/// A region apart that holds a centre of C's class is taken only when an empty triangle of its
/// surface has every corner in C's open interior (hasInnerTriangle): the level below presses
/// that centre in from such a triangle alone. Without one (the tetrahedron of a single point
/// and T: each of its faces holds two corners of T, on C's surface; the aneurism at v >= 55),
/// a later region apart that has one is taken, else the first other candidate tried after the
/// nearest apart (merged with the region it meets, as above); only when there is neither is
/// the nearest apart kept, and its level then reports the failure.
///
/// Why a clean hull first: the region's own pressed-in groups need empty triangles of its
/// surface inside C, and its faces away from T are spanned by the group's corners alone. A flat
/// group (a row or a sheet of one layer of a thin plate) with T on the far side of its plane has
/// no such face at all: every face of the hull then has a corner of T on C's surface, and a
/// centre of C's class inside that hull can be pressed in from nowhere. With T on one side of
/// the group's plane the group's polygon is a face of the region, and a thin region has no
/// lattice point inside.
bool pressedRegion(const CellList& c,
  const CellList* parent,
  const PointGroup& group,
  const std::vector<const BoxedHull*>& others,
  const BitVolume& objects,
  bool cls,
  CoplanarFaces coplanar,
  BoxedHull& out)
{
  EmptyFaceTriangles triangles(c, group.points);
  std::array<LatticePoint, 3> t;
  BoxedHull nearest, nearestApart, pressableApart;
  bool nearestApartPressable = false;
  for (int tried = 0; tried < 64 && triangles.next(t);)
  {
    if (parent &&
      !std::all_of(
        t.begin(), t.end(), [&](const LatticePoint& p) { return strictlyInside(*parent, p); }))
      continue;
    ++tried;
    std::vector<LatticePoint> points = group.shape.vertices;
    points.insert(points.end(), t.begin(), t.end());
    BoxedHull region(convexHull(points, coplanar));
    const bool apart = std::none_of(
      others.begin(), others.end(), [&](const BoxedHull* o) { return hullsMeet(region, *o); });
    if (apart && holdsNoCentreOf(region.hull, objects, cls))
    {
      out = std::move(region);
      return true;
    }
    if (apart && nearestApart.hull.dimension < 0)
    {
      nearestApartPressable = hasInnerTriangle(region.hull, c);
      nearestApart = std::move(region);
      continue;
    }
    if (apart && !nearestApartPressable && pressableApart.hull.dimension < 0 &&
      hasInnerTriangle(region.hull, c))
      pressableApart = region;
    if (nearest.hull.dimension < 0)
      nearest = std::move(region);
  }
  if (nearestApart.hull.dimension >= 0 && !nearestApartPressable &&
    pressableApart.hull.dimension >= 0)
    out = std::move(pressableApart);
  else if (nearestApart.hull.dimension >= 0 && !nearestApartPressable &&
    nearest.hull.dimension >= 0)
    out = std::move(nearest);
  else if (nearestApart.hull.dimension >= 0)
    out = std::move(nearestApart);
  else if (nearest.hull.dimension >= 0)
    out = std::move(nearest);
  else
    return false;
  return true;
}

/// A group kept apart and its region (dimension -1 until found), pressed in or a cavity;
/// `checked` once the region is known to keep off every other live region.
struct ApartGroup
{
  PointGroup group;
  BoxedHull region;
  bool pressed = false;
  bool alive = true;
  bool checked = false;
  /// Known of an unchecked region that has not changed since: it keeps off the live regions
  /// before index `from`, and off every checked region when `apartFromChecked`.
  std::size_t from = 0;
  bool apartFromChecked = false;
};

/// The regions of the live groups that have none: a cavity where the group's hull thickened in
/// the open interior of C is solid, otherwise pressed in (pressedRegion) away from the
/// obstacles and every region found so far. False when a new region meets an obstacle.
bool findRegions(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  const std::vector<BoxedHull>& obstacles,
  std::vector<ApartGroup>& groups)
{
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < groups.size(); ++i)
    if (groups[i].alive && groups[i].region.hull.dimension < 0)
    {
      todo.push_back(i);
      groups[i].pressed = groups[i].group.solid.hull.dimension < 3;
      if (!groups[i].pressed)
        groups[i].region = groups[i].group.solid;
    }
  for (std::size_t i : todo)
  {
    if (!groups[i].pressed)
      continue;
    std::vector<const BoxedHull*> others;
    for (const auto& o : obstacles)
      others.push_back(&o);
    for (const auto& g : groups)
      if (g.alive && g.region.hull.dimension == 3)
        others.push_back(&g.region);
    if (!pressedRegion(
          c, parent, groups[i].group, others, ctx.objects, cls, ctx.coplanar, groups[i].region))
      throw Unresolved("no empty triangle of the surface to press a group in from");
  }
  return std::none_of(todo.begin(),
    todo.end(),
    [&](std::size_t i)
    {
      return std::any_of(obstacles.begin(),
        obstacles.end(),
        [&](const BoxedHull& o) { return hullsMeet(groups[i].region, o); });
    });
}

/// Merges the groups of the first two regions that meet (into the lower index, whose region is
/// to be found again, so that it can still find a triangle apart from the rest). Regions
/// already checked keep off every other live region, so only the unchecked ones are tested.
///
/// A merge whose hulls stay those of the lower group (mergeGroups) leaves its region as it was
/// (a solid group's region is its solid hull), and what was known of it still holds: tested as
/// the unchecked region i, it keeps off the regions before the one it met; checked before, it
/// keeps off every checked region (of two regions unchanged since checked, the later checked
/// was tested against the other). Those pairs are not tested again; the pair found first, and
/// so every merge, is the same.
bool mergeMeetingRegions(Context& ctx, const CellList& c, std::vector<ApartGroup>& groups)
{
  for (std::size_t i = 0; i < groups.size(); ++i)
  {
    if (!groups[i].alive || groups[i].checked)
      continue;
    for (std::size_t j = groups[i].from; j < groups.size(); ++j)
      if (j != i && groups[j].alive && !(groups[i].apartFromChecked && groups[j].checked) &&
        hullsMeet(groups[i].region, groups[j].region))
      {
        const std::size_t k = std::min(i, j), l = std::max(i, j);
        const bool kept = mergeGroups(groups[k].group, { &groups[l].group }, c, true, ctx.coplanar);
        groups[l].alive = false;
        if (kept && !groups[k].pressed)
        {
          groups[k].from = k == i ? j + 1 : 0;
          groups[k].apartFromChecked = k == i ? groups[k].apartFromChecked : true;
        }
        else
        {
          groups[k].region = BoxedHull();
          for (auto& g : groups)
            g.from = 0; // a region changes: what is known of the pairs with it no longer holds
          groups[k].apartFromChecked = false;
        }
        groups[k].checked = false;
        return true;
      }
    groups[i].checked = true;
  }
  return false;
}

/// The regions of the touching rule (see the header) for the points of the other class in the
/// open interior of C (a hull of class `cls`): their face-connected groups, each with a solid
/// region holding it that meets the surface of C at most in one empty triangle (a cavity: the
/// hull of its thickening in the open interior; or pressed in, pressedRegion). Groups whose
/// regions meet are merged until the regions are apart. False when a region meets an obstacle
/// (a pit of this level).
bool apartRegions(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  const PointRuns& points,
  const std::vector<BoxedHull>& obstacles,
  std::vector<CellList>& regions,
  std::vector<bool>& pressed)
{
  std::vector<ApartGroup> groups;
  for (auto& g : componentsOf(points, ctx.objects.dims()[2] == 1, false))
    groups.push_back({ makeGroup(std::move(g), c, true, ctx.coplanar) });
  do
  {
    if (!findRegions(ctx, c, parent, cls, obstacles, groups))
      return false;
  } while (mergeMeetingRegions(ctx, c, groups));
  regions.clear();
  pressed.clear();
  for (auto& g : groups)
    if (g.alive)
    {
      regions.push_back(std::move(g.region.hull));
      pressed.push_back(g.pressed);
    }
  return true;
}

/// The regions of apartRegions solved one level down: the pressed ones subtracted from C (each
/// meets its surface in its triangle only, so the difference is a 2-manifold), the cavities
/// added inside out.
void solveApart(Context& ctx,
  const CellList& c,
  bool cls,
  int level,
  const std::vector<CellList>& regions,
  const std::vector<bool>& pressed,
  LevelSurface& out,
  int& depth)
{
  std::vector<LatticeMesh> cavities;
  for (std::size_t i = 0; i < regions.size(); ++i)
  {
    ++ctx.keptApart;
    int below = 0;
    LevelSurface g = solveLevel(ctx, regions[i], &c, !cls, false, level + 1, below);
    depth = std::max(depth, below + 1);
    if (!pressed[i])
      cavities.push_back(std::move(g.mesh));
    else if (!out.subtract(g))
      throw Unresolved("a region pressed in from an empty triangle did not give a 2-manifold");
  }
  for (const auto& g : cavities)
    out.addCavity(g);
}

/// Presses the solved hull G of a group in as a pit, C - G, when the difference is a closed
/// 2-manifold with lattice corners and every level below resolves.
bool pressInPit(Context& ctx,
  const CellList& c,
  const CellList& hull,
  bool cls,
  int level,
  LevelSurface& out,
  int& depth)
{
  const int keptApart = ctx.keptApart;
  try
  {
    int below = 0;
    const LevelSurface g = solveLevel(ctx, hull, &c, !cls, true, level + 1, below);
    if (out.subtract(g))
    {
      depth = std::max(depth, below + 1);
      return true;
    }
  }
  catch (const Unresolved&)
  {
  }
  ctx.keptApart = keptApart;
  return false;
}

/// The pits of one level: the groups of pressingInGroups pressed in where pressInPit succeeds
/// (their hulls returned as obstacles), the points of the others in the open interior of C
/// returned in `apart`. A group holding a point on the surface C shares with its parent (`pit`)
/// can only stay on H through a pit: when that fails, the level throws and the parent keeps C
/// apart instead.
void pressInPits(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  bool pit,
  int level,
  LevelSurface& out,
  PointRuns& apart,
  std::vector<BoxedHull>& pits,
  int& depth)
{
  RowSides sides(c);
  std::optional<RowSides> parentSides;
  if (pit)
    parentSides.emplace(*parent);
  for (PointGroup& g : pressingInGroups(ctx, c, pit ? parent : nullptr, cls))
  {
    // The difference is decided beforehand only for a group that is its own solid hull: a
    // thickened one's corners are points of the other class, which a pit of the next level
    // can take off the surface again (and with them an edge or corner that made C - G fail).
    if (g.solid.hull.dimension == 3 && missesACorner(g.solid.hull, c) &&
      (g.shape.dimension < 3 || convexDifferenceIsManifold(c, g.solid.hull)) &&
      pressInPit(ctx, c, g.solid.hull, cls, level, out, depth))
    {
      pits.push_back(std::move(g.solid));
      continue;
    }
    for (const Run& r : g.points.runs)
    {
      std::int64_t lo = 0, hi = -1;
      const bool inside = sides.strictRange(r, lo, hi);
      if (inside)
        apart.push(lo, hi, r.y, r.z);
      for (std::int64_t x = r.lo; pit && x <= r.hi; ++x)
      {
        if (inside && x == lo)
          x = hi; // the points strictly inside C stay (apart), the others must be off the floor
        else if (parentSides->onSurface({ x, r.y, r.z }))
          throw Unresolved("a centre on a shared surface can only be kept by a pit");
      }
    }
  }
}

/// A box that leaves the lattice points' bounds open.
const LatticeBox kUnbounded{ LatticePoint{ INT64_MIN / 4, INT64_MIN / 4, INT64_MIN / 4 },
  LatticePoint{ INT64_MAX / 4, INT64_MAX / 4, INT64_MAX / 4 } };

} // namespace

bool convexDifferenceIsManifold(const CellList& c, const CellList& g)
{
  if (c.dimension < 3 || g.dimension < 3)
    return true; // a flat G takes nothing off C: the regularised difference is C
  const std::set<FacePlane> planesOfC(c.planes.begin(), c.planes.end());
  std::vector<bool> contactFace(g.faces.size());
  for (std::size_t f = 0; f < g.faces.size(); ++f)
    contactFace[f] = planesOfC.count(g.planes[f]) > 0;
  // Per corner of G, the faces of C through it (sorted indices).
  std::vector<std::vector<std::uint32_t>> onC(g.vertices.size());
  for (std::size_t v = 0; v < g.vertices.size(); ++v)
    for (std::size_t f = 0; f < c.planes.size(); ++f)
      if (c.planes[f].evaluate(g.vertices[v]) == 0)
        onC[v].push_back(static_cast<std::uint32_t>(f));
  std::vector<bool> contactEdge(g.edges.size());
  for (std::size_t e = 0; e < g.edges.size(); ++e)
  {
    const auto& a = onC[g.edges[e][0]];
    const auto& b = onC[g.edges[e][1]];
    std::vector<std::uint32_t> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    contactEdge[e] = !common.empty();
    if (contactEdge[e] && !contactFace[g.edgeFaces[e][0]] && !contactFace[g.edgeFaces[e][1]])
      return false;
  }
  for (std::size_t v = 0; v < g.vertices.size(); ++v)
  {
    if (onC[v].empty())
      continue;
    // The contact edges at v, joined through the contact faces holding two of them.
    const auto& edges = g.vertexEdges[v];
    UnionFind pieces(edges.size());
    for (std::uint32_t f : g.vertexFaces[v])
    {
      if (!contactFace[f])
        continue;
      std::vector<std::size_t> atV;
      for (std::size_t k = 0; k < edges.size(); ++k)
        if (g.edgeFaces[edges[k]][0] == f || g.edgeFaces[edges[k]][1] == f)
          atV.push_back(k);
      for (std::size_t k = 1; k < atV.size(); ++k)
        pieces.unite(static_cast<std::uint32_t>(atV[0]), static_cast<std::uint32_t>(atV[k]));
    }
    std::set<std::uint32_t> roots;
    for (std::size_t k = 0; k < edges.size(); ++k)
      if (contactEdge[edges[k]])
        roots.insert(pieces.find(static_cast<std::uint32_t>(k)));
    if (roots.size() != 1)
      return false;
  }
  return true;
}

namespace detail
{

std::vector<LatticePoint> rowEnds(const std::vector<LatticePoint>& listed)
{
  auto zyx = [](const LatticePoint& a, const LatticePoint& b)
  { return std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]); };
  std::vector<LatticePoint> sorted;
  const bool inOrder = std::is_sorted(listed.begin(), listed.end(), zyx);
  if (!inOrder)
  {
    sorted = listed;
    std::sort(sorted.begin(), sorted.end(), zyx);
  }
  const std::vector<LatticePoint>& points = inOrder ? listed : sorted;
  std::vector<LatticePoint> ends;
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    const bool first =
      k == 0 || points[k - 1][1] != points[k][1] || points[k - 1][2] != points[k][2];
    const bool last = k + 1 == points.size() || points[k + 1][1] != points[k][1] ||
      points[k + 1][2] != points[k][2];
    if (first || last)
      ends.push_back(points[k]);
  }
  return ends;
}

std::vector<LatticePoint> rowEnds(const PointRuns& listed)
{
  auto zyx = [](const Run& a, const Run& b)
  { return std::tie(a.z, a.y, a.lo) < std::tie(b.z, b.y, b.lo); };
  std::vector<Run> sorted;
  const bool inOrder = std::is_sorted(listed.runs.begin(), listed.runs.end(), zyx);
  if (!inOrder)
  {
    sorted = listed.runs;
    std::sort(sorted.begin(), sorted.end(), zyx);
  }
  const std::vector<Run>& runs = inOrder ? listed.runs : sorted;
  std::vector<LatticePoint> ends;
  for (std::size_t k = 0; k < runs.size();)
  {
    std::size_t last = k;
    while (last + 1 < runs.size() && runs[last + 1].y == runs[k].y && runs[last + 1].z == runs[k].z)
      ++last;
    ends.push_back({ runs[k].lo, runs[k].y, runs[k].z });
    if (runs[last].hi != runs[k].lo)
      ends.push_back({ runs[last].hi, runs[k].y, runs[k].z });
    k = last + 1;
  }
  return ends;
}

/// Of points in row order (rowEnds), the corners of each slice's polygon (x, y at one z;
/// Andrew's monotone chain over the points in (y, x) order, corners where it turns strictly):
/// a point that is no corner of its slice's polygon lies between other points of the set, so
/// it is no vertex of their hull either, and the hull of the corners is the same polytope.
std::vector<LatticePoint> sliceCorners(const std::vector<LatticePoint>& ends)
{
  // A slice's points come in (y, x) order without repeats, as monotoneChain asks (its
  // orientation, clockwise in (x, y), does not matter: only the set of corners is used).
  const auto turn = [](const LatticePoint& o, const LatticePoint& a, const LatticePoint& b)
  { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); };
  std::vector<LatticePoint> corners, slice;
  for (std::size_t k = 0; k < ends.size();)
  {
    std::size_t end = k;
    while (end < ends.size() && ends[end][2] == ends[k][2])
      ++end;
    slice.assign(ends.begin() + k, ends.begin() + end);
    const std::vector<LatticePoint> chain = monotoneChain(slice, turn);
    corners.insert(corners.end(), chain.begin(), chain.end());
    k = end;
  }
  return corners;
}

bool EmptyFaceTriangles::next(std::array<LatticePoint, 3>& out)
{
  while (!this->queue.empty())
  {
    FaceTriangle t = this->queue.top();
    this->queue.pop();
    if (!t.enumerated)
      forEachPointOnTriangle(
        t.corners, kUnbounded, [&](const LatticePoint& p) { t.points.push_back(p); });
    if (t.points.size() <= 3)
    {
      out = t.corners;
      return true;
    }
    const LatticePoint* split = nullptr;
    for (const auto& p : t.points)
      if (p != t.corners[0] && p != t.corners[1] && p != t.corners[2] &&
        (!split ||
          scaledDistance(p, 1, this->sum, this->m) < scaledDistance(*split, 1, this->sum, this->m)))
        split = &p;
    for (int e = 0; e < 3; ++e)
    {
      const std::array<LatticePoint, 3> child{ t.corners[e], t.corners[(e + 1) % 3], *split };
      if (planeThrough(child[0], child[1], child[2]).normal == LatticePoint{ 0, 0, 0 })
        continue; // the split point lies on this edge
      std::vector<LatticePoint> inside;
      for (const auto& p : t.points)
        if (onTriangle(child[0], child[1], child[2], t.plane, p))
          inside.push_back(p);
      this->push(child, t.plane, std::move(inside), true);
    }
  }
  return false;
}

bool fanIsEmbedded(const CellList& c)
{
  if (c.dimension != 3)
    return false;
  for (std::size_t f = 0; f < c.faces.size(); ++f)
  {
    const auto& face = c.faces[f];
    const FacePlane& plane = c.planes[f];
    for (std::size_t k = 0; k < face.size(); ++k)
    {
      const LatticePoint& a = c.vertices[face[k]];
      const LatticePoint edge = sub(c.vertices[face[(k + 1) % face.size()]], a);
      if (plane.evaluate(a) != 0)
        return false;
      for (std::size_t j = 0; j < face.size(); ++j)
        if (j != k && j != (k + 1) % face.size() &&
          dot(plane.normal, cross(edge, sub(c.vertices[face[j]], a))) <= 0)
          return false;
    }
  }
  return std::all_of(c.vertices.begin(),
    c.vertices.end(),
    [&](const LatticePoint& p)
    {
      return std::all_of(c.planes.begin(),
        c.planes.end(),
        [&](const FacePlane& plane) { return plane.evaluate(p) <= 0; });
    });
}

LevelSurface solveLevel(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  bool pit,
  int level,
  int& depth)
{
  if (ctx.exec.stopRequested())
    throw std::runtime_error("aborted");
  recordPlanes(ctx, c, level);
  depth = 0;
  LevelSurface out(c);
  PointRuns apart;
  std::vector<BoxedHull> pits;
  if (ctx.pits)
    pressInPits(ctx, c, parent, cls, pit, level, out, apart, pits, depth);
  else
    apart = pointsOfClass(c, ctx.objects, !cls, true);
  if (apart.empty())
    return out;
  std::vector<CellList> regions;
  std::vector<bool> pressed;
  if (!apartRegions(ctx, c, parent, cls, apart, pits, regions, pressed))
  {
    // A region kept apart meets a pit: the whole level kept apart, unless C must keep pits.
    if (pit)
      throw Unresolved("a group kept apart meets a pit");
    out = LevelSurface(c);
    depth = 0;
    apartRegions(
      ctx, c, parent, cls, pointsOfClass(c, ctx.objects, !cls, true), {}, regions, pressed);
  }
  solveApart(ctx, c, cls, level, regions, pressed, out, depth);
  return out;
}

CellList groupShape(const std::vector<LatticePoint>& points, CoplanarFaces coplanar)
{
  return shapeOf(PointRuns::of(points), coplanar);
}

} // namespace detail

} // namespace vbr
