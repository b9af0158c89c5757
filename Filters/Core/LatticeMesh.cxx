#include "LatticeMesh.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Fraction_traits.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>

namespace vbr
{
namespace
{

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
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

/// The integer value of an exact number, or false when it has a fractional part.
bool integerValue(const Kernel::FT& value, std::int64_t& out)
{
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

bool isClosedEmbeddedManifold(const LatticeMesh& m)
{
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertices;
  for (const auto& p : m.points)
    vertices.push_back(mesh.add_vertex(Kernel::Point_3(
      static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]))));
  for (const auto& t : m.triangles)
    if (mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == Mesh::null_face())
      return false;
  return CGAL::is_closed(mesh) && PMP::duplicate_non_manifold_vertices(mesh) == 0 &&
    !PMP::does_self_intersect(mesh);
}

bool isEmbeddedWithin(const LatticeMesh& m, const LatticePoint& lo, const LatticePoint& hi)
{
  Mesh mesh;
  std::map<std::uint32_t, Mesh::Vertex_index> vertices;
  auto vertex = [&](std::uint32_t i)
  {
    auto it = vertices.find(i);
    if (it == vertices.end())
    {
      const auto& p = m.points[i];
      it = vertices
             .emplace(i,
               mesh.add_vertex(Kernel::Point_3(
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
    if (meets && mesh.add_face(vertex(t[0]), vertex(t[1]), vertex(t[2])) == Mesh::null_face())
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
  std::map<Mesh::Vertex_index, std::uint32_t> index;
  for (auto v : out.vertices())
  {
    const auto& p = out.point(v);
    LatticePoint q;
    if (!integerValue(p.x(), q[0]) || !integerValue(p.y(), q[1]) || !integerValue(p.z(), q[2]))
      return false;
    index[v] = static_cast<std::uint32_t>(result.points.size());
    result.points.push_back(q);
  }
  // Pieces touching at a corner or along an edge can come out with that corner as two
  // vertices at one point: a closed 2-manifold combinatorially, but not an embedded one.
  std::vector<LatticePoint> sorted = result.points;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    return false;
  for (auto f : out.faces())
  {
    std::vector<std::uint32_t> corners;
    for (auto v : CGAL::vertices_around_face(out.halfedge(f), out))
      corners.push_back(index[v]);
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      result.triangles.push_back({ corners[0], corners[k], corners[k + 1] });
  }
  return true;
}

/// The exact union or difference of two closed lattice meshes; false (never an exception)
/// when CGAL refuses the operands or the result is not a closed 2-manifold of lattice points.
bool latticeBoolean(const LatticeMesh& a,
  const LatticeMesh& b,
  bool unite,
  Operands operands,
  LatticeMesh& result)
{
  try
  {
    Mesh first = toSurfaceMesh(a), second = toSurfaceMesh(b), out;
    // The self-intersection test of a large operand costs about as much as the corefinement.
    const bool check = operands == Operands::Check;
    if (!CGAL::is_closed(first) || !CGAL::is_closed(second) ||
      (check && (PMP::does_self_intersect(first) || PMP::does_self_intersect(second))))
      return false; // not valid operands (corefinement needs two closed, embedded surfaces)
    const bool ok = unite ? PMP::corefine_and_compute_union(first, second, out)
                          : PMP::corefine_and_compute_difference(first, second, out);
    return ok && CGAL::is_closed(out) && PMP::duplicate_non_manifold_vertices(out) == 0 &&
      removeSteinerPoints(out) && toLatticeMesh(out, result);
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
  Operands operands)
{
  return latticeBoolean(a, b, false, operands, result);
}

bool latticeUnion(const LatticeMesh& a,
  const LatticeMesh& b,
  LatticeMesh& result,
  Operands operands)
{
  return latticeBoolean(a, b, true, operands, result);
}

} // namespace vbr
