// Selection of voxels from a scalar array into a BitVolume (templated, VTK-free).
#ifndef vbr_Selection_h
#define vbr_Selection_h

#include "BitVolume.h"
#include "Execution.h"
#include "Geometry.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#include <emmintrin.h>
#endif

namespace vbr
{

/// Where the scalars of a box of voxels are: element (i, j, k) is
/// data[i * stride[0] + j * stride[1] + k * stride[2]] (strides in elements).
template<typename T>
struct ScalarGrid
{
  const T* data = nullptr;
  std::array<std::int64_t, 3> stride{ 0, 0, 0 };
  std::array<std::int32_t, 3> dims{ 0, 0, 0 };

  const T& at(std::int32_t i, std::int32_t j, std::int32_t k) const
  {
    return data[i * stride[0] + j * stride[1] + k * stride[2]];
  }
};

/// Bit k of the result is byte k of `flags`, whose bytes are 0 or 1: the product places byte k
/// at bit 49 + k, and no two partial products share a bit, so nothing carries.
inline Word packEightFlags(std::uint64_t flags)
{
  return ((flags * 0x0002040810204081ULL) >> 49) & 0xFF;
}

/// Bit k of the result is flags[k], for 64 flags whose bytes are 0 or 1: with SSE2 sixteen at a
/// time (the sign bits of a comparison with zero, gathered by movemask), otherwise eight per
/// multiply (packEightFlags).
inline Word packSixtyFourFlags(const std::uint8_t* flags)
{
  Word w = 0;
#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
  const __m128i zero = _mm_setzero_si128();
  for (int i = 0; i < 4; ++i)
  {
    const __m128i f = _mm_loadu_si128(reinterpret_cast<const __m128i*>(flags + 16 * i));
    const auto bits = static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_cmpgt_epi8(f, zero)));
    w |= Word(bits & 0xFFFFu) << (16 * i);
  }
#else
  for (int byte = 0; byte < 8; ++byte)
  {
    std::uint64_t eight;
    std::memcpy(&eight, flags + 8 * byte, 8);
    w |= packEightFlags(eight) << (8 * byte);
  }
#endif
  return w;
}

/// Voxels of `box` whose value satisfies `selected`, packed 64 per word, parallel over rows.
template<typename T, typename Predicate>
BitVolume selectVoxels(const ScalarGrid<T>& grid,
  const Box& box,
  Predicate selected,
  const Execution& exec)
{
  BitVolume out(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]);
  const std::int32_t nx = out.size(0), ny = out.size(1);
  exec.forRange(static_cast<std::int64_t>(ny) * out.size(2),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t r = b; r < e; ++r)
      {
        const std::int32_t y = static_cast<std::int32_t>(r % ny);
        const std::int32_t z = static_cast<std::int32_t>(r / ny);
        const T* src = &grid.at(box.lo[0], box.lo[1] + y, box.lo[2] + z);
        const std::int64_t sx = grid.stride[0];
        Word* dst = out.row(y, z);
        std::uint8_t flags[64];
        for (std::int32_t x0 = 0; x0 < nx; x0 += 64)
        {
          const std::int32_t n = std::min<std::int32_t>(64, nx - x0);
          // Flags first (a loop the compiler vectorizes, in a copy for unit strides: a loop
          // of its own for them was vectorized worse, twice the instructions on porous 64^3),
          // then packed (packSixtyFourFlags).
          for (std::int32_t i = 0; i < n; ++i)
            flags[i] = selected(src[(x0 + i) * sx]) ? 1 : 0;
          for (std::int32_t i = n; i < 64; ++i)
            flags[i] = 0;
          dst[x0 >> 6] = packSixtyFourFlags(flags);
        }
      }
    });
  return out;
}

/// Every distinct value other than `*background` (none when null) and NaN, with the
/// bounding box of its voxels.
template<typename T>
std::map<T, Box> labelBoxes(const ScalarGrid<T>& grid, const T* background)
{
  std::map<T, Box> boxes;
  for (std::int32_t k = 0; k < grid.dims[2]; ++k)
    for (std::int32_t j = 0; j < grid.dims[1]; ++j)
    {
      Box* current = nullptr;
      T currentValue{};
      for (std::int32_t i = 0; i < grid.dims[0]; ++i)
      {
        const T value = grid.at(i, j, k);
        if ((background && value == *background) || value != value) // background or NaN
          continue;
        if (!current || !(value == currentValue))
        {
          auto it = boxes.find(value);
          if (it == boxes.end())
          {
            Box b;
            b.lo = { i, j, k };
            b.hi = { i + 1, j + 1, k + 1 };
            it = boxes.emplace(value, b).first;
          }
          current = &it->second;
          currentValue = value;
        }
        const std::array<std::int32_t, 3> p{ i, j, k };
        for (int d = 0; d < 3; ++d)
        {
          current->lo[d] = std::min(current->lo[d], p[d]);
          current->hi[d] = std::max(current->hi[d], p[d] + 1);
        }
      }
    }
  return boxes;
}

} // namespace vbr

#endif
