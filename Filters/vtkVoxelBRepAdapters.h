// Shared adaptation of VTK data to the VTK-free core: where the voxels of an image are, how
// grid vertices map to world coordinates, and vtkSMPTools as the core's parallel loop.
// Private to the module (not wrapped, not installed).
#ifndef vtkVoxelBRepAdapters_h
#define vtkVoxelBRepAdapters_h

#include "Execution.h"
#include "Selection.h"

#include "vtkDataArray.h"
#include "vtkType.h"

#include <array>
#include <string>

class vtkAlgorithm;
class vtkImageData;

namespace vbr
{
namespace vtk
{

/// vtkSMPTools as parallel loop; progress goes to the algorithm, whose abort flag stops work.
Execution makeExecution(vtkAlgorithm* algorithm, double progressFrom, double progressTo);

/// The voxel grid an image's scalars describe.
struct VoxelGrid
{
  bool cellData = false;
  std::array<std::int32_t, 3> dims{ 0, 0, 0 };  ///< voxels along each axis
  std::array<int, 3> extentMin{ 0, 0, 0 };      ///< index of the first point
  std::array<double, 3> vertexShift{ 0, 0, 0 }; ///< index of grid vertex 0 minus extentMin
  std::array<double, 3> origin{ 0, 0, 0 };
  std::array<double, 3> spacing{ 1, 1, 1 };
  std::array<double, 9> direction{ 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  int flatAxis = -1; ///< the axis with a single voxel when the image is 2D, else -1

  /// World position of grid vertex (i, j, k) (voxel i spans vertices i and i + 1).
  void vertexToWorld(const std::array<std::int32_t, 3>& v, double world[3]) const;
};

/// Describes the voxels of `image` carried by `scalars` (point or cell data). Returns an
/// empty string on success, else a message for vtkErrorMacro.
std::string describeVoxels(vtkImageData* image,
  vtkDataArray* scalars,
  bool cellData,
  bool flatImagesAs2D,
  VoxelGrid& grid);

template<typename T, typename F>
void callWithGrid(void* raw, int nc, int component, const VoxelGrid& grid, F& f)
{
  ScalarGrid<T> sg;
  sg.data = static_cast<const T*>(raw) + component;
  sg.dims = grid.dims;
  sg.stride = {
    nc, std::int64_t(nc) * grid.dims[0], std::int64_t(nc) * grid.dims[0] * grid.dims[1]
  };
  f(sg);
}

/// Calls f(ScalarGrid<T>) with the typed component `component` of `scalars`; false if the
/// array type is not a plain numeric array.
template<typename F>
bool dispatchScalars(vtkDataArray* scalars, int component, const VoxelGrid& grid, F&& f)
{
  const int nc = scalars->GetNumberOfComponents();
  void* raw = scalars->GetVoidPointer(0);
  switch (scalars->GetDataType())
  {
    vtkTemplateMacro(callWithGrid<VTK_TT>(raw, nc, component, grid, f));
    default:
      return false;
  }
  return true;
}

} // namespace vtk
} // namespace vbr

#endif
