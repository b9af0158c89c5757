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
// The method is a tree of nested lattice hulls, the plane version of Algorithm 1 with the
// touching rule of the 3D method applied everywhere (every piece kept apart). Level 0: the
// object centres grouped by 8-connectivity, each group's convex hull; hulls that meet (closed
// sets, corners and edges included) have their groups merged until they are pairwise apart.
// Below a hull C of one class (object at even levels, background at odd ones) the centres of
// the other class strictly inside C are grouped the same way, and each group gets one convex
// region strictly inside C (its hull) or, when no such region exists, a notch pressed in from
// one edge of C (below). The regions of a level are merged until they are pairwise apart, and
// the recursion goes on inside every hull. The separating set is C0 - (C1 - (C2 - ...)) over
// the tree: even-level hulls bound the object, odd-level ones its holes.
//
// Flat groups (a single centre or centres on one line) are thickened: at level 0 by one lattice
// point off their line, chosen so that the triangle holds no lattice point but its corners and
// the group (a pixel touching others only at a corner, or a row, becomes such a triangle; its
// extra corner is a background centre on the boundary, off the image when the image is one
// pixel thick); below C by the lattice points strictly inside C nearest to them. When C holds no
// lattice point off the group's line strictly inside, the group is pressed in as a notch
// conv(a, b, group) from a piece [a, b] of an edge of C between consecutive lattice points
// (definition PR of the paper): accepted only when the notch holds no lattice point strictly
// inside, so that nothing lies below it. A notch meets C exactly in [a, b] (its other corners
// are strictly inside C), so the loop of C with [a, b] replaced by the notch's other sides is
// still simple.
//
// Touching pixels (the documented rule). Pieces that would touch only at a corner are kept
// apart: hulls of one level are closed sets pairwise apart, every hull lies strictly inside its
// parent, and notches meet their parent only in their own edge piece. So no boundary pinches:
// pixels touching only at a corner end up in one polygon (their groups merge, 8-connectivity)
// with the other two centres of that 2x2 square on its boundary or outside it.
//
// Separation, by induction over the tree: let p be a centre and C the deepest hull holding p.
// If p has C's class it lies in C minus its children (closed): inside or on the boundary. If
// not, p is on C's boundary, since a centre of the other class strictly inside C lies in a child
// of C. Every child holds fewer lattice points than its parent (it misses the parent's corners),
// so the recursion ends. The result is checked (its reversion against the input); `complete`
// is false, with a reason, only when a flat group finds neither a thickening nor a notch.
#ifndef vbr_ConvexHullModifier2D_h
#define vbr_ConvexHullModifier2D_h

#include "BitVolume.h"
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
SeparatingPolygons separatingPolygons2D(const BitVolume& image);

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
