// vtkEVMBoundaryFilter on random and degenerate images, checked against brute force computed
// from the input voxels and from the output polydata alone: faces per plane, holes, area,
// volume, closedness, orientation and the exact round trip, for point and cell scalars,
// several scalar types, non-unit anisotropic spacing and extents not starting at 0.
#include "vtkEVMBoundaryFilter.h"

#include "PixelTopology.h"
#include "TestImages.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLongLongArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <tuple>
#include <vector>

namespace
{

using Int3 = std::array<int, 3>;
using PixelSet = bf::PixelSet;
using vbrtest::AbortAtProgress;
using vbrtest::Layout;
using vbrtest::makeImage;
using vbrtest::randomVolume;
using vbrtest::Volume;

vtkIdType fieldValue(vtkPolyData* out, const char* name, int component = 0)
{
  vtkDataArray* a = out->GetFieldData()->GetArray(name);
  return a ? static_cast<vtkIdType>(a->GetComponent(0, component)) : -1;
}

/// Output point i back in grid-vertex indices (exact integers or the test fails).
Int3 toGrid(vtkPolyData* out, vtkIdType i, const Layout& l, bool& exact)
{
  double p[3];
  out->GetPoint(i, p);
  Int3 g{};
  for (int d = 0; d < 3; ++d)
  {
    const double shift = l.cellData ? 0.0 : -0.5;
    const double index = (p[d] - l.origin[d]) / l.spacing[d] - l.extentMin[d] - shift;
    g[d] = static_cast<int>(std::lround(index));
    exact = exact && std::abs(index - g[d]) < 1e-9;
  }
  return g;
}

using bf::components;
using bf::PlaneKey;

/// Everything one expects for the voxels of one label (label < 0: every non-zero value).
struct Expected
{
  std::map<PlaneKey, std::vector<PixelSet>> faces;
  long long surfels = 0, voxels = 0, extremeVertices = 0, holes = 0;
};

Expected expect(const Volume& v, int label, bool merged)
{
  auto in = [&](int x, int y, int z)
  {
    const int value = v.at(x, y, z);
    return label < 0 ? value != 0 : value == label;
  };
  Expected e;
  std::map<PlaneKey, PixelSet> surfels;
  for (int z = 0; z < v.dims[2]; ++z)
    for (int y = 0; y < v.dims[1]; ++y)
      for (int x = 0; x < v.dims[0]; ++x)
      {
        if (!in(x, y, z))
          continue;
        ++e.voxels;
        const Int3 p{ x, y, z };
        for (int axis = 0; axis < 3; ++axis)
          for (int sign = -1; sign <= 1; sign += 2)
          {
            Int3 n = p;
            n[axis] += sign;
            if (in(n[0], n[1], n[2]))
              continue;
            ++e.surfels;
            surfels[{ axis, sign, p[axis] + (sign > 0) }].insert(
              { p[(axis + 1) % 3], p[(axis + 2) % 3] });
          }
      }
  for (int z = 0; z <= v.dims[2]; ++z)
    for (int y = 0; y <= v.dims[1]; ++y)
      for (int x = 0; x <= v.dims[0]; ++x)
      {
        int n = 0;
        for (int k = 0; k < 8; ++k)
          n += in(x - (k & 1), y - ((k >> 1) & 1), z - ((k >> 2) & 1));
        e.extremeVertices += n % 2;
      }
  for (const auto& s : surfels)
  {
    e.faces[s.first] = components(s.second, merged);
    for (const auto& f : e.faces[s.first])
      e.holes += bf::holeCount(f);
  }
  return e;
}

/// The axis along which all `points` have the same coordinate (the last such axis), -1 when
/// there is none or no point.
int constantAxis(const std::vector<Int3>& points)
{
  int axis = -1;
  for (int d = 0; d < 3 && !points.empty(); ++d)
  {
    bool constant = true;
    for (const Int3& q : points)
      constant = constant && q[d] == points[0][d];
    if (constant)
      axis = d;
  }
  return axis;
}

/// Twice the signed area of the polygon `points`, lying in a plane normal to `axis`, in the
/// (axis + 1, axis + 2) coordinates (shoelace formula): positive counter-clockwise.
long long twiceSignedArea(const std::vector<Int3>& points, int axis)
{
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  long long area = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const Int3& a = points[i];
    const Int3& b = points[(i + 1) % points.size()];
    area += static_cast<long long>(a[ua]) * b[va] - static_cast<long long>(b[ua]) * a[va];
  }
  return area;
}

/// Faces of a Loops output, rasterized per FaceId in grid coordinates (even-odd rule).
struct Produced
{
  std::map<PlaneKey, std::vector<PixelSet>> faces;
  std::map<vtkIdType, int> labelOfFace;
  long long holeLoops = 0;
  bool exact = true, oriented = true;
};

Produced readFaces(vtkPolyData* out, const Layout& l, double labelFilter)
{
  Produced r;
  vtkDataArray* faceIds = out->GetCellData()->GetArray("FaceId");
  vtkDataArray* loopType = out->GetCellData()->GetArray("LoopType");
  vtkDataArray* labels = out->GetCellData()->GetArray("Label");
  if (!faceIds || !loopType || !labels)
  {
    r.exact = false;
    return r;
  }
  struct Loop
  {
    std::vector<Int3> p;
    bool hole;
  };
  std::map<vtkIdType, std::vector<Loop>> loops;
  vtkCellArray* polys = out->GetPolys();
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    if (labelFilter >= 0 && labels->GetTuple1(c) != labelFilter)
      continue;
    out->GetCellPoints(c, ids);
    Loop loop;
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      loop.p.push_back(toGrid(out, ids->GetId(i), l, r.exact));
    loop.hole = loopType->GetTuple1(c) != 0;
    r.holeLoops += loop.hole;
    loops[static_cast<vtkIdType>(faceIds->GetTuple1(c))].push_back(loop);
  }
  (void)polys;
  for (const auto& entry : loops)
  {
    const Int3& p0 = entry.second.front().p.front();
    std::vector<Int3> facePoints;
    for (const Loop& loop : entry.second)
      facePoints.insert(facePoints.end(), loop.p.begin(), loop.p.end());
    const int axis = constantAxis(facePoints);
    if (axis < 0)
    {
      r.exact = false;
      continue;
    }
    const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
    std::map<int, std::vector<int>> crossings;
    int sign = 0;
    for (const Loop& loop : entry.second)
    {
      const long long area = twiceSignedArea(loop.p, axis);
      for (std::size_t i = 0; i < loop.p.size(); ++i)
      {
        const Int3& a = loop.p[i];
        const Int3& b = loop.p[(i + 1) % loop.p.size()];
        if (a[ua] == b[ua])
          for (int j = std::min(a[va], b[va]); j < std::max(a[va], b[va]); ++j)
            crossings[j].push_back(a[ua]);
      }
      const int s = area > 0 ? 1 : -1;
      const int loopSign = loop.hole ? -s : s;
      if (sign == 0)
        sign = loopSign;
      r.oriented = r.oriented && sign == loopSign;
    }
    PixelSet pixels;
    for (auto& c : crossings)
    {
      std::sort(c.second.begin(), c.second.end());
      for (std::size_t k = 0; k + 1 < c.second.size(); k += 2)
        for (int u = c.second[k]; u < c.second[k + 1]; ++u)
          pixels.insert({ u, c.first });
    }
    r.faces[{ axis, sign, p0[axis] }].push_back(pixels);
  }
  for (auto& e : r.faces)
    std::sort(e.second.begin(), e.second.end());
  return r;
}

/// Runs the filter in Loops mode and compares everything with brute force.
void checkPolygons(const Volume& v, const Layout& l, int mode, bool merged, const std::string& what)
{
  vtkNew<vtkEVMBoundaryFilter> f;
  f->SetInputData(makeImage(v, l));
  f->SetSelectionMode(mode);
  f->SetOutputModeToLoops();
  f->SetMergeNonManifoldFaces(merged);
  f->Update();
  vtkPolyData* out = f->GetOutput();
  std::vector<int> labels;
  if (mode == vtkEVMBoundaryFilter::LABELS)
  {
    std::set<int> s(v.values.begin(), v.values.end());
    s.erase(0);
    labels.assign(s.begin(), s.end());
  }
  else
    labels.push_back(-1);
  long long evs = 0, voxels = 0, surfels = 0, holes = 0, faces = 0;
  for (int label : labels)
  {
    Expected e = expect(v, label, merged);
    for (auto& entry : e.faces)
      std::sort(entry.second.begin(), entry.second.end());
    const Produced p = readFaces(out, l, label < 0 ? -1.0 : label);
    CHECK(p.exact, what << ": output points are not on the voxel grid");
    CHECK(p.oriented, what << ": loops of a face are not oriented consistently");
    // Outer loops counter-clockwise seen from outside: the face's sign is its normal.
    CHECK(p.faces == e.faces, what << " label " << label << ": faces differ from brute force");
    CHECK(p.holeLoops == e.holes, what << ": " << p.holeLoops << " holes, expected " << e.holes);
    evs += e.extremeVertices;
    voxels += e.voxels;
    surfels += e.surfels;
    holes += e.holes;
    for (const auto& entry : e.faces)
      faces += static_cast<long long>(entry.second.size());
  }
  CHECK(fieldValue(out, "NumberOfExtremeVertices") == evs, what << ": extreme vertices");
  CHECK(fieldValue(out, "NumberOfVoxels") == voxels, what << ": voxels");
  CHECK(fieldValue(out, "NumberOfSurfels") == surfels, what << ": surfels");
  CHECK(fieldValue(out, "NumberOfFaces") == faces, what << ": faces");
  CHECK(fieldValue(out, "NumberOfHoles") == holes, what << ": holes");
}

/// The plane of a face's cells (normal `axis`, at `position` along it) and twice their area
/// in grid units.
struct FacePlaneArea
{
  int axis = -1;
  int position = 0;
  long long twiceArea = 0;
  bool operator==(const FacePlaneArea& o) const
  {
    return this->axis == o.axis && this->position == o.position && this->twiceArea == o.twiceArea;
  }
};

/// Per FaceId of an output: the plane of its cells and their area, from the cells alone (a
/// hole's loop counts negative); `exact` false when a cell lies in no grid plane or the cells
/// of one face in two planes. `loopTypes` sums the LoopType of the cells when they are not
/// loops (the Triangles and Polygons modes, whose cells all have LoopType 0).
struct FaceAreas
{
  std::map<vtkIdType, FacePlaneArea> faces;
  bool exact = true;
  long long loopTypes = 0;
};

FaceAreas faceAreasOf(vtkPolyData* out, const Layout& l, bool fromLoopsMode)
{
  FaceAreas r;
  vtkDataArray* faceIds = out->GetCellData()->GetArray("FaceId");
  vtkDataArray* loopType = out->GetCellData()->GetArray("LoopType");
  if (!faceIds || !loopType)
  {
    r.exact = false;
    return r;
  }
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    out->GetCellPoints(c, ids);
    std::vector<Int3> p;
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      p.push_back(toGrid(out, ids->GetId(i), l, r.exact));
    const int axis = constantAxis(p);
    if (axis < 0)
    {
      r.exact = false;
      continue;
    }
    const long long area = std::llabs(twiceSignedArea(p, axis));
    const bool hole = fromLoopsMode && loopType->GetTuple1(c) != 0;
    if (!fromLoopsMode)
      r.loopTypes += static_cast<long long>(loopType->GetTuple1(c));
    FacePlaneArea& face = r.faces[static_cast<vtkIdType>(faceIds->GetTuple1(c))];
    if (face.axis < 0)
    {
      face.axis = axis;
      face.position = p[0][axis];
    }
    if (face.axis != axis || face.position != p[0][axis])
      r.exact = false; // the cells of one face in two planes
    face.twiceArea += hole ? -area : area;
  }
  return r;
}

/// Whether the FaceId of the cells of `out` runs through 0, 1, ..., NumberOfFaces - 1 in
/// order, every face with one cell or more (the Triangles and Polygons modes of a 3D image).
bool faceIdsFollowOn(vtkPolyData* out)
{
  vtkDataArray* faceIds = out->GetCellData()->GetArray("FaceId");
  if (!faceIds)
    return false;
  vtkIdType next = 0;
  for (vtkIdType c = 0; c < faceIds->GetNumberOfTuples(); ++c)
  {
    const vtkIdType id = static_cast<vtkIdType>(faceIds->GetTuple1(c));
    if (id != next && id != next - 1)
      return false;
    next = id + 1;
  }
  return next == fieldValue(out, "NumberOfFaces");
}

/// The cells of the Triangles and Polygons modes carry the FaceId of the face they cover:
/// per FaceId, the same plane and area as the face's loops in Loops mode (whose FaceId is
/// written cell by cell, where the triangles and fan polygons count their cells per face and
/// write it at the end); LoopType 0; the ids in order, face after face.
void checkFaceIdsOfCells(const Volume& v,
  const Layout& l,
  const std::string& what,
  int selection = vtkEVMBoundaryFilter::POSITIVE)
{
  vtkNew<vtkEVMBoundaryFilter> f;
  f->SetInputData(makeImage(v, l));
  f->SetSelectionMode(selection);
  f->SetOutputModeToLoops();
  f->Update();
  const FaceAreas loops = faceAreasOf(f->GetOutput(), l, true);
  CHECK(loops.exact, what << ": Loops output off the grid");
  for (int mode : { vtkEVMBoundaryFilter::TRIANGLES, vtkEVMBoundaryFilter::POLYGONS })
  {
    f->SetOutputMode(mode);
    f->Update();
    const FaceAreas cells = faceAreasOf(f->GetOutput(), l, false);
    CHECK(
      cells.exact, what << " " << f->GetOutputModeAsString() << ": a face's cells off its plane");
    CHECK(cells.loopTypes == 0, what << " " << f->GetOutputModeAsString() << ": LoopType not 0");
    CHECK(cells.faces == loops.faces,
      what << " " << f->GetOutputModeAsString() << ": FaceId, plane or area differ from Loops");
    CHECK(faceIdsFollowOn(f->GetOutput()),
      what << " " << f->GetOutputModeAsString() << ": FaceIds not 0 to NumberOfFaces - 1 in order");
  }
}

/// Triangles: closed, oriented outwards (divergence theorem gives +volume), exact area.
void checkTriangles(const Volume& v, const Layout& l, const std::string& what, bool flatAs2D = true)
{
  vtkNew<vtkEVMBoundaryFilter> f;
  f->SetInputData(makeImage(v, l));
  f->SetFlatImagesAs2D(flatAs2D);
  f->SetOutputModeToTriangles();
  f->Update();
  vtkPolyData* out = f->GetOutput();
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  double area = 0, volume = 0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    out->GetCellPoints(c, ids);
    CHECK(ids->GetNumberOfIds() == 3, what << ": not a triangle");
    if (ids->GetNumberOfIds() != 3)
      return;
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      out->GetPoint(ids->GetId(k), p[k]);
      ++edges[{ ids->GetId(k), ids->GetId((k + 1) % 3) }];
    }
    double u[3], w[3], n[3];
    for (int d = 0; d < 3; ++d)
    {
      u[d] = p[1][d] - p[0][d];
      w[d] = p[2][d] - p[0][d];
    }
    n[0] = u[1] * w[2] - u[2] * w[1];
    n[1] = u[2] * w[0] - u[0] * w[2];
    n[2] = u[0] * w[1] - u[1] * w[0];
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    volume += (p[0][0] * n[0] + p[0][1] * n[1] + p[0][2] * n[2]) / 6.0;
  }
  bool closed = true;
  for (const auto& e : edges)
  {
    auto it = edges.find({ e.first.second, e.first.first });
    closed = closed && it != edges.end() && it->second == e.second;
  }
  CHECK(closed, what << ": the triangle mesh has boundary or inconsistently oriented edges");
  const Expected e = expect(v, -1, false);
  const double sx = l.spacing[0], sy = l.spacing[1], sz = l.spacing[2];
  double expectedArea = 0;
  for (const auto& entry : e.faces)
    for (const auto& c : entry.second)
      expectedArea += c.size() *
        (entry.first.axis == 0      ? sy * sz
            : entry.first.axis == 1 ? sx * sz
                                    : sx * sy);
  const double expectedVolume = e.voxels * sx * sy * sz;
  CHECK(std::abs(area - expectedArea) < 1e-6 * (1 + expectedArea),
    what << ": area " << area << " expected " << expectedArea);
  CHECK(std::abs(volume - expectedVolume) < 1e-6 * (1 + expectedVolume),
    what << ": volume " << volume << " expected " << expectedVolume);
}

/// Counts error events of an algorithm.
/// Asks the filter to stop at its first progress report.
void checkAbort()
{
  const Volume v = randomVolume({ 30, 30, 30 }, 0.4, 1, 5);
  vtkNew<vtkEVMBoundaryFilter> f;
  f->SetInputData(makeImage(v, Layout()));
  f->SetOutputModeToLoops();
  f->Update();
  const vtkIdType full = f->GetOutput()->GetNumberOfCells();
  vtkNew<AbortAtProgress> abort;
  f->AddObserver(vtkCommand::ProgressEvent, abort);
  f->Modified();
  f->Update();
  CHECK(abort->Calls > 0, "progress is reported");
  CHECK(f->GetOutput()->GetNumberOfCells() < full, "an aborted run stops early");
}

/// Aborts the algorithm at the first progress event past `Threshold`.
class AbortPast : public vtkCommand
{
public:
  static AbortPast* New() { return new AbortPast; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    const double progress = *static_cast<double*>(data);
    if (progress > this->Threshold && progress < 1.0 && !this->Fired)
    {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      this->Fired = true;
    }
  }
  double Threshold = 0.0;
  bool Fired = false;
};

/// An abort inside the output-cell phase (the last tenth of an object) stops it there and
/// leaves an empty output, not a part of the boundary.
void checkAbortWhileWritingCells()
{
  const Volume v = randomVolume({ 64, 64, 64 }, 0.5, 1, 8);
  for (int mode : { vtkEVMBoundaryFilter::TRIANGLES, vtkEVMBoundaryFilter::POLYGONS })
  {
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(makeImage(v, Layout()));
    f->SetOutputMode(mode);
    vtkNew<AbortPast> abort;
    abort->Threshold = 0.1 + 0.9 * 0.9; // one object: its cells are written past 0.91
    f->AddObserver(vtkCommand::ProgressEvent, abort);
    f->Update();
    CHECK(abort->Fired, f->GetOutputModeAsString() << ": progress is reported while writing cells");
    CHECK(f->GetOutput()->GetNumberOfCells() == 0,
      f->GetOutputModeAsString() << ": an abort while writing cells leaves an empty output");
  }
}

/// Signed volume enclosed by a closed triangle output (divergence theorem).
double enclosedVolume(vtkPolyData* out)
{
  double volume = 0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    out->GetCellPoints(c, ids);
    double p[3][3];
    for (int k = 0; k < 3; ++k)
      out->GetPoint(ids->GetId(k), p[k]);
    volume += (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
                p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
                p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) /
      6.0;
  }
  return volume;
}

/// Value types, layouts and geometry that need care: 64-bit ranges, NaN labels, a
/// background the type cannot hold, SOA arrays and a mirrored direction matrix.
void checkTypesAndLayouts()
{
  // 64-bit integers near the limits, default UpperThreshold (VTK_DOUBLE_MAX).
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(3, 3, 3);
    vtkNew<vtkLongLongArray> a;
    a->SetNumberOfTuples(27);
    for (vtkIdType i = 0; i < 27; ++i)
      a->SetValue(i, i % 3 == 0 ? VTK_LONG_LONG_MAX : 0);
    image->GetPointData()->SetScalars(a);
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(image);
    f->SetSelectionModeToRange();
    f->SetLowerThreshold(1e18);
    f->Update();
    CHECK(fieldValue(f->GetOutput(), "NumberOfVoxels") == 9, "64-bit range selects the maxima");
  }
  // NaN is never a label; a background of -1 on unsigned data means every value is a label.
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(4, 1, 1);
    vtkNew<vtkFloatArray> a;
    a->SetNumberOfTuples(4);
    a->SetValue(0, std::nanf(""));
    a->SetValue(1, 2.0f);
    a->SetValue(2, 2.0f);
    a->SetValue(3, 0.0f);
    image->GetPointData()->SetScalars(a);
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(image);
    f->SetSelectionModeToLabels();
    f->SetFlatImagesAs2D(false);
    f->Update();
    CHECK(fieldValue(f->GetOutput(), "NumberOfVoxels") == 2, "NaN is not a label");
    vtkNew<vtkUnsignedCharArray> u;
    u->SetNumberOfTuples(4);
    for (vtkIdType i = 0; i < 4; ++i)
      u->SetValue(i, static_cast<unsigned char>(i == 3 ? 255 : 0));
    image->GetPointData()->SetScalars(u);
    f->SetBackgroundValue(-1);
    f->Update();
    CHECK(fieldValue(f->GetOutput(), "NumberOfVoxels") == 4,
      "a background the type cannot hold leaves every value a label (255 kept)");
  }
  // SOA arrays give the same boundary as AOS ones.
  {
    const Volume v = randomVolume({ 6, 5, 4 }, 0.5, 1, 31);
    vtkSmartPointer<vtkImageData> image = makeImage(v, Layout());
    vtkNew<vtkSOADataArrayTemplate<float>> soa;
    soa->SetNumberOfComponents(1);
    soa->SetNumberOfTuples(static_cast<vtkIdType>(v.values.size()));
    for (std::size_t i = 0; i < v.values.size(); ++i)
      soa->SetTypedComponent(static_cast<vtkIdType>(i), 0, static_cast<float>(v.values[i]));
    vtkNew<vtkEVMBoundaryFilter> aos, split;
    aos->SetInputData(image);
    aos->Update();
    vtkNew<vtkImageData> soaImage;
    soaImage->CopyStructure(image);
    soaImage->GetPointData()->SetScalars(soa);
    split->SetInputData(soaImage);
    split->Update();
    CHECK(split->GetOutput()->GetNumberOfCells() == aos->GetOutput()->GetNumberOfCells() &&
        fieldValue(split->GetOutput(), "NumberOfExtremeVertices") ==
          fieldValue(aos->GetOutput(), "NumberOfExtremeVertices"),
      "SOA input gives the AOS result");
  }
  // A mirrored image (direction with determinant -1): still closed and oriented outwards.
  {
    const Volume v = randomVolume({ 7, 6, 5 }, 0.5, 1, 41);
    vtkSmartPointer<vtkImageData> image = makeImage(v, Layout());
    image->SetDirectionMatrix(-1, 0, 0, 0, 1, 0, 0, 0, 1);
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(image);
    f->Update();
    const double volume = enclosedVolume(f->GetOutput());
    long long voxels = 0;
    for (int x : v.values)
      voxels += x != 0;
    CHECK(std::abs(volume - static_cast<double>(voxels)) < 1e-6,
      "mirrored image: enclosed volume " << volume << ", expected " << voxels);
  }
}

void checkErrorsAndDegenerateInputs()
{

  // No scalars at all: an error, not a crash.
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(3, 3, 3);
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(image);
    const int errorCount = vbrtest::updateCountingErrors(f);
    CHECK(errorCount > 0, "missing scalars must raise an error");
    CHECK(f->GetOutput()->GetNumberOfCells() == 0, "missing scalars must give no cells");
  }
  // Component out of range.
  {
    Volume v = randomVolume({ 3, 3, 3 }, 0.5, 1, 1);
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(makeImage(v, Layout()));
    f->SetArrayComponent(2);
    const int errorCount = vbrtest::updateCountingErrors(f);
    CHECK(errorCount > 0, "ArrayComponent out of range must raise an error");
  }

  // Empty selection: empty output, no error.
  {
    Volume v = randomVolume({ 4, 5, 6 }, 0.0, 1, 1);
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(makeImage(v, Layout()));
    const int errorCount = vbrtest::updateCountingErrors(f);
    CHECK(errorCount == 0 && f->GetOutput()->GetNumberOfCells() == 0,
      "an empty selection gives an empty output without error");
    CHECK(fieldValue(f->GetOutput(), "NumberOfFaces") == 0, "empty: no faces");
  }
  // Full selection and a single voxel: 6 faces each.
  for (int n : { 1, 5 })
  {
    Volume v = randomVolume({ n, n + 1, n + 2 }, 1.0, 1, 2);
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(makeImage(v, Layout()));
    f->SetFlatImagesAs2D(false);
    f->SetOutputModeToLoops();
    f->Update();
    CHECK(fieldValue(f->GetOutput(), "NumberOfFaces") == 6, "a box has 6 faces, n=" << n);
    CHECK(fieldValue(f->GetOutput(), "NumberOfExtremeVertices") == 8, "a box has 8 EVs");
  }
  // Range selection on float data, and the multi-component component choice.
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(4, 4, 4);
    vtkNew<vtkFloatArray> a;
    a->SetNumberOfComponents(2);
    a->SetNumberOfTuples(64);
    for (vtkIdType i = 0; i < 64; ++i)
    {
      a->SetComponent(i, 0, 0.0f);
      a->SetComponent(i, 1, i == 21 || i == 22 ? 0.25f : 0.0f);
    }
    image->GetPointData()->SetScalars(a);
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(image);
    f->SetArrayComponent(1);
    f->SetSelectionModeToRange();
    f->SetLowerThreshold(0.2);
    f->SetUpperThreshold(0.3);
    f->SetOutputModeToLoops();
    f->Update();
    CHECK(fieldValue(f->GetOutput(), "NumberOfVoxels") == 2, "range on component 1");
    CHECK(fieldValue(f->GetOutput(), "NumberOfFaces") == 6, "two voxels: 6 faces");
    // Positive mode selects 0.25 (> 0) too.
    f->SetSelectionModeToPositive();
    f->Update();
    CHECK(fieldValue(f->GetOutput(), "NumberOfVoxels") == 2, "positive selects > 0 floats");
  }
}

/// A 2D image's statistics (`flat`: the axis of its one slice) by brute force over its pixels,
/// for the pixels of `label` (< 0: every non-zero value): pixels, their sides facing an unset
/// pixel or the outside (4-neighbours), the extreme vertices of the plane (an odd number of
/// the four pixels around a vertex set) and their distinct coordinates along each axis (none
/// along the flat one).
struct PlanarExpected
{
  long long pixels = 0, edges = 0, vertices = 0;
  std::array<long long, 3> planes{ 0, 0, 0 };
};

PlanarExpected expectPlanar(const Volume& v, int flat, int label)
{
  const int a = (flat + 1) % 3, b = (flat + 2) % 3;
  auto in = [&](int i, int j)
  {
    Int3 p{ 0, 0, 0 };
    p[a] = i;
    p[b] = j;
    const int value = v.at(p[0], p[1], p[2]);
    return label < 0 ? value != 0 : value == label;
  };
  PlanarExpected e;
  for (int j = 0; j < v.dims[b]; ++j)
    for (int i = 0; i < v.dims[a]; ++i)
      if (in(i, j))
      {
        ++e.pixels;
        e.edges += !in(i - 1, j) + !in(i + 1, j) + !in(i, j - 1) + !in(i, j + 1);
      }
  std::set<int> is, js;
  for (int j = 0; j <= v.dims[b]; ++j)
    for (int i = 0; i <= v.dims[a]; ++i)
      if ((in(i - 1, j - 1) + in(i, j - 1) + in(i - 1, j) + in(i, j)) % 2 == 1)
      {
        ++e.vertices;
        is.insert(i);
        js.insert(j);
      }
  e.planes[a] = static_cast<long long>(is.size());
  e.planes[b] = static_cast<long long>(js.size());
  return e;
}

/// The statistics of a 2D image (flat along `flat`) in Positive or Labels mode against
/// expectPlanar, summed over the labels.
void checkPlanarStatistics(const Volume& v,
  const Layout& l,
  int flat,
  int mode,
  const std::string& what)
{
  vtkNew<vtkEVMBoundaryFilter> f;
  f->SetInputData(makeImage(v, l));
  f->SetSelectionMode(mode);
  f->SetOutputModeToPolylines();
  f->Update();
  vtkPolyData* out = f->GetOutput();
  std::set<int> labels{ -1 };
  if (mode == vtkEVMBoundaryFilter::LABELS)
  {
    labels = std::set<int>(v.values.begin(), v.values.end());
    labels.erase(0);
  }
  PlanarExpected sum;
  for (int label : labels)
  {
    const PlanarExpected e = expectPlanar(v, flat, label);
    sum.pixels += e.pixels;
    sum.edges += e.edges;
    sum.vertices += e.vertices;
    for (int k = 0; k < 3; ++k)
      sum.planes[k] += e.planes[k];
  }
  CHECK(fieldValue(out, "NumberOfVoxels") == sum.pixels,
    what << ": " << fieldValue(out, "NumberOfVoxels") << " pixels, expected " << sum.pixels);
  CHECK(fieldValue(out, "NumberOfSurfels") == sum.edges,
    what << ": " << fieldValue(out, "NumberOfSurfels") << " edges, expected " << sum.edges);
  CHECK(fieldValue(out, "NumberOfExtremeVertices") == sum.vertices,
    what << ": " << fieldValue(out, "NumberOfExtremeVertices") << " extreme vertices, expected "
         << sum.vertices);
  for (int k = 0; k < 3; ++k)
    CHECK(fieldValue(out, "NumberOfPlanesOfVertices", k) == sum.planes[k],
      what << ": " << fieldValue(out, "NumberOfPlanesOfVertices", k) << " planes along axis " << k
           << ", expected " << sum.planes[k]);
}

/// A 2D image: closed loops in its plane with the inclusion tree; off: a closed slab.
void checkTwoDimensional()
{
  // Rings with a dot in the middle: a ring face with one hole holding a face.
  Volume v;
  v.dims = { 7, 7, 1 };
  v.values.assign(49, 0);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 7; ++x)
    {
      const int r = std::max(std::abs(x - 3), std::abs(y - 3));
      v.values[y * 7 + x] = (r == 3 || r == 0) ? 1 : 0;
    }
  for (int flat = 0; flat < 3; ++flat)
  {
    // The same picture in the XY, XZ or YZ plane.
    Volume w;
    w.dims = { 7, 7, 7 };
    w.dims[flat] = 1;
    w.values.assign(49, 0);
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 7; ++i)
        w.values[j * 7 + i] = v.values[j * 7 + i];
    vtkNew<vtkEVMBoundaryFilter> f;
    f->SetInputData(makeImage(w, Layout()));
    f->SetOutputModeToPolylines();
    f->Update();
    vtkPolyData* out = f->GetOutput();
    CHECK(out->GetNumberOfLines() == 3, "2D: 3 loops, plane " << flat);
    // The statistics of the 2D path (counted with the extreme vertices): the rings, and
    // random labelled images across word boundaries, point and cell scalars, offset extents.
    Int3 wide{ 70, 131, 9 };
    wide[flat] = 1;
    const Volume labelled = randomVolume(wide, 0.5, 3, 40 + flat);
    for (const bool cellData : { false, true })
    {
      Layout l;
      l.cellData = cellData;
      l.extentMin = { -5 + flat, 7, -2 * flat - 1 };
      const std::string where =
        "2D statistics plane " + std::to_string(flat) + (cellData ? " cells" : " points");
      checkPlanarStatistics(w, l, flat, vtkEVMBoundaryFilter::POSITIVE, where + " rings");
      checkPlanarStatistics(labelled, l, flat, vtkEVMBoundaryFilter::POSITIVE, where);
      checkPlanarStatistics(labelled, l, flat, vtkEVMBoundaryFilter::LABELS, where + " labels");
    }
    CHECK(fieldValue(out, "NumberOfFaces") == 2 && fieldValue(out, "NumberOfHoles") == 1,
      "2D: 2 faces, 1 hole");
    vtkDataArray* depth = out->GetCellData()->GetArray("Depth");
    vtkDataArray* parent = out->GetCellData()->GetArray("ParentFace");
    vtkDataArray* face = out->GetCellData()->GetArray("FaceId");
    CHECK(depth && parent && face, "2D: Depth, ParentFace and FaceId arrays");
    if (depth && parent && face)
    {
      std::multiset<int> depths;
      for (vtkIdType c = 0; c < 3; ++c)
        depths.insert(static_cast<int>(depth->GetTuple1(c)));
      CHECK((depths == std::multiset<int>{ 0, 1, 2 }), "2D: depths 0, 1, 2");
      for (vtkIdType c = 0; c < 3; ++c)
        if (depth->GetTuple1(c) == 2)
          CHECK(parent->GetTuple1(c) == 0, "2D: the dot's parent is the ring");
    }
    // Outer loops run counter-clockwise seen from the positive side of the flat axis.
    vtkDataArray* loopType = out->GetCellData()->GetArray("LoopType");
    for (vtkIdType c = 0; c < out->GetNumberOfCells() && loopType; ++c)
    {
      vtkNew<vtkIdList> ids;
      out->GetCellPoints(c, ids);
      double normal = 0;
      for (vtkIdType i = 0; i + 1 < ids->GetNumberOfIds(); ++i)
      {
        double p[3], q[3];
        out->GetPoint(ids->GetId(i), p);
        out->GetPoint(ids->GetId(i + 1), q);
        const int a = (flat + 1) % 3, b = (flat + 2) % 3;
        normal += p[a] * q[b] - q[a] * p[b];
      }
      CHECK((normal > 0) == (loopType->GetTuple1(c) == 0),
        "2D plane " << flat << ": loop " << c << " winds the wrong way");
    }
    double bounds[6];
    out->GetBounds(bounds);
    CHECK(bounds[2 * flat] == 0 && bounds[2 * flat + 1] == 0, "2D: loops lie in the image plane");
    // As a slab: a closed boundary with 2 x (the ring's and the dot's) faces plus the sides.
    f->SetFlatImagesAs2D(false);
    f->SetOutputModeToLoops();
    f->Update();
    CHECK(fieldValue(f->GetOutput(), "NumberOfVoxels") == 25, "slab voxels");
    Layout l;
    checkTriangles(w, l, "slab plane " + std::to_string(flat), false);
  }
}

} // namespace

int TestEVMBoundaryFilter(int, char*[])
{
  unsigned seed = 7;
  const int types[] = {
    VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_INT, VTK_FLOAT, VTK_DOUBLE, VTK_LONG_LONG, VTK_UNSIGNED_SHORT
  };
  for (int trial = 0; trial < 24; ++trial)
  {
    const Int3 dims{ 2 + (trial * 5) % 11, 2 + (trial * 3) % 9, 2 + (trial * 7) % 8 };
    const double density = 0.1 + 0.8 * (trial % 6) / 5.0;
    Layout l;
    l.cellData = trial % 2 == 1;
    l.extentMin = { -3 + trial % 5, 2 * (trial % 3), -(trial % 4) };
    l.origin = { 0.5 * trial, -1.25, 3.0 };
    l.spacing = { 1.0 + 0.5 * (trial % 3), 0.75, 2.0 };
    l.scalarType = types[trial % 7];
    const Volume v = randomVolume(dims, density, 1 + trial % 3, seed++);
    std::ostringstream what;
    what << "trial " << trial;
    checkPolygons(v, l, vtkEVMBoundaryFilter::POSITIVE, trial % 4 == 3, what.str());
    checkPolygons(v, l, vtkEVMBoundaryFilter::LABELS, false, what.str() + " labels");
    checkTriangles(v, l, what.str());
    checkFaceIdsOfCells(v, l, what.str());
    checkFaceIdsOfCells(v, l, what.str() + " labels", vtkEVMBoundaryFilter::LABELS);
    // The same trial flat (a 2D image): its statistics by the 2D path.
    Int3 flatDims = dims;
    flatDims[trial % 3] = 1;
    const Volume flat = randomVolume(flatDims, density, 1 + trial % 3, 1000u + trial);
    checkPlanarStatistics(flat, l, trial % 3, vtkEVMBoundaryFilter::POSITIVE, what.str() + " flat");
    checkPlanarStatistics(
      flat, l, trial % 3, vtkEVMBoundaryFilter::LABELS, what.str() + " flat labels");
  }
  // 64^3, sparse and dense (many non-manifold contacts), cell scalars, offset extent.
  for (double density : { 0.25, 0.6 })
  {
    const Volume big = randomVolume({ 64, 64, 64 }, density, 1, 99);
    Layout l;
    l.cellData = density > 0.5;
    l.extentMin = { 10, -20, 5 };
    l.spacing = { 0.5, 1.0, 1.5 };
    checkPolygons(big, l, vtkEVMBoundaryFilter::POSITIVE, false, "64^3");
    checkTriangles(big, l, "64^3");
    checkFaceIdsOfCells(big, l, "64^3");
  }
  // The parts of the streamed sweeps made side by side (several slots) and appended in order:
  // their counts of cells per face joined, with threads as on one thread; three labels.
  const std::string backend = vtkSMPTools::GetBackend() ? vtkSMPTools::GetBackend() : "";
  if (vtkSMPTools::SetBackend("STDThread"))
  {
    vtkSMPTools::Initialize(2);
    const Volume labels = randomVolume({ 64, 56, 48 }, 0.5, 3, 5);
    checkFaceIdsOfCells(
      labels, Layout(), "64x56x48 labels, two threads", vtkEVMBoundaryFilter::LABELS);
    checkFaceIdsOfCells(labels, Layout(), "64x56x48, two threads");
    vtkSMPTools::SetBackend(backend.c_str());
  }
  checkErrorsAndDegenerateInputs();
  checkTypesAndLayouts();
  checkAbort();
  checkAbortWhileWritingCells();
  checkTwoDimensional();
  vtkNew<vtkEVMBoundaryFilter> f;
  std::ostringstream print;
  f->Print(print);
  CHECK(print.str().find("OutputMode: Triangles") != std::string::npos, "PrintSelf");
  return vbrtest::testResult();
}
