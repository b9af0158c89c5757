#include "BruteForce.h"

#include <algorithm>
#include <deque>
#include <random>

namespace bf
{

vbr::BitVolume randomVolume(const Int3& dims, double density, unsigned seed)
{
  vbr::BitVolume v(dims[0], dims[1], dims[2]);
  std::mt19937 rng(seed);
  std::bernoulli_distribution coin(density);
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
        if (coin(rng))
          v.set(x, y, z);
  return v;
}

bool voxel(const vbr::BitVolume& v, std::int32_t x, std::int32_t y, std::int32_t z)
{
  return x >= 0 && y >= 0 && z >= 0 && x < v.size(0) && y < v.size(1) && z < v.size(2) &&
    v.get(x, y, z);
}

std::set<Int3> extremeVertices(const vbr::BitVolume& v)
{
  std::set<Int3> out;
  for (int z = 0; z <= v.size(2); ++z)
    for (int y = 0; y <= v.size(1); ++y)
      for (int x = 0; x <= v.size(0); ++x)
      {
        int n = 0;
        for (int dz = -1; dz <= 0; ++dz)
          for (int dy = -1; dy <= 0; ++dy)
            for (int dx = -1; dx <= 0; ++dx)
              n += voxel(v, x + dx, y + dy, z + dz);
        if (n % 2)
          out.insert({ x, y, z });
      }
  return out;
}

std::set<Int3> extremeVertices2D(const vbr::BitVolume& v)
{
  std::set<Int3> out;
  for (int y = 0; y <= v.size(1); ++y)
    for (int x = 0; x <= v.size(0); ++x)
    {
      const int n = voxel(v, x - 1, y - 1, 0) + voxel(v, x, y - 1, 0) + voxel(v, x - 1, y, 0) +
        voxel(v, x, y, 0);
      if (n % 2)
        out.insert({ x, y, 0 });
    }
  return out;
}

std::vector<PixelSet> components(const PixelSet& pixels, bool eightConnected)
{
  std::vector<PixelSet> out;
  PixelSet left = pixels;
  while (!left.empty())
  {
    PixelSet comp;
    std::deque<std::pair<int, int>> queue{ *left.begin() };
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

int holeCount(const PixelSet& face)
{
  int u0 = 1 << 30, u1 = -(1 << 30), v0 = u0, v1 = u1;
  for (const auto& p : face)
  {
    u0 = std::min(u0, p.first);
    u1 = std::max(u1, p.first);
    v0 = std::min(v0, p.second);
    v1 = std::max(v1, p.second);
  }
  // Complement inside a box one pixel larger: the component touching the box border is the
  // unbounded one, every other is a hole.
  PixelSet complement;
  for (int u = u0 - 1; u <= u1 + 1; ++u)
    for (int v = v0 - 1; v <= v1 + 1; ++v)
      if (!face.count({ u, v }))
        complement.insert({ u, v });
  int holes = 0;
  for (const auto& c : components(complement, false))
  {
    const bool border = std::any_of(c.begin(),
      c.end(),
      [&](const std::pair<int, int>& p) {
        return p.first == u0 - 1 || p.first == u1 + 1 || p.second == v0 - 1 || p.second == v1 + 1;
      });
    holes += border ? 0 : 1;
  }
  return holes;
}

std::map<PlaneKey, std::vector<PixelSet>> expectedFaces(const vbr::BitVolume& v, bool merged)
{
  std::map<PlaneKey, PixelSet> surfels;
  for (int z = 0; z < v.size(2); ++z)
    for (int y = 0; y < v.size(1); ++y)
      for (int x = 0; x < v.size(0); ++x)
      {
        if (!v.get(x, y, z))
          continue;
        const Int3 p{ x, y, z };
        for (int axis = 0; axis < 3; ++axis)
          for (int sign = -1; sign <= 1; sign += 2)
          {
            Int3 n = p;
            n[axis] += sign;
            if (voxel(v, n[0], n[1], n[2]))
              continue;
            const int position = p[axis] + (sign > 0 ? 1 : 0);
            surfels[{ axis, sign, position }].insert({ p[(axis + 1) % 3], p[(axis + 2) % 3] });
          }
      }
  std::map<PlaneKey, std::vector<PixelSet>> out;
  for (const auto& entry : surfels)
    out[entry.first] = components(entry.second, merged);
  return out;
}

PixelSet rasterize(const vbr::BRep& brep, int f)
{
  const vbr::BRepFace& face = brep.faces[f];
  const int a = face.axis, ua = (a + 1) % 3, va = (a + 2) % 3;
  // Edges along v (constant u) cross the horizontal scanlines v = j + 1/2.
  std::map<int, std::vector<int>> crossings; // scanline j -> u of crossing edges
  for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
  {
    const auto pts = brep.loopPoints(l);
    for (std::size_t i = 0; i < pts.size(); ++i)
    {
      const auto& p = pts[i];
      const auto& q = pts[(i + 1) % pts.size()];
      if (p[ua] != q[ua])
        continue;
      for (int j = std::min(p[va], q[va]); j < std::max(p[va], q[va]); ++j)
        crossings[j].push_back(p[ua]);
    }
  }
  PixelSet out;
  for (auto& entry : crossings)
  {
    auto& us = entry.second;
    std::sort(us.begin(), us.end());
    for (std::size_t k = 0; k + 1 < us.size(); k += 2)
      for (int u = us[k]; u < us[k + 1]; ++u)
        out.insert({ u, entry.first });
  }
  return out;
}

long long doubledSignedArea(const vbr::BRep& brep, int l)
{
  const vbr::BRepFace& face = brep.faces[brep.loops[l].face];
  const int ua = (face.axis + 1) % 3, va = (face.axis + 2) % 3;
  const auto pts = brep.loopPoints(l);
  long long s = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
  {
    const auto& p = pts[i];
    const auto& q = pts[(i + 1) % pts.size()];
    s += static_cast<long long>(p[ua]) * q[va] - static_cast<long long>(q[ua]) * p[va];
  }
  return s;
}

} // namespace bf
