#include "FaceOctreeBoundary.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

namespace vbr
{
namespace
{

inline __int128 turn(const Point2L& a, const Point2L& b, const Point2L& c)
{
  return (__int128)(b[0] - a[0]) * (c[1] - a[1]) - (__int128)(b[1] - a[1]) * (c[0] - a[0]);
}

/// Whether corner `at` of the piece turns left or goes straight.
bool convexAt(const std::vector<int>& piece, std::size_t at, const std::vector<Point2L>& c)
{
  const std::size_t n = piece.size();
  return turn(c[piece[(at + n - 1) % n]], c[piece[at]], c[piece[(at + 1) % n]]) >= 0;
}

/// Joins two pieces along their common edge a -> b (in `first`) / b -> a (in `second`).
std::vector<int> joined(const std::vector<int>& first, const std::vector<int>& second, int a, int b)
{
  std::vector<int> out;
  const std::size_t i = std::find(first.begin(), first.end(), a) - first.begin();
  const std::size_t j = std::find(second.begin(), second.end(), a) - second.begin();
  for (std::size_t k = 0; k < first.size(); ++k)
    out.push_back(first[(i + 1 + k) % first.size()]); // b ... a
  for (std::size_t k = 1; k + 1 < second.size(); ++k)
    out.push_back(second[(j + k) % second.size()]); // after a, before b, in second
  (void)b;
  return out;
}

int fanApex(const std::vector<Point2L>& flat);

struct Assembler
{
  const DeformedModel& model;
  const FaceOctree& octree;
  BoundaryMesh& mesh;
  std::vector<std::int32_t> outputId; ///< per model point, -1 until used

  std::int32_t pointFor(std::int32_t p, const Vec3& at)
  {
    if (this->outputId[p] < 0)
    {
      this->outputId[p] = std::int32_t(this->mesh.points.size());
      this->mesh.points.push_back(at);
      this->mesh.pointOf.push_back(p);
    }
    return this->outputId[p];
  }

  void addCell(const std::vector<std::int32_t>& modelPoints,
    std::int32_t node,
    int level,
    const std::vector<Vec3>& at)
  {
    for (std::int32_t p : modelPoints)
      this->mesh.connectivity.push_back(this->pointFor(p, at[p]));
    this->mesh.offsets.push_back(std::int64_t(this->mesh.connectivity.size()));
    this->mesh.faceNode.push_back(node);
    this->mesh.nodeLevel.push_back(level);
    if (modelPoints.size() == 3)
      ++this->mesh.triangles;
    if (node >= 0)
      ++this->mesh.polygons;
  }

  void addNodePolygon(std::int32_t id, BoundaryCells cells);
  void addSewingTriangles(const Quad& q);
};

void Assembler::addNodePolygon(std::int32_t id, BoundaryCells cells)
{
  const FaceNode& node = this->octree.nodes[id];
  const auto& loop = node.polygon;
  std::vector<Vec3> corners;
  for (std::int32_t p : loop)
    corners.push_back(this->octree.projected[p]);
  if (cells == BoundaryCells::Triangles)
  {
    for (const Triangle& t : polygonTriangles(node, corners))
      this->addCell({ loop[t[0]], loop[t[1]], loop[t[2]] }, id, node.level, this->octree.projected);
    return;
  }
  const auto flat = planeCoordinates(node, corners);
  std::vector<std::vector<int>> pieces;
  if (fanApex(flat) >= 0)
  {
    pieces.emplace_back(loop.size());
    std::iota(pieces.back().begin(), pieces.back().end(), 0);
  }
  else
    pieces = convexPieces(flat);
  // Each piece from the corner whose fan has no flat triangle if there is one.
  for (const auto& piece : pieces)
  {
    std::vector<Point2L> sub;
    for (int i : piece)
      sub.push_back(flat[i]);
    const int apex = std::max(0, fanApex(sub));
    std::vector<std::int32_t> ids;
    for (std::size_t k = 0; k < piece.size(); ++k)
      ids.push_back(loop[piece[(apex + k) % piece.size()]]);
    this->addCell(ids, id, node.level, this->octree.projected);
  }
}

void Assembler::addSewingTriangles(const Quad& q)
{
  const auto& at = this->octree.projected;
  auto normal = [&](std::int32_t a, std::int32_t b, std::int32_t c)
  {
    Vec3 u, v;
    for (int d = 0; d < 3; ++d)
      u[d] = at[b][d] - at[a][d], v[d] = at[c][d] - at[a][d];
    return Vec3{ u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
  };
  // The quadrilateral's mean normal (the sum of its two splits' is the same); each split's
  // triangles measured along it: the diagonal whose smaller signed triangle is the larger
  // keeps both triangles facing out (the other folds where the quadrilateral is concave).
  const Vec3 a = normal(q[0], q[1], q[2]), b = normal(q[0], q[2], q[3]);
  const Vec3 c = normal(q[0], q[1], q[3]), d = normal(q[1], q[2], q[3]);
  const Vec3 n{ a[0] + b[0], a[1] + b[1], a[2] + b[2] };
  auto along = [&n](const Vec3& x) { return x[0] * n[0] + x[1] * n[1] + x[2] * n[2]; };
  if (std::min(along(a), along(b)) >= std::min(along(c), along(d)))
  {
    this->addCell({ q[0], q[1], q[2] }, -1, -1, at);
    this->addCell({ q[0], q[2], q[3] }, -1, -1, at);
  }
  else
  {
    this->addCell({ q[0], q[1], q[3] }, -1, -1, at);
    this->addCell({ q[1], q[2], q[3] }, -1, -1, at);
  }
}

/// A corner whose fan covers the polygon, preferring one with no flat triangle; -1 if none.
int fanApex(const std::vector<Point2L>& flat)
{
  const std::size_t n = flat.size();
  int covering = -1;
  for (std::size_t apex = 0; apex < n; ++apex)
  {
    if (!fanCoversPolygon(flat, apex))
      continue;
    bool strict = true;
    for (std::size_t i = 1; i + 1 < n && strict; ++i)
      strict = turn(flat[apex], flat[(apex + i) % n], flat[(apex + i + 1) % n]) > 0;
    if (strict)
      return int(apex);
    if (covering < 0)
      covering = int(apex);
  }
  return covering;
}

} // namespace

std::vector<std::vector<int>> convexPieces(const std::vector<Point2L>& corners)
{
  std::vector<std::vector<int>> pieces;
  for (const Triangle& t : triangulateSimplePolygon(corners))
    pieces.push_back({ t[0], t[1], t[2] });
  const int n = int(corners.size());
  // Directed edge -> piece, kept up to date as pieces merge (a merged piece is left empty):
  // one map for all the merges, not one a merge (large polygons have hundreds of pieces).
  std::map<std::pair<int, int>, std::size_t> owner;
  for (std::size_t i = 0; i < pieces.size(); ++i)
    for (std::size_t k = 0; k < pieces[i].size(); ++k)
      owner[{ pieces[i][k], pieces[i][(k + 1) % pieces[i].size()] }] = i;
  for (bool merged = true; merged;)
  {
    merged = false;
    for (const auto& entry : owner)
    {
      const int a = entry.first.first, b = entry.first.second;
      if ((b - a + n) % n == 1 || (a - b + n) % n == 1)
        continue; // a polygon edge
      const auto other = owner.find({ b, a });
      if (other == owner.end() || other->second == entry.second)
        continue; // a diagonal already removed
      std::vector<int> j = joined(pieces[entry.second], pieces[other->second], a, b);
      const std::size_t ia = std::find(j.begin(), j.end(), a) - j.begin();
      const std::size_t ib = std::find(j.begin(), j.end(), b) - j.begin();
      if (!convexAt(j, ia, corners) || !convexAt(j, ib, corners))
        continue;
      const std::size_t keep = std::min(entry.second, other->second);
      const std::size_t drop = std::max(entry.second, other->second);
      pieces[keep] = std::move(j);
      pieces[drop].clear();
      for (std::size_t k = 0; k < pieces[keep].size(); ++k)
        owner[{ pieces[keep][k], pieces[keep][(k + 1) % pieces[keep].size()] }] = keep;
      owner[{ a, b }] = keep; // the removed diagonal, both ways, now inside one piece
      owner[{ b, a }] = keep;
      merged = true;
    }
  }
  pieces.erase(std::remove_if(
                 pieces.begin(), pieces.end(), [](const std::vector<int>& p) { return p.empty(); }),
    pieces.end());
  return pieces;
}

BoundaryMesh assembleBoundary(const DeformedModel& model,
  const FaceOctree& octree,
  BoundaryCells cells)
{
  BoundaryMesh mesh;
  Assembler as{ model, octree, mesh, std::vector<std::int32_t>(model.pointCount(), -1) };
  if (cells == BoundaryCells::Quadrilaterals)
  {
    for (const Quad& q : model.quads)
      as.addCell({ q[0], q[1], q[2], q[3] }, -1, -1, model.position);
    return mesh;
  }
  for (std::size_t id = 0; id < octree.nodes.size(); ++id)
    if (!octree.nodes[id].polygon.empty())
      as.addNodePolygon(std::int32_t(id), cells);
  for (const Quad& q : model.quads)
  {
    const std::int32_t node = octree.nodeOf[q[0]];
    if (node >= 0 && octree.nodeOf[q[1]] == node && octree.nodeOf[q[2]] == node &&
      octree.nodeOf[q[3]] == node)
      continue; // inside its node's polygon
    as.addSewingTriangles(q);
  }
  return mesh;
}

double maximumDistanceToSurfels(const BitVolume& object,
  const std::vector<Vec3>& points,
  const Execution& exec)
{
  return maximumOverPoints(
    points, [&object](const Vec3& p) { return distanceToSurfels(object, p); }, exec);
}

} // namespace vbr
