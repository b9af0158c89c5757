// H's planar faces, their loops and levels, and H's canonical order (HullFaces.h).
#include "HullFaces.h"

#include "UnionFind.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

/// Coplanar edge-connected triangles of H as its faces, with their boundary loops and levels.
/// The triangle on each directed edge (a, b) of a closed mesh, by key(a, b).
std::uint64_t edgeKey(Index a, Index b)
{
  return (std::uint64_t(a) << 32) | b;
}

/// The classes of edge-adjacent triangles on the same plane: the faces of the mesh.
UnionFind coplanarTriangles(const LatticeMesh& m,
  const std::vector<FacePlane>& planes,
  const std::unordered_map<std::uint64_t, Index>& owner)
{
  UnionFind faces(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
    {
      const auto& tri = m.triangles[t];
      auto it = owner.find(edgeKey(tri[(k + 1) % 3], tri[k]));
      if (it != owner.end() && planes[it->second] == planes[t])
        faces.unite(static_cast<std::uint32_t>(t), it->second);
    }
  return faces;
}

/// The boundary loops of a face from its boundary edges (next: a -> b), each once.
void traceLoops(std::multimap<Index, Index>& next, ModifiedFace& face)
{
  while (!next.empty())
  {
    std::vector<Index> loop{ next.begin()->first };
    Index at = next.begin()->second;
    next.erase(next.begin());
    while (at != loop.front())
    {
      loop.push_back(at);
      auto it = next.find(at);
      if (it == next.end())
        break;
      at = it->second;
      next.erase(it);
    }
    face.loops.push_back(loop);
  }
}

/// The outer loop first: the one of largest area along the normal.
void putOuterLoopFirst(const LatticeMesh& m, ModifiedFace& face)
{
  auto area = [&](const std::vector<Index>& loop)
  {
    LatticePoint sum{ 0, 0, 0 };
    for (std::size_t k = 0; k < loop.size(); ++k)
    {
      const LatticePoint c = cross(m.points[loop[k]], m.points[loop[(k + 1) % loop.size()]]);
      sum = { sum[0] + c[0], sum[1] + c[1], sum[2] + c[2] };
    }
    return dot(sum, face.plane.normal);
  };
  std::sort(face.loops.begin(),
    face.loops.end(),
    [&](const std::vector<Index>& a, const std::vector<Index>& b) { return area(a) > area(b); });
}

/// The loops of every face from the edges between its triangles and other faces'; the number
/// of distinct edges of the polyhedron.
std::size_t loopsOfFaces(const LatticeMesh& m,
  const std::unordered_map<std::uint64_t, Index>& owner,
  UnionFind& faceOf,
  std::vector<ModifiedFace>& faces)
{
  std::vector<std::pair<Index, Index>> edges;
  for (ModifiedFace& face : faces)
  {
    std::multimap<Index, Index> next;
    for (Index t : face.triangles)
      for (int k = 0; k < 3; ++k)
      {
        const Index a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
        auto it = owner.find(edgeKey(b, a));
        if (it == owner.end() || faceOf.find(it->second) != faceOf.find(t))
        {
          next.emplace(a, b);
          edges.push_back({ std::min(a, b), std::max(a, b) });
        }
      }
    traceLoops(next, face);
    putOuterLoopFirst(m, face);
  }
  std::sort(edges.begin(), edges.end());
  return static_cast<std::size_t>(std::unique(edges.begin(), edges.end()) - edges.begin());
}

/// Numbers the points of the surface in (x, y, z) order and the loops' corners following
/// (each loop from its least point, its cyclic order kept, the holes after the outer loop in
/// the order of their least point).
void numberPointsInOrder(ModifiedHull& r)
{
  std::vector<LatticePoint>& points = r.surface.points;
  std::vector<Index> byPoint(points.size());
  std::iota(byPoint.begin(), byPoint.end(), Index(0));
  std::sort(
    byPoint.begin(), byPoint.end(), [&](Index a, Index b) { return points[a] < points[b]; });
  std::vector<Index> newIndex(points.size());
  std::vector<LatticePoint> sorted(points.size());
  for (std::size_t k = 0; k < byPoint.size(); ++k)
  {
    newIndex[byPoint[k]] = static_cast<Index>(k);
    sorted[k] = points[byPoint[k]];
  }
  points = std::move(sorted);
  for (auto& t : r.surface.triangles)
    for (auto& corner : t)
      corner = newIndex[corner];
  for (ModifiedFace& face : r.faces)
  {
    for (auto& loop : face.loops)
    {
      for (auto& corner : loop)
        corner = newIndex[corner];
      std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    }
    if (face.loops.size() > 2)
      std::sort(face.loops.begin() + 1, face.loops.end());
  }
}

/// Triangles from their least corner (orientation kept) in the order of their corners, each
/// face's triangles in that order and the faces in the order of their first triangle.
void orderTrianglesAndFaces(ModifiedHull& r)
{
  auto& triangles = r.surface.triangles;
  for (auto& t : triangles)
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::vector<Index> byTriangle(triangles.size());
  std::iota(byTriangle.begin(), byTriangle.end(), Index(0));
  std::sort(byTriangle.begin(),
    byTriangle.end(),
    [&](Index a, Index b) { return triangles[a] < triangles[b]; });
  std::vector<Index> newIndex(triangles.size());
  std::vector<std::array<std::uint32_t, 3>> sorted(triangles.size());
  for (std::size_t k = 0; k < byTriangle.size(); ++k)
  {
    newIndex[byTriangle[k]] = static_cast<Index>(k);
    sorted[k] = triangles[byTriangle[k]];
  }
  triangles = std::move(sorted);
  for (ModifiedFace& face : r.faces)
  {
    for (auto& t : face.triangles)
      t = newIndex[t];
    std::sort(face.triangles.begin(), face.triangles.end());
  }
  std::sort(r.faces.begin(),
    r.faces.end(),
    [](const ModifiedFace& a, const ModifiedFace& b) { return a.triangles < b.triangles; });
}

/// Puts the surface and its faces in an order that depends only on their shape. The surface
/// comes out of CGAL's corefinement, whose vertex and face order follows the order in which its
/// box intersection reports pairs, and that breaks ties by the boxes' addresses
/// (ID_FROM_BOX_ADDRESS): the same points and faces in an order that changed with the heap
/// layout from one run to the next.
void putInCanonicalOrder(ModifiedHull& r)
{
  numberPointsInOrder(r);
  orderTrianglesAndFaces(r);
}

} // namespace

namespace detail
{

void mergeIntoFaces(const std::map<FacePlane, int>& planeLevel,
  const std::vector<int>& triangleLevel,
  ModifiedHull& r)
{
  const LatticeMesh& m = r.surface;
  const std::size_t nt = m.triangles.size();
  std::vector<FacePlane> planes(nt);
  std::unordered_map<std::uint64_t, Index> owner;
  for (std::size_t t = 0; t < nt; ++t)
  {
    const auto& tri = m.triangles[t];
    planes[t] = planeThrough(m.points[tri[0]], m.points[tri[1]], m.points[tri[2]]);
    for (int k = 0; k < 3; ++k)
      owner[edgeKey(tri[k], tri[(k + 1) % 3])] = static_cast<Index>(t);
  }
  UnionFind faceOf = coplanarTriangles(m, planes, owner);
  std::unordered_map<Index, Index> faceOfRoot;
  for (std::size_t t = 0; t < nt; ++t)
  {
    const Index root = faceOf.find(static_cast<std::uint32_t>(t));
    auto it = faceOfRoot.find(root);
    if (it == faceOfRoot.end())
    {
      it = faceOfRoot.emplace(root, static_cast<Index>(r.faces.size())).first;
      ModifiedFace face;
      face.plane = planes[t];
      if (triangleLevel.size() == nt)
        face.level = triangleLevel[t];
      else
      {
        auto level = planeLevel.find(planes[t]);
        face.level = level == planeLevel.end() ? -1 : level->second;
      }
      r.faces.push_back(face);
    }
    r.faces[it->second].triangles.push_back(static_cast<Index>(t));
  }
  r.edgeCount = loopsOfFaces(m, owner, faceOf, r.faces);
  putInCanonicalOrder(r);
}

} // namespace detail

} // namespace vbr
