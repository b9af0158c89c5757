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
// Cost: every XOR (of a section with a plane, of a 1D section with a line) is one merge of
// sorted integers without branches on the comparisons (mergeCancelling: porous and noisy
// objects make them unpredictable); sections are packed (B, C) integers (SectionPoint); the
// per-slice and per-line lists live in buffers kept from slice to slice; a pair of rectangles
// is recorded once at a segment pair chosen from the rectangles (addContactAlongA), not by
// sorting the pairs found.
//
// The labelling (section 3.5) reads the contacts: each box starts as its own provisional
// label, every usable contact is an equivalence (Algorithms 3 and 4, makeEquivalences, in the
// union-find whose representatives are the first boxes of their classes) and relabel is
// Algorithm 5. buildCUDBComponents makes the same equivalences during the sweep, as each
// contact is found (ContactSink), for callers that need no contact list. paintBoxes writes a
// value per box into a label grid, parallel over slices.
//
// A 2D image in its stored sorting needs no EVM: buildCUDBComponents2D reads the runs of each
// pixel row from its bits and matches them with the runs of the row before (PixelRowSweep),
// which gives the rectangles, their order and their contacts of the EVM sweep, and unites the
// boxes of each contact as it goes. On a 6001^2 maze the EVM (12.5 M vertices, 150 MB) and
// its section decomposition cost more than all the rest of the update.

#include "CUDB.h"
#include "DefaultInitAllocator.h"

#include "UnionFind.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace vbr
{

namespace
{

/// A list of the sweep's, grown without zeroing (see Uninitialized).
template<typename T>
using List = std::vector<T, Uninitialized<T>>;

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
  std::uint32_t box; ///< the rectangle's box, once known (labelling only)
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

/// A point (B, C) of a section packed in one integer whose order is the points' order (B
/// first): sections are merged as plain integers. The sign bits are flipped so that negative
/// coordinates keep their order.
using SectionPoint = std::uint64_t;
using Section = List<SectionPoint>;

SectionPoint sectionPoint(Coord b, Coord c)
{
  constexpr std::uint32_t Sign = std::uint32_t(1) << 31;
  return std::uint64_t(std::uint32_t(b) ^ Sign) << 32 | (std::uint32_t(c) ^ Sign);
}
Coord bOf(SectionPoint p)
{
  return static_cast<Coord>(std::uint32_t(p >> 32) ^ (std::uint32_t(1) << 31));
}
Coord cOf(SectionPoint p)
{
  return static_cast<Coord>(std::uint32_t(p) ^ (std::uint32_t(1) << 31));
}

/// The XOR of two sorted sequences without repeats, written from `out` (room for both):
/// an element in both cancels. The second sequence is read through `key` (a plane's vertices,
/// a line's points), so that it is not copied first. Without branches on the comparisons,
/// which a porous or noisy object makes unpredictable. Returns the end of the output.
template<typename T, typename U, typename Key>
T* mergeCancelling(const T* a, const T* aEnd, const U* b, const U* bEnd, Key key, T* out)
{
  while (a != aEnd && b != bEnd)
  {
    // Two flags rather than `x != y` keep the compiler from branching again.
    const T x = *a, y = key(*b);
    const bool takeA = x <= y, takeB = y <= x;
    *out = takeA ? x : y;
    out += takeA != takeB;
    a += takeA;
    b += takeB;
  }
  out = std::copy(a, aEnd, out);
  return std::transform(b, bEnd, out, key);
}

/// The 2D CUDB of one section (Algorithm 1 at Dim2, with Algorithm 2, AppendBox, for its lines):
/// line by line, the 1D section is the XOR of the previous one with the line of vertices;
/// an interval equal to one of the previous line extends its rectangle, any other interval
/// starts a new one. Rectangles of consecutive lines that meet are contacts along B.
class SectionDecomposition
{
public:
  List<Rect> rects;       ///< by (b0, c0): creation order
  List<Segment> segments; ///< the non-empty ones
  List<Interval> intervals;
  List<RectContact> contacts;
  /// Intervals of all lines, i.e. the OUDB rectangles of the section.
  std::size_t intervalCount = 0;

  /// Keep only the last line's intervals and segment (enough for a 2D EVM, whose boxes
  /// have no neighbours along A): memory in the width of the image, not its area.
  void keepLastLineOnly(bool last) { this->LastLineOnly = last; }
  /// Keep only the contacts of positive area (labelling with face connectivity).
  void keepFaceContactsOnly(bool faceOnly) { this->FaceContactsOnly = faceOnly; }

  void build(const Section& section)
  {
    this->build(section.data(), section.data() + section.size(), bOf, cOf);
  }

  /// The same for points [begin, end) sorted by (B, C) and read through `b` and `c`: a 2D
  /// EVM is its own section, read in place (a copy is as large as the EVM).
  template<typename Point, typename BOf, typename COf>
  void build(const Point* begin, const Point* end, BOf b, COf c)
  {
    this->intervalCount = 0;
    this->rects.clear();
    this->segments.clear();
    this->intervals.clear();
    this->contacts.clear();
    this->Breaks.clear();
    const Point* line = begin;
    while (line != end)
    {
      const Coord lineB = b(*line);
      const Point* next = line;
      while (next != end && b(*next) == lineB)
        ++next;
      this->crossLine(line, next, c);
      this->appendLineBoxes(lineB);
      line = next;
    }
    if (!this->Breaks.empty())
      throw std::invalid_argument("section is not closed: not a valid EVM");
  }

  /// Room for `rects` rectangles and as many contacts, so that a section of millions of
  /// rectangles (a 2D image) is not copied each time its lists double. Reserved only: pages
  /// that are never written cost no memory.
  void reserve(std::size_t rects)
  {
    this->rects.reserve(rects);
    this->contacts.reserve(rects);
  }

private:
  /// The 1D section past a line of vertices: the one before it XOR the line's C coordinates
  /// (both sorted), in buffers kept from line to line.
  template<typename Point, typename COf>
  void crossLine(const Point* line, const Point* end, COf c)
  {
    this->Next.resize(this->Breaks.size() + static_cast<std::size_t>(end - line));
    const Coord* out = mergeCancelling(this->Breaks.data(),
      this->Breaks.data() + this->Breaks.size(),
      line,
      end,
      c,
      this->Next.data());
    this->Next.resize(static_cast<std::size_t>(out - this->Next.data()));
    this->Breaks.swap(this->Next);
  }

  /// Algorithm 2 (AppendBox) for the brinks of line b, with the 2D compaction: the segment
  /// before b ends, the one after it has the 1D section `Breaks`.
  void appendLineBoxes(Coord b)
  {
    if (this->Breaks.size() % 2 != 0)
      throw std::invalid_argument("odd 1D section: not a valid EVM");
    std::uint32_t prevFirst = 0, prevEnd = 0;
    this->closePreviousSegment(b, prevFirst, prevEnd);
    if (this->Breaks.empty())
      return;
    const std::uint32_t first = static_cast<std::uint32_t>(this->intervals.size());
    this->appendIntervals(b, prevFirst, prevEnd);
    this->segments.push_back(
      { b, Open, first, static_cast<std::uint32_t>(this->intervals.size()) });
    this->intervalCount += this->intervals.size() - first;
  }

  /// The segment before line b ends there, with every rectangle of its intervals (those that
  /// an equal interval of the line extends are opened again by appendIntervals). Gives that
  /// segment's intervals [prevFirst, prevEnd).
  void closePreviousSegment(Coord b, std::uint32_t& prevFirst, std::uint32_t& prevEnd)
  {
    if (this->segments.empty() || this->segments.back().b1 != Open)
      return;
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
    for (std::uint32_t p = prevFirst; p < prevEnd; ++p)
      this->rects[this->intervals[p].rect].b1 = b;
  }

  /// The intervals of the 1D section `Breaks` after line b: an interval equal to one of the
  /// previous segment [prevFirst, prevEnd) continues its rectangle (no other previous interval
  /// can meet it: intervals of a line are separated by a gap), any other starts a rectangle
  /// and meets previous intervals along B. The lists are grown to their largest size first
  /// (at most n + m - 1 pairs of two lines' intervals meet) and written through pointers:
  /// push_back re-read the vectors after every store into a rectangle.
  void appendIntervals(Coord b, std::uint32_t prevFirst, std::uint32_t prevEnd)
  {
    const std::size_t count = this->Breaks.size() / 2;
    const std::size_t firstInterval = this->intervals.size(), firstRect = this->rects.size();
    const std::size_t firstContact = this->contacts.size();
    this->intervals.resize(firstInterval + count);
    this->rects.resize(firstRect + count);
    this->contacts.resize(firstContact + count + (prevEnd - prevFirst));
    const Coord* const breaks = this->Breaks.data();
    Interval* const in = this->intervals.data();
    Interval* out = in + firstInterval;
    Rect* const rects = this->rects.data();
    auto rect = static_cast<std::uint32_t>(firstRect);
    RectContact* contact = this->contacts.data() + firstContact;
    std::uint32_t p = prevFirst;
    for (std::size_t k = 0; k < count; ++k)
    {
      const Coord c0 = breaks[2 * k], c1 = breaks[2 * k + 1];
      // Previous intervals entirely before this one meet no later interval either.
      while (p < prevEnd && in[p].c1 < c0)
        ++p;
      std::uint32_t q = p;
      if (q < prevEnd && in[q].c0 == c0 && in[q].c1 == c1)
      {
        rects[in[q].rect].b1 = Open; // 2D compaction
        *out++ = { c0, c1, in[q].rect, 0 };
        continue;
      }
      rects[rect] = { b, Open, c0, c1 };
      *out++ = { c0, c1, rect, 0 };
      // Every previous interval from p on that starts no later than c1 meets [c0, c1]; kept
      // without a branch (all, or those with a face when labelling by faces).
      for (; q < prevEnd && in[q].c0 <= c1; ++q)
      {
        const bool face = overlap(in[q].c0, in[q].c1, c0, c1);
        *contact = { in[q].rect, rect, face };
        contact += face || !this->FaceContactsOnly;
      }
      ++rect;
    }
    this->rects.resize(rect);
    this->contacts.resize(static_cast<std::size_t>(contact - this->contacts.data()));
  }

  List<Coord> Breaks, Next;
  bool LastLineOnly = false;
  bool FaceContactsOnly = false;
};

/// Formula (1) of Cruz-Matias & Ayala: the section after plane of vertices [begin, end) is the
/// previous section XOR the plane's projection.
void nextSection(const Vertex* begin, const Vertex* end, Section& section, Section& scratch)
{
  scratch.resize(section.size() + static_cast<std::size_t>(end - begin));
  const SectionPoint* out = mergeCancelling(
    section.data(),
    section.data() + section.size(),
    begin,
    end,
    [](const Vertex& v) { return sectionPoint(v[1], v[2]); },
    scratch.data());
  scratch.resize(static_cast<std::size_t>(out - scratch.data()));
  section.swap(scratch);
}

/// Box of a rectangle spanning [a0, a1) along A, in world axes. Each world axis picks its
/// sorting role, so that the box is written at fixed places: stores at places known only at
/// run time, read back at once as a whole box, stalled the sweep.
Box boxOf(const Rect& r, Coord a0, Coord a1, const AxisOrder& order)
{
  const Coord lo[3] = { a0, r.b0, r.c0 }, hi[3] = { a1, r.b1, r.c1 };
  Box box;
  for (int d = 0; d < 3; ++d)
  {
    const int role = order[0] == d ? 0 : (order[1] == d ? 1 : 2);
    box.lo[d] = lo[role];
    box.hi[d] = hi[role];
  }
  return box;
}

/// Box ids with this bit are ghosts: in a piece of the sweep, the boxes of the piece before
/// that are still open where it starts (see SliceSweep::enterAfter).
constexpr std::uint32_t GhostBit = std::uint32_t(1) << 31;

/// Where the sweep's contacts go. Recording: every contact into the CUDB's list, once. Labelling
/// (Algorithms 3 and 4 on the fly): each contact of the wanted connectivity is an equivalence
/// as soon as it is found, so that no contact list is written and read back; a contact may
/// then be found more than once (the equivalence is the same), and contacts with a ghost box
/// are kept in the list for the stitching, which knows the ghost's box.
class ContactSink
{
public:
  explicit ContactSink(std::vector<BoxContact>& list)
    : List(list)
  {
  }
  ContactSink(std::vector<BoxContact>& ghostContacts,
    UnionFind& equivalences,
    Connectivity connectivity)
    : List(ghostContacts)
    , Equivalences(&equivalences)
    , FaceOnly(connectivity == Connectivity::Face)
  {
  }

  bool labelling() const { return this->Equivalences != nullptr; }
  /// Only contacts of positive area count (labelling with face connectivity).
  bool faceOnly() const { return this->FaceOnly; }

  /// A new box, numbered after the others.
  void addBox()
  {
    if (this->Equivalences)
      this->Equivalences->add();
  }

  void add(std::uint32_t backward, std::uint32_t forward, int axis, bool face)
  {
    if (this->Equivalences && ((backward | forward) & GhostBit) == 0)
    {
      if (face || !this->FaceOnly)
        this->Equivalences->unite(backward, forward);
      return;
    }
    if (face || !this->FaceOnly)
      this->List.push_back({ backward, forward, static_cast<std::uint8_t>(axis), face });
  }

private:
  std::vector<BoxContact>& List;
  UnionFind* Equivalences = nullptr;
  bool FaceOnly = false;
};

/// The 3D part of Algorithm 1 (at Dim3): slice after slice, the rectangles of the section are
/// matched with those of the previous section; an equal rectangle extends its box along A (3D
/// compaction), any other starts a box. Contacts along A join the boxes that end at the
/// plane between two slices to the boxes that start there.
class SliceSweep
{
public:
  SliceSweep(const AxisOrder& order, CUDB& out, ContactSink sink)
    : Order(order)
    , Out(out)
    , Sink(sink)
  {
    for (SectionDecomposition* d : { &this->Previous, &this->Current })
      d->keepFaceContactsOnly(sink.labelling() && sink.faceOnly());
  }

  /// Starts a piece of the sweep after an earlier piece: the section before the first slice
  /// stands for the slice the earlier piece ended with. Its rectangles get ghost boxes,
  /// which the stitching maps to the earlier piece's open boxes (the two decompositions of
  /// one section are the same).
  void enterAfter(const Section& section)
  {
    this->Previous.build(section);
    const std::size_t n = this->Previous.rects.size();
    this->PreviousBox.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      this->PreviousBox[i] = GhostBit | static_cast<std::uint32_t>(i);
    this->GhostEnd.assign(n, Open);
    if (this->Sink.labelling())
      for (Interval& in : this->Previous.intervals)
        in.box = this->PreviousBox[in.rect];
  }

  /// The section of the slice starting at plane a (empty past the last plane).
  void nextSlice(Coord a, const Section& section)
  {
    this->Current.build(section);
    this->Out.oudbBoxCount += this->Current.intervalCount;
    const std::size_t n = this->Current.rects.size();
    this->CurrentBox.assign(n, 0);
    this->CurrentIsNew.assign(n, 1);
    this->PreviousContinues.assign(this->Previous.rects.size(), 0);
    this->compactRectangles(a);
    if (this->Sink.labelling())
      for (Interval& in : this->Current.intervals)
        in.box = this->CurrentBox[in.rect];
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
    this->matchRectangles();
    const auto& cur = this->Current.rects;
    for (std::size_t r = 0; r < cur.size(); ++r)
      if (this->CurrentIsNew[r])
      {
        this->CurrentBox[r] = static_cast<std::uint32_t>(this->Out.boxes.size());
        this->Out.boxes.push_back(boxOf(cur[r], a, Open, this->Order));
        this->Sink.addBox();
      }
    for (std::size_t q = 0; q < this->Previous.rects.size(); ++q)
      if (!this->PreviousContinues[q])
        this->endBox(this->PreviousBox[q], a);
  }

  /// The rectangles equal in both sections, found by one merge of the two lists (sorted by
  /// (b0, c0), disjoint rectangles) whose steps do not branch: equal rectangles are few in
  /// noise and the order of the others random.
  void matchRectangles()
  {
    const Rect* const prev = this->Previous.rects.data();
    const Rect* const cur = this->Current.rects.data();
    const std::size_t np = this->Previous.rects.size(), nc = this->Current.rects.size();
    std::size_t p = 0, r = 0;
    while (p < np && r < nc)
    {
      const SectionPoint kp = sectionPoint(prev[p].b0, prev[p].c0);
      const SectionPoint kc = sectionPoint(cur[r].b0, cur[r].c0);
      if (kp == kc && prev[p].sameAs(cur[r]))
      {
        this->CurrentBox[r] = this->PreviousBox[p];
        this->CurrentIsNew[r] = 0;
        this->PreviousContinues[p] = 1;
      }
      p += kp <= kc;
      r += kc <= kp;
    }
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
        this->Sink.add(
          this->CurrentBox[c.backward], this->CurrentBox[c.forward], this->Order[1], c.face);
  }

  /// Contacts across the plane between the previous slice and this one, between a box that
  /// ends there and a box that starts there. Segments of the two sections that meet along B
  /// are compared interval by interval (when labelling by faces, only those that overlap:
  /// segments that merely touch give edge or vertex contacts).
  void addContactsAlongA()
  {
    const auto& ps = this->Previous.segments;
    const auto& cs = this->Current.segments;
    const bool touchingToo = !this->Sink.faceOnly();
    std::size_t first = 0;
    for (const Segment& s : ps)
    {
      // Segments of either list are sorted and disjoint but may touch: every segment of
      // the other list from the first that does not end before s to the last that starts
      // no later than s ends.
      while (first < cs.size() && cs[first].b1 < s.b0)
        ++first;
      for (std::size_t j = first; j < cs.size() && cs[j].b0 <= s.b1; ++j)
        if (!this->Sink.labelling())
          this->compareSegments(s, cs[j]);
        else if (touchingToo || overlap(s.b0, s.b1, cs[j].b0, cs[j].b1))
          this->uniteAlongA(s, cs[j]);
    }
  }

  /// Every interval x of s (previous section) and y of t (current) that meet, x of a box
  /// that ends at the plane and y of a box that starts there, is a contact candidate.
  void compareSegments(const Segment& s, const Segment& t)
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
        this->addContactAlongA(x.rect, y.rect, s.b0, t.b0);
      // The interval that ends first goes: without a branch, which noise makes random.
      const bool nextX = x.c1 < y.c1;
      i += nextX;
      j += !nextX;
    }
  }

  /// Labelling: every pair of intervals of s and t that meet (overlap, by faces: s and t
  /// then overlap) is an equivalence, found again in every pair of segments of the same
  /// rectangles and whether or not its boxes end and start at the plane: a box that goes on
  /// through the plane touches the other box within one slice too, so no extra equivalence
  /// changes a class. The pairs are gathered without branches (noise makes them random),
  /// then united.
  void uniteAlongA(const Segment& s, const Segment& t)
  {
    const auto& pi = this->Previous.intervals;
    const auto& ci = this->Current.intervals;
    // Only grown: resizing down and up again constructed the pairs anew at every segment.
    const std::size_t room = (s.end - s.first) + (t.end - t.first);
    if (this->Pending.size() < room)
      this->Pending.resize(room);
    std::size_t n = 0;
    const bool faceOnly = this->Sink.faceOnly();
    std::uint32_t i = s.first, j = t.first;
    while (i < s.end && j < t.end)
    {
      const Interval& x = pi[i];
      const Interval& y = ci[j];
      const bool hit = faceOnly ? overlap(x.c0, x.c1, y.c0, y.c1) : meet(x.c0, x.c1, y.c0, y.c1);
      this->Pending[n] = { x.box, y.box };
      n += hit && x.box != y.box; // a box continued through the plane meets itself
      const bool nextX = x.c1 < y.c1;
      i += nextX;
      j += !nextX;
    }
    for (std::size_t k = 0; k < n; ++k)
      this->Sink.add(this->Pending[k].first, this->Pending[k].second, this->Order[0], true);
  }

  /// Two rectangles that meet do so in every pair of their segments that meet (a rectangle
  /// has the same interval in all its segments): the pair is recorded once, at the first
  /// segment of the previous rectangle that meets the current one and the first segment of
  /// the current rectangle that meets that one. No list of found pairs to sort and merge.
  void addContactAlongA(std::uint32_t previous, std::uint32_t current, Coord sb0, Coord tb0)
  {
    const Rect& p = this->Previous.rects[previous];
    const Rect& c = this->Current.rects[current];
    // The segment before s in p (ending at sb0) meets c unless c starts after sb0; the same
    // for the segment before t in c against s.
    if ((sb0 != p.b0 && sb0 >= c.b0) || (tb0 != c.b0 && tb0 >= sb0))
      return;
    const bool face = overlap(p.b0, p.b1, c.b0, c.b1) && overlap(p.c0, p.c1, c.c0, c.c1);
    this->Sink.add(this->PreviousBox[previous], this->CurrentBox[current], this->Order[0], face);
  }

public:
  /// Boxes still open after the last slice, by rectangle of that slice.
  const std::vector<std::uint32_t>& openBoxes() const { return this->PreviousBox; }
  /// Where each ghost box ended along A (Open: it goes on past this piece).
  const std::vector<Coord>& ghostEnds() const { return this->GhostEnd; }

private:
  const AxisOrder Order;
  CUDB& Out;
  ContactSink Sink;
  std::vector<Coord> GhostEnd;
  SectionDecomposition Previous, Current;
  std::vector<std::uint32_t> PreviousBox, CurrentBox; ///< box of each rectangle
  std::vector<char> CurrentIsNew, PreviousContinues;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> Pending; ///< see uniteAlongA
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

/// The sweep over planes [first, last) of an EVM, with its own boxes and contacts (when
/// labelling: its equivalences, and only the contacts with ghost boxes).
struct SweptPiece
{
  CUDB part;
  UnionFind equivalences;
  std::vector<std::uint32_t> openBoxes;
  std::vector<Coord> ghostEnds;
  bool aborted = false;
  bool lastSectionEmpty = false;

  void sweep(const EVM& evm,
    const std::vector<std::size_t>& starts,
    Section section,
    std::size_t first,
    std::size_t last,
    bool afterAnotherPiece,
    const Connectivity* labelling,
    const Execution& exec)
  {
    const std::vector<Vertex>& v = evm.vertices();
    Section scratch;
    // Room for the boxes and contacts of porous and noisy volumes (about 0.4 boxes and 2.1
    // contacts per extreme vertex): growing would copy them and fault their pages in twice.
    // Pages reserved but never written cost nothing.
    const std::size_t vertices = starts[last] - starts[first];
    this->part.boxes.reserve(vertices / 2);
    if (labelling)
      this->equivalences.reserve(vertices / 2);
    else
      this->part.contacts.reserve(vertices * 5 / 2 + 16);
    SliceSweep sweep(evm.order(),
      this->part,
      labelling ? ContactSink(this->part.contacts, this->equivalences, *labelling)
                : ContactSink(this->part.contacts));
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
      const std::size_t before = this->part.boxes.size();
      sweep.nextSlice(v[starts[k]][0], section);
      this->reserveAhead(
        this->part.boxes.size() - before, k + 1 - first, last - first, labelling != nullptr);
    }
    this->openBoxes = sweep.openBoxes();
    this->ghostEnds = sweep.ghostEnds();
    this->lastSectionEmpty = section.empty();
  }

  /// Before the room for boxes runs out (less than two more slices like the last one), room
  /// for as many as the planes swept so far predict for the whole piece, with a margin. Left
  /// to itself the vector doubles when full, and holds the old and the new copy at once, of
  /// up to twice the final size: a checkerboard has a box per selected voxel from a handful of
  /// extreme vertices, so the first reservation is far too small. Growth is at least 3/2.
  void reserveAhead(std::size_t lastSlice,
    std::size_t planesDone,
    std::size_t planes,
    bool labelling)
  {
    std::vector<Box>& boxes = this->part.boxes;
    if (boxes.capacity() - boxes.size() >= 2 * lastSlice)
      return;
    const std::size_t predicted = boxes.size() / planesDone * planes;
    const std::size_t room =
      std::max(predicted + predicted / 8 + 2 * lastSlice, boxes.capacity() / 2 * 3);
    boxes.reserve(room);
    if (labelling)
      this->equivalences.reserve(room);
  }
};

/// Sweeps the planes of a 3D EVM in `pieces` runs (0: automatic), concurrently. False when
/// aborted.
bool sweepPieces(const EVM& evm,
  const Execution& exec,
  int pieces,
  const Connectivity* labelling,
  std::vector<SweptPiece>& swept)
{
  const std::vector<Vertex>& v = evm.vertices();
  const std::vector<std::size_t> starts = evm.planeStarts();
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
  std::vector<Section> entering(pieces);
  Section section, scratch;
  for (int p = 1; p < pieces; ++p)
  {
    for (std::size_t k = firstPlane[p - 1]; k < firstPlane[p]; ++k)
      nextSection(v.data() + starts[k], v.data() + starts[k + 1], section, scratch);
    entering[p] = section;
  }
  swept.resize(pieces);
  exec.forRange(pieces,
    [&](std::int64_t begin, std::int64_t end)
    {
      for (std::int64_t p = begin; p < end; ++p)
        swept[p].sweep(
          evm, starts, entering[p], firstPlane[p], firstPlane[p + 1], p > 0, labelling, exec);
    });
  for (const SweptPiece& piece : swept)
    if (piece.aborted)
      return false;
  if (!swept.back().lastSectionEmpty)
    throw std::invalid_argument("the last section is not empty: not a valid EVM");
  return true;
}

/// Joins the pieces in sweep order: a piece's ghost boxes are the open boxes of the piece
/// before, so its boxes come after theirs and the result is the one sequential sweep's. When
/// labelling, the pieces' equivalences are joined into `equivalences` instead of contacts.
void stitch(std::vector<SweptPiece>& pieces, CUDB& out, UnionFind* equivalences)
{
  const int axisA = out.order[0];
  std::vector<std::uint32_t> open; // global ids of the boxes open before the current piece
  for (SweptPiece& piece : pieces)
  {
    const std::uint32_t offset = static_cast<std::uint32_t>(out.boxes.size());
    auto global = [&](std::uint32_t id)
    { return (id & GhostBit) ? open[id & ~GhostBit] : offset + id; };
    for (std::size_t g = 0; g < piece.ghostEnds.size(); ++g)
      if (piece.ghostEnds[g] != Open)
        out.boxes[open[g]].hi[axisA] = piece.ghostEnds[g];
    if (offset == 0) // the first piece (the only one of a sequential sweep): ids are global
      out.boxes.swap(piece.part.boxes);
    else
      out.boxes.insert(out.boxes.end(), piece.part.boxes.begin(), piece.part.boxes.end());
    if (equivalences)
      equivalences->append(std::move(piece.equivalences));
    std::vector<BoxContact>& contacts = equivalences ? piece.part.contacts : out.contacts;
    if (offset == 0 && !equivalences)
      out.contacts.swap(piece.part.contacts);
    else
      for (const BoxContact& c : piece.part.contacts)
        if (equivalences)
          equivalences->unite(global(c.backward), global(c.forward));
        else
          contacts.push_back({ global(c.backward), global(c.forward), c.axis, c.face });
    out.oudbBoxCount += piece.part.oudbBoxCount;
    for (std::uint32_t& id : piece.openBoxes)
      id = global(id);
    open.swap(piece.openBoxes);
    piece.part = CUDB(); // memory: one copy of the boxes at a time
  }
}

/// A 2D EVM is a single section: its rectangles are the boxes, one voxel thick. The contacts
/// go to `out`, or, when labelling (`equivalences`), each usable one is an equivalence at once
/// (rectangle r is box r), so that no contact list is copied and read back. Each list is
/// released once read: on a 6001^2 maze they are tens of MB each.
void buildCUDB2D(const EVM& evm, CUDB& out, UnionFind* equivalences, Connectivity connectivity)
{
  SectionDecomposition d;
  d.keepLastLineOnly(true);
  d.keepFaceContactsOnly(equivalences && connectivity == Connectivity::Face);
  // Images have fewer rectangles than half their vertices (the 6001^2 maze: 12.5 M vertices,
  // 4.9 M rectangles; the fax pages 3 to 4 vertices a rectangle); more only grow the lists.
  const std::vector<Vertex>& v = evm.vertices();
  d.reserve(v.size() / 2);
  d.build(
    v.data(),
    v.data() + v.size(),
    [](const Vertex& p) { return p[1]; },
    [](const Vertex& p) { return p[2]; });
  out.oudbBoxCount = d.intervalCount;
  out.boxes.reserve(d.rects.size());
  for (const Rect& r : d.rects)
    out.boxes.push_back(boxOf(r, 0, 1, out.order));
  List<Rect>().swap(d.rects);
  if (equivalences)
  {
    *equivalences = UnionFind(out.boxes.size());
    for (const RectContact& c : d.contacts)
      equivalences->unite(c.backward, c.forward); // only usable ones were kept
    return;
  }
  out.contacts.reserve(d.contacts.size());
  for (const RectContact& c : d.contacts)
    out.contacts.push_back(
      { c.backward, c.forward, static_cast<std::uint8_t>(out.order[1]), c.face });
}

/// Algorithms 3 and 4 (CCL, makeEquivalence) with the box itself as its provisional label:
/// every usable contact is an equivalence between two boxes, recorded in the union-find
/// whose representative is the smallest member, i.e. the box created first. The classes come
/// out as the paper's labelling leaves them, without per-box neighbour lists to build.
void makeEquivalences(const CUDB& cudb, Connectivity connectivity, UnionFind& equivalences)
{
  const bool all = connectivity == Connectivity::Vertex;
  for (const BoxContact& c : cudb.contacts)
    if (all || c.face)
      equivalences.unite(c.backward, c.forward);
}

/// Algorithm 5 (relabeling): the classes numbered 1..count in order of first appearance
/// along the boxes (the order of their representatives). Returns count.
std::uint32_t relabel(UnionFind& equivalences, std::vector<std::uint32_t>& label)
{
  label.resize(equivalences.size());
  return equivalences.numberClasses(label.data(), 1);
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
  if (evm.dimension() == 2)
  {
    buildCUDB2D(evm, out, nullptr, Connectivity::Vertex);
    return true;
  }
  std::vector<SweptPiece> swept;
  if (!sweepPieces(evm, exec, pieces, nullptr, swept))
    return false;
  stitch(swept, out, nullptr);
  return true;
}

bool buildCUDBComponents(const EVM& evm,
  Connectivity connectivity,
  const Execution& exec,
  CUDB& out,
  Components& components,
  int pieces)
{
  out = CUDB();
  out.dimension = evm.dimension();
  out.order = evm.order();
  if (evm.dimension() == 2)
  {
    UnionFind equivalences;
    buildCUDB2D(evm, out, &equivalences, connectivity);
    components.count = relabel(equivalences, components.boxLabel);
    return true;
  }
  std::vector<SweptPiece> swept;
  if (!sweepPieces(evm, exec, pieces, &connectivity, swept))
    return false;
  UnionFind equivalences;
  stitch(swept, out, &equivalences);
  components.count = relabel(equivalences, components.boxLabel);
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
  Section section, scratch;
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

Components labelComponents(const CUDB& cudb, Connectivity connectivity)
{
  UnionFind equivalences(cudb.boxes.size());
  makeEquivalences(cudb, connectivity, equivalences);
  Components result;
  result.count = relabel(equivalences, result.boxLabel);
  return result;
}

namespace
{

/// How many boxes a painting worker paints between two questions whether to stop.
constexpr std::size_t StopPollBoxes = 4096;

/// How paintBoxes walks a box: its coordinates k = 0..2 (box axes) and their steps in the
/// grid, the row axis (the grid's x, contiguous) and the two others.
struct PaintLayout
{
  std::array<std::int64_t, 3> step;
  int row, outer, inner, split;
};

PaintLayout paintLayout(const std::array<int, 3>& axes, const std::array<Coord, 3>& dims)
{
  const std::int64_t gridStep[3] = { 1, dims[0], std::int64_t(dims[0]) * dims[1] };
  PaintLayout layout{};
  // Workers own disjoint ranges of slices (of rows when the grid is a single slice).
  const int splitAxis = dims[2] > 1 ? 2 : 1;
  for (int k = 0; k < 3; ++k)
  {
    layout.step[k] = gridStep[axes[k]];
    if (axes[k] == 0)
      layout.row = k;
    if (axes[k] == splitAxis)
      layout.split = k;
  }
  layout.inner = (layout.row + 1) % 3;
  layout.outer = (layout.row + 2) % 3;
  return layout;
}

/// paintBoxes on a single slice (a 2D image): boxes one voxel thick, of a few rows each, by a
/// loop with fewer steps per box than the 3D one (a maze has millions of boxes of 3.6 pixels
/// on 1.9 rows; the 3D loop took half again as long there). Workers own ranges of rows. The
/// box's numbers are read into locals before its pixels are written: the pixels are int32
/// like the coordinates, so each store would otherwise reload them.
bool paintPlanarBoxes(const std::vector<Box>& boxes,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 3>& offset,
  const PaintLayout& layout,
  const std::array<Coord, 3>& dims,
  std::int32_t* labels,
  const Execution& exec)
{
  const int row = layout.row, split = layout.split, flat = 3 - row - split;
  const std::int64_t rowStep = layout.step[split];
  const std::int64_t rowOffset = offset[row], splitOffset = offset[split];
  std::int32_t* const origin = labels + std::int64_t(offset[flat]) * layout.step[flat];
  const Box* const box = boxes.data();
  const std::int32_t* const values = value.data();
  const std::size_t count = boxes.size();
  const Execution* const stop = &exec;
  exec.forRange(dims[1],
    [=](std::int64_t from, std::int64_t to)
    {
      for (std::size_t b = 0; b < count; ++b)
      {
        if (b % StopPollBoxes == 0 && stop->stopRequested())
          return;
        const std::int32_t v = values[b];
        const std::int64_t lo = std::max<std::int64_t>(box[b].lo[split] + splitOffset, from);
        const std::int64_t hi = std::min<std::int64_t>(box[b].hi[split] + splitOffset, to);
        const std::int64_t x0 = box[b].lo[row] + rowOffset,
                           length = box[b].hi[row] - box[b].lo[row];
        const std::int64_t flatAt = std::int64_t(box[b].lo[flat]) * layout.step[flat];
        if (v == 0)
          continue;
        std::int32_t* line = origin + flatAt + lo * rowStep + x0;
        for (std::int64_t y = lo; y < hi; ++y, line += rowStep)
          for (std::int64_t x = 0; x < length; ++x)
            line[x] = v;
      }
    });
  return !exec.stopRequested();
}

/// Writes v into line[0, length), length > 0, by stores that may overlap but never leave the
/// range: three single values for up to 3, two or four groups of 4 (one from each end) for up
/// to 16, groups of 4 then one from the end beyond. The rows of porous and noisy boxes are a
/// few voxels of random lengths, and a store loop mispredicted its exit at nearly every row.
inline void fillRow(std::int32_t* line, std::int64_t length, std::int32_t v)
{
  if (length < 4)
  {
    line[0] = v;
    line[length / 2] = v;
    line[length - 1] = v;
    return;
  }
  const std::int32_t four[4] = { v, v, v, v };
  std::int32_t* const last = line + length - 4;
  if (length > 8)
  {
    if (length > 16)
    {
      for (std::int32_t* at = line + 8; at < last; at += 4)
        std::memcpy(at, four, sizeof four);
    }
    else
      std::memcpy(last - 4, four, sizeof four);
    std::memcpy(line + 4, four, sizeof four);
  }
  std::memcpy(line, four, sizeof four);
  std::memcpy(last, four, sizeof four);
}

/// The part of every box between slices [from, to) along the layout's split axis, painted:
/// the box's first voxel found by one sum and a plain loop per row. Noise has hundreds of
/// thousands of boxes of a few voxels, so the work per box (six clipped coordinates, steps
/// looked up by axis) cost as much as its stores; inlined with the image's own layout the steps
/// and axes are constants.
inline void paintSlab(const std::vector<Box>& boxes,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 3>& offset,
  const PaintLayout& layout,
  std::int64_t from,
  std::int64_t to,
  std::int32_t* labels,
  const Execution& exec)
{
  const int split = layout.split;
  const std::int64_t firstVoxel =
    offset[0] * layout.step[0] + offset[1] * layout.step[1] + offset[2] * layout.step[2];
  const std::int64_t innerStep = layout.step[layout.inner];
  const std::int64_t outerStep = layout.step[layout.outer];
  for (std::size_t b = 0; b < boxes.size(); ++b)
  {
    if (b % StopPollBoxes == 0 && exec.stopRequested())
      return;
    const std::int32_t v = value[b];
    const Box& box = boxes[b];
    const std::int64_t start = std::int64_t(box.lo[split]) + offset[split];
    const std::int64_t lo = std::max(start, from);
    const std::int64_t hi = std::min(std::int64_t(box.hi[split]) + offset[split], to);
    if (v == 0 || lo >= hi)
      continue;
    std::int64_t extent[3] = {
      box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]
    };
    extent[split] = hi - lo;
    const std::int64_t length = extent[layout.row], rows = extent[layout.inner];
    if (length <= 0)
      continue;
    std::int32_t* plane = labels + firstVoxel + box.lo[0] * layout.step[0] +
      box.lo[1] * layout.step[1] + box.lo[2] * layout.step[2] + (lo - start) * layout.step[split];
    for (std::int64_t i = extent[layout.outer]; i > 0; --i, plane += outerStep)
    {
      std::int32_t* line = plane;
      for (std::int64_t j = rows; j > 0; --j, line += innerStep)
        fillRow(line, length, v);
    }
  }
}

} // namespace

bool paintBoxes(const std::vector<Box>& boxes,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 3>& offset,
  const std::array<int, 3>& axes,
  const std::array<Coord, 3>& dims,
  std::int32_t* labels,
  const Execution& exec)
{
  const PaintLayout layout = paintLayout(axes, dims);
  if (dims[2] == 1)
    return paintPlanarBoxes(boxes, value, offset, layout, dims, labels, exec);
  if (axes == std::array<int, 3>{ 0, 1, 2 })
    exec.forRange(dims[2],
      [&](std::int64_t from, std::int64_t to)
      {
        paintSlab(boxes,
          value,
          offset,
          PaintLayout{ { 1, layout.step[1], layout.step[2] }, 0, 2, 1, 2 },
          from,
          to,
          labels,
          exec);
      });
  else
    exec.forRange(dims[axes[layout.split]],
      [&](std::int64_t from, std::int64_t to)
      { paintSlab(boxes, value, offset, layout, from, to, labels, exec); });
  return !exec.stopRequested();
}

namespace
{

/// A run [c0, c1) of set pixels of a row, and the box (rectangle) it belongs to.
struct PixelRun
{
  Coord c0, c1;
  std::uint32_t box;
};

/// The ends of the runs of set pixels of a row of bits (the bits past the row's end are
/// clear), c0 and c1 alternately, from `out` on: a run starts or ends at x where pixels x - 1
/// and x differ. Returns the end of the output.
Coord* rowRunEnds(const Word* bits, std::size_t words, Coord* out)
{
  Word carry = 0;
  for (std::size_t w = 0; w < words; ++w)
  {
    const Word b = bits[w];
    Word change = b ^ ((b << 1) | carry);
    carry = b >> 63;
    while (change)
    {
      *out++ = static_cast<Coord>(w * 64 + countTrailingZeros(change));
      change &= change - 1;
    }
  }
  if (carry)
    *out++ = static_cast<Coord>(words * 64);
  return out;
}

/// The number of points where the parity of `bits` changes along a row (x - 1 and x differ,
/// the bits past the end clear): of the XOR of two rows, the extreme vertices of the line of
/// vertices between them; of one row, twice its runs.
std::size_t rowChanges(const Word* a, const Word* b, std::size_t words)
{
  std::size_t n = 0;
  Word carry = 0;
  for (std::size_t w = 0; w < words; ++w)
  {
    const Word x = a[w] ^ (b ? b[w] : 0);
    n += static_cast<std::size_t>(popCount(x ^ ((x << 1) | carry)));
    carry = x >> 63;
  }
  return n + static_cast<std::size_t>(carry);
}

/// Algorithm 1 at Dim2 read from the pixel rows instead of an EVM. Between two lines of
/// vertices the 1D section is constant, so its rows are equal: an interval equal to one of the
/// segment before (the 2D compaction) is a run equal to one of the row before, and the
/// rectangles, their creation order (by first row, then c0) and their contacts across lines
/// are those of SectionDecomposition on the EVM of the pixels. Boxes are numbered 0, 1, ... as
/// they start; `visit` hears of each: started(run, [first, end) of the previous row's runs
/// from the first that may meet it), continued(run).
class PixelRowSweep
{
public:
  explicit PixelRowSweep(const BitVolume& pixels)
    : Pixels(pixels)
    , Ends(pixels.wordsPerRow() * 64 + 2)
  {
  }

  /// The runs of row y, after those of row y - 1 (rows are visited in order from 0).
  template<typename Visit>
  const std::vector<PixelRun>& nextRow(std::int32_t y, Visit& visit)
  {
    std::swap(this->Previous, this->Current);
    Coord* const ends = this->Ends.data();
    const Coord* endsEnd = rowRunEnds(this->Pixels.row(y, 0), this->Pixels.wordsPerRow(), ends);
    const std::size_t count = static_cast<std::size_t>(endsEnd - ends) / 2;
    this->Current.resize(count);
    // Pointers and counters in locals: the runs' and boxes' int32 stores could alias members,
    // which were reloaded (and spilled) at every run.
    const PixelRun* p = this->Previous.data();
    const PixelRun* const prevEnd = p + this->Previous.size();
    PixelRun* cur = this->Current.data();
    std::uint32_t nextBox = this->NextBox;
    bool same = count == this->Previous.size();
    for (const Coord* e = ends; e != endsEnd; e += 2, ++cur)
    {
      const Coord c0 = e[0], c1 = e[1];
      // Runs of the row before that end before this one meet no later run either.
      while (p != prevEnd && p->c1 < c0)
        ++p;
      if (p != prevEnd && p->c0 == c0 && p->c1 == c1)
      {
        *cur = *p; // no other run of the row before meets it: runs have gaps
        visit.continued(*cur);
        continue;
      }
      same = false;
      *cur = { c0, c1, nextBox++ };
      visit.started(*cur, p, prevEnd);
    }
    this->NextBox = nextBox;
    this->Same = same;
    return this->Current;
  }

  /// Whether the last row's runs are those of the row before (no line of vertices between).
  bool sameAsPrevious() const { return this->Same; }

private:
  const BitVolume& Pixels;
  std::vector<Coord> Ends;
  std::vector<PixelRun> Previous, Current;
  std::uint32_t NextBox = 0;
  bool Same = false;
};

/// What buildCUDBComponents2D does with the sweep's rectangles: boxes grown a row at a time
/// (WithBoxes; labelPixelRuns keeps only their numbers), and the contacts of the connectivity
/// as equivalences.
template<bool WithBoxes>
struct BoxesAndEquivalences
{
  std::vector<Box>& Boxes;
  UnionFind& Equivalences;
  bool FaceOnly;
  Coord Row = 0;
  /// Where the box of the next run is written, if the runs are kept (PixelRuns::boxes): here,
  /// as the runs come, where a copy of each row's boxes from its runs (12-byte records) was
  /// vectorized through the stack and stalled on every store forwarded to a wider load.
  std::uint32_t* Kept = nullptr;

  void started(const PixelRun& run, const PixelRun* first, const PixelRun* end)
  {
    if (this->Kept)
      *this->Kept++ = run.box;
    if (WithBoxes)
    {
      Box box;
      box.lo = { run.c0, this->Row, 0 };
      box.hi = { run.c1, this->Row + 1, 1 };
      this->Boxes.push_back(box);
    }
    this->Equivalences.add();
    // The runs from `first` on that start no later than this one ends meet it (one loop that
    // finds and unites them: its exits are mispredicted once, not twice). The union's root
    // is carried from contact to contact rather than found again from the new box, a root
    // itself (no union has reached it yet).
    std::uint32_t root = run.box;
    for (const PixelRun* r = first; r != end && r->c0 <= run.c1; ++r)
      if (!this->FaceOnly || (r->c0 < run.c1 && run.c0 < r->c1))
        root = this->Equivalences.uniteWithRoot(r->box, root);
  }
  void continued(const PixelRun& run)
  {
    if (this->Kept)
      *this->Kept++ = run.box;
    if (WithBoxes)
      this->Boxes[run.box].hi[1] = this->Row + 1;
  }
};

void checkSingleSlice(const BitVolume& pixels)
{
  if (pixels.size(2) != 1)
    throw std::invalid_argument("a 2D CUDB needs a single slice (nz == 1)");
}

/// Transposes a 64 x 64 block of bits in place: bit j of word i goes to bit i of word j
/// (the recursive exchange of off-diagonal blocks, 32 x 32 down to 1 x 1).
void transposeBlock(Word block[64])
{
  Word mask = 0x00000000FFFFFFFFull;
  for (int width = 32; width != 0; width >>= 1, mask ^= mask << width)
    for (int i = 0; i < 64; i = (i + width + 1) & ~width)
    {
      const Word t = ((block[i] >> width) ^ block[i + width]) & mask;
      block[i] ^= t << width;
      block[i + width] ^= t;
    }
}

/// The image with its two axes exchanged (pixel (x, y) becomes (y, x)), a block of 64 x 64
/// bits at a time: rows along y, so that the sweep of the sorting with lines along x reads
/// the runs of its columns from words, as it reads those of rows.
BitVolume transposed(const BitVolume& pixels)
{
  const std::int32_t nx = pixels.size(0), ny = pixels.size(1);
  BitVolume out(ny, nx, 1);
  const std::size_t inWords = pixels.wordsPerRow(), outWords = out.wordsPerRow();
  Word block[64];
  for (std::size_t by = 0; by < outWords; ++by)  // 64 rows of the input
    for (std::size_t bx = 0; bx < inWords; ++bx) // 64 columns of the input
    {
      for (std::int32_t i = 0; i < 64; ++i)
      {
        const auto y = static_cast<std::int32_t>(by * 64) + i;
        block[i] = y < ny ? pixels.row(y, 0)[bx] : 0;
      }
      transposeBlock(block);
      for (std::int32_t j = 0; j < 64; ++j)
      {
        const auto x = static_cast<std::int32_t>(bx * 64) + j;
        if (x < nx)
          out.row(x, 0)[by] = block[j];
      }
    }
  return out;
}

/// The runs of set pixels of all rows, the extreme vertices of the EVM (the changes between
/// consecutive rows) and their count: a pass over the bits (a few words per row) that bounds
/// the boxes, so that their lists are reserved once.
std::size_t countRuns(const BitVolume& pixels, std::size_t& vertices)
{
  const std::int32_t ny = pixels.size(1);
  const std::size_t words = pixels.wordsPerRow();
  std::size_t runs = 0;
  vertices = 0;
  for (std::int32_t y = 0; y <= ny; ++y)
  {
    const Word* row = y < ny ? pixels.row(y, 0) : nullptr;
    const Word* before = y > 0 ? pixels.row(y - 1, 0) : nullptr;
    if (row)
      runs += rowChanges(row, nullptr, words) / 2;
    if (row || before)
      vertices += rowChanges(row ? row : before, row ? before : nullptr, words);
  }
  // Box numbers and the union-find are 32-bit: refuse rather than wrap.
  if (runs >= std::numeric_limits<std::uint32_t>::max())
    throw std::length_error(
      "a 2D CUDB of " + std::to_string(runs) + " runs of pixels: more than 2^32 - 1 boxes");
  return runs;
}

/// The sweep of buildCUDBComponents2D over rows along x (stored sorting, or of the transposed
/// image), boxes (WithBoxes) in the sweep's own (x, y); false when aborted. It asks whether to
/// stop every 2048 words of pixels or so (a few ms of a maze, a few dozen rows) and reports
/// the rows done.
template<bool WithBoxes>
bool sweepPixelRows(const BitVolume& pixels,
  Connectivity connectivity,
  std::int32_t stride,
  ProgressPoll& poll,
  CUDB& out,
  UnionFind& equivalences,
  PixelRuns* kept)
{
  const std::int32_t ny = pixels.size(1);
  BoxesAndEquivalences<WithBoxes> visit{
    out.boxes, equivalences, connectivity == Connectivity::Face
  };
  std::uint32_t* const keptBoxes = kept ? kept->boxes.data() : nullptr;
  visit.Kept = keptBoxes;
  PixelRowSweep sweep(pixels);
  // Polled between blocks of rows, so that the loop over a block's rows has no test of its own.
  for (std::int64_t block = 0; block < ny; block += stride)
  {
    poll.at(double(block) / ny);
    if (!poll.poll())
      return false;
    const auto end = static_cast<std::int32_t>(std::min<std::int64_t>(ny, block + stride));
    for (auto y = static_cast<std::int32_t>(block); y < end; ++y)
    {
      visit.Row = y;
      const std::vector<PixelRun>& runs = sweep.nextRow(y, visit);
      if (!sweep.sameAsPrevious())
        out.oudbBoxCount += runs.size(); // a line of vertices at y: the OUDB cuts every interval
      if (kept) // reserved for all rows: no reallocation; the boxes written by `visit`
        kept->rowStarts.push_back(static_cast<std::size_t>(visit.Kept - keptBoxes) - runs.size());
    }
  }
  if (kept)
    kept->rowStarts.push_back(static_cast<std::size_t>(visit.Kept - keptBoxes));
  return true;
}

/// `components` emptied, the memory of its labels kept for the sweep to write again.
void clearKeepingMemory(Components& components)
{
  components.boxLabel.clear();
  components.count = 0;
}

/// `out` as a new CUDB, the memory of its boxes kept for the sweep to write again.
void clearKeepingMemory(CUDB& out)
{
  std::vector<Box> boxes = std::move(out.boxes);
  boxes.clear();
  out = CUDB();
  out.boxes = std::move(boxes);
}

/// buildCUDBComponents2D on rows along x (`rows`: the pixels, or their transpose), the boxes
/// only `withBoxes`; false when aborted, with `out` and `pixelRuns` empty. The union-find
/// lives in `memory` when given (and is left there).
bool sweepRowsForComponents(const BitVolume& rows,
  Connectivity connectivity,
  bool withBoxes,
  const Execution& exec,
  CUDB& out,
  Components& components,
  std::size_t& vertices,
  PixelRuns* pixelRuns,
  std::vector<std::uint32_t>* memory)
{
  clearKeepingMemory(components);
  const std::size_t runs = countRuns(rows, vertices);
  UnionFind equivalences(memory ? std::move(*memory) : std::vector<std::uint32_t>(), 0);
  equivalences.reserve(runs);
  if (withBoxes)
    out.boxes.reserve(runs);
  if (pixelRuns)
  {
    pixelRuns->clear();
    pixelRuns->boxes.resize(runs); // the box of every run, written by the sweep
    pixelRuns->rowStarts.reserve(std::size_t(rows.size(1)) + 1);
  }
  const std::size_t words = std::max<std::size_t>(rows.wordsPerRow(), 1);
  const auto stride = static_cast<std::int32_t>(std::max<std::size_t>(2048 / words, 1));
  ProgressPoll poll(exec, 0.0, 1.0);
  const bool swept = withBoxes
    ? sweepPixelRows<true>(rows, connectivity, stride, poll, out, equivalences, pixelRuns)
    : sweepPixelRows<false>(rows, connectivity, stride, poll, out, equivalences, pixelRuns);
  if (!swept || !poll.poll())
  {
    out.boxes.clear();
    out.oudbBoxCount = 0;
    if (pixelRuns)
      pixelRuns->clear();
    if (memory)
      *memory = equivalences.release();
    return false;
  }
  components.count = relabel(equivalences, components.boxLabel);
  if (memory)
    *memory = equivalences.release();
  return true;
}

} // namespace

bool buildCUDBComponents2D(const BitVolume& pixels,
  const AxisOrder& order,
  Connectivity connectivity,
  const Execution& exec,
  CUDB& out,
  Components& components,
  std::size_t* vertices,
  PixelRuns* pixelRuns,
  std::vector<std::uint32_t>* memory)
{
  checkSingleSlice(pixels);
  const bool alongY = order == AxisOrder{ 2, 0, 1 };
  if (!alongY && order != AxisOrder{ 2, 1, 0 })
    throw std::invalid_argument("a 2D CUDB from pixel rows sorts ZYX or ZXY");
  clearKeepingMemory(out);
  out.dimension = 2;
  out.order = order;
  const BitVolume columns = alongY ? transposed(pixels) : BitVolume();
  std::size_t extremeVertices = 0;
  if (!sweepRowsForComponents(alongY ? columns : pixels,
        connectivity,
        true,
        exec,
        out,
        components,
        extremeVertices,
        pixelRuns,
        memory))
  {
    clearKeepingMemory(out);
    return false;
  }
  if (vertices)
    *vertices = extremeVertices;
  if (alongY) // the sweep's (x, y) are the image's (y, x)
    for (Box& box : out.boxes)
    {
      std::swap(box.lo[0], box.lo[1]);
      std::swap(box.hi[0], box.hi[1]);
    }
  return true;
}

bool labelPixelRuns(const BitVolume& pixels,
  Connectivity connectivity,
  const Execution& exec,
  PixelRunComponents& out,
  std::vector<std::uint32_t>* memory)
{
  checkSingleSlice(pixels);
  CUDB counts; // its OUDB count only: no boxes
  out.oudbBoxCount = 0;
  out.extremeVertices = 0;
  if (!sweepRowsForComponents(pixels,
        connectivity,
        false,
        exec,
        counts,
        out.components,
        out.extremeVertices,
        &out.runs,
        memory))
    return false;
  out.oudbBoxCount = counts.oudbBoxCount;
  return true;
}

std::size_t countPixelRuns(const BitVolume& pixels)
{
  checkSingleSlice(pixels);
  std::size_t runs = 0;
  for (std::int32_t y = 0; y < pixels.size(1); ++y)
    runs += rowChanges(pixels.row(y, 0), nullptr, pixels.wordsPerRow()) / 2;
  return runs;
}

Coord* pixelRowRunEnds(const BitVolume& pixels, std::int32_t y, Coord* out)
{
  return rowRunEnds(pixels.row(y, 0), pixels.wordsPerRow(), out);
}

std::size_t buildCUDBComponents2D(const BitVolume& pixels,
  Connectivity connectivity,
  CUDB& out,
  Components& components)
{
  std::size_t vertices = 0;
  buildCUDBComponents2D(
    pixels, AxisOrder{ 2, 1, 0 }, connectivity, Execution(), out, components, &vertices);
  return vertices;
}

namespace
{

/// The runs of pixel row y painted into `row` (pixel x at row[x]), which holds 0 from x = 0 to
/// `room` (at least the row's width): the run i of the row gets value[runs.boxes[i]]. The row's
/// count of runs is checked before its pixels are written (a compare per row): runs that are
/// not the row's own would be read past.
void paintRowRuns(const BitVolume& pixels,
  std::int32_t y,
  const PixelRuns& runs,
  const std::int32_t* value,
  std::int32_t* row,
  std::int64_t room,
  Coord* ends)
{
  const std::uint32_t* runBox = runs.boxes.data() + runs.rowStarts[y];
  const Coord* const last = rowRunEnds(pixels.row(y, 0), pixels.wordsPerRow(), ends);
  if (std::size_t(last - ends) / 2 != runs.rowStarts[y + 1] - runs.rowStarts[y])
    throw std::invalid_argument("paintPixelRuns: the runs are not those of the pixels' rows");
  std::int32_t* const rowEnd = row + room;
  constexpr std::ptrdiff_t Width = 8;
  for (const Coord* e = ends; e != last; e += 2)
  {
    std::int32_t *const first = row + e[0], *const end = row + e[1];
    const std::int32_t v = value[*runBox++];
    if (end - first <= Width && rowEnd - first >= 2 * Width)
    {
      // A short run: Width values from its start, then Width zeros from its end over the
      // gap's pixels they covered (the gap is 0 already; the next run is written after).
      for (std::ptrdiff_t k = 0; k < Width; ++k)
        first[k] = v;
      for (std::ptrdiff_t k = 0; k < Width; ++k)
        end[k] = 0;
    }
    else
      std::fill(first, end, v);
  }
}

/// paintPixelRuns over rows [from, to).
void paintRowsOfRuns(const BitVolume& pixels,
  std::int64_t from,
  std::int64_t to,
  const PixelRuns& runs,
  const std::int32_t* value,
  std::int32_t* origin,
  std::int64_t rowStep,
  Coord* ends)
{
  for (std::int64_t y = from; y < to; ++y)
    paintRowRuns(pixels,
      static_cast<std::int32_t>(y),
      runs,
      value,
      origin + y * rowStep,
      pixels.size(0),
      ends);
}

/// paintPixelRunsOverwriting over image rows [from, to): each row zeroed, then its pixels'
/// runs (if it has some) painted while it is in the cache. (Rows built in scratch and copied
/// out by streaming stores, which skip reading the lines first, took 4 to 14 % longer on the
/// fax pages.)
void overwriteRowsOfRuns(const BitVolume& pixels,
  std::int64_t from,
  std::int64_t to,
  const PixelRuns& runs,
  const std::int32_t* value,
  const std::array<Coord, 2>& offset,
  std::int64_t width,
  std::int32_t* labels,
  Coord* ends)
{
  for (std::int64_t r = from; r < to; ++r)
  {
    std::int32_t* const row = labels + r * width;
    std::fill_n(row, width, 0);
    const std::int64_t y = r - offset[1];
    if (y >= 0 && y < pixels.size(1))
      paintRowRuns(pixels,
        static_cast<std::int32_t>(y),
        runs,
        value,
        row + offset[0],
        width - offset[0],
        ends);
  }
}

/// Calls paint(first, last) for the steps of `rows` rows, each in parallel (paint(from, to,
/// ends) over its part, with scratch for a row's run ends): progress is reported and the stop
/// asked for between steps, from the calling thread. Few and large steps, as a parallel loop
/// may cost a thread start-up; a huge image still stops within a sixteenth of it. False when
/// stopped.
template<typename Paint>
bool paintInSteps(const BitVolume& pixels,
  std::int64_t rows,
  std::int64_t wordsPerRow,
  const Execution& exec,
  Paint paint)
{
  // Steps of about 2^14 words of work, at most 16 (abort checks and progress between them).
  const std::int64_t words = std::max<std::int64_t>(wordsPerRow, 1);
  const std::int64_t step =
    std::max((rows + 15) / 16, ((std::int64_t(1) << 14) + words - 1) / words);
  for (std::int64_t first = 0; first < rows; first += step)
  {
    if (exec.stopRequested() || !exec.report(double(first) / double(rows)))
      return false;
    const std::int64_t last = std::min(rows, first + step);
    exec.forRange(last - first,
      [&](std::int64_t from, std::int64_t to)
      {
        std::vector<Coord> ends(pixels.wordsPerRow() * 64 + 2);
        paint(first + from, first + to, ends.data());
      });
  }
  return !exec.stopRequested();
}

/// Whether `runs` could be one box per run of the rows of `pixels` (their row starts
/// increasing from 0 to the number of boxes); each row's own count is checked as it is painted.
bool fitsRows(const BitVolume& pixels, const PixelRuns& runs)
{
  const std::vector<std::size_t>& starts = runs.rowStarts;
  return starts.size() == std::size_t(pixels.size(1)) + 1 && starts.front() == 0 &&
    starts.back() == runs.boxes.size() && std::is_sorted(starts.begin(), starts.end());
}

/// Throws std::invalid_argument unless `pixels` is one slice and `runs` those of its rows.
void checkRunsOfRows(const BitVolume& pixels, const PixelRuns& runs, const char* caller)
{
  checkSingleSlice(pixels);
  if (!fitsRows(pixels, runs))
    throw std::invalid_argument(
      std::string(caller) + ": the runs are not those of the pixels' rows");
}

} // namespace

bool paintPixelRuns(const BitVolume& pixels,
  const PixelRuns& runs,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 2>& offset,
  std::int64_t rowStep,
  std::int32_t* labels,
  const Execution& exec)
{
  checkRunsOfRows(pixels, runs, "paintPixelRuns");
  std::int32_t* const origin = labels + std::int64_t(offset[1]) * rowStep + offset[0];
  return paintInSteps(pixels,
    pixels.size(1),
    static_cast<std::int64_t>(pixels.wordsPerRow()),
    exec,
    [&](std::int64_t from, std::int64_t to, Coord* ends)
    { paintRowsOfRuns(pixels, from, to, runs, value.data(), origin, rowStep, ends); });
}

bool paintPixelRunsOverwriting(const BitVolume& pixels,
  const PixelRuns& runs,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 2>& offset,
  std::int64_t width,
  std::int64_t rows,
  std::int32_t* labels,
  const Execution& exec)
{
  checkRunsOfRows(pixels, runs, "paintPixelRunsOverwriting");
  if (offset[0] < 0 || offset[1] < 0 || offset[0] + std::int64_t(pixels.size(0)) > width ||
    offset[1] + std::int64_t(pixels.size(1)) > rows)
    throw std::invalid_argument("paintPixelRunsOverwriting: the pixels are not inside the image");
  // Every pixel of a row of the image is written, not only the object's words.
  return paintInSteps(pixels,
    rows,
    std::max<std::int64_t>(static_cast<std::int64_t>(pixels.wordsPerRow()), (width + 63) / 64),
    exec,
    [&](std::int64_t from, std::int64_t to, Coord* ends)
    { overwriteRowsOfRuns(pixels, from, to, runs, value.data(), offset, width, labels, ends); });
}

} // namespace vbr
