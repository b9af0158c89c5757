// The numbering of the connected regions: the regions kept by the filters on them (a minimum
// size, the regions holding a seed, a number of largest ones) get RegionIds 1, 2, ... either
// in sweep order or ranked by size, largest first, ties in sweep order (as std::stable_sort of
// the regions in sweep order by decreasing size). The ranking picks its sort by the sizes: a
// counting sort of small sizes (noise and halftones: hundreds of thousands of regions of a few
// voxels), a radix or comparison sort of keys that hold both the size and the region index,
// and none where the sizes already never grow (a checkerboard's million regions of one voxel).
#ifndef vbr_RegionNumbering_h
#define vbr_RegionNumbering_h

#include "BlockCache.h"
#include "RegionStatistics.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

/// The RegionId of every region (0 when removed), by region in sweep order.
using RegionIdList = std::vector<std::int32_t, BlockAllocator<std::int32_t>>;
/// Region indices: the kept regions, the region of each row of the table.
/// Both lists' resize(n) and list(n) leave their new values unset (BlockAllocator, DefaultInit):
/// they are for values written next (countingSortBySize's places, numberEveryRegion's rows),
/// never read before.
using RegionList = std::vector<std::size_t, BlockAllocator<std::size_t>>;

/// The order of the RegionIds of the kept regions.
enum class RegionOrder
{
  BySize, ///< largest first, ties in sweep order
  BySweep ///< in the order the sweep meets the regions
};

namespace detail
{

// Steps of numberRegions, declared for their test (TestRegionStatistics).

/// Sorts the kept regions (indices, in sweep order) largest first, ties in sweep order, from
/// their sizes (`sizes`, by region). Small sizes by a counting sort; otherwise, when the sizes and
/// the indices fit in one 64-bit key together, by a sort of those keys (unique, so any sort
/// gives the same order): a radix sort for many (a maze has 642,115 regions, whose comparison
/// sort took longer than their table), else a comparison sort.
void rankBySize(const std::int64_t* sizes, std::size_t count, RegionList& kept);

/// numberRegions of `count` regions of sizes `sizes` when none is removed by seeds or a number
/// of largest regions: false, nothing written, when one is smaller than `minimumSize`. Every
/// region is then a row, so no list of kept regions is made and sorted apart, no RegionId is
/// zeroed first, and regions in order (by sweep, or of sizes that do not grow) are numbered
/// as they come; others are ranked by one counting sort of all the regions, which writes the
/// rows and the RegionIds as it places them (a fax-like page's 278,445 regions: a quarter of
/// the numbering's instructions).
bool numberEveryRegion(const std::int64_t* sizes,
  std::size_t count,
  std::int64_t minimumSize,
  RegionOrder ordering,
  RegionIdList& ids,
  RegionList& rows);

} // namespace detail

/// Applies the region filters and numbers the kept regions: `ids` has the RegionId of every
/// region (0 when removed), `rows` the region of each RegionId (row of the table, from 0).
/// Returns how many are kept. The sizes come from the regions' dense array of them, not from
/// their records (a cache line each).
std::int32_t numberRegions(const Regions& regions,
  std::int64_t minimumSize,
  bool useSeeds,
  std::int64_t largest,
  RegionOrder ordering,
  RegionIdList& ids,
  RegionList& rows);

/// The value painted for each label of an object labelled on its runs (by label, from 1): with
/// `regionIds`, its region's RegionId (0 where removed); without, the region's number.
std::vector<std::int32_t> valuesOfRunLabels(const LabelledObject& o, const RegionIdList* regionIds);

/// The value painted for each box of an object labelled from its boxes (a label per box, kept
/// or not): with `regionIds`, its region's RegionId (0 where removed); without, the region's
/// number.
std::vector<std::int32_t> valuesOfBoxes(const LabelledObject& o, const RegionIdList* regionIds);

} // namespace vbr

#endif
