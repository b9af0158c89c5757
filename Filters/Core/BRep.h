// The boundary representation of an orthogonal pseudo-polyhedron (or polygon): orthogonal
// faces with holes, each face a plane perpendicular to an axis with its loops of corners,
// oriented outwards. The plane sweeps build it (planeSweep3D in PlaneSweep3D.h for a 3D EVM,
// extractBoundary2D here for a 2D one, both from the 2D solutions of planeSweep2D); the
// filters triangulate its faces (FaceTriangulator.h) after insertTJunctionVertices.
#ifndef vbr_BRep_h
#define vbr_BRep_h

#include "BitVolume.h"
#include "EVM.h"
#include "Execution.h"
#include "Geometry.h"
#include "PlaneSweep2D.h"
#include "Prefetch.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
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
  /// The faces are vertex-connected regions (FaceConnectivity::Vertex): a face's parts may
  /// touch at corners, where it can be cut into its edge-connected parts.
  bool mergedAtVertices = false;
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

/// The faces of a 2D EVM as extractBoundary2D makes them, every loop corner given by its
/// number among the distinct corners in the order of their keys (the numbers of a CornerSet
/// of this B-Rep alone), as the sweep met them: no set of corners to build, no corner to
/// look up.
struct NumberedBRep
{
  BRep brep;                         ///< the points only when asked for
  std::vector<Point3> corners;       ///< the distinct corners, by number
  std::vector<std::int64_t> numbers; ///< the number of every loop corner, in brep's loops
};
NumberedBRep extractNumberedBoundary2D(const EVM& evm,
  FaceConnectivity connectivity,
  bool withPoints);

/// planeSweep2DNumbered of a 2D EVM, its corners numbered in the order of their keys (u first
/// when u's axis comes first in the EVM's order): the loops of extractNumberedBoundary2D
/// without the B-Rep.
Contours2D numberedContours2D(const EVM& evm, FaceConnectivity connectivity);

/// Inserts into every loop the vertices of other loops lying inside its edges, so that edges
/// of adjacent faces match exactly (no T-junctions).
void insertTJunctionVertices(BRep& brep, const Execution& exec = Execution());

/// A B-Rep and where its points lie in a grid common to several (the objects of a label map).
struct PlacedBRep
{
  const BRep* brep;
  Point3 offset;
};

/// The distinct corners of one or more B-Reps placed in a common grid, numbered in the order
/// of their packed keys (KeyPacker), so that the corners of a line along the last axis have
/// consecutive numbers. A bit per grid point of the corners' box marks them, next to the
/// corners before each word of bits: a corner's number is the rank of its bit, and the
/// corners strictly inside an edge are the set bits between its two ends along the edge's
/// line, so the T-junction pass reads them in order without a search and without ordering
/// the corners along the lines of the other axes. The numbers serve as the output's point
/// ids: every corner is a vertex of some output cell.
class CornerSet
{
public:
  /// Numbers the corners of `breps`. Throws std::out_of_range for a corner outside the
  /// packer's range, std::length_error for 2^32 corners or more.
  CornerSet(const std::vector<PlacedBRep>& breps, const KeyPacker& packer);

  /// The same set from its corners given directly (in the common grid, repeats allowed), e.g.
  /// faceCorners of the objects' voxels: no B-Rep needs to exist yet, so that the faces can be
  /// made, given their numbers and written part after part.
  CornerSet(const std::vector<Point3>& corners, const KeyPacker& packer);

  /// The numbers of the points of `brep` at `offset`, one of the B-Reps numbered (as they were
  /// then): asked for one B-Rep at a time, so that all of them are never held at once.
  std::vector<std::int64_t> numbersOf(const BRep& brep, const Point3& offset) const;

  std::size_t size() const { return this->Points.size(); }

  /// Every corner, in the common grid, by number (empty after releasePoints).
  const std::vector<Point3>& points() const { return this->Points; }

  /// Frees points() once the caller has copied them (the output's points): the numbers and
  /// the T-junction pass keep working on the bits.
  void releasePoints() { std::vector<Point3>().swap(this->Points); }

  /// Calls emit(number, coordinate along `axis`) for the corners strictly between `from` and
  /// `to`, two grid points of the box (common grid) on one line along `axis`, in order from
  /// `from` to `to`: the set bits between theirs, a stride of the box apart.
  template<typename Emit>
  void forEachBetween(int axis, const Point3& from, const Point3& to, Emit&& emit) const
  {
    const Coord step = to[axis] > from[axis] ? 1 : -1;
    const std::int64_t stride = step * this->strideAlong(axis);
    std::uint64_t i = this->indexInBox(from);
    for (Coord c = from[axis] + step; c != to[axis]; c += step)
    {
      i += stride;
      if (this->isCorner(i))
        emit(this->rankOf(i), c);
    }
  }

  /// How many corners lie strictly between `from` and `to`, two corners of one line along
  /// `axis` numbered `fromNumber` and `toNumber`: along the last axis the difference of the
  /// numbers, along the others the set bits between theirs.
  std::size_t countBetween(int axis,
    const Point3& from,
    const Point3& to,
    std::int64_t fromNumber,
    std::int64_t toNumber) const
  {
    if (axis == 2)
      return static_cast<std::size_t>(
        std::max<std::int64_t>(std::abs(toNumber - fromNumber) - 1, 0));
    const Coord steps = std::abs(to[axis] - from[axis]);
    const std::int64_t stride = (to[axis] > from[axis] ? 1 : -1) * this->strideAlong(axis);
    std::uint64_t i = this->indexInBox(from);
    std::size_t count = 0;
    for (Coord k = 1; k < steps; ++k)
    {
      i += stride;
      count += this->isCorner(i);
    }
    return count;
  }

  /// Asks the processor for the first bits countBetween reads for the edge from `from` to
  /// `to` (grid points of the box, maybe not on one line: then nothing), before it needs them.
  void prefetchBetween(const Point3& from, const Point3& to) const
  {
    for (int axis = 0; axis < 2; ++axis)
      if (from[axis] != to[axis])
      {
        const Coord steps = to[axis] - from[axis];
        if ((steps > 1 || steps < -1) && from[axis ^ 1] == to[axis ^ 1] && from[2] == to[2])
          prefetch(&this->Words[(this->indexInBox(from) +
                                  std::uint64_t((steps > 0 ? 1 : -1) * this->strideAlong(axis))) >>
            6]);
        return;
      }
  }

private:
  /// The bits of 64 grid points of the box (indexInBox order) and the corners before them.
  struct RankedWord
  {
    std::uint64_t bits;
    std::uint64_t rank;
  };

  /// The box of grid points holding the corners, its points indexed in lexicographic order
  /// (the last coordinate fastest: the order of their packed keys).
  Point3 Lo{ 0, 0, 0 };
  std::array<std::uint64_t, 3> Extent{ 0, 0, 0 };
  std::vector<RankedWord> Words;
  std::uint64_t indexInBox(const Point3& p) const
  {
    return (std::uint64_t(p[0] - this->Lo[0]) * this->Extent[1] +
             std::uint64_t(p[1] - this->Lo[1])) *
      this->Extent[2] +
      std::uint64_t(p[2] - this->Lo[2]);
  }
  std::int64_t strideAlong(int axis) const
  {
    return axis == 2
      ? 1
      : std::int64_t(axis == 1 ? this->Extent[2] : this->Extent[1] * this->Extent[2]);
  }
  bool isCorner(std::uint64_t i) const { return (this->Words[i >> 6].bits >> (i & 63)) & 1; }
  std::int64_t rankOf(std::uint64_t i) const
  {
    const RankedWord& w = this->Words[i >> 6];
    return std::int64_t(w.rank) + popCount(w.bits & ((std::uint64_t(1) << (i & 63)) - 1));
  }
  Point3 pointInBox(std::uint64_t i) const;
  /// Both constructors: forEach(visit) calls visit(corner) for `total` corners.
  template<typename ForEach>
  void numberCorners(std::size_t total, ForEach&& forEach, const KeyPacker& packer);
  template<typename ForEach>
  void boundCorners(std::size_t total, ForEach&& forEach, const KeyPacker& packer);

  std::vector<Point3> Points;
};

/// The corners of the faces planeSweep3D makes of these voxels (voxel (x, y, z) spans
/// [x, x + 1] x [y, y + 1] x [z, z + 1]), plus `offset`, appended to `out` in no particular
/// order: the grid points where, in the plane of one axis through the point, the faces
/// facing +axis or those facing -axis turn (one or three of the four unit squares around the
/// point, or two diagonal ones: the corners of a loop, under either FaceConnectivity). Read
/// from the 2x2x2 voxels around each point, 64 points per step, without making the faces.
void appendFaceCorners(const BitVolume& voxels, const Point3& offset, std::vector<Point3>& out);

/// Inserts into every loop of `brep` (at `offset` in the common grid) the `corners` lying
/// inside its edges: with the corners of several B-Reps, the edges of neighbouring B-Reps
/// (the labels of a label map) match exactly as well. `numbers` holds the corner number of every
/// point of `brep` (from the CornerSet) and follows the points.
void insertTJunctionVertices(BRep& brep,
  std::vector<std::int64_t>& numbers,
  const CornerSet& corners,
  const Point3& offset,
  const Execution& exec = Execution());

} // namespace vbr

#endif
