#include "vtkStandardPlaneReversion.h"

#include "Polyhedrization.h"
#include "vtkVoxelBRepAdapters.h"
#include "vtkVoxelBRepDistributed.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

vtkStandardNewMacro(vtkStandardPlaneReversion);

namespace
{

/// Voxels per axis the reversion takes (as the polyhedrizer: corners fit in 21 bits).
constexpr double MaximumVoxelsPerAxis = (1 << 20) - 1;
/// Voxels in all (one byte each in the output).
constexpr double MaximumVoxels = double(std::int64_t(1) << 33);

/// Whether v is an integer of magnitude at most `limit` (false for NaN and infinities), and
/// then that integer: no out-of-range float-to-int conversion.
bool integerValue(double v, double limit, std::int64_t& out)
{
  if (!(std::fabs(v) <= limit) || v != std::floor(v))
    return false;
  out = static_cast<std::int64_t>(v);
  return true;
}

/// The grid the faces were made in, and the layout of the image they came from, from the
/// polyhedrizer's field data.
struct Grid
{
  double origin[3]; ///< world position of voxel corner (0, 0, 0)
  double spacing[3];
  std::array<std::int32_t, 3> dims;
  // The output's layout: the input image's (or, for faces without it, cell data on the
  // grid of voxel corners).
  int extent[6];
  double imageOrigin[3];
  bool cellData = true;
};

/// A field array with one tuple of `components` values, or null.
vtkDataArray* fieldArray(vtkFieldData* fd, const char* name, int components)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  return a && a->GetNumberOfComponents() == components && a->GetNumberOfTuples() >= 1 ? a : nullptr;
}

/// The grid of the voxels; an error message, or an empty string.
std::string readVoxelGrid(vtkFieldData* fd, Grid& grid)
{
  vtkDataArray* origin = fieldArray(fd, "VoxelGridOrigin", 3);
  vtkDataArray* spacing = fieldArray(fd, "VoxelGridSpacing", 3);
  vtkDataArray* dims = fieldArray(fd, "VoxelGridDimensions", 3);
  if (!origin || !spacing || !dims)
    return "The input must be the StandardFaces output of vtkStandardPlanePolyhedrizer "
           "(field data VoxelGridOrigin, VoxelGridSpacing, VoxelGridDimensions of 3 "
           "components).";
  double voxels = 1;
  for (int d = 0; d < 3; ++d)
  {
    grid.origin[d] = origin->GetComponent(0, d);
    grid.spacing[d] = spacing->GetComponent(0, d);
    std::int64_t n = 0;
    if (!std::isfinite(grid.origin[d]) || !std::isfinite(grid.spacing[d]) || grid.spacing[d] == 0)
      return "VoxelGridOrigin and VoxelGridSpacing must be finite, the spacing non-zero.";
    if (!integerValue(dims->GetComponent(0, d), MaximumVoxelsPerAxis, n) || n < 0)
    {
      std::ostringstream msg;
      msg << "VoxelGridDimensions must be whole numbers from 0 to " << MaximumVoxelsPerAxis
          << "; axis " << d << " has " << dims->GetComponent(0, d) << ".";
      return msg.str();
    }
    grid.dims[d] = static_cast<std::int32_t>(n);
    voxels *= double(n);
  }
  if (voxels > MaximumVoxels)
  {
    std::ostringstream msg;
    msg << "VoxelGridDimensions ask for " << voxels << " voxels; at most " << MaximumVoxels
        << " are supported.";
    return msg.str();
  }
  return std::string();
}

/// The layout of the image the faces came from (extent, origin, association): the output
/// takes it. Faces written before it was recorded give cell data on the grid of corners.
std::string readLayout(vtkFieldData* fd, Grid& grid)
{
  vtkDataArray* extent = fieldArray(fd, "VoxelGridExtent", 6);
  vtkDataArray* origin = fieldArray(fd, "VoxelGridImageOrigin", 3);
  vtkDataArray* association = fieldArray(fd, "VoxelGridAssociation", 1);
  if (!extent && !origin && !association)
  {
    for (int d = 0; d < 3; ++d)
    {
      grid.extent[2 * d] = 0;
      grid.extent[2 * d + 1] = grid.dims[d];
      grid.imageOrigin[d] = grid.origin[d];
    }
    grid.cellData = true;
    return std::string();
  }
  std::int64_t kind = -1;
  if (!extent || !origin || !association || !integerValue(association->GetComponent(0, 0), 1, kind))
    return "VoxelGridExtent (6 components), VoxelGridImageOrigin (3) and VoxelGridAssociation "
           "(0 points, 1 cells) must be given together.";
  grid.cellData = kind == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  for (int d = 0; d < 3; ++d)
  {
    std::int64_t lo = 0, hi = 0;
    grid.imageOrigin[d] = origin->GetComponent(0, d);
    if (!integerValue(extent->GetComponent(0, 2 * d), VTK_INT_MAX / 2, lo) ||
      !integerValue(extent->GetComponent(0, 2 * d + 1), VTK_INT_MAX / 2, hi) ||
      !std::isfinite(grid.imageOrigin[d]))
      return "VoxelGridExtent must hold whole numbers, VoxelGridImageOrigin finite ones.";
    const std::int64_t points = hi - lo + 1;
    const std::int64_t voxels = grid.cellData ? (points > 1 ? points - 1 : 1) : points;
    if (points < 1 || voxels != grid.dims[d])
      return "VoxelGridExtent does not match VoxelGridDimensions.";
    grid.extent[2 * d] = static_cast<int>(lo);
    grid.extent[2 * d + 1] = static_cast<int>(hi);
  }
  return std::string();
}

/// Whether the faces were made in a grid with a direction matrix (not supported).
bool rotated(vtkFieldData* fd)
{
  vtkDataArray* direction = fieldArray(fd, "VoxelGridDirection", 9);
  if (!direction)
    return false;
  for (int i = 0; i < 9; ++i)
    if (direction->GetComponent(0, i) != (i % 4 == 0 ? 1.0 : 0.0))
      return true;
  return false;
}

/// The face arrays, one tuple per cell; an error message, or an empty string.
std::string checkFaceArrays(vtkPolyData* input,
  vtkDataArray* normals,
  vtkDataArray* offsets,
  vtkDataArray* labels)
{
  const vtkIdType cells = input->GetNumberOfCells();
  if (cells == 0)
    return std::string();
  if (!normals || !offsets || normals->GetNumberOfComponents() != 3 ||
    offsets->GetNumberOfComponents() != 1 || input->GetPolys()->GetNumberOfCells() != cells)
    return "The input must be polygons with the cell arrays PlaneNormal (3 components) and "
           "PlaneOffset (the StandardFaces output mode).";
  std::ostringstream msg;
  for (vtkDataArray* a : { normals, offsets, labels })
    if (a && a->GetNumberOfTuples() != cells)
      msg << "The cell array " << a->GetName() << " has " << a->GetNumberOfTuples()
          << " tuples for " << cells << " faces.";
  if (labels && labels->GetNumberOfComponents() != 1)
    msg << "The cell array Label must have one component.";
  return msg.str();
}

/// The plane of face c: whole numbers within the core's range (no overflowing casts).
bool readPlane(vtkDataArray* normals, vtkDataArray* offsets, vtkIdType c, vbr::StandardPlane& plane)
{
  constexpr double NormalLimit = double(std::int64_t(1) << 31);
  constexpr double OffsetLimit = double(std::int64_t(1) << 52);
  for (int d = 0; d < 3; ++d)
    if (!integerValue(normals->GetComponent(c, d), NormalLimit, plane.normal[d]))
      return false;
  return integerValue(offsets->GetComponent(c, 0), OffsetLimit, plane.mu);
}

/// The voxel corner of a world point; false when it is not one within the core's range.
bool cornerOf(const Grid& grid, const double p[3], vbr::Point3& corner)
{
  constexpr double CornerLimit = double(1 << 20);
  for (int d = 0; d < 3; ++d)
  {
    const double index = std::nearbyint((p[d] - grid.origin[d]) / grid.spacing[d]);
    std::int64_t i = 0;
    if (!integerValue(index, CornerLimit, i))
      return false;
    corner[d] = static_cast<std::int32_t>(i);
  }
  return true;
}

using Outlines = std::map<vbr::vtk::LabelValue, std::vector<vbr::FaceOutline>>; // exact labels

/// One face of the input: a cell carrying its arrays, and its loop of point ids.
struct FaceLoop
{
  vtkIdType cell = 0;
  std::vector<vtkIdType> ids;
  std::vector<vtkIdType> cells; ///< every cell of the face (its triangles), `cell` first
};

/// Whether the faces are TriangulatedFaces (or SemiDiscrete) output: several cells per
/// FaceId. StandardFaces output has one polygon per face.
bool facesAreSplit(vtkDataArray* faceIds)
{
  if (!faceIds)
    return false;
  std::unordered_set<vtkIdType> seen;
  for (vtkIdType c = 0; c < faceIds->GetNumberOfTuples(); ++c)
    if (!seen.insert(static_cast<vtkIdType>(faceIds->GetComponent(c, 0))).second)
      return true;
  return false;
}

/// The boundary of a face given by its triangles: its loop edges (`allOnLoop`: `edges` are
/// them, from LoopEdges), else the directed edges whose reverse is not in the face, chained
/// into one closed walk (Hierholzer's, so that a loop passing twice through a pointel is
/// followed whole). An error message, or an empty string.
std::string boundaryLoop(const std::vector<std::pair<vtkIdType, vtkIdType>>& edges,
  bool allOnLoop,
  std::vector<vtkIdType>& loop)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> count;
  for (const auto& e : edges)
    if (++count[e] > 1)
      return "an edge of its triangles is given twice (faces given twice?)";
  std::map<vtkIdType, std::vector<vtkIdType>> next; // boundary edges by their first point
  std::size_t boundary = 0;
  for (const auto& e : edges)
    if (allOnLoop || !count.count({ e.second, e.first }))
    {
      next[e.first].push_back(e.second);
      ++boundary;
    }
  if (boundary < 3)
    return "its triangles have no boundary loop";
  std::vector<vtkIdType> stack{ next.begin()->first }, walk;
  while (!stack.empty())
  {
    std::vector<vtkIdType>& out = next[stack.back()];
    if (out.empty())
    {
      walk.push_back(stack.back());
      stack.pop_back();
      continue;
    }
    stack.push_back(out.back());
    out.pop_back();
  }
  if (walk.size() != boundary + 1)
    return "its triangles do not make a disk (several boundary loops)";
  loop.assign(walk.rbegin(), walk.rend() - 1); // the walk is built backwards, closed
  return std::string();
}

/// The faces' loops: one per polygon (StandardFaces), or rebuilt from the triangles of each
/// FaceId (TriangulatedFaces). An error message, or an empty string.
std::string gatherLoops(vtkPolyData* input, std::vector<FaceLoop>& faces)
{
  vtkDataArray* faceIds = input->GetCellData()->GetArray("FaceId");
  vtkCellArray* polys = input->GetPolys();
  vtkIdType npts;
  const vtkIdType* pts;
  polys->InitTraversal();
  if (!facesAreSplit(faceIds))
  {
    for (vtkIdType c = 0; polys->GetNextCell(npts, pts); ++c)
      faces.push_back({ c, std::vector<vtkIdType>(pts, pts + npts), { c } });
    return std::string();
  }
  // With LoopEdges (bit k: the edge from corner k to k + 1 runs along the loop) the loop
  // edges are known; without, they are the edges whose reverse is not in the face.
  vtkDataArray* loopEdges = input->GetCellData()->GetArray("LoopEdges");
  if (loopEdges && loopEdges->GetNumberOfTuples() != input->GetNumberOfCells())
    return "LoopEdges must have one value per cell.";
  std::map<vtkIdType, std::pair<FaceLoop, std::vector<std::pair<vtkIdType, vtkIdType>>>> byFace;
  for (vtkIdType c = 0; polys->GetNextCell(npts, pts); ++c)
  {
    auto& face = byFace[static_cast<vtkIdType>(faceIds->GetComponent(c, 0))];
    if (face.first.cells.empty())
      face.first.cell = c;
    face.first.cells.push_back(c);
    const int bits = loopEdges ? static_cast<int>(loopEdges->GetComponent(c, 0)) : -1;
    for (vtkIdType i = 0; i < npts; ++i)
      if (bits < 0 || (i < 8 && ((bits >> i) & 1)))
        face.second.emplace_back(pts[i], pts[(i + 1) % npts]);
  }
  for (auto& [id, face] : byFace)
  {
    const std::string problem = boundaryLoop(face.second, loopEdges != nullptr, face.first.ids);
    if (!problem.empty())
      return "Face " + std::to_string(id) + ": " + problem + ".";
    faces.push_back(std::move(face.first));
  }
  return std::string();
}

/// What is wrong with the plane and label of cell c (its plane in `plane`), or nothing.
std::string cellProblem(vtkDataArray* normals,
  vtkDataArray* offsets,
  vtkDataArray* labels,
  vtkIdType c,
  vbr::StandardPlane& plane)
{
  std::ostringstream msg;
  if (!readPlane(normals, offsets, c, plane))
    msg << "Face " << c << ": PlaneNormal and PlaneOffset must be whole numbers (normal "
        << "components within 2^31, offset within 2^52).";
  else if (labels && std::isnan(labels->GetComponent(c, 0)))
    msg << "Face " << c << ": its Label is NaN.";
  return msg.str();
}

/// The outlines of the faces by label: corners from world points, loops in the faces'
/// orientation. An error message, or an empty string.
std::string readOutlines(vtkAlgorithm* self,
  vtkPolyData* input,
  const Grid& grid,
  vtkDataArray* normals,
  vtkDataArray* offsets,
  vtkDataArray* labels,
  Outlines& byLabel)
{
  const bool mirrored = grid.spacing[0] * grid.spacing[1] * grid.spacing[2] < 0;
  std::vector<FaceLoop> faces;
  const std::string problem = gatherLoops(input, faces);
  if (!problem.empty())
    return problem;
  for (std::size_t f = 0; f < faces.size(); ++f)
  {
    const vtkIdType c = faces[f].cell;
    const std::vector<vtkIdType>& ids = faces[f].ids;
    const std::size_t npts = ids.size();
    std::ostringstream msg;
    vbr::FaceOutline outline;
    const vbr::vtk::LabelValue label =
      labels ? vbr::vtk::labelAt(labels, c) : vbr::vtk::LabelValue();
    msg << cellProblem(normals, offsets, labels, c, outline.plane);
    for (std::size_t k = 1; k < faces[f].cells.size() && msg.tellp() == 0; ++k)
    {
      // Every triangle of a face carries the face's plane and label.
      vbr::StandardPlane plane;
      const vtkIdType t = faces[f].cells[k];
      msg << cellProblem(normals, offsets, labels, t, plane);
      if (msg.tellp() == 0 &&
        (plane.normal != outline.plane.normal || plane.mu != outline.plane.mu ||
          (labels && !(vbr::vtk::labelAt(labels, t) == label))))
        msg << "Face " << t << ": its plane or label differs from the other cells of its face.";
    }
    for (std::size_t i = 0; i < npts && msg.tellp() == 0; ++i)
    {
      double p[3];
      input->GetPoint(ids[mirrored ? npts - 1 - i : i], p);
      vbr::Point3 corner;
      if (!cornerOf(grid, p, corner))
        msg << "Face " << c << ": point " << i << " is not a voxel corner of the grid.";
      outline.loop.push_back(corner);
    }
    if (msg.tellp() != 0)
      return msg.str();
    byLabel[label].push_back(std::move(outline));
    if (f % 1024 == 0)
    {
      self->UpdateProgress(0.5 * double(f) / double(std::max<std::size_t>(faces.size(), 1)));
      if (self->GetAbortExecute())
        return std::string();
    }
  }
  return std::string();
}

/// The voxels of each label's faces, in the layout of the grid.
/// The outlines moved into the box of their corners (its first corner `lo`, `dims` voxels),
/// planes shifted with them (n.(p - lo) = n.p - n.lo). An error message when a corner lies
/// outside the grid.
std::string outlinesInBox(const std::vector<vbr::FaceOutline>& outlines,
  const std::array<std::int32_t, 3>& gridDims,
  std::vector<vbr::FaceOutline>& boxed,
  vbr::Point3& lo,
  std::array<std::int32_t, 3>& dims)
{
  vbr::Point3 hi{ 0, 0, 0 };
  lo = gridDims;
  for (const vbr::FaceOutline& f : outlines)
    for (const vbr::Point3& p : f.loop)
      for (int d = 0; d < 3; ++d)
      {
        if (p[d] < 0 || p[d] > gridDims[d])
          return "the faces do not bound a set of voxels of the grid";
        lo[d] = std::min(lo[d], p[d]);
        hi[d] = std::max(hi[d], p[d]);
      }
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = std::min(lo[d], hi[d]);
    dims[d] = std::max(hi[d] - lo[d], 1);
    lo[d] = std::min(lo[d], gridDims[d] - dims[d]); // a flat box keeps one voxel inside
  }
  boxed = outlines;
  for (vbr::FaceOutline& f : boxed)
  {
    for (vbr::Point3& p : f.loop)
      for (int d = 0; d < 3; ++d)
        p[d] -= lo[d];
    for (int d = 0; d < 3; ++d)
      f.plane.mu -= f.plane.normal[d] * lo[d];
  }
  return std::string();
}

/// The voxels of one label's faces, reverted within the box of their corners (the cost per
/// label is its own box, not the whole grid): the box's origin `lo` and size `boxDims` in the
/// grid. Returns a problem, or an empty string.
std::string revertInBox(const std::vector<vbr::FaceOutline>& outlines,
  const Grid& grid,
  const vbr::Execution& exec,
  vbr::BitVolume& voxels,
  vbr::Point3& lo,
  std::array<std::int32_t, 3>& boxDims)
{
  std::vector<vbr::FaceOutline> boxed;
  std::string problem = outlinesInBox(outlines, grid.dims, boxed, lo, boxDims);
  if (problem.empty())
    problem = vbr::revert(boxed, boxDims, voxels, exec);
  return problem;
}

/// Sets the Selection (and the Label, when `labelValues` is given) of a label's voxels, given
/// in the box at `lo` of size `boxDims`.
void paintLabel(const vbr::BitVolume& voxels,
  const std::array<std::int32_t, 3>& boxDims,
  const vbr::Point3& lo,
  const Grid& grid,
  const vbr::vtk::LabelValue& label,
  vtkUnsignedCharArray* selection,
  vtkDataArray* labelValues)
{
  for (std::int32_t z = 0; z < boxDims[2]; ++z)
    for (std::int32_t y = 0; y < boxDims[1]; ++y)
      for (std::int32_t x = 0; x < boxDims[0]; ++x)
        if (voxels.get(x, y, z))
        {
          const vtkIdType i =
            (vtkIdType(z + lo[2]) * grid.dims[1] + (y + lo[1])) * grid.dims[0] + (x + lo[0]);
          selection->SetValue(i, 1);
          if (labelValues)
            vbr::vtk::setLabel(labelValues, i, label);
        }
}

int writeVoxels(vtkAlgorithm* self,
  const Grid& grid,
  const Outlines& byLabel,
  vtkDataArray* faceLabels,
  vtkImageData* output)
{
  output->SetOrigin(grid.imageOrigin);
  output->SetSpacing(grid.spacing);
  output->SetExtent(const_cast<int*>(grid.extent));
  const vtkIdType n = vtkIdType(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  vtkNew<vtkUnsignedCharArray> selection;
  selection->SetName("Selection");
  vbr::vtk::resizeOrThrow(selection, n);
  selection->FillValue(0);
  // Label of the faces' type, so that every label is exact.
  const bool withLabels = faceLabels != nullptr;
  vtkSmartPointer<vtkDataArray> labelValues = vbr::vtk::newLabelArray(
    withLabels ? faceLabels->GetDataType() : VTK_DOUBLE, withLabels ? n : 0);
  std::size_t done = 0;
  for (const auto& [label, outlines] : byLabel)
  {
    if (self->GetAbortExecute())
      break;
    const double from = 0.5 + 0.5 * double(done++) / double(byLabel.size());
    vbr::Point3 lo{ 0, 0, 0 };
    std::array<std::int32_t, 3> boxDims{ 0, 0, 0 };
    vbr::BitVolume voxels;
    const std::string problem = revertInBox(outlines,
      grid,
      vbr::vtk::makeExecution(self, from, from + 0.5 / double(byLabel.size())),
      voxels,
      lo,
      boxDims);
    if (self->GetAbortExecute())
      break;
    if (!problem.empty())
    {
      vtkErrorWithObjectMacro(self, << "Reversion failed: " << problem << ".");
      output->Initialize();
      return 0;
    }
    paintLabel(voxels, boxDims, lo, grid, label, selection, withLabels ? labelValues : nullptr);
  }
  if (self->GetAbortExecute())
  {
    output->Initialize();
    return 1;
  }
  vtkDataSetAttributes* attributes = grid.cellData
    ? static_cast<vtkDataSetAttributes*>(output->GetCellData())
    : static_cast<vtkDataSetAttributes*>(output->GetPointData());
  attributes->SetScalars(selection);
  if (withLabels)
    attributes->AddArray(labelValues);
  return 1;
}

} // namespace

vtkStandardPlaneReversion::vtkStandardPlaneReversion()
{
  this->SetProgressText("Standard Plane Reversion");
}
vtkStandardPlaneReversion::~vtkStandardPlaneReversion() = default;

int vtkStandardPlaneReversion::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkStandardPlaneReversion::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The extent is known only from the faces' field data: produce it whole in RequestData.
  vtkInformation* out = outputVector->GetInformationObject(0);
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  Grid grid;
  if (input && readVoxelGrid(input->GetFieldData(), grid).empty() &&
    readLayout(input->GetFieldData(), grid).empty())
  {
    out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), grid.extent, 6);
    out->Set(vtkDataObject::ORIGIN(), grid.imageOrigin, 3);
    out->Set(vtkDataObject::SPACING(), grid.spacing, 3);
  }
  return 1;
}

int vtkStandardPlaneReversion::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vbr::vtk::executeGuarded(
    this, outputVector, "Reversion", [&] { return this->Execute(inputVector, outputVector); });
}

int vtkStandardPlaneReversion::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro(<< "The input must be the StandardFaces output of "
                     "vtkStandardPlanePolyhedrizer.");
    return 0;
  }
  if (vtkMultiProcessController* c = vbr::vtk::distributedController(this))
    if (c->GetLocalProcessId() != 0)
    {
      // Under MPI the faces are the whole image's, on rank 0 (see vtkVoxelBRepDistributed.h):
      // rank 0 rebuilds the whole image, the other ranks output none of it.
      output->Initialize();
      return 1;
    }
  Grid grid;
  std::string problem = readVoxelGrid(input->GetFieldData(), grid);
  if (problem.empty())
    problem = readLayout(input->GetFieldData(), grid);
  if (problem.empty() && rotated(input->GetFieldData()))
    problem = "The faces come from an image with a direction matrix, which the reversion does "
              "not support; use the polyhedrizer's output port 1.";
  vtkDataArray* normals = input->GetCellData()->GetArray("PlaneNormal");
  vtkDataArray* offsets = input->GetCellData()->GetArray("PlaneOffset");
  vtkDataArray* labels = input->GetCellData()->GetArray("Label");
  if (problem.empty())
    problem = checkFaceArrays(input, normals, offsets, labels);
  Outlines byLabel;
  if (problem.empty())
    problem = readOutlines(this, input, grid, normals, offsets, labels, byLabel);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    output->Initialize();
    return 0;
  }
  return writeVoxels(this, grid, byLabel, labels, output);
}

void vtkStandardPlaneReversion::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
