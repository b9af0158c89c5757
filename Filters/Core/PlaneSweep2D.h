// 2D EVM -> B-Rep by the plane sweep of Ayala & Vergara, "An improved boundary extraction
// algorithm using a plane-sweep technique" (section 3).
//
// The 2D EVM is swept line of vertices by line of vertices (coordinate u). Each line (a cut,
// a 1D EVM of brinks) is merged with the active 1D section by XOR (formula 1), and during that
// merge every brink and every horizontal edge closed by it is attached to its contour: the
// first sweep builds the oriented edges and the contours. Section intervals that overlap from
// one section to the next are united (union-find), which merges contours of the same face on
// the fly. A non-manifold vertex (a brink that contains a vertex of the active section, paper
// section 3.3) splits the brink and the horizontal edge there; how its four edges pair up is
// decided once the faces are known. The information of the stored sections that the second
// sweep needs (for each interval that starts a face: the edge below it in its section) then
// classifies outer loops and holes and gives the inclusion tree with 1D tests only, without
// any point-in-polygon test. Finally the domino step orders each contour's edges into loops.
//
// Conventions: input vertices are (0, u, v) sorted; every loop keeps its face on the left, so
// an outer loop runs counter-clockwise in the (u, v) plane and a hole clockwise.
#ifndef vbr_PlaneSweep2D_h
#define vbr_PlaneSweep2D_h

#include "DefaultInitAllocator.h"
#include "EVM.h"
#include "Geometry.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace vbr
{

/// How faces meet at a non-manifold vertex (two pixels of the face touching at a corner only).
enum class FaceConnectivity
{
  /// Faces are edge-connected: the vertex splits them into manifold faces (default).
  Edge,
  /// Faces are vertex-connected: the paper's non-manifold faces are kept whole.
  Vertex
};

struct Loop2D
{
  std::size_t begin = 0, end = 0; ///< its corners in Boundary2D::points, face on the left
  int face = -1;
  bool hole = false;
};

struct Face2D
{
  int outerLoop = -1;
  std::vector<int> holeLoops;
  int parent = -1; ///< the face in one of whose holes this face lies, or -1
  int depth = 0;   ///< 0 for top-level faces, parent depth + 2 otherwise
};

struct Boundary2D
{
  std::vector<Face2D> faces; ///< in order of first appearance in the sweep
  std::vector<Loop2D> loops;
  /// The corners of all loops, loop after loop: grown to their number and then written by
  /// the domino step, not zeroed first (see Uninitialized).
  std::vector<Point2, Uninitialized<Point2>> points;
  std::size_t nonManifoldVertices = 0;

  std::size_t holeCount() const
  {
    std::size_t holes = 0;
    for (const Loop2D& loop : this->loops)
      holes += loop.hole ? 1 : 0;
    return holes;
  }

  std::vector<Point2> loopPoints(int loop) const
  {
    return { this->points.begin() + this->loops[loop].begin,
      this->points.begin() + this->loops[loop].end };
  }
};

/// Faces, loops and inclusion tree of a 2D EVM given as vertices (0, u, v) in sorted order.
Boundary2D planeSweep2D(const Vertex* begin,
  const Vertex* end,
  FaceConnectivity connectivity = FaceConnectivity::Edge);

namespace detail
{
struct PlaneSweep2DMemory;
}

/// planeSweep2D for one plane after another (the 3D sweep runs two per plane), in arrays kept
/// from one sweep to the next: emptied, not freed, so that a sweep no larger than an earlier one
/// allocates nothing, and its edges, sections and intervals are neither copied as they grow
/// nor written into pages faulted in afresh.
class PlaneSweeper2D
{
public:
  explicit PlaneSweeper2D(FaceConnectivity connectivity = FaceConnectivity::Edge);
  ~PlaneSweeper2D();
  PlaneSweeper2D(PlaneSweeper2D&&) noexcept;
  PlaneSweeper2D& operator=(PlaneSweeper2D&&) noexcept;

  /// planeSweep2D(begin, end, connectivity): the same boundary, held by this object until the
  /// next sweep. Throws as planeSweep2D does; the object may sweep again after that.
  const Boundary2D& sweep(const Vertex* begin, const Vertex* end);

private:
  std::unique_ptr<detail::PlaneSweep2DMemory> Memory;
};

/// The order in which planeSweep2DNumbered numbers the distinct corners: lexicographic in
/// (u, v), the sweep's own order, or in (v, u).
enum class CornerOrder
{
  UThenV,
  VThenU
};

/// The distinct corners of a 2D solution (its extreme vertices and its non-manifold vertices)
/// as a grid of bits, column by column: corner (u, v) is bit u - uLo of column v - vLo. Read
/// column after column, bit after bit, they come in the order (v, u).
struct CornerColumns
{
  Coord uLo = 0, vLo = 0;
  std::size_t columns = 0;        ///< of v
  std::size_t wordsPerColumn = 0; ///< 64 values of u a word
  std::size_t count = 0;          ///< of corners
  std::vector<std::uint64_t> bits;

  /// Calls visit(u, v) for every corner in the order (v, u).
  template<typename Visit>
  void forEach(Visit&& visit) const
  {
    const std::uint64_t* word = this->bits.data();
    for (std::size_t k = 0; k < this->columns; ++k)
    {
      const Coord v = this->vLo + static_cast<Coord>(k);
      for (std::size_t w = 0; w < this->wordsPerColumn; ++w, ++word)
        for (std::uint64_t b = *word; b != 0; b &= b - 1)
          visit(this->uLo + static_cast<Coord>(64 * w + countTrailingZeros(b)), v);
    }
  }
};

/// The loops of planeSweep2D with each corner given by its number among the distinct corners
/// (a non-manifold vertex is one corner of two loops, or twice of one).
struct Contours2D
{
  Boundary2D boundary;                    ///< its loops index loopCorners; no points
  std::vector<Point2> corners;            ///< the corners by number (sorted; UThenV, sparse VThenU)
  CornerColumns columns;                  ///< the corners by number (by column; dense VThenU)
  std::vector<std::uint32_t> loopCorners; ///< the numbers of all loops' corners, loop after loop

  /// Calls visit(u, v) for every distinct corner in the order of their numbers.
  template<typename Visit>
  void forEachCorner(Visit&& visit) const
  {
    if (this->corners.empty())
      this->columns.forEach(visit);
    for (const Point2& p : this->corners)
      visit(p.u, p.v);
  }
  std::size_t cornerCount() const
  {
    return this->corners.empty() ? this->columns.count : this->corners.size();
  }
};

/// The fewest vertices for which planeSweep2DNumbered finds the corners by column (below, the
/// sort after the sweep stays in the cache and is faster; PlaneSweep2D.cxx has the figures).
constexpr std::size_t FewestVerticesByColumn = 250000;

/// planeSweep2D, with the corners numbered in `order` as the sweep meets them: the same faces,
/// loops (each from the same corner) and inclusion tree, without a later pass to number them.
/// In the order (v, u), with at least `fewestByColumn` vertices and at least one per word of
/// the grid of columns, a first pass over the vertices finds the corners of every column (the
/// extreme vertices and the non-manifold vertices), so that each corner the sweep meets gets
/// its number at once, the next one of its column (Contours2D::columns); otherwise the corners
/// are sorted along v after the sweep (Contours2D::corners). Both give the same numbers.
/// Throws std::length_error for 2^32 corners or 2^31 - 1 edges or more.
Contours2D planeSweep2DNumbered(const Vertex* begin,
  const Vertex* end,
  CornerOrder order,
  FaceConnectivity connectivity = FaceConnectivity::Edge,
  std::size_t fewestByColumn = FewestVerticesByColumn);

namespace detail
{
struct NumberedPlaneSweep2DMemory;
}

/// planeSweep2DNumbered for one image after another (a filter's updates), in arrays kept from
/// one sweep to the next, PlaneSweeper2D's way: a sweep no larger than the one before writes
/// into memory already mapped, not into pages the kernel must first fault in and zero (on the
/// 6001^2 maze about a fifth of an update's time). The memory kept is that of the largest sweep
/// since it was last released, and it is released when a sweep has fewer than a quarter of that
/// sweep's vertices (and that sweep had at least `fewestKept` vertices), so that it stays within
/// a constant times the current sweep's.
/// The memory kept is in small pages, not huge ones: it is faulted in once, at the first sweep,
/// where a fresh huge page can cost six times the 512 small pages it replaces. On a virtual
/// machine whose host takes back the guest's free huge pages (virtio free page reporting, of
/// blocks of 2 MiB and more: Firecracker here), each one is faulted in again on the host, while
/// small pages come from the guest's own fragments (3.1 against 0.5 ms per MB, a fresh process
/// writing 3 GB; 0.2 ms per MB for huge pages the process just freed): the 6001^2 maze's first
/// update spent 1.6-1.8 s in the kernel, 0.6-1.1 s now, most of the rest under VTK's output
/// arrays. The later sweeps pay some TLB misses for it in the domino step's jumps (the 4001^2
/// maze: 0.265-0.268 s of user time per update against 0.244-0.260 s in huge pages).
class NumberedPlaneSweeper2D
{
public:
  explicit NumberedPlaneSweeper2D(std::size_t fewestKept = DefaultFewestKept);
  ~NumberedPlaneSweeper2D();
  NumberedPlaneSweeper2D(NumberedPlaneSweeper2D&&) noexcept;
  NumberedPlaneSweeper2D& operator=(NumberedPlaneSweeper2D&&) noexcept;

  /// planeSweep2DNumbered(begin, end, order, connectivity, fewestByColumn): the same contours,
  /// held by this object until the next sweep. Throws as planeSweep2DNumbered does; the object
  /// may sweep again after that.
  const Contours2D& sweep(const Vertex* begin,
    const Vertex* end,
    CornerOrder order,
    FaceConnectivity connectivity = FaceConnectivity::Edge,
    std::size_t fewestByColumn = FewestVerticesByColumn);

  /// Every array freed.
  void release();

  /// Memory for the vertices of the next image (extractEVM2D's `memory`, which takes it): that
  /// of the image before, handed back by keepVertexMemory, so that its pages too are faulted in
  /// once, not at every image.
  std::vector<Vertex>& vertexMemory();
  /// Keeps the memory of `vertices` (EVM::takeVertices, once swept) for the next image; frees
  /// it instead when it is more than four times what they fill (sweep's rule).
  void keepVertexMemory(std::vector<Vertex>&& vertices);

  /// Below this many vertices the memory kept is small, and never released for being too large.
  static constexpr std::size_t DefaultFewestKept = std::size_t(1) << 16;

private:
  std::unique_ptr<detail::NumberedPlaneSweep2DMemory> Memory;
};

} // namespace vbr

#endif
