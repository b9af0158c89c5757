// The shared label surfaces (LabelNet) against independent references: the voxel faces
// between different labels listed voxel by voxel, each label's surface checked for closure
// and manifoldness from its cells alone, voxel centres classified by ray parity against each
// label's triangles, CGAL's self-intersection test, and distances to the label's own faces.
#include "LabelNet.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

namespace
{
using vbr::LabelVolume;
using vbr::Vec3;
using Int3 = std::array<std::int32_t, 3>;

vbr::Execution sequential;

/// Random label map: Voronoi cells of a few random sites (label 0 among them), with a
/// sprinkling of single voxels of random labels, so that voxels of one label often touch
/// only along an edge or at a corner.
LabelVolume randomLabels(unsigned seed, int labels)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> size(8, 24), label(0, labels);
  LabelVolume v;
  v.dims = { size(rng), size(rng), size(rng) };
  std::vector<std::pair<Vec3, int>> sites;
  for (int s = 0; s < 3 * labels; ++s)
  {
    std::uniform_real_distribution<double> u(0, 1);
    sites.push_back({ { u(rng) * v.dims[0], u(rng) * v.dims[1], u(rng) * v.dims[2] },
      s <= labels ? s : label(rng) });
  }
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i)
      {
        double best = 1e300;
        int l = 0;
        for (const auto& s : sites)
        {
          const double d = std::pow(i + .5 - s.first[0], 2) + std::pow(j + .5 - s.first[1], 2) +
            std::pow(k + .5 - s.first[2], 2);
          if (d < best)
            best = d, l = s.second;
        }
        v.labels.push_back(u(rng) < 0.08 ? label(rng) : l);
      }
  return v;
}

struct Mesh
{
  std::vector<Vec3> points;
  std::vector<std::vector<int>> cells;
  std::vector<vbr::LabelPair> labels;
};

Mesh meshOf(const vbr::LabelBoundary& b)
{
  Mesh m;
  m.points = b.mesh.points;
  for (std::size_t c = 0; c < b.mesh.cellCount(); ++c)
    m.cells.emplace_back(b.mesh.connectivity.begin() + b.mesh.offsets[c],
      b.mesh.connectivity.begin() + b.mesh.offsets[c + 1]);
  m.labels = b.labels;
  return m;
}

/// The cells that carry label L, turned so that their normals leave L's voxels.
std::vector<std::vector<int>> surfaceOf(const Mesh& m, int L)
{
  std::vector<std::vector<int>> out;
  for (std::size_t c = 0; c < m.cells.size(); ++c)
  {
    if (m.labels[c][0] != L && m.labels[c][1] != L)
      continue;
    out.push_back(m.cells[c]);
    if (m.labels[c][1] == L)
      std::reverse(out.back().begin(), out.back().end());
  }
  return out;
}

/// Empty when the cells are closed, manifold and consistently oriented: every directed edge
/// once with its reverse once, and the cells around each point one cycle.
std::string closedManifoldProblem(const std::vector<std::vector<int>>& cells)
{
  std::map<std::pair<int, int>, int> edges;
  std::map<int, std::map<int, int>> around; // point -> (next corner -> previous corner)
  std::map<int, int> cellsAt;
  for (const auto& c : cells)
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      const int p = c[i], n = c[(i + 1) % c.size()], q = c[(i + c.size() - 1) % c.size()];
      ++edges[{ p, n }];
      around[p][n] = q;
      ++cellsAt[p];
    }
  for (const auto& e : edges)
    if (e.second != 1 || edges.count({ e.first.second, e.first.first }) == 0)
      return "edge " + std::to_string(e.first.first) + "-" + std::to_string(e.first.second);
  for (const auto& a : around)
  {
    int x = a.second.begin()->first, steps = 0;
    do
    {
      const auto it = a.second.find(x);
      if (it == a.second.end())
        return "open fan at point " + std::to_string(a.first);
      x = it->second;
      ++steps;
    } while (x != a.second.begin()->first && steps <= cellsAt[a.first]);
    if (steps != cellsAt[a.first] || int(a.second.size()) != cellsAt[a.first])
      return "pinched point " + std::to_string(a.first);
  }
  return {};
}

/// Whether a ray from p along dir crosses triangle abc (Moeller-Trumbore); `grazing` is set
/// when it passes within a hair of an edge (the parity would be ambiguous).
bool crosses(const Vec3& p,
  const Vec3& dir,
  const Vec3& a,
  const Vec3& b,
  const Vec3& c,
  bool& grazing)
{
  const Vec3 e1{ b[0] - a[0], b[1] - a[1], b[2] - a[2] },
    e2{ c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const Vec3 h{ dir[1] * e2[2] - dir[2] * e2[1],
    dir[2] * e2[0] - dir[0] * e2[2],
    dir[0] * e2[1] - dir[1] * e2[0] };
  const double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
  if (std::abs(det) < 1e-14)
    return false;
  const Vec3 s{ p[0] - a[0], p[1] - a[1], p[2] - a[2] };
  const double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / det;
  const Vec3 q{
    s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]
  };
  const double v = (dir[0] * q[0] + dir[1] * q[1] + dir[2] * q[2]) / det;
  const double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
  const double eps = 1e-9;
  if (t > eps && u > -eps && v > -eps && u + v < 1 + eps && (u < eps || v < eps || u + v > 1 - eps))
    grazing = true;
  return t > 0 && u >= 0 && v >= 0 && u + v <= 1;
}

/// Whether p is inside the closed surface (fan triangles of the cells), by ray parity.
bool insideOf(const Mesh& m, const std::vector<std::vector<int>>& cells, const Vec3& p)
{
  const Vec3 dirs[3] = {
    { 1, 0.1234567, 0.0456789 }, { 0.0312, 1, 0.2718 }, { 0.1414, 0.0577, 1 }
  };
  for (const Vec3& dir : dirs)
  {
    bool grazing = false, inside = false;
    for (const auto& c : cells)
      for (std::size_t i = 1; i + 1 < c.size(); ++i)
        inside ^= crosses(p, dir, m.points[c[0]], m.points[c[i]], m.points[c[i + 1]], grazing);
    if (!grazing)
      return inside;
  }
  ADD_FAILURE() << "every ray grazes an edge";
  return false;
}

bool selfIntersecting(const Mesh& m, const std::vector<std::vector<int>>& cells)
{
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  CGAL::Surface_mesh<K::Point_3> sm;
  std::map<int, CGAL::Surface_mesh<K::Point_3>::Vertex_index> vertex;
  for (const auto& c : cells)
    for (int p : c)
      if (!vertex.count(p))
        vertex[p] = sm.add_vertex(K::Point_3(m.points[p][0], m.points[p][1], m.points[p][2]));
  for (const auto& c : cells)
    for (std::size_t i = 1; i + 1 < c.size(); ++i)
      sm.add_face(vertex[c[0]], vertex[c[i]], vertex[c[i + 1]]);
  return CGAL::Polygon_mesh_processing::does_self_intersect(sm);
}

/// Distance from p to the nearest face between a voxel of L and one of another label.
double distanceToLabelFaces(const LabelVolume& v, int L, const Vec3& p)
{
  // The faces within three voxels: anything farther is beyond the bound checked.
  double best = 9.0;
  const Int3 c{ int(std::floor(p[0])), int(std::floor(p[1])), int(std::floor(p[2])) };
  for (int k = c[2] - 3; k <= c[2] + 3; ++k)
    for (int j = c[1] - 3; j <= c[1] + 3; ++j)
      for (int i = c[0] - 3; i <= c[0] + 3; ++i)
        for (int a = 0; a < 3; ++a)
        {
          Int3 w{ i, j, k };
          ++w[a];
          const int x = v.at(i, j, k), y = v.at(w[0], w[1], w[2]);
          if (x == y || (x != L && y != L))
            continue;
          double d2 = 0;
          const Int3 u{ i, j, k };
          for (int d = 0; d < 3; ++d)
          {
            const double lo = d == a ? u[d] + 1 : u[d], hi = u[d] + 1;
            const double e = std::max({ lo - p[d], 0.0, p[d] - hi });
            d2 += e * e;
          }
          best = std::min(best, d2);
        }
  return std::sqrt(best);
}

vbr::LabelBoundary extract(const LabelVolume& v,
  vbr::BoundaryCells cells,
  vbr::LabelNet* keep = nullptr)
{
  vbr::LabelNet net = vbr::buildLabelNet(v, {}, sequential);
  vbr::LabelBoundary b = vbr::assembleLabelBoundary(net, {}, cells, sequential);
  if (keep)
    *keep = std::move(net);
  return b;
}

/// Every property of each label's surface the brief asks for.
void checkLabelSurfaces(const LabelVolume& v,
  const Mesh& m,
  const std::string& what,
  bool triangles)
{
  std::set<int> present(v.labels.begin(), v.labels.end());
  present.insert(0);
  for (int L : present)
  {
    const auto cells = surfaceOf(m, L);
    ASSERT_FALSE(cells.empty()) << what << " label " << L;
    EXPECT_EQ(closedManifoldProblem(cells), "") << what << " label " << L;
    // The triangles (and the net) are free of self-intersections; polygons are only as
    // their cut into triangles (the fan VTK draws may fold where corners run straight).
    if (triangles)
      EXPECT_FALSE(selfIntersecting(m, cells)) << what << " label " << L;
    for (int k = 0; k < v.dims[2]; ++k)
      for (int j = 0; j < v.dims[1]; ++j)
        for (int i = 0; i < v.dims[0]; ++i)
          // Label 0 (the background) reaches infinity: its voxels are outside its surface.
          ASSERT_EQ(
            insideOf(m, cells, { i + .5, j + .5, k + .5 }), (v.at(i, j, k) == L) != (L == 0))
            << what << " label " << L << " voxel " << i << " " << j << " " << k;

    double worst = 0;
    for (const auto& c : cells)
      for (int p : c)
        worst = std::max(worst, distanceToLabelFaces(v, L, m.points[p]));
    EXPECT_LE(worst, std::sqrt(3.0) + 1e-9) << what << " label " << L;
  }
}

/// No cell twice (the same corners in any order); each cell between two different labels,
/// smaller first, so that it is in exactly two labels' surfaces: the shared surface of a and
/// b is the same cells seen from either side.
void checkSharedOnce(const Mesh& m, const std::string& what)
{
  std::set<std::vector<int>> seen;
  std::size_t inSurfaces = 0;
  std::set<int> labels;
  for (std::size_t c = 0; c < m.cells.size(); ++c)
  {
    std::vector<int> key = m.cells[c];
    std::sort(key.begin(), key.end());
    EXPECT_TRUE(seen.insert(key).second) << what << ": a cell emitted twice";
    EXPECT_LT(m.labels[c][0], m.labels[c][1]) << what;
    labels.insert(m.labels[c].begin(), m.labels[c].end());
  }
  for (int L : labels)
    inSurfaces += surfaceOf(m, L).size();
  EXPECT_EQ(inSurfaces, 2 * m.cells.size()) << what;
}

/// The net's faces against the voxel faces between different labels: each face once, with
/// its two labels (smaller first), its normal from the smaller label to the larger.
void checkNetFaces(const LabelVolume& v, const vbr::LabelNet& net)
{
  std::map<std::pair<Int3, int>, vbr::LabelPair> expected, found;
  for (int k = -1; k < v.dims[2]; ++k)
    for (int j = -1; j < v.dims[1]; ++j)
      for (int i = -1; i < v.dims[0]; ++i)
        for (int a = 0; a < 3; ++a)
        {
          Int3 w{ i, j, k };
          ++w[a];
          const int x = v.at(i, j, k), y = v.at(w[0], w[1], w[2]);
          if (x != y)
            expected[{ Int3{ i, j, k }, a }] = { std::min(x, y), std::max(x, y) };
        }
  // A polygon, or the fan of triangles a face of a blown-up vertex became (consecutive,
  // around one new point), gives its grid vertices and its area vector over them.
  for (std::size_t c = 0; c < net.polygonCount();)
  {
    std::size_t last = c + 1;
    const auto size = [&net](std::size_t x) { return net.offsets[x + 1] - net.offsets[x]; };
    if (size(c) == 3)
      while (last < net.polygonCount() && size(last) == 3 &&
        net.corners[net.offsets[last]] == net.corners[net.offsets[c]])
        ++last;
    std::set<Int3> vertices;
    Vec3 area{ 0, 0, 0 };
    for (std::size_t x = c; x < last; ++x)
    {
      const std::int64_t b = net.offsets[x], e = net.offsets[x + 1];
      for (std::int64_t i = b; i < e; ++i)
      {
        const auto& s = net.model.voxel[net.corners[i]];
        const auto& t = net.model.voxel[net.corners[i + 1 < e ? i + 1 : b]];
        vertices.insert(s);
        for (int d = 0; d < 3; ++d)
          area[d] += double(s[(d + 1) % 3] - t[(d + 1) % 3]) * (s[(d + 2) % 3] + t[(d + 2) % 3]);
      }
    }
    const vbr::LabelPair pair = net.labels[c];
    c = last;
    if (vertices.size() == 1)
      continue; // a patch of a blown-up vertex
    ASSERT_EQ(vertices.size(), 4u);
    Int3 lo = *vertices.begin(), hi = *vertices.rbegin();
    int axis = -1;
    for (int d = 0; d < 3; ++d)
      if (lo[d] == hi[d])
        axis = d;
    ASSERT_GE(axis, 0);
    Int3 u = lo;
    --u[axis];
    EXPECT_TRUE(found.insert({ { u, axis }, pair }).second) << "a face twice";
    // Orientation: the area vector over the grid vertices, from the smaller label's voxel.
    Int3 w = u;
    ++w[axis];
    const bool lowIsSmaller = v.at(u[0], u[1], u[2]) < v.at(w[0], w[1], w[2]);
    EXPECT_EQ(area[axis] > 0, lowIsSmaller) << "face orientation";
  }
  EXPECT_EQ(found, expected);
}

} // namespace

TEST(LabelNet, FacesBetweenLabelsOnceWithBothLabels)
{
  for (unsigned seed = 1; seed <= 12; ++seed)
  {
    const LabelVolume v = randomLabels(seed, 2 + seed % 4);
    vbr::LabelNet net;
    extract(v, vbr::BoundaryCells::Quadrilaterals, &net);
    checkNetFaces(v, net);
  }
}

TEST(LabelNet, EachLabelsNetIsClosedManifoldAndEnclosesItsVoxels)
{
  for (unsigned seed = 1; seed <= 12; ++seed)
  {
    const LabelVolume v = randomLabels(seed, 2 + seed % 4);
    const Mesh m = meshOf(extract(v, vbr::BoundaryCells::Quadrilaterals));
    const std::string what = "seed " + std::to_string(seed);
    checkSharedOnce(m, what);
    checkLabelSurfaces(v, m, what, true);
  }
}

TEST(LabelNet, EachLabelsBoundaryIsClosedManifoldAndEnclosesItsVoxels)
{
  for (auto cells : { vbr::BoundaryCells::Triangles, vbr::BoundaryCells::Polygons })
    for (unsigned seed = 1; seed <= 12; ++seed)
    {
      const LabelVolume v = randomLabels(seed, 2 + seed % 4);
      const Mesh m = meshOf(extract(v, cells));
      const std::string what = "seed " + std::to_string(seed) +
        (cells == vbr::BoundaryCells::Triangles ? " triangles" : " polygons");
      checkSharedOnce(m, what);
      checkLabelSurfaces(v, m, what, cells == vbr::BoundaryCells::Triangles);
    }
}
