/**
 * @class   vtkEVMBoundaryFilter
 * @brief   exact, compact orthogonal boundary of the voxels of an image, through the
 *          Extreme Vertices Model
 *
 * vtkEVMBoundaryFilter selects voxels of a vtkImageData (a threshold range, every value
 * above zero, or every label of a label map), encodes them as an Extreme Vertices Model
 * (EVM: the grid vertices incident to an odd number of selected voxels) and converts the EVM
 * into a boundary representation made of maximal orthogonal faces with holes, by the plane
 * sweep of D. Ayala and E. Vergara, "An improved boundary extraction algorithm using a
 * plane-sweep technique" (Computer-Aided Design & Applications). For each axis the sections
 * of the EVM give, cut by cut, the forward and backward differences (the faces facing +axis
 * and -axis), and each of these 2D EVMs is turned into faces, holes and their inclusion by a
 * two-pass line sweep without point-in-polygon tests.
 *
 * A face is one edge-connected region of coplanar, equally oriented boundary surfels; it may
 * have holes. Where two pieces of a face touch only at a vertex (a non-manifold vertex) the
 * face is split into manifold faces, unless MergeNonManifoldFaces is on (the paper's variant).
 *
 * Point scalars are voxels centred at the points (the surface lies half a spacing away from
 * the selected points); cell scalars are the voxels themselves. The output is in world
 * coordinates (origin, spacing, extent and direction matrix).
 *
 * Output modes:
 * - Triangles (default): each face triangulated together with its holes. Closed and
 *   consistently oriented (normals point out of the object); renders correctly.
 * - Polygons: each face as few polygons as VTK draws right. VTK's OpenGL mapper draws a
 *   polygon as the fan of triangles from its first point, so a polygon is drawn right only
 *   when that fan covers it: a face without holes from one of whose corners the fan covers
 *   it (a rectangle, an L) is one polygon starting at that corner; any other face (with
 *   holes, or concave) is cut into fans of its triangles, polygons made of a corner and the
 *   far sides of the triangles round it. All pieces of a face carry its FaceId and its
 *   orientation (counter-clockwise seen from outside), keep every vertex of the loops (no
 *   T-junctions) and add none. Closed; renders correctly.
 * - Loops (for export): one polygon per loop, the faces as they are. An outer loop runs
 *   counter-clockwise seen from outside (its right-hand normal points out of the object), a
 *   hole loop the other way. Loops carry every vertex of neighbouring faces that lies on
 *   their edges (no T-junctions), in Labels mode those of the other labels' faces too. Does
 *   not render correctly: a hole is drawn as a filled
 *   polygon over its face and concave loops as wrong fans.
 * - Polylines: the same loops as closed polylines (the contours of a 2D image).
 * - Surfels: one quad per boundary voxel face (what Threshold + Extract Surface gives), for
 *   comparison.
 *
 * Cell arrays: `FaceId` (shared by a face's loops, polygons or triangles), `LoopType` (0
 * outer, 1 hole; triangles and Polygons pieces 0), `Label` (the selected label, or 1 outside
 * Labels mode, in the data type of the selected values: the input array's, double for
 * MAGNITUDE; so every label is exact), `FaceColor` (a hash of FaceId in [0, 1), for colouring:
 * neighbouring faces get unrelated values). The active cell scalars are Label in Labels mode,
 * else FaceColor. For 2D images also `ParentFace` (for a hole: its face; for a face inside a
 * hole: the face owning that hole; -1 at top level) and `Depth` (outer faces 0, their holes 1,
 * faces inside them 2, ...); the hole loops themselves are in the Loops and Polylines outputs.
 *
 * Field data: `NumberOfVoxels`, `NumberOfExtremeVertices`, `NumberOfSurfels`,
 * `NumberOfFaces`, `NumberOfHoles`, `NumberOfNonManifoldVertices` and
 * `NumberOfPlanesOfVertices` (three components: planes perpendicular to x, y and z).
 *
 * 2D images: an image with one voxel along exactly one axis is 2D when FlatImagesAs2D is on
 * (the default): its output is the faces of that plane with their inclusion tree (the
 * contour hierarchy of OpenCV's RETR_TREE, exact on pixel edges), outer loops
 * counter-clockwise seen from the positive side of the flat axis. With FlatImagesAs2D off it
 * is a one-voxel-thick slab with a closed 3D boundary. Cell scalars on a single layer of
 * points are pixels without thickness and always give the 2D output. In Labels mode the
 * inclusion tree is computed label by label.
 *
 * Orientation is kept in world coordinates: a direction matrix with negative determinant (a
 * mirrored image) reverses the cells so that normals still point out of the object.
 *
 * Arrays that are not stored as contiguous tuples (SOA, implicit arrays) are copied once.
 * Labels mode extracts one label at a time (its voxels within its bounding box); NaN values
 * are never labels.
 *
 * @warning The EVM extraction and the three sweeps run with vtkSMPTools (set
 * VTK_SMP_BACKEND_IN_USE=STDThread with ParaView's VTK, whose default is sequential).
 *
 * Under MPI (ParaView running the filter on N ranks, one piece each) the output is the
 * 1-rank output: the ranks send the extreme vertices of the voxels they own to rank 0, which
 * outputs the faces of the whole image once (see vtkVoxelBRepDistributed.h).
 *
 * @sa vtkDiscreteFlyingEdges3D vtkThreshold vtkGeometryFilter
 */
#ifndef vtkEVMBoundaryFilter_h
#define vtkEVMBoundaryFilter_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkVoxelSelection.h" // for vtkVoxelSelectionMacro

#include <memory> // for std::unique_ptr

class VOXELBREPFILTERS_EXPORT vtkEVMBoundaryFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkEVMBoundaryFilter* New();
  vtkTypeMacro(vtkEVMBoundaryFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputModes
  {
    POLYGONS = 0,
    TRIANGLES = 1,
    POLYLINES = 2,
    SURFELS = 3,
    LOOPS = 4
  };

  /**
   * The selection (SelectionMode Positive, Range or Labels, LowerThreshold, UpperThreshold,
   * BackgroundValue, ArrayComponent): see vtkVoxelSelection. The default is POSITIVE (value >
   * 0). (The ParaView plugin's default is Range, with thresholds from the selected array's
   * range: see the XML.)
   */
  vtkVoxelSelectionMacro();

  ///@{
  /**
   * What the output cells are (see the class comment). The default is TRIANGLES; LOOPS is
   * for export (it does not render correctly).
   */
  vtkSetClampMacro(OutputMode, int, POLYGONS, LOOPS);
  vtkGetMacro(OutputMode, int);
  void SetOutputModeToPolygons() { this->SetOutputMode(POLYGONS); }
  void SetOutputModeToTriangles() { this->SetOutputMode(TRIANGLES); }
  void SetOutputModeToPolylines() { this->SetOutputMode(POLYLINES); }
  void SetOutputModeToSurfels() { this->SetOutputMode(SURFELS); }
  void SetOutputModeToLoops() { this->SetOutputMode(LOOPS); }
  const char* GetOutputModeAsString();
  ///@}

  ///@{
  /**
   * Keep faces whole at non-manifold vertices (faces are then vertex-connected regions, the
   * paper's non-manifold faces). The default is off: faces are split into manifold faces.
   */
  vtkSetMacro(MergeNonManifoldFaces, bool);
  vtkGetMacro(MergeNonManifoldFaces, bool);
  vtkBooleanMacro(MergeNonManifoldFaces, bool);
  ///@}

  ///@{
  /**
   * Treat an image with a single voxel along one axis as 2D (contours in its plane with
   * their inclusion tree). Off: treat it as a one-voxel-thick slab. The default is on.
   */
  vtkSetMacro(FlatImagesAs2D, bool);
  vtkGetMacro(FlatImagesAs2D, bool);
  vtkBooleanMacro(FlatImagesAs2D, bool);
  ///@}

protected:
  vtkEVMBoundaryFilter();
  ~vtkEVMBoundaryFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /// The work of RequestData, which turns exceptions (out of memory) into errors.
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  int OutputMode = TRIANGLES;
  bool MergeNonManifoldFaces = false;
  bool FlatImagesAs2D = true;

private:
  vtkEVMBoundaryFilter(const vtkEVMBoundaryFilter&) = delete;
  void operator=(const vtkEVMBoundaryFilter&) = delete;

  /// The 2D plane sweep's arrays, kept from one update to the next (a 2D image's Polylines and
  /// Loops): an update no larger than the one before writes into memory already mapped.
  class vtkPlanarSweep;
  std::unique_ptr<vtkPlanarSweep> PlanarSweep;
};

#endif
