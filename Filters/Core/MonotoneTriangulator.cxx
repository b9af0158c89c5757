#include "MonotoneTriangulator.h"

#include "Geometry.h"

#include <algorithm>
#include <utility>

namespace vbr
{

namespace
{

enum VertexType : char
{
  Start,
  End,
  Split,
  Merge,
  Regular
};

int signOf64(std::int64_t w)
{
  return (w > 0) - (w < 0);
}

/// The number of bits that hold the values [0, span].
int bitsFor(std::uint64_t span)
{
  int bits = 1;
  while ((span >> bits) != 0)
    ++bits;
  return bits;
}

} // namespace

void PredecessorSet::reserve(std::size_t slots)
{
  std::size_t size = slots, level = 0;
  do
  {
    size = (size + 63) / 64;
    if (this->Levels.size() <= level)
      this->Levels.emplace_back();
    if (this->Levels[level].size() < size)
      this->Levels[level].resize(size, 0);
    ++level;
  } while (size > 1);
}

void PredecessorSet::insert(std::size_t slot)
{
  for (std::vector<std::uint64_t>& words : this->Levels)
  {
    std::uint64_t& word = words[slot >> 6];
    const bool wasEmpty = word == 0;
    word |= std::uint64_t(1) << (slot & 63);
    if (!wasEmpty)
      return;
    slot >>= 6;
  }
}

void PredecessorSet::erase(std::size_t slot)
{
  for (std::vector<std::uint64_t>& words : this->Levels)
  {
    std::uint64_t& word = words[slot >> 6];
    word &= ~(std::uint64_t(1) << (slot & 63));
    if (word != 0)
      return;
    slot >>= 6;
  }
}

std::int64_t PredecessorSet::below(std::size_t slot) const
{
  std::size_t level = 0;
  for (;; ++level)
  {
    if (level == this->Levels.size())
      return -1;
    const std::size_t w = slot >> 6;
    if (w >= this->Levels[level].size())
      return -1;
    const std::uint64_t bits = this->Levels[level][w] & ((std::uint64_t(1) << (slot & 63)) - 1);
    if (bits != 0)
    {
      slot = (w << 6) | static_cast<std::size_t>(63 - countLeadingZeros(bits));
      break;
    }
    slot = w; // the words of this level strictly before w, one level up
  }
  for (; level > 0; --level) // down, taking the highest member each time
    slot =
      (slot << 6) | static_cast<std::size_t>(63 - countLeadingZeros(this->Levels[level - 1][slot]));
  return static_cast<std::int64_t>(slot);
}

void PredecessorSet::clear()
{
  for (std::vector<std::uint64_t>& words : this->Levels)
    std::fill(words.begin(), words.end(), 0);
}

/// LSD radix sort of Order[0 .. count) by SortKeys (both permuted), 11-bit digits, skipping the
/// digits where all keys agree; stable.
void MonotoneTriangulator::sortByKey(std::size_t count)
{
  if (count < 2)
    return;
  std::uint64_t differing = 0;
  for (std::size_t i = 0; i < count; ++i)
    differing |= this->SortKeys[i] ^ this->SortKeys[0];
  constexpr int Bits = 11;
  constexpr std::uint64_t Mask = (1u << Bits) - 1;
  this->SortScratch.resize(std::max(this->SortScratch.size(), count));
  this->OrderScratch.resize(std::max(this->OrderScratch.size(), count));
  this->Count.resize((1u << Bits) + 1);
  for (int shift = 0; shift < 64; shift += Bits)
  {
    if (((differing >> shift) & Mask) == 0)
      continue;
    std::fill(this->Count.begin(), this->Count.end(), 0);
    for (std::size_t i = 0; i < count; ++i)
      ++this->Count[((this->SortKeys[i] >> shift) & Mask) + 1];
    for (std::size_t i = 1; i < this->Count.size(); ++i)
      this->Count[i] += this->Count[i - 1];
    for (std::size_t i = 0; i < count; ++i)
    {
      const std::uint32_t to = this->Count[(this->SortKeys[i] >> shift) & Mask]++;
      this->SortScratch[to] = this->SortKeys[i];
      this->OrderScratch[to] = this->Order[i];
    }
    std::copy(this->SortScratch.begin(), this->SortScratch.begin() + count, this->SortKeys.begin());
    std::copy(this->OrderScratch.begin(), this->OrderScratch.begin() + count, this->Order.begin());
  }
}

/// The corners that turn become vertices, linked round their loops past the corners that go
/// straight on. False when next is not a permutation of the corners, an edge is not
/// axis-parallel or has no length, a loop goes back on itself or never turns, or the coordinates
/// are too large.
bool MonotoneTriangulator::setUpRings(const std::vector<std::array<std::int64_t, 2>>& at,
  const std::vector<int>& next)
{
  const int n = static_cast<int>(at.size());
  this->V.clear();
  // Room for the copies the diagonals make (two per split or merge vertex at most), so that
  // the sweep never moves the vertices; pages never touched cost nothing.
  this->V.reserve(3 * at.size());
  this->VertexOf.assign(at.size(), -1);
  this->PrevCorner.assign(at.size(), -1);
  std::int64_t maxX = at[0][0], maxY = at[0][1];
  this->MinX = maxX;
  this->MinY = maxY;
  for (int i = 0; i < n; ++i)
  {
    if (next[i] < 0 || next[i] >= n || this->PrevCorner[next[i]] >= 0)
      return false; // next is not a permutation of the corners: no loops
    this->PrevCorner[next[i]] = i;
    this->MinX = std::min(this->MinX, at[i][0]);
    this->MinY = std::min(this->MinY, at[i][1]);
    maxX = std::max(maxX, at[i][0]);
    maxY = std::max(maxY, at[i][1]);
  }
  constexpr std::int64_t Limit = std::int64_t(1) << 30;
  if (this->MinX <= -Limit || this->MinY <= -Limit || maxX >= Limit || maxY >= Limit)
    return false;
  for (int i = 0; i < n; ++i)
  {
    const auto &a = at[this->PrevCorner[i]], &b = at[i], &c = at[next[i]];
    const std::int64_t ex = c[0] - b[0], ey = c[1] - b[1];
    if ((ex == 0) == (ey == 0))
      return false; // not axis-parallel, or no length
    const std::int64_t turn = (b[0] - a[0]) * ey - (b[1] - a[1]) * ex;
    if (turn == 0 && (b[0] - a[0]) * ex + (b[1] - a[1]) * ey <= 0)
      return false; // going back
    if (turn == 0)
      continue;
    this->VertexOf[i] = static_cast<int>(this->V.size());
    Vertex v{};
    v.x = static_cast<std::int32_t>(b[0]);
    v.y = static_cast<std::int32_t>(b[1]);
    v.corner = v.outCorner = v.reported = i;
    this->V.push_back(v);
  }
  for (Vertex& v : this->V)
  {
    int c = next[v.corner], steps = 0;
    for (; this->VertexOf[c] < 0; c = next[c])
      if (++steps > n)
        return false;
    v.next = this->VertexOf[c];
    this->V[v.next].prev = static_cast<int>(&v - this->V.data());
  }
  return !this->V.empty();
}

/// Where two vertices share a place (loops touching at a corner), each is joined to the edge
/// that turns left from its incoming one; both corners are then reported as the first.
bool MonotoneTriangulator::joinSharedCorners()
{
  const std::size_t m = this->V.size();
  const int xBits = bitsFor(static_cast<std::uint64_t>(
    std::max_element(
      this->V.begin(), this->V.end(), [](const Vertex& a, const Vertex& b) { return a.x < b.x; })
      ->x -
    this->MinX));
  this->SortKeys.resize(std::max(this->SortKeys.size(), m));
  this->Order.resize(std::max(this->Order.size(), m));
  for (std::size_t v = 0; v < m; ++v)
  {
    this->SortKeys[v] = (static_cast<std::uint64_t>(this->V[v].y - this->MinY) << xBits) |
      static_cast<std::uint64_t>(this->V[v].x - this->MinX);
    this->Order[v] = static_cast<int>(v);
  }
  this->sortByKey(m);
  const auto turnsLeft = [this](int v)
  {
    const Vertex &a = this->V[this->V[v].prev], &b = this->V[v], &c = this->V[b.next];
    return std::int64_t(b.x - a.x) * (c.y - b.y) - std::int64_t(b.y - a.y) * (c.x - b.x) > 0;
  };
  for (std::size_t k = 1; k < m; ++k)
  {
    if (this->SortKeys[k] != this->SortKeys[k - 1])
      continue;
    if (k >= 2 && this->SortKeys[k - 2] == this->SortKeys[k])
      return false; // three corners at one place: not an orthogonal face
    const int a = this->Order[k - 1], b = this->Order[k];
    const int first = std::min(this->V[a].corner, this->V[b].corner);
    this->V[a].reported = this->V[b].reported = first;
    if (!turnsLeft(a))
    {
      const int na = this->V[a].next, nb = this->V[b].next;
      this->V[a].next = nb;
      this->V[b].next = na;
      this->V[nb].prev = a;
      this->V[na].prev = b;
      std::swap(this->V[a].outCorner, this->V[b].outCorner);
    }
    if (!turnsLeft(a) || !turnsLeft(b))
      return false;
  }
  return true;
}

/// Each vertex's shift in the shrunk polygon: the sum of the inward (left) normals of its two
/// edges, one horizontal and one vertical.
void MonotoneTriangulator::shiftCorners()
{
  for (Vertex& v : this->V)
  {
    const Vertex &a = this->V[v.prev], &c = this->V[v.next];
    const std::int64_t inX = v.x - a.x, inY = v.y - a.y, outX = c.x - v.x, outY = c.y - v.y;
    v.dx = static_cast<std::int8_t>(-signOf64(inY) - signOf64(outY));
    v.dy = static_cast<std::int8_t>(signOf64(inX) + signOf64(outX));
  }
}

/// Order: the vertices from the top, by (y, dy, x) decreasing, each with its key. Made from
/// their order by place (joinSharedCorners left it in Order), row by row: the vertices of a row
/// with dy = -1 come before those with dy = +1 (every vertex turns, so dy is never 0).
bool MonotoneTriangulator::orderForSweep(std::int64_t maxX)
{
  const std::size_t m = this->V.size();
  const int xBits = bitsFor(static_cast<std::uint64_t>(maxX - this->MinX));
  this->OrderScratch.resize(std::max(this->OrderScratch.size(), m));
  std::size_t out = 0;
  for (std::size_t rowBegin = 0, rowEnd = 0; rowBegin < m; rowBegin = rowEnd)
  {
    const std::int32_t y = this->V[this->Order[rowBegin]].y;
    for (rowEnd = rowBegin; rowEnd < m && this->V[this->Order[rowEnd]].y == y; ++rowEnd)
      ;
    for (int dy = -1; dy <= 1; dy += 2)
      for (std::size_t k = rowBegin; k < rowEnd; ++k)
        if (this->V[this->Order[k]].dy == dy)
          this->OrderScratch[out++] = this->Order[k];
  }
  if (out != m)
    return false;
  std::uint64_t last = 0;
  for (std::size_t k = 0; k < m; ++k)
  {
    Vertex& p = this->V[this->OrderScratch[k]];
    p.key =
      ((static_cast<std::uint64_t>(p.y - this->MinY) * 3 + static_cast<std::uint64_t>(p.dy + 1))
        << xBits) |
      static_cast<std::uint64_t>(p.x - this->MinX);
    if (k > 0 && p.key <= last)
      return false; // two vertices tie: the loops are not those of an orthogonal face
    last = p.key;
    this->Order[m - 1 - k] = this->OrderScratch[k];
  }
  this->Status.reserve(static_cast<std::size_t>(maxX - this->MinX) + 1);
  this->EdgeAt.resize(
    std::max(this->EdgeAt.size(), static_cast<std::size_t>(maxX - this->MinX) + 1));
  return true;
}

/// Start, split, end, merge or regular, from the places of its neighbours in the sweep and the
/// way it turns (every vertex turns).
void MonotoneTriangulator::classify()
{
  for (std::size_t v = 0; v < this->V.size(); ++v)
  {
    const int i = static_cast<int>(v), p = this->V[v].prev, q = this->V[v].next;
    const bool convex = this->orientation(p, i, q) > 0;
    if (this->below(p, i) && this->below(q, i))
      this->V[v].type = convex ? Start : Split;
    else if (this->below(i, p) && this->below(i, q))
      this->V[v].type = convex ? End : Merge;
    else
      this->V[v].type = Regular;
  }
}

/// The sign of the orientation of triangle abc in the shrunk polygon: the real cross product,
/// then its terms in delta and delta^2.
int MonotoneTriangulator::orientation(int a, int b, int c) const
{
  const Vertex &p = this->V[a], &q = this->V[b], &r = this->V[c];
  const std::int64_t ax = q.x - p.x, ay = q.y - p.y, bx = r.x - p.x, by = r.y - p.y;
  const std::int64_t real = ax * by - ay * bx;
  if (real != 0)
    return signOf64(real);
  const std::int64_t dax = q.dx - p.dx, day = q.dy - p.dy, dbx = r.dx - p.dx, dby = r.dy - p.dy;
  const std::int64_t linear = ax * dby - ay * dbx + dax * by - day * bx;
  if (linear != 0)
    return signOf64(linear);
  return signOf64(dax * dby - day * dbx);
}

/// Joins a and b by a diagonal: each gets a copy that keeps its edge to its old next vertex
/// (and that edge's place in the status), while a goes on to b's copy and b to a's, which
/// parts the ring (or joins two rings) along the diagonal.
void MonotoneTriangulator::addDiagonal(int a, int b)
{
  const int na = static_cast<int>(this->V.size()), nb = na + 1;
  this->V.push_back(this->V[a]);
  this->V.push_back(this->V[b]);
  Vertex *A = &this->V[a], *B = &this->V[b], *NA = &this->V[na], *NB = &this->V[nb];
  this->V[A->next].prev = na;
  this->V[B->next].prev = nb;
  A->next = nb;
  NB->prev = a;
  B->next = na;
  NA->prev = b;
  A->diagonalOut = B->diagonalOut = true;
  if (NA->inStatus && NA->x == this->V[NA->next].x)
    this->EdgeAt[static_cast<std::size_t>(NA->x - this->MinX)] = na;
  if (NB->inStatus && NB->x == this->V[NB->next].x)
    this->EdgeAt[static_cast<std::size_t>(NB->x - this->MinX)] = nb;
}

/// Puts vertex v's edge (to its next vertex) in the status: by its x when vertical.
void MonotoneTriangulator::insertEdge(int v)
{
  Vertex& p = this->V[v];
  p.inStatus = true;
  if (p.x != this->V[p.next].x)
    return; // horizontal: never crossed at a vertex, so never left of one
  const std::size_t slot = static_cast<std::size_t>(p.x - this->MinX);
  this->Status.insert(slot);
  this->EdgeAt[slot] = v;
}

void MonotoneTriangulator::eraseEdge(int v)
{
  Vertex& p = this->V[v];
  if (p.inStatus && p.x == this->V[p.next].x)
    this->Status.erase(static_cast<std::size_t>(p.x - this->MinX));
  p.inStatus = false;
}

/// The slot of the edge of the status directly left of vertex v, or -1.
int MonotoneTriangulator::leftOf(int v) const
{
  return static_cast<int>(this->Status.below(static_cast<std::size_t>(this->V[v].x - this->MinX)));
}

/// At a split vertex: a diagonal to the helper of the edge left of it, and its copy's edge (the
/// one leaving it) in the status.
bool MonotoneTriangulator::handleSplit(int v)
{
  const int slot = this->leftOf(v);
  if (slot < 0)
    return false;
  this->addDiagonal(v, this->V[this->EdgeAt[static_cast<std::size_t>(slot)]].helper);
  const int copy = static_cast<int>(this->V.size()) - 2;
  this->V[this->EdgeAt[static_cast<std::size_t>(slot)]].helper = v;
  this->insertEdge(copy);
  this->V[copy].helper = copy;
  return true;
}

/// Ends the edge into v: a diagonal to its helper when that is a merge vertex. Returns the
/// vertex that goes on below v (v's copy after a diagonal, v otherwise).
int MonotoneTriangulator::closeEdgeInto(int v)
{
  int self = v;
  if (this->V[this->V[this->V[v].prev].helper].type == Merge)
  {
    this->addDiagonal(v, this->V[this->V[v].prev].helper);
    self = static_cast<int>(this->V.size()) - 2;
  }
  this->eraseEdge(this->V[v].prev);
  return self;
}

/// `self` becomes the helper of the edge left of v, after a diagonal to the old helper when that
/// is a merge vertex.
bool MonotoneTriangulator::helpEdgeLeftOf(int v, int self)
{
  const int slot = this->leftOf(v);
  if (slot < 0)
    return false;
  const std::size_t at = static_cast<std::size_t>(slot);
  if (this->V[this->V[this->EdgeAt[at]].helper].type == Merge)
    this->addDiagonal(self, this->V[this->EdgeAt[at]].helper);
  this->V[this->EdgeAt[at]].helper = self; // the diagonal may have moved the edge to a copy
  return true;
}

/// One event of the sweep (de Berg et al., HandleStartVertex and the others).
bool MonotoneTriangulator::handleVertex(int v)
{
  switch (this->V[v].type)
  {
    case Start:
      this->insertEdge(v);
      this->V[v].helper = v;
      return true;
    case End:
      // Never a merge helper for orthogonal loops: the edge into an end vertex goes down and
      // the edge out of it goes right along the bottom of the inside to a vertex swept just
      // before it (same row, larger x). Nothing crosses the inside just above that bottom edge,
      // so that vertex, a regular one, found this edge directly left of it and became its
      // helper. Kept as in de Berg et al.
      this->closeEdgeInto(v);
      return true;
    case Split:
      return this->handleSplit(v);
    case Merge:
      return this->helpEdgeLeftOf(v, this->closeEdgeInto(v));
    default:
      break;
  }
  if (this->below(v, this->V[v].prev)) // the inside on the right: a left chain going down
  {
    const int self = this->closeEdgeInto(v);
    this->insertEdge(self);
    this->V[self].helper = self;
    return true;
  }
  return this->helpEdgeLeftOf(v, v);
}

bool MonotoneTriangulator::sweep()
{
  const std::size_t m = this->V.size();
  for (std::size_t k = 0; k < m; ++k)
    if (!this->handleVertex(this->Order[k]))
    {
      this->Status.clear();
      return false;
    }
  return true;
}

/// The straight-on corners on the loop edge from vertex a to vertex b, in order, in `corners`;
/// false when the edge does not lead to b.
bool MonotoneTriangulator::straightCornersOf(int a,
  int b,
  const std::vector<int>& next,
  std::vector<int>& corners)
{
  corners.clear();
  int c = next[this->V[a].outCorner];
  for (; this->VertexOf[c] < 0; c = next[c])
    corners.push_back(c);
  return c == this->V[b].corner;
}

/// Appends triangle abc of corners (reported) after checking it turns strictly left.
bool MonotoneTriangulator::pushTriangle(int a, int b, int c, std::vector<int>& triangles)
{
  const auto &p = (*this->At)[a], &q = (*this->At)[b], &r = (*this->At)[c];
  if ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]) <= 0)
    return false;
  triangles.insert(
    triangles.end(), { this->reportedOf(a), this->reportedOf(b), this->reportedOf(c) });
  return true;
}

/// Emits the triangle Top[0..3) with the straight-on corners Side[k] on its side from Top[k] to
/// Top[k + 1]: turned so that side 0 has some, it is cut from s1 (the first corner of side 0)
/// into the fan over side 2, then triangles (s_i, s_i+1, Top[2]), then the fan from s_k over
/// side 1. No triangle is flat: the apex of each fan lies strictly inside another side.
bool MonotoneTriangulator::emitExpanded(std::vector<int>& triangles)
{
  int turn = 0;
  while (this->Side[turn].empty())
    ++turn;
  const int a = this->Top[turn], b = this->Top[(turn + 1) % 3], c = this->Top[(turn + 2) % 3];
  const std::vector<int>& s = this->Side[turn];
  const std::vector<int>& q = this->Side[(turn + 1) % 3];
  const std::vector<int>& r = this->Side[(turn + 2) % 3];
  int from = c;
  for (int corner : r)
  {
    if (!this->pushTriangle(s.front(), from, corner, triangles))
      return false;
    from = corner;
  }
  if (!this->pushTriangle(s.front(), from, a, triangles))
    return false;
  for (std::size_t i = 0; i + 1 < s.size(); ++i)
    if (!this->pushTriangle(s[i], s[i + 1], c, triangles))
      return false;
  from = b;
  for (int corner : q)
  {
    if (!this->pushTriangle(s.back(), from, corner, triangles))
      return false;
    from = corner;
  }
  return this->pushTriangle(s.back(), from, c, triangles);
}

/// Emits triangle abc of vertices (counter-clockwise), with the straight-on corners of the
/// loop edges among its sides.
bool MonotoneTriangulator::emitTriangle(int a,
  int b,
  int c,
  const std::vector<int>& next,
  std::vector<int>& triangles)
{
  const Vertex &p = this->V[a], &q = this->V[b], &r = this->V[c];
  if (!p.straightAfter && !q.straightAfter && !r.straightAfter)
  { // no corner to put back: the vertices' own coordinates and reported corners
    if (std::int64_t(q.x - p.x) * (r.y - p.y) - std::int64_t(q.y - p.y) * (r.x - p.x) <= 0)
      return false;
    triangles.insert(triangles.end(), { p.reported, q.reported, r.reported });
    return true;
  }
  const int vertices[3] = { a, b, c };
  bool any = false;
  for (int k = 0; k < 3; ++k)
  {
    const int from = vertices[k], to = vertices[(k + 1) % 3];
    this->Top[k] = this->V[from].corner;
    this->Side[k].clear();
    if (this->V[from].next != to || this->V[from].diagonalOut || !this->V[from].straightAfter)
      continue;
    if (!this->straightCornersOf(from, to, next, this->Side[k]))
      return false;
    any |= !this->Side[k].empty();
  }
  if (!any)
    return this->pushTriangle(this->Top[0], this->Top[1], this->Top[2], triangles);
  return this->emitExpanded(triangles);
}

/// Merged: the places in Piece from the top down, ChainOf: the chain of each (1 left, -1 right,
/// 0 the top and bottom). False when the piece is not y-monotone.
bool MonotoneTriangulator::mergeChains()
{
  const std::size_t k = this->Piece.size();
  const int* P = this->Piece.data();
  std::size_t top = 0, bottom = 0;
  for (std::size_t i = 1; i < k; ++i)
  {
    if (this->below(P[i], P[bottom]))
      bottom = i;
    if (this->below(P[top], P[i]))
      top = i;
  }
  // Merge the chains: the left one follows the ring down from the top, the right one goes
  // back along it.
  this->ChainOf.resize(std::max(this->ChainOf.size(), k));
  this->Merged.resize(k);
  std::size_t left = (top + 1) % k, right = (top + k - 1) % k;
  this->Merged[0] = static_cast<int>(top);
  this->ChainOf[top] = 0;
  for (std::size_t i = 1; i + 1 < k; ++i)
  {
    const bool takeLeft = right == bottom || (left != bottom && this->below(P[right], P[left]));
    std::size_t& at = takeLeft ? left : right;
    if (at == bottom)
      return false; // not monotone
    this->Merged[i] = static_cast<int>(at);
    this->ChainOf[at] = takeLeft ? 1 : -1;
    at = takeLeft ? (at + 1) % k : (at + k - 1) % k;
  }
  if (left != bottom || right != bottom)
    return false;
  this->Merged[k - 1] = static_cast<int>(bottom);
  this->ChainOf[bottom] = 0;
  for (std::size_t i = 1; i < k; ++i)
    if (!this->below(P[this->Merged[i]], P[this->Merged[i - 1]]))
      return false; // the chains do not go down
  return true;
}

/// The stack walk down the two chains of the y-monotone piece Piece (de Berg et al.,
/// TriangulateMonotonePolygon), orientations in the shrunk polygon.
bool MonotoneTriangulator::triangulatePiece(const std::vector<int>& next,
  std::vector<int>& triangles)
{
  const std::size_t k = this->Piece.size();
  const int* P = this->Piece.data();
  if (k < 3)
    return false;
  if (k == 3)
    return this->emitTriangle(P[0], P[1], P[2], next, triangles);
  if (!this->mergeChains())
    return false;
  std::vector<int>& stack = this->Stack;
  stack.assign({ this->Merged[0], this->Merged[1] });
  const auto tri = [&](std::size_t x, std::size_t y, std::size_t z)
  { return this->emitTriangle(P[x], P[y], P[z], next, triangles); };
  for (std::size_t i = 2; i + 1 < k; ++i)
  {
    const int u = this->Merged[i];
    const int side = this->ChainOf[u];
    if (side != this->ChainOf[stack.back()])
    {
      for (std::size_t j = 0; j + 1 < stack.size(); ++j)
        if (!(side == 1 ? tri(stack[j + 1], stack[j], u) : tri(stack[j], stack[j + 1], u)))
          return false;
      stack.assign({ this->Merged[i - 1], u });
      continue;
    }
    int last = stack.back();
    stack.pop_back();
    while (!stack.empty())
    {
      const int w = stack.back();
      const bool convex = side == 1 ? this->orientation(P[u], P[w], P[last]) > 0
                                    : this->orientation(P[u], P[last], P[w]) > 0;
      if (!convex)
        break;
      if (!(side == 1 ? tri(u, w, last) : tri(u, last, w)))
        return false;
      last = w;
      stack.pop_back();
    }
    stack.push_back(last);
    stack.push_back(u);
  }
  const int u = this->Merged[k - 1];
  for (std::size_t j = 0; j + 1 < stack.size(); ++j)
    if (!(this->ChainOf[stack[j + 1]] == 1 ? tri(stack[j], stack[j + 1], u)
                                           : tri(stack[j + 1], stack[j], u)))
      return false;
  return true;
}

bool MonotoneTriangulator::triangulatePieces(const std::vector<int>& next,
  std::vector<int>& triangles)
{
  const std::size_t count = this->V.size();
  for (std::size_t start = 0; start < count; ++start)
  {
    if (this->V[start].used)
      continue;
    this->Piece.clear();
    for (int v = static_cast<int>(start); !this->V[v].used; v = this->V[v].next)
    {
      this->V[v].used = true;
      this->Piece.push_back(v);
    }
    if (this->Piece.front() != this->V[this->Piece.back()].next)
      return false;
    if (!this->triangulatePiece(next, triangles))
      return false;
  }
  return true;
}

bool MonotoneTriangulator::triangulate(const std::vector<std::array<std::int64_t, 2>>& at,
  const std::vector<int>& next,
  std::vector<int>& triangles)
{
  if (at.size() < 4 || next.size() != at.size())
    return false;
  this->At = &at;
  if (!this->setUpRings(at, next) || !this->joinSharedCorners())
    return false;
  std::int64_t maxX = this->MinX;
  for (Vertex& v : this->V)
  {
    maxX = std::max<std::int64_t>(maxX, v.x);
    v.straightAfter = this->VertexOf[next[v.outCorner]] < 0;
  }
  // The status and EdgeAt have one slot per x in the face's width, kept from call to call:
  // a face much wider than its corners are many is left to the caller's general method, so
  // that memory stays linear in the corners.
  if (maxX - this->MinX > MaxWidthPerCorner * static_cast<std::int64_t>(at.size()) + MaxWidthBase)
    return false;
  this->shiftCorners();
  if (!this->orderForSweep(maxX))
    return false;
  this->classify();
  if (!this->sweep())
    return false;
  return this->triangulatePieces(next, triangles);
}

} // namespace vbr
