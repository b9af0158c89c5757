// Triangles and fan polygons of the orthogonal faces of a B-Rep, in the face's (u, v) plane
// with (u, v, axis) right-handed.
//
// A face without holes and of at most EarClippingLimit corners is ear-clipped exactly
// (clipEars); so is each edge-connected part of a face whose parts touch at corners, when no
// part has a hole (edgeConnectedParts); every other face is cut into monotone pieces by a sweep
// and each piece triangulated in linear time (MonotoneTriangulator); only a face the sweep
// refuses goes through CGAL's constrained Delaunay triangulation of all its loops, whose
// triangles inside the face are those at odd nesting depth from the outside (markNesting).
// fanPolygons gives what a renderer drawing a polygon as the fan from its first corner draws right:
// the outer loop itself, started at a corner whose fan covers it (fanApex), unless it passes a
// corner twice; else each edge-connected part of a face merged at vertices likewise; or else the
// triangles grouped into fans round shared corners (FanGrouper).

#include "FaceTriangulator.h"

#include "PopCount.h" // VBR_ALWAYS_INLINE
#include "RadixSort.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace vbr
{

namespace
{

/// Two 32-bit integers as one key whose order is theirs, the first first: a corner's (u, v)
/// location, or an edge's two corner indices.
std::uint64_t pairKey(std::int64_t a, std::int64_t b)
{
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint64_t(std::uint32_t(b));
}

struct FaceInfo
{
  int nesting = -1;
  bool inside() const { return this->nesting % 2 == 1; }
};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using FaceBaseInfo = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBaseInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

/// Flood fill from the infinite face: crossing a constrained edge increases the nesting level,
/// and the triangles at odd levels are inside the face. The constrained edges met are
/// crossed first in, first out, so that each region gets the level of the first region that
/// reaches it (a region touching the outside is at level 1 whatever else it touches). The
/// queues are vectors read from the front, not lists: one allocation per face, not per
/// triangle.
void markNesting(Cdt& cdt)
{
  std::vector<Cdt::Edge> border;
  std::vector<Cdt::Face_handle> queue;
  auto fill = [&](Cdt::Face_handle start, int level)
  {
    queue.assign(1, start);
    for (std::size_t next = 0; next < queue.size(); ++next)
    {
      Cdt::Face_handle fh = queue[next];
      if (fh->info().nesting != -1)
        continue;
      fh->info().nesting = level;
      for (int i = 0; i < 3; ++i)
      {
        Cdt::Face_handle n = fh->neighbor(i);
        if (n->info().nesting != -1)
          continue;
        if (cdt.is_constrained(Cdt::Edge(fh, i)))
          border.push_back(Cdt::Edge(fh, i));
        else
          queue.push_back(n);
      }
    }
  };
  fill(cdt.infinite_face(), 0);
  for (std::size_t next = 0; next < border.size(); ++next)
  {
    const Cdt::Edge e = border[next];
    Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1)
      fill(n, e.first->info().nesting + 1);
  }
}

} // namespace

void EarScratch::load(const PointRange& pts, int x, int y)
{
  const std::size_t n = pts.size();
  this->x.resize(n);
  this->y.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    this->x[i] = pts[i][x];
    this->y[i] = pts[i][y];
  }
}

namespace
{

/// The corners of a ring being ear-clipped, in coordinates (x, y) in which it runs
/// counter-clockwise, those that may block an ear also listed densely (in no order) with their
/// coordinates, for the scan of an ear's triangle; kept in an EarScratch. Every corner may block
/// an ear, unless the ring is `simple`: a simple polygon that passes no place twice, where only
/// the corners that do not turn strictly left can (see isEar). Cutting an ear leaves such a ring
/// (no edge crosses the cut, whose triangle holds no corner) and changes the turns only at its
/// two ends, where the list is brought up to date.
class EarCorners
{
public:
  /// Starts a ring of the corners `pts`, (x, y) their coordinates along axes `x` and `y`.
  EarCorners(EarScratch& scratch, const PointRange& pts, int x, int y, bool simple)
    : S(scratch)
    , Simple(simple)
  {
    const std::size_t n = pts.size();
    this->S.load(pts, x, y);
    this->S.slot.resize(n);
    this->S.alive.clear();
    this->S.aliveX.clear();
    this->S.aliveY.clear();
    for (std::size_t i = 0; i < n; ++i)
    {
      const int c = static_cast<int>(i);
      // The neighbours without the modulo: an integer division each, at every corner of every
      // ear-clipped ring (and two more in clipEars' links).
      const int before = i == 0 ? static_cast<int>(n) - 1 : c - 1;
      const int after = i + 1 == n ? 0 : c + 1;
      const bool blocks = !simple || this->turn(before, c, after) <= 0;
      this->S.slot[i] = blocks ? static_cast<int>(this->S.alive.size()) : -1;
      if (blocks)
      {
        this->S.alive.push_back(c);
        this->S.aliveX.push_back(this->S.x[i]);
        this->S.aliveY.push_back(this->S.y[i]);
      }
    }
    this->Left = n;
  }

  /// The number of corners still in the ring.
  std::size_t size() const { return this->Left; }

  /// Twice the signed area of triangle abc (corners of the ring; EarScratch::turn).
  std::int64_t turn(int a, int b, int c) const { return this->S.turn(a, b, c); }

  /// Whether b, between a and c in the ring, is an ear: it turns strictly left and no other
  /// corner of the ring lies in the closed triangle abc. In a simple ring that passes no place
  /// twice, if some corner does, so does one that does not turn strictly left: of the corners
  /// in the triangle, take one, d, farthest from the line ac. Any corner farther from ac in the
  /// triangle is b, whose edges are ab and bc, so no edge crosses the part of the triangle
  /// beyond d's distance, which is thus inside the polygon like the corner of the triangle at
  /// b; and each edge at d either stays in the triangle, ending no farther from ac, or leaves it
  /// through ac (not through ab nor bc: the polygon is simple). The inside at d then spans at
  /// least a half-turn: d turns right or goes straight on.
  bool isEar(int a, int b, int c) const
  {
    if (this->turn(a, b, c) <= 0)
      return false;
    const std::int64_t xa = this->S.x[a], xb = this->S.x[b], xc = this->S.x[c];
    const std::int64_t ya = this->S.y[a], yb = this->S.y[b], yc = this->S.y[c];
    // Every corner is tested in full without a branch but the one that stops at a corner in
    // the triangle: a test that stopped early at one condition or another would branch
    // unpredictably (corners of orthogonal faces often lie on the lines of the ear's sides).
    const std::int64_t *ax = this->S.aliveX.data(), *ay = this->S.aliveY.data();
    const int* alive = this->S.alive.data();
    const std::size_t n = this->S.alive.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::int64_t x = ax[k], y = ay[k];
      const int i = alive[k];
      const bool inside = ((xb - xa) * (y - ya) - (yb - ya) * (x - xa) >= 0) &
        ((xc - xb) * (y - yb) - (yc - yb) * (x - xb) >= 0) &
        ((xa - xc) * (y - yc) - (ya - yc) * (x - xc) >= 0) & (i != a) & (i != b) & (i != c);
      if (inside)
        return false;
    }
    return true;
  }

  /// Takes the ear b out of the ring, whose ends a and c are now neighbours (`prev` and `next`
  /// link the ring, already without b).
  void cut(int a, int b, int c, const int* prev, const int* next)
  {
    this->unlist(b);
    --this->Left;
    if (!this->Simple)
      return;
    this->relist(a, this->turn(prev[a], a, c) <= 0);
    this->relist(c, this->turn(a, c, next[c]) <= 0);
  }

private:
  /// Lists corner i (when it may block an ear) or takes it out of the list.
  void relist(int i, bool blocks)
  {
    if (!blocks)
      this->unlist(i);
    else if (this->S.slot[i] < 0)
    {
      this->S.slot[i] = static_cast<int>(this->S.alive.size());
      this->S.alive.push_back(i);
      this->S.aliveX.push_back(this->S.x[i]);
      this->S.aliveY.push_back(this->S.y[i]);
    }
  }

  /// Takes corner i out of the list of the corners that may block an ear.
  void unlist(int i)
  {
    const int slot = this->S.slot[i];
    if (slot < 0)
      return;
    const int last = this->S.alive.back();
    this->S.alive[slot] = last;
    this->S.aliveX[slot] = this->S.aliveX.back();
    this->S.aliveY[slot] = this->S.aliveY.back();
    this->S.slot[last] = slot;
    this->S.slot[i] = -1;
    this->S.alive.pop_back();
    this->S.aliveX.pop_back();
    this->S.aliveY.pop_back();
  }

  EarScratch& S;
  bool Simple;
  std::size_t Left = 0;
};

/// The corners of a ring that goes round a rectangle (rectangleApex: four left turns, no right
/// turn, straight on elsewhere), where isEar needs no scan. Such a ring is a convex polygon that
/// passes no place twice, and stays one as its ears are cut (cutting the triangle abc of an ear
/// off a convex polygon leaves a convex one). In a convex polygon P, another corner d in the
/// closed triangle abc of a corner b that turns strictly left lies on the open segment ac: d is on
/// the border of P, not on the edges ab and bc (P passes no place twice), so not inside abc,
/// which is inside P. The segment ac then lies on the border of P (a convex set whose border
/// holds a point strictly between two of its points holds the segment), so the rest of the
/// ring, from c round to a, is that segment: every other corner lies on it, the one after c
/// among them. So abc holds another corner if and only if it holds the one after c: the answer
/// of EarCorners::isEar, from one corner instead of all of them.
class ConvexRing
{
public:
  /// Starts a ring of the corners `pts`, (x, y) their coordinates along axes `x` and `y`;
  /// `next` links the ring (the caller's, kept up to date as corners are taken out).
  ConvexRing(EarScratch& scratch, const PointRange& pts, int x, int y, const int* next)
    : S(scratch)
    , Next(next)
    , Left(pts.size())
  {
    this->S.load(pts, x, y);
  }

  std::size_t size() const { return this->Left; }

  /// Twice the signed area of triangle abc (EarScratch::turn).
  std::int64_t turn(int a, int b, int c) const { return this->S.turn(a, b, c); }

  /// EarCorners::isEar on a convex ring: only the corner after c is tested.
  bool isEar(int a, int b, int c) const
  {
    if (this->turn(a, b, c) <= 0)
      return false;
    if (this->Left == 3)
      return true;
    const int d = this->Next[c];
    return this->turn(a, b, d) < 0 || this->turn(b, c, d) < 0 || this->turn(c, a, d) < 0;
  }

  void cut(int, int, int, const int*, const int*) { --this->Left; }

private:
  EarScratch& S;
  const int* Next;
  std::size_t Left;
};

/// What is known of a loop to ear-clip: nothing, a simple polygon that passes no place twice,
/// or one that goes round a rectangle (rectangleApex).
enum class RingKind
{
  Any,
  Simple,
  Rectangle
};

/// Rings of at most this many corners are ear-clipped in arrays on the stack (SmallRing).
constexpr std::size_t SmallRingLimit = 32;

/// EarCorners, or ConvexRing when `convex`, for a ring of at most SmallRingLimit corners: the
/// same answers from arrays on the stack, the corners that may block an ear kept as bits of a
/// word rather than listed (isEar asks whether any of them lies in the ear's triangle: the order
/// in which they are tested changes nothing). On 50 % noise most faces that are not rectangles
/// have 5 to 8 corners, where setting up EarCorners' vectors (sizes, the coordinates copied in
/// 64 bits, the list) cost about as much as the clipping.
class SmallRing
{
public:
  /// Starts a ring of the corners `pts` (at most SmallRingLimit), (x, y) their coordinates along
  /// axes `x` and `y`; `next` links the ring (the caller's, kept up to date). `kind` as in
  /// clipEars: Rectangle makes the ring convex (ConvexRing), Simple lists only the corners that
  /// do not turn strictly left, Any every corner.
  SmallRing(const PointRange& pts, int x, int y, RingKind kind, const int* next)
    : Next(next)
    , Left(static_cast<int>(pts.size()))
    , Convex(kind == RingKind::Rectangle)
    , Simple(kind == RingKind::Simple)
  {
    const int n = this->Left;
    for (int i = 0; i < n; ++i)
    {
      this->X[i] = pts[i][x];
      this->Y[i] = pts[i][y];
    }
    if (this->Convex)
      return;
    if (!this->Simple)
    {
      this->Blocks = n == 32 ? ~std::uint32_t(0) : (std::uint32_t(1) << n) - 1;
      return;
    }
    for (int i = 0; i < n; ++i)
    {
      const int before = i == 0 ? n - 1 : i - 1, after = i + 1 == n ? 0 : i + 1;
      if (this->turn(before, i, after) <= 0)
        this->Blocks |= std::uint32_t(1) << i;
    }
  }

  std::size_t size() const { return static_cast<std::size_t>(this->Left); }

  /// Twice the signed area of triangle abc (EarScratch::turn).
  std::int64_t turn(int a, int b, int c) const
  {
    return (this->X[b] - this->X[a]) * (this->Y[c] - this->Y[a]) -
      (this->Y[b] - this->Y[a]) * (this->X[c] - this->X[a]);
  }

  /// EarCorners::isEar, or ConvexRing::isEar on a convex ring.
  bool isEar(int a, int b, int c) const
  {
    if (this->turn(a, b, c) <= 0)
      return false;
    if (this->Convex)
    {
      if (this->Left == 3)
        return true;
      const int d = this->Next[c];
      return this->turn(a, b, d) < 0 || this->turn(b, c, d) < 0 || this->turn(c, a, d) < 0;
    }
    const std::uint32_t others =
      this->Blocks & ~((std::uint32_t(1) << a) | (std::uint32_t(1) << b) | (std::uint32_t(1) << c));
    const std::int64_t xa = this->X[a], xb = this->X[b], xc = this->X[c];
    const std::int64_t ya = this->Y[a], yb = this->Y[b], yc = this->Y[c];
    for (std::uint32_t m = others; m != 0; m &= m - 1)
    {
      const int k = countTrailingZeros(m);
      const std::int64_t x = this->X[k], y = this->Y[k];
      if (((xb - xa) * (y - ya) - (yb - ya) * (x - xa) >= 0) &
        ((xc - xb) * (y - yb) - (yc - yb) * (x - xb) >= 0) &
        ((xa - xc) * (y - yc) - (ya - yc) * (x - xc) >= 0))
        return false;
    }
    return true;
  }

  /// EarCorners::cut: b leaves the ring; in a simple ring the turns at a and c change.
  void cut(int a, int b, int c, const int* prev, const int* next)
  {
    --this->Left;
    this->Blocks &= ~(std::uint32_t(1) << b);
    if (!this->Simple)
      return;
    this->relist(a, this->turn(prev[a], a, c) <= 0);
    this->relist(c, this->turn(a, c, next[c]) <= 0);
  }

private:
  void relist(int i, bool blocks)
  {
    const std::uint32_t bit = std::uint32_t(1) << i;
    this->Blocks = blocks ? this->Blocks | bit : this->Blocks & ~bit;
  }

  std::int64_t X[SmallRingLimit], Y[SmallRingLimit];
  const int* Next;
  int Left;
  bool Convex, Simple;
  std::uint32_t Blocks = 0; ///< bit i: corner i may block an ear
};

/// The triangles across the edges of the triangles an ear clipping cuts, found as it cuts them
/// (for FanGrouper, which would otherwise pair their edges by a sort): triangle t = (a, b, c),
/// cut at ear b, has edges (a, b), (b, c) and (c, a), in that order; the first two are edges of
/// the ring, either the loop's or the cuts of earlier triangles, and the third is the cut that
/// replaces b in the ring (or, for the last triangle, the ring's last edge). `cutBy[i]`: the
/// triangle whose cut is the ring's edge from corner i to the next, or -1 for an edge of the
/// loop. Every edge inside the polygon is a cut, made once and then the edge of one later
/// triangle, so this pairs exactly the edges the sort pairs (the corners of one loop are
/// distinct indices).
class EarNeighbours
{
public:
  /// Records into `across` (emptied), for a ring of n corners; `cutBy` is scratch space.
  EarNeighbours(std::vector<std::array<int, 3>>* across, int* cutBy, int n)
    : Across(across)
    , CutBy(cutBy)
  {
    if (!across)
      return;
    across->clear();
    std::fill(cutBy, cutBy + n, -1);
  }

  /// Triangle (a, b, c) cut at ear b, its third edge the ring's new edge from a.
  void cut(int a, int b)
  {
    if (!this->Across)
      return;
    const int t = this->add(this->CutBy[a], this->CutBy[b], -1);
    this->CutBy[a] = t;
  }

  /// The last triangle (a, b, c), all three of its edges the ring's.
  void last(int a, int b, int c)
  {
    if (this->Across)
      this->add(this->CutBy[a], this->CutBy[b], this->CutBy[c]);
  }

private:
  int add(int s0, int s1, int s2)
  {
    const int t = static_cast<int>(this->Across->size());
    this->Across->push_back({ s0, s1, s2 });
    for (const int s : { s0, s1, s2 })
      if (s >= 0)
        (*this->Across)[s][2] = t; // the cut is the third edge of the triangle that made it
    return t;
  }

  std::vector<std::array<int, 3>>* Across;
  int* CutBy;
};

/// Appends triangle (a, b, c) as one cell. Three stores, not an insertion of an initializer list
/// (a call to memmove per triangle, with the vector's checks of room before it), inlined at
/// every caller (a call per triangle otherwise: 3 % of the instructions on 50 % noise).
VBR_ALWAYS_INLINE void appendTriangle(int a, int b, int c, FaceCells& out)
{
  out.corners.push_back(a);
  out.corners.push_back(b);
  out.corners.push_back(c);
  out.cellEnds.push_back(static_cast<std::uint32_t>(out.corners.size()));
}

/// The axes (u, v) of a face's plane, with (u, v, axis) right-handed, and the coordinates
/// (x, y) of clipEars, in which an outer loop runs counter-clockwise: (u, v) swapped when the
/// face looks down its axis. From a table, not from two remainders by 3 per face.
struct FaceAxes
{
  int u, v, x, y;

  explicit FaceAxes(const BRepFace& face)
  {
    static constexpr int Next[3] = { 1, 2, 0 }, After[3] = { 2, 0, 1 };
    this->u = Next[face.axis];
    this->v = After[face.axis];
    this->x = face.normalSign > 0 ? this->u : this->v;
    this->y = face.normalSign > 0 ? this->v : this->u;
  }
};

/// The triangles of clipQuadrilateral for a loop of four corners that goes round a rectangle
/// counter-clockwise in (x, y) (a face of one loop of four corners: a unit square of a
/// checkerboard, two thirds of the faces of 50 % noise), found without its tests: every corner
/// turns strictly left there, so corner 0 is an ear (its triangle (3, 0, 1) leaves out corner 2,
/// across the diagonal from 1 to 3), and (2, 3, 1) follows, the same cyclic order round the
/// rectangle. False, with nothing appended, for any other four corners (then clipQuadrilateral).
/// The test is rectangleApex's for four corners, in comparisons and one 64-bit product (four
/// corners leave no room for corners straight on), cheap enough for every face.
bool appendRectangleTriangles(const Point3* p, int x, int y, FaceCells& out)
{
  // Edges along y, x, y, x, or along x, y, x, y.
  const bool alongY =
    (p[0][x] == p[1][x]) & (p[1][y] == p[2][y]) & (p[2][x] == p[3][x]) & (p[3][y] == p[0][y]);
  const bool alongX =
    (p[0][y] == p[1][y]) & (p[1][x] == p[2][x]) & (p[2][y] == p[3][y]) & (p[3][x] == p[0][x]);
  if (!(alongY | alongX))
    return false;
  // Twice the area of triangle (3, 0, 1): positive exactly when the rectangle has an area and
  // runs counter-clockwise.
  const std::int64_t turn = (std::int64_t(p[0][x]) - p[3][x]) * (std::int64_t(p[1][y]) - p[3][y]) -
    (std::int64_t(p[0][y]) - p[3][y]) * (std::int64_t(p[1][x]) - p[3][x]);
  if (turn <= 0)
    return false;
  appendTriangle(3, 0, 1, out);
  appendTriangle(2, 3, 1, out);
  return true;
}

/// clipEars on a ring of four corners (most faces: rectangles), with no ring to set up: the
/// same tests in the same order. (x, y): the coordinates in which the ring runs
/// counter-clockwise. `across`: as in clipEars.
bool clipQuadrilateral(const PointRange& pts,
  int x,
  int y,
  FaceCells& out,
  std::vector<std::array<int, 3>>* across)
{
  const Point3* p = pts.begin();
  const auto turn = [&](int a, int b, int c)
  {
    return (std::int64_t(p[b][x]) - p[a][x]) * (std::int64_t(p[c][y]) - p[a][y]) -
      (std::int64_t(p[b][y]) - p[a][y]) * (std::int64_t(p[c][x]) - p[a][x]);
  };
  const auto emit = [&out](int a, int b, int c) { appendTriangle(a, b, c, out); };
  for (int b = 0; b < 4; ++b)
  {
    const int a = (b + 3) % 4, c = (b + 1) % 4, d = (b + 2) % 4;
    // An ear: a left turn whose closed triangle does not hold the fourth corner.
    if (turn(a, b, c) <= 0 || (turn(a, b, d) >= 0 && turn(b, c, d) >= 0 && turn(c, a, d) >= 0))
      continue;
    emit(a, b, c);
    if (turn(d, a, c) <= 0)
      return false;
    emit(d, a, c);
    if (across) // (a, b, c) and (d, a, c) share the edge (c, a), resp. (a, c)
      *across = { { -1, -1, 1 }, { -1, 0, -1 } };
    return true;
  }
  return false;
}

/// The walk of clipEars round a ring (SmallRing up to SmallRingLimit corners; beyond, EarCorners,
/// or ConvexRing for a loop round a rectangle)
/// linked both ways by `prev` and `next`, from corner 0; the triangles' neighbours recorded by
/// `neighbours`.
template<typename Ring>
bool clipRing(Ring& left, int* prev, int* next, EarNeighbours& neighbours, FaceCells& out)
{
  auto emit = [&out](int a, int b, int c) { appendTriangle(a, b, c, out); };
  int b = 0, misses = 0;
  while (left.size() > 3)
  {
    if (misses >= static_cast<int>(left.size()))
      return false;
    const int a = prev[b], c = next[b];
    if (!left.isEar(a, b, c))
    {
      b = c;
      ++misses;
      continue;
    }
    emit(a, b, c);
    neighbours.cut(a, b);
    next[a] = c;
    prev[c] = a;
    left.cut(a, b, c, prev, next);
    misses = 0;
    b = a;
  }
  const int a = prev[b], c = next[b];
  if (left.turn(a, b, c) <= 0)
    return false;
  emit(a, b, c);
  neighbours.last(a, b, c);
  return true;
}

/// Ear clipping of a face without holes, exact on integers: an ear is a strictly convex
/// corner whose triangle holds no other corner (not even on its border; a corner at the same
/// place as one of the ear's, where the loop visits a place twice, is on it). The corners left
/// form a ring linked both ways, walked from corner to corner: after an ear is cut the walk
/// goes back to the corner before it, the only one besides the next whose ear changed, so
/// that a face takes about one pass round its ring rather than one per ear. Appends the
/// triangles to `out`; returns false when a whole round finds no ear (left to the general
/// triangulation, the caller then drops what was appended). `kind` says what the caller knows
/// of the loop, which spares scans of the ring without changing a triangle (EarCorners,
/// ConvexRing). `out.ring` and `out.earCorners` are scratch space. When `across` is given, it
/// receives the neighbours of the triangles (FanGrouper's Across, from 0 for the first triangle
/// appended here; EarNeighbours).
bool clipEars(const PointRange& pts,
  int u,
  int v,
  int sign,
  RingKind kind,
  FaceCells& out,
  std::vector<std::array<int, 3>>* across = nullptr)
{
  const int n = static_cast<int>(pts.size());
  const int x = sign > 0 ? u : v, y = sign > 0 ? v : u;
  if (n == 4)
    return clipQuadrilateral(pts, x, y, out, across);
  if (n < 3)
    return false;
  if (n <= static_cast<int>(SmallRingLimit))
  {
    int ring[3 * SmallRingLimit];
    int* prev = ring;
    int* next = ring + n;
    for (int i = 0; i < n; ++i)
    {
      prev[i] = i - 1;
      next[i] = i + 1;
    }
    prev[0] = n - 1;
    next[n - 1] = 0;
    EarNeighbours neighbours(across, ring + 2 * n, n);
    SmallRing left(pts, x, y, kind, next);
    return clipRing(left, prev, next, neighbours, out);
  }
  out.ring.resize((across ? 3 : 2) * static_cast<std::size_t>(n));
  int* prev = out.ring.data();
  int* next = out.ring.data() + n;
  for (int i = 0; i < n; ++i)
  {
    prev[i] = i - 1;
    next[i] = i + 1;
  }
  prev[0] = n - 1;
  next[n - 1] = 0;
  EarNeighbours neighbours(across, out.ring.data() + 2 * n, n);
  if (kind == RingKind::Rectangle)
  {
    ConvexRing left(out.earCorners, pts, x, y, next);
    return clipRing(left, prev, next, neighbours, out);
  }
  EarCorners left(out.earCorners, pts, x, y, kind == RingKind::Simple);
  return clipRing(left, prev, next, neighbours, out);
}

/// Faces up to this many corners without holes are ear-clipped. Measured against the
/// constrained Delaunay triangulation face by face on porous volumes and the Berea pore
/// space: ear clipping is 5x to 10x faster up to 48 corners, 1.5x to 5x up to 96, about
/// level near 200 corners, and slower beyond (its cost grows as the cube in the worst case).
constexpr std::size_t EarClippingLimit = 128;

/// The outer loop of a face in (u, v) coordinates, counter-clockwise seen from outside.
/// Returns whether every coordinate lies in [-2^30, 2^30) (smallCoordinates), found on the way:
/// c + 2^30 in 32 bits without sign is below 2^31 exactly then.
bool outerLoop2D(const BRep& brep, const BRepFace& face, std::vector<Point2L>& corners)
{
  const int u = (face.axis + 1) % 3, v = (face.axis + 2) % 3;
  const PointRange pts = brep.loopPoints(face.firstLoop);
  const int x = face.normalSign > 0 ? u : v, y = face.normalSign > 0 ? v : u;
  constexpr std::uint32_t Half = std::uint32_t(1) << 30;
  std::uint32_t shifted = 0;
  corners.resize(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
  {
    corners[i][0] = pts[i][x];
    corners[i][1] = pts[i][y];
    shifted |= (static_cast<std::uint32_t>(pts[i][x]) + Half) |
      (static_cast<std::uint32_t>(pts[i][y]) + Half);
  }
  return (shifted >> 31) == 0;
}

/// Whether every coordinate of the loop lies in [-2^30, 2^30), so that the difference of two
/// products of coordinate differences fits in 64 bits.
bool smallCoordinates(const std::vector<Point2L>& corners)
{
  constexpr std::int64_t Limit = std::int64_t(1) << 30;
  bool small = true;
  for (const Point2L& p : corners)
    small &= p[0] >= -Limit && p[0] < Limit && p[1] >= -Limit && p[1] < Limit;
  return small;
}

/// fanCoversPolygonOfArea(corners, apex, area) for a loop of area `area`, without the area: the
/// fan's triangles add up to it (the shoelace formula from the apex), so when none of them is
/// clockwise the area is positive exactly when one of them is counter-clockwise. In integers of
/// type Int (see cross2).
template<typename Int>
bool fanCoversLoop(const std::vector<Point2L>& corners, std::size_t apex)
{
  const std::size_t n = corners.size();
  if (n < 3)
    return false;
  const Point2L& o = corners[apex];
  std::size_t b = apex + 1 == n ? 0 : apex + 1;
  bool positive = false;
  for (std::size_t i = 1; i + 1 < n; ++i)
  {
    const std::size_t c = b + 1 == n ? 0 : b + 1;
    const Int turn = cross2<Int>(o, corners[b], corners[c]);
    if (turn < 0)
      return false;
    positive |= turn > 0;
    b = c;
  }
  return positive;
}

/// fanApex in integers of type Int (see cross2).
template<typename Int>
int fanApexAs(const std::vector<Point2L>& corners)
{
  const std::size_t n = corners.size();
  std::array<std::size_t, 5> candidates;
  std::size_t count = 0, convex = n;
  for (std::size_t i = 0; i < n && count < 4; ++i)
  {
    const Int turn =
      cross2<Int>(corners[i == 0 ? n - 1 : i - 1], corners[i], corners[i + 1 == n ? 0 : i + 1]);
    if (turn < 0)
      candidates[count++] = i;
    else if (turn > 0 && convex == n)
      convex = i;
  }
  if (count == 0 && convex < n)
    return static_cast<int>(convex);
  if (convex < n)
    candidates[count++] = convex;
  for (std::size_t k = 0; k < count; ++k)
    if (fanCoversLoop<Int>(corners, candidates[k]))
      return static_cast<int>(candidates[k]);
  return -1;
}

/// A corner of the loop from which its fan covers it, or -1. Tried: the first few corners
/// that turn right (the kernel of an orthogonal polygon starts at them), then the first one
/// that turns left (enough for a rectangle with corners on its sides). A loop that never
/// turns right is convex: the first left turn is its apex, with no check (most faces of
/// porous volumes are rectangles, often with corners of their neighbours on their sides).
/// `small`: whether the coordinates are known to be small (smallCoordinates).
int fanApex(const std::vector<Point2L>& corners, bool small)
{
  if (corners.empty())
    return -1;
  return small ? fanApexAs<std::int64_t>(corners) : fanApexAs<Wide>(corners);
}

/// fanApex for a loop whose coordinates are not known to be small.
int fanApex(const std::vector<Point2L>& corners)
{
  return fanApex(corners, smallCoordinates(corners));
}

/// The apex fanApex picks for a face's outer loop that goes round a rectangle: four left
/// turns, no right turn, straight on at every other corner (the corners of neighbouring
/// faces on its sides), as most faces of porous volumes do. Such a loop turns once round, so
/// it is a convex polygon that passes no corner twice, and fanApex takes its first left turn
/// without a check. -1 for any other loop. Read from the face's points, in the coordinates of
/// outerLoop2D, without making them.
int rectangleApex(const PointRange& pts, int u, int v, int sign)
{
  const int x = sign > 0 ? u : v, y = sign > 0 ? v : u;
  const std::size_t n = pts.size();
  const Point3* p = pts.begin();
  int first = -1, lefts = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Point3& a = p[i == 0 ? n - 1 : i - 1];
    const Point3& b = p[i];
    const Point3& c = p[i + 1 == n ? 0 : i + 1];
    const std::int64_t dx0 = std::int64_t(b[x]) - a[x], dy0 = std::int64_t(b[y]) - a[y];
    const std::int64_t dx1 = std::int64_t(c[x]) - b[x], dy1 = std::int64_t(c[y]) - b[y];
    const Wide turn = Wide(dx0) * dy1 - Wide(dy0) * dx1;
    if (turn < 0)
      return -1;
    if (turn > 0 && lefts++ == 0)
      first = static_cast<int>(i);
    else if (turn == 0 && Wide(dx0) * dx1 + Wide(dy0) * dy1 <= 0)
      return -1; // going back, or a corner twice in a row
  }
  return lefts == 4 ? first : -1;
}

/// Whether a loop passes a corner twice (parts of a face, or of its background, touching
/// there): such a loop is no simple polygon even where its fan would cover it. `keys` is
/// scratch space.
bool visitsACornerTwice(const std::vector<Point2L>& corners, std::vector<std::uint64_t>& keys)
{
  if (corners.size() < 8) // the fewest: two squares touching at a corner, merged
    return false;
  keys.resize(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i)
    keys[i] = pairKey(corners[i][0], corners[i][1]);
  std::sort(keys.begin(), keys.end());
  return std::adjacent_find(keys.begin(), keys.end()) != keys.end();
}

/// Triangles grouped into fans: from each triangle not yet taken, the longest fan of
/// untaken triangles round one of its corners (neighbours across the edges at that corner).
/// Neighbours come from a counting sort of the edges by their smaller corner, and a fan's rim grows
/// at both ends in two vectors: linear work in the triangles, whatever the size of the face and of
/// its fans. Its arrays live in a FanScratch reused from face to face (no allocation per face).
class FanGrouper
{
public:
  /// `acrossKnown`: whether `scratch.across` already holds the triangles' neighbours (from the
  /// ear clipping, EarNeighbours); else they are found here.
  FanGrouper(const std::vector<std::array<int, 3>>& triangles,
    FanScratch& scratch,
    bool acrossKnown)
    : Triangles(triangles)
    , Across(scratch.across)
    , Taken(scratch.taken)
    , Stamp(scratch.stamp)
    , Members(scratch.members)
    , Front(scratch.front)
    , Back(scratch.back)
    , BestMembers(scratch.bestMembers)
    , BestFront(scratch.bestFront)
    , BestBack(scratch.bestBack)
  {
    this->Taken.assign(triangles.size(), 0);
    this->Stamp.assign(triangles.size(), -1);
    if (acrossKnown)
      return;
    this->Across.assign(triangles.size(), { -1, -1, -1 });
    this->findNeighbours(scratch);
  }

  void run(FaceCells& out)
  {
    for (std::size_t start = 0; start < this->Triangles.size(); ++start)
    {
      if (this->Taken[start])
        continue;
      int best = 0;
      std::size_t bestSize = 0;
      for (int k = 0; k < 3; ++k)
      {
        const std::size_t size = this->growFan(static_cast<int>(start), k);
        if (size > bestSize)
        {
          bestSize = size;
          best = k;
          this->Members.swap(this->BestMembers); // the largest fan so far, taken as it is
          this->Front.swap(this->BestFront);
          this->Back.swap(this->BestBack);
        }
      }
      for (int t : this->BestMembers)
        this->Taken[t] = 1;
      const int apex = this->Triangles[start][best];
      out.corners.push_back(apex);
      out.corners.insert(out.corners.end(), this->BestBack.rbegin(), this->BestBack.rend());
      out.corners.insert(out.corners.end(), this->BestFront.begin(), this->BestFront.end());
      out.cellEnds.push_back(static_cast<std::uint32_t>(out.corners.size()));
    }
  }

private:
  /// Across[t][k]: the triangle on the other side of edge (t[k], t[k+1]), or -1. The edges
  /// (3t + k) in the order of their corners, smaller then larger, then of 3t + k: a counting
  /// sort by the smaller corner, stable, then each bucket (the edges from one corner to larger
  /// ones, a handful) by the larger by insertion. The two sides of an edge then come together.
  void findNeighbours(FanScratch& s)
  {
    const std::size_t n = this->Triangles.size();
    int top = 0;
    for (const auto& tri : this->Triangles)
      top = std::max({ top, tri[0], tri[1], tri[2] });
    s.bucketEnd.assign(static_cast<std::size_t>(top) + 2, 0);
    for (const auto& tri : this->Triangles)
      for (int k = 0; k < 3; ++k)
        ++s.bucketEnd[static_cast<std::size_t>(std::min(tri[k], tri[(k + 1) % 3])) + 1];
    for (std::size_t c = 1; c < s.bucketEnd.size(); ++c)
      s.bucketEnd[c] += s.bucketEnd[c - 1];
    s.edges.resize(3 * n); // (larger corner, 3t + k)
    for (std::size_t t = 0; t < n; ++t)
      for (int k = 0; k < 3; ++k)
      {
        const int a = this->Triangles[t][k], b = this->Triangles[t][(k + 1) % 3];
        s.edges[s.bucketEnd[std::min(a, b)]++] = { std::max(a, b), static_cast<int>(3 * t + k) };
      }
    // bucketEnd[c] now ends the bucket of corner c.
    for (std::size_t c = 0, begin = 0; c <= static_cast<std::size_t>(top); begin = s.bucketEnd[c++])
      this->pairBucket(s.edges.data() + begin, s.edges.data() + s.bucketEnd[c]);
  }

  /// Orders one bucket of edges (all from one corner, by 3t + k) by their larger corner, 3t + k
  /// next (by insertion; a sort for large buckets gives the same order, the ids being distinct),
  /// and joins the triangles of each two edges in a row with the same corners.
  void pairBucket(std::pair<int, int>* first, std::pair<int, int>* last)
  {
    if (last - first > 32)
      std::sort(first, last);
    else
      for (std::pair<int, int>* i = first + 1; i < last; ++i)
      {
        const std::pair<int, int> edge = *i;
        std::pair<int, int>* j = i;
        for (; j > first && (j - 1)->first > edge.first; --j)
          *j = *(j - 1);
        *j = edge;
      }
    for (std::pair<int, int>* i = first; i + 1 < last; ++i)
    {
      if (i->first != (i + 1)->first)
        continue;
      const int a = i->second, b = (i + 1)->second;
      this->Across[a / 3][a % 3] = b / 3;
      this->Across[b / 3][b % 3] = a / 3;
      ++i;
    }
  }

  /// The triangle across edge e (from corner e to corner e + 1) of triangle t, if untaken and
  /// not yet in this fan, or -1.
  int across(int t, int e) const
  {
    const int other = this->Across[t][e];
    return other >= 0 && !this->Taken[other] && this->Stamp[other] != this->Round ? other : -1;
  }

  /// The place of corner `apex` in triangle t (one of its corners).
  int placeOf(int t, int apex) const
  {
    const auto& tri = this->Triangles[t];
    return tri[0] == apex ? 0 : tri[1] == apex ? 1 : 2;
  }

  /// The fan of untaken triangles round corner k of triangle t0, both ways, in Members;
  /// returns its number of triangles. Leaves its rim (the corners after the apex,
  /// counter-clockwise) in Back reversed, then Front. With the apex at place j of a triangle,
  /// the fan goes on forwards across the triangle's edge j + 2 (from the corner before the
  /// apex to the apex) and backwards across its edge j (from the apex to the corner after it).
  std::size_t growFan(int t0, int k)
  {
    const auto& first = this->Triangles[t0];
    const int apex = first[k];
    ++this->Round;
    // Emptied and pushed rather than assigned: an assignment is a call that checks the capacity
    // first, three of them per triangle that starts a fan.
    this->Members.clear();
    this->Members.push_back(t0);
    this->Stamp[t0] = this->Round;
    this->Front.clear();
    this->Front.push_back(first[(k + 1) % 3]);
    this->Front.push_back(first[(k + 2) % 3]);
    this->Back.clear();
    for (int t = this->across(t0, (k + 2) % 3); t >= 0;)
    {
      this->Stamp[t] = this->Round;
      this->Members.push_back(t);
      const int j = this->placeOf(t, apex);
      this->Front.push_back(this->Triangles[t][(j + 2) % 3]);
      t = this->across(t, (j + 2) % 3);
    }
    for (int t = this->across(t0, k); t >= 0;)
    {
      this->Stamp[t] = this->Round;
      this->Members.push_back(t);
      const int j = this->placeOf(t, apex);
      this->Back.push_back(this->Triangles[t][(j + 1) % 3]);
      t = this->across(t, j);
    }
    return this->Members.size();
  }

  const std::vector<std::array<int, 3>>& Triangles;
  std::vector<std::array<int, 3>>& Across;
  std::vector<int>&Taken, &Stamp;
  std::vector<int>&Members, &Front, &Back;
  std::vector<int>&BestMembers, &BestFront, &BestBack; ///< the largest fan of the three tried
  int Round = 0;
};

} // namespace

namespace detail
{
int rectangleApexOf(const PointRange& pts, int u, int v, int sign)
{
  return rectangleApex(pts, u, v, sign);
}
} // namespace detail

namespace
{

/// The index of (x, y) along the Hilbert curve through the side x side grid (side a power of
/// two above x and y): points close along it are close in the plane.
std::uint64_t hilbertIndex(std::uint64_t x, std::uint64_t y, std::uint64_t side)
{
  std::uint64_t d = 0;
  for (std::uint64_t s = side / 2; s > 0; s >>= 1)
  {
    const std::uint64_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry); // s <= 2^31: below 2^64
    if (ry == 0)                  // turn the quadrant so that the curve runs on in it
    {
      if (rx == 1)
      {
        x = ~x;
        y = ~y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

/// A corner of a face's loops, by its index there, with its place along the Hilbert curve.
struct CornerCode
{
  std::uint64_t code;
  int index;
};

/// The corners `at` (in the plane (u, v)) sorted along the Hilbert curve through their
/// bounding square, stably: the corners at one location together, in the order of their
/// indices.
std::vector<CornerCode> cornersAlongHilbertCurve(const std::vector<Point3>& at, int u, int v)
{
  std::int64_t uLo = std::numeric_limits<std::int64_t>::max(), vLo = uLo, span = 0;
  for (const Point3& p : at)
  {
    uLo = std::min<std::int64_t>(uLo, p[u]);
    vLo = std::min<std::int64_t>(vLo, p[v]);
  }
  for (const Point3& p : at)
    span = std::max({ span, p[u] - uLo, p[v] - vLo });
  std::uint64_t side = 2; // at most 2^32: 32-bit coordinates differ by less
  while (side <= static_cast<std::uint64_t>(span))
    side *= 2;
  std::vector<CornerCode> corners(at.size());
  for (std::size_t i = 0; i < at.size(); ++i)
    corners[i] = { hilbertIndex(static_cast<std::uint64_t>(at[i][u] - uLo),
                     static_cast<std::uint64_t>(at[i][v] - vLo),
                     side),
      static_cast<int>(i) };
  radixSortBy(corners, [](const CornerCode& c) { return c.code; });
  return corners;
}

} // namespace

/// The loops of a face as the constraints of `cdt`, each vertex carrying the index (in the
/// face's loop corners) of the first corner at its location. The distinct corners go in one
/// by one along the Hilbert curve, each located from the vertex before it: the short walks of
/// CGAL's spatial sort, from one radix sort that also brings the corners at one location
/// together (on a face of millions of corners, a maze, a hash table of the locations and
/// CGAL's sort took longer than the triangulation's flips). The loop edges follow as
/// constraints between their vertices.
void insertLoops(const BRep& brep, const BRepFace& face, int u, int v, Cdt& cdt)
{
  std::vector<Point3> at;
  for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
  {
    const PointRange pts = brep.loopPoints(l);
    at.insert(at.end(), pts.begin(), pts.end());
  }
  const std::vector<CornerCode> sorted = cornersAlongHilbertCurve(at, u, v);
  std::vector<int> firstAt(at.size()); // per corner: the first corner at its location
  std::vector<Cdt::Vertex_handle> handleOf(at.size()); // by index of a first corner
  Cdt::Face_handle hint;
  for (std::size_t k = 0; k < sorted.size(); ++k)
  {
    const int index = sorted[k].index;
    if (k > 0 && sorted[k].code == sorted[k - 1].code)
    {
      firstAt[index] = firstAt[sorted[k - 1].index];
      continue;
    }
    const Point3& p = at[index];
    const Cdt::Vertex_handle vh = cdt.insert(Kernel::Point_2(p[u], p[v]), hint);
    vh->info() = index;
    firstAt[index] = index;
    handleOf[index] = vh;
    hint = vh->face();
  }
  int start = 0;
  for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
  {
    const int n = static_cast<int>(brep.loopPoints(l).size());
    for (int i = 0; i < n; ++i)
      cdt.insert_constraint(handleOf[firstAt[start + i]], handleOf[firstAt[start + (i + 1) % n]]);
    start += n;
  }
}

namespace
{

/// Appends the triangles of the constrained Delaunay triangulation of the face's loops that
/// lie inside the face.
void appendDelaunayTriangles(const BRep& brep, const BRepFace& face, FaceCells& out)
{
  const int u = (face.axis + 1) % 3, v = (face.axis + 2) % 3; // (u, v, axis) is right-handed
  Cdt cdt;
  insertLoops(brep, face, u, v, cdt);
  markNesting(cdt);
  const bool flip = face.normalSign < 0; // CGAL faces are counter-clockwise in (u, v)
  for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh)
  {
    if (!fh->info().inside())
      continue;
    const int a = fh->vertex(0)->info(), b = fh->vertex(1)->info(), c = fh->vertex(2)->info();
    out.corners.insert(out.corners.end(), { a, flip ? c : b, flip ? b : c });
    out.cellEnds.push_back(static_cast<std::uint32_t>(out.corners.size()));
  }
}

/// Appends the triangles of a face with holes or a long loop from the sweep into monotone
/// pieces (MonotoneTriangulator), in the coordinates of clipEars, where every loop runs with the
/// inside on its left; false when the sweep refuses the face.
bool appendMonotoneTriangles(const BRep& brep, const BRepFace& face, FaceCells& out)
{
  const int u = (face.axis + 1) % 3, v = (face.axis + 2) % 3;
  const int x = face.normalSign > 0 ? u : v, y = face.normalSign > 0 ? v : u;
  out.loop2D.clear();
  out.loopNext.clear();
  for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
  {
    const PointRange pts = brep.loopPoints(l);
    const int start = static_cast<int>(out.loop2D.size()), n = static_cast<int>(pts.size());
    for (int i = 0; i < n; ++i)
    {
      out.loop2D.push_back({ pts[i][x], pts[i][y] });
      out.loopNext.push_back(start + (i + 1 == n ? 0 : i + 1));
    }
  }
  const std::size_t from = out.corners.size();
  if (!out.monotone.triangulate(out.loop2D, out.loopNext, out.corners))
    return false;
  for (std::size_t c = from + 3; c <= out.corners.size(); c += 3)
    out.cellEnds.push_back(static_cast<std::uint32_t>(c));
  return true;
}

/// The corners of all the loops of a face (outer loop first), each with the next corner of its
/// own loop.
struct LoopCorners
{
  std::vector<Point3> at;
  std::vector<int> next;

  LoopCorners(const BRep& brep, const BRepFace& face)
  {
    for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
    {
      const PointRange pts = brep.loopPoints(l);
      const int start = static_cast<int>(this->at.size()), n = static_cast<int>(pts.size());
      this->at.insert(this->at.end(), pts.begin(), pts.end());
      for (int i = 0; i < n; ++i)
        this->next.push_back(start + (i + 1) % n);
    }
  }
};

/// The edge-connected parts of a face, each a cycle of corners: cycle k is corners
/// `corners[ends[k - 1] .. ends[k])` (ends[-1] = 0), indices as in triangulateFace (a corner
/// shared by two loops or visited twice by one by its first index), at `points`.
struct FaceParts
{
  std::vector<int> corners;
  std::vector<std::size_t> ends;
  std::vector<Point3> points;

  std::size_t count() const { return this->ends.size(); }
  std::size_t begin(std::size_t k) const { return k == 0 ? 0 : this->ends[k - 1]; }
  PointRange pointsOf(std::size_t k) const
  {
    return { this->points.data() + this->begin(k), this->points.data() + this->ends[k] };
  }
};

/// Joins the loop edges at the corners where two parts of a face meet diagonally (parts merged
/// at vertices, MergeNonManifoldFaces): each edge coming into such a corner is joined to the
/// edge going out that turns left from it (the corner of its own part) rather than to the one
/// crossing over to the other part. `first[i]`: the first index at corner i's location;
/// `partner[i]`: the other index there, or -1. False when no corner is shared (nothing to
/// cut) or a location holds three (never on an orthogonal face).
bool joinPartsAtSharedCorners(LoopCorners& loops,
  int u,
  int v,
  int sign,
  std::vector<int>& first,
  std::vector<int>& partner)
{
  const int n = static_cast<int>(loops.at.size());
  std::vector<std::pair<std::uint64_t, int>> byLocation(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    byLocation[i] = { pairKey(loops.at[i][u], loops.at[i][v]), i };
  if (byLocation.size() < 256)
    std::sort(byLocation.begin(), byLocation.end());
  else // stable: the corners of one location stay in index order
    radixSortBy(byLocation, [](const std::pair<std::uint64_t, int>& c) { return c.first; });
  std::vector<int> prev(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    prev[loops.next[i]] = i;
  const auto turnsLeft = [&](int from, int at, int to)
  {
    const Point3 &a = loops.at[from], &b = loops.at[at], &c = loops.at[to];
    return sign *
      (static_cast<long long>(b[u] - a[u]) * (c[v] - b[v]) -
        static_cast<long long>(b[v] - a[v]) * (c[u] - b[u])) >
      0;
  };
  first.assign(static_cast<std::size_t>(n), -1);
  partner.assign(static_cast<std::size_t>(n), -1);
  bool shared = false;
  for (int k = 0; k < n; ++k)
  {
    const bool repeated = k > 0 && byLocation[k - 1].first == byLocation[k].first;
    first[byLocation[k].second] = repeated ? first[byLocation[k - 1].second] : byLocation[k].second;
    if (!repeated)
      continue;
    if (k > 1 && byLocation[k - 2].first == byLocation[k].first)
      return false;
    const int a = byLocation[k - 1].second, b = byLocation[k].second;
    partner[a] = b;
    partner[b] = a;
    if (!turnsLeft(prev[a], a, loops.next[a]))
      std::swap(loops.next[a], loops.next[b]);
    shared = true;
  }
  return shared;
}

/// The parts of a face whose loops touch at corners: the cycles of the loop edges joined at
/// the shared corners (joinPartsAtSharedCorners) bound the face's edge-connected parts. When
/// each turns counter-clockwise, the parts have no holes and do not nest (a part inside
/// another would need a clockwise cycle between them): each is a polygon of its own, to be cut
/// on its own, in linear time for a face of many small parts where the triangulation of all
/// its loops at once takes a point location per corner. False when no corner is shared, or a
/// cycle is clockwise (a hole), longer than EarClippingLimit or touches itself.
bool edgeConnectedParts(const BRep& brep, const BRepFace& face, int u, int v, FaceParts& parts)
{
  LoopCorners loops(brep, face);
  std::vector<int> first, partner;
  if (!joinPartsAtSharedCorners(loops, u, v, face.normalSign, first, partner))
    return false;
  const int n = static_cast<int>(loops.at.size());
  std::vector<int> cycleOf(static_cast<std::size_t>(n), -1);
  for (int start = 0; start < n; ++start)
  {
    if (cycleOf[start] >= 0)
      continue;
    const int cycle = static_cast<int>(parts.count());
    long long area = 0;
    std::size_t size = 0;
    for (int i = start; cycleOf[i] < 0; i = loops.next[i], ++size)
    {
      if (partner[i] >= 0 && cycleOf[partner[i]] == cycle)
        return false; // the part touches itself: not a simple polygon
      cycleOf[i] = cycle;
      parts.corners.push_back(first[i]);
      parts.points.push_back(loops.at[i]);
      const Point3 &p = loops.at[i], &q = loops.at[loops.next[i]];
      area += static_cast<long long>(p[u]) * q[v] - static_cast<long long>(q[u]) * p[v];
    }
    if (size > EarClippingLimit || face.normalSign * area <= 0)
      return false;
    parts.ends.push_back(parts.corners.size());
  }
  return true;
}

/// Ear clipping of each part of a face (edgeConnectedParts); false when a part has no ear,
/// the triangles then left in `out` for the caller to drop.
bool clipParts(const FaceParts& parts, int u, int v, int sign, FaceCells& out)
{
  for (std::size_t k = 0; k < parts.count(); ++k)
  {
    const std::size_t from = out.corners.size(), first = parts.begin(k);
    if (!clipEars(parts.pointsOf(k), u, v, sign, RingKind::Any, out))
      return false;
    for (std::size_t c = from; c < out.corners.size(); ++c)
      out.corners[c] = parts.corners[first + static_cast<std::size_t>(out.corners[c])];
  }
  return true;
}

/// What clipEars may know of a face's outer loop of more than four corners: whether it goes round
/// a rectangle, else whether it runs counter-clockwise (as outer loops do) and passes no place
/// twice, which makes it a simple polygon (its edges
/// lie on the lines of the pixels, and a point where the border of a set of pixels meets itself
/// is a corner it passes twice: the diagonal pixels around it are in the set, the two others
/// not). `out.keys` is scratch space.
RingKind ringKind(const PointRange& pts, int u, int v, int sign, FaceCells& out)
{
  if (pts.size() <= 4)
    return RingKind::Any; // clipQuadrilateral
  if (rectangleApex(pts, u, v, sign) >= 0)
    return RingKind::Rectangle;
  // Counter-clockwise in clipEars' coordinates, as an outer loop runs.
  const int x = sign > 0 ? u : v, y = sign > 0 ? v : u;
  Wide area = 0;
  for (std::size_t i = 0, j = pts.size() - 1; i < pts.size(); j = i++)
    area += Wide(pts[j][x]) * pts[i][y] - Wide(pts[j][y]) * pts[i][x];
  if (area <= 0)
    return RingKind::Any;
  out.keys.resize(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    out.keys[i] = pairKey(pts[i][u], pts[i][v]);
  std::sort(out.keys.begin(), out.keys.end());
  return std::adjacent_find(out.keys.begin(), out.keys.end()) == out.keys.end() ? RingKind::Simple
                                                                                : RingKind::Any;
}

/// Appends the triangles of face `f` without closing the face. `tryParts`: whether the face may
/// have edge-connected parts to ear-clip (false when the caller found it has none). Returns
/// whether `across`, when given, holds the triangles' neighbours (clipEars of the face's one
/// loop); else it holds nothing of use.
bool appendTrianglesOf(const BRep& brep,
  int f,
  FaceCells& out,
  bool tryParts = true,
  std::vector<std::array<int, 3>>* across = nullptr)
{
  const BRepFace& face = brep.faces[f];
  const PointRange outer = brep.loopPoints(face.firstLoop);
  const std::size_t corners = out.corners.size(), cells = out.cellEnds.size();
  const FaceAxes axes(face);
  const int u = axes.u, v = axes.v;
  if (face.loopCount == 1 && outer.size() <= EarClippingLimit)
  {
    if (clipEars(
          outer, u, v, face.normalSign, ringKind(outer, u, v, face.normalSign, out), out, across))
      return across != nullptr;
    out.corners.resize(corners); // no ear: the general method from scratch
    out.cellEnds.resize(cells);
  }
  FaceParts parts;
  if (tryParts && brep.mergedAtVertices && edgeConnectedParts(brep, face, u, v, parts) &&
    clipParts(parts, u, v, face.normalSign, out))
    return false;
  out.corners.resize(corners);
  out.cellEnds.resize(cells);
  if (appendMonotoneTriangles(brep, face, out))
    return false;
  out.corners.resize(corners);
  out.cellEnds.resize(cells);
  appendDelaunayTriangles(brep, face, out);
  return false;
}

} // namespace

void appendTriangles(const BRep& brep, int f, FaceCells& cells)
{
  const BRepFace& face = brep.faces[f];
  const PointRange outer = brep.loopPoints(face.firstLoop);
  bool done = false;
  if (face.loopCount == 1 && outer.size() == 4)
  {
    const FaceAxes axes(face);
    done = appendRectangleTriangles(outer.begin(), axes.x, axes.y, cells);
  }
  if (!done)
    appendTrianglesOf(brep, f, cells);
  cells.endFace();
}

std::vector<std::array<int, 3>> triangulateFace(const BRep& brep, int f)
{
  FaceCells cells;
  appendTrianglesOf(brep, f, cells);
  std::vector<std::array<int, 3>> triangles(cells.cellEnds.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      triangles[t][k] = cells.corners[3 * t + k];
  return triangles;
}

namespace
{

/// Appends the loop of `n` corners, from corner `apex` on, as one polygon.
void appendLoopFrom(std::size_t apex, std::size_t n, FaceCells& cells)
{
  for (std::size_t i = apex; i < n; ++i)
    cells.corners.push_back(static_cast<int>(i));
  for (std::size_t i = 0; i < apex; ++i)
    cells.corners.push_back(static_cast<int>(i));
  cells.cellEnds.push_back(static_cast<std::uint32_t>(cells.corners.size()));
  cells.endFace();
}

/// Appends the fans of the triangles of face `f` (triangulateFace), its triangles made in
/// `cells` itself and moved to its scratch space; `tryParts` as in appendTrianglesOf.
void appendFanGroups(const BRep& brep,
  int f,
  FaceCells& cells,
  bool tryParts,
  bool neighboursFromEars)
{
  const std::size_t corners = cells.corners.size(), cellCount = cells.cellEnds.size();
  const bool acrossKnown =
    appendTrianglesOf(brep, f, cells, tryParts, neighboursFromEars ? &cells.fans.across : nullptr);
  std::vector<std::array<int, 3>>& triangles = cells.fans.triangles;
  triangles.resize((cells.corners.size() - corners) / 3);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      triangles[t][k] = cells.corners[corners + 3 * t + k];
  cells.corners.resize(corners);
  cells.cellEnds.resize(cellCount);
  FanGrouper(triangles, cells.fans, acrossKnown).run(cells);
}

/// The polygons of a face whose edge-connected parts touch at corners (edgeConnectedParts),
/// one per part, when each part is drawn right as the fan from one of its corners; false,
/// with nothing appended, otherwise. `hasParts`: whether the face has such parts at all.
bool appendPartPolygons(const BRep& brep, const BRepFace& face, FaceCells& cells, bool& hasParts)
{
  const int u = (face.axis + 1) % 3, v = (face.axis + 2) % 3;
  FaceParts parts;
  hasParts = brep.mergedAtVertices && edgeConnectedParts(brep, face, u, v, parts);
  if (!hasParts)
    return false;
  const std::size_t corners = cells.corners.size(), cellCount = cells.cellEnds.size();
  for (std::size_t k = 0; k < parts.count(); ++k)
  {
    cells.loop2D.clear();
    for (const Point3& p : parts.pointsOf(k))
      cells.loop2D.push_back(face.normalSign > 0 ? Point2L{ p[u], p[v] } : Point2L{ p[v], p[u] });
    const std::size_t m = cells.loop2D.size();
    const int apex = m == 4 ? 0 : fanApex(cells.loop2D); // 4 corners: a rectangle
    if (apex < 0)
    {
      cells.corners.resize(corners);
      cells.cellEnds.resize(cellCount);
      return false;
    }
    for (std::size_t i = 0; i < m; ++i)
      cells.corners.push_back(
        parts.corners[parts.begin(k) + (static_cast<std::size_t>(apex) + i) % m]);
    cells.cellEnds.push_back(static_cast<std::uint32_t>(cells.corners.size()));
  }
  return true;
}

/// appendFanPolygons; `neighboursFromEars`: whether the fans of an ear-clipped face take the
/// triangles' neighbours from the ear clipping (EarNeighbours) rather than from the sort of their
/// edges (a test's reference).
void appendFanPolygonsOf(const BRep& brep, int f, FaceCells& cells, bool neighboursFromEars)
{
  const BRepFace& face = brep.faces[f];
  if (face.loopCount == 1 && brep.loopPoints(face.firstLoop).size() == 4)
  {
    appendLoopFrom(0, 4, cells); // a rectangle: the fan from any corner covers it
    return;
  }
  if (face.loopCount == 1)
  {
    const PointRange outer = brep.loopPoints(face.firstLoop);
    const FaceAxes axes(face);
    int apex = rectangleApex(outer, axes.u, axes.v, face.normalSign);
    if (apex < 0)
    {
      const bool small = outerLoop2D(brep, face, cells.loop2D);
      apex = fanApex(cells.loop2D, small);
      if (apex >= 0 && visitsACornerTwice(cells.loop2D, cells.keys))
        apex = -1;
    }
    if (apex >= 0)
    {
      appendLoopFrom(static_cast<std::size_t>(apex), outer.size(), cells);
      return;
    }
  }
  bool hasParts = false;
  if (!appendPartPolygons(brep, face, cells, hasParts))
    appendFanGroups(brep, f, cells, hasParts, neighboursFromEars);
  cells.endFace();
}

} // namespace

void appendFanPolygons(const BRep& brep, int f, FaceCells& cells)
{
  appendFanPolygonsOf(brep, f, cells, true);
}

namespace
{
/// The cells of `cells` as lists of corner numbers, one per polygon.
std::vector<std::vector<int>> polygonsOf(const FaceCells& cells)
{
  std::vector<std::vector<int>> polygons;
  for (std::size_t c = 0; c < cells.cellEnds.size(); ++c)
    polygons.emplace_back(
      cells.corners.begin() + cells.cornerBegin(c), cells.corners.begin() + cells.cellEnds[c]);
  return polygons;
}
} // namespace

namespace detail
{
std::vector<std::vector<int>> fanPolygonsFromSortedEdges(const BRep& brep, int f)
{
  FaceCells cells;
  appendFanPolygonsOf(brep, f, cells, false);
  return polygonsOf(cells);
}
} // namespace detail

std::vector<std::vector<int>> edgeConnectedPartsOf(const BRep& brep, int f)
{
  const BRepFace& face = brep.faces[f];
  FaceParts parts;
  std::vector<std::vector<int>> out;
  if (edgeConnectedParts(brep, face, (face.axis + 1) % 3, (face.axis + 2) % 3, parts))
    for (std::size_t k = 0; k < parts.count(); ++k)
      out.emplace_back(parts.corners.begin() + static_cast<std::ptrdiff_t>(parts.begin(k)),
        parts.corners.begin() + static_cast<std::ptrdiff_t>(parts.ends[k]));
  return out;
}

std::vector<std::vector<int>> fanPolygons(const BRep& brep, int f)
{
  FaceCells cells;
  appendFanPolygons(brep, f, cells);
  return polygonsOf(cells);
}

} // namespace vbr
