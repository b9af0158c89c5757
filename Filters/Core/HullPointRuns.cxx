// Lattice points of a class in a hull, as runs along rows, and their components (HullPointRuns.h).
#include "HullPointRuns.h"

#include "CUDB.h"
#include "Geometry.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <utility>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

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

} // namespace

namespace detail
{

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

std::vector<std::vector<LatticePoint>> componentsOf(const std::vector<LatticePoint>& points,
  bool plane,
  bool vertex)
{
  std::vector<std::vector<LatticePoint>> out;
  for (const PointRuns& c : componentsOf(PointRuns::of(points), plane, vertex))
    out.push_back(c.points());
  return out;
}

namespace
{

std::vector<std::array<std::int64_t, 4>> runsOf(const PointRuns& points)
{
  std::vector<std::array<std::int64_t, 4>> out;
  for (const Run& r : points.runs)
    out.push_back({ r.lo, r.hi, r.y, r.z });
  return out;
}

} // namespace

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

} // namespace detail

} // namespace vbr
