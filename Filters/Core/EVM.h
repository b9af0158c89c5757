// The Extreme Vertices Model of an orthogonal pseudo-polyhedron (3D) or polygon (2D).
//
// The extreme vertices of a voxel set are the grid vertices incident to an odd number of
// set voxels (pixels in 2D). They are kept ABC-sorted: each vertex stores its coordinates in
// the order (A, B, C) of the sorting, so that planes of vertices (equal A) and lines of
// vertices (equal A and B) are contiguous runs.
//
// A 2D EVM uses the same storage with A = 0: its vertices are (0, B, C), its lines of vertices
// are runs of equal B, and AxisOrder[0] names the axis normal to its plane. The sections and
// the projections of planes of a 3D EVM are such 2D EVMs, which is what makes the algorithms
// recursive in the dimension.
#ifndef vbr_EVM_h
#define vbr_EVM_h

#include "BitVolume.h"
#include "Execution.h"
#include "Geometry.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vbr
{

/// A point in sorting order (A, B, C), compared lexicographically.
using Vertex = Point3;
/// AxisOrder[k] is the world axis (0 = x, 1 = y, 2 = z) of the k-th sorting coordinate.
using AxisOrder = std::array<int, 3>;

/// The six ABC sortings, by name ("XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX").
AxisOrder axisOrderFromName(const std::string& name);
std::string axisOrderName(const AxisOrder& order);
/// +1 when (A, B, C) is a cyclic permutation of (x, y, z), else -1: B x C = sign * A.
int axisOrderParity(const AxisOrder& order);

class EVM
{
public:
  EVM() = default;
  /// Takes vertices already sorted in `order` (checked in debug builds).
  EVM(int dimension, const AxisOrder& order, std::vector<Vertex> sortedVertices);

  int dimension() const { return this->Dimension; }
  const AxisOrder& order() const { return this->Order; }
  const std::vector<Vertex>& vertices() const { return this->Vertices; }
  std::size_t size() const { return this->Vertices.size(); }
  bool empty() const { return this->Vertices.empty(); }

  /// Vertex i in world axes (x, y, z).
  std::array<Coord, 3> worldVertex(std::size_t i) const;

  /// The same vertex set sorted in another order (same dimension; for 2D only B and C swap).
  EVM sortedAs(const AxisOrder& order, const Execution& exec = Execution()) const;
  /// The same, written into `storage` (its contents dropped): the memory of an EVM no longer
  /// needed (takeVertices), already mapped, rather than fresh pages to fault in.
  EVM sortedAs(const AxisOrder& order, const Execution& exec, std::vector<Vertex> storage) const;

  /// Moves the vertices out, leaving this EVM empty (for their memory: see sortedAs).
  std::vector<Vertex> takeVertices()
  {
    std::vector<Vertex> out;
    out.swap(this->Vertices);
    return out;
  }

  /// Start index of every plane of vertices (3D) or line of vertices (2D), plus size().
  std::vector<std::size_t> planeStarts() const;
  std::size_t planeCount() const;

  /// Rebuilds the voxel set of the given grid size (exact inverse of extraction).
  BitVolume toVoxels(const std::array<std::int32_t, 3>& dims) const;

  bool operator==(const EVM& other) const
  {
    return this->Dimension == other.Dimension && this->Order == other.Order &&
      this->Vertices == other.Vertices;
  }

private:
  /// Stable counting sort on coordinate `key` (1 or 2): the result is sorted in `order`.
  /// With threads, by slabs of the vertices (the same order).
  EVM bucketedOn(int key,
    const AxisOrder& order,
    const Execution& exec,
    std::vector<Vertex> out) const;

  int Dimension = 3;
  AxisOrder Order{ 2, 1, 0 };
  std::vector<Vertex> Vertices;
};

/// Extreme vertices of a 3D voxel set, ZYX-sorted. One pass over the bit rows, XOR of the four
/// rows around each row of vertices, parallel over planes of vertices.
EVM extractEVM(const BitVolume& voxels, const Execution& exec = Execution());

/// What the passes of extractEVM2D count on the way, which would otherwise take passes of
/// their own (BitVolume::count, countSurfels, planesPerAxis).
struct PlanarCounts
{
  std::size_t pixels = 0; ///< set pixels (BitVolume::count)
  /// Sides of set pixels that face an unset pixel or the outside (countSurfels of the
  /// one-slice volume minus the two faces of each pixel along z).
  std::size_t edges = 0;
  std::array<std::size_t, 3> planes{ 0, 0, 0 }; ///< planesPerAxis of the EVM
};

/// Extreme vertices of a 2D pixel set stored in a BitVolume with nz == 1: vertices (0, y, x),
/// order {z, y, x}. With `counts`, also its pixels, boundary edges and lines of vertices.
/// With `memory`, the vertices are written into its memory (it is left empty), grown in small
/// pages: for a caller that hands the vertices' memory back (EVM::takeVertices) for the next
/// image, so that the pages are faulted in once (in small pages: see NumberedPlaneSweeper2D).
EVM extractEVM2D(const BitVolume& pixels,
  const Execution& exec = Execution(),
  PlanarCounts* counts = nullptr,
  std::vector<Vertex>* memory = nullptr);

/// Number of distinct coordinates of the vertices along each world axis (planes of vertices
/// perpendicular to x, y, z).
std::array<std::size_t, 3> planesPerAxis(const EVM& evm);

/// Projection of a plane (or line) of vertices: drops the leading sorting coordinate `level`
/// (sets it to 0), keeping the order.
std::vector<Vertex> project(const Vertex* begin, const Vertex* end, int level);

} // namespace vbr

#endif
