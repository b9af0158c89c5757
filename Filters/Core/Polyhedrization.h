// Polyhedrization of a surfel boundary into standard faces (J. Francon and L. Papier,
// "Polyhedrization of the Boundary of a Voxel Object", DGCI'99; its section 3): faces are grown
// surfel by surfel, breadth first from a seed, and a surfel joins the face only if the face stays a
// topological disk and all its pointels stay in one standard plane (with the face's surfels all on
// the outer side of that plane, see StandardPlane.h).
//
// Beyond the paper, against its open problem of small faces: a pass that moves surfels from
// smaller faces to a larger neighbour whose plane takes them unchanged (the rim of a large
// planar patch goes back to it; faces emptied disappear), and an optional merging pass that
// hands each small face to the faces around it when they can take all its surfels; both
// keep the two conditions. And the reversion: from the planes and boundary loops
// alone, the surfels and the voxels are recomputed exactly.
#ifndef vbr_Polyhedrization_h
#define vbr_Polyhedrization_h

#include "BitVolume.h"
#include "Execution.h"
#include "StandardPlane.h"
#include "SurfelGraph.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vbr
{

struct PolyhedrizationOptions
{
  /// Largest number of surfels in a face (0: no limit).
  std::size_t maximumFaceSize = 0;
  /// Largest breadth-first depth from the seed (0: no limit).
  std::uint32_t maximumDepth = 0;
  /// Then move surfels from smaller faces to larger neighbouring faces (largest first) when
  /// the larger face's plane takes them unchanged and both faces stay disks; faces emptied
  /// disappear.
  bool moveToLargerFaces = true;
  /// After the growth, hand each face, smallest first, to the faces around it when they can
  /// take all its surfels (each staying a disk of one standard plane, within the size
  /// limit); the face then disappears.
  bool mergeFaces = false;
  /// Faces of more surfels are not offered to their neighbours (their surfels have nearly
  /// always been refused by them already, and each offer costs a recognition).
  std::size_t mergeFacesUpTo = 8;
  /// Also trace the face beyond each loop edge (Polyhedron::across: 4 bytes per loop edge,
  /// held with the whole surfel graph).
  bool facesAcross = true;
};

/// A face's run of ids in one of its Polyhedron's arrays (valid while they are).
struct IdRange
{
  const std::uint32_t* first = nullptr;
  std::size_t count = 0;

  const std::uint32_t* begin() const { return this->first; }
  const std::uint32_t* end() const { return this->first + this->count; }
  std::size_t size() const { return this->count; }
  bool empty() const { return this->count == 0; }
  std::uint32_t operator[](std::size_t i) const { return this->first[i]; }
  std::uint32_t front() const { return this->first[0]; }
  bool operator==(const IdRange& other) const
  {
    return this->count == other.count && std::equal(this->begin(), this->end(), other.begin());
  }
};

struct StandardFace
{
  StandardPlane plane;
  std::vector<std::uint32_t> surfels;
  IdRange loop; ///< graph vertices, counter-clockwise seen from outside
};

/// Move-only: the faces' loops point into its arrays (a move keeps them, a copy would not).
struct Polyhedron
{
  Polyhedron() = default;
  Polyhedron(Polyhedron&&) = default;
  Polyhedron& operator=(Polyhedron&&) = default;
  Polyhedron(const Polyhedron&) = delete;
  Polyhedron& operator=(const Polyhedron&) = delete;

  std::vector<StandardFace> faces;
  /// The loops of all the faces, face after face, and the face beyond each loop edge (with
  /// PolyhedrizationOptions::facesAcross, else empty): arrays of the boundary's size, not heap
  /// blocks per face (most faces are small).
  std::vector<std::uint32_t> loopVertices, loopAcross;

  /// The face beyond each edge of face f's loop (loop[i] to loop[i + 1]); empty when they
  /// were not traced.
  IdRange across(std::uint32_t f) const
  {
    if (this->loopAcross.empty())
      return {};
    const IdRange& loop = this->faces[f].loop;
    return { this->loopAcross.data() + (loop.first - this->loopVertices.data()), loop.count };
  }
  std::vector<std::uint32_t> faceOfSurfel;
  /// Number of faces around each graph vertex; standard vertices have 3 or more.
  std::vector<std::uint8_t> facesAtVertex;
  std::size_t mergedFaces = 0;  ///< faces absorbed by the merging pass
  std::size_t movedSurfels = 0; ///< surfels moved to larger faces
};

/// Grows the faces; returns false when aborted, and `out` is then unspecified (partial faces,
/// or face numbers of faces not yet gathered): not to be read. With `exec.parallelFor` and a
/// concurrency above 1, different boundary components grow on different threads (and their moves,
/// loops and vertex counts are made so too); the result is the same, face for face and in the same
/// order, as on one thread.
bool polyhedrize(const SurfelGraph& graph,
  const PolyhedrizationOptions& options,
  const Execution& exec,
  Polyhedron& out);

/// A face as the reversion reads it: its plane and its boundary loop of pointels.
struct FaceOutline
{
  StandardPlane plane;
  std::vector<Point3> loop;
};

/// The reversion face by face, for outlines made one at a time (revert is this over a list):
/// add each face, then finish. Holds 6 bits per voxel of the grid and the face being filled.
class Reversion
{
public:
  explicit Reversion(const std::array<std::int32_t, 3>& dims);
  ~Reversion();
  Reversion(const Reversion&) = delete;
  Reversion& operator=(const Reversion&) = delete;

  /// Fills the next face's surfels; an error message as revert's, else empty.
  std::string add(const FaceOutline& face);
  /// The voxels, by parity along x; an error message as revert's, else empty.
  std::string finish(BitVolume& voxels, std::size_t* surfelCount = nullptr);

private:
  struct Filling;
  std::array<std::int32_t, 3> Dims;
  std::unique_ptr<Filling> State;
  std::size_t Faces = 0;
};

/// Surfels of each face recomputed from its outline: the squares of the plane enclosed by
/// the loop. Then the voxels, by parity along x, in a grid of `dims`. Returns an error
/// message for outlines that do not bound a disk of their plane, for faces that share
/// surfels (a face given twice), for surfels outside the grid, or "aborted" when `exec` asked
/// to stop; else an empty string. The surfels are kept as bits (6 per voxel of the grid),
/// not listed; `surfelCount`, when given, receives their number.
std::string revert(const std::vector<FaceOutline>& faces,
  const std::array<std::int32_t, 3>& dims,
  BitVolume& voxels,
  const Execution& exec = Execution(),
  std::size_t* surfelCount = nullptr);

/// The surfels of one face recomputed from its outline alone, as the reversion fills them
/// (their voxels within a grid of `dims`); an error message, and no surfels, when the outline
/// does not bound a disk of its plane in the grid.
std::string surfelsOfOutline(const FaceOutline& face,
  const std::array<std::int32_t, 3>& dims,
  std::vector<Surfel>& surfels);

namespace detail
{
/// The cells of the array in which the reversion marks the surfels of `face` (0 when its box
/// is too large for its surfels and they all go to hash indexes instead): for tests of both ways.
std::size_t faceMarkArrayCells(const FaceOutline& face, const std::array<std::int32_t, 3>& dims);
} // namespace detail

} // namespace vbr

#endif
