// The face octree boundary (DeformedModel, FaceOctree, FaceOctreeBoundary) against
// independent references: brute-force quadrilateral sets, plane checks voxel by voxel, mesh
// topology from the cells alone, CGAL's exact self-intersection test, and distances to the
// surfels computed here by a separate bucketed search.
#include "BoundarySimplifier.h"
#include "BruteForce.h"
#include "DeformedModel.h"
#include "FaceOctree.h"
#include "FaceOctreeBoundary.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>

namespace
{
using vbr::BitVolume;
using vbr::Vec3;
using Int3 = std::array<std::int32_t, 3>;

vbr::Execution sequential;

BitVolume sample(const Int3& n, const std::function<bool(double, double, double)>& inside)
{
  BitVolume v(n[0], n[1], n[2]);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        if (inside(i + 0.5, j + 0.5, k + 0.5))
          v.set(i, j, k);
  return v;
}

bool at(const BitVolume& v, int i, int j, int k)
{
  return i >= 0 && j >= 0 && k >= 0 && i < v.size(0) && j < v.size(1) && k < v.size(2) &&
    v.get(i, j, k);
}

// ---- Shapes (voxel-centre predicates on an n^3 grid, scaled to the grid) ----

struct Shape
{
  std::string name;
  std::function<bool(double, double, double)> inside; // in [0, 1]^3
};

std::vector<Shape> solids()
{
  auto sq = [](double x) { return x * x; };
  std::vector<Shape> s;
  s.push_back({ "ball",
    [=](double x, double y, double z) { return sq(x - .5) + sq(y - .5) + sq(z - .5) < sq(.38); } });
  s.push_back({ "torus",
    [=](double x, double y, double z)
    {
      const double r = std::sqrt(sq(x - .5) + sq(y - .5)) - .27;
      return sq(r) + sq(z - .5) < sq(.13);
    } });
  s.push_back({ "chamferedCube",
    [=](double x, double y, double z)
    {
      const double a = std::abs(x - .5), b = std::abs(y - .5), c = std::abs(z - .5);
      return a < .33 && b < .33 && c < .33 && a + b < .55 && b + c < .55 && a + c < .55;
    } });
  s.push_back({ "rotatedCube",
    [=](double x, double y, double z)
    {
      const double cz = std::cos(.5), sz = std::sin(.5), cx = std::cos(.3), sx = std::sin(.3);
      const double u = (x - .5) * cz - (y - .5) * sz, v0 = (x - .5) * sz + (y - .5) * cz;
      const double v = v0 * cx - (z - .5) * sx, w = v0 * sx + (z - .5) * cx;
      return std::abs(u) < .27 && std::abs(v) < .27 && std::abs(w) < .27;
    } });
  s.push_back({ "csg",
    [=](double x, double y, double z)
    {
      const bool box = std::abs(x - .45) < .3 && std::abs(y - .5) < .2 && std::abs(z - .5) < .3;
      const bool cylinder = sq(x - .7) + sq(y - .5) < sq(.18) && std::abs(z - .5) < .4;
      const bool hole = sq(x - .35) + sq(y - .5) + sq(z - .8) < sq(.2);
      const bool drill = sq(y - .5) + sq(z - .4) < sq(.08) && x < .5;
      return (box || cylinder) && !hole && !drill;
    } });
  return s;
}

/// Random porous blob: a smoothed random field thresholded inside a ball.
BitVolume porous(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> centres;
  for (int i = 0; i < 40; ++i)
    centres.push_back({ u(rng) * n, u(rng) * n, u(rng) * n });
  return sample({ n, n, n },
    [&](double x, double y, double z)
    {
      const double c = 0.5 * n, r2 = (x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c);
      if (r2 > 0.16 * n * n)
        return false;
      for (const Vec3& p : centres)
      {
        const double d2 =
          (x - p[0]) * (x - p[0]) + (y - p[1]) * (y - p[1]) + (z - p[2]) * (z - p[2]);
        if (d2 < 0.012 * n * n)
          return false;
      }
      return true;
    });
}

BitVolume shapeVolume(const Shape& s, int n)
{
  return sample(
    { n, n, n }, [&](double x, double y, double z) { return s.inside(x / n, y / n, z / n); });
}

// ---- Independent references ----

bool interiorVertex(const BitVolume& v, int i, int j, int k)
{
  for (int c = 0; c < 8; ++c)
    if (!at(v, i - 1 + (c & 1), j - 1 + ((c >> 1) & 1), k - 1 + (c >> 2)))
      return false;
  return true;
}

/// Voxel quadruples (sorted) around grid edges with exactly one interior end.
std::set<std::array<Int3, 4>> expectedQuads(const BitVolume& v)
{
  std::set<std::array<Int3, 4>> out;
  for (int k = 0; k <= v.size(2); ++k)
    for (int j = 0; j <= v.size(1); ++j)
      for (int i = 0; i <= v.size(0); ++i)
        for (int a = 0; a < 3; ++a)
        {
          Int3 e{ i, j, k };
          e[a] += 1;
          if (interiorVertex(v, i, j, k) == interiorVertex(v, e[0], e[1], e[2]))
            continue;
          std::array<Int3, 4> q;
          for (int r = 0; r < 4; ++r)
          {
            q[r] = { i, j, k };
            q[r][(a + 1) % 3] -= r & 1;
            q[r][(a + 2) % 3] -= r >> 1;
          }
          std::sort(q.begin(), q.end());
          out.insert(q);
        }
  return out;
}

/// Boundary voxels (a background 26-neighbour) and those without an interior corner.
void expectedCounts(const BitVolume& v, std::size_t& boundary, std::size_t& pruned)
{
  boundary = pruned = 0;
  for (int k = 0; k < v.size(2); ++k)
    for (int j = 0; j < v.size(1); ++j)
      for (int i = 0; i < v.size(0); ++i)
      {
        if (!v.get(i, j, k))
          continue;
        bool b = false, corner = false;
        for (int d = 0; d < 27; ++d)
          b = b || !at(v, i + d % 3 - 1, j + (d / 3) % 3 - 1, k + d / 9 - 1);
        for (int c = 0; c < 8; ++c)
          corner = corner || interiorVertex(v, i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2));
        boundary += b;
        pruned += b && !corner;
      }
}

struct Mesh
{
  std::vector<Vec3> points;
  std::vector<std::vector<int>> cells;
};

Mesh meshOf(const vbr::BoundaryMesh& m)
{
  Mesh out;
  out.points = m.points;
  for (std::size_t c = 0; c + 1 < m.offsets.size(); ++c)
    out.cells.emplace_back(
      m.connectivity.begin() + m.offsets[c], m.connectivity.begin() + m.offsets[c + 1]);
  return out;
}

/// Closed, manifold, consistently oriented: every directed edge once, its reverse once, and
/// the cells around each vertex one cycle. Returns the Euler characteristic.
long long checkClosedManifold(const Mesh& m, std::string& error)
{
  std::map<std::pair<int, int>, int> directed;
  for (const auto& c : m.cells)
    for (std::size_t i = 0; i < c.size(); ++i)
      ++directed[{ c[i], c[(i + 1) % c.size()] }];
  for (const auto& e : directed)
  {
    if (e.second != 1 || !directed.count({ e.first.second, e.first.first }))
    {
      error = "edge " + std::to_string(e.first.first) + "-" + std::to_string(e.first.second) +
        " used " + std::to_string(e.second) + " times or not reversed";
      return 0;
    }
  }
  // Vertex links: successor map per vertex (next of the incoming edge in the cell) is one cycle.
  std::vector<std::map<int, int>> fan(m.points.size());
  std::vector<std::size_t> used(m.points.size(), 0);
  for (const auto& c : m.cells)
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      const int p = c[i], prev = c[(i + c.size() - 1) % c.size()], next = c[(i + 1) % c.size()];
      fan[p][next] = prev;
      ++used[p];
    }
  for (std::size_t p = 0; p < m.points.size(); ++p)
  {
    if (fan[p].empty())
      continue;
    int start = fan[p].begin()->first, x = start;
    std::size_t steps = 0;
    do
    {
      auto it = fan[p].find(x);
      if (it == fan[p].end())
        break;
      x = it->second;
      ++steps;
    } while (x != start && steps <= used[p]);
    if (x != start || steps != used[p])
    {
      error = "non-manifold vertex " + std::to_string(p);
      return 0;
    }
  }
  long long pointsUsed = 0;
  for (std::size_t p = 0; p < m.points.size(); ++p)
    pointsUsed += used[p] > 0;
  return pointsUsed - (long long)directed.size() / 2 + (long long)m.cells.size();
}

Vec3 newellNormal(const Mesh& m, const std::vector<int>& c)
{
  Vec3 n{ 0, 0, 0 };
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const Vec3& a = m.points[c[i]];
    const Vec3& b = m.points[c[(i + 1) % c.size()]];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n)
    x /= l;
  return n;
}

/// Largest distance of a cell's points to the plane of its Newell normal through its
/// centroid, and whether its fan from the first point turns one way (drawn right).
double planarity(const Mesh& m, const std::vector<int>& c, bool& fanRight)
{
  const Vec3 n = newellNormal(m, c);
  Vec3 o{ 0, 0, 0 };
  for (int p : c)
    for (int d = 0; d < 3; ++d)
      o[d] += m.points[p][d] / c.size();
  double worst = 0;
  for (int p : c)
    worst = std::max(worst,
      std::abs((m.points[p][0] - o[0]) * n[0] + (m.points[p][1] - o[1]) * n[1] +
        (m.points[p][2] - o[2]) * n[2]));
  fanRight = true;
  const Vec3& a = m.points[c[0]];
  for (std::size_t i = 1; i + 1 < c.size(); ++i)
  {
    const Vec3& b = m.points[c[i]];
    const Vec3& d = m.points[c[i + 1]];
    const Vec3 u{ b[0] - a[0], b[1] - a[1], b[2] - a[2] },
      v{ d[0] - a[0], d[1] - a[1], d[2] - a[2] };
    const double s = (u[1] * v[2] - u[2] * v[1]) * n[0] + (u[2] * v[0] - u[0] * v[2]) * n[1] +
      (u[0] * v[1] - u[1] * v[0]) * n[2];
    fanRight = fanRight && s >= -1e-7;
  }
  return worst;
}

/// Enclosed volume (divergence theorem over the fans of the cells).
double enclosedVolume(const Mesh& m)
{
  double v = 0;
  for (const auto& c : m.cells)
    for (std::size_t i = 1; i + 1 < c.size(); ++i)
    {
      const Vec3 &a = m.points[c[0]], &b = m.points[c[i]], &d = m.points[c[i + 1]];
      v += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
             a[2] * (b[0] * d[1] - b[1] * d[0])) /
        6.0;
    }
  return v;
}

bool selfIntersects(const Mesh& m, const std::vector<std::int32_t>* node = nullptr)
{
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  CGAL::Surface_mesh<K::Point_3> sm;
  std::vector<CGAL::Surface_mesh<K::Point_3>::Vertex_index> vi;
  for (const Vec3& p : m.points)
    vi.push_back(sm.add_vertex(K::Point_3(p[0], p[1], p[2])));
  std::vector<int> cellOf;
  for (std::size_t ci = 0; ci < m.cells.size(); ++ci)
  {
    const auto& c = m.cells[ci];
    for (std::size_t i = 1; i + 1 < c.size(); ++i)
    {
      // A flat fan triangle (its apex in line with an edge) covers nothing: left out.
      const Vec3 &a = m.points[c[0]], &b = m.points[c[i]], &d = m.points[c[i + 1]];
      const Vec3 u{ b[0] - a[0], b[1] - a[1], b[2] - a[2] },
        v{ d[0] - a[0], d[1] - a[1], d[2] - a[2] };
      const double area2 = std::pow(u[1] * v[2] - u[2] * v[1], 2) +
        std::pow(u[2] * v[0] - u[0] * v[2], 2) + std::pow(u[0] * v[1] - u[1] * v[0], 2);
      if (c.size() > 3 && area2 < 1e-24)
        continue;
      sm.add_face(vi[c[0]], vi[c[i]], vi[c[i + 1]]);
      cellOf.push_back(int(ci));
    }
  }
  const bool found = CGAL::Polygon_mesh_processing::does_self_intersect(sm);
  if (found && node)
  {
    using Face = CGAL::Surface_mesh<K::Point_3>::Face_index;
    std::vector<std::pair<Face, Face>> pairs;
    CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
    for (std::size_t i = 0; i < std::min<std::size_t>(pairs.size(), 4); ++i)
    {
      const int a = cellOf[pairs[i].first], b = cellOf[pairs[i].second];
      std::cout << "  cells " << a << " (node " << (*node)[a] << ", " << m.cells[a].size()
                << " points) and " << b << " (node " << (*node)[b] << ", " << m.cells[b].size()
                << " points) near " << m.points[m.cells[a][0]][0] << " "
                << m.points[m.cells[a][0]][1] << " " << m.points[m.cells[a][0]][2] << "\n";
      for (int cell : { a, b })
      {
        std::cout << "    ";
        for (int p : m.cells[cell])
          std::cout << p << " (" << m.points[p][0] << " " << m.points[p][1] << " " << m.points[p][2]
                    << ") ";
        std::cout << "\n";
      }
    }
    std::cout << "  " << pairs.size() << " intersecting pairs\n";
  }
  return found;
}

/// Surfels: unit squares between an object voxel and a background one, as (voxel, axis, side).
struct Surfel
{
  Int3 voxel;
  int axis, side;
};

std::vector<Surfel> surfels(const BitVolume& v)
{
  std::vector<Surfel> out;
  for (int k = 0; k < v.size(2); ++k)
    for (int j = 0; j < v.size(1); ++j)
      for (int i = 0; i < v.size(0); ++i)
        if (v.get(i, j, k))
          for (int a = 0; a < 3; ++a)
            for (int s = 0; s < 2; ++s)
            {
              Int3 w{ i, j, k };
              w[a] += s ? 1 : -1;
              if (!at(v, w[0], w[1], w[2]))
                out.push_back({ { i, j, k }, a, s });
            }
  return out;
}

double pointSquareDistance(const Vec3& p, const Surfel& s)
{
  double d2 = 0;
  for (int d = 0; d < 3; ++d)
  {
    const double lo = s.voxel[d] + (d == s.axis ? s.side : 0);
    const double hi = s.voxel[d] + (d == s.axis ? s.side : 1);
    const double e = std::max({ lo - p[d], 0.0, p[d] - hi });
    d2 += e * e;
  }
  return std::sqrt(d2);
}

Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  // Ericson, Real-Time Collision Detection, 5.1.5.
  auto sub = [](const Vec3& x, const Vec3& y) {
    return Vec3{ x[0] - y[0], x[1] - y[1], x[2] - y[2] };
  };
  auto dot = [](const Vec3& x, const Vec3& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  auto lerp = [](const Vec3& x, const Vec3& d, double t) {
    return Vec3{ x[0] + t * d[0], x[1] + t * d[1], x[2] + t * d[2] };
  };
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
    return a;
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
    return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return lerp(a, ab, d1 / (d1 - d3));
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
    return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return lerp(a, ac, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return lerp(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double den = 1 / (va + vb + vc);
  const double v = vb * den, w = vc * den;
  return {
    a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w
  };
}

/// Two-sided Hausdorff distance between the mesh and the surfels, by samples on both (the
/// mesh: its vertices, edge points and interior points at 1/8 voxel or finer; the surfels:
/// a 5 x 5 lattice each), each searched in buckets of 4 voxels. Surfels of `excluded`
/// voxels (the pruned ones) are skipped on the surfel side.
void hausdorff(const Mesh& m,
  const BitVolume& v,
  const std::set<Int3>& excluded,
  double& meshToSurfels,
  double& surfelsToMesh)
{
  const int B = 2;
  auto bucket = [&](const Vec3& p) {
    return Int3{ int(std::floor(p[0] / B)), int(std::floor(p[1] / B)), int(std::floor(p[2] / B)) };
  };
  std::map<Int3, std::vector<Surfel>> sb;
  const auto all = surfels(v);
  for (const Surfel& s : all)
    sb[bucket({ s.voxel[0] + .5, s.voxel[1] + .5, s.voxel[2] + .5 })].push_back(s);
  std::vector<std::array<Vec3, 3>> tris;
  for (const auto& c : m.cells)
    for (std::size_t i = 1; i + 1 < c.size(); ++i)
      tris.push_back({ m.points[c[0]], m.points[c[i]], m.points[c[i + 1]] });
  std::map<Int3, std::vector<int>> tb;
  for (std::size_t t = 0; t < tris.size(); ++t)
  {
    Int3 lo = bucket(tris[t][0]), hi = lo;
    for (int r = 1; r < 3; ++r)
    {
      const Int3 b = bucket(tris[t][r]);
      for (int d = 0; d < 3; ++d)
        lo[d] = std::min(lo[d], b[d]), hi[d] = std::max(hi[d], b[d]);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          tb[{ x, y, z }].push_back(int(t));
  }
  meshToSurfels = 0;
  for (const auto& t : tris)
  {
    const int steps = 4 *
      int(std::ceil(std::max(
        { std::abs(t[1][0] - t[0][0]) + std::abs(t[1][1] - t[0][1]) + std::abs(t[1][2] - t[0][2]),
          std::abs(t[2][0] - t[0][0]) + std::abs(t[2][1] - t[0][1]) + std::abs(t[2][2] - t[0][2]),
          1.0 })));
    for (int a = 0; a <= steps; ++a)
      for (int b = 0; a + b <= steps; ++b)
      {
        const double u = double(a) / steps, w = double(b) / steps;
        const Vec3 p{ t[0][0] + u * (t[1][0] - t[0][0]) + w * (t[2][0] - t[0][0]),
          t[0][1] + u * (t[1][1] - t[0][1]) + w * (t[2][1] - t[0][1]),
          t[0][2] + u * (t[1][2] - t[0][2]) + w * (t[2][2] - t[0][2]) };
        const Int3 c = bucket(p);
        double best = 1e9;
        // A sample no farther than the largest so far cannot change the maximum.
        for (int d = 0; d < 27 && best > meshToSurfels; ++d)
        {
          auto it = sb.find({ c[0] + d % 3 - 1, c[1] + (d / 3) % 3 - 1, c[2] + d / 9 - 1 });
          if (it != sb.end())
            for (const Surfel& s : it->second)
              best = std::min(best, pointSquareDistance(p, s));
        }
        meshToSurfels = std::max(meshToSurfels, best);
      }
  }
  surfelsToMesh = 0;
  for (const Surfel& s : all)
  {
    if (excluded.count(s.voxel))
      continue;
    for (int a = 0; a <= 4; ++a)
      for (int b = 0; b <= 4; ++b)
      {
        Vec3 p{ double(s.voxel[0]), double(s.voxel[1]), double(s.voxel[2]) };
        p[s.axis] += s.side;
        p[(s.axis + 1) % 3] += a / 4.0;
        p[(s.axis + 2) % 3] += b / 4.0;
        const Int3 c = bucket(p);
        double best = 1e9;
        for (int d = 0; d < 27 && best > surfelsToMesh; ++d)
        {
          auto it = tb.find({ c[0] + d % 3 - 1, c[1] + (d / 3) % 3 - 1, c[2] + d / 9 - 1 });
          if (it == tb.end())
            continue;
          for (std::size_t i = 0; i < it->second.size() && best > surfelsToMesh; ++i)
          {
            const int t = it->second[i];
            const Vec3 q = closestOnTriangle(p, tris[t][0], tris[t][1], tris[t][2]);
            best = std::min(best,
              std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                (p[2] - q[2]) * (p[2] - q[2])));
          }
        }
        surfelsToMesh = std::max(surfelsToMesh, best);
      }
  }
}

/// Euler characteristic of the union of the closed voxels (cubical complex, brute force).
long long solidEuler(const BitVolume& v)
{
  std::set<std::array<int, 4>> cells[4]; // by dimension: doubled coordinates of the centres
  for (int k = 0; k < v.size(2); ++k)
    for (int j = 0; j < v.size(1); ++j)
      for (int i = 0; i < v.size(0); ++i)
        if (v.get(i, j, k))
          for (int c = 0; c < 27; ++c)
          {
            const int dx = c % 3, dy = (c / 3) % 3, dz = c / 9;
            const int dim = (dx == 1) + (dy == 1) + (dz == 1);
            cells[dim].insert({ 2 * i + dx, 2 * j + dy, 2 * k + dz, 0 });
          }
  return (long long)cells[0].size() - cells[1].size() + cells[2].size() - cells[3].size();
}

std::set<Int3> prunedVoxelSet(const BitVolume& v)
{
  std::set<Int3> out;
  for (int k = 0; k < v.size(2); ++k)
    for (int j = 0; j < v.size(1); ++j)
      for (int i = 0; i < v.size(0); ++i)
      {
        if (!v.get(i, j, k))
          continue;
        bool corner = false;
        for (int c = 0; c < 8; ++c)
          corner = corner || interiorVertex(v, i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2));
        if (!corner)
          out.insert({ i, j, k });
      }
  return out;
}

struct Result
{
  vbr::DeformedModel model;
  vbr::FaceOctree octree;
  vbr::BoundaryMesh mesh;
};

/// Whether run() merges adjacent face nodes (the boundary checks run with merging).
bool mergeFaceNodes = true;
/// Whether run() keeps the paper's rule (planes meet every point's voxel), and the
/// precision it asks for (0: the default).
bool keepPointsInVoxels = false;
double precision = 0.0;

Result run(const BitVolume& v,
  vbr::BoundaryCells cells,
  const vbr::Execution& exec = sequential,
  int maximumLevel = 10)
{
  Result r;
  r.model = vbr::buildDeformedModel(v, {}, exec);
  vbr::FaceOctreeOptions o;
  o.maximumLevel = maximumLevel;
  o.mergeFaceNodes = mergeFaceNodes;
  o.keepPointsInVoxels = keepPointsInVoxels;
  if (precision > 0)
    o.precision = precision;
  r.octree = vbr::buildFaceOctree(v, r.model, o, exec);
  r.mesh = vbr::assembleBoundary(r.model, r.octree, cells);
  return r;
}

/// The checks of the polygons: planar, drawn right, on their node's plane, enclosing about
/// the voxels' volume, within a voxel diagonal of the surfels both ways.
void checkPolygons(const std::string& name, const BitVolume& v, const Result& r, const Mesh& m)
{
  double worstPlanarity = 0;
  for (std::size_t c = 0; c < m.cells.size(); ++c)
  {
    bool fanRight = true;
    double flatness = m.cells[c].size() > 3 ? planarity(m, m.cells[c], fanRight) : 0.0;
    // A long, thin convex piece of a large (merged) face has an ill-conditioned Newell
    // normal: its node's plane is a second witness of planarity (any plane that close will do).
    if (r.mesh.faceNode[c] >= 0 && flatness > 0)
    {
      const auto& node = r.octree.nodes[r.mesh.faceNode[c]];
      double worst = 0;
      for (int p : m.cells[c])
        worst = std::max(worst,
          std::abs(node.normal[0] * m.points[p][0] + node.normal[1] * m.points[p][1] +
            node.normal[2] * m.points[p][2] - node.offset));
      flatness = std::min(flatness, worst);
    }
    EXPECT_LT(flatness, 1e-9) << "cell " << c << " of " << m.cells[c].size() << " points, node "
                              << r.mesh.faceNode[c];
    worstPlanarity = std::max(worstPlanarity, flatness);
    ASSERT_TRUE(fanRight) << "cell " << c << " of " << m.cells[c].size() << " points, node "
                          << r.mesh.faceNode[c] << ", first " << m.points[m.cells[c][0]][0] << " "
                          << m.points[m.cells[c][0]][1] << " " << m.points[m.cells[c][0]][2]
                          << ", second " << m.points[m.cells[c][1]][0] << " "
                          << m.points[m.cells[c][1]][1] << " " << m.points[m.cells[c][1]][2]
                          << ", third " << m.points[m.cells[c][2]][0] << " "
                          << m.points[m.cells[c][2]][1] << " " << m.points[m.cells[c][2]][2];
  }
  EXPECT_LT(worstPlanarity, 1e-9);
  // Every polygon lies on its face node's plane.
  for (std::size_t c = 0; c < m.cells.size(); ++c)
  {
    const int id = r.mesh.faceNode[c];
    if (id < 0)
      continue;
    const auto& node = r.octree.nodes[id];
    for (int p : m.cells[c])
    {
      const Vec3& x = m.points[p];
      ASSERT_NEAR(
        node.normal[0] * x[0] + node.normal[1] * x[1] + node.normal[2] * x[2], node.offset, 1e-9)
        << "cell " << c << " node " << id << " level " << node.level;
    }
  }
  // Outwards and close to the voxels' volume: the surface runs through the boundary
  // voxels, on average about half a voxel inside the surfels.
  const double volume = enclosedVolume(m), voxels = double(v.count());
  const double area = double(surfels(v).size());
  EXPECT_GT(volume, 0);
  EXPECT_LT(std::abs(volume - voxels), 0.75 * area) << volume << " vs " << voxels;
  double there = 0, back = 0;
  hausdorff(m, v, prunedVoxelSet(v), there, back);
  EXPECT_LE(there, std::sqrt(3.0) + 1e-9);
  EXPECT_LE(back, std::sqrt(3.0) + 1e-9);
  EXPECT_LE(vbr::maximumDistanceToSurfels(v, r.mesh.points), std::sqrt(3.0) + 1e-9);
  std::cout << name << ": " << r.model.pointCount() << " points, " << r.octree.nodes.size()
            << " face nodes, " << m.cells.size() << " cells (" << r.mesh.polygons
            << " polygons), volume " << volume << " / " << voxels << ", Hausdorff " << there
            << " / " << back << ", " << r.model.iterationsRun << " iterations\n";
}

/// Per face node, the area of its cells; and the sewing triangles as model points (each
/// from its smallest, orientation kept).
void surfaceOf(const vbr::BoundaryMesh& r,
  std::map<int, double>& nodeArea,
  std::set<std::array<int, 3>>& sewing)
{
  const Mesh m = meshOf(r);
  for (std::size_t c = 0; c < m.cells.size(); ++c)
  {
    const auto& cell = m.cells[c];
    if (r.faceNode[c] < 0)
    {
      std::array<int, 3> t{ r.pointOf[cell[0]], r.pointOf[cell[1]], r.pointOf[cell[2]] };
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      sewing.insert(t);
      continue;
    }
    Vec3 n{ 0, 0, 0 };
    for (std::size_t i = 0; i < cell.size(); ++i)
    {
      const Vec3& a = m.points[cell[i]];
      const Vec3& b = m.points[cell[(i + 1) % cell.size()]];
      n[0] += (a[1] - b[1]) * (a[2] + b[2]);
      n[1] += (a[2] - b[2]) * (a[0] + b[0]);
      n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    nodeArea[r.faceNode[c]] += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
}

/// Every check of the boundary of one solid. The polygons and their cut into triangles are
/// the same surface (same sewing triangles, same area per node); CGAL checks the triangles:
/// a polygon's fan has flat triangles wherever its corners run straight (points clamped to a
/// face of their voxel box line up), and CGAL takes a flat triangle for an intersection, a
/// dropped one for a crack.
void checkBoundary(const std::string& name, const BitVolume& v, bool expectTopology)
{
  SCOPED_TRACE(name);
  std::map<int, double> polygonArea, triangleArea;
  std::set<std::array<int, 3>> polygonSewing, triangleSewing;
  const long long expectedEuler = expectTopology ? 2 * solidEuler(v) : 0;
  for (auto cells : { vbr::BoundaryCells::Polygons, vbr::BoundaryCells::Triangles })
  {
    const bool polygons = cells == vbr::BoundaryCells::Polygons;
    const Result r = run(v, cells);
    const Mesh m = meshOf(r.mesh);
    ASSERT_FALSE(m.cells.empty());
    std::string error;
    const long long euler = checkClosedManifold(m, error);
    ASSERT_TRUE(error.empty()) << error;
    if (expectTopology)
      EXPECT_EQ(euler, expectedEuler);
    surfaceOf(
      r.mesh, polygons ? polygonArea : triangleArea, polygons ? polygonSewing : triangleSewing);
    if (polygons)
      checkPolygons(name, v, r, m);
    else
    {
      for (const auto& c : m.cells)
        ASSERT_EQ(c.size(), 3u);
      EXPECT_FALSE(selfIntersects(m, &r.mesh.faceNode));
    }
  }
  EXPECT_TRUE(polygonSewing == triangleSewing);
  ASSERT_EQ(polygonArea.size(), triangleArea.size());
  for (const auto& [node, area] : polygonArea)
    EXPECT_NEAR(triangleArea[node], area, 1e-9 * (1 + area)) << "node " << node;
}

/// The Triangles boundary of a Result as a plain surface.
vbr::TriangleSurface triangleSurface(const Result& r)
{
  vbr::TriangleSurface in;
  in.points = r.mesh.points;
  for (std::size_t c = 0; c < r.mesh.cellCount(); ++c)
    in.triangles.push_back({ r.mesh.connectivity[r.mesh.offsets[c]],
      r.mesh.connectivity[r.mesh.offsets[c] + 1],
      r.mesh.connectivity[r.mesh.offsets[c] + 2] });
  return in;
}

Mesh meshOf(const vbr::TriangleSurface& s)
{
  Mesh m;
  m.points = s.points;
  for (const auto& t : s.triangles)
    m.cells.push_back({ t[0], t[1], t[2] });
  return m;
}

/// The simplified boundary of one object (Triangles cut, then BoundarySimplifier) against the
/// references: closed and manifold with the voxels' Euler characteristic (when expected), no
/// self-intersection (CGAL), within the bound both ways (the surfels of pruned voxels
/// excepted; where the input itself is farther from the surfels, no farther than it plus the
/// half diagonal of the smallest surfel piece), the reported distances upper bounds of the
/// measured ones, and at least `fewer` times fewer triangles than its input.
vbr::SimplifiedSurface checkSimplified(const std::string& name,
  const BitVolume& v,
  bool expectTopology,
  double fewer,
  double bound = std::sqrt(3.0),
  const vbr::Execution& exec = vbr::Execution(),
  int regions = vbr::SimplifyOptions().regions)
{
  SCOPED_TRACE(name);
  const vbr::TriangleSurface in = triangleSurface(run(v, vbr::BoundaryCells::Triangles));
  vbr::SimplifyOptions options;
  options.distance = bound;
  options.regions = regions;
  const auto start = std::chrono::steady_clock::now();
  const vbr::SimplifiedSurface out = vbr::simplifyBoundary(v, in, options, exec);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(out.simplified);
  if (!out.simplified)
    return out;
  const Mesh m = meshOf(out.surface);
  std::string error;
  const long long euler = checkClosedManifold(m, error);
  EXPECT_TRUE(error.empty()) << error;
  if (!error.empty())
    return out;
  if (expectTopology)
    EXPECT_EQ(euler, 2 * solidEuler(v));
  EXPECT_FALSE(selfIntersects(m));
  EXPECT_GT(enclosedVolume(m), 0);
  const std::set<Int3> pruned = prunedVoxelSet(v);
  double there = 0, back = 0, inThere = 0, inBack = 0;
  hausdorff(m, v, pruned, there, back);
  hausdorff(meshOf(in), v, pruned, inThere, inBack);
  EXPECT_LE(there, bound + 1e-9);
  EXPECT_LE(back, std::max(bound, inBack + 0.125 * std::sqrt(0.5)) + 1e-9);
  EXPECT_LE(there, out.surfaceDistance + 1e-9); // the reported distances are upper bounds
  EXPECT_LE(back, out.surfelDistance + 1e-9);
  EXPECT_LE(out.surfaceDistance, there + 0.1); // and close ones
  EXPECT_LE(double(out.surface.triangles.size()) * fewer, double(in.triangles.size()));
  std::cout << name << ": " << in.triangles.size() << " -> " << out.surface.triangles.size()
            << " triangles, Hausdorff " << there << " / " << back << " (input " << inThere << " / "
            << inBack << ", reported " << out.surfaceDistance << " / " << out.surfelDistance
            << "), " << seconds << " s\n";
  return out;
}

} // namespace

TEST(FaceOctreeBoundarySimplifier, SolidsAt32)
{
  for (const Shape& s : solids())
    checkSimplified(s.name + "32", shapeVolume(s, 32), true, 20);
}

TEST(FaceOctreeBoundarySimplifier, RoundSolidsAndCSGAt64)
{
  for (const Shape& s : solids())
    if (s.name == "ball" || s.name == "torus" || s.name == "csg")
      checkSimplified(s.name + "64", shapeVolume(s, 64), true, 50);
}

TEST(FaceOctreeBoundarySimplifier, PorousBlobs)
{
  for (unsigned seed : { 1u, 2u })
    checkSimplified("porous" + std::to_string(seed), porous(48, seed), false, 20);
}

/// The regions of the first phase (BoundarySimplifier.cxx) give the same surface on one thread
/// and on two or three (the regions run concurrently), and it passes the independent checks
/// (closed, manifold, the voxels' Euler characteristic, CGAL's self-intersection test, the
/// brute-force Hausdorff distance both ways within the bound); one region (a single loop)
/// passes them too. Each input has more triangles than the simplifier cuts into regions.
TEST(FaceOctreeBoundarySimplifier, RegionsTheSameOnAnyThreads)
{
  struct Case
  {
    std::string name;
    BitVolume v;
    bool topology;
    double bound;
  };
  const std::vector<Case> cases{ { "ball48", shapeVolume(solids()[0], 48), true, std::sqrt(3.0) },
    { "csg44 within 1.2", shapeVolume(solids()[4], 44), true, 1.2 },
    { "porous3", porous(40, 3), false, std::sqrt(3.0) } };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.name);
    ASSERT_GE(triangleSurface(run(c.v, vbr::BoundaryCells::Triangles)).triangles.size(), 4096u);
    const vbr::SimplifiedSurface one = checkSimplified(c.name, c.v, c.topology, 2, c.bound);
    for (int threads : { 2, 3 })
    {
      const vbr::SimplifiedSurface many =
        checkSimplified(c.name + " on " + std::to_string(threads) + " threads",
          c.v,
          c.topology,
          2,
          c.bound,
          bf::threadedExecution(threads));
      EXPECT_EQ(many.surface.points, one.surface.points);
      EXPECT_EQ(many.surface.triangles, one.surface.triangles);
      EXPECT_EQ(many.collapses, one.collapses);
      EXPECT_EQ(many.surfaceDistance, one.surfaceDistance);
      EXPECT_EQ(many.surfelDistance, one.surfelDistance);
    }
    for (int regions : { 1, 3 })
      checkSimplified(c.name + " in " + std::to_string(regions) + " regions",
        c.v,
        c.topology,
        2,
        c.bound,
        bf::threadedExecution(2),
        regions);
  }
}

/// Asked to stop while the regions run (polled from both threads), the simplifier returns its
/// input.
TEST(FaceOctreeBoundarySimplifier, StopsWhileTheRegionsRun)
{
  const BitVolume v = shapeVolume(solids()[0], 48);
  const vbr::TriangleSurface in = triangleSurface(run(v, vbr::BoundaryCells::Triangles));
  std::atomic<int> polls{ 0 };
  int atHalf = -1; // the polls when the regions are done (the first progress reported)
  vbr::Execution counting;
  counting.aborted = [&] { return ++polls < 0; };
  counting.progress = [&](double)
  {
    if (atHalf < 0)
      atHalf = polls;
    return true;
  };
  ASSERT_TRUE(vbr::simplifyBoundary(v, in, {}, counting).simplified);
  ASSERT_GT(atHalf, 10);
  vbr::Execution exec = bf::threadedExecution(2);
  polls = 0;
  exec.aborted = [&] { return ++polls > atHalf - 3; };
  const vbr::SimplifiedSurface out = vbr::simplifyBoundary(v, in, {}, exec);
  EXPECT_TRUE(out.aborted);
  EXPECT_FALSE(out.simplified);
  EXPECT_EQ(out.surface.triangles, in.triangles);
}

TEST(FaceOctreeBoundarySimplifier, TighterBound)
{
  checkSimplified("ball48 within 1.5", shapeVolume(solids()[0], 48), true, 2, 1.5);
}

// End to end at the tightest bounds the input allows (it runs within about 1.0003 of the
// surfels, so no tighter): closed, manifold, the topology kept, against the same independent
// distances. (The proof by voxels on its own is ProofByVoxelsHolds and the tests after it.)
TEST(FaceOctreeBoundarySimplifier, TightestBounds)
{
  checkSimplified("torus40 within 1.2", shapeVolume(solids()[1], 40), true, 10, 1.2);
  checkSimplified("csg40 within 1.1", shapeVolume(solids()[4], 40), true, 10, 1.1);
}

// (a)'s proof by voxels on its own: random triangles about the surfels of a porous blob,
// small and large, many with corners on voxel faces; every point of a lattice on each triangle
// it accepts must be within d of a surfel (brute force over all of them), and it must accept
// and refuse a fair share (the proof is no empty one).
TEST(FaceOctreeBoundarySimplifier, ProofByVoxelsHolds)
{
  const BitVolume v = porous(20, 3);
  const std::vector<Surfel> all = surfels(v);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (double d : { std::sqrt(3.0), 1.5, 1.2 })
  {
    SCOPED_TRACE(d);
    int proven = 0, refused = 0;
    double worst = 0;
    for (int n = 0; n < 1500; ++n)
    {
      const Surfel& s = all[std::size_t(u(rng) * double(all.size())) % all.size()];
      const double size = std::pow(10.0, -0.7 + 1.2 * u(rng));
      std::array<Vec3, 3> t;
      for (Vec3& p : t)
        for (int a = 0; a < 3; ++a)
          p[a] = s.voxel[a] + 0.5 + (u(rng) - 0.5) * 3 + (u(rng) - 0.5) * size;
      if (n % 3 == 0)
        for (int a = 0; a < 3; ++a)
          t[1][a] = std::round(t[1][a]); // a corner on voxel corners
      if (!vbr::provenByVoxels(v, t, d))
      {
        ++refused;
        continue;
      }
      ++proven;
      constexpr int Steps = 8;
      for (int i = 0; i <= Steps; ++i)
        for (int j = 0; i + j <= Steps; ++j)
        {
          Vec3 p;
          for (int a = 0; a < 3; ++a)
            p[a] = t[0][a] + (t[1][a] - t[0][a]) * i / Steps + (t[2][a] - t[0][a]) * j / Steps;
          double nearest = 1e9;
          for (const Surfel& f : all)
            nearest = std::min(nearest, pointSquareDistance(p, f));
          worst = std::max(worst, nearest);
        }
    }
    EXPECT_LE(worst, d + 1e-9);
    EXPECT_GT(proven, 50);
    EXPECT_GT(refused, 150);
    std::cout << "within " << d << ": " << proven << " proven, " << refused
              << " refused, farthest point of a proven one " << worst << "\n";
  }
}

// The marks of the proof by voxels, every voxel from 3 before the grid to 3 after it, against
// brute force: a voxel is proven when some surfel is within d of all 8 of its corners. Grids
// across 64-bit words along x (64, 70, 130) and one along y, objects random and whole (their
// surfels on the grid's border). The marks are read through a tiny triangle at each voxel's
// centre, which meets that voxel alone.
TEST(FaceOctreeBoundarySimplifier, ProofByVoxelsMarksEveryVoxel)
{
  const double reaches[] = { 0.99, 1, 1.2, std::sqrt(2.0), 1.5, std::sqrt(3.0), 1.8, 1.99 };
  std::mt19937 rng(5);
  for (const Int3& n : { Int3{ 64, 3, 3 }, Int3{ 70, 3, 2 }, Int3{ 130, 2, 2 }, Int3{ 3, 64, 5 } })
    for (int filled = 0; filled < 2; ++filled)
    {
      SCOPED_TRACE(std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
        std::to_string(n[2]) + (filled ? " whole" : " random"));
      BitVolume v(n[0], n[1], n[2]);
      for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
          for (int i = 0; i < n[0]; ++i)
            if (filled || rng() % 2)
              v.set(i, j, k);
      int wrong = 0, proven = 0;
      for (int k = -3; k < n[2] + 3; ++k)
        for (int j = -3; j < n[1] + 3; ++j)
          for (int i = -3; i < n[0] + 3; ++i)
          {
            // the surfels of voxels up to 2 away (farther ones are 2 from a corner)
            double nearest = 1e9;
            for (int r = k - 2; r <= k + 2; ++r)
              for (int q = j - 2; q <= j + 2; ++q)
                for (int p = i - 2; p <= i + 2; ++p)
                  if (at(v, p, q, r))
                    for (int a = 0; a < 3; ++a)
                      for (int side = 0; side < 2; ++side)
                      {
                        Int3 w{ p, q, r };
                        w[a] += side ? 1 : -1;
                        if (at(v, w[0], w[1], w[2]))
                          continue;
                        double farthest = 0;
                        for (int c = 0; c < 8; ++c)
                          farthest = std::max(farthest,
                            pointSquareDistance(Vec3{ double(i + (c & 1)),
                                                  double(j + (c >> 1 & 1)),
                                                  double(k + (c >> 2)) },
                              Surfel{ { p, q, r }, a, side }));
                        nearest = std::min(nearest, farthest);
                      }
            const std::array<Vec3, 3> t{ Vec3{ i + 0.49, j + 0.5, k + 0.5 },
              Vec3{ i + 0.51, j + 0.49, k + 0.5 },
              Vec3{ i + 0.5, j + 0.51, k + 0.51 } };
            for (double d : reaches)
            {
              const bool marked = vbr::provenByVoxels(v, t, d);
              proven += marked;
              if (marked != (nearest <= d * (1 + 1e-12)) && ++wrong <= 5)
                ADD_FAILURE() << "voxel " << i << " " << j << " " << k << " within " << d
                              << ": marked " << marked << ", nearest surfel " << nearest;
            }
          }
      EXPECT_EQ(wrong, 0);
      EXPECT_GT(proven, 100);
    }
}

// A needle (its corners off a line by some 1e-14) whose rounded normal is noise: its heights
// over a column must not be trusted. It reaches 6.2 voxels above the surfels of z = 10.
TEST(FaceOctreeBoundarySimplifier, ProofByVoxelsRefusesAFarNeedle)
{
  BitVolume v(40, 40, 40);
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i)
        v.set(i, j, k);
  const std::array<Vec3, 3> t{ Vec3{ 14.200888097065292, 13.82425941696782, 10.999999531278789 },
    Vec3{ 17.933591376596876, 22.065063018540592, 16.218754910984366 },
    Vec3{ 17.534647400979907, 21.184302158410652, 15.660984613417757 } };
  EXPECT_FALSE(vbr::provenByVoxels(v, t, 1.0));
  EXPECT_FALSE(vbr::provenByVoxels(v, t, std::sqrt(3.0)));
}

// Slivers and needles (a corner off the line of the other two by 0 to 1e-6) about the planes
// 9 and 11 of the half space below 10 along each axis. At d = 1 the proven voxels away from
// the grid's border are exactly those 9 and 10 along the axis, the slab [9, 11]: every
// triangle it proves must have its corners in the slab (exact, no sampling), and a fair share
// (those inside, their corners off the planes by 1e-9 to 1e-5 inward) must be proven.
TEST(FaceOctreeBoundarySimplifier, ProofByVoxelsHoldsForSlivers)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int axis = 0; axis < 3; ++axis)
  {
    SCOPED_TRACE(axis);
    BitVolume v(40, 40, 40);
    for (int k = 0; k < 40; ++k)
      for (int j = 0; j < 40; ++j)
        for (int i = 0; i < 40; ++i)
          if (std::array<int, 3>{ i, j, k }[axis] < 10)
            v.set(i, j, k);
    int proven = 0, outside = 0;
    double worst = 0;
    for (int n = 0; n < 20000; ++n)
    {
      // in (x, y, h), h along the axis: t0, t1 = t0 + L (dx, dy, slope), t2 on t0 t1 moved off
      const double length = std::pow(10.0, -1 + 2 * u(rng));
      const double x0 = 12 + 16 * u(rng), y0 = 12 + 16 * u(rng), phi = 6.283 * u(rng);
      const double slope = (u(rng) - 0.5) * 2 * std::pow(10.0, -3 * u(rng));
      const double h0 =
        (u(rng) < 0.5 ? 11 : 9) + (u(rng) < 0.5 ? 1 : -1) * std::pow(10.0, -9 + 4 * u(rng));
      const int kind = n % 4;
      const double off =
        kind == 0 ? 0.0 : std::pow(10.0, -(kind == 1 ? 16 : (kind == 2 ? 12 : 6)) - 2 * u(rng));
      const double dx = std::cos(phi), dy = std::sin(phi), along = u(rng), up = u(rng) - 0.5;
      const double p[3][3] = { { x0, y0, h0 },
        { x0 + length * dx, y0 + length * dy, h0 + length * slope },
        { x0 + along * length * dx - off * dy,
          y0 + along * length * dy + off * dx,
          h0 + along * length * slope + off * up } };
      std::array<Vec3, 3> t;
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
          t[c][d < 2 ? (axis + 1 + d) % 3 : axis] = p[c][d];
      if (!vbr::provenByVoxels(v, t, 1.0))
        continue;
      ++proven;
      double out = 0;
      for (const Vec3& q : t)
        out = std::max({ out, q[axis] - 11, 9 - q[axis] });
      outside += out > 0;
      worst = std::max(worst, out);
    }
    EXPECT_EQ(outside, 0) << "the farthest corner " << worst << " beyond the slab";
    EXPECT_GT(proven, 1500);
    std::cout << "axis " << axis << ": " << proven << " of 20000 slivers proven, " << outside
              << " of them outside the slab\n";
  }
}

/// An input the simplifier refuses comes back unchanged with its own distances: upper bounds
/// of the measured ones both ways (the surfels' side infinite when CGAL cannot hold it).
TEST(FaceOctreeBoundarySimplifier, RefusedInputKeepsItsOwnDistances)
{
  const BitVolume v = shapeVolume(solids()[0], 32);
  const vbr::TriangleSurface closed = triangleSurface(run(v, vbr::BoundaryCells::Triangles));
  const std::set<Int3> pruned = prunedVoxelSet(v);
  vbr::TriangleSurface open = closed; // not closed: refused, but a mesh CGAL holds
  open.triangles.pop_back();
  vbr::TriangleSurface twice = closed; // a triangle twice: not a manifold mesh
  twice.triangles.push_back(twice.triangles.front());
  for (const vbr::TriangleSurface* in : { &open, &twice })
  {
    const vbr::SimplifiedSurface out = vbr::simplifyBoundary(v, *in);
    EXPECT_FALSE(out.simplified);
    EXPECT_FALSE(out.aborted);
    EXPECT_EQ(out.surface.triangles, in->triangles);
    double there = 0, back = 0;
    hausdorff(meshOf(*in), v, pruned, there, back);
    EXPECT_GT(there, 0.5); // a surface measured, not a default
    EXPECT_LE(there, out.surfaceDistance + 1e-9);
    EXPECT_LE(out.surfaceDistance, there + 0.1);
    EXPECT_LE(back, out.surfelDistance + 1e-9);
    if (in == &open)
      EXPECT_LE(out.surfelDistance, std::sqrt(3.0));
    else
      EXPECT_TRUE(std::isinf(out.surfelDistance));
  }
}

TEST(FaceOctreeBoundarySimplifier, StopsWhenAskedAndReturnsItsInput)
{
  const BitVolume v = shapeVolume(solids()[0], 32);
  const vbr::TriangleSurface in = triangleSurface(run(v, vbr::BoundaryCells::Triangles));
  int total = 0; // the polls of a whole run
  vbr::Execution counting;
  counting.aborted = [&] { return ++total < 0; };
  ASSERT_TRUE(vbr::simplifyBoundary(v, in, {}, counting).simplified);
  // asked while the surfels are assigned, then during the collapses (most polls)
  for (int asked : { 2, total - total / 4 })
  {
    SCOPED_TRACE(asked);
    int polls = 0;
    std::vector<double> reported;
    vbr::Execution exec;
    exec.aborted = [&] { return ++polls > asked; };
    exec.progress = [&](double f)
    {
      reported.push_back(f);
      return true;
    };
    const vbr::SimplifiedSurface out = vbr::simplifyBoundary(v, in, {}, exec);
    EXPECT_TRUE(out.aborted);
    EXPECT_FALSE(out.simplified);
    EXPECT_EQ(out.surface.triangles, in.triangles);
    std::cout << "asked at poll " << asked << " of " << total << ": " << out.collapses
              << " collapses\n";
    EXPECT_EQ(out.collapses == 0, asked == 2);
    EXPECT_EQ(reported.empty(), asked == 2);
    EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
  }
}

TEST(DeformedModel, QuadrilateralsArePrunedNet)
{
  for (const Shape& s : solids())
  {
    const BitVolume v = shapeVolume(s, 24);
    const auto m = vbr::buildDeformedModel(v, {}, sequential);
    std::set<std::array<Int3, 4>> got;
    for (const auto& q : m.quads)
    {
      std::array<Int3, 4> key{ m.voxel[q[0]], m.voxel[q[1]], m.voxel[q[2]], m.voxel[q[3]] };
      std::sort(key.begin(), key.end());
      got.insert(key);
    }
    EXPECT_EQ(got.size(), m.quads.size()) << s.name;
    EXPECT_EQ(got, expectedQuads(v)) << s.name;
    std::size_t boundary, pruned;
    expectedCounts(v, boundary, pruned);
    EXPECT_EQ(m.boundaryVoxels, boundary);
    EXPECT_EQ(m.prunedVoxels, pruned);
    // Every kept quadrilateral is among the unpruned net's 4-cycles.
    std::set<std::array<Int3, 4>> unpruned;
    for (auto q : vbr::unprunedQuadrilaterals(v))
    {
      std::sort(q.begin(), q.end());
      unpruned.insert(q);
    }
    for (const auto& q : got)
      EXPECT_TRUE(unpruned.count(q));
  }
}

TEST(DeformedModel, CrestsArePruned)
{
  // A one-voxel wall on a block: its voxels are lost; a two-voxel wall keeps no inner
  // quadrilateral (the net stays closed and manifold).
  for (int thickness : { 1, 2 })
  {
    const BitVolume v = sample({ 20, 20, 20 },
      [&](double x, double y, double z)
      {
        const bool block = x > 3 && x < 17 && y > 3 && y < 17 && z > 3 && z < 9;
        const bool wall = x > 3 && x < 17 && y > 9 && y < 9 + thickness + 0.5 && z > 3 && z < 16;
        return block || wall;
      });
    const auto m = vbr::buildDeformedModel(v, {}, sequential);
    std::size_t boundary, pruned;
    expectedCounts(v, boundary, pruned);
    EXPECT_EQ(m.prunedVoxels, pruned);
    if (thickness == 1)
      EXPECT_GT(m.prunedVoxels, 14u * 6u);
    else
      EXPECT_EQ(m.prunedVoxels, 0u);
    const Result r = run(v, vbr::BoundaryCells::Quadrilaterals);
    std::string error;
    checkClosedManifold(meshOf(r.mesh), error);
    EXPECT_TRUE(error.empty()) << error;
  }
}

TEST(DeformedModel, RelaxationLowersTheCostInsideTheVoxels)
{
  const BitVolume v = shapeVolume(solids()[0], 32);
  double last = 1e300;
  for (int iterations : { 0, 1, 2, 5, 20 })
  {
    vbr::DeformedModelOptions o;
    o.iterations = iterations;
    o.tolerance = 0;
    const auto m = vbr::buildDeformedModel(v, o, sequential);
    const double cost = vbr::relaxationCost(m, o.attachment);
    EXPECT_LE(cost, last + 1e-9);
    last = cost;
    for (std::size_t p = 0; p < m.pointCount(); ++p)
      for (int d = 0; d < 3; ++d)
      {
        ASSERT_GE(m.position[p][d], m.voxel[p][d] + (m.shared[p] ? 0 : o.margin));
        ASSERT_LE(m.position[p][d], m.voxel[p][d] + 1 - (m.shared[p] ? 0 : o.margin));
      }
  }
  vbr::DeformedModelOptions o;
  o.iterations = 1000;
  o.tolerance = 1e-3;
  const auto m = vbr::buildDeformedModel(v, o, sequential);
  EXPECT_LT(m.iterationsRun, 1000);
  EXPECT_LE(m.lastDisplacement, 1e-3);
}

/// The face nodes' rules, checked directly: every point projected inside its voxel and in its
/// node's box, on the node's plane, and no plane cutting a voxel whose 26 neighbours are all
/// of its own kind inside the node's box; octree nodes are aligned cubes.
/// The farthest any point of a surfel is from p: the farthest of its four corners.
double farthestOfSurfel(const Vec3& p, const Surfel& s)
{
  double worst = 0;
  for (int c = 0; c < 4; ++c)
  {
    Vec3 x{ double(s.voxel[0]), double(s.voxel[1]), double(s.voxel[2]) };
    x[s.axis] += s.side;
    x[(s.axis + 1) % 3] += c & 1;
    x[(s.axis + 2) % 3] += c >> 1;
    worst = std::max(worst,
      std::sqrt((p[0] - x[0]) * (p[0] - x[0]) + (p[1] - x[1]) * (p[1] - x[1]) +
        (p[2] - x[2]) * (p[2] - x[2])));
  }
  return worst;
}

/// The compaction's rules, checked from the voxels. Every projected point lies on its node's
/// plane, in its node's box; under the paper's rule in its own voxel, under the reach rule
/// within `precision` of its relaxed point along the normal and within a voxel diagonal of
/// every point of every surfel of its voxel (so every surfel of an unpruned voxel is that
/// close to a vertex of the surface).
static void checkCompactionCriterion(const BitVolume& v,
  const vbr::DeformedModel& model,
  const vbr::FaceOctree& octree,
  bool merged,
  bool papersRule = false,
  double precision = 0.5)
{
  std::map<Int3, std::vector<Surfel>> surfelsOf;
  for (const Surfel& s : surfels(v))
    surfelsOf[s.voxel].push_back(s);
  int maxLevel = 0;
  for (std::size_t p = 0; p < model.pointCount(); ++p)
  {
    const int id = octree.nodeOf[p];
    if (id < 0)
      continue;
    const auto& node = octree.nodes[id];
    maxLevel = std::max(maxLevel, node.level);
    const Vec3& q = octree.projected[p];
    for (int d = 0; d < 3; ++d)
    {
      if (papersRule)
      {
        ASSERT_GE(q[d], model.voxel[p][d] - 1e-12);
        ASSERT_LE(q[d], model.voxel[p][d] + 1 + 1e-12);
      }
      ASSERT_GE(q[d], node.lo[d] - 1e-12);
      ASSERT_LE(q[d], node.hi[d] + 1e-12);
      ASSERT_GE(model.voxel[p][d], node.lo[d]);
      ASSERT_LT(model.voxel[p][d], node.hi[d]);
    }
    const double off = node.normal[0] * q[0] + node.normal[1] * q[1] + node.normal[2] * q[2];
    ASSERT_NEAR(off, node.offset, 1e-9);
    if (papersRule)
      continue;
    const Vec3& x = model.position[p];
    ASSERT_LE(
      std::abs(node.normal[0] * x[0] + node.normal[1] * x[1] + node.normal[2] * x[2] - node.offset),
      precision + 1e-9);
    const auto& vox = model.voxel[p];
    for (const Surfel& s : surfelsOf[{ vox[0], vox[1], vox[2] }])
      ASSERT_LE(farthestOfSurfel(q, s), std::sqrt(3.0) + 1e-9)
        << "point " << p << " of node " << id << " at level " << node.level;
  }
  EXPECT_GE(maxLevel, 3);
  // Under the reach rule, every point inside a node's disk (all its quadrilaterals in the
  // node, not a corner of the polygon) projects inside the polygon that replaces the disk
  // (even-odd ray test in the plane, in a basis of its own).
  std::vector<int> interiorPoints(octree.nodes.size());
  for (std::size_t p = 0; p < model.pointCount() && !papersRule; ++p)
  {
    const int id = octree.nodeOf[p];
    if (id < 0 || octree.nodes[id].polygon.empty())
      continue;
    const auto& node = octree.nodes[id];
    bool interior =
      std::find(node.polygon.begin(), node.polygon.end(), int(p)) == node.polygon.end();
    for (auto l = model.linkOffsets[p]; l < model.linkOffsets[p + 1] && interior; ++l)
      for (int r = 0; r < 4; ++r)
        interior = interior && octree.nodeOf[model.quads[model.quadsOf[l]][r]] == id;
    if (!interior)
      continue;
    ++interiorPoints[id];
    const Vec3& n = node.normal;
    const Vec3 a = std::abs(n[0]) < 0.6 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
    Vec3 u{ n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0] };
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& x : u)
      x /= lu;
    const Vec3 w{ n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0] };
    auto flat = [&](const Vec3& x)
    {
      return std::array<double, 2>{ x[0] * u[0] + x[1] * u[1] + x[2] * u[2],
        x[0] * w[0] + x[1] * w[1] + x[2] * w[2] };
    };
    const auto q = flat(octree.projected[p]);
    bool in = false;
    for (std::size_t i = 0, k = node.polygon.size() - 1; i < node.polygon.size(); k = i++)
    {
      const auto pi = flat(octree.projected[node.polygon[i]]);
      const auto pk = flat(octree.projected[node.polygon[k]]);
      if ((pi[1] > q[1]) != (pk[1] > q[1]) &&
        q[0] < (pk[0] - pi[0]) * (q[1] - pi[1]) / (pk[1] - pi[1]) + pi[0])
        in = !in;
    }
    ASSERT_TRUE(in) << "point " << p << " inside node " << id << " (level " << node.level
                    << ") projects outside its polygon";
  }
  EXPECT_TRUE(papersRule ||
    std::any_of(interiorPoints.begin(), interiorPoints.end(), [](int k) { return k > 0; }));
  // Under the reach rule, the box of every sewing quadrilateral's corners meets no voxel whose
  // 26 neighbours are all of its own kind (its triangles stay near the surfels).
  const auto far = [&](int i, int j, int k)
  {
    for (int d = 0; d < 27; ++d)
      if (at(v, i + d % 3 - 1, j + (d / 3) % 3 - 1, k + d / 9 - 1) != at(v, i, j, k))
        return false;
    return true;
  };
  for (const auto& q : papersRule ? std::vector<vbr::Quad>() : model.quads)
  {
    const int node = octree.nodeOf[q[0]];
    if (node >= 0 && octree.nodeOf[q[1]] == node && octree.nodeOf[q[2]] == node &&
      octree.nodeOf[q[3]] == node)
      continue; // inside a polygon
    int lo[3], hi[3];
    for (int d = 0; d < 3; ++d)
    {
      double a = 1e300, b = -1e300;
      for (int r = 0; r < 4; ++r)
        a = std::min(a, octree.projected[q[r]][d]), b = std::max(b, octree.projected[q[r]][d]);
      lo[d] = std::max(0, int(std::floor(a)));
      hi[d] = std::min(v.size(d) - 1, int(std::floor(b)));
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
          ASSERT_FALSE(far(i, j, k))
            << "a sewing quadrilateral's box meets voxel " << i << " " << j << " " << k;
  }
  // No plane cuts the open interior of a voxel whose 26 neighbours are all of its own kind.
  for (const auto& node : octree.nodes)
  {
    if (!merged)
      ASSERT_EQ(node.lo[0] % (1 << node.level), 0);
    for (int k = node.lo[2]; k < node.hi[2]; ++k)
      for (int j = node.lo[1]; j < node.hi[1]; ++j)
        for (int i = node.lo[0]; i < node.hi[0]; ++i)
        {
          bool same = true;
          for (int d = 0; d < 27; ++d)
            same =
              same && at(v, i + d % 3 - 1, j + (d / 3) % 3 - 1, k + d / 9 - 1) == at(v, i, j, k);
          if (!same)
            continue;
          double lo = 1e300, hi = -1e300;
          for (int c = 0; c < 8; ++c)
          {
            const double x = node.normal[0] * (i + (c & 1)) +
              node.normal[1] * (j + ((c >> 1) & 1)) + node.normal[2] * (k + (c >> 2));
            lo = std::min(lo, x), hi = std::max(hi, x);
          }
          ASSERT_FALSE(lo < node.offset - 1e-9 && hi > node.offset + 1e-9)
            << "node at level " << node.level << " cuts voxel " << i << " " << j << " " << k;
        }
  }
}

TEST(FaceOctree, NodesSatisfyTheCompactionCriterion)
{
  // A grid that is no power of two along any axis.
  const std::vector<Shape> shapes = solids(); // the shape must outlive the sampling
  const Shape& s = shapes[4];
  const BitVolume v = sample(
    { 45, 38, 41 }, [&](double x, double y, double z) { return s.inside(x / 45, y / 38, z / 41); });
  const auto model = vbr::buildDeformedModel(v, {}, sequential);
  for (bool papers : { false, true })
    for (bool merge : { false, true })
    {
      SCOPED_TRACE(std::string(merge ? "merged" : "octree") + (papers ? ", paper's rule" : ""));
      vbr::FaceOctreeOptions options;
      options.mergeFaceNodes = merge;
      options.keepPointsInVoxels = papers;
      checkCompactionCriterion(
        v, model, vbr::buildFaceOctree(v, model, options, sequential), merge, papers);
    }
}

TEST(FaceOctree, ReachRuleHoldsAtLargePrecision)
{
  // With a point allowed 1.5 voxels off its node's plane, only the reach rule's own checks
  // (every projection within a voxel diagonal of its voxel's surfels, no far voxel in a
  // sewing quadrilateral's box) keep the surface within a voxel diagonal of the surfels,
  // both ways (brute force: checkPolygons' Hausdorff samples), and closed, manifold and free
  // of self-intersections.
  precision = 1.5;
  for (const Shape& s : solids())
  {
    const BitVolume v = shapeVolume(s, 40);
    const auto model = vbr::buildDeformedModel(v, {}, sequential);
    vbr::FaceOctreeOptions options;
    options.precision = precision;
    options.mergeFaceNodes = false;
    SCOPED_TRACE(s.name);
    checkCompactionCriterion(
      v, model, vbr::buildFaceOctree(v, model, options, sequential), false, false, precision);
    checkBoundary(s.name + "40 at precision 1.5", v, true);
  }
  for (unsigned seed : { 1u, 2u })
    checkBoundary(
      "porous" + std::to_string(seed) + "_40 at precision 1.5", porous(40, seed), false);
  precision = 0.0;
}

TEST(FaceOctree, MergingCrossesOctreeCellsAndDropsSewingTriangles)
{
  // The same surface rules (the boundary checks above run with merging); here
  // what merging is for: faces whose box is no octree cube, and fewer cells than without.
  for (const Shape& s : solids())
  {
    SCOPED_TRACE(s.name);
    const BitVolume v = shapeVolume(s, 48);
    const auto model = vbr::buildDeformedModel(v, {}, sequential);
    vbr::FaceOctreeOptions options;
    options.mergeFaceNodes = false;
    const auto octree = vbr::buildFaceOctree(v, model, options, sequential);
    options.mergeFaceNodes = true;
    const auto merged = vbr::buildFaceOctree(v, model, options, sequential);
    EXPECT_LT(merged.nodes.size(), octree.nodes.size());
    std::size_t across = 0;
    for (const auto& node : merged.nodes)
      for (int d = 0; d < 3; ++d)
        if (node.lo[d] % (1 << node.level) != 0 || node.hi[d] - node.lo[d] > (1 << node.level))
        {
          ++across;
          break;
        }
    EXPECT_GT(across, 0u);
    // Merged boxes stay disjoint (port 1 of the filter draws them), as the octree's cells.
    for (std::size_t x = 0; x < merged.nodes.size(); ++x)
      for (std::size_t y = x + 1; y < merged.nodes.size(); ++y)
      {
        const auto &a = merged.nodes[x], &b = merged.nodes[y];
        bool overlap = true;
        for (int d = 0; d < 3; ++d)
          overlap = overlap && a.lo[d] < b.hi[d] && b.lo[d] < a.hi[d];
        ASSERT_FALSE(overlap) << "faces " << x << " and " << y;
      }
    const auto cells = [&](const vbr::FaceOctree& o)
    { return vbr::assembleBoundary(model, o, vbr::BoundaryCells::Triangles).cellCount(); };
    EXPECT_LT(cells(merged), cells(octree));
    std::cout << s.name << "48: " << octree.nodes.size() << " -> " << merged.nodes.size()
              << " face nodes, " << cells(octree) << " -> " << cells(merged) << " triangles\n";
  }
}

TEST(FaceOctree, MergingReportsProgressAndStopsWhenAsked)
{
  // The merging is about as long as the compaction: it takes the second half of the
  // progress, rising, and an abort asked in its middle stops it there (fewer merges done).
  const BitVolume v = shapeVolume(solids().front(), 48);
  const auto model = vbr::buildDeformedModel(v, {}, sequential);
  vbr::FaceOctreeOptions options;
  options.mergeFaceNodes = true;
  std::vector<double> reported;
  vbr::Execution watched;
  watched.progress = [&](double f)
  {
    reported.push_back(f);
    return true;
  };
  const auto merged = vbr::buildFaceOctree(v, model, options, watched);
  ASSERT_FALSE(reported.empty());
  EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
  EXPECT_GE(reported.front(), 0.0);
  EXPECT_LE(reported.back(), 1.0);
  const double middle = 0.75;
  ASSERT_TRUE(std::any_of(reported.begin(), reported.end(), [&](double f) { return f > middle; }))
    << "the merging reports its progress";

  bool stop = false;
  vbr::Execution stopped;
  stopped.progress = [&](double f)
  {
    stop = stop || f > middle;
    return true;
  };
  stopped.aborted = [&] { return stop; };
  const auto partial = vbr::buildFaceOctree(v, model, options, stopped);
  EXPECT_TRUE(stop);
  EXPECT_GT(partial.nodes.size(), merged.nodes.size());

  // Asked to stop before it starts, with no progress callback (as Labels mode runs each pair):
  // no level is compacted, the voxel faces stay what they are at level 0.
  vbr::Execution before;
  before.aborted = [] { return true; };
  vbr::FaceOctreeOptions flat = options;
  flat.maximumLevel = 0;
  EXPECT_EQ(vbr::buildFaceOctree(v, model, options, before).nodes.size(),
    vbr::buildFaceOctree(v, model, flat, sequential).nodes.size());
}

TEST(FaceOctreeBoundary, ConvexPiecesCoverThePolygon)
{
  // An L and a comb, exact corners.
  std::vector<std::vector<vbr::Point2L>> polygons = {
    { { 0, 0 }, { 4, 0 }, { 4, 1 }, { 1, 1 }, { 1, 4 }, { 0, 4 } },
    { { 0, 0 },
      { 7, 0 },
      { 7, 3 },
      { 6, 3 },
      { 6, 1 },
      { 5, 1 },
      { 5, 3 },
      { 4, 3 },
      { 4, 1 },
      { 3, 1 },
      { 3, 3 },
      { 0, 3 } },
  };
  for (const auto& poly : polygons)
  {
    const auto pieces = vbr::convexPieces(poly);
    ASSERT_FALSE(pieces.empty());
    __int128 total = 0;
    for (const auto& piece : pieces)
    {
      std::vector<vbr::Point2L> c;
      for (int i : piece)
        c.push_back(poly[i]);
      EXPECT_TRUE(vbr::fanCoversPolygon(c, 0));
      total += vbr::doubledArea(c);
    }
    EXPECT_TRUE(total == vbr::doubledArea(poly));
    EXPECT_LT(pieces.size(), poly.size() - 2);
  }
}

TEST(FaceOctreeBoundary, SolidsAt32)
{
  for (const Shape& s : solids())
    checkBoundary(s.name + "32", shapeVolume(s, 32), true);
}

TEST(FaceOctreeBoundary, SolidsAt32WithoutMerging)
{
  mergeFaceNodes = false;
  for (const Shape& s : solids())
    checkBoundary(s.name + "32", shapeVolume(s, 32), true);
  mergeFaceNodes = true;
}

TEST(FaceOctreeBoundary, SolidsAt32UnderThePapersRule)
{
  // The paper's rule (keepPointsInVoxels): every check of the boundary, with and without
  // merging.
  keepPointsInVoxels = true;
  for (bool merge : { true, false })
  {
    mergeFaceNodes = merge;
    for (const Shape& s : solids())
      checkBoundary(s.name + "32, paper's rule", shapeVolume(s, 32), true);
  }
  mergeFaceNodes = true;
  keepPointsInVoxels = false;
}

TEST(FaceOctreeBoundary, RoundSolidsAt64)
{
  for (const Shape& s : solids())
    if (s.name == "ball" || s.name == "torus")
      checkBoundary(s.name + "64", shapeVolume(s, 64), true);
}

TEST(FaceOctreeBoundary, CubesAndCSGAt64)
{
  for (const Shape& s : solids())
    if (s.name != "ball" && s.name != "torus")
      checkBoundary(s.name + "64", shapeVolume(s, 64), true);
}

TEST(FaceOctreeBoundary, PorousBlobs)
{
  for (int n : { 32, 40, 64 })
    for (unsigned seed : { 1u, 2u, 3u })
      checkBoundary(
        "porous" + std::to_string(seed) + "_" + std::to_string(n), porous(n, seed), false);
}

/// The Triangles boundary of v closed and manifold, and no two of its triangles crossing
/// (CGAL's exact does_self_intersect): the checks of the larger sizes, where the others'
/// brute force would be slow.
static void expectClosedWithoutCrossings(const BitVolume& v)
{
  const Result r = run(v, vbr::BoundaryCells::Triangles);
  const Mesh m = meshOf(r.mesh);
  std::string error;
  checkClosedManifold(m, error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_FALSE(selfIntersects(m, &r.mesh.faceNode));
}

TEST(FaceOctreeBoundary, SolidsAt80DoNotSelfIntersect)
{
  // Larger nodes (levels 3 and 4) with long straight runs of corners along their voxel boxes'
  // faces, where cutting the polygons on the rounded plane grid made slivers fold. Only the
  // triangles' topology and CGAL here: the other checks are those of the smaller sizes.
  for (const Shape& s : solids())
  {
    SCOPED_TRACE(s.name);
    expectClosedWithoutCrossings(shapeVolume(s, 80));
  }
}

TEST(FaceOctreeBoundary, SolidsAt128DoNotSelfIntersect)
{
  // The reach rule's nodes at the benchmark's size, where its larger nodes move points farther
  // from their voxels than at 80 (a fold showed first at 128): no crossing of sheets, closed
  // and manifold.
  for (const Shape& s : solids())
  {
    SCOPED_TRACE(s.name);
    expectClosedWithoutCrossings(shapeVolume(s, 128));
  }
}

TEST(FaceOctreeBoundary, LargerPorousBlobsDoNotSelfIntersect)
{
  // Porous blobs larger than PorousBlobs': thin walls between pores two or three voxels
  // apart, where the reach rule's nodes could push the points of facing sheets into the gap.
  for (unsigned seed : { 1u, 2u, 3u, 4u, 5u, 6u })
  {
    SCOPED_TRACE(seed);
    expectClosedWithoutCrossings(porous(96, seed));
  }
}

TEST(FaceOctreeBoundary, RandomVoxels)
{
  // Noise: many diagonal contacts, crests and pruned voxels; the surface stays closed and
  // manifold.
  std::mt19937 rng(7);
  for (double density : { 0.5, 0.7, 0.85 })
  {
    BitVolume v(14, 13, 12);
    std::bernoulli_distribution b(density);
    for (int k = 0; k < 12; ++k)
      for (int j = 0; j < 13; ++j)
        for (int i = 0; i < 14; ++i)
          if (b(rng))
            v.set(i, j, k);
    checkBoundary("random" + std::to_string(density), v, false);
  }
}

TEST(FaceOctreeBoundary, MaximumDistanceToSurfelsMatchesEverySurfel)
{
  // The filter's MaximumDistance and distanceToSurfels against the distance to every surfel of
  // the volume, on noise and a ball, for points spread over the grid and a margin around it
  // (the search near each point is capped at 2 voxels: so is the reference), with one thread
  // and with a pool.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-2.5, 14.5);
  BitVolume noise(12, 11, 10), ball(12, 11, 10);
  std::bernoulli_distribution b(0.4);
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 11; ++j)
      for (int i = 0; i < 12; ++i)
      {
        if (b(rng))
          noise.set(i, j, k);
        if ((i - 5.5) * (i - 5.5) + (j - 5) * (j - 5) + (k - 4.5) * (k - 4.5) < 16)
          ball.set(i, j, k);
      }
  vbr::Execution pool;
  pool.parallelFor = [](std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& f)
  {
    for (std::int64_t b = 0; b < n; b += 7)
      f(b, std::min(n, b + 7));
  };
  for (const BitVolume* v : { &noise, &ball })
  {
    const auto faces = surfels(*v);
    ASSERT_FALSE(faces.empty());
    for (int trial = 0; trial < 200; ++trial)
    {
      std::vector<Vec3> points(1 + trial % 5);
      for (Vec3& p : points)
        p = { coordinate(rng), coordinate(rng), coordinate(rng) };
      double expected = 0;
      for (const Vec3& p : points)
      {
        double best = 2.0;
        for (const auto& f : faces)
          best = std::min(best, pointSquareDistance(p, f));
        expected = std::max(expected, best);
      }
      EXPECT_NEAR(vbr::maximumDistanceToSurfels(*v, points), expected, 1e-12) << trial;
      EXPECT_NEAR(vbr::maximumDistanceToSurfels(*v, points, pool), expected, 1e-12) << trial;
      // the single-point search the simplifier proves its triangles with (its voxels read
      // once per block)
      for (const Vec3& p : points)
      {
        double best = 2.0;
        for (const auto& f : faces)
          best = std::min(best, pointSquareDistance(p, f));
        EXPECT_NEAR(vbr::distanceToSurfels(*v, p), best, 1e-12) << trial;
      }
    }
  }
}

TEST(DeformedModel, NetIsClosedManifold)
{
  std::mt19937 rng(7);
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const BitVolume v = porous(40, seed);
    const Result r = run(v, vbr::BoundaryCells::Quadrilaterals);
    std::string error;
    checkClosedManifold(meshOf(r.mesh), error);
    EXPECT_TRUE(error.empty()) << error;
  }
}

TEST(DeformedModel, NetDoesNotSelfIntersect)
{
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const Result r = run(porous(40, seed), vbr::BoundaryCells::Triangles, sequential, 0);
    EXPECT_FALSE(selfIntersects(meshOf(r.mesh), &r.mesh.faceNode));
  }
}
