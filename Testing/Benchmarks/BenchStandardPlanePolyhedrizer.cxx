// Benchmark of vtkStandardPlanePolyhedrizer: faces and time on the paper's sphere, on balls,
// on a twice-rotated cube (a hexahedron, the intersection of six half-spaces), on real objects,
// on porous volumes, on 50 % noise and on one-voxel-thin spirals of several sizes (the class
// `spiral`, built here: long thin faces whose polygons of normals are thin; sizes 32, 64 and
// 96, 128 too with --large, 24 with --quick), next to vtkDiscreteFlyingEdges3D (the triangles
// a user would get instead) on the same input, in turns in the same process (the harness of
// BenchCommon.h).
//
// Per input: surfels, faces (the paper's growth alone, then with the move to larger faces,
// the default, then with the merging pass too), face sizes, the number of faces of at most
// 5 surfels, the time of the surfel graph (one thread) and of the faces (core, on the backend's
// threads: the boundary components are grown concurrently), the surfels per
// second of the core and of the whole filter, whether the reversion from the faces gives the
// voxels back (WRONG otherwise), the whole filter (standard faces and the reversion) and the
// peer.
//
//   BenchStandardPlanePolyhedrizer --help     the options, with this program's defaults
#include "vtkStandardPlanePolyhedrizer.h"

#include "Polyhedrization.h"
#include "SurfelGraph.h"

#include "BenchCommon.h"

#include "vtkDataArray.h"
#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace
{

using namespace vbrbench;

std::size_t faceCount(const vbr::SurfelGraph& g, vbr::PolyhedrizationOptions o)
{
  vbr::Polyhedron p;
  vbr::polyhedrize(g, o, vbr::Execution(), p);
  return p.faces.size();
}

/// The core's execution on the current vtkSMPTools backend, as the filter runs it (Sequential:
/// one thread; STDThread: the boundary components grown concurrently).
vbr::Execution backendExecution()
{
  vbr::Execution exec;
  exec.concurrency = std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
  if (exec.concurrency > 1)
    exec.parallelFor =
      [](std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body)
    { vtkSMPTools::For(std::int64_t(0), n, [&](std::int64_t b, std::int64_t e) { body(b, e); }); };
  return exec;
}

/// The reversion from the faces' outlines gives the voxels back: empty, else what is wrong.
std::string reversionError(const vbr::SurfelGraph& graph,
  const vbr::Polyhedron& poly,
  const vbr::BitVolume& voxels)
{
  std::vector<vbr::FaceOutline> outlines;
  for (const auto& f : poly.faces)
  {
    vbr::FaceOutline o;
    o.plane = f.plane;
    for (std::uint32_t v : f.loop)
      o.loop.push_back(graph.vertexPointel[v]);
    outlines.push_back(std::move(o));
  }
  vbr::BitVolume back;
  const std::string error = vbr::revert(outlines, voxels.dims(), back);
  return !error.empty() ? error : (back == voxels ? "" : "the voxels differ");
}

/// Faces with the paper's growth, the default and merging; sizes; the reversion.
void printFaces(const vbr::SurfelGraph& graph, const vbr::Polyhedron& poly, const vbr::BitVolume& v)
{
  vbr::PolyhedrizationOptions paper, merged;
  paper.moveToLargerFaces = false;
  merged.mergeFaces = true;
  std::size_t smallest = graph.size(), largest = 0, small = 0;
  for (const auto& f : poly.faces)
  {
    smallest = std::min(smallest, f.surfels.size());
    largest = std::max(largest, f.surfels.size());
    small += f.surfels.size() <= 5;
  }
  const std::string error = reversionError(graph, poly, v);
  std::printf("surfels %s | faces: paper %s, default %s, merged %s | size min %zu mean %.1f max "
              "%zu, <=5: %zu | reversion %s\n",
    formatCount(static_cast<long long>(graph.size())).c_str(),
    formatCount(static_cast<long long>(faceCount(graph, paper))).c_str(),
    formatCount(static_cast<long long>(poly.faces.size())).c_str(),
    formatCount(static_cast<long long>(faceCount(graph, merged))).c_str(),
    smallest,
    poly.faces.empty() ? 0.0 : double(graph.size()) / poly.faces.size(),
    largest,
    small,
    error.empty() ? "exact" : ("WRONG " + error).c_str());
}

/// Surfels per second of the core (graph + faces) and of the whole filter; bytes per surfel.
void printThroughput(std::size_t surfels, const std::vector<Measured>& rows)
{
  const Measured* graph = findMeasured(rows, "surfel graph");
  const Measured* faces = findMeasured(rows, "faces");
  const Measured* filter = findMeasured(rows, "filter");
  const Measured* peer = findMeasured(rows, "DiscreteFlyingEdges3D");
  std::printf("M surfels/s: core %.2f, filter %.2f | peak bytes per surfel: filter %.0f, "
              "DiscreteFlyingEdges3D %.0f\n\n",
    surfels / (graph->median + faces->median) / 1e6,
    surfels / filter->median / 1e6,
    double(filter->peakBytes) / double(std::max<std::size_t>(surfels, 1)),
    double(peer->peakBytes) / double(std::max<std::size_t>(surfels, 1)));
}

/// Labels mode on a label map (each label its own object), against Flying Edges with one
/// contour value per label.
void addLabelContenders(const Input& in,
  vtkImageData* labels,
  vtkStandardPlanePolyhedrizer* filter,
  vtkDiscreteFlyingEdges3D* peer,
  std::vector<Contender>& out)
{
  filter->SetInputData(labels);
  filter->SetSelectionModeToLabels();
  const int n = maxLabel(in);
  peer->SetInputData(labels);
  peer->GenerateValues(n, 1, n);
  peer->ComputeNormalsOff();
  peer->ComputeGradientsOff();
  vtkAlgorithm* f = filter;
  vtkAlgorithm* p = peer;
  out.push_back({ "filter Labels",
    Role::Tool,
    "labels",
    [f] { update(f); },
    [filter] { return filter->GetOutput()->GetNumberOfCells(); } });
  out.push_back({ "DFE, one value per label",
    Role::Peer,
    "labels",
    [p] { update(p); },
    [peer] { return peer->GetOutput()->GetNumberOfCells(); } });
}

/// Labels mode: the surfels of every label's boundary (a surfel between two labels counts
/// once for each) per second of the whole filter.
void printLabelsThroughput(const Input& in,
  vtkStandardPlanePolyhedrizer* filter,
  const std::vector<Measured>& rows)
{
  const Measured* m = findMeasured(rows, "filter Labels");
  vtkDataArray* surfels = filter->GetOutput()->GetFieldData()->GetArray("NumberOfSurfels");
  const double count = surfels ? surfels->GetComponent(0, 0) : 0.0;
  std::printf("Labels mode: labels 1 to %s, surfels %s | M surfels/s: filter %.2f\n\n",
    formatCount(maxLabel(in)).c_str(),
    formatCount(static_cast<long long>(count)).c_str(),
    count / m->median / 1e6);
}

void benchmarkInput(const Input& in, const Options& options, Report& report)
{
  Report::printInput(in);
  const vbr::BitVolume voxels = bitsOf(in);
  vtkNew<vtkImageData> image = maskImageOf(in);
  vtkNew<vtkImageData> labelImage = in.labels ? labelImageOf(in) : vtkNew<vtkImageData>();
  forEachBackend(options,
    [&](const std::string& backend)
    {
      vbr::SurfelGraph graph;
      vbr::Polyhedron poly;
      vtkNew<vtkStandardPlanePolyhedrizer> filter;
      filter->SetInputData(image);
      vtkNew<vtkDiscreteFlyingEdges3D> peer;
      peer->SetInputData(image);
      peer->SetValue(0, 1);
      peer->ComputeNormalsOff();
      peer->ComputeGradientsOff();
      vtkAlgorithm* f = filter;
      vtkAlgorithm* p = peer;
      const std::vector<Contender> contenders{
        { "surfel graph",
          Role::Phase,
          "",
          [&] { vbr::buildSurfelGraph(voxels, vbr::Execution(), graph); },
          nullptr },
        { "faces",
          Role::Phase,
          "",
          [&] { vbr::polyhedrize(graph, vbr::PolyhedrizationOptions(), backendExecution(), poly); },
          nullptr },
        { "filter",
          Role::Tool,
          "mask",
          [f] { update(f); },
          [filter = filter.Get()] { return filter->GetOutput()->GetNumberOfCells(); } },
        { "DiscreteFlyingEdges3D",
          Role::Peer,
          "mask",
          [p] { update(p); },
          [peer = peer.Get()] { return peer->GetOutput()->GetNumberOfCells(); } },
      };
      std::vector<Contender> all = contenders;
      vtkNew<vtkStandardPlanePolyhedrizer> labelsFilter;
      vtkNew<vtkDiscreteFlyingEdges3D> labelsPeer;
      if (in.labels)
        addLabelContenders(in, labelImage, labelsFilter, labelsPeer, all);
      const std::vector<Measured> rows = timeInTurns(options.repeat, all);
      report.add(in, backend, rows);
      printFaces(graph, poly, voxels);
      printThroughput(graph.size(), rows);
      if (in.labels)
        printLabelsThroughput(in, labelsFilter, rows);
    });
}

/// A one-voxel-thin Archimedean spiral wall, r = 4 theta / (2 pi) (turns 4 voxels apart) out
/// to 2 voxels from the border, 4-connected in each slice and extruded along z over n - 2
/// slices: the inner turns are short arcs, the outer ones long, gently curved strips.
Input spiral(int n)
{
  Input in;
  in.name = "spiral " + std::to_string(n) + "^3";
  in.inputClass = "spiral";
  in.dims = { n, n, n };
  in.values.assign(in.voxelCount(), 0);
  const double c = (n - 1) / 2.0, gap = 4.0, pi = std::acos(-1.0);
  auto wall = [&](int x, int y)
  {
    for (int z = 1; z < n - 1; ++z)
      in.at(x, y, z) = 1;
  };
  int px = -1, py = -1;
  for (long i = 0;; ++i)
  {
    const double t = 0.002 * double(i), r = gap * t / (2 * pi);
    if (r >= c - 2)
      break;
    const int x = int(std::lround(c + r * std::cos(t))), y = int(std::lround(c + r * std::sin(t)));
    if (px >= 0 && x != px && y != py)
      wall(x, py); // a diagonal step: the corner keeps the wall 4-connected
    wall(x, y);
    px = x, py = y;
  }
  return in;
}

/// The spiral sizes the options select (the class `spiral`).
std::vector<int> spiralSizes(const Options& options)
{
  const auto& classes = options.inputs.classes;
  const bool all = std::find(classes.begin(), classes.end(), "all") != classes.end();
  if (!all && std::find(classes.begin(), classes.end(), "spiral") == classes.end())
    return {};
  if (options.inputs.quick)
    return { 24 };
  std::vector<int> sizes{ 32, 64, 96 };
  if (options.inputs.large)
    sizes.push_back(128);
  return sizes;
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  options.inputs.classes = splitList("balls,porous,noise,spiral,berea,volumes,labelmaps");
  options.inputs.sizes = { 64 };
  options.inputs.solid = { 45 };
  options.inputs.seeds = { 1 };
  options.repeat = 3;
  // runBenchmark, with the spirals (a class of this benchmark only) after the shared inputs.
  const char* title = "BenchStandardPlanePolyhedrizer";
  const std::string purpose = std::string(title) +
    ": vtkStandardPlanePolyhedrizer against vtkDiscreteFlyingEdges3D (input class 'spiral': "
    "one-voxel-thin spirals, built here)";
  const int stop = parseOptions(argc, argv, purpose.c_str(), options);
  if (stop >= 0)
    return stop;
  printPreamble(title, options);
  Report report;
  forEachInput(options, [&](const Input& in) { benchmarkInput(in, options, report); });
  for (int n : spiralSizes(options))
  {
    benchmarkInput(spiral(n), options, report);
    std::fflush(stdout);
  }
  report.printSummary();
  return 0;
}
