// Triangulation of an orthogonal face with holes (exact predicates, no new vertices).
#ifndef vbr_FaceTriangulator_h
#define vbr_FaceTriangulator_h

#include "BRep.h"

#include <array>
#include <vector>

namespace vbr
{

/// Triangles covering face `f` of `brep`, as indices into the concatenation of its loops'
/// points (outer loop first), oriented like the face (right-hand normal outwards). Vertices
/// shared by several loops (non-manifold contacts) are referred to by their first index.
std::vector<std::array<int, 3>> triangulateFace(const BRep& brep, int f);

} // namespace vbr

#endif
