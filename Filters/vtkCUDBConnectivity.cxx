#include "vtkCUDBConnectivity.h"

#include "CUDB.h"
#include "EVM.h"
#include "vtkVoxelBRepAdapters.h"

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
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCUDBConnectivity);

namespace
{

using Int3 = std::array<std::int32_t, 3>;

const char* const OrderNames[] = { "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX" };

/// The CUDB of one selected object (a label, or the whole selection) and its components.
struct ObjectBoxes
{
  vbr::vtk::LabelValue label;
  Int3 offset{ 0, 0, 0 }; ///< box origin of the object, in processing axes
  vbr::CUDB cudb;
  vbr::Components components;
  std::uint32_t firstRegion = 0; ///< global index of the object's component 1
  std::size_t extremeVertices = 0;
};

/// What is known of one connected component.
struct Region
{
  vbr::vtk::LabelValue label;
  std::int64_t voxels = 0;
  std::int64_t boxes = 0;
  std::array<double, 3> weightedCentre{ 0, 0, 0 }; ///< sum of voxel centres, processing axes
  Int3 lo{ std::numeric_limits<std::int32_t>::max(),
    std::numeric_limits<std::int32_t>::max(),
    std::numeric_limits<std::int32_t>::max() };
  Int3 hi{ std::numeric_limits<std::int32_t>::min(),
    std::numeric_limits<std::int32_t>::min(),
    std::numeric_limits<std::int32_t>::min() };
  bool seeded = false;
  std::int32_t id = 0; ///< output RegionId, 0 when removed
};

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

/// The CUDB of the EVM in the candidate sorting with the fewest boxes. False when aborted.
bool buildBestCUDB(const vbr::EVM& evm,
  const std::vector<vbr::AxisOrder>& sortings,
  const vbr::Execution& exec,
  vbr::CUDB& best)
{
  bool found = false;
  for (const vbr::AxisOrder& order : sortings)
  {
    vbr::CUDB cudb;
    const vbr::EVM sorted = order == evm.order() ? vbr::EVM() : evm.sortedAs(order, exec);
    if (!vbr::buildCUDB(order == evm.order() ? evm : sorted, exec, cudb))
      return false;
    if (!found || cudb.boxes.size() < best.boxes.size())
      best = std::move(cudb);
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

/// Statistics of every region from its boxes.
std::vector<Region> measureRegions(const std::vector<ObjectBoxes>& objects, std::size_t count)
{
  std::vector<Region> regions(count);
  for (const ObjectBoxes& o : objects)
  {
    for (std::size_t b = 0; b < o.cudb.boxes.size(); ++b)
    {
      Region& r = regions[o.firstRegion + o.components.boxLabel[b] - 1];
      const vbr::Box& box = o.cudb.boxes[b];
      const std::int64_t volume = box.volume();
      r.label = o.label;
      r.voxels += volume;
      ++r.boxes;
      for (int d = 0; d < 3; ++d)
      {
        const std::int32_t lo = box.lo[d] + o.offset[d], hi = box.hi[d] + o.offset[d];
        r.lo[d] = std::min(r.lo[d], lo);
        r.hi[d] = std::max(r.hi[d], hi);
        r.weightedCentre[d] += static_cast<double>(volume) * (0.5 * (lo + hi));
      }
    }
  }
  return regions;
}

/// Marks the regions containing a seed point, read from `regionOf`: the image of region
/// numbers (index + 1, 0 where nothing is selected) painted from the boxes. One image lookup
/// per seed: the cost is linear in the seeds, whatever the number of boxes.
/// Returns how many seeds fell on a selected voxel.
vtkIdType markSeeds(vtkDataSet* seeds,
  const vbr::vtk::VoxelGrid& grid,
  const std::int32_t* regionOf,
  std::vector<Region>& regions)
{
  vtkIdType hits = 0;
  for (vtkIdType i = 0; i < seeds->GetNumberOfPoints(); ++i)
  {
    double p[3];
    seeds->GetPoint(i, p);
    Int3 voxel; // image axes, from the first voxel of the extent
    if (!grid.worldToVoxel(p, voxel))
      continue;
    const std::int64_t index =
      voxel[0] + std::int64_t(grid.dims[0]) * (voxel[1] + std::int64_t(grid.dims[1]) * voxel[2]);
    const std::int32_t region = regionOf[index];
    if (region > 0)
    {
      regions[region - 1].seeded = true;
      ++hits;
    }
  }
  return hits;
}

/// Applies the region filters and numbers the kept regions; returns how many are kept.
std::int32_t numberRegions(std::vector<Region>& regions,
  vtkIdType minimumSize,
  bool useSeeds,
  vtkIdType largest,
  int ordering)
{
  std::vector<std::size_t> kept;
  for (std::size_t r = 0; r < regions.size(); ++r)
    if (regions[r].voxels >= minimumSize && (!useSeeds || regions[r].seeded))
      kept.push_back(r);
  auto bySize = [&regions](std::size_t a, std::size_t b)
  { return regions[a].voxels > regions[b].voxels; };
  std::stable_sort(kept.begin(), kept.end(), bySize); // ties stay in sweep order
  if (largest > 0 && static_cast<std::size_t>(largest) < kept.size())
    kept.resize(static_cast<std::size_t>(largest));
  if (ordering == vtkCUDBConnectivity::SWEEP_ORDER)
    std::sort(kept.begin(), kept.end());
  for (std::size_t k = 0; k < kept.size(); ++k)
    regions[kept[k]].id = static_cast<std::int32_t>(k + 1);
  return static_cast<std::int32_t>(kept.size());
}

/// Every voxel painted from its box: with `regions`, the region's RegionId (0 where removed);
/// without, the region's number (index + 1). Voxels of no box stay 0.
vtkSmartPointer<vtkIntArray> paintRegions(const std::vector<ObjectBoxes>& objects,
  const std::vector<Region>* regions,
  const vbr::vtk::VoxelGrid& grid,
  const std::array<int, 3>& axes,
  const vbr::Execution& exec)
{
  const std::int64_t n = std::int64_t(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  vtkSmartPointer<vtkIntArray> ids = vbr::vtk::newZeroedIntArray(static_cast<vtkIdType>(n));
  ids->SetName("RegionId");
  std::int32_t* out = ids->GetPointer(0);
  std::vector<std::int32_t> values;
  for (const ObjectBoxes& o : objects)
  {
    values.resize(o.cudb.boxes.size());
    for (std::size_t b = 0; b < o.cudb.boxes.size(); ++b)
    {
      const std::size_t r = o.firstRegion + o.components.boxLabel[b] - 1;
      values[b] = regions ? (*regions)[r].id : static_cast<std::int32_t>(r + 1);
    }
    vbr::paintBoxes(o.cudb.boxes, values, o.offset, axes, grid.dims, out, exec);
  }
  return ids;
}

/// Region numbers (index + 1) replaced in place by the regions' RegionIds (0: removed).
void renumberRegions(vtkIntArray* ids, const std::vector<Region>& regions)
{
  std::int32_t* values = ids->GetPointer(0);
  vtkSMPTools::For(0,
    ids->GetNumberOfValues(),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
        if (values[i] > 0)
          values[i] = regions[values[i] - 1].id;
    });
}

/// World position of a grid vertex given in processing axes (a 2D image's plane at 0).
void worldOf(const vbr::vtk::VoxelGrid& grid,
  const std::array<int, 3>& axes,
  Int3 p,
  double world[3])
{
  if (grid.flatAxis >= 0)
    p[2] = 0;
  grid.vertexToWorld(toImageAxes(p, axes), world);
}

/// Port 1: the boxes of the kept regions.
void writeBoxes(const std::vector<ObjectBoxes>& objects,
  const std::vector<Region>& regions,
  const vbr::vtk::VoxelGrid& grid,
  const std::array<int, 3>& axes,
  int labelType,
  vtkUnstructuredGrid* output)
{
  const bool planar = grid.flatAxis >= 0;
  const bool aligned = axisAligned(grid);
  const int corners = planar ? 4 : 8;
  // Corner k of a box as (low/high) bits per image axis, in the cell type's order.
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
  const int(*bits)[3] = aligned ? voxelOrder : hexOrder;
  const int cellType =
    planar ? (aligned ? VTK_PIXEL : VTK_QUAD) : (aligned ? VTK_VOXEL : VTK_HEXAHEDRON);
  // In 2D the two in-plane image axes play the roles of the first two bits.
  std::array<int, 3> role{ 0, 1, 2 };
  if (planar)
    role = { std::min(axes[0], axes[1]), std::max(axes[0], axes[1]), grid.flatAxis };

  vtkIdType count = 0;
  for (const ObjectBoxes& o : objects)
    for (std::size_t b = 0; b < o.cudb.boxes.size(); ++b)
      count += regions[o.firstRegion + o.components.boxLabel[b] - 1].id != 0;
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  vbr::vtk::resizeOrThrow(coordinates, count * corners);
  vtkNew<vtkIdTypeArray> offsets, connectivity, boxIds;
  vtkNew<vtkIntArray> regionIds;
  vtkSmartPointer<vtkDataArray> labels = vbr::vtk::newLabelArray(labelType, count);
  vbr::vtk::resizeOrThrow(offsets, count + 1);
  vbr::vtk::resizeOrThrow(connectivity, count * corners);
  vbr::vtk::resizeOrThrow(boxIds, count);
  vbr::vtk::resizeOrThrow(regionIds, count);
  boxIds->SetName("BoxId");
  regionIds->SetName("RegionId");
  double* xyz = coordinates->GetPointer(0);
  vtkIdType cell = 0, boxBase = 0;
  offsets->SetValue(0, 0);
  for (const ObjectBoxes& o : objects)
  {
    for (std::size_t b = 0; b < o.cudb.boxes.size(); ++b)
    {
      const Region& region = regions[o.firstRegion + o.components.boxLabel[b] - 1];
      if (region.id == 0)
        continue;
      const vbr::Box& box = o.cudb.boxes[b];
      Int3 lo = box.lo, hi = box.hi;
      for (int d = 0; d < 3; ++d)
      {
        lo[d] += o.offset[d];
        hi[d] += o.offset[d];
      }
      const Int3 imageLo = toImageAxes(lo, axes), imageHi = toImageAxes(hi, axes);
      for (int k = 0; k < corners; ++k)
      {
        Int3 v = imageLo;
        for (int r = 0; r < 3; ++r)
          if (bits[k][r])
            v[role[r]] = imageHi[role[r]];
        grid.vertexToWorld(v, xyz); // a 2D image's corners lie in its plane (flat at 0)
        xyz += 3;
        connectivity->SetValue(cell * corners + k, cell * corners + k);
      }
      offsets->SetValue(cell + 1, (cell + 1) * corners);
      boxIds->SetValue(cell, boxBase + static_cast<vtkIdType>(b));
      regionIds->SetValue(cell, region.id);
      vbr::vtk::setLabel(labels, cell, o.label);
      ++cell;
    }
    boxBase += static_cast<vtkIdType>(o.cudb.boxes.size());
  }
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  output->SetPoints(points);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  output->SetCells(cellType, cells);
  output->GetCellData()->AddArray(regionIds);
  output->GetCellData()->AddArray(boxIds);
  output->GetCellData()->AddArray(labels);
  output->GetCellData()->SetActiveScalars("RegionId");
}

/// One table column per component of `array`, named `names`, of the array's type.
void addColumnsOfComponents(vtkTable* table, vtkDataArray* array, const char* const* names)
{
  for (int c = 0; c < array->GetNumberOfComponents(); ++c)
  {
    vtkSmartPointer<vtkDataArray> column;
    column.TakeReference(vtkDataArray::CreateDataArray(array->GetDataType()));
    column->SetName(names[c]);
    vbr::vtk::resizeOrThrow(column, array->GetNumberOfTuples());
    column->CopyComponent(0, array, c);
    table->AddColumn(column);
  }
}

/// Port 2: one row per kept region, in RegionId order.
void writeRegionTable(const std::vector<Region>& regions,
  std::int32_t kept,
  const vbr::vtk::VoxelGrid& grid,
  const std::array<int, 3>& axes,
  int labelType,
  vtkTable* table)
{
  std::vector<const Region*> byId(static_cast<std::size_t>(kept), nullptr);
  for (const Region& r : regions)
    if (r.id > 0)
      byId[r.id - 1] = &r;
  vtkNew<vtkIntArray> ids, indexBounds;
  vtkSmartPointer<vtkDataArray> labels = vbr::vtk::newLabelArray(labelType);
  vtkNew<vtkDoubleArray> volumes, bounds, centroids;
  vtkNew<vtkIdTypeArray> voxels, boxes;
  ids->SetName("RegionId");
  voxels->SetName("VoxelCount");
  volumes->SetName("Volume");
  indexBounds->SetName("IndexBounds");
  indexBounds->SetNumberOfComponents(6);
  bounds->SetName("Bounds");
  bounds->SetNumberOfComponents(6);
  centroids->SetName("Centroid");
  centroids->SetNumberOfComponents(3);
  boxes->SetName("NumberOfBoxes");
  const double measure = voxelMeasure(grid);
  for (const Region* r : byId)
  {
    ids->InsertNextValue(r->id);
    vbr::vtk::appendLabel(labels, r->label);
    voxels->InsertNextValue(static_cast<vtkIdType>(r->voxels));
    volumes->InsertNextValue(static_cast<double>(r->voxels) * measure);
    boxes->InsertNextValue(static_cast<vtkIdType>(r->boxes));
    const Int3 lo = toImageAxes(r->lo, axes), hi = toImageAxes(r->hi, axes);
    int index[6];
    double world[6] = {
      VTK_DOUBLE_MAX, VTK_DOUBLE_MIN, VTK_DOUBLE_MAX, VTK_DOUBLE_MIN, VTK_DOUBLE_MAX, VTK_DOUBLE_MIN
    };
    for (int d = 0; d < 3; ++d)
    {
      index[2 * d] = grid.extentMin[d] + lo[d];
      index[2 * d + 1] = grid.extentMin[d] + (hi[d] - 1); // no overflow at INT_MAX
    }
    for (int k = 0; k < 8; ++k)
    {
      double p[3];
      worldOf(grid,
        axes,
        { k & 1 ? r->hi[0] : r->lo[0], k & 2 ? r->hi[1] : r->lo[1], k & 4 ? r->hi[2] : r->lo[2] },
        p);
      for (int d = 0; d < 3; ++d)
      {
        world[2 * d] = std::min(world[2 * d], p[d]);
        world[2 * d + 1] = std::max(world[2 * d + 1], p[d]);
      }
    }
    indexBounds->InsertNextTypedTuple(index);
    bounds->InsertNextTuple(world);
    std::array<double, 3> centre; // processing axes, continuous vertex coordinates
    for (int d = 0; d < 3; ++d)
      centre[d] = r->weightedCentre[d] / static_cast<double>(r->voxels);
    if (grid.flatAxis >= 0)
      centre[2] = 0.0;
    const std::array<double, 3> image = toImageAxes(centre, axes);
    double c[3];
    grid.positionToWorld(image.data(), c);
    centroids->InsertNextTuple(c);
  }
  table->AddColumn(ids);
  table->AddColumn(labels);
  table->AddColumn(voxels);
  table->AddColumn(volumes);
  // Bounds as six columns each: a 6-component array would show a meaningless magnitude.
  static const char* const indexNames[6] = { "IMin", "IMax", "JMin", "JMax", "KMin", "KMax" };
  static const char* const worldNames[6] = { "XMin", "XMax", "YMin", "YMax", "ZMin", "ZMax" };
  addColumnsOfComponents(table, indexBounds, indexNames);
  addColumnsOfComponents(table, bounds, worldNames);
  centroids->SetComponentName(0, "X");
  centroids->SetComponentName(1, "Y");
  centroids->SetComponentName(2, "Z");
  table->AddColumn(centroids);
  table->AddColumn(boxes);
}

/// Summary written to the field data of every output.
struct Summary
{
  vtkIdType regions = 0, components = 0, boxes = 0, oudbBoxes = 0, extremeVertices = 0;
  std::vector<std::string> sortings;

  void write(vtkFieldData* fd) const
  {
    vbr::vtk::addFieldValue(fd, "NumberOfRegions", this->regions);
    vbr::vtk::addFieldValue(fd, "NumberOfComponents", this->components);
    vbr::vtk::addFieldValue(fd, "NumberOfBoxes", this->boxes);
    vbr::vtk::addFieldValue(fd, "NumberOfOUDBBoxes", this->oudbBoxes);
    vbr::vtk::addFieldValue(fd, "NumberOfExtremeVertices", this->extremeVertices);
    vtkNew<vtkStringArray> s;
    s->SetName("SortingOrder");
    for (const std::string& name : this->sortings)
      s->InsertNextValue(name);
    fd->AddArray(s);
  }
};

/// Name of a sorting given in processing axes, in the image's axes.
std::string sortingName(const vbr::AxisOrder& order, const std::array<int, 3>& axes, bool planar)
{
  vbr::AxisOrder image{ axes[order[0]], axes[order[1]], axes[order[2]] };
  const std::string name = vbr::axisOrderName(image);
  return planar ? name.substr(1) : name; // 2D: lines along B, rows along C
}

} // namespace

//------------------------------------------------------------------------------
vtkCUDBConnectivity::vtkCUDBConnectivity()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, vtkDataSetAttributes::SCALARS);
  this->SetProgressText("CUDB Connectivity");
}

//------------------------------------------------------------------------------
vtkCUDBConnectivity::~vtkCUDBConnectivity() = default;

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

vtkImageData* vtkCUDBConnectivity::GetOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
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
vtkTypeBool vtkCUDBConnectivity::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(inputVector, outputVector);
  }
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
  {
    return this->RequestUpdateExtent(inputVector, outputVector);
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    return this->RequestInformation(inputVector, outputVector);
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::RequestInformation(vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // Port 0 inherits the image's extent, origin and spacing (copied by the executive); the
  // boxes and the table are not structured.
  for (int port = 1; port < 3; ++port)
  {
    vtkInformation* info = outputVector->GetInformationObject(port);
    info->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
    info->Remove(vtkDataObject::ORIGIN());
    info->Remove(vtkDataObject::SPACING());
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::RequestUpdateExtent(vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // Components are global: the whole image is needed whatever piece is asked for.
  vtkInformation* in = inputVector[0]->GetInformationObject(0);
  if (in && in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()),
      6);
  }
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
int vtkCUDBConnectivity::RequestData(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vbr::vtk::executeGuarded(this,
    outputVector,
    "Connected components",
    [&] { return this->Execute(inputVector, outputVector); });
}

//------------------------------------------------------------------------------
int vtkCUDBConnectivity::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkDataSet* seeds = vtkDataSet::GetData(inputVector[1]);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkUnstructuredGrid* boxesOutput = vtkUnstructuredGrid::GetData(outputVector, 1);
  vtkTable* table = vtkTable::GetData(outputVector, 2);
  if (!input || !output || !boxesOutput || !table)
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
  if (!vbr::vtk::readInputObjects(this, input, scalars, association, settings, in))
  {
    return 0;
  }
  if (in.objects.empty() && !scalars)
  {
    return 1; // an empty image has no components
  }
  const vbr::vtk::VoxelGrid& grid = in.grid;
  const std::array<int, 3>& axes = in.axes;
  const std::vector<vbr::vtk::Selected>& selected = in.objects;
  const bool planar = grid.flatAxis >= 0;
  this->UpdateProgress(0.05);

  // Boxes and components of every object; its voxels live only while its EVM is built.
  const std::vector<vbr::AxisOrder> sortings = candidateSortings(this->SortingOrder, planar, axes);
  const vbr::Connectivity connectivity =
    this->Connectivity == VERTEX ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
  std::vector<ObjectBoxes> objects;
  Summary summary;
  std::uint32_t regionCount = 0;
  for (std::size_t i = 0; i < selected.size(); ++i)
  {
    const vbr::Execution exec = vbr::vtk::makeExecution(
      this, 0.05 + 0.65 * i / selected.size(), 0.05 + 0.65 * (i + 1) / selected.size());
    if (this->GetAbortExecute())
    {
      break;
    }
    ObjectBoxes o;
    o.label = selected[i].label;
    o.offset = selected[i].offset;
    vbr::EVM evm;
    {
      vtkLogScopeF(TRACE, "select voxels and extract the EVM");
      const vbr::BitVolume voxels = selected[i].select(exec);
      evm = planar ? vbr::extractEVM2D(voxels, exec) : vbr::extractEVM(voxels, exec);
    }
    if (evm.empty())
    {
      continue;
    }
    {
      vtkLogScopeF(TRACE, "EVM to CUDB");
      if (!buildBestCUDB(evm, sortings, exec, o.cudb))
      {
        break; // aborted
      }
    }
    {
      vtkLogScopeF(TRACE, "connected components of the boxes");
      o.components = vbr::labelComponents(o.cudb, connectivity);
    }
    o.extremeVertices = evm.size();
    o.firstRegion = regionCount;
    regionCount += o.components.count;
    summary.boxes += static_cast<vtkIdType>(o.cudb.boxes.size());
    summary.oudbBoxes += static_cast<vtkIdType>(o.cudb.oudbBoxCount);
    summary.extremeVertices += static_cast<vtkIdType>(o.extremeVertices);
    const std::string name = sortingName(o.cudb.order, axes, planar);
    if (std::find(summary.sortings.begin(), summary.sortings.end(), name) == summary.sortings.end())
    {
      summary.sortings.push_back(name);
    }
    objects.push_back(std::move(o));
    this->UpdateProgress(0.05 + 0.65 * (i + 1) / selected.size());
  }
  if (this->GetAbortExecute())
  {
    output->GetPointData()->Initialize();
    output->GetCellData()->Initialize();
    return 1;
  }

  std::vector<Region> regions = measureRegions(objects, regionCount);
  const bool useSeeds = seeds != nullptr;
  vtkSmartPointer<vtkIntArray> ids;
  if (useSeeds)
  {
    // The seeds read their regions from the painted image, which is then renumbered.
    vtkLogScopeF(TRACE, "regions of the seeds");
    ids = paintRegions(objects, nullptr, grid, axes, vbr::vtk::makeExecution(this, 0.7, 0.8));
    if (markSeeds(seeds, grid, ids->GetPointer(0), regions) == 0 && !regions.empty())
    {
      vtkWarningMacro(<< "None of the " << seeds->GetNumberOfPoints()
                      << " seed points lies on a selected voxel: every region is removed.");
    }
  }
  const std::int32_t kept = numberRegions(
    regions, this->MinimumRegionSize, useSeeds, this->LargestRegions, this->RegionOrdering);
  summary.components = static_cast<vtkIdType>(regionCount);
  summary.regions = kept;

  {
    vtkLogScopeF(TRACE, "write the region ids");
    if (useSeeds)
    {
      renumberRegions(ids, regions);
    }
    else
    {
      ids = paintRegions(objects, &regions, grid, axes, vbr::vtk::makeExecution(this, 0.7, 0.9));
    }
    vtkDataSetAttributes* attributes = grid.cellData
      ? static_cast<vtkDataSetAttributes*>(output->GetCellData())
      : static_cast<vtkDataSetAttributes*>(output->GetPointData());
    attributes->AddArray(ids);
    attributes->SetActiveScalars("RegionId");
  }
  this->UpdateProgress(0.9);
  {
    vtkLogScopeF(TRACE, "boxes and region table");
    if (this->GenerateBoxes)
    {
      writeBoxes(objects, regions, grid, axes, in.labelType, boxesOutput);
    }
    writeRegionTable(regions, kept, grid, axes, in.labelType, table);
  }
  summary.write(output->GetFieldData());
  summary.write(boxesOutput->GetFieldData());
  summary.write(table->GetFieldData());
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
}
