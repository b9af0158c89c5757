// Triangulation of an orthogonal face with holes (exact predicates, no new vertices).
#ifndef vbr_FaceTriangulator_h
#define vbr_FaceTriangulator_h

#include "BRep.h"
#include "MonotoneTriangulator.h"
#include "PolygonTriangulator.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace vbr
{

/// Triangles covering face `f` of `brep`, as indices into the concatenation of its loops'
/// points (outer loop first), oriented like the face (right-hand normal outwards). Vertices
/// shared by several loops (non-manifold contacts) are referred to by their first index.
std::vector<std::array<int, 3>> triangulateFace(const BRep& brep, int f);

/// Polygons covering face `f` exactly, each drawn right by a renderer that draws a polygon
/// as the fan of triangles from its first corner (VTK's OpenGL mapper does), and each simple
/// (no corner twice): the outer loop itself, started at a corner from which its fan covers
/// it, when the face has no holes, its loop passes no corner twice and such a corner exists;
/// else, for a face whose edge-connected parts touch at corners (merged at vertices) and have
/// no holes, each part likewise; otherwise the triangles of triangulateFace grouped into fans
/// round shared corners (each polygon is a corner followed by the far sides of its
/// triangles). Indices and orientation as in triangulateFace; every corner of the loops is a
/// corner of the polygons.
std::vector<std::vector<int>> fanPolygons(const BRep& brep, int f);

/// The edge-connected parts of face `f` when its loops touch at corners (a face merged at
/// vertices) and every part is a polygon without holes of at most 128 corners that passes no
/// corner twice: each part's corners, counter-clockwise seen from outside, indices as in
/// triangulateFace. Empty otherwise: the face is then triangulated as a whole.
std::vector<std::vector<int>> edgeConnectedPartsOf(const BRep& brep, int f);

/// Scratch space of the faces whose polygons are fans of their triangles (fanPolygons), kept
/// from face to face so that such a face allocates nothing once the run has met a larger one.
struct FanScratch
{
  std::vector<std::array<int, 3>> triangles, across;
  std::vector<int> taken, stamp, members, front, back, bestMembers, bestFront, bestBack;
  std::vector<int> bucketEnd;
  std::vector<std::pair<int, int>> edges;
};

/// Scratch space of the ear clipping, kept from face to face: the coordinates of a ring's
/// corners, and the corners still in the ring that may block an ear listed densely (in no order)
/// with theirs.
struct EarScratch
{
  std::vector<std::int64_t> x, y; ///< by corner
  std::vector<int> alive, slot;   ///< the corners listed; the place of each in alive or -1
  std::vector<std::int64_t> aliveX, aliveY; ///< the coordinates of alive's corners

  /// Takes the coordinates of the corners `pts` along axes `x` and `y`.
  void load(const PointRange& pts, int x, int y);
  /// Twice the signed area of triangle abc (corners). Exact in 64 bits: it overflows only for
  /// a face that spans 2^31 voxels along both of its axes, which no image held in memory has.
  std::int64_t turn(int a, int b, int c) const
  {
    return (this->x[b] - this->x[a]) * (this->y[c] - this->y[a]) -
      (this->y[b] - this->y[a]) * (this->x[c] - this->x[a]);
  }
};

/// The cells of a run of faces in flat arrays (no allocation per cell, nor per face but for faces
/// merged at vertices): cell k has the corners `corners[cellEnds[k - 1] .. cellEnds[k])`
/// (cellEnds[-1] = 0), indices as in triangulateFace; the cells of the run's i-th face end at cell
/// `faceEnds[i]`. `ring`, `earCorners`, `loop2D`, `loopNext`, `keys`, `fans` and `monotone` are
/// scratch space reused from face to face.
struct FaceCells
{
  std::vector<int> corners;
  std::vector<std::uint32_t> cellEnds;
  std::vector<std::uint32_t> faceEnds;
  std::vector<int> ring;
  EarScratch earCorners;
  std::vector<Point2L> loop2D;
  std::vector<int> loopNext;
  std::vector<std::uint64_t> keys;
  FanScratch fans;
  MonotoneTriangulator monotone;

  std::size_t cellBegin(std::size_t face) const { return face == 0 ? 0 : this->faceEnds[face - 1]; }
  std::size_t cornerBegin(std::size_t cell) const
  {
    return cell == 0 ? 0 : this->cellEnds[cell - 1];
  }
  /// Closes the current face's list of cells.
  void endFace() { this->faceEnds.push_back(static_cast<std::uint32_t>(this->cellEnds.size())); }
};

/// Appends the triangles of face `f` (triangulateFace) to `cells` as one face.
void appendTriangles(const BRep& brep, int f, FaceCells& cells);

/// Appends the polygons of face `f` (fanPolygons) to `cells` as one face.
void appendFanPolygons(const BRep& brep, int f, FaceCells& cells);

namespace detail
{
/// For tests: the corner appendFanPolygons takes as the apex of a face's outer loop `pts`
/// (coordinates along axes u and v, swapped when `sign` < 0) without its general search, when
/// the loop goes round a rectangle (four left turns, no right turn, straight on elsewhere);
/// -1 for any other loop, which then takes the general search.
int rectangleApexOf(const PointRange& pts, int u, int v, int sign);

/// For tests: fanPolygons with the neighbours of the triangles of every face found by sorting
/// their edges, as for the faces that are not ear-clipped, where fanPolygons takes those of an
/// ear-clipped face from its ear clipping. The two must give the same polygons.
std::vector<std::vector<int>> fanPolygonsFromSortedEdges(const BRep& brep, int f);
} // namespace detail

} // namespace vbr

#endif
