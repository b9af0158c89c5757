/**
 * @class   vtkCUDBConnectivity
 * @brief   connected components of the voxels of an image, through the Compact Union of
 *          Disjoint Boxes
 *
 * vtkCUDBConnectivity selects voxels of a vtkImageData (a threshold range, every value above
 * zero, or every label of a label map), encodes them as an Extreme Vertices Model (EVM) and
 * converts it into a Compact Union of Disjoint Boxes (CUDB) by the sweep of I. Cruz-Matias
 * and D. Ayala, "CUDB: An Improved Decomposition Model for Orthogonal Pseudo-Polyhedra": the
 * slices of the EVM are cut into boxes that are merged on the fly wherever the Ordered Union
 * of Disjoint Boxes would split them needlessly, and every box records the boxes it touches.
 * The connected components are then labelled on the boxes (a few thousand where the image
 * has millions of voxels) and written back to the voxels. A 2D image swept in its stored
 * order (the default sorting) gets the same boxes straight from its pixel rows, without
 * building the EVM. A 3D image in the default sorting (one process, RunLabelling on, the
 * default) needs no EVM either: its
 * components are labelled on the runs of its voxel rows (scan-line labelling,
 * vbr::labelRuns), the CUDB's counts in the field data and the table's NumberOfBoxes are read
 * from the runs, and with GenerateBoxes the CUDB's boxes are built from them (a run, the equal
 * runs of the rows after it, the equal rectangles of the planes after it); every output is the
 * same as through the sweep, faster on porous and noisy volumes, whose boxes are barely
 * larger than the runs. A 2D image of one object in the default sorting without the boxes
 * output (GenerateBoxes off) and many runs (MinimumPixelRuns) is labelled on the runs of its
 * pixel rows in the same way (vbr::labelPixelRuns: the sweep's union-find over the chains of
 * equal runs, no box written) and its regions are measured from the runs; otherwise (the
 * boxes output, a label map, fewer runs) it takes the boxes straight from the pixel rows.
 *
 * Connectivity: Face (6-connected in 3D, 4 in 2D, the default) or Vertex (26 in 3D, 8 in
 * 2D: voxels touching along an edge or at a corner are connected too). In Labels mode the
 * components are computed within each label: touching regions of different labels are
 * different components.
 *
 * Outputs:
 * - Port 0: the input image (its arrays passed through) with an integer array `RegionId`
 *   (0 = not selected or removed, 1..N) of the same association (point or cell) as the
 *   input scalars, set as active scalars. RegionOrdering numbers the regions by size, the
 *   largest first (the default, like vtkImageConnectivityFilter's SizeRank), or in sweep
 *   order (the order in which the sweep first meets them).
 * - Port 1 (when GenerateBoxes is on, the default): the boxes of the kept regions, a
 * vtkUnstructuredGrid of VTK_VOXEL cells (VTK_PIXEL for 2D images; VTK_HEXAHEDRON / VTK_QUAD when a
 * direction matrix or a negative spacing makes boxes not axis-aligned) with cell arrays `RegionId`,
 * `BoxId` (the box's index in the CUDB) and `Label`.
 * - Port 2: a vtkTable with one row per kept region: `RegionId`, `Label`, `VoxelCount`,
 *   `Volume` (world units; the area for a 2D image), `IMin`, `IMax`, `JMin`, `JMax`, `KMin`,
 *   `KMax` (first and last voxel index along i, j, k), `XMin`, `XMax`, `YMin`, `YMax`, `ZMin`,
 *   `ZMax` (world bounds of the voxels), `Centroid` (world; components X, Y, Z) and
 *   `NumberOfBoxes`.
 *
 * `Label` (boxes and table) is the selected label (1 outside Labels mode) in the data type of
 * the selected values: the input array's type (double for MAGNITUDE), so every label is exact.
 *
 * Every output carries the field data `NumberOfRegions` (kept), `NumberOfComponents` (found),
 * `NumberOfBoxes` (CUDB), `NumberOfOUDBBoxes` (what the OUDB of the same sorting would have),
 * `NumberOfExtremeVertices` and `SortingOrder` (the sorting used; with Auto, per label). The three
 * outputs hold the same arrays (one object each, not copies): a consumer that edits one
 * output's summary in place changes the others'.
 *
 * Region filters, applied in this order: regions smaller than MinimumRegionSize voxels are
 * removed (dust removal); with seed points on the optional second input (SetSeedData), only
 * regions containing a seed are kept; with LargestRegions = N > 0 only the N largest of the
 * rest are kept.
 *
 * SortingOrder chooses the ABC sorting of the EVM the boxes are built from (A is the axis
 * the slices are perpendicular to, C the axis the boxes' rows run along); Auto builds all of
 * them (two for a 2D image) and keeps the one with the fewest boxes. The components do not
 * depend on it, only the boxes of port 1.
 *
 * Point scalars are voxels centred at the points; cell scalars are the voxels themselves. An
 * image with one voxel along exactly one axis is 2D. Arrays not stored as contiguous tuples
 * are copied once. NaN values are never selected nor labels.
 *
 * @warning The selection, the EVM extraction and the write-back of the labels run with
 * vtkSMPTools (set VTK_SMP_BACKEND_IN_USE=STDThread with ParaView's VTK, whose default is
 * sequential).
 *
 * @warning Memory kept between updates, so that the next update does not have the kernel fault
 * in and zero it again:
 * - by each filter: the working memory of its labelling, up to 512 MiB in all: when an image
 *   has one object, the runs and labels of a 3D image or the boxes, labels, runs and union-find
 *   of a 2D image's sweep (about 190 MB for a 6001^2 maze), and the union-find and notes of the
 *   3D run labelling. It is freed at the end of an update that would leave more than 512 MiB,
 *   at the end of every update with ReleaseDataFlag on, and with the filter; the 2D sweep's
 *   memory also by an update of anything but a 2D image of one object, and at the end of an
 *   update that used less than a quarter of it. Also small output arrays to write into.
 * - by all the filters of the process together: released blocks of 2 MiB or more. While idle,
 *   at most 512 MiB: the last update's scratch (the region numbering's). The outputs the
 *   pipeline releases just before their filter executes are kept, up to 2 GiB with that
 *   scratch, for that execution, which frees what it does not reuse; outputs released at any
 *   other time (ReleaseData, ReleaseDataFlag, a filter destroyed) are freed at once. The last
 *   filter's destruction frees all of it, as does a memory check that would refuse an input.
 *
 * Under MPI (ParaView running the filter on N ranks, one piece each) the RegionIds are the
 * 1-rank ones on every rank's piece: rank 0 labels the whole image from the ranks' extreme
 * vertices and sends the kept boxes back (see vtkVoxelBRepDistributed.h).
 *
 * @sa vtkImageConnectivityFilter vtkConnectivityFilter vtkEVMBoundaryFilter
 */
#ifndef vtkCUDBConnectivity_h
#define vtkCUDBConnectivity_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkVoxelSelection.h" // for vtkVoxelSelectionMacro

class vtkDataSet;
class vtkImageData;
class vtkTable;
class vtkUnstructuredGrid;
struct vtkCUDBConnectivityKept;

class VOXELBREPFILTERS_EXPORT vtkCUDBConnectivity : public vtkImageAlgorithm
{
public:
  static vtkCUDBConnectivity* New();
  vtkTypeMacro(vtkCUDBConnectivity, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ConnectivityModes
  {
    FACE = 0,  ///< 6-connected (4 in 2D)
    VERTEX = 1 ///< 26-connected (8 in 2D)
  };
  enum SortingOrders
  {
    XYZ = 0,
    XZY = 1,
    YXZ = 2,
    YZX = 3,
    ZXY = 4,
    ZYX = 5,
    AUTO = 6 ///< the sorting with the fewest boxes
  };
  enum RegionOrderings
  {
    SIZE_RANK = 0,  ///< largest region first
    SWEEP_ORDER = 1 ///< in the order the sweep meets the regions (labels in increasing order)
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
   * Which voxels are connected: sharing a face (FACE, the default) or also an edge or a
   * vertex (VERTEX).
   */
  vtkSetClampMacro(Connectivity, int, FACE, VERTEX);
  vtkGetMacro(Connectivity, int);
  void SetConnectivityToFace() { this->SetConnectivity(FACE); }
  void SetConnectivityToVertex() { this->SetConnectivity(VERTEX); }
  const char* GetConnectivityAsString();
  ///@}

  ///@{
  /**
   * ABC sorting of the EVM the boxes are built from. The default is ZYX (slices along z,
   * rows along x: the image's own memory order, which needs no sorting).
   */
  vtkSetClampMacro(SortingOrder, int, XYZ, AUTO);
  vtkGetMacro(SortingOrder, int);
  void SetSortingOrderToXYZ() { this->SetSortingOrder(XYZ); }
  void SetSortingOrderToXZY() { this->SetSortingOrder(XZY); }
  void SetSortingOrderToYXZ() { this->SetSortingOrder(YXZ); }
  void SetSortingOrderToYZX() { this->SetSortingOrder(YZX); }
  void SetSortingOrderToZXY() { this->SetSortingOrder(ZXY); }
  void SetSortingOrderToZYX() { this->SetSortingOrder(ZYX); }
  void SetSortingOrderToAuto() { this->SetSortingOrder(AUTO); }
  const char* GetSortingOrderAsString();
  ///@}

  ///@{
  /**
   * How regions are numbered. The default is SIZE_RANK (largest first; ties in sweep order).
   */
  vtkSetClampMacro(RegionOrdering, int, SIZE_RANK, SWEEP_ORDER);
  vtkGetMacro(RegionOrdering, int);
  void SetRegionOrderingToSizeRank() { this->SetRegionOrdering(SIZE_RANK); }
  void SetRegionOrderingToSweepOrder() { this->SetRegionOrdering(SWEEP_ORDER); }
  const char* GetRegionOrderingAsString();
  ///@}

  ///@{
  /**
   * Regions with fewer voxels are removed. The default is 1 (keep all).
   */
  vtkSetClampMacro(MinimumRegionSize, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MinimumRegionSize, vtkIdType);
  ///@}

  ///@{
  /**
   * Keep only this many of the largest regions; 0 (the default) keeps all.
   */
  vtkSetClampMacro(LargestRegions, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(LargestRegions, vtkIdType);
  ///@}

  ///@{
  /**
   * Whether port 1 receives the boxes (a cell per box, 8 points each: for images of millions
   * of boxes this costs more than the labelling). The default is on.
   */
  vtkSetMacro(GenerateBoxes, bool);
  vtkGetMacro(GenerateBoxes, bool);
  vtkBooleanMacro(GenerateBoxes, bool);
  ///@}

  ///@{
  /**
   * Whether a 3D image in the default sorting is labelled on the runs of its voxel rows (the
   * default, on) rather than through its EVM and the CUDB sweep, and a 2D image of one object
   * without the boxes output on the runs of its pixel rows rather than from its boxes. Every
   * output is the same either way; off is there to compare the two (tests, benchmarks).
   */
  vtkSetMacro(RunLabelling, bool);
  vtkGetMacro(RunLabelling, bool);
  vtkBooleanMacro(RunLabelling, bool);
  ///@}

  ///@{
  /**
   * A 2D image takes the runs of its pixel rows (RunLabelling on, GenerateBoxes off, one
   * object, the default sorting) when it has at least this many runs of selected pixels; with
   * fewer, it is labelled from its boxes. Measuring the regions per box is cheaper than per
   * run, and the runs only gain where the boxes would be many (millions, on a maze). Every
   * output is the same either way. The default is 2^21; 0 takes the runs always.
   */
  vtkSetClampMacro(MinimumPixelRuns, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MinimumPixelRuns, vtkIdType);
  ///@}

  ///@{
  /**
   * Optional seed points (any vtkDataSet, world coordinates): when given, only the regions
   * containing a seed are kept. Seeds outside the selected voxels select nothing.
   */
  void SetSeedConnection(vtkAlgorithmOutput* port);
  vtkAlgorithmOutput* GetSeedConnection();
  void SetSeedData(vtkDataSet* seeds);
  ///@}

  ///@{
  /**
   * Outputs 1 and 2 (output 0, the labelled image, is GetOutput()).
   */
  vtkUnstructuredGrid* GetBoxesOutput();
  vtkTable* GetRegionsOutput();
  ///@}

  /**
   * Opens, on REQUEST_DATA_NOT_GENERATED, the window in which the pipeline releases the
   * outputs this filter is about to regenerate (their memory is kept for that execution), and
   * closes it once REQUEST_DATA has been processed.
   */
  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inInfo,
    vtkInformationVector* outInfo) override;

  /**
   * Bytes of released blocks every vtkCUDBConnectivity of the process keeps now for a next
   * update (see the memory warning above); for tests.
   */
  static vtkIdType GetCachedBlockBytes();

  /**
   * For tests: whether the last update kept its regions in the 32-byte records of 2D images
   * of at most 32,767 pixels a side (rather than the 64-byte records of 3D ones).
   */
  bool GetUsedPlanarRecords();

  /**
   * For tests: `trials` random regions of boxes and rows of a 2D image (coordinates often 0
   * and 32,767) gathered in a 32-byte record and in a 64-byte one, which must agree field by
   * field, and the record's bounds from its SSE2 code and from its scalar code. Returns
   * whether all agree (the first difference printed on std::cerr).
   */
  static bool CheckPlanarRecords(int seed, int trials);

protected:
  vtkCUDBConnectivity();
  ~vtkCUDBConnectivity() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The work of RequestData, which turns exceptions (out of memory) into errors.
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  int Connectivity = FACE;
  int SortingOrder = ZYX;
  int RegionOrdering = SIZE_RANK;
  vtkIdType MinimumRegionSize = 1;
  vtkIdType LargestRegions = 0;
  bool GenerateBoxes = true;
  bool RunLabelling = true;
  vtkIdType MinimumPixelRuns = vtkIdType(1) << 21;

private:
  vtkCUDBConnectivityKept* Kept; // small output arrays written again at the next update
  vtkCUDBConnectivity(const vtkCUDBConnectivity&) = delete;
  void operator=(const vtkCUDBConnectivity&) = delete;
};

#endif
