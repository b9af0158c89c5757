#include "ConvexHullModifier.h"

#include "CUDB.h"
#include "ConvexHullModifier2D.h"
#include "EVM.h"
#include "Geometry.h"
#include "LatticeBasis.h"
#include "UnionFind.h"

#include <algorithm>
#include <bitset>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <queue>
#include <set>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <unordered_map>

namespace vbr
{
namespace
{

using Index = std::uint32_t;
using Dims = std::array<std::int32_t, 3>;

std::int64_t floorDiv(std::int64_t a, std::int64_t b)
{
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0)))
  {
    --q;
  }
  return q;
}

std::int64_t ceilDiv(std::int64_t a, std::int64_t b)
{
  return -floorDiv(-a, b);
}

LatticePoint sub(const LatticePoint& a, const LatticePoint& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

__int128 dot(const LatticePoint& a, const LatticePoint& b)
{
  return __int128(a[0]) * b[0] + __int128(a[1]) * b[1] + __int128(a[2]) * b[2];
}

LatticePoint cross(const LatticePoint& a, const LatticePoint& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

bool inGrid(const Dims& d, const LatticePoint& p)
{
  return p[0] >= 0 && p[1] >= 0 && p[2] >= 0 && p[0] < d[0] && p[1] < d[1] && p[2] < d[2];
}

/// 1 for an object centre, 0 for a background one (everything outside the grid).
bool voxelClass(const BitVolume& v, const LatticePoint& p)
{
  return inGrid(v.dims(), p) &&
    v.get(static_cast<std::int32_t>(p[0]),
      static_cast<std::int32_t>(p[1]),
      static_cast<std::int32_t>(p[2]));
}

/// How a RowScan's slices are asked for their rows: all of each slice's rows (forEachRowIn), so
/// that leaving planes out of a slice (setSlice) pays, or a few rows per slice (RowSides), where
/// finding the slice's box cost more than it saved (setSlice 2.4 % of the aneurism's profile).
enum class SliceRows
{
  Few,
  All
};

/// Hulls of at most this many planes are scanned on all their planes: a box has 6 and a wedge
/// 5, few to leave out, while the slice's box passes over all the hull's vertices and edges.
/// Measured on the aneurism v >= 128 (CPU of Update, three rounds in turns, load 3.6-4.4):
/// finding boxes for every solid hull (0) cost 4-7 % more than 8; 4 and 16 were within the
/// noise of 8 (medians 10.96, 11.03, 11.19 s).
constexpr std::size_t kPlanesBeforeSliceBoxes = 8;

/// The planes of a hull arranged for scanning its rows along x: those parallel to x first (they
/// decide whether a row meets the hull without a division), each with its offset at the current
/// slice. Most rows of a hull's box miss the hull, and a row is left at the first plane that
/// empties it; every level of the recursion scans its hull's rows this way (pointsOfClass).
/// With SliceRows::All, a solid c must be a convexHull result with its incidences: its vertices
/// and edges bound the slices' boxes (sliceBox), and a vertex or edge missing from them would
/// give too small a box and silently shortened rows. Without edges (planes alone) every plane
/// is tested on every row.
class RowScan
{
public:
  RowScan(const CellList& c, bool strict, SliceRows rows = SliceRows::Few)
    : Strict(strict)
    , Hull(rows == SliceRows::All && c.dimension == 3 && !c.edges.empty() &&
            c.planes.size() > kPlanesBeforeSliceBoxes
          ? &c
          : nullptr)
  {
    for (const FacePlane& p : c.planes)
      this->Planes.push_back({ p.normal[0], p.normal[1], p.normal[2], p.offset, p.offset });
    std::stable_partition(
      this->Planes.begin(), this->Planes.end(), [](const Plane& p) { return p.nx == 0; });
  }

  /// The slice z. A solid hull's slice is bounded by a few of its planes: the planes that keep
  /// the whole box of the lattice points the slice can hold (sliceBox; kept at its four corners,
  /// so in all of it) are left out of its rows, whose ranges are cut to that box instead (most
  /// planes of a large hull, each a product per row before). The ranges are the same: within
  /// the box those planes exclude no lattice point, and every lattice point of the slice lies
  /// in the box.
  void setSlice(std::int64_t z)
  {
    for (Plane& p : this->Planes)
      p.atSlice = p.offset - p.nz * z;
    if (!this->Hull)
      return;
    this->Box = this->sliceBox(z);
    this->Active.clear();
    if (this->Box[0] > this->Box[1] || this->Box[2] > this->Box[3])
      return;
    for (const Plane& p : this->Planes)
    {
      bool keepsBox = true;
      for (int corner = 0; corner < 4 && keepsBox; ++corner)
      {
        const std::int64_t x = this->Box[corner & 1], y = this->Box[2 + (corner >> 1)];
        const __int128 v = __int128(p.nx) * x + __int128(p.ny) * y;
        keepsBox = this->Strict ? v < p.atSlice : v <= p.atSlice;
      }
      if (!keepsBox)
        this->Active.push_back(p);
    }
  }

  /// The x range [lo, hi] of the row y of the slice inside the hull (its open interior when
  /// `strict`); false when the row misses it.
  bool range(std::int64_t y, std::int64_t& lo, std::int64_t& hi) const
  {
    if (!this->Hull)
      return this->rangeOf(this->Planes,
        y,
        std::numeric_limits<std::int64_t>::min() / 4,
        std::numeric_limits<std::int64_t>::max() / 4,
        lo,
        hi);
    if (this->Box[0] > this->Box[1] || y < this->Box[2] || y > this->Box[3])
      return false;
    return this->rangeOf(this->Active, y, this->Box[0], this->Box[1], lo, hi);
  }

  /// How many planes the current slice leaves out of its rows (0 when the slices keep all).
  std::size_t planesLeftOut() const
  {
    return this->Hull ? this->Planes.size() - this->Active.size() : 0;
  }

private:
  struct Plane
  {
    std::int64_t nx, ny, nz, offset, atSlice;
  };

  bool rangeOf(const std::vector<Plane>& planes,
    std::int64_t y,
    std::int64_t from,
    std::int64_t to,
    std::int64_t& lo,
    std::int64_t& hi) const
  {
    lo = from;
    hi = to;
    for (const Plane& p : planes)
    {
      const std::int64_t r = p.atSlice - p.ny * y;
      if (p.nx == 0)
      {
        if (this->Strict ? r <= 0 : r < 0)
          return false;
      }
      else if (p.nx > 0)
      {
        // The division only when the plane cuts the range: most planes of a large hull do not
        // (a product is cheaper than a division, and hi already keeps the plane then).
        if (!this->keeps(p.nx, hi, r))
          hi = std::min(hi, this->Strict ? ceilDiv(r, p.nx) - 1 : floorDiv(r, p.nx));
      }
      else if (!this->keeps(p.nx, lo, r))
        lo = std::max(lo, this->Strict ? floorDiv(r, p.nx) + 1 : ceilDiv(r, p.nx));
      if (lo > hi)
        return false;
    }
    return true;
  }

  /// The box {x0, x1, y0, y1} of the lattice points that the hull's slice z can hold: the
  /// bounds of its corners (the hull's vertices in the slice and its edges' crossings), rounded
  /// inwards; x0 > x1 (or y0 > y1) when it holds none.
  std::array<std::int64_t, 4> sliceBox(std::int64_t z) const
  {
    std::array<std::int64_t, 4> box{ std::numeric_limits<std::int64_t>::max(),
      std::numeric_limits<std::int64_t>::min(),
      std::numeric_limits<std::int64_t>::max(),
      std::numeric_limits<std::int64_t>::min() };
    const auto take = [&](int k, std::int64_t low, std::int64_t high)
    {
      box[2 * k] = std::min(box[2 * k], low);
      box[2 * k + 1] = std::max(box[2 * k + 1], high);
    };
    for (const LatticePoint& v : this->Hull->vertices)
      if (v[2] == z)
      {
        take(0, v[0], v[0]);
        take(1, v[1], v[1]);
      }
    for (const auto& e : this->Hull->edges)
    {
      const LatticePoint* a = &this->Hull->vertices[e[0]];
      const LatticePoint* b = &this->Hull->vertices[e[1]];
      if ((*a)[2] > (*b)[2])
        std::swap(a, b);
      if (!((*a)[2] < z && z < (*b)[2]))
        continue;
      // The crossing a + (b - a) t / dz, each coordinate a fraction over dz > 0.
      const std::int64_t dz = (*b)[2] - (*a)[2], t = z - (*a)[2];
      for (int k = 0; k < 2; ++k)
      {
        const std::int64_t n = (*a)[k] * dz + ((*b)[k] - (*a)[k]) * t;
        take(k, ceilDiv(n, dz), floorDiv(n, dz));
      }
    }
    return box;
  }

  /// Whether x keeps the plane (nx x < r, or <= when not strict): then the bound the plane
  /// gives on the range's side of x lies beyond x and cannot narrow a range ending at x.
  bool keeps(std::int64_t nx, std::int64_t x, std::int64_t r) const
  {
    const __int128 v = __int128(nx) * x;
    return this->Strict ? v < r : v <= r;
  }

  std::vector<Plane> Planes, Active;
  bool Strict;
  const CellList* Hull;
  std::array<std::int64_t, 4> Box{ 0, -1, 0, -1 };
};

std::array<std::int64_t, 6> boundsOf(const CellList& c)
{
  std::array<std::int64_t, 6> b{ c.vertices[0][0],
    c.vertices[0][0],
    c.vertices[0][1],
    c.vertices[0][1],
    c.vertices[0][2],
    c.vertices[0][2] };
  for (const auto& p : c.vertices)
  {
    for (int k = 0; k < 3; ++k)
    {
      b[2 * k] = std::min(b[2 * k], p[k]);
      b[2 * k + 1] = std::max(b[2 * k + 1], p[k]);
    }
  }
  return b;
}

/// Calls f(y, z, lo, hi) for every row of the solid hull's box that meets the hull (its open
/// interior when `strict`), [lo, hi] the x range of its lattice points there. An f that returns
/// a bool stops the scan by returning false; forEachRowIn returns whether the scan ran to its end.
/// c is a convexHull result with its incidences (vertices and edges bound the slices: RowScan).
template<typename F>
bool forEachRowIn(const CellList& c, bool strict, F&& f)
{
  const auto b = boundsOf(c);
  RowScan rows(c, strict, SliceRows::All);
  for (std::int64_t z = b[4]; z <= b[5]; ++z)
  {
    rows.setSlice(z);
    for (std::int64_t y = b[2]; y <= b[3]; ++y)
    {
      std::int64_t lo, hi;
      if (!rows.range(y, lo, hi) || std::max(lo, b[0]) > std::min(hi, b[1]))
        continue;
      if constexpr (std::is_same_v<decltype(f(y, z, lo, hi)), bool>)
      {
        if (!f(y, z, std::max(lo, b[0]), std::min(hi, b[1])))
          return false;
      }
      else
        f(y, z, std::max(lo, b[0]), std::min(hi, b[1]));
    }
  }
  return true;
}

/// Calls f(p) for every lattice point of the solid hull (of its open interior when `strict`).
template<typename F>
void forEachPointIn(const CellList& c, bool strict, F&& f)
{
  forEachRowIn(c,
    strict,
    [&](std::int64_t y, std::int64_t z, std::int64_t lo, std::int64_t hi)
    {
      for (std::int64_t x = lo; x <= hi; ++x)
        f(LatticePoint{ x, y, z });
    });
}

bool strictlyInside(const CellList& c, const LatticePoint& p)
{
  return std::all_of(c.planes.begin(),
    c.planes.end(),
    [&](const FacePlane& plane) { return plane.evaluate(p) < 0; });
}

/// Whether p lies on the closed triangle abc (exactly).
bool onTriangle(const LatticePoint& a,
  const LatticePoint& b,
  const LatticePoint& c,
  const FacePlane& plane,
  const LatticePoint& p)
{
  if (plane.evaluate(p) != 0)
    return false;
  return dot(plane.normal, cross(sub(b, a), sub(p, a))) >= 0 &&
    dot(plane.normal, cross(sub(c, b), sub(p, b))) >= 0 &&
    dot(plane.normal, cross(sub(a, c), sub(p, c))) >= 0;
}

/// A box that leaves the lattice points' bounds open.
const LatticeBox kUnbounded{ LatticePoint{ INT64_MIN / 4, INT64_MIN / 4, INT64_MIN / 4 },
  LatticePoint{ INT64_MAX / 4, INT64_MAX / 4, INT64_MAX / 4 } };

/// Calls f(p) for every lattice point p of the closed triangle t within the box (each once: the
/// points of the triangle's plane are one per point of its projection along its largest normal
/// component).
template<typename F>
void forEachPointOnTriangle(const std::array<LatticePoint, 3>& t, const LatticeBox& box, F&& f)
{
  const LatticePoint &a = t[0], &b = t[1], &c = t[2];
  const FacePlane plane = planeThrough(a, b, c);
  int k = 0;
  for (int q = 1; q < 3; ++q)
    if (std::abs(plane.normal[q]) > std::abs(plane.normal[k]))
      k = q;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const bool unitK = plane.normal[k] == 1 || plane.normal[k] == -1;
  const std::int64_t loI = std::max(box[0][i], std::min({ a[i], b[i], c[i] }));
  const std::int64_t hiI = std::min(box[1][i], std::max({ a[i], b[i], c[i] }));
  const std::int64_t loJ = std::max(box[0][j], std::min({ a[j], b[j], c[j] }));
  const std::int64_t hiJ = std::min(box[1][j], std::max({ a[j], b[j], c[j] }));
  // p lies in the plane, so each cross product of onTriangle is a multiple of the normal, with
  // the sign of its k-th component times that of n_k: the same test on the projection.
  const std::int64_t sk = plane.normal[k] > 0 ? 1 : -1;
  auto leftOf = [&](const LatticePoint& e0, const LatticePoint& e1, std::int64_t u, std::int64_t v)
  { return sk * ((e1[i] - e0[i]) * (v - e0[j]) - (e1[j] - e0[j]) * (u - e0[i])) >= 0; };
  for (std::int64_t u = loI; u <= hiI; ++u)
    for (std::int64_t v = loJ; v <= hiJ; ++v)
    {
      const std::int64_t r = plane.offset - plane.normal[i] * u - plane.normal[j] * v;
      // A unit component (the faces of a voxel surface, mostly) divides every r: no division.
      if (!unitK && r % plane.normal[k] != 0)
        continue;
      LatticePoint p;
      p[i] = u;
      p[j] = v;
      p[k] = unitK ? r * plane.normal[k] : r / plane.normal[k];
      if (p[k] >= box[0][k] && p[k] <= box[1][k] && leftOf(a, b, u, v) && leftOf(b, c, u, v) &&
        leftOf(c, a, u, v))
        f(p);
    }
}

/// A lattice vector v with n.v = 1 for a primitive normal n (extended Euclid, twice).
LatticePoint unitStep(const LatticePoint& n)
{
  std::int64_t a, b, c, e;
  std::int64_t g = signedExtendedGcd(n[0], n[1], a, b);
  const std::int64_t h = signedExtendedGcd(g, n[2], c, e);
  LatticePoint v{ c * a, c * b, e };
  if (h < 0)
  {
    v = { -v[0], -v[1], -v[2] };
  }
  return v;
}

/// A configuration the pressing-in cannot resolve (see the header).
struct Unresolved : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

struct Context
{
  const BitVolume& objects;
  CoplanarFaces coplanar;
  const Execution& exec;
  std::map<FacePlane, int> planeLevel;
  int keptApart = 0;
  /// Joins or handle cuts dropped together because H with all of them did not separate.
  int discardedChanges = 0;
  /// Whether groups are pressed in as pits (the first pass) or all kept apart (the second).
  bool pits = true;
  /// The object's boundary Euler characteristic once counted (none inside when the object is
  /// not well-composed) and its number of surfaces (-1 until counted; objectSurfaces).
  std::optional<std::optional<long>> euler;
  long surfaces = -1;
  /// The level of each triangle of H when its components were solved apart (empty otherwise):
  /// a plane can then hold faces of different levels in different components.
  std::vector<int> triangleLevel;
};

/// The hull of the points; a flat one is thickened by the points one lattice step off its
/// plane or line that lie in the parent hull (in its open interior when `strict`).
bool solidHull(const std::vector<LatticePoint>& points,
  const CellList& parent,
  bool strict,
  CoplanarFaces coplanar,
  CellList& out)
{
  out = convexHull(points, coplanar);
  if (out.dimension == 3)
  {
    return true;
  }
  std::vector<LatticePoint> steps{ { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  if (out.dimension == 2)
  {
    steps.push_back(unitStep(out.planes[0].normal));
  }
  std::vector<LatticePoint> thick = points;
  for (const auto& p : points)
  {
    for (const auto& s : steps)
    {
      for (int sign : { -1, 1 })
      {
        const LatticePoint q{ p[0] + sign * s[0], p[1] + sign * s[1], p[2] + sign * s[2] };
        if (strict ? strictlyInside(parent, q) : hullContains(parent, q))
        {
          thick.push_back(q);
        }
      }
    }
  }
  out = convexHull(thick, coplanar);
  return out.dimension == 3;
}

/// Whether a hull inside the closed C misses a corner of C, that is (C being the hull of its
/// lattice corners) whether it holds fewer lattice points than C: the lattice count of the
/// hulls strictly decreases from level to level, so the recursion ends.
bool missesACorner(const CellList& inside, const CellList& c)
{
  return std::any_of(c.vertices.begin(),
    c.vertices.end(),
    [&](const LatticePoint& p) { return !hullContains(inside, p); });
}

/// A run of lattice points along a row: (x, y, z) for lo <= x <= hi.
struct Run
{
  std::int64_t lo, hi, y, z;
};

/// Lattice points as runs along rows, in the order of their points (each run's points from
/// low to high x), `count` points in all. Every level of the recursion lists the points of
/// the other class in its hull, and the top levels' hulls hold millions of them: as a list of
/// points that was most of the time of listing, labelling and merging them, memory-bound (the
/// list written, grown and copied point by point); as runs it costs about the rows. The
/// points, their order and so every hull made from them are those of the list they replace.
struct PointRuns
{
  std::vector<Run> runs;
  std::size_t count = 0;

  bool empty() const { return this->count == 0; }

  /// Appends the points lo..hi of row (y, z), extending the last run when they continue it.
  void push(std::int64_t lo, std::int64_t hi, std::int64_t y, std::int64_t z)
  {
    if (!this->runs.empty() && this->runs.back().hi + 1 == lo && this->runs.back().y == y &&
      this->runs.back().z == z)
      this->runs.back().hi = hi;
    else
      this->runs.push_back({ lo, hi, y, z });
    this->count += static_cast<std::size_t>(hi - lo + 1);
  }

  void append(const PointRuns& other)
  {
    for (const Run& r : other.runs)
      this->push(r.lo, r.hi, r.y, r.z);
  }

  template<typename F>
  void forEachPoint(F&& f) const
  {
    for (const Run& r : this->runs)
      for (std::int64_t x = r.lo; x <= r.hi; ++x)
        f(LatticePoint{ x, r.y, r.z });
  }

  std::vector<LatticePoint> points() const
  {
    std::vector<LatticePoint> out;
    out.reserve(this->count);
    this->forEachPoint([&](const LatticePoint& p) { out.push_back(p); });
    return out;
  }

  static PointRuns of(const std::vector<LatticePoint>& points)
  {
    PointRuns out;
    for (const auto& p : points)
      out.push(p[0], p[0], p[1], p[2]);
    return out;
  }
};

/// Whether f holds for a point of the runs (the points tried in their order).
template<typename F>
bool anyPoint(const PointRuns& points, F&& f)
{
  for (const Run& r : points.runs)
    for (std::int64_t x = r.lo; x <= r.hi; ++x)
      if (f(LatticePoint{ x, r.y, r.z }))
        return true;
  return false;
}

/// Appends the runs of set bits of a word whose bit 0 is x = x0, in row (y, z).
void pushRunsOfWord(Word word, std::int64_t x0, std::int64_t y, std::int64_t z, PointRuns& out)
{
  while (word != 0)
  {
    const int start = __builtin_ctzll(word);
    const Word zerosAfter = ~(word >> start); // the run ends at its first zero bit
    const int length = zerosAfter == 0 ? 64 : __builtin_ctzll(zerosAfter);
    out.push(x0 + start, x0 + start + length - 1, y, z);
    word = start + length >= 64 ? 0 : word & (~Word(0) << (start + length));
  }
}

/// The bits of word w (x = 64 w .. 64 w + 63) among x = first..last, for a word that meets that
/// range (first <= last, first >> 6 <= w <= last >> 6).
Word runMask(std::int64_t w, std::int64_t first, std::int64_t last)
{
  Word bits = ~Word(0);
  if (w == first >> 6)
    bits &= ~Word(0) << (first & 63);
  if (w == last >> 6 && (last & 63) != 63)
    bits &= (Word(1) << ((last & 63) + 1)) - 1;
  return bits;
}

/// Appends the runs of the points of class `cls` among x = lo..hi of row (y, z): off the grid's
/// row every centre is background; on it, the class's bits word by word.
void pushRunsOfRow(const BitVolume& objects,
  bool cls,
  std::int64_t lo,
  std::int64_t hi,
  std::int64_t y,
  std::int64_t z,
  PointRuns& points)
{
  const Dims d = objects.dims();
  const bool rowInGrid = y >= 0 && z >= 0 && y < d[1] && z < d[2];
  if (!rowInGrid)
  {
    if (!cls)
      points.push(lo, hi, y, z);
    return;
  }
  const Word* bits = objects.row(static_cast<std::int32_t>(y), static_cast<std::int32_t>(z));
  if (!cls && lo <= -1)
    points.push(lo, std::min<std::int64_t>(hi, -1), y, z);
  const std::int64_t first = std::max<std::int64_t>(lo, 0);
  const std::int64_t last = std::min<std::int64_t>(hi, d[0] - 1);
  for (std::int64_t w = first >> 6; first <= last && w <= last >> 6; ++w)
  {
    const Word word = (cls ? bits[w] : ~bits[w]) & runMask(w, first, last);
    pushRunsOfWord(word, 64 * w, y, z, points);
  }
  if (!cls && std::max<std::int64_t>(lo, d[0]) <= hi)
    points.push(std::max<std::int64_t>(lo, d[0]), hi, y, z);
}

/// The lattice points of class `cls` in the hull (its open interior when `strict`), row by row
/// from the volume's words, as runs: every level of the recursion collects its points so.
PointRuns pointsOfClass(const CellList& c, const BitVolume& objects, bool cls, bool strict)
{
  PointRuns points;
  forEachRowIn(c,
    strict,
    [&](std::int64_t y, std::int64_t z, std::int64_t lo, std::int64_t hi)
    { pushRunsOfRow(objects, cls, lo, hi, y, z, points); });
  return points;
}

void recordPlanes(Context& ctx, const CellList& c, int level)
{
  for (FacePlane p : c.planes)
  {
    if (level % 2 == 1)
    {
      for (auto& n : p.normal)
      {
        n = -n;
      }
      p.offset = -p.offset;
    }
    ctx.planeLevel.emplace(p, level);
  }
}

/// The label of each point (comps' label of the CUDB box holding it), the boxes' rows looked up
/// among the points sorted by a key that packs their offsets from `lo` `shift` bits apart.
template<typename Key>
std::vector<std::uint32_t> labelsByRows(const std::vector<LatticePoint>& points,
  const LatticePoint& lo,
  const CUDB& cudb,
  const Components& comps,
  int shift)
{
  const auto key = [&](std::int64_t x, std::int64_t y, std::int64_t z)
  {
    return (static_cast<Key>(z - lo[2]) << (2 * shift)) | (static_cast<Key>(y - lo[1]) << shift) |
      static_cast<Key>(x - lo[0]);
  };
  std::vector<std::pair<Key, std::uint32_t>> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    order[i] = { key(points[i][0], points[i][1], points[i][2]), static_cast<std::uint32_t>(i) };
  if (!std::is_sorted(order.begin(), order.end()))
    std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> label(points.size(), 0);
  for (std::size_t b = 0; b < cudb.boxes.size(); ++b)
  {
    const Box& box = cudb.boxes[b];
    for (std::int64_t z = lo[2] + box.lo[2]; z < lo[2] + box.hi[2]; ++z)
      for (std::int64_t y = lo[1] + box.lo[1]; y < lo[1] + box.hi[1]; ++y)
      {
        const Key first = key(lo[0] + box.lo[0], y, z), last = key(lo[0] + box.hi[0] - 1, y, z);
        for (auto at = std::lower_bound(
               order.begin(), order.end(), std::pair<Key, std::uint32_t>{ first, 0 });
             at != order.end() && at->first <= last;
             ++at)
          label[at->second] = comps.boxLabel[b];
      }
  }
  return label;
}

/// The label of each point from the x intervals the boxes give each row of the points' box (a
/// table of rows, each listing its intervals): no sort of the points, which labelsByRows needs
/// and which was most of the time of labelling the groups kept apart (their points come group
/// after group, out of row order). For boxes of few rows against the points; labelsByRows
/// otherwise (points spread over a wide sparse box).
std::vector<std::uint32_t> labelsByRowIntervals(const std::vector<LatticePoint>& points,
  const LatticePoint& lo,
  const Dims& d,
  const CUDB& cudb,
  const Components& comps)
{
  struct Interval
  {
    std::int32_t lo, hi;
    std::uint32_t label;
  };
  const auto rowOf = [&](std::int64_t y, std::int64_t z) { return std::size_t(z) * d[1] + y; };
  std::vector<std::size_t> start(std::size_t(d[1]) * d[2] + 1, 0);
  for (const Box& box : cudb.boxes)
    for (std::int32_t z = box.lo[2]; z < box.hi[2]; ++z)
      for (std::int32_t y = box.lo[1]; y < box.hi[1]; ++y)
        ++start[rowOf(y, z) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<Interval> intervals(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t b = 0; b < cudb.boxes.size(); ++b)
  {
    const Box& box = cudb.boxes[b];
    for (std::int32_t z = box.lo[2]; z < box.hi[2]; ++z)
      for (std::int32_t y = box.lo[1]; y < box.hi[1]; ++y)
        intervals[fill[rowOf(y, z)]++] = { box.lo[0], box.hi[0], comps.boxLabel[b] };
  }
  // A row of many intervals (stripes, combs) is sorted once and searched, so that a point costs
  // a logarithm of its row's intervals, not their number; the intervals of a row are disjoint
  // (the boxes are), so the last one starting at or before x is the only one that can hold it.
  constexpr std::size_t fewIntervals = 8;
  const auto byStart = [](const Interval& a, const Interval& b) { return a.lo < b.lo; };
  for (std::size_t row = 0; row + 1 < start.size(); ++row)
    if (start[row + 1] - start[row] > fewIntervals)
      std::sort(intervals.begin() + static_cast<std::ptrdiff_t>(start[row]),
        intervals.begin() + static_cast<std::ptrdiff_t>(start[row + 1]),
        byStart);
  std::vector<std::uint32_t> label(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const std::size_t row = rowOf(points[i][1] - lo[1], points[i][2] - lo[2]);
    const std::int64_t x = points[i][0] - lo[0];
    const Interval* first = intervals.data() + start[row];
    const Interval* last = intervals.data() + start[row + 1];
    if (static_cast<std::size_t>(last - first) > fewIntervals)
    {
      const Interval* after = std::upper_bound(
        first, last, x, [](std::int64_t value, const Interval& v) { return value < v.lo; });
      first = after == first ? after : after - 1; // none starts at or before x: no interval
      last = after;
    }
    for (const Interval* at = first; at != last; ++at)
      if (x >= at->lo && x < at->hi)
      {
        label[i] = at->label;
        break;
      }
  }
  return label;
}

/// Components of a set of lattice points (CUDB, connected through faces, edges or corners when
/// `vertex`), as runs in the order of the set's. Only the box of the points is voxelised: a level
/// deep inside a large grid pays for its own points, not for the grid. `plane`: the grid is one
/// slice (2D components); a 3D grid keeps 3D extraction even when the points lie in one slice.
std::vector<PointRuns> componentsOf(PointRuns points, bool plane, bool vertex)
{
  if (points.empty())
    return {};
  LatticePoint lo{ points.runs[0].lo, points.runs[0].y, points.runs[0].z }, hi = lo;
  for (const Run& r : points.runs)
  {
    lo = { std::min(lo[0], r.lo), std::min(lo[1], r.y), std::min(lo[2], r.z) };
    hi = { std::max(hi[0], r.hi), std::max(hi[1], r.y), std::max(hi[2], r.z) };
  }
  const Dims d{ static_cast<std::int32_t>(hi[0] - lo[0] + 1),
    static_cast<std::int32_t>(hi[1] - lo[1] + 1),
    static_cast<std::int32_t>(hi[2] - lo[2] + 1) };
  BitVolume set(d[0], d[1], d[2]);
  for (const Run& r : points.runs)
  {
    Word* row =
      set.row(static_cast<std::int32_t>(r.y - lo[1]), static_cast<std::int32_t>(r.z - lo[2]));
    const std::int64_t first = r.lo - lo[0], last = r.hi - lo[0];
    for (std::int64_t w = first >> 6; w <= last >> 6; ++w)
    {
      Word word = ~Word(0);
      if (w == first >> 6)
        word &= ~Word(0) << (first & 63);
      if (w == last >> 6 && (last & 63) != 63)
        word &= (Word(1) << ((last & 63) + 1)) - 1;
      row[w] |= word;
    }
  }
  CUDB cudb;
  Components comps;
  buildCUDBComponents(plane ? extractEVM2D(set) : extractEVM(set),
    vertex ? Connectivity::Vertex : Connectivity::Face,
    Execution(),
    cudb,
    comps);
  if (comps.count == 1)
  {
    // One group (most levels' groups): no labels needed, nor a copy.
    std::vector<PointRuns> one(1);
    one[0] = std::move(points);
    return one;
  }
  // The points of a run are face-neighbours in a row, so one component holds them all: each
  // run's label is its first point's. That label from the boxes' rows instead of painting the
  // labels into a grid of the points' box (the top levels' groups of background points span
  // most of the grid: 64 MB of labels on the full aneurism, each level again): from a table of
  // each row's intervals when the box has few rows against the runs (labelsByRowIntervals),
  // else found among the runs in row order, a key per run (labelsByRows; keys of 64 bits hold
  // extents below 2^21, wider boxes take 128).
  std::vector<LatticePoint> starts;
  starts.reserve(points.runs.size());
  for (const Run& r : points.runs)
    starts.push_back({ r.lo, r.y, r.z });
  const std::int64_t rows = std::int64_t(d[1]) * d[2];
  const std::vector<std::uint32_t> label =
    rows <= std::max<std::int64_t>(1 << 20, 4 * static_cast<std::int64_t>(starts.size()))
    ? labelsByRowIntervals(starts, lo, d, cudb, comps)
    : std::max({ d[0], d[1], d[2] }) < (1 << 21)
    ? labelsByRows<std::uint64_t>(starts, lo, cudb, comps, 21)
    : labelsByRows<unsigned __int128>(starts, lo, cudb, comps, 32);
  std::vector<std::size_t> sizes(comps.count, 0);
  for (std::uint32_t l : label)
    ++sizes[l - 1];
  std::vector<PointRuns> groups(comps.count);
  for (std::uint32_t g = 0; g < comps.count; ++g)
    groups[g].runs.reserve(sizes[g]);
  for (std::size_t i = 0; i < points.runs.size(); ++i)
  {
    const Run& r = points.runs[i];
    groups[label[i] - 1].push(r.lo, r.hi, r.y, r.z);
  }
  return groups;
}

/// componentsOf for a list of points, as lists.
std::vector<std::vector<LatticePoint>> componentsOf(const std::vector<LatticePoint>& points,
  bool plane,
  bool vertex)
{
  std::vector<std::vector<LatticePoint>> out;
  for (const PointRuns& c : componentsOf(PointRuns::of(points), plane, vertex))
    out.push_back(c.points());
  return out;
}

/// Whether the hull's edges each have their two faces (a solid with its incidences) and its
/// normals are small enough for mayBeMinkowskiFace's products in 128 bits.
bool gaussArcsKnown(const CellList& c)
{
  if (c.dimension != 3 || c.edgeFaces.size() != c.edges.size())
    return false;
  for (const auto& ef : c.edgeFaces)
    if (ef[0] >= c.planes.size() || ef[1] >= c.planes.size())
      return false;
  for (const auto& plane : c.planes)
    for (std::int64_t n : plane.normal)
      if (n <= -(std::int64_t(1) << 30) || n >= (std::int64_t(1) << 30))
        return false;
  return true;
}

__int128 dot128(const std::array<__int128, 3>& u, const LatticePoint& v)
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

std::array<__int128, 3> cross128(const LatticePoint& u, const LatticePoint& v)
{
  return { __int128(u[1]) * v[2] - __int128(u[2]) * v[1],
    __int128(u[2]) * v[0] - __int128(u[0]) * v[2],
    __int128(u[0]) * v[1] - __int128(u[1]) * v[0] };
}

/// Whether an edge of A (faces of outward normals a1, a2) and one of B (b1, b2) may span a face
/// of the Minkowski difference A - B: the arc a1 a2 of A's Gauss map and the arc of -b1 -b2
/// cross (the test of Gregorius, "The Separating Axis Test between Convex Polyhedra", 2013).
/// Only such pairs give a separating axis that the face normals do not: a face of A - B is a
/// face of A, of -B, or spanned by two edges whose arcs cross inside both. Exact (integer signs),
/// and conservative: a pair whose arcs touch or lie on one great circle (a sign 0) is kept.
bool mayBeMinkowskiFace(const LatticePoint& a1,
  const LatticePoint& a2,
  const LatticePoint& b1,
  const LatticePoint& b2)
{
  const LatticePoint c{ -b1[0], -b1[1], -b1[2] }, d{ -b2[0], -b2[1], -b2[2] };
  const std::array<__int128, 3> bxa = cross128(a2, a1), dxc = cross128(d, c);
  const int cba = signOf(dot128(bxa, c)), dba = signOf(dot128(bxa, d)),
            adc = signOf(dot128(dxc, a1)), bdc = signOf(dot128(dxc, a2));
  if (cba == 0 || dba == 0 || adc == 0 || bdc == 0)
    return true;
  return cba * dba < 0 && adc * bdc < 0 && cba * bdc > 0;
}

} // namespace

bool hullsIntersect(const CellList& a, const CellList& b)
{
  // A corner of one inside the other answers first, since meeting hulls mostly overlap so.
  auto contains = [](const CellList& h, const CellList& o)
  {
    return std::any_of(o.vertices.begin(),
      o.vertices.end(),
      [&](const LatticePoint& p) { return hullContains(h, p); });
  };
  if (a.dimension == 3 && b.dimension == 3 && (contains(a, b) || contains(b, a)))
    return true;
  // The projections in 64 bits when |n_k| * |p_k| summed stays below 2^62 (every hull of a grid
  // of a few thousand voxels a side), else in 128.
  std::int64_t reach = 0;
  for (const auto* h : { &a, &b })
    for (const auto& p : h->vertices)
      for (std::int64_t c : p)
        reach = std::max(reach, std::abs(c));
  const std::int64_t smallNormal = (std::int64_t(1) << 62) / (3 * std::max<std::int64_t>(reach, 1));
  // Whether the projections of A and B on n are apart; B's corners stop the scan as soon as
  // their range overlaps A's (most axes tried do not separate).
  auto separatesIn = [&](const LatticePoint& n, auto zero)
  {
    using T = decltype(zero);
    const auto along = [&](const LatticePoint& p)
    { return T(n[0]) * p[0] + T(n[1]) * p[1] + T(n[2]) * p[2]; };
    T aLo = along(a.vertices[0]), aHi = aLo;
    for (const auto& p : a.vertices)
    {
      aLo = std::min(aLo, along(p));
      aHi = std::max(aHi, along(p));
    }
    T bLo = along(b.vertices[0]), bHi = bLo;
    for (const auto& p : b.vertices)
    {
      bLo = std::min(bLo, along(p));
      bHi = std::max(bHi, along(p));
      if (bLo <= aHi && aLo <= bHi)
        return false;
    }
    return aHi < bLo || bHi < aLo;
  };
  auto separates = [&](const LatticePoint& n)
  {
    if (n == LatticePoint{ 0, 0, 0 })
      return false;
    if (std::abs(n[0]) < smallNormal && std::abs(n[1]) < smallNormal &&
      std::abs(n[2]) < smallNormal)
      return separatesIn(n, std::int64_t(0));
    return separatesIn(n, __int128(0));
  };
  for (const auto& p : a.planes)
    if (separates(p.normal))
      return false;
  for (const auto& p : b.planes)
    if (separates(p.normal))
      return false;
  const bool arcs = gaussArcsKnown(a) && gaussArcsKnown(b);
  for (std::size_t i = 0; i < a.edges.size(); ++i)
    for (std::size_t j = 0; j < b.edges.size(); ++j)
    {
      const auto &ea = a.edges[i], &eb = b.edges[j];
      if (arcs &&
        !mayBeMinkowskiFace(a.planes[a.edgeFaces[i][0]].normal,
          a.planes[a.edgeFaces[i][1]].normal,
          b.planes[b.edgeFaces[j][0]].normal,
          b.planes[b.edgeFaces[j][1]].normal))
        continue;
      if (separates(cross(
            sub(a.vertices[ea[1]], a.vertices[ea[0]]), sub(b.vertices[eb[1]], b.vertices[eb[0]]))))
        return false;
    }
  return true;
}

namespace
{

/// A hull with its bounding box: hulls whose boxes miss each other are apart without the
/// separating axis test, which is what keeps the pairwise merging of groups cheap.
struct BoxedHull
{
  CellList hull;
  std::array<std::int64_t, 6> box{ 0, -1, 0, -1, 0, -1 };

  BoxedHull() = default;
  explicit BoxedHull(CellList h)
    : hull(std::move(h))
  {
    if (this->hull.dimension >= 0)
      this->box = boundsOf(this->hull);
  }
};

bool hullsMeet(const BoxedHull& a, const BoxedHull& b)
{
  for (int k = 0; k < 3; ++k)
    if (a.box[2 * k + 1] < b.box[2 * k] || b.box[2 * k + 1] < a.box[2 * k])
      return false;
  return hullsIntersect(a.hull, b.hull);
}

/// Whether p lies on a face plane of the (solid) hull.
bool onSurface(const CellList& c, const LatticePoint& p)
{
  return std::any_of(c.planes.begin(),
    c.planes.end(),
    [&](const FacePlane& plane) { return plane.evaluate(p) == 0; });
}

/// strictlyInside and onSurface of one hull for many points, answered from the x ranges of
/// their rows (RowScan), the last row kept: the points of a group come row by row, and testing
/// each of them against every plane of C and of its parent was a tenth of the time on large
/// objects. A point in the closed range but not in the open one lies on a plane (each plane
/// keeps it inside, one not strictly); only points outside the closed range are tested plane by
/// plane for lying on one.
class RowSides
{
public:
  explicit RowSides(const CellList& c)
    : Hull(c)
    , Closed(c, false)
    , Open(c, true)
  {
  }

  bool strictlyInside(const LatticePoint& p)
  {
    this->row(p);
    return this->OpenRow && p[0] >= this->OpenLo && p[0] <= this->OpenHi;
  }

  /// The points [lo, hi] of the run strictly inside (one range: the open interior is convex);
  /// false when none is.
  bool strictRange(const Run& r, std::int64_t& lo, std::int64_t& hi)
  {
    this->row({ r.lo, r.y, r.z });
    lo = std::max(r.lo, this->OpenLo);
    hi = std::min(r.hi, this->OpenHi);
    return this->OpenRow && lo <= hi;
  }

  bool onSurface(const LatticePoint& p)
  {
    this->row(p);
    if (!this->ClosedRow || p[0] < this->ClosedLo || p[0] > this->ClosedHi)
      return vbr::onSurface(this->Hull, p);
    return !(this->OpenRow && p[0] >= this->OpenLo && p[0] <= this->OpenHi);
  }

private:
  void row(const LatticePoint& p)
  {
    if (this->Known && p[1] == this->Y && p[2] == this->Z)
      return;
    if (!this->Known || p[2] != this->Z)
    {
      this->Closed.setSlice(p[2]);
      this->Open.setSlice(p[2]);
    }
    this->Known = true;
    this->Y = p[1];
    this->Z = p[2];
    this->ClosedRow = this->Closed.range(this->Y, this->ClosedLo, this->ClosedHi);
    this->OpenRow = this->Open.range(this->Y, this->OpenLo, this->OpenHi);
  }

  const CellList& Hull;
  RowScan Closed, Open;
  bool Known = false, ClosedRow = false, OpenRow = false;
  std::int64_t Y = 0, Z = 0, ClosedLo = 0, ClosedHi = 0, OpenLo = 0, OpenHi = 0;
};

/// A group of points of the other class: its points, the hull of the points (any dimension)
/// and a solid hull holding them (solidHull; dimension below 3 when no thickening fits). The
/// hull of two merged groups is the hull of their hulls' corners, so a merge costs the
/// corners, not the points.
struct PointGroup
{
  PointRuns points;
  CellList shape;
  BoxedHull solid;
};

/// The solid hull of the group (its shape when that is solid, else its points thickened inside
/// C, in C's open interior when `strict`).
BoxedHull solidOf(const PointGroup& g, const CellList& c, bool strict, CoplanarFaces coplanar)
{
  if (g.shape.dimension == 3)
    return BoxedHull(g.shape);
  CellList out;
  solidHull(g.points.points(), c, strict, coplanar, out);
  return BoxedHull(std::move(out));
}

/// The first and last point of every row (along x) of the points: every other point lies
/// between two of them, so they span the same hull, and a solid group of n points gives the
/// hull about n^(2/3) points instead of n. Points in row order (as listed) are read in place.
std::vector<LatticePoint> rowEnds(const std::vector<LatticePoint>& listed)
{
  auto zyx = [](const LatticePoint& a, const LatticePoint& b)
  { return std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]); };
  std::vector<LatticePoint> sorted;
  const bool inOrder = std::is_sorted(listed.begin(), listed.end(), zyx);
  if (!inOrder)
  {
    sorted = listed;
    std::sort(sorted.begin(), sorted.end(), zyx);
  }
  const std::vector<LatticePoint>& points = inOrder ? listed : sorted;
  std::vector<LatticePoint> ends;
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    const bool first =
      k == 0 || points[k - 1][1] != points[k][1] || points[k - 1][2] != points[k][2];
    const bool last = k + 1 == points.size() || points[k + 1][1] != points[k][1] ||
      points[k + 1][2] != points[k][2];
    if (first || last)
      ends.push_back(points[k]);
  }
  return ends;
}

/// rowEnds of points given as runs: a row's first point is its first run's, its last the last
/// run's (the runs of a set are disjoint, so runs in row order list the points in row order).
std::vector<LatticePoint> rowEnds(const PointRuns& listed)
{
  auto zyx = [](const Run& a, const Run& b)
  { return std::tie(a.z, a.y, a.lo) < std::tie(b.z, b.y, b.lo); };
  std::vector<Run> sorted;
  const bool inOrder = std::is_sorted(listed.runs.begin(), listed.runs.end(), zyx);
  if (!inOrder)
  {
    sorted = listed.runs;
    std::sort(sorted.begin(), sorted.end(), zyx);
  }
  const std::vector<Run>& runs = inOrder ? listed.runs : sorted;
  std::vector<LatticePoint> ends;
  for (std::size_t k = 0; k < runs.size();)
  {
    std::size_t last = k;
    while (last + 1 < runs.size() && runs[last + 1].y == runs[k].y && runs[last + 1].z == runs[k].z)
      ++last;
    ends.push_back({ runs[k].lo, runs[k].y, runs[k].z });
    if (runs[last].hi != runs[k].lo)
      ends.push_back({ runs[last].hi, runs[k].y, runs[k].z });
    k = last + 1;
  }
  return ends;
}

/// Of points in row order (rowEnds), the corners of each slice's polygon (x, y at one z;
/// Andrew's monotone chain over the points in (y, x) order, corners where it turns strictly):
/// a point that is no corner of its slice's polygon lies between other points of the set, so
/// it is no vertex of their hull either, and the hull of the corners is the same polytope.
std::vector<LatticePoint> sliceCorners(const std::vector<LatticePoint>& ends)
{
  // A slice's points come in (y, x) order without repeats, as monotoneChain asks (its
  // orientation, clockwise in (x, y), does not matter: only the set of corners is used).
  const auto turn = [](const LatticePoint& o, const LatticePoint& a, const LatticePoint& b)
  { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); };
  std::vector<LatticePoint> corners, slice;
  for (std::size_t k = 0; k < ends.size();)
  {
    std::size_t end = k;
    while (end < ends.size() && ends[end][2] == ends[k][2])
      ++end;
    slice.assign(ends.begin() + k, ends.begin() + end);
    const std::vector<LatticePoint> chain = monotoneChain(slice, turn);
    corners.insert(corners.end(), chain.begin(), chain.end());
    k = end;
  }
  return corners;
}

/// The hull of the points (see makeGroup).
CellList shapeOf(const PointRuns& points, CoplanarFaces coplanar)
{
  const std::vector<LatticePoint> ends = rowEnds(points);
  CellList shape = convexHull(sliceCorners(ends), coplanar);
  if (shape.dimension < 3)
    shape = convexHull(ends, coplanar);
  return shape;
}

/// A group with its hulls. The shape is the hull of the slices' corners (sliceCorners: the same
/// polytope, and a solid hull's cell list depends only on its polytope, faces in the order of
/// their planes, each polygon from its least corner), which spares the hull most row ends of a
/// large group (most of making a group's hull on the aneurism); a flat one is made from the
/// row ends as before, since a flat hull's polygon is not given in such an order.
PointGroup makeGroup(PointRuns points, const CellList& c, bool strict, CoplanarFaces coplanar)
{
  PointGroup g;
  g.points = std::move(points);
  g.shape = shapeOf(g.points, coplanar);
  g.solid = solidOf(g, c, strict, coplanar);
  return g;
}

/// Whether every corner of the groups' shapes lies in the closed solid shape of `into`.
bool shapesWithin(const PointGroup& into, const std::vector<PointGroup*>& from)
{
  if (into.shape.dimension != 3)
    return false;
  for (const PointGroup* g : from)
    for (const auto& p : g->shape.vertices)
      if (!hullContains(into.shape, p))
        return false;
  return true;
}

/// Moves the points of the groups `from` into `into` (the largest list kept, so a growing group
/// is not copied again and again) and finds the hulls of the union from the shapes' corners;
/// true when they are those of `into` already. When those corners all lie in the solid shape of
/// `into` its hulls stay as they are: a merged hull (convexHull merges coplanar faces) depends only
/// on the polytope, faces in the order of their planes and each polygon from its least corner, so
/// computing it again gives the same cell list. Most merges of the groups kept apart are of that
/// kind (8,204 of 9,268 on the full aneurism): a small group whose region met the region of a large
/// one that already holds it.
bool mergeGroups(PointGroup& into,
  const std::vector<PointGroup*>& from,
  const CellList& c,
  bool strict,
  CoplanarFaces coplanar)
{
  const bool within = shapesWithin(into, from);
  std::vector<LatticePoint> corners;
  if (!within)
    corners = into.shape.vertices;
  for (PointGroup* g : from)
  {
    if (into.points.count < g->points.count)
      std::swap(into.points, g->points);
    into.points.append(g->points);
    if (!within)
      corners.insert(corners.end(), g->shape.vertices.begin(), g->shape.vertices.end());
    *g = PointGroup();
  }
  if (within)
    return true; // a solid shape is its own solid hull (solidOf), unchanged too
  into.shape = convexHull(corners, coplanar);
  into.solid = solidOf(into, c, strict, coplanar);
  return false;
}

/// Merges groups while two of them meet, until they are pairwise apart: a group takes every
/// group it meets at once (they all end up with it: a hull holding it meets them), and having
/// grown is tested again. Two groups found apart stay apart until one of them grows, so no
/// pair is tested twice at the same size. The survivors keep their order.
template<typename Meet>
void mergeWhileMeeting(std::vector<PointGroup>& groups,
  const CellList& c,
  bool strict,
  CoplanarFaces coplanar,
  Meet&& meet)
{
  std::vector<bool> alive(groups.size(), true);
  std::vector<std::size_t> todo(groups.size());
  std::iota(todo.rbegin(), todo.rend(), std::size_t(0));
  while (!todo.empty())
  {
    const std::size_t i = todo.back();
    todo.pop_back();
    if (!alive[i])
      continue;
    std::vector<PointGroup*> meeting;
    for (std::size_t j = 0; j < groups.size(); ++j)
      if (j != i && alive[j] && meet(groups[i], groups[j]))
      {
        meeting.push_back(&groups[j]);
        alive[j] = false;
      }
    if (meeting.empty())
      continue;
    mergeGroups(groups[i], meeting, c, strict, coplanar);
    todo.push_back(i);
  }
  std::vector<PointGroup> kept;
  for (std::size_t i = 0; i < groups.size(); ++i)
    if (alive[i])
      kept.push_back(std::move(groups[i]));
  groups = std::move(kept);
}

/// The groups of points of the other class to press in: the components (face-connected: two
/// groups meeting only along an edge or at a corner stay two, and their hulls apart) in the
/// closed hull that reach its open interior, merged while their hulls meet (a group without a
/// solid hull meets every other), each with its hull.
std::vector<PointGroup> pressingInGroups(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls)
{
  std::vector<PointGroup> groups;
  RowSides sides(c);
  std::optional<RowSides> parentSides;
  if (parent)
    parentSides.emplace(*parent);
  for (auto& g :
    componentsOf(pointsOfClass(c, ctx.objects, !cls, false), ctx.objects.dims()[2] == 1, false))
    if (anyPoint(g,
          [&](const LatticePoint& p)
          { return sides.strictlyInside(p) || (parentSides && parentSides->onSurface(p)); }))
      groups.push_back(makeGroup(std::move(g), c, false, ctx.coplanar));
  mergeWhileMeeting(groups,
    c,
    false,
    ctx.coplanar,
    [](const PointGroup& a, const PointGroup& b)
    {
      return a.solid.hull.dimension < 3 || b.solid.hull.dimension < 3 ||
        hullsMeet(a.solid, b.solid);
    });
  return groups;
}

struct LevelSurface;
LevelSurface solveLevel(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  bool pit,
  int level,
  int& depth);

/// A lattice triangle on a face of C (counter-clockwise about the face's outer normal), with the
/// lattice points of its closed area once enumerated, and its distance from the group pressed in.
struct FaceTriangle
{
  std::array<LatticePoint, 3> corners;
  FacePlane plane;
  std::vector<LatticePoint> points;
  bool enumerated = false;
  __int128 distance = 0;
  /// Reversed, so that a priority queue gives the nearest first.
  bool operator<(const FaceTriangle& o) const { return this->distance > o.distance; }
};

/// The squared distance, scaled by m^2, between the point p / k and the centroid sum / m of a
/// group of m points (it only orders the candidates).
__int128 scaledDistance(const LatticePoint& p,
  std::int64_t k,
  const LatticePoint& sum,
  std::int64_t m)
{
  __int128 d = 0;
  for (int a = 0; a < 3; ++a)
  {
    const __int128 e = __int128(m) * p[a] - __int128(k) * sum[a];
    d += e * e;
  }
  return d;
}

/// The empty lattice triangles on the surface of a solid hull (no lattice point but their
/// corners), nearest to a group of points first: its faces are fanned, and a triangle holding
/// another lattice point is split at the one nearest to the group. In its plane an empty lattice
/// triangle is unimodular (Pick), so a solid pressed in from it meets no other centre of C.
struct EmptyFaceTriangles
{
  std::priority_queue<FaceTriangle> queue;
  LatticePoint sum{ 0, 0, 0 };
  std::int64_t m = 0;

  EmptyFaceTriangles(const CellList& c, const PointRuns& group)
    : m(static_cast<std::int64_t>(group.count))
  {
    // A run's x sum is its length times its middle, (lo + hi) n / 2 (one factor is even).
    for (const Run& r : group.runs)
    {
      const std::int64_t n = r.hi - r.lo + 1;
      this->sum[0] += (r.lo + r.hi) * n / 2;
      this->sum[1] += r.y * n;
      this->sum[2] += r.z * n;
    }
    for (std::size_t f = 0; f < c.faces.size(); ++f)
      for (std::size_t k = 1; k + 1 < c.faces[f].size(); ++k)
        this->push(
          { c.vertices[c.faces[f][0]], c.vertices[c.faces[f][k]], c.vertices[c.faces[f][k + 1]] },
          c.planes[f],
          {},
          false);
  }

  void push(const std::array<LatticePoint, 3>& t,
    const FacePlane& plane,
    std::vector<LatticePoint> points,
    bool enumerated)
  {
    FaceTriangle f{ t, plane, std::move(points), enumerated, 0 };
    const LatticePoint corners{
      t[0][0] + t[1][0] + t[2][0], t[0][1] + t[1][1] + t[2][1], t[0][2] + t[1][2] + t[2][2]
    };
    f.distance = scaledDistance(corners, 3, this->sum, this->m);
    this->queue.push(std::move(f));
  }

  /// The next empty triangle, false when none is left.
  bool next(std::array<LatticePoint, 3>& out);
};

bool EmptyFaceTriangles::next(std::array<LatticePoint, 3>& out)
{
  while (!this->queue.empty())
  {
    FaceTriangle t = this->queue.top();
    this->queue.pop();
    if (!t.enumerated)
      forEachPointOnTriangle(
        t.corners, kUnbounded, [&](const LatticePoint& p) { t.points.push_back(p); });
    if (t.points.size() <= 3)
    {
      out = t.corners;
      return true;
    }
    const LatticePoint* split = nullptr;
    for (const auto& p : t.points)
      if (p != t.corners[0] && p != t.corners[1] && p != t.corners[2] &&
        (!split ||
          scaledDistance(p, 1, this->sum, this->m) < scaledDistance(*split, 1, this->sum, this->m)))
        split = &p;
    for (int e = 0; e < 3; ++e)
    {
      const std::array<LatticePoint, 3> child{ t.corners[e], t.corners[(e + 1) % 3], *split };
      if (planeThrough(child[0], child[1], child[2]).normal == LatticePoint{ 0, 0, 0 })
        continue; // the split point lies on this edge
      std::vector<LatticePoint> inside;
      for (const auto& p : t.points)
        if (onTriangle(child[0], child[1], child[2], t.plane, p))
          inside.push_back(p);
      this->push(child, t.plane, std::move(inside), true);
    }
  }
  return false;
}

/// Whether the open interior of a region holds no centre of class `cls`: such a region is
/// final one level down (nothing in it is pressed in again).
bool holdsNoCentreOf(const CellList& region, const BitVolume& objects, bool cls)
{
  bool none = true;
  forEachPointIn(region,
    true,
    [&](const LatticePoint& p)
    {
      if (none && voxelClass(objects, p) == cls)
        none = false;
    });
  return none;
}

/// Definition PR with an empty triangle: the hull of the group and an empty triangle T on the
/// surface of C whose corners lie in the open interior of the parent (so T keeps off every piece
/// of surface C shares with it), the nearest T whose hull keeps off the other regions and holds
/// no centre of C's class `cls` in its open interior, else the nearest that keeps off the other
/// regions, or when every candidate meets one, the nearest (its group is then merged with that
/// region's group). The hull of the group and T is the hull of the group's corners and T.
///
/// Why a clean hull first: the region's own pressed-in groups need empty triangles of its
/// surface inside C, and its faces away from T are spanned by the group's corners alone. A flat
/// group (a row or a sheet of one layer of a thin plate) with T on the far side of its plane has
/// no such face at all: every face of the hull then has a corner of T on C's surface, and a
/// centre of C's class inside that hull can be pressed in from nowhere. With T on one side of
/// the group's plane the group's polygon is a face of the region, and a thin region has no
/// lattice point inside.
bool pressedRegion(const CellList& c,
  const CellList* parent,
  const PointGroup& group,
  const std::vector<const BoxedHull*>& others,
  const BitVolume& objects,
  bool cls,
  CoplanarFaces coplanar,
  BoxedHull& out)
{
  EmptyFaceTriangles triangles(c, group.points);
  std::array<LatticePoint, 3> t;
  BoxedHull nearest, nearestApart;
  for (int tried = 0; tried < 64 && triangles.next(t);)
  {
    if (parent &&
      !std::all_of(
        t.begin(), t.end(), [&](const LatticePoint& p) { return strictlyInside(*parent, p); }))
      continue;
    ++tried;
    std::vector<LatticePoint> points = group.shape.vertices;
    points.insert(points.end(), t.begin(), t.end());
    BoxedHull region(convexHull(points, coplanar));
    const bool apart = std::none_of(
      others.begin(), others.end(), [&](const BoxedHull* o) { return hullsMeet(region, *o); });
    if (apart && holdsNoCentreOf(region.hull, objects, cls))
    {
      out = std::move(region);
      return true;
    }
    if (apart && nearestApart.hull.dimension < 0)
      nearestApart = std::move(region);
    else if (nearest.hull.dimension < 0)
      nearest = std::move(region);
  }
  if (nearestApart.hull.dimension >= 0)
    out = std::move(nearestApart);
  else if (nearest.hull.dimension >= 0)
    out = std::move(nearest);
  else
    return false;
  return true;
}

/// A group kept apart and its region (dimension -1 until found), pressed in or a cavity;
/// `checked` once the region is known to keep off every other live region.
struct ApartGroup
{
  PointGroup group;
  BoxedHull region;
  bool pressed = false;
  bool alive = true;
  bool checked = false;
  /// Known of an unchecked region that has not changed since: it keeps off the live regions
  /// before index `from`, and off every checked region when `apartFromChecked`.
  std::size_t from = 0;
  bool apartFromChecked = false;
};

/// The regions of the live groups that have none: a cavity where the group's hull thickened in
/// the open interior of C is solid, otherwise pressed in (pressedRegion) away from the
/// obstacles and every region found so far. False when a new region meets an obstacle.
bool findRegions(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  const std::vector<BoxedHull>& obstacles,
  std::vector<ApartGroup>& groups)
{
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < groups.size(); ++i)
    if (groups[i].alive && groups[i].region.hull.dimension < 0)
    {
      todo.push_back(i);
      groups[i].pressed = groups[i].group.solid.hull.dimension < 3;
      if (!groups[i].pressed)
        groups[i].region = groups[i].group.solid;
    }
  for (std::size_t i : todo)
  {
    if (!groups[i].pressed)
      continue;
    std::vector<const BoxedHull*> others;
    for (const auto& o : obstacles)
      others.push_back(&o);
    for (const auto& g : groups)
      if (g.alive && g.region.hull.dimension == 3)
        others.push_back(&g.region);
    if (!pressedRegion(
          c, parent, groups[i].group, others, ctx.objects, cls, ctx.coplanar, groups[i].region))
      throw Unresolved("no empty triangle of the surface to press a group in from");
  }
  return std::none_of(todo.begin(),
    todo.end(),
    [&](std::size_t i)
    {
      return std::any_of(obstacles.begin(),
        obstacles.end(),
        [&](const BoxedHull& o) { return hullsMeet(groups[i].region, o); });
    });
}

/// Merges the groups of the first two regions that meet (into the lower index, whose region is
/// to be found again, so that it can still find a triangle apart from the rest). Regions
/// already checked keep off every other live region, so only the unchecked ones are tested.
///
/// A merge whose hulls stay those of the lower group (mergeGroups) leaves its region as it was
/// (a solid group's region is its solid hull), and what was known of it still holds: tested as
/// the unchecked region i, it keeps off the regions before the one it met; checked before, it
/// keeps off every checked region (of two regions unchanged since checked, the later checked
/// was tested against the other). Those pairs are not tested again; the pair found first, and
/// so every merge, is the same.
bool mergeMeetingRegions(Context& ctx, const CellList& c, std::vector<ApartGroup>& groups)
{
  for (std::size_t i = 0; i < groups.size(); ++i)
  {
    if (!groups[i].alive || groups[i].checked)
      continue;
    for (std::size_t j = groups[i].from; j < groups.size(); ++j)
      if (j != i && groups[j].alive && !(groups[i].apartFromChecked && groups[j].checked) &&
        hullsMeet(groups[i].region, groups[j].region))
      {
        const std::size_t k = std::min(i, j), l = std::max(i, j);
        const bool kept = mergeGroups(groups[k].group, { &groups[l].group }, c, true, ctx.coplanar);
        groups[l].alive = false;
        if (kept && !groups[k].pressed)
        {
          groups[k].from = k == i ? j + 1 : 0;
          groups[k].apartFromChecked = k == i ? groups[k].apartFromChecked : true;
        }
        else
        {
          groups[k].region = BoxedHull();
          for (auto& g : groups)
            g.from = 0; // a region changes: what is known of the pairs with it no longer holds
          groups[k].apartFromChecked = false;
        }
        groups[k].checked = false;
        return true;
      }
    groups[i].checked = true;
  }
  return false;
}

/// The regions of the touching rule (see the header) for the points of the other class in the
/// open interior of C (a hull of class `cls`): their face-connected groups, each with a solid
/// region holding it that meets the surface of C at most in one empty triangle (a cavity: the
/// hull of its thickening in the open interior; or pressed in, pressedRegion). Groups whose
/// regions meet are merged until the regions are apart. False when a region meets an obstacle
/// (a pit of this level).
bool apartRegions(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  const PointRuns& points,
  const std::vector<BoxedHull>& obstacles,
  std::vector<CellList>& regions,
  std::vector<bool>& pressed)
{
  std::vector<ApartGroup> groups;
  for (auto& g : componentsOf(points, ctx.objects.dims()[2] == 1, false))
    groups.push_back({ makeGroup(std::move(g), c, true, ctx.coplanar) });
  do
  {
    if (!findRegions(ctx, c, parent, cls, obstacles, groups))
      return false;
  } while (mergeMeetingRegions(ctx, c, groups));
  regions.clear();
  pressed.clear();
  for (auto& g : groups)
    if (g.alive)
    {
      regions.push_back(std::move(g.region.hull));
      pressed.push_back(g.pressed);
    }
  return true;
}

/// Whether the faces of a solid hull fanned (triangulateHull) make an embedded surface, in
/// exact integer arithmetic: every face strictly convex, counter-clockwise about its outward
/// normal (each corner strictly left of every edge it is not on) and no corner beyond a face's
/// plane. Fan triangles of one strictly convex face then meet only in their shared corner and
/// edges, and those of two faces only where the faces meet, in corners and edges of both.
/// Checking that costs far less than CGAL's self-intersection test of the fan, which every
/// level ran on its hull and on every leaf hull pressed into it.
bool fanIsEmbedded(const CellList& c)
{
  if (c.dimension != 3)
    return false;
  for (std::size_t f = 0; f < c.faces.size(); ++f)
  {
    const auto& face = c.faces[f];
    const FacePlane& plane = c.planes[f];
    for (std::size_t k = 0; k < face.size(); ++k)
    {
      const LatticePoint& a = c.vertices[face[k]];
      const LatticePoint edge = sub(c.vertices[face[(k + 1) % face.size()]], a);
      if (plane.evaluate(a) != 0)
        return false;
      for (std::size_t j = 0; j < face.size(); ++j)
        if (j != k && j != (k + 1) % face.size() &&
          dot(plane.normal, cross(edge, sub(c.vertices[face[j]], a))) <= 0)
          return false;
    }
  }
  return std::all_of(c.vertices.begin(),
    c.vertices.end(),
    [&](const LatticePoint& p)
    {
      return std::all_of(c.planes.begin(),
        c.planes.end(),
        [&](const FacePlane& plane) { return plane.evaluate(p) <= 0; });
    });
}

/// A level's surface while its pits and regions are cut out of it, with the boxes of the
/// triangles made since it was last known embedded (none: test it all; empty: embedded).
/// Levels of large objects cut thousands of pits, mostly small hulls out of small hulls, and
/// testing both whole operands of every cut for self-intersections cost about a third of the
/// cut; the test of a known part is skipped (latticeDifference's aChangedIn and bChangedIn).
struct LevelSurface
{
  LatticeMesh mesh;
  std::optional<std::vector<LatticeBox>> changed;

  explicit LevelSurface(const CellList& c)
    : mesh(triangulateHull(c))
  {
    if (fanIsEmbedded(c))
      this->changed.emplace();
  }

  /// The surface minus g when the exact difference is a closed 2-manifold with lattice corners.
  bool subtract(const LevelSurface& g)
  {
    LatticeMesh difference;
    if (!latticeDifference(this->mesh,
          g.mesh,
          difference,
          Operands::Check,
          this->changed ? &*this->changed : nullptr,
          g.changed ? &*g.changed : nullptr))
      return false;
    // The difference tested the surface embedded: what is new is the difference's own.
    this->changed = newTriangleBoxes(this->mesh, difference);
    this->mesh = std::move(difference);
    return true;
  }

  /// Adds a cavity's surface inside out; its triangles are new.
  void addCavity(const LatticeMesh& cavity)
  {
    this->mesh.append(cavity, true);
    if (this->changed)
      for (const auto& box : newTriangleBoxes(LatticeMesh(), cavity))
        this->changed->push_back(box);
  }
};

/// The regions of apartRegions solved one level down: the pressed ones subtracted from C (each
/// meets its surface in its triangle only, so the difference is a 2-manifold), the cavities
/// added inside out.
void solveApart(Context& ctx,
  const CellList& c,
  bool cls,
  int level,
  const std::vector<CellList>& regions,
  const std::vector<bool>& pressed,
  LevelSurface& out,
  int& depth)
{
  std::vector<LatticeMesh> cavities;
  for (std::size_t i = 0; i < regions.size(); ++i)
  {
    ++ctx.keptApart;
    int below = 0;
    LevelSurface g = solveLevel(ctx, regions[i], &c, !cls, false, level + 1, below);
    depth = std::max(depth, below + 1);
    if (!pressed[i])
      cavities.push_back(std::move(g.mesh));
    else if (!out.subtract(g))
      throw Unresolved("a region pressed in from an empty triangle did not give a 2-manifold");
  }
  for (const auto& g : cavities)
    out.addCavity(g);
}

/// Presses the solved hull G of a group in as a pit, C - G, when the difference is a closed
/// 2-manifold with lattice corners and every level below resolves.
bool pressInPit(Context& ctx,
  const CellList& c,
  const CellList& hull,
  bool cls,
  int level,
  LevelSurface& out,
  int& depth)
{
  const int keptApart = ctx.keptApart;
  try
  {
    int below = 0;
    const LevelSurface g = solveLevel(ctx, hull, &c, !cls, true, level + 1, below);
    if (out.subtract(g))
    {
      depth = std::max(depth, below + 1);
      return true;
    }
  }
  catch (const Unresolved&)
  {
  }
  ctx.keptApart = keptApart;
  return false;
}

/// The pits of one level: the groups of pressingInGroups pressed in where pressInPit succeeds
/// (their hulls returned as obstacles), the points of the others in the open interior of C
/// returned in `apart`. A group holding a point on the surface C shares with its parent (`pit`)
/// can only stay on H through a pit: when that fails, the level throws and the parent keeps C
/// apart instead.
void pressInPits(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  bool pit,
  int level,
  LevelSurface& out,
  PointRuns& apart,
  std::vector<BoxedHull>& pits,
  int& depth)
{
  RowSides sides(c);
  std::optional<RowSides> parentSides;
  if (pit)
    parentSides.emplace(*parent);
  for (PointGroup& g : pressingInGroups(ctx, c, pit ? parent : nullptr, cls))
  {
    // The difference is decided beforehand only for a group that is its own solid hull: a
    // thickened one's corners are points of the other class, which a pit of the next level
    // can take off the surface again (and with them an edge or corner that made C - G fail).
    if (g.solid.hull.dimension == 3 && missesACorner(g.solid.hull, c) &&
      (g.shape.dimension < 3 || convexDifferenceIsManifold(c, g.solid.hull)) &&
      pressInPit(ctx, c, g.solid.hull, cls, level, out, depth))
    {
      pits.push_back(std::move(g.solid));
      continue;
    }
    for (const Run& r : g.points.runs)
    {
      std::int64_t lo = 0, hi = -1;
      const bool inside = sides.strictRange(r, lo, hi);
      if (inside)
        apart.push(lo, hi, r.y, r.z);
      for (std::int64_t x = r.lo; pit && x <= r.hi; ++x)
      {
        if (inside && x == lo)
          x = hi; // the points strictly inside C stay (apart), the others must be off the floor
        else if (parentSides->onSurface({ x, r.y, r.z }))
          throw Unresolved("a centre on a shared surface can only be kept by a pit");
      }
    }
  }
}

/// One level of Algorithm 1 (see the header): C minus the pits, the groups that fail as pits
/// kept apart (cavities and regions pressed in from empty triangles). `pit`: C touches the
/// surface of its parent in pieces of faces. `depth` receives the number of levels below.
LevelSurface solveLevel(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  bool pit,
  int level,
  int& depth)
{
  if (ctx.exec.stopRequested())
    throw std::runtime_error("aborted");
  recordPlanes(ctx, c, level);
  depth = 0;
  LevelSurface out(c);
  PointRuns apart;
  std::vector<BoxedHull> pits;
  if (ctx.pits)
    pressInPits(ctx, c, parent, cls, pit, level, out, apart, pits, depth);
  else
    apart = pointsOfClass(c, ctx.objects, !cls, true);
  if (apart.empty())
    return out;
  std::vector<CellList> regions;
  std::vector<bool> pressed;
  if (!apartRegions(ctx, c, parent, cls, apart, pits, regions, pressed))
  {
    // A region kept apart meets a pit: the whole level kept apart, unless C must keep pits.
    if (pit)
      throw Unresolved("a group kept apart meets a pit");
    out = LevelSurface(c);
    depth = 0;
    apartRegions(
      ctx, c, parent, cls, pointsOfClass(c, ctx.objects, !cls, true), {}, regions, pressed);
  }
  solveApart(ctx, c, cls, level, regions, pressed, out, depth);
  return out;
}

/// Whether a neighbour (26) of p lies outside the closed (solid) hull (only then can a corner
/// of the voxel of p lie outside or on the hull), along a row: the x for which none does are
/// the interval [lo, hi] returned (empty when lo > hi). Over the offsets d in {-1, 0, 1}^3 the
/// largest n.d is |n|_1 (d the signs of n), so the neighbours all lie inside exactly when every
/// plane keeps n.p - d + |n|_1 <= 0: one bound on x per plane and row instead of a pass over
/// the planes per point.
std::array<__int128, 2> farFromHullBoundary(const CellList& c, std::int64_t y, std::int64_t z)
{
  // The floor of a / b for b != 0 in 128 bits (a ceiling is minus the floor of -a / b).
  const auto floorOf = [](__int128 a, __int128 b)
  {
    __int128 q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
  };
  std::array<__int128, 2> range{ std::numeric_limits<std::int64_t>::min(),
    std::numeric_limits<std::int64_t>::max() };
  if (c.dimension < 3)
    return { 1, 0 };
  for (const FacePlane& plane : c.planes)
  {
    const __int128 reach =
      std::abs(plane.normal[0]) + std::abs(plane.normal[1]) + std::abs(plane.normal[2]);
    // n.p - d + reach <= 0  <=>  nx x <= bound
    const __int128 bound = __int128(plane.offset) - reach - __int128(plane.normal[1]) * y -
      __int128(plane.normal[2]) * z;
    const __int128 nx = plane.normal[0];
    if (nx == 0)
    {
      if (bound < 0)
        return { 1, 0 };
    }
    else if (nx > 0)
      range[1] = std::min(range[1], floorOf(bound, nx));
    else
      range[0] = std::max(range[0], -floorOf(bound, -nx)); // ceil(bound / nx), nx < 0
  }
  return range;
}

/// Number of edge-connected sets among the marked faces of the hull.
int connectedFaceSets(const CellList& hull, const std::vector<bool>& marked)
{
  UnionFind sets(hull.faces.size());
  for (const auto& ef : hull.edgeFaces)
    if (ef[0] != Index(-1) && ef[1] != Index(-1) && marked[ef[0]] && marked[ef[1]])
      sets.unite(ef[0], ef[1]);
  int count = 0;
  for (std::size_t f = 0; f < marked.size(); ++f)
    count += marked[f] && sets.find(static_cast<std::uint32_t>(f)) == f;
  return count;
}

/// Section 4.1: the background components in the closed hull (CUDB, face-connected), each a
/// cavity, concavity or tunnel by the faces seen from (or coplanar with) its voxels' corners.
void classifyBackgroundComponents(const BitVolume& objects, const CellList& hull, ModifiedHull& r)
{
  const std::vector<LatticePoint> background = pointsOfClass(hull, objects, false, false).points();
  if (background.empty())
  {
    return;
  }
  const Dims d = objects.dims();
  BitVolume inside(d[0], d[1], d[2]);
  for (const auto& p : background)
  {
    inside.set(static_cast<std::int32_t>(p[0]),
      static_cast<std::int32_t>(p[1]),
      static_cast<std::int32_t>(p[2]));
  }
  const CUDB cudb = buildCUDB(d[2] == 1 ? extractEVM2D(inside) : extractEVM(inside));
  const Components comps = labelComponents(cudb, Connectivity::Face);
  std::vector<std::int32_t> value(comps.boxLabel.begin(), comps.boxLabel.end());
  std::vector<std::int32_t> labels(inside.voxelCount(), 0);
  paintBoxes(cudb.boxes, value, { 0, 0, 0 }, { 0, 1, 2 }, d, labels.data());
  std::vector<std::vector<bool>> seen(comps.count + 1, std::vector<bool>(hull.faces.size()));
  // A face is seen from (or coplanar with) a corner 2p + s (s in {-1, 1}^3, doubled
  // coordinates) of the voxel of a background point p near the hull's boundary when
  // n.(2p + s) - 2d >= 0; the largest n.s is |n|_1, so when 2(n.p - d) + |n|_1 >= 0. Along a
  // row that is linear in x, so over a component's near points of the row it holds for one of
  // them exactly when it holds for the one of least or greatest x (by the sign of n_x): each
  // row costs one test per face and component there instead of one per face and point. The
  // background points come row by row (pointsOfClass).
  struct Span
  {
    std::int32_t label;
    std::int64_t lo, hi;
  };
  std::vector<Span> spans;
  for (std::size_t i = 0; i < background.size();)
  {
    const std::int64_t y = background[i][1], z = background[i][2];
    const std::array<__int128, 2> far = farFromHullBoundary(hull, y, z);
    spans.clear();
    for (; i < background.size() && background[i][1] == y && background[i][2] == z; ++i)
    {
      const LatticePoint& p = background[i];
      if (far[0] <= p[0] && p[0] <= far[1])
        continue; // no neighbour outside the hull
      const std::int32_t label = labels[(p[2] * d[1] + p[1]) * d[0] + p[0]];
      auto span =
        std::find_if(spans.begin(), spans.end(), [&](const Span& s) { return s.label == label; });
      if (span == spans.end())
        spans.push_back({ label, p[0], p[0] });
      else
      {
        span->lo = std::min(span->lo, p[0]);
        span->hi = std::max(span->hi, p[0]);
      }
    }
    if (spans.empty())
      continue;
    for (std::size_t f = 0; f < hull.faces.size(); ++f)
    {
      const FacePlane& plane = hull.planes[f];
      const __int128 reach =
        std::abs(plane.normal[0]) + std::abs(plane.normal[1]) + std::abs(plane.normal[2]);
      const __int128 rest = 2 *
          (__int128(plane.normal[1]) * y + __int128(plane.normal[2]) * z - __int128(plane.offset)) +
        reach;
      for (const Span& span : spans)
      {
        const std::int64_t x = plane.normal[0] > 0 ? span.hi : span.lo;
        if (2 * __int128(plane.normal[0]) * x + rest >= 0)
          seen[span.label][f] = true;
      }
    }
  }
  for (std::uint32_t l = 1; l <= comps.count; ++l)
  {
    const int sets = connectedFaceSets(hull, seen[l]);
    (sets == 0 ? r.cavities : sets == 1 ? r.concavities : r.tunnels)++;
  }
}

/// Coplanar edge-connected triangles of H as its faces, with their boundary loops and levels.
/// The triangle on each directed edge (a, b) of a closed mesh, by key(a, b).
std::uint64_t edgeKey(Index a, Index b)
{
  return (std::uint64_t(a) << 32) | b;
}

/// The classes of edge-adjacent triangles on the same plane: the faces of the mesh.
UnionFind coplanarTriangles(const LatticeMesh& m,
  const std::vector<FacePlane>& planes,
  const std::unordered_map<std::uint64_t, Index>& owner)
{
  UnionFind faces(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
    {
      const auto& tri = m.triangles[t];
      auto it = owner.find(edgeKey(tri[(k + 1) % 3], tri[k]));
      if (it != owner.end() && planes[it->second] == planes[t])
        faces.unite(static_cast<std::uint32_t>(t), it->second);
    }
  return faces;
}

/// The boundary loops of a face from its boundary edges (next: a -> b), each once.
void traceLoops(std::multimap<Index, Index>& next, ModifiedFace& face)
{
  while (!next.empty())
  {
    std::vector<Index> loop{ next.begin()->first };
    Index at = next.begin()->second;
    next.erase(next.begin());
    while (at != loop.front())
    {
      loop.push_back(at);
      auto it = next.find(at);
      if (it == next.end())
        break;
      at = it->second;
      next.erase(it);
    }
    face.loops.push_back(loop);
  }
}

/// The outer loop first: the one of largest area along the normal.
void putOuterLoopFirst(const LatticeMesh& m, ModifiedFace& face)
{
  auto area = [&](const std::vector<Index>& loop)
  {
    LatticePoint sum{ 0, 0, 0 };
    for (std::size_t k = 0; k < loop.size(); ++k)
    {
      const LatticePoint c = cross(m.points[loop[k]], m.points[loop[(k + 1) % loop.size()]]);
      sum = { sum[0] + c[0], sum[1] + c[1], sum[2] + c[2] };
    }
    return dot(sum, face.plane.normal);
  };
  std::sort(face.loops.begin(),
    face.loops.end(),
    [&](const std::vector<Index>& a, const std::vector<Index>& b) { return area(a) > area(b); });
}

/// The loops of every face from the edges between its triangles and other faces'; the number
/// of distinct edges of the polyhedron.
std::size_t loopsOfFaces(const LatticeMesh& m,
  const std::unordered_map<std::uint64_t, Index>& owner,
  UnionFind& faceOf,
  std::vector<ModifiedFace>& faces)
{
  std::vector<std::pair<Index, Index>> edges;
  for (ModifiedFace& face : faces)
  {
    std::multimap<Index, Index> next;
    for (Index t : face.triangles)
      for (int k = 0; k < 3; ++k)
      {
        const Index a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
        auto it = owner.find(edgeKey(b, a));
        if (it == owner.end() || faceOf.find(it->second) != faceOf.find(t))
        {
          next.emplace(a, b);
          edges.push_back({ std::min(a, b), std::max(a, b) });
        }
      }
    traceLoops(next, face);
    putOuterLoopFirst(m, face);
  }
  std::sort(edges.begin(), edges.end());
  return static_cast<std::size_t>(std::unique(edges.begin(), edges.end()) - edges.begin());
}

/// Numbers the points of the surface in (x, y, z) order and the loops' corners following
/// (each loop from its least point, its cyclic order kept, the holes after the outer loop in
/// the order of their least point).
void numberPointsInOrder(ModifiedHull& r)
{
  std::vector<LatticePoint>& points = r.surface.points;
  std::vector<Index> byPoint(points.size());
  std::iota(byPoint.begin(), byPoint.end(), Index(0));
  std::sort(
    byPoint.begin(), byPoint.end(), [&](Index a, Index b) { return points[a] < points[b]; });
  std::vector<Index> newIndex(points.size());
  std::vector<LatticePoint> sorted(points.size());
  for (std::size_t k = 0; k < byPoint.size(); ++k)
  {
    newIndex[byPoint[k]] = static_cast<Index>(k);
    sorted[k] = points[byPoint[k]];
  }
  points = std::move(sorted);
  for (auto& t : r.surface.triangles)
    for (auto& corner : t)
      corner = newIndex[corner];
  for (ModifiedFace& face : r.faces)
  {
    for (auto& loop : face.loops)
    {
      for (auto& corner : loop)
        corner = newIndex[corner];
      std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    }
    if (face.loops.size() > 2)
      std::sort(face.loops.begin() + 1, face.loops.end());
  }
}

/// Triangles from their least corner (orientation kept) in the order of their corners, each
/// face's triangles in that order and the faces in the order of their first triangle.
void orderTrianglesAndFaces(ModifiedHull& r)
{
  auto& triangles = r.surface.triangles;
  for (auto& t : triangles)
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::vector<Index> byTriangle(triangles.size());
  std::iota(byTriangle.begin(), byTriangle.end(), Index(0));
  std::sort(byTriangle.begin(),
    byTriangle.end(),
    [&](Index a, Index b) { return triangles[a] < triangles[b]; });
  std::vector<Index> newIndex(triangles.size());
  std::vector<std::array<std::uint32_t, 3>> sorted(triangles.size());
  for (std::size_t k = 0; k < byTriangle.size(); ++k)
  {
    newIndex[byTriangle[k]] = static_cast<Index>(k);
    sorted[k] = triangles[byTriangle[k]];
  }
  triangles = std::move(sorted);
  for (ModifiedFace& face : r.faces)
  {
    for (auto& t : face.triangles)
      t = newIndex[t];
    std::sort(face.triangles.begin(), face.triangles.end());
  }
  std::sort(r.faces.begin(),
    r.faces.end(),
    [](const ModifiedFace& a, const ModifiedFace& b) { return a.triangles < b.triangles; });
}

/// Puts the surface and its faces in an order that depends only on their shape. The surface
/// comes out of CGAL's corefinement, whose vertex and face order follows the order in which its
/// box intersection reports pairs, and that breaks ties by the boxes' addresses
/// (ID_FROM_BOX_ADDRESS): the same points and faces in an order that changed with the heap
/// layout from one run to the next.
void putInCanonicalOrder(ModifiedHull& r)
{
  numberPointsInOrder(r);
  orderTrianglesAndFaces(r);
}

/// The faces of the surface: coplanar edge-adjacent triangles merged, with their loops and
/// the level of their first triangle when `triangleLevel` holds one per triangle, else of
/// their plane.
void mergeIntoFaces(const std::map<FacePlane, int>& planeLevel,
  const std::vector<int>& triangleLevel,
  ModifiedHull& r)
{
  const LatticeMesh& m = r.surface;
  const std::size_t nt = m.triangles.size();
  std::vector<FacePlane> planes(nt);
  std::unordered_map<std::uint64_t, Index> owner;
  for (std::size_t t = 0; t < nt; ++t)
  {
    const auto& tri = m.triangles[t];
    planes[t] = planeThrough(m.points[tri[0]], m.points[tri[1]], m.points[tri[2]]);
    for (int k = 0; k < 3; ++k)
      owner[edgeKey(tri[k], tri[(k + 1) % 3])] = static_cast<Index>(t);
  }
  UnionFind faceOf = coplanarTriangles(m, planes, owner);
  std::unordered_map<Index, Index> faceOfRoot;
  for (std::size_t t = 0; t < nt; ++t)
  {
    const Index root = faceOf.find(static_cast<std::uint32_t>(t));
    auto it = faceOfRoot.find(root);
    if (it == faceOfRoot.end())
    {
      it = faceOfRoot.emplace(root, static_cast<Index>(r.faces.size())).first;
      ModifiedFace face;
      face.plane = planes[t];
      if (triangleLevel.size() == nt)
        face.level = triangleLevel[t];
      else
      {
        auto level = planeLevel.find(planes[t]);
        face.level = level == planeLevel.end() ? -1 : level->second;
      }
      r.faces.push_back(face);
    }
    r.faces[it->second].triangles.push_back(static_cast<Index>(t));
  }
  r.edgeCount = loopsOfFaces(m, owner, faceOf, r.faces);
  putInCanonicalOrder(r);
}

/// Sign of orient2D(u, v, q + (delta, delta^2)) in (y, z), delta infinitesimal and positive,
/// the products taken in `Wide` (std::int64_t only where they fit: see rayCrossings).
template<typename Wide>
int perturbedOrientationIn(const LatticePoint& u,
  const LatticePoint& v,
  std::int64_t y,
  std::int64_t z)
{
  const Wide o = Wide(v[1] - u[1]) * (z - u[2]) - Wide(v[2] - u[2]) * (y - u[1]);
  if (o != 0)
    return o > 0 ? 1 : -1;
  if (v[2] != u[2])
    return v[2] > u[2] ? -1 : 1;
  return v[1] > u[1] ? 1 : -1;
}

/// Whether the ray from (y, z) along +x, perturbed as in perturbedOrientationIn, meets the
/// triangle abc, s the sign of its normal's x component (the orientation of abc in (y, z)).
template<typename Wide>
bool rayMeetsTriangle(const LatticePoint& a,
  const LatticePoint& b,
  const LatticePoint& c,
  std::int64_t y,
  std::int64_t z,
  int s)
{
  return perturbedOrientationIn<Wide>(a, b, y, z) == s &&
    perturbedOrientationIn<Wide>(b, c, y, z) == s && perturbedOrientationIn<Wide>(c, a, y, z) == s;
}

/// Sets the bits lo..hi of a row of words, a word at a time; any lo > hi sets none.
void setRun(Word* row, std::int64_t lo, std::int64_t hi)
{
  for (std::int64_t w = lo >> 6; lo <= hi && w <= hi >> 6; ++w)
    row[w] |= runMask(w, lo, hi);
}

} // namespace

bool convexDifferenceIsManifold(const CellList& c, const CellList& g)
{
  if (c.dimension < 3 || g.dimension < 3)
    return true; // a flat G takes nothing off C: the regularised difference is C
  const std::set<FacePlane> planesOfC(c.planes.begin(), c.planes.end());
  std::vector<bool> contactFace(g.faces.size());
  for (std::size_t f = 0; f < g.faces.size(); ++f)
    contactFace[f] = planesOfC.count(g.planes[f]) > 0;
  // Per corner of G, the faces of C through it (sorted indices).
  std::vector<std::vector<std::uint32_t>> onC(g.vertices.size());
  for (std::size_t v = 0; v < g.vertices.size(); ++v)
    for (std::size_t f = 0; f < c.planes.size(); ++f)
      if (c.planes[f].evaluate(g.vertices[v]) == 0)
        onC[v].push_back(static_cast<std::uint32_t>(f));
  std::vector<bool> contactEdge(g.edges.size());
  for (std::size_t e = 0; e < g.edges.size(); ++e)
  {
    const auto& a = onC[g.edges[e][0]];
    const auto& b = onC[g.edges[e][1]];
    std::vector<std::uint32_t> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    contactEdge[e] = !common.empty();
    if (contactEdge[e] && !contactFace[g.edgeFaces[e][0]] && !contactFace[g.edgeFaces[e][1]])
      return false;
  }
  for (std::size_t v = 0; v < g.vertices.size(); ++v)
  {
    if (onC[v].empty())
      continue;
    // The contact edges at v, joined through the contact faces holding two of them.
    const auto& edges = g.vertexEdges[v];
    UnionFind pieces(edges.size());
    for (std::uint32_t f : g.vertexFaces[v])
    {
      if (!contactFace[f])
        continue;
      std::vector<std::size_t> atV;
      for (std::size_t k = 0; k < edges.size(); ++k)
        if (g.edgeFaces[edges[k]][0] == f || g.edgeFaces[edges[k]][1] == f)
          atV.push_back(k);
      for (std::size_t k = 1; k < atV.size(); ++k)
        pieces.unite(static_cast<std::uint32_t>(atV[0]), static_cast<std::uint32_t>(atV[k]));
    }
    std::set<std::uint32_t> roots;
    for (std::size_t k = 0; k < edges.size(); ++k)
      if (contactEdge[edges[k]])
        roots.insert(pieces.find(static_cast<std::uint32_t>(k)));
    if (roots.size() != 1)
      return false;
  }
  return true;
}

std::vector<LatticePoint> latticePointsOnSurface(const LatticeMesh& surface, const Dims& dims)
{
  // The points lie in the grid, so (x * ny + y) * nz + z numbers them in the lexicographic
  // order of (x, y, z): sorting these integers (the corners and edges shared by triangles come
  // several times) is much cheaper than sorting the triples, and gives the same list.
  const std::uint64_t ny = static_cast<std::uint64_t>(dims[1]);
  const std::uint64_t nz = static_cast<std::uint64_t>(dims[2]);
  std::vector<std::uint64_t> keys;
  keys.reserve(2 * surface.triangles.size());
  const LatticeBox grid{ LatticePoint{ 0, 0, 0 },
    LatticePoint{ dims[0] - 1, dims[1] - 1, dims[2] - 1 } };
  for (const auto& tri : surface.triangles)
    forEachPointOnTriangle(
      { surface.points[tri[0]], surface.points[tri[1]], surface.points[tri[2]] },
      grid,
      [&](const LatticePoint& p)
      {
        keys.push_back(
          (static_cast<std::uint64_t>(p[0]) * ny + static_cast<std::uint64_t>(p[1])) * nz +
          static_cast<std::uint64_t>(p[2]));
      });
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<LatticePoint> found(keys.size());
  for (std::size_t n = 0; n < keys.size(); ++n)
  {
    const std::uint64_t yz = keys[n] % (ny * nz);
    found[n] = { static_cast<std::int64_t>(keys[n] / (ny * nz)),
      static_cast<std::int64_t>(yz / nz),
      static_cast<std::int64_t>(yz % nz) };
  }
  return found;
}

namespace
{

/// A ray's crossing with a triangle: its row z * ny + y, and ceil(xc) - 1 for its x xc.
using RowCrossing = std::pair<std::uint32_t, std::int64_t>;

/// Appends the crossings of the rays (x -> +infinity, y + delta, z + delta^2) of the grid's rows
/// with the triangle abc (its plane `plane`, whose normal's x component is not 0).
template<typename Wide>
void appendCrossings(const LatticePoint& a,
  const LatticePoint& b,
  const LatticePoint& c,
  const FacePlane& plane,
  const Dims& dims,
  std::vector<RowCrossing>& crossings)
{
  const std::int64_t nx = plane.normal[0];
  const int s = nx > 0 ? 1 : -1;
  for (std::int64_t z = std::max<std::int64_t>(0, std::min({ a[2], b[2], c[2] }));
       z <= std::min<std::int64_t>(dims[2] - 1, std::max({ a[2], b[2], c[2] }));
       ++z)
    for (std::int64_t y = std::max<std::int64_t>(0, std::min({ a[1], b[1], c[1] }));
         y <= std::min<std::int64_t>(dims[1] - 1, std::max({ a[1], b[1], c[1] }));
         ++y)
    {
      if (!rayMeetsTriangle<Wide>(a, b, c, y, z, s))
        continue;
      const std::int64_t r = plane.offset - plane.normal[1] * y - plane.normal[2] * z;
      crossings.emplace_back(static_cast<std::uint32_t>(z * dims[1] + y), ceilDiv(r, nx) - 1);
    }
}

/// The crossings of the rays of the grid's rows with the surface's triangles, in no order: the
/// crossings as (row, x) pairs, grouped by row later (one vector per row of a large grid cost
/// an allocation for each row the surface crosses).
std::vector<RowCrossing> rayCrossings(const LatticeMesh& surface, const Dims& dims)
{
  // Corners below 2^30 in magnitude (H's are voxel centres, below 2^20 as convexHull's; but
  // revertModifiedHull takes any mesh, so the 128-bit products stay for the others, within what
  // planeThrough's 64-bit normals allow): the rows (y, z) tried lie within the triangle's
  // bounds, so every difference in an orientation is at most 2^31 - 2 in magnitude, each
  // product at most (2^31 - 2)^2 < 2^62, and the difference of two products below 2^63.
  const bool productsFit64 = std::all_of(surface.points.begin(),
    surface.points.end(),
    [](const LatticePoint& p)
    {
      return std::all_of(p.begin(),
        p.end(),
        [](std::int64_t c) { return c > -(std::int64_t(1) << 30) && c < (std::int64_t(1) << 30); });
    });
  std::vector<RowCrossing> crossings;
  for (const auto& tri : surface.triangles)
  {
    const LatticePoint &a = surface.points[tri[0]], &b = surface.points[tri[1]],
                       &c = surface.points[tri[2]];
    const FacePlane plane = planeThrough(a, b, c);
    if (plane.normal[0] == 0)
      continue;
    if (productsFit64)
      appendCrossings<std::int64_t>(a, b, c, plane, dims, crossings);
    else
      appendCrossings<__int128>(a, b, c, plane, dims, crossings);
  }
  return crossings;
}

/// Sets in `out` the centres with an odd number of crossings beyond them in their row.
void fillInsideRuns(const std::vector<RowCrossing>& crossings, BitVolume& out)
{
  const Dims& dims = out.dims();
  // Grouped by row by a counting sort.
  const std::size_t rowCount = static_cast<std::size_t>(dims[1]) * dims[2];
  std::vector<std::uint32_t> rowStart(rowCount + 1, 0);
  for (const auto& c : crossings)
    ++rowStart[c.first + 1];
  for (std::size_t n = 0; n < rowCount; ++n)
    rowStart[n + 1] += rowStart[n];
  std::vector<std::int64_t> xs(crossings.size());
  {
    std::vector<std::uint32_t> next(rowStart.begin(), rowStart.end() - 1);
    for (const auto& c : crossings)
      xs[next[c.first]++] = c.second;
  }
  // Centre x of a row is inside when an odd number of its crossings have an index >= x: with
  // the indices in decreasing order c_1 >= c_2 >= ..., the centres in (c_{j+1}, c_j] for odd j
  // (c_{m+1} = -1), only the runs inside visited.
  for (std::int32_t z = 0; z < dims[2]; ++z)
    for (std::int32_t y = 0; y < dims[1]; ++y)
    {
      const std::size_t row = static_cast<std::size_t>(z) * dims[1] + y;
      if (rowStart[row] == rowStart[row + 1])
        continue; // no crossing: the row is outside (most rows of a large grid)
      const auto first = xs.begin() + rowStart[row], last = xs.begin() + rowStart[row + 1];
      std::sort(first, last, std::greater<>());
      bool parity = false;
      for (auto c = first; c != last && *c >= 0; ++c)
      {
        parity = !parity;
        if (!parity)
          continue;
        const std::int64_t hi = std::min<std::int64_t>(*c, dims[0] - 1);
        const std::int64_t lo = c + 1 != last ? std::max<std::int64_t>(*(c + 1), -1) + 1 : 0;
        setRun(out.row(y, z), lo, hi);
      }
    }
}

/// revertModifiedHull with the lattice points on the surface (latticePointsOnSurface) given:
/// the whole-H check and the shells' marks list them anyway. Only bits of centres in the grid
/// are set (x < dims[0]: the words' padding bits stay 0).
BitVolume revertWithPointsOn(const LatticeMesh& surface,
  const std::vector<LatticePoint>& on,
  const std::vector<LatticePoint>& backgroundOnSurface,
  const Dims& dims)
{
  BitVolume out(dims[0], dims[1], dims[2]);
  fillInsideRuns(rayCrossings(surface, dims), out);
  for (const auto& p : on)
    out.set(static_cast<std::int32_t>(p[0]),
      static_cast<std::int32_t>(p[1]),
      static_cast<std::int32_t>(p[2]),
      !std::binary_search(backgroundOnSurface.begin(), backgroundOnSurface.end(), p));
  return out;
}

} // namespace

BitVolume revertModifiedHull(const LatticeMesh& surface,
  const std::vector<LatticePoint>& backgroundOnSurface,
  const Dims& dims)
{
  return revertWithPointsOn(
    surface, latticePointsOnSurface(surface, dims), backgroundOnSurface, dims);
}

namespace
{

/// Whether the centres inside or on the closed surface, less the background centres on it, are
/// the object (for a closed embedded surface: the voxel set reverts exactly).
bool revertsToObjects(const BitVolume& objects, const LatticeMesh& surface)
{
  const std::vector<LatticePoint> on = latticePointsOnSurface(surface, objects.dims());
  std::vector<LatticePoint> background;
  for (const auto& p : on)
    if (!voxelClass(objects, p))
      background.push_back(p);
  return revertWithPointsOn(surface, on, background, objects.dims()) == objects;
}

struct Shell;
std::vector<Shell> shellsOf(const LatticeMesh& m);
bool shellsFaceOutward(const std::vector<Shell>& shells);

/// Whether H separates: a closed embedded 2-manifold, each shell oriented away from its solid
/// (the joins turn parts of H over and back; shellsFaceOutward, exact), from which the voxel
/// set reverts exactly.
bool separates(const BitVolume& objects, const LatticeMesh& surface)
{
  return isClosedEmbeddedManifold(surface) && shellsFaceOutward(shellsOf(surface)) &&
    revertsToObjects(objects, surface);
}

/// Whether the mesh is a closed, consistently oriented 2-manifold: every directed edge once and
/// its reverse once (each edge in two triangles, oriented alike), and the triangles about every
/// point one fan (no point where two pieces touch), what boundsAVolume asks of the mesh before
/// its self-intersection test.
bool isClosedManifold(const LatticeMesh& m)
{
  std::vector<std::pair<Index, Index>> edges;
  edges.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles)
  {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      return false;
    for (int k = 0; k < 3; ++k)
      edges.emplace_back(t[k], t[(k + 1) % 3]);
  }
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end())
    return false;
  for (const auto& [a, b] : edges)
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a)))
      return false;
  // About point v each triangle (v, x, y) leads from x to y: a permutation of v's neighbours
  // (each edge vx in two triangles), which must be one cycle.
  std::vector<std::vector<std::pair<Index, Index>>> around(m.points.size());
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      around[t[k]].emplace_back(t[(k + 1) % 3], t[(k + 2) % 3]);
  for (auto& fan : around)
  {
    if (fan.empty())
      continue;
    std::sort(fan.begin(), fan.end());
    std::size_t length = 0;
    Index x = fan[0].first;
    do
    {
      x = std::lower_bound(fan.begin(), fan.end(), std::make_pair(x, Index(0)))->second;
      ++length;
    } while (x != fan[0].first && length <= fan.size());
    if (length != fan.size())
      return false;
  }
  return true;
}

/// separates for H made from an H that separates by joins and handle cuts each checked on the
/// part of H it changed (joinAlongPrism): each Boolean's result is a closed 2-manifold oriented
/// as its operands, and the triangles that meet its prism's box are tested for
/// self-intersections, which is the whole test for a closed embedded mesh that a Boolean
/// changed only inside that box (isEmbeddedWithin). So the whole H is embedded; the
/// self-intersection test of all of H (about 0.9 s of CPU on the aneurism's 48,000 triangles)
/// is left out, and what the changes could still have missed is checked: closed, manifold,
/// consistently oriented within each shell, each shell facing away from its solid (exact signed
/// volumes and nesting, shellsFaceOutward: the reversion counts crossings by parity and would
/// not see a shell turned over whole), and the reversion.
bool separatesAfterLocalChecks(const BitVolume& objects, const LatticeMesh& surface)
{
  return isClosedManifold(surface) && shellsFaceOutward(shellsOf(surface)) &&
    revertsToObjects(objects, surface);
}

/// Repairing the topology (see the header): a void of H whose background centres reach the
/// rest of the background through face-connected background centres, or a piece of H whose
/// object centres are face-neighbours of object centres of another piece, is joined to the rest
/// by a prism conv(T1 + T2) between an empty lattice triangle T1 of its shell and one T2 of
/// another shell, cut out of H (a void) or added to it (a piece).

/// A shell of H (a connected set of triangles; H's points are distinct, so triangles sharing a
/// point belong to one shell) with six times its signed volume (negative: an inner surface,
/// oriented into a void).
struct Shell
{
  LatticeMesh mesh;
  __int128 volume = 0;
  LatticeBox box; ///< the box of its points
  /// sideOf's index, built at its kSideQueriesBeforeIndex-th query (the joins ask many points
  /// of one shell, and scanned all its triangles for each): the triangles whose z-range meets
  /// the rows z = box[0][2] + (n << zShift) .. + 2^zShift - 1 are byZ[zStart[n] ..
  /// zStart[n + 1]). Rows are grouped by 2^zShift so that the index stays within a few
  /// entries per triangle on tall shells of long triangles. The mesh is not changed once its
  /// shell is built, so the index stays true. Built on a query through a const Shell: one
  /// thread asks a shell at a time (nothing in the modifier runs in parallel).
  mutable std::uint32_t sideQueries = 0;
  mutable int zShift = 0;
  mutable std::vector<std::size_t> zStart;
  mutable std::vector<Index> byZ;
};

std::vector<Shell> shellsOf(const LatticeMesh& m)
{
  UnionFind sets(m.points.size());
  for (const auto& t : m.triangles)
  {
    sets.unite(t[0], t[1]);
    sets.unite(t[0], t[2]);
  }
  // Flat tables, not maps: the joins split a large H into its shells after every Boolean. A
  // point lies in one shell, so one local index per point does.
  constexpr Index none = std::numeric_limits<Index>::max();
  std::vector<Index> shellOfRoot(m.points.size(), none), local(m.points.size(), none);
  std::vector<Shell> shells;
  for (const auto& t : m.triangles)
  {
    Index& shell = shellOfRoot[sets.find(t[0])];
    if (shell == none)
    {
      shell = static_cast<Index>(shells.size());
      shells.emplace_back();
    }
    Shell& s = shells[shell];
    std::array<Index, 3> tri;
    for (int k = 0; k < 3; ++k)
    {
      if (local[t[k]] == none)
      {
        local[t[k]] = static_cast<Index>(s.mesh.points.size());
        s.mesh.points.push_back(m.points[t[k]]);
      }
      tri[k] = local[t[k]];
    }
    s.mesh.triangles.push_back(tri);
    s.volume += dot(m.points[t[0]], cross(m.points[t[1]], m.points[t[2]]));
  }
  for (Shell& s : shells)
  {
    s.box = { s.mesh.points[0], s.mesh.points[0] };
    for (const auto& p : s.mesh.points)
      for (int k = 0; k < 3; ++k)
      {
        s.box[0][k] = std::min(s.box[0][k], p[k]);
        s.box[1][k] = std::max(s.box[1][k], p[k]);
      }
  }
  return shells;
}

/// H as its shells while shells are joined: a join replaces the shells it changed
/// (joinAlongPrism), so H is not split into its shells again after every join, and H is put
/// together from its shells only when asked for (takeMesh), not after every join. The whole H
/// given is kept only until the first replacement (it is then stale, and freed: copies of the
/// surface, one per attempted chain of cuts, do not copy it).
class ShelledSurface
{
public:
  std::vector<Shell> shells;

  explicit ShelledSurface(const LatticeMesh& m)
    : shells(shellsOf(m))
    , mesh(m)
  {
  }

  /// H, its shells appended in their order when one was replaced; the surface is left empty.
  LatticeMesh takeMesh()
  {
    if (this->stale)
    {
      this->mesh = LatticeMesh{};
      for (const Shell& s : this->shells)
        this->mesh.append(s.mesh, false);
    }
    this->stale = false;
    this->shells.clear();
    return std::move(this->mesh);
  }

  /// Puts `pieces` in the place of the shells flagged in `changed` (where the first of them
  /// was); H is put together from the shells by takeMesh.
  void replace(const std::vector<bool>& changed, std::vector<Shell>&& pieces)
  {
    std::vector<Shell> kept;
    bool placed = false;
    for (std::size_t i = 0; i < this->shells.size(); ++i)
      if (!changed[i])
        kept.push_back(std::move(this->shells[i]));
      else if (!placed)
      {
        placed = true;
        for (Shell& p : pieces)
          kept.push_back(std::move(p));
      }
    this->shells = std::move(kept);
    this->stale = true;
    this->mesh = LatticeMesh{};
  }

private:
  LatticeMesh mesh;
  bool stale = false;
};

long eulerCharacteristic(const LatticeMesh& m)
{
  return static_cast<long>(m.points.size()) - static_cast<long>(m.triangles.size()) / 2;
}

std::size_t gridIndex(const Dims& d, const LatticePoint& p)
{
  return (static_cast<std::size_t>(p[2]) * d[1] + p[1]) * d[0] + p[0];
}

/// A closed shell in its own box (lo its least corner, a lattice point p at p - lo there): the
/// box's lattice points on the shell and those strictly inside it (ray parity).
struct ShellInBox
{
  LatticePoint lo;
  Dims box;
  std::vector<LatticePoint> on;
  BitVolume inside;
};

ShellInBox shellInItsBox(const LatticeMesh& shell)
{
  ShellInBox s;
  s.lo = shell.points[0];
  LatticePoint hi = s.lo;
  for (const auto& p : shell.points)
    for (int k = 0; k < 3; ++k)
    {
      s.lo[k] = std::min(s.lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  LatticeMesh local = shell;
  for (auto& p : local.points)
    p = sub(p, s.lo);
  s.box = { static_cast<std::int32_t>(hi[0] - s.lo[0] + 1),
    static_cast<std::int32_t>(hi[1] - s.lo[1] + 1),
    static_cast<std::int32_t>(hi[2] - s.lo[2] + 1) };
  s.on = latticePointsOnSurface(local, s.box);
  s.inside = revertWithPointsOn(local, s.on, s.on, s.box);
  return s;
}

/// Flags (value `flag`) the lattice points of the grid strictly enclosed by a closed shell (ray
/// parity) and, with `onFlag`, those on it; only the shell's box is scanned.
void markShell(const LatticeMesh& shell,
  const Dims& d,
  std::uint8_t flag,
  std::uint8_t onFlag,
  std::vector<std::uint8_t>& out)
{
  const ShellInBox s = shellInItsBox(shell);
  const LatticePoint& lo = s.lo;
  const Dims& box = s.box;
  const std::vector<LatticePoint>& on = s.on;
  const BitVolume& inside = s.inside;
  // The inside's words scanned for their set bits: most of a large shell's box is outside it.
  // All wordsPerRow() words of a row: their padding bits (x >= box[0]) are 0, as
  // revertWithPointsOn sets bits only of centres in the box.
  for (std::int32_t z = 0; z < box[2]; ++z)
    for (std::int32_t y = 0; y < box[1]; ++y)
    {
      const Word* row = inside.row(y, z);
      for (std::size_t w = 0; w < inside.wordsPerRow(); ++w)
        for (Word bits = row[w]; bits != 0; bits &= bits - 1)
        {
          const auto x = static_cast<std::int64_t>(64 * w) + __builtin_ctzll(bits);
          const LatticePoint p{ x + lo[0], y + lo[1], z + lo[2] };
          if (inGrid(d, p))
            out[gridIndex(d, p)] = flag;
        }
    }
  for (const auto& q : on)
  {
    const LatticePoint p{ q[0] + lo[0], q[1] + lo[1], q[2] + lo[2] };
    if (onFlag && inGrid(d, p))
      out[gridIndex(d, p)] = onFlag;
  }
}

/// Where each lattice point of the grid lies with respect to H.
enum Where : std::uint8_t
{
  Outside = 0,
  On = 1,
  Inside = 2
};

std::vector<std::uint8_t> whereInGrid(const LatticeMesh& surface, const Dims& d)
{
  std::vector<std::uint8_t> where(static_cast<std::size_t>(d[0]) * d[1] * d[2], Outside);
  markShell(surface, d, Inside, On, where);
  return where;
}

LatticePoint step(const LatticePoint& p, int k)
{
  LatticePoint q = p;
  q[k / 2] += k % 2 ? 1 : -1;
  return q;
}

/// voidCrossing's table: a centre not reached, a centre of the void (else the step 0-5 by which
/// a centre was reached).
constexpr std::uint8_t kUnreached = 255, kSeed = 6;

/// Calls f for each lattice point of the box, x fastest (the order of a scan of the grid).
template<typename F>
void forEachInBox(const LatticeBox& box, F&& f)
{
  for (std::int64_t z = box[0][2]; z <= box[1][2]; ++z)
    for (std::int64_t y = box[0][1]; y <= box[1][1]; ++y)
      for (std::int64_t x = box[0][0]; x <= box[1][0]; ++x)
        f(LatticePoint{ x, y, z });
}

/// The shell's box within the grid: where markShell flags centres (the box may be empty).
LatticeBox gridBoxOf(const Shell& shell, const Dims& d)
{
  LatticeBox box = shell.box;
  for (int k = 0; k < 3; ++k)
  {
    box[0][k] = std::max<std::int64_t>(box[0][k], 0);
    box[1][k] = std::min<std::int64_t>(box[1][k], d[k] - 1);
  }
  return box;
}

/// The tables of voidCrossing's searches, kept by the caller from one search to the next so that
/// a search allocates nothing once they have grown: the step each centre was reached by (kSeed: a
/// centre of the void; all kUnreached between searches) and the centres a search reached, in
/// the order reached: its queue (visited from the front, first in first out), and afterwards
/// the centres whose steps it resets. Each search stays
/// near its shell: a table of the grid allocated per shell cost more than the search on the full
/// aneurism, a hash map a twentieth of its time.
struct VoidSearch
{
  std::vector<std::uint8_t> from;
  std::vector<LatticePoint> todo;

  explicit VoidSearch(std::size_t centres)
    : from(centres, kUnreached)
  {
  }
};

/// The shortest face-connected path of background centres from a centre of a void (`mine`
/// flags the centres the shell encloses or holds: a thin void encloses none) to a background centre
/// strictly outside H and not flagged (or off the grid), every centre between them on H. The two
/// centres where the path leaves the shell (the last one flagged and the next), or nothing when the
/// void is sealed from the rest of the background.
std::vector<LatticePoint> voidCrossing(const BitVolume& objects,
  const std::vector<std::uint8_t>& where,
  const std::vector<std::uint8_t>& mine,
  const LatticeBox& box,
  VoidSearch& search)
{
  const Dims d = objects.dims();
  std::vector<std::uint8_t>& from = search.from;
  std::vector<LatticePoint>& todo = search.todo; // every centre reached, visited from head on
  std::size_t head = 0;
  todo.clear();
  const auto reach = [&](const LatticePoint& p, std::uint8_t how)
  {
    from[gridIndex(d, p)] = how;
    todo.push_back(p);
  };
  forEachInBox(box,
    [&](const LatticePoint& p)
    {
      if (mine[gridIndex(d, p)] && !voxelClass(objects, p))
      {
        reach(p, kSeed);
      }
    });
  std::vector<LatticePoint> found;
  bool done = false; // the first path out decides, a crossing or none
  while (head < todo.size() && !done)
  {
    const LatticePoint p = todo[head++]; // a copy: pushing below may move the list
    for (int k = 0; k < 6; ++k)
    {
      const LatticePoint q = step(p, k);
      if (!inGrid(d, q) ||
        (where[gridIndex(d, q)] == Outside && !mine[gridIndex(d, q)] && !voxelClass(objects, q)))
      {
        done = true;
        std::vector<LatticePoint> path{ q };
        for (LatticePoint r = p;;)
        {
          path.push_back(r);
          const std::uint8_t how = from[gridIndex(d, r)];
          if (how == kSeed)
            break;
          r = step(r, how ^ 1); // back along the step that reached r
        }
        // path runs from outside back to the void: the crossing is the first step (from the
        // void's side) onto a centre the shell does not hold.
        for (std::size_t i = path.size() - 1; i > 0; --i)
          if (!inGrid(d, path[i - 1]) || !mine[gridIndex(d, path[i - 1])])
          {
            found = { path[i], path[i - 1] };
            break;
          }
        break;
      }
      if (where[gridIndex(d, q)] == On && !voxelClass(objects, q) &&
        from[gridIndex(d, q)] == kUnreached)
      {
        reach(q, static_cast<std::uint8_t>(k));
      }
    }
  }
  for (const LatticePoint& p : todo) // visited or not: the search may stop at its first way out
    from[gridIndex(d, p)] = kUnreached;
  return found;
}

/// The lattice points of the box of a closed shell that lie inside or on it, in the box's own
/// coordinates (a lattice point p of the grid is p - lo there).
BitVolume heldByShell(const LatticeMesh& shell, LatticePoint& lo)
{
  ShellInBox s = shellInItsBox(shell);
  lo = s.lo;
  BitVolume held = std::move(s.inside);
  for (const auto& p : s.on)
    held.set(static_cast<std::int32_t>(p[0]),
      static_cast<std::int32_t>(p[1]),
      static_cast<std::int32_t>(p[2]));
  return held;
}

/// The points of row (y, z) of `held` (words) some face-neighbour of which is not held: the
/// others cannot have a neighbour outside the shell.
std::vector<Word> rowBorder(const BitVolume& held, std::int32_t y, std::int32_t z)
{
  const std::size_t n = held.wordsPerRow();
  const Word* row = held.row(y, z);
  const auto other = [&](std::int32_t v, std::int32_t w, std::size_t i) -> Word
  { return v < 0 || w < 0 || v >= held.size(1) || w >= held.size(2) ? 0 : held.row(v, w)[i]; };
  std::vector<Word> border(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Word h = row[i];
    const Word before = (h << 1) | (i > 0 ? row[i - 1] >> 63 : 0);    // bit x: x - 1 held
    const Word after = (h >> 1) | (i + 1 < n ? row[i + 1] << 63 : 0); // bit x: x + 1 held
    const Word inner = h & before & after & other(y - 1, z, i) & other(y + 1, z, i) &
      other(y, z - 1, i) & other(y, z + 1, i);
    border[i] = h & ~inner;
  }
  return border;
}

/// An object centre of the piece (inside or on its shell) and an object centre of another piece
/// that are face-neighbours, the first in scan order, or nothing. Only the piece's points with
/// a face-neighbour it does not hold are visited (some of these pieces' boxes hold millions of
/// their points).
std::vector<LatticePoint> pieceCrossing(const BitVolume& objects, const LatticeMesh& shell)
{
  LatticePoint lo;
  const BitVolume held = heldByShell(shell, lo);
  const auto isHeld = [&](const LatticePoint& q)
  {
    const LatticePoint r = sub(q, lo);
    for (int k = 0; k < 3; ++k)
      if (r[k] < 0 || r[k] >= held.size(k))
        return false;
    return held.get(static_cast<std::int32_t>(r[0]),
      static_cast<std::int32_t>(r[1]),
      static_cast<std::int32_t>(r[2]));
  };
  for (std::int32_t z = 0; z < held.size(2); ++z)
    for (std::int32_t y = 0; y < held.size(1); ++y)
    {
      const std::vector<Word> border = rowBorder(held, y, z);
      for (std::size_t i = 0; i < border.size(); ++i)
        for (Word bits = border[i]; bits != 0; bits &= bits - 1)
        {
          const LatticePoint p{
            lo[0] + static_cast<std::int64_t>(64 * i) + __builtin_ctzll(bits), lo[1] + y, lo[2] + z
          };
          if (!voxelClass(objects, p))
            continue;
          for (int k = 0; k < 6; ++k)
          {
            const LatticePoint q = step(p, k);
            if (voxelClass(objects, q) && !isHeld(q))
              return { p, q };
          }
        }
    }
  return {};
}

/// The empty lattice triangles of the mesh's triangles near the two centres (their boxes
/// within one step), nearest first, at most `count`.
std::vector<std::array<LatticePoint, 3>> emptyTrianglesNear(const LatticeMesh& m,
  const std::vector<LatticePoint>& near,
  std::size_t count)
{
  CellList faces;
  faces.vertices = m.points;
  for (const auto& t : m.triangles)
  {
    bool close = false;
    for (const auto& p : near)
    {
      bool in = true;
      for (int k = 0; k < 3; ++k)
        in = in &&
          std::min({ m.points[t[0]][k], m.points[t[1]][k], m.points[t[2]][k] }) <= p[k] + 1 &&
          std::max({ m.points[t[0]][k], m.points[t[1]][k], m.points[t[2]][k] }) >= p[k] - 1;
      close = close || in;
    }
    if (!close)
      continue;
    faces.faces.push_back({ t[0], t[1], t[2] });
    faces.planes.push_back(planeThrough(m.points[t[0]], m.points[t[1]], m.points[t[2]]));
  }
  std::vector<std::array<LatticePoint, 3>> found;
  EmptyFaceTriangles triangles(faces, PointRuns::of(near));
  std::array<LatticePoint, 3> t;
  while (found.size() < count && triangles.next(t))
    found.push_back(t);
  return found;
}

/// The empty triangles taken on each side of a crossing. 6 left extra shells on porous blobs
/// and hollow balls whose prisms all held a lattice point or failed the Boolean.
constexpr std::size_t kTrianglesNear = 12;

/// The empty triangles taken when none of the first prisms joined the shell: a void reaching
/// out along a 1 wide tunnel in long thin triangles (the hollow balls of R 10 with an
/// off-centre tunnel) has no prism of the 12 nearest that a Boolean accepts (36 joined one of
/// the two, 60 both).
constexpr std::size_t kMoreTrianglesNear = 60;

/// The candidate prisms conv(T1 + T2), T1 from `first` and T2 from `second` (empty lattice
/// triangles, nearest first), pair (i, j) the candidate i * second.size() + j; the pairs of the
/// `tried` first on both sides are left out (the round before offered them; it may not have
/// tried them all). A candidate is a prism when its hull is solid with no lattice point in its
/// open interior; tryPrisms makes the hulls one at a time as it needs them, since a join mostly
/// comes from one of the first prisms (making all 144 or 3,600 hulls up front was 7 % of the
/// aneurism's time).
struct PrismPairs
{
  std::vector<std::array<LatticePoint, 3>> first;
  std::vector<std::array<LatticePoint, 3>> second;
  std::size_t tried = 0;

  std::size_t size() const { return this->first.size() * this->second.size(); }
  bool offered(std::size_t k) const
  {
    return k / this->second.size() >= this->tried || k % this->second.size() >= this->tried;
  }
  std::vector<LatticePoint> corners(std::size_t k) const
  {
    const auto& a = this->first[k / this->second.size()];
    const auto& b = this->second[k % this->second.size()];
    return { a[0], a[1], a[2], b[0], b[1], b[2] };
  }
};

/// Whether the solid hull (its open interior when `strict`) holds a lattice point: the first
/// row that holds one ends the scan.
bool holdsALatticePoint(const CellList& c, bool strict)
{
  return !forEachRowIn(
    c, strict, [](std::int64_t, std::int64_t, std::int64_t, std::int64_t) { return false; });
}

/// The prism of candidate k of `pairs`, or none when its hull is flat or holds a lattice point
/// in its open interior.
std::optional<CellList> emptyPrism(const PrismPairs& pairs, std::size_t k)
{
  CellList prism = convexHull(pairs.corners(k));
  if (prism.dimension != 3 || holdsALatticePoint(prism, true))
    return std::nullopt;
  return prism;
}

/// The candidates between the `count` nearest empty triangles of the shell and of the rest of H
/// near the crossing (PrismPairs).
PrismPairs prismsAt(const LatticeMesh& shell,
  const LatticeMesh& rest,
  const std::vector<LatticePoint>& crossing,
  std::size_t count,
  std::size_t tried)
{
  return {
    emptyTrianglesNear(shell, crossing, count), emptyTrianglesNear(rest, crossing, count), tried
  };
}

/// Whether the triangle's box (scaled by k) misses the row of p across y or z, or ends before p
/// along x.
bool behindOrBeside(const LatticeMesh& surface,
  const std::array<Index, 3>& tri,
  const LatticePoint& p,
  std::int64_t k)
{
  const LatticePoint& a = surface.points[tri[0]];
  const LatticePoint& b = surface.points[tri[1]];
  const LatticePoint& c = surface.points[tri[2]];
  for (int axis = 0; axis < 3; ++axis)
  {
    const std::int64_t hi = k * std::max({ a[axis], b[axis], c[axis] });
    if (p[axis] > hi)
      return true;
    if (axis > 0 && p[axis] < k * std::min({ a[axis], b[axis], c[axis] }))
      return true;
  }
  return false;
}

/// sideOf's step for one triangle: false when p / k lies on it, else flips `parity` when the
/// ray from p crosses it.
bool crossesBeyond(const LatticeMesh& surface,
  const std::array<Index, 3>& tri,
  const LatticePoint& p,
  std::int64_t k,
  int& parity)
{
  // A triangle whose box misses p's row across y and z, or lies wholly before p along x,
  // neither holds p nor crosses the ray beyond it (the ray's perturbation stays in the row):
  // integer comparisons spare most triangles of a large H their plane.
  if (behindOrBeside(surface, tri, p, k))
    return true;
  LatticePoint q[3];
  for (int v = 0; v < 3; ++v)
    for (int a = 0; a < 3; ++a)
      q[v][a] = surface.points[tri[v]][a] * k;
  const FacePlane plane = planeThrough(q[0], q[1], q[2]);
  if (plane.evaluate(p) == 0 && onTriangle(q[0], q[1], q[2], plane, p))
    return false;
  const std::int64_t nx = plane.normal[0];
  if (nx == 0)
    return true;
  const int s = nx > 0 ? 1 : -1;
  if (!rayMeetsTriangle<__int128>(q[0], q[1], q[2], p[1], p[2], s))
    return true;
  // The crossing lies beyond p when n.p < d along +x for an outward normal with nx > 0.
  const __int128 e = plane.evaluate(p);
  parity ^= (nx > 0) == (e < 0);
  return true;
}

/// sideOf from those of the surface's triangles that can reach p / k (all of them, or for k = 1
/// those trianglesAheadOf keeps for a box that holds p).
int sideOf(const LatticeMesh& surface,
  const std::vector<std::array<Index, 3>>& triangles,
  const LatticePoint& p,
  std::int64_t k)
{
  int parity = 0;
  for (const auto& tri : triangles)
    if (!crossesBeyond(surface, tri, p, k, parity))
      return 0;
  return parity ? 1 : -1;
}

/// Whether the point p / k lies strictly inside the closed surface (+1), strictly outside (-1)
/// or on it (0): the crossings of the ray towards +x (perturbed as in revertModifiedHull).
int sideOf(const LatticeMesh& surface, const LatticePoint& p, std::int64_t k)
{
  return sideOf(surface, surface.triangles, p, k);
}

/// Whether the triangle meets the open interior of the solid hull, or with `closed` the closed
/// hull (exact separating axes: the hull's face normals, the triangle's normal and the cross
/// products of their edges; a plane along one of them that leaves the triangle on one closed
/// side and the hull on the other, or with `closed` strictly apart, is the witness that it does
/// not, as for any two convex polytopes).
bool meetsConvex(const CellList& solid, const std::array<LatticePoint, 3>& t, bool closed)
{
  auto apart = [&](const LatticePoint& n)
  {
    if (n == LatticePoint{ 0, 0, 0 })
      return false;
    __int128 tLo = dot(n, t[0]), tHi = tLo, sLo = dot(n, solid.vertices[0]), sHi = sLo;
    for (const auto& p : t)
    {
      tLo = std::min(tLo, dot(n, p));
      tHi = std::max(tHi, dot(n, p));
    }
    for (const auto& p : solid.vertices)
    {
      sLo = std::min(sLo, dot(n, p));
      sHi = std::max(sHi, dot(n, p));
    }
    return closed ? tHi < sLo || sHi < tLo : tHi <= sLo || sHi <= tLo;
  };
  if (apart(cross(sub(t[1], t[0]), sub(t[2], t[0]))))
    return false;
  for (const auto& plane : solid.planes)
    if (apart(plane.normal))
      return false;
  for (int k = 0; k < 3; ++k)
    for (const auto& e : solid.edges)
      if (apart(cross(sub(t[(k + 1) % 3], t[k]), sub(solid.vertices[e[1]], solid.vertices[e[0]]))))
        return false;
  return true;
}

bool meetsOpenInterior(const CellList& solid, const std::array<LatticePoint, 3>& t)
{
  return meetsConvex(solid, t, false);
}

/// P's bounding box.
std::array<LatticePoint, 2> boxOf(const CellList& prism)
{
  std::array<LatticePoint, 2> box{ prism.vertices[0], prism.vertices[0] };
  for (const auto& v : prism.vertices)
    for (int a = 0; a < 3; ++a)
    {
      box[0][a] = std::min(box[0][a], v[a]);
      box[1][a] = std::max(box[1][a], v[a]);
    }
  return box;
}

/// Whether the prism's open interior misses H: then the Boolean changes H only on the prism's
/// boundary (a tube between T1 and T2). Where a triangle of H crosses the prism the Boolean
/// cuts it at points that are mostly not lattice points, or adds more than a tube: such prisms
/// were the bulk of the rejected Booleans (each an exact corefinement of the whole H), so they
/// are tried last; this test costs the triangles in the prism's box.
bool prismMissesSurface(const CellList& prism, const LatticeMesh& surface)
{
  for (const auto& t : trianglesInBoxOf(surface, prism))
    if (meetsOpenInterior(prism, t))
      return false;
  return true;
}

/// Whether the shell's box meets the open box of the convex hull: the shells that do not hold no
/// triangle that trianglesInBoxOf gives, so the tests local to the hull skip them whole.
bool shellNear(const Shell& shell, const CellList& convex)
{
  const LatticeBox box = boxOf(convex);
  for (int a = 0; a < 3; ++a)
    if (shell.box[1][a] <= box[0][a] || shell.box[0][a] >= box[1][a])
      return false;
  return true;
}

bool prismMissesSurface(const CellList& prism, const std::vector<Shell>& shells)
{
  for (const Shell& shell : shells)
    if (shellNear(shell, prism) && !prismMissesSurface(prism, shell.mesh))
      return false;
  return true;
}

bool booleanLeavesTheLattice(const std::vector<Shell>& shells, const CellList& prism)
{
  for (const Shell& shell : shells)
    if (shellNear(shell, prism) && booleanLeavesTheLattice(shell.mesh, prism))
      return true;
  return false;
}

/// The shells cut down to their triangles that meet the open box `box` (each shell keeps its
/// own box; its volume is not kept). For a convex hull whose box lies in `box`, a triangle
/// that meets the hull's open box meets `box`'s, so trianglesInBoxOf finds the same triangles
/// in the same order here as in the whole shells: the tests above give the same answers. The
/// prisms tried at one crossing all lie near it, and these tests ran over every triangle of the
/// vessel's main shell for each of them (8 % of the full aneurism's time).
std::vector<Shell> shellsInBox(const std::vector<Shell>& shells, const LatticeBox& box)
{
  std::vector<Shell> near;
  for (const Shell& shell : shells)
  {
    Shell cut;
    cut.box = shell.box;
    std::vector<Index> local(shell.mesh.points.size(), std::numeric_limits<Index>::max());
    for (const auto& t : shell.mesh.triangles)
    {
      bool meets = true;
      for (int a = 0; a < 3 && meets; ++a)
      {
        const auto c = [&](int k) { return shell.mesh.points[t[k]][a]; };
        meets =
          std::max({ c(0), c(1), c(2) }) > box[0][a] && std::min({ c(0), c(1), c(2) }) < box[1][a];
      }
      if (!meets)
        continue;
      std::array<Index, 3> tri;
      for (int k = 0; k < 3; ++k)
      {
        if (local[t[k]] == std::numeric_limits<Index>::max())
        {
          local[t[k]] = static_cast<Index>(cut.mesh.points.size());
          cut.mesh.points.push_back(shell.mesh.points[t[k]]);
        }
        tri[k] = local[t[k]];
      }
      cut.mesh.triangles.push_back(tri);
    }
    near.push_back(std::move(cut));
  }
  return near;
}

/// The entries of the z-row index with rows grouped by 2^shift: each triangle is listed
/// once per group its z-range meets.
std::size_t zIndexEntries(const Shell& shell, int shift)
{
  const LatticeMesh& m = shell.mesh;
  const std::int64_t z0 = shell.box[0][2];
  std::size_t entries = 0;
  for (const auto& t : m.triangles)
  {
    const auto [lo, hi] = std::minmax({ m.points[t[0]][2], m.points[t[1]][2], m.points[t[2]][2] });
    entries += static_cast<std::size_t>(((hi - z0) >> shift) - ((lo - z0) >> shift) + 1);
  }
  return entries;
}

/// Entries per triangle the z-row index may hold before rows are grouped (the aneurism's
/// shells reach 17, so real objects keep one row per group); a group's scan still reads a
/// small part of a tall shell, and the index stays linear in the triangles.
constexpr std::size_t kZIndexEntriesPerTriangle = 64;

/// The triangles of the shell by the groups of integer z-rows they span (Shell::byZ).
void indexByZ(const Shell& shell)
{
  const LatticeMesh& m = shell.mesh;
  const std::int64_t z0 = shell.box[0][2];
  const auto rows = static_cast<std::size_t>(shell.box[1][2] - z0 + 1);
  const std::size_t budget = kZIndexEntriesPerTriangle * m.triangles.size() + rows;
  int shift = 0;
  while ((rows >> shift) > 1 && zIndexEntries(shell, shift) > budget)
    ++shift;
  shell.zShift = shift;
  const std::size_t groups = ((rows - 1) >> shift) + 1;
  auto groupRange = [&](const std::array<Index, 3>& t)
  {
    const auto [lo, hi] = std::minmax({ m.points[t[0]][2], m.points[t[1]][2], m.points[t[2]][2] });
    return std::make_pair(
      static_cast<std::size_t>((lo - z0) >> shift), static_cast<std::size_t>((hi - z0) >> shift));
  };
  shell.zStart.assign(groups + 1, 0);
  for (const auto& t : m.triangles)
  {
    const auto [lo, hi] = groupRange(t);
    for (std::size_t g = lo; g <= hi; ++g)
      ++shell.zStart[g + 1];
  }
  for (std::size_t n = 0; n < groups; ++n)
    shell.zStart[n + 1] += shell.zStart[n];
  shell.byZ.resize(shell.zStart[groups]);
  std::vector<std::size_t> next(shell.zStart.begin(), shell.zStart.end() - 1);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
  {
    const auto [lo, hi] = groupRange(m.triangles[t]);
    for (std::size_t g = lo; g <= hi; ++g)
      shell.byZ[next[g]++] = static_cast<Index>(t);
  }
}

constexpr std::uint32_t kSideQueriesBeforeIndex = 4;

/// sideOf for one shell whose box holds p's row (sideOf for H checks): the triangles scanned
/// are, once the shell is asked often, only those spanning the group of the integer z-row
/// floor(p_z / k), a superset of those behindOrBeside keeps (a triangle whose z-range meets
/// p_z / k holds floor(p_z / k) in it, its corners being integers). The same exact tests
/// decide.
int sideOf(const Shell& shell, const LatticePoint& p, std::int64_t k)
{
  if (shell.sideQueries < kSideQueriesBeforeIndex && ++shell.sideQueries == kSideQueriesBeforeIndex)
    indexByZ(shell);
  if (shell.sideQueries < kSideQueriesBeforeIndex)
    return sideOf(shell.mesh, p, k);
  const std::int64_t row = floorDiv(p[2], k) - shell.box[0][2];
  if (row < 0 || row > shell.box[1][2] - shell.box[0][2])
    return sideOf(shell.mesh, p, k);
  const auto group = static_cast<std::size_t>(row >> shell.zShift);
  int parity = 0;
  for (std::size_t n = shell.zStart[group]; n < shell.zStart[group + 1]; ++n)
    if (!crossesBeyond(shell.mesh, shell.mesh.triangles[shell.byZ[n]], p, k, parity))
      return 0;
  return parity ? 1 : -1;
}

/// sideOf for H from its shells: the parity of the crossings is the sum of the shells'; those
/// whose box misses p's row or ends before p are not crossed (as in sideOf).
int sideOf(const ShelledSurface& surface, const LatticePoint& p, std::int64_t k)
{
  bool inside = false;
  for (const Shell& shell : surface.shells)
  {
    const LatticeBox& b = shell.box;
    if (p[0] > k * b[1][0] || p[1] < k * b[0][1] || p[1] > k * b[1][1] || p[2] < k * b[0][2] ||
      p[2] > k * b[1][2])
      continue;
    const int side = sideOf(shell, p, k);
    if (side == 0)
      return 0;
    inside = inside != (side > 0);
  }
  return inside ? 1 : -1;
}

/// Whether every shell of a closed embedded mesh faces away from the solid it bounds, tested
/// exactly: six times a shell's signed volume (Shell::volume, the sum of det(a, b, c) over its
/// triangles, integer) is positive when it is oriented outwards, and a shell nested in an odd
/// number of others bounds a void, so it must face into it (negative), one nested in an even
/// number (none: an outer shell; two: an island in a void) outwards. The shells are apart (no
/// shared point, no crossing), so a shell lies inside another exactly when one of its points
/// does (exact ray parity, sideOf). Stricter than CGAL's does_bound_a_volume, which also
/// accepts a mesh whose shells are all turned over; unlike the closedness, manifoldness and
/// reversion checks, it sees a shell turned over whole (the ray parity of the reversion does not).
bool shellsFaceOutward(const std::vector<Shell>& shells)
{
  for (std::size_t i = 0; i < shells.size(); ++i)
  {
    if (shells[i].volume == 0)
      return false;
    const LatticePoint& p = shells[i].mesh.points[0];
    bool nestedOddly = false;
    for (std::size_t j = 0; j < shells.size(); ++j)
    {
      const LatticeBox& b = shells[j].box;
      if (j == i || p[0] < b[0][0] || p[0] > b[1][0] || p[1] < b[0][1] || p[1] > b[1][1] ||
        p[2] < b[0][2] || p[2] > b[1][2])
        continue;
      const int side = sideOf(shells[j], p, 1);
      if (side == 0)
        return false; // shells that touch: not embedded
      nestedOddly = nestedOddly != (side > 0);
    }
    if ((shells[i].volume > 0) == nestedOddly)
      return false;
  }
  return true;
}

/// The surface's triangles in their order, without those that behindOrBeside(., p, 1) skips for
/// every lattice point p of the box: box[0] <= p <= box[1] makes max_x < lo_x imply max_x < p_x,
/// and likewise max_y < lo_y, min_y > hi_y and the same along z, so sideOf(., p, 1) on the rest
/// gives the same answer for every point of the box as on the whole surface. Locating each of a
/// prism's points against every triangle of the part of H the join changed (on the aneurism
/// mostly the vessels' main shell, tens of thousands of triangles) was most of the check.
std::vector<std::array<Index, 3>> trianglesAheadOf(const LatticeMesh& surface,
  const std::array<LatticePoint, 2>& box)
{
  std::vector<std::array<Index, 3>> near;
  for (const auto& tri : surface.triangles)
  {
    const LatticePoint& a = surface.points[tri[0]];
    const LatticePoint& b = surface.points[tri[1]];
    const LatticePoint& c = surface.points[tri[2]];
    bool skipped = std::max({ a[0], b[0], c[0] }) < box[0][0];
    for (int axis = 1; axis < 3 && !skipped; ++axis)
      skipped = std::max({ a[axis], b[axis], c[axis] }) < box[0][axis] ||
        std::min({ a[axis], b[axis], c[axis] }) > box[1][axis];
    if (!skipped)
      near.push_back(tri);
  }
  return near;
}

/// Whether every lattice point of the closed prism P lies on the right side of `joined`, the
/// part of H that P changed after P was cut out of it or added to it (no object centre outside,
/// no background centre inside, off the grid included), with the new sides of those in the grid;
/// `reversed`: P lies inside the other shells of H, so a point inside the part is outside H
/// (changedPart). The solid changes only inside the closed P, so a lattice point outside P keeps
/// its side (a neighbourhood of it misses P); P's open interior holds no lattice point, but a
/// centre on its boundary can change side, so each is located again (exact ray parity) instead
/// of every point of the grid.
bool prismKeepsSeparation(const LatticeMesh& joined,
  bool reversed,
  const CellList& prism,
  const BitVolume& objects,
  std::vector<std::pair<std::size_t, std::uint8_t>>& sides)
{
  const Dims d = objects.dims();
  const std::vector<std::array<Index, 3>> near = trianglesAheadOf(joined, boxOf(prism));
  bool ok = true;
  forEachPointIn(prism,
    false,
    [&](const LatticePoint& p)
    {
      if (!ok)
        return;
      const int side = reversed ? -sideOf(joined, near, p, 1) : sideOf(joined, near, p, 1);
      const bool object = voxelClass(objects, p);
      if ((object && side < 0) || (!object && side > 0))
        ok = false;
      else if (inGrid(d, p))
        sides.emplace_back(gridIndex(d, p), side > 0 ? Inside : side == 0 ? On : Outside);
    });
  return ok;
}

bool boxesMeet(const LatticeBox& a, const LatticeBox& b)
{
  for (int k = 0; k < 3; ++k)
    if (a[1][k] < b[0][k] || b[1][k] < a[0][k])
      return false;
  return true;
}

/// The shells of H that the closed P meets (exact separating axes against their triangles in
/// P's box).
std::vector<bool> shellsMeeting(const std::vector<Shell>& shells, const CellList& prism)
{
  const LatticeBox box = boxOf(prism);
  std::vector<bool> met(shells.size(), false);
  for (std::size_t i = 0; i < shells.size(); ++i)
  {
    if (!boxesMeet(shells[i].box, box))
      continue;
    const LatticeMesh& m = shells[i].mesh;
    for (const auto& t : m.triangles)
    {
      const std::array<LatticePoint, 3> c{ m.points[t[0]], m.points[t[1]], m.points[t[2]] };
      LatticeBox b{ c[0], c[0] };
      for (const auto& p : c)
        for (int k = 0; k < 3; ++k)
        {
          b[0][k] = std::min(b[0][k], p[k]);
          b[1][k] = std::max(b[1][k], p[k]);
        }
      if (boxesMeet(b, box) && meetsConvex(prism, c, true))
      {
        met[i] = true;
        break;
      }
    }
  }
  return met;
}

/// Whether p lies inside an odd number of the shells not flagged in `skip` (p on none of them).
bool insideOtherShells(const std::vector<Shell>& shells,
  const std::vector<bool>& skip,
  const LatticePoint& p)
{
  bool inside = false;
  for (std::size_t i = 0; i < shells.size(); ++i)
  {
    // sideOf's ray towards +x stays in p's row: a shell whose box misses the row or ends
    // before p is not crossed.
    const LatticeBox& b = shells[i].box;
    if (skip[i] || p[0] > b[1][0] || p[1] < b[0][1] || p[1] > b[1][1] || p[2] < b[0][2] ||
      p[2] > b[1][2])
      continue;
    inside = inside != (sideOf(shells[i], p, 1) > 0);
  }
  return inside;
}

/// The part of H that a Boolean with the prism P can change: the shells that the closed P meets
/// (flagged in `changed`) as one mesh, reversed when P lies inside an odd number of the other
/// shells (`reversed`).
///
/// Why the Boolean of the part is the Boolean of H (so that a join costs a corefinement of the
/// shells it joins, not of all of H, and its checks look at those shells only). The solid of H
/// is the set of points inside an odd number of its shells. The other shells miss the closed P
/// (each triangle of theirs strictly apart from it) and P is connected, so the parity c of the
/// other shells is one constant on a neighbourhood of P; it is c on each shell of the part too
/// (checked below; it holds for every shell that meets P). Near P and the part, the solid of H
/// is then the part's solid (c = 0: the part bounds a volume as it is oriented) or its
/// complement (c = 1: the reversed part bounds the complement, and cutting P out of H is adding
/// P to it, and back); away from them nothing changes. So H op P is (part op P) with the other
/// shells, which miss it (it lies in the part and the boundary of P, both apart from them): H
/// op P is embedded exactly when part op P is, its shells and Euler characteristic change as
/// the part's do, and a point of P lies inside H op P exactly when it lies inside part op P,
/// or outside when c = 1. Should the parity differ on a shell of the part (it cannot when the
/// separating axes are exact), the part is all of H.
struct ChangedPart
{
  std::vector<bool> changed;
  LatticeMesh mesh;
  bool reversed = false;
};

ChangedPart changedPart(const std::vector<Shell>& shells, const CellList& prism)
{
  ChangedPart part;
  part.changed = shellsMeeting(shells, prism);
  part.reversed = insideOtherShells(shells, part.changed, prism.vertices[0]);
  for (std::size_t i = 0; i < shells.size(); ++i)
    if (part.changed[i] &&
      insideOtherShells(shells, part.changed, shells[i].mesh.points[0]) != part.reversed)
    {
      part.changed.assign(shells.size(), true);
      part.reversed = false;
      break;
    }
  for (std::size_t i = 0; i < shells.size(); ++i)
    if (part.changed[i])
      part.mesh.append(shells[i].mesh, part.reversed);
  return part;
}

/// Whether the prism may join a shell by a Boolean, from the cheap tests: it runs through H's
/// solid (a cut) or through the space between two pieces (a join), as its centroid tells, and
/// no edge of it crosses a triangle of H off the lattice (a Boolean latticeBoolean refuses,
/// nearly all the prisms refused on the Al cartoon and the headsq bone), found from the
/// triangles in P's box, without the corefinement.
bool worthABoolean(const ShelledSurface& surface,
  const std::vector<Shell>& near,
  const CellList& prism,
  bool cut)
{
  LatticePoint centroid{ 0, 0, 0 };
  for (const auto& v : prism.vertices)
    for (int a = 0; a < 3; ++a)
      centroid[a] += v[a];
  const auto n = static_cast<std::int64_t>(prism.vertices.size());
  return sideOf(surface, centroid, n) == (cut ? 1 : -1) && !booleanLeavesTheLattice(near, prism);
}

/// The exact union (unite) or difference of a part of H and a prism, computed near the prism
/// where latticeBooleanNear can tell, else by the whole Boolean; false when refused.
bool booleanWithPrism(const LatticeMesh& part,
  const CellList& prism,
  bool unite,
  LatticeMesh& result)
{
  const NearBoolean near = latticeBooleanNear(part, prism, unite, result);
  if (near != NearBoolean::Unknown)
    return near == NearBoolean::Done;
  const LatticeMesh hull = triangulateHull(prism);
  return unite ? latticeUnion(part, hull, result, Operands::Embedded)
               : latticeDifference(part, hull, result, Operands::Embedded);
}

/// H with the prism cut out (a void or a handle) or added (a piece), kept only when the exact
/// Boolean is a closed 2-manifold with lattice corners, `shells` shells (one less for a join,
/// as many for a handle or a dent) and an Euler characteristic `eulerDrop` lower (2: a tube;
/// 0: the dent of a chain, joinByChain), and every lattice point of P stays on its class's side
/// (prismKeepsSeparation). The Boolean and the checks are those of the part of H that P meets
/// (changedPart says why that is H's). A Boolean that fails, or throws, rejects this prism only.
bool joinAlongPrism(Context& ctx,
  const CellList& prism,
  bool cut,
  std::size_t shells,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where,
  long eulerDrop = 2)
{
  // The part was embedded and the Boolean changed it only inside P, so only triangles meeting
  // P's box can cross (the operands are not tested again: that test of a large operand costs
  // about as much as the corefinement).
  const std::array<LatticePoint, 2> box = boxOf(prism);
  const ChangedPart part = changedPart(surface.shells, prism);
  // A Boolean bound to fail costs no corefinement (it still counts as one tried: tryPrisms).
  if (creaseLeavesTheLattice(part.mesh, prism))
    return false;
  const auto others =
    static_cast<std::size_t>(std::count(part.changed.begin(), part.changed.end(), false));
  LatticeMesh joined;
  std::vector<Shell> pieces;
  std::vector<std::pair<std::size_t, std::uint8_t>> sides;
  try
  {
    // Reversed, the part bounds the complement of H's solid near P: cutting is adding. The
    // Boolean from the part's triangles near P first (the part is mostly the vessel's main
    // shell on the aneurism: the whole corefinement costs all of it for every prism tried).
    const bool unite = cut == part.reversed;
    if (edgeCrossingLeavesTheLattice(part.mesh, prism, unite) ||
      !booleanWithPrism(part.mesh, prism, unite, joined))
      return false;
    if (part.reversed)
      for (auto& t : joined.triangles)
        std::swap(t[1], t[2]);
    pieces = shellsOf(joined);
    if (pieces.size() + others != shells ||
      eulerCharacteristic(joined) + eulerDrop != eulerCharacteristic(part.mesh) ||
      !isEmbeddedWithin(joined, box[0], box[1]) ||
      !prismKeepsSeparation(joined, part.reversed, prism, ctx.objects, sides))
      return false;
  }
  catch (const std::exception&)
  {
    return false; // CGAL refused the operands or the result: try the next prism
  }
  recordPlanes(ctx, prism, cut ? 1 : 2);
  surface.replace(part.changed, std::move(pieces));
  for (const auto& [index, side] : sides)
    where[index] = side;
  return true;
}

/// The prisms tried per shell and round, nearest first (each costs an exact Boolean and a check;
/// those worthABoolean rejects are not counted).
constexpr std::size_t kPrismsTried = 48;

/// The box of every corner of the candidates: each prism's box lies in it.
LatticeBox boxOfCandidates(const PrismPairs& pairs)
{
  LatticeBox all{ pairs.first[0][0], pairs.first[0][0] };
  for (const auto* side : { &pairs.first, &pairs.second })
    for (const auto& t : *side)
      for (const auto& p : t)
        for (int a = 0; a < 3; ++a)
        {
          all[0][a] = std::min(all[0][a], p[a]);
          all[1][a] = std::max(all[1][a], p[a]);
        }
  return all;
}

/// Cuts out (`cut`) or adds the first of the prisms of `pairs` that joinAlongPrism keeps with
/// `shells` shells: those whose open interior misses H first (nearest first among them), then
/// the others; the cheap tests of worthABoolean run only until kPrismsTried prisms have passed
/// them. Each hull is made once, when the first round reaches it.
bool tryPrisms(Context& ctx,
  const PrismPairs& pairs,
  bool cut,
  std::size_t shells,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where)
{
  const std::size_t n = pairs.size();
  if (n == 0)
    return false;
  // The shells near the candidates (a join ends the loop, so H does not change under them).
  // Every prism's box lies in the candidates' box, so the tests find the same triangles here.
  const std::vector<Shell> near = shellsInBox(surface.shells, boxOfCandidates(pairs));
  enum : std::uint8_t
  {
    Unmade,
    NoPrism,
    Misses,
    Crosses
  };
  std::vector<std::uint8_t> state(n, Unmade);
  std::vector<CellList> prisms(n);
  std::size_t booleans = 0;
  for (const std::uint8_t round : { Misses, Crosses })
    for (std::size_t k = 0; k < n && booleans < kPrismsTried; ++k)
    {
      if (!pairs.offered(k))
        continue;
      if (state[k] == Unmade)
      {
        std::optional<CellList> prism = emptyPrism(pairs, k);
        state[k] = !prism ? NoPrism : prismMissesSurface(*prism, near) ? Misses : Crosses;
        if (prism)
          prisms[k] = std::move(*prism);
      }
      if (state[k] != round)
        continue;
      if (ctx.exec.stopRequested())
        throw std::runtime_error("aborted");
      if (!worthABoolean(surface, near, prisms[k], cut))
        continue;
      ++booleans;
      if (joinAlongPrism(ctx, prisms[k], cut, shells, surface, where))
        return true;
    }
  return false;
}

/// The shells of H other than shell s, as one mesh.
LatticeMesh restOfH(const std::vector<Shell>& shells, std::size_t s)
{
  LatticeMesh rest;
  for (std::size_t o = 0; o < shells.size(); ++o)
    if (o != s)
      rest.append(shells[o].mesh, false);
  return rest;
}

/// Joins the shell to the rest of H by one of the prisms between the `count` nearest empty
/// triangles on each side of the crossing (see prismsAt for `tried`); false when none joins.
bool joinAtCrossing(Context& ctx,
  const std::vector<Shell>& shells,
  std::size_t s,
  const std::vector<LatticePoint>& crossing,
  std::size_t count,
  std::size_t tried,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where)
{
  const LatticeMesh rest = restOfH(shells, s);
  return tryPrisms(ctx,
    prismsAt(shells[s].mesh, rest, crossing, count, tried),
    shells[s].volume < 0,
    shells.size() - 1,
    surface,
    where);
}

/// The chains of two prisms tried per void whose single prisms all failed (each one or two
/// exact Booleans).
constexpr std::size_t kChainsTried = 8;

/// The corners of the middle triangles of the chains: at most this many, nearest first (560
/// triangles; the hollow balls have 10 to 16 near their crossing).
constexpr std::size_t kChainCorners = 16;

/// The lattice points strictly inside H within one step (in each coordinate) of a centre of the
/// crossing, the kChainCorners nearest to its middle: the corners of the middle triangles.
std::vector<LatticePoint> chainCorners(const std::vector<std::uint8_t>& where,
  const Dims& d,
  const std::vector<LatticePoint>& crossing)
{
  std::set<LatticePoint> found;
  LatticePoint sum{ 0, 0, 0 };
  for (const LatticePoint& c : crossing)
  {
    for (int a = 0; a < 3; ++a)
      sum[a] += c[a];
    for (std::int64_t z = c[2] - 1; z <= c[2] + 1; ++z)
      for (std::int64_t y = c[1] - 1; y <= c[1] + 1; ++y)
        for (std::int64_t x = c[0] - 1; x <= c[0] + 1; ++x)
          if (inGrid(d, { x, y, z }) && where[gridIndex(d, { x, y, z })] == Inside)
            found.insert({ x, y, z });
  }
  std::vector<LatticePoint> corners(found.begin(), found.end());
  const auto m = static_cast<std::int64_t>(crossing.size());
  std::stable_sort(corners.begin(),
    corners.end(),
    [&](const LatticePoint& p, const LatticePoint& q)
    { return scaledDistance(p, 1, sum, m) < scaledDistance(q, 1, sum, m); });
  if (corners.size() > kChainCorners)
    corners.resize(kChainCorners);
  return corners;
}

/// The side of the plane the triangle lies on: 1 or -1 when it lies in that closed side and
/// not in the plane, 0 otherwise. A corner may touch the plane, so M need not be a whole face
/// of the hull of each triangle with M, and the two hulls may share more than M; the chain is
/// kept only when each cut passes joinAlongPrism's checks. (Requiring every corner strictly
/// off the plane leaves 4 of the 72 hollow balls of HollowBallsWithOffCentreTunnels without
/// the object's topology.)
int sideOfPlane(const FacePlane& plane, const std::array<LatticePoint, 3>& t)
{
  bool below = false, above = false;
  for (const auto& p : t)
  {
    below = below || plane.evaluate(p) < 0;
    above = above || plane.evaluate(p) > 0;
  }
  return above == below ? 0 : above ? 1 : -1;
}

/// conv(t + m) when it is solid with no lattice point in its open interior and its open
/// interior misses H (tests local to its box; worthABoolean, which scans H, is left for the
/// prisms that are cut).
std::optional<CellList> emptyPrismMissingH(const std::array<LatticePoint, 3>& t,
  const std::array<LatticePoint, 3>& m,
  const ShelledSurface& surface)
{
  CellList prism = convexHull({ t[0], t[1], t[2], m[0], m[1], m[2] });
  bool empty = prism.dimension == 3;
  if (empty)
    forEachPointIn(prism, true, [&](const LatticePoint&) { empty = false; });
  if (!empty || !prismMissesSurface(prism, surface.shells))
    return std::nullopt;
  return prism;
}

/// Cuts the chain out of H: P1 first (a dent: as many shells, the same Euler characteristic),
/// then the first of the P2 that joins (joinAlongPrism checks each); H unchanged unless one
/// does.
bool cutChain(Context& ctx,
  const CellList& first,
  const std::vector<CellList>& second,
  std::size_t shells,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where)
{
  const auto planes = ctx.planeLevel;
  ShelledSurface dented = surface;
  std::vector<std::uint8_t> sides = where;
  if (joinAlongPrism(ctx, first, true, shells, dented, sides, 0))
    for (const CellList& p2 : second)
      if (joinAlongPrism(ctx, p2, true, shells - 1, dented, sides))
      {
        surface = std::move(dented);
        where = std::move(sides);
        return true;
      }
  ctx.planeLevel = planes;
  return false;
}

/// A void whose shell reaches the crossing only in long thin triangles, so that every prism
/// between one of them and a triangle of the rest of H holds a lattice point (the hollow balls
/// of R 8 to 10 with a 1 wide off-centre tunnel: the void's shell ends in a cone whose apex is
/// the tunnel's last centre, a lattice plane of object centres between it and the hull face
/// beyond): a chain of two prisms through a middle triangle M of lattice points strictly inside
/// H near the crossing, P1 = conv(T1 + M) from an empty triangle T1 of the void's shell and
/// P2 = conv(M + T2) to one T2 of the rest of H (the 12 nearest of each), M a face of both,
/// each with no lattice point in its open interior and its open interior missing H.
bool joinByChain(Context& ctx,
  const std::vector<Shell>& shells,
  std::size_t s,
  const std::vector<LatticePoint>& crossing,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where)
{
  const LatticeMesh rest = restOfH(shells, s);
  const auto first = emptyTrianglesNear(shells[s].mesh, crossing, kTrianglesNear);
  const auto second = emptyTrianglesNear(rest, crossing, kTrianglesNear);
  const std::vector<LatticePoint> c = chainCorners(where, ctx.objects.dims(), crossing);
  std::size_t chains = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = i + 1; j < c.size(); ++j)
      for (std::size_t k = j + 1; k < c.size(); ++k)
      {
        if (ctx.exec.stopRequested())
          throw std::runtime_error("aborted");
        const std::array<LatticePoint, 3> m{ c[i], c[j], c[k] };
        const FacePlane plane = planeThrough(m[0], m[1], m[2]);
        if (plane.normal == LatticePoint{ 0, 0, 0 })
          continue;
        // The P2 beyond M from each side, made only once a P1 from that side is found (the
        // prisms from the long thin triangles of the void's shell mostly hold a lattice point).
        std::optional<std::vector<CellList>> beyond[2];
        for (const auto& t1 : first)
        {
          const int side = sideOfPlane(plane, t1);
          if (side == 0)
            continue;
          const auto p1 = emptyPrismMissingH(t1, m, surface);
          if (!p1 || !worthABoolean(surface, surface.shells, *p1, true))
            continue;
          auto& p2 = beyond[side > 0];
          if (!p2)
          {
            p2.emplace();
            for (const auto& t2 : second)
              if (sideOfPlane(plane, t2) == -side)
                if (auto p = emptyPrismMissingH(t2, m, surface))
                  if (worthABoolean(surface, surface.shells, *p, true))
                    p2->push_back(std::move(*p));
          }
          if (p2->empty())
            continue;
          if (cutChain(ctx, *p1, *p2, shells.size(), surface, where))
            return true;
          if (++chains == kChainsTried)
            return false;
        }
      }
  return false;
}

/// Joins one shell of H to the rest where the object's or the background's face-connected
/// centres cross it (see above), from the nearest empty triangles and, when none of their
/// prisms joins, from more of them, and a void then by a chain of two prisms; false when no
/// shell could be joined.
bool joinOneShell(Context& ctx,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where,
  std::vector<std::uint8_t>& mine,
  VoidSearch& search,
  std::set<LatticePoint>& failed)
{
  // A join changes the shells only when it returns true, and then this returns at once.
  const std::vector<Shell>& shells = surface.shells;
  if (shells.size() < 2)
    return false;
  const Dims d = ctx.objects.dims();
  for (std::size_t s = 0; s < shells.size(); ++s)
  {
    if (ctx.exec.stopRequested())
      throw std::runtime_error("aborted");
    const LatticePoint key =
      *std::min_element(shells[s].mesh.points.begin(), shells[s].mesh.points.end());
    if (failed.count(key))
      continue;
    failed.insert(key);
    std::vector<LatticePoint> crossing;
    if (shells[s].volume < 0)
    {
      // `mine` is all 0 but where markShell flags the shell's box, cleared after the search.
      const LatticeBox box = gridBoxOf(shells[s], d);
      markShell(shells[s].mesh, d, 1, 2, mine);
      crossing = voidCrossing(ctx.objects, where, mine, box, search);
      forEachInBox(box, [&](const LatticePoint& p) { mine[gridIndex(d, p)] = 0; });
    }
    else
      crossing = pieceCrossing(ctx.objects, shells[s].mesh);
    if (crossing.empty())
      continue;
    if (joinAtCrossing(ctx, shells, s, crossing, kTrianglesNear, 0, surface, where) ||
      joinAtCrossing(
        ctx, shells, s, crossing, kMoreTrianglesNear, kTrianglesNear, surface, where) ||
      (shells[s].volume < 0 && joinByChain(ctx, shells, s, crossing, surface, where)))
    {
      // A shell that failed stays failed although a later join may open a way for it: trying
      // the failed ones again once after a later join did not join a single further shell on
      // the hollow balls (their voids' prisms still crossed H off the lattice) and cost
      // Booleans on the Al cartoon.
      failed.erase(key);
      return true;
    }
  }
  return false;
}

/// Puts `changed` (made by `count` changes to `surface`) in the place of `surface` when there
/// was a change and it still separates; otherwise keeps `surface` and gives the face planes back
/// the levels they had before (`planes`). Returns the changes kept.
int keepIfSeparates(Context& ctx,
  int count,
  LatticeMesh&& changed,
  const std::map<FacePlane, int>& planes,
  LatticeMesh& surface)
{
  if (count == 0 || !separatesAfterLocalChecks(ctx.objects, changed))
  {
    ctx.discardedChanges += count;
    ctx.planeLevel = planes;
    return 0;
  }
  surface = std::move(changed);
  return count;
}

/// Joins shells while one can be joined; returns how many were.
int joinShells(Context& ctx, LatticeMesh& surface)
{
  if (shellsOf(surface).size() < 2)
    return 0; // nothing to join: the grid is not located at all
  int joined = 0;
  std::set<LatticePoint> failed;
  ShelledSurface repaired(surface);
  const auto planes = ctx.planeLevel;
  std::vector<std::uint8_t> where = whereInGrid(surface, ctx.objects.dims());
  std::vector<std::uint8_t> mine(where.size(), 0);
  VoidSearch search(where.size());
  while (joinOneShell(ctx, repaired, where, mine, search, failed))
    ++joined;
  // Checked once at the end, without a self-intersection test of the whole surface
  // (separatesAfterLocalChecks).
  return keepIfSeparates(ctx, joined, repaired.takeMesh(), planes, surface);
}

/// The contribution to the Euler characteristic of the union of the closed voxel cubes of the
/// cells whose lowest corner is a grid corner, from the 8 voxels about that corner (bit
/// dx + 2 dy + 4 dz for the voxel at corner - 1 + (dx, dy, dz)): the corner itself (any voxel),
/// its edges towards +x, +y, +z (the 4 voxels on that side), its faces (the 2 voxels on both
/// sides) and its cube (the one voxel on all three).
int cornerEuler(unsigned config)
{
  auto any = [&](unsigned mask, unsigned value)
  {
    for (unsigned b = 0; b < 8; ++b)
      if ((b & mask) == value && (config >> b & 1))
        return 1;
    return 0;
  };
  return any(0, 0) - any(1, 1) - any(2, 2) - any(4, 4) + any(3, 3) + any(5, 5) + any(6, 6) -
    any(7, 7);
}

/// Whether the 8 voxels about a grid corner (bits as in cornerEuler) are not well-composed:
/// two diagonally opposite voxels alone (of either class), or a face of the block whose two
/// diagonals hold different classes (its low faces; every face is the low face of some block).
bool criticalCorner(unsigned config)
{
  const std::size_t count = std::bitset<8>(config).count();
  for (unsigned k = 0; k < 4; ++k)
  {
    const bool a = config >> k & 1, b = config >> (7 - k) & 1;
    if ((count == 2 && a && b) || (count == 6 && !a && !b))
      return true;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    // u and w: the indices of the voxels one step along the face's two axes from voxel 0.
    const unsigned u = 1u << ((axis + 1) % 3), w = 1u << ((axis + 2) % 3);
    const bool s0 = config & 1, s1 = config >> u & 1, s2 = config >> (u | w) & 1,
               s3 = config >> w & 1;
    if (s0 == s2 && s1 == s3 && s0 != s1)
      return true;
  }
  return false;
}

} // namespace

bool shellsFaceOutward(const LatticeMesh& surface)
{
  return shellsFaceOutward(shellsOf(surface));
}

std::optional<long> wellComposedBoundaryEuler(const BitVolume& objects, const Execution& exec)
{
  std::array<int, 256> euler;
  std::array<bool, 256> critical;
  for (unsigned c = 0; c < 256; ++c)
  {
    euler[c] = cornerEuler(c);
    critical[c] = criticalCorner(c);
  }
  const Dims d = objects.dims();
  long chi = 0;
  for (std::int32_t z = 0; z <= d[2]; ++z)
  {
    if (exec.stopRequested())
      throw std::runtime_error("aborted");
    for (std::int32_t y = 0; y <= d[1]; ++y)
      for (std::int32_t x = 0; x <= d[0]; ++x)
      {
        unsigned config = 0;
        for (unsigned b = 0; b < 8; ++b)
          config |= static_cast<unsigned>(voxelClass(
                      objects, { x - 1 + (b & 1), y - 1 + (b >> 1 & 1), z - 1 + (b >> 2) }))
            << b;
        if (critical[config])
          return std::nullopt;
        chi += euler[config];
      }
  }
  return 2 * chi;
}

namespace
{

/// The face-connected components of a voxel set: how many, and how many of them reach the
/// border of the grid.
std::array<long, 2> componentCount(const BitVolume& set, bool plane)
{
  CUDB cudb;
  Components comps;
  buildCUDBComponents(
    plane ? extractEVM2D(set) : extractEVM(set), Connectivity::Face, Execution(), cudb, comps);
  // A component reaches the border when one of its boxes does: no labels painted.
  const Dims d = set.dims();
  std::vector<bool> border(static_cast<std::size_t>(comps.count) + 1, false);
  for (std::size_t b = 0; b < cudb.boxes.size(); ++b)
  {
    const Box& box = cudb.boxes[b];
    bool atBorder = false;
    for (int a = 0; a < 3; ++a)
      atBorder |= box.lo[a] == 0 || box.hi[a] == d[a];
    if (atBorder)
      border[comps.boxLabel[b]] = true;
  }
  return { static_cast<long>(comps.count),
    static_cast<long>(std::count(border.begin() + 1, border.end(), true)) };
}

/// The Euler characteristic of the object's boundary, counted once; none when the object is not
/// well-composed (see wellComposedBoundaryEuler).
const std::optional<long>& objectEuler(Context& ctx)
{
  if (!ctx.euler)
    ctx.euler = wellComposedBoundaryEuler(ctx.objects, ctx.exec);
  return *ctx.euler;
}

/// The number of surfaces of the object's boundary, counted once: its face-connected
/// components and those of the background that do not reach the grid's border.
long objectSurfaces(Context& ctx)
{
  if (ctx.surfaces < 0)
  {
    const Dims d = ctx.objects.dims();
    BitVolume background(d[0], d[1], d[2]);
    for (std::int32_t z = 0; z < d[2]; ++z)
      for (std::int32_t y = 0; y < d[1]; ++y)
        for (std::int32_t x = 0; x < d[0]; ++x)
          background.set(x, y, z, !ctx.objects.get(x, y, z));
    const std::array<long, 2> voids = componentCount(background, d[2] == 1);
    ctx.surfaces = componentCount(ctx.objects, d[2] == 1)[0] + voids[0] - voids[1];
  }
  return ctx.surfaces;
}

/// Missing handles (see the header): the walls of H between two face-neighbouring background
/// centres, neither inside H and one on it, whose segment's midpoint lies strictly inside H.
/// At most `limit`, in grid order; `skip` holds those already tried.
std::vector<std::array<LatticePoint, 2>> wallCrossings(const BitVolume& objects,
  const LatticeMesh& surface,
  const std::vector<std::uint8_t>& where,
  const std::set<std::array<LatticePoint, 2>>& skip,
  std::size_t limit)
{
  const Dims d = objects.dims();
  std::vector<std::array<LatticePoint, 2>> found;
  for (std::int32_t z = 0; z < d[2]; ++z)
    for (std::int32_t y = 0; y < d[1]; ++y)
      for (std::int32_t x = 0; x < d[0] && found.size() < limit; ++x)
      {
        const LatticePoint p{ x, y, z };
        if (where[gridIndex(d, p)] != On || voxelClass(objects, p))
          continue;
        for (int k = 0; k < 6 && found.size() < limit; ++k)
        {
          const LatticePoint q = step(p, k);
          if (!inGrid(d, q) || voxelClass(objects, q) || where[gridIndex(d, q)] == Inside ||
            (where[gridIndex(d, q)] == On && q < p) || skip.count({ p, q }))
            continue;
          if (sideOf(surface, { p[0] + q[0], p[1] + q[1], p[2] + q[2] }, 2) > 0)
            found.push_back({ p, q });
        }
      }
  return found;
}

/// Cuts one handle through H at a wall crossing: a prism conv(T1 + T2) between an empty
/// triangle of H near each of the two centres, cut out when H keeps its shells, its Euler
/// characteristic drops by 2 and every centre stays on its side (joinAlongPrism).
bool cutAtCrossing(Context& ctx,
  const std::array<LatticePoint, 2>& crossing,
  LatticeMesh& surface,
  std::vector<std::uint8_t>& where)
{
  ShelledSurface shelled(surface);
  const std::size_t shells = shelled.shells.size();
  for (const auto& [count, tried] : { std::array<std::size_t, 2>{ kTrianglesNear, 0 },
         std::array<std::size_t, 2>{ kMoreTrianglesNear, kTrianglesNear } })
  {
    const PrismPairs pairs{ emptyTrianglesNear(surface, { crossing[0] }, count),
      emptyTrianglesNear(surface, { crossing[1] }, count),
      tried };
    if (tryPrisms(ctx, pairs, true, shells, shelled, where))
    {
      surface = shelled.takeMesh();
      return true;
    }
  }
  return false;
}

/// The wall crossings tried per round of cutMissingHandles.
constexpr std::size_t kCrossingsTried = 16;

/// Missing handles (see the header): while H has the object's number of surfaces and a higher
/// Euler characteristic than its boundary (a well-composed object), handles are cut through the
/// walls that seal its tunnels. Returns how many; H unchanged when none was cut or the result
/// does not separate.
int cutMissingHandles(Context& ctx, LatticeMesh& surface)
{
  const std::optional<long>& target = objectEuler(ctx);
  if (!target || eulerCharacteristic(surface) <= *target ||
    static_cast<long>(shellsOf(surface).size()) != objectSurfaces(ctx))
    return 0;
  const auto planes = ctx.planeLevel;
  LatticeMesh cut = surface;
  std::vector<std::uint8_t> where = whereInGrid(cut, ctx.objects.dims());
  std::set<std::array<LatticePoint, 2>> failed;
  int cuts = 0;
  while (eulerCharacteristic(cut) > *target)
  {
    bool done = false;
    for (const auto& c : wallCrossings(ctx.objects, cut, where, failed, kCrossingsTried))
    {
      if (cutAtCrossing(ctx, c, cut, where))
      {
        done = true;
        break;
      }
      failed.insert(c);
    }
    if (!done)
      break;
    ++cuts;
  }
  return keepIfSeparates(ctx, cuts, std::move(cut), planes, surface);
}

/// One pass of the levels, with pits or with every level kept apart: true when H separates
/// (checked, see the header), its shells then joined and its missing handles cut.
bool solvePass(Context& ctx, ModifiedHull& r, bool pits)
{
  ctx.pits = pits;
  ctx.keptApart = 0;
  ctx.planeLevel.clear();
  try
  {
    r.surface = solveLevel(ctx, r.hull, nullptr, true, false, 0, r.degreeOfNonConvexity).mesh;
  }
  catch (const Unresolved& e)
  {
    r.failure = e.what();
    return false;
  }
  if (!separates(ctx.objects, r.surface))
  {
    r.failure = "the surface does not separate";
    return false;
  }
  r.complete = true;
  r.failure.clear();
  r.withoutPits = !pits;
  r.keptApart = ctx.keptApart;
  r.joinedShells = joinShells(ctx, r.surface);
  r.cutHandles = cutMissingHandles(ctx, r.surface);
  r.discardedChanges = ctx.discardedChanges;
  return true;
}

/// Whether H has the topology of the well-composed object's boundary: its Euler characteristic
/// and number of surfaces (one shell per surface).
bool hasTopology(Context& ctx, const LatticeMesh& surface)
{
  return eulerCharacteristic(surface) == *objectEuler(ctx) &&
    static_cast<long>(shellsOf(surface).size()) == objectSurfaces(ctx);
}

/// Topology of the second pass (see the header): when H from the pits, its shells joined and
/// its missing handles cut, has not the topology of the well-composed object's boundary (a
/// spurious handle, or a shell no prism joined), H with every level kept apart is made as well
/// and kept when it has. A ring of object voxels about a wide tunnel that a pit cut off comes
/// back as a torus of its own that one tube joins; kept apart, the ring stays part of its
/// level's solid.
void keepTheObjectsTopology(Context& ctx, ModifiedHull& r)
{
  if (!objectEuler(ctx) || hasTopology(ctx, r.surface))
    return;
  ModifiedHull apart = r;
  const auto planes = ctx.planeLevel;
  if (solvePass(ctx, apart, false) && hasTopology(ctx, apart.surface))
  {
    r = std::move(apart);
    r.handlePass = ModifiedHull::HandlePass::Kept;
    return;
  }
  ctx.planeLevel = planes;
  r.handlePass = ModifiedHull::HandlePass::Rejected;
}

/// The levels solved with pits and, when that leaves something unresolved or the result does
/// not separate, again with every level kept apart.
void solveAndCheck(Context& ctx, ModifiedHull& r)
{
  r.complete = false;
  if (solvePass(ctx, r, true))
  {
    keepTheObjectsTopology(ctx, r);
    return;
  }
  if (!solvePass(ctx, r, false))
    r.surface = triangulateHull(r.hull);
}

/// The component in its own box, whose corner is `lo` in the grid: its H lies in the hull of
/// its centres, so many small components do not each pay for the whole grid.
BitVolume inItsBox(const std::vector<LatticePoint>& component, LatticePoint& lo)
{
  lo = component[0];
  LatticePoint hi = component[0];
  for (const auto& p : component)
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  BitVolume part(static_cast<std::int32_t>(hi[0] - lo[0] + 1),
    static_cast<std::int32_t>(hi[1] - lo[1] + 1),
    static_cast<std::int32_t>(hi[2] - lo[2] + 1));
  for (const auto& p : component)
    part.set(static_cast<std::int32_t>(p[0] - lo[0]),
      static_cast<std::int32_t>(p[1] - lo[1]),
      static_cast<std::int32_t>(p[2] - lo[2]));
  return part;
}

/// One part of the object solved on its own (components first): its centres and the box that
/// holds its H (its hull's box, one voxel wider unless the hull is solid: a flat H is a prism
/// one step off its plane, a segment's a tetrahedron one step off its line).
struct ObjectPart
{
  std::vector<LatticePoint> points;
  BoxedHull extent;
};

ObjectPart partOf(std::vector<LatticePoint> points, CoplanarFaces coplanar)
{
  ObjectPart part;
  part.points = std::move(points);
  part.extent = BoxedHull(convexHull(rowEnds(part.points), coplanar));
  if (part.extent.hull.dimension < 3)
    for (int k = 0; k < 3; ++k)
      --part.extent.box[2 * k], ++part.extent.box[2 * k + 1];
  return part;
}

/// Whether the H of two parts may meet, or one hold a centre of the other: H of a solid part
/// lies in its hull (pits and handles are cut out of it, cavities and joins lie inside), so two
/// solid parts whose hulls share no point cannot; parts that are not solid are compared by
/// their boxes only.
bool partsMayMeet(const ObjectPart& a, const ObjectPart& b)
{
  const BoxedHull& p = a.extent;
  const BoxedHull& q = b.extent;
  for (int k = 0; k < 3; ++k)
    if (p.box[2 * k + 1] < q.box[2 * k] || q.box[2 * k + 1] < p.box[2 * k])
      return false;
  return p.hull.dimension < 3 || q.hull.dimension < 3 || hullsIntersect(p.hull, q.hull);
}

/// Parts that may meet, merged into one; false when none may.
bool mergeMeetingParts(std::vector<ObjectPart>& parts, CoplanarFaces coplanar)
{
  // sorted by the boxes' lower x, so that only boxes overlapping in x are compared
  std::sort(parts.begin(),
    parts.end(),
    [](const ObjectPart& a, const ObjectPart& b) { return a.extent.box[0] < b.extent.box[0]; });
  UnionFind classes(parts.size());
  bool merged = false;
  for (std::size_t i = 0; i < parts.size(); ++i)
    for (std::size_t j = i + 1;
         j < parts.size() && parts[j].extent.box[0] <= parts[i].extent.box[1];
         ++j)
      if (partsMayMeet(parts[i], parts[j]))
      {
        classes.unite(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
        merged = true;
      }
  if (!merged)
    return false;
  std::map<std::uint32_t, std::vector<LatticePoint>> unions;
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    auto& u = unions[classes.find(static_cast<std::uint32_t>(i))];
    u.insert(u.end(), parts[i].points.begin(), parts[i].points.end());
  }
  parts.clear();
  for (auto& [root, u] : unions)
    parts.push_back(partOf(std::move(u), coplanar));
  return true;
}

/// The object's components (vertex-connected, so that voxels touching at an edge or a corner
/// stay in one part and the touching rule decides there), merged until no two parts may meet
/// (when `mergeMeeting`); none for an object of one component.
std::vector<ObjectPart> separateParts(const std::vector<LatticePoint>& points,
  CoplanarFaces coplanar,
  bool mergeMeeting)
{
  std::vector<std::vector<LatticePoint>> components = componentsOf(points, false, true);
  if (components.size() < 2)
    return {}; // no parts to make
  std::vector<ObjectPart> parts;
  for (auto& c : components)
    parts.push_back(partOf(std::move(c), coplanar));
  while (mergeMeeting && parts.size() > 1 && mergeMeetingParts(parts, coplanar))
    continue;
  return parts;
}

ModifiedHull modifyHull(const BitVolume& objects,
  CoplanarFaces coplanar,
  const Execution& exec,
  bool componentsFirst);

int gridPlaneAxis(const std::vector<LatticePoint>& points);

/// For a segment off the axes' planes (no component of ab zero), an axis along which its
/// primitive direction ab / gcd has a component +-1; -1 when there is none or the segment lies
/// in an axis plane (the flat path's).
int unitStepAxis(const LatticePoint& ab)
{
  std::int64_t m = 0;
  for (int k = 0; k < 3; ++k)
    m = std::gcd(m, std::abs(ab[k]));
  int unit = -1;
  for (int k = 0; k < 3 && m > 0; ++k)
    if (ab[k] == 0)
      return -1;
    else if (std::abs(ab[k]) == m)
      unit = k;
  return unit;
}

/// Whether the part can have an H of its own: not a flat set in no plane of the grid's axes
/// nor a segment with no direction component +-1 (the corners their pyramids add may lie
/// beyond the part's box grown by one voxel, where another part may be).
bool partHasH(const ObjectPart& part)
{
  const CellList& hull = part.extent.hull;
  if (hull.dimension == 2)
    return gridPlaneAxis(part.points) >= 0;
  if (hull.dimension != 1)
    return true;
  return unitStepAxis(sub(hull.vertices[1], hull.vertices[0])) >= 0 ||
    gridPlaneAxis(part.points) >= 0;
}

/// Whether the part's H stays in the grid: a flat part's prism (or a segment's tetrahedron)
/// near the grid's side would put centres off the grid on H, which only a flat object's H may
/// (the whole object is then solved as one).
bool partInGrid(const ObjectPart& part, const Dims& d)
{
  for (int k = 0; k < 3; ++k)
    if (part.extent.box[2 * k] < 0 || part.extent.box[2 * k + 1] >= d[k])
      return false;
  return true;
}

/// H of one part alone (in the box of its centres, the rest of the object its background, not
/// split into parts again) appended to `together`, moved back into the grid, with the level
/// of each of its triangles (those of its own faces). False when that H is incomplete.
bool appendPartH(Context& ctx,
  const ObjectPart& part,
  const Execution& exec,
  ModifiedHull& r,
  LatticeMesh& together,
  std::vector<int>& levels)
{
  LatticePoint lo;
  ModifiedHull h = modifyHull(inItsBox(part.points, lo), ctx.coplanar, exec, false);
  if (!h.complete || h.surface.triangles.empty())
    return false;
  for (auto& p : h.surface.points)
    for (int k = 0; k < 3; ++k)
      p[k] += lo[k];
  const std::size_t base = levels.size();
  levels.resize(base + h.surface.triangles.size(), -1);
  for (const auto& f : h.faces)
    for (const Index t : f.triangles)
      levels[base + t] = f.level;
  together.append(h.surface, false);
  if (!h.failure.empty())
    r.failure += (r.failure.empty() ? "" : "; ") + h.failure; // a part's note stays
  r.joinedShells += h.joinedShells;
  r.cutHandles += h.cutHandles;
  r.discardedChanges += h.discardedChanges;
  r.keptApart += h.keptApart;
  r.degreeOfNonConvexity = std::max(r.degreeOfNonConvexity, h.degreeOfNonConvexity);
  return true;
}

/// Components first (see the header): when the object's components fall into several parts
/// that cannot meet, H is the union of the H of each part alone, kept when it separates (with
/// the object's topology when the object is well-composed); only otherwise is the object
/// solved as one, from the hull of all its components, which presses in every gap between
/// them level after level (the lobster at v >= 128: its 130 smaller components took 15.5 s of
/// CPU as one object, 3.2 s one by one). Each face keeps the level it has in its part's H (a
/// plane can hold a face of one part's hull and a pit's bottom in another). The parts share
/// [from, to] of the progress.
bool solveComponentsFirst(Context& ctx,
  ModifiedHull& r,
  double from,
  double to,
  bool mergeMeeting = true)
{
  const Dims d = ctx.objects.dims();
  std::vector<LatticePoint> points;
  for (std::int32_t z = 0; z < d[2]; ++z)
    for (std::int32_t y = 0; y < d[1]; ++y)
      for (std::int32_t x = 0; x < d[0]; ++x)
        if (ctx.objects.get(x, y, z))
          points.push_back({ x, y, z });
  const std::vector<ObjectPart> parts = separateParts(points, ctx.coplanar, mergeMeeting);
  if (parts.size() < 2 ||
    !std::all_of(parts.begin(),
      parts.end(),
      [&](const ObjectPart& p) { return partInGrid(p, d) && partHasH(p); }))
    return false;
  ModifiedHull apart;
  LatticeMesh together;
  std::vector<int> levels;
  const double step = (to - from) / static_cast<double>(parts.size());
  for (std::size_t c = 0; c < parts.size(); ++c)
  {
    const Execution exec = ctx.exec.within(from + step * c, from + step * (c + 1));
    if (!appendPartH(ctx, parts[c], exec, apart, together, levels))
      return false;
  }
  if (!separates(ctx.objects, together) || (objectEuler(ctx) && !hasTopology(ctx, together)))
    return false;
  r.surface = std::move(together);
  ctx.triangleLevel = std::move(levels);
  r.joinedShells = apart.joinedShells;
  r.cutHandles = apart.cutHandles;
  r.discardedChanges = apart.discardedChanges;
  r.keptApart = apart.keptApart;
  r.degreeOfNonConvexity = apart.degreeOfNonConvexity;
  r.componentsApart = true;
  r.complete = true;
  r.failure = apart.failure;
  return true;
}

/// The pyramid over a convex polygon `base` (corners in order, at least three, not collinear)
/// with `apex` off its plane, triangles oriented outwards: away from the centroid of all
/// corners, which lies strictly inside (a convex combination of every corner with positive
/// weights). A tetrahedron is the pyramid over a triangle.
LatticeMesh pyramidOver(const std::vector<LatticePoint>& base, const LatticePoint& apex)
{
  LatticeMesh out;
  out.points = base;
  out.points.push_back(apex);
  const auto n = static_cast<std::uint32_t>(base.size());
  LatticePoint sum{ 0, 0, 0 };
  for (const LatticePoint& p : out.points)
    for (int k = 0; k < 3; ++k)
      sum[k] += p[k];
  const auto count = static_cast<std::int64_t>(out.points.size());
  const auto addOutwards = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c)
  {
    const LatticePoint &p = out.points[a], &q = out.points[b], &s = out.points[c];
    const LatticePoint inward{
      sum[0] - count * p[0], sum[1] - count * p[1], sum[2] - count * p[2]
    };
    if (dot(cross(sub(q, p), sub(s, p)), inward) < 0)
      out.triangles.push_back({ a, b, c });
    else
      out.triangles.push_back({ a, c, b });
  };
  for (std::uint32_t k = 1; k + 1 < n; ++k)
    addOutwards(0, k, k + 1);
  for (std::uint32_t k = 0; k < n; ++k)
    addOutwards(k, (k + 1) % n, n);
  return out;
}

bool insideGrid(const LatticePoint& p, const Dims& dims)
{
  for (int k = 0; k < 3; ++k)
    if (p[k] < 0 || p[k] >= dims[k])
      return false;
  return true;
}

LatticePoint plus(const LatticePoint& a, const LatticePoint& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}

/// H of a segment off the axes' planes (its centres on a line whose direction d, primitive,
/// has no zero component: voxels touching only at corners, or nowhere): the tetrahedron T = conv{a,
/// b, x, y} of its ends a, b = a + m d and two lattice points x = a + u', y = a + w' where (d, u',
/// w') is a basis of Z^3 (LatticeBasis.h; u' = +-u + k d, w' = +-w + j u + k' d keep it one, and
/// the first such corners inside the grid are taken, near the segment). In that basis a
/// lattice point of T has integer coordinates (t, b, c), all >= 0 with t / m + b + c <= 1: a
/// point of the segment (b = c = 0), x or y. So no lattice point lies inside T, the segment's
/// centres are its edge and the two other corners are background centres (off the line that
/// holds every object centre) on H, marked.
LatticeMesh segmentTetrahedron(const CellList& hull, const Dims& dims)
{
  const LatticePoint a = hull.vertices[0], b = hull.vertices[1];
  const LatticePoint ab = sub(b, a), d = primitive(ab);
  const std::int64_t m = std::gcd(std::gcd(std::abs(ab[0]), std::abs(ab[1])), std::abs(ab[2]));
  const auto uw = basisAroundLine(d);
  // the first corner a + step + k d (k = 0..m) inside the grid; a + steps[0] when none is
  const auto cornerNearSegment = [&](const std::vector<LatticePoint>& steps)
  {
    for (std::int64_t k = 0; k <= m; ++k)
      for (const LatticePoint& s : steps)
      {
        const LatticePoint p{
          a[0] + s[0] + k * d[0], a[1] + s[1] + k * d[1], a[2] + s[2] + k * d[2]
        };
        if (insideGrid(p, dims))
          return p;
      }
    return plus(a, steps[0]);
  };
  const LatticePoint &u = uw[0], &w = uw[1];
  const LatticePoint minusU = sub({ 0, 0, 0 }, u), minusW = sub({ 0, 0, 0 }, w);
  const LatticePoint x = cornerNearSegment({ u, minusU });
  const LatticePoint y =
    cornerNearSegment({ w, minusW, plus(w, u), plus(minusW, u), sub(w, u), sub(minusW, u) });
  return pyramidOver({ a, b, x }, y);
}

/// H of a flat set in a plane n . p = c off the grid's axes (its centres never face-connected):
/// the pyramid over its convex polygon P with an apex y in the next lattice plane on either
/// side, n . y = c +- 1 (LatticeBasis.h: y = p + -+z + a v1 + b v2, the one nearest P's
/// centroid, inside the grid if one of those tried is). No lattice plane lies strictly between
/// the two planes, so a lattice point of the pyramid lies in P (an object centre or a
/// background centre on the base, marked) or is y; the sides hold no other lattice point. So
/// every object centre is on H and no background centre is inside it.
LatticeMesh flatSetPyramid(const CellList& hull, const Dims& dims)
{
  std::vector<LatticePoint> base;
  for (std::uint32_t v : hull.faces[0])
    base.push_back(hull.vertices[v]);
  const PlaneLattice lattice = latticeOfPlane(hull.planes[0].normal);
  double centroid[3] = { 0, 0, 0 };
  for (const LatticePoint& p : base)
    for (int k = 0; k < 3; ++k)
      centroid[k] += double(p[k]) / double(base.size());
  const LatticePoint &v1 = lattice.basis[0], &v2 = lattice.basis[1];
  const auto dotD = [](const LatticePoint& p, const double* q)
  { return double(p[0]) * q[0] + double(p[1]) * q[1] + double(p[2]) * q[2]; };
  const double g11 = double(dot(v1, v1)), g12 = double(dot(v1, v2)), g22 = double(dot(v2, v2));
  LatticePoint best{};
  double bestDistance = std::numeric_limits<double>::infinity();
  bool bestInside = false;
  for (int side : { 1, -1 })
  {
    const LatticePoint origin = side > 0 ? plus(base[0], lattice.step) : sub(base[0], lattice.step);
    const double toCentroid[3] = { centroid[0] - double(origin[0]),
      centroid[1] - double(origin[1]),
      centroid[2] - double(origin[2]) };
    const double b1 = dotD(v1, toCentroid), b2 = dotD(v2, toCentroid), det = g11 * g22 - g12 * g12;
    const auto a0 = std::llround((b1 * g22 - b2 * g12) / det);
    const auto c0 = std::llround((b2 * g11 - b1 * g12) / det);
    for (std::int64_t i = a0 - 1; i <= a0 + 1; ++i)
      for (std::int64_t j = c0 - 1; j <= c0 + 1; ++j)
      {
        const LatticePoint y{ origin[0] + i * v1[0] + j * v2[0],
          origin[1] + i * v1[1] + j * v2[1],
          origin[2] + i * v1[2] + j * v2[2] };
        double distance = 0;
        for (int k = 0; k < 3; ++k)
          distance += (double(y[k]) - centroid[k]) * (double(y[k]) - centroid[k]);
        const bool inside = insideGrid(y, dims);
        if ((inside && !bestInside) || (inside == bestInside && distance < bestDistance))
        {
          best = y;
          bestDistance = distance;
          bestInside = inside;
        }
      }
  }
  return pyramidOver(base, best);
}

/// Flat objects (see the header): every object centre in one plane x_a = c. H is the prism of
/// the object's separating polygons in that plane (ConvexHullModifier2D) from x_a = c - 1 to
/// c + 1: the planes beside hold no object centre, so their centres inside the polygons may lie
/// on its caps, and the prism is a solid whose genus is the polygons' number of holes. A hole
/// whose background reaches beyond its polygon in the plane (a dent under an edge of the hull
/// that passes between lattice points) is no hole of the object: it is filled below the plane,
/// a pit from the top cap down to x_a = c, so that it adds no handle.

/// The last axis along which every point has one coordinate (that of flatAxisOf in the vtk
/// filter, so a 2D image in z is solved in its (x, y) plane), or -1 when the points lie in no
/// plane of the grid's axes.
int gridPlaneAxis(const std::vector<LatticePoint>& points)
{
  for (int a = 2; a >= 0; --a)
    if (std::all_of(points.begin(),
          points.end(),
          [&](const LatticePoint& p) { return p[a] == points.front()[a]; }))
      return a;
  return -1;
}

} // namespace

std::array<int, 2> planeAxesOf(int a)
{
  return { (a + 1) % 3, (a + 2) % 3 };
}

BitVolume layerImage(const BitVolume& objects, int a, std::int32_t c)
{
  const auto uv = planeAxesOf(a);
  BitVolume image(objects.size(uv[0]), objects.size(uv[1]), 1);
  std::array<std::int32_t, 3> i{ 0, 0, 0 };
  i[a] = c;
  for (i[uv[1]] = 0; i[uv[1]] < objects.size(uv[1]); ++i[uv[1]])
    for (i[uv[0]] = 0; i[uv[0]] < objects.size(uv[0]); ++i[uv[0]])
      if (objects.get(i[0], i[1], i[2]))
        image.set(i[uv[0]], i[uv[1]], 0);
  return image;
}

namespace
{

/// The lattice points strictly inside a polygon's outer loop, in the loop's box (none beyond).
struct OuterRegion
{
  Point2L lo{ 0, 0 };
  BitVolume inside;

  explicit OuterRegion(const SeparatingLoop& outer)
  {
    Point2L hi = outer.corners.front();
    this->lo = hi;
    for (const Point2L& p : outer.corners)
      for (int k = 0; k < 2; ++k)
      {
        this->lo[k] = std::min(this->lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    std::vector<SeparatingLoop> local{ outer };
    for (Point2L& p : local[0].corners)
      p = { p[0] - this->lo[0], p[1] - this->lo[1] };
    this->inside = revertSeparatingPolygons2D(local,
      latticePointsOnLoops(local),
      static_cast<std::int32_t>(hi[0] - this->lo[0] + 1),
      static_cast<std::int32_t>(hi[1] - this->lo[1] + 1));
  }

  bool strictlyInside(const Point2L& p) const
  {
    const std::int64_t x = p[0] - this->lo[0], y = p[1] - this->lo[1];
    return x >= 0 && y >= 0 && x < this->inside.size(0) && y < this->inside.size(1) &&
      this->inside.get(static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), 0);
  }
};

/// Whether the face-connected background of the image through the hole's first background
/// corner reaches a centre that is not strictly inside its polygon's outer loop (beyond the
/// image everything is background, and outside the loop): then the hole is a dent of the
/// object, not a hole. A centre strictly inside a ring of object centres is strictly inside
/// every loop about the ring, so a hole of the object never does. Only the outer loop's box
/// is searched.
bool holeReachesOut(const SeparatingLoop& hole, const OuterRegion& region, const BitVolume& image)
{
  const std::int32_t nx = image.size(0), ny = image.size(1);
  auto background = [&](const Point2L& p)
  {
    return p[0] < 0 || p[1] < 0 || p[0] >= nx || p[1] >= ny ||
      !image.get(static_cast<std::int32_t>(p[0]), static_cast<std::int32_t>(p[1]), 0);
  };
  auto start = std::find_if(hole.corners.begin(), hole.corners.end(), background);
  if (start == hole.corners.end())
    return false;
  BitVolume seen(region.inside.size(0), region.inside.size(1), 1);
  std::vector<Point2L> stack{ *start };
  while (!stack.empty())
  {
    const Point2L p = stack.back();
    stack.pop_back();
    if (!region.strictlyInside(p))
      return true; // beyond the image too: the loop lies about object centres of the image
    const auto x = static_cast<std::int32_t>(p[0] - region.lo[0]),
               y = static_cast<std::int32_t>(p[1] - region.lo[1]);
    if (seen.get(x, y, 0))
      continue;
    seen.set(x, y, 0);
    for (const Point2L& q : { Point2L{ p[0] + 1, p[1] },
           Point2L{ p[0] - 1, p[1] },
           Point2L{ p[0], p[1] + 1 },
           Point2L{ p[0], p[1] - 1 } })
      if (background(q))
        stack.push_back(q);
  }
  return false;
}

/// Whether a polygon of the plane lies inside the hole (its loops are apart from the hole's,
/// so one corner tells).
bool holdsAPolygon(const SeparatingPolygons& s, std::size_t hole)
{
  const auto& loop = s.loops[hole].corners;
  for (const SeparatingPolygon& other : s.polygons)
  {
    const Point2L& p = s.loops[other.outer].corners.front();
    bool in = false;
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
      if ((loop[i][1] > p[1]) != (loop[j][1] > p[1]) &&
        (orientation(loop[j], loop[i], p) > 0) == (loop[i][1] > loop[j][1]))
        in = !in;
    if (in)
      return true;
  }
  return false;
}

/// The point (u, v) of the plane at height h along axis a.
LatticePoint inSpace(const Point2L& p, int a, std::int64_t h)
{
  const auto uv = planeAxesOf(a);
  LatticePoint q{ 0, 0, 0 };
  q[uv[0]] = p[0];
  q[uv[1]] = p[1];
  q[a] = h;
  return q;
}

/// The triangles of a flat object's H, one vertex per lattice point, with their levels.
struct FlatMesh
{
  int axis;
  LatticeMesh& mesh;
  std::vector<int>& levels;
  std::map<LatticePoint, Index> index;

  Index vertex(const Point2L& p, std::int64_t h)
  {
    const LatticePoint q = inSpace(p, this->axis, h);
    auto it = this->index.emplace(q, static_cast<Index>(this->mesh.points.size()));
    if (it.second)
      this->mesh.points.push_back(q);
    return it.first->second;
  }

  /// The polygon's triangles at height h, counter-clockwise seen from +a unless `down`.
  void cap(const std::vector<Point2L>& corners,
    const std::vector<Triangle>& triangles,
    std::int64_t h,
    bool down,
    int level)
  {
    for (const Triangle& t : triangles)
    {
      std::array<Index, 3> tri{ this->vertex(corners[static_cast<std::size_t>(t[0])], h),
        this->vertex(corners[static_cast<std::size_t>(t[1])], h),
        this->vertex(corners[static_cast<std::size_t>(t[2])], h) };
      if (down)
        std::swap(tri[0], tri[2]);
      this->mesh.triangles.push_back(tri);
      this->levels.push_back(level);
    }
  }

  /// The quad from the edge [p0, q0] at height lo to [p1, q1] at hi, facing to the right of
  /// p -> q (away from the object on its left).
  void wall(const Point2L& p0,
    const Point2L& q0,
    const Point2L& p1,
    const Point2L& q1,
    std::int64_t lo,
    std::int64_t hi,
    int level)
  {
    const Index a0 = this->vertex(p0, lo), b0 = this->vertex(q0, lo), b1 = this->vertex(q1, hi),
                a1 = this->vertex(p1, hi);
    this->mesh.triangles.push_back({ a0, b0, b1 });
    this->mesh.triangles.push_back({ a0, b1, a1 });
    this->levels.insert(this->levels.end(), 2, level);
  }

  /// One quad per edge of the loop from height lo to hi, facing away from the loop's left side
  /// (the object's).
  void sides(const SeparatingLoop& loop, std::int64_t lo, std::int64_t hi)
  {
    const std::size_t n = loop.corners.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const Point2L &p = loop.corners[k], &q = loop.corners[(k + 1) % n];
      const Index p0 = this->vertex(p, lo), q0 = this->vertex(q, lo), q1 = this->vertex(q, hi),
                  p1 = this->vertex(p, hi);
      this->mesh.triangles.push_back({ p0, q0, q1 });
      this->mesh.triangles.push_back({ p0, q1, p1 });
      this->levels.insert(this->levels.end(), 2, loop.level);
    }
  }
};

/// The prism of one polygon with holes from x_a = c - 1 to c + 1: its caps at the polygon's
/// level, a quad per loop edge at the loop's level; a hole that reaches out (and holds no
/// polygon) only from c to c + 1 above its floor at c, and closed in the bottom cap. The loops
/// are simple, pairwise apart and carry the object on their left, so the sides face outwards
/// (away from holes as well) and the prisms of different polygons are apart: a closed
/// 2-manifold.
void appendPrism(const SeparatingPolygons& s,
  const SeparatingPolygon& polygon,
  const BitVolume& image,
  std::int64_t c,
  FlatMesh& out)
{
  SeparatingPolygon bottom = polygon;
  bottom.holes.clear();
  std::vector<std::size_t> dents;
  const std::optional<OuterRegion> region = polygon.holes.empty()
    ? std::nullopt
    : std::optional<OuterRegion>(OuterRegion(s.loops[polygon.outer]));
  for (const std::size_t h : polygon.holes)
    if (holeReachesOut(s.loops[h], *region, image) && !holdsAPolygon(s, h))
      dents.push_back(h);
    else
      bottom.holes.push_back(h);
  // The bottom cap is the top one unless a dent is filled: one triangulation saved.
  const std::vector<Triangle> top = triangulatePolygonWithHoles(s, polygon);
  out.cap(polygonCorners(s, polygon), top, c + 1, false, polygon.level);
  out.cap(polygonCorners(s, bottom),
    dents.empty() ? top : triangulatePolygonWithHoles(s, bottom),
    c - 1,
    true,
    polygon.level);
  out.sides(s.loops[polygon.outer], c - 1, c + 1);
  for (const std::size_t h : bottom.holes)
    out.sides(s.loops[h], c - 1, c + 1);
  for (const std::size_t h : dents)
  {
    // The floor: the hole's region (its loop reversed, counter-clockwise) facing +a.
    std::vector<Point2L> floor(s.loops[h].corners.rbegin(), s.loops[h].corners.rend());
    out.cap(floor, triangulateSimplePolygon(floor), c, false, s.loops[h].level);
    out.sides(s.loops[h], c, c + 1);
  }
}

/// The bounded face-connected background components of the layer that lie in one row of an
/// axis and outside every hole of the plane's polygons (closed): holes of the object that the
/// polygons lost (the 2D modifier found no lattice triangle for them inside the ring and
/// opened them as notches).
std::vector<std::vector<Point2L>> lostHoles(const BitVolume& image, const SeparatingPolygons& s)
{
  const std::int32_t nx = image.size(0), ny = image.size(1);
  std::vector<SeparatingLoop> holeLoops;
  for (const SeparatingLoop& loop : s.loops)
    if (loop.level % 2 == 1)
      holeLoops.push_back(loop);
  const BitVolume inHole = revertSeparatingPolygons2D(holeLoops, {}, nx, ny);
  BitVolume seen(nx, ny, 1);
  std::vector<std::vector<Point2L>> lost;
  for (std::int32_t y = 0; y < ny; ++y)
    for (std::int32_t x = 0; x < nx; ++x)
    {
      if (image.get(x, y, 0) || seen.get(x, y, 0))
        continue;
      std::vector<Point2L> component, stack{ { x, y } };
      bool bounded = true;
      seen.set(x, y, 0);
      while (!stack.empty())
      {
        const Point2L p = stack.back();
        stack.pop_back();
        component.push_back(p);
        for (const Point2L& q : { Point2L{ p[0] + 1, p[1] },
               Point2L{ p[0] - 1, p[1] },
               Point2L{ p[0], p[1] + 1 },
               Point2L{ p[0], p[1] - 1 } })
        {
          const auto qx = static_cast<std::int32_t>(q[0]), qy = static_cast<std::int32_t>(q[1]);
          if (qx < 0 || qy < 0 || qx >= nx || qy >= ny)
            bounded = false;
          else if (!image.get(qx, qy, 0) && !seen.get(qx, qy, 0))
          {
            seen.set(qx, qy, 0);
            stack.push_back(q);
          }
        }
      }
      auto sameAs = [&](int k)
      {
        return std::all_of(component.begin(),
          component.end(),
          [&](const Point2L& p) { return p[k] == component.front()[k]; });
      };
      if (bounded && (sameAs(0) || sameAs(1)) && !inHole.get(x, y, 0))
        lost.push_back(std::move(component));
    }
  return lost;
}

/// The planes of a mesh's triangles given `level` where they have none yet.
void addPlanes(const LatticeMesh& m, int level, std::map<FacePlane, int>& planeLevel)
{
  for (const auto& t : m.triangles)
    planeLevel.emplace(planeThrough(m.points[t[0]], m.points[t[1]], m.points[t[2]]), level);
}

/// B's box two steps wider than B on the plane's axes, from c - 1 to c + 1: its open interior
/// holds, in the plane, B and its eight neighbours only.
LatticeMesh lostHoleBox(const std::vector<Point2L>& hole, int a, std::int64_t c, bool tunnel)
{
  Point2L lo = hole.front(), hi = lo;
  for (const Point2L& p : hole)
    for (int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  std::vector<LatticePoint> corners;
  for (const std::int64_t h : { c - 1, c + 1 })
    if (!tunnel)
    {
      for (const std::int64_t u : { lo[0] - 2, hi[0] + 2 })
        for (const std::int64_t v : { lo[1] - 2, hi[1] + 2 })
          corners.push_back(inSpace({ u, v }, a, h));
    }
    else
      for (const Point2L& p : { lo, hi })
        for (const Point2L& d :
          { Point2L{ 1, 0 }, Point2L{ -1, 0 }, Point2L{ 0, 1 }, Point2L{ 0, -1 } })
          corners.push_back(inSpace({ p[0] + d[0], p[1] + d[1] }, a, h));
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  return triangulateHull(convexHull(corners));
}

/// Whether a cut through the lost hole B can separate, checked in the plane before any
/// Boolean: B's eight neighbours are object centres (they come strictly inside its box, B
/// inside its tunnel).
bool cuttable(const std::vector<Point2L>& hole, const BitVolume& image)
{
  Point2L lo = hole.front(), hi = lo;
  for (const Point2L& p : hole)
    for (int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  for (std::int64_t v = lo[1] - 1; v <= hi[1] + 1; ++v)
    for (std::int64_t u = lo[0] - 1; u <= hi[0] + 1; ++u)
    {
      const bool inHole = u >= lo[0] && v >= lo[1] && u <= hi[0] && v <= hi[1];
      const bool object = u >= 0 && v >= 0 && u < image.size(0) && v < image.size(1) &&
        image.get(static_cast<std::int32_t>(u), static_cast<std::int32_t>(v), 0);
      if (!inHole && !object)
        return false;
    }
  return true;
}

/// Handles through lost holes (see the header): H united with the box of the holes two steps
/// wider than them (lostHoleBox; one notch can hold several holes, and a hole on another's box
/// would come inside it) less the prism of each hole B's hexagon (the hull of B's four
/// neighbours, which holds B alone inside), kept when the result separates with as many shells
/// and one handle more per hole. The new planes get level 0 (the box) and 1 (the tunnels).
bool cutLostHoles(const BitVolume& objects,
  int a,
  std::int64_t c,
  const std::vector<std::vector<Point2L>>& holes,
  LatticeMesh& surface,
  std::map<FacePlane, int>& planeLevel)
{
  std::vector<Point2L> all;
  std::vector<LatticeMesh> tunnels;
  for (const auto& hole : holes)
  {
    all.insert(all.end(), hole.begin(), hole.end());
    tunnels.push_back(lostHoleBox(hole, a, c, true));
  }
  const LatticeMesh box = lostHoleBox(all, a, c, false);
  LatticeMesh cut;
  if (!latticeUnion(surface, box, cut))
    return false;
  for (const LatticeMesh& t : tunnels)
  {
    LatticeMesh next;
    if (!latticeDifference(cut, t, next))
      return false;
    cut = std::move(next);
  }
  const long handles = static_cast<long>(holes.size());
  if (shellsOf(cut).size() != shellsOf(surface).size() ||
    eulerCharacteristic(cut) != eulerCharacteristic(surface) - 2 * handles ||
    !separates(objects, cut))
    return false;
  surface = std::move(cut);
  addPlanes(box, 0, planeLevel);
  for (const LatticeMesh& t : tunnels)
  {
    LatticeMesh walls; // the tunnel's faces as H has them: facing into the tunnel
    walls.append(t, true);
    addPlanes(walls, 1, planeLevel);
  }
  return true;
}

/// At most this many lost holes are cut per object: each costs two exact Booleans of H, and
/// three more when they are tried one by one.
constexpr std::size_t MaxLostHoles = 16;

/// Reports the flat path's progress; throws (as the rest of the modifier does) when asked to
/// stop.
void flatStep(const Execution& exec, double fraction)
{
  if (exec.stopRequested() || !exec.report(fraction))
    throw std::runtime_error("aborted");
}

/// Appends a note to the result's failure text (a complete H that misses something says so).
void note(ModifiedHull& r, const std::string& text)
{
  r.failure += (r.failure.empty() ? "" : "; ") + text;
}

/// The face-connected regions of a layer's image padded by one pixel (both classes: in a
/// well-composed layer face and corner connectivity agree), with their nesting depth: the
/// number of region boundaries crossed from the outer background (the padding's region, depth
/// 0; the object components about it 1, their holes 2, islands in those 3, ...).
struct PlaneRegions
{
  std::int32_t nx = 0, ny = 0; ///< the padded size; pixel (x, y) of the image is (x + 1, y + 1)
  std::vector<std::int32_t> region; ///< per padded pixel
  std::vector<bool> object;         ///< per region: of the object's class
  std::vector<int> depth;           ///< per region

  std::int32_t at(std::int64_t x, std::int64_t y) const
  {
    return this->region[static_cast<std::size_t>(y * this->nx + x)];
  }
};

/// The regions of the padded image (CUDB components of each class) and their depths (breadth
/// first over the regions that share a pixel edge).
PlaneRegions planeRegions(const BitVolume& image)
{
  PlaneRegions g;
  g.nx = image.size(0) + 2;
  g.ny = image.size(1) + 2;
  g.region.assign(static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny), -1);
  std::array<std::vector<LatticePoint>, 2> points; // background, object
  for (std::int32_t y = 0; y < g.ny; ++y)
    for (std::int32_t x = 0; x < g.nx; ++x)
    {
      const bool in =
        x > 0 && y > 0 && x <= image.size(0) && y <= image.size(1) && image.get(x - 1, y - 1, 0);
      points[in].push_back({ x, y, 0 });
    }
  for (const bool cls : { false, true })
    for (const auto& component : componentsOf(points[cls], true, false))
    {
      for (const auto& p : component)
        g.region[static_cast<std::size_t>(p[1] * g.nx + p[0])] =
          static_cast<std::int32_t>(g.object.size());
      g.object.push_back(cls);
    }
  std::vector<std::set<std::int32_t>> next(g.object.size());
  for (std::int32_t y = 0; y < g.ny; ++y)
    for (std::int32_t x = 0; x < g.nx; ++x)
      for (const Point2L& q : { Point2L{ x + 1, y }, Point2L{ x, y + 1 } })
        if (q[0] < g.nx && q[1] < g.ny && g.at(x, y) != g.at(q[0], q[1]))
        {
          next[static_cast<std::size_t>(g.at(x, y))].insert(g.at(q[0], q[1]));
          next[static_cast<std::size_t>(g.at(q[0], q[1]))].insert(g.at(x, y));
        }
  g.depth.assign(g.object.size(), -1);
  std::vector<std::int32_t> queue{ g.at(0, 0) };
  g.depth[static_cast<std::size_t>(queue[0])] = 0;
  for (std::size_t k = 0; k < queue.size(); ++k)
    for (const std::int32_t r : next[static_cast<std::size_t>(queue[k])])
      if (g.depth[static_cast<std::size_t>(r)] < 0)
      {
        g.depth[static_cast<std::size_t>(r)] = g.depth[static_cast<std::size_t>(queue[k])] + 1;
        queue.push_back(r);
      }
  return g;
}

/// Per region, twice the Euler characteristic of its pixels' union (V - E + F of the pixels,
/// the pixel edges and the 2 x 2 blocks within it: in a well-composed layer that complex has
/// the homotopy type of the union of the closed pixel squares): for an object component, the
/// Euler characteristic of the surface about it.
std::vector<long> regionSurfaceEulers(const PlaneRegions& g)
{
  std::vector<long> chi(g.object.size(), 0);
  for (std::int32_t y = 0; y < g.ny; ++y)
    for (std::int32_t x = 0; x < g.nx; ++x)
    {
      const std::int32_t r = g.at(x, y);
      const bool right = x + 1 < g.nx && g.at(x + 1, y) == r,
                 up = y + 1 < g.ny && g.at(x, y + 1) == r;
      const bool block = right && up && g.at(x + 1, y + 1) == r;
      chi[static_cast<std::size_t>(r)] += 2 * (1 - right - up + block);
    }
  return chi;
}

/// Whether H of a well-composed flat layer has the topology of the object's boundary shell by
/// shell: as many shells as object components, each shell holding (inside or on it) the
/// centres of exactly one component and all of them, and with the Euler characteristic of the
/// surface about that component (the layer's background is one component in space, about
/// every shell: separation keeps its centres out of H).
bool flatShellsMatch(const BitVolume& objects,
  int a,
  std::int64_t c,
  const PlaneRegions& g,
  const LatticeMesh& surface)
{
  const std::vector<Shell> shells = shellsOf(surface);
  const long objectRegions = std::count(g.object.begin(), g.object.end(), true);
  if (static_cast<long>(shells.size()) != objectRegions)
    return false;
  const std::vector<long> chi = regionSurfaceEulers(g);
  if (objectRegions == 1)
  {
    // One shell for one component: H separates, so the shell holds all of its centres.
    const auto r = static_cast<std::size_t>(
      std::find(g.object.begin(), g.object.end(), true) - g.object.begin());
    return eulerCharacteristic(shells[0].mesh) == chi[r];
  }
  const Dims d = objects.dims();
  const auto uv = planeAxesOf(a);
  std::vector<long> size(g.object.size(), 0);
  for (const std::int32_t r : g.region)
    ++size[static_cast<std::size_t>(r)];
  std::vector<bool> claimed(g.object.size(), false);
  std::vector<std::uint8_t> held(objects.voxelCount(), 0);
  for (const Shell& shell : shells)
  {
    // The shell's box in the grid: only there can it hold a centre (and be cleared again).
    LatticePoint lo = shell.mesh.points[0], hi = lo;
    for (const auto& q : shell.mesh.points)
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::max<std::int64_t>(std::min(lo[k], q[k]), 0);
        hi[k] = std::min<std::int64_t>(std::max(hi[k], q[k]), d[k] - 1);
      }
    markShell(shell.mesh, d, 1, 1, held);
    std::map<std::int32_t, long> count; // object pixels held, per component
    LatticePoint p = lo;
    for (p[2] = lo[2]; p[2] <= hi[2]; ++p[2])
      for (p[1] = lo[1]; p[1] <= hi[1]; ++p[1])
        for (p[0] = lo[0]; p[0] <= hi[0]; ++p[0])
        {
          std::uint8_t& mark = held[gridIndex(d, p)];
          const std::int32_t r = g.at(p[uv[0]] + 1, p[uv[1]] + 1);
          if (mark != 0 && p[a] == c && g.object[static_cast<std::size_t>(r)])
            ++count[r];
          mark = 0;
        }
    if (count.size() != 1)
      return false; // no component, or two in one shell
    const auto r = static_cast<std::size_t>(count.begin()->first);
    if (claimed[r] || count.begin()->second != size[r] || eulerCharacteristic(shell.mesh) != chi[r])
      return false;
    claimed[r] = true;
  }
  return true;
}

/// The sheared pixel solid of a well-composed layer (see the header): each object pixel p's
/// square p + [-1/2, 1/2]^2 at x_a = c is the middle section of the parallelepiped with top
/// p + [0, 1]^2 at c + 1 and bottom p + [-1, 0]^2 at c - 1; those of all pixels tile the slab
/// face to face, and H is the boundary of the union of the object pixels' ones: a cap square
/// per pixel on top and below, a wall per pixel edge between an object and a background
/// pixel. Levels: caps one less than their component's depth, walls one less than the deeper
/// of their two regions (0 about the outer background, 1 about a hole, 2 about an island, ...).
void appendPixelSolid(const PlaneRegions& g, std::int64_t c, FlatMesh& out)
{
  static const std::array<Point2L, 4> corner{
    Point2L{ 0, 0 }, Point2L{ 1, 0 }, Point2L{ 1, 1 }, Point2L{ 0, 1 }
  };
  // The pixel's sides, counter-clockwise: the neighbour beyond corner k -> k + 1.
  static const std::array<Point2L, 4> beyond{
    Point2L{ 0, -1 }, Point2L{ 1, 0 }, Point2L{ 0, 1 }, Point2L{ -1, 0 }
  };
  const std::vector<Triangle> square{ { 0, 1, 2 }, { 0, 2, 3 } };
  for (std::int32_t y = 1; y + 1 < g.ny; ++y)
    for (std::int32_t x = 1; x + 1 < g.nx; ++x)
    {
      const auto r = static_cast<std::size_t>(g.at(x, y));
      if (!g.object[r])
        continue;
      const Point2L p{ x - 1, y - 1 };
      std::vector<Point2L> top, bottom;
      for (const Point2L& k : corner)
      {
        top.push_back({ p[0] + k[0], p[1] + k[1] });
        bottom.push_back({ p[0] + k[0] - 1, p[1] + k[1] - 1 });
      }
      out.cap(top, square, c + 1, false, g.depth[r] - 1);
      out.cap(bottom, square, c - 1, true, g.depth[r] - 1);
      for (std::size_t k = 0; k < 4; ++k)
      {
        const auto n = static_cast<std::size_t>(g.at(x + beyond[k][0], y + beyond[k][1]));
        if (!g.object[n])
          out.wall(bottom[k],
            bottom[(k + 1) % 4],
            top[k],
            top[(k + 1) % 4],
            c - 1,
            c + 1,
            std::max(g.depth[r], g.depth[n]) - 1);
      }
    }
}

/// Whether the layer is well-composed (no two object pixels touching only at a corner: then
/// its boundary in space is a 2-manifold, which H must match shell by shell).
bool wellComposedLayer(const BitVolume& image, const Execution& exec)
{
  BitVolume layer(image.size(0), image.size(1), 3);
  for (std::int32_t y = 0; y < image.size(1); ++y)
    for (std::int32_t x = 0; x < image.size(0); ++x)
      if (image.get(x, y, 0))
        layer.set(x, y, 1);
  return wellComposedBoundaryEuler(layer, exec).has_value();
}

/// H of a well-composed layer replaced by its sheared pixel solid (see the header), complete
/// and with nothing to note: the plane's counts become its holes (background regions below
/// the outer one) and its deepest level.
void usePixelSolid(const PlaneRegions& g, int a, std::int64_t c, ModifiedHull& r)
{
  r.surface = LatticeMesh();
  r.faces.clear();
  std::vector<int> levels;
  FlatMesh out{ a, r.surface, levels, {} };
  appendPixelSolid(g, c, out);
  r.complete = true;
  r.failure.clear();
  r.cutHandles = 0;
  r.concavities = 0;
  r.cavities = 0;
  r.degreeOfNonConvexity = 0;
  for (std::size_t k = 0; k < g.object.size(); ++k)
  {
    r.cavities += !g.object[k] && g.depth[k] > 0;
    r.degreeOfNonConvexity = std::max(r.degreeOfNonConvexity, g.depth[k] - 1);
  }
  r.flatPixelSolid = true;
  mergeIntoFaces({}, levels, r);
}

/// H of a flat object whose centres lie in x_a = c: the prisms of its separating polygons, a
/// handle cut through each hole they lost (when one separates), its faces with their levels;
/// the counts of the plane (notches as concavities, holes as cavities). Incomplete when the
/// plane's polygons are; lost holes beyond MaxLostHoles are noted in the failure text. A
/// well-composed layer whose prisms are incomplete or have not its topology shell by shell
/// gets its sheared pixel solid instead (complete, nothing noted).
void solveFlatObject(const BitVolume& objects,
  int a,
  std::int64_t c,
  const Execution& exec,
  ModifiedHull& r)
{
  const BitVolume image = layerImage(objects, a, static_cast<std::int32_t>(c));
  const SeparatingPolygons s = separatingPolygons2D(image, exec.within(0, 0.3));
  flatStep(exec, 0.3);
  r.complete = s.complete;
  if (!s.complete)
    r.failure = "in the object's plane: " + s.failure;
  r.concavities = s.notches;
  r.cavities = s.holes;
  r.degreeOfNonConvexity = s.degreeOfNonConvexity;
  std::vector<int> levels;
  FlatMesh out{ a, r.surface, levels, {} };
  for (const SeparatingPolygon& polygon : s.polygons)
    appendPrism(s, polygon, image, c, out);
  std::map<FacePlane, int> planeLevel;
  std::vector<std::vector<Point2L>> lost;
  std::size_t dropped = 0;
  for (auto& hole : lostHoles(image, s))
    if (!cuttable(hole, image))
      continue;
    else if (lost.size() < MaxLostHoles)
      lost.push_back(std::move(hole));
    else
      ++dropped;
  if (dropped > 0)
    note(r,
      "in the object's plane: " + std::to_string(dropped) + " lost hole(s) beyond the first " +
        std::to_string(MaxLostHoles) + " not cut");
  if (!lost.empty())
  {
    for (std::size_t t = 0; t < r.surface.triangles.size(); ++t)
    {
      const auto& tri = r.surface.triangles[t];
      planeLevel.emplace(
        planeThrough(r.surface.points[tri[0]], r.surface.points[tri[1]], r.surface.points[tri[2]]),
        levels[t]);
    }
    flatStep(exec, 0.4);
    // All together first; when that fails (a hole's box that holds background), one by one.
    if (cutLostHoles(objects, a, c, lost, r.surface, planeLevel))
      r.cutHandles = static_cast<int>(lost.size());
    else if (lost.size() > 1)
      for (std::size_t k = 0; k < lost.size(); ++k)
      {
        flatStep(exec, 0.4 + 0.3 * static_cast<double>(k) / static_cast<double>(lost.size()));
        r.cutHandles += cutLostHoles(objects, a, c, { lost[k] }, r.surface, planeLevel);
      }
  }
  mergeIntoFaces(planeLevel, r.cutHandles > 0 ? std::vector<int>() : levels, r);
  flatStep(exec, 0.7);
  if (!wellComposedLayer(image, exec))
    return;
  const PlaneRegions g = planeRegions(image);
  if (!r.complete || !flatShellsMatch(objects, a, c, g, r.surface))
    usePixelSolid(g, a, c, r);
}

} // namespace

namespace
{

ModifiedHull modifyHull(const BitVolume& objects,
  CoplanarFaces coplanar,
  const Execution& exec,
  bool componentsFirst)
{
  ModifiedHull r;
  const std::vector<LatticePoint> candidates = vertexCandidates(objects);
  if (candidates.empty())
    return r;
  r.hull = convexHull(candidates, coplanar);
  if (!exec.report(0.2))
    throw std::runtime_error("aborted");
  const int flat = r.hull.dimension < 3 ? gridPlaneAxis(candidates) : -1;
  if (flat >= 0)
    solveFlatObject(objects, flat, candidates.front()[flat], exec.within(0.2, 0.8), r);
  else if (r.hull.dimension == 1 || r.hull.dimension == 2)
  {
    // A segment or a flat set in no plane of the grid's axes (never face-connected): its parts
    // apart when they cannot meet (voxels apart keep their own shells), else the tetrahedron or
    // pyramid of the header, every object centre on it.
    Context ctx{ objects, coplanar, exec, {}, 0 };
    if (componentsFirst && solveComponentsFirst(ctx, r, 0.2, 0.8))
      mergeIntoFaces(ctx.planeLevel, ctx.triangleLevel, r);
    else
    {
      r.surface = r.hull.dimension == 1 ? segmentTetrahedron(r.hull, objects.dims())
                                        : flatSetPyramid(r.hull, objects.dims());
      r.complete = true;
      mergeIntoFaces({}, std::vector<int>(r.surface.triangles.size(), 0), r);
      // voxels apart that could not be solved apart share the one solid: said, not silent
      if (objectEuler(ctx) && !hasTopology(ctx, r.surface))
        r.failure = "voxels apart in a plane or on a line off the grid's axes share one solid "
                    "(one shell for several components)";
    }
  }
  else if (r.hull.dimension < 3)
  {
    r.complete = false; // unreachable: a point lies in a plane of the grid's axes
    r.failure = "the object spans no solid";
  }
  else
  {
    classifyBackgroundComponents(objects, r.hull, r);
    Context ctx{ objects, coplanar, exec, {}, 0 };
    if (!componentsFirst || !solveComponentsFirst(ctx, r, 0.2, 0.8))
    {
      solveAndCheck(ctx, r);
      // When H of the object as one misses its topology (a ball in a torus's hole: their hulls
      // meet, so they were one part), each component alone, as a last resort.
      if (r.complete && objectEuler(ctx) && !hasTopology(ctx, r.surface))
        solveComponentsFirst(ctx, r, 0.2, 0.8, false);
    }
    if (!exec.report(0.8))
      throw std::runtime_error("aborted");
    mergeIntoFaces(ctx.planeLevel, ctx.triangleLevel, r);
  }
  for (const auto& p : r.surface.points)
    r.vertexMark.push_back(voxelClass(objects, p) ? 1 : 0);
  for (const auto& p : latticePointsOnSurface(r.surface, objects.dims()))
    if (!voxelClass(objects, p))
      r.backgroundOnSurface.push_back(p);
  return r;
}

} // namespace

ModifiedHull modifyConvexHull(const BitVolume& objects,
  CoplanarFaces coplanar,
  const Execution& exec)
{
  return modifyHull(objects, coplanar, exec, true);
}

namespace detail
{

std::vector<std::array<std::int64_t, 4>> runsOf(const PointRuns& points)
{
  std::vector<std::array<std::int64_t, 4>> out;
  for (const Run& r : points.runs)
    out.push_back({ r.lo, r.hi, r.y, r.z });
  return out;
}

std::vector<std::array<std::int64_t, 4>> runsOfRow(const BitVolume& objects,
  bool cls,
  std::int64_t lo,
  std::int64_t hi,
  std::int64_t y,
  std::int64_t z)
{
  PointRuns points;
  pushRunsOfRow(objects, cls, lo, hi, y, z, points);
  return runsOf(points);
}

std::vector<std::array<std::int64_t, 4>> runsOfClass(const CellList& c,
  const BitVolume& objects,
  bool cls,
  bool strict)
{
  return runsOf(pointsOfClass(c, objects, cls, strict));
}

bool rowRange(const CellList& c,
  bool strict,
  std::int64_t y,
  std::int64_t z,
  std::int64_t& lo,
  std::int64_t& hi)
{
  RowScan rows(c, strict, SliceRows::All);
  rows.setSlice(z);
  return rows.range(y, lo, hi);
}

std::size_t planesLeftOutOfSlice(const CellList& c, bool strict, std::int64_t z)
{
  RowScan rows(c, strict, SliceRows::All);
  rows.setSlice(z);
  return rows.planesLeftOut();
}

std::vector<LatticePoint> sliceCorners(const std::vector<LatticePoint>& ends)
{
  return vbr::sliceCorners(ends);
}

CellList groupShape(const std::vector<LatticePoint>& points, CoplanarFaces coplanar)
{
  return shapeOf(PointRuns::of(points), coplanar);
}

std::vector<int> sidesInBox(const LatticeMesh& surface,
  const LatticePoint& lo,
  const LatticePoint& hi)
{
  const std::vector<std::array<Index, 3>> near = trianglesAheadOf(surface, { lo, hi });
  std::vector<int> sides;
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        sides.push_back(sideOf(surface, near, { x, y, z }, 1));
  return sides;
}

} // namespace detail

} // namespace vbr
