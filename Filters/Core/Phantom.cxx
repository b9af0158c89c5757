// The procedural phantom: each voxel centre, in [0, 1]^3 coordinates so that the parts scale
// with the grid, is tested against the implicit shapes of the five parts (later parts win
// where they overlap).

#include "Phantom.h"

#include <cmath>
#include <cstddef>

namespace vbr
{

namespace
{

/// The label of voxel (i, j, k) of a grid of `dims`.
std::uint8_t phantomLabel(std::int32_t i,
  std::int32_t j,
  std::int32_t k,
  const std::array<std::int32_t, 3>& dims)
{
  const std::int32_t nx = dims[0], ny = dims[1], nz = dims[2];
  const double x = (i + 0.5) / nx, y = (j + 0.5) / ny, z = (k + 0.5) / nz;
  std::uint8_t label = 0;
  // 1: nested shells around (0.3, 0.3, 0.5): a shell with a cavity and a ball inside.
  const double r1 =
    std::sqrt((x - 0.3) * (x - 0.3) + (y - 0.3) * (y - 0.3) + (z - 0.5) * (z - 0.5));
  if ((r1 < 0.22 && r1 > 0.15) || r1 < 0.08)
    label = 1;
  // 2: a torus (a handle) around (0.72, 0.3, 0.5), axis z.
  const double rho = std::sqrt((x - 0.72) * (x - 0.72) + (y - 0.3) * (y - 0.3));
  if ((rho - 0.14) * (rho - 0.14) + (z - 0.5) * (z - 0.5) < 0.05 * 0.05)
    label = 2;
  // 3: a plate pierced by a row of square holes, near y = 0.75.
  if (x > 0.08 && x < 0.55 && y > 0.6 && y < 0.9 && z > 0.45 && z < 0.55)
  {
    const double hx = std::fmod((x - 0.08) / 0.47 * 4.0, 1.0);
    const bool hole = hx > 0.35 && hx < 0.65 && y > 0.7 && y < 0.8;
    if (!hole)
      label = 3;
  }
  // 4: a hollow square frame standing in x = 0.8.
  if (x > 0.76 && x < 0.84 && y > 0.6 && y < 0.9 && z > 0.2 && z < 0.8 &&
    !(y > 0.66 && y < 0.84 && z > 0.3 && z < 0.7))
    label = 4;
  // 5: three boxes, the second touching the first along an edge, the third touching
  // the second at a corner only; they sit on the frame's lower bar.
  auto box = [&](double x0, double y0, double z0, double s)
  { return x >= x0 && x < x0 + s && y >= y0 && y < y0 + s && z >= z0 && z < z0 + s; };
  const double s = 0.08;
  if (box(0.6, 0.1, 0.1, s) || box(0.6 + s, 0.1 + s, 0.1, s) ||
    box(0.6 + 2 * s, 0.1 + 2 * s, 0.1 + s, s))
    label = 5;
  return label;
}

} // namespace

std::vector<std::uint8_t> makePhantom(const std::array<std::int32_t, 3>& dims)
{
  return makePhantomPiece(dims, { 0, 0, 0 }, dims);
}

std::vector<std::uint8_t> makePhantomPiece(const std::array<std::int32_t, 3>& dims,
  const std::array<std::int32_t, 3>& first,
  const std::array<std::int32_t, 3>& size)
{
  std::vector<std::uint8_t> v(static_cast<std::size_t>(size[0]) * size[1] * size[2], 0);
  std::size_t at = 0;
  for (std::int32_t k = first[2]; k < first[2] + size[2]; ++k)
    for (std::int32_t j = first[1]; j < first[1] + size[1]; ++j)
      for (std::int32_t i = first[0]; i < first[0] + size[0]; ++i)
        v[at++] = phantomLabel(i, j, k, dims);
  return v;
}

} // namespace vbr
