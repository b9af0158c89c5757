// H of segments, flat sets and flat layers, which span no solid (FlatObjects.h).
#include "FlatObjects.h"

#include "ConvexHullModifier2D.h"
#include "HullFaces.h"
#include "HullPointRuns.h"
#include "HullShells.h"
#include "LatticeBasis.h"
#include "PolyhedronReversion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

/// The pyramid over a convex polygon `base` (corners in order, at least three, not collinear)
/// with `apex` off its plane, triangles oriented outwards: away from the centroid of all
/// corners, which lies strictly inside (a convex combination of every corner with positive
/// weights). A tetrahedron is the pyramid over a triangle.
LatticeMesh pyramidOver(const std::vector<LatticePoint>& base, const LatticePoint& apex)
{
  LatticeMesh out;
  out.points = base;
  out.points.push_back(apex);
  const auto n = static_cast<std::uint32_t>(base.size());
  LatticePoint sum{ 0, 0, 0 };
  for (const LatticePoint& p : out.points)
    for (int k = 0; k < 3; ++k)
      sum[k] += p[k];
  const auto count = static_cast<std::int64_t>(out.points.size());
  const auto addOutwards = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c)
  {
    const LatticePoint &p = out.points[a], &q = out.points[b], &s = out.points[c];
    const LatticePoint inward{
      sum[0] - count * p[0], sum[1] - count * p[1], sum[2] - count * p[2]
    };
    if (dot(cross(sub(q, p), sub(s, p)), inward) < 0)
      out.triangles.push_back({ a, b, c });
    else
      out.triangles.push_back({ a, c, b });
  };
  for (std::uint32_t k = 1; k + 1 < n; ++k)
    addOutwards(0, k, k + 1);
  for (std::uint32_t k = 0; k < n; ++k)
    addOutwards(k, (k + 1) % n, n);
  return out;
}

bool insideGrid(const LatticePoint& p, const Dims& dims)
{
  for (int k = 0; k < 3; ++k)
    if (p[k] < 0 || p[k] >= dims[k])
      return false;
  return true;
}

LatticePoint plus(const LatticePoint& a, const LatticePoint& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}

/// Flat objects (see the header): every object centre in one plane x_a = c. H is the prism of
/// the object's separating polygons in that plane (ConvexHullModifier2D) from x_a = c - 1 to
/// c + 1: the planes beside hold no object centre, so their centres inside the polygons may lie
/// on its caps, and the prism is a solid whose genus is the polygons' number of holes. A hole
/// whose background reaches beyond its polygon in the plane (a dent under an edge of the hull
/// that passes between lattice points) is no hole of the object: it is filled below the plane,
/// a pit from the top cap down to x_a = c, so that it adds no handle.

/// The lattice points strictly inside a polygon's outer loop, in the loop's box (none beyond).
struct OuterRegion
{
  Point2L lo{ 0, 0 };
  BitVolume inside;

  explicit OuterRegion(const SeparatingLoop& outer)
  {
    Point2L hi = outer.corners.front();
    this->lo = hi;
    for (const Point2L& p : outer.corners)
      for (int k = 0; k < 2; ++k)
      {
        this->lo[k] = std::min(this->lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    std::vector<SeparatingLoop> local{ outer };
    for (Point2L& p : local[0].corners)
      p = { p[0] - this->lo[0], p[1] - this->lo[1] };
    this->inside = revertSeparatingPolygons2D(local,
      latticePointsOnLoops(local),
      static_cast<std::int32_t>(hi[0] - this->lo[0] + 1),
      static_cast<std::int32_t>(hi[1] - this->lo[1] + 1));
  }

  bool strictlyInside(const Point2L& p) const
  {
    const std::int64_t x = p[0] - this->lo[0], y = p[1] - this->lo[1];
    return x >= 0 && y >= 0 && x < this->inside.size(0) && y < this->inside.size(1) &&
      this->inside.get(static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), 0);
  }
};

/// Whether the face-connected background of the image through the hole's first background
/// corner reaches a centre that is not strictly inside its polygon's outer loop (beyond the
/// image everything is background, and outside the loop): then the hole is a dent of the
/// object, not a hole. A centre strictly inside a ring of object centres is strictly inside
/// every loop about the ring, so a hole of the object never does. Only the outer loop's box
/// is searched.
bool holeReachesOut(const SeparatingLoop& hole, const OuterRegion& region, const BitVolume& image)
{
  const std::int32_t nx = image.size(0), ny = image.size(1);
  auto background = [&](const Point2L& p)
  {
    return p[0] < 0 || p[1] < 0 || p[0] >= nx || p[1] >= ny ||
      !image.get(static_cast<std::int32_t>(p[0]), static_cast<std::int32_t>(p[1]), 0);
  };
  auto start = std::find_if(hole.corners.begin(), hole.corners.end(), background);
  if (start == hole.corners.end())
    return false;
  BitVolume seen(region.inside.size(0), region.inside.size(1), 1);
  std::vector<Point2L> stack{ *start };
  while (!stack.empty())
  {
    const Point2L p = stack.back();
    stack.pop_back();
    if (!region.strictlyInside(p))
      return true; // beyond the image too: the loop lies about object centres of the image
    const auto x = static_cast<std::int32_t>(p[0] - region.lo[0]),
               y = static_cast<std::int32_t>(p[1] - region.lo[1]);
    if (seen.get(x, y, 0))
      continue;
    seen.set(x, y, 0);
    for (const Point2L& q : { Point2L{ p[0] + 1, p[1] },
           Point2L{ p[0] - 1, p[1] },
           Point2L{ p[0], p[1] + 1 },
           Point2L{ p[0], p[1] - 1 } })
      if (background(q))
        stack.push_back(q);
  }
  return false;
}

/// Whether a polygon of the plane lies inside the hole (its loops are apart from the hole's,
/// so one corner tells).
bool holdsAPolygon(const SeparatingPolygons& s, std::size_t hole)
{
  const auto& loop = s.loops[hole].corners;
  for (const SeparatingPolygon& other : s.polygons)
  {
    const Point2L& p = s.loops[other.outer].corners.front();
    bool in = false;
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
      if ((loop[i][1] > p[1]) != (loop[j][1] > p[1]) &&
        (orientation(loop[j], loop[i], p) > 0) == (loop[i][1] > loop[j][1]))
        in = !in;
    if (in)
      return true;
  }
  return false;
}

/// The point (u, v) of the plane at height h along axis a.
LatticePoint inSpace(const Point2L& p, int a, std::int64_t h)
{
  const auto uv = planeAxesOf(a);
  LatticePoint q{ 0, 0, 0 };
  q[uv[0]] = p[0];
  q[uv[1]] = p[1];
  q[a] = h;
  return q;
}

/// The triangles of a flat object's H, one vertex per lattice point, with their levels.
struct FlatMesh
{
  int axis;
  LatticeMesh& mesh;
  std::vector<int>& levels;
  std::map<LatticePoint, Index> index;

  Index vertex(const Point2L& p, std::int64_t h)
  {
    const LatticePoint q = inSpace(p, this->axis, h);
    auto it = this->index.emplace(q, static_cast<Index>(this->mesh.points.size()));
    if (it.second)
      this->mesh.points.push_back(q);
    return it.first->second;
  }

  /// The polygon's triangles at height h, counter-clockwise seen from +a unless `down`.
  void cap(const std::vector<Point2L>& corners,
    const std::vector<Triangle>& triangles,
    std::int64_t h,
    bool down,
    int level)
  {
    for (const Triangle& t : triangles)
    {
      std::array<Index, 3> tri{ this->vertex(corners[static_cast<std::size_t>(t[0])], h),
        this->vertex(corners[static_cast<std::size_t>(t[1])], h),
        this->vertex(corners[static_cast<std::size_t>(t[2])], h) };
      if (down)
        std::swap(tri[0], tri[2]);
      this->mesh.triangles.push_back(tri);
      this->levels.push_back(level);
    }
  }

  /// The quad from the edge [p0, q0] at height lo to [p1, q1] at hi, facing to the right of
  /// p -> q (away from the object on its left).
  void wall(const Point2L& p0,
    const Point2L& q0,
    const Point2L& p1,
    const Point2L& q1,
    std::int64_t lo,
    std::int64_t hi,
    int level)
  {
    const Index a0 = this->vertex(p0, lo), b0 = this->vertex(q0, lo), b1 = this->vertex(q1, hi),
                a1 = this->vertex(p1, hi);
    this->mesh.triangles.push_back({ a0, b0, b1 });
    this->mesh.triangles.push_back({ a0, b1, a1 });
    this->levels.insert(this->levels.end(), 2, level);
  }

  /// One quad per edge of the loop from height lo to hi, facing away from the loop's left side
  /// (the object's).
  void sides(const SeparatingLoop& loop, std::int64_t lo, std::int64_t hi)
  {
    const std::size_t n = loop.corners.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const Point2L &p = loop.corners[k], &q = loop.corners[(k + 1) % n];
      const Index p0 = this->vertex(p, lo), q0 = this->vertex(q, lo), q1 = this->vertex(q, hi),
                  p1 = this->vertex(p, hi);
      this->mesh.triangles.push_back({ p0, q0, q1 });
      this->mesh.triangles.push_back({ p0, q1, p1 });
      this->levels.insert(this->levels.end(), 2, loop.level);
    }
  }
};

/// The prism of one polygon with holes from x_a = c - 1 to c + 1: its caps at the polygon's
/// level, a quad per loop edge at the loop's level; a hole that reaches out (and holds no
/// polygon) only from c to c + 1 above its floor at c, and closed in the bottom cap. The loops
/// are simple, pairwise apart and carry the object on their left, so the sides face outwards
/// (away from holes as well) and the prisms of different polygons are apart: a closed
/// 2-manifold.
void appendPrism(const SeparatingPolygons& s,
  const SeparatingPolygon& polygon,
  const BitVolume& image,
  std::int64_t c,
  FlatMesh& out)
{
  SeparatingPolygon bottom = polygon;
  bottom.holes.clear();
  std::vector<std::size_t> dents;
  const std::optional<OuterRegion> region = polygon.holes.empty()
    ? std::nullopt
    : std::optional<OuterRegion>(OuterRegion(s.loops[polygon.outer]));
  for (const std::size_t h : polygon.holes)
    if (holeReachesOut(s.loops[h], *region, image) && !holdsAPolygon(s, h))
      dents.push_back(h);
    else
      bottom.holes.push_back(h);
  // The bottom cap is the top one unless a dent is filled: one triangulation saved.
  const std::vector<Triangle> top = triangulatePolygonWithHoles(s, polygon);
  out.cap(polygonCorners(s, polygon), top, c + 1, false, polygon.level);
  out.cap(polygonCorners(s, bottom),
    dents.empty() ? top : triangulatePolygonWithHoles(s, bottom),
    c - 1,
    true,
    polygon.level);
  out.sides(s.loops[polygon.outer], c - 1, c + 1);
  for (const std::size_t h : bottom.holes)
    out.sides(s.loops[h], c - 1, c + 1);
  for (const std::size_t h : dents)
  {
    // The floor: the hole's region (its loop reversed, counter-clockwise) facing +a.
    std::vector<Point2L> floor(s.loops[h].corners.rbegin(), s.loops[h].corners.rend());
    out.cap(floor, triangulateSimplePolygon(floor), c, false, s.loops[h].level);
    out.sides(s.loops[h], c, c + 1);
  }
}

/// The bounded face-connected background components of the layer that lie in one row of an
/// axis and outside every hole of the plane's polygons (closed): holes of the object that the
/// polygons lost (the 2D modifier found no lattice triangle for them inside the ring and
/// opened them as notches).
std::vector<std::vector<Point2L>> lostHoles(const BitVolume& image, const SeparatingPolygons& s)
{
  const std::int32_t nx = image.size(0), ny = image.size(1);
  std::vector<SeparatingLoop> holeLoops;
  for (const SeparatingLoop& loop : s.loops)
    if (loop.level % 2 == 1)
      holeLoops.push_back(loop);
  const BitVolume inHole = revertSeparatingPolygons2D(holeLoops, {}, nx, ny);
  BitVolume seen(nx, ny, 1);
  std::vector<std::vector<Point2L>> lost;
  for (std::int32_t y = 0; y < ny; ++y)
    for (std::int32_t x = 0; x < nx; ++x)
    {
      if (image.get(x, y, 0) || seen.get(x, y, 0))
        continue;
      std::vector<Point2L> component, stack{ { x, y } };
      bool bounded = true;
      seen.set(x, y, 0);
      while (!stack.empty())
      {
        const Point2L p = stack.back();
        stack.pop_back();
        component.push_back(p);
        for (const Point2L& q : { Point2L{ p[0] + 1, p[1] },
               Point2L{ p[0] - 1, p[1] },
               Point2L{ p[0], p[1] + 1 },
               Point2L{ p[0], p[1] - 1 } })
        {
          const auto qx = static_cast<std::int32_t>(q[0]), qy = static_cast<std::int32_t>(q[1]);
          if (qx < 0 || qy < 0 || qx >= nx || qy >= ny)
            bounded = false;
          else if (!image.get(qx, qy, 0) && !seen.get(qx, qy, 0))
          {
            seen.set(qx, qy, 0);
            stack.push_back(q);
          }
        }
      }
      auto sameAs = [&](int k)
      {
        return std::all_of(component.begin(),
          component.end(),
          [&](const Point2L& p) { return p[k] == component.front()[k]; });
      };
      if (bounded && (sameAs(0) || sameAs(1)) && !inHole.get(x, y, 0))
        lost.push_back(std::move(component));
    }
  return lost;
}

/// The planes of a mesh's triangles given `level` where they have none yet.
void addPlanes(const LatticeMesh& m, int level, std::map<FacePlane, int>& planeLevel)
{
  for (const auto& t : m.triangles)
    planeLevel.emplace(planeThrough(m.points[t[0]], m.points[t[1]], m.points[t[2]]), level);
}

/// B's box two steps wider than B on the plane's axes, from c - 1 to c + 1: its open interior
/// holds, in the plane, B and its eight neighbours only.
LatticeMesh lostHoleBox(const std::vector<Point2L>& hole, int a, std::int64_t c, bool tunnel)
{
  Point2L lo = hole.front(), hi = lo;
  for (const Point2L& p : hole)
    for (int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  std::vector<LatticePoint> corners;
  for (const std::int64_t h : { c - 1, c + 1 })
    if (!tunnel)
    {
      for (const std::int64_t u : { lo[0] - 2, hi[0] + 2 })
        for (const std::int64_t v : { lo[1] - 2, hi[1] + 2 })
          corners.push_back(inSpace({ u, v }, a, h));
    }
    else
      for (const Point2L& p : { lo, hi })
        for (const Point2L& d :
          { Point2L{ 1, 0 }, Point2L{ -1, 0 }, Point2L{ 0, 1 }, Point2L{ 0, -1 } })
          corners.push_back(inSpace({ p[0] + d[0], p[1] + d[1] }, a, h));
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  return triangulateHull(convexHull(corners));
}

/// Whether a cut through the lost hole B can separate, checked in the plane before any
/// Boolean: B's eight neighbours are object centres (they come strictly inside its box, B
/// inside its tunnel).
bool cuttable(const std::vector<Point2L>& hole, const BitVolume& image)
{
  Point2L lo = hole.front(), hi = lo;
  for (const Point2L& p : hole)
    for (int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  for (std::int64_t v = lo[1] - 1; v <= hi[1] + 1; ++v)
    for (std::int64_t u = lo[0] - 1; u <= hi[0] + 1; ++u)
    {
      const bool inHole = u >= lo[0] && v >= lo[1] && u <= hi[0] && v <= hi[1];
      const bool object = u >= 0 && v >= 0 && u < image.size(0) && v < image.size(1) &&
        image.get(static_cast<std::int32_t>(u), static_cast<std::int32_t>(v), 0);
      if (!inHole && !object)
        return false;
    }
  return true;
}

/// Handles through lost holes (see the header): H united with the box of the holes two steps
/// wider than them (lostHoleBox; one notch can hold several holes, and a hole on another's box
/// would come inside it) less the prism of each hole B's hexagon (the hull of B's four
/// neighbours, which holds B alone inside), kept when the result separates with as many shells
/// and one handle more per hole. The new planes get level 0 (the box) and 1 (the tunnels).
bool cutLostHoles(const BitVolume& objects,
  int a,
  std::int64_t c,
  const std::vector<std::vector<Point2L>>& holes,
  LatticeMesh& surface,
  std::map<FacePlane, int>& planeLevel)
{
  std::vector<Point2L> all;
  std::vector<LatticeMesh> tunnels;
  for (const auto& hole : holes)
  {
    all.insert(all.end(), hole.begin(), hole.end());
    tunnels.push_back(lostHoleBox(hole, a, c, true));
  }
  const LatticeMesh box = lostHoleBox(all, a, c, false);
  LatticeMesh cut;
  if (!latticeUnion(surface, box, cut))
    return false;
  for (const LatticeMesh& t : tunnels)
  {
    LatticeMesh next;
    if (!latticeDifference(cut, t, next))
      return false;
    cut = std::move(next);
  }
  const long handles = static_cast<long>(holes.size());
  if (shellsOf(cut).size() != shellsOf(surface).size() ||
    eulerCharacteristic(cut) != eulerCharacteristic(surface) - 2 * handles ||
    !separates(objects, cut))
    return false;
  surface = std::move(cut);
  addPlanes(box, 0, planeLevel);
  for (const LatticeMesh& t : tunnels)
  {
    LatticeMesh walls; // the tunnel's faces as H has them: facing into the tunnel
    walls.append(t, true);
    addPlanes(walls, 1, planeLevel);
  }
  return true;
}

/// At most this many lost holes are cut per object: each costs two exact Booleans of H, and
/// three more when they are tried one by one.
constexpr std::size_t MaxLostHoles = 16;

/// Reports the flat path's progress; throws (as the rest of the modifier does) when asked to
/// stop.
void flatStep(const Execution& exec, double fraction)
{
  if (exec.stopRequested() || !exec.report(fraction))
    throw std::runtime_error("aborted");
}

/// Appends a note to the result's failure text (a complete H that misses something says so).
void note(ModifiedHull& r, const std::string& text)
{
  r.failure += (r.failure.empty() ? "" : "; ") + text;
}

/// The face-connected regions of a layer's image padded by one pixel (both classes: in a
/// well-composed layer face and corner connectivity agree), with their nesting depth: the
/// number of region boundaries crossed from the outer background (the padding's region, depth
/// 0; the object components about it 1, their holes 2, islands in those 3, ...).
struct PlaneRegions
{
  std::int32_t nx = 0, ny = 0; ///< the padded size; pixel (x, y) of the image is (x + 1, y + 1)
  std::vector<std::int32_t> region; ///< per padded pixel
  std::vector<bool> object;         ///< per region: of the object's class
  std::vector<int> depth;           ///< per region

  std::int32_t at(std::int64_t x, std::int64_t y) const
  {
    return this->region[static_cast<std::size_t>(y * this->nx + x)];
  }
};

/// The regions of the padded image (CUDB components of each class) and their depths (breadth
/// first over the regions that share a pixel edge).
PlaneRegions planeRegions(const BitVolume& image)
{
  PlaneRegions g;
  g.nx = image.size(0) + 2;
  g.ny = image.size(1) + 2;
  g.region.assign(static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny), -1);
  std::array<std::vector<LatticePoint>, 2> points; // background, object
  for (std::int32_t y = 0; y < g.ny; ++y)
    for (std::int32_t x = 0; x < g.nx; ++x)
    {
      const bool in =
        x > 0 && y > 0 && x <= image.size(0) && y <= image.size(1) && image.get(x - 1, y - 1, 0);
      points[in].push_back({ x, y, 0 });
    }
  for (const bool cls : { false, true })
    for (const auto& component : componentsOf(points[cls], true, false))
    {
      for (const auto& p : component)
        g.region[static_cast<std::size_t>(p[1] * g.nx + p[0])] =
          static_cast<std::int32_t>(g.object.size());
      g.object.push_back(cls);
    }
  std::vector<std::set<std::int32_t>> next(g.object.size());
  for (std::int32_t y = 0; y < g.ny; ++y)
    for (std::int32_t x = 0; x < g.nx; ++x)
      for (const Point2L& q : { Point2L{ x + 1, y }, Point2L{ x, y + 1 } })
        if (q[0] < g.nx && q[1] < g.ny && g.at(x, y) != g.at(q[0], q[1]))
        {
          next[static_cast<std::size_t>(g.at(x, y))].insert(g.at(q[0], q[1]));
          next[static_cast<std::size_t>(g.at(q[0], q[1]))].insert(g.at(x, y));
        }
  g.depth.assign(g.object.size(), -1);
  std::vector<std::int32_t> queue{ g.at(0, 0) };
  g.depth[static_cast<std::size_t>(queue[0])] = 0;
  for (std::size_t k = 0; k < queue.size(); ++k)
    for (const std::int32_t r : next[static_cast<std::size_t>(queue[k])])
      if (g.depth[static_cast<std::size_t>(r)] < 0)
      {
        g.depth[static_cast<std::size_t>(r)] = g.depth[static_cast<std::size_t>(queue[k])] + 1;
        queue.push_back(r);
      }
  return g;
}

/// Per region, twice the Euler characteristic of its pixels' union (V - E + F of the pixels,
/// the pixel edges and the 2 x 2 blocks within it: in a well-composed layer that complex has
/// the homotopy type of the union of the closed pixel squares): for an object component, the
/// Euler characteristic of the surface about it.
std::vector<long> regionSurfaceEulers(const PlaneRegions& g)
{
  std::vector<long> chi(g.object.size(), 0);
  for (std::int32_t y = 0; y < g.ny; ++y)
    for (std::int32_t x = 0; x < g.nx; ++x)
    {
      const std::int32_t r = g.at(x, y);
      const bool right = x + 1 < g.nx && g.at(x + 1, y) == r,
                 up = y + 1 < g.ny && g.at(x, y + 1) == r;
      const bool block = right && up && g.at(x + 1, y + 1) == r;
      chi[static_cast<std::size_t>(r)] += 2 * (1 - right - up + block);
    }
  return chi;
}

/// Whether H of a well-composed flat layer has the topology of the object's boundary shell by
/// shell: as many shells as object components, each shell holding (inside or on it) the
/// centres of exactly one component and all of them, and with the Euler characteristic of the
/// surface about that component (the layer's background is one component in space, about
/// every shell: separation keeps its centres out of H).
bool flatShellsMatch(const BitVolume& objects,
  int a,
  std::int64_t c,
  const PlaneRegions& g,
  const LatticeMesh& surface)
{
  const std::vector<Shell> shells = shellsOf(surface);
  const long objectRegions = std::count(g.object.begin(), g.object.end(), true);
  if (static_cast<long>(shells.size()) != objectRegions)
    return false;
  const std::vector<long> chi = regionSurfaceEulers(g);
  if (objectRegions == 1)
  {
    // One shell for one component: H separates, so the shell holds all of its centres.
    const auto r = static_cast<std::size_t>(
      std::find(g.object.begin(), g.object.end(), true) - g.object.begin());
    return eulerCharacteristic(shells[0].mesh) == chi[r];
  }
  const Dims d = objects.dims();
  const auto uv = planeAxesOf(a);
  std::vector<long> size(g.object.size(), 0);
  for (const std::int32_t r : g.region)
    ++size[static_cast<std::size_t>(r)];
  std::vector<bool> claimed(g.object.size(), false);
  std::vector<std::uint8_t> held(objects.voxelCount(), 0);
  for (const Shell& shell : shells)
  {
    // The shell's box in the grid: only there can it hold a centre (and be cleared again).
    LatticePoint lo = shell.mesh.points[0], hi = lo;
    for (const auto& q : shell.mesh.points)
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::max<std::int64_t>(std::min(lo[k], q[k]), 0);
        hi[k] = std::min<std::int64_t>(std::max(hi[k], q[k]), d[k] - 1);
      }
    markShell(shell.mesh, d, 1, 1, held);
    std::map<std::int32_t, long> count; // object pixels held, per component
    LatticePoint p = lo;
    for (p[2] = lo[2]; p[2] <= hi[2]; ++p[2])
      for (p[1] = lo[1]; p[1] <= hi[1]; ++p[1])
        for (p[0] = lo[0]; p[0] <= hi[0]; ++p[0])
        {
          std::uint8_t& mark = held[gridIndex(d, p)];
          const std::int32_t r = g.at(p[uv[0]] + 1, p[uv[1]] + 1);
          if (mark != 0 && p[a] == c && g.object[static_cast<std::size_t>(r)])
            ++count[r];
          mark = 0;
        }
    if (count.size() != 1)
      return false; // no component, or two in one shell
    const auto r = static_cast<std::size_t>(count.begin()->first);
    if (claimed[r] || count.begin()->second != size[r] || eulerCharacteristic(shell.mesh) != chi[r])
      return false;
    claimed[r] = true;
  }
  return true;
}

/// The sheared pixel solid of a well-composed layer (see the header): each object pixel p's
/// square p + [-1/2, 1/2]^2 at x_a = c is the middle section of the parallelepiped with top
/// p + [0, 1]^2 at c + 1 and bottom p + [-1, 0]^2 at c - 1; those of all pixels tile the slab
/// face to face, and H is the boundary of the union of the object pixels' ones: a cap square
/// per pixel on top and below, a wall per pixel edge between an object and a background
/// pixel. Levels: caps one less than their component's depth, walls one less than the deeper
/// of their two regions (0 about the outer background, 1 about a hole, 2 about an island, ...).
void appendPixelSolid(const PlaneRegions& g, std::int64_t c, FlatMesh& out)
{
  static const std::array<Point2L, 4> corner{
    Point2L{ 0, 0 }, Point2L{ 1, 0 }, Point2L{ 1, 1 }, Point2L{ 0, 1 }
  };
  // The pixel's sides, counter-clockwise: the neighbour beyond corner k -> k + 1.
  static const std::array<Point2L, 4> beyond{
    Point2L{ 0, -1 }, Point2L{ 1, 0 }, Point2L{ 0, 1 }, Point2L{ -1, 0 }
  };
  const std::vector<Triangle> square{ { 0, 1, 2 }, { 0, 2, 3 } };
  for (std::int32_t y = 1; y + 1 < g.ny; ++y)
    for (std::int32_t x = 1; x + 1 < g.nx; ++x)
    {
      const auto r = static_cast<std::size_t>(g.at(x, y));
      if (!g.object[r])
        continue;
      const Point2L p{ x - 1, y - 1 };
      std::vector<Point2L> top, bottom;
      for (const Point2L& k : corner)
      {
        top.push_back({ p[0] + k[0], p[1] + k[1] });
        bottom.push_back({ p[0] + k[0] - 1, p[1] + k[1] - 1 });
      }
      out.cap(top, square, c + 1, false, g.depth[r] - 1);
      out.cap(bottom, square, c - 1, true, g.depth[r] - 1);
      for (std::size_t k = 0; k < 4; ++k)
      {
        const auto n = static_cast<std::size_t>(g.at(x + beyond[k][0], y + beyond[k][1]));
        if (!g.object[n])
          out.wall(bottom[k],
            bottom[(k + 1) % 4],
            top[k],
            top[(k + 1) % 4],
            c - 1,
            c + 1,
            std::max(g.depth[r], g.depth[n]) - 1);
      }
    }
}

/// Whether the layer is well-composed (no two object pixels touching only at a corner: then
/// its boundary in space is a 2-manifold, which H must match shell by shell).
bool wellComposedLayer(const BitVolume& image, const Execution& exec)
{
  BitVolume layer(image.size(0), image.size(1), 3);
  for (std::int32_t y = 0; y < image.size(1); ++y)
    for (std::int32_t x = 0; x < image.size(0); ++x)
      if (image.get(x, y, 0))
        layer.set(x, y, 1);
  return wellComposedBoundaryEuler(layer, exec).has_value();
}

/// H of a well-composed layer replaced by its sheared pixel solid (see the header), complete
/// and with nothing to note: the plane's counts become its holes (background regions below
/// the outer one) and its deepest level.
void usePixelSolid(const PlaneRegions& g, int a, std::int64_t c, ModifiedHull& r)
{
  r.surface = LatticeMesh();
  r.faces.clear();
  std::vector<int> levels;
  FlatMesh out{ a, r.surface, levels, {} };
  appendPixelSolid(g, c, out);
  r.complete = true;
  r.failure.clear();
  r.cutHandles = 0;
  r.concavities = 0;
  r.cavities = 0;
  r.degreeOfNonConvexity = 0;
  for (std::size_t k = 0; k < g.object.size(); ++k)
  {
    r.cavities += !g.object[k] && g.depth[k] > 0;
    r.degreeOfNonConvexity = std::max(r.degreeOfNonConvexity, g.depth[k] - 1);
  }
  r.flatPixelSolid = true;
  mergeIntoFaces({}, levels, r);
}

} // namespace

std::array<int, 2> planeAxesOf(int a)
{
  return { (a + 1) % 3, (a + 2) % 3 };
}

BitVolume layerImage(const BitVolume& objects, int a, std::int32_t c)
{
  const auto uv = planeAxesOf(a);
  BitVolume image(objects.size(uv[0]), objects.size(uv[1]), 1);
  std::array<std::int32_t, 3> i{ 0, 0, 0 };
  i[a] = c;
  for (i[uv[1]] = 0; i[uv[1]] < objects.size(uv[1]); ++i[uv[1]])
    for (i[uv[0]] = 0; i[uv[0]] < objects.size(uv[0]); ++i[uv[0]])
      if (objects.get(i[0], i[1], i[2]))
        image.set(i[uv[0]], i[uv[1]], 0);
  return image;
}

namespace detail
{

LatticeMesh segmentTetrahedron(const CellList& hull, const Dims& dims)
{
  const LatticePoint a = hull.vertices[0], b = hull.vertices[1];
  const LatticePoint ab = sub(b, a), d = primitive(ab);
  const std::int64_t m = std::gcd(std::gcd(std::abs(ab[0]), std::abs(ab[1])), std::abs(ab[2]));
  const auto uw = basisAroundLine(d);
  // the first corner a + step + k d (k = 0..m) inside the grid; a + steps[0] when none is
  const auto cornerNearSegment = [&](const std::vector<LatticePoint>& steps)
  {
    for (std::int64_t k = 0; k <= m; ++k)
      for (const LatticePoint& s : steps)
      {
        const LatticePoint p{
          a[0] + s[0] + k * d[0], a[1] + s[1] + k * d[1], a[2] + s[2] + k * d[2]
        };
        if (insideGrid(p, dims))
          return p;
      }
    return plus(a, steps[0]);
  };
  const LatticePoint &u = uw[0], &w = uw[1];
  const LatticePoint minusU = sub({ 0, 0, 0 }, u), minusW = sub({ 0, 0, 0 }, w);
  const LatticePoint x = cornerNearSegment({ u, minusU });
  const LatticePoint y =
    cornerNearSegment({ w, minusW, plus(w, u), plus(minusW, u), sub(w, u), sub(minusW, u) });
  return pyramidOver({ a, b, x }, y);
}

LatticeMesh flatSetPyramid(const CellList& hull, const Dims& dims)
{
  std::vector<LatticePoint> base;
  for (std::uint32_t v : hull.faces[0])
    base.push_back(hull.vertices[v]);
  const PlaneLattice lattice = latticeOfPlane(hull.planes[0].normal);
  double centroid[3] = { 0, 0, 0 };
  for (const LatticePoint& p : base)
    for (int k = 0; k < 3; ++k)
      centroid[k] += double(p[k]) / double(base.size());
  const LatticePoint &v1 = lattice.basis[0], &v2 = lattice.basis[1];
  const auto dotD = [](const LatticePoint& p, const double* q)
  { return double(p[0]) * q[0] + double(p[1]) * q[1] + double(p[2]) * q[2]; };
  const double g11 = double(dot(v1, v1)), g12 = double(dot(v1, v2)), g22 = double(dot(v2, v2));
  LatticePoint best{};
  double bestDistance = std::numeric_limits<double>::infinity();
  bool bestInside = false;
  for (int side : { 1, -1 })
  {
    const LatticePoint origin = side > 0 ? plus(base[0], lattice.step) : sub(base[0], lattice.step);
    const double toCentroid[3] = { centroid[0] - double(origin[0]),
      centroid[1] - double(origin[1]),
      centroid[2] - double(origin[2]) };
    const double b1 = dotD(v1, toCentroid), b2 = dotD(v2, toCentroid), det = g11 * g22 - g12 * g12;
    const auto a0 = std::llround((b1 * g22 - b2 * g12) / det);
    const auto c0 = std::llround((b2 * g11 - b1 * g12) / det);
    for (std::int64_t i = a0 - 1; i <= a0 + 1; ++i)
      for (std::int64_t j = c0 - 1; j <= c0 + 1; ++j)
      {
        const LatticePoint y{ origin[0] + i * v1[0] + j * v2[0],
          origin[1] + i * v1[1] + j * v2[1],
          origin[2] + i * v1[2] + j * v2[2] };
        double distance = 0;
        for (int k = 0; k < 3; ++k)
          distance += (double(y[k]) - centroid[k]) * (double(y[k]) - centroid[k]);
        const bool inside = insideGrid(y, dims);
        if ((inside && !bestInside) || (inside == bestInside && distance < bestDistance))
        {
          best = y;
          bestDistance = distance;
          bestInside = inside;
        }
      }
  }
  return pyramidOver(base, best);
}

int gridPlaneAxis(const std::vector<LatticePoint>& points)
{
  for (int a = 2; a >= 0; --a)
    if (std::all_of(points.begin(),
          points.end(),
          [&](const LatticePoint& p) { return p[a] == points.front()[a]; }))
      return a;
  return -1;
}

void solveFlatObject(const BitVolume& objects,
  int a,
  std::int64_t c,
  const Execution& exec,
  ModifiedHull& r)
{
  const BitVolume image = layerImage(objects, a, static_cast<std::int32_t>(c));
  const SeparatingPolygons s = separatingPolygons2D(image, exec.within(0, 0.3));
  flatStep(exec, 0.3);
  r.complete = s.complete;
  if (!s.complete)
    r.failure = "in the object's plane: " + s.failure;
  r.concavities = s.notches;
  r.cavities = s.holes;
  r.degreeOfNonConvexity = s.degreeOfNonConvexity;
  std::vector<int> levels;
  FlatMesh out{ a, r.surface, levels, {} };
  for (const SeparatingPolygon& polygon : s.polygons)
    appendPrism(s, polygon, image, c, out);
  std::map<FacePlane, int> planeLevel;
  std::vector<std::vector<Point2L>> lost;
  std::size_t dropped = 0;
  for (auto& hole : lostHoles(image, s))
    if (!cuttable(hole, image))
      continue;
    else if (lost.size() < MaxLostHoles)
      lost.push_back(std::move(hole));
    else
      ++dropped;
  if (dropped > 0)
    note(r,
      "in the object's plane: " + std::to_string(dropped) + " lost hole(s) beyond the first " +
        std::to_string(MaxLostHoles) + " not cut");
  if (!lost.empty())
  {
    for (std::size_t t = 0; t < r.surface.triangles.size(); ++t)
    {
      const auto& tri = r.surface.triangles[t];
      planeLevel.emplace(
        planeThrough(r.surface.points[tri[0]], r.surface.points[tri[1]], r.surface.points[tri[2]]),
        levels[t]);
    }
    flatStep(exec, 0.4);
    // All together first; when that fails (a hole's box that holds background), one by one.
    if (cutLostHoles(objects, a, c, lost, r.surface, planeLevel))
      r.cutHandles = static_cast<int>(lost.size());
    else if (lost.size() > 1)
      for (std::size_t k = 0; k < lost.size(); ++k)
      {
        flatStep(exec, 0.4 + 0.3 * static_cast<double>(k) / static_cast<double>(lost.size()));
        r.cutHandles += cutLostHoles(objects, a, c, { lost[k] }, r.surface, planeLevel);
      }
  }
  mergeIntoFaces(planeLevel, r.cutHandles > 0 ? std::vector<int>() : levels, r);
  flatStep(exec, 0.7);
  if (!wellComposedLayer(image, exec))
    return;
  const PlaneRegions g = planeRegions(image);
  if (!r.complete || !flatShellsMatch(objects, a, c, g, r.surface))
    usePixelSolid(g, a, c, r);
}

} // namespace detail

} // namespace vbr
