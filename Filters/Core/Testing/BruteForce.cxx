#include "BruteForce.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <deque>
#include <functional>
#include <random>
#include <thread>

namespace bf
{

vbr::Execution threadedExecution(int threads)
{
  vbr::Execution exec;
  exec.concurrency = threads;
  exec.parallelFor = [threads](
                       std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body)
  {
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t)
      workers.emplace_back(body, n * t / threads, n * (t + 1) / threads);
    for (std::thread& w : workers)
      w.join();
  };
  return exec;
}

vbr::BitVolume randomVolume(const vbr::Point3& dims, double density, unsigned seed)
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

std::vector<int> floodFillLabels(const vbr::BitVolume& v, bool vertexConnected, int& count)
{
  const int nx = v.size(0), ny = v.size(1), nz = v.size(2);
  std::vector<int> label(static_cast<std::size_t>(nx) * ny * nz, 0);
  std::vector<vbr::Point3> offsets;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
      {
        const int n = std::abs(dx) + std::abs(dy) + std::abs(dz);
        if (n > 0 && (vertexConnected || n == 1))
          offsets.push_back({ dx, dy, dz });
      }
  count = 0;
  std::vector<vbr::Point3> stack;
  auto index = [&](int x, int y, int z) { return (std::size_t(z) * ny + y) * nx + x; };
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
      {
        if (!v.get(x, y, z) || label[index(x, y, z)] != 0)
          continue;
        label[index(x, y, z)] = ++count;
        stack.push_back({ x, y, z });
        while (!stack.empty())
        {
          const vbr::Point3 p = stack.back();
          stack.pop_back();
          for (const vbr::Point3& o : offsets)
          {
            const int qx = p[0] + o[0], qy = p[1] + o[1], qz = p[2] + o[2];
            if (voxel(v, qx, qy, qz) && label[index(qx, qy, qz)] == 0)
            {
              label[index(qx, qy, qz)] = count;
              stack.push_back({ qx, qy, qz });
            }
          }
        }
      }
  return label;
}

std::set<vbr::Point3> extremeVertices(const vbr::BitVolume& v)
{
  std::set<vbr::Point3> out;
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

std::set<vbr::Point3> extremeVertices2D(const vbr::BitVolume& v)
{
  std::set<vbr::Point3> out;
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

std::map<PlaneKey, std::vector<PixelSet>> expectedFaces(const vbr::BitVolume& v, bool merged)
{
  std::map<PlaneKey, PixelSet> surfels;
  for (int z = 0; z < v.size(2); ++z)
    for (int y = 0; y < v.size(1); ++y)
      for (int x = 0; x < v.size(0); ++x)
      {
        if (!v.get(x, y, z))
          continue;
        const vbr::Point3 p{ x, y, z };
        for (int axis = 0; axis < 3; ++axis)
          for (int sign = -1; sign <= 1; sign += 2)
          {
            vbr::Point3 n = p;
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
