/**
 * @class   vtkFaceOctreeBoundaryFilter
 * @brief   closed, compact polygonal boundary of the voxels of an image, from a relaxed
 *          deformed model and a face octree of planes
 *
 * vtkFaceOctreeBoundaryFilter implements R. Joan-Arinyo and J. Solé, "Boundary Generation
 * from Voxel-based Volume Representations" (report LSI-96-20-R, UPC, 1996), in three steps:
 * 1. Deformed model (section 3.2, Filters/Core/DeformedModel.h): a representative point per
 *    boundary voxel (an object voxel with a background voxel among its 26 neighbours),
 *    linked to the points of its face neighbours; the net is relaxed by minimising the sum of
 *    squared link lengths plus a pull of each point to its anchor on the voxel boundary,
 *    each point staying inside its voxel; its 4-cycles are the non-planar quadrilaterals.
 *    The dangling quadrilaterals of one-voxel crests and the internal quadrilaterals of
 *    two-voxel crests are pruned: a quadrilateral is kept when its grid edge joins an
 *    interior vertex (eight object voxels) to another. The voxels of one-voxel crests are
 *    lost (NumberOfPrunedVoxels).
 * 2. Face octree (section 3.3, FaceOctree.h): a plane per boundary voxel (the area-weighted
 *    normal of the fan of triangles around its point) and a compaction of octree nodes into
 *    face nodes whose one plane passes within Precision of the node's points and cuts no
 *    voxel that is far from the boundary. By default (the reach rule, beyond the paper) the
 *    nodes are tried from the root down, the plane need not meet the points' voxels, and a
 *    node is kept only if every point, moved onto the plane inside the node's box, stays
 *    within one voxel diagonal of every surfel of its voxel and no sewing quadrilateral's box
 *    meets a far voxel. With KeepPointsInVoxels (the paper's rule) the compaction is
 *    bottom-up and the plane meets every point's voxel.
 * 3. Boundary (section 3.4, FaceOctreeBoundary.h): the points of each face node moved onto
 *    its plane (inside the node's box; with KeepPointsInVoxels inside their voxels) and its
 *    quadrilaterals collapsed into one planar polygon; the quadrilaterals spanning nodes split
 *    into two triangles that sew them.
 *
 * The result is closed and manifold (every edge of exactly two cells, consistently
 * oriented, normals out of the object) and lies within one voxel diagonal of the voxel
 * boundary, both ways, except at pruned voxels: every output vertex lies in a voxel that
 * touches the boundary, every surfel of an unpruned voxel lies within a voxel diagonal of that
 * voxel's vertex, no polygon
 * crosses a voxel that does not touch the boundary, and no sewing triangle leaves the voxels
 * that do (FaceOctree.h gives the argument).
 *
 * Manifold rule (where voxels touch only along an edge or at a corner): interior vertices
 * that touch only diagonally stay apart unless the voxels on either side join them; a voxel
 * holding two sheets of the surface then has a point for each (see DeformedModel.h).
 *
 * Output modes:
 * - Polygons (default): one polygon per face node (cut into convex pieces where no corner's
 *   fan covers it, VTK drawing a polygon as the fan from its first point; every polygon is
 *   planar, simple and starts at a corner whose fan covers it), plus the sewing triangles.
 * - Triangles: the same surface, each polygon as the fan of triangles VTK would draw.
 * - Quadrilaterals: the relaxed net alone, before the octree (the paper's intermediate
 *   surface; non-planar quadrilaterals). With PruneCrests off it is the unpruned net (every
 *   ring of four boundary voxels around a grid edge, at the voxel centres), which is not a
 *   surface on crests; Polygons and Triangles always prune.
 *
 * Cell data: `FaceNodeId` (the face node of a polygon, -1 for sewing triangles and
 * quadrilaterals), `NodeLevel` (its level: 2^level voxels a side; -1 likewise), `Label` (the
 * selected label, 1 outside Labels mode, in the selected values' type; in Labels mode the
 * larger of the cell's two labels) and, in Labels mode, `BoundaryLabels` (see below). Field data:
 * `NumberOfBoundaryVoxels`, `NumberOfFaceNodes`, `NumberOfPolygons` (cells of face nodes),
 * `NumberOfTriangles` (triangles among all cells), `NumberOfPrunedVoxels` and
 * `MaximumDistance` (the largest distance from an output vertex to the voxel boundary, the
 * surfels, measured by the filter in voxel units: 1 is a voxel edge, the bound is sqrt(3);
 * with Simplify an upper bound over the whole surface, and `MaximumSurfelDistance` is added:
 * an upper bound of the distance from the surfels of unpruned voxels to the surface).
 *
 * Output port 1: the face octree, one hexahedron per face node (its box, in world
 * coordinates; with MergeFaceNodes a merged face's box is the bounding box of its octree
 * nodes, and the boxes stay disjoint like the octree's cells) with cell data `PlaneNormal`
 * (unit, world), `PlaneOffset` (world: the plane is PlaneNormal . x = PlaneOffset), `NodeLevel`,
 * `FaceNodeId` and `Label` (in Labels mode the larger label of the node's pair; its box is that of
 * its grid vertices' boxes, offset by half a voxel from the voxels).
 *
 * Labels mode (beyond the paper; Filters/Core/LabelNet.h): neighbouring labels share one
 * surface, with no gap and no overlap between them. One net serves all labels: a point near
 * each grid vertex where labels meet (relaxed inside the box of half a voxel around the
 * vertex, shrunk by the margin) and a quadrilateral for each voxel face between two labels,
 * oriented from the smaller label to the larger; the face octree is then compacted per pair
 * of labels (a node's plane and polygon belong to one pair; points where three labels meet
 * are never projected) and the boundary assembled as above. Every cell carries its two
 * labels in the 2-component cell array `BoundaryLabels` (the background, BackgroundValue,
 * first, then by value: the order of the labels; the normal points from the first label to
 * the second), and `Label` holds the second (the label that is not the background). The
 * cells carrying a label, turned out of it, are that label's closed, manifold surface,
 * within one voxel diagonal of its voxels' boundary; the Triangles output is free of
 * self-intersections (tested on random label maps). NumberOfBoundaryVoxels counts the net's
 * points in Labels mode, NumberOfPrunedVoxels is 0 (nothing is pruned), and MaximumDistance
 * is measured to the faces between different labels. With PruneCrests off the
 * Quadrilaterals output stays the unpruned net of each label on its own.
 *
 * Manifold rule of Labels mode: where two voxels of one label touch only along an edge, and
 * neither other voxel around the edge has that label, the label is joined across the edge
 * (the edge is split, one copy for each other voxel); in a checkerboard A B A B the larger
 * label is joined and the smaller kept apart. Where a label's voxels touch only at a vertex,
 * or both copies of a split edge meet again there, the vertex becomes a small ball of the
 * largest such label (the label joined by the split edge otherwise), with a point on each
 * edge copy and a fan of triangles for each region of another label around it.
 *
 * Point scalars are voxels centred at the points; cell scalars are the voxels. Images are 3D (a
 * flat image is a one-voxel slab, all pruned). A direction matrix with negative determinant (a
 * mirrored image) reverses the cells so that normals still point out of the object.
 *
 * @warning The relaxation (per point, in two colours), the plane fits of each octree level
 * and the voxel classifications run with vtkSMPTools (set VTK_SMP_BACKEND_IN_USE=STDThread
 * with ParaView's VTK, whose default is sequential).
 *
 * Under MPI (ParaView running the filter on N ranks, one piece each) both outputs are the
 * 1-rank outputs, by rank 0 (from the extreme vertices of every rank's voxels; see
 * vtkVoxelBRepDistributed.h).
 *
 * @sa vtkEVMBoundaryFilter vtkDiscreteFlyingEdges3D vtkSurfaceNets3D
 */
#ifndef vtkFaceOctreeBoundaryFilter_h
#define vtkFaceOctreeBoundaryFilter_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkVoxelSelection.h" // for vtkVoxelSelectionMacro

class VOXELBREPFILTERS_EXPORT vtkFaceOctreeBoundaryFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkFaceOctreeBoundaryFilter* New();
  vtkTypeMacro(vtkFaceOctreeBoundaryFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputModes
  {
    POLYGONS = 0,
    TRIANGLES = 1,
    QUADRILATERALS = 2
  };

  /**
   * The selection (SelectionMode Positive, Range or Labels, LowerThreshold, UpperThreshold,
   * BackgroundValue, ArrayComponent): see vtkVoxelSelection. The default is POSITIVE.
   */
  vtkVoxelSelectionMacro();

  ///@{
  /**
   * What the output cells are (see the class comment). The default is POLYGONS.
   */
  vtkSetClampMacro(OutputMode, int, POLYGONS, QUADRILATERALS);
  vtkGetMacro(OutputMode, int);
  void SetOutputModeToPolygons() { this->SetOutputMode(POLYGONS); }
  void SetOutputModeToTriangles() { this->SetOutputMode(TRIANGLES); }
  void SetOutputModeToQuadrilaterals() { this->SetOutputMode(QUADRILATERALS); }
  const char* GetOutputModeAsString();
  ///@}

  ///@{
  /**
   * Relaxation sweeps at most (each moves every point once). The default is 50.
   */
  vtkSetClampMacro(RelaxationIterations, int, 0, VTK_INT_MAX);
  vtkGetMacro(RelaxationIterations, int);
  ///@}

  ///@{
  /**
   * The relaxation stops once no point moved more than this in a sweep (voxel units). The
   * default is 1e-4.
   */
  vtkSetClampMacro(RelaxationTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RelaxationTolerance, double);
  ///@}

  ///@{
  /**
   * Largest face node: 2^level voxels a side (0: every boundary voxel its own node, no
   * polygons). The default is 10.
   */
  vtkSetClampMacro(MaximumOctreeLevel, int, 0, 20);
  vtkGetMacro(MaximumOctreeLevel, int);
  ///@}

  ///@{
  /**
   * Largest distance (world units) a relaxed point may be from its face node's plane; 0
   * (the default) means half a voxel (half the smallest spacing). Whatever the value, the
   * output stays within one voxel diagonal of the voxel boundary (the reach rule checks it
   * for every moved point and sewing quadrilateral; with KeepPointsInVoxels points stay in
   * their voxels; planes cut no voxel far from the boundary); larger values compact more.
   */
  vtkSetClampMacro(Precision, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Precision, double);
  ///@}

  ///@{
  /**
   * Prune the quadrilaterals of one- and two-voxel crests (section 3.2). Off only changes
   * the Quadrilaterals output (the unpruned net); the other modes always prune. The default
   * is on.
   */
  vtkSetMacro(PruneCrests, bool);
  vtkGetMacro(PruneCrests, bool);
  vtkBooleanMacro(PruneCrests, bool);
  ///@}

  ///@{
  /**
   * The paper's rule for a face node's plane (default off): the plane meets every point's
   * voxel, the points are moved onto it inside their own voxels, and the octree is compacted
   * bottom-up. Off (the default): the reach rule (see above and FaceOctree.h), from the root
   * down, whose planes may leave the points' voxels while every moved point stays within one
   * voxel diagonal of its voxel's surfels: the same guarantees with about half the cells on
   * the benchmark's round solids (0.15 instead of 0.28 cells per object voxel on the torus at
   * 128^3, README). Labels mode always keeps the paper's rule.
   */
  vtkSetMacro(KeepPointsInVoxels, bool);
  vtkGetMacro(KeepPointsInVoxels, bool);
  vtkBooleanMacro(KeepPointsInVoxels, bool);
  ///@}

  ///@{
  /**
   * Merge adjacent face nodes (beyond the paper; default off): after the octree's compaction,
   * face nodes that share quadrilaterals are merged greedily, the largest first, whenever one
   * plane fits their union under the same rules as an octree node (FaceOctree.h), so that a
   * planar patch across octree cell boundaries becomes one polygon and the sewing triangles
   * between the merged nodes disappear. A merged face is one face node: one `FaceNodeId`,
   * as `NodeLevel` the largest level of the octree nodes merged into it, and on output port
   * 1 one box, the bounding box of its octree nodes. Faces merge only while their boxes
   * stay disjoint and no face facing away (another sheet) or point in no face lies within a
   * voxel of the box: each polygon keeps a box of its own, as in the octree. Off (the
   * default): the face octree alone. The merging is serial: on the 128^3 solids it removes 14
   * to 24 % of the cells after the reach rule (10 to 16 % under the paper's rule) for about
   * 1.4x the filter's time (about 2x under the paper's rule; README).
   */
  vtkSetMacro(MergeFaceNodes, bool);
  vtkGetMacro(MergeFaceNodes, bool);
  vtkBooleanMacro(MergeFaceNodes, bool);
  ///@}

  ///@{
  /**
   * Simplify the boundary (beyond the paper; Filters/Core/BoundarySimplifier.h): edge
   * collapses of the Triangles boundary, each accepted only when the new triangles stay
   * within SimplificationDistance of the voxel boundary, every surfel point (of the voxels
   * that are not pruned) stays within it of the surface, and no triangle meets another. The
   * output is then triangles in the Polygons and Triangles modes (FaceNodeId and NodeLevel
   * -1; port 1 keeps the face octree), still closed, manifold, of the same genus and free
   * of self-intersections (checked at the end with CGAL; if a check fails, a warning and
   * the unsimplified triangles). MaximumDistance is then an upper bound (within 0.02 voxel)
   * of the largest distance from the surface to the surfels, not only from its vertices,
   * and the field `MaximumSurfelDistance` bounds the other side (both measured on the
   * unsimplified triangles of an object that kept them). Exception: where the unsimplified
   * surface is itself farther from a surfel than SimplificationDistance (it reaches about
   * 1.56 voxels), that surfel may stay farther (at most its input distance plus 0.09 voxel;
   * measured: distance 1.0 gives MaximumSurfelDistance 1.38); a warning says so whenever
   * MaximumSurfelDistance exceeds SimplificationDistance. Ignored in the
   * Quadrilaterals mode; not supported in Labels mode (a warning). Off by default: it takes
   * 9 to 15 times the filter's own CPU time (3.5 to 4.3 M voxels per CPU second on the 256^3
   * solids); an object of 4096 triangles or more is cut into two slabs simplified
   * concurrently when the SMP backend has threads, then as a whole (BoundarySimplifier.h, Regions:
   * the same output with any SMP backend and thread count; on two idle cores with the STDThread
   * backend 1.24x to 1.72x less wall time on the 256^3 ball and torus and the 128^3 CSG solid, none
   * when the cores are busy; on one thread up to 16 % more CPU). On the benchmark's 128^3 ball,
   * torus and CSG solid it keeps 2.2, 2.2 and 1.5 times fewer triangles than flying edges,
   * windowed-sinc smoothing and quadric decimation decimated as far as their distance stays within
   * the filter's, in less time; with KeepPointsInVoxels, whose surface leaves the collapses more
   * room near sharp edges, 2.2 times fewer on the CSG solid too, at up to 1.7 times the reach
   * rule's time (README).
   */
  vtkSetMacro(Simplify, bool);
  vtkGetMacro(Simplify, bool);
  vtkBooleanMacro(Simplify, bool);
  ///@}

  ///@{
  /**
   * With Simplify, the largest distance (world units) between the simplified surface and the
   * voxel boundary, both ways; 0 (the default) means one voxel diagonal (sqrt(3) voxels).
   * Converted to voxels by the largest spacing, and at most 1.99 voxels.
   */
  vtkSetClampMacro(SimplificationDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SimplificationDistance, double);
  ///@}

protected:
  vtkFaceOctreeBoundaryFilter();
  ~vtkFaceOctreeBoundaryFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /// The work of RequestData, which turns exceptions (out of memory) into errors.
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  int OutputMode = POLYGONS;
  int RelaxationIterations = 50;
  double RelaxationTolerance = 1e-4;
  int MaximumOctreeLevel = 10;
  double Precision = 0.0;
  bool PruneCrests = true;
  bool MergeFaceNodes = false;
  bool KeepPointsInVoxels = false;
  bool Simplify = false;
  double SimplificationDistance = 0.0;

private:
  vtkFaceOctreeBoundaryFilter(const vtkFaceOctreeBoundaryFilter&) = delete;
  void operator=(const vtkFaceOctreeBoundaryFilter&) = delete;
};

#endif
