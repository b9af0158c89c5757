#include "vtkStandardPlaneReversion.h"

#include "Polyhedrization.h"
#include "vtkVoxelBRepAdapters.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkStandardPlaneReversion);

namespace
{

/// The grid the faces were made in, from the polyhedrizer's field data.
struct Grid
{
  double origin[3];
  double spacing[3];
  std::array<std::int32_t, 3> dims;
};

bool readGrid(vtkFieldData* fd, Grid& grid)
{
  vtkDataArray* origin = fd ? fd->GetArray("VoxelGridOrigin") : nullptr;
  vtkDataArray* spacing = fd ? fd->GetArray("VoxelGridSpacing") : nullptr;
  vtkDataArray* dims = fd ? fd->GetArray("VoxelGridDimensions") : nullptr;
  if (!origin || !spacing || !dims || origin->GetNumberOfComponents() != 3 ||
    spacing->GetNumberOfComponents() != 3 || dims->GetNumberOfComponents() != 3)
    return false;
  for (int d = 0; d < 3; ++d)
  {
    grid.origin[d] = origin->GetComponent(0, d);
    grid.spacing[d] = spacing->GetComponent(0, d);
    grid.dims[d] = static_cast<std::int32_t>(dims->GetComponent(0, d));
    if (grid.spacing[d] == 0 || grid.dims[d] < 0)
      return false;
  }
  return true;
}

/// Whether the faces were made in a grid with a direction matrix (not supported).
bool rotated(vtkFieldData* fd)
{
  vtkDataArray* direction = fd ? fd->GetArray("VoxelGridDirection") : nullptr;
  if (!direction || direction->GetNumberOfComponents() != 9)
    return false;
  for (int i = 0; i < 9; ++i)
    if (direction->GetComponent(0, i) != (i % 4 == 0 ? 1.0 : 0.0))
      return true;
  return false;
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
  if (input && readGrid(input->GetFieldData(), grid))
  {
    const int extent[6] = { 0, grid.dims[0], 0, grid.dims[1], 0, grid.dims[2] };
    out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    out->Set(vtkDataObject::ORIGIN(), grid.origin, 3);
    out->Set(vtkDataObject::SPACING(), grid.spacing, 3);
  }
  return 1;
}

int vtkStandardPlaneReversion::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  Grid grid;
  if (!input || !output || !readGrid(input->GetFieldData(), grid))
  {
    vtkErrorMacro(<< "The input must be the StandardFaces output of "
                     "vtkStandardPlanePolyhedrizer (field data VoxelGridOrigin, "
                     "VoxelGridSpacing, VoxelGridDimensions).");
    return 0;
  }
  if (rotated(input->GetFieldData()))
  {
    vtkErrorMacro(<< "The faces come from an image with a direction matrix, which the "
                     "reversion does not support; use the polyhedrizer's output port 1.");
    return 0;
  }
  vtkDataArray* normals = input->GetCellData()->GetArray("PlaneNormal");
  vtkDataArray* offsets = input->GetCellData()->GetArray("PlaneOffset");
  vtkDataArray* labels = input->GetCellData()->GetArray("Label");
  const vtkIdType cells = input->GetNumberOfCells();
  if (cells > 0 &&
    (!normals || !offsets || normals->GetNumberOfComponents() != 3 ||
      input->GetPolys()->GetNumberOfCells() != cells))
  {
    vtkErrorMacro(<< "The input must be polygons with the cell arrays PlaneNormal and "
                     "PlaneOffset (the StandardFaces output mode).");
    return 0;
  }
  const bool mirrored = grid.spacing[0] * grid.spacing[1] * grid.spacing[2] < 0;

  // Outlines by label: corners from world points, loops in the faces' orientation.
  std::map<vbr::vtk::LabelValue, std::vector<vbr::FaceOutline>> byLabel; // exact labels
  vtkCellArray* polys = input->GetPolys();
  polys->InitTraversal();
  vtkIdType npts;
  const vtkIdType* pts;
  for (vtkIdType c = 0; polys->GetNextCell(npts, pts); ++c)
  {
    vbr::FaceOutline outline;
    for (int d = 0; d < 3; ++d)
      outline.plane.normal[d] = std::llround(normals->GetComponent(c, d));
    outline.plane.mu = std::llround(offsets->GetTuple1(c));
    for (vtkIdType i = 0; i < npts; ++i)
    {
      double p[3];
      input->GetPoint(pts[mirrored ? npts - 1 - i : i], p);
      vbr::Point3 corner;
      for (int d = 0; d < 3; ++d)
        corner[d] =
          static_cast<std::int32_t>(std::lround((p[d] - grid.origin[d]) / grid.spacing[d]));
      outline.loop.push_back(corner);
    }
    byLabel[labels ? vbr::vtk::labelAt(labels, c) : vbr::vtk::LabelValue()].push_back(
      std::move(outline));
    if (c % 1024 == 0)
      this->UpdateProgress(0.5 * c / std::max<vtkIdType>(cells, 1));
  }

  output->SetOrigin(grid.origin);
  output->SetSpacing(grid.spacing);
  output->SetExtent(0, grid.dims[0], 0, grid.dims[1], 0, grid.dims[2]);
  const vtkIdType n = vtkIdType(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  vtkNew<vtkUnsignedCharArray> selection;
  selection->SetName("Selection");
  selection->SetNumberOfValues(n);
  selection->FillValue(0);
  // Label of the faces' type, so that every label is exact.
  vtkSmartPointer<vtkDataArray> labelValues =
    vbr::vtk::newLabelArray(labels ? labels->GetDataType() : VTK_DOUBLE, labels ? n : 0);
  for (const auto& [label, outlines] : byLabel)
  {
    std::vector<vbr::SurfelGraph::Surfel> surfels;
    vbr::BitVolume voxels;
    const std::string problem = vbr::revert(outlines, grid.dims, surfels, voxels);
    if (!problem.empty())
    {
      vtkErrorMacro(<< "Reversion failed: " << problem << ".");
      output->Initialize();
      return 0;
    }
    vtkIdType i = 0;
    for (std::int32_t z = 0; z < grid.dims[2]; ++z)
      for (std::int32_t y = 0; y < grid.dims[1]; ++y)
        for (std::int32_t x = 0; x < grid.dims[0]; ++x, ++i)
          if (voxels.get(x, y, z))
          {
            selection->SetValue(i, 1);
            if (labels)
              vbr::vtk::setLabel(labelValues, i, label);
          }
  }
  output->GetCellData()->SetScalars(selection);
  if (labels)
    output->GetCellData()->AddArray(labelValues);
  return 1;
}

void vtkStandardPlaneReversion::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
