/**
 * @class   vtkStandardPlaneReversion
 * @brief   the voxels back from standard faces alone
 *
 * vtkStandardPlaneReversion reads the StandardFaces output of vtkStandardPlanePolyhedrizer (one
 * polygon per face along its boundary loop, counter-clockwise seen from outside, with the
 * cell arrays `PlaneNormal` and `PlaneOffset`), or its TriangulatedFaces output (the default:
 * each face's loop is rebuilt from the triangles of its `FaceId`, along the edges `LoopEdges`
 * marks, or without that array along the edges no other triangle of the face shares), and
 * recomputes the voxels: for each face, the
 * surfels of its standard plane enclosed by its loop; then the voxels by parity. Faces of
 * different `Label` values are reverted separately (a label map's objects share boundaries).
 *
 * The voxel grid comes from the field data the polyhedrizer writes: `VoxelGridOrigin` (world
 * position of voxel corner (0, 0, 0)), `VoxelGridSpacing` and `VoxelGridDimensions` (voxels
 * along each axis), and the layout of the image the faces came from: `VoxelGridExtent`,
 * `VoxelGridImageOrigin` and `VoxelGridAssociation` (vtkDataObject::FIELD_ASSOCIATION_POINTS
 * or FIELD_ASSOCIATION_CELLS, the association of the scalars the voxels were selected from).
 *
 * One convention, shared with the polyhedrizer's output port 1: the reversion has the layout
 * of the input the faces came from (the same extent, origin, spacing and association), with
 * an unsigned char array `Selection` (1 on the voxels) as its scalars and, when the faces
 * carry `Label`, an array `Label` of the same association and of the faces' Label type
 * (labels stay exact). Faces written without the
 * layout fields (older files) give cell data on the grid of voxel corners: extent 0 to
 * `VoxelGridDimensions`, origin `VoxelGridOrigin`.
 *
 * The input is checked before use: every array has one tuple per face, planes and corners
 * are whole numbers within range (no NaN, no overflow), the grid is finite and at most
 * 2^20 - 1 voxels per axis and 2^33 in all; faces given twice (or sharing surfels) are an
 * error. Faces made from an image with a direction matrix (field `VoxelGridDirection` not
 * the identity) are not supported: the filter reports an error.
 *
 * Under MPI (ParaView running the filter on N ranks) the faces are on rank 0 (see
 * vtkStandardPlanePolyhedrizer): rank 0 outputs the whole image, the other ranks none.
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

  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
};

#endif
