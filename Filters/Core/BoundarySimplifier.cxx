#include "BoundarySimplifier.h"

#include "FaceOctreeBoundary.h"
#include "Geometry.h"
#include "Prefetch.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_profile.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/internal/LindstromTurk_params.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/internal/Lindstrom_Turk_core.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <queue>

namespace vbr
{
namespace
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point3>;
using VertexId = Mesh::Vertex_index;
using FaceId = Mesh::Face_index;
namespace SMS = CGAL::Surface_mesh_simplification;

/// Pieces of triangles are no longer halved below this radius (voxel units).
constexpr double SmallestPiece = 0.05;

Vec3 vec(const Point3& p)
{
  return { p.x(), p.y(), p.z() };
}

double dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Squared distances compared with a box's lower bound are allowed this rounding (voxel units
/// squared; the rounding of both is below 1e-10 for coordinates up to 10^4).
constexpr double NearestSlack = 1e-6;

/// Squared distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
double squaredDistanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  auto at = [&](double v, double w)
  {
    const Vec3 q{
      a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w
    };
    const Vec3 d = sub(p, q);
    return dot(d, d);
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
    return dot(ap, ap);
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
    return dot(bp, bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return at(d1 / (d1 - d3), 0);
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
    return dot(cp, cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w);
  }
  const double denom = 1 / (va + vb + vc);
  return at(vb * denom, vc * denom);
}

/// The distance from a point to the surfels of an object (FaceOctreeBoundary.h's search).
/// With a box given, the surfels among the faces of the box's voxels are marked once (three
/// bits per voxel, the faces towards +x, +y, +z), and a point whose search stays inside the
/// box reads them there instead of reading the voxels around it on each call: the same faces
/// in the same search (distanceToNearestFace), so the same distance, several times faster
/// (the simplifier asks for millions of distances). Points whose search leaves the box are
/// answered as without it.
class SurfelDistance
{
public:
  explicit SurfelDistance(const BitVolume& object)
    : Object(object)
  {
  }

  /// Marks the surfels of the voxels within Margin of the box [lo, hi] (voxel units) of a
  /// surface of `faces` triangles, unless the box is large for the surface (a byte per voxel
  /// of a sparse surface's box would grow with the box, not the surface): then every distance
  /// is searched in the object itself, as without marks.
  SurfelDistance(const BitVolume& object,
    const Vec3& lo,
    const Vec3& hi,
    std::size_t faces,
    const Execution& exec)
    : Object(object)
  {
    double voxels = 1;
    for (int d = 0; d < 3; ++d)
    {
      this->First[d] = std::int32_t(std::floor(lo[d])) - Margin;
      this->Size[d] = std::int32_t(std::floor(hi[d])) + Margin + 1 - this->First[d];
      voxels *= double(this->Size[d]);
    }
    if (voxels > 64.0 * double(faces) + double(std::int64_t(1) << 24))
      return;
    for (int d = 0; d < 3; ++d)
      this->Bricks[d] = std::size_t(this->Size[d] + 3) / 4;
    this->Faces.assign(this->Bricks[0] * this->Bricks[1] * this->Bricks[2] * 64, 0);
    exec.forWork(std::int64_t(this->Faces.size()))
      .forRange(std::int64_t(this->Bricks[2]),
        [this](std::int64_t begin, std::int64_t end)
        {
          for (std::int32_t z = 4 * std::int32_t(begin);
               z < std::min(4 * std::int32_t(end), this->Size[2]);
               ++z)
            this->markSlice(z);
        });
  }

  bool at(std::int32_t i, std::int32_t j, std::int32_t k) const
  {
    return inObject(this->Object, i, j, k);
  }

  double operator()(const Vec3& p) const
  {
    const std::int32_t c[3] = {
      std::int32_t(std::floor(p[0])), std::int32_t(std::floor(p[1])), std::int32_t(std::floor(p[2]))
    };
    for (int d = 0; d < 3; ++d) // the wide search reads the faces of the voxels c - 3..c + 2
      if (this->Faces.empty() || c[d] - 3 < this->First[d] ||
        c[d] + 2 >= this->First[d] + this->Size[d])
        return distanceToSurfels(this->Object, p);
    return distanceInTwoSearches(p, // distanceToNearestFace's searches, over the marked faces
      [&](
        const std::int32_t*, const std::int32_t lo[3], const std::int32_t hi[3], double best, bool)
      { return this->nearestMarkedSquared(p, lo, hi, best); });
  }

private:
  static constexpr std::int32_t Margin = 4;

  /// The marks are stored by bricks of 4^3 voxels, 64 bytes: a search's 27 voxels then span
  /// about 3 cache lines instead of 9 rows (the marks miss the cache: the pieces measured one
  /// after the other are far apart on the surface).
  std::size_t index(std::int32_t i, std::int32_t j, std::int32_t k) const
  {
    const std::uint32_t x = std::uint32_t(i - this->First[0]),
                        y = std::uint32_t(j - this->First[1]),
                        z = std::uint32_t(k - this->First[2]);
    const std::size_t brick =
      (std::size_t(z >> 2) * this->Bricks[1] + (y >> 2)) * this->Bricks[0] + (x >> 2);
    return brick * 64 + (x & 3) + ((y & 3) << 2) + ((z & 3) << 4);
  }

  /// nearestFaceSquared over the marked faces: the same squared distances, so the same
  /// smallest. Each axis's terms are computed once per search, as nearestFaceSquared computes
  /// them (along a face's normal the distance to its plane, along the other axes to its
  /// voxel's side), and summed in the same order. A voxel whose box is farther than the
  /// nearest face so far is skipped (each term of its faces is at least the box's), and p's
  /// own voxel comes first, so that most of the others are.
  double nearestMarkedSquared(const Vec3& p,
    const std::int32_t lo[3],
    const std::int32_t hi[3],
    double best) const
  {
    constexpr int Widest = 6; // the wide search's voxels per axis
    double side[3][Widest], plane[3][Widest];
    for (int d = 0; d < 3; ++d)
      for (std::int32_t v = lo[d]; v <= hi[d]; ++v)
      {
        const double faceLo = v, faceHi = v + 1.0;
        const double e = p[d] < faceLo ? faceLo - p[d] : (p[d] > faceHi ? p[d] - faceHi : 0.0);
        const double f = p[d] < faceHi ? faceHi - p[d] : (p[d] > faceHi ? p[d] - faceHi : 0.0);
        side[d][v - lo[d]] = e * e;
        plane[d][v - lo[d]] = f * f;
      }
    const auto visit = [&](std::int32_t i, std::int32_t j, std::int32_t k)
    {
      const int o[3] = { i - lo[0], j - lo[1], k - lo[2] };
      if (side[0][o[0]] + side[1][o[1]] + side[2][o[2]] > best)
        return;
      for (unsigned bits = this->Faces[this->index(i, j, k)]; bits != 0; bits &= bits - 1)
      {
        const int a = bits & 1 ? 0 : (bits & 2 ? 1 : 2);
        double d2 = 0;
        for (int d = 0; d < 3; ++d)
          d2 += d == a ? plane[d][o[d]] : side[d][o[d]];
        best = std::min(best, d2);
      }
    };
    std::int32_t own[3];
    for (int d = 0; d < 3; ++d)
      own[d] = std::clamp(std::int32_t(std::floor(p[d])), lo[d], hi[d]);
    visit(own[0], own[1], own[2]);
    for (std::int32_t k = lo[2]; k <= hi[2]; ++k)
      for (std::int32_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int32_t i = lo[0]; i <= hi[0]; ++i)
          if (i != own[0] || j != own[1] || k != own[2])
            visit(i, j, k);
    return best;
  }

  void markSlice(std::int32_t z)
  {
    const std::int32_t k = this->First[2] + z;
    for (std::int32_t j = this->First[1]; j < this->First[1] + this->Size[1]; ++j)
      for (std::int32_t i = this->First[0]; i < this->First[0] + this->Size[0]; ++i)
      {
        const bool here = this->at(i, j, k);
        this->Faces[this->index(i, j, k)] = std::uint8_t((here != this->at(i + 1, j, k)) |
          ((here != this->at(i, j + 1, k)) << 1) | ((here != this->at(i, j, k + 1)) << 2));
      }
  }

  const BitVolume& Object;
  std::int32_t First[3] = { 0, 0, 0 }, Size[3] = { 0, 0, 0 };
  std::size_t Bricks[3] = { 0, 0, 0 };
  std::vector<std::uint8_t> Faces; ///< per voxel of the box, bit a: its face towards +a
};

using Corners = std::array<Vec3, 3>;

/// The distance of a piece's centre and its radius (see (a) on top), and its halving.
struct Piece
{
  Corners t;
  double centre = 0, radius = 0;

  void measure(const SurfelDistance& distance) { this->centre = distance(this->measureRadius()); }

  /// The radius about the centre of the enclosing ball, and that centre.
  Vec3 measureRadius()
  {
    const Vec3 c = this->enclosingCentre();
    this->radius = 0;
    for (const Vec3& p : this->t)
      this->radius = std::max(this->radius, std::sqrt(dot(sub(p, c), sub(p, c))));
    return c;
  }

  /// The centre of the smallest ball about t (the middle of its longest side when the angle
  /// opposite is not acute, else the circumcentre), or the centroid for a degenerate t: the
  /// bound centre + radius is then as small as one distance can make it (the centroid's ball
  /// is larger, much larger for the long thin triangles that simplification makes).
  Vec3 enclosingCentre() const
  {
    const Vec3 centroid{ (t[0][0] + t[1][0] + t[2][0]) / 3,
      (t[0][1] + t[1][1] + t[2][1]) / 3,
      (t[0][2] + t[1][2] + t[2][2]) / 3 };
    for (int i = 0; i < 3; ++i)
    {
      const Vec3 &a = this->t[i], &b = this->t[(i + 1) % 3], &o = this->t[(i + 2) % 3];
      if (dot(sub(a, o), sub(b, o)) <= 0) // the angle at o is not acute: ab is the longest
        return { 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]) };
    }
    const Vec3 a = sub(this->t[0], this->t[2]), b = sub(this->t[1], this->t[2]);
    const Vec3 n = cross(a, b);
    const double n2 = dot(n, n);
    if (!(n2 > 0))
      return centroid;
    const double a2 = dot(a, a), b2 = dot(b, b);
    const Vec3 w =
      cross(Vec3{ a2 * b[0] - b2 * a[0], a2 * b[1] - b2 * a[1], a2 * b[2] - b2 * a[2] }, n);
    const Vec3& o = this->t[2];
    return { o[0] + w[0] / (2 * n2), o[1] + w[1] / (2 * n2), o[2] + w[2] / (2 * n2) };
  }

  std::array<Corners, 2> halves() const
  {
    int e = 0;
    double longest = -1;
    for (int i = 0; i < 3; ++i)
    {
      const Vec3 d = sub(this->t[(i + 1) % 3], this->t[i]);
      if (dot(d, d) > longest)
        longest = dot(d, d), e = i;
    }
    const Vec3 &a = this->t[e], &b = this->t[(e + 1) % 3], &c = this->t[(e + 2) % 3];
    const Vec3 m{ 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]) };
    return { Corners{ a, m, c }, Corners{ m, b, c } };
  }
};

/// The distances to the surfels at the voxel corners of a box, each searched once, on first
/// use, and kept in blocks of 8^3 corners allocated as the surface reaches them (memory grows
/// with the surface, not the box). The distance is 1-Lipschitz (and so is its value capped
/// at 2, which the search reports), so the value at the corner nearest to p bounds p's within
/// their distance: (a)'s pieces are decided by that bound where it suffices, at the cost of a
/// look-up instead of a search. The simplification proves the same regions again and again as
/// the stars around them collapse, so the corners are reused: on the 128^3 ball 54,000
/// corners were searched and 480,000 pieces, against 1.14 million pieces searched without
/// them (a lattice of quarter voxels decided more pieces but searched more points in all).
class LatticeDistances
{
public:
  LatticeDistances(const SurfelDistance& distance, const Vec3& lo, const Vec3& hi)
    : Distance(distance)
  {
    double blocks = 1;
    for (int d = 0; d < 3; ++d)
    {
      this->Origin[d] = std::floor(lo[d]) - Margin;
      const double corners = std::floor(hi[d]) + Margin - this->Origin[d] + 1;
      this->Blocks[d] = std::int64_t(corners + Block - 1) / Block;
      blocks *= double(this->Blocks[d]);
    }
    if (blocks <= double(MostBlocks))
      this->BlockOf.assign(std::size_t(blocks), -1);
    else
      this->Blocks[0] = this->Blocks[1] = this->Blocks[2] = 0; // no corner kept
  }

  /// The distance at the corner nearest p and how far that corner is; false when p is
  /// outside the box.
  bool nearest(const Vec3& p, double& value, double& offset)
  {
    std::int64_t q[3];
    double offset2 = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double x = p[d] - this->Origin[d];
      if (!(x >= 0 && x < double(this->Blocks[d] * Block - 1)))
        return false;
      q[d] = std::int64_t(std::nearbyint(x));
      offset2 += (double(q[d]) - x) * (double(q[d]) - x);
    }
    const std::size_t block = std::size_t(
      ((q[2] / Block) * this->Blocks[1] + q[1] / Block) * this->Blocks[0] + q[0] / Block);
    std::int32_t& number = this->BlockOf[block];
    if (number < 0)
    {
      number = std::int32_t(this->Values.size() / (Block * Block * Block));
      this->Values.resize(this->Values.size() + Block * Block * Block, Unknown);
    }
    float& v = this->Values[std::size_t(number) * Block * Block * Block +
      std::size_t(((q[2] % Block) * Block + q[1] % Block) * Block + q[0] % Block)];
    if (v == Unknown)
      v = float(this->Distance({ this->Origin[0] + double(q[0]),
        this->Origin[1] + double(q[1]),
        this->Origin[2] + double(q[2]) }));
    value = v;
    offset = std::sqrt(offset2);
    return true;
  }

  /// Starts fetching the value nearest() reads for p (the values of distant corners miss the
  /// cache); no effect where nearest() would find no value kept.
  void prefetchNearest(const Vec3& p) const
  {
    std::int64_t q[3];
    for (int d = 0; d < 3; ++d)
    {
      const double x = p[d] - this->Origin[d];
      if (!(x >= 0 && x < double(this->Blocks[d] * Block - 1)))
        return;
      q[d] = std::int64_t(std::nearbyint(x));
    }
    const std::size_t block = std::size_t(
      ((q[2] / Block) * this->Blocks[1] + q[1] / Block) * this->Blocks[0] + q[0] / Block);
    const std::int32_t number = this->BlockOf[block];
    if (number >= 0)
      prefetch(&this->Values[std::size_t(number) * Block * Block * Block +
        std::size_t(((q[2] % Block) * Block + q[1] % Block) * Block + q[0] % Block)]);
  }

  const SurfelDistance& exact() const { return this->Distance; }

private:
  static constexpr std::int64_t Block = 8;
  static constexpr double Margin = 3;
  static constexpr double MostBlocks = double(1 << 24); // a table of 64 MB
  static constexpr float Unknown = -1;

  const SurfelDistance& Distance;
  double Origin[3];
  std::int64_t Blocks[3];
  std::vector<std::int32_t> BlockOf; // per block: its number among those allocated, or -1
  std::vector<float> Values;
};

/// Whether every point of t is proven within `reach` of the surfels ((a) on top). `stack` is
/// the caller's workspace, kept between calls so that a call allocates nothing. A piece is
/// accepted when its centre's distance plus its radius is within reach, refused when its
/// centre is beyond reach or it is too small to halve, else halved. The lattice's bounds on
/// the centre's distance decide most pieces; the search runs only where they leave the
/// decision open, so the decisions are those of searching every centre (the bounds are kept
/// Slack away from the thresholds, far above the rounding of the floats kept and of the
/// distances), and so is the surface.
bool withinReach(const Corners& t,
  double reach,
  LatticeDistances& distances,
  std::vector<Corners>& stack)
{
  enum class Decision
  {
    Accept,
    Refuse,
    Halve,
    Open
  };
  // The piece's decision when its centre's distance lies in [lower, upper], the thresholds
  // moved `slack` towards the open side; with the distance itself and no slack it is never
  // open.
  const auto decide = [reach](double lower, double upper, double radius, double slack)
  {
    if (upper + radius <= reach - slack)
      return Decision::Accept;
    if (lower + radius <= reach + slack)
      return Decision::Open;
    if (radius < SmallestPiece || lower > reach + slack)
      return Decision::Refuse;
    return upper <= reach - slack ? Decision::Halve : Decision::Open;
  };
  constexpr double Slack = 1e-6;
  stack.assign(1, t);
  while (!stack.empty())
  {
    Piece piece{ stack.back() };
    stack.pop_back();
    const Vec3 c = piece.measureRadius();
    double value = 0, offset = 0;
    Decision decision = Decision::Open;
    if (distances.nearest(c, value, offset))
      decision = decide(value - offset, value + offset, piece.radius, Slack);
    if (decision == Decision::Open)
    {
      piece.centre = distances.exact()(c);
      decision = decide(piece.centre, piece.centre, piece.radius, 0.0);
    }
    if (decision == Decision::Refuse)
      return false;
    if (decision == Decision::Halve)
      for (const Corners& h : piece.halves())
        stack.push_back(h);
  }
  return true;
}

/// A face in a cell of the grid below, with its box when it was inserted, in floats rounded
/// outwards (it contains the box in doubles): the queries reject most entries by these boxes
/// without reading the face's own data, which is scattered in memory.
struct GridEntry
{
  FaceId face;
  std::array<float, 3> lo, hi;

  /// Whether the box [lo, hi] is apart from this entry's box (a box that touches is not).
  bool apart(const Vec3& l, const Vec3& h) const
  {
    for (int d = 0; d < 3; ++d)
      if (double(this->lo[d]) > h[d] || double(this->hi[d]) < l[d])
        return true;
    return false;
  }

  /// Squared distance from p to this entry's box (no point of the face's box is nearer).
  double squaredDistance(const Vec3& p) const
  {
    double d2 = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double l = this->lo[d], h = this->hi[d];
      const double e = p[d] < l ? l - p[d] : (p[d] > h ? p[d] - h : 0.0);
      d2 += e * e;
    }
    return d2;
  }
};

/// x in float, rounded down (up) when it is not exact.
float floatBelow(double x)
{
  const float f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float floatAbove(double x)
{
  const float f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

/// A uniform grid of triangle boxes: each face has one entry, with its current box, in every
/// cell that box meets (a face that moves or goes is erased from the cells of the box it was
/// inserted with). Entries left in place until a cell was cleaned had the intersection tests
/// read six times as many entries as faces they kept (the 128^3 ball: 118 entries against 23
/// faces per collapse), each with a look-up in the mesh to tell a removed face.
class FaceGrid
{
public:
  /// Cells of side `cellSize` over the box [lo, hi] (the surface's, so that a small object in
  /// a large grid costs little) with a margin; points outside fall in the border cells, which
  /// keeps the search exact, only slower there.
  void reset(const Vec3& lo, const Vec3& hi, double cellSize)
  {
    this->CellSize = cellSize;
    for (int d = 0; d < 3; ++d)
    {
      this->Origin[d] = std::floor(lo[d]) - 2;
      this->Cells[d] = std::int32_t(std::ceil((hi[d] - this->Origin[d] + 2) / this->CellSize)) + 1;
    }
    this->Faces.assign(std::size_t(this->Cells[0]) * this->Cells[1] * this->Cells[2], {});
  }

  /// Adds f to the cells its box meets.
  void insert(FaceId f, const Vec3& lo, const Vec3& hi)
  {
    GridEntry entry{ f, {}, {} };
    for (int d = 0; d < 3; ++d)
      entry.lo[d] = floatBelow(lo[d]), entry.hi[d] = floatAbove(hi[d]);
    this->forCells(lo, hi, [&entry](std::vector<GridEntry>& cell) { cell.push_back(entry); });
  }

  /// Takes f out of the cells of the box it was inserted with (the entries of a cell are not
  /// kept in order: a query's answer is a set).
  void erase(FaceId f, const Vec3& lo, const Vec3& hi)
  {
    this->forCells(lo,
      hi,
      [f](std::vector<GridEntry>& cell)
      {
        for (GridEntry& e : cell)
          if (e.face == f)
          {
            e = cell.back();
            cell.pop_back();
            return;
          }
      });
  }

  template<typename Visit>
  void forCells(const Vec3& lo, const Vec3& hi, Visit&& visit)
  {
    std::int32_t a[3], b[3];
    for (int d = 0; d < 3; ++d)
    {
      a[d] = this->cell(lo[d], d);
      b[d] = this->cell(hi[d], d);
    }
    for (std::int32_t k = a[2]; k <= b[2]; ++k)
      for (std::int32_t j = a[1]; j <= b[1]; ++j)
        for (std::int32_t i = a[0]; i <= b[0]; ++i)
          visit(this->Faces[(std::size_t(k) * this->Cells[1] + j) * this->Cells[0] + i]);
  }

  /// Visits the entries of the cells that the box [lo, hi] meets, cell by cell as forCells;
  /// the cells' entries are prefetched first (each cell's entries are a separate block of
  /// memory, which a scan cell by cell waited for one after the other).
  template<typename Visit>
  void forEntries(const Vec3& lo, const Vec3& hi, Visit&& visit)
  {
    this->Visited.clear();
    this->forCells(lo,
      hi,
      [this](std::vector<GridEntry>& cell)
      {
        if (cell.empty())
          return;
        const char* first = reinterpret_cast<const char*>(cell.data());
        const char* end = reinterpret_cast<const char*>(cell.data() + cell.size());
        for (const char* line = first; line < end && line < first + 512; line += 64)
          prefetch(line);
        this->Visited.push_back(&cell);
      });
    for (const std::vector<GridEntry>* cell : this->Visited)
      for (const GridEntry& e : *cell)
        visit(e);
  }

private:
  std::int32_t cell(double x, int d) const
  {
    const double at = std::floor((x - this->Origin[d]) / this->CellSize);
    return std::int32_t(std::clamp(at, 0.0, double(this->Cells[d] - 1)));
  }

  double CellSize = 4;
  double Origin[3] = { 0, 0, 0 };
  std::int32_t Cells[3] = { 1, 1, 1 };
  std::vector<std::vector<GridEntry>> Faces;
  std::vector<const std::vector<GridEntry>*> Visited; // forEntries's cells
};

/// A square piece of a surfel ((b) on top): its centre, side and normal axis, and how far
/// its centre may be from its triangle (d minus the half diagonal, or more where the input
/// itself is farther).
struct SurfelPiece
{
  Vec3 centre;
  double side;
  int axis;
  double limit;

  double halfDiagonal() const { return this->side * std::sqrt(0.5); }

  std::array<SurfelPiece, 4> quarters() const
  {
    std::array<SurfelPiece, 4> q;
    for (int c = 0; c < 4; ++c)
    {
      q[c] = *this;
      q[c].side = 0.5 * this->side;
      q[c].centre[(this->axis + 1) % 3] += (c & 1 ? 0.25 : -0.25) * this->side;
      q[c].centre[(this->axis + 2) % 3] += (c & 2 ? 0.25 : -0.25) * this->side;
    }
    return q;
  }
};

/// Pieces are not quartered below this side: the sampling of the surfels is then finer than
/// the 5 x 5 lattice of the tests and the benchmark.
constexpr double SmallestSide = 0.125;

/// Row (j, k) of the object as words, bits past the grid's end cleared, with one more word of
/// zeros; all zeros outside the grid (the background around it).
void readRow(const BitVolume& object, std::int32_t j, std::int32_t k, std::vector<Word>& out)
{
  const std::size_t words = object.wordsPerRow();
  out.assign(words + 1, 0);
  const auto& n = object.dims();
  if (j < 0 || k < 0 || j >= n[1] || k >= n[2])
    return;
  const Word* row = object.row(j, k);
  std::copy(row, row + words, out.begin());
  if (n[0] % 64 != 0)
    out[words - 1] &= (Word(1) << (n[0] % 64)) - 1;
}

/// The surfels of unpruned voxels (pruned: no interior corner), whole (side 1), in the order
/// of the voxels (k, j, i, then the axis). Each row of voxels is compared with the next voxel
/// along x, the next row along y and along z a word (64 voxels) at a time, and only the faces
/// so found are read one by one: reading both voxels of every face of the grid took most of
/// the set-up (0.27 s of the 256^3 ball's 0.66 s).
std::vector<SurfelPiece> unprunedSurfels(const BitVolume& object, const SurfelDistance& surfels)
{
  const auto& n = object.dims();
  auto interior = [&](std::int32_t i, std::int32_t j, std::int32_t k)
  {
    for (int c = 0; c < 8; ++c)
      if (!surfels.at(i - 1 + (c & 1), j - 1 + ((c >> 1) & 1), k - 1 + (c >> 2)))
        return false;
    return true;
  };
  auto pruned = [&](std::int32_t i, std::int32_t j, std::int32_t k)
  {
    for (int c = 0; c < 8; ++c)
      if (interior(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)))
        return false;
    return true;
  };
  std::vector<SurfelPiece> out;
  const auto add = [&](std::int32_t i, std::int32_t j, std::int32_t k, int a)
  {
    const std::int32_t i1 = i + (a == 0), j1 = j + (a == 1), k1 = k + (a == 2);
    if (surfels.at(i, j, k) ? pruned(i, j, k) : pruned(i1, j1, k1))
      return;
    Vec3 c{ i + 0.5, j + 0.5, k + 0.5 };
    c[a] += 0.5;
    out.push_back({ c, 1.0, a, 0.0 });
  };
  const std::size_t words = object.wordsPerRow();
  std::vector<Word> here, nextY, nextZ, alongX(words + 1), acrossY(words + 1), acrossZ(words + 1);
  for (std::int32_t k = -1; k < n[2]; ++k)
    for (std::int32_t j = -1; j < n[1]; ++j)
    {
      readRow(object, j, k, here);
      readRow(object, j + 1, k, nextY);
      readRow(object, j, k + 1, nextZ);
      // bit i: voxel i differs from voxel i + 1 (alongX), from its neighbour in the next row
      // along y (acrossY) or z (acrossZ)
      for (std::size_t w = 0; w <= words; ++w)
      {
        const Word next = (here[w] >> 1) | (w < words ? here[w + 1] << 63 : 0);
        alongX[w] = here[w] ^ next;
        acrossY[w] = here[w] ^ nextY[w];
        acrossZ[w] = here[w] ^ nextZ[w];
      }
      if (here[0] & 1) // the face between voxel 0 and the background before it
        add(-1, j, k, 0);
      for (std::size_t w = 0; w < words; ++w)
        for (Word m = alongX[w] | acrossY[w] | acrossZ[w]; m != 0; m &= m - 1)
        {
          const int b = __builtin_ctzll(m);
          const std::int32_t i = std::int32_t(64 * w) + b;
          const Word bit = Word(1) << b;
          for (int a = 0; a < 3; ++a)
            if ((a == 0 ? alongX : (a == 1 ? acrossY : acrossZ))[w] & bit)
              add(i, j, k, a);
        }
    }
  return out;
}

using Box = std::array<Vec3, 2>; ///< lower and upper corner

/// The box of a triangle.
Box boxOf(const Corners& t)
{
  Box b;
  for (int d = 0; d < 3; ++d)
  {
    b[0][d] = std::min({ t[0][d], t[1][d], t[2][d] });
    b[1][d] = std::max({ t[0][d], t[1][d], t[2][d] });
  }
  return b;
}

/// One collapse's new star: each kept face with its new corners and their vertices (a null
/// VertexId for the collapsed vertex).
struct StarFace
{
  FaceId face;
  std::array<VertexId, 3> ids;
  Corners t;
  Box box;                    ///< of t
  Vec3 normal;                ///< of t, not unit
  double normal2 = 0;         ///< its squared length
  std::array<Vec3, 3> inward; ///< per edge t[i] t[i + 1]: in t's plane, towards t

  /// The box, normal and inward edge normals of t.
  void measure()
  {
    this->box = boxOf(this->t);
    this->normal = cross(sub(this->t[1], this->t[0]), sub(this->t[2], this->t[0]));
    this->normal2 = dot(this->normal, this->normal);
    for (int i = 0; i < 3; ++i)
      this->inward[i] = cross(this->normal, sub(this->t[(i + 1) % 3], this->t[i]));
  }

  /// Whether the piece's centre is within its limit of this triangle. Most centres lie over
  /// the triangle, where the distance is the plane's: that is decided from the normals,
  /// unless it is within a rounding margin of the limit; the others, and those, are measured
  /// as nearestOf measures them, so the answer is the same.
  bool keeps(const SurfelPiece& piece) const
  {
    const double limit2 = piece.limit * piece.limit;
    const double margin = 1e-9 * limit2 + 1e-12;
    const Vec3 w = sub(piece.centre, this->t[0]);
    const double height = dot(this->normal, w);
    const double plane2 = height * height / this->normal2;
    if (plane2 > limit2 + margin)
      return false; // no point of the plane is within the limit
    const bool over = dot(this->inward[0], w) >= 0 &&
      dot(this->inward[1], sub(piece.centre, this->t[1])) >= 0 &&
      dot(this->inward[2], sub(piece.centre, this->t[2])) >= 0;
    if (over && plane2 < limit2 - margin)
      return true;
    return squaredDistanceToTriangle(piece.centre, this->t[0], this->t[1], this->t[2]) <= limit2;
  }
};

/// Whether two boxes are apart (boxes that touch are not).
bool apart(const Box& a, const Box& b)
{
  for (int d = 0; d < 3; ++d)
    if (a[0][d] > b[1][d] || a[1][d] < b[0][d])
      return true;
  return false;
}

/// Squared distance from p to box b: no point of the box is nearer.
double squaredDistanceToBox(const Vec3& p, const Box& b)
{
  double d2 = 0;
  for (int d = 0; d < 3; ++d)
  {
    const double e = p[d] < b[0][d] ? b[0][d] - p[d] : (p[d] > b[1][d] ? p[d] - b[1][d] : 0.0);
    d2 += e * e;
  }
  return d2;
}

/// Whether the corners of t not in `skip` (a bit per corner) lie strictly on one side of the
/// plane of s, decided in floating point where the sign is certain: the orientation
/// determinant beyond an error bound 20 times that of CGAL's static filter for orientation
/// (5.1e-15 times the largest coordinate differences); false where it is not certain. Such a t
/// does not meet s but at the skipped corners, which spares most exact tests.
bool strictlyOneSide(const Corners& s, const Corners& t, int skip)
{
  const Vec3 u = sub(s[1], s[0]), v = sub(s[2], s[0]), n = cross(u, v);
  int side = 0;
  for (int c = 0; c < 3; ++c)
  {
    if (skip & (1 << c))
      continue;
    const Vec3 w = sub(t[c], s[0]);
    double bound = 1e-13;
    for (int d = 0; d < 3; ++d)
      bound *= std::max({ std::abs(u[d]), std::abs(v[d]), std::abs(w[d]) });
    const double o = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
    const int here = o > bound ? 1 : (o < -bound ? -1 : 0);
    if (here == 0 || (side != 0 && here != side))
      return false;
    side = here;
  }
  return side != 0;
}

/// The lower (or upper) corner of the box of a mesh's points.
Vec3 corner(const Mesh& mesh, bool upper)
{
  Vec3 c{ 0, 0, 0 };
  bool first = true;
  for (VertexId v : mesh.vertices())
  {
    const Vec3 p = vec(mesh.point(v));
    for (int d = 0; d < 3; ++d)
      c[d] = first ? p[d] : (upper ? std::max(c[d], p[d]) : std::min(c[d], p[d]));
    first = false;
  }
  return c;
}

/// Whole voxels proven within reach of the surfels, for (a): a triangle all of whose voxels
/// (those it meets) are proven is within reach, with no branch and bound. The distance to one
/// surfel (a square, convex) is convex, so over a voxel (a cube) its largest value is at one
/// of the cube's 8 corners; and since the corners are the product of the two ends per axis,
/// that largest value squared is the sum of each axis's largest term: for a surfel in the
/// plane x = s and the voxel [i, i + 1] x [j, j + 1] x [k, k + 1], it is
/// max(|i - s|, |i + 1 - s|)^2 + (j' - j)^2 + (k' - k)^2, (j', k') the surfel's place in the
/// plane, an integer. Below two voxels (d <= 1.99) only the surfels in the planes of the
/// voxel's own faces, at most one voxel from the face along the plane, give less than 4:
/// 1 for the face itself, 2 and 3 for its side and corner neighbours. A voxel is proven when
/// one of these values is within reach squared (a relative 1e-12 allowed for the rounding of
/// reach: at d = sqrt(3), the default, 3 is reach squared itself). The proven voxels of the
/// surface's box are marked once, a bit each, a row of voxels along x a few words at a time
/// (the surfels of a row of planes are the exclusive or of two rows of voxels); not for a
/// box large for its surface (as SurfelDistance's marks), which is then left to the branch
/// and bound.
class VoxelCover
{
public:
  VoxelCover(const BitVolume& object,
    const Vec3& lo,
    const Vec3& hi,
    std::size_t faces,
    double reach)
  {
    const double limit = reach * reach * (1 + 1e-12);
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        if (1 + a * a + b * b <= limit)
          this->Offsets.push_back({ a, b });
    this->Words = object.wordsPerRow() + 2; // a word of background on either side
    this->First[0] = std::int32_t(std::floor(lo[1])) - Margin;
    this->First[1] = std::int32_t(std::floor(lo[2])) - Margin;
    this->Rows[0] = std::int32_t(std::floor(hi[1])) + Margin + 1 - this->First[0];
    this->Rows[1] = std::int32_t(std::floor(hi[2])) + Margin + 1 - this->First[1];
    const double bits = 64.0 * double(this->Words) * this->Rows[0] * this->Rows[1];
    if (this->Offsets.empty() || bits > 64.0 * double(faces) + double(std::int64_t(1) << 24))
      return;
    this->readVoxels(object);
    this->Proven.assign(this->Words * std::size_t(this->Rows[0]) * std::size_t(this->Rows[1]), 0);
    for (std::int32_t k = 0; k < this->Rows[1]; ++k)
      for (std::int32_t j = 0; j < this->Rows[0]; ++j)
        this->markRow(j, k);
    std::vector<Word>().swap(this->Voxels);
    this->Scratch = RowScratch();
  }

  /// Whether every voxel that triangle t may meet is proven; false when one is not (or lies
  /// outside the box). The voxels are those of the columns along the axis nearest t's normal
  /// whose squares meet t's shadow, between the heights of t's plane over the square: a
  /// superset of the voxels t meets (each bound widened by Widen, far above the rounding).
  bool proves(const Corners& t) const
  {
    if (this->Proven.empty())
      return false;
    const Vec3 n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    const int c = std::abs(n[0]) > std::abs(n[1]) ? (std::abs(n[0]) > std::abs(n[2]) ? 0 : 2)
                                                  : (std::abs(n[1]) > std::abs(n[2]) ? 1 : 2);
    const int a = (c + 1) % 3, b = (c + 2) % 3;
    std::int32_t lo[3], hi[3];
    double low[3], high[3];
    for (int d = 0; d < 3; ++d)
    {
      low[d] = std::min({ t[0][d], t[1][d], t[2][d] }) - Widen;
      high[d] = std::max({ t[0][d], t[1][d], t[2][d] }) + Widen;
      if (!(low[d] > -1e9 && high[d] < 1e9))
        return false;
      lo[d] = std::int32_t(std::floor(low[d]));
      hi[d] = std::int32_t(std::floor(high[d]));
    }
    if (n[c] == 0)
      return this->provesBox(lo, hi); // no plane to follow (a degenerate t): its whole box
    const double slack = heightSlack(t, n[c]);
    if (!(slack < high[c] - low[c] + 1))
      return this->provesBox(lo, hi); // the heights say no more than the box (or not finite)
    const double offset = dot(n, t[0]);
    // the height along c of t's plane at (x, y) along (a, b)
    const auto height = [&](double x, double y) { return (offset - n[a] * x - n[b] * y) / n[c]; };
    for (std::int32_t u = lo[a]; u <= hi[a]; ++u)
      for (std::int32_t v = lo[b]; v <= hi[b]; ++v)
      {
        const double x0 = double(u) - Widen, x1 = double(u + 1) + Widen;
        const double y0 = double(v) - Widen, y1 = double(v + 1) + Widen;
        if (!shadowMeets(t, a, b, x0, x1, y0, y1))
          continue;
        const double h[4] = { height(x0, y0), height(x1, y0), height(x0, y1), height(x1, y1) };
        const double top = std::min(high[c], std::max({ h[0], h[1], h[2], h[3] }) + slack);
        const double bottom = std::max(low[c], std::min({ h[0], h[1], h[2], h[3] }) - slack);
        for (std::int32_t w = std::int32_t(std::floor(bottom)); w <= std::int32_t(std::floor(top));
             ++w)
        {
          std::int32_t q[3];
          q[a] = u, q[b] = v, q[c] = w;
          if (!this->proven(q[0], q[1], q[2]))
            return false;
        }
      }
    return true;
  }

private:
  static constexpr std::int32_t Margin = 3;
  static constexpr double Widen = 1e-7;

  /// The rows of bits markRow works on, a word per 64 voxels of a row.
  struct RowScratch
  {
    std::vector<Word> proven;  ///< the row's voxels proven so far
    std::vector<Word> across;  ///< the faces normal to x within reach, a bit per plane x = i
    std::vector<Word> faces;   ///< the faces normal to y or z of one plane
    std::vector<Word> shifted; ///< a row shifted by a voxel
  };

  /// How far the heights of t's plane computed from the rounded normal n (n[c] its largest
  /// component, not 0) may be from those of t's points: a point p of t is within the slack of
  /// the height computed at p's place. Why: with u = 2^-53, the sides t[1] - t[0], t[2] - t[0]
  /// are rounded with a relative error u per coordinate, and the cross product of the rounded
  /// sides with a few more, so n = N + e with N normal to the exact t and each |e[k]| <= 8 u L^2
  /// (L the longest side). The computed plane through t[0] is at height H(p) = p[c] -
  /// n.(p - t[0]) / n[c] over p's place, and n.(p - t[0]) = e.(p - t[0]) as N.(p - t[0]) = 0, so
  /// |H(p) - p[c]| <= 8 sqrt(3) u L^3 / |n[c]|: tiny for a fair triangle, but for a sliver
  /// (corners off a line by 1e-14) n is rounding noise, |n[c]| as small as e, and the heights land
  /// anywhere. The evaluation of H (the offset, a dot product of three terms, two more
  /// products and a division; each |n[k]| <= |n[c]|) adds at most about 25 u times the largest
  /// coordinate M + 1 (the places are within a voxel of t's box). 1e-14 (90 u) times
  /// L^3 / |n[c]| + M + 1 is over three times both, and Widen covers points on voxel faces. H is
  /// linear, so over a column's square its values lie between those at the square's corners.
  /// The columns themselves need no such bound: where the sign of a side's test in shadowMeets
  /// is rounded the wrong way, all of t lies within about u L of that side, far inside the
  /// squares' widening by Widen.
  static double heightSlack(const Corners& t, double nc)
  {
    double longest = 0, largest = 0;
    for (int e = 0; e < 3; ++e)
    {
      const Vec3 side = sub(t[(e + 1) % 3], t[e]);
      longest = std::max(longest, std::sqrt(dot(side, side)));
      for (int k = 0; k < 3; ++k)
        largest = std::max(largest, std::abs(t[e][k]));
    }
    return Widen + 1e-14 * (longest * longest * longest / std::abs(nc) + largest + 1);
  }

  /// Whether every voxel of the box lo .. hi is proven.
  bool provesBox(const std::int32_t lo[3], const std::int32_t hi[3]) const
  {
    for (std::int32_t k = lo[2]; k <= hi[2]; ++k)
      for (std::int32_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int32_t i = lo[0]; i <= hi[0]; ++i)
          if (!this->proven(i, j, k))
            return false;
    return true;
  }

  /// Whether the shadow of t along the third axis (on axes a, b) meets the rectangle
  /// [x0, x1] x [y0, y1]: no side of the shadow separates them (the rectangle's own sides
  /// are t's box, which the caller keeps to). Either winding.
  static bool
  shadowMeets(const Corners& t, int a, int b, double x0, double x1, double y0, double y1)
  {
    for (int e = 0; e < 3; ++e)
    {
      const Vec3 &p = t[e], &q = t[(e + 1) % 3], &r = t[(e + 2) % 3];
      const double nx = q[b] - p[b], ny = p[a] - q[a]; // normal of pq in the shadow
      const double side = nx * (r[a] - p[a]) + ny * (r[b] - p[b]);
      if (side == 0)
        continue; // a degenerate shadow: the box alone decides
      // the rectangle's corner farthest towards r's side of pq
      const double cx = (nx > 0) == (side > 0) ? x1 : x0;
      const double cy = (ny > 0) == (side > 0) ? y1 : y0;
      const double corner = nx * (cx - p[a]) + ny * (cy - p[b]);
      if (side > 0 ? corner < 0 : corner > 0)
        return false; // the whole rectangle beyond pq
    }
    return true;
  }

  bool proven(std::int32_t i, std::int32_t j, std::int32_t k) const
  {
    const std::int64_t x = std::int64_t(i) + 64, y = j - this->First[0], z = k - this->First[1];
    if (x < 0 || x >= std::int64_t(64 * this->Words) || y < 0 || y >= this->Rows[0] || z < 0 ||
      z >= this->Rows[1])
      return false;
    const Word w = this->Proven[(std::size_t(z) * this->Rows[0] + std::size_t(y)) * this->Words +
      std::size_t(x >> 6)];
    return (w >> (x & 63)) & 1;
  }

  /// The voxels of rows First - 1 .. First + Rows along y and z, bit x + 64 of a row for
  /// voxel x (all background outside the grid).
  void readVoxels(const BitVolume& object)
  {
    const std::size_t ny = std::size_t(this->Rows[0]) + 2, nz = std::size_t(this->Rows[1]) + 2;
    this->Voxels.assign(ny * nz * this->Words, 0);
    std::vector<Word> row;
    for (std::size_t z = 0; z < nz; ++z)
      for (std::size_t y = 0; y < ny; ++y)
      {
        readRow(
          object, this->First[0] - 1 + std::int32_t(y), this->First[1] - 1 + std::int32_t(z), row);
        std::copy(row.begin(),
          row.end() - 1,
          this->Voxels.begin() + std::ptrdiff_t((z * ny + y) * this->Words + 1));
      }
  }

  /// Row (y, z) of the voxels (y, z relative to First, from -1 to Rows).
  const Word* voxels(std::int32_t y, std::int32_t z) const
  {
    return this->Voxels.data() +
      (std::size_t(z + 1) * std::size_t(this->Rows[0] + 2) + std::size_t(y + 1)) * this->Words;
  }

  /// out |= row shifted so that bit i of out reads bit i + by of row (by in -1, 0, 1).
  void orShifted(std::vector<Word>& out, const Word* row, int by) const
  {
    const std::size_t n = this->Words;
    for (std::size_t w = 0; w < n; ++w)
      out[w] |= by == 0 ? row[w]
                        : (by > 0 ? (row[w] >> 1) | (w + 1 < n ? row[w + 1] << 63 : 0)
                                  : (row[w] << 1) | (w > 0 ? row[w - 1] >> 63 : 0));
  }

  /// out = the surfels of the planes between rows p and q of voxels (their exclusive or).
  void planes(std::vector<Word>& out, const Word* p, const Word* q) const
  {
    for (std::size_t w = 0; w < this->Words; ++w)
      out[w] = p[w] ^ q[w];
  }

  /// The proven voxels of row (y, z) (relative to First).
  void markRow(std::int32_t y, std::int32_t z)
  {
    const std::size_t n = this->Words;
    RowScratch& row = this->Scratch; // kept across rows: no allocation a row
    std::vector<Word>& proven = row.proven;
    std::vector<Word>& across = row.across;
    std::vector<Word>& faces = row.faces;
    std::vector<Word>& shifted = row.shifted;
    proven.assign(n, 0);
    across.assign(n, 0);
    faces.resize(n);
    shifted.resize(n);
    // faces normal to x: the planes x = i (bit i: voxel i - 1 against voxel i); voxel i has
    // the planes i and i + 1
    for (const auto& [a, b] : this->Offsets)
    {
      const Word* r = this->voxels(y + a, z + b);
      std::fill(shifted.begin(), shifted.end(), 0);
      this->orShifted(shifted, r, -1);
      for (std::size_t w = 0; w < n; ++w)
        across[w] |= r[w] ^ shifted[w];
    }
    this->orShifted(proven, across.data(), 0);
    this->orShifted(proven, across.data(), 1);
    // faces normal to y (planes y and y + 1, offsets along x and z) and to z (planes z and
    // z + 1, offsets along x and y)
    for (int plane = 0; plane < 2; ++plane)
      for (const auto& [a, b] : this->Offsets)
      {
        this->planes(faces, this->voxels(y + plane - 1, z + b), this->voxels(y + plane, z + b));
        this->orShifted(proven, faces.data(), a);
        this->planes(faces, this->voxels(y + b, z + plane - 1), this->voxels(y + b, z + plane));
        this->orShifted(proven, faces.data(), a);
      }
    std::copy(proven.begin(),
      proven.end(),
      this->Proven.begin() + std::ptrdiff_t((std::size_t(z) * this->Rows[0] + std::size_t(y)) * n));
  }

  std::vector<std::pair<int, int>> Offsets; // in-plane offsets of the surfels within reach
  std::size_t Words = 0;                    // per row, bit x + 64 for voxel x
  std::int32_t First[2] = { 0, 0 }, Rows[2] = { 0, 0 }; // along y and z
  std::vector<Word> Voxels;                             // while marking
  RowScratch Scratch;                                   // while marking
  std::vector<Word> Proven;                             // a bit per voxel of the box
};

/// What the checks read of the object and nobody changes once made: the marked surfels of
/// (a)'s and (b)'s distances and (a)'s proven voxels, over the input surface's box. The
/// regions' collapse loops share it (only const reads), each with its own lattice.
struct SurfelField
{
  SurfelField(const BitVolume& object, const Mesh& mesh, double distance, const Execution& exec)
    : Lo(corner(mesh, false))
    , Hi(corner(mesh, true))
    , Surfels(object, this->Lo, this->Hi, mesh.number_of_faces(), exec)
    , Cover(object, this->Lo, this->Hi, mesh.number_of_faces(), std::min(distance, 1.99))
    , Reach(std::min(distance, 1.99))
  {
  }

  Vec3 Lo, Hi; // the input surface's box
  SurfelDistance Surfels;
  VoxelCover Cover;
  double Reach;
};

/// Where a collapse may be: every corner of its old star and its placement strictly between
/// lo and hi along the axis (a region of simplifyBoundary's first phase), or anywhere.
struct Slab
{
  int axis = 0;
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();

  bool inside(const Vec3& p) const { return p[this->axis] > this->lo && p[this->axis] < this->hi; }
};

/// The pieces of the surfels per face ((b) on top), by face number.
using SamplesByFace = std::vector<std::vector<SurfelPiece>>;

/// The simplification's state: accept checks a collapse and records the reassignment of the
/// samples, collapsed applies it once the collapse loop has collapsed the edge. Every member
/// but the field is its own: simplifiers of separate meshes may run on separate threads.
class Simplifier
{
public:
  /// The state of `mesh` without samples (assignSamples or setSamples gives them); its
  /// progress reported from `from` to `to` of `exec`'s as its faces go.
  Simplifier(const SurfelField& field,
    Mesh& mesh,
    const Execution& exec,
    double from = 0.1,
    double to = 0.95,
    const Slab& slab = Slab())
    : Lo(corner(mesh, false))
    , Hi(corner(mesh, true))
    , Field(field)
    , Lattice(field.Surfels, field.Lo, field.Hi)
    , M(mesh)
    , Reach(field.Reach)
    , Poll(exec, from, to)
    , Bounds(slab)
  {
    this->Stamp.assign(mesh.number_of_faces(), 0);
    this->Faces.resize(mesh.number_of_faces());
    this->SamplesOf.assign(mesh.number_of_faces(), {});
    for (FaceId f : mesh.faces())
      this->keepCorners(f);
    this->rebuildGrid();
  }

  void assignSamples(const BitVolume& object, const Execution& exec);
  /// The pieces of each face (by face number, as the mesh's), given.
  void setSamples(SamplesByFace samples) { this->SamplesOf = std::move(samples); }
  /// The pieces of each face, taken out of the state.
  SamplesByFace takeSamples() { return std::move(this->SamplesOf); }
  bool accept(VertexId v0, VertexId v1, const Point3& placed);
  /// Applies the accepted collapse of (v0, v1), moving the vertex the collapse kept to the accepted
  /// point; false (nothing applied) when the last accepted collapse was another edge's.
  bool collapsed(VertexId v0, VertexId v1, VertexId kept);
  /// Whether v lies where collapses may be (a region's slab, strictly inside): a cheap
  /// first test, accept makes the whole one.
  bool inside(VertexId v) const { return this->Bounds.inside(vec(this->M.point(v))); }
  bool stopped() { return !this->Poll.tick(); }
  bool aborted() const { return this->Poll.stopped(); }
  void at(double fraction) { this->Poll.at(fraction); }
  double surfelDistance() const;

private:
  /// Copies face f's vertices and corners from the mesh, in the mesh's order around it (the
  /// order of the tests' arithmetic, so the copies give the same results as the mesh).
  void keepCorners(FaceId f)
  {
    FaceCorners& kept = this->Faces[std::size_t(f)];
    int i = 0;
    for (VertexId v : CGAL::vertices_around_face(this->M.halfedge(f), this->M))
      kept.ids[i] = v, kept.t[i++] = vec(this->M.point(v));
  }
  const Corners& triangleOf(FaceId f) const { return this->Faces[std::size_t(f)].t; }
  /// Face f as a StarFace (its ids, corners and box).
  StarFace faceOf(FaceId f) const
  {
    const FaceCorners& kept = this->Faces[std::size_t(f)];
    StarFace s;
    s.face = f;
    s.ids = kept.ids;
    s.t = kept.t;
    s.box = boxOf(s.t);
    return s;
  }
  void rebuildGrid();
  FaceId nearestFace(const Vec3& p, double halfWidth, double& best2);
  FaceId nearestFaceAnywhere(const Vec3& p) const;
  bool newStar(VertexId v0, VertexId v1, const Point3& placed);
  /// The index of face f in Star (its new triangle), or Star.size() if the collapse removes f.
  std::size_t starIndexOf(FaceId f) const
  {
    std::size_t i = 0;
    while (i < this->Star.size() && this->Star[i].face != f)
      ++i;
    return i;
  }
  bool reassignSamples();
  bool placePiece(const SurfelPiece& piece);

  bool freeOfIntersections();
  bool intersects(const StarFace& s, const Corners& t, const std::array<VertexId, 3>& ids) const;

  Vec3 Lo, Hi; // the mesh's box
  const SurfelField& Field;
  LatticeDistances Lattice;
  Mesh& M;
  double Reach;
  ProgressPoll Poll;
  Slab Bounds;
  FaceGrid Grid;
  std::size_t FacesInGrid = 0; // when the grid was built
  /// Per face: its vertices and corners, copied from the mesh (kept up to date by collapsed):
  /// the tests read them for the faces near each star, scattered over the mesh, where walking
  /// the mesh's halfedges to the points missed the cache several times per face. The box a
  /// face has in the grid is that of its corners here (a separate array of boxes missed the
  /// cache again when the star's faces left the grid).
  struct FaceCorners
  {
    std::array<VertexId, 3> ids;
    Corners t;
  };
  std::vector<FaceCorners> Faces;
  std::vector<std::uint32_t> Stamp;
  std::uint32_t Round = 0;
  std::vector<std::vector<SurfelPiece>> SamplesOf; // per face: its pieces, kept in place
                                                   // (an index into one array of pieces
                                                   // cost a cache miss per piece)
  // the collapse being checked
  std::vector<FaceId> OldStar;
  std::vector<StarFace> Star;
  std::vector<std::pair<SurfelPiece, std::size_t>> Moves; // the pieces that move (or their
                                                          // quarters), index in Star
  std::vector<char> Stays; // per piece of the old star, in order: whether it stays with its face
  std::size_t Guess = 0;   // the last piece's triangle
  struct NearFace          // a face near the star: its vertices, corners and their box
  {
    std::array<VertexId, 3> ids;
    Corners t;
    Box box;
  };
  std::vector<FaceId> NearIds;      // faces near the star, found in the grid
  std::vector<NearFace> Near;       // and their corners
  std::vector<Corners> Pieces;      // withinReach's workspace
  std::array<VertexId, 2> Accepted; // the edge they are for
  Point3 AcceptedPoint;             // and where its vertex goes
};

/// The grid of the faces' boxes, its cells twice the mean box side (at least 2 voxels): the
/// cells stay about as fine as the faces, which grow as they collapse (a fixed side of 4 had
/// the intersection tests scan dozens of tiny faces per cell at the start). The cells are no
/// more than twice the faces, so that a large sparse surface does not get a dense grid.
void Simplifier::rebuildGrid()
{
  double sides = 0;
  for (FaceId f : this->M.faces())
  {
    const Box b = boxOf(this->triangleOf(f));
    sides += std::max({ b[1][0] - b[0][0], b[1][1] - b[0][1], b[1][2] - b[0][2] });
  }
  this->FacesInGrid = this->M.number_of_faces();
  const double mean = sides / double(std::max<std::size_t>(1, this->FacesInGrid));
  double volume = 1;
  for (int d = 0; d < 3; ++d)
    volume *= this->Hi[d] - this->Lo[d] + 4;
  const double sparse =
    std::cbrt(volume / (2.0 * double(std::max<std::size_t>(1, this->FacesInGrid))));
  this->Grid.reset(this->Lo, this->Hi, std::max({ 2.0, 2 * mean, sparse }));
  for (FaceId f : this->M.faces())
  {
    const Box b = boxOf(this->triangleOf(f));
    this->Grid.insert(f, b[0], b[1]);
  }
}

FaceId Simplifier::nearestFace(const Vec3& p, double halfWidth, double& best2)
{
  FaceId nearest;
  const Vec3 lo{ p[0] - halfWidth, p[1] - halfWidth, p[2] - halfWidth };
  const Vec3 hi{ p[0] + halfWidth, p[1] + halfWidth, p[2] + halfWidth };
  best2 = halfWidth * halfWidth;
  this->Grid.forCells(lo,
    hi,
    [&](const std::vector<GridEntry>& cell)
    {
      for (const GridEntry& e : cell)
      {
        // a face whose box is farther than the nearest so far would not be taken
        if (e.squaredDistance(p) > best2 + NearestSlack)
          continue;
        const Corners& t = this->triangleOf(e.face);
        const double d2 = squaredDistanceToTriangle(p, t[0], t[1], t[2]);
        if (d2 <= best2)
          best2 = d2, nearest = e.face;
      }
    });
  return nearest;
}

/// The nearest face of all (for the rare point no face is near).
FaceId Simplifier::nearestFaceAnywhere(const Vec3& p) const
{
  FaceId nearest;
  double best2 = std::numeric_limits<double>::infinity();
  for (FaceId f : this->M.faces())
  {
    const Corners& t = this->triangleOf(f);
    const double d2 = squaredDistanceToTriangle(p, t[0], t[1], t[2]);
    if (d2 <= best2)
      best2 = d2, nearest = f;
  }
  return nearest;
}

/// Each surfel of an unpruned voxel, quartered until each piece's centre is within d minus
/// its half diagonal of its nearest triangle; a piece of the smallest side still farther, or
/// whose smallest pieces would all be, keeps its input distance as its limit; one with no
/// triangle within 2.5 has no limit. Stops early when the caller asks (the state is then
/// dropped).
void Simplifier::assignSamples(const BitVolume& object, const Execution& exec)
{
  const std::vector<SurfelPiece> surfels = unprunedSurfels(object, this->Field.Surfels);
  std::mutex guard;
  exec.forWork(std::int64_t(surfels.size()))
    .forRange(std::int64_t(surfels.size()),
      [&](std::int64_t begin, std::int64_t end)
      {
        std::vector<std::pair<SurfelPiece, FaceId>> local;
        std::vector<SurfelPiece> stack;
        for (std::int64_t i = begin; i < end; ++i)
        {
          for (stack.assign(1, surfels[std::size_t(i)]); !stack.empty();)
          {
            SurfelPiece piece = stack.back();
            stack.pop_back();
            double d2 = 0;
            // the input runs within about a voxel of the surfels: a search of 1 first reads
            // fewer cells (0.18 -> 0.15 s on the 128^3 ball) and finds the same face (the
            // nearest, the same of those equally near: the wider one visits their cells in
            // the same order)
            FaceId f = this->nearestFace(piece.centre, 1.0, d2);
            if (f == FaceId())
              f = this->nearestFace(piece.centre, 2.5, d2);
            if (f == FaceId())
            {
              // an input farther than allowed: kept on its nearest triangle, any triangle
              // will do, and its distance (beyond 2.5) is reported
              f = this->nearestFaceAnywhere(piece.centre);
              piece.limit = std::numeric_limits<double>::infinity();
              local.emplace_back(piece, f);
              continue;
            }
            const double d = std::sqrt(d2);
            // the smallest pieces inside this one have centres within its half diagonal
            // less theirs: none passes when even the nearest would be too far
            const double smallest = SmallestSide * std::sqrt(0.5);
            const bool somePasses = d - piece.halfDiagonal() + 2 * smallest <= this->Reach;
            if (d + piece.halfDiagonal() > this->Reach && piece.side > SmallestSide && somePasses)
            {
              for (const SurfelPiece& q : piece.quarters())
                stack.push_back(q);
              continue;
            }
            piece.limit = std::max(this->Reach - piece.halfDiagonal(), d);
            local.emplace_back(piece, f);
          }
          if (i % 64 == 0 && exec.stopRequested())
            break;
        }
        const std::lock_guard<std::mutex> lock(guard);
        for (const auto& [piece, f] : local)
          this->SamplesOf[std::size_t(f)].push_back(piece);
      });
}

/// The kept faces around the collapsed edge with their new corners; false when one would be
/// degenerate or turned over.
bool Simplifier::newStar(VertexId v0, VertexId v1, const Point3& placed)
{
  this->OldStar.clear();
  this->Star.clear();
  for (VertexId v : { v0, v1 })
    for (FaceId f : CGAL::faces_around_target(this->M.halfedge(v), this->M))
      if (f != FaceId() &&
        std::find(this->OldStar.begin(), this->OldStar.end(), f) == this->OldStar.end())
        this->OldStar.push_back(f);
  // their corners and pieces lie far apart in memory: fetched together, not one by one
  for (FaceId f : this->OldStar)
  {
    prefetch(&this->Faces[std::size_t(f)]);
    prefetch(&this->SamplesOf[std::size_t(f)]);
  }
  const Vec3 p = vec(placed);
  if (!this->Bounds.inside(p))
    return false;
  for (FaceId f : this->OldStar)
    for (const Vec3& c : this->triangleOf(f))
      if (!this->Bounds.inside(c))
        return false;
  for (FaceId f : this->OldStar)
  {
    StarFace s = this->faceOf(f);
    const bool has0 = std::find(s.ids.begin(), s.ids.end(), v0) != s.ids.end();
    const bool has1 = std::find(s.ids.begin(), s.ids.end(), v1) != s.ids.end();
    if (has0 && has1)
      continue; // removed by the collapse
    const Vec3 before = cross(sub(s.t[1], s.t[0]), sub(s.t[2], s.t[0]));
    for (int i = 0; i < 3; ++i)
      if (s.ids[i] == v0 || s.ids[i] == v1)
        s.ids[i] = VertexId(), s.t[i] = p;
    const Point3 a(s.t[0][0], s.t[0][1], s.t[0][2]), b(s.t[1][0], s.t[1][1], s.t[1][2]),
      c(s.t[2][0], s.t[2][1], s.t[2][2]);
    if (CGAL::collinear(a, b, c) ||
      dot(before, cross(sub(s.t[1], s.t[0]), sub(s.t[2], s.t[0]))) <= 0)
      return false;
    s.measure();
    this->Star.push_back(s);
  }
  return true;
}

/// The new triangle nearest to a piece's centre within its limit (of those equally near, the
/// last), or star.size(). `guess` (an index, or star.size()): a triangle likely to be the
/// nearest (the previous piece's), measured first. A triangle whose box is farther than the
/// nearest so far or than the guess is skipped: it would not be taken, or could not be the
/// nearest (the slack covers the rounding of both squared distances), so the answer is the
/// one of measuring every triangle in order, with a few measured instead of all.
std::size_t nearestOf(const std::vector<StarFace>& star,
  const SurfelPiece& piece,
  std::size_t guess)
{
  constexpr double Slack = NearestSlack;
  const Vec3& p = piece.centre;
  double best = piece.limit * piece.limit, guessed = best;
  if (guess < star.size())
  {
    const Corners& t = star[guess].t;
    guessed = std::min(best, squaredDistanceToTriangle(p, t[0], t[1], t[2]));
  }
  std::size_t to = star.size();
  for (std::size_t i = 0; i < star.size(); ++i)
  {
    if (squaredDistanceToBox(p, star[i].box) > std::min(best, guessed) + Slack)
      continue;
    const Corners& t = star[i].t;
    const double d2 = squaredDistanceToTriangle(p, t[0], t[1], t[2]);
    if (d2 <= best)
      best = d2, to = i;
  }
  return to;
}

/// A piece that no new triangle keeps within its limit, quartered (each quarter's limit is
/// larger by the difference of the half diagonals) until each finds one; false if none does.
bool Simplifier::placePiece(const SurfelPiece& piece)
{
  if (piece.side <= SmallestSide || piece.limit > this->Reach - piece.halfDiagonal())
    return false; // the smallest, or kept at its input distance
  for (SurfelPiece q : piece.quarters())
  {
    q.limit = this->Reach - q.halfDiagonal();
    const std::size_t to = nearestOf(this->Star, q, this->Guess);
    if (to < this->Star.size())
      this->Moves.emplace_back(q, to), this->Guess = to;
    else if (!this->placePiece(q))
      return false;
  }
  return true;
}

/// (b): every piece of the old star's surfels finds a new triangle within its limit, whole or
/// quartered. A piece stays with its face when the face's new triangle keeps it within its
/// limit (the bound holds through any triangle within the limit, not only the nearest); else
/// it goes to the nearest new triangle. Staying spares the search over the star for most
/// pieces (nearestOf took 18 % of the instructions of the 128^3 ball's simplification, 6 %
/// after), and on the 128^3 ball, torus and CSG solid the triangles came out 174, 208 and 180
/// instead of 176, 208 and 178.
bool Simplifier::reassignSamples()
{
  this->Moves.clear();
  this->Stays.clear();
  this->Guess = this->Star.size();
  for (FaceId f : this->OldStar) // the first pieces of each face fetched together
    if (!this->SamplesOf[std::size_t(f)].empty())
      prefetch(this->SamplesOf[std::size_t(f)].data());
  for (FaceId f : this->OldStar)
  {
    const std::size_t same = this->starIndexOf(f);
    for (const SurfelPiece& piece : this->SamplesOf[std::size_t(f)])
    {
      const bool stays = same < this->Star.size() && this->Star[same].keeps(piece);
      this->Stays.push_back(stays);
      if (stays)
        continue;
      const std::size_t to = nearestOf(this->Star, piece, this->Guess);
      if (to < this->Star.size())
        this->Moves.emplace_back(piece, to), this->Guess = to;
      else if (!this->placePiece(piece))
        return false;
    }
  }
  return true;
}

/// Whether new triangle s meets triangle t (of a face, or another new triangle) with corner
/// ids `ids` anywhere but their common vertices and edge.
bool Simplifier::intersects(const StarFace& s,
  const Corners& t,
  const std::array<VertexId, 3>& ids) const
{
  auto point = [](const Vec3& v) { return Point3(v[0], v[1], v[2]); };
  int shared = 0, si[3], ti[3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (s.ids[i] == ids[j])
        si[shared] = i, ti[shared] = j, ++shared;
  // separated by the plane of either (but at the shared corner): no exact test needed
  if (shared < 2 &&
    (strictlyOneSide(s.t, t, shared ? 1 << ti[0] : 0) ||
      strictlyOneSide(t, s.t, shared ? 1 << si[0] : 0)))
    return false;
  const Kernel::Triangle_3 a(point(s.t[0]), point(s.t[1]), point(s.t[2]));
  const Kernel::Triangle_3 b(point(t[0]), point(t[1]), point(t[2]));
  if (shared == 0)
    return CGAL::do_intersect(a, b);
  if (shared == 1)
  {
    const Kernel::Segment_3 oppositeS(point(s.t[(si[0] + 1) % 3]), point(s.t[(si[0] + 2) % 3]));
    const Kernel::Segment_3 oppositeT(point(t[(ti[0] + 1) % 3]), point(t[(ti[0] + 2) % 3]));
    return CGAL::do_intersect(oppositeS, b) || CGAL::do_intersect(oppositeT, a);
  }
  if (shared == 2)
  {
    const int sOther = 3 - si[0] - si[1], tOther = 3 - ti[0] - ti[1];
    const Point3 p = point(s.t[si[0]]), q = point(s.t[si[1]]);
    const Point3 r = point(s.t[sOther]), x = point(t[tOther]);
    return CGAL::coplanar(p, q, r, x) && CGAL::coplanar_orientation(p, q, r, x) == CGAL::POSITIVE;
  }
  return true; // the same three vertices twice
}

/// (c): the new star against itself and against the faces near it: the faces whose boxes
/// meet the star's box, gathered once from the grid with their corners (not for each new
/// triangle: the new triangles' boxes overlap), then each new triangle against those whose
/// boxes meet its own.
bool Simplifier::freeOfIntersections()
{
  if (this->Star.empty())
    return true; // nothing kept: nothing to meet
  Box star = this->Star.front().box;
  for (std::size_t i = 0; i < this->Star.size(); ++i)
  {
    const StarFace& s = this->Star[i];
    for (std::size_t j = i + 1; j < this->Star.size(); ++j)
      if (this->intersects(s, this->Star[j].t, this->Star[j].ids))
        return false;
    for (int d = 0; d < 3; ++d)
      star[0][d] = std::min(star[0][d], s.box[0][d]),
      star[1][d] = std::max(star[1][d], s.box[1][d]);
  }
  if (++this->Round == 0)
    std::fill(this->Stamp.begin(), this->Stamp.end(), 0), this->Round = 1;
  for (FaceId f : this->OldStar)
    this->Stamp[std::size_t(f)] = this->Round;
  // The faces are found first, each face's corners prefetched, then read: the corners of
  // the faces near a star lie far apart in memory, and read one by one each read waited for
  // its own miss (those reads were a sixth of the checks' own time in perf, 128^3 torus).
  this->NearIds.clear();
  this->Grid.forEntries(star[0],
    star[1],
    [&](const GridEntry& e)
    {
      // a face apart from every new triangle's box is tested against none: not gathered
      // (the union of the star's boxes is much larger than the boxes themselves); a face
      // has one box in all its cells, so this drops the same faces in every cell
      if (e.apart(star[0], star[1]) ||
        std::all_of(this->Star.begin(),
          this->Star.end(),
          [&e](const StarFace& s) { return e.apart(s.box[0], s.box[1]); }))
        return;
      const FaceId f = e.face;
      if (this->Stamp[std::size_t(f)] == this->Round)
        return;
      this->Stamp[std::size_t(f)] = this->Round;
      prefetch(&this->Faces[std::size_t(f)]);
      this->NearIds.push_back(f);
    });
  this->Near.clear();
  for (FaceId f : this->NearIds)
  {
    const FaceCorners& kept = this->Faces[std::size_t(f)];
    this->Near.push_back({ kept.ids, kept.t, boxOf(kept.t) });
  }
  for (const StarFace& s : this->Star)
    for (const NearFace& n : this->Near)
      if (!apart(n.box, s.box) && this->intersects(s, n.t, n.ids))
        return false;
  return true;
}

bool Simplifier::accept(VertexId v0, VertexId v1, const Point3& placed)
{
  // cheapest first; the samples' side rejects most collapses
  if (!this->newStar(v0, v1, placed))
    return false;
  for (const StarFace& s : this->Star) // the first look-up of each triangle in (a), fetched early
    this->Lattice.prefetchNearest(Piece{ s.t }.enclosingCentre());
  if (!this->reassignSamples() || !this->freeOfIntersections())
    return false;
  for (const StarFace& s : this->Star)
    if (!this->Field.Cover.proves(s.t) &&
      !withinReach(s.t, this->Reach, this->Lattice, this->Pieces))
      return false;
  this->Accepted = { v0, v1 };
  this->AcceptedPoint = placed;
  return true;
}

bool Simplifier::collapsed(VertexId v0, VertexId v1, VertexId kept)
{
  if (this->Accepted != std::array<VertexId, 2>{ v0, v1 })
    return false;
  this->Accepted = {};
  this->M.point(kept) = this->AcceptedPoint;
  std::size_t next = 0; // in Stays
  for (FaceId f : this->OldStar)
  {
    std::vector<SurfelPiece>& pieces = this->SamplesOf[std::size_t(f)];
    if (this->M.is_removed(f))
    {
      next += pieces.size();
      std::vector<SurfelPiece>().swap(pieces); // its memory freed
      continue;
    }
    std::size_t staying = 0;
    for (const SurfelPiece& piece : pieces)
      if (this->Stays[next++])
        pieces[staying++] = piece;
    pieces.resize(staying);
  }
  for (const auto& [piece, to] : this->Moves)
    this->SamplesOf[std::size_t(this->Star[to].face)].push_back(piece);
  for (FaceId f : this->OldStar)
  {
    const Box b = boxOf(this->triangleOf(f));
    this->Grid.erase(f, b[0], b[1]);
  }
  for (const StarFace& s : this->Star)
  {
    this->keepCorners(s.face); // its new triangle: the kept vertex is now at the accepted point
    this->Grid.insert(s.face, s.box[0], s.box[1]);
  }
  if (2 * this->M.number_of_faces() < this->FacesInGrid)
    this->rebuildGrid();
  return true;
}

double Simplifier::surfelDistance() const
{
  double worst2 = 0;
  for (FaceId f : this->M.faces())
  {
    const Corners& t = this->triangleOf(f);
    for (const SurfelPiece& piece : this->SamplesOf[std::size_t(f)])
    {
      const double d = std::sqrt(squaredDistanceToTriangle(piece.centre, t[0], t[1], t[2]));
      worst2 = std::max(worst2, std::pow(d + piece.halfDiagonal(), 2));
    }
  }
  return std::sqrt(worst2);
}

/// How far the collapsed vertex is moved outwards from Lindstrom-Turk's placement (voxels):
/// the input surface runs about half a voxel inside the surfels, so the surfels' side of the
/// bound binds first; a small push outwards evens the two sides (0.05 to 0.1 halved the
/// triangles of the 64^3 ball and torus, 0.2 gave back the count without it). 0.07: of 0.05,
/// 0.06, 0.07, 0.08, 0.1 and 0.13, the fewest triangles on the 128^3 ball, torus and CSG
/// solid together with the lazy queue below (184, 222, 190 against 202, 234, 220 at 0.1; the
/// counts vary by several percent from one push to the next, as the greedy order shifts).
constexpr double OutwardShift = 0.07;

/// The unit area-weighted normal of the star of a collapsing edge (outwards: the surface is
/// oriented outwards), or zero.
template<typename Profile>
Vec3 starNormal(const Profile& profile)
{
  Vec3 n{ 0, 0, 0 };
  for (const auto& t : profile.triangles())
  {
    const Vec3 a = vec(get(profile.vertex_point_map(), t.v0)),
               b = vec(get(profile.vertex_point_map(), t.v1)),
               c = vec(get(profile.vertex_point_map(), t.v2));
    const Vec3 x = cross(sub(b, a), sub(c, a));
    for (int d = 0; d < 3; ++d)
      n[d] += x[d];
  }
  const double len = std::sqrt(dot(n, n));
  if (len > 0)
    for (int d = 0; d < 3; ++d)
      n[d] /= len;
  return n;
}

Point3 moved(const Point3& p, const Vec3& n, double by)
{
  return Point3(p.x() + by * n[0], p.y() + by * n[1], p.z() + by * n[2]);
}

using VertexPointMap = Mesh::Property_map<VertexId, Point3>;
using Profile = SMS::Edge_profile<Mesh, VertexPointMap, Kernel>;
using EdgeId = Mesh::Edge_index;
using HalfedgeId = Mesh::Halfedge_index;

/// The profile of an edge (CGAL's: its star, link and triangles), from its first halfedge.
Profile profileOf(Mesh& mesh, EdgeId e)
{
  static const Kernel traits;
  return Profile(mesh.halfedge(e),
    mesh,
    traits,
    get(CGAL::vertex_index, mesh),
    mesh.points(),
    get(CGAL::halfedge_index, mesh),
    false);
}

/// Lindstrom-Turk's placement moved OutwardShift along the area-weighted normal of the
/// collapsed star (outwards: the surface is oriented outwards), and its cost there; none when
/// Lindstrom-Turk finds no placement.
struct Costed
{
  boost::optional<Point3> placed;
  boost::optional<double> cost;
};

Costed lindstromTurk(const Profile& profile)
{
  const SMS::internal::LindstromTurk_params params; // the core keeps a reference to it
  SMS::internal::LindstromTurkCore<Mesh, Profile> core(params, profile);
  Costed c;
  c.placed = core.compute_placement();
  if (!c.placed)
    return c;
  c.placed = moved(*c.placed, starNormal(profile), OutwardShift);
  c.cost = core.compute_cost(c.placed);
  return c;
}

/// The vertex that makes a triangle with link edge e outside the collapsing star (CGAL's
/// find_exterior_link_triangle_3rd_vertex), or a null vertex.
VertexId outsideThird(const Mesh& m, HalfedgeId e, VertexId v0, VertexId v1)
{
  if (e == HalfedgeId())
    return VertexId();
  for (HalfedgeId h : { e, m.opposite(e) })
  {
    const VertexId a = m.target(m.next(h)), b = m.source(m.prev(h));
    if (a == b && a != v0 && a != v1)
      return a;
  }
  return VertexId();
}

/// CGAL's test of two triangles p0 p1 p2 and p0 p2 p3 sharing the edge p0 p2: areas within a
/// ratio of 1e8, and no fold (their normals no more than 179 degrees apart).
bool sharedTrianglesValid(const Point3& p0, const Point3& p1, const Point3& p2, const Point3& p3)
{
  const Vec3 a = vec(p0), e01 = sub(vec(p1), a), e02 = sub(vec(p2), a), e03 = sub(vec(p3), a);
  const Vec3 n012 = cross(e01, e02), n023 = cross(e02, e03);
  const double l012 = dot(n012, n012), l023 = dot(n023, n023);
  if (std::max(l012, l023) >= 1e8 * std::min(l012, l023))
    return false;
  const double l0123 = dot(n012, n023);
  static const double maxCos2 = std::pow(std::cos(CGAL_PI / 180.0), 2);
  return l0123 > 0 || l0123 * l0123 <= maxCos2 * (l012 * l023);
}

/// CGAL's geometric test of a collapse (Edge_collapse's is_collapse_geometrically_valid): with
/// the vertex at k0, no two adjacent triangles of the new star, nor a new triangle and its
/// neighbour outside the star, fold into each other.
bool geometricallyValid(const Mesh& m, const Profile& profile, const Point3& k0)
{
  const auto& link = profile.link();
  const auto connection = [&m](VertexId a, VertexId b)
  {
    for (HalfedgeId h : CGAL::halfedges_around_source(a, m))
      if (m.target(h) == b)
        return h;
    return HalfedgeId();
  };
  const std::size_t n = link.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const VertexId k1 = link[(i + n - 1) % n], k2 = link[i], k3 = link[(i + 1) % n];
    const HalfedgeId e12 = connection(k1, k2);
    const HalfedgeId e23 = k3 != k1 ? connection(k2, k3) : HalfedgeId();
    if (e12 != HalfedgeId() && e23 != HalfedgeId() &&
      !sharedTrianglesValid(k0, m.point(k1), m.point(k2), m.point(k3)))
      return false;
    const VertexId k4 = outsideThird(m, e12, profile.v0(), profile.v1());
    if (k4 != VertexId() && !sharedTrianglesValid(m.point(k1), m.point(k4), m.point(k2), k0))
      return false;
    const VertexId k5 = outsideThird(m, e23, profile.v0(), profile.v1());
    if (k5 != VertexId() && !sharedTrianglesValid(m.point(k2), m.point(k5), m.point(k3), k0))
      return false;
  }
  return true;
}

/// Where the collapse of the profile's edge goes, if anywhere: at the placement if the
/// Simplifier accepts it there (and CGAL's geometric test passes), or else at
/// Lindstrom-Turk's point pushed out less (0, then half of OutwardShift), at one of the edge's
/// ends or at its midpoint (the first accepted). The other points let collapses through where
/// the placement breaks the bound, mostly late, on large stars: the ends and midpoint gave 11
/// to 18 % fewer triangles on the 128^3 ball and CSG solid and 5 % on the torus, the smaller
/// pushes 1 to 8 % fewer again. `wider` (the last sweep, on the few edges left) tries more
/// points still: pushed further out or in, a quarter of the way along the edge, the middle
/// and the ends pushed out. The geometric test is made at the placement only; the other
/// points pass the Simplifier's checks alone (no degenerate or turned-over face, no
/// intersection).
boost::optional<Point3> acceptedPoint(Simplifier& state,
  const Mesh& mesh,
  const Profile& profile,
  const Point3& placed,
  bool wider)
{
  if (!geometricallyValid(mesh, profile, placed))
    return boost::none;
  if (state.accept(profile.v0(), profile.v1(), placed))
    return placed;
  const Point3 &a = profile.p0(), &b = profile.p1();
  const auto along = [&a, &b](double t)
  {
    return Point3(
      (1 - t) * a.x() + t * b.x(), (1 - t) * a.y() + t * b.y(), (1 - t) * a.z() + t * b.z());
  };
  const Vec3 n = starNormal(profile);
  for (const Point3& p :
    { moved(placed, n, -OutwardShift), moved(placed, n, -0.5 * OutwardShift), a, b, along(0.5) })
    if (state.accept(profile.v0(), profile.v1(), p))
      return p;
  if (!wider)
    return boost::none;
  for (const Point3& p : { moved(placed, n, 0.5 * OutwardShift),
         moved(placed, n, OutwardShift),
         moved(placed, n, 2 * OutwardShift),
         moved(placed, n, -2 * OutwardShift),
         along(0.25),
         along(0.75),
         moved(along(0.5), n, OutwardShift),
         moved(a, n, OutwardShift),
         moved(b, n, OutwardShift) })
    if (state.accept(profile.v0(), profile.v1(), p))
      return p;
  return boost::none;
}

/// The queue of edges by cost (the cheapest first, then the smallest edge number): a 4-ary
/// heap with each edge's place in it, so that a new cost moves the edge's one entry. An
/// entry's cost may be stale (the caller measures the edge again when it pops it). A heap
/// of the pushes, whose older entries were skipped when popped, held up to 151,000 entries
/// on the 128^3 ball, where 283,000 of its 492,000 pops were of such entries.
class EdgeQueue
{
public:
  explicit EdgeQueue(std::size_t edges)
    : Edges(edges, { NotQueued, std::numeric_limits<double>::quiet_NaN() })
  {
  }

  void push(EdgeId e, double cost)
  {
    const std::uint32_t edge = std::uint32_t(std::size_t(e));
    this->Edges[edge].cost = cost;
    std::size_t at = this->Edges[edge].place;
    if (at == NotQueued)
    {
      at = this->Heap.size();
      this->Heap.push_back({ cost, edge });
    }
    else
      this->Heap[at].cost = cost;
    this->siftDown(this->siftUp(at));
  }
  bool queued(EdgeId e) const { return this->Edges[std::size_t(e)].place != NotQueued; }
  /// The cost last pushed for e (NaN if none).
  double lastCost(EdgeId e) const { return this->Edges[std::size_t(e)].cost; }
  /// Takes the cheapest entry off the queue; false when empty.
  bool pop(EdgeId& e, double& cost)
  {
    if (this->Heap.empty())
      return false;
    const Entry top = this->Heap.front();
    this->Edges[top.edge].place = NotQueued;
    const Entry last = this->Heap.back();
    this->Heap.pop_back();
    if (!this->Heap.empty())
    {
      this->Heap.front() = last;
      this->Edges[last.edge].place = 0;
      this->siftDown(0);
    }
    e = EdgeId(top.edge);
    cost = top.cost;
    return true;
  }
  /// The cost of the cheapest entry, or infinity.
  double cheapest() const
  {
    return this->Heap.empty() ? std::numeric_limits<double>::infinity() : this->Heap.front().cost;
  }

private:
  struct Entry
  {
    double cost;
    std::uint32_t edge;
    bool before(const Entry& o) const
    {
      return this->cost < o.cost || (this->cost == o.cost && this->edge < o.edge);
    }
  };
  static constexpr std::size_t NotQueued = std::numeric_limits<std::size_t>::max();

  void put(std::size_t at, const Entry& entry)
  {
    this->Heap[at] = entry;
    this->Edges[entry.edge].place = at;
  }
  std::size_t siftUp(std::size_t at)
  {
    const Entry entry = this->Heap[at];
    while (at > 0 && entry.before(this->Heap[(at - 1) / 4]))
    {
      this->put(at, this->Heap[(at - 1) / 4]);
      at = (at - 1) / 4;
    }
    this->put(at, entry);
    return at;
  }
  void siftDown(std::size_t at)
  {
    const Entry entry = this->Heap[at];
    const std::size_t n = this->Heap.size();
    for (;;)
    {
      const std::size_t first = 4 * at + 1;
      if (first >= n)
        break;
      std::size_t best = first;
      for (std::size_t c = first + 1; c < std::min(first + 4, n); ++c)
        if (this->Heap[c].before(this->Heap[best]))
          best = c;
      if (!this->Heap[best].before(entry))
        break;
      this->put(at, this->Heap[best]);
      at = best;
    }
    this->put(at, entry);
  }

  struct Edge // read together (two arrays missed the cache twice)
  {
    std::size_t place; // its entry in Heap, or NotQueued
    double cost;       // the cost last pushed (NaN if none)
  };
  std::vector<Entry> Heap;
  std::vector<Edge> Edges; // per edge
};

/// The greedy edge collapse (CGAL's Surface_mesh_simplification loop, with lazy costs): the
/// cheapest edge by Lindstrom-Turk's cost is taken off the queue, measured again (an edge whose
/// star changed since it was queued and whose cost rose above the next one's goes back with
/// its new cost), and collapsed if the link condition holds and the Simplifier accepts it.
/// CGAL re-costs the 20 to 40 edges around each collapse at once (1.6 M placements for 41,000
/// collapses on the 128^3 ball, most of its time); here only the edges of the kept vertex are,
/// and the other edges of its neighbours only when they come to the top (those that had been
/// refused are queued again, at their last cost: their star changed).
class CollapseLoop
{
public:
  CollapseLoop(Mesh& mesh, Simplifier& state)
    : M(mesh)
    , State(state)
    , Queue(mesh.num_edges()) // edge numbers, removed ones included
    , InitialFaces(mesh.number_of_faces())
    , Measured(mesh.num_edges())
    , ChangedAt(mesh.num_vertices(), 0)
  {
    this->measureAll();
  }

  /// Collapses until no edge may be; the number of collapses, or -1 if a collapse was not the
  /// one the Simplifier accepted last (then nothing is proven).
  std::ptrdiff_t run();
  /// Sweeps once more over every edge left, with more points tried (acceptedPoint's
  /// `wider`): every edge is measured and tried again; within the sweep, an edge refused
  /// stays refused unless its star changes.
  /// Adds its collapses to `collapses` (or sets -1 as run does). A second sweep collapsed
  /// nothing on the 128^3 ball, torus and CSG solid (the first took 8, 14 and 12 triangles
  /// off, for 4-9 % of the loop's time).
  void sweep(std::ptrdiff_t& collapses);

private:
  void measure(EdgeId e)
  {
    const Costed& c = this->costed(e);
    if (c.cost)
      this->Queue.push(e, *c.cost);
  }
  /// Lindstrom-Turk's placement and cost of e, measured again only if the star of either end
  /// changed since e was last measured, or the edge's first halfedge turned (a collapse may
  /// turn an edge it keeps; the result is then the same but for rounding): they depend on
  /// nothing else. Most popped edges were measured when their vertex was kept, just before
  /// (on the 128^3 ball 222,000 placements were made for 49,000 pops, each pop measuring
  /// again).
  const Costed& costed(EdgeId e)
  {
    Measure& m = this->Measured[std::size_t(e)];
    const HalfedgeId h = this->M.halfedge(e);
    const std::uint32_t changed = std::max(this->ChangedAt[std::size_t(this->M.source(h))],
      this->ChangedAt[std::size_t(this->M.target(h))]);
    if (m.at == NotMeasured || m.at < changed || m.from != this->M.source(h))
    {
      m.costed = lindstromTurk(profileOf(this->M, e));
      m.at = this->Epoch;
      m.from = this->M.source(h);
    }
    return m.costed;
  }
  /// After a collapse: the kept vertex and its neighbours, whose stars changed.
  void changedAround(VertexId kept)
  {
    ++this->Epoch;
    this->ChangedAt[std::size_t(kept)] = this->Epoch;
    for (VertexId v : CGAL::vertices_around_target(this->M.halfedge(kept), this->M))
      this->ChangedAt[std::size_t(v)] = this->Epoch;
  }
  /// Measures every edge (about 80,000 Lindstrom-Turk placements at 128^3): stops early when
  /// asked to, and run() then stops at once.
  void measureAll()
  {
    std::size_t k = 0;
    for (EdgeId e : this->M.edges())
    {
      if ((++k & 4095) == 0 && this->State.stopped())
        return;
      this->measure(e);
    }
  }
  void requeueAround(VertexId kept);

  Mesh& M;
  Simplifier& State;
  EdgeQueue Queue;
  std::size_t InitialFaces;
  bool Wider = false;
  static constexpr std::uint32_t NotMeasured = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t Epoch = 0; // collapses so far
  struct Measure           // one per edge, read at once (three arrays missed the cache three times)
  {
    Costed costed;                  // its last placement and cost
    std::uint32_t at = NotMeasured; // the epoch they were measured in
    VertexId from;                  // the source of its first halfedge then
  };
  std::vector<Measure> Measured;
  std::vector<std::uint32_t> ChangedAt; // per vertex: the epoch its star last changed
};

std::ptrdiff_t CollapseLoop::run()
{
  std::ptrdiff_t collapses = 0;
  EdgeId e;
  double queuedCost = 0;
  while (this->Queue.pop(e, queuedCost))
  {
    if (this->M.is_removed(e))
      continue;
    if (this->State.stopped())
      break;
    const Costed c = this->costed(e);
    if (!c.cost)
      continue; // queued again when its star changes
    if (*c.cost > queuedCost && *c.cost > this->Queue.cheapest())
    {
      this->Queue.push(e, *c.cost); // its cost rose: not the cheapest any more
      continue;
    }
    const HalfedgeId h = this->M.halfedge(e);
    if (!this->State.inside(this->M.source(h)) || !this->State.inside(this->M.target(h)) ||
      !CGAL::Euler::does_satisfy_link_condition(e, this->M))
      continue;
    const Profile profile = profileOf(this->M, e);
    const boost::optional<Point3> at =
      acceptedPoint(this->State, this->M, profile, *c.placed, this->Wider);
    if (!at)
      continue;
    const VertexId v0 = profile.v0(), v1 = profile.v1();
    const VertexId kept = CGAL::Euler::collapse_edge(e, this->M);
    if (!this->State.collapsed(v0, v1, kept))
      return -1;
    ++collapses;
    this->changedAround(kept);
    this->requeueAround(kept);
    this->State.at(1.0 - double(this->M.number_of_faces()) / double(this->InitialFaces));
  }
  return collapses;
}

void CollapseLoop::sweep(std::ptrdiff_t& collapses)
{
  if (collapses < 0 || this->State.aborted())
    return;
  this->Wider = true;
  this->measureAll();
  const std::ptrdiff_t more = this->run();
  collapses = more < 0 ? more : collapses + more;
}

/// After a collapse: the edges of the kept vertex measured again, and the refused edges of its
/// neighbours queued again at their last cost.
void CollapseLoop::requeueAround(VertexId kept)
{
  for (HalfedgeId h : CGAL::halfedges_around_target(kept, this->M))
  {
    this->measure(this->M.edge(h));
    for (HalfedgeId g : CGAL::halfedges_around_target(this->M.source(h), this->M))
    {
      const EdgeId f = this->M.edge(g);
      if (this->M.source(g) == kept || this->Queue.queued(f))
        continue;
      const double last = this->Queue.lastCost(f);
      if (std::isnan(last))
        this->measure(f);
      else
        this->Queue.push(f, last);
    }
  }
}

/// The tolerance of the reported surface distance (maximumTriangleDistanceToSurfels's default).
constexpr double DistanceTolerance = 0.02;

/// maximumTriangleDistanceToSurfels with the distances of `distance` (the simplifier's, whose
/// marks make the searches cheaper and give the same distances).
double maximumDistance(const SurfelDistance& distance,
  const TriangleSurface& surface,
  double tolerance)
{
  double lower = 0, upper = 0;
  std::vector<Corners> stack;
  for (const auto& tri : surface.triangles)
  {
    stack.push_back({ surface.points[std::size_t(tri[0])],
      surface.points[std::size_t(tri[1])],
      surface.points[std::size_t(tri[2])] });
    while (!stack.empty())
    {
      Piece piece{ stack.back() };
      stack.pop_back();
      piece.measure(distance);
      lower = std::max(lower, piece.centre);
      if (piece.centre + piece.radius <= lower + tolerance || piece.radius < tolerance / 2)
      {
        upper = std::max(upper, piece.centre + piece.radius);
        continue;
      }
      for (const Corners& h : piece.halves())
        stack.push_back(h);
    }
  }
  return std::min(upper, 2.0);
}

Mesh meshOf(const TriangleSurface& s)
{
  Mesh mesh;
  std::vector<VertexId> v;
  v.reserve(s.points.size());
  for (const Vec3& p : s.points)
    v.push_back(mesh.add_vertex(Point3(p[0], p[1], p[2])));
  for (const auto& t : s.triangles)
    if (mesh.add_face(v[std::size_t(t[0])], v[std::size_t(t[1])], v[std::size_t(t[2])]) ==
      Mesh::null_face())
      return Mesh();
  return mesh;
}

TriangleSurface surfaceOf(Mesh& mesh)
{
  mesh.collect_garbage();
  TriangleSurface s;
  for (VertexId v : mesh.vertices())
    s.points.push_back(vec(mesh.point(v)));
  for (FaceId f : mesh.faces())
  {
    std::array<std::int32_t, 3> t;
    int i = 0;
    for (VertexId v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      t[i++] = std::int32_t(v);
    s.triangles.push_back(t);
  }
  return s;
}

/// Whether the input can be simplified: a closed, valid triangle mesh without degenerate
/// triangles (the exact tests of (c) need proper triangles).
bool simplifiable(const Mesh& mesh)
{
  if (mesh.number_of_faces() == 0 || !CGAL::is_valid_polygon_mesh(mesh) || !CGAL::is_closed(mesh))
    return false;
  for (FaceId f : mesh.faces())
  {
    std::vector<Point3> p;
    for (VertexId v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      p.push_back(mesh.point(v));
    if (CGAL::collinear(p[0], p[1], p[2]))
      return false;
  }
  return true;
}

/// The input returned unchanged, with its own distances: the triangles' bound, and the
/// surfels' measured as at the start of a simplification (infinite when the input is no
/// triangle mesh CGAL can hold).
SimplifiedSurface unsimplified(const BitVolume& object,
  const TriangleSurface& input,
  Mesh mesh,
  const SimplifyOptions& options,
  const Execution& exec)
{
  SimplifiedSurface out;
  out.surface = input;
  out.surfaceDistance = maximumTriangleDistanceToSurfels(object, input);
  out.surfelDistance = std::numeric_limits<double>::infinity();
  if (mesh.number_of_faces() == 0)
    return out;
  const SurfelField field(object, mesh, options.distance, exec);
  Simplifier state(field, mesh, exec);
  state.assignSamples(object, exec);
  if (state.aborted() || exec.stopRequested())
    out.aborted = true;
  else
    out.surfelDistance = state.surfelDistance();
  return out;
}

// The first phase: the surface cut into slabs along the longest axis of its box, at the
// quantiles of its points' coordinates (the geometry alone, never the threads: the result is
// the same with any number of threads, or none). Each slab's region is a mesh of its own, of
// the input triangles whose box meets the closed slab, with their pieces; its collapse loop
// (CollapseLoop::run) collapses only edges whose old star's corners and placement lie strictly
// inside the slab. So:
//  - the faces a region changes (its old stars, strictly inside) are in no other region (whose
//    faces meet its own closed slab), nor are their vertices; the faces two regions share (those
//    meeting the cut between them) are changed by neither: the frozen band;
//  - a region's checks are exact: (c) tests the new star against the faces whose boxes meet
//    its box, strictly inside the slab, all of them in the region (a face meeting that box
//    meets the slab) and none changed by another region; (b) moves pieces among the star's
//    faces only; (a) reads the object alone. The link condition, the costs and the geometric
//    test read the faces around the edge's ends and their link, which are in the region too;
//  - the regions share no data that changes: each has its own mesh, pieces, grid, lattice,
//    queue and scratch; the object and the SurfelField (the marked surfels, the proven voxels)
//    are only read. The regions run concurrently without a lock (exec's parallel loop, one
//    region per iteration), one after another without one.
// Then the regions' surviving faces are merged (a face shared by regions from the first that
// holds it: the copies are the same) and the existing loop runs over the whole, the band
// included, with its last sweep. The collapses differ from those of one loop over the whole
// (the order is another), and so does the output, within a few percent of its triangles.

/// Regions below this many faces are not cut: the first phase would save less than the
/// second costs.
constexpr std::size_t RegionFacesMinimum = 4096;

/// One slab's region: its mesh, with each vertex's and face's number in the input.
struct Region
{
  Slab slab;
  Mesh mesh;
  std::vector<std::int32_t> pointOf;    // per vertex of mesh: its input point
  std::vector<std::int32_t> triangleOf; // per face of mesh: its input triangle
  SamplesByFace samples;                // per face of mesh: its pieces
  std::ptrdiff_t collapses = 0;         // -1: not the collapse accepted (nothing proven)
  bool aborted = false;
  bool built = true; // false: CGAL refused a face of the region
};

/// `count` slabs along the longest axis of the points' box, cut at the quantiles of the points'
/// coordinates along it.
std::vector<Slab> slabsOf(const TriangleSurface& s, int count)
{
  Vec3 lo = s.points.front(), hi = lo;
  for (const Vec3& p : s.points)
    for (int d = 0; d < 3; ++d)
      lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (hi[d] - lo[d] > hi[axis] - lo[axis])
      axis = d;
  std::vector<double> x;
  x.reserve(s.points.size());
  for (const Vec3& p : s.points)
    x.push_back(p[axis]);
  std::vector<Slab> slabs(static_cast<std::size_t>(count));
  for (Slab& slab : slabs)
    slab.axis = axis;
  for (std::size_t r = 1; r < slabs.size(); ++r)
  {
    const auto at = x.begin() + std::ptrdiff_t(x.size() * r / slabs.size());
    std::nth_element(x.begin(), at, x.end());
    slabs[r].lo = slabs[r - 1].hi = *at;
  }
  return slabs;
}

/// The region of the input triangles whose box along the slab's axis meets the closed slab,
/// with copies of their pieces.
Region regionOf(const TriangleSurface& input, const SamplesByFace& samples, const Slab& slab)
{
  Region region;
  region.slab = slab;
  std::vector<VertexId> vertexOf(input.points.size());
  for (std::size_t i = 0; i < input.triangles.size(); ++i)
  {
    const auto& t = input.triangles[i];
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::int32_t c : t)
      lo = std::min(lo, input.points[std::size_t(c)][slab.axis]),
      hi = std::max(hi, input.points[std::size_t(c)][slab.axis]);
    if (hi < slab.lo || lo > slab.hi)
      continue;
    std::array<VertexId, 3> v;
    for (int k = 0; k < 3; ++k)
    {
      VertexId& id = vertexOf[std::size_t(t[k])];
      if (id == VertexId())
      {
        const Vec3& p = input.points[std::size_t(t[k])];
        id = region.mesh.add_vertex(Point3(p[0], p[1], p[2]));
        region.pointOf.push_back(t[k]);
      }
      v[k] = id;
    }
    if (region.mesh.add_face(v[0], v[1], v[2]) == Mesh::null_face())
    {
      region.built = false;
      return region;
    }
    region.triangleOf.push_back(std::int32_t(i));
    region.samples.push_back(samples[i]);
  }
  return region;
}

/// The region's collapse loop (without the last sweep, left to the whole).
void simplifyRegion(const SurfelField& field, Region& region, const Execution& exec)
{
  if (!region.built)
    return;
  Simplifier state(field, region.mesh, exec, 0, 0, region.slab);
  state.setSamples(std::move(region.samples));
  CollapseLoop loop(region.mesh, state);
  region.collapses = loop.run();
  region.samples = state.takeSamples();
  region.aborted = state.aborted();
}

/// The surface after the regions' collapses, with the pieces of its triangles: each region's
/// surviving faces of which it is the first to hold the input triangle, region by region in
/// face order, the points in input order.
TriangleSurface mergedSurface(const TriangleSurface& input,
  std::vector<Region>& regions,
  SamplesByFace& samples)
{
  std::vector<int> home(input.triangles.size(), -1);
  for (std::size_t r = regions.size(); r-- > 0;)
    for (std::int32_t t : regions[r].triangleOf)
      home[std::size_t(t)] = int(r);
  std::vector<Vec3> at(input.points.size());
  std::vector<std::int32_t> number(input.points.size(), -1);
  TriangleSurface merged;
  for (std::size_t r = 0; r < regions.size(); ++r)
  {
    Region& region = regions[r];
    for (FaceId f : region.mesh.faces())
    {
      if (home[std::size_t(region.triangleOf[std::size_t(f)])] != int(r))
        continue;
      std::array<std::int32_t, 3> t;
      int i = 0;
      for (VertexId v : CGAL::vertices_around_face(region.mesh.halfedge(f), region.mesh))
      {
        const std::int32_t p = region.pointOf[std::size_t(v)];
        at[std::size_t(p)] = vec(region.mesh.point(v));
        number[std::size_t(p)] = 0;
        t[i++] = p;
      }
      merged.triangles.push_back(t);
      samples.push_back(std::move(region.samples[std::size_t(f)]));
    }
  }
  for (std::size_t p = 0; p < number.size(); ++p)
    if (number[p] == 0)
    {
      number[p] = std::int32_t(merged.points.size());
      merged.points.push_back(at[p]);
    }
  for (auto& t : merged.triangles)
    for (std::int32_t& c : t)
      c = number[std::size_t(c)];
  return merged;
}

/// The first phase (above): the regions simplified, then merged into `mesh`, their pieces into
/// `merged`; false (mesh untouched) when a region could not be built or its loop proved
/// nothing.
bool simplifyRegions(const SurfelField& field,
  const TriangleSurface& input,
  const SamplesByFace& samples,
  int count,
  const Execution& exec,
  Mesh& mesh,
  SamplesByFace& merged,
  std::size_t& collapses,
  bool& aborted)
{
  std::vector<Region> regions;
  for (const Slab& slab : slabsOf(input, count))
    regions.push_back(regionOf(input, samples, slab));
  const Execution silent = exec.silent(); // progress is reported on the calling thread only
  exec.forRange(std::int64_t(regions.size()),
    [&](std::int64_t begin, std::int64_t end)
    {
      for (std::int64_t r = begin; r < end; ++r)
        simplifyRegion(field, regions[std::size_t(r)], silent);
    });
  for (const Region& region : regions)
    aborted = aborted || region.aborted;
  if (aborted)
    return false; // the caller returns the input: nothing to merge
  for (const Region& region : regions)
  {
    if (!region.built || region.collapses < 0)
      return false;
    collapses += std::size_t(region.collapses);
  }
  const TriangleSurface surface = mergedSurface(input, regions, merged);
  Mesh cut = meshOf(surface);
  if (cut.number_of_faces() != surface.triangles.size())
    return false;
  mesh = std::move(cut);
  return true;
}

} // namespace

SimplifiedSurface simplifyBoundary(const BitVolume& object,
  const TriangleSurface& input,
  const SimplifyOptions& options,
  const Execution& exec)
{
  SimplifiedSurface out;
  out.surface = input;
  Mesh mesh = meshOf(input);
  if (!simplifiable(mesh))
    return unsimplified(object, input, mesh, options, exec);
  const SurfelField field(object, mesh, options.distance, exec);
  SamplesByFace samples;
  {
    Simplifier first(field, mesh, exec);
    first.assignSamples(object, exec);
    samples = first.takeSamples();
  }
  if (exec.stopRequested())
  {
    out.aborted = true;
    return out;
  }
  bool aborted = false;
  double from = 0.1;
  if (options.regions > 1 && mesh.number_of_faces() >= RegionFacesMinimum)
  {
    SamplesByFace merged;
    if (simplifyRegions(
          field, input, samples, options.regions, exec, mesh, merged, out.collapses, aborted))
      samples = std::move(merged), from = 0.5;
    else
      out.collapses = 0; // the whole from its start, as if not cut
    if (aborted || exec.stopRequested() || !exec.report(from))
    {
      out.aborted = true;
      return out;
    }
  }
  Simplifier state(field, mesh, exec, from, 0.95);
  state.setSamples(std::move(samples));
  CollapseLoop loop(mesh, state);
  std::ptrdiff_t collapses = loop.run();
  loop.sweep(collapses);
  out.collapses += std::size_t(std::max<std::ptrdiff_t>(0, collapses));
  if (state.aborted() || exec.stopRequested())
  {
    out.aborted = true;
    return out;
  }
  if (collapses < 0) // the samples no longer follow the mesh: nothing after it is proven
    return unsimplified(object, input, meshOf(input), options, exec);
  out.surfelDistance = state.surfelDistance();
  if (!CGAL::is_valid_polygon_mesh(mesh) || !CGAL::is_closed(mesh) ||
    CGAL::Polygon_mesh_processing::does_self_intersect(mesh))
    return unsimplified(object, input, meshOf(input), options, exec);
  out.surface = surfaceOf(mesh);
  out.simplified = true;
  out.surfaceDistance = maximumDistance(field.Surfels, out.surface, DistanceTolerance);
  return out;
}

double maximumTriangleDistanceToSurfels(const BitVolume& object,
  const TriangleSurface& surface,
  double tolerance)
{
  return maximumDistance(SurfelDistance(object), surface, tolerance);
}

bool provenByVoxels(const BitVolume& object, const std::array<Vec3, 3>& t, double distance)
{
  const auto box = boxOf(t);
  // faces: as many as the box's voxels, so that the box is never refused as large
  const VoxelCover cover(object, box[0], box[1], std::size_t(1) << 40, std::min(distance, 1.99));
  return cover.proves(t);
}

} // namespace vbr
