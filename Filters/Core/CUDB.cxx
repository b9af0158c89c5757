// EVM -> CUDB and the connected components of its boxes (Cruz-Matias & Ayala, sections 3.2 to 3.5).
//
// The conversion is Algorithm 1 at its three levels. Along A, the section S(i) of each slice
// follows from the previous one by XOR with the plane of vertices (nextSection, formula 1).
// Each section is decomposed line by line along B (SectionDecomposition::build, Algorithm 1 at
// Dim2): the 1D section of each segment between two lines of vertices is the XOR of the
// previous one with the line, and its intervals are the boxes of Algorithm 2, AppendBox
// (appendLineBoxes): an interval equal to one of the previous segment continues that
// rectangle (the 2D compaction), any other starts one; rectangles of consecutive segments
// that meet are contacts along B. Slice after slice (SliceSweep::nextSlice), the rectangles
// equal to one of the previous section continue its box along A (compactRectangles, the 3D
// compaction) and the others start boxes; addContactsAlongB and addContactsAlongA record the
// paper's backward and forward neighbours once per pair, as contacts (face contacts, or
// edge/vertex contacts that are non-manifold). A large 3D sweep is cut into pieces of planes
// (SweptPiece) swept concurrently from the sections entering them and joined by stitch: a
// piece's first rectangles are ghost boxes standing for the open boxes of the piece before.
// The OUDB (buildOUDB) is the same sweep without compaction; toEVM (section 3.3) XORs the
// boxes' corners; volume (section 3.4) adds up the boxes.
//
// The labelling (section 3.5) reads the contacts: earlierNeighbours lists at each box the
// boxes it is compared with (all created before it), labelProvisionally is Algorithm 3 with
// the union-find's unite as Algorithm 4 (makeEquivalence), relabel is Algorithm 5. paintBoxes
// writes a value per box into a label grid, parallel over slices.

#include "CUDB.h"

#include "UnionFind.h"

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <utility>

namespace vbr
{

namespace
{

/// A rectangle of a section's 2D CUDB: [b0, b1) x [c0, c1).
struct Rect
{
  Coord b0, b1, c0, c1;
  bool sameAs(const Rect& o) const { return b0 == o.b0 && b1 == o.b1 && c0 == o.c0 && c1 == o.c1; }
};

/// An interval [c0, c1) of a 1D section, and the rectangle it belongs to.
struct Interval
{
  Coord c0, c1;
  std::uint32_t rect;
};

/// The B-range [b0, b1) between two lines of vertices, over which the 1D section is
/// constant: intervals [first, end) of the section's interval list.
struct Segment
{
  Coord b0, b1;
  std::uint32_t first, end;
};

struct RectContact
{
  std::uint32_t backward, forward;
  bool face;
};

/// Closed intervals [a0, a1] and [b0, b1] meet (possibly in a single point).
bool meet(Coord a0, Coord a1, Coord b0, Coord b1)
{
  return a0 <= b1 && b0 <= a1;
}

/// Open intervals (a0, a1) and (b0, b1) overlap.
bool overlap(Coord a0, Coord a1, Coord b0, Coord b1)
{
  return a0 < b1 && b0 < a1;
}

constexpr Coord Open = std::numeric_limits<Coord>::max(); ///< end not reached yet

/// The 2D CUDB of one section (Algorithm 1 at Dim2, with Algorithm 2, AppendBox, for its lines):
/// line by line, the 1D section is the XOR of the previous one with the line of vertices;
/// an interval equal to one of the previous line extends its rectangle, any other interval
/// starts a new one. Rectangles of consecutive lines that meet are contacts along B.
class SectionDecomposition
{
public:
  std::vector<Rect> rects;       ///< by (b0, c0): creation order
  std::vector<Segment> segments; ///< the non-empty ones
  std::vector<Interval> intervals;
  std::vector<RectContact> contacts;
  /// Intervals of all lines, i.e. the OUDB rectangles of the section.
  std::size_t intervalCount = 0;

  /// Keep only the last line's intervals and segment (enough for a 2D EVM, whose boxes
  /// have no neighbours along A): memory in the width of the image, not its area.
  void keepLastLineOnly(bool last) { this->LastLineOnly = last; }

  void build(const std::vector<Point2>& section)
  {
    this->intervalCount = 0;
    this->rects.clear();
    this->segments.clear();
    this->intervals.clear();
    this->contacts.clear();
    this->Breaks.clear();
    std::size_t i = 0;
    const std::size_t n = section.size();
    while (i < n)
    {
      const Coord b = section[i].u;
      this->Line.clear();
      for (; i < n && section[i].u == b; ++i)
        this->Line.push_back(section[i].v);
      this->Next.clear();
      std::set_symmetric_difference(this->Breaks.begin(),
        this->Breaks.end(),
        this->Line.begin(),
        this->Line.end(),
        std::back_inserter(this->Next));
      this->Breaks.swap(this->Next);
      this->appendLineBoxes(b);
    }
    if (!this->Breaks.empty())
      throw std::invalid_argument("section is not closed: not a valid EVM");
  }

private:
  /// Algorithm 2 (AppendBox) for the brinks of line b, with the 2D compaction: the segment
  /// before b ends, the one after it has the 1D section `Breaks`.
  void appendLineBoxes(Coord b)
  {
    if (this->Breaks.size() % 2 != 0)
      throw std::invalid_argument("odd 1D section: not a valid EVM");
    std::uint32_t prevFirst = 0, prevEnd = 0;
    if (!this->segments.empty() && this->segments.back().b1 == Open)
    {
      Segment& previous = this->segments.back();
      previous.b1 = b;
      prevFirst = previous.first;
      prevEnd = previous.end;
      if (this->LastLineOnly && prevFirst > 0)
      {
        this->intervals.erase(this->intervals.begin(), this->intervals.begin() + prevFirst);
        prevEnd -= prevFirst;
        prevFirst = 0;
        this->segments.assign(1, { previous.b0, b, prevFirst, prevEnd });
      }
    }
    // Every rectangle of the previous line ends here unless an equal interval extends it.
    for (std::uint32_t p = prevFirst; p < prevEnd; ++p)
      this->rects[this->intervals[p].rect].b1 = b;
    if (this->Breaks.empty())
      return;

    const std::uint32_t first = static_cast<std::uint32_t>(this->intervals.size());
    std::uint32_t p = prevFirst;
    for (std::size_t k = 0; k < this->Breaks.size(); k += 2)
    {
      const Coord c0 = this->Breaks[k], c1 = this->Breaks[k + 1];
      // Previous intervals entirely before this one meet no later interval either.
      while (p < prevEnd && this->intervals[p].c1 < c0)
        ++p;
      std::uint32_t q = p;
      if (q < prevEnd && this->intervals[q].c0 == c0 && this->intervals[q].c1 == c1)
      {
        // 2D compaction: the same interval continues its rectangle. No other previous
        // interval can meet it (intervals of a line are separated by a gap).
        const std::uint32_t rect = this->intervals[q].rect;
        this->rects[rect].b1 = Open;
        this->intervals.push_back({ c0, c1, rect });
        continue;
      }
      const std::uint32_t rect = static_cast<std::uint32_t>(this->rects.size());
      this->rects.push_back({ b, Open, c0, c1 });
      this->intervals.push_back({ c0, c1, rect });
      for (; q < prevEnd && this->intervals[q].c0 <= c1; ++q)
      {
        const Interval& prev = this->intervals[q];
        if (meet(prev.c0, prev.c1, c0, c1))
          this->contacts.push_back({ prev.rect, rect, overlap(prev.c0, prev.c1, c0, c1) });
      }
    }
    this->segments.push_back(
      { b, Open, first, static_cast<std::uint32_t>(this->intervals.size()) });
    this->intervalCount += this->intervals.size() - first;
  }

  std::vector<Coord> Breaks, Next, Line;
  bool LastLineOnly = false;
};

/// Formula (1) of Cruz-Matias & Ayala: the section after plane of vertices [begin, end) is the
/// previous section XOR the plane's projection.
void nextSection(const Vertex* begin,
  const Vertex* end,
  std::vector<Point2>& section,
  std::vector<Point2>& scratch)
{
  scratch.clear();
  std::size_t i = 0;
  const Vertex* v = begin;
  while (i < section.size() || v != end)
  {
    if (v == end || (i < section.size() && section[i] < Point2{ (*v)[1], (*v)[2] }))
      scratch.push_back(section[i++]);
    else if (i == section.size() || Point2{ (*v)[1], (*v)[2] } < section[i])
      scratch.push_back({ (*v)[1], (*v)[2] }), ++v;
    else
      ++i, ++v; // a vertex in both cancels
  }
  section.swap(scratch);
}

/// Box of a rectangle spanning [a0, a1) along A, in world axes.
Box boxOf(const Rect& r, Coord a0, Coord a1, const AxisOrder& order)
{
  Box box;
  box.lo[order[0]] = a0;
  box.hi[order[0]] = a1;
  box.lo[order[1]] = r.b0;
  box.hi[order[1]] = r.b1;
  box.lo[order[2]] = r.c0;
  box.hi[order[2]] = r.c1;
  return box;
}

/// The 3D part of Algorithm 1 (at Dim3): slice after slice, the rectangles of the section are
/// matched with those of the previous section; an equal rectangle extends its box along A (3D
/// compaction), any other starts a box. Contacts along A join the boxes that end at the
/// plane between two slices to the boxes that start there.
class SliceSweep
{
public:
  SliceSweep(const AxisOrder& order, CUDB& out)
    : Order(order)
    , Out(out)
  {
  }

  /// Starts a piece of the sweep after an earlier piece: the section before the first slice
  /// stands for the slice the earlier piece ended with. Its rectangles get ghost boxes,
  /// which the stitching maps to the earlier piece's open boxes (the two decompositions of
  /// one section are the same).
  void enterAfter(const std::vector<Point2>& section)
  {
    this->Previous.build(section);
    const std::size_t n = this->Previous.rects.size();
    this->PreviousBox.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      this->PreviousBox[i] = GhostBit | static_cast<std::uint32_t>(i);
    this->GhostEnd.assign(n, Open);
  }

  /// The section of the slice starting at plane a (empty past the last plane).
  void nextSlice(Coord a, const std::vector<Point2>& section)
  {
    this->Current.build(section);
    this->Out.oudbBoxCount += this->Current.intervalCount;
    const std::size_t n = this->Current.rects.size();
    this->CurrentBox.assign(n, 0);
    this->CurrentIsNew.assign(n, 1);
    this->PreviousContinues.assign(this->Previous.rects.size(), 0);
    this->compactRectangles(a);
    this->addContactsAlongB();
    this->addContactsAlongA();
    std::swap(this->Previous, this->Current);
    std::swap(this->PreviousBox, this->CurrentBox);
  }

private:
  /// The 3D compaction (Algorithm 1's loop over SliceBoxesTmp): a rectangle equal to one of
  /// the previous section continues its box, any other starts a box at a; boxes of the
  /// previous section not continued end at a.
  void compactRectangles(Coord a)
  {
    const auto& prev = this->Previous.rects;
    const auto& cur = this->Current.rects;
    std::size_t p = 0;
    for (std::size_t r = 0; r < cur.size(); ++r)
    {
      // Both lists are sorted by (b0, c0) and hold disjoint rectangles.
      while (p < prev.size() &&
        (prev[p].b0 < cur[r].b0 || (prev[p].b0 == cur[r].b0 && prev[p].c0 < cur[r].c0)))
        ++p;
      if (p < prev.size() && prev[p].sameAs(cur[r]))
      {
        this->CurrentBox[r] = this->PreviousBox[p];
        this->CurrentIsNew[r] = 0;
        this->PreviousContinues[p] = 1;
        continue;
      }
      this->CurrentBox[r] = static_cast<std::uint32_t>(this->Out.boxes.size());
      this->Out.boxes.push_back(boxOf(cur[r], a, Open, this->Order));
    }
    for (std::size_t q = 0; q < prev.size(); ++q)
      if (!this->PreviousContinues[q])
        this->endBox(this->PreviousBox[q], a);
  }

  void endBox(std::uint32_t box, Coord a)
  {
    if (box & GhostBit)
      this->GhostEnd[box & ~GhostBit] = a;
    else
      this->Out.boxes[box].hi[this->Order[0]] = a;
  }

  /// Contacts across lines within the slice; those between two continued boxes were
  /// recorded in an earlier slice.
  void addContactsAlongB()
  {
    for (const RectContact& c : this->Current.contacts)
      if (this->CurrentIsNew[c.backward] || this->CurrentIsNew[c.forward])
        this->Out.contacts.push_back({ this->CurrentBox[c.backward],
          this->CurrentBox[c.forward],
          static_cast<std::uint8_t>(this->Order[1]),
          c.face });
  }

  /// Contacts across the plane between the previous slice and this one, between a box that
  /// ends there and a box that starts there. Segments of the two sections that meet along B
  /// are compared interval by interval; a pair found in several segments is kept once.
  void addContactsAlongA()
  {
    const auto& ps = this->Previous.segments;
    const auto& cs = this->Current.segments;
    this->Found.clear();
    std::size_t first = 0;
    for (const Segment& s : ps)
    {
      // Segments of either list are sorted and disjoint but may touch: every segment of
      // the other list from the first that does not end before s to the last that starts
      // no later than s ends.
      while (first < cs.size() && cs[first].b1 < s.b0)
        ++first;
      for (std::size_t j = first; j < cs.size() && cs[j].b0 <= s.b1; ++j)
        this->compareSegments(s, cs[j], overlap(s.b0, s.b1, cs[j].b0, cs[j].b1));
    }
    if (this->Found.empty())
      return;
    std::sort(this->Found.begin(),
      this->Found.end(),
      [](const RectContact& x, const RectContact& y)
      { return x.backward < y.backward || (x.backward == y.backward && x.forward < y.forward); });
    std::size_t k = 0;
    while (k < this->Found.size())
    {
      RectContact c = this->Found[k];
      for (++k; k < this->Found.size() && this->Found[k].backward == c.backward &&
           this->Found[k].forward == c.forward;
           ++k)
        c.face = c.face || this->Found[k].face;
      this->Out.contacts.push_back({ this->PreviousBox[c.backward],
        this->CurrentBox[c.forward],
        static_cast<std::uint8_t>(this->Order[0]),
        c.face });
    }
  }

  void compareSegments(const Segment& s, const Segment& t, bool openAlongB)
  {
    const auto& pi = this->Previous.intervals;
    const auto& ci = this->Current.intervals;
    std::uint32_t i = s.first, j = t.first;
    while (i < s.end && j < t.end)
    {
      const Interval& x = pi[i];
      const Interval& y = ci[j];
      if (meet(x.c0, x.c1, y.c0, y.c1) && !this->PreviousContinues[x.rect] &&
        this->CurrentIsNew[y.rect])
        this->Found.push_back({ x.rect, y.rect, openAlongB && overlap(x.c0, x.c1, y.c0, y.c1) });
      if (x.c1 < y.c1)
        ++i;
      else
        ++j;
    }
  }

public:
  /// Box ids with this bit are ghosts (see enterAfter).
  static constexpr std::uint32_t GhostBit = std::uint32_t(1) << 31;
  /// Boxes still open after the last slice, by rectangle of that slice.
  const std::vector<std::uint32_t>& openBoxes() const { return this->PreviousBox; }
  /// Where each ghost box ended along A (Open: it goes on past this piece).
  const std::vector<Coord>& ghostEnds() const { return this->GhostEnd; }

private:
  const AxisOrder Order;
  CUDB& Out;
  std::vector<Coord> GhostEnd;
  SectionDecomposition Previous, Current;
  std::vector<std::uint32_t> PreviousBox, CurrentBox; ///< box of each rectangle
  std::vector<char> CurrentIsNew, PreviousContinues;
  std::vector<RectContact> Found;
};

/// Pieces of a 3D sweep: one per thread when the EVM is large enough to repay the
/// stitching and each piece keeps many planes.
int automaticPieces(std::size_t vertices, std::size_t planes, int concurrency)
{
  constexpr std::size_t MinimumVertices = 50000, MinimumPlanesPerPiece = 16;
  if (concurrency < 2 || vertices < MinimumVertices)
    return 1;
  return static_cast<int>(std::min<std::size_t>(concurrency, planes / MinimumPlanesPerPiece));
}

/// The sweep over planes [first, last) of an EVM, with its own boxes and contacts.
struct SweptPiece
{
  CUDB part;
  std::vector<std::uint32_t> openBoxes;
  std::vector<Coord> ghostEnds;
  bool aborted = false;
  bool lastSectionEmpty = false;

  void sweep(const EVM& evm,
    const std::vector<std::size_t>& starts,
    std::vector<Point2> section,
    std::size_t first,
    std::size_t last,
    bool afterAnotherPiece,
    const Execution& exec)
  {
    const std::vector<Vertex>& v = evm.vertices();
    std::vector<Point2> scratch;
    SliceSweep sweep(evm.order(), this->part);
    if (afterAnotherPiece)
      sweep.enterAfter(section);
    for (std::size_t k = first; k < last; ++k)
    {
      if (((k - first) & 15) == 0 && exec.stopRequested())
      {
        this->aborted = true;
        return;
      }
      nextSection(v.data() + starts[k], v.data() + starts[k + 1], section, scratch);
      sweep.nextSlice(v[starts[k]][0], section);
    }
    this->openBoxes = sweep.openBoxes();
    this->ghostEnds = sweep.ghostEnds();
    this->lastSectionEmpty = section.empty();
  }
};

/// Joins the pieces in sweep order: a piece's ghost boxes are the open boxes of the piece
/// before, so its boxes come after theirs and the result is the one sequential sweep's.
void stitch(std::vector<SweptPiece>& pieces, CUDB& out)
{
  const int axisA = out.order[0];
  std::vector<std::uint32_t> open; // global ids of the boxes open before the current piece
  for (SweptPiece& piece : pieces)
  {
    const std::uint32_t offset = static_cast<std::uint32_t>(out.boxes.size());
    auto global = [&](std::uint32_t id)
    { return (id & SliceSweep::GhostBit) ? open[id & ~SliceSweep::GhostBit] : offset + id; };
    for (std::size_t g = 0; g < piece.ghostEnds.size(); ++g)
      if (piece.ghostEnds[g] != Open)
        out.boxes[open[g]].hi[axisA] = piece.ghostEnds[g];
    out.boxes.insert(out.boxes.end(), piece.part.boxes.begin(), piece.part.boxes.end());
    out.contacts.reserve(out.contacts.size() + piece.part.contacts.size());
    for (const BoxContact& c : piece.part.contacts)
      out.contacts.push_back({ global(c.backward), global(c.forward), c.axis, c.face });
    out.oudbBoxCount += piece.part.oudbBoxCount;
    for (std::uint32_t& id : piece.openBoxes)
      id = global(id);
    open.swap(piece.openBoxes);
    piece.part = CUDB(); // memory: one copy of the boxes at a time
  }
}

} // namespace

std::int64_t CUDB::volume() const
{
  std::int64_t v = 0;
  for (const Box& b : this->boxes)
    v += b.volume();
  return v;
}

bool buildCUDB(const EVM& evm, const Execution& exec, CUDB& out, int pieces)
{
  out = CUDB();
  out.dimension = evm.dimension();
  out.order = evm.order();
  const std::vector<Vertex>& v = evm.vertices();
  const std::vector<std::size_t> starts = evm.planeStarts();
  std::vector<Point2> section, scratch;
  if (evm.dimension() == 2)
  {
    // A 2D EVM is a single section: its rectangles are the boxes, one voxel thick.
    nextSection(v.data(), v.data() + v.size(), section, scratch);
    SectionDecomposition d;
    d.keepLastLineOnly(true);
    d.build(section);
    out.oudbBoxCount = d.intervalCount;
    for (const Rect& r : d.rects)
      out.boxes.push_back(boxOf(r, 0, 1, out.order));
    for (const RectContact& c : d.contacts)
      out.contacts.push_back(
        { c.backward, c.forward, static_cast<std::uint8_t>(out.order[1]), c.face });
    return true;
  }
  const std::size_t planes = starts.size() - 1;
  if (pieces <= 0)
    pieces = automaticPieces(evm.size(), planes, exec.concurrency);
  pieces =
    static_cast<int>(std::min<std::size_t>(std::max(pieces, 1), std::max<std::size_t>(planes, 1)));
  std::vector<std::size_t> firstPlane(pieces + 1);
  for (int p = 0; p <= pieces; ++p)
    firstPlane[p] = planes * p / pieces;
  // The section entering each piece: the XOR of all planes before it (a sequential pass,
  // cheap next to the decompositions).
  std::vector<std::vector<Point2>> entering(pieces);
  for (int p = 1; p < pieces; ++p)
  {
    for (std::size_t k = firstPlane[p - 1]; k < firstPlane[p]; ++k)
      nextSection(v.data() + starts[k], v.data() + starts[k + 1], section, scratch);
    entering[p] = section;
  }
  std::vector<SweptPiece> swept(pieces);
  exec.forRange(pieces,
    [&](std::int64_t begin, std::int64_t end)
    {
      for (std::int64_t p = begin; p < end; ++p)
        swept[p].sweep(evm, starts, entering[p], firstPlane[p], firstPlane[p + 1], p > 0, exec);
    });
  for (const SweptPiece& piece : swept)
    if (piece.aborted)
      return false;
  if (!swept.back().lastSectionEmpty)
    throw std::invalid_argument("the last section is not empty: not a valid EVM");
  stitch(swept, out);
  return true;
}

CUDB buildCUDB(const EVM& evm)
{
  CUDB out;
  buildCUDB(evm, Execution(), out);
  return out;
}

std::vector<Box> buildOUDB(const EVM& evm)
{
  std::vector<Box> boxes;
  const AxisOrder& order = evm.order();
  const std::vector<Vertex>& v = evm.vertices();
  const std::vector<std::size_t> starts = evm.planeStarts();
  std::vector<Point2> section, scratch;
  SectionDecomposition d;
  // Every interval of every segment is a box: no compaction along B nor along A.
  auto addBoxes = [&](Coord a0, Coord a1)
  {
    d.build(section);
    for (const Segment& s : d.segments)
      for (std::uint32_t i = s.first; i < s.end; ++i)
      {
        const Interval& in = d.intervals[i];
        boxes.push_back(boxOf({ s.b0, s.b1, in.c0, in.c1 }, a0, a1, order));
      }
  };
  if (evm.dimension() == 2)
  {
    nextSection(v.data(), v.data() + v.size(), section, scratch);
    addBoxes(0, 1);
    return boxes;
  }
  for (std::size_t k = 0; k + 1 < starts.size(); ++k)
  {
    nextSection(v.data() + starts[k], v.data() + starts[k + 1], section, scratch);
    if (!section.empty())
      addBoxes(v[starts[k]][0], v[starts[k + 1]][0]);
  }
  return boxes;
}

EVM toEVM(const CUDB& cudb)
{
  // Corners in sorting coordinates; a vertex shared by an even number of boxes cancels.
  const AxisOrder& order = cudb.order;
  std::vector<Vertex> corners;
  const int n = cudb.dimension == 2 ? 4 : 8;
  corners.reserve(n * cudb.boxes.size());
  for (const Box& box : cudb.boxes)
    for (int k = 0; k < n; ++k)
    {
      Vertex c;
      for (int d = 0; d < 3; ++d)
      {
        const int axis = order[d];
        const bool high = cudb.dimension == 2 ? (d > 0 && (k >> (d - 1) & 1)) : (k >> d & 1);
        c[d] = cudb.dimension == 2 && d == 0 ? 0 : (high ? box.hi[axis] : box.lo[axis]);
      }
      corners.push_back(c);
    }
  std::sort(corners.begin(), corners.end());
  std::vector<Vertex> odd;
  for (std::size_t i = 0; i < corners.size();)
  {
    std::size_t j = i + 1;
    while (j < corners.size() && corners[j] == corners[i])
      ++j;
    if ((j - i) % 2 == 1)
      odd.push_back(corners[i]);
    i = j;
  }
  return EVM(cudb.dimension, order, std::move(odd));
}

CUDB::NeighbourLists CUDB::neighbours(int axisRole, bool forward, Connectivity connectivity) const
{
  const int axis = this->order[this->dimension == 2 ? 1 : axisRole];
  NeighbourLists lists;
  lists.start.assign(this->boxes.size() + 1, 0);
  auto wanted = [&](const BoxContact& c)
  { return c.axis == axis && (connectivity == Connectivity::Vertex || c.face); };
  auto owner = [&](const BoxContact& c) { return forward ? c.backward : c.forward; };
  auto other = [&](const BoxContact& c) { return forward ? c.forward : c.backward; };
  for (const BoxContact& c : this->contacts)
    if (wanted(c))
      ++lists.start[owner(c) + 1];
  for (std::size_t i = 0; i < this->boxes.size(); ++i)
    lists.start[i + 1] += lists.start[i];
  lists.boxes.resize(lists.start.back());
  std::vector<std::uint32_t> fill(lists.start.begin(), lists.start.end() - 1);
  for (const BoxContact& c : this->contacts)
    if (wanted(c))
      lists.boxes[fill[owner(c)]++] = other(c);
  return lists;
}

namespace
{

/// The neighbours each box is compared with when it is labelled (the paper's
/// ABackwardNeighbors and BBackwardNeighbors together): every usable contact listed at the
/// later of its two boxes in creation order, pointing to the earlier one, so that each box
/// is labelled after all the boxes it is compared with.
CUDB::NeighbourLists earlierNeighbours(const CUDB& cudb, Connectivity connectivity)
{
  const std::size_t n = cudb.boxes.size();
  CUDB::NeighbourLists lists;
  lists.start.assign(n + 1, 0);
  auto usable = [&](const BoxContact& c) { return connectivity == Connectivity::Vertex || c.face; };
  for (const BoxContact& c : cudb.contacts)
    if (usable(c))
      ++lists.start[std::max(c.backward, c.forward) + 1];
  for (std::size_t i = 0; i < n; ++i)
    lists.start[i + 1] += lists.start[i];
  lists.boxes.resize(lists.start.back());
  std::vector<std::uint32_t> fill(lists.start.begin(), lists.start.end() - 1);
  for (const BoxContact& c : cudb.contacts)
    if (usable(c))
      lists.boxes[fill[std::max(c.backward, c.forward)]++] = std::min(c.backward, c.forward);
  return lists;
}

/// Algorithm 3 (CCL), the labelling pass: boxes in creation order take the smallest label of
/// their backward neighbours, or a new label when they have none; where two labels meet, the
/// equivalence is recorded (Algorithm 4, makeEquivalence: the union-find's unite, which keeps
/// the smaller label as representative). Provisional labels are 0-based here.
std::vector<std::uint32_t> labelProvisionally(const CUDB::NeighbourLists& earlier,
  UnionFind& equivalences)
{
  const std::size_t n = earlier.start.size() - 1;
  std::vector<std::uint32_t> label(n, 0);
  for (std::size_t b = 0; b < n; ++b)
  {
    if (earlier.start[b] == earlier.start[b + 1])
    {
      label[b] = equivalences.add();
      continue;
    }
    std::uint32_t l = equivalences.find(label[earlier.boxes[earlier.start[b]]]);
    for (std::uint32_t k = earlier.start[b] + 1; k < earlier.start[b + 1]; ++k)
      l = equivalences.unite(l, label[earlier.boxes[k]]);
    label[b] = l;
  }
  return label;
}

/// Algorithm 5 (relabeling): every label replaced by the representative of its class, then
/// the classes numbered 1..count in order of first appearance along the boxes. Returns count.
std::uint32_t relabel(UnionFind& equivalences, std::vector<std::uint32_t>& label)
{
  std::uint32_t count = 0;
  std::vector<std::uint32_t> consecutive(equivalences.size(), 0);
  for (std::uint32_t& l : label)
  {
    const std::uint32_t root = equivalences.find(l);
    if (consecutive[root] == 0)
      consecutive[root] = ++count;
    l = consecutive[root];
  }
  return count;
}

} // namespace

Components labelComponents(const CUDB& cudb, Connectivity connectivity)
{
  UnionFind equivalences;
  Components result;
  result.boxLabel = labelProvisionally(earlierNeighbours(cudb, connectivity), equivalences);
  result.count = relabel(equivalences, result.boxLabel);
  return result;
}

void paintBoxes(const std::vector<Box>& boxes,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 3>& offset,
  const std::array<int, 3>& axes,
  const std::array<Coord, 3>& dims,
  std::int32_t* labels,
  const Execution& exec)
{
  const std::int64_t nx = dims[0], nxy = std::int64_t(dims[0]) * dims[1];
  // Workers own disjoint ranges of slices (of rows when the grid is a single slice) and
  // paint the part of every box inside them.
  const int split = dims[2] > 1 ? 2 : 1;
  exec.forRange(dims[split],
    [&](std::int64_t from, std::int64_t to)
    {
      for (std::size_t b = 0; b < boxes.size(); ++b)
      {
        const std::int32_t v = value[b];
        if (v == 0)
          continue;
        std::array<std::int64_t, 3> lo, hi;
        for (int k = 0; k < 3; ++k)
        {
          lo[axes[k]] = std::int64_t(boxes[b].lo[k]) + offset[k];
          hi[axes[k]] = std::int64_t(boxes[b].hi[k]) + offset[k];
        }
        lo[split] = std::max(lo[split], from);
        hi[split] = std::min(hi[split], to);
        for (std::int64_t z = lo[2]; z < hi[2]; ++z)
          for (std::int64_t y = lo[1]; y < hi[1]; ++y)
          {
            std::int32_t* row = labels + z * nxy + y * nx;
            std::fill(row + lo[0], row + hi[0], v);
          }
      }
    });
}

} // namespace vbr
