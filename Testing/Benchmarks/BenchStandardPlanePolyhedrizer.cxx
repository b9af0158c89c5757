// Benchmark of vtkStandardPlanePolyhedrizer: faces and time on the paper's sphere, on balls,
// on a twice-rotated cube (a hexahedron, the intersection of six half-spaces) and on real
// objects, next to vtkDiscreteFlyingEdges3D (the triangles a user would get instead) on the
// same input in the same process.
//
//   BenchStandardPlanePolyhedrizer [--radii 8,16,32,64] [--repeat 3] [--data DIR] [--no-data]
//
// Per input: surfels, faces (the paper's growth alone, then with the move to larger faces,
// the default, then with the merging pass too), face sizes, the number of faces of at most
// 5 surfels, the time of the surfel graph and of the faces (core, median), the surfels per
// second, whether the reversion from the faces gives the voxels back, the whole filter
// (standard faces and the reversion), and the peer's triangles and time.
#include "vtkStandardPlanePolyhedrizer.h"

#include "Polyhedrization.h"
#include "SurfelGraph.h"

#include "BenchCommon.h"

#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{

using namespace vbrbench;

Input ball(const std::string& name, long radiusSquared)
{
  int r = 0;
  while (long(r) * r <= radiusSquared)
    ++r;
  const int n = 2 * r + 1, c = r;
  Input in = emptyInput(name, { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        if (long(x - c) * (x - c) + long(y - c) * (y - c) + long(z - c) * (z - c) <= radiusSquared)
          in.at(x, y, z) = 1;
  return in;
}

/// A hexahedron, the intersection of six half-spaces: |n_i . centre| <= h_i for the
/// orthogonal integer normals (2, 2, 1), (-2, 1, 2), (1, -2, 2) (a box turned about two
/// axes) and h = (17, 17, 29), which gives the 1,962 surfels of the paper's hexahedron
/// (whose exact half-spaces the paper does not give).
Input hexahedron()
{
  const int n = 33, c = 16;
  const int normals[3][3] = { { 2, 2, 1 }, { -2, 1, 2 }, { 1, -2, 2 } };
  const int half[3] = { 17, 17, 29 };
  Input in = emptyInput("hexahedron", { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        bool inside = true;
        for (int i = 0; i < 3; ++i)
          inside = inside &&
            std::abs(normals[i][0] * (x - c) + normals[i][1] * (y - c) + normals[i][2] * (z - c)) <=
              half[i];
        in.at(x, y, z) = inside;
      }
  return in;
}

std::size_t faceCount(const vbr::SurfelGraph& g, vbr::PolyhedrizationOptions o)
{
  vbr::Polyhedron p;
  vbr::polyhedrize(g, o, vbr::Execution(), p);
  return p.faces.size();
}

void run(const Input& in, int repeat)
{
  const vbr::BitVolume voxels = bitsOf(in);
  vbr::SurfelGraph graph;
  vbr::Polyhedron poly;
  const vbr::PolyhedrizationOptions defaults;
  const double tGraph =
    medianSeconds(repeat, [&] { vbr::buildSurfelGraph(voxels, vbr::Execution(), graph); });
  const double tFaces =
    medianSeconds(repeat, [&] { vbr::polyhedrize(graph, defaults, vbr::Execution(), poly); });
  vbr::PolyhedrizationOptions paper;
  paper.moveToLargerFaces = false;
  vbr::PolyhedrizationOptions merged;
  merged.mergeFaces = true;
  std::size_t smallest = graph.size(), largest = 0, small = 0;
  for (const auto& f : poly.faces)
  {
    smallest = std::min(smallest, f.surfels.size());
    largest = std::max(largest, f.surfels.size());
    small += f.surfels.size() <= 5;
  }
  std::vector<vbr::FaceOutline> outlines;
  for (const auto& f : poly.faces)
  {
    vbr::FaceOutline o;
    o.plane = f.plane;
    for (std::uint32_t v : f.loop)
      o.loop.push_back(graph.vertexPointel[v]);
    outlines.push_back(std::move(o));
  }
  std::vector<vbr::Surfel> surfels;
  vbr::BitVolume back;
  const std::string error = vbr::revert(outlines, voxels.dims(), surfels, back);
  const bool exact = error.empty() && back == voxels;

  vtkNew<vtkImageData> image = imageOf(in);
  vtkNew<vtkStandardPlanePolyhedrizer> filter;
  filter->SetInputData(image);
  const long long filterPeak = peakBytesOf([&] { update(filter); }); // a first run
  const double tFilter = medianSeconds(repeat, [&] { update(filter); });
  vtkNew<vtkDiscreteFlyingEdges3D> peer;
  peer->SetInputData(image);
  peer->SetValue(0, 1);
  peer->ComputeNormalsOff();
  peer->ComputeGradientsOff();
  const long long peerPeak = peakBytesOf([&] { update(peer); });
  const double tPeer = medianSeconds(repeat, [&] { update(peer); });
  const long long cells = filter->GetOutput()->GetNumberOfCells();
  const long long triangles = peer->GetOutput()->GetNumberOfCells();
  const double mean = poly.faces.empty() ? 0.0 : double(graph.size()) / poly.faces.size();
  std::printf("%-22s %8zu surfels | faces paper %6zu default %6zu merged %6zu | size min %zu "
              "mean %.1f max %zu, <=5: %zu | graph %7.2f faces %7.2f ms %5.2f M surfels/s | "
              "reversion %s | filter %7.2f ms | DiscreteFlyingEdges3D %8lld triangles %7.2f ms | "
              "peak bytes per surfel: filter %.0f (%.0f per output cell), DFE %.0f per triangle\n",
    in.name.c_str(),
    graph.size(),
    faceCount(graph, paper),
    poly.faces.size(),
    faceCount(graph, merged),
    smallest,
    mean,
    largest,
    small,
    1e3 * tGraph,
    1e3 * tFaces,
    graph.size() / (tGraph + tFaces) / 1e6,
    exact ? "exact" : ("WRONG " + error).c_str(),
    1e3 * tFilter,
    triangles,
    1e3 * tPeer,
    double(filterPeak) / double(std::max<std::size_t>(graph.size(), 1)),
    double(filterPeak) / double(std::max(cells, 1LL)),
    double(peerPeak) / double(std::max(triangles, 1LL)));
}

} // namespace

int main(int argc, char* argv[])
{
  Arguments args;
  args.list = { 8, 16, 32, 64 };
  args.repeat = 3;
  args.dataDir = VOXELBREP_DEFAULT_DATA_DIR;
  if (!parseArguments(argc, argv, "radii", args))
    return 2;
  run(ball("paper sphere r2<=240", 240), args.repeat);
  run(hexahedron(), args.repeat);
  for (int r : args.list)
    run(ball("ball r=" + std::to_string(r), long(r) * r), args.repeat);
  if (!args.data)
    return 0;
  struct Real
  {
    const char* file;
    std::array<int, 3> dims;
    int lo, hi;
    const char* name;
  };
  const Real objects[] = {
    { "/dgtal_al/dgtal_al_100x100x100_uint8.raw", { 100, 100, 100 }, 1, 1, "Al (v=1)" },
    { "/lobster/lobster_301x324x56_uint8.raw", { 301, 324, 56 }, 40, 255, "lobster>=40" },
    { "/engine/engine_256x256x128_uint8.raw", { 256, 256, 128 }, 130, 255, "engine>=130" },
  };
  for (const Real& r : objects)
  {
    Input in;
    if (readThresholded(args.dataDir + r.file, r.dims, r.lo, r.hi, r.name, in))
      run(in, args.repeat);
  }
  return 0;
}
