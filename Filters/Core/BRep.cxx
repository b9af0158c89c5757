#include "BRep.h"

#include "EVMBoolean.h"

#include <algorithm>
#include <atomic>

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
      for (const Point2& p : b2.loops[l].points)
      {
        Point3 q;
        q[order[0]] = position;
        q[order[1]] = p.u;
        q[order[2]] = p.v;
        loop.points.push_back(q);
      }
      if (reverse)
      {
        std::reverse(loop.points.begin(), loop.points.end());
      }
      out.loops.push_back(std::move(loop));
    };
    addLoop(f2.outerLoop, false);
    for (int h : f2.holeLoops)
    {
      addLoop(h, true);
    }
    out.faces.push_back(face);
  }
  out.nonManifoldVertices += b2.nonManifoldVertices;
}

/// Sweeps one axis: sections, forward and backward differences, 2D solutions.
bool sweepAxis(const EVM& sorted,
  FaceConnectivity connectivity,
  const std::atomic<bool>& abort,
  BRep& out)
{
  const auto starts = sorted.planeStarts();
  const Vertex* v = sorted.vertices().data();
  std::vector<Vertex> section;
  for (std::size_t p = 0; p + 1 < starts.size(); ++p)
  {
    if (abort)
    {
      return false;
    }
    const Coord position = v[starts[p]][0];
    std::vector<Vertex> next = xorVertices(section, project(v + starts[p], v + starts[p + 1], 0));
    const auto* s = section.data();
    const auto* n = next.data();
    const auto fd =
      booleanVertices(s, s + section.size(), n, n + next.size(), 1, BooleanOp::Difference);
    const auto bd =
      booleanVertices(n, n + next.size(), s, s + section.size(), 1, BooleanOp::Difference);
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
  for (BRepFace f : from.faces)
  {
    f.firstLoop += loopBase;
    f.parent = f.parent < 0 ? -1 : f.parent + faceBase;
    to.faces.push_back(f);
  }
  for (BRepLoop& l : from.loops)
  {
    l.face += faceBase;
    to.loops.push_back(std::move(l));
  }
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
  BRep perAxis[3];
  std::atomic<bool> abort{ false };
  // The three sweeps are independent: one task per axis.
  exec.forRange(3,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t a = b; a < e; ++a)
      {
        const int axis = static_cast<int>(a);
        const AxisOrder order{ axis, (axis + 1) % 3, (axis + 2) % 3 };
        if (!sweepAxis(evm.sortedAs(order), connectivity, abort, perAxis[axis]))
        {
          abort = true;
        }
      }
    });
  if (abort || !exec.report(1.0))
  {
    return false;
  }
  for (BRep& b : perAxis)
  {
    appendBRep(out, std::move(b));
  }
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

void insertTJunctionVertices(BRep& brep, const Execution& exec)
{
  // For each axis d, every loop vertex keyed by (other two coordinates, then d): the vertices
  // inside an edge along d are one contiguous range.
  std::vector<Point3> keyed[3];
  for (int d = 0; d < 3; ++d)
  {
    for (const BRepLoop& l : brep.loops)
    {
      for (const Point3& p : l.points)
      {
        keyed[d].push_back({ p[(d + 1) % 3], p[(d + 2) % 3], p[d] });
      }
    }
    std::sort(keyed[d].begin(), keyed[d].end());
    keyed[d].erase(std::unique(keyed[d].begin(), keyed[d].end()), keyed[d].end());
  }
  exec.forRange(static_cast<std::int64_t>(brep.loops.size()),
    [&](std::int64_t b, std::int64_t e)
    {
      std::vector<Point3> refined;
      for (std::int64_t l = b; l < e; ++l)
      {
        auto& points = brep.loops[l].points;
        refined.clear();
        for (std::size_t i = 0; i < points.size(); ++i)
        {
          const Point3& p = points[i];
          const Point3& q = points[(i + 1) % points.size()];
          refined.push_back(p);
          int d = 0;
          while (d < 3 && p[d] == q[d])
          {
            ++d;
          }
          if (d == 3)
          {
            continue;
          }
          const Coord lo = std::min(p[d], q[d]), hi = std::max(p[d], q[d]);
          const Coord c1 = p[(d + 1) % 3], c2 = p[(d + 2) % 3];
          auto first = std::upper_bound(keyed[d].begin(), keyed[d].end(), Point3{ c1, c2, lo });
          auto last = std::lower_bound(keyed[d].begin(), keyed[d].end(), Point3{ c1, c2, hi });
          const std::size_t at = refined.size();
          for (auto it = first; it < last; ++it)
          {
            Point3 r = p;
            r[d] = (*it)[2];
            refined.push_back(r);
          }
          if (p[d] > q[d])
          {
            std::reverse(refined.begin() + at, refined.end());
          }
        }
        if (refined.size() != points.size())
        {
          points = refined;
        }
      }
    });
}

} // namespace vbr
