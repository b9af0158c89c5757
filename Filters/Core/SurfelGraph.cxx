// The surfel graph built in four stages (buildSurfelGraph).
//
// findSurfels scans the bit rows a word at a time for the voxels with an unselected
// face-neighbour and lists their boundary faces; they come in the order of their voxels (z, y,
// x) then direction, so a surfel is found again by a binary search within its row of voxels
// (RowIndex: where each row's surfels start, 4 bytes per row), with no hash table (it took
// 32 to 64 bytes per surfel). linkNeighbours finds the surfel across each edge (neighbourKey:
// concave, flat or convex, the voxel beyond reached only through a face-neighbour, which keeps
// edge-touching voxels apart) and, from the two surfels' directions, which edge of the
// neighbour is the same linel. numberVertices walks the umbrella of each corner not yet numbered
// (one vertex per umbrella, so a pointel where voxels touch only at a corner gets several), and
// countComponents unites the surfels into connected components.

#include "SurfelGraph.h"

#include "Surfels.h"
#include "UnionFind.h"

#include <algorithm>
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
    // 0 <= v_i < dims_i as one unsigned compare per axis (a negative v_i wraps above dims_i).
    return std::uint32_t(v[0]) < std::uint32_t(dims[0]) &&
      std::uint32_t(v[1]) < std::uint32_t(dims[1]) &&
      std::uint32_t(v[2]) < std::uint32_t(dims[2]) && voxels.get(v[0], v[1], v[2]);
  }
};

/// A surfel as searched for: its voxel and direction.
struct SurfelKey
{
  Point3 voxel;
  int direction;
};

/// Where the surfels of each row of voxels start in the graph's list (in (z, y) order, one more
/// for the end), so that a surfel is found by a binary search among the few of its row.
class RowIndex
{
public:
  RowIndex(const Point3& dims)
    : Ny(dims[1])
  {
    this->Start.reserve(static_cast<std::size_t>(dims[1]) * dims[2] + 1);
  }

  /// Records that the next row starts at surfel `first` (rows in order).
  void beginRow(std::size_t first) { this->Start.push_back(static_cast<std::uint32_t>(first)); }

  /// The number of the surfel, or -1 when absent. `near` is a surfel of the graph: when the
  /// key's voxel lies in its row (a surfel of the same voxel, or of the next voxel along x),
  /// a walk from it finds the key in a few steps, with no search of the row.
  std::int64_t find(const std::vector<Surfel>& surfels,
    const SurfelKey& key,
    std::uint32_t near) const
  {
    const std::size_t row = static_cast<std::size_t>(key.voxel[2]) * this->Ny + key.voxel[1];
    const std::int64_t wanted = std::int64_t(key.voxel[0]) * 8 + key.direction;
    auto order = [](const Surfel& s) { return std::int64_t(s.voxel[0]) * 8 + s.direction; };
    const Surfel& from = surfels[near];
    if (from.voxel[1] == key.voxel[1] && from.voxel[2] == key.voxel[2])
    {
      std::int64_t i = near;
      if (order(from) < wanted)
      {
        const std::int64_t last = this->Start[row + 1];
        while (++i < last && order(surfels[i]) < wanted)
          ;
        return i < last && order(surfels[i]) == wanted ? i : -1;
      }
      const std::int64_t first = this->Start[row];
      while (i > first && order(surfels[i]) > wanted)
        --i;
      return order(surfels[i]) == wanted ? i : -1;
    }
    const auto first = surfels.begin() + this->Start[row];
    const auto last = surfels.begin() + this->Start[row + 1];
    const auto it = std::lower_bound(
      first, last, wanted, [&](const Surfel& s, std::int64_t w) { return order(s) < w; });
    if (it == last || order(*it) != wanted)
      return -1;
    return it - surfels.begin();
  }

private:
  std::size_t Ny;
  std::vector<std::uint32_t> Start;
};

/// Stage 1, the surfels: only voxels with an unselected face-neighbour bear surfels, found a
/// word at a time. Returns false when aborted.
bool findSurfels(const VoxelSet& set, const Execution& exec, SurfelGraph& out, RowIndex& index)
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
      index.beginRow(out.surfels.size());
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
              out.surfels.push_back({ v, static_cast<std::uint8_t>(d) });
        }
      }
    }
  }
  index.beginRow(out.surfels.size()); // the end of the last row
  return true;
}

/// For each direction of a surfel and each of its edges, the step g from the surfel towards
/// the edge (in the surfel's plane) and the directions of the surfel beyond it when the surface
/// turns round the surfel's own voxel (convex) or into the voxel beyond (concave).
struct EdgeSteps
{
  Point3 Toward[6][4];
  std::uint8_t Convex[6][4], Concave[6][4];

  EdgeSteps()
  {
    for (int d = 0; d < 6; ++d)
    {
      const Surfel s{ { 0, 0, 0 }, static_cast<std::uint8_t>(d) };
      for (int k = 0; k < 4; ++k)
      {
        const Point3 g = cross(sub(s.corner((k + 1) % 4), s.corner(k)), unitVector(d));
        this->Toward[d][k] = g; // a unit vector
        this->Convex[d][k] = static_cast<std::uint8_t>(directionOf(g));
        this->Concave[d][k] = static_cast<std::uint8_t>(directionOf(g) ^ 1);
      }
    }
  }
};

/// The surfel beyond edge k of surfel sf: the surface turns into the voxel beyond (concave),
/// goes on flat, or turns round its own voxel (convex). The voxel beyond is reached only
/// through a face-neighbour in the set, which keeps edge-touching voxels apart.
SurfelKey neighbourKey(const VoxelSet& set, const Surfel& sf, int k)
{
  static const EdgeSteps steps;
  const Point3 side = add(sf.voxel, steps.Toward[sf.direction][k]);
  if (!set.contains(side))
    return { sf.voxel, steps.Convex[sf.direction][k] };
  const Point3 beyond = add(side, unitVector(sf.direction));
  if (set.contains(beyond))
    return { beyond, steps.Concave[sf.direction][k] };
  return { side, sf.direction };
}

/// The edges of surfels by direction: SharedEdge[d][k][e] is the edge of a surfel of direction e
/// that runs against edge k of a surfel of direction d (-1 when none does). Two surfels that
/// share a linel see it run in opposite directions, and the four edges of a surfel run in four
/// different directions, so the shared edge follows from the two directions alone.
struct SharedEdgeTable
{
  std::int8_t SharedEdge[6][4][6];

  SharedEdgeTable()
  {
    int along[6][4]; // the direction of each edge of a surfel of each direction
    for (int d = 0; d < 6; ++d)
    {
      const Surfel s{ { 0, 0, 0 }, static_cast<std::uint8_t>(d) };
      for (int k = 0; k < 4; ++k)
        along[d][k] = directionOf(sub(s.corner((k + 1) % 4), s.corner(k)));
    }
    for (int d = 0; d < 6; ++d)
      for (int k = 0; k < 4; ++k)
        for (int e = 0; e < 6; ++e)
        {
          this->SharedEdge[d][k][e] = -1;
          for (int j = 0; j < 4; ++j)
            if (along[e][j] == (along[d][k] ^ 1))
              this->SharedEdge[d][k][e] = static_cast<std::int8_t>(j);
        }
  }
};

/// Stage 2, the neighbour across each edge and the edge of the neighbour that is the same
/// linel (from the two directions: the key found tells the neighbour's, so no second pass
/// reads it). A neighbour in another row of voxels (one step in y, z or both) is searched from
/// the last one found in that row: the surfels come in order along x, so their neighbours in a
/// row do too, a few surfels on (the walk of RowIndex::find, not a binary search of the row).
/// The pairing is symmetric (t is across edge k of s with its edge j exactly when s is across
/// edge j of t with its edge k: the rule of neighbourKey pairs the two surfels of a linel), so
/// a link found from s to a later surfel t of the same range is written for t too, and t's
/// search for it is skipped: each linel is searched for once, not twice.
void linkNeighbours(const VoxelSet& set,
  const RowIndex& index,
  const Execution& exec,
  SurfelGraph& out)
{
  // Not a link: surfels are numbered below 2^30 - 1, so no link is all ones.
  constexpr std::uint32_t None = ~std::uint32_t(0);
  static const SharedEdgeTable table;
  const std::size_t n = out.surfels.size();
  out.neighbour.assign(4 * n, None);
  exec.forWork(static_cast<std::int64_t>(n))
    .forRange(static_cast<std::int64_t>(n),
      [&](std::int64_t b, std::int64_t e)
      {
        std::uint32_t recent[9]; // by the row's step (dy, dz) from the surfel's row
        std::fill(recent, recent + 9, None);
        for (auto s = static_cast<std::uint32_t>(b); s < e; ++s)
          for (int k = 0; k < 4; ++k)
          {
            if (out.neighbour[4 * s + k] != None)
              continue; // linked from the other side, by an earlier surfel of this range
            const Surfel& sf = out.surfels[s];
            const SurfelKey key = neighbourKey(set, sf, k);
            const int row = 3 * (key.voxel[2] - sf.voxel[2] + 1) + (key.voxel[1] - sf.voxel[1] + 1);
            const std::uint32_t near = row == 4 || recent[row] == None ? s : recent[row];
            const std::int64_t id = index.find(out.surfels, key, near);
            if (id < 0)
              throw std::logic_error("surfel neighbour missing");
            const int j = table.SharedEdge[sf.direction][k][key.direction];
            if (j < 0)
              throw std::logic_error("neighbouring surfels do not share their linel");
            out.neighbour[4 * s + k] = SurfelGraph::link(static_cast<std::uint32_t>(id), j);
            if (id > s && id < e) // a later surfel of this range: its link back, found
              out.neighbour[4 * std::size_t(id) + j] = SurfelGraph::link(s, k);
            recent[row] = static_cast<std::uint32_t>(id);
          }
      });
}

/// Stage 4, the vertices: one per umbrella of corners glued across shared edges (so that a
/// pointel gets one vertex per umbrella), numbered in the order of their first corner. A walk
/// round each umbrella, with no union-find over the 4 corners of every surfel.
void numberVertices(SurfelGraph& out)
{
  constexpr std::uint32_t None = ~std::uint32_t(0);
  const std::size_t n = out.surfels.size();
  out.vertex.assign(4 * n, None);
  out.vertexPointel.clear();
  // V = F + 2 (C - G) on a closed surface of F surfels (E = 2F): at most F + F / 3, as each of
  // the C components has 6 surfels or more. Made to size once numbered.
  out.vertexPointel.reserve(n + n / 3 + 2);
  std::uint32_t count = 0;
  for (std::uint32_t s = 0; s < n; ++s)
    for (int k = 0; k < 4; ++k)
    {
      if (out.vertex[4 * s + k] != None)
        continue;
      const std::uint32_t v = count++;
      out.vertexPointel.push_back(out.cornerOf(s, k)); // every corner of the umbrella is there
      std::uint32_t u = s;
      int corner = k; // the edge of u that starts at the vertex
      int steps = 0;
      do
      {
        if (++steps > 64) // an umbrella has a handful of surfels
          throw std::logic_error("surfel umbrella does not close");
        out.vertex[4 * u + corner] = v;
        const int j = out.sharedEdge(u, corner);
        u = out.neighbourOf(u, corner);
        corner = (j + 1) % 4;
      } while (u != s || corner != k);
    }
  out.vertexPointel.shrink_to_fit();
}

/// The connected components of the surface (only their number is kept).
void countComponents(SurfelGraph& out)
{
  const std::size_t n = out.surfels.size();
  UnionFind faces(n);
  for (std::uint32_t s = 0; s < n; ++s)
    for (int k = 0; k < 4; ++k)
    {
      const std::uint32_t t = out.neighbourOf(s, k);
      if (t > s) // each linel once: from its other surfel the pair is the same
        faces.unite(s, t);
    }
  std::uint32_t roots = 0;
  for (std::uint32_t s = 0; s < n; ++s)
    roots += faces.find(s) == s;
  out.componentCount = roots;
}

} // namespace

bool buildSurfelGraph(const BitVolume& voxels, const Execution& exec, SurfelGraph& out)
{
  out = SurfelGraph();
  out.dims = voxels.dims();
  const VoxelSet set{ voxels, voxels.dims() };
  const std::size_t count = countSurfels(voxels);
  if (count >= SurfelGraph::MaximumSize)
    throw std::length_error("the boundary has 2^30 surfels or more");
  out.surfels.reserve(count); // exactly: no growth by doubling
  {
    RowIndex index(out.dims);
    if (!findSurfels(set, exec, out, index))
      return false;
    linkNeighbours(set, index, exec, out);
  }
  numberVertices(out);
  countComponents(out);
  return true;
}

} // namespace vbr
