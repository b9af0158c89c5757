#include "SurfelGraph.h"

#include "GridPointIndex.h"
#include "Surfels.h"
#include "UnionFind.h"

#include <stdexcept>

namespace vbr
{

bool buildSurfelGraph(const BitVolume& voxels, const Execution& exec, SurfelGraph& out)
{
  out = SurfelGraph();
  out.dims = voxels.dims();
  const Point3 dims = voxels.dims();
  auto in = [&](const Point3& v)
  {
    return v[0] >= 0 && v[1] >= 0 && v[2] >= 0 && v[0] < dims[0] && v[1] < dims[1] &&
      v[2] < dims[2] && voxels.get(v[0], v[1], v[2]);
  };
  auto keyOf = [&](const Point3& v, int direction)
  { return ((std::uint64_t(v[2]) * dims[1] + v[1]) * dims[0] + v[0]) * 6 + direction; };

  // Only voxels with an unselected face-neighbour bear surfels: found a word at a time.
  const std::size_t expected = countSurfels(voxels);
  GridPointIndex index(expected);
  out.surfels.reserve(expected);
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
            if (!in(add(v, unitVector(d))))
            {
              out.surfels.push_back({ v, static_cast<std::uint8_t>(d) });
              index.insert(keyOf(v, d));
            }
        }
      }
    }
  }

  // Neighbour across each edge: the surface turns into the voxel beyond (concave), goes on
  // flat, or turns round its own voxel (convex). The voxel beyond is reached only through
  // a face-neighbour in the set, which keeps edge-touching voxels apart.
  const std::size_t n = out.surfels.size();
  out.corners.resize(4 * n);
  for (std::size_t s = 0; s < n; ++s)
    for (int k = 0; k < 4; ++k)
      out.corners[4 * s + k] = out.surfels[s].corner(k);
  out.neighbour.resize(4 * n);
  for (std::size_t s = 0; s < n; ++s)
  {
    const Surfel& sf = out.surfels[s];
    const Point3 normal = unitVector(sf.direction);
    for (int k = 0; k < 4; ++k)
    {
      const Point3& a = out.cornerOf(static_cast<std::uint32_t>(s), k);
      const Point3& b = out.cornerOf(static_cast<std::uint32_t>(s), (k + 1) % 4);
      const Point3 t{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
      const Point3 g = cross(t, normal); // from the surfel towards the edge
      const Point3 side = add(sf.voxel, g);
      Point3 voxel = sf.voxel;
      int direction = directionOf(g); // g is a unit vector
      if (in(side))
      {
        const Point3 beyond = add(side, normal);
        if (in(beyond))
        {
          voxel = beyond;
          direction = directionOf({ -g[0], -g[1], -g[2] });
        }
        else
        {
          voxel = side;
          direction = sf.direction;
        }
      }
      const std::int64_t id = index.find(keyOf(voxel, direction));
      if (id < 0)
        throw std::logic_error("surfel neighbour missing");
      out.neighbour[4 * s + k] = static_cast<std::uint32_t>(id);
    }
  }

  // The same linel seen from the neighbour: its edge runs the other way.
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

  // Vertices: corners glued across shared edges; a pointel gets one per umbrella.
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
  return true;
}

} // namespace vbr
