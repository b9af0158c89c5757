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
// Every filter gathers this way (EVM boundary, CUDB connectivity, standard-plane
// polyhedrizer, convex hull modifier, face octree boundary): their faces are those of the
// whole image, output once, by rank 0; the other ranks output none.
//
// Reversions. The filters whose port 1 is the image rebuilt from their faces (the
// polyhedrizer, the hull modifier) give every rank its own piece of it: rank 0 broadcasts the
// EVM of the rebuilt voxels of the whole image and the self-check's result; each rank crops
// the EVM to its piece (see scatterSelection) and rebuilds only the piece's voxels, ghosts
// included. So the reversion too costs extreme vertices, not voxels.
//
// Costs and limits. Rank 0 holds the whole image's objects (as bits, one object at a time
// where the filter allows) and does the whole computation; the other ranks only read and
// select their pieces. The distribution is for volumes read and selected on several
// machines, not a parallel speed-up. An exception on one rank (out of memory) between two
// collective steps leaves the others waiting at the next one.
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
class vtkDataSet;
class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;
class vtkUnsignedCharArray;

namespace vbr
{
namespace vtk
{

/// The global controller when it has more than one process and the algorithm is asked for
/// one of as many pieces (a pipeline run by ParaView on every rank), else null: a filter run
/// on one rank alone (a script's own pipeline in pvbatch) is not distributed.
vtkMultiProcessController* distributedController(vtkAlgorithm* algorithm);

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
Box ownedBox(const Piece& piece, const std::array<int, 3>& axes);

/// Collective: gathers the objects of every rank on rank 0 as EVMs and merges them there (see
/// the file comment). On rank 0 `in` then holds the whole image's grid and objects; on the
/// other ranks no objects. `ok` is this rank's status; returns false on every rank when any
/// rank failed.
bool mergeObjectsOnFirstRank(bool ok, Piece& piece, InputObjects& in);

/// Collective, from rank 0: `values` (resized on the other ranks). False on failure.
bool broadcastValues(Piece& piece, std::vector<long long>& values);

/// Collective: the points of every rank's `points` (null: none) on rank 0, null elsewhere.
vtkSmartPointer<vtkDataSet> gatherPoints(Piece& piece, vtkDataSet* points);

/// Collective, from rank 0: the voxels that rank 0's `wholeSelection` marks (one value per
/// voxel of the whole image, image axes, x fastest; null when rank 0 failed) and its `status`,
/// to every rank, which writes the voxels of its own piece (`piece.local`, ghost voxels
/// included, x fastest) into `pieceSelection` as 0 and 1. On rank 0 `pieceSelection` may be
/// `wholeSelection` itself. Rank 0 sends the EVM of the marked voxels;
/// each rank crops it to its piece (a vertex below the piece's box is moved onto the box, one
/// above it dropped: the parity of the vertices at or below every voxel of the box is kept) and
/// rebuilds only its piece. Returns false on every rank when the exchange failed or rank 0 had
/// nothing to send; `status` is then 0.
bool scatterSelection(Piece& piece,
  vtkUnsignedCharArray* wholeSelection,
  int& status,
  vtkUnsignedCharArray* pieceSelection);

} // namespace vtk
} // namespace vbr

#endif
