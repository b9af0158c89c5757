// Repairing H's topology after it separates (see the modifier's header, "Joining shells" and
// "Missing handles"): H held as its shells, a void or an extra piece joined to the rest by an
// empty lattice prism conv(T1 + T2) cut out of H or added to it (or a chain of two prisms),
// and a handle cut where a wall of H seals a tunnel of the object. Every change is an exact
// Boolean (LatticeMesh.h) kept only when it gives a closed 2-manifold with lattice corners,
// the expected shells and Euler characteristic, and every centre of its prism on its side.
// The object's own counts (boundary Euler characteristic, surfaces) are what H is compared with.
#ifndef vbr_TopologyRepair_h
#define vbr_TopologyRepair_h

#include "HullModifierContext.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace vbr
{
namespace detail
{

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

inline std::size_t gridIndex(const Dims& d, const LatticePoint& p)
{
  return (static_cast<std::size_t>(p[2]) * d[1] + p[1]) * d[0] + p[0];
}

/// Flags (value `flag`) the lattice points of the grid strictly enclosed by a closed shell (ray
/// parity) and, with `onFlag`, those on it; only the shell's box is scanned.
void markShell(const LatticeMesh& shell,
  const Dims& d,
  std::uint8_t flag,
  std::uint8_t onFlag,
  std::vector<std::uint8_t>& out);

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

/// Joins shells while one can be joined; returns how many were.
int joinShells(Context& ctx, LatticeMesh& surface);

/// The Euler characteristic of the object's boundary, counted once; none when the object is not
/// well-composed (see wellComposedBoundaryEuler).
const std::optional<long>& objectEuler(Context& ctx);

/// The number of surfaces of the object's boundary, counted once: its face-connected
/// components and those of the background that do not reach the grid's border.
long objectSurfaces(Context& ctx);

/// Missing handles (see the header): while H has the object's number of surfaces and a higher
/// Euler characteristic than its boundary (a well-composed object), handles are cut through the
/// walls that seal its tunnels. Returns how many; H unchanged when none was cut or the result
/// does not separate.
int cutMissingHandles(Context& ctx, LatticeMesh& surface);

} // namespace detail
} // namespace vbr

#endif
