// The shared surfaces of a label map (Labels mode of the face octree boundary, beyond the
// paper of Joan-Arinyo and Solé): one net for all labels, in which neighbouring labels share
// the polygons between them, then the face octree compaction of FaceOctree.h run on the
// polygons of each pair of labels, and the boundary assembly of FaceOctreeBoundary.h.
//
// The net. Its polygons are the voxel faces (surfels) between two different labels, label 0
// being the background and everything outside the grid; each carries both labels and is
// oriented with its normal from the smaller label to the larger. Its points sit at the grid
// vertices where labels meet: a vertex whose eight voxels do not all have one label has one
// point, relaxed (DeformedModel.h's cost and iteration) inside the box of half a voxel around
// the vertex shrunk by the margin, pulled to the vertex itself. This is the primal of
// vtkSurfaceNets3D's dual (its points sit in the cubes of voxel centres, here the boxes
// around the vertices). The polygons of label L (those that carry L) bound the voxels of L.
//
// Manifold rule. Around a grid edge four voxels meet. When two diagonal voxels have one label
// that neither other voxel has, that label is joined across the edge and the edge is split
// in two, one copy for the faces of each other voxel (a thin neck of the diagonal label);
// when both diagonals hold one label each (a checkerboard A B A B), the larger label is
// joined and the two voxels of the smaller kept apart. Every other edge stays one edge (with
// two, three or four faces: three or four labels meet there and each has two). Every label
// then has two faces at each copy of an edge. At a vertex the faces linked through shared
// edge copies form the vertex's sheets, each with its own point (several sheets: each point
// fixed at half the mean of its faces' centres from the vertex, so that sheets stay apart). A
// sheet along which one label has two or more separate regions (the voxels of that label
// touch only at this vertex), or that holds both copies of a split edge (they would meet
// again here), is blown up: the vertex becomes a small ball of the largest label with two
// regions there, else of the label joined across that edge. The ball has a point on each
// edge copy of the sheet (0.3 voxel from the vertex, leaning towards the voxel a split copy
// is formed around), each face at the vertex replaces its corner by the two points of its
// edges there, and the ball's surface gets a patch for each region of another label around
// it. Such patches and faces (more than four corners, not planar) become fans of triangles
// around a new point (the mean of their corners, moved a twentieth of a voxel towards the
// region for a patch), their corners fixed: a fan from a corner could cross the ball. The
// ball joins the regions of its label at the vertex and separates those
// of the others. Each label's surface is then closed and manifold: every edge bounds exactly
// two of its polygons, and the polygons around each of its points form one disk.
//
// The face octree. A point of a single sheet whose polygons all carry one pair of labels may
// be projected onto a face node's plane; the others (where three labels meet, several sheets,
// blown-up vertices and their polygons' corners) stay where they are and are never inside a
// face node. The quadrilaterals of each pair are compacted as FaceOctree.h compacts an
// object's, in the grid of the vertices' boxes: a node's plane may cut only the boxes of
// vertices of that pair's faces, so every point of its polygon lies within half a voxel
// diagonal of a face between the two labels. Each node, its plane and its polygon belong to
// one pair; the sewing triangles too. The boundary of each pair is assembled as in
// FaceOctreeBoundary.h, and the pairs share the points that are not projected.
#ifndef vbr_LabelNet_h
#define vbr_LabelNet_h

#include "DeformedModel.h"
#include "Execution.h"
#include "FaceOctree.h"
#include "FaceOctreeBoundary.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vbr
{

using LabelPair = std::array<std::int32_t, 2>;

/// A label per voxel, x fastest; 0 is the background (and everything outside the grid).
struct LabelVolume
{
  std::array<std::int32_t, 3> dims{ 0, 0, 0 };
  std::vector<std::int32_t> labels;

  std::int32_t at(std::int32_t i, std::int32_t j, std::int32_t k) const
  {
    if (i < 0 || j < 0 || k < 0 || i >= dims[0] || j >= dims[1] || k >= dims[2])
      return 0;
    return labels[i + std::size_t(dims[0]) * (j + std::size_t(dims[1]) * k)];
  }
};

/// The relaxed net of all labels.
struct LabelNet
{
  /// Points: `voxel` is the point's grid vertex (vertex v is at position v, voxel i spans
  /// [i, i + 1]), boxes, positions, anchors, normals (from all its polygons) and links; `shared`
  /// marks the points that are never projected. Its `quads` are left empty.
  DeformedModel model;
  /// The polygons (point ids), quadrilaterals except at blown-up vertices, in CSR form.
  std::vector<std::int64_t> offsets{ 0 };
  std::vector<std::int32_t> corners;
  std::vector<LabelPair> labels; ///< per polygon: its two labels, smaller first
  std::size_t blownUpVertices = 0;
  std::size_t polygonCount() const { return this->labels.size(); }
};

LabelNet buildLabelNet(const LabelVolume& volume,
  const DeformedModelOptions& options,
  const Execution& exec);

/// The shared boundary of all labels.
struct LabelBoundary
{
  BoundaryMesh mesh;               ///< points in voxel units; faceNode: index into nodes
  std::vector<LabelPair> labels;   ///< per cell: its two labels, smaller first
  std::vector<FaceNode> nodes;     ///< terminal face nodes, plane in voxel units
  std::vector<LabelPair> nodePair; ///< per node: its pair of labels
  /// Per node: its box in voxel units (the boxes of its vertices: [lo - 0.5, hi - 0.5]).
  std::vector<std::array<Vec3, 2>> nodeBox;
};

LabelBoundary assembleLabelBoundary(const LabelNet& net,
  const FaceOctreeOptions& options,
  BoundaryCells cells,
  const Execution& exec);

/// Largest distance from the points to the faces between voxels of different labels (voxel
/// units), each point searched within two voxels of its own (distances beyond are reported
/// as 2).
double maximumDistanceToLabelFaces(const LabelVolume& volume,
  const std::vector<Vec3>& points,
  const Execution& exec = Execution());

} // namespace vbr

#endif
