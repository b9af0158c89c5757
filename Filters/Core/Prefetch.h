// A hint to the processor to start reading a cache line that is read soon. The walks over
// surfels, the simplifier's collapses and CUDB's labelling read data scattered over memory;
// fetched ahead, their cache misses overlap instead of following one another. Results never
// depend on it; where the compiler has no such hint it does nothing.
#ifndef vbr_Prefetch_h
#define vbr_Prefetch_h

namespace vbr
{

inline void prefetch(const void* address)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

/// prefetch, kept by the compiler in a loop that does nothing else: GCC 12 at -O3 removed the
/// prefetches of the plane sweep's read-ahead loop (PlaneSweep2D.cxx), whose hints have no
/// effect it must keep; an empty asm statement, which it must keep, takes the address.
inline void prefetchKept(const void* address)
{
  prefetch(address);
#if defined(__GNUC__) || defined(__clang__)
  __asm__ __volatile__("" : : "r"(address));
#endif
}

} // namespace vbr

#endif
