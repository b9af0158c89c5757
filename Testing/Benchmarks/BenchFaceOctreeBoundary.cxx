// Benchmark of vtkFaceOctreeBoundaryFilter against the pipeline a VTK user runs today for a
// smooth, compact surface of voxels: vtkDiscreteFlyingEdges3D, vtkWindowedSincPolyDataFilter
// (20 iterations, pass band 0.1), then vtkQuadricDecimation, decimated as far as its distance
// to the voxel boundary stays at most this filter's (bisection on the target reduction, before
// the timing), in turns in one process (the harness of BenchCommon.h).
//
// Distance: the largest distance from an output vertex to the surfels (the same measure for
// both, vbr::maximumDistanceToSurfels; vertices beyond two voxels count as 2). Both outputs
// are in the same index frame (point scalars, unit spacing; the surfels half a voxel from the
// points). Per solid (the solids class: ball, torus, CSG of n^3 voxels): the table of the
// harness (median time, cells, peak memory of a first run of the whole pipeline, time ratio),
// then for both: polygons, triangles (each polygon counted as its fan), the distance, and
// polygons per object voxel (the paper's Table 1: 0.19-0.31 at 128^3), the ratio of the
// triangles, and the filter's voxels per second (the paper's target on 256^3: --sizes 256).
//
//   BenchFaceOctreeBoundary --help     the options, with this program's defaults
//   BenchFaceOctreeBoundary --quick    the smoke run of ctest
#include "vtkFaceOctreeBoundaryFilter.h"

#include "BitVolume.h"
#include "FaceOctreeBoundary.h"

#include "BenchCommon.h"

#include "vtkCellArray.h"
#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkQuadricDecimation.h"
#include "vtkWindowedSincPolyDataFilter.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace
{

using namespace vbrbench;

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

long long fanTriangles(vtkPolyData* p)
{
  long long n = 0;
  vtkCellArray* polys = p->GetPolys();
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
    n += polys->GetCellSize(c) - 2;
  return n;
}

/// vtkDiscreteFlyingEdges3D -> vtkWindowedSincPolyDataFilter -> vtkQuadricDecimation.
struct Pipeline
{
  vtkNew<vtkDiscreteFlyingEdges3D> contour;
  vtkNew<vtkWindowedSincPolyDataFilter> smooth;
  vtkNew<vtkQuadricDecimation> decimate;

  explicit Pipeline(vtkImageData* image)
  {
    this->contour->SetInputData(image);
    this->contour->SetValue(0, 1);
    this->contour->ComputeNormalsOff();
    this->contour->ComputeGradientsOff();
    this->smooth->SetInputConnection(this->contour->GetOutputPort());
    this->smooth->SetNumberOfIterations(20);
    this->smooth->SetPassBand(0.1);
    this->smooth->NonManifoldSmoothingOn();
    this->smooth->NormalizeCoordinatesOn();
    this->decimate->SetInputConnection(this->smooth->GetOutputPort());
  }

  /// Decimates as far as the distance stays within `bound` (8 bisection steps).
  void decimateWithin(const vbr::BitVolume& bits, double bound)
  {
    double lo = 0.0, hi = 0.995;
    for (int i = 0; i < 8; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      this->decimate->SetTargetReduction(mid);
      this->decimate->Update();
      const double d = vbr::maximumDistanceToSurfels(bits, vertices(this->decimate->GetOutput()));
      (d <= bound ? lo : hi) = mid;
    }
    this->decimate->SetTargetReduction(lo);
  }

  void run()
  {
    this->contour->Modified();
    this->decimate->Update();
  }
};

Contender contenderOf(const char* name, Role role, std::function<void()> run, vtkPolyData* out)
{
  return { name, role, "", std::move(run), [out] {
            return static_cast<long long>(out->GetNumberOfCells());
          } };
}

/// One output's polygons, triangles, distance and polygons per voxel.
std::vector<std::string> outputRow(const char* who, vtkPolyData* out, double distance, double v)
{
  return { who,
    formatCount(out->GetNumberOfCells()),
    formatCount(fanTriangles(out)),
    formatFixed(distance, 3),
    formatFixed(double(out->GetNumberOfCells()) / v, 3) };
}

void printOutputs(const Input& in,
  const vbr::BitVolume& bits,
  vtkPolyData* ours,
  vtkPolyData* theirs,
  double filterSeconds)
{
  const double voxels = double(std::max<std::size_t>(bits.count(), 1));
  const double mine = vbr::maximumDistanceToSurfels(bits, vertices(ours));
  const double peer = vbr::maximumDistanceToSurfels(bits, vertices(theirs));
  Table table({ "output", "polygons", "triangles", "distance", "polygons/voxel" });
  table.add(outputRow("FaceOctreeBoundary", ours, mine, voxels));
  table.add(outputRow("DFE+WindowedSinc+QDec", theirs, peer, voxels));
  table.print();
  if (peer > mine)
    std::printf("\n(the pipeline is farther than the filter even undecimated)\n");
  std::printf("\ntriangles: pipeline / filter %s | filter %s M voxels/s (of %s voxels)\n\n",
    formatRatio(double(fanTriangles(theirs)) / double(std::max(1LL, fanTriangles(ours)))).c_str(),
    formatFixed(double(in.voxelCount()) / std::max(1e-9, filterSeconds) / 1e6, 1).c_str(),
    formatCount(static_cast<long long>(in.voxelCount())).c_str());
}

void benchmarkInput(const Input& in, const Options& options, Report& report)
{
  Report::printInput(in);
  const vbr::BitVolume bits = bitsOf(in);
  vtkNew<vtkImageData> image = maskImageOf(in);
  forEachBackend(options,
    [&](const std::string& backend)
    {
      vtkNew<vtkFaceOctreeBoundaryFilter> filter;
      filter->SetInputData(image);
      filter->Update();
      Pipeline pipeline(image);
      pipeline.decimateWithin(
        bits, vbr::maximumDistanceToSurfels(bits, vertices(filter->GetOutput())));
      vtkAlgorithm* f = filter;
      const std::vector<Contender> contenders{
        contenderOf(
          "FaceOctreeBoundary", Role::Tool, [f] { update(f); }, filter->GetOutput()),
        contenderOf(
          "DFE+WindowedSinc+QDec",
          Role::Peer,
          [&pipeline] { pipeline.run(); },
          pipeline.decimate->GetOutput()),
      };
      const std::vector<Measured> rows = timeInTurns(options.repeat, contenders);
      report.add(in, backend, rows);
      printOutputs(in,
        bits,
        filter->GetOutput(),
        pipeline.decimate->GetOutput(),
        findMeasured(rows, "FaceOctreeBoundary")->median);
    });
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  options.inputs.classes = { "solids" };
  options.inputs.sizes = { 128 };
  options.repeat = 3;
  return runBenchmark(argc,
    argv,
    "BenchFaceOctreeBoundary",
    "vtkFaceOctreeBoundaryFilter against vtkDiscreteFlyingEdges3D -> "
    "vtkWindowedSincPolyDataFilter -> vtkQuadricDecimation at the same distance",
    options,
    benchmarkInput);
}
