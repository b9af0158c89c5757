// The shells of H: the connected pieces of its surface (each a closed 2-manifold once H
// separates), with the exact ray parity that tells on which side of a shell, or of H, a point
// lies. The modifier's H is one mesh with points that are distinct, but most of what it asks of
// H is asked shell by shell: topology repair joins a void or an extra piece to the rest of H and
// then looks only at the shells a prism meets (TopologyRepair.h); the separation check
// (PolyhedronReversion.h) holds each shell to face away from the solid it bounds, which its
// signed volume and its nesting in the others tell; a flat layer's prisms are compared with the
// layer's regions one shell at a time (FlatObjects.h); and H's number of shells and Euler
// characteristic are compared with the object's (ConvexHullModifier.cxx). The side of a point is
// the parity of the crossings of a ray towards +x, perturbed symbolically (the same exact test as
// the reversion's rows); a shell asked often indexes its triangles by z-rows for it.
#ifndef vbr_HullShells_h
#define vbr_HullShells_h

#include "HullModifierContext.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{
namespace detail
{

/// Sign of orient2D(u, v, q + (delta, delta^2)) in (y, z), delta infinitesimal and positive,
/// the products taken in `Wide` (std::int64_t only where they fit: see rayCrossings in
/// PolyhedronReversion.cxx).
template<typename Wide>
int perturbedOrientationIn(const LatticePoint& u,
  const LatticePoint& v,
  std::int64_t y,
  std::int64_t z)
{
  const Wide o = Wide(v[1] - u[1]) * (z - u[2]) - Wide(v[2] - u[2]) * (y - u[1]);
  if (o != 0)
    return o > 0 ? 1 : -1;
  if (v[2] != u[2])
    return v[2] > u[2] ? -1 : 1;
  return v[1] > u[1] ? 1 : -1;
}

/// Whether the ray from (y, z) along +x, perturbed as in perturbedOrientationIn, meets the
/// triangle abc, s the sign of its normal's x component (the orientation of abc in (y, z)).
template<typename Wide>
bool rayMeetsTriangle(const LatticePoint& a,
  const LatticePoint& b,
  const LatticePoint& c,
  std::int64_t y,
  std::int64_t z,
  int s)
{
  return perturbedOrientationIn<Wide>(a, b, y, z) == s &&
    perturbedOrientationIn<Wide>(b, c, y, z) == s && perturbedOrientationIn<Wide>(c, a, y, z) == s;
}

/// A shell of H (a connected set of triangles; H's points are distinct, so triangles sharing a
/// point belong to one shell) with six times its signed volume (negative: an inner surface,
/// oriented into a void).
struct Shell
{
  LatticeMesh mesh;
  __int128 volume = 0;
  LatticeBox box; ///< the box of its points
  /// sideOf's index, built at its kSideQueriesBeforeIndex-th query (the joins ask many points
  /// of one shell, and scanned all its triangles for each): the triangles whose z-range meets
  /// the rows z = box[0][2] + (n << zShift) .. + 2^zShift - 1 are byZ[zStart[n] ..
  /// zStart[n + 1]). Rows are grouped by 2^zShift so that the index stays within a few
  /// entries per triangle on tall shells of long triangles. The mesh is not changed once its
  /// shell is built, so the index stays true. Built on a query through a const Shell: one
  /// thread asks a shell at a time (nothing in the modifier runs in parallel).
  mutable std::uint32_t sideQueries = 0;
  mutable int zShift = 0;
  mutable std::vector<std::size_t> zStart;
  mutable std::vector<Index> byZ;
};

std::vector<Shell> shellsOf(const LatticeMesh& m);

inline long eulerCharacteristic(const LatticeMesh& m)
{
  return static_cast<long>(m.points.size()) - static_cast<long>(m.triangles.size()) / 2;
}

/// Whether the point p / k lies strictly inside the closed surface (+1), strictly outside (-1)
/// or on it (0): the crossings of the ray towards +x (perturbed as in revertModifiedHull).
int sideOf(const LatticeMesh& surface, const LatticePoint& p, std::int64_t k);

/// sideOf from those of the surface's triangles that can reach p / k (all of them, or for k = 1
/// those trianglesAheadOf keeps for a box that holds p).
int sideOf(const LatticeMesh& surface,
  const std::vector<std::array<Index, 3>>& triangles,
  const LatticePoint& p,
  std::int64_t k);

/// sideOf for one shell whose box holds p's row, through its z-row index once it is asked often
/// (Shell::byZ).
int sideOf(const Shell& shell, const LatticePoint& p, std::int64_t k);

/// The surface's triangles in their order that can reach a lattice point of the box (sideOf with
/// k = 1 on them gives the same answer as on the whole surface for every point of the box).
std::vector<std::array<Index, 3>> trianglesAheadOf(const LatticeMesh& surface,
  const std::array<LatticePoint, 2>& box);

/// Whether every shell of a closed embedded mesh faces away from the solid it bounds, tested
/// exactly: six times a shell's signed volume (Shell::volume, the sum of det(a, b, c) over its
/// triangles, integer) is positive when it is oriented outwards, and a shell nested in an odd
/// number of others bounds a void, so it must face into it (negative), one nested in an even
/// number (none: an outer shell; two: an island in a void) outwards. The shells are apart (no
/// shared point, no crossing), so a shell lies inside another exactly when one of its points
/// does (exact ray parity, sideOf). Stricter than CGAL's does_bound_a_volume, which also
/// accepts a mesh whose shells are all turned over; unlike the closedness, manifoldness and
/// reversion checks, it sees a shell turned over whole (the ray parity of the reversion does not).
bool shellsFaceOutward(const std::vector<Shell>& shells);

} // namespace detail
} // namespace vbr

#endif
