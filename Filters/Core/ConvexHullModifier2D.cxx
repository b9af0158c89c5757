// Separating polygons of a 2D pixel set by recursive pressing-in of lattice hulls (the method
// is described in ConvexHullModifier2D.h). The passes: group the centres of one class strictly
// inside a region with those on its boundary (8-connected components), give each group a
// region (a notch opened through the edge it touches; else its lattice hull by Andrew's
// monotone chain, a thickened triangle when flat, or a notch from an empty edge piece), merge
// the groups of regions that meet until the regions are pairwise apart, recurse into every
// region; then write each region's loop with its notches spliced in recursively, holes
// reversed, and the background centres on the loops. Every decision
// is an exact integer test: orientations and row spans of hulls in 128-bit products, lattice
// points inside a notch by Pick's theorem, disjointness of convex regions by separating edges.
// The triangles of a polygon with holes come from a constrained Delaunay triangulation of its
// loops (corners are integers, exact in doubles, and no constraints cross, so exact predicates
// suffice), each triangle kept when its centroid lies inside.
#include "ConvexHullModifier2D.h"

#include "Geometry.h"
#include "UnionFind.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <deque>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace vbr
{
namespace
{

using Points = std::vector<Point2L>;

Wide cross(const Point2L& o, const Point2L& a, const Point2L& b)
{
  return Wide(a[0] - o[0]) * (b[1] - o[1]) - Wide(a[1] - o[1]) * (b[0] - o[0]);
}

std::int64_t gcdOf(std::int64_t a, std::int64_t b)
{
  return std::gcd(a < 0 ? -a : a, b < 0 ? -b : b);
}

Wide absWide(Wide w)
{
  return w < 0 ? -w : w;
}

std::int64_t dist2(const Point2L& a, const Point2L& b)
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]);
}

/// Row order: by y, then x, the order in which the image and a hull's interior are scanned.
bool rowOrder(const Point2L& a, const Point2L& b)
{
  return a[1] < b[1] || (a[1] == b[1] && a[0] < b[0]);
}

/// The strictly convex hull, counter-clockwise from its lowest corner; one or two corners when
/// the points are flat. The monotone chain runs along y: points scanned row by row need no sort.
Points latticeHull(Points p)
{
  if (!std::is_sorted(p.begin(), p.end(), rowOrder))
    std::sort(p.begin(), p.end(), rowOrder);
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return monotoneChain(
    p, [](const Point2L& o, const Point2L& a, const Point2L& b) { return cross(o, a, b); });
}

/// The x of the lattice points strictly inside a convex counter-clockwise polygon on row y,
/// [lo, hi] (empty when lo > hi). An edge u -> v keeps p when cross(v - u, p - u) > 0, that is
/// c - ey * x > 0 with c = ex (y - uy) + ey ux: a bound on x, or on the row when ey = 0.
std::pair<std::int64_t, std::int64_t> interiorSpan(const Points& h, std::int64_t y)
{
  std::int64_t lo = std::numeric_limits<std::int64_t>::min() / 4;
  std::int64_t hi = std::numeric_limits<std::int64_t>::max() / 4;
  for (std::size_t i = 0; i < h.size(); ++i)
  {
    const Point2L& u = h[i];
    const Point2L& v = h[(i + 1) % h.size()];
    const Wide ex = v[0] - u[0], ey = v[1] - u[1];
    const Wide c = ex * (y - u[1]) + ey * u[0];
    if (ey == 0 && c <= 0)
      return { 1, 0 };
    if (ey > 0) // x < c / ey
    {
      Wide q = c / ey;
      if (c % ey != 0 && c > 0)
        ++q;
      hi = std::min<std::int64_t>(hi, static_cast<std::int64_t>(q - 1));
    }
    else if (ey < 0) // x > -c / m, m = -ey
    {
      const Wide m = -ey, n = -c;
      Wide q = n / m;
      if (n % m != 0 && n < 0)
        --q;
      lo = std::max<std::int64_t>(lo, static_cast<std::int64_t>(q + 1));
    }
  }
  return { lo, hi };
}

struct Box
{
  std::int64_t x0, y0, x1, y1;
};

Box boxOf(const Points& p)
{
  Box b{ p[0][0], p[0][1], p[0][0], p[0][1] };
  for (const Point2L& q : p)
  {
    b.x0 = std::min(b.x0, q[0]);
    b.y0 = std::min(b.y0, q[1]);
    b.x1 = std::max(b.x1, q[0]);
    b.y1 = std::max(b.y1, q[1]);
  }
  return b;
}

/// The object pixels of the image; lattice points off it are background.
struct Image2D
{
  const BitVolume& pixels;
  std::int64_t nx, ny;

  bool inside(const Point2L& p) const { return p[0] >= 0 && p[1] >= 0 && p[0] < nx && p[1] < ny; }
  bool object(const Point2L& p) const
  {
    return this->inside(p) &&
      this->pixels.get(static_cast<std::int32_t>(p[0]), static_cast<std::int32_t>(p[1]), 0);
  }
};

/// The centres of one class strictly inside a hull. Only hulls whose corners are pixels have
/// lattice points inside (the thickened triangles of level 0 are empty), so the image's rows
/// and columns bound the scan.
Points centresInside(const Points& h, const Image2D& img, bool object)
{
  Points found;
  const Box b = boxOf(h);
  for (std::int64_t y = std::max<std::int64_t>(b.y0 + 1, 0); y < std::min(b.y1, img.ny); ++y)
  {
    const auto span = interiorSpan(h, y);
    for (std::int64_t x = std::max<std::int64_t>(span.first, 0);
         x <= std::min(span.second, img.nx - 1);
         ++x)
      if (img.object({ x, y }) == object)
        found.push_back({ x, y });
  }
  return found;
}

/// The 8-connected components of a set of lattice points (sorted only when not in row order
/// already: every nested level scans its hull's points in that order, and sorting them again
/// was half of the time on noise).
std::vector<Points> components(Points p)
{
  if (!std::is_sorted(p.begin(), p.end(), rowOrder))
    std::sort(p.begin(), p.end(), rowOrder);
  p.erase(std::unique(p.begin(), p.end()), p.end());
  UnionFind sets(p.size());
  // In row order the neighbour (x + 1, y) is the next point, and the neighbours (x - 1 ..
  // x + 1, y + 1) lie at a position that only moves forward: one pass, no search.
  std::size_t next = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const auto i32 = static_cast<std::uint32_t>(i);
    if (i + 1 < p.size() && p[i + 1] == Point2L{ p[i][0] + 1, p[i][1] })
      sets.unite(i32, i32 + 1);
    const Point2L lowest{ p[i][0] - 1, p[i][1] + 1 };
    while (next < p.size() && rowOrder(p[next], lowest))
      ++next;
    for (std::size_t j = next; j < p.size() && j < next + 3; ++j)
      if (p[j][1] == lowest[1] && p[j][0] <= lowest[0] + 2)
        sets.unite(i32, static_cast<std::uint32_t>(j));
  }
  std::uint32_t count = 0;
  const std::vector<std::uint32_t> number = sets.numberClasses(count);
  std::vector<Points> groups(count);
  for (std::size_t i = 0; i < p.size(); ++i)
    groups[number[i]].push_back(p[i]);
  return groups;
}

/// Calls f for every lattice point of the loop (each once: an edge without its end).
template<typename F>
void forLatticePointsOf(const Points& loop, F&& f)
{
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const Point2L& u = loop[i];
    const Point2L& v = loop[(i + 1) % loop.size()];
    const std::int64_t k = gcdOf(v[0] - u[0], v[1] - u[1]);
    for (std::int64_t j = 0; j < k; ++j)
      f(Point2L{ u[0] + j * (v[0] - u[0]) / k, u[1] + j * (v[1] - u[1]) / k });
  }
}

/// The region of one group: a hull (three corners or more, counter-clockwise), or none.
struct Shape
{
  /// The hull of the group's centres (one or two corners when flat): all a merge needs.
  Points core;
  /// Centres of the group's class on the parent's boundary 8-connected to it (a concavity
  /// opening there), not on a notch parent's own piece.
  Points touching;
  Points hull;
  bool notch = false;
  std::size_t edge = 0; ///< a notch's edge of the parent hull, and its piece [a, b] on it
  Point2L a{ 0, 0 }, b{ 0, 0 };
};

/// Level 0: a flat group plus one lattice point (two for a single centre) off its line, making
/// a triangle with no lattice point but its corners and the group; inside the image if it can.
Points thickenFree(const Points& flat, const Image2D& img)
{
  const Point2L g = flat[0];
  if (flat.size() == 1)
  {
    const std::int64_t sx = g[0] + 1 < img.nx || g[0] == 0 ? 1 : -1;
    const std::int64_t sy = g[1] + 1 < img.ny || g[1] == 0 ? 1 : -1;
    return latticeHull({ g, { g[0] + sx, g[1] }, { g[0], g[1] + sy } });
  }
  const std::int64_t k = gcdOf(flat[1][0] - g[0], flat[1][1] - g[1]);
  const Point2L d{ (flat[1][0] - g[0]) / k, (flat[1][1] - g[1]) / k };
  // n with det(d, n) = 1 (extended Euclid on the primitive d): every triangle g1 g2 (g1 + n +
  // t d) then has area k / 2 and k + 2 boundary points, so none inside (Pick).
  std::int64_t s0 = 1, t0 = 0, s1 = 0, t1 = 1, r0 = d[0], r1 = d[1];
  while (r1 != 0)
  {
    const std::int64_t q = r0 / r1;
    std::tie(r0, r1) = std::make_pair(r1, r0 - q * r1);
    std::tie(s0, s1) = std::make_pair(s1, s0 - q * s1);
    std::tie(t0, t1) = std::make_pair(t1, t0 - q * t1);
  }
  const Point2L n{ -t0 * r0, s0 * r0 }; // d0 s0 + d1 t0 = r0 = +-1
  Point2L q{ g[0] + n[0], g[1] + n[1] };
  const std::int64_t reach = img.nx + img.ny;
  for (std::int64_t t = 0; t <= reach && !img.inside(q); ++t)
    for (const Point2L& c : { Point2L{ g[0] + n[0] + t * d[0], g[1] + n[1] + t * d[1] },
           Point2L{ g[0] - n[0] + t * d[0], g[1] - n[1] + t * d[1] },
           Point2L{ g[0] + n[0] - t * d[0], g[1] + n[1] - t * d[1] },
           Point2L{ g[0] - n[0] - t * d[0], g[1] - n[1] - t * d[1] } })
      if (!img.inside(q) && img.inside(c))
        q = c;
  return latticeHull({ flat[0], flat[1], q });
}

/// The lattice points strictly inside the parent within a window around a flat group.
Points candidatesNear(const Points& flat, const Points& parent, const Box& window)
{
  Points found;
  for (std::int64_t y = window.y0; y <= window.y1; ++y)
  {
    const auto span = interiorSpan(parent, y);
    for (std::int64_t x = std::max(span.first, window.x0); x <= std::min(span.second, window.x1);
         ++x)
    {
      const Point2L q{ x, y };
      const bool off = flat.size() == 1 ? q != flat[0] : cross(flat[0], flat[1], q) != 0;
      if (off)
        found.push_back(q);
    }
  }
  return found;
}

/// The corners a flat group needs to become a triangle from the candidates (the nearest, of
/// least area); empty when the candidates are all on one line through the group.
Points thickeningFrom(const Points& flat, const Points& candidates)
{
  const Point2L g = flat[0];
  const Point2L h = flat.size() == 1 ? g : flat[1];
  auto best = [&](const Point2L& o, const Point2L& p, const Points& c)
  {
    Points pick;
    Wide area = 0;
    std::int64_t far = 0;
    for (const Point2L& q : c)
    {
      const Wide w = absWide(cross(o, p, q));
      const std::int64_t f = dist2(q, g) + dist2(q, h);
      if (w != 0 && (pick.empty() || w < area || (w == area && f < far)))
      {
        pick = { q };
        area = w;
        far = f;
      }
    }
    return pick;
  };
  if (flat.size() == 2)
    return best(g, h, candidates);
  const Point2L* nearest = &candidates[0];
  for (const Point2L& q : candidates)
    if (dist2(q, g) < dist2(*nearest, g))
      nearest = &q;
  Points second = best(g, *nearest, candidates);
  if (second.empty())
    return {};
  return { *nearest, second[0] };
}

/// Below a hull: the lattice points strictly inside it nearest to the flat group, in windows
/// doubling in size until one has a point off the group's line.
bool thickenInside(Shape& s, const Points& flat, const Points& parent)
{
  const Box outer = boxOf(parent);
  const Box near = boxOf(flat);
  for (std::int64_t r = 1;; r *= 2)
  {
    const Box w{ std::max(near.x0 - r, outer.x0),
      std::max(near.y0 - r, outer.y0),
      std::min(near.x1 + r, outer.x1),
      std::min(near.y1 + r, outer.y1) };
    const Points c = candidatesNear(flat, parent, w);
    if (!c.empty())
    {
      Points corners = thickeningFrom(flat, c);
      if (!corners.empty())
      {
        corners.insert(corners.end(), flat.begin(), flat.end());
        s.hull = latticeHull(corners);
        return true;
      }
    }
    if (w.x0 == outer.x0 && w.y0 == outer.y0 && w.x1 == outer.x1 && w.y1 == outer.y1)
      return false;
  }
}

/// Twice the area and the lattice points on the boundary of a convex polygon.
std::int64_t interiorLatticePoints(const Points& p)
{
  Wide twice = 0, boundary = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Point2L& u = p[i];
    const Point2L& v = p[(i + 1) % p.size()];
    twice += Wide(u[0]) * v[1] - Wide(v[0]) * u[1];
    boundary += gcdOf(v[0] - u[0], v[1] - u[1]);
  }
  return static_cast<std::int64_t>((twice - boundary + 2) / 2); // Pick: A = I + B / 2 - 1
}

/// A flat group pressed in from a piece [a, b] of an edge of the parent between consecutive
/// lattice points: the notch conv(a, b, group) of least area with no lattice point inside.
/// Never from a notch parent's own piece (that is its parent's boundary).
bool notchFrom(Shape& s, const Points& flat, const Shape& region)
{
  const Points& parent = region.hull;
  Wide bestArea = -1;
  for (std::size_t e = 0; e < parent.size(); ++e)
  {
    const Point2L& u = parent[e];
    const Point2L& v = parent[(e + 1) % parent.size()];
    if (region.notch && u == region.a && v == region.b)
      continue;
    const std::int64_t k = gcdOf(v[0] - u[0], v[1] - u[1]);
    const Point2L step{ (v[0] - u[0]) / k, (v[1] - u[1]) / k };
    for (std::int64_t j = 0; j < k; ++j)
    {
      const Point2L a{ u[0] + j * step[0], u[1] + j * step[1] };
      const Point2L b{ a[0] + step[0], a[1] + step[1] };
      Points corners = flat;
      corners.push_back(a);
      corners.push_back(b);
      Points p = latticeHull(corners);
      if (p.size() < 3 || interiorLatticePoints(p) != 0)
        continue;
      const Wide area = absWide(cross(a, b, flat[0])) + absWide(cross(a, b, flat.back()));
      if (bestArea < 0 || area < bestArea)
      {
        bestArea = area;
        s.hull = std::move(p);
        s.notch = true;
        s.edge = e;
        s.a = a;
        s.b = b;
      }
    }
  }
  return bestArea >= 0;
}

/// Whether every lattice point strictly between a and b has the class `object`.
bool openRun(const Point2L& a, const Point2L& b, const Image2D& img, bool object)
{
  const std::int64_t k = gcdOf(b[0] - a[0], b[1] - a[1]);
  for (std::int64_t j = 1; j < k; ++j)
    if (img.object({ a[0] + j * (b[0] - a[0]) / k, a[1] + j * (b[1] - a[1]) / k }) != object)
      return false;
  return true;
}

/// A group touching its parent's boundary on one edge opens there (definition CO, pressing-in
/// of the paper): the notch conv(group, a, b), [a, b] the touching centres' span on that edge
/// (one lattice step when a single centre touches), every centre strictly between a and b of
/// the group's class (they end up outside the parent's region). False when the touching
/// centres lie on no single edge or the run between them holds the other class.
bool openNotch(Shape& s, const Points& parent, const Image2D& img, bool object)
{
  for (std::size_t e = 0; e < parent.size(); ++e)
  {
    const Point2L& u = parent[e];
    const Point2L& v = parent[(e + 1) % parent.size()];
    if (!std::all_of(s.touching.begin(),
          s.touching.end(),
          [&](const Point2L& p) { return cross(u, v, p) == 0; }))
      continue;
    auto along = [&](const Point2L& p)
    { return Wide(p[0] - u[0]) * (v[0] - u[0]) + Wide(p[1] - u[1]) * (v[1] - u[1]); };
    const auto [lo, hi] = std::minmax_element(s.touching.begin(),
      s.touching.end(),
      [&](const Point2L& x, const Point2L& y) { return along(x) < along(y); });
    Point2L a = *lo, b = *hi;
    if (a == b)
    {
      const std::int64_t k = gcdOf(v[0] - u[0], v[1] - u[1]);
      const Point2L step{ (v[0] - u[0]) / k, (v[1] - u[1]) / k };
      if (b != v)
        b = { a[0] + step[0], a[1] + step[1] };
      else
        a = { b[0] - step[0], b[1] - step[1] };
    }
    if (!openRun(a, b, img, object))
      return false;
    Points corners = s.core;
    corners.push_back(a);
    corners.push_back(b);
    s.hull = latticeHull(corners);
    s.notch = true;
    s.edge = e;
    s.a = a;
    s.b = b;
    return s.hull.size() >= 3;
  }
  return false;
}

/// The region of a group of class `object` below `parent` (null at level 0): opened through
/// the parent's boundary where it touches it, else a hull strictly inside (thickened when
/// flat) or a notch from an empty edge piece. False when none was found.
bool shapeGroup(Shape& s, const Shape* parent, const Image2D& img, bool object)
{
  s.notch = false;
  if (parent && !s.touching.empty() && openNotch(s, parent->hull, img, object))
    return true;
  s.notch = false;
  s.hull = s.core;
  if (s.hull.size() >= 3)
    return true;
  const Points flat = s.hull;
  s.hull.clear();
  if (!parent)
  {
    s.hull = thickenFree(flat, img);
    return true;
  }
  return thickenInside(s, flat, parent->hull) || notchFrom(s, flat, *parent);
}

/// Whether every corner of q lies strictly outside one edge of p.
bool separatedByEdgeOf(const Points& p, const Points& q)
{
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Point2L& u = p[i];
    const Point2L& v = p[(i + 1) % p.size()];
    if (std::all_of(q.begin(), q.end(), [&](const Point2L& c) { return cross(u, v, c) < 0; }))
      return true;
  }
  return false;
}

bool boxesApart(const Box& a, const Box& b)
{
  return a.x1 < b.x0 || b.x1 < a.x0 || a.y1 < b.y0 || b.y1 < a.y0;
}

/// Whether two closed convex regions, with their boxes, meet (share a point); a missing region
/// meets nothing.
bool meet(const Points& p, const Box& a, const Points& q, const Box& b)
{
  if (p.empty() || q.empty() || boxesApart(a, b))
    return false;
  return !separatedByEdgeOf(p, q) && !separatedByEdgeOf(q, p);
}

/// The regions of one level (groups of class `object`): every group shaped, groups of regions
/// that meet merged until the regions are pairwise apart. Each region is checked against all
/// others once; one that grew by a merge is checked again (the others were apart from each
/// other already). The regions' boxes are kept, so that most pairs, far apart, cost one box
/// test rather than a pass over both hulls. Groups without a region are reported in `failed`.
std::vector<Shape> settleLevel(std::vector<Shape> shapes,
  const Shape* parent,
  const Image2D& img,
  bool object,
  std::size_t& failed)
{
  std::vector<char> alive(shapes.size(), 1);
  std::vector<Box> boxes(shapes.size(), Box{ 0, 0, -1, -1 });
  auto shape = [&](std::size_t i)
  {
    shapeGroup(shapes[i], parent, img, object);
    if (!shapes[i].hull.empty())
      boxes[i] = boxOf(shapes[i].hull);
  };
  for (std::size_t i = 0; i < shapes.size(); ++i)
    shape(i);
  for (std::size_t i = 0; i < shapes.size(); ++i)
    for (std::size_t k = 0; alive[i] && k < shapes.size(); ++k)
      if (k != i && alive[k] && meet(shapes[i].hull, boxes[i], shapes[k].hull, boxes[k]))
      {
        Points& c = shapes[i].core;
        c.insert(c.end(), shapes[k].core.begin(), shapes[k].core.end());
        c = latticeHull(c);
        Points& t = shapes[i].touching;
        t.insert(t.end(), shapes[k].touching.begin(), shapes[k].touching.end());
        alive[k] = 0;
        shape(i);
        k = std::numeric_limits<std::size_t>::max(); // grown: against all again (k wraps to 0)
      }
  std::vector<Shape> settled;
  for (std::size_t i = 0; i < shapes.size(); ++i)
    if (alive[i])
    {
      failed += shapes[i].hull.empty() ? 1 : 0;
      settled.push_back(std::move(shapes[i]));
    }
  return settled;
}

/// One region of the tree of nested hulls.
struct Node
{
  Shape shape;
  int level = 0;
  std::vector<std::size_t> children;
};

/// The groups of class `object` below a region: the 8-connected components of its centres of
/// that class strictly inside and on its boundary (not on a notch's own piece, which is the
/// parent's boundary), each with its inside centres (its core) and its boundary ones.
std::vector<Shape> groupsBelow(const Shape& region, const Image2D& img, bool object)
{
  const Points inside = centresInside(region.hull, img, object); // in row order
  if (inside.empty())
    return {};
  Points boundary;
  forLatticePointsOf(region.hull,
    [&](const Point2L& p)
    {
      const bool own = region.notch && cross(region.a, region.b, p) == 0 &&
        std::min(region.a, region.b) <= p && p <= std::max(region.a, region.b);
      if (img.inside(p) && img.object(p) == object && !own)
        boundary.push_back(p);
    });
  std::sort(boundary.begin(), boundary.end(), rowOrder);
  Points all(inside.size() + boundary.size());
  std::merge(inside.begin(), inside.end(), boundary.begin(), boundary.end(), all.begin(), rowOrder);
  const std::vector<Points> parts = components(std::move(all));
  std::vector<Shape> groups;
  for (const Points& part : parts)
  {
    Shape g;
    Points core;
    for (const Point2L& p : part)
      (std::binary_search(inside.begin(), inside.end(), p, rowOrder) ? core : g.touching)
        .push_back(p);
    if (core.empty())
      continue; // only on the boundary: marked there, nothing to press in
    g.core = latticeHull(core);
    groups.push_back(std::move(g));
  }
  return groups;
}

/// The tree, breadth first: level 0 from the object's groups, then the groups of the other
/// class below every region. Polls the abort per region (throws "aborted") and reports the
/// share of the regions done as [0.1, 0.9] of exec's progress.
std::vector<Node> buildTree(const Image2D& img,
  const Points& objects,
  std::size_t& failed,
  const Execution& exec)
{
  ProgressPoll poll(exec, 0.1, 0.9, 1);
  double done = 0;
  std::vector<Node> nodes;
  std::vector<Shape> first;
  for (const Points& group : components(objects))
  {
    first.emplace_back();
    first.back().core = latticeHull(group);
  }
  for (Shape& s : settleLevel(std::move(first), nullptr, img, true, failed))
    nodes.push_back({ std::move(s), 0, {} });
  for (std::size_t n = 0; n < nodes.size(); ++n)
  {
    // the share of the regions listed so far that are done: the list grows as regions are
    // found, so the share can fall; the largest so far is reported
    done = std::max(done, static_cast<double>(n) / static_cast<double>(nodes.size()));
    poll.at(done);
    if (!poll.tick())
      throw std::runtime_error("aborted");
    if (nodes[n].shape.hull.empty())
      continue;
    const Shape region = nodes[n].shape;
    const int level = nodes[n].level + 1;
    std::vector<Shape> groups = groupsBelow(region, img, level % 2 == 0);
    if (groups.empty())
      continue;
    for (Shape& s : settleLevel(std::move(groups), &region, img, level % 2 == 0, failed))
    {
      nodes[n].children.push_back(nodes.size());
      nodes.push_back({ std::move(s), level, {} });
    }
  }
  return nodes;
}

void append(Points& loop, const Point2L& p)
{
  if (loop.empty() || loop.back() != p)
    loop.push_back(p);
}

/// A region's loop, counter-clockwise: its hull with the loops of its notch children spliced
/// into their pieces (each notch's loop walked backwards from a to b), recursively.
Points ccwLoop(const std::vector<Node>& nodes, const Node& node)
{
  const Points& h = node.shape.hull;
  std::vector<std::pair<std::pair<std::size_t, Wide>, std::size_t>> notches;
  for (std::size_t c : node.children)
    if (nodes[c].shape.notch)
    {
      const Shape& s = nodes[c].shape;
      const Point2L& u = h[s.edge];
      const Point2L& v = h[(s.edge + 1) % h.size()];
      const Wide t = Wide(s.a[0] - u[0]) * (v[0] - u[0]) + Wide(s.a[1] - u[1]) * (v[1] - u[1]);
      notches.push_back({ { s.edge, t }, c });
    }
  std::sort(notches.begin(), notches.end());
  Points loop;
  std::size_t k = 0;
  for (std::size_t i = 0; i < h.size(); ++i)
  {
    append(loop, h[i]);
    for (; k < notches.size() && notches[k].first.first == i; ++k)
    {
      const Shape& s = nodes[notches[k].second].shape;
      const Points p = ccwLoop(nodes, nodes[notches[k].second]);
      const std::size_t ia =
        static_cast<std::size_t>(std::find(p.begin(), p.end(), s.a) - p.begin());
      append(loop, s.a);
      for (std::size_t t = 1; t < p.size(); ++t)
        append(loop, p[(ia + p.size() - t) % p.size()]);
    }
  }
  if (loop.size() > 1 && loop.front() == loop.back())
    loop.pop_back();
  return loop;
}

/// The region's loop with the object on the left: reversed for odd levels (holes).
Points nodeLoop(const std::vector<Node>& nodes, const Node& node)
{
  Points loop = ccwLoop(nodes, node);
  if (node.level % 2 == 1)
    std::reverse(loop.begin(), loop.end());
  return loop;
}

/// The loops and polygons of the tree: every region that is not a notch gives a loop; even
/// ones are outer boundaries, odd ones holes of the polygon that owns their parent (a polygon
/// owns itself and, through notches, the regions spliced into its loops).
void writeLoops(const std::vector<Node>& nodes, SeparatingPolygons& out)
{
  std::vector<std::size_t> parent(nodes.size(), nodes.size()), owner(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n)
    for (std::size_t c : nodes[n].children)
      parent[c] = n;
  std::vector<std::size_t> polygonOf(nodes.size(), 0);
  for (std::size_t n = 0; n < nodes.size(); ++n) // breadth first: parents come first
  {
    const Node& node = nodes[n];
    const bool own = !node.shape.notch && node.level % 2 == 0;
    owner[n] = own || parent[n] == nodes.size() ? n : owner[parent[n]];
    out.degreeOfNonConvexity = std::max(out.degreeOfNonConvexity, node.level);
    out.notches += node.shape.notch ? 1 : 0;
    if (node.shape.hull.empty() || node.shape.notch)
      continue;
    const std::size_t loop = out.loops.size();
    out.loops.push_back({ nodeLoop(nodes, node), node.level });
    if (own)
    {
      polygonOf[n] = out.polygons.size();
      out.polygons.push_back({ loop, {}, node.level });
      continue;
    }
    ++out.holes;
    out.polygons[polygonOf[owner[parent[n]]]].holes.push_back(loop);
  }
}

} // namespace

SeparatingPolygons separatingPolygons2D(const BitVolume& image, const Execution& exec)
{
  SeparatingPolygons out;
  const Image2D img{ image, image.size(0), image.size(1) };
  Points objects;
  for (std::int64_t y = 0; y < img.ny; ++y)
    for (std::int64_t x = 0; x < img.nx; ++x)
      if (img.object({ x, y }))
        objects.push_back({ x, y });
  if (objects.empty())
    return out;
  Shape all;
  all.core = latticeHull(objects);
  shapeGroup(all, nullptr, img, true);
  out.hull = all.hull;

  std::size_t failed = 0;
  if (!exec.report(0.1))
    throw std::runtime_error("aborted");
  const std::vector<Node> nodes = buildTree(img, objects, failed, exec);
  if (!exec.report(0.9))
    throw std::runtime_error("aborted");
  writeLoops(nodes, out);
  for (const SeparatingLoop& loop : out.loops)
    forLatticePointsOf(loop.corners,
      [&](const Point2L& p)
      {
        if (img.inside(p) && !img.object(p))
          out.backgroundOnBoundary.push_back(p);
      });
  if (failed > 0)
  {
    out.complete = false;
    out.failure = std::to_string(failed) + " flat group(s) found neither a thickening nor a notch";
  }
  else if (revertSeparatingPolygons2D(
             out.loops, out.backgroundOnBoundary, image.size(0), image.size(1)) != image)
  {
    out.complete = false;
    out.failure = "the pixels rebuilt from the loops differ from the input";
  }
  return out;
}

std::vector<Point2L> latticePointsOnLoops(const std::vector<SeparatingLoop>& loops)
{
  Points points;
  for (const SeparatingLoop& loop : loops)
    forLatticePointsOf(loop.corners, [&](const Point2L& p) { points.push_back(p); });
  return points;
}

std::vector<Point2L> polygonCorners(const SeparatingPolygons& result,
  const SeparatingPolygon& polygon)
{
  Points corners = result.loops[polygon.outer].corners;
  for (std::size_t h : polygon.holes)
    corners.insert(corners.end(), result.loops[h].corners.begin(), result.loops[h].corners.end());
  return corners;
}

std::vector<Triangle> triangulatePolygonWithHoles(const SeparatingPolygons& result,
  const SeparatingPolygon& polygon)
{
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<K,
    CGAL::Triangulation_face_base_with_info_2<int, K>>;
  using CDT =
    CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, Fb>>;
  std::vector<const Points*> loops{ &result.loops[polygon.outer].corners };
  for (std::size_t h : polygon.holes)
    loops.push_back(&result.loops[h].corners);
  CDT cdt;
  int index = 0;
  for (const Points* loop : loops)
  {
    std::vector<CDT::Vertex_handle> vertices;
    for (const Point2L& p : *loop)
    {
      vertices.push_back(cdt.insert(K::Point_2(double(p[0]), double(p[1]))));
      vertices.back()->info() = index++;
    }
    for (std::size_t i = 0; i < vertices.size(); ++i)
      cdt.insert_constraint(vertices[i], vertices[(i + 1) % vertices.size()]);
  }
  // A triangle is inside when an odd number of loop edges separates it from the infinite face
  // (the loops are simple and apart): one walk over the faces, each face's nesting depth the
  // number of constrained edges crossed to reach it.
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
    f->info() = -1;
  std::deque<std::pair<CDT::Face_handle, int>> across{ { cdt.infinite_face(), 0 } };
  while (!across.empty())
  {
    const auto [start, depth] = across.front();
    across.pop_front();
    std::deque<CDT::Face_handle> queue{ start };
    while (!queue.empty())
    {
      const CDT::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info() != -1)
        continue;
      f->info() = depth;
      for (int i = 0; i < 3; ++i)
        if (f->neighbor(i)->info() == -1)
        {
          if (cdt.is_constrained(CDT::Edge(f, i)))
            across.push_back({ f->neighbor(i), depth + 1 });
          else
            queue.push_back(f->neighbor(i));
        }
    }
  }
  std::vector<Triangle> triangles;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info() % 2 == 1)
      triangles.push_back({ f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() });
  return triangles;
}

BitVolume revertSeparatingPolygons2D(const std::vector<SeparatingLoop>& loops,
  const std::vector<Point2L>& backgroundOnBoundary,
  std::int32_t nx,
  std::int32_t ny)
{
  BitVolume out(nx, ny, 1);
  // 0 off the loops, 1 on them, 2 on them and marked background.
  std::vector<std::uint8_t> on(static_cast<std::size_t>(nx) * ny, 0);
  auto cell = [&](const Point2L& p) -> std::uint8_t*
  {
    if (p[0] < 0 || p[1] < 0 || p[0] >= nx || p[1] >= ny)
      return nullptr;
    return &on[static_cast<std::size_t>(p[1]) * nx + static_cast<std::size_t>(p[0])];
  };
  for (const SeparatingLoop& loop : loops)
    forLatticePointsOf(loop.corners,
      [&](const Point2L& p)
      {
        if (std::uint8_t* c = cell(p))
          *c = 1;
      });
  for (const Point2L& p : backgroundOnBoundary)
    if (std::uint8_t* c = cell(p))
      *c = *c ? 2 : 0;
  for (std::int32_t y = 0; y < ny; ++y)
  {
    // Crossings of the row with the edges (half-open in y), as fractions num / den, den > 0.
    std::vector<std::pair<Wide, Wide>> xs;
    for (const SeparatingLoop& loop : loops)
      for (std::size_t i = 0; i < loop.corners.size(); ++i)
      {
        const Point2L& u = loop.corners[i];
        const Point2L& v = loop.corners[(i + 1) % loop.corners.size()];
        if ((u[1] <= y) == (v[1] <= y))
          continue;
        const Wide den = v[1] - u[1];
        const Wide num = Wide(u[0]) * den + Wide(y - u[1]) * (v[0] - u[0]);
        xs.push_back(den > 0 ? std::make_pair(num, den) : std::make_pair(-num, -den));
      }
    std::sort(xs.begin(),
      xs.end(),
      [](const auto& a, const auto& b) { return a.first * b.second < b.first * a.second; });
    std::size_t passed = 0;
    for (std::int32_t x = 0; x < nx; ++x)
    {
      while (passed < xs.size() && xs[passed].first < Wide(x) * xs[passed].second)
        ++passed;
      const std::uint8_t c = on[static_cast<std::size_t>(y) * nx + static_cast<std::size_t>(x)];
      if (c == 1 || (c == 0 && passed % 2 == 1))
        out.set(x, y, 0);
    }
  }
  return out;
}

} // namespace vbr
