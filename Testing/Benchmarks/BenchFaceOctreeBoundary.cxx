// Benchmark of vtkFaceOctreeBoundaryFilter against the pipeline a VTK user runs today for a
// smooth, compact surface of voxels: vtkDiscreteFlyingEdges3D, vtkWindowedSincPolyDataFilter
// (20 iterations, pass band 0.1), then vtkQuadricDecimation, decimated as far as its distance
// to the voxel boundary stays at most this filter's (bisection on the kept fraction, before
// the timing), in turns in one process (the harness of BenchCommon.h).
//
// Distance: the two-sided Hausdorff distance between the output surface and the surfels, the
// same measure for both, by samples on both sides (twoSidedDistance below):
//  - surface to surfels: every vertex and the corners of the pieces of every triangle (each
//    polygon as its fan) halved at their longest edge until no edge exceeds 1/8 voxel, each
//    sample's distance to the nearest surfel (vbr::maximumDistanceToSurfels; beyond two
//    voxels counts as 2);
//  - surfels to surface: the 3 x 3 lattice of every surfel (centre, corners, edge midpoints),
//    each point's distance to the nearest point of the surface (vtkStaticCellLocator),
//    searched within two voxels like the other side (beyond counts as 2: an unbounded search
//    from points far from a decimated surface visited most of the locator's bins).
// The distance is the larger of the two; a value printed "(cap)" is that bound of 2, not a
// distance. The earlier one-sided measure (output vertices to the surfels only) is printed
// too: with it a decimated mesh whose large triangles cut far from the voxels in their
// interiors still "matched". Both outputs are in the same index frame (point scalars, unit
// spacing; the surfels half a voxel from the points).
//
// Pruned voxels: the bound of one voxel diagonal does not hold there. They are the object
// voxels none of whose eight corners is interior (a grid vertex whose eight voxels are all
// object voxels; see DeformedModel.h): the voxels of one-voxel crests, whose points the filter
// drops. They are found here from the voxels by that definition, their count checked against
// the filter's NumberOfPrunedVoxels, and the surfels-to-surface side is measured twice: over
// all surfels, and over the surfels of unpruned voxels only ("excl. pruned").
//
// The filter runs three times: with MergeFaceNodes, without (the default: the paper's octree
// alone), and with Simplify (BoundarySimplifier.h, its default distance: one voxel diagonal);
// the pipeline is decimated twice, to the merged output's distance and to the simplified
// output's, both excluding the pruned voxels' surfels, measured the same way on all (with all
// surfels, a crest the filter drops would set the bound at the search's cap). With
// VOXELBREP_BENCH_ONLY set, only the inputs whose name starts with its value run (e.g. "CSG": the
// CSG solid of each size). With VOXELBREP_BENCH_FORMER_MEASURE set, the pipeline is also decimated
// to the filter's vertex distance (the former measure) and its triangles printed (eight more
// decimations). With VOXELBREP_BENCH_SIMPLIFY_KEEP_POINTS set, the filter with Simplify starts from
// the paper's rule (KeepPointsInVoxels) rather than the reach rule. Per solid (the solids class:
// ball, torus, CSG of n^3 voxels): the pruned voxels, the table of the harness (median time, cells,
// peak memory of a first run of the whole pipeline, time ratio), then for both: polygons, triangles
// (each polygon counted as its fan), the distances, and polygons per object voxel (the paper's
// Table 1: 0.19-0.31 at 128^3), the ratio of the triangles, and the filter's voxels per second
// (the paper's target on 256^3: --sizes 256).
//
//   BenchFaceOctreeBoundary --help     the options, with this program's defaults
//   BenchFaceOctreeBoundary --quick    the smoke run of ctest
#include "vtkFaceOctreeBoundaryFilter.h"

#include "BitVolume.h"
#include "FaceOctreeBoundary.h"

#include "BenchCommon.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkFieldData.h"
#include "vtkGenericCell.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkQuadricDecimation.h"
#include "vtkStaticCellLocator.h"
#include "vtkWindowedSincPolyDataFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
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

/// The largest distance from the surface to the surfels, sampled at the vertices and on each
/// triangle of each polygon's fan at the corners of its pieces after halving the longest edge
/// until no edge is longer than `spacing`. Halving rather than a barycentric lattice keeps the
/// samples of a long thin triangle (decimation makes them) in proportion to its area and
/// length, not to its longest edge squared; the samples go to the distance search in batches,
/// so memory stays bounded whatever the triangles.
double surfaceDistance(const vbr::BitVolume& bits, vtkPolyData* p, double spacing)
{
  const std::vector<vbr::Vec3> v = vertices(p);
  double worst = vbr::maximumDistanceToSurfels(bits, v);
  std::vector<vbr::Vec3> batch;
  auto flush = [&]
  {
    worst = std::max(worst, vbr::maximumDistanceToSurfels(bits, batch));
    batch.clear();
  };
  auto length2 = [](const vbr::Vec3& a, const vbr::Vec3& b)
  { return std::pow(a[0] - b[0], 2) + std::pow(a[1] - b[1], 2) + std::pow(a[2] - b[2], 2); };
  std::vector<std::array<vbr::Vec3, 3>> pieces;
  vtkCellArray* polys = p->GetPolys();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
    for (vtkIdType i = 1; i + 1 < n; ++i)
    {
      pieces.push_back({ v[ids[0]], v[ids[i]], v[ids[i + 1]] });
      while (!pieces.empty())
      {
        const std::array<vbr::Vec3, 3> t = pieces.back();
        pieces.pop_back();
        int longest = 0; // the edge from corner `longest` to the next
        for (int e = 1; e < 3; ++e)
          if (length2(t[e], t[(e + 1) % 3]) > length2(t[longest], t[(longest + 1) % 3]))
            longest = e;
        const vbr::Vec3 &a = t[longest], &b = t[(longest + 1) % 3], &c = t[(longest + 2) % 3];
        if (length2(a, b) <= spacing * spacing)
        {
          batch.insert(batch.end(), { a, b, c });
          if (batch.size() >= (1u << 20))
            flush();
          continue;
        }
        const vbr::Vec3 m{ 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]) };
        pieces.push_back({ a, m, c });
        pieces.push_back({ m, b, c });
      }
    }
  flush();
  return worst;
}

/// Whether voxel (i, j, k) is an object voxel, outside the grid counting as background.
bool objectAt(const vbr::BitVolume& bits, std::int32_t i, std::int32_t j, std::int32_t k)
{
  const auto& n = bits.dims();
  return i >= 0 && j >= 0 && k >= 0 && i < n[0] && j < n[1] && k < n[2] && bits.get(i, j, k);
}

/// The pruned voxels (x fastest), by the definition on top, from the voxels alone: grid
/// vertex (i, j, k) is the corner shared by voxels i - 1..i, j - 1..j, k - 1..k.
std::vector<char> prunedVoxels(const vbr::BitVolume& bits)
{
  const auto& n = bits.dims();
  const std::size_t nx = std::size_t(n[0]) + 1, ny = std::size_t(n[1]) + 1;
  std::vector<char> interior(nx * ny * (std::size_t(n[2]) + 1), 0);
  for (std::int32_t k = 0; k <= n[2]; ++k)
    for (std::int32_t j = 0; j <= n[1]; ++j)
      for (std::int32_t i = 0; i <= n[0]; ++i)
      {
        bool all = true;
        for (int c = 0; c < 8 && all; ++c)
          all = objectAt(bits, i - 1 + (c & 1), j - 1 + ((c >> 1) & 1), k - 1 + (c >> 2));
        interior[(k * ny + j) * nx + i] = all;
      }
  std::vector<char> pruned(std::size_t(n[0]) * n[1] * n[2], 0);
  for (std::int32_t k = 0; k < n[2]; ++k)
    for (std::int32_t j = 0; j < n[1]; ++j)
      for (std::int32_t i = 0; i < n[0]; ++i)
      {
        bool any = false;
        for (int c = 0; c < 8 && !any; ++c)
          any = interior[((k + (c >> 2)) * ny + j + ((c >> 1) & 1)) * nx + i + (c & 1)];
        pruned[(std::size_t(k) * n[1] + j) * n[0] + i] = objectAt(bits, i, j, k) && !any;
      }
  return pruned;
}

/// Samples of the surfels, each flagged with whether its object voxel is pruned.
struct SurfelSamples
{
  std::vector<vbr::Vec3> points;
  std::vector<char> pruned;
  long long prunedVoxels = 0;
};

/// The 3 x 3 lattice of every surfel (the face between an object voxel and a background one,
/// outside the grid counting as background), in the core's frame.
SurfelSamples surfelSamples(const vbr::BitVolume& bits)
{
  const auto& n = bits.dims();
  const std::vector<char> pruned = prunedVoxels(bits);
  SurfelSamples out;
  out.prunedVoxels = std::count(pruned.begin(), pruned.end(), 1);
  for (std::int32_t k = -1; k < n[2]; ++k)
    for (std::int32_t j = -1; j < n[1]; ++j)
      for (std::int32_t i = -1; i < n[0]; ++i)
        for (int a = 0; a < 3; ++a)
        {
          const std::int32_t i1 = i + (a == 0), j1 = j + (a == 1), k1 = k + (a == 2);
          const bool here = objectAt(bits, i, j, k);
          if (here == objectAt(bits, i1, j1, k1))
            continue;
          const std::size_t object = here ? (std::size_t(k) * n[1] + j) * n[0] + i
                                          : (std::size_t(k1) * n[1] + j1) * n[0] + i1;
          for (int s = 0; s <= 2; ++s)
            for (int t = 0; t <= 2; ++t)
            {
              vbr::Vec3 p{ double(i), double(j), double(k) };
              p[a] += 1;
              p[(a + 1) % 3] += 0.5 * s;
              p[(a + 2) % 3] += 0.5 * t;
              out.points.push_back(p);
              out.pruned.push_back(pruned[object]);
            }
        }
  return out;
}

/// Distances between an output and the voxel boundary (voxel units).
struct Distance
{
  double vertices = 0.0;        ///< the former, one-sided measure: vertices to surfels
  double toSurfels = 0.0;       ///< surface samples to surfels
  double fromSurfels = 0.0;     ///< surfel samples to the surface
  double fromKeptSurfels = 0.0; ///< the same over the surfels of unpruned voxels
  double hausdorff() const { return std::max(this->toSurfels, this->fromSurfels); }
  /// The filter's bound (one voxel diagonal) holds everywhere but at the pruned voxels: the
  /// distance over all but their surfels.
  double hausdorffExclPruned() const { return std::max(this->toSurfels, this->fromKeptSurfels); }
};

/// The distance search's bound: a value there is "at least this", not a distance.
constexpr double searchCap = 2.0;

std::string formatDistance(double d)
{
  return formatFixed(d, 3) + (d >= searchCap ? " (cap)" : "");
}

/// The two-sided distance described on top (spacing 1/8 voxel on the surface).
Distance twoSidedDistance(const vbr::BitVolume& bits, const SurfelSamples& surfels, vtkPolyData* p)
{
  Distance d;
  d.vertices = vbr::maximumDistanceToSurfels(bits, vertices(p));
  d.toSurfels = surfaceDistance(bits, p, 0.125);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(p);
  locator->BuildLocator();
  vtkNew<vtkGenericCell> generic;
  const double cap2 = searchCap * searchCap;
  double worst2 = 0.0, worstKept2 = 0.0;
  for (std::size_t i = 0; i < surfels.points.size(); ++i)
  {
    const vbr::Vec3& s = surfels.points[i];
    double x[3] = { s[0] - 0.5, s[1] - 0.5, s[2] - 0.5 };
    double closest[3], d2 = 0.0;
    vtkIdType cell = -1;
    int sub = 0;
    int inside = 0;
    if (!locator->FindClosestPointWithinRadius(
          x, searchCap, closest, generic, cell, sub, d2, inside))
      d2 = cap2;
    d2 = std::min(d2, cap2);
    worst2 = std::max(worst2, d2);
    if (!surfels.pruned[i])
      worstKept2 = std::max(worstKept2, d2);
  }
  d.fromSurfels = std::sqrt(worst2);
  d.fromKeptSurfels = std::sqrt(worstKept2);
  return d;
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

  /// Decimates as far as the distance (the two-sided one without the pruned voxels' surfels,
  /// or the former vertex measure) stays within `bound`: 10 bisection steps on the logarithm
  /// of the kept fraction (1 down to 1e-4), so that the kept triangles are found within about
  /// 1 % whatever their number (a bisection on the reduction itself left steps of 0.4 % of the
  /// input, hundreds of triangles at 128^3).
  void decimateWithin(const vbr::BitVolume& bits,
    const SurfelSamples& surfels,
    double bound,
    bool verticesOnly = false)
  {
    auto reduction = [](double u) { return 1.0 - std::pow(10.0, -u); };
    double lo = 0.0, hi = 4.0;
    for (int i = 0; i < 10; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      this->decimate->SetTargetReduction(reduction(mid));
      this->decimate->Update();
      vtkPolyData* out = this->decimate->GetOutput();
      const double d = verticesOnly ? vbr::maximumDistanceToSurfels(bits, vertices(out))
                                    : twoSidedDistance(bits, surfels, out).hausdorffExclPruned();
      (d <= bound ? lo : hi) = mid;
    }
    this->decimate->SetTargetReduction(reduction(lo));
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

/// One output's polygons, triangles, distances and polygons per voxel.
std::vector<std::string> outputRow(const char* who, vtkPolyData* out, const Distance& d, double v)
{
  return { who,
    formatCount(out->GetNumberOfCells()),
    formatCount(fanTriangles(out)),
    formatDistance(d.hausdorff()),
    formatDistance(d.hausdorffExclPruned()),
    formatDistance(d.toSurfels),
    formatDistance(d.fromSurfels),
    formatDistance(d.fromKeptSurfels),
    formatDistance(d.vertices),
    formatFixed(double(out->GetNumberOfCells()) / v, 3) };
}

void printOutputs(const Input& in,
  const vbr::BitVolume& bits,
  const SurfelSamples& surfels,
  vtkPolyData* ours,
  vtkPolyData* octreeOnly,
  vtkPolyData* simplified,
  vtkPolyData* theirs,
  vtkPolyData* theirsAtSimplified,
  double filterSeconds,
  double simplifiedSeconds,
  double theirsAtSimplifiedSeconds)
{
  const double voxels = double(std::max<std::size_t>(bits.count(), 1));
  const Distance mine = twoSidedDistance(bits, surfels, ours);
  const Distance unmerged = twoSidedDistance(bits, surfels, octreeOnly);
  const Distance simple = twoSidedDistance(bits, surfels, simplified);
  const Distance peer = twoSidedDistance(bits, surfels, theirs);
  const Distance peerAtSimplified = twoSidedDistance(bits, surfels, theirsAtSimplified);
  Table table({ "output",
    "polygons",
    "triangles",
    "Hausdorff",
    "excl. pruned",
    "to surfels",
    "from surfels",
    "from excl. pruned",
    "vertices (old)",
    "polygons/voxel" });
  table.add(outputRow("FaceOctreeBoundary", ours, mine, voxels));
  table.add(outputRow("FaceOctreeBoundary (octree only)", octreeOnly, unmerged, voxels));
  table.add(outputRow("FaceOctreeBoundary (Simplify)", simplified, simple, voxels));
  table.add(outputRow("DFE+WindowedSinc+QDec", theirs, peer, voxels));
  table.add(
    outputRow("DFE+WindowedSinc+QDec (at Simplify)", theirsAtSimplified, peerAtSimplified, voxels));
  table.print();
  std::printf("\nSimplify: triangles pipeline / filter %s at distance %s / %s, time filter / "
              "pipeline %s\n",
    formatRatio(
      double(fanTriangles(theirsAtSimplified)) / double(std::max(1LL, fanTriangles(simplified))))
      .c_str(),
    formatFixed(peerAtSimplified.hausdorffExclPruned(), 3).c_str(),
    formatFixed(simple.hausdorffExclPruned(), 3).c_str(),
    formatRatio(simplifiedSeconds / std::max(1e-9, theirsAtSimplifiedSeconds)).c_str());
  if (peer.hausdorffExclPruned() > mine.hausdorffExclPruned())
    std::printf("\n(the pipeline is farther than the filter even undecimated)\n");
  std::printf("\ntriangles: pipeline / filter %s | filter %s M voxels/s (of %s voxels)\n\n",
    formatRatio(double(fanTriangles(theirs)) / double(std::max(1LL, fanTriangles(ours)))).c_str(),
    formatFixed(double(in.voxelCount()) / std::max(1e-9, filterSeconds) / 1e6, 1).c_str(),
    formatCount(static_cast<long long>(in.voxelCount())).c_str());
}

/// Set when the filter's NumberOfPrunedVoxels differs from the count here: the exit code is
/// then 1, so that the smoke run of ctest fails.
bool prunedMismatch = false;

/// Prints the pruned voxels found here, and a mismatch line when the filter reports another
/// count.
void checkPrunedVoxels(const SurfelSamples& surfels, vtkPolyData* out)
{
  vtkDataArray* reported = out->GetFieldData()->GetArray("NumberOfPrunedVoxels");
  const long long filter = reported ? static_cast<long long>(reported->GetTuple1(0)) : -1;
  const long long samples = std::count(surfels.pruned.begin(), surfels.pruned.end(), 1);
  std::printf("pruned voxels (no interior corner): %s, their surfels %s of %s\n",
    formatCount(surfels.prunedVoxels).c_str(),
    formatCount(samples / 9).c_str(),
    formatCount(static_cast<long long>(surfels.points.size() / 9)).c_str());
  prunedMismatch = prunedMismatch || filter != surfels.prunedVoxels;
  if (filter != surfels.prunedVoxels)
    std::printf("MISMATCH: the filter reports NumberOfPrunedVoxels %s, the benchmark counts %s\n",
      formatCount(filter).c_str(),
      formatCount(surfels.prunedVoxels).c_str());
}

void benchmarkInput(const Input& in, const Options& options, Report& report)
{
  const char* only = std::getenv("VOXELBREP_BENCH_ONLY");
  if (only && in.name.rfind(only, 0) != 0)
    return;
  Report::printInput(in);
  const vbr::BitVolume bits = bitsOf(in);
  vtkNew<vtkImageData> image = maskImageOf(in);
  forEachBackend(options,
    [&](const std::string& backend)
    {
      vtkNew<vtkFaceOctreeBoundaryFilter> filter, octreeOnly, simplified;
      filter->SetInputData(image);
      filter->MergeFaceNodesOn();
      filter->Update();
      octreeOnly->SetInputData(image);
      octreeOnly->MergeFaceNodesOff();
      octreeOnly->Update();
      simplified->SetInputData(image);
      simplified->SimplifyOn();
      if (std::getenv("VOXELBREP_BENCH_SIMPLIFY_KEEP_POINTS"))
      {
        simplified->KeepPointsInVoxelsOn();
        std::printf("Simplify starts from the paper's rule (KeepPointsInVoxels)\n");
      }
      simplified->Update();
      const SurfelSamples surfels = surfelSamples(bits);
      checkPrunedVoxels(surfels, filter->GetOutput());
      Pipeline pipeline(image);
      pipeline.decimateWithin(
        bits, surfels, twoSidedDistance(bits, surfels, filter->GetOutput()).hausdorffExclPruned());
      Pipeline pipelineAtSimplified(image);
      pipelineAtSimplified.decimateWithin(bits,
        surfels,
        twoSidedDistance(bits, surfels, simplified->GetOutput()).hausdorffExclPruned());
      if (std::getenv("VOXELBREP_BENCH_FORMER_MEASURE"))
      {
        // The former measure, for comparison with earlier reports: output vertices only.
        Pipeline former(image);
        const double bound = vbr::maximumDistanceToSurfels(bits, vertices(filter->GetOutput()));
        former.decimateWithin(bits, surfels, bound, true);
        former.decimate->Update();
        std::printf("former measure (vertices to surfels): filter %s, pipeline decimated to it: "
                    "%s triangles\n",
          formatFixed(bound, 3).c_str(),
          formatCount(fanTriangles(former.decimate->GetOutput())).c_str());
      }
      vtkAlgorithm* f = filter;
      vtkAlgorithm* g = octreeOnly;
      vtkAlgorithm* h = simplified;
      const std::vector<Contender> contenders{
        contenderOf(
          "FaceOctreeBoundary", Role::Tool, [f] { update(f); }, filter->GetOutput()),
        contenderOf(
          "FaceOctreeBoundary (octree only)",
          Role::Tool,
          [g] { update(g); },
          octreeOnly->GetOutput()),
        contenderOf(
          "FaceOctreeBoundary (Simplify)", Role::Tool, [h] { update(h); }, simplified->GetOutput()),
        contenderOf(
          "DFE+WindowedSinc+QDec",
          Role::Peer,
          [&pipeline] { pipeline.run(); },
          pipeline.decimate->GetOutput()),
        contenderOf(
          "DFE+WindowedSinc+QDec (at Simplify)",
          Role::Peer,
          [&pipelineAtSimplified] { pipelineAtSimplified.run(); },
          pipelineAtSimplified.decimate->GetOutput()),
      };
      const std::vector<Measured> rows = timeInTurns(options.repeat, contenders);
      report.add(in, backend, rows);
      printOutputs(in,
        bits,
        surfels,
        filter->GetOutput(),
        octreeOnly->GetOutput(),
        simplified->GetOutput(),
        pipeline.decimate->GetOutput(),
        pipelineAtSimplified.decimate->GetOutput(),
        findMeasured(rows, "FaceOctreeBoundary")->median,
        findMeasured(rows, "FaceOctreeBoundary (Simplify)")->median,
        findMeasured(rows, "DFE+WindowedSinc+QDec (at Simplify)")->median);
    });
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  options.inputs.classes = { "solids" };
  options.inputs.sizes = { 128 };
  options.repeat = 3;
  const int code = runBenchmark(argc,
    argv,
    "BenchFaceOctreeBoundary",
    "vtkFaceOctreeBoundaryFilter against vtkDiscreteFlyingEdges3D -> "
    "vtkWindowedSincPolyDataFilter -> vtkQuadricDecimation at the same distance",
    options,
    benchmarkInput);
  return code != 0 ? code : (prunedMismatch ? 1 : 0);
}
