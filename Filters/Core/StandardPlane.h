// Exact, incremental recognition of pieces of standard arithmetic planes.
//
// A standard plane (a, b, c, mu) is the set of integer points p with
//   mu <= a*x + b*y + c*z < mu + |a| + |b| + |c|
// (the arithmetic plane of width omega = |a| + |b| + |c|, Francon & Papier, section 2).
// Its unit squares form a 2-manifold: the boundary of the digital half-space of the voxels
// whose centres satisfy n.centre < mu + omega / 2. A surfel of that boundary has its outward
// normal s*e_d with s*n_d > 0, so the recognizer also takes the orientation of the surfels:
// a face is a piece of the boundary of one digital half-space, not merely a set of pointels
// in a slab, and its plane normal points out of the object.
//
// Method: for a fixed octant sigma of the normal, |n|_1 = sigma.n and the pointels fit iff
// max n.q - min n.q < sigma.n; on the slice sigma.n = 1 the normals with width <= 1 form a
// convex polygon, the intersection of half-planes n.(sigma - (q - r)) >= 0. The polygon is
// kept exactly (vertices are integer rays, intersections of two constraint planes through
// the origin) and clipped lazily: a vertex whose width exceeds 1 is cut by the pair (q, r)
// realizing its extremes, until every vertex fits; since the width is convex, the whole
// polygon then fits. Strict inequalities are decided at a relative interior point. The
// integer normal returned is the one of smallest omega (the smallest (n_x, n_y) among those),
// found by scanning the lattice points of the polygon level by level (omega = 1, 2, ...), in
// columns along the polygon's lattice-width direction (a shortest vector of the lattice for
// the polygon's width norm, by Gauss's reduction): level omega has at most omega * w + 1
// columns for a polygon of lattice width w, and a polygon with no lattice point inside at
// level W - 1 has (W - 1) w <= 1 + 2 / sqrt(3) (Hurkens' flatness bound in the plane), so
// reaching the smallest omega W costs O(W * E) column bounds for E edges, plus the
// candidates, instead of O(W^2 * E * x-extent) along a fixed axis (thin polygons, long across
// n_x, were the superlinear cliff). Points only accumulate, so the smallest omega never
// decreases: a search after the first starts at the current plane's omega, not at 1 (a face
// grown to omega W paid O(W^2 * E) over its searches, now O(W * E) plus one level a search).
// The same planes as searching from 1, except where a search from 1 ran out of its level
// budget (SearchBudget) before the solution's level: starting higher, it may now find it.
// Floating point only chooses the frame (any frame finds the same normal); no floating point
// decides anything.
#ifndef vbr_StandardPlane_h
#define vbr_StandardPlane_h

#include "Geometry.h"
#include "GridPointIndex.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vbr
{

struct StandardPlane
{
  std::array<std::int64_t, 3> normal{ 0, 0, 0 }; ///< (a, b, c)
  std::int64_t mu = 0;

  std::int64_t omega() const
  {
    return (this->normal[0] < 0 ? -this->normal[0] : this->normal[0]) +
      (this->normal[1] < 0 ? -this->normal[1] : this->normal[1]) +
      (this->normal[2] < 0 ? -this->normal[2] : this->normal[2]);
  }
  std::int64_t value(const Point3& p) const
  {
    return this->normal[0] * p[0] + this->normal[1] * p[1] + this->normal[2] * p[2];
  }
  bool contains(const Point3& p) const
  {
    const std::int64_t v = this->value(p);
    return this->mu <= v && v < this->mu + this->omega();
  }
};

class StandardPlaneRecognizer
{
public:
  StandardPlaneRecognizer() { this->reset(); }

  /// Forgets every point: any plane fits.
  void reset();

  /// Adds the points (and surfel orientations: sign[d] in {-1, 0, +1} asks s*n_d > 0) if
  /// the union still lies in one standard plane; otherwise changes nothing. Points must lie
  /// less than 2^15 from the first point added along every axis: the call refuses (returns
  /// false) any farther point, so that every product of the recognition fits its integers.
  ///
  /// Bit i of `known` (i < 32) tells that points[i] is one of the points added already: the
  /// caller knows it (the growth: the ends of the edges a surfel shares with the face), and its
  /// lookup is skipped. A wrong bit drops a new point: only certain knowledge may be passed.
  bool tryAdd(const Point3* points,
    std::size_t count,
    const std::array<int, 3>& signs,
    std::uint32_t known = 0);
  bool tryAdd(const std::vector<Point3>& points, const std::array<int, 3>& signs)
  {
    return this->tryAdd(points.data(), points.size(), signs);
  }

  /// A plane of smallest omega found for the points added so far (undefined when empty).
  const StandardPlane& plane() const { return this->Current; }
  /// Number of distinct points added.
  std::size_t pointCount() const { return this->Points.size(); }

  /// Recognition work done: polygon clips and solution searches (for benchmarks).
  std::size_t clipCount() const { return this->Clips; }
  std::size_t searchCount() const { return this->Searches; }
  /// Slow paths of later calls repeated from records (for tests).
  std::size_t laterCallsRepeated() const { return this->Repeated; }
  /// Points sifted out of the measures, known to be the midpoint of two others (for tests).
  std::size_t siftedOutCount() const { return this->Scanned - this->Extremes.size(); }

private:
  using Vec = std::array<std::int64_t, 3>;
  struct Vertex
  {
    Vec ray;             ///< a normal on the polygon's boundary, up to a positive factor
    std::int64_t lo, hi; ///< min and max of ray.q over the points applied
    std::uint32_t argLo, argHi;
    /// The edge from this vertex to the next: edge.n >= 0 inside, and whether it bounds the
    /// octant (n_d = 0 allowed there). Kept with the vertex: a clip copies one array, not three.
    Vec edge;
    bool octantEdge;
  };
  /// The normals of one octant with width <= 1, as a convex polygon on the slice.
  struct Octant
  {
    std::array<int, 3> sigma;
    std::vector<Vertex> vertices; ///< cyclic
    std::size_t applied = 0;      ///< points clipped into the polygon so far
  };

  /// A polygon edge's half-plane on the columns of a frame: along * t + across * k +
  /// level * omega >= 0 at the normal k a + t v of level omega (> 0 when strict).
  struct FrameForm
  {
    std::int64_t along, across, level;
    bool strict;
  };

  /// The eight octants' triangles before any point (restoreOctant copies them).
  static std::array<Octant, 8> initialOctants();
  /// Octant s's triangle put back, no point applied, after a reset.
  void restoreOctant(int s);
  /// Clips o with the points from o.applied to count; false when it empties.
  bool applyPoints(Octant& o, std::size_t count) const;
  bool clip(Octant& o, const Vec& h, std::size_t count) const;
  void measure(Vertex& v, std::size_t count) const;
  /// Calls f(j) for every point index j < count that may be a vertex of the points' convex
  /// hull: the sifted points not known to be a midpoint (Extremes), then every later one.
  template<typename F>
  void forEachExtreme(std::size_t count, F&& f) const;
  /// Sifts the committed points into Extremes, when there are enough of them to matter.
  void refreshExtremes();
  /// Whether q is the midpoint of two committed points along an axis or a face diagonal.
  bool isMidpoint(const Point3& q) const;
  static bool hasInterior(const Octant& o);
  bool solve(const Octant& o,
    const std::array<int, 3>& present,
    std::int64_t omegaStart,
    std::int64_t omegaLimit,
    Vec& normal) const;
  /// The phases of solve: the polygon's strict edges (StrictEdges), its vertices and its
  /// edges' half-planes on the slices (Rays, Forms).
  void markStrictEdges(const Octant& o) const;
  void sliceThePolygon(const Octant& o, const Vec& sigma) const;
  bool fits(const Vec& n, const std::array<int, 3>& present) const;
  /// The min and max of n.p over the points (not empty).
  void rangeOf(const Vec& n, std::int64_t& lo, std::int64_t& hi) const;
  /// Whether the width is exactly 1 all along polygon edge e (between vertices e, e + 1).
  bool saturated(const Octant& o, std::size_t e) const;
  /// tryAdd after the last reset (no point yet): the recognition of a first call made before
  /// with the same points relative to the first one and the same orientations is repeated
  /// from its record (FirstCalls) rather than recognised again; false when the call is not
  /// one it records (too many points, or too far apart), with nothing done.
  bool firstCallFromRecord(const Point3* points,
    std::size_t count,
    const std::array<int, 3>& signs,
    bool& taken);
  /// The state-changing calls of the face since its first (Path, while recorded): false, the
  /// path given up for the face, when the call is not one a path holds.
  bool extendPath(const Point3* points, std::size_t count, const std::array<int, 3>& signs);
  /// Path started by the number of the face's first call.
  void startPath(std::uint32_t node);
  /// A slow path repeated from the record of an earlier face with the same Path: whether
  /// there is one, and then whether it took the points.
  bool laterCallFromRecord(std::uint64_t pathHash, const std::array<int, 3>& present, bool& taken);
  /// The slot of the record of Path (hash `pathHash`) in LaterTable, or of the empty slot
  /// where it would go.
  std::size_t laterSlot(std::uint64_t pathHash) const;
  /// Records the slow path just taken by a call on the Path, while there is room.
  void recordLaterCall(std::uint64_t pathHash, bool taken, std::size_t clips, std::size_t searches);
  bool recognise(const Point3* points,
    std::size_t count,
    const std::array<int, 3>& signs,
    std::uint32_t known);
  // The phases of tryAdd.
  /// The surfel orientations asked so far and now; false when two are opposite.
  static bool addOrientations(const std::array<int, 3>& signs, std::array<int, 3>& present);
  /// The new points relative to Origin, without repeats, into Fresh (and FreshKeys); false
  /// when one is too far from Origin.
  bool collectFreshPoints(const Point3* points, std::size_t count, std::uint32_t known);
  /// Sorts Fresh by key without repeats, and fills FreshKeys.
  void sortFreshPoints();
  /// Fast path: the current plane takes the new points and orientations (then committed).
  bool takenByCurrentPlane(const std::array<int, 3>& present);
  /// Whether an octant cannot hold a normal for the orientations and the new points.
  bool octantExcluded(const Octant& o, const std::array<int, 3>& present) const;
  /// Slow path: clips a copy of every live octant with the new points and searches it for
  /// the normal of smallest omega; false when none is found.
  bool searchOctants(const std::array<int, 3>& present, std::array<bool, 8>& survives, Vec& best);
  /// Keeps the clipped octants that survived and the plane of normal `best`.
  void adoptNormal(const Vec& best, const std::array<bool, 8>& survives);
  void commit(const std::array<int, 3>& present);
  void takePlane(const std::array<std::int64_t, 3>& normal, std::int64_t lo, std::int64_t hi);

  Point3 Origin{ 0, 0, 0 };   ///< points are kept relative to the first one
  std::vector<Point3> Points; ///< without repeats
  GridPointIndex Keys;        ///< of Points
  std::size_t KeysPeak = 0;   ///< most points Keys held since it was made
  /// Indices of the first Scanned points but the midpoints of two other points, in
  /// increasing order. A midpoint is not a vertex of the points' convex hull, and every
  /// linear form reaches its minimum and maximum over the points on a vertex: the
  /// recognizer's measures read only these and the points after the first Scanned.
  std::vector<std::uint32_t> Extremes;
  std::size_t Scanned = 0;
  std::vector<Point3> Fresh;            ///< the new points of a call
  std::vector<std::uint64_t> FreshKeys; ///< theirs, sorted
  std::array<Octant, 8> Octants;        ///< one per sign pattern of the normal
  std::array<Octant, 8> Trials; ///< the octants with the points of a call, until it succeeds
  std::array<bool, 8> Alive;    ///< octants that may still hold a solution
  /// Octants whose triangle the last reset has not put back yet (restoreOctant).
  std::array<bool, 8> Unrestored{};
  /// Octants a call left without its new points (see searchOctants), until it succeeds.
  std::array<bool, 8> Deferred{};
  std::array<int, 3> Present{ 0, 0, 0 }; ///< orientation asked per axis
  StandardPlane Current;
  std::int64_t CurrentLo = 0, CurrentHi = 0; ///< range of the current normal over the points
  std::int64_t BestLo = 0, BestHi = 0;       ///< range of searchOctants' best normal
  mutable std::int64_t FitLo = 0, FitHi = 0; ///< range of the last normal fits accepted
  mutable std::size_t Clips = 0, Searches = 0;
  mutable std::vector<char> StrictEdges;                      ///< per polygon edge, in solve
  mutable std::vector<Vec> Rays;                              ///< the polygon's vertices, in solve
  mutable std::vector<std::array<double, 2>> FrameEdges;      ///< in solve's thinFrame
  mutable std::vector<std::pair<double, double>> FrameBreaks; ///< in solve's thinFrame
  mutable std::vector<std::int64_t> ClipValues;               ///< per vertex, in clip
  mutable Octant ClipPolygon; ///< the clipped polygon's storage, in clip
  mutable std::vector<std::array<std::int64_t, 3>> Forms; ///< its edges on the slices, in solve
  mutable std::vector<FrameForm> FrameForms;              ///< the Forms in solve's column frame

  /// What a first call left (firstCallFromRecord): whether it took the points, and then the
  /// points, the octants it put back and clipped, and the plane relative to the first point;
  /// the clips and searches it counted.
  struct FirstCall
  {
    bool taken = false;
    std::vector<Point3> points;
    std::array<Octant, 8> octants;
    std::array<bool, 8> alive{}, unrestored{};
    std::array<int, 3> present{ 0, 0, 0 };
    Vec normal{ 0, 0, 0 };
    std::int64_t lo = 0, hi = 0;
    std::size_t clips = 0, searches = 0;
    std::uint32_t node = 0; ///< its number, which starts the Path of the calls after it
  };
  /// A first call's orientations and points relative to its first point, a byte each, in
  /// fixed-size words (makeFirstCallKey): hashed and compared a word at a time, with no
  /// allocation per call (std::string keys cost about 56 M instructions on noise 64^3).
  struct FirstCallKey
  {
    static constexpr std::size_t PointsAtMost = 24; ///< an umbrella of six surfels
    /// The key of a first call: false, the key unspecified, when a coordinate is more than
    /// 127 from the first point's or there are more than PointsAtMost points (such calls are
    /// not recorded).
    bool assign(const Point3* points, std::size_t count, const std::array<int, 3>& signs);
    /// The count, three orientations and 3 PointsAtMost offsets, zero-padded.
    std::array<std::uint64_t, (4 + 3 * PointsAtMost + 7) / 8> words{};
    bool operator==(const FirstCallKey& other) const { return this->words == other.words; }
  };
  struct FirstCallKeyHash
  {
    std::size_t operator()(const FirstCallKey& key) const;
  };
  /// By the call's orientations and points relative to its first (makeFirstCallKey).
  std::unordered_map<FirstCallKey, FirstCall, FirstCallKeyHash> FirstCalls;

  /// The calls of a face after its first one are repeated from records too, on their slow
  /// path only (a fast path is cheaper than a look-up): the state after the same calls is the
  /// same relative to the first point. A path: the number of the face's first call (its
  /// record), then each later call that passed collectFreshPoints (it may have changed the state,
  /// so it is kept even when it changed nothing), CallBytes each (the point count,
  /// the orientations and the points relative to the first point, a byte each). Empty when
  /// the face's calls are not recorded (a first call without a record, a call beyond reach, or
  /// more than CallsAtMost calls: deeper slow paths were seldom met again on 50 % noise).
  struct CallPath
  {
    static constexpr std::size_t CallPoints = 4, CallBytes = 4 + 3 * CallPoints;
    static constexpr std::size_t CallsAtMost = 3, BytesAtMost = 4 + CallBytes * CallsAtMost;
    std::array<std::uint8_t, BytesAtMost + 4> bytes{}; ///< whole words, for the hash
    std::size_t size = 0;
    bool operator==(const CallPath& other) const
    {
      return this->size == other.size && this->bytes == other.bytes; // zero beyond the size
    }
    std::uint64_t hash() const;
  };
  CallPath Path;
  /// What a slow path left: its path, whether it took the points, the clips
  /// and searches it counted, the octants restored and alive (their vertices one after the
  /// other in LaterVertices, `sizes` each) and the plane.
  struct LaterCall
  {
    CallPath path;
    bool taken = false;
    std::uint32_t clips = 0, searches = 0, verticesAt = 0;
    std::array<std::uint8_t, 8> sizes{}, applied{};
    std::array<bool, 8> alive{}, unrestored{};
    Vec normal{ 0, 0, 0 };
    std::int64_t lo = 0, hi = 0;
  };
  /// The records, found by the hashes of their paths in an open-addressed table (hash, index
  /// of the record; LaterTableSize slots, twice the records kept), and their vertices in one
  /// array: no allocation per record.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> LaterTable;
  std::vector<LaterCall> LaterRecords;
  std::vector<Vertex> LaterVertices;
  std::size_t Repeated = 0; ///< slow paths repeated from records
};

} // namespace vbr

#endif
