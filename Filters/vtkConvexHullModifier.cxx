#include "vtkConvexHullModifier.h"

#include "ConvexHullModifier.h"
#include "ConvexHullModifier2D.h"
#include "Geometry.h"
#include "vtkVoxelBRepAdapters.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkConvexHullModifier);

namespace
{

using Int3 = vbr::Point3; // a lattice point or voxel index

/// One selected object: its label, the offset of its box in the grid, its voxels and H, or on
/// a 2D image (flatAxis >= 0) its separating polygons in the plane axes (u, v) of the box.
struct ModifiedObject
{
  vbr::vtk::LabelValue label;
  Int3 offset{ 0, 0, 0 };
  vbr::BitVolume voxels;
  vbr::ModifiedHull result;
  int flatAxis = -1;
  vbr::SeparatingPolygons polygons;
  /// The background centres of the image on the loops, or of the grid on the prism of a flat
  /// object in a volume (the core lists those of the box only; a thickened corner and the
  /// prism's caps lie outside the box), in index coordinates.
  std::vector<Int3> backgroundOnLoops;

  bool complete() const
  {
    return this->flatAxis >= 0 ? this->polygons.complete : this->result.complete;
  }
  const std::string& failure() const
  {
    return this->flatAxis >= 0 ? this->polygons.failure : this->result.failure;
  }
};

/// The axis of a 2D image (one pixel thick along it), or -1 for a volume: the grid's own flat
/// axis (cell data on one layer of points), else the last axis with one voxel.
int flatAxisOf(const vbr::vtk::VoxelGrid& grid)
{
  if (grid.flatAxis >= 0)
    return grid.flatAxis;
  for (int d = 2; d >= 0; --d)
    if (grid.dims[d] == 1)
      return d;
  return -1;
}

/// The object's separating polygons and the background centres of the image on them.
void separateInPlane(ModifiedObject& o,
  int flat,
  const std::array<std::int32_t, 3>& dims,
  const vbr::Execution& exec)
{
  o.flatAxis = flat;
  o.polygons = vbr::separatingPolygons2D(vbr::layerImage(o.voxels, flat, 0), exec);
  const auto uv = vbr::planeAxesOf(flat);
  for (const vbr::Point2L& p : vbr::latticePointsOnLoops(o.polygons.loops))
  {
    Int3 box{ 0, 0, 0 };
    box[uv[0]] = p[0];
    box[uv[1]] = p[1];
    Int3 index = box;
    bool inImage = true;
    for (int a = 0; a < 3; ++a)
    {
      index[a] += o.offset[a];
      inImage = inImage && index[a] >= 0 && index[a] < dims[a];
    }
    const bool inBox =
      p[0] >= 0 && p[1] >= 0 && p[0] < o.voxels.size(uv[0]) && p[1] < o.voxels.size(uv[1]);
    const bool object = inBox &&
      o.voxels.get(static_cast<std::int32_t>(box[0]),
        static_cast<std::int32_t>(box[1]),
        static_cast<std::int32_t>(box[2]));
    if (inImage && !object)
      o.backgroundOnLoops.push_back(index);
  }
}

/// The background centres of the grid on H of a flat object in a volume (the prism of its
/// polygons, whose caps lie one layer off its box on either side): the core lists those of the
/// box only.
void listFlatBackground(ModifiedObject& o, const std::array<std::int32_t, 3>& dims)
{
  vbr::LatticeMesh inGrid = o.result.surface;
  for (auto& p : inGrid.points)
    for (int a = 0; a < 3; ++a)
      p[a] += o.offset[a];
  for (const vbr::LatticePoint& p : vbr::latticePointsOnSurface(inGrid, dims))
  {
    bool inBox = true;
    for (int a = 0; a < 3; ++a)
      inBox = inBox && p[a] >= o.offset[a] && p[a] < o.offset[a] + o.voxels.size(a);
    if (!inBox ||
      !o.voxels.get(static_cast<std::int32_t>(p[0] - o.offset[0]),
        static_cast<std::int32_t>(p[1] - o.offset[1]),
        static_cast<std::int32_t>(p[2] - o.offset[2])))
      o.backgroundOnLoops.push_back({ static_cast<std::int32_t>(p[0]),
        static_cast<std::int32_t>(p[1]),
        static_cast<std::int32_t>(p[2]) });
  }
}

/// The voxels of an object rebuilt from its H or its polygons and their marks alone.
vbr::BitVolume revertObject(const ModifiedObject& o)
{
  if (o.flatAxis < 0)
    return vbr::revertModifiedHull(o.result.surface, o.result.backgroundOnSurface, o.voxels.dims());
  const auto uv = vbr::planeAxesOf(o.flatAxis);
  const vbr::BitVolume plane = vbr::revertSeparatingPolygons2D(
    o.polygons.loops, o.polygons.backgroundOnBoundary, o.voxels.size(uv[0]), o.voxels.size(uv[1]));
  vbr::BitVolume back(o.voxels.size(0), o.voxels.size(1), o.voxels.size(2));
  std::array<std::int32_t, 3> i{ 0, 0, 0 };
  for (i[uv[1]] = 0; i[uv[1]] < plane.size(1); ++i[uv[1]])
    for (i[uv[0]] = 0; i[uv[0]] < plane.size(0); ++i[uv[0]])
      if (plane.get(i[uv[0]], i[uv[1]], 0))
        back.set(i[0], i[1], i[2]);
  return back;
}

bool mirrored(const vbr::vtk::VoxelGrid& grid)
{
  return grid.mirrorsSpace();
}

/// The cells and arrays of port 0.
class OutputBuilder
{
public:
  OutputBuilder(const vbr::vtk::VoxelGrid& grid, int labelType)
    : Grid(grid)
    , Reverse(mirrored(grid))
    , Labels(vbr::vtk::newLabelArray(labelType))
  {
    this->FaceIds->SetName("FaceId");
    this->Levels->SetName("Level");
    this->Marks->SetName("VoxelMark");
  }

  /// The points of one object (voxel centres in world coordinates) and their marks.
  vtkIdType addPoints(const ModifiedObject& o,
    const std::vector<vbr::LatticePoint>& points,
    const std::vector<std::uint8_t>& marks)
  {
    const vtkIdType first = this->Points->GetNumberOfPoints();
    for (std::size_t k = 0; k < points.size(); ++k)
    {
      double index[3], world[3];
      for (int a = 0; a < 3; ++a)
        index[a] = static_cast<double>(points[k][a] + o.offset[a]) + 0.5;
      this->Grid.positionToWorld(index, world);
      this->Points->InsertNextPoint(world);
      this->Marks->InsertNextValue(marks[k]);
    }
    return first;
  }

  void addCell(std::vector<vtkIdType> ids,
    vtkIdType base,
    vtkIdType faceId,
    int level,
    const vbr::vtk::LabelValue& label)
  {
    for (auto& id : ids)
      id += base;
    if (this->Reverse)
      std::reverse(ids.begin(), ids.end());
    this->Polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    this->FaceIds->InsertNextValue(faceId);
    this->Levels->InsertNextValue(level);
    vbr::vtk::appendLabel(this->Labels, label);
  }

  void addHull(const ModifiedObject& o)
  {
    const vbr::CellList& hull = o.result.hull;
    const vtkIdType base = this->addPoints(o, hull.vertices, marksOf(o.voxels, hull.vertices));
    for (const auto& face : hull.faces)
      this->addCell(
        std::vector<vtkIdType>(face.begin(), face.end()), base, this->NextFace++, 0, o.label);
  }

  void addPolyhedron(const ModifiedObject& o, bool triangles)
  {
    const vbr::ModifiedHull& r = o.result;
    const vtkIdType base = this->addPoints(o, r.surface.points, r.vertexMark);
    for (const vbr::ModifiedFace& face : r.faces)
    {
      const vtkIdType id = this->NextFace++;
      if (!triangles && face.loops.size() == 1)
      {
        this->addCell(std::vector<vtkIdType>(face.loops[0].begin(), face.loops[0].end()),
          base,
          id,
          face.level,
          o.label);
        continue;
      }
      for (std::uint32_t t : face.triangles)
      {
        const auto& tri = r.surface.triangles[t];
        this->addCell({ tri[0], tri[1], tri[2] }, base, id, face.level, o.label);
      }
    }
  }

  /// A 2D object: the convex polygon, or every polygon with holes (one cell when it has no
  /// hole and triangles are not asked for, else its triangles), in the image plane.
  void addPolygons(const ModifiedObject& o, int mode)
  {
    const vbr::SeparatingPolygons& r = o.polygons;
    if (mode == vtkConvexHullModifier::CONVEX_HULL)
    {
      const vtkIdType base = this->addPlanePoints(o, r.hull);
      std::vector<vtkIdType> ids(r.hull.size());
      std::iota(ids.begin(), ids.end(), 0);
      this->addCell(ids, base, this->NextFace++, 0, o.label);
      return;
    }
    for (const vbr::SeparatingPolygon& polygon : r.polygons)
    {
      const vtkIdType id = this->NextFace++;
      const std::vector<vbr::Point2L> corners = vbr::polygonCorners(r, polygon);
      const vtkIdType base = this->addPlanePoints(o, corners);
      if (mode == vtkConvexHullModifier::POLYHEDRON && polygon.holes.empty())
      {
        std::vector<vtkIdType> ids(corners.size());
        std::iota(ids.begin(), ids.end(), 0);
        this->addCell(ids, base, id, polygon.level, o.label);
        continue;
      }
      for (const vbr::Triangle& t : vbr::triangulatePolygonWithHoles(r, polygon))
        this->addCell({ t[0], t[1], t[2] }, base, id, polygon.level, o.label);
    }
  }

  /// Corners of a 2D object (lattice points of its box's plane) at their pixel centres in the
  /// image plane, with their marks.
  vtkIdType addPlanePoints(const ModifiedObject& o, const std::vector<vbr::Point2L>& corners)
  {
    const auto uv = vbr::planeAxesOf(o.flatAxis);
    // A flat axis of the grid (cell data on one layer of points) has no half-voxel shift: the
    // pixels' plane is the points' plane either way.
    const double flatPosition = this->Grid.flatAxis == o.flatAxis ? 0.0 : 0.5;
    const vtkIdType first = this->Points->GetNumberOfPoints();
    for (const vbr::Point2L& c : corners)
    {
      double index[3], world[3];
      index[uv[0]] = static_cast<double>(c[0] + o.offset[uv[0]]) + 0.5;
      index[uv[1]] = static_cast<double>(c[1] + o.offset[uv[1]]) + 0.5;
      index[o.flatAxis] = static_cast<double>(o.offset[o.flatAxis]) + flatPosition;
      this->Grid.positionToWorld(index, world);
      this->Points->InsertNextPoint(world);
      Int3 box{ 0, 0, 0 };
      box[uv[0]] = c[0];
      box[uv[1]] = c[1];
      const bool inBox =
        c[0] >= 0 && c[1] >= 0 && c[0] < o.voxels.size(uv[0]) && c[1] < o.voxels.size(uv[1]);
      this->Marks->InsertNextValue(inBox &&
            o.voxels.get(static_cast<std::int32_t>(box[0]),
              static_cast<std::int32_t>(box[1]),
              static_cast<std::int32_t>(box[2]))
          ? 1
          : 0);
    }
    return first;
  }

  void finish(vtkPolyData* output)
  {
    output->SetPoints(this->Points);
    output->SetPolys(this->Polys);
    output->GetCellData()->AddArray(this->FaceIds);
    output->GetCellData()->AddArray(this->Levels);
    this->Labels->SetName("Label");
    output->GetCellData()->AddArray(this->Labels);
    output->GetPointData()->AddArray(this->Marks);
  }

  static std::vector<std::uint8_t> marksOf(const vbr::BitVolume& v,
    const std::vector<vbr::LatticePoint>& points)
  {
    std::vector<std::uint8_t> marks;
    for (const auto& p : points)
      marks.push_back(v.get(static_cast<std::int32_t>(p[0]),
                        static_cast<std::int32_t>(p[1]),
                        static_cast<std::int32_t>(p[2]))
          ? 1
          : 0);
    return marks;
  }

private:
  const vbr::vtk::VoxelGrid& Grid;
  bool Reverse;
  vtkIdType NextFace = 0;
  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Polys;
  vtkNew<vtkIdTypeArray> FaceIds;
  vtkNew<vtkIntArray> Levels;
  vtkNew<vtkUnsignedCharArray> Marks;
  vtkSmartPointer<vtkDataArray> Labels;
};

/// PASS 1: H of every selected object. False when aborted.
bool modifyObjects(vtkConvexHullModifier* self,
  const vbr::vtk::InputObjects& in,
  std::vector<ModifiedObject>& objects)
{
  const std::size_t n = in.objects.size();
  const auto coplanar = static_cast<vbr::CoplanarFaces>(self->GetCoplanarFaces());
  const int flat = flatAxisOf(in.grid); // a 2D image: separating polygons in its plane
  for (std::size_t i = 0; i < n; ++i)
  {
    if (self->GetAbortExecute())
      return false;
    const double from = 0.05 + 0.85 * i / n, to = 0.05 + 0.85 * (i + 1) / n;
    ModifiedObject o;
    o.label = in.objects[i].label;
    o.offset = in.objects[i].offset;
    o.voxels = vbr::vtk::inImageAxes(
      in.objects[i].select(vbr::vtk::makeExecution(self, from, from)), in.axes, o.offset);
    if (o.voxels.empty())
      continue;
    if (flat >= 0)
      separateInPlane(o, flat, in.grid.dims, vbr::vtk::makeExecution(self, from, to));
    else
      o.result = vbr::modifyConvexHull(o.voxels, coplanar, vbr::vtk::makeExecution(self, from, to));
    if (flat < 0 && o.result.hull.dimension < 3)
      listFlatBackground(o, in.grid.dims);
    objects.push_back(std::move(o));
  }
  return !self->GetAbortExecute();
}

/// Port 0: the cells of every object by the output mode.
void writeCells(const std::vector<ModifiedObject>& objects,
  const vbr::vtk::InputObjects& in,
  int mode,
  bool labelsMode,
  vtkPolyData* output)
{
  OutputBuilder builder(in.grid, in.labelType);
  for (const ModifiedObject& o : objects)
  {
    if (o.flatAxis >= 0)
      builder.addPolygons(o, mode);
    else if (mode == vtkConvexHullModifier::CONVEX_HULL)
      builder.addHull(o);
    else
      builder.addPolyhedron(o, mode == vtkConvexHullModifier::TRIANGLES);
  }
  builder.finish(output);
  vbr::vtk::setBoundaryColoring(output, labelsMode);
}

/// The statistics of section 5, summed over the objects (the degree: their maximum).
struct Statistics
{
  vtkIdType vertices = 0, edges = 0, faces = 0, hullFaces = 0, concavities = 0, cavities = 0,
            tunnels = 0, degree = 0, joinedShells = 0, cutHandles = 0;

  /// H of a volume's object, or the polygons of a 2D image's (loops: as many edges as corners;
  /// notches count as concavities, holes as cavities, no tunnels in the plane).
  void add(const ModifiedObject& o)
  {
    if (o.flatAxis >= 0)
    {
      const vbr::SeparatingPolygons& r = o.polygons;
      for (const vbr::SeparatingLoop& loop : r.loops)
      {
        this->vertices += static_cast<vtkIdType>(loop.corners.size());
        this->edges += static_cast<vtkIdType>(loop.corners.size());
      }
      this->faces += static_cast<vtkIdType>(r.polygons.size());
      this->hullFaces += r.hull.empty() ? 0 : 1;
      this->concavities += r.notches;
      this->cavities += r.holes;
      this->degree = std::max<vtkIdType>(this->degree, r.degreeOfNonConvexity);
      return;
    }
    const vbr::ModifiedHull& r = o.result;
    this->vertices += static_cast<vtkIdType>(r.surface.points.size());
    this->edges += static_cast<vtkIdType>(r.edgeCount);
    this->faces += static_cast<vtkIdType>(r.faces.size());
    this->hullFaces += static_cast<vtkIdType>(r.hull.faces.size());
    this->concavities += r.concavities;
    this->cavities += r.cavities;
    this->tunnels += r.tunnels;
    this->degree = std::max<vtkIdType>(this->degree, r.degreeOfNonConvexity);
    this->joinedShells += r.joinedShells;
    this->cutHandles += r.cutHandles;
  }
};

/// The background centres on H (or on the loops) of every object, in index coordinates.
void addBackgroundCentres(const ModifiedObject& o, vtkIntArray* onSurface)
{
  if (o.flatAxis >= 0 || o.result.hull.dimension < 3)
  {
    for (const Int3& p : o.backgroundOnLoops)
      onSurface->InsertNextTuple3(
        static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]));
    return;
  }
  for (const auto& p : o.result.backgroundOnSurface)
    onSurface->InsertNextTuple3(static_cast<double>(p[0] + o.offset[0]),
      static_cast<double>(p[1] + o.offset[1]),
      static_cast<double>(p[2] + o.offset[2]));
}

/// The statistics of section 5 and the marks (field data of port 0).
void writeStatistics(const std::vector<ModifiedObject>& objects, bool separates, vtkFieldData* fd)
{
  Statistics n;
  vtkNew<vtkIntArray> onSurface;
  onSurface->SetName("BackgroundCentresOnSurface");
  onSurface->SetNumberOfComponents(3);
  for (const ModifiedObject& o : objects)
  {
    n.add(o);
    addBackgroundCentres(o, onSurface);
  }
  vbr::vtk::addFieldValue(fd, "NumberOfVertices", n.vertices);
  vbr::vtk::addFieldValue(fd, "NumberOfEdges", n.edges);
  vbr::vtk::addFieldValue(fd, "NumberOfFaces", n.faces);
  vbr::vtk::addFieldValue(fd, "NumberOfHullFaces", n.hullFaces);
  vbr::vtk::addFieldValue(fd, "NumberOfConcavities", n.concavities);
  vbr::vtk::addFieldValue(fd, "NumberOfCavities", n.cavities);
  vbr::vtk::addFieldValue(fd, "NumberOfTunnels", n.tunnels);
  vbr::vtk::addFieldValue(fd, "DegreeOfNonConvexity", n.degree);
  vbr::vtk::addFieldValue(fd, "NumberOfJoinedShells", n.joinedShells);
  vbr::vtk::addFieldValue(fd, "NumberOfCutHandles", n.cutHandles);
  vbr::vtk::addFieldValue(fd, "Separates", separates ? 1 : 0);
  fd->AddArray(onSurface);
}

/// PASS 2, port 1: the voxels rebuilt from H and its marks alone, per object, compared with
/// the object's voxels and, written as the user reads them, with the selection (each rank's
/// piece under MPI, collective then; on the ranks other than 0 `objects` is empty). Returns
/// the first object whose reversion differs (or whose H is incomplete), or -1.
long writeReversion(const std::vector<ModifiedObject>& objects,
  vbr::vtk::InputObjects& in,
  vtkImageData* input,
  vtkImageData* output)
{
  const vbr::vtk::VoxelGrid& grid = in.grid;
  const vtkIdType n = vtkIdType(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  const bool distributed = in.piece.distributed();
  vtkNew<vtkUnsignedCharArray> selection;
  vbr::vtk::resizeOrThrow(selection, distributed && in.piece.rank != 0 ? 0 : n);
  std::fill_n(selection->GetPointer(0), selection->GetNumberOfValues(), 0);
  std::vector<unsigned char> expected(static_cast<std::size_t>(selection->GetNumberOfValues()), 0);
  long wrong = -1;
  for (std::size_t i = 0; i < objects.size(); ++i)
  {
    const ModifiedObject& o = objects[i];
    const vbr::BitVolume back = revertObject(o);
    if ((back != o.voxels || !o.complete()) && wrong < 0)
      wrong = static_cast<long>(i);
    vbr::vtk::markVoxels(back, o.offset, grid.dims, selection->GetPointer(0));
    vbr::vtk::markVoxels(o.voxels, o.offset, grid.dims, expected.data());
  }
  // Under MPI rank 0's grid is the whole image's, by construction; its input is a piece.
  const vtkIdType tuples = distributed ? n
    : grid.cellData                    ? input->GetNumberOfCells()
                                       : input->GetNumberOfPoints();
  const bool same = wrong < 0 && tuples == n &&
    std::equal(expected.begin(), expected.end(), selection->GetPointer(0));
  vbr::vtk::writeReversionImage(in, selection, same, input, output);
  return same ? -1 : std::max(wrong, 0L);
}

} // namespace

//------------------------------------------------------------------------------
vtkConvexHullModifier::vtkConvexHullModifier()
{
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, vtkDataSetAttributes::SCALARS);
  this->SetProgressText("Convex Hull Modifier");
}

vtkConvexHullModifier::~vtkConvexHullModifier() = default;

int vtkConvexHullModifier::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkConvexHullModifier::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkImageData");
  return 1;
}

int vtkConvexHullModifier::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vbr::vtk::removeImageInformation(outputVector, 0);
  return 1;
}

int vtkConvexHullModifier::RequestUpdateExtent(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vbr::vtk::requestWholeImage(this, request, inputVector[0], outputVector);
  return 1;
}

const char* vtkConvexHullModifier::GetOutputModeAsString()
{
  switch (this->OutputMode)
  {
    case CONVEX_HULL:
      return "ConvexHull";
    case TRIANGLES:
      return "Triangles";
    default:
      return "Polyhedron";
  }
}

const char* vtkConvexHullModifier::GetCoplanarFacesAsString()
{
  switch (this->CoplanarFaces)
  {
    case VISIBLE:
      return "Visible";
    case INVISIBLE:
      return "Invisible";
    default:
      return "Extension";
  }
}

int vtkConvexHullModifier::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vbr::vtk::executeGuarded(this,
    outputVector,
    "Convex hull modification",
    [&] { return this->Execute(inputVector, outputVector); });
}

int vtkConvexHullModifier::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkImageData* reversion = vtkImageData::GetData(outputVector, 1);
  if (!input || !output || !reversion)
  {
    vtkErrorMacro(<< "Input must be a vtkImageData.");
    return 0;
  }
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  vbr::vtk::SelectionSettings settings = vbr::vtk::selectionSettingsOf(this);
  // The selection reads a flat image like any other; flatAxisOf then finds its plane.
  settings.flatImagesAs2D = false;
  settings.maximumVoxelsPerAxis = (1 << 20) - 1;
  settings.bytesPerVoxel = 1.0 / 8.0 + 2.0;
  settings.distributed = true; // H of the whole image on rank 0 (N ranks = 1 rank)
  vbr::vtk::InputObjects in;
  if (!vbr::vtk::readInputObjects(this, input, scalars, association, settings, in))
    return 0;
  this->UpdateProgress(0.05);

  // PASS 1: the hull and H of every object (sections 3 and 4), one object at a time.
  std::vector<ModifiedObject> objects;
  if (!modifyObjects(this, in, objects))
  {
    output->Initialize(); // aborted
    if (in.piece.distributed())
      vbr::vtk::writeReversionImage(in, nullptr, false, input, reversion); // tell the others
    reversion->Initialize();
    return 1;
  }
  this->UpdateProgress(0.9);

  // PASS 2: the voxels rebuilt from H and its marks alone, checked against the selection.
  const long wrong = writeReversion(objects, in, input, reversion);

  // PASS 3: the cells and statistics.
  writeCells(objects, in, this->OutputMode, this->GetSelectionMode() == LABELS, output);
  writeStatistics(objects, wrong < 0, output->GetFieldData());
  vbr::vtk::addDistributionFields(output->GetFieldData(), in.piece);
  if (wrong >= 0)
  {
    const ModifiedObject& o = objects[static_cast<std::size_t>(wrong)];
    vtkErrorMacro(<< "The " << (o.flatAxis >= 0 ? "polygons do" : "polyhedron does")
                  << " not separate object " << wrong << " (" << o.voxels.count() << " voxels)"
                  << (o.failure().empty() ? "" : ": " + o.failure()) << ".");
    return 0;
  }
  // A complete H that misses something (a topology it could not give, lost holes not cut)
  // says so in its failure text: warned, never silent.
  long noted = -1, notes = 0;
  for (std::size_t k = 0; k < objects.size(); ++k)
    if (objects[k].complete() && !objects[k].failure().empty())
    {
      noted = noted < 0 ? static_cast<long>(k) : noted;
      ++notes;
    }
  if (noted >= 0)
    vtkWarningMacro(<< notes << " object(s) with a note, the first object " << noted << ": "
                    << objects[static_cast<std::size_t>(noted)].failure() << ".");
  return 1;
}

void vtkConvexHullModifier::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Selection:\n";
  this->Selection->PrintSelf(os, indent.GetNextIndent());
  os << indent << "OutputMode: " << this->GetOutputModeAsString() << "\n";
  os << indent << "CoplanarFaces: " << this->GetCoplanarFacesAsString() << "\n";
}
