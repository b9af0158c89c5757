// The 3D plane sweep of Ayala & Vergara (section 2) in chunks of planes run concurrently.
//
// sortForTheThreeSweeps gives the three cyclic sortings, one sweep per normal axis. The
// planes of each are cut into chunks (chunkPlanes), the section entering each chunk found by
// one sequential pass of XORs (formula 1), the cheap part. Each chunk (sweepChunk) then runs
// its cuts: the next section S(i) = S(i-1) XOR C(i), the forward and backward differences
// (forwardAndBackwardDifferences, formulas 3 and 4), and for each the faces of that 2D EVM by
// planeSweep2D, placed in their plane by appendFaces, FD facing +A and BD facing -A. The
// chunks' B-Reps are joined in order (appendBRep), so the result does not depend on the
// chunking.

#include "PlaneSweep3D.h"

#include "EVMBoolean.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace vbr
{

namespace
{

/// The order of a vertex of a plane (first coordinate 0, as the sections and cuts are) as one
/// integer: (u, v) with the sign bits flipped, so that unsigned order is Vertex order.
std::uint64_t planeKey(const Vertex& p)
{
  return (std::uint64_t(std::uint32_t(p[1]) ^ 0x80000000u) << 32) |
    (std::uint32_t(p[2]) ^ 0x80000000u);
}

/// The XOR of two sorted vertex lists of a plane (formula 1, and BD = C XOR FD), into `out`:
/// xorVertices with one comparison of integers per step, the hot merge of the sweep.
void xorPlanes(const std::vector<Vertex>& a, const std::vector<Vertex>& b, std::vector<Vertex>& out)
{
  out.resize(a.size() + b.size());
  const Vertex *i = a.data(), *iEnd = i + a.size(), *j = b.data(), *jEnd = j + b.size();
  Vertex* o = out.data();
  while (i != iEnd && j != jEnd)
  {
    const std::uint64_t ki = planeKey(*i), kj = planeKey(*j);
    if (ki < kj)
      *o++ = *i++;
    else if (kj < ki)
      *o++ = *j++;
    else
    {
      ++i;
      ++j;
    }
  }
  o = std::copy(i, iEnd, o);
  o = std::copy(j, jEnd, o);
  out.resize(static_cast<std::size_t>(o - out.data()));
}

/// Chunks of planes per sorting when the faces are streamed (planeSweep3DStream): the faces
/// of the few chunks swept at a time are all that is alive of them.
constexpr std::size_t StreamChunks = 64;

/// A run of consecutive planes of vertices of one sorting, with the section before it.
struct PlaneChunk
{
  const EVM* sorted = nullptr;
  const std::vector<std::size_t>* starts = nullptr; ///< plane starts of *sorted
  std::size_t firstPlane = 0, endPlane = 0;
  std::vector<Vertex> section; ///< S(firstPlane - 1)
};

/// Splits every sorting's planes into about `perAxis` chunks; the sections at chunk starts come
/// from one sequential pass of XORs (formula 1), the cheap part of the sweep.
std::vector<PlaneChunk> chunkPlanes(const EVM (&sorted)[3],
  const std::vector<std::size_t> (&planeStarts)[3],
  std::size_t perAxis)
{
  std::vector<PlaneChunk> chunks;
  for (int axis = 0; axis < 3; ++axis)
  {
    const EVM& evm = sorted[axis];
    const auto& starts = planeStarts[axis];
    const std::size_t planes = starts.size() - 1;
    const std::size_t step = std::max<std::size_t>(1, (planes + perAxis - 1) / perAxis);
    const Vertex* v = evm.vertices().data();
    std::vector<Vertex> section;
    for (std::size_t p = 0; p < planes; ++p)
    {
      if (p % step == 0)
      {
        PlaneChunk c;
        c.sorted = &evm;
        c.starts = &starts;
        c.firstPlane = p;
        c.endPlane = std::min(planes, p + step);
        c.section = section;
        chunks.push_back(std::move(c));
      }
      std::vector<Vertex> next;
      xorPlanes(section, project(v + starts[p], v + starts[p + 1], 0), next);
      section.swap(next);
    }
  }
  return chunks;
}

/// The forward and backward differences of cut C(i) (formula 4): the cut is FD + BD
/// (formula 3), FD = S(i-1) - S(i) is the part of the cut covered by S(i-1), and BD the rest
/// of the cut, so one Boolean and one XOR give both.
void forwardAndBackwardDifferences(const std::vector<Vertex>& cut,
  const std::vector<Vertex>& previousSection,
  std::vector<Vertex>& fd,
  std::vector<Vertex>& bd)
{
  fd = booleanVertices(cut.data(),
    cut.data() + cut.size(),
    previousSection.data(),
    previousSection.data() + previousSection.size(),
    1,
    BooleanOp::Intersection);
  xorPlanes(cut, fd, bd);
}

/// The cut of plane `p` (formula 1's C(i)): its vertices projected along the sweep's axis, into
/// `cut`, whose memory is reused from plane to plane.
void cutOf(const Vertex* v,
  const std::vector<std::size_t>& starts,
  std::size_t p,
  std::vector<Vertex>& cut)
{
  cut.assign(v + starts[p], v + starts[p + 1]);
  for (Vertex& c : cut)
    c[0] = 0;
}

/// Sweeps a chunk of planes: for each cut, the next section (formula 1), the forward and
/// backward differences (formula 4) and their faces by the 2D plane sweep, FD facing +A and
/// BD facing -A.
bool sweepChunk(const PlaneChunk& chunk,
  FaceConnectivity connectivity,
  const Execution& exec,
  std::atomic<bool>& abort,
  BRep& out)
{
  out.mergedAtVertices = connectivity == FaceConnectivity::Vertex;
  const EVM& sorted = *chunk.sorted;
  const auto& starts = *chunk.starts;
  const Vertex* v = sorted.vertices().data();
  std::vector<Vertex> section = chunk.section, next, cut, fd, bd;
  for (std::size_t p = chunk.firstPlane; p < chunk.endPlane; ++p)
  {
    if (abort || exec.stopRequested())
    {
      abort = true;
      return false;
    }
    const Coord position = v[starts[p]][0];
    cutOf(v, starts, p, cut);
    xorPlanes(section, cut, next);
    forwardAndBackwardDifferences(cut, section, fd, bd);
    appendFaces(planeSweep2D(fd.data(), fd.data() + fd.size(), connectivity),
      sorted.order(),
      position,
      +1,
      out);
    appendFaces(planeSweep2D(bd.data(), bd.data() + bd.size(), connectivity),
      sorted.order(),
      position,
      -1,
      out);
    section.swap(next);
  }
  return true;
}

/// The three cyclic sortings (A, B, C) = (x, y, z), (y, z, x), (z, x, y), one per sweep,
/// each from the previous one by one stable bucket pass when the EVM comes ZYX-sorted from
/// extraction: ZYX -> YZX -> XYZ -> ZXY.
void sortForTheThreeSweeps(const EVM& evm, const Execution& exec, EVM (&sorted)[3])
{
  sorted[1] = evm.sortedAs({ 1, 2, 0 }, exec);
  sorted[0] = sorted[1].sortedAs({ 0, 1, 2 }, exec);
  sorted[2] = sorted[0].sortedAs({ 2, 0, 1 }, exec);
}

/// Appends one B-Rep to another, renumbering its faces, loops and points.
void appendBRep(BRep& to, BRep&& from)
{
  const int faceBase = static_cast<int>(to.faces.size());
  const int loopBase = static_cast<int>(to.loops.size());
  to.faces.reserve(to.faces.size() + from.faces.size());
  to.loops.reserve(to.loops.size() + from.loops.size());
  for (BRepFace f : from.faces)
  {
    f.firstLoop += loopBase;
    f.parent = f.parent < 0 ? -1 : f.parent + faceBase;
    to.faces.push_back(f);
  }
  const std::size_t pointBase = to.points.size();
  for (BRepLoop l : from.loops)
  {
    l.face += faceBase;
    l.begin += pointBase;
    l.end += pointBase;
    to.loops.push_back(l);
  }
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  to.nonManifoldVertices += from.nonManifoldVertices;
}

/// Sweeps the planes of one sorting in chunks of `step` planes, `batch` chunks at a time
/// (concurrently), each batch's parts handed to consume in order before the next batch is
/// swept. `planesDone` (of `planesAll`, for the progress) counts the planes swept so far.
bool streamSorting(const EVM& sorted,
  FaceConnectivity connectivity,
  const Execution& exec,
  const std::function<bool(BRep&)>& consume,
  std::size_t& planesDone,
  std::size_t planesAll)
{
  const std::vector<std::size_t> starts = sorted.planeStarts();
  const std::size_t planes = starts.size() - 1;
  const std::size_t batch = static_cast<std::size_t>(std::max(1, exec.concurrency));
  const std::size_t step = std::max<std::size_t>(1, (planes + StreamChunks - 1) / StreamChunks);
  const Vertex* v = sorted.vertices().data();
  std::atomic<bool> abort{ false };
  std::vector<Vertex> section, next; // S(p - 1), entering the next chunk
  std::vector<PlaneChunk> chunks;
  std::vector<BRep> parts;
  for (std::size_t p = 0; p < planes;)
  {
    // The next chunks with the sections entering them (formula 1, sequential and cheap).
    chunks.clear();
    for (; p < planes && chunks.size() < batch; p = chunks.back().endPlane)
    {
      chunks.push_back({ &sorted, &starts, p, std::min(planes, p + step), section });
      for (std::size_t q = p; q < chunks.back().endPlane; ++q)
      {
        xorPlanes(section, project(v + starts[q], v + starts[q + 1], 0), next);
        section.swap(next);
      }
    }
    parts.assign(chunks.size(), BRep());
    exec.forRange(static_cast<std::int64_t>(chunks.size()),
      [&](std::int64_t b, std::int64_t e)
      {
        for (std::int64_t c = b; c < e; ++c)
          if (!sweepChunk(chunks[c], connectivity, exec, abort, parts[c]))
            abort = true;
      });
    for (BRep& part : parts)
      if (abort || !consume(part))
        return false;
    planesDone += p - chunks.front().firstPlane;
    if (!exec.report(double(planesDone) / double(std::max<std::size_t>(planesAll, 1))))
      return false;
  }
  return true;
}

} // namespace

bool planeSweep3DStream(EVM evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  const std::function<bool(BRep&)>& consume)
{
  // sortForTheThreeSweeps' sortings, made as late and released as early as the sweeps allow.
  EVM first = evm.sortedAs({ 1, 2, 0 }, exec);
  evm = EVM();
  EVM zeroth = first.sortedAs({ 0, 1, 2 }, exec);
  const std::size_t planesAll =
    3 * std::max<std::size_t>(1, zeroth.planeStarts().size() - 1); // about
  std::size_t done = 0;
  if (!streamSorting(zeroth, connectivity, exec, consume, done, planesAll))
    return false;
  EVM second = zeroth.sortedAs({ 2, 0, 1 }, exec);
  zeroth = EVM();
  if (!streamSorting(first, connectivity, exec, consume, done, planesAll))
    return false;
  first = EVM();
  return streamSorting(second, connectivity, exec, consume, done, planesAll);
}

bool planeSweep3DParts(const EVM& evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  std::vector<BRep>& parts)
{
  parts.clear();
  std::atomic<bool> abort{ false };
  EVM sorted[3];
  sortForTheThreeSweeps(evm, exec, sorted);
  // Chunks of planes of all three sweeps are independent tasks.
  const std::vector<std::size_t> starts[3] = {
    sorted[0].planeStarts(), sorted[1].planeStarts(), sorted[2].planeStarts()
  };
  const std::vector<PlaneChunk> chunks = chunkPlanes(sorted, starts, 8);
  parts.resize(chunks.size());
  exec.forRange(static_cast<std::int64_t>(chunks.size()),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t c = b; c < e; ++c)
      {
        if (!sweepChunk(chunks[c], connectivity, exec, abort, parts[c]))
          abort = true;
        // The parts stay alive side by side until their cells are written: no slack in them.
        parts[c].faces.shrink_to_fit();
        parts[c].loops.shrink_to_fit();
        parts[c].points.shrink_to_fit();
      }
    });
  if (abort || !exec.report(1.0))
  {
    parts.clear();
    return false;
  }
  return true;
}

bool planeSweep3D(const EVM& evm, FaceConnectivity connectivity, const Execution& exec, BRep& out)
{
  out = BRep();
  out.mergedAtVertices = connectivity == FaceConnectivity::Vertex;
  std::vector<BRep> parts;
  if (!planeSweep3DParts(evm, connectivity, exec, parts))
    return false;
  // The chunks' faces in order: by axis, then plane.
  std::size_t faces = 0, loops = 0, points = 0;
  for (const BRep& b : parts)
  {
    faces += b.faces.size();
    loops += b.loops.size();
    points += b.points.size();
  }
  out.faces.reserve(faces);
  out.loops.reserve(loops);
  out.points.reserve(points);
  for (BRep& b : parts)
  {
    appendBRep(out, std::move(b));
    b = BRep(); // released as soon as copied
  }
  return true;
}

} // namespace vbr
