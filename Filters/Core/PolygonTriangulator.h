// Exact triangulation of simple polygons with integer corners, and the projection that turns
// a non-planar loop of pointels into one.
//
// Ear clipping: a corner b (between a and c) is an ear when it turns strictly left and no
// other corner lies in the closed triangle abc; cutting it off leaves a simple polygon, and a
// simple polygon of n corners always has an ear (its triangulations have n - 2 triangles,
// whose dual tree has two leaves or more), so n - 2 cuts triangulate it. Corners where the
// boundary goes straight on (collinear with their neighbours) are kept: they are never ears
// themselves, but they are corners of the triangles, so an edge a neighbouring face shares
// with the polygon is an edge of its triangles too (no T-junctions, no new points). Only
// corners that do not turn left can lie in an ear's triangle: of the corners in it, the one
// farthest from ac has both neighbours no farther (no edge crosses ab or bc) and the inside
// of the polygon above it, so it turns right or goes straight. Only those are tested.
// Orientation tests are exact (128-bit products of 64-bit coordinates).
//
// The projection: a loop of pointels that lies on a surface crossed once by every line
// parallel to a normal n (the boundary of a digital half-space with outward normal n, which
// holds a standard face) projects along n to a simple polygon. Coordinates (u.p, v.p) with
// u = n x e_i and v = n x e_j, for (i, j, k) a cyclic order of the axes with n_k != 0, are an
// affine image of that projection (u x v = n_k n): integers, with the orientation seen from
// the side n points to when n_k > 0 (u and v are swapped when n_k < 0).
#ifndef vbr_PolygonTriangulator_h
#define vbr_PolygonTriangulator_h

#include "Geometry.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

using Point2L = std::array<std::int64_t, 2>;
using Triangle = std::array<int, 3>;

/// Sign of twice the signed area of triangle abc: +1 counter-clockwise, -1 clockwise, 0 flat.
int orientation(const Point2L& a, const Point2L& b, const Point2L& c);

/// Twice the signed area of triangle abc in integers of type Int: exact in Wide, and in 64
/// bits when every coordinate lies in [-2^30, 2^30). Inline: the faces' hot loops call it.
template<typename Int = Wide>
inline Int cross2(const Point2L& a, const Point2L& b, const Point2L& c)
{
  return Int(b[0] - a[0]) * (c[1] - a[1]) - Int(b[1] - a[1]) * (c[0] - a[0]);
}

/// Twice the signed area of a polygon (positive when counter-clockwise).
inline Wide doubledArea(const std::vector<Point2L>& corners)
{
  Wide sum = 0;
  const std::size_t n = corners.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const Point2L& p = corners[i];
    const Point2L& q = corners[i + 1 == n ? 0 : i + 1];
    sum += Wide(p[0]) * q[1] - Wide(p[1]) * q[0];
  }
  return sum;
}

/// Whether the closed polygon is simple: no corner repeated, no two edges meeting except
/// consecutive edges at their common corner (exact, quadratic).
bool isSimplePolygon(const std::vector<Point2L>& corners);

/// Triangles (indices into `corners`, counter-clockwise) covering a simple counter-clockwise
/// polygon exactly: n - 2 of them, none flat. The polygon may also touch itself at corners
/// without crossing (a corner repeated, as the loop of a face through a pointel where the
/// object touches itself): each repetition is a corner of its own, and there are
/// n - 2r - 2chi triangles (r repetitions, chi the Euler characteristic of the region: n - 2
/// for a disk's loop, two fewer for each corner that joins two pieces). Empty when the polygon
/// has fewer than three corners or no ear is found (it was not simple or not
/// counter-clockwise).
std::vector<Triangle> triangulateSimplePolygon(const std::vector<Point2L>& corners);

/// The triangles of a polygon when every corner turns strictly left, no two lie at one place and
/// every triangle of the fan from the last corner, (n - 1, i, i + 1), turns strictly left: then
/// PolygonTriangulator::triangulate makes exactly that fan, in that order (it has no blocker, every
/// corner it meets is an ear), and this appends it without the ear clipping's set-up (most faces of
/// a noisy boundary are such squares and hexagons); PolygonTriangulator::triangulate tries it
/// first. False, with nothing appended, for any other polygon and for more than FanCornersAtMost
/// corners: the ear clipping decides those.
bool fanStrictlyConvexPolygon(const std::vector<Point2L>& corners,
  std::vector<Triangle>& triangles);
constexpr std::size_t FanCornersAtMost = 12;

/// triangulateSimplePolygon with its working memory kept between calls (a caller that
/// triangulates many polygons, such as every face of a polyhedrization, allocates nothing per
/// polygon once the arrays have grown, except where a polygon touches itself at a corner and
/// is parted there). The same triangles in the same order.
class PolygonTriangulator
{
public:
  /// Appends triangulateSimplePolygon(corners) to `triangles`; false, with nothing appended,
  /// when that is empty.
  bool triangulate(const std::vector<Point2L>& corners, std::vector<Triangle>& triangles);
  /// triangulate without the shortcut of fanStrictlyConvexPolygon: the ear clipping alone.
  bool triangulateByEars(const std::vector<Point2L>& corners, std::vector<Triangle>& triangles);

private:
  struct Blocker
  {
    std::int64_t x, y;
    int corner;
  };
  bool triangulatePiece(const std::vector<Point2L>& corners,
    const std::vector<int>& piece,
    std::vector<Triangle>& triangles);
  bool hasRepeatedCorner(const std::vector<Point2L>& corners, const std::vector<int>& piece);
  bool splitAtTouchingCorner(const std::vector<Point2L>& corners,
    const std::vector<int>& piece,
    std::vector<Triangle>& triangles,
    bool& triangulated);
  bool clipEars(const std::vector<Point2L>& corners,
    const std::vector<int>& piece,
    std::vector<Triangle>& triangles);
  /// clipEars once the ring is set up, with cross2 in integers of type Int (std::int64_t when
  /// Narrow: one choice per piece rather than one per orientation test).
  template<typename Int>
  bool clipRing(const std::vector<int>& piece, std::vector<Triangle>& triangles);
  template<typename Int>
  bool isEar(int b);
  /// Pieces of at most this many corners (one bit each) are clipped by clipSmallRing.
  static constexpr int SmallRingCorners = 64;
  bool clipSmallRing(const std::vector<int>& piece, std::vector<Triangle>& triangles);
  bool isSmallRingEar(int b, std::uint64_t blocking) const;
  template<typename Int, typename IsEar, typename UpdateConvexity>
  bool cutEars(const std::vector<int>& piece,
    std::vector<Triangle>& triangles,
    IsEar isEarAt,
    UpdateConvexity convexityAt);
  /// Whether corners a, b, c of the piece turn strictly left.
  template<typename Int>
  bool turnsLeft(int a, int b, int c) const
  {
    return cross2<Int>(this->P[a], this->P[b], this->P[c]) > 0;
  }
  template<typename Int>
  void updateConvexity(int i);

  std::vector<int> All;        ///< the corners' indices, the first piece
  std::vector<Point2L> P;      ///< the piece's corners, in order
  bool Narrow = false;         ///< P's products fit in 64 bits (cross2)
  std::vector<int> Next, Prev; ///< the ring of corners not cut off
  /// Per corner of the piece. A corner cut off was convex (an ear) and stays so (only the
  /// cut's neighbours are updated): Convex alone tells the corners that may block an ear.
  std::vector<char> Convex;
  /// The corners that did not turn left at the start (a corner only ever becomes convex or
  /// goes: cutting an ear narrows its neighbours' angles), by x; Stale counts the corners that
  /// became convex since the list was last swept (blockers or not: it only sets how often the
  /// list is swept).
  std::vector<Blocker> Blockers;
  std::size_t Stale = 0;
  std::vector<std::uint32_t> Slots;    ///< hash of the corners (hasRepeatedCorner)
  std::vector<std::uint32_t> SlotMark; ///< the call that wrote each slot
  std::uint32_t Mark = 0;
  std::vector<Wide> Prefix;       ///< splitAtTouchingCorner's doubled areas
  std::vector<std::size_t> Order; ///< splitAtTouchingCorner's corners by place
};

/// Whether the fan of triangles (apex, i, i + 1) over the polygon's corners covers a simple
/// counter-clockwise polygon exactly (every triangle counter-clockwise or flat): then a
/// renderer that draws the polygon as that fan (VTK does, from its first point) draws it right.
bool fanCoversPolygon(const std::vector<Point2L>& corners, std::size_t apex);

/// fanCoversPolygon for a corner `apex` of the polygon whose doubled area `area` is known
/// (doubledArea), in integers of type Int (see cross2).
template<typename Int = Wide>
inline bool fanCoversPolygonOfArea(const std::vector<Point2L>& corners, std::size_t apex, Wide area)
{
  const std::size_t n = corners.size();
  if (n < 3 || area <= 0)
    return false;
  const Point2L& o = corners[apex];
  std::size_t b = apex + 1 == n ? 0 : apex + 1;
  for (std::size_t i = 1; i + 1 < n; ++i)
  {
    const std::size_t c = b + 1 == n ? 0 : b + 1;
    if (cross2<Int>(o, corners[b], corners[c]) < 0)
      return false;
    b = c;
  }
  return true;
}

/// Exact 2D coordinates of 3D points projected along a normal (see the file comment).
class ProjectionAlong
{
public:
  explicit ProjectionAlong(const std::array<std::int64_t, 3>& normal);
  template<typename Point3>
  Point2L operator()(const Point3& p) const
  {
    return { this->U[0] * p[0] + this->U[1] * p[1] + this->U[2] * p[2],
      this->V[0] * p[0] + this->V[1] * p[1] + this->V[2] * p[2] };
  }

private:
  std::array<std::int64_t, 3> U{ 0, 0, 0 }, V{ 0, 0, 0 };
};

} // namespace vbr

#endif
