// Boolean operations on vertex sets, recursive in the dimension.
//
// booleanVertices at level 0 sweeps the planes of vertices of both operands together,
// keeping the sections of both up to date (XOR of the projections, formula 1); the section
// of the result is the Boolean of the operands' sections one dimension lower, and the
// result's plane of vertices there is the XOR of two consecutive result sections (formula 2).
// Level 1 is the same over lines (booleanLines, with the 1D sections kept as plain coordinate
// lists: the hot path of the 3D plane sweep's forward and backward differences), and level 2
// merges the end points of 1D intervals (booleanCoordinates). xorVertices is the symmetric
// difference of two sorted lists (symmetricDifference).

#include "EVMBoolean.h"

#include <stdexcept>

namespace vbr
{

namespace
{

bool apply(BooleanOp op, bool inP, bool inQ)
{
  switch (op)
  {
    case BooleanOp::Union:
      return inP || inQ;
    case BooleanOp::Intersection:
      return inP && inQ;
    case BooleanOp::Difference:
      return inP && !inQ;
    case BooleanOp::Xor:
      return inP != inQ;
  }
  return false;
}

/// Symmetric difference of two sorted lists (the XOR of the sets they represent), into `out`.
template<typename T>
void symmetricDifference(const std::vector<T>& a, const std::vector<T>& b, std::vector<T>& out)
{
  out.clear();
  out.reserve(a.size() + b.size());
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end())
  {
    if (*i < *j)
      out.push_back(*i++);
    else if (*j < *i)
      out.push_back(*j++);
    else
    {
      ++i;
      ++j;
    }
  }
  out.insert(out.end(), i, a.end());
  out.insert(out.end(), j, b.end());
}

/// 1D Boolean of two sorted interval end point lists, into `out`.
void booleanCoordinates(const std::vector<Coord>& a,
  const std::vector<Coord>& b,
  BooleanOp op,
  std::vector<Coord>& out)
{
  out.clear();
  bool inA = false, inB = false, inR = false;
  auto i = a.begin(), j = b.begin();
  while (i != a.end() || j != b.end())
  {
    const Coord c = (j == b.end() || (i != a.end() && *i < *j)) ? *i : *j;
    if (i != a.end() && *i == c)
    {
      inA = !inA;
      ++i;
    }
    if (j != b.end() && *j == c)
    {
      inB = !inB;
      ++j;
    }
    const bool r = apply(op, inA, inB);
    if (r != inR)
    {
      out.push_back(c);
      inR = r;
    }
  }
}

/// 2D Boolean by a line sweep over 1D sections kept as plain coordinate lists (the hot path
/// of the 3D boundary extraction: the forward and backward differences of every cut).
std::vector<Vertex> booleanLines(const Vertex* p,
  const Vertex* pEnd,
  const Vertex* q,
  const Vertex* qEnd,
  BooleanOp op)
{
  std::vector<Vertex> out;
  std::vector<Coord> sectionP, sectionQ, sectionR, next, line, scratch;
  auto advance = [&](const Vertex*& it, const Vertex* end, Coord u, std::vector<Coord>& section)
  {
    line.clear();
    while (it != end && (*it)[1] == u)
      line.push_back((*it++)[2]);
    symmetricDifference(section, line, scratch);
    section.swap(scratch);
  };
  const bool needsP = op != BooleanOp::Union && op != BooleanOp::Xor;
  while (p != pEnd || q != qEnd)
  {
    const Coord u = (q == qEnd || (p != pEnd && (*p)[1] < (*q)[1])) ? (*p)[1] : (*q)[1];
    if (p != pEnd && (*p)[1] == u)
      advance(p, pEnd, u, sectionP);
    if (q != qEnd && (*q)[1] == u)
      advance(q, qEnd, u, sectionQ);
    booleanCoordinates(sectionP, sectionQ, op, next);
    symmetricDifference(sectionR, next, line);
    for (Coord v : line)
      out.push_back({ 0, u, v });
    sectionR.swap(next);
    // Nothing more can come out once the operand that bounds the result is exhausted.
    const bool pDone = p == pEnd && sectionP.empty();
    const bool qDone = q == qEnd && sectionQ.empty();
    if (sectionR.empty() && ((needsP && pDone) || (op == BooleanOp::Intersection && qDone)))
      break;
  }
  return out;
}

/// End of the run of vertices sharing coordinate `level` with *begin.
const Vertex* planeEnd(const Vertex* begin, const Vertex* end, int level)
{
  const Coord c = (*begin)[level];
  while (begin != end && (*begin)[level] == c)
    ++begin;
  return begin;
}

} // namespace

std::vector<Vertex> xorVertices(const std::vector<Vertex>& a, const std::vector<Vertex>& b)
{
  std::vector<Vertex> out;
  symmetricDifference(a, b, out);
  return out;
}

void xorVertices(const std::vector<Vertex>& a,
  const std::vector<Vertex>& b,
  std::vector<Vertex>& out)
{
  symmetricDifference(a, b, out);
}

std::vector<Vertex> booleanVertices(const Vertex* p,
  const Vertex* pEnd,
  const Vertex* q,
  const Vertex* qEnd,
  int level,
  BooleanOp op)
{
  if (level >= 2)
  {
    // 1D: interval end points, equal in the first two coordinates.
    std::vector<Coord> a, b, r;
    for (; p != pEnd; ++p)
      a.push_back((*p)[2]);
    for (; q != qEnd; ++q)
      b.push_back((*q)[2]);
    booleanCoordinates(a, b, op, r);
    std::vector<Vertex> out;
    for (Coord c : r)
      out.push_back({ 0, 0, c });
    return out;
  }
  if (level == 1)
    return booleanLines(p, pEnd, q, qEnd, op);
  std::vector<Vertex> out, sectionP, sectionQ, sectionR;
  while (p != pEnd || q != qEnd)
  {
    const Coord c =
      (q == qEnd || (p != pEnd && (*p)[level] < (*q)[level])) ? (*p)[level] : (*q)[level];
    if (p != pEnd && (*p)[level] == c)
    {
      const Vertex* e = planeEnd(p, pEnd, level);
      sectionP = xorVertices(sectionP, project(p, e, level));
      p = e;
    }
    if (q != qEnd && (*q)[level] == c)
    {
      const Vertex* e = planeEnd(q, qEnd, level);
      sectionQ = xorVertices(sectionQ, project(q, e, level));
      q = e;
    }
    std::vector<Vertex> next = booleanVertices(sectionP.data(),
      sectionP.data() + sectionP.size(),
      sectionQ.data(),
      sectionQ.data() + sectionQ.size(),
      level + 1,
      op);
    for (Vertex v : xorVertices(sectionR, next))
    {
      v[level] = c;
      out.push_back(v);
    }
    sectionR.swap(next);
  }
  return out;
}

EVM booleanOp(const EVM& p, const EVM& q, BooleanOp op)
{
  if (p.dimension() != q.dimension() || p.order() != q.order())
    throw std::invalid_argument("Boolean operands need the same dimension and sorting");
  const auto& a = p.vertices();
  const auto& b = q.vertices();
  const int level = p.dimension() == 3 ? 0 : 1;
  return EVM(p.dimension(),
    p.order(),
    booleanVertices(a.data(), a.data() + a.size(), b.data(), b.data() + b.size(), level, op));
}

} // namespace vbr
