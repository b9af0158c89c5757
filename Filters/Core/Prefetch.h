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

} // namespace vbr

#endif
