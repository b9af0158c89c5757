#include "vtkCUDBConnectivity.h"

#include "BlockCache.h"
#include "CUDB.h"
#include "EVM.h"
#include "Geometry.h"
#include "Prefetch.h"
#include "RegionNumbering.h"
#include "RegionStatistics.h"
#include "RunLabelling.h"
#include "Sanitizers.h"
#include "vtkVoxelBRepAdapters.h"
#include "vtkVoxelBRepDistributed.h"
#include "vtkVoxelBRepMemory.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTypeFloat64Array.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <memory>
#include <new>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

// Stores past the caches for the large outputs; plain stores under AddressSanitizer, which
// does not see the SSE2 built-ins' writes. Only with SSE2 arithmetic: a 32-bit build's x87
// arithmetic keeps excess precision in registers, so the block writer's rows (below) could
// differ from the row writer's.
#if defined(__SSE2__) && (defined(__x86_64__) || defined(__SSE2_MATH__)) &&                        \
  !defined(VBR_ADDRESS_SANITIZER)
#define VBR_STREAM_STORES 1
#endif
#if defined(VBR_STREAM_STORES)
#include <emmintrin.h>
#endif

// A large region table's rows computed in blocks (RegionColumns::RowBlock): streamed where
// stores past the caches are, copied under AddressSanitizer so that its runs check the block
// writer too.
#if defined(VBR_STREAM_STORES) || defined(VBR_ADDRESS_SANITIZER)
#define VBR_ROW_BLOCKS 1
#endif

vtkStandardNewMacro(vtkCUDBConnectivity);

namespace
{

using Int3 = vbr::Point3; // a lattice point or voxel index

// The block memory (BlockCache.h), the regions' statistics (RegionStatistics.h) and their
// numbering (RegionNumbering.h) of the core, as the adapter's own.
using vbr::allocateBlock;
using vbr::BlockCache;
using vbr::CacheUpdate;
using vbr::HugePagesFromBytes;
using vbr::onHugePages;
using vbr::PlanarRegion;
using vbr::RegionIdList;
using vbr::RegionList;
using vbr::regionOf;
using vbr::RegionRecords;
using vbr::Regions;
using vbr::RegionStats;
using vbr::releaseBlock;
using vbr::ReleaseWindow;
using vbr::valuesOfBoxes;
using vbr::valuesOfRunLabels;

const char* const OrderNames[] = { "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX" };

/// An object's CUDB and components (vbr::LabelledObject) with its label and its count of
/// extreme vertices (the summary's).
struct ObjectBoxes : vbr::LabelledObject
{
  vbr::vtk::LabelValue label;
  std::size_t extremeVertices = 0;
};

/// The process's BlockCache, registered once as the memory vbr::vtk::reclaimMemory gives back
/// before a memory check refuses an allocation or after one failed.
BlockCache& blockCache()
{
  static BlockCache& cache = []() -> BlockCache&
  {
    vbr::vtk::setMemoryReclaimer([] { BlockCache::instance().clear(); });
    return BlockCache::instance();
  }();
  return cache;
}

/// Refuses (throws) `bytes` of new arrays the memory cannot take (what resizeOrThrow checks).
void checkBytes(double bytes, vtkIdType tuples, std::size_t arrays)
{
  const std::string refused = vbr::vtk::checkAllocation(
    bytes, std::to_string(arrays) + " output arrays of " + std::to_string(tuples) + " tuples");
  if (!refused.empty())
    throw std::runtime_error(refused);
}

/// The holders of an AOS array's block of values (its vtkBuffer): vtkDataArray::ShallowCopy
/// (and so vtkMergeArrays) shares the block, not the array, whose own count stays at one.
template<typename T>
struct ValueBlockOf : vtkAOSDataArrayTemplate<T>
{
  static int holders(vtkAOSDataArrayTemplate<T>* array)
  {
    return (array->*(&ValueBlockOf::Buffer))->GetReferenceCount();
  }
};

/// Whether the filter alone holds `array` and its values: no other reference to the array (a
/// dataset or table, a Python object, a numpy view through it) and none to its block of values
/// (an array's ShallowCopy), so that writing it again changes nothing anyone else sees. String
/// arrays are only ever copied whole.
bool heldByTheFilterAlone(vtkAbstractArray* array)
{
  if (!array || array->GetReferenceCount() != 1)
    return false;
  auto* data = vtkDataArray::SafeDownCast(array);
  if (!data)
    return vtkStringArray::SafeDownCast(array) != nullptr;
  int holders = 0;
  switch (data->GetDataType())
  {
    vtkTemplateMacro(if (auto* aos = vtkAOSDataArrayTemplate<VTK_TT>::FastDownCast(data)) holders =
                       ValueBlockOf<VTK_TT>::holders(aos););
  }
  return holders == 1;
}

/// An array of the last update that the filter writes again (no one else holds it): what a
/// new array would not have is dropped (cached ranges and other keys, a lookup table), and its
/// values are marked modified.
void prepareForNewValues(vtkAbstractArray* array)
{
  if (array->HasInformation())
    array->GetInformation()->Clear();
  if (auto* data = vtkDataArray::SafeDownCast(array))
    data->SetLookupTable(nullptr);
  array->Modified();
}

/// `tuples` tuples of each array (of the AOS layout: every array the filter writes), in
/// memory of allocateBlock, unset: the filter writes every value. On huge pages when the
/// arrays are `groupBytes` together with the others of their output. Throws when refused.
void allocateTuples(const std::vector<vtkDataArray*>& arrays, vtkIdType tuples, double groupBytes)
{
  double bytes = 0.0;
  for (vtkDataArray* array : arrays)
    bytes += double(tuples) * array->GetNumberOfComponents() * array->GetDataTypeSize();
  checkBytes(bytes, tuples, arrays.size());
  const bool huge = onHugePages(std::max(bytes, groupBytes));
  for (vtkDataArray* array : arrays)
  {
    const vtkIdType values = tuples * array->GetNumberOfComponents();
    void* block = allocateBlock(static_cast<std::size_t>(values) * array->GetDataTypeSize(), huge);
    if (!block)
      throw std::bad_alloc();
    bool taken = false;
    switch (array->GetDataType())
    {
      vtkTemplateMacro(if (auto* aos = vtkAOSDataArrayTemplate<VTK_TT>::FastDownCast(array)) {
        aos->SetArray(
          static_cast<VTK_TT*>(block), values, 0, vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
        aos->SetArrayFreeFunction(releaseBlock);
        taken = true;
      });
    }
    if (!taken)
    {
      releaseBlock(block);
      vbr::vtk::resizeOrThrow(array, tuples);
    }
  }
}

/// A Label array of `tuples` values of `labelType` (as vbr::vtk::newLabelArray), unset.
vtkSmartPointer<vtkDataArray> newUnsetLabelArray(int labelType, vtkIdType tuples, double groupBytes)
{
  vtkSmartPointer<vtkDataArray> labels = vbr::vtk::newLabelArray(labelType, 0);
  allocateTuples({ labels }, tuples, groupBytes);
  return labels;
}

/// The sortings to try, in processing axes. A 2D image (flat processing axis 2) is swept
/// along lines: only the order of its two in-plane axes matters, taken from the name.
std::vector<vbr::AxisOrder> candidateSortings(int sorting,
  bool planar,
  const std::array<int, 3>& axes)
{
  std::vector<vbr::AxisOrder> out;
  const int first = sorting == vtkCUDBConnectivity::AUTO ? 0 : sorting;
  const int last = sorting == vtkCUDBConnectivity::AUTO ? 5 : sorting;
  for (int s = first; s <= last; ++s)
  {
    const vbr::AxisOrder world = vbr::axisOrderFromName(OrderNames[s]);
    vbr::AxisOrder order{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
      order[k] = static_cast<int>(std::find(axes.begin(), axes.end(), world[k]) - axes.begin());
    if (planar)
    {
      std::array<int, 2> inPlane{ 0, 0 };
      int n = 0;
      for (int k = 0; k < 3; ++k)
        if (order[k] != 2)
          inPlane[n++] = order[k];
      order = { 2, inPlane[0], inPlane[1] };
    }
    if (std::find(out.begin(), out.end(), order) == out.end())
      out.push_back(order);
  }
  return out;
}

/// The CUDB of the EVM in the candidate sorting with the fewest boxes, and the components of
/// its boxes (labelled during the sweep: the filter needs no contacts). False when aborted.
bool buildBestCUDB(const vbr::EVM& evm,
  const std::vector<vbr::AxisOrder>& sortings,
  vbr::Connectivity connectivity,
  const vbr::Execution& exec,
  vbr::CUDB& best,
  vbr::Components& components)
{
  bool found = false;
  for (const vbr::AxisOrder& order : sortings)
  {
    vbr::CUDB cudb;
    vbr::Components labelled;
    const vbr::EVM sorted = order == evm.order() ? vbr::EVM() : evm.sortedAs(order, exec);
    if (!vbr::buildCUDBComponents(
          order == evm.order() ? evm : sorted, connectivity, exec, cudb, labelled))
      return false;
    if (!found || cudb.boxes.size() < best.boxes.size())
    {
      best = std::move(cudb);
      components = std::move(labelled);
    }
    found = true;
  }
  return true;
}

/// Processing-axes coordinates to the image's own axes.
template<typename T>
std::array<T, 3> toImageAxes(const std::array<T, 3>& p, const std::array<int, 3>& axes)
{
  std::array<T, 3> out{};
  for (int k = 0; k < 3; ++k)
    out[axes[k]] = p[k];
  return out;
}

/// World measure of one voxel: its volume, or its area for a 2D image.
double voxelMeasure(const vbr::vtk::VoxelGrid& grid)
{
  std::array<std::array<double, 3>, 3> edge; // edge[d]: world vector of one step along d
  for (int d = 0; d < 3; ++d)
    for (int r = 0; r < 3; ++r)
      edge[d][r] = grid.direction[3 * r + d] * grid.spacing[d];
  auto cross = [](const std::array<double, 3>& a, const std::array<double, 3>& b)
  {
    return std::array<double, 3>{
      a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
    };
  };
  if (grid.flatAxis >= 0)
  {
    const int a = (grid.flatAxis + 1) % 3, b = (grid.flatAxis + 2) % 3;
    const auto n = cross(edge[a], edge[b]);
    return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  const auto n = cross(edge[1], edge[2]);
  return std::abs(edge[0][0] * n[0] + edge[0][1] * n[1] + edge[0][2] * n[2]);
}

/// Whether boxes are axis-aligned in world coordinates (VTK_VOXEL / VTK_PIXEL apply).
bool axisAligned(const vbr::vtk::VoxelGrid& grid)
{
  const std::array<double, 9> identity{ 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  return grid.direction == identity && grid.spacing[0] > 0 && grid.spacing[1] > 0 &&
    grid.spacing[2] > 0;
}

/// Marks the regions containing a seed point, read from `regionOf`: the image of region
/// numbers (index + 1, 0 where nothing is selected) painted from the boxes. One image lookup
/// per seed: the cost is linear in the seeds, whatever the number of boxes. The voxels are
/// found first and looked up after, in a loop of loads alone: scattered seeds miss the cache
/// at each lookup, and between transforms of points those misses were waited for one at a
/// time (59,000 seeds on a 128^3 image: most of the seeded run's extra time).
/// Returns how many seeds fell on a selected voxel.
vtkIdType markSeeds(vtkDataSet* seeds,
  const vbr::vtk::VoxelGrid& grid,
  const std::int32_t* regionOf,
  Regions& regions)
{
  std::vector<std::int64_t> voxels;
  voxels.reserve(static_cast<std::size_t>(seeds->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < seeds->GetNumberOfPoints(); ++i)
  {
    double p[3];
    seeds->GetPoint(i, p);
    Int3 voxel; // image axes, from the first voxel of the extent
    if (grid.worldToVoxel(p, voxel))
      voxels.push_back(
        voxel[0] + std::int64_t(grid.dims[0]) * (voxel[1] + std::int64_t(grid.dims[1]) * voxel[2]));
  }
  vtkIdType hits = 0;
  for (const std::int64_t index : voxels)
  {
    const std::int32_t region = regionOf[index];
    if (region > 0)
    {
      regions.markSeeded(static_cast<std::size_t>(region - 1));
      ++hits;
    }
  }
  return hits;
}

/// The voxels of an object labelled on its runs, one of several objects (a label map), painted
/// from the runs into the zeroed image, as paintRegions does (the only object of an image takes
/// paintOnlyObjectOfRuns).
bool paintRegionsOfRuns(const ObjectBoxes& o,
  const RegionIdList* regionIds,
  const vbr::vtk::VoxelGrid& grid,
  std::int32_t* out,
  const vbr::Execution& exec)
{
  const std::vector<std::int32_t> values = valuesOfRunLabels(o, regionIds);
  return vbr::paintRuns(
    o.voxelRuns, o.runComponents.runLabel, values, o.offset, grid.dims, out, exec);
}

/// RegionId images below this many values (those allocateTuples leaves on the heap, where
/// BlockCache keeps nothing) are kept by the filter for its next update: glibc returned their
/// memory to the kernel, which faulted it in again at every update (a third of the painting of
/// a 448 x 172 image).
constexpr vtkIdType KeptRegionIdValues = vtkIdType(HugePagesFromBytes / sizeof(int));

/// The RegionId image, its values unset, in memory of allocateTuples (an earlier update's,
/// when one released it), or the image of the last update (`kept`) when nothing else holds it
/// and it has as many values: for painters that write every voxel. A small image is kept in
/// `kept` (when given) for the next update.
vtkSmartPointer<vtkIntArray> newRegionIdsInReusedMemory(const vbr::vtk::VoxelGrid& grid,
  vtkSmartPointer<vtkIntArray>* kept)
{
  const vtkIdType n = vtkIdType(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  vtkSmartPointer<vtkIntArray> ids;
  if (kept && heldByTheFilterAlone(*kept) && (*kept)->GetNumberOfTuples() == n &&
    (*kept)->GetNumberOfComponents() == 1)
  {
    ids = *kept;
    prepareForNewValues(ids);
  }
  else
  {
    ids = vtkSmartPointer<vtkIntArray>::New();
    allocateTuples({ ids }, n, 0.0);
  }
  ids->SetName("RegionId");
  if (kept)
    *kept = n < KeptRegionIdValues ? ids : nullptr;
  return ids;
}

/// paintRegions of the image's only object, labelled on its runs: the RegionId image in memory
/// of allocateTuples (an earlier update's, when one released it), every voxel written by
/// vbr::paintRunsOverwriting rather than faulted in zeroed and painted over.
vtkSmartPointer<vtkIntArray> paintOnlyObjectOfRuns(const ObjectBoxes& o,
  const RegionIdList* regionIds,
  const vbr::vtk::VoxelGrid& grid,
  const vbr::Execution& exec,
  vtkSmartPointer<vtkIntArray>* kept)
{
  vtkSmartPointer<vtkIntArray> ids = newRegionIdsInReusedMemory(grid, kept);
  const std::vector<std::int32_t> values = valuesOfRunLabels(o, regionIds);
  if (!vbr::paintRunsOverwriting(o.voxelRuns,
        o.runComponents.runLabel,
        values,
        o.offset,
        grid.dims,
        ids->GetPointer(0),
        exec))
    return nullptr;
  return ids;
}

/// Whether the RegionIds of the image's objects are painted from the pixel runs of the only
/// one, whose rows are the image's (x fastest): paintOnlyObjectOfPixelRuns.
bool onlyObjectOfPixelRuns(const std::vector<ObjectBoxes>& objects, const std::array<int, 3>& axes)
{
  return objects.size() == 1 && !objects[0].labelledFromRuns && !objects[0].runs.empty() &&
    axes[0] == 0;
}

/// paintRegions of a 2D image's only object swept along the image's rows: the RegionId image in
/// memory of allocateTuples (an earlier update's, when one released it), every pixel written
/// by vbr::paintPixelRunsOverwriting rather than mapped zeroed, faulted in and painted over
/// (16 MB of a fax page at each update). The image's rows follow one another: the flat axis
/// is the last processing axis, so with processing x along the image's x the rows of the
/// processing y are the image's rows, dims[0] pixels each.
vtkSmartPointer<vtkIntArray> paintOnlyObjectOfPixelRuns(const ObjectBoxes& o,
  const RegionIdList* regionIds,
  const vbr::vtk::VoxelGrid& grid,
  const vbr::Execution& exec,
  vtkSmartPointer<vtkIntArray>* kept)
{
  vtkSmartPointer<vtkIntArray> ids = newRegionIdsInReusedMemory(grid, kept);
  if (!vbr::paintPixelRunsOverwriting(o.pixels,
        o.runs,
        valuesOfBoxes(o, regionIds),
        { o.offset[0], o.offset[1] },
        grid.dims[0],
        ids->GetNumberOfTuples() / std::max<vtkIdType>(grid.dims[0], 1),
        ids->GetPointer(0),
        exec))
    return nullptr;
  return ids;
}

/// Every voxel painted from its box: with `regionIds`, the region's RegionId (0 where removed);
/// without, the region's number (index + 1). Voxels of no box stay 0. Null when aborted.
/// `kept` (when given): the last update's RegionId image, which the painters of every voxel
/// write again when they can (newRegionIdsInReusedMemory).
vtkSmartPointer<vtkIntArray> paintRegions(const std::vector<ObjectBoxes>& objects,
  const RegionIdList* regionIds,
  const vbr::vtk::VoxelGrid& grid,
  const std::array<int, 3>& axes,
  const vbr::Execution& exec,
  vtkSmartPointer<vtkIntArray>* kept = nullptr)
{
  const std::int64_t n = std::int64_t(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  if (objects.size() == 1 && objects[0].labelledFromRuns)
    return paintOnlyObjectOfRuns(objects[0], regionIds, grid, exec, kept);
  if (onlyObjectOfPixelRuns(objects, axes))
    return paintOnlyObjectOfPixelRuns(objects[0], regionIds, grid, exec, kept);
  vtkSmartPointer<vtkIntArray> ids = vbr::vtk::newZeroedIntArray(static_cast<vtkIdType>(n));
  ids->SetName("RegionId");
  std::int32_t* out = ids->GetPointer(0);
  for (const ObjectBoxes& o : objects)
  {
    if (o.labelledFromRuns)
    {
      if (!paintRegionsOfRuns(o, regionIds, grid, out, exec))
        return nullptr;
      continue;
    }
    if (!vbr::paintBoxes(
          o.cudb.boxes, valuesOfBoxes(o, regionIds), o.offset, axes, grid.dims, out, exec))
      return nullptr;
  }
  return ids;
}

/// Region numbers (index + 1) replaced in place by the regions' RegionIds (0: removed).
void renumberRegions(vtkIntArray* ids, const RegionIdList& regionIds)
{
  std::int32_t* values = ids->GetPointer(0);
  vtkSMPTools::For(0,
    ids->GetNumberOfValues(),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
        if (values[i] > 0)
          values[i] = regionIds[values[i] - 1];
    });
}

/// How a box becomes a cell: its corners, in the cell type's order, as (low/high) bits per
/// role, and the image axis of each role (in 2D the two in-plane image axes take the roles of
/// the first two bits).
struct BoxCellLayout
{
  int corners = 8;
  const int (*bits)[3] = nullptr;
  int cellType = VTK_VOXEL;
  std::array<int, 3> role{ 0, 1, 2 };
};

BoxCellLayout boxCellLayout(const vbr::vtk::VoxelGrid& grid, const std::array<int, 3>& axes)
{
  static const int voxelOrder[8][3] = { { 0, 0, 0 },
    { 1, 0, 0 },
    { 0, 1, 0 },
    { 1, 1, 0 },
    { 0, 0, 1 },
    { 1, 0, 1 },
    { 0, 1, 1 },
    { 1, 1, 1 } };
  static const int hexOrder[8][3] = { { 0, 0, 0 },
    { 1, 0, 0 },
    { 1, 1, 0 },
    { 0, 1, 0 },
    { 0, 0, 1 },
    { 1, 0, 1 },
    { 1, 1, 1 },
    { 0, 1, 1 } };
  const bool planar = grid.flatAxis >= 0;
  const bool aligned = axisAligned(grid);
  BoxCellLayout layout;
  layout.corners = planar ? 4 : 8;
  layout.bits = aligned ? voxelOrder : hexOrder;
  layout.cellType =
    planar ? (aligned ? VTK_PIXEL : VTK_QUAD) : (aligned ? VTK_VOXEL : VTK_HEXAHEDRON);
  if (planar)
    layout.role = { std::min(axes[0], axes[1]), std::max(axes[0], axes[1]), grid.flatAxis };
  return layout;
}

/// The RegionId of box b of an object (0: its region is removed).
std::int32_t regionIdOfBox(const ObjectBoxes& o, std::size_t b, const RegionIdList& regionIds)
{
  return regionIds[o.firstRegion + o.components.boxLabel[b] - 1];
}

/// The boxes of the kept regions. When every region is kept (no size or seed filter: the
/// default), all boxes, without the pass over every box's label and region (a maze's 4.9
/// million, where its 642,115 regions are read in a few hundred microseconds).
vtkIdType countKeptBoxes(const std::vector<ObjectBoxes>& objects, const RegionIdList& regionIds)
{
  vtkIdType count = 0;
  if (std::find(regionIds.begin(), regionIds.end(), 0) == regionIds.end())
  {
    for (const ObjectBoxes& o : objects)
      count += static_cast<vtkIdType>(o.cudb.boxes.size());
    return count;
  }
  for (const ObjectBoxes& o : objects)
    for (std::size_t b = 0; b < o.cudb.boxes.size(); ++b)
      count += regionIdOfBox(o, b, regionIds) != 0;
  return count;
}

/// Writes the Label values [begin, end) of a Label array (of the label's type), in one loop.
void fillLabels(vtkDataArray* labels,
  vtkIdType begin,
  vtkIdType end,
  const vbr::vtk::LabelValue& label)
{
  if (begin >= end)
    return;
  switch (labels->GetDataType())
  {
    vtkTemplateMacro(std::fill(static_cast<VTK_TT*>(labels->GetVoidPointer(0)) + begin,
      static_cast<VTK_TT*>(labels->GetVoidPointer(0)) + end,
      label.as<VTK_TT>()));
  }
}

/// Writes `label` at the rows of the regions of one object (ids[c] - 1 for its component c,
/// where ids[c] is not 0), in one loop of its type.
void scatterLabel(vtkDataArray* labels,
  const std::int32_t* ids,
  std::uint32_t count,
  const vbr::vtk::LabelValue& label)
{
  switch (labels->GetDataType())
  {
    vtkTemplateMacro(
      VTK_TT* out = static_cast<VTK_TT*>(labels->GetVoidPointer(0));
      const VTK_TT value = label.as<VTK_TT>();
      for (std::uint32_t c = 0; c < count; ++c) if (ids[c] != 0) out[ids[c] - 1] = value;);
  }
}

/// The corners of boxes in world coordinates, in a cell layout's order. A corner's world
/// coordinate is origin + t0 + t1 + t2, a term per image axis taken at the box's low or high
/// index: the terms are VoxelGrid::vertexToWorld's products, summed in its order (so the same
/// values where the compiler contracts neither into fused multiply-adds: x86-64 without
/// -march). The eight sums of a world axis share their partial sums (14 additions, not 24),
/// and each corner of the layout reads its sum by a fixed index (a 2D image's corners lie in
/// its plane, flat axis at lo).
struct CornerWriter
{
  const vbr::vtk::VoxelGrid& grid;
  int corners = 8;
  std::array<int, 8> sumOfCorner{}; ///< corner k: bit d of the index is "image axis d at hi"
  std::array<double, 3> base{};     ///< extentMin + vertexShift, as vertexToWorld adds them
  std::array<int, 3> source{};      ///< the processing axis of each image axis

  CornerWriter(const vbr::vtk::VoxelGrid& voxelGrid,
    const BoxCellLayout& layout,
    const std::array<int, 3>& axes)
    : grid(voxelGrid)
    , corners(layout.corners)
  {
    for (int k = 0; k < 3; ++k)
      this->source[axes[k]] = k;
    for (int k = 0; k < layout.corners; ++k)
    {
      int index = 0;
      for (int r = 0; r < 3; ++r)
        if (layout.bits[k][r])
          index |= 1 << layout.role[r];
      this->sumOfCorner[k] = index;
    }
    for (int d = 0; d < 3; ++d)
      this->base[d] = this->grid.extentMin[d] + this->grid.vertexShift[d];
  }

  /// Whether the processing axes are the image axes and corner k reads sum k (a 3D image in
  /// the default sorting, axis-aligned): write<true> then indexes nothing at run time.
  bool plain() const
  {
    for (int k = 0; k < 8; ++k)
      if (this->sumOfCorner[k] != k)
        return false;
    return this->corners == 8 && this->source == std::array<int, 3>{ 0, 1, 2 };
  }

  /// The corners of `box` (processing axes, at `offset`) into xyz (3 * corners doubles). With
  /// Plain (plain() holds), the same arithmetic with every index known at compile time: the
  /// sums stay in registers instead of being gathered through the stack by run-time indices.
  template<bool Plain>
  void write(const vbr::Box& box, const Int3& offset, double* xyz) const
  {
    double local[3][2]; // [image axis][lo, hi]
    for (int d = 0; d < 3; ++d)
    {
      const int k = Plain ? d : this->source[d];
      local[d][0] = (this->base[d] + double(box.lo[k] + offset[k])) * this->grid.spacing[d];
      local[d][1] = (this->base[d] + double(box.hi[k] + offset[k])) * this->grid.spacing[d];
    }
    double sum[3][8]; // [world axis][corner index]
    for (int w = 0; w < 3; ++w)
    {
      const double* m = &this->grid.direction[3 * w];
      for (int a = 0; a < 2; ++a)
      {
        const double s0 = this->grid.origin[w] + m[0] * local[0][a];
        for (int b = 0; b < 2; ++b)
        {
          const double s1 = s0 + m[1] * local[1][b];
          sum[w][a | b << 1] = s1 + m[2] * local[2][0];
          sum[w][a | b << 1 | 4] = s1 + m[2] * local[2][1];
        }
      }
    }
    if (Plain)
    {
      writePlain(sum, xyz);
      return;
    }
    double out[24];
    for (int k = 0; k < this->corners; ++k)
      for (int w = 0; w < 3; ++w)
        out[3 * k + w] = sum[w][this->sumOfCorner[k]];
    streamValues(out, 3 * this->corners, xyz);
  }

  /// Whether a 2D image's four corners k read sums k in its own axes (flat z, axis-aligned:
  /// the usual image), so that writePlanar indexes nothing at run time.
  bool planarPlain() const
  {
    for (int k = 0; k < 4; ++k)
      if (this->sumOfCorner[k] != k)
        return false;
    return this->corners == 4 && this->source == std::array<int, 3>{ 0, 1, 2 };
  }

  /// write<false> where planarPlain() holds: the same sums, in the same order, of the four
  /// corners in the plane only (the flat axis at lo), with every index known at compile time.
  /// The general path computed the eight corners' sums and gathered four of them through the
  /// stack by run-time indices (a maze's 4.9 million boxes: a fifth of the boxes output).
  void writePlanar(const vbr::Box& box, const Int3& offset, double* xyz) const
  {
    double local[2][2]; // [image axis][lo, hi]
    for (int d = 0; d < 2; ++d)
    {
      local[d][0] = (this->base[d] + double(box.lo[d] + offset[d])) * this->grid.spacing[d];
      local[d][1] = (this->base[d] + double(box.hi[d] + offset[d])) * this->grid.spacing[d];
    }
    const double flat = (this->base[2] + double(box.lo[2] + offset[2])) * this->grid.spacing[2];
    double out[12]; // corner k = a | b << 1 at 3 * k
    for (int w = 0; w < 3; ++w)
    {
      const double* m = &this->grid.direction[3 * w];
      const double flatTerm = m[2] * flat;
      for (int a = 0; a < 2; ++a)
      {
        const double s0 = this->grid.origin[w] + m[0] * local[0][a];
        for (int b = 0; b < 2; ++b)
          out[3 * (a | b << 1) + w] = (s0 + m[1] * local[1][b]) + flatTerm;
      }
    }
    streamValues(out, 12, xyz);
  }

  /// The eight corners k = 0..7 of sum[w][k] into xyz, pair by pair.
  static void writePlain(const double (&sum)[3][8], double* xyz)
  {
#ifdef VBR_STREAM_STORES
    for (int i = 0; i < 24; i += 2)
      _mm_stream_pd(xyz + i, _mm_set_pd(sum[(i + 1) % 3][(i + 1) / 3], sum[i % 3][i / 3]));
#else
    for (int i = 0; i < 24; ++i)
      xyz[i] = sum[i % 3][i / 3];
#endif
  }

  /// `n` (even) doubles to `to` (16-byte aligned) past the caches where SSE2 allows: the
  /// coordinates are written once, and the cache lines read in before each write (the
  /// boxes' 192 bytes are the most of port 1) were half of the memory traffic.
  static void streamValues(const double* values, int n, double* to)
  {
#ifdef VBR_STREAM_STORES
    for (int i = 0; i < n; i += 2)
      _mm_stream_pd(to + i, _mm_loadu_pd(values + i));
#else
    std::copy(values, values + n, to);
#endif
  }
};

/// The arrays of port 1 for `count` boxes, written through their raw pointers.
struct BoxCells
{
  BoxCellLayout layout;
  vtkNew<vtkDoubleArray> coordinates;
  vtkNew<vtkIdTypeArray> boxIds;
  vtkNew<vtkIntArray> regionIds;
  vtkSmartPointer<vtkDataArray> labels;

  BoxCells(const BoxCellLayout& cellLayout, vtkIdType count, int labelType)
    : layout(cellLayout)
  {
    const int corners = this->layout.corners;
    this->coordinates->SetNumberOfComponents(3);
    const double bytes = outputBytes(count, corners);
    allocateTuples({ this->coordinates }, count * corners, bytes);
    this->labels = newUnsetLabelArray(labelType, count, bytes);
    allocateTuples({ this->boxIds, this->regionIds }, count, bytes);
    this->boxIds->SetName("BoxId");
    this->regionIds->SetName("RegionId");
  }

  /// The bytes of port 1 for `count` boxes: coordinates, cell ids (32-bit), ids and labels.
  static double outputBytes(vtkIdType count, int corners)
  {
    return double(count) *
      (corners * (3 * sizeof(double) + sizeof(std::int32_t)) + sizeof(std::int32_t) +
        sizeof(vtkIdType) + sizeof(int) + 1);
  }

  /// 0, 1, ..., n - 1 into `out`, as 32-bit values past the caches where SSE2 allows (as
  /// the coordinates).
  template<typename T>
  static void writeIota(T* out, vtkIdType n)
  {
#ifdef VBR_STREAM_STORES
    if (sizeof(T) == 4 && reinterpret_cast<std::uintptr_t>(out) % 16 == 0)
    {
      __m128i values = _mm_setr_epi32(0, 1, 2, 3);
      const __m128i step = _mm_set1_epi32(4);
      vtkIdType i = 0;
      for (; i + 4 <= n; i += 4)
      {
        _mm_stream_si128(reinterpret_cast<__m128i*>(out + i), values);
        values = _mm_add_epi32(values, step);
      }
      for (; i < n; ++i)
        out[i] = static_cast<T>(i);
      _mm_sfence(); // the streamed values before anything reads them
      return;
    }
#endif
    std::iota(out, out + n, T(0));
  }

  /// Cells whose corners are their own points, in order (cell i: points corners * i to
  /// corners * i + corners - 1), with 32-bit ids when they fit: vtkCellArray reads both, and
  /// on a checkerboard (a box per voxel) the ids were a quarter of the boxes' memory.
  template<typename ArrayType>
  static vtkSmartPointer<vtkCellArray> ownCornerCells(vtkIdType count, int corners)
  {
    vtkNew<ArrayType> offsets, connectivity;
    const double bytes = outputBytes(count, corners);
    allocateTuples({ offsets }, count + 1, bytes);
    allocateTuples({ connectivity }, count * corners, bytes);
    auto* offset = offsets->GetPointer(0);
    for (vtkIdType i = 0; i <= count; ++i)
      offset[i] = static_cast<typename ArrayType::ValueType>(i * corners);
    if (count > 0)
      writeIota(connectivity->GetPointer(0), count * corners);
    auto cells = vtkSmartPointer<vtkCellArray>::New();
    cells->SetData(offsets, connectivity);
    return cells;
  }

  void moveTo(vtkUnstructuredGrid* output)
  {
    vtkNew<vtkPoints> points;
    points->SetData(this->coordinates);
    output->SetPoints(points);
    const vtkIdType count = this->boxIds->GetNumberOfTuples();
    const vtkIdType ids = count * this->layout.corners;
    output->SetCells(this->layout.cellType,
      ids <= std::numeric_limits<std::int32_t>::max()
        ? ownCornerCells<vtkTypeInt32Array>(count, this->layout.corners)
        : ownCornerCells<vtkTypeInt64Array>(count, this->layout.corners));
    vbr::vtk::reserveArrays(output->GetCellData(), 3);
    output->GetCellData()->AddArray(this->regionIds);
    output->GetCellData()->AddArray(this->boxIds);
    output->GetCellData()->AddArray(this->labels);
    output->GetCellData()->SetActiveScalars("RegionId");
  }
};

/// The kept boxes of one object into cells [cell, ...) of `cells`; returns the next cell. The
/// arrays are written through raw pointers and the object's one label in one fill: a box
/// of a porous volume is about ten voxels, and calls per box were a good part of its cost.
vtkIdType writeObjectBoxes(const ObjectBoxes& o,
  const std::int32_t* regionIdOfLabel, // by the object's labels, from 1 (at index 0)
  vtkIdType boxBase,
  const CornerWriter& corners,
  BoxCells& cells,
  vtkIdType cell)
{
  const vtkIdType first = cell;
  double* xyz = cells.coordinates->GetPointer(0) + 3 * corners.corners * cell;
  vtkIdType* boxIds = cells.boxIds->GetPointer(0);
  int* regionIds = cells.regionIds->GetPointer(0);
  const std::uint32_t* label = o.components.boxLabel.data();
  const std::vector<vbr::Box>& boxes = o.cudb.boxes;
  // writeCorners(box, xyz): one of CornerWriter's ways, chosen once per object.
  auto writeAll = [&](auto writeCorners)
  {
    for (std::size_t b = 0; b < boxes.size(); ++b)
    {
      const std::int32_t id = regionIdOfLabel[label[b] - 1];
      if (id == 0)
        continue;
      writeCorners(boxes[b], xyz);
      xyz += 3 * corners.corners;
      boxIds[cell] = boxBase + static_cast<vtkIdType>(b);
      regionIds[cell] = id;
      ++cell;
    }
  };
  const Int3& offset = o.offset;
  if (corners.plain())
    writeAll([&](const vbr::Box& box, double* to) { corners.write<true>(box, offset, to); });
  else if (corners.planarPlain())
    writeAll([&](const vbr::Box& box, double* to) { corners.writePlanar(box, offset, to); });
  else
    writeAll([&](const vbr::Box& box, double* to) { corners.write<false>(box, offset, to); });
  fillLabels(cells.labels, first, cell, o.label);
  return cell;
}

/// Port 1: the boxes of the kept regions, one voxel (or hexahedron, pixel, quad) cell each.
void writeBoxes(const std::vector<ObjectBoxes>& objects,
  const RegionIdList& regionIds,
  const vbr::vtk::VoxelGrid& grid,
  const std::array<int, 3>& axes,
  int labelType,
  vtkUnstructuredGrid* output)
{
  const BoxCellLayout layout = boxCellLayout(grid, axes);
  BoxCells cells(layout, countKeptBoxes(objects, regionIds), labelType);
  const CornerWriter corners(grid, layout, axes);
  vtkIdType cell = 0, boxBase = 0;
  for (const ObjectBoxes& o : objects)
  {
    const std::int32_t* regionIdOfLabel = regionIds.data() + o.firstRegion;
    cell = writeObjectBoxes(o, regionIdOfLabel, boxBase, corners, cells, cell);
    boxBase += static_cast<vtkIdType>(o.cudb.boxes.size());
  }
#ifdef VBR_STREAM_STORES
  _mm_sfence(); // the streamed coordinates before anything reads them
#endif
  cells.moveTo(output);
}

/// A region's row of the table from its statistics (processing axes) in the image's index and
/// world coordinates, with VoxelGrid's arithmetic in its order (the same values). Each image
/// axis reads its processing axis from the region's record (`source`): permuted copies of the
/// bounds on the stack stalled every row of a million-region table on their reloads.
struct RowTransform
{
  const vbr::vtk::VoxelGrid& grid;
  std::array<int, 3> source{}; ///< the processing axis of each image axis
  bool planar = false;

  RowTransform(const vbr::vtk::VoxelGrid& voxelGrid, const std::array<int, 3>& axes)
    : grid(voxelGrid)
    , planar(voxelGrid.flatAxis >= 0)
  {
    for (int k = 0; k < 3; ++k)
      this->source[axes[k]] = k;
    for (int d = 0; d < 3; ++d)
      this->axisTerms[d] = { this->grid.extentMin[d] + this->grid.vertexShift[d],
        this->grid.spacing[d],
        this->planar && this->source[d] == 2 };
  }

  /// The voxel index bounds (IMin, IMax, JMin, ...: first and last voxel per axis).
  void indexBounds(const RegionStats& r, std::int32_t index[6]) const
  {
    for (int d = 0; d < 3; ++d)
    {
      const int k = this->source[d];
      index[2 * d] = this->grid.extentMin[d] + r.lo[k];
      index[2 * d + 1] = this->grid.extentMin[d] + (r.hi[k] - 1); // no overflow at INT_MAX
    }
  }

  /// The world bounds: those of the corners of the index box. Each world coordinate is
  /// origin + t0 + t1 + t2 (vertexToWorld's terms, one per image axis), and a rounded sum
  /// only grows with its terms: the extreme corner takes each term at its own extreme, so two
  /// terms per axis give the bounds of the eight corners exactly (a table of 100,000 regions
  /// spent more on eight full transforms per row than on labelling). A 2D image's corners lie
  /// in its plane (worldOf's: processing axis 2 at 0).
  void worldBounds(const RegionStats& r, double world[6]) const
  {
    double low[3], high[3];
    for (int d = 0; d < 3; ++d)
    {
      const Axis a = this->axis(d);
      low[d] = localVertex(a, r.lo[this->source[d]]);
      high[d] = localVertex(a, r.hi[this->source[d]]);
    }
    for (int w = 0; w < 3; ++w)
    {
      double least = this->grid.origin[w], most = this->grid.origin[w];
      for (int d = 0; d < 3; ++d)
        addWorldTerm(this->grid.direction[3 * w + d], low[d], high[d], least, most);
      world[2 * w] = least;
      world[2 * w + 1] = most;
    }
  }

  /// The centroid in world coordinates (the mean of the voxel centres): positionToWorld's
  /// arithmetic inlined (the call was a sixth of the table of a million regions).
  void centroid(const RegionStats& r, double world[3]) const
  {
    double local[3];
    for (int d = 0; d < 3; ++d)
      local[d] = localCentre(this->axis(d),
        static_cast<double>(r.doubledCentre[this->source[d]]),
        static_cast<double>(r.voxels));
    for (int w = 0; w < 3; ++w)
      world[w] = worldPoint(this->grid.origin[w], &this->grid.direction[3 * w], local);
  }

  // The terms of the rows' coordinates, shared by the row and the block writer (the same
  // operations in the same order give the same values).

  /// What the local coordinates along one image axis take from the grid, copied once for a
  /// table (the block writer's loops copy them again: then they read no member that their
  /// stores could alias).
  struct Axis
  {
    double base; ///< extentMin + vertexShift
    double spacing;
    bool flat; ///< the flat axis of a 2D image (at 0 in its plane, worldOf's)
  };

  std::array<Axis, 3> axisTerms{}; ///< by image axis, set once for the table

  const Axis& axis(int d) const { return this->axisTerms[d]; }

  /// The local coordinate of lattice vertex `index` along axis `a` (of its processing
  /// axis), as VoxelGrid::vertexToWorld computes it before the direction matrix.
  static double localVertex(const Axis& a, std::int32_t index)
  {
    return (a.base + double(a.flat ? 0 : index)) * a.spacing;
  }

  /// The local coordinate along axis `a` of the mean of `voxels` voxel centres whose doubled
  /// indices sum to `doubled` (positionToWorld's).
  static double localCentre(const Axis& a, double doubled, double voxels)
  {
    const double centre = a.flat ? 0.0 : 0.5 * doubled / voxels;
    return (a.base + centre) * a.spacing;
  }

  /// One term of a world bound: direction entry `m` times the local coordinates `low` and
  /// `high`, the lesser added to `least` and the greater to `most`.
  static void addWorldTerm(double m, double low, double high, double& least, double& most)
  {
    const double a = m * low, b = m * high;
    least += std::min(a, b);
    most += std::max(a, b);
  }

  /// origin + m[0] local[0] + m[1] local[1] + m[2] local[2], in that order.
  static double worldPoint(double origin, const double* m, const double* local)
  {
    return origin + m[0] * local[0] + m[1] * local[1] + m[2] * local[2];
  }
};

/// The columns of port 2, sized for the kept regions, each row written once from its region's
/// statistics through raw pointers (a table of tens of thousands of regions, as noise gives,
/// filled value by value through the generic array interface cost more than its labelling).
struct RegionColumns
{
  vtkNew<vtkIntArray> ids;
  vtkSmartPointer<vtkDataArray> labels;
  vtkNew<vtkIdTypeArray> voxels, boxes;
  vtkNew<vtkDoubleArray> volumes, centroids;
  // Bounds as six columns each: a 6-component array would show a meaningless magnitude.
  // (The fixed-size classes, which the columns have always had.)
  std::array<vtkNew<vtkTypeInt32Array>, 6> indexBounds;
  std::array<vtkNew<vtkTypeFloat64Array>, 6> worldBounds;

  explicit RegionColumns(int labelType)
    : labels(vbr::vtk::newLabelArray(labelType, 0))
  {
    static const char* const indexNames[6] = { "IMin", "IMax", "JMin", "JMax", "KMin", "KMax" };
    static const char* const worldNames[6] = { "XMin", "XMax", "YMin", "YMax", "ZMin", "ZMax" };
    this->ids->SetName("RegionId");
    this->voxels->SetName("VoxelCount");
    this->volumes->SetName("Volume");
    this->centroids->SetName("Centroid");
    this->centroids->SetNumberOfComponents(3);
    this->centroids->SetComponentName(0, "X");
    this->centroids->SetComponentName(1, "Y");
    this->centroids->SetComponentName(2, "Z");
    this->boxes->SetName("NumberOfBoxes");
    for (int k = 0; k < 6; ++k)
    {
      this->indexBounds[k]->SetName(indexNames[k]);
      this->worldBounds[k]->SetName(worldNames[k]);
    }
  }

  std::vector<vtkDataArray*> all() const
  {
    std::vector<vtkDataArray*> columns{
      this->ids, this->labels, this->voxels, this->volumes, this->centroids, this->boxes
    };
    for (int k = 0; k < 6; ++k)
    {
      columns.push_back(this->indexBounds[k]);
      columns.push_back(this->worldBounds[k]);
    }
    return columns;
  }

  /// Whether only these columns hold their arrays and values (the table they were added to was
  /// released or initialized for a new update), so that they can be written again.
  bool unshared() const
  {
    for (vtkDataArray* a : this->all())
      if (!heldByTheFilterAlone(a))
        return false;
    return true;
  }

  /// Room for `count` rows, unset (memory of the last rows kept when there were as many).
  void allocate(vtkIdType count)
  {
    const std::vector<vtkDataArray*> columns = this->all();
    if (this->ids->GetNumberOfTuples() != count)
      allocateTuples(columns, count, 0.0);
    for (vtkDataArray* a : columns)
      prepareForNewValues(a); // new values: cached ranges are stale
  }

  /// Bytes of `count` rows.
  static double bytesOf(vtkIdType count, int labelType)
  {
    return double(count) *
      (4 + 8 + 8 + 8 + 24 + 6 * 4 + 6 * 8 + vtkDataArray::GetDataTypeSize(labelType));
  }

  /// Rows [0, regionOfRow.size()) (ids 1, 2, ...) from the statistics of their regions. A
  /// table larger than the last-level cache is written past the caches (streamed) in blocks of
  /// RowBlock rows: its lines were read in before each write, half of the memory traffic of the
  /// table of a million regions, which no one reads in this update.
  void write(const Regions& regions,
    const RegionList& regionOfRow,
    const vbr::vtk::VoxelGrid& grid,
    const std::array<int, 3>& axes,
    double voxelMeasure)
  {
    regions.visit([&](const auto& records)
      { this->writeRows(records, regions.z, regionOfRow, grid, axes, voxelMeasure); });
  }

  /// write of the records `regions` (of plane z when planar).
  template<typename Record>
  void writeRows(const RegionRecords<Record>& regions,
    std::int32_t z,
    const RegionList& regionOfRow,
    const vbr::vtk::VoxelGrid& grid,
    const std::array<int, 3>& axes,
    double voxelMeasure)
  {
    const Columns out = this->pointers();
    const RowWriter<Record> writer{
      regions, z, regionOfRow, RowTransform(grid, axes), voxelMeasure
    };
    const std::size_t rows = regionOfRow.size();
    std::size_t row = 0;
#ifdef VBR_ROW_BLOCKS
    if (bytesOf(static_cast<vtkIdType>(rows), VTK_CHAR) >= StreamedTableBytes && out.aligned())
    {
      RowBlock block;
      for (; row + RowBlock::Rows <= rows; row += RowBlock::Rows)
      {
        writer.fill(row, block);
        block.streamTo(out, row);
      }
#ifdef VBR_STREAM_STORES
      _mm_sfence(); // the streamed rows before anything reads them
#endif
    }
#endif
    for (; row < rows; ++row)
      writer.write(row, out, row);
  }

  /// Tables from this size (bytes of their rows) are streamed: larger than the last-level
  /// cache of the machines measured (32 MiB), where nothing written stays for the next reader.
  static constexpr double StreamedTableBytes = 32.0 * 1024.0 * 1024.0;

  /// The columns' values, but the labels' (written by scatterLabel).
  struct Columns
  {
    int* ids;
    vtkIdType* voxels;
    vtkIdType* boxes;
    double* volumes;
    double* centroids;
    std::array<std::int32_t*, 6> index;
    std::array<double*, 6> world;

    /// Whether every column begins on a cache line (allocateTuples' blocks do): whole blocks
    /// of rows are then whole lines of each column.
    bool aligned() const
    {
      std::vector<const void*> all{
        this->ids, this->voxels, this->boxes, this->volumes, this->centroids
      };
      all.insert(all.end(), this->index.begin(), this->index.end());
      all.insert(all.end(), this->world.begin(), this->world.end());
      return std::all_of(all.begin(),
        all.end(),
        [](const void* p) { return reinterpret_cast<std::uintptr_t>(p) % 64 == 0; });
    }
  };

  Columns pointers()
  {
    Columns c{ this->ids->GetPointer(0),
      this->voxels->GetPointer(0),
      this->boxes->GetPointer(0),
      this->volumes->GetPointer(0),
      this->centroids->GetPointer(0),
      {},
      {} };
    for (int k = 0; k < 6; ++k)
    {
      c.index[k] = this->indexBounds[k]->GetPointer(0);
      c.world[k] = this->worldBounds[k]->GetPointer(0);
    }
    return c;
  }

#ifdef VBR_ROW_BLOCKS
  /// Rows staged in the cache, then streamed to the columns a whole line at a time: 16 rows
  /// are one line of each 32-bit column and two of each 64-bit one.
  struct RowBlock
  {
    static constexpr std::size_t Rows = 16;
    alignas(64) int ids[Rows];
    alignas(64) vtkIdType voxels[Rows];
    alignas(64) vtkIdType boxes[Rows];
    alignas(64) double volumes[Rows];
    alignas(64) double centroids[3 * Rows];
    alignas(64) std::int32_t index[6][Rows];
    alignas(64) double world[6][Rows];

    /// `bytes` (a multiple of 16) from `from` to `to` (16-byte aligned) past the caches; a
    /// copy where stores are not streamed.
    static void stream(const void* from, void* to, std::size_t bytes)
    {
#ifdef VBR_STREAM_STORES
      const auto* source = static_cast<const __m128i*>(from);
      auto* target = static_cast<__m128i*>(to);
      for (std::size_t i = 0; i < bytes / 16; ++i)
        _mm_stream_si128(target + i, _mm_load_si128(source + i));
#else
      std::memcpy(to, from, bytes);
#endif
    }

    /// The block's rows to rows [row, row + Rows) of `out`.
    void streamTo(const Columns& out, std::size_t row) const
    {
      stream(this->ids, out.ids + row, sizeof(this->ids));
      stream(this->voxels, out.voxels + row, sizeof(this->voxels));
      stream(this->boxes, out.boxes + row, sizeof(this->boxes));
      stream(this->volumes, out.volumes + row, sizeof(this->volumes));
      stream(this->centroids, out.centroids + 3 * row, sizeof(this->centroids));
      for (int k = 0; k < 6; ++k)
      {
        stream(this->index[k], out.index[k] + row, sizeof(this->index[k]));
        stream(this->world[k], out.world[k] + row, sizeof(this->world[k]));
      }
    }
  };
#endif

  /// Writes the row of a region into columns.
  template<typename Record>
  struct RowWriter
  {
    const RegionRecords<Record>& regions;
    std::int32_t z; ///< the plane of planar records
    const RegionList& regionOfRow;
    RowTransform transform;
    double voxelMeasure;

    /// Row `row` of the table at position `at` of the columns `out`.
    void write(std::size_t row, const Columns& out, std::size_t at) const
    {
      // Rows in RegionId (size) order read the regions, in sweep order, at random: a maze's
      // 642,115 rows waited for a cache miss each, so the region of a row further on is
      // fetched ahead.
      constexpr std::size_t Ahead = 16;
      if (row + Ahead < this->regionOfRow.size())
        vbr::prefetch(&this->regions[this->regionOfRow[row + Ahead]]);
      decltype(auto) r = regionOf(this->regions[this->regionOfRow[row]], this->z);
      out.ids[at] = static_cast<int>(row + 1);
      out.voxels[at] = r.voxels;
      out.boxes[at] = r.boxes;
      out.volumes[at] = static_cast<double>(r.voxels) * this->voxelMeasure;
      std::int32_t indexBounds[6];
      this->transform.indexBounds(r, indexBounds);
      double worldBounds[6];
      this->transform.worldBounds(r, worldBounds);
      for (int k = 0; k < 6; ++k)
      {
        out.index[k][at] = indexBounds[k];
        out.world[k][at] = worldBounds[k];
      }
      this->transform.centroid(r, out.centroids + 3 * at);
    }

#ifdef VBR_ROW_BLOCKS
    /// Rows of a block (fill's, a RowBlock's).
    static constexpr std::size_t Rows = RowBlock::Rows;

    /// The records of a block's rows, by image axis.
    struct BlockRecords
    {
      alignas(64) std::int32_t lo[3][Rows], hi[3][Rows];
      alignas(64) double doubledCentre[3][Rows];
      alignas(64) double voxels[Rows];
    };

    /// The local coordinates (before the direction matrix) of a block's rows, by image axis.
    struct BlockLocals
    {
      alignas(64) double low[3][Rows], high[3][Rows], middle[3][Rows];
    };

    /// Rows [row, row + Rows) of the table into `block`, the same values as write's: the
    /// same terms (RowTransform's) in the same order. The rows' records are read first, then
    /// each column's values are computed for all the rows in one loop over arrays of the rows
    /// (GCC 12 at -O3, the Release flags, vectorizes the loops of the index bounds and of the local
    /// and the world coordinates): on a fax-like page's 278,445 rows, 28 % fewer instructions than
    /// row by row (9 % fewer for its whole update), and 10 % to 17 % less time for the update of a
    /// 128^3 checkerboard's million rows. Only for the tables streamed from RowBlock: writing the
    /// columns of a smaller table straight (or copying them from a block) took 4 % to 8 % longer
    /// than write's rows.
    void fill(std::size_t row, RowBlock& block) const
    {
      BlockRecords records;
      this->readRecords(row, records, block);
      BlockLocals locals;
      this->localCoordinates(records, locals, block);
      this->worldCoordinates(locals, block);
    }

    /// The records of rows [row, row + Rows): their counts into `block`, their bounds and
    /// centres into `records`.
    void readRecords(std::size_t row, BlockRecords& records, RowBlock& block) const
    {
      for (std::size_t i = 0; i < Rows; ++i)
      {
        // Rows in RegionId (size) order read the regions, in sweep order, at random: a
        // maze's 642,115 rows waited for a cache miss each, so the region of a row further
        // on is fetched ahead.
        constexpr std::size_t Ahead = 16;
        if (row + i + Ahead < this->regionOfRow.size())
          vbr::prefetch(&this->regions[this->regionOfRow[row + i + Ahead]]);
        decltype(auto) r = regionOf(this->regions[this->regionOfRow[row + i]], this->z);
        block.ids[i] = static_cast<int>(row + i + 1);
        block.voxels[i] = r.voxels;
        block.boxes[i] = r.boxes;
        records.voxels[i] = static_cast<double>(r.voxels);
        block.volumes[i] = records.voxels[i] * this->voxelMeasure;
        for (int d = 0; d < 3; ++d)
        {
          const int k = this->transform.source[d];
          records.lo[d][i] = r.lo[k];
          records.hi[d][i] = r.hi[k];
          records.doubledCentre[d][i] = static_cast<double>(r.doubledCentre[k]);
        }
      }
    }

    /// The index bounds into `block`, the local coordinates of the bounds and the centroids
    /// into `locals`.
    void localCoordinates(const BlockRecords& records, BlockLocals& locals, RowBlock& block) const
    {
      for (int d = 0; d < 3; ++d)
      {
        const std::int32_t first = this->transform.grid.extentMin[d];
        for (std::size_t i = 0; i < Rows; ++i)
        {
          block.index[2 * d][i] = first + records.lo[d][i];
          block.index[2 * d + 1][i] = first + (records.hi[d][i] - 1); // no overflow at INT_MAX
        }
        const RowTransform::Axis a = this->transform.axis(d);
        for (std::size_t i = 0; i < Rows; ++i)
        {
          locals.low[d][i] = RowTransform::localVertex(a, records.lo[d][i]);
          locals.high[d][i] = RowTransform::localVertex(a, records.hi[d][i]);
          locals.middle[d][i] =
            RowTransform::localCentre(a, records.doubledCentre[d][i], records.voxels[i]);
        }
      }
    }

    /// The world bounds and centroids into `block` from the local coordinates.
    void worldCoordinates(const BlockLocals& locals, RowBlock& block) const
    {
      for (int w = 0; w < 3; ++w)
      {
        // Copies: the block's stores could otherwise alias the grid's values.
        const double origin = this->transform.grid.origin[w];
        const double m[3] = { this->transform.grid.direction[3 * w],
          this->transform.grid.direction[3 * w + 1],
          this->transform.grid.direction[3 * w + 2] };
        for (std::size_t i = 0; i < Rows; ++i)
        {
          double least = origin, most = origin;
          for (int d = 0; d < 3; ++d)
            RowTransform::addWorldTerm(m[d], locals.low[d][i], locals.high[d][i], least, most);
          block.world[2 * w][i] = least;
          block.world[2 * w + 1][i] = most;
          const double middle[3] = {
            locals.middle[0][i], locals.middle[1][i], locals.middle[2][i]
          };
          block.centroids[3 * i + w] = RowTransform::worldPoint(origin, m, middle);
        }
      }
    }
#endif
  };

  void addTo(vtkTable* table)
  {
    vbr::vtk::reserveArrays(table->GetRowData(), 18);
    table->AddColumn(this->ids);
    table->AddColumn(this->labels);
    table->AddColumn(this->voxels);
    table->AddColumn(this->volumes);
    for (vtkTypeInt32Array* a : this->indexBounds)
      table->AddColumn(a);
    for (vtkTypeFloat64Array* a : this->worldBounds)
      table->AddColumn(a);
    table->AddColumn(this->centroids);
    table->AddColumn(this->boxes);
  }
};

/// Tables up to this size keep their columns for the next update: making, naming, adding and
/// releasing 18 arrays was a tenth of an update of a small image (a few hundred rows). Larger
/// ones are not held past their update (their memory goes back to the cache of blocks).
constexpr double KeptTableBytes = 1024.0 * 1024.0;

/// Port 2: one row per kept region, in RegionId order, from the regions' statistics. The
/// columns are those of `kept` when only it still holds them and their label type fits; a small
/// table's columns are left in `kept` for the next update.
void writeRegionTable(const std::vector<ObjectBoxes>& objects,
  const Regions& regions,
  const RegionIdList& regionIds,
  const RegionList& regionOfRow,
  const vbr::vtk::VoxelGrid& grid,
  const std::array<int, 3>& axes,
  int labelType,
  vtkTable* table,
  std::unique_ptr<RegionColumns>& kept)
{
  std::unique_ptr<RegionColumns> columns;
  if (kept && kept->labels->GetDataType() == labelType && kept->unshared())
    columns = std::move(kept);
  else
    columns = std::make_unique<RegionColumns>(labelType);
  kept.reset();
  const auto rows = static_cast<vtkIdType>(regionOfRow.size());
  columns->allocate(rows);
  for (const ObjectBoxes& o : objects)
    scatterLabel(columns->labels, regionIds.data() + o.firstRegion, o.componentCount(), o.label);
  columns->write(regions, regionOfRow, grid, axes, voxelMeasure(grid));
  columns->addTo(table);
  if (RegionColumns::bytesOf(rows, labelType) <= KeptTableBytes)
    kept = std::move(columns);
}

/// The data objects of the filter's ports.
struct Ports
{
  vtkImageData* input;
  vtkDataSet* seeds; ///< null without seeds
  vtkImageData* output;
  vtkUnstructuredGrid* boxes;
  vtkTable* table;

  Ports(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
    : input(vtkImageData::GetData(inputVector[0]))
    , seeds(vtkDataSet::GetData(inputVector[1]))
    , output(vtkImageData::GetData(outputVector, 0))
    , boxes(vtkUnstructuredGrid::GetData(outputVector, 1))
    , table(vtkTable::GetData(outputVector, 2))
  {
  }
};

/// Summary written to the field data of every output.
struct Summary
{
  vtkIdType regions = 0, components = 0, boxes = 0, oudbBoxes = 0, extremeVertices = 0;
  std::vector<std::string> sortings;

  /// Counts an object's boxes and extreme vertices, and the sorting its boxes were built in.
  void add(const ObjectBoxes& o, const std::string& sorting)
  {
    this->boxes += static_cast<vtkIdType>(o.boxCount());
    this->oudbBoxes += static_cast<vtkIdType>(o.oudbBoxCount());
    this->extremeVertices += static_cast<vtkIdType>(o.extremeVertices);
    if (std::find(this->sortings.begin(), this->sortings.end(), sorting) == this->sortings.end())
      this->sortings.push_back(sorting);
  }

  /// The summary's field arrays. Every port gets the same arrays: making, naming, adding and
  /// later releasing each small array was a large part of an update of a small image. So the
  /// arrays of the last update (`kept`) are written again when nothing but `kept` holds them
  /// (the ports they were added to were initialized for this update).
  std::vector<vtkSmartPointer<vtkAbstractArray>> fieldArrays(
    const std::vector<vtkSmartPointer<vtkAbstractArray>>& kept) const
  {
    const std::pair<const char*, vtkIdType> values[] = { { "NumberOfRegions", this->regions },
      { "NumberOfComponents", this->components },
      { "NumberOfBoxes", this->boxes },
      { "NumberOfOUDBBoxes", this->oudbBoxes },
      { "NumberOfExtremeVertices", this->extremeVertices } };
    constexpr std::size_t Count = sizeof(values) / sizeof(values[0]) + 1;
    bool reuse = kept.size() == Count;
    for (std::size_t k = 0; reuse && k < Count; ++k)
      reuse = heldByTheFilterAlone(kept[k]);
    std::vector<vtkSmartPointer<vtkAbstractArray>> arrays;
    for (std::size_t k = 0; k + 1 < Count; ++k)
    {
      vtkSmartPointer<vtkIdTypeArray> a = reuse
        ? vtkSmartPointer<vtkIdTypeArray>(vtkIdTypeArray::SafeDownCast(kept[k]))
        : vtkSmartPointer<vtkIdTypeArray>::New();
      a->SetName(values[k].first);
      a->SetNumberOfValues(1);
      a->SetValue(0, values[k].second);
      prepareForNewValues(a);
      arrays.emplace_back(a);
    }
    vtkSmartPointer<vtkStringArray> s = reuse
      ? vtkSmartPointer<vtkStringArray>(vtkStringArray::SafeDownCast(kept.back()))
      : vtkSmartPointer<vtkStringArray>::New();
    s->SetName("SortingOrder");
    s->SetNumberOfValues(static_cast<vtkIdType>(this->sortings.size()));
    for (std::size_t k = 0; k < this->sortings.size(); ++k)
      s->SetValue(static_cast<vtkIdType>(k), this->sortings[k]);
    prepareForNewValues(s);
    arrays.emplace_back(s);
    return arrays;
  }
};

/// Name of a sorting given in processing axes, in the image's axes.
std::string sortingName(const vbr::AxisOrder& order, const std::array<int, 3>& axes, bool planar)
{
  vbr::AxisOrder image{ axes[order[0]], axes[order[1]], axes[order[2]] };
  const std::string name = vbr::axisOrderName(image);
  return planar ? name.substr(1) : name; // 2D: lines along B, rows along C
}

/// The memory of the 2D sweep of an image's only object kept from one update to the next (part
/// of RunMemory, bounded with it): its boxes, their labels, its runs and its union-find, handed
/// back to vbr::buildCUDBComponents2D and vbr::labelPixelRuns, which write into them. New
/// blocks were faulted in and zeroed by the kernel at every update: a 6001^2 maze's 190 MB, a
/// fifth of its update with the boxes output.
struct PlanarMemory
{
  std::vector<vbr::Box> boxes;
  std::vector<std::uint32_t> boxLabel;
  vbr::PixelRuns runs;
  std::vector<std::uint32_t> equivalences;

  /// Takes the vectors of `o`, the update's only object, for the next update; frees them
  /// all when they hold more than MostSpareFactor times what this update used (an image
  /// of far fewer boxes or runs than an earlier one).
  void keep(ObjectBoxes& o)
  {
    this->boxes = std::move(o.cudb.boxes);
    this->boxLabel = std::move(o.components.boxLabel);
    this->runs = std::move(o.runs);
    if (this->bytes() > MostSpareFactor * this->usedBytes())
      *this = PlanarMemory();
  }

  /// Hands the kept vectors to a sweep's outputs, with their values: a sweep replaces them;
  /// a caller that does not write one clears it.
  void lend(vbr::CUDB& cudb, vbr::Components& components, vbr::PixelRuns& pixelRuns)
  {
    cudb.boxes = std::move(this->boxes);
    components.boxLabel = std::move(this->boxLabel);
    pixelRuns = std::move(this->runs);
  }

  std::size_t bytes() const
  {
    return this->boxes.capacity() * sizeof(vbr::Box) +
      (this->boxLabel.capacity() + this->runs.boxes.capacity() + this->equivalences.capacity()) *
      sizeof(std::uint32_t) +
      this->runs.rowStarts.capacity() * sizeof(std::size_t);
  }

  /// bytes() of the values the last sweep wrote.
  std::size_t usedBytes() const
  {
    return this->boxes.size() * sizeof(vbr::Box) +
      (this->boxLabel.size() + this->runs.boxes.size() + this->equivalences.size()) *
      sizeof(std::uint32_t) +
      this->runs.rowStarts.size() * sizeof(std::size_t);
  }

  static constexpr std::size_t MostSpareFactor = 4;
};

/// The CUDB of a 2D object in the candidate sorting with the fewest boxes (the first of
/// equals, as buildBestCUDB), and the components of its boxes, straight from the pixel rows
/// (of the transposed pixels for lines along the first in-plane axis): the same boxes, counts
/// and components as through its EVM, without the EVM. False when empty or aborted. With
/// `keepRuns` (the image's only object: only then are RegionIds painted from the runs) an
/// object swept along its rows keeps its pixels and runs; others free them at once, as a
/// label image of many objects would otherwise hold a bit image per label. `pixels` are the
/// object's, selected already (progress 0 to 0.1 of `exec`). With `memory`, the first sorting
/// is swept in its vectors.
bool boxesOfPixels(vbr::BitVolume pixels,
  const std::vector<vbr::AxisOrder>& sortings,
  vbr::Connectivity connectivity,
  bool keepRuns,
  const vbr::Execution& exec,
  PlanarMemory* memory,
  ObjectBoxes& o)
{
  vtkLogScopeF(TRACE, "the 2D CUDB of the pixels and its components");
  bool found = false;
  const double step = 0.9 / static_cast<double>(sortings.size());
  for (std::size_t k = 0; k < sortings.size(); ++k)
  {
    const double from = 0.1 + step * static_cast<double>(k);
    vbr::CUDB cudb;
    vbr::Components labelled;
    std::size_t vertices = 0;
    vbr::PixelRuns runs; // rows along processing x: painted from the runs
    const bool alongRows = keepRuns && sortings[k] == vbr::AxisOrder{ 2, 1, 0 };
    if (memory && k == 0)
      memory->lend(cudb, labelled, runs);
    if (!vbr::buildCUDBComponents2D(pixels,
          sortings[k],
          connectivity,
          exec.within(from, from + step),
          cudb,
          labelled,
          &vertices,
          alongRows ? &runs : nullptr,
          memory ? &memory->equivalences : nullptr))
      return false;
    if (!alongRows)
      runs = vbr::PixelRuns(); // not kept with the object
    if (!found || cudb.boxes.size() < o.cudb.boxes.size())
    {
      o.cudb = std::move(cudb);
      o.components = std::move(labelled);
      o.extremeVertices = vertices;
      o.runs = std::move(runs);
    }
    found = true;
  }
  if (!o.runs.empty())
    o.pixels = std::move(pixels);
  return !o.cudb.boxes.empty();
}

/// boxesOfPixels of the object's pixels, selected here.
bool boxesOfPixelRows(const vbr::vtk::Selected& selected,
  const std::vector<vbr::AxisOrder>& sortings,
  vbr::Connectivity connectivity,
  bool keepRuns,
  const vbr::Execution& exec,
  PlanarMemory* memory,
  ObjectBoxes& o)
{
  vtkLogScopeF(TRACE, "select pixels");
  return boxesOfPixels(
    selected.select(exec.within(0.0, 0.1)), sortings, connectivity, keepRuns, exec, memory, o);
}

/// The components of a 2D object labelled on the runs of its rows, the image's only object,
/// swept along its rows (ZYX) and without the boxes output: the counts of its CUDB, and its
/// pixels and runs, from which its regions are measured and its RegionIds painted. With fewer
/// than `minimumRuns` runs, from its boxes (boxesOfPixels): measuring a region per box is
/// cheaper than per run, and the run route only gains where the boxes are many (a maze's 4.9
/// million boxes, 117 MB, were written and faulted in for nothing). False when the object is
/// empty or the work was aborted.
bool labelObjectPixelRuns(const vbr::vtk::Selected& selected,
  vbr::Connectivity connectivity,
  vtkIdType minimumRuns,
  const vbr::Execution& exec,
  PlanarMemory* memory,
  ObjectBoxes& o)
{
  vtkLogScopeF(TRACE, "select pixels and label the runs of their rows");
  o.pixels = selected.select(exec.within(0.0, 0.1));
  // A row of n pixels has at most (n + 1) / 2 runs: below the threshold whatever the pixels,
  // they need not be counted (a scan of every row of a fax page).
  const std::uint64_t mostRuns =
    std::uint64_t(o.pixels.size(1)) * ((std::uint64_t(o.pixels.size(0)) + 1) / 2);
  if (mostRuns < static_cast<std::uint64_t>(minimumRuns) ||
    vbr::countPixelRuns(o.pixels) < static_cast<std::uint64_t>(minimumRuns))
    return boxesOfPixels(
      std::move(o.pixels), { vbr::AxisOrder{ 2, 1, 0 } }, connectivity, true, exec, memory, o);
  vbr::PixelRunComponents labelled;
  vbr::CUDB noBoxes;
  if (memory)
  {
    memory->lend(noBoxes, labelled.components, labelled.runs);
    noBoxes.boxes.clear(); // lent with the last update's boxes: only its capacity is wanted
  }
  if (!vbr::labelPixelRuns(o.pixels,
        connectivity,
        exec.within(0.1, 1.0),
        labelled,
        memory ? &memory->equivalences : nullptr) ||
    labelled.boxCount() == 0)
    return false;
  o.cudb.boxes = std::move(noBoxes.boxes); // empty (cleared), its capacity kept for the next
  o.labelledFromPixelRuns = true;
  o.runs = std::move(labelled.runs);
  o.components = std::move(labelled.components);
  o.extremeVertices = labelled.extremeVertices;
  o.cudb.dimension = 2;
  o.cudb.order = vbr::AxisOrder{ 2, 1, 0 };
  o.cudb.oudbBoxCount = labelled.oudbBoxCount;
  return true;
}

/// The labelling's memory a filter keeps from one update to the next: of a 3D image, the runs
/// and their labels of its only object and the union-find and notes of every object; of a 2D
/// image's only object, its sweep's vectors (PlanarMemory, about 190 MB for a 6001^2 maze).
/// The next update of as many runs or boxes or fewer writes into it, where new blocks were
/// faulted in and zeroed by the kernel at every update (glibc had returned them): on a 128^3
/// checkerboard, 29 MB and 2,793 page faults an update, 256 with it kept. Kept between updates
/// too (the price: the filter holds it while idle) when all of it is within KeptBytes, else
/// all freed at the end of the update; freed at the end of every update when the filter
/// releases its data after use (ReleaseDataFlag), and with the filter.
struct RunMemory
{
  static constexpr std::size_t KeptBytes = std::size_t(512) << 20;
  vbr::VoxelRuns voxelRuns;
  vbr::RunComponents runComponents;
  vbr::RunLabellingScratch scratch;
  PlanarMemory planar;

  /// Takes the runs and labels of `o`, the update's only object, for the next update, or
  /// frees them with the scratch when they are more than KeptBytes together.
  void keep(ObjectBoxes& o)
  {
    this->voxelRuns = std::move(o.voxelRuns);
    this->runComponents = std::move(o.runComponents);
    this->limit();
  }

  /// Frees everything when more than KeptBytes is held.
  void limit()
  {
    const std::size_t bytes = this->scratch.bytes() + this->planar.bytes() +
      this->voxelRuns.runs.capacity() * sizeof(vbr::VoxelRun) +
      this->voxelRuns.rowStarts.capacity() * sizeof(std::uint32_t) +
      this->runComponents.runLabel.capacity() * sizeof(std::uint32_t) +
      this->runComponents.beginsBox.capacity();
    if (bytes > KeptBytes)
      *this = RunMemory();
  }
};

/// Bounds the run labelling's memory kept past an update whatever its exit (an abort, a
/// distributed run, an error, an exception): within RunMemory::KeptBytes, and nothing at all
/// when the filter releases its data after use (ReleaseDataFlag).
class KeptRunsBound
{
public:
  KeptRunsBound(RunMemory& runs, bool releaseAll)
    : Runs(runs)
    , ReleaseAll(releaseAll)
  {
  }
  KeptRunsBound(const KeptRunsBound&) = delete;
  KeptRunsBound& operator=(const KeptRunsBound&) = delete;
  ~KeptRunsBound()
  {
    if (this->ReleaseAll)
      this->Runs = RunMemory();
    else
      this->Runs.limit();
  }

private:
  RunMemory& Runs;
  const bool ReleaseAll;
};

/// The components of a 3D object labelled on the runs of its rows, with the counts of the CUDB
/// in the ZYX sorting and, `withBoxes`, its boxes and their labels (moved where the sweep would
/// have put them); false when the object is empty or the work was aborted. With `memory`, the
/// scratch of the labelling comes from it and stays there, and the image's only object
/// (`onlyObject`) writes its runs and labels into the vectors kept there.
bool labelObjectRuns(const vbr::vtk::Selected& selected,
  vbr::Connectivity connectivity,
  bool withBoxes,
  bool onlyObject,
  const vbr::Execution& exec,
  RunMemory* memory,
  ObjectBoxes& o)
{
  vtkLogScopeF(TRACE, "select voxels and label the runs of their rows");
  const vbr::BitVolume voxels = selected.select(exec.within(0.0, 0.2));
  if (memory && onlyObject)
  {
    o.voxelRuns = std::move(memory->voxelRuns);
    o.runComponents = std::move(memory->runComponents);
  }
  if (!vbr::extractRuns(voxels, exec.within(0.2, 0.3), o.voxelRuns) || o.voxelRuns.empty())
    return false;
  vbr::RunComponents& c = o.runComponents;
  if (!vbr::labelRuns(voxels,
        o.voxelRuns,
        connectivity,
        exec.within(0.3, 1.0),
        c,
        withBoxes,
        memory ? &memory->scratch : nullptr))
    return false;
  o.labelledFromRuns = true;
  o.extremeVertices = c.extremeVertices;
  o.cudb.order = vbr::AxisOrder{ 2, 1, 0 };
  o.cudb.oudbBoxCount = c.oudbBoxCount;
  o.cudb.boxes = std::move(c.boxes);
  o.components.boxLabel = std::move(c.boxLabel);
  o.components.count = c.count;
  return true;
}

/// How the objects of an image are labelled (see buildObjectBoxes).
struct Route
{
  bool planar = false;     ///< a 2D image
  bool onlyObject = false; ///< the image's only object
  bool fromRuns = false;   ///< on the runs of the rows
  bool withBoxes = false;  ///< the boxes are output
  vtkIdType minimumPixelRuns = 0;
};

/// The CUDB of one object and the components of its boxes (or, from runs, the components of
/// the runs of its rows and the CUDB's counts); false when the object is empty or the work was
/// aborted. Its voxels live only while its EVM is built.
bool boxesOfObject(const vbr::vtk::Selected& selected,
  const std::vector<vbr::AxisOrder>& sortings,
  vbr::Connectivity connectivity,
  const Route& route,
  const vbr::Execution& exec,
  RunMemory* memory,
  ObjectBoxes& o)
{
  o.label = selected.label;
  o.offset = selected.offset;
  PlanarMemory* const planar = memory && route.onlyObject ? &memory->planar : nullptr;
  if (route.fromRuns && route.planar)
    return labelObjectPixelRuns(selected, connectivity, route.minimumPixelRuns, exec, planar, o);
  if (route.fromRuns)
    return labelObjectRuns(
      selected, connectivity, route.withBoxes, route.onlyObject, exec, memory, o);
  if (route.planar)
    return boxesOfPixelRows(selected, sortings, connectivity, route.onlyObject, exec, planar, o);
  vbr::EVM evm;
  {
    vtkLogScopeF(TRACE, "select voxels and extract the EVM");
    const vbr::BitVolume voxels = selected.select(exec);
    evm = vbr::extractEVM(voxels, exec);
  }
  if (evm.empty())
    return false;
  {
    vtkLogScopeF(TRACE, "EVM to CUDB and the connected components of the boxes");
    if (!buildBestCUDB(evm, sortings, connectivity, exec, o.cudb, o.components))
      return false;
  }
  o.extremeVertices = evm.size();
  return true;
}

/// PASS 1 of the filter: the boxes and components of every selected object, in order; returns
/// the number of components (regions) of all objects.
std::uint32_t buildObjectBoxes(vtkCUDBConnectivity* self,
  const vbr::vtk::InputObjects& in,
  std::vector<ObjectBoxes>& objects,
  Summary& summary,
  RunMemory* memory)
{
  const bool planar = in.grid.flatAxis >= 0;
  const std::vector<vbr::AxisOrder> sortings =
    candidateSortings(self->GetSortingOrder(), planar, in.axes);
  const vbr::Connectivity connectivity = self->GetConnectivity() == vtkCUDBConnectivity::VERTEX
    ? vbr::Connectivity::Vertex
    : vbr::Connectivity::Face;
  // On one rank (several exchange the boxes of their sweeps), the ZYX CUDB is fixed by the
  // voxels: the runs of the rows give its counts, its boxes and the components, faster (a box
  // of a porous volume is barely larger than a run). A 2D image's sweep reads the runs of its
  // rows already and its boxes are the chains of equal runs: without the boxes output, the
  // image's only object, rows along the image's x (painted from the runs), keeps the sweep's
  // labelling and, with many runs, measures its regions from the runs instead of writing its
  // boxes.
  const std::size_t n = in.objects.size();
  Route route;
  route.planar = planar;
  route.onlyObject = n == 1;
  route.withBoxes = self->GetGenerateBoxes();
  route.minimumPixelRuns = self->GetMinimumPixelRuns();
  const bool zyx = self->GetRunLabelling() && !in.piece.distributed() && sortings.size() == 1 &&
    sortings[0] == vbr::AxisOrder{ 2, 1, 0 };
  route.fromRuns = zyx &&
    (planar ? !route.withBoxes && n == 1 && in.axes[0] == 0
            : in.axes == std::array<int, 3>{ 0, 1, 2 });
  std::uint32_t regionCount = 0;
  for (std::size_t i = 0; i < n && !self->GetAbortExecute(); ++i)
  {
    const vbr::Execution exec =
      vbr::vtk::makeExecution(self, 0.05 + 0.65 * i / n, 0.05 + 0.65 * (i + 1) / n);
    ObjectBoxes o;
    if (!boxesOfObject(in.objects[i], sortings, connectivity, route, exec, memory, o))
      continue; // empty, or aborted
    o.firstRegion = regionCount;
    regionCount += o.componentCount();
    summary.add(o, sortingName(o.cudb.order, in.axes, planar));
    objects.push_back(std::move(o));
    self->UpdateProgress(0.05 + 0.65 * (i + 1) / n);
  }
  return regionCount;
}

/// Marks the regions that hold a seed, from the image of region numbers painted for them
/// (returned, to be renumbered; null when aborted), with a warning when no seed lies on a
/// selected voxel.
vtkSmartPointer<vtkIntArray> markRegionsOfSeeds(vtkCUDBConnectivity* self,
  vtkDataSet* seeds,
  const vbr::vtk::InputObjects& in,
  const std::vector<ObjectBoxes>& objects,
  Regions& regions)
{
  vtkLogScopeF(TRACE, "regions of the seeds");
  vtkSmartPointer<vtkIntArray> ids =
    paintRegions(objects, nullptr, in.grid, in.axes, vbr::vtk::makeExecution(self, 0.7, 0.8));
  if (ids && markSeeds(seeds, in.grid, ids->GetPointer(0), regions) == 0 && regions.size() > 0)
  {
    vtkWarningWithObjectMacro(self,
      << "None of the " << seeds->GetNumberOfPoints()
      << " seed points lies on a selected voxel: every region is removed.");
  }
  return ids;
}

/// An aborted run writes no labels: the input's arrays, passed on, are removed too.
void clearLabels(vtkImageData* output)
{
  output->GetPointData()->Initialize();
  output->GetCellData()->Initialize();
}

/// The RegionId array on the output image, with the association of the selected scalars.
void addRegionIds(vtkImageData* output, vtkIntArray* ids, bool cellData)
{
  vtkDataSetAttributes* attributes = cellData
    ? static_cast<vtkDataSetAttributes*>(output->GetCellData())
    : static_cast<vtkDataSetAttributes*>(output->GetPointData());
  attributes->AddArray(ids);
  attributes->SetActiveScalars("RegionId");
}

/// Rank 0: the kept boxes of all objects as [lo, hi (image axes, whole-grid voxels), RegionId]
/// per box; [-1] when aborted.
std::vector<long long> keptBoxValues(const std::vector<ObjectBoxes>& objects,
  const RegionIdList& regionIds,
  const std::array<int, 3>& axes,
  bool aborted)
{
  if (aborted)
    return { -1 };
  std::vector<long long> values;
  for (const ObjectBoxes& o : objects)
    for (std::size_t b = 0; b < o.cudb.boxes.size(); ++b)
    {
      const std::int32_t id = regionIdOfBox(o, b, regionIds);
      if (id == 0)
        continue;
      Int3 lo = o.cudb.boxes[b].lo, hi = o.cudb.boxes[b].hi;
      for (int d = 0; d < 3; ++d)
        lo[d] += o.offset[d], hi[d] += o.offset[d];
      for (const Int3& corner : { toImageAxes(lo, axes), toImageAxes(hi, axes) })
        values.insert(values.end(), corner.begin(), corner.end());
      values.push_back(id);
    }
  return values;
}

/// Under MPI, every rank: the RegionIds of its own piece (ghost voxels included) from the
/// kept boxes rank 0 broadcasts. Null when rank 0 aborted or the exchange failed.
vtkSmartPointer<vtkIntArray> paintPieceFromBoxes(vbr::vtk::Piece& piece,
  const vbr::vtk::VoxelGrid& pieceGrid,
  std::vector<long long> values)
{
  if (!vbr::vtk::broadcastValues(piece, values) || (values.size() == 1 && values[0] < 0))
    return nullptr;
  const std::array<std::int32_t, 3>& n = pieceGrid.dims;
  vtkSmartPointer<vtkIntArray> ids = vbr::vtk::newZeroedIntArray(vtkIdType(n[0]) * n[1] * n[2]);
  ids->SetName("RegionId");
  std::int32_t* out = ids->GetPointer(0);
  for (std::size_t at = 0; at + 6 < values.size(); at += 7)
  {
    std::array<long long, 3> lo, hi; // clipped to the piece, piece voxels
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::max<long long>(values[at + d] - piece.offset[d], 0);
      hi[d] = std::min<long long>(values[at + 3 + d] - piece.offset[d], n[d]);
    }
    for (long long z = lo[2]; z < hi[2]; ++z)
      for (long long y = lo[1]; y < hi[1]; ++y)
        if (lo[0] < hi[0])
          std::fill(out + (z * n[1] + y) * n[0] + lo[0],
            out + (z * n[1] + y) * n[0] + hi[0],
            static_cast<std::int32_t>(values[at + 6]));
  }
  return ids;
}

/// PASS 2 of the filter: the regions measured (`regions`, with their table's statistics),
/// those with a seed marked (`painted`, when given, keeps the image of region numbers the
/// seeds were read from), filtered and numbered: `regionIds` has the RegionId of every region
/// (0 when removed), `regionOfRow` the region of each RegionId. Returns how many are kept.
std::int32_t numberAllRegions(vtkCUDBConnectivity* self,
  vtkDataSet* seeds,
  const vbr::vtk::InputObjects& in,
  const std::vector<ObjectBoxes>& objects,
  std::uint32_t regionCount,
  Regions& regions,
  RegionIdList& regionIds,
  RegionList& regionOfRow,
  Summary& summary,
  vtkSmartPointer<vtkIntArray>* painted)
{
  regions = vbr::measureRegions(objects, regionCount, in.grid.dims, in.grid.flatAxis);
  if (seeds)
  {
    vtkSmartPointer<vtkIntArray> ids = markRegionsOfSeeds(self, seeds, in, objects, regions);
    if (painted)
      *painted = ids;
  }
  const std::int32_t kept = vbr::numberRegions(regions,
    self->GetMinimumRegionSize(),
    seeds != nullptr,
    self->GetLargestRegions(),
    self->GetRegionOrdering() == vtkCUDBConnectivity::SWEEP_ORDER ? vbr::RegionOrder::BySweep
                                                                  : vbr::RegionOrder::BySize,
    regionIds,
    regionOfRow);
  summary.components = static_cast<vtkIdType>(regionCount);
  summary.regions = kept;
  return kept;
}

} // namespace

/// The arrays of the last update's small outputs that the filter writes again when no one
/// else holds them (writeRegionTable, Summary::fieldArrays).
struct vtkCUDBConnectivityKept
{
  std::unique_ptr<RegionColumns> columns;
  std::vector<vtkSmartPointer<vtkAbstractArray>> fields;
  vtkSmartPointer<vtkIntArray> regionIds; ///< a small RegionId image (paintRegions)
  RunMemory runs;                         ///< the run labelling's memory
  ReleaseWindow window;                   ///< open while the pipeline releases the outputs
  bool planarRecords = false;             ///< whether the last update used PlanarRegion
};

namespace
{

/// Ports 1 and 2 (the boxes, the region table) and the summary on every port.
void writeBoxesAndTable(vtkCUDBConnectivity* self,
  const vbr::vtk::InputObjects& in,
  const std::vector<ObjectBoxes>& objects,
  const Regions& regions,
  const RegionIdList& regionIds,
  const RegionList& regionOfRow,
  const Summary& summary,
  const Ports& ports,
  vtkCUDBConnectivityKept& kept)
{
  vtkLogScopeF(TRACE, "boxes and region table");
  if (self->GetGenerateBoxes())
    writeBoxes(objects, regionIds, in.grid, in.axes, in.labelType, ports.boxes);
  writeRegionTable(objects,
    regions,
    regionIds,
    regionOfRow,
    in.grid,
    in.axes,
    in.labelType,
    ports.table,
    kept.columns);
  const std::vector<vtkSmartPointer<vtkAbstractArray>> fields = summary.fieldArrays(kept.fields);
  kept.fields = fields;
  for (vtkDataObject* port :
    std::initializer_list<vtkDataObject*>{ ports.output, ports.boxes, ports.table })
  {
    vtkFieldData* fd = port->GetFieldData();
    vbr::vtk::reserveArrays(fd, static_cast<int>(fields.size()));
    for (vtkAbstractArray* a : fields)
      fd->AddArray(a);
    vbr::vtk::addDistributionFields(fd, in.piece);
  }
}

/// Under MPI (passes 2 and 3): rank 0 numbers the regions of the whole image (the seeds of
/// every rank gathered) and writes the boxes and the region table; every rank writes the
/// RegionIds of its own piece from the kept boxes. False when the exchange failed.
bool writeDistributed(vtkCUDBConnectivity* self,
  vbr::vtk::InputObjects& in,
  const std::vector<ObjectBoxes>& objects,
  std::uint32_t regionCount,
  Summary& summary,
  const Ports& ports,
  vtkCUDBConnectivityKept& kept)
{
  vbr::vtk::Piece& piece = in.piece;
  vtkSmartPointer<vtkDataSet> seeds =
    ports.seeds ? vbr::vtk::gatherPoints(piece, ports.seeds) : nullptr;
  const bool first = piece.rank == 0, aborted = first && self->GetAbortExecute();
  Regions regions;
  RegionIdList regionIds;
  RegionList regionOfRow;
  if (first && !aborted)
    numberAllRegions(
      self, seeds, in, objects, regionCount, regions, regionIds, regionOfRow, summary, nullptr);
  kept.planarRecords = regions.isPlanar();
  vtkSmartPointer<vtkIntArray> ids = paintPieceFromBoxes(piece,
    piece.local,
    first ? keptBoxValues(objects, regionIds, in.axes, aborted) : std::vector<long long>());
  if (!ids)
  {
    ports.output->GetPointData()->Initialize(); // aborted: no labels
    ports.output->GetCellData()->Initialize();
    return aborted;
  }
  addRegionIds(ports.output, ids, piece.local.cellData);
  if (!first)
    return true;
  writeBoxesAndTable(self, in, objects, regions, regionIds, regionOfRow, summary, ports, kept);
  return true;
}

} // namespace

//------------------------------------------------------------------------------
vtkCUDBConnectivity::vtkCUDBConnectivity()
  : Kept(new vtkCUDBConnectivityKept)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, vtkDataSetAttributes::SCALARS);
  this->SetProgressText("CUDB Connectivity");
  blockCache().addUser(1);
}

//------------------------------------------------------------------------------
vtkCUDBConnectivity::~vtkCUDBConnectivity()
{
  delete this->Kept; // before the cache of blocks its arrays may come from is freed
  blockCache().addUser(-1);
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::FillOutputPortInformation(int port, vtkInformation* info)
{
  const char* types[] = { "vtkImageData", "vtkUnstructuredGrid", "vtkTable" };
  info->Set(vtkDataObject::DATA_TYPE_NAME(), types[port]);
  return 1;
}

//------------------------------------------------------------------------------
void vtkCUDBConnectivity::SetSeedConnection(vtkAlgorithmOutput* port)
{
  this->SetInputConnection(1, port);
}

vtkAlgorithmOutput* vtkCUDBConnectivity::GetSeedConnection()
{
  return this->GetNumberOfInputConnections(1) > 0 ? this->GetInputConnection(1, 0) : nullptr;
}

void vtkCUDBConnectivity::SetSeedData(vtkDataSet* seeds)
{
  this->SetInputDataObject(1, seeds);
}

vtkUnstructuredGrid* vtkCUDBConnectivity::GetBoxesOutput()
{
  return vtkUnstructuredGrid::SafeDownCast(this->GetOutputDataObject(1));
}

vtkTable* vtkCUDBConnectivity::GetRegionsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(2));
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // Port 0 inherits the image's extent, origin and spacing (copied by the executive); the
  // boxes and the table are not structured.
  vbr::vtk::removeImageInformation(outputVector, 1);
  vbr::vtk::removeImageInformation(outputVector, 2);
  return 1;
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::RequestUpdateExtent(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // Components are global: the whole image is needed whatever piece is asked for.
  vbr::vtk::requestWholeImage(this, request, inputVector[0], outputVector);
  return 1;
}

const char* vtkCUDBConnectivity::GetConnectivityAsString()
{
  return this->Connectivity == FACE ? "Face" : "Vertex";
}

const char* vtkCUDBConnectivity::GetSortingOrderAsString()
{
  return this->SortingOrder == AUTO ? "Auto" : OrderNames[this->SortingOrder];
}

const char* vtkCUDBConnectivity::GetRegionOrderingAsString()
{
  return this->RegionOrdering == SIZE_RANK ? "SizeRank" : "SweepOrder";
}

//------------------------------------------------------------------------------
vtkTypeBool vtkCUDBConnectivity::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // Only the outputs the pipeline releases just before this filter executes are worth
  // keeping beyond the scratch bound: the execution takes them at once (BlockCache).
  // vtkDemandDrivenPipeline::ExecuteDataStart sends REQUEST_DATA_NOT_GENERATED to the
  // algorithm, then releases the outputs it will regenerate (PrepareForNewData), then sends
  // REQUEST_DATA: the window (ReleaseWindow) is open from the first request to the end of
  // REQUEST_DATA, also after an error or an abort.
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_NOT_GENERATED()))
    this->Kept->window.open();
  if (!request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
    return this->Superclass::ProcessRequest(request, inputVector, outputVector);
  struct Closer
  {
    ReleaseWindow& window;
    ~Closer() { this->window.close(); }
  } closer{ this->Kept->window };
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
vtkIdType vtkCUDBConnectivity::GetCachedBlockBytes()
{
  return static_cast<vtkIdType>(blockCache().bytesKept());
}

//------------------------------------------------------------------------------
bool vtkCUDBConnectivity::GetUsedPlanarRecords()
{
  return this->Kept->planarRecords;
}

//------------------------------------------------------------------------------
bool vtkCUDBConnectivity::CheckPlanarRecords(int seed, int trials)
{
  return vbr::checkPlanarRecords(seed, trials, std::cerr);
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const CacheUpdate update;
  const KeptRunsBound keptRuns(this->Kept->runs, this->GetReleaseDataFlag() != 0);
  return vbr::vtk::executeGuarded(this,
    outputVector,
    "Connected components",
    [&] { return this->Execute(inputVector, outputVector); });
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const Ports ports(inputVector, outputVector);
  vtkImageData *input = ports.input, *output = ports.output;
  vtkDataSet* seeds = ports.seeds;
  if (!input || !output || !ports.boxes || !ports.table)
  {
    vtkErrorMacro(<< "Input must be a vtkImageData.");
    return 0;
  }
  output->CopyStructure(input);
  output->GetPointData()->PassData(input->GetPointData());
  output->GetCellData()->PassData(input->GetCellData());
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  vbr::vtk::InputObjects in;
  vbr::vtk::SelectionSettings settings = vbr::vtk::selectionSettingsOf(this);
  settings.bytesPerVoxel = sizeof(std::int32_t) + 1.0 / 8.0; // RegionId image, selection bits
  settings.distributed = true; // one RegionId per component across the ranks
  if (!vbr::vtk::readInputObjects(this, input, scalars, association, settings, in))
    return 0;
  if (in.objects.empty() && !scalars)
    return 1; // an empty image has no components
  this->UpdateProgress(0.05);

  // PASS 1: the boxes (CUDB) and their components, object by object (paper 002). Under MPI
  // rank 0 has every object, from the EVMs of all ranks (see vtkVoxelBRepDistributed.h).
  Summary summary;
  std::vector<ObjectBoxes> objects;
  if (in.grid.flatAxis < 0 || in.objects.size() != 1)
    this->Kept->runs.planar = PlanarMemory(); // only a 2D image's only object sweeps in it
  const std::uint32_t regionCount = buildObjectBoxes(this, in, objects, summary, &this->Kept->runs);
  if (in.piece.distributed())
  {
    // The boxes and the table are whole on rank 0 and absent elsewhere: no ghost layer can be
    // missing from them. ParaView asks unstructured outputs for one by default (the image
    // port for none); without this the filter would execute again for that request.
    const bool written =
      writeDistributed(this, in, objects, regionCount, summary, ports, *this->Kept);
    vbr::vtk::markGhostLevelsComplete(outputVector, { 1, 2 });
    return written ? 1 : 0;
  }
  if (this->GetAbortExecute())
  {
    clearLabels(output);
    return 1;
  }

  // PASS 2: the regions, filtered (size, seeds, largest) and numbered.
  Regions regions;
  RegionIdList regionIds;
  RegionList regionOfRow;
  vtkSmartPointer<vtkIntArray> ids; // with seeds, painted now to find their regions
  numberAllRegions(
    this, seeds, in, objects, regionCount, regions, regionIds, regionOfRow, summary, &ids);
  this->Kept->planarRecords = regions.isPlanar();

  // PASS 3: the outputs: RegionId image, boxes, region table.
  {
    vtkLogScopeF(TRACE, "write the region ids");
    if (!seeds)
      ids = paintRegions(objects,
        &regionIds,
        in.grid,
        in.axes,
        vbr::vtk::makeExecution(this, 0.7, 0.9),
        &this->Kept->regionIds);
    else if (ids)
      renumberRegions(ids, regionIds);
    if (!ids)
    {
      clearLabels(output);
      return 1;
    }
    addRegionIds(output, ids, in.grid.cellData);
  }
  this->UpdateProgress(0.9);
  writeBoxesAndTable(
    this, in, objects, regions, regionIds, regionOfRow, summary, ports, *this->Kept);
  if (objects.size() == 1 && objects[0].labelledFromRuns && in.objects.size() == 1)
    this->Kept->runs.keep(objects[0]); // bounded on the way out (KeptRunsBound)
  if (objects.size() == 1 && in.grid.flatAxis >= 0 && in.objects.size() == 1)
    this->Kept->runs.planar.keep(objects[0]); // bounded on the way out too
  return 1;
}

//------------------------------------------------------------------------------
void vtkCUDBConnectivity::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Selection:\n";
  this->Selection->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Connectivity: " << this->GetConnectivityAsString() << "\n";
  os << indent << "SortingOrder: " << this->GetSortingOrderAsString() << "\n";
  os << indent << "RegionOrdering: " << this->GetRegionOrderingAsString() << "\n";
  os << indent << "MinimumRegionSize: " << this->MinimumRegionSize << "\n";
  os << indent << "LargestRegions: " << this->LargestRegions << "\n";
  os << indent << "GenerateBoxes: " << (this->GenerateBoxes ? "On\n" : "Off\n");
  os << indent << "RunLabelling: " << (this->RunLabelling ? "On\n" : "Off\n");
  os << indent << "MinimumPixelRuns: " << this->MinimumPixelRuns << "\n";
}
