// Blocks of memory kept from one update of a filter to the next. An update writes outputs and
// scratch of hundreds of megabytes that the previous update has just released: freed, that
// memory went back to the kernel, which faulted in and zeroed fresh pages for the next update.
// allocateBlock takes large blocks from BlockCache (blocks an earlier update released, on
// transparent huge pages) and releaseBlock gives them back to it; BlockAllocator and
// newBlockArray put containers and arrays of scratch in such blocks. A VTK adapter hands these
// blocks to its output arrays (with releaseBlock as their free function), brackets each update
// (CacheUpdate) and each window in which the pipeline releases a filter's outputs
// (ReleaseWindow). Everything here only changes where memory comes from, never a value.
#ifndef vbr_BlockCache_h
#define vbr_BlockCache_h

#include "DefaultInitAllocator.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <new>
#include <unordered_map>
#include <vector>

namespace vbr
{

/// Whether the blocks of an output or scratch of `bytes` in all go on huge pages. glibc maps
/// a block of 32 MiB or more afresh at each update, and returns the heap's top to the kernel
/// when much is freed: the kernel then faulted the outputs in 4 KiB at a time (about 2
/// microseconds a page on the benchmark machine: half of a checkerboard's update, which
/// writes hundreds of MB once), and did so for a porous volume's 21 MB of boxes whenever other
/// work had moved the heap's top. Smaller groups stay on the heap.
constexpr std::size_t HugePagesFromBytes = std::size_t(8) << 20;
inline bool onHugePages(double bytes)
{
  return bytes >= double(HugePagesFromBytes);
}

/// Huge blocks of allocateBlock kept from one update to the next. The pipeline releases an
/// update's outputs when the next update starts, before the filter allocates that update's:
/// freed, their memory went back to the kernel (glibc unmaps or trims blocks this large), which
/// then faulted in and zeroed fresh pages for every output array again (on a porous volume with
/// boxes, about 20 MB an update and a tenth of its time). One cache for the process, shared by
/// every filter that uses it (addUser); the last one's destruction frees what it keeps.
///
/// Memory stays linear in the outputs: the cache keeps at most KeptBytes of scratch while idle,
/// and outputs only for the execution about to write them again.
/// - While the filters are idle it holds only scratch of 1 MiB or more (the region numbering's,
///   about 20 bytes a region, the regions' records, released before the update ends), at most
///   KeptBytes of it: the newest first, a block released when KeptBytes is full evicting the
///   oldest. Scratch stays past updates that do not take it: filters taking turns (a face and a
///   vertex connectivity of one image) each find their own at their next update, where the
///   update of another filter freed it and the kernel faulted it in again (a 128^3
///   checkerboard's 64 MB of records: 1,070 faults and 34 ms an update against 22 ms). Outputs are
///   kept only when the pipeline releases them just before their filter executes (ReleaseWindow,
///   from REQUEST_DATA_NOT_GENERATED to the end of REQUEST_DATA), up to KeptOutputBytes in all with
///   the scratch: that execution takes them or frees them at its end. Outputs released at any other
///   time (ReleaseData, a downstream ReleaseDataFlag, a filter destroyed) are freed at once, so no
///   more than KeptBytes is ever held while idle. (A 6001^2 maze's outputs with boxes are 884 MB,
///   468 of them the boxes' coordinates: with 512 MiB for everything, most were freed, and faulted
///   in and zeroed again by the kernel, a third of each update.)
/// - An update takes the kept blocks its arrays fit (1 to 1.25 times the size asked). When none
///   fits, the oldest kept blocks are freed before a new one is allocated, so that what is
///   kept plus what the update has taken or allocated stays within the larger of the bytes kept
///   at its start and the bytes it uses: the peak is about max(old outputs, new outputs), not
///   their sum, when the sizes change.
/// - At its end (endUpdate, also after an abort, an error or an exception) every output kept
///   before it began (in its release window) and not taken by it is freed.
/// - Before a memory check refuses an allocation, and after one failed, everything kept is
///   freed (clear: the VTK adapter registers it as vbr::vtk::reclaimMemory's reclaimer).
class BlockCache
{
public:
  static constexpr std::size_t KeptBytes = std::size_t(512) << 20;
  static constexpr std::size_t KeptOutputBytes = std::size_t(2048) << 20;

  /// The process's cache. Never destroyed: arrays may release their blocks after static
  /// destruction. It does not register itself with anything: an adapter whose host frees
  /// memory on demand registers clear() there once, before its first block is allocated
  /// through the cache (vtkCUDBConnectivity's blockCache() sets vbr::vtk::reclaimMemory's
  /// reclaimer; its constructor's addUser is the first use).
  static BlockCache& instance();

  /// A kept block of `length` bytes or a little more (a multiple of the huge page), now in use;
  /// null when none fits, after freeing the oldest kept blocks the update's budget needs.
  void* take(std::size_t length);
  /// Notes a new huge block of `length` bytes, in use.
  void track(void* block, std::size_t length);
  /// A block of allocateBlock no longer used: kept when huge, a filter exists and there is
  /// room (KeptBytes for scratch, released during an update, the oldest scratch freed to make
  /// room; KeptOutputBytes for outputs released while a filter is about to execute, see
  /// ReleaseWindow), else freed: outputs released at any other
  /// time (ReleaseData, ReleaseDataFlag, a filter destroyed) are freed at once.
  void release(void* block);
  /// A filter is about to execute: the pipeline now releases its outputs (ReleaseWindow).
  void openWindow();
  /// That filter's execution is over (blocks still kept are freed by its endUpdate).
  void closeWindow();
  /// The bytes kept now.
  std::size_t bytesKept();
  /// An update begins: its budget is what is kept now (see the class comment).
  void beginUpdate();
  /// An update ends: the outputs kept before it began and not taken by it are freed.
  void endUpdate();
  /// Frees every kept block (the memory is wanted: a check would refuse, an allocation failed).
  void clear();
  /// A filter created or destroyed; the last one frees the kept blocks.
  void addUser(int change);

private:
  struct Kept
  {
    void* block;
    std::size_t length;
    std::uint64_t release; ///< the order of releases
    bool scratch;          ///< released during an update
  };

  /// Removes the `count` oldest kept blocks (keptBytes already counted), to be freed.
  std::vector<void*> forget(std::size_t count);
  /// Removes the kept blocks for which evict(kept) holds, oldest first, counting them out of
  /// keptBytes and keptScratchBytes; returns them, to be freed.
  template<typename Predicate>
  std::vector<void*> forgetIf(Predicate evict);
  /// Removes the oldest kept scratch until at most `most` bytes of it are kept; returns the
  /// blocks, to be freed.
  std::vector<void*> forgetOldestScratch(std::size_t most);
  static void freeAll(const std::vector<void*>& blocks);

  std::mutex mutex;
  std::unordered_map<void*, std::size_t> lengths; ///< the huge blocks, in use or kept
  std::vector<Kept> kept;                         ///< oldest release first
  std::size_t keptBytes = 0;
  std::size_t keptScratchBytes = 0; ///< of keptBytes, of blocks released during an update
  std::uint64_t releases = 0;       ///< blocks kept so far: the next one's release
  int updates = 0;                  ///< updates in progress
  std::uint64_t updateStart = 0;    ///< releases when the first of them began
  std::size_t budget = 0;           ///< keptBytes then
  std::size_t used = 0;             ///< bytes taken or allocated by them since
  int users = 0;
  int windows = 0; ///< filters between their REQUEST_DATA_NOT_GENERATED and REQUEST_DATA's end
};

/// Brackets an update for BlockCache, also when it ends by an exception.
class CacheUpdate
{
public:
  CacheUpdate() { BlockCache::instance().beginUpdate(); }
  ~CacheUpdate() { BlockCache::instance().endUpdate(); }
  CacheUpdate(const CacheUpdate&) = delete;
  CacheUpdate& operator=(const CacheUpdate&) = delete;
};

/// Opens BlockCache's window for a filter's outputs: opened by the adapter just before its
/// pipeline releases the outputs the filter is about to regenerate, closed when that execution
/// is over (also after an error or an abort), or by the filter's destruction.
class ReleaseWindow
{
public:
  void open();
  void close();
  ~ReleaseWindow() { this->close(); }

private:
  bool opened = false;
};

/// Releases a block of allocateBlock (to BlockCache).
void releaseBlock(void* block);

/// Memory of `bytes` that releaseBlock releases, aligned to 64 bytes. With `huge`, a block of 1
/// MiB or more is 2 MiB-aligned, rounded up to whole huge pages (a partial one at the end is
/// faulted in 4 KiB pages) and marked for transparent huge pages, like
/// vbr::vtk::newZeroedIntArray's RegionId image, and taken from the blocks an earlier update
/// released when one fits (BlockCache). Null when refused.
void* allocateBlock(std::size_t bytes, bool huge);

/// A std::allocator over allocateBlock, whose values made without a value are left unset
/// (DefaultInit: a resize for values written next does not zero them first): scratch of 1 MiB or
/// more that an update fills comes from the blocks an earlier update released (BlockCache) rather
/// than from pages the kernel faults in and zeroes at every update (a checkerboard's region
/// numbering has 20 MB of it).
template<typename T>
struct BlockAllocator : vbr::DefaultInit<>
{
  using value_type = T;
  BlockAllocator() = default;
  template<typename U>
  BlockAllocator(const BlockAllocator<U>&) // NOLINT: rebinding, as std::allocator
  {
  }
  T* allocate(std::size_t n)
  {
    void* block = allocateBlock(n * sizeof(T), true);
    if (!block)
      throw std::bad_alloc();
    return static_cast<T*>(block);
  }
  void deallocate(T* p, std::size_t) { releaseBlock(p); }
  friend bool operator==(const BlockAllocator&, const BlockAllocator&) { return true; }
  friend bool operator!=(const BlockAllocator&, const BlockAllocator&) { return false; }
};

/// Releases a block of allocateBlock (a std::unique_ptr's deleter).
struct BlockRelease
{
  void operator()(void* block) const { releaseBlock(block); }
};

/// Room for n values of a trivial type, unset, in a block of allocateBlock (huge: cached).
template<typename T>
T* newBlockArray(std::size_t n)
{
  void* block = allocateBlock(std::max<std::size_t>(n, 1) * sizeof(T), true);
  if (!block)
    throw std::bad_alloc();
  return static_cast<T*>(block);
}

} // namespace vbr

#endif
