// Standard-plane recognition against a brute-force search of normals, and the
// polyhedrization against independent checks: plane inequalities evaluated here, faces that
// are disks (Euler characteristic and one boundary loop), a partition of the surfels counted
// voxel by voxel, and the reversion back to the same voxels.
#include "BruteForce.h"
#include "PolygonTriangulator.h"
#include "Polyhedrization.h"
#include "StandardPlane.h"
#include "StandardPlaneColumns.h"
#include "SurfelGraph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{

using vbr::Point3;

/// A face's outline as the reversion reads it: its plane and its loop's pointels.
vbr::FaceOutline outlineOf(const vbr::StandardFace& face, const vbr::SurfelGraph& g)
{
  vbr::FaceOutline outline;
  outline.plane = face.plane;
  for (std::uint32_t u : face.loop)
    outline.loop.push_back(g.vertexPointel[u]);
  return outline;
}

/// The outlines of all faces of p, in face order.
std::vector<vbr::FaceOutline> outlinesOf(const vbr::Polyhedron& p, const vbr::SurfelGraph& g)
{
  std::vector<vbr::FaceOutline> outlines;
  for (const vbr::StandardFace& f : p.faces)
    outlines.push_back(outlineOf(f, g));
  return outlines;
}

/// Whether some normal with |n|_1 <= bound fits the points with the orientations asked.
bool bruteForcePlane(const std::vector<Point3>& points, const std::array<int, 3>& signs, int bound)
{
  for (int a = -bound; a <= bound; ++a)
    for (int b = -bound; b <= bound; ++b)
      for (int c = -bound; c <= bound; ++c)
      {
        const int omega = std::abs(a) + std::abs(b) + std::abs(c);
        if (omega == 0 || omega > bound)
          continue;
        const int n[3] = { a, b, c };
        bool oriented = true;
        for (int d = 0; d < 3; ++d)
          oriented = oriented && (signs[d] == 0 || signs[d] * n[d] > 0);
        if (!oriented)
          continue;
        long lo = 0, hi = 0;
        for (std::size_t i = 0; i < points.size(); ++i)
        {
          const long v = long(a) * points[i][0] + long(b) * points[i][1] + long(c) * points[i][2];
          lo = i == 0 ? v : std::min(lo, v);
          hi = i == 0 ? v : std::max(hi, v);
        }
        if (hi - lo < omega)
          return true;
      }
  return false;
}

/// The smallest omega <= bound of a normal that fits the points with the orientations asked,
/// level by level over every integer normal; 0 when there is none.
int bruteForceOmega(const std::vector<Point3>& points, const std::array<int, 3>& signs, int bound)
{
  for (int omega = 1; omega <= bound; ++omega)
    for (int a = -omega; a <= omega; ++a)
      for (int b = std::abs(a) - omega; b <= omega - std::abs(a); ++b)
        for (int c : { omega - std::abs(a) - std::abs(b), std::abs(a) + std::abs(b) - omega })
        {
          const int n[3] = { a, b, c };
          bool oriented = true;
          for (int d = 0; d < 3; ++d)
            oriented = oriented && (signs[d] == 0 || signs[d] * n[d] > 0);
          long lo = 0, hi = 0;
          for (std::size_t i = 0; i < points.size() && oriented; ++i)
          {
            const long v = long(a) * points[i][0] + long(b) * points[i][1] + long(c) * points[i][2];
            lo = i == 0 ? v : std::min(lo, v);
            hi = i == 0 ? v : std::max(hi, v);
          }
          if (oriented && hi - lo < omega)
            return omega;
          if (c == 0)
            break; // one normal, not two
        }
  return 0;
}

/// mu <= a x + b y + c z < mu + |a| + |b| + |c|, evaluated here.
bool inPlane(const vbr::StandardPlane& p, const Point3& q)
{
  const long v = long(p.normal[0]) * q[0] + long(p.normal[1]) * q[1] + long(p.normal[2]) * q[2];
  const long omega =
    std::labs(long(p.normal[0])) + std::labs(long(p.normal[1])) + std::labs(long(p.normal[2]));
  return p.mu <= v && v < p.mu + omega;
}

/// Surfels counted voxel by voxel: selected voxel faces whose neighbour is not selected.
std::size_t countBoundaryFaces(const vbr::BitVolume& v)
{
  auto in = [&](int x, int y, int z)
  {
    return x >= 0 && y >= 0 && z >= 0 && x < v.size(0) && y < v.size(1) && z < v.size(2) &&
      v.get(x, y, z);
  };
  std::size_t count = 0;
  for (int z = 0; z < v.size(2); ++z)
    for (int y = 0; y < v.size(1); ++y)
      for (int x = 0; x < v.size(0); ++x)
        if (in(x, y, z))
          count += !in(x - 1, y, z) + !in(x + 1, y, z) + !in(x, y - 1, z) + !in(x, y + 1, z) +
            !in(x, y, z - 1) + !in(x, y, z + 1);
  return count;
}

/// Every property of a polyhedrization of v, checked without the code under test.
void checkPolyhedron(const vbr::BitVolume& v,
  const vbr::SurfelGraph& g,
  const vbr::Polyhedron& p,
  const vbr::PolyhedrizationOptions& options = {})
{
  ASSERT_EQ(g.size(), countBoundaryFaces(v));
  // A partition of the surfels.
  std::vector<int> owners(g.size(), 0);
  for (std::size_t f = 0; f < p.faces.size(); ++f)
    for (std::uint32_t s : p.faces[f].surfels)
    {
      ++owners[s];
      EXPECT_EQ(p.faceOfSurfel[s], f);
    }
  EXPECT_EQ(std::count(owners.begin(), owners.end(), 1), static_cast<long>(g.size()))
    << "a surfel is in no face or in several";
  std::vector<vbr::FaceOutline> outlines;
  for (std::size_t f = 0; f < p.faces.size(); ++f)
  {
    const vbr::StandardFace& face = p.faces[f];
    SCOPED_TRACE("face " + std::to_string(f));
    if (options.maximumFaceSize)
      EXPECT_LE(face.surfels.size(), options.maximumFaceSize);
    // Pointels in the plane, normal towards the outside of every surfel.
    std::set<std::uint32_t> vertices;
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    std::size_t outside = 0, misoriented = 0;
    for (std::uint32_t s : face.surfels)
    {
      const auto& sf = g.surfels[s];
      misoriented += sf.sign() * face.plane.normal[sf.axis()] <= 0;
      for (int k = 0; k < 4; ++k)
      {
        outside += !inPlane(face.plane, sf.corner(k));
        const std::uint32_t a = g.vertexOf(s, k), b = g.vertexOf(s, (k + 1) % 4);
        vertices.insert(a);
        edges.insert(std::minmax(a, b));
      }
    }
    EXPECT_EQ(outside, 0u) << "pointels outside the face's standard plane";
    EXPECT_EQ(misoriented, 0u) << "surfels facing away from the plane's normal";
    // A disk: Euler characteristic 1 and one boundary loop through every boundary edge.
    const long euler = long(vertices.size()) - long(edges.size()) + long(face.surfels.size());
    EXPECT_EQ(euler, 1) << "not a disk";
    std::size_t boundaryEdges = 0;
    for (std::uint32_t s : face.surfels)
      for (int k = 0; k < 4; ++k)
        boundaryEdges += p.faceOfSurfel[g.neighbourOf(s, k)] != f;
    EXPECT_EQ(face.loop.size(), boundaryEdges) << "boundary is not one loop";
    EXPECT_EQ(std::set<std::uint32_t>(face.loop.begin(), face.loop.end()).size(), face.loop.size())
      << "loop visits a vertex twice";
    outlines.push_back(outlineOf(face, g));
  }
  // Faces around each vertex: the distinct faces of the surfels with that vertex as a corner.
  std::vector<std::set<std::uint32_t>> facesAround(g.vertexPointel.size());
  for (std::uint32_t s = 0; s < g.size(); ++s)
    for (int k = 0; k < 4; ++k)
      facesAround[g.vertexOf(s, k)].insert(p.faceOfSurfel[s]);
  ASSERT_EQ(p.facesAtVertex.size(), facesAround.size());
  std::size_t miscounted = 0;
  for (std::size_t v = 0; v < facesAround.size(); ++v)
    miscounted += p.facesAtVertex[v] != std::min<std::size_t>(facesAround[v].size(), 255);
  EXPECT_EQ(miscounted, 0u) << "vertices whose count of faces around is wrong";
  // Reversion from the planes and loops alone.
  std::size_t surfels = 0;
  vbr::BitVolume back;
  EXPECT_EQ(vbr::revert(outlines, v.dims(), back, vbr::Execution(), &surfels), "");
  EXPECT_EQ(surfels, g.size());
  EXPECT_TRUE(back == v) << "the reversion gives other voxels";
}

void polyhedrizeAndCheck(const vbr::BitVolume& v, const vbr::PolyhedrizationOptions& options = {})
{
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  vbr::Polyhedron p;
  ASSERT_TRUE(vbr::polyhedrize(g, options, vbr::Execution(), p));
  checkPolyhedron(v, g, p, options);
}

vbr::BitVolume ball(int radiusSquared)
{
  int r = 0;
  while (r * r <= radiusSquared)
    ++r;
  const int n = 2 * r + 3, c = n / 2;
  vbr::BitVolume v(n, n, n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        if ((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c) <= radiusSquared)
          v.set(x, y, z);
  return v;
}

} // namespace

TEST(StandardPlane, AgreesWithBruteForce)
{
  std::mt19937 rng(11);
  int feasible = 0, checked = 0;
  for (int t = 0; t < 3000; ++t)
  {
    std::vector<Point3> points;
    const int m = 1 + int(rng() % 9);
    for (int i = 0; i < m; ++i)
      points.push_back({ int(rng() % 5) - 2, int(rng() % 5) - 2, int(rng() % 4) });
    std::array<int, 3> signs{ 0, 0, 0 };
    for (int d = 0; d < 3; ++d)
      signs[d] = int(rng() % 5) == 0 ? 1 : (int(rng() % 5) == 0 ? -1 : 0);
    vbr::StandardPlaneRecognizer r;
    bool all = true;
    for (std::size_t i = 0; i < points.size() && all; ++i)
      all = r.tryAdd({ points[i] }, i == 0 ? signs : std::array<int, 3>{ 0, 0, 0 });
    const bool expected = bruteForcePlane(points, signs, 14);
    if (all)
    {
      ++feasible;
      for (const Point3& q : points)
        ASSERT_TRUE(inPlane(r.plane(), q)) << "point outside the plane returned";
      for (int d = 0; d < 3; ++d)
        ASSERT_TRUE(signs[d] == 0 || signs[d] * r.plane().normal[d] > 0);
      if (expected) // the smallest omega: no bigger than the brute force's
        EXPECT_TRUE(bruteForcePlane(points, signs, int(r.plane().omega())));
    }
    else
    {
      EXPECT_FALSE(expected) << "a plane exists but was not found (trial " << t << ")";
    }
    ++checked;
  }
  EXPECT_GT(feasible, 300);
  EXPECT_LT(feasible, checked - 300);
}

// Points the caller marks as added already (tryAdd's known bits) are not looked up: the same
// answers and planes as with every point looked up, on random calls of 4 points, with the bits of
// the points a set of the points accepted so far holds.
TEST(StandardPlane, KnownPointsGiveTheSameAnswers)
{
  std::mt19937 rng(5);
  std::size_t marked = 0, accepted = 0;
  for (int t = 0; t < 300; ++t)
  {
    vbr::StandardPlaneRecognizer told, plain;
    std::set<std::array<int, 3>> added;
    const std::array<int, 3> signs{ 1, 0, 0 };
    for (int call = 0; call < 12; ++call)
    {
      std::array<Point3, 4> points;
      std::uint32_t known = 0;
      for (int i = 0; i < 4; ++i)
      {
        points[i] = { int(rng() % 3), int(rng() % 6), int(rng() % 6) };
        if (added.count(points[i]) && rng() % 2)
          known |= 1u << i;
      }
      marked += known != 0;
      const bool a = told.tryAdd(points.data(), 4, signs, known);
      const bool b = plain.tryAdd(points.data(), 4, signs);
      ASSERT_EQ(a, b) << "trial " << t << " call " << call;
      if (!a)
        continue;
      ++accepted;
      added.insert(points.begin(), points.end());
      ASSERT_EQ(told.plane().normal, plain.plane().normal);
      ASSERT_EQ(told.plane().mu, plain.plane().mu);
      ASSERT_EQ(told.pointCount(), plain.pointCount());
    }
  }
  EXPECT_GT(marked, 300u);
  EXPECT_GT(accepted, 600u);
}

// Two points that differ by a sign vector sigma have width exactly |n|_1 for every normal n of
// octant sigma, which tryAdd excludes at once: it finds the pair among a call's new points
// (scanned when they are few, searched when many) or between a new point and an accepted one.
// Against brute force, on calls of 1 to 4 and of 9 to 20 points, a third of them moved to a
// diagonal neighbour of another: an exclusion found where there is no pair refuses a plane that
// exists, or gives a larger omega.
TEST(StandardPlane, DiagonalPairsAgreeWithBruteForce)
{
  std::mt19937 rng(23);
  constexpr int Bound = 8;
  int accepted = 0, refused = 0, large = 0;
  for (int t = 0; t < 500; ++t)
  {
    vbr::StandardPlaneRecognizer r;
    std::vector<Point3> all;
    const std::array<int, 3> signs{ 0, 0, rng() % 2 ? 1 : 0 };
    for (int call = 0; call < 4; ++call)
    {
      std::vector<Point3> points;
      const int m = rng() % 2 ? 1 + int(rng() % 4) : 9 + int(rng() % 12);
      for (int i = 0; i < m; ++i)
      {
        Point3 p{ int(rng() % 7) - 3, int(rng() % 7) - 3, int(rng() % 2) };
        if (!points.empty() && rng() % 4 == 0)
          p = points[rng() % points.size()];
        else if (!all.empty() && rng() % 3 == 0)
          p = all[rng() % all.size()];
        if (rng() % 3 == 0)
          for (int d = 0; d < 3; ++d)
            p[d] += rng() % 2 ? 1 : -1;
        points.push_back(p);
      }
      std::vector<Point3> with = all;
      with.insert(with.end(), points.begin(), points.end());
      const int omega = bruteForceOmega(with, signs, Bound);
      const bool taken = r.tryAdd(points, signs);
      if (!taken)
      {
        ++refused;
        ASSERT_EQ(omega, 0) << "a plane exists but was refused (trial " << t << ", call " << call
                            << ")";
        continue;
      }
      ++accepted;
      large += m > 8;
      all = with;
      for (const Point3& q : all)
        ASSERT_TRUE(inPlane(r.plane(), q)) << "point outside the plane returned";
      if (omega != 0)
        ASSERT_EQ(r.plane().omega(), omega) << "not the smallest omega (trial " << t << ")";
    }
  }
  EXPECT_GT(accepted, 300);
  EXPECT_GT(refused, 300);
  EXPECT_GT(large, 50);
}

// The exclusion itself: with the orientations of one octant asked, a pair differing by its sign
// vector is refused before any clip, whether the pair is a new point and an accepted one, two new
// points of a call of two (scanned) or two of a call of twelve (searched).
TEST(StandardPlane, DiagonalPairsAreRefusedBeforeClipping)
{
  for (int s = 0; s < 8; ++s)
  {
    const std::array<int, 3> sigma{ s & 1 ? -1 : 1, s & 2 ? -1 : 1, s & 4 ? -1 : 1 };
    const Point3 p{ 3, -2, 5 };
    const Point3 q{ p[0] + sigma[0], p[1] + sigma[1], p[2] + sigma[2] };
    vbr::StandardPlaneRecognizer accepted;
    ASSERT_TRUE(accepted.tryAdd({ p }, sigma));
    const std::size_t clips = accepted.clipCount();
    EXPECT_FALSE(accepted.tryAdd({ q }, sigma));
    EXPECT_EQ(accepted.clipCount(), clips) << "octant " << s << ": clipped after an accepted p";
    vbr::StandardPlaneRecognizer two;
    EXPECT_FALSE(two.tryAdd({ q, p }, sigma));
    EXPECT_EQ(two.clipCount(), 0u) << "octant " << s << ": clipped in a call of two";
    std::vector<Point3> twelve;
    for (int i = 0; i < 10; ++i)
      twelve.push_back({ p[0] + 7 * i - 30, p[1] - 7 * sigma[2] * i, p[2] + 9 * sigma[0] * i });
    twelve.insert(twelve.begin() + 4, q);
    twelve.insert(twelve.begin() + 9, p);
    vbr::StandardPlaneRecognizer many;
    EXPECT_FALSE(many.tryAdd(twelve, sigma));
    EXPECT_EQ(many.clipCount(), 0u) << "octant " << s << ": clipped in a call of twelve";
  }
}

TEST(StandardPlane, SmallestOmegaOnThinStrips)
{
  // Points added one by one along thin strips (a digital segment of a random direction and a
  // neighbouring one), whose polygons of normals are long and thin in directions the search
  // frame must find, and random sets: after every call, the recognizer's feasibility and
  // omega against every integer normal of omega <= Bound (such small sets have their smallest
  // omega far below the recognizer's limit, so a refusal means no plane at all).
  constexpr int Bound = 28;
  std::mt19937 rng(23);
  int accepted = 0, refused = 0, large = 0;
  for (int t = 0; t < 400; ++t)
  {
    std::vector<Point3> candidates;
    if (t % 4 == 3)
      for (int i = 0; i < 10; ++i)
        candidates.push_back({ int(rng() % 7) - 3, int(rng() % 7) - 3, int(rng() % 4) });
    else
    {
      std::array<int, 3> dir{ int(rng() % 11) - 5, int(rng() % 11) - 5, int(rng() % 11) - 5 };
      const int den = 2 + int(rng() % 7);
      const std::array<int, 3> side{ int(rng() % 3) - 1, int(rng() % 3) - 1, int(rng() % 3) - 1 };
      for (int i = 0; i < 14; ++i)
      {
        Point3 q;
        for (int d = 0; d < 3; ++d)
          q[d] = int(std::floor(double(i * dir[d]) / den + 0.5)) + (i % 2) * side[d];
        candidates.push_back(q);
      }
      std::shuffle(candidates.begin(), candidates.end(), rng);
    }
    std::array<int, 3> signs{ 0, 0, 0 };
    signs[rng() % 3] = rng() % 2 ? 1 : -1;
    vbr::StandardPlaneRecognizer r;
    std::vector<Point3> points;
    for (const Point3& q : candidates)
    {
      std::vector<Point3> with = points;
      with.push_back(q);
      const int expected = bruteForceOmega(with, signs, Bound);
      const bool added = r.tryAdd({ q }, signs);
      SCOPED_TRACE("trial " + std::to_string(t) + ", point " + std::to_string(with.size()));
      if (!added)
      {
        ++refused;
        EXPECT_EQ(expected, 0) << "a plane of omega " << expected << " exists but was refused";
        continue;
      }
      ++accepted;
      points = with;
      const vbr::StandardPlane& plane = r.plane();
      for (const Point3& p : points)
        ASSERT_TRUE(inPlane(plane, p)) << "point outside the plane returned";
      for (int d = 0; d < 3; ++d)
        ASSERT_TRUE(signs[d] == 0 || signs[d] * plane.normal[d] > 0) << "wrong orientation";
      if (expected == 0)
      {
        EXPECT_GT(plane.omega(), Bound) << "a plane the exhaustive search missed";
        ++large;
      }
      else
        EXPECT_EQ(plane.omega(), expected) << "not the smallest omega";
    }
  }
  EXPECT_GT(accepted, 1500);
  EXPECT_GT(refused, 200);
  RecordProperty("omega above the bound", large);
}

/// The normal the recognizer promises, by brute force over every integer normal of |n|_1 <=
/// bound that fits the points with the orientations asked: the smallest omega, then the first
/// octant holding it (octant s has n_x < 0 when bit 0 of s is set, n_y < 0 for bit 1, n_z < 0
/// for bit 2; a zero component lies in the octant of the positive sign, the earlier one), then
/// the smallest (n_x, n_y). {0, 0, 0} when none fits.
std::array<std::int64_t, 3> bruteForceNormal(const std::vector<Point3>& points,
  const std::array<int, 3>& signs,
  int bound)
{
  for (int omega = 1; omega <= bound; ++omega)
  {
    bool found = false;
    std::array<int, 3> bestKey{ 0, 0, 0 };
    std::array<std::int64_t, 3> best{ 0, 0, 0 };
    for (int a = -omega; a <= omega; ++a)
      for (int b = std::abs(a) - omega; b <= omega - std::abs(a); ++b)
        for (int c : { omega - std::abs(a) - std::abs(b), std::abs(a) + std::abs(b) - omega })
        {
          const int n[3] = { a, b, c };
          bool fits = true;
          for (int d = 0; d < 3; ++d)
            fits = fits && (signs[d] == 0 || signs[d] * n[d] > 0);
          long lo = 0, hi = 0;
          for (std::size_t i = 0; i < points.size() && fits; ++i)
          {
            const long v = long(a) * points[i][0] + long(b) * points[i][1] + long(c) * points[i][2];
            lo = i == 0 ? v : std::min(lo, v);
            hi = i == 0 ? v : std::max(hi, v);
          }
          fits = fits && hi - lo < omega;
          const std::array<int, 3> key{ (a < 0) + 2 * (b < 0) + 4 * (c < 0), a, b };
          if (fits && (!found || key < bestKey))
          {
            found = true;
            bestKey = key;
            best = { a, b, c };
          }
          if (c == 0)
            break; // one normal, not two
        }
    if (found)
      return best;
  }
  return { 0, 0, 0 };
}

TEST(StandardPlane, ChosenNormalIsTheFirstInOrder)
{
  // Calls of 1 to 4 points (the growth adds a surfel's new corners, the merging whole faces)
  // with an orientation each, along thin strips and in random boxes, so that calls are taken by
  // the current plane, need a new normal, or are refused, in every order: the octants are
  // clipped lazily, some only when a later call searches them, and a refused call must leave
  // them as they were. After every call, the plane must be exactly the brute force's first
  // normal (not only its omega), and its offset the smallest value over the points.
  constexpr int Bound = 24;
  std::mt19937 rng(71);
  int accepted = 0, refused = 0, multiPoint = 0, large = 0;
  for (int t = 0; t < 300; ++t)
  {
    std::vector<Point3> candidates;
    if (t % 3 == 2)
      for (int i = 0; i < 12; ++i)
        candidates.push_back({ int(rng() % 6) - 3, int(rng() % 6) - 3, int(rng() % 3) });
    else
    {
      const std::array<int, 3> dir{ int(rng() % 9) - 4, int(rng() % 9) - 4, int(rng() % 9) - 4 };
      const int den = 2 + int(rng() % 6);
      const std::array<int, 3> side{ int(rng() % 3) - 1, int(rng() % 3) - 1, int(rng() % 3) - 1 };
      for (int i = 0; i < 16; ++i)
      {
        Point3 q;
        for (int d = 0; d < 3; ++d)
          q[d] = int(std::floor(double(i * dir[d]) / den + 0.5)) + (i % 3 == 1) * side[d];
        candidates.push_back(q);
      }
      std::shuffle(candidates.begin() + 2, candidates.end(), rng);
    }
    vbr::StandardPlaneRecognizer r;
    std::vector<Point3> points;
    std::array<int, 3> present{ 0, 0, 0 };
    for (std::size_t i = 0; i < candidates.size();)
    {
      const std::size_t count = std::min<std::size_t>(1 + rng() % 4, candidates.size() - i);
      const std::vector<Point3> call(candidates.begin() + i, candidates.begin() + i + count);
      i += count;
      std::array<int, 3> signs{ 0, 0, 0 };
      if (rng() % 3 == 0)
        signs[rng() % 3] = rng() % 2 ? 1 : -1;
      std::array<int, 3> asked = present;
      bool opposite = false;
      for (int d = 0; d < 3; ++d)
        if (signs[d] != 0)
        {
          opposite = opposite || asked[d] == -signs[d];
          asked[d] = signs[d];
        }
      std::vector<Point3> with = points;
      with.insert(with.end(), call.begin(), call.end());
      const std::array<std::int64_t, 3> expected =
        opposite ? std::array<std::int64_t, 3>{ 0, 0, 0 } : bruteForceNormal(with, asked, Bound);
      const bool none = expected == std::array<std::int64_t, 3>{ 0, 0, 0 };
      SCOPED_TRACE("trial " + std::to_string(t) + ", point " + std::to_string(i));
      if (!r.tryAdd(call, signs))
      {
        ++refused;
        EXPECT_TRUE(none) << "a plane exists but the call was refused";
        continue;
      }
      ++accepted;
      multiPoint += count > 1;
      points = with;
      present = asked;
      const vbr::StandardPlane& plane = r.plane();
      long lo = 0;
      for (std::size_t j = 0; j < points.size(); ++j)
      {
        const long v = long(plane.value(points[j]));
        lo = j == 0 ? v : std::min(lo, v);
      }
      EXPECT_EQ(plane.mu, lo) << "the offset is not the smallest value over the points";
      if (none)
      {
        EXPECT_GT(plane.omega(), Bound) << "a plane the exhaustive search missed";
        ++large;
        continue;
      }
      EXPECT_EQ(plane.normal, expected) << "not the first normal in order";
    }
  }
  EXPECT_GT(accepted, 1000);
  EXPECT_GT(refused, 300);
  EXPECT_GT(multiPoint, 500);
  RecordProperty("omega above the bound", large);
}

TEST(StandardPlane, LargePiecesAgreeWithBruteForce)
{
  // Pieces of standard planes of 121 to 363 points, added one by one (in random order or row
  // by row), then probes near them. Faces of 128 points or more measure only the points that
  // are not the midpoint of two others (StandardPlane.h); the answers must stay those of every
  // integer normal of omega <= Bound over all the points.
  constexpr int Bound = 12, R = 5;
  std::mt19937 rng(5);
  int accepted = 0, refused = 0;
  std::size_t siftedOut = 0;
  for (int t = 0; t < 16; ++t)
  {
    std::array<int, 3> n{ 0, 0, 0 };
    while (std::gcd(std::gcd(n[0], n[1]), n[2]) != 1)
      for (int& c : n)
        c = int(rng() % 7) - 3;
    const int omega = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
    int m = 0; // the dominant axis: the piece is a graph over the other two
    for (int d = 1; d < 3; ++d)
      m = std::abs(n[d]) > std::abs(n[m]) ? d : m;
    const int mu = int(rng() % omega);
    auto point = [&](int u, int v, int w)
    {
      Point3 p;
      p[m] = w, p[(m + 1) % 3] = u, p[(m + 2) % 3] = v;
      return p;
    };
    auto value = [&](const Point3& p) { return n[0] * p[0] + n[1] * p[1] + n[2] * p[2]; };
    std::vector<Point3> piece;
    for (int u = -R; u <= R; ++u)
      for (int v = -R; v <= R; ++v)
        for (int w = -25; w <= 25; ++w)
          if (mu <= value(point(u, v, w)) && value(point(u, v, w)) < mu + omega)
            piece.push_back(point(u, v, w));
    if (t % 2)
      std::shuffle(piece.begin(), piece.end(), rng);
    std::array<int, 3> signs{ 0, 0, 0 };
    signs[m] = n[m] > 0 ? 1 : -1;
    vbr::StandardPlaneRecognizer r;
    for (const Point3& q : piece)
      ASSERT_TRUE(r.tryAdd({ q }, signs)) << "a point of the piece refused (trial " << t << ")";
    ASSERT_EQ(r.plane().omega(), bruteForceOmega(piece, signs, Bound));
    for (int probe = 0; probe < 16; ++probe)
    {
      // Near the piece: a column of it, shifted by up to 2 along the dominant axis.
      const int u = int(rng() % (2 * R + 3)) - R - 1, v = int(rng() % (2 * R + 3)) - R - 1;
      int w = -25;
      while (value(point(u, v, w)) * signs[m] < mu * signs[m] && w < 25)
        ++w;
      const Point3 q = point(u, v, w + int(rng() % 5) - 2);
      std::vector<Point3> with = piece;
      with.push_back(q);
      const int expected = bruteForceOmega(with, signs, Bound);
      SCOPED_TRACE("trial " + std::to_string(t) + ", probe " + std::to_string(probe));
      if (!r.tryAdd({ q }, signs))
      {
        ++refused;
        EXPECT_EQ(expected, 0) << "a plane of omega " << expected << " exists but was refused";
        continue;
      }
      ++accepted;
      piece = with;
      for (const Point3& p : piece)
        ASSERT_TRUE(inPlane(r.plane(), p)) << "point outside the plane returned";
      if (expected == 0)
        EXPECT_GT(r.plane().omega(), Bound) << "a plane the exhaustive search missed";
      else
        EXPECT_EQ(r.plane().omega(), expected) << "not the smallest omega";
    }
    siftedOut += r.siftedOutCount(); // the probes' slow paths sift the piece
  }
  EXPECT_GT(accepted, 30);
  EXPECT_GT(refused, 30);
  EXPECT_GT(siftedOut, 1000u) << "the probes never met a face that measures its extremes only";
}

TEST(StandardPlane, PaperUmbrellaAndCube)
{
  // The umbrella of one voxel at the origin (outward -x, -y, -z): the paper's plane
  // 0 <= x + y + z < 3, oriented out of the voxel.
  vbr::StandardPlaneRecognizer r;
  ASSERT_TRUE(r.tryAdd(
    { { 0, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0, 1, 1 }, { 1, 0, 0 }, { 1, 0, 1 }, { 1, 1, 0 } },
    { -1, -1, -1 }));
  EXPECT_EQ(r.plane().normal, (std::array<std::int64_t, 3>{ -1, -1, -1 }));
  EXPECT_EQ(r.plane().mu, -2);
  // The opposite corner joins no plane of that orientation, and nothing changes.
  EXPECT_FALSE(r.tryAdd({ { 1, 1, 1 } }, { 0, 0, 0 }));
  EXPECT_FALSE(r.tryAdd({ { 0, 0, 2 } }, { 1, 0, 0 }));
  EXPECT_EQ(r.pointCount(), 7u);
  EXPECT_EQ(r.plane().omega(), 3);
}

TEST(StandardPlane, DigitalPlanesAreRecognized)
{
  // Pointels of standard planes of random normals over a patch: always one plane, of the
  // same or a smaller omega.
  std::mt19937 rng(5);
  for (int t = 0; t < 200; ++t)
  {
    const std::array<int, 3> n{ int(rng() % 9) - 4, int(rng() % 9) - 4, 1 + int(rng() % 6) };
    const int omega = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
    const int mu = int(rng() % 7) - 3;
    std::vector<Point3> points;
    for (int x = -6; x <= 6; ++x)
      for (int y = -6; y <= 6; ++y)
        for (int z = -40; z <= 40; ++z)
        {
          const int v = n[0] * x + n[1] * y + n[2] * z;
          if (mu <= v && v < mu + omega)
            points.push_back({ x, y, z });
        }
    vbr::StandardPlaneRecognizer r;
    std::shuffle(points.begin(), points.end(), rng);
    bool all = true;
    for (std::size_t i = 0; i < points.size() && all; i += 7)
    {
      std::vector<Point3> chunk(
        points.begin() + i, points.begin() + std::min(points.size(), i + 7));
      all = r.tryAdd(chunk, { 0, 0, 1 });
    }
    ASSERT_TRUE(all) << "plane " << n[0] << " " << n[1] << " " << n[2];
    EXPECT_LE(r.plane().omega(), omega);
    for (const Point3& q : points)
      ASSERT_TRUE(inPlane(r.plane(), q));
  }
}

namespace
{

/// A frame form as StandardPlaneRecognizer::FrameForm: along * t + across * k + level * omega
/// >= 0 (> 0 when strict).
struct ColumnForm
{
  std::int64_t along, across, level;
  bool strict;
};

bool columnFormHolds(const ColumnForm& F, vbr::Wide k, std::int64_t omega, vbr::Wide t)
{
  const vbr::Wide value =
    vbr::Wide(F.along) * t + vbr::Wide(F.across) * k + vbr::Wide(F.level) * omega;
  return F.strict ? value > 0 : value >= 0;
}

/// rangeOfT's answer written from the definition: per form the first (last) t that holds,
/// found by stepping from a truncated quotient, clamped to +-2^62 as rangeOfT's.
/// Empty ranges are told by `empty` only (rangeOfT's bounds then are any tLo > tHi).
void referenceRangeOfT(const std::vector<ColumnForm>& forms,
  std::int64_t omega,
  vbr::Wide k,
  bool& empty,
  vbr::Wide& lo,
  vbr::Wide& hi)
{
  const vbr::Wide Far = vbr::Wide(1) << 62;
  lo = -Far, hi = Far;
  empty = false;
  for (const ColumnForm& F : forms)
  {
    const vbr::Wide A = F.along, B = vbr::Wide(F.across) * k + vbr::Wide(F.level) * omega;
    if (A == 0)
    {
      empty = empty || !columnFormHolds(F, k, omega, 0);
      continue;
    }
    // From the truncated quotient, out of the half-line of t that hold, then back to its end:
    // the first t that holds (A > 0) or the last one (A < 0).
    const vbr::Wide step = A > 0 ? 1 : -1;
    vbr::Wide t = -B / A;
    while (columnFormHolds(F, k, omega, t))
      t -= step;
    while (!columnFormHolds(F, k, omega, t))
      t += step;
    if (A > 0)
      lo = std::max(lo, t);
    else
      hi = std::min(hi, t);
  }
  empty = empty || lo > hi;
}

vbr::Wide randomWide(std::mt19937_64& rng, vbr::Wide lo, vbr::Wide hi)
{
  const auto span = static_cast<unsigned __int128>(hi - lo) + 1;
  const auto r = (static_cast<unsigned __int128>(rng()) << 64) | rng();
  return lo + static_cast<vbr::Wide>(span == 0 ? r : r % span);
}

} // namespace

// levelColumns: kLo is the least k with k minDen >= omega minNum and kHi the greatest with
// k maxDen <= omega maxNum (checked by those products in Wide, no division), on both sides
// of its 64-bit path's bounds (|numerators| < 2^40, omega <= MaximumOmega).
TEST(StandardPlaneColumns, LevelColumnsAreTheExactQuotients)
{
  using vbr::Wide;
  std::mt19937_64 rng(20261207);
  const std::int64_t Small = std::int64_t(1) << 40;
  std::size_t narrow = 0, wide = 0;
  for (int i = 0; i < 200000; ++i)
  {
    auto numerator = [&]() -> std::int64_t
    {
      switch (rng() % 4)
      {
        case 0:
          return std::int64_t(randomWide(rng, -(1 << 20), 1 << 20));
        case 1:
          return std::int64_t(randomWide(rng, -Small - 1000, -Small + 1000));
        case 2:
          return std::int64_t(randomWide(rng, Small - 1000, Small + 1000));
        default:
          return std::int64_t(randomWide(rng, -(Wide(1) << 60), Wide(1) << 60));
      }
    };
    auto denominator = [&]() -> std::int64_t
    { return std::int64_t(randomWide(rng, 1, rng() % 2 ? 1000 : (Wide(1) << 40))); };
    vbr::detail::ColumnRange range;
    range.minNum = numerator(), range.minDen = denominator();
    range.maxNum = numerator(), range.maxDen = denominator();
    const std::int64_t omega = rng() % 3 == 0
      ? std::int64_t(randomWide(rng, vbr::detail::MaximumOmega - 2, vbr::detail::MaximumOmega + 2))
      : std::int64_t(randomWide(rng, 1, rng() % 2 ? 64 : (Wide(1) << 24)));
    Wide kLo = 0, kHi = 0;
    vbr::detail::levelColumns(range, omega, kLo, kHi);
    const bool isNarrow = omega <= vbr::detail::MaximumOmega && std::llabs(range.minNum) < Small &&
      std::llabs(range.maxNum) < Small;
    ++(isNarrow ? narrow : wide);
    const Wide lowest = Wide(omega) * range.minNum, highest = Wide(omega) * range.maxNum;
    ASSERT_TRUE(kLo * range.minDen >= lowest && (kLo - 1) * range.minDen < lowest)
      << "kLo " << double(kLo) << " minNum " << range.minNum << " minDen " << range.minDen
      << " omega " << omega << (isNarrow ? " (64 bits)" : " (Wide)");
    ASSERT_TRUE(kHi * range.maxDen <= highest && (kHi + 1) * range.maxDen > highest)
      << "kHi " << double(kHi) << " maxNum " << range.maxNum << " maxDen " << range.maxDen
      << " omega " << omega << (isNarrow ? " (64 bits)" : " (Wide)");
  }
  EXPECT_GT(narrow, 20000u);
  EXPECT_GT(wide, 20000u);
}

// rangeOfT on small forms: [tLo, tHi] is the set of t of a scan that hold every form (strict
// ones strictly), in both overloads (std::int64_t and Wide k).
TEST(StandardPlaneColumns, RangeOfTIsTheScannedRange)
{
  std::mt19937_64 rng(7);
  const std::int64_t Far = std::int64_t(1) << 62, Window = 2200;
  std::size_t nonEmpty = 0, strictDecided = 0;
  for (int i = 0; i < 3000; ++i)
  {
    std::vector<ColumnForm> forms(1 + rng() % 6);
    for (ColumnForm& F : forms)
      F = { std::int64_t(rng() % 4 == 0 ? 0 : std::int64_t(rng() % 41) - 20),
        std::int64_t(rng() % 41) - 20,
        std::int64_t(rng() % 41) - 20,
        rng() % 2 == 0 };
    const std::int64_t omega = 1 + std::int64_t(rng() % 50);
    const std::int64_t k = std::int64_t(rng() % 101) - 50;
    std::int64_t tLo, tHi, wLo, wHi;
    vbr::detail::rangeOfT(forms, omega, k, tLo, tHi);
    vbr::detail::rangeOfT(forms, omega, vbr::Wide(k), wLo, wHi);
    for (std::int64_t t = -Window; t <= Window; ++t)
    {
      bool holds = true, holdsLoosely = true;
      for (const ColumnForm& F : forms)
      {
        holds = holds && columnFormHolds(F, k, omega, t);
        holdsLoosely =
          holdsLoosely && columnFormHolds({ F.along, F.across, F.level, false }, k, omega, t);
      }
      strictDecided += holds != holdsLoosely;
      ASSERT_EQ(holds, tLo <= t && t <= tHi) << "t " << t << " in [" << tLo << ", " << tHi << "]";
      ASSERT_EQ(holds, wLo <= t && t <= wHi)
        << "t " << t << " in [" << wLo << ", " << wHi << "] (Wide)";
    }
    if (tLo <= tHi) // the bounds are in the window or unbounded
    {
      ++nonEmpty;
      EXPECT_TRUE(tLo == -Far || tLo > -Window);
      EXPECT_TRUE(tHi == Far || tHi < Window);
      EXPECT_EQ(tLo, wLo);
      EXPECT_EQ(tHi, wHi);
    }
    else
      EXPECT_GT(wLo, wHi);
  }
  EXPECT_GT(nonEmpty, 300u);
  EXPECT_GT(strictDecided, 300u);
}

// rangeOfT on large forms (frame coefficients up to 2^39 as frameForms makes them), k beyond
// SmallColumn (2^20) and omega beyond MaximumOmega, negative ones included: the Wide overload
// equals the reference from the definition, and the std::int64_t one equals both wherever
// searchColumns takes it (|k| and omega below 2^20).
TEST(StandardPlaneColumns, RangeOfTOverloadsAgreeOnLargeForms)
{
  using vbr::Wide;
  std::mt19937_64 rng(11);
  const std::int64_t SmallColumn = std::int64_t(1) << 20;
  std::size_t narrow = 0, nonEmpty = 0;
  for (int i = 0; i < 100000; ++i)
  {
    const Wide Coefficient = Wide(1) << (rng() % 2 ? 39 : 8);
    std::vector<ColumnForm> forms(1 + rng() % 6);
    for (ColumnForm& F : forms)
      F = { rng() % 8 == 0 ? 0 : std::int64_t(randomWide(rng, -Coefficient, Coefficient)),
        std::int64_t(randomWide(rng, -Coefficient, Coefficient)),
        std::int64_t(randomWide(rng, -(1 << 18), 1 << 18)),
        rng() % 2 == 0 };
    const bool small = rng() % 2 == 0;
    const std::int64_t omega =
      std::int64_t(randomWide(rng, 1, small ? SmallColumn - 1 : (Wide(1) << 24)));
    const Wide k = small ? randomWide(rng, -SmallColumn + 1, SmallColumn - 1)
                         : randomWide(rng, -(Wide(1) << 22), Wide(1) << 22);
    bool empty;
    Wide lo, hi;
    referenceRangeOfT(forms, omega, k, empty, lo, hi);
    std::int64_t wLo, wHi;
    vbr::detail::rangeOfT(forms, omega, k, wLo, wHi);
    ASSERT_EQ(empty, wLo > wHi) << "k " << double(k) << " omega " << omega;
    if (!empty)
    {
      ++nonEmpty;
      ASSERT_EQ(Wide(wLo), lo) << "k " << double(k) << " omega " << omega;
      ASSERT_EQ(Wide(wHi), hi) << "k " << double(k) << " omega " << omega;
    }
    if (-SmallColumn < k && k < SmallColumn && omega < SmallColumn)
    {
      ++narrow;
      std::int64_t tLo, tHi;
      vbr::detail::rangeOfT(forms, omega, std::int64_t(k), tLo, tHi);
      ASSERT_EQ(empty, tLo > tHi) << "k " << double(k) << " omega " << omega;
      if (!empty)
      {
        ASSERT_EQ(tLo, wLo);
        ASSERT_EQ(tHi, wHi);
      }
    }
  }
  EXPECT_GT(narrow, 20000u);
  EXPECT_GT(nonEmpty, 1000u);
}

TEST(Polyhedrization, RandomVolumes)
{
  unsigned seed = 700;
  const vbr::Point3 sizes[] = {
    { 1, 1, 1 }, { 3, 2, 4 }, { 6, 6, 6 }, { 9, 5, 7 }, { 12, 12, 12 }
  };
  for (const auto& d : sizes)
    for (double density : { 0.1, 0.3, 0.5, 0.7, 0.9 })
    {
      SCOPED_TRACE("seed " + std::to_string(seed));
      const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
      polyhedrizeAndCheck(v);
      vbr::PolyhedrizationOptions merged;
      merged.mergeFaces = true;
      merged.mergeFacesUpTo = 1000;
      polyhedrizeAndCheck(v, merged);
    }
  // A volume where a surfel moves to a larger face and back: listed once in the end.
  const char* const backAndForth =
    "010111111101111111111011111111111101110110111111101011111111110111111011110101110111"
    "111011011011101111000111101111101111101111110101111111111111111111011111111001011111"
    "111011011110111100111011111101110111011111100111111111110110111111110101111101100111"
    "111110111111110111111111110111111111101111110111111101101111111001111101111110111011";
  vbr::BitVolume v(7, 6, 8);
  for (int i = 0; i < 7 * 6 * 8; ++i)
    if (backAndForth[i] == '1')
      v.set(i % 7, (i / 7) % 6, i / 42);
  polyhedrizeAndCheck(v);
  // Many small volumes: surfels moving between faces and back.
  std::mt19937 rng(17);
  for (int t = 0; t < 500; ++t)
  {
    const vbr::Point3 d{ 3 + int(rng() % 7), 3 + int(rng() % 7), 3 + int(rng() % 7) };
    SCOPED_TRACE("small volume " + std::to_string(t));
    polyhedrizeAndCheck(bf::randomVolume(d, 0.2 + 0.1 * (t % 7), 900 + t));
  }
}

namespace
{

/// Whether two polyhedrizations are the same: every face in the same place, with the same
/// surfels in the same order, plane, loop and faces across; the same counts.
void expectSamePolyhedron(const vbr::Polyhedron& a, const vbr::Polyhedron& b)
{
  ASSERT_EQ(a.faces.size(), b.faces.size());
  EXPECT_EQ(a.faceOfSurfel, b.faceOfSurfel);
  EXPECT_EQ(a.facesAtVertex, b.facesAtVertex);
  EXPECT_EQ(a.mergedFaces, b.mergedFaces);
  EXPECT_EQ(a.movedSurfels, b.movedSurfels);
  for (std::size_t f = 0; f < a.faces.size(); ++f)
  {
    const vbr::StandardFace &p = a.faces[f], &q = b.faces[f];
    ASSERT_EQ(p.surfels, q.surfels) << "face " << f;
    ASSERT_EQ(p.loop, q.loop) << "face " << f;
    ASSERT_EQ(a.across(f), b.across(f)) << "face " << f;
    ASSERT_EQ(p.plane.normal, q.plane.normal) << "face " << f;
    ASSERT_EQ(p.plane.mu, q.plane.mu) << "face " << f;
  }
}

} // namespace

// The growth of boundary components on several threads gives the sequential growth's faces
// exactly, with every option (the merging reads the refusals the growth left), on inputs of
// many components (noise, scattered balls, a checkerboard) and of one large component next
// to small ones; and the faces are still checked independently.
TEST(Polyhedrization, ThreadsGiveTheSequentialFaces)
{
  std::vector<vbr::BitVolume> inputs;
  for (unsigned seed : { 31u, 32u, 33u })
    inputs.push_back(bf::randomVolume({ 18, 16, 16 }, 0.3 + 0.1 * (seed - 31), seed));
  vbr::BitVolume checker(14, 14, 14), shell(30, 30, 30);
  for (int z = 0; z < 14; ++z)
    for (int y = 0; y < 14; ++y)
      for (int x = 0; x < 14; ++x)
        checker.set(x, y, z, (x + y + z) % 2 == 0);
  // A hollow ball (two components: outside and cavity) with small cubes around it.
  std::mt19937 rng(5);
  for (int z = 0; z < 30; ++z)
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 30; ++x)
      {
        const int r2 = (x - 15) * (x - 15) + (y - 15) * (y - 15) + (z - 15) * (z - 15);
        shell.set(x, y, z, (r2 >= 36 && r2 <= 100) || (r2 > 150 && (x & y & z & 2) && rng() % 3));
      }
  inputs.push_back(checker);
  inputs.push_back(shell);
  std::vector<vbr::PolyhedrizationOptions> settings(4);
  settings[1].mergeFaces = true;
  settings[2].moveToLargerFaces = false;
  settings[3].maximumFaceSize = 12;
  settings[3].maximumDepth = 3;
  settings[3].mergeFaces = true;
  for (std::size_t i = 0; i < inputs.size(); ++i)
  {
    SCOPED_TRACE("input " + std::to_string(i));
    vbr::SurfelGraph g;
    ASSERT_TRUE(vbr::buildSurfelGraph(inputs[i], vbr::Execution(), g));
    ASSERT_GE(g.size(), 4096u) << "below the threaded growth's minimum";
    ASSERT_GT(g.componentCount, 2u);
    for (std::size_t o = 0; o < settings.size(); ++o)
    {
      SCOPED_TRACE("options " + std::to_string(o));
      vbr::Polyhedron sequential;
      ASSERT_TRUE(vbr::polyhedrize(g, settings[o], vbr::Execution(), sequential));
      for (int threads : { 1, 2, 5 })
      {
        SCOPED_TRACE(std::to_string(threads) + " threads");
        vbr::Polyhedron threaded;
        ASSERT_TRUE(vbr::polyhedrize(g, settings[o], bf::threadedExecution(threads), threaded));
        expectSamePolyhedron(sequential, threaded);
      }
      if (o == 1)
        checkPolyhedron(inputs[i], g, sequential, settings[o]);
    }
  }
  // The surfel graph on threads (its stages split over the surfels past 2^15 of them): the
  // same arrays as on one thread.
  const vbr::BitVolume large = bf::randomVolume({ 40, 36, 34 }, 0.5, 41);
  vbr::SurfelGraph one, several;
  ASSERT_TRUE(vbr::buildSurfelGraph(large, vbr::Execution(), one));
  ASSERT_TRUE(vbr::buildSurfelGraph(large, bf::threadedExecution(3), several));
  ASSERT_GT(one.size(), std::size_t(1) << 15);
  EXPECT_EQ(one.neighbour, several.neighbour);
  EXPECT_EQ(one.vertex, several.vertex);
  EXPECT_EQ(one.componentCount, several.componentCount);
  // Aborted on every thread: no faces claimed finished.
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(inputs[0], vbr::Execution(), g));
  vbr::Execution stop = bf::threadedExecution(2);
  stop.aborted = [] { return true; };
  vbr::Polyhedron p;
  EXPECT_FALSE(vbr::polyhedrize(g, {}, stop, p));
  // Only an abort within the threaded growth leaves no faces gathered (a later phase's poll
  // would stop a growth that ran to its end, after gathering them).
  EXPECT_TRUE(p.faces.empty()) << "the threaded growth did not stop";
  // The threaded growth reports its progress (between its waves, on the calling thread), and
  // an abort asked there stops it within the growth.
  const std::thread::id caller = std::this_thread::get_id();
  bool offThread = false, stopped = false;
  double highest = 0.0;
  vbr::Execution watched = bf::threadedExecution(2);
  watched.progress = [&](double f)
  {
    offThread = offThread || std::this_thread::get_id() != caller;
    highest = std::max(highest, f);
    stopped = stopped || (f > 0.0 && f < 0.6);
    return !stopped;
  };
  EXPECT_FALSE(vbr::polyhedrize(g, {}, watched, p));
  EXPECT_TRUE(stopped) << "no progress inside the growth";
  EXPECT_LT(highest, 0.6);
  EXPECT_FALSE(offThread) << "progress reported off the calling thread";
}

TEST(Polyhedrization, DegenerateAndNonManifold)
{
  polyhedrizeAndCheck(vbr::BitVolume(4, 4, 4)); // empty
  vbr::BitVolume full(5, 4, 3);
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x)
        full.set(x, y, z);
  polyhedrizeAndCheck(full);

  // One voxel: six surfels in two umbrellas of x + y + z, as the paper says.
  vbr::BitVolume one(1, 1, 1);
  one.set(0, 0, 0);
  vbr::SurfelGraph g;
  vbr::buildSurfelGraph(one, vbr::Execution(), g);
  vbr::Polyhedron p;
  vbr::polyhedrize(g, {}, vbr::Execution(), p);
  ASSERT_EQ(p.faces.size(), 2u);
  for (const auto& face : p.faces)
  {
    EXPECT_EQ(face.surfels.size(), 3u);
    EXPECT_EQ(std::abs(face.plane.normal[0]) + std::abs(face.plane.normal[1]) +
        std::abs(face.plane.normal[2]),
      3);
  }
  checkPolyhedron(one, g, p);

  // Voxels touching along an edge and at a corner only: two boundary components each.
  for (const auto& other : { vbr::Point3{ 1, 1, 0 }, vbr::Point3{ 1, 1, 1 } })
  {
    vbr::BitVolume v(2, 2, 2);
    v.set(0, 0, 0);
    v.set(other[0], other[1], other[2]);
    vbr::SurfelGraph pair;
    vbr::buildSurfelGraph(v, vbr::Execution(), pair);
    EXPECT_EQ(pair.componentCount, 2u);
    EXPECT_EQ(pair.size(), 12u);
    polyhedrizeAndCheck(v);
  }
  // Thin plates and a checkerboard, full of non-manifold edges.
  vbr::BitVolume plate(9, 7, 1), checker(6, 6, 6);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x)
      plate.set(x, y, 0);
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 6; ++x)
        if ((x + y + z) % 2 == 0)
          checker.set(x, y, z);
  polyhedrizeAndCheck(plate);
  polyhedrizeAndCheck(checker);
}

TEST(Polyhedrization, TorusAndPorousBlobs)
{
  // A torus (a handle: genus 1) and a porous union of balls (cavities, tunnels, many
  // boundary components).
  vbr::BitVolume torus(40, 40, 16), blobs(32, 32, 32);
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x)
      {
        const double r = std::hypot(x - 19.5, y - 19.5) - 12.0;
        if (r * r + (z - 7.5) * (z - 7.5) <= 25.0)
          torus.set(x, y, z);
      }
  std::mt19937 rng(8);
  for (int b = 0; b < 60; ++b)
  {
    const int cx = int(rng() % 32), cy = int(rng() % 32), cz = int(rng() % 32);
    for (int z = 0; z < 32; ++z)
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
          if ((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) <= 12)
            blobs.set(x, y, z);
  }
  polyhedrizeAndCheck(torus);
  polyhedrizeAndCheck(blobs);
  vbr::PolyhedrizationOptions merged;
  merged.mergeFaces = true;
  polyhedrizeAndCheck(blobs, merged);
}

TEST(Polyhedrization, PaperSphere)
{
  // Voxels with integer centres x^2 + y^2 + z^2 <= 240: the paper's 4,494 surfels, and
  // fewer faces than its 135.
  const vbr::BitVolume v = ball(240);
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  EXPECT_EQ(g.size(), 4494u);
  EXPECT_EQ(g.componentCount, 1u);
  vbr::Polyhedron p;
  ASSERT_TRUE(vbr::polyhedrize(g, {}, vbr::Execution(), p));
  EXPECT_LE(p.faces.size(), 120u);
  std::size_t largest = 0;
  for (const auto& f : p.faces)
    largest = std::max(largest, f.surfels.size());
  RecordProperty("faces", static_cast<int>(p.faces.size()));
  RecordProperty("largest", static_cast<int>(largest));
  checkPolyhedron(v, g, p);
}

TEST(Polyhedrization, PaperHexahedron)
{
  // A box turned about two axes, |n_i . centre| <= h_i: the paper's 1,962 surfels; it got 11
  // faces, the growth alone gives 31 here, the move to larger faces 13, merging 9.
  const int normals[3][3] = { { 2, 2, 1 }, { -2, 1, 2 }, { 1, -2, 2 } };
  const int half[3] = { 17, 17, 29 };
  vbr::BitVolume v(33, 33, 33);
  for (int z = 0; z < 33; ++z)
    for (int y = 0; y < 33; ++y)
      for (int x = 0; x < 33; ++x)
      {
        bool inside = true;
        for (int i = 0; i < 3; ++i)
          inside = inside &&
            std::abs(normals[i][0] * (x - 16) + normals[i][1] * (y - 16) +
              normals[i][2] * (z - 16)) <= half[i];
        if (inside)
          v.set(x, y, z);
      }
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  EXPECT_EQ(g.size(), 1962u);
  vbr::PolyhedrizationOptions merged;
  merged.mergeFaces = true;
  vbr::Polyhedron p;
  ASSERT_TRUE(vbr::polyhedrize(g, merged, vbr::Execution(), p));
  EXPECT_LE(p.faces.size(), 11u);
  checkPolyhedron(v, g, p, merged);
}

TEST(Polyhedrization, DigitalPlaneIsOneFace)
{
  // The voxels of a box below the plane 2x + 3y + 7z = 60 (by their centres): the surfels
  // between a voxel below and one above (not the box's walls) form one face of that plane.
  const std::array<int, 3> n{ 2, 3, 7 };
  vbr::BitVolume v(16, 16, 16);
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x)
        if (n[0] * (2 * x + 1) + n[1] * (2 * y + 1) + n[2] * (2 * z + 1) < 2 * 60)
          v.set(x, y, z);
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  vbr::Polyhedron p;
  ASSERT_TRUE(vbr::polyhedrize(g, {}, vbr::Execution(), p));
  checkPolyhedron(v, g, p);
  std::set<std::uint32_t> facesOfPlanarPart;
  for (std::uint32_t s = 0; s < g.size(); ++s)
  {
    const auto& sf = g.surfels[s];
    if (sf.sign() < 0)
      continue;
    std::array<int, 3> beyond = sf.voxel;
    ++beyond[sf.axis()];
    if (beyond[sf.axis()] < 16) // not on the box's wall
      facesOfPlanarPart.insert(p.faceOfSurfel[s]);
  }
  ASSERT_EQ(facesOfPlanarPart.size(), 1u);
  EXPECT_EQ(p.faces[*facesOfPlanarPart.begin()].plane.normal,
    (std::array<std::int64_t, 3>{ n[0], n[1], n[2] }));
}

TEST(Polyhedrization, Limits)
{
  const vbr::BitVolume v = ball(60);
  vbr::PolyhedrizationOptions small;
  small.maximumFaceSize = 5;
  polyhedrizeAndCheck(v, small);
  vbr::PolyhedrizationOptions shallow;
  shallow.maximumDepth = 2;
  shallow.mergeFaces = true;
  shallow.mergeFacesUpTo = 50;
  polyhedrizeAndCheck(v, shallow);
  // Merging never adds faces.
  vbr::SurfelGraph g;
  vbr::buildSurfelGraph(v, vbr::Execution(), g);
  vbr::Polyhedron plain, merged;
  vbr::PolyhedrizationOptions depth;
  depth.maximumDepth = 2;
  vbr::polyhedrize(g, depth, vbr::Execution(), plain);
  depth.mergeFaces = true;
  depth.mergeFacesUpTo = 50;
  vbr::polyhedrize(g, depth, vbr::Execution(), merged);
  EXPECT_LT(merged.faces.size(), plain.faces.size());
  EXPECT_EQ(merged.faces.size() + merged.mergedFaces, plain.faces.size());
}

TEST(Polyhedrization, AbortAndBadOutlines)
{
  const vbr::BitVolume v = ball(100);
  vbr::SurfelGraph g;
  vbr::buildSurfelGraph(v, vbr::Execution(), g);
  vbr::Execution stop;
  stop.aborted = [] { return true; };
  vbr::Polyhedron p;
  EXPECT_FALSE(vbr::polyhedrize(g, {}, stop, p));
  vbr::SurfelGraph none;
  EXPECT_FALSE(vbr::buildSurfelGraph(v, stop, none));

  // An outline whose loop is not made of linels of its plane is refused, not followed.
  vbr::BitVolume back;
  vbr::FaceOutline bad;
  bad.plane.normal = { 0, 0, 1 };
  bad.plane.mu = 0;
  bad.loop = { { 0, 0, 0 }, { 2, 0, 0 }, { 2, 1, 0 } };
  EXPECT_NE(vbr::revert({ bad }, { 4, 4, 4 }, back), "");
  bad.loop = { { 0, 0, 5 }, { 1, 0, 5 }, { 1, 1, 5 }, { 0, 1, 5 } }; // off the plane
  EXPECT_NE(vbr::revert({ bad }, { 4, 4, 4 }, back), "");
}

// Abort inside each phase: a progress callback asks to stop at its first report inside the
// phase (growth 0 - 0.6, moves 0.6 - 0.7, merging 0.7 - 0.95, loops 0.95 - 1). Each phase
// must report from inside (so it polls while it runs) and stop there: nothing reported past
// its end, and no further poll answered once stopped.
TEST(Polyhedrization, AbortInsideEachPhase)
{
  std::mt19937 rng(8);
  vbr::BitVolume v(32, 32, 32);
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        v.set(x, y, z, rng() & 1);
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  vbr::PolyhedrizationOptions options;
  options.mergeFaces = true;
  const std::pair<double, double> phases[] = {
    { 0.0, 0.6 }, { 0.6, 0.7 }, { 0.7, 0.95 }, { 0.95, 1.0 }
  };
  for (const auto& [from, to] : phases)
  {
    bool stop = false;
    double highest = 0.0;
    int pollsAfterStop = 0;
    vbr::Execution exec;
    exec.progress = [&](double f)
    {
      highest = std::max(highest, f);
      stop = stop || (f > from && f < to);
      return !stop;
    };
    exec.aborted = [&]
    {
      pollsAfterStop += stop;
      return stop;
    };
    vbr::Polyhedron p;
    EXPECT_FALSE(vbr::polyhedrize(g, options, exec, p)) << "phase from " << from;
    EXPECT_TRUE(stop) << "no report inside the phase from " << from;
    EXPECT_LT(highest, to) << "went on past the phase from " << from;
    EXPECT_LE(pollsAfterStop, 1) << "phase from " << from;
  }
  // The reversion stops too.
  vbr::Polyhedron p;
  ASSERT_TRUE(vbr::polyhedrize(g, {}, vbr::Execution(), p));
  std::vector<vbr::FaceOutline> outlines = outlinesOf(p, g);
  vbr::Execution stopNow;
  stopNow.aborted = [] { return true; };
  vbr::BitVolume back;
  EXPECT_EQ(vbr::revert(outlines, v.dims(), back, stopNow), "aborted");
  // A face given twice is an error (the parity would cancel it silently).
  outlines.push_back(outlines.front());
  EXPECT_NE(vbr::revert(outlines, v.dims(), back).find("twice"), std::string::npos);
}

// The surfel graph against an independent reference: the corners of every surfel are the four
// corners of its unit square, counter-clockwise about its outward normal; its vertices are
// the classes of corners glued across shared edges (a union-find over all 4n corners, the
// graph's own method before it walked umbrellas), numbered by their first corner. And the
// graph holds no more than its documented arrays: about 52 bytes per surfel plus 12 per
// vertex (it held 48 more per surfel when it stored the corners).
TEST(SurfelGraph, VerticesAreGluedCornersAndTheGraphIsCompact)
{
  unsigned seed = 40;
  for (const Point3 d : { Point3{ 5, 4, 6 }, Point3{ 9, 9, 9 }, Point3{ 16, 3, 11 } })
    for (double density : { 0.2, 0.5, 0.8 })
    {
      SCOPED_TRACE("seed " + std::to_string(seed));
      const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
      vbr::SurfelGraph g;
      ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
      const std::size_t n = g.size();
      for (std::uint32_t s = 0; s < n; ++s)
      {
        const vbr::Surfel& sf = g.surfels[s];
        Point3 c[4];
        for (int k = 0; k < 4; ++k)
        {
          c[k] = g.cornerOf(s, k);
          for (int a = 0; a < 3; ++a)
          {
            const int lo = sf.voxel[a] + (a == sf.axis() && sf.sign() > 0 ? 1 : 0);
            const int hi = a == sf.axis() ? lo : lo + 1;
            ASSERT_TRUE(c[k][a] >= lo && c[k][a] <= hi) << "corner off the surfel's square";
          }
        }
        for (int k = 0; k < 4; ++k) // each turn is to the left about the outward normal
        {
          const Point3 e = vbr::sub(c[(k + 1) % 4], c[k]),
                       f = vbr::sub(c[(k + 2) % 4], c[(k + 1) % 4]);
          const Point3 turn = vbr::cross(e, f);
          ASSERT_EQ(turn[sf.axis()], sf.sign()) << "corners not counter-clockwise";
        }
      }
      // The reference: corners glued across each shared edge, in both directions.
      std::vector<std::uint32_t> parent(4 * n);
      for (std::uint32_t i = 0; i < 4 * n; ++i)
        parent[i] = i;
      auto find = [&](std::uint32_t x)
      {
        while (parent[x] != x)
          x = parent[x] = parent[parent[x]];
        return x;
      };
      auto unite = [&](std::uint32_t a, std::uint32_t b)
      {
        a = find(a), b = find(b);
        parent[std::max(a, b)] = std::min(a, b);
      };
      for (std::uint32_t s = 0; s < n; ++s)
        for (int k = 0; k < 4; ++k)
        {
          const std::uint32_t t = g.neighbourOf(s, k);
          const int j = g.sharedEdge(s, k);
          ASSERT_EQ(g.cornerOf(t, j), g.cornerOf(s, (k + 1) % 4)) << "edges not shared";
          ASSERT_EQ(g.cornerOf(t, (j + 1) % 4), g.cornerOf(s, k)) << "edges not shared";
          unite(4 * s + k, 4 * t + (j + 1) % 4);
          unite(4 * s + (k + 1) % 4, 4 * t + j);
        }
      std::map<std::uint32_t, std::uint32_t> number; // root -> vertex, by first corner
      for (std::uint32_t c = 0; c < 4 * n; ++c)
      {
        const std::uint32_t root = find(c);
        const auto it = number.emplace(root, static_cast<std::uint32_t>(number.size())).first;
        ASSERT_EQ(g.vertex[c], it->second) << "vertex of corner " << c;
        ASSERT_EQ(g.vertexPointel[g.vertex[c]], g.cornerOf(c / 4, c % 4));
      }
      ASSERT_EQ(g.vertexPointel.size(), number.size());
      const std::size_t perSurfel = g.surfels.capacity() * sizeof(vbr::Surfel) +
        g.neighbour.capacity() * 4 + g.vertex.capacity() * 4;
      EXPECT_LE(perSurfel, 48 * n) << "the graph stores more than its arrays per surfel";
      EXPECT_LE(g.vertexPointel.capacity(), g.vertexPointel.size());
    }
}

/// The graph's links against the pairing rule, found here from the corners alone: the surfel
/// across edge a -> b of s is the one surfel with an edge b -> a, or, at a linel of four
/// surfels (two voxels diagonal across it), the one of those two that bounds s's own voxel;
/// the shared edge is that edge. On one thread and on three, where a link found from one side
/// is also written for the other side when both surfels are of the same range of surfels.
void expectLinksFollowThePairingRule(const vbr::SurfelGraph& g)
{
  std::map<std::pair<Point3, Point3>, std::vector<std::pair<std::uint32_t, int>>> edges;
  for (std::uint32_t u = 0; u < g.size(); ++u)
    for (int j = 0; j < 4; ++j)
      edges[{ g.cornerOf(u, j), g.cornerOf(u, (j + 1) % 4) }].emplace_back(u, j);
  for (std::uint32_t s = 0; s < g.size(); ++s)
    for (int k = 0; k < 4; ++k)
    {
      const auto& across = edges.at({ g.cornerOf(s, (k + 1) % 4), g.cornerOf(s, k) });
      ASSERT_TRUE(across.size() == 1 || across.size() == 2) << "linel of surfel " << s;
      std::pair<std::uint32_t, int> expected = across[0];
      if (across.size() == 2)
        expected = g.surfels[across[1].first].voxel == g.surfels[s].voxel ? across[1] : across[0];
      ASSERT_TRUE(across.size() == 1 || g.surfels[expected.first].voxel == g.surfels[s].voxel)
        << "no surfel of the own voxel at a linel of four, surfel " << s;
      ASSERT_EQ(g.neighbourOf(s, k), expected.first) << "surfel " << s << " edge " << k;
      ASSERT_EQ(g.sharedEdge(s, k), expected.second) << "surfel " << s << " edge " << k;
    }
}

TEST(SurfelGraph, LinksFollowThePairingRule)
{
  unsigned seed = 70;
  for (const Point3 d : { Point3{ 6, 5, 7 }, Point3{ 12, 9, 10 } })
    for (double density : { 0.2, 0.5, 0.8 })
    {
      SCOPED_TRACE("seed " + std::to_string(seed));
      vbr::SurfelGraph g;
      ASSERT_TRUE(vbr::buildSurfelGraph(bf::randomVolume(d, density, seed++), vbr::Execution(), g));
      expectLinksFollowThePairingRule(g);
    }
  // Past 2^15 surfels the links are made in ranges on threads: a link written for the other
  // side must stay within its range and be the one that side would find.
  vbr::SurfelGraph large;
  ASSERT_TRUE(vbr::buildSurfelGraph(
    bf::randomVolume({ 40, 36, 34 }, 0.5, 41), bf::threadedExecution(3), large));
  ASSERT_GT(large.size(), std::size_t(1) << 15);
  expectLinksFollowThePairingRule(large);
}

// The reversion into a grid too small for the faces: an error that names the grid, not a
// write outside it.
TEST(Polyhedrization, RevertIntoTooSmallAGrid)
{
  vbr::BitVolume v(4, 4, 4);
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        v.set(x, y, z, x * x + y * y + z * z <= 12);
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  vbr::Polyhedron p;
  ASSERT_TRUE(vbr::polyhedrize(g, {}, vbr::Execution(), p));
  std::vector<vbr::FaceOutline> outlines = outlinesOf(p, g);
  vbr::BitVolume back;
  std::size_t surfels = 0;
  ASSERT_EQ(vbr::revert(outlines, v.dims(), back, vbr::Execution(), &surfels), "");
  EXPECT_TRUE(back == v);
  EXPECT_EQ(surfels, g.size());
  for (const std::array<std::int32_t, 3> small : { std::array<std::int32_t, 3>{ 3, 4, 4 },
         std::array<std::int32_t, 3>{ 4, 3, 4 },
         std::array<std::int32_t, 3>{ 4, 4, 3 } })
    EXPECT_NE(vbr::revert(outlines, small, back).find("grid"), std::string::npos);
}

// Each face's surfels refilled from its outline alone (what the filter draws when a loop does
// not triangulate) are the surfels the growth gave it, on random volumes.
namespace
{
// The surfels that surfelsOfOutline refills from a face's outline are the face's own, each once.
void expectOutlineRefillsFace(const vbr::FaceOutline& o,
  const vbr::StandardFace& f,
  const vbr::SurfelGraph& g,
  const std::array<int, 3>& dims,
  const std::string& what)
{
  std::vector<vbr::Surfel> refilled;
  ASSERT_EQ(vbr::surfelsOfOutline(o, dims, refilled), "") << what;
  std::set<std::pair<Point3, int>> got, want;
  for (const vbr::Surfel& s : refilled)
    got.emplace(s.voxel, s.direction);
  for (std::uint32_t s : f.surfels)
    want.emplace(g.surfels[s].voxel, g.surfels[s].direction);
  EXPECT_EQ(got, want) << what;
  EXPECT_EQ(refilled.size(), f.surfels.size()) << what;
}
} // namespace

TEST(Polyhedrization, SurfelsOfOutlineAreTheFacesSurfels)
{
  for (unsigned seed = 60; seed < 66; ++seed)
  {
    const vbr::BitVolume v = bf::randomVolume({ 9, 8, 7 }, 0.3 + 0.1 * (seed % 5), seed);
    vbr::SurfelGraph g;
    ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
    vbr::Polyhedron p;
    ASSERT_TRUE(vbr::polyhedrize(g, {}, vbr::Execution(), p));
    for (const vbr::StandardFace& f : p.faces)
    {
      expectOutlineRefillsFace(outlineOf(f, g), f, g, v.dims(), "seed " + std::to_string(seed));
    }
  }
}

TEST(Polyhedrization, ThinDiagonalFacesAreMarkedInHashes)
{
  // A wall 3 voxels thick and 3 high along the diagonal x = y of a 160 x 160 grid: its long
  // faces are strips of about 500 surfels whose loops project to boxes of about 160 x 160
  // cells, more than 8 per surfel, so the reversion marks them in hash indexes, not in an array.
  // Their surfels must still be the graph's (which the array's marks give, as
  // SurfelsOfOutlineAreTheFacesSurfels checks), and the reversion the voxels: the two ways of
  // marking are keyed alike, so the faces and the reversion do not depend on the box.
  const int n = 160;
  vbr::BitVolume v(n, n, 3);
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = y; x < std::min(n, y + 3); ++x)
        v.set(x, y, z);
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  vbr::Polyhedron p;
  ASSERT_TRUE(vbr::polyhedrize(g, {}, vbr::Execution(), p));
  checkPolyhedron(v, g, p); // the reversion gives the voxels
  std::size_t hashed = 0, arrayed = 0;
  for (const vbr::StandardFace& f : p.faces)
  {
    const vbr::FaceOutline o = outlineOf(f, g);
    const std::size_t cells = vbr::detail::faceMarkArrayCells(o, v.dims());
    (cells == 0 ? hashed : arrayed) += 1;
    EXPECT_LE(cells, 8 * std::max(f.surfels.size(), o.loop.size()) + 64);
    expectOutlineRefillsFace(o, f, g, v.dims(), cells == 0 ? "hashed face" : "face in an array");
  }
  EXPECT_GE(hashed, 2u) << "the long faces should be marked in hashes";
  EXPECT_GE(arrayed, 2u) << "the end caps should be marked in arrays";
}

namespace
{

/// Whether surfels `a` plus `extra` form a disk of the boundary, counted without the code under
/// test: connected (the caller's), Euler characteristic 1 and one boundary loop that meets no
/// vertex twice.
bool isDisk(const vbr::SurfelGraph& g,
  std::vector<std::uint32_t> a,
  const std::vector<std::uint32_t>& extra)
{
  a.insert(a.end(), extra.begin(), extra.end());
  const std::set<std::uint32_t> in(a.begin(), a.end());
  std::set<std::uint32_t> vertices;
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  std::map<std::uint32_t, std::uint32_t> next; // boundary edges, oriented with their surfel
  for (std::uint32_t s : a)
    for (int k = 0; k < 4; ++k)
    {
      const std::uint32_t u = g.vertexOf(s, k), w = g.vertexOf(s, (k + 1) % 4);
      vertices.insert(u);
      edges.insert(std::minmax(u, w));
      if (!in.count(g.neighbourOf(s, k)) && !next.emplace(u, w).second)
        return false; // the boundary pinches at u
    }
  if (long(vertices.size()) - long(edges.size()) + long(a.size()) != 1 || next.empty())
    return false;
  std::size_t length = 0;
  std::uint32_t v = next.begin()->first;
  do
  {
    v = next.at(v);
    ++length;
  } while (v != next.begin()->first && length <= next.size());
  return length == next.size();
}

/// Whether face `a` takes every part of `extra` that is connected to it, whichever part: then
/// a growth that adds the surfels of `extra` one by one from `a` keeps a disk at every step.
bool takesEveryConnectedPart(const vbr::SurfelGraph& g,
  const std::vector<std::uint32_t>& a,
  const std::vector<std::uint32_t>& extra)
{
  const std::set<std::uint32_t> face(a.begin(), a.end());
  for (unsigned mask = 1; mask < (1u << extra.size()); ++mask)
  {
    std::vector<std::uint32_t> part;
    for (std::size_t i = 0; i < extra.size(); ++i)
      if (mask >> i & 1)
        part.push_back(extra[i]);
    // Connected to the face: reached from it across edges within the part.
    std::set<std::uint32_t> reached;
    for (bool grew = true; grew;)
    {
      grew = false;
      for (std::uint32_t s : part)
        for (int k = 0; k < 4 && !reached.count(s); ++k)
        {
          const std::uint32_t t = g.neighbourOf(s, k);
          if (face.count(t) || reached.count(t))
            grew = reached.insert(s).second;
        }
    }
    if (reached.size() == part.size() && !isDisk(g, a, part))
      return false;
  }
  return true;
}

/// Whether the pointels of surfels `a` plus `extra` lie in one standard plane with every
/// surfel on its outer side, by the brute-force search of normals (|n|_1 <= bound).
bool inOneStandardPlane(const vbr::SurfelGraph& g,
  std::vector<std::uint32_t> a,
  const std::vector<std::uint32_t>& extra)
{
  a.insert(a.end(), extra.begin(), extra.end());
  std::vector<Point3> points;
  std::array<int, 3> signs{ 0, 0, 0 };
  for (std::uint32_t s : a)
  {
    const auto& sf = g.surfels[s];
    if (signs[sf.axis()] == -sf.sign())
      return false;
    signs[sf.axis()] = sf.sign();
    for (int k = 0; k < 4; ++k)
      points.push_back(sf.corner(k));
  }
  return bruteForcePlane(points, signs, 16);
}

/// For each face f of at most 3 surfels left by the merging of v among faces that the merging
/// left as they were (so they were so when f was offered to them): whether the face g that
/// the merging offers f to first (the most edges shared with f, then the lowest number before
/// the merging) takes f, by the brute force: g plus any connected part of f is a disk (so the
/// growth of g over f keeps a disk at every step, whatever its order) and g plus f lies in
/// one standard plane. Adds to the counts of faces checked and merges lost.
void countLostMerges(const vbr::BitVolume& v, std::size_t& checked, std::size_t& lost)
{
  vbr::SurfelGraph g;
  ASSERT_TRUE(vbr::buildSurfelGraph(v, vbr::Execution(), g));
  vbr::PolyhedrizationOptions merged;
  merged.mergeFaces = true;
  vbr::Polyhedron before, after;
  ASSERT_TRUE(vbr::polyhedrize(g, {}, vbr::Execution(), before));
  ASSERT_TRUE(vbr::polyhedrize(g, merged, vbr::Execution(), after));
  auto numberBefore = [&](std::uint32_t f)
  { return before.faceOfSurfel[after.faces[f].surfels[0]]; };
  auto unchanged = [&](std::uint32_t f)
  { return before.faces[numberBefore(f)].surfels == after.faces[f].surfels; };
  for (std::uint32_t f = 0; f < after.faces.size(); ++f)
  {
    const std::vector<std::uint32_t>& small = after.faces[f].surfels;
    if (small.size() > 3 || !unchanged(f))
      continue;
    std::map<std::uint32_t, int> shared;
    for (std::uint32_t s : small)
      for (int k = 0; k < 4; ++k)
        ++shared[after.faceOfSurfel[g.neighbourOf(s, k)]];
    shared.erase(f);
    std::pair<int, long> first{ 0, 0 }; // (edges shared, -number before the merging)
    bool asBefore = true;
    std::uint32_t target = f;
    for (const auto& [h, edges] : shared)
    {
      asBefore = asBefore && unchanged(h);
      const std::pair<int, long> key{ edges, -long(numberBefore(h)) };
      if (target == f || key > first)
        first = key, target = h;
    }
    if (!asBefore || target == f)
      continue;
    const std::vector<std::uint32_t>& large = after.faces[target].surfels;
    ++checked;
    const bool takes =
      takesEveryConnectedPart(g, large, small) && inOneStandardPlane(g, large, small);
    lost += takes;
    EXPECT_FALSE(takes) << "face " << f << " of " << small.size() << " surfels left next to face "
                        << target << " of " << large.size() << ", which takes it";
  }
}

} // namespace

// The merging hands a small face f to the first face g it offers f to whenever g takes f
// (checked by countLostMerges with the brute force), on balls and random volumes. A refusal that
// the growth stamped with a face's number, read by the merging after the moves renumbered the faces
// (or after the refusing face gave surfels away), lost such merges.
TEST(Polyhedrization, MergingTakesTheFacesItCan)
{
  std::size_t checked = 0, lost = 0;
  for (int r2 : { 60, 150, 300, 600 })
  {
    SCOPED_TRACE("ball r^2 <= " + std::to_string(r2));
    countLostMerges(ball(r2), checked, lost);
  }
  for (unsigned seed = 0; seed < 240; ++seed)
  {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const vbr::Point3 d{ 4 + int(seed % 5), 4 + int(seed / 5 % 4), 4 + int(seed / 20 % 5) };
    countLostMerges(bf::randomVolume(d, 0.3 + 0.1 * (seed % 5), 4000 + seed), checked, lost);
  }
  EXPECT_GT(checked, 100u) << "too few faces checked";
  std::printf("%zu small faces checked, %zu merges lost\n", checked, lost);
}

namespace
{

/// The strictly convex hull of random lattice points in [-span, span]^2 shifted by `shift`
/// (Andrew's monotone chain, collinear points dropped), counter-clockwise.
std::vector<vbr::Point2L> randomConvexPolygon(std::mt19937& rng,
  int points,
  std::int64_t span,
  std::int64_t shift)
{
  std::uniform_int_distribution<std::int64_t> coordinate(-span, span);
  std::vector<vbr::Point2L> p(static_cast<std::size_t>(points));
  for (vbr::Point2L& q : p)
    q = { coordinate(rng) + shift, coordinate(rng) - shift };
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3)
    return p;
  std::vector<vbr::Point2L> hull(2 * p.size());
  std::size_t k = 0;
  auto turnsLeft = [](const vbr::Point2L& a, const vbr::Point2L& b, const vbr::Point2L& c)
  { return vbr::cross2(a, b, c) > 0; };
  for (std::size_t i = 0; i < p.size(); ++i) // lower hull
  {
    while (k >= 2 && !turnsLeft(hull[k - 2], hull[k - 1], p[i]))
      --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) // upper hull
  {
    while (k >= t && !turnsLeft(hull[k - 2], hull[k - 1], p[i]))
      --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

/// Polygons of every kind that the fan must take or leave: strictly convex ones (from any
/// corner, with small and with large coordinates), with straight corners, traversed twice,
/// star-shaped windings, clockwise ones, random ones.
std::vector<vbr::Point2L> randomFanCandidate(std::mt19937& rng, int kind)
{
  const std::int64_t shift = kind % 2 ? (std::int64_t(1) << 40) : 0; // beyond 64-bit products
  std::vector<vbr::Point2L> p = randomConvexPolygon(rng, 3 + int(rng() % 12), 1 + rng() % 6, shift);
  std::rotate(p.begin(), p.begin() + (p.empty() ? 0 : rng() % p.size()), p.end());
  switch (kind / 2)
  {
    case 0: // strictly convex
      break;
    case 1: // a straight corner: an edge's midpoint, where it is a lattice point
      for (std::size_t i = 0; i < p.size(); ++i)
      {
        const vbr::Point2L& a = p[i];
        const vbr::Point2L& b = p[(i + 1) % p.size()];
        if ((a[0] + b[0]) % 2 == 0 && (a[1] + b[1]) % 2 == 0)
        {
          p.insert(p.begin() + std::ptrdiff_t(i + 1), { (a[0] + b[0]) / 2, (a[1] + b[1]) / 2 });
          break;
        }
      }
      break;
    case 2: // traversed twice: every corner repeated
    {
      const std::vector<vbr::Point2L> once = p;
      p.insert(p.end(), once.begin(), once.end());
      break;
    }
    case 3: // every other corner, twice round (a star when the count is odd)
    {
      std::vector<vbr::Point2L> star;
      for (std::size_t i = 0; i < p.size(); ++i)
        star.push_back(p[(2 * i) % p.size()]);
      p = star;
      break;
    }
    case 4: // clockwise
      std::reverse(p.begin(), p.end());
      break;
    default: // random corners
      for (vbr::Point2L& q : p)
        q = { q[0] + std::int64_t(rng() % 5) - 2, q[1] + std::int64_t(rng() % 5) - 2 };
      break;
  }
  return p;
}

} // namespace

// fanStrictlyConvexPolygon is PolygonTriangulator's shortcut: whatever it takes must give the ear
// clipping's triangles (triangulateByEars), in its order; whatever it leaves, untouched.
TEST(Polyhedrization, ConvexFanIsTheTriangulatorsTriangles)
{
  vbr::PolygonTriangulator triangulator;
  {
    // Twice round, every corner turning left and every triangle of the fan from the last corner
    // too, but corners 1 and 4 at one place: the triangulator parts the polygon there.
    const std::vector<vbr::Point2L> touching{
      { 6, 0 }, { -6, 10 }, { -5, -9 }, { 2, 0 }, { -6, 10 }, { -4, -7 }
    };
    std::vector<vbr::Triangle> fan, general;
    EXPECT_FALSE(vbr::fanStrictlyConvexPolygon(touching, fan)) << "a repeated corner fanned";
    triangulator.triangulateByEars(touching, general);
    EXPECT_NE(general.size(), touching.size() - 2) << "the triangulator fans it too";
  }
  std::mt19937 rng(41);
  std::size_t taken = 0, left = 0;
  for (int round = 0; round < 30000; ++round)
  {
    const int kind = round % 12;
    const std::vector<vbr::Point2L> p = randomFanCandidate(rng, kind);
    std::vector<vbr::Triangle> fan{ { 7, 8, 9 } }, general{ { 7, 8, 9 } }; // appended to
    const bool fanned = vbr::fanStrictlyConvexPolygon(p, fan);
    const bool triangulated = triangulator.triangulateByEars(p, general);
    if (!fanned)
    {
      ASSERT_EQ(fan.size(), 1u) << "round " << round << ": left, yet appended to";
      ++left;
      continue;
    }
    ++taken;
    ASSERT_TRUE(triangulated) << "round " << round << ": fanned, yet not a polygon";
    ASSERT_EQ(fan, general) << "round " << round << " (kind " << kind << ", " << p.size()
                            << " corners): not the triangulator's triangles";
    if (kind / 2 == 2 || kind / 2 == 4) // corners repeated, or clockwise
      ADD_FAILURE() << "round " << round << " (kind " << kind << "): fanned";
  }
  EXPECT_GT(taken, 5000u) << "too few polygons fanned";
  EXPECT_GT(left, 5000u) << "too few polygons left to the triangulator";
  std::printf("%zu polygons fanned, %zu left to the triangulator\n", taken, left);
}

namespace
{

/// A recognizer's call: the corners of some surfels and their orientations.
struct RecognizerCall
{
  std::vector<vbr::Point3> points;
  std::array<int, 3> signs{ 0, 0, 0 };

  void add(const vbr::Surfel& s)
  {
    for (int k = 0; k < 4; ++k)
      this->points.push_back(s.corner(k));
    this->signs[s.axis()] = s.sign();
  }
};

/// A face's first call (a lone surfel, the umbrella of a cube's corner, or two surfels side by
/// side: shapes that come back, at `at`) and then surfels near it, a call each.
std::vector<RecognizerCall> randomFaceCalls(std::mt19937& rng,
  const vbr::Point3& at,
  int spread = 2)
{
  std::vector<RecognizerCall> calls(1);
  const int shape = static_cast<int>(rng() % 9);
  const auto direction = static_cast<std::uint8_t>(rng() % 6);
  if (shape < 6)
    calls[0].add({ at, direction });
  else if (shape < 8) // the umbrella of the corner of voxel at, +x +y +z (or -x -y -z)
    for (int axis = 0; axis < 3; ++axis)
      calls[0].add({ at, static_cast<std::uint8_t>(2 * axis + (shape == 6 ? 1 : 0)) });
  else // two surfels of one direction side by side
  {
    calls[0].add({ at, direction });
    vbr::Point3 next = at;
    ++next[(direction / 2 + 1) % 3];
    calls[0].add({ next, direction });
  }
  // Then surfels of two or three directions of one octant, near: some taken, some refused.
  const std::array<int, 3> signs{ rng() % 2 ? 1 : -1, rng() % 2 ? 1 : -1, rng() % 2 ? 1 : -1 };
  std::uniform_int_distribution<int> near(-spread, spread);
  for (int c = 0; c < 8; ++c)
  {
    const int axis = static_cast<int>(rng() % 3);
    RecognizerCall call;
    call.add({ { at[0] + near(rng), at[1] + near(rng), at[2] + near(rng) },
      static_cast<std::uint8_t>(2 * axis + (signs[axis] > 0 ? 1 : 0)) });
    calls.push_back(call);
  }
  return calls;
}

/// Grows one face by `calls` with `kept` (reset first, its records kept) and with a recognizer
/// that never saw an earlier face: every answer, the points, the plane and the recognition work
/// counted must be the same. Counts the calls taken and refused.
void growAlikeAfterReset(vbr::StandardPlaneRecognizer& kept,
  const std::vector<RecognizerCall>& calls,
  int face,
  std::size_t& taken,
  std::size_t& refused)
{
  kept.reset();
  vbr::StandardPlaneRecognizer fresh;
  const std::size_t clips = kept.clipCount(), searches = kept.searchCount();
  for (std::size_t c = 0; c < calls.size(); ++c)
  {
    const bool a = kept.tryAdd(calls[c].points, calls[c].signs);
    const bool b = fresh.tryAdd(calls[c].points, calls[c].signs);
    ASSERT_EQ(a, b) << "face " << face << ", call " << c;
    (a ? taken : refused) += 1;
    ASSERT_EQ(kept.pointCount(), fresh.pointCount()) << "face " << face << ", call " << c;
    ASSERT_EQ(kept.clipCount() - clips, fresh.clipCount()) << "face " << face << ", call " << c;
    ASSERT_EQ(kept.searchCount() - searches, fresh.searchCount())
      << "face " << face << ", call " << c;
    if (kept.pointCount() > 0)
    {
      ASSERT_EQ(kept.plane().normal, fresh.plane().normal) << "face " << face << ", call " << c;
      ASSERT_EQ(kept.plane().mu, fresh.plane().mu) << "face " << face << ", call " << c;
    }
  }
}

/// `faces` random faces (randomFaceCalls with `spread`, anywhere within 60 of the origin) grown
/// by `kept`, reset for each face with its records kept, each compared with a fresh recognizer
/// (growAlikeAfterReset); stops at the first fatal failure.
void growFacesAlikeAfterReset(vbr::StandardPlaneRecognizer& kept,
  unsigned seed,
  int faces,
  int spread,
  std::size_t& taken,
  std::size_t& refused)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> shift(-60, 60);
  for (int face = 0; face < faces; ++face)
  {
    const std::vector<RecognizerCall> calls =
      randomFaceCalls(rng, { shift(rng), shift(rng), shift(rng) }, spread);
    growAlikeAfterReset(kept, calls, face, taken, refused);
    if (::testing::Test::HasFatalFailure())
      return;
  }
}

} // namespace

// A recognizer repeats a first call it recorded after an earlier reset rather than recognising
// it again: every call, then and after, must answer as a recognizer that never saw it (the same
// plane, points and recognition work counted).
TEST(StandardPlane, FirstCallsFromRecordsAreRecognisedAlike)
{
  vbr::StandardPlaneRecognizer kept; // reset for each face, its records kept
  std::size_t taken = 0, refused = 0;
  growFacesAlikeAfterReset(kept, 17, 4000, 2, taken, refused);
  if (::testing::Test::HasFatalFailure())
    return;
  EXPECT_GT(taken, 4000u);
  EXPECT_GT(refused, 4000u);
}

// Its later calls too: a face's slow path after the same calls relative to its first point is
// repeated from the record of an earlier face. Faces of a few shapes, their later surfels one
// voxel apart at most, so that paths come back often: every answer, the points, the plane and
// the work counted must be those of a recognizer that never saw an earlier face.
TEST(StandardPlane, LaterCallsFromRecordsAreRecognisedAlike)
{
  vbr::StandardPlaneRecognizer kept; // reset for each face, its records kept
  std::size_t taken = 0, refused = 0;
  growFacesAlikeAfterReset(kept, 23, 20000, 1, taken, refused);
  if (::testing::Test::HasFatalFailure())
    return;
  EXPECT_GT(taken, 20000u);
  EXPECT_GT(refused, 20000u);
  EXPECT_GT(kept.laterCallsRepeated(), 5000u) << "too few slow paths repeated from records";
  std::printf("%zu slow paths of later calls repeated from records\n", kept.laterCallsRepeated());
}
