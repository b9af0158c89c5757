// Shells of H joined and handles cut by exact Booleans with empty lattice prisms
// (TopologyRepair.h).
#include "TopologyRepair.h"

#include "CUDB.h"
#include "HullPointRuns.h"
#include "HullShells.h"
#include "PolyhedronReversion.h"
#include "PressingIn.h"
#include "UnionFind.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace vbr
{
using namespace detail;

namespace
{

/// Repairing the topology (see the header): a void of H whose background centres reach the
/// rest of the background through face-connected background centres, or a piece of H whose
/// object centres are face-neighbours of object centres of another piece, is joined to the rest
/// by a prism conv(T1 + T2) between an empty lattice triangle T1 of its shell and one T2 of
/// another shell, cut out of H (a void) or added to it (a piece).

/// H as its shells while shells are joined: a join replaces the shells it changed
/// (joinAlongPrism), so H is not split into its shells again after every join, and H is put
/// together from its shells only when asked for (takeMesh), not after every join. The whole H
/// given is kept only until the first replacement (it is then stale, and freed: copies of the
/// surface, one per attempted chain of cuts, do not copy it).
class ShelledSurface
{
public:
  std::vector<Shell> shells;

  explicit ShelledSurface(const LatticeMesh& m)
    : shells(shellsOf(m))
    , mesh(m)
  {
  }

  /// H, its shells appended in their order when one was replaced; the surface is left empty.
  LatticeMesh takeMesh()
  {
    if (this->stale)
    {
      this->mesh = LatticeMesh{};
      for (const Shell& s : this->shells)
        this->mesh.append(s.mesh, false);
    }
    this->stale = false;
    this->shells.clear();
    return std::move(this->mesh);
  }

  /// Puts `pieces` in the place of the shells flagged in `changed` (where the first of them
  /// was); H is put together from the shells by takeMesh.
  void replace(const std::vector<bool>& changed, std::vector<Shell>&& pieces)
  {
    std::vector<Shell> kept;
    bool placed = false;
    for (std::size_t i = 0; i < this->shells.size(); ++i)
      if (!changed[i])
        kept.push_back(std::move(this->shells[i]));
      else if (!placed)
      {
        placed = true;
        for (Shell& p : pieces)
          kept.push_back(std::move(p));
      }
    this->shells = std::move(kept);
    this->stale = true;
    this->mesh = LatticeMesh{};
  }

private:
  LatticeMesh mesh;
  bool stale = false;
};

/// Where each lattice point of the grid lies with respect to H.
enum Where : std::uint8_t
{
  Outside = 0,
  On = 1,
  Inside = 2
};

std::vector<std::uint8_t> whereInGrid(const LatticeMesh& surface, const Dims& d)
{
  std::vector<std::uint8_t> where(static_cast<std::size_t>(d[0]) * d[1] * d[2], Outside);
  markShell(surface, d, Inside, On, where);
  return where;
}

LatticePoint step(const LatticePoint& p, int k)
{
  LatticePoint q = p;
  q[k / 2] += k % 2 ? 1 : -1;
  return q;
}

/// voidCrossing's table: a centre not reached, a centre of the void (else the step 0-5 by which
/// a centre was reached).
constexpr std::uint8_t kUnreached = 255, kSeed = 6;

/// Calls f for each lattice point of the box, x fastest (the order of a scan of the grid).
template<typename F>
void forEachInBox(const LatticeBox& box, F&& f)
{
  for (std::int64_t z = box[0][2]; z <= box[1][2]; ++z)
    for (std::int64_t y = box[0][1]; y <= box[1][1]; ++y)
      for (std::int64_t x = box[0][0]; x <= box[1][0]; ++x)
        f(LatticePoint{ x, y, z });
}

/// The shell's box within the grid: where markShell flags centres (the box may be empty).
LatticeBox gridBoxOf(const Shell& shell, const Dims& d)
{
  LatticeBox box = shell.box;
  for (int k = 0; k < 3; ++k)
  {
    box[0][k] = std::max<std::int64_t>(box[0][k], 0);
    box[1][k] = std::min<std::int64_t>(box[1][k], d[k] - 1);
  }
  return box;
}

/// The tables of voidCrossing's searches, kept by the caller from one search to the next so that
/// a search allocates nothing once they have grown: the step each centre was reached by (kSeed: a
/// centre of the void; all kUnreached between searches) and the centres a search reached, in
/// the order reached: its queue (visited from the front, first in first out), and afterwards
/// the centres whose steps it resets. Each search stays
/// near its shell: a table of the grid allocated per shell cost more than the search on the full
/// aneurism, a hash map a twentieth of its time.
struct VoidSearch
{
  std::vector<std::uint8_t> from;
  std::vector<LatticePoint> todo;

  explicit VoidSearch(std::size_t centres)
    : from(centres, kUnreached)
  {
  }
};

/// The shortest face-connected path of background centres from a centre of a void (`mine`
/// flags the centres the shell encloses or holds: a thin void encloses none) to a background centre
/// strictly outside H and not flagged (or off the grid), every centre between them on H. The two
/// centres where the path leaves the shell (the last one flagged and the next), or nothing when the
/// void is sealed from the rest of the background.
std::vector<LatticePoint> voidCrossing(const BitVolume& objects,
  const std::vector<std::uint8_t>& where,
  const std::vector<std::uint8_t>& mine,
  const LatticeBox& box,
  VoidSearch& search)
{
  const Dims d = objects.dims();
  std::vector<std::uint8_t>& from = search.from;
  std::vector<LatticePoint>& todo = search.todo; // every centre reached, visited from head on
  std::size_t head = 0;
  todo.clear();
  const auto reach = [&](const LatticePoint& p, std::uint8_t how)
  {
    from[gridIndex(d, p)] = how;
    todo.push_back(p);
  };
  forEachInBox(box,
    [&](const LatticePoint& p)
    {
      if (mine[gridIndex(d, p)] && !voxelClass(objects, p))
      {
        reach(p, kSeed);
      }
    });
  std::vector<LatticePoint> found;
  bool done = false; // the first path out decides, a crossing or none
  while (head < todo.size() && !done)
  {
    const LatticePoint p = todo[head++]; // a copy: pushing below may move the list
    for (int k = 0; k < 6; ++k)
    {
      const LatticePoint q = step(p, k);
      if (!inGrid(d, q) ||
        (where[gridIndex(d, q)] == Outside && !mine[gridIndex(d, q)] && !voxelClass(objects, q)))
      {
        done = true;
        std::vector<LatticePoint> path{ q };
        for (LatticePoint r = p;;)
        {
          path.push_back(r);
          const std::uint8_t how = from[gridIndex(d, r)];
          if (how == kSeed)
            break;
          r = step(r, how ^ 1); // back along the step that reached r
        }
        // path runs from outside back to the void: the crossing is the first step (from the
        // void's side) onto a centre the shell does not hold.
        for (std::size_t i = path.size() - 1; i > 0; --i)
          if (!inGrid(d, path[i - 1]) || !mine[gridIndex(d, path[i - 1])])
          {
            found = { path[i], path[i - 1] };
            break;
          }
        break;
      }
      if (where[gridIndex(d, q)] == On && !voxelClass(objects, q) &&
        from[gridIndex(d, q)] == kUnreached)
      {
        reach(q, static_cast<std::uint8_t>(k));
      }
    }
  }
  for (const LatticePoint& p : todo) // visited or not: the search may stop at its first way out
    from[gridIndex(d, p)] = kUnreached;
  return found;
}

/// The lattice points of the box of a closed shell that lie inside or on it, in the box's own
/// coordinates (a lattice point p of the grid is p - lo there).
BitVolume heldByShell(const LatticeMesh& shell, LatticePoint& lo)
{
  ShellInBox s = shellInItsBox(shell);
  lo = s.lo;
  BitVolume held = std::move(s.inside);
  for (const auto& p : s.on)
    held.set(static_cast<std::int32_t>(p[0]),
      static_cast<std::int32_t>(p[1]),
      static_cast<std::int32_t>(p[2]));
  return held;
}

/// The points of row (y, z) of `held` (words) some face-neighbour of which is not held: the
/// others cannot have a neighbour outside the shell.
std::vector<Word> rowBorder(const BitVolume& held, std::int32_t y, std::int32_t z)
{
  const std::size_t n = held.wordsPerRow();
  const Word* row = held.row(y, z);
  const auto other = [&](std::int32_t v, std::int32_t w, std::size_t i) -> Word
  { return v < 0 || w < 0 || v >= held.size(1) || w >= held.size(2) ? 0 : held.row(v, w)[i]; };
  std::vector<Word> border(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Word h = row[i];
    const Word before = (h << 1) | (i > 0 ? row[i - 1] >> 63 : 0);    // bit x: x - 1 held
    const Word after = (h >> 1) | (i + 1 < n ? row[i + 1] << 63 : 0); // bit x: x + 1 held
    const Word inner = h & before & after & other(y - 1, z, i) & other(y + 1, z, i) &
      other(y, z - 1, i) & other(y, z + 1, i);
    border[i] = h & ~inner;
  }
  return border;
}

/// An object centre of the piece (inside or on its shell) and an object centre of another piece
/// that are face-neighbours, the first in scan order, or nothing. Only the piece's points with
/// a face-neighbour it does not hold are visited (some of these pieces' boxes hold millions of
/// their points).
std::vector<LatticePoint> pieceCrossing(const BitVolume& objects, const LatticeMesh& shell)
{
  LatticePoint lo;
  const BitVolume held = heldByShell(shell, lo);
  const auto isHeld = [&](const LatticePoint& q)
  {
    const LatticePoint r = sub(q, lo);
    for (int k = 0; k < 3; ++k)
      if (r[k] < 0 || r[k] >= held.size(k))
        return false;
    return held.get(static_cast<std::int32_t>(r[0]),
      static_cast<std::int32_t>(r[1]),
      static_cast<std::int32_t>(r[2]));
  };
  for (std::int32_t z = 0; z < held.size(2); ++z)
    for (std::int32_t y = 0; y < held.size(1); ++y)
    {
      const std::vector<Word> border = rowBorder(held, y, z);
      for (std::size_t i = 0; i < border.size(); ++i)
        for (Word bits = border[i]; bits != 0; bits &= bits - 1)
        {
          const LatticePoint p{
            lo[0] + static_cast<std::int64_t>(64 * i) + __builtin_ctzll(bits), lo[1] + y, lo[2] + z
          };
          if (!voxelClass(objects, p))
            continue;
          for (int k = 0; k < 6; ++k)
          {
            const LatticePoint q = step(p, k);
            if (voxelClass(objects, q) && !isHeld(q))
              return { p, q };
          }
        }
    }
  return {};
}

/// The empty lattice triangles of the mesh's triangles near the two centres (their boxes
/// within one step), nearest first, at most `count`.
std::vector<std::array<LatticePoint, 3>> emptyTrianglesNear(const LatticeMesh& m,
  const std::vector<LatticePoint>& near,
  std::size_t count)
{
  CellList faces;
  faces.vertices = m.points;
  for (const auto& t : m.triangles)
  {
    bool close = false;
    for (const auto& p : near)
    {
      bool in = true;
      for (int k = 0; k < 3; ++k)
        in = in &&
          std::min({ m.points[t[0]][k], m.points[t[1]][k], m.points[t[2]][k] }) <= p[k] + 1 &&
          std::max({ m.points[t[0]][k], m.points[t[1]][k], m.points[t[2]][k] }) >= p[k] - 1;
      close = close || in;
    }
    if (!close)
      continue;
    faces.faces.push_back({ t[0], t[1], t[2] });
    faces.planes.push_back(planeThrough(m.points[t[0]], m.points[t[1]], m.points[t[2]]));
  }
  std::vector<std::array<LatticePoint, 3>> found;
  EmptyFaceTriangles triangles(faces, PointRuns::of(near));
  std::array<LatticePoint, 3> t;
  while (found.size() < count && triangles.next(t))
    found.push_back(t);
  return found;
}

/// The empty triangles taken on each side of a crossing. 6 left extra shells on porous blobs
/// and hollow balls whose prisms all held a lattice point or failed the Boolean.
constexpr std::size_t kTrianglesNear = 12;

/// The empty triangles taken when none of the first prisms joined the shell: a void reaching
/// out along a 1 wide tunnel in long thin triangles (the hollow balls of R 10 with an
/// off-centre tunnel) has no prism of the 12 nearest that a Boolean accepts (36 joined one of
/// the two, 60 both).
constexpr std::size_t kMoreTrianglesNear = 60;

/// The candidate prisms conv(T1 + T2), T1 from `first` and T2 from `second` (empty lattice
/// triangles, nearest first), pair (i, j) the candidate i * second.size() + j; the pairs of the
/// `tried` first on both sides are left out (the round before offered them; it may not have
/// tried them all). A candidate is a prism when its hull is solid with no lattice point in its
/// open interior; tryPrisms makes the hulls one at a time as it needs them, since a join mostly
/// comes from one of the first prisms (making all 144 or 3,600 hulls up front was 7 % of the
/// aneurism's time).
struct PrismPairs
{
  std::vector<std::array<LatticePoint, 3>> first;
  std::vector<std::array<LatticePoint, 3>> second;
  std::size_t tried = 0;

  std::size_t size() const { return this->first.size() * this->second.size(); }
  bool offered(std::size_t k) const
  {
    return k / this->second.size() >= this->tried || k % this->second.size() >= this->tried;
  }
  std::vector<LatticePoint> corners(std::size_t k) const
  {
    const auto& a = this->first[k / this->second.size()];
    const auto& b = this->second[k % this->second.size()];
    return { a[0], a[1], a[2], b[0], b[1], b[2] };
  }
};

/// Whether the solid hull (its open interior when `strict`) holds a lattice point: the first
/// row that holds one ends the scan.
bool holdsALatticePoint(const CellList& c, bool strict)
{
  return !forEachRowIn(
    c, strict, [](std::int64_t, std::int64_t, std::int64_t, std::int64_t) { return false; });
}

/// The prism of candidate k of `pairs`, or none when its hull is flat or holds a lattice point
/// in its open interior.
std::optional<CellList> emptyPrism(const PrismPairs& pairs, std::size_t k)
{
  CellList prism = convexHull(pairs.corners(k));
  if (prism.dimension != 3 || holdsALatticePoint(prism, true))
    return std::nullopt;
  return prism;
}

/// The candidates between the `count` nearest empty triangles of the shell and of the rest of H
/// near the crossing (PrismPairs).
PrismPairs prismsAt(const LatticeMesh& shell,
  const LatticeMesh& rest,
  const std::vector<LatticePoint>& crossing,
  std::size_t count,
  std::size_t tried)
{
  return {
    emptyTrianglesNear(shell, crossing, count), emptyTrianglesNear(rest, crossing, count), tried
  };
}

/// Whether the triangle meets the open interior of the solid hull, or with `closed` the closed
/// hull (exact separating axes: the hull's face normals, the triangle's normal and the cross
/// products of their edges; a plane along one of them that leaves the triangle on one closed
/// side and the hull on the other, or with `closed` strictly apart, is the witness that it does
/// not, as for any two convex polytopes).
bool meetsConvex(const CellList& solid, const std::array<LatticePoint, 3>& t, bool closed)
{
  auto apart = [&](const LatticePoint& n)
  {
    if (n == LatticePoint{ 0, 0, 0 })
      return false;
    __int128 tLo = dot(n, t[0]), tHi = tLo, sLo = dot(n, solid.vertices[0]), sHi = sLo;
    for (const auto& p : t)
    {
      tLo = std::min(tLo, dot(n, p));
      tHi = std::max(tHi, dot(n, p));
    }
    for (const auto& p : solid.vertices)
    {
      sLo = std::min(sLo, dot(n, p));
      sHi = std::max(sHi, dot(n, p));
    }
    return closed ? tHi < sLo || sHi < tLo : tHi <= sLo || sHi <= tLo;
  };
  if (apart(cross(sub(t[1], t[0]), sub(t[2], t[0]))))
    return false;
  for (const auto& plane : solid.planes)
    if (apart(plane.normal))
      return false;
  for (int k = 0; k < 3; ++k)
    for (const auto& e : solid.edges)
      if (apart(cross(sub(t[(k + 1) % 3], t[k]), sub(solid.vertices[e[1]], solid.vertices[e[0]]))))
        return false;
  return true;
}

bool meetsOpenInterior(const CellList& solid, const std::array<LatticePoint, 3>& t)
{
  return meetsConvex(solid, t, false);
}

/// P's bounding box.
std::array<LatticePoint, 2> boxOf(const CellList& prism)
{
  std::array<LatticePoint, 2> box{ prism.vertices[0], prism.vertices[0] };
  for (const auto& v : prism.vertices)
    for (int a = 0; a < 3; ++a)
    {
      box[0][a] = std::min(box[0][a], v[a]);
      box[1][a] = std::max(box[1][a], v[a]);
    }
  return box;
}

/// Whether the prism's open interior misses H: then the Boolean changes H only on the prism's
/// boundary (a tube between T1 and T2). Where a triangle of H crosses the prism the Boolean
/// cuts it at points that are mostly not lattice points, or adds more than a tube: such prisms
/// were the bulk of the rejected Booleans (each an exact corefinement of the whole H), so they
/// are tried last; this test costs the triangles in the prism's box.
bool prismMissesSurface(const CellList& prism, const LatticeMesh& surface)
{
  for (const auto& t : trianglesInBoxOf(surface, prism))
    if (meetsOpenInterior(prism, t))
      return false;
  return true;
}

/// Whether the shell's box meets the open box of the convex hull: the shells that do not hold no
/// triangle that trianglesInBoxOf gives, so the tests local to the hull skip them whole.
bool shellNear(const Shell& shell, const CellList& convex)
{
  const LatticeBox box = boxOf(convex);
  for (int a = 0; a < 3; ++a)
    if (shell.box[1][a] <= box[0][a] || shell.box[0][a] >= box[1][a])
      return false;
  return true;
}

bool prismMissesSurface(const CellList& prism, const std::vector<Shell>& shells)
{
  for (const Shell& shell : shells)
    if (shellNear(shell, prism) && !prismMissesSurface(prism, shell.mesh))
      return false;
  return true;
}

bool booleanLeavesTheLattice(const std::vector<Shell>& shells, const CellList& prism)
{
  for (const Shell& shell : shells)
    if (shellNear(shell, prism) && booleanLeavesTheLattice(shell.mesh, prism))
      return true;
  return false;
}

/// The shells cut down to their triangles that meet the open box `box` (each shell keeps its
/// own box; its volume is not kept). For a convex hull whose box lies in `box`, a triangle
/// that meets the hull's open box meets `box`'s, so trianglesInBoxOf finds the same triangles
/// in the same order here as in the whole shells: the tests above give the same answers. The
/// prisms tried at one crossing all lie near it, and these tests ran over every triangle of the
/// vessel's main shell for each of them (8 % of the full aneurism's time).
std::vector<Shell> shellsInBox(const std::vector<Shell>& shells, const LatticeBox& box)
{
  std::vector<Shell> near;
  for (const Shell& shell : shells)
  {
    Shell cut;
    cut.box = shell.box;
    std::vector<Index> local(shell.mesh.points.size(), std::numeric_limits<Index>::max());
    for (const auto& t : shell.mesh.triangles)
    {
      bool meets = true;
      for (int a = 0; a < 3 && meets; ++a)
      {
        const auto c = [&](int k) { return shell.mesh.points[t[k]][a]; };
        meets =
          std::max({ c(0), c(1), c(2) }) > box[0][a] && std::min({ c(0), c(1), c(2) }) < box[1][a];
      }
      if (!meets)
        continue;
      std::array<Index, 3> tri;
      for (int k = 0; k < 3; ++k)
      {
        if (local[t[k]] == std::numeric_limits<Index>::max())
        {
          local[t[k]] = static_cast<Index>(cut.mesh.points.size());
          cut.mesh.points.push_back(shell.mesh.points[t[k]]);
        }
        tri[k] = local[t[k]];
      }
      cut.mesh.triangles.push_back(tri);
    }
    near.push_back(std::move(cut));
  }
  return near;
}

// The sideOf of a mesh and of a shell (HullShells.h), found next to the one of H below.
using detail::sideOf;

/// sideOf for H from its shells: the parity of the crossings is the sum of the shells'; those
/// whose box misses p's row or ends before p are not crossed (as in sideOf).
int sideOf(const ShelledSurface& surface, const LatticePoint& p, std::int64_t k)
{
  bool inside = false;
  for (const Shell& shell : surface.shells)
  {
    const LatticeBox& b = shell.box;
    if (p[0] > k * b[1][0] || p[1] < k * b[0][1] || p[1] > k * b[1][1] || p[2] < k * b[0][2] ||
      p[2] > k * b[1][2])
      continue;
    const int side = sideOf(shell, p, k);
    if (side == 0)
      return 0;
    inside = inside != (side > 0);
  }
  return inside ? 1 : -1;
}

/// Whether every lattice point of the closed prism P lies on the right side of `joined`, the
/// part of H that P changed after P was cut out of it or added to it (no object centre outside,
/// no background centre inside, off the grid included), with the new sides of those in the grid;
/// `reversed`: P lies inside the other shells of H, so a point inside the part is outside H
/// (changedPart). The solid changes only inside the closed P, so a lattice point outside P keeps
/// its side (a neighbourhood of it misses P); P's open interior holds no lattice point, but a
/// centre on its boundary can change side, so each is located again (exact ray parity) instead
/// of every point of the grid.
bool prismKeepsSeparation(const LatticeMesh& joined,
  bool reversed,
  const CellList& prism,
  const BitVolume& objects,
  std::vector<std::pair<std::size_t, std::uint8_t>>& sides)
{
  const Dims d = objects.dims();
  const std::vector<std::array<Index, 3>> near = trianglesAheadOf(joined, boxOf(prism));
  bool ok = true;
  forEachPointIn(prism,
    false,
    [&](const LatticePoint& p)
    {
      if (!ok)
        return;
      const int side = reversed ? -sideOf(joined, near, p, 1) : sideOf(joined, near, p, 1);
      const bool object = voxelClass(objects, p);
      if ((object && side < 0) || (!object && side > 0))
        ok = false;
      else if (inGrid(d, p))
        sides.emplace_back(gridIndex(d, p), side > 0 ? Inside : side == 0 ? On : Outside);
    });
  return ok;
}

bool boxesMeet(const LatticeBox& a, const LatticeBox& b)
{
  for (int k = 0; k < 3; ++k)
    if (a[1][k] < b[0][k] || b[1][k] < a[0][k])
      return false;
  return true;
}

/// The shells of H that the closed P meets (exact separating axes against their triangles in
/// P's box).
std::vector<bool> shellsMeeting(const std::vector<Shell>& shells, const CellList& prism)
{
  const LatticeBox box = boxOf(prism);
  std::vector<bool> met(shells.size(), false);
  for (std::size_t i = 0; i < shells.size(); ++i)
  {
    if (!boxesMeet(shells[i].box, box))
      continue;
    const LatticeMesh& m = shells[i].mesh;
    for (const auto& t : m.triangles)
    {
      const std::array<LatticePoint, 3> c{ m.points[t[0]], m.points[t[1]], m.points[t[2]] };
      LatticeBox b{ c[0], c[0] };
      for (const auto& p : c)
        for (int k = 0; k < 3; ++k)
        {
          b[0][k] = std::min(b[0][k], p[k]);
          b[1][k] = std::max(b[1][k], p[k]);
        }
      if (boxesMeet(b, box) && meetsConvex(prism, c, true))
      {
        met[i] = true;
        break;
      }
    }
  }
  return met;
}

/// Whether p lies inside an odd number of the shells not flagged in `skip` (p on none of them).
bool insideOtherShells(const std::vector<Shell>& shells,
  const std::vector<bool>& skip,
  const LatticePoint& p)
{
  bool inside = false;
  for (std::size_t i = 0; i < shells.size(); ++i)
  {
    // sideOf's ray towards +x stays in p's row: a shell whose box misses the row or ends
    // before p is not crossed.
    const LatticeBox& b = shells[i].box;
    if (skip[i] || p[0] > b[1][0] || p[1] < b[0][1] || p[1] > b[1][1] || p[2] < b[0][2] ||
      p[2] > b[1][2])
      continue;
    inside = inside != (sideOf(shells[i], p, 1) > 0);
  }
  return inside;
}

/// The part of H that a Boolean with the prism P can change: the shells that the closed P meets
/// (flagged in `changed`) as one mesh, reversed when P lies inside an odd number of the other
/// shells (`reversed`).
///
/// Why the Boolean of the part is the Boolean of H (so that a join costs a corefinement of the
/// shells it joins, not of all of H, and its checks look at those shells only). The solid of H
/// is the set of points inside an odd number of its shells. The other shells miss the closed P
/// (each triangle of theirs strictly apart from it) and P is connected, so the parity c of the
/// other shells is one constant on a neighbourhood of P; it is c on each shell of the part too
/// (checked below; it holds for every shell that meets P). Near P and the part, the solid of H
/// is then the part's solid (c = 0: the part bounds a volume as it is oriented) or its
/// complement (c = 1: the reversed part bounds the complement, and cutting P out of H is adding
/// P to it, and back); away from them nothing changes. So H op P is (part op P) with the other
/// shells, which miss it (it lies in the part and the boundary of P, both apart from them): H
/// op P is embedded exactly when part op P is, its shells and Euler characteristic change as
/// the part's do, and a point of P lies inside H op P exactly when it lies inside part op P,
/// or outside when c = 1. Should the parity differ on a shell of the part (it cannot when the
/// separating axes are exact), the part is all of H.
struct ChangedPart
{
  std::vector<bool> changed;
  LatticeMesh mesh;
  bool reversed = false;
};

ChangedPart changedPart(const std::vector<Shell>& shells, const CellList& prism)
{
  ChangedPart part;
  part.changed = shellsMeeting(shells, prism);
  part.reversed = insideOtherShells(shells, part.changed, prism.vertices[0]);
  for (std::size_t i = 0; i < shells.size(); ++i)
    if (part.changed[i] &&
      insideOtherShells(shells, part.changed, shells[i].mesh.points[0]) != part.reversed)
    {
      part.changed.assign(shells.size(), true);
      part.reversed = false;
      break;
    }
  for (std::size_t i = 0; i < shells.size(); ++i)
    if (part.changed[i])
      part.mesh.append(shells[i].mesh, part.reversed);
  return part;
}

/// Whether the prism may join a shell by a Boolean, from the cheap tests: it runs through H's
/// solid (a cut) or through the space between two pieces (a join), as its centroid tells, and
/// no edge of it crosses a triangle of H off the lattice (a Boolean latticeBoolean refuses,
/// nearly all the prisms refused on the Al cartoon and the headsq bone), found from the
/// triangles in P's box, without the corefinement.
bool worthABoolean(const ShelledSurface& surface,
  const std::vector<Shell>& near,
  const CellList& prism,
  bool cut)
{
  LatticePoint centroid{ 0, 0, 0 };
  for (const auto& v : prism.vertices)
    for (int a = 0; a < 3; ++a)
      centroid[a] += v[a];
  const auto n = static_cast<std::int64_t>(prism.vertices.size());
  return sideOf(surface, centroid, n) == (cut ? 1 : -1) && !booleanLeavesTheLattice(near, prism);
}

/// The exact union (unite) or difference of a part of H and a prism, computed near the prism
/// where latticeBooleanNear can tell, else by the whole Boolean; false when refused.
bool booleanWithPrism(const LatticeMesh& part,
  const CellList& prism,
  bool unite,
  LatticeMesh& result)
{
  const NearBoolean near = latticeBooleanNear(part, prism, unite, result);
  if (near != NearBoolean::Unknown)
    return near == NearBoolean::Done;
  const LatticeMesh hull = triangulateHull(prism);
  return unite ? latticeUnion(part, hull, result, Operands::Embedded)
               : latticeDifference(part, hull, result, Operands::Embedded);
}

/// H with the prism cut out (a void or a handle) or added (a piece), kept only when the exact
/// Boolean is a closed 2-manifold with lattice corners, `shells` shells (one less for a join,
/// as many for a handle or a dent) and an Euler characteristic `eulerDrop` lower (2: a tube;
/// 0: the dent of a chain, joinByChain), and every lattice point of P stays on its class's side
/// (prismKeepsSeparation). The Boolean and the checks are those of the part of H that P meets
/// (changedPart says why that is H's). A Boolean that fails, or throws, rejects this prism only.
bool joinAlongPrism(Context& ctx,
  const CellList& prism,
  bool cut,
  std::size_t shells,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where,
  long eulerDrop = 2)
{
  // The part was embedded and the Boolean changed it only inside P, so only triangles meeting
  // P's box can cross (the operands are not tested again: that test of a large operand costs
  // about as much as the corefinement).
  const std::array<LatticePoint, 2> box = boxOf(prism);
  const ChangedPart part = changedPart(surface.shells, prism);
  // A Boolean bound to fail costs no corefinement (it still counts as one tried: tryPrisms).
  if (creaseLeavesTheLattice(part.mesh, prism))
    return false;
  const auto others =
    static_cast<std::size_t>(std::count(part.changed.begin(), part.changed.end(), false));
  LatticeMesh joined;
  std::vector<Shell> pieces;
  std::vector<std::pair<std::size_t, std::uint8_t>> sides;
  try
  {
    // Reversed, the part bounds the complement of H's solid near P: cutting is adding. The
    // Boolean from the part's triangles near P first (the part is mostly the vessel's main
    // shell on the aneurism: the whole corefinement costs all of it for every prism tried).
    const bool unite = cut == part.reversed;
    if (edgeCrossingLeavesTheLattice(part.mesh, prism, unite) ||
      !booleanWithPrism(part.mesh, prism, unite, joined))
      return false;
    if (part.reversed)
      for (auto& t : joined.triangles)
        std::swap(t[1], t[2]);
    pieces = shellsOf(joined);
    if (pieces.size() + others != shells ||
      eulerCharacteristic(joined) + eulerDrop != eulerCharacteristic(part.mesh) ||
      !isEmbeddedWithin(joined, box[0], box[1]) ||
      !prismKeepsSeparation(joined, part.reversed, prism, ctx.objects, sides))
      return false;
  }
  catch (const std::exception&)
  {
    return false; // CGAL refused the operands or the result: try the next prism
  }
  recordPlanes(ctx, prism, cut ? 1 : 2);
  surface.replace(part.changed, std::move(pieces));
  for (const auto& [index, side] : sides)
    where[index] = side;
  return true;
}

/// The prisms tried per shell and round, nearest first (each costs an exact Boolean and a check;
/// those worthABoolean rejects are not counted).
constexpr std::size_t kPrismsTried = 48;

/// The box of every corner of the candidates: each prism's box lies in it.
LatticeBox boxOfCandidates(const PrismPairs& pairs)
{
  LatticeBox all{ pairs.first[0][0], pairs.first[0][0] };
  for (const auto* side : { &pairs.first, &pairs.second })
    for (const auto& t : *side)
      for (const auto& p : t)
        for (int a = 0; a < 3; ++a)
        {
          all[0][a] = std::min(all[0][a], p[a]);
          all[1][a] = std::max(all[1][a], p[a]);
        }
  return all;
}

/// Cuts out (`cut`) or adds the first of the prisms of `pairs` that joinAlongPrism keeps with
/// `shells` shells: those whose open interior misses H first (nearest first among them), then
/// the others; the cheap tests of worthABoolean run only until kPrismsTried prisms have passed
/// them. Each hull is made once, when the first round reaches it.
bool tryPrisms(Context& ctx,
  const PrismPairs& pairs,
  bool cut,
  std::size_t shells,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where)
{
  const std::size_t n = pairs.size();
  if (n == 0)
    return false;
  // The shells near the candidates (a join ends the loop, so H does not change under them).
  // Every prism's box lies in the candidates' box, so the tests find the same triangles here.
  const std::vector<Shell> near = shellsInBox(surface.shells, boxOfCandidates(pairs));
  enum : std::uint8_t
  {
    Unmade,
    NoPrism,
    Misses,
    Crosses
  };
  std::vector<std::uint8_t> state(n, Unmade);
  std::vector<CellList> prisms(n);
  std::size_t booleans = 0;
  for (const std::uint8_t round : { Misses, Crosses })
    for (std::size_t k = 0; k < n && booleans < kPrismsTried; ++k)
    {
      if (!pairs.offered(k))
        continue;
      if (state[k] == Unmade)
      {
        std::optional<CellList> prism = emptyPrism(pairs, k);
        state[k] = !prism ? NoPrism : prismMissesSurface(*prism, near) ? Misses : Crosses;
        if (prism)
          prisms[k] = std::move(*prism);
      }
      if (state[k] != round)
        continue;
      if (ctx.exec.stopRequested())
        throw std::runtime_error("aborted");
      if (!worthABoolean(surface, near, prisms[k], cut))
        continue;
      ++booleans;
      if (joinAlongPrism(ctx, prisms[k], cut, shells, surface, where))
        return true;
    }
  return false;
}

/// The shells of H other than shell s, as one mesh.
LatticeMesh restOfH(const std::vector<Shell>& shells, std::size_t s)
{
  LatticeMesh rest;
  for (std::size_t o = 0; o < shells.size(); ++o)
    if (o != s)
      rest.append(shells[o].mesh, false);
  return rest;
}

/// Joins the shell to the rest of H by one of the prisms between the `count` nearest empty
/// triangles on each side of the crossing (see prismsAt for `tried`); false when none joins.
bool joinAtCrossing(Context& ctx,
  const std::vector<Shell>& shells,
  std::size_t s,
  const std::vector<LatticePoint>& crossing,
  std::size_t count,
  std::size_t tried,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where)
{
  const LatticeMesh rest = restOfH(shells, s);
  return tryPrisms(ctx,
    prismsAt(shells[s].mesh, rest, crossing, count, tried),
    shells[s].volume < 0,
    shells.size() - 1,
    surface,
    where);
}

/// The chains of two prisms tried per void whose single prisms all failed (each one or two
/// exact Booleans).
constexpr std::size_t kChainsTried = 8;

/// The corners of the middle triangles of the chains: at most this many, nearest first (560
/// triangles; the hollow balls have 10 to 16 near their crossing).
constexpr std::size_t kChainCorners = 16;

/// The lattice points strictly inside H within one step (in each coordinate) of a centre of the
/// crossing, the kChainCorners nearest to its middle: the corners of the middle triangles.
std::vector<LatticePoint> chainCorners(const std::vector<std::uint8_t>& where,
  const Dims& d,
  const std::vector<LatticePoint>& crossing)
{
  std::set<LatticePoint> found;
  LatticePoint sum{ 0, 0, 0 };
  for (const LatticePoint& c : crossing)
  {
    for (int a = 0; a < 3; ++a)
      sum[a] += c[a];
    for (std::int64_t z = c[2] - 1; z <= c[2] + 1; ++z)
      for (std::int64_t y = c[1] - 1; y <= c[1] + 1; ++y)
        for (std::int64_t x = c[0] - 1; x <= c[0] + 1; ++x)
          if (inGrid(d, { x, y, z }) && where[gridIndex(d, { x, y, z })] == Inside)
            found.insert({ x, y, z });
  }
  std::vector<LatticePoint> corners(found.begin(), found.end());
  const auto m = static_cast<std::int64_t>(crossing.size());
  std::stable_sort(corners.begin(),
    corners.end(),
    [&](const LatticePoint& p, const LatticePoint& q)
    { return scaledDistance(p, 1, sum, m) < scaledDistance(q, 1, sum, m); });
  if (corners.size() > kChainCorners)
    corners.resize(kChainCorners);
  return corners;
}

/// The side of the plane the triangle lies on: 1 or -1 when it lies in that closed side and
/// not in the plane, 0 otherwise. A corner may touch the plane, so M need not be a whole face
/// of the hull of each triangle with M, and the two hulls may share more than M; the chain is
/// kept only when each cut passes joinAlongPrism's checks. (Requiring every corner strictly
/// off the plane leaves 4 of the 72 hollow balls of HollowBallsWithOffCentreTunnels without
/// the object's topology.)
int sideOfPlane(const FacePlane& plane, const std::array<LatticePoint, 3>& t)
{
  bool below = false, above = false;
  for (const auto& p : t)
  {
    below = below || plane.evaluate(p) < 0;
    above = above || plane.evaluate(p) > 0;
  }
  return above == below ? 0 : above ? 1 : -1;
}

/// conv(t + m) when it is solid with no lattice point in its open interior and its open
/// interior misses H (tests local to its box; worthABoolean, which scans H, is left for the
/// prisms that are cut).
std::optional<CellList> emptyPrismMissingH(const std::array<LatticePoint, 3>& t,
  const std::array<LatticePoint, 3>& m,
  const ShelledSurface& surface)
{
  CellList prism = convexHull({ t[0], t[1], t[2], m[0], m[1], m[2] });
  bool empty = prism.dimension == 3;
  if (empty)
    forEachPointIn(prism, true, [&](const LatticePoint&) { empty = false; });
  if (!empty || !prismMissesSurface(prism, surface.shells))
    return std::nullopt;
  return prism;
}

/// Cuts the chain out of H: P1 first (a dent: as many shells, the same Euler characteristic),
/// then the first of the P2 that joins (joinAlongPrism checks each); H unchanged unless one
/// does.
bool cutChain(Context& ctx,
  const CellList& first,
  const std::vector<CellList>& second,
  std::size_t shells,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where)
{
  const auto planes = ctx.planeLevel;
  ShelledSurface dented = surface;
  std::vector<std::uint8_t> sides = where;
  if (joinAlongPrism(ctx, first, true, shells, dented, sides, 0))
    for (const CellList& p2 : second)
      if (joinAlongPrism(ctx, p2, true, shells - 1, dented, sides))
      {
        surface = std::move(dented);
        where = std::move(sides);
        return true;
      }
  ctx.planeLevel = planes;
  return false;
}

/// A void whose shell reaches the crossing only in long thin triangles, so that every prism
/// between one of them and a triangle of the rest of H holds a lattice point (the hollow balls
/// of R 8 to 10 with a 1 wide off-centre tunnel: the void's shell ends in a cone whose apex is
/// the tunnel's last centre, a lattice plane of object centres between it and the hull face
/// beyond): a chain of two prisms through a middle triangle M of lattice points strictly inside
/// H near the crossing, P1 = conv(T1 + M) from an empty triangle T1 of the void's shell and
/// P2 = conv(M + T2) to one T2 of the rest of H (the 12 nearest of each), M a face of both,
/// each with no lattice point in its open interior and its open interior missing H.
bool joinByChain(Context& ctx,
  const std::vector<Shell>& shells,
  std::size_t s,
  const std::vector<LatticePoint>& crossing,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where)
{
  const LatticeMesh rest = restOfH(shells, s);
  const auto first = emptyTrianglesNear(shells[s].mesh, crossing, kTrianglesNear);
  const auto second = emptyTrianglesNear(rest, crossing, kTrianglesNear);
  const std::vector<LatticePoint> c = chainCorners(where, ctx.objects.dims(), crossing);
  std::size_t chains = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = i + 1; j < c.size(); ++j)
      for (std::size_t k = j + 1; k < c.size(); ++k)
      {
        if (ctx.exec.stopRequested())
          throw std::runtime_error("aborted");
        const std::array<LatticePoint, 3> m{ c[i], c[j], c[k] };
        const FacePlane plane = planeThrough(m[0], m[1], m[2]);
        if (plane.normal == LatticePoint{ 0, 0, 0 })
          continue;
        // The P2 beyond M from each side, made only once a P1 from that side is found (the
        // prisms from the long thin triangles of the void's shell mostly hold a lattice point).
        std::optional<std::vector<CellList>> beyond[2];
        for (const auto& t1 : first)
        {
          const int side = sideOfPlane(plane, t1);
          if (side == 0)
            continue;
          const auto p1 = emptyPrismMissingH(t1, m, surface);
          if (!p1 || !worthABoolean(surface, surface.shells, *p1, true))
            continue;
          auto& p2 = beyond[side > 0];
          if (!p2)
          {
            p2.emplace();
            for (const auto& t2 : second)
              if (sideOfPlane(plane, t2) == -side)
                if (auto p = emptyPrismMissingH(t2, m, surface))
                  if (worthABoolean(surface, surface.shells, *p, true))
                    p2->push_back(std::move(*p));
          }
          if (p2->empty())
            continue;
          if (cutChain(ctx, *p1, *p2, shells.size(), surface, where))
            return true;
          if (++chains == kChainsTried)
            return false;
        }
      }
  return false;
}

/// Joins one shell of H to the rest where the object's or the background's face-connected
/// centres cross it (see above), from the nearest empty triangles and, when none of their
/// prisms joins, from more of them, and a void then by a chain of two prisms; false when no
/// shell could be joined.
bool joinOneShell(Context& ctx,
  ShelledSurface& surface,
  std::vector<std::uint8_t>& where,
  std::vector<std::uint8_t>& mine,
  VoidSearch& search,
  std::set<LatticePoint>& failed)
{
  // A join changes the shells only when it returns true, and then this returns at once.
  const std::vector<Shell>& shells = surface.shells;
  if (shells.size() < 2)
    return false;
  const Dims d = ctx.objects.dims();
  for (std::size_t s = 0; s < shells.size(); ++s)
  {
    if (ctx.exec.stopRequested())
      throw std::runtime_error("aborted");
    const LatticePoint key =
      *std::min_element(shells[s].mesh.points.begin(), shells[s].mesh.points.end());
    if (failed.count(key))
      continue;
    failed.insert(key);
    std::vector<LatticePoint> crossing;
    if (shells[s].volume < 0)
    {
      // `mine` is all 0 but where markShell flags the shell's box, cleared after the search.
      const LatticeBox box = gridBoxOf(shells[s], d);
      markShell(shells[s].mesh, d, 1, 2, mine);
      crossing = voidCrossing(ctx.objects, where, mine, box, search);
      forEachInBox(box, [&](const LatticePoint& p) { mine[gridIndex(d, p)] = 0; });
    }
    else
      crossing = pieceCrossing(ctx.objects, shells[s].mesh);
    if (crossing.empty())
      continue;
    if (joinAtCrossing(ctx, shells, s, crossing, kTrianglesNear, 0, surface, where) ||
      joinAtCrossing(
        ctx, shells, s, crossing, kMoreTrianglesNear, kTrianglesNear, surface, where) ||
      (shells[s].volume < 0 && joinByChain(ctx, shells, s, crossing, surface, where)))
    {
      // A shell that failed stays failed although a later join may open a way for it: trying
      // the failed ones again once after a later join did not join a single further shell on
      // the hollow balls (their voids' prisms still crossed H off the lattice) and cost
      // Booleans on the Al cartoon.
      failed.erase(key);
      return true;
    }
  }
  return false;
}

/// Puts `changed` (made by `count` changes to `surface`) in the place of `surface` when there
/// was a change and it still separates; otherwise keeps `surface` and gives the face planes back
/// the levels they had before (`planes`). Returns the changes kept.
int keepIfSeparates(Context& ctx,
  int count,
  LatticeMesh&& changed,
  const std::map<FacePlane, int>& planes,
  LatticeMesh& surface)
{
  if (count == 0 || !separatesAfterLocalChecks(ctx.objects, changed))
  {
    ctx.discardedChanges += count;
    ctx.planeLevel = planes;
    return 0;
  }
  surface = std::move(changed);
  return count;
}

/// The face-connected components of a voxel set: how many, and how many of them reach the
/// border of the grid.
std::array<long, 2> componentCount(const BitVolume& set, bool plane)
{
  CUDB cudb;
  Components comps;
  buildCUDBComponents(
    plane ? extractEVM2D(set) : extractEVM(set), Connectivity::Face, Execution(), cudb, comps);
  // A component reaches the border when one of its boxes does: no labels painted.
  const Dims d = set.dims();
  std::vector<bool> border(static_cast<std::size_t>(comps.count) + 1, false);
  for (std::size_t b = 0; b < cudb.boxes.size(); ++b)
  {
    const Box& box = cudb.boxes[b];
    bool atBorder = false;
    for (int a = 0; a < 3; ++a)
      atBorder |= box.lo[a] == 0 || box.hi[a] == d[a];
    if (atBorder)
      border[comps.boxLabel[b]] = true;
  }
  return { static_cast<long>(comps.count),
    static_cast<long>(std::count(border.begin() + 1, border.end(), true)) };
}

/// Missing handles (see the header): the walls of H between two face-neighbouring background
/// centres, neither inside H and one on it, whose segment's midpoint lies strictly inside H.
/// At most `limit`, in grid order; `skip` holds those already tried.
std::vector<std::array<LatticePoint, 2>> wallCrossings(const BitVolume& objects,
  const LatticeMesh& surface,
  const std::vector<std::uint8_t>& where,
  const std::set<std::array<LatticePoint, 2>>& skip,
  std::size_t limit)
{
  const Dims d = objects.dims();
  std::vector<std::array<LatticePoint, 2>> found;
  for (std::int32_t z = 0; z < d[2]; ++z)
    for (std::int32_t y = 0; y < d[1]; ++y)
      for (std::int32_t x = 0; x < d[0] && found.size() < limit; ++x)
      {
        const LatticePoint p{ x, y, z };
        if (where[gridIndex(d, p)] != On || voxelClass(objects, p))
          continue;
        for (int k = 0; k < 6 && found.size() < limit; ++k)
        {
          const LatticePoint q = step(p, k);
          if (!inGrid(d, q) || voxelClass(objects, q) || where[gridIndex(d, q)] == Inside ||
            (where[gridIndex(d, q)] == On && q < p) || skip.count({ p, q }))
            continue;
          if (sideOf(surface, { p[0] + q[0], p[1] + q[1], p[2] + q[2] }, 2) > 0)
            found.push_back({ p, q });
        }
      }
  return found;
}

/// Cuts one handle through H at a wall crossing: a prism conv(T1 + T2) between an empty
/// triangle of H near each of the two centres, cut out when H keeps its shells, its Euler
/// characteristic drops by 2 and every centre stays on its side (joinAlongPrism).
bool cutAtCrossing(Context& ctx,
  const std::array<LatticePoint, 2>& crossing,
  LatticeMesh& surface,
  std::vector<std::uint8_t>& where)
{
  ShelledSurface shelled(surface);
  const std::size_t shells = shelled.shells.size();
  for (const auto& [count, tried] : { std::array<std::size_t, 2>{ kTrianglesNear, 0 },
         std::array<std::size_t, 2>{ kMoreTrianglesNear, kTrianglesNear } })
  {
    const PrismPairs pairs{ emptyTrianglesNear(surface, { crossing[0] }, count),
      emptyTrianglesNear(surface, { crossing[1] }, count),
      tried };
    if (tryPrisms(ctx, pairs, true, shells, shelled, where))
    {
      surface = shelled.takeMesh();
      return true;
    }
  }
  return false;
}

/// The wall crossings tried per round of cutMissingHandles.
constexpr std::size_t kCrossingsTried = 16;

} // namespace

namespace detail
{

int joinShells(Context& ctx, LatticeMesh& surface)
{
  if (shellsOf(surface).size() < 2)
    return 0; // nothing to join: the grid is not located at all
  int joined = 0;
  std::set<LatticePoint> failed;
  ShelledSurface repaired(surface);
  const auto planes = ctx.planeLevel;
  std::vector<std::uint8_t> where = whereInGrid(surface, ctx.objects.dims());
  std::vector<std::uint8_t> mine(where.size(), 0);
  VoidSearch search(where.size());
  while (joinOneShell(ctx, repaired, where, mine, search, failed))
    ++joined;
  // Checked once at the end, without a self-intersection test of the whole surface
  // (separatesAfterLocalChecks).
  return keepIfSeparates(ctx, joined, repaired.takeMesh(), planes, surface);
}

const std::optional<long>& objectEuler(Context& ctx)
{
  if (!ctx.euler)
    ctx.euler = wellComposedBoundaryEuler(ctx.objects, ctx.exec);
  return *ctx.euler;
}

long objectSurfaces(Context& ctx)
{
  if (ctx.surfaces < 0)
  {
    const Dims d = ctx.objects.dims();
    BitVolume background(d[0], d[1], d[2]);
    for (std::int32_t z = 0; z < d[2]; ++z)
      for (std::int32_t y = 0; y < d[1]; ++y)
        for (std::int32_t x = 0; x < d[0]; ++x)
          background.set(x, y, z, !ctx.objects.get(x, y, z));
    const std::array<long, 2> voids = componentCount(background, d[2] == 1);
    ctx.surfaces = componentCount(ctx.objects, d[2] == 1)[0] + voids[0] - voids[1];
  }
  return ctx.surfaces;
}

int cutMissingHandles(Context& ctx, LatticeMesh& surface)
{
  const std::optional<long>& target = objectEuler(ctx);
  if (!target || eulerCharacteristic(surface) <= *target ||
    static_cast<long>(shellsOf(surface).size()) != objectSurfaces(ctx))
    return 0;
  const auto planes = ctx.planeLevel;
  LatticeMesh cut = surface;
  std::vector<std::uint8_t> where = whereInGrid(cut, ctx.objects.dims());
  std::set<std::array<LatticePoint, 2>> failed;
  int cuts = 0;
  while (eulerCharacteristic(cut) > *target)
  {
    bool done = false;
    for (const auto& c : wallCrossings(ctx.objects, cut, where, failed, kCrossingsTried))
    {
      if (cutAtCrossing(ctx, c, cut, where))
      {
        done = true;
        break;
      }
      failed.insert(c);
    }
    if (!done)
      break;
    ++cuts;
  }
  return keepIfSeparates(ctx, cuts, std::move(cut), planes, surface);
}

} // namespace detail

} // namespace vbr
