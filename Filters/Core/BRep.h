// The boundary representation of an orthogonal pseudo-polyhedron (or polygon): orthogonal
// faces with holes, each face a plane perpendicular to an axis with its loops of corners,
// oriented outwards. The plane sweeps build it (planeSweep3D in PlaneSweep3D.h for a 3D EVM,
// extractBoundary2D here for a 2D one, both from the 2D solutions of planeSweep2D); the
// filters triangulate its faces (FaceTriangulator.h) after insertTJunctionVertices.
#ifndef vbr_BRep_h
#define vbr_BRep_h

#include "BitVolume.h"
#include "DefaultInitAllocator.h"
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

/// Points grown to their size and then written through pointers (appendFaces, the corners
/// of appendFaceCorners, the numbered corners): not zeroed first (see Uninitialized).
using PointList = std::vector<Point3, Uninitialized<Point3>>;

struct BRep
{
  std::vector<BRepFace> faces;
  std::vector<BRepLoop> loops;
  /// Corners of all loops, loop after loop; outer loops run counter-clockwise seen from
  /// outside, holes the other way.
  PointList points;
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
/// outer loops run counter-clockwise seen from outside. Throws std::invalid_argument when
/// `order` is not an order of the three axes.
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
  /// With threads, the numbered points are written side by side (the same points).
  CornerSet(const PointList& corners, const KeyPacker& packer, const Execution& exec = Execution());

  /// The numbers of the points of `brep` at `offset`, one of the B-Reps numbered (as they were
  /// then): asked for one B-Rep at a time, so that all of them are never held at once.
  std::vector<std::int64_t> numbersOf(const BRep& brep, const Point3& offset) const;
  /// The same into `out`, resized to the points of `brep` (the values it held are overwritten,
  /// not zeroed first: a caller keeps it from one B-Rep to the next).
  void numbersOf(const BRep& brep, const Point3& offset, std::vector<std::int64_t>& out) const;

  std::size_t size() const { return this->Points.size(); }

  /// numbersOf into `out` (one number per point of `brep`), each corner's rank counted by
  /// bitCount<Hardware> (PopCount.h): numbersOf runs the copy compiled for POPCNT where the
  /// processor has it. Defined in BRep.cxx, for its two copies.
  template<bool Hardware>
  void numbersInto(const BRep& brep, const Point3& offset, std::int64_t* out) const;

  /// Every corner, in the common grid, by number (empty after releasePoints).
  const PointList& points() const { return this->Points; }

  /// The bounds of the corners (each coordinate's least and greatest; undefined when empty).
  Point3 lowest() const { return this->Lo; }
  Point3 highest() const
  {
    return { this->Lo[0] + static_cast<Coord>(this->Extent[0]) - 1,
      this->Lo[1] + static_cast<Coord>(this->Extent[1]) - 1,
      this->Lo[2] + static_cast<Coord>(this->Extent[2]) - 1 };
  }

  /// Frees points() once the caller has copied them (the output's points): the numbers and
  /// the T-junction pass keep working on the bits.
  void releasePoints() { PointList().swap(this->Points); }

  /// Calls emit(number, coordinate along `axis`) for the corners strictly between `from` and
  /// `to`, two grid points of the box (common grid) on one line along `axis`, in order from
  /// `from` to `to`: along the last axis the set bits between theirs, along the others the set
  /// bits of the line's own bitmap (LineBits), each numbered by its bit in the box.
  template<typename Emit>
  void forEachBetween(int axis, const Point3& from, const Point3& to, Emit&& emit) const
  {
    const bool up = to[axis] > from[axis];
    const std::uint64_t a = this->indexOnLine(axis, from), b = this->indexOnLine(axis, to);
    const std::uint64_t lo = (up ? a : b) + 1, hi = up ? b : a; // bits [lo, hi)
    Point3 p = from;
    const auto visit = [&](std::uint64_t j)
    {
      p[axis] = from[axis] + static_cast<Coord>(std::int64_t(j) - std::int64_t(a));
      emit(this->rankOf(this->indexInBox(p)), p[axis]);
    };
    if (axis == 2)
      forEachSetBit(this->Words, lo, hi, up, visit);
    else
      forEachSetBit(this->LineBits[axis], lo, hi, up, visit);
  }

  /// How many corners lie strictly between `from` and `to`, two corners of one line along
  /// `axis` numbered `fromNumber` and `toNumber`: along the last axis the difference of the
  /// numbers, along the others the set bits between theirs in the line's bitmap, a word at a
  /// time (a long edge costs its length / 64, not a read per grid step).
  std::size_t countBetween(int axis,
    const Point3& from,
    const Point3& to,
    std::int64_t fromNumber,
    std::int64_t toNumber) const
  {
    if (axis == 2)
      return static_cast<std::size_t>(
        std::max<std::int64_t>(std::abs(toNumber - fromNumber) - 1, 0));
    const std::uint64_t a = this->indexOnLine(axis, from), b = this->indexOnLine(axis, to);
    return countSetBits(this->LineBits[axis], std::min(a, b) + 1, std::max(a, b));
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
          prefetch(&this->LineBits[axis][this->indexOnLine(axis, from) >> 6]);
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
  /// For axes 0 and 1, the corners' bits again with the grid points of each line along that
  /// axis consecutive (indexOnLine), so that the corners inside a long edge along x or y are
  /// counted and found a word at a time; 1 bit per grid point of the box each.
  std::array<std::vector<std::uint64_t>, 2> LineBits;
  /// The index of grid point p of the box in LineBits[axis] (axis 0 or 1), or in the box's
  /// own order for axis 2.
  std::uint64_t indexOnLine(int axis, const Point3& p) const
  {
    const std::uint64_t x = std::uint64_t(p[0] - this->Lo[0]),
                        y = std::uint64_t(p[1] - this->Lo[1]),
                        z = std::uint64_t(p[2] - this->Lo[2]);
    if (axis == 0)
      return (y * this->Extent[2] + z) * this->Extent[0] + x;
    if (axis == 1)
      return (x * this->Extent[2] + z) * this->Extent[1] + y;
    return this->indexInBox(p);
  }
  static std::uint64_t bitsOf(const RankedWord& w) { return w.bits; }
  static std::uint64_t bitsOf(std::uint64_t w) { return w; }
  /// The set bits of `words` in [lo, hi), counted a word at a time.
  template<typename Word>
  static std::size_t countSetBits(const std::vector<Word>& words,
    std::uint64_t lo,
    std::uint64_t hi)
  {
    std::size_t count = 0;
    for (std::uint64_t i = lo; i < hi;)
    {
      const std::uint64_t end = std::min(hi, (i | 63) + 1);
      const std::uint64_t span = end - i; // 1 to 64 bits of word i >> 6, from bit i & 63
      const std::uint64_t mask = (span == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << span) - 1)
        << (i & 63);
      count += static_cast<std::size_t>(popCount(bitsOf(words[i >> 6]) & mask));
      i = end;
    }
    return count;
  }
  /// Calls visit(index) for the set bits of `words` in [lo, hi), upwards or downwards.
  template<typename Word, typename Visit>
  static void forEachSetBit(const std::vector<Word>& words,
    std::uint64_t lo,
    std::uint64_t hi,
    bool up,
    Visit&& visit)
  {
    if (lo >= hi)
      return;
    const std::uint64_t first = lo >> 6, last = (hi - 1) >> 6;
    const auto maskedWord = [&](std::uint64_t w)
    {
      std::uint64_t bits = bitsOf(words[w]);
      if (w == first)
        bits &= ~std::uint64_t(0) << (lo & 63);
      if (w == last && ((hi & 63) != 0))
        bits &= (std::uint64_t(1) << (hi & 63)) - 1;
      return bits;
    };
    for (std::uint64_t k = 0; k <= last - first; ++k)
    {
      const std::uint64_t w = up ? first + k : last - k;
      for (std::uint64_t bits = maskedWord(w); bits != 0;)
        if (up)
        {
          visit(64 * w + std::uint64_t(countTrailingZeros(bits)));
          bits &= bits - 1;
        }
        else
        {
          const int top = 63 - countLeadingZeros(bits);
          visit(64 * w + std::uint64_t(top));
          bits &= ~(std::uint64_t(1) << top);
        }
    }
  }
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
  class BoxWalker;
  /// Both constructors: forEach(begin, end, visit) calls visit(corner) for the corners
  /// [begin, end) of `total` (with one thread, [0, total) only).
  template<typename ForEach>
  void numberCorners(std::size_t total,
    ForEach&& forEach,
    const KeyPacker& packer,
    const Execution& exec);
  template<typename ForEach>
  void boundCorners(std::size_t total,
    ForEach&& forEach,
    const KeyPacker& packer,
    const Execution& exec,
    std::int64_t slabs);
  /// Marks the corners' bits; returns the bits that slabs 1, 2, ... marked into bitmaps of
  /// their own (Words' bits, LineBits[0], LineBits[1], a word each per word of Words).
  template<typename ForEach>
  std::vector<std::vector<std::uint64_t>> markCorners(std::size_t total,
    ForEach&& forEach,
    const Execution& exec,
    std::int64_t slabs);
  /// ORs in the slabs' bits, ranks the words and lists the points by number.
  void rankAndListCorners(const std::vector<std::vector<std::uint64_t>>& slabBits,
    const Execution& exec);

  PointList Points;
};

/// The corners of the faces planeSweep3D makes of these voxels (voxel (x, y, z) spans
/// [x, x + 1] x [y, y + 1] x [z, z + 1]), plus `offset`, appended to `out` in no particular
/// order: the grid points where, in the plane of one axis through the point, the faces
/// facing +axis or those facing -axis turn (one or three of the four unit squares around the
/// point, or two diagonal ones: the corners of a loop, under either FaceConnectivity). Read
/// from the 2x2x2 voxels around each point, 64 points per step, without making the faces.
/// With threads, slabs of planes are read side by side; the corners' order is the same.
void appendFaceCorners(const BitVolume& voxels,
  const Point3& offset,
  PointList& out,
  const Execution& exec = Execution());

/// Arrays insertTJunctionVertices works in, kept by a caller that inserts into many B-Reps
/// one after the other (the parts of a streamed sweep): the loops' new points and numbers are
/// written here and swapped with the B-Rep's, whose former arrays are kept here in turn for the
/// next B-Rep (their memory, not their values). Fresh arrays for each part were zeroed, then
/// written, in pages faulted in afresh.
struct TJunctionScratch
{
  PointList points;
  std::vector<std::int64_t> numbers;
  std::vector<std::uint32_t> inside; ///< per point, the corners inside the edge from it
  std::vector<std::size_t> begins;   ///< per loop, where it begins with its new vertices
};

/// Inserts into every loop of `brep` (at `offset` in the common grid) the `corners` lying
/// inside its edges: with the corners of several B-Reps, the edges of neighbouring B-Reps
/// (the labels of a label map) match exactly as well. `numbers` holds the corner number of every
/// point of `brep` (from the CornerSet) and follows the points.
void insertTJunctionVertices(BRep& brep,
  std::vector<std::int64_t>& numbers,
  const CornerSet& corners,
  const Point3& offset,
  const Execution& exec = Execution());

/// The same, in the arrays of `scratch` (TJunctionScratch).
void insertTJunctionVertices(BRep& brep,
  std::vector<std::int64_t>& numbers,
  const CornerSet& corners,
  const Point3& offset,
  const Execution& exec,
  TJunctionScratch& scratch);

} // namespace vbr

#endif
