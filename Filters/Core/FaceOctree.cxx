#include "FaceOctree.h"

#include "PolygonTriangulator.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <utility>

namespace vbr
{
namespace
{

inline double dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double norm(const Vec3& a)
{
  return std::sqrt(dot(a, a));
}

/// Morton code of a voxel (21 bits an axis).
std::uint64_t mortonOf(const std::array<std::int32_t, 3>& v)
{
  auto spread = [](std::uint64_t x)
  {
    x &= 0x1FFFFF;
    x = (x | x << 32) & 0x1F00000000FFFFULL;
    x = (x | x << 16) & 0x1F0000FF0000FFULL;
    x = (x | x << 8) & 0x100F00F00F00F00FULL;
    x = (x | x << 4) & 0x10C30C30C30C30C3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
  };
  return spread(std::uint64_t(v[0])) | spread(std::uint64_t(v[1])) << 1 |
    spread(std::uint64_t(v[2])) << 2;
}

/// A candidate node: its points, contiguous in Morton order.
struct Candidate
{
  int level;
  std::uint64_t key; ///< Morton code >> 3 level
  std::size_t begin, end;
};

/// The points a plane is fitted to: an octree node's (the cube of a Morton prefix) or the
/// union of two face nodes (the merging of mergeFaceNodes below), with the box no far voxel
/// of which the plane may cut.
struct Region
{
  const std::int32_t* first = nullptr; ///< its points: by Morton code, or by id for faces
  std::size_t size = 0;
  int level = 0;
  std::array<std::int32_t, 3> lo{ 0, 0, 0 }, hi{ 0, 0, 0 };
  const std::uint64_t* codes = nullptr; ///< an octree node: codes >> 3 level == key
  std::uint64_t key = 0;
  const std::int32_t* faceOf = nullptr; ///< else two faces: faceOf[p] is a or b
  std::int32_t a = -1, b = -1;

  bool contains(std::int32_t p) const
  {
    if (this->codes)
      return (this->codes[p] >> (3 * this->level)) == this->key;
    return this->faceOf[p] == this->a || this->faceOf[p] == this->b;
  }
  /// The position of one of its points among them.
  std::size_t indexOf(std::int32_t p) const
  {
    const std::int32_t* last = this->first + this->size;
    const std::int32_t* it = this->codes
      ? std::lower_bound(this->first,
          last,
          p,
          [&](std::int32_t x, std::int32_t y) { return this->codes[x] < this->codes[y]; })
      : std::lower_bound(this->first, last, p);
    while (*it != p)
      ++it; // two points share a voxel (and its code)
    return std::size_t(it - this->first);
  }
};

struct NodeFit
{
  bool ok = false;
  FaceNode node;
  std::vector<Vec3> projected; ///< of the candidate's points, in order
  /// The candidate's points with a quadrilateral that leaves it (the sewing's only points).
  std::vector<std::int32_t> rim;
  /// The quadrilaterals inside it (the reach rule only: checked for folds).
  std::vector<std::int32_t> inside;
};

struct Compactor
{
  const BitVolume& far;
  const DeformedModel& model;
  const FaceOctreeOptions& options;
  /// The object, for the surfels each projection must reach (FaceOctree.h's second rule);
  /// null: the paper's rule (the label net, or keepPointsInVoxels).
  const BitVolume* object = nullptr;
  std::vector<std::int32_t> order;  ///< points by Morton code of their voxel
  std::vector<std::uint64_t> codes; ///< per point
  double precision = std::sqrt(3.0);
  const std::vector<Vec3>* current = nullptr; ///< the points' positions so far

  Region regionOf(const Candidate& c) const;
  NodeFit fit(const Region& c) const;
  bool sewingUnfolded(const Region& c, const NodeFit& f) const;
  bool planeNormal(const Region& c, Vec3& n) const;
  bool planeOffset(const Region& c, const FaceNode& node, double& t) const;
  bool reachesSurfels(std::int32_t p, const Vec3& q) const;
  bool insideUnfolded(const Region& c, const NodeFit& f) const;
  bool sewingNearBoundary(const std::array<Vec3, 4>& corners) const;
  void forbiddenIntervals(const FaceNode& node,
    double lo,
    double hi,
    std::vector<std::pair<double, double>>& out) const;
  bool collapseToPolygon(const Region& c, NodeFit& f) const;
};

Region Compactor::regionOf(const Candidate& c) const
{
  Region r;
  r.first = this->order.data() + c.begin;
  r.size = c.end - c.begin;
  r.level = c.level;
  r.codes = this->codes.data();
  r.key = c.key;
  const auto& v = this->model.voxel[*r.first];
  for (int d = 0; d < 3; ++d)
  {
    r.lo[d] = (v[d] >> c.level) << c.level;
    r.hi[d] = std::min<std::int32_t>(this->model.dims[d], r.lo[d] + (std::int32_t(1) << c.level));
  }
  return r;
}

bool Compactor::planeNormal(const Region& c, Vec3& n) const
{
  n = { 0, 0, 0 };
  for (std::size_t i = 0; i < c.size; ++i)
    for (int d = 0; d < 3; ++d)
      n[d] += this->model.normal[c.first[i]][d];
  const double len = norm(n);
  if (!(len > 1e-12))
    return false;
  for (int d = 0; d < 3; ++d)
    n[d] /= len;
  for (std::size_t i = 0; i < c.size; ++i)
  {
    const Vec3& m = this->model.normal[c.first[i]];
    if (dot(m, n) < this->options.minimumCosine * norm(m))
      return false;
  }
  return true;
}

/// Open intervals of offsets whose plane cuts a far voxel of the node, for offsets in
/// [lo, hi]; only voxels whose slab along n reaches that range are visited, row by row.
void Compactor::forbiddenIntervals(const FaceNode& node,
  double lo,
  double hi,
  std::vector<std::pair<double, double>>& out) const
{
  const Vec3& n = node.normal;
  const double r = 0.5 * (std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]));
  for (std::int32_t k = node.lo[2]; k < node.hi[2]; ++k)
    for (std::int32_t j = node.lo[1]; j < node.hi[1]; ++j)
    {
      const double base = n[1] * (j + 0.5) + n[2] * (k + 0.5);
      std::int32_t i0 = node.lo[0], i1 = node.hi[0];
      if (std::abs(n[0]) > 1e-12)
      {
        // centre value v = base + n0 (i + 0.5) must lie in (lo - r, hi + r).
        double a = (lo - r - base) / n[0] - 0.5, b = (hi + r - base) / n[0] - 0.5;
        if (a > b)
          std::swap(a, b);
        // Clamped in double first: a nearly perpendicular normal gives offsets far outside
        // the int range.
        const double first = std::floor(a) - 1, last = std::ceil(b) + 2;
        if (first > i0)
          i0 = first >= i1 ? i1 : static_cast<std::int32_t>(first);
        if (last < i1)
          i1 = last <= i0 ? i0 : static_cast<std::int32_t>(last);
      }
      for (std::int32_t i = i0; i < i1; ++i)
      {
        const double v = base + n[0] * (i + 0.5);
        if (v - r < hi && v + r > lo && this->far.get(i, j, k))
          out.emplace_back(v - r, v + r);
      }
    }
}

bool Compactor::planeOffset(const Region& c, const FaceNode& node, double& t) const
{
  const Vec3& n = node.normal;
  double lo = -1e300, hi = 1e300, sum = 0.0, weight = 0.0;
  for (std::size_t i = 0; i < c.size; ++i)
  {
    const std::int32_t p = c.first[i];
    double bmin = 0.0, bmax = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      bmin += n[d] * (n[d] > 0 ? this->model.boxLo[p][d] : this->model.boxHi[p][d]);
      bmax += n[d] * (n[d] > 0 ? this->model.boxHi[p][d] : this->model.boxLo[p][d]);
    }
    const double at = dot(n, this->model.position[p]);
    if (!this->object)
      lo = std::max(lo, bmin), hi = std::min(hi, bmax);
    lo = std::max(lo, at - this->precision);
    hi = std::min(hi, at + this->precision);
    const double w = norm(this->model.normal[p]) + 1e-12;
    sum += w * at;
    weight += w;
  }
  if (this->object)
  { // the plane meets the node's box: the projections stay in it
    double boxMin = 0.0, boxMax = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      boxMin += n[d] * (n[d] > 0 ? node.lo[d] : node.hi[d]);
      boxMax += n[d] * (n[d] > 0 ? node.hi[d] : node.lo[d]);
    }
    lo = std::max(lo, boxMin);
    hi = std::min(hi, boxMax);
  }
  if (!(lo <= hi))
    return false;
  std::vector<std::pair<double, double>> cuts;
  this->forbiddenIntervals(node, lo, hi, cuts);
  // The allowed offsets: [lo, hi] minus the open cuts; pick the one nearest the mean.
  std::sort(cuts.begin(), cuts.end());
  const double wanted = std::clamp(sum / weight, lo, hi);
  bool found = false;
  double best = 0.0, cursor = lo;
  auto consider = [&](double a, double b)
  {
    if (a > b)
      return;
    const double x = std::clamp(wanted, a, b);
    if (!found || std::abs(x - wanted) < std::abs(best - wanted))
      best = x, found = true;
  };
  for (const auto& cut : cuts)
  {
    consider(cursor, std::min(cut.first, hi));
    cursor = std::max(cursor, cut.second);
  }
  consider(cursor, hi);
  t = best;
  return found;
}

/// The inside quadrilaterals' boundary as one simple counter-clockwise loop around a disk.
bool Compactor::collapseToPolygon(const Region& c, NodeFit& f) const
{
  const DeformedModel& m = this->model;
  std::vector<std::uint64_t> edges; // directed edges of the inside quadrilaterals
  std::size_t faces = 0;
  std::vector<std::int32_t> used;
  for (std::size_t i = 0; i < c.size; ++i)
  {
    const std::int32_t p = c.first[i];
    bool any = false, leaves = false;
    for (std::int64_t l = m.linkOffsets[p]; l < m.linkOffsets[p + 1]; ++l)
    {
      const Quad& q = m.quads[m.quadsOf[l]];
      if (!(c.contains(q[0]) && c.contains(q[1]) && c.contains(q[2]) && c.contains(q[3])))
      {
        if (!leaves)
          f.rim.push_back(p), leaves = true;
        continue;
      }
      any = true;
      if (q[0] != p)
        continue;
      ++faces;
      if (this->object)
        f.inside.push_back(m.quadsOf[l]);
      for (int r = 0; r < 4; ++r)
        edges.push_back(std::uint64_t(std::uint32_t(q[r])) << 32 | std::uint32_t(q[(r + 1) % 4]));
    }
    if (any)
      used.push_back(p);
  }
  if (faces == 0)
    return true;
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<std::int32_t, std::int32_t>> boundary;
  for (std::uint64_t e : edges)
  {
    const std::uint64_t reverse = (e << 32) | (e >> 32);
    if (!std::binary_search(edges.begin(), edges.end(), reverse))
      boundary.emplace_back(std::int32_t(e >> 32), std::int32_t(e & 0xFFFFFFFF));
  }
  const std::size_t B = boundary.size();
  const long long euler =
    (long long)used.size() - (long long)(4 * faces + B) / 2 + (long long)faces;
  if (B < 3 || euler != 1)
    return false;
  std::sort(boundary.begin(), boundary.end());
  for (std::size_t i = 1; i < B; ++i)
    if (boundary[i].first == boundary[i - 1].first)
      return false; // the disk is pinched at a point
  auto next = [&](std::int32_t a)
  {
    auto it = std::lower_bound(boundary.begin(), boundary.end(), std::make_pair(a, INT32_MIN));
    return (it != boundary.end() && it->first == a) ? it->second : -1;
  };
  auto& loop = f.node.polygon;
  std::int32_t a = boundary[0].first;
  do
  {
    loop.push_back(a);
    a = next(a);
  } while (a >= 0 && a != loop.front() && loop.size() <= B);
  return a == loop.front() && loop.size() == B;
}

/// Whether every quadrilateral that leaves the node still has a split into two triangles
/// facing the way the relaxed quadrilateral faces (with the node's points projected and the
/// others where they are now): projecting must not fold the sewing triangles.
bool Compactor::sewingUnfolded(const Region& c, const NodeFit& f) const
{
  const DeformedModel& m = this->model;
  const std::vector<Vec3>& projected = f.projected;
  auto positionOf = [&](std::int32_t p) -> const Vec3&
  { return c.contains(p) ? projected[c.indexOf(p)] : (*this->current)[p]; };
  auto normal = [](const Vec3& a, const Vec3& b, const Vec3& d)
  {
    const Vec3 u{ b[0] - a[0], b[1] - a[1], b[2] - a[2] },
      v{ d[0] - a[0], d[1] - a[1], d[2] - a[2] };
    return Vec3{ u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
  };
  for (const std::int32_t p : f.rim)
  {
    for (std::int64_t l = m.linkOffsets[p]; l < m.linkOffsets[p + 1]; ++l)
    {
      const Quad& q = m.quads[m.quadsOf[l]];
      if (c.contains(q[0]) && c.contains(q[1]) && c.contains(q[2]) && c.contains(q[3]))
        continue;
      const Vec3 a = normal(m.position[q[0]], m.position[q[1]], m.position[q[2]]);
      const Vec3 b = normal(m.position[q[0]], m.position[q[2]], m.position[q[3]]);
      const Vec3 n{ a[0] + b[0], a[1] + b[1], a[2] + b[2] };
      const Vec3 &x0 = positionOf(q[0]), &x1 = positionOf(q[1]), &x2 = positionOf(q[2]),
                 &x3 = positionOf(q[3]);
      if (this->object && !this->sewingNearBoundary({ x0, x1, x2, x3 }))
        return false;
      const double first = std::min(dot(normal(x0, x1, x2), n), dot(normal(x0, x2, x3), n));
      const double second = std::min(dot(normal(x0, x1, x3), n), dot(normal(x1, x2, x3), n));
      if (!(std::max(first, second) > 1e-3 * dot(n, n)))
        return false;
    }
  }
  return true;
}

/// Whether every quadrilateral inside the node, projected, has a split into two triangles
/// turning counter-clockwise about the normal: the projected disk then covers its polygon
/// once (a disk mapped locally one-to-one whose boundary goes to a simple loop), so each
/// point inside it, which the polygon replaces, lies on the polygon (its surfels stay within
/// reach of the surface, not only of the point).
bool Compactor::insideUnfolded(const Region& c, const NodeFit& f) const
{
  const Vec3& n = f.node.normal;
  auto turn = [&](const Vec3& a, const Vec3& b, const Vec3& d)
  {
    const Vec3 u{ b[0] - a[0], b[1] - a[1], b[2] - a[2] },
      v{ d[0] - a[0], d[1] - a[1], d[2] - a[2] };
    return n[0] * (u[1] * v[2] - u[2] * v[1]) + n[1] * (u[2] * v[0] - u[0] * v[2]) +
      n[2] * (u[0] * v[1] - u[1] * v[0]);
  };
  for (const std::int32_t i : f.inside)
  {
    const Quad& q = this->model.quads[i];
    const Vec3 &x0 = f.projected[c.indexOf(q[0])], &x1 = f.projected[c.indexOf(q[1])],
               &x2 = f.projected[c.indexOf(q[2])], &x3 = f.projected[c.indexOf(q[3])];
    const bool first = turn(x0, x1, x2) > 0 && turn(x0, x2, x3) > 0;
    if (!first && !(turn(x0, x1, x3) > 0 && turn(x1, x2, x3) > 0))
      return false;
  }
  return true;
}

/// Whether q lies within one voxel diagonal of every corner of every surfel of p's voxel (a
/// face of it whose neighbour across is background): then of every point of those surfels.
bool Compactor::reachesSurfels(std::int32_t p, const Vec3& q) const
{
  const auto& v = this->model.voxel[p];
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side)
    {
      std::array<std::int32_t, 3> w = v;
      w[a] += side ? 1 : -1;
      if (this->object->getOrBackground(w[0], w[1], w[2]))
        continue;
      // The face's corners: coordinate a fixed, the two others at both ends of the voxel.
      for (int corner = 0; corner < 4; ++corner)
      {
        double d2 = 0.0;
        for (int d = 0, bit = 0; d < 3; ++d)
        {
          const double x = d == a ? v[d] + side : v[d] + ((corner >> bit++) & 1);
          d2 += (q[d] - x) * (q[d] - x);
        }
        if (d2 > 3.0)
          return false;
      }
    }
  return true;
}

/// Whether no far voxel meets the bounding box of a sewing quadrilateral's corners: its two
/// triangles lie in that box, so every point of them is in a voxel that touches the surfels.
bool Compactor::sewingNearBoundary(const std::array<Vec3, 4>& corners) const
{
  std::array<std::int32_t, 3> lo, hi;
  const auto& dims = this->far.dims();
  for (int d = 0; d < 3; ++d)
  {
    double a = corners[0][d], b = corners[0][d];
    for (const Vec3& x : corners)
      a = std::min(a, x[d]), b = std::max(b, x[d]);
    lo[d] = std::max<std::int32_t>(0, std::int32_t(std::floor(a)));
    hi[d] = std::min<std::int32_t>(dims[d] - 1, std::int32_t(std::floor(b)));
  }
  for (std::int32_t k = lo[2]; k <= hi[2]; ++k)
    for (std::int32_t j = lo[1]; j <= hi[1]; ++j)
      for (std::int32_t i = lo[0]; i <= hi[0]; ++i)
        if (this->far.get(i, j, k))
          return false;
  return true;
}

NodeFit Compactor::fit(const Region& c) const
{
  NodeFit f;
  FaceNode& node = f.node;
  node.level = c.level;
  node.lo = c.lo;
  node.hi = c.hi;
  if (!this->planeNormal(c, node.normal) || !this->planeOffset(c, node, node.offset))
    return f;
  const Vec3 nodeLo{ double(node.lo[0]), double(node.lo[1]), double(node.lo[2]) };
  const Vec3 nodeHi{ double(node.hi[0]), double(node.hi[1]), double(node.hi[2]) };
  for (std::size_t i = 0; i < c.size; ++i)
  {
    const std::int32_t p = c.first[i];
    const bool inVoxel = !this->object;
    f.projected.push_back(projectIntoBox(this->model.position[p],
      node.normal,
      node.offset,
      inVoxel ? this->model.boxLo[p] : nodeLo,
      inVoxel ? this->model.boxHi[p] : nodeHi));
    if (!inVoxel && !this->reachesSurfels(p, f.projected.back()))
      return f;
  }
  if (!this->collapseToPolygon(c, f) || !this->sewingUnfolded(c, f) ||
    (this->object && !this->insideUnfolded(c, f)))
    return f;
  if (!node.polygon.empty())
  {
    std::vector<Vec3> corners;
    for (std::int32_t p : node.polygon)
    {
      corners.push_back(f.projected[c.indexOf(p)]);
    }
    const auto flat = planeCoordinates(node, corners);
    if (!(doubledArea(flat) > 0) || !isSimplePolygon(flat) ||
      polygonTriangles(node, corners).empty())
      return f;
  }
  f.ok = true;
  return f;
}

/// Straight runs, in plane units of 2^-30 voxel: a corner off the chord of its run by at
/// most `runTolerance` lies on the run, and a run's end lies more than `endTolerance` off the
/// chord of its neighbouring ends. The grid rounds by half a unit, the doubles far less: both
/// are well above that and far below anything the voxels shape.
constexpr double endTolerance = 16.0, runTolerance = 64.0;

double offChord(const std::vector<Point2L>& c, std::size_t a, std::size_t i, std::size_t b)
{
  const double len = std::hypot(double(c[b][0] - c[a][0]), double(c[b][1] - c[a][1]));
  return len > 0 ? std::abs(double(cross2(c[a], c[i], c[b]))) / len : HUGE_VAL;
}

/// The corner between ends a and b (cyclic) farthest off their chord or out of order along
/// it, if it is not on the run; n when the run holds.
std::size_t breakOfRun(const std::vector<Point2L>& c, std::size_t a, std::size_t b)
{
  const std::size_t n = c.size();
  const double dx = double(c[b][0] - c[a][0]), dy = double(c[b][1] - c[a][1]);
  std::size_t worst = n;
  double far = runTolerance, last = 0.0;
  for (std::size_t i = (a + 1) % n; i != b; i = (i + 1) % n)
  {
    const double along = dx * double(c[i][0] - c[a][0]) + dy * double(c[i][1] - c[a][1]);
    if (!(along > last) || !(along < dx * dx + dy * dy))
      return i;
    last = along;
    const double off = offChord(c, a, i, b);
    if (off > far)
      far = off, worst = i;
  }
  return worst;
}

/// The ends of the straight runs of a polygon (corners kept), by splitting runs at their
/// farthest corner and merging runs at ends that go nearly straight, until both hold; empty
/// if that does not settle or leaves fewer than three ends.
std::vector<char> runEnds(const std::vector<Point2L>& c)
{
  const std::size_t n = c.size();
  std::vector<char> end(n);
  for (std::size_t i = 0; i < n; ++i)
    end[i] = offChord(c, (i + n - 1) % n, i, (i + 1) % n) > endTolerance;
  for (std::size_t round = 0; round < 2 * n; ++round)
  {
    std::vector<std::size_t> ends;
    for (std::size_t i = 0; i < n; ++i)
      if (end[i])
        ends.push_back(i);
    const std::size_t m = ends.size();
    if (m < 3)
      return {};
    bool changed = false;
    for (std::size_t k = 0; k < m; ++k)
    {
      const std::size_t split = breakOfRun(c, ends[k], ends[(k + 1) % m]);
      if (split < n)
        end[split] = 1, changed = true;
    }
    for (std::size_t k = 0; k < m && !changed && m > 3; ++k)
      if (offChord(c, ends[(k + m - 1) % m], ends[k], ends[(k + 1) % m]) <= endTolerance)
        end[ends[k]] = 0, changed = true;
    if (!changed)
      return end;
  }
  return {};
}

/// The coordinates a polygon is cut into triangles in: the plane coordinates scaled up, with
/// the corners of each straight run moved exactly onto the chord of the run. The triangles
/// keep the points' own (double) positions, and a corner the plane grid rounds onto one side
/// of its neighbours' chord may lie a hair on the other: a sliver decided on the grid would
/// then fold, or a triangle's edge pass through a corner where sewing triangles meet the
/// polygon. Runs are common: points clamped to a face of their voxel box line up where the
/// node's plane crosses that face, and flat faces relax into rows. On exact chords a run's
/// corner is never an ear's tip nor inside a triangle's edge; its triangles take their third
/// corner well off the run.
std::vector<Point2L> straightened(const std::vector<Point2L>& flat)
{
  const std::size_t n = flat.size();
  std::int64_t extent = 1;
  for (const Point2L& p : flat)
    extent = std::max<std::int64_t>({ extent, std::llabs(p[0]), std::llabs(p[1]) });
  int bits = 0;
  while (bits < 63 && (extent >> bits) > 0)
    ++bits;
  const std::int64_t scale = std::int64_t(1) << std::clamp(55 - bits, 0, 20);
  std::vector<Point2L> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = { flat[i][0] * scale, flat[i][1] * scale };
  const std::vector<char> end = n > 3 ? runEnds(flat) : std::vector<char>();
  if (end.empty())
    return out;
  std::size_t a = 0;
  while (!end[a])
    ++a;
  for (std::size_t steps = 0; steps < n;)
  {
    std::size_t b = (a + 1) % n;
    while (!end[b])
      b = (b + 1) % n;
    const double dx = double(flat[b][0] - flat[a][0]), dy = double(flat[b][1] - flat[a][1]);
    std::int64_t last = 0;
    for (std::size_t i = (a + 1) % n; i != b; i = (i + 1) % n)
    {
      const double along =
        (dx * double(flat[i][0] - flat[a][0]) + dy * double(flat[i][1] - flat[a][1])) /
        (dx * dx + dy * dy);
      const std::int64_t j =
        std::clamp<std::int64_t>(std::llround(along * double(scale)), last + 1, scale - 1);
      for (int d = 0; d < 2; ++d)
        out[i][d] = flat[a][d] * scale + j * (flat[b][d] - flat[a][d]);
      last = j;
    }
    steps += (b + n - a) % n;
    a = b;
  }
  return out;
}

/// Distance from p to segment ab (plane units).
double toSegment(const Point2L& p, const Point2L& a, const Point2L& b)
{
  const double dx = double(b[0] - a[0]), dy = double(b[1] - a[1]);
  const double px = double(p[0] - a[0]), py = double(p[1] - a[1]);
  const double len2 = dx * dx + dy * dy;
  const double s = len2 > 0 ? std::clamp((dx * px + dy * py) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(px - s * dx, py - s * dy);
}

/// Whether the triangles of a polygon keep the orientation and the incidences they have on
/// the grid once their corners are back at their own positions: no triangle thinner than
/// the tolerance, and no corner that close to a diagonal it does not end.
bool robustTriangles(const std::vector<Point2L>& c, const std::vector<Triangle>& triangles)
{
  const std::size_t n = c.size();
  for (const Triangle& t : triangles)
  {
    double longest = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const Point2L &a = c[t[k]], &b = c[t[(k + 1) % 3]];
      longest = std::max(longest, std::hypot(double(b[0] - a[0]), double(b[1] - a[1])));
    }
    if (!(double(cross2(c[t[0]], c[t[1]], c[t[2]])) > endTolerance * longest))
      return false;
    for (int k = 0; k < 3; ++k)
    {
      const std::size_t a = std::size_t(t[k]), b = std::size_t(t[(k + 1) % 3]);
      if ((a + 1) % n == b || (b + 1) % n == a)
        continue; // an edge of the polygon
      // Only corners in the diagonal's box grown by the tolerance can be that close.
      const double reach = endTolerance + 1;
      const double x0 = double(std::min(c[a][0], c[b][0])) - reach,
                   x1 = double(std::max(c[a][0], c[b][0])) + reach,
                   y0 = double(std::min(c[a][1], c[b][1])) - reach,
                   y1 = double(std::max(c[a][1], c[b][1])) + reach;
      for (std::size_t i = 0; i < n; ++i)
      {
        const double x = double(c[i][0]), y = double(c[i][1]);
        if (x < x0 || x > x1 || y < y0 || y > y1 || i == a || i == b)
          continue;
        if (toSegment(c[i], c[a], c[b]) <= endTolerance)
          return false;
      }
    }
  }
  return true;
}

} // namespace

std::vector<Point2L> planeCoordinates(const FaceNode& node, const std::vector<Vec3>& points)
{
  const Vec3& n = node.normal;
  int e = 0;
  for (int d = 1; d < 3; ++d)
    if (std::abs(n[d]) < std::abs(n[e]))
      e = d;
  Vec3 axis{ 0, 0, 0 };
  axis[e] = 1;
  Vec3 u{ n[1] * axis[2] - n[2] * axis[1],
    n[2] * axis[0] - n[0] * axis[2],
    n[0] * axis[1] - n[1] * axis[0] };
  const double lu = norm(u);
  for (double& x : u)
    x /= lu;
  const Vec3 v{ n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0] };
  std::vector<Point2L> out;
  const Vec3 o{ double(node.lo[0]), double(node.lo[1]), double(node.lo[2]) };
  for (const Vec3& p : points)
  {
    const Vec3 d{ p[0] - o[0], p[1] - o[1], p[2] - o[2] };
    out.push_back(
      { std::llround(dot(d, u) * 1073741824.0), std::llround(dot(d, v) * 1073741824.0) });
  }
  return out;
}

std::vector<Triangle> polygonTriangles(const FaceNode& node, const std::vector<Vec3>& corners)
{
  const std::vector<Point2L> grid = planeCoordinates(node, corners);
  std::vector<Triangle> triangles = triangulateSimplePolygon(straightened(grid));
  if (triangles.size() + 2 != grid.size() || !robustTriangles(grid, triangles))
    triangles.clear();
  return triangles;
}

BitVolume farVoxels(const BitVolume& object, const Execution& exec)
{
  const auto& n = object.dims();
  BitVolume out(n[0], n[1], n[2]);
  const std::size_t words = object.wordsPerRow();
  const Word lastMask = (n[0] % 64) ? ((Word(1) << (n[0] % 64)) - 1) : ~Word(0);
  exec.forRange(n[2],
    [&](std::int64_t kb, std::int64_t ke)
    {
      std::vector<Word> all(words), any(words);
      for (std::int32_t k = std::int32_t(kb); k < ke; ++k)
        for (std::int32_t j = 0; j < n[1]; ++j)
        {
          std::fill(all.begin(), all.end(), ~Word(0));
          std::fill(any.begin(), any.end(), Word(0));
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
            {
              const std::int32_t y = j + dj, z = k + dk;
              const bool inside = y >= 0 && z >= 0 && y < n[1] && z < n[2];
              for (std::size_t w = 0; w < words; ++w)
              {
                const Word r = inside ? object.row(y, z)[w] : 0;
                const Word mask = (w + 1 == words) ? lastMask : ~Word(0);
                // Outside the grid along x counts as background.
                const Word prev = w > 0 ? (inside ? object.row(y, z)[w - 1] : 0) : 0;
                const Word nxt = w + 1 < words ? (inside ? object.row(y, z)[w + 1] : 0) : 0;
                const Word left = (r << 1) | (prev >> 63), right = (r >> 1) | (nxt << 63);
                all[w] &= r & left & right & mask;
                any[w] |= r | left | right;
              }
            }
          Word* dst = out.row(j, k);
          for (std::size_t w = 0; w < words; ++w)
          {
            const Word mask = (w + 1 == words) ? lastMask : ~Word(0);
            dst[w] = (all[w] | ~any[w]) & mask;
          }
        }
    });
  return out;
}

Vec3 projectIntoBox(const Vec3& p, const Vec3& n, double t, const Vec3& lo, const Vec3& hi)
{
  // x(lambda) = clamp(p - lambda n) minimises |x - p| over the box on the plane
  // n . x = n . x(lambda); g(lambda) = n . x(lambda) does not increase and is linear between
  // the lambdas where a coordinate reaches a side of the box: solve g = t on its piece.
  auto at = [&](double lambda)
  {
    Vec3 x;
    for (int d = 0; d < 3; ++d)
      x[d] = std::clamp(p[d] - lambda * n[d], lo[d], hi[d]);
    return x;
  };
  std::vector<double> breaks;
  for (int d = 0; d < 3; ++d)
    if (n[d] != 0)
    {
      breaks.push_back((p[d] - lo[d]) / n[d]);
      breaks.push_back((p[d] - hi[d]) / n[d]);
    }
  std::sort(breaks.begin(), breaks.end());
  if (breaks.empty() || dot(n, at(breaks.front())) <= t)
    return at(breaks.empty() ? 0.0 : breaks.front());
  for (std::size_t i = 1; i < breaks.size(); ++i)
  {
    const double ga = dot(n, at(breaks[i - 1])), gb = dot(n, at(breaks[i]));
    if (gb <= t)
    {
      const double f = ga > gb ? (ga - t) / (ga - gb) : 0.0;
      return at(breaks[i - 1] + f * (breaks[i] - breaks[i - 1]));
    }
  }
  return at(breaks.back());
}

namespace
{

/// The first face octree: every voxel with a single point is a face node, with its GDM plane.
void voxelFaceNodes(const DeformedModel& model, FaceOctree& out, std::vector<int>& faceLevel)
{
  for (std::size_t p = 0; p < model.pointCount(); ++p)
  {
    if (model.shared[p] || out.nodeOf[p] >= 0)
      continue;
    FaceNode node;
    node.lo = model.voxel[p];
    node.hi = { node.lo[0] + 1, node.lo[1] + 1, node.lo[2] + 1 };
    const double len = norm(model.normal[p]);
    node.normal = len > 0
      ? Vec3{ model.normal[p][0] / len, model.normal[p][1] / len, model.normal[p][2] / len }
      : Vec3{ 0, 0, 1 };
    node.offset = dot(node.normal, model.position[p]);
    out.nodeOf[p] = std::int32_t(out.nodes.size());
    out.nodes.push_back(std::move(node));
    faceLevel[p] = 0;
  }
}

/// The nodes of a level all of whose points p satisfy qualifies(p).
template<typename Qualifies>
std::vector<Candidate> nodesOfLevelWhere(const Compactor& cp, int level, Qualifies qualifies)
{
  std::vector<Candidate> candidates;
  const std::size_t np = cp.order.size();
  for (std::size_t i = 0; i < np;)
  {
    const std::uint64_t key = cp.codes[cp.order[i]] >> (3 * level);
    std::size_t j = i;
    bool all = true;
    for (; j < np && (cp.codes[cp.order[j]] >> (3 * level)) == key; ++j)
      all = all && qualifies(cp.order[j]);
    if (all)
      candidates.push_back({ level, key, i, j });
    i = j;
  }
  return candidates;
}

/// The nodes of a level whose children holding points are all face nodes.
std::vector<Candidate> candidatesOfLevel(const Compactor& cp,
  int level,
  const std::vector<int>& faceLevel)
{
  return nodesOfLevelWhere(cp, level, [&](std::size_t p) { return faceLevel[p] == level - 1; });
}

/// The nodes of a level, largest first (the reach rule): those none of whose points is in a
/// face node yet (no larger node took them) nor shared by two sheets.
std::vector<Candidate> candidatesFromAbove(const Compactor& cp,
  int level,
  const std::vector<int>& faceLevel)
{
  return nodesOfLevelWhere(
    cp, level, [&](std::size_t p) { return faceLevel[p] < 0 && !cp.model.shared[p]; });
}

/// Compacts one level: every candidate fitted in parallel, then committed in order (the
/// sewing checked again against the projections committed before). False when none fits.
bool compactLevel(const Compactor& cp,
  int level,
  const Execution& exec,
  FaceOctree& out,
  std::vector<int>& faceLevel)
{
  const std::vector<Candidate> candidates =
    cp.object ? candidatesFromAbove(cp, level, faceLevel) : candidatesOfLevel(cp, level, faceLevel);
  std::vector<NodeFit> fits(candidates.size());
  exec.forRange(std::int64_t(candidates.size()),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t c = b; c < e; ++c)
        fits[c] = cp.fit(cp.regionOf(candidates[c]));
    });
  bool any = false;
  for (std::size_t c = 0; c < candidates.size(); ++c)
  {
    if (!fits[c].ok || !cp.sewingUnfolded(cp.regionOf(candidates[c]), fits[c]))
      continue;
    const std::int32_t id = std::int32_t(out.nodes.size());
    for (std::size_t i = candidates[c].begin; i < candidates[c].end; ++i)
    {
      const std::int32_t p = cp.order[i];
      faceLevel[p] = level;
      out.nodeOf[p] = id;
      out.projected[p] = fits[c].projected[i - candidates[c].begin];
    }
    out.nodes.push_back(std::move(fits[c].node));
    any = true;
  }
  return any;
}

/// The level of the octree's root: the first whose cube holds the whole grid.
int topLevel(const std::array<std::int32_t, 3>& dims)
{
  const std::int32_t largest = *std::max_element(dims.begin(), dims.end());
  int top = 0;
  while (top < 30 && (std::int32_t(1) << top) < largest)
    ++top;
  return top;
}

/// The reach rule's compaction, from the root down: each level's nodes whose points no larger
/// node took are fitted (compactLevel), and the points no node took are then face nodes of
/// their own voxels. A node fails mostly at its first, cheap tests (the normals, the
/// precision), so the levels above the face nodes cost little; bottom-up, every level below
/// them would be fitted in full. Every node meets the same rules either way.
void compactFromAbove(const Compactor& cp,
  int top,
  const Execution& exec,
  double compaction,
  FaceOctree& out,
  std::vector<int>& faceLevel)
{
  for (int level = top; level >= 1; --level)
  {
    if (exec.stopRequested() || !exec.report(compaction * (top - level) / top))
      break;
    compactLevel(cp, level, exec, out, faceLevel);
  }
  voxelFaceNodes(cp.model, out, faceLevel);
}

/// Keeps the terminal face nodes only, renumbered in the order of their first point.
void keepTerminalNodes(FaceOctree& out)
{
  std::vector<std::int32_t> renumber(out.nodes.size(), -1);
  std::vector<FaceNode> kept;
  for (std::int32_t& id : out.nodeOf)
  {
    if (id < 0)
      continue;
    if (renumber[id] < 0)
    {
      renumber[id] = std::int32_t(kept.size());
      kept.push_back(std::move(out.nodes[id]));
    }
    id = renumber[id];
  }
  out.nodes = std::move(kept);
}

/// The boxes of the faces and the voxels of the points in no face, in buckets of 8^3 voxels:
/// a merged face's box must overlap no other. The octree's boxes are disjoint cells holding
/// their own points only; keeping them so keeps every polygon in a box of its own, apart from
/// the others' (their sewing is checked as for octree nodes).
class BoxIndex
{
public:
  static constexpr int bucket = 8;

  BoxIndex(const std::array<std::int32_t, 3>& dims, const FaceOctree& out, const DeformedModel& m)
    : faces(std::int32_t(out.nodes.size()))
    , nodes(out.nodes)
    , model(m)
  {
    for (int d = 0; d < 3; ++d)
      this->n[d] = dims[d] / bucket + 1;
    this->entries.resize(std::size_t(this->n[0]) * this->n[1] * this->n[2]);
    for (std::int32_t f = 0; f < this->faces; ++f)
      this->insert(f, out.nodes[f].lo, out.nodes[f].hi);
    for (std::size_t p = 0; p < out.nodeOf.size(); ++p)
      if (out.nodeOf[p] < 0)
      {
        const auto& v = m.voxel[p];
        this->insert(this->faces + std::int32_t(p), v, { v[0] + 1, v[1] + 1, v[2] + 1 });
      }
  }

  void insert(std::int32_t id,
    const std::array<std::int32_t, 3>& lo,
    const std::array<std::int32_t, 3>& hi)
  {
    this->forBuckets(lo,
      hi,
      [&](std::vector<std::int32_t>& e)
      {
        e.push_back(id);
        return false;
      });
  }

  /// Whether the box [lo, hi) overlaps the box of a face other than a and b for which
  /// `counts` holds, or the voxel of a point in no face.
  template<typename Counts>
  bool overlapsOther(const std::array<std::int32_t, 3>& lo,
    const std::array<std::int32_t, 3>& hi,
    std::int32_t a,
    std::int32_t b,
    const Counts& counts) const
  {
    return this->forBuckets(lo,
      hi,
      [&](const std::vector<std::int32_t>& e)
      {
        for (std::int32_t id : e)
        {
          if (id == a || id == b || (id < this->faces && !counts(id)))
            continue;
          std::array<std::int32_t, 3> olo, ohi;
          if (id < this->faces)
            olo = this->nodes[id].lo, ohi = this->nodes[id].hi;
          else
          {
            olo = this->model.voxel[id - this->faces];
            ohi = { olo[0] + 1, olo[1] + 1, olo[2] + 1 };
          }
          if (lo[0] < ohi[0] && olo[0] < hi[0] && lo[1] < ohi[1] && olo[1] < hi[1] &&
            lo[2] < ohi[2] && olo[2] < hi[2])
            return true;
        }
        return false;
      });
  }

private:
  std::int32_t faces;
  const std::vector<FaceNode>& nodes; ///< the faces' current boxes
  const DeformedModel& model;
  std::array<std::int32_t, 3> n{ 1, 1, 1 };
  std::vector<std::vector<std::int32_t>> entries;

  /// Calls visit on each bucket the box meets until it returns true.
  template<typename Entries, typename Visit>
  static bool visitBuckets(Entries& entries,
    const std::array<std::int32_t, 3>& n,
    const std::array<std::int32_t, 3>& lo,
    const std::array<std::int32_t, 3>& hi,
    const Visit& visit)
  {
    for (std::int32_t k = lo[2] / bucket; k <= (hi[2] - 1) / bucket; ++k)
      for (std::int32_t j = lo[1] / bucket; j <= (hi[1] - 1) / bucket; ++j)
        for (std::int32_t i = lo[0] / bucket; i <= (hi[0] - 1) / bucket; ++i)
          if (visit(entries[(std::size_t(k) * n[1] + j) * n[0] + i]))
            return true;
    return false;
  }
  template<typename Visit>
  bool forBuckets(const std::array<std::int32_t, 3>& lo,
    const std::array<std::int32_t, 3>& hi,
    const Visit& visit)
  {
    return visitBuckets(this->entries, this->n, lo, hi, visit);
  }
  template<typename Visit>
  bool forBuckets(const std::array<std::int32_t, 3>& lo,
    const std::array<std::int32_t, 3>& hi,
    const Visit& visit) const
  {
    return visitBuckets(this->entries, this->n, lo, hi, visit);
  }
};

/// The merging of adjacent face nodes (beyond the paper; see FaceOctree.h): the faces, each
/// with its points (by id), the faces next to it across a quadrilateral, and where it went.
struct FaceMerger
{
  const Compactor& cp;
  FaceOctree& out;
  std::vector<std::vector<std::int32_t>> members, neighbours;
  std::vector<std::int32_t> into; ///< per face: itself, or a face it was merged into
  BoxIndex boxes;

  std::int32_t find(std::int32_t f)
  {
    while (this->into[f] != f)
      f = this->into[f] = this->into[this->into[f]];
    return f;
  }

  FaceMerger(const Compactor& c, FaceOctree& o)
    : cp(c)
    , out(o)
    , boxes(c.model.dims, o, c.model)
  {
    const std::size_t faces = o.nodes.size();
    this->members.resize(faces);
    this->neighbours.resize(faces);
    this->into.resize(faces);
    std::iota(this->into.begin(), this->into.end(), 0);
    for (std::size_t p = 0; p < o.nodeOf.size(); ++p)
      if (o.nodeOf[p] >= 0)
        this->members[o.nodeOf[p]].push_back(std::int32_t(p));
    for (const Quad& q : c.model.quads)
      for (int r = 0; r < 4; ++r)
        for (int t = r + 1; t < 4; ++t)
        {
          const std::int32_t a = o.nodeOf[q[r]], b = o.nodeOf[q[t]];
          if (a >= 0 && b >= 0 && a != b)
            this->neighbours[a].push_back(b), this->neighbours[b].push_back(a);
        }
    for (auto& n : this->neighbours)
    {
      std::sort(n.begin(), n.end());
      n.erase(std::unique(n.begin(), n.end()), n.end());
    }
  }

  /// The faces next to s now, the best aligned with its plane first.
  std::vector<std::int32_t> candidates(std::int32_t s)
  {
    std::vector<std::int32_t> c;
    for (std::int32_t n : this->neighbours[s])
      if (this->find(n) != s)
        c.push_back(this->find(n));
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    const Vec3& m = this->out.nodes[s].normal;
    std::stable_sort(c.begin(),
      c.end(),
      [&](std::int32_t a, std::int32_t b)
      { return dot(m, this->out.nodes[a].normal) > dot(m, this->out.nodes[b].normal); });
    return c;
  }

  /// Whether the union's box overlaps another face's box, or its box grown by a voxel meets
  /// a point in no face or a face facing away (normals more than 90 degrees apart): another
  /// sheet close by, whose sewing triangles a larger projection could cross (noise, thin
  /// walls; random voxels at 85 % showed such crossings before this rule). Creases, with
  /// their faces at right angles, still merge along them.
  bool crowded(const Region& r, std::int32_t a, std::int32_t b)
  {
    auto alive = [&](std::int32_t f) { return this->into[f] == f; };
    if (this->boxes.overlapsOther(r.lo, r.hi, a, b, alive))
      return true;
    const Vec3 &na = this->out.nodes[a].normal, &nb = this->out.nodes[b].normal;
    std::array<std::int32_t, 3> lo = r.lo, hi = r.hi;
    for (int d = 0; d < 3; ++d)
      lo[d] = std::max(0, lo[d] - 1), hi[d] = std::min(this->cp.model.dims[d], hi[d] + 1);
    return this->boxes.overlapsOther(lo,
      hi,
      a,
      b,
      [&](std::int32_t f)
      {
        const Vec3& m = this->out.nodes[f].normal;
        return alive(f) && (dot(m, na) < 0 || dot(m, nb) < 0);
      });
  }

  /// Merges face b into face a if one plane fits both (the rules of the octree's nodes).
  bool tryMerge(std::int32_t a, std::int32_t b)
  {
    const FaceNode &na = this->out.nodes[a], &nb = this->out.nodes[b];
    if (dot(na.normal, nb.normal) < this->cp.options.minimumCosine)
      return false;
    std::vector<std::int32_t> points;
    points.reserve(this->members[a].size() + this->members[b].size());
    std::merge(this->members[a].begin(),
      this->members[a].end(),
      this->members[b].begin(),
      this->members[b].end(),
      std::back_inserter(points));
    Region r;
    r.first = points.data();
    r.size = points.size();
    r.level = std::max(na.level, nb.level);
    for (int d = 0; d < 3; ++d)
      r.lo[d] = std::min(na.lo[d], nb.lo[d]), r.hi[d] = std::max(na.hi[d], nb.hi[d]);
    r.faceOf = this->out.nodeOf.data();
    r.a = a;
    r.b = b;
    if (this->crowded(r, a, b))
      return false;
    NodeFit f = this->cp.fit(r);
    if (!f.ok)
      return false;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      this->out.nodeOf[points[i]] = a;
      this->out.projected[points[i]] = f.projected[i];
    }
    this->out.nodes[a] = std::move(f.node);
    this->members[a] = std::move(points);
    this->members[b].clear();
    this->neighbours[a].insert(
      this->neighbours[a].end(), this->neighbours[b].begin(), this->neighbours[b].end());
    this->into[b] = a;
    this->boxes.insert(a, this->out.nodes[a].lo, this->out.nodes[a].hi);
    return true;
  }

  /// Grows face s over its neighbours, in rounds, until a round merges none. Each attempt
  /// refits a plane to both faces' points, so a large face's growth alone can be long: the
  /// poll counts attempts. False when the caller asked to stop.
  bool grow(std::int32_t s, ProgressPoll& poll)
  {
    for (bool grew = true; grew;)
    {
      grew = false;
      for (std::int32_t n : this->candidates(s))
      {
        if (!poll.tick())
          return false;
        grew = this->tryMerge(s, n) || grew;
      }
    }
    return true;
  }
};

/// Merges adjacent face nodes greedily (the largest first) and renumbers the faces in the
/// order of their first point.
void mergeFaceNodes(const Compactor& cp, const Execution& exec, FaceOctree& out)
{
  FaceMerger m(cp, out);
  std::vector<std::int32_t> order(out.nodes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::int32_t a, std::int32_t b) { return m.members[a].size() > m.members[b].size(); });
  ProgressPoll poll(exec, 0.0, 1.0, 4);
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    poll.at(double(i) / double(order.size()));
    if (m.find(order[i]) == order[i] && !m.grow(order[i], poll))
      break;
  }
  keepTerminalNodes(out);
}

FaceOctree compactFaceOctree(const BitVolume& far,
  const BitVolume* object,
  const DeformedModel& model,
  const FaceOctreeOptions& options,
  const Execution& exec);

} // namespace

FaceOctree buildFaceOctree(const BitVolume& object,
  const DeformedModel& model,
  const FaceOctreeOptions& options,
  const Execution& exec)
{
  return compactFaceOctree(
    farVoxels(object, exec), options.keepPointsInVoxels ? nullptr : &object, model, options, exec);
}

FaceOctree buildFaceOctreeAvoiding(const BitVolume& far,
  const DeformedModel& model,
  const FaceOctreeOptions& options,
  const Execution& exec)
{
  return compactFaceOctree(far, nullptr, model, options, exec);
}

namespace
{

FaceOctree compactFaceOctree(const BitVolume& far,
  const BitVolume* object,
  const DeformedModel& model,
  const FaceOctreeOptions& options,
  const Execution& exec)
{
  Compactor cp{ far, model, options, object, {}, {} };
  if (options.precision > 0)
    cp.precision = options.precision;
  const std::size_t np = model.pointCount();
  cp.codes.resize(np);
  for (std::size_t p = 0; p < np; ++p)
    cp.codes[p] = mortonOf(model.voxel[p]);
  cp.order.resize(np);
  std::iota(cp.order.begin(), cp.order.end(), 0);
  std::sort(cp.order.begin(),
    cp.order.end(),
    [&](std::int32_t a, std::int32_t b) { return cp.codes[a] < cp.codes[b]; });

  FaceOctree out;
  out.projected = model.position;
  cp.current = &out.projected;
  out.nodeOf.assign(np, -1);
  std::vector<int> faceLevel(np, -1);
  if (!cp.object)
    voxelFaceNodes(model, out, faceLevel);
  // Progress: the levels take the first part (the lower levels, with the most candidates,
  // the most time), the merging, when asked, the rest (about as long as the compaction).
  const bool merging = options.mergeFaceNodes && options.maximumLevel > 0;
  const double compaction = merging ? 0.5 : 1.0;
  const int levels = std::min(options.maximumLevel, 20);
  if (cp.object)
    compactFromAbove(cp, std::min(levels, topLevel(model.dims)), exec, compaction, out, faceLevel);
  else
    for (int level = 1; level <= levels; ++level)
      if (exec.stopRequested() || !exec.report(compaction * (level - 1) / levels) ||
        !compactLevel(cp, level, exec, out, faceLevel))
        break;
  keepTerminalNodes(out);
  if (merging && !exec.stopRequested())
    mergeFaceNodes(cp, exec.within(compaction, 1.0), out);
  return out;
}

} // namespace

} // namespace vbr
