// BlockCache: the blocks kept between updates, and the allocation of blocks through it (see
// BlockCache.h).
#include "BlockCache.h"

#include "HugePages.h"
#include "Sanitizers.h"

#include <cstdlib>
#include <cstring>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#ifdef __linux__
#include <sys/mman.h>
#endif

// Under AddressSanitizer BlockCache keeps no block: a use of a freed output stays detectable.
#if defined(VBR_ADDRESS_SANITIZER)
#define VBR_KEEP_BLOCKS 0
#else
#define VBR_KEEP_BLOCKS 1
#endif

namespace vbr
{
namespace
{

constexpr std::size_t HugePage = HugePageBytes;

/// A new block of `length` bytes, null when refused: with `huge` (length a multiple of
/// HugePage) 2 MiB-aligned and marked for transparent huge pages, else 64-byte aligned. From
/// the heap (glibc maps the largest apart): while the cache keeps the blocks there, the heap's
/// top is not returned to the kernel after each update with the labelling's scratch above them
/// (a block mapped apart left 50 MB of scratch faulted in again at each update of a 256^3
/// porous volume).
void* newBlock(std::size_t length, bool huge)
{
  void* block = nullptr;
  if (posix_memalign(&block, huge ? HugePage : 64, std::max<std::size_t>(length, 1)) != 0)
    return nullptr;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (huge)
    madvise(block, length, MADV_HUGEPAGE); // a hint: failure only costs time
#endif
  return block;
}

} // namespace

//------------------------------------------------------------------------------
BlockCache& BlockCache::instance()
{
  static BlockCache* cache = new BlockCache;
  return *cache;
}

//------------------------------------------------------------------------------
void* BlockCache::take(std::size_t length)
{
  std::vector<void*> evicted;
  void* block = nullptr;
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    const std::size_t most = length + length / 4;
    std::size_t best = this->kept.size();
    for (std::size_t i = 0; i < this->kept.size(); ++i)
    {
      const std::size_t l = this->kept[i].length;
      if (l >= length && l <= most && (best == this->kept.size() || l < this->kept[best].length))
        best = i;
    }
    if (best != this->kept.size())
    {
      block = this->kept[best].block;
      this->used += this->kept[best].length;
      this->keptBytes -= this->kept[best].length;
      this->keptScratchBytes -= this->kept[best].scratch ? this->kept[best].length : 0;
      this->kept.erase(this->kept.begin() + static_cast<std::ptrdiff_t>(best));
      return block;
    }
    this->used += length;
    std::size_t oldest = 0;
    while (oldest < this->kept.size() && this->keptBytes + this->used > this->budget)
      this->keptBytes -= this->kept[oldest++].length;
    evicted = this->forget(oldest);
  }
  freeAll(evicted);
  return nullptr;
}

//------------------------------------------------------------------------------
void BlockCache::track(void* block, std::size_t length)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->lengths[block] = length;
}

//------------------------------------------------------------------------------
void BlockCache::release(void* block)
{
  if (!block)
    return;
  std::vector<void*> evicted;
  bool keep = false;
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    const auto found = this->lengths.find(block);
    if (found != this->lengths.end())
    {
      const std::size_t length = found->second;
      const bool scratch = this->updates > 0;
      // Scratch makes room for itself by evicting the oldest scratch kept (of earlier updates,
      // perhaps of another filter), within KeptBytes.
      if (VBR_KEEP_BLOCKS && scratch && this->users > 0 && length <= KeptBytes)
        evicted = this->forgetOldestScratch(KeptBytes - length);
      const bool room = scratch ? this->keptBytes + length <= KeptOutputBytes &&
          this->keptScratchBytes + length <= KeptBytes
                                : this->windows > 0 && this->keptBytes + length <= KeptOutputBytes;
      if (VBR_KEEP_BLOCKS && this->users > 0 && room)
      {
        this->kept.push_back({ block, length, this->releases++, scratch });
        this->keptBytes += length;
        this->keptScratchBytes += scratch ? length : 0;
        keep = true;
      }
      else
        this->lengths.erase(found);
    }
  }
  freeAll(evicted);
  if (!keep)
    std::free(block);
}

//------------------------------------------------------------------------------
void BlockCache::openWindow()
{
  std::lock_guard<std::mutex> lock(this->mutex);
  ++this->windows;
}

//------------------------------------------------------------------------------
void BlockCache::closeWindow()
{
  std::lock_guard<std::mutex> lock(this->mutex);
  --this->windows;
}

//------------------------------------------------------------------------------
std::size_t BlockCache::bytesKept()
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->keptBytes;
}

//------------------------------------------------------------------------------
void BlockCache::beginUpdate()
{
  std::lock_guard<std::mutex> lock(this->mutex);
  if (this->updates++ > 0)
    return; // concurrent updates share the first one's budget
  this->updateStart = this->releases;
  this->budget = this->keptBytes;
  this->used = 0;
}

//------------------------------------------------------------------------------
void BlockCache::endUpdate()
{
  std::vector<void*> evicted;
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    if (--this->updates > 0)
      return;
    // Outputs released for this update and not taken by it; scratch stays (within KeptBytes)
    // for the update that needs it, which may come after other filters' updates.
    evicted =
      this->forgetIf([this](const Kept& k) { return !k.scratch && k.release < this->updateStart; });
  }
  freeAll(evicted);
}

//------------------------------------------------------------------------------
void BlockCache::clear()
{
  std::vector<void*> evicted;
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    this->keptBytes = 0;
    evicted = this->forget(this->kept.size());
  }
  freeAll(evicted);
#if defined(__GLIBC__)
  if (!evicted.empty())
    malloc_trim(0); // blocks below glibc's mmap threshold go back to the kernel too
#endif
}

//------------------------------------------------------------------------------
void BlockCache::addUser(int change)
{
  bool last = false;
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    this->users += change;
    last = this->users == 0;
  }
  if (last)
    this->clear();
}

//------------------------------------------------------------------------------
std::vector<void*> BlockCache::forget(std::size_t count)
{
  std::vector<void*> blocks;
  blocks.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    this->keptScratchBytes -= this->kept[i].scratch ? this->kept[i].length : 0;
    blocks.push_back(this->kept[i].block);
    this->lengths.erase(this->kept[i].block);
  }
  this->kept.erase(this->kept.begin(), this->kept.begin() + static_cast<std::ptrdiff_t>(count));
  return blocks;
}

//------------------------------------------------------------------------------
template<typename Predicate>
std::vector<void*> BlockCache::forgetIf(Predicate evict)
{
  std::vector<void*> blocks;
  std::size_t next = 0;
  for (const Kept& k : this->kept)
  {
    if (evict(k))
    {
      this->keptBytes -= k.length;
      this->keptScratchBytes -= k.scratch ? k.length : 0;
      blocks.push_back(k.block);
      this->lengths.erase(k.block);
    }
    else
      this->kept[next++] = k;
  }
  this->kept.resize(next);
  return blocks;
}

//------------------------------------------------------------------------------
std::vector<void*> BlockCache::forgetOldestScratch(std::size_t most)
{
  std::size_t excess = this->keptScratchBytes > most ? this->keptScratchBytes - most : 0;
  return this->forgetIf(
    [&excess](const Kept& k)
    {
      if (excess == 0 || !k.scratch)
        return false;
      excess -= std::min(excess, k.length);
      return true;
    });
}

//------------------------------------------------------------------------------
void BlockCache::freeAll(const std::vector<void*>& blocks)
{
  for (void* block : blocks)
    std::free(block);
}

//------------------------------------------------------------------------------
void ReleaseWindow::open()
{
  if (!this->opened)
    BlockCache::instance().openWindow();
  this->opened = true;
}

//------------------------------------------------------------------------------
void ReleaseWindow::close()
{
  if (this->opened)
    BlockCache::instance().closeWindow();
  this->opened = false;
}

//------------------------------------------------------------------------------
void releaseBlock(void* block)
{
  BlockCache::instance().release(block);
}

//------------------------------------------------------------------------------
void* allocateBlock(std::size_t bytes, bool huge)
{
  // From half a huge page: a block of 1 to 2 MiB (a 32-bit column of a table of 278,445 rows)
  // came from glibc's heap, whose top glibc returned to the kernel between updates depending on
  // the heap's history, and in some processes was faulted in again at every update (1,872
  // faults an update of test-t82, 17 ms against 13.4 ms without them). Rounded up to a whole
  // huge page, it is kept by the cache like the larger ones.
  huge = huge && bytes >= HugePage / 2;
  const std::size_t length = huge ? (bytes + HugePage - 1) / HugePage * HugePage : bytes;
  BlockCache& cache = BlockCache::instance();
  void* block = huge ? cache.take(length) : nullptr;
  if (!block)
  {
    block = newBlock(length, huge);
    if (!block && huge)
    {
      cache.clear();
      block = newBlock(length, huge);
    }
    if (!block)
      return nullptr;
    if (huge)
    {
      try
      {
        cache.track(block, length);
      }
      catch (...)
      {
        std::free(block); // not yet an array's
        throw;
      }
    }
  }
#ifndef NDEBUG
  // Every value is written by the filter: in a debug build (the sanitizers' tests) a value left
  // unwritten reads NaN or -1, not the zeros of fresh pages.
  std::memset(block, 0xFF, length);
#endif
  return block;
}

} // namespace vbr
