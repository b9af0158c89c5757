// H of objects that span no solid: a segment or a flat set off the grid's axis planes gets a
// lattice tetrahedron or pyramid with no lattice point inside; a flat object in a plane of the
// grid's axes is solved by the 2D modifier (ConvexHullModifier2D.h), each polygon made a prism
// one lattice step thick on both sides, its lost thin holes cut again, and the layer's sheared
// pixel solid used instead when the prisms miss the layer's topology shell by shell.
#ifndef vbr_FlatObjects_h
#define vbr_FlatObjects_h

#include "HullModifierContext.h"

#include <cstdint>
#include <vector>

namespace vbr
{
namespace detail
{

/// H of a segment off the axes' planes (its centres on a line whose direction d, primitive,
/// has no zero component: voxels touching only at corners, or nowhere): the tetrahedron T = conv{a,
/// b, x, y} of its ends a, b = a + m d and two lattice points x = a + u', y = a + w' where (d, u',
/// w') is a basis of Z^3 (LatticeBasis.h; u' = +-u + k d, w' = +-w + j u + k' d keep it one, and
/// the first such corners inside the grid are taken, near the segment). In that basis a
/// lattice point of T has integer coordinates (t, b, c), all >= 0 with t / m + b + c <= 1: a
/// point of the segment (b = c = 0), x or y. So no lattice point lies inside T, the segment's
/// centres are its edge and the two other corners are background centres (off the line that
/// holds every object centre) on H, marked.
LatticeMesh segmentTetrahedron(const CellList& hull, const Dims& dims);

/// H of a flat set in a plane n . p = c off the grid's axes (its centres never face-connected):
/// the pyramid over its convex polygon P with an apex y in the next lattice plane on either
/// side, n . y = c +- 1 (LatticeBasis.h: y = p + -+z + a v1 + b v2, the one nearest P's
/// centroid, inside the grid if one of those tried is). No lattice plane lies strictly between
/// the two planes, so a lattice point of the pyramid lies in P (an object centre or a
/// background centre on the base, marked) or is y; the sides hold no other lattice point. So
/// every object centre is on H and no background centre is inside it.
LatticeMesh flatSetPyramid(const CellList& hull, const Dims& dims);

/// The last axis along which every point has one coordinate (that of flatAxisOf in the vtk
/// filter, so a 2D image in z is solved in its (x, y) plane), or -1 when the points lie in no
/// plane of the grid's axes.
int gridPlaneAxis(const std::vector<LatticePoint>& points);

/// H of a flat object whose centres lie in x_a = c: the prisms of its separating polygons, a
/// handle cut through each hole they lost (when one separates), its faces with their levels;
/// the counts of the plane (notches as concavities, holes as cavities). Incomplete when the
/// plane's polygons are; lost holes beyond MaxLostHoles are noted in the failure text. A
/// well-composed layer whose prisms are incomplete or have not its topology shell by shell
/// gets its sheared pixel solid instead (complete, nothing noted).
void solveFlatObject(const BitVolume& objects,
  int a,
  std::int64_t c,
  const Execution& exec,
  ModifiedHull& r);

} // namespace detail
} // namespace vbr

#endif
