// Scan-line labelling of the runs of a bit volume's rows (see RunLabelling.h for the method).
//
// Passes: extractRuns counts the runs of every row (popcounts of the run starts) and writes
// them (bit scans of the rows' changes), parallel over planes; labelRuns sweeps the rows in
// scan order, merging each row's runs with those of its backward neighbour rows (uniteRow, or
// uniteRowBits from the rows' bits where the runs are short), and
// notes on the way the equal runs that the CUDB's compactions join (the row before, the plane
// before; uniteSequentially, or with threads uniteInPieces: pieces of planes swept concurrently,
// then joined plane to plane); boxBeginnings, countOUDBBoxes and countExtremeVertices turn those
// notes and the bits into the CUDB's counts, and buildBoxes (when asked) the notes into the
// CUDB's boxes; paintRuns writes a value per run into a label grid.
#include "RunLabelling.h"

#include "HugePages.h"

#include "Geometry.h"
#include "PopCount.h"
#include "UnionFind.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace vbr
{
namespace
{

constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();

/// The labelling's scratch is allocated anew at each update, and glibc often returns it to the
/// kernel in between (the top of its heap, or a mapping of its own), which then faulted it in
/// 4 KiB at a time: about 3 microseconds a page on the benchmark machine, where an update of a
/// 256^3 porous volume with 9,000 to 12,000 such faults took 95 to 100 ms of CPU, and 70 ms
/// with about 300. Hence its arrays on huge pages (HugePages.h), from the first whole one.

/// `v` emptied with room for n values: its own memory when it has room (kept from an earlier
/// labelling, already faulted in), else a new block on huge pages where they fill some.
template<typename T>
void emptyWithRoom(std::vector<T>& v, std::size_t n)
{
  v.clear();
  if (v.capacity() < n)
  {
    v = std::vector<T>();
    reserveHugePages(v, n, HugePageBytes);
  }
}

/// n values in `v`, in its memory when it has room (emptyWithRoom).
template<typename T>
void resizeOnHugePages(std::vector<T>& v, std::size_t n)
{
  emptyWithRoom(v, n);
  v.resize(n);
}

/// The number of runs of a row of bits (the bits past the row's end are clear): its run starts,
/// a set bit whose left neighbour is clear.
std::uint32_t countRowRuns(const Word* bits, std::size_t words)
{
  std::uint32_t n = 0;
  Word carry = 0;
  for (std::size_t w = 0; w < words; ++w)
  {
    const Word b = bits[w];
    n += static_cast<std::uint32_t>(popCount(b & ~((b << 1) | carry)));
    carry = b >> 63;
  }
  return n;
}

/// The runs of a row of bits from `out` on: a run starts or ends at x where bits x - 1 and x
/// differ. Returns the end of the output.
VoxelRun* writeRowRuns(const Word* bits, std::size_t words, VoxelRun* out)
{
  Word carry = 0;
  bool open = false;
  std::int32_t start = 0;
  for (std::size_t w = 0; w < words; ++w)
  {
    const Word b = bits[w];
    Word change = b ^ ((b << 1) | carry);
    carry = b >> 63;
    while (change)
    {
      const auto x = static_cast<std::int32_t>(w * 64 + countTrailingZeros(change));
      if (open)
        *out++ = { start, x };
      start = x;
      open = !open;
      change &= change - 1;
    }
  }
  if (open)
    *out++ = { start, static_cast<std::int32_t>(words * 64) };
  return out;
}

/// Unites every run of one row [a, aEnd) with the runs of a neighbour row [b, bEnd) it touches:
/// overlapping (Widen = 0) or also meeting diagonally at an end (Widen = 1). With `twin`, the
/// run of the neighbour row equal to run i (if any) is written to twin[i], and with `twinOf`,
/// i to twinOf[that run]. Both rows are sorted and their runs have gaps, so one forward walk
/// finds every pair; the union's root is carried from contact to contact rather than found
/// again from the run.
template<int Widen>
void uniteRow(UnionFind& uf,
  const VoxelRun* runs,
  std::uint32_t a,
  std::uint32_t aEnd,
  std::uint32_t b,
  std::uint32_t bEnd,
  std::uint32_t* twin,
  std::uint32_t* twinOf = nullptr)
{
  for (; a < aEnd; ++a)
  {
    const VoxelRun run = runs[a];
    // Runs of the neighbour row that end before this one begins meet no later run either.
    while (b < bEnd && runs[b].x1 + Widen <= run.x0)
      ++b;
    std::uint32_t root = a;
    for (std::uint32_t k = b; k < bEnd && runs[k].x0 < run.x1 + Widen; ++k)
    {
      root = uf.unite(k, root);
      if (twin && runs[k].x0 == run.x0 && runs[k].x1 == run.x1)
      {
        twin[a] = k;
        if (twinOf)
          twinOf[k] = a;
      }
    }
  }
}

/// The run starts of a word of a row's bits: set bits whose bit before (`carry`, the last bit
/// of the word before, for bit 0) is clear.
inline Word runStartsOf(Word bits, Word carry)
{
  return bits & ~((bits << 1) | carry);
}

/// A row's bits and the indices [first, end) of its runs.
struct RowBits
{
  const Word* bits;
  std::uint32_t first;
  std::uint32_t end;
};

/// uniteRow read from the rows' bits rather than their runs, for rows of many short runs
/// (noise, checkerboards), where the walk over the runs mispredicted a branch at nearly every
/// run. Every contact of a run of row a with a run of row b is a single bit position p of
/// the word scan: the start of an overlap (a run of the bits of a & b: one per overlapping
/// pair), and with vertex connectivity (Widen = 1) where the runs meet only diagonally, a run
/// of one row starting at p right after a run of the other ended at p - 1. The runs at p are
/// numbered by the run starts at p or before (the run ending at p - 1 for the row whose bit p
/// is clear), so the word scan costs a few bit operations a word and one iteration a contact;
/// rows without contacts (a face-connected checkerboard) cost no branch a run. The contacts
/// come in order of x, those of a run of row a together, and are those of uniteRow: the
/// classes, and so the labels, are the same. The runs' numbers come from counts of the bits,
/// so each RowBits' runs must be those of its bits: else the numbers go past them (checked at
/// the end in debug builds).
template<int Widen, bool HardwareCount>
VBR_ALWAYS_INLINE void uniteRowBitsWith(UnionFind& uf,
  const VoxelRun* runs,
  RowBits rowA,
  RowBits rowB,
  std::size_t words,
  std::uint32_t* twin,
  std::uint32_t* twinOf)
{
  std::uint32_t a = rowA.first, b = rowB.first;
  Word carryA = 0, carryB = 0;
  std::uint32_t lastA = None, root = None;
  for (std::size_t w = 0; w < words; ++w)
  {
    const Word bitsA = rowA.bits[w], bitsB = rowB.bits[w];
    const Word startsA = runStartsOf(bitsA, carryA), startsB = runStartsOf(bitsB, carryB);
    const Word both = bitsA & bitsB;
    Word contacts = runStartsOf(both, carryA & carryB);
    if (Widen)
      contacts |=
        (startsA & ~bitsB & ((bitsB << 1) | carryB)) | (startsB & ~bitsA & ((bitsA << 1) | carryA));
    while (contacts)
    {
      const int p = countTrailingZeros(contacts);
      const Word upToP = ~Word(0) >> (63 - p);
      const std::uint32_t i =
        a + static_cast<std::uint32_t>(bitCount<HardwareCount>(startsA & upToP)) - 1;
      const std::uint32_t k =
        b + static_cast<std::uint32_t>(bitCount<HardwareCount>(startsB & upToP)) - 1;
      root = i == lastA ? uf.uniteWithRoot(k, root) : uf.unite(k, i);
      lastA = i;
      // Equal runs start together at an overlap and end together.
      if (twin && ((startsA & startsB) >> p & 1) && runs[i].x1 == runs[k].x1)
      {
        twin[i] = k;
        if (twinOf)
          twinOf[k] = i;
      }
      contacts &= contacts - 1;
    }
    a += static_cast<std::uint32_t>(bitCount<HardwareCount>(startsA));
    b += static_cast<std::uint32_t>(bitCount<HardwareCount>(startsB));
    carryA = bitsA >> 63;
    carryB = bitsB >> 63;
  }
  assert(a == rowA.end && b == rowB.end);
}

/// uniteRowBitsWith, counting bits by popCount.
template<int Widen>
void uniteRowBits(UnionFind& uf,
  const VoxelRun* runs,
  RowBits rowA,
  RowBits rowB,
  std::size_t words,
  std::uint32_t* twin,
  std::uint32_t* twinOf)
{
  uniteRowBitsWith<Widen, false>(uf, runs, rowA, rowB, words, twin, twinOf);
}

#if VBR_POPCNT_COPY
/// uniteRowBitsWith compiled for processors with POPCNT.
template<int Widen>
__attribute__((target("popcnt"))) void uniteRowBitsPopCount(UnionFind& uf,
  const VoxelRun* runs,
  RowBits rowA,
  RowBits rowB,
  std::size_t words,
  std::uint32_t* twin,
  std::uint32_t* twinOf)
{
  uniteRowBitsWith<Widen, true>(uf, runs, rowA, rowB, words, twin, twinOf);
}
#endif

/// A uniteRowBits, or its copy compiled for POPCNT.
using RowBitsUniter = void (*)(UnionFind&,
  const VoxelRun*,
  RowBits,
  RowBits,
  std::size_t,
  std::uint32_t*,
  std::uint32_t*);

/// uniteRowBits, counting bits by the instruction when `popCountInstruction` (the processor
/// has it, and the build does not assume it).
template<int Widen>
RowBitsUniter pickUniteRowBits(bool popCountInstruction)
{
#if VBR_POPCNT_COPY
  if (popCountInstruction)
    return uniteRowBitsPopCount<Widen>;
#endif
  (void)popCountInstruction;
  return uniteRowBits<Widen>;
}

/// Where the CUDB compactions are read from: for every run, the equal run of the row before
/// and of the row after in its plane (chains of them are the rectangles, the 2D compaction), and
/// the equal run of the same row in the plane before (the 3D compaction); None where none.
struct CompactionNotes
{
  std::size_t size;
  /// The three notes of every run in one block, large enough for whole huge pages where three
  /// blocks of a run each (2 MB on 50 % noise at 128^3) held none.
  std::vector<std::uint32_t> storage;
  std::uint32_t* above = nullptr;
  std::uint32_t* below = nullptr;
  std::uint32_t* behind = nullptr;

  /// The notes of n runs in the memory of `memory` when it has room.
  CompactionNotes(std::size_t n, std::vector<std::uint32_t>&& memory)
    : size(n)
    , storage(std::move(memory))
  {
    assignHugePages(this->storage, 3 * n, None, HugePageBytes);
    this->above = this->storage.data();
    this->below = this->storage.data() + n;
    this->behind = this->storage.data() + 2 * n;
  }
  CompactionNotes(const CompactionNotes&) = delete;
  CompactionNotes& operator=(const CompactionNotes&) = delete;
};

/// Which backward neighbour rows of a plane's rows unitePlane reads: all, those of the plane
/// itself (the first plane of a piece labelled concurrently), or those of the plane before
/// (the same plane when the pieces are joined).
enum class NeighbourRows
{
  All,
  InPlane,
  PlaneBefore
};

/// What unitePlane reads: the runs, and the bits of the rows for the rows of short runs.
struct RowSource
{
  const VoxelRuns& runs;
  const BitVolume& voxels;
  ContactSearch search;
  /// Whether uniteRowBits counts bits by the instruction: where the processor has it, unless
  /// the portable count is asked for (ContactSearch::BitsPortable).
  bool popCountInstruction = search != ContactSearch::BitsPortable && hasPopCountInstruction();

  /// Whether rows a and b of `na` and `nb` runs are united from their bits (uniteRowBits):
  /// when asked, or, adaptively, when the two rows hold more than 8 runs a word together (runs
  /// and gaps of under 16 voxels on average: noise, checkerboards), where the word scan costs
  /// less than the walk's mispredicted branches. Below that (porous volumes, real images) the
  /// two cost about the same and the walk is kept: the choice itself is a branch per pair of
  /// rows, mispredicted where rows fall on either side of it.
  bool fromBits(std::uint32_t na, std::uint32_t nb) const
  {
    if (this->search != ContactSearch::Adaptive)
      return this->search != ContactSearch::Runs;
    return na + nb > 8 * this->voxels.wordsPerRow();
  }
};

/// Unites the runs of row (y, z) with those of row (yb, zb), by uniteRow or `uniteFromBits`
/// (a uniteRowBits). Inlined at each neighbour row, as uniteRow was: a walk of its own for each,
/// whose branches are predicted apart (one shared walk mispredicted about 40 % more on real
/// volumes).
template<int Widen>
VBR_ALWAYS_INLINE void uniteRows(const RowSource& src,
  RowBitsUniter uniteFromBits,
  UnionFind& uf,
  std::int32_t y,
  std::int32_t z,
  std::int32_t yb,
  std::int32_t zb,
  std::uint32_t* twin,
  std::uint32_t* twinOf = nullptr)
{
  const VoxelRuns& r = src.runs;
  const std::size_t row = r.rowOf(y, z), other = r.rowOf(yb, zb);
  const std::uint32_t a = r.rowStarts[row], aEnd = r.rowStarts[row + 1];
  const std::uint32_t b = r.rowStarts[other], bEnd = r.rowStarts[other + 1];
  if (b == bEnd)
    return;
  if (src.fromBits(aEnd - a, bEnd - b))
    uniteFromBits(uf,
      r.runs.data(),
      { src.voxels.row(y, z), a, aEnd },
      { src.voxels.row(yb, zb), b, bEnd },
      src.voxels.wordsPerRow(),
      twin,
      twinOf);
  else
    uniteRow<Widen>(uf, r.runs.data(), a, aEnd, b, bEnd, twin, twinOf);
}

/// The rows (y, z) of one plane united with their backward neighbour rows: (y - 1, z) and
/// (y, z - 1), and with vertex connectivity (Widen = 1) (y - 1, z - 1) and (y + 1, z - 1) too.
template<int Widen>
void unitePlane(const RowSource& src,
  std::int32_t z,
  NeighbourRows which,
  UnionFind& uf,
  CompactionNotes& notes)
{
  const VoxelRuns& r = src.runs;
  const std::int32_t ny = r.dims[1];
  const std::uint32_t* starts = r.rowStarts.data();
  const RowBitsUniter uniteFromBits = pickUniteRowBits<Widen>(src.popCountInstruction);
  for (std::int32_t y = 0; y < ny; ++y)
  {
    const std::size_t row = r.rowOf(y, z);
    if (starts[row] == starts[row + 1])
      continue;
    if (y > 0 && which != NeighbourRows::PlaneBefore)
      uniteRows<Widen>(src, uniteFromBits, uf, y, z, y - 1, z, notes.above, notes.below);
    if (z == 0 || which == NeighbourRows::InPlane)
      continue;
    uniteRows<Widen>(src, uniteFromBits, uf, y, z, y, z - 1, notes.behind);
    if (Widen == 0)
      continue;
    if (y > 0)
      uniteRows<Widen>(src, uniteFromBits, uf, y, z, y - 1, z - 1, nullptr);
    if (y + 1 < ny)
      uniteRows<Widen>(src, uniteFromBits, uf, y, z, y + 1, z - 1, nullptr);
  }
}

/// unitePlane for a connectivity given at run time.
void unitePlane(const RowSource& r,
  std::int32_t z,
  NeighbourRows which,
  Connectivity connectivity,
  UnionFind& uf,
  CompactionNotes& notes)
{
  if (connectivity == Connectivity::Face)
    unitePlane<0>(r, z, which, uf, notes);
  else
    unitePlane<1>(r, z, which, uf, notes);
}

/// How many pieces of consecutive planes to label concurrently: one per thread when the runs
/// are many and each piece keeps several planes, else one.
int labellingPieces(std::size_t runs, std::int32_t planes, int concurrency)
{
  if (concurrency < 2 || runs < (std::size_t(1) << 16))
    return 1;
  return std::max(1, std::min(concurrency, planes / 8));
}

/// All planes united in one sweep on the calling thread, with progress and abort.
bool uniteSequentially(const RowSource& r,
  Connectivity connectivity,
  const Execution& exec,
  UnionFind& uf,
  CompactionNotes& notes)
{
  const std::int32_t nz = r.runs.dims[2];
  ProgressPoll poll(exec, 0.0, 0.8, 4);
  for (std::int32_t z = 0; z < nz; ++z)
  {
    unitePlane(r, z, NeighbourRows::All, connectivity, uf, notes);
    poll.at(static_cast<double>(z + 1) / nz);
    if (!poll.tick())
      return false;
  }
  return true;
}

/// The planes cut into `pieces` runs of consecutive planes united concurrently, then joined:
/// the first plane of each piece but the first with the plane before. A piece's runs are
/// consecutive numbers that only its own unions touch, so the pieces share the union-find and
/// the notes without locks; the classes, and their smallest elements, are the sequential
/// sweep's. Workers ask whether to stop after every plane.
bool uniteInPieces(const RowSource& r,
  Connectivity connectivity,
  int pieces,
  const Execution& exec,
  UnionFind& uf,
  CompactionNotes& notes)
{
  const std::int32_t nz = r.runs.dims[2];
  auto firstPlane = [nz, pieces](std::int64_t piece)
  { return static_cast<std::int32_t>(nz * piece / pieces); };
  std::atomic<bool> stopped{ false };
  exec.forRange(pieces,
    [&](std::int64_t begin, std::int64_t end)
    {
      for (std::int64_t piece = begin; piece < end; ++piece)
        for (std::int32_t z = firstPlane(piece); z < firstPlane(piece + 1) && !stopped; ++z)
        {
          const bool first = z == firstPlane(piece);
          unitePlane(
            r, z, first ? NeighbourRows::InPlane : NeighbourRows::All, connectivity, uf, notes);
          if (exec.stopRequested())
            stopped = true;
        }
    });
  if (stopped || !exec.report(0.7))
    return false;
  for (int piece = 1; piece < pieces; ++piece)
    unitePlane(r, firstPlane(piece), NeighbourRows::PlaneBefore, connectivity, uf, notes);
  return exec.report(0.8);
}

/// Whether the rectangles whose first runs are a and b have as many rows.
bool sameHeight(const CompactionNotes& notes, std::uint32_t a, std::uint32_t b)
{
  for (;;)
  {
    a = notes.below[a];
    b = notes.below[b];
    if (a == None || b == None)
      return a == b;
  }
}

/// The runs that begin a CUDB box: the first run of a rectangle (no equal run in the row before)
/// whose plane before holds no equal rectangle, that is no rectangle beginning with the equal
/// run of the same row and as many rows high. Returns the number of boxes.
std::size_t boxBeginnings(const CompactionNotes& notes, std::vector<std::uint8_t>& begins)
{
  const std::size_t n = notes.size;
  begins.assign(n, 0);
  std::size_t boxes = 0;
  for (std::uint32_t i = 0; i < n; ++i)
  {
    if (notes.above[i] != None)
      continue;
    const std::uint32_t back = notes.behind[i];
    const bool continued = back != None && notes.above[back] == None && sameHeight(notes, i, back);
    begins[i] = !continued;
    boxes += !continued;
  }
  return boxes;
}

/// The number of rows of the rectangle whose first run is `first`: its chain of equal runs.
std::int32_t rectangleHeight(const CompactionNotes& notes, std::uint32_t first)
{
  std::int32_t rows = 1;
  for (std::uint32_t i = notes.below[first]; i != None; i = notes.below[i])
    ++rows;
  return rows;
}

/// The CUDB's boxes from the runs, in its order, and their beginnings as boxBeginnings marks
/// them (in the same pass: its branches, taken once, mispredicted as often as the runs vary);
/// returns the number of boxes. The sweep meets the rectangles of a plane by their first row,
/// then x, and appends those that begin a box, so the boxes come in the scan order of the runs
/// that begin them. A rectangle that continues a box (the equal rectangle of the plane before)
/// moves the box's end along z to its own plane; the rectangle's box is noted at its first run,
/// where the rectangle of the plane after finds it (`behind`).
std::size_t buildBoxes(const VoxelRuns& r,
  const CompactionNotes& notes,
  const std::vector<std::uint32_t>& runLabel,
  std::vector<std::uint8_t>& begins,
  std::vector<Box>& boxes,
  std::vector<std::uint32_t>& boxLabel,
  std::vector<std::uint32_t>& boxOfRun)
{
  const std::size_t n = r.runs.size();
  begins.assign(n, 0);
  // Room for a box per run, touched only as far as the boxes go; each box is written field by
  // field (a box built on the stack and pushed back was copied by a wide load of narrow
  // stores, which stalled every box).
  boxes = std::vector<Box>();
  boxLabel = std::vector<std::uint32_t>();
  reserveHugePages(boxes, n, HugePageBytes);
  reserveHugePages(boxLabel, n, HugePageBytes);
  assignHugePages(boxOfRun, n, None, HugePageBytes);
  const std::int32_t ny = r.dims[1], nz = r.dims[2];
  for (std::int32_t z = 0; z < nz; ++z)
    for (std::int32_t y = 0; y < ny; ++y)
    {
      const std::size_t row = r.rowOf(y, z);
      for (std::uint32_t i = r.rowStarts[row]; i < r.rowStarts[row + 1]; ++i)
      {
        if (notes.above[i] != None) // inside a rectangle, not its first run
          continue;
        const std::uint32_t back = notes.behind[i];
        if (back != None && notes.above[back] == None && sameHeight(notes, i, back))
        {
          const std::uint32_t box = boxOfRun[back];
          boxOfRun[i] = box;
          boxes[box].hi[2] = z + 1;
          continue;
        }
        begins[i] = 1;
        boxOfRun[i] = static_cast<std::uint32_t>(boxes.size());
        const VoxelRun run = r.runs[i];
        Box& box = boxes.emplace_back();
        box.lo[0] = run.x0;
        box.lo[1] = y;
        box.lo[2] = z;
        box.hi[0] = run.x1;
        box.hi[1] = y + rectangleHeight(notes, i);
        box.hi[2] = z + 1;
        boxLabel.push_back(runLabel[i]);
      }
    }
  return boxes.size();
}

/// Whether `words` words from a and from b are equal. Rows of one or two words (images up to
/// 128 voxels wide) are compared inline: a call of memcmp per row was a few percent of the
/// labelling of a 64-voxel-wide head.
bool sameWords(const Word* a, const Word* b, std::size_t words)
{
  if (words <= 2)
    return a[0] == b[0] && (words == 1 || a[1] == b[1]);
  return std::memcmp(a, b, words * sizeof(Word)) == 0;
}

/// The OUDB's boxes: each slice (planes equal to the one before belong to its slice) cut at
/// every line of vertices (rows equal to the one before belong to its line), one box per run
/// of the first row of a line in the first plane of a slice.
std::size_t countOUDBBoxes(const BitVolume& voxels, const VoxelRuns& r)
{
  const std::int32_t ny = voxels.size(1), nz = voxels.size(2);
  const std::size_t words = voxels.wordsPerRow();
  std::size_t boxes = 0;
  for (std::int32_t z = 0; z < nz; ++z)
  {
    if (z > 0 && sameWords(voxels.row(0, z), voxels.row(0, z - 1), words * ny))
      continue;
    for (std::int32_t y = 0; y < ny; ++y)
    {
      // An empty row adds no box whatever the row before: not compared (most rows of a small
      // object in a large image).
      const std::size_t row = r.rowOf(y, z);
      const std::uint32_t runs = r.rowStarts[row + 1] - r.rowStarts[row];
      if (runs > 0 && (y == 0 || !sameWords(voxels.row(y, z), voxels.row(y - 1, z), words)))
        boxes += runs;
    }
  }
  return boxes;
}

/// The EVM's vertices: the lattice points (x, y, z) with an odd number of set voxels among the
/// eight around them. The parity of the four rows around a line of points, then its changes
/// along x. Rows without runs add nothing to a parity and are not read: a line of points
/// between four empty rows (most of a small object's image) costs no word. Bits counted by
/// the instruction when HardwareCount (see PopCount.h).
template<bool HardwareCount>
VBR_ALWAYS_INLINE std::size_t countExtremeVerticesWith(const BitVolume& voxels, const VoxelRuns& r)
{
  const std::int32_t ny = voxels.size(1), nz = voxels.size(2);
  const std::size_t words = voxels.wordsPerRow();
  std::size_t vertices = 0;
  for (std::int32_t z = 0; z <= nz; ++z)
    for (std::int32_t y = 0; y <= ny; ++y)
    {
      const Word* rows[4] = { nullptr, nullptr, nullptr, nullptr };
      int n = 0;
      for (std::int32_t dz = -1; dz <= 0; ++dz)
        for (std::int32_t dy = -1; dy <= 0; ++dy)
          if (z + dz >= 0 && z + dz < nz && y + dy >= 0 && y + dy < ny)
          {
            const std::size_t row = r.rowOf(y + dy, z + dz);
            if (r.rowStarts[row] != r.rowStarts[row + 1])
              rows[n++] = voxels.row(y + dy, z + dz);
          }
      if (n == 0)
        continue;
      Word carry = 0;
      for (std::size_t w = 0; w < words; ++w)
      {
        Word parity = 0;
        for (int k = 0; k < n; ++k)
          parity ^= rows[k][w];
        vertices +=
          static_cast<std::size_t>(bitCount<HardwareCount>(parity ^ ((parity << 1) | carry)));
        carry = parity >> 63;
      }
      vertices += static_cast<std::size_t>(carry);
    }
  return vertices;
}

#if VBR_POPCNT_COPY
/// countExtremeVerticesWith compiled for processors with POPCNT.
__attribute__((target("popcnt"))) std::size_t countExtremeVerticesPopCount(const BitVolume& voxels,
  const VoxelRuns& r)
{
  return countExtremeVerticesWith<true>(voxels, r);
}
#endif

/// countExtremeVerticesWith, by the instruction where the processor has it (and the build does
/// not assume it).
std::size_t countExtremeVertices(const BitVolume& voxels, const VoxelRuns& r)
{
#if VBR_POPCNT_COPY
  if (hasPopCountInstruction())
    return countExtremeVerticesPopCount(voxels, r);
#endif
  return countExtremeVerticesWith<false>(voxels, r);
}

/// Writes v into 4 consecutive values (one 16-byte store).
inline void store4(std::int32_t* p, std::int32_t v)
{
  for (int k = 0; k < 4; ++k)
    p[k] = v;
}

/// Writes v into 8 consecutive values.
inline void store8(std::int32_t* p, std::int32_t v)
{
  store4(p, v);
  store4(p + 4, v);
}

/// Writes v into line[run.x0, run.x1). A run of up to 8 voxels whose row has `room` for 4 values
/// past its end is written by three stores of 4 values: from its start, from 4 before its end
/// (from its start when it is shorter than 4), then 4 zeros from its end over what the first
/// wrote past it (the gap, 0 before; a later run of the row is written after). A longer run by
/// 8-wide stores, the last one ending at its end. The runs of porous and noisy volumes are a
/// few voxels of random lengths, and a store loop mispredicted its exit at nearly every run;
/// on a checkerboard's one-voxel runs the stores are the painting's time (four stores a run
/// before: 8 values, then 8 zeros).
inline void paintRun(std::int32_t* line, const VoxelRun& run, std::int32_t v, std::int32_t room)
{
  const std::int32_t length = run.x1 - run.x0;
  if (length <= 8 && run.x1 <= room - 4)
  {
    store4(line + run.x0, v);
    store4(line + run.x0 + std::max(length - 4, 0), v);
    store4(line + run.x1, 0);
  }
  else if (length >= 8)
  {
    for (std::int32_t x = run.x0; x <= run.x1 - 8; x += 8)
      store8(line + x, v);
    store8(line + run.x1 - 8, v);
  }
  else
    std::fill(line + run.x0, line + run.x1, v);
}

/// paintRun of every run of row `row` whose value is not 0, the row's voxel x at line[x]. The
/// arrays are read through local pointers and each run copied first: the label stores could
/// otherwise alias them, and the loop read the runs' vector, the row's end and the run's end
/// again after every store.
inline void paintRowOfRuns(const VoxelRuns& runs,
  std::size_t row,
  const std::vector<std::uint32_t>& runLabel,
  const std::vector<std::int32_t>& value,
  std::int32_t* line,
  std::int32_t room)
{
  const VoxelRun* const run = runs.runs.data();
  const std::uint32_t* const label = runLabel.data();
  const std::int32_t* const values = value.data();
  const std::uint32_t end = runs.rowStarts[row + 1];
  for (std::uint32_t i = runs.rowStarts[row]; i < end; ++i)
  {
    const VoxelRun r = run[i];
    if (const std::int32_t v = values[label[i]])
      paintRun(line, r, v, room);
  }
}

} // namespace

bool extractRuns(const BitVolume& voxels, const Execution& exec, VoxelRuns& out)
{
  const std::int32_t ny = voxels.size(1), nz = voxels.size(2);
  const std::size_t words = voxels.wordsPerRow();
  const std::size_t rows = static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
  out.dims = voxels.dims();
  out.rowStarts.assign(rows + 1, 0);
  std::vector<std::uint64_t> counts(rows + 1, 0);
  const Execution work = exec.forWork(static_cast<std::int64_t>(voxels.voxelCount() / 64));
  work.forRange(nz,
    [&](std::int64_t begin, std::int64_t end)
    {
      for (auto z = static_cast<std::int32_t>(begin); z < end; ++z)
        for (std::int32_t y = 0; y < ny; ++y)
          counts[out.rowOf(y, z) + 1] = countRowRuns(voxels.row(y, z), words);
    });
  for (std::size_t r = 0; r < rows; ++r)
    counts[r + 1] += counts[r];
  // Run numbers and the union-find are 32-bit: refuse rather than wrap.
  if (counts[rows] >= None)
    throw std::length_error(
      "labelling " + std::to_string(counts[rows]) + " runs of voxels: more than 2^32 - 2 runs");
  std::copy(counts.begin(), counts.end(), out.rowStarts.begin());
  resizeOnHugePages(out.runs, counts[rows]);
  if (exec.stopRequested())
    return false;
  work.forRange(nz,
    [&](std::int64_t begin, std::int64_t end)
    {
      for (auto z = static_cast<std::int32_t>(begin); z < end; ++z)
        for (std::int32_t y = 0; y < ny; ++y)
          writeRowRuns(voxels.row(y, z), words, out.runs.data() + out.rowStarts[out.rowOf(y, z)]);
    });
  return !exec.stopRequested();
}

bool labelRuns(const BitVolume& voxels,
  const VoxelRuns& runs,
  Connectivity connectivity,
  const Execution& exec,
  RunComponents& out,
  bool withBoxes,
  RunLabellingScratch* scratch,
  ContactSearch search)
{
  // The runs' numbers in the rows' bits are counts of their bits (uniteRowBits): other runs
  // would have them unite past the union-find's elements.
  if (runs.dims != voxels.dims() ||
    runs.rowStarts.size() != std::size_t(runs.dims[1]) * std::size_t(runs.dims[2]) + 1 ||
    runs.rowStarts.back() != runs.runs.size())
    throw std::invalid_argument("labelling runs that are not those of a volume of this size");
  RunLabellingScratch local;
  RunLabellingScratch& memory = scratch ? *scratch : local;
  const std::size_t n = runs.runs.size();
  const std::int32_t nz = runs.dims[2];
  emptyWithRoom(memory.parents, n);
  UnionFind uf(std::move(memory.parents), n);
  CompactionNotes notes(n, std::move(memory.notes));
  // The working memory goes back to `memory` however the labelling ends.
  struct GiveBack
  {
    RunLabellingScratch& memory;
    UnionFind& uf;
    CompactionNotes& notes;
    ~GiveBack()
    {
      this->memory.parents = this->uf.release();
      this->memory.notes = std::move(this->notes.storage);
    }
  } giveBack{ memory, uf, notes };
  const int pieces = labellingPieces(n, nz, exec.concurrency);
  const RowSource source{ runs, voxels, search };
  const bool united = pieces > 1 ? uniteInPieces(source, connectivity, pieces, exec, uf, notes)
                                 : uniteSequentially(source, connectivity, exec, uf, notes);
  if (!united)
    return false;
  // The classes numbered from 1 in order of their first run.
  resizeOnHugePages(out.runLabel, n);
  out.count = uf.numberClasses(out.runLabel.data(), 1);
  if (withBoxes)
    out.boxCount = buildBoxes(
      runs, notes, out.runLabel, out.beginsBox, out.boxes, out.boxLabel, memory.boxOfRun);
  else
  {
    out.boxCount = boxBeginnings(notes, out.beginsBox);
    out.boxes.clear();
    out.boxLabel.clear();
  }
  if (exec.stopRequested())
    return false;
  out.oudbBoxCount = countOUDBBoxes(voxels, runs);
  out.extremeVertices = countExtremeVertices(voxels, runs);
  return exec.report(1.0);
}

bool paintRuns(const VoxelRuns& runs,
  const std::vector<std::uint32_t>& runLabel,
  const std::vector<std::int32_t>& value,
  const std::array<std::int32_t, 3>& offset,
  const std::array<std::int32_t, 3>& dims,
  std::int32_t* labels,
  const Execution& exec,
  bool zeroAround)
{
  const std::int32_t ny = runs.dims[1];
  // The room from the runs' x = 0 to the end of the grid's row, which wide stores stay within.
  const std::int32_t room = zeroAround ? dims[0] - offset[0] : 0;
  std::atomic<bool> stopped{ false };
  const Execution work = exec.forWork(static_cast<std::int64_t>(runs.runs.size()));
  work.forRange(runs.dims[2],
    [&](std::int64_t begin, std::int64_t end)
    {
      for (auto z = static_cast<std::int32_t>(begin); z < end && !stopped; ++z)
      {
        for (std::int32_t y = 0; y < ny; ++y)
        {
          const std::size_t row = runs.rowOf(y, z);
          std::int32_t* line = labels +
            ((static_cast<std::int64_t>(z) + offset[2]) * dims[1] + y + offset[1]) * dims[0] +
            offset[0];
          paintRowOfRuns(runs, row, runLabel, value, line, room);
        }
        if ((z & 7) == 7 && exec.stopRequested())
          stopped = true;
      }
    });
  return !stopped && !exec.stopRequested();
}

bool paintRunsOverwriting(const VoxelRuns& runs,
  const std::vector<std::uint32_t>& runLabel,
  const std::vector<std::int32_t>& value,
  const std::array<std::int32_t, 3>& offset,
  const std::array<std::int32_t, 3>& dims,
  std::int32_t* labels,
  const Execution& exec)
{
  const std::int64_t rowLength = dims[0];
  const std::int64_t planeLength = rowLength * dims[1];
  const std::int32_t room = dims[0] - offset[0];
  std::atomic<bool> stopped{ false };
  const Execution work = exec.forWork(static_cast<std::int64_t>(runs.runs.size()));
  work.forRange(dims[2],
    [&](std::int64_t begin, std::int64_t end)
    {
      for (std::int64_t z = begin; z < end && !stopped; ++z)
      {
        std::int32_t* plane = labels + z * planeLength;
        const std::int64_t rz = z - offset[2];
        if (rz < 0 || rz >= runs.dims[2])
        {
          std::fill_n(plane, planeLength, 0);
          continue;
        }
        for (std::int32_t y = 0; y < dims[1]; ++y)
        {
          std::int32_t* line = plane + y * rowLength;
          std::fill_n(line, rowLength, 0);
          const std::int32_t ry = y - offset[1];
          if (ry < 0 || ry >= runs.dims[1])
            continue;
          const std::size_t row = runs.rowOf(ry, static_cast<std::int32_t>(rz));
          paintRowOfRuns(runs, row, runLabel, value, line + offset[0], room);
        }
        if ((z & 7) == 7 && exec.stopRequested())
          stopped = true;
      }
    });
  return !stopped && !exec.stopRequested();
}

} // namespace vbr
