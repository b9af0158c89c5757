// EVM -> boundary representation (Aguilera & Ayala's conversion with the 2D plane sweep of
// Ayala & Vergara): orthogonal faces with holes, oriented outwards.
//
// For each axis A the EVM is sorted in the cyclic order (A, B, C) and swept plane of vertices
// by plane of vertices. Each section follows from the previous one by XOR (formula 1); at cut
// i the forward difference FD = S(i-1) - S(i) holds the faces whose outward normal is +A and
// the backward difference BD = S(i) - S(i-1) those facing -A (formula 4). Both are 2D EVMs,
// turned into faces, holes and loops by sweep2D.
#ifndef vbr_BRep_h
#define vbr_BRep_h

#include "EVM.h"
#include "Execution.h"
#include "PlaneSweep2D.h"

#include <array>
#include <cstddef>
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

/// Faces of a 3D EVM (any sorting), grouped by normal axis, then plane, then +A before -A.
/// Returns false (and an empty BRep) when the caller asked to abort.
bool extractBoundary3D(const EVM& evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  BRep& out);

/// Faces of a 2D EVM with their inclusion tree; loops run counter-clockwise seen from the
/// positive side of the plane's normal axis (holes clockwise).
BRep extractBoundary2D(const EVM& evm, FaceConnectivity connectivity);

/// Inserts into every loop the vertices of other loops lying inside its edges, so that edges
/// of adjacent faces match exactly (no T-junctions).
void insertTJunctionVertices(BRep& brep, const Execution& exec = Execution());

} // namespace vbr

#endif
