// Huge pages under the large arrays of one update. A boundary of a porous volume writes some
// hundreds of megabytes that no earlier update left mapped (EVM sortings, the corners' bitmaps,
// the output's points and cells): in 4 KiB pages that is a page fault per 4 KiB, 14 % to 19 %
// of the filter's CPU time in the kernel on a porous 256^3 volume (about 100,000 faults per
// update). Linux maps a 2 MiB page per fault in a range advised with MADV_HUGEPAGE
// (transparent huge pages in "madvise" mode, the common default). Everything here is a hint:
// where it is refused or unknown, only time changes, never a value.
#ifndef vbr_HugePages_h
#define vbr_HugePages_h

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace vbr
{

constexpr std::size_t HugePageBytes = std::size_t(2) << 20;

/// Arrays of at least this size are worth a huge page or more: below it the rounding to whole
/// huge pages would cost more memory than the faults cost time.
constexpr std::size_t HugePageMinimum = 2 * HugePageBytes;

/// Asks for huge pages under [data, data + bytes), widened to whole 4 KiB pages, for the memory
/// not touched yet (pages already mapped stay as they are; the kernel maps huge pages only
/// where a whole 2 MiB-aligned page lies inside the range). Widened, the range covers the whole
/// mapping of a block malloc made with mmap: advising part of it would split the mapping in
/// two or three, and realloc could then no longer move it by mremap but would copy it (and
/// fault in every page again). Nothing below HugePageMinimum.
inline void adviseHugePages(const void* data, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes < HugePageMinimum)
    return;
  constexpr std::uintptr_t Page = 4096;
  const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = begin & ~(Page - 1);
  const std::uintptr_t last = (begin + bytes + Page - 1) & ~(Page - 1);
  madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

/// Room for n values in `v`, with huge pages asked for under it when it is large; for a vector
/// about to be filled (resize, assign, push_back up to n) while its pages are not touched.
template<typename T, typename A>
void reserveHugePages(std::vector<T, A>& v, std::size_t n)
{
  v.reserve(n);
  adviseHugePages(v.data(), v.capacity() * sizeof(T));
}

/// `v` emptied and then holding n copies of `value`, its new memory advised (reserveHugePages)
/// before it is written.
template<typename T, typename A>
void assignHugePages(std::vector<T, A>& v, std::size_t n, const T& value)
{
  if (v.capacity() < n)
    std::vector<T, A>().swap(v); // no copy of the old values into the new room
  reserveHugePages(v, n);
  v.assign(n, value);
}

/// Blocks of memory of their own mapping, apart from the heap, advised for huge pages from the
/// start: for arrays that grow by doubling to hundreds of megabytes (the output's points and
/// cells). malloc serves blocks up to 32 MiB from its heap once a block that large was freed,
/// and realloc then copies them into pages faulted in afresh; a mapping grows by mremap, which
/// moves its pages and copies nothing. The mapping's length (a multiple of 2 MiB, so that the
/// kernel places it on a huge page boundary) is kept in a header before the data; the data
/// are 64-byte aligned. nullptr when the system refuses (or is not Linux): use malloc then.
namespace hugeblock
{
constexpr std::size_t Header = 64;

inline std::size_t mappingLength(std::size_t bytes)
{
  return (bytes + Header + HugePageBytes - 1) / HugePageBytes * HugePageBytes;
}

inline char* baseOf(void* data)
{
  return static_cast<char*>(data) - Header;
}
} // namespace hugeblock

/// A block of at least `bytes` bytes (HugePageMinimum or more is what it is for), or nullptr.
inline void* mapHugeBlock(std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::size_t length = hugeblock::mappingLength(bytes);
  void* base = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (base == MAP_FAILED)
    return nullptr;
  madvise(base, length, MADV_HUGEPAGE); // before the header's write faults its page in
  *static_cast<std::size_t*>(base) = length;
  return static_cast<char*>(base) + hugeblock::Header;
#else
  (void)bytes;
  return nullptr;
#endif
}

/// The block of mapHugeBlock made `bytes` long, its values kept, moved if need be; nullptr
/// (and the block unchanged) when the system refuses.
inline void* remapHugeBlock(void* data, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE) && defined(MREMAP_MAYMOVE)
  char* base = hugeblock::baseOf(data);
  const std::size_t old = *reinterpret_cast<std::size_t*>(base);
  const std::size_t length = hugeblock::mappingLength(bytes);
  if (length == old)
    return data;
  void* moved = mremap(base, old, length, MREMAP_MAYMOVE); // the advice goes with the pages
  if (moved == MAP_FAILED)
    return nullptr;
  if (length > old)
    madvise(moved, length, MADV_HUGEPAGE);
  *static_cast<std::size_t*>(moved) = length;
  return static_cast<char*>(moved) + hugeblock::Header;
#else
  (void)data;
  (void)bytes;
  return nullptr;
#endif
}

/// Unmaps a block of mapHugeBlock (a free function for arrays that take the block over).
inline void unmapHugeBlock(void* data)
{
#if defined(__linux__)
  if (!data)
    return;
  char* base = hugeblock::baseOf(data);
  munmap(base, *reinterpret_cast<std::size_t*>(base));
#else
  (void)data;
#endif
}

} // namespace vbr

#endif
