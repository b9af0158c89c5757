// The geometrically deformed model of Joan-Arinyo and Solé, "Boundary Generation from
// Voxel-based Volume Representations" (1996), section 3.2: one representative point per
// boundary voxel (an object voxel with a background voxel among its 26 neighbours), linked
// to the points of its face neighbours; the net is relaxed while each point stays inside its
// voxel, and its 4-cycles are the non-planar quadrilaterals that cover the boundary voxels.
//
// The pruned net, stated directly. A 4-cycle of face-linked voxels is the ring of four voxels
// around one grid edge. Call a grid vertex *interior* when its eight voxels are object voxels.
// The quadrilaterals kept are those around a grid edge that joins an interior vertex to a
// non-interior one; its four voxels are then boundary voxels (each is a 26-neighbour of the
// background voxel at the non-interior end). The 4-cycles the paper prunes are exactly the
// others: the dangling quadrilaterals on top of a one-voxel crest lie around edges with no
// interior end (their voxels have no interior corner at all: those voxels are lost, and
// counted), and the internal quadrilaterals of a two-voxel crest around edges whose both ends
// are interior. The kept quadrilaterals are the dual (surface-nets) surface of the interior
// vertices, which is closed; each is oriented with its normal from the interior end of its
// edge to the other end, so the surface faces outwards.
//
// Manifold rule. Where the interior vertices touch only diagonally, some voxels hold two or
// more sheets of the surface. Each voxel's crossing edges (those joining an interior and a
// non-interior corner) are chained face by face: on a face with two crossing edges they are
// chained together; on a face with four (interior corners on one diagonal) the two edges at
// each interior corner are chained (the interior corners kept apart), unless those two
// interior corners are joined by interior corners along the edges of one of the face's two
// voxels: then the edges at each non-interior corner are chained (the interior joined across
// the face). Both voxels of a face see the same rule, so every link bounds exactly two
// quadrilaterals, and the second case keeps two points from being linked twice (the voxel
// whose corners join the diagonal holds the face's two pairs on two different chains). Each
// chain (a cycle) of a voxel is one representative point; a voxel with one sheet has one
// point, as in the paper. A point of a voxel with several sheets stays in the box of its own
// crossing edges' midpoints (shrunk by 10 %), so the sheets stay apart.
//
// Relaxation (the cost, documented): E = sum over links of |p_a - p_b|^2 + w sum over
// points of |p - a_p|^2, minimised with each point inside its box (its voxel shrunk by a
// margin, 0.1 voxel by default, so that points of neighbouring voxels never meet). The first
// term is the discrete Laplacian smoothing of the GDM; the second (w = 1 by default) holds
// each point to its anchor a_p, the mean of the non-interior ends of its crossing edges,
// which are grid vertices on the voxel boundary: without it the net shrinks into the object.
// Links join face-neighbouring voxels, whose index parities differ, so the net is
// bipartite: the even points are all moved at once to the clamped weighted mean of their
// neighbours and anchor (the exact minimiser of E over each of them, the others fixed), then
// the odd ones. This is block coordinate descent: E never increases; it stops after a fixed number
// of iterations or once no point moved more than the tolerance. Each half-step is parallel.
//
// GDM plane (section 3.3): the normal of a point is the area-weighted mean of the normals of
// the fan of triangles (point, link neighbour, next link neighbour) around it; each fan
// triangle is the half of an incident quadrilateral at the point.
#ifndef vbr_DeformedModel_h
#define vbr_DeformedModel_h

#include "BitVolume.h"
#include "Execution.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vbr
{

using Vec3 = std::array<double, 3>;
using Quad = std::array<std::int32_t, 4>;

struct DeformedModelOptions
{
  int iterations = 50;     ///< relaxation sweeps at most
  double tolerance = 1e-4; ///< stop when no point moved more (voxel units)
  double attachment = 1.0; ///< weight of the pull towards the anchors (0: pure smoothing)
  double margin = 0.1;     ///< a point stays this far inside its voxel (voxel units)
};

/// The relaxed, pruned net of one object.
struct DeformedModel
{
  std::array<std::int32_t, 3> dims{ 0, 0, 0 };
  /// Per representative point: its voxel, its box (voxel units: voxel i spans [i, i + 1]),
  /// the relaxed position, the GDM normal (unnormalised: twice the fan's area times its
  /// mean unit normal) and whether its voxel holds other points too.
  std::vector<std::array<std::int32_t, 3>> voxel;
  std::vector<Vec3> boxLo, boxHi, position, normal;
  /// Per point: the mean of the outer ends of its crossing edges (on the voxel boundary).
  std::vector<Vec3> anchor;
  std::vector<std::uint8_t> shared;
  /// Quadrilaterals (point ids), counter-clockwise seen from outside.
  std::vector<Quad> quads;
  /// Links of each point (its face neighbours in the net), in CSR form, in the cyclic order
  /// of the fan: linkOffsets[p] .. linkOffsets[p + 1] into links; quadsOf likewise lists the
  /// quadrilaterals at each point.
  std::vector<std::int64_t> linkOffsets;
  std::vector<std::int32_t> links, quadsOf;
  std::size_t boundaryVoxels = 0; ///< object voxels with a background 26-neighbour
  std::size_t prunedVoxels = 0;   ///< boundary voxels left without a point (thin crests)
  int iterationsRun = 0;
  double lastDisplacement = 0.0;
  std::size_t pointCount() const { return this->position.size(); }
};

/// Builds the net of `object` (outside the box is background), relaxes it and computes the
/// GDM normals.
DeformedModel buildDeformedModel(const BitVolume& object,
  const DeformedModelOptions& options,
  const Execution& exec);

/// The 4-cycles of the unpruned net: every ring of four boundary voxels around a grid edge,
/// as voxel-index quadruples (for inspection: it is not a surface on crests).
std::vector<std::array<std::array<std::int32_t, 3>, 4>> unprunedQuadrilaterals(
  const BitVolume& object);

/// The relaxation above, on a model whose points, boxes, anchors and links are set (the
/// label net of LabelNet.h uses it too): links join points whose voxels' index parities
/// differ, except points whose box is a single position.
void relaxDeformedModel(DeformedModel& model,
  const DeformedModelOptions& options,
  const Execution& exec);

/// Fills the links and quadsOf lists (CSR, in linkOffsets) of a model from its quads.
void linkQuadrilaterals(DeformedModel& model);

/// The relaxation's cost: sum over links of |p_a - p_b|^2 + attachment * sum over points of
/// |p - anchor|^2.
double relaxationCost(const DeformedModel& model, double attachment);

} // namespace vbr

#endif
