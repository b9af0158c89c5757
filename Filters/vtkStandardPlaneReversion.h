/**
 * @class   vtkStandardPlaneReversion
 * @brief   the voxels back from standard faces alone
 *
 * vtkStandardPlaneReversion reads the StandardFaces output of vtkStandardPlanePolyhedrizer (one
 * polygon per face along its boundary loop, counter-clockwise seen from outside, with the
 * cell arrays `PlaneNormal` and `PlaneOffset`) and recomputes the voxels: for each face, the
 * surfels of its standard plane enclosed by its loop; then the voxels by parity. Faces of
 * different `Label` values are reverted separately (a label map's objects share boundaries).
 *
 * The voxel grid comes from the field data the polyhedrizer writes: `VoxelGridOrigin` (world
 * position of voxel corner (0, 0, 0)), `VoxelGridSpacing` and `VoxelGridDimensions` (voxels
 * along each axis). The output is an image whose cells are those voxels, with an unsigned char
 * cell array `Selection` (1 on the voxels) and, for label maps, an array `Label` of the faces'
 * Label type (labels stay exact). Faces made from an image with a direction matrix (field
 * `VoxelGridDirection` not the identity) are not supported: the filter reports an error.
 *
 * @sa vtkStandardPlanePolyhedrizer
 */
#ifndef vtkStandardPlaneReversion_h
#define vtkStandardPlaneReversion_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class VOXELBREPFILTERS_EXPORT vtkStandardPlaneReversion : public vtkImageAlgorithm
{
public:
  static vtkStandardPlaneReversion* New();
  vtkTypeMacro(vtkStandardPlaneReversion, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkStandardPlaneReversion();
  ~vtkStandardPlaneReversion() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkStandardPlaneReversion(const vtkStandardPlaneReversion&) = delete;
  void operator=(const vtkStandardPlaneReversion&) = delete;
};

#endif
