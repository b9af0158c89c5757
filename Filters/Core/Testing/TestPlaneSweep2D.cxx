// The 2D plane sweep: the paper's worked example and random images against brute force.
#include "BRep.h"
#include "BruteForce.h"
#include "EVM.h"
#include "PlaneSweep2D.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace
{

using Corners = std::vector<vbr::Point2>;

/// The 2D EVM of Fig. 5 of Ayala & Vergara, written from its cuts x = 2 ... 18 (brinks in y).
std::vector<vbr::Vertex> paperFigure5()
{
  const std::vector<std::pair<int, std::vector<int>>> cuts = { { 2, { 2, 18 } },
    { 4, { 4, 16 } },
    { 6, { 6, 15, 16, 18 } },
    { 8, { 7, 11, 12, 14 } },
    { 10, { 8, 10 } },
    { 12, { 8, 10, 12, 14 } },
    { 14, { 7, 11 } },
    { 16, { 7, 18 } },
    { 18, { 2, 4, 6, 7, 15, 18 } } };
  std::vector<vbr::Vertex> v;
  for (const auto& c : cuts)
    for (int y : c.second)
      v.push_back({ 0, c.first, y });
  return v;
}

/// A loop as a cyclic sequence starting at its smallest corner, for comparison.
Corners canonical(Corners c)
{
  auto smallest = std::min_element(c.begin(),
    c.end(),
    [](const vbr::Point2& a, const vbr::Point2& b)
    { return std::tie(a.u, a.v) < std::tie(b.u, b.v); });
  std::rotate(c.begin(), smallest, c.end());
  return c;
}

Corners corners(std::initializer_list<std::pair<int, int>> l)
{
  Corners c;
  for (const auto& p : l)
    c.push_back({ p.first, p.second });
  return c;
}

int findLoop(const vbr::Boundary2D& b, const Corners& expected)
{
  for (std::size_t l = 0; l < b.loops.size(); ++l)
    if (canonical(b.loopPoints(static_cast<int>(l))) == canonical(expected))
      return static_cast<int>(l);
  return -1;
}

} // namespace

TEST(PlaneSweep2D, PaperFigure5SplitsTheNonManifoldFace)
{
  const auto v = paperFigure5();
  const vbr::Boundary2D b = vbr::planeSweep2D(v.data(), v.data() + v.size());
  EXPECT_EQ(b.nonManifoldVertices, 1u); // (16, 15)
  ASSERT_EQ(b.faces.size(), 4u);        // r1, r3, r2 (split at the vertex) and r6
  ASSERT_EQ(b.loops.size(), 6u);
  // Outer loops counter-clockwise, holes clockwise (face on the left).
  const int r1 = findLoop(b,
    corners(
      { { 2, 2 }, { 18, 2 }, { 18, 4 }, { 4, 4 }, { 4, 16 }, { 6, 16 }, { 6, 18 }, { 2, 18 } }));
  const int r3 =
    findLoop(b, corners({ { 6, 6 }, { 18, 6 }, { 18, 7 }, { 16, 7 }, { 16, 15 }, { 6, 15 } }));
  const int r2 = findLoop(b, corners({ { 16, 15 }, { 18, 15 }, { 18, 18 }, { 16, 18 } }));
  const int r4 = findLoop(b, corners({ { 8, 7 }, { 8, 11 }, { 14, 11 }, { 14, 7 } }));
  const int r5 = findLoop(b, corners({ { 8, 12 }, { 8, 14 }, { 12, 14 }, { 12, 12 } }));
  const int r6 = findLoop(b, corners({ { 10, 8 }, { 12, 8 }, { 12, 10 }, { 10, 10 } }));
  for (int l : { r1, r2, r3, r4, r5, r6 })
    ASSERT_GE(l, 0);
  EXPECT_TRUE(b.loops[r4].hole);
  EXPECT_TRUE(b.loops[r5].hole);
  for (int l : { r1, r2, r3, r6 })
    EXPECT_FALSE(b.loops[l].hole);
  const vbr::Face2D& f3 = b.faces[b.loops[r3].face];
  EXPECT_EQ(b.loops[r4].face, b.loops[r3].face);
  EXPECT_EQ(b.loops[r5].face, b.loops[r3].face);
  EXPECT_EQ(f3.holeLoops.size(), 2u);
  EXPECT_EQ(f3.parent, -1);
  const vbr::Face2D& f6 = b.faces[b.loops[r6].face];
  EXPECT_EQ(f6.parent, b.loops[r3].face); // r6 lies in hole r4 of r3
  EXPECT_EQ(f6.depth, 2);
  EXPECT_EQ(b.faces[b.loops[r1].face].depth, 0);
  EXPECT_EQ(b.faces[b.loops[r2].face].depth, 0);
  // Faces are numbered in order of first appearance in the sweep: r1, r3, r6, r2.
  EXPECT_EQ(b.loops[r1].face, 0);
  EXPECT_EQ(b.loops[r3].face, 1);
  EXPECT_EQ(b.loops[r6].face, 2);
  EXPECT_EQ(b.loops[r2].face, 3);
}

TEST(PlaneSweep2D, PaperFigure5KeepsTheNonManifoldFaceWhenMerging)
{
  const auto v = paperFigure5();
  const vbr::Boundary2D b =
    vbr::planeSweep2D(v.data(), v.data() + v.size(), vbr::FaceConnectivity::Vertex);
  ASSERT_EQ(b.faces.size(), 3u);
  // r3 and r2 form one face whose outer loop passes twice through the vertex (16, 15).
  const int merged = findLoop(b,
    corners({ { 6, 6 },
      { 18, 6 },
      { 18, 7 },
      { 16, 7 },
      { 16, 15 },
      { 18, 15 },
      { 18, 18 },
      { 16, 18 },
      { 16, 15 },
      { 6, 15 } }));
  ASSERT_GE(merged, 0);
  EXPECT_EQ(b.faces[b.loops[merged].face].holeLoops.size(), 2u);
}

TEST(PlaneSweep2D, RejectsInvalidEVM)
{
  const std::vector<vbr::Vertex> odd = { { 0, 0, 0 }, { 0, 0, 1 }, { 0, 0, 2 } };
  EXPECT_THROW(vbr::planeSweep2D(odd.data(), odd.data() + odd.size()), std::invalid_argument);
  const std::vector<vbr::Vertex> open = { { 0, 0, 0 }, { 0, 0, 1 } };
  EXPECT_THROW(vbr::planeSweep2D(open.data(), open.data() + open.size()), std::invalid_argument);
  EXPECT_TRUE(vbr::planeSweep2D(nullptr, nullptr).faces.empty());
}

namespace
{

/// Inclusion tree: A is an ancestor of B when B lies in a bounded component of the
/// complement of A; the parent is the innermost ancestor and the depth twice their count.
void checkInclusionTree(const vbr::BRep& brep,
  const std::vector<bf::PixelSet>& expected,
  const std::vector<int>& faceOf)
{
  const std::size_t n = expected.size();
  std::vector<std::vector<int>> ancestors(n);
  for (std::size_t a = 0; a < n; ++a)
  {
    for (const auto& entry : bf::complementComponents(expected[a]))
    {
      if (!entry.second)
        continue;
      const bf::PixelSet& c = entry.first;
      for (std::size_t b = 0; b < n; ++b)
        if (b != a && c.count(*expected[b].begin()))
          ancestors[b].push_back(static_cast<int>(a));
    }
  }
  for (std::size_t f = 0; f < brep.faces.size(); ++f)
  {
    const int e = faceOf[f];
    const vbr::BRepFace& face = brep.faces[f];
    EXPECT_EQ(face.depth, 2 * static_cast<int>(ancestors[e].size())) << "face " << f;
    if (ancestors[e].empty())
    {
      EXPECT_EQ(face.parent, -1);
      continue;
    }
    ASSERT_GE(face.parent, 0);
    const int innermost = *std::max_element(ancestors[e].begin(),
      ancestors[e].end(),
      [&](int x, int y) { return ancestors[x].size() < ancestors[y].size(); });
    EXPECT_EQ(faceOf[face.parent], innermost) << "face " << f;
  }
}

/// Checks the faces, holes, orientation and inclusion tree of a 2D image's B-Rep against
/// brute force.
void checkFaces(const vbr::BitVolume& image, const vbr::BRep& brep, bool merged)
{
  bf::PixelSet pixels;
  for (int y = 0; y < image.size(1); ++y)
    for (int x = 0; x < image.size(0); ++x)
      if (image.get(x, y, 0))
        pixels.insert({ x, y });
  const auto expected = bf::components(pixels, merged);
  ASSERT_EQ(brep.faces.size(), expected.size());

  // Match every output face to an expected component by its exact pixels.
  std::map<bf::PixelSet, int> index;
  for (std::size_t i = 0; i < expected.size(); ++i)
    index[expected[i]] = static_cast<int>(i);
  std::vector<int> faceOf(brep.faces.size());
  for (std::size_t f = 0; f < brep.faces.size(); ++f)
  {
    auto it = index.find(bf::rasterize(brep, static_cast<int>(f)));
    ASSERT_NE(it, index.end()) << "face " << f << " does not cover one component exactly";
    faceOf[f] = it->second;
    const vbr::BRepFace& face = brep.faces[f];
    EXPECT_EQ(face.loopCount - 1, bf::holeCount(it->first)) << "face " << f;
    for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
    {
      const long long area = bf::doubledSignedArea(brep, l);
      EXPECT_EQ(brep.loops[l].hole, l != face.firstLoop);
      EXPECT_EQ(area > 0, !brep.loops[l].hole) << "loop " << l << " area " << area;
    }
  }

  checkInclusionTree(brep, expected, faceOf);
}

/// The grid points (x, y, 0) where a loop turns, by brute force: their four pixels hold an odd
/// count of the image's pixels, or two diagonal ones (a non-manifold vertex).
std::vector<vbr::Point3> cornersOf(const vbr::BitVolume& image)
{
  std::vector<vbr::Point3> corners;
  for (int x = 0; x <= image.size(0); ++x)
    for (int y = 0; y <= image.size(1); ++y)
    {
      const bool a = bf::voxel(image, x - 1, y - 1, 0), b = bf::voxel(image, x, y - 1, 0);
      const bool c = bf::voxel(image, x - 1, y, 0), d = bf::voxel(image, x, y, 0);
      if ((a != b) != (c != d) || (a == d && b == c && a != b))
        corners.push_back({ x, y, 0 }); // in (x, y, z) order: sorted as keys compare
    }
  return corners;
}

/// extractNumberedBoundary2D on an EVM sorted in `order`: the faces pass checkFaces, the
/// corners are those of brute force in the order of their keys, and the numbers of every
/// loop's corners name its points.
void checkNumbered(const vbr::BitVolume& image, bool merged, const char* order)
{
  SCOPED_TRACE(order);
  const vbr::EVM evm = vbr::extractEVM2D(image).sortedAs(vbr::axisOrderFromName(order));
  const auto connectivity = merged ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge;
  const vbr::NumberedBRep n = vbr::extractNumberedBoundary2D(evm, connectivity, true);
  checkFaces(image, n.brep, merged);
  EXPECT_EQ(n.corners, cornersOf(image));
  ASSERT_EQ(n.numbers.size(), n.brep.points.size());
  for (std::size_t i = 0; i < n.numbers.size(); ++i)
  {
    ASSERT_LT(static_cast<std::size_t>(n.numbers[i]), n.corners.size());
    EXPECT_EQ(n.corners[n.numbers[i]], n.brep.points[i]) << "corner " << i;
  }
  // The same faces, loops and corners as extractBoundary2D's, which the filters relied on.
  const vbr::BRep b = vbr::extractBoundary2D(evm, connectivity);
  EXPECT_EQ(n.brep.points, b.points);
  ASSERT_EQ(n.brep.faces.size(), b.faces.size());
  for (std::size_t f = 0; f < b.faces.size(); ++f)
  {
    EXPECT_EQ(n.brep.faces[f].parent, b.faces[f].parent);
    EXPECT_EQ(n.brep.faces[f].loopCount, b.faces[f].loopCount);
  }
  const vbr::NumberedBRep bare = vbr::extractNumberedBoundary2D(evm, connectivity, false);
  EXPECT_TRUE(bare.brep.points.empty());
  EXPECT_EQ(bare.numbers, n.numbers);
}

/// Checks a 2D image's faces from extractBoundary2D and extractNumberedBoundary2D.
void checkImage(const vbr::BitVolume& image, bool merged)
{
  checkFaces(image,
    vbr::extractBoundary2D(vbr::extractEVM2D(image),
      merged ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge),
    merged);
  checkNumbered(image, merged, "ZYX"); // corners numbered across the sweep's lines
  checkNumbered(image, merged, "ZXY"); // corners numbered along them
}

} // namespace

TEST(PlaneSweep2D, RandomImagesMatchBruteForce)
{
  unsigned seed = 1000;
  for (int trial = 0; trial < 40; ++trial)
  {
    const vbr::Point3 d{ 4 + (trial * 7) % 37, 3 + (trial * 5) % 29, 1 };
    const double density = 0.15 + 0.7 * (trial % 10) / 9.0;
    const vbr::BitVolume image = bf::randomVolume(d, density, seed++);
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    checkImage(image, false);
    checkImage(image, true);
  }
}

namespace
{

/// Whether two boundaries are the same: faces, loops, corners and the non-manifold count.
void expectSameBoundary(const vbr::Boundary2D& a, const vbr::Boundary2D& b)
{
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (std::size_t f = 0; f < a.faces.size(); ++f)
  {
    EXPECT_EQ(a.faces[f].outerLoop, b.faces[f].outerLoop);
    EXPECT_EQ(a.faces[f].holeLoops, b.faces[f].holeLoops);
    EXPECT_EQ(a.faces[f].parent, b.faces[f].parent);
    EXPECT_EQ(a.faces[f].depth, b.faces[f].depth);
  }
  ASSERT_EQ(a.loops.size(), b.loops.size());
  for (std::size_t l = 0; l < a.loops.size(); ++l)
  {
    EXPECT_EQ(a.loops[l].begin, b.loops[l].begin);
    EXPECT_EQ(a.loops[l].end, b.loops[l].end);
    EXPECT_EQ(a.loops[l].face, b.loops[l].face);
    EXPECT_EQ(a.loops[l].hole, b.loops[l].hole);
  }
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t k = 0; k < a.points.size(); ++k)
    EXPECT_TRUE(a.points[k].u == b.points[k].u && a.points[k].v == b.points[k].v) << k;
  EXPECT_EQ(a.nonManifoldVertices, b.nonManifoldVertices);
}

} // namespace

TEST(PlaneSweep2D, SweeperKeptFromPlaneToPlaneSweepsAsAFreshOne)
{
  // One PlaneSweeper2D per connectivity sweeps random images larger and smaller than the one
  // before (its arrays kept from either), the empty image, and sweeps on after an invalid EVM
  // threw midway (its last line dropped: the last section is not empty): every boundary equals
  // planeSweep2D's from scratch.
  unsigned seed = 3000;
  for (const auto connectivity : { vbr::FaceConnectivity::Edge, vbr::FaceConnectivity::Vertex })
  {
    vbr::PlaneSweeper2D sweeper(connectivity);
    for (int trial = 0; trial < 36; ++trial)
    {
      SCOPED_TRACE(testing::Message()
        << "trial " << trial << " merged " << (connectivity == vbr::FaceConnectivity::Vertex));
      const bool large = trial % 3 != 1;
      const vbr::Point3 d{ large ? 30 + (trial * 7) % 23 : 3 + trial % 5,
        large ? 20 + (trial * 5) % 19 : 2 + trial % 4,
        1 };
      const double density = 0.2 + 0.6 * (trial % 7) / 6.0;
      const vbr::EVM evm = vbr::extractEVM2D(bf::randomVolume(d, density, seed++));
      const std::vector<vbr::Vertex>& v = evm.vertices();
      if (trial % 6 == 5 && !v.empty())
      {
        std::size_t lastLine = v.size() - 1;
        while (lastLine > 0 && v[lastLine - 1][1] == v.back()[1])
          --lastLine;
        EXPECT_THROW(sweeper.sweep(v.data(), v.data() + lastLine), std::invalid_argument);
      }
      expectSameBoundary(sweeper.sweep(v.data(), v.data() + v.size()),
        vbr::planeSweep2D(v.data(), v.data() + v.size(), connectivity));
      if (trial % 9 == 8)
        EXPECT_TRUE(sweeper.sweep(nullptr, nullptr).faces.empty());
    }
  }
}

TEST(PlaneSweep2D, ManyBarsTouchedHereAndThere)
{
  // Vertical bars make a section of many intervals; a few pixels added beside them or cut out
  // of them touch one or two of those intervals per line, so that the sweep passes long and
  // short runs of untouched intervals (found by galloping and bisection) between them.
  unsigned state = 7;
  const auto next = [&state](int n)
  {
    state = state * 1103515245u + 12345u;
    return static_cast<int>((state >> 8) % static_cast<unsigned>(n));
  };
  for (int trial = 0; trial < 12; ++trial)
  {
    const int nx = 60 + 17 * trial, ny = 24;
    vbr::BitVolume image(nx, ny, 1);
    for (int y = 1; y + 1 < ny; ++y)
      for (int x = 0; x < nx; x += 3)
        image.set(x, y, 0);
    for (int k = 0; k < 4 + trial; ++k)
    {
      const int x = next(nx), y = 1 + next(ny - 2);
      image.set(x, y, 0, x % 3 != 0); // a pixel beside a bar, or a bar broken
    }
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    checkImage(image, false);
    checkImage(image, true);
  }
}

TEST(PlaneSweep2D, NestedRingsAndDegenerateImages)
{
  // Concentric square rings: faces and holes alternate down to depth 8.
  vbr::BitVolume rings(19, 19, 1);
  for (int y = 0; y < 19; ++y)
    for (int x = 0; x < 19; ++x)
      if (std::max(std::abs(x - 9), std::abs(y - 9)) % 2 == 0)
        rings.set(x, y, 0);
  checkImage(rings, false);
  const vbr::BRep b = vbr::extractBoundary2D(vbr::extractEVM2D(rings), vbr::FaceConnectivity::Edge);
  int deepest = 0;
  for (const auto& f : b.faces)
    deepest = std::max(deepest, f.depth);
  EXPECT_EQ(deepest, 8);

  vbr::BitVolume checker(9, 7, 1);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x)
      if ((x + y) % 2 == 0)
        checker.set(x, y, 0);
  checkImage(checker, false); // every pixel its own face
  checkImage(checker, true);  // one face with holes touching at corners

  vbr::BitVolume full = bf::randomVolume({ 5, 4, 1 }, 1.0, 1);
  checkImage(full, false);
  vbr::BitVolume empty(5, 4, 1);
  EXPECT_TRUE(
    vbr::extractBoundary2D(vbr::extractEVM2D(empty), vbr::FaceConnectivity::Edge).faces.empty());
  const vbr::NumberedBRep none =
    vbr::extractNumberedBoundary2D(vbr::extractEVM2D(empty), vbr::FaceConnectivity::Edge, true);
  EXPECT_TRUE(none.brep.faces.empty() && none.corners.empty() && none.numbers.empty());
}

namespace
{

/// The corners of a sweep in the order (v, u), (u, v) listed in the order of their numbers.
std::vector<std::pair<vbr::Coord, vbr::Coord>> cornersInOrder(const vbr::Contours2D& c)
{
  std::vector<std::pair<vbr::Coord, vbr::Coord>> out;
  c.forEachCorner([&](vbr::Coord u, vbr::Coord v) { out.emplace_back(u, v); });
  return out;
}

/// Both ways of numbering the corners in the order (v, u) (by column before the sweep, forced
/// with fewestByColumn 0; sorted after it, forced with the largest count) give brute force's
/// corners, and the same numbers, loops and faces. Returns whether the first was numbered by column
/// (at least one vertex per word of the grid of columns).
bool checkColumnsAgainstSort(const vbr::BitVolume& image, vbr::FaceConnectivity connectivity)
{
  const vbr::EVM evm = vbr::extractEVM2D(image).sortedAs(vbr::axisOrderFromName("ZYX"));
  const auto& v = evm.vertices();
  const vbr::Contours2D byColumn = vbr::planeSweep2DNumbered(
    v.data(), v.data() + v.size(), vbr::CornerOrder::VThenU, connectivity, 0);
  const vbr::Contours2D sorted = vbr::planeSweep2DNumbered(v.data(),
    v.data() + v.size(),
    vbr::CornerOrder::VThenU,
    connectivity,
    std::numeric_limits<std::size_t>::max());
  EXPECT_TRUE(sorted.columns.count == 0 && !sorted.corners.empty());
  // Both against brute force: in the order ZYX, u is y and v is x, numbered by (x, y).
  std::vector<std::pair<vbr::Coord, vbr::Coord>> expected;
  for (const vbr::Point3& p : cornersOf(image))
    expected.emplace_back(p[1], p[0]);
  EXPECT_EQ(cornersInOrder(sorted), expected);
  EXPECT_EQ(cornersInOrder(byColumn), cornersInOrder(sorted));
  EXPECT_EQ(byColumn.loopCorners, sorted.loopCorners);
  EXPECT_EQ(byColumn.boundary.loops.size(), sorted.boundary.loops.size());
  for (std::size_t l = 0;
       l < std::min(byColumn.boundary.loops.size(), sorted.boundary.loops.size());
       ++l)
  {
    EXPECT_EQ(byColumn.boundary.loops[l].begin, sorted.boundary.loops[l].begin);
    EXPECT_EQ(byColumn.boundary.loops[l].face, sorted.boundary.loops[l].face);
    EXPECT_EQ(byColumn.boundary.loops[l].hole, sorted.boundary.loops[l].hole);
  }
  EXPECT_EQ(byColumn.boundary.faces.size(), sorted.boundary.faces.size());
  for (std::size_t f = 0;
       f < std::min(byColumn.boundary.faces.size(), sorted.boundary.faces.size());
       ++f)
    EXPECT_EQ(byColumn.boundary.faces[f].parent, sorted.boundary.faces[f].parent);
  return byColumn.corners.empty();
}

} // namespace

namespace
{

/// Whether two numbered sweeps are the same: the boundary, the corners by number (sorted or by
/// column, and the grid of columns), and the loops' corners.
void expectSameContours(const vbr::Contours2D& a, const vbr::Contours2D& b)
{
  expectSameBoundary(a.boundary, b.boundary);
  EXPECT_EQ(cornersInOrder(a), cornersInOrder(b));
  EXPECT_EQ(a.cornerCount(), b.cornerCount());
  EXPECT_EQ(a.corners.size(), b.corners.size());
  EXPECT_TRUE(a.columns.uLo == b.columns.uLo && a.columns.vLo == b.columns.vLo &&
    a.columns.columns == b.columns.columns &&
    a.columns.wordsPerColumn == b.columns.wordsPerColumn && a.columns.count == b.columns.count);
  EXPECT_EQ(a.columns.bits, b.columns.bits);
  EXPECT_EQ(a.loopCorners, b.loopCorners);
}

} // namespace

TEST(PlaneSweep2D, NumberedSweeperKeptFromUpdateToUpdateSweepsAsAFreshOne)
{
  // A NumberedPlaneSweeper2D sweeps random images that grow and shrink (its arrays kept from a
  // larger or a smaller sweep), in both corner orders, numbered by column (fewestByColumn 0)
  // and sorted, with the connectivity changing from sweep to sweep, the empty image, and
  // sweeps on after an invalid EVM threw midway (its last line dropped): every sweep equals
  // planeSweep2DNumbered's from scratch. Once with its memory released whenever an image has
  // fewer than a quarter of the largest one's vertices (fewestKept 0: the small images after
  // large ones), once never released (every small image swept in a large one's arrays).
  unsigned seed = 5000;
  for (const std::size_t fewestKept : { std::size_t(0), std::numeric_limits<std::size_t>::max() })
  {
    vbr::NumberedPlaneSweeper2D sweeper(fewestKept);
    for (int trial = 0; trial < 48; ++trial)
    {
      const auto connectivity =
        trial % 2 ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge;
      const bool alongV = (trial / 2) % 2 == 1;
      const std::size_t fewestByColumn =
        (trial / 4) % 2 ? std::numeric_limits<std::size_t>::max() : 0;
      const int size = trial % 5; // 0, 1, 2: large, growing; 3, 4: small, shrinking
      const vbr::Point3 d{ size < 3 ? 40 + 30 * size + trial % 7 : 9 - size + trial % 3,
        size < 3 ? 30 + 25 * size + trial % 5 : 6 - size + trial % 2,
        1 };
      const double density = 0.2 + 0.6 * (trial % 7) / 6.0;
      SCOPED_TRACE(testing::Message()
        << "trial " << trial << " kept from " << fewestKept << " size " << d[0] << " x " << d[1]
        << " along v " << alongV << " fewest by column " << fewestByColumn);
      const vbr::EVM evm = vbr::extractEVM2D(bf::randomVolume(d, density, seed++))
                             .sortedAs(vbr::axisOrderFromName(alongV ? "ZYX" : "ZXY"));
      const std::vector<vbr::Vertex>& v = evm.vertices();
      const vbr::CornerOrder order = alongV ? vbr::CornerOrder::VThenU : vbr::CornerOrder::UThenV;
      if (trial % 6 == 5 && !v.empty())
      {
        std::size_t lastLine = v.size() - 1;
        while (lastLine > 0 && v[lastLine - 1][1] == v.back()[1])
          --lastLine;
        EXPECT_THROW(
          sweeper.sweep(v.data(), v.data() + lastLine, order, connectivity, fewestByColumn),
          std::invalid_argument);
      }
      expectSameContours(
        sweeper.sweep(v.data(), v.data() + v.size(), order, connectivity, fewestByColumn),
        vbr::planeSweep2DNumbered(
          v.data(), v.data() + v.size(), order, connectivity, fewestByColumn));
      if (trial % 9 == 8)
      {
        const vbr::Contours2D& none = sweeper.sweep(nullptr, nullptr, order, connectivity);
        EXPECT_TRUE(
          none.boundary.faces.empty() && none.loopCorners.empty() && none.cornerCount() == 0);
      }
    }
  }
}

TEST(PlaneSweep2D, VerticesInTheMemoryKeptFromImageToImage)
{
  // extractEVM2D into the memory of the image before (NumberedPlaneSweeper2D::vertexMemory,
  // handed back by keepVertexMemory): images that grow and shrink, so that the memory holds
  // more or fewer old vertices than the new image has, give the same vertices and counts as
  // extractEVM2D into fresh memory; the memory is freed when it is more than four times what
  // the last image filled (from fewestKept values of room), kept otherwise.
  vbr::NumberedPlaneSweeper2D sweeper(64);
  unsigned seed = 7000;
  for (int trial = 0; trial < 24; ++trial)
  {
    // Growing, shrinking a little (old vertices left past the new ones) and much (freed).
    constexpr int Sizes[] = { 0, 1, 3, 2, 3, 1, 0, 2 };
    const int size = Sizes[trial % 8];
    const vbr::Point3 d{ 5 + 40 * size + trial % 3, 4 + 30 * size + trial % 5, 1 };
    SCOPED_TRACE(testing::Message() << "trial " << trial << " size " << d[0] << " x " << d[1]);
    const vbr::BitVolume pixels = bf::randomVolume(d, 0.2 + 0.1 * (trial % 6), seed++);
    vbr::PlanarCounts freshCounts, keptCounts;
    const vbr::EVM fresh = vbr::extractEVM2D(pixels, vbr::Execution(), &freshCounts);
    std::vector<vbr::Vertex>& memory = sweeper.vertexMemory();
    const std::size_t room = memory.capacity();
    vbr::EVM kept = vbr::extractEVM2D(pixels, vbr::Execution(), &keptCounts, &memory);
    EXPECT_TRUE(memory.empty() && memory.capacity() == 0); // taken by the EVM
    EXPECT_EQ(kept.vertices(), fresh.vertices());
    EXPECT_EQ(kept.order(), fresh.order());
    EXPECT_EQ(keptCounts.pixels, freshCounts.pixels);
    EXPECT_EQ(keptCounts.edges, freshCounts.edges);
    EXPECT_EQ(keptCounts.planes, freshCounts.planes);
    if (room >= fresh.size())
      EXPECT_GE(kept.vertices().capacity(), room); // written into the memory kept
    std::vector<vbr::Vertex> back = kept.takeVertices();
    const std::size_t n = back.size(), capacity = back.capacity();
    sweeper.keepVertexMemory(std::move(back));
    const bool freed = capacity >= 64 && n < capacity / 4;
    EXPECT_EQ(sweeper.vertexMemory().capacity(), freed ? 0 : capacity);
  }
  sweeper.release();
  EXPECT_EQ(sweeper.vertexMemory().capacity(), 0u);
}

TEST(PlaneSweep2D, NumberedCornersOfLargeDenseAndSparseImages)
{
  // Small images are numbered by the sort (FewestVerticesByColumn): the path by column is
  // forced here and compared with it, on images wider and taller than 64, with many
  // non-manifold vertices, and lines of 63, 64, 65, 128 and 129 pixels.
  for (const auto& size : std::vector<std::array<int, 2>>{
         { 150, 140 }, { 63, 65 }, { 64, 64 }, { 65, 63 }, { 128, 3 }, { 1, 129 }, { 129, 1 } })
    for (unsigned seed = 1; seed <= 2; ++seed)
    {
      SCOPED_TRACE(std::to_string(size[0]) + " x " + std::to_string(size[1]));
      const vbr::BitVolume image = bf::randomVolume({ size[0], size[1], 1 }, 0.5, 7100 + seed);
      const bool edge = checkColumnsAgainstSort(image, vbr::FaceConnectivity::Edge);
      const bool vertex = checkColumnsAgainstSort(image, vbr::FaceConnectivity::Vertex);
      if (size[0] == 150)
        EXPECT_TRUE(edge && vertex) << "a dense image numbered by column";
    }

  // Dense (more vertices than words in the grid of columns) but small: numbered by the sort
  // (FewestVerticesByColumn); wider and taller than 64 (several words a line and a column),
  // with many non-manifold vertices.
  for (unsigned seed = 1; seed <= 2; ++seed)
  {
    const vbr::BitVolume dense = bf::randomVolume({ 150, 140, 1 }, 0.5, 7000 + seed);
    checkNumbered(dense, false, "ZYX");
    checkNumbered(dense, true, "ZYX");
  }
  // Sparse: fewer vertices than grid words, the corners sorted by v after the sweep; two
  // rectangles, one inside the other's hole, and two pixels touching at a corner.
  vbr::BitVolume sparse(300, 200, 1);
  for (int y = 20; y < 180; ++y)
    for (int x = 10; x < 290; ++x)
      if (y < 30 || y >= 170 || x < 20 || x >= 280 || (y >= 90 && y < 100 && x >= 140 && x < 160))
        sparse.set(x, y, 0);
  sparse.set(200, 50, 0);
  sparse.set(201, 51, 0);
  checkNumbered(sparse, false, "ZYX");
  checkNumbered(sparse, true, "ZYX");
}

namespace
{

/// The bounds (uLo, vLo, uHi, vHi) of a loop's corners, from their numbers.
std::array<vbr::Coord, 4> loopBounds(const vbr::Contours2D& c,
  const std::vector<std::pair<vbr::Coord, vbr::Coord>>& corners,
  int loop)
{
  const vbr::Loop2D& l = c.boundary.loops[static_cast<std::size_t>(loop)];
  std::array<vbr::Coord, 4> b{ std::numeric_limits<vbr::Coord>::max(),
    std::numeric_limits<vbr::Coord>::max(),
    std::numeric_limits<vbr::Coord>::min(),
    std::numeric_limits<vbr::Coord>::min() };
  for (std::size_t i = l.begin; i < l.end; ++i)
  {
    const auto& p = corners[c.loopCorners[i]];
    b = { std::min(b[0], p.first),
      std::min(b[1], p.second),
      std::max(b[2], p.first),
      std::max(b[3], p.second) };
  }
  return b;
}

} // namespace

TEST(PlaneSweep2D, LoopsOfNestedRingsFromTheEdgeLinks)
{
  // R square rings one inside the other's hole: ring k covers the pixels at Chebyshev distance
  // 2k from the image's border. The domino step marks each edge's link with its loop, which
  // the second sweep reads back for every face's outer loop and the loop below it: ring k must
  // be the face of depth 2k, in ring k - 1's hole, its outer loop on [2k, N - 2k] and its one
  // hole on [2k + 1, N - 2k - 1] (closed form, both ways of numbering the corners).
  constexpr int R = 100, N = 4 * R;
  vbr::BitVolume image(N, N, 1);
  for (int y = 0; y < N; ++y)
    for (int x = 0; x < N; ++x)
      if (std::min(std::min(x, y), std::min(N - 1 - x, N - 1 - y)) % 2 == 0)
        image.set(x, y, 0);
  const vbr::EVM evm = vbr::extractEVM2D(image).sortedAs(vbr::axisOrderFromName("ZYX"));
  const auto& v = evm.vertices();
  for (const std::size_t fewest : { std::size_t(0), std::numeric_limits<std::size_t>::max() })
    for (const auto connectivity : { vbr::FaceConnectivity::Edge, vbr::FaceConnectivity::Vertex })
    {
      const vbr::Contours2D c = vbr::planeSweep2DNumbered(
        v.data(), v.data() + v.size(), vbr::CornerOrder::VThenU, connectivity, fewest);
      const auto corners = cornersInOrder(c);
      const vbr::Boundary2D& b = c.boundary;
      ASSERT_EQ(b.faces.size(), static_cast<std::size_t>(R));
      ASSERT_EQ(b.loops.size(), static_cast<std::size_t>(2 * R));
      for (std::size_t f = 0; f < b.faces.size(); ++f)
      {
        const vbr::Face2D& face = b.faces[f];
        const int k = face.depth / 2;
        SCOPED_TRACE(testing::Message() << "face " << f << " depth " << face.depth);
        ASSERT_TRUE(face.depth % 2 == 0 && k < R);
        EXPECT_EQ(face.parent < 0, k == 0);
        if (face.parent >= 0)
          EXPECT_EQ(b.faces[static_cast<std::size_t>(face.parent)].depth, face.depth - 2);
        ASSERT_GE(face.outerLoop, 0);
        EXPECT_EQ(b.loops[static_cast<std::size_t>(face.outerLoop)].face, static_cast<int>(f));
        EXPECT_FALSE(b.loops[static_cast<std::size_t>(face.outerLoop)].hole);
        const std::array<vbr::Coord, 4> outer{ 2 * k, 2 * k, N - 2 * k, N - 2 * k };
        EXPECT_EQ(loopBounds(c, corners, face.outerLoop), outer);
        ASSERT_EQ(face.holeLoops.size(), 1u);
        const int hole = face.holeLoops[0];
        EXPECT_TRUE(b.loops[static_cast<std::size_t>(hole)].hole);
        EXPECT_EQ(b.loops[static_cast<std::size_t>(hole)].face, static_cast<int>(f));
        const std::array<vbr::Coord, 4> inner{ 2 * k + 1, 2 * k + 1, N - 2 * k - 1, N - 2 * k - 1 };
        EXPECT_EQ(loopBounds(c, corners, hole), inner);
      }
    }
}
