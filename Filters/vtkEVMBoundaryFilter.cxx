#include "vtkEVMBoundaryFilter.h"

#include "BRep.h"
#include "EVM.h"
#include "FaceTriangulator.h"
#include "RadixSort.h"
#include "Surfels.h"
#include "vtkVoxelBRepAdapters.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
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

#include <algorithm>
#include <array>
#include <unordered_map>
#include <vector>

vtkStandardNewMacro(vtkEVMBoundaryFilter);

namespace
{

using vbr::Point3;

/// One selected object: a label (or the whole selection) and its voxels in a box.
struct Selected
{
  double label = 1.0;
  std::array<std::int32_t, 3> offset{ 0, 0, 0 }; ///< box origin, in permuted axes
  vbr::BitVolume voxels;
};

/// Statistics written to the output's field data.
struct Statistics
{
  vtkIdType voxels = 0, extremeVertices = 0, surfels = 0, faces = 0, holes = 0,
            nonManifoldVertices = 0;
  std::array<vtkIdType, 3> planes{ 0, 0, 0 };
};

/// Reads the selection: permutes axes so that a 2D image lies in the first two, and returns
/// one Selected per label (or a single one).
template<typename T>
std::vector<Selected> selectObjects(const vbr::ScalarGrid<T>& grid,
  int mode,
  double lower,
  double upper,
  double background,
  const vbr::Execution& exec)
{
  std::vector<Selected> out;
  vbr::Box3 whole;
  whole.hi = grid.dims;
  if (mode == vtkEVMBoundaryFilter::LABELS)
  {
    for (const auto& entry : vbr::labelBoxes(grid, static_cast<T>(background)))
    {
      const T label = entry.first;
      Selected s;
      s.label = static_cast<double>(label);
      s.offset = entry.second.lo;
      s.voxels = vbr::selectVoxels(
        grid, entry.second, [label](T v) { return v == label; }, exec);
      out.push_back(std::move(s));
    }
    return out;
  }
  Selected s;
  if (mode == vtkEVMBoundaryFilter::POSITIVE)
  {
    s.voxels = vbr::selectVoxels(
      grid, whole, [](T v) { return v > T(0); }, exec);
  }
  else
  {
    s.voxels = vbr::selectVoxels(
      grid,
      whole,
      [lower, upper](T v)
      {
        const double d = static_cast<double>(v);
        return d >= lower && d <= upper;
      },
      exec);
  }
  out.push_back(std::move(s));
  return out;
}

Point3 shifted(const Point3& p, const std::array<std::int32_t, 3>& offset)
{
  return { p[0] + offset[0], p[1] + offset[1], p[2] + offset[2] };
}

/// Builds the output polydata: shared points, cells and cell arrays.
class OutputBuilder
{
public:
  OutputBuilder(const vbr::vtk::VoxelGrid& grid, const std::array<int, 3>& axes, int labelType)
    : Grid(grid)
    , Axes(axes)
  {
    this->Points->SetDataTypeToDouble();
    this->FaceId->SetName("FaceId");
    this->LoopType->SetName("LoopType");
    this->Label.TakeReference(vtkDataArray::CreateDataArray(labelType));
    this->Label->SetName("Label");
    this->ParentFace->SetName("ParentFace");
    this->Depth->SetName("Depth");
  }

  /// Point id of a grid vertex given in permuted axes, relative to the whole grid.
  vtkIdType pointId(const Point3& p)
  {
    const std::uint64_t key = static_cast<std::uint64_t>(p[0]) |
      (static_cast<std::uint64_t>(p[1]) << 21) | (static_cast<std::uint64_t>(p[2]) << 42);
    auto it = this->Ids.find(key);
    if (it != this->Ids.end())
    {
      return it->second;
    }
    std::array<std::int32_t, 3> v{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      v[this->Axes[k]] = p[k];
    }
    double world[3];
    this->Grid.vertexToWorld(v, world);
    const vtkIdType id = this->Points->InsertNextPoint(world);
    this->Ids.emplace(key, id);
    return id;
  }

  /// Point ids of many grid vertices at once (the corners of every loop of an object): the
  /// distinct vertices are found by sorting, so the map is consulted once per vertex only.
  std::vector<vtkIdType> pointIds(const std::vector<Point3>& corners,
    const std::array<std::int32_t, 3>& offset,
    const vbr::Execution& exec)
  {
    const vbr::KeyPacker packer = vbr::KeyPacker::forMaximum(
      std::max({ this->Grid.dims[0], this->Grid.dims[1], this->Grid.dims[2] }));
    std::vector<std::uint64_t> keys(corners.size());
    exec.forRange(static_cast<std::int64_t>(corners.size()),
      [&](std::int64_t b, std::int64_t e)
      {
        for (std::int64_t i = b; i < e; ++i)
        {
          const Point3 p = shifted(corners[i], offset);
          keys[i] = packer.pack(p[0], p[1], p[2]);
        }
      });
    std::vector<std::uint64_t> distinct = keys;
    vbr::radixSort(distinct);
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    std::vector<vtkIdType> idOfDistinct(distinct.size());
    for (std::size_t i = 0; i < distinct.size(); ++i)
    {
      idOfDistinct[i] = this->pointId(packer.unpack(distinct[i]));
    }
    std::vector<vtkIdType> ids(corners.size());
    exec.forRange(static_cast<std::int64_t>(corners.size()),
      [&](std::int64_t b, std::int64_t e)
      {
        for (std::int64_t i = b; i < e; ++i)
        {
          ids[i] = idOfDistinct[std::lower_bound(distinct.begin(), distinct.end(), keys[i]) -
            distinct.begin()];
        }
      });
    return ids;
  }

  void addCell(vtkCellArray* cells,
    const std::vector<vtkIdType>& ids,
    vtkIdType faceId,
    int loopType,
    double label,
    vtkIdType parent,
    int depth)
  {
    cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    this->FaceId->InsertNextValue(faceId);
    this->LoopType->InsertNextValue(loopType);
    this->Label->InsertNextTuple1(label);
    this->ParentFace->InsertNextValue(parent);
    this->Depth->InsertNextValue(depth);
  }

  void finish(vtkPolyData* output, bool planar, bool lines)
  {
    output->SetPoints(this->Points);
    if (lines)
      output->SetLines(this->Lines);
    else
      output->SetPolys(this->Polys);
    vtkCellData* cd = output->GetCellData();
    cd->AddArray(this->FaceId);
    cd->AddArray(this->LoopType);
    cd->AddArray(this->Label);
    if (planar)
    {
      cd->AddArray(this->ParentFace);
      cd->AddArray(this->Depth);
    }
  }

  vtkNew<vtkCellArray> Polys;
  vtkNew<vtkCellArray> Lines;

private:
  const vbr::vtk::VoxelGrid& Grid;
  std::array<int, 3> Axes;
  vtkNew<vtkPoints> Points;
  std::unordered_map<std::uint64_t, vtkIdType> Ids;
  vtkNew<vtkIdTypeArray> FaceId;
  vtkNew<vtkIntArray> LoopType;
  vtkSmartPointer<vtkDataArray> Label;
  vtkNew<vtkIdTypeArray> ParentFace;
  vtkNew<vtkIntArray> Depth;
};

void addFieldValue(vtkFieldData* fd, const char* name, vtkIdType value)
{
  vtkNew<vtkIdTypeArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

} // namespace

//------------------------------------------------------------------------------
vtkEVMBoundaryFilter::vtkEVMBoundaryFilter()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
vtkEVMBoundaryFilter::~vtkEVMBoundaryFilter() = default;

//------------------------------------------------------------------------------
int vtkEVMBoundaryFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
const char* vtkEVMBoundaryFilter::GetSelectionModeAsString()
{
  switch (this->SelectionMode)
  {
    case POSITIVE:
      return "Positive";
    case RANGE:
      return "Range";
    default:
      return "Labels";
  }
}

//------------------------------------------------------------------------------
const char* vtkEVMBoundaryFilter::GetOutputModeAsString()
{
  switch (this->OutputMode)
  {
    case POLYGONS:
      return "Polygons";
    case TRIANGLES:
      return "Triangles";
    case POLYLINES:
      return "Polylines";
    default:
      return "Surfels";
  }
}

//------------------------------------------------------------------------------
int vtkEVMBoundaryFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro(<< "Input must be a vtkImageData and output a vtkPolyData.");
    return 0;
  }
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  if (!scalars)
  {
    if (input->GetNumberOfPoints() == 0)
    {
      return 1; // an empty image has an empty boundary
    }
    vtkErrorMacro(<< "No input scalars to select voxels from (set the input array to process).");
    return 0;
  }
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    vtkErrorMacro(<< "The input array must be point or cell data.");
    return 0;
  }
  if (this->ArrayComponent >= scalars->GetNumberOfComponents())
  {
    vtkErrorMacro(<< "ArrayComponent " << this->ArrayComponent << " is out of range: the array '"
                  << (scalars->GetName() ? scalars->GetName() : "") << "' has "
                  << scalars->GetNumberOfComponents() << " component(s).");
    return 0;
  }
  if (this->SelectionMode == RANGE && this->LowerThreshold > this->UpperThreshold)
  {
    vtkWarningMacro(<< "LowerThreshold > UpperThreshold: nothing is selected.");
  }
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  vbr::vtk::VoxelGrid grid;
  const std::string problem =
    vbr::vtk::describeVoxels(input, scalars, cellData, this->FlatImagesAs2D, grid);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot read the voxels: " << problem << ".");
    return 0;
  }
  if (grid.dims[0] * static_cast<std::int64_t>(grid.dims[1]) * grid.dims[2] == 0)
  {
    return 1;
  }
  for (int d = 0; d < 3; ++d)
  {
    if (grid.dims[d] >= (1 << 21) - 1)
    {
      vtkErrorMacro(<< "The image has " << grid.dims[d] << " voxels along axis " << d
                    << "; at most 2097150 are supported.");
      return 0;
    }
  }

  // A 2D image is processed in its own plane: permute its flat axis last.
  const bool planar = grid.flatAxis >= 0;
  std::array<int, 3> axes{ 0, 1, 2 };
  if (planar)
  {
    int k = 0;
    for (int d = 0; d < 3; ++d)
      if (d != grid.flatAxis)
        axes[k++] = d;
    axes[2] = grid.flatAxis;
  }
  vbr::vtk::VoxelGrid permutedGrid = grid;
  for (int k = 0; k < 3; ++k)
  {
    permutedGrid.dims[k] = grid.dims[axes[k]];
  }

  std::vector<Selected> objects;
  const vbr::Execution selectExec = vbr::vtk::makeExecution(this, 0.0, 0.1);
  const bool known = vbr::vtk::dispatchScalars(scalars,
    this->ArrayComponent,
    grid,
    [&](auto scalarGrid)
    {
      auto permuted = scalarGrid;
      for (int k = 0; k < 3; ++k)
      {
        permuted.dims[k] = scalarGrid.dims[axes[k]];
        permuted.stride[k] = scalarGrid.stride[axes[k]];
      }
      objects = selectObjects(permuted,
        this->SelectionMode,
        this->LowerThreshold,
        this->UpperThreshold,
        this->BackgroundValue,
        selectExec);
    });
  if (!known)
  {
    vtkErrorMacro(<< "Unsupported scalar type " << scalars->GetDataTypeAsString() << ".");
    return 0;
  }
  this->UpdateProgress(0.1);

  const vbr::FaceConnectivity connectivity =
    this->MergeNonManifoldFaces ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge;
  OutputBuilder builder(grid, axes, scalars->GetDataType());
  Statistics stats;
  vtkIdType faceBase = 0;
  const bool lines = this->OutputMode == POLYLINES || (planar && this->OutputMode == SURFELS);
  vtkCellArray* cells = lines ? builder.Lines.Get() : builder.Polys.Get();
  std::vector<vtkIdType> ids;

  for (std::size_t o = 0; o < objects.size(); ++o)
  {
    if (this->GetAbortExecute())
    {
      break;
    }
    const Selected& object = objects[o];
    const double from = 0.1 + 0.9 * o / objects.size();
    const double to = 0.1 + 0.9 * (o + 1) / objects.size();
    const vbr::Execution exec = vbr::vtk::makeExecution(this, from, to);
    const std::size_t count = object.voxels.count();
    if (count == 0)
    {
      continue;
    }
    stats.voxels += static_cast<vtkIdType>(count);
    const std::size_t faces3 = vbr::countSurfels(object.voxels);
    stats.surfels += static_cast<vtkIdType>(planar ? faces3 - 2 * count : faces3);
    const vbr::EVM evm =
      planar ? vbr::extractEVM2D(object.voxels, exec) : vbr::extractEVM(object.voxels, exec);
    stats.extremeVertices += static_cast<vtkIdType>(evm.size());
    const auto planes = vbr::planesPerAxis(evm);
    for (int k = 0; k < 3; ++k)
    {
      stats.planes[axes[k]] += static_cast<vtkIdType>(planes[k]);
    }

    if (this->OutputMode == SURFELS)
    {
      for (const vbr::Surfel& s : vbr::extractSurfels(object.voxels, planar))
      {
        // The unit square (segment in 2D) spanned by the two other axes from its corner.
        const int a = (s.axis + 1) % 3, b = (s.axis + 2) % 3;
        Point3 c = shifted(s.corner, object.offset);
        ids.clear();
        if (planar)
        {
          const int along = 1 - s.axis; // the in-plane axis the pixel edge runs along
          Point3 e = c;
          ++e[along];
          ids = { builder.pointId(c), builder.pointId(e) };
          if (s.normalSign * (s.axis == 0 ? 1 : -1) < 0)
            std::swap(ids[0], ids[1]); // keep the pixel on the left
        }
        else
        {
          Point3 p1 = c, p2 = c, p3 = c;
          ++p1[a];
          ++p2[a];
          ++p2[b];
          ++p3[b];
          ids = {
            builder.pointId(c), builder.pointId(p1), builder.pointId(p2), builder.pointId(p3)
          };
          if (s.normalSign < 0)
            std::swap(ids[1], ids[3]);
        }
        builder.addCell(cells, ids, -1, 0, object.label, -1, 0);
      }
      continue;
    }

    vbr::BRep brep;
    if (planar)
    {
      brep = vbr::extractBoundary2D(evm, connectivity);
    }
    else if (!vbr::extractBoundary3D(evm, connectivity, exec, brep))
    {
      break; // aborted
    }
    vbr::insertTJunctionVertices(brep, exec);
    stats.faces += static_cast<vtkIdType>(brep.faces.size());
    stats.holes += static_cast<vtkIdType>(brep.holeCount());
    stats.nonManifoldVertices += static_cast<vtkIdType>(brep.nonManifoldVertices);

    std::vector<std::vector<std::array<int, 3>>> triangles;
    if (this->OutputMode == TRIANGLES)
    {
      triangles.resize(brep.faces.size());
      exec.forRange(static_cast<std::int64_t>(brep.faces.size()),
        [&](std::int64_t b, std::int64_t e)
        {
          for (std::int64_t f = b; f < e; ++f)
            triangles[f] = vbr::triangulateFace(brep, static_cast<int>(f));
        });
    }
    const std::vector<vtkIdType> cornerIds = builder.pointIds(brep.points, object.offset, exec);
    for (std::size_t f = 0; f < brep.faces.size(); ++f)
    {
      const vbr::BRepFace& face = brep.faces[f];
      const vtkIdType faceId = faceBase + static_cast<vtkIdType>(f);
      const vtkIdType parent = face.parent < 0 ? -1 : faceBase + face.parent;
      const vbr::BRepLoop& first = brep.loops[face.firstLoop];
      if (this->OutputMode == TRIANGLES)
      {
        // Triangle corners index the face's loops' corners, which are contiguous.
        const vtkIdType* corner = cornerIds.data() + first.begin;
        for (const auto& t : triangles[f])
        {
          ids = { corner[t[0]], corner[t[1]], corner[t[2]] };
          builder.addCell(cells, ids, faceId, 0, object.label, parent, face.depth);
        }
        continue;
      }
      for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
      {
        const vbr::BRepLoop& loop = brep.loops[l];
        ids.assign(cornerIds.begin() + loop.begin, cornerIds.begin() + loop.end);
        if (this->OutputMode == POLYLINES)
        {
          ids.push_back(ids.front());
        }
        builder.addCell(cells,
          ids,
          faceId,
          loop.hole ? 1 : 0,
          object.label,
          loop.hole ? faceId : parent,
          loop.hole ? face.depth + 1 : face.depth);
      }
    }
    faceBase += static_cast<vtkIdType>(brep.faces.size());
    this->UpdateProgress(to);
  }

  builder.finish(output, planar, lines);
  vtkFieldData* fd = output->GetFieldData();
  addFieldValue(fd, "NumberOfVoxels", stats.voxels);
  addFieldValue(fd, "NumberOfExtremeVertices", stats.extremeVertices);
  addFieldValue(fd, "NumberOfSurfels", stats.surfels);
  addFieldValue(fd, "NumberOfFaces", stats.faces);
  addFieldValue(fd, "NumberOfHoles", stats.holes);
  addFieldValue(fd, "NumberOfNonManifoldVertices", stats.nonManifoldVertices);
  vtkNew<vtkIdTypeArray> planes;
  planes->SetName("NumberOfPlanesOfVertices");
  planes->SetNumberOfComponents(3);
  planes->InsertNextTypedTuple(stats.planes.data());
  fd->AddArray(planes);
  return 1;
}

//------------------------------------------------------------------------------
void vtkEVMBoundaryFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SelectionMode: " << this->GetSelectionModeAsString() << "\n";
  os << indent << "LowerThreshold: " << this->LowerThreshold << "\n";
  os << indent << "UpperThreshold: " << this->UpperThreshold << "\n";
  os << indent << "BackgroundValue: " << this->BackgroundValue << "\n";
  os << indent << "ArrayComponent: " << this->ArrayComponent << "\n";
  os << indent << "OutputMode: " << this->GetOutputModeAsString() << "\n";
  os << indent << "MergeNonManifoldFaces: " << (this->MergeNonManifoldFaces ? "On\n" : "Off\n");
  os << indent << "FlatImagesAs2D: " << (this->FlatImagesAs2D ? "On\n" : "Off\n");
}
