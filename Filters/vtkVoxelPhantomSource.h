/**
 * @class   vtkVoxelPhantomSource
 * @brief   procedural label volume with nested shells, holes, a handle and non-manifold
 *          contacts
 *
 * Produces an unsigned char image of Dimensions voxels (point scalars "Labels", 0 is
 * background) holding: 1, a spherical shell with a cavity and a ball inside it (nested
 * shells); 2, a torus (a handle); 3, a plate pierced by a row of square holes; 4, a hollow
 * square frame; 5, three boxes touching along an edge and at a corner only (non-manifold
 * contacts). All parts scale with the dimensions, so the same shapes exist at every size. It
 * is the default input of the VoxelBRep examples and benchmarks.
 *
 * It produces any sub-extent asked for (CAN_PRODUCE_SUB_EXTENT), computing only that piece:
 * under MPI each rank makes its own piece.
 *
 * Pieces whose image (and the phantom's own copy: two bytes per voxel) cannot fit in the
 * memory this process can allocate are refused with an error and an empty output.
 */
#ifndef vtkVoxelPhantomSource_h
#define vtkVoxelPhantomSource_h

#include "VoxelBRepFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class VOXELBREPFILTERS_EXPORT vtkVoxelPhantomSource : public vtkImageAlgorithm
{
public:
  static vtkVoxelPhantomSource* New();
  vtkTypeMacro(vtkVoxelPhantomSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of voxels along x, y and z. The default is 128 x 128 x 128.
   */
  vtkSetVector3Macro(Dimensions, int);
  vtkGetVector3Macro(Dimensions, int);
  ///@}

protected:
  vtkVoxelPhantomSource();
  ~vtkVoxelPhantomSource() override = default;

  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  void ExecuteDataWithInformation(vtkDataObject* output, vtkInformation* outInfo) override;

  int Dimensions[3] = { 128, 128, 128 };

private:
  vtkVoxelPhantomSource(const vtkVoxelPhantomSource&) = delete;
  void operator=(const vtkVoxelPhantomSource&) = delete;
};

#endif
