// Closed triangle meshes with lattice-point corners, and the exact Boolean difference (and union)
// of two of them (the "merge H and CH(S')" of section 4.2 of Schulz 2009), the only place of the
// core that uses CGAL (kept to one translation unit: LatticeMesh.cxx).
//
// The difference is CGAL's Polygon Mesh Processing corefinement
// (corefine_and_compute_difference) on Surface_mesh with the
// Exact_predicates_exact_constructions_kernel: every intersection and every coplanar contact is
// decided exactly, and the result is the regularised difference (closure of the interior). It
// fails, and latticeDifference() returns false, when the result would not be a closed embedded
// 2-manifold (two pieces touching only along an edge or at a point, also when the
// corefinement gives that point as two vertices, on the lattice or not) or when one of its
// corners is not a lattice point; the caller then keeps the two surfaces apart.
#ifndef vbr_LatticeMesh_h
#define vbr_LatticeMesh_h

#include "ConvexHull.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vbr
{

struct LatticeMesh
{
  std::vector<LatticePoint> points;
  /// Counter-clockwise seen from outside.
  std::vector<std::array<std::uint32_t, 3>> triangles;

  /// Appends another mesh, its triangles reversed when `reverse` (a cavity's surface).
  void append(const LatticeMesh& other, bool reverse);
};

/// The faces of a solid convex hull, each fanned from its first corner.
LatticeMesh triangulateHull(const CellList& hull);

/// Whether the mesh is a closed oriented 2-manifold without self-intersections (exact).
bool isClosedEmbeddedManifold(const LatticeMesh& mesh);

/// Whether the mesh is a closed embedded 2-manifold that bounds a volume (CGAL's
/// does_bound_a_volume, exact): its shells consistently oriented with their nesting, which
/// CGAL also grants a mesh whose shells are all turned over (ConvexHullModifier's
/// shellsFaceOutward refuses that). A whole shell turned over is consistent within itself, so
/// isClosedEmbeddedManifold takes it.
bool boundsAVolume(const LatticeMesh& mesh);

/// Whether no two triangles of the mesh that meet the box [lo, hi] intersect but in their
/// shared corners and edges (exact). A closed embedded mesh that a Boolean changed only inside
/// the box is embedded exactly when this holds: two triangles that cross are both new (inside
/// the box) or one new and one meeting it there.
bool isEmbeddedWithin(const LatticeMesh& m, const LatticePoint& lo, const LatticePoint& hi);

/// What the Booleans check of their operands: Check, that both are closed embedded surfaces
/// (corefinement needs them so; false otherwise); Embedded, only that they are closed, the
/// caller knowing them embedded (the self-intersection test of a large operand costs about as
/// much as the corefinement itself).
enum class Operands
{
  Check,
  Embedded
};

/// Bounds of a box of lattice points, [lo, hi] per axis (empty when lo > hi on an axis).
using LatticeBox = std::array<LatticePoint, 2>;

/// a minus b, exactly; false when the result is not a closed 2-manifold with lattice corners.
/// `aChangedIn`, `bChangedIn` (with Operands::Check): the operand is known to be embedded but
/// for its triangles that meet one of these boxes (a Boolean's result, whose first operand was
/// embedded, with the boxes of its new triangles: newTriangleBoxes; none when it is known
/// embedded), so only those are tested for self-intersections. That is the whole test: two
/// triangles that cross are both new or one new and one meeting it, so both meet a new
/// triangle's box; it saves testing a large H again for every pit pressed into it.
bool latticeDifference(const LatticeMesh& a,
  const LatticeMesh& b,
  LatticeMesh& result,
  Operands operands = Operands::Check,
  const std::vector<LatticeBox>* aChangedIn = nullptr,
  const std::vector<LatticeBox>* bChangedIn = nullptr);

/// The boxes of the triangles of `after` that are not triangles of `before` (the same corners
/// in the same cyclic order).
std::vector<LatticeBox> newTriangleBoxes(const LatticeMesh& before, const LatticeMesh& after);

/// a united with b, exactly; false as for the difference.
bool latticeUnion(const LatticeMesh& a,
  const LatticeMesh& b,
  LatticeMesh& result,
  Operands operands = Operands::Check);

/// What latticeBooleanNear found: the result, that the whole Boolean refuses too, or nothing.
enum class NearBoolean
{
  Done,
  Refused,
  Unknown
};

/// The union (`unite`) or the difference of the closed embedded mesh a and a solid convex hull
/// whose open interior misses a and lies outside its solid (a union) or inside it (a
/// difference), the two touching on areas of the hull's boundary: the polyhedron of
/// latticeUnion or latticeDifference, computed from a's triangles near the hull only (those
/// whose box meets the hull's box grown by one). Those triangles, an open mesh whose border
/// (edges of triangles outside the grown box) cannot meet the hull, are corefined with the hull
/// (CGAL, exact); their pieces on the hull's boundary are dropped with the hull's pieces they
/// cover (the two surfaces cancel where they touch), the other pieces kept (the hull's reversed
/// for a difference), the corners off the lattice collapsed as latticeBoolean does, and the
/// result stitched to a's other triangles, which the whole Boolean keeps as they are. So it
/// costs the hull's neighbourhood, not all of a. Refused where the result near the hull is no
/// 2-manifold with lattice corners: two fans of faces at one point (also when CGAL's mesh does
/// not take the kept faces in their order) or an edge of three faces
/// (the whole Boolean's result has the same faces there and is refused too), or a corner off
/// the lattice that no collapse removes (the collapses are greedy and their order differs from
/// the whole Boolean's: it refused too wherever both were run, but that is not proven; a
/// refusal only leaves a join undone). Unknown (the caller runs the whole Boolean) when the
/// configuration is not that one: a piece of a in the hull's open interior, a contact of the wrong
/// orientation (the hull on the other side), no contact, or faces CGAL's mesh does not take.
NearBoolean latticeBooleanNear(const LatticeMesh& a,
  const CellList& convex,
  bool unite,
  LatticeMesh& result);

/// The mesh's triangles that meet the open bounding box of a convex cell list (by their own
/// boxes: a superset of those meeting the hull), for the tests local to a hull.
std::vector<std::array<LatticePoint, 3>> trianglesInBoxOf(const LatticeMesh& surface,
  const CellList& convex);

/// Whether the exact union and the exact difference of the closed mesh and a solid convex
/// hull (its faces merged: every edge a crease) are both bound to have a corner that is not a
/// lattice point, so that latticeUnion and latticeDifference refuse them: an edge of the hull
/// crosses the open interior of a triangle of the mesh transversally at a point off the
/// lattice. That point lies on both surfaces, hence on the surface of the union and of the
/// difference, where the planes of the two faces along the edge meet the triangle's plane in
/// two lines crossing there: a corner that no collapse keeps the shape without. Exact and cheap
/// (the triangles in the hull's box against its edges), to skip such Booleans before the
/// corefinement. False does not promise a lattice result.
bool booleanLeavesTheLattice(const LatticeMesh& surface, const CellList& convex);

/// The other half of that, and the crossings of edges: whether a crease edge of the mesh (its
/// two triangles not coplanar) enters the open interior of the hull from outside at a point
/// off the lattice (through a face, an edge or a diagonal of a face's fan), or an edge of the
/// hull crosses an edge of the mesh (flat or a crease, inside both) at a point off the lattice,
/// going from strictly outside the mesh's solid about that edge to strictly inside. Either way a
/// crease of one solid runs into the other from outside. A crease of the mesh stays a crease of
/// the union and of the difference outside the hull and is gone inside it (interior of the
/// union, outside the difference); a crease of the hull is one of the union outside the mesh's
/// solid and of the difference inside it, and gone on the other side. So the result's crease
/// ends at that point, which is a corner of it off the lattice: both Booleans refuse. Exact; a
/// flat edge of the mesh (a diagonal of a planar face) crossing the hull's surface is left to
/// the Boolean, whose straight crease may not need the point. On the aneurism (v >= 128) this
/// skips 11 of the 29 joins' whole Booleans refused for a corner off the lattice (each a
/// corefinement of a large part of H); at the other 18 a crease of one solid meets an edge of
/// the other lying on one of its faces (a coplanar contact), which is left to the Boolean.
bool creaseLeavesTheLattice(const LatticeMesh& surface, const CellList& convex);

/// The crossings of a crease edge of the mesh and an edge of the hull (inside both, off the
/// lattice) where one solid touches a face of the other, which creaseLeavesTheLattice leaves
/// (coplanar contacts), for the union (`unite`) or the difference: whether the result has a
/// corner there. Along each of the four rays from the point on the two edges the result has
/// a crease, none, or it is not known from the edges alone (the ray on a face of the other
/// solid): along the mesh's crease outside the hull a crease (the result is the mesh's solid
/// there), inside none; along the hull's edge inside the mesh's solid a crease of the difference
/// (the hull's complement) and none of the union, outside the other way round. The point is
/// inside a face or on a straight edge of the result only when its creases there lie on one
/// line through it, so a crease opposite a known none, or creases along both edges, make it a
/// corner off the lattice, which the Boolean refuses. Exact. On the aneurism (v >= 128) it
/// skips 11 of the 18 whole Booleans of the joins that creaseLeavesTheLattice leaves and that
/// are refused for such a corner.
bool edgeCrossingLeavesTheLattice(const LatticeMesh& surface, const CellList& convex, bool unite);

} // namespace vbr

#endif
