#include "PlaneSweep2D.h"

#include "UnionFind.h"

#include <cstdint>
#include <limits>
#include <stdexcept>

namespace vbr
{

namespace
{

constexpr Coord Unset = std::numeric_limits<Coord>::min();

struct Edge
{
  Point2 from{ Unset, Unset };
  Point2 to{ Unset, Unset };
  int interval = -1; ///< a section interval of the face on the edge's left
  int next = -1;     ///< following edge of the loop (domino)
};

/// An end point of an interval of the active section and the horizontal edge it draws.
struct SectionEnd
{
  Coord v;
  int edge;
};

/// A section interval that overlaps no interval of the previous section: a candidate first
/// interval of a face, with what the second sweep needs from its section.
struct FirstInterval
{
  int interval;
  int bottomEdge; ///< horizontal edge at its lower end
  int belowEdge;  ///< horizontal edge of the section end just below it, or -1
};

struct NonManifoldVertex
{
  Point2 at;
  int edges[4]; ///< two in, two out
};

class Sweep
{
public:
  explicit Sweep(FaceConnectivity connectivity)
    : MergeAtVertices(connectivity == FaceConnectivity::Vertex)
  {
  }

  Boundary2D run(const Vertex* begin, const Vertex* end)
  {
    while (begin != end)
    {
      const Vertex* lineEnd = begin;
      while (lineEnd != end && (*lineEnd)[1] == (*begin)[1])
        ++lineEnd;
      if ((lineEnd - begin) % 2)
        throw std::invalid_argument("sweep2D: a line of vertices has an odd count (not an EVM)");
      this->processLine((*begin)[1], begin, lineEnd);
      begin = lineEnd;
    }
    if (!this->Section.empty())
      throw std::invalid_argument("sweep2D: the last section is not empty (not an EVM)");
    this->pairNonManifoldVertices();
    return this->collect();
  }

private:
  // ---- union-find over section intervals (roots follow sweep order) -----------------------
  int newInterval() { return static_cast<int>(this->Intervals.add()); }
  int find(int i) { return static_cast<int>(this->Intervals.find(static_cast<std::uint32_t>(i))); }
  void unite(int a, int b)
  {
    this->Intervals.unite(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
  }

  // ---- edges ---------------------------------------------------------------------------------
  /// Starts an edge at `here`; `outgoing` says whether it leaves or enters `here`.
  int startEdge(Point2 here, bool outgoing, int interval)
  {
    Edge e;
    (outgoing ? e.from : e.to) = here;
    e.interval = interval;
    this->Edges.push_back(e);
    return static_cast<int>(this->Edges.size()) - 1;
  }
  void finishEdge(int e, Point2 here)
  {
    Edge& edge = this->Edges[e];
    (edge.from.u == Unset ? edge.from : edge.to) = here;
  }
  /// Links the two edges meeting at an ordinary corner: the one entering it is followed by
  /// the one leaving it.
  void link(int a, int b, Point2 here)
  {
    if (this->Edges[a].to == here)
      this->Edges[a].next = b;
    else
      this->Edges[b].next = a;
  }

  /// Merges the cut [cut, cutEnd) at u into the active section (formula 1 of the paper),
  /// emitting edges, uniting overlapping intervals and recording first intervals.
  void processLine(Coord u, const Vertex* cut, const Vertex* cutEnd)
  {
    std::vector<SectionEnd>& next = this->NextSection;
    std::vector<int>& nextIntervals = this->NextIntervals;
    next.clear();
    nextIntervals.clear();
    std::size_t i = 0;
    bool inPrev = false, inCut = false;
    int prevInterval = -1, newIntervalId = -1, piece = -1;
    bool newTouched = false;
    int newBottomEdge = -1, newBelowEdge = -1;

    while (i < this->Section.size() || cut != cutEnd)
    {
      const bool takePrev =
        i < this->Section.size() && (cut == cutEnd || this->Section[i].v <= (*cut)[2]);
      const Coord v = takePrev ? this->Section[i].v : (*cut)[2];
      const bool atPrev = i < this->Section.size() && this->Section[i].v == v;
      const bool atCut = cut != cutEnd && (*cut)[2] == v;
      const bool inNew = inPrev != inCut;
      if (inPrev && inNew)
      {
        // The open intervals of both sections overlap on the segment just below v.
        this->unite(prevInterval, newIntervalId);
        newTouched = true;
      }
      const bool inPrev2 = inPrev != atPrev;
      const bool inCut2 = inCut != atCut;
      const bool inNew2 = inPrev2 != inCut2;
      const Point2 here{ u, v };

      if (atPrev && inPrev2)
        prevInterval = this->SectionIntervals[i / 2];
      if (inNew2 && !inNew)
      {
        newIntervalId = this->newInterval();
        nextIntervals.push_back(newIntervalId);
        newTouched = false;
        newBelowEdge = next.empty() ? -1 : next.back().edge;
      }
      // A vertical piece keeps the face on its left: upwards when the face lies before u.
      auto startPiece = [&]()
      { return this->startEdge(here, !inNew2, inNew2 ? newIntervalId : prevInterval); };

      if (atPrev && atCut)
      {
        // Extreme vertex matching the section: its horizontal edge ends here.
        const int h = this->Section[i].edge;
        this->finishEdge(h, here);
        if (inCut)
        {
          this->finishEdge(piece, here);
          this->link(piece, h, here);
          piece = -1;
        }
        else
        {
          piece = startPiece();
          this->link(piece, h, here);
        }
      }
      else if (atCut)
      {
        // New extreme vertex of the section: a horizontal edge starts here.
        const int h = this->startEdge(here, inNew2, newIntervalId);
        if (inNew2)
          newBottomEdge = h;
        next.push_back({ v, h });
        if (inCut)
        {
          this->finishEdge(piece, here);
          this->link(piece, h, here);
          piece = -1;
        }
        else
        {
          piece = startPiece();
          this->link(piece, h, here);
        }
      }
      else if (atPrev && inCut)
      {
        // Non-manifold vertex: a brink of the cut contains a vertex of the section.
        const int hOld = this->Section[i].edge;
        this->finishEdge(hOld, here);
        this->finishEdge(piece, here);
        const int below = piece;
        piece = startPiece();
        const int hNew = this->startEdge(here, inNew2, newIntervalId);
        if (inNew2)
          newBottomEdge = hNew;
        next.push_back({ v, hNew });
        this->NonManifold.push_back({ here, { hOld, hNew, below, piece } });
        if (this->MergeAtVertices)
        {
          this->unite(prevInterval, newIntervalId);
          newTouched = true;
        }
      }
      else
      {
        next.push_back(this->Section[i]); // the horizontal edge goes on
      }

      if (inNew && !inNew2 && !newTouched)
        this->First.push_back({ newIntervalId, newBottomEdge, newBelowEdge });
      if (atPrev)
        ++i;
      if (atCut)
        ++cut;
      inPrev = inPrev2;
      inCut = inCut2;
    }
    this->Section.swap(next);
    this->SectionIntervals.swap(nextIntervals);
  }

  /// Pairs the two entering and two leaving edges of each non-manifold vertex (paper Fig. 7):
  /// when both corners belong to the same face, the loop turns right, so that every loop
  /// follows one component of the face's complement; otherwise each loop stays in its face.
  void pairNonManifoldVertices()
  {
    for (const auto& nmv : this->NonManifold)
    {
      int in[2], out[2], ni = 0, no = 0;
      for (int e : nmv.edges)
        if (this->Edges[e].to == nmv.at)
          in[ni++] = e;
        else
          out[no++] = e;
      if (ni != 2 || no != 2)
        throw std::logic_error("sweep2D: inconsistent non-manifold vertex");
      const bool sameFace =
        this->find(this->Edges[in[0]].interval) == this->find(this->Edges[in[1]].interval);
      for (int k = 0; k < 2; ++k)
      {
        const Edge& a = this->Edges[in[k]];
        int chosen = -1;
        for (int o : out)
        {
          const Edge& b = this->Edges[o];
          if (sameFace)
          {
            const long long du1 = a.to.u - a.from.u, dv1 = a.to.v - a.from.v;
            const long long du2 = b.to.u - b.from.u, dv2 = b.to.v - b.from.v;
            if (du1 * dv2 - dv1 * du2 < 0)
              chosen = o; // right turn
          }
          else if (this->find(b.interval) == this->find(a.interval))
          {
            chosen = o;
          }
        }
        if (chosen < 0)
          throw std::logic_error("sweep2D: no continuation at a non-manifold vertex");
        this->Edges[in[k]].next = chosen;
      }
    }
  }

  /// Domino step, face numbering and the second sweep (classification and inclusion).
  Boundary2D collect()
  {
    Boundary2D out;
    out.nonManifoldVertices = this->NonManifold.size();
    std::vector<int> faceOfRoot(this->Intervals.size(), -1);
    std::vector<const FirstInterval*> firstOfFace;
    for (const auto& f : this->First)
    {
      int& face = faceOfRoot[this->find(f.interval)];
      if (face < 0)
      {
        face = static_cast<int>(firstOfFace.size());
        firstOfFace.push_back(&f);
      }
    }
    out.faces.resize(firstOfFace.size());

    std::vector<int> loopOfEdge(this->Edges.size(), -1);
    out.points.reserve(this->Edges.size());
    for (std::size_t e0 = 0; e0 < this->Edges.size(); ++e0)
    {
      if (loopOfEdge[e0] >= 0)
        continue;
      Loop2D loop;
      loop.face = faceOfRoot[this->find(this->Edges[e0].interval)];
      loop.begin = out.points.size();
      const int id = static_cast<int>(out.loops.size());
      for (int e = static_cast<int>(e0); loopOfEdge[e] < 0; e = this->Edges[e].next)
      {
        if (e < 0 || this->Edges[e].next < 0)
          throw std::logic_error("sweep2D: open contour");
        loopOfEdge[e] = id;
        out.points.push_back(this->Edges[e].from);
      }
      loop.end = out.points.size();
      out.loops.push_back(loop);
    }

    // Second sweep: faces in order of first appearance. A face's first interval is bounded
    // below by its outer loop; the section end just below it tells where the face lies: in a
    // hole of the face owning that end, or beside it (then it shares that face's parent).
    for (std::size_t f = 0; f < out.faces.size(); ++f)
    {
      Face2D& face = out.faces[f];
      const FirstInterval& first = *firstOfFace[f];
      face.outerLoop = loopOfEdge[first.bottomEdge];
      if (first.belowEdge >= 0)
      {
        const Loop2D& below = out.loops[loopOfEdge[first.belowEdge]];
        const bool inHole = out.faces[below.face].outerLoop != loopOfEdge[first.belowEdge];
        face.parent = inHole ? below.face : out.faces[below.face].parent;
      }
      face.depth = face.parent < 0 ? 0 : out.faces[face.parent].depth + 2;
    }
    for (std::size_t l = 0; l < out.loops.size(); ++l)
    {
      Loop2D& loop = out.loops[l];
      Face2D& face = out.faces[loop.face];
      if (face.outerLoop != static_cast<int>(l))
      {
        loop.hole = true;
        face.holeLoops.push_back(static_cast<int>(l));
      }
    }
    return out;
  }

  const bool MergeAtVertices;
  std::vector<SectionEnd> Section;     ///< active section, sorted by v
  std::vector<SectionEnd> NextSection; ///< the section being built (reused buffers)
  std::vector<int> NextIntervals;
  std::vector<int> SectionIntervals; ///< interval id of each pair of section ends
  UnionFind Intervals;               ///< the section intervals, united into faces
  std::vector<Edge> Edges;
  std::vector<FirstInterval> First;
  std::vector<NonManifoldVertex> NonManifold;
};

} // namespace

Boundary2D sweep2D(const Vertex* begin, const Vertex* end, FaceConnectivity connectivity)
{
  return Sweep(connectivity).run(begin, end);
}

} // namespace vbr
