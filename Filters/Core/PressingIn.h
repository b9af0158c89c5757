// The pressing-in (FZD-514, section 4.2, Algorithm 1, with the changes the modifier's header
// describes): at each level the points of the other class in the hull C are grouped (groups
// whose hulls meet are merged), each group is pressed in as a pit (the exact difference of C
// and the group's solved hull, refused beforehand when convexDifferenceIsManifold says it cannot
// be a 2-manifold) or kept apart (a cavity strictly inside C, or a region pressed in from an
// empty lattice triangle of C's surface), and solveLevel returns the level's surface.
#ifndef vbr_PressingIn_h
#define vbr_PressingIn_h

#include "HullModifierContext.h"
#include "HullPointRuns.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

namespace vbr
{
namespace detail
{

/// A hull with its bounding box: hulls whose boxes miss each other are apart without the
/// separating axis test, which is what keeps the pairwise merging of groups cheap.
struct BoxedHull
{
  CellList hull;
  std::array<std::int64_t, 6> box{ 0, -1, 0, -1, 0, -1 };

  BoxedHull() = default;
  explicit BoxedHull(CellList h)
    : hull(std::move(h))
  {
    if (this->hull.dimension >= 0)
      this->box = boundsOf(this->hull);
  }
};

/// The first and last point of every row (along x) of the points: every other point lies
/// between two of them, so they span the same hull, and a solid group of n points gives the
/// hull about n^(2/3) points instead of n. Points in row order (as listed) are read in place.
std::vector<LatticePoint> rowEnds(const std::vector<LatticePoint>& listed);

/// rowEnds of points given as runs: a row's first point is its first run's, its last the last
/// run's (the runs of a set are disjoint, so runs in row order list the points in row order).
std::vector<LatticePoint> rowEnds(const PointRuns& listed);

/// A lattice triangle on a face of C (counter-clockwise about the face's outer normal), with the
/// lattice points of its closed area once enumerated, and its distance from the group pressed in.
struct FaceTriangle
{
  std::array<LatticePoint, 3> corners;
  FacePlane plane;
  std::vector<LatticePoint> points;
  bool enumerated = false;
  __int128 distance = 0;
  /// Reversed, so that a priority queue gives the nearest first.
  bool operator<(const FaceTriangle& o) const { return this->distance > o.distance; }
};

/// The squared distance, scaled by m^2, between the point p / k and the centroid sum / m of a
/// group of m points (it only orders the candidates).
inline __int128 scaledDistance(const LatticePoint& p,
  std::int64_t k,
  const LatticePoint& sum,
  std::int64_t m)
{
  __int128 d = 0;
  for (int a = 0; a < 3; ++a)
  {
    const __int128 e = __int128(m) * p[a] - __int128(k) * sum[a];
    d += e * e;
  }
  return d;
}

/// The empty lattice triangles on the surface of a solid hull (no lattice point but their
/// corners), nearest to a group of points first: its faces are fanned, and a triangle holding
/// another lattice point is split at the one nearest to the group. In its plane an empty lattice
/// triangle is unimodular (Pick), so a solid pressed in from it meets no other centre of C.
struct EmptyFaceTriangles
{
  std::priority_queue<FaceTriangle> queue;
  LatticePoint sum{ 0, 0, 0 };
  std::int64_t m = 0;

  EmptyFaceTriangles(const CellList& c, const PointRuns& group)
    : m(static_cast<std::int64_t>(group.count))
  {
    // A run's x sum is its length times its middle, (lo + hi) n / 2 (one factor is even).
    for (const Run& r : group.runs)
    {
      const std::int64_t n = r.hi - r.lo + 1;
      this->sum[0] += (r.lo + r.hi) * n / 2;
      this->sum[1] += r.y * n;
      this->sum[2] += r.z * n;
    }
    for (std::size_t f = 0; f < c.faces.size(); ++f)
      for (std::size_t k = 1; k + 1 < c.faces[f].size(); ++k)
        this->push(
          { c.vertices[c.faces[f][0]], c.vertices[c.faces[f][k]], c.vertices[c.faces[f][k + 1]] },
          c.planes[f],
          {},
          false);
  }

  void push(const std::array<LatticePoint, 3>& t,
    const FacePlane& plane,
    std::vector<LatticePoint> points,
    bool enumerated)
  {
    FaceTriangle f{ t, plane, std::move(points), enumerated, 0 };
    const LatticePoint corners{
      t[0][0] + t[1][0] + t[2][0], t[0][1] + t[1][1] + t[2][1], t[0][2] + t[1][2] + t[2][2]
    };
    f.distance = scaledDistance(corners, 3, this->sum, this->m);
    this->queue.push(std::move(f));
  }

  /// The next empty triangle, false when none is left.
  bool next(std::array<LatticePoint, 3>& out);
};

/// Whether the faces of a solid hull fanned (triangulateHull) make an embedded surface, in
/// exact integer arithmetic: every face strictly convex, counter-clockwise about its outward
/// normal (each corner strictly left of every edge it is not on) and no corner beyond a face's
/// plane. Fan triangles of one strictly convex face then meet only in their shared corner and
/// edges, and those of two faces only where the faces meet, in corners and edges of both.
/// Checking that costs far less than CGAL's self-intersection test of the fan, which every
/// level ran on its hull and on every leaf hull pressed into it.
bool fanIsEmbedded(const CellList& c);

/// A level's surface while its pits and regions are cut out of it, with the boxes of the
/// triangles made since it was last known embedded (none: test it all; empty: embedded).
/// Levels of large objects cut thousands of pits, mostly small hulls out of small hulls, and
/// testing both whole operands of every cut for self-intersections cost about a third of the
/// cut; the test of a known part is skipped (latticeDifference's aChangedIn and bChangedIn).
struct LevelSurface
{
  LatticeMesh mesh;
  std::optional<std::vector<LatticeBox>> changed;

  explicit LevelSurface(const CellList& c)
    : mesh(triangulateHull(c))
  {
    if (fanIsEmbedded(c))
      this->changed.emplace();
  }

  /// The surface minus g when the exact difference is a closed 2-manifold with lattice corners.
  bool subtract(const LevelSurface& g)
  {
    LatticeMesh difference;
    if (!latticeDifference(this->mesh,
          g.mesh,
          difference,
          Operands::Check,
          this->changed ? &*this->changed : nullptr,
          g.changed ? &*g.changed : nullptr))
      return false;
    // The difference tested the surface embedded: what is new is the difference's own.
    this->changed = newTriangleBoxes(this->mesh, difference);
    this->mesh = std::move(difference);
    return true;
  }

  /// Adds a cavity's surface inside out; its triangles are new.
  void addCavity(const LatticeMesh& cavity)
  {
    this->mesh.append(cavity, true);
    if (this->changed)
      for (const auto& box : newTriangleBoxes(LatticeMesh(), cavity))
        this->changed->push_back(box);
  }
};

/// One level of Algorithm 1 (see the header): C minus the pits, the groups that fail as pits
/// kept apart (cavities and regions pressed in from empty triangles). `pit`: C touches the
/// surface of its parent in pieces of faces. `depth` receives the number of levels below.
LevelSurface solveLevel(Context& ctx,
  const CellList& c,
  const CellList* parent,
  bool cls,
  bool pit,
  int level,
  int& depth);

} // namespace detail
} // namespace vbr

#endif
