// Boundary generation, section 3.4 of Joan-Arinyo and Solé (1996): the relaxed points of
// each face node are projected onto the node's plane (FaceOctree.h keeps each projection in
// the node's box, or under the paper's rule in its own voxel) and the node's quadrilaterals
// collapse into one planar polygon, the boundary of their disk; quadrilaterals whose points lie in
// different nodes are split into two triangles (the shorter diagonal), which sew the polygons
// together. Points inside a node's disk disappear. Replacing a disk by a disk with the same
// boundary keeps the surface closed, manifold and of the same genus as the net.
//
// Drawing. VTK draws a polygon as the fan from its first point, so each polygon starts at a
// corner whose fan covers it (PolygonTriangulator.h's fanCoversPolygon); a polygon no corner
// of which does is cut along diagonals of an ear-clipping triangulation into convex pieces
// (Hertel and Mehlhorn: a diagonal is removed while both its ends stay convex), each drawn
// from any corner and each carrying its node's id. Such a fan is flat wherever corners run
// straight (points clamped to a face of their voxel box line up), so the triangles of the
// Triangles output are cut apart from it, by FaceOctree.h's polygonTriangles: the cut that
// keeps its orientations and incidences at the points' own positions, which the compaction
// made sure exists. That triangle mesh is free of self-intersections (CGAL, in the tests).
#ifndef vbr_FaceOctreeBoundary_h
#define vbr_FaceOctreeBoundary_h

#include "BitVolume.h"
#include "DeformedModel.h"
#include "Execution.h"
#include "FaceOctree.h"
#include "PolygonTriangulator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <vector>

namespace vbr
{

enum class BoundaryCells
{
  Polygons,      ///< a polygon per face node (or its convex pieces) and sewing triangles
  Triangles,     ///< the same surface, every polygon cut into triangles (polygonTriangles)
  Quadrilaterals ///< the relaxed net's quadrilaterals (non-planar), before the octree
};

struct BoundaryMesh
{
  std::vector<Vec3> points;          ///< voxel units (voxel i spans [i, i + 1])
  std::vector<std::int32_t> pointOf; ///< per output point: the model's point
  std::vector<std::int64_t> offsets{ 0 };
  std::vector<std::int32_t> connectivity;
  std::vector<std::int32_t> faceNode;  ///< per cell: its face node, -1 for sewing triangles
  std::vector<std::int32_t> nodeLevel; ///< per cell: its node's level, -1 for sewing
  std::size_t polygons = 0;            ///< cells from face nodes
  std::size_t triangles = 0;           ///< triangles among all cells
  std::size_t cellCount() const { return this->faceNode.size(); }
};

BoundaryMesh assembleBoundary(const DeformedModel& model,
  const FaceOctree& octree,
  BoundaryCells cells);

/// Convex pieces of a simple counter-clockwise polygon (corner indices, each piece
/// counter-clockwise), from its ear-clipping triangulation; empty if it cannot be triangulated.
std::vector<std::vector<int>> convexPieces(const std::vector<Point2L>& corners);

/// Largest distance from the points to the surfels of `object` (voxel units), each point
/// searched within two voxels of its own (distances beyond are reported as 2).
double maximumDistanceToSurfels(const BitVolume& object,
  const std::vector<Vec3>& points,
  const Execution& exec = Execution());

/// The smallest squared distance from p to the voxel faces for which isFace(i, j, k, a) holds
/// (the face between voxel (i, j, k) and the next along axis a) among the faces of the voxels
/// lo..hi (per axis, inclusive), or `best` when none is nearer.
template<typename IsFace>
double nearestFaceSquared(const Vec3& p,
  const std::int32_t lo[3],
  const std::int32_t hi[3],
  double best,
  const IsFace& isFace)
{
  for (std::int32_t k = lo[2]; k <= hi[2]; ++k)
    for (std::int32_t j = lo[1]; j <= hi[1]; ++j)
      for (std::int32_t i = lo[0]; i <= hi[0]; ++i)
        for (int a = 0; a < 3; ++a)
        {
          if (!isFace(i, j, k, a))
            continue;
          const std::int32_t v[3] = { i, j, k };
          double d2 = 0;
          for (int d = 0; d < 3; ++d)
          {
            const double faceLo = d == a ? v[d] + 1 : v[d], faceHi = v[d] + 1;
            const double e = p[d] < faceLo ? faceLo - p[d] : (p[d] > faceHi ? p[d] - faceHi : 0.0);
            d2 += e * e;
          }
          best = std::min(best, d2);
        }
  return best;
}

/// Distance from p to the nearest of some voxel faces, in two searches among the faces of the
/// voxels within two of p's own (distances beyond are reported as 2):
/// nearestSquared(c, lo, hi, best, wide) returns the smallest squared distance from p to those
/// faces of the voxels lo..hi (inclusive), or `best` when none is nearer, given p's voxel c and
/// whether this is the wider search. The faces of the voxels next to p's own come first: a face
/// of any other voxel lies at least `margin` away (at least one voxel), so when one of them is
/// that near the wider search cannot find a nearer one. The answer is the same; most points
/// stop after 81 faces instead of 648.
template<typename NearestSquared>
double distanceInTwoSearches(const Vec3& p, const NearestSquared& nearestSquared)
{
  const std::int32_t c[3] = {
    std::int32_t(std::floor(p[0])), std::int32_t(std::floor(p[1])), std::int32_t(std::floor(p[2]))
  };
  const std::int32_t nearLo[3] = { c[0] - 1, c[1] - 1, c[2] - 1 };
  const std::int32_t nearHi[3] = { c[0] + 1, c[1] + 1, c[2] + 1 };
  const double best = nearestSquared(c, nearLo, nearHi, 4.0, false);
  double margin = 2.0;
  for (int d = 0; d < 3; ++d)
    margin = std::min({ margin, p[d] - (c[d] - 1), (c[d] + 2) - p[d] });
  if (best <= margin * margin)
    return std::sqrt(best);
  const std::int32_t lo[3] = { c[0] - 3, c[1] - 3, c[2] - 3 };
  const std::int32_t hi[3] = { c[0] + 2, c[1] + 2, c[2] + 2 };
  return std::sqrt(nearestSquared(c, lo, hi, best, true));
}

/// Distance from p to the nearest face for which isFace holds (distanceInTwoSearches). The
/// wider search asks wideFaces(c), given p's voxel c, for its predicate (one that reads the
/// voxels around c once, say).
template<typename IsFace, typename WideFaces>
double distanceToNearestFace(const Vec3& p, const IsFace& isFace, const WideFaces& wideFaces)
{
  return distanceInTwoSearches(p,
    [&](const std::int32_t c[3],
      const std::int32_t lo[3],
      const std::int32_t hi[3],
      double best,
      bool wide)
    {
      return wide ? nearestFaceSquared(p, lo, hi, best, wideFaces(c))
                  : nearestFaceSquared(p, lo, hi, best, isFace);
    });
}

template<typename IsFace>
double distanceToNearestFace(const Vec3& p, const IsFace& isFace)
{
  return distanceToNearestFace(p, isFace, [&isFace](const std::int32_t*) { return isFace; });
}

/// Whether voxel (i, j, k) is in `object` (false outside its grid).
inline bool inObject(const BitVolume& object, std::int32_t i, std::int32_t j, std::int32_t k)
{
  const auto& n = object.dims();
  return i >= 0 && j >= 0 && k >= 0 && i < n[0] && j < n[1] && k < n[2] && object.get(i, j, k);
}

/// The surfels among the faces of the voxels c - Below to c - Below + N - 2 per axis around a
/// voxel c, from the N^3 voxels from c - Below read once (each face would read two):
/// distanceToNearestFace's first search needs 4^3 voxels for 81 faces (162 reads), its wider
/// one 7^3 for 648 (1,296 reads).
template<int N, int Below>
class SurfelFacesAround
{
public:
  SurfelFacesAround(const BitVolume& object, const std::int32_t c[3])
  {
    for (int d = 0; d < 3; ++d)
      this->Lo[d] = c[d] - Below;
    for (int k = 0; k < N; ++k)
      for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i)
          this->In[k][j][i] = inObject(object, this->Lo[0] + i, this->Lo[1] + j, this->Lo[2] + k);
  }

  bool operator()(std::int32_t i, std::int32_t j, std::int32_t k, int a) const
  {
    const int x = i - this->Lo[0], y = j - this->Lo[1], z = k - this->Lo[2];
    return this->In[z][y][x] != this->In[z + (a == 2)][y + (a == 1)][x + (a == 0)];
  }

private:
  std::int32_t Lo[3];
  bool In[N][N][N];
};

/// Distance from p to the surfels of `object`, as distanceToNearestFace (beyond two voxels
/// reported as 2).
inline double distanceToSurfels(const BitVolume& object, const Vec3& p)
{
  const std::int32_t c[3] = {
    std::int32_t(std::floor(p[0])), std::int32_t(std::floor(p[1])), std::int32_t(std::floor(p[2]))
  };
  return distanceToNearestFace(p,
    SurfelFacesAround<4, 1>(object, c),
    [&object](const std::int32_t around[3]) { return SurfelFacesAround<7, 3>(object, around); });
}

/// Largest distanceOf(p) over the points, the points shared among threads (distanceOf is
/// called from several at once).
template<typename DistanceOf>
double maximumOverPoints(const std::vector<Vec3>& points,
  const DistanceOf& distanceOf,
  const Execution& exec = Execution())
{
  std::mutex guard;
  double worst = 0.0;
  exec.forWork(std::int64_t(points.size()))
    .forRange(std::int64_t(points.size()),
      [&](std::int64_t begin, std::int64_t end)
      {
        double local = 0.0;
        for (std::int64_t i = begin; i < end; ++i)
          local = std::max(local, distanceOf(points[std::size_t(i)]));
        const std::lock_guard<std::mutex> lock(guard);
        worst = std::max(worst, local);
      });
  return worst;
}

/// Largest distance from the points to the voxel faces for which isFace(i, j, k, a) holds, each
/// point searched within two voxels of its own (distances beyond are reported as 2). isFace is
/// called from several threads at once.
template<typename IsFace>
double maximumDistanceToFaces(const std::vector<Vec3>& points,
  const IsFace& isFace,
  const Execution& exec = Execution())
{
  return maximumOverPoints(
    points, [&isFace](const Vec3& p) { return distanceToNearestFace(p, isFace); }, exec);
}

} // namespace vbr

#endif
