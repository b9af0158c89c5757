// Triangulation of an orthogonal face with holes (exact predicates, no new vertices).
#ifndef vbr_FaceTriangulator_h
#define vbr_FaceTriangulator_h

#include "BRep.h"
#include "PolygonTriangulator.h"

#include <array>
#include <vector>

namespace vbr
{

/// Triangles covering face `f` of `brep`, as indices into the concatenation of its loops'
/// points (outer loop first), oriented like the face (right-hand normal outwards). Vertices
/// shared by several loops (non-manifold contacts) are referred to by their first index.
std::vector<std::array<int, 3>> triangulateFace(const BRep& brep, int f);

/// Polygons covering face `f` exactly, each drawn right by a renderer that draws a polygon
/// as the fan of triangles from its first corner (VTK's OpenGL mapper does): the outer loop
/// itself, started at a corner from which its fan covers it, when the face has no holes and
/// such a corner exists; otherwise the triangles of triangulateFace grouped into fans round
/// shared corners (each polygon is a corner followed by the far sides of its triangles).
/// Indices and orientation as in triangulateFace; every corner of the loops is a corner of
/// the polygons.
std::vector<std::vector<int>> fanPolygons(const BRep& brep, int f);

} // namespace vbr

#endif
