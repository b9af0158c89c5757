// Connected components of a set of voxels labelled on the runs of its rows, the way scan-line
// labelling does it (and scipy.ndimage.label): every row of the bit volume is cut into its runs
// of set voxels along x, each run is an element of a union-find, and a run is united with the
// runs of the neighbouring rows it touches. With face connectivity the neighbours of row (y, z)
// are rows (y - 1, z) and (y, z - 1) (the rows after it find it in turn) and two runs touch
// when they overlap; with vertex connectivity they are the four rows (y - 1, z), (y, z - 1),
// (y - 1, z - 1) and (y + 1, z - 1), and a run is widened by one voxel at each end (a diagonal
// contact is enough). Runs are numbered in scan order (z, then y, then x), so the union-find's
// roots are the first runs of their components and the components come out numbered in the
// order of their first run.
//
// That is the order in which the CUDB sweep in the ZYX sorting meets them: the first run of a
// component begins a box, whose origin is the earliest of the component's. So the runs give the
// CUDB connectivity's labels, and, since the CUDB in that sorting is fixed by the voxels, its
// counts too: a CUDB rectangle of a slice is a chain of equal runs in consecutive rows (the 2D
// compaction), and a box a chain of equal rectangles in consecutive planes (the 3D compaction),
// so a run begins a box when it has no equal run in the row before and the plane before holds
// no rectangle equal to the one it begins. The OUDB cuts a box at every plane and line of
// vertices, that is wherever a plane differs from the one before or a row from the one before
// in its plane; the extreme vertices are the lattice points with an odd number of set voxels
// among their eight. The boxes themselves follow: a box begins at such a run, spans its x
// interval, the rows of its chain of equal runs, and the planes of its chain of equal
// rectangles, and the boxes come in the scan order of their first runs, which is the sweep's
// (by z, then y, then x where they begin). Where a box is barely larger than a run (porous
// volumes: 1.4 rows a box), labelling the runs does without the EVM, its sections and the
// sweep's three levels of merges.
#ifndef vbr_RunLabelling_h
#define vbr_RunLabelling_h

#include "BitVolume.h"
#include "CUDB.h"
#include "Execution.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

/// A run [x0, x1) of set voxels along a row.
struct VoxelRun
{
  std::int32_t x0 = 0, x1 = 0;
};

/// The runs of set voxels of every row of a bit volume, in scan order.
struct VoxelRuns
{
  std::array<std::int32_t, 3> dims{ 0, 0, 0 };
  std::vector<VoxelRun> runs;
  /// The runs of row (y, z) are runs[rowStarts[r]] to runs[rowStarts[r + 1] - 1], r = z * ny + y.
  std::vector<std::uint32_t> rowStarts;

  std::size_t rowOf(std::int32_t y, std::int32_t z) const
  {
    return static_cast<std::size_t>(z) * static_cast<std::size_t>(this->dims[1]) +
      static_cast<std::size_t>(y);
  }
  bool empty() const { return this->runs.empty(); }
};

/// The runs of `voxels` (one pass to count them, one to write them; parallel over planes).
/// Throws std::length_error past 2^32 - 1 runs. Returns false when aborted.
bool extractRuns(const BitVolume& voxels, const Execution& exec, VoxelRuns& out);

/// The components of the runs and what the CUDB of the same voxels (ZYX sorting) counts.
struct RunComponents
{
  std::vector<std::uint32_t> runLabel; ///< 1..count per run, in order of first run
  std::uint32_t count = 0;
  /// 1 where the run begins a box of the CUDB (the box's first row in its first plane).
  std::vector<std::uint8_t> beginsBox;
  std::size_t boxCount = 0;        ///< CUDB boxes
  std::size_t oudbBoxCount = 0;    ///< OUDB boxes
  std::size_t extremeVertices = 0; ///< vertices of the EVM
  /// With `withBoxes`: the CUDB's boxes themselves (those of buildCUDB of the voxels' EVM in
  /// the ZYX sorting, in its order: by z, then y, then x where they begin) and the label of each
  /// box (labelComponents' boxLabel: the label of the run that begins it).
  std::vector<Box> boxes;
  std::vector<std::uint32_t> boxLabel;
};

/// The working memory of labelRuns (its union-find, the compaction notes, the boxes of the
/// runs), kept by a caller that labels one image after another and passed to every call: the
/// next call of as many runs or fewer writes into it rather than into new blocks, which the
/// allocator had often returned to the kernel in between and the kernel faulted in and zeroed
/// again (with the outputs' vectors, 2,793 page faults an update of a 128^3 checkerboard,
/// 256 with them kept). extractRuns and labelRuns likewise write their outputs into the vectors of
/// `out` when they are large enough.
struct RunLabellingScratch
{
  std::vector<std::uint32_t> parents;
  std::vector<std::uint32_t> notes;
  std::vector<std::uint32_t> boxOfRun;

  /// The bytes held.
  std::size_t bytes() const
  {
    return (this->parents.capacity() + this->notes.capacity() + this->boxOfRun.capacity()) *
      sizeof(std::uint32_t);
  }
};

/// How labelRuns finds the runs of two neighbour rows that touch: by a walk over the runs of
/// both rows, by a scan of the words of their bits (one step a word and one a contact: rows
/// of many short runs), or, by default, whichever costs less for the rows' numbers of runs.
/// The result is the same. BitsPortable is Bits counting the words' bits without the
/// processor's instruction where the build has a copy of its own for that instruction (x86-64
/// builds that do not assume it), for tests of the other copy; elsewhere it is Bits.
enum class ContactSearch
{
  Adaptive,
  Runs,
  Bits,
  BitsPortable
};

/// Labels the runs of `voxels` (as extractRuns gave them) with `connectivity`, and counts the
/// CUDB's boxes, the OUDB's and the EVM's vertices. With several threads (exec.concurrency) and
/// many runs, pieces of consecutive planes are labelled concurrently and then joined; the
/// result is the same. Asks `exec` whether to stop every few planes and reports its progress;
/// returns false when aborted. With `withBoxes`, builds the CUDB's boxes too (RunComponents::
/// boxes): a box is a rectangle (a run and the chain of equal runs in the rows after it), grown
/// through the planes after it while they hold an equal rectangle. With `scratch`, its working
/// memory comes from there and is left there. `search`: see ContactSearch. `runs` must be
/// extractRuns(voxels): the rows' bits give the runs' numbers. Throws std::invalid_argument
/// when they are not even runs of a volume of the size of `voxels` (other runs of that size
/// are not detected).
bool labelRuns(const BitVolume& voxels,
  const VoxelRuns& runs,
  Connectivity connectivity,
  const Execution& exec,
  RunComponents& out,
  bool withBoxes = false,
  RunLabellingScratch* scratch = nullptr,
  ContactSearch search = ContactSearch::Adaptive);

/// Writes value[runLabel[i]] into every voxel of run i (value 0 are skipped) of `labels`, a grid
/// of `dims` voxels stored x fastest, the runs' voxel (x, y, z) at (x, y, z) + offset. Voxels of
/// no run are left as they are, unless `zeroAround`: then the grid must hold 0 on the rows of the
/// runs, from the runs' box to the row's end, and nothing else may write there: the runs are
/// written by wide stores that zero the voxels after them (see paintRun). Parallel over planes;
/// false when stopped (partly written).
bool paintRuns(const VoxelRuns& runs,
  const std::vector<std::uint32_t>& runLabel,
  const std::vector<std::int32_t>& value,
  const std::array<std::int32_t, 3>& offset,
  const std::array<std::int32_t, 3>& dims,
  std::int32_t* labels,
  const Execution& exec = Execution(),
  bool zeroAround = false);

/// paintRuns into a grid of any content: every voxel of `labels` is written, a run's value (0
/// where it is 0) or 0, so the grid need not be zeroed first (memory an earlier update used).
/// Each row is zeroed while in the CPU cache and its runs then painted by the wide stores of
/// `zeroAround`: the grid is written once, not zeroed by the kernel and written again.
/// Parallel over planes; false when stopped (partly written).
bool paintRunsOverwriting(const VoxelRuns& runs,
  const std::vector<std::uint32_t>& runLabel,
  const std::vector<std::int32_t>& value,
  const std::array<std::int32_t, 3>& offset,
  const std::array<std::int32_t, 3>& dims,
  std::int32_t* labels,
  const Execution& exec = Execution());

} // namespace vbr

#endif
