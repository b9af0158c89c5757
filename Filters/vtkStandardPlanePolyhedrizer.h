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
 * - Surfels: every surfel as a quad, with the FaceId of its face (the paper's figures).
 * - StandardFaces (default): one polygon per face along its whole boundary loop of pointels,
 *   counter-clockwise seen from outside.
 * - SemiDiscrete: one polygon per face through its standard vertices only (the pointels
 *   where three or more faces meet), the paper's section 5; a face with fewer than three
 *   standard vertices keeps three pointels of its loop spread along it.
 * - StandardEdges: the standard edges, each once, as polylines of pointels between two
 *   standard vertices (a closed polyline where two faces meet along a whole loop), with the
 *   cell arrays `FaceId` and `OtherFaceId` (the faces on either side) and `Label`.
 * Cell arrays: `FaceId`, `PlaneNormal` (a, b, c), `PlaneOffset` (mu), `SurfelCount` and
 * `Label`. The plane coefficients are in the image's corner index space: voxel (i, j, k),
 * counted from the first voxel of the extent, spans the corners i..i+1, j..j+1, k..k+1.
 * Field data: `NumberOfSurfels`, `NumberOfFaces`, `MinimumFaceSize`, `MeanFaceSize`,
 * `MaximumFaceSize`, `NumberOfStandardVertices`, `NumberOfBoundaryComponents`, and the grid
 * for vtkStandardPlaneReversion (`VoxelGridOrigin`, `VoxelGridSpacing`, `VoxelGridDimensions`,
 * `VoxelGridDirection`) with the input's layout (`VoxelGridExtent`, `VoxelGridImageOrigin`,
 * `VoxelGridAssociation`).
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
 * @sa vtkEVMBoundaryFilter vtkStandardPlaneReversion
 */
#ifndef vtkStandardPlanePolyhedrizer_h
#define vtkStandardPlanePolyhedrizer_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class VOXELBREPFILTERS_EXPORT vtkStandardPlanePolyhedrizer : public vtkPolyDataAlgorithm
{
public:
  static vtkStandardPlanePolyhedrizer* New();
  vtkTypeMacro(vtkStandardPlanePolyhedrizer, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SelectionModes
  {
    POSITIVE = 0, ///< every voxel whose value is > 0
    RANGE = 1,    ///< LowerThreshold <= value <= UpperThreshold
    LABELS = 2    ///< every distinct value other than BackgroundValue, each on its own
  };

  enum OutputModes
  {
    SURFELS = 0,
    STANDARD_FACES = 1,
    SEMI_DISCRETE = 2,
    STANDARD_EDGES = 3
  };

  ///@{
  /**
   * How voxels are selected. The default is POSITIVE (value > 0).
   */
  vtkSetClampMacro(SelectionMode, int, POSITIVE, LABELS);
  vtkGetMacro(SelectionMode, int);
  void SetSelectionModeToPositive() { this->SetSelectionMode(POSITIVE); }
  void SetSelectionModeToRange() { this->SetSelectionMode(RANGE); }
  void SetSelectionModeToLabels() { this->SetSelectionMode(LABELS); }
  const char* GetSelectionModeAsString();
  ///@}

  ///@{
  /**
   * Inclusive range of selected values in RANGE mode. The default is [1, VTK_DOUBLE_MAX].
   */
  vtkSetMacro(LowerThreshold, double);
  vtkGetMacro(LowerThreshold, double);
  vtkSetMacro(UpperThreshold, double);
  vtkGetMacro(UpperThreshold, double);
  ///@}

  ///@{
  /**
   * Value that is not a label in LABELS mode. The default is 0.
   */
  vtkSetMacro(BackgroundValue, double);
  vtkGetMacro(BackgroundValue, double);
  ///@}

  ///@{
  /**
   * Component of the input array to use. The default is 0.
   */
  vtkSetClampMacro(ArrayComponent, int, 0, VTK_INT_MAX);
  vtkGetMacro(ArrayComponent, int);
  ///@}

  ///@{
  /**
   * What the cells of output port 0 are. The default is STANDARD_FACES.
   */
  vtkSetClampMacro(OutputMode, int, SURFELS, STANDARD_EDGES);
  vtkGetMacro(OutputMode, int);
  void SetOutputModeToSurfels() { this->SetOutputMode(SURFELS); }
  void SetOutputModeToStandardFaces() { this->SetOutputMode(STANDARD_FACES); }
  void SetOutputModeToSemiDiscrete() { this->SetOutputMode(SEMI_DISCRETE); }
  void SetOutputModeToStandardEdges() { this->SetOutputMode(STANDARD_EDGES); }
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

  int SelectionMode = POSITIVE;
  double LowerThreshold = 1.0;
  double UpperThreshold = VTK_DOUBLE_MAX;
  double BackgroundValue = 0.0;
  int ArrayComponent = 0;
  int OutputMode = STANDARD_FACES;
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
