#include "vtkFaceOctreeBoundaryFilter.h"

#include "DeformedModel.h"
#include "FaceOctree.h"
#include "FaceOctreeBoundary.h"
#include "vtkVoxelBRepAdapters.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkFaceOctreeBoundaryFilter);

namespace
{

using vbr::Vec3;

/// Statistics written to the output's field data.
struct Statistics
{
  vtkIdType boundaryVoxels = 0, faceNodes = 0, polygons = 0, triangles = 0, prunedVoxels = 0;
  double maximumDistance = 0.0;
};

/// What every object is extracted with.
struct ObjectSettings
{
  int outputMode;
  bool pruneCrests;
  vbr::DeformedModelOptions relaxation;
  vbr::FaceOctreeOptions octree;
};

/// Whether the grid's map to world coordinates mirrors space (a direction matrix with
/// negative determinant, or a negative spacing): cells are then reversed.
bool reversesOrientation(const vbr::vtk::VoxelGrid& grid)
{
  return grid.mirrorsSpace();
}

/// The boundary and the face octree in world coordinates, gathered object by object.
class OutputBuilder
{
public:
  OutputBuilder(const vbr::vtk::VoxelGrid& grid, int labelType)
    : Grid(grid)
    , Reverse(reversesOrientation(grid))
    , Labels(vbr::vtk::newLabelArray(labelType))
    , BoxLabels(vbr::vtk::newLabelArray(labelType))
  {
    this->Points->SetDataTypeToDouble();
    this->BoxPoints->SetDataTypeToDouble();
    this->FaceNodeId->SetName("FaceNodeId");
    this->NodeLevel->SetName("NodeLevel");
    this->BoxNodeId->SetName("FaceNodeId");
    this->BoxLevel->SetName("NodeLevel");
    this->PlaneNormal->SetName("PlaneNormal");
    this->PlaneNormal->SetNumberOfComponents(3);
    this->PlaneOffset->SetName("PlaneOffset");
  }

  Vec3 toWorld(const Vec3& p, const std::array<std::int32_t, 3>& offset) const
  {
    const double v[3] = { p[0] + offset[0], p[1] + offset[1], p[2] + offset[2] };
    Vec3 w;
    this->Grid.positionToWorld(v, w.data());
    return w;
  }

  void appendMesh(const vbr::BoundaryMesh& mesh,
    const vbr::vtk::Selected& object,
    vtkIdType nodeBase)
  {
    const vtkIdType base = this->Points->GetNumberOfPoints();
    for (const Vec3& p : mesh.points)
      this->Points->InsertNextPoint(this->toWorld(p, object.offset).data());
    std::vector<vtkIdType> ids;
    for (std::size_t c = 0; c < mesh.cellCount(); ++c)
    {
      ids.assign(mesh.connectivity.begin() + mesh.offsets[c],
        mesh.connectivity.begin() + mesh.offsets[c + 1]);
      for (vtkIdType& id : ids)
        id += base;
      if (this->Reverse)
        std::reverse(ids.begin(), ids.end());
      this->Cells->InsertNextCell(vtkIdType(ids.size()), ids.data());
      this->FaceNodeId->InsertNextValue(
        mesh.faceNode[c] < 0 ? -1 : int(nodeBase + mesh.faceNode[c]));
      this->NodeLevel->InsertNextValue(mesh.nodeLevel[c]);
      vbr::vtk::appendLabel(this->Labels, object.label);
    }
  }

  void appendOctree(const vbr::FaceOctree& octree,
    const vbr::vtk::Selected& object,
    vtkIdType nodeBase);

  void finish(vtkPolyData* output, vtkUnstructuredGrid* boxes)
  {
    output->SetPoints(this->Points);
    output->SetPolys(this->Cells);
    vtkCellData* cd = output->GetCellData();
    cd->AddArray(this->FaceNodeId);
    cd->AddArray(this->NodeLevel);
    cd->AddArray(this->Labels);
    cd->SetActiveScalars("FaceNodeId");
    boxes->SetPoints(this->BoxPoints);
    boxes->SetCells(VTK_HEXAHEDRON, this->Boxes);
    vtkCellData* bd = boxes->GetCellData();
    bd->AddArray(this->PlaneNormal);
    bd->AddArray(this->PlaneOffset);
    bd->AddArray(this->BoxLevel);
    bd->AddArray(this->BoxNodeId);
    bd->AddArray(this->BoxLabels);
  }

private:
  const vbr::vtk::VoxelGrid& Grid;
  const bool Reverse;
  vtkNew<vtkPoints> Points, BoxPoints;
  vtkNew<vtkCellArray> Cells, Boxes;
  vtkNew<vtkIntArray> FaceNodeId, NodeLevel, BoxNodeId, BoxLevel;
  vtkNew<vtkDoubleArray> PlaneNormal, PlaneOffset;
  vtkSmartPointer<vtkDataArray> Labels, BoxLabels;
};

/// One hexahedron per face node, with its plane mapped to world coordinates: the plane's
/// normal from two tangents' images (oriented like the normal's image), its offset through
/// the image of a point on it.
void OutputBuilder::appendOctree(const vbr::FaceOctree& octree,
  const vbr::vtk::Selected& object,
  vtkIdType nodeBase)
{
  for (std::size_t id = 0; id < octree.nodes.size(); ++id)
  {
    const vbr::FaceNode& node = octree.nodes[id];
    vtkIdType corners[8];
    const int order[8][3] = { { 0, 0, 0 },
      { 1, 0, 0 },
      { 1, 1, 0 },
      { 0, 1, 0 },
      { 0, 0, 1 },
      { 1, 0, 1 },
      { 1, 1, 1 },
      { 0, 1, 1 } };
    for (int c = 0; c < 8; ++c)
    {
      Vec3 p;
      for (int d = 0; d < 3; ++d)
        p[d] = order[c][d] ? node.hi[d] : node.lo[d];
      corners[c] = this->BoxPoints->InsertNextPoint(this->toWorld(p, object.offset).data());
    }
    this->Boxes->InsertNextCell(8, corners);
    const Vec3& n = node.normal;
    const Vec3 o{ n[0] * node.offset, n[1] * node.offset, n[2] * node.offset };
    Vec3 u{ 0, 0, 0 };
    u[std::abs(n[0]) < 0.9 ? 0 : 1] = 1;
    const Vec3 t1{
      n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]
    };
    const Vec3 t2{
      n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]
    };
    auto image = [&](const Vec3& d)
    {
      const Vec3 a = this->toWorld(o, object.offset);
      const Vec3 b = this->toWorld({ o[0] + d[0], o[1] + d[1], o[2] + d[2] }, object.offset);
      return Vec3{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    };
    const Vec3 a = image(t1), b = image(t2), along = image(n);
    Vec3 w{ a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
    const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    const double sign = (w[0] * along[0] + w[1] * along[1] + w[2] * along[2]) < 0 ? -1.0 : 1.0;
    for (double& x : w)
      x *= sign / len;
    const Vec3 origin = this->toWorld(o, object.offset);
    this->PlaneNormal->InsertNextTuple(w.data());
    this->PlaneOffset->InsertNextValue(w[0] * origin[0] + w[1] * origin[1] + w[2] * origin[2]);
    this->BoxLevel->InsertNextValue(node.level);
    this->BoxNodeId->InsertNextValue(int(nodeBase + vtkIdType(id)));
    vbr::vtk::appendLabel(this->BoxLabels, object.label);
  }
}

/// The relaxed net of the unpruned 4-cycles (PruneCrests off): voxel centres.
vbr::BoundaryMesh unprunedNet(const vbr::BitVolume& voxels)
{
  vbr::BoundaryMesh mesh;
  const auto& n = voxels.dims();
  std::vector<std::int32_t> pointOfVoxel;
  std::vector<std::int64_t> keys;
  for (const auto& q : vbr::unprunedQuadrilaterals(voxels))
  {
    for (const auto& v : q)
    {
      keys.push_back(v[0] + std::int64_t(n[0]) * (v[1] + std::int64_t(n[1]) * v[2]));
      mesh.connectivity.push_back(0);
    }
    mesh.offsets.push_back(std::int64_t(mesh.connectivity.size()));
    mesh.faceNode.push_back(-1);
    mesh.nodeLevel.push_back(-1);
  }
  std::vector<std::int64_t> sorted = keys;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  for (std::int64_t k : sorted)
    mesh.points.push_back({ double(k % n[0]) + 0.5,
      double((k / n[0]) % n[1]) + 0.5,
      double(k / (std::int64_t(n[0]) * n[1])) + 0.5 });
  for (std::size_t i = 0; i < keys.size(); ++i)
    mesh.connectivity[i] =
      std::int32_t(std::lower_bound(sorted.begin(), sorted.end(), keys[i]) - sorted.begin());
  return mesh;
}

/// One object: its voxels, relaxed net, face octree and boundary, appended to the output.
/// False when aborted.
bool appendObject(const vbr::vtk::Selected& object,
  const ObjectSettings& settings,
  const vbr::Execution& exec,
  Statistics& stats,
  OutputBuilder& builder)
{
  const vbr::BitVolume voxels = object.select(exec);
  if (voxels.count() == 0)
    return !exec.stopRequested();
  if (settings.outputMode == vtkFaceOctreeBoundaryFilter::QUADRILATERALS && !settings.pruneCrests)
  {
    builder.appendMesh(unprunedNet(voxels), object, stats.faceNodes);
    return !exec.stopRequested();
  }
  const vbr::DeformedModel model = vbr::buildDeformedModel(voxels, settings.relaxation, exec);
  if (!exec.report(0.4))
    return false;
  stats.boundaryVoxels += vtkIdType(model.boundaryVoxels);
  stats.prunedVoxels += vtkIdType(model.prunedVoxels);
  vbr::FaceOctree octree;
  vbr::FaceOctreeOptions options = settings.octree;
  if (settings.outputMode == vtkFaceOctreeBoundaryFilter::QUADRILATERALS)
    options.maximumLevel = 0;
  octree = vbr::buildFaceOctree(voxels, model, options, exec);
  if (!exec.report(0.8))
    return false;
  const vbr::BoundaryCells cells = settings.outputMode == vtkFaceOctreeBoundaryFilter::POLYGONS
    ? vbr::BoundaryCells::Polygons
    : settings.outputMode == vtkFaceOctreeBoundaryFilter::TRIANGLES
    ? vbr::BoundaryCells::Triangles
    : vbr::BoundaryCells::Quadrilaterals;
  const vbr::BoundaryMesh mesh = vbr::assembleBoundary(model, octree, cells);
  stats.polygons += vtkIdType(mesh.polygons);
  stats.triangles += vtkIdType(mesh.triangles);
  stats.maximumDistance =
    std::max(stats.maximumDistance, vbr::maximumDistanceToSurfels(voxels, mesh.points));
  builder.appendMesh(mesh, object, stats.faceNodes);
  if (settings.outputMode != vtkFaceOctreeBoundaryFilter::QUADRILATERALS)
  {
    builder.appendOctree(octree, object, stats.faceNodes);
    stats.faceNodes += vtkIdType(octree.nodes.size());
  }
  return !exec.stopRequested();
}

void writeStatistics(const Statistics& stats, vtkFieldData* fd)
{
  vbr::vtk::addFieldValue(fd, "NumberOfBoundaryVoxels", stats.boundaryVoxels);
  vbr::vtk::addFieldValue(fd, "NumberOfFaceNodes", stats.faceNodes);
  vbr::vtk::addFieldValue(fd, "NumberOfPolygons", stats.polygons);
  vbr::vtk::addFieldValue(fd, "NumberOfTriangles", stats.triangles);
  vbr::vtk::addFieldValue(fd, "NumberOfPrunedVoxels", stats.prunedVoxels);
  vtkNew<vtkDoubleArray> distance;
  distance->SetName("MaximumDistance");
  distance->InsertNextValue(stats.maximumDistance);
  fd->AddArray(distance);
}

} // namespace

//------------------------------------------------------------------------------
vtkFaceOctreeBoundaryFilter::vtkFaceOctreeBoundaryFilter()
{
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, vtkDataSetAttributes::SCALARS);
  this->SetProgressText("Face Octree Boundary");
}

//------------------------------------------------------------------------------
vtkFaceOctreeBoundaryFilter::~vtkFaceOctreeBoundaryFilter() = default;

//------------------------------------------------------------------------------
int vtkFaceOctreeBoundaryFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkFaceOctreeBoundaryFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkUnstructuredGrid");
  return 1;
}

//------------------------------------------------------------------------------
const char* vtkFaceOctreeBoundaryFilter::GetOutputModeAsString()
{
  switch (this->OutputMode)
  {
    case POLYGONS:
      return "Polygons";
    case TRIANGLES:
      return "Triangles";
    default:
      return "Quadrilaterals";
  }
}

//------------------------------------------------------------------------------
int vtkFaceOctreeBoundaryFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vbr::vtk::executeGuarded(this,
    outputVector,
    "Face octree boundary",
    [&] { return this->Execute(inputVector, outputVector); });
}

//------------------------------------------------------------------------------
int vtkFaceOctreeBoundaryFilter::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkUnstructuredGrid* boxes = vtkUnstructuredGrid::GetData(outputVector, 1);
  if (!input || !output || !boxes)
  {
    vtkErrorMacro(<< "Input must be a vtkImageData.");
    return 0;
  }
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  vbr::vtk::SelectionSettings settings = vbr::vtk::selectionSettingsOf(this);
  settings.flatImagesAs2D = false;
  settings.maximumVoxelsPerAxis = (1 << 21) - 2;
  settings.bytesPerVoxel = 1.0 / 8.0 * 3; // object, interior vertices and far voxels
  settings.distributed = true; // the boundary of the whole image on rank 0 (N ranks = 1 rank)
  vbr::vtk::InputObjects in;
  if (!vbr::vtk::readInputObjects(this, input, scalars, association, settings, in))
    return 0;
  const vbr::vtk::VoxelGrid& grid = in.grid;
  if (std::int64_t(grid.dims[0]) * grid.dims[1] * grid.dims[2] == 0)
    return 1; // no voxels: an empty boundary
  this->UpdateProgress(0.1);

  ObjectSettings each;
  each.outputMode = this->OutputMode;
  each.pruneCrests = this->PruneCrests;
  each.relaxation.iterations = this->RelaxationIterations;
  each.relaxation.tolerance = this->RelaxationTolerance;
  each.octree.maximumLevel = this->MaximumOctreeLevel;
  const double spacing =
    std::min({ std::abs(grid.spacing[0]), std::abs(grid.spacing[1]), std::abs(grid.spacing[2]) });
  each.octree.precision = (this->Precision > 0 && spacing > 0) ? this->Precision / spacing : 0.5;
  OutputBuilder builder(grid, in.labelType);
  Statistics stats;
  const auto& objects = in.objects;
  for (std::size_t o = 0; o < objects.size() && !this->GetAbortExecute(); ++o)
  {
    const double to = 0.1 + 0.9 * (o + 1) / objects.size();
    const vbr::Execution exec = vbr::vtk::makeExecution(this, 0.1 + 0.9 * o / objects.size(), to);
    if (!appendObject(objects[o], each, exec, stats, builder))
      break; // aborted
    this->UpdateProgress(to);
  }
  if (this->GetAbortExecute())
    return 1; // aborted: an empty output rather than a part of the boundary
  builder.finish(output, boxes);
  if (this->GetSelectionMode() == LABELS)
    output->GetCellData()->SetActiveScalars("Label");
  writeStatistics(stats, output->GetFieldData());
  vbr::vtk::addDistributionFields(output->GetFieldData(), in.piece);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFaceOctreeBoundaryFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Selection:\n";
  this->Selection->PrintSelf(os, indent.GetNextIndent());
  os << indent << "OutputMode: " << this->GetOutputModeAsString() << "\n";
  os << indent << "RelaxationIterations: " << this->RelaxationIterations << "\n";
  os << indent << "RelaxationTolerance: " << this->RelaxationTolerance << "\n";
  os << indent << "MaximumOctreeLevel: " << this->MaximumOctreeLevel << "\n";
  os << indent << "Precision: " << this->Precision << "\n";
  os << indent << "PruneCrests: " << (this->PruneCrests ? "On\n" : "Off\n");
}
