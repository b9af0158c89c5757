// Brute-force topology of sets of pixels of one plane, shared by the core and filter tests:
// flood-fill components and the holes of a face. Independent of the code under test.
#ifndef vbr_test_PixelTopology_h
#define vbr_test_PixelTopology_h

#include <algorithm>
#include <cstdint>
#include <deque>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

namespace bf
{

/// A set of pixels (u, v) of one plane.
using PixelSet = std::set<std::pair<std::int32_t, std::int32_t>>;

/// A plane of faces: normal axis, normal sign and position along the axis.
struct PlaneKey
{
  int axis, sign, position;
  bool operator<(const PlaneKey& o) const
  {
    return std::tie(axis, sign, position) < std::tie(o.axis, o.sign, o.position);
  }
  bool operator==(const PlaneKey& o) const
  {
    return axis == o.axis && sign == o.sign && position == o.position;
  }
};

/// Connected components of a pixel set, 4- or 8-connected, by flood fill.
inline std::vector<PixelSet> components(PixelSet left, bool eightConnected)
{
  std::vector<PixelSet> out;
  while (!left.empty())
  {
    PixelSet comp;
    std::deque<std::pair<std::int32_t, std::int32_t>> queue{ *left.begin() };
    left.erase(left.begin());
    while (!queue.empty())
    {
      const auto p = queue.front();
      queue.pop_front();
      comp.insert(p);
      for (int du = -1; du <= 1; ++du)
        for (int dv = -1; dv <= 1; ++dv)
        {
          if ((du == 0 && dv == 0) || (!eightConnected && du != 0 && dv != 0))
            continue;
          auto it = left.find({ p.first + du, p.second + dv });
          if (it != left.end())
          {
            queue.push_back(*it);
            left.erase(it);
          }
        }
    }
    out.push_back(std::move(comp));
  }
  return out;
}

/// The 4-connected components of the complement of `pixels` in a box one pixel larger than
/// their bounding box, and for each whether it is bounded (does not touch the box border).
inline std::vector<std::pair<PixelSet, bool>> complementComponents(const PixelSet& pixels)
{
  int u0 = 1 << 30, u1 = -(1 << 30), v0 = u0, v1 = u1;
  for (const auto& p : pixels)
  {
    u0 = std::min(u0, p.first);
    u1 = std::max(u1, p.first);
    v0 = std::min(v0, p.second);
    v1 = std::max(v1, p.second);
  }
  PixelSet complement;
  for (int u = u0 - 1; u <= u1 + 1; ++u)
    for (int v = v0 - 1; v <= v1 + 1; ++v)
      if (!pixels.count({ u, v }))
        complement.insert({ u, v });
  std::vector<std::pair<PixelSet, bool>> out;
  for (auto& c : components(complement, false))
  {
    const bool bounded = std::none_of(c.begin(),
      c.end(),
      [&](const auto& p) {
        return p.first == u0 - 1 || p.first == u1 + 1 || p.second == v0 - 1 || p.second == v1 + 1;
      });
    out.emplace_back(std::move(c), bounded);
  }
  return out;
}

/// Number of holes of a face: bounded 4-connected components of its complement.
inline int holeCount(const PixelSet& face)
{
  int holes = 0;
  for (const auto& c : complementComponents(face))
    holes += c.second ? 1 : 0;
  return holes;
}

} // namespace bf

#endif
