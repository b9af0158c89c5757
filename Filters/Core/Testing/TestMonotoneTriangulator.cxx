// MonotoneTriangulator against brute force on orthogonal faces: the faces of random volumes and
// of random images (holes, loops touching at corners when faces are merged at vertices, corners
// that go straight on where T-junction vertices are inserted) and hand-made faces. For every
// face the sweep must succeed and its triangles must: turn strictly counter-clockwise; add up
// to twice the face's area (exact integers); hold every sample point of the face (four per
// pixel, moved to generic places) exactly once and no point outside it (even-odd rule of the
// loops, counted independently); use every loop corner; and meet edge to edge (each loop edge
// is one triangle edge, every other triangle edge has exactly one reversed twin: no
// T-junction).
#include "BRep.h"
#include "BruteForce.h"
#include "EVM.h"
#include "FaceTriangulator.h"
#include "Geometry.h"
#include "MonotoneTriangulator.h"
#include "PlaneSweep3D.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{

using P2 = std::array<std::int64_t, 2>;
using vbr::Wide;

Wide cross(const P2& a, const P2& b, const P2& c)
{
  return Wide(b[0] - a[0]) * (c[1] - a[1]) - Wide(b[1] - a[1]) * (c[0] - a[0]);
}

/// Whether the point p (coordinates scaled by `scale`) lies inside the loops by the even-odd
/// rule: the vertical loop edges crossed by the ray from p towards +x.
bool insideLoops(const std::vector<P2>& at,
  const std::vector<int>& next,
  const P2& p,
  std::int64_t scale)
{
  bool inside = false;
  for (std::size_t i = 0; i < at.size(); ++i)
  {
    const P2 &a = at[i], &b = at[static_cast<std::size_t>(next[i])];
    if (a[0] != b[0] || a[0] * scale < p[0])
      continue;
    const std::int64_t lo = std::min(a[1], b[1]) * scale, hi = std::max(a[1], b[1]) * scale;
    inside ^= lo < p[1] && p[1] < hi;
  }
  return inside;
}

/// Asserts that the generic sample point at quarter units (x, y) of the face lies in exactly
/// one triangle of `tri` (corners scaled by `scale` = 4 M^2) when inside the loops, in none
/// outside.
void expectCoveredOnceInside(const std::vector<std::array<P2, 3>>& tri,
  const std::vector<P2>& at,
  const std::vector<int>& next,
  std::int64_t M,
  std::int64_t x,
  std::int64_t y)
{
  const std::int64_t scale = 4 * M * M;
  const P2 s{ x * M * M + M, y * M * M + 1 };
  int covered = 0;
  for (const auto& t : tri)
    covered += cross(t[0], t[1], s) > 0 && cross(t[1], t[2], s) > 0 && cross(t[2], t[0], s) > 0;
  ASSERT_EQ(covered, insideLoops(at, next, s, scale) ? 1 : 0)
    << "sample " << x << "/4 " << y << "/4";
}

struct Counts
{
  std::size_t faces = 0, withHoles = 0, touching = 0, straight = 0, triangles = 0;
};

/// Runs the sweep on one face (corners `at`, loops by `next`, `loops` of them) and checks
/// everything the file comment lists.
void checkFace(vbr::MonotoneTriangulator& sweep,
  const std::vector<P2>& at,
  const std::vector<int>& next,
  int loops,
  Counts& counts)
{
  std::vector<int> triangles;
  ASSERT_TRUE(sweep.triangulate(at, next, triangles)) << "the sweep refused the face";
  ASSERT_EQ(triangles.size() % 3, 0u);
  ++counts.faces;
  counts.withHoles += loops > 1;
  counts.triangles += triangles.size() / 3;
  std::set<P2> places;
  std::map<P2, int> seen;
  for (std::size_t i = 0; i < at.size(); ++i)
  {
    places.insert(at[i]);
    counts.touching += ++seen[at[i]] == 2;
  }
  std::vector<int> prev(at.size());
  for (std::size_t i = 0; i < at.size(); ++i)
    prev[static_cast<std::size_t>(next[i])] = static_cast<int>(i);
  for (std::size_t i = 0; i < at.size(); ++i)
    counts.straight +=
      cross(at[static_cast<std::size_t>(prev[i])], at[i], at[static_cast<std::size_t>(next[i])]) ==
      0;

  // Orientation and area.
  Wide area = 0, twiceTriangles = 0;
  for (std::size_t i = 0; i < at.size(); ++i)
  {
    const P2 &p = at[i], &q = at[static_cast<std::size_t>(next[i])];
    area += Wide(p[0]) * q[1] - Wide(p[1]) * q[0];
  }
  std::set<P2> used;
  std::map<std::pair<P2, P2>, int> edges;
  std::vector<std::array<P2, 3>> tri;
  for (std::size_t t = 0; t < triangles.size(); t += 3)
  {
    std::array<P2, 3> corners;
    for (int k = 0; k < 3; ++k)
    {
      const int c = triangles[t + static_cast<std::size_t>(k)];
      ASSERT_TRUE(c >= 0 && c < static_cast<int>(at.size()));
      ASSERT_EQ(c, std::find(at.begin(), at.end(), at[static_cast<std::size_t>(c)]) - at.begin())
        << "a corner not reported by the smallest index of the corners at its place";
      corners[static_cast<std::size_t>(k)] = at[static_cast<std::size_t>(c)];
      used.insert(at[static_cast<std::size_t>(c)]);
    }
    const Wide c = cross(corners[0], corners[1], corners[2]);
    ASSERT_GT(c, 0) << "a triangle flat or turned clockwise";
    twiceTriangles += c;
    for (int k = 0; k < 3; ++k)
      ++edges[{
        corners[static_cast<std::size_t>(k)], corners[static_cast<std::size_t>((k + 1) % 3)] }];
    tri.push_back(corners);
  }
  EXPECT_TRUE(area == twiceTriangles) << "the triangles do not add up to the face's area";
  EXPECT_EQ(used, places) << "a loop corner is no triangle corner";

  // Edge to edge: loop edges once, in their direction; every other edge with one twin.
  std::map<std::pair<P2, P2>, int> loopEdges;
  for (std::size_t i = 0; i < at.size(); ++i)
    ++loopEdges[{ at[i], at[static_cast<std::size_t>(next[i])] }];
  for (const auto& [edge, count] : edges)
  {
    EXPECT_EQ(count, 1) << "an edge twice in one direction";
    const auto twin = edges.find({ edge.second, edge.first });
    const bool onLoop = loopEdges.count(edge) != 0;
    EXPECT_TRUE(onLoop != (twin != edges.end())) << "a T-junction or an edge of no face";
  }
  for (const auto& [edge, count] : loopEdges)
    EXPECT_EQ(edges.count(edge), 1u) << "a loop edge is no triangle edge";

  // Coverage at generic sample points, four per pixel.
  std::int64_t x0 = at[0][0], x1 = x0, y0 = at[0][1], y1 = y0;
  for (const P2& p : at)
  {
    x0 = std::min(x0, p[0]);
    x1 = std::max(x1, p[0]);
    y0 = std::min(y0, p[1]);
    y1 = std::max(y1, p[1]);
  }
  const std::int64_t M = 8 * std::max(x1 - x0, y1 - y0) + 11, scale = 4 * M * M;
  for (auto& t : tri)
    for (auto& q : t)
      q = { q[0] * scale, q[1] * scale };
  for (std::int64_t x = 4 * x0; x < 4 * x1; ++x)
    for (std::int64_t y = 4 * y0; y < 4 * y1; ++y)
    {
      expectCoveredOnceInside(tri, at, next, M, x, y);
      if (testing::Test::HasFatalFailure())
        return;
    }
}

/// Every face of the B-Rep of `volume`, in the coordinates the face triangulator uses.
void checkVolume(const vbr::BitVolume& volume, bool merged, bool tJunctions, Counts& counts)
{
  vbr::BRep brep;
  ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(volume),
    merged ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge,
    vbr::Execution(),
    brep));
  if (tJunctions)
    vbr::insertTJunctionVertices(brep);
  vbr::MonotoneTriangulator sweep; // one for all faces: its arrays pass from face to face
  for (std::size_t f = 0; f < brep.faces.size(); ++f)
  {
    const vbr::BRepFace& face = brep.faces[f];
    const int u = (face.axis + 1) % 3, v = (face.axis + 2) % 3;
    const int x = face.normalSign > 0 ? u : v, y = face.normalSign > 0 ? v : u;
    std::vector<P2> at;
    std::vector<int> next;
    for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
    {
      const vbr::PointRange pts = brep.loopPoints(l);
      const int start = static_cast<int>(at.size()), n = static_cast<int>(pts.size());
      for (int i = 0; i < n; ++i)
      {
        at.push_back({ pts[static_cast<std::size_t>(i)][x], pts[static_cast<std::size_t>(i)][y] });
        next.push_back(start + (i + 1) % n);
      }
    }
    SCOPED_TRACE("face " + std::to_string(f));
    checkFace(sweep, at, next, face.loopCount, counts);
    if (testing::Test::HasFatalFailure())
      return;
  }
}

TEST(MonotoneTriangulator, TilesTheFacesOfRandomVolumes)
{
  Counts counts;
  unsigned seed = 9100;
  for (int trial = 0; trial < 48; ++trial)
  {
    const vbr::Point3 d = bf::trialDims(trial, 2);
    const double density = 0.1 + 0.8 * (trial % 8) / 7.0;
    const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
    SCOPED_TRACE(testing::Message() << "trial " << trial << " density " << density);
    checkVolume(v, trial % 2 == 0, trial % 3 != 0, counts);
    if (HasFatalFailure())
      return;
  }
  EXPECT_GT(counts.withHoles, 20u);
  EXPECT_GT(counts.touching, 20u);
  EXPECT_GT(counts.straight, 1000u);
}

// Random images (one slice) of many sizes and densities: faces with many holes, holes touching
// each other and the outer loop at corners (merged faces), long loops.
TEST(MonotoneTriangulator, TilesTheFacesOfRandomImages)
{
  Counts counts;
  unsigned seed = 7300;
  for (int trial = 0; trial < 60; ++trial)
  {
    const vbr::Coord w = 3 + (trial * 7) % 37, h = 3 + (trial * 11) % 29;
    const double density = 0.2 + 0.6 * (trial % 7) / 6.0;
    vbr::BitVolume v = bf::randomVolume({ w, h, 1 }, density, seed++);
    if (trial % 3 == 0) // a frame: one face with many holes
      for (vbr::Coord y = 0; y < h; ++y)
        for (vbr::Coord x = 0; x < w; ++x)
          if (x == 0 || y == 0 || x == w - 1 || y == h - 1)
            v.set(x, y, 0, true);
    SCOPED_TRACE(testing::Message() << "image " << trial << " " << w << "x" << h);
    checkVolume(v, trial % 2 == 0, trial % 4 == 1, counts);
    if (HasFatalFailure())
      return;
  }
  RecordProperty("faces", static_cast<int>(counts.faces));
  RecordProperty("withHoles", static_cast<int>(counts.withHoles));
  RecordProperty("touching", static_cast<int>(counts.touching));
  EXPECT_GT(counts.withHoles, 40u);
  EXPECT_GT(counts.touching, 100u);
}

/// A face from loops given as corner lists (each closed, the inside on its left).
void checkLoops(const std::vector<std::vector<P2>>& loops)
{
  std::vector<P2> at;
  std::vector<int> next;
  for (const auto& loop : loops)
  {
    const int start = static_cast<int>(at.size()), n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i)
    {
      at.push_back(loop[static_cast<std::size_t>(i)]);
      next.push_back(start + (i + 1) % n);
    }
  }
  vbr::MonotoneTriangulator sweep;
  Counts counts;
  SCOPED_TRACE(testing::Message() << "loops starting at (" << at[0][0] << ", " << at[0][1] << "), "
                                  << at.size() << " corners");
  checkFace(sweep, at, next, static_cast<int>(loops.size()), counts);
}

// Degenerate cases by hand: straight-on corners on every side and next to the sweep's extreme
// corners, a hole touching the outer loop at a corner (both diagonals), two holes touching each
// other, a hole whose sides carry straight-on corners, a comb (many split and merge corners).
TEST(MonotoneTriangulator, HandMadeDegenerateFaces)
{
  // A rectangle with straight-on corners on all four sides, two in a row at its bottom.
  checkLoops({ { { 0, 0 },
    { 1, 0 },
    { 2, 0 },
    { 4, 0 },
    { 4, 2 },
    { 4, 3 },
    { 2, 3 },
    { 0, 3 },
    { 0, 1 } } });
  // An L whose long sides go straight on at several corners.
  checkLoops({ { { 0, 0 },
    { 3, 0 },
    { 5, 0 },
    { 5, 1 },
    { 2, 1 },
    { 2, 2 },
    { 2, 4 },
    { 0, 4 },
    { 0, 2 } } });
  // A square with a square hole (clockwise), both with straight-on corners on their sides.
  checkLoops({ { { 0, 0 }, { 2, 0 }, { 4, 0 }, { 4, 4 }, { 0, 4 }, { 0, 3 } },
    { { 1, 1 }, { 1, 2 }, { 1, 3 }, { 3, 3 }, { 3, 1 }, { 2, 1 } } });
  // Hole touching the outer loop at a corner: the 3x3 square without its centre and without its
  // top right pixel; the hole meets the outer loop at (2, 2). Both diagonals.
  checkLoops({ { { 0, 0 }, { 3, 0 }, { 3, 2 }, { 2, 2 }, { 2, 3 }, { 0, 3 } },
    { { 1, 1 }, { 1, 2 }, { 2, 2 }, { 2, 1 } } });
  checkLoops({ { { 0, 0 }, { 3, 0 }, { 3, 3 }, { 1, 3 }, { 1, 2 }, { 0, 2 } },
    { { 1, 1 }, { 1, 2 }, { 2, 2 }, { 2, 1 } } });
  // Two holes touching each other at a corner inside a 4x4 square.
  checkLoops({ { { 0, 0 }, { 4, 0 }, { 4, 4 }, { 0, 4 } },
    { { 1, 1 }, { 1, 2 }, { 2, 2 }, { 2, 1 } },
    { { 2, 2 }, { 2, 3 }, { 3, 3 }, { 3, 2 } } });
  checkLoops({ { { 0, 0 }, { 4, 0 }, { 4, 4 }, { 0, 4 } },
    { { 2, 1 }, { 2, 2 }, { 3, 2 }, { 3, 1 } },
    { { 1, 2 }, { 1, 3 }, { 2, 3 }, { 2, 2 } } });
  // Two squares touching at a corner, as one loop passing the corner twice (merged).
  checkLoops(
    { { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 2, 1 }, { 2, 2 }, { 1, 2 }, { 1, 1 }, { 0, 1 } } });
  // A comb opening downwards then upwards: many split and merge corners.
  std::vector<P2> comb{ { 0, 0 } };
  for (int k = 0; k < 6; ++k) // slots up from the bottom
  {
    comb.push_back({ 4 * k + 1, 0 });
    comb.push_back({ 4 * k + 1, 3 });
    comb.push_back({ 4 * k + 2, 3 });
    comb.push_back({ 4 * k + 2, 0 });
  }
  comb.push_back({ 25, 0 });
  comb.push_back({ 25, 5 });
  for (int k = 5; k >= 0; --k) // slots down from the top, between those from the bottom
  {
    comb.push_back({ 4 * k + 4, 5 });
    comb.push_back({ 4 * k + 4, 2 });
    comb.push_back({ 4 * k + 3, 2 });
    comb.push_back({ 4 * k + 3, 5 });
  }
  comb.push_back({ 0, 5 });
  checkLoops({ comb });
}

/// Whether the sweep refuses the loops (corner lists, each closed).
bool refuses(const std::vector<std::vector<P2>>& loops)
{
  std::vector<P2> at;
  std::vector<int> next;
  for (const std::vector<P2>& loop : loops)
  {
    const int start = static_cast<int>(at.size()), n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i)
    {
      at.push_back(loop[static_cast<std::size_t>(i)]);
      next.push_back(start + (i + 1) % n);
    }
  }
  vbr::MonotoneTriangulator sweep;
  std::vector<int> triangles;
  return !sweep.triangulate(at, next, triangles);
}

// The invalid inputs the header says are refused.
TEST(MonotoneTriangulator, RefusesInvalidLoops)
{
  const std::vector<P2> square{ { 0, 0 }, { 4, 0 }, { 4, 4 }, { 0, 4 } };
  EXPECT_FALSE(refuses({ square }));
  // A clockwise outer loop.
  EXPECT_TRUE(refuses({ { { 0, 0 }, { 0, 4 }, { 4, 4 }, { 4, 0 } } }));
  // A hole crossing the outer loop.
  EXPECT_TRUE(refuses({ square, { { 2, 1 }, { 2, 3 }, { 6, 3 }, { 6, 1 } } }));
  // A hole outside the outer loop.
  EXPECT_TRUE(refuses({ square, { { 6, 1 }, { 6, 3 }, { 8, 3 }, { 8, 1 } } }));
  // The outer loop twice.
  EXPECT_TRUE(refuses({ square, square }));
  // A hole with an edge on the outer loop's.
  EXPECT_TRUE(refuses({ square, { { 0, 1 }, { 0, 3 }, { 2, 3 }, { 2, 1 } } }));
  // next not a permutation: corner 3 goes back to corner 1, nothing goes to corner 0.
  vbr::MonotoneTriangulator sweep;
  std::vector<int> triangles;
  EXPECT_FALSE(sweep.triangulate(square, { 1, 2, 3, 1 }, triangles));
  EXPECT_FALSE(sweep.triangulate(square, { 1, 2, 3, 4 }, triangles));
  EXPECT_TRUE(sweep.triangulate(square, { 1, 2, 3, 0 }, triangles)); // the arrays recover
}

/// A square of side `width` with a square hole (8 corners).
std::vector<std::vector<P2>> frame(std::int64_t width)
{
  return { { { 0, 0 }, { width, 0 }, { width, width }, { 0, width } },
    { { 1, 1 }, { 1, width - 1 }, { width - 1, width - 1 }, { width - 1, 1 } } };
}

// A face much wider than its corners are many is refused (its arrays would grow with the
// width: 2^25 wide took 141 MB); up to the limit it is tiled.
TEST(MonotoneTriangulator, RefusesFacesTooWideForTheirCorners)
{
  const std::int64_t limit =
    vbr::MonotoneTriangulator::MaxWidthPerCorner * 8 + vbr::MonotoneTriangulator::MaxWidthBase;
  EXPECT_FALSE(refuses(frame(limit)));
  EXPECT_TRUE(refuses(frame(limit + 1)));
  EXPECT_TRUE(refuses(frame(std::int64_t(1) << 25)));
}

// A face the sweep refuses (too wide for its corners) goes to triangulateFace's Delaunay
// method: its triangles must turn counter-clockwise, add up to the face's area, use every
// corner and hold generic sample points (near every corner's lines and random ones) exactly
// when the loops do.
TEST(MonotoneTriangulator, FaceTriangulatorFallsBackWhenTheSweepRefuses)
{
  const std::vector<std::vector<P2>> loops{
    { { 0, 0 }, { 10000, 0 }, { 10000, 10000 }, { 0, 10000 } },
    { { 1000, 1000 }, { 1000, 2000 }, { 2000, 2000 }, { 2000, 1000 } },
    { { 5000, 3000 }, { 5000, 3500 }, { 7000, 3500 }, { 7000, 3000 } }
  };
  ASSERT_TRUE(refuses(loops));
  vbr::BRep brep;
  brep.faces.push_back(vbr::BRepFace{});
  brep.faces[0].firstLoop = 0;
  brep.faces[0].loopCount = static_cast<int>(loops.size());
  std::vector<P2> at;
  std::vector<int> next;
  for (const std::vector<P2>& loop : loops)
  {
    vbr::BRepLoop l;
    l.begin = brep.points.size();
    l.face = 0;
    l.hole = !brep.loops.empty();
    const int start = static_cast<int>(at.size()), n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i)
    {
      const P2& p = loop[static_cast<std::size_t>(i)];
      brep.points.push_back({ static_cast<vbr::Coord>(p[0]), static_cast<vbr::Coord>(p[1]), 0 });
      at.push_back(p);
      next.push_back(start + (i + 1) % n);
    }
    l.end = brep.points.size();
    brep.loops.push_back(l);
  }
  const auto triangles = vbr::triangulateFace(brep, 0);
  ASSERT_FALSE(triangles.empty());
  Wide area = 0, twiceTriangles = 0;
  for (std::size_t i = 0; i < at.size(); ++i)
    area += cross({ 0, 0 }, at[i], at[static_cast<std::size_t>(next[i])]);
  std::set<P2> used;
  std::vector<std::array<P2, 3>> tri;
  const std::int64_t M = 8 * 10000 + 11, scale = 4 * M * M;
  for (const std::array<int, 3>& t : triangles)
  {
    std::array<P2, 3> corners;
    for (std::size_t k = 0; k < 3; ++k)
    {
      ASSERT_TRUE(t[k] >= 0 && t[k] < static_cast<int>(at.size()));
      corners[k] = at[static_cast<std::size_t>(t[k])];
      used.insert(corners[k]);
    }
    const Wide c = cross(corners[0], corners[1], corners[2]);
    ASSERT_GT(c, 0) << "a triangle flat or turned clockwise";
    twiceTriangles += c;
    for (P2& q : corners)
      q = { q[0] * scale, q[1] * scale };
    tri.push_back(corners);
  }
  EXPECT_TRUE(area == twiceTriangles) << "the triangles do not add up to the face's area";
  EXPECT_EQ(used, std::set<P2>(at.begin(), at.end())) << "a loop corner is no triangle corner";
  // Sample abscissae and ordinates in quarter units: round every corner's lines, and random.
  std::vector<std::int64_t> quarters;
  for (const P2& p : at)
    for (const std::int64_t c : { p[0], p[1] })
      for (std::int64_t d = -1; d <= 1; ++d)
        if (4 * c + d >= 0 && 4 * c + d < 40000)
          quarters.push_back(4 * c + d);
  std::uint64_t state = 99;
  for (int k = 0; k < 40; ++k)
  {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    quarters.push_back(static_cast<std::int64_t>((state >> 33) % 40000));
  }
  for (const std::int64_t x : quarters)
    for (const std::int64_t y : quarters)
    {
      expectCoveredOnceInside(tri, at, next, M, x, y);
      if (testing::Test::HasFatalFailure())
        return;
    }
}

// The face triangulator on a large face with many holes (a frame round a random image) and on
// long tree-shaped loops: its triangles come from the sweep, and tile the face as above.
TEST(MonotoneTriangulator, FaceTriangulatorUsesTheSweepForHoles)
{
  vbr::BitVolume v = bf::randomVolume({ 60, 50, 1 }, 0.7, 4242);
  for (vbr::Coord y = 0; y < 50; ++y)
    for (vbr::Coord x = 0; x < 60; ++x)
      if (x == 0 || y == 0 || x == 59 || y == 49)
        v.set(x, y, 0, true);
  for (bool merged : { false, true })
  {
    vbr::BRep brep;
    ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(v),
      merged ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge,
      vbr::Execution(),
      brep));
    std::size_t holes = 0;
    for (std::size_t f = 0; f < brep.faces.size(); ++f)
    {
      const vbr::BRepFace& face = brep.faces[f];
      if (face.loopCount < 3)
        continue;
      ++holes;
      // The triangles of triangulateFace are those of the sweep, reported the same way.
      std::vector<P2> at;
      std::vector<int> next;
      const int u = (face.axis + 1) % 3, w = (face.axis + 2) % 3;
      const int x = face.normalSign > 0 ? u : w, y = face.normalSign > 0 ? w : u;
      for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
      {
        const vbr::PointRange pts = brep.loopPoints(l);
        const int start = static_cast<int>(at.size()), n = static_cast<int>(pts.size());
        for (int i = 0; i < n; ++i)
        {
          at.push_back(
            { pts[static_cast<std::size_t>(i)][x], pts[static_cast<std::size_t>(i)][y] });
          next.push_back(start + (i + 1) % n);
        }
      }
      vbr::MonotoneTriangulator sweep;
      std::vector<int> expected;
      ASSERT_TRUE(sweep.triangulate(at, next, expected));
      const auto triangles = vbr::triangulateFace(brep, static_cast<int>(f));
      ASSERT_EQ(triangles.size() * 3, expected.size());
      for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
          EXPECT_EQ(triangles[t][static_cast<std::size_t>(k)],
            expected[3 * t + static_cast<std::size_t>(k)]);
      Counts counts;
      checkFace(sweep, at, next, face.loopCount, counts);
    }
    EXPECT_GT(holes, 0u);
  }
}

// The status set against a std::set: predecessors of random members and queries.
TEST(MonotoneTriangulator, PredecessorSetAnswersAsASortedSet)
{
  vbr::PredecessorSet bits;
  std::set<std::size_t> reference;
  const std::size_t slots = 300000;
  bits.reserve(slots);
  std::uint64_t state = 12345;
  const auto random = [&state]()
  {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<std::size_t>(state >> 33);
  };
  for (int step = 0; step < 200000; ++step)
  {
    const std::size_t slot = random() % (step < 100000 ? 5000 : slots);
    if (random() % 3 != 0)
    {
      bits.insert(slot);
      reference.insert(slot);
    }
    else if (reference.erase(slot) != 0)
      bits.erase(slot);
    const std::size_t query = random() % slots;
    auto it = reference.lower_bound(query);
    const std::int64_t expected = it == reference.begin() ? -1 : static_cast<std::int64_t>(*--it);
    ASSERT_EQ(bits.below(query), expected) << "step " << step;
  }
}

} // namespace
