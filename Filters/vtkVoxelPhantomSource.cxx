#include "vtkVoxelPhantomSource.h"

#include "Phantom.h"
#include "vtkVoxelBRepAdapters.h"
#include "vtkVoxelBRepMemory.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
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
  // The image and the phantom's own labels: two bytes per voxel, refused before allocating.
  const double voxels = double(std::max(this->Dimensions[0], 1)) *
    std::max(this->Dimensions[1], 1) * std::max(this->Dimensions[2], 1);
  const std::string refused = vbr::vtk::checkAllocation(2.0 * voxels, "The phantom");
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
  int extent[6];
  image->GetExtent(extent);
  const std::array<std::int32_t, 3> dims{ std::max(this->Dimensions[0], 1),
    std::max(this->Dimensions[1], 1),
    std::max(this->Dimensions[2], 1) };
  const std::vector<std::uint8_t> labels = vbr::makePhantom(dims);
  // Copy the requested extent (the whole extent unless a consumer streams pieces).
  unsigned char* out = scalars->GetPointer(0);
  for (int k = extent[4]; k <= extent[5]; ++k)
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      const std::size_t src = (static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + extent[0];
      std::copy_n(labels.data() + src, extent[1] - extent[0] + 1, out);
      out += extent[1] - extent[0] + 1;
    }
}

//------------------------------------------------------------------------------
void vtkVoxelPhantomSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Dimensions: " << this->Dimensions[0] << " " << this->Dimensions[1] << " "
     << this->Dimensions[2] << "\n";
}
