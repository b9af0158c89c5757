#include "vtkVoxelPhantomSource.h"

#include "Phantom.h"
#include "vtkVoxelBRepAdapters.h"
#include "vtkVoxelBRepMemory.h"

#include "vtkAlgorithm.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkVoxelPhantomSource);

//------------------------------------------------------------------------------
vtkVoxelPhantomSource::vtkVoxelPhantomSource()
{
  this->SetNumberOfInputPorts(0);
  this->SetProgressText("Voxel Phantom");
}

//------------------------------------------------------------------------------
int vtkVoxelPhantomSource::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6] = { 0,
    std::max(this->Dimensions[0], 1) - 1,
    0,
    std::max(this->Dimensions[1], 1) - 1,
    0,
    std::max(this->Dimensions[2], 1) - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 1);
  // Any sub-extent on request: under MPI each rank computes its own piece alone.
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkVoxelPhantomSource::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // std::bad_alloc (when the estimate below was too optimistic) becomes an error.
  return vbr::vtk::executeGuarded(this,
    outputVector,
    "The phantom",
    [&] { return this->Superclass::RequestData(request, inputVector, outputVector); });
}

//------------------------------------------------------------------------------
void vtkVoxelPhantomSource::ExecuteDataWithInformation(vtkDataObject* output,
  vtkInformation* outInfo)
{
  // The piece asked for (the whole extent unless a consumer streams or distributes pieces).
  int extent[6];
  outInfo->Get(outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT())
      ? vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()
      : vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(),
    extent);
  std::array<std::int32_t, 3> first, size;
  for (int d = 0; d < 3; ++d)
  {
    first[d] = extent[2 * d];
    size[d] = std::max(extent[2 * d + 1] - extent[2 * d] + 1, 0);
  }
  // The image and the piece's labels: two bytes per voxel, refused before allocating.
  const std::string refused =
    vbr::vtk::checkAllocation(2.0 * size[0] * size[1] * size[2], "The phantom");
  if (!refused.empty())
  {
    vtkErrorMacro(<< refused);
    return;
  }
  vtkImageData* image = this->AllocateOutputData(output, outInfo);
  vtkUnsignedCharArray* scalars =
    vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  if (!scalars)
  {
    vtkErrorMacro(<< "Could not allocate the phantom's scalars.");
    return;
  }
  scalars->SetName("Labels");
  const std::array<std::int32_t, 3> dims{ std::max(this->Dimensions[0], 1),
    std::max(this->Dimensions[1], 1),
    std::max(this->Dimensions[2], 1) };
  const std::vector<std::uint8_t> labels = vbr::makePhantomPiece(dims, first, size);
  std::copy(labels.begin(), labels.end(), scalars->GetPointer(0));
}

//------------------------------------------------------------------------------
void vtkVoxelPhantomSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Dimensions: " << this->Dimensions[0] << " " << this->Dimensions[1] << " "
     << this->Dimensions[2] << "\n";
}
