// Benchmark of vtkConvexHullModifier: the exact hull against Qhull and CGAL's convex_hull_3 on
// the same vertex candidates, and the whole filter on balls, the pac-man (the paper's example)
// and real objects, next to vtkDiscreteFlyingEdges3D's triangles, the EVM boundary's polygons
// and the standard-plane polyhedrizer's faces on the same input, in one process.
//
//   BenchConvexHullModifier [--radii 12,24,32,48,64] [--repeat 3] [--data DIR] [--no-data]
//
// Per input: voxels, candidates, the hull's faces and vertices, the hull time (median; our
// Extension variant, then Visible and Invisible), Qhull's ("qhull Qt" would triangulate; the
// default merges coplanar facets) and CGAL's (Epick, a triangulated hull) on the same
// candidates; the filter's faces, edges, vertices, degree of non-convexity, Separates, time;
// the peers' cells and the ratio DFE triangles / our faces.
#include "vtkConvexHullModifier.h"
#include "vtkEVMBoundaryFilter.h"
#include "vtkStandardPlanePolyhedrizer.h"

#include "ConvexHull.h"
#include "ConvexHullModifier.h"

#include "BenchCommon.h"

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

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{

using namespace vbrbench;

Input ball(const std::string& name, int r, bool mouth)
{
  const int n = 2 * r + 3;
  const double c = r + 1;
  Input in = emptyInput(name, { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        const double dx = x - c, dy = y - c, dz = z - c;
        const bool cut = mouth && dx > 0 && std::abs(dy) < 0.6 * dx;
        in.at(x, y, z) = dx * dx + dy * dy + dz * dz <= double(r) * r && !cut;
      }
  return in;
}

long qhullFacets(const std::vector<vbr::LatticePoint>& points)
{
  std::vector<coordT> coords;
  for (const auto& p : points)
    coords.insert(coords.end(), { coordT(p[0]), coordT(p[1]), coordT(p[2]) });
  qhT storage;
  qhT* qh = &storage;
  static FILE* quiet = std::fopen("/dev/null", "w");
  qh_zero(qh, quiet);
  char options[] = "qhull";
  long facets = -1;
  if (qh_new_qhull(qh, 3, int(points.size()), coords.data(), False, options, nullptr, quiet) == 0)
    facets = qh->num_facets;
  int curlong, totlong;
  qh_freeqhull(qh, !qh_ALL);
  qh_memfreeshort(qh, &curlong, &totlong);
  return facets;
}

long long field(vtkPolyData* p, const char* name)
{
  auto* a = p->GetFieldData()->GetArray(name);
  return a ? static_cast<long long>(a->GetTuple1(0)) : -1;
}

void run(const Input& in, int repeat)
{
  const vbr::BitVolume voxels = bitsOf(in);
  const auto candidates = vbr::vertexCandidates(voxels);
  vbr::CellList hull;
  const double tOurs = medianSeconds(repeat, [&] { hull = vbr::convexHull(candidates); });
  const double tVisible =
    medianSeconds(repeat, [&] { vbr::convexHull(candidates, vbr::CoplanarFaces::Visible); });
  const double tInvisible =
    medianSeconds(repeat, [&] { vbr::convexHull(candidates, vbr::CoplanarFaces::Invisible); });
  long qfacets = 0;
  const double tQhull = medianSeconds(repeat, [&] { qfacets = qhullFacets(candidates); });
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Point_3> cp;
  for (const auto& p : candidates)
    cp.emplace_back(double(p[0]), double(p[1]), double(p[2]));
  CGAL::Surface_mesh<K::Point_3> cgalHull;
  const double tCgal = medianSeconds(repeat,
    [&]
    {
      cgalHull.clear();
      CGAL::convex_hull_3(cp.begin(), cp.end(), cgalHull);
    });

  vtkNew<vtkImageData> image = imageOf(in);
  vtkNew<vtkConvexHullModifier> filter;
  filter->SetInputData(image);
  const double tFilter = medianSeconds(repeat, [&] { update(filter); });
  vtkPolyData* out = filter->GetOutput();
  vtkNew<vtkDiscreteFlyingEdges3D> dfe;
  dfe->SetInputData(image);
  dfe->SetValue(0, 1);
  dfe->ComputeNormalsOff();
  dfe->ComputeGradientsOff();
  update(dfe);
  vtkNew<vtkEVMBoundaryFilter> evm;
  evm->SetInputData(image);
  evm->SetOutputModeToPolygons();
  update(evm);
  vtkNew<vtkStandardPlanePolyhedrizer> spp;
  spp->SetInputData(image);
  spp->GenerateReversionOff();
  update(spp);
  const long long faces = field(out, "NumberOfFaces");
  const long long triangles = dfe->GetOutput()->GetNumberOfCells();
  std::printf("%-18s %8zu voxels %6zu candidates | hull %5zu faces %5zu vertices: ours %7.2f ms "
              "(Visible %7.2f, Invisible %7.2f), Qhull %7.2f ms (%ld facets), CGAL %7.2f ms | "
              "H %5lld faces %5lld edges %5lld vertices NK %lld Separates %lld %8.1f ms | "
              "DFE %7lld triangles (%.1fx) EVM %6lld polygons polyhedrizer %6lld faces\n",
    in.name.c_str(),
    voxels.count(),
    candidates.size(),
    hull.faces.size(),
    hull.vertices.size(),
    1e3 * tOurs,
    1e3 * tVisible,
    1e3 * tInvisible,
    1e3 * tQhull,
    qfacets,
    1e3 * tCgal,
    faces,
    field(out, "NumberOfEdges"),
    field(out, "NumberOfVertices"),
    field(out, "DegreeOfNonConvexity"),
    field(out, "Separates"),
    1e3 * tFilter,
    triangles,
    faces > 0 ? double(triangles) / faces : 0.0,
    evm->GetOutput()->GetNumberOfCells(),
    field(spp->GetOutput(), "NumberOfFaces"));
}

} // namespace

int main(int argc, char* argv[])
{
  Arguments args;
  args.list = { 12, 24, 32, 48, 64 };
  args.repeat = 3;
  args.dataDir = VOXELBREP_DEFAULT_DATA_DIR;
  if (!parseArguments(argc, argv, "radii", args))
    return 2;
  run(ball("pac-man r=11", 11, true), args.repeat);
  for (int r : args.list)
    run(ball("ball r=" + std::to_string(r), r, false), args.repeat);
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
  };
  for (const Real& r : objects)
  {
    Input in;
    if (readThresholded(args.dataDir + r.file, r.dims, r.lo, r.hi, r.name, in))
      run(in, args.repeat);
  }
  return 0;
}
