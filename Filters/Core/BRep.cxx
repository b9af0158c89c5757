// The B-Rep's own operations, after the plane sweeps have found its faces.
//
// appendFaces places the faces of a 2D solution (planeSweep2D works in the (B, C) coordinates
// of a sorting) in their plane A = position of 3D space, reversing the loops of a face whose
// (B, C) orientation is not counter-clockwise seen from outside: B x C = parity * A, so the
// loops turn when the parity of the sorting and the side the face looks to differ.
// extractBoundary2D is that for a 2D EVM, the whole image being one plane.
//
// insertTJunctionVertices makes the edges of adjacent faces match exactly. The distinct
// corners are numbered in the order of their packed keys (CornerSet, KeyPacker) by the ranks
// of their bits in a bitmap of their box; the corners strictly inside an edge are then the set
// bits between its two ends along its line (a stride of the box apart), inserted in order
// (walkWithEdgeVertices) with their numbers, which the filters use as point ids. How many each
// loop gains is counted first (along the last axis, the difference of the two ends' numbers),
// then the loops are walked concurrently, once each, into arrays of their final size. Several
// B-Reps placed in one grid (the objects of a label map) share one set of corners, so that the
// edges of neighbouring objects match too.

#include "BRep.h"

#include "HugePages.h"
#include "PopCount.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <utility>
#include <vector>

namespace vbr
{

namespace
{

/// The point (position, u, v) of a plane A = position in the order (A, B, C), in (x, y, z).
Point3 placed(const AxisOrder& order, Coord position, const Point2& p)
{
  Point3 q;
  q[order[0]] = position;
  q[order[1]] = p.u;
  q[order[2]] = p.v;
  return q;
}

/// Room for `more` elements past the end of `v`, at least doubling its capacity when it
/// grows: appendFaces adds a plane's faces at a time, thousands of planes of few faces each on
/// noise (a reservation of the exact size each time would copy the faces at every plane).
template<typename T>
void reserveGrowing(std::vector<T>& v, std::size_t more)
{
  if (v.size() + more > v.capacity())
    v.reserve(std::max(v.size() + more, 2 * v.capacity()));
}

/// appendFaces, the corners of each loop [begin, end) of b2 appended by
/// copyLoop(begin, end, reverse) as `corners` counts them.
template<typename CopyLoop>
void appendFacesOf(const Boundary2D& b2,
  const AxisOrder& order,
  Coord position,
  int normalSign,
  std::size_t corners,
  BRep& out,
  CopyLoop&& copyLoop)
{
  // planeSweep2D loops are counter-clockwise in (B, C), whose right-hand normal is parity * A.
  const bool reverse = axisOrderParity(order) != normalSign;
  const int faceBase = static_cast<int>(out.faces.size());
  reserveGrowing(out.faces, b2.faces.size());
  reserveGrowing(out.loops, b2.loops.size());
  for (const Face2D& f2 : b2.faces)
  {
    // Faces and loops written in place, not made apart and copied in (see appendFacesPlaced).
    const int faceId = static_cast<int>(out.faces.size());
    BRepFace& face = out.faces.emplace_back();
    face.axis = order[0];
    face.normalSign = normalSign;
    face.position = position;
    face.firstLoop = static_cast<int>(out.loops.size());
    face.loopCount = static_cast<int>(1 + f2.holeLoops.size());
    face.parent = f2.parent < 0 ? -1 : faceBase + f2.parent;
    face.depth = f2.depth;
    auto addLoop = [&](int l, bool hole)
    {
      BRepLoop& loop = out.loops.emplace_back();
      loop.face = faceId;
      loop.hole = hole;
      loop.begin = corners;
      const Loop2D& l2 = b2.loops[l];
      copyLoop(l2.begin, l2.end, reverse);
      corners += l2.end - l2.begin;
      loop.end = corners;
    };
    addLoop(f2.outerLoop, false);
    for (int h : f2.holeLoops)
      addLoop(h, true);
  }
  out.nonManifoldVertices += b2.nonManifoldVertices;
}

} // namespace

namespace
{

/// appendFaces in the sorting (A, B, C) = order, known at compile time: each corner placed by
/// three stores at fixed offsets, not at offsets read from the order at every corner.
template<int A, int B, int C>
void appendFacesPlaced(const Boundary2D& b2,
  const AxisOrder& order,
  Coord position,
  int normalSign,
  BRep& out)
{
  // The loops hold all of b2's points: one resize (not zeroed: PointList), then each loop
  // written in place in its final order, with no check of capacity per corner.
  const std::size_t first = out.points.size();
  out.points.resize(first + b2.points.size());
  Point3* to = out.points.data() + first;
  const auto place = [&](const Point2& p)
  {
    // Coordinate by coordinate: a point made apart and then copied is read back in wider words
    // than its coordinates were written in, which the processor cannot forward from its
    // stores (a stall per corner, most of appendFaces' time on a checkerboard).
    Point3& q = *to++;
    q[A] = position;
    q[B] = p.u;
    q[C] = p.v;
  };
  appendFacesOf(b2,
    order,
    position,
    normalSign,
    first,
    out,
    [&](std::size_t begin, std::size_t end, bool reverse)
    {
      const Point2* from = b2.points.data();
      if (reverse)
        for (std::size_t i = end; i-- > begin;)
          place(from[i]);
      else
        for (std::size_t i = begin; i < end; ++i)
          place(from[i]);
    });
  // Every point of b2 lies in exactly one of its loops, so the loops fill the resize exactly.
  assert(to == out.points.data() + out.points.size());
}

} // namespace

void appendFaces(const Boundary2D& b2,
  const AxisOrder& order,
  Coord position,
  int normalSign,
  BRep& out)
{
  // The 3D sweep's sortings are the cyclic ones; a 2D EVM may come in any of the six.
  const int key = 9 * order[0] + 3 * order[1] + order[2];
  switch (key)
  {
    case 0 * 9 + 1 * 3 + 2:
      return appendFacesPlaced<0, 1, 2>(b2, order, position, normalSign, out);
    case 1 * 9 + 2 * 3 + 0:
      return appendFacesPlaced<1, 2, 0>(b2, order, position, normalSign, out);
    case 2 * 9 + 0 * 3 + 1:
      return appendFacesPlaced<2, 0, 1>(b2, order, position, normalSign, out);
    case 0 * 9 + 2 * 3 + 1:
      return appendFacesPlaced<0, 2, 1>(b2, order, position, normalSign, out);
    case 1 * 9 + 0 * 3 + 2:
      return appendFacesPlaced<1, 0, 2>(b2, order, position, normalSign, out);
    case 2 * 9 + 1 * 3 + 0:
      return appendFacesPlaced<2, 1, 0>(b2, order, position, normalSign, out);
    default:
      throw std::invalid_argument("appendFaces: not an order of the three axes");
  }
}

std::size_t BRep::holeCount() const
{
  return static_cast<std::size_t>(std::count_if(
    this->loops.begin(), this->loops.end(), [](const BRepLoop& l) { return l.hole; }));
}

BRep extractBoundary2D(const EVM& evm, FaceConnectivity connectivity)
{
  BRep out;
  out.mergedAtVertices = connectivity == FaceConnectivity::Vertex;
  const auto& v = evm.vertices();
  const Boundary2D b2 = planeSweep2D(v.data(), v.data() + v.size(), connectivity);
  out.faces.reserve(b2.faces.size());
  out.loops.reserve(b2.loops.size());
  out.points.reserve(b2.points.size());
  appendFaces(b2, evm.order(), 0, +1, out);
  return out;
}

Contours2D numberedContours2D(const EVM& evm, FaceConnectivity connectivity)
{
  // The key of corner (0, u, v) is that of the point q, q[order[1]] = u, q[order[2]] = v:
  // keys compare u first when u's axis comes first.
  const AxisOrder& order = evm.order();
  const CornerOrder cornerOrder = order[1] < order[2] ? CornerOrder::UThenV : CornerOrder::VThenU;
  const auto& v = evm.vertices();
  return planeSweep2DNumbered(v.data(), v.data() + v.size(), cornerOrder, connectivity);
}

NumberedBRep extractNumberedBoundary2D(const EVM& evm,
  FaceConnectivity connectivity,
  bool withPoints)
{
  const AxisOrder& order = evm.order();
  const Contours2D c = numberedContours2D(evm, connectivity);
  NumberedBRep out;
  out.brep.mergedAtVertices = connectivity == FaceConnectivity::Vertex;
  out.corners.reserve(c.cornerCount());
  c.forEachCorner([&](Coord u, Coord v) { out.corners.push_back(placed(order, 0, { u, v })); });
  out.brep.faces.reserve(c.boundary.faces.size());
  out.brep.loops.reserve(c.boundary.loops.size());
  out.numbers.resize(c.loopCorners.size());
  if (withPoints)
    out.brep.points.reserve(c.loopCorners.size());
  std::int64_t* to = out.numbers.data();
  appendFacesOf(c.boundary,
    order,
    0,
    +1,
    0,
    out.brep,
    [&](std::size_t begin, std::size_t end, bool reverse)
    {
      const std::uint32_t* from = c.loopCorners.data() + begin;
      const std::size_t n = end - begin;
      for (std::size_t i = 0; i < n; ++i)
        to[i] = from[reverse ? n - 1 - i : i];
      if (withPoints)
        for (std::size_t i = 0; i < n; ++i)
          out.brep.points.push_back(out.corners[to[i]]);
      to += n;
    });
  return out;
}

namespace
{

/// The axis along which the edge from p to q runs (3 for a point).
int edgeAxis(const Point3& p, const Point3& q)
{
  int d = 0;
  while (d < 3 && p[d] == q[d])
    ++d;
  return d;
}

/// Writes a loop's corners to `points` and their numbers to `numbers`, each followed by the
/// corners of the set lying strictly inside the edge that starts there, in order along the
/// edge. `inside` holds per corner how many lie inside its edge (countEdgeVertices): the runs of
/// edges that hold none, most of them, are copied whole, without looking their ends up in the
/// corner set.
void walkWithEdgeVertices(const PointRange& loop,
  const std::int64_t* loopNumbers,
  const std::uint32_t* inside,
  const CornerSet& corners,
  const Point3& offset,
  Point3* points,
  std::int64_t* numbers)
{
  std::size_t run = 0; // the first corner not written yet
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    if (inside[i] == 0)
      continue;
    points = std::copy(loop.begin() + run, loop.begin() + i + 1, points);
    numbers = std::copy(loopNumbers + run, loopNumbers + i + 1, numbers);
    run = i + 1;
    const std::size_t j = i + 1 < loop.size() ? i + 1 : 0;
    const int d = edgeAxis(loop[i], loop[j]);
    Point3 q = loop[i]; // a corner inside the edge differs from its start along d only
    corners.forEachBetween(d,
      add(loop[i], offset),
      add(loop[j], offset),
      [&](std::int64_t n, Coord c)
      {
        q[d] = c - offset[d];
        *points++ = q;
        *numbers++ = n;
      });
  }
  std::copy(loop.begin() + run, loop.end(), points);
  std::copy(loopNumbers + run, loopNumbers + loop.size(), numbers);
}

/// The largest coordinate of the corners; throws when one lies outside [0, 2^21).
Coord checkedMaximum(const PointList& points)
{
  Coord lo = points[0][0], hi = lo;
  for (const Point3& p : points)
    for (Coord c : p)
    {
      lo = std::min(lo, c);
      hi = std::max(hi, c);
    }
  if (lo < 0 || hi >= PackedCoordinateLimit)
    throw std::out_of_range("insertTJunctionVertices: coordinates outside [0, 2^21)");
  return hi;
}

/// The sum of a point's coordinates: along an edge, which runs along one axis (as every edge
/// of an EVM's B-Rep does), the difference of its ends' sums is its signed length.
Coord coordinateSum(const Point3& p)
{
  return p[0] + p[1] + p[2];
}

/// How many corners of the set lie strictly inside the edges of a loop: per edge into
/// `inside` (at the edge's first corner), and in all. An edge of length 1 holds none: told by
/// the difference of its ends' coordinate sums, each point's sum made once (a checkerboard's
/// unit squares, all of whose edges are so, cost 20 instructions an edge when each edge's axis
/// was looked for first).
/// `pointsEnd`: the end of the B-Rep's points, up to which the edges ahead (those of the next
/// loops too) are prefetched.
std::size_t countEdgeVertices(const PointRange& points,
  const Point3* pointsEnd,
  const std::int64_t* numbers,
  const CornerSet& corners,
  const Point3& offset,
  std::uint32_t* inside)
{
  constexpr std::size_t ahead = 8;
  std::size_t count = 0;
  const auto countEdge = [&](std::size_t i, std::size_t j, Coord step)
  {
    if (std::size_t(pointsEnd - points.begin()) > i + ahead + 1)
    {
      const Point3* next = points.begin() + i + ahead;
      corners.prefetchBetween(add(next[0], offset), add(next[1], offset));
    }
    const Point3& p = points[i];
    const Point3& q = points[j];
    std::size_t between = 0;
    if (step > 1 || step < -1)
    {
      const int d = edgeAxis(p, q);
      if (d < 3 && std::abs(q[d] - p[d]) > 1)
        between = corners.countBetween(d, add(p, offset), add(q, offset), numbers[i], numbers[j]);
    }
    // Only an edge along one axis has its length in `step` (the edges of B-Reps of EVMs).
    assert(step > 1 || step < -1 || edgeAxis(p, q) == 3 ||
      std::abs(q[edgeAxis(p, q)] - p[edgeAxis(p, q)]) <= 1);
    inside[i] = static_cast<std::uint32_t>(between); // fewer than 2^32 corners in the set
    count += between;
  };
  const std::size_t n = points.size();
  if (n == 0)
    return 0;
  const Coord firstSum = coordinateSum(points[0]);
  Coord sum = firstSum;
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const Coord nextSum = coordinateSum(points[i + 1]);
    countEdge(i, i + 1, nextSum - sum);
    sum = nextSum;
  }
  countEdge(n - 1, 0, firstSum - sum);
  return count;
}

/// Per loop, where it begins once its T-junction vertices are in (`begins`, the last entry:
/// the new number of points); per point, the corners inside the edge that starts there
/// (`inside`).
void newLoopBegins(const BRep& brep,
  const std::vector<std::int64_t>& numbers,
  const CornerSet& corners,
  const Point3& offset,
  const Execution& exec,
  std::vector<std::uint32_t>& inside,
  std::vector<std::size_t>& begins)
{
  const std::size_t n = brep.loops.size();
  begins.resize(n + 1); // every entry written below
  begins[0] = 0;
  inside.resize(brep.points.size());
  exec.forRange(static_cast<std::int64_t>(n),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t l = b; l < e; ++l)
      {
        const BRepLoop& loop = brep.loops[l];
        begins[l + 1] = loop.end - loop.begin +
          countEdgeVertices(brep.loopPoints(static_cast<int>(l)),
            brep.points.data() + brep.points.size(),
            numbers.data() + loop.begin,
            corners,
            offset,
            inside.data() + loop.begin);
      }
    });
  for (std::size_t l = 0; l < n; ++l)
    begins[l + 1] += begins[l];
}

} // namespace

void insertTJunctionVertices(BRep& brep, const Execution& exec)
{
  if (brep.points.empty())
    return;
  const KeyPacker packer = KeyPacker::forMaximum(checkedMaximum(brep.points));
  const CornerSet corners({ { &brep, { 0, 0, 0 } } }, packer);
  std::vector<std::int64_t> numbers = corners.numbersOf(brep, { 0, 0, 0 });
  insertTJunctionVertices(brep, numbers, corners, { 0, 0, 0 }, exec);
}

namespace
{

/// Calls visit(corner in the common grid) for every corner of every B-Rep.
template<typename Visit>
void forEachCorner(const std::vector<PlacedBRep>& breps, Visit&& visit)
{
  for (const PlacedBRep& b : breps)
    for (const Point3& p : b.brep->points)
      visit(add(p, b.offset));
}

/// Slabs of `total` corners, or 1 without threads: each read by its own thread.
std::int64_t cornerSlabs(std::size_t total, const Execution& exec)
{
  return exec.parallelFor && total > 0
    ? std::clamp<std::int64_t>(exec.concurrency, 1, static_cast<std::int64_t>(total))
    : 1;
}

} // namespace

template<typename ForEach>
void CornerSet::boundCorners(std::size_t total,
  ForEach&& forEach,
  const KeyPacker& packer,
  const Execution& exec,
  std::int64_t slabs)
{
  const Coord limit = Coord(1) << packer.bits;
  if (total >= UINT32_MAX)
    throw std::length_error("CornerSet: more than 2^32 corners");
  if (total == 0)
    return;
  // The bounds of each slab, then of all: a corner outside the grid is told after the loop
  // (no exception leaves a thread of the loop).
  std::vector<Point3> slabLo(static_cast<std::size_t>(slabs), Point3{ limit, limit, limit });
  std::vector<Point3> slabHi(slabLo.size(), Point3{ -1, -1, -1 });
  std::vector<char> outside(slabLo.size(), 0);
  exec.forRange(slabs,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t s = b; s < e; ++s)
      {
        Point3 lo = slabLo[s], hi = slabHi[s];
        bool out = false;
        forEach(total * s / slabs,
          total * (s + 1) / slabs,
          [&](const Point3& p)
          {
            for (int d = 0; d < 3; ++d)
            {
              out = out || p[d] < 0 || p[d] >= limit;
              lo[d] = std::min(lo[d], p[d]);
              hi[d] = std::max(hi[d], p[d]);
            }
          });
        slabLo[s] = lo;
        slabHi[s] = hi;
        outside[s] = out;
      }
    });
  if (std::find(outside.begin(), outside.end(), 1) != outside.end())
    throw std::out_of_range("CornerSet: a corner lies outside the common grid");
  Point3 lo = slabLo[0], hi = slabHi[0];
  for (std::size_t s = 1; s < slabLo.size(); ++s)
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], slabLo[s][d]);
      hi[d] = std::max(hi[d], slabHi[s][d]);
    }
  this->Lo = lo;
  for (int d = 0; d < 3; ++d)
    this->Extent[d] = std::uint64_t(hi[d] - lo[d]) + 1;
}

/// The grid points of the box by increasing index: each from the one before by additions,
/// a division only where the index passes to another line along z (pointInBox divides twice
/// per point).
class CornerSet::BoxWalker
{
public:
  BoxWalker(const CornerSet& set, std::uint64_t first)
    : Set(set)
    , Index(first)
    , Local(set.pointInBox(first))
  {
    for (int d = 0; d < 3; ++d)
      this->Local[d] -= set.Lo[d];
  }

  /// Grid point i of the box, i >= the index asked before.
  Point3 pointAt(std::uint64_t i)
  {
    const std::uint64_t ez = this->Set.Extent[2], ey = this->Set.Extent[1];
    std::uint64_t z = std::uint64_t(this->Local[2]) + (i - this->Index);
    this->Index = i;
    if (z >= ez)
    {
      std::uint64_t y = std::uint64_t(this->Local[1]) + z / ez;
      z %= ez;
      if (y >= ey)
      {
        this->Local[0] += static_cast<Coord>(y / ey);
        y %= ey;
      }
      this->Local[1] = static_cast<Coord>(y);
    }
    this->Local[2] = static_cast<Coord>(z);
    const Point3& lo = this->Set.Lo;
    return { lo[0] + this->Local[0], lo[1] + this->Local[1], lo[2] + this->Local[2] };
  }

private:
  const CornerSet& Set;
  std::uint64_t Index; ///< of the point last asked
  Point3 Local;        ///< that point less Lo
};

Point3 CornerSet::pointInBox(std::uint64_t i) const
{
  const Coord z = static_cast<Coord>(i % this->Extent[2]);
  i /= this->Extent[2];
  const Coord y = static_cast<Coord>(i % this->Extent[1]);
  const Coord x = static_cast<Coord>(i / this->Extent[1]);
  return { this->Lo[0] + x, this->Lo[1] + y, this->Lo[2] + z };
}

template<typename ForEach>
void CornerSet::numberCorners(std::size_t total,
  ForEach&& forEach,
  const KeyPacker& packer,
  const Execution& exec)
{
  // One bit per grid point of the corners' box marks the corners, and a corner's number is
  // the rank of its bit: the set bits of the words before it (kept with each word, so that a
  // lookup reads one place) and of its own word below it. The numbers follow the packed keys'
  // order with no sort and no hash table, in 2 bits per grid point of the box. The corners
  // inside an edge along z are the set bits between its ends; along x and y, those of two
  // more bitmaps in which each line along that axis is consecutive (a bit per grid point
  // each), so that a long edge is read a word at a time rather than a cache line per grid
  // step; ordering the corners along the lines of x and y took 28 bytes per corner.
  const std::int64_t slabs = cornerSlabs(total, exec);
  this->boundCorners(total, forEach, packer, exec, slabs);
  assignHugePages(this->Words,
    (this->Extent[0] * this->Extent[1] * this->Extent[2] + 63) / 64,
    RankedWord{ 0, 0 });
  const std::size_t lineWords = this->Words.size();
  assignHugePages(this->LineBits[0], lineWords, std::uint64_t(0));
  assignHugePages(this->LineBits[1], lineWords, std::uint64_t(0));
  this->rankAndListCorners(this->markCorners(total, forEach, exec, slabs), exec);
}

template<typename ForEach>
std::vector<std::vector<std::uint64_t>> CornerSet::markCorners(std::size_t total,
  ForEach&& forEach,
  const Execution& exec,
  std::int64_t slabs)
{
  // With threads, slab 0 marks its corners in Words and LineBits, each other slab in bitmaps
  // of its own (ORed in by rankAndListCorners), when the box is small beside the corners:
  // the bitmaps cost a word per 64 grid points of the box to clear and to OR in, the corners
  // a scattered read and write each.
  const std::size_t words = this->Words.size();
  if (slabs < 2 || 3 * words * std::size_t(slabs - 1) > total / 2)
    slabs = 1;
  std::vector<std::vector<std::uint64_t>> slabBits(static_cast<std::size_t>(slabs - 1));
  const auto mark = [&](std::int64_t s, auto&& setBit, std::uint64_t* line0, std::uint64_t* line1)
  {
    forEach(total * s / slabs,
      total * (s + 1) / slabs,
      [&](const Point3& p)
      {
        const std::uint64_t i = this->indexInBox(p);
        setBit(i >> 6, std::uint64_t(1) << (i & 63));
        const std::uint64_t j0 = this->indexOnLine(0, p), j1 = this->indexOnLine(1, p);
        line0[j0 >> 6] |= std::uint64_t(1) << (j0 & 63);
        line1[j1 >> 6] |= std::uint64_t(1) << (j1 & 63);
      });
  };
  exec.forRange(slabs,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t s = b; s < e; ++s)
      {
        if (s == 0)
        {
          mark(
            s,
            [&](std::uint64_t w, std::uint64_t bit) { this->Words[w].bits |= bit; },
            this->LineBits[0].data(),
            this->LineBits[1].data());
          continue;
        }
        std::vector<std::uint64_t>& own = slabBits[s - 1];
        own.assign(3 * words, 0);
        std::uint64_t* bits = own.data();
        mark(
          s,
          [&](std::uint64_t w, std::uint64_t bit) { bits[w] |= bit; },
          own.data() + words,
          own.data() + 2 * words);
      }
    });
  return slabBits;
}

void CornerSet::rankAndListCorners(const std::vector<std::vector<std::uint64_t>>& slabBits,
  const Execution& exec)
{
  // By runs of words, each by its own thread: the slabs' own bits ORed in and the corners
  // counted, then (after a prefix sum over the runs) the words ranked and their points
  // written at their first word's rank, each found from the point before (BoxWalker) rather
  // than by pointInBox's two divisions.
  const std::size_t words = this->Words.size();
  const std::int64_t runs = exec.parallelFor && words > 0
    ? std::clamp<std::int64_t>(4 * std::int64_t(exec.concurrency), 1, std::int64_t(words))
    : 1;
  const auto runBegin = [&](std::int64_t r) { return words * r / runs; };
  std::vector<std::uint64_t> runStart(static_cast<std::size_t>(runs) + 1, 0);
  exec.forRange(runs,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t r = b; r < e; ++r)
      {
        std::uint64_t count = 0;
        for (std::size_t w = runBegin(r), end = runBegin(r + 1); w < end; ++w)
        {
          for (const std::vector<std::uint64_t>& own : slabBits)
          {
            this->Words[w].bits |= own[w];
            this->LineBits[0][w] |= own[words + w];
            this->LineBits[1][w] |= own[2 * words + w];
          }
          count += static_cast<std::uint64_t>(popCount(this->Words[w].bits));
        }
        runStart[r + 1] = count;
      }
    });
  for (std::size_t r = 1; r < runStart.size(); ++r)
    runStart[r] += runStart[r - 1];
  reserveHugePages(this->Points, runStart.back());
  this->Points.resize(runStart.back());
  exec.forRange(runs,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t r = b; r < e; ++r)
      {
        if (runBegin(r) == runBegin(r + 1))
          continue;
        std::uint64_t rank = runStart[r];
        Point3* out = this->Points.data() + rank;
        BoxWalker at(*this, 64 * std::uint64_t(runBegin(r)));
        for (std::size_t w = runBegin(r), end = runBegin(r + 1); w < end; ++w)
        {
          std::uint64_t bits = this->Words[w].bits;
          this->Words[w].rank = rank;
          rank += static_cast<std::uint64_t>(popCount(bits));
          for (; bits != 0; bits &= bits - 1)
            *out++ = at.pointAt(64 * std::uint64_t(w) + countTrailingZeros(bits));
        }
      }
    });
}

CornerSet::CornerSet(const std::vector<PlacedBRep>& breps, const KeyPacker& packer)
{
  std::size_t total = 0;
  for (const PlacedBRep& b : breps)
    total += b.brep->points.size();
  this->numberCorners(
    total,
    [&](std::size_t, std::size_t, auto&& visit) { forEachCorner(breps, visit); },
    packer,
    Execution());
}

CornerSet::CornerSet(const PointList& corners, const KeyPacker& packer, const Execution& exec)
{
  this->numberCorners(
    corners.size(),
    [&](std::size_t begin, std::size_t end, auto&& visit)
    {
      for (std::size_t i = begin; i < end; ++i)
        visit(corners[i]);
    },
    packer,
    exec);
}

namespace
{

/// Bit k of the result: bit k - 1 of the row (voxel x - 1 at vertex x), `carry` the word before.
std::uint64_t shiftedByOne(std::uint64_t word, std::uint64_t carry)
{
  return (word << 1) | (carry >> 63);
}

/// Per bit: whether the boundary of a set of unit squares turns at the point where the four
/// squares p00, p10 (along u), p01 (along v) and p11 meet: neither both pairs along u nor both
/// pairs along v alike (one or three squares, or two diagonal ones).
std::uint64_t turns(std::uint64_t p00, std::uint64_t p10, std::uint64_t p01, std::uint64_t p11)
{
  return ((p00 ^ p10) | (p01 ^ p11)) & ((p00 ^ p01) | (p10 ^ p11));
}

/// Per bit: whether the faces facing +axis (before & ~after) or -axis (~before & after) of the
/// plane between the voxels `before[4]` and `after[4]` (the four squares around the point in
/// the order p00, p10, p01, p11) turn at the point.
std::uint64_t facesTurn(const std::uint64_t (&before)[4], const std::uint64_t (&after)[4])
{
  std::uint64_t fd[4], bd[4];
  for (int k = 0; k < 4; ++k)
  {
    fd[k] = before[k] & ~after[k];
    bd[k] = ~before[k] & after[k];
  }
  return turns(fd[0], fd[1], fd[2], fd[3]) | turns(bd[0], bd[1], bd[2], bd[3]);
}

/// The corner bits of a word of vertices from the 2x2x2 voxels a[dx][dy][dz] around each.
std::uint64_t cornerBits(const std::uint64_t (&a)[2][2][2])
{
  const std::uint64_t x0[4] = { a[0][0][0], a[0][1][0], a[0][0][1], a[0][1][1] };
  const std::uint64_t x1[4] = { a[1][0][0], a[1][1][0], a[1][0][1], a[1][1][1] };
  const std::uint64_t y0[4] = { a[0][0][0], a[1][0][0], a[0][0][1], a[1][0][1] };
  const std::uint64_t y1[4] = { a[0][1][0], a[1][1][0], a[0][1][1], a[1][1][1] };
  const std::uint64_t z0[4] = { a[0][0][0], a[1][0][0], a[0][1][0], a[1][1][0] };
  const std::uint64_t z1[4] = { a[0][0][1], a[1][0][1], a[0][1][1], a[1][1][1] };
  return facesTurn(x0, x1) | facesTurn(y0, y1) | facesTurn(z0, z1);
}

/// Calls visit(ky, kz, w, bits) with the corner bits of every word w of every row (ky, kz) of
/// vertices that has some, for the planes of vertices kz in [kzBegin, kzEnd).
template<typename Visit>
void forEachCornerWord(const BitVolume& voxels,
  std::int32_t kzBegin,
  std::int32_t kzEnd,
  Visit&& visit)
{
  const std::int32_t nx = voxels.size(0), ny = voxels.size(1), nz = voxels.size(2);
  const std::size_t rowWords = voxels.wordsPerRow();
  if (nx == 0 || ny == 0 || nz == 0)
    return;
  std::vector<Word> empty(rowWords + 1, 0);
  for (std::int32_t kz = kzBegin; kz < kzEnd; ++kz)
    for (std::int32_t ky = 0; ky <= ny; ++ky)
    {
      // The four rows of voxels around the row of vertices (none outside the volume).
      const Word* rows[2][2];
      for (int dy = 0; dy < 2; ++dy)
        for (int dz = 0; dz < 2; ++dz)
        {
          const std::int32_t y = ky - 1 + dy, z = kz - 1 + dz;
          rows[dy][dz] = y < 0 || y >= ny || z < 0 || z >= nz ? empty.data() : voxels.row(y, z);
        }
      for (std::size_t w = 0; w <= rowWords; ++w)
      {
        std::uint64_t a[2][2][2];
        std::uint64_t any = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dz = 0; dz < 2; ++dz)
          {
            const Word* r = rows[dy][dz];
            const Word here = w < rowWords ? r[w] : 0, before = w > 0 ? r[w - 1] : 0;
            a[0][dy][dz] = shiftedByOne(here, before);
            a[1][dy][dz] = here;
            any |= here | before;
          }
        if (any == 0) // no voxel around these vertices (most of a sparse object's box)
          continue;
        if (const std::uint64_t bits = cornerBits(a))
          visit(ky, kz, w, bits);
      }
    }
}

/// The corners of the planes of vertices kz in [kzBegin, kzEnd) of forEachCornerWord, written
/// from `out` on, in the order of the words; returns the end of what it wrote.
Point3* writeFaceCorners(const BitVolume& voxels,
  const Point3& offset,
  std::int32_t kzBegin,
  std::int32_t kzEnd,
  Point3* out)
{
  forEachCornerWord(voxels,
    kzBegin,
    kzEnd,
    [&](std::int32_t ky, std::int32_t kz, std::size_t w, std::uint64_t bits)
    {
      for (; bits != 0; bits &= bits - 1)
      {
        const Coord x = static_cast<Coord>(64 * w + countTrailingZeros(bits));
        *out++ = { x + offset[0], ky + offset[1], kz + offset[2] };
      }
    });
  return out;
}

} // namespace

void appendFaceCorners(const BitVolume& voxels,
  const Point3& offset,
  PointList& out,
  const Execution& exec)
{
  // Counted first, so that the corners (12 bytes each, millions at 256^3) are written once
  // into memory of their size, not copied and faulted in again at every doubling; the
  // counting pass reads the voxels' bits again, much less memory than the corners. With
  // threads, each counts and then writes the corners of its slab of planes of vertices at the
  // place the slabs before leave it: the order is the one-thread order, corner for corner.
  const std::int32_t planes = voxels.size(2) + 1;
  const std::int64_t slabs = exec.parallelFor
    ? std::clamp<std::int64_t>(4 * static_cast<std::int64_t>(exec.concurrency), 1, planes)
    : 1;
  const auto slabBegin = [&](std::int64_t s)
  { return static_cast<std::int32_t>(planes * s / slabs); };
  std::vector<std::size_t> starts(static_cast<std::size_t>(slabs) + 1, 0);
  exec.forRange(slabs,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t s = b; s < e; ++s)
        forEachCornerWord(voxels,
          slabBegin(s),
          slabBegin(s + 1),
          [&](std::int32_t, std::int32_t, std::size_t, std::uint64_t bits)
          { starts[s + 1] += static_cast<std::size_t>(popCount(bits)); });
    });
  starts[0] = out.size();
  for (std::size_t s = 1; s < starts.size(); ++s)
    starts[s] += starts[s - 1];
  const std::size_t needed = starts.back();
  if (out.capacity() < needed) // geometric growth over the objects of a label map
    reserveHugePages(out, std::max(needed, 2 * out.capacity()));
  out.resize(needed);
  exec.forRange(slabs,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t s = b; s < e; ++s)
      {
        const Point3* end =
          writeFaceCorners(voxels, offset, slabBegin(s), slabBegin(s + 1), out.data() + starts[s]);
        assert(end == out.data() + starts[s + 1]);
        (void)end;
      }
    });
}

template<bool Hardware>
VBR_ALWAYS_INLINE void CornerSet::numbersInto(const BRep& brep,
  const Point3& offset,
  std::int64_t* out) const
{
  // The loops wander over the box, whose bits outgrow the cache with the volume: each
  // lookup is a cache miss, so the word of the corner a few places ahead is asked for first.
  // The index of that corner in the box is kept until its turn (a ring of `ahead` indices),
  // not worked out twice. The hint is prefetchKept's: GCC 12 dropped prefetch's here (and
  // with it the point of the ring).
  constexpr std::size_t ahead = 16;
  static_assert((ahead & (ahead - 1)) == 0, "the ring's slot is i & (ahead - 1)");
  // indexInBox of the point at `offset` as one sum, x * extent1 * extent2 + y * extent2 + z
  // + base, in arithmetic modulo 2^64 like indexInBox's (the same index: the coordinates and
  // their sums with the offset and the box's bounds are ints within +-2^22). In locals: written
  // through `out`, the numbers might alias the box's bounds, which were read again at every
  // point (8 of the 38 instructions a point on a checkerboard).
  const std::uint64_t stride0 = this->Extent[1] * this->Extent[2], stride1 = this->Extent[2];
  const std::uint64_t base = std::uint64_t(std::int64_t(offset[0]) - this->Lo[0]) * stride0 +
    std::uint64_t(std::int64_t(offset[1]) - this->Lo[1]) * stride1 +
    std::uint64_t(std::int64_t(offset[2]) - this->Lo[2]);
  const auto indexOf = [=](const Point3& p)
  {
    return std::uint64_t(std::int64_t(p[0])) * stride0 +
      std::uint64_t(std::int64_t(p[1])) * stride1 + std::uint64_t(std::int64_t(p[2])) + base;
  };
  const RankedWord* words = this->Words.data();
  const Point3* points = brep.points.data();
  const std::size_t n = brep.points.size();
  std::uint64_t boxIndexAhead[ahead] = {}; // of points i to i + ahead - 1, at i & (ahead - 1)
  for (std::size_t i = 0; i < std::min(n, ahead); ++i)
    boxIndexAhead[i] = indexOf(points[i]);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::uint64_t& slot = boxIndexAhead[i & (ahead - 1)];
    const std::uint64_t here = slot;
    if (i + ahead < n)
    {
      slot = indexOf(points[i + ahead]);
      prefetchKept(&words[slot >> 6]);
    }
    const RankedWord& w = words[here >> 6]; // rankOf, its bits counted as asked
    out[i] =
      std::int64_t(w.rank) + bitCount<Hardware>(w.bits & ((std::uint64_t(1) << (here & 63)) - 1));
  }
}

namespace
{

/// CornerSet::numbersInto by the portable count, and (numbersByInstruction) compiled for
/// processors with POPCNT: a software count was a fifth of the instructions of numbersOf, which
/// was 11 % of the filter's time on a checkerboard (four lookups per unit square).
void numbersPortable(const CornerSet& set,
  const BRep& brep,
  const Point3& offset,
  std::int64_t* out)
{
  set.numbersInto<false>(brep, offset, out);
}

#if VBR_POPCNT_COPY
__attribute__((target("popcnt"))) void numbersByInstruction(const CornerSet& set,
  const BRep& brep,
  const Point3& offset,
  std::int64_t* out)
{
  set.numbersInto<true>(brep, offset, out);
}
#endif

} // namespace

std::vector<std::int64_t> CornerSet::numbersOf(const BRep& brep, const Point3& offset) const
{
  std::vector<std::int64_t> numbers;
  this->numbersOf(brep, offset, numbers);
  return numbers;
}

void CornerSet::numbersOf(const BRep& brep,
  const Point3& offset,
  std::vector<std::int64_t>& out) const
{
  out.resize(brep.points.size());
#if VBR_POPCNT_COPY
  if (hasPopCountInstruction())
  {
    numbersByInstruction(*this, brep, offset, out.data());
    return;
  }
#endif
  numbersPortable(*this, brep, offset, out.data());
}

void insertTJunctionVertices(BRep& brep,
  std::vector<std::int64_t>& numbers,
  const CornerSet& corners,
  const Point3& offset,
  const Execution& exec)
{
  TJunctionScratch scratch;
  insertTJunctionVertices(brep, numbers, corners, offset, exec, scratch);
}

void insertTJunctionVertices(BRep& brep,
  std::vector<std::int64_t>& numbers,
  const CornerSet& corners,
  const Point3& offset,
  const Execution& exec,
  TJunctionScratch& scratch)
{
  if (brep.loops.empty())
    return;
  // The vertices each loop gains are counted first (in O(1) per edge), so that the loops are
  // written once, concurrently, straight into arrays of their final size: no buffers per run
  // to join, and nothing at all when no edge holds a corner (a checkerboard's unit faces).
  std::vector<std::uint32_t>& inside = scratch.inside;
  std::vector<std::size_t>& begins = scratch.begins;
  newLoopBegins(brep, numbers, corners, offset, exec, inside, begins);
  if (begins.back() == brep.points.size())
    return;
  // Every point and number of the new arrays is written below, loop by loop: what the
  // scratch held before is overwritten, not zeroed first.
  PointList& points = scratch.points;
  std::vector<std::int64_t>& pointNumbers = scratch.numbers;
  points.resize(begins.back());
  pointNumbers.resize(begins.back());
  exec.forRange(static_cast<std::int64_t>(brep.loops.size()),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t l = b; l < e; ++l)
      {
        const BRepLoop& loop = brep.loops[l];
        if (begins[l + 1] - begins[l] == loop.end - loop.begin)
        {
          // No edge of the loop holds a corner (most loops): copied whole, its edges' counts
          // not read again.
          std::copy(brep.points.begin() + loop.begin,
            brep.points.begin() + loop.end,
            points.begin() + begins[l]);
          std::copy(numbers.begin() + loop.begin,
            numbers.begin() + loop.end,
            pointNumbers.begin() + begins[l]);
          continue;
        }
        walkWithEdgeVertices(brep.loopPoints(static_cast<int>(l)),
          numbers.data() + brep.loops[l].begin,
          inside.data() + brep.loops[l].begin,
          corners,
          offset,
          points.data() + begins[l],
          pointNumbers.data() + begins[l]);
      }
    });
  for (std::size_t l = 0; l < brep.loops.size(); ++l)
  {
    brep.loops[l].begin = begins[l];
    brep.loops[l].end = begins[l + 1];
  }
  brep.points.swap(points);
  numbers.swap(pointNumbers);
}

} // namespace vbr
