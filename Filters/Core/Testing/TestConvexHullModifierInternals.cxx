// The hull modifier's point lists and first hulls against brute force: the runs listed from the
// volume's words against the points listed bit by bit (rows of 1 to 130 voxels, so that runs
// cross the 64-bit words' boundaries, ranges reaching off the grid, rows outside it), the x range
// of a row in a set of half spaces against the integers tested one by one, the corners of the
// slices' polygons against the points no triangle of other points holds, a group's first hull
// against the hull of all its points, and the sides of H that the joins find from the triangles
// near a box against the voxel classes H separates.
#include "ConvexHull.h"
#include "ConvexHullModifier.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

namespace
{

using vbr::LatticePoint;
using Runs = std::vector<std::array<std::int64_t, 4>>;

bool classAt(const vbr::BitVolume& v, std::int64_t x, std::int64_t y, std::int64_t z)
{
  return x >= 0 && y >= 0 && z >= 0 && x < v.size(0) && y < v.size(1) && z < v.size(2) &&
    v.get(static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), static_cast<std::int32_t>(z));
}

/// Appends the point (x, y, z) to maximal runs listed in row order.
void appendPoint(Runs& runs, std::int64_t x, std::int64_t y, std::int64_t z)
{
  if (!runs.empty() && runs.back()[1] + 1 == x && runs.back()[2] == y && runs.back()[3] == z)
    ++runs.back()[1];
  else
    runs.push_back({ x, x, y, z });
}

vbr::BitVolume randomVolume(std::mt19937& rng, std::int32_t nx, std::int32_t ny, std::int32_t nz)
{
  // Densities from empty to full, so that rows have long runs and whole words of one class.
  const double density = std::array<double, 6>{ 0.0, 0.1, 0.5, 0.9, 0.97, 1.0 }[rng() % 6];
  std::bernoulli_distribution bit(density);
  vbr::BitVolume v(nx, ny, nz);
  for (std::int32_t z = 0; z < nz; ++z)
    for (std::int32_t y = 0; y < ny; ++y)
      for (std::int32_t x = 0; x < nx; ++x)
        if (bit(rng))
          v.set(x, y, z);
  return v;
}

/// p on the inner side of the face's plane (strictly, or on it too).
bool inHalfSpace(const vbr::FacePlane& f, const LatticePoint& p, bool strict)
{
  const auto v = f.evaluate(p);
  return strict ? v < 0 : v <= 0;
}

bool inAllHalfSpaces(const vbr::CellList& c, const LatticePoint& p, bool strict)
{
  return std::all_of(c.planes.begin(),
    c.planes.end(),
    [&](const vbr::FacePlane& f) { return inHalfSpace(f, p, strict); });
}

/// `count` planes of random normals (never zero) and offsets; `shapeX` may set a normal's x
/// component (planes parallel to x, or nearly).
template<typename ShapeX>
vbr::CellList randomHalfSpaces(std::mt19937& rng,
  int count,
  std::uniform_int_distribution<std::int64_t>& normal,
  std::uniform_int_distribution<std::int64_t>& offset,
  ShapeX shapeX)
{
  vbr::CellList c;
  while (static_cast<int>(c.planes.size()) < count)
  {
    vbr::FacePlane f;
    f.normal = { normal(rng), normal(rng), normal(rng) };
    shapeX(f);
    f.offset = offset(rng);
    if (f.normal != LatticePoint{ 0, 0, 0 })
      c.planes.push_back(f);
  }
  return c;
}

TEST(ConvexHullModifierInternals, RunsOfARowMatchItsBits)
{
  for (std::int32_t width : { 1, 63, 64, 65, 127, 128, 129, 130 })
  {
    for (unsigned seed = 0; seed < 40; ++seed)
    {
      std::mt19937 rng(seed * 131 + static_cast<unsigned>(width));
      const vbr::BitVolume v = randomVolume(rng, width, 2, 2);
      std::uniform_int_distribution<std::int64_t> end(-70, width + 70);
      for (int trial = 0; trial < 60; ++trial)
      {
        std::int64_t lo = end(rng), hi = end(rng);
        if (lo > hi)
          std::swap(lo, hi);
        // Word boundaries and the grid's ends exactly, now and then.
        if (trial % 5 == 0)
          lo = std::array<std::int64_t, 5>{ 0, 63, 64, width - 1, -1 }[rng() % 5];
        if (trial % 7 == 0)
          hi = std::array<std::int64_t, 5>{ 63, 64, 127, width - 1, width }[rng() % 5];
        if (lo > hi)
          std::swap(lo, hi);
        const std::int64_t y = std::uniform_int_distribution<std::int64_t>(-1, 2)(rng);
        const std::int64_t z = std::uniform_int_distribution<std::int64_t>(-1, 2)(rng);
        for (bool cls : { false, true })
        {
          Runs expected;
          for (std::int64_t x = lo; x <= hi; ++x)
            if (classAt(v, x, y, z) == cls)
              appendPoint(expected, x, y, z);
          ASSERT_EQ(vbr::detail::runsOfRow(v, cls, lo, hi, y, z), expected)
            << "width " << width << " seed " << seed << " class " << cls << " x " << lo << ".."
            << hi << " row " << y << ", " << z;
        }
      }
    }
  }
}

TEST(ConvexHullModifierInternals, RunsOfAHullMatchItsPoints)
{
  for (std::int32_t width : { 1, 63, 64, 65, 128, 130 })
  {
    for (unsigned seed = 0; seed < 20; ++seed)
    {
      std::mt19937 rng(seed * 977 + static_cast<unsigned>(width));
      const vbr::BitVolume v = randomVolume(rng, width, 4, 3);
      // A hull reaching beyond the grid on every side.
      std::uniform_int_distribution<std::int64_t> px(-5, width + 5), pyz(-3, 6);
      std::vector<LatticePoint> corners;
      for (int k = 0; k < 12; ++k)
        corners.push_back({ px(rng), pyz(rng), pyz(rng) });
      const vbr::CellList c = vbr::convexHull(corners);
      if (c.dimension != 3)
        continue;
      for (bool strict : { false, true })
        for (bool cls : { false, true })
        {
          Runs expected;
          // The hull lies in the box its corners were drawn from.
          for (std::int64_t z = pyz.min(); z <= pyz.max(); ++z)
            for (std::int64_t y = pyz.min(); y <= pyz.max(); ++y)
              for (std::int64_t x = px.min(); x <= px.max(); ++x)
                if (inAllHalfSpaces(c, { x, y, z }, strict) && classAt(v, x, y, z) == cls)
                  appendPoint(expected, x, y, z);
          ASSERT_EQ(vbr::detail::runsOfClass(c, v, cls, strict), expected)
            << "width " << width << " seed " << seed << " strict " << strict << " class " << cls;
        }
    }
  }
}

/// The x range of row (y, z) in the half spaces: every x tried in [-window, window].
void expectRangeByScan(const vbr::CellList& c,
  bool strict,
  std::int64_t y,
  std::int64_t z,
  std::int64_t window)
{
  std::int64_t first = std::numeric_limits<std::int64_t>::max(), last = 0;
  std::size_t count = 0;
  for (std::int64_t x = -window; x <= window; ++x)
  {
    if (inAllHalfSpaces(c, { x, y, z }, strict))
    {
      first = std::min(first, x);
      last = x;
      ++count;
    }
  }
  std::int64_t lo = 0, hi = 0;
  const bool meets = vbr::detail::rowRange(c, strict, y, z, lo, hi);
  ASSERT_EQ(meets, count > 0) << "row " << y << ", " << z << " strict " << strict;
  if (!meets)
    return;
  // The points are an interval, and the range has no gaps.
  ASSERT_EQ(static_cast<std::int64_t>(count), last - first + 1);
  EXPECT_EQ(std::max(lo, -window), first) << "row " << y << ", " << z << " strict " << strict;
  EXPECT_EQ(std::min(hi, window), last) << "row " << y << ", " << z << " strict " << strict;
  // An unbounded side is no plane's bound.
  EXPECT_TRUE(lo > -window || lo == std::numeric_limits<std::int64_t>::min() / 4);
  EXPECT_TRUE(hi < window || hi == std::numeric_limits<std::int64_t>::max() / 4);
}

TEST(ConvexHullModifierInternals, RowRangeMatchesAScanOfItsIntegers)
{
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::int64_t> normal(-5, 5), offset(-40, 40), row(-10, 10);
  for (int trial = 0; trial < 6000; ++trial)
  {
    // Many planes parallel to x, which decide a row alone.
    const vbr::CellList c = randomHalfSpaces(rng,
      1 + trial % 6,
      normal,
      offset,
      [&](vbr::FacePlane& f)
      {
        if (rng() % 4 == 0)
          f.normal[0] = 0;
      });
    for (int r = 0; r < 8; ++r)
    {
      const std::int64_t y = row(rng), z = row(rng);
      // |n.p| <= 5 * 10 * 2 + 40 = 140 on the row apart from x: every bound lies in +-300.
      expectRangeByScan(c, false, y, z, 300);
      expectRangeByScan(c, true, y, z, 300);
    }
  }
}

/// The largest x (or the least when !up) of row (y, z) on the half space's side, by bisection.
std::int64_t boundBySearch(const vbr::FacePlane& f,
  bool strict,
  std::int64_t y,
  std::int64_t z,
  bool up)
{
  const auto in = [&](std::int64_t x) { return inHalfSpace(f, { x, y, z }, strict); };
  std::int64_t a = -(std::int64_t(1) << 50), b = std::int64_t(1) << 50;
  // up: in(a), !in(b); else !in(a), in(b).
  while (b - a > 1)
  {
    const std::int64_t m = a + (b - a) / 2;
    if (in(m) == up)
      a = m;
    else
      b = m;
  }
  return up ? a : b;
}

TEST(ConvexHullModifierInternals, RowRangeMatchesABisectionOnLargeCoordinates)
{
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::int64_t> normal(-1000, 1000), offset(-2000000, 2000000),
    row(-20000, 20000);
  for (int trial = 0; trial < 3000; ++trial)
  {
    const vbr::CellList c = randomHalfSpaces(rng,
      1 + trial % 5,
      normal,
      offset,
      [&](vbr::FacePlane& f)
      {
        if (trial % 3 == 0)
          f.normal[0] = std::uniform_int_distribution<std::int64_t>(-3, 3)(rng);
      });
    const std::int64_t y = row(rng), z = row(rng);
    for (bool strict : { false, true })
    {
      std::int64_t lo = std::numeric_limits<std::int64_t>::min() / 4;
      std::int64_t hi = std::numeric_limits<std::int64_t>::max() / 4;
      bool rowIn = true;
      for (const vbr::FacePlane& f : c.planes)
      {
        if (f.normal[0] == 0)
          rowIn = rowIn && inHalfSpace(f, { 0, y, z }, strict);
        else if (f.normal[0] > 0)
          hi = std::min(hi, boundBySearch(f, strict, y, z, true));
        else
          lo = std::max(lo, boundBySearch(f, strict, y, z, false));
      }
      std::int64_t gotLo = 0, gotHi = 0;
      const bool meets = vbr::detail::rowRange(c, strict, y, z, gotLo, gotHi);
      ASSERT_EQ(meets, rowIn && lo <= hi) << "trial " << trial << " strict " << strict;
      if (meets)
      {
        EXPECT_EQ(gotLo, lo) << "trial " << trial << " strict " << strict;
        EXPECT_EQ(gotHi, hi) << "trial " << trial << " strict " << strict;
      }
    }
  }
}

TEST(ConvexHullModifierInternals, RowRangeOfASolidHullMatchesAScanOfItsRows)
{
  // The rows of a solid hull leave out the planes that keep the slice's box: every row of the
  // hull's box and two beyond it, against the lattice points tested on every plane. The
  // coordinates stay within +-20 (the products of large ones: the bisection test above, on
  // planes alone); the slices that leave planes out are counted, so that the test fails when
  // that path is never taken.
  std::mt19937 rng(23);
  std::size_t planesLeftOut = 0;
  for (int trial = 0; trial < 300; ++trial)
  {
    const std::int64_t size = 2 + trial % 19;
    std::uniform_int_distribution<std::int64_t> coordinate(-size, size);
    std::vector<LatticePoint> points(4 + trial % 40);
    for (auto& p : points)
      p = { coordinate(rng), coordinate(rng), coordinate(rng) / (trial % 3 == 0 ? 4 : 1) };
    const vbr::CellList c = vbr::convexHull(points);
    if (c.dimension != 3)
      continue;
    for (bool strict : { false, true })
      for (std::int64_t z = -size - 2; z <= size + 2; ++z)
      {
        planesLeftOut += vbr::detail::planesLeftOutOfSlice(c, strict, z);
        for (std::int64_t y = -size - 2; y <= size + 2; ++y)
        {
          std::int64_t first = 0, last = -1, count = 0;
          for (std::int64_t x = -size - 3; x <= size + 3; ++x)
          {
            const bool in = std::all_of(c.planes.begin(),
              c.planes.end(),
              [&](const vbr::FacePlane& f)
              {
                const auto v = f.evaluate({ x, y, z });
                return strict ? v < 0 : v <= 0;
              });
            if (!in)
              continue;
            first = count == 0 ? x : first;
            last = x;
            ++count;
          }
          std::int64_t lo = 0, hi = 0;
          const bool meets = vbr::detail::rowRange(c, strict, y, z, lo, hi);
          ASSERT_EQ(meets, count > 0) << "trial " << trial << " row " << y << ", " << z;
          if (!meets)
            continue;
          EXPECT_EQ(lo, first) << "trial " << trial << " row " << y << ", " << z;
          EXPECT_EQ(hi, last) << "trial " << trial << " row " << y << ", " << z;
        }
      }
  }
  EXPECT_GT(planesLeftOut, 0u) << "no slice left a plane out: the box path was not tested";
}

TEST(ConvexHullModifierInternals, ReversionOfABoxSetsItsRunsAcrossWords)
{
  // The reversion sets the inside runs of a row a word at a time: boxes whose x ends lie at and
  // about the words' boundaries and beyond the grid, in grids 63 to 128 wide, against the
  // centres of the closed box in the grid (no background listed on the surface).
  for (std::int32_t width : { 63, 64, 65, 127, 128 })
    for (std::int64_t lo : { -2, 0, 1, 62, 63, 64, 65 })
      for (std::int64_t hi : { 62, 63, 64, 65, 126, 127, 128, 130 })
      {
        if (hi <= lo)
          continue;
        std::vector<LatticePoint> corners;
        for (std::int64_t x : { lo, hi })
          for (std::int64_t y : { 1, 2 })
            for (std::int64_t z : { 1, 3 })
              corners.push_back({ x, y, z });
        const vbr::LatticeMesh box = vbr::triangulateHull(vbr::convexHull(corners));
        vbr::BitVolume expected(width, 4, 5);
        for (std::int32_t z = 1; z <= 3; ++z)
          for (std::int32_t y = 1; y <= 2; ++y)
            for (std::int64_t x = std::max<std::int64_t>(lo, 0);
                 x <= std::min<std::int64_t>(hi, width - 1);
                 ++x)
              expected.set(static_cast<std::int32_t>(x), y, z);
        EXPECT_EQ(vbr::revertModifiedHull(box, {}, { width, 4, 5 }), expected)
          << "width " << width << " box x " << lo << ".." << hi;
      }
}

bool zyx(const LatticePoint& a, const LatticePoint& b)
{
  return std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]);
}

/// Twice the signed area of (a, b, c) in (x, y).
std::int64_t turn(const LatticePoint& a, const LatticePoint& b, const LatticePoint& c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// Whether p lies in the closed triangle (a, b, c) or, when that is flat, on the segments
/// between them (in (x, y)).
bool inTriangle(const LatticePoint& p,
  const LatticePoint& a,
  const LatticePoint& b,
  const LatticePoint& c)
{
  const std::int64_t t1 = turn(a, b, p), t2 = turn(b, c, p), t3 = turn(c, a, p);
  if (turn(a, b, c) != 0)
    return (t1 >= 0 && t2 >= 0 && t3 >= 0) || (t1 <= 0 && t2 <= 0 && t3 <= 0);
  const auto onSegment = [&](const LatticePoint& u, const LatticePoint& w)
  {
    return turn(u, w, p) == 0 && std::min(u[0], w[0]) <= p[0] && p[0] <= std::max(u[0], w[0]) &&
      std::min(u[1], w[1]) <= p[1] && p[1] <= std::max(u[1], w[1]);
  };
  return onSegment(a, b) || onSegment(b, c) || onSegment(a, c);
}

/// The corners of each z-slice's polygon: the points no triangle of three other points of
/// their slice holds (Caratheodory), sorted.
std::vector<LatticePoint> cornersByTriangles(const std::vector<LatticePoint>& points)
{
  std::vector<LatticePoint> out;
  for (const LatticePoint& p : points)
  {
    std::vector<LatticePoint> others;
    for (const LatticePoint& q : points)
      if (q[2] == p[2] && q != p)
        others.push_back(q);
    bool held = false;
    const std::size_t n = others.size();
    for (std::size_t i = 0; i < n && !held; ++i)
      for (std::size_t j = i; j < n && !held; ++j)
        for (std::size_t k = j; k < n && !held; ++k)
          held = inTriangle(p, others[i], others[j], others[k]);
    if (!held)
      out.push_back(p);
  }
  std::sort(out.begin(), out.end(), zyx);
  return out;
}

std::vector<LatticePoint> randomPoints(std::mt19937& rng, int count, std::int64_t extent)
{
  std::uniform_int_distribution<std::int64_t> coordinate(-extent, extent);
  std::vector<LatticePoint> points;
  for (int k = 0; k < count; ++k)
    points.push_back({ coordinate(rng), coordinate(rng), coordinate(rng) });
  std::sort(points.begin(), points.end(), zyx);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

/// Point sets whose slices or whole hull are degenerate, in (z, y, x) order.
std::vector<std::vector<LatticePoint>> degenerateSets()
{
  std::vector<std::vector<LatticePoint>> sets;
  sets.push_back({ { 3, -2, 5 } });                                             // one point
  sets.push_back({ { -4, 1, 0 }, { -3, 1, 0 }, { 0, 1, 0 }, { 6, 1, 0 } });     // one row
  sets.push_back({ { 2, -1, -3 }, { 2, -1, -2 }, { 2, -1, 0 }, { 2, -1, 4 } }); // a column
  std::vector<LatticePoint> diagonal, diagonals, plane, wedge, twoRows, steps;
  for (std::int64_t k = -3; k <= 4; ++k)
  {
    diagonal.push_back({ k, 2 * k, 1 }); // collinear, one slice
    plane.push_back({ k % 3, k, 0 });
    for (std::int64_t z = 0; z < 3; ++z)
      diagonals.push_back({ 2 * k + z, k, z }); // each slice collinear, solid hull
  }
  for (std::int64_t z = -2; z <= 2; ++z)
    for (std::int64_t x = -2; x <= 2; ++x)
      wedge.push_back({ x, z, z }); // each slice one row, flat hull
  for (std::int64_t x = 0; x < 5; ++x)
    for (std::int64_t y : { 0, 3 })
      twoRows.push_back({ x, y, 7 });
  for (std::int64_t z = 0; z < 4; ++z)
    for (std::int64_t y = 0; y <= z; ++y)
      steps.push_back({ y - z, y, z }); // one point per row, collinear slices
  for (auto* s : { &diagonal, &diagonals, &plane, &wedge, &twoRows, &steps })
  {
    std::sort(s->begin(), s->end(), zyx);
    sets.push_back(*s);
  }
  // Small sets whose slices hold two or three points.
  std::mt19937 rng(5);
  for (int k = 0; k < 200; ++k)
    sets.push_back(randomPoints(rng, 2 + k % 5, 1));
  return sets;
}

TEST(ConvexHullModifierInternals, SliceCornersAreThePolygonsCorners)
{
  std::vector<std::vector<LatticePoint>> sets = degenerateSets();
  for (unsigned seed = 0; seed < 300; ++seed)
  {
    std::mt19937 rng(seed);
    sets.push_back(randomPoints(rng, 4 + static_cast<int>(seed % 60), 1 + seed % 5));
  }
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    std::vector<LatticePoint> corners = vbr::detail::sliceCorners(sets[s]);
    std::sort(corners.begin(), corners.end(), zyx);
    ASSERT_EQ(corners, cornersByTriangles(sets[s])) << "set " << s;
  }
}

void expectSameHull(const vbr::CellList& got, const vbr::CellList& want, const std::string& what)
{
  ASSERT_EQ(got.dimension, want.dimension) << what;
  if (got.dimension == 3)
  {
    // A solid hull's cell list depends only on its polytope.
    EXPECT_EQ(got.vertices, want.vertices) << what;
    EXPECT_EQ(got.faces, want.faces) << what;
    EXPECT_EQ(got.planes, want.planes) << what;
    EXPECT_EQ(got.edges, want.edges) << what;
    return;
  }
  std::vector<LatticePoint> a = got.vertices, b = want.vertices;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b) << what;
}

TEST(ConvexHullModifierInternals, GroupShapeIsTheHullOfAllPoints)
{
  std::vector<std::vector<LatticePoint>> sets = degenerateSets();
  for (unsigned seed = 0; seed < 150; ++seed)
  {
    std::mt19937 rng(1000 + seed);
    // Sparse sets, and dense blobs whose rows are long runs with many points inside.
    if (seed % 2 == 0)
      sets.push_back(randomPoints(rng, 4 + static_cast<int>(seed % 40), 2 + seed % 4));
    else
    {
      std::vector<LatticePoint> blob;
      const std::int64_t r2 = 4 + seed % 30;
      std::bernoulli_distribution keep(0.7);
      for (std::int64_t z = -6; z <= 6; ++z)
        for (std::int64_t y = -6; y <= 6; ++y)
          for (std::int64_t x = -6; x <= 6; ++x)
            if (x * x + 2 * y * y + 3 * z * z + x * y <= r2 && keep(rng))
              blob.push_back({ x, y, z });
      sets.push_back(blob);
    }
  }
  for (vbr::CoplanarFaces mode :
    { vbr::CoplanarFaces::Extension, vbr::CoplanarFaces::Visible, vbr::CoplanarFaces::Invisible })
    for (std::size_t s = 0; s < sets.size(); ++s)
    {
      if (sets[s].empty())
        continue;
      // The group's points in any order: shuffled, as merged groups come.
      std::vector<LatticePoint> points = sets[s];
      std::mt19937 rng(static_cast<unsigned>(s));
      std::shuffle(points.begin(), points.end(), rng);
      const std::string what =
        "set " + std::to_string(s) + " mode " + std::to_string(static_cast<int>(mode));
      expectSameHull(vbr::detail::groupShape(points, mode), vbr::convexHull(sets[s], mode), what);
      if (::testing::Test::HasFatalFailure())
        return;
    }
}

/// Whether the centre (x, y, z) lies in one of the balls (centre and radius).
bool inAnyBall(const std::vector<std::array<double, 4>>& balls, double x, double y, double z)
{
  for (const auto& b : balls)
    if ((x - b[0]) * (x - b[0]) + (y - b[1]) * (y - b[1]) + (z - b[2]) * (z - b[2]) <= b[3] * b[3])
      return true;
  return false;
}

/// Objects of random density (noise), or the union of a few balls (holes and handles between
/// them), so that H has pits, voids and several shells. The balls are drawn in both modes, so
/// that each volume of a sequence stays the one it was.
vbr::BitVolume randomObjects(std::mt19937& rng, std::int32_t n)
{
  vbr::BitVolume v(n, n, n);
  std::uniform_real_distribution<double> at(0.0, n), radius(1.5, n / 3.0), unit(0.0, 1.0);
  const bool noise = rng() % 2 == 0;
  const double density = 0.05 + 0.9 * unit(rng);
  std::vector<std::array<double, 4>> balls(2 + rng() % 4);
  for (auto& b : balls)
    b = { at(rng), at(rng), at(rng), radius(rng) };
  for (std::int32_t z = 0; z < n; ++z)
    for (std::int32_t y = 0; y < n; ++y)
      for (std::int32_t x = 0; x < n; ++x)
        if (noise ? unit(rng) < density : inAnyBall(balls, x, y, z))
          v.set(x, y, z);
  return v;
}

} // namespace

// The side of H of the lattice points of a box, located as the joins locate a prism's points
// (against the triangles that can reach the box only), against what H must give when it
// separates: 0 on H (its lattice points, listed by latticePointsOnSurface), else inside for an
// object centre and outside for a background centre or a point off the grid. Boxes of every
// size, in and about the grid, so that most triangles of H are left out of many of them.
TEST(ConvexHullModifierInternals, SidesInABoxAreTheVoxelClasses)
{
  std::mt19937 rng(2027);
  std::size_t located = 0;
  for (int trial = 0; trial < 24; ++trial)
  {
    const std::int32_t n = 6 + static_cast<std::int32_t>(rng() % 9);
    const vbr::BitVolume v = randomObjects(rng, n);
    const vbr::ModifiedHull h = vbr::modifyConvexHull(v);
    if (!h.complete || h.surface.triangles.empty())
      continue;
    std::vector<LatticePoint> on = vbr::latticePointsOnSurface(h.surface, v.dims());
    std::sort(on.begin(), on.end());
    std::uniform_int_distribution<std::int64_t> corner(-2, n + 1);
    for (int b = 0; b < 12; ++b)
    {
      LatticePoint lo{ corner(rng), corner(rng), corner(rng) }, hi{};
      for (int k = 0; k < 3; ++k)
      {
        const std::int64_t other = b == 0 ? (k == 0 ? n + 1 : -2) : corner(rng);
        hi[k] = std::max(lo[k], other);
        lo[k] = std::min(lo[k], other);
      }
      const std::vector<int> sides = vbr::detail::sidesInBox(h.surface, lo, hi);
      std::size_t i = 0;
      for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
          for (std::int64_t x = lo[0]; x <= hi[0]; ++x, ++i)
          {
            const LatticePoint p{ x, y, z };
            const int want = std::binary_search(on.begin(), on.end(), p) ? 0
              : classAt(v, x, y, z)                                      ? 1
                                                                         : -1;
            ASSERT_EQ(sides[i], want)
              << "trial " << trial << " box " << b << " at " << x << "," << y << "," << z;
          }
      located += sides.size();
    }
  }
  EXPECT_GT(located, 10000u);
}
