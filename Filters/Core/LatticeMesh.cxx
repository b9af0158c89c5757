#include "LatticeMesh.h"

#include "Geometry.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fraction_traits.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>

namespace vbr
{
namespace
{

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
/// For the tests that only decide (closed, embedded, bounding a volume) on lattice points: the
/// coordinates are small integers, exact as doubles, and those tests use predicates only
/// (CGAL's self-intersection test constructs triangles and segments from the points as they
/// are, no new coordinates), which this kernel evaluates exactly; without the lazy exact
/// numbers of every point they cost a fraction (the whole-H checks were a tenth of the full
/// aneurism's time).
using PredicateKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using PredicateMesh = CGAL::Surface_mesh<PredicateKernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh toSurfaceMesh(const LatticeMesh& m)
{
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertices;
  vertices.reserve(m.points.size());
  for (const auto& p : m.points)
  {
    vertices.push_back(mesh.add_vertex(Kernel::Point_3(
      static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]))));
  }
  for (const auto& t : m.triangles)
  {
    mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  }
  return mesh;
}

/// The integer value of an exact number, or false when it has a fractional part. The lazy
/// number's interval decides first: a point interval is the exact value, and an interval holding
/// no integer rules one out. Only the rest (corners of the corefinement near a lattice point)
/// pays for the exact rational, which every corner of every Boolean's result is tested for.
bool integerValue(const Kernel::FT& value, std::int64_t& out)
{
  const std::pair<double, double> range = CGAL::to_interval(value);
  if (range.first == range.second && std::abs(range.first) < 0x1p52 &&
    std::floor(range.first) == range.first)
  {
    out = static_cast<std::int64_t>(range.first);
    return true;
  }
  if (std::floor(range.second) < range.first)
    return false;
  using Exact = std::decay_t<decltype(CGAL::exact(value))>;
  using Traits = CGAL::Fraction_traits<Exact>;
  const Exact exact = CGAL::exact(value);
  typename Traits::Numerator_type num, den;
  typename Traits::Decompose()(exact, num, den);
  if (den != 1)
  {
    return false;
  }
  out = static_cast<std::int64_t>(CGAL::to_double(num));
  return true;
}

bool isLattice(const Kernel::Point_3& p)
{
  std::int64_t q;
  return integerValue(p.x(), q) && integerValue(p.y(), q) && integerValue(p.z(), q);
}

/// Whether moving the source v of h onto its target u keeps every other triangle around v in
/// its plane, with its orientation and a positive area (the surface keeps its exact shape).
bool collapseKeepsShape(const Mesh& m, Mesh::Halfedge_index h)
{
  const Mesh::Vertex_index v = m.source(h), u = m.target(h);
  const Kernel::Point_3 &pv = m.point(v), &pu = m.point(u);
  for (auto f : CGAL::faces_around_target(m.opposite(h), m))
  {
    if (f == Mesh::null_face())
      return false;
    std::vector<Mesh::Vertex_index> corners;
    for (auto w : CGAL::vertices_around_face(m.halfedge(f), m))
      corners.push_back(w);
    if (std::find(corners.begin(), corners.end(), u) != corners.end())
      continue;
    while (corners[0] != v)
      std::rotate(corners.begin(), corners.begin() + 1, corners.end());
    const auto &a = m.point(corners[1]), &b = m.point(corners[2]);
    const Kernel::Vector_3 before = CGAL::cross_product(a - pv, b - pv);
    const Kernel::Vector_3 after = CGAL::cross_product(a - pu, b - pu);
    if (after == CGAL::NULL_VECTOR || CGAL::cross_product(before, after) != CGAL::NULL_VECTOR ||
      before * after <= 0)
      return false;
  }
  return true;
}

/// Whether two vertices lie at one point: pieces touching only there come out of the
/// corefinement that way, a closed 2-manifold combinatorially but not an embedded one. If that
/// point is off the lattice, removeSteinerPoints would delete both vertices and hide the
/// contact.
bool hasCoincidentVertices(const Mesh& m)
{
  std::vector<Kernel::Point_3> points;
  points.reserve(m.number_of_vertices());
  for (auto v : m.vertices())
    points.push_back(m.point(v));
  std::sort(points.begin(),
    points.end(),
    [](const Kernel::Point_3& a, const Kernel::Point_3& b)
    { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; });
  return std::adjacent_find(points.begin(), points.end()) != points.end();
}

/// Removes the corners that are not lattice points: the triangulations of coplanar pieces meet
/// at such points (diagonals crossing), which lie inside faces or on straight edges of the
/// true result; each is collapsed onto a neighbour when that keeps the shape exactly.
bool removeSteinerPoints(Mesh& m)
{
  for (bool progress = true; progress;)
  {
    progress = false;
    for (auto v : m.vertices())
    {
      if (isLattice(m.point(v)))
        continue;
      for (auto h : CGAL::halfedges_around_source(v, m))
      {
        if (!CGAL::Euler::does_satisfy_link_condition(m.edge(h), m) || !collapseKeepsShape(m, h))
          continue;
        const Kernel::Point_3 target = m.point(m.target(h));
        const auto kept = CGAL::Euler::collapse_edge(m.edge(h), m);
        m.point(kept) = target;
        progress = true;
        break;
      }
      if (progress)
        break;
    }
  }
  m.collect_garbage();
  for (auto v : m.vertices())
    if (!isLattice(m.point(v)))
      return false;
  return true;
}

} // namespace

void LatticeMesh::append(const LatticeMesh& other, bool reverse)
{
  const auto base = static_cast<std::uint32_t>(this->points.size());
  this->points.insert(this->points.end(), other.points.begin(), other.points.end());
  for (auto t : other.triangles)
  {
    if (reverse)
    {
      std::swap(t[1], t[2]);
    }
    this->triangles.push_back({ t[0] + base, t[1] + base, t[2] + base });
  }
}

LatticeMesh triangulateHull(const CellList& hull)
{
  LatticeMesh mesh;
  mesh.points = hull.vertices;
  for (const auto& face : hull.faces)
  {
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
    {
      mesh.triangles.push_back({ face[0], face[k], face[k + 1] });
    }
  }
  return mesh;
}

namespace
{

/// The mesh as a CGAL surface mesh; false when a triangle cannot be added (an edge used twice
/// the same way, or a non-manifold edge).
template<typename M>
bool toSurfaceMesh(const LatticeMesh& m, M& mesh)
{
  using Point = typename M::Point;
  std::vector<typename M::Vertex_index> vertices;
  vertices.reserve(m.points.size());
  for (const auto& p : m.points)
    vertices.push_back(mesh.add_vertex(
      Point(static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]))));
  for (const auto& t : m.triangles)
    if (mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == M::null_face())
      return false;
  return true;
}

template<typename M>
bool isClosedEmbedded(M& mesh)
{
  return CGAL::is_closed(mesh) && PMP::duplicate_non_manifold_vertices(mesh) == 0 &&
    !PMP::does_self_intersect(mesh);
}

} // namespace

bool isClosedEmbeddedManifold(const LatticeMesh& m)
{
  PredicateMesh mesh;
  return toSurfaceMesh(m, mesh) && isClosedEmbedded(mesh);
}

bool boundsAVolume(const LatticeMesh& m)
{
  PredicateMesh mesh;
  return toSurfaceMesh(m, mesh) && isClosedEmbedded(mesh) && PMP::does_bound_a_volume(mesh);
}

bool isEmbeddedWithin(const LatticeMesh& m, const LatticePoint& lo, const LatticePoint& hi)
{
  PredicateMesh mesh;
  std::map<std::uint32_t, PredicateMesh::Vertex_index> vertices;
  auto vertex = [&](std::uint32_t i)
  {
    auto it = vertices.find(i);
    if (it == vertices.end())
    {
      const auto& p = m.points[i];
      it = vertices
             .emplace(i,
               mesh.add_vertex(PredicateKernel::Point_3(
                 static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]))))
             .first;
    }
    return it->second;
  };
  for (const auto& t : m.triangles)
  {
    bool meets = true;
    for (int k = 0; k < 3 && meets; ++k)
      meets = std::max({ m.points[t[0]][k], m.points[t[1]][k], m.points[t[2]][k] }) >= lo[k] &&
        std::min({ m.points[t[0]][k], m.points[t[1]][k], m.points[t[2]][k] }) <= hi[k];
    if (meets &&
      mesh.add_face(vertex(t[0]), vertex(t[1]), vertex(t[2])) == PredicateMesh::null_face())
      return isClosedEmbeddedManifold(m); // a subset CGAL does not take: test the whole mesh
  }
  return !PMP::does_self_intersect(mesh);
}

namespace
{

/// `out` (a corefinement's result without its Steiner points) as a LatticeMesh: false when a
/// corner is not a lattice point or two corners coincide.
bool toLatticeMesh(const Mesh& out, LatticeMesh& result)
{
  result = LatticeMesh();
  // By the vertices' indices (removed ones included, out.vertices() skips them): a table, not
  // a map.
  std::vector<std::uint32_t> index(out.num_vertices());
  result.points.reserve(out.number_of_vertices());
  for (auto v : out.vertices())
  {
    const auto& p = out.point(v);
    LatticePoint q;
    if (!integerValue(p.x(), q[0]) || !integerValue(p.y(), q[1]) || !integerValue(p.z(), q[2]))
      return false;
    index[static_cast<std::size_t>(v)] = static_cast<std::uint32_t>(result.points.size());
    result.points.push_back(q);
  }
  // Pieces touching at a corner or along an edge can come out with that corner as two
  // vertices at one point: a closed 2-manifold combinatorially, but not an embedded one.
  std::vector<LatticePoint> sorted = result.points;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    return false;
  std::vector<std::uint32_t> corners;
  for (auto f : out.faces())
  {
    corners.clear();
    for (auto v : CGAL::vertices_around_face(out.halfedge(f), out))
      corners.push_back(index[static_cast<std::size_t>(v)]);
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      result.triangles.push_back({ corners[0], corners[k], corners[k + 1] });
  }
  return true;
}

CGAL::Bbox_3 toBbox(const LatticeBox& b)
{
  return CGAL::Bbox_3(static_cast<double>(b[0][0]),
    static_cast<double>(b[0][1]),
    static_cast<double>(b[0][2]),
    static_cast<double>(b[1][0]),
    static_cast<double>(b[1][1]),
    static_cast<double>(b[1][2]));
}

/// Whether the mesh self-intersects; with `changed`, among its faces that meet one of those
/// boxes only (the mesh being embedded elsewhere, see latticeDifference).
bool selfIntersects(const Mesh& m, const std::vector<LatticeBox>* changed)
{
  if (!changed)
    return PMP::does_self_intersect(m);
  if (changed->empty())
    return false;
  std::vector<CGAL::Bbox_3> boxes;
  CGAL::Bbox_3 all;
  for (const auto& b : *changed)
  {
    boxes.push_back(toBbox(b));
    all += boxes.back();
  }
  std::vector<Mesh::Face_index> near;
  for (auto f : m.faces())
  {
    CGAL::Bbox_3 faceBox;
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m))
      faceBox += m.point(v).bbox();
    if (CGAL::do_overlap(faceBox, all) &&
      std::any_of(boxes.begin(),
        boxes.end(),
        [&](const CGAL::Bbox_3& b) { return CGAL::do_overlap(faceBox, b); }))
      near.push_back(f);
  }
  return PMP::does_self_intersect(near, m);
}

/// The exact union or difference of two closed lattice meshes; false (never an exception)
/// when CGAL refuses the operands or the result is not a closed 2-manifold of lattice points.
bool latticeBoolean(const LatticeMesh& a,
  const LatticeMesh& b,
  bool unite,
  Operands operands,
  const std::vector<LatticeBox>* aChangedIn,
  const std::vector<LatticeBox>* bChangedIn,
  LatticeMesh& result)
{
  try
  {
    Mesh first = toSurfaceMesh(a), second = toSurfaceMesh(b), out;
    // The self-intersection test of a large operand costs about as much as the corefinement.
    const bool check = operands == Operands::Check;
    if (!CGAL::is_closed(first) || !CGAL::is_closed(second) ||
      (check && (selfIntersects(first, aChangedIn) || selfIntersects(second, bChangedIn))))
      return false; // not valid operands (corefinement needs two closed, embedded surfaces)
    const bool ok = unite ? PMP::corefine_and_compute_union(first, second, out)
                          : PMP::corefine_and_compute_difference(first, second, out);
    return ok && CGAL::is_closed(out) && PMP::duplicate_non_manifold_vertices(out) == 0 &&
      !hasCoincidentVertices(out) && removeSteinerPoints(out) && toLatticeMesh(out, result);
  }
  catch (const std::exception&)
  {
    return false;
  }
}

} // namespace

bool latticeDifference(const LatticeMesh& a,
  const LatticeMesh& b,
  LatticeMesh& result,
  Operands operands,
  const std::vector<LatticeBox>* aChangedIn,
  const std::vector<LatticeBox>* bChangedIn)
{
  return latticeBoolean(a, b, false, operands, aChangedIn, bChangedIn, result);
}

std::vector<LatticeBox> newTriangleBoxes(const LatticeMesh& before, const LatticeMesh& after)
{
  using Corners = std::array<LatticePoint, 3>;
  // Each triangle from its least corner on, so that one cyclic order gives one key.
  auto corners = [](const LatticeMesh& m, const std::array<std::uint32_t, 3>& t)
  {
    Corners c{ m.points[t[0]], m.points[t[1]], m.points[t[2]] };
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    return c;
  };
  std::vector<Corners> old;
  old.reserve(before.triangles.size());
  for (const auto& t : before.triangles)
    old.push_back(corners(before, t));
  std::sort(old.begin(), old.end());
  std::vector<LatticeBox> boxes;
  for (const auto& t : after.triangles)
  {
    const Corners c = corners(after, t);
    if (std::binary_search(old.begin(), old.end(), c))
      continue;
    LatticeBox box{ c[0], c[0] };
    for (const auto& p : c)
      for (int k = 0; k < 3; ++k)
      {
        box[0][k] = std::min(box[0][k], p[k]);
        box[1][k] = std::max(box[1][k], p[k]);
      }
    boxes.push_back(box);
  }
  return boxes;
}

bool latticeUnion(const LatticeMesh& a,
  const LatticeMesh& b,
  LatticeMesh& result,
  Operands operands)
{
  return latticeBoolean(a, b, true, operands, nullptr, nullptr, result);
}

namespace
{

using Point = Kernel::Point_3;
using Triangle = std::array<std::uint32_t, 3>;

/// The triangles of `a` whose closed box meets the box [lo, hi] (Q, `near`), the others (R).
void splitByBox(const LatticeMesh& a,
  const LatticeBox& box,
  std::vector<Triangle>& near,
  std::vector<Triangle>& far)
{
  for (const auto& t : a.triangles)
  {
    bool meets = true;
    for (int k = 0; k < 3 && meets; ++k)
    {
      const auto c = [&](int i) { return a.points[t[i]][k]; };
      meets =
        std::max({ c(0), c(1), c(2) }) >= box[0][k] && std::min({ c(0), c(1), c(2) }) <= box[1][k];
    }
    (meets ? near : far).push_back(t);
  }
}

/// The triangles as a CGAL mesh of the points they use; false when one cannot be added.
bool toSurfaceMesh(const LatticeMesh& a, const std::vector<Triangle>& triangles, Mesh& mesh)
{
  std::map<std::uint32_t, Mesh::Vertex_index> vertex;
  for (const auto& t : triangles)
    for (auto i : t)
      if (vertex.find(i) == vertex.end())
      {
        const auto& p = a.points[i];
        vertex[i] = mesh.add_vertex(
          Point(static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])));
      }
  for (const auto& t : triangles)
    if (mesh.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) == Mesh::null_face())
      return false;
  return true;
}

/// The planes of the convex hull's faces, each with the hull's interior on its negative side.
std::vector<Kernel::Plane_3> innerPlanes(const CellList& convex)
{
  Kernel::Vector_3 sum(0, 0, 0);
  for (const auto& v : convex.vertices)
    sum = sum + (Point(v[0], v[1], v[2]) - CGAL::ORIGIN);
  const Point centroid = CGAL::ORIGIN + sum / static_cast<int>(convex.vertices.size());
  std::vector<Kernel::Plane_3> planes;
  for (const auto& f : convex.faces)
  {
    const auto& a = convex.vertices[f[0]];
    const auto& b = convex.vertices[f[1]];
    const auto& c = convex.vertices[f[2]];
    Kernel::Plane_3 h(Point(a[0], a[1], a[2]), Point(b[0], b[1], b[2]), Point(c[0], c[1], c[2]));
    planes.push_back(h.oriented_side(centroid) == CGAL::ON_POSITIVE_SIDE ? h.opposite() : h);
  }
  return planes;
}

std::array<Point, 3> cornersOf(const Mesh& m, Mesh::Face_index f)
{
  std::array<Point, 3> c;
  int k = 0;
  for (auto v : CGAL::vertices_around_face(m.halfedge(f), m))
    c[k++] = m.point(v);
  return c;
}

/// Where a face of the corefined surface lies against the convex hull: on its boundary (the
/// index of the plane holding it, its orientation the plane's when `same`), or -1 apart from
/// its open interior; -2 when it enters that interior.
int faceOnHull(const std::array<Point, 3>& c,
  const std::vector<Kernel::Plane_3>& planes,
  bool& same)
{
  int on = -1;
  for (std::size_t j = 0; j < planes.size(); ++j)
  {
    int zero = 0;
    for (const auto& p : c)
    {
      const auto side = planes[j].oriented_side(p);
      if (side == CGAL::ON_POSITIVE_SIDE)
        return -1; // a corner outside the closed hull: the face (not crossing it) is outside
      zero += side == CGAL::ON_ORIENTED_BOUNDARY;
    }
    if (zero == 3)
      on = static_cast<int>(j);
  }
  if (on < 0)
    return -2;
  const Kernel::Vector_3 n = CGAL::cross_product(c[1] - c[0], c[2] - c[0]);
  same = n * planes[on].orthogonal_vector() > 0;
  return on;
}

/// The kept faces of both corefined meshes (the hull's reversed for a difference) as one
/// polygon soup of exact points; false when the configuration is not the one the local
/// Boolean assumes (a face inside the hull, no contact, or a contact with the wrong
/// orientation).
bool keptFaces(const Mesh& q,
  const Mesh& p,
  const std::vector<Kernel::Plane_3>& planes,
  bool unite,
  std::vector<std::array<Point, 3>>& kept)
{
  // Union: the hull lies outside the solid, so where they touch their normals are opposite;
  // difference: inside it, the same. There both surfaces cancel.
  std::vector<Kernel::Triangle_3> contact;
  for (auto f : q.faces())
  {
    const auto c = cornersOf(q, f);
    bool same = false;
    const int on = faceOnHull(c, planes, same);
    if (on == -2 || (on >= 0 && same == unite))
      return false;
    if (on >= 0)
      contact.emplace_back(c[0], c[1], c[2]);
    else
      kept.push_back(c);
  }
  for (auto f : p.faces())
  {
    auto c = cornersOf(p, f);
    const Point centroid = CGAL::centroid(c[0], c[1], c[2]);
    if (std::any_of(contact.begin(),
          contact.end(),
          [&](const Kernel::Triangle_3& t) { return t.has_on(centroid); }))
      continue;
    if (!unite)
      std::swap(c[1], c[2]);
    kept.push_back(c);
  }
  // Without a contact the side of the hull is not known here (nor a join made).
  return !contact.empty();
}

/// The polygon soup as a mesh, equal points one vertex; false when a face cannot be added (an
/// edge of more than two faces or used twice the same way).
bool soupToMesh(const std::vector<std::array<Point, 3>>& soup, Mesh& mesh)
{
  std::vector<Point> points;
  for (const auto& c : soup)
    points.insert(points.end(), c.begin(), c.end());
  const auto less = [](const Point& a, const Point& b)
  { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; };
  std::sort(points.begin(), points.end(), less);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::vector<Mesh::Vertex_index> vertex;
  for (const auto& p : points)
    vertex.push_back(mesh.add_vertex(p));
  const auto index = [&](const Point& p)
  { return vertex[std::lower_bound(points.begin(), points.end(), p, less) - points.begin()]; };
  for (const auto& c : soup)
    if (mesh.add_face(index(c[0]), index(c[1]), index(c[2])) == Mesh::null_face())
      return false;
  return true;
}

/// Whether an edge of the soup bounds more than two faces, or two faces on one side (by the
/// order of its ends): then no triangulation of these faces is a 2-manifold.
bool nonManifoldEdge(const std::vector<std::array<Point, 3>>& soup)
{
  const auto less = [](const Point& a, const Point& b)
  { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; };
  std::vector<std::pair<Point, Point>> directed, undirected;
  for (const auto& c : soup)
    for (int k = 0; k < 3; ++k)
    {
      const Point &a = c[k], &b = c[(k + 1) % 3];
      directed.emplace_back(a, b);
      undirected.push_back(less(a, b) ? std::make_pair(a, b) : std::make_pair(b, a));
    }
  const auto pairLess = [&](const std::pair<Point, Point>& x, const std::pair<Point, Point>& y)
  { return less(x.first, y.first) || (x.first == y.first && less(x.second, y.second)); };
  std::sort(directed.begin(), directed.end(), pairLess);
  std::sort(undirected.begin(), undirected.end(), pairLess);
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end())
    return true;
  for (std::size_t i = 0; i + 2 < undirected.size(); ++i)
    if (undirected[i] == undirected[i + 2])
      return true;
  return false;
}

/// Whether every vertex of the mesh that is not a corner of `border` has one closed fan of
/// faces around it (two pieces touching at a point share a vertex with two fans).
bool manifoldInside(const Mesh& m, const std::vector<LatticePoint>& border)
{
  std::map<Mesh::Vertex_index, std::size_t> faces;
  for (auto f : m.faces())
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m))
      ++faces[v];
  for (const auto& [v, count] : faces)
  {
    LatticePoint q;
    const Point& p = m.point(v);
    if (integerValue(p.x(), q[0]) && integerValue(p.y(), q[1]) && integerValue(p.z(), q[2]) &&
      std::binary_search(border.begin(), border.end(), q))
      continue;
    std::size_t fan = 0;
    for (auto f : CGAL::faces_around_target(m.halfedge(v), m))
    {
      if (f == Mesh::null_face())
        return false;
      ++fan;
    }
    if (fan != count)
      return false;
  }
  return true;
}

/// The number of closed fans around a vertex whose link edges (for a face v, b, c the edge
/// b -> c) are `next`: its cycles, or 0 when a chain of the link is open (an open fan).
std::size_t closedFans(const std::map<std::ptrdiff_t, std::ptrdiff_t>& next)
{
  std::set<std::ptrdiff_t> seen;
  std::size_t cycles = 0;
  for (const auto& [start, unused] : next)
  {
    if (seen.count(start))
      continue;
    std::ptrdiff_t at = start;
    while (seen.insert(at).second)
    {
      const auto it = next.find(at);
      if (it == next.end())
        return 0; // an open fan
      at = it->second;
    }
    if (at != start)
      return 0; // ran into another chain: not closed fans
    ++cycles;
  }
  return cycles;
}

/// Whether a vertex of the soup that is not a corner of `border` has its faces in two or more
/// closed fans: the links of its faces make two or more cycles. The soup is taken to have no
/// edge of three faces nor one used twice the same way (nonManifoldEdge); a vertex with an
/// open fan is not counted, the vertices after it still are.
bool twoFansInside(const std::vector<std::array<Point, 3>>& soup,
  const std::vector<LatticePoint>& border)
{
  const auto less = [](const Point& a, const Point& b)
  { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; };
  std::vector<Point> points;
  for (const auto& c : soup)
    points.insert(points.end(), c.begin(), c.end());
  std::sort(points.begin(), points.end(), less);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  const auto index = [&](const Point& p)
  { return std::lower_bound(points.begin(), points.end(), p, less) - points.begin(); };
  // Per vertex, its link edges b -> c.
  std::vector<std::map<std::ptrdiff_t, std::ptrdiff_t>> link(points.size());
  for (const auto& c : soup)
    for (int k = 0; k < 3; ++k)
      link[index(c[k])][index(c[(k + 1) % 3])] = index(c[(k + 2) % 3]);
  for (std::size_t v = 0; v < points.size(); ++v)
  {
    LatticePoint q;
    const Point& p = points[v];
    if (integerValue(p.x(), q[0]) && integerValue(p.y(), q[1]) && integerValue(p.z(), q[2]) &&
      std::binary_search(border.begin(), border.end(), q))
      continue;
    if (closedFans(link[v]) > 1)
      return true;
  }
  return false;
}

/// The directed edges of the triangles that no triangle of them runs the other way, by their
/// corners.
std::vector<std::array<LatticePoint, 2>> borderOf(const LatticeMesh& a,
  const std::vector<Triangle>& triangles)
{
  std::vector<std::array<LatticePoint, 2>> edges, border;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k)
      edges.push_back({ a.points[t[k]], a.points[t[(k + 1) % 3]] });
  std::sort(edges.begin(), edges.end());
  for (const auto& e : edges)
    if (!std::binary_search(edges.begin(), edges.end(), std::array<LatticePoint, 2>{ e[1], e[0] }))
      border.push_back(e);
  return border;
}

/// `far` (triangles of a) and the lattice mesh `changed` (what became of the triangles
/// `near`) together, points shared by their coordinates: a's points first, in a's order, those
/// no triangle uses any more dropped.
LatticeMesh stitch(const LatticeMesh& a,
  const std::vector<Triangle>& near,
  const std::vector<Triangle>& far,
  const LatticeMesh& changed)
{
  LatticeMesh out;
  out.points = a.points;
  std::map<LatticePoint, std::uint32_t> index; // a's points near, and the new ones
  for (const auto& t : near)
    for (auto i : t)
      index.emplace(a.points[i], i);
  const auto add = [&](const LatticePoint& p)
  {
    const auto it = index.emplace(p, static_cast<std::uint32_t>(out.points.size()));
    if (it.second)
      out.points.push_back(p);
    return it.first->second;
  };
  out.triangles = far;
  for (const auto& t : changed.triangles)
    out.triangles.push_back(
      { add(changed.points[t[0]]), add(changed.points[t[1]]), add(changed.points[t[2]]) });
  std::vector<std::uint32_t> renumber(out.points.size(), 0);
  for (const auto& t : out.triangles)
    for (auto i : t)
      renumber[i] = 1;
  if (std::find(renumber.begin(), renumber.end(), 0u) == renumber.end())
    return out; // every point still used: the compact mesh is this one
  LatticeMesh compact;
  for (std::size_t i = 0; i < out.points.size(); ++i)
    if (renumber[i])
    {
      renumber[i] = static_cast<std::uint32_t>(compact.points.size());
      compact.points.push_back(out.points[i]);
    }
  for (const auto& t : out.triangles)
    compact.triangles.push_back({ renumber[t[0]], renumber[t[1]], renumber[t[2]] });
  return compact;
}

/// The corefined neighbourhood's kept faces as a lattice mesh whose border is the
/// neighbourhood's (`border`, sorted), or why not (see latticeBooleanNear).
NearBoolean nearResult(const std::vector<std::array<Point, 3>>& soup,
  const std::vector<std::array<LatticePoint, 2>>& border,
  LatticeMesh& near)
{
  Mesh m;
  std::vector<LatticePoint> corners;
  for (const auto& e : border)
    corners.push_back(e[0]);
  std::sort(corners.begin(), corners.end());
  // A face CGAL's mesh cannot take may be the order of the faces only: the whole Boolean tells,
  // unless an edge has more than two faces or two on one side, or a vertex inside has two
  // closed fans of faces (the whole Boolean's result has these faces too; the last, on the
  // full aneurism, sent 22 of the joins' Booleans to the whole Boolean).
  if (!soupToMesh(soup, m))
    return nonManifoldEdge(soup) || twoFansInside(soup, corners) ? NearBoolean::Refused
                                                                 : NearBoolean::Unknown;
  // The whole Boolean's result has these faces near the hull (and a's others): two fans at a
  // point are refused there too; a corner off the lattice that no collapse removes was refused
  // there too wherever both were run (the greedy collapses may differ in order).
  if (!manifoldInside(m, corners) || !removeSteinerPoints(m) || !toLatticeMesh(m, near))
    return NearBoolean::Refused;
  std::vector<Triangle> all(near.triangles.begin(), near.triangles.end());
  return borderOf(near, all) == border ? NearBoolean::Done : NearBoolean::Unknown;
}

} // namespace

NearBoolean latticeBooleanNear(const LatticeMesh& a,
  const CellList& convex,
  bool unite,
  LatticeMesh& result)
{
  try
  {
    // The neighbourhood: a's triangles whose box meets the hull's box grown by one, so that
    // its border (edges of triangles out of that box) stays away from the hull.
    LatticeBox box{ convex.vertices[0], convex.vertices[0] };
    for (const auto& v : convex.vertices)
      for (int k = 0; k < 3; ++k)
      {
        box[0][k] = std::min(box[0][k], v[k] - 1);
        box[1][k] = std::max(box[1][k], v[k] + 1);
      }
    std::vector<Triangle> near, far;
    splitByBox(a, box, near, far);
    Mesh q, p = toSurfaceMesh(triangulateHull(convex));
    if (near.empty() || !toSurfaceMesh(a, near, q))
      return NearBoolean::Unknown;
    PMP::corefine(q, p);
    std::vector<std::array<Point, 3>> soup;
    LatticeMesh changed;
    if (!keptFaces(q, p, innerPlanes(convex), unite, soup))
      return NearBoolean::Unknown;
    const NearBoolean outcome = nearResult(soup, borderOf(a, near), changed);
    if (outcome == NearBoolean::Done)
      result = stitch(a, near, far, changed);
    return outcome;
  }
  catch (const std::exception&)
  {
    return NearBoolean::Unknown;
  }
}

namespace
{

LatticePoint minus(const LatticePoint& a, const LatticePoint& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

/// Sign of the volume of the tetrahedron abcd (exact: lattice coordinates below 2^20).
int orientation(const LatticePoint& a,
  const LatticePoint& b,
  const LatticePoint& c,
  const LatticePoint& d)
{
  const LatticePoint u = minus(b, a), v = minus(c, a), w = minus(d, a);
  const Wide det = static_cast<Wide>(u[0]) * (v[1] * w[2] - v[2] * w[1]) -
    static_cast<Wide>(u[1]) * (v[0] * w[2] - v[2] * w[0]) +
    static_cast<Wide>(u[2]) * (v[0] * w[1] - v[1] * w[0]);
  return (det > 0) - (det < 0);
}

/// Whether the segment ab crosses the open triangle t transversally (a and b strictly on
/// either side of its plane, the line through them strictly inside its edges) at a point that
/// is not a lattice point: a + s (b - a) with s = n.(t0 - a) / n.(b - a), exactly.
bool crossesOffLattice(const LatticePoint& a,
  const LatticePoint& b,
  const std::array<LatticePoint, 3>& t)
{
  const int sa = orientation(t[0], t[1], t[2], a), sb = orientation(t[0], t[1], t[2], b);
  if (sa == 0 || sb == 0 || sa == sb)
    return false;
  const int s0 = orientation(a, b, t[0], t[1]), s1 = orientation(a, b, t[1], t[2]),
            s2 = orientation(a, b, t[2], t[0]);
  if (s0 == 0 || s0 != s1 || s1 != s2)
    return false;
  const LatticePoint u = minus(t[1], t[0]), v = minus(t[2], t[0]), e = minus(b, a),
                     w = minus(t[0], a);
  const LatticePoint n{
    u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
  };
  Wide num = 0, den = 0;
  for (int k = 0; k < 3; ++k)
  {
    num += static_cast<Wide>(n[k]) * w[k];
    den += static_cast<Wide>(n[k]) * e[k];
  }
  for (int k = 0; k < 3; ++k)
    if ((num * e[k]) % den != 0)
      return true;
  return false;
}

} // namespace

std::vector<std::array<LatticePoint, 3>> trianglesInBoxOf(const LatticeMesh& surface,
  const CellList& convex)
{
  LatticePoint lo = convex.vertices[0], hi = lo;
  for (const auto& v : convex.vertices)
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], v[a]);
      hi[a] = std::max(hi[a], v[a]);
    }
  std::vector<std::array<LatticePoint, 3>> inBox;
  for (const auto& tri : surface.triangles)
  {
    const std::array<LatticePoint, 3> t{
      surface.points[tri[0]], surface.points[tri[1]], surface.points[tri[2]]
    };
    bool meets = true;
    for (int a = 0; a < 3 && meets; ++a)
      meets = std::max({ t[0][a], t[1][a], t[2][a] }) > lo[a] &&
        std::min({ t[0][a], t[1][a], t[2][a] }) < hi[a];
    if (meets)
      inBox.push_back(t);
  }
  return inBox;
}

bool booleanLeavesTheLattice(const LatticeMesh& surface, const CellList& convex)
{
  for (const auto& t : trianglesInBoxOf(surface, convex))
    for (const auto& e : convex.edges)
      if (crossesOffLattice(convex.vertices[e[0]], convex.vertices[e[1]], t))
        return true;
  return false;
}

namespace
{

/// Whether a + (num / den) e is off the lattice, for a lattice point a (den != 0).
bool offLatticeAt(const LatticePoint& e, Wide num, Wide den)
{
  for (int k = 0; k < 3; ++k)
    if ((num * e[k]) % den != 0)
      return true;
  return false;
}

/// A parameter num / den of a line, den > 0.
struct Fraction
{
  Wide num = 0;
  Wide den = 0; ///< 0: unbounded
};

bool less(const Fraction& x, const Fraction& y)
{
  return x.num * y.den < y.num * x.den;
}

/// Whether the segment ab (a crease of a mesh) enters or leaves the open interior of the
/// solid hull at a point strictly between a and b that is not a lattice point. The line
/// a + t (b - a) lies in the open interior for t in the open interval (lo, hi) of the hull's
/// half spaces; when that is not empty, the line enters at lo and leaves at hi, from strictly
/// outside the closed hull (the half space giving the bound is left strictly) to strictly
/// inside, wherever on the hull's surface that is (a face, an edge or a corner).
bool segmentEntersOffLattice(const LatticePoint& a, const LatticePoint& b, const CellList& hull)
{
  const LatticePoint e = minus(b, a);
  Fraction lo, hi;
  for (const FacePlane& plane : hull.planes)
  {
    // n.(a + t e) < d: t (n.e) < d - n.a.
    const Wide slope = static_cast<Wide>(plane.normal[0]) * e[0] +
      static_cast<Wide>(plane.normal[1]) * e[1] + static_cast<Wide>(plane.normal[2]) * e[2];
    const Wide room = -plane.evaluate(a);
    // less() multiplies two of these: beyond 2^62 it could overflow, so the test gives up
    // (false only costs the Boolean this test would have spared; grids of 2^19 voxels stay
    // far below).
    constexpr Wide Limit = Wide(1) << 62;
    if (slope >= Limit || slope <= -Limit || room >= Limit || room <= -Limit)
      return false;
    if (slope == 0)
    {
      if (room <= 0)
        return false; // the line misses the open half space
      continue;
    }
    const Fraction bound = slope > 0 ? Fraction{ room, slope } : Fraction{ -room, -slope };
    if (slope > 0 && (hi.den == 0 || less(bound, hi)))
      hi = bound;
    if (slope < 0 && (lo.den == 0 || less(lo, bound)))
      lo = bound;
  }
  if (lo.den == 0 || hi.den == 0 || !less(lo, hi))
    return false;
  for (const Fraction& t : { lo, hi })
    if (t.num > 0 && t.num < t.den && offLatticeAt(e, t.num, t.den))
      return true;
  return false;
}

/// The outward normal of the triangle abc (counter-clockwise seen from outside).
LatticePoint normalOf(const LatticePoint& a, const LatticePoint& b, const LatticePoint& c)
{
  const LatticePoint u = minus(b, a), v = minus(c, a);
  return { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
}

Wide dot(const LatticePoint& a, const LatticePoint& b)
{
  return static_cast<Wide>(a[0]) * b[0] + static_cast<Wide>(a[1]) * b[1] +
    static_cast<Wide>(a[2]) * b[2];
}

/// An edge ab of a closed mesh with its two triangles' outward normals and whether it is
/// convex (the solid about it the intersection of their inner half spaces), reflex (their
/// union) or flat (coplanar triangles).
struct MeshEdge
{
  LatticePoint a, b, nt, nu;
  int convexity = 0; ///< 1 convex, -1 reflex, 0 flat
};

/// Whether moving from a point of the open edge along d goes strictly into the solid about
/// the edge (1), strictly out of it (-1), or neither (0: along one of its half planes).
int sideAlong(const MeshEdge& edge, const LatticePoint& d)
{
  const int st = signOf(dot(edge.nt, d)), su = signOf(dot(edge.nu, d));
  if (edge.convexity == 0)
    return -st;
  if (edge.convexity > 0)
    return st < 0 && su < 0 ? 1 : st > 0 || su > 0 ? -1 : 0;
  return st < 0 || su < 0 ? 1 : st > 0 && su > 0 ? -1 : 0;
}

/// Whether the segment pq crosses the open edge of the mesh at a point strictly inside both
/// that is not a lattice point.
bool edgesCrossOffLattice(const LatticePoint& p, const LatticePoint& q, const MeshEdge& edge)
{
  const LatticePoint d = minus(q, p);
  if (orientation(p, q, edge.a, edge.b) != 0)
    return false; // the lines do not meet
  const LatticePoint pa = normalOf(edge.a, edge.b, p), qa = normalOf(edge.a, edge.b, q);
  const LatticePoint ap = normalOf(p, q, edge.a), bp = normalOf(p, q, edge.b);
  if (dot(pa, qa) >= 0 || dot(ap, bp) >= 0)
    return false;
  const LatticePoint& n = dot(edge.nt, d) != 0 ? edge.nt : edge.nu;
  const Wide den = dot(n, d), num = dot(n, minus(edge.a, p));
  return den != 0 && offLatticeAt(d, num, den);
}

/// Whether the segment pq (an edge of a solid hull) crosses the open edge of the mesh at a
/// point strictly inside both that is not a lattice point, going from strictly outside the
/// mesh's solid about the edge to strictly inside (either way along pq).
bool hullEdgeCrossesOffLattice(const LatticePoint& p, const LatticePoint& q, const MeshEdge& edge)
{
  if (!edgesCrossOffLattice(p, q, edge))
    return false;
  const LatticePoint d = minus(q, p), back{ -d[0], -d[1], -d[2] };
  const int forward = sideAlong(edge, d), backward = sideAlong(edge, back);
  return (forward > 0 && backward < 0) || (forward < 0 && backward > 0);
}

/// The edges of the triangles of `surface` that meet the open box of the hull's vertices, as
/// edges between two triangles (a crossing point lies in the box, so both triangles of its edge
/// are there, or the edge is left out), with their convexity (1 convex, -1 reflex, 0
/// flat).
std::vector<MeshEdge> meshEdgesInOpenBox(const LatticeMesh& surface, const CellList& convex)
{
  LatticePoint lo = convex.vertices[0], hi = lo;
  for (const auto& v : convex.vertices)
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], v[a]);
      hi[a] = std::max(hi[a], v[a]);
    }
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edges;
  for (std::size_t i = 0; i < surface.triangles.size(); ++i)
  {
    const auto& tri = surface.triangles[i];
    bool meets = true;
    for (int a = 0; a < 3 && meets; ++a)
    {
      const auto c = [&](int k) { return surface.points[tri[k]][a]; };
      meets = std::max({ c(0), c(1), c(2) }) > lo[a] && std::min({ c(0), c(1), c(2) }) < hi[a];
    }
    for (int k = 0; k < 3 && meets; ++k)
      edges[std::minmax(tri[k], tri[(k + 1) % 3])].push_back(i);
  }
  std::vector<MeshEdge> meshEdges;
  for (const auto& [ends, incident] : edges)
  {
    if (incident.size() != 2)
      continue;
    const auto& t = surface.triangles[incident[0]];
    const auto& u = surface.triangles[incident[1]];
    const std::uint32_t apex = u[0] != ends.first && u[0] != ends.second ? u[0]
      : u[1] != ends.first && u[1] != ends.second                        ? u[1]
                                                                         : u[2];
    const auto point = [&](std::uint32_t i) -> const LatticePoint& { return surface.points[i]; };
    MeshEdge edge;
    edge.a = point(ends.first);
    edge.b = point(ends.second);
    edge.nt = normalOf(point(t[0]), point(t[1]), point(t[2]));
    edge.nu = normalOf(point(u[0]), point(u[1]), point(u[2]));
    // The apex of u below t's plane: the solid about the edge is the wedge under both.
    edge.convexity = -orientation(point(t[0]), point(t[1]), point(t[2]), point(apex));
    meshEdges.push_back(edge);
  }
  return meshEdges;
}

} // namespace

bool creaseLeavesTheLattice(const LatticeMesh& surface, const CellList& convex)
{
  if (convex.dimension != 3)
    return false; // a flat hull takes nothing away and adds no volume
  for (const MeshEdge& edge : meshEdgesInOpenBox(surface, convex))
  {
    if (edge.convexity != 0 && segmentEntersOffLattice(edge.a, edge.b, convex))
      return true;
    for (const auto& e : convex.edges)
      if (hullEdgeCrossesOffLattice(convex.vertices[e[0]], convex.vertices[e[1]], edge))
        return true;
  }
  return false;
}

namespace
{

/// A ray from the crossing point of an edge of the mesh and an edge of the hull, along one of
/// the two edges: whether the result of the Boolean has a crease along it (1), has none (0), or
/// that is not known here (-1).
struct Ray
{
  LatticePoint direction;
  int crease = -1;
};

/// The rays along the mesh's crease edge and the hull's edge from their crossing point. Along
/// the mesh's crease: outside the hull the result is the mesh's solid (a crease), inside it is
/// all solid (union) or none (difference). Along the hull's edge: inside the mesh's solid the
/// difference is the hull's complement (a crease) and the union all solid; outside it the
/// union is the hull (a crease) and the difference empty. On a face of the other: not known.
std::array<Ray, 4> raysAt(const MeshEdge& mesh, const MeshEdge& hull, bool unite)
{
  const LatticePoint f = minus(mesh.b, mesh.a), d = minus(hull.b, hull.a);
  std::array<Ray, 4> rays{
    Ray{ f }, Ray{ { -f[0], -f[1], -f[2] } }, Ray{ d }, Ray{ { -d[0], -d[1], -d[2] } }
  };
  for (int k = 0; k < 2; ++k)
  {
    const int side = sideAlong(hull, rays[k].direction);
    rays[k].crease = side < 0 ? 1 : side > 0 ? 0 : -1;
  }
  for (int k = 2; k < 4; ++k)
  {
    const int side = sideAlong(mesh, rays[k].direction);
    rays[k].crease = side == 0 ? -1 : (side > 0) != unite ? 1 : 0;
  }
  return rays;
}

/// Whether the creases of the result about the crossing point cannot lie on one line through
/// it (they would, were the point inside a face or a straight edge of the result): a crease
/// along a ray whose opposite ray has none, or creases along both edges' lines.
bool creasesMakeACorner(const std::array<Ray, 4>& rays)
{
  for (int k = 0; k < 4; ++k)
    if (rays[k].crease == 1 && rays[k ^ 1].crease == 0)
      return true;
  const bool meshLine = rays[0].crease == 1 || rays[1].crease == 1;
  const bool hullLine = rays[2].crease == 1 || rays[3].crease == 1;
  return meshLine && hullLine;
}

} // namespace

bool edgeCrossingLeavesTheLattice(const LatticeMesh& surface, const CellList& convex, bool unite)
{
  if (convex.dimension != 3 || convex.edgeFaces.size() != convex.edges.size())
    return false; // no solid, or no faces known for its edges: nothing decided here
  // The hull's edges as edges of a convex solid: the outward normals of their two faces.
  std::vector<MeshEdge> hullEdges;
  for (std::size_t e = 0; e < convex.edges.size(); ++e)
  {
    MeshEdge h;
    h.a = convex.vertices[convex.edges[e][0]];
    h.b = convex.vertices[convex.edges[e][1]];
    h.nt = convex.planes[convex.edgeFaces[e][0]].normal;
    h.nu = convex.planes[convex.edgeFaces[e][1]].normal;
    h.convexity = 1;
    hullEdges.push_back(h);
  }
  for (const MeshEdge& edge : meshEdgesInOpenBox(surface, convex))
  {
    if (edge.convexity == 0)
      continue; // a flat edge: creaseLeavesTheLattice's rule is the whole answer there
    for (const MeshEdge& h : hullEdges)
      if (edgesCrossOffLattice(h.a, h.b, edge) && creasesMakeACorner(raysAt(edge, h, unite)))
        return true;
  }
  return false;
}

} // namespace vbr
