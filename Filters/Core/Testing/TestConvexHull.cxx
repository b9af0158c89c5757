// The exact convex hull against Qhull (libqhull_r, which merges coplanar facets by default and
// is exact on these small integer inputs) and against exact integer checks written here: every
// point on the inner side of every face plane, each face's corners on its plane and turning
// strictly left, each edge shared by two faces in opposite directions, V - E + F = 2.
#include "BruteForce.h"
#include "ConvexHull.h"

#include <gtest/gtest.h>

extern "C"
{
#include <libqhull_r/qhull_ra.h>
}

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

namespace
{

using vbr::LatticePoint;
using Facets = std::set<std::vector<LatticePoint>>;

struct Reference
{
  std::set<LatticePoint> vertices;
  Facets facets; ///< sorted corner sets
};

/// Qhull of the points in `dim` (2 or 3) of their coordinates (the first ones).
Reference qhullOf(const std::vector<LatticePoint>& points, int dim)
{
  std::vector<coordT> coords;
  for (const auto& p : points)
  {
    for (int k = 0; k < dim; ++k)
    {
      coords.push_back(static_cast<coordT>(p[k]));
    }
  }
  qhT qhStorage;
  qhT* qh = &qhStorage;
  static FILE* quiet = std::fopen("/dev/null", "w");
  qh_zero(qh, quiet);
  char options[] = "qhull";
  Reference ref;
  const int exitCode = qh_new_qhull(
    qh, dim, static_cast<int>(points.size()), coords.data(), False, options, nullptr, quiet);
  if (exitCode == 0)
  {
    facetT* facet;
    vertexT *vertex, **vertexp;
    FORALLfacets
    {
      std::vector<LatticePoint> corners;
      FOREACHvertex_(facet->vertices)
      {
        corners.push_back(points[qh_pointid(qh, vertex->point)]);
        ref.vertices.insert(corners.back());
      }
      std::sort(corners.begin(), corners.end());
      ref.facets.insert(corners);
    }
  }
  int curlong, totlong;
  qh_freeqhull(qh, !qh_ALL);
  qh_memfreeshort(qh, &curlong, &totlong);
  return ref;
}

LatticePoint minus(const LatticePoint& a, const LatticePoint& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

__int128 tripleProduct(const LatticePoint& n, const LatticePoint& a, const LatticePoint& b)
{
  const __int128 c0 = __int128(a[1]) * b[2] - __int128(a[2]) * b[1];
  const __int128 c1 = __int128(a[2]) * b[0] - __int128(a[0]) * b[2];
  const __int128 c2 = __int128(a[0]) * b[1] - __int128(a[1]) * b[0];
  return n[0] * c0 + n[1] * c1 + n[2] * c2;
}

/// n.p - d of a face plane, in 128 bits here (not the core's FacePlane::evaluate).
__int128 heightAbove(const vbr::FacePlane& plane, const LatticePoint& p)
{
  __int128 h = -__int128(plane.offset);
  for (int k = 0; k < 3; ++k)
    h += __int128(plane.normal[k]) * p[k];
  return h;
}

/// The cell list's incidences against its vertices and faces: every edge in the lists of its
/// two vertices and bounding the two faces edgeFaces gives it (in opposite directions), each
/// face's k-th edge from its k-th corner to the next, each vertex in the faces listing it.
void expectIncidences(const vbr::CellList& hull)
{
  ASSERT_EQ(hull.vertexEdges.size(), hull.vertices.size());
  ASSERT_EQ(hull.vertexFaces.size(), hull.vertices.size());
  ASSERT_EQ(hull.edgeFaces.size(), hull.edges.size());
  ASSERT_EQ(hull.faceEdges.size(), hull.faces.size());
  const auto has = [](const std::vector<std::uint32_t>& list, std::uint32_t x)
  { return std::find(list.begin(), list.end(), x) != list.end(); };
  std::size_t vertexFaceCount = 0;
  for (std::size_t f = 0; f < hull.faces.size(); ++f)
  {
    const auto& v = hull.faces[f];
    ASSERT_EQ(hull.faceEdges[f].size(), v.size());
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const std::uint32_t a = v[k], b = v[(k + 1) % v.size()], e = hull.faceEdges[f][k];
      ASSERT_LT(e, hull.edges.size());
      EXPECT_EQ(hull.edges[e], (std::array<std::uint32_t, 2>{ std::min(a, b), std::max(a, b) }));
      // the face listed first is the one where the edge runs from its lower vertex
      EXPECT_EQ(hull.edgeFaces[e][a < b ? 0 : 1], f) << "edge " << e << " of face " << f;
      EXPECT_TRUE(has(hull.vertexFaces[a], static_cast<std::uint32_t>(f)));
    }
    vertexFaceCount += v.size();
  }
  std::size_t listed = 0;
  for (const auto& faces : hull.vertexFaces)
    listed += faces.size();
  EXPECT_EQ(listed, vertexFaceCount) << "a vertex lists a face it is not in";
  for (std::size_t e = 0; e < hull.edges.size(); ++e)
  {
    EXPECT_TRUE(has(hull.vertexEdges[hull.edges[e][0]], static_cast<std::uint32_t>(e)));
    EXPECT_TRUE(has(hull.vertexEdges[hull.edges[e][1]], static_cast<std::uint32_t>(e)));
  }
  std::size_t vertexEdgeCount = 0;
  for (const auto& edges : hull.vertexEdges)
    vertexEdgeCount += edges.size();
  EXPECT_EQ(vertexEdgeCount, 2 * hull.edges.size()) << "a vertex lists an edge it is not on";
}

/// The exact checks of a solid hull, with no reference but the points.
void expectValidSolid(const vbr::CellList& hull, const std::vector<LatticePoint>& points)
{
  ASSERT_EQ(hull.dimension, 3);
  ASSERT_EQ(hull.faces.size(), hull.planes.size());
  for (std::size_t f = 0; f < hull.faces.size(); ++f)
  {
    const auto& v = hull.faces[f];
    const auto& n = hull.planes[f].normal;
    ASSERT_GE(v.size(), 3u);
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const LatticePoint& a = hull.vertices[v[k]];
      const LatticePoint& b = hull.vertices[v[(k + 1) % v.size()]];
      const LatticePoint& c = hull.vertices[v[(k + 2) % v.size()]];
      EXPECT_TRUE(heightAbove(hull.planes[f], a) == 0) << "corner off its face plane";
      EXPECT_GT(tripleProduct(n, minus(b, a), minus(c, b)), 0) << "corner not turning left";
    }
    for (const auto& p : points)
    {
      ASSERT_TRUE(heightAbove(hull.planes[f], p) <= 0) << "a point outside face " << f;
    }
  }
  for (std::size_t f = 0; f < hull.faces.size(); ++f)
  {
    for (std::size_t g = f + 1; g < hull.faces.size(); ++g)
    {
      EXPECT_FALSE(hull.planes[f] == hull.planes[g]) << "two faces on one plane";
    }
  }
  for (const auto& ef : hull.edgeFaces)
  {
    EXPECT_NE(ef[0], std::uint32_t(-1));
    EXPECT_NE(ef[1], std::uint32_t(-1));
    EXPECT_NE(ef[0], ef[1]);
  }
  EXPECT_EQ(static_cast<long>(hull.vertices.size()) - static_cast<long>(hull.edges.size()) +
      static_cast<long>(hull.faces.size()),
    2);
  expectIncidences(hull);
}

Facets facetsOf(const vbr::CellList& hull)
{
  Facets facets;
  for (const auto& v : hull.faces)
  {
    std::vector<LatticePoint> corners;
    for (auto id : v)
    {
      corners.push_back(hull.vertices[id]);
    }
    std::sort(corners.begin(), corners.end());
    facets.insert(corners);
  }
  return facets;
}

/// The faces as cycles of coordinates, each starting at its smallest corner (order kept).
std::set<std::vector<LatticePoint>> cyclesOf(const vbr::CellList& hull)
{
  std::set<std::vector<LatticePoint>> cycles;
  for (const auto& v : hull.faces)
  {
    std::vector<LatticePoint> c;
    for (auto id : v)
    {
      c.push_back(hull.vertices[id]);
    }
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    cycles.insert(c);
  }
  return cycles;
}

/// Our hull of `points` in all three variants against Qhull of `reference` (the same convex
/// set: the points, or all voxel centres when `points` are the candidates).
void expectLikeQhull(const std::vector<LatticePoint>& points,
  const std::vector<LatticePoint>& reference)
{
  const Reference ref = qhullOf(reference, 3);
  ASSERT_FALSE(ref.vertices.empty()) << "Qhull failed";
  const vbr::CellList hull = vbr::convexHull(points);
  expectValidSolid(hull, reference);
  const std::set<LatticePoint> vertices(hull.vertices.begin(), hull.vertices.end());
  EXPECT_EQ(vertices, ref.vertices);
  EXPECT_EQ(hull.faces.size(), ref.facets.size());
  EXPECT_EQ(facetsOf(hull), ref.facets);
  const vbr::CellList unmerged = vbr::convexHull(points, vbr::CoplanarFaces::Extension, false);
  EXPECT_EQ(cyclesOf(unmerged), cyclesOf(hull)) << "the extension method left faces to merge";
  for (auto variant : { vbr::CoplanarFaces::Visible, vbr::CoplanarFaces::Invisible })
  {
    const vbr::CellList triangles = vbr::convexHull(points, variant, false);
    for (const auto& face : triangles.faces)
    {
      EXPECT_EQ(face.size(), 3u);
    }
    EXPECT_EQ(cyclesOf(vbr::convexHull(points, variant)), cyclesOf(hull));
  }
}

std::vector<LatticePoint> objectCentres(const vbr::BitVolume& v)
{
  std::vector<LatticePoint> centres;
  for (std::int32_t z = 0; z < v.size(2); ++z)
    for (std::int32_t y = 0; y < v.size(1); ++y)
      for (std::int32_t x = 0; x < v.size(0); ++x)
        if (v.get(x, y, z))
          centres.push_back({ x, y, z });
  return centres;
}

std::vector<LatticePoint> randomPoints(std::mt19937& rng, int count, int extent)
{
  std::uniform_int_distribution<int> c(0, extent - 1);
  std::vector<LatticePoint> points;
  for (int i = 0; i < count; ++i)
  {
    points.push_back({ c(rng), c(rng), c(rng) });
  }
  return points;
}

vbr::BitVolume ball(int radius, LatticePoint centreTimes2)
{
  const int n = 2 * radius + 3;
  vbr::BitVolume v(n, n, n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        const long dx = 2 * x - centreTimes2[0], dy = 2 * y - centreTimes2[1],
                   dz = 2 * z - centreTimes2[2];
        if (dx * dx + dy * dy + dz * dz <= 4L * radius * radius)
          v.set(x, y, z);
      }
  return v;
}

} // namespace

TEST(ConvexHull, RandomLatticePointsMatchQhull)
{
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 300; ++trial)
  {
    const int extent = 2 + trial % 40;
    const int count = 5 + static_cast<int>(rng() % 200);
    const auto points = randomPoints(rng, count, extent);
    if (qhullOf(points, 3).vertices.empty())
    {
      continue;
    }
    SCOPED_TRACE(trial);
    expectLikeQhull(points, points);
  }
}

TEST(ConvexHull, CandidatesOfRandomVolumesSpanTheHullOfAllCentres)
{
  unsigned seed = 1;
  for (int trial = 0; trial < 200; ++trial)
  {
    const vbr::Point3 d{ 3 + trial % 13, 2 + (trial * 7) % 11, 2 + (trial * 5) % 9 };
    const double density = 0.05 + 0.1 * (trial % 9);
    const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
    const auto centres = objectCentres(v);
    const auto candidates = vbr::vertexCandidates(v);
    if (centres.size() < 4 || qhullOf(centres, 3).vertices.empty())
    {
      continue;
    }
    SCOPED_TRACE(trial);
    EXPECT_TRUE(std::is_sorted(candidates.begin(), candidates.end()));
    expectLikeQhull(candidates, centres);
  }
}

TEST(ConvexHull, LargeVolumesUpTo64Cubed)
{
  unsigned seed = 100;
  for (int trial = 0; trial < 6; ++trial)
  {
    const vbr::BitVolume v = bf::randomVolume({ 64, 64, 64 }, 0.02 + 0.15 * trial, seed++);
    const auto centres = objectCentres(v);
    expectLikeQhull(vbr::vertexCandidates(v), centres);
  }
  for (int r : { 5, 12, 20, 31 })
  {
    const vbr::BitVolume b = ball(r, { 2 * r + 2, 2 * r + 3, 2 * r + 2 });
    SCOPED_TRACE(r);
    expectLikeQhull(vbr::vertexCandidates(b), objectCentres(b));
  }
}

TEST(ConvexHull, RotatedCubeHasSixFaces)
{
  // The corners of a cube with edge vectors (3, 4, 0), (-4, 3, 0), (0, 0, 5) and every
  // lattice point inside it: six faces, eight vertices.
  std::vector<LatticePoint> points;
  for (int x = -10; x <= 10; ++x)
    for (int y = -10; y <= 10; ++y)
      for (int z = 0; z <= 5; ++z)
      {
        const long u = 3L * x + 4L * y, w = -4L * x + 3L * y;
        if (u >= 0 && u <= 25 && w >= 0 && w <= 25)
          points.push_back({ x, y, z });
      }
  const vbr::CellList hull = vbr::convexHull(points);
  expectValidSolid(hull, points);
  EXPECT_EQ(hull.faces.size(), 6u);
  EXPECT_EQ(hull.vertices.size(), 8u);
  expectLikeQhull(points, points);
}

TEST(ConvexHull, FlatInputs)
{
  std::mt19937 rng(7);
  // Empty, one point (repeated), two points, collinear rows (axis and diagonal).
  EXPECT_EQ(vbr::convexHull({}).dimension, -1);
  const vbr::CellList one = vbr::convexHull({ { 3, 4, 5 }, { 3, 4, 5 } });
  EXPECT_EQ(one.dimension, 0);
  ASSERT_EQ(one.vertices.size(), 1u);
  EXPECT_TRUE(vbr::hullContains(one, { 3, 4, 5 }));
  for (const LatticePoint step : { LatticePoint{ 1, 0, 0 }, LatticePoint{ 2, -1, 3 } })
  {
    std::vector<LatticePoint> row;
    for (int k : { 5, 0, 3, 9, 1 })
      row.push_back({ 10 + k * step[0], 10 + k * step[1], 10 + k * step[2] });
    const vbr::CellList segment = vbr::convexHull(row);
    ASSERT_EQ(segment.dimension, 1);
    EXPECT_EQ(std::set<LatticePoint>(segment.vertices.begin(), segment.vertices.end()),
      (std::set<LatticePoint>{ row[1], row[3] }));
    EXPECT_EQ(segment.edges.size(), 1u);
    EXPECT_TRUE(vbr::hullContains(segment, row[2]));
    EXPECT_FALSE(vbr::hullContains(segment, { 10 + step[1], 10 + step[0], 10 }));
  }
  // Coplanar sets: on z = 4 and on the tilted plane x + 2y - z = 0; the reference is Qhull
  // in the (x, y) coordinates, which map the plane one to one.
  for (int trial = 0; trial < 100; ++trial)
  {
    auto points = randomPoints(rng, 3 + trial % 60, 2 + trial % 20);
    for (auto& p : points)
      p[2] = trial % 2 ? 4 : p[0] + 2 * p[1];
    const Reference ref = qhullOf(points, 2);
    if (ref.vertices.size() < 3)
      continue;
    SCOPED_TRACE(trial);
    const vbr::CellList hull = vbr::convexHull(points);
    ASSERT_EQ(hull.dimension, 2);
    ASSERT_EQ(hull.faces.size(), 2u);
    EXPECT_EQ(std::set<LatticePoint>(hull.vertices.begin(), hull.vertices.end()), ref.vertices);
    EXPECT_EQ(hull.edges.size(), hull.vertices.size());
    EXPECT_EQ(
      hull.faces[0], std::vector<std::uint32_t>(hull.faces[1].rbegin(), hull.faces[1].rend()));
    for (const auto& p : points)
    {
      EXPECT_EQ(hull.planes[0].evaluate(p), 0);
      EXPECT_TRUE(vbr::hullContains(hull, p));
    }
    EXPECT_FALSE(vbr::hullContains(hull, { points[0][0], points[0][1], points[0][2] + 1 }));
  }
}
