// The standard plane recognizer of the header, one octant of normals at a time.
//
// Each octant keeps its polygon of normals (reset starts from the triangle of the octant;
// applyPoints clips it lazily by the pair of points realizing a violating vertex's width:
// clip, measure). tryAdd runs in phases: the surfel orientations (addOrientations), the new
// points without repeats (collectFreshPoints), the fast path where the current plane takes
// them (takenByCurrentPlane), and the slow path (searchOctants) that clips a copy of every
// octant still alive, drops those without interior (hasInterior), and searches each for the
// integer normal of smallest omega (solve: the strict edges, markStrictEdges, the polygon on
// the slices, sliceThePolygon, then omega level by level, searchLevel: columns
// k = u.(n_x, n_y) over the polygon's range in a thin frame, thinFrame, and t along each
// column bounded by every edge, rangeOfT; each candidate checked by fits); adoptNormal keeps
// the result. Every range over the points (measure, rangeOf) reads only the points that may
// be vertices of their hull (forEachExtreme; refreshExtremes drops the midpoints of two
// others once a face has 128 points). All arithmetic that decides is on integers;
// determinants and column bounds use Wide. A face's first call, read relative to its first
// point, is repeated from the record of an earlier face's first call of the same shape
// (firstCallFromRecord), and so is the slow path of a later call after the same calls
// (laterCallFromRecord, along the face's CallPath); reset puts each octant's triangle back only
// when a slow path first clips it (restoreOctant).

#include "StandardPlane.h"
#include "StandardPlaneColumns.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numeric>
#include <tuple>
#include <type_traits>
#include <utility>

namespace vbr
{

namespace
{

using Vec = std::array<std::int64_t, 3>;
using detail::ceilDiv;
using detail::ColumnRange;
using detail::floorDiv;
using detail::levelColumns;
using detail::MaximumOmega;
using detail::rangeOfT;

/// Points may differ by less than this along every axis: it bounds every product below
/// (constraint normals < 2^17, polygon rays < 2^35, their dot products with points < 2^54,
/// determinants of three rays < 2^108).
constexpr std::int64_t CoordinateLimit = std::int64_t(1) << 16;
/// Lattice candidates examined by one search before giving up (the face then stops growing
/// in that direction: a refusal is always safe).
constexpr std::int64_t SearchBudget = std::int64_t(1) << 18;
/// Faces of fewer points measure them all: the midpoints would cost more than they save.
constexpr std::size_t ExtremesFrom = 128;
/// The point index a reset keeps holds this many points without growing (see reset).
constexpr std::size_t KeptIndexPoints = 32;
/// Calls of at most this many points insert their fresh points in order instead of sorting.
constexpr std::size_t SmallCall = 16;

/// At most this many slow paths of later calls are recorded per recognizer (CallPath).
constexpr std::size_t LaterCallsKept = 16384;
constexpr std::size_t LaterTableSize = 2 * LaterCallsKept; // a power of 2
constexpr std::uint32_t NoRecord = 0xFFFFFFFFu;

/// Writes a call as bytes from `bytes` on: its point count, its orientations, then its points
/// relative to `origin`, a byte per coordinate (the records' keys and paths). False when a point
/// lies farther than 127 from the origin along an axis.
bool writeCallBytes(std::uint8_t* bytes,
  const Point3* points,
  std::size_t count,
  const std::array<int, 3>& signs,
  const Point3& origin)
{
  bytes[0] = static_cast<std::uint8_t>(count);
  for (int d = 0; d < 3; ++d)
    bytes[1 + d] = static_cast<std::uint8_t>(signs[d]);
  std::size_t at = 4;
  for (std::size_t i = 0; i < count; ++i)
    for (int d = 0; d < 3; ++d)
    {
      const std::int64_t offset = std::int64_t(points[i][d]) - origin[d];
      if (offset < -127 || offset > 127)
        return false;
      bytes[at++] = static_cast<std::uint8_t>(offset);
    }
  return true;
}

Vec primitive(Vec v)
{
  // A component of +-1 makes the vector primitive already: the common case of the clips, and
  // three gcds of rays up to 2^35 cost more than the rest of a clip.
  if (std::llabs(v[0]) == 1 || std::llabs(v[1]) == 1 || std::llabs(v[2]) == 1)
    return v;
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

/// Lattice coordinates of the slice in which a polygon is thin along the first one: the
/// integer (nx, ny) with u.(nx, ny) = k are k a + t v for every integer t (u primitive,
/// u.a = 1, v = (-u_y, u_x)). Any such frame has the same lattice points as (nx, ny); a thin
/// one has few columns k per level.
struct ColumnFrame
{
  std::array<std::int64_t, 2> u{ 1, 0 }, a{ 1, 0 }, v{ 0, 1 };
};

/// Reduction stops before a basis vector gets this long (the frame then is merely less thin).
constexpr std::int64_t FrameLimit = std::int64_t(1) << 20;
/// Levels below this one are scanned in the frame of (n_x, n_y); most searches end there, and
/// a thin frame is computed only for those that go on.
constexpr std::int64_t ThinFrameLevel = 6;
/// From ThinFrameLevel on, a level of at most this many columns in the frame of (n_x, n_y) is
/// still scanned in it: a thin frame would save at most this many columns minus one, and
/// finding it costs more than a few columns.
constexpr std::int64_t ThinFrameColumns = 4;

ColumnRange columnRange(const std::vector<Vec>& rays, const Vec& sigma, const ColumnFrame& frame)
{
  ColumnRange r;
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    const std::int64_t num = frame.u[0] * rays[i][0] + frame.u[1] * rays[i][1];
    const std::int64_t den = dot(sigma, rays[i]);
    if (i == 0 || Wide(num) * r.minDen < Wide(r.minNum) * den)
      r.minNum = num, r.minDen = den;
    if (i == 0 || Wide(num) * r.maxDen > Wide(r.maxNum) * den)
      r.maxNum = num, r.maxDen = den;
  }
  return r;
}

/// Width of the polygon of `rays` (on the slice sigma.n = 1, in (nx, ny)) along u: half the
/// sum of |u.e| over its edges e. Floating point only chooses the frame, never the result.
double widthAlong(const std::vector<std::array<double, 2>>& edges,
  const std::array<std::int64_t, 2>& u)
{
  double w = 0;
  for (const auto& e : edges)
    w += std::fabs(double(u[0]) * e[0] + double(u[1]) * e[1]);
  return w / 2;
}

/// The integer mu minimizing the width along b2 - mu b1: the width is convex and piecewise
/// linear in mu, least at the weighted median of the edges' breakpoints.
std::int64_t bestShift(const std::vector<std::array<double, 2>>& edges,
  const std::array<std::int64_t, 2>& b1,
  const std::array<std::int64_t, 2>& b2,
  std::vector<std::pair<double, double>>& breaks)
{
  breaks.clear(); // (breakpoint, weight)
  double total = 0;
  for (const auto& e : edges)
  {
    const double d = double(b1[0]) * e[0] + double(b1[1]) * e[1];
    const double c = double(b2[0]) * e[0] + double(b2[1]) * e[1];
    if (d != 0)
      breaks.emplace_back(c / d, std::fabs(d)), total += std::fabs(d);
  }
  if (breaks.empty())
    return 0;
  std::sort(breaks.begin(), breaks.end());
  double sum = 0, median = breaks.back().first;
  for (const auto& [at, weight] : breaks)
    if ((sum += weight) >= total / 2)
    {
      median = at;
      break;
    }
  const double limit = double(FrameLimit);
  median = std::max(-limit, std::min(limit, median));
  auto widthAt = [&](std::int64_t mu) {
    return widthAlong(edges, { b2[0] - mu * b1[0], b2[1] - mu * b1[1] });
  };
  const std::int64_t lo = std::int64_t(std::floor(median)), hi = lo + 1;
  return widthAt(lo) <= widthAt(hi) ? lo : hi;
}

/// x, y with a x + b y = gcd(a, b) = 1 (a, b coprime).
std::array<std::int64_t, 2> bezout(std::int64_t a, std::int64_t b)
{
  std::int64_t r0 = a, r1 = b, x0 = 1, x1 = 0, y0 = 0, y1 = 1;
  while (r1 != 0)
  {
    const std::int64_t q = r0 / r1;
    std::tie(r0, r1) = std::make_pair(r1, r0 - q * r1);
    std::tie(x0, x1) = std::make_pair(x1, x0 - q * x1);
    std::tie(y0, y1) = std::make_pair(y1, y0 - q * y1);
  }
  return r0 < 0 ? std::array<std::int64_t, 2>{ -x0, -y0 } : std::array<std::int64_t, 2>{ x0, y0 };
}

/// The frame whose first coordinate is a shortest lattice vector for the polygon's width
/// norm (Gauss's reduction, which finds one for any norm of the plane): the polygon's lattice
/// width. Every level omega then has at most omega * width + 1 columns.
ColumnFrame thinFrame(const std::vector<Vec>& rays,
  const Vec& sigma,
  std::vector<std::array<double, 2>>& edges,
  std::vector<std::pair<double, double>>& breaks)
{
  edges.clear();
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    const Vec& p = rays[i];
    const Vec& q = rays[(i + 1) % rays.size()];
    const double sp = double(dot(sigma, p)), sq = double(dot(sigma, q));
    edges.push_back({ q[0] / sq - p[0] / sp, q[1] / sq - p[1] / sp });
  }
  std::array<std::int64_t, 2> b1{ 1, 0 }, b2{ 0, 1 };
  if (widthAlong(edges, b1) > widthAlong(edges, b2))
    std::swap(b1, b2);
  for (int step = 0; step < 64; ++step)
  {
    const std::int64_t mu = bestShift(edges, b1, b2, breaks);
    const std::array<std::int64_t, 2> c{ b2[0] - mu * b1[0], b2[1] - mu * b1[1] };
    if (std::llabs(c[0]) >= FrameLimit || std::llabs(c[1]) >= FrameLimit ||
      widthAlong(edges, c) >= widthAlong(edges, b1))
      break;
    b2 = b1;
    b1 = c;
  }
  ColumnFrame f;
  f.u = b1; // primitive: a basis vector of the lattice
  f.a = bezout(b1[0], b1[1]);
  f.v = { -b1[1], b1[0] };
  return f;
}

/// The half-plane of normals of a polygon edge in the coordinates (nx, ny, omega) of the
/// slices: alpha nx + beta ny + gamma omega >= 0 (> 0 when strict).
std::array<std::int64_t, 3> sliceForm(const Vec& E, const Vec& sigma)
{
  return { E[0] - E[2] * sigma[2] * sigma[0], E[1] - E[2] * sigma[2] * sigma[1], E[2] * sigma[2] };
}

/// The slices' edge forms F in frame f: along = F.(v, 0), across = F.(a, 0), level = F_omega
/// (each below 2^39: forms < 2^18, frames < 2^20).
template<typename Form>
void frameForms(const std::vector<std::array<std::int64_t, 3>>& forms,
  const std::vector<char>& strict,
  const ColumnFrame& f,
  std::vector<Form>& out)
{
  out.resize(forms.size());
  for (std::size_t e = 0; e < forms.size(); ++e)
  {
    const auto& F = forms[e];
    out[e] = { F[0] * f.v[0] + F[1] * f.v[1], F[0] * f.a[0] + F[1] * f.a[1], F[2], strict[e] != 0 };
  }
}

constexpr std::int64_t SmallColumn = std::int64_t(1) << 20;

Vec sigmaOf(const std::array<int, 3>& s)
{
  return { s[0], s[1], s[2] };
}

/// Whether a lattice normal n of a level must be measured: in the octant, before the best
/// found so far in (nx, ny) order, and primitive.
bool worthTesting(const Vec& n, const Vec& sigma, bool found, const Vec& best)
{
  if (sigma[0] * n[0] < 0 || sigma[1] * n[1] < 0 || sigma[2] * n[2] < 0)
    return false;
  if (found && (n[0] > best[0] || (n[0] == best[0] && n[1] >= best[1])))
    return false;
  // A multiple k n of a normal n fits exactly when n does, and n came first.
  return std::gcd(std::gcd(std::llabs(n[0]), std::llabs(n[1])), std::llabs(n[2])) == 1;
}

/// Columns kLo..kHi of level omega of an octant's search (each bounded by the polygon's
/// edges, rangeOfT): the normal of smallest (nx, ny) that fits, into `normal`, found set when
/// one does. K: std::int64_t when every k and omega are below SmallColumn, else Wide.
template<typename K, typename Form, typename Fits>
void searchColumns(const std::vector<Form>& forms,
  const Vec& sigma,
  const ColumnFrame& frame,
  std::int64_t omega,
  K kLo,
  K kHi,
  std::int64_t& budget,
  Vec& normal,
  bool& found,
  const Fits& fits)
{
  for (K k = kLo; k <= kHi && budget > 0; ++k, --budget)
  {
    std::int64_t tLo, tHi;
    if constexpr (std::is_same_v<K, std::int64_t>) // searchLevel checked the bounds
      rangeOfT(forms, omega, k, tLo, tHi);
    else if (-SmallColumn < k && k < SmallColumn && omega < SmallColumn)
      rangeOfT(forms, omega, std::int64_t(k), tLo, tHi);
    else
      rangeOfT(forms, omega, k, tLo, tHi);
    for (std::int64_t t = tLo; t <= tHi && budget > 0; ++t, --budget)
    {
      const std::int64_t nx = std::int64_t(Wide(k) * frame.a[0] + Wide(t) * frame.v[0]);
      const std::int64_t ny = std::int64_t(Wide(k) * frame.a[1] + Wide(t) * frame.v[1]);
      const Vec n{ nx, ny, sigma[2] * (omega - sigma[0] * nx - sigma[1] * ny) };
      if (worthTesting(n, sigma, found, normal) && fits(n))
      {
        normal = n;
        found = true;
      }
    }
  }
}

/// Level omega of an octant's search over its columns kLo..kHi (levelColumns): the normal of
/// smallest (nx, ny) that fits, into `normal`; false when none.
template<typename Form, typename Fits>
bool searchLevel(const std::vector<Form>& forms,
  const Vec& sigma,
  const ColumnFrame& frame,
  std::int64_t omega,
  Wide kLo,
  Wide kHi,
  std::int64_t& budget,
  Vec& normal,
  const Fits& fits)
{
  // Within the level, the smallest (nx, ny) in lexicographic order, whatever the frame.
  bool found = false;
  if (-SmallColumn < kLo && kHi < SmallColumn && omega < SmallColumn)
    searchColumns(forms,
      sigma,
      frame,
      omega,
      std::int64_t(kLo),
      std::int64_t(kHi),
      budget,
      normal,
      found,
      fits);
  else
    searchColumns(forms, sigma, frame, omega, kLo, kHi, budget, normal, found, fits);
  return found;
}

} // namespace

void StandardPlaneRecognizer::reset()
{
  // Storage is kept from face to face: a recognizer is reset once per face. But a point index
  // grown by an earlier, larger face is replaced by a small one rather than cleared, so that a
  // reset costs the size of the face it ends, not that of the largest face so far; one for
  // KeptIndexPoints points is kept whatever the faces (cleared, not made anew and grown twice
  // again by the next small face: most faces are small, and many).
  this->KeysPeak = std::max(this->KeysPeak, this->Points.size());
  if (this->KeysPeak > std::max(2 * this->Points.size() + 16, KeptIndexPoints))
  {
    this->Keys = GridPointIndex(KeptIndexPoints);
    this->KeysPeak = 0;
  }
  else
    this->Keys.clear();
  this->Points.clear();
  this->Extremes.clear();
  this->Scanned = 0;
  this->Present = { 0, 0, 0 };
  this->Current = StandardPlane();
  // The octants' triangles are put back when a slow path first clips them (restoreOctant):
  // the orientations of a small face rule most octants out before that, and the copies of
  // all eight cost as much as the rest of the reset.
  for (int s = 0; s < 8; ++s) // the sign patterns, which octantExcluded reads: set always
    this->Octants[s].sigma = { (s & 1) ? -1 : 1, (s & 2) ? -1 : 1, (s & 4) ? -1 : 1 };
  this->Alive.fill(true);
  this->Unrestored.fill(true);
}

void StandardPlaneRecognizer::restoreOctant(int s)
{
  // The octants' triangles, made once. Three entries each, copied one by one into the
  // octant's storage (vector::assign and memmove cost more).
  static const std::array<Octant, 8> initial = initialOctants();
  Octant& o = this->Octants[s];
  const Octant& from = initial[s];
  o.sigma = from.sigma;
  o.vertices.resize(3);
  for (int i = 0; i < 3; ++i)
    o.vertices[i] = from.vertices[i];
  o.applied = 0;
  this->Unrestored[s] = false;
}

std::array<StandardPlaneRecognizer::Octant, 8> StandardPlaneRecognizer::initialOctants()
{
  std::array<Octant, 8> octants;
  for (int s = 0; s < 8; ++s)
  {
    Octant& o = octants[s];
    o.sigma = { (s & 1) ? -1 : 1, (s & 2) ? -1 : 1, (s & 4) ? -1 : 1 };
    // The triangle sigma.n = 1, sigma_d n_d >= 0; edge i lies on n_(i+2) = 0.
    for (int d = 0; d < 3; ++d)
    {
      Vertex v;
      v.ray = { 0, 0, 0 };
      v.ray[d] = o.sigma[d];
      v.lo = v.hi = 0;
      v.argLo = v.argHi = 0;
      v.edge = { 0, 0, 0 };
      v.edge[(d + 2) % 3] = o.sigma[(d + 2) % 3];
      v.octantEdge = true;
      o.vertices.push_back(v);
    }
  }
  return octants;
}

template<typename F>
void StandardPlaneRecognizer::forEachExtreme(std::size_t count, F&& f) const
{
  for (std::uint32_t j : this->Extremes)
  {
    if (j >= count)
      return;
    f(j);
  }
  for (std::size_t j = this->Scanned; j < count; ++j)
    f(j);
}

bool StandardPlaneRecognizer::isMidpoint(const Point3& q) const
{
  // Pairs along the axes, then the face diagonals: a standard plane's points lie in layers
  // n.p = const, and a point inside a tilted layer has its pair along a diagonal.
  static constexpr std::array<std::array<int, 3>, 9> Steps{ { { 1, 0, 0 },
    { 0, 1, 0 },
    { 0, 0, 1 },
    { 1, 1, 0 },
    { 1, -1, 0 },
    { 1, 0, 1 },
    { 1, 0, -1 },
    { 0, 1, 1 },
    { 0, 1, -1 } } };
  for (const auto& s : Steps)
    if (this->Keys.find(packBiased({ q[0] + s[0], q[1] + s[1], q[2] + s[2] })) >= 0 &&
      this->Keys.find(packBiased({ q[0] - s[0], q[1] - s[1], q[2] - s[2] })) >= 0)
      return true;
  return false;
}

void StandardPlaneRecognizer::refreshExtremes()
{
  // Points join the face on its rim, where they are seldom midpoints yet: the extremes are
  // sifted again (each checked anew) only when the face has grown by a quarter, a constant
  // number of checks per point; the points since are measured all.
  const std::size_t to = this->Points.size();
  if (to < ExtremesFrom || 4 * to < 5 * this->Scanned)
    return;
  for (std::size_t i = this->Scanned; i < to; ++i)
    this->Extremes.push_back(static_cast<std::uint32_t>(i));
  this->Scanned = to;
  this->Extremes.erase(std::remove_if(this->Extremes.begin(),
                         this->Extremes.end(),
                         [&](std::uint32_t j) { return this->isMidpoint(this->Points[j]); }),
    this->Extremes.end());
}

// The range of a new vertex over the points before count, read on the extremes only: they
// hold every vertex of the hull of all the points (committed and trial) that comes before
// count, and applyPoints applies every later point to the vertex, so once all points are
// applied every range is exact and the polygon is the same set as with every point measured
// (only the pair chosen for a cut, among equal extremes, may differ).
void StandardPlaneRecognizer::measure(Vertex& v, std::size_t count) const
{
  // In locals: stores through v could alias the counters the loop reads.
  const Vec ray = v.ray;
  std::int64_t lo = std::numeric_limits<std::int64_t>::max();
  std::int64_t hi = std::numeric_limits<std::int64_t>::min();
  std::uint32_t argLo = 0, argHi = 0;
  this->forEachExtreme(count,
    [&](std::size_t j)
    {
      const std::int64_t x = dot(ray, this->Points[j]);
      if (x < lo)
        lo = x, argLo = static_cast<std::uint32_t>(j);
      if (x > hi)
        hi = x, argHi = static_cast<std::uint32_t>(j);
    });
  // Every scanned point before count is the midpoint of other points, some at or after count:
  // take the last.
  if (lo == std::numeric_limits<std::int64_t>::max())
  {
    lo = hi = dot(ray, this->Points[count - 1]);
    argLo = argHi = static_cast<std::uint32_t>(count - 1);
  }
  v.lo = lo, v.hi = hi, v.argLo = argLo, v.argHi = argHi;
}

bool StandardPlaneRecognizer::clip(Octant& o, const Vec& h, std::size_t count) const
{
  ++this->Clips;
  const std::size_t n = o.vertices.size();
  std::vector<std::int64_t>& f = this->ClipValues;
  if (f.size() < n) // grown only: a resize per clip cost a call
    f.resize(n);
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
    return false;
  }
  const Vec sigma = sigmaOf(o.sigma);
  // Built in the scratch polygon, then swapped in: no allocation once the storage has grown.
  std::vector<Vertex>& vertices = this->ClipPolygon.vertices;
  vertices.clear();
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t j = i + 1 == n ? 0 : i + 1; // no division in the loop
    const Vertex& from = o.vertices[i];
    if (f[i] >= 0)
    {
      vertices.push_back(from);
      if (f[i] == 0 && f[j] < 0) // its edge leaves along h
      {
        vertices.back().edge = h;
        vertices.back().octantEdge = false;
      }
    }
    if ((f[i] > 0 && f[j] < 0) || (f[i] < 0 && f[j] > 0))
    {
      Vertex v;
      v.ray = primitive(cross(from.edge, h));
      if (dot(sigma, v.ray) < 0)
        for (std::int64_t& c : v.ray)
          c = -c;
      this->measure(v, count);
      const bool leaving = f[i] > 0;
      v.edge = leaving ? h : from.edge;
      v.octantEdge = leaving ? false : from.octantEdge;
      vertices.push_back(v);
    }
  }
  o.vertices.swap(vertices);
  return true;
}

bool StandardPlaneRecognizer::applyPoints(Octant& o, std::size_t count) const
{
  const Vec sigma = sigmaOf(o.sigma);
  for (std::size_t j = o.applied; j < count; ++j)
  {
    const Point3& p = this->Points[j];
    if (j == 0)
      for (Vertex& v : o.vertices)
      {
        v.lo = v.hi = dot(v.ray, p);
        v.argLo = v.argHi = 0;
      }
    else
      for (Vertex& v : o.vertices)
      {
        const std::int64_t x = dot(v.ray, p);
        if (x < v.lo)
          v.lo = x, v.argLo = static_cast<std::uint32_t>(j);
        if (x > v.hi)
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
  o.applied = count;
  return true;
}

bool StandardPlaneRecognizer::fits(const Vec& n, const std::array<int, 3>& present) const
{
  for (int d = 0; d < 3; ++d)
    if (present[d] != 0 && present[d] * n[d] <= 0)
      return false;
  std::int64_t lo, hi;
  this->rangeOf(n, lo, hi);
  if (hi - lo >= std::llabs(n[0]) + std::llabs(n[1]) + std::llabs(n[2]))
    return false;
  this->FitLo = lo, this->FitHi = hi; // the range adoptNormal needs, if n is the one kept
  return true;
}

void StandardPlaneRecognizer::rangeOf(const Vec& n, std::int64_t& lo, std::int64_t& hi) const
{
  std::int64_t l = dot(n, this->Points.front()), h = l; // locals: lo, hi could alias counters
  this->forEachExtreme(this->Points.size(),
    [&](std::size_t j)
    {
      const std::int64_t x = dot(n, this->Points[j]);
      l = std::min(l, x);
      h = std::max(h, x);
    });
  lo = l, hi = h;
}

bool StandardPlaneRecognizer::hasInterior(const Octant& o)
{
  const std::size_t n = o.vertices.size();
  if (n < 3)
    return false;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t j = i + 1 == n ? 0 : i + 1, k = j + 1 == n ? 0 : j + 1;
    if (det(o.vertices[i].ray, o.vertices[j].ray, o.vertices[k].ray) != 0)
      return true;
  }
  return false;
}

bool StandardPlaneRecognizer::saturated(const Octant& o, std::size_t e) const
{
  const Vertex& u = o.vertices[e];
  const Vertex& v = o.vertices[(e + 1) % o.vertices.size()];
  const Vec sigma = sigmaOf(o.sigma);
  if (u.hi - u.lo < dot(sigma, u.ray) || v.hi - v.lo < dot(sigma, v.ray))
    return false;
  // The width is at least (q - r).n for any two points q, r. If the pair realizing one end's
  // width also has (q - r).n = sigma.n at the other end, that linear bound is sigma.n all along
  // the edge, where the width (convex, sigma.n at both ends) is also at most sigma.n: the edge
  // is saturated, without measuring every point at its midpoint.
  auto pairSaturates = [&](const Vertex& w, const Vertex& at)
  {
    const Point3 d = sub(this->Points[w.argHi], this->Points[w.argLo]);
    return dot(d, at.ray) == dot(sigma, at.ray);
  };
  if (pairSaturates(u, v) || pairSaturates(v, u))
    return true;
  const Vec m{ u.ray[0] + v.ray[0], u.ray[1] + v.ray[1], u.ray[2] + v.ray[2] };
  std::int64_t lo, hi;
  this->rangeOf(m, lo, hi);
  return hi - lo >= dot(sigma, m);
}

void StandardPlaneRecognizer::markStrictEdges(const Octant& o) const
{
  // Every normal strictly inside the polygon fits (the width is convex, at most 1 on the
  // polygon, and 1 inside only if constant). On an octant edge, where n_d = 0 is allowed,
  // the width is convex along the edge too: it is exactly 1 inside the edge only when it is
  // 1 all along, and then no normal of that edge fits. Such edges are made strict, or the
  // search would measure every point for each of their lattice normals (up to the budget:
  // minutes on a large face).
  std::vector<char>& strict = this->StrictEdges;
  strict.assign(o.vertices.size(), 0);
  for (std::size_t e = 0; e < o.vertices.size(); ++e)
    strict[e] = !o.vertices[e].octantEdge || this->saturated(o, e);
}

void StandardPlaneRecognizer::sliceThePolygon(const Octant& o, const Vec& sigma) const
{
  this->Rays.clear();
  for (const Vertex& v : o.vertices)
    this->Rays.push_back(v.ray);
  this->Forms.clear();
  for (const Vertex& v : o.vertices)
    this->Forms.push_back(sliceForm(v.edge, sigma));
}

bool StandardPlaneRecognizer::solve(const Octant& o,
  const std::array<int, 3>& present,
  std::int64_t omegaStart,
  std::int64_t omegaLimit,
  Vec& normal) const
{
  ++this->Searches;
  const Vec sigma = sigmaOf(o.sigma);
  this->markStrictEdges(o);
  this->sliceThePolygon(o, sigma);
  // Columns k = u.(nx, ny), first with u = (1, 0), then over a thin frame of the polygon
  // (thinFrame): the range of k / omega over the polygon, as fractions.
  ColumnFrame frame;
  ColumnRange range = columnRange(this->Rays, sigma, frame);
  frameForms(this->Forms, this->StrictEdges, frame, this->FrameForms);
  std::int64_t budget = SearchBudget;
  bool thin = false;
  for (std::int64_t omega = omegaStart; omega <= omegaLimit && budget > 0; ++omega, --budget)
  {
    // The level's result does not depend on the frame, only the columns scanned (and so the
    // budget spent, by at most ThinFrameColumns - 1 a level) do.
    Wide kLo, kHi;
    levelColumns(range, omega, kLo, kHi);
    if (!thin && omega >= ThinFrameLevel && kHi - kLo >= ThinFrameColumns)
    {
      frame = thinFrame(this->Rays, sigma, this->FrameEdges, this->FrameBreaks);
      range = columnRange(this->Rays, sigma, frame);
      frameForms(this->Forms, this->StrictEdges, frame, this->FrameForms);
      thin = true;
      levelColumns(range, omega, kLo, kHi);
    }
    auto fits = [&](const Vec& n) { return this->fits(n, present); };
    if (searchLevel(this->FrameForms, sigma, frame, omega, kLo, kHi, budget, normal, fits))
      return true;
  }
  return false;
}

bool StandardPlaneRecognizer::tryAdd(const Point3* points,
  std::size_t count,
  const std::array<int, 3>& signs,
  std::uint32_t known)
{
  bool taken = false;
  if (this->Points.empty())
  {
    this->Path.size = 0; // firstCallFromRecord starts it when the call has a record
    if (known == 0 && this->firstCallFromRecord(points, count, signs, taken))
      return taken;
  }
  return this->recognise(points, count, signs, known);
}

/// The point count, the orientations, then the points relative to the first one, a byte each,
/// the rest of the words zero.
bool StandardPlaneRecognizer::FirstCallKey::assign(const Point3* points,
  std::size_t count,
  const std::array<int, 3>& signs)
{
  if (count == 0 || count > PointsAtMost)
    return false;
  std::array<std::uint8_t, sizeof(words)> bytes{};
  if (!writeCallBytes(bytes.data(), points, count, signs, points[0]))
    return false;
  std::memcpy(this->words.data(), bytes.data(), sizeof(this->words));
  return true;
}

std::size_t StandardPlaneRecognizer::FirstCallKeyHash::operator()(const FirstCallKey& key) const
{
  // Multiply and fold each word (the high bits of a product depend on every bit below them),
  // so keys that differ in one offset land in different buckets.
  std::uint64_t h = 0x9E3779B97F4A7C15ull;
  for (const std::uint64_t w : key.words)
  {
    h = (h ^ w) * 0xFF51AFD7ED558CCDull;
    h ^= h >> 32;
  }
  return static_cast<std::size_t>(h);
}

bool StandardPlaneRecognizer::firstCallFromRecord(const Point3* points,
  std::size_t count,
  const std::array<int, 3>& signs,
  bool& taken)
{
  // The recognition reads the points relative to the first one (Origin) only: a first call
  // with the same key leaves the same state, but for the origin and the plane's offset mu.
  // Most faces start with one surfel or an umbrella of a few, of a few shapes: their first
  // call, a search of every octant from omega 1, was a tenth of the growth's instructions on
  // noise.
  constexpr std::size_t FirstCallsKept = 4096;
  FirstCallKey key;
  if (!key.assign(points, count, signs))
    return false;
  const auto found = this->FirstCalls.find(key);
  if (found == this->FirstCalls.end())
  {
    const std::size_t clips = this->Clips, searches = this->Searches;
    taken = this->recognise(points, count, signs, 0);
    if (this->FirstCalls.size() < FirstCallsKept)
    {
      FirstCall& r = this->FirstCalls[key];
      r.taken = taken;
      r.node = static_cast<std::uint32_t>(this->FirstCalls.size());
      if (taken)
        this->startPath(r.node);
      r.clips = this->Clips - clips;
      r.searches = this->Searches - searches;
      if (taken)
      {
        r.points = this->Points;
        for (int s = 0; s < 8; ++s)
          if (!this->Unrestored[s])
            r.octants[s] = this->Octants[s];
        r.alive = this->Alive;
        r.unrestored = this->Unrestored;
        r.present = this->Present;
        r.normal = this->Current.normal;
        r.lo = this->CurrentLo;
        r.hi = this->CurrentHi;
      }
    }
    return true;
  }
  const FirstCall& r = found->second;
  this->Clips += r.clips;
  this->Searches += r.searches;
  this->Origin = points[0];
  taken = r.taken;
  if (!taken)
    return true; // a refusal changes nothing
  for (const Point3& q : r.points)
  {
    this->Points.push_back(q);
    this->Keys.insert(packBiased(q));
  }
  for (int s = 0; s < 8; ++s)
    if (!r.unrestored[s])
      this->Octants[s] = r.octants[s];
  this->Alive = r.alive;
  this->Unrestored = r.unrestored;
  this->Present = r.present;
  this->takePlane(r.normal, r.lo, r.hi);
  this->startPath(r.node);
  return true;
}

std::uint64_t StandardPlaneRecognizer::CallPath::hash() const
{
  // Multiply and fold each 8 bytes, as FirstCallKeyHash does (zero beyond the size).
  std::uint64_t h = 0x9E3779B97F4A7C15ull ^ this->size;
  for (std::size_t i = 0; i < this->size; i += 8)
  {
    std::uint64_t w = 0;
    std::memcpy(&w, this->bytes.data() + i, 8);
    h = (h ^ w) * 0xFF51AFD7ED558CCDull;
    h ^= h >> 32;
  }
  return h;
}

void StandardPlaneRecognizer::startPath(std::uint32_t node)
{
  this->Path.bytes.fill(0);
  std::memcpy(this->Path.bytes.data(), &node, 4);
  this->Path.size = 4;
}

bool StandardPlaneRecognizer::extendPath(const Point3* points,
  std::size_t count,
  const std::array<int, 3>& signs)
{
  static_assert(
    FirstCallKey::PointsAtMost + CallPath::CallPoints * CallPath::CallsAtMost < ExtremesFrom,
    "a recorded slow path sifts no extremes (refreshExtremes changes nothing)");
  static_assert(CallPath::BytesAtMost % 8 == 4, "CallPath::hash reads whole words");
  CallPath& path = this->Path;
  if (path.size == 0)
    return false;
  if (count > CallPath::CallPoints || path.size == CallPath::BytesAtMost)
  {
    path.size = 0;
    return false;
  }
  std::uint8_t* bytes = path.bytes.data() + path.size;
  if (!writeCallBytes(bytes, points, count, signs, this->Origin))
  {
    path.size = 0;
    return false;
  }
  // Zero past the call's points: paths are compared and hashed in whole words.
  std::fill(bytes + 4 + 3 * count, bytes + CallPath::CallBytes, std::uint8_t(0));
  path.size += CallPath::CallBytes;
  return true;
}

std::size_t StandardPlaneRecognizer::laterSlot(std::uint64_t pathHash) const
{
  std::size_t i = static_cast<std::size_t>(pathHash) & (LaterTableSize - 1);
  for (;; i = (i + 1) & (LaterTableSize - 1))
  {
    const auto& [hash, record] = this->LaterTable[i];
    if (record == NoRecord || (hash == pathHash && this->LaterRecords[record].path == this->Path))
      return i;
  }
}

bool StandardPlaneRecognizer::laterCallFromRecord(std::uint64_t pathHash,
  const std::array<int, 3>& present,
  bool& taken)
{
  if (this->LaterTable.empty())
    return false;
  const std::uint32_t record = this->LaterTable[this->laterSlot(pathHash)].second;
  if (record == NoRecord)
    return false;
  const LaterCall& r = this->LaterRecords[record];
  ++this->Repeated;
  this->Clips += r.clips;
  this->Searches += r.searches;
  taken = r.taken;
  if (taken)
    this->commit(present); // the same fresh points as the recorded call's
  const Vertex* vertex = this->LaterVertices.data() + r.verticesAt;
  for (int s = 0; s < 8; ++s)
    if (r.alive[s] && !r.unrestored[s])
    {
      Octant& o = this->Octants[s];
      o.vertices.assign(vertex, vertex + r.sizes[s]);
      o.applied = r.applied[s];
      vertex += r.sizes[s];
    }
  this->Alive = r.alive;
  this->Unrestored = r.unrestored;
  this->takePlane(r.normal, r.lo, r.hi);
  return true;
}

void StandardPlaneRecognizer::recordLaterCall(std::uint64_t pathHash,
  bool taken,
  std::size_t clips,
  std::size_t searches)
{
  if (this->LaterRecords.size() >= LaterCallsKept)
    return;
  if (this->LaterTable.empty())
    this->LaterTable.assign(LaterTableSize, { 0, NoRecord });
  const std::size_t slot = this->laterSlot(pathHash); // empty: the look-up found no record
  LaterCall r;
  r.path = this->Path;
  r.taken = taken;
  r.clips = static_cast<std::uint32_t>(this->Clips - clips);
  r.searches = static_cast<std::uint32_t>(this->Searches - searches);
  r.verticesAt = static_cast<std::uint32_t>(this->LaterVertices.size());
  for (int s = 0; s < 8; ++s)
    if (this->Alive[s] && !this->Unrestored[s])
    {
      const Octant& o = this->Octants[s];
      this->LaterVertices.insert(this->LaterVertices.end(), o.vertices.begin(), o.vertices.end());
      // At most 36 points clip an octant's triangle here: far fewer than 256 corners.
      assert(o.vertices.size() < 256);
      r.sizes[s] = static_cast<std::uint8_t>(o.vertices.size());
      r.applied[s] = static_cast<std::uint8_t>(o.applied);
    }
  r.alive = this->Alive;
  r.unrestored = this->Unrestored;
  r.normal = this->Current.normal;
  r.lo = this->CurrentLo;
  r.hi = this->CurrentHi;
  this->LaterTable[slot] = { pathHash, static_cast<std::uint32_t>(this->LaterRecords.size()) };
  this->LaterRecords.push_back(r);
}

bool StandardPlaneRecognizer::recognise(const Point3* points,
  std::size_t count,
  const std::array<int, 3>& signs,
  std::uint32_t known)
{
  std::array<int, 3> present = this->Present;
  if (!addOrientations(signs, present) || !this->collectFreshPoints(points, count, known))
    return false;
  // From here on the call may change the state, even when refused (the octants are clipped
  // with the points committed since, for good): it extends the face's path.
  const bool onPath = this->extendPath(points, count, signs);
  if (this->takenByCurrentPlane(present))
    return true;
  const std::uint64_t hash = onPath ? this->Path.hash() : 0;
  bool taken = false;
  if (onPath && this->laterCallFromRecord(hash, present, taken))
    return taken;
  const std::size_t clips = this->Clips, searches = this->Searches;
  // Slow path: clip the octants with the points already accepted (for good), then with the
  // new ones (on copies), and search each surviving octant for a normal (searchOctants).
  this->refreshExtremes();
  const std::size_t before = this->Points.size();
  this->Points.insert(this->Points.end(), this->Fresh.begin(), this->Fresh.end());
  std::array<bool, 8> survives{};
  Vec best{ 0, 0, 0 };
  taken = this->searchOctants(present, survives, best);
  this->Points.resize(before);
  if (taken)
  {
    this->commit(present);
    this->adoptNormal(best, survives);
  }
  if (onPath)
    this->recordLaterCall(hash, taken, clips, searches);
  return taken;
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

bool StandardPlaneRecognizer::collectFreshPoints(const Point3* points,
  std::size_t count,
  std::uint32_t known)
{
  if (this->Points.empty() && count > 0)
    this->Origin = points[0];
  // New points relative to the origin, without repeats, sorted by key (their order does not
  // matter, but it is the same whatever the order of the call's points).
  std::vector<Point3>& fresh = this->Fresh;
  std::vector<std::uint64_t>& keys = this->FreshKeys;
  fresh.clear();
  keys.clear();
  for (std::size_t i = 0; i < count; ++i)
  {
    if (i < 32 && (known >> i) & 1u)
    {
      // Added already (and so within reach of the origin): a wrong bit would drop a point.
      assert(this->Keys.find(packBiased(sub(points[i], this->Origin))) >= 0);
      continue;
    }
    const Point3 q = sub(points[i], this->Origin);
    for (int d = 0; d < 3; ++d) // -CoordinateLimit / 2 < q[d] < CoordinateLimit / 2
      if (std::uint64_t(std::int64_t(q[d]) + CoordinateLimit / 2 - 1) >=
        std::uint64_t(CoordinateLimit - 1))
        return false;
    const std::uint64_t key = packBiased(q);
    if (this->Keys.find(key) >= 0)
      continue;
    if (count > SmallCall) // a whole face (merging): sorted once below
    {
      fresh.push_back(q);
      continue;
    }
    // A surfel's corners (the growth's calls): inserted in place, without a sort (a few keys:
    // a scan for a repeat, then the insertion by shifts).
    std::size_t j = keys.size();
    if (std::find(keys.begin(), keys.end(), key) != keys.end())
      continue;
    keys.push_back(key);
    fresh.push_back(q);
    for (; j > 0 && keys[j - 1] > key; --j)
    {
      keys[j] = keys[j - 1];
      fresh[j] = fresh[j - 1];
    }
    keys[j] = key;
    fresh[j] = q;
  }
  if (count > SmallCall)
    this->sortFreshPoints();
  return true;
}

void StandardPlaneRecognizer::sortFreshPoints()
{
  std::vector<Point3>& fresh = this->Fresh;
  std::sort(fresh.begin(),
    fresh.end(),
    [](const Point3& a, const Point3& b) { return packBiased(a) < packBiased(b); });
  fresh.erase(std::unique(fresh.begin(),
                fresh.end(),
                [](const Point3& a, const Point3& b)
                { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }),
    fresh.end());
  for (const Point3& q : fresh)
    this->FreshKeys.push_back(packBiased(q));
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
  // A committed point r has n.r in [CurrentLo, CurrentHi] for the current normal n: outside
  // that slab r is only looked up among the new points (no hash probe).
  // The key and the value of q + s sigma are those of q plus s times those of sigma: the
  // packing is linear while each biased coordinate stays in its 21 bits (|q| < 2^15 here).
  const Vec& n = this->Current.normal;
  const bool anyCommitted = this->Points.size() > this->Fresh.size();
  const std::int64_t valueStep = n[0] * o.sigma[0] + n[1] * o.sigma[1] + n[2] * o.sigma[2];
  const std::uint64_t keyStep = (std::uint64_t(std::int64_t(o.sigma[0])) << 42) +
    (std::uint64_t(std::int64_t(o.sigma[1])) << 21) + std::uint64_t(std::int64_t(o.sigma[2]));
  const std::vector<std::uint64_t>& freshKeys = this->FreshKeys; // Fresh's, in its order
  auto isFresh = [&](std::uint64_t key)
  {
    // A surfel's few new corners are scanned; a merged face's many are searched.
    if (freshKeys.size() <= 8)
      return std::find(freshKeys.begin(), freshKeys.end(), key) != freshKeys.end();
    return std::binary_search(freshKeys.begin(), freshKeys.end(), key);
  };
  for (std::size_t i = 0; i < this->Fresh.size(); ++i)
  {
    const std::int64_t xq = dot(n, this->Fresh[i]);
    for (int s : { -1, 1 })
    {
      const std::uint64_t key = freshKeys[i] + (s > 0 ? keyStep : std::uint64_t(0) - keyStep);
      const std::int64_t x = xq + s * valueStep;
      if (isFresh(key) ||
        (anyCommitted && this->CurrentLo <= x && x <= this->CurrentHi && this->Keys.find(key) >= 0))
        return true;
    }
  }
  return false;
}

bool StandardPlaneRecognizer::searchOctants(const std::array<int, 3>& present,
  std::array<bool, 8>& survives,
  Vec& best)
{
  std::int64_t bestOmega = MaximumOmega + 1;
  this->Deferred.fill(false);
  // Points and orientations only accumulate, so the normals that fit them only get fewer: no
  // normal of an omega below the current plane's fits now (its omega was the smallest).
  const std::size_t committed = this->Points.size() - this->Fresh.size();
  const std::int64_t omegaStart = committed > 0 ? this->Current.omega() : 1;
  for (int i = 0; i < 8; ++i)
  {
    const Octant& original = this->Octants[i]; // its sign pattern, even unrestored
    survives[i] = false;
    if (!this->Alive[i] || this->octantExcluded(original, present))
      continue;
    if (bestOmega == omegaStart)
    {
      // No normal of a later octant can win (a tie goes to the earlier octant): this one is
      // clipped with the new points lazily, by the next slow path's applyPoints, which gives
      // the same polygon. Only the exclusion above reads the new points of this call alone.
      survives[i] = true;
      this->Deferred[i] = true;
      continue;
    }
    // The points accepted since the octant's last clipping, for good. Only here, past the
    // exclusion and the deferral: an octant excluded by the new points dies if they are
    // taken, and one deferred or left alive by a refusal is clipped by a later slow path,
    // to the same polygon (the points only accumulate).
    if (this->Unrestored[i])
      this->restoreOctant(i);
    if (!this->applyPoints(this->Octants[i], committed))
    {
      this->Alive[i] = false;
      continue;
    }
    Octant& o = this->Trials[i];
    o = original; // reuses the trial's storage
    if (!this->applyPoints(o, this->Points.size()) || !hasInterior(o))
      continue;
    survives[i] = true;
    Vec n;
    if (this->solve(o, present, omegaStart, bestOmega - 1, n))
    {
      // The last normal fits accepted is the one solve returns (searchLevel keeps a normal
      // right after fits accepts it): its range over the points, committed and new.
      this->BestLo = this->FitLo, this->BestHi = this->FitHi;
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
    if (survives[i] && !this->Deferred[i])
    {
      std::swap(this->Octants[i], this->Trials[i]);
      this->Octants[i].applied = this->Points.size();
    }
  }
  this->takePlane(best, this->BestLo, this->BestHi); // the range measured by fits
}

/// The current plane: `normal`, whose range over the points is [lo, hi], its offset mu the
/// lowest value taken relative to the face's first point.
void StandardPlaneRecognizer::takePlane(const std::array<std::int64_t, 3>& normal,
  std::int64_t lo,
  std::int64_t hi)
{
  this->Current.normal = normal;
  this->CurrentLo = lo;
  this->CurrentHi = hi;
  this->Current.mu = lo + dot(normal, this->Origin);
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
