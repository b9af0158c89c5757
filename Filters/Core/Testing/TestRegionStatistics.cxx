// The regions' statistics (RegionStatistics.h) and their numbering (RegionNumbering.h) against
// brute force: each region's voxel count, bounds, doubled centre sum and box count measured from
// an object's boxes, its 3D runs or its pixel runs, in RegionRecord and PlanarRegion records,
// against the same values summed voxel by voxel over the labels painted from those boxes or runs;
// the ranking by size against std::stable_sort; the numbering's filters against a direct selection.
#include "BruteForce.h"
#include "CUDB.h"
#include "EVM.h"
#include "RegionNumbering.h"
#include "RegionStatistics.h"
#include "RunLabelling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{

/// How an object's regions are labelled, as the filter's routes label them.
enum class Labelling
{
  Boxes,     ///< the CUDB's boxes and their components
  Runs,      ///< the runs of the rows (3D or 2D), with the CUDB's counts
  PixelRuns, ///< a 2D image's pixel runs, without boxes
};

/// An object labelled one way, with the region (component, from 1) of each of its voxels
/// painted directly from its boxes or runs (0 where not set), x fastest.
struct Labelled
{
  vbr::LabelledObject object;
  std::vector<std::uint32_t> voxelLabel;
  /// The boxes of each component (from 1): the boxes, the runs beginning one, or the
  /// distinct box numbers of its pixel runs.
  std::vector<std::uint32_t> boxesOf;
};

std::size_t indexOf(const vbr::Point3& dims, std::int32_t x, std::int32_t y, std::int32_t z)
{
  return (std::size_t(z) * dims[1] + y) * dims[0] + x;
}

Labelled labelFromBoxes(const vbr::BitVolume& v, vbr::Connectivity c)
{
  Labelled l;
  vbr::LabelledObject& o = l.object;
  if (v.size(2) == 1) // as the filter sweeps a 2D image: rows along x, without the EVM
    vbr::buildCUDBComponents2D(v, c, o.cudb, o.components);
  else
    EXPECT_TRUE(
      vbr::buildCUDBComponents(vbr::extractEVM(v), c, vbr::Execution(), o.cudb, o.components));
  l.voxelLabel.assign(v.voxelCount(), 0);
  l.boxesOf.assign(o.components.count + 1, 0);
  for (std::size_t b = 0; b < o.cudb.boxes.size(); ++b)
  {
    const vbr::Box& box = o.cudb.boxes[b];
    const std::uint32_t label = o.components.boxLabel[b];
    ++l.boxesOf[label];
    for (std::int32_t z = box.lo[2]; z < box.hi[2]; ++z)
      for (std::int32_t y = box.lo[1]; y < box.hi[1]; ++y)
        for (std::int32_t x = box.lo[0]; x < box.hi[0]; ++x)
          l.voxelLabel[indexOf(v.dims(), x, y, z)] = label;
  }
  return l;
}

Labelled labelFromRuns(const vbr::BitVolume& v, vbr::Connectivity c)
{
  Labelled l;
  vbr::LabelledObject& o = l.object;
  EXPECT_TRUE(vbr::extractRuns(v, vbr::Execution(), o.voxelRuns));
  EXPECT_TRUE(vbr::labelRuns(v, o.voxelRuns, c, vbr::Execution(), o.runComponents));
  o.labelledFromRuns = true;
  o.components.count = o.runComponents.count;
  l.voxelLabel.assign(v.voxelCount(), 0);
  l.boxesOf.assign(o.runComponents.count + 1, 0);
  const vbr::VoxelRuns& r = o.voxelRuns;
  for (std::int32_t z = 0; z < r.dims[2]; ++z)
    for (std::int32_t y = 0; y < r.dims[1]; ++y)
    {
      const std::size_t row = r.rowOf(y, z);
      for (std::uint32_t i = r.rowStarts[row]; i < r.rowStarts[row + 1]; ++i)
      {
        const std::uint32_t label = o.runComponents.runLabel[i];
        l.boxesOf[label] += o.runComponents.beginsBox[i];
        for (std::int32_t x = r.runs[i].x0; x < r.runs[i].x1; ++x)
          l.voxelLabel[indexOf(v.dims(), x, y, z)] = label;
      }
    }
  return l;
}

/// The runs of a 2D image's pixel rows, read from the bits one pixel at a time, each given
/// the label of the box its pixel runs name (runs in scan order, as labelPixelRuns numbers them).
Labelled labelFromPixelRuns(const vbr::BitVolume& v, vbr::Connectivity c)
{
  Labelled l;
  vbr::LabelledObject& o = l.object;
  vbr::PixelRunComponents labelled;
  EXPECT_TRUE(vbr::labelPixelRuns(v, c, vbr::Execution(), labelled));
  o.labelledFromPixelRuns = true;
  o.pixels = v;
  o.runs = labelled.runs;
  o.components = labelled.components;
  l.voxelLabel.assign(v.voxelCount(), 0);
  std::vector<std::set<std::uint32_t>> boxes(o.components.count + 1);
  std::size_t run = 0;
  for (std::int32_t y = 0; y < v.size(1); ++y)
    for (std::int32_t x = 0; x < v.size(0); ++x)
    {
      if (!v.get(x, y, 0))
        continue;
      if (x == 0 || !v.get(x - 1, y, 0))
        ++run; // a run begins
      const std::uint32_t box = o.runs.boxes.at(run - 1);
      const std::uint32_t label = o.components.boxLabel.at(box);
      boxes[label].insert(box);
      l.voxelLabel[indexOf(v.dims(), x, y, 0)] = label;
    }
  EXPECT_EQ(run, o.runs.boxes.size());
  l.boxesOf.assign(o.components.count + 1, 0);
  for (std::size_t k = 0; k < boxes.size(); ++k)
    l.boxesOf[k] = static_cast<std::uint32_t>(boxes[k].size());
  return l;
}

Labelled labelObject(const vbr::BitVolume& v, vbr::Connectivity c, Labelling how)
{
  switch (how)
  {
    case Labelling::Boxes:
      return labelFromBoxes(v, c);
    case Labelling::Runs:
      return labelFromRuns(v, c);
    default:
      return labelFromPixelRuns(v, c);
  }
}

/// The statistics of every region of the objects (at their offsets), voxel by voxel.
std::vector<vbr::RegionRecord> bruteForceRegions(const std::vector<Labelled>& objects,
  const std::vector<vbr::Point3>& dims,
  std::size_t count)
{
  std::vector<vbr::RegionRecord> out(count);
  for (vbr::RegionRecord& r : out)
    r.start();
  for (std::size_t i = 0; i < objects.size(); ++i)
  {
    const vbr::LabelledObject& o = objects[i].object;
    for (std::uint32_t label = 1; label < objects[i].boxesOf.size(); ++label)
      out[o.firstRegion + label - 1].boxes = objects[i].boxesOf[label];
    for (std::int32_t z = 0; z < dims[i][2]; ++z)
      for (std::int32_t y = 0; y < dims[i][1]; ++y)
        for (std::int32_t x = 0; x < dims[i][0]; ++x)
        {
          const std::uint32_t label = objects[i].voxelLabel[indexOf(dims[i], x, y, z)];
          if (label == 0)
            continue;
          vbr::RegionRecord& r = out[o.firstRegion + label - 1];
          const vbr::Point3 p{ x + o.offset[0], y + o.offset[1], z + o.offset[2] };
          ++r.voxels;
          for (int d = 0; d < 3; ++d)
          {
            r.lo[d] = std::min(r.lo[d], p[d]);
            r.hi[d] = std::max(r.hi[d], p[d] + 1);
            r.doubledCentre[d] += 2 * std::int64_t(p[d]) + 1;
          }
        }
  }
  return out;
}

std::string describe(const vbr::RegionRecord& r)
{
  std::ostringstream s;
  s << "voxels " << r.voxels << " boxes " << r.boxes << " lo " << r.lo[0] << ' ' << r.lo[1] << ' '
    << r.lo[2] << " hi " << r.hi[0] << ' ' << r.hi[1] << ' ' << r.hi[2] << " centre*2 "
    << r.doubledCentre[0] << ' ' << r.doubledCentre[1] << ' ' << r.doubledCentre[2];
  return s.str();
}

/// Measures the objects into records of `Record` and compares every region with brute force.
template<typename Record>
void expectMeasured(const std::vector<Labelled>& objects,
  const std::vector<vbr::Point3>& dims,
  std::size_t count,
  std::int32_t z,
  const std::string& what)
{
  vbr::RegionRecords<Record> records(count);
  for (const Labelled& l : objects)
    vbr::measureObject(l.object, records);
  records.startAll();
  const std::vector<vbr::RegionRecord> expected = bruteForceRegions(objects, dims, count);
  for (std::size_t r = 0; r < count; ++r)
  {
    const vbr::RegionRecord got = vbr::regionOf(records[r], z);
    ASSERT_EQ(describe(got), describe(expected[r])) << what << ", region " << r;
    ASSERT_EQ(records.sizes()[r], expected[r].voxels) << what << ", region " << r;
  }
}

/// Two random objects (the second's regions after the first's), of `dims`, labelled `how`.
std::vector<Labelled> randomObjects(const vbr::Point3& dims,
  vbr::Connectivity c,
  Labelling how,
  unsigned seed,
  std::vector<vbr::Point3>& objectDims)
{
  std::mt19937 random(seed);
  std::vector<Labelled> objects;
  std::uint32_t first = 0;
  for (int k = 0; k < 2; ++k)
  {
    const double density = 0.2 + 0.6 * (random() % 100) / 100.0;
    const vbr::BitVolume v = bf::randomVolume(dims, density, seed * 7 + k);
    Labelled l = labelObject(v, c, how);
    l.object.firstRegion = first;
    // Offsets as the filter's objects have them: in the image, and on plane 0 for a 2D image.
    l.object.offset = { static_cast<std::int32_t>(random() % 40),
      static_cast<std::int32_t>(random() % 40),
      dims[2] == 1 ? 0 : static_cast<std::int32_t>(random() % 40) };
    first += l.object.components.count;
    objects.push_back(std::move(l));
    objectDims.push_back(dims);
  }
  return objects;
}

std::size_t regionCount(const std::vector<Labelled>& objects)
{
  std::size_t n = 0;
  for (const Labelled& l : objects)
    n += l.object.components.count;
  return n;
}

} // namespace

TEST(RegionStatistics, VolumesAgainstVoxelSums)
{
  for (int trial = 0; trial < 24; ++trial)
    for (vbr::Connectivity c : { vbr::Connectivity::Face, vbr::Connectivity::Vertex })
      for (Labelling how : { Labelling::Boxes, Labelling::Runs })
      {
        std::vector<vbr::Point3> dims;
        const std::vector<Labelled> objects =
          randomObjects(bf::trialDims(trial, 2), c, how, 100 + trial, dims);
        expectMeasured<vbr::RegionRecord>(objects,
          dims,
          regionCount(objects),
          0,
          "3D trial " + std::to_string(trial) + (how == Labelling::Runs ? " runs" : " boxes"));
      }
}

TEST(RegionStatistics, ImagesAgainstPixelSums)
{
  for (int trial = 0; trial < 24; ++trial)
    for (vbr::Connectivity c : { vbr::Connectivity::Face, vbr::Connectivity::Vertex })
      for (Labelling how : { Labelling::Boxes, Labelling::Runs, Labelling::PixelRuns })
      {
        const vbr::Point3 d = bf::trialDims(trial, 3);
        // Rows of one word and of several (the pixel runs' scan across words).
        const vbr::Point3 image{ d[0] + (trial % 3) * 61, d[1], 1 };
        std::vector<vbr::Point3> dims;
        const std::vector<Labelled> objects = randomObjects(image, c, how, 300 + trial, dims);
        const std::string what = "2D trial " + std::to_string(trial) + " labelling " +
          std::to_string(static_cast<int>(how));
        const std::size_t n = regionCount(objects);
        expectMeasured<vbr::RegionRecord>(objects, dims, n, 0, what + " RegionRecord");
        if (how != Labelling::Runs) // PlanarRegion records are not for 3D runs
          expectMeasured<vbr::PlanarRegion>(objects, dims, n, 0, what + " PlanarRegion");
      }
}

TEST(RegionStatistics, PlanarRecordsHoldRegionValues)
{
  std::ostringstream log;
  EXPECT_TRUE(vbr::checkPlanarRecords(5, 2000, log)) << log.str();
}

namespace
{

/// Region indices, largest first, ties in sweep order: the reference ranking.
std::vector<std::size_t> stableRanking(const std::vector<std::int64_t>& sizes,
  std::vector<std::size_t> kept)
{
  std::stable_sort(kept.begin(),
    kept.end(),
    [&sizes](std::size_t a, std::size_t b) { return sizes[a] > sizes[b]; });
  return kept;
}

/// `n` sizes of 1 to `largest` (some of them `largest` itself or 1, so that ties abound).
std::vector<std::int64_t> randomSizes(std::size_t n, std::int64_t largest, std::mt19937_64& random)
{
  std::vector<std::int64_t> sizes(n);
  for (std::int64_t& s : sizes)
  {
    const unsigned pick = random() % 8;
    s = pick == 0
      ? largest
      : (pick == 1 ? 1 : 1 + static_cast<std::int64_t>(random() % std::uint64_t(largest)));
  }
  return sizes;
}

} // namespace

TEST(RegionNumbering, RankBySizeAsStableSort)
{
  std::mt19937_64 random(17);
  // Counts and sizes that take each of rankBySize's sorts: the counting sort (small sizes), a
  // comparison sort of keys (few regions), the radix sort of keys (many), and std::stable_sort
  // (sizes and indices beyond 64 bits together).
  const std::vector<std::pair<std::size_t, std::int64_t>> cases = { { 10, 5 },
    { 300, 2000 },
    { 3000, 1000000 },
    { 20000, 30 },
    { 20000, 50000000 },
    { 70000, 1 },
    { 5000, std::int64_t(1) << 55 },
    { 1, 1 },
    { 0, 1 } };
  for (const auto& [count, largest] : cases)
  {
    const std::vector<std::int64_t> sizes = randomSizes(count, largest, random);
    vbr::RegionList kept;
    std::vector<std::size_t> reference;
    for (std::size_t r = 0; r < count; ++r)
      if (random() % 4 != 0)
      {
        kept.push_back(r);
        reference.push_back(r);
      }
    vbr::detail::rankBySize(sizes.data(), count, kept);
    const std::vector<std::size_t> expected = stableRanking(sizes, reference);
    ASSERT_TRUE(std::equal(kept.begin(), kept.end(), expected.begin(), expected.end()))
      << count << " regions of sizes up to " << largest;
  }
}

namespace
{

/// Regions of objects from random volumes, measured by measureRegions (planar records for a 2D
/// image): single voxels, and sizes in a random order or already largest first.
vbr::Regions measuredRegions(unsigned seed, bool planar, std::size_t& count)
{
  std::vector<vbr::Point3> dims;
  const vbr::Point3 d = planar ? vbr::Point3{ 40, 30, 1 } : vbr::Point3{ 12, 11, 9 };
  const std::vector<Labelled> objects =
    randomObjects(d, vbr::Connectivity::Face, Labelling::Boxes, seed, dims);
  count = regionCount(objects);
  std::vector<vbr::LabelledObject> plain;
  for (const Labelled& l : objects)
    plain.push_back(l.object);
  // The image holds both objects at their offsets (below 40): a 2D one gets planar records.
  const vbr::Point3 image{ d[0] + 40, d[1] + 40, planar ? 1 : d[2] + 40 };
  vbr::Regions regions = vbr::measureRegions(plain, count, image, planar ? 2 : -1);
  EXPECT_EQ(regions.isPlanar(), planar);
  return regions;
}

} // namespace

TEST(RegionNumbering, NumberRegionsAsDirectSelection)
{
  std::mt19937 random(23);
  for (int trial = 0; trial < 40; ++trial)
  {
    std::size_t count = 0;
    vbr::Regions regions = measuredRegions(500 + trial, trial % 2 == 0, count);
    const std::int64_t* sizes = regions.sizes();
    const std::vector<std::int64_t> sizeList(sizes, sizes + count);
    const bool useSeeds = trial % 4 == 3;
    if (useSeeds)
      for (std::size_t r = 0; r < count; ++r)
        if (random() % 3 == 0)
          regions.markSeeded(r);
    const std::int64_t minimumSize = trial % 5 == 0 ? 1 + random() % 4 : 0;
    const std::int64_t largest =
      trial % 3 == 0 ? static_cast<std::int64_t>(random() % (count + 2)) : 0;
    for (vbr::RegionOrder order : { vbr::RegionOrder::BySize, vbr::RegionOrder::BySweep })
    {
      // The reference: the regions that pass the filters, ranked by size, the largest ones
      // kept, then in sweep order when asked.
      std::vector<std::size_t> kept;
      for (std::size_t r = 0; r < count; ++r)
        if (sizeList[r] >= minimumSize && (!useSeeds || regions.seeded(r)))
          kept.push_back(r);
      kept = stableRanking(sizeList, kept);
      if (largest > 0 && static_cast<std::size_t>(largest) < kept.size())
        kept.resize(static_cast<std::size_t>(largest));
      if (order == vbr::RegionOrder::BySweep)
        std::sort(kept.begin(), kept.end());
      std::vector<std::int32_t> ids(count, 0);
      for (std::size_t k = 0; k < kept.size(); ++k)
        ids[kept[k]] = static_cast<std::int32_t>(k + 1);

      vbr::RegionIdList gotIds;
      vbr::RegionList gotRows;
      const std::int32_t n =
        vbr::numberRegions(regions, minimumSize, useSeeds, largest, order, gotIds, gotRows);
      const std::string what =
        "trial " + std::to_string(trial) + " order " + std::to_string(static_cast<int>(order));
      ASSERT_EQ(static_cast<std::size_t>(n), kept.size()) << what;
      ASSERT_TRUE(std::equal(gotIds.begin(), gotIds.end(), ids.begin(), ids.end())) << what;
      ASSERT_TRUE(std::equal(gotRows.begin(), gotRows.begin() + n, kept.begin(), kept.end()))
        << what;
    }
  }
}

TEST(RegionNumbering, EveryRegionNumberedBySize)
{
  // numberEveryRegion's counting sort of all the regions (sizes that grow somewhere) and its
  // refusal when a region is below the minimum size.
  std::mt19937_64 random(29);
  for (const std::int64_t largest : { std::int64_t(3), std::int64_t(100), std::int64_t(1) << 40 })
  {
    const std::vector<std::int64_t> sizes = randomSizes(5000, largest, random);
    std::vector<std::size_t> all(sizes.size());
    std::iota(all.begin(), all.end(), std::size_t(0));
    const std::vector<std::size_t> expected = stableRanking(sizes, all);
    vbr::RegionIdList ids;
    vbr::RegionList rows;
    ASSERT_TRUE(vbr::detail::numberEveryRegion(
      sizes.data(), sizes.size(), 1, vbr::RegionOrder::BySize, ids, rows));
    ASSERT_TRUE(std::equal(rows.begin(), rows.end(), expected.begin(), expected.end())) << largest;
    for (std::size_t k = 0; k < rows.size(); ++k)
      ASSERT_EQ(ids[rows[k]], static_cast<std::int32_t>(k + 1));
    EXPECT_FALSE(vbr::detail::numberEveryRegion(
      sizes.data(), sizes.size(), 2, vbr::RegionOrder::BySize, ids, rows));
  }
}
