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

/// 1D: the operands are sorted interval end points (equal in the first two coordinates).
std::vector<Vertex> booleanIntervals(const Vertex* p,
  const Vertex* pEnd,
  const Vertex* q,
  const Vertex* qEnd,
  BooleanOp op)
{
  std::vector<Vertex> out;
  bool inP = false, inQ = false, inR = false;
  while (p != pEnd || q != qEnd)
  {
    const Coord c = (q == qEnd || (p != pEnd && (*p)[2] < (*q)[2])) ? (*p)[2] : (*q)[2];
    if (p != pEnd && (*p)[2] == c)
    {
      inP = !inP;
      ++p;
    }
    if (q != qEnd && (*q)[2] == c)
    {
      inQ = !inQ;
      ++q;
    }
    const bool r = apply(op, inP, inQ);
    if (r != inR)
    {
      out.push_back({ 0, 0, c });
      inR = r;
    }
  }
  return out;
}

/// End of the run of vertices sharing coordinate `level` with *begin.
const Vertex* planeEnd(const Vertex* begin, const Vertex* end, int level)
{
  const Coord c = (*begin)[level];
  while (begin != end && (*begin)[level] == c)
  {
    ++begin;
  }
  return begin;
}

} // namespace

std::vector<Vertex> xorVertices(const std::vector<Vertex>& a, const std::vector<Vertex>& b)
{
  std::vector<Vertex> out;
  out.reserve(a.size() + b.size());
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end())
  {
    if (*i < *j)
    {
      out.push_back(*i++);
    }
    else if (*j < *i)
    {
      out.push_back(*j++);
    }
    else
    {
      ++i;
      ++j;
    }
  }
  out.insert(out.end(), i, a.end());
  out.insert(out.end(), j, b.end());
  return out;
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
    return booleanIntervals(p, pEnd, q, qEnd, op);
  }
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
  {
    throw std::invalid_argument("Boolean operands need the same dimension and sorting");
  }
  const auto& a = p.vertices();
  const auto& b = q.vertices();
  const int level = p.dimension() == 3 ? 0 : 1;
  return EVM(p.dimension(),
    p.order(),
    booleanVertices(a.data(), a.data() + a.size(), b.data(), b.data() + b.size(), level, op));
}

} // namespace vbr
