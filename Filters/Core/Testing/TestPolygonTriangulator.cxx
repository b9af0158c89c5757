// Exact polygon triangulation, simplicity, fan cover and projection (PolygonTriangulator.h)
// against brute force written here: pixel sets traced into orthogonal polygons (hole-free,
// staircases, sets touching themselves at corners), monotone and star-shaped polygons with
// collinear runs, a parametric segment-intersection test, exact separating-line overlap
// tests, Euler characteristics counted on the pixel complex, and the projection formula
// evaluated with cross products on the loops of real standard faces.
#include "BitVolume.h"
#include "BruteForce.h"
#include "Geometry.h"
#include "PolygonTriangulator.h"
#include "Polyhedrization.h"
#include "SurfelGraph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{

using vbr::Point2L;
using Polygon = std::vector<Point2L>;
using vbr::Wide;
using Pixel = std::pair<int, int>;
using Pixels = std::set<Pixel>;

// ---------------------------------------------------------------------------------------
// Exact arithmetic of the references (written here, not taken from the code under test).

Wide cross(const Point2L& a, const Point2L& b, const Point2L& c)
{
  return Wide(b[0] - a[0]) * (c[1] - a[1]) - Wide(b[1] - a[1]) * (c[0] - a[0]);
}

/// Twice the signed area by the trapezoid formula (not the shoelace of the code).
Wide trapezoidArea(const Polygon& p)
{
  Wide sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Point2L& a = p[i];
    const Point2L& b = p[(i + 1) % p.size()];
    sum += Wide(a[0] - b[0]) * (a[1] + b[1]);
  }
  return sum;
}

std::string str(const Polygon& p)
{
  std::string s;
  for (const Point2L& q : p)
    s += "(" + std::to_string(q[0]) + "," + std::to_string(q[1]) + ")";
  return s;
}

/// Whether the closed segments p + t r and q + s w (t, s in [0, 1]) share a point, and
/// whether they share more than one; solved parametrically with exact fractions.
void segmentIntersection(const Point2L& p0,
  const Point2L& p1,
  const Point2L& q0,
  const Point2L& q1,
  bool& meet,
  bool& overlap)
{
  const Wide rx = p1[0] - p0[0], ry = p1[1] - p0[1], wx = q1[0] - q0[0], wy = q1[1] - q0[1];
  const Wide dx = q0[0] - p0[0], dy = q0[1] - p0[1];
  const Wide den = rx * wy - ry * wx;
  overlap = false;
  if (den != 0)
  {
    Wide t = dx * wy - dy * wx, s = dx * ry - dy * rx, d = den;
    if (d < 0)
    {
      t = -t;
      s = -s;
      d = -d;
    }
    meet = 0 <= t && t <= d && 0 <= s && s <= d;
    return;
  }
  if (dx * ry - dy * rx != 0)
  {
    meet = false; // parallel lines
    return;
  }
  // Collinear: q0 and q1 as parameters along r, in units of 1 / |r|^2.
  const Wide rr = rx * rx + ry * ry;
  const Wide a = dx * rx + dy * ry, b = a + wx * rx + wy * ry;
  const Wide lo = std::max<Wide>(0, std::min(a, b)), hi = std::min<Wide>(rr, std::max(a, b));
  meet = lo <= hi;
  overlap = lo < hi;
}

/// O(n^2) simplicity: every pair of edges, adjacent ones meeting in their common corner only.
bool bruteForceSimple(const Polygon& p)
{
  const std::size_t n = p.size();
  if (n < 3)
    return false;
  for (std::size_t i = 0; i < n; ++i)
    if (p[i] == p[(i + 1) % n])
      return false; // an edge of length zero
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
    {
      bool meet = false, overlap = false;
      segmentIntersection(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n], meet, overlap);
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent ? overlap : meet)
        return false;
      if (adjacent && n == 3 && cross(p[0], p[1], p[2]) == 0)
        return false;
    }
  return true;
}

/// Whether the interiors of two counter-clockwise triangles meet: they do not iff one edge
/// line of either has the other triangle in its closed outer half-plane (separating axes).
bool interiorsMeet(const std::array<Point2L, 3>& s, const std::array<Point2L, 3>& t)
{
  for (int pass = 0; pass < 2; ++pass)
  {
    const auto& a = pass ? t : s;
    const auto& b = pass ? s : t;
    for (int e = 0; e < 3; ++e)
    {
      bool separates = true;
      for (int k = 0; k < 3 && separates; ++k)
        separates = cross(a[e], a[(e + 1) % 3], b[k]) <= 0;
      if (separates)
        return false;
    }
  }
  return true;
}

/// Euler characteristic V - E + F of the closed union of the pixels.
long eulerCharacteristic(const Pixels& pixels)
{
  std::set<Pixel> vertices;
  std::set<std::pair<Pixel, int>> edges; // start and direction (0: +x, 1: +y)
  for (const Pixel& q : pixels)
  {
    for (int dx = 0; dx < 2; ++dx)
      for (int dy = 0; dy < 2; ++dy)
        vertices.insert({ q.first + dx, q.second + dy });
    edges.insert({ q, 0 });
    edges.insert({ q, 1 });
    edges.insert({ { q.first, q.second + 1 }, 0 });
    edges.insert({ { q.first + 1, q.second }, 1 });
  }
  return long(vertices.size()) - long(edges.size()) + long(pixels.size());
}

// ---------------------------------------------------------------------------------------
// Polygons.

/// The unit steps of the boundary of a pixel set traced as one loop (interior on the
/// left), or empty when it is more than one. Where the set touches itself at a corner the
/// loop turns right (going on round the other piece there) or left (round this one), at
/// random; several tries.
Polygon traceUnitSteps(const Pixels& pixels, std::mt19937& rng)
{
  auto in = [&](int x, int y) { return pixels.count({ x, y }) > 0; };
  std::multimap<Point2L, Point2L> edges; // unit edges, from -> to
  for (const Pixel& q : pixels)
  {
    const std::int64_t x = q.first, y = q.second;
    if (!in(q.first, q.second - 1))
      edges.insert({ { x, y }, { x + 1, y } });
    if (!in(q.first + 1, q.second))
      edges.insert({ { x + 1, y }, { x + 1, y + 1 } });
    if (!in(q.first, q.second + 1))
      edges.insert({ { x + 1, y + 1 }, { x, y + 1 } });
    if (!in(q.first - 1, q.second))
      edges.insert({ { x, y + 1 }, { x, y } });
  }
  // The lowest, then leftmost, corner: convex, left by one edge only.
  Point2L start = edges.begin()->first;
  for (const auto& e : edges)
    if (std::make_pair(e.first[1], e.first[0]) < std::make_pair(start[1], start[0]))
      start = e.first;
  for (int attempt = 0; attempt < 16; ++attempt)
  {
    std::multimap<Point2L, Point2L> out = edges;
    std::map<Point2L, bool> turnRight; // per corner where the set touches itself
    Polygon loop;
    Point2L at = start, previous = start;
    while (true)
    {
      auto range = out.equal_range(at);
      if (range.first == range.second)
        break;
      auto chosen = range.first;
      if (std::next(range.first) != range.second)
      {
        const bool right = turnRight.emplace(at, rng() % 2 == 0).first->second;
        for (auto it = range.first; it != range.second; ++it)
          if ((cross(previous, at, it->second) < 0) == right)
            chosen = it;
      }
      loop.push_back(at);
      previous = at;
      at = chosen->second;
      out.erase(chosen);
    }
    if (out.empty() && at == start)
      return loop;
  }
  return {};
}

/// traceUnitSteps, with straight corners dropped with probability `dropStraight`.
Polygon traceBoundary(const Pixels& pixels, std::mt19937& rng, double dropStraight)
{
  const Polygon loop = traceUnitSteps(pixels, rng);
  Polygon kept;
  std::bernoulli_distribution drop(dropStraight);
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const bool straight = cross(loop[(i + n - 1) % n], loop[i], loop[(i + 1) % n]) == 0;
    if (!straight || !drop(rng))
      kept.push_back(loop[i]);
  }
  return kept;
}

/// A random 4-connected pixel set grown from one pixel, then made hole-free and free of
/// corner-only contacts (its boundary is then one simple loop).
Pixels randomSimplePixels(std::mt19937& rng, int size, int count)
{
  Pixels pixels{ { 0, 0 } };
  std::vector<Pixel> list{ { 0, 0 } };
  const int step[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
  while (static_cast<int>(pixels.size()) < count)
  {
    const Pixel q = list[rng() % list.size()];
    const int* d = step[rng() % 4];
    const Pixel r{ q.first + d[0], q.second + d[1] };
    if (std::abs(r.first) <= size && std::abs(r.second) <= size && pixels.insert(r).second)
      list.push_back(r);
  }
  for (bool changed = true; changed;)
  {
    changed = false;
    for (const auto& hole : bf::complementComponents(pixels))
      if (hole.second)
      {
        pixels.insert(hole.first.begin(), hole.first.end());
        changed = true;
      }
    for (int x = -size; x <= size + 1; ++x)
      for (int y = -size; y <= size + 1; ++y)
      {
        const bool sw = pixels.count({ x - 1, y - 1 }), se = pixels.count({ x, y - 1 });
        const bool nw = pixels.count({ x - 1, y }), ne = pixels.count({ x, y });
        if ((sw && ne && !se && !nw) || (se && nw && !sw && !ne))
        {
          pixels.insert(rng() % 2 ? Pixel{ x, y - 1 } : Pixel{ x - 1, y });
          changed = true;
        }
      }
  }
  return pixels;
}

/// Columns of random bottoms and tops, each overlapping the next (x-monotone and, when
/// both ends only climb, a staircase).
Pixels randomColumns(std::mt19937& rng, bool staircase)
{
  Pixels pixels;
  const int columns = 1 + int(rng() % 9);
  int bottom = 0, top = 1 + int(rng() % 4);
  for (int x = 0; x < columns; ++x)
  {
    for (int y = bottom; y < top; ++y)
      pixels.insert({ x, y });
    // The next column shares a pixel row with this one: max(bottoms) < min(tops).
    const int next = staircase ? bottom + int(rng() % (top - bottom))
                               : std::min(top - 1, bottom - 2 + int(rng() % (top - bottom + 2)));
    const int floor = std::max(bottom, next) + 1;
    top = staircase ? std::max(top, floor) + int(rng() % 3) : floor + int(rng() % 5);
    bottom = next;
  }
  return pixels;
}

/// Intermediate lattice points on some edges (collinear corners), chosen at random.
Polygon withCollinearRuns(const Polygon& p, std::mt19937& rng)
{
  Polygon out;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Point2L a = p[i], b = p[(i + 1) % p.size()];
    out.push_back(a);
    const std::int64_t g = std::gcd(std::llabs(b[0] - a[0]), std::llabs(b[1] - a[1]));
    if (g < 2 || rng() % 2)
      continue;
    for (std::int64_t j = 1; j < g; ++j)
      if (rng() % 3)
        out.push_back({ a[0] + (b[0] - a[0]) / g * j, a[1] + (b[1] - a[1]) / g * j });
  }
  return out;
}

/// An x-monotone polygon: a lower and an upper chain over the same abscissae, apart except
/// possibly at the ends, with runs of equal slopes.
Polygon randomMonotone(std::mt19937& rng)
{
  const int m = 1 + int(rng() % 8);
  std::vector<std::int64_t> xs{ 0 }, lo{ 0 }, hi;
  for (int i = 1; i <= m; ++i)
    xs.push_back(xs.back() + 1 + int(rng() % 2));
  for (int i = 1; i <= m; ++i)
  {
    const bool linear = i >= 2 && rng() % 2 && xs[i] - xs[i - 1] == xs[i - 1] - xs[i - 2];
    lo.push_back(linear ? 2 * lo[i - 1] - lo[i - 2] : lo[i - 1] + int(rng() % 7) - 3);
  }
  for (int i = 0; i <= m; ++i)
  {
    const bool linear = i >= 2 && rng() % 2 && xs[i] - xs[i - 1] == xs[i - 1] - xs[i - 2];
    std::int64_t y = linear ? 2 * hi[i - 1] - hi[i - 2] : lo[i] + 1 + int(rng() % 5);
    const bool end = i == 0 || i == m;
    if (y <= lo[i] && !(end && y == lo[i]))
      y = lo[i] + 1;
    if (end && rng() % 3 == 0)
      y = lo[i];
    hi.push_back(std::max(y, lo[i]));
  }
  Polygon p;
  for (int i = 0; i <= m; ++i)
    p.push_back({ xs[i], lo[i] });
  for (int i = m; i >= 0; --i)
    if (hi[i] != lo[i])
      p.push_back({ xs[i], hi[i] });
  return p;
}

/// Points sorted by angle round the origin, exactly (half-plane, then cross product).
bool byAngle(const Point2L& a, const Point2L& b)
{
  const bool ha = a[1] < 0 || (a[1] == 0 && a[0] < 0), hb = b[1] < 0 || (b[1] == 0 && b[0] < 0);
  if (ha != hb)
    return hb;
  return cross({ 0, 0 }, a, b) > 0;
}

/// A polygon star-shaped round the origin (inside it), or, with `apexAtOrigin`, round its
/// corner at the origin; corners scaled so that edges carry lattice points, then collinear
/// runs added.
Polygon randomStar(std::mt19937& rng, bool apexAtOrigin)
{
  std::vector<Point2L> points;
  const int m = 3 + int(rng() % 9);
  while (static_cast<int>(points.size()) < m)
  {
    const Point2L q{ int(rng() % 13) - 6, int(rng() % 13) - 6 };
    if (q == Point2L{ 0, 0 } || (apexAtOrigin && q[1] <= 0 && !(q[1] == 0 && q[0] > 0)))
      continue;
    bool sameRay = false;
    for (const Point2L& r : points)
      sameRay = sameRay || (cross({ 0, 0 }, q, r) == 0 && q[0] * r[0] + q[1] * r[1] > 0);
    if (!sameRay)
      points.push_back(q);
  }
  std::sort(points.begin(), points.end(), byAngle);
  Polygon p;
  if (apexAtOrigin)
    p.push_back({ 0, 0 });
  const std::int64_t scale = 1 + int(rng() % 3);
  for (const Point2L& q : points)
    p.push_back({ q[0] * scale, q[1] * scale });
  if (!apexAtOrigin)
  {
    for (std::size_t i = 0; i < p.size(); ++i) // the origin strictly inside: no gap >= pi
      if (cross({ 0, 0 }, p[i], p[(i + 1) % p.size()]) <= 0)
        return {};
  }
  return withCollinearRuns(p, rng);
}

/// Random corners in a small box: mostly not simple.
Polygon randomScribble(std::mt19937& rng)
{
  Polygon p;
  const int n = 3 + int(rng() % 6), box = 2 + int(rng() % 4);
  for (int i = 0; i < n; ++i)
    p.push_back({ int(rng() % box), int(rng() % box) });
  return p;
}

// ---------------------------------------------------------------------------------------
// The checks.

/// One triangulator for all the checks: each polygon meets the working memory the earlier
/// ones left.
vbr::PolygonTriangulator& sharedTriangulator()
{
  static vbr::PolygonTriangulator triangulator;
  return triangulator;
}

/// The polygon scaled by 3,037,000,499 (about 2^31.5) and moved by (2^40, -2^41): the products
/// of its corners' differences (cross2) no longer fit in 64 bits as soon as two corners are
/// two units apart, and a positive scale keeps the sign of every orientation. (A translation
/// alone changes no difference; a scale by 2^33 + 1 would wrap its square round to a small
/// number modulo 2^64 and let 64-bit products pass.)
Polygon farAway(const Polygon& p)
{
  constexpr std::int64_t Scale = 3037000499;
  Polygon far(p);
  for (Point2L& c : far)
  {
    c[0] = c[0] * Scale + (std::int64_t(1) << 40);
    c[1] = c[1] * Scale - (std::int64_t(1) << 41);
  }
  return far;
}

/// The shared triangulator appends, after what the output held, the triangles of a fresh one
/// (a positive scale and a translation change no orientation, so the far copy gives the same), or
/// nothing when that has none.
void checkReusedTriangulator(const Polygon& p, const std::vector<vbr::Triangle>& fresh)
{
  const vbr::Triangle held{ -1, -2, -3 };
  for (const Polygon& q : { p, farAway(p) })
  {
    std::vector<vbr::Triangle> out{ held };
    EXPECT_EQ(sharedTriangulator().triangulate(q, out), !fresh.empty());
    ASSERT_EQ(out.size(), fresh.size() + 1);
    EXPECT_EQ(out[0], held);
    EXPECT_TRUE(std::equal(fresh.begin(), fresh.end(), out.begin() + 1))
      << "reused working memory or wide products change the triangles";
  }
}

/// Everything about a triangulation of a counter-clockwise polygon, by brute force.
void checkTriangulation(const Polygon& p, std::size_t expectedTriangles)
{
  SCOPED_TRACE("polygon " + str(p));
  const std::vector<vbr::Triangle> triangles = vbr::triangulateSimplePolygon(p);
  ASSERT_EQ(triangles.size(), expectedTriangles);
  checkReusedTriangulator(p, triangles);
  const int n = static_cast<int>(p.size());
  // Edges by place: a corner visited twice is one point of the plane.
  std::vector<int> place(p.size());
  for (int i = 0; i < n; ++i)
    place[i] = static_cast<int>(std::find(p.begin(), p.end(), p[i]) - p.begin());
  std::map<std::pair<int, int>, int> directed;
  Wide sum = 0;
  for (const vbr::Triangle& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
      ASSERT_TRUE(t[k] >= 0 && t[k] < n) << "corner not a polygon vertex";
    const Wide c = cross(p[t[0]], p[t[1]], p[t[2]]);
    EXPECT_GT(c, 0) << "triangle " << t[0] << " " << t[1] << " " << t[2] << " clockwise or flat";
    sum += c;
    for (int k = 0; k < 3; ++k)
      ++directed[{ place[t[k]], place[t[(k + 1) % 3]] }];
  }
  EXPECT_TRUE(sum == trapezoidArea(p)) << "areas do not add up";
  auto count = [&](int a, int b)
  {
    const auto it = directed.find({ a, b });
    return it == directed.end() ? 0 : it->second;
  };
  std::set<std::pair<int, int>> boundary;
  for (int e = 0; e < n; ++e)
    boundary.insert({ place[e], place[(e + 1) % n] });
  for (int e = 0; e < n; ++e)
  {
    const int i = place[e], j = place[(e + 1) % n];
    EXPECT_EQ(count(i, j), 1) << "polygon edge " << e << " in " << count(i, j) << " triangles";
    if (!boundary.count({ j, i })) // unless the boundary runs back along it (a slit)
      EXPECT_EQ(count(j, i), 0) << "polygon edge " << e << " used reversed";
  }
  for (const auto& e : directed)
    if (!boundary.count(e.first))
    {
      EXPECT_EQ(e.second, 1) << "internal edge " << e.first.first << " " << e.first.second;
      EXPECT_EQ(count(e.first.second, e.first.first), 1)
        << "internal edge " << e.first.first << " " << e.first.second << " unmatched";
    }
  if (triangles.size() > 80)
    return;
  for (std::size_t s = 0; s < triangles.size(); ++s)
    for (std::size_t t = s + 1; t < triangles.size(); ++t)
    {
      const std::array<Point2L, 3> a{ p[triangles[s][0]], p[triangles[s][1]], p[triangles[s][2]] };
      const std::array<Point2L, 3> b{ p[triangles[t][0]], p[triangles[t][1]], p[triangles[t][2]] };
      EXPECT_FALSE(interiorsMeet(a, b)) << "triangles " << s << " and " << t << " overlap";
    }
}

/// Corners visited more than once.
std::size_t repetitions(const Polygon& p)
{
  return p.size() - std::set<Point2L>(p.begin(), p.end()).size();
}

/// Fan cover by brute force: the absolute areas of the fan triangles add up to the area of
/// the polygon (none turns the other way), and for small polygons every generic sample
/// point is covered by as many fan triangles as the polygon covers it (even-odd rule).
bool bruteForceFanCovers(const Polygon& p, std::size_t apex)
{
  const std::size_t n = p.size();
  Wide absolute = 0;
  for (std::size_t i = 1; i + 1 < n; ++i)
  {
    const Wide c = cross(p[apex], p[(apex + i) % n], p[(apex + i + 1) % n]);
    absolute += c < 0 ? -c : c;
  }
  return trapezoidArea(p) > 0 && absolute == trapezoidArea(p);
}

/// Sample points (x + 1/M, y + 1/M^2) in coordinates scaled by M^2 lie on no line through
/// two corners when M exceeds twice the polygon's span: counts per unit cell of the fan
/// triangles holding the point strictly, against the even-odd rule on the polygon.
void checkFanBySampling(const Polygon& p, std::size_t apex)
{
  const auto [x0, x1, y0, y1] = bf::bounds2D(p);
  if (std::max(x1 - x0, y1 - y0) > 16)
    return; // kept fast
  const std::int64_t M = 2 * std::max(x1 - x0, y1 - y0) + 3, M2 = M * M;
  Polygon scaled;
  for (const Point2L& q : p)
    scaled.push_back({ q[0] * M2, q[1] * M2 });
  const std::size_t n = p.size();
  for (std::int64_t x = x0; x < x1; ++x)
    for (std::int64_t y = y0; y < y1; ++y)
    {
      const Point2L s{ x * M2 + M, y * M2 + 1 };
      bool inside = false; // crossings of the ray to +x
      for (std::size_t i = 0; i < n; ++i)
      {
        const Point2L &a = scaled[i], &b = scaled[(i + 1) % n];
        if ((a[1] > s[1]) != (b[1] > s[1]) &&
          (cross(a, b, s) > 0) ==
            (b[1] > a[1])) // s left of an upward edge, or right of a downward one
          inside = !inside;
      }
      int covered = 0;
      for (std::size_t i = 1; i + 1 < n; ++i)
      {
        const Point2L &a = scaled[apex], &b = scaled[(apex + i) % n],
                      &c = scaled[(apex + i + 1) % n];
        const Wide o = cross(a, b, c);
        if (o == 0)
          continue;
        const int sg = o > 0 ? 1 : -1;
        covered += sg * cross(a, b, s) > 0 && sg * cross(b, c, s) > 0 && sg * cross(c, a, s) > 0;
      }
      ASSERT_EQ(covered, inside ? 1 : 0) << "cell " << x << " " << y << " apex " << apex;
    }
}

/// p x n for a pointel and a normal.
std::array<std::int64_t, 3> crossWith(const vbr::Point3& p, const std::array<std::int64_t, 3>& n)
{
  return { p[1] * n[2] - p[2] * n[1], p[2] * n[0] - p[0] * n[2], p[0] * n[1] - p[1] * n[0] };
}

/// The axes k for which the projection is the header's (u.p, v.p) = ((p x n)_i, (p x n)_j),
/// (i, j, k) cyclic, u and v swapped when n_k < 0, on all the points.
std::vector<int> matchingAxes(const vbr::ProjectionAlong& project,
  const std::array<std::int64_t, 3>& n,
  const std::vector<vbr::Point3>& points)
{
  std::vector<int> axes;
  for (int k = 0; k < 3; ++k)
  {
    if (n[k] == 0)
      continue;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    bool all = true;
    for (const vbr::Point3& q : points)
    {
      const auto c = crossWith(q, n);
      const Point2L expected = n[k] > 0 ? Point2L{ c[i], c[j] } : Point2L{ c[j], c[i] };
      all = all && project(q) == expected;
    }
    if (all)
      axes.push_back(k);
  }
  return axes;
}

/// n . (twice the vector area of a closed 3D loop), which has the sign of the loop's turning
/// seen from the side n points to.
Wide normalTimesVectorArea(const std::vector<vbr::Point3>& loop,
  const std::array<std::int64_t, 3>& n)
{
  Wide a[3] = { 0, 0, 0 };
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const vbr::Point3& p = loop[i];
    const vbr::Point3& q = loop[(i + 1) % loop.size()];
    a[0] += Wide(p[1]) * q[2] - Wide(p[2]) * q[1];
    a[1] += Wide(p[2]) * q[0] - Wide(p[0]) * q[2];
    a[2] += Wide(p[0]) * q[1] - Wide(p[1]) * q[0];
  }
  return a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
}

/// The projection of every face of a polyhedrization of v: formula, orientation, simplicity
/// and the tiling of its surfels' projection by the triangles of its loop.
void checkProjectedFaces(const vbr::BitVolume& v, std::size_t& faces, std::size_t& pinched)
{
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  vbr::Polyhedron poly;
  ASSERT_TRUE(vbr::polyhedrize(g, {}, vbr::Execution(), poly));
  for (std::size_t f = 0; f < poly.faces.size(); ++f)
  {
    const vbr::StandardFace& face = poly.faces[f];
    const auto& n = face.plane.normal;
    SCOPED_TRACE("face " + std::to_string(f) + " normal " + std::to_string(n[0]) + " " +
      std::to_string(n[1]) + " " + std::to_string(n[2]));
    const vbr::ProjectionAlong project(n);
    std::vector<vbr::Point3> loop;
    for (std::uint32_t vtx : face.loop)
      loop.push_back(g.vertexPointel[vtx]);
    const std::vector<int> axes = matchingAxes(project, n, loop);
    ASSERT_FALSE(axes.empty()) << "projection is not the header's formula";
    Polygon corners;
    for (const vbr::Point3& q : loop)
      corners.push_back(project(q));
    const Wide area = trapezoidArea(corners);
    const Wide turning = normalTimesVectorArea(loop, n);
    EXPECT_GT(turning, 0) << "loop not counter-clockwise seen from outside";
    EXPECT_TRUE(area == Wide(std::llabs(n[axes[0]])) * turning) << "orientation not kept";
    Wide surfelArea = 0;
    for (std::uint32_t s : face.surfels)
    {
      Polygon square;
      for (int k = 0; k < 4; ++k)
        square.push_back(project(g.cornerOf(s, k)));
      const Wide a = trapezoidArea(square);
      EXPECT_GT(a, 0) << "surfel " << s << " projected upside down";
      surfelArea += a;
    }
    EXPECT_TRUE(surfelArea == area) << "loop does not bound the surfels' projection";
    const std::size_t r = repetitions(corners);
    ++faces;
    if (r == 0)
    {
      EXPECT_TRUE(bruteForceSimple(corners)) << "projected loop not simple: " << str(corners);
      checkTriangulation(corners, corners.size() - 2);
    }
    else
    {
      // A disk whose loop passes a pointel twice: the projection pinched there (Euler
      // characteristic 1 - r of the region, see PinchedPixelSets): n - 2 triangles still.
      ++pinched;
      checkTriangulation(corners, corners.size() - 2);
    }
  }
}

} // namespace

TEST(PolygonTriangulator, OrthogonalPolygonsFromPixelSets)
{
  std::mt19937 rng(41);
  std::size_t polygons = 0, corners = 0;
  for (int t = 0; t < 1500; ++t)
  {
    const Pixels pixels =
      t % 3 == 0 ? randomColumns(rng, t % 2 == 0) : randomSimplePixels(rng, 6, 1 + int(rng() % 40));
    const Polygon p = traceBoundary(pixels, rng, (t % 4) / 3.0);
    ASSERT_FALSE(p.empty());
    ASSERT_TRUE(bruteForceSimple(p)) << str(p);
    ASSERT_TRUE(trapezoidArea(p) == Wide(2 * pixels.size()));
    checkTriangulation(p, p.size() - 2);
    ++polygons;
    corners += p.size();
  }
  RecordProperty("corners", static_cast<int>(corners));
  EXPECT_GT(corners, 20 * polygons);
}

// The ear clipping of pieces of at most 64 corners (their convexity in the bits of a word) and
// the general one (blockers sorted by x), on orthogonal polygons of either side of that size
// and at it.
TEST(PolygonTriangulator, OrthogonalPolygonsAroundSixtyFourCorners)
{
  std::mt19937 rng(43);
  std::map<bool, int> bySide; // more than 64 corners or not
  int atLimit = 0;
  for (int t = 0; t < 400; ++t)
  {
    const Pixels pixels = randomSimplePixels(rng, 9, 30 + int(rng() % 90));
    const Polygon p = traceBoundary(pixels, rng, (t % 4) / 3.0);
    ASSERT_FALSE(p.empty());
    ASSERT_TRUE(bruteForceSimple(p)) << str(p);
    checkTriangulation(p, p.size() - 2);
    // The same polygon moved beyond 2^30 takes the general ring with 128-bit products; every
    // test is unchanged by the move, so the small-ring path must cut the same ears.
    Polygon far = p;
    for (Point2L& c : far)
      c[0] += std::int64_t(1) << 31;
    EXPECT_EQ(vbr::triangulateSimplePolygon(p), vbr::triangulateSimplePolygon(far)) << str(p);
    ++bySide[p.size() > 64];
    atLimit += p.size() >= 63 && p.size() <= 65;
  }
  EXPECT_GT(bySide[false], 20);
  EXPECT_GT(bySide[true], 20);
  EXPECT_GT(atLimit, 0);
}

TEST(PolygonTriangulator, MonotoneAndStarPolygonsWithCollinearRuns)
{
  std::mt19937 rng(42);
  int monotone = 0, stars = 0, collinear = 0;
  for (int t = 0; t < 3000; ++t)
  {
    Polygon p = t % 3 == 0 ? randomMonotone(rng) : randomStar(rng, t % 3 == 1);
    if (p.size() < 3 || !bruteForceSimple(p))
    {
      ASSERT_NE(t % 3, 1) << "star polygon not simple: " << str(p);
      continue;
    }
    ASSERT_GT(trapezoidArea(p), 0) << str(p);
    (t % 3 == 0 ? monotone : stars) += 1;
    for (std::size_t i = 0; i < p.size(); ++i)
      collinear += cross(p[(i + p.size() - 1) % p.size()], p[i], p[(i + 1) % p.size()]) == 0;
    checkTriangulation(p, p.size() - 2);
    // Any rotation of the corners and a mirror image (reversed to stay counter-clockwise).
    std::rotate(p.begin(), p.begin() + rng() % p.size(), p.end());
    checkTriangulation(p, p.size() - 2);
    Polygon mirror;
    for (auto it = p.rbegin(); it != p.rend(); ++it)
      mirror.push_back({ -(*it)[0], (*it)[1] });
    checkTriangulation(mirror, p.size() - 2);
    // Clockwise: refused.
    EXPECT_TRUE(vbr::triangulateSimplePolygon(Polygon(p.rbegin(), p.rend())).empty());
  }
  EXPECT_GT(monotone, 500);
  EXPECT_GT(stars, 1500);
  EXPECT_GT(collinear, 3000);
}

TEST(PolygonTriangulator, PinchedPixelSets)
{
  // Two squares sharing a corner, traced as one loop: 8 corners, 4 triangles.
  const Polygon twoSquares{
    { 0, 0 }, { 1, 0 }, { 1, 1 }, { 2, 1 }, { 2, 2 }, { 1, 2 }, { 1, 1 }, { 0, 1 }
  };
  checkTriangulation(twoSquares, 4);
  // A ring of pixels whose hole touches the outside at a corner: one loop through (2, 2)
  // twice, Euler characteristic 0, n - 2 triangles.
  std::mt19937 rng(43);
  const Pixels ring{ { 0, 0 }, { 1, 0 }, { 2, 0 }, { 0, 1 }, { 2, 1 }, { 0, 2 }, { 1, 2 } };
  const Polygon r = traceBoundary(ring, rng, 0);
  ASSERT_EQ(repetitions(r), 1u);
  checkTriangulation(r, r.size() - 2);

  // Random pixel sets whose boundary is one loop touching itself at corners. A
  // triangulation of the region on its V = n - r corners with n boundary edges has
  // E = (3T + n) / 2 edges and V - E + T = chi, so T = n - 2r - 2 chi.
  int pinched = 0, lobes = 0;
  for (int t = 0; t < 6000; ++t)
  {
    const int w = 2 + int(rng() % 5), h = 2 + int(rng() % 5);
    Pixels pixels;
    for (int x = 0; x < w; ++x)
      for (int y = 0; y < h; ++y)
        if (rng() % 100 < 55)
          pixels.insert({ x, y });
    if (pixels.empty())
      continue;
    const Polygon p = traceBoundary(pixels, rng, 0.5);
    if (p.empty() || repetitions(p) == 0)
      continue;
    const long chi = eulerCharacteristic(pixels);
    const long expected = long(p.size()) - 2 * long(repetitions(p)) - 2 * chi;
    ASSERT_GT(expected, 0);
    ASSERT_TRUE(trapezoidArea(p) == Wide(2 * pixels.size()));
    ++pinched;
    lobes += chi > 1 - long(repetitions(p));
    checkTriangulation(p, static_cast<std::size_t>(expected));
  }
  RecordProperty("pinched", pinched);
  EXPECT_GT(pinched, 500);
  EXPECT_GT(lobes, 100);
}

TEST(PolygonTriangulator, RefusedPolygonsAppendNothing)
{
  // Scribbles of positive area that are not simple: the ear clipping may cut some ears before
  // it finds none; the shared triangulator must then take them back.
  std::mt19937 rng(47);
  int refused = 0;
  for (int t = 0; t < 20000; ++t)
  {
    const Polygon p = randomScribble(rng);
    if (trapezoidArea(p) <= 0 || bruteForceSimple(p))
      continue;
    const std::vector<vbr::Triangle> fresh = vbr::triangulateSimplePolygon(p);
    checkReusedTriangulator(p, fresh);
    refused += fresh.empty();
  }
  RecordProperty("refused", refused);
  EXPECT_GT(refused, 1000);
}

TEST(PolygonTriangulator, SimplicityAgreesWithBruteForce)
{
  std::mt19937 rng(44);
  int simple = 0, notSimple = 0;
  auto check = [&](const Polygon& p)
  {
    const bool expected = bruteForceSimple(p);
    ASSERT_EQ(vbr::isSimplePolygon(p), expected) << str(p);
    (expected ? simple : notSimple) += 1;
  };
  for (int t = 0; t < 20000; ++t)
  {
    Polygon p;
    switch (t % 5)
    {
      case 0:
      case 1:
        p = randomScribble(rng);
        break;
      case 2:
        p = randomStar(rng, t % 2 == 0);
        break;
      case 3:
        p = traceBoundary(randomSimplePixels(rng, 3, 1 + int(rng() % 10)), rng, 0.7);
        break;
      default:
        p = randomMonotone(rng);
    }
    if (p.empty())
      continue;
    check(p);
    check(Polygon(p.rbegin(), p.rend()));
    // One corner moved a little: often a crossing, a touching or a fold.
    Polygon moved = p;
    Point2L& q = moved[rng() % moved.size()];
    q[0] += int(rng() % 5) - 2;
    q[1] += int(rng() % 5) - 2;
    check(moved);
    // A corner repeated next to itself, or elsewhere.
    Polygon doubled = p;
    doubled.insert(doubled.begin() + rng() % doubled.size(), p[rng() % p.size()]);
    check(doubled);
  }
  // Pinched loops are not simple.
  std::mt19937 pixels(45);
  const Pixels ring{ { 0, 0 }, { 1, 0 }, { 2, 0 }, { 0, 1 }, { 2, 1 }, { 0, 2 }, { 1, 2 } };
  EXPECT_FALSE(vbr::isSimplePolygon(traceBoundary(ring, pixels, 0)));
  RecordProperty("simple", simple);
  RecordProperty("notSimple", notSimple);
  EXPECT_GT(simple, 10000);
  EXPECT_GT(notSimple, 20000);
}

TEST(PolygonTriangulator, FanCoverAgreesWithBruteForce)
{
  std::mt19937 rng(46);
  int covers = 0, fails = 0, flatFans = 0;
  for (int t = 0; t < 3000; ++t)
  {
    Polygon p;
    switch (t % 4)
    {
      case 0:
        p = traceBoundary(randomSimplePixels(rng, 3, 1 + int(rng() % 12)), rng, 0.5);
        break;
      case 1:
        p = randomMonotone(rng);
        break;
      default:
        p = randomStar(rng, t % 2 == 0);
    }
    if (p.size() < 3 || !bruteForceSimple(p))
      continue;
    bool sampled = false;
    for (std::size_t apex = 0; apex < p.size(); ++apex)
    {
      const bool expected = bruteForceFanCovers(p, apex);
      ASSERT_EQ(vbr::fanCoversPolygon(p, apex), expected) << str(p) << " apex " << apex;
      (expected ? covers : fails) += 1;
      if (expected && !sampled)
      {
        checkFanBySampling(p, apex);
        sampled = true;
      }
      if (expected)
      {
        for (std::size_t i = 1; i + 1 < p.size(); ++i)
          flatFans += cross(p[apex], p[(apex + i) % p.size()], p[(apex + i + 1) % p.size()]) == 0;
      }
      // Clockwise: never.
      const Polygon reversed(p.rbegin(), p.rend());
      EXPECT_FALSE(vbr::fanCoversPolygon(reversed, apex));
    }
    EXPECT_FALSE(vbr::fanCoversPolygon(p, p.size()));
  }
  RecordProperty("covers", covers);
  RecordProperty("fails", fails);
  EXPECT_GT(covers, 5000);
  EXPECT_GT(fails, 5000);
  EXPECT_GT(flatFans, 500);
}

TEST(ProjectionAlong, FormulaAndOrientationForRandomNormals)
{
  // Random normals and random closed 3D loops: the projection is the header's formula for
  // an axis k with n_k != 0, and the projected area is |n_k| n . (vector area), so the
  // orientation is the one seen from the side n points to.
  std::mt19937 rng(47);
  for (int t = 0; t < 5000; ++t)
  {
    std::array<std::int64_t, 3> n{ 0, 0, 0 };
    while (n == std::array<std::int64_t, 3>{ 0, 0, 0 })
      for (auto& c : n)
        c = t % 2 ? int(rng() % 13) - 6 : int(rng() % 2001) - 1000;
    std::vector<vbr::Point3> loop(3 + rng() % 6);
    for (auto& q : loop)
      q = { int(rng() % 41) - 20, int(rng() % 41) - 20, int(rng() % 41) - 20 };
    const vbr::ProjectionAlong project(n);
    const std::vector<int> axes = matchingAxes(project, n, loop);
    ASSERT_FALSE(axes.empty()) << "normal " << n[0] << " " << n[1] << " " << n[2];
    Polygon corners;
    for (const auto& q : loop)
      corners.push_back(project(q));
    EXPECT_TRUE(
      trapezoidArea(corners) == Wide(std::llabs(n[axes[0]])) * normalTimesVectorArea(loop, n));
  }
}

TEST(ProjectionAlong, StandardFacesOfRandomVolumes)
{
  std::size_t faces = 0, pinched = 0;
  unsigned seed = 4100;
  for (int t = 0; t < 60; ++t)
  {
    const vbr::Point3 d{ 2 + t % 7, 2 + (t * 3) % 6, 2 + (t * 5) % 7 };
    SCOPED_TRACE("seed " + std::to_string(seed));
    checkProjectedFaces(bf::randomVolume(d, 0.2 + 0.1 * (t % 7), seed++), faces, pinched);
  }
  // Digital half-spaces of random normals cut by a box: large faces of those normals.
  std::mt19937 rng(48);
  for (int t = 0; t < 30; ++t)
  {
    const int n[3] = { int(rng() % 15) - 7, int(rng() % 15) - 7, int(rng() % 15) - 7 };
    vbr::BitVolume v(10, 10, 10);
    for (int z = 0; z < 10; ++z)
      for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x)
          if (n[0] * (2 * x - 9) + n[1] * (2 * y - 9) + n[2] * (2 * z - 9) < int(rng() % 3))
            v.set(x, y, z);
    SCOPED_TRACE("half-space " + std::to_string(t));
    checkProjectedFaces(v, faces, pinched);
  }
  RecordProperty("faces", static_cast<int>(faces));
  RecordProperty("pinched", static_cast<int>(pinched));
  EXPECT_GT(faces, 1000u);
}
