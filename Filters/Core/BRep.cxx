// The B-Rep's own operations, after the plane sweeps have found its faces.
//
// appendFaces places the faces of a 2D solution (planeSweep2D works in the (B, C) coordinates
// of a sorting) in their plane A = position of 3D space, reversing the loops of a face whose
// (B, C) orientation is not counter-clockwise seen from outside: B x C = parity * A, so the
// loops turn when the parity of the sorting and the side the face looks to differ.
// extractBoundary2D is that for a 2D EVM, the whole image being one plane.
//
// insertTJunctionVertices makes the edges of adjacent faces match exactly: every corner goes
// into a hash set of packed keys (GridPointIndex, KeyPacker); each loop's edges are walked
// unit step by unit step and the corners of other loops found inside them are inserted in
// order (walkWithEdgeVertices). Two parallel passes over the loops, one counting and one
// writing after a prefix sum, so that no thread allocates. Several B-Reps placed in one grid
// (the objects of a label map) share one set of corners (insertCorners), so that the edges
// of neighbouring objects match too.

#include "BRep.h"

#include "GridPointIndex.h"
#include "RadixSort.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace vbr
{

void appendFaces(const Boundary2D& b2,
  const AxisOrder& order,
  Coord position,
  int normalSign,
  BRep& out)
{
  // planeSweep2D loops are counter-clockwise in (B, C), whose right-hand normal is parity * A.
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

std::size_t BRep::holeCount() const
{
  return static_cast<std::size_t>(std::count_if(
    this->loops.begin(), this->loops.end(), [](const BRepLoop& l) { return l.hole; }));
}

BRep extractBoundary2D(const EVM& evm, FaceConnectivity connectivity)
{
  BRep out;
  const auto& v = evm.vertices();
  const Boundary2D b2 = planeSweep2D(v.data(), v.data() + v.size(), connectivity);
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
  const Point3& offset,
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
      if (corners.find(packer.pack(r[0] + offset[0], r[1] + offset[1], r[2] + offset[2])) >= 0)
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
  insertCorners(brep, { 0, 0, 0 }, packer, corners);
  insertTJunctionVertices(brep, corners, packer, { 0, 0, 0 }, exec);
}

void insertCorners(const BRep& brep,
  const Point3& offset,
  const KeyPacker& packer,
  GridPointIndex& corners)
{
  const std::int64_t highest = brep.points.empty() ? 0 : checkedMaximum(brep.points);
  for (Coord o : offset)
    if (o < 0 || highest + o >= PackedCoordinateLimit)
      throw std::out_of_range("insertCorners: coordinates outside [0, 2^21)");
  for (const Point3& p : brep.points)
    corners.insert(packer.pack(p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]));
}

void insertTJunctionVertices(BRep& brep,
  const GridPointIndex& corners,
  const KeyPacker& packer,
  const Point3& offset,
  const Execution& exec)
{
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
        walkWithEdgeVertices(brep.loopPoints(static_cast<int>(l)),
          corners,
          packer,
          offset,
          [&n](const Point3&) { ++n; });
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
          offset,
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
