// The face octree of section 3.3 of Joan-Arinyo and Solé (1996), built from the relaxed
// deformed model (DeformedModel.h) by a compaction of the octree's nodes: bottom up, as in
// their reference [7], under the paper's rule; from the root down under the reach rule (below).
//
// Under the paper's rule the first face octree is the voxel grid itself: every boundary voxel with
// one representative point is a face node, with its GDM plane (through the point, with the point's
// area-weighted fan normal). Level L groups the voxels of a 2^L cube of the grid (the cubes of
// a root of the next power of two above the grid's size, clipped to the grid: any grid size
// works). A node of level L becomes a face node when one plane fits the node. "Fits"
// (section 3.3: "a plane that is both interior to all boundary voxels inside the region
// bounded by the current face octree node and does not intersect any other voxel in the
// node") is one of two rules, with these parts in common:
//  - no relaxed point of the node is farther from the plane than the precision (default half
//    a voxel: larger values compact more but move points farther from their neighbours'
//    sewing triangles);
//  - it cuts the open interior of no *far* voxel of the node: an object voxel whose 26
//    neighbours are all object voxels, or a background voxel whose 26 neighbours are all
//    background. Every point of the plane inside the node then lies in a voxel that shares a
//    grid vertex with a voxel of the other kind, a vertex on the voxel boundary: within one
//    voxel diagonal of the surfels;
//  - the points' normals agree with it (angle below 60 degrees): two sheets facing each other
//    never share a node;
//  - the quadrilaterals with all four points in the node form one disk, whose boundary, with
//    each point moved onto the plane (below), is a simple polygon turning counter-clockwise
//    about the normal: the planar polygon that replaces the node's quadrilaterals;
//  - that polygon can be cut into triangles that keep their orientations and incidences at
//    the points' own (double) positions (polygonTriangles below). Points clamped to a face of
//    their box line up along the plane's trace on that face, and flat faces relax into rows:
//    the 2^-30 plane grid rounds such corners to either side of their neighbours' chord, and
//    a triangle cut there could fold by a hair or pass through a corner where the sewing
//    triangles meet the polygon (self-intersections in exact arithmetic). Straight runs are
//    cut on exact chords; a node whose cut still has a sliver or a diagonal grazing a corner
//    (a corner on the line of a run elsewhere on the boundary) stays uncompacted;
//  - the sewing quadrilaterals that leave the node keep a split into two triangles facing the
//    way the relaxed quadrilateral faces.
//
// The paper's rule (keepPointsInVoxels): the plane also meets the box of every point of the
// node (its voxel, shrunk by the model's margin), and each point moves to the nearest point of
// the plane inside its own box (the projection of section 3.4, kept inside the voxel). Every
// vertex then stays in its boundary voxel, and the sewing triangles in the boundary voxels
// around their grid edge. Digital planes of generic slope meet every boundary voxel's box only
// over a few voxels, so most nodes stay small (0.28 polygons per object voxel on the torus of
// the benchmark at 128^3).
//
// The reach rule (the default): the plane need not meet the points' voxels. Each point moves
// to the nearest point of the plane inside the node's box (the plane must meet that box), and
// - every moved point lies within one voxel diagonal of every corner of every surfel of its
//   own voxel (a face of it whose neighbour across is background), hence of every point of
//   those surfels (a ball holds the hull of the corners it holds);
// - the box of the four corners of every sewing quadrilateral meets no far voxel (checked by
//   whichever node moves a corner last, against the others' positions);
// - every quadrilateral inside the node, projected, has a split into two triangles turning
//   counter-clockwise about the normal: the projected disk covers its polygon once, so the
//   points inside the disk, which the polygon replaces, lie on the polygon (without this
//   check such points were found outside it on the 128^3 ball).
// Why the bound of one voxel diagonal still holds both ways (except at pruned voxels, whose
// points the model drops):
// - surface to surfels: a polygon lies in its corners' hull, in the node's box, and on a
//   plane that cuts no far voxel there, so each of its points is in a voxel that is not far:
//   within a voxel diagonal of the surfels (above); a sewing triangle lies in its corners'
//   box, which meets no far voxel (a point in it is in the closure of a voxel that meets the
//   box); a point of no node stays in its own boundary voxel;
// - surfels to surface: every surfel belongs to an object voxel with a background face
//   neighbour, a boundary voxel, whose point lies on the surface (unless pruned): a vertex,
//   or a point inside a disk, on its polygon by the last check. A moved point is within the
//   diagonal of the whole surfel by the first check; an unmoved one lies in its voxel, within
//   the voxel's diagonal of every point of its faces.
// The vertices then reach the planes of larger nodes (0.15 polygons per object voxel on that
// torus). Nodes are tried from the root down (the first node of each branch that fits is
// kept; the points no node took are face nodes of their own voxels): the levels above a face
// node mostly fail at the cheap first tests, where a bottom-up pass would fit every level
// below it in full. The label net (buildFaceOctreeAvoiding) keeps the paper's rule: its boxes
// are grid vertices', not voxels'.
// Neither rule proves that two sheets never cross (the output's freedom from
// self-intersections): the normals' test keeps facing sheets out of one node, and the core
// tests check it with CGAL's exact does_self_intersect on the solids up to 128^3, porous
// blobs up to 96^3 and noise.
// The normal is the sum of the points' GDM normals (area-weighted); the offset is the one
// nearest the points' mean that the constraints allow (an interval minus open intervals).
//
// Merging (beyond the paper, mergeFaceNodes): the octree only compacts the points of one
// power-of-two cube, so a planar patch that crosses a cube's side stays split into nodes,
// sewn by triangles. After the compaction, face nodes that share a quadrilateral are merged,
// greedily: each face, the largest first, absorbs its neighbours (the best aligned first, in
// rounds until a round absorbs none) whenever one plane fits the union by the rules above,
// with the union's points as the node's and the bounding box of its nodes' boxes as the box
// whose far voxels the plane may not cut (the polygon lies in the hull of its corners, inside
// that box, so the bound of one voxel diagonal holds as for a node). The sewing quadrilaterals
// between merged nodes become inside quadrilaterals of the disk. Two more rules keep each
// polygon in a box of its own, as the octree's disjoint cells do: the merged box overlaps no
// other face's box, and within a voxel of it lies no point in no face and no face facing
// away (normals more than 90 degrees apart: another sheet, whose sewing triangles a larger
// projection could cross; random voxels at 85 % showed such crossings without this rule).
// A merged face is a FaceNode: its box is that bounding box and its level the largest of its
// octree nodes'.
#ifndef vbr_FaceOctree_h
#define vbr_FaceOctree_h

#include "BitVolume.h"
#include "DeformedModel.h"
#include "Execution.h"
#include "PolygonTriangulator.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vbr
{

struct FaceOctreeOptions
{
  int maximumLevel = 10;  ///< largest node: 2^level voxels a side
  double precision = 0.5; ///< largest point-to-plane distance (voxel units)
  double minimumCosine = 0.5;
  /// Merge adjacent face nodes after the compaction (beyond the paper, see above).
  bool mergeFaceNodes = false;
  /// The paper's rule (bottom-up): every node's plane meets each point's voxel box and the
  /// points are projected inside their voxels. Off (the default): the reach rule above, from
  /// the root down. The label net (buildFaceOctreeAvoiding) always keeps the paper's rule.
  bool keepPointsInVoxels = false;
};

struct FaceNode
{
  int level = 0; ///< octree level; of a merged face, the largest of its nodes'
  std::array<std::int32_t, 3> lo{ 0, 0, 0 }, hi{ 0, 0, 0 }; ///< voxel box [lo, hi)
  Vec3 normal{ 0, 0, 1 };                                   ///< unit, outwards
  double offset = 0.0;                                      ///< plane: normal . x = offset
  /// The planar polygon's corners (point ids), counter-clockwise about the normal; empty
  /// when no quadrilateral lies inside the node.
  std::vector<std::int32_t> polygon;
};

struct FaceOctree
{
  std::vector<FaceNode> nodes;      ///< the terminal face nodes (merged, if asked)
  std::vector<std::int32_t> nodeOf; ///< per point: its face node, -1 for none
  std::vector<Vec3> projected;      ///< per point: its position on its node's plane
};

/// Voxels no face node's plane may cut (see above): object voxels with no background
/// 26-neighbour and background voxels with no object 26-neighbour (outside is background).
BitVolume farVoxels(const BitVolume& object, const Execution& exec);

/// The nearest point to p on the plane n . x = t inside the box [lo, hi] (which the plane
/// must meet).
Vec3 projectIntoBox(const Vec3& p, const Vec3& n, double t, const Vec3& lo, const Vec3& hi);

/// Coordinates of points of a node's plane in an orthonormal basis (u, v) with u x v = the
/// normal, relative to the node's lowest corner, on an integer grid of 2^-30 voxel.
std::vector<Point2L> planeCoordinates(const FaceNode& node, const std::vector<Vec3>& points);

/// The triangles of a node's polygon (indices into its corners, counter-clockwise), cut
/// so that they keep their orientation and incidences at the corners' own positions: the
/// corners of straight runs (which the plane grid rounds to either side) are cut on exact
/// chords, and no triangle is a sliver nor has a diagonal grazing a corner. Empty when that
/// cannot be had: the node is then not compacted.
std::vector<Triangle> polygonTriangles(const FaceNode& node, const std::vector<Vec3>& corners);

FaceOctree buildFaceOctree(const BitVolume& object,
  const DeformedModel& model,
  const FaceOctreeOptions& options,
  const Execution& exec);

/// The same compaction with the voxels no plane may cut given: `far` has the model's dims
/// (the label net of LabelNet.h compacts in the grid of its vertices' boxes).
FaceOctree buildFaceOctreeAvoiding(const BitVolume& far,
  const DeformedModel& model,
  const FaceOctreeOptions& options,
  const Execution& exec);

} // namespace vbr

#endif
