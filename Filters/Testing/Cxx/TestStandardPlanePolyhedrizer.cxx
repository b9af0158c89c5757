// vtkStandardPlanePolyhedrizer against checks written here: surfels counted voxel by voxel,
// every surfel corner inside its face's standard plane (recomputed from the world points),
// surfel normals along the plane normal, per-face surfel counts, the reversion equal to the
// selection; point/cell scalars, scalar types, extents, origins and spacings; label maps;
// the LoopEdges bits against the loops of StandardFaces; the paper's sphere; errors, abort and
// PrintSelf; and the real "Al" object when the shared data is present.
#include "vtkStandardPlanePolyhedrizer.h"

#include "TestImages.h"

#include "vtkAbstractArray.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using vbrtest::AbortAtProgress;
using vbrtest::Layout;
using vbrtest::makeImage;
using vbrtest::randomVolume;
using vbrtest::Volume;

long fieldValue(vtkDataObject* d, const char* name)
{
  vtkDataArray* a = vtkDataArray::SafeDownCast(d->GetFieldData()->GetAbstractArray(name));
  return a ? static_cast<long>(a->GetTuple1(0)) : -1;
}

/// Selected voxel faces whose other side is not selected (of the same label in Labels mode).
long surfelCount(const Volume& v, bool labels)
{
  long count = 0;
  for (int z = 0; z < v.dims[2]; ++z)
    for (int y = 0; y < v.dims[1]; ++y)
      for (int x = 0; x < v.dims[0]; ++x)
      {
        const int value = v.at(x, y, z);
        if (value == 0)
          continue;
        const int n[6] = { v.at(x - 1, y, z),
          v.at(x + 1, y, z),
          v.at(x, y - 1, z),
          v.at(x, y + 1, z),
          v.at(x, y, z - 1),
          v.at(x, y, z + 1) };
        for (int k : n)
          count += labels ? k != value : k == 0;
      }
  return count;
}

/// Integer voxel-corner coordinates of a world point (voxel i spans corners i and i + 1).
bool cornerOf(const double world[3], const Layout& l, long corner[3])
{
  bool onCorner = true;
  for (int d = 0; d < 3; ++d)
  {
    const double shift = l.cellData ? 0.0 : -0.5;
    const double index = (world[d] - l.origin[d]) / l.spacing[d] - l.extentMin[d] - shift;
    corner[d] = std::lround(index);
    onCorner = onCorner && std::abs(index - corner[d]) < 1e-6;
  }
  return onCorner;
}

/// Everything the output promises, for one image.
/// Every point array has one tuple per point and every cell array one per cell: an array
/// written through pointers whose count was left short still reads right cell by cell.
void checkOneTuplePerElement(vtkPolyData* out, const std::string& what)
{
  for (int a = 0; a < out->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = out->GetPointData()->GetAbstractArray(a);
    CHECK(array->GetNumberOfTuples() == out->GetNumberOfPoints(),
      what << ": point array " << array->GetName() << " has " << array->GetNumberOfTuples()
           << " tuples for " << out->GetNumberOfPoints() << " points");
  }
  for (int a = 0; a < out->GetCellData()->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = out->GetCellData()->GetAbstractArray(a);
    CHECK(array->GetNumberOfTuples() == out->GetNumberOfCells(),
      what << ": cell array " << array->GetName() << " has " << array->GetNumberOfTuples()
           << " tuples for " << out->GetNumberOfCells() << " cells");
  }
}

void checkImage(const Volume& v, const Layout& l, bool labels, const std::string& what)
{
  vtkSmartPointer<vtkImageData> image = makeImage(v, l);
  vtkNew<vtkStandardPlanePolyhedrizer> f;
  f->SetInputData(image);
  if (labels)
    f->SetSelectionModeToLabels();
  f->SetOutputModeToSurfels();
  f->Update();
  vtkPolyData* out = f->GetOutput();
  const long surfels = surfelCount(v, labels);
  CHECK(out->GetNumberOfCells() == surfels,
    what << ": " << out->GetNumberOfCells() << " quads, " << surfels << " surfels");
  CHECK(fieldValue(out, "NumberOfSurfels") == surfels, what << ": NumberOfSurfels");
  // The ids fit in 32 bits: the cells use vtkCellArray's 32-bit storage (half the memory).
  CHECK(!out->GetPolys()->IsStorage64Bit(), what << ": 64-bit cell storage for small ids");
  vtkDataArray* normals = out->GetCellData()->GetArray("PlaneNormal");
  vtkDataArray* offsets = out->GetCellData()->GetArray("PlaneOffset");
  vtkDataArray* ids = out->GetCellData()->GetArray("FaceId");
  vtkDataArray* sizes = out->GetCellData()->GetArray("SurfelCount");
  CHECK(surfels == 0 || (normals && offsets && ids && sizes), what << ": cell arrays");
  if (surfels > 0 && normals && offsets && ids && sizes)
  {
    long outside = 0, misoriented = 0, offCorner = 0;
    std::map<long, long> quadsPerFace;
    const bool mirror = l.spacing[0] * l.spacing[1] * l.spacing[2] < 0;
    vtkIdType npts;
    const vtkIdType* pts;
    vtkCellArray* polys = out->GetPolys();
    polys->InitTraversal();
    for (vtkIdType c = 0; polys->GetNextCell(npts, pts); ++c)
    {
      long p[4][3];
      for (int k = 0; k < 4; ++k)
        offCorner += !cornerOf(out->GetPoint(pts[k]), l, p[k]);
      const long n[3] = { static_cast<long>(normals->GetComponent(c, 0)),
        static_cast<long>(normals->GetComponent(c, 1)),
        static_cast<long>(normals->GetComponent(c, 2)) };
      const long mu = static_cast<long>(offsets->GetTuple1(c));
      const long omega = std::labs(n[0]) + std::labs(n[1]) + std::labs(n[2]);
      for (auto& q : p)
      {
        const long value = n[0] * q[0] + n[1] * q[1] + n[2] * q[2];
        outside += value < mu || value >= mu + omega;
      }
      long e1[3], e2[3];
      for (int d = 0; d < 3; ++d)
        e1[d] = p[1][d] - p[0][d], e2[d] = p[2][d] - p[1][d];
      const long quadNormal[3] = {
        e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]
      };
      const long along = quadNormal[0] * n[0] + quadNormal[1] * n[1] + quadNormal[2] * n[2];
      misoriented += mirror ? along >= 0 : along <= 0;
      ++quadsPerFace[static_cast<long>(ids->GetTuple1(c))];
    }
    CHECK(offCorner == 0, what << ": points off the voxel corners");
    CHECK(outside == 0, what << ": " << outside << " surfel corners outside their plane");
    CHECK(misoriented == 0, what << ": " << misoriented << " surfels facing away from the normal");
    CHECK(static_cast<long>(quadsPerFace.size()) == fieldValue(out, "NumberOfFaces"),
      what << ": NumberOfFaces");
    long badSizes = 0;
    for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
      badSizes += quadsPerFace[static_cast<long>(ids->GetTuple1(c))] != sizes->GetTuple1(c);
    CHECK(badSizes == 0, what << ": SurfelCount differs from the face's quads");
  }
  checkOneTuplePerElement(out, what + " (surfels)");
  f->SetOutputModeToTriangulatedFaces();
  f->Update();
  checkOneTuplePerElement(f->GetOutput(), what + " (triangulated faces)");
  // Standard faces: one polygon per face.
  f->SetOutputModeToStandardFaces();
  f->Update();
  checkOneTuplePerElement(f->GetOutput(), what + " (standard faces)");
  CHECK(f->GetOutput()->GetNumberOfCells() == fieldValue(f->GetOutput(), "NumberOfFaces"),
    what << ": one polygon per face");
  CHECK(!f->GetOutput()->GetPolys()->IsStorage64Bit(), what << ": 64-bit polygon storage");
  // The reversion, from the faces alone.
  vtkImageData* back = vtkImageData::SafeDownCast(f->GetOutputDataObject(1));
  vtkDataArray* selection = nullptr;
  if (back)
    selection = l.cellData ? back->GetCellData()->GetArray("Selection")
                           : back->GetPointData()->GetArray("Selection");
  CHECK(selection && selection->GetNumberOfTuples() == static_cast<vtkIdType>(v.values.size()),
    what << ": reversion array");
  if (selection && selection->GetNumberOfTuples() == static_cast<vtkIdType>(v.values.size()))
  {
    long wrong = 0;
    for (std::size_t i = 0; i < v.values.size(); ++i)
      wrong += (selection->GetTuple1(static_cast<vtkIdType>(i)) != 0) != (v.values[i] != 0);
    CHECK(wrong == 0, what << ": reversion differs at " << wrong << " voxels");
    CHECK(fieldValue(back, "ReversionMatches") == 1, what << ": ReversionMatches");
  }
}

void checkRandomImages()
{
  const Layout layouts[] = {
    Layout(),
    { true, { 3, -2, 5 }, { -1.5, 2.0, 0.25 }, { 0.5, 1.25, 2.0 }, VTK_SHORT },
    { false, { -4, 0, 1 }, { 10, 0, -3 }, { 1, 1, 1 }, VTK_FLOAT },
    { true, { 0, 0, 0 }, { 0, 0, 0 }, { 2, 2, 2 }, VTK_DOUBLE },
    { false, { 1, 1, 1 }, { 0, 0, 0 }, { 1, 1, 1 }, VTK_UNSIGNED_INT },
    { false, { 0, 0, 0 }, { 4, 0, 0 }, { -1, 1, 1 }, VTK_CHAR },
  };
  unsigned seed = 40;
  int k = 0;
  for (const Layout& l : layouts)
    for (double density : { 0.2, 0.5, 0.8 })
    {
      const Volume v = randomVolume({ 5 + k % 4, 9 - k % 3, 7 }, density, 1, seed++);
      checkImage(v, l, false, "random " + std::to_string(seed));
      ++k;
    }
  const Volume labels = randomVolume({ 8, 7, 6 }, 0.7, 3, 77);
  checkImage(labels, Layout(), true, "labels");
}

/// The LoopEdges bits of the triangulated faces against the loops of StandardFaces: bit k of
/// a triangle is set exactly when its edge from corner k to k + 1 is an edge of its face's
/// polygon, in the polygon's direction (points compared by place). Random volumes whose loops
/// pass some point twice (where voxels touch along an edge), on a plain and a mirrored grid.
void checkLoopEdgeBits()
{
  const Layout layouts[] = { Layout(),
    { false, { 0, 0, 0 }, { 4, 0, 0 }, { -1, 1, 1 }, VTK_CHAR } };
  long facesPassingTwice = 0;
  unsigned seed = 300;
  for (const Layout& l : layouts)
    for (double density : { 0.3, 0.5, 0.7 })
    {
      const Volume v = randomVolume({ 9, 8, 7 }, density, 1, seed++);
      const std::string what = "loop edges " + std::to_string(seed);
      vtkNew<vtkStandardPlanePolyhedrizer> f;
      f->SetInputData(makeImage(v, l));
      f->SetOutputModeToStandardFaces();
      f->Update();
      using Place = std::array<double, 3>;
      auto placeOf = [](vtkPolyData* d, vtkIdType id)
      {
        Place p;
        d->GetPoint(id, p.data());
        return p;
      };
      std::map<long, std::set<std::pair<Place, Place>>> edgesOfFace;
      vtkPolyData* loops = f->GetOutput();
      vtkDataArray* loopFace = loops->GetCellData()->GetArray("FaceId");
      vtkNew<vtkIdList> ids;
      for (vtkIdType c = 0; c < loops->GetNumberOfCells(); ++c)
      {
        loops->GetCellPoints(c, ids);
        std::set<Place> seen;
        bool twice = false;
        const vtkIdType m = ids->GetNumberOfIds();
        for (vtkIdType i = 0; i < m; ++i)
        {
          const Place a = placeOf(loops, ids->GetId(i));
          twice = !seen.insert(a).second || twice;
          edgesOfFace[static_cast<long>(loopFace->GetTuple1(c))].insert(
            { a, placeOf(loops, ids->GetId((i + 1) % m)) });
        }
        facesPassingTwice += twice;
      }
      f->SetOutputModeToTriangulatedFaces();
      f->Update();
      vtkPolyData* triangles = f->GetOutput();
      checkOneTuplePerElement(triangles, what);
      vtkDataArray* face = triangles->GetCellData()->GetArray("FaceId");
      vtkDataArray* bits = triangles->GetCellData()->GetArray("LoopEdges");
      CHECK(face && bits, what << ": FaceId and LoopEdges");
      if (!face || !bits)
        continue;
      long wrong = 0;
      for (vtkIdType c = 0; c < triangles->GetNumberOfCells(); ++c)
      {
        triangles->GetCellPoints(c, ids);
        const auto& edges = edgesOfFace[static_cast<long>(face->GetTuple1(c))];
        const int mask = static_cast<int>(bits->GetTuple1(c));
        for (vtkIdType k = 0; k < 3; ++k)
        {
          const bool along = edges.count({ placeOf(triangles, ids->GetId(k)),
                               placeOf(triangles, ids->GetId((k + 1) % 3)) }) > 0;
          wrong += along != (((mask >> k) & 1) != 0);
        }
      }
      CHECK(wrong == 0, what << ": " << wrong << " LoopEdges bits differ from the loops");
    }
  CHECK(facesPassingTwice > 0, "loop edges: no loop passes a point twice");
}

void checkSphereAndDegenerate()
{
  Volume ball;
  ball.dims = { 35, 35, 35 };
  for (int z = 0; z < 35; ++z)
    for (int y = 0; y < 35; ++y)
      for (int x = 0; x < 35; ++x)
        ball.values.push_back(
          (x - 17) * (x - 17) + (y - 17) * (y - 17) + (z - 17) * (z - 17) <= 240);
  checkImage(ball, Layout(), false, "sphere");
  vtkNew<vtkStandardPlanePolyhedrizer> f;
  f->SetInputData(makeImage(ball, Layout()));
  f->Update();
  CHECK(fieldValue(f->GetOutput(), "NumberOfSurfels") == 4494, "sphere: the paper's 4494");
  CHECK(fieldValue(f->GetOutput(), "NumberOfFaces") <= 120, "sphere: at most 120 faces");
  f->SetMaximumFaceSize(10);
  f->Update();
  CHECK(fieldValue(f->GetOutput(), "MaximumFaceSize") <= 10, "MaximumFaceSize");
  f->SetMaximumFaceSize(0);
  f->SetMaximumDepth(2);
  f->SetMergeFaces(true);
  f->Update();
  CHECK(fieldValue(f->GetOutputDataObject(1), "ReversionMatches") == 1, "depth and merge");

  for (double density : { 0.0, 1.0 })
    checkImage(
      randomVolume({ 6, 5, 4 }, density, 1, 3), Layout(), false, density > 0 ? "full" : "empty");
  Volume plate = randomVolume({ 9, 7, 1 }, 1.0, 1, 4);
  checkImage(plate, Layout(), false, "one-voxel-thick plate");
}

void checkErrorsAbortPrint()
{
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(3, 3, 3);
    vtkNew<vtkStandardPlanePolyhedrizer> f;
    f->SetInputData(image);
    const int errorCount = vbrtest::updateCountingErrors(f);
    CHECK(errorCount > 0, "missing scalars must raise an error");
  }
  {
    vtkNew<vtkImageData> image; // no points at all
    vtkNew<vtkStandardPlanePolyhedrizer> f;
    f->SetInputData(image);
    const int errorCount = vbrtest::updateCountingErrors(f);
    CHECK(errorCount == 0 && f->GetOutput()->GetNumberOfCells() == 0, "empty image");
  }
  {
    const Volume v = randomVolume({ 12, 12, 12 }, 0.5, 1, 5);
    vtkNew<vtkStandardPlanePolyhedrizer> f;
    vtkNew<AbortAtProgress> abort;
    f->AddObserver(vtkCommand::ProgressEvent, abort);
    f->SetInputData(makeImage(v, Layout()));
    f->Update();
    CHECK(abort->Calls > 0 && f->GetOutput()->GetNumberOfCells() == 0, "abort: empty output");
  }
  vtkNew<vtkStandardPlanePolyhedrizer> f;
  std::ostringstream print;
  f->Print(print);
  CHECK(print.str().find("OutputMode: TriangulatedFaces") != std::string::npos, "PrintSelf");
}

/// The "Al" object of the shared data, when present.
void checkRealObject()
{
  std::ifstream in(
    std::string(VOXELBREP_DATA_DIR) + "/dgtal_al/dgtal_al_100x100x100_uint8.raw", std::ios::binary);
  if (!in)
  {
    std::cout << "shared data absent: the Al object is skipped" << std::endl;
    return;
  }
  Volume v;
  v.dims = { 100, 100, 100 };
  std::vector<char> raw(1000000);
  in.read(raw.data(), static_cast<std::streamsize>(raw.size()));
  for (char c : raw)
    v.values.push_back(c == 1);
  checkImage(v, Layout(), false, "Al");
}

} // namespace

int TestStandardPlanePolyhedrizer(int, char*[])
{
  checkRandomImages();
  checkLoopEdgeBits();
  checkSphereAndDegenerate();
  checkErrorsAbortPrint();
  checkRealObject();
  return vbrtest::testResult();
}
