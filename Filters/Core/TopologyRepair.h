// Repairing H's topology after it separates (see the modifier's header, "Joining shells" and
// "Missing handles"): H held as its shells (HullShells.h), a void or an extra piece joined to the
// rest by an empty lattice prism conv(T1 + T2) cut out of H or added to it (or a chain of two
// prisms), and a handle cut where a wall of H seals a tunnel of the object. Every change is an
// exact Boolean (LatticeMesh.h) kept only when it gives a closed 2-manifold with lattice corners,
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
