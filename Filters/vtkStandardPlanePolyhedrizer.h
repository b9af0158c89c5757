/**
 * @class   vtkStandardPlanePolyhedrizer
 * @brief   reversible polyhedrization of the surfel boundary of the voxels of an image into
 *          pieces of standard arithmetic planes
 *
 * vtkStandardPlanePolyhedrizer selects voxels of a vtkImageData (as vtkEVMBoundaryFilter:
 * values > 0, a threshold range, or each label of a label map on its own), takes the surfels
 * of their boundary (the unit squares between a selected voxel and an unselected one) and
 * groups them into faces, following J. Francon and L. Papier, "Polyhedrization of the
 * Boundary of a Voxel Object" (DGCI'99). Each face is a topological disk of surfels whose
 * pointels (the voxel corners) lie in one standard arithmetic plane
 *   mu <= a x + b y + c z < mu + |a| + |b| + |c|,
 * with (a, b, c) pointing out of the object: the face is a piece of the boundary of the
 * digital half-space below the plane. Recognition is exact (integer arithmetic only).
 * Faces grow breadth first from a seed (an umbrella of surfels where possible).
 *
 * Every input works: each connected piece of boundary is treated on its own, and where
 * voxels touch only along an edge or at a corner they are kept apart (the selection is taken
 * 6-connected), which makes the boundary a closed 2-manifold.
 *
 * Output port 0, by OutputMode:
 * - TriangulatedFaces (default): each face as triangles whose corners are the pointels of
 *   its boundary loop (no other points), n - 2 for a loop of n pointels. A face lies on the
 *   boundary of a digital half-space, which every line parallel to its normal crosses once,
 *   so its loop projected along the normal is a simple polygon; it is triangulated there
 *   exactly (integer ear clipping, see PolygonTriangulator.h). Neighbouring faces share
 *   their loop edges, so the triangles form a closed surface, oriented outwards: renders
 *   correctly. The cell array `LoopEdges` (bit k: the triangle's edge from corner k to k + 1
 *   runs along its face's loop) lets vtkStandardPlaneReversion rebuild the loops.
 * - Surfels: every surfel as a quad, with the FaceId of its face (the paper's figures).
 * - StandardFaces (for export): one polygon per face along its whole boundary loop of
 *   pointels, counter-clockwise seen from outside (vtkStandardPlaneReversion reads it). The
 *   loop is not planar and the face may be concave, and VTK draws a polygon as a fan of
 *   triangles from its first point, so this output does not render correctly: use
 *   TriangulatedFaces to look at the faces.
 * - SemiDiscrete: the paper's section 5, triangulated like TriangulatedFaces: each face's
 *   polygon runs through its standard vertices (the pointels where three or more faces meet),
 *   a standard edge being the chord between its two ends. Where that would not give a
 *   correct surface an edge keeps its pointels: the edges of faces with fewer than three
 *   standard vertices, and then, until there is none, the edges of each face whose polygon
 *   is not simple and counter-clockwise in the projection along its normal. An edge is drawn
 *   the same way on both its sides, so the triangles still form a closed surface.
 * - StandardEdges: the standard edges, each once, as polylines of pointels between two
 *   standard vertices (a closed polyline where two faces meet along a whole loop), with the
 *   cell arrays `FaceId` and `OtherFaceId` (the faces on either side) and `Label`.
 * Cell arrays (per triangle, polygon or quad, those of its face): `FaceId`, `PlaneNormal`
 * (a, b, c), `PlaneOffset` (mu), `SurfelCount`, `Label` (the selected label, 1 outside Labels
 * mode, in the selected values' data type: the input array's, double for MAGNITUDE) and
 * `FaceColor` (a hash of FaceId in [0, 1) for colouring; the active cell scalars are Label in
 * Labels mode, else FaceColor). The plane coefficients are in the image's corner index space:
 * voxel (i, j, k), counted from the first voxel of the extent, spans the corners i..i+1,
 * j..j+1, k..k+1. Field data: `NumberOfSurfels`, `NumberOfFaces`, `MinimumFaceSize`,
 * `MeanFaceSize`, `MaximumFaceSize`, `NumberOfStandardVertices`, `NumberOfBoundaryComponents`,
 * and the grid for vtkStandardPlaneReversion (`VoxelGridOrigin`, `VoxelGridSpacing`,
 * `VoxelGridDimensions`, `VoxelGridDirection`) with the input's layout (`VoxelGridExtent`,
 * `VoxelGridImageOrigin`, `VoxelGridAssociation`).
 *
 * Output port 1: the reversion, an image with the input's structure and an unsigned char
 * array `Selection` (1 on the selected voxels, with the association of the input scalars),
 * recomputed from the faces alone: the surfels enclosed by each face's loop in its plane,
 * then the voxels by parity. It equals the selection; `ReversionMatches` in its field data
 * says whether it did (the filter reports an error otherwise). vtkStandardPlaneReversion does
 * the same from a StandardFaces output alone (a file, say), with the same layout: both
 * reversions have the extent, origin, spacing and association of the input. With
 * GenerateReversion off, port 1 is empty.
 *
 * Long runs: progress is reported and the abort flag polled inside every phase (growth,
 * moves, merging, loops, reversion); a selection of more than 2^21 surfels (background noise
 * selected with value > 0, typically) raises a warning first.
 *
 * A flat image (one voxel along an axis) is polyhedrized as a one-voxel-thick slab.
 *
 * A boundary of 2^30 surfels or more (about 64 GB of working memory) is refused with an error.
 *
 * @warning Threaded with vtkSMPTools (VTK_SMP_BACKEND_IN_USE=STDThread, for instance): the
 * faces of different boundary components grow concurrently, with the same faces, in the same
 * order, as on one thread, and their moves, loops and vertex counts likewise; the surfel graph's
 * stages are split over the surfels; and each object's reversion check runs beside the writing
 * of its cells, its thread then making the triangles (SemiDiscrete, TriangulatedFaces) of the
 * faces the cells have not reached, which raises the peak memory (by about 50 bytes per surfel
 * on noise, and 12 bytes per triangle made ahead). The faces of one component grow on one
 * thread: a boundary that is mostly one component (porous volumes, and 50 % noise, which
 * percolates) gains little. In Labels mode the objects (one per label) are made in batches
 * (up to four objects per thread, and about eight batches when there are enough objects), each
 * object on one thread, while the cells of the batch before are written and its reversion
 * checked, in object order (the same output). Each object's surfel graph is held whole while
 * its faces grow (one per thread at a time), and the faces and what the cells read of two
 * batches are held at once instead of one object's: on a map of a few large labels the peak
 * memory is about 1.2x to 1.8x that of one thread. The progress moves between batches, and
 * the warning of a very large selection comes after the first batch rather than before it.
 *
 * Under MPI (ParaView running the filter on N ranks, one piece each) the faces are the 1-rank
 * faces, output once by rank 0 (from the extreme vertices of every rank's voxels), and port 1
 * gives every rank its own piece of the reversion (see vtkVoxelBRepDistributed.h).
 *
 * @sa vtkEVMBoundaryFilter vtkStandardPlaneReversion
 */
#ifndef vtkStandardPlanePolyhedrizer_h
#define vtkStandardPlanePolyhedrizer_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkVoxelSelection.h" // for vtkVoxelSelectionMacro

class VOXELBREPFILTERS_EXPORT vtkStandardPlanePolyhedrizer : public vtkPolyDataAlgorithm
{
public:
  static vtkStandardPlanePolyhedrizer* New();
  vtkTypeMacro(vtkStandardPlanePolyhedrizer, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputModes
  {
    SURFELS = 0,
    STANDARD_FACES = 1,
    SEMI_DISCRETE = 2,
    STANDARD_EDGES = 3,
    TRIANGULATED_FACES = 4
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
   * What the cells of output port 0 are (see the class comment). The default is
   * TRIANGULATED_FACES; STANDARD_FACES is for export (it does not render correctly).
   */
  vtkSetClampMacro(OutputMode, int, SURFELS, TRIANGULATED_FACES);
  vtkGetMacro(OutputMode, int);
  void SetOutputModeToSurfels() { this->SetOutputMode(SURFELS); }
  void SetOutputModeToStandardFaces() { this->SetOutputMode(STANDARD_FACES); }
  void SetOutputModeToSemiDiscrete() { this->SetOutputMode(SEMI_DISCRETE); }
  void SetOutputModeToStandardEdges() { this->SetOutputMode(STANDARD_EDGES); }
  void SetOutputModeToTriangulatedFaces() { this->SetOutputMode(TRIANGULATED_FACES); }
  const char* GetOutputModeAsString();
  ///@}

  ///@{
  /**
   * Largest number of surfels in a face; 0 (the default) means no limit.
   */
  vtkSetClampMacro(MaximumFaceSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumFaceSize, int);
  ///@}

  ///@{
  /**
   * Largest breadth-first depth of a surfel from its face's seed; 0 (the default) means no
   * limit.
   */
  vtkSetClampMacro(MaximumDepth, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumDepth, int);
  ///@}

  ///@{
  /**
   * After the growth, move surfels from smaller faces to a larger neighbouring face whose
   * plane takes them unchanged, when both faces stay disks (faces emptied disappear). The
   * default is on; off gives the paper's growth alone.
   */
  vtkSetMacro(MoveToLargerFaces, bool);
  vtkGetMacro(MoveToLargerFaces, bool);
  vtkBooleanMacro(MoveToLargerFaces, bool);
  ///@}

  ///@{
  /**
   * After the growth, offer each small face (at most MergeFacesUpTo surfels), smallest
   * first, to the faces around it: when they can take all its surfels, each staying a disk of
   * one standard plane (and within MaximumFaceSize), the face disappears. The default is off.
   */
  vtkSetMacro(MergeFaces, bool);
  vtkGetMacro(MergeFaces, bool);
  vtkBooleanMacro(MergeFaces, bool);
  vtkSetClampMacro(MergeFacesUpTo, int, 1, VTK_INT_MAX);
  vtkGetMacro(MergeFacesUpTo, int);
  ///@}

  ///@{
  /**
   * Compute output port 1 (the reversion). The default is on.
   */
  vtkSetMacro(GenerateReversion, bool);
  vtkGetMacro(GenerateReversion, bool);
  vtkBooleanMacro(GenerateReversion, bool);
  ///@}

protected:
  vtkStandardPlanePolyhedrizer();
  ~vtkStandardPlanePolyhedrizer() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int OutputMode = TRIANGULATED_FACES;
  int MaximumFaceSize = 0;
  int MaximumDepth = 0;
  bool MoveToLargerFaces = true;
  bool MergeFaces = false;
  int MergeFacesUpTo = 8;
  bool GenerateReversion = true;

private:
  vtkStandardPlanePolyhedrizer(const vtkStandardPlanePolyhedrizer&) = delete;
  void operator=(const vtkStandardPlanePolyhedrizer&) = delete;

  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
};

#endif
