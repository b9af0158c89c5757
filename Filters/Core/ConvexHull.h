// Exact convex hull of a voxel set (H. Schulz, "Polyhedral Surface Approximation of Non-Convex
// Voxel Sets and Improvements to the Convex Hull Computing Method", FZD-514, 2009, sections
// 3.1 and 3.2; V. Kovalevsky and H. Schulz, "Convex Hulls in a 3-dimensional Space", 2004).
//
// Vertex candidates (section 3.1): a grid vertex (0-cell) is convex when exactly one of its
// eight incident voxels (3-cells) is an object voxel; the object voxels incident to a convex
// 0-cell are the only voxels that can be vertices of the hull of the voxel centres, and one
// pass over the bit volume finds them, sorted lexicographically (x, then y, then z) as the
// list L of the paper.
//
// The hull (section 3.1) grows a current polyhedron CP voxel by voxel. A face is visible from a
// point when the point lies in its open outer half-space, coplanar when it lies on its plane
// (definition VI); every such decision is an exact integer test: face planes n.x = d have
// primitive integer normals (cross products reduced by their gcd) and n.p - d is evaluated in
// 128 bits. A point that sees no face is inside (or on) CP and is dropped. Otherwise the
// visible faces go, and the edges bounding them (the horizon) are joined to the point. The
// faces coplanar with the point are handled by one of the paper's three variants:
//   Extension (default): a coplanar face is extended towards the point, into the convex
//     polygon conv(F + p); new triangles on one plane are one face. Faces are then convex
//     polygons with any number of edges and every face is a facet (no two faces coplanar).
//   Visible: coplanar faces next to the visible ones are removed too and the point is joined
//     to the boundary of the larger region by triangles.
//   Invisible: coplanar faces are kept; the point is joined by triangles to the horizon of the
//     strictly visible faces only.
// The last two give triangulations; mergeCoplanarFaces() then merges every set of faces on
// one plane into its facet (the exact 2D convex hull of their corners, which drops corners
// where the boundary goes straight on), so all three variants give the same polyhedron.
//
// Speed (section 3.2, and the conflict lists of Clarkson and Shor): the first eight points
// processed are the extreme candidates of section 3.2 (min/max x, y, z in the paper's order),
// so the initial polyhedron is their octahedron (built from a tetrahedron of four of them that
// are not coplanar, then the other four). Every point not yet processed is attached to one
// face it sees; when faces are removed their points are tested against the new faces only (a
// point outside the new polyhedron that saw a removed face sees a new face), and points that
// see none are inside for good. After the octahedron the points are processed farthest first
// (as in Qhull and CGAL): a face's next point is its conflict point farthest from its plane
// (largest n.p - d, an exact comparison), which is far more often a vertex of the final hull
// than the next point of L_s, so fewer faces are built only to be removed again. The
// polyhedron does not depend on the order.
//
// Flat input (section 3.1 needs four non-coplanar points for its tetrahedron): the hull of
// coplanar points is their convex polygon, given as two faces with opposite orientations (a
// closed two-sided surface: V - E + F = 2); of collinear points, the segment between the two
// extreme ones (2 vertices, 1 edge, no face); of one point, that point.
//
// Coordinates are lattice points of magnitude below 2^20 (so cross products and plane offsets
// fit in 64 bits and every evaluation in 128 bits); below 2^19, as voxel indices are, the
// evaluations fit in 64 bits and are done so.
#ifndef vbr_ConvexHull_h
#define vbr_ConvexHull_h

#include "BitVolume.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vbr
{

using LatticePoint = std::array<std::int64_t, 3>;

namespace detail
{
/// Lattice vector arithmetic shared by the hull and its modifier (ConvexHull.cxx,
/// LatticeArithmetic.h); the dot product in 128 bits.
inline LatticePoint sub(const LatticePoint& a, const LatticePoint& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
inline __int128 dot(const LatticePoint& a, const LatticePoint& b)
{
  return __int128(a[0]) * b[0] + __int128(a[1]) * b[1] + __int128(a[2]) * b[2];
}
inline LatticePoint cross(const LatticePoint& a, const LatticePoint& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
} // namespace detail

/// The paper's three ways of treating a face coplanar with the new point (section 3.1).
enum class CoplanarFaces
{
  Extension = 0,
  Visible = 1,
  Invisible = 2
};

/// A plane n.x = d, n primitive (gcd of its components 1); the inside is n.x <= d.
struct FacePlane
{
  LatticePoint normal{ 0, 0, 0 };
  std::int64_t offset = 0;
  bool operator==(const FacePlane& o) const
  {
    return this->normal == o.normal && this->offset == o.offset;
  }
  bool operator<(const FacePlane& o) const
  {
    return this->normal != o.normal ? this->normal < o.normal : this->offset < o.offset;
  }
  /// n.p - d, exactly (inline: the hull tests of the modifier evaluate planes in tight loops).
  __int128 evaluate(const LatticePoint& p) const
  {
    return __int128(this->normal[0]) * p[0] + __int128(this->normal[1]) * p[1] +
      __int128(this->normal[2]) * p[2] - this->offset;
  }
};

/// The two-dimensional cell list of section 3.1: vertices with coordinates, edges and faces,
/// each with its incidences. Faces list their vertices counter-clockwise seen from outside.
struct CellList
{
  /// 0: one point, 1: a segment, 2: a flat polygon (two faces), 3: a solid.
  int dimension = -1;
  std::vector<LatticePoint> vertices;
  /// Vertex pairs (lower index first).
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::vector<std::vector<std::uint32_t>> faces;
  std::vector<FacePlane> planes;

  /// Incidences: edges and faces of each vertex, the two faces of each edge (the one where
  /// the edge runs from its lower to its higher vertex first), the edges of each face in the
  /// order of its vertices (edge k from vertex k to vertex k + 1).
  std::vector<std::vector<std::uint32_t>> vertexEdges;
  std::vector<std::vector<std::uint32_t>> vertexFaces;
  std::vector<std::array<std::uint32_t, 2>> edgeFaces;
  std::vector<std::vector<std::uint32_t>> faceEdges;

  /// Fills the edge list and every incidence from the vertices and faces.
  void buildIncidences();
};

/// The plane through a, b and c, normal (b - a) x (c - a) reduced by the gcd of its
/// components (0 when the three points are collinear).
FacePlane planeThrough(const LatticePoint& a, const LatticePoint& b, const LatticePoint& c);

/// Object voxels incident to a convex 0-cell (section 3.1), as (x, y, z) voxel indices,
/// sorted lexicographically.
std::vector<LatticePoint> vertexCandidates(const BitVolume& voxels);

/// The list L_s of section 3.2: the eight extreme points first (duplicates once), then the
/// others in their order. `points` must be sorted lexicographically without duplicates.
std::vector<LatticePoint> extremesFirst(const std::vector<LatticePoint>& points);

/// Exact convex hull of the points (any order, duplicates allowed), processed in the order of
/// L_s. With mergeCoplanar the faces of the Visible and Invisible variants are merged into
/// facets (the Extension method gives facets already).
CellList convexHull(const std::vector<LatticePoint>& points,
  CoplanarFaces coplanar = CoplanarFaces::Extension,
  bool mergeCoplanar = true);

/// Merges faces lying on one plane into their facet: the exact 2D convex hull of their
/// corners (corners where the boundary goes straight on are dropped, with their edges).
void mergeCoplanarFaces(CellList& hull);

/// Whether p lies in the closed hull (exact; for dimension < 3 whether it lies on it).
bool hullContains(const CellList& hull, const LatticePoint& p);

} // namespace vbr

#endif
