// The boundary representation of an orthogonal pseudo-polyhedron (or polygon): orthogonal
// faces with holes, each face a plane perpendicular to an axis with its loops of corners,
// oriented outwards. The plane sweeps build it (planeSweep3D in PlaneSweep3D.h for a 3D EVM,
// extractBoundary2D here for a 2D one, both from the 2D solutions of planeSweep2D); the
// filters triangulate its faces (FaceTriangulator.h) after insertTJunctionVertices.
#ifndef vbr_BRep_h
#define vbr_BRep_h

#include "EVM.h"
#include "Execution.h"
#include "Geometry.h"
#include "GridPointIndex.h"
#include "PlaneSweep2D.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

struct BRepLoop
{
  std::size_t begin = 0, end = 0; ///< its corners in BRep::points
  int face = -1;
  bool hole = false;
};

/// The corners of one loop, in order.
struct PointRange
{
  const Point3* first;
  const Point3* last;
  const Point3* begin() const { return this->first; }
  const Point3* end() const { return this->last; }
  std::size_t size() const { return static_cast<std::size_t>(this->last - this->first); }
  const Point3& operator[](std::size_t i) const { return this->first[i]; }
};

struct BRepFace
{
  int axis = 2;       ///< world axis of the normal
  int normalSign = 1; ///< +1: the normal points to +axis
  Coord position = 0; ///< coordinate of the face's plane along axis
  int firstLoop = 0;  ///< loops [firstLoop, firstLoop + loopCount); the first is the outer one
  int loopCount = 0;
  int parent = -1; ///< 2D only: face in one of whose holes this face lies
  int depth = 0;   ///< 2D only: depth in the inclusion tree (faces even, holes odd)
};

struct BRep
{
  std::vector<BRepFace> faces;
  std::vector<BRepLoop> loops;
  /// Corners of all loops, loop after loop; outer loops run counter-clockwise seen from
  /// outside, holes the other way.
  std::vector<Point3> points;
  std::size_t nonManifoldVertices = 0;
  std::size_t holeCount() const;
  PointRange loopPoints(int loop) const
  {
    const BRepLoop& l = this->loops[loop];
    return { this->points.data() + l.begin, this->points.data() + l.end };
  }
};

/// Appends the faces of a 2D solution (loops in (B, C) of `order`) lying in the plane
/// A = `position`, facing +A (normalSign +1) or -A: loops are reversed where needed so that
/// outer loops run counter-clockwise seen from outside.
void appendFaces(const Boundary2D& b2,
  const AxisOrder& order,
  Coord position,
  int normalSign,
  BRep& out);

/// Faces of a 2D EVM with their inclusion tree; loops run counter-clockwise seen from the
/// positive side of the plane's normal axis (holes clockwise).
BRep extractBoundary2D(const EVM& evm, FaceConnectivity connectivity);

/// Inserts into every loop the vertices of other loops lying inside its edges, so that edges
/// of adjacent faces match exactly (no T-junctions).
void insertTJunctionVertices(BRep& brep, const Execution& exec = Execution());

/// The distinct corners of one or more B-Reps placed in a grid common to them (the objects
/// of a label map), numbered in the order they are first met. The T-junction pass finds in
/// it the corners lying inside edges, and the numbers serve as the output's point ids: every
/// corner is a vertex of some output cell.
class CornerSet
{
public:
  /// `packer` must hold every coordinate of the common grid; about `expected` corners.
  CornerSet(const KeyPacker& packer, std::size_t expected);

  /// Adds the corners of `brep`, whose points lie at `offset` in the common grid; returns the
  /// number of each of its points. Throws std::out_of_range for coordinates outside the
  /// packer's range.
  std::vector<std::int64_t> insert(const BRep& brep, const Point3& offset);

  /// The number of the corner at `p` (common grid), or -1.
  std::int64_t find(const Point3& p) const
  {
    return this->Index.find(this->Packer.pack(p[0], p[1], p[2]));
  }

  /// Every corner, in the common grid, by number.
  const std::vector<Point3>& points() const { return this->Points; }

private:
  KeyPacker Packer;
  GridPointIndex Index;
  std::vector<Point3> Points;
};

/// Inserts into every loop of `brep` (at `offset` in the common grid) the `corners` lying
/// inside its edges: with the corners of several B-Reps, the edges of neighbouring B-Reps
/// (the labels of a label map) match exactly as well. `numbers` holds the corner number of
/// every point of `brep` (CornerSet::insert) and follows the points.
void insertTJunctionVertices(BRep& brep,
  std::vector<std::int64_t>& numbers,
  const CornerSet& corners,
  const Point3& offset,
  const Execution& exec = Execution());

} // namespace vbr

#endif
