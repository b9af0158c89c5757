// The column arithmetic of the standard plane recognizer's search (StandardPlane.cxx): the
// columns of a level (levelColumns) and the t range of a column (rangeOfT), each with a 64-bit
// and a 128-bit (Wide) path. It is a header of its own so that both paths can be tested
// directly: the recognizer's inputs of checkable size never reach the Wide ones. Internal:
// namespace vbr::detail, included by StandardPlane.cxx and its tests only.
#ifndef vbr_StandardPlaneColumns_h
#define vbr_StandardPlaneColumns_h

#include "Geometry.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

// The search's column loop calls these for every column and level: inlined, their calls
// cost more than their bodies.
#if defined(__GNUC__) || defined(__clang__)
#define VBR_PLANE_INLINE inline __attribute__((always_inline))
#else
#define VBR_PLANE_INLINE inline
#endif

namespace vbr
{
namespace detail
{

/// Largest omega searched for an integer normal.
constexpr std::int64_t MaximumOmega = std::int64_t(1) << 16;

inline std::int64_t floorDiv(std::int64_t a, std::int64_t b) // b > 0
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

inline std::int64_t ceilDiv(std::int64_t a, std::int64_t b) // b > 0
{
  return -floorDiv(-a, b);
}

inline Wide floorDiv(Wide a, Wide b) // b > 0
{
  constexpr Wide Small = Wide(1) << 62; // 64-bit division when it suffices: much cheaper
  if (-Small < a && a < Small && b < Small)
  {
    const std::int64_t x = std::int64_t(a), y = std::int64_t(b);
    return x >= 0 ? x / y : -((-x + y - 1) / y);
  }
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

inline Wide ceilDiv(Wide a, Wide b) // b > 0
{
  return -floorDiv(-a, b);
}

/// The polygon's range of k / omega in a frame (minNum / minDen to maxNum / maxDen).
struct ColumnRange
{
  std::int64_t minNum = 0, minDen = 1, maxNum = 0, maxDen = 1;
};

/// The t of column k of level omega inside every edge's half-plane (strictly on the strict
/// ones): [tLo, tHi], empty when tLo > tHi. In Int: std::int64_t when |k| and omega are below
/// SmallColumn (forms < 2^18 and frames < 2^20 keep every product below 2^59), else Wide.
/// The forms' coefficients along and across the columns are made once per frame (frameForms).
template<typename Int, typename Form>
VBR_PLANE_INLINE void rangeOfT(const std::vector<Form>& forms,
  std::int64_t omega,
  Int k,
  std::int64_t& tLo,
  std::int64_t& tHi)
{
  constexpr Int Far = Int(1) << 62;
  Int lo = -Far, hi = Far;
  for (std::size_t e = 0; e < forms.size() && lo <= hi; ++e)
  {
    const Form& F = forms[e];
    // F.(k a + t v, omega) = A t + B
    const Int A = F.along;
    const Int B = k * Int(F.across) + Int(F.level) * omega;
    if (A == 0)
    {
      if (B < 0 || (F.strict && B == 0))
        lo = hi + 1;
    }
    else if (A > 0) // t >= -B / A (>)
      lo = std::max(lo, F.strict ? floorDiv(-B, A) + 1 : ceilDiv(-B, A));
    else // t <= B / -A (<)
      hi = std::min(hi, F.strict ? ceilDiv(B, -A) - 1 : floorDiv(B, -A));
  }
  tLo = std::int64_t(std::max(lo, -Far));
  tHi = std::int64_t(std::min(hi, Far));
}

/// The columns kLo..kHi of level omega over the polygon's range (none when kLo > kHi). In
/// 64 bits when the numerators are below 2^40 (omega is at most MaximumOmega, 2^16, so every
/// product is below 2^56), else in Wide: the same integers.
VBR_PLANE_INLINE void levelColumns(const ColumnRange& range,
  std::int64_t omega,
  Wide& kLo,
  Wide& kHi)
{
  constexpr std::int64_t SmallNumerator = std::int64_t(1) << 40;
  if (omega <= MaximumOmega && std::llabs(range.minNum) < SmallNumerator &&
    std::llabs(range.maxNum) < SmallNumerator)
  {
    kLo = ceilDiv(omega * range.minNum, range.minDen);
    kHi = floorDiv(omega * range.maxNum, range.maxDen);
    return;
  }
  kLo = ceilDiv(Wide(omega) * range.minNum, Wide(range.minDen));
  kHi = floorDiv(Wide(omega) * range.maxNum, Wide(range.maxDen));
}

} // namespace detail
} // namespace vbr

#endif
