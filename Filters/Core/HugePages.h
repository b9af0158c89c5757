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
#include <cstdlib>
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

/// Asks for huge pages under the whole 2 MiB pages inside [data, data + bytes), for the memory
/// not touched yet (pages already mapped stay as they are). Rounded inwards: the advice stays on
/// the range's own memory, never on a neighbour's in the heap (an advised range of the heap
/// keeps its flag after it is freed; a block malloc mapped on its own is then split, and
/// realloc copies it rather than remapping it: no matter for a std::vector, which never
/// reallocs). Nothing below `minimum` bytes (at least one whole huge page lies in 4 MiB).
inline void adviseHugePages(const void* data,
  std::size_t bytes,
  std::size_t minimum = HugePageMinimum)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes < minimum)
    return;
  const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + HugePageBytes - 1) & ~(HugePageBytes - 1);
  const std::uintptr_t last = (begin + bytes) & ~(HugePageBytes - 1);
  if (last > first)
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
  (void)minimum;
#endif
}

/// Room for n values in `v`, with huge pages asked for under it when it is large; for a vector
/// about to be filled (resize, assign, push_back up to n) while its pages are not touched.
template<typename T, typename A>
void reserveHugePages(std::vector<T, A>& v, std::size_t n, std::size_t minimum = HugePageMinimum)
{
  v.reserve(n);
  adviseHugePages(v.data(), v.capacity() * sizeof(T), minimum);
}

/// `v` emptied and then holding n copies of `value`, its new memory advised (reserveHugePages)
/// before it is written.
template<typename T, typename A>
void assignHugePages(std::vector<T, A>& v,
  std::size_t n,
  const T& value,
  std::size_t minimum = HugePageMinimum)
{
  if (v.capacity() < n)
    std::vector<T, A>().swap(v); // no copy of the old values into the new room
  reserveHugePages(v, n, minimum);
  v.assign(n, value);
}

#if defined(__linux__) && defined(MADV_HUGEPAGE) && defined(MREMAP_MAYMOVE)
#define VBR_HUGE_BLOCKS 1
#endif

/// Blocks of memory of their own mapping, apart from the heap, advised for huge pages from the
/// start: for arrays that grow by doubling to hundreds of megabytes (the output's points and
/// cells). malloc serves blocks up to 32 MiB from its heap once a block that large was freed,
/// and realloc then copies them into pages faulted in afresh; a mapping grows by mremap, which
/// moves its pages and copies nothing. The mapping's length is a multiple of 2 MiB (Linux 6.7
/// and later then place it on a huge page boundary; earlier kernels may leave its first and
/// last 2 MiB in small pages) and is kept in a header before the data; the data are 64-byte
/// aligned. nullptr when the system refuses (or is not Linux): use malloc then.
namespace hugeblock
{
/// The header before a block's data: its mapping's length, then Cookie. The data start Header
/// bytes after the mapping's (page-aligned) start.
constexpr std::size_t Header = 64;
constexpr std::uint64_t Cookie = 0x5642524875676542ull;

inline std::size_t mappingLength(std::size_t bytes)
{
  return (bytes + Header + HugePageBytes - 1) / HugePageBytes * HugePageBytes;
}

inline char* baseOf(void* data)
{
  return static_cast<char*>(data) - Header;
}

/// Whether `data` is a block of mapHugeBlock: Header bytes into a page, after the cookie. The
/// words read lie in the same page as `data`, so they are mapped whatever `data` is; for a
/// block of malloc they are the allocator's or a neighbour's bytes, hence no address check.
#if defined(__clang__) || defined(__GNUC__)
__attribute__((no_sanitize_address))
#endif
inline bool
isBlock(const void* data)
{
  if (reinterpret_cast<std::uintptr_t>(data) % 4096 != Header)
    return false;
  const std::uint64_t* words =
    reinterpret_cast<const std::uint64_t*>(baseOf(const_cast<void*>(data)));
  return words[1] == Cookie;
}
} // namespace hugeblock

/// A block of at least `bytes` bytes (HugePageMinimum or more is what it is for), or nullptr.
inline void* mapHugeBlock(std::size_t bytes)
{
#ifdef VBR_HUGE_BLOCKS
  if (bytes > std::size_t(-1) / 2)
    return nullptr;
  const std::size_t length = hugeblock::mappingLength(bytes);
  void* base = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (base == MAP_FAILED)
    return nullptr;
  madvise(base, length, MADV_HUGEPAGE); // before the header's write faults its page in
  static_cast<std::uint64_t*>(base)[0] = length;
  static_cast<std::uint64_t*>(base)[1] = hugeblock::Cookie;
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
#ifdef VBR_HUGE_BLOCKS
  if (bytes > std::size_t(-1) / 2)
    return nullptr;
  char* base = hugeblock::baseOf(data);
  const std::uint64_t old = *reinterpret_cast<std::uint64_t*>(base);
  const std::size_t length = hugeblock::mappingLength(bytes);
  if (length == old)
    return data;
  void* moved = mremap(base, static_cast<std::size_t>(old), length, MREMAP_MAYMOVE); // advice kept
  if (moved == MAP_FAILED)
    return nullptr;
  if (length > old)
    madvise(moved, length, MADV_HUGEPAGE);
  *static_cast<std::uint64_t*>(moved) = length;
  return static_cast<char*>(moved) + hugeblock::Header;
#else
  (void)data;
  (void)bytes;
  return nullptr;
#endif
}

/// Unmaps a block of mapHugeBlock (the free function of arrays that take the block over), or
/// frees a block of malloc: VTK keeps an array's free function when it empties the array and
/// later reallocates it with malloc (vtkBuffer::Allocate(0), then Reallocate by realloc), and
/// then hands that block to the same function.
inline void unmapHugeBlock(void* data)
{
  if (!data)
    return;
#ifdef VBR_HUGE_BLOCKS
  if (hugeblock::isBlock(data))
  {
    char* base = hugeblock::baseOf(data);
    munmap(base, static_cast<std::size_t>(*reinterpret_cast<std::uint64_t*>(base)));
    return;
  }
#endif
  std::free(data);
}

} // namespace vbr

#endif
