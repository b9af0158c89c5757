// The lattice points of a class inside a convex hull, the point sets of the pressing-in's
// recursion (H. Schulz, FZD-514, 2009, section 4.2): every level lists the points of the other
// class in its hull C. The hull's planes are arranged for scanning its rows along x (RowScan:
// the slice's box leaves most planes of a large hull out of its rows), the points are kept as
// maximal runs along rows read from the volume's words (PointRuns), and they are grouped into
// face- or vertex-connected components a run at a time.
#ifndef vbr_HullPointRuns_h
#define vbr_HullPointRuns_h

#include "HullModifierContext.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace vbr
{
namespace detail
{

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

inline std::array<std::int64_t, 6> boundsOf(const CellList& c)
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

/// The bits of word w (x = 64 w .. 64 w + 63) among x = first..last, for a word that meets that
/// range (first <= last, first >> 6 <= w <= last >> 6).
inline Word runMask(std::int64_t w, std::int64_t first, std::int64_t last)
{
  Word bits = ~Word(0);
  if (w == first >> 6)
    bits &= ~Word(0) << (first & 63);
  if (w == last >> 6 && (last & 63) != 63)
    bits &= (Word(1) << ((last & 63) + 1)) - 1;
  return bits;
}

/// The lattice points of class `cls` in the hull (its open interior when `strict`), row by row
/// from the volume's words, as runs: every level of the recursion collects its points so.
PointRuns pointsOfClass(const CellList& c, const BitVolume& objects, bool cls, bool strict);

void recordPlanes(Context& ctx, const CellList& c, int level);

/// Components of a set of lattice points (CUDB, connected through faces, edges or corners when
/// `vertex`), as runs in the order of the set's. Only the box of the points is voxelised: a level
/// deep inside a large grid pays for its own points, not for the grid. `plane`: the grid is one
/// slice (2D components); a 3D grid keeps 3D extraction even when the points lie in one slice.
std::vector<PointRuns> componentsOf(PointRuns points, bool plane, bool vertex);

/// componentsOf for a list of points, as lists.
std::vector<std::vector<LatticePoint>> componentsOf(const std::vector<LatticePoint>& points,
  bool plane,
  bool vertex);

} // namespace detail
} // namespace vbr

#endif
