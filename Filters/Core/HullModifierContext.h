// What every step of the convex hull modifier (ConvexHullModifier.h) shares beyond the lattice
// arithmetic (LatticeArithmetic.h): the Context of one run (the object, the options, the planes'
// levels, the counts) and the exception of an unresolved configuration. Internal to the
// modifier's files; nothing here is installed or used outside them.
#ifndef vbr_HullModifierContext_h
#define vbr_HullModifierContext_h

#include "ConvexHull.h"
#include "ConvexHullModifier.h"
#include "LatticeArithmetic.h"
#include "LatticeMesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <stdexcept>
#include <vector>

namespace vbr
{
namespace detail
{

/// A configuration the pressing-in cannot resolve (see the header).
struct Unresolved : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

struct Context
{
  const BitVolume& objects;
  CoplanarFaces coplanar;
  const Execution& exec;
  std::map<FacePlane, int> planeLevel;
  int keptApart = 0;
  /// Joins or handle cuts dropped together because H with all of them did not separate.
  int discardedChanges = 0;
  /// Whether groups are pressed in as pits (the first pass) or all kept apart (the second).
  bool pits = true;
  /// The object's boundary Euler characteristic once counted (none inside when the object is
  /// not well-composed) and its number of surfaces (-1 until counted; objectSurfaces).
  std::optional<std::optional<long>> euler;
  long surfaces = -1;
  /// The level of each triangle of H when its components were solved apart (empty otherwise):
  /// a plane can then hold faces of different levels in different components.
  std::vector<int> triangleLevel;
};

} // namespace detail
} // namespace vbr

#endif
