// The 2D analogue of ConvexHullModifier.h: polygons with holes that separate the object pixels
// of a 2D image from its background pixels, made from convex hulls by recursive pressing-in
// (H. Schulz, FZD-514, 2009, section 4, in the plane).
//
// Pixels are their centres, integer lattice points (x, y). The result is a set of closed loops
// with lattice corners and straight edges as long as possible (no corner goes straight on):
// every loop is a simple polygon, no two loops meet, outer boundaries run counter-clockwise and
// holes clockwise (the object on the left). No object centre lies outside, no background centre
// inside; the centres on a loop are marked, so that the pixel set is rebuilt from the loops and
// the marks alone (revertSeparatingPolygons2D).
//
// The method is a tree of nested regions, the plane version of Algorithm 1 with the touching
// rule of the 3D method (pieces kept apart unless they share a whole edge piece). Level 0: the
// object centres grouped by 8-connectivity, each group's convex hull; regions that meet (closed
// sets, corners and edges included) have their groups merged until they are pairwise apart.
// Below a region C of one class (object at even levels, background at odd ones) the centres of
// the other class strictly inside C are grouped with those on C's boundary (8-connected
// components; a component with no centre strictly inside needs nothing, its centres are marked
// on the boundary). Each group gets one convex region R:
//   a concavity (definition CO) opens: when the group's centres on C's boundary lie on one edge
//     of C, R = conv(group inside, a, b) with [a, b] their span on that edge (one lattice step
//     when a single centre touches), accepted when every centre strictly between a and b has
//     the group's class (those end up outside C's region);
//   otherwise R is the group's hull strictly inside C (a hole, a cavity of the paper);
//   a flat group that touches nothing is thickened: by the lattice points strictly inside C
//     nearest to it, or, when C holds none off its line, pressed in as a notch conv(a, b, group)
//     from a piece [a, b] of an edge of C between consecutive lattice points with no lattice
//     point inside the notch (definition PR).
// A notch R meets C exactly in [a, b] (its other corners are strictly inside C), so C's loop with
// [a, b] replaced by R's other sides (and, recursively, the notches of R spliced into those) is
// still simple. The regions of a level are merged until pairwise apart, and the recursion goes
// on inside every region; a notch's own piece [a, b] is never pressed in again from below. The
// separating set is C0 - (C1 - (C2 - ...)) over the tree: even levels bound the object, odd ones
// its holes and notches. Level 0 thickens flat groups by one lattice point off their line, so
// that the triangle holds no lattice point but its corners and the group (a lone pixel or a row
// becomes such a triangle; its extra corner is a background centre on the boundary, off the
// image when the image is one pixel thick).
//
// Touching pixels (the documented rule). Pieces that would touch only at a corner are kept
// apart: regions of one level are closed sets pairwise apart, hulls lie strictly inside their
// parent, and notches meet their parent only in their own edge piece. So no boundary pinches:
// pixels touching only at a corner end up in one polygon (their groups merge, 8-connectivity)
// with the other two centres of that 2x2 square on its boundary or outside it.
//
// Separation, by induction over the tree: let p be a centre and R the deepest region holding p.
// If p has R's class it lies in R minus its children (closed): on R's side, or on a boundary.
// If not, p is on R's boundary, since a centre of the other class strictly inside R lies in a
// child of R; it stays on the final boundary unless it lies strictly inside a notch's piece,
// which only centres of the notch's class do. Every child holds fewer lattice points than its
// parent (it misses the parent's corners), so the recursion ends. The result is checked (its
// reversion against the input); `complete` is false, with a reason, only when a flat group finds
// neither a thickening nor a notch.
//
// Where it departs from the paper: one region per group and level, merged while they meet (the
// paper spans one hull per concavity from the labelled faces); a concavity touching the hull
// on more than one edge (around a corner of the hull) is kept apart as a hole inside, its
// centres on the hull marked, rather than opened.
#ifndef vbr_ConvexHullModifier2D_h
#define vbr_ConvexHullModifier2D_h

#include "BitVolume.h"
#include "Execution.h"
#include "PolygonTriangulator.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vbr
{

/// One closed boundary: lattice corners, the object on the left (outer boundaries
/// counter-clockwise, holes clockwise).
struct SeparatingLoop
{
  std::vector<Point2L> corners;
  /// The level of the hull it comes from: even bounds an object region, odd a hole.
  int level = 0;
};

/// One polygon with holes (a face): indices into SeparatingPolygons::loops.
struct SeparatingPolygon
{
  std::size_t outer = 0;
  std::vector<std::size_t> holes;
  int level = 0;
};

struct SeparatingPolygons
{
  std::vector<SeparatingLoop> loops;
  std::vector<SeparatingPolygon> polygons;
  /// The convex hull of all object centres (thickened like a level-0 group when flat),
  /// counter-clockwise; empty for an empty image.
  std::vector<Point2L> hull;
  /// Every background centre of the image on a loop (corners and points inside edges).
  std::vector<Point2L> backgroundOnBoundary;
  int holes = 0;                ///< hulls strictly inside their parent, pressed in as holes
  int notches = 0;              ///< groups pressed in from an edge of their parent
  int degreeOfNonConvexity = 0; ///< the deepest level
  bool complete = true;
  std::string failure;
};

/// The separating polygons of the object pixels of a 2D image (nz = 1; z = 0 is read).
/// Reports its progress through `exec` and polls its abort once per region of the tree
/// (throws std::runtime_error("aborted") when asked to stop).
SeparatingPolygons separatingPolygons2D(const BitVolume& image,
  const Execution& exec = Execution());

/// The pixel set (nx * ny * 1) rebuilt from the loops and the marks alone: centres strictly
/// inside (exact crossing parity), and centres on a loop that are not listed as background.
BitVolume revertSeparatingPolygons2D(const std::vector<SeparatingLoop>& loops,
  const std::vector<Point2L>& backgroundOnBoundary,
  std::int32_t nx,
  std::int32_t ny);

/// Every lattice point on the loops, each once (corners and points inside edges).
std::vector<Point2L> latticePointsOnLoops(const std::vector<SeparatingLoop>& loops);

/// The corners of a polygon with holes, outer loop first then each hole's, as one list.
std::vector<Point2L> polygonCorners(const SeparatingPolygons& result,
  const SeparatingPolygon& polygon);

/// Counter-clockwise triangles (indices into polygonCorners) covering the polygon with holes
/// exactly, no new corners (a constrained triangulation of its loops).
std::vector<Triangle> triangulatePolygonWithHoles(const SeparatingPolygons& result,
  const SeparatingPolygon& polygon);

} // namespace vbr

#endif
