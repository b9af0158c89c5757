// The small integer geometry every part of the core shares, each defined once: lattice
// points and vectors (Point3), points of a plane (Point2), boxes of voxels (Box), the six
// axis directions, vector arithmetic, packed keys of points (KeyPacker, packBiased) and the
// two compiler builtins the exact predicates and the bit scans need (Wide, countTrailingZeros).
//
// Conventions: voxel (i, j, k) is the unit cube [i, i+1] x [j, j+1] x [k, k+1], so grid
// vertices (pointels) are the integer points; a direction is 2 * axis + (1 if it points to
// +axis), the numbering of the six faces of a voxel.
#ifndef vbr_Geometry_h
#define vbr_Geometry_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(_MSC_VER) && !defined(__clang__)
#include <intrin.h>
#endif

namespace vbr
{

/// A grid coordinate.
using Coord = std::int32_t;

/// A lattice point or vector of 3D space.
using Point3 = std::array<Coord, 3>;

/// A lattice point of a plane: (u, v) = (B, C) of an ABC sorting.
struct Point2
{
  Coord u, v;
  bool operator==(const Point2& o) const { return this->u == o.u && this->v == o.v; }
  bool operator!=(const Point2& o) const { return !(*this == o); }
  /// Lexicographic: the order of the vertices of a 2D EVM.
  bool operator<(const Point2& o) const { return u < o.u || (u == o.u && v < o.v); }
};

/// The voxels [lo, hi) along x, y and z.
struct Box
{
  Point3 lo{ 0, 0, 0 };
  Point3 hi{ 0, 0, 0 };

  std::int64_t volume() const
  {
    return std::int64_t(hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  }
  bool operator==(const Box& o) const { return this->lo == o.lo && this->hi == o.hi; }
};

// ---- vectors -------------------------------------------------------------------------

template<typename T>
std::array<T, 3> add(const std::array<T, 3>& a, const std::array<T, 3>& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}

template<typename T>
std::array<T, 3> sub(const std::array<T, 3>& a, const std::array<T, 3>& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

template<typename T>
std::array<T, 3> cross(const std::array<T, 3>& a, const std::array<T, 3>& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

/// a.b in 64 bits (a 64-bit normal against a point, or two such vectors).
template<typename T, typename U>
std::int64_t dot(const std::array<T, 3>& a, const std::array<U, 3>& b)
{
  return std::int64_t(a[0]) * b[0] + std::int64_t(a[1]) * b[1] + std::int64_t(a[2]) * b[2];
}

/// The unit vector of a direction (2 * axis + 1 for +axis, 2 * axis for -axis).
inline Point3 unitVector(int direction)
{
  Point3 u{ 0, 0, 0 };
  u[direction >> 1] = (direction & 1) ? 1 : -1;
  return u;
}

/// The direction of a vector along one axis (of its first non-zero coordinate); -1 for the
/// zero vector.
inline int directionOf(const Point3& u)
{
  for (int axis = 0; axis < 3; ++axis)
    if (u[axis] != 0)
      return 2 * axis + (u[axis] > 0 ? 1 : 0);
  return -1;
}

// ---- packed keys -----------------------------------------------------------------------

/// Grid coordinates of packed keys are non-negative and below 2^21.
constexpr std::int32_t PackedCoordinateLimit = 1 << 21;

/// Packs three non-negative coordinates below 2^bits into one key, the first one highest, so
/// that the integer order of keys is the lexicographic order of the points. The fewer the
/// bits, the fewer radix passes.
struct KeyPacker
{
  int bits = 21;

  /// The narrowest packer for coordinates in [0, maxCoordinate].
  static KeyPacker forMaximum(std::int32_t maxCoordinate)
  {
    KeyPacker p;
    p.bits = 1;
    while (p.bits < 21 && (std::int64_t(1) << p.bits) <= maxCoordinate)
      ++p.bits;
    return p;
  }
  std::uint64_t pack(std::int32_t a, std::int32_t b, std::int32_t c) const
  {
    return (static_cast<std::uint64_t>(a) << (2 * this->bits)) |
      (static_cast<std::uint64_t>(b) << this->bits) | static_cast<std::uint64_t>(c);
  }
  std::array<std::int32_t, 3> unpack(std::uint64_t k) const
  {
    const std::uint64_t mask = (std::uint64_t(1) << this->bits) - 1;
    return { static_cast<std::int32_t>(k >> (2 * this->bits)),
      static_cast<std::int32_t>((k >> this->bits) & mask),
      static_cast<std::int32_t>(k & mask) };
  }
  /// Third coordinate of a key.
  std::int32_t last(std::uint64_t k) const
  {
    return static_cast<std::int32_t>(k & ((std::uint64_t(1) << this->bits) - 1));
  }
};

/// Points with signed coordinates (relative positions, voxels next to the grid) packed
/// 21 bits a coordinate after a bias of 2^20: one key per point of [-2^20, 2^20)^3, below
/// 2^63, so that eight directions or less still fit beside it (key * 8 + direction).
constexpr std::int32_t BiasedCoordinateLimit = 1 << 20;
inline std::uint64_t packBiased(const Point3& p)
{
  constexpr std::uint64_t Bias = BiasedCoordinateLimit;
  return (std::uint64_t(p[0] + Bias) << 42) | (std::uint64_t(p[1] + Bias) << 21) |
    std::uint64_t(p[2] + Bias);
}

// ---- compiler builtins, wrapped once -----------------------------------------------------

#if defined(__SIZEOF_INT128__)
/// The 128-bit integer of the exact predicates: products of two 64-bit numbers, and
/// determinants of three vectors below 2^35.
using Wide = __int128;
#else
#error "VoxelBRep's exact predicates need a 128-bit integer type (GCC or Clang on a 64-bit target)"
#endif

/// The sign of an exact predicate's value: -1, 0 or 1.
inline int signOf(Wide w)
{
  return (w > 0) - (w < 0);
}

/// Number of zero bits above the highest set bit of a non-zero word.
inline int countLeadingZeros(std::uint64_t w)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_clzll(w);
#else
  int n = 0;
  for (std::uint64_t top = std::uint64_t(1) << 63; !(w & top); top >>= 1)
    ++n;
  return n;
#endif
}

/// Index of the lowest set bit of a non-zero word.
inline int countTrailingZeros(std::uint64_t w)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctzll(w);
#elif defined(_MSC_VER)
  unsigned long index = 0;
  _BitScanForward64(&index, w);
  return static_cast<int>(index);
#else
  int n = 0;
  for (; !(w & 1); w >>= 1)
    ++n;
  return n;
#endif
}

/// Number of set bits of a word.
inline int popCount(std::uint64_t w)
{
#if (defined(__POPCNT__) || defined(__aarch64__)) && (defined(__GNUC__) || defined(__clang__))
  // AArch64 counts bits in its vector unit (CNT), always there.
  return __builtin_popcountll(w);
#else
  // Without the instruction the builtin is a call into the compiler's runtime library, per
  // word: the same sum of bits by halves, inline.
  w -= (w >> 1) & 0x5555555555555555ULL;
  w = (w & 0x3333333333333333ULL) + ((w >> 2) & 0x3333333333333333ULL);
  w = (w + (w >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((w * 0x0101010101010101ULL) >> 56);
#endif
}

/// The bits of a row's word that differ from the bit before them (bit 0 from `carry`, the last
/// bit of the word before, 0 or 1): the transitions along the row, where runs start or end.
inline std::uint64_t transitions(std::uint64_t w, std::uint64_t carry)
{
  return w ^ ((w << 1) | carry);
}

// ---- convex polygons ---------------------------------------------------------------------

/// Andrew's monotone chain over items sorted lexicographically by their 2D position, without
/// repeats: the corners of their strictly convex hull, counter-clockwise when turn(o, a, b) is
/// the cross product (a - o) x (b - o); corners where the boundary goes straight on are
/// dropped. One item gives itself, flat items their two extremes.
template<typename T, typename Turn>
std::vector<T> monotoneChain(const std::vector<T>& sorted, Turn turn)
{
  if (sorted.size() <= 1)
    return sorted;
  std::vector<T> chain(2 * sorted.size());
  std::size_t n = 0;
  for (std::size_t s = 0; s < sorted.size(); ++s)
  {
    while (n >= 2 && turn(chain[n - 2], chain[n - 1], sorted[s]) <= 0)
      --n;
    chain[n++] = sorted[s];
  }
  for (std::size_t s = sorted.size() - 1, lower = n + 1; s-- > 0;)
  {
    while (n >= lower && turn(chain[n - 2], chain[n - 1], sorted[s]) <= 0)
      --n;
    chain[n++] = sorted[s];
  }
  chain.resize(n - 1);
  return chain;
}

} // namespace vbr

#endif
