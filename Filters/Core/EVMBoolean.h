// Regularized Boolean operations on EVMs by the recursive plane sweep of the EVM papers:
// the sections of both operands are kept up to date plane by plane (XOR of projections),
// the sections of the result are the Boolean of the operands' sections one dimension lower,
// and each plane of vertices of the result is the XOR of two consecutive result sections.
#ifndef vbr_EVMBoolean_h
#define vbr_EVMBoolean_h

#include "EVM.h"

#include <vector>

namespace vbr
{

enum class BooleanOp
{
  Union,
  Intersection,
  Difference,
  Xor
};

/// Symmetric difference of two sorted vertex sets (the XOR of the sets they represent).
std::vector<Vertex> xorVertices(const std::vector<Vertex>& a, const std::vector<Vertex>& b);

/// The same into `out` (neither `a` nor `b`), whose memory is reused: a sweep calls it once
/// per plane.
void xorVertices(const std::vector<Vertex>& a,
  const std::vector<Vertex>& b,
  std::vector<Vertex>& out);

/// Boolean of two sorted vertex sets whose coordinates before `level` are all equal:
/// level 0 sweeps 3D planes, 1 sweeps 2D lines, 2 merges 1D intervals.
std::vector<Vertex> booleanVertices(const Vertex* p,
  const Vertex* pEnd,
  const Vertex* q,
  const Vertex* qEnd,
  int level,
  BooleanOp op);

/// Boolean of two EVMs of the same dimension and sorting. Test oracle only: the filters use
/// booleanVertices and xorVertices (the forward and backward differences of the plane
/// sweep); the tests check this whole-EVM entry point against voxel-wise Booleans.
EVM booleanOp(const EVM& p, const EVM& q, BooleanOp op);

} // namespace vbr

#endif
