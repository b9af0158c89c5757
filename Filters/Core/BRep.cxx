#include "BRep.h"

#include "EVMBoolean.h"
#include "GridPointIndex.h"
#include "RadixSort.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>

namespace vbr
{

namespace
{

/// Appends the faces of one 2D solution lying in plane `position` of axis order `order`.
void appendFaces(const Boundary2D& b2,
  const AxisOrder& order,
  Coord position,
  int normalSign,
  BRep& out)
{
  // sweep2D loops are counter-clockwise in (B, C), whose right-hand normal is parity * A.
  const bool reverse = axisOrderParity(order) != normalSign;
  const int faceBase = static_cast<int>(out.faces.size());
  for (const Face2D& f2 : b2.faces)
  {
    BRepFace face;
    face.axis = order[0];
    face.normalSign = normalSign;
    face.position = position;
    face.firstLoop = static_cast<int>(out.loops.size());
    face.loopCount = static_cast<int>(1 + f2.holeLoops.size());
    face.parent = f2.parent < 0 ? -1 : faceBase + f2.parent;
    face.depth = f2.depth;
    const int faceId = static_cast<int>(out.faces.size());
    auto addLoop = [&](int l, bool hole)
    {
      BRepLoop loop;
      loop.face = faceId;
      loop.hole = hole;
      loop.begin = out.points.size();
      const Loop2D& l2 = b2.loops[l];
      for (std::size_t i = l2.begin; i < l2.end; ++i)
      {
        Point3 q;
        q[order[0]] = position;
        q[order[1]] = b2.points[i].u;
        q[order[2]] = b2.points[i].v;
        out.points.push_back(q);
      }
      loop.end = out.points.size();
      if (reverse)
        std::reverse(out.points.begin() + loop.begin, out.points.end());
      out.loops.push_back(loop);
    };
    addLoop(f2.outerLoop, false);
    for (int h : f2.holeLoops)
      addLoop(h, true);
    out.faces.push_back(face);
  }
  out.nonManifoldVertices += b2.nonManifoldVertices;
}

/// A run of consecutive planes of vertices of one sorting, with the section before it.
struct PlaneChunk
{
  const EVM* sorted = nullptr;
  const std::vector<std::size_t>* starts = nullptr; ///< plane starts of *sorted
  std::size_t firstPlane = 0, endPlane = 0;
  std::vector<Vertex> section; ///< S(firstPlane - 1)
};

/// Splits every sorting's planes into about `perAxis` chunks; the sections at chunk starts come
/// from one sequential pass of XORs (formula 1), the cheap part of the sweep.
std::vector<PlaneChunk> chunkPlanes(const EVM (&sorted)[3],
  const std::vector<std::size_t> (&planeStarts)[3],
  std::size_t perAxis)
{
  std::vector<PlaneChunk> chunks;
  for (int axis = 0; axis < 3; ++axis)
  {
    const EVM& evm = sorted[axis];
    const auto& starts = planeStarts[axis];
    const std::size_t planes = starts.size() - 1;
    const std::size_t step = std::max<std::size_t>(1, (planes + perAxis - 1) / perAxis);
    const Vertex* v = evm.vertices().data();
    std::vector<Vertex> section;
    for (std::size_t p = 0; p < planes; ++p)
    {
      if (p % step == 0)
      {
        PlaneChunk c;
        c.sorted = &evm;
        c.starts = &starts;
        c.firstPlane = p;
        c.endPlane = std::min(planes, p + step);
        c.section = section;
        chunks.push_back(std::move(c));
      }
      section = xorVertices(section, project(v + starts[p], v + starts[p + 1], 0));
    }
  }
  return chunks;
}

/// Sweeps a chunk of planes: sections, forward and backward differences, 2D solutions.
bool sweepChunk(const PlaneChunk& chunk,
  FaceConnectivity connectivity,
  const Execution& exec,
  std::atomic<bool>& abort,
  BRep& out)
{
  const EVM& sorted = *chunk.sorted;
  const auto& starts = *chunk.starts;
  const Vertex* v = sorted.vertices().data();
  std::vector<Vertex> section = chunk.section, next;
  for (std::size_t p = chunk.firstPlane; p < chunk.endPlane; ++p)
  {
    if (abort || exec.stopRequested())
    {
      abort = true;
      return false;
    }
    const Coord position = v[starts[p]][0];
    const std::vector<Vertex> plane = project(v + starts[p], v + starts[p + 1], 0);
    next = xorVertices(section, plane);
    // The cut is FD + BD (formula 3): FD = S(i-1) - S(i) is the part of the cut covered by
    // S(i-1), and BD the rest of the cut, so one Boolean and one XOR give both.
    const std::vector<Vertex> fd = booleanVertices(plane.data(),
      plane.data() + plane.size(),
      section.data(),
      section.data() + section.size(),
      1,
      BooleanOp::Intersection);
    const std::vector<Vertex> bd = xorVertices(plane, fd);
    appendFaces(
      sweep2D(fd.data(), fd.data() + fd.size(), connectivity), sorted.order(), position, +1, out);
    appendFaces(
      sweep2D(bd.data(), bd.data() + bd.size(), connectivity), sorted.order(), position, -1, out);
    section.swap(next);
  }
  return true;
}

void appendBRep(BRep& to, BRep&& from)
{
  const int faceBase = static_cast<int>(to.faces.size());
  const int loopBase = static_cast<int>(to.loops.size());
  to.faces.reserve(to.faces.size() + from.faces.size());
  to.loops.reserve(to.loops.size() + from.loops.size());
  for (BRepFace f : from.faces)
  {
    f.firstLoop += loopBase;
    f.parent = f.parent < 0 ? -1 : f.parent + faceBase;
    to.faces.push_back(f);
  }
  const std::size_t pointBase = to.points.size();
  for (BRepLoop l : from.loops)
  {
    l.face += faceBase;
    l.begin += pointBase;
    l.end += pointBase;
    to.loops.push_back(l);
  }
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  to.nonManifoldVertices += from.nonManifoldVertices;
}

} // namespace

std::size_t BRep::holeCount() const
{
  return static_cast<std::size_t>(std::count_if(
    this->loops.begin(), this->loops.end(), [](const BRepLoop& l) { return l.hole; }));
}

bool extractBoundary3D(const EVM& evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  BRep& out)
{
  out = BRep();
  std::atomic<bool> abort{ false };
  // The three cyclic sortings, each from the previous one by one stable bucket pass when
  // the EVM comes ZYX-sorted from extraction: ZYX -> YZX -> XYZ -> ZXY.
  EVM sorted[3];
  sorted[1] = evm.sortedAs({ 1, 2, 0 }, exec);
  sorted[0] = sorted[1].sortedAs({ 0, 1, 2 }, exec);
  sorted[2] = sorted[0].sortedAs({ 2, 0, 1 }, exec);
  // Chunks of planes of all three sweeps are independent tasks.
  const std::vector<std::size_t> starts[3] = {
    sorted[0].planeStarts(), sorted[1].planeStarts(), sorted[2].planeStarts()
  };
  const std::vector<PlaneChunk> chunks = chunkPlanes(sorted, starts, 8);
  std::vector<BRep> perChunk(chunks.size());
  exec.forRange(static_cast<std::int64_t>(chunks.size()),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t c = b; c < e; ++c)
        if (!sweepChunk(chunks[c], connectivity, exec, abort, perChunk[c]))
          abort = true;
    });
  if (abort || !exec.report(1.0))
    return false;
  std::size_t faces = 0, loops = 0, points = 0;
  for (const BRep& b : perChunk)
  {
    faces += b.faces.size();
    loops += b.loops.size();
    points += b.points.size();
  }
  out.faces.reserve(faces);
  out.loops.reserve(loops);
  out.points.reserve(points);
  for (BRep& b : perChunk)
    appendBRep(out, std::move(b));
  return true;
}

BRep extractBoundary2D(const EVM& evm, FaceConnectivity connectivity)
{
  BRep out;
  const auto& v = evm.vertices();
  const Boundary2D b2 = sweep2D(v.data(), v.data() + v.size(), connectivity);
  appendFaces(b2, evm.order(), 0, +1, out);
  return out;
}

namespace
{

/// Calls emit(p) for each corner of a loop and, after it, for each corner of other loops
/// lying strictly inside the edge that starts there, in order along the edge. The grid
/// positions inside an edge are probed one by one, so the work is bounded by the number of
/// unit edges of the boundary.
template<typename Emit>
void walkWithEdgeVertices(const PointRange& points,
  const GridPointIndex& corners,
  const KeyPacker& packer,
  Emit&& emit)
{
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const Point3& p = points[i];
    const Point3& q = points[(i + 1) % points.size()];
    emit(p);
    int d = 0;
    while (d < 3 && p[d] == q[d])
      ++d;
    if (d == 3)
      continue;
    const Coord step = q[d] > p[d] ? 1 : -1;
    Point3 r = p;
    for (r[d] = p[d] + step; r[d] != q[d]; r[d] += step)
      if (corners.find(packer.pack(r[0], r[1], r[2])) >= 0)
        emit(r);
  }
}

/// The largest coordinate of the corners; throws when one lies outside [0, 2^21).
Coord checkedMaximum(const std::vector<Point3>& points)
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

} // namespace

void insertTJunctionVertices(BRep& brep, const Execution& exec)
{
  if (brep.points.empty())
    return;
  // Every corner in a hash set.
  const KeyPacker packer = KeyPacker::forMaximum(checkedMaximum(brep.points));
  GridPointIndex corners(brep.points.size() / 2); // corners repeat about three times
  for (const Point3& p : brep.points)
    corners.insert(packer.pack(p[0], p[1], p[2]));
  // Two parallel passes over the loops: count each loop's corners with the vertices inside
  // its edges, then (after a prefix sum) write them, so that no thread allocates.
  const std::int64_t loops = static_cast<std::int64_t>(brep.loops.size());
  std::vector<std::size_t> start(brep.loops.size() + 1, 0);
  exec.forRange(loops,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t l = b; l < e; ++l)
      {
        std::size_t n = 0;
        walkWithEdgeVertices(
          brep.loopPoints(static_cast<int>(l)), corners, packer, [&n](const Point3&) { ++n; });
        start[l + 1] = n;
      }
    });
  for (std::size_t l = 0; l < brep.loops.size(); ++l)
    start[l + 1] += start[l];
  std::vector<Point3> points(start.back());
  exec.forRange(loops,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t l = b; l < e; ++l)
      {
        Point3* out = points.data() + start[l];
        walkWithEdgeVertices(brep.loopPoints(static_cast<int>(l)),
          corners,
          packer,
          [&out](const Point3& p) { *out++ = p; });
      }
    });
  for (std::size_t l = 0; l < brep.loops.size(); ++l)
  {
    brep.loops[l].begin = start[l];
    brep.loops[l].end = start[l + 1];
  }
  brep.points.swap(points);
}

} // namespace vbr
