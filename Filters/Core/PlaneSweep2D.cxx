// The 2D plane sweep of Ayala & Vergara (section 3) as one Sweep object over a 2D EVM.
//
// run is the whole method. The first sweep goes line of vertices by line of vertices
// (processLine): the cut is merged with the active section by XOR (formula 1), point by point
// along v. At each point enterPoint updates the open intervals (those of the previous and
// next sections that overlap are united in the union-find: the paper's contour merging),
// then one of three events: an extreme vertex of the cut matching one of the section ends a
// horizontal edge (closeHorizontalEdge), a new one starts one (openHorizontalEdge), a brink of
// the cut running through a vertex of the section is a non-manifold vertex
// (splitAtNonManifoldVertex, section 3.3); at each corner the vertical piece of the brink and
// the horizontal edge are linked (turnAtCorner). An interval of the next section that ends
// without having met the previous section is recorded as a candidate first interval of a face
// for the second sweep. After the sweep, pairNonManifoldVertices applies the rules of
// Fig. 7 at the split vertices, numberFaces numbers the faces in order of first appearance,
// orderEdgesIntoLoops is the domino step, and classifyContours is the second sweep (outer
// loops, holes and the inclusion tree from 1D tests on the stored section ends).
//
// Numbered in the order (v, u) (runNumbered) on a large image with dense corners, the corners get
// their numbers as the sweep meets them from cornersByColumn, a pass over the vertices before the
// sweep that finds every column's corners with bit operations on whole lines: the extreme
// vertices, and the non-manifold vertices, where a vertex of the section lies inside a brink of
// the cut. Otherwise they are sorted along v after the sweep.
//
// Terms: a cut is a line of vertices; a brink a maximal segment of it; a section end an
// extreme vertex of the active section with the horizontal edge it draws; an interval a
// pair of section ends (a piece of face between two consecutive cuts).

#include "PlaneSweep2D.h"

#include "HugePages.h"
#include "Prefetch.h"
#include "UnionFind.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

namespace vbr
{

namespace
{

/// An edge end not reached yet.
constexpr std::uint32_t Unset = std::numeric_limits<std::uint32_t>::max();

/// Sweep::processLine with the checks of every corner and edge, or without (lineNeedsChecks).
constexpr bool Checked = true, Unchecked = false;

/// Numbered in the order (v, u), the corners are found by column before the sweep when there
/// are at least as many vertices as words in the grid of columns (cornersByColumn) and at
/// least FewestVerticesByColumn vertices, and sorted by v after the sweep otherwise. Below
/// about FewestVerticesByColumn the sort's scattered writes stay in the cache and the sort wins
/// even where corners are dense (sweep and numbering, CPU time: ccitt7, 186,544 vertices, 4.1 per
/// word, 4.9 ms sorted against 5.4-5.8 by column; pollen, 65,432, 3.5 per word, 1.9 against 2.1);
/// beyond it the grid wins (feyn, 282,760 vertices, 2.2 per word, 9.5 against 15 ms;
/// pageseg2 and scots-frag, 555,042 and 577,326: 24 against 35 and 26 against 32-36 ms).

/// An oriented edge between two corners, by their numbers, kept as two records of 8 bytes
/// each in arrays of their own: what the domino step follows (EdgeLink: where the edge starts
/// and the next edge of its loop) apart from what only the first sweep and the pairing at
/// non-manifold vertices read (EdgeEnd). The domino step reads the links in no order of
/// memory: eight of them to a cache line rather than four of whole 16-byte edges, so the
/// same reads ahead cover twice the edges (on the 6001^2 maze the wait for the next edge fell
/// from about 24 % to 11 % of an update's samples; README, round "Edge links apart").
struct EdgeLink
{
  std::uint32_t from = Unset;
  int next = -1; ///< following edge of its loop, Unlinked, or visitedMark(its loop) once passed
};

struct EdgeEnd
{
  std::uint32_t to = Unset;
  int interval = -1; ///< a section interval of the face on the edge's left
};

/// EdgeLink::next of an edge no corner has linked yet (an open contour if it stays so).
constexpr int Unlinked = -1;

/// EdgeLink::next of an edge the domino step has put in loop `loop`, and back.
constexpr int visitedMark(std::size_t loop)
{
  return -2 - static_cast<int>(loop);
}
constexpr int loopOfMark(int mark)
{
  return -2 - mark;
}

/// An end point of an interval of the active section and the horizontal edge it draws.
struct SectionEnd
{
  Coord v;
  int edge;
};

/// A section interval that overlaps no interval of the previous section: a candidate first
/// interval of a face, with what the second sweep needs from its section.
struct FirstInterval
{
  int interval;
  int bottomEdge; ///< horizontal edge at its lower end
  int belowEdge;  ///< horizontal edge of the section end just below it, or -1
};

/// The four edges of a non-manifold vertex, as the split found them: two enter the vertex, two
/// leave it, and in[k] is followed by out[k] when the loop turns right there (both corners
/// in the same face), by out[1 - k] when each loop stays in its own corner's face.
struct NonManifoldVertex
{
  int in[2];
  int out[2];
};

/// Calls visit(u, first, last) for every line of vertices [first, last) of [begin, end).
template<typename Visit>
void forEachLine(const Vertex* begin, const Vertex* end, Visit&& visit)
{
  while (begin != end)
  {
    const Vertex* lineEnd = begin;
    while (lineEnd != end && (*lineEnd)[1] == (*begin)[1])
      ++lineEnd;
    visit((*begin)[1], begin, lineEnd);
    begin = lineEnd;
  }
}

/// The parity of the bits of `w` at and below each bit (a prefix XOR within the word).
inline std::uint64_t prefixParity(std::uint64_t w)
{
  w ^= w << 1;
  w ^= w << 2;
  w ^= w << 4;
  w ^= w << 8;
  w ^= w << 16;
  w ^= w << 32;
  return w;
}

/// The range of v of the vertices [begin, end), not empty.
std::pair<Coord, Coord> rangeOfV(const Vertex* begin, const Vertex* end)
{
  Coord vLo = (*begin)[2], vHi = vLo;
  for (const Vertex* p = begin; p != end; ++p)
  {
    vLo = std::min(vLo, (*p)[2]);
    vHi = std::max(vHi, (*p)[2]);
  }
  return { vLo, vHi };
}

/// The words of the grid of cornersByColumn for the vertices [begin, end), not empty, whose v
/// range is [vLo, vHi].
std::size_t columnGridWords(const Vertex* begin, const Vertex* end, Coord vLo, Coord vHi)
{
  const std::size_t rows = static_cast<std::size_t>((*(end - 1))[1] - (*begin)[1]) + 1;
  return (static_cast<std::size_t>(vHi - vLo) + 1) * ((rows + 63) / 64);
}

/// The corners the sweep of [begin, end) meets, by column (CornerColumns): on each line u, the
/// vertices of the cut, and the vertices of the section (the XOR of the cuts before) that are
/// not in the cut but inside one of its brinks (an odd number of cut vertices below them), the
/// non-manifold vertices of Sweep::processLine. Whole words of a line at a time. [vLo, vHi]: the
/// range of v. Into `g`, whose memory is kept (NumberedPlaneSweeper2D).
void cornersByColumn(const Vertex* begin, const Vertex* end, Coord vLo, Coord vHi, CornerColumns& g)
{
  g.uLo = (*begin)[1];
  g.vLo = vLo;
  g.columns = static_cast<std::size_t>(vHi - vLo) + 1;
  g.wordsPerColumn = (static_cast<std::size_t>((*(end - 1))[1] - g.uLo) + 64) / 64;
  g.bits.assign(g.columns * g.wordsPerColumn, 0);
  const std::size_t lineWords = (g.columns + 63) / 64;
  std::vector<std::uint64_t> section(lineWords, 0), cut(lineWords, 0);
  std::size_t count = 0;
  forEachLine(begin,
    end,
    [&](Coord u, const Vertex* first, const Vertex* last)
    {
      for (const Vertex* p = first; p != last; ++p)
      {
        const std::size_t k = static_cast<std::size_t>((*p)[2] - vLo);
        cut[k / 64] ^= std::uint64_t(1) << (k % 64);
      }
      const std::size_t row = static_cast<std::size_t>(u - g.uLo);
      const std::uint64_t rowBit = std::uint64_t(1) << (row % 64);
      std::uint64_t* column = g.bits.data() + row / 64;
      std::uint64_t below = 0; // all ones when the cut is open at the word's start
      for (std::size_t w = 0; w < lineWords; ++w)
      {
        const std::uint64_t c = cut[w];
        if ((c | section[w]) == 0)
          continue; // nothing here, and `below` goes on
        const std::uint64_t inCut = prefixParity(c) ^ below ^ c; // open just below each bit
        below = (inCut ^ c) >> 63 ? ~std::uint64_t(0) : 0;
        const std::uint64_t nonManifold = section[w] & ~c & inCut;
        section[w] ^= c;
        cut[w] = 0;
        for (std::uint64_t k = c | nonManifold; k != 0; k &= k - 1, ++count)
          column[(64 * w + countTrailingZeros(k)) * g.wordsPerColumn] |= rowBit;
      }
    });
  if (count >= Unset)
    throw std::length_error("planeSweep2D: 2^32 corners or more");
  g.count = count;
}

class Sweep
{
public:
  explicit Sweep(FaceConnectivity connectivity)
    : MergeAtVertices(connectivity == FaceConnectivity::Vertex)
  {
  }

  /// Keep the scratch arrays of numberCornersAlongV from one sweep to the next, as the others
  /// (NumberedPlaneSweeper2D). A sweep made once frees them as soon as the corners are numbered,
  /// so that the loops' arrays reuse their memory (keeping them to the end made a single sweep
  /// of porous 1024^2 at 45 % take 6.2-6.3 ms instead of 5.5-5.7).
  void keepScratch() { this->KeepsScratch = true; }

  /// How faces meet at the non-manifold vertices of the next sweeps.
  void setConnectivity(FaceConnectivity connectivity)
  {
    this->MergeAtVertices = connectivity == FaceConnectivity::Vertex;
  }

  /// The whole method: the first sweep line by line, the pairing at non-manifold vertices,
  /// the domino step and the second sweep; the loops' corners as points.
  Boundary2D run(const Vertex* begin, const Vertex* end)
  {
    Boundary2D out;
    this->runInto(begin, end, out);
    return out;
  }

  /// run, into `out` (emptied first) and after any earlier sweep of this object, whose arrays
  /// are emptied with their memory kept (PlaneSweeper2D).
  void runInto(const Vertex* begin, const Vertex* end, Boundary2D& out)
  {
    this->emptyKeepingCapacity();
    out.faces.clear();
    out.loops.clear();
    out.points.clear();
    this->firstSweep(begin, end);
    out.nonManifoldVertices = this->NonManifold.size();
    this->numberFaces(out);
    // Every edge gives its loop one corner: the points fill exactly this, written through a
    // pointer without a check of capacity per corner (and without reading the corners' array
    // anew after each store of the points' end, which push_back made).
    reserveHugePages(out.points, this->Links.size());
    out.points.resize(this->Links.size());
    Point2* to = out.points.data();
    const Point2* corners = this->Corners.data();
    this->orderEdgesIntoLoops(out, [&](std::uint32_t c) { *to++ = corners[c]; });
    this->classifyContours(out);
  }

  /// The same method, the loops' corners as numbers of the distinct corners in `order`.
  Contours2D runNumbered(const Vertex* begin,
    const Vertex* end,
    CornerOrder order,
    std::size_t fewestByColumn)
  {
    Contours2D out;
    this->runNumberedInto(begin, end, order, fewestByColumn, out);
    return out;
  }

  /// runNumbered, into `out` (emptied first, its memory kept) and after any earlier sweep of
  /// this object, whose arrays are emptied with their memory kept (NumberedPlaneSweeper2D).
  void runNumberedInto(const Vertex* begin,
    const Vertex* end,
    CornerOrder order,
    std::size_t fewestByColumn,
    Contours2D& out)
  {
    this->emptyKeepingCapacity();
    emptyKeepingCapacity(out);
    bool sortAlongV = false;
    if (order == CornerOrder::VThenU && begin != end)
    {
      // The grid of columns costs a bit per grid point, the sort after the sweep a scattered
      // write per corner: the grid where corners are dense (a maze, a scan of text), the sort
      // where they are few (a fax page's large black areas).
      const auto [vLo, vHi] = rangeOfV(begin, end);
      const std::size_t vertices = static_cast<std::size_t>(end - begin);
      sortAlongV = vertices < fewestByColumn || vertices < columnGridWords(begin, end, vLo, vHi);
      if (!sortAlongV)
      {
        cornersByColumn(begin, end, vLo, vHi, out.columns);
        this->numberByColumn(out.columns);
      }
    }
    this->firstSweep(begin, end);
    if (sortAlongV)
      this->numberCornersAlongV();
    else if (order == CornerOrder::VThenU && begin != end)
      this->checkEveryColumnNumbered(out.columns);
    out.boundary.nonManifoldVertices = this->NonManifold.size();
    this->numberFaces(out.boundary);
    this->reserveRoom(out.loopCorners, this->Links.size());
    out.loopCorners.resize(this->Links.size()); // each corner written once (zeroed first)
    std::uint32_t* to = out.loopCorners.data();
    this->orderEdgesIntoLoops(out.boundary, [&](std::uint32_t c) { *to++ = c; });
    this->classifyContours(out.boundary);
    out.corners.swap(this->Corners); // empty when numbered by column
  }

private:
  /// Every array of a sweep emptied, its memory kept for the next sweep.
  void emptyKeepingCapacity()
  {
    this->Section.clear();
    this->NextSection.clear();
    this->NextIntervals.clear();
    this->SectionIntervals.clear();
    this->Corners.clear();
    this->ColumnNext.clear();
    this->ColumnLo = 0;
    this->Links.clear();
    this->Ends.clear();
    this->First.clear();
    this->NonManifold.clear();
    this->FaceOfRoot.clear();
    this->FirstOfFace.clear();
  }

  /// Contours emptied, their memory kept for the next sweep.
  static void emptyKeepingCapacity(Contours2D& out)
  {
    out.boundary.faces.clear();
    out.boundary.loops.clear();
    out.boundary.points.clear();
    out.boundary.nonManifoldVertices = 0;
    out.corners.clear();
    out.loopCorners.clear();
    CornerColumns& columns = out.columns;
    columns.uLo = columns.vLo = 0;
    columns.columns = columns.wordsPerColumn = columns.count = 0;
    columns.bits.clear();
  }

  /// The first sweep (line by line) and the pairing at the non-manifold vertices: every edge
  /// then knows the next one of its loop.
  void firstSweep(const Vertex* begin, const Vertex* end)
  {
    // Every extreme vertex is the corner where one edge starts (a non-manifold vertex starts
    // two, and only then does the array grow): growing it from empty would copy the edges
    // about twice.
    this->Links.reserve(static_cast<std::size_t>(end - begin));
    this->Ends.reserve(static_cast<std::size_t>(end - begin));
    if (this->ColumnNext.empty())
      this->Corners.reserve(static_cast<std::size_t>(end - begin));
    // Huge pages under the edges, which the domino step reads in no order of memory: a miss in
    // the cache then rarely misses in the TLB as well.
    if (!this->KeepsScratch) // kept arrays: see reserveRoom
    {
      adviseHugePages(this->Links.data(), this->Links.capacity() * sizeof(EdgeLink), HugePageBytes);
      adviseHugePages(this->Ends.data(), this->Ends.capacity() * sizeof(EdgeEnd), HugePageBytes);
    }
    this->reserveIntervals(static_cast<std::size_t>(end - begin));
    while (begin != end)
    {
      const Vertex* lineEnd = begin;
      while (lineEnd != end && (*lineEnd)[1] == (*begin)[1])
        ++lineEnd;
      if ((lineEnd - begin) % 2)
        throw std::invalid_argument(
          "planeSweep2D: a line of vertices has an odd count (not an EVM)");
      if (this->lineNeedsChecks(begin, lineEnd))
        this->processLine<Checked>((*begin)[1], begin, lineEnd);
      else
        this->processLine<Unchecked>((*begin)[1], begin, lineEnd);
      begin = lineEnd;
    }
    if (!this->Section.empty())
      throw std::invalid_argument("planeSweep2D: the last section is not empty (not an EVM)");
    this->pairNonManifoldVertices();
  }

  // ---- union-find over section intervals (roots follow sweep order) -----------------------
  /// Room, under huge pages, for the section intervals and the first intervals of faces of a
  /// sweep over `vertices` vertices; grown from empty they would be copied and faulted in about
  /// twice. Guesses, not bounds: the intervals number 0.3 to 0.46 of the vertices on real
  /// images (0.39 and 0.46 on the 6001^2 maze and its complement), many more where the
  /// vertices are non-manifold (64 times on a checkerboard); the first intervals 0.03 to 0.22
  /// (0.09 on the maze), so an eighth covers the maze and most scans. More only grow the arrays.
  void reserveIntervals(std::size_t vertices)
  {
    std::vector<std::uint32_t> storage = this->Intervals.release(); // an earlier sweep's
    this->reserveRoom(storage, vertices / 2);
    this->Intervals = UnionFind(std::move(storage), 0);
    this->reserveRoom(this->First, vertices / 8);
  }
  /// Room for n values in `v`: under huge pages for a sweep made once, in small pages for a
  /// sweep that keeps its arrays (keepScratch), which are faulted in once, at the first sweep,
  /// and reused after: there a fresh huge page can cost far more than the 512 small ones it
  /// replaces (NumberedPlaneSweeper2D), for a few percent of TLB misses in the later sweeps.
  template<typename T>
  void reserveRoom(std::vector<T>& v, std::size_t n) const
  {
    if (this->KeepsScratch)
      v.reserve(n);
    else
      reserveHugePages(v, n);
  }
  /// `v` holding n copies of `value`, in the pages reserveRoom would choose.
  template<typename T>
  void assignRoom(std::vector<T>& v, std::size_t n, const T& value) const
  {
    if (this->KeepsScratch)
      v.assign(n, value);
    else
      assignHugePages(v, n, value);
  }

  int newInterval() { return static_cast<int>(this->Intervals.add()); }
  int find(int i) { return static_cast<int>(this->Intervals.find(static_cast<std::uint32_t>(i))); }
  void unite(int a, int b)
  {
    this->Intervals.unite(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
  }

  // ---- corners and edges ---------------------------------------------------------------------
  /// Whether the line of cut [cut, cutEnd) takes the checked corners and edges (Checked): when
  /// its corners are numbered by column, or its corners or edges may reach the limits of their
  /// numbers. Each point of the merge takes a section end or a vertex of the cut, or both, and
  /// makes at most one corner and two edges, so the line makes at most twice as many of either
  /// as the section has ends and the cut vertices. Elsewhere (Unchecked) the checks that never
  /// fire are not made at every corner and edge.
  bool lineNeedsChecks(const Vertex* cut, const Vertex* cutEnd) const
  {
    const std::size_t most = 2 * (this->Section.size() + static_cast<std::size_t>(cutEnd - cut));
    return !this->ColumnNext.empty() || this->Corners.size() + most >= Unset ||
      this->Links.size() + most >= static_cast<std::size_t>(std::numeric_limits<int>::max());
  }

  /// Numbers a corner: the sweep meets them line after line, along each line in order, so
  /// their numbers follow the order (u, v); or, numbered by column (numberByColumn), the next
  /// number of its column, which makes the order (v, u). Unchecked: in a line that
  /// lineNeedsChecks passed.
  template<bool Checks>
  std::uint32_t newCorner(Point2 here)
  {
    if (!Checks)
    {
      // In place (see startHorizontalEdge), after push_back's inlined fast path: emplace_back()
      // of the Point2, an instantiation shared with other files, was called out of line
      // (through the PLT; 5 % of a porous 1024^2 update's samples).
      static constexpr Point2 Blank{ 0, 0 };
      this->Corners.push_back(Blank); // of a const Point2&: push_back(Point2&&) is not inlined
      Point2& corner = this->Corners.back();
      corner.u = here.u;
      corner.v = here.v;
      return static_cast<std::uint32_t>(this->Corners.size() - 1);
    }
    if (!this->ColumnNext.empty())
      return this->ColumnNext[static_cast<std::size_t>(here.v - this->ColumnLo)]++;
    if (this->Corners.size() >= Unset)
      throw std::length_error("planeSweep2D: 2^32 corners or more");
    this->Corners.push_back(here);
    return static_cast<std::uint32_t>(this->Corners.size() - 1);
  }
  /// Starts an edge at corner c; `outgoing` says whether it leaves or enters c.
  template<bool Checks>
  int startEdge(std::uint32_t c, bool outgoing, int interval)
  {
    // Edges are numbered by int (their links and the non-manifold pairs): refuse, not wrap.
    if (Checks && this->Links.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw std::length_error("planeSweep2D: 2^31 - 1 edges or more");
    // Written in place (see startHorizontalEdge): records made apart and copied in were read
    // back as one word from two smaller stores, a stall at every edge.
    EdgeLink& link = this->Links.emplace_back();
    EdgeEnd& end = this->Ends.emplace_back();
    link.from = outgoing ? c : Unset;
    end.to = outgoing ? Unset : c;
    end.interval = interval;
    return static_cast<int>(this->Links.size()) - 1;
  }
  /// Ends edge e at corner c: `leaves` when it left the corner it started at (then it ends at
  /// c), which the caller knows from the flags of the merge (Point). Nothing read: a horizontal
  /// edge of the section was started lines before, and reading its record to tell its direction
  /// waited for memory (6 % of the first sweep's samples on the 6001^2 maze).
  void finishEdge(int e, std::uint32_t c, bool leaves)
  {
    assert((leaves ? this->Ends[e].to : this->Links[e].from) == Unset);
    (leaves ? this->Ends[e].to : this->Links[e].from) = c;
  }
  /// Links the two edges meeting at an ordinary corner c: the one entering it is followed by
  /// the one leaving it.
  void link(int a, int b, std::uint32_t c)
  {
    if (this->Ends[a].to == c)
      this->Links[a].next = b;
    else
      this->Links[b].next = a;
  }

  /// The open intervals and edges while a cut is merged with the active section: what the
  /// events at the points of the line change. (The flags that say which sections are open
  /// at a point stay local to processLine: kept in registers, they are half its work.)
  struct OpenIntervals
  {
    int prevInterval = -1;   ///< the open interval of the previous section
    int newInterval = -1;    ///< the open interval of the next section
    int piece = -1;          ///< the vertical edge (a piece of a brink) open on the line
    bool newTouched = false; ///< the open new interval overlaps one of the previous section
    int newBottomEdge = -1, newBelowEdge = -1; ///< for FirstInterval
  };

  /// Where the merge stands at point v of the line: `i` the section end there (if atPrev),
  /// whether the cut is open just below v and the next section just above it, and whether the
  /// previous section is open just below and just above v. The latter tell which way the edges
  /// ending at v run (finishEdge), as the face lies on their left: the section's horizontal
  /// edge ending at v left its first corner when that section is open above v (inPrev2; see
  /// startHorizontalEdge), and the cut's piece ending at v ran up when the previous section is
  /// open below v (inPrev; see startPiece).
  struct Point
  {
    Point2 here;
    std::size_t i;
    bool inCut, inNew2;
    bool inPrev, inPrev2;
  };

  /// First sweep, one line (Ayala & Vergara, section 3.1): merges the cut [cut, cutEnd) at u
  /// into the active section (formula 1) point by point along v, emitting edges, uniting
  /// overlapping intervals (the contour merging) and recording the first intervals of faces
  /// for the second sweep. in* say whether the previous section, the cut and the next section
  /// are open just below v, in*2 just above it.
  template<bool Checks>
  void processLine(Coord u, const Vertex* cut, const Vertex* cutEnd)
  {
    this->NextSection.clear();
    this->NextIntervals.clear();
    OpenIntervals o;
    std::size_t i = 0;
    bool inPrev = false, inCut = false;
    while (i < this->Section.size() || cut != cutEnd)
    {
      if (!inCut && i % 2 == 0 && i < this->Section.size() &&
        (cut == cutEnd || (*cut)[2] > this->Section[i + 1].v))
      {
        const std::size_t end = this->endOfUntouched(i, cut == cutEnd ? nullptr : &*cut);
        this->passIntervals(o, i, end);
        i = end;
        continue;
      }
      const bool takePrev =
        i < this->Section.size() && (cut == cutEnd || this->Section[i].v <= (*cut)[2]);
      const Coord v = takePrev ? this->Section[i].v : (*cut)[2];
      const bool atPrev = i < this->Section.size() && this->Section[i].v == v;
      const bool atCut = cut != cutEnd && (*cut)[2] == v;
      const bool inNew = inPrev != inCut;
      const bool inPrev2 = inPrev != atPrev, inCut2 = inCut != atCut;
      const bool inNew2 = inPrev2 != inCut2;
      this->enterPoint(o, inPrev && inNew, atPrev && inPrev2, inNew2 && !inNew, i);
      const Point at{ { u, v }, i, inCut, inNew2, inPrev, inPrev2 };
      if (atPrev && atCut)
        this->closeHorizontalEdge<Checks>(o, at); // an extreme vertex matching the section
      else if (atCut)
        this->openHorizontalEdge<Checks>(o, at); // a new extreme vertex of the section
      else if (atPrev && inCut)
        this->splitAtNonManifoldVertex<Checks>(o, at);
      else
        this->NextSection.push_back(this->Section[i]); // the horizontal edge goes on
      if (inNew && !inNew2 && !o.newTouched)           // a candidate first interval of a face ends
      {
        FirstInterval& first = this->First.emplace_back(); // in place, as above
        first.interval = o.newInterval;
        first.bottomEdge = o.newBottomEdge;
        first.belowEdge = o.newBelowEdge;
      }
      if (atPrev)
        ++i;
      if (atCut)
        ++cut;
      inPrev = inPrev2;
      inCut = inCut2;
    }
    this->Section.swap(this->NextSection);
    this->SectionIntervals.swap(this->NextIntervals);
  }

  /// The end of the intervals of the previous section from section end i (even, an interval
  /// the cut does not touch) that the cut neither enters nor touches: those whose upper end
  /// lies below the cut's next vertex `next` (all of them when null). Gallops from i, then
  /// bisects, which the section allows because its ends are sorted along v (its intervals are
  /// disjoint and in order): a fax page's line crosses few of its many intervals, a maze's
  /// nearly all.
  std::size_t endOfUntouched(std::size_t i, const Vertex* next) const
  {
    const std::size_t pairs = this->Section.size() / 2;
    std::size_t lo = i / 2 + 1; // pairs before lo are untouched
    if (!next)
      return 2 * pairs;
    const Coord v = (*next)[2];
    const auto untouched = [&](std::size_t pair) { return this->Section[2 * pair + 1].v < v; };
    std::size_t step = 1, hi = lo;
    while (hi < pairs && untouched(hi))
    {
      lo = hi + 1;
      hi = lo + step;
      step *= 2;
    }
    hi = std::min(hi, pairs);
    while (lo < hi) // pairs before lo untouched, from hi on touched
    {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (untouched(mid))
        lo = mid + 1;
      else
        hi = mid;
    }
    // Checked over the ends passed over only, which the caller copies anyway.
    assert(std::is_sorted(this->Section.begin() + static_cast<std::ptrdiff_t>(i),
      this->Section.begin() + static_cast<std::ptrdiff_t>(std::min(2 * lo + 1, 2 * pairs)),
      [](const auto& a, const auto& b) { return a.v < b.v; }));
    return 2 * lo;
  }

  /// The intervals of the previous section from section end i to `end` (even), which the cut
  /// neither enters nor touches (no vertex of the cut in them or at their ends, and the cut
  /// closed there): they go on into the next section as they are, the same intervals, where
  /// the point by point merge would start a new interval at each start and unite it with the
  /// old one at its end (the same faces, one interval and one union fewer each: most intervals
  /// of a sparse image). Copied as a block: on a fax page most of a long section is passed
  /// line after line.
  void passIntervals(OpenIntervals& o, std::size_t i, std::size_t end)
  {
    const int last = this->SectionIntervals[end / 2 - 1];
    o.prevInterval = o.newInterval = last;
    o.newTouched = true;
    this->NextIntervals.insert(this->NextIntervals.end(),
      this->SectionIntervals.begin() + static_cast<std::ptrdiff_t>(i / 2),
      this->SectionIntervals.begin() + static_cast<std::ptrdiff_t>(end / 2));
    this->NextSection.insert(this->NextSection.end(),
      this->Section.begin() + static_cast<std::ptrdiff_t>(i),
      this->Section.begin() + static_cast<std::ptrdiff_t>(end));
  }

  /// Updates the open intervals at a point of the line: the intervals of both sections that
  /// overlap just below it are the same face (bothBelow); the previous section's interval
  /// starting at section end i is entered (prevStarts); an interval of the next section
  /// starts there (newStarts).
  void enterPoint(OpenIntervals& o, bool bothBelow, bool prevStarts, bool newStarts, std::size_t i)
  {
    if (bothBelow)
    {
      this->unite(o.prevInterval, o.newInterval);
      o.newTouched = true;
    }
    if (prevStarts)
      o.prevInterval = this->SectionIntervals[i / 2];
    if (newStarts)
    {
      o.newInterval = this->newInterval();
      this->NextIntervals.push_back(o.newInterval);
      o.newTouched = false;
      o.newBelowEdge = this->NextSection.empty() ? -1 : this->NextSection.back().edge;
    }
  }

  /// A vertical piece starting at v keeps the face on its left: upwards when the face lies
  /// before u.
  template<bool Checks>
  int startPiece(const OpenIntervals& o, const Point& at, std::uint32_t c)
  {
    return this->startEdge<Checks>(c, !at.inNew2, at.inNew2 ? o.newInterval : o.prevInterval);
  }

  /// A horizontal edge of the next section starting at v, its end kept in the next section.
  template<bool Checks>
  int startHorizontalEdge(OpenIntervals& o, const Point& at, std::uint32_t c)
  {
    const int h = this->startEdge<Checks>(c, at.inNew2, o.newInterval);
    if (at.inNew2)
      o.newBottomEdge = h;
    // Its fields written in place: a section end made apart and copied is read back as one
    // word from two smaller stores, which the processor cannot forward (a stall per corner).
    SectionEnd& end = this->NextSection.emplace_back();
    end.v = at.here.v;
    end.edge = h;
    return h;
  }

  /// The brink being crossed ends at v (its vertical piece ends there, at horizontal edge h)
  /// or starts there (a piece starts); either way the corner links the two edges.
  template<bool Checks>
  void turnAtCorner(OpenIntervals& o, const Point& at, int h, std::uint32_t c)
  {
    if (at.inCut)
    {
      this->finishEdge(o.piece, c, at.inPrev);
      this->link(o.piece, h, c);
      o.piece = -1;
    }
    else
    {
      o.piece = this->startPiece<Checks>(o, at, c);
      this->link(o.piece, h, c);
    }
  }

  /// An extreme vertex of the cut matching one of the section: its horizontal edge ends here.
  template<bool Checks>
  void closeHorizontalEdge(OpenIntervals& o, const Point& at)
  {
    const std::uint32_t c = this->newCorner<Checks>(at.here);
    const int h = this->Section[at.i].edge;
    this->finishEdge(h, c, at.inPrev2);
    this->turnAtCorner<Checks>(o, at, h, c);
  }

  /// A new extreme vertex of the section: a horizontal edge starts here.
  template<bool Checks>
  void openHorizontalEdge(OpenIntervals& o, const Point& at)
  {
    const std::uint32_t c = this->newCorner<Checks>(at.here);
    const int h = this->startHorizontalEdge<Checks>(o, at, c);
    this->turnAtCorner<Checks>(o, at, h, c);
  }

  /// A non-manifold vertex (Ayala & Vergara, section 3.3): a brink of the cut contains a
  /// vertex of the section. The vertex is split: the brink's piece and the section's
  /// horizontal edge end there and new ones start; the four edges are paired once the faces
  /// are known.
  template<bool Checks>
  void splitAtNonManifoldVertex(OpenIntervals& o, const Point& at)
  {
    const std::uint32_t c = this->newCorner<Checks>(at.here);
    const int hOld = this->Section[at.i].edge;
    this->finishEdge(hOld, c, at.inPrev2);
    this->finishEdge(o.piece, c, at.inPrev);
    const int below = o.piece;
    o.piece = this->startPiece<Checks>(o, at, c);
    const int hNew = this->startHorizontalEdge<Checks>(o, at, c);
    // Which way each edge runs there follows from one flag of the merge: inside a brink
    // (inCut) at a section end, the next section is open above v exactly when the previous one
    // is open below it (inNew2 == inPrev). When it is (the solid corners: before u below v,
    // after u above v), the pieces enter the vertex and the horizontal edges leave it; otherwise
    // the other way round (see finishEdge, startPiece, startHorizontalEdge). The loop turns
    // right from the piece below to the new horizontal edge and from the new piece to the old
    // horizontal edge, or from the old horizontal edge to the piece below and from the new
    // horizontal edge to the new piece; the other pairing keeps each corner's two edges
    // together. Recorded so, the pairing reads no edge's ends to tell its direction.
    // A blank record pushed and then filled in place: a record made apart and then copied in
    // had cost 7.7 % of a checkerboard's samples once processLine had two copies (see
    // startHorizontalEdge), and emplace_back() was called out of line, about 25 instructions a
    // vertex; push_back of a constant is inlined (see newCorner).
    static constexpr NonManifoldVertex Blank{ { -1, -1 }, { -1, -1 } };
    this->NonManifold.push_back(Blank);
    NonManifoldVertex& vertex = this->NonManifold.back();
    assert(at.inNew2 == at.inPrev);
    vertex.in[0] = at.inPrev ? below : hOld;
    vertex.in[1] = at.inPrev ? o.piece : hNew;
    vertex.out[0] = at.inPrev ? hNew : below;
    vertex.out[1] = at.inPrev ? hOld : o.piece;
    if (this->MergeAtVertices)
    {
      this->unite(o.prevInterval, o.newInterval);
      o.newTouched = true;
    }
  }

  /// Pairs the two entering and two leaving edges of each non-manifold vertex (paper Fig. 7):
  /// when both corners belong to the same face, the loop turns right, so that every loop
  /// follows one component of the face's complement; otherwise each loop stays in its face.
  /// Only the faces of the two entering edges are looked up: the split recorded which way
  /// every edge runs and which pairing turns right (NonManifoldVertex), and each leaving edge
  /// bounds the same corner, so lies in the same face, as the entering edge it keeps to when
  /// the faces differ (on a checkerboard, where nearly every vertex is non-manifold and its
  /// corners lie in different faces, reading the four edges' ends and the leaving edges'
  /// faces was most of this step).
  void pairNonManifoldVertices()
  {
    for (const NonManifoldVertex& nmv : this->NonManifold)
    {
      const int inFace0 = this->find(this->Ends[nmv.in[0]].interval);
      const int inFace1 = this->find(this->Ends[nmv.in[1]].interval);
      const bool turnRight = inFace0 == inFace1;
      assert(turnRight ||
        (this->find(this->Ends[nmv.out[1]].interval) == inFace0 &&
          this->find(this->Ends[nmv.out[0]].interval) == inFace1));
      this->Links[nmv.in[0]].next = turnRight ? nmv.out[0] : nmv.out[1];
      this->Links[nmv.in[1]].next = turnRight ? nmv.out[1] : nmv.out[0];
    }
  }

  /// Numbers the faces in order of first appearance: the classes of united intervals that
  /// hold a first interval, each with the first of them.
  void numberFaces(Boundary2D& out)
  {
    this->assignRoom(this->FaceOfRoot, this->Intervals.size(), -1);
    this->FirstOfFace.clear();
    for (const auto& f : this->First)
    {
      int& face = this->FaceOfRoot[this->find(f.interval)];
      if (face < 0)
      {
        face = static_cast<int>(this->FirstOfFace.size());
        this->FirstOfFace.push_back(&f);
      }
    }
    this->reserveRoom(out.faces, this->FirstOfFace.size());
    out.faces.resize(this->FirstOfFace.size());
  }

  /// Numbers the corners in the order (v, u) instead of the sweep's (u, v): a stable counting
  /// sort of the corners by v. Only the edges' starts are renumbered: the domino step reads
  /// nothing else of the corners.
  void numberCornersAlongV()
  {
    if (this->Corners.empty())
      return;
    Coord lo = this->Corners[0].v, hi = lo;
    for (const Point2& p : this->Corners)
    {
      lo = std::min(lo, p.v);
      hi = std::max(hi, p.v);
    }
    std::vector<std::uint32_t> next(static_cast<std::size_t>(hi - lo) + 2, 0);
    for (const Point2& p : this->Corners)
      ++next[static_cast<std::size_t>(p.v - lo) + 1];
    for (std::size_t k = 1; k < next.size(); ++k)
      next[k] += next[k - 1];
    // In arrays kept from sweep to sweep, as the corners are (their old values overwritten).
    std::vector<std::uint32_t>& number = this->CornerNumbers;
    std::vector<Point2>& sorted = this->SortedCorners;
    number.resize(this->Corners.size());
    sorted.resize(this->Corners.size());
    for (std::size_t c = 0; c < this->Corners.size(); ++c)
    {
      const std::uint32_t n = next[static_cast<std::size_t>(this->Corners[c].v - lo)]++;
      number[c] = n;
      sorted[n] = this->Corners[c];
    }
    this->Corners.swap(sorted);
    for (EdgeLink& e : this->Links)
      e.from = number[e.from];
    if (!this->KeepsScratch)
    {
      std::vector<std::uint32_t>().swap(number);
      std::vector<Point2>().swap(sorted);
    }
  }

  /// Numbers the corners in the order (v, u) as the sweep meets them: the first corner of
  /// each column gets the number after those of the columns before, the next ones follow.
  void numberByColumn(const CornerColumns& columns)
  {
    this->ColumnLo = columns.vLo;
    this->ColumnNext.assign(columns.columns, 0);
    std::uint32_t number = 0;
    const std::uint64_t* word = columns.bits.data();
    for (std::size_t k = 0; k < columns.columns; ++k)
    {
      this->ColumnNext[k] = number;
      for (std::size_t w = 0; w < columns.wordsPerColumn; ++w, ++word)
        number += static_cast<std::uint32_t>(popCount(*word));
    }
  }

  /// After the sweep: every column's next number is the first of the column after it, so the
  /// sweep met each corner of the grid once, and no corner outside it (a corner missed or met
  /// twice would share a number). One pass over the grid's words.
  void checkEveryColumnNumbered(const CornerColumns& columns) const
  {
    std::uint32_t number = 0;
    const std::uint64_t* word = columns.bits.data();
    for (std::size_t k = 0; k < columns.columns; ++k)
    {
      for (std::size_t w = 0; w < columns.wordsPerColumn; ++w, ++word)
        number += static_cast<std::uint32_t>(popCount(*word));
      if (this->ColumnNext[k] != number)
        throw std::logic_error("planeSweep2D: a column's corners not all numbered");
    }
  }

  /// The domino step (Ayala & Vergara, end of section 3.1): each contour's edges, already linked
  /// corner to corner, are followed into loops, each keeping its face on the left; emit gets
  /// the corner each edge starts at. A loop visits its edges in no order of memory (a long
  /// loop jumps across the whole sweep at every step), so each edge's link is read once and
  /// marked in place: its next edge, read, becomes its loop (visitedMark, loopOfEdge), without
  /// a second array to miss in. The edges' ends are read in memory order only, at each loop's
  /// first edge (its face).
  template<typename Emit>
  void orderEdgesIntoLoops(Boundary2D& out, Emit&& emit)
  {
    std::size_t corners = 0, prefetched = 0;
    // Every loop of an EVM has at least four edges (its edges alternate horizontal and
    // vertical, and at a non-manifold vertex a loop always turns): room for all loops, so that
    // they are neither copied nor faulted in twice as they grow (only the pages written are
    // mapped; on a sparse image most of this room is address space the returned boundary holds
    // but never touches). Invalid input only grows the array.
    this->reserveRoom(out.loops, this->Links.size() / 4);
    EdgeLink* links = this->Links.data();
    const std::size_t edges = this->Links.size();
    for (std::size_t e0 = 0; e0 < edges; ++e0)
    {
      if (links[e0].next < Unlinked)
        continue; // in a loop already
      prefetched = this->prefetchEdgesAhead(e0, prefetched);
      // Written in place, not copied in (see startHorizontalEdge).
      const int visited = visitedMark(out.loops.size());
      Loop2D& loop = out.loops.emplace_back();
      loop.face = this->FaceOfRoot[this->find(this->Ends[e0].interval)];
      loop.begin = corners;
      for (int e = static_cast<int>(e0); links[e].next >= Unlinked; ++corners)
      {
        EdgeLink& link = links[e];
        const int next = link.next;
        if (next == Unlinked)
          throw std::logic_error("planeSweep2D: open contour");
        link.next = visited;
        emit(link.from);
        e = next;
      }
      loop.end = corners;
    }
  }

  /// How far ahead of each loop's first edge, in memory order, the domino step reads. A loop
  /// (a small one mostly) runs over the few lines of the sweep after e0's (on the 6001^2 maze,
  /// every other step goes to the next edge in memory and nearly all others less than 2^15
  /// edges away), where it meets edges that no earlier loop read, each a cache line read from
  /// memory while the domino step waits for it, one dependent read after another. Read ahead in
  /// memory order instead, many at once: the maze's whole numbered sweep (12.5 M edges) took
  /// 0.76-1.09 s of CPU without, 0.60-0.81 s with (medians of rounds in turns, load 3-4). The
  /// distance (1 MiB of links) was chosen on machines with 1 MiB of L2 cache per core; with
  /// 16-byte edges 2^14 to 2^18 could not be told apart under that load; with the 8-byte links
  /// 2^17 links gave 0.46-0.47 s of user time per update on the maze against 0.49-0.52 s for
  /// 2^16 (three rounds in turns, load 3).
  static constexpr std::size_t EdgesAhead = std::size_t(1) << 17;
  static_assert(sizeof(EdgeLink) <= 64, "the read-ahead steps a cache line of edges at a time");

  /// Prefetches the edges from `prefetched` up to EdgesAhead after e0, a cache line at a time;
  /// returns where it stopped.
  std::size_t prefetchEdgesAhead(std::size_t e0, std::size_t prefetched) const
  {
    constexpr std::size_t perLine = 64 / sizeof(EdgeLink);
    const std::size_t from = std::max(prefetched, e0);
    const std::size_t until = std::min(e0 + EdgesAhead, this->Links.size());
    const EdgeLink* edges = this->Links.data();
    for (std::size_t e = from; e < until; e += perLine)
      prefetchKept(edges + e);
    return std::max(from, until);
  }

  /// The loop of an edge, once orderEdgesIntoLoops has run.
  int loopOfEdge(int e) const { return loopOfMark(this->Links[e].next); }

  /// The second sweep (Ayala & Vergara, section 3.1): faces in order of first appearance, with 1D
  /// inclusion tests only. A face's first interval is bounded below by its outer loop; the
  /// section end just below it tells where the face lies: in a hole of the face owning that
  /// end, or beside it (then it shares that face's parent).
  void classifyContours(Boundary2D& out) const
  {
    for (std::size_t f = 0; f < out.faces.size(); ++f)
    {
      Face2D& face = out.faces[f];
      const FirstInterval& first = *this->FirstOfFace[f];
      face.outerLoop = this->loopOfEdge(first.bottomEdge);
      if (first.belowEdge >= 0)
      {
        const int belowLoop = this->loopOfEdge(first.belowEdge);
        const Loop2D& below = out.loops[belowLoop];
        const bool inHole = out.faces[below.face].outerLoop != belowLoop;
        face.parent = inHole ? below.face : out.faces[below.face].parent;
      }
      face.depth = face.parent < 0 ? 0 : out.faces[face.parent].depth + 2;
    }
    // Every other loop of a face is one of its holes.
    for (std::size_t l = 0; l < out.loops.size(); ++l)
    {
      Loop2D& loop = out.loops[l];
      Face2D& face = out.faces[loop.face];
      if (face.outerLoop != static_cast<int>(l))
      {
        loop.hole = true;
        face.holeLoops.push_back(static_cast<int>(l));
      }
    }
  }

  bool MergeAtVertices;
  bool KeepsScratch = false;
  std::vector<SectionEnd> Section;     ///< active section, sorted by v
  std::vector<SectionEnd> NextSection; ///< the section being built (reused buffers)
  std::vector<int> NextIntervals;
  std::vector<int> SectionIntervals;        ///< interval id of each pair of section ends
  UnionFind Intervals;                      ///< the section intervals, united into faces
  std::vector<Point2> Corners;              ///< by number, when not numbered by column
  std::vector<std::uint32_t> CornerNumbers; ///< numberCornersAlongV: (u, v) number -> (v, u)
  std::vector<Point2> SortedCorners;        ///< numberCornersAlongV: the corners it sorts into
  std::vector<std::uint32_t> ColumnNext;    ///< numbered by column: the next number of each
  Coord ColumnLo = 0;                       ///< the v of the first column
  std::vector<EdgeLink> Links;              ///< the edges: what the domino step follows
  std::vector<EdgeEnd> Ends; ///< the edges: what the first sweep and the pairing read
  std::vector<FirstInterval> First;
  std::vector<NonManifoldVertex> NonManifold;
  std::vector<int> FaceOfRoot;                   ///< face of each root interval, or -1
  std::vector<const FirstInterval*> FirstOfFace; ///< by face
};

} // namespace

struct detail::PlaneSweep2DMemory
{
  explicit PlaneSweep2DMemory(FaceConnectivity connectivity)
    : Sweeper(connectivity)
  {
  }
  Sweep Sweeper;
  Boundary2D Out;
};

Boundary2D planeSweep2D(const Vertex* begin, const Vertex* end, FaceConnectivity connectivity)
{
  return Sweep(connectivity).run(begin, end);
}

PlaneSweeper2D::PlaneSweeper2D(FaceConnectivity connectivity)
  : Memory(std::make_unique<detail::PlaneSweep2DMemory>(connectivity))
{
}

PlaneSweeper2D::~PlaneSweeper2D() = default;
PlaneSweeper2D::PlaneSweeper2D(PlaneSweeper2D&&) noexcept = default;
PlaneSweeper2D& PlaneSweeper2D::operator=(PlaneSweeper2D&&) noexcept = default;

const Boundary2D& PlaneSweeper2D::sweep(const Vertex* begin, const Vertex* end)
{
  this->Memory->Sweeper.runInto(begin, end, this->Memory->Out);
  return this->Memory->Out;
}

Contours2D planeSweep2DNumbered(const Vertex* begin,
  const Vertex* end,
  CornerOrder order,
  FaceConnectivity connectivity,
  std::size_t fewestByColumn)
{
  return Sweep(connectivity).runNumbered(begin, end, order, fewestByColumn);
}

struct detail::NumberedPlaneSweep2DMemory
{
  explicit NumberedPlaneSweep2DMemory(std::size_t fewestKept)
    : FewestKept(fewestKept)
  {
  }
  Sweep Sweeper = keptSweep();
  Contours2D Out;
  std::vector<Vertex> VertexMemory;

  static Sweep keptSweep()
  {
    Sweep sweep(FaceConnectivity::Edge);
    sweep.keepScratch();
    return sweep;
  }
  std::size_t KeptFor = 0; ///< vertices of the largest sweep since the memory was released
  std::size_t FewestKept;

  /// The rule that keeps memory within a constant times what is used: memory made for `kept`
  /// values (at least FewestKept) is released when fewer than a quarter of them are needed.
  bool tooLargeToKeep(std::size_t kept, std::size_t needed) const
  {
    return kept >= this->FewestKept && needed < kept / 4;
  }
};

NumberedPlaneSweeper2D::NumberedPlaneSweeper2D(std::size_t fewestKept)
  : Memory(std::make_unique<detail::NumberedPlaneSweep2DMemory>(fewestKept))
{
}

NumberedPlaneSweeper2D::~NumberedPlaneSweeper2D() = default;
NumberedPlaneSweeper2D::NumberedPlaneSweeper2D(NumberedPlaneSweeper2D&&) noexcept = default;
NumberedPlaneSweeper2D& NumberedPlaneSweeper2D::operator=(
  NumberedPlaneSweeper2D&&) noexcept = default;

const Contours2D& NumberedPlaneSweeper2D::sweep(const Vertex* begin,
  const Vertex* end,
  CornerOrder order,
  FaceConnectivity connectivity,
  std::size_t fewestByColumn)
{
  detail::NumberedPlaneSweep2DMemory& m = *this->Memory;
  const auto vertices = static_cast<std::size_t>(end - begin);
  // Every array of a sweep is at most linear in its vertices (or, where non-manifold vertices
  // add corners, edges and intervals, in its output): much more than this sweep's is released.
  if (m.tooLargeToKeep(m.KeptFor, vertices))
    this->release();
  m.KeptFor = std::max(m.KeptFor, vertices);
  m.Sweeper.setConnectivity(connectivity);
  m.Sweeper.runNumberedInto(begin, end, order, fewestByColumn, m.Out);
  return m.Out;
}

void NumberedPlaneSweeper2D::release()
{
  detail::NumberedPlaneSweep2DMemory& m = *this->Memory;
  m.Sweeper = detail::NumberedPlaneSweep2DMemory::keptSweep();
  m.Out = Contours2D();
  m.VertexMemory = std::vector<Vertex>();
  m.KeptFor = 0;
}

std::vector<Vertex>& NumberedPlaneSweeper2D::vertexMemory()
{
  return this->Memory->VertexMemory;
}

void NumberedPlaneSweeper2D::keepVertexMemory(std::vector<Vertex>&& vertices)
{
  detail::NumberedPlaneSweep2DMemory& m = *this->Memory;
  if (m.tooLargeToKeep(vertices.capacity(), vertices.size()))
    m.VertexMemory = std::vector<Vertex>();
  else
    m.VertexMemory = std::move(vertices);
}

} // namespace vbr
