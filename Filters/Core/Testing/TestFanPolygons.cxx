// fanPolygons (FaceTriangulator.h) against brute force on the orthogonal faces, holes
// included, of the B-Reps of random volumes: every polygon drawn as the fan from its first
// corner (as VTK draws it) must tile the face. Checked with signed areas, orientations and
// generic sample points per pixel, counted against the face's own rasterization; the same for
// the faces' polygons made one after the other in one run of faces (the filter's way, with
// scratch space reused from face to face).
#include "BRep.h"
#include "BruteForce.h"
#include "EVM.h"
#include "FaceTriangulator.h"
#include "Geometry.h"
#include "PlaneSweep3D.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{

using vbr::Wide;
using P2 = std::array<std::int64_t, 2>;

Wide cross(const P2& a, const P2& b, const P2& c)
{
  return Wide(b[0] - a[0]) * (c[1] - a[1]) - Wide(b[1] - a[1]) * (c[0] - a[0]);
}

struct FaceStats
{
  std::size_t faces = 0, withHoles = 0, single = 0, grouped = 0, flat = 0;
};

/// Every pixel centre (moved to a generic point) in exactly one triangle of the fans when
/// the face holds the pixel and in none otherwise.
void checkPixelCoverage(const vbr::BRepFace& face,
  const bf::PixelSet& pixels,
  const std::vector<P2>& corner,
  std::vector<std::array<P2, 3>> fan)
{
  // Sample (x + 1/M, y + 1/M^2) per pixel, in coordinates scaled by M^2: on no line through
  // two corners when M > span + 1.
  const auto [x0, x1, y0, y1] = bf::bounds2D(corner);
  const std::int64_t M = 2 * std::max(x1 - x0, y1 - y0) + 3, M2 = M * M;
  for (auto& t : fan)
    for (auto& q : t)
      q = { q[0] * M2, q[1] * M2 };
  for (std::int64_t x = x0; x < x1; ++x)
    for (std::int64_t y = y0; y < y1; ++y)
    {
      const P2 s{ x * M2 + M, y * M2 + 1 };
      int covered = 0;
      for (const auto& t : fan)
        covered += cross(t[0], t[1], s) > 0 && cross(t[1], t[2], s) > 0 && cross(t[2], t[0], s) > 0;
      // The pixel in the face's own (u, v) coordinates.
      const std::pair<std::int32_t, std::int32_t> pixel = face.normalSign > 0
        ? std::make_pair(std::int32_t(x), std::int32_t(y))
        : std::make_pair(std::int32_t(-x - 1), std::int32_t(y));
      ASSERT_EQ(covered, pixels.count(pixel) ? 1 : 0)
        << "pixel " << pixel.first << " " << pixel.second;
    }
}

/// The fans of the polygons of face f cover it exactly: counter-clockwise or flat triangles
/// (seen from outside) whose doubled areas add up to twice the face's pixels, every pixel
/// centre (moved to a generic point) in exactly one triangle when the face holds the pixel
/// and in none otherwise, every loop corner a polygon corner.
void checkFace(const vbr::BRep& brep,
  int f,
  const std::vector<std::vector<int>>& polygons,
  FaceStats& stats)
{
  const vbr::BRepFace& face = brep.faces[f];
  SCOPED_TRACE("face " + std::to_string(f));
  const int u = (face.axis + 1) % 3, v = (face.axis + 2) % 3;
  // Corners seen from outside: (u, v) when the normal is +axis, mirrored otherwise.
  std::vector<P2> corner;
  std::set<P2> loopCorners;
  for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
    for (const vbr::Point3& p : brep.loopPoints(l))
    {
      corner.push_back(face.normalSign > 0 ? P2{ p[u], p[v] } : P2{ -p[u], p[v] });
      loopCorners.insert(corner.back());
    }
  const bf::PixelSet pixels = bf::rasterize(brep, f);
  ASSERT_FALSE(polygons.empty());
  ++stats.faces;
  stats.withHoles += face.loopCount > 1;
  (polygons.size() == 1 ? stats.single : stats.grouped) += 1;

  std::vector<std::array<P2, 3>> fan;
  std::set<P2> used;
  Wide total = 0;
  for (const auto& polygon : polygons)
  {
    ASSERT_GE(polygon.size(), 3u);
    std::set<P2> distinct;
    for (int i : polygon)
    {
      ASSERT_TRUE(i >= 0 && i < static_cast<int>(corner.size())) << "not a loop corner";
      used.insert(corner[i]);
      distinct.insert(corner[i]);
    }
    EXPECT_EQ(distinct.size(), polygon.size()) << "a polygon visits a corner twice";
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
    {
      const std::array<P2, 3> t{ corner[polygon[0]], corner[polygon[i]], corner[polygon[i + 1]] };
      const Wide c = cross(t[0], t[1], t[2]);
      EXPECT_GE(c, 0) << "fan triangle turned inwards";
      stats.flat += c == 0;
      total += c;
      if (c != 0)
        fan.push_back(t);
    }
  }
  EXPECT_TRUE(total == Wide(2 * pixels.size())) << "fans do not add up to the face's area";
  EXPECT_EQ(used, loopCorners) << "a loop corner is no polygon corner";

  checkPixelCoverage(face, pixels, corner, fan);
}

/// The polygons of the i-th face of a run of faces (FaceCells).
std::vector<std::vector<int>> polygonsOfRun(const vbr::FaceCells& run, std::size_t i)
{
  std::vector<std::vector<int>> polygons;
  for (std::size_t c = run.cellBegin(i); c < run.faceEnds[i]; ++c)
    polygons.emplace_back(
      run.corners.begin() + run.cornerBegin(c), run.corners.begin() + run.cellEnds[c]);
  return polygons;
}

/// The faces of `volume` as the plane sweep gives them: merged at vertices (`merged`) or
/// kept apart, with the T-junction vertices inserted or not.
bool sweptFaces(const vbr::BitVolume& volume, bool merged, bool tJunctions, vbr::BRep& brep)
{
  if (!vbr::planeSweep3D(vbr::extractEVM(volume),
        merged ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge,
        vbr::Execution(),
        brep))
    return false;
  if (tJunctions)
    vbr::insertTJunctionVertices(brep);
  return true;
}

void checkVolume(const vbr::BitVolume& volume, bool merged, bool tJunctions, FaceStats& stats)
{
  vbr::BRep brep;
  ASSERT_TRUE(sweptFaces(volume, merged, tJunctions, brep));
  for (std::size_t f = 0; f < brep.faces.size(); ++f)
    checkFace(brep, static_cast<int>(f), vbr::fanPolygons(brep, static_cast<int>(f)), stats);
  // The filter's way: all faces in one run whose scratch space passes from face to face, the
  // faces in reverse order (the larger plates' faces come last in the sweep, so smaller faces
  // then reuse a larger face's scratch). Each face's cells must tile it all the same.
  vbr::FaceCells run;
  const std::size_t n = brep.faces.size();
  for (std::size_t i = 0; i < n; ++i)
    vbr::appendFanPolygons(brep, static_cast<int>(n - 1 - i), run);
  ASSERT_EQ(run.faceEnds.size(), n);
  FaceStats runStats;
  for (std::size_t i = 0; i < n; ++i)
  {
    SCOPED_TRACE("in one run");
    checkFace(brep, static_cast<int>(n - 1 - i), polygonsOfRun(run, i), runStats);
  }
}

/// The loop round the rectangle [x0, x0 + w] x [y0, y0 + h], counter-clockwise from (x0, y0),
/// with the points of its sides that `keep()` takes (asked once per point, in loop order).
template<typename Keep>
std::vector<P2> rectangleLoop(int x0, int y0, int w, int h, Keep keep)
{
  std::vector<P2> loop;
  const std::array<P2, 4> corner{
    P2{ x0, y0 }, P2{ x0 + w, y0 }, P2{ x0 + w, y0 + h }, P2{ x0, y0 + h }
  };
  for (int side = 0; side < 4; ++side)
  {
    loop.push_back(corner[side]);
    const P2 &a = corner[side], &b = corner[(side + 1) % 4];
    const int length = static_cast<int>(std::abs(b[0] - a[0]) + std::abs(b[1] - a[1]));
    for (int s = 1; s < length; ++s)
      if (keep())
        loop.push_back({ a[0] + (b[0] - a[0]) / length * s, a[1] + (b[1] - a[1]) / length * s });
  }
  return loop;
}

/// A B-Rep of one face without holes whose loop runs counter-clockwise through `loop` in the
/// face's own coordinates (seen from outside), normal `axis` and `normalSign`, at `position`.
vbr::BRep faceOfLoop(const std::vector<P2>& loop, int axis, int normalSign, vbr::Coord position)
{
  vbr::BRepFace face;
  face.axis = axis;
  face.normalSign = normalSign;
  face.position = position;
  face.loopCount = 1;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  vbr::BRep brep;
  for (const P2& p : loop)
  {
    vbr::Point3 q{ 0, 0, 0 };
    q[axis] = position;
    q[normalSign > 0 ? u : v] = static_cast<vbr::Coord>(p[0]);
    q[normalSign > 0 ? v : u] = static_cast<vbr::Coord>(p[1]);
    brep.points.push_back(q);
  }
  brep.loops.push_back({ 0, loop.size(), 0, false });
  brep.faces.push_back(face);
  return brep;
}

} // namespace

TEST(FanPolygons, TileTheFacesOfRandomVolumes)
{
  FaceStats stats;
  unsigned seed = 5100;
  for (int trial = 0; trial < 40; ++trial)
  {
    const vbr::Point3 d = bf::trialDims(trial, 2);
    const double density = 0.1 + 0.8 * (trial % 8) / 7.0;
    const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
    SCOPED_TRACE(testing::Message() << "trial " << trial << " density " << density);
    checkVolume(v, trial % 2 == 0, trial % 3 != 0, stats);
  }
  // Plates with holes: large faces with many holes, some touching the outer loop or each
  // other at corners.
  for (int trial = 0; trial < 12; ++trial)
  {
    vbr::BitVolume v = bf::randomVolume({ 14, 12, 1 }, 0.15 + 0.05 * (trial % 4), seed++);
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 14; ++x)
        v.set(x, y, 0, !v.get(x, y, 0) || x == 0 || y == 0 || x == 13 || y == 11);
    SCOPED_TRACE(testing::Message() << "plate " << trial);
    checkVolume(v, trial % 2 == 0, trial % 3 != 0, stats);
  }
  RecordProperty("faces", static_cast<int>(stats.faces));
  RecordProperty("withHoles", static_cast<int>(stats.withHoles));
  RecordProperty("grouped", static_cast<int>(stats.grouped));
  RecordProperty("flat", static_cast<int>(stats.flat));
  EXPECT_GT(stats.withHoles, 50u);
  EXPECT_GT(stats.grouped, 100u);
  EXPECT_GT(stats.single, 1000u);
  EXPECT_GT(stats.flat, 100u);
}

// The fans of an ear-clipped face group its triangles by their neighbours as the ear clipping
// found them (each cut is the edge between the triangle it cuts off and a later one); the
// reference finds them by sorting the triangles' edges, as for the faces the sweep into
// monotone pieces or CGAL triangulate. The same polygons, face for face, on random volumes with
// and without T-junction vertices, merged at vertices or not (faces with parts, and faces with
// holes, which take the reference's way in both).
TEST(FanPolygons, NeighboursFromTheEarClippingGroupAsTheSortedEdges)
{
  unsigned seed = 7300;
  std::size_t grouped = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    const vbr::Point3 d = bf::trialDims(trial, 2);
    const vbr::BitVolume v = bf::randomVolume(d, 0.1 + 0.8 * (trial % 8) / 7.0, seed++);
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    vbr::BRep brep;
    ASSERT_TRUE(sweptFaces(v, trial % 2 == 0, trial % 3 != 0, brep));
    for (std::size_t f = 0; f < brep.faces.size(); ++f)
    {
      const auto polygons = vbr::fanPolygons(brep, static_cast<int>(f));
      EXPECT_EQ(polygons, vbr::detail::fanPolygonsFromSortedEdges(brep, static_cast<int>(f)))
        << "face " << f;
      grouped += brep.faces[f].loopCount == 1 && polygons.size() > 1;
    }
  }
  RecordProperty("grouped", static_cast<int>(grouped));
  EXPECT_GT(grouped, 200u); // faces without holes whose triangles were grouped into fans
}

// Faces merged at vertices (MergeNonManifoldFaces) whose parts touch only at corners: a
// checkerboard plate's top and bottom faces are one face each, with the white squares as
// holes that touch the outer loop and each other at corners. Each black square is an
// edge-connected part of its own, so the face's polygons are its squares, one 4-corner
// polygon each, and they are its parts (edgeConnectedPartsOf) up to the corner they start at;
// the same with one black square grown into an L (a part of 6 corners).
TEST(FanPolygons, FacesMergedAtCornersArePolygonsPerPart)
{
  for (bool grown : { false, true })
  {
    SCOPED_TRACE(grown ? "one part an L" : "checkerboard");
    vbr::BitVolume v({ 9, 7, 1 });
    int black = 0;
    for (int y = 0; y < 7; ++y)
      for (int x = 0; x < 9; ++x)
        if ((x + y) % 2 == 0)
        {
          v.set(x, y, 0, true);
          ++black;
        }
    if (grown) // (3, 3), (4, 3) and (4, 2) as an L: (4, 3) set, its other neighbours cleared
    {
      v.set(4, 3, 0, true);
      v.set(5, 3, 0, false);
      v.set(4, 4, 0, false);
    }
    vbr::BRep brep;
    ASSERT_TRUE(
      vbr::planeSweep3D(vbr::extractEVM(v), vbr::FaceConnectivity::Vertex, vbr::Execution(), brep));
    FaceStats stats;
    int plateFaces = 0;
    for (std::size_t f = 0; f < brep.faces.size(); ++f)
    {
      const std::vector<std::vector<int>> polygons = vbr::fanPolygons(brep, static_cast<int>(f));
      checkFace(brep, static_cast<int>(f), polygons, stats);
      if (brep.faces[f].axis != 2)
        continue;
      ++plateFaces;
      std::size_t squares = 0, others = 0;
      for (const auto& p : polygons)
        (p.size() == 4 ? squares : others) += 1;
      EXPECT_EQ(squares + others, polygons.size());
      EXPECT_EQ(int(squares), grown ? black - 4 : black) << "face " << f;
      EXPECT_EQ(int(others), grown ? 1 : 0) << "face " << f;
      std::set<std::vector<int>> parts, drawn;
      const auto fromSmallest = [](std::vector<int> p)
      {
        std::rotate(p.begin(), std::min_element(p.begin(), p.end()), p.end());
        return p;
      };
      for (const auto& p : vbr::edgeConnectedPartsOf(brep, static_cast<int>(f)))
        parts.insert(fromSmallest(p));
      for (const auto& p : polygons)
        drawn.insert(fromSmallest(p));
      EXPECT_EQ(parts, drawn) << "face " << f;
    }
    EXPECT_EQ(plateFaces, 2);
  }
}

// The parts of faces merged at vertices (edgeConnectedPartsOf) against a flood fill of the
// face's pixels: as many parts as 4-connected components, the same areas, each part a
// counter-clockwise polygon that passes no corner twice. Random volumes and checkerboard
// plates, merged at vertices or not (a face that is not split yields no parts).
TEST(FanPolygons, PartsOfFacesAreTheirEdgeConnectedComponents)
{
  int split = 0, parts = 0;
  unsigned seed = 7300;
  for (int trial = 0; trial < 48; ++trial)
  {
    const bool merged = trial % 4 != 3;
    const vbr::Point3 d{ 3 + (trial * 5) % 10, 3 + (trial * 3) % 9, 1 + (trial * 7) % 6 };
    vbr::BitVolume v = bf::randomVolume(d, 0.2 + 0.6 * (trial % 7) / 6.0, seed++);
    if (trial % 6 == 0) // a checkerboard plate with a few voxels flipped
      for (int z = 0; z < d[2]; ++z)
        for (int y = 0; y < d[1]; ++y)
          for (int x = 0; x < d[0]; ++x)
            v.set(x, y, z, ((x + y + z) % 2 == 0) != (v.get(x, y, z) && (x * y + z) % 7 == 0));
    SCOPED_TRACE(testing::Message() << "trial " << trial << (merged ? " merged" : ""));
    vbr::BRep brep;
    ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(v),
      merged ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge,
      vbr::Execution(),
      brep));
    if (trial % 2 == 0)
      vbr::insertTJunctionVertices(brep);
    for (std::size_t f = 0; f < brep.faces.size(); ++f)
    {
      const std::vector<std::vector<int>> found = vbr::edgeConnectedPartsOf(brep, int(f));
      if (found.empty())
        continue;
      SCOPED_TRACE(testing::Message() << "face " << f);
      const vbr::BRepFace& face = brep.faces[f];
      const int u = (face.axis + 1) % 3, v2 = (face.axis + 2) % 3;
      std::vector<vbr::Point3> corner;
      for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
        for (const vbr::Point3& p : brep.loopPoints(l))
          corner.push_back(p);
      std::multiset<long long> partAreas, componentAreas;
      for (const std::vector<int>& part : found)
      {
        std::set<std::pair<int, int>> distinct;
        long long twice = 0;
        for (std::size_t i = 0; i < part.size(); ++i)
        {
          const vbr::Point3& p = corner[part[i]];
          const vbr::Point3& q = corner[part[(i + 1) % part.size()]];
          twice += static_cast<long long>(p[u]) * q[v2] - static_cast<long long>(q[u]) * p[v2];
          distinct.insert({ p[u], p[v2] });
        }
        EXPECT_EQ(distinct.size(), part.size()) << "a part passes a corner twice";
        EXPECT_GT(face.normalSign * twice, 0) << "a part turns clockwise";
        EXPECT_EQ(twice % 2, 0);
        partAreas.insert(face.normalSign * twice / 2);
      }
      for (const bf::PixelSet& c : bf::components(bf::rasterize(brep, int(f)), false))
        componentAreas.insert(static_cast<long long>(c.size()));
      EXPECT_EQ(partAreas, componentAreas);
      split += found.size() > 1;
      parts += static_cast<int>(found.size());
    }
  }
  RecordProperty("split", split);
  RecordProperty("parts", parts);
  EXPECT_GT(split, 30) << "too few faces split into parts to test";
  EXPECT_GT(parts, 300);
}

// Loops that are no rectangle for the test that spares rectangles the general apex search:
// each has four left turns or looks like a rectangle in some way, and a fan from its first
// left turn would draw it wrong (overlapping sides, a loop round twice) or it turns right.
TEST(FanPolygons, OnlyLoopsRoundARectangleSkipTheApexSearch)
{
  auto apexOf = [](const std::vector<P2>& loop)
  {
    std::vector<vbr::Point3> points;
    for (const P2& p : loop)
      points.push_back({ static_cast<vbr::Coord>(p[0]), static_cast<vbr::Coord>(p[1]), 0 });
    return vbr::detail::rectangleApexOf(
      vbr::PointRange{ points.data(), points.data() + points.size() }, 0, 1, 1);
  };
  EXPECT_EQ(apexOf({ { 0, 0 }, { 4, 0 }, { 4, 2 }, { 0, 2 } }), 0);
  EXPECT_EQ(apexOf({ { 2, 0 }, { 4, 0 }, { 4, 2 }, { 0, 2 }, { 0, 0 } }), 1);
  // Back and forth along the bottom side: four left turns, but its sides overlap.
  EXPECT_EQ(apexOf({ { 0, 0 }, { 3, 0 }, { 1, 0 }, { 4, 0 }, { 4, 2 }, { 0, 2 } }), -1);
  // A corner twice in a row.
  EXPECT_EQ(apexOf({ { 0, 0 }, { 4, 0 }, { 4, 0 }, { 4, 2 }, { 0, 2 } }), -1);
  // Round the rectangle twice: eight left turns.
  EXPECT_EQ(
    apexOf({ { 0, 0 }, { 4, 0 }, { 4, 2 }, { 0, 2 }, { 0, 0 }, { 4, 0 }, { 4, 2 }, { 0, 2 } }), -1);
  // An L: five left turns and a right one.
  EXPECT_EQ(apexOf({ { 0, 0 }, { 4, 0 }, { 4, 1 }, { 1, 1 }, { 1, 3 }, { 0, 3 } }), -1);
  // Clockwise: four right turns.
  EXPECT_EQ(apexOf({ { 0, 0 }, { 0, 2 }, { 4, 2 }, { 4, 0 } }), -1);
}

// A face whose loop goes round a rectangle with corners of neighbouring faces on its sides
// (most faces of porous volumes) is one polygon: the loop from its first corner that turns
// left (brute force on the loop's own coordinates), whichever corner the loop starts at and
// whichever way the face looks. Its triangles: n - 2 counter-clockwise ones, none flat, that
// add up to the rectangle's area.
TEST(FanPolygons, RectanglesWithCornersOnTheirSidesStartAtTheirFirstLeftTurn)
{
  unsigned seed = 9100;
  auto next = [&seed](unsigned m)
  {
    seed = seed * 1103515245u + 12345u;
    return static_cast<int>((seed >> 16) % m);
  };
  for (int trial = 0; trial < 400; ++trial)
  {
    const int w = 1 + next(9), h = 1 + next(9), x0 = next(20) - 10, y0 = next(20) - 10;
    // Counter-clockwise in (X, Y), the coordinates in which the face is seen from outside.
    std::vector<P2> loop =
      rectangleLoop(x0, y0, w, h, [&] { return trial % 4 != 0 && next(3) == 0; });
    const std::size_t n = loop.size(), shift = static_cast<std::size_t>(next(int(n)));
    std::rotate(loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(shift), loop.end());
    const vbr::BRep brep = faceOfLoop(loop, trial % 3, trial % 2 == 0 ? 1 : -1, 3);
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", " << n << " corners");

    std::size_t firstLeft = 0;
    while (cross(loop[(firstLeft + n - 1) % n], loop[firstLeft], loop[(firstLeft + 1) % n]) <= 0)
      ++firstLeft;
    std::vector<int> expected;
    for (std::size_t i = 0; i < n; ++i)
      expected.push_back(static_cast<int>((firstLeft + i) % n));
    const std::vector<std::vector<int>> polygons = vbr::fanPolygons(brep, 0);
    ASSERT_EQ(polygons.size(), 1u);
    EXPECT_EQ(polygons[0], expected);
    // The same apex from the rectangle's own test, without the general search.
    const vbr::PointRange points{ brep.points.data(), brep.points.data() + n };
    const vbr::BRepFace& face = brep.faces[0];
    EXPECT_EQ(vbr::detail::rectangleApexOf(
                points, (face.axis + 1) % 3, (face.axis + 2) % 3, face.normalSign),
      static_cast<int>(firstLeft));

    const std::vector<std::array<int, 3>> triangles = vbr::triangulateFace(brep, 0);
    ASSERT_EQ(triangles.size(), n - 2);
    Wide area = 0;
    for (const auto& t : triangles)
    {
      const Wide a = cross(loop[t[0]], loop[t[1]], loop[t[2]]);
      EXPECT_GT(a, 0);
      area += a;
    }
    EXPECT_TRUE(area == Wide(2) * w * h);
  }
}

namespace
{

/// Ear clipping by its definition, every corner of the ring scanned for every ear: from corner 0,
/// an ear is a corner that turns strictly left whose closed triangle holds no other corner of the
/// ring; after a cut the walk goes back to the corner before the ear; the last three corners are
/// the last triangle. Empty when a whole round finds no ear.
std::vector<std::array<int, 3>> bruteForceEars(const std::vector<P2>& loop)
{
  const int n = static_cast<int>(loop.size());
  std::vector<int> prev(n), next(n);
  std::vector<bool> alive(n, true);
  for (int i = 0; i < n; ++i)
  {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  auto isEar = [&](int a, int b, int c)
  {
    if (cross(loop[a], loop[b], loop[c]) <= 0)
      return false;
    for (int d = 0; d < n; ++d)
      if (alive[d] && d != a && d != b && d != c && cross(loop[a], loop[b], loop[d]) >= 0 &&
        cross(loop[b], loop[c], loop[d]) >= 0 && cross(loop[c], loop[a], loop[d]) >= 0)
        return false;
    return true;
  };
  std::vector<std::array<int, 3>> triangles;
  int b = 0, misses = 0, left = n;
  while (left > 3)
  {
    if (misses >= left)
      return {};
    const int a = prev[b], c = next[b];
    if (!isEar(a, b, c))
    {
      b = c;
      ++misses;
      continue;
    }
    triangles.push_back({ a, b, c });
    next[a] = c;
    prev[c] = a;
    alive[b] = false;
    --left;
    misses = 0;
    b = a;
  }
  triangles.push_back({ prev[b], b, next[b] });
  return triangles;
}

} // namespace

// The triangles of a face whose loop goes round a rectangle with corners of neighbouring faces on
// its sides are those of ear clipping by its definition (bruteForceEars), triangle for triangle:
// such loops skip the scan of the ring for every ear (the ring stays convex), which must not
// change a single triangle. Every corner of the loop's start and every orientation of the face.
TEST(FanPolygons, RectanglesWithCornersOnTheirSidesAreEarClippedAsByDefinition)
{
  unsigned seed = 4242;
  auto next = [&seed](unsigned m)
  {
    seed = seed * 1103515245u + 12345u;
    return static_cast<int>((seed >> 16) % m);
  };
  std::size_t checked = 0, checkedLong = 0;
  for (int trial = 0; trial < 600; ++trial)
  {
    const int w = 1 + next(12), h = 1 + next(12), x0 = next(20) - 10, y0 = next(20) - 10;
    const int density = 1 + next(4); // one corner in `density` points of the sides
    std::vector<P2> loop =
      rectangleLoop(x0, y0, w, h, [&] { return next(static_cast<unsigned>(density)) == 0; });
    const std::size_t n = loop.size(), shift = static_cast<std::size_t>(next(int(n)));
    std::rotate(loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(shift), loop.end());
    const vbr::BRep brep = faceOfLoop(loop, trial % 3, (trial / 3) % 2 == 0 ? 1 : -1, -2);
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", " << n << " corners");
    const std::vector<std::array<int, 3>> expected = bruteForceEars(loop);
    ASSERT_EQ(expected.size(), n - 2); // a convex loop always has an ear
    EXPECT_EQ(vbr::triangulateFace(brep, 0), expected);
    checked += n > 4;
    checkedLong += n > 32;
  }
  EXPECT_GT(checked, 500u);
  // Loops of more than 32 corners are clipped in arrays of their own, the shorter ones on the
  // stack (SmallRing): both ways checked.
  RecordProperty("long", static_cast<int>(checkedLong));
  EXPECT_GT(checkedLong, 20u);
}

// The triangles of every face without holes of up to 128 corners of random volumes (L shapes,
// stairs, loops that pass a corner twice; both connectivities, with and without T-junction
// vertices) are those of ear clipping by its definition (bruteForceEars), triangle for
// triangle, wherever the definition finds ears all round: the scans that simple loops skip
// (only the corners that do not turn left are tested against an ear) must not change one.
TEST(FanPolygons, SimpleLoopsAreEarClippedAsByDefinition)
{
  unsigned seed = 7300;
  std::size_t simple = 0, rectangles = 0;
  for (int trial = 0; trial < 48; ++trial)
  {
    const vbr::Point3 d{ 4 + (trial * 5) % 9, 4 + (trial * 3) % 7, 3 + (trial * 7) % 6 };
    const double density = 0.2 + 0.6 * (trial % 7) / 6.0;
    const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
    vbr::BRep brep;
    ASSERT_TRUE(sweptFaces(v, trial % 2 == 0, trial % 3 != 0, brep));
    for (std::size_t f = 0; f < brep.faces.size(); ++f)
    {
      const vbr::BRepFace& face = brep.faces[f];
      const vbr::PointRange pts = brep.loopPoints(face.firstLoop);
      if (face.loopCount != 1 || pts.size() > 128)
        continue;
      const int u = (face.axis + 1) % 3, v2 = (face.axis + 2) % 3;
      const int x = face.normalSign > 0 ? u : v2, y = face.normalSign > 0 ? v2 : u;
      std::vector<P2> loop;
      for (const vbr::Point3& p : pts)
        loop.push_back({ p[x], p[y] });
      SCOPED_TRACE(testing::Message()
        << "trial " << trial << ", face " << f << ", " << loop.size() << " corners");
      const std::vector<std::array<int, 3>> expected = bruteForceEars(loop);
      const std::vector<std::array<int, 3>> triangles =
        vbr::triangulateFace(brep, static_cast<int>(f));
      if (expected.empty())
      {
        // No ear somewhere by the definition: the general triangulation's, which must still
        // cover the face exactly (an ear wrongly found would leave a triangle sticking out).
        Wide area = 0, covered = 0;
        for (std::size_t i = 0; i < loop.size(); ++i)
          area += cross(P2{ 0, 0 }, loop[i], loop[(i + 1) % loop.size()]);
        for (const std::array<int, 3>& t : triangles)
        {
          const Wide a = cross(loop[t[0]], loop[t[1]], loop[t[2]]);
          EXPECT_GT(a, 0);
          covered += a;
        }
        EXPECT_TRUE(covered == area);
        continue;
      }
      EXPECT_EQ(triangles, expected);
      // The filter's path (appendTriangles, whose loops of four corners round a rectangle skip
      // the ear clipping): the same triangles, as one face.
      vbr::FaceCells cells;
      vbr::appendTriangles(brep, static_cast<int>(f), cells);
      std::vector<std::array<int, 3>> appended(cells.cellEnds.size());
      for (std::size_t t = 0; t < appended.size(); ++t)
        for (int k = 0; k < 3; ++k)
          appended[t][k] = cells.corners[3 * t + k];
      EXPECT_EQ(appended, expected);
      EXPECT_EQ(
        cells.faceEnds, std::vector<std::uint32_t>{ static_cast<std::uint32_t>(appended.size()) });
      rectangles += loop.size() == 4;
      // The loops that take the simple path: no corner twice, and not round a rectangle (a
      // corner that turns right).
      bool turnsRight = false;
      for (std::size_t i = 0; i < loop.size(); ++i)
        turnsRight = turnsRight ||
          cross(loop[(i + loop.size() - 1) % loop.size()], loop[i], loop[(i + 1) % loop.size()]) <
            0;
      simple += turnsRight && std::set<P2>(loop.begin(), loop.end()).size() == loop.size();
    }
  }
  RecordProperty("simple", static_cast<int>(simple));
  EXPECT_GT(simple, 300u);
  EXPECT_GT(rectangles, 300u);
}

namespace
{

/// A staircase counter-clockwise from the origin, its bottom-left corner: along x to (w, 0), then
/// `steps` steps up and to the left back to the y axis, down to the origin; a step of random
/// height and width, and a corner of a neighbouring face on the bottom side now and then.
std::vector<P2> staircase(int steps, const std::function<int(unsigned)>& next)
{
  std::vector<int> widths(static_cast<std::size_t>(steps));
  int w = 0;
  for (int& width : widths)
    w += width = 1 + next(3);
  std::vector<P2> loop{ { 0, 0 } };
  for (int x = 1; x < w; ++x)
    if (next(4) == 0)
      loop.push_back({ x, 0 });
  int x = w, y = 0;
  loop.push_back({ x, y });
  for (const int width : widths)
  {
    y += 1 + next(3);
    loop.push_back({ x, y });
    x -= width;
    loop.push_back({ x, y }); // after the last step x is 0: the y axis, above the origin
  }
  return loop;
}

} // namespace

// Ear clipping keeps loops of up to 32 corners on the stack (SmallRing) and longer ones in arrays
// of their own (EarCorners, ConvexRing); on staircases of 2 to 30 steps (6 to about 100
// corners), simple, and two of them touching at a corner (a loop that passes the corner twice),
// every start and orientation, the triangles are those of ear clipping by its definition
// (bruteForceEars) either way.
TEST(FanPolygons, StaircasesShortAndLongAreEarClippedAsByDefinition)
{
  unsigned seed = 515;
  const std::function<int(unsigned)> next = [&seed](unsigned m)
  {
    seed = seed * 1103515245u + 12345u;
    return static_cast<int>((seed >> 16) % m);
  };
  std::size_t shortLoops = 0, longLoops = 0;
  for (int trial = 0; trial < 240; ++trial)
  {
    std::vector<P2> loop = staircase(2 + next(29), next);
    if (trial % 2 == 1) // a second staircase turned half round, touching the first at the origin
      for (const P2& p : staircase(1 + next(12), next))
        loop.push_back({ -p[0], -p[1] });
    const std::size_t n = loop.size(), shift = static_cast<std::size_t>(next(int(n)));
    std::rotate(loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(shift), loop.end());
    const vbr::BRep brep = faceOfLoop(loop, trial % 3, (trial / 3) % 2 == 0 ? 1 : -1, 5);
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", " << n << " corners");
    const std::vector<std::array<int, 3>> expected = bruteForceEars(loop);
    if (expected.empty() || n > 128)
      continue; // no ear somewhere: not ear-clipped (SimpleLoopsAreEarClippedAsByDefinition)
    EXPECT_EQ(vbr::triangulateFace(brep, 0), expected);
    shortLoops += n <= 32;
    longLoops += n > 32;
  }
  EXPECT_GT(shortLoops, 40u);
  EXPECT_GT(longLoops, 40u);
}
