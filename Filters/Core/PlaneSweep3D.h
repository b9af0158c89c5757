// 3D EVM -> boundary representation by the plane sweep of Aguilera & Ayala, as reviewed in
// section 2 of Ayala & Vergara, "An improved boundary extraction algorithm using a
// plane-sweep technique": orthogonal faces with holes, oriented outwards.
//
// For each axis A the EVM is sorted in the cyclic order (A, B, C) and swept plane of vertices
// by plane of vertices: three sweeps, one per family of faces. The projection of the plane
// of vertices at position i is the cut C(i); each section follows from the previous one by
// XOR (formula 1: S(i) = S(i-1) XOR C(i)); the cut splits into the forward difference
// FD = S(i-1) - S(i), the faces whose outward normal is +A, and the backward difference
// BD = S(i) - S(i-1), those facing -A (formulas 3 and 4). Both are 2D EVMs, turned into faces,
// holes and loops by the 2D plane sweep (PlaneSweep2D.h), the paper's section 3.
#ifndef vbr_PlaneSweep3D_h
#define vbr_PlaneSweep3D_h

#include "BRep.h"
#include "EVM.h"
#include "Execution.h"
#include "PlaneSweep2D.h"

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

namespace vbr
{

/// Faces of a 3D EVM (any sorting), grouped by normal axis, then plane, then +A before -A.
/// Returns false (and an empty BRep) when the caller asked to abort. The three sweeps are
/// cut into chunks of planes swept concurrently; the result does not depend on the chunks.
bool planeSweep3D(const EVM& evm, FaceConnectivity connectivity, const Execution& exec, BRep& out);

/// The same faces in parts, one per chunk of planes, in order: concatenated, they are
/// planeSweep3D's B-Rep. Each part's vectors fit their size, and a caller that writes and
/// releases the parts one after the other never holds the faces twice (the concatenation
/// does, for a moment). False (and no part) when the caller asked to abort.
bool planeSweep3DParts(const EVM& evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  std::vector<BRep>& parts);

/// What planeSweep3DStream does with each part of the faces. `prepare` (optional) runs on the
/// thread that swept the part, right after it and concurrently with the other parts' sweeps
/// and prepares: the work on a part that needs no other part (its cells, say) goes there.
/// `append` then runs part after part in planeSweep3DParts' order, never two at once: the work
/// that must follow the order (writing into one output). With threads it runs on whichever
/// worker finds the part next in order ready, so it must not need the calling thread (no
/// toolkit calls; the progress is reported by the stream, on the calling thread). `slot` is
/// the part's place among the parts alive at once, in [0, streamBatch(exec)): a caller keeps
/// what a part's prepare leaves for its append in that slot, free again once append returns.
/// Either returns false to stop the stream.
struct StreamedPartHandlers
{
  std::function<bool(BRep& part, std::size_t slot)> prepare;
  std::function<bool(BRep& part, std::size_t slot)> append;
};

/// The most parts planeSweep3DStream has alive (swept or prepared, not yet appended) at a time
/// with `exec`: the slots of StreamedPartHandlers. 1 without threads.
std::size_t streamBatch(const Execution& exec);

/// The same faces made and handed over part by part, in planeSweep3DParts' order. With threads,
/// exec.concurrency workers (one parallel loop per sorting) take the chunks of planes in order,
/// sweep and prepare them concurrently, and append each part as soon as the parts before it are
/// appended; a worker takes a chunk only when its slot is free, so at most streamBatch(exec)
/// parts are alive. On one thread each part is swept, prepared and appended before the next.
/// Only those parts' faces are alive at a time (and two of the three sortings): a caller that
/// writes and releases each part never holds the object's faces. The EVM is taken (moved in)
/// and freed once sorted. Parts may be empty. The progress is reported on the calling thread
/// only. False when the caller asked to abort or a handler returned false.
/// `planesPerAxis` (when given) gets planesPerAxis(evm) (EVM.h), read off the three sortings
/// rather than counted by passes over the vertices: the planes of vertices along each axis, by
/// world axis (complete when the stream is).
bool planeSweep3DStream(EVM evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  const StreamedPartHandlers& handlers,
  std::array<std::size_t, 3>* planesPerAxis = nullptr);

/// The same, every part handed to consume(part) in order, never two at once (an append: on a
/// worker thread when there are threads; no prepare step).
bool planeSweep3DStream(EVM evm,
  FaceConnectivity connectivity,
  const Execution& exec,
  const std::function<bool(BRep&)>& consume);

namespace detail
{
/// Whether each of the three sweeps of `evm` (normal axis x, y, z) keeps its sections as rows
/// of bits rather than vertex lists (see PlaneSweep3D.cxx): for tests of both ways.
std::array<bool, 3> sectionsAsBitRows(const EVM& evm);
} // namespace detail

} // namespace vbr

#endif
