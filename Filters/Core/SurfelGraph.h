// The surfel boundary of a voxel set as a closed, oriented 2-manifold: surfels, their
// neighbours across each linel and the vertices (pointels split per umbrella).
//
// Voxel (i, j, k) is the unit cube [i, i+1] x [j, j+1] x [k, k+1] (centre at half-integers),
// so pointels are the integer points. A surfel is a face of a selected voxel whose other
// side is not selected; its corners are listed counter-clockwise seen from outside.
//
// Adjacency rule (one rule everywhere, so every input gives a manifold): voxels of the set
// that share only an edge or only a corner are kept apart, i.e. the set is taken
// 6-connected and its complement 18/26-connected. At a linel with four surfels (two
// selected voxels diagonal across it) each surfel is paired with the other surfel of its
// own voxel; a pointel where voxels touch only at the corner gets one vertex per umbrella.
#ifndef vbr_SurfelGraph_h
#define vbr_SurfelGraph_h

#include "BitVolume.h"
#include "Execution.h"
#include "Geometry.h"
#include "Surfels.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

/// About 60 bytes per surfel (16 for the surfel, 16 for its neighbours and their edges, 16 for
/// its vertices, 12 for about one vertex per surfel): the corners are computed from the surfel
/// when asked, not stored (they were 48 bytes per surfel, the largest array).
struct SurfelGraph
{
  /// A link (neighbour) holds the neighbour's number in its low EdgeShift bits and the
  /// neighbour's edge above them; surfels are numbered below MaximumSize.
  static constexpr int EdgeShift = 30;
  static constexpr std::uint32_t MaximumSize = std::uint32_t(1) << EdgeShift;
  static constexpr std::uint32_t NumberMask = MaximumSize - 1;
  /// The link to surfel `number` across its edge `edge`.
  static std::uint32_t link(std::uint32_t number, int edge)
  {
    return number | static_cast<std::uint32_t>(edge) << EdgeShift;
  }

  std::array<std::int32_t, 3> dims{ 0, 0, 0 };
  std::vector<Surfel> surfels; ///< by voxel (z, y, x) then direction
  /// 4 per surfel, across edge k (corner k to k+1): the neighbour's number (low EdgeShift bits) and
  /// the edge of the neighbour that is the same linel (the 2 bits above; link). One word, so that a
  /// step round an umbrella (aroundVertex: the growth's disk test, its hottest loop) waits for one
  /// load, not two from two arrays.
  std::vector<std::uint32_t> neighbour;
  std::vector<std::uint32_t> vertex; ///< 4 per surfel: vertex at corner k
  std::vector<Point3> vertexPointel; ///< per vertex
  std::uint32_t componentCount = 0;  ///< connected boundary components

  std::size_t size() const { return this->surfels.size(); }
  std::uint32_t neighbourOf(std::uint32_t s, int edge) const
  {
    return this->neighbour[4 * s + edge] & NumberMask;
  }
  std::uint32_t vertexOf(std::uint32_t s, int k) const { return this->vertex[4 * s + k]; }
  Point3 cornerOf(std::uint32_t s, int k) const { return this->surfels[s].corner(k); }
  /// The edge of the neighbour across edge `edge` of surfel s that is the same linel.
  int sharedEdge(std::uint32_t s, int edge) const
  {
    return static_cast<int>(this->neighbour[4 * s + edge] >> EdgeShift);
  }

  /// Calls visit(u) for each surfel of the umbrella of the vertex at corner k of surfel s,
  /// in order round it, s first; stops early when visit returns false.
  template<typename Visit>
  void aroundVertex(std::uint32_t s, int k, Visit visit) const
  {
    std::uint32_t u = s;
    int corner = k; // the edge of u that starts at the vertex
    do
    {
      if (!visit(u))
        return;
      const std::uint32_t link = this->neighbour[4 * u + corner]; // one load for both
      u = link & NumberMask;
      corner = static_cast<int>((link >> EdgeShift) + 1) % 4;
    } while (u != s);
  }
};

/// Builds the graph; returns false when aborted. Throws std::length_error for MaximumSize
/// surfels or more.
bool buildSurfelGraph(const BitVolume& voxels, const Execution& exec, SurfelGraph& out);

} // namespace vbr

#endif
