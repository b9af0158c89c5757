// Exact ear clipping of simple polygons (see the header for why it is correct), and the
// tests of simplicity and fan cover, on integer corners with 128-bit products (Wide).
//
// triangulateSimplePolygon first parts the polygon at corners where it touches itself into
// two counter-clockwise loops (triangulatePiece: the doubled areas of the two loops, from a
// prefix sum, tell whether the corner joins two pieces), then ear-clips each piece on a
// doubly linked ring (EarClipper), testing only the corners that do not turn left (the
// blockers). isSimplePolygon compares every pair of non-adjacent edges (segmentsMeet).

#include "PolygonTriangulator.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <utility>

namespace vbr
{

namespace
{

/// Whether p lies in the closed counter-clockwise triangle abc.
bool inClosedTriangle(const Point2L& a, const Point2L& b, const Point2L& c, const Point2L& p)
{
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
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

/// The ear clipping of the file comment on a doubly linked ring of corners.
class EarClipper
{
public:
  explicit EarClipper(const std::vector<Point2L>& corners)
    : P(corners)
    , Next(corners.size())
    , Prev(corners.size())
    , Convex(corners.size())
    , Alive(corners.size(), 1)
  {
    const int n = static_cast<int>(corners.size());
    for (int i = 0; i < n; ++i)
    {
      this->Next[i] = (i + 1) % n;
      this->Prev[i] = (i + n - 1) % n;
    }
    for (int i = 0; i < n; ++i)
    {
      this->updateConvexity(i);
      if (!this->Convex[i])
        this->Blockers.push_back(i);
    }
  }

  bool run(std::vector<Triangle>& triangles)
  {
    int remaining = static_cast<int>(this->P.size());
    int b = 0;
    int misses = 0; // corners tested since the last ear
    while (remaining > 3)
    {
      if (!this->isEar(b))
      {
        b = this->Next[b];
        if (++misses > remaining)
          return false; // no ear: not a simple counter-clockwise polygon
        continue;
      }
      const int a = this->Prev[b], c = this->Next[b];
      triangles.push_back({ a, b, c });
      this->Next[a] = c;
      this->Prev[c] = a;
      this->Alive[b] = 0;
      this->updateConvexity(a);
      this->updateConvexity(c);
      --remaining;
      misses = 0;
      b = c;
    }
    const int a = this->Prev[b], c = this->Next[b];
    if (cross2(this->P[a], this->P[b], this->P[c]) <= 0)
      return false;
    triangles.push_back({ a, b, c });
    return true;
  }

private:
  void updateConvexity(int i)
  {
    this->Convex[i] = cross2(this->P[this->Prev[i]], this->P[i], this->P[this->Next[i]]) > 0;
  }

  bool isEar(int b)
  {
    if (!this->Convex[b])
      return false;
    const int a = this->Prev[b], c = this->Next[b];
    // The triangle's bounding box: most blockers fall outside it, decided without products.
    const Point2L lo{ std::min({ this->P[a][0], this->P[b][0], this->P[c][0] }),
      std::min({ this->P[a][1], this->P[b][1], this->P[c][1] }) };
    const Point2L hi{ std::max({ this->P[a][0], this->P[b][0], this->P[c][0] }),
      std::max({ this->P[a][1], this->P[b][1], this->P[c][1] }) };
    std::size_t stale = 0;
    for (int k : this->Blockers)
    {
      if (!this->Alive[k] || this->Convex[k])
      {
        ++stale;
        continue;
      }
      // A corner at the same place as one of the ear's (where the boundary touches itself)
      // leaves that place on the other side: it does not block the ear.
      const Point2L& q = this->P[k];
      if (q[0] < lo[0] || q[0] > hi[0] || q[1] < lo[1] || q[1] > hi[1])
        continue;
      if (q != this->P[a] && q != this->P[b] && q != this->P[c] &&
        inClosedTriangle(this->P[a], this->P[b], this->P[c], q))
        return false;
    }
    if (2 * stale > this->Blockers.size()) // corners only ever become convex or go
    {
      this->Blockers.erase(std::remove_if(this->Blockers.begin(),
                             this->Blockers.end(),
                             [&](int k) { return !this->Alive[k] || this->Convex[k]; }),
        this->Blockers.end());
    }
    return true;
  }

  const std::vector<Point2L>& P;
  std::vector<int> Next, Prev;
  std::vector<char> Convex, Alive;
  std::vector<int> Blockers; ///< corners that did not turn left when last looked at
};

/// Triangles of one piece of the polygon (indices into `corners`, in order). Where the
/// piece touches itself at a corner so that the two loops it parts into there both run
/// counter-clockwise (two pieces joined at that corner), each loop is triangulated alone:
/// ear clipping would cut across the gap between them. The loops parted where one runs
/// inside the other (a hole reaching the boundary) or along a slit stay together.
bool triangulatePiece(const std::vector<Point2L>& corners,
  const std::vector<int>& piece,
  std::vector<Triangle>& triangles)
{
  const std::size_t n = piece.size();
  std::vector<Wide> prefix(n + 1, 0); // doubled area swept by the first edges
  for (std::size_t i = 0; i < n; ++i)
  {
    const Point2L& p = corners[piece[i]];
    const Point2L& q = corners[piece[(i + 1) % n]];
    prefix[i + 1] = prefix[i] + Wide(p[0]) * q[1] - Wide(p[1]) * q[0];
  }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = i;
  std::sort(order.begin(),
    order.end(),
    [&](std::size_t a, std::size_t b)
    { return std::make_pair(corners[piece[a]], a) < std::make_pair(corners[piece[b]], b); });
  for (std::size_t s = 0, e = 0; s < n; s = e)
  {
    for (e = s + 1; e < n && corners[piece[order[e]]] == corners[piece[order[s]]]; ++e)
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
        return triangulatePiece(corners, first, triangles) &&
          triangulatePiece(corners, second, triangles);
      }
  }
  std::vector<Point2L> points(n);
  for (std::size_t i = 0; i < n; ++i)
    points[i] = corners[piece[i]];
  std::vector<Triangle> local;
  local.reserve(n - 2);
  EarClipper clipper(points);
  if (!clipper.run(local))
    return false;
  for (const Triangle& t : local)
    triangles.push_back({ piece[t[0]], piece[t[1]], piece[t[2]] });
  return true;
}

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

std::vector<Triangle> triangulateSimplePolygon(const std::vector<Point2L>& corners)
{
  std::vector<Triangle> triangles;
  if (corners.size() < 3 || doubledArea(corners) <= 0)
    return triangles;
  triangles.reserve(corners.size() - 2);
  std::vector<int> all(corners.size());
  for (std::size_t i = 0; i < all.size(); ++i)
    all[i] = static_cast<int>(i);
  if (!triangulatePiece(corners, all, triangles))
    triangles.clear();
  return triangles;
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
