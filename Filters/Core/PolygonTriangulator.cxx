// Exact ear clipping of simple polygons (see the header for why it is correct), and the
// tests of simplicity and fan cover, on integer corners with 128-bit products (Wide; the ear
// clipping in 64 bits when every corner lies within 2^30, see cross2).
//
// PolygonTriangulator first parts the polygon at corners where it touches itself into two
// counter-clockwise loops (splitAtTouchingCorner: the doubled areas of the two loops, from a
// prefix sum, tell whether the corner joins two pieces; looked for only when a hash of the
// corners finds one repeated), then ear-clips each piece on a doubly linked ring (clipEars),
// testing only the corners that do not turn left (the blockers), kept sorted by x so that an
// ear reads only those in its bounding box's columns; a piece of at most 64 corners within
// 2^30 of the origin tests all
// of its blockers, kept in the bits of a word (clipSmallRing: no sort, no search, loops of
// foreseeable length). isSimplePolygon compares every pair of non-adjacent edges
// (segmentsMeet).

#include "PolygonTriangulator.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <type_traits>
#include <utility>

namespace vbr
{

namespace
{

/// Whether a and b are the same corner place (compared as two integers: std::array's == called
/// memcmp, the most of hasRepeatedCorner's time on the short loops of small faces).
bool samePlace(const Point2L& a, const Point2L& b)
{
  return a[0] == b[0] && a[1] == b[1];
}

/// Pieces of at most this many corners find their repeated corners pairwise
/// (splitAtTouchingCorner).
constexpr std::size_t PairwiseRepeatsAtMost = 32;

/// Whether p lies in the closed counter-clockwise triangle abc (products in Int, see cross2).
template<typename Int = Wide>
bool inClosedTriangle(const Point2L& a, const Point2L& b, const Point2L& c, const Point2L& p)
{
  return cross2<Int>(a, b, p) >= 0 && cross2<Int>(b, c, p) >= 0 && cross2<Int>(c, a, p) >= 0;
}

/// Whether every coordinate lies in [-2^30, 2^30), where cross2 is exact in 64 bits.
bool fitsIn64BitProducts(const std::vector<Point2L>& points)
{
  constexpr std::int64_t limit = std::int64_t(1) << 30;
  for (const Point2L& p : points)
    if (p[0] < -limit || p[0] >= limit || p[1] < -limit || p[1] >= limit)
      return false;
  return true;
}

/// Whether p, known to be collinear with segment ab, lies on it.
bool onSegment(const Point2L& a, const Point2L& b, const Point2L& p)
{
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
    std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

/// Whether the closed segments ab and cd have a point in common.
bool segmentsMeet(const Point2L& a, const Point2L& b, const Point2L& c, const Point2L& d)
{
  const int o1 = signOf(cross2(a, b, c)), o2 = signOf(cross2(a, b, d));
  const int o3 = signOf(cross2(c, d, a)), o4 = signOf(cross2(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0)
    return true;
  return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) ||
    (o3 == 0 && onSegment(c, d, a)) || (o4 == 0 && onSegment(c, d, b));
}

/// cross2<std::int64_t>(p, q, r) for many r: dx r_y - dy r_x - (dx p_y - dy p_x), where
/// (dx, dy) = q - p, in unsigned arithmetic (modulo 2^64, so that no intermediate value can be
/// a signed overflow): the result, below 2^63 in magnitude for corners within 2^30 (cross2),
/// is exact.
class EdgeLine
{
public:
  EdgeLine(const Point2L& p, const Point2L& q)
    : Dx(static_cast<std::uint64_t>(q[0] - p[0]))
    , Dy(static_cast<std::uint64_t>(q[1] - p[1]))
    , K(this->Dx * static_cast<std::uint64_t>(p[1]) - this->Dy * static_cast<std::uint64_t>(p[0]))
  {
  }

  std::int64_t at(const Point2L& r) const
  {
    return static_cast<std::int64_t>(this->Dx * static_cast<std::uint64_t>(r[1]) -
      this->Dy * static_cast<std::uint64_t>(r[0]) - this->K);
  }

private:
  std::uint64_t Dx, Dy, K;
};

} // namespace

int orientation(const Point2L& a, const Point2L& b, const Point2L& c)
{
  return signOf(cross2(a, b, c));
}

bool isSimplePolygon(const std::vector<Point2L>& corners)
{
  const std::size_t n = corners.size();
  if (n < 3)
    return false;
  std::vector<Point2L> sorted(corners);
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    return false;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Point2L& a = corners[i];
    const Point2L& b = corners[(i + 1) % n];
    const Point2L& c = corners[(i + 2) % n];
    // Consecutive edges meet only at b: they must not fold back onto each other.
    if (cross2(a, b, c) == 0 &&
      Wide(b[0] - a[0]) * (c[0] - b[0]) + Wide(b[1] - a[1]) * (c[1] - b[1]) < 0)
      return false;
    for (std::size_t j = i + 2; j < n; ++j)
    {
      if ((j + 1) % n == i)
        continue; // edge j ends where edge i starts
      if (segmentsMeet(a, b, corners[j], corners[(j + 1) % n]))
        return false;
    }
  }
  return true;
}

namespace
{

/// fanStrictlyConvexPolygon's tests, in integers of type Int (see cross2).
template<typename Int>
bool isStrictlyConvexFan(const std::vector<Point2L>& p)
{
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    if (cross2<Int>(p[i == 0 ? n - 1 : i - 1], p[i], p[i + 1 == n ? 0 : i + 1]) <= 0)
      return false;
  // The fan's first and last triangles are the turns of corners 0 and n - 2, tested above.
  for (std::size_t i = 1; i + 3 < n; ++i)
    if (cross2<Int>(p[n - 1], p[i], p[i + 1]) <= 0)
      return false;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (p[i][0] == p[j][0] && p[i][1] == p[j][1])
        return false;
  return true;
}

} // namespace

bool fanStrictlyConvexPolygon(const std::vector<Point2L>& corners, std::vector<Triangle>& triangles)
{
  const std::size_t n = corners.size();
  if (n < 3 || n > FanCornersAtMost)
    return false;
  constexpr std::int64_t limit = std::int64_t(1) << 30; // cross2 exact in 64 bits below
  const bool narrow = std::all_of(corners.begin(),
    corners.end(),
    [](const Point2L& p)
    { return p[0] >= -limit && p[0] < limit && p[1] >= -limit && p[1] < limit; });
  if (!(narrow ? isStrictlyConvexFan<std::int64_t>(corners) : isStrictlyConvexFan<Wide>(corners)))
    return false;
  const int last = static_cast<int>(n - 1);
  for (int i = 0; i + 1 < last; ++i)
    triangles.push_back({ last, i, i + 1 });
  return true;
}

std::vector<Triangle> triangulateSimplePolygon(const std::vector<Point2L>& corners)
{
  std::vector<Triangle> triangles;
  if (corners.size() >= 3)
    triangles.reserve(corners.size() - 2);
  PolygonTriangulator().triangulate(corners, triangles);
  return triangles;
}

bool PolygonTriangulator::triangulate(const std::vector<Point2L>& corners,
  std::vector<Triangle>& triangles)
{
  return fanStrictlyConvexPolygon(corners, triangles) ||
    this->triangulateByEars(corners, triangles);
}

bool PolygonTriangulator::triangulateByEars(const std::vector<Point2L>& corners,
  std::vector<Triangle>& triangles)
{
  if (corners.size() < 3 || doubledArea(corners) <= 0)
    return false;
  const std::size_t before = triangles.size();
  this->All.resize(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i)
    this->All[i] = static_cast<int>(i);
  if (this->triangulatePiece(corners, this->All, triangles))
    return true;
  triangles.resize(before);
  return false;
}

/// Triangles of one piece of the polygon (indices into `corners`, in order). Where the
/// piece touches itself at a corner so that the two loops it parts into there both run
/// counter-clockwise (two pieces joined at that corner), each loop is triangulated alone:
/// ear clipping would cut across the gap between them. The loops parted where one runs
/// inside the other (a hole reaching the boundary) or along a slit stay together.
bool PolygonTriangulator::triangulatePiece(const std::vector<Point2L>& corners,
  const std::vector<int>& piece,
  std::vector<Triangle>& triangles)
{
  bool triangulated = false;
  if (this->hasRepeatedCorner(corners, piece) &&
    this->splitAtTouchingCorner(corners, piece, triangles, triangulated))
    return triangulated;
  return this->clipEars(corners, piece, triangles);
}

/// Whether two corners of the piece are at the same place: pairwise for a few corners, else
/// through a hash table of the corners (open addressing, slots of an earlier call told apart
/// by their mark, so the table is never cleared).
bool PolygonTriangulator::hasRepeatedCorner(const std::vector<Point2L>& corners,
  const std::vector<int>& piece)
{
  const std::size_t n = piece.size();
  if (n <= 12)
  {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (samePlace(corners[piece[i]], corners[piece[j]]))
          return true;
    return false;
  }
  int bits = 1;
  while ((std::size_t(1) << bits) < 2 * n)
    ++bits;
  const std::size_t size = std::size_t(1) << bits, mask = size - 1;
  if (this->Slots.size() < size)
  {
    this->SlotMark.assign(size, 0); // first: if the other throws, Slots stays the smaller
    this->Slots.resize(size);
    this->Mark = 0;
  }
  if (++this->Mark == 0) // wrapped: forget every mark
  {
    std::fill(this->SlotMark.begin(), this->SlotMark.end(), 0);
    this->Mark = 1;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const Point2L& p = corners[piece[i]];
    const std::uint64_t h = static_cast<std::uint64_t>(p[0]) * 0x9E3779B97F4A7C15ull ^
      static_cast<std::uint64_t>(p[1]) * 0xC2B2AE3D27D4EB4Full;
    for (std::size_t slot = (h >> (64 - bits)) & mask;; slot = (slot + 1) & mask)
    {
      if (this->SlotMark[slot] != this->Mark)
      {
        this->SlotMark[slot] = this->Mark;
        this->Slots[slot] = static_cast<std::uint32_t>(i);
        break;
      }
      if (samePlace(corners[piece[this->Slots[slot]]], p))
        return true;
    }
  }
  return false;
}

/// The parting of `piece` at a repeated corner into two counter-clockwise loops, each
/// triangulated alone (`triangulated` tells whether both were); false when no repeated corner
/// parts it so. Pairs are tried in the order of their place, then of their indices.
bool PolygonTriangulator::splitAtTouchingCorner(const std::vector<Point2L>& corners,
  const std::vector<int>& piece,
  std::vector<Triangle>& triangles,
  bool& triangulated)
{
  // Prefix and Order are the object's, so a piece parted again reuses them: nothing reads
  // them once the two loops are made.
  const std::size_t n = piece.size();
  std::vector<Wide>& prefix = this->Prefix; // doubled area swept by the first edges
  prefix.resize(n + 1);
  prefix[0] = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Point2L& p = corners[piece[i]];
    const Point2L& q = corners[piece[(i + 1) % n]];
    prefix[i + 1] = prefix[i] + Wide(p[0]) * q[1] - Wide(p[1]) * q[0];
  }
  // Only corners at a repeated place make pairs: on a short piece those are found pairwise
  // (predictable comparisons, where sorting every corner by place was most of this step), so
  // that the sort has only them.
  std::vector<std::size_t>& order = this->Order;
  order.clear();
  if (n <= PairwiseRepeatsAtMost)
  {
    std::array<bool, PairwiseRepeatsAtMost> repeated{};
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (samePlace(corners[piece[i]], corners[piece[j]]))
          repeated[i] = repeated[j] = true;
    for (std::size_t i = 0; i < n; ++i)
      if (repeated[i])
        order.push_back(i);
  }
  else
    for (std::size_t i = 0; i < n; ++i)
      order.push_back(i);
  // By place (x, then y), then by index: a strict total order, so the sort's result is unique.
  std::sort(order.begin(),
    order.end(),
    [&](std::size_t a, std::size_t b)
    {
      const Point2L &p = corners[piece[a]], &q = corners[piece[b]];
      if (p[0] != q[0])
        return p[0] < q[0];
      if (p[1] != q[1])
        return p[1] < q[1];
      return a < b;
    });
  const std::size_t m = order.size();
  for (std::size_t s = 0, e = 0; s < m; s = e)
  {
    for (e = s + 1; e < m && samePlace(corners[piece[order[e]]], corners[piece[order[s]]]); ++e)
      ;
    for (std::size_t a = s; a < e; ++a)
      for (std::size_t b = a + 1; b < e; ++b)
      {
        const std::size_t i = order[a], j = order[b]; // i < j: the loop i .. j - 1 and the rest
        const Wide inner = prefix[j] - prefix[i];
        if (inner <= 0 || prefix[n] - inner <= 0)
          continue;
        const std::vector<int> first(piece.begin() + i, piece.begin() + j);
        std::vector<int> second(piece.begin() + j, piece.end());
        second.insert(second.end(), piece.begin(), piece.begin() + i);
        triangulated = this->triangulatePiece(corners, first, triangles) &&
          this->triangulatePiece(corners, second, triangles);
        return true;
      }
  }
  return false;
}

/// The ear clipping of the file comment on a doubly linked ring of the piece's corners.
bool PolygonTriangulator::clipEars(const std::vector<Point2L>& corners,
  const std::vector<int>& piece,
  std::vector<Triangle>& triangles)
{
  const int n = static_cast<int>(piece.size());
  this->P.resize(piece.size());
  for (int i = 0; i < n; ++i)
    this->P[i] = corners[piece[i]];
  this->Next.resize(piece.size());
  this->Prev.resize(piece.size());
  this->Convex.resize(piece.size());
  for (int i = 0; i < n; ++i)
  {
    this->Next[i] = i + 1 == n ? 0 : i + 1;
    this->Prev[i] = i == 0 ? n - 1 : i - 1;
  }
  this->Narrow = fitsIn64BitProducts(this->P);
  if (this->Narrow && n <= SmallRingCorners)
    return this->clipSmallRing(piece, triangles);
  return this->Narrow ? this->clipRing<std::int64_t>(piece, triangles)
                      : this->clipRing<Wide>(piece, triangles);
}

/// clipRing<std::int64_t> for a piece of at most SmallRingCorners corners, with the corners'
/// convexity in bits: an ear's blockers are the corners that did not turn left at the start and
/// do not now (a corner cut off turned left), all tested (a corner in the triangle is in its
/// box, so the box's columns, which clipRing reads through its blockers sorted by x, only spare
/// tests). The same ears in the same order: on the small pieces of most faces, the sort and the
/// binary searches of clipRing's list, and its loops of unforeseeable length, cost more than
/// testing every blocker.
bool PolygonTriangulator::clipSmallRing(const std::vector<int>& piece,
  std::vector<Triangle>& triangles)
{
  using Int = std::int64_t;
  const int n = static_cast<int>(piece.size());
  std::uint64_t concave = 0; // the corners that do not turn left (clipRing's !Convex)
  for (int i = 0; i < n; ++i)
    if (!this->turnsLeft<Int>(this->Prev[i], i, this->Next[i]))
      concave |= std::uint64_t(1) << i;
  const std::uint64_t atStart = concave; // clipRing's blockers
  // A corner's convexity after a neighbour was cut off (clipRing's updateConvexity).
  auto update = [&](int i)
  {
    const std::uint64_t bit = std::uint64_t(1) << i;
    concave =
      this->turnsLeft<Int>(this->Prev[i], i, this->Next[i]) ? concave & ~bit : concave | bit;
  };
  return this->cutEars<Int>(
    piece,
    triangles,
    [&](int b) { return !((concave >> b) & 1) && this->isSmallRingEar(b, concave & atStart); },
    update);
}

/// isEar<std::int64_t> of clipSmallRing: no corner of `blocking` in the closed triangle of b
/// and its neighbours but at their own places, every one tested without branches. b turns
/// strictly left, so the lines of the triangle's sides meet only at its corners: a corner is at
/// the place of one of them exactly when it lies on two of the lines (two of its products are
/// 0), which spares comparing places.
bool PolygonTriangulator::isSmallRingEar(int b, std::uint64_t blocking) const
{
  const int a = this->Prev[b], c = this->Next[b];
  const EdgeLine ab(this->P[a], this->P[b]), bc(this->P[b], this->P[c]), ca(this->P[c], this->P[a]);
  bool blocked = false;
  for (std::uint64_t m = blocking; m != 0; m &= m - 1)
  {
    const Point2L& q = this->P[static_cast<std::size_t>(countTrailingZeros(m))];
    const std::int64_t c1 = ab.at(q), c2 = bc.at(q), c3 = ca.at(q);
    const int onLines = (c1 == 0) + (c2 == 0) + (c3 == 0);
    blocked |= ((c1 | c2 | c3) >= 0) & (onLines <= 1);
  }
  return !blocked;
}

template<typename Int>
bool PolygonTriangulator::clipRing(const std::vector<int>& piece, std::vector<Triangle>& triangles)
{
  const int n = static_cast<int>(piece.size());
  this->Blockers.clear();
  for (int i = 0; i < n; ++i)
  {
    this->Convex[i] = this->turnsLeft<Int>(this->Prev[i], i, this->Next[i]);
    if (!this->Convex[i])
      this->Blockers.push_back({ this->P[i][0], this->P[i][1], i });
  }
  std::sort(this->Blockers.begin(),
    this->Blockers.end(),
    [](const Blocker& l, const Blocker& r) { return l.x < r.x; });
  this->Stale = 0;
  return this->cutEars<Int>(
    piece,
    triangles,
    [this](int b) { return this->Convex[b] && this->isEar<Int>(b); },
    [this](int i) { this->updateConvexity<Int>(i); });
}

/// The walk both ear clippings share: from corner 0 along the ring, cuts off each corner that
/// isEarAt accepts (updating its two neighbours' convexity through convexityAt), until three
/// corners are left; false when a whole turn of the ring finds no ear (not a simple
/// counter-clockwise polygon).
template<typename Int, typename IsEar, typename UpdateConvexity>
bool PolygonTriangulator::cutEars(const std::vector<int>& piece,
  std::vector<Triangle>& triangles,
  IsEar isEarAt,
  UpdateConvexity convexityAt)
{
  int remaining = static_cast<int>(piece.size());
  int b = 0;
  int misses = 0; // corners tested since the last ear
  while (remaining > 3)
  {
    if (!isEarAt(b))
    {
      b = this->Next[b];
      if (++misses > remaining)
        return false; // no ear: not a simple counter-clockwise polygon
      continue;
    }
    const int a = this->Prev[b], c = this->Next[b];
    triangles.push_back({ piece[a], piece[b], piece[c] });
    this->Next[a] = c;
    this->Prev[c] = a;
    convexityAt(a);
    convexityAt(c);
    --remaining;
    misses = 0;
    b = c;
  }
  const int a = this->Prev[b], c = this->Next[b];
  if (!this->turnsLeft<Int>(a, b, c))
    return false;
  triangles.push_back({ piece[a], piece[b], piece[c] });
  return true;
}

/// Corner i's convexity after a neighbour was cut off; a blocker that turns left is stale.
template<typename Int>
inline void PolygonTriangulator::updateConvexity(int i)
{
  const bool was = this->Convex[i] != 0;
  this->Convex[i] = this->turnsLeft<Int>(this->Prev[i], i, this->Next[i]);
  if (!was && this->Convex[i])
    ++this->Stale;
}

/// Whether convex corner b is an ear: no blocker in the closed triangle of b and its
/// neighbours but at their own places. Only the blockers in the columns of the triangle's
/// bounding box are read (a binary search in the blockers by x); the stale ones (convex now,
/// cut off or not) are swept out once they are half of the list.
template<typename Int>
bool PolygonTriangulator::isEar(int b)
{
  const int a = this->Prev[b], c = this->Next[b];
  const Point2L &pa = this->P[a], &pb = this->P[b], &pc = this->P[c];
  const std::int64_t loX = std::min({ pa[0], pb[0], pc[0] }),
                     hiX = std::max({ pa[0], pb[0], pc[0] });
  const std::int64_t loY = std::min({ pa[1], pb[1], pc[1] }),
                     hiY = std::max({ pa[1], pb[1], pc[1] });
  auto k = std::lower_bound(this->Blockers.begin(),
    this->Blockers.end(),
    loX,
    [](const Blocker& l, std::int64_t x) { return l.x < x; });
  // A corner at the same place as one of the ear's (where the boundary touches itself) leaves
  // that place on the other side: it does not block the ear.
  if constexpr (std::is_same<Int, std::int64_t>::value)
  {
    // Every blocker of the columns tested in full and the answers joined without branches:
    // whether a blocker is in the box, convex or in the triangle is unpredictable, and the
    // mispredictions cost more than the tests (-26 % of the triangulation's time on 50 %
    // noise). A point in the closed triangle is in its box; the products are exact in 64 bits
    // for every corner of the piece (Narrow).
    bool blocked = false;
    for (; k != this->Blockers.end() && k->x <= hiX; ++k)
    {
      const Point2L q{ k->x, k->y };
      const bool elsewhere = !((q[0] == pa[0]) & (q[1] == pa[1])) &
        !((q[0] == pb[0]) & (q[1] == pb[1])) & !((q[0] == pc[0]) & (q[1] == pc[1]));
      const bool inside = (cross2<Int>(pa, pb, q) >= 0) & (cross2<Int>(pb, pc, q) >= 0) &
        (cross2<Int>(pc, pa, q) >= 0);
      blocked |= elsewhere & inside & !this->Convex[k->corner];
    }
    if (blocked)
      return false;
  }
  else
  {
    for (; k != this->Blockers.end() && k->x <= hiX; ++k)
    {
      // 128-bit products: only for the blockers in the box.
      const bool inBox = (k->y >= loY) & (k->y <= hiY);
      if (!inBox || this->Convex[k->corner])
        continue;
      const Point2L q{ k->x, k->y };
      if (!samePlace(q, pa) && !samePlace(q, pb) && !samePlace(q, pc) &&
        inClosedTriangle<Int>(pa, pb, pc, q))
        return false;
    }
  }
  if (2 * this->Stale > this->Blockers.size())
  {
    this->Blockers.erase(std::remove_if(this->Blockers.begin(),
                           this->Blockers.end(),
                           [&](const Blocker& k) { return this->Convex[k.corner] != 0; }),
      this->Blockers.end());
    this->Stale = 0;
  }
  return true;
}

bool fanCoversPolygon(const std::vector<Point2L>& corners, std::size_t apex)
{
  return apex < corners.size() && fanCoversPolygonOfArea(corners, apex, doubledArea(corners));
}

ProjectionAlong::ProjectionAlong(const std::array<std::int64_t, 3>& n)
{
  int k = 0;
  for (int d = 1; d < 3; ++d)
    if (std::llabs(n[d]) > std::llabs(n[k]))
      k = d;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  // n x e_d for a unit vector e_d.
  auto crossAxis = [&](int d)
  {
    std::array<std::int64_t, 3> e{ 0, 0, 0 }, r;
    e[d] = 1;
    r[0] = n[1] * e[2] - n[2] * e[1];
    r[1] = n[2] * e[0] - n[0] * e[2];
    r[2] = n[0] * e[1] - n[1] * e[0];
    return r;
  };
  this->U = crossAxis(i);
  this->V = crossAxis(j);
  if (n[k] < 0)
    std::swap(this->U, this->V);
}

} // namespace vbr
