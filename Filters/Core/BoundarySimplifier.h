// Bounded simplification of a closed boundary surface (beyond the paper): greedy edge
// collapses by Lindstrom-Turk's cost (CGAL's Surface_mesh_simplification policies in a loop
// of our own with a lazily updated queue; the placement moved 0.07 voxel outwards along the
// star's normal, since the input runs inside the surfels) that keep the surface within a
// distance d of the voxel boundary (the surfels) on both sides, and free of
// self-intersections. The collapses run until no edge may collapse, then one more sweep over
// the edges left tries more points; a collapse is accepted with its vertex at the
// placement, or else at Lindstrom-Turk's point pushed out less, at one of the edge's ends or
// at its midpoint (the first point for which all of these hold):
//  (a) surface to surfels: every new triangle (the star of the collapsed vertex) lies within d
//      of the surfels. Proven by branch and bound on the distance to the surfels, which is
//      1-Lipschitz: a piece of triangle whose centre c (of its smallest enclosing ball) is at
//      distance dc from the surfels and whose corners are within r of c is within dc + r;
//      pieces are halved at their longest edge until dc + r <= d (accepted) or r < 1/20
//      voxel (rejected). The distance at the voxel corner nearest c, searched once and kept,
//      bounds dc (the same Lipschitz bound); dc itself is searched only where that bound
//      leaves the decision open, so the decisions are the same. Before it, a cheaper proof
//      decides most triangles (over 99 % on the 256^3 ball): every voxel the triangle may
//      meet is one whose largest distance to some surfel is within d. That largest distance,
//      over a voxel and to one surfel, is at a corner of the voxel (the distance to a square
//      is convex), and its square is an integer: 1, 2 or 3 for a surfel in the plane of one
//      of the voxel's faces, at most one voxel from it along the plane, 4 or more otherwise.
//      Those voxels are marked once, a bit each, a row at a time; the branch and bound runs
//      only for the triangles they leave open;
//  (b) surfels to surface: every surfel of an unpruned voxel is covered by square pieces
//      (the whole surfel, or its quarters, down to 1/8 voxel), each assigned to a triangle
//      within its limit of the piece's centre: d minus the piece's half diagonal, so that
//      every point of the piece is within d of that triangle. The pieces of the star's
//      triangles must find such a triangle among the new star (a piece that finds none is
//      quartered, the quarters' limits being larger) and are reassigned to it; triangles
//      outside the star keep theirs. So every surfel point stays within d of the surface,
//      except where the input itself is farther: a piece of the smallest side that no
//      triangle keeps within d at the start keeps its input distance as its limit (the
//      surface there stays within that distance plus 1/8 voxel's half diagonal, 0.09), and so
//      does, whole, a larger piece none of whose smallest pieces could be kept within d (the
//      surface there stays within its centre's input distance plus its half diagonal, the
//      input's own bound for it); a piece with no triangle within 2.5 (an input farther than
//      the precondition) has no limit and its distance is reported. The
//      surfels of pruned voxels (no interior corner: DeformedModel.h's one-voxel crests,
//      which the input already misses) are left out;
//  (c) no self-intersection: each new triangle is tested with exact predicates against the
//      triangles whose boxes meet its box (a uniform grid of triangle boxes, updated after
//      each collapse) and against the other new triangles; triangles that share a vertex
//      with it are tested on the opposite edges, those sharing an edge on the fourth
//      corner's side (as CGAL's Polygon_mesh_processing does). New triangles must not be
//      degenerate nor turn their normal by more than 90 degrees.
// The topology (closed, manifold, the genus of each component) is kept by the link condition
// (CGAL::Euler::does_satisfy_link_condition); CGAL's test against folds between neighbouring
// triangles is made at the placement. The result is checked at the end with
// Polygon_mesh_processing's does_self_intersect, is_closed and is_valid_polygon_mesh; if a check
// fails (or the input is not a closed triangle mesh without degenerate triangles), the input is
// returned unchanged with `simplified` false and its own distances (those of the returned surface).
//
// Distances are in voxel units (voxel i spans [i, i + 1]); d is at most 1.99 (the distance
// search of FaceOctreeBoundary.h's distanceToNearestFace reaches two voxels).
//
// Regions: a surface of 4096 triangles or more is first cut into slabs along the longest axis
// of its box, at the quantiles of its points (SimplifyOptions::regions, 2 by default: the
// geometry alone decides, so the result is the same on any number of threads). Each slab's
// triangles are simplified as a mesh of their own, concurrently, by the loop above restricted
// to collapses whose star and point lie strictly inside the slab; the triangles that meet a cut
// are changed by neither side, and all checks stay exact (BoundarySimplifier.cxx, "The first
// phase"). The loop then runs over the merged whole, with its last sweep. The output differs
// from one loop's (another order of collapses), within a few percent of its triangles (on
// the 64^3 to 256^3 ball, torus and CSG solid under both rules, from 5 % fewer to 5 % more;
// one region gives the output of one loop). The regions cost more CPU (the band's collapses
// after them, a second grid and queue; on two threads the threads also share the caches).
// Measured on two idle cores (the whole filter, STDThread,
// two runs in turns with one loop), wall time: the 256^3 ball 1.45x and 1.66x-1.70x less
// (reach rule, KeepPointsInVoxels), the 256^3 torus 1.49x-1.50x and 1.68x-1.72x, the 128^3 CSG
// solid 1.33x-1.39x and 1.24x-1.35x; on the Sequential backend the same runs took 0 % to 16 %
// more CPU (the CSG solid the most). On a machine whose cores are busy it gains no wall time.
//
// Cost (one loop, before the regions): 50 to 65 microseconds of CPU per collapse (the 128^3
// ball of the benchmark:
// 37,148 -> 176 triangles in 18,486 collapses, about 0.9 s; its 256^3 ball: 134,924 -> 378
// triangles in 67,273 collapses, about 4.3 s), most of it in the checks above and in reads
// that miss the cache; only the kept vertex's edges are re-costed at once (CGAL's loop
// re-costs the 20 to 40 edges around each collapse), and an edge's placement is kept until
// the star of one of its ends changes. A little less than the time of flying edges,
// windowed-sinc smoothing and quadric decimation on the 128^3 ball and torus, half of it on a
// CSG solid, with about half their triangles at the same distance (README, Performance).
// vtkFaceOctreeBoundaryFilter leaves it off by default: the filter with it takes about 10x
// its time without it under the reach rule and 16x to 18x with KeepPointsInVoxels (3.7 to
// 4.6 and 2.0 to 2.8 M voxels per CPU second on the 256^3 ball and torus, one thread). The
// time is spread over the checks, the costs and the queue, none above a quarter of it
// (README, face octree section); the faces, pieces and lattice values a collapse reads are
// prefetched together, since they lie far apart in memory. (a)'s proof by voxels took the
// branch and bound (a fifth of the time, a third of that in exact distance searches) off all
// but 0.7 % of the triangles of the 256^3 ball, the output unchanged on every input measured:
// 1.03x to 1.19x less CPU time on the 256^3 ball and torus and the 128^3 CSG solid under both
// rules. What is left is mostly Lindstrom-Turk (11 evaluations per collapse, about a quarter
// of the time), (b), (c), the link condition and the queue.
#ifndef vbr_BoundarySimplifier_h
#define vbr_BoundarySimplifier_h

#include "BitVolume.h"
#include "DeformedModel.h"
#include "Execution.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace vbr
{

struct SimplifyOptions
{
  /// d: the largest distance between the surface and the surfels, both ways (voxel units);
  /// the default is one voxel diagonal, the bound of the unsimplified boundary.
  double distance = std::sqrt(3.0);
  /// Slabs along the surface's longest axis whose collapses run first, concurrently with
  /// Execution's parallel loop (BoundarySimplifier.cxx, "The first phase"); 1: one loop over
  /// the whole. A surface of fewer than 4096 triangles is not cut. The result depends on
  /// this number, never on the threads.
  int regions = 2;
};

struct TriangleSurface
{
  std::vector<Vec3> points;
  std::vector<std::array<std::int32_t, 3>> triangles; ///< counter-clockwise seen from outside
};

struct SimplifiedSurface
{
  TriangleSurface surface;
  bool simplified = false; ///< false: the input returned (aborted, refused, or a final check
                           ///< failed)
  bool aborted = false;    ///< the caller asked to stop (the distances are then not measured)
  /// Both distances are those of the returned surface, the input's when not simplified.
  double surfaceDistance = 0; ///< upper bound (within 0.02) of the surface's distance to surfels
  double surfelDistance = 0;  ///< upper bound of the distance from the surfels of unpruned
                              ///< voxels to the surface (each piece: its centre's distance to
                              ///< its triangle plus its half diagonal); infinite when the input
                              ///< is refused as no manifold mesh
  std::size_t collapses = 0;
};

/// Simplifies `input` (closed, manifold, outward, free of self-intersections, within d of
/// the surfels of `object`) as described on top. Runs on the calling thread except the first
/// assignment of the samples and the regions, which run in `exec`'s parallel loop.
SimplifiedSurface simplifyBoundary(const BitVolume& object,
  const TriangleSurface& input,
  const SimplifyOptions& options = SimplifyOptions(),
  const Execution& exec = Execution());

/// Upper bound, within `tolerance`, of the largest distance from the triangles to the surfels
/// of `object` (branch and bound as in (a) on top); distances beyond two voxels count as 2.
double maximumTriangleDistanceToSurfels(const BitVolume& object,
  const TriangleSurface& surface,
  double tolerance = 0.02);

/// Whether (a)'s proof by voxels (on top) holds for triangle t at distance d: every voxel t
/// may meet has a surfel of `object` within d of all of the voxel's points. When true, t is
/// within d of the surfels; false says nothing. For tests of that proof on its own.
bool provenByVoxels(const BitVolume& object, const std::array<Vec3, 3>& t, double distance);

} // namespace vbr

#endif
