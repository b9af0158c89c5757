#include "vtkConvexHullModifier.h"

#include "ConvexHullModifier.h"
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
#include <string>
#include <vector>

vtkStandardNewMacro(vtkConvexHullModifier);

namespace
{

using Int3 = vbr::Point3; // a lattice point or voxel index

/// One selected object: its label, the offset of its box in the grid, its voxels and H.
struct ModifiedObject
{
  vbr::vtk::LabelValue label;
  Int3 offset{ 0, 0, 0 };
  vbr::BitVolume voxels;
  vbr::ModifiedHull result;
};

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
    o.result = vbr::modifyConvexHull(o.voxels, coplanar, vbr::vtk::makeExecution(self, from, to));
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
    if (mode == vtkConvexHullModifier::CONVEX_HULL)
      builder.addHull(o);
    else
      builder.addPolyhedron(o, mode == vtkConvexHullModifier::TRIANGLES);
  }
  builder.finish(output);
  vbr::vtk::setBoundaryColoring(output, labelsMode);
}

/// The statistics of section 5 and the marks (field data of port 0).
void writeStatistics(const std::vector<ModifiedObject>& objects, bool separates, vtkFieldData* fd)
{
  vtkIdType vertices = 0, edges = 0, faces = 0, hullFaces = 0, concavities = 0, cavities = 0,
            tunnels = 0, degree = 0;
  vtkNew<vtkIntArray> onSurface;
  onSurface->SetName("BackgroundCentresOnSurface");
  onSurface->SetNumberOfComponents(3);
  for (const ModifiedObject& o : objects)
  {
    const vbr::ModifiedHull& r = o.result;
    vertices += static_cast<vtkIdType>(r.surface.points.size());
    edges += static_cast<vtkIdType>(r.edgeCount);
    faces += static_cast<vtkIdType>(r.faces.size());
    hullFaces += static_cast<vtkIdType>(r.hull.faces.size());
    concavities += r.concavities;
    cavities += r.cavities;
    tunnels += r.tunnels;
    degree = std::max<vtkIdType>(degree, r.degreeOfNonConvexity);
    for (const auto& p : r.backgroundOnSurface)
      onSurface->InsertNextTuple3(static_cast<double>(p[0] + o.offset[0]),
        static_cast<double>(p[1] + o.offset[1]),
        static_cast<double>(p[2] + o.offset[2]));
  }
  vbr::vtk::addFieldValue(fd, "NumberOfVertices", vertices);
  vbr::vtk::addFieldValue(fd, "NumberOfEdges", edges);
  vbr::vtk::addFieldValue(fd, "NumberOfFaces", faces);
  vbr::vtk::addFieldValue(fd, "NumberOfHullFaces", hullFaces);
  vbr::vtk::addFieldValue(fd, "NumberOfConcavities", concavities);
  vbr::vtk::addFieldValue(fd, "NumberOfCavities", cavities);
  vbr::vtk::addFieldValue(fd, "NumberOfTunnels", tunnels);
  vbr::vtk::addFieldValue(fd, "DegreeOfNonConvexity", degree);
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
    const vbr::BitVolume back =
      vbr::revertModifiedHull(o.result.surface, o.result.backgroundOnSurface, o.voxels.dims());
    if ((back != o.voxels || !o.result.complete) && wrong < 0)
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
  settings.flatImagesAs2D = false; // a flat image is a one-voxel-thick slab
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
    vtkErrorMacro(<< "The polyhedron does not separate object " << wrong << " (" << o.voxels.count()
                  << " voxels)" << (o.result.failure.empty() ? "" : ": " + o.result.failure)
                  << ".");
    return 0;
  }
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
