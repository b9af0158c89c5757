// A polyhedron H that separates object voxels from background voxels, made from the convex hull
// by recursive pressing-in (H. Schulz, "Polyhedral Surface Approximation of Non-Convex Voxel
// Sets and Improvements to the Convex Hull Computing Method", FZD-514, 2009, section 4).
//
// Voxels are their centres, integer lattice points. H is a closed triangle mesh with lattice
// corners whose coplanar, edge-connected triangles form its faces; no object centre lies outside
// H, no background centre inside, and the centres on H are marked, so that the voxel set can be
// rebuilt from H and its marks alone (revertModifiedHull).
//
// Background components (section 4.1): the background voxels whose centres lie in the closed
// convex hull CH(S) are labelled by the CUDB connected components (face-connected); a component
// is a cavity (definition CA) when no corner (0-cell) of its voxels lies outside or on CH(S), a
// concavity (CO) when the hull faces seen from such corners form one edge-connected set, a tunnel
// (TU) when they form more than one.
//
// Modification (section 4.2, Algorithm 1), with one change that removes the paper's genus-0
// restriction. At each level the current polyhedron is a convex hull C of points of one class
// (object at even levels, background at odd ones). When no point of the other class lies in the
// open interior of C, C is the answer for that level (points of the other class on C are kept on
// the surface and marked). Otherwise all those points in the closed C together span one convex
// polyhedron C' = CH(them) inside C (the role swap of the paper), solved recursively into a set G,
// and the level's answer is the exact regularised Boolean difference C - G (LatticeMesh.h, CGAL
// corefinement with an exact kernel). Because C' lies inside C, their surfaces only touch (at
// corners, along edges or in coplanar pieces of faces) and never cross, so every corner of the
// result is a corner of one of the nested hulls: a lattice point. The difference opens a pit or
// a tunnel wherever C' touches C in pieces of faces, so tori, pierced cubes and porous blobs come
// out with their genus; nothing in it depends on the genus. Where C' touches C only along an
// edge or at a corner the difference would not be a 2-manifold (the touching-voxels case); the
// touching rule below then keeps them apart. Flat sets of points are thickened by their lattice
// neighbours inside C (one lattice step off their plane or line), so every hull is solid.
//
// The touching rule (voxels touching along an edge or at a corner; flat sets). A group is
// pressed in as a pit only when its hull meets C so that C less the hull can be a 2-manifold
// (convexDifferenceIsManifold, decided from the two cell lists before the group is solved), the
// exact difference is a closed 2-manifold with lattice corners and every level below it resolves;
// otherwise the group is kept apart: its points in the open interior of C, grouped again
// (face-connected), each group given one solid region R that meets the surface of C at most in one
// empty lattice triangle T:
//   a cavity: the hull of the group thickened by its lattice neighbours in the open interior of
//     C, strictly inside C, added as an inward-oriented inner surface (section 4.2, last
//     paragraphs);
//   pressed in (definition PR) when no solid fits in the open interior there: R = conv(T + the
//     group), T an empty triangle of the surface of C (no lattice point but its corners; the
//     faces of C fanned and split at lattice points, nearest to the group first) whose corners
//     lie in the open interior of C's parent hull. R meets the surface of C exactly in T and T
//     keeps off every surface C shares with its parent, so C - R is a 2-manifold, and the only
//     centres of T, its corners, stay on H. Of the candidate triangles the nearest whose R holds
//     no centre of C's class in its open interior comes first: R's own groups could only be
//     pressed in from faces of R with every corner inside C, and a flat group (one layer of a
//     thin plate) with T beyond its plane gives R no such face.
// Regions that meet are merged into one group until they are pairwise apart (and apart from the
// pits of the level; if not, the whole level is kept apart). Below a region the same rule holds
// with C as the parent, so regions pressed in from T' keep off T. A centre of the other class on
// the part of C's surface shared with its parent (a pit's floor) stays on H only through a pit
// below C; when that fails the level fails and its parent keeps C apart instead. So every region
// is a pit accepted by the exact difference, a cavity strictly inside C apart from the others,
// or a solid meeting C in one triangle away from the rest: H is a closed 2-manifold.
//
// Separation, by induction on the levels: each level's answer holds every point of its class of
// its hull and no point of the other class in its interior; the lattice count of the hulls
// strictly decreases (a region misses a corner of C), so the recursion ends. The answer is
// checked (a closed embedded 2-manifold whose reversion equals the input); should the first pass
// fail that check or leave a level unresolved, a second pass keeps every level apart (no pits:
// cavities and triangles only, for which the induction needs no difference to be accepted;
// withoutPits). Only when no empty triangle is left for a group is the result incomplete (not
// seen on any input tried since the clean regions come first; the full lobster, v >= 40, failed
// so in both passes before).
//
// Joining shells (after H separates). The recursion can leave H with more shells than the
// object has: a void whose background centres are face-connected to the rest of the background
// through background centres lying on H (a hollow ball whose tunnel into the cavity is sealed by
// a face through the tunnel's centres), or a piece of H whose object centres are
// face-neighbours of object centres of another piece (a level kept apart as a cavity of its
// parent's region, which comes back as a solid of its own). Each such shell is joined to the
// rest: a void by the shortest face-connected path of background centres from it (from a centre
// it encloses or one on its shell: a thin void, a polyhedron spanned by a few background
// centres, encloses none), through centres on H, to a background centre outside H beyond it
// (the step where the path leaves the shell is the crossing); a piece by a pair of
// face-neighbouring object centres, one in it and one in another piece. Near the crossing an empty
// lattice triangle T1 of the shell and one T2 of the rest of H (no lattice point but their corners;
// the 12 nearest of each) span a prism P = conv(T1 + T2) with no lattice point in its open
// interior; P is cut out of H for a void (exact difference) and added to H for a piece (exact
// union), at most 48 candidates: first those whose open interior no triangle of H meets (exact
// separating axes; only they change H on P's boundary alone, a clean tube), nearest first.
// Sound: P's open interior holds no centre, so only the centres on P's boundary can change
// side, and each of them is located again after the Boolean (no object centre may fall
// outside, no background centre inside); a join is kept only when that holds and the exact
// Boolean is a closed 2-manifold with lattice corners, with one shell less and an Euler
// characteristic 2 lower (a tube between two shells), and the whole result is checked once more
// at the end (closed, consistently oriented within each shell, one fan per point, exact
// reversion, and each shell facing away from its solid: exact signed volumes against the
// shells' nesting, shellsFaceOutward; embedded it is by each join's test in its prism's box),
// else H stays as it was. Octahedra conv{c +- e_i} along
// the path (the obvious channel) do not work: their faces cut H's faces at points that are not
// lattice points.
// Cost of the joining: H is embedded before a join and the Boolean changes it only inside P,
// so the operands are not tested for self-intersections again (that test of a large H cost
// about as much as the corefinement), only the result's triangles that meet P's box are; and
// the side of every lattice point of the grid (inside, on or outside H) is found once and,
// after a join, only at the lattice points of P (a point outside the closed P keeps its side).
// Nothing is located when H has one shell. A prism one of whose edges crosses the open
// interior of a triangle of H off the lattice is skipped without a Boolean
// (booleanLeavesTheLattice, LatticeMesh.h): that crossing is a corner of the result, which
// latticeBoolean would refuse; such prisms were nearly all the refused Booleans on real objects
// (83 of 97 on the Al cartoon and the headsq bone at half resolution, none of them a join).
// The join's own part of H then meets creaseLeavesTheLattice (a crease of H entering P through
// a face, an edge or a diagonal, or an edge of P crossing an edge of H, off the lattice), still
// counted as a Boolean tried, so the same prisms are tried, and then edgeCrossingLeavesTheLattice
// (an edge of P meeting a crease of H where one touches a face of the other, for the Boolean to
// be made): on the aneurism (v >= 128) the two skip 11 and 11 of the 29 whole corefinements
// that were refused for a corner off the lattice (7 are left, each of a large part of H).
// When none of the prisms from the 12 nearest empty triangles joins a shell, those from the 60
// nearest are tried (a void reaching out along a 1 wide tunnel in long thin triangles, the
// hollow balls of R 10 with an off-centre tunnel, needs them); the prisms the cheap tests
// reject (centroid, booleanLeavesTheLattice) do not count against the 48 Booleans per round.
// When none of those joins a void, a chain of two prisms is tried. A void whose shell reaches the
// crossing only in long thin triangles has no empty prism at all: a 1 wide off-centre tunnel into a
// hollow ball leaves the void's shell ending in a cone whose apex is the tunnel's last centre, with
// a lattice plane of object centres between that apex and the hull face beyond (6 of the 72 hollow
// balls of R 8 to 10 in the tests, whose void stays an extra shell in both passes without it). The
// chain passes through a middle triangle M of lattice points strictly inside H within one step of
// the crossing (the 16 nearest): P1 = conv(T1 + M) from one of the 12 nearest empty triangles of
// the void's shell and P2 = conv(M + T2) to one of the rest of H, M a face of both (T1 and T2 on
// its two sides), each with no lattice point in its open interior and its open interior missing H.
// P1 is cut out first, a dent kept only when the exact difference is a closed 2-manifold with
// lattice corners, as many shells, the same Euler characteristic and every centre of P1 on its
// side; then each P2 is tried as a join (the checks above); H keeps neither unless a P2 joins. At
// most 8 dents per void, tried only after both rounds of single prisms failed; the cheap tests run
// on a P2 only once a P1 from the other side of M passed them (a chain search on the hollow balls
// takes 0.005 to 0.010 s of CPU).
//
// The object's topology. Separation alone does not fix H's genus: a thin torus (a tube two
// voxels thick) has every background centre of its hole on its hull's faces, and no lattice
// point lies strictly between its top and bottom faces, so the hull separates as a sphere. When
// the object is well-composed (its boundary a 2-manifold whose genus H must have), H is
// compared with its boundary: the Euler characteristic, twice that of the union of the closed
// voxel cubes counted from the 2x2x2 blocks, and the number of surfaces, the object's
// face-connected components plus the background's that do not reach the grid's border.
// Only these totals are compared here, not shell by shell: two tori whose H were a shell of
// genus 2 and a sphere would pass (Euler characteristics -2 + 2 against 0 + 0, two surfaces
// each). The core tests compare each shell with the surface between the object component and
// the background component on its two sides (their own Euler characteristic, from the surfels
// between them); a per-shell check here would need both labellings of the grid (the
// components are only counted, from their boxes).
// Missing handles: while H has that many shells and a higher Euler characteristic, a handle is
// cut where a wall of H seals a tunnel: two face-neighbouring background centres, neither
// inside H and one on it, whose midpoint lies strictly inside H (the hole's centres on the top
// and bottom faces of the thin torus). The prisms conv(T1 + T2) between the 12 (then 60)
// nearest empty triangles of H about each of the two centres, with no lattice point in their
// open interior, are cut out as above and kept only when the exact difference is a closed
// 2-manifold with lattice corners, as many shells, an Euler characteristic 2 lower (one handle
// more) and every centre of the prism on its side; 16 crossings are tried per handle, and the
// whole is checked at the end. Any one handle cut there is right for an object of one
// component; with several, the handle could in principle land on another component than the
// one missing it (the total is what is compared).
// Spurious handles and extra shells: the pits can leave a ring of object voxels about a wide
// tunnel as a torus of its own, which a join then ties to the rest by one tube, a handle the
// object has not (a hollow ball of R 11 with a 5 wide tunnel into a cavity of radius 6). When
// H, its shells joined and its handles cut, still has not the object's topology, H with every
// level kept apart (the second pass, its shells joined and its handles cut as well) is made
// and kept when it has (kept apart, the ring stays part of its level's solid; a hollow ball
// with a spurious handle and a real tunnel beside the cavity gets a sphere whose sealed tunnel
// is then cut). The count costs one pass over the grid (the 2x2x2 blocks, about 0.02 s of CPU
// on 131^3) and, for a well-composed object, two component labellings (4 bytes per voxel;
// not measurable against the rest on a ball of radius 64, which cut no handle and solved no
// components apart); the second H is made only when the first has not the object's topology.
// Not covered by that timing, and limits of the method as it stands: each search for wall
// crossings locates the midpoint of every candidate pair of background centres by scanning all
// triangles of H, each handle tries up to 16 crossings with up to 2 rounds of 48 Booleans
// each, and components first labels the object's points again and makes H of every part.
// Components first: one H for several objects presses in every gap between them, level after
// level, and the pressing-in between two objects can leave a bridge that the joins keep, so
// that one H for both is one shell (two balls 5 voxels apart give a surface of genus 2, a ball
// beside a thin torus one sphere). So the object's vertex-connected components (voxels
// touching at an edge or a corner stay together: the touching rule decides there) are first
// made into parts that cannot meet: two solid parts whose convex hulls share no point (H of a
// solid part lies in its hull: pits and handles are cut out of it, cavities and joins lie
// inside), other parts (flat ones, whose prism reaches one step off their plane, and
// segments) whose boxes grown by one voxel miss each other; parts that may meet are merged,
// until none may. With two parts or more, each in the grid, H of each part alone is made in
// the part's box (the rest of the object its background there) and their union is kept when
// it separates (with the object's topology when the object is well-composed); otherwise the
// object is solved as one, and when that H of a well-composed object misses its topology, the
// union of the H of each component alone (parts not merged) is tried as a last resort. The check
// stays: nothing else keeps a centre of one part off another part's H. A flat part whose prism
// would leave the grid makes the object solved as one, so only a flat object's H has centres off
// the grid. The faces' levels are those of each part's own H, carried triangle by triangle (level
// 0: a face of its part's hull); one plane can hold a face of one part's hull and the bottom of
// another's pit. The parts share the progress range of this step. On the lobster at v >= 128 (one
// component of 62,826 voxels, 130 smaller ones, not well-composed) the smaller components took 15.5
// s of CPU as one object and 3.2 s one by one; the whole object 39 s before, 30 s with the parts
// (the largest part, the large component with the 36 small ones inside its hull, takes most of it).
// Not done (the README's limits): shells for which no prism or chain of those is accepted (none
// left in the tests' hollow balls and porous blobs), spurious handles on objects that are not
// well-composed or where the second pass has them too (a join can only add a tube and a cut a
// handle, never remove one); flat objects are below.
//
// Flat objects (every object centre in one plane x_a = c of the grid's axes: a plate, a ring,
// a row, one voxel, a 2D image): no hull of theirs is solid, so H is made in the plane. The
// layer is solved by the 2D modifier (ConvexHullModifier2D.h: polygons with holes, lattice
// corners, pairwise apart) and each polygon P becomes the prism P x [c - 1, c + 1]: its caps
// are P's triangles, its sides a quad per loop edge. It separates: the centres of the plane
// lie on P's side as they do in 2D (strictly inside the prism or on its sides), the planes
// c - 1 and c + 1 hold only background centres, which lie on the caps or outside, and beyond
// them nothing is inside. The loops are simple and apart, so the prisms are closed 2-manifolds
// apart from each other, and a prism's genus is its polygon's number of holes: a ring gives a
// torus. Pixels touching only at a corner share one polygon (the 2D touching rule), so two
// squares touching at a corner give one prism. A row or a point is a lattice triangle in the
// plane (thickened by a lattice point off its line, a background centre), a prism of genus 0.
// Corners may lie beyond the grid (caps beside its first or last layer, a thickened corner);
// the reversion reads the grid's rows only and the centres beyond are background. A hole of a
// polygon whose face-connected background reaches a centre not strictly inside the polygon's
// outer loop (a dent under a hull edge that passes between lattice points, as beside an L's
// inner corner) is no hole of the object: it is filled below the plane, a pit from the top cap
// down to its floor at c (the hole's region, whose centres are background and lie on it), so
// it adds no handle; a hole of the object never reaches out (a centre strictly inside a ring
// of object centres is strictly inside every loop about the ring). Levels: the caps have their
// polygon's level (0 for the object's, 2 for an island in a hole), the sides and a filled
// hole's floor their loop's.
// Thin holes: a hole of the object whose centres lie in one row (or a single voxel) inside a
// ring one voxel wide has no lattice triangle inside the polygon's hull about it, so the 2D
// modifier opens it as a notch and the prism loses its handle. Such lost holes (bounded
// face-connected background components of the layer in one row, outside every hole of the
// polygons, their eight neighbours object centres) get it back by a cut: H united with the
// holes' box two lattice steps wider than them from c - 1 to c + 1 (its open interior holds,
// in the plane, the holes and their neighbours only; outside the plane only caps) less, for
// each hole B, the prism of B's hexagon (the hull of B's four neighbours, which holds B alone
// inside, B's neighbours on it). That is the ring's box one step thicker less a prism about
// its hole, a solid of genus 1 with lattice corners beyond the object's hull. The cut is kept
// when the exact Booleans give a closed 2-manifold with lattice corners that separates (the
// reversion is exact), with as many shells and one handle more per hole; all lost holes are
// tried together first (one notch can hold several, and a hole on another's box would come
// inside it), then one by one, at most 16 per object (each try costs two exact Booleans of
// H or more). Its faces' levels then go by plane (the box's planes 0, the tunnels' 1; an
// island's cap takes the level of the first cap in its plane).
// The topology, shell by shell. The prisms and cuts above can still miss it: two thin holes one
// voxel apart keep no handle (their tunnels would touch along the voxel between them), an island in
// a thin hole is joined to the ring by the notch, a dent that holds an island keeps its hole, and a
// component the plane's modifier puts on another polygon's loop shares that polygon's prism. So H
// of a well-composed layer (no two object pixels touching only at a corner; then the object's
// boundary is a 2-manifold) is checked against the layer shell by shell: one shell per
// face-connected component, holding (inside or on it) all of that component's centres and no
// other's, with the Euler characteristic 2 (V - E + F) of the component's pixels, their edges and
// their 2 x 2 blocks (that complex has the homotopy type of the union of the closed pixel squares).
// When it differs (or the plane's polygons are incomplete), H is the layer's sheared pixel solid
// instead. The parallelepiped of pixel p, with top p + [0, 1]^2 at c + 1 and bottom p + [-1, 0]^2
// at c - 1 (in the plane axes), has the pixel's square p + [-1/2, 1/2]^2 as its section at c: it is
// the image of the square's prism under the shear (y, t) -> (y + (t - c) / 2 (1, 1), t), whose
// determinant is 1, so the parallelepipeds of all pixels tile the slab face to face and the union U
// of the object pixels' ones is the shear of the pixel union's prism. Every corner is a lattice
// point (the squares' corners at c +- 1). The shear is affine, so U has the topology of the union
// of the closed pixel squares times an interval: one solid per face-connected component (components
// of a well-composed layer are never 8-adjacent, so their squares are apart), a 2-manifold boundary
// (no two squares of it meet at a corner only) of genus its number of holes. It separates: a
// lattice point of the plane c lies in U exactly when it is an object centre, strictly inside (the
// centre of its square); the planes c +- 1 meet U only in its caps (their centres on H,
// background); nothing lies beyond. H is then the boundary of U: per object pixel two cap squares,
// per pixel edge between an object and a background pixel a wall (a lattice parallelogram, no
// lattice point but its corners), merged into faces by plane. Levels follow the nesting of the
// layer's regions: a component at depth k (regions crossed from the outer background: 1 for the
// object about it, 3 for an island in its hole) has caps of level k - 1, a wall the level of the
// deeper of its two regions less one (0 outside, 1 about a hole, 2 about an island). The counts:
// its holes as cavities, no concavities or cut handles. Layers that are not well-composed keep the
// prisms (no one topology to match; they separate as above). Sets of no volume off the axes'
// planes (never face-connected) are given one by a lattice basis (LatticeBasis.h). A segment
// a..b on a line of primitive direction d is the tetrahedron conv{a, b, x, y} with (d, x - a,
// y - a) a basis of Z^3 (x - a = +-u + k d and y - a = +-w + j u + k' d for the reduced basis
// (d, u, w)): no lattice point lies inside it, the segment's centres lie on an edge and the two
// other corners are background centres on H. A flat set in a plane n . p = c is the
// pyramid over its convex polygon with an apex in the plane n . p = c +- 1 next to it: no lattice
// plane lies between, so the pyramid's lattice points are those of the polygon (object centres,
// and background ones on the base, marked) and the apex. Both are solids of genus 0; their extra
// corners are taken inside the grid when the near ones tried allow it (else they lie off it,
// background by definition). Such a set's voxels touch along edges or at corners, or not at
// all: parts that cannot meet are first solved apart as for solids (each voxel apart its own
// prism, keeping the topology), unless a part is itself a segment with no direction component
// +-1 or a polygon off the axes' planes (its solid's corners may leave its box); voxels apart
// whose grown boxes meet, on the grid's side, or with such a part share the one tetrahedron or
// pyramid: one shell for several components there, noted in `failure` (the filter warns).
//
// Cost: groups merge from their hulls' corners (the hull of a union is the hull of the two
// hulls), a group's first hull from the corners of its slices' polygons of its rows' ends, boxes
// are compared before the exact separating axis test, each level's points of the other class
// are kept as runs along rows (listed from the volume's words, labelled a run at a time: the
// points of a run are face-neighbours), components are labelled in the box of their points
// (each run's label from its row's box intervals, no sort), and a merge whose corners all lie in
// the larger group's solid hull keeps that hull, its region and the pairs already known apart;
// what remains is the recursion itself (every level scans the rows of its hull) and the exact
// differences of the pits (about 27,000 corefinements on the full Al object, most of a few dozen
// triangles). Those test their operands for self-intersections only where they are not known
// to be embedded: a hull's fan is checked in integer arithmetic instead, and a level's surface
// keeps the boxes of the triangles its last cut made, the rest being the surface the cut tested.
// Pits whose hull meets C so that C less it is no 2-manifold are refused before they are solved
// (convexDifferenceIsManifold): on the aneurism's vessel tree they were two thirds of the pits
// tried, each solved down several levels (and its failure often passed up through the levels
// above) before the difference or a level below refused it, and nearly all the time. Joins now
// cost the prisms' neighbourhoods (their Booleans near the prism where possible, their cheap
// tests on the shells' triangles near the prisms of a crossing), the whole-H checks are decided
// by exact predicates without exact constructions, and the classification of the background
// works per row; what remains on the vessel tree is the recursion's hulls and point sets, and
// the joins' Booleans whose prism's interior crosses H (a corefinement of the whole part).
//
// The degree of non-convexity (definition NK) is the number of levels below the hull.
//
// Where it departs from the paper: the paper spans one hull per concavity from the labelled
// faces; here each face-connected group of points of the other class at a level gets the hull
// of its own points, and groups whose hulls meet are merged (so no two hulls of one level
// overlap or cross), and a pit opens exactly where a group's hull touches C. A dent
// whose background centres all lie strictly inside CH(S) (the hull face passing over them between
// lattice points) becomes a cavity with a thin skin rather than a pit.
#ifndef vbr_ConvexHullModifier_h
#define vbr_ConvexHullModifier_h

#include "BitVolume.h"
#include "ConvexHull.h"
#include "Execution.h"
#include "LatticeMesh.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vbr
{

/// One planar face of H: its triangles (indices into LatticeMesh::triangles), its boundary loops
/// (the first one outer, counter-clockwise seen from outside; holes clockwise) and its level.
struct ModifiedFace
{
  FacePlane plane;
  std::vector<std::uint32_t> triangles;
  std::vector<std::vector<std::uint32_t>> loops;
  /// 0 for pieces of faces of CH(S) (of the component's hull when componentsApart), 1 for faces
  /// pressed in from a background hull, 2 for faces pushed back out, ...; for a flat object the
  /// levels of its polygons and loops in the plane (see above).
  int level = 0;
};

struct ModifiedHull
{
  CellList hull;
  LatticeMesh surface;
  std::vector<ModifiedFace> faces;
  /// Per surface point: 1 object, 0 background.
  std::vector<std::uint8_t> vertexMark;
  /// Every background centre on H (vertices and points inside faces or on edges).
  std::vector<LatticePoint> backgroundOnSurface;
  std::size_t edgeCount = 0;
  /// Section 4.1's counts; for a flat object the notches and holes of its polygons.
  int concavities = 0;
  int cavities = 0;
  int tunnels = 0;
  int degreeOfNonConvexity = 0;
  /// Groups the touching rule kept apart (cavities and regions pressed in from a triangle).
  int keptApart = 0;
  /// Shells of H joined to the rest after H separated (see above).
  int joinedShells = 0;
  /// Handles cut through walls of H that sealed a tunnel of the object, or through the thin
  /// holes of a flat object (see above).
  int cutHandles = 0;
  /// Joins and handle cuts each checked on the part of H it changed but dropped together
  /// because H with all of them did not separate (H is then the one before them): 0 unless the
  /// local checks missed something the whole H's check found.
  int discardedChanges = 0;
  /// Whether H is the union of the H of each component of the object (see above).
  bool componentsApart = false;
  /// Whether H of a flat object is its sheared pixel solid (see above) rather than the prisms
  /// of its polygons.
  bool flatPixelSolid = false;
  /// Whether H came from the second pass, every level kept apart (no pits, see above).
  bool withoutPits = false;
  /// The second pass for the object's topology (see above): NotRun when the first pass did not
  /// call for it (also when H comes from the pass run after a first pass that failed, where
  /// withoutPits is true), Kept when H is its result, Rejected when it did not separate with the
  /// topology of the object's boundary and H is the first pass's.
  enum class HandlePass
  {
    NotRun,
    Kept,
    Rejected
  };
  HandlePass handlePass = HandlePass::NotRun;
  bool complete = true;
  std::string failure;
};

/// H of the object voxels (empty input: an empty result), its shells joined (see above); for a
/// flat object the prisms of its polygons (see above). Incomplete (complete false, failure saying
/// why) when
/// no empty triangle is left to press a group in from (see above).
ModifiedHull modifyConvexHull(const BitVolume& objects,
  CoplanarFaces coplanar = CoplanarFaces::Extension,
  const Execution& exec = Execution());

/// The voxel set rebuilt from H and its marks: centres strictly inside H, and centres on H that
/// are not listed as background. Exact (integer ray crossing with a symbolic perturbation).
BitVolume revertModifiedHull(const LatticeMesh& surface,
  const std::vector<LatticePoint>& backgroundOnSurface,
  const std::array<std::int32_t, 3>& dims);

/// Twice the Euler characteristic of the union of the object's closed voxel cubes, the Euler
/// characteristic of its boundary, counted from the 2x2x2 blocks about every grid corner, when
/// the object is well-composed (no two voxels of one class touching only along an edge or at a
/// corner; then its boundary is a 2-manifold and H must have its genus); none otherwise (the
/// touching rule decides H there). Throws std::runtime_error when `exec` asks to stop.
std::optional<long> wellComposedBoundaryEuler(const BitVolume& objects,
  const Execution& exec = Execution());

/// The plane axes (u, v) of a flat axis a, (u, v, a) right-handed: polygons counter-clockwise
/// in (u, v) face +a.
std::array<int, 2> planeAxesOf(int a);

/// The layer x_a = c of `objects` as a 2D image in its plane axes (planeAxesOf).
BitVolume layerImage(const BitVolume& objects, int a, std::int32_t c);

/// Whether the difference C - G of two solid convex hulls, G inside the closed C, can be a
/// 2-manifold, decided from the cell lists alone (no Boolean). G meets the surface of C only in
/// faces, edges and corners of G lying on faces of C (a point of G on the surface of C lies in
/// a supporting plane; a corner of C on G is a corner of G), so C - G is a 2-manifold exactly
/// when it is one about every edge and corner of G on the surface of C:
///  - about an edge e of G on a face of C, the section of C is an angle (a half plane when e
///    lies inside the face) and that of G an angle inside it; C - G is one angle (or none)
///    only when one of G's two faces along e lies on a face of C, else two angles meet in e;
///  - about a corner v of G on the surface of C, the link of C - G (a small sphere about v) is
///    the link of C less that of G, which is a disk only when G's link meets the boundary of
///    C's link in one connected piece: G's faces and edges at v lying on faces of C must form
///    one connected set about v (none: G touches C at v only; two: C - G is two cones at v).
/// A pit is pressed in as the difference of C and the solved pit, its hull less its own pits,
/// which open inside the hull's faces. So a group that is its own solid hull, whose corners
/// are points of its class and stay, fails as its hull does, and is refused before it is
/// solved when this fails; a flat group thickened by points of the other class is solved
/// first, since a pit of the next level can take such a corner, and with it the edge or corner
/// that made C - G fail, off the surface (one of about 17,000 random volumes up to 12^3 had
/// such a pit). A flat C or G gives true (nothing is decided beforehand). On a
/// 48^3 crop of the aneurism's vessel tree, all 4,740 of the 6,912 pits tried that fail it were
/// refused by their exact difference or by a level below, each after being solved down several
/// levels (the exact difference of the two hulls alone, tried for each, failed for exactly
/// those 4,740).
bool convexDifferenceIsManifold(const CellList& c, const CellList& g);

/// Whether two convex hulls (any dimension, with their incidences as convexHull gives them)
/// share a point: an exact separating axis test, whose axes are the face normals of both and
/// the cross products of an edge of each. Of the edge pairs only those whose arcs on the Gauss
/// maps cross (or touch) are tried when both are solid: every other pair spans no face of the
/// Minkowski difference A - B, so its axis separates only where a face normal does too (the
/// pressing-in tests its groups' and regions' hulls pairwise, and the edge pairs were most of
/// that on the aneurism). The test checks it against all the pairs on random lattice hulls.
/// (HullIntersection.cxx)
bool hullsIntersect(const CellList& a, const CellList& b);

/// The lattice points of the grid of `dims` on the surface (exactly on one of its triangles).
std::vector<LatticePoint> latticePointsOnSurface(const LatticeMesh& surface,
  const std::array<std::int32_t, 3>& dims);

/// Whether each shell of a closed embedded lattice mesh faces away from the solid it bounds:
/// six times its signed volume, exact in integers, positive for a shell nested in an even number
/// of others (an outer shell, an island in a void) and negative for one nested in an odd number
/// (the surface of a void), the nesting found by exact ray parity. The checks of H use it (a
/// shell turned over whole keeps the reversion's parity and the manifold tests intact).
bool shellsFaceOutward(const LatticeMesh& surface);

namespace detail
{
/// For tests of the recursion's point lists and first hulls (see HullPointRuns.h and
/// PressingIn.cxx). Runs are (lo, hi, y, z): the lattice points (x, y, z) for lo <= x <= hi,
/// maximal, in row order.

/// The runs of the points of class `cls` (1 object) among x = lo..hi of row (y, z), from the
/// volume's words; every centre off the grid is background.
std::vector<std::array<std::int64_t, 4>> runsOfRow(const BitVolume& objects,
  bool cls,
  std::int64_t lo,
  std::int64_t hi,
  std::int64_t y,
  std::int64_t z);

/// The runs of the lattice points of class `cls` in the solid hull `c` (its open interior when
/// `strict`).
std::vector<std::array<std::int64_t, 4>> runsOfClass(const CellList& c,
  const BitVolume& objects,
  bool cls,
  bool strict);

/// The x range [lo, hi] of row (y, z) in the intersection of the half spaces of c.planes
/// (n.p <= offset, < when `strict`); false when it is empty. Unbounded sides are +-2^61.
/// A solid c (dimension 3, with edges, more than 8 planes) must be a convexHull result with its
/// incidences: the range is cut to the box of the slice's corners (its vertices in the slice
/// and its edges' crossings), so a missing vertex or edge would shorten it.
bool rowRange(const CellList& c,
  bool strict,
  std::int64_t y,
  std::int64_t z,
  std::int64_t& lo,
  std::int64_t& hi);

/// How many of c's planes the rows of slice z leave out, as rowRange does (the planes that keep
/// the slice's box); 0 when the slice is scanned on all of them.
std::size_t planesLeftOutOfSlice(const CellList& c, bool strict, std::int64_t z);

/// Of points in (z, y, x) order without repeats, the corners of each z-slice's polygon.
std::vector<LatticePoint> sliceCorners(const std::vector<LatticePoint>& ends);

/// A group's first hull as the recursion makes it from the points (in any order): the hull of
/// its slices' corners, or of its rows' ends when that is flat.
CellList groupShape(const std::vector<LatticePoint>& points,
  CoplanarFaces coplanar = CoplanarFaces::Extension);
/// The side of `surface` (a closed mesh: 1 inside, 0 on it, -1 outside) of every lattice point
/// of the box [lo, hi], x fastest, located as the joins locate a prism's points: by exact ray
/// parity against only the triangles that can reach the box.
std::vector<int> sidesInBox(const LatticeMesh& surface,
  const LatticePoint& lo,
  const LatticePoint& hi);

} // namespace detail

} // namespace vbr

#endif
