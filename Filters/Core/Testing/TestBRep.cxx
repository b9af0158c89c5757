// 3D EVM -> B-Rep: faces, holes, orientation, closedness, triangulation and round trip,
// each checked against brute force on random volumes (sparse to dense, many non-manifold
// contacts) and degenerate ones.
#include "BRep.h"
#include "BruteForce.h"
#include "EVM.h"
#include "FaceTriangulator.h"
#include "PlaneSweep3D.h"
#include "PopCount.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

namespace
{

using Segment = std::pair<vbr::Point3, vbr::Point3>;

/// Every loop edge cut into unit segments, directed. A closed, consistently oriented surface
/// uses each unit segment as often in one direction as in the other.
std::map<Segment, int> unitSegments(const vbr::BRep& brep)
{
  std::map<Segment, int> count;
  for (std::size_t l = 0; l < brep.loops.size(); ++l)
  {
    const auto points = brep.loopPoints(static_cast<int>(l));
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      vbr::Point3 p = points[i];
      const vbr::Point3 q = points[(i + 1) % points.size()];
      int d = 0;
      while (d < 3 && p[d] == q[d])
        ++d;
      EXPECT_LT(d, 3) << "repeated corner";
      for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(k == d || p[k] == q[k]) << "edge not axis-parallel";
      if (d == 3)
        continue;
      const int step = q[d] > p[d] ? 1 : -1;
      while (p != q)
      {
        vbr::Point3 n = p;
        n[d] += step;
        ++count[{ p, n }];
        p = n;
      }
    }
  }
  return count;
}

/// Faces: exactly the connected regions of equally oriented surfels of each plane.
void checkFaces(const vbr::BitVolume& v, const vbr::BRep& brep, bool merged)
{
  const auto expected = bf::expectedFaces(v, merged);
  std::map<bf::PlaneKey, std::vector<bf::PixelSet>> produced;
  long long area = 0;
  std::array<long long, 3> volume{ 0, 0, 0 };
  for (std::size_t f = 0; f < brep.faces.size(); ++f)
  {
    const vbr::BRepFace& face = brep.faces[f];
    const bf::PixelSet pixels = bf::rasterize(brep, static_cast<int>(f));
    produced[{ face.axis, face.normalSign, face.position }].push_back(pixels);
    EXPECT_EQ(face.loopCount - 1, bf::holeCount(pixels)) << "face " << f;
    for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
    {
      // Outer loops counter-clockwise seen from outside, holes the other way.
      const long long a = bf::doubledSignedArea(brep, l) * face.normalSign;
      EXPECT_EQ(a > 0, !brep.loops[l].hole) << "face " << f << " loop " << l;
      EXPECT_EQ(brep.loops[l].face, static_cast<int>(f));
    }
    area += static_cast<long long>(pixels.size());
    // Divergence theorem per axis: sum of normal * position * area is the volume.
    volume[face.axis] += static_cast<long long>(face.normalSign) * face.position * pixels.size();
  }
  for (auto& entry : produced)
    std::sort(entry.second.begin(), entry.second.end());
  auto sortedExpected = expected;
  for (auto& entry : sortedExpected)
    std::sort(entry.second.begin(), entry.second.end());
  EXPECT_EQ(produced, sortedExpected);
  long long surfels = 0;
  for (const auto& entry : expected)
    for (const auto& c : entry.second)
      surfels += static_cast<long long>(c.size());
  EXPECT_EQ(area, surfels);
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(volume[a], static_cast<long long>(v.count()));
}

/// Round trip: a voxel is inside when an odd number of x-faces lie before it on its row.
void checkRoundTrip(const vbr::BitVolume& v, const vbr::BRep& brep)
{
  vbr::BitVolume back(v.size(0), v.size(1), v.size(2));
  std::map<std::pair<int, int>, std::vector<int>> crossings; // (y, z) -> x positions
  for (std::size_t f = 0; f < brep.faces.size(); ++f)
    if (brep.faces[f].axis == 0)
      for (const auto& p : bf::rasterize(brep, static_cast<int>(f)))
        crossings[{ p.first, p.second }].push_back(brep.faces[f].position);
  for (auto& entry : crossings)
  {
    auto& xs = entry.second;
    std::sort(xs.begin(), xs.end());
    ASSERT_EQ(xs.size() % 2, 0u);
    for (std::size_t k = 0; k < xs.size(); k += 2)
      for (int x = xs[k]; x < xs[k + 1]; ++x)
        back.set(x, entry.first.first, entry.first.second);
  }
  EXPECT_EQ(back, v);
}

/// Closed and consistently oriented: every unit segment matched by as many reversed ones.
void checkClosed(const vbr::BRep& brep)
{
  const auto segments = unitSegments(brep);
  for (const auto& entry : segments)
  {
    auto it = segments.find({ entry.first.second, entry.first.first });
    ASSERT_NE(it, segments.end());
    EXPECT_EQ(it->second, entry.second);
  }
}

/// Triangles: no T-junctions left, so every triangle edge is matched by reversed edges;
/// the triangles of a face cover exactly its area.
void checkTriangles(const vbr::BRep& brep)
{
  std::map<Segment, int> edges;
  for (std::size_t f = 0; f < brep.faces.size(); ++f)
  {
    const vbr::BRepFace& face = brep.faces[f];
    std::vector<vbr::Point3> corner;
    for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
    {
      const auto points = brep.loopPoints(l);
      corner.insert(corner.end(), points.begin(), points.end());
    }
    long long doubled = 0;
    const int u = (face.axis + 1) % 3, w = (face.axis + 2) % 3;
    for (const auto& t : vbr::triangulateFace(brep, static_cast<int>(f)))
    {
      const vbr::Point3 &a = corner[t[0]], &b = corner[t[1]], &c = corner[t[2]];
      const long long cross = static_cast<long long>(b[u] - a[u]) * (c[w] - a[w]) -
        static_cast<long long>(b[w] - a[w]) * (c[u] - a[u]);
      EXPECT_GT(cross * face.normalSign, 0) << "triangle oriented inwards or degenerate";
      doubled += cross * face.normalSign;
      ++edges[{ a, b }];
      ++edges[{ b, c }];
      ++edges[{ c, a }];
    }
    EXPECT_EQ(doubled, 2 * static_cast<long long>(bf::rasterize(brep, static_cast<int>(f)).size()));
  }
  for (const auto& entry : edges)
  {
    auto it = edges.find({ entry.first.second, entry.first.first });
    ASSERT_NE(it, edges.end()) << "boundary edge in the triangle mesh";
    EXPECT_EQ(it->second, entry.second);
  }
}

/// Checks everything about the boundary of `v` (each step stops the checks on a fatal
/// failure, as one function would).
void checkVolume(const vbr::BitVolume& v, bool merged)
{
  const vbr::EVM evm = vbr::extractEVM(v);
  vbr::BRep brep;
  ASSERT_TRUE(vbr::planeSweep3D(evm,
    merged ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge,
    vbr::Execution(),
    brep));
  checkFaces(v, brep, merged);
  checkRoundTrip(v, brep);
  if (::testing::Test::HasFatalFailure())
    return;
  // Before and after inserting T-junction vertices.
  checkClosed(brep);
  if (::testing::Test::HasFatalFailure())
    return;
  vbr::insertTJunctionVertices(brep);
  checkClosed(brep);
  if (::testing::Test::HasFatalFailure())
    return;
  checkTriangles(brep);
}

/// The loops with the corners of all loops that lie strictly inside their edges inserted in
/// order, found by brute force: the corners of every line of the grid in a set.
std::vector<std::vector<vbr::Point3>> loopsWithEdgeCorners(const vbr::BRep& brep)
{
  std::map<std::tuple<int, int, int>, std::set<int>> lines; // (axis, other coordinates)
  for (const vbr::Point3& p : brep.points)
    for (int d = 0; d < 3; ++d)
      lines[{ d, p[(d + 1) % 3], p[(d + 2) % 3] }].insert(p[d]);
  std::vector<std::vector<vbr::Point3>> loops;
  for (std::size_t l = 0; l < brep.loops.size(); ++l)
  {
    const auto points = brep.loopPoints(static_cast<int>(l));
    std::vector<vbr::Point3> loop;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const vbr::Point3 p = points[i], q = points[(i + 1) % points.size()];
      loop.push_back(p);
      int d = 0;
      while (d < 3 && p[d] == q[d])
        ++d;
      if (d == 3)
        continue;
      const std::set<int>& line = lines[{ d, p[(d + 1) % 3], p[(d + 2) % 3] }];
      std::vector<int> inside(
        line.upper_bound(std::min(p[d], q[d])), line.lower_bound(std::max(p[d], q[d])));
      if (q[d] < p[d])
        std::reverse(inside.begin(), inside.end());
      for (int c : inside)
      {
        vbr::Point3 r = p;
        r[d] = c;
        loop.push_back(r);
      }
    }
    loops.push_back(loop);
  }
  return loops;
}

/// insertTJunctionVertices against loopsWithEdgeCorners, the B-Rep placed at `offset` in a
/// grid of the packer's size; the numbers it keeps are those of the corners they follow.
void checkEdgeCorners(vbr::BRep brep, const vbr::Point3& offset, const vbr::KeyPacker& packer)
{
  const auto expected = loopsWithEdgeCorners(brep);
  const vbr::CornerSet corners({ { &brep, offset } }, packer);
  std::vector<std::int64_t> numbers = corners.numbersOf(brep, offset);
  vbr::insertTJunctionVertices(brep, numbers, corners, offset);
  ASSERT_EQ(brep.loops.size(), expected.size());
  ASSERT_EQ(numbers.size(), brep.points.size());
  for (std::size_t l = 0; l < expected.size(); ++l)
  {
    const auto points = brep.loopPoints(static_cast<int>(l));
    ASSERT_EQ(std::vector<vbr::Point3>(points.begin(), points.end()), expected[l]) << "loop " << l;
  }
  for (std::size_t i = 0; i < numbers.size(); ++i)
    ASSERT_EQ(corners.points()[numbers[i]], vbr::add(brep.points[i], offset)) << "point " << i;
}

} // namespace

TEST(BRep, TJunctionVerticesMatchBruteForce)
{
  unsigned seed = 4100;
  for (int trial = 0; trial < 8; ++trial)
  {
    const vbr::Point3 d = bf::trialDims(trial, 3);
    const vbr::BitVolume v = bf::randomVolume(d, 0.2 + 0.1 * trial, seed++);
    vbr::BRep brep;
    ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(v), vbr::FaceConnectivity::Edge, {}, brep));
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    checkEdgeCorners(brep, { 0, 0, 0 }, vbr::KeyPacker::forMaximum(16));
    checkEdgeCorners(brep, { 5, 2, 7 }, vbr::KeyPacker::forMaximum(40));
  }
  // A small porous block and one voxel far from it: the lines along x are too many to count
  // (the set orders them by a sort of keys instead).
  vbr::BitVolume sparse(12, 300, 300);
  const vbr::BitVolume block = bf::randomVolume({ 10, 8, 6 }, 0.5, 99);
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 10; ++x)
        if (block.get(x, y, z))
          sparse.set(x, y, z);
  sparse.set(11, 299, 299);
  vbr::BRep brep;
  ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(sparse), vbr::FaceConnectivity::Vertex, {}, brep));
  checkEdgeCorners(brep, { 0, 0, 0 }, vbr::KeyPacker::forMaximum(300));
}

TEST(BRep, RandomVolumesMatchBruteForce)
{
  unsigned seed = 3000;
  for (int trial = 0; trial < 24; ++trial)
  {
    const vbr::Point3 d{ 2 + (trial * 5) % 13, 2 + (trial * 3) % 11, 2 + (trial * 7) % 9 };
    const double density = 0.1 + 0.8 * (trial % 8) / 7.0;
    const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
    SCOPED_TRACE(testing::Message() << "trial " << trial << " density " << density);
    checkVolume(v, false);
    checkVolume(v, true);
  }
}

TEST(BRep, LargerRandomVolume)
{
  const vbr::BitVolume v = bf::randomVolume({ 24, 20, 16 }, 0.35, 77);
  checkVolume(v, false);
}

TEST(BRep, DegenerateVolumes)
{
  vbr::BitVolume one(3, 3, 3);
  one.set(1, 1, 1);
  checkVolume(one, false);
  vbr::BRep b;
  ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(one), vbr::FaceConnectivity::Edge, {}, b));
  EXPECT_EQ(b.faces.size(), 6u);

  checkVolume(bf::randomVolume({ 6, 5, 4 }, 1.0, 1), false); // every voxel selected
  vbr::BitVolume plate(7, 6, 1);                             // one-voxel-thick plate
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 7; ++x)
      if (!(x == 3 && y == 2))
        plate.set(x, y, 0);
  checkVolume(plate, false);

  // Two voxels touching along an edge, two at a corner: non-manifold edges and vertices.
  vbr::BitVolume contacts(4, 4, 4);
  contacts.set(0, 0, 0);
  contacts.set(1, 1, 0);
  contacts.set(2, 2, 1);
  checkVolume(contacts, false);
  checkVolume(contacts, true);

  vbr::BitVolume empty(4, 4, 4);
  ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(empty), vbr::FaceConnectivity::Edge, {}, b));
  EXPECT_TRUE(b.faces.empty());
}

TEST(BRep, AbortStopsTheSweep)
{
  const vbr::BitVolume v = bf::randomVolume({ 8, 8, 8 }, 0.5, 5);
  vbr::Execution exec;
  exec.progress = [](double) { return false; };
  vbr::BRep b;
  EXPECT_FALSE(vbr::planeSweep3D(vbr::extractEVM(v), vbr::FaceConnectivity::Edge, exec, b));
  // A stop requested while the planes are swept (polled from the workers) also aborts.
  vbr::Execution polled;
  int polls = 0;
  polled.aborted = [&polls]() { return ++polls > 3; };
  EXPECT_FALSE(vbr::planeSweep3D(vbr::extractEVM(v), vbr::FaceConnectivity::Edge, polled, b));
  EXPECT_GT(polls, 3);
}

namespace
{

/// The corners of a B-Rep's loops, placed at `offset`, as a set.
std::set<vbr::Point3> loopCorners(const vbr::BRep& brep, const vbr::Point3& offset)
{
  std::set<vbr::Point3> corners;
  for (const vbr::Point3& p : brep.points)
    corners.insert(vbr::add(p, offset));
  return corners;
}

/// Faces, loops and points of `parts` joined in order, face and point indices shifted (a
/// face's parent too: a face of a plane can lie in a hole of another, as appendBRep has it).
vbr::BRep joined(const std::vector<vbr::BRep>& parts)
{
  vbr::BRep all;
  for (const vbr::BRep& part : parts)
  {
    const int faceBase = static_cast<int>(all.faces.size());
    const int loopBase = static_cast<int>(all.loops.size());
    const std::size_t pointBase = all.points.size();
    for (vbr::BRepFace f : part.faces)
    {
      f.firstLoop += loopBase;
      if (f.parent >= 0)
        f.parent += faceBase;
      all.faces.push_back(f);
    }
    for (vbr::BRepLoop l : part.loops)
    {
      l.face += faceBase;
      l.begin += pointBase;
      l.end += pointBase;
      all.loops.push_back(l);
    }
    all.points.insert(all.points.end(), part.points.begin(), part.points.end());
  }
  return all;
}

void expectSameBRep(const vbr::BRep& a, const vbr::BRep& b)
{
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (std::size_t f = 0; f < a.faces.size(); ++f)
  {
    const vbr::BRepFace &x = a.faces[f], &y = b.faces[f];
    ASSERT_EQ(std::make_tuple(x.axis, x.normalSign, x.position, x.firstLoop, x.loopCount, x.parent),
      std::make_tuple(y.axis, y.normalSign, y.position, y.firstLoop, y.loopCount, y.parent))
      << "face " << f;
  }
  ASSERT_EQ(a.loops.size(), b.loops.size());
  for (std::size_t l = 0; l < a.loops.size(); ++l)
    ASSERT_EQ(std::make_tuple(a.loops[l].begin, a.loops[l].end, a.loops[l].face, a.loops[l].hole),
      std::make_tuple(b.loops[l].begin, b.loops[l].end, b.loops[l].face, b.loops[l].hole))
      << "loop " << l;
  ASSERT_EQ(a.points, b.points);
}

/// The faces of `brep` whose plane is not one of `skipped` (axis, position), with their loops
/// and points, in order, and their parents renumbered (none when the parent is skipped).
vbr::BRep withoutFacesAt(const vbr::BRep& brep, const std::set<std::pair<int, int>>& skipped)
{
  vbr::BRep kept;
  std::vector<int> keptAs(brep.faces.size(), -1); // the new number of each face kept
  for (std::size_t i = 0; i < brep.faces.size(); ++i)
  {
    const vbr::BRepFace& f = brep.faces[i];
    if (skipped.count({ f.axis, f.position }))
      continue;
    keptAs[i] = static_cast<int>(kept.faces.size());
    vbr::BRepFace g = f;
    g.parent = f.parent < 0 ? -1 : keptAs[static_cast<std::size_t>(f.parent)];
    g.firstLoop = static_cast<int>(kept.loops.size());
    for (int l = f.firstLoop; l < f.firstLoop + f.loopCount; ++l)
    {
      vbr::BRepLoop loop = brep.loops[l];
      loop.face = static_cast<int>(kept.faces.size());
      loop.begin = kept.points.size();
      const auto points = brep.loopPoints(l);
      kept.points.insert(kept.points.end(), points.begin(), points.end());
      loop.end = kept.points.size();
      kept.loops.push_back(loop);
    }
    kept.faces.push_back(g);
  }
  return kept;
}

} // namespace

// The corners read from the voxels are exactly those of the plane sweep's loops (its own
// output is the reference: two unrelated ways to the same set), under both connectivities,
// across 64-voxel words along x, and the set numbered from them is the one numbered from the
// loops.
TEST(BRep, FaceCornersFromVoxelsAreTheLoopCorners)
{
  unsigned seed = 5200;
  for (int trial = 0; trial < 14; ++trial)
  {
    const vbr::Point3 d{
      trial < 4 ? 60 + 5 * trial : 1 + (trial * 5) % 13, 1 + (trial * 3) % 11, 1 + (trial * 7) % 9
    };
    const double density = 0.1 + 0.8 * (trial % 6) / 5.0;
    const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
    SCOPED_TRACE(testing::Message() << "trial " << trial << " density " << density);
    const vbr::Point3 offset{ 3, 1, 4 };
    vbr::PointList fromVoxels;
    vbr::appendFaceCorners(v, offset, fromVoxels);
    const std::set<vbr::Point3> voxelSet(fromVoxels.begin(), fromVoxels.end());
    EXPECT_EQ(voxelSet.size(), fromVoxels.size()); // each once
    // With threads (slabs of planes side by side, more slabs than planes for the thin
    // volumes), appended after corners already there: the same corners in the same order.
    for (int threads : { 2, 3, 16 })
    {
      vbr::PointList threaded{ { 7, 7, 7 } };
      vbr::appendFaceCorners(v, offset, threaded, bf::threadedExecution(threads));
      ASSERT_EQ(threaded.size(), fromVoxels.size() + 1);
      EXPECT_EQ(threaded[0], (vbr::Point3{ 7, 7, 7 }));
      EXPECT_TRUE(std::equal(fromVoxels.begin(), fromVoxels.end(), threaded.begin() + 1));
    }
    for (vbr::FaceConnectivity c : { vbr::FaceConnectivity::Edge, vbr::FaceConnectivity::Vertex })
    {
      vbr::BRep brep;
      ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(v), c, {}, brep));
      ASSERT_EQ(voxelSet, loopCorners(brep, offset));
      const vbr::KeyPacker packer = vbr::KeyPacker::forMaximum(80);
      const vbr::CornerSet a(fromVoxels, packer), b({ { &brep, offset } }, packer);
      ASSERT_EQ(a.points(), b.points());
      // Written side by side from the ranks of their words: the same points, the same numbers.
      const vbr::CornerSet threaded(fromVoxels, packer, bf::threadedExecution(3));
      ASSERT_EQ(threaded.points(), b.points());
      ASSERT_EQ(threaded.numbersOf(brep, offset), b.numbersOf(brep, offset));
      ASSERT_EQ(a.numbersOf(brep, offset), b.numbersOf(brep, offset));
    }
  }
  // The checkerboard: every grid point of the volume is a corner but the four corners of the
  // box whose one voxel is not selected.
  vbr::BitVolume checker(5, 4, 3);
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x)
        checker.set(x, y, z, (x + y + z) % 2 == 0);
  vbr::PointList corners;
  vbr::appendFaceCorners(checker, { 0, 0, 0 }, corners);
  EXPECT_EQ(corners.size(), 6u * 5u * 4u - 4u);
  vbr::BitVolume empty(4, 4, 4);
  corners.clear();
  vbr::appendFaceCorners(empty, { 0, 0, 0 }, corners);
  EXPECT_TRUE(corners.empty());
}

// The corner set with threads: slabs of the corners marked side by side (the first in the
// set's bitmaps, the others in bitmaps of their own ORed in after), the words ranked and the
// points listed by runs. Dense corners, repeated, in small boxes take the slabs' own bitmaps;
// sparse ones do not. For 2, 3 and 16 threads: the points of one thread, which are the
// distinct corners in key order (brute force), the same numbers, and the same corners found
// and counted between grid points along each axis. A slab or run one place off loses or moves
// a corner.
TEST(BRep, ThreadedCornerSetEqualsOneThread)
{
  std::mt19937 random(7100);
  for (int trial = 0; trial < 12; ++trial)
  {
    const vbr::Point3 box{ 1 + trial % 5 * 3, 2 + trial % 4 * 5, 1 + trial * 7 % 11 };
    const vbr::Point3 lo{ trial % 3, 5, trial };
    const std::size_t count = trial < 8 ? 4000 : 40; // dense (with repeats) or sparse
    vbr::BRep brep;
    for (std::size_t i = 0; i < count; ++i)
      brep.points.push_back({ lo[0] + int(random() % box[0]),
        lo[1] + int(random() % box[1]),
        lo[2] + int(random() % box[2]) });
    const vbr::PointList corners(brep.points.begin(), brep.points.end());
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    const vbr::KeyPacker packer = vbr::KeyPacker::forMaximum(40);
    const vbr::CornerSet one(corners, packer);
    const std::set<vbr::Point3> distinct(corners.begin(), corners.end());
    ASSERT_TRUE(
      std::equal(distinct.begin(), distinct.end(), one.points().begin(), one.points().end()));
    const std::vector<std::int64_t> numbers = one.numbersOf(brep, { 0, 0, 0 });
    for (int threads : { 2, 3, 16 })
    {
      SCOPED_TRACE(testing::Message() << threads << " threads");
      const vbr::CornerSet set(corners, packer, bf::threadedExecution(threads));
      ASSERT_EQ(set.points(), one.points());
      EXPECT_EQ(set.lowest(), one.lowest());
      EXPECT_EQ(set.highest(), one.highest());
      EXPECT_EQ(set.numbersOf(brep, { 0, 0, 0 }), numbers);
      // Between each corner and the far end of its line's box, along each axis.
      for (std::size_t i = 0; i < brep.points.size(); i += 7)
        for (int axis = 0; axis < 3; ++axis)
        {
          const vbr::Point3 from = brep.points[i];
          vbr::Point3 to = from;
          to[axis] = (i & 8) ? one.lowest()[axis] : one.highest()[axis];
          std::vector<std::int64_t> a, b;
          one.forEachBetween(axis, from, to, [&](std::int64_t n, vbr::Coord) { a.push_back(n); });
          set.forEachBetween(axis, from, to, [&](std::int64_t n, vbr::Coord) { b.push_back(n); });
          ASSERT_EQ(a, b) << "axis " << axis;
          std::size_t between = 0;
          for (const vbr::Point3& p : distinct)
            between += p[(axis + 1) % 3] == from[(axis + 1) % 3] &&
              p[(axis + 2) % 3] == from[(axis + 2) % 3] &&
              std::min(from[axis], to[axis]) < p[axis] && p[axis] < std::max(from[axis], to[axis]);
          EXPECT_EQ(a.size(), between) << "axis " << axis;
          if (axis < 2) // along z it is told from the numbers of two corners
            EXPECT_EQ(set.countBetween(axis, from, to, numbers[i], -1), between) << "axis " << axis;
        }
    }
  }
  // Empty, and a corner outside the packer's grid told from any slab.
  EXPECT_EQ(
    vbr::CornerSet(vbr::PointList(), vbr::KeyPacker::forMaximum(40), bf::threadedExecution(3))
      .size(),
    0u);
  vbr::PointList outside(100, vbr::Point3{ 1, 2, 3 });
  outside[70] = { 1, -2, 3 };
  EXPECT_THROW(vbr::CornerSet(outside, vbr::KeyPacker::forMaximum(40), bf::threadedExecution(3)),
    std::out_of_range);
}

namespace
{

/// CornerNumbersOfPointsMatchSortedCorners with the bit counts as set by the caller.
void expectCornerNumbersMatchSortedCorners()
{
  std::mt19937 random(6300);
  std::uniform_int_distribution<int> coordinate(0, 70);
  vbr::PointList corners;
  for (int i = 0; i < 300; ++i)
    corners.push_back({ coordinate(random), coordinate(random), coordinate(random) });
  const vbr::KeyPacker packer = vbr::KeyPacker::forMaximum(80);
  const vbr::CornerSet set(corners, packer);
  std::vector<vbr::Point3> sorted(corners.begin(), corners.end());
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  ASSERT_EQ(set.size(), sorted.size());
  const vbr::Point3 offset{ 2, 5, 1 };
  for (std::size_t n : { 0, 1, 15, 16, 17, 33 })
  {
    vbr::BRep brep;
    std::uniform_int_distribution<std::size_t> pick(0, corners.size() - 1);
    for (std::size_t i = 0; i < n; ++i)
    {
      const vbr::Point3 c = corners[pick(random)];
      brep.points.push_back({ c[0] - offset[0], c[1] - offset[1], c[2] - offset[2] });
    }
    const std::vector<std::int64_t> numbers = set.numbersOf(brep, offset);
    ASSERT_EQ(numbers.size(), n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const vbr::Point3 c = vbr::add(brep.points[i], offset);
      const auto at = std::lower_bound(sorted.begin(), sorted.end(), c);
      EXPECT_EQ(numbers[i], at - sorted.begin()) << "n " << n << " point " << i;
    }
  }
}

} // namespace

// numbersOf keeps the box index of the 16 points ahead in a ring: at batch sizes around the
// ring's (none, one, a ring less one, a ring, a ring and one, two rings and one) each point's
// number is its corner's place among the distinct corners in lexicographic order (a sorted
// vector, searched). The points, at an offset, repeat corners and come in random order. Both
// copies of numbersOf: the one counting bits by the POPCNT instruction and the portable one.
TEST(BRep, CornerNumbersOfPointsMatchSortedCorners)
{
  for (const bool portable : { false, true })
  {
    SCOPED_TRACE(portable ? "portable bit counts" : "bit counts by the instruction, if any");
    vbr::portableBitCountsForTesting() = portable;
    expectCornerNumbersMatchSortedCorners();
  }
  vbr::portableBitCountsForTesting() = false;
}

// The T-junction vertices and the corner numbers written into arrays kept from one B-Rep to the
// next (TJunctionScratch, numbersOf into a vector), larger or smaller than needed and holding
// the values of the B-Rep before, are those made in fresh arrays.
TEST(BRep, TJunctionScratchKeptMatchesFresh)
{
  unsigned seed = 4400;
  vbr::TJunctionScratch scratch;
  std::vector<std::int64_t> kept(5000, -7); // stale values, more than the first B-Rep needs
  for (int trial = 0; trial < 10; ++trial)
  {
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    // Large and small B-Reps in turns, so that the kept arrays both grow and shrink.
    const int edge = trial % 2 ? 4 : 9 + trial;
    const vbr::BitVolume v = bf::randomVolume({ edge, edge + 1, edge + 2 }, 0.45, seed++);
    vbr::BRep fresh;
    ASSERT_TRUE(vbr::planeSweep3D(vbr::extractEVM(v), vbr::FaceConnectivity::Edge, {}, fresh));
    vbr::BRep reused = fresh;
    const vbr::Point3 offset{ 1, 2, 3 };
    const vbr::CornerSet corners({ { &fresh, offset } }, vbr::KeyPacker::forMaximum(40));
    std::vector<std::int64_t> numbers = corners.numbersOf(fresh, offset);
    corners.numbersOf(reused, offset, kept);
    ASSERT_EQ(kept, numbers);
    vbr::insertTJunctionVertices(fresh, numbers, corners, offset);
    vbr::insertTJunctionVertices(reused, kept, corners, offset, {}, scratch);
    expectSameBRep(reused, fresh);
    ASSERT_EQ(kept, numbers);
  }
}

// The streamed parts, joined, are planeSweep3D's B-Rep, on one thread and on several, and the
// caller stops the stream by returning false.
TEST(BRep, StreamedPartsAreTheSweepsFaces)
{
  unsigned seed = 6100;
  for (int trial = 0; trial < 6; ++trial)
  {
    const vbr::Point3 d{ 3 + (trial * 5) % 17, 150 + trial, 2 + (trial * 7) % 9 };
    const vbr::BitVolume v = bf::randomVolume(d, 0.2 + 0.12 * trial, seed++);
    const vbr::EVM evm = vbr::extractEVM(v);
    const vbr::FaceConnectivity c =
      trial % 2 ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge;
    vbr::BRep whole;
    ASSERT_TRUE(vbr::planeSweep3D(evm, c, {}, whole));
    for (int threads : { 1, 3 })
    {
      SCOPED_TRACE(testing::Message() << "trial " << trial << " threads " << threads);
      const vbr::Execution exec = threads == 1 ? vbr::Execution() : bf::threadedExecution(threads);
      std::vector<vbr::BRep> parts;
      ASSERT_TRUE(vbr::planeSweep3DStream(evm,
        c,
        exec,
        [&](vbr::BRep& part)
        {
          parts.push_back(std::move(part));
          return true;
        }));
      EXPECT_GT(parts.size(), 40u); // the chunks of the long axis were streamed
      expectSameBRep(joined(parts), whole);

      // Copied, not moved: each part is emptied for its next chunk with its arrays' memory
      // kept, and holds nothing of the chunk before (faces, loops, points, the count of
      // non-manifold vertices).
      std::vector<vbr::BRep> copies;
      ASSERT_TRUE(vbr::planeSweep3DStream(evm,
        c,
        exec,
        [&](vbr::BRep& part)
        {
          copies.push_back(part);
          return true;
        }));
      expectSameBRep(joined(copies), whole);
      std::size_t nonManifold = 0;
      for (const vbr::BRep& part : copies)
        nonManifold += part.nonManifoldVertices;
      EXPECT_EQ(nonManifold, whole.nonManifoldVertices);
      int calls = 0;
      EXPECT_FALSE(vbr::planeSweep3DStream(evm, c, exec, [&](vbr::BRep&) { return ++calls < 5; }));
      EXPECT_EQ(calls, 5);

      // Prepared on the threads, each part into its slot, then appended in order: the part
      // prepared in a slot is the one appended from it, the slots fit the batch.
      const std::size_t batch = vbr::streamBatch(exec);
      EXPECT_GE(batch, static_cast<std::size_t>(threads)); // a slot per worker at least
      std::vector<vbr::BRep> slots(batch), appended;
      std::vector<int> prepared(batch, 0);
      std::atomic<bool> badSlot{ false };
      ASSERT_TRUE(vbr::planeSweep3DStream(evm,
        c,
        exec,
        vbr::StreamedPartHandlers{ [&](vbr::BRep& part, std::size_t slot)
          {
            if (slot >= batch)
              return !(badSlot = true);
            ++prepared[slot];
            slots[slot] = std::move(part);
            return true;
          },
          [&](vbr::BRep& part, std::size_t slot)
          {
            EXPECT_TRUE(part.faces.empty() && part.points.empty()); // moved by prepare
            EXPECT_EQ(prepared[slot], 1);
            prepared[slot] = 0;
            appended.push_back(std::move(slots[slot]));
            return true;
          } }));
      EXPECT_FALSE(badSlot);
      expectSameBRep(joined(appended), whole);
      // A prepare that fails stops the stream: its part is never appended, nor any after it,
      // and no append starts once it has failed (the slot it failed in is not appended from).
      std::atomic<int> prepares{ 0 };
      std::atomic<std::size_t> failedSlot{ batch };
      std::size_t appends = 0;
      EXPECT_FALSE(vbr::planeSweep3DStream(evm,
        c,
        exec,
        vbr::StreamedPartHandlers{ [&](vbr::BRep&, std::size_t slot)
          {
            if (++prepares != 4 * threads)
              return true;
            failedSlot = slot;
            return false;
          },
          [&](vbr::BRep&, std::size_t slot)
          {
            EXPECT_NE(slot, failedSlot.load());
            ++appends;
            return true;
          } }));
      EXPECT_LT(appends, static_cast<std::size_t>(prepares.load()));
    }
  }
}

// The sweep keeps its sections as rows of bits when its planes are full of vertices and as
// vertex lists when they are sparse in their box: a porous block alone (rows of bits, checked
// against brute force by RandomVolumesMatchBruteForce) and with one voxel far from it (lists)
// has the same faces, streamed or not, on one thread or several (on 3 threads the pool's
// walker XORs its way to each chunk's entering section, both ways).
TEST(BRep, SparseAndDenseSectionsGiveTheSameFaces)
{
  unsigned seed = 7300;
  for (int trial = 0; trial < 4; ++trial)
  {
    const vbr::Point3 d{ 9 + trial, 8, 6 + trial };
    const vbr::BitVolume block = bf::randomVolume(d, 0.3 + 0.15 * trial, seed++);
    vbr::BitVolume sparse(200, 400, 400);
    for (int z = 0; z < d[2]; ++z)
      for (int y = 0; y < d[1]; ++y)
        for (int x = 0; x < d[0]; ++x)
          if (block.get(x, y, z))
            sparse.set(x, y, z);
    sparse.set(199, 399, 399);
    const std::set<std::pair<int, int>> farPlanes{
      { 0, 199 }, { 0, 200 }, { 1, 399 }, { 1, 400 }, { 2, 399 }, { 2, 400 }
    };
    const vbr::FaceConnectivity c =
      trial % 2 ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge;
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    vbr::BRep alone, withFar;
    const vbr::EVM dense = vbr::extractEVM(block);
    ASSERT_TRUE(vbr::planeSweep3D(dense, c, {}, alone));
    const vbr::EVM evm = vbr::extractEVM(sparse);
    ASSERT_TRUE(vbr::planeSweep3D(evm, c, {}, withFar));
    EXPECT_EQ(vbr::detail::sectionsAsBitRows(dense), (std::array<bool, 3>{ true, true, true }));
    EXPECT_EQ(vbr::detail::sectionsAsBitRows(evm), (std::array<bool, 3>{ false, false, false }));
    EXPECT_EQ(withFar.faces.size(), alone.faces.size() + 6);
    expectSameBRep(withoutFacesAt(withFar, farPlanes), alone);
    for (int threads : { 1, 3 })
    {
      const vbr::Execution exec = threads == 1 ? vbr::Execution() : bf::threadedExecution(threads);
      for (const vbr::BRep* whole : { &alone, &withFar })
      {
        std::vector<vbr::BRep> parts;
        ASSERT_TRUE(vbr::planeSweep3DStream(whole == &alone ? dense : evm,
          c,
          exec,
          [&](vbr::BRep& part)
          {
            parts.push_back(std::move(part));
            return true;
          }));
        expectSameBRep(joined(parts), *whole);
      }
    }
  }
}

// The streamed sweeps take the box of each sorting's sections from the ranges of the axes,
// read off the sortings' first and last vertices (and a pass over the vertices for the third
// axis when the EVM given is not ZYX-sorted), and count the planes per axis from the
// sortings: a block away from the origin (its box starts past 0 on every axis, its rows of
// bits chosen), given in each of the six sortings, has planeSweep3D's faces streamed, on one
// thread and on three, and planesPerAxis' planes. A box one row or one word short, or a range
// taken from the wrong axis, changes the faces or fails.
TEST(BRep, StreamedSectionBoxesAndPlanesFromTheSortings)
{
  unsigned seed = 8300;
  for (int trial = 0; trial < 4; ++trial)
  {
    const vbr::Point3 d{ 70 + 9 * trial, 9 + 3 * trial, 66 + 5 * trial };
    const vbr::BitVolume block = bf::randomVolume(d, 0.3 + 0.12 * trial, seed++);
    const vbr::Point3 shift{ 5 + trial, 11 - trial, 3 + 2 * trial };
    vbr::BitVolume shifted(d[0] + shift[0] + 2, d[1] + shift[1] + 1, d[2] + shift[2] + 3);
    for (int z = 0; z < d[2]; ++z)
      for (int y = 0; y < d[1]; ++y)
        for (int x = 0; x < d[0]; ++x)
          if (block.get(x, y, z))
            shifted.set(x + shift[0], y + shift[1], z + shift[2]);
    const vbr::EVM zyx = vbr::extractEVM(shifted);
    ASSERT_EQ(vbr::detail::sectionsAsBitRows(zyx), (std::array<bool, 3>{ true, true, true }));
    const vbr::FaceConnectivity c =
      trial % 2 ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge;
    vbr::BRep whole;
    ASSERT_TRUE(vbr::planeSweep3D(zyx, c, {}, whole));
    for (const char* order : { "ZYX", "XYZ", "XZY", "YXZ", "YZX", "ZXY" })
    {
      const vbr::EVM evm = zyx.sortedAs(vbr::axisOrderFromName(order));
      for (int threads : { 1, 3 })
      {
        SCOPED_TRACE(
          testing::Message() << "trial " << trial << " order " << order << " threads " << threads);
        const vbr::Execution exec =
          threads == 1 ? vbr::Execution() : bf::threadedExecution(threads);
        std::vector<vbr::BRep> parts;
        std::array<std::size_t, 3> planes{ 7, 7, 7 };
        ASSERT_TRUE(vbr::planeSweep3DStream(evm,
          c,
          exec,
          vbr::StreamedPartHandlers{ nullptr,
            [&](vbr::BRep& part, std::size_t)
            {
              parts.push_back(std::move(part));
              return true;
            } },
          &planes));
        expectSameBRep(joined(parts), whole);
        EXPECT_EQ(planes, vbr::planesPerAxis(zyx));
      }
    }
  }
  std::array<std::size_t, 3> planes{ 7, 7, 7 };
  EXPECT_TRUE(vbr::planeSweep3DStream(vbr::EVM(),
    vbr::FaceConnectivity::Edge,
    {},
    vbr::StreamedPartHandlers{ nullptr, [](vbr::BRep&, std::size_t) { return true; } },
    &planes));
  EXPECT_EQ(planes, (std::array<std::size_t, 3>{ 0, 0, 0 }));
}

namespace
{

/// A parallel loop of `threads` std::threads, each body call one thread, that keeps the first
/// exception of a thread and throws it again once all are joined (as the VTK adapter's does).
vbr::Execution rethrowingThreadedExecution(int threads)
{
  vbr::Execution exec;
  exec.concurrency = threads;
  exec.parallelFor = [threads](
                       std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body)
  {
    std::exception_ptr failure;
    std::mutex guard;
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t)
      workers.emplace_back(
        [&, t]
        {
          try
          {
            body(n * t / threads, n * (t + 1) / threads);
          }
          catch (...)
          {
            std::lock_guard<std::mutex> lock(guard);
            if (!failure)
              failure = std::current_exception();
          }
        });
    for (std::thread& w : workers)
      w.join();
    if (failure)
      std::rethrow_exception(failure);
  };
  return exec;
}

/// The parts of a streamed sweep as its handlers get them: each prepared (on some thread,
/// after a delay that differs from part to part, so that parts get ready out of order) into its
/// slot, then appended from that slot. Checks that no slot is prepared twice before it is
/// appended, that the slots fit streamBatch(exec), that no two appends run at once and that
/// the progress is reported on the calling thread only.
std::vector<vbr::BRep> streamedParts(const vbr::EVM& evm,
  vbr::FaceConnectivity c,
  vbr::Execution exec)
{
  const std::size_t slots = vbr::streamBatch(exec);
  std::vector<vbr::BRep> prepared(slots), appended;
  std::vector<std::atomic<int>> inSlot(slots);
  std::atomic<int> appending{ 0 }, offCaller{ 0 };
  const std::thread::id caller = std::this_thread::get_id();
  exec.progress = [&](double) { return !(std::this_thread::get_id() != caller && ++offCaller); };
  const bool done = vbr::planeSweep3DStream(evm,
    c,
    exec,
    vbr::StreamedPartHandlers{ [&](vbr::BRep& part, std::size_t slot)
      {
        EXPECT_LT(slot, slots);
        if (slot >= slots)
          return false;
        EXPECT_EQ(++inSlot[slot], 1) << "slot " << slot << " prepared twice";
        std::this_thread::sleep_for(std::chrono::microseconds(37 * (part.faces.size() % 11)));
        prepared[slot] = part;
        return true;
      },
      [&](vbr::BRep& part, std::size_t slot)
      {
        EXPECT_EQ(++appending, 1) << "two appends at once";
        EXPECT_EQ(part.faces.size(), prepared[slot].faces.size()); // the part of that slot
        EXPECT_EQ(inSlot[slot]--, 1);
        appended.push_back(std::move(prepared[slot]));
        --appending;
        return true;
      } });
  EXPECT_TRUE(done);
  EXPECT_EQ(offCaller, 0) << "progress reported off the calling thread";
  return appended;
}

} // namespace

// A pool of 2, 3 and 16 workers (std::threads, and 3 workers run one after the other in one
// body call on the calling thread) appends the very parts of one thread, one by one in the same
// order, though they are prepared out of order; a stop requested while the workers sweep, a
// prepare that fails and one that throws end the stream (the exception leaves through the
// parallel loop) without a worker left waiting.
TEST(BRep, StreamedPoolAppendsThePartsInOrder)
{
  unsigned seed = 8100;
  for (int trial = 0; trial < 4; ++trial)
  {
    const vbr::Point3 d{ 6 + 5 * trial, 127, 4 + 3 * trial };
    const vbr::EVM evm = vbr::extractEVM(bf::randomVolume(d, 0.25 + 0.12 * trial, seed++));
    const vbr::FaceConnectivity c =
      trial % 2 ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge;
    const std::vector<vbr::BRep> alone = streamedParts(evm, c, vbr::Execution());
    ASSERT_GT(alone.size(), 64u); // the 128 planes along y streamed in 64 chunks, and more
    vbr::Execution serial;        // workers one after the other on the calling thread
    serial.concurrency = 3;
    serial.parallelFor =
      [](std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body)
    { body(0, n); };
    for (const int threads : { 2, 3, 16, -3 })
    {
      SCOPED_TRACE(testing::Message() << "trial " << trial << " threads " << threads);
      const vbr::Execution exec = threads > 0 ? rethrowingThreadedExecution(threads) : serial;
      EXPECT_GE(vbr::streamBatch(exec), static_cast<std::size_t>(std::abs(threads)));
      const std::vector<vbr::BRep> parts = streamedParts(evm, c, exec);
      ASSERT_EQ(parts.size(), alone.size());
      for (std::size_t i = 0; i < parts.size(); ++i)
      {
        SCOPED_TRACE(testing::Message() << "part " << i);
        expectSameBRep(parts[i], alone[i]);
      }

      vbr::Execution stopped = exec;
      std::atomic<int> polls{ 0 };
      stopped.aborted = [&polls] { return ++polls > 40; };
      EXPECT_FALSE(vbr::planeSweep3DStream(evm, c, stopped, [](vbr::BRep&) { return true; }));

      std::atomic<int> prepares{ 0 };
      const std::size_t failing = 5;
      std::size_t appends = 0;
      EXPECT_FALSE(vbr::planeSweep3DStream(evm,
        c,
        exec,
        vbr::StreamedPartHandlers{ [&](vbr::BRep&, std::size_t)
          { return ++prepares != static_cast<int>(failing); },
          [&](vbr::BRep&, std::size_t)
          {
            ++appends;
            return true;
          } }));
      EXPECT_LT(appends, failing); // only parts prepared before the failing one

      prepares = 0;
      EXPECT_THROW(vbr::planeSweep3DStream(evm,
                     c,
                     exec,
                     vbr::StreamedPartHandlers{ [&](vbr::BRep&, std::size_t)
                       {
                         if (++prepares == 7)
                           throw std::runtime_error("prepare failed");
                         return true;
                       },
                       [](vbr::BRep&, std::size_t) { return true; } }),
        std::runtime_error);
    }
  }
}
