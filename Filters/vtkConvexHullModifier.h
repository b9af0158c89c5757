/**
 * @class   vtkConvexHullModifier
 * @brief   the convex hull of the voxels of an image, pressed in recursively into a polyhedron
 *          that separates object voxels from background voxels, reversibly
 *
 * vtkConvexHullModifier selects voxels of a vtkImageData (values > 0, a threshold range, or
 * each label of a label map on its own, point or cell scalars of any type: see
 * vtkVoxelSelection) and follows H. Schulz, "Polyhedral Surface Approximation of Non-Convex
 * Voxel Sets and Improvements to the Convex Hull Computing Method" (FZD-514, 2009). Voxels are
 * their centres. The core is plain C++ in Filters/Core:
 * - ConvexHull.h: the exact convex hull of the vertex candidates (voxels at a convex 0-cell,
 *   section 3.1), grown from the octahedron of the eight extreme candidates (section 3.2) with
 *   exact integer visibility tests and one of the three ways of treating coplanar faces
 *   (CoplanarFaces: the extension method, faces as convex polygons; or Visible / Invisible,
 *   triangulations merged exactly into the same facets afterwards).
 * - ConvexHullModifier.h: the background components inside the hull (section 4.1, CUDB
 *   components) classified as concavities, cavities and tunnels, and the pressing-in of
 *   Algorithm 1 (section 4.2) done as exact Boolean differences of nested lattice hulls (CGAL
 *   corefinement with an exact kernel, confined to LatticeMesh.cxx), which needs no genus-0
 *   restriction: tori and pierced cubes keep their tunnels. Every corner of H is a voxel
 *   centre. Where pieces would touch only along an edge or at a corner (voxels touching that
 *   way), the surfaces are kept apart (a cavity inside, or a solid pressed in from one empty
 *   lattice triangle of the surface; see ConvexHullModifier.h) so that H stays a closed
 *   embedded 2-manifold.
 *
 * Output port 0, by OutputMode (vertices are voxel centres in world coordinates: origin,
 * spacing and direction matrix; cells counter-clockwise seen from outside, reversed on a
 * mirrored grid):
 * - Polyhedron (default): one polygon per face of H along its boundary (faces that have
 *   holes, where a pit opens inside a hull face, are written as their triangles, with the
 *   face's FaceId). After pressing-in a face may be non-convex and VTK draws a polygon as a
 *   fan from its first point, so this output is for export: use Triangles to look at it.
 * - Triangles: the triangles of H (the faces triangulated exactly), which render correctly.
 * - ConvexHull: the faces of the convex hull only, convex polygons.
 * Cell data: `FaceId`, `Level` (0 for pieces of faces of the object's hull, or of its
 * part's hull where the object's components are solved in parts (see ConvexHullModifier.h), 1 for
 * faces pressed in from a background hull, 2 for faces pushed back out, ...), `Label` (the selected
 * label, 1 outside Labels mode, in the selected values' data type) and `FaceColor`. Point
 * data: `VoxelMark` (1 object voxel, 0 background voxel). Field data: `NumberOfVertices`,
 * `NumberOfEdges`, `NumberOfFaces`, `NumberOfHullFaces`, `NumberOfConcavities`,
 * `NumberOfCavities`, `NumberOfTunnels`, `DegreeOfNonConvexity` (maxima and sums over labels),
 * `NumberOfJoinedShells` (shells of H joined to the rest after H separated, summed over
 * labels: voids reached by face-connected background centres and pieces face-next to others,
 * each joined by a lattice prism; ConvexHullModifier.h; 0 on a 2D image),
 * `NumberOfCutHandles` (handles cut through walls of H that sealed a tunnel of a well-composed
 * object, summed over labels: a thin torus whose hole's centres lie on its hull's faces, each
 * cut by a lattice prism; ConvexHullModifier.h; 0 on a 2D image),
 * `Separates` (1 when the filter's own check passed for every object: the voxels rebuilt from
 * H and its marks equal the selection; a 0 comes with an error message) and
 * `BackgroundCentresOnSurface` (the index coordinates of the background voxel centres that lie
 * on H, vertices or not: with VoxelMark, the marks the reversion needs).
 *
 * Output port 1: the reversion, an image with the input's structure and an unsigned char
 * array `Selection` (with the association of the input scalars), rebuilt from H and its marks
 * alone (exact ray crossing parity with a symbolic perturbation), and `ReversionMatches` in
 * its field data.
 *
 * A 2D image (one voxel thick along an axis: the flat axis of cell data on one layer of
 * points, else the last axis with one voxel) gives the 2D analogue (ConvexHullModifier2D.h):
 * polygons with holes in the image plane, whose loops are simple closed polygons with pixel
 * centres as corners, pairwise apart, straight edges as long as possible; no object centre
 * outside, no background centre inside, the centres on the loops marked. Polyhedron writes a
 * polygon without holes as one cell and one with holes as its triangles (with its FaceId),
 * Triangles writes triangles, ConvexHull the convex polygon of the pixel centres. Cells are
 * counter-clockwise seen from the flat axis's positive side (x, y, z cyclic; reversed on a
 * mirrored grid). Level is the polygon's nesting level (0, 2, ...); NumberOfCavities counts
 * holes, NumberOfConcavities notches, NumberOfTunnels is 0, NumberOfHullFaces is 1 per object.
 *
 * @warning On a 2D image a flat object (one pixel, a row) is thickened by lattice points off
 * its line, background centres on the boundary; for an image one pixel thick in the plane too
 * such a corner lies off the image (outside the grid, background by definition, not listed in
 * BackgroundCentresOnSurface). Pixels touching only at a corner are kept in one polygon, the two
 * other centres of their square on its boundary or outside, so no boundary pinches. A noisy 2D
 * image gives deeply nested rings (one region per group and level: 512^2 pixels of 50 % noise
 * take about 1.7 s). In 3D a single voxel or a row becomes a lattice triangle in its plane and
 * H its prism (Separates 1); a segment or a flat set in no plane of the grid's axes becomes a
 * tetrahedron or a pyramid over its polygon with lattice corners beside it. Inputs
 * full of voxels touching along edges and at corners (random noise, porous blobs) separate; the
 * pressing-in of large real objects can take minutes.
 *
 * Under MPI (ParaView running the filter on N ranks, one piece each) H is the 1-rank H, output
 * once by rank 0 (from the extreme vertices of every rank's voxels), and port 1 gives every
 * rank its own piece of the reversion (see vtkVoxelBRepDistributed.h).
 *
 * @sa vtkStandardPlanePolyhedrizer vtkEVMBoundaryFilter
 */
#ifndef vtkConvexHullModifier_h
#define vtkConvexHullModifier_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkVoxelSelection.h" // for vtkVoxelSelectionMacro

class VOXELBREPFILTERS_EXPORT vtkConvexHullModifier : public vtkPolyDataAlgorithm
{
public:
  static vtkConvexHullModifier* New();
  vtkTypeMacro(vtkConvexHullModifier, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputModes
  {
    CONVEX_HULL = 0,
    POLYHEDRON = 1,
    TRIANGLES = 2
  };
  enum CoplanarFacesModes
  {
    EXTENSION = 0,
    VISIBLE = 1,
    INVISIBLE = 2
  };

  vtkVoxelSelectionMacro();

  ///@{
  /**
   * What port 0 holds: ConvexHull, Polyhedron (default) or Triangles.
   */
  vtkSetClampMacro(OutputMode, int, CONVEX_HULL, TRIANGLES);
  vtkGetMacro(OutputMode, int);
  void SetOutputModeToConvexHull() { this->SetOutputMode(CONVEX_HULL); }
  void SetOutputModeToPolyhedron() { this->SetOutputMode(POLYHEDRON); }
  void SetOutputModeToTriangles() { this->SetOutputMode(TRIANGLES); }
  const char* GetOutputModeAsString();
  ///@}

  ///@{
  /**
   * How the hull treats a face coplanar with a new voxel (section 3.1): Extension (default),
   * Visible or Invisible. The polyhedron is the same; the time differs.
   */
  vtkSetClampMacro(CoplanarFaces, int, EXTENSION, INVISIBLE);
  vtkGetMacro(CoplanarFaces, int);
  void SetCoplanarFacesToExtension() { this->SetCoplanarFaces(EXTENSION); }
  void SetCoplanarFacesToVisible() { this->SetCoplanarFaces(VISIBLE); }
  void SetCoplanarFacesToInvisible() { this->SetCoplanarFaces(INVISIBLE); }
  const char* GetCoplanarFacesAsString();
  ///@}

protected:
  vtkConvexHullModifier();
  ~vtkConvexHullModifier() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int OutputMode = POLYHEDRON;
  int CoplanarFaces = EXTENSION;

private:
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  vtkConvexHullModifier(const vtkConvexHullModifier&) = delete;
  void operator=(const vtkConvexHullModifier&) = delete;
};

#endif
