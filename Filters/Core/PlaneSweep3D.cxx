// The 3D plane sweep of Ayala & Vergara (section 2) in chunks of planes run concurrently.
//
// sortForTheThreeSweeps gives the three cyclic sortings, one sweep per normal axis. The
// planes of each are cut into chunks (chunkPlanes), the section entering each chunk found by
// one sequential pass of XORs (formula 1), the cheap part. Each chunk (sweepChunk) then runs
// its cuts: the next section S(i) = S(i-1) XOR C(i), the forward and backward differences
// (forwardAndBackwardDifferences, formulas 3 and 4), and for each the faces of that 2D EVM by
// planeSweep2D, placed in their plane by appendFaces, FD facing +A and BD facing -A. The
// chunks' B-Reps are joined in order (appendBRep), so the result does not depend on the
// chunking.
//
// A section is kept one of two ways, chosen per sorting by bitRowsPay. As a sorted vertex
// list, a cut costs merges proportional to the vertices of the section and the cut. As rows
// of bits over the box of all the sorting's vertices (BitSection: one bit per cell, 64 per
// word), formula 1 and both differences are word ANDs and XORs, a cost proportional to the
// box's words whatever the vertices. The rows are chosen when all the planes' boxes together
// hold no more than 4 words per vertex of the sorting: a step of a merge (a comparison and a
// copy of a vertex) costs about what a few word operations do, so then the words cost no more
// than the merges would, and a box (one is alive per chunk being swept) takes at most 32 /
// planes bytes per vertex, against the EVM's 12. Porous and noisy volumes, whose planes are
// full of vertices, take the rows; a sparse object in a large box keeps the lists.
// Either way the differences found are the same vertex lists (an EVM is unique), so the faces
// do not depend on the choice.
//
// Streamed (planeSweep3DStream) with threads, a sorting is swept by a pool of workers, one
// parallel loop per sorting (SortingPool): each takes the next chunk in order, its entering
// section from a shared walker that XORs the cuts of the chunks before under a lock (with rows
// of bits, word by word), sweeps it and prepares its part (StreamedPartHandlers::prepare); the
// parts are appended strictly in order by whichever worker finds the next one ready, so the
// caller's work per part runs on the threads too, all but what must follow the order. On one
// thread each chunk hands its exit section to the next and needs no walker.

#include "PlaneSweep3D.h"

#include "EVMBoolean.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace vbr
{

namespace
{

/// The order of a vertex of a plane (first coordinate 0, as the sections and cuts are) as one
/// integer: (u, v) with the sign bits flipped, so that unsigned order is Vertex order.
std::uint64_t planeKey(const Vertex& p)
{
  return (std::uint64_t(std::uint32_t(p[1]) ^ 0x80000000u) << 32) |
    (std::uint32_t(p[2]) ^ 0x80000000u);
}

/// The XOR of two sorted vertex lists of a plane (formula 1, and BD = C XOR FD), into `out`:
/// xorVertices with one comparison of integers per step, the hot merge of the sweep.
void xorPlanes(const std::vector<Vertex>& a, const std::vector<Vertex>& b, std::vector<Vertex>& out)
{
  out.resize(a.size() + b.size());
  const Vertex *i = a.data(), *iEnd = i + a.size(), *j = b.data(), *jEnd = j + b.size();
  Vertex* o = out.data();
  while (i != iEnd && j != jEnd)
  {
    const std::uint64_t ki = planeKey(*i), kj = planeKey(*j);
    if (ki < kj)
      *o++ = *i++;
    else if (kj < ki)
      *o++ = *j++;
    else
    {
      ++i;
      ++j;
    }
  }
  o = std::copy(i, iEnd, o);
  o = std::copy(j, jEnd, o);
  out.resize(static_cast<std::size_t>(o - out.data()));
}

/// Chunks of planes per sorting when the faces are streamed (planeSweep3DStream): the faces
/// of the few chunks swept at a time are all that is alive of them.
constexpr std::size_t StreamChunks = 64;

/// Parts alive at most per thread when the faces are streamed: a worker whose part waits for
/// an earlier one to be appended sweeps the next chunk meanwhile instead of waiting.
constexpr std::size_t StreamSlotsPerThread = 2;

/// Chunks of one plane each at the end of a streamed sorting: the chunks a pool's workers
/// take last are short, so that none idles long at the end of the sorting while another
/// sweeps a long last chunk (the last plane, an object's top, is often the heaviest: on porous
/// 128^3 with two workers and 3-plane chunks, one idled 0.4-0.6 ms at the end of each
/// sorting). The same chunks on one thread, so that the parts do not depend on the threads.
constexpr std::size_t StreamLastSingles = 4;

/// The chunks of planes of a streamed sorting: `step` planes each (the last of them maybe
/// fewer), then the last StreamLastSingles planes one a chunk.
struct ChunkLayout
{
  std::size_t planes = 0, step = 1, singles = 0;

  ChunkLayout(std::size_t planeCount, std::size_t planeStep)
    : planes(planeCount)
    , step(planeStep)
    , singles(planeStep > 1 ? std::min(planeCount, StreamLastSingles) : 0)
  {
  }

  /// The chunks of `step` planes.
  std::size_t steps() const { return (this->planes - this->singles + this->step - 1) / this->step; }
  std::size_t count() const { return this->steps() + this->singles; }
  /// The first plane of chunk k (k <= count(): the end of the last chunk for k = count()).
  std::size_t firstPlane(std::size_t k) const
  {
    const std::size_t steps = this->steps();
    return k <= steps ? std::min(k * this->step, this->planes - this->singles)
                      : this->planes - this->singles + (k - steps);
  }
};

/// The box of (B, C) cells that every section and cut of one sorting lies in: row r holds the
/// cells between lines u = lowU + r and u + 1, bit k of it the cell between v = lowV + k and
/// v + 1. With one word per 64 cells, a section is a few words per line.
struct SectionBox
{
  Coord lowU = 0, lowV = 0;
  std::size_t rows = 0;  ///< lines of vertices - 1
  std::size_t words = 0; ///< per row, room for the vertices' bits too (one more than the cells)
};

/// The box of the vertices of a sorting in (B, C).
SectionBox sectionBoxOf(const EVM& sorted)
{
  SectionBox box;
  if (sorted.empty())
    return box;
  const Vertex& first = sorted.vertices()[0];
  Coord lowU = first[1], highU = lowU, lowV = first[2], highV = lowV;
  for (const Vertex& p : sorted.vertices())
  {
    lowU = std::min(lowU, p[1]);
    highU = std::max(highU, p[1]);
    lowV = std::min(lowV, p[2]);
    highV = std::max(highV, p[2]);
  }
  box.lowU = lowU;
  box.lowV = lowV;
  box.rows = static_cast<std::size_t>(std::int64_t(highU) - lowU);
  box.words = static_cast<std::size_t>(std::int64_t(highV) - lowV) / 64 + 1;
  return box;
}

/// The range [lo[a], hi[a]] of each world axis a over the vertices of a 3D EVM. A sorting
/// gives its first axis's for free (its first and last vertices), so the three sortings of
/// the sweeps give all three without a pass over the vertices.
struct AxisRanges
{
  std::array<Coord, 3> lo{ 0, 0, 0 }, hi{ 0, 0, 0 };
};

/// Records the range of the first axis of `sorted` (not empty) in `ranges`.
void recordFirstAxisRange(const EVM& sorted, AxisRanges& ranges)
{
  const int a = sorted.order()[0];
  ranges.lo[a] = sorted.vertices().front()[0];
  ranges.hi[a] = sorted.vertices().back()[0];
}

/// Records the range of the world axis of coordinate k of `evm` (not empty), by a pass over
/// its vertices: for the axis no sorting at hand starts with.
void scanAxisRange(const EVM& evm, int k, AxisRanges& ranges)
{
  Coord lo = evm.vertices()[0][k], hi = lo;
  for (const Vertex& p : evm.vertices())
  {
    lo = std::min(lo, p[k]);
    hi = std::max(hi, p[k]);
  }
  ranges.lo[evm.order()[k]] = lo;
  ranges.hi[evm.order()[k]] = hi;
}

/// sectionBoxOf for a sorting in `order` of vertices whose axes span `ranges`: the same box,
/// the vertices' bounds in (B, C) being those of the world axes B and C.
SectionBox sectionBoxOf(const AxisRanges& ranges, const AxisOrder& order)
{
  const int b = order[1], c = order[2];
  SectionBox box;
  box.lowU = ranges.lo[b];
  box.lowV = ranges.lo[c];
  box.rows = static_cast<std::size_t>(std::int64_t(ranges.hi[b]) - ranges.lo[b]);
  box.words = static_cast<std::size_t>(std::int64_t(ranges.hi[c]) - ranges.lo[c]) / 64 + 1;
  return box;
}

/// Whether the sections of a sorting are better kept as rows of bits than as vertex lists:
/// when the words of all its planes' boxes are no more than a few per vertex (porous and noisy
/// volumes, whose planes are full of vertices). A sparse object in a large box keeps lists.
bool bitRowsPay(const SectionBox& box, std::size_t planes, std::size_t vertices)
{
  const double words = double(box.rows + 1) * double(box.words) * double(planes);
  return box.rows > 0 && words <= 4.0 * double(vertices);
}

/// Whether the sections of the planes `sorted` are swept in are kept as rows of bits (then over
/// `box`, set) or as vertex lists.
bool bitRowsOf(const EVM& sorted, std::size_t planes, SectionBox& box)
{
  box = sectionBoxOf(sorted);
  return bitRowsPay(box, planes, sorted.size());
}

/// The prefix XOR of a row of bits along v, XORed into `into`: cell k of a region is the
/// parity of the vertices at or before k on its line and the lines before.
void xorPrefixInto(const std::vector<Word>& bits, std::vector<Word>& into)
{
  Word carry = 0; // all ones when the bits of the words before have odd parity
  for (std::size_t w = 0; w < bits.size(); ++w)
  {
    Word x = bits[w];
    x ^= x << 1;
    x ^= x << 2;
    x ^= x << 4;
    x ^= x << 8;
    x ^= x << 16;
    x ^= x << 32;
    x ^= carry;
    carry = Word(0) - (x >> 63);
    into[w] ^= x;
  }
}

/// The vertices (0, u, v) of a line, where the cells of `change` (the XOR of the cell rows on
/// either side of the line) begin or end, appended in order of v.
void appendLineVertices(const Word* change,
  std::size_t words,
  Coord u,
  Coord lowV,
  std::vector<Vertex>& out)
{
  Word carry = 0;
  for (std::size_t w = 0; w < words; ++w)
  {
    Word x = change[w] ^ ((change[w] << 1) | carry);
    carry = change[w] >> 63;
    for (; x != 0; x &= x - 1)
      out.push_back(
        { 0, u, static_cast<Coord>(lowV + 64 * std::int64_t(w) + countTrailingZeros(x)) });
  }
}

/// The section of a sweep kept as rows of bits over the sorting's box (formula 1 as a word
/// XOR), with the forward and backward differences of each cut found word by word: FD = S(i-1)
/// AND C(i), BD = S(i) AND C(i), their vertices where their rows change from line to line.
/// The results are the vertex lists the merges of sorted lists give (an EVM is unique).
class BitSection
{
public:
  explicit BitSection(const SectionBox& box)
    : Box(box)
    , Cells(box.rows * box.words, 0)
    , Cut(box.words)
    , LineBits(box.words)
    , FdBelow(box.words)
    , BdBelow(box.words)
    , Change(box.words)
  {
  }

  /// S = the region of these vertices (0, u, v), sorted.
  void assign(const std::vector<Vertex>& section)
  {
    std::fill(this->Cells.begin(), this->Cells.end(), 0);
    std::fill(this->Cut.begin(), this->Cut.end(), 0);
    const Vertex *c = section.data(), *end = c + section.size();
    for (std::size_t r = 0; r < this->Box.rows; ++r)
    {
      this->readLine(c, end, this->Box.lowU + static_cast<Coord>(r));
      Word* s = this->Cells.data() + r * this->Box.words;
      for (std::size_t w = 0; w < this->Box.words; ++w)
        s[w] = this->Cut[w];
    }
  }

  /// Formula 1 for the cut [cut, cutEnd) (vertices (a, u, v), sorted) and the vertices of its
  /// forward and backward differences (formula 4), into `fd` and `bd`.
  void sweepCut(const Vertex* cut,
    const Vertex* cutEnd,
    std::vector<Vertex>& fd,
    std::vector<Vertex>& bd)
  {
    fd.clear();
    bd.clear();
    const std::size_t words = this->Box.words;
    std::fill(this->Cut.begin(), this->Cut.end(), 0);
    std::fill(this->FdBelow.begin(), this->FdBelow.end(), 0);
    std::fill(this->BdBelow.begin(), this->BdBelow.end(), 0);
    bool cutAny = false, fdAny = false, bdAny = false; // in Cut, FdBelow, BdBelow
    for (std::size_t r = 0; r < this->Box.rows; ++r)
    {
      const Coord u = this->Box.lowU + static_cast<Coord>(r);
      if (this->readLine(cut, cutEnd, u))
        cutAny = std::any_of(this->Cut.begin(), this->Cut.end(), [](Word x) { return x != 0; });
      if (!cutAny && !fdAny && !bdAny)
        continue; // no cut here nor a difference below: nothing changes on this line
      Word* s = this->Cells.data() + r * words;
      Word fdOr = 0, bdOr = 0;
      for (std::size_t w = 0; w < words; ++w)
      {
        const Word c = this->Cut[w], before = s[w], after = before ^ c;
        const Word f = before & c, b = after & c;
        s[w] = after;
        this->Change[w] = f ^ this->FdBelow[w];
        this->FdBelow[w] = f;
        this->LineBits[w] = b ^ this->BdBelow[w];
        this->BdBelow[w] = b;
        fdOr |= f;
        bdOr |= b;
      }
      appendLineVertices(this->Change.data(), words, u, this->Box.lowV, fd);
      appendLineVertices(this->LineBits.data(), words, u, this->Box.lowV, bd);
      fdAny = fdOr != 0;
      bdAny = bdOr != 0;
    }
    const Coord top = this->Box.lowU + static_cast<Coord>(this->Box.rows);
    appendLineVertices(this->FdBelow.data(), words, top, this->Box.lowV, fd);
    appendLineVertices(this->BdBelow.data(), words, top, this->Box.lowV, bd);
  }

  /// Formula 1 alone: S ^= the region of the cut [cut, cutEnd), whose rows end where the cut's
  /// lines do (the rows past its last line are outside its region).
  void xorCut(const Vertex* cut, const Vertex* cutEnd)
  {
    std::fill(this->Cut.begin(), this->Cut.end(), 0);
    for (std::size_t r = 0; r < this->Box.rows && cut != cutEnd; ++r)
    {
      this->readLine(cut, cutEnd, this->Box.lowU + static_cast<Coord>(r));
      Word* s = this->Cells.data() + r * this->Box.words;
      for (std::size_t w = 0; w < this->Box.words; ++w)
        s[w] ^= this->Cut[w];
    }
  }

  /// S as its rows of bits, to be handed to another BitSection of the same box.
  const std::vector<Word>& cells() const { return this->Cells; }
  void assignCells(const std::vector<Word>& cells) { this->Cells = cells; }

  /// S = the section a chunk enters with, as the chunk holds it (see PlaneChunk).
  void assignEntering(const std::vector<Vertex>& section, const std::vector<Word>& cells)
  {
    if (cells.empty())
      this->assign(section);
    else
      this->assignCells(cells);
  }

private:
  /// Reads the vertices of line u from `at` on (advancing it) into Cut, the region of the
  /// lines read so far at this line; false when the line has none.
  bool readLine(const Vertex*& at, const Vertex* end, Coord u)
  {
    if (at == end || (*at)[1] != u)
      return false;
    std::fill(this->LineBits.begin(), this->LineBits.end(), 0);
    for (; at != end && (*at)[1] == u; ++at)
    {
      const std::size_t k = static_cast<std::size_t>(std::int64_t((*at)[2]) - this->Box.lowV);
      this->LineBits[k >> 6] ^= Word(1) << (k & 63);
    }
    xorPrefixInto(this->LineBits, this->Cut);
    return true;
  }

  SectionBox Box;
  std::vector<Word> Cells; ///< S, row after row
  std::vector<Word> Cut;   ///< the cut's region on the current row
  std::vector<Word> LineBits, FdBelow, BdBelow, Change;
};

/// A run of consecutive planes of vertices of one sorting, with the section before it.
struct PlaneChunk
{
  const EVM* sorted = nullptr;
  const std::vector<std::size_t>* starts = nullptr; ///< plane starts of *sorted
  std::size_t firstPlane = 0, endPlane = 0;
  std::vector<Vertex> section;     ///< S(firstPlane - 1), as vertices
  const SectionBox* box = nullptr; ///< when the sections are kept as rows of bits
  std::vector<Word> cells; ///< S(firstPlane - 1) as rows of bits, when not empty (then not section)
};

/// The cut of plane `p` (formula 1's C(i)): its vertices projected along the sweep's axis, into
/// `cut`, whose memory is reused from plane to plane.
void cutOf(const Vertex* v,
  const std::vector<std::size_t>& starts,
  std::size_t p,
  std::vector<Vertex>& cut)
{
  cut.assign(v + starts[p], v + starts[p + 1]);
  for (Vertex& c : cut)
    c[0] = 0;
}

/// Splits every sorting's planes into about `perAxis` chunks; the sections at chunk starts come
/// from one sequential pass of XORs of vertex lists (formula 1), the cheap part of the sweep.
/// A chunk of a sorting whose `boxes` entry is set turns its entering section into rows of bits
/// itself (BitSection::assign), in its own task, so that only one box per chunk being swept is
/// alive.
std::vector<PlaneChunk> chunkPlanes(const EVM (&sorted)[3],
  const std::vector<std::size_t> (&planeStarts)[3],
  const SectionBox* (&boxes)[3],
  std::size_t perAxis)
{
  std::vector<PlaneChunk> chunks;
  for (int axis = 0; axis < 3; ++axis)
  {
    const EVM& evm = sorted[axis];
    const auto& starts = planeStarts[axis];
    const std::size_t planes = starts.size() - 1;
    const std::size_t step = std::max<std::size_t>(1, (planes + perAxis - 1) / perAxis);
    const Vertex* v = evm.vertices().data();
    std::vector<Vertex> section, next, cut;
    for (std::size_t p = 0; p < planes; ++p)
    {
      if (p % step == 0)
        chunks.push_back({ &evm, &starts, p, std::min(planes, p + step), section, boxes[axis] });
      cutOf(v, starts, p, cut);
      xorPlanes(section, cut, next);
      section.swap(next);
    }
  }
  return chunks;
}

/// The forward and backward differences of cut C(i) (formula 4): the cut is FD + BD
/// (formula 3), FD = S(i-1) - S(i) is the part of the cut covered by S(i-1), and BD the rest
/// of the cut, so one Boolean and one XOR give both.
void forwardAndBackwardDifferences(const std::vector<Vertex>& cut,
  const std::vector<Vertex>& previousSection,
  std::vector<Vertex>& fd,
  std::vector<Vertex>& bd)
{
  fd = booleanVertices(cut.data(),
    cut.data() + cut.size(),
    previousSection.data(),
    previousSection.data() + previousSection.size(),
    1,
    BooleanOp::Intersection);
  xorPlanes(cut, fd, bd);
}

/// What sweepChunk writes besides its part, kept from chunk to chunk by the thread that sweeps
/// them (a sorting's planes make 64 chunks, a few planes each at 128^3): the 2D sweeps' arrays,
/// the section, the cut and the differences. Made afresh per chunk, they were allocated and
/// grown again for every plane.
struct ChunkMemory
{
  explicit ChunkMemory(FaceConnectivity connectivity)
    : Sweeper(connectivity)
  {
  }
  PlaneSweeper2D Sweeper;
  std::vector<Vertex> Section, Next, Cut, Fd, Bd;
};

/// Sweeps a chunk of planes: for each cut, the next section (formula 1), the forward and
/// backward differences (formula 4) and their faces by the 2D plane sweep, FD facing +A and
/// BD facing -A. With `exit`, the section after the chunk's last plane goes there (as the
/// chunk holds it: rows of bits or vertices). `memory` was made for the same connectivity.
bool sweepChunk(const PlaneChunk& chunk,
  FaceConnectivity connectivity,
  const Execution& exec,
  std::atomic<bool>& abort,
  BRep& out,
  ChunkMemory& memory,
  PlaneChunk* exit = nullptr)
{
  out.mergedAtVertices = connectivity == FaceConnectivity::Vertex;
  const EVM& sorted = *chunk.sorted;
  const auto& starts = *chunk.starts;
  const Vertex* v = sorted.vertices().data();
  std::vector<Vertex>& section = memory.Section;
  std::vector<Vertex>& next = memory.Next;
  std::vector<Vertex>& cut = memory.Cut;
  std::vector<Vertex>& fd = memory.Fd;
  std::vector<Vertex>& bd = memory.Bd;
  std::unique_ptr<BitSection> bits;
  if (chunk.box)
  {
    bits = std::make_unique<BitSection>(*chunk.box);
    bits->assignEntering(chunk.section, chunk.cells);
  }
  else
    section = chunk.section;
  for (std::size_t p = chunk.firstPlane; p < chunk.endPlane; ++p)
  {
    if (abort || exec.stopRequested())
    {
      abort = true;
      return false;
    }
    const Coord position = v[starts[p]][0];
    if (bits)
      bits->sweepCut(v + starts[p], v + starts[p + 1], fd, bd);
    else
    {
      cutOf(v, starts, p, cut);
      xorPlanes(section, cut, next);
      forwardAndBackwardDifferences(cut, section, fd, bd);
      section.swap(next);
    }
    appendFaces(
      memory.Sweeper.sweep(fd.data(), fd.data() + fd.size()), sorted.order(), position, +1, out);
    appendFaces(
      memory.Sweeper.sweep(bd.data(), bd.data() + bd.size()), sorted.order(), position, -1, out);
  }
  if (exit && bits)
    exit->cells = bits->cells();
  else if (exit)
    exit->section.swap(section);
  return true;
}

/// The three cyclic sortings (A, B, C) = (x, y, z), (y, z, x), (z, x, y), one per sweep,
/// each from the previous one by one stable bucket pass when the EVM comes ZYX-sorted from
/// extraction: ZYX -> YZX -> XYZ -> ZXY.
void sortForTheThreeSweeps(const EVM& evm, const Execution& exec, EVM (&sorted)[3])
{
  sorted[1] = evm.sortedAs({ 1, 2, 0 }, exec);
  sorted[0] = sorted[1].sortedAs({ 0, 1, 2 }, exec);
  sorted[2] = sorted[0].sortedAs({ 2, 0, 1 }, exec);
}

/// Appends one B-Rep to another, renumbering its faces, loops and points.
void appendBRep(BRep& to, BRep&& from)
{
  const int faceBase = static_cast<int>(to.faces.size());
  const int loopBase = static_cast<int>(to.loops.size());
  to.faces.reserve(to.faces.size() + from.faces.size());
  to.loops.reserve(to.loops.size() + from.loops.size());
  for (BRepFace f : from.faces)
  {
    f.firstLoop += loopBase;
    f.parent = f.parent < 0 ? -1 : f.parent + faceBase;
    to.faces.push_back(f);
  }
  const std::size_t pointBase = to.points.size();
  for (BRepLoop l : from.loops)
  {
    l.face += faceBase;
    l.begin += pointBase;
    l.end += pointBase;
    to.loops.push_back(l);
  }
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  to.nonManifoldVertices += from.nonManifoldVertices;
}

/// Empties a part for the next chunk of planes, keeping its arrays' memory: a part grown from
/// empty copied its points at each doubling of the arrays, in pages taken afresh from the
/// heap, 192 parts an object (64 chunks per sorting). The chunks that follow are about as
/// large, so the memory is kept for them until the sorting is done (a handler may also have
/// released or moved the part's arrays: then they grow again).
void emptyKeepingCapacity(BRep& part)
{
  part.faces.clear();
  part.loops.clear();
  part.points.clear();
  part.nonManifoldVertices = 0;
  part.mergedAtVertices = false;
}

/// The progress of the streamed sweeps: `planesDone` of about `planesAll` planes.
bool reportPlanes(const Execution& exec, std::size_t planesDone, std::size_t planesAll)
{
  return exec.report(double(planesDone) / double(std::max<std::size_t>(planesAll, 1)));
}

/// Sweeps the planes of one sorting on the calling thread in chunks (ChunkLayout: of `step` planes,
/// the last ones of one), each chunk's exit section handed to the next, each part prepared and
/// appended (in slot 0) before the next chunk is swept. `planesDone` (of `planesAll`, for the
/// progress) counts the planes swept so far.
bool streamSortingAlone(const EVM& sorted,
  const std::vector<std::size_t>& starts,
  std::size_t step,
  const SectionBox* bitBox,
  FaceConnectivity connectivity,
  const Execution& exec,
  const StreamedPartHandlers& handlers,
  std::size_t& planesDone,
  std::size_t planesAll)
{
  const ChunkLayout layout(starts.size() - 1, step);
  std::atomic<bool> abort{ false };
  PlaneChunk chunk{ &sorted, &starts, 0, 0, {}, bitBox, {} };
  BRep part;
  ChunkMemory memory(connectivity);
  for (std::size_t k = 0; k < layout.count(); ++k)
  {
    const std::size_t p = layout.firstPlane(k);
    chunk.firstPlane = p;
    chunk.endPlane = layout.firstPlane(k + 1);
    emptyKeepingCapacity(part);
    // The chunk is its own exit: sweepChunk reads the entering section before it writes the
    // exit one, which the next chunk enters with.
    if (!sweepChunk(chunk, connectivity, exec, abort, part, memory, &chunk) ||
      (handlers.prepare && !handlers.prepare(part, 0)) || !handlers.append(part, 0))
      return false;
    planesDone += chunk.endPlane - p;
    if (!reportPlanes(exec, planesDone, planesAll))
      return false;
  }
  return true;
}

/// One sorting's chunks of planes swept by a pool of workers: one parallel loop over the
/// workers (a thread start and join per sorting, not per few chunks). A worker takes the next
/// chunk in order, with its entering section from a walker that XORs the cuts of the chunks
/// before (formula 1) under the lock, sweeps and prepares it into its slot (chunk k into slot
/// k % slots), then marks it ready. The parts are appended strictly in order: whoever finds the
/// next part in order ready appends it and the ready ones after it, one appender at a time, out
/// of the lock. A chunk is taken only once its slot is free (the chunk `slots` places before it
/// appended), so no more than `slots` parts are alive. A worker waits for that only while the
/// next part to append is being swept by another worker, so workers run one after the other on
/// one thread never wait. The parts, and their order, are the one-thread loop's.
class SortingPool
{
public:
  SortingPool(const EVM& sorted,
    const std::vector<std::size_t>& starts,
    std::size_t step,
    const SectionBox* bitBox,
    FaceConnectivity connectivity,
    const Execution& exec,
    const StreamedPartHandlers& handlers)
    : Sorted(sorted)
    , Starts(starts)
    , Planes(starts.size() - 1)
    , Layout(this->Planes, step)
    , Count(this->Layout.count())
    , Slots(streamBatch(exec))
    , BitBox(bitBox)
    , Connectivity(connectivity)
    , Exec(exec)
    , Handlers(handlers)
    , Parts(this->Slots)
    , Ready(this->Slots, 0)
  {
    if (bitBox)
      this->Walker = std::make_unique<BitSection>(*bitBox);
  }

  /// Sweeps the sorting; false when the caller asked to abort or a handler returned false.
  /// The progress is reported on the calling thread only: by a worker that runs there after
  /// each of its chunks, and after the sorting.
  bool run(std::size_t& planesDone, std::size_t planesAll)
  {
    this->Caller = std::this_thread::get_id();
    this->PlanesBefore = planesDone;
    this->PlanesAll = planesAll;
    const std::size_t workers =
      std::min(this->Count, static_cast<std::size_t>(std::max(1, this->Exec.concurrency)));
    this->Exec.forRange(static_cast<std::int64_t>(workers),
      [this](std::int64_t b, std::int64_t e)
      {
        for (std::int64_t w = b; w < e; ++w)
          this->work();
      });
    if (this->Stopped) // the workers are done: no lock needed
      return false;
    planesDone += this->Planes;
    return reportPlanes(this->Exec, planesDone, planesAll);
  }

private:
  /// One worker: chunks until none is left or the stream stops. An exception stops the other
  /// workers (none is left waiting) and leaves through the parallel loop.
  void work()
  {
    try
    {
      PlaneChunk chunk{ &this->Sorted, &this->Starts, 0, 0, {}, this->BitBox, {} };
      ChunkMemory memory(this->Connectivity);
      std::size_t index = 0;
      while (this->take(chunk, index))
      {
        const std::size_t slot = index % this->Slots;
        BRep& part = this->Parts[slot];
        emptyKeepingCapacity(part);
        const bool prepared =
          sweepChunk(chunk, this->Connectivity, this->Exec, this->Abort, part, memory) &&
          !this->Abort && (!this->Handlers.prepare || this->Handlers.prepare(part, slot));
        this->finish(index, prepared);
        if (std::this_thread::get_id() == this->Caller && !this->reportOnCaller())
          this->stop();
      }
    }
    catch (...)
    {
      this->stop();
      throw;
    }
  }

  /// The next chunk in order and its entering section, once its slot is free; false when no
  /// chunk is left or the stream stopped.
  bool take(PlaneChunk& chunk, std::size_t& index)
  {
    std::unique_lock<std::mutex> lock(this->Lock);
    this->SlotFreed.wait(lock,
      [this]
      {
        return this->Stopped || this->Taken == this->Count ||
          this->Taken < this->Appended + this->Slots;
      });
    if (this->Stopped || this->Taken == this->Count)
      return false;
    index = this->Taken++;
    chunk.firstPlane = this->Layout.firstPlane(index);
    chunk.endPlane = this->Layout.firstPlane(index + 1);
    this->walkTo(chunk, index + 1 < this->Count);
    return true;
  }

  /// Under the lock: the walker's section, S(firstPlane - 1), into `chunk`, and with `onward`
  /// the walker past the chunk's cuts (formula 1), for the next chunk.
  void walkTo(PlaneChunk& chunk, bool onward)
  {
    const Vertex* v = this->Sorted.vertices().data();
    if (this->Walker)
    {
      chunk.cells = this->Walker->cells(); // into the worker's kept memory
      if (onward)
        for (std::size_t q = chunk.firstPlane; q < chunk.endPlane; ++q)
          this->Walker->xorCut(v + this->Starts[q], v + this->Starts[q + 1]);
      return;
    }
    chunk.section = this->Section;
    if (onward)
      for (std::size_t q = chunk.firstPlane; q < chunk.endPlane; ++q)
      {
        cutOf(v, this->Starts, q, this->Cut);
        xorPlanes(this->Section, this->Cut, this->Next);
        this->Section.swap(this->Next);
      }
  }

  /// Marks chunk `index`'s part ready (or stops the stream when it was not prepared), then
  /// appends the parts ready in order unless another worker is appending them.
  void finish(std::size_t index, bool prepared)
  {
    std::unique_lock<std::mutex> lock(this->Lock);
    if (!prepared || this->Stopped)
    {
      this->stopLocked();
      return;
    }
    this->Ready[index % this->Slots] = 1;
    if (this->Appending)
      return; // the appender finds it ready after the part it is appending
    this->Appending = true;
    while (
      !this->Stopped && this->Appended < this->Count && this->Ready[this->Appended % this->Slots])
    {
      const std::size_t slot = this->Appended % this->Slots;
      lock.unlock();
      const bool appended = this->Handlers.append(this->Parts[slot], slot);
      lock.lock();
      this->Ready[slot] = 0;
      ++this->Appended;
      if (!appended)
        this->stopLocked();
      this->SlotFreed.notify_all();
    }
    this->Appending = false;
  }

  /// On the calling thread: the planes of the parts appended so far; false to abort.
  bool reportOnCaller()
  {
    std::size_t appended = 0;
    {
      std::lock_guard<std::mutex> lock(this->Lock);
      appended = this->Appended;
    }
    const std::size_t planes = this->Layout.firstPlane(appended);
    return reportPlanes(this->Exec, this->PlanesBefore + planes, this->PlanesAll);
  }

  void stop()
  {
    std::lock_guard<std::mutex> lock(this->Lock);
    this->stopLocked();
  }

  void stopLocked()
  {
    this->Stopped = true;
    this->Abort = true;
    this->SlotFreed.notify_all();
  }

  const EVM& Sorted;
  const std::vector<std::size_t>& Starts;
  const std::size_t Planes;
  const ChunkLayout Layout; ///< chunk k is planes [firstPlane(k), firstPlane(k + 1))
  const std::size_t Count;  ///< chunks
  const std::size_t Slots;  ///< parts alive at most
  const SectionBox* BitBox;
  const FaceConnectivity Connectivity;
  const Execution& Exec;
  const StreamedPartHandlers& Handlers;
  std::vector<BRep> Parts; ///< chunk k's in Parts[k % Slots], kept with their arrays' memory
  std::vector<char> Ready; ///< per slot: its part is prepared and waits to be appended

  std::mutex Lock; ///< guards what follows but Abort (the sweeps poll it)
  std::condition_variable SlotFreed;
  std::size_t Taken = 0, Appended = 0;
  bool Appending = false, Stopped = false;
  std::atomic<bool> Abort{ false };
  std::unique_ptr<BitSection> Walker;     ///< the walker's section as rows of bits, or
  std::vector<Vertex> Section, Next, Cut; ///< as vertices

  std::thread::id Caller;
  std::size_t PlanesBefore = 0, PlanesAll = 0;
};

/// Sweeps the planes of one sorting in chunks of planes (StreamChunks of them), each part
/// prepared by the thread that swept it and appended in order: on the calling thread alone, or
/// by a pool of exec.concurrency workers. `ranges` are those of the vertices' axes (for the
/// box of the sections). `planesDone` (of `planesAll`, for the progress) counts the planes
/// swept so far; `planes` (when given) gets the sorting's planes at its first axis.
bool streamSorting(const EVM& sorted,
  const AxisRanges& ranges,
  FaceConnectivity connectivity,
  const Execution& exec,
  const StreamedPartHandlers& handlers,
  std::size_t& planesDone,
  std::size_t planesAll,
  std::array<std::size_t, 3>* planesPerAxis)
{
  const std::vector<std::size_t> starts = sorted.planeStarts();
  const std::size_t planes = starts.size() - 1;
  if (planesPerAxis)
    (*planesPerAxis)[sorted.order()[0]] = planes;
  if (planes == 0)
    return true;
  const std::size_t step = std::max<std::size_t>(1, (planes + StreamChunks - 1) / StreamChunks);
  // The box from the axes' ranges: a pass over the vertices for their bounds was a serial
  // 0.3 ms per sorting on porous 128^3, 2 % of an update on two threads.
  SectionBox box = sectionBoxOf(ranges, sorted.order());
  const SectionBox* bitBox = bitRowsPay(box, planes, sorted.size()) ? &box : nullptr;
  if (!exec.parallelFor || exec.concurrency <= 1)
    return streamSortingAlone(
      sorted, starts, step, bitBox, connectivity, exec, handlers, planesDone, planesAll);
  SortingPool pool(sorted, starts, step, bitBox, connectivity, exec, handlers);
  return pool.run(planesDone, planesAll);
}

} // namespace

std::size_t streamBatch(const Execution& exec)
{
  if (!exec.parallelFor || exec.concurrency <= 1)
    return 1;
  return StreamSlotsPerThread * static_cast<std::size_t>(exec.concurrency);
}

bool planeSweep3DStream(EVM evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  const std::function<bool(BRep&)>& consume)
{
  return planeSweep3DStream(std::move(evm),
    connectivity,
    exec,
    StreamedPartHandlers{ nullptr, [&](BRep& part, std::size_t) { return consume(part); } });
}

bool planeSweep3DStream(EVM evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  const StreamedPartHandlers& handlers,
  std::array<std::size_t, 3>* planesPerAxis)
{
  if (planesPerAxis)
    *planesPerAxis = { 0, 0, 0 };
  if (evm.empty())
    return true;
  // sortForTheThreeSweeps' sortings, made as late and released as early as the sweeps allow,
  // no more than two alive at once; each written into the memory of one no longer needed (the
  // given EVM's, then the first's), not into fresh pages: at 256^3 and more a sorting is tens
  // of MB, and the kernel's faulting in and zeroing of new pages weighed as much as the sort.
  AxisRanges ranges;
  const bool zFirst = evm.order()[0] == 2; // extractEVM's ZYX sorting
  if (zFirst)
    recordFirstAxisRange(evm, ranges);
  EVM first = evm.sortedAs({ 1, 2, 0 }, exec);
  EVM zeroth = first.sortedAs({ 0, 1, 2 }, exec, evm.takeVertices());
  recordFirstAxisRange(first, ranges);
  recordFirstAxisRange(zeroth, ranges);
  if (!zFirst)
    scanAxisRange(zeroth, 2, ranges);
  const std::size_t planesAll =
    3 * std::max<std::size_t>(1, zeroth.planeStarts().size() - 1); // about
  std::size_t done = 0;
  if (!streamSorting(
        zeroth, ranges, connectivity, exec, handlers, done, planesAll, planesPerAxis) ||
    !streamSorting(first, ranges, connectivity, exec, handlers, done, planesAll, planesPerAxis))
    return false;
  EVM second = zeroth.sortedAs({ 2, 0, 1 }, exec, first.takeVertices());
  zeroth = EVM();
  return streamSorting(
    second, ranges, connectivity, exec, handlers, done, planesAll, planesPerAxis);
}

bool planeSweep3DParts(const EVM& evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  std::vector<BRep>& parts)
{
  parts.clear();
  std::atomic<bool> abort{ false };
  EVM sorted[3];
  sortForTheThreeSweeps(evm, exec, sorted);
  // Chunks of planes of all three sweeps are independent tasks.
  const std::vector<std::size_t> starts[3] = {
    sorted[0].planeStarts(), sorted[1].planeStarts(), sorted[2].planeStarts()
  };
  SectionBox box[3];
  const SectionBox* bitBoxes[3];
  for (int axis = 0; axis < 3; ++axis)
    bitBoxes[axis] =
      bitRowsOf(sorted[axis], starts[axis].size() - 1, box[axis]) ? &box[axis] : nullptr;
  const std::vector<PlaneChunk> chunks = chunkPlanes(sorted, starts, bitBoxes, 8);
  parts.resize(chunks.size());
  exec.forRange(static_cast<std::int64_t>(chunks.size()),
    [&](std::int64_t b, std::int64_t e)
    {
      ChunkMemory memory(connectivity);
      for (std::int64_t c = b; c < e; ++c)
      {
        if (!sweepChunk(chunks[c], connectivity, exec, abort, parts[c], memory))
          abort = true;
        // The parts stay alive side by side until their cells are written: no slack in them.
        parts[c].faces.shrink_to_fit();
        parts[c].loops.shrink_to_fit();
        parts[c].points.shrink_to_fit();
      }
    });
  if (abort || !exec.report(1.0))
  {
    parts.clear();
    return false;
  }
  return true;
}

bool planeSweep3D(const EVM& evm, FaceConnectivity connectivity, const Execution& exec, BRep& out)
{
  out = BRep();
  out.mergedAtVertices = connectivity == FaceConnectivity::Vertex;
  std::vector<BRep> parts;
  if (!planeSweep3DParts(evm, connectivity, exec, parts))
    return false;
  // The chunks' faces in order: by axis, then plane.
  std::size_t faces = 0, loops = 0, points = 0;
  for (const BRep& b : parts)
  {
    faces += b.faces.size();
    loops += b.loops.size();
    points += b.points.size();
  }
  out.faces.reserve(faces);
  out.loops.reserve(loops);
  out.points.reserve(points);
  for (BRep& b : parts)
  {
    appendBRep(out, std::move(b));
    b = BRep(); // released as soon as copied
  }
  return true;
}

namespace detail
{
std::array<bool, 3> sectionsAsBitRows(const EVM& evm)
{
  EVM sorted[3];
  sortForTheThreeSweeps(evm, Execution(), sorted);
  std::array<bool, 3> bitRows{};
  for (int axis = 0; axis < 3; ++axis)
  {
    SectionBox box;
    bitRows[axis] = bitRowsOf(sorted[axis], sorted[axis].planeStarts().size() - 1, box);
  }
  return bitRows;
}
} // namespace detail

} // namespace vbr
