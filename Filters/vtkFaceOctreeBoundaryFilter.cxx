#include "vtkFaceOctreeBoundaryFilter.h"

#include "BoundarySimplifier.h"
#include "DeformedModel.h"
#include "FaceOctree.h"
#include "FaceOctreeBoundary.h"
#include "LabelNet.h"
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
  double surfelDistance = 0.0; ///< with Simplify: bound of the surfels' distance to the output
  bool simplifyFailed = false; ///< a simplified surface failed its checks: its input was kept
};

/// What every object is extracted with.
struct ObjectSettings
{
  int outputMode;
  bool pruneCrests;
  vbr::DeformedModelOptions relaxation;
  vbr::FaceOctreeOptions octree;
  bool simplify;
  vbr::SimplifyOptions simplification;
};

/// The triangles of a Triangles boundary as a plain surface.
vbr::TriangleSurface triangleSurface(const vbr::BoundaryMesh& mesh)
{
  vbr::TriangleSurface s;
  s.points = mesh.points;
  for (std::size_t c = 0; c < mesh.cellCount(); ++c)
    s.triangles.push_back({ mesh.connectivity[mesh.offsets[c]],
      mesh.connectivity[mesh.offsets[c] + 1],
      mesh.connectivity[mesh.offsets[c] + 2] });
  return s;
}

/// A simplified surface as a boundary mesh: triangles of no face node (FaceNodeId and
/// NodeLevel -1).
vbr::BoundaryMesh boundaryOf(const vbr::TriangleSurface& s)
{
  vbr::BoundaryMesh mesh;
  mesh.points = s.points;
  for (const auto& t : s.triangles)
  {
    mesh.connectivity.insert(mesh.connectivity.end(), t.begin(), t.end());
    mesh.offsets.push_back(std::int64_t(mesh.connectivity.size()));
  }
  mesh.faceNode.assign(s.triangles.size(), -1);
  mesh.nodeLevel.assign(s.triangles.size(), -1);
  mesh.triangles = s.triangles.size();
  return mesh;
}

/// The Triangles boundary of one object simplified (BoundarySimplifier.h), its measured
/// distances added to the statistics; false when aborted.
bool simplifyObject(const vbr::BitVolume& voxels,
  const ObjectSettings& settings,
  const vbr::Execution& exec,
  vbr::BoundaryMesh& mesh,
  Statistics& stats)
{
  if (mesh.cellCount() == 0)
    return true; // nothing to simplify (every voxel pruned)
  const vbr::SimplifiedSurface out =
    vbr::simplifyBoundary(voxels, triangleSurface(mesh), settings.simplification, exec);
  if (out.aborted)
    return false;
  if (!out.simplified)
    stats.simplifyFailed = true; // the input kept, with its own distances
  else
    mesh = boundaryOf(out.surface);
  stats.maximumDistance = std::max(stats.maximumDistance, out.surfaceDistance);
  stats.surfelDistance = std::max(stats.surfelDistance, out.surfelDistance);
  return true;
}

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
    vtkIdType nodeBase)
  {
    for (std::size_t id = 0; id < octree.nodes.size(); ++id)
      this->appendNode(
        octree.nodes[id], object.label, object.offset, 0.0, int(nodeBase + vtkIdType(id)));
  }

  /// The shared boundary of Labels mode: each cell's `Label` is its larger label (the one
  /// that is not the background), `BoundaryLabels` both; `labels[i]` is the value of label
  /// i (0: the background).
  void appendLabelBoundary(const vbr::LabelBoundary& b,
    const std::vector<vbr::vtk::LabelValue>& labels,
    int labelType);

  void appendNode(const vbr::FaceNode& node,
    const vbr::vtk::LabelValue& label,
    const std::array<std::int32_t, 3>& offset,
    double shift,
    int id);

  void finish(vtkPolyData* output, vtkUnstructuredGrid* boxes)
  {
    output->SetPoints(this->Points);
    output->SetPolys(this->Cells);
    vtkCellData* cd = output->GetCellData();
    cd->AddArray(this->FaceNodeId);
    cd->AddArray(this->NodeLevel);
    cd->AddArray(this->Labels);
    if (this->BoundaryLabels)
      cd->AddArray(this->BoundaryLabels);
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
  vtkSmartPointer<vtkDataArray> Labels, BoxLabels, BoundaryLabels;
};

void OutputBuilder::appendLabelBoundary(const vbr::LabelBoundary& b,
  const std::vector<vbr::vtk::LabelValue>& labels,
  int labelType)
{
  const std::array<std::int32_t, 3> origin{ 0, 0, 0 };
  vbr::vtk::Selected whole;
  vtkIdType nodeBase = 0;
  this->BoundaryLabels = vbr::vtk::newLabelArray(labelType);
  this->BoundaryLabels->SetName("BoundaryLabels");
  this->BoundaryLabels->SetNumberOfComponents(2);
  this->BoundaryLabels->SetNumberOfTuples(vtkIdType(b.mesh.cellCount()));
  const vtkIdType first = this->Labels->GetNumberOfTuples();
  whole.offset = origin;
  this->appendMesh(b.mesh, whole, nodeBase);
  for (std::size_t c = 0; c < b.mesh.cellCount(); ++c)
  {
    vbr::vtk::setLabel(this->Labels, first + vtkIdType(c), labels[b.labels[c][1]]);
    vbr::vtk::setLabel(this->BoundaryLabels, 2 * vtkIdType(c), labels[b.labels[c][0]]);
    vbr::vtk::setLabel(this->BoundaryLabels, 2 * vtkIdType(c) + 1, labels[b.labels[c][1]]);
  }
  for (std::size_t id = 0; id < b.nodes.size(); ++id)
    this->appendNode(b.nodes[id], labels[b.nodePair[id][1]], origin, -0.5, int(id));
}

/// One hexahedron per face node (its box: [lo, hi) + shift in voxel units), with its plane
/// mapped to world coordinates: the plane's normal from two tangents' images (oriented like
/// the normal's image), its offset through the image of a point on it.
void OutputBuilder::appendNode(const vbr::FaceNode& node,
  const vbr::vtk::LabelValue& label,
  const std::array<std::int32_t, 3>& offset,
  double shift,
  int id)
{
  {
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
        p[d] = (order[c][d] ? node.hi[d] : node.lo[d]) + shift;
      corners[c] = this->BoxPoints->InsertNextPoint(this->toWorld(p, offset).data());
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
      const Vec3 a = this->toWorld(o, offset);
      const Vec3 b = this->toWorld({ o[0] + d[0], o[1] + d[1], o[2] + d[2] }, offset);
      return Vec3{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    };
    const Vec3 a = image(t1), b = image(t2), along = image(n);
    Vec3 w{ a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
    const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    const double sign = (w[0] * along[0] + w[1] * along[1] + w[2] * along[2]) < 0 ? -1.0 : 1.0;
    for (double& x : w)
      x *= sign / len;
    const Vec3 origin = this->toWorld(o, offset);
    this->PlaneNormal->InsertNextTuple(w.data());
    this->PlaneOffset->InsertNextValue(w[0] * origin[0] + w[1] * origin[1] + w[2] * origin[2]);
    this->BoxLevel->InsertNextValue(node.level);
    this->BoxNodeId->InsertNextValue(id);
    vbr::vtk::appendLabel(this->BoxLabels, label);
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
  octree = vbr::buildFaceOctree(voxels, model, options, exec.within(0.4, 0.8));
  if (!exec.report(0.8))
    return false;
  const bool simplify =
    settings.simplify && settings.outputMode != vtkFaceOctreeBoundaryFilter::QUADRILATERALS;
  const vbr::BoundaryCells cells =
    settings.outputMode == vtkFaceOctreeBoundaryFilter::POLYGONS && !simplify
    ? vbr::BoundaryCells::Polygons
    : settings.outputMode != vtkFaceOctreeBoundaryFilter::QUADRILATERALS
    ? vbr::BoundaryCells::Triangles
    : vbr::BoundaryCells::Quadrilaterals;
  vbr::BoundaryMesh mesh = vbr::assembleBoundary(model, octree, cells);
  if (simplify && !simplifyObject(voxels, settings, exec.within(0.8, 1.0), mesh, stats))
    return false;
  stats.polygons += vtkIdType(mesh.polygons);
  stats.triangles += vtkIdType(mesh.triangles);
  if (!simplify)
    stats.maximumDistance =
      std::max(stats.maximumDistance, vbr::maximumDistanceToSurfels(voxels, mesh.points, exec));
  builder.appendMesh(mesh, object, stats.faceNodes);
  if (settings.outputMode != vtkFaceOctreeBoundaryFilter::QUADRILATERALS)
  {
    builder.appendOctree(octree, object, stats.faceNodes);
    stats.faceNodes += vtkIdType(octree.nodes.size());
  }
  return !exec.stopRequested();
}

/// The label map of Labels mode: each selected label's voxels numbered by its object (1, 2,
/// ...), 0 elsewhere (the background); `values` gets the label of each number.
vbr::LabelVolume labelMap(const vbr::vtk::InputObjects& in,
  const vbr::vtk::LabelValue& background,
  const vbr::Execution& exec,
  std::vector<vbr::vtk::LabelValue>& values)
{
  vbr::LabelVolume volume;
  volume.dims = in.grid.dims;
  volume.labels.assign(std::size_t(volume.dims[0]) * volume.dims[1] * volume.dims[2], 0);
  values.assign(1, background);
  for (std::size_t o = 0; o < in.objects.size() && !exec.stopRequested(); ++o)
  {
    const vbr::vtk::Selected& object = in.objects[o];
    values.push_back(object.label);
    const vbr::BitVolume voxels = object.select(exec);
    const auto& n = voxels.dims();
    for (std::int32_t k = 0; k < n[2]; ++k)
      for (std::int32_t j = 0; j < n[1]; ++j)
      {
        const vbr::Word* row = voxels.row(j, k);
        const std::size_t base = object.offset[0] +
          std::size_t(volume.dims[0]) *
            (object.offset[1] + j + std::size_t(volume.dims[1]) * (object.offset[2] + k));
        for (std::size_t w = 0; w < voxels.wordsPerRow(); ++w)
          for (vbr::Word m = row[w]; m; m &= m - 1)
            volume.labels[base + w * 64 + std::size_t(__builtin_ctzll(m))] = std::int32_t(o + 1);
      }
  }
  return volume;
}

/// Labels mode: one net of all labels, its face octree compacted per pair of labels and the
/// shared boundary (LabelNet.h). False when aborted.
bool appendLabelBoundary(const vbr::vtk::InputObjects& in,
  const ObjectSettings& settings,
  const vbr::vtk::LabelValue& background,
  const vbr::Execution& exec,
  Statistics& stats,
  OutputBuilder& builder)
{
  std::vector<vbr::vtk::LabelValue> values;
  const vbr::LabelVolume volume = labelMap(in, background, exec, values);
  const vbr::LabelNet net = vbr::buildLabelNet(volume, settings.relaxation, exec);
  if (!exec.report(0.4))
    return false;
  vbr::FaceOctreeOptions options = settings.octree;
  if (settings.outputMode == vtkFaceOctreeBoundaryFilter::QUADRILATERALS)
    options.maximumLevel = 0;
  const vbr::BoundaryCells cells = settings.outputMode == vtkFaceOctreeBoundaryFilter::POLYGONS
    ? vbr::BoundaryCells::Polygons
    : settings.outputMode == vtkFaceOctreeBoundaryFilter::TRIANGLES
    ? vbr::BoundaryCells::Triangles
    : vbr::BoundaryCells::Quadrilaterals;
  const vbr::LabelBoundary boundary = vbr::assembleLabelBoundary(net, options, cells, exec);
  if (exec.stopRequested())
    return false;
  stats.boundaryVoxels += vtkIdType(net.model.pointCount());
  stats.polygons += vtkIdType(boundary.mesh.polygons);
  stats.triangles += vtkIdType(boundary.mesh.triangles);
  stats.faceNodes += vtkIdType(boundary.nodes.size());
  stats.maximumDistance = vbr::maximumDistanceToLabelFaces(volume, boundary.mesh.points, exec);
  builder.appendLabelBoundary(boundary, values, in.labelType);
  return true;
}

void writeStatistics(const Statistics& stats, bool simplified, vtkFieldData* fd)
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
  if (simplified)
  {
    vtkNew<vtkDoubleArray> back;
    back->SetName("MaximumSurfelDistance");
    back->InsertNextValue(stats.surfelDistance);
    fd->AddArray(back);
  }
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
  // object, interior vertices and far voxels; Labels mode: a 32-bit label map
  settings.bytesPerVoxel = 1.0 / 8.0 * 3 + (this->GetSelectionMode() == LABELS ? 4.0 : 0.0);
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
  each.octree.mergeFaceNodes = this->MergeFaceNodes;
  each.octree.keepPointsInVoxels = this->KeepPointsInVoxels;
  const double largestSpacing =
    std::max({ std::abs(grid.spacing[0]), std::abs(grid.spacing[1]), std::abs(grid.spacing[2]) });
  each.simplify = this->Simplify && this->OutputMode != QUADRILATERALS;
  if (this->SimplificationDistance > 0 && largestSpacing > 0)
    each.simplification.distance = this->SimplificationDistance / largestSpacing;
  if (each.simplify && this->GetSelectionMode() == LABELS)
  {
    vtkWarningMacro(<< "Simplify is not supported in Labels mode: the shared boundary is "
                       "not simplified.");
    each.simplify = false;
  }
  const double spacing =
    std::min({ std::abs(grid.spacing[0]), std::abs(grid.spacing[1]), std::abs(grid.spacing[2]) });
  each.octree.precision = (this->Precision > 0 && spacing > 0) ? this->Precision / spacing : 0.5;
  OutputBuilder builder(grid, in.labelType);
  Statistics stats;
  const auto& objects = in.objects;
  if (this->GetSelectionMode() == LABELS && !objects.empty() &&
    !(this->OutputMode == QUADRILATERALS && !this->PruneCrests))
  {
    vtkSmartPointer<vtkDataArray> background = vbr::vtk::newLabelArray(in.labelType, 1);
    background->SetComponent(0, 0, this->GetBackgroundValue());
    appendLabelBoundary(in,
      each,
      vbr::vtk::labelAt(background, 0),
      vbr::vtk::makeExecution(this, 0.1, 1.0),
      stats,
      builder);
  }
  for (std::size_t o = 0; o < objects.size() && !this->GetAbortExecute() &&
       (this->GetSelectionMode() != LABELS ||
         (this->OutputMode == QUADRILATERALS && !this->PruneCrests));
       ++o)
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
  if (stats.simplifyFailed)
    vtkWarningMacro(<< "The boundary was not simplified (its triangles were not a closed "
                       "mesh free of degenerate triangles, or the simplified surface failed "
                       "its final checks: closed, manifold, free of self-intersections): the "
                       "unsimplified triangles are output.");
  const double bound = std::min(each.simplification.distance, 1.99);
  if (each.simplify && stats.surfelDistance > bound + 1e-9)
    vtkWarningMacro(<< "Some surfels stay " << stats.surfelDistance
                    << " voxels from the surface, beyond SimplificationDistance (" << bound
                    << " voxels): the unsimplified surface is already that far there.");
  writeStatistics(stats, each.simplify, output->GetFieldData());
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
  os << indent << "MergeFaceNodes: " << (this->MergeFaceNodes ? "On\n" : "Off\n");
  os << indent << "KeepPointsInVoxels: " << (this->KeepPointsInVoxels ? "On\n" : "Off\n");
  os << indent << "Simplify: " << (this->Simplify ? "On\n" : "Off\n");
  os << indent << "SimplificationDistance: " << this->SimplificationDistance << "\n";
}
