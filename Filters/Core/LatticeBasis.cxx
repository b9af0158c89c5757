#include "LatticeBasis.h"

#include <cmath>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace vbr
{

namespace
{

using Wide = __int128;

LatticePoint minus(const LatticePoint& a, const LatticePoint& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

LatticePoint times(std::int64_t k, const LatticePoint& a)
{
  return { k * a[0], k * a[1], k * a[2] };
}

LatticePoint crossOf(const LatticePoint& a, const LatticePoint& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

Wide dotOf(const LatticePoint& a, const LatticePoint& b)
{
  return Wide(a[0]) * b[0] + Wide(a[1]) * b[1] + Wide(a[2]) * b[2];
}

/// a / b rounded to the nearest integer (b > 0; halves upwards).
std::int64_t roundedQuotient(Wide a, Wide b)
{
  Wide twice = 2 * a + b, q = twice / (2 * b);
  if (twice % (2 * b) != 0 && twice < 0)
    --q; // floor, not truncation
  return static_cast<std::int64_t>(q);
}

/// g = gcd(a, b) >= 0 with a x + b y = g.
std::int64_t extendedGcd(std::int64_t a, std::int64_t b, std::int64_t& x, std::int64_t& y)
{
  std::int64_t g = signedExtendedGcd(a, b, x, y);
  if (g < 0)
  {
    g = -g;
    x = -x;
    y = -y;
  }
  return g;
}

/// Lagrange-Gauss reduction of the 2D lattice spanned by u and w under the inner product
/// `inner` (positive definite on it): u shortest, |<u, w>| <= <u, u> / 2.
template<typename Inner>
void reducePair(LatticePoint& u, LatticePoint& w, Inner inner)
{
  for (;;)
  {
    if (inner(u, u) > inner(w, w))
      std::swap(u, w);
    const std::int64_t k = roundedQuotient(inner(u, w), inner(u, u));
    if (k == 0)
      return;
    w = minus(w, times(k, u));
  }
}

} // namespace

std::int64_t signedExtendedGcd(std::int64_t a, std::int64_t b, std::int64_t& x, std::int64_t& y)
{
  std::int64_t x0 = 1, y0 = 0, x1 = 0, y1 = 1;
  while (b != 0)
  {
    const std::int64_t q = a / b;
    std::tie(a, b) = std::make_pair(b, a - q * b);
    std::tie(x0, x1) = std::make_pair(x1, x0 - q * x1);
    std::tie(y0, y1) = std::make_pair(y1, y0 - q * y1);
  }
  x = x0;
  y = y0;
  return a;
}

LatticePoint primitive(const LatticePoint& d)
{
  const std::int64_t g = std::gcd(std::gcd(std::abs(d[0]), std::abs(d[1])), std::abs(d[2]));
  if (g == 0)
    throw std::invalid_argument("primitive: the zero vector");
  return { d[0] / g, d[1] / g, d[2] / g };
}

std::array<LatticePoint, 2> basisAroundLine(const LatticePoint& direction)
{
  const LatticePoint d = primitive(direction);
  LatticePoint u, w;
  std::int64_t s = 0, t = 0, p = 0, q = 0;
  const std::int64_t g = extendedGcd(d[0], d[1], s, t);
  if (g == 0) // d = (0, 0, +-1)
  {
    u = { 1, 0, 0 };
    w = { 0, 1, 0 };
  }
  else
  {
    extendedGcd(g, d[2], p, q); // p g + q d_z = 1
    u = { -t, s, 0 };
    w = { -q * (d[0] / g), -q * (d[1] / g), p };
  }
  // (v x d) . (w x d): d.d times the inner product of the projections orthogonal to d
  const auto alongD = [&](const LatticePoint& a, const LatticePoint& b)
  { return dotOf(a, b) * dotOf(d, d) - dotOf(a, d) * dotOf(b, d); };
  reducePair(u, w, alongD);
  for (LatticePoint* v : { &u, &w })
    *v = minus(*v, times(roundedQuotient(dotOf(*v, d), dotOf(d, d)), d));
  return { u, w };
}

PlaneLattice latticeOfPlane(const LatticePoint& normal)
{
  const LatticePoint n = primitive(normal);
  const auto uw = basisAroundLine(n);
  const Wide det = dotOf(n, crossOf(uw[0], uw[1]));
  PlaneLattice out;
  out.step = det > 0 ? crossOf(uw[0], uw[1]) : crossOf(uw[1], uw[0]);
  out.basis = { crossOf(uw[1], n), crossOf(n, uw[0]) };
  reducePair(out.basis[0], out.basis[1], dotOf);
  // the step nearest the normal through the origin: its component in the plane taken off in
  // the reduced basis (rounded; any such step is as good, a short one keeps solids compact)
  const LatticePoint &v1 = out.basis[0], &v2 = out.basis[1];
  const double g11 = double(dotOf(v1, v1)), g12 = double(dotOf(v1, v2)),
               g22 = double(dotOf(v2, v2)), b1 = double(dotOf(out.step, v1)),
               b2 = double(dotOf(out.step, v2)), det2 = g11 * g22 - g12 * g12;
  const auto a = static_cast<std::int64_t>(std::llround((b1 * g22 - b2 * g12) / det2));
  const auto b = static_cast<std::int64_t>(std::llround((b2 * g11 - b1 * g12) / det2));
  out.step = minus(minus(out.step, times(a, v1)), times(b, v2));
  return out;
}

} // namespace vbr
