// The statistics of the connected regions of labelled objects, gathered in one pass over their
// boxes (or runs) in sweep order: per region its voxel count, its bounds, the sum of its voxel
// centres (doubled: integers, exact) and its box count, which the region table and the
// numbering by size read. A region's record is one cache line (RegionRecord); a 2D image's regions
// fit a record of 32 bytes (PlanarRegion), two a cache line, whose bounds follow a box by one
// SSE2 minimum. The records of all regions are one block of memory (RegionRecords, from
// BlockCache), written once as the pass first meets each region, with the sizes kept apart
// for the numbering (RegionNumbering.h).
#ifndef vbr_RegionStatistics_h
#define vbr_RegionStatistics_h

#include "BitVolume.h"
#include "BlockCache.h"
#include "CUDB.h"
#include "Geometry.h"
#include "RunLabelling.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h> // PlanarRegion::addBoxBounds
#endif

namespace vbr
{

/// The CUDB of one selected object (a label, or the whole selection of an image) and its
/// components: what the regions are measured and numbered from.
struct LabelledObject
{
  Point3 offset{ 0, 0, 0 }; ///< box origin of the object, in processing axes
  CUDB cudb;
  Components components;
  std::uint32_t firstRegion = 0; ///< global index of the object's component 1
  /// A 2D object swept along its rows (ZYX in processing axes): its pixels and their runs,
  /// from which its RegionIds are painted (paintPixelRunsOverwriting).
  BitVolume pixels;
  PixelRuns runs;
  /// A 2D object labelled on the runs of its rows without its boxes (labelPixelRuns): its
  /// regions are measured from the runs too, and `cudb` has no boxes.
  bool labelledFromPixelRuns = false;
  /// A 3D object labelled on the runs of its rows (labelledFromRuns): the runs' labels and the
  /// counts of the CUDB, and its boxes only when they are output (then in `cudb` and
  /// `components`, as the sweep would have left them).
  bool labelledFromRuns = false;
  VoxelRuns voxelRuns;
  RunComponents runComponents;

  std::uint32_t componentCount() const
  {
    return this->labelledFromRuns ? this->runComponents.count : this->components.count;
  }
  std::size_t boxCount() const
  {
    if (this->labelledFromRuns)
      return this->runComponents.boxCount;
    return this->labelledFromPixelRuns ? this->components.boxLabel.size() : this->cudb.boxes.size();
  }
  std::size_t oudbBoxCount() const
  {
    return this->labelledFromRuns ? this->runComponents.oudbBoxCount : this->cudb.oudbBoxCount;
  }
};

/// The statistics of one region's row of the table, as gathered from its boxes. Trivial: the
/// records of a million regions are started one by one as the pass meets them, not zeroed
/// first (start()).
struct RegionStats
{
  std::int64_t voxels;
  /// Twice the sum of the voxel centres, processing axes: integers, whose sums are one cycle
  /// each where the doubles' were a chain of four-cycle adds for a region of many boxes, and
  /// exact as the doubles were (below 2^53).
  std::array<std::int64_t, 3> doubledCentre;
  Point3 lo, hi; ///< processing axes, hi exclusive
};

/// One connected component: what numbering needs (its size) and its row of the table, all
/// gathered in one pass over the boxes in sweep order. One cache line per region, since the
/// boxes of a region are met in turn with those of its neighbours; the price is 64 bytes per
/// region, removed ones included, where a checkerboard has a region per selected voxel.
struct alignas(64) RegionRecord : RegionStats
{
  std::uint32_t boxes;

  /// An empty region: no voxels, bounds any box replaces.
  void start()
  {
    this->voxels = 0;
    this->doubledCentre = { 0, 0, 0 };
    this->lo.fill(std::numeric_limits<std::int32_t>::max());
    this->hi.fill(std::numeric_limits<std::int32_t>::min());
    this->boxes = 0;
  }

  /// Adds a box (processing axes, at `offset`) of the region.
  void add(const Box& box, const Point3& offset)
  {
    ++this->boxes;
    const std::int64_t volume = box.volume();
    this->voxels += volume;
    for (int d = 0; d < 3; ++d)
    {
      const std::int32_t first = box.lo[d] + offset[d], last = box.hi[d] + offset[d];
      this->lo[d] = std::min(this->lo[d], first);
      this->hi[d] = std::max(this->hi[d], last);
      this->doubledCentre[d] += volume * (std::int64_t(first) + last);
    }
  }

  /// Adds runs of row (y, z) of the region (processing axes, offset included): `voxels` voxels
  /// from extent.x0 to extent.x1, whose doubled x centres add up to `doubledX`, of which
  /// `boxes` begin a box.
  void addRowRuns(const VoxelRun& extent,
    std::int32_t y,
    std::int32_t z,
    std::int64_t voxelCount,
    std::int64_t doubledX,
    std::uint32_t boxCount)
  {
    this->boxes += boxCount;
    this->voxels += voxelCount;
    this->lo = {
      std::min(this->lo[0], extent.x0), std::min(this->lo[1], y), std::min(this->lo[2], z)
    };
    this->hi = {
      std::max(this->hi[0], extent.x1), std::max(this->hi[1], y + 1), std::max(this->hi[2], z + 1)
    };
    this->doubledCentre[0] += doubledX;
    this->doubledCentre[1] += voxelCount * (2 * std::int64_t(y) + 1);
    this->doubledCentre[2] += voxelCount * (2 * std::int64_t(z) + 1);
  }
};

/// A region of a 2D image (processing axis 2 flat) of at most 32,767 pixels a side: a
/// RegionRecord's values in 32 bytes, two records a cache line. Its voxels and boxes fit 32 bits
/// (fewer than 2^30 pixels), its bounds 16 bits, and its doubled centres' sums (below 2^46) are
/// kept along the two in-plane axes only: those along the flat axis follow from the voxels
/// (asRegion). A fax-like page's 278,445 regions are 8.9 MB rather than 17.8: the pass over its
/// boxes wrote, and the table read again, half as many lines, and each box's update does half the
/// arithmetic of a 3D one.
struct PlanarRegion
{
  std::uint32_t voxels;
  std::uint32_t boxes;
  /// lo[0], lo[1], -hi[0], -hi[1] (processing axes 0 and 1, hi exclusive): the four bounds
  /// follow a box by one minimum (one SSE2 instruction for the four).
  std::array<std::int16_t, 4> bounds;
  std::array<std::int64_t, 2> doubledCentre;

  /// Sides of the images whose regions fit the record (bounds of 16 bits, signed). Deliberately
  /// one pixel cautious: an exclusive upper bound of 32,767 would still fit a side of 32,768,
  /// but the bounds' negations then stay clear of -32,768 by one.
  static constexpr std::int64_t LargestSide = std::numeric_limits<std::int16_t>::max();

  /// An empty region: no voxels, bounds any box replaces.
  void start()
  {
    this->voxels = 0;
    this->boxes = 0;
    this->bounds.fill(std::numeric_limits<std::int16_t>::max());
    this->doubledCentre = { 0, 0 };
  }

  /// The bounds of the box (x0, y0) to (x1, y1) added.
  void addBounds(std::int32_t x0, std::int32_t y0, std::int32_t x1, std::int32_t y1)
  {
    const std::int32_t box[4] = { x0, y0, -x1, -y1 };
    for (int k = 0; k < 4; ++k)
      this->bounds[k] = static_cast<std::int16_t>(std::min<std::int32_t>(this->bounds[k], box[k]));
  }

  /// addBounds of a box (processing axes, at `offset`). With SSE2, (x0, y0, -x1, -y1) as four
  /// 16-bit values and their minimum with the bounds in one register (in scalar code the
  /// compiler merged the four 16-bit minima into one store, built by shifts and ors). Inline
  /// here: the pass over the boxes calls it for every box, and out of line (a call through the
  /// shared library's interposable symbol) that pass took 26% more instructions on test-t82.
  void addBoxBounds(const Box& box, const Point3& offset)
  {
#if defined(__SSE2__)
    const __m128i shift = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(offset.data()));
    const __m128i low =
      _mm_add_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(box.lo.data())), shift);
    const __m128i high =
      _mm_add_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(box.hi.data())), shift);
    const __m128i corners =
      _mm_unpacklo_epi64(low, _mm_sub_epi32(_mm_setzero_si128(), high)); // x0 y0 -x1 -y1
    const __m128i packed = _mm_packs_epi32(corners, corners);
    auto* const bounds = reinterpret_cast<__m128i*>(this->bounds.data());
    _mm_storel_epi64(bounds, _mm_min_epi16(_mm_loadl_epi64(bounds), packed));
#else
    this->addBounds(
      box.lo[0] + offset[0], box.lo[1] + offset[1], box.hi[0] + offset[0], box.hi[1] + offset[1]);
#endif
  }

  /// Adds a box (processing axes, at `offset`; one pixel thick along axis 2) of the region.
  void add(const Box& box, const Point3& offset)
  {
    ++this->boxes;
    const std::int32_t x0 = box.lo[0] + offset[0], x1 = box.hi[0] + offset[0];
    const std::int32_t y0 = box.lo[1] + offset[1], y1 = box.hi[1] + offset[1];
    const std::uint32_t volume =
      static_cast<std::uint32_t>(x1 - x0) * static_cast<std::uint32_t>(y1 - y0);
    this->voxels += volume;
    this->addBoxBounds(box, offset);
    this->doubledCentre[0] += std::int64_t(volume) * (x0 + x1);
    this->doubledCentre[1] += std::int64_t(volume) * (y0 + y1);
  }

  /// RegionRecord::addRowRuns of a row y of a 2D image (z, the plane, follows from the voxels).
  void addRowRuns(const VoxelRun& extent,
    std::int32_t y,
    std::int32_t /*z*/,
    std::int64_t voxelCount,
    std::int64_t doubledX,
    std::uint32_t boxCount)
  {
    this->boxes += boxCount;
    this->voxels += static_cast<std::uint32_t>(voxelCount);
    this->addBounds(extent.x0, y, extent.x1, y + 1);
    this->doubledCentre[0] += doubledX;
    this->doubledCentre[1] += voxelCount * (2 * std::int64_t(y) + 1);
  }

  /// The region's RegionRecord, its pixels in plane z of processing axis 2: the values a
  /// RegionRecord gathering the same boxes would have.
  RegionRecord asRegion(std::int32_t z) const
  {
    RegionRecord r;
    r.voxels = this->voxels;
    r.boxes = this->boxes;
    r.lo = { this->bounds[0], this->bounds[1], z };
    r.hi = { -std::int32_t(this->bounds[2]), -std::int32_t(this->bounds[3]), z + 1 };
    r.doubledCentre = { this->doubledCentre[0],
      this->doubledCentre[1],
      std::int64_t(this->voxels) * (2 * std::int64_t(z) + 1) };
    return r;
  }
};
static_assert(sizeof(PlanarRegion) == 32, "two planar regions a cache line");

/// The regions' values as a RegionRecord: the record itself, or a planar record's in plane z.
inline const RegionRecord& regionOf(const RegionRecord& r, std::int32_t)
{
  return r;
}
inline RegionRecord regionOf(const PlanarRegion& r, std::int32_t z)
{
  return r.asRegion(z);
}

/// The records of all regions, in sweep order (global region index), in one block of
/// allocateBlock. Regions are numbered in the order of their first box or run, so a pass in
/// that order starts each record when it first meets it (touch): the block is written once,
/// not zeroed and then written. The sizes are also kept apart, 8 bytes a region (noteSize):
/// the numbering reads nothing else of a region, and read them a cache line of record each
/// (64 MB on a checkerboard's million regions).
template<typename Record>
class RegionRecords
{
public:
  RegionRecords() = default;
  explicit RegionRecords(std::size_t count)
    : records(static_cast<Record*>(
        allocateBlock(count * sizeof(Record), onHugePages(double(count) * sizeof(Record)))))
    , voxelCounts(newBlockArray<std::int64_t>(count))
    , count(count)
  {
    if (!this->records)
      throw std::bad_alloc();
    std::uninitialized_default_construct_n(this->records.get(), count); // trivial: no writes
  }

  std::size_t size() const { return this->count; }
  const Record& operator[](std::size_t r) const { return this->records[r]; }
  const Record* data() const { return this->records.get(); }
  /// The voxel count of every region (as noted).
  const std::int64_t* sizes() const { return this->voxelCounts.get(); }

  /// Region r, started with those before it that were not yet.
  Record& touch(std::size_t r)
  {
    while (this->started <= r)
    {
      this->voxelCounts[this->started] = 0;
      this->records[this->started++].start();
    }
    return this->records[r];
  }

  /// Notes the size of region r after voxels were added to its record.
  void noteSize(std::size_t r) { this->voxelCounts[r] = this->records[r].voxels; }

  /// Adds boxes [0, count) (processing axes, at `offset`) to the regions first + label[b]:
  /// touch, add and noteSize of each box, with the count of records started and the block's
  /// pointers in registers (through the records' stores of 64-bit sums, which may alias
  /// them, the count was loaded and stored again at every box).
  void addBoxes(const Box* boxes,
    const std::uint32_t* label,
    std::size_t count,
    std::size_t first,
    const Point3& offset)
  {
    Record* const records = this->records.get();
    std::int64_t* const sizes = this->voxelCounts.get();
    std::size_t started = this->started;
    for (std::size_t b = 0; b < count; ++b)
    {
      const std::size_t r = first + label[b];
      for (; started <= r; ++started)
      {
        sizes[started] = 0;
        records[started].start();
      }
      Record& region = records[r];
      region.add(boxes[b], offset);
      sizes[r] = region.voxels;
    }
    this->started = started;
  }

  /// Starts the records not met (none when every region has a voxel).
  void startAll()
  {
    if (this->count > 0)
      this->touch(this->count - 1);
  }

private:
  struct Free
  {
    void operator()(Record* p) const { releaseBlock(p); }
  };
  std::unique_ptr<Record[], Free> records;
  std::unique_ptr<std::int64_t[], BlockRelease> voxelCounts;
  std::size_t count = 0, started = 0;
};

/// The regions of an image: RegionRecord records, or PlanarRegion records for a 2D image that fits
/// them (all its regions in plane `z` of processing axis 2), and which regions hold a seed.
class Regions
{
public:
  Regions() = default;
  Regions(std::size_t count, bool planar, std::int32_t z)
    : z(z)
    , planar(planar)
  {
    if (planar)
      this->flat = RegionRecords<PlanarRegion>(count);
    else
      this->full = RegionRecords<RegionRecord>(count);
  }

  bool isPlanar() const { return this->planar; }
  /// f(records) of the records in use (RegionRecords<PlanarRegion> or RegionRecords<RegionRecord>).
  template<typename F>
  decltype(auto) visit(F&& f) const
  {
    return this->planar ? f(this->flat) : f(this->full);
  }
  template<typename F>
  decltype(auto) visit(F&& f)
  {
    return this->planar ? f(this->flat) : f(this->full);
  }
  std::size_t size() const
  {
    return this->visit([](const auto& records) { return records.size(); });
  }
  const std::int64_t* sizes() const
  {
    return this->visit([](const auto& records) { return records.sizes(); });
  }

  /// Whether region r holds a seed (markSeeded).
  bool seeded(std::size_t r) const { return !this->seeds.empty() && this->seeds[r] != 0; }
  void markSeeded(std::size_t r)
  {
    if (this->seeds.empty())
      this->seeds.assign(this->size(), 0);
    this->seeds[r] = 1;
  }

  /// Starts the records not met.
  void startAll()
  {
    this->visit([](auto& records) { records.startAll(); });
  }

  RegionRecords<RegionRecord> full;
  RegionRecords<PlanarRegion> flat;
  /// The plane of a 2D image's pixels along processing axis 2.
  std::int32_t z = 0;

private:
  bool planar = false;
  std::vector<std::uint8_t> seeds;
};

/// Adds the regions of object `o` to `regions` (its component c is region o.firstRegion + c - 1):
/// their sizes and statistics from its boxes, or from its runs when it was labelled on them.
/// Records of PlanarRegion only for objects in one plane, not labelled on 3D runs.
template<typename Record>
void measureObject(const LabelledObject& o, RegionRecords<Record>& regions);
extern template void measureObject(const LabelledObject&, RegionRecords<RegionRecord>&);
extern template void measureObject(const LabelledObject&, RegionRecords<PlanarRegion>&);

/// Whether the regions of `objects` (of an image of `dims` voxels; `flatAxis` its single-voxel
/// axis when 2D, else -1) fit PlanarRegion records: the image is 2D, at most LargestSide voxels
/// a side, and its objects lie in one plane `z` (set) of processing axis 2, at non-negative
/// in-plane offsets, none labelled on 3D runs.
template<typename Object>
bool planarRecordsFit(const std::vector<Object>& objects,
  const Point3& dims,
  int flatAxis,
  std::int32_t& z)
{
  static_assert(std::is_base_of<LabelledObject, Object>::value, "objects of LabelledObject");
  if (flatAxis < 0 || objects.empty())
    return false;
  for (int d = 0; d < 3; ++d)
    if (dims[d] > PlanarRegion::LargestSide)
      return false;
  z = objects[0].offset[2]; // 0 as objects are cut today; checked in case that changes
  for (const LabelledObject& o : objects)
    if (o.labelledFromRuns || o.offset[2] != z || o.offset[0] < 0 || o.offset[1] < 0)
      return false;
  return true;
}

/// The size and the statistics of every region of `objects` (`count` regions in all, of an
/// image of `dims` voxels flat along `flatAxis` or -1), in PlanarRegion records when they fit
/// (planarRecordsFit), every record started.
template<typename Object>
Regions measureRegions(const std::vector<Object>& objects,
  std::size_t count,
  const Point3& dims,
  int flatAxis)
{
  std::int32_t z = 0;
  const bool planar = planarRecordsFit(objects, dims, flatAxis, z);
  Regions regions(count, planar, z);
  regions.visit(
    [&objects](auto& records)
    {
      for (const LabelledObject& o : objects)
        measureObject(o, records);
    });
  regions.startAll();
  return regions;
}

/// Whether PlanarRegion, over `trials` random sets of boxes and row runs (from `seed`) of a
/// plane of LargestSide pixels a side, holds the values a RegionRecord gathering them holds (its
/// SSE2 bounds as the scalar ones): the first difference is told on `log`.
bool checkPlanarRecords(int seed, int trials, std::ostream& log);

} // namespace vbr

#endif
