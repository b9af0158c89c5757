// The numbering of the connected regions (see RegionNumbering.h).
#include "RegionNumbering.h"

#include "RadixSort.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace vbr
{
namespace
{

/// Below this many kept regions their sort keys are sorted by comparisons: the counting sort's
/// pass over every size up to the largest (a page of a few hundred regions, one of thousands of
/// pixels) and the radix sort's 2,048 buckets per digit cost more there.
constexpr std::size_t FewRegions = 4096;

/// Bits needed for the values 0 .. n.
int bitsFor(std::uint64_t n)
{
  int bits = 0;
  for (; n != 0; n >>= 1)
    ++bits;
  return bits;
}

/// Whether n regions of sizes at most `largest` are sorted by a counting sort of their sizes:
/// its pass over every size up to the largest costs little next to the regions' passes.
bool countingSortFits(std::int64_t largest, std::size_t n)
{
  const auto count = static_cast<std::int64_t>(n);
  return largest <= count + 65536 && (n >= FewRegions || largest <= 8 * count + 1024);
}

/// Ranks regions [first, last) (indices, in sweep order) largest first, ties in sweep order, by
/// a counting sort of their sizes, all at most `largest`: two passes over the regions and one
/// over the sizes (noise and halftones have hundreds of thousands of regions of a few voxels).
/// Calls place(k, r) for each region r, of rank k from 0, in sweep order.
template<typename Index, typename Place>
void countingSortBySize(const std::int64_t* sizes,
  std::int64_t largest,
  Index first,
  Index last,
  Place&& place)
{
  std::vector<std::size_t> start(static_cast<std::size_t>(largest) + 2, 0);
  for (Index i = first; i != last; ++i)
    ++start[static_cast<std::size_t>(largest - sizes[*i]) + 1];
  for (std::size_t k = 1; k < start.size(); ++k)
    start[k] += start[k - 1];
  for (Index i = first; i != last; ++i) // in sweep order: ties stay in it
  {
    const std::size_t r = *i;
    place(start[static_cast<std::size_t>(largest - sizes[r])]++, r);
  }
}

/// An iterator over the region indices 0, 1, ... themselves (countingSortBySize of them all).
struct RegionIndex
{
  std::size_t r;
  std::size_t operator*() const { return this->r; }
  RegionIndex& operator++()
  {
    ++this->r;
    return *this;
  }
  bool operator!=(const RegionIndex& other) const { return this->r != other.r; }
};

/// Whether the sizes given one after another (add) never grew: regions already largest first,
/// ties in sweep order, which no sort would move.
class AlreadyInOrder
{
public:
  void add(std::int64_t size)
  {
    this->inOrder = this->inOrder && size <= this->previous;
    this->previous = size;
  }
  bool holds() const { return this->inOrder; }

private:
  bool inOrder = true;
  std::int64_t previous = std::numeric_limits<std::int64_t>::max();
};

} // namespace

namespace detail
{

//------------------------------------------------------------------------------
void rankBySize(const std::int64_t* sizes, std::size_t count, RegionList& kept)
{
  const auto larger = [sizes](std::size_t a, std::size_t b) { return sizes[a] > sizes[b]; };
  std::int64_t largest = 0;
  for (std::size_t r : kept)
    largest = std::max(largest, sizes[r]);
  if (countingSortFits(largest, kept.size()))
  {
    RegionList sorted(kept.size()); // unset: every place written
    countingSortBySize(sizes,
      largest,
      kept.cbegin(),
      kept.cend(),
      [&sorted](std::size_t k, std::size_t r) { sorted[k] = r; });
    kept = std::move(sorted);
    return;
  }
  const int indexBits = bitsFor(count);
  if (bitsFor(static_cast<std::uint64_t>(largest)) + indexBits > 64)
  {
    std::stable_sort(kept.begin(), kept.end(), larger);
    return;
  }
  std::vector<std::uint64_t> keys(kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k)
    keys[k] = static_cast<std::uint64_t>(largest - sizes[kept[k]]) << indexBits | kept[k];
  if (keys.size() < FewRegions)
    std::sort(keys.begin(), keys.end());
  else
    radixSort(keys);
  const std::uint64_t indexMask = (std::uint64_t(1) << indexBits) - 1;
  for (std::size_t k = 0; k < kept.size(); ++k)
    kept[k] = static_cast<std::size_t>(keys[k] & indexMask);
}

//------------------------------------------------------------------------------
bool numberEveryRegion(const std::int64_t* sizes,
  std::size_t count,
  std::int64_t minimumSize,
  RegionOrder ordering,
  RegionIdList& ids,
  RegionList& rows)
{
  std::int64_t smallest = std::numeric_limits<std::int64_t>::max(), largest = 0;
  AlreadyInOrder ranked;
  for (std::size_t r = 0; r < count; ++r)
  {
    const std::int64_t size = sizes[r];
    smallest = std::min(smallest, size);
    largest = std::max(largest, size);
    ranked.add(size);
  }
  if (count > 0 && smallest < minimumSize)
    return false;
  rows.resize(count); // unset: written below
  ids.resize(count);
  if (ranked.holds() || ordering == RegionOrder::BySweep)
  {
    for (std::size_t r = 0; r < count; ++r)
    {
      rows[r] = r;
      ids[r] = static_cast<std::int32_t>(r + 1);
    }
    return true;
  }
  if (countingSortFits(largest, count))
  {
    countingSortBySize(sizes,
      largest,
      RegionIndex{ 0 },
      RegionIndex{ count },
      [&rows, &ids](std::size_t k, std::size_t r)
      {
        rows[k] = r;
        ids[r] = static_cast<std::int32_t>(k + 1);
      });
    return true;
  }
  for (std::size_t r = 0; r < count; ++r)
    rows[r] = r;
  rankBySize(sizes, count, rows);
  for (std::size_t k = 0; k < count; ++k)
    ids[rows[k]] = static_cast<std::int32_t>(k + 1);
  return true;
}

} // namespace detail

//------------------------------------------------------------------------------
std::int32_t numberRegions(const Regions& regions,
  std::int64_t minimumSize,
  bool useSeeds,
  std::int64_t largest,
  RegionOrder ordering,
  RegionIdList& ids,
  RegionList& rows)
{
  const std::int64_t* sizes = regions.sizes();
  if (!useSeeds && (largest <= 0 || static_cast<std::size_t>(largest) >= regions.size()) &&
    detail::numberEveryRegion(sizes, regions.size(), minimumSize, ordering, ids, rows))
    return static_cast<std::int32_t>(regions.size());
  RegionList& kept = rows;
  kept.clear();
  kept.reserve(regions.size());
  // Regions of one size, or already largest first (a checkerboard's million regions of one
  // voxel), are in order: the sort's keys and scratch were a fifth of that update.
  AlreadyInOrder ranked;
  for (std::size_t r = 0; r < regions.size(); ++r)
  {
    const std::int64_t size = sizes[r];
    if (size >= minimumSize && (!useSeeds || regions.seeded(r)))
    {
      ranked.add(size);
      kept.push_back(r);
    }
  }
  if (!ranked.holds())
    detail::rankBySize(sizes, regions.size(), kept);
  if (largest > 0 && static_cast<std::size_t>(largest) < kept.size())
    kept.resize(static_cast<std::size_t>(largest));
  if (ordering == RegionOrder::BySweep)
    std::sort(kept.begin(), kept.end());
  ids.assign(regions.size(), 0);
  for (std::size_t k = 0; k < kept.size(); ++k)
    ids[kept[k]] = static_cast<std::int32_t>(k + 1);
  return static_cast<std::int32_t>(kept.size());
}

//------------------------------------------------------------------------------
std::vector<std::int32_t> valuesOfRunLabels(const LabelledObject& o, const RegionIdList* regionIds)
{
  std::vector<std::int32_t> values(o.runComponents.count + 1, 0);
  for (std::uint32_t c = 1; c <= o.runComponents.count; ++c)
  {
    const std::size_t r = o.firstRegion + c - 1;
    values[c] = regionIds ? (*regionIds)[r] : static_cast<std::int32_t>(r + 1);
  }
  return values;
}

//------------------------------------------------------------------------------
std::vector<std::int32_t> valuesOfBoxes(const LabelledObject& o, const RegionIdList* regionIds)
{
  std::vector<std::int32_t> values(o.components.boxLabel.size());
  for (std::size_t b = 0; b < values.size(); ++b)
  {
    const std::size_t r = o.firstRegion + o.components.boxLabel[b] - 1;
    values[b] = regionIds ? (*regionIds)[r] : static_cast<std::int32_t>(r + 1);
  }
  return values;
}

} // namespace vbr
