// The faces of H: its coplanar, edge-connected triangles merged into faces with their boundary
// loops (outer first, counter-clockwise seen from outside; holes clockwise) and their levels,
// and H put in a canonical order (points, triangles and faces sorted) so that the output does
// not depend on the order in which the pits, regions and joins were made.
#ifndef vbr_HullFaces_h
#define vbr_HullFaces_h

#include "HullModifierContext.h"

#include <map>
#include <vector>

namespace vbr
{
namespace detail
{

/// The faces of the surface: coplanar edge-adjacent triangles merged, with their loops and
/// the level of their first triangle when `triangleLevel` holds one per triangle, else of
/// their plane.
void mergeIntoFaces(const std::map<FacePlane, int>& planeLevel,
  const std::vector<int>& triangleLevel,
  ModifiedHull& r);

} // namespace detail
} // namespace vbr

#endif
