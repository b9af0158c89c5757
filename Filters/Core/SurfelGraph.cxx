// The surfel graph built in four stages (buildSurfelGraph).
//
// findSurfels scans the bit rows a word at a time for the voxels with an unselected
// face-neighbour and lists their boundary faces, each keyed in a hash index. linkNeighbours
// finds the surfel across each edge (neighbourKey: concave, flat or convex, the voxel beyond
// reached only through a face-neighbour, which keeps edge-touching voxels apart).
// matchSharedEdges records which edge of the neighbour is the same linel. glueVertices unites
// the corners glued across shared edges (one vertex per umbrella, so a pointel where voxels
// touch only at a corner gets several) and the surfels into connected components.

#include "SurfelGraph.h"

#include "GridPointIndex.h"
#include "Surfels.h"
#include "UnionFind.h"

#include <cstddef>
#include <stdexcept>

namespace vbr
{

namespace
{

/// The voxel set as the graph reads it: membership of any voxel (outside the grid: not in
/// the set) and the key of a surfel in the index.
struct VoxelSet
{
  const BitVolume& voxels;
  Point3 dims;

  bool contains(const Point3& v) const
  {
    return v[0] >= 0 && v[1] >= 0 && v[2] >= 0 && v[0] < dims[0] && v[1] < dims[1] &&
      v[2] < dims[2] && voxels.get(v[0], v[1], v[2]);
  }
  std::uint64_t key(const Point3& v, int direction) const
  {
    return ((std::uint64_t(v[2]) * dims[1] + v[1]) * dims[0] + v[0]) * 6 + direction;
  }
};

/// Stage 1, the surfels: only voxels with an unselected face-neighbour bear surfels, found a
/// word at a time. Returns false when aborted.
bool findSurfels(const VoxelSet& set,
  const Execution& exec,
  SurfelGraph& out,
  GridPointIndex& index)
{
  const BitVolume& voxels = set.voxels;
  const Point3& dims = set.dims;
  const std::size_t words = voxels.wordsPerRow();
  const std::vector<Word> none(words, 0);
  for (std::int32_t z = 0; z < dims[2]; ++z)
  {
    if (exec.stopRequested())
      return false;
    for (std::int32_t y = 0; y < dims[1]; ++y)
    {
      const Word* row = voxels.row(y, z);
      const Word* down = y > 0 ? voxels.row(y - 1, z) : none.data();
      const Word* up = y + 1 < dims[1] ? voxels.row(y + 1, z) : none.data();
      const Word* back = z > 0 ? voxels.row(y, z - 1) : none.data();
      const Word* front = z + 1 < dims[2] ? voxels.row(y, z + 1) : none.data();
      for (std::size_t i = 0; i < words; ++i)
      {
        const Word w = row[i];
        if (!w)
          continue;
        const Word left = (w << 1) | (i > 0 ? row[i - 1] >> 63 : 0);
        const Word right = (w >> 1) | (i + 1 < words ? row[i + 1] << 63 : 0);
        Word boundary = w & ~(left & right & down[i] & up[i] & back[i] & front[i]);
        while (boundary)
        {
          const int bit = countTrailingZeros(boundary);
          boundary &= boundary - 1;
          const Point3 v{ static_cast<std::int32_t>(i * 64 + bit), y, z };
          for (int d = 0; d < 6; ++d)
            if (!set.contains(add(v, unitVector(d))))
            {
              out.surfels.push_back({ v, static_cast<std::uint8_t>(d) });
              index.insert(set.key(v, d));
            }
        }
      }
    }
  }
  return true;
}

/// The surfel beyond edge (a, b) of surfel sf: the surface turns into the voxel beyond
/// (concave), goes on flat, or turns round its own voxel (convex). The voxel beyond is
/// reached only through a face-neighbour in the set, which keeps edge-touching voxels apart.
std::uint64_t neighbourKey(const VoxelSet& set, const Surfel& sf, const Point3& a, const Point3& b)
{
  const Point3 normal = unitVector(sf.direction);
  const Point3 g = cross(sub(b, a), normal); // from the surfel towards the edge
  const Point3 side = add(sf.voxel, g);
  if (!set.contains(side))
    return set.key(sf.voxel, directionOf(g)); // g is a unit vector
  const Point3 beyond = add(side, normal);
  if (set.contains(beyond))
    return set.key(beyond, directionOf({ -g[0], -g[1], -g[2] }));
  return set.key(side, sf.direction);
}

/// Stage 2, the neighbour across each edge.
void linkNeighbours(const VoxelSet& set, const GridPointIndex& index, SurfelGraph& out)
{
  const std::size_t n = out.surfels.size();
  out.corners.resize(4 * n);
  for (std::size_t s = 0; s < n; ++s)
    for (int k = 0; k < 4; ++k)
      out.corners[4 * s + k] = out.surfels[s].corner(k);
  out.neighbour.resize(4 * n);
  for (std::uint32_t s = 0; s < n; ++s)
    for (int k = 0; k < 4; ++k)
    {
      const std::int64_t id = index.find(
        neighbourKey(set, out.surfels[s], out.cornerOf(s, k), out.cornerOf(s, (k + 1) % 4)));
      if (id < 0)
        throw std::logic_error("surfel neighbour missing");
      out.neighbour[4 * s + k] = static_cast<std::uint32_t>(id);
    }
}

/// Stage 3, the same linel seen from the neighbour: its edge runs the other way.
void matchSharedEdges(SurfelGraph& out)
{
  const std::size_t n = out.surfels.size();
  out.neighbourEdge.resize(4 * n);
  for (std::uint32_t s = 0; s < n; ++s)
    for (int k = 0; k < 4; ++k)
    {
      const std::uint32_t t = out.neighbourOf(s, k);
      const Point3& from = out.cornerOf(s, (k + 1) % 4);
      int j = 0;
      while (j < 4 && out.cornerOf(t, j) != from)
        ++j;
      if (j == 4 || out.cornerOf(t, (j + 1) % 4) != out.cornerOf(s, k))
        throw std::logic_error("neighbouring surfels do not share their linel");
      out.neighbourEdge[4 * s + k] = static_cast<std::uint8_t>(j);
    }
}

/// Stage 4, the vertices: corners glued across shared edges, so that a pointel gets one
/// vertex per umbrella; and the connected components of the surface.
void glueVertices(SurfelGraph& out)
{
  const std::size_t n = out.surfels.size();
  UnionFind corners(4 * n);
  UnionFind faces(n);
  for (std::uint32_t s = 0; s < n; ++s)
    for (int k = 0; k < 4; ++k)
    {
      const std::uint32_t t = out.neighbourOf(s, k);
      const int j = out.sharedEdge(s, k);
      corners.unite(4 * s + k, 4 * t + (j + 1) % 4);
      corners.unite(4 * s + (k + 1) % 4, 4 * t + j);
      faces.unite(s, t);
    }
  std::uint32_t vertexCount = 0;
  out.vertex = corners.numberClasses(vertexCount);
  out.vertexPointel.resize(vertexCount);
  for (std::uint32_t c = 0; c < 4 * n; ++c)
    out.vertexPointel[out.vertex[c]] = out.corners[c];
  out.component = faces.numberClasses(out.componentCount);
}

} // namespace

bool buildSurfelGraph(const BitVolume& voxels, const Execution& exec, SurfelGraph& out)
{
  out = SurfelGraph();
  out.dims = voxels.dims();
  const VoxelSet set{ voxels, voxels.dims() };
  const std::size_t expected = countSurfels(voxels);
  GridPointIndex index(expected);
  out.surfels.reserve(expected);
  if (!findSurfels(set, exec, out, index))
    return false;
  linkNeighbours(set, index, out);
  matchSharedEdges(out);
  glueVertices(out);
  return true;
}

} // namespace vbr
