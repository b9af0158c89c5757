// Two lattice hulls tested for a common point, exactly (hullsIntersect, declared in
// ConvexHullModifier.h: the separating axis test, with the edge pairs of Gregorius), which the
// grouping of points and regions of the pressing-in asks pairwise, and the hulls it builds for
// its groups: a flat hull thickened into a solid (solidHull), and whether a hull misses a corner
// of the hull it lies in (the recursion's termination).
#ifndef vbr_HullIntersection_h
#define vbr_HullIntersection_h

#include "HullModifierContext.h"

#include <vector>

namespace vbr
{
namespace detail
{

/// The hull of the points; a flat one is thickened by the points one lattice step off its
/// plane or line that lie in the parent hull (in its open interior when `strict`).
bool solidHull(const std::vector<LatticePoint>& points,
  const CellList& parent,
  bool strict,
  CoplanarFaces coplanar,
  CellList& out);

/// Whether a hull inside the closed C misses a corner of C, that is (C being the hull of its
/// lattice corners) whether it holds fewer lattice points than C: the lattice count of the
/// hulls strictly decreases from level to level, so the recursion ends.
bool missesACorner(const CellList& inside, const CellList& c);

} // namespace detail
} // namespace vbr

#endif
