// Distributed execution under ParaView's MPI (vtkMultiProcessController): how a rank's piece
// of an image maps to the whole, and the exchange that gives every filter the 1-rank result.
// Private to the module (not wrapped, not installed).
//
// Ownership. pvbatch and pvserver hand each rank an extent of the image; neighbouring pieces
// share one plane of points, and carry ghost layers (vtkGhostType) when a filter downstream
// asks for them. A rank owns:
// - with cell scalars, the cells of its piece that are not ghosts (DUPLICATECELL);
// - with point scalars, the points of its piece that are not ghosts (DUPLICATEPOINT), minus
//   the upper plane of points along each axis where the piece does not reach the whole
//   extent's upper end (that plane belongs to the neighbour above).
// So every voxel of the whole image is owned by exactly one rank, and ghost voxels are never
// objects of their own.
//
// Exchange. The Extreme Vertices Model of a union of disjoint voxel sets is the XOR of their
// EVMs (a vertex is extreme when an odd number of voxels meet at it, and counts add up over
// disjoint sets). Each rank extracts the EVM of its owned voxels, object by object (a label,
// or the whole selection), in the whole image's voxel coordinates, and sends it to rank 0:
// far fewer values than voxels (the EVM holds only the corners of the selection). Rank 0
// merges the EVMs of each label by XOR and processes the whole selection from them exactly
// as a single process would, so its faces, components and counts are the 1-rank ones, each
// output once, by rank 0. Messages: a count per rank (Gather), then per rank its status, its
// objects' label bits and vertices (GatherV of 64-bit values), then the status of all
// (Broadcast). CUDB connectivity adds one broadcast of the boxes and one of the region
// numbering, so that every rank writes the RegionIds of its own piece (ghosts included).
//
// Without MPI, in a serial ParaView or with one rank, nothing of this runs.
#ifndef vtkVoxelBRepDistributed_h
#define vtkVoxelBRepDistributed_h

#include "vtkVoxelBRepAdapters.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;

namespace vbr
{
namespace vtk
{

/// The global controller when it has more than one process, else null.
vtkMultiProcessController* distributedController();

/// The piece `image` is of the whole extent in the algorithm's input information, with
/// `cellData` scalars: the whole image's grid and the voxels this rank owns. Returns a
/// problem, or an empty string. Without a controller, a piece that is not distributed.
std::string describePiece(vtkMultiProcessController* controller,
  vtkInformation* inputInformation,
  vtkImageData* image,
  bool cellData,
  bool flatImagesAs2D,
  Piece& piece);

/// The owned voxels of the piece in processing axes.
Box3 ownedBox(const Piece& piece, const std::array<int, 3>& axes);

/// Collective: gathers the objects of every rank on rank 0 as EVMs and merges them there (see
/// the file comment). On rank 0 `in` then holds the whole image's grid and objects; on the
/// other ranks no objects. `ok` is this rank's status; returns false on every rank when any
/// rank failed.
bool mergeObjectsOnFirstRank(bool ok, Piece& piece, InputObjects& in);

/// Collective, from rank 0: `values` (resized on the other ranks). False on failure.
bool broadcastValues(Piece& piece, std::vector<long long>& values);

} // namespace vtk
} // namespace vbr

#endif
