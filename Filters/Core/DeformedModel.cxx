#include "DeformedModel.h"

#include "UnionFind.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>

namespace vbr
{
namespace
{

// ---- The voxel's crossing edges and their chains (the manifold rule) ----

/// Edge e = 4a + db + 2dc of a voxel runs along axis a from the corner with offset db along
/// b = a + 1 and dc along c = a + 2 (mod 3). Corner index: dx + 2dy + 4dz.
int edgeCorner(int e, int end)
{
  const int a = e / 4, db = e & 1, dc = (e >> 1) & 1;
  std::array<int, 3> off{ 0, 0, 0 };
  off[a] = end;
  off[(a + 1) % 3] = db;
  off[(a + 2) % 3] = dc;
  return off[0] + 2 * off[1] + 4 * off[2];
}

int edgeBetween(int c0, int c1)
{
  for (int e = 0; e < 12; ++e)
    if ((edgeCorner(e, 0) == c0 && edgeCorner(e, 1) == c1) ||
      (edgeCorner(e, 0) == c1 && edgeCorner(e, 1) == c0))
      return e;
  return -1;
}

/// The corners of face 2f + s (perpendicular to axis f, at offset s) in cyclic order.
std::array<int, 4> faceCorners(int face)
{
  const int f = face / 2, s = face % 2, g = (f + 1) % 3, h = (f + 2) % 3;
  const int step[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  std::array<int, 4> corner;
  for (int i = 0; i < 4; ++i)
  {
    std::array<int, 3> off{ 0, 0, 0 };
    off[f] = s;
    off[g] = step[i][0];
    off[h] = step[i][1];
    corner[i] = off[0] + 2 * off[1] + 4 * off[2];
  }
  return corner;
}

/// Whether the face's interior corners lie on one diagonal, the others not (four crossings).
bool ambiguousFace(int cfg, int face)
{
  const auto c = faceCorners(face);
  const int a = (cfg >> c[0]) & 1, b = (cfg >> c[1]) & 1;
  return a != b && ((cfg >> c[2]) & 1) == a && ((cfg >> c[3]) & 1) == b;
}

/// Whether the two interior corners of an ambiguous face are joined by a path of interior
/// corners along the voxel's edges.
bool joinedInside(int cfg, int face)
{
  const auto c = faceCorners(face);
  const int from = ((cfg >> c[0]) & 1) ? c[0] : c[1], to = ((cfg >> c[0]) & 1) ? c[2] : c[3];
  int reached = 1 << from;
  for (int round = 0; round < 8; ++round)
    for (int x = 0; x < 8; ++x)
      if ((reached >> x) & 1)
        for (int d = 0; d < 3; ++d)
          if ((cfg >> (x ^ (1 << d))) & 1)
            reached |= 1 << (x ^ (1 << d));
  return (reached >> to) & 1;
}

struct CycleTable
{
  /// Per key (corner configuration | ambiguous faces chained across their interior
  /// diagonal << 8): the number of chains and each edge's chain.
  std::vector<std::uint8_t> count;
  std::vector<std::array<std::int8_t, 12>> edgeCycle;

  CycleTable()
    : count(1 << 14)
    , edgeCycle(1 << 14)
  {
    for (int key = 0; key < (1 << 14); ++key)
      this->chain(key);
  }

  void chain(int key)
  {
    const int cfg = key & 255;
    auto in = [cfg](int c) { return (cfg >> c) & 1; };
    UnionFind edges(12); // the crossed edges of one cycle of the surface in the cube
    auto crossing = [&](int e) { return in(edgeCorner(e, 0)) != in(edgeCorner(e, 1)); };
    for (int face = 0; face < 6; ++face)
    {
      const auto corner = faceCorners(face);
      std::array<int, 4> edge;
      std::vector<int> crossed;
      for (int i = 0; i < 4; ++i)
      {
        edge[i] = edgeBetween(corner[i], corner[(i + 1) % 4]);
        if (crossing(edge[i]))
          crossed.push_back(i);
      }
      auto unite = [&](int x, int y) { edges.unite(x, y); };
      const int cut = ((key >> (8 + face)) & 1) ? 0 : 1; // chain around exterior / interior
      if (crossed.size() == 2)
        unite(edge[crossed[0]], edge[crossed[1]]);
      else if (crossed.size() == 4)
        for (int i = 0; i < 4; ++i)
          if (in(corner[i]) == cut)
            unite(edge[(i + 3) % 4], edge[i]);
    }
    std::array<int, 12> id;
    id.fill(-1);
    for (int e = 0; e < 12; ++e)
    {
      this->edgeCycle[key][e] = -1;
      if (!crossing(e))
        continue;
      const int r = static_cast<int>(edges.find(e));
      if (id[r] < 0)
        id[r] = this->count[key]++;
      this->edgeCycle[key][e] = static_cast<std::int8_t>(id[r]);
    }
  }
};

const CycleTable& cycleTable()
{
  static const CycleTable table;
  return table;
}

// ---- Interior grid vertices and voxel configurations ----

inline Word shiftedDown(const Word* row, std::size_t w, std::size_t words)
{
  return (row[w] >> 1) | (w + 1 < words ? row[w + 1] << 63 : 0);
}

/// Grid vertices whose eight voxels are all object voxels: bit volume of (n + 1) vertices.
BitVolume interiorVertices(const BitVolume& object, const Execution& exec)
{
  const auto& n = object.dims();
  BitVolume out(n[0] + 1, n[1] + 1, n[2] + 1);
  const std::size_t vw = out.wordsPerRow(), ow = object.wordsPerRow();
  exec.forRange(n[2] + 1,
    [&](std::int64_t kb, std::int64_t ke)
    {
      for (std::int32_t k = std::int32_t(kb); k < ke; ++k)
        for (std::int32_t j = 1; j < n[1] && k >= 1 && k < n[2]; ++j)
        {
          const Word* r[4] = {
            object.row(j - 1, k - 1), object.row(j, k - 1), object.row(j - 1, k), object.row(j, k)
          };
          Word* dst = out.row(j, k);
          Word carry = 0;
          for (std::size_t w = 0; w < vw; ++w)
          {
            const Word a = w < ow ? (r[0][w] & r[1][w] & r[2][w] & r[3][w]) : 0;
            dst[w] = a & ((a << 1) | carry);
            carry = a >> 63;
          }
        }
    });
  return out;
}

/// Configuration of a voxel's corners (bit dx + 2dy + 4dz set when that corner is interior);
/// voxels outside the grid have no interior corner.
inline int cornerConfig(const BitVolume& interior, std::int32_t i, std::int32_t j, std::int32_t k)
{
  const auto& n = interior.dims();
  if (i < 0 || j < 0 || k < 0 || i + 1 >= n[0] || j + 1 >= n[1] || k + 1 >= n[2])
    return 0;
  int cfg = 0;
  for (int c = 0; c < 8; ++c)
    if (interior.get(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)))
      cfg |= 1 << c;
  return cfg;
}

/// The chaining key of a voxel: its configuration, and for each ambiguous face whether its
/// interior corners are joined across it. They are when they are joined inside the voxel or
/// inside the neighbour through that face (a rule both see alike): then one of the two holds
/// the face's two crossings pairs on two different chains, so that two points are never
/// linked twice.
inline int chainKey(const BitVolume& interior,
  std::int32_t i,
  std::int32_t j,
  std::int32_t k,
  const std::vector<std::uint64_t>& flipped)
{
  const int cfg = cornerConfig(interior, i, j, k);
  int key = cfg;
  for (int face = 0; face < 6; ++face)
  {
    if (!ambiguousFace(cfg, face))
      continue;
    std::array<std::int32_t, 3> w{ i, j, k };
    w[face / 2] += (face % 2) ? 1 : -1;
    const int other = cornerConfig(interior, w[0], w[1], w[2]);
    const auto& n = interior.dims(); // one more vertex than voxels along each axis
    const std::uint64_t id =
      (std::uint64_t(i) + std::uint64_t(n[0] - 1) * (j + std::uint64_t(n[1] - 1) * k)) * 8 + face;
    const bool flip = std::binary_search(flipped.begin(), flipped.end(), id);
    if ((joinedInside(cfg, face) || joinedInside(other, face ^ 1)) != flip)
      key |= 1 << (8 + face);
  }
  return key;
}

/// Voxels of row (j, k) with an interior and a non-interior corner: bits of word w.
inline Word mixedVoxels(const BitVolume& interior, std::int32_t j, std::int32_t k, std::size_t w)
{
  const std::size_t vw = interior.wordsPerRow();
  Word any = 0, all = ~Word(0);
  for (int c = 0; c < 4; ++c)
  {
    const Word* r = interior.row(j + (c & 1), k + (c >> 1));
    const Word both = r[w] & shiftedDown(r, w, vw), either = r[w] | shiftedDown(r, w, vw);
    any |= either;
    all &= both;
  }
  return any & ~all;
}

// ---- The points ----

struct PointBuilder
{
  const BitVolume& object;
  const BitVolume& interior;
  DeformedModel& model;
  std::vector<std::int64_t> voxelKey; ///< linear voxel index of each point (sorted)
  std::vector<std::uint16_t> config;  ///< chaining key of each point's voxel
  std::vector<std::uint8_t> cycle;    ///< the point's chain in its voxel
  double margin = 0.0;
  std::vector<std::uint64_t> flipped; ///< ambiguous faces chained the other way (sorted)

  std::int64_t keyOf(std::int32_t i, std::int32_t j, std::int32_t k) const
  {
    const auto& n = this->object.dims();
    return i + std::int64_t(n[0]) * (j + std::int64_t(n[1]) * k);
  }

  template<typename Visit>
  void forMixedVoxelsOfRow(std::int32_t j, std::int32_t k, Visit visit) const
  {
    const std::size_t words = this->object.wordsPerRow();
    for (std::size_t w = 0; w < words; ++w)
      for (Word m = mixedVoxels(this->interior, j, k, w); m; m &= m - 1)
      {
        const std::int32_t i = std::int32_t(w * 64 + __builtin_ctzll(m));
        if (i < this->object.size(0))
          visit(i, chainKey(this->interior, i, j, k, this->flipped));
      }
  }

  void build(const Execution& exec);
  void placePoint(std::int64_t p, std::int32_t i, std::int32_t j, std::int32_t k);
};

void PointBuilder::build(const Execution& exec)
{
  const auto& n = this->object.dims();
  const std::int64_t rows = std::int64_t(n[1]) * n[2];
  std::vector<std::int64_t> start(rows + 1, 0);
  const auto& table = cycleTable();
  exec.forRange(rows,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t r = b; r < e; ++r)
        this->forMixedVoxelsOfRow(std::int32_t(r % n[1]),
          std::int32_t(r / n[1]),
          [&](std::int32_t, int cfg) { start[r + 1] += table.count[cfg]; });
    });
  std::partial_sum(start.begin(), start.end(), start.begin());
  const std::int64_t total = start[rows];
  auto& m = this->model;
  m.voxel.resize(total);
  m.boxLo.resize(total);
  m.boxHi.resize(total);
  m.position.resize(total);
  m.anchor.resize(total);
  m.shared.resize(total);
  this->voxelKey.resize(total);
  this->config.resize(total);
  this->cycle.resize(total);
  exec.forRange(rows,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t r = b; r < e; ++r)
      {
        std::int64_t p = start[r];
        const std::int32_t j = std::int32_t(r % n[1]), k = std::int32_t(r / n[1]);
        this->forMixedVoxelsOfRow(j,
          k,
          [&](std::int32_t i, int cfg)
          {
            for (int c = 0; c < table.count[cfg]; ++c, ++p)
            {
              this->config[p] = std::uint16_t(cfg);
              this->cycle[p] = std::uint8_t(c);
              m.shared[p] = table.count[cfg] > 1;
              this->placePoint(p, i, j, k);
            }
          });
      }
    });
}

/// Voxel, box, anchor and starting position. The box is the voxel shrunk by the margin (for
/// a voxel with several sheets: the box of its chain's edge midpoints, shrunk by 10 %); the
/// anchor is the mean of the chain's crossing edges' non-interior ends (grid vertices on the
/// voxel boundary); the start is the voxel centre (the centroid of the midpoints with several
/// sheets), in the box.
void PointBuilder::placePoint(std::int64_t p, std::int32_t i, std::int32_t j, std::int32_t k)
{
  auto& m = this->model;
  m.voxel[p] = { i, j, k };
  this->voxelKey[p] = this->keyOf(i, j, k);
  const Vec3 base{ double(i), double(j), double(k) };
  const int cfg = this->config[p] & 255;
  const auto& chainOf = cycleTable().edgeCycle[this->config[p]];
  Vec3 lo{ 1, 1, 1 }, hi{ 0, 0, 0 }, sum{ 0, 0, 0 }, outer{ 0, 0, 0 };
  int count = 0;
  for (int e = 0; e < 12; ++e)
  {
    if (chainOf[e] != this->cycle[p])
      continue;
    const int c0 = edgeCorner(e, 0), c1 = edgeCorner(e, 1);
    const int out = ((cfg >> c0) & 1) ? c1 : c0;
    for (int d = 0; d < 3; ++d)
    {
      const double mid = 0.5 * (((c0 >> d) & 1) + ((c1 >> d) & 1));
      lo[d] = std::min(lo[d], mid);
      hi[d] = std::max(hi[d], mid);
      sum[d] += mid;
      outer[d] += (out >> d) & 1;
    }
    ++count;
  }
  const double margin = std::clamp(this->margin, 0.0, 0.45);
  for (int d = 0; d < 3; ++d)
  {
    if (m.shared[p])
    {
      const double mid = 0.5 * (lo[d] + hi[d]), half = 0.45 * (hi[d] - lo[d]);
      m.boxLo[p][d] = base[d] + mid - half;
      m.boxHi[p][d] = base[d] + mid + half;
    }
    else
    {
      m.boxLo[p][d] = base[d] + margin;
      m.boxHi[p][d] = base[d] + 1 - margin;
    }
    const double start = m.shared[p] ? sum[d] / count : 0.5;
    m.position[p][d] = std::clamp(base[d] + start, m.boxLo[p][d], m.boxHi[p][d]);
    m.anchor[p][d] = base[d] + outer[d] / count;
  }
}

// ---- The quadrilaterals ----

struct QuadBuilder
{
  const PointBuilder& points;
  const BitVolume& interior;

  /// The point of voxel v that holds local edge e.
  std::int32_t pointAt(const std::array<std::int32_t, 3>& v, int e) const
  {
    const auto& keys = this->points.voxelKey;
    const std::int64_t key = this->points.keyOf(v[0], v[1], v[2]);
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    if (it == keys.end() || *it != key)
      return -1;
    const std::int64_t first = it - keys.begin();
    const int c = cycleTable().edgeCycle[this->points.config[first]][e];
    return c < 0 ? -1 : std::int32_t(first + c);
  }

  /// The edges point p generates a quadrilateral for: its chain's edges at the voxel's
  /// lowest b and c offsets (each crossing edge has exactly one voxel seeing it there).
  template<typename Visit>
  void forOwnEdges(std::int64_t p, Visit visit) const
  {
    const auto& chainOf = cycleTable().edgeCycle[this->points.config[p]];
    for (int a = 0; a < 3; ++a)
      if (chainOf[4 * a] == this->points.cycle[p])
        visit(a);
  }

  Quad quadAround(std::int64_t p, int a) const;
};

Quad QuadBuilder::quadAround(std::int64_t p, int a) const
{
  const auto& v = this->points.model.voxel[p];
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const int ring[4][2] = { { 1, 1 }, { 0, 1 }, { 0, 0 }, { 1, 0 } };
  Quad q;
  for (int r = 0; r < 4; ++r)
  {
    std::array<std::int32_t, 3> w = v;
    w[b] -= ring[r][0];
    w[c] -= ring[r][1];
    q[r] = this->pointAt(w, 4 * a + ring[r][0] + 2 * ring[r][1]);
  }
  // Outward: from the interior end of the edge (the voxel's corner at offset 0 along a).
  if (!this->interior.get(v[0], v[1], v[2]))
    std::swap(q[1], q[3]);
  return q;
}

void buildQuads(const PointBuilder& points,
  const BitVolume& interior,
  DeformedModel& m,
  const Execution& exec)
{
  const QuadBuilder builder{ points, interior };
  const std::int64_t np = std::int64_t(m.pointCount());
  std::vector<std::int64_t> start(np + 1, 0);
  exec.forRange(np,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t p = b; p < e; ++p)
        builder.forOwnEdges(p, [&](int) { ++start[p + 1]; });
    });
  std::partial_sum(start.begin(), start.end(), start.begin());
  m.quads.resize(start[np]);
  exec.forRange(np,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t p = b; p < e; ++p)
      {
        std::int64_t q = start[p];
        builder.forOwnEdges(p, [&](int a) { m.quads[q++] = builder.quadAround(p, a); });
      }
    });
}

} // namespace

/// CSR lists of each point's quadrilaterals and links (the successor of the point in each
/// of its quadrilaterals: every link once, on an oriented closed net).
void linkQuadrilaterals(DeformedModel& m)
{
  const std::size_t np = m.pointCount();
  m.linkOffsets.assign(np + 1, 0);
  for (const Quad& q : m.quads)
    for (int r = 0; r < 4; ++r)
      ++m.linkOffsets[q[r] + 1];
  std::partial_sum(m.linkOffsets.begin(), m.linkOffsets.end(), m.linkOffsets.begin());
  m.links.resize(m.linkOffsets[np]);
  m.quadsOf.resize(m.linkOffsets[np]);
  std::vector<std::int64_t> fill(m.linkOffsets.begin(), m.linkOffsets.end() - 1);
  for (std::size_t qi = 0; qi < m.quads.size(); ++qi)
  {
    const Quad& q = m.quads[qi];
    for (int r = 0; r < 4; ++r)
    {
      const std::int64_t slot = fill[q[r]]++;
      m.links[slot] = q[(r + 1) % 4];
      m.quadsOf[slot] = std::int32_t(qi);
    }
  }
}

namespace
{

/// The ambiguous faces (voxel linear index * 8 + face, for both voxels of the face) across
/// which two points are linked twice.
std::vector<std::uint64_t> doublyLinkedFaces(const DeformedModel& m)
{
  std::vector<std::uint64_t> out;
  const auto& n = m.dims;
  auto id = [&](const std::array<std::int32_t, 3>& v, int face)
  {
    return (std::uint64_t(v[0]) + std::uint64_t(n[0]) * (v[1] + std::uint64_t(n[1]) * v[2])) * 8 +
      face;
  };
  for (std::size_t p = 0; p < m.pointCount(); ++p)
  {
    std::vector<std::int32_t> next(
      m.links.begin() + m.linkOffsets[p], m.links.begin() + m.linkOffsets[p + 1]);
    std::sort(next.begin(), next.end());
    for (std::size_t i = 1; i < next.size(); ++i)
    {
      if (next[i] != next[i - 1])
        continue;
      const auto& a = m.voxel[p];
      const auto& b = m.voxel[next[i]];
      for (int axis = 0; axis < 3; ++axis)
        if (a[axis] != b[axis])
        {
          const bool up = b[axis] > a[axis];
          out.push_back(id(a, 2 * axis + (up ? 1 : 0)));
          out.push_back(id(b, 2 * axis + (up ? 0 : 1)));
        }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// ---- Relaxation and GDM normals ----

double relaxColour(DeformedModel& m,
  const std::vector<std::int32_t>& ids,
  double attachment,
  const Execution& exec)
{
  std::mutex mutex;
  double moved = 0.0;
  exec.forRange(std::int64_t(ids.size()),
    [&](std::int64_t b, std::int64_t e)
    {
      double local = 0.0;
      for (std::int64_t i = b; i < e; ++i)
      {
        const std::int32_t p = ids[i];
        const std::int64_t lb = m.linkOffsets[p], le = m.linkOffsets[p + 1];
        if (lb == le)
          continue;
        Vec3 mean{
          attachment * m.anchor[p][0], attachment * m.anchor[p][1], attachment * m.anchor[p][2]
        };
        for (std::int64_t l = lb; l < le; ++l)
          for (int d = 0; d < 3; ++d)
            mean[d] += m.position[m.links[l]][d];
        const double weight = double(le - lb) + attachment;
        for (int d = 0; d < 3; ++d)
        {
          const double x = std::clamp(mean[d] / weight, m.boxLo[p][d], m.boxHi[p][d]);
          local = std::max(local, std::abs(x - m.position[p][d]));
          m.position[p][d] = x;
        }
      }
      std::lock_guard<std::mutex> lock(mutex);
      moved = std::max(moved, local);
    });
  return moved;
}

} // namespace

void relaxDeformedModel(DeformedModel& m,
  const DeformedModelOptions& options,
  const Execution& exec)
{
  std::vector<std::int32_t> colour[2];
  for (std::size_t p = 0; p < m.pointCount(); ++p)
  {
    const auto& v = m.voxel[p];
    colour[(v[0] + v[1] + v[2]) & 1].push_back(std::int32_t(p));
  }
  for (int it = 0; it < options.iterations; ++it)
  {
    if (exec.stopRequested())
      return;
    const double moved = std::max(relaxColour(m, colour[0], options.attachment, exec),
      relaxColour(m, colour[1], options.attachment, exec));
    m.iterationsRun = it + 1;
    m.lastDisplacement = moved;
    if (moved <= options.tolerance)
      break;
  }
}

namespace
{

inline Vec3 sub(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

void computeNormals(DeformedModel& m, const Execution& exec)
{
  m.normal.assign(m.pointCount(), Vec3{ 0, 0, 0 });
  exec.forRange(std::int64_t(m.pointCount()),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t p = b; p < e; ++p)
        for (std::int64_t l = m.linkOffsets[p]; l < m.linkOffsets[p + 1]; ++l)
        {
          const Quad& q = m.quads[m.quadsOf[l]];
          int r = 0;
          while (q[r] != p)
            ++r;
          const Vec3& P = m.position[p];
          const Vec3 n =
            cross(sub(m.position[q[(r + 1) % 4]], P), sub(m.position[q[(r + 3) % 4]], P));
          for (int d = 0; d < 3; ++d)
            m.normal[p][d] += n[d];
        }
    });
}

void countBoundaryVoxels(const BitVolume& object, const BitVolume& interior, DeformedModel& m)
{
  const auto& n = object.dims();
  for (std::int32_t k = 0; k < n[2]; ++k)
    for (std::int32_t j = 0; j < n[1]; ++j)
    {
      const Word* o = object.row(j, k);
      for (std::size_t w = 0; w < object.wordsPerRow(); ++w)
      {
        const std::size_t vw = interior.wordsPerRow();
        Word any = 0, all = ~Word(0);
        for (int c = 0; c < 4; ++c)
        {
          const Word* r = interior.row(j + (c & 1), k + (c >> 1));
          any |= r[w] | shiftedDown(r, w, vw);
          all &= r[w] & shiftedDown(r, w, vw);
        }
        m.boundaryVoxels += __builtin_popcountll(o[w] & ~all);
        m.prunedVoxels += __builtin_popcountll(o[w] & ~any);
      }
    }
}

} // namespace

DeformedModel buildDeformedModel(const BitVolume& object,
  const DeformedModelOptions& options,
  const Execution& exec)
{
  DeformedModel m;
  m.dims = object.dims();
  if (object.voxelCount() == 0)
    return m;
  const BitVolume interior = interiorVertices(object, exec);
  std::vector<std::uint64_t> flipped;
  for (int attempt = 0;; ++attempt)
  {
    m = DeformedModel();
    m.dims = object.dims();
    PointBuilder points{ object, interior, m, {}, {}, {}, options.margin, flipped };
    points.build(exec);
    buildQuads(points, interior, m, exec);
    linkQuadrilaterals(m);
    // Where the rule still links two points twice (chains joined through other faces), the
    // face between them is chained the other way, and the net built again.
    const std::vector<std::uint64_t> twice = doublyLinkedFaces(m);
    if (twice.empty() || attempt == 8)
      break;
    flipped.insert(flipped.end(), twice.begin(), twice.end());
    std::sort(flipped.begin(), flipped.end());
  }
  countBoundaryVoxels(object, interior, m);
  relaxDeformedModel(m, options, exec);
  computeNormals(m, exec);
  return m;
}

std::vector<std::array<std::array<std::int32_t, 3>, 4>> unprunedQuadrilaterals(
  const BitVolume& object)
{
  const auto& n = object.dims();
  auto at = [&](std::int32_t i, std::int32_t j, std::int32_t k)
  { return object.getOrBackground(i, j, k); };
  auto boundary = [&](const std::array<std::int32_t, 3>& v)
  {
    if (!at(v[0], v[1], v[2]))
      return false;
    for (int d = 0; d < 27; ++d)
      if (!at(v[0] + d % 3 - 1, v[1] + (d / 3) % 3 - 1, v[2] + d / 9 - 1))
        return true;
    return false;
  };
  std::vector<std::array<std::array<std::int32_t, 3>, 4>> out;
  const int ring[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  for (std::int32_t k = 0; k < n[2]; ++k)
    for (std::int32_t j = 0; j < n[1]; ++j)
      for (std::int32_t i = 0; i < n[0]; ++i)
        for (int a = 0; a < 3; ++a)
        {
          std::array<std::array<std::int32_t, 3>, 4> q;
          bool all = true;
          for (int r = 0; r < 4 && all; ++r)
          {
            q[r] = { i, j, k };
            q[r][(a + 1) % 3] += ring[r][0];
            q[r][(a + 2) % 3] += ring[r][1];
            all = boundary(q[r]);
          }
          if (all)
            out.push_back(q);
        }
  return out;
}

double relaxationCost(const DeformedModel& m, double attachment)
{
  double cost = 0.0;
  for (std::size_t p = 0; p < m.pointCount(); ++p)
    for (std::int64_t l = m.linkOffsets[p]; l < m.linkOffsets[p + 1]; ++l)
    {
      const Vec3 d = sub(m.position[p], m.position[m.links[l]]);
      cost += 0.5 * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]); // each link is seen twice
    }
  for (std::size_t p = 0; p < m.pointCount(); ++p)
  {
    const Vec3 d = sub(m.position[p], m.anchor[p]);
    cost += attachment * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  return cost;
}

} // namespace vbr
