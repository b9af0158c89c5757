// vtkFaceOctreeBoundaryFilter through VTK: every scalar type (point and cell scalars), a
// mirrored direction matrix (cells reversed: the enclosed volume stays positive; on this thin
// torus, tube radius 3 voxels, the surface runs about half a voxel inside the surfels, so the
// volume is only bounded loosely here: the core test bounds it by the surfel area), closedness
// from the output cells alone, the face octree port, abort (an empty output), errors on bad
// input (vtkErrorMacro, no crash), and PrintSelf naming every property.
#include "vtkFaceOctreeBoundaryFilter.h"

#include "TestImages.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include <map>
#include <sstream>
#include <utility>

namespace
{

using vbrtest::AbortAtProgress;
using vbrtest::Layout;
using vbrtest::makeImage;
using vbrtest::Volume;

Volume torus(int n)
{
  Volume v;
  v.dims = { n, n, n };
  v.values.resize(std::size_t(n) * n * n);
  std::size_t i = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x, ++i)
      {
        const double u = (x + 0.5) / n - 0.5, w = (y + 0.5) / n - 0.5, h = (z + 0.5) / n - 0.5;
        const double r = std::sqrt(u * u + w * w) - 0.27;
        v.values[i] = r * r + h * h < 0.13 * 0.13 ? 1 : 0;
      }
  return v;
}

/// Every directed edge once and its reverse once; the divergence-theorem volume.
bool closed(vtkPolyData* p, double& volume)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> directed;
  volume = 0;
  vtkCellArray* polys = p->GetPolys();
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    vtkIdType n;
    const vtkIdType* ids;
    polys->GetCellAtId(c, n, ids);
    double a[3], b[3], d[3];
    p->GetPoint(ids[0], a);
    for (vtkIdType i = 0; i < n; ++i)
      ++directed[{ ids[i], ids[(i + 1) % n] }];
    for (vtkIdType i = 1; i + 1 < n; ++i)
    {
      p->GetPoint(ids[i], b);
      p->GetPoint(ids[i + 1], d);
      volume += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                  a[2] * (b[0] * d[1] - b[1] * d[0])) /
        6.0;
    }
  }
  for (const auto& e : directed)
    if (e.second != 1 || !directed.count({ e.first.second, e.first.first }))
      return false;
  return !directed.empty();
}

void checkTypesAndLayouts()
{
  const Volume v = torus(24);
  double voxels = 0;
  for (int x : v.values)
    voxels += x;
  for (int type : { VTK_CHAR,
         VTK_UNSIGNED_CHAR,
         VTK_SHORT,
         VTK_UNSIGNED_SHORT,
         VTK_INT,
         VTK_UNSIGNED_INT,
         VTK_LONG_LONG,
         VTK_UNSIGNED_LONG_LONG,
         VTK_FLOAT,
         VTK_DOUBLE })
    for (bool cells : { false, true })
    {
      Layout l;
      l.scalarType = type;
      l.cellData = cells;
      l.spacing = { 0.5, 0.5, 0.5 };
      vtkNew<vtkFaceOctreeBoundaryFilter> f;
      f->SetInputData(makeImage(v, l));
      f->SetMergeFaceNodes(cells); // both ways, once per type
      f->Update();
      double volume = 0;
      CHECK(closed(f->GetOutput(), volume), "closed for type " << type << " cells " << cells);
      volume /= 0.125;
      CHECK(volume > 0.4 * voxels && volume < 1.05 * voxels,
        "volume " << volume << " of " << voxels << " voxels, type " << type);
      auto* boxes = vtkUnstructuredGrid::SafeDownCast(f->GetOutputDataObject(1));
      CHECK(boxes &&
          boxes->GetNumberOfCells() ==
            f->GetOutput()->GetFieldData()->GetArray("NumberOfFaceNodes")->GetTuple1(0),
        "one box per face node");
    }
}

void checkMirrored()
{
  const Volume v = torus(20);
  auto image = makeImage(v, Layout());
  image->SetDirectionMatrix(-1, 0, 0, 0, 1, 0, 0, 0, 1);
  for (int mode : { vtkFaceOctreeBoundaryFilter::POLYGONS,
         vtkFaceOctreeBoundaryFilter::TRIANGLES,
         vtkFaceOctreeBoundaryFilter::QUADRILATERALS })
  {
    vtkNew<vtkFaceOctreeBoundaryFilter> f;
    f->SetInputData(image);
    f->SetOutputMode(mode);
    f->Update();
    double volume = 0;
    CHECK(closed(f->GetOutput(), volume), "mirrored: closed, mode " << mode);
    CHECK(volume > 0, "mirrored: outwards, mode " << mode << " volume " << volume);
  }
}

void checkAbort()
{
  vtkNew<vtkFaceOctreeBoundaryFilter> f;
  f->SetInputData(makeImage(torus(32), Layout()));
  vtkNew<AbortAtProgress> abort;
  f->AddObserver(vtkCommand::ProgressEvent, abort);
  f->Update();
  CHECK(abort->Calls > 0, "progress is reported");
  CHECK(f->GetOutput()->GetNumberOfCells() == 0, "an aborted run leaves an empty output");
}

void checkErrors()
{
  // No scalars at all.
  vtkNew<vtkImageData> empty;
  empty->SetDimensions(4, 4, 4);
  vtkNew<vtkFaceOctreeBoundaryFilter> f;
  f->SetInputData(empty);
  CHECK(vbrtest::updateCountingErrors(f) > 0, "an image without scalars is an error");
  CHECK(f->GetOutput()->GetNumberOfCells() == 0, "and gives an empty output");
  // A named array that does not exist.
  vtkNew<vtkFaceOctreeBoundaryFilter> g;
  g->SetInputData(makeImage(torus(8), Layout()));
  g->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "missing");
  CHECK(vbrtest::updateCountingErrors(g) > 0, "a missing array is an error");
}

void checkPrintSelf()
{
  vtkNew<vtkFaceOctreeBoundaryFilter> f;
  std::ostringstream os;
  f->Print(os);
  for (const char* name : { "OutputMode",
         "RelaxationIterations",
         "RelaxationTolerance",
         "MaximumOctreeLevel",
         "Precision",
         "PruneCrests",
         "Selection" })
    CHECK(os.str().find(name) != std::string::npos, "PrintSelf names " << name);
}

} // namespace

int TestFaceOctreeBoundaryFilter(int, char*[])
{
  checkTypesAndLayouts();
  checkMirrored();
  checkAbort();
  checkErrors();
  checkPrintSelf();
  return vbrtest::testResult();
}
