// The exact separating axis test of two lattice hulls (hullsIntersect) and the flat hull
// thickened into a solid, which the pressing-in asks of its groups and regions
// (HullIntersection.h).
#include "HullIntersection.h"

#include "Geometry.h"
#include "LatticeBasis.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

/// A lattice vector v with n.v = 1 for a primitive normal n (extended Euclid, twice).
LatticePoint unitStep(const LatticePoint& n)
{
  std::int64_t a, b, c, e;
  std::int64_t g = signedExtendedGcd(n[0], n[1], a, b);
  const std::int64_t h = signedExtendedGcd(g, n[2], c, e);
  LatticePoint v{ c * a, c * b, e };
  if (h < 0)
  {
    v = { -v[0], -v[1], -v[2] };
  }
  return v;
}

/// Whether the hull's edges each have their two faces (a solid with its incidences) and its
/// normals are small enough for mayBeMinkowskiFace's products in 128 bits.
bool gaussArcsKnown(const CellList& c)
{
  if (c.dimension != 3 || c.edgeFaces.size() != c.edges.size())
    return false;
  for (const auto& ef : c.edgeFaces)
    if (ef[0] >= c.planes.size() || ef[1] >= c.planes.size())
      return false;
  for (const auto& plane : c.planes)
    for (std::int64_t n : plane.normal)
      if (n <= -(std::int64_t(1) << 30) || n >= (std::int64_t(1) << 30))
        return false;
  return true;
}

__int128 dot128(const std::array<__int128, 3>& u, const LatticePoint& v)
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

std::array<__int128, 3> cross128(const LatticePoint& u, const LatticePoint& v)
{
  return { __int128(u[1]) * v[2] - __int128(u[2]) * v[1],
    __int128(u[2]) * v[0] - __int128(u[0]) * v[2],
    __int128(u[0]) * v[1] - __int128(u[1]) * v[0] };
}

/// Whether an edge of A (faces of outward normals a1, a2) and one of B (b1, b2) may span a face
/// of the Minkowski difference A - B: the arc a1 a2 of A's Gauss map and the arc of -b1 -b2
/// cross (the test of Gregorius, "The Separating Axis Test between Convex Polyhedra", 2013).
/// Only such pairs give a separating axis that the face normals do not: a face of A - B is a
/// face of A, of -B, or spanned by two edges whose arcs cross inside both. Exact (integer signs),
/// and conservative: a pair whose arcs touch or lie on one great circle (a sign 0) is kept.
bool mayBeMinkowskiFace(const LatticePoint& a1,
  const LatticePoint& a2,
  const LatticePoint& b1,
  const LatticePoint& b2)
{
  const LatticePoint c{ -b1[0], -b1[1], -b1[2] }, d{ -b2[0], -b2[1], -b2[2] };
  const std::array<__int128, 3> bxa = cross128(a2, a1), dxc = cross128(d, c);
  const int cba = signOf(dot128(bxa, c)), dba = signOf(dot128(bxa, d)),
            adc = signOf(dot128(dxc, a1)), bdc = signOf(dot128(dxc, a2));
  if (cba == 0 || dba == 0 || adc == 0 || bdc == 0)
    return true;
  return cba * dba < 0 && adc * bdc < 0 && cba * bdc > 0;
}

} // namespace

bool hullsIntersect(const CellList& a, const CellList& b)
{
  // A corner of one inside the other answers first, since meeting hulls mostly overlap so.
  auto contains = [](const CellList& h, const CellList& o)
  {
    return std::any_of(o.vertices.begin(),
      o.vertices.end(),
      [&](const LatticePoint& p) { return hullContains(h, p); });
  };
  if (a.dimension == 3 && b.dimension == 3 && (contains(a, b) || contains(b, a)))
    return true;
  // The projections in 64 bits when |n_k| * |p_k| summed stays below 2^62 (every hull of a grid
  // of a few thousand voxels a side), else in 128.
  std::int64_t reach = 0;
  for (const auto* h : { &a, &b })
    for (const auto& p : h->vertices)
      for (std::int64_t c : p)
        reach = std::max(reach, std::abs(c));
  const std::int64_t smallNormal = (std::int64_t(1) << 62) / (3 * std::max<std::int64_t>(reach, 1));
  // Whether the projections of A and B on n are apart; B's corners stop the scan as soon as
  // their range overlaps A's (most axes tried do not separate).
  auto separatesIn = [&](const LatticePoint& n, auto zero)
  {
    using T = decltype(zero);
    const auto along = [&](const LatticePoint& p)
    { return T(n[0]) * p[0] + T(n[1]) * p[1] + T(n[2]) * p[2]; };
    T aLo = along(a.vertices[0]), aHi = aLo;
    for (const auto& p : a.vertices)
    {
      aLo = std::min(aLo, along(p));
      aHi = std::max(aHi, along(p));
    }
    T bLo = along(b.vertices[0]), bHi = bLo;
    for (const auto& p : b.vertices)
    {
      bLo = std::min(bLo, along(p));
      bHi = std::max(bHi, along(p));
      if (bLo <= aHi && aLo <= bHi)
        return false;
    }
    return aHi < bLo || bHi < aLo;
  };
  auto separates = [&](const LatticePoint& n)
  {
    if (n == LatticePoint{ 0, 0, 0 })
      return false;
    if (std::abs(n[0]) < smallNormal && std::abs(n[1]) < smallNormal &&
      std::abs(n[2]) < smallNormal)
      return separatesIn(n, std::int64_t(0));
    return separatesIn(n, __int128(0));
  };
  for (const auto& p : a.planes)
    if (separates(p.normal))
      return false;
  for (const auto& p : b.planes)
    if (separates(p.normal))
      return false;
  const bool arcs = gaussArcsKnown(a) && gaussArcsKnown(b);
  for (std::size_t i = 0; i < a.edges.size(); ++i)
    for (std::size_t j = 0; j < b.edges.size(); ++j)
    {
      const auto &ea = a.edges[i], &eb = b.edges[j];
      if (arcs &&
        !mayBeMinkowskiFace(a.planes[a.edgeFaces[i][0]].normal,
          a.planes[a.edgeFaces[i][1]].normal,
          b.planes[b.edgeFaces[j][0]].normal,
          b.planes[b.edgeFaces[j][1]].normal))
        continue;
      if (separates(cross(
            sub(a.vertices[ea[1]], a.vertices[ea[0]]), sub(b.vertices[eb[1]], b.vertices[eb[0]]))))
        return false;
    }
  return true;
}

namespace detail
{

bool solidHull(const std::vector<LatticePoint>& points,
  const CellList& parent,
  bool strict,
  CoplanarFaces coplanar,
  CellList& out)
{
  out = convexHull(points, coplanar);
  if (out.dimension == 3)
  {
    return true;
  }
  std::vector<LatticePoint> steps{ { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  if (out.dimension == 2)
  {
    steps.push_back(unitStep(out.planes[0].normal));
  }
  std::vector<LatticePoint> thick = points;
  for (const auto& p : points)
  {
    for (const auto& s : steps)
    {
      for (int sign : { -1, 1 })
      {
        const LatticePoint q{ p[0] + sign * s[0], p[1] + sign * s[1], p[2] + sign * s[2] };
        if (strict ? strictlyInside(parent, q) : hullContains(parent, q))
        {
          thick.push_back(q);
        }
      }
    }
  }
  out = convexHull(thick, coplanar);
  return out.dimension == 3;
}

bool missesACorner(const CellList& inside, const CellList& c)
{
  return std::any_of(c.vertices.begin(),
    c.vertices.end(),
    [&](const LatticePoint& p) { return !hullContains(inside, p); });
}

} // namespace detail

} // namespace vbr
