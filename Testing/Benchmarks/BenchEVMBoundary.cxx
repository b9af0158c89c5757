// BenchEVMBoundary: times vtkEVMBoundaryFilter against the VTK filters that give a boundary
// of the same voxels, in one process, in turns, on the same input (the harness of
// BenchCommon.h: options, inputs, turns, medians, ratios, peak memory).
//
// For every input and every requested vtkSMPTools backend:
//  - phases of the VTK-free core: thresholding into a BitVolume (vbr::selectVoxels) and
//    vbr::extractEVM, on one thread (an Execution without parallelFor), and both with
//    vtkSMPTools;
//  - tools: the whole vtkEVMBoundaryFilter, Polygons and Triangles (3D) or Polylines and
//    Polygons (2D images), Range selection on the original values;
//  - peers: vtkDiscreteFlyingEdges3D (2D: vtkDiscreteFlyingEdges2D), contour value 1 of the
//    0/1 image of the same selection, and (3D) vtkThreshold [1, 1] on 0/1 cell scalars followed
//    by vtkGeometryFilter, what a ParaView user does today (Threshold + Extract Surface);
//  - label maps (labelmaps, compact): Labels mode, every label, against
//    vtkDiscreteFlyingEdges3D with one contour value per label (a pass over the image per
//    value).
// The extreme vertices of the core and of the filter must agree, and with the manifest's.
//
//   BenchEVMBoundary --help          the options (BenchCommon.h), with this program's defaults
//   BenchEVMBoundary --quick         the smoke run of ctest
//   BenchEVMBoundary --large --backends STDThread,Sequential
#include "BitVolume.h"
#include "EVM.h"
#include "Execution.h"
#include "Selection.h"

#include "BenchCommon.h"

#include "vtkEVMBoundaryFilter.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDiscreteFlyingEdges2D.h"
#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkFieldData.h"
#include "vtkGeometryFilter.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkThreshold.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace
{

using namespace vbrbench;

long long fieldValue(vtkDataObject* data, const char* name)
{
  vtkDataArray* array = vtkDataArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(name));
  return array && array->GetNumberOfTuples() > 0 ? static_cast<long long>(array->GetTuple1(0)) : -1;
}

/// vtkSMPTools as the core's parallel loop: what vbr::vtk::makeExecution (private to the
/// module, not exported) does, without progress reporting.
vbr::Execution smpExecution()
{
  vbr::Execution exec;
  exec.parallelFor = [](std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body)
  {
    vtkSMPTools::For(
      vtkIdType(0), static_cast<vtkIdType>(n), [&body](vtkIdType b, vtkIdType e) { body(b, e); });
  };
  return exec;
}

/// The core's extreme vertices of a 3D voxel set or a 2D image (nz == 1).
std::size_t extremeVertices(const vbr::BitVolume& v, const vbr::Execution& exec)
{
  return (v.size(2) == 1 ? vbr::extractEVM2D(v, exec) : vbr::extractEVM(v, exec)).size();
}

/// What the contenders of one input share: its images and the core's last results.
struct Fixture
{
  const Input& in;
  vtkNew<vtkImageData> values, labels, mask;
  vtkSmartPointer<vtkImageData> cells;
  vbr::BitVolume bits;
  std::size_t coreExtremeVertices = 0;
  std::vector<vtkSmartPointer<vtkAlgorithm>> keep; ///< the filters the contenders run

  explicit Fixture(const Input& input)
    : in(input)
    , values(valueImageOf(input))
    , labels(input.labels ? labelImageOf(input) : vtkNew<vtkImageData>())
    , mask(maskImageOf(input))
  {
    if (!input.is2D())
      this->cells = cellImageOf(input);
  }

  template<class Filter>
  Filter* make(vtkImageData* image)
  {
    auto f = vtkSmartPointer<Filter>::New();
    f->SetInputData(image);
    this->keep.push_back(f);
    return f;
  }
};

Contender algorithm(const std::string& name, Role role, const std::string& group, vtkAlgorithm* a)
{
  auto cells = [a]
  { return vtkDataSet::SafeDownCast(a->GetOutputDataObject(0))->GetNumberOfCells(); };
  return { name, role, group, [a] { update(a); }, cells };
}

/// The core's image -> EVM, on one thread and with vtkSMPTools.
void addCorePhases(Fixture& fx, std::vector<Contender>& out)
{
  const Input& in = fx.in;
  vbr::ScalarGrid<std::uint8_t> grid;
  grid.data = in.values.data();
  grid.dims = { in.dims[0], in.dims[1], in.dims[2] };
  grid.stride = { 1, in.dims[0], std::int64_t(in.dims[0]) * in.dims[1] };
  vbr::Box box;
  box.hi = grid.dims;
  const int lo = in.lo, hi = in.hi;
  auto select = [grid, box, lo, hi](const vbr::Execution& exec)
  {
    return vbr::selectVoxels(
      grid, box, [lo, hi](std::uint8_t v) { return v >= lo && v <= hi; }, exec);
  };
  Fixture* f = &fx;
  out.push_back({ "select, 1 thread",
    Role::Phase,
    "",
    [f, select] { f->bits = select(vbr::Execution()); },
    nullptr });
  out.push_back({ "extractEVM, 1 thread",
    Role::Phase,
    "",
    [f] { f->coreExtremeVertices = extremeVertices(f->bits, vbr::Execution()); },
    nullptr });
  out.push_back({ "select + extractEVM, 1 thread",
    Role::Phase,
    "",
    [f, select]
    { f->coreExtremeVertices = extremeVertices(select(vbr::Execution()), vbr::Execution()); },
    nullptr });
  out.push_back({ "select + extractEVM, SMP",
    Role::Phase,
    "",
    [f, select]
    {
      const vbr::Execution exec = smpExecution();
      f->coreExtremeVertices = extremeVertices(select(exec), exec);
    },
    nullptr });
}

vtkEVMBoundaryFilter* evmFilter(Fixture& fx, int outputMode, bool labels)
{
  vtkEVMBoundaryFilter* f = fx.make<vtkEVMBoundaryFilter>(labels ? fx.labels : fx.values);
  if (labels)
  {
    f->SetSelectionModeToLabels();
    f->SetGlobalWarningDisplay(0); // more than 1,000 labels warns; expected for compact labels
  }
  else
  {
    f->SetSelectionModeToRange();
    f->SetLowerThreshold(fx.in.lo);
    f->SetUpperThreshold(fx.in.hi);
  }
  f->SetOutputMode(outputMode);
  return f;
}

void addThresholdGeometry(Fixture& fx, std::vector<Contender>& out)
{
  vtkThreshold* threshold = fx.make<vtkThreshold>(fx.cells);
  threshold->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, vtkDataSetAttributes::SCALARS);
  threshold->SetLowerThreshold(1.0); // VTK >= 9.1 API (ThresholdBetween is deprecated there)
  threshold->SetUpperThreshold(1.0);
  threshold->SetThresholdFunction(vtkThreshold::THRESHOLD_BETWEEN);
  vtkGeometryFilter* geometry = fx.make<vtkGeometryFilter>(nullptr);
  geometry->SetInputConnection(threshold->GetOutputPort());
  out.push_back({ "Threshold + Geometry",
    Role::Peer,
    "mask",
    [threshold, geometry]
    {
      threshold->Modified();
      geometry->Update();
    },
    [geometry] { return geometry->GetOutput()->GetNumberOfCells(); } });
}

/// The binary selection: the filter's outputs, Flying Edges, Threshold + Geometry.
void addMaskContenders(Fixture& fx, std::vector<Contender>& out)
{
  const bool flat = fx.in.is2D();
  const int modes[2] = { flat ? vtkEVMBoundaryFilter::POLYLINES : vtkEVMBoundaryFilter::POLYGONS,
    flat ? vtkEVMBoundaryFilter::POLYGONS : vtkEVMBoundaryFilter::TRIANGLES };
  for (int mode : modes)
  {
    vtkEVMBoundaryFilter* f = evmFilter(fx, mode, false);
    out.push_back(
      algorithm(std::string("EVM ") + f->GetOutputModeAsString(), Role::Tool, "mask", f));
  }
  if (flat)
  {
    vtkDiscreteFlyingEdges2D* dfe = fx.make<vtkDiscreteFlyingEdges2D>(fx.mask);
    dfe->SetValue(0, 1.0);
    out.push_back(algorithm("DiscreteFlyingEdges2D", Role::Peer, "mask", dfe));
    return;
  }
  vtkDiscreteFlyingEdges3D* dfe = fx.make<vtkDiscreteFlyingEdges3D>(fx.mask);
  dfe->SetValue(0, 1.0);
  dfe->ComputeNormalsOff();
  dfe->ComputeGradientsOff();
  out.push_back(algorithm("DiscreteFlyingEdges3D", Role::Peer, "mask", dfe));
  addThresholdGeometry(fx, out);
}

/// Labels mode on a label map, against Flying Edges with one contour value per label.
void addLabelContenders(Fixture& fx, std::vector<Contender>& out)
{
  for (int mode : { vtkEVMBoundaryFilter::TRIANGLES, vtkEVMBoundaryFilter::POLYGONS })
  {
    vtkEVMBoundaryFilter* f = evmFilter(fx, mode, true);
    out.push_back(
      algorithm(std::string("EVM Labels ") + f->GetOutputModeAsString(), Role::Tool, "labels", f));
  }
  const int labels = maxLabel(fx.in);
  vtkDiscreteFlyingEdges3D* dfe = fx.make<vtkDiscreteFlyingEdges3D>(fx.labels);
  dfe->GenerateValues(labels, 1, labels);
  dfe->ComputeNormalsOff();
  dfe->ComputeGradientsOff();
  out.push_back(algorithm("DFE, one value per label", Role::Peer, "labels", dfe));
}

/// The extreme vertices of the core and of the filter, against the manifest's.
void checkExtremeVertices(const Fixture& fx)
{
  long long filterEV = -1;
  for (const auto& a : fx.keep)
    if (auto* f = vtkEVMBoundaryFilter::SafeDownCast(a))
      if (f->GetSelectionMode() != vtkEVMBoundaryFilter::LABELS)
        filterEV = fieldValue(f->GetOutput(), "NumberOfExtremeVertices");
  const long long core = static_cast<long long>(fx.coreExtremeVertices);
  std::printf("extreme vertices: %s", formatCount(core).c_str());
  if (fx.in.expectedExtremeVertices >= 0)
    std::printf(" (manifest %s)", formatCount(fx.in.expectedExtremeVertices).c_str());
  std::printf("\n\n");
  if (filterEV != core)
    std::printf("WARNING: %s: the filter reports %lld extreme vertices, the core %lld\n\n",
      fx.in.name.c_str(),
      filterEV,
      core);
  if (fx.in.expectedExtremeVertices >= 0 && core != fx.in.expectedExtremeVertices)
    std::printf("WARNING: %s: %lld extreme vertices, expected %lld\n\n",
      fx.in.name.c_str(),
      core,
      fx.in.expectedExtremeVertices);
}

void benchmarkInput(const Input& in, const Options& options, Report& report)
{
  Report::printInput(in);
  forEachBackend(options,
    [&](const std::string& backend)
    {
      Fixture fx(in);
      std::vector<Contender> contenders;
      addCorePhases(fx, contenders);
      addMaskContenders(fx, contenders);
      if (in.labels && !in.is2D())
        addLabelContenders(fx, contenders);
      const std::vector<Measured> rows = timeInTurns(options.repeat, contenders);
      report.add(in, backend, rows);
      if (const Measured* m = findMeasured(rows, "EVM Labels Triangles"))
        std::printf("Labels mode: %s labels, %.2f us per label (EVM Labels Triangles)\n\n",
          formatCount(maxLabel(in)).c_str(),
          1e6 * m->median / std::max(1, maxLabel(in)));
      checkExtremeVertices(fx);
    });
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  options.inputs.classes = splitList(
    "phantom,porous,checkerboard,noise,compact,berea,volumes,labelmaps,porous2d,images2d");
  options.backends = { "STDThread", "Sequential" };
  return runBenchmark(argc,
    argv,
    "BenchEVMBoundary",
    "vtkEVMBoundaryFilter against vtkDiscreteFlyingEdges3D/2D and Threshold + Geometry",
    options,
    benchmarkInput);
}
