// Bit counts by the POPCNT instruction in builds that do not assume it (internal header).
//
// A build for plain x86-64 has no POPCNT, and popCount (Geometry.h) is then a dozen
// operations. Every x86-64 processor since about 2008 has the instruction: a loop that counts
// many bits is compiled twice, once as is and once in a function marked
// __attribute__((target("popcnt"))) whose body calls bitCount<true>, and the copy is picked at
// run time by hasPopCountInstruction(). Not with clang-cl (which defines __clang__ too), whose
// link against MSVC's libraries is not assumed to hold the runtime of __builtin_cpu_supports.
//
// VBR_POPCNT_COPY says whether the second copy is compiled; VBR_ALWAYS_INLINE marks the
// templated bodies, so that the copy compiled for POPCNT inlines them (a function compiled for
// a narrower target is not inlined into a wider one otherwise). The macros are not #undef'd by
// the files that include this header: in a unity build, the include guard would not define them
// again for the next file.
#ifndef vbr_PopCount_h
#define vbr_PopCount_h

#include "BitVolume.h"
#include "Geometry.h"

#include <atomic>

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(__POPCNT__) &&    \
  !defined(_MSC_VER)
#define VBR_POPCNT_COPY 1
#define VBR_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define VBR_POPCNT_COPY 0
#define VBR_ALWAYS_INLINE inline
#endif

namespace vbr
{

/// The number of set bits of w: by the instruction (Hardware, in a function compiled for it),
/// else by popCount.
template<bool Hardware>
VBR_ALWAYS_INLINE int bitCount(Word w)
{
#if VBR_POPCNT_COPY
  if constexpr (Hardware)
    return __builtin_popcountll(w);
#endif
  return popCount(w);
}

/// Set by tests to run the portable copies where the processor has the instruction too, so
/// that both copies are compared.
inline std::atomic<bool>& portableBitCountsForTesting()
{
  static std::atomic<bool> portable{ false };
  return portable;
}

/// Whether the processor counts bits by an instruction that the build does not assume (and
/// tests did not ask for the portable copies).
inline bool hasPopCountInstruction()
{
#if VBR_POPCNT_COPY
  return !portableBitCountsForTesting().load(std::memory_order_relaxed) &&
    __builtin_cpu_supports("popcnt");
#else
  return false;
#endif
}

} // namespace vbr

#endif
