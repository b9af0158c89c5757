// The standard plane recognizer of the header, one octant of normals at a time.
//
// Each octant keeps its polygon of normals (reset starts from the triangle of the octant;
// applyPoints clips it lazily by the pair of points realizing a violating vertex's width:
// clip, measure). tryAdd runs in phases: the surfel orientations (addOrientations), the new
// points without repeats (collectFreshPoints), the fast path where the current plane takes
// them (takenByCurrentPlane), and the slow path (searchOctants) that clips a copy of every
// octant still alive, drops those without interior (hasInterior), and searches each for the
// integer normal of smallest omega (solve: omega level by level, n_x over the polygon's range,
// n_y bounded by every edge: rangeOfNy, each candidate checked by fits); adoptNormal keeps the
// result. All arithmetic is on integers; determinants use Wide.

#include "StandardPlane.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <numeric>
#include <utility>

namespace vbr
{

namespace
{

using Vec = std::array<std::int64_t, 3>;

/// Points may differ by less than this along every axis: it bounds every product below
/// (constraint normals < 2^17, polygon rays < 2^35, their dot products with points < 2^54,
/// determinants of three rays < 2^108).
constexpr std::int64_t CoordinateLimit = std::int64_t(1) << 16;
/// Largest omega searched for an integer normal.
constexpr std::int64_t MaximumOmega = std::int64_t(1) << 16;
/// Lattice candidates examined by one search before giving up (the face then stops growing
/// in that direction: a refusal is always safe).
constexpr std::int64_t SearchBudget = std::int64_t(1) << 18;

Vec primitive(Vec v)
{
  const std::int64_t g = std::gcd(std::gcd(std::llabs(v[0]), std::llabs(v[1])), std::llabs(v[2]));
  if (g > 1)
    for (std::int64_t& c : v)
      c /= g;
  return v;
}

Wide det(const Vec& a, const Vec& b, const Vec& c)
{
  return Wide(a[0]) * (Wide(b[1]) * c[2] - Wide(b[2]) * c[1]) -
    Wide(a[1]) * (Wide(b[0]) * c[2] - Wide(b[2]) * c[0]) +
    Wide(a[2]) * (Wide(b[0]) * c[1] - Wide(b[1]) * c[0]);
}

std::int64_t floorDiv(std::int64_t a, std::int64_t b) // b > 0
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

std::int64_t ceilDiv(std::int64_t a, std::int64_t b) // b > 0
{
  return -floorDiv(-a, b);
}

/// The normals n = (nx, ny, sigma_z (omega - sigma_x nx - sigma_y ny)) of the slice
/// sigma.n = omega inside the polygon of `edges` (strictly on the strict ones): every edge
/// bounds ny, to [yLo, yHi] (empty when yLo > yHi).
void rangeOfNy(const std::vector<Vec>& edges,
  const std::vector<char>& strict,
  const Vec& sigma,
  std::int64_t omega,
  std::int64_t nx,
  std::int64_t& yLo,
  std::int64_t& yHi)
{
  yLo = -MaximumOmega - 1;
  yHi = MaximumOmega + 1;
  for (std::size_t e = 0; e < edges.size() && yLo <= yHi; ++e)
  {
    const Vec& E = edges[e];
    const std::int64_t a = E[1] - E[2] * sigma[2] * sigma[1];
    const std::int64_t b = E[0] * nx + E[2] * sigma[2] * (omega - sigma[0] * nx);
    if (a == 0)
    {
      if (b < 0 || (strict[e] && b == 0))
        yLo = yHi + 1;
    }
    else if (a > 0) // a ny + b >= 0 (> 0)
      yLo = std::max(yLo, strict[e] ? floorDiv(-b, a) + 1 : ceilDiv(-b, a));
    else // ny <= b / -a (<)
      yHi = std::min(yHi, strict[e] ? ceilDiv(b, -a) - 1 : floorDiv(b, -a));
  }
}

Vec sigmaOf(const std::array<int, 3>& s)
{
  return { s[0], s[1], s[2] };
}

} // namespace

std::int64_t StandardPlane::omega() const
{
  return std::llabs(this->normal[0]) + std::llabs(this->normal[1]) + std::llabs(this->normal[2]);
}

void StandardPlaneRecognizer::reset()
{
  // Storage is kept from face to face: a recognizer is reset once per face.
  this->Points.clear();
  this->Keys.clear();
  this->Present = { 0, 0, 0 };
  this->Current = StandardPlane();
  for (int s = 0; s < 8; ++s)
  {
    Octant& o = this->Octants[s];
    o.sigma = { (s & 1) ? -1 : 1, (s & 2) ? -1 : 1, (s & 4) ? -1 : 1 };
    o.vertices.clear();
    o.edges.clear();
    o.octantEdge.clear();
    o.applied = 0;
    // The triangle sigma.n = 1, sigma_d n_d >= 0; edge i lies on n_(i+2) = 0.
    for (int d = 0; d < 3; ++d)
    {
      Vertex v;
      v.ray = { 0, 0, 0 };
      v.ray[d] = o.sigma[d];
      v.lo = v.hi = 0;
      v.argLo = v.argHi = 0;
      o.vertices.push_back(v);
      Vec e{ 0, 0, 0 };
      e[(d + 2) % 3] = o.sigma[(d + 2) % 3];
      o.edges.push_back(e);
      o.octantEdge.push_back(1);
    }
    this->Alive[s] = true;
  }
}

void StandardPlaneRecognizer::measure(Vertex& v, std::size_t count) const
{
  v.lo = v.hi = 0;
  v.argLo = v.argHi = 0;
  for (std::size_t j = 0; j < count; ++j)
  {
    const std::int64_t x = dot(v.ray, this->Points[j]);
    if (j == 0 || x < v.lo)
      v.lo = x, v.argLo = static_cast<std::uint32_t>(j);
    if (j == 0 || x > v.hi)
      v.hi = x, v.argHi = static_cast<std::uint32_t>(j);
  }
}

bool StandardPlaneRecognizer::clip(Octant& o, const Vec& h, std::size_t count) const
{
  ++this->Clips;
  const std::size_t n = o.vertices.size();
  std::vector<std::int64_t> f(n);
  bool anyNegative = false, anyNonNegative = false;
  for (std::size_t i = 0; i < n; ++i)
  {
    f[i] = dot(h, o.vertices[i].ray);
    anyNegative = anyNegative || f[i] < 0;
    anyNonNegative = anyNonNegative || f[i] >= 0;
  }
  if (!anyNegative)
    return true;
  if (!anyNonNegative)
  {
    o.vertices.clear();
    o.edges.clear();
    o.octantEdge.clear();
    return false;
  }
  const Vec sigma = sigmaOf(o.sigma);
  std::vector<Vertex> vertices;
  std::vector<Vec> edges;
  std::vector<char> octantEdge;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t j = (i + 1) % n;
    if (f[i] >= 0)
    {
      vertices.push_back(o.vertices[i]);
      const bool leaving = f[i] == 0 && f[j] < 0;
      edges.push_back(leaving ? h : o.edges[i]);
      octantEdge.push_back(leaving ? 0 : o.octantEdge[i]);
    }
    if ((f[i] > 0 && f[j] < 0) || (f[i] < 0 && f[j] > 0))
    {
      Vertex v;
      v.ray = primitive(cross(o.edges[i], h));
      if (dot(sigma, v.ray) < 0)
        for (std::int64_t& c : v.ray)
          c = -c;
      this->measure(v, count);
      vertices.push_back(v);
      const bool leaving = f[i] > 0;
      edges.push_back(leaving ? h : o.edges[i]);
      octantEdge.push_back(leaving ? 0 : o.octantEdge[i]);
    }
  }
  o.vertices.swap(vertices);
  o.edges.swap(edges);
  o.octantEdge.swap(octantEdge);
  return true;
}

bool StandardPlaneRecognizer::applyPoints(Octant& o) const
{
  const Vec sigma = sigmaOf(o.sigma);
  for (std::size_t j = o.applied; j < this->Points.size(); ++j)
  {
    const Point3& p = this->Points[j];
    for (Vertex& v : o.vertices)
    {
      const std::int64_t x = dot(v.ray, p);
      if (j == 0 || x < v.lo)
        v.lo = x, v.argLo = static_cast<std::uint32_t>(j);
      if (j == 0 || x > v.hi)
        v.hi = x, v.argHi = static_cast<std::uint32_t>(j);
    }
    // Cut every vertex whose width exceeds 1 by the pair of points realizing it.
    for (;;)
    {
      const Vertex* violating = nullptr;
      for (const Vertex& v : o.vertices)
        if (v.hi - v.lo > dot(sigma, v.ray))
        {
          violating = &v;
          break;
        }
      if (!violating)
        break;
      const Point3& q = this->Points[violating->argHi];
      const Point3& r = this->Points[violating->argLo];
      const Vec h{ sigma[0] - (q[0] - r[0]), sigma[1] - (q[1] - r[1]), sigma[2] - (q[2] - r[2]) };
      if (!this->clip(o, h, j + 1))
        return false;
    }
  }
  o.applied = this->Points.size();
  return true;
}

bool StandardPlaneRecognizer::fits(const Vec& n, const std::array<int, 3>& present) const
{
  for (int d = 0; d < 3; ++d)
    if (present[d] != 0 && present[d] * n[d] <= 0)
      return false;
  std::int64_t lo = 0, hi = 0;
  for (std::size_t j = 0; j < this->Points.size(); ++j)
  {
    const std::int64_t x = dot(n, this->Points[j]);
    lo = j == 0 ? x : std::min(lo, x);
    hi = j == 0 ? x : std::max(hi, x);
  }
  return hi - lo < std::llabs(n[0]) + std::llabs(n[1]) + std::llabs(n[2]);
}

bool StandardPlaneRecognizer::hasInterior(const Octant& o)
{
  const std::size_t n = o.vertices.size();
  if (n < 3)
    return false;
  for (std::size_t i = 0; i < n; ++i)
    if (det(o.vertices[i].ray, o.vertices[(i + 1) % n].ray, o.vertices[(i + 2) % n].ray) != 0)
      return true;
  return false;
}

bool StandardPlaneRecognizer::saturated(const Octant& o, std::size_t e) const
{
  const Vertex& u = o.vertices[e];
  const Vertex& v = o.vertices[(e + 1) % o.vertices.size()];
  const Vec sigma = sigmaOf(o.sigma);
  if (u.hi - u.lo < dot(sigma, u.ray) || v.hi - v.lo < dot(sigma, v.ray))
    return false;
  const Vec m{ u.ray[0] + v.ray[0], u.ray[1] + v.ray[1], u.ray[2] + v.ray[2] };
  std::int64_t lo = 0, hi = 0;
  for (std::size_t j = 0; j < this->Points.size(); ++j)
  {
    const std::int64_t x = dot(m, this->Points[j]);
    lo = j == 0 ? x : std::min(lo, x);
    hi = j == 0 ? x : std::max(hi, x);
  }
  return hi - lo >= dot(sigma, m);
}

bool StandardPlaneRecognizer::solve(const Octant& o,
  const std::array<int, 3>& present,
  std::int64_t omegaLimit,
  Vec& normal) const
{
  ++this->Searches;
  const Vec sigma = sigmaOf(o.sigma);
  // Every normal strictly inside the polygon fits (the width is convex, at most 1 on the
  // polygon, and 1 inside only if constant). On an octant edge, where n_d = 0 is allowed,
  // the width is convex along the edge too: it is exactly 1 inside the edge only when it is
  // 1 all along, and then no normal of that edge fits. Such edges are made strict, or the
  // search would measure every point for each of their lattice normals (up to the budget:
  // minutes on a large face).
  std::vector<char>& strict = this->StrictEdges;
  strict.assign(o.edges.size(), 0);
  for (std::size_t e = 0; e < o.edges.size(); ++e)
    strict[e] = !o.octantEdge[e] || this->saturated(o, e);
  // Range of n_x / omega over the polygon, as fractions.
  std::int64_t minNum = 0, minDen = 1, maxNum = 0, maxDen = 1;
  for (std::size_t i = 0; i < o.vertices.size(); ++i)
  {
    const std::int64_t num = o.vertices[i].ray[0], den = dot(sigma, o.vertices[i].ray);
    if (i == 0 || Wide(num) * minDen < Wide(minNum) * den)
      minNum = num, minDen = den;
    if (i == 0 || Wide(num) * maxDen > Wide(maxNum) * den)
      maxNum = num, maxDen = den;
  }
  std::int64_t budget = SearchBudget;
  for (std::int64_t omega = 1; omega <= omegaLimit && budget > 0; ++omega, --budget)
  {
    const std::int64_t xLo = ceilDiv(omega * minNum, minDen);
    const std::int64_t xHi = floorDiv(omega * maxNum, maxDen);
    for (std::int64_t nx = xLo; nx <= xHi && budget > 0; ++nx, --budget)
    {
      std::int64_t yLo, yHi;
      rangeOfNy(o.edges, strict, sigma, omega, nx, yLo, yHi);
      for (std::int64_t ny = yLo; ny <= yHi && budget > 0; ++ny, --budget)
      {
        const Vec n{ nx, ny, sigma[2] * (omega - sigma[0] * nx - sigma[1] * ny) };
        if (sigma[0] * n[0] < 0 || sigma[1] * n[1] < 0 || sigma[2] * n[2] < 0)
          continue;
        // A multiple k n of a normal n fits exactly when n does, and n came first.
        if (std::gcd(std::gcd(std::llabs(n[0]), std::llabs(n[1])), std::llabs(n[2])) > 1)
          continue;
        if (this->fits(n, present))
        {
          normal = n;
          return true;
        }
      }
    }
  }
  return false;
}

bool StandardPlaneRecognizer::known(std::uint64_t key) const
{
  return this->Keys.find(key) >= 0 ||
    std::binary_search(this->FreshKeys.begin(), this->FreshKeys.end(), key);
}

bool StandardPlaneRecognizer::tryAdd(const Point3* points,
  std::size_t count,
  const std::array<int, 3>& signs)
{
  std::array<int, 3> present = this->Present;
  if (!addOrientations(signs, present) || !this->collectFreshPoints(points, count))
    return false;
  if (this->takenByCurrentPlane(present))
    return true;
  // Slow path: clip the octants with the points already accepted (for good), then with the
  // new ones (on copies), and search each surviving octant for a normal.
  for (int i = 0; i < 8; ++i)
    this->Alive[i] = this->Alive[i] && this->applyPoints(this->Octants[i]);
  const std::size_t before = this->Points.size();
  this->Points.insert(this->Points.end(), this->Fresh.begin(), this->Fresh.end());
  std::array<bool, 8> survives{};
  Vec best{ 0, 0, 0 };
  const bool found = this->searchOctants(present, survives, best);
  this->Points.resize(before);
  if (!found)
    return false;
  this->commit(present);
  this->adoptNormal(best, survives);
  return true;
}

bool StandardPlaneRecognizer::addOrientations(const std::array<int, 3>& signs,
  std::array<int, 3>& present)
{
  for (int d = 0; d < 3; ++d)
  {
    if (signs[d] == 0)
      continue;
    if (present[d] == -signs[d])
      return false; // opposite surfel normals: no plane has both
    present[d] = signs[d];
  }
  return true;
}

bool StandardPlaneRecognizer::collectFreshPoints(const Point3* points, std::size_t count)
{
  if (this->Points.empty() && count > 0)
    this->Origin = points[0];
  // New points relative to the origin, without repeats.
  std::vector<Point3>& fresh = this->Fresh;
  fresh.clear();
  this->FreshKeys.clear();
  for (std::size_t i = 0; i < count; ++i)
  {
    const Point3 q = sub(points[i], this->Origin);
    for (int d = 0; d < 3; ++d)
      if (q[d] <= -CoordinateLimit / 2 || q[d] >= CoordinateLimit / 2)
        return false;
    if (this->Keys.find(packBiased(q)) < 0)
      fresh.push_back(q);
  }
  // Repeats within the call: sorted, kept once (their order does not matter).
  std::sort(fresh.begin(),
    fresh.end(),
    [](const Point3& a, const Point3& b) { return packBiased(a) < packBiased(b); });
  fresh.erase(std::unique(fresh.begin(), fresh.end()), fresh.end());
  for (const Point3& q : fresh)
    this->FreshKeys.push_back(packBiased(q));
  return true;
}

bool StandardPlaneRecognizer::takenByCurrentPlane(const std::array<int, 3>& present)
{
  if (this->Points.empty())
    return false;
  const Vec& n = this->Current.normal;
  for (int d = 0; d < 3; ++d)
    if (present[d] != 0 && present[d] * n[d] <= 0)
      return false;
  std::int64_t lo = this->CurrentLo, hi = this->CurrentHi;
  for (const Point3& q : this->Fresh)
  {
    const std::int64_t x = dot(n, q);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  if (hi - lo >= this->Current.omega())
    return false;
  this->commit(present);
  this->CurrentLo = lo;
  this->CurrentHi = hi;
  this->Current.mu = lo + dot(n, this->Origin);
  return true;
}

bool StandardPlaneRecognizer::octantExcluded(const Octant& o,
  const std::array<int, 3>& present) const
{
  for (int d = 0; d < 3; ++d)
    if (present[d] != 0 && present[d] != o.sigma[d])
      return true;
  // Two points differing by sigma have width exactly 1 in every normal of the octant.
  for (const Point3& q : this->Fresh)
    for (int s : { -1, 1 })
    {
      const Point3 r{ q[0] + s * o.sigma[0], q[1] + s * o.sigma[1], q[2] + s * o.sigma[2] };
      if (this->known(packBiased(r)))
        return true;
    }
  return false;
}

bool StandardPlaneRecognizer::searchOctants(const std::array<int, 3>& present,
  std::array<bool, 8>& survives,
  Vec& best)
{
  std::int64_t bestOmega = MaximumOmega + 1;
  for (int i = 0; i < 8; ++i)
  {
    const Octant& original = this->Octants[i];
    survives[i] = false;
    if (!this->Alive[i] || this->octantExcluded(original, present))
      continue;
    Octant& o = this->Trials[i];
    o = original; // reuses the trial's storage
    if (!this->applyPoints(o) || !hasInterior(o))
      continue;
    survives[i] = true;
    Vec n;
    if (this->solve(o, present, bestOmega - 1, n))
    {
      best = n;
      bestOmega = std::llabs(n[0]) + std::llabs(n[1]) + std::llabs(n[2]);
    }
  }
  return bestOmega <= MaximumOmega;
}

void StandardPlaneRecognizer::adoptNormal(const Vec& best, const std::array<bool, 8>& survives)
{
  for (int i = 0; i < 8; ++i)
  {
    // Octants the new points emptied, or whose signs they contradict, stay dead.
    this->Alive[i] = survives[i];
    if (survives[i])
    {
      std::swap(this->Octants[i], this->Trials[i]);
      this->Octants[i].applied = this->Points.size();
    }
  }
  this->Current.normal = best;
  this->CurrentLo = this->CurrentHi = dot(best, this->Points.front());
  for (const Point3& q : this->Points)
  {
    const std::int64_t x = dot(best, q);
    this->CurrentLo = std::min(this->CurrentLo, x);
    this->CurrentHi = std::max(this->CurrentHi, x);
  }
  this->Current.mu = this->CurrentLo + dot(best, this->Origin);
}

void StandardPlaneRecognizer::commit(const std::array<int, 3>& present)
{
  for (const Point3& q : this->Fresh)
  {
    this->Points.push_back(q);
    this->Keys.insert(packBiased(q));
  }
  this->Present = present;
}

} // namespace vbr
