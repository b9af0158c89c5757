// The statistics of the connected regions of labelled objects (see RegionStatistics.h): the
// pass over an object's boxes (RegionRecords::addBoxes), or over its runs when it was labelled
// on them (measureRegionsOfRuns, measureRegionsOfPixelRuns), which adds up a row's consecutive
// runs of one region before its record is read and written.
#include "RegionStatistics.h"

#include "Prefetch.h"

#include <cassert>
#include <ostream>
#include <random>
#include <type_traits>
#include <utility>

namespace vbr
{

namespace
{

/// The statistics of the regions of an object labelled on its runs, from the runs.
void measureRegionsOfRuns(const LabelledObject& o, RegionRecords<RegionRecord>& regions)
{
  const VoxelRuns& r = o.voxelRuns;
  const std::vector<VoxelRun>& runs = r.runs;
  const std::vector<std::uint32_t>& label = o.runComponents.runLabel;
  const std::vector<std::uint8_t>& begins = o.runComponents.beginsBox;
  const std::int32_t dx = o.offset[0];
  for (std::int32_t z = 0; z < r.dims[2]; ++z)
    for (std::int32_t y = 0; y < r.dims[1]; ++y)
    {
      const std::size_t row = r.rowOf(y, z);
      const std::uint32_t end = r.rowStarts[row + 1];
      // Consecutive runs of one region (most runs of a porous volume's large component) are
      // added up before their region's record is read and written once.
      for (std::uint32_t i = r.rowStarts[row]; i < end;)
      {
        const std::uint32_t region = label[i];
        std::int64_t voxels = 0, doubledX = 0;
        std::uint32_t boxes = 0, j = i;
        do
        {
          const std::int64_t length = runs[j].x1 - runs[j].x0;
          voxels += length;
          doubledX += length * (std::int64_t(runs[j].x0) + runs[j].x1 + 2 * dx);
          boxes += begins[j];
        } while (++j < end && label[j] == region);
        const std::size_t g = o.firstRegion + region - 1;
        regions.touch(g).addRowRuns({ runs[i].x0 + dx, runs[j - 1].x1 + dx },
          y + o.offset[1],
          z + o.offset[2],
          voxels,
          doubledX,
          boxes);
        regions.noteSize(g);
        i = j;
      }
    }
}

/// The statistics of the regions of a 2D object labelled on its pixel runs, from the runs read
/// again from its pixels (a bit scan per row: cheaper than keeping 8 bytes per run). A run
/// begins a box when its box number is the next one not met yet (boxes are numbered as their
/// first runs come in scan order).
template<typename Record>
void measureRegionsOfPixelRuns(const LabelledObject& o, RegionRecords<Record>& regions)
{
  const BitVolume& pixels = o.pixels;
  const std::uint32_t* runBox = o.runs.boxes.data();
  const std::uint32_t* const runsEnd = runBox + o.runs.boxes.size();
  const std::uint32_t* label = o.components.boxLabel.data();
  std::vector<Coord> ends(pixels.wordsPerRow() * 64 + 2);
  const std::int32_t dx = o.offset[0];
  std::uint32_t nextBox = 0;
  for (std::int32_t y = 0; y < pixels.size(1); ++y)
  {
    const Coord* const last = pixelRowRunEnds(pixels, y, ends.data());
    // Consecutive runs of one region are added up before their region's record is touched.
    for (const Coord* e = ends.data(); e != last;)
    {
      // The runs of a row meet regions at random (a maze's 642,115): the record of a run
      // further on is fetched ahead.
      constexpr std::ptrdiff_t Ahead = 16;
      if (runsEnd - runBox > Ahead)
        prefetch(regions.data() + o.firstRegion + label[runBox[Ahead]] - 1);
      const std::uint32_t region = label[*runBox];
      const Coord x0 = e[0];
      std::int64_t voxels = 0, doubledX = 0;
      std::uint32_t boxes = 0;
      Coord x1 = x0;
      do
      {
        x1 = e[1];
        const std::int64_t length = x1 - e[0];
        voxels += length;
        doubledX += length * (std::int64_t(e[0]) + x1 + 2 * dx);
        const bool begins = *runBox == nextBox;
        boxes += begins;
        nextBox += begins;
        ++runBox;
        e += 2;
      } while (e != last && label[*runBox] == region);
      const std::size_t g = o.firstRegion + region - 1;
      regions.touch(g).addRowRuns(
        { x0 + dx, x1 + dx }, y + o.offset[1], o.offset[2], voxels, doubledX, boxes);
      regions.noteSize(g);
    }
  }
}

} // namespace

//------------------------------------------------------------------------------
template<typename Record>
void measureObject(const LabelledObject& o, RegionRecords<Record>& regions)
{
  if constexpr (std::is_same<Record, RegionRecord>::value)
  {
    if (o.labelledFromRuns)
    {
      measureRegionsOfRuns(o, regions);
      return;
    }
  }
  else
    assert(!o.labelledFromRuns); // PlanarRegion records are not for 3D runs
  if (o.labelledFromPixelRuns)
  {
    measureRegionsOfPixelRuns(o, regions);
    return;
  }
  regions.addBoxes(o.cudb.boxes.data(),
    o.components.boxLabel.data(),
    o.cudb.boxes.size(),
    std::size_t(o.firstRegion) - 1, // labels start at 1
    o.offset);
}

template void measureObject(const LabelledObject&, RegionRecords<RegionRecord>&);
template void measureObject(const LabelledObject&, RegionRecords<PlanarRegion>&);

namespace
{

/// Whether `planar`, seen as a RegionRecord of plane z, holds `full`'s values, field by field (the
/// first difference told on `log`).
bool sameRegion(const PlanarRegion& planar,
  std::int32_t z,
  const RegionRecord& full,
  int trial,
  std::ostream& log)
{
  const RegionRecord r = planar.asRegion(z);
  bool same = r.voxels == full.voxels && r.boxes == full.boxes;
  for (int d = 0; d < 3; ++d)
    same = same && r.lo[d] == full.lo[d] && r.hi[d] == full.hi[d] &&
      r.doubledCentre[d] == full.doubledCentre[d];
  if (!same)
    log << "planar record " << trial << ": voxels " << r.voxels << " / " << full.voxels
        << ", boxes " << r.boxes << " / " << full.boxes << ", bounds " << r.lo[0] << ' ' << r.lo[1]
        << ' ' << r.lo[2] << ' ' << r.hi[0] << ' ' << r.hi[1] << ' ' << r.hi[2] << " / "
        << full.lo[0] << ' ' << full.lo[1] << ' ' << full.lo[2] << ' ' << full.hi[0] << ' '
        << full.hi[1] << ' ' << full.hi[2] << '\n';
  return same;
}

} // namespace

//------------------------------------------------------------------------------
bool checkPlanarRecords(int seed, int trials, std::ostream& log)
{
  constexpr std::int32_t Side = static_cast<std::int32_t>(PlanarRegion::LargestSide);
  std::mt19937 random(static_cast<unsigned>(seed));
  // Coordinates in [0, Side], one in two at the ends 0 and Side.
  const auto coordinate = [&random]() -> std::int32_t
  {
    switch (random() % 4)
    {
      case 0:
        return 0;
      case 1:
        return Side;
      default:
        return static_cast<std::int32_t>(random() % (Side + 1));
    }
  };
  // [a, b), a < b, of at most `longest` along the axis.
  const auto span = [&](std::int32_t longest)
  {
    std::int32_t a = coordinate(), b = coordinate();
    if (a > b)
      std::swap(a, b);
    if (b - a > longest)
      (random() % 2 ? b = a + longest : a = b - longest);
    if (a == b)
      (a == 0 ? ++b : --a);
    return std::make_pair(a, b);
  };
  bool same = true;
  for (int trial = 0; trial < trials; ++trial)
  {
    const std::int32_t z = static_cast<std::int32_t>(random() % 3);
    PlanarRegion planar, bounded;
    RegionRecord full;
    planar.start();
    bounded.start();
    full.start();
    const int items = trial == 0 ? 1 : 1 + static_cast<int>(random() % 24);
    for (int item = 0; item < items; ++item)
    {
      // Boxes thin along one axis (the voxels of a region of a 2D image stay below 2^32; the
      // first trial is the whole image), rows one pixel high.
      const bool wide = random() % 2 == 0;
      const auto xs = span(trial == 0 || wide ? Side : 3);
      const auto ys = span(trial == 0 || !wide ? Side : 3);
      if (random() % 3 != 0)
      {
        const Point3 offset{ static_cast<std::int32_t>(random() % (xs.first + 1)),
          static_cast<std::int32_t>(random() % (ys.first + 1)),
          z };
        Box box;
        box.lo = { xs.first - offset[0], ys.first - offset[1], 0 };
        box.hi = { xs.second - offset[0], ys.second - offset[1], 1 };
        planar.add(box, offset);
        full.add(box, offset);
        PlanarRegion boxBounds = bounded; // its bounds before the box
        boxBounds.addBoxBounds(box, offset);
        bounded.addBounds(xs.first, ys.first, xs.second, ys.second);
        same = same && boxBounds.bounds == bounded.bounds;
      }
      else
      {
        const std::int32_t y = ys.first;
        const std::int64_t length = xs.second - xs.first;
        const std::int64_t doubledX = length * (std::int64_t(xs.first) + xs.second);
        const std::uint32_t boxes = random() % 2;
        planar.addRowRuns({ xs.first, xs.second }, y, z, length, doubledX, boxes);
        full.addRowRuns({ xs.first, xs.second }, y, z, length, doubledX, boxes);
        bounded.addBounds(xs.first, y, xs.second, y + 1);
      }
      same = same && planar.bounds == bounded.bounds && sameRegion(planar, z, full, trial, log);
    }
  }
  return same;
}

} // namespace vbr
