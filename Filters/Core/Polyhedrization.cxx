// The polyhedrization of Francon & Papier (section 3) and the reversion.
//
// The growth (FaceGrower): faces are grown one by one from seeds in surfel order. A face
// starts from an umbrella of the seed when one fits one standard plane (seedUmbrella, the
// paper's heuristic), else from the seed alone (growFrom); drainWave then takes the surfels
// of the queue q(f) breadth first, each only if the face stays a topological disk (condition
// 1: meetsAlongOneArc) and all its pointels stay in one standard plane with the surfels on
// its outer side (condition 2: StandardPlaneRecognizer::tryAdd). A surfel refused by the
// plane is never offered to that face again. Beyond the paper: moveToLargerFaces gives the rim
// of large faces back to them, mergeSmallFaces hands small faces to their neighbours
// (absorb, extend, with recognizers kept for large faces: recognizerOf), dropEmptyFaces
// renumbers. Threads (growFaces): a face never leaves its boundary component, so the components
// are dealt to groups grown concurrently (groupComponents, growGroupsInWaves), and their faces put
// back in the order of their seeds (gatherInSeedOrder), the sequential order, with the stamps
// renumbered: the same faces, numbers and refusals as on one thread. The steps after the growth go
// over the same groups concurrently (Part, forEachPart: the moves and the loops), each touching
// only its components' surfels, faces and vertices; the vertex counts are one pass over the loops.
// The output: each face's boundary loop (LoopTracer, all loops in one array), when asked the face
// beyond each loop edge, and the number of faces around each vertex (countFacesAtVertices: the
// standard vertices have three or more).
//
// The reversion (revert): each face's surfels are refilled from its outline (FaceFiller: the
// squares of the plane on the left of the loop's linels, seedFromLoop, flooded across every
// linel that is not a loop edge, each once), marked in bits per voxel and direction (SurfelBits),
// which also tells a surfel filled by two faces, and the voxels follow by parity along x
// (fillByParity).

#include "Polyhedrization.h"

#include "GridPointIndex.h"
#include "Prefetch.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace vbr
{

namespace
{

constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();

/// How far ahead a walk over a list of surfels prefetches their entries.
constexpr std::size_t PrefetchAhead = 8;

/// The sign vector of a surfel's normal (its sign on its axis, 0 elsewhere), from a table:
/// writing one element picked by index and reading the array back whole stalled on the store.
const std::array<int, 3>& signsOf(const Surfel& s)
{
  static constexpr std::array<int, 3> Signs[6] = {
    { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 0, 1, 0 }, { 0, 0, -1 }, { 0, 0, 1 }
  };
  return Signs[s.direction];
}

/// Reads ahead of a walk over faces (their numbers `faces(i)`, i < count) that reads each
/// face's record, its surfel list and the graph's entries of its surfels, at the walk's face i:
/// the record of the face 4 on, the list of the face 2 on and the first surfels' entries of the
/// next face (`entries(s)` prefetches those of surfel s). Most faces are small (7 surfels on 50 %
/// noise), so the read-ahead within one face's list alone never started for them, and the
/// faces, taken by size, lie far apart. (prefetchKept: GCC 12 dropped these hints otherwise.)
template<typename FaceAt, typename Entries>
void prefetchFaces(const Polyhedron& poly,
  std::size_t i,
  std::size_t count,
  FaceAt faces,
  Entries entries)
{
  if (i + 4 < count)
    prefetchKept(&poly.faces[faces(i + 4)]);
  if (i + 2 < count)
    prefetchKept(poly.faces[faces(i + 2)].surfels.data());
  if (i + 1 < count)
  {
    const std::vector<std::uint32_t>& next = poly.faces[faces(i + 1)].surfels;
    for (std::size_t j = 0; j < std::min(next.size(), PrefetchAhead); ++j)
      entries(next[j]);
  }
}

/// Which edges of surfel s face f shares (its neighbour across them is of f), and how many.
int sharedEdgesWith(const SurfelGraph& graph,
  const std::vector<std::uint32_t>& faceOf,
  std::uint32_t s,
  std::uint32_t f,
  bool shared[4])
{
  int count = 0;
  for (int k = 0; k < 4; ++k)
  {
    shared[k] = faceOf[graph.neighbourOf(s, k)] == f;
    count += shared[k];
  }
  return count;
}

/// Condition 1 of Francon & Papier (section 3), "we keep a topological disk": whether
/// surfel s meets the surfels of face f (other than s) along one arc of its boundary: 1 to 3
/// consecutive shared edges, and no other vertex of s touched by f. Adding s to the disk f then
/// leaves a disk; taking s out of the disk f + s does too when, in addition, f fills the umbrellas
/// of the vertices inside the arc. Vertices are checked by walking their umbrellas, so no per-face
/// state is needed.
bool meetsAlongOneArc(const SurfelGraph& graph,
  const std::vector<std::uint32_t>& faceOf,
  std::uint32_t s,
  std::uint32_t f,
  bool removing)
{
  bool shared[4];
  const int count = sharedEdgesWith(graph, faceOf, s, f, shared);
  if (count == 0 || count == 4)
    return false;
  int arcs = 0;
  for (int k = 0; k < 4; ++k)
  {
    const bool onArc = shared[k] || shared[(k + 3) % 4];
    const bool insideArc = shared[k] && shared[(k + 3) % 4];
    arcs += shared[k] && !shared[(k + 3) % 4];
    // Touched: another surfel of f round the vertex. Taken out, s must not pinch f at a
    // vertex inside the arc: f must fill the rest of that umbrella (f + s is a disk, so
    // then f alone is one).
    // The walk stops at the first surfel of f unless the whole umbrella is asked for.
    const bool whole = removing && insideArc;
    if (onArc && !whole)
      continue; // touched: the surfel across edge k or k - 1 is of f and round this vertex
    bool touched = false, filled = true;
    graph.aroundVertex(s,
      k,
      [&](std::uint32_t u)
      {
        if (u != s)
        {
          touched = touched || faceOf[u] == f;
          filled = filled && faceOf[u] == f;
        }
        return whole || !touched;
      });
    if (touched != onArc || (removing && insideArc && !filled))
      return false;
  }
  return arcs == 1;
}

/// meetsAlongOneArc(graph, faceOf, s, f, false) while face f grows (FaceGrower::run), read from
/// the stamps of the vertices instead of walks round their umbrellas: a vertex of s off the arc
/// is touched by f exactly when a surfel of f has it as a corner (its umbrella is the surfels
/// with that vertex), i.e. when the growth stamped it with f (FaceGrower::take). Two loads
/// where a walk waited for one load per surfel of the umbrella, one after the other.
/// `onFace` receives the corners of s at the ends of the edges it shares with f: corners of
/// surfels of f.
bool meetsAlongOneArcGrowing(const SurfelGraph& graph,
  const std::vector<std::uint32_t>& faceOf,
  const std::vector<std::uint32_t>& touching,
  std::uint32_t s,
  std::uint32_t f,
  std::uint32_t& onFace)
{
  bool shared[4];
  const int count = sharedEdgesWith(graph, faceOf, s, f, shared);
  if (count == 0 || count == 4)
    return false;
  int arcs = 0;
  onFace = 0;
  for (int k = 0; k < 4; ++k)
  {
    const bool onArc = shared[k] || shared[(k + 3) % 4];
    arcs += shared[k] && !shared[(k + 3) % 4];
    if (!onArc && touching[graph.vertexOf(s, k)] == f)
      return false;
    onFace |= std::uint32_t(onArc) << k; // corner k ends edge k or edge k - 1
  }
  return arcs == 1;
}

/// Per surfel: its face, and the face that last queued it and last refused it; per vertex, the
/// face that last took a surfel round it (the growth's stamps; the merging reads the refusals
/// the growth left).
struct SurfelStamps
{
  SurfelStamps(std::vector<std::uint32_t>& faceOfSurfel, std::size_t surfels, std::size_t vertices)
    : faceOf(faceOfSurfel)
    , queued(surfels, None)
    , refused(surfels, None)
    , touching(vertices, None)
  {
    faceOf.assign(surfels, None);
  }
  std::vector<std::uint32_t>& faceOf;
  std::vector<std::uint32_t> queued, refused, touching;

  /// Frees the vertex stamps, which only the growth reads.
  void releaseTouching() { std::vector<std::uint32_t>().swap(this->touching); }
  /// Frees the queue stamps and the refusals, which only the growth and the merging read.
  void releaseQueues()
  {
    std::vector<std::uint32_t>().swap(this->queued);
    std::vector<std::uint32_t>().swap(this->refused);
  }
};

/// The growth of the faces: per-face state kept in arrays stamped with the face number, so
/// that starting a face costs nothing. Every surfel examined ticks the progress poll being
/// watched; once it says stop, the growth ends early and the faces are left unfinished.
class FaceGrower
{
public:
  /// Grows into `faces`, with the face of each surfel, the queue stamps and the refusals in
  /// arrays over all the graph's surfels (all None at first), which growers of other boundary
  /// components share: each grower touches only its own components' surfels.
  FaceGrower(const SurfelGraph& graph,
    const PolyhedrizationOptions& options,
    std::vector<StandardFace>& faces,
    SurfelStamps& stamps)
    : Graph(graph)
    , Options(options)
    , Faces(faces)
    , FaceOf(stamps.faceOf)
    , Queued(stamps.queued)
    , Refused(stamps.refused)
    , Touching(stamps.touching)
    , DepthLimit(options.maximumDepth)
  {
  }

  /// The poll the growth ticks from now on (it must outlive the calls).
  void watch(ProgressPoll& poll) { this->Poll = &poll; }

  /// Grows faces from the free surfels of `seeds`, in order; false when stopped.
  bool run(const std::vector<std::uint32_t>& seeds)
  {
    // The per-vertex stamps (Touching) exist only during the growth: they are freed before the
    // merging, so nothing may write them once run returns, stopped or not.
    this->Growing = true;
    const bool done = this->growAll(seeds);
    this->Growing = false;
    return done;
  }

  /// Frees the recognizers kept for large faces by the merging.
  void releaseCache() { this->Cache.clear(); }

private:
  bool growAll(const std::vector<std::uint32_t>& seeds)
  {
    for (std::uint32_t s : seeds)
    {
      if (this->FaceOf[s] != None)
        continue;
      if (!this->Poll->tick())
        return false;
      this->growFrom(s);
      if (this->Poll->stopped())
        return false;
    }
    return true;
  }

  void growFrom(std::uint32_t seed)
  {
    const std::uint32_t f = static_cast<std::uint32_t>(this->Faces.size());
    this->Faces.emplace_back();
    // The face grows in storage kept from face to face, then gets a list of its size: one
    // allocation a face, not one per doubling (most faces are small, and many).
    this->Faces[f].surfels.swap(this->Growth);
    this->Recognizer.reset();
    this->Wave.clear();
    if (!this->seedUmbrella(seed, f))
    {
      this->Recognizer.tryAdd(this->pointelsOf(seed), 4, signsOf(this->Graph.surfels[seed]));
      this->take(seed, f, 0);
    }
    this->drainWave(f);
    StandardFace& face = this->Faces[f];
    face.plane = this->Recognizer.plane();
    this->Growth.swap(face.surfels);
    face.surfels.assign(this->Growth.begin(), this->Growth.end());
    this->Growth.clear();
  }

  /// The growth of face f over its queue q(f) (Francon & Papier, section 3), breadth first
  /// ("the propagation of a circular wave"): each queued surfel joins f if f stays a disk
  /// (condition 1) of one standard plane (condition 2).
  void drainWave(std::uint32_t f)
  {
    std::size_t head = 0; // the queue is Wave from head on (a vector: no deque blocks to manage)
    while (head < this->Wave.size())
    {
      if (!this->Poll->tick())
        break;
      if (head >= 4096 && 2 * head >= this->Wave.size())
      {
        // The entries read are dropped, in order, so that a large face's queue holds its
        // frontier rather than every surfel ever queued for it.
        this->Wave.erase(
          this->Wave.begin(), this->Wave.begin() + static_cast<std::ptrdiff_t>(head));
        head = 0;
      }
      if (head + WaveAhead < this->Wave.size())
        this->prefetchDiskTest(this->Wave[head + WaveAhead].first);
      const auto [s, depth] = this->Wave[head++];
      this->Queued[s] = None;
      if (this->FaceOf[s] != None || this->Refused[s] == f)
        continue;
      if (this->Options.maximumFaceSize &&
        this->Faces[f].surfels.size() >= this->Options.maximumFaceSize)
        break;
      // While growing, the corners on the arc are known points of the recognizer (the corners
      // of f's surfels): their lookups are skipped.
      std::uint32_t onFace = 0;
      const bool disk = this->Growing
        ? meetsAlongOneArcGrowing(this->Graph, this->FaceOf, this->Touching, s, f, onFace)
        : meetsAlongOneArc(this->Graph, this->FaceOf, s, f, false);
      if (!disk)
        continue; // may fit later, when it is queued again by a new neighbour
      if (!this->Active->tryAdd(this->pointelsOf(s), 4, signsOf(this->Graph.surfels[s]), onFace))
      {
        this->Refused[s] = f; // points only accumulate: it never fits this face again
        continue;
      }
      this->take(s, f, depth);
    }
    for (; head < this->Wave.size(); ++head)
      this->Queued[this->Wave[head].first] = None;
    this->Wave.clear();
  }

  /// How many queue entries ahead drainWave reads for the disk test.
  static constexpr std::size_t WaveAhead = 4;

  /// Reads ahead for the disk test of surfel s, a few entries on in the queue: the faces of
  /// its neighbours and the stamps of its vertices. Its own entries (neighbours, vertices) were
  /// read ahead when it was queued (take), so they are at hand now; without this the test
  /// waited for each neighbour's face, rows of voxels away in the array, one after the other.
  void prefetchDiskTest(std::uint32_t s) const
  {
    for (int k = 0; k < 4; ++k)
    {
      prefetchKept(&this->FaceOf[this->Graph.neighbourOf(s, k)]);
      if (this->Growing)
        prefetchKept(&this->Touching[this->Graph.vertexOf(s, k)]);
    }
  }

public:
  /// Hands every surfel of face f to the faces around it, each keeping the disk and plane
  /// conditions as in the growth; f then disappears. Changes nothing unless all its
  /// surfels find a face.
  bool absorb(std::uint32_t f)
  {
    std::vector<std::uint32_t>& freed = this->Faces[f].surfels;
    for (std::uint32_t s : freed)
      this->FaceOf[s] = None;
    struct Saved
    {
      std::uint32_t face;
      std::size_t size;
      StandardPlane plane;
    };
    std::vector<Saved> saved;
    std::size_t left = freed.size();
    for (int round = 0; round < 4 && left > 0; ++round)
    {
      const std::vector<std::uint32_t> around = this->facesAround(freed);
      if (around.empty())
        break;
      for (std::uint32_t g : around)
      {
        saved.push_back({ g, this->Faces[g].surfels.size(), this->Faces[g].plane });
        left -= this->extend(g, freed);
        if (left == 0 || this->Poll->stopped())
          break;
      }
      if (this->Poll->stopped())
        return false; // the faces are discarded: no need to undo
    }
    if (left == 0)
    {
      freed.clear();
      return true;
    }
    // Undo, latest first, so that each face gets its first saved state back.
    for (auto it = saved.rbegin(); it != saved.rend(); ++it)
    {
      StandardFace& g = this->Faces[it->face];
      if (g.surfels.size() != it->size)
        this->Cache.erase(it->face); // its recognizer holds the surfels given back
      g.surfels.resize(it->size);
      g.plane = it->plane;
    }
    for (std::uint32_t s : freed)
      this->FaceOf[s] = f;
    return false;
  }

private:
  /// Faces sharing an edge with the free surfels among `surfels`, most shared edges first.
  std::vector<std::uint32_t> facesAround(const std::vector<std::uint32_t>& surfels) const
  {
    std::unordered_map<std::uint32_t, int> shared;
    for (std::uint32_t s : surfels)
      if (this->FaceOf[s] == None)
        for (int k = 0; k < 4; ++k)
        {
          const std::uint32_t g = this->FaceOf[this->Graph.neighbourOf(s, k)];
          if (g != None)
            ++shared[g];
        }
    std::vector<std::pair<int, std::uint32_t>> byCount;
    for (const auto& [g, count] : shared)
      byCount.emplace_back(-count, g);
    std::sort(byCount.begin(), byCount.end());
    std::vector<std::uint32_t> faces;
    for (const auto& c : byCount)
      faces.push_back(c.second);
    return faces;
  }

  /// A recognizer holding the points of face g: rebuilt from its surfels, or for a large
  /// face the one kept from the previous extension of g. (A small face is offered to each of
  /// its neighbours, and rebuilding a neighbour of 10^4 surfels for each small face next to
  /// it made the merging quadratic: hours on the engine > 0.) Null when the surfels are
  /// beyond the search's reach from scratch.
  StandardPlaneRecognizer* recognizerOf(std::uint32_t g)
  {
    const std::vector<std::uint32_t>& surfels = this->Faces[g].surfels;
    StandardPlaneRecognizer* r = &this->Recognizer;
    if (surfels.size() >= CachedFrom)
    {
      Kept& kept = this->Cache[g];
      if (kept.recognizer && kept.surfels == surfels.size())
        return kept.recognizer.get();
      if (!kept.recognizer)
        kept.recognizer = std::make_unique<StandardPlaneRecognizer>();
      kept.surfels = surfels.size();
      r = kept.recognizer.get();
    }
    std::vector<Point3> points;
    std::array<int, 3> signs{ 0, 0, 0 };
    for (std::uint32_t s : surfels)
    {
      const auto& sf = this->Graph.surfels[s];
      signs[sf.axis()] = sf.sign();
      for (int k = 0; k < 4; ++k)
        points.push_back(this->Graph.cornerOf(s, k));
    }
    r->reset();
    if (!r->tryAdd(points, signs))
    {
      this->Cache.erase(g);
      return nullptr;
    }
    return r;
  }

  /// Grows face g again over the free surfels next to it; returns how many it took.
  std::size_t extend(std::uint32_t g, const std::vector<std::uint32_t>& freed)
  {
    StandardFace& face = this->Faces[g];
    StandardPlaneRecognizer* recognizer = this->recognizerOf(g);
    if (!recognizer)
      return 0; // leave g as it is
    const std::size_t before = face.surfels.size();
    this->Wave.clear();
    for (std::uint32_t s : freed)
      if (this->FaceOf[s] == None)
        for (int k = 0; k < 4; ++k)
          if (this->FaceOf[this->Graph.neighbourOf(s, k)] == g && this->Queued[s] != g)
          {
            this->Queued[s] = g;
            this->Wave.emplace_back(s, 0);
          }
    // The depth limit shapes the growth from a seed; absorbed surfels have no depth.
    this->DepthLimit = 0;
    this->Active = recognizer;
    this->drainWave(g);
    this->Active = &this->Recognizer;
    this->DepthLimit = this->Options.maximumDepth;
    face.plane = recognizer->plane();
    const auto kept = this->Cache.find(g);
    if (kept != this->Cache.end())
      kept->second.surfels = face.surfels.size(); // it holds exactly the points taken
    return face.surfels.size() - before;
  }

  /// The umbrella of a corner of the seed as the first face, when all its surfels are free
  /// and lie in one standard plane (the seed of one umbrella that Francon & Papier prefer).
  bool seedUmbrella(std::uint32_t seed, std::uint32_t f)
  {
    std::vector<std::uint32_t>& umbrella = this->Umbrella; // storage kept from seed to seed
    std::vector<Point3>& points = this->UmbrellaPoints;
    for (int k = 0; k < 4; ++k)
    {
      umbrella.clear();
      bool free = true;
      this->Graph.aroundVertex(seed,
        k,
        [&](std::uint32_t u)
        {
          umbrella.push_back(u);
          free = free && this->FaceOf[u] == None;
          return free;
        });
      if (!free ||
        (this->Options.maximumFaceSize && umbrella.size() > this->Options.maximumFaceSize))
        continue;
      points.clear();
      std::array<int, 3> signs{ 0, 0, 0 };
      bool opposite = false;
      for (std::uint32_t u : umbrella)
      {
        const auto& sf = this->Graph.surfels[u];
        opposite = opposite || signs[sf.axis()] == -sf.sign();
        signs[sf.axis()] = sf.sign();
        for (int c = 0; c < 4; ++c)
          points.push_back(this->Graph.cornerOf(u, c));
      }
      if (opposite || !this->Recognizer.tryAdd(points, signs))
        continue;
      for (std::uint32_t u : umbrella)
        this->take(u, f, 0);
      return true;
    }
    return false;
  }

  /// The 4 corners of surfel s (computed: the graph does not store them), valid until the next
  /// call.
  const Point3* pointelsOf(std::uint32_t s)
  {
    for (int k = 0; k < 4; ++k)
      this->Corners[k] = this->Graph.cornerOf(s, k);
    return this->Corners.data();
  }

  void take(std::uint32_t s, std::uint32_t f, std::uint32_t depth)
  {
    this->FaceOf[s] = f;
    if (this->Growing) // the stamps exist only during the growth (freed before the merging)
      for (int k = 0; k < 4; ++k)
        this->Touching[this->Graph.vertexOf(s, k)] = f;
    this->Faces[f].surfels.push_back(s);
    ++this->Taken;
    if (this->Growing && this->Poll->due()) // the division only when the fraction is read
      this->Poll->at(double(this->Taken) / double(this->Graph.size()));
    if (this->DepthLimit && depth + 1 > this->DepthLimit)
      return;
    for (int k = 0; k < 4; ++k)
    {
      const std::uint32_t t = this->Graph.neighbourOf(s, k);
      if (this->FaceOf[t] == None && this->Queued[t] != f && this->Refused[t] != f)
      {
        this->Queued[t] = f;
        this->Wave.emplace_back(t, depth + 1);
        // Read when t comes out of the queue, a wave later: neighbours across rows of voxels
        // lie far apart in the arrays, and these loads were the growth's cache misses.
        prefetch(&this->Graph.surfels[t]);
        prefetch(&this->Graph.neighbour[4 * std::size_t(t)]);
        prefetch(&this->Graph.vertex[4 * std::size_t(t)]);
      }
    }
  }

  const SurfelGraph& Graph;
  const PolyhedrizationOptions& Options;
  std::vector<StandardFace>& Faces; ///< where the faces go
  std::vector<std::uint32_t>& FaceOf;
  StandardPlaneRecognizer Recognizer;
  StandardPlaneRecognizer* Active = &this->Recognizer; ///< the one drainWave grows with
  /// Faces of at least this many surfels keep their recognizer through the merging.
  static constexpr std::size_t CachedFrom = 64;
  struct Kept
  {
    std::size_t surfels = 0; ///< the face's surfel count the recognizer was made for
    std::unique_ptr<StandardPlaneRecognizer> recognizer;
  };
  std::unordered_map<std::uint32_t, Kept> Cache;
  ProgressPoll* Poll = nullptr;
  bool Growing = false;
  std::size_t Taken = 0; ///< surfels taken by the growth, for its progress
  std::vector<std::pair<std::uint32_t, std::uint32_t>> Wave; ///< (surfel, depth)
  std::vector<std::uint32_t> Growth;           ///< the storage of the face growing, in growFrom
  std::vector<std::uint32_t> Umbrella;         ///< in seedUmbrella
  std::vector<Point3> UmbrellaPoints;          ///< in seedUmbrella
  std::array<Point3, 4> Corners;               ///< in pointelsOf
  std::vector<std::uint32_t>&Queued, &Refused; ///< stamped with the face
  /// Per vertex, the last face of the growth that took a surfel round it. Growers of different
  /// groups share it safely: a vertex's umbrella never leaves its boundary component.
  std::vector<std::uint32_t>& Touching;
  std::uint32_t DepthLimit;
};

/// The output of Francon & Papier (section 3), each face's boundary: the loops of disk
/// faces, counter-clockwise seen from outside, with the face beyond each loop edge. Each
/// boundary vertex of a disk starts exactly one boundary edge, kept per vertex in arrays
/// stamped with the face.
class LoopTracer
{
public:
  /// With `across`, also the face beyond each loop edge.
  LoopTracer(const SurfelGraph& graph, bool across)
    : Graph(graph)
    , Across(across)
    , Edge(graph.vertexPointel.size())
    , Stamp(graph.vertexPointel.size(), None)
  {
  }

  /// The number of edges of face f's loop: its surfels' edges to other faces.
  std::size_t loopLength(const Polyhedron& poly, std::uint32_t f) const
  {
    std::size_t edges = 0;
    const std::vector<std::uint32_t>& list = poly.faces[f].surfels;
    for (std::size_t j = 0; j < list.size(); ++j)
    {
      if (j + PrefetchAhead < list.size())
        prefetch(&this->Graph.neighbour[4 * std::size_t(list[j + PrefetchAhead])]);
      for (int k = 0; k < 4; ++k)
        edges += poly.faceOfSurfel[this->Graph.neighbourOf(list[j], k)] != f;
    }
    return edges;
  }

  /// Writes face f's loop of `length` edges (loopLength) from `vertices`, and the face beyond
  /// each edge from `across` when traced. Faces of different boundary components may be traced
  /// concurrently: they share no vertex.
  void trace(const Polyhedron& poly,
    std::uint32_t f,
    std::size_t length,
    std::uint32_t* vertices,
    std::uint32_t* across)
  {
    std::uint32_t start = None;
    const std::vector<std::uint32_t>& list = poly.faces[f].surfels;
    for (std::size_t j = 0; j < list.size(); ++j)
    {
      if (j + PrefetchAhead < list.size())
      {
        prefetch(&this->Graph.neighbour[4 * std::size_t(list[j + PrefetchAhead])]);
        prefetch(&this->Graph.vertex[4 * std::size_t(list[j + PrefetchAhead])]);
      }
      const std::uint32_t s = list[j];
      for (int k = 0; k < 4; ++k)
        if (poly.faceOfSurfel[this->Graph.neighbourOf(s, k)] != f)
        {
          const std::uint32_t v = this->Graph.vertexOf(s, k);
          if (this->Stamp[v] == f)
            throw std::logic_error("face boundary is not one loop");
          this->Stamp[v] = f;
          this->Edge[v] = 4 * s + static_cast<std::uint32_t>(k);
          start = v;
        }
    }
    if (start == None)
      return;
    std::size_t i = 0;
    std::uint32_t v = start;
    do
    {
      if (this->Stamp[v] != f || i >= length)
        throw std::logic_error("face boundary is not one loop");
      const std::uint32_t s = this->Edge[v] / 4;
      const int k = static_cast<int>(this->Edge[v] % 4);
      vertices[i] = v;
      if (this->Across)
        across[i] = poly.faceOfSurfel[this->Graph.neighbourOf(s, k)];
      ++i;
      v = this->Graph.vertexOf(s, (k + 1) % 4);
    } while (v != start);
    if (i != length)
      throw std::logic_error("face boundary is not one loop");
  }

  /// Each face's loop as its run of `poly`'s array, once all are traced
  /// (`lengths`: each face's loop length).
  static void pointLoops(Polyhedron& poly, const std::vector<std::size_t>& lengths)
  {
    std::size_t first = 0;
    for (std::size_t f = 0; f < poly.faces.size(); ++f)
    {
      poly.faces[f].loop = { poly.loopVertices.data() + first, lengths[f] };
      first += lengths[f];
    }
  }

private:
  const SurfelGraph& Graph;
  const bool Across;
  std::vector<std::uint32_t> Edge;  ///< 4 * surfel + edge leaving each boundary vertex
  std::vector<std::uint32_t> Stamp; ///< the face Edge is for
};

/// Whether surfel t, now in face g (of more than one surfel when `leavesRest`), may move to
/// face f of plane `plane`: the larger face's plane must take the surfel as it is (its
/// coefficients stay), and both faces must stay disks (t meets f along one arc, and the rest
/// of g along one arc).
bool surfelCanMove(const SurfelGraph& graph,
  const std::vector<std::uint32_t>& faceOf,
  std::uint32_t t,
  std::uint32_t f,
  const StandardPlane& plane,
  bool leavesRest)
{
  const auto& tf = graph.surfels[t];
  bool fits = tf.sign() * plane.normal[tf.axis()] > 0;
  for (int k = 0; k < 4 && fits; ++k)
    fits = plane.contains(graph.cornerOf(t, k));
  const std::uint32_t g = faceOf[t];
  return fits && meetsAlongOneArc(graph, faceOf, t, f, false) &&
    (!leavesRest || meetsAlongOneArc(graph, faceOf, t, g, true));
}

/// Ids a step goes over: those of a list, in increasing order, or all below `count`.
struct IdSet
{
  const std::vector<std::uint32_t>* list = nullptr;
  std::uint32_t count = 0;

  std::size_t size() const { return this->list ? this->list->size() : this->count; }
  std::uint32_t operator[](std::size_t i) const
  {
    return this->list ? (*this->list)[i] : static_cast<std::uint32_t>(i);
  }
};

/// A part of the boundary that the steps after the growth go over on its own: some boundary
/// components, their surfels (in increasing order) and their faces (in increasing number). No
/// step reads or writes the surfels, faces or vertices of another component, so the parts may
/// be run concurrently and give what one pass over the whole boundary gives.
struct Part
{
  IdSet surfels, faces;
};

/// Runs body(part, poll) over each part: a single part on the calling thread, reporting its
/// progress as [0, 1] of `exec`'s; several on the threads of `exec`, in waves of
/// `exec.concurrency` parts (the growth's groups: four waves), each part polling the abort
/// alone, the calling thread reporting the progress between the waves (VTK's progress belongs
/// to it), by the parts' surfels. False when stopped.
bool forEachPart(const Execution& exec,
  const std::vector<Part>& parts,
  const std::function<bool(const Part&, ProgressPoll&)>& body)
{
  if (parts.size() == 1)
  {
    ProgressPoll poll(exec, 0.0, 1.0);
    return body(parts[0], poll) && !poll.stopped();
  }
  const Execution quiet = exec.silent();
  const std::size_t wave = static_cast<std::size_t>(std::max(1, exec.concurrency));
  std::size_t all = 0, done = 0;
  for (const Part& part : parts)
    all += part.surfels.size();
  std::vector<char> finished(parts.size(), 0);
  for (std::size_t first = 0; first < parts.size(); first += wave)
  {
    const std::size_t end = std::min(parts.size(), first + wave);
    exec.forRange(static_cast<std::int64_t>(end - first),
      [&](std::int64_t b, std::int64_t e)
      {
        for (std::size_t p = first + b; p < first + e; ++p)
        {
          ProgressPoll poll(quiet, 0.0, 1.0);
          finished[p] = body(parts[p], poll) && !poll.stopped();
        }
      });
    for (std::size_t p = first; p < end; ++p)
      done += parts[p].surfels.size();
    if (std::find(finished.begin() + first, finished.begin() + end, 0) != finished.begin() + end ||
      exec.stopRequested() || !exec.report(double(done) / double(std::max<std::size_t>(all, 1))))
      return false;
  }
  return true;
}

/// The faces' surfel lists of a part after the moves (a surfel may have moved more than once),
/// each allocated to its size: faces that grew would double their storage. A list already of
/// its size (the growth makes them so; most faces keep theirs) is refilled in place.
void refillSurfelLists(const Part& part, const std::vector<std::size_t>& size, Polyhedron& poly)
{
  for (std::size_t i = 0; i < part.faces.size(); ++i)
  {
    StandardFace& face = poly.faces[part.faces[i]];
    face.surfels.clear();
    if (face.surfels.capacity() != size[part.faces[i]])
    {
      std::vector<std::uint32_t>().swap(face.surfels);
      face.surfels.reserve(size[part.faces[i]]);
    }
  }
  for (std::size_t i = 0; i < part.surfels.size(); ++i)
  {
    const std::uint32_t s = part.surfels[i];
    poly.faces[poly.faceOfSurfel[s]].surfels.push_back(s);
  }
}

/// The moves into the faces of one part (moveToLargerFaces), largest faces first (ties in the
/// order of their numbers, as over the whole boundary); returns the surfels moved.
std::size_t movesInPart(const SurfelGraph& graph,
  const Part& part,
  std::size_t maximumSize,
  std::vector<std::size_t>& size,
  std::vector<char>& shrunk,
  Polyhedron& poly,
  ProgressPoll& poll)
{
  std::vector<std::uint32_t> order(part.faces.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = part.faces[i];
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::uint32_t a, std::uint32_t b) { return size[a] > size[b]; });
  std::vector<std::uint32_t>& faceOf = poly.faceOfSurfel;
  std::vector<std::uint32_t> queue;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    const std::uint32_t f = order[i];
    poll.at(double(i) / double(order.size()));
    if (!poll.tick())
      return moved;
    prefetchFaces(
      poly,
      i,
      order.size(),
      [&](std::size_t at) { return order[at]; },
      [&](std::uint32_t s)
      {
        prefetchKept(&faceOf[s]);
        prefetchKept(&graph.neighbour[4 * std::size_t(s)]);
      });
    if (size[f] == 0)
      continue;
    StandardFace& face = poly.faces[f];
    queue.clear();
    // Only the surfels across f's rim: those already in f would be skipped when dequeued. The
    // lists and the candidates are read ahead (prefetch): a face's surfels lie rows of voxels
    // apart in the arrays, and these loads were the moves' cache misses.
    const std::vector<std::uint32_t>& list = face.surfels;
    for (std::size_t j = 0; j < list.size(); ++j)
    {
      if (j + PrefetchAhead < list.size())
      {
        prefetch(&faceOf[list[j + PrefetchAhead]]);
        prefetch(&graph.neighbour[4 * std::size_t(list[j + PrefetchAhead])]);
      }
      const std::uint32_t s = list[j];
      if (faceOf[s] == f)
        for (int k = 0; k < 4; ++k)
        {
          const std::uint32_t t = graph.neighbourOf(s, k);
          if (faceOf[t] != f)
          {
            queue.push_back(t);
            prefetch(&graph.surfels[t]);
          }
        }
    }
    for (std::size_t q = 0; q < queue.size(); ++q)
    {
      if (!poll.tick())
        return moved;
      const std::uint32_t t = queue[q];
      const std::uint32_t g = faceOf[t];
      if (g == f || size[g] >= size[f] || (maximumSize && size[f] >= maximumSize))
        continue;
      if (!surfelCanMove(graph, faceOf, t, f, face.plane, size[g] > 1))
        continue;
      faceOf[t] = f;
      shrunk[g] = 1;
      --size[g];
      ++size[f];
      ++moved;
      for (int k = 0; k < 4; ++k)
      {
        queue.push_back(graph.neighbourOf(t, k));
        prefetch(&graph.surfels[queue.back()]);
      }
    }
  }
  refillSurfelLists(part, size, poly);
  return moved;
}

/// Moves surfels from smaller faces to a larger neighbouring face, largest faces first,
/// when the larger face's plane takes them as it is and both faces stay disks (or the
/// smaller one empties).
/// The growth leaves the rim of a large face to whichever face reached it first; this gives
/// it back, and faces emptied this way disappear. Counts the surfels moved in
/// poly.movedSurfels, and marks the faces that gave surfels away in `shrunk`. The parts on the
/// threads of `exec` (a move never leaves a component); false when stopped.
bool moveToLargerFaces(const SurfelGraph& graph,
  const std::vector<Part>& parts,
  std::size_t maximumSize,
  const Execution& exec,
  Polyhedron& poly,
  std::vector<char>& shrunk)
{
  shrunk.assign(poly.faces.size(), 0);
  std::vector<std::size_t> size(poly.faces.size());
  for (std::size_t f = 0; f < size.size(); ++f)
    size[f] = poly.faces[f].surfels.size();
  std::vector<std::size_t> moved(parts.size(), 0);
  const bool done = forEachPart(exec,
    parts,
    [&](const Part& part, ProgressPoll& poll)
    {
      moved[&part - parts.data()] = movesInPart(graph, part, maximumSize, size, shrunk, poly, poll);
      return true;
    });
  for (std::size_t m : moved)
    poly.movedSurfels += m;
  return done;
}

/// Renumbers the faces left (those with surfels), in order, moving them down in place (a
/// second array of faces was the growth's peak on boundaries of small faces). The refusals the
/// growth stamped follow the numbers (the merging compares them with the faces it extends);
/// those of a face dropped, or of a face that gave surfels away (`shrunk`: its points no
/// longer hold those that refused), are forgotten.
void dropEmptyFaces(Polyhedron& poly,
  std::vector<std::uint32_t>& refused,
  const Execution& exec,
  const std::vector<char>& shrunk = {})
{
  std::vector<std::uint32_t> number(poly.faces.size(), None);
  std::uint32_t kept = 0;
  for (std::uint32_t f = 0; f < poly.faces.size(); ++f)
    if (!poly.faces[f].surfels.empty())
    {
      number[f] = kept;
      if (kept != f)
        poly.faces[kept] = std::move(poly.faces[f]);
      ++kept;
    }
  poly.faces.resize(kept);
  const std::int64_t n = static_cast<std::int64_t>(poly.faceOfSurfel.size());
  exec.forWork(n).forRange(n,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t s = b; s < e; ++s)
        poly.faceOfSurfel[s] = number[poly.faceOfSurfel[s]];
      if (refused.empty())
        return;
      for (std::int64_t s = b; s < e; ++s)
        if (refused[s] != None)
          refused[s] = !shrunk.empty() && shrunk[refused[s]] ? None : number[refused[s]];
    });
}

/// Faces around each vertex, from the loops: a face is a disk, so it meets the umbrella of a
/// vertex in one run, and when the vertex lies on its boundary its loop passes there once (the
/// tracer checks it: a second loop edge of the face from the vertex is an error). So a vertex
/// on the loops of k faces has k faces around it (k >= 2), and a vertex on no loop lies inside
/// one face: one. Francon & Papier's standard vertices are those of three faces or more. One
/// pass over the loops' vertices, instead of a walk round every umbrella.
void countFacesAtVertices(const SurfelGraph& graph, Polyhedron& poly)
{
  std::vector<std::uint8_t>& count = poly.facesAtVertex;
  count.assign(graph.vertexPointel.size(), 0);
  for (std::uint32_t v : poly.loopVertices)
    if (count[v] < 255)
      ++count[v];
  for (std::uint8_t& c : count)
    c = c == 0 ? 1 : c;
}

} // namespace

namespace
{

/// Surfels below which the growth stays on the calling thread (it takes a few microseconds a
/// surfel: below this, starting threads costs more than it saves).
constexpr std::size_t ParallelGrowthMinimum = 4096;

/// The boundary components dealt to groups that threads grow concurrently: the group of each
/// surfel, and the surfels of each group in increasing order (its seeds, met in the order of
/// the sequential growth).
struct ComponentGroups
{
  std::vector<std::uint32_t> groupOf;
  std::vector<std::vector<std::uint32_t>> seeds;
};

/// The components (depth first over the neighbours), dealt to `count` groups: the largest first,
/// each to the lightest group so far, so that the groups weigh about the same.
ComponentGroups groupComponents(const SurfelGraph& graph, std::size_t count)
{
  const std::uint32_t n = static_cast<std::uint32_t>(graph.size());
  ComponentGroups groups;
  std::vector<std::uint32_t>& label = groups.groupOf; // the component first, then its group
  label.assign(n, None);
  std::vector<std::uint32_t> sizes, stack;
  for (std::uint32_t s = 0; s < n; ++s)
  {
    if (label[s] != None)
      continue;
    const std::uint32_t c = static_cast<std::uint32_t>(sizes.size());
    std::uint32_t size = 0;
    label[s] = c;
    stack.push_back(s);
    while (!stack.empty())
    {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      ++size;
      for (int k = 0; k < 4; ++k)
      {
        const std::uint32_t t = graph.neighbourOf(u, k);
        if (label[t] == None)
        {
          label[t] = c;
          stack.push_back(t);
        }
      }
    }
    sizes.push_back(size);
  }
  std::vector<std::uint32_t> order(sizes.size());
  for (std::uint32_t c = 0; c < order.size(); ++c)
    order[c] = c;
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::uint32_t a, std::uint32_t b) { return sizes[a] > sizes[b]; });
  std::vector<std::uint64_t> weight(count, 0);
  std::vector<std::uint32_t> groupOfComponent(sizes.size());
  for (std::uint32_t c : order)
  {
    const auto lightest = std::min_element(weight.begin(), weight.end()) - weight.begin();
    groupOfComponent[c] = static_cast<std::uint32_t>(lightest);
    weight[lightest] += sizes[c];
  }
  groups.seeds.resize(count);
  for (std::size_t g = 0; g < count; ++g)
    groups.seeds[g].reserve(weight[g]);
  for (std::uint32_t s = 0; s < n; ++s)
  {
    label[s] = groupOfComponent[label[s]];
    groups.seeds[label[s]].push_back(s);
  }
  return groups;
}

/// The growth of each group of components on its own, concurrently, into `grown` (its faces
/// numbered from 0 in the stamps). The groups run in waves of `exec.concurrency`, between which
/// the calling thread reports the progress (the workers only poll the abort). False when
/// aborted.
bool growGroupsInWaves(const SurfelGraph& graph,
  const PolyhedrizationOptions& options,
  const Execution& exec,
  const ComponentGroups& groups,
  SurfelStamps& stamps,
  std::vector<std::vector<StandardFace>>& grown)
{
  const std::size_t count = groups.seeds.size();
  const std::size_t wave = static_cast<std::size_t>(std::max(1, exec.concurrency));
  grown.assign(count, {});
  std::vector<char> finished(count, 0);
  Execution quiet = exec;
  quiet.progress = nullptr;
  std::size_t done = 0;
  for (std::size_t first = 0; first < count; first += wave)
  {
    const std::size_t end = std::min(count, first + wave);
    exec.forRange(static_cast<std::int64_t>(end - first),
      [&](std::int64_t b, std::int64_t e)
      {
        for (std::size_t g = first + b; g < first + e; ++g)
        {
          grown[g].reserve(groups.seeds[g].size() / 4 + 16);
          FaceGrower grower(graph, options, grown[g], stamps);
          ProgressPoll poll(quiet, 0.0, 0.6);
          grower.watch(poll);
          finished[g] = grower.run(groups.seeds[g]);
        }
      });
    for (std::size_t g = first; g < end; ++g)
      done += groups.seeds[g].size();
    // A group of fewer surfels than the poll's period never polls: ask here too.
    if (std::find(finished.begin() + first, finished.begin() + end, 0) != finished.begin() + end ||
      exec.stopRequested() || !exec.report(0.6 * double(done) / double(graph.size())))
      return false;
  }
  return true;
}

/// The faces of all groups into `faces` in the order of their seeds (the sequential growth's
/// order: faces start from the free surfels in increasing order, and a face never leaves its
/// component); returns, per group, the number each of its faces gets.
std::vector<std::vector<std::uint32_t>> gatherInSeedOrder(const SurfelGraph& graph,
  const ComponentGroups& groups,
  std::vector<std::vector<StandardFace>>& grown,
  std::vector<StandardFace>& faces)
{
  const std::size_t count = groups.seeds.size();
  std::vector<std::vector<std::uint32_t>> number(count);
  std::size_t total = 0;
  for (std::size_t g = 0; g < count; ++g)
  {
    number[g].resize(grown[g].size());
    total += grown[g].size();
  }
  faces.reserve(total);
  std::vector<std::size_t> next(count, 0);
  for (std::uint32_t s = 0; s < graph.size(); ++s)
  {
    const std::uint32_t g = groups.groupOf[s];
    const std::size_t i = next[g];
    if (i < grown[g].size() && grown[g][i].surfels.front() == s) // a face's seed comes first
    {
      number[g][i] = static_cast<std::uint32_t>(faces.size());
      faces.push_back(std::move(grown[g][i]));
      ++next[g];
    }
  }
  return number;
}

/// The growth of the groups (growGroupsInWaves), then all the faces in the order of their
/// seeds (gatherInSeedOrder), with the face stamps renumbered to match (the per-vertex stamps are
/// freed before they would be read again). Same faces, same numbers,
/// same refusals as the sequential growth.
bool growGroups(const SurfelGraph& graph,
  const PolyhedrizationOptions& options,
  const Execution& exec,
  const ComponentGroups& groups,
  SurfelStamps& stamps,
  std::vector<StandardFace>& faces)
{
  std::vector<std::vector<StandardFace>> grown;
  if (!growGroupsInWaves(graph, options, exec, groups, stamps, grown))
    return false;
  const std::vector<std::vector<std::uint32_t>> number =
    gatherInSeedOrder(graph, groups, grown, faces);
  exec.forWork(static_cast<std::int64_t>(graph.size()))
    .forRange(static_cast<std::int64_t>(graph.size()),
      [&](std::int64_t b, std::int64_t e)
      {
        for (std::int64_t s = b; s < e; ++s)
        {
          const std::vector<std::uint32_t>& to = number[groups.groupOf[s]];
          stamps.faceOf[s] = to[stamps.faceOf[s]];
          if (stamps.refused[s] != None)
            stamps.refused[s] = to[stamps.refused[s]];
        }
      });
  return true;
}

/// The growth of all the faces (progress 0 - 0.6): the boundary components on the threads of
/// `exec` when there are several and enough surfels, else on the calling thread, with the same
/// faces either way; `groups` receives the groups the threads grew (none on one thread), for the
/// later steps. False when aborted.
bool growFaces(const SurfelGraph& graph,
  const PolyhedrizationOptions& options,
  const Execution& exec,
  SurfelStamps& stamps,
  std::vector<StandardFace>& faces,
  ComponentGroups& groups)
{
  const bool threaded = exec.parallelFor && exec.concurrency > 1 && graph.componentCount > 1 &&
    graph.size() >= ParallelGrowthMinimum;
  if (threaded)
  {
    // Four waves of groups, for the progress between them.
    const std::size_t count =
      std::min<std::size_t>(graph.componentCount, 4 * static_cast<std::size_t>(exec.concurrency));
    groups = groupComponents(graph, count);
    return growGroups(graph, options, exec, groups, stamps, faces);
  }
  else
  {
    std::vector<std::uint32_t> seeds(graph.size());
    for (std::uint32_t s = 0; s < seeds.size(); ++s)
      seeds[s] = s;
    // Room for faces of 4 surfels on average (noise makes 7, a checkerboard 3): pages not
    // reached are never touched, and each doubling past it copies every face.
    faces.reserve(graph.size() / 4 + 16);
    FaceGrower grower(graph, options, faces, stamps);
    ProgressPoll growth(exec, 0.0, 0.6);
    grower.watch(growth);
    return grower.run(seeds);
  }
}

/// The merging pass, smallest faces first: each is handed to its neighbours when they can
/// take it whole. Returns false when stopped.
bool mergeSmallFaces(FaceGrower& grower,
  const PolyhedrizationOptions& options,
  const Execution& exec,
  Polyhedron& out,
  ProgressPoll& poll)
{
  std::vector<std::uint32_t> order(out.faces.size());
  for (std::uint32_t f = 0; f < order.size(); ++f)
    order[f] = f;
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::uint32_t a, std::uint32_t b)
    { return out.faces[a].surfels.size() < out.faces[b].surfels.size(); });
  grower.watch(poll);
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    poll.at(double(i) / double(order.size()));
    if (!poll.tick())
      return false;
    const std::size_t size = out.faces[order[i]].surfels.size();
    if (size == 0 || size > options.mergeFacesUpTo)
      continue; // faces grow as they take others: the order is only a start
    out.mergedFaces += grower.absorb(order[i]);
    if (poll.stopped())
      return false;
  }
  grower.releaseCache();
  std::vector<std::uint32_t> noRefusals; // none are read after the merging
  dropEmptyFaces(out, noRefusals, exec);
  return true;
}

/// The parts of the boundary that the steps after the growth go over: the groups the threads
/// grew, with their faces (`faceLists`, in increasing number, receives them; the parts point
/// into it), or the whole boundary as one part.
std::vector<Part> partsOf(const ComponentGroups& groups,
  const Polyhedron& poly,
  std::vector<std::vector<std::uint32_t>>& faceLists)
{
  if (groups.seeds.empty())
    return { Part{ { nullptr, static_cast<std::uint32_t>(poly.faceOfSurfel.size()) },
      { nullptr, static_cast<std::uint32_t>(poly.faces.size()) } } };
  faceLists.assign(groups.seeds.size(), {});
  for (std::uint32_t f = 0; f < poly.faces.size(); ++f)
    if (!poly.faces[f].surfels.empty()) // a face never leaves the group of its first surfel
      faceLists[groups.groupOf[poly.faces[f].surfels.front()]].push_back(f);
  std::vector<Part> parts(groups.seeds.size());
  for (std::size_t g = 0; g < parts.size(); ++g)
    parts[g] = { { &groups.seeds[g], 0 }, { &faceLists[g], 0 } };
  return parts;
}

/// Every face's loop, into the arrays of `out` in face order: first each loop's length, then
/// the loops traced into their runs; the parts (of faces only) on the threads of `exec`. The
/// tracer's arrays are freed on return. False when stopped.
bool traceLoops(const SurfelGraph& graph,
  bool across,
  const std::vector<Part>& parts,
  const Execution& exec,
  Polyhedron& out)
{
  LoopTracer tracer(graph, across);
  std::vector<std::size_t> lengths(out.faces.size()), first(out.faces.size());
  // Both steps read each surfel's neighbours and the faces beyond; the second its vertices too.
  auto overFaces = [&](const Execution& e, bool vertices, auto step)
  {
    return forEachPart(e,
      parts,
      [&](const Part& part, ProgressPoll& poll)
      {
        for (std::size_t i = 0; i < part.faces.size(); ++i)
        {
          poll.at(double(i) / double(part.faces.size()));
          if (!poll.tick())
            return false;
          prefetchFaces(
            out,
            i,
            part.faces.size(),
            [&](std::size_t at) { return part.faces[at]; },
            [&](std::uint32_t s)
            {
              prefetchKept(&graph.neighbour[4 * std::size_t(s)]);
              if (vertices)
                prefetchKept(&graph.vertex[4 * std::size_t(s)]);
            });
          step(part.faces[i]);
        }
        return true;
      });
  };
  if (!overFaces(exec.within(0.0, 0.2),
        false,
        [&](std::uint32_t f) { lengths[f] = tracer.loopLength(out, f); }))
    return false;
  std::size_t edges = 0;
  for (std::size_t f = 0; f < lengths.size(); ++f)
  {
    first[f] = edges;
    edges += lengths[f];
  }
  out.loopVertices.resize(edges);
  out.loopAcross.resize(across ? edges : 0);
  if (!overFaces(exec.within(0.2, 1.0),
        true,
        [&](std::uint32_t f)
        {
          tracer.trace(out,
            f,
            lengths[f],
            out.loopVertices.data() + first[f],
            across ? out.loopAcross.data() + first[f] : nullptr);
        }))
    return false;
  LoopTracer::pointLoops(out, lengths);
  return true;
}

} // namespace

bool polyhedrize(const SurfelGraph& graph,
  const PolyhedrizationOptions& options,
  const Execution& exec,
  Polyhedron& out)
{
  // Progress: growth 0 - 0.6, moves 0.6 - 0.7, merging 0.7 - 0.95, loops 0.95 - 1.
  out = Polyhedron();
  SurfelStamps stamps(out.faceOfSurfel, graph.size(), graph.vertexPointel.size());
  ComponentGroups groups;
  if (!growFaces(graph, options, exec, stamps, out.faces, groups))
    return false;
  stamps.releaseTouching();
  std::vector<std::vector<std::uint32_t>> faceLists;
  if (options.moveToLargerFaces)
  {
    std::vector<char> shrunk;
    if (!moveToLargerFaces(graph,
          partsOf(groups, out, faceLists),
          options.maximumFaceSize,
          exec.within(0.6, 0.7),
          out,
          shrunk))
      return false;
    dropEmptyFaces(out, stamps.refused, exec, shrunk);
  }
  ProgressPoll merging(exec, 0.7, 0.95);
  if (options.mergeFaces)
  {
    // A grower of its own: it reads only the refusals the growth left in the stamps.
    FaceGrower merger(graph, options, out.faces, stamps);
    if (!mergeSmallFaces(merger, options, exec, out, merging))
      return false;
  }
  // The loops go over the parts' faces alone: the groups are freed.
  std::vector<Part> parts = partsOf(groups, out, faceLists);
  for (Part& part : parts)
    part.surfels = {};
  groups = ComponentGroups();
  stamps.releaseQueues(); // the peak is the loops' tracing, with the whole graph
  if (!traceLoops(graph, options.facesAcross, parts, exec.within(0.95, 1.0), out))
    return false;
  countFacesAtVertices(graph, out);
  return exec.report(1.0);
}

// ---- reversion ------------------------------------------------------------------------

namespace
{

/// The surfels of a standard plane, with its constants computed once per face: the boundary of
/// the digital half-space below it (the voxels whose centre c has n.c < mu + omega / 2, i.e.
/// 2 n.v < 2 mu + omega - (a + b + c) for the lower corner v).
class PlaneSurfels
{
public:
  explicit PlaneSurfels(const StandardPlane& plane)
    : Normal(plane.normal)
    , Bound(2 * plane.mu + plane.omega() - plane.normal[0] - plane.normal[1] - plane.normal[2])
  {
  }

  /// A square on the left of a unit step p -> q that may be a surfel of the plane: its inner
  /// voxel (the one below the plane if it is one), its direction, and 2 |n_d| (n.v grows by
  /// |n_d| from the inner voxel to the outer one).
  struct Candidate
  {
    Point3 inner;
    std::uint8_t direction;
    std::int64_t twiceStep;
  };

  /// The squares on the left of the step p -> q, one per axis d across the step with n_d != 0
  /// (at most two); returns how many.
  int candidatesLeftOf(const Point3& p, const Point3& q, Candidate out[2]) const
  {
    const Point3 t = sub(q, p);
    const int along = directionOf(t) >> 1;
    int count = 0;
    for (int d = 0; d < 3; ++d)
    {
      if (d == along || this->Normal[d] == 0)
        continue;
      Point3 normal{ 0, 0, 0 };
      normal[d] = this->Normal[d] > 0 ? 1 : -1;
      const Point3 left = cross(normal, t);
      // Lower corner of the square p, q, q + left, p + left; its inner voxel.
      Point3 inner;
      for (int i = 0; i < 3; ++i)
        inner[i] = std::min(std::min(p[i], q[i]), std::min(p[i], q[i]) + left[i]);
      if (normal[d] > 0)
        --inner[d];
      out[count++] = { inner,
        static_cast<std::uint8_t>(2 * d + (normal[d] > 0 ? 1 : 0)),
        2 * std::llabs(this->Normal[d]) };
    }
    return count;
  }

  /// Whether a candidate whose inner voxel has n.v = `value` is a surfel of the plane: its
  /// inner voxel below the plane and its outer one not.
  bool takes(std::int64_t value, std::int64_t twiceStep) const
  {
    const std::int64_t twice = 2 * value;
    return twice < this->Bound && twice + twiceStep >= this->Bound;
  }

  /// The surfel of the plane whose counter-clockwise boundary runs p -> q (a unit step), if
  /// any: of the two squares on the left of the step, the one whose inner voxel is below the
  /// plane and whose outer voxel is not.
  bool leftOf(const Point3& p, const Point3& q, Surfel& out) const
  {
    Candidate c[2];
    const int count = this->candidatesLeftOf(p, q, c);
    int found = 0;
    for (int i = 0; i < count; ++i)
      if (this->takes(this->value(c[i].inner), c[i].twiceStep))
      {
        out = { c[i].inner, c[i].direction };
        ++found;
      }
    return found == 1;
  }

  /// Whether surfels of direction d may be squares of the plane (s n_a > 0): leftOf finds
  /// no others.
  bool facesOut(int d) const
  {
    const std::int64_t n = this->Normal[d >> 1];
    return (d & 1) ? n > 0 : n < 0;
  }

  std::int64_t value(const Point3& v) const
  {
    return this->Normal[0] * v[0] + this->Normal[1] * v[1] + this->Normal[2] * v[2];
  }

private:
  std::array<std::int64_t, 3> Normal;
  std::int64_t Bound; ///< 2 n.v below this: the voxel with lower corner v is below the plane
};

} // namespace

namespace
{

std::string faceError(std::size_t f, const char* what)
{
  std::ostringstream msg;
  msg << "face " << f << ": " << what;
  return msg.str();
}

/// A set of surfels whose voxels lie in the grid: one bit per voxel and direction (6 bits per
/// voxel), in place of a list of every surfel and its sort (32 bytes per surfel, most of the
/// reversion's memory on boundaries with many surfels per voxel).
class SurfelBits
{
public:
  explicit SurfelBits(const std::array<std::int32_t, 3>& dims)
  {
    for (BitVolume& b : this->Bits)
      b = BitVolume(dims[0], dims[1], dims[2]);
  }

  bool get(const Surfel& s) const
  {
    return this->Bits[s.direction].get(s.voxel[0], s.voxel[1], s.voxel[2]);
  }
  /// Sets s; whether it was set already.
  bool testAndSet(const Surfel& s)
  {
    Word& w = this->Bits[s.direction].row(s.voxel[1], s.voxel[2])[s.voxel[0] >> 6];
    const Word bit = Word(1) << (s.voxel[0] & 63);
    const bool was = (w & bit) != 0;
    w |= bit;
    return was;
  }
  void set(const Surfel& s, bool value = true)
  {
    this->Bits[s.direction].set(s.voxel[0], s.voxel[1], s.voxel[2], value);
  }
  const BitVolume& direction(int d) const { return this->Bits[d]; }

private:
  std::array<BitVolume, 6> Bits;
};

/// A point projected along a plane's sign vector (FaceMarks).
using UV = std::array<std::int64_t, 2>;

UV plus(const UV& a, const UV& b)
{
  return { a[0] + b[0], a[1] + b[1] };
}

/// The signs of a normal as FaceMarks projects along them (0 counted positive).
std::array<int, 3> projectionSigns(const std::array<std::int64_t, 3>& normal)
{
  return { normal[0] < 0 ? -1 : 1, normal[1] < 0 ? -1 : 1, normal[2] < 0 ? -1 : 1 };
}

/// A point projected along the sign vector `sign` (FaceMarks).
UV projectAlong(const std::array<int, 3>& sign, const Point3& p)
{
  const std::int64_t w = sign[2] * std::int64_t(p[2]);
  return { sign[0] * std::int64_t(p[0]) - w, sign[1] * std::int64_t(p[1]) - w };
}

/// Key of a surfel whose voxel lies in the grid (coordinates below 2^20): 63 bits.
std::uint64_t surfelKey(const Surfel& s)
{
  const Point3& v = s.voxel;
  return ((((std::uint64_t(v[2]) << 20) | std::uint64_t(v[1])) << 20 | std::uint64_t(v[0])) << 3) |
    s.direction;
}

/// The surfels of the face being filled and the edges of its loop, marked in a 2D array. A
/// standard plane's surfels bound the digital half-space below it, which is closed under the
/// steps -sign(n_i) e_i: they form a stepped surface that meets every line along s = (sign
/// a, sign b, sign c) once (0 counted positive), so projected along s they tile the plane and
/// no two of its points share a projection. A surfel of the plane is then known by its axis
/// and the projection of its lowest corner, a directed linel of it by its direction and the
/// projection of its start. The array covers the projection of the loop (where a disk's
/// surfels lie) within the grid's; surfels outside it (an outline that bounds no disk, which
/// the flood reports) go to a hash index. The marked cells are cleared after each face, so a
/// face costs its surfels, not its box.
///
/// The box can be far larger than the face: a thin diagonal strip of length L has about L
/// surfels in an L x L box. Each surfel projects to a parallelogram of area 1 and they tile
/// the loop's projection, so the loop's shoelace area counts the face's surfels before they are
/// filled. A box of more than 8 cells per surfel (or per loop edge, for loops that enclose
/// little, and 64 cells for the smallest faces) is not allocated: its surfels and loop edges
/// all go to the hash indexes. 8 cells of 2 bytes are the size of a surfel in the face's list
/// of them, so the array never outweighs that list, while a face that fills an eighth of its
/// box (rectangles, discs, any face about as wide as it is long) keeps the array's cheaper
/// marks. Either way a surfel and a linel are keyed by the same things (the array's cell is
/// the projection), so the faces filled are the same.
class FaceMarks
{
public:
  explicit FaceMarks(const std::array<std::int32_t, 3>& dims)
    : Dims(dims)
  {
  }

  /// Starts a face of `plane` bounded by `loop`: nothing marked.
  void begin(const StandardPlane& plane, const std::vector<Point3>& loop)
  {
    for (std::size_t cell : this->Touched)
      this->Marks[cell] = 0;
    this->Touched.clear();
    // Most faces hash nothing: clearing an empty index would still sweep its table (kept up to
    // 4096 slots once a large face grew it).
    if (this->Outside.size() != 0)
      this->Outside.clear();
    if (this->OutsideEdges.size() != 0)
      this->OutsideEdges.clear();
    this->Sign = projectionSigns(plane.normal);
    std::array<std::int64_t, 2> lo{ 0, 0 }, hi{ -1, -1 };
    std::int64_t twiceArea = 0; // the shoelace sum of the loop's projection
    std::array<std::int64_t, 2> last = loop.empty() ? lo : this->project(loop.back());
    for (std::size_t i = 0; i < loop.size(); ++i)
    {
      const std::array<std::int64_t, 2> uv = this->project(loop[i]);
      twiceArea += last[0] * uv[1] - uv[0] * last[1];
      last = uv;
      for (int j = 0; j < 2; ++j)
      {
        lo[j] = i == 0 ? uv[j] : std::min(lo[j], uv[j]);
        hi[j] = i == 0 ? uv[j] : std::max(hi[j], uv[j]);
      }
    }
    // Lowest corners of surfels of the grid project within the projection of [0, dims]^3.
    for (int j = 0; j < 2; ++j)
    {
      const std::int64_t a = this->Sign[j] * std::int64_t(this->Dims[j]);
      const std::int64_t c = this->Sign[2] * std::int64_t(this->Dims[2]);
      lo[j] = std::max(lo[j], std::min<std::int64_t>(0, a) - std::max<std::int64_t>(0, c));
      hi[j] = std::min(hi[j], std::max<std::int64_t>(0, a) - std::min<std::int64_t>(0, c));
    }
    this->Low = lo;
    this->Width = std::max<std::int64_t>(0, hi[0] - lo[0] + 1);
    this->Height = std::max<std::int64_t>(0, hi[1] - lo[1] + 1);
    const std::uint64_t surfels = std::uint64_t(twiceArea < 0 ? -twiceArea : twiceArea) / 2;
    if (!arrayPays(std::uint64_t(this->Width) * std::uint64_t(this->Height), surfels, loop.size()))
      this->Width = this->Height = 0; // every cell "outside": all hashed
    const std::size_t cells = static_cast<std::size_t>(this->Width * this->Height);
    if (this->Marks.size() < cells)
      this->Marks.resize(cells, 0);
  }

  /// The projection of a point along the plane's sign vector (the array's coordinates before
  /// the shift by Low). Linear: the flood projects a surfel's voxel and adds its steps'.
  UV project(const Point3& p) const { return projectAlong(this->Sign, p); }

  /// Marks surfel s of the plane (its voxel in the grid) whose lowest corner projects to
  /// `lowest`; false when it was marked already.
  bool markSurfel(const Surfel& s, const UV& lowest)
  {
    std::size_t cell = 0;
    if (!this->cellOf(lowest, cell))
      return this->Outside.insert(surfelKey(s)).second;
    return this->mark(cell, 1u << s.axis());
  }

  /// Marks the loop edge of `direction` from the point projected to `uv` (a linel of a
  /// surfel of the plane in the grid).
  void markLoopEdge(const UV& uv, int direction)
  {
    std::size_t cell = 0;
    if (this->cellOf(uv, cell))
      this->mark(cell, 8u << direction);
    else
      this->OutsideEdges.insert(this->edgeKey(uv, direction));
  }

  /// Whether the linel of `direction` from the point projected to `from`, a linel of a surfel
  /// of the plane in the grid, is a loop edge or was crossed already (markCrossed).
  bool isLoopEdgeOrCrossed(const UV& from, int direction) const
  {
    std::size_t cell = 0;
    if (this->cellOf(from, cell))
      return this->Marks[cell] & (0x208u << direction);
    return this->OutsideEdges.size() != 0 &&
      this->OutsideEdges.find(this->edgeKey(from, direction)) >= 0;
  }

  /// Marks the linel of `direction` from the point projected to `from` as crossed: the flood
  /// came into its surfel across it, so crossing it back from there would find a surfel
  /// already filled (only within the array; outside it the linel is crossed back).
  void markCrossed(const UV& from, int direction)
  {
    std::size_t cell = 0;
    if (this->cellOf(from, cell))
      this->mark(cell, 0x200u << direction);
  }

  /// Whether a face of `surfels` (its loop's shoelace area) and `loopEdges` is marked in an
  /// array of `boxCells` cells, not in the hash indexes (see the class comment for the 8).
  static bool arrayPays(std::uint64_t boxCells, std::uint64_t surfels, std::size_t loopEdges)
  {
    return boxCells <= 8 * std::max<std::uint64_t>(surfels, loopEdges) + 64;
  }

  /// The cells of the array of the face begun last (0 when it is all hashed).
  std::size_t arrayCells() const { return static_cast<std::size_t>(this->Width * this->Height); }

private:
  bool mark(std::size_t cell, unsigned bit)
  {
    std::uint16_t& marks = this->Marks[cell];
    if (marks & bit)
      return false;
    if (!marks)
      this->Touched.push_back(cell);
    marks = static_cast<std::uint16_t>(marks | bit);
    return true;
  }

  /// A linel by the projection of its start and its direction, as the array keys it:
  /// projections lie within +-2^21 (coordinates below 2^20), shifted to 23 bits each.
  static std::uint64_t edgeKey(const UV& uv, int direction)
  {
    const std::uint64_t u = std::uint64_t(uv[0] + (std::int64_t(1) << 22));
    const std::uint64_t v = std::uint64_t(uv[1] + (std::int64_t(1) << 22));
    return (((u << 23) | v) << 3) | std::uint64_t(direction);
  }

  bool cellOf(const UV& uv, std::size_t& cell) const
  {
    // A negative u or v wraps to more than any width or height (both below 2^63): one test
    // for each side of the array (three calls per step of the flood).
    const auto u = static_cast<std::uint64_t>(uv[0] - this->Low[0]);
    const auto v = static_cast<std::uint64_t>(uv[1] - this->Low[1]);
    if (u >= static_cast<std::uint64_t>(this->Width) ||
      v >= static_cast<std::uint64_t>(this->Height))
      return false;
    cell = static_cast<std::size_t>(v * static_cast<std::uint64_t>(this->Width) + u);
    return true;
  }

  std::array<std::int32_t, 3> Dims;
  std::array<int, 3> Sign{ 1, 1, 1 };
  std::array<std::int64_t, 2> Low{ 0, 0 };
  std::int64_t Width = 0, Height = 0;
  /// Per cell: bit a, a surfel of axis a; bit 3 + d, a loop edge of direction d; bit 9 + d,
  /// a linel of direction d crossed by the flood.
  std::vector<std::uint16_t> Marks;
  std::vector<std::size_t> Touched; ///< the cells marked for this face
  GridPointIndex Outside;           ///< keys of the face's surfels outside the array
  GridPointIndex OutsideEdges;      ///< keys of the loop edges outside the array (edgeKey)
};

/// The flood's steps (FaceFiller) for the planes of one sign pattern of the normal (each n_i
/// negative, zero or positive), relative to a surfel's voxel: what PlaneSurfels::candidatesLeftOf
/// and FaceMarks' projection give, which depend on the signs alone. Made once per pattern, so
/// that a face sets up only the values n.v of its candidates (small faces are most faces).
struct FloodGeometry
{
  /// The step across edge k (corner k to k + 1) of a surfel of direction d: the projections
  /// of the edge's ends, its direction both ways, and the squares on the left of the step
  /// back, with the shift of each one's voxel's projection; or (loop) the squares on the left
  /// of a loop edge of direction d, relative to its start.
  struct Step
  {
    UV from{ 0, 0 }, to{ 0, 0 };   ///< corners k and k + 1 projected
    int forward = 0, backward = 0; ///< directions of k -> k + 1 and k + 1 -> k
    int count = 0;
    PlaneSurfels::Candidate candidate[2];
    UV shift[2];
  };
  Step steps[6][4];
  Step loop[6];
  UV lowestShift[6]; ///< the projection of a surfel's lowest corner less its voxel's

  explicit FloodGeometry(const std::array<std::int64_t, 3>& signs)
  {
    StandardPlane unit;
    unit.normal = signs;
    const PlaneSurfels plane(unit);
    const std::array<int, 3> sign = projectionSigns(signs);
    auto shifts = [&](Step& step)
    {
      for (int i = 0; i < step.count; ++i)
        step.shift[i] = projectAlong(sign, step.candidate[i].inner);
    };
    for (int d = 0; d < 6; ++d)
    {
      const Surfel origin{ { 0, 0, 0 }, static_cast<std::uint8_t>(d) };
      Point3 lowest{ 0, 0, 0 };
      lowest[origin.axis()] += d & 1;
      this->lowestShift[d] = projectAlong(sign, lowest);
      for (int k = 0; k < 4; ++k)
      {
        Step& step = this->steps[d][k];
        const Point3 a = origin.corner(k), b = origin.corner((k + 1) & 3);
        step.from = projectAlong(sign, a);
        step.to = projectAlong(sign, b);
        step.forward = directionOf(sub(b, a));
        step.backward = directionOf(sub(a, b));
        step.count = plane.candidatesLeftOf(b, a, step.candidate);
        shifts(step);
      }
      Step& step = this->loop[d];
      step.forward = d;
      step.count = plane.candidatesLeftOf({ 0, 0, 0 }, unitVector(d), step.candidate);
      shifts(step);
    }
  }

  /// The geometry of the sign pattern of `normal`.
  static const FloodGeometry& of(const std::array<std::int64_t, 3>& normal)
  {
    static const std::vector<FloodGeometry> patterns = []
    {
      std::vector<FloodGeometry> all;
      for (int p = 0; p < 27; ++p)
        all.emplace_back(std::array<std::int64_t, 3>{ p % 3 - 1, p / 3 % 3 - 1, p / 9 - 1 });
      return all;
    }();
    auto sign = [](std::int64_t x) { return x < 0 ? 0 : x == 0 ? 1 : 2; };
    return patterns[sign(normal[0]) + 3 * sign(normal[1]) + 9 * sign(normal[2])];
  }
};

/// The filling of the faces, one after the other: the surfels of every face filled so far
/// (All, bits over the grid) and of the face being filled (Face, marks in the plane of its
/// projection, so that the grid needs one set of bits, not two).
class FaceFiller
{
public:
  /// With `keepAll` false, faces are filled one by one and forgotten (no bits over the grid).
  explicit FaceFiller(const std::array<std::int32_t, 3>& dims, bool keepAll = true)
    : Dims(dims)
    , All(keepAll ? dims : std::array<std::int32_t, 3>{ 0, 0, 0 })
    , KeepAll(keepAll)
    , Face(dims)
  {
  }

  /// The surfels of face f: the squares of its plane enclosed by its loop, filled from the
  /// loop's edges across every linel that is not a loop edge. Adds them to All.
  std::string fill(const FaceOutline& face, std::size_t f)
  {
    const std::size_t n = face.loop.size();
    this->Visited.clear();
    this->FaceSurfels = 0;
    this->Stack.clear();
    this->Face.begin(face.plane, face.loop);
    const PlaneSurfels plane(face.plane);
    this->prepareSteps(plane, face.plane);
    const char* error = this->seedFromLoop(face, plane);
    if (!error)
      error = this->flood(plane, 8 * n * n + 64);
    this->Count += this->FaceSurfels;
    if (error == SharedSurfels)
      return "face " + std::to_string(f) + " " + SharedSurfels;
    return error ? faceError(f, error) : std::string();
  }

  /// Surfels filled in all.
  std::size_t count() const { return this->Count; }
  /// The surfels of the last face filled (kept only without keepAll).
  const std::vector<Surfel>& lastFace() const { return this->Visited; }
  const SurfelBits& surfels() const { return this->All; }

private:
  static constexpr const char* SharedSurfels =
    "shares surfels with an earlier face (is a face given twice?)";

  /// A surfel of the face to flood from, with the projection of its voxel (FaceMarks) and
  /// the plane's value n.v at its voxel, which its steps shift by constants (Step).
  struct Entry
  {
    Surfel surfel;
    UV voxel;
    std::int64_t value;
  };

  /// The face's values n.v of the candidates of its geometry's steps (relative to the
  /// surfel's voxel, or to the loop edge's start), for the directions of its surfels (s n_a >
  /// 0), and 2 |n_a| per axis (PlaneSurfels::Candidate::twiceStep for the face's plane).
  void prepareSteps(const PlaneSurfels& plane, const StandardPlane& facePlane)
  {
    const FloodGeometry& g = FloodGeometry::of(facePlane.normal);
    this->Geometry = &g;
    for (int a = 0; a < 3; ++a)
      this->TwiceStep[a] = 2 * std::llabs(facePlane.normal[a]);
    for (int d = 0; d < 6; ++d)
    {
      if (plane.facesOut(d)) // else no surfel of the plane has this direction
        for (int k = 0; k < 4; ++k)
          for (int i = 0; i < g.steps[d][k].count; ++i)
            this->ValueShift[d][k][i] = plane.value(g.steps[d][k].candidate[i].inner);
      for (int i = 0; i < g.loop[d].count; ++i)
        this->LoopValueShift[d][i] = plane.value(g.loop[d].candidate[i].inner);
    }
  }

  /// The square a step finds, of the candidates with n.v = value + shift: the only one the
  /// plane takes (PlaneSurfels::leftOf), or -1.
  int stepTarget(const PlaneSurfels& plane,
    const FloodGeometry::Step& step,
    std::int64_t value,
    const std::int64_t* shift) const
  {
    int found = 0, which = -1;
    for (int i = 0; i < step.count; ++i)
      if (plane.takes(value + shift[i], this->TwiceStep[step.candidate[i].direction >> 1]))
        ++found, which = i;
    return found == 1 ? which : -1;
  }

  /// Visits surfel s of the face once: marked and stacked; an error when it lies outside
  /// the grid or in an earlier face. `voxel` and `value` are its Entry's.
  const char* visit(const Surfel& s, const UV& voxel, std::int64_t value)
  {
    const Point3& v = s.voxel;
    // A negative coordinate wraps to more than any size (below 2^31): one test per axis.
    if (static_cast<std::uint32_t>(v[0]) >= static_cast<std::uint32_t>(this->Dims[0]) ||
      static_cast<std::uint32_t>(v[1]) >= static_cast<std::uint32_t>(this->Dims[1]) ||
      static_cast<std::uint32_t>(v[2]) >= static_cast<std::uint32_t>(this->Dims[2]))
      return "it leaves the grid (the faces do not bound a set of voxels of it)";
    if (!this->Face.markSurfel(s, plus(voxel, this->Geometry->lowestShift[s.direction])))
      return nullptr; // seen in this face
    // All keeps the face's surfels as they come (a surfel is visited once per face).
    if (this->KeepAll && this->All.testAndSet(s))
      return SharedSurfels;
    ++this->FaceSurfels;
    if (!this->KeepAll)
      this->Visited.push_back(s);
    this->Stack.push_back({ s, voxel, value });
    return nullptr;
  }

  /// The surfels of the plane on the left of the loop's edges: where the filling starts.
  const char* seedFromLoop(const FaceOutline& face, const PlaneSurfels& plane)
  {
    const std::size_t n = face.loop.size();
    for (std::size_t i = 0; i < n; ++i)
    {
      const Point3& p = face.loop[i];
      const Point3& q = face.loop[i + 1 == n ? 0 : i + 1];
      const Point3 t = sub(q, p);
      // The square on the left of p -> q, as PlaneSurfels::leftOf(p, q) finds it.
      const bool unit = std::abs(t[0]) + std::abs(t[1]) + std::abs(t[2]) == 1;
      const int direction = unit ? directionOf(t) : 0;
      const FloodGeometry::Step& step = this->Geometry->loop[direction];
      const std::int64_t value = plane.value(p);
      const int which =
        unit ? this->stepTarget(plane, step, value, this->LoopValueShift[direction]) : -1;
      if (which < 0)
      {
        this->BadEdge = "loop edge " + std::to_string(i) + " is not a linel of its plane";
        return this->BadEdge.c_str();
      }
      const UV from = this->Face.project(p);
      const Surfel s{ add(p, step.candidate[which].inner), step.candidate[which].direction };
      if (const char* error = this->visit(
            s, plus(from, step.shift[which]), value + this->LoopValueShift[direction][which]))
        return error;
      this->Face.markLoopEdge(from, step.forward); // an edge of s, a surfel of the grid
    }
    return nullptr;
  }

  /// Across every linel that is not a loop edge, at most `limit` surfels.
  const char* flood(const PlaneSurfels& plane, std::size_t limit)
  {
    while (!this->Stack.empty())
    {
      const Entry e = this->Stack.back();
      this->Stack.pop_back();
      if (this->FaceSurfels > limit)
        return "its loop does not enclose a disk of its plane";
      for (int k = 0; k < 4; ++k)
      {
        // The edge a -> b (corners k, k + 1) and the square on the left of b -> a: what
        // PlaneSurfels::leftOf(b, a) finds, from the steps of the surfel's direction.
        const FloodGeometry::Step& step = this->Geometry->steps[e.surfel.direction][k];
        if (this->Face.isLoopEdgeOrCrossed(plus(e.voxel, step.from), step.forward))
          continue;
        const std::int64_t* shift = this->ValueShift[e.surfel.direction][k];
        const int which = this->stepTarget(plane, step, e.value, shift);
        if (which < 0)
          return "its plane is not a surface around a linel";
        const Surfel t{ add(e.surfel.voxel, step.candidate[which].inner),
          step.candidate[which].direction };
        if (const char* error =
              this->visit(t, plus(e.voxel, step.shift[which]), e.value + shift[which]))
          return error;
        // t's edge b -> a leads back to s, filled: the plane is a surface, so each linel has
        // one surfel on either side, and crossing it once says all (half the crossings).
        this->Face.markCrossed(plus(e.voxel, step.to), step.backward);
      }
    }
    return nullptr;
  }

  std::array<std::int32_t, 3> Dims;
  SurfelBits All;
  bool KeepAll;
  FaceMarks Face;                          ///< the face's surfels and loop edges
  std::vector<Surfel> Visited;             ///< of the face (only when not KeepAll)
  std::size_t FaceSurfels = 0;             ///< visited in the face
  std::vector<Entry> Stack;                ///< of the face, to flood from
  const FloodGeometry* Geometry = nullptr; ///< of the face's plane's signs
  std::int64_t ValueShift[6][4][2];        ///< of the face's plane, by direction and edge
  std::int64_t LoopValueShift[6][2];       ///< a loop edge's, by its direction
  std::int64_t TwiceStep[3];               ///< 2 |n_a|
  std::string BadEdge;                     ///< the message of a loop edge off the plane
  std::size_t Count = 0;
};

/// Voxels by parity along x: each row starts at a -x surfel and ends at a +x one (a voxel
/// is inside from the -x surfel of its row's run to the +x surfel of it). Whole words without
/// x surfels are filled at once.
std::string fillByParity(const SurfelBits& surfels,
  const std::array<std::int32_t, 3>& dims,
  BitVolume& voxels)
{
  voxels = BitVolume(dims[0], dims[1], dims[2]);
  const BitVolume& minus = surfels.direction(0);
  const BitVolume& plus = surfels.direction(1);
  const std::size_t words = voxels.wordsPerRow();
  const char* const notBounding = "the faces do not bound a set of voxels of the grid";
  for (std::int32_t z = 0; z < dims[2]; ++z)
    for (std::int32_t y = 0; y < dims[1]; ++y)
    {
      const Word* m = minus.row(y, z);
      const Word* p = plus.row(y, z);
      Word* out = voxels.row(y, z);
      bool inside = false;
      for (std::size_t i = 0; i < words; ++i)
      {
        const int bits = static_cast<int>(std::min<std::size_t>(64, dims[0] - 64 * i));
        const Word valid = bits == 64 ? ~Word(0) : (Word(1) << bits) - 1;
        if ((m[i] | p[i]) == 0)
        {
          out[i] = inside ? valid : 0;
          continue;
        }
        Word w = 0;
        for (int b = 0; b < bits; ++b)
        {
          if ((m[i] >> b) & 1)
          {
            if (inside)
              return notBounding; // a run opened twice
            inside = true;
          }
          if (!inside)
          {
            if ((p[i] >> b) & 1)
              return notBounding; // a run closed before it opened
            continue;
          }
          w |= Word(1) << b;
          if ((p[i] >> b) & 1)
            inside = false;
        }
        out[i] = w;
      }
      if (inside)
        return notBounding; // a run never closed
    }
  return std::string();
}

} // namespace

std::string surfelsOfOutline(const FaceOutline& face,
  const std::array<std::int32_t, 3>& dims,
  std::vector<Surfel>& surfels)
{
  FaceFiller filler(dims, false);
  const std::string error = filler.fill(face, 0);
  surfels = error.empty() ? filler.lastFace() : std::vector<Surfel>();
  return error;
}

namespace detail
{
std::size_t faceMarkArrayCells(const FaceOutline& face, const std::array<std::int32_t, 3>& dims)
{
  FaceMarks marks(dims);
  marks.begin(face.plane, face.loop);
  return marks.arrayCells();
}
} // namespace detail

struct Reversion::Filling
{
  explicit Filling(const std::array<std::int32_t, 3>& dims)
    : filler(dims)
  {
  }
  FaceFiller filler;
};

Reversion::Reversion(const std::array<std::int32_t, 3>& dims)
  : Dims(dims)
  , State(std::make_unique<Filling>(dims))
{
}

Reversion::~Reversion() = default;

std::string Reversion::add(const FaceOutline& face)
{
  return this->State->filler.fill(face, this->Faces++);
}

std::string Reversion::finish(BitVolume& voxels, std::size_t* surfelCount)
{
  if (surfelCount)
    *surfelCount = this->State->filler.count();
  return fillByParity(this->State->filler.surfels(), this->Dims, voxels);
}

std::string revert(const std::vector<FaceOutline>& faces,
  const std::array<std::int32_t, 3>& dims,
  BitVolume& voxels,
  const Execution& exec,
  std::size_t* surfelCount)
{
  ProgressPoll poll(exec, 0.0, 1.0);
  Reversion reversion(dims);
  for (std::size_t f = 0; f < faces.size(); ++f)
  {
    poll.at(0.9 * double(f) / double(faces.size()));
    if (!poll.tick())
      return "aborted";
    const std::string error = reversion.add(faces[f]);
    if (!error.empty())
      return error;
  }
  return reversion.finish(voxels, surfelCount);
}

} // namespace vbr
