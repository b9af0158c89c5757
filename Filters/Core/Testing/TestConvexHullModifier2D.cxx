// The separating polygons of 2D pixel sets checked against an independent brute force: every
// lattice point of the image and a margin around it classified by an exact winding number
// (integer orientations, loops summed) or found on an edge, object centres inside or on the
// loops and background centres outside or on them, the background centres on the loops exactly
// the marked ones, the pixels rebuilt from that classification and the marks equal to the input
// (and the core's own reversion too), every pair of edges meeting only as consecutive edges of
// one loop at their common corner, no corner going straight on, outer loops counter-clockwise
// around their holes, and the triangles of every polygon covering it exactly.
#include "ConvexHullModifier2D.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

using vbr::Point2L;
using Loop = std::vector<Point2L>;
using W = __int128;

W orient(const Point2L& a, const Point2L& b, const Point2L& c)
{
  return W(b[0] - a[0]) * (c[1] - a[1]) - W(b[1] - a[1]) * (c[0] - a[0]);
}

bool between(const Point2L& p, const Point2L& a, const Point2L& b)
{
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
    std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

bool onSegment(const Point2L& p, const Point2L& a, const Point2L& b)
{
  return orient(a, b, p) == 0 && between(p, a, b);
}

int sgn(W w)
{
  return (w > 0) - (w < 0);
}

/// Closed segments ab and cd share a point.
bool segmentsMeet(const Point2L& a, const Point2L& b, const Point2L& c, const Point2L& d)
{
  const int o1 = sgn(orient(a, b, c)), o2 = sgn(orient(a, b, d));
  const int o3 = sgn(orient(c, d, a)), o4 = sgn(orient(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0)
    return true;
  return onSegment(c, a, b) || onSegment(d, a, b) || onSegment(a, c, d) || onSegment(b, c, d);
}

/// Winding number of a loop around p (p not on it), upward and downward crossings.
int winding(const Loop& loop, const Point2L& p)
{
  int w = 0;
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const Point2L& a = loop[i];
    const Point2L& b = loop[(i + 1) % loop.size()];
    if (a[1] <= p[1] && b[1] > p[1] && orient(a, b, p) > 0)
      ++w;
    else if (a[1] > p[1] && b[1] <= p[1] && orient(a, b, p) < 0)
      --w;
  }
  return w;
}

W twiceArea(const Loop& loop)
{
  W s = 0;
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const Point2L& a = loop[i];
    const Point2L& b = loop[(i + 1) % loop.size()];
    s += W(a[0]) * b[1] - W(b[0]) * a[1];
  }
  return s;
}

bool pixel(const vbr::BitVolume& img, const Point2L& p)
{
  return p[0] >= 0 && p[1] >= 0 && p[0] < img.size(0) && p[1] < img.size(1) &&
    img.get(static_cast<int>(p[0]), static_cast<int>(p[1]), 0);
}

void checkLoopsSimple(const vbr::SeparatingPolygons& r, const std::string& tag)
{
  struct Edge
  {
    std::size_t loop, index;
    Point2L a, b;
  };
  std::vector<Edge> edges;
  for (std::size_t l = 0; l < r.loops.size(); ++l)
  {
    const Loop& c = r.loops[l].corners;
    ASSERT_GE(c.size(), 3u) << tag;
    ASSERT_EQ(std::set<Point2L>(c.begin(), c.end()).size(), c.size()) << tag << ": corner repeated";
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      const Point2L& prev = c[(i + c.size() - 1) % c.size()];
      const Point2L& next = c[(i + 1) % c.size()];
      EXPECT_NE(orient(prev, c[i], next), 0) << tag << ": a corner goes straight on";
      edges.push_back({ l, i, c[i], next });
    }
  }
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (std::size_t f = e + 1; f < edges.size(); ++f)
    {
      const Edge& x = edges[e];
      const Edge& y = edges[f];
      const std::size_t n = r.loops[x.loop].corners.size();
      const bool next = x.loop == y.loop && (y.index == (x.index + 1) % n);
      const bool prev = x.loop == y.loop && (x.index == (y.index + 1) % n);
      if (!next && !prev)
      {
        ASSERT_FALSE(segmentsMeet(x.a, x.b, y.a, y.b)) << tag << ": edges meet";
        continue;
      }
      // Consecutive edges: only their common corner (not folding back onto each other).
      const Point2L& far = next ? y.b : y.a;
      const Point2L& farX = next ? x.a : x.b;
      ASSERT_FALSE(onSegment(far, x.a, x.b) || onSegment(farX, y.a, y.b)) << tag;
    }
}

void checkPolygons(const vbr::SeparatingPolygons& r, const std::string& tag)
{
  std::vector<int> used(r.loops.size(), 0);
  for (const vbr::SeparatingPolygon& p : r.polygons)
  {
    const Loop& outer = r.loops[p.outer].corners;
    ++used[p.outer];
    EXPECT_GT(twiceArea(outer), 0) << tag << ": outer loop not counter-clockwise";
    W area = twiceArea(outer);
    for (std::size_t h : p.holes)
    {
      ++used[h];
      EXPECT_LT(twiceArea(r.loops[h].corners), 0) << tag << ": hole not clockwise";
      EXPECT_EQ(winding(outer, r.loops[h].corners[0]), 1) << tag << ": hole outside its polygon";
      area += twiceArea(r.loops[h].corners);
    }
    // The triangles: counter-clockwise, inside (centroid, scaled by 3), areas summing up.
    const std::vector<Point2L> corners = vbr::polygonCorners(r, p);
    W sum = 0;
    for (const vbr::Triangle& t : vbr::triangulatePolygonWithHoles(r, p))
    {
      const Point2L &a = corners[t[0]], &b = corners[t[1]], &c = corners[t[2]];
      EXPECT_GT(orient(a, b, c), 0) << tag;
      sum += orient(a, b, c);
      const Point2L g{ a[0] + b[0] + c[0], a[1] + b[1] + c[1] };
      int w = 0;
      for (std::size_t l :
        [&]
        {
          auto v = p.holes;
          v.push_back(p.outer);
          return v;
        }())
      {
        Loop scaled;
        for (const Point2L& q : r.loops[l].corners)
          scaled.push_back({ 3 * q[0], 3 * q[1] });
        w += winding(scaled, g);
      }
      EXPECT_EQ(w, 1) << tag << ": a triangle outside its polygon";
    }
    EXPECT_TRUE(sum == area) << tag << ": triangles do not cover the polygon";
  }
  for (int u : used)
    EXPECT_EQ(u, 1) << tag << ": a loop in no polygon or in two";
}

/// Every lattice point of the image and a margin of two: inside, outside or on the loops.
void checkSeparation(const vbr::BitVolume& img,
  const vbr::SeparatingPolygons& r,
  const std::string& tag)
{
  const std::set<Point2L> marked(r.backgroundOnBoundary.begin(), r.backgroundOnBoundary.end());
  EXPECT_EQ(marked.size(), r.backgroundOnBoundary.size()) << tag << ": a mark listed twice";
  vbr::BitVolume rebuilt(img.size(0), img.size(1), 1);
  std::size_t markedSeen = 0;
  for (std::int64_t y = -2; y < img.size(1) + 2; ++y)
    for (std::int64_t x = -2; x < img.size(0) + 2; ++x)
    {
      const Point2L p{ x, y };
      const bool in = x >= 0 && y >= 0 && x < img.size(0) && y < img.size(1);
      bool on = false;
      int w = 0;
      for (const vbr::SeparatingLoop& l : r.loops)
      {
        for (std::size_t i = 0; i < l.corners.size() && !on; ++i)
          on = onSegment(p, l.corners[i], l.corners[(i + 1) % l.corners.size()]);
        w += winding(l.corners, p);
      }
      const bool object = pixel(img, p);
      if (on)
      {
        EXPECT_EQ(marked.count(p) == 1, in && !object)
          << tag << ": wrong mark at " << x << "," << y;
        markedSeen += marked.count(p);
      }
      else
      {
        ASSERT_TRUE(w == 0 || w == 1) << tag << ": winding " << w;
        EXPECT_EQ(w == 1, object) << tag << ": "
                                  << (object ? "object centre outside "
                                             : "background centre inside ")
                                  << x << "," << y;
      }
      if (in && ((on && marked.count(p) == 0) || (!on && w == 1)))
        rebuilt.set(static_cast<int>(x), static_cast<int>(y), 0);
    }
  EXPECT_EQ(markedSeen, marked.size()) << tag << ": a mark off the loops";
  EXPECT_TRUE(rebuilt == img) << tag << ": brute-force reversion differs";
  EXPECT_TRUE(vbr::revertSeparatingPolygons2D(
                r.loops, r.backgroundOnBoundary, img.size(0), img.size(1)) == img)
    << tag << ": reversion differs";
}

vbr::SeparatingPolygons check(const vbr::BitVolume& img, const std::string& tag)
{
  const vbr::SeparatingPolygons r = vbr::separatingPolygons2D(img);
  EXPECT_TRUE(r.complete) << tag << ": " << r.failure;
  checkLoopsSimple(r, tag);
  checkPolygons(r, tag);
  checkSeparation(img, r, tag);
  return r;
}

template<typename F>
vbr::BitVolume image(int nx, int ny, F&& inside)
{
  vbr::BitVolume v(nx, ny, 1);
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
      if (inside(x, y))
        v.set(x, y, 0);
  return v;
}

TEST(ConvexHullModifier2D, RandomImagesSeparateAgainstBruteForce)
{
  const auto start = std::chrono::steady_clock::now();
  std::mt19937 rng(2024);
  std::size_t notches = 0, holes = 0, polygons = 0, deepest = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    const int nx = 2 + static_cast<int>(rng() % 23), ny = 2 + static_cast<int>(rng() % 23);
    const double density = 0.2 + 0.6 * (rng() % 1000) / 1000.0;
    std::bernoulli_distribution bit(density);
    const vbr::BitVolume img = image(nx, ny, [&](int, int) { return bit(rng); });
    const auto r = check(img,
      "trial " + std::to_string(trial) + " (" + std::to_string(nx) + "x" + std::to_string(ny) +
        ", density " + std::to_string(density) + ")");
    notches += static_cast<std::size_t>(r.notches);
    holes += static_cast<std::size_t>(r.holes);
    polygons += r.polygons.size();
    deepest = std::max(deepest, static_cast<std::size_t>(r.degreeOfNonConvexity));
    if (::testing::Test::HasFailure())
      break;
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "400 random images: " << polygons << " polygons, " << holes << " holes, " << notches
            << " notches, deepest level " << deepest << ", " << seconds << " s\n";
  EXPECT_GT(notches, 0u); // the notch path is exercised
}

TEST(ConvexHullModifier2D, LargerRandomImagesNestDeeply)
{
  std::mt19937 rng(99);
  int deepest = 0;
  for (int trial = 0; trial < 12; ++trial)
  {
    const int nx = 40 + static_cast<int>(rng() % 25), ny = 40 + static_cast<int>(rng() % 25);
    std::bernoulli_distribution bit(0.3 + 0.04 * trial);
    const auto r = check(
      image(nx, ny, [&](int, int) { return bit(rng); }), "large trial " + std::to_string(trial));
    deepest = std::max(deepest, r.degreeOfNonConvexity);
    if (::testing::Test::HasFailure())
      break;
  }
  EXPECT_GE(deepest, 8); // rings nested in rings: noise near half density
}

TEST(ConvexHullModifier2D, ReportsProgressAndStopsWhenAborted)
{
  // Noise nests regions deeply: the tree's regions report an increasing progress in [0, 1]
  // and the abort, asked for after a few polls, stops the tree (an exception, no result).
  std::mt19937 rng(5);
  std::bernoulli_distribution bit(0.45);
  const vbr::BitVolume noise = image(96, 96, [&](int, int) { return bit(rng); });
  std::vector<double> seen;
  vbr::Execution watch;
  watch.progress = [&](double f)
  {
    seen.push_back(f);
    return true;
  };
  vbr::separatingPolygons2D(noise, watch);
  ASSERT_GE(seen.size(), 4u) << "progress from inside the tree";
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GE(seen.front(), 0.0);
  EXPECT_LE(seen.back(), 1.0);
  int polls = 0;
  vbr::Execution stop;
  stop.aborted = [&] { return ++polls > 3; };
  EXPECT_THROW(vbr::separatingPolygons2D(noise, stop), std::runtime_error);
  EXPECT_EQ(polls, 4) << "stopped at the first poll that asked";
}

TEST(ConvexHullModifier2D, DegenerateImages)
{
  const auto empty = check(image(5, 4, [](int, int) { return false; }), "empty");
  EXPECT_TRUE(empty.loops.empty());
  check(image(1, 1, [](int, int) { return true; }), "1x1 pixel");
  check(image(5, 5, [](int x, int y) { return x == 2 && y == 2; }), "one pixel");
  check(image(5, 5, [](int x, int y) { return x == 4 && y == 4; }), "corner pixel");
  check(image(9, 1, [](int x, int) { return x % 3 != 1; }), "one row, gaps");
  check(image(1, 9, [](int, int y) { return y != 4; }), "one column, a gap");
  check(image(8, 1, [](int, int) { return true; }), "full row");
  const auto full = check(image(6, 5, [](int, int) { return true; }), "full");
  EXPECT_EQ(full.loops.size(), 1u);
  EXPECT_EQ(full.loops[0].corners.size(), 4u);
  check(image(7, 7, [](int x, int y) { return x == y; }), "diagonal line");
  check(image(7, 7, [](int x, int y) { return x == 3 || y == 3; }), "cross");
}

TEST(ConvexHullModifier2D, DiscWithHolesAndRing)
{
  const auto disc = check(image(24,
                            24,
                            [](int x, int y)
                            {
                              const double r = std::hypot(x - 11.5, y - 11.5);
                              const bool hole = std::hypot(x - 7, y - 11) < 2 ||
                                std::hypot(x - 15, y - 8) < 2.5 || (x == 15 && y == 16);
                              return r < 11 && !hole;
                            }),
    "disc with holes");
  ASSERT_EQ(disc.polygons.size(), 1u);
  EXPECT_EQ(disc.polygons[0].holes.size(), 3u);
  const auto ring = check(image(20,
                            20,
                            [](int x, int y)
                            {
                              const double r = std::hypot(x - 9.5, y - 9.5);
                              return r < 9 && r > 5;
                            }),
    "ring");
  ASSERT_EQ(ring.polygons.size(), 1u);
  EXPECT_EQ(ring.polygons[0].holes.size(), 1u);
  EXPECT_EQ(ring.degreeOfNonConvexity, 1);
  // A square ring with a mouth through the bottom edge of its hull: the hole opens there
  // (a concavity pressed in from the touching edge piece), no hole is left.
  const auto c = check(image(15,
                         15,
                         [](int x, int y)
                         {
                           const bool hole = x >= 4 && x <= 10 && y >= 4 && y <= 10;
                           const bool mouth = x >= 5 && x <= 9 && y < 4;
                           return !hole && !mouth;
                         }),
    "C shape");
  ASSERT_EQ(c.polygons.size(), 1u);
  EXPECT_TRUE(c.polygons[0].holes.empty());
  EXPECT_EQ(c.notches, 1);
  const auto two = check(
    image(20, 9, [](int x, int y) { return y > 1 && y < 7 && (x < 6 || x > 12); }), "two blobs");
  EXPECT_EQ(two.polygons.size(), 2u);
}

TEST(ConvexHullModifier2D, PixelsTouchingAtACorner)
{
  check(image(2, 2, [](int x, int y) { return x == y; }), "2x2 diagonal");
  check(image(2, 2, [](int x, int y) { return x != y; }), "2x2 anti-diagonal");
  check(image(6, 6, [](int x, int y) { return (x + y) % 2 == 0; }), "checkerboard 6x6");
  check(image(7, 5, [](int x, int y) { return (x + y) % 2 == 1; }), "checkerboard 7x5");
  check(
    image(9, 9, [](int x, int y) { return (x / 3 + y / 3) % 2 == 0; }), "checkerboard 3x3 blocks");
  // An 8-connected loop around one background centre with no other lattice point inside its
  // hull: the centre can only be pressed in from an edge (a notch).
  const std::set<Point2L> around{ { 0, 0 }, { 1, 0 }, { 2, 1 }, { 1, 2 }, { 0, 1 } };
  const auto notch = check(image(3,
                             3,
                             [&](int x, int y) {
                               return around.count({ x, y }) == 1;
                             }),
    "notch");
  EXPECT_EQ(notch.notches, 1);
}

} // namespace
