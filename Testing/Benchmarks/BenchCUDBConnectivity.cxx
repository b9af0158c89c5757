// Benchmark of vtkCUDBConnectivity against vtkImageConnectivityFilter (face connectivity; that
// filter exists only in stock VTK, so the comparison is made in the stock-VTK build), on the
// harness of BenchCommon.h (options, inputs, turns, medians, ratios, peak memory).
//
// For each input: the EVM, OUDB and CUDB sizes (the paper's Table 1); the phases run on the
// core alone, one thread (image -> EVM, EVM -> CUDB, CCL on the boxes, label write-back: the
// paper's Table 2; and EVM -> CUDB + CCL, the sweep that labels as it goes, which the filter
// runs in place of the two); the whole filter with face and vertex connectivity and with seeds
// (every 16th selected voxel), and the peer, all in turns. The peer's region count must be the
// filter's. Run with VTK_SMP_BACKEND_IN_USE=STDThread (or --backends) to use every core.
//
//   BenchCUDBConnectivity --help     the options, with this program's defaults
#include "vtkCUDBConnectivity.h"

#include "CUDB.h"
#include "EVM.h"

#include "BenchCommon.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#if __has_include(<vtkImageConnectivityFilter.h>)
#include <vtkImageConnectivityFilter.h>
#define VOXELBREP_HAVE_PEER 1
#endif

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace
{

using namespace vbrbench;

/// Every `step`-th selected voxel's centre as a seed point (the image has origin 0, spacing 1).
vtkNew<vtkPolyData> seedsOf(const Input& in, std::size_t step)
{
  vtkNew<vtkPoints> points;
  std::size_t selected = 0;
  for (std::size_t i = 0; i < in.voxelCount(); ++i)
    if (in.selected(i) && selected++ % step == 0)
      points->InsertNextPoint(static_cast<double>(i % in.dims[0]),
        static_cast<double>(i / in.dims[0] % in.dims[1]),
        static_cast<double>(i / (std::size_t(in.dims[0]) * in.dims[1])));
  vtkNew<vtkPolyData> seeds;
  seeds->SetPoints(points);
  return seeds;
}

/// The core's stages, each from the stored result of the one before.
struct Core
{
  vbr::BitVolume bits;
  vbr::EVM evm;
  vbr::CUDB cudb;
  vbr::Components comps;
  std::vector<std::int32_t> labels;
};

void addCorePhases(const Input& in, Core& core, std::vector<Contender>& out)
{
  core.bits = bitsOf(in);
  core.labels.resize(in.voxelCount());
  Core* c = &core;
  const std::array<int, 3> dims = in.dims;
  out.push_back({ "EVM",
    Role::Phase,
    "",
    [c] { c->evm = c->bits.size(2) == 1 ? vbr::extractEVM2D(c->bits) : vbr::extractEVM(c->bits); },
    nullptr });
  out.push_back(
    { "EVM -> CUDB", Role::Phase, "", [c] { c->cudb = vbr::buildCUDB(c->evm); }, nullptr });
  out.push_back({ "CCL",
    Role::Phase,
    "",
    [c] { c->comps = vbr::labelComponents(c->cudb, vbr::Connectivity::Face); },
    nullptr });
  out.push_back({ "EVM -> CUDB + CCL",
    Role::Phase,
    "",
    [c]
    {
      vbr::CUDB boxes;
      vbr::Components components;
      vbr::buildCUDBComponents(
        c->evm, vbr::Connectivity::Face, vbr::Execution(), boxes, components);
    },
    nullptr });
  out.push_back({ "write-back",
    Role::Phase,
    "",
    [c, dims]
    {
      std::fill(c->labels.begin(), c->labels.end(), 0);
      const std::vector<std::int32_t> values(c->comps.boxLabel.begin(), c->comps.boxLabel.end());
      vbr::paintBoxes(c->cudb.boxes, values, { 0, 0, 0 }, { 0, 1, 2 }, dims, c->labels.data());
    },
    nullptr });
}

long long regionsOf(vtkCUDBConnectivity* f)
{
  vtkDataArray* a =
    vtkDataArray::SafeDownCast(f->GetOutput()->GetFieldData()->GetAbstractArray("NumberOfRegions"));
  return a ? static_cast<long long>(a->GetTuple1(0)) : -1;
}

/// The three runs of the filter and the peer.
struct Filters
{
  vtkNew<vtkCUDBConnectivity> face, vertex, seeded;
  vtkNew<vtkPolyData> seeds;
#ifdef VOXELBREP_HAVE_PEER
  vtkNew<vtkImageConnectivityFilter> peer;
#endif
};

void addFilters(vtkImageData* image, const Input& in, Filters& f, std::vector<Contender>& out)
{
  for (vtkCUDBConnectivity* c : { f.face.Get(), f.vertex.Get(), f.seeded.Get() })
  {
    c->SetInputData(image);
    c->GenerateBoxesOff();
  }
  f.vertex->SetConnectivityToVertex();
  f.seeds->DeepCopy(seedsOf(in, 16)); // cost linear in the seeds, not seeds x boxes
  f.seeded->SetSeedData(f.seeds);
  auto add = [&out](const char* name, const char* group, vtkAlgorithm* a, Role role) {
    out.push_back({ name, role, group, [a] { update(a); }, nullptr });
  };
  add("filter face", "face", f.face, Role::Tool);
  add("filter vertex", "vertex", f.vertex, Role::Tool);
  add("filter seeded", "seeded", f.seeded, Role::Tool);
#ifdef VOXELBREP_HAVE_PEER
  f.peer->SetInputData(image);
  f.peer->SetScalarRange(1, 1);
  f.peer->SetExtractionModeToAllRegions();
  f.peer->SetLabelModeToSizeRank();
  f.peer->SetLabelScalarTypeToInt(); // the default (unsigned char) caps the count at 255
  add("vtkImageConnectivityFilter", "face", f.peer, Role::Peer);
#endif
}

void printSizes(const Input& in,
  const Core& core,
  const Filters& f,
  const std::vector<Measured>& rows)
{
  const Measured* face = findMeasured(rows, "filter face");
  const long long peak = face ? face->peakBytes : -1;
  std::printf("EV %s, OUDB boxes %s, CUDB boxes %s, components (face) %u, seeds %lld; "
              "filter face: %.1f peak bytes per voxel, %.0f per box\n\n",
    formatCount(static_cast<long long>(core.evm.size())).c_str(),
    formatCount(static_cast<long long>(core.cudb.oudbBoxCount)).c_str(),
    formatCount(static_cast<long long>(core.cudb.boxes.size())).c_str(),
    core.comps.count,
    static_cast<long long>(f.seeds->GetNumberOfPoints()),
    double(peak) / double(std::max<std::size_t>(in.voxelCount(), 1)),
    double(peak) / double(std::max<std::size_t>(core.cudb.boxes.size(), 1)));
  const long long regions = regionsOf(f.face);
  if (regions != static_cast<long long>(core.comps.count))
    std::printf("WARNING: %s: the filter finds %lld regions, the core %u\n\n",
      in.name.c_str(),
      regions,
      core.comps.count);
#ifdef VOXELBREP_HAVE_PEER
  if (f.peer->GetNumberOfExtractedRegions() != regions)
    std::printf("WARNING: %s: vtkImageConnectivityFilter finds %lld regions, the filter %lld\n\n",
      in.name.c_str(),
      static_cast<long long>(f.peer->GetNumberOfExtractedRegions()),
      regions);
#endif
}

void benchmarkInput(const Input& in, const Options& options, Report& report)
{
  Report::printInput(in);
  vtkNew<vtkImageData> image = maskImageOf(in);
  forEachBackend(options,
    [&](const std::string& backend)
    {
      Core core;
      Filters filters;
      std::vector<Contender> contenders;
      addCorePhases(in, core, contenders);
      addFilters(image, in, filters, contenders);
      const std::vector<Measured> rows = timeInTurns(options.repeat, contenders);
      report.add(in, backend, rows);
      printSizes(in, core, filters, rows);
    });
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  options.inputs.classes = splitList(
    "phantom,boxes,blobs,porous,checkerboard,noise,berea,volumes,labelmaps,porous2d,images2d");
  options.inputs.sizes = { 128, 256 };
#ifndef VOXELBREP_HAVE_PEER
  options.note =
    "(vtkImageConnectivityFilter is not in this VTK: build against stock VTK to compare)";
#endif
  return runBenchmark(argc,
    argv,
    "BenchCUDBConnectivity",
    "vtkCUDBConnectivity against vtkImageConnectivityFilter (stock VTK)",
    options,
    benchmarkInput);
}
