// Unimodular bases of the integer lattice Z^3 around a line or a plane, for the solids that
// span objects of no volume (ConvexHullModifier.h): a segment of voxel centres on a line, or a
// flat set of centres in a plane off the grid's axes.
//
// A primitive vector d (the gcd of its components 1) is the first vector of a basis (d, u, w) of
// Z^3: with g = gcd(d_x, d_y) = s d_x + t d_y and 1 = p g + q d_z (extended Euclid; gcd(g, d_z) =
// 1 because d is primitive), u = (-t, s, 0) and w = (-q d_x / g, -q d_y / g, p) give
// det(d, u, w) = d . (u x w) = p g + q d_z = 1. Adding multiples of d to u or w, of u to w, or
// swapping them keeps |det| = 1, so the basis is then reduced (Lagrange-Gauss) in the lattice
// Z^3 / Zd projected along d: u and w become the shortest steps away from the line, and each is
// moved along d towards the plane through the origin orthogonal to d.
//
// For a plane n . x = c with primitive normal n, the same basis (n, u, w) gives its inverse's
// columns: z = u x w with n . z = 1, and v1 = w x n, v2 = n x u with n . v = 0, a basis of Z^3
// too (the inverse of a unimodular matrix is integral). So the lattice points of the plane are
// p + a v1 + b v2 (a, b integers) and those of the next plane n . x = c + 1 are p + z + a v1 +
// b v2: there is no lattice point strictly between the two planes. (v1, v2) is reduced too.
//
// Components are voxel indices or small steps (below 2^20): products are taken in 128 bits.
#ifndef vbr_LatticeBasis_h
#define vbr_LatticeBasis_h

#include "ConvexHull.h"

#include <array>

namespace vbr
{

/// u, w with det(d, u, w) = +-1 for a primitive d, reduced in the projection along d (see
/// above). d must not be zero.
std::array<LatticePoint, 2> basisAroundLine(const LatticePoint& d);

/// For a primitive normal n: z with n . z = 1 and a reduced basis v1, v2 of the lattice
/// vectors orthogonal to n (see above).
struct PlaneLattice
{
  LatticePoint step;                 ///< z: from a plane to the next one, n . z = 1
  std::array<LatticePoint, 2> basis; ///< v1, v2: within the plane
};
PlaneLattice latticeOfPlane(const LatticePoint& n);

/// Euclid's algorithm with the Bezout coefficients: g with a x + b y = g, g = +-gcd(a, b) (the
/// sign the remainders leave; 0 when a = b = 0).
std::int64_t signedExtendedGcd(std::int64_t a, std::int64_t b, std::int64_t& x, std::int64_t& y);

/// The components of d divided by their gcd (d not zero).
LatticePoint primitive(const LatticePoint& d);

} // namespace vbr

#endif
