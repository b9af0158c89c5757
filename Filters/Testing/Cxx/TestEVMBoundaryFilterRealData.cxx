// The paper's extreme-vertex counts through the filter: aneurism and engine at value >= 55
// give 70,260 and 85,866 extreme vertices (Ayala & Vergara, Table 1). Skipped when the shared
// data directory is absent.
#include "vtkEVMBoundaryFilter.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <fstream>
#include <iostream>
#include <string>

namespace
{

bool load(const std::string& path, int nx, int ny, int nz, vtkImageData* image)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return false;
  image->SetDimensions(nx, ny, nz);
  vtkNew<vtkUnsignedCharArray> a;
  a->SetName("density");
  a->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  in.read(reinterpret_cast<char*>(a->GetPointer(0)), a->GetNumberOfTuples());
  image->GetPointData()->SetScalars(a);
  return static_cast<bool>(in);
}

vtkIdType value(vtkPolyData* out, const char* name, int component = 0)
{
  return static_cast<vtkIdType>(out->GetFieldData()->GetArray(name)->GetComponent(0, component));
}

} // namespace

int TestEVMBoundaryFilterRealData(int, char*[])
{
  struct Case
  {
    const char* file;
    int dims[3];
    vtkIdType evs;
    vtkIdType planes[3];
  } cases[] = {
    { "/aneurism/aneurism_256x256x256_uint8.raw", { 256, 256, 256 }, 70260, { 215, 216, 237 } },
    { "/engine/engine_256x256x128_uint8.raw", { 256, 256, 128 }, 85866, { 142, 199, 109 } }
  };
  int failures = 0, found = 0;
  for (const Case& c : cases)
  {
    vtkNew<vtkImageData> image;
    if (!load(std::string(VOXELBREP_DATA_DIR) + c.file, c.dims[0], c.dims[1], c.dims[2], image))
      continue;
    ++found;
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(image);
    f->SetSelectionModeToRange();
    f->SetLowerThreshold(55);
    f->SetOutputModeToLoops();
    f->Update();
    vtkPolyData* out = f->GetOutput();
    const vtkIdType evs = value(out, "NumberOfExtremeVertices");
    std::cout << c.file << ": " << evs << " extreme vertices, " << value(out, "NumberOfFaces")
              << " faces, " << value(out, "NumberOfSurfels") << " surfels, "
              << out->GetNumberOfCells() << " polygons" << std::endl;
    if (evs != c.evs)
    {
      std::cerr << c.file << ": expected " << c.evs << " extreme vertices" << std::endl;
      ++failures;
    }
    for (int k = 0; k < 3; ++k)
      if (value(out, "NumberOfPlanesOfVertices", k) != c.planes[k])
      {
        std::cerr << c.file << ": planes of vertices along axis " << k << " differ" << std::endl;
        ++failures;
      }
    // Faces are maximal: fewer polygons than surfels, and the surfel count matches the
    // Surfels mode's cell count.
    f->SetOutputModeToSurfels();
    f->Update();
    if (f->GetOutput()->GetNumberOfCells() != value(f->GetOutput(), "NumberOfSurfels"))
    {
      std::cerr << c.file << ": Surfels mode cell count differs from NumberOfSurfels" << std::endl;
      ++failures;
    }
  }
  if (found == 0)
  {
    std::cout << "Shared data not found under " << VOXELBREP_DATA_DIR << ": skipped" << std::endl;
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
