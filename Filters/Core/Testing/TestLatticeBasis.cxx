// LatticeBasis against the definitions: det(d, u, w) = +-1 by a cofactor expansion written
// here, n . z = 1 and n . v = 0, and (z, v1, v2) a basis (determinant +-1), for every primitive
// vector with components up to 9 in size and a few large ones; reduced steps are short.
#include "LatticeBasis.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <numeric>
#include <vector>

namespace
{

using vbr::LatticePoint;

__int128 determinant(const LatticePoint& a, const LatticePoint& b, const LatticePoint& c)
{
  return __int128(a[0]) * (__int128(b[1]) * c[2] - __int128(b[2]) * c[1]) -
    __int128(a[1]) * (__int128(b[0]) * c[2] - __int128(b[2]) * c[0]) +
    __int128(a[2]) * (__int128(b[0]) * c[1] - __int128(b[1]) * c[0]);
}

__int128 dotOf(const LatticePoint& a, const LatticePoint& b)
{
  return __int128(a[0]) * b[0] + __int128(a[1]) * b[1] + __int128(a[2]) * b[2];
}

std::vector<LatticePoint> primitiveVectors()
{
  std::vector<LatticePoint> out{ { 1021, 4093, -8191 }, { 511, -262143, 3 }, { 0, 0, -1 } };
  for (long x = -9; x <= 9; ++x)
    for (long y = -9; y <= 9; ++y)
      for (long z = -9; z <= 9; ++z)
        if (std::gcd(std::gcd(std::labs(x), std::labs(y)), std::labs(z)) == 1)
          out.push_back({ x, y, z });
  return out;
}

} // namespace

TEST(LatticeBasis, CompletesAnyPrimitiveVectorToABasis)
{
  for (const LatticePoint& d : primitiveVectors())
  {
    SCOPED_TRACE(testing::Message() << d[0] << " " << d[1] << " " << d[2]);
    const auto uw = vbr::basisAroundLine(d);
    const __int128 det = determinant(d, uw[0], uw[1]);
    EXPECT_TRUE(det == 1 || det == -1);
    // reduced: each step within half of d of the plane orthogonal to d through the origin
    for (const LatticePoint& v : uw)
      EXPECT_LE(2 * (dotOf(v, d) < 0 ? -dotOf(v, d) : dotOf(v, d)), dotOf(d, d));
  }
  EXPECT_EQ(vbr::primitive({ 4, -6, 10 }), (LatticePoint{ 2, -3, 5 }));
  EXPECT_THROW(vbr::primitive({ 0, 0, 0 }), std::invalid_argument);
}

TEST(LatticeBasis, PlaneLatticeAndTheStepToTheNextPlane)
{
  for (const LatticePoint& n : primitiveVectors())
  {
    SCOPED_TRACE(testing::Message() << n[0] << " " << n[1] << " " << n[2]);
    const vbr::PlaneLattice p = vbr::latticeOfPlane(n);
    EXPECT_EQ(dotOf(n, p.step), 1);
    EXPECT_EQ(dotOf(n, p.basis[0]), 0);
    EXPECT_EQ(dotOf(n, p.basis[1]), 0);
    const __int128 det = determinant(p.step, p.basis[0], p.basis[1]);
    EXPECT_TRUE(det == 1 || det == -1);
    // Lagrange-Gauss reduced: |v1| <= |v2| and 2 |v1 . v2| <= |v1|^2
    const __int128 g12 = dotOf(p.basis[0], p.basis[1]);
    EXPECT_LE(dotOf(p.basis[0], p.basis[0]), dotOf(p.basis[1], p.basis[1]));
    EXPECT_LE(2 * (g12 < 0 ? -g12 : g12), dotOf(p.basis[0], p.basis[0]));
  }
}
