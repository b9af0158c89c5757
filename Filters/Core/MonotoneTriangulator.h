// Triangulation of an orthogonal polygon with holes in near-linear time, by a sweep that cuts it
// into y-monotone pieces (no new vertices) and the linear triangulation of each piece.
//
// The polygon: loops of integer corners, every edge axis-parallel, the inside on the left of
// every loop; loops may touch at corners (two corners at one place, each turning), and corners
// where a loop goes straight on are allowed. The method:
// 1. The corners that go straight on are set aside; the others form rings whose corners all
//    turn a quarter left or right. Where two corners share a place, each is joined to the edge
//    that turns left from its incoming one (the corner of its own part of the polygon).
// 2. The polygon is shrunk by an infinitesimal delta: each corner moves by delta times the sum of
//    the inward normals of its two edges. The shrunk polygon's loops no longer touch, and its
//    corners are swept from top to bottom in the order (y, dy, x) (y first, then the corner's
//    shift along y, then x: a sweep line tilted by an infinitesimal much smaller than delta).
//    Exact integer keys; no two corners tie.
// 3. The sweep of de Berg et al. (Computational Geometry, ch. 3) joins each split and merge
//    corner to a helper by a diagonal. The edges on the sweep line that have the inside on
//    their right are vertical ones shifted by +delta along x (a horizontal edge is never crossed
//    at a corner: no corner lies inside another edge), so the status is a set of integer x
//    values: a bitset of several levels answers "the edge directly left of a corner" in a few
//    word operations.
// 4. Each y-monotone piece is triangulated by the stack walk down its two chains; orientations
//    are those of the shrunk polygon (exact: the real cross product, then the delta terms).
// 5. Each triangle side that is a loop edge gets back the straight-on corners set aside on it:
//    the triangle is cut into a fan from a corner off that side, so every corner of the loops is
//    a corner of the triangles and no triangle is flat.
// Every triangle is checked to turn strictly left in real coordinates; a failed check makes
// triangulate return false, and the caller uses its general method. The loops must be valid
// (as the B-Rep gives them): not every invalid input is detected (see triangulate).
// Work: a radix sort of the corners and O(log_64 width) per sweep event; the arrays are kept
// from call to call, so a caller triangulating many faces allocates nothing once they have grown.
#ifndef vbr_MonotoneTriangulator_h
#define vbr_MonotoneTriangulator_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

/// The largest member below a value in a set of small integers: a bitset with one summary bit
/// per word on each level above. Empty after every sweep (each inserted slot is erased), so it
/// is never cleared, only grown.
class PredecessorSet
{
public:
  /// Makes room for slots [0, slots).
  void reserve(std::size_t slots);
  void insert(std::size_t slot);
  void erase(std::size_t slot);
  /// The largest member below `slot`, or -1.
  std::int64_t below(std::size_t slot) const;
  /// Empties the set (after a sweep that stopped early).
  void clear();

private:
  std::vector<std::vector<std::uint64_t>> Levels;
};

class MonotoneTriangulator
{
public:
  /// Appends to `triangles` (three corner indices each) the triangles covering the polygon of
  /// the corners `at` ((x, y), coordinates below 2^30 in magnitude), where next[i] follows
  /// corner i in its loop, counter-clockwise round the inside (outer loops counter-clockwise,
  /// holes clockwise). Each triangle turns counter-clockwise; a corner is reported by the
  /// smallest index of the corners at its place.
  /// The loops must be valid: next a permutation of the corners, one outer loop counter-clockwise
  /// with its holes clockwise inside it, as the B-Rep gives them. False, with `triangles` possibly
  /// lengthened, for next not a permutation, an edge not axis-parallel or of no length, three
  /// corners at one place, coordinates too large, and for the invalid loops found by the sweep or
  /// its checks: loops that cross, a hole outside the outer loop, a loop given twice, loops with
  /// overlapping edges, a clockwise outer loop. Not detected (true, with overlapping triangles):
  /// a counter-clockwise hole inside the outer loop, a counter-clockwise loop nested in it.
  /// Also false, leaving the face to a general method, when its x-extent exceeds
  /// MaxWidthPerCorner * corners + MaxWidthBase (the sweep's arrays have one slot per x).
  bool triangulate(const std::vector<std::array<std::int64_t, 2>>& at,
    const std::vector<int>& next,
    std::vector<int>& triangles);

  static constexpr std::int64_t MaxWidthPerCorner = 64, MaxWidthBase = 4096;

private:
  struct Vertex
  {
    std::uint64_t key; ///< its place in the sweep, (y, dy, x): larger first
    std::int32_t x, y;
    int corner;    ///< the corner of the loops it stands for
    int outCorner; ///< the corner whose next edge of its loop leaves this vertex
    int reported;  ///< the first corner at its place
    int next, prev;
    int helper;
    std::int8_t dx, dy; ///< the shift of the shrunk polygon, in delta units
    char type;
    bool inStatus;      ///< its edge (to next) is in the status
    bool diagonalOut;   ///< the edge to next is a diagonal
    bool straightAfter; ///< the loop edge it starts holds corners that go straight on
    bool used;          ///< taken into a monotone piece
  };

  bool setUpRings(const std::vector<std::array<std::int64_t, 2>>& at, const std::vector<int>& next);
  bool joinSharedCorners();
  void shiftCorners();
  bool orderForSweep(std::int64_t maxX);
  void classify();
  bool sweep();
  bool handleVertex(int v);
  bool handleSplit(int v);
  int closeEdgeInto(int v);
  bool helpEdgeLeftOf(int v, int self);
  int leftOf(int v) const;
  void addDiagonal(int a, int b);
  void insertEdge(int v);
  void eraseEdge(int v);
  bool triangulatePieces(const std::vector<int>& next, std::vector<int>& triangles);
  bool triangulatePiece(const std::vector<int>& next, std::vector<int>& triangles);
  bool mergeChains();
  bool emitTriangle(int a, int b, int c, const std::vector<int>& next, std::vector<int>& triangles);
  bool straightCornersOf(int a, int b, const std::vector<int>& next, std::vector<int>& corners);
  bool emitExpanded(std::vector<int>& triangles);
  bool pushTriangle(int a, int b, int c, std::vector<int>& triangles);
  void sortByKey(std::size_t count);
  int orientation(int a, int b, int c) const;
  bool below(int a, int b) const { return this->V[a].key < this->V[b].key; }
  int reportedOf(int corner) const
  {
    const int v = this->VertexOf[corner];
    return v < 0 ? corner : this->V[v].reported;
  }

  const std::vector<std::array<std::int64_t, 2>>* At = nullptr;
  std::vector<Vertex> V;       ///< the turning corners, then the copies made by diagonals
  std::vector<int> VertexOf;   ///< by corner: its vertex, or -1 if it goes straight on
  std::vector<int> PrevCorner; ///< by corner: the corner before it in its loop
  std::vector<std::uint64_t> SortKeys, SortScratch;
  std::vector<int> Order, OrderScratch; ///< the vertices sorted (from the top for the sweep)
  std::vector<std::uint32_t> Count;
  std::vector<int> EdgeAt; ///< by slot: the vertex whose edge is there
  std::int64_t MinX = 0, MinY = 0;
  PredecessorSet Status;
  std::vector<int> Piece, Stack, Side[3];
  std::vector<signed char> ChainOf; ///< by place in Piece: 1 left chain, -1 right, 0 ends
  std::vector<int> Merged;          ///< Piece's places from the top
  int Top[3] = { 0, 0, 0 };         ///< the corners of the triangle being emitted
};

} // namespace vbr

#endif
