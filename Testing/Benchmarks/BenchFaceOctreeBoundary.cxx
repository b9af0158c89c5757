// Benchmark of vtkFaceOctreeBoundaryFilter against the pipeline a VTK user runs today for a
// smooth, compact surface of voxels: vtkDiscreteFlyingEdges3D, vtkWindowedSincPolyDataFilter
// (20 iterations, pass band 0.1), then vtkQuadricDecimation, decimated as far as its distance
// to the voxel boundary stays at most this filter's (bisection on the target reduction).
//
// Distance: the largest distance from an output vertex to the surfels (the same measure for
// both, vbr::maximumDistanceToSurfels; vertices beyond two voxels count as 2). Both outputs
// are in the same index frame (point scalars, unit spacing; the surfels half a voxel from the
// points). Reported per solid: cells, triangles (each polygon counted as its fan), median
// time, the peak memory of a first run, the distance, and this filter's polygons per voxel
// (the paper's Table 1: 0.19-0.31 at 128^3), then voxels per second on a 256^3 ball.
//
// Run by hand: BenchFaceOctreeBoundary [--sizes 128] [--repeat 3]
#include "BenchCommon.h"

#include "FaceOctreeBoundary.h"
#include "vtkFaceOctreeBoundaryFilter.h"

#include "vtkCellArray.h"
#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkFieldData.h"
#include "vtkPolyData.h"
#include "vtkQuadricDecimation.h"
#include "vtkSmartPointer.h"
#include "vtkWindowedSincPolyDataFilter.h"

#include <cmath>
#include <cstdio>

namespace
{

using vbrbench::Input;

Input solid(const std::string& name, int n, const std::function<bool(double, double, double)>& f)
{
  Input in = vbrbench::emptyInput(name, { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        in.at(x, y, z) = f((x + 0.5) / n - 0.5, (y + 0.5) / n - 0.5, (z + 0.5) / n - 0.5);
  return in;
}

std::vector<Input> solids(int n)
{
  auto sq = [](double x) { return x * x; };
  std::vector<Input> out;
  out.push_back(solid(
    "ball", n, [&](double x, double y, double z) { return sq(x) + sq(y) + sq(z) < sq(0.38); }));
  out.push_back(solid("torus",
    n,
    [&](double x, double y, double z)
    { return sq(std::sqrt(sq(x) + sq(y)) - 0.27) + sq(z) < sq(0.13); }));
  out.push_back(solid("csg",
    n,
    [&](double x, double y, double z)
    {
      const bool box = std::abs(x + 0.05) < 0.3 && std::abs(y) < 0.2 && std::abs(z) < 0.3;
      const bool cylinder = sq(x - 0.2) + sq(y) < sq(0.18) && std::abs(z) < 0.4;
      const bool hole = sq(x + 0.15) + sq(y) + sq(z - 0.3) < sq(0.2);
      return (box || cylinder) && !hole;
    }));
  return out;
}

/// Output vertices in the core's frame (voxel i spans [i, i + 1]).
std::vector<vbr::Vec3> vertices(vtkPolyData* p)
{
  std::vector<vbr::Vec3> out(std::size_t(p->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < p->GetNumberOfPoints(); ++i)
  {
    double x[3];
    p->GetPoint(i, x);
    out[i] = { x[0] + 0.5, x[1] + 0.5, x[2] + 0.5 };
  }
  return out;
}

vtkIdType fanTriangles(vtkPolyData* p)
{
  vtkIdType n = 0;
  vtkCellArray* polys = p->GetPolys();
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
    n += polys->GetCellSize(c) - 2;
  return n;
}

struct Row
{
  vtkIdType cells = 0, triangles = 0;
  double seconds = 0, distance = 0;
  long long peak = 0;
};

Row runFilter(const Input& in, vtkImageData* image, int repeat, const vbr::BitVolume& bits)
{
  vtkNew<vtkFaceOctreeBoundaryFilter> f;
  f->SetInputData(image);
  Row r;
  r.peak = vbrbench::peakBytesOf([&] { f->Update(); });
  r.seconds = vbrbench::medianSeconds(repeat, [&] { vbrbench::update(f); });
  vtkPolyData* out = f->GetOutput();
  r.cells = out->GetNumberOfCells();
  r.triangles = fanTriangles(out);
  r.distance = vbr::maximumDistanceToSurfels(bits, vertices(out));
  (void)in;
  return r;
}

/// The pipeline, decimated as far as its distance stays within `bound`.
Row runPipeline(vtkImageData* image, int repeat, const vbr::BitVolume& bits, double bound)
{
  vtkNew<vtkDiscreteFlyingEdges3D> fe;
  fe->SetInputData(image);
  fe->SetValue(0, 1);
  fe->ComputeNormalsOff();
  fe->ComputeGradientsOff();
  vtkNew<vtkWindowedSincPolyDataFilter> smooth;
  smooth->SetInputConnection(fe->GetOutputPort());
  smooth->SetNumberOfIterations(20);
  smooth->SetPassBand(0.1);
  smooth->NonManifoldSmoothingOn();
  smooth->NormalizeCoordinatesOn();
  vtkNew<vtkQuadricDecimation> decimate;
  decimate->SetInputConnection(smooth->GetOutputPort());
  smooth->Update();
  double lo = 0.0, hi = 0.995;
  for (int i = 0; i < 8; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    decimate->SetTargetReduction(mid);
    decimate->Update();
    (vbr::maximumDistanceToSurfels(bits, vertices(decimate->GetOutput())) <= bound ? lo : hi) = mid;
  }
  decimate->SetTargetReduction(lo);
  Row r;
  r.peak = vbrbench::peakBytesOf([&] { decimate->Update(); });
  r.seconds = vbrbench::medianSeconds(repeat,
    [&]
    {
      fe->Modified();
      decimate->Update();
    });
  vtkPolyData* out = decimate->GetOutput();
  r.cells = out->GetNumberOfCells();
  r.triangles = fanTriangles(out);
  r.distance = vbr::maximumDistanceToSurfels(bits, vertices(out));
  return r;
}

void print(const char* solidName, const char* who, const Row& r, double voxels)
{
  std::printf("%-6s %-22s %9lld %9lld %9.3f %9.1f %8.3f %7.3f\n",
    solidName,
    who,
    (long long)r.cells,
    (long long)r.triangles,
    r.seconds * 1e3,
    r.peak / 1048576.0,
    r.distance,
    r.cells / voxels);
}

} // namespace

int main(int argc, char* argv[])
{
  vbrbench::Arguments args;
  args.list = { 128 };
  args.repeat = 3;
  if (!vbrbench::parseArguments(argc, argv, "sizes", args))
    return 1;
  std::printf("%-6s %-22s %9s %9s %9s %9s %8s %7s\n",
    "solid",
    "method",
    "cells",
    "triangles",
    "ms",
    "peak MiB",
    "distance",
    "cells/v");
  for (int n : args.list)
    for (const Input& in : solids(n))
    {
      vtkNew<vtkImageData> image = vbrbench::imageOf(in);
      const vbr::BitVolume bits = vbrbench::bitsOf(in);
      const double voxels = double(bits.count());
      const Row mine = runFilter(in, image, args.repeat, bits);
      const std::string name = in.name + std::to_string(n);
      print(name.c_str(), "FaceOctreeBoundary", mine, voxels);
      const Row theirs = runPipeline(image, args.repeat, bits, mine.distance);
      print(name.c_str(), "DFE+WindowedSinc+QDec", theirs, voxels);
      std::printf("%-6s triangles ratio %.2f, time ratio %.2f\n",
        name.c_str(),
        double(theirs.triangles) / std::max<vtkIdType>(1, mine.triangles),
        theirs.seconds / std::max(1e-9, mine.seconds));
    }
  const int big = args.list.empty() ? 256 : std::max(256, 2 * args.list.front());
  if (args.list.front() >= 64)
  {
    const Input ball = solids(big).front();
    vtkNew<vtkImageData> image = vbrbench::imageOf(ball);
    vtkNew<vtkFaceOctreeBoundaryFilter> f;
    f->SetInputData(image);
    const double s = vbrbench::medianSeconds(args.repeat, [&] { vbrbench::update(f); });
    std::printf("ball%d: %.3f s, %.1f M voxels/s\n", big, s, double(big) * big * big / s / 1e6);
  }
  return 0;
}
