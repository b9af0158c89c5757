// Benchmark of vtkConvexHullModifier: the exact hull against Qhull and CGAL's convex_hull_3 on
// the same vertex candidates, and the whole filter on balls, the pac-man (the paper's example)
// and real objects, next to vtkDiscreteFlyingEdges3D's triangles, the EVM boundary's polygons
// and the standard-plane polyhedrizer's faces on the same input, in turns in one process (the
// harness of BenchCommon.h).
//
// Per input, two groups of contenders:
//  - hull: our exact hull of the candidates (vbr::convexHull, Extension variant; Visible and
//    Invisible as phases), against Qhull (libqhull_r, default options: merged coplanar
//    facets, floating point; "Qt" would triangulate) and CGAL (Epick, a triangulated hull);
//  - filter: the whole vtkConvexHullModifier (Polyhedron mode, its reversion and check), against
//    vtkDiscreteFlyingEdges3D, vtkEVMBoundaryFilter (Polygons) and
//    vtkStandardPlanePolyhedrizer (standard faces, no reversion).
// Then: voxels, candidates, the hull's faces and vertices (and Qhull's facets), the filter's
// faces, edges, vertices, degree of non-convexity, joined shells and Separates, and the ratio of
// DFE triangles to our faces; a WARNING (a failed smoke run) where the filter does not separate an
// input. Of the real volumes the objects run: the Al, the headsq bone (>= 1150) and the
// lobster (>= 40; about 10 s of CPU a run).
//
//   BenchConvexHullModifier --help     the options, with this program's defaults
//   BenchConvexHullModifier --quick --no-data     the smoke run of ctest
#include "vtkConvexHullModifier.h"
#include "vtkEVMBoundaryFilter.h"
#include "vtkStandardPlanePolyhedrizer.h"

#include "BitVolume.h"
#include "ConvexHull.h"

#include "BenchCommon.h"

#include "vtkDataArray.h"
#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

extern "C"
{
#include <libqhull_r/qhull_ra.h>
}

#include <cstdio>
#include <string>
#include <vector>

namespace
{

using namespace vbrbench;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// Qhull's facets of the points (default options), -1 when it fails.
long long qhullFacets(const std::vector<vbr::LatticePoint>& points)
{
  std::vector<coordT> coords;
  for (const auto& p : points)
    coords.insert(coords.end(), { coordT(p[0]), coordT(p[1]), coordT(p[2]) });
  qhT storage;
  qhT* qh = &storage;
  static FILE* quiet = std::fopen("/dev/null", "w");
  qh_zero(qh, quiet);
  char options[] = "qhull";
  long long facets = -1;
  if (qh_new_qhull(qh, 3, int(points.size()), coords.data(), False, options, nullptr, quiet) == 0)
    facets = qh->num_facets;
  int curlong, totlong;
  qh_freeqhull(qh, !qh_ALL);
  qh_memfreeshort(qh, &curlong, &totlong);
  return facets;
}

long long field(vtkPolyData* p, const char* name)
{
  auto* a = vtkDataArray::SafeDownCast(p->GetFieldData()->GetAbstractArray(name));
  return a && a->GetNumberOfTuples() > 0 ? static_cast<long long>(a->GetTuple1(0)) : -1;
}

/// What the hull contenders leave for the line after the table.
struct HullRuns
{
  std::vector<vbr::LatticePoint> candidates;
  std::vector<Kernel::Point_3> cgalPoints;
  vbr::CellList hull;
  long long qhull = -1;
  CGAL::Surface_mesh<Kernel::Point_3> cgal;
};

std::vector<Contender> hullContenders(HullRuns& h)
{
  auto variant = [&h](const char* name, vbr::CoplanarFaces coplanar)
  {
    return Contender{ name,
      Role::Phase,
      "hull",
      [&h, coplanar] { vbr::convexHull(h.candidates, coplanar); },
      nullptr };
  };
  return {
    { "hull",
      Role::Tool,
      "hull",
      [&h] { h.hull = vbr::convexHull(h.candidates); },
      [&h] { return static_cast<long long>(h.hull.faces.size()); } },
    variant("hull Visible", vbr::CoplanarFaces::Visible),
    variant("hull Invisible", vbr::CoplanarFaces::Invisible),
    { "Qhull",
      Role::Peer,
      "hull",
      [&h] { h.qhull = qhullFacets(h.candidates); },
      [&h] { return h.qhull; } },
    { "CGAL convex_hull_3",
      Role::Peer,
      "hull",
      [&h]
      {
        h.cgal.clear();
        CGAL::convex_hull_3(h.cgalPoints.begin(), h.cgalPoints.end(), h.cgal);
      },
      [&h] { return static_cast<long long>(h.cgal.number_of_faces()); } },
  };
}

/// The filter and its peers on the same image.
struct FilterRuns
{
  vtkNew<vtkConvexHullModifier> filter;
  vtkNew<vtkDiscreteFlyingEdges3D> dfe;
  vtkNew<vtkEVMBoundaryFilter> evm;
  vtkNew<vtkStandardPlanePolyhedrizer> spp;

  explicit FilterRuns(vtkImageData* image)
  {
    this->filter->SetInputData(image);
    this->dfe->SetInputData(image);
    this->dfe->SetValue(0, 1);
    this->dfe->ComputeNormalsOff();
    this->dfe->ComputeGradientsOff();
    this->evm->SetInputData(image);
    this->evm->SetOutputModeToPolygons();
    this->spp->SetInputData(image);
    this->spp->GenerateReversionOff();
  }
};

Contender filterContender(const char* name, Role role, vtkAlgorithm* a, vtkPolyData* out)
{
  return { name,
    role,
    "filter",
    [a] { update(a); },
    [out] { return static_cast<long long>(out->GetNumberOfCells()); } };
}

std::vector<Contender> filterContenders(FilterRuns& f)
{
  return {
    filterContender("filter", Role::Tool, f.filter, f.filter->GetOutput()),
    filterContender("DiscreteFlyingEdges3D", Role::Peer, f.dfe, f.dfe->GetOutput()),
    filterContender("EVMBoundary Polygons", Role::Peer, f.evm, f.evm->GetOutput()),
    filterContender("StandardPlanePolyhedrizer", Role::Peer, f.spp, f.spp->GetOutput()),
  };
}

/// The counts of the hull and of the filter's output; a note where our hull's faces are not
/// Qhull's merged facets.
void printCounts(const Input& in, const HullRuns& h, FilterRuns& f)
{
  vtkPolyData* out = f.filter->GetOutput();
  const long long faces = field(out, "NumberOfFaces");
  const long long triangles = f.dfe->GetOutput()->GetNumberOfCells();
  const bool same = h.qhull == static_cast<long long>(h.hull.faces.size());
  std::printf("voxels %s, candidates %s | hull %s faces, %s vertices, Qhull %s facets%s | H %s "
              "faces, %s edges, %s vertices, NK %lld, shells joined %lld, handles cut %lld, "
              "Separates %lld | DFE "
              "triangles / faces "
              "%s | EVM %s polygons, polyhedrizer %s faces\n\n",
    formatCount(static_cast<long long>(selectedCount(in))).c_str(),
    formatCount(static_cast<long long>(h.candidates.size())).c_str(),
    formatCount(static_cast<long long>(h.hull.faces.size())).c_str(),
    formatCount(static_cast<long long>(h.hull.vertices.size())).c_str(),
    formatCount(h.qhull).c_str(),
    same ? "" : " (not our faces)",
    formatCount(faces).c_str(),
    formatCount(field(out, "NumberOfEdges")).c_str(),
    formatCount(field(out, "NumberOfVertices")).c_str(),
    field(out, "DegreeOfNonConvexity"),
    field(out, "NumberOfJoinedShells"),
    field(out, "NumberOfCutHandles"),
    field(out, "Separates"),
    formatRatio(faces > 0 ? double(triangles) / double(faces) : 0.0).c_str(),
    formatCount(f.evm->GetOutput()->GetNumberOfCells()).c_str(),
    formatCount(field(f.spp->GetOutput(), "NumberOfFaces")).c_str());
  // Every input must separate (the filter's own check; the README).
  if (field(out, "Separates") != 1)
    std::printf("WARNING: the filter does not separate %s\n\n", in.name.c_str());
}

/// The real volumes this benchmark runs: the real objects (the Al, the headsq bone,
/// the lobster); the others are CT volumes whose selection is not one object (the aneurism's
/// vessel tree at 55 takes minutes).
bool skipped(const Input& in)
{
  return in.inputClass == "volumes" && in.name != "Al (v=1)" && in.name != "headsq bone>=1150" &&
    in.name != "lobster>=40";
}

void benchmarkInput(const Input& in, const Options& options, Report& report)
{
  if (skipped(in))
    return;
  Report::printInput(in);
  HullRuns h;
  h.candidates = vbr::vertexCandidates(bitsOf(in));
  for (const auto& p : h.candidates)
    h.cgalPoints.emplace_back(double(p[0]), double(p[1]), double(p[2]));
  vtkNew<vtkImageData> image = maskImageOf(in);
  forEachBackend(options,
    [&](const std::string& backend)
    {
      FilterRuns f(image);
      std::vector<Contender> contenders = hullContenders(h);
      for (Contender& c : filterContenders(f))
        contenders.push_back(std::move(c));
      report.add(in, backend, timeInTurns(options.repeat, contenders));
      printCounts(in, h, f);
    });
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  options.inputs.classes = splitList("pacman,balls,volumes");
  options.inputs.radii = { 12, 24, 32, 48, 64 };
  options.repeat = 3;
  return runBenchmark(argc,
    argv,
    "BenchConvexHullModifier",
    "vtkConvexHullModifier (and its exact hull against Qhull and CGAL) against "
    "vtkDiscreteFlyingEdges3D, vtkEVMBoundaryFilter and vtkStandardPlanePolyhedrizer",
    options,
    benchmarkInput);
}
