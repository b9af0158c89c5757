// VoxelBRep C++ pipeline example: vtkVoxelPhantomSource -> vtkEVMBoundaryFilter ->
// vtkXMLPolyDataWriter.
//
//   VoxelBRepPipelineExample [output.vtp] [N]
//
// Builds an N^3 phantom (default 64), extracts the boundary of each of its labels as
// triangulated maximal faces, writes it (default voxelbrep_example.vtp) and prints the
// statistics the filter stores in the output's field data.
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkEVMBoundaryFilter.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkVoxelPhantomSource.h"
#include "vtkXMLPolyDataWriter.h"

#include <cstdlib>
#include <iostream>

namespace
{
vtkIdType fieldValue(vtkPolyData* data, const char* name)
{
  vtkDataArray* array = data->GetFieldData()->GetArray(name);
  return array ? static_cast<vtkIdType>(array->GetTuple1(0)) : -1;
}
}

int main(int argc, char* argv[])
{
  const char* fileName = argc > 1 ? argv[1] : "voxelbrep_example.vtp";
  const int n = argc > 2 ? std::atoi(argv[2]) : 64;
  if (n < 1)
  {
    std::cerr << "usage: " << argv[0] << " [output.vtp] [N >= 1]\n";
    return EXIT_FAILURE;
  }

  vtkNew<vtkVoxelPhantomSource> phantom;
  phantom->SetDimensions(n, n, n);

  vtkNew<vtkEVMBoundaryFilter> boundary;
  boundary->SetInputConnection(phantom->GetOutputPort());
  boundary->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Labels");
  boundary->SetSelectionModeToLabels(); // each label its own closed boundary
  boundary->SetOutputModeToTriangles(); // or Polygons: fewer cells, also drawn right

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(boundary->GetOutputPort());
  writer->SetFileName(fileName);
  // Inline binary rather than the default appended data: VTK 9.2's readers cannot parse
  // appended data with the expat of current Debian 12 (VTK issue 19258).
  writer->SetDataModeToBinary();
  if (writer->Write() != 1)
  {
    std::cerr << "could not write " << fileName << "\n";
    return EXIT_FAILURE;
  }

  vtkPolyData* output = boundary->GetOutput();
  std::cout << "phantom " << n << "^3: " << fieldValue(output, "NumberOfVoxels") << " voxels, "
            << fieldValue(output, "NumberOfSurfels") << " surfels, "
            << fieldValue(output, "NumberOfExtremeVertices") << " extreme vertices, "
            << fieldValue(output, "NumberOfFaces") << " faces, "
            << fieldValue(output, "NumberOfHoles") << " holes, " << output->GetNumberOfCells()
            << " triangles -> " << fileName << "\n";
  if (output->GetNumberOfCells() == 0 || !output->GetCellData()->GetArray("FaceId"))
  {
    std::cerr << "unexpected empty output\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
