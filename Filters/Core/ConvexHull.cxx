#include "ConvexHull.h"

#include "Geometry.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace vbr
{
namespace
{

using Index = std::uint32_t;
constexpr std::int32_t NoFace = -1;
constexpr std::int32_t Processed = -2;

using detail::cross;
using detail::dot;
using detail::sub;

std::int64_t gcd64(std::int64_t a, std::int64_t b)
{
  a = a < 0 ? -a : a;
  b = b < 0 ? -b : b;
  while (b != 0)
  {
    const std::int64_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}

} // namespace

FacePlane planeThrough(const LatticePoint& a, const LatticePoint& b, const LatticePoint& c)
{
  FacePlane plane;
  plane.normal = cross(sub(b, a), sub(c, a));
  const std::int64_t g = gcd64(gcd64(plane.normal[0], plane.normal[1]), plane.normal[2]);
  if (g == 0)
  {
    return plane;
  }
  for (auto& n : plane.normal)
  {
    n /= g;
  }
  plane.offset = static_cast<std::int64_t>(dot(plane.normal, a));
  return plane;
}

namespace
{

/// Exact strict 2D convex hull (Andrew's monotone chain) of the points `ids` of `points`, all
/// on `plane`; counter-clockwise seen from the side the normal points to. Corners where the
/// boundary goes straight on are dropped.
std::vector<Index> convexPolygon(std::vector<Index> ids,
  const std::vector<LatticePoint>& points,
  const FacePlane& plane)
{
  int k = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (std::abs(plane.normal[a]) > std::abs(plane.normal[k]))
    {
      k = a;
    }
  }
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  auto uv = [&](Index id) { return std::array<std::int64_t, 2>{ points[id][i], points[id][j] }; };
  std::sort(ids.begin(), ids.end(), [&](Index a, Index b) { return uv(a) < uv(b); });
  ids.erase(
    std::unique(ids.begin(), ids.end(), [&](Index a, Index b) { return points[a] == points[b]; }),
    ids.end());
  if (ids.size() < 3)
  {
    return ids;
  }
  auto turn = [&](Index o, Index a, Index b)
  {
    const auto po = uv(o), pa = uv(a), pb = uv(b);
    return __int128(pa[0] - po[0]) * (pb[1] - po[1]) - __int128(pa[1] - po[1]) * (pb[0] - po[0]);
  };
  std::vector<Index> chain = monotoneChain(ids, turn);
  if (plane.normal[k] < 0)
  {
    std::reverse(chain.begin(), chain.end());
  }
  return chain;
}

std::uint64_t edgeKey(Index a, Index b)
{
  return (std::uint64_t(a) << 32) | b;
}

/// The face on the left of each directed edge, in one flat table with linear probing: every
/// insertion adds and removes a few dozen edges, and a node-based hash map allocates and frees
/// a node for each.
class EdgeOwners
{
public:
  void reserve(std::size_t edges)
  {
    std::size_t capacity = 16;
    while (capacity < 2 * edges)
      capacity *= 2;
    this->Slots.assign(capacity, Slot{ Empty, 0 });
    this->Count = 0;
  }

  void set(std::uint64_t key, Index face)
  {
    if (2 * (this->Count + 1) > this->Slots.size())
      this->grow();
    std::size_t i = this->home(key);
    while (this->Slots[i].key != Empty && this->Slots[i].key != key)
      i = (i + 1) & (this->Slots.size() - 1);
    this->Count += this->Slots[i].key == Empty;
    this->Slots[i] = Slot{ key, face };
  }

  Index at(std::uint64_t key) const
  {
    std::size_t i = this->home(key);
    while (this->Slots[i].key != key)
    {
      if (this->Slots[i].key == Empty)
        throw std::logic_error("convexHull: an edge without its face");
      i = (i + 1) & (this->Slots.size() - 1);
    }
    return this->Slots[i].face;
  }

  /// Removes the key if `face` owns it (a newer face may have taken the edge over).
  void eraseOwnedBy(std::uint64_t key, Index face);

private:
  static constexpr std::uint64_t Empty = ~std::uint64_t(0);
  struct Slot
  {
    std::uint64_t key;
    Index face;
  };
  std::vector<Slot> Slots;
  std::size_t Count = 0;

  std::size_t home(std::uint64_t key) const
  {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & (this->Slots.size() - 1);
  }
  void grow();
};

void EdgeOwners::eraseOwnedBy(std::uint64_t key, Index face)
{
  const std::size_t mask = this->Slots.size() - 1;
  std::size_t i = this->home(key);
  while (this->Slots[i].key != key)
  {
    if (this->Slots[i].key == Empty)
      return;
    i = (i + 1) & mask;
  }
  if (this->Slots[i].face != face)
    return;
  // Backward shift: later keys of the probe run move into the hole, so no tombstones pile up.
  for (std::size_t j = (i + 1) & mask; this->Slots[j].key != Empty; j = (j + 1) & mask)
  {
    const std::size_t h = this->home(this->Slots[j].key);
    if (((j - h) & mask) >= ((j - i) & mask))
    {
      this->Slots[i] = this->Slots[j];
      i = j;
    }
  }
  this->Slots[i].key = Empty;
  --this->Count;
}

void EdgeOwners::grow()
{
  std::vector<Slot> old = std::move(this->Slots);
  this->reserve(old.size());
  for (const Slot& s : old)
    if (s.key != Empty)
      this->set(s.key, s.face);
}

/// The incremental construction of section 3.1 with the conflict lists described on top.
class HullBuilder
{
public:
  HullBuilder(const std::vector<LatticePoint>& points, CoplanarFaces coplanar)
    : Points(points)
    , Coplanar(coplanar)
  {
  }

  CellList run();

private:
  struct Face
  {
    std::vector<Index> v;
    bool alive = true;
    std::vector<Index> conflicts;
    /// The conflict point farthest from the plane, the next one inserted from this face.
    Index farthest = 0;
    __int128 farthestHeight = 0;
  };
  /// Per face and per insertion: not reached, visible, coplanar, invisible, in the region.
  enum State : std::uint8_t
  {
    Unseen,
    Visible,
    Coplanar_,
    Hidden,
    Queued
  };

  const std::vector<LatticePoint>& Points;
  CoplanarFaces Coplanar;
  std::vector<Face> Faces;
  /// Apart from the faces: the conflict tests scan the planes of all new faces.
  std::vector<FacePlane> Planes;
  /// Faces that were given conflict points (some may be gone since).
  std::vector<Index> Pending;
  /// All coordinates below 2^19 in magnitude: heights fit in 64 bits.
  bool Small = false;
  EdgeOwners Owner;
  std::vector<std::int32_t> PointFace;
  std::vector<std::uint32_t> Tag;
  std::vector<State> States;
  std::uint32_t Epoch = 0;

  Index neighbour(Index a, Index b) const { return this->Owner.at(edgeKey(b, a)); }
  __int128 height(Index f, const LatticePoint& p) const;
  void insertFarthestFirst();
  State classify(Index f, const LatticePoint& p);
  Index addFace(std::vector<Index> v, const FacePlane& plane);
  void removeFace(Index f, std::vector<Index>& orphans);
  bool initialSimplex(std::array<Index, 4>& simplex, CellList& flat);
  void insert(Index ip);
  using NewFaces = std::vector<std::pair<FacePlane, std::vector<Index>>>;
  NewFaces facesOverHorizon(Index ip, const std::vector<Index>& region, bool extend);
  void replaceRegion(Index ip,
    const std::vector<Index>& region,
    const std::vector<Index>& coplanar,
    bool extend,
    NewFaces& created);
  void addInitialTetrahedron(const std::array<Index, 4>& s);
  CellList cellList() const;
  void collectRegion(Index ip, std::vector<Index>& region, std::vector<Index>& coplanar);
  void closeVisibleRegion(Index ip, std::vector<Index>& region, std::vector<Index>& coplanar);
  void reassign(const std::vector<Index>& orphans, Index first, Index ip);
  std::vector<Index> RegionBuffer, CoplanarBuffer, OrphanBuffer; ///< reused by insert
  void attach(Index q, Index f, __int128 h);
  CellList flatHull(const std::array<Index, 3>& corners) const;
};

/// n.p - d of face f's plane, in 64 bits when the coordinates allow it: |n| <= 8 M^2 for
/// coordinates below M, so |n.p - d| <= 48 M^3 < 2^63 for M <= 2^19.
__int128 HullBuilder::height(Index f, const LatticePoint& p) const
{
  const FacePlane& plane = this->Planes[f];
  if (this->Small)
    return plane.normal[0] * p[0] + plane.normal[1] * p[1] + plane.normal[2] * p[2] - plane.offset;
  return plane.evaluate(p);
}

void HullBuilder::attach(Index q, Index f, __int128 h)
{
  Face& face = this->Faces[f];
  if (face.conflicts.empty())
    this->Pending.push_back(f);
  if (face.conflicts.empty() || h > face.farthestHeight)
  {
    face.farthest = q;
    face.farthestHeight = h;
  }
  this->PointFace[q] = static_cast<std::int32_t>(f);
  face.conflicts.push_back(q);
}

/// The rest of the points, farthest first (as Qhull and CGAL do): the farthest point of a face
/// is a vertex of the final hull more often than a point close to the plane, so fewer faces
/// are built only to be replaced again. The output does not depend on the order.
void HullBuilder::insertFarthestFirst()
{
  while (!this->Pending.empty())
  {
    const Index f = this->Pending.back();
    this->Pending.pop_back();
    if (this->Faces[f].alive && !this->Faces[f].conflicts.empty())
      this->insert(this->Faces[f].farthest);
  }
}

HullBuilder::State HullBuilder::classify(Index f, const LatticePoint& p)
{
  if (this->Tag[f] != this->Epoch)
  {
    this->Tag[f] = this->Epoch;
    const int s = signOf(this->height(f, p));
    this->States[f] = s > 0 ? Visible : (s == 0 ? Coplanar_ : Hidden);
  }
  return this->States[f];
}

Index HullBuilder::addFace(std::vector<Index> v, const FacePlane& plane)
{
  const Index f = static_cast<Index>(this->Faces.size());
  for (std::size_t k = 0; k < v.size(); ++k)
  {
    this->Owner.set(edgeKey(v[k], v[(k + 1) % v.size()]), f);
  }
  this->Faces.push_back(Face{ std::move(v), true, {} });
  this->Planes.push_back(plane);
  this->Tag.push_back(0);
  this->States.push_back(Unseen);
  return f;
}

void HullBuilder::removeFace(Index f, std::vector<Index>& orphans)
{
  Face& face = this->Faces[f];
  for (std::size_t k = 0; k < face.v.size(); ++k)
  {
    this->Owner.eraseOwnedBy(edgeKey(face.v[k], face.v[(k + 1) % face.v.size()]), f);
  }
  for (Index q : face.conflicts)
  {
    if (this->PointFace[q] == static_cast<std::int32_t>(f))
    {
      orphans.push_back(q);
    }
  }
  face.alive = false;
  std::vector<Index>().swap(face.conflicts);
  std::vector<Index>().swap(face.v);
}

/// The faces the point sees (a connected set holding its conflict face) and the coplanar
/// faces next to them, found by walking across edges from the conflict face.
void HullBuilder::collectRegion(Index ip, std::vector<Index>& region, std::vector<Index>& coplanar)
{
  const LatticePoint& p = this->Points[ip];
  ++this->Epoch;
  const Index f0 = static_cast<Index>(this->PointFace[ip]);
  this->classify(f0, p);
  region.push_back(f0);
  for (std::size_t r = 0; r < region.size(); ++r)
  {
    const std::vector<Index>& v = this->Faces[region[r]].v;
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const Index g = this->neighbour(v[k], v[(k + 1) % v.size()]);
      if (this->Tag[g] == this->Epoch)
      {
        continue;
      }
      const State s = this->classify(g, p);
      if (s == Visible)
      {
        region.push_back(g);
      }
      else if (s == Coplanar_)
      {
        coplanar.push_back(g);
      }
    }
  }
}

/// The Visible variant: coplanar faces next to the visible ones join them, and so does every
/// coplanar face across an edge of a joined face that the point does not see from inside
/// (else the new triangle on that edge would fold over or be flat).
void HullBuilder::closeVisibleRegion(Index ip,
  std::vector<Index>& region,
  std::vector<Index>& coplanar)
{
  const LatticePoint& p = this->Points[ip];
  for (Index t : coplanar)
  {
    this->States[t] = Queued;
  }
  for (std::size_t c = 0; c < coplanar.size(); ++c)
  {
    const Index t = coplanar[c];
    this->States[t] = Visible;
    region.push_back(t);
    const std::vector<Index>& v = this->Faces[t].v;
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const LatticePoint& a = this->Points[v[k]];
      const LatticePoint& b = this->Points[v[(k + 1) % v.size()]];
      if (dot(this->Planes[t].normal, cross(sub(b, a), sub(p, a))) > 0)
      {
        continue;
      }
      const Index g = this->neighbour(v[k], v[(k + 1) % v.size()]);
      if (this->classify(g, p) == Coplanar_)
      {
        this->States[g] = Queued;
        coplanar.push_back(g);
      }
    }
  }
  coplanar.clear();
}

void HullBuilder::reassign(const std::vector<Index>& orphans, Index first, Index ip)
{
  for (Index q : orphans)
  {
    if (q == ip || this->PointFace[q] == Processed)
    {
      continue;
    }
    this->PointFace[q] = NoFace;
    for (Index f = first; f < this->Faces.size(); ++f)
    {
      const __int128 h = this->height(f, this->Points[q]);
      if (h > 0)
      {
        this->attach(q, f, h);
        break;
      }
    }
  }
}

/// One step of section 3.1: the visible faces (and, by the variant, coplanar ones) are
/// replaced by faces joining their boundary to the point.
/// Section 3.1: point ip joins the hull. The faces it sees (its region, with the coplanar
/// ones in the Extension variant) are replaced by the faces over the region's horizon.
void HullBuilder::insert(Index ip)
{
  // buffers kept across insertions: one point's region is a few faces, and allocating them
  // anew was a tenth of the hull's time on real objects' candidates
  std::vector<Index>& region = this->RegionBuffer;
  std::vector<Index>& coplanar = this->CoplanarBuffer;
  region.clear();
  coplanar.clear();
  this->collectRegion(ip, region, coplanar);
  if (this->Coplanar == CoplanarFaces::Visible)
    this->closeVisibleRegion(ip, region, coplanar);
  const bool extend = this->Coplanar == CoplanarFaces::Extension;
  NewFaces created = this->facesOverHorizon(ip, region, extend);
  this->replaceRegion(ip, region, coplanar, extend, created);
}

/// One new face per horizon edge of the region and point ip; in the Extension variant the
/// edges of one plane make one polygon.
HullBuilder::NewFaces HullBuilder::facesOverHorizon(Index ip,
  const std::vector<Index>& region,
  bool extend)
{
  const LatticePoint& p = this->Points[ip];
  NewFaces created;
  for (Index f : region)
  {
    const std::vector<Index>& v = this->Faces[f].v;
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const Index a = v[k], b = v[(k + 1) % v.size()];
      const State s = this->classify(this->neighbour(a, b), p);
      if (s == Visible || (extend && s == Coplanar_))
        continue;
      const FacePlane plane = planeThrough(this->Points[a], this->Points[b], p);
      if (plane.normal == LatticePoint{ 0, 0, 0 })
        throw std::logic_error("convexHull: flat triangle on the horizon");
      auto same = std::find_if(created.begin(),
        created.end(),
        [&](const std::pair<FacePlane, std::vector<Index>>& c) { return c.first == plane; });
      if (extend && same != created.end())
        same->second.insert(same->second.end(), { a, b });
      else
        created.push_back({ plane, { a, b, ip } });
    }
  }
  return created;
}

/// The region's faces (and the coplanar ones, extended by ip) removed, the new faces added,
/// and the points the removed faces saw handed to the new ones.
void HullBuilder::replaceRegion(Index ip,
  const std::vector<Index>& region,
  const std::vector<Index>& coplanar,
  bool extend,
  NewFaces& created)
{
  if (extend)
    for (Index t : coplanar)
    {
      std::vector<Index> ids = this->Faces[t].v;
      ids.push_back(ip);
      created.push_back({ this->Planes[t], std::move(ids) });
    }
  this->PointFace[ip] = Processed;
  std::vector<Index>& orphans = this->OrphanBuffer;
  orphans.clear();
  for (Index f : region)
    this->removeFace(f, orphans);
  if (extend)
    for (Index t : coplanar)
      this->removeFace(t, orphans);
  const Index first = static_cast<Index>(this->Faces.size());
  for (auto& c : created)
  {
    // A lone triangle over a horizon edge is convex and in order already; only merged
    // triangles and extended faces need their polygon.
    const bool polygon = extend && c.second.size() > 3;
    this->addFace(polygon ? convexPolygon(c.second, this->Points, c.first) : c.second, c.first);
  }
  this->reassign(orphans, first, ip);
}

CellList HullBuilder::flatHull(const std::array<Index, 3>& corners) const
{
  CellList hull;
  std::vector<Index> all(this->Points.size());
  std::iota(all.begin(), all.end(), Index(0));
  const FacePlane plane =
    planeThrough(this->Points[corners[0]], this->Points[corners[1]], this->Points[corners[2]]);
  std::vector<Index> polygon = convexPolygon(all, this->Points, plane);
  std::vector<Index> local(polygon.size());
  for (std::size_t k = 0; k < polygon.size(); ++k)
  {
    hull.vertices.push_back(this->Points[polygon[k]]);
    local[k] = static_cast<Index>(k);
  }
  hull.dimension = 2;
  hull.faces = { local, std::vector<Index>(local.rbegin(), local.rend()) };
  FacePlane back = plane;
  for (auto& n : back.normal)
  {
    n = -n;
  }
  back.offset = -plane.offset;
  hull.planes = { plane, back };
  hull.buildIncidences();
  return hull;
}

/// Four points not on one plane, the first ones of L_s that qualify (the extremes of section
/// 3.2 come first); otherwise `flat` gets the hull of the lower-dimensional set.
bool HullBuilder::initialSimplex(std::array<Index, 4>& simplex, CellList& flat)
{
  const std::vector<LatticePoint>& P = this->Points;
  const std::size_t n = P.size();
  simplex = { 0, 0, 0, 0 };
  std::size_t i = 1;
  for (; i < n && P[i] == P[0]; ++i)
  {
  }
  simplex[1] = static_cast<Index>(i);
  for (++i; simplex[1] < n && i < n &&
       cross(sub(P[simplex[1]], P[0]), sub(P[i], P[0])) == LatticePoint{ 0, 0, 0 };
       ++i)
  {
  }
  simplex[2] = static_cast<Index>(std::min(i, n));
  if (simplex[2] < n)
  {
    // A plane through three points: the first point off it is the fourth corner.
    const LatticePoint normal = cross(sub(P[simplex[1]], P[0]), sub(P[simplex[2]], P[0]));
    for (++i; i < n && dot(normal, sub(P[i], P[0])) == 0; ++i)
    {
    }
  }
  simplex[3] = static_cast<Index>(std::min(i, n));
  if (simplex[1] >= n || simplex[2] >= n)
  {
    // One point, or collinear points: the sorted order runs along the line.
    const std::vector<LatticePoint> ends = simplex[1] >= n
      ? std::vector<LatticePoint>{ P[0] }
      : std::vector<LatticePoint>{ *std::min_element(P.begin(), P.end()),
          *std::max_element(P.begin(), P.end()) };
    flat.dimension = static_cast<int>(ends.size()) - 1;
    flat.vertices = ends;
    flat.buildIncidences();
    if (flat.dimension == 1)
    {
      flat.edges = { { 0, 1 } };
      flat.edgeFaces = { { 0, 0 } };
      flat.vertexEdges = { { 0 }, { 0 } };
      flat.vertexFaces = { {}, {} };
    }
    return false;
  }
  if (simplex[3] >= n)
  {
    flat = this->flatHull({ simplex[0], simplex[1], simplex[2] });
    return false;
  }
  return true;
}

CellList HullBuilder::run()
{
  const std::size_t n = this->Points.size();
  CellList hull;
  if (n == 0)
    return hull;
  this->PointFace.assign(n, NoFace);
  this->Owner.reserve(64);
  this->Small = std::all_of(this->Points.begin(),
    this->Points.end(),
    [](const LatticePoint& p)
    {
      return std::all_of(p.begin(),
        p.end(),
        [](std::int64_t c) { return c > -(std::int64_t(1) << 19) && c < (std::int64_t(1) << 19); });
    });
  std::array<Index, 4> s;
  if (!this->initialSimplex(s, hull))
    return hull; // flat: the degenerate hull
  this->addInitialTetrahedron(s);
  std::vector<Index> all(n);
  std::iota(all.begin(), all.end(), Index(0));
  this->reassign(all, 0, s[0]);
  // The octahedron of section 3.2: the remaining extremes (the first eight of L_s) in order.
  for (Index ip = 0; ip < std::min<std::size_t>(n, 8); ++ip)
    if (this->PointFace[ip] >= 0)
      this->insert(ip);
  this->insertFarthestFirst();
  return this->cellList();
}

/// The four outward faces of the initial tetrahedron.
void HullBuilder::addInitialTetrahedron(const std::array<Index, 4>& s)
{
  for (int omit = 0; omit < 4; ++omit)
  {
    std::vector<Index> v;
    for (int k = 0; k < 4; ++k)
      if (k != omit)
        v.push_back(s[k]);
    if (planeThrough(this->Points[v[0]], this->Points[v[1]], this->Points[v[2]])
          .evaluate(this->Points[s[omit]]) > 0)
      std::swap(v[1], v[2]);
    this->addFace(v, planeThrough(this->Points[v[0]], this->Points[v[1]], this->Points[v[2]]));
  }
  for (Index k : s)
    this->PointFace[k] = Processed;
}

/// The live faces as a cell list, their vertices numbered in order of appearance (the
/// incidences are left to the caller).
CellList HullBuilder::cellList() const
{
  CellList hull;
  std::vector<std::int64_t> local(this->Points.size(), -1);
  hull.dimension = 3;
  for (std::size_t k = 0; k < this->Faces.size(); ++k)
  {
    const Face& f = this->Faces[k];
    if (!f.alive)
      continue;
    std::vector<Index> v;
    for (Index id : f.v)
    {
      if (local[id] < 0)
      {
        local[id] = static_cast<std::int64_t>(hull.vertices.size());
        hull.vertices.push_back(this->Points[id]);
      }
      v.push_back(static_cast<Index>(local[id]));
    }
    hull.faces.push_back(std::move(v));
    hull.planes.push_back(this->Planes[k]);
  }
  return hull;
}

} // namespace

void CellList::buildIncidences()
{
  this->edges.clear();
  this->edgeFaces.clear();
  this->faceEdges.assign(this->faces.size(), {});
  this->vertexEdges.assign(this->vertices.size(), {});
  this->vertexFaces.assign(this->vertices.size(), {});
  // An edge met before is in the edge list of both its vertices: found there instead of in a
  // hash map, which cost an allocation per edge. A vertex may have many edges (a cone's apex),
  // but the shorter of the two lists is searched: on a polyhedron's planar graph the searches
  // cost O(E) in all (the sum over the edges of their ends' smaller degree is at most 6 E,
  // Chiba and Nishizeki 1985: arboricity 3).
  const auto findEdge = [this](Index lo, Index hi)
  {
    const std::vector<Index>& around = this->vertexEdges[lo].size() <= this->vertexEdges[hi].size()
      ? this->vertexEdges[lo]
      : this->vertexEdges[hi];
    for (const Index e : around)
      if (this->edges[e][0] == lo && this->edges[e][1] == hi)
        return e;
    return Index(-1);
  };
  for (std::size_t f = 0; f < this->faces.size(); ++f)
  {
    const std::vector<Index>& v = this->faces[f];
    this->faceEdges[f].reserve(v.size());
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const Index a = v[k], b = v[(k + 1) % v.size()];
      Index e = findEdge(std::min(a, b), std::max(a, b));
      if (e == Index(-1))
      {
        e = static_cast<Index>(this->edges.size());
        this->edges.push_back({ std::min(a, b), std::max(a, b) });
        this->edgeFaces.push_back({ Index(-1), Index(-1) });
        this->vertexEdges[a].push_back(e);
        this->vertexEdges[b].push_back(e);
      }
      this->edgeFaces[e][a < b ? 0 : 1] = static_cast<Index>(f);
      this->faceEdges[f].push_back(e);
      this->vertexFaces[a].push_back(static_cast<Index>(f));
    }
  }
}

std::vector<LatticePoint> vertexCandidates(const BitVolume& voxels)
{
  const auto& d = voxels.dims();
  auto object = [&](std::int64_t x, std::int64_t y, std::int64_t z)
  {
    return x >= 0 && y >= 0 && z >= 0 && x < d[0] && y < d[1] && z < d[2] &&
      voxels.get(
        static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), static_cast<std::int32_t>(z));
  };
  std::vector<LatticePoint> candidates;
  for (std::int32_t x = 0; x < d[0]; ++x)
  {
    for (std::int32_t y = 0; y < d[1]; ++y)
    {
      for (std::int32_t z = 0; z < d[2]; ++z)
      {
        if (!voxels.get(x, y, z))
        {
          continue;
        }
        bool convex = false;
        for (int corner = 0; corner < 8 && !convex; ++corner)
        {
          const int sx = corner & 1 ? 1 : -1, sy = corner & 2 ? 1 : -1, sz = corner & 4 ? 1 : -1;
          convex = true;
          for (int other = 1; other < 8 && convex; ++other)
          {
            convex =
              !object(x + (other & 1 ? sx : 0), y + (other & 2 ? sy : 0), z + (other & 4 ? sz : 0));
          }
        }
        if (convex)
        {
          candidates.push_back({ x, y, z });
        }
      }
    }
  }
  return candidates;
}

std::vector<LatticePoint> extremesFirst(const std::vector<LatticePoint>& points)
{
  // Signs of (x, y, z) minimised lexicographically: v1 .. v8 of section 3.2.
  static const int signs[8][3] = { { 1, 1, 1 },
    { -1, 1, 1 },
    { 1, -1, 1 },
    { 1, 1, -1 },
    { -1, -1, -1 },
    { 1, -1, -1 },
    { -1, 1, -1 },
    { -1, -1, 1 } };
  // The points are sorted by x first: the extremes minimising x lie in the first slab of equal
  // x, those maximising it in the last, so only those two slabs are searched (the keys are
  // distinct, so the extreme is the same as over all points).
  std::size_t firstSlabEnd = 0, lastSlabBegin = points.size();
  while (firstSlabEnd < points.size() && points[firstSlabEnd][0] == points.front()[0])
    ++firstSlabEnd;
  while (lastSlabBegin > 0 && points[lastSlabBegin - 1][0] == points.back()[0])
    --lastSlabBegin;
  std::vector<std::size_t> chosen;
  for (const auto& s : signs)
  {
    auto key = [&](const LatticePoint& p) {
      return std::array<std::int64_t, 3>{ s[0] * p[0], s[1] * p[1], s[2] * p[2] };
    };
    const std::size_t from = s[0] > 0 ? 0 : lastSlabBegin;
    const std::size_t to = s[0] > 0 ? firstSlabEnd : points.size();
    std::size_t best = from;
    for (std::size_t i = from + 1; i < to; ++i)
    {
      if (key(points[i]) < key(points[best]))
      {
        best = i;
      }
    }
    if (!points.empty() && std::find(chosen.begin(), chosen.end(), best) == chosen.end())
    {
      chosen.push_back(best);
    }
  }
  std::vector<LatticePoint> ordered;
  ordered.reserve(points.size());
  for (std::size_t i : chosen)
  {
    ordered.push_back(points[i]);
  }
  std::vector<bool> taken(points.size(), false);
  for (std::size_t i : chosen)
  {
    taken[i] = true;
  }
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!taken[i])
    {
      ordered.push_back(points[i]);
    }
  }
  return ordered;
}

CellList convexHull(const std::vector<LatticePoint>& input, CoplanarFaces coplanar, bool merge)
{
  std::vector<LatticePoint> points = input;
  if (!std::is_sorted(points.begin(), points.end())) // vertexCandidates' lists are sorted
    std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  for (const auto& p : points)
  {
    for (std::int64_t c : p)
    {
      if (c <= -(std::int64_t(1) << 20) || c >= (std::int64_t(1) << 20))
      {
        throw std::invalid_argument("convexHull: coordinates must be below 2^20 in magnitude");
      }
    }
  }
  points = extremesFirst(points);
  CellList hull = HullBuilder(points, coplanar).run();
  // The merge builds the incidences of its own faces; the flat hulls come with theirs.
  if (merge)
    mergeCoplanarFaces(hull);
  else if (hull.dimension == 3)
    hull.buildIncidences();
  return hull;
}

void mergeCoplanarFaces(CellList& hull)
{
  if (hull.dimension < 3)
  {
    return;
  }
  // The faces in the order of their planes, those of one plane in their order (what a map
  // from plane to corners gave, without a node per plane).
  std::vector<Index> order(hull.faces.size());
  std::iota(order.begin(), order.end(), Index(0));
  std::stable_sort(
    order.begin(), order.end(), [&](Index f, Index g) { return hull.planes[f] < hull.planes[g]; });
  std::vector<std::vector<Index>> faces;
  std::vector<FacePlane> planes;
  std::vector<std::int64_t> local(hull.vertices.size(), -1);
  std::vector<LatticePoint> vertices;
  std::vector<Index> corners;
  for (std::size_t first = 0; first < order.size();)
  {
    const FacePlane& plane = hull.planes[order[first]];
    corners.clear();
    std::size_t next = first;
    for (; next < order.size() && hull.planes[order[next]] == plane; ++next)
      corners.insert(corners.end(), hull.faces[order[next]].begin(), hull.faces[order[next]].end());
    first = next;
    std::vector<Index> polygon = convexPolygon(corners, hull.vertices, plane);
    for (Index& id : polygon)
    {
      if (local[id] < 0)
      {
        local[id] = static_cast<std::int64_t>(vertices.size());
        vertices.push_back(hull.vertices[id]);
      }
      id = static_cast<Index>(local[id]);
    }
    faces.push_back(std::move(polygon));
    planes.push_back(plane);
  }
  hull.vertices = std::move(vertices);
  hull.faces = std::move(faces);
  hull.planes = std::move(planes);
  hull.buildIncidences();
}

bool hullContains(const CellList& hull, const LatticePoint& p)
{
  if (hull.dimension == 3)
  {
    return std::all_of(hull.planes.begin(),
      hull.planes.end(),
      [&](const FacePlane& plane) { return plane.evaluate(p) <= 0; });
  }
  if (hull.dimension == 2)
  {
    const std::vector<Index>& v = hull.faces[0];
    if (hull.planes[0].evaluate(p) != 0)
    {
      return false;
    }
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const LatticePoint& a = hull.vertices[v[k]];
      const LatticePoint& b = hull.vertices[v[(k + 1) % v.size()]];
      if (dot(hull.planes[0].normal, cross(sub(b, a), sub(p, a))) < 0)
      {
        return false;
      }
    }
    return true;
  }
  if (hull.dimension == 1)
  {
    const LatticePoint ab = sub(hull.vertices[1], hull.vertices[0]);
    const LatticePoint ap = sub(p, hull.vertices[0]);
    return cross(ab, ap) == LatticePoint{ 0, 0, 0 } && dot(ab, ap) >= 0 &&
      dot(ab, ap) <= dot(ab, ab);
  }
  return hull.dimension == 0 && p == hull.vertices[0];
}

} // namespace vbr
