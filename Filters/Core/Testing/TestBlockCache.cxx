// BlockCache's rules (BlockCache.h), on a cache of the test's own whose blocks are one byte
// each but tracked with the lengths of large blocks (the cache only counts and frees them):
// an update's scratch is kept up to KeptBytes and taken by a later update (the smallest block
// of 1 to 1.25 times the length asked); a take that finds none evicts the oldest kept blocks
// until the kept bytes and the update's use fit its budget, and no further; an update's end
// frees what was kept before it began and not taken; outputs are kept only in a release
// window, up to KeptOutputBytes; nothing is kept without a user, and the last user's leaving
// frees everything. Then allocateBlock and releaseBlock on the process's cache.
#include "BlockCache.h"
#include "Sanitizers.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>

namespace
{

constexpr std::size_t MiB = std::size_t(1) << 20;

class BlockCacheRules : public ::testing::Test
{
protected:
  void SetUp() override
  {
#if defined(VBR_ADDRESS_SANITIZER)
    GTEST_SKIP() << "the cache keeps no block under AddressSanitizer";
#endif
    this->cache.addUser(1);
  }
  void TearDown() override
  {
    this->cache.clear();
  }

  /// A new block of `length` bytes for the cache (one byte really), in use.
  void* block(std::size_t length)
  {
    void* b = std::malloc(1);
    this->cache.track(b, length);
    return b;
  }

  vbr::BlockCache cache;
};

TEST_F(BlockCacheRules, ScratchIsKeptAcrossUpdatesThatDoNotTakeIt)
{
  this->cache.beginUpdate();
  void* a = this->block(8 * MiB);
  this->cache.release(a);
  EXPECT_EQ(this->cache.bytesKept(), 8 * MiB);
  this->cache.endUpdate();
  EXPECT_EQ(this->cache.bytesKept(), 8 * MiB); // released during the update that ended

  // Another filter's update in between, which takes nothing and keeps its own scratch: the
  // first filter's scratch stays for its next update (freed there, it was faulted in again at
  // every update of filters taking turns).
  this->cache.beginUpdate();
  void* b = this->block(2 * MiB);
  this->cache.release(b);
  this->cache.endUpdate();
  EXPECT_EQ(this->cache.bytesKept(), 10 * MiB);

  this->cache.beginUpdate();
  ASSERT_EQ(this->cache.take(7 * MiB), a); // 8 <= 1.25 * 7
  EXPECT_EQ(this->cache.bytesKept(), 2 * MiB);
  this->cache.release(a);
  this->cache.endUpdate();
  EXPECT_EQ(this->cache.bytesKept(), 10 * MiB);
}

TEST_F(BlockCacheRules, NewScratchEvictsTheOldestScratchBeyondKeptBytes)
{
  using vbr::BlockCache;
  this->cache.beginUpdate();
  void* old = this->block(BlockCache::KeptBytes / 2);
  this->cache.release(old);
  this->cache.endUpdate();

  this->cache.beginUpdate();
  void* newer = this->block(BlockCache::KeptBytes / 4);
  this->cache.release(newer);
  EXPECT_EQ(this->cache.bytesKept(), BlockCache::KeptBytes / 2 + BlockCache::KeptBytes / 4);
  // Beyond KeptBytes with both: the oldest goes, the newer and the newest stay.
  this->cache.release(this->block(BlockCache::KeptBytes / 8 * 3));
  EXPECT_EQ(this->cache.bytesKept(), BlockCache::KeptBytes / 4 + BlockCache::KeptBytes / 8 * 3);
  this->cache.endUpdate();
  this->cache.beginUpdate();
  EXPECT_EQ(this->cache.take(BlockCache::KeptBytes / 4), newer);
  EXPECT_EQ(this->cache.take(BlockCache::KeptBytes / 2 - MiB), nullptr); // the old one is gone
  this->cache.endUpdate();
}

TEST_F(BlockCacheRules, TakesTheSmallestBlockThatFits)
{
  this->cache.beginUpdate();
  void* b10 = this->block(10 * MiB);
  void* b12 = this->block(12 * MiB);
  void* b9 = this->block(9 * MiB);
  this->cache.release(b10);
  this->cache.release(b12);
  this->cache.release(b9);
  this->cache.endUpdate();

  this->cache.beginUpdate();
  ASSERT_EQ(this->cache.take(8 * MiB), b9);
  ASSERT_EQ(this->cache.take(8 * MiB), b10);     // 10 = 1.25 * 8: still fits
  EXPECT_EQ(this->cache.take(8 * MiB), nullptr); // 12 > 1.25 * 8
  EXPECT_EQ(this->cache.bytesKept(), 0u);        // 12 kept + 27 used > the 31 of the budget
  this->cache.release(b9);
  this->cache.release(b10);
  this->cache.endUpdate();
}

TEST_F(BlockCacheRules, EvictsTheOldestBlocksOnlyAsFarAsTheBudgetNeeds)
{
  this->cache.beginUpdate();
  void* first = this->block(2 * MiB);
  void* second = this->block(2 * MiB);
  void* third = this->block(8 * MiB);
  this->cache.release(first);
  this->cache.release(second);
  this->cache.release(third);
  this->cache.endUpdate();

  this->cache.beginUpdate(); // budget: the 12 MiB kept
  // Nothing fits 4 MiB (2 < 4, 8 > 5): 4 MiB more used, so 12 + 4 > 12 evicts the two oldest
  // (then 8 + 4 = 12 fits) and not the third.
  EXPECT_EQ(this->cache.take(4 * MiB), nullptr);
  EXPECT_EQ(this->cache.bytesKept(), 8 * MiB);
  ASSERT_EQ(this->cache.take(8 * MiB), third); // else freed by the cache
  this->cache.release(third);
  this->cache.endUpdate();
}

TEST_F(BlockCacheRules, ScratchIsKeptUpToKeptBytes)
{
  using vbr::BlockCache;
  this->cache.beginUpdate();
  this->cache.release(this->block(BlockCache::KeptBytes - 2 * MiB));
  this->cache.release(this->block(2 * MiB)); // exactly KeptBytes: kept
  EXPECT_EQ(this->cache.bytesKept(), BlockCache::KeptBytes);
  this->cache.release(this->block(BlockCache::KeptBytes + 2 * MiB)); // larger alone: freed
  EXPECT_EQ(this->cache.bytesKept(), BlockCache::KeptBytes);
  this->cache.endUpdate();
}

TEST_F(BlockCacheRules, OutputsAreKeptOnlyInAReleaseWindow)
{
  using vbr::BlockCache;
  this->cache.release(this->block(4 * MiB)); // idle, no window: freed at once
  EXPECT_EQ(this->cache.bytesKept(), 0u);

  this->cache.openWindow();
  this->cache.release(this->block(4 * MiB));
  EXPECT_EQ(this->cache.bytesKept(), 4 * MiB);
  this->cache.release(this->block(BlockCache::KeptOutputBytes)); // beyond KeptOutputBytes
  EXPECT_EQ(this->cache.bytesKept(), 4 * MiB);
  this->cache.closeWindow();
  this->cache.release(this->block(4 * MiB)); // window closed: freed
  EXPECT_EQ(this->cache.bytesKept(), 4 * MiB);

  this->cache.beginUpdate(); // the output kept is not taken: freed at the update's end
  this->cache.endUpdate();
  EXPECT_EQ(this->cache.bytesKept(), 0u);
}

TEST_F(BlockCacheRules, TheLastUserFreesWhatIsKeptAndWithoutUsersNothingIsKept)
{
  this->cache.beginUpdate();
  this->cache.release(this->block(4 * MiB));
  this->cache.addUser(1);
  this->cache.addUser(-1); // one user left
  EXPECT_EQ(this->cache.bytesKept(), 4 * MiB);
  this->cache.addUser(-1); // none
  EXPECT_EQ(this->cache.bytesKept(), 0u);
  this->cache.release(this->block(4 * MiB));
  EXPECT_EQ(this->cache.bytesKept(), 0u);
  this->cache.endUpdate();
}

/// Allocates and releases a block of `heapBytes` (from the heap: never kept), then one of
/// `bytes`, which the cache keeps as `keptBytes` of whole huge pages and gives back for a
/// request of `reuseBytes`.
void expectKeptOnWholeHugePages(std::size_t heapBytes,
  bool heapHuge,
  std::size_t bytes,
  std::size_t keptBytes,
  std::size_t reuseBytes)
{
  vbr::BlockCache& cache = vbr::BlockCache::instance();
  cache.addUser(1);
  {
    vbr::CacheUpdate update;
    void* fromHeap = vbr::allocateBlock(heapBytes, heapHuge);
    vbr::releaseBlock(fromHeap);
    EXPECT_EQ(cache.bytesKept(), 0u);
    void* a = vbr::allocateBlock(bytes, true);
    vbr::releaseBlock(a);
    EXPECT_EQ(cache.bytesKept(), keptBytes);
    void* b = vbr::allocateBlock(reuseBytes, true);
    EXPECT_EQ(b, a);
    EXPECT_EQ(cache.bytesKept(), 0u);
    vbr::releaseBlock(b);
  }
  cache.addUser(-1); // the last user: everything freed
  EXPECT_EQ(cache.bytesKept(), 0u);
}

TEST(BlockCache, AllocateBlockRoundsToHugePagesAndReusesReleasedBlocks)
{
#if defined(VBR_ADDRESS_SANITIZER)
  GTEST_SKIP() << "the cache keeps no block under AddressSanitizer";
#endif
  // A block not asked huge is never kept; 3 MiB is kept as two whole 2 MiB pages.
  expectKeptOnWholeHugePages(3 * MiB, false, 3 * MiB, 4 * MiB, 4 * MiB);
}

TEST(BlockCache, AllocateBlockKeepsBlocksFromHalfAHugePage)
{
#if defined(VBR_ADDRESS_SANITIZER)
  GTEST_SKIP() << "the cache keeps no block under AddressSanitizer";
#endif
  // Below 1 MiB a block comes from the heap; 1 MiB (a 32-bit column of 262,144 rows) is kept
  // on a whole huge page.
  expectKeptOnWholeHugePages(MiB - 64, true, MiB, 2 * MiB, MiB + MiB / 2);
}

} // namespace
