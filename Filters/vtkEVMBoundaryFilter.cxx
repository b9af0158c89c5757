#include "vtkEVMBoundaryFilter.h"

#include "BRep.h"
#include "EVM.h"
#include "FaceTriangulator.h"
#include "Geometry.h"
#include "GridPointIndex.h"
#include "PlaneSweep3D.h"
#include "RadixSort.h"
#include "Surfels.h"
#include "vtkVoxelBRepAdapters.h"
#include "vtkVoxelBRepBuffers.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#if defined(__GLIBC__)
#include <malloc.h> // malloc_trim
#endif

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkEVMBoundaryFilter);

namespace
{

using vbr::Point3;
using vbr::vtk::MallocBuffer;

/// The cells of the faces (Triangles or Polygons mode) in runs of consecutive faces, one run
/// per concurrent task, as indices into each face's loop corners.
struct FaceRuns
{
  std::vector<vbr::FaceCells> runs;
  std::vector<std::size_t> firstFace; ///< per run
  /// The output point ids of a run's cells' corners, in the run's order (appendRunOfFaces):
  /// scratch space kept from call to call.
  std::vector<std::int64_t> pointIds;
  /// A part's corner numbers (partCells) and the T-junction insertion's arrays, kept from part
  /// to part likewise: made afresh, each part's were zeroed and faulted in first.
  std::vector<std::int64_t> cornerNumbers;
  vbr::TJunctionScratch tJunctions;
};

/// Statistics written to the output's field data.
struct Statistics
{
  vtkIdType voxels = 0, extremeVertices = 0, surfels = 0, faces = 0, holes = 0,
            nonManifoldVertices = 0;
  std::array<vtkIdType, 3> planes{ 0, 0, 0 };
};

/// Whether the map from processing axes to world coordinates mirrors space: an odd
/// permutation of the axes (a 2D image flat along y), a direction matrix with negative
/// determinant, or a negative spacing. Cells are then reversed to keep their orientation.
bool reversesOrientation(const vbr::vtk::VoxelGrid& grid, const std::array<int, 3>& axes)
{
  const bool odd = (axes[1] - axes[0] + 3) % 3 != 1;
  return odd != grid.mirrorsSpace();
}

/// Cells and their attributes in plain arrays (MallocBuffer, CellArrayBuffer), in the order
/// written: the output's, or one part's, made on a worker thread and then appended to the
/// output's (append). Per cell only what varies is kept (corners, offset, FaceId, LoopType;
/// ParentFace and Depth for 2D images only); the Label is kept once per run of cells of one
/// object. The triangles or fan polygons of a 3D object's faces (addRunAttributes) keep instead
/// a count of cells per face, their faces' ids being consecutive: FaceId and LoopType (12 bytes
/// a cell, 4 a face instead) are written per cell at the end (finish), once the sweeps' memory
/// is freed, rather than held next to it (noise 128^3, Triangles: 64 of the 247 MB at the
/// sweeps' end).
class CellStore
{
public:
  CellStore(bool planar, bool reverse)
    : Planar(planar)
    , Reverse(reverse)
  {
  }

  void addCell(const vtkIdType* ids,
    std::size_t n,
    vtkIdType faceId,
    int loopType,
    const vbr::vtk::LabelValue& label,
    vtkIdType parent,
    int depth)
  {
    assert(!this->Written); // setLoopCells's cells are final: nothing is added to them
    this->writeFaceIds();
    this->startLabel(label);
    this->Cells.addCell(ids, n, this->Reverse);
    this->FaceId.push_back(faceId);
    this->LoopType.push_back(loopType);
    if (this->Planar)
    {
      this->ParentFace.push_back(parent);
      this->Depth.push_back(depth);
    }
  }

  /// The cells of one face, in a run of faces' cells (triangles or fan polygons): cell k has
  /// the points `pointIds[corners[j]]` for j in [ends[k - 1], ends[k]) (ends[-1] = `begin`).
  /// The same as addCell cell after cell, with the face's attributes and label added once.
  void addFaceCells(const int* corners,
    std::size_t begin,
    const std::uint32_t* ends,
    std::size_t count,
    const std::int64_t* pointIds,
    vtkIdType faceId,
    const vbr::vtk::LabelValue& label,
    vtkIdType parent,
    int depth)
  {
    if (count == 0)
      return;
    assert(!this->Written);
    this->writeFaceIds();
    this->startLabel(label);
    this->Cells.addMappedCells(corners, pointIds, ends, count, begin, this->Reverse);
    std::fill_n(this->FaceId.extend(count), count, faceId);
    std::fill_n(this->LoopType.extend(count), count, 0);
    if (this->Planar)
    {
      std::fill_n(this->ParentFace.extend(count), count, parent);
      std::fill_n(this->Depth.extend(count), count, depth);
    }
  }

  /// The cells of the first faces of a run of a 3D object's faces' cells, as addFaceCells gives
  /// them face after face, without their attributes (addRunAttributes writes those for a
  /// stretch of faces at once: growing two arrays and filling them face by face was 2 % of the
  /// filter's instructions on porous volumes and the headsq bone): cell k has the point ids
  /// `pointIds[ends[k - 1] .. ends[k])` (ends[-1] = 0).
  void addRunConnectivity(const std::int64_t* pointIds,
    const std::uint32_t* ends,
    std::size_t count)
  {
    assert(!this->Written && !this->Planar);
    if (count != 0)
      this->Cells.addCells(pointIds, ends, count, 0, this->Reverse);
  }

  /// The FaceId and LoopType (0) of the cells addRunConnectivity added for the first `faces`
  /// faces of a run (their cells end at faceEnds[i], from 0), whose ids are `firstFaceId` on,
  /// and their label: the attributes addFaceCells gives them face after face. Kept as counts
  /// of cells per face while the faces' ids follow on from the last ones (CellsPerFace).
  void addRunAttributes(const std::vector<std::uint32_t>& faceEnds,
    std::size_t faces,
    vtkIdType firstFaceId,
    const vbr::vtk::LabelValue& label)
  {
    assert(!this->Written && !this->Planar);
    const std::size_t total = faces == 0 ? 0 : faceEnds[faces - 1];
    if (faces != 0 && this->continuesFaces(firstFaceId))
    {
      if (total != 0)
        this->startLabel(label);
      this->addCellsPerFace(faceEnds.data(), faces, firstFaceId, total);
      return;
    }
    if (total == 0)
      return;
    this->writeFaceIds();
    this->startLabel(label); // before FaceId grows: its size is the stretch's first cell
    vtkIdType* id = this->FaceId.extend(total);
    std::size_t begin = 0;
    for (std::size_t i = 0; i < faces; ++i)
    {
      std::fill(id + begin, id + faceEnds[i], firstFaceId + static_cast<vtkIdType>(i));
      begin = faceEnds[i];
    }
    std::fill_n(this->LoopType.extend(total), total, 0);
  }

  bool planar() const { return this->Planar; }

  /// The bytes of the FaceId and LoopType of the cells counted per face, not written yet.
  std::size_t pendingAttributeBytes() const
  {
    return this->CellsOfFaces * (sizeof(vtkIdType) + sizeof(int));
  }

  /// Appends the cells of `part` (made with face ids from 0) with their face ids, and parent
  /// faces, shifted by `faceBase`: the same cells as if they had been added here. `part` is
  /// then empty, its memory kept for its next cells.
  void append(CellStore& part, vtkIdType faceBase)
  {
    assert(!this->Written && !part.Written); // the cells of setLoopCells are not appended
    const vtkIdType cells = static_cast<vtkIdType>(this->cellCount());
    for (const auto& run : part.LabelRuns)
      if (this->LabelRuns.empty() || !(this->LabelRuns.back().second == run.second))
        this->LabelRuns.emplace_back(cells + run.first, run.second);
    this->Cells.append(part.Cells);
    if (part.CellsPerFace.size() != 0 && this->continuesFaces(part.FirstFaceId + faceBase))
      this->addCellsPerFace(part, faceBase);
    else if (part.cellCount() != 0)
    {
      this->writeFaceIds();
      part.writeFaceIds();
      appendShifted(this->FaceId, part.FaceId, faceBase);
      appendShifted(this->LoopType, part.LoopType, 0);
      if (this->Planar)
      {
        appendShifted(this->ParentFace, part.ParentFace, faceBase);
        appendShifted(this->Depth, part.Depth, 0);
      }
    }
    part.clearKeepingMemory();
  }

  /// The cells of the loops of a 2D solution, one per loop (Polylines mode: closed, its first
  /// point repeated at its end), face after face, the outer loop first: what addCell gives
  /// loop after loop, their ids (numbers of `contours`' corners, the output's points) reversed
  /// when `reverseLoops`, written straight into the output's arrays, sized beforehand. Into an
  /// empty store only. `tick(f)` is called at every face f; false (abort) when it returns
  /// false.
  template<typename Tick>
  bool setLoopCells(const vbr::Contours2D& contours,
    bool reverseLoops,
    bool closePolylines,
    const vbr::vtk::LabelValue& label,
    Tick&& tick)
  {
    assert(this->cellCount() == 0 && this->Cells.numberOfCells() == 0);
    const std::size_t loops = contours.boundary.loops.size();
    const std::size_t total = contours.loopCorners.size() + (closePolylines ? loops : 0);
    // CellArrayBuffer's choice: 32 bits while every id and offset fits.
    constexpr std::size_t Narrow = std::numeric_limits<vtkTypeInt32>::max();
    if (total <= Narrow && contours.cornerCount() <= Narrow + std::size_t(1))
      return this->writeLoopCells<vtkTypeInt32Array>(
        contours, reverseLoops, closePolylines, total, label, tick);
    return this->writeLoopCells<vtkTypeInt64Array>(
      contours, reverseLoops, closePolylines, total, label, tick);
  }

  void finish(vtkPolyData* output, bool lines, int labelType)
  {
    assert(!this->Written || this->Cells.numberOfCells() == 0);
    this->writeFaceIds();
    const vtkIdType cellCount = static_cast<vtkIdType>(this->FaceId.size());
    vtkSmartPointer<vtkCellArray> cells =
      this->Written ? std::move(this->Written) : this->Cells.release();
    if (lines)
      output->SetLines(cells);
    else
      output->SetPolys(cells);

    vtkCellData* cd = output->GetCellData();
    vbr::vtk::reserveArrays(cd, this->Planar ? 6 : 4); // and FaceColor (setBoundaryColoring)
    cd->AddArray(named(toArray<vtkIdTypeArray>(this->FaceId), "FaceId"));
    cd->AddArray(named(toArray<vtkIntArray>(this->LoopType), "LoopType"));
    cd->AddArray(this->labelArray(labelType, cellCount));
    if (this->Planar)
    {
      cd->AddArray(named(toArray<vtkIdTypeArray>(this->ParentFace), "ParentFace"));
      cd->AddArray(named(toArray<vtkIntArray>(this->Depth), "Depth"));
    }
  }

private:
  template<typename ArrayType, typename Tick>
  bool writeLoopCells(const vbr::Contours2D& contours,
    bool reverseLoops,
    bool closePolylines,
    std::size_t total,
    const vbr::vtk::LabelValue& label,
    Tick&& tick)
  {
    using Id = typename ArrayType::ValueType;
    const vbr::Boundary2D& b = contours.boundary;
    const std::size_t cells = b.loops.size();
    if (cells == 0)
      return true;
    this->startLabel(label);
    MallocBuffer<Id> offsets, connectivity;
    Id* offset = offsets.extend(cells + 1);
    Id* out = connectivity.extend(total);
    vtkIdType* faceId = this->FaceId.extend(cells);
    int* loopType = this->LoopType.extend(cells);
    vtkIdType* parentFace = this->ParentFace.extend(cells);
    int* depth = this->Depth.extend(cells);
    const std::uint32_t* corners = contours.loopCorners.data();
    std::size_t at = 0;
    *offset++ = 0;
    const auto writeLoop = [&](int l, vtkIdType face, vtkIdType parent, int d, bool hole)
    {
      const vbr::Loop2D& loop = b.loops[l];
      const std::size_t n = loop.end - loop.begin;
      Id* cell = out + at;
      const std::uint32_t* from = corners + loop.begin;
      if (reverseLoops)
        for (std::size_t i = 0; i < n; ++i)
          cell[i] = static_cast<Id>(from[n - 1 - i]);
      else
        for (std::size_t i = 0; i < n; ++i)
          cell[i] = static_cast<Id>(from[i]);
      const std::size_t m = n + (closePolylines ? 1 : 0);
      if (closePolylines)
        cell[n] = cell[0];
      if (this->Reverse)
        std::reverse(cell, cell + m);
      at += m;
      *offset++ = static_cast<Id>(at);
      *faceId++ = face;
      *loopType++ = hole ? 1 : 0;
      *parentFace++ = hole ? face : parent;
      *depth++ = hole ? d + 1 : d;
    };
    for (std::size_t f = 0; f < b.faces.size(); ++f)
    {
      if (!tick(f))
        return false;
      const vbr::Face2D& face = b.faces[f];
      const vtkIdType id = static_cast<vtkIdType>(f);
      writeLoop(face.outerLoop, id, face.parent, face.depth, false);
      for (int h : face.holeLoops)
        writeLoop(h, id, face.parent, face.depth, true);
    }
    assert(at == total);
    vtkNew<ArrayType> offsetArray, connectivityArray;
    offsets.handTo(offsetArray.GetPointer());
    connectivity.handTo(connectivityArray.GetPointer());
    this->Written = vtkSmartPointer<vtkCellArray>::New();
    this->Written->SetData(offsetArray, connectivityArray);
    return true;
  }

  void startLabel(const vbr::vtk::LabelValue& label)
  {
    if (this->LabelRuns.empty() || !(this->LabelRuns.back().second == label))
      this->LabelRuns.emplace_back(static_cast<vtkIdType>(this->cellCount()), label);
  }

  /// The cells added so far, whichever way their FaceId is kept.
  std::size_t cellCount() const { return this->FaceId.size() + this->CellsOfFaces; }

  /// Whether faces from `firstFaceId` on can be kept as counts of cells per face: nothing was
  /// written per cell yet, and they follow the faces counted so far, if any.
  bool continuesFaces(vtkIdType firstFaceId) const
  {
    if (this->FaceId.size() != 0)
      return false;
    const std::size_t counted = this->CellsPerFace.size();
    return counted == 0 || firstFaceId == this->FirstFaceId + static_cast<vtkIdType>(counted);
  }

  /// Counts the cells of `faces` faces, face i's ending at ends[i] (from 0; `total` the last).
  void addCellsPerFace(const std::uint32_t* ends,
    std::size_t faces,
    vtkIdType firstFaceId,
    std::size_t total)
  {
    if (this->CellsPerFace.size() == 0)
      this->FirstFaceId = firstFaceId;
    std::uint32_t* count = this->CellsPerFace.extend(faces);
    std::uint32_t begin = 0;
    for (std::size_t i = 0; i < faces; ++i)
    {
      count[i] = ends[i] - begin;
      begin = ends[i];
    }
    this->CellsOfFaces += total;
  }

  /// Counts the cells of the faces `part` counted (continuesFaces), their ids shifted by
  /// `faceBase`.
  void addCellsPerFace(const CellStore& part, vtkIdType faceBase)
  {
    const std::size_t faces = part.CellsPerFace.size();
    const std::uint32_t* from = part.CellsPerFace.data();
    if (this->CellsPerFace.size() == 0)
      this->FirstFaceId = part.FirstFaceId + faceBase;
    std::copy(from, from + faces, this->CellsPerFace.extend(faces));
    this->CellsOfFaces += part.CellsOfFaces;
  }

  /// Writes the FaceId and LoopType (0) of the cells counted per face (CellsPerFace), cell by
  /// cell: before other cells are added, and at the end.
  void writeFaceIds()
  {
    const std::size_t faces = this->CellsPerFace.size();
    if (faces == 0)
      return;
    assert(this->FaceId.size() == 0 && this->LoopType.size() == 0);
    const std::size_t total = this->CellsOfFaces;
    vtkIdType* id = this->FaceId.extend(total);
    const std::uint32_t* count = this->CellsPerFace.data();
    for (std::size_t i = 0; i < faces; ++i)
      id = std::fill_n(id, count[i], this->FirstFaceId + static_cast<vtkIdType>(i));
    this->CellsPerFace.clear(); // freed before LoopType is made
    this->CellsOfFaces = 0;
    std::fill_n(this->LoopType.extend(total), total, 0);
  }

  /// Appends `from` to `to`, the ids (values >= 0; -1 stands for none) shifted by `base`.
  template<typename Value>
  static void appendShifted(MallocBuffer<Value>& to, const MallocBuffer<Value>& from, Value base)
  {
    const std::size_t n = from.size();
    const Value* in = from.data();
    Value* out = to.extend(n);
    for (std::size_t i = 0; i < n; ++i)
      out[i] = in[i] < 0 ? in[i] : in[i] + base;
  }

  void clearKeepingMemory()
  {
    this->Cells.clearKeepingMemory();
    this->CellsPerFace.clearKeepingMemory();
    this->CellsOfFaces = 0;
    this->FaceId.clearKeepingMemory();
    this->ParentFace.clearKeepingMemory();
    this->LoopType.clearKeepingMemory();
    this->Depth.clearKeepingMemory();
    this->LabelRuns.clear();
  }

  /// The Label of every cell from the runs.
  vtkSmartPointer<vtkDataArray> labelArray(int labelType, vtkIdType cellCount)
  {
    vtkSmartPointer<vtkDataArray> label = vbr::vtk::newLabelArray(labelType, cellCount);
    for (std::size_t r = 0; r < this->LabelRuns.size(); ++r)
    {
      const vtkIdType end =
        r + 1 < this->LabelRuns.size() ? this->LabelRuns[r + 1].first : cellCount;
      vbr::vtk::fillLabel(label, this->LabelRuns[r].first, end, this->LabelRuns[r].second);
    }
    std::vector<std::pair<vtkIdType, vbr::vtk::LabelValue>>().swap(this->LabelRuns);
    return label;
  }

  template<typename ArrayType>
  static vtkSmartPointer<ArrayType> named(vtkSmartPointer<ArrayType> a, const char* name)
  {
    a->SetName(name);
    return a;
  }

  /// A VTK array that takes over the values of `v`.
  template<typename ArrayType, typename Value>
  static vtkSmartPointer<ArrayType> toArray(MallocBuffer<Value>& v)
  {
    auto a = vtkSmartPointer<ArrayType>::New();
    v.handTo(a.GetPointer());
    return a;
  }

  const bool Planar;  ///< a 2D image: the cells carry ParentFace and Depth
  const bool Reverse; ///< world coordinates mirror the processing axes: reverse every cell
  vbr::vtk::CellArrayBuffer Cells;
  vtkSmartPointer<vtkCellArray> Written; ///< the cells when written whole (setLoopCells)
  MallocBuffer<vtkIdType> FaceId, ParentFace;
  MallocBuffer<int> LoopType;
  /// The cells of faces FirstFaceId, FirstFaceId + 1, ..., their FaceId and LoopType not
  /// written yet (addRunAttributes); CellsOfFaces cells in all. FaceId is then empty.
  MallocBuffer<std::uint32_t> CellsPerFace;
  vtkIdType FirstFaceId = 0;
  std::size_t CellsOfFaces = 0;
  MallocBuffer<int> Depth;
  std::vector<std::pair<vtkIdType, vbr::vtk::LabelValue>> LabelRuns; ///< (first cell, label)
};

/// Builds the output polydata: shared points, then cells and their attributes (CellStore),
/// gathered in plain arrays that VTK takes over at the end.
class OutputBuilder
{
public:
  OutputBuilder(const vbr::vtk::VoxelGrid& grid, const std::array<int, 3>& axes, bool planar)
    : Grid(grid)
    , Axes(axes)
    , Planar(planar)
    , Reverse(reversesOrientation(grid, axes))
    , Packer(vbr::KeyPacker::forMaximum(std::max({ grid.dims[0], grid.dims[1], grid.dims[2] })))
    , Cells(planar, this->Reverse)
  {
  }

  /// The output's cells.
  CellStore& cells() { return this->Cells; }

  /// An empty store for cells written apart and appended to cells() later.
  CellStore newPartStore() const { return CellStore(this->Planar, this->Reverse); }

  /// Point ids of grid vertices given in an object's coordinates (permuted axes) plus its
  /// offset; vertices shared by several objects (labels) get one point.
  std::vector<vtkIdType> pointIds(const std::vector<Point3>& corners,
    const std::array<std::int32_t, 3>& offset)
  {
    std::vector<vtkIdType> ids(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i)
    {
      const Point3 p = vbr::add(corners[i], offset);
      const std::uint64_t key = this->Packer.pack(p[0], p[1], p[2]);
      const auto number = this->Index.insert(key);
      if (number.second)
      {
        this->addPoint(p);
      }
      ids[i] = static_cast<vtkIdType>(number.first);
    }
    return ids;
  }

  /// Adds the corners of the objects' faces (common grid, permuted axes) as the output's
  /// points, their numbers as point ids; first, before any other point. `offset` is added
  /// to every corner (an object's corners in its own grid).
  template<typename Corners> // a vector of Point3, of any allocator
  void addCornerPoints(const Corners& corners,
    const std::array<std::int32_t, 3>& offset = { 0, 0, 0 })
  {
    if (corners.empty())
      return;
    Point3 lo = corners[0], hi = lo;
    for (const Point3& p : corners)
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    this->addGridPoints(lo,
      hi,
      offset,
      corners.size(),
      [&](auto&& add)
      {
        for (const Point3& p : corners)
          add(p);
      });
  }

  /// addCornerPoints for the numbered corners of `corners` (its points, whose bounds it
  /// knows), written in ranges side by side with threads (the same values).
  void addCornerPoints(const vbr::CornerSet& corners, const vbr::Execution& exec)
  {
    const vbr::PointList& points = corners.points();
    if (points.empty())
      return;
    const GridTerms terms(*this, corners.lowest(), corners.highest(), { 0, 0, 0 });
    double* xyz = this->Coordinates.extend(3 * points.size());
    exec.forRange(static_cast<std::int64_t>(points.size()),
      [&](std::int64_t b, std::int64_t e)
      {
        double* out = xyz + 3 * b;
        for (std::int64_t i = b; i < e; ++i)
          out = terms.write(points[i], out);
      });
  }

  /// addCornerPoints for the distinct corners of a 2D solution (u, v) in the plane 0 of the
  /// axis order `order`, read from the sweep's own record of them in the order of their
  /// numbers (its columns, or its sorted corners: Contours2D::forEachCorner).
  void addContourCorners(const vbr::Contours2D& contours,
    const vbr::AxisOrder& order,
    const std::array<std::int32_t, 3>& offset)
  {
    const std::size_t count = contours.cornerCount();
    if (count == 0)
      return;
    // Ranges that hold every corner (the tables' values do not depend on them): the columns'
    // grid, or the corners' bounds.
    Point3 lo{ 0, 0, 0 }, hi{ 0, 0, 0 };
    const vbr::CornerColumns& grid = contours.columns;
    lo[order[1]] = grid.uLo;
    hi[order[1]] = grid.uLo + static_cast<vbr::Coord>(64 * grid.wordsPerColumn) - 1;
    lo[order[2]] = grid.vLo;
    hi[order[2]] = grid.vLo + static_cast<vbr::Coord>(grid.columns) - 1;
    if (!contours.corners.empty())
    {
      lo[order[1]] = hi[order[1]] = contours.corners[0].u;
      lo[order[2]] = hi[order[2]] = contours.corners[0].v;
      for (const vbr::Point2& p : contours.corners)
      {
        lo[order[1]] = std::min(lo[order[1]], p.u);
        hi[order[1]] = std::max(hi[order[1]], p.u);
        lo[order[2]] = std::min(lo[order[2]], p.v);
        hi[order[2]] = std::max(hi[order[2]], p.v);
      }
    }
    this->addGridPoints(lo,
      hi,
      offset,
      count,
      [&](auto&& add)
      {
        contours.forEachCorner(
          [&](vbr::Coord u, vbr::Coord v)
          {
            Point3 p;
            p[order[0]] = 0;
            p[order[1]] = u;
            p[order[2]] = v;
            add(p);
          });
      });
  }

  void finish(vtkPolyData* output, bool lines, int labelType)
  {
    vtkNew<vtkDoubleArray> coordinates;
    coordinates->SetNumberOfComponents(3);
    this->Coordinates.handTo(coordinates.GetPointer());
    vtkNew<vtkPoints> points;
    points->SetData(coordinates);
    output->SetPoints(points);
    this->Cells.finish(output, lines, labelType);
  }

private:
  /// Appends `count` points, the grid vertices (permuted axes, in [lo, hi], plus `offset`)
  /// that forEach(add) gives to add one after the other, in world coordinates. Each world
  /// coordinate is origin + t0 + t1 + t2, a term per image axis (VoxelGrid::vertexToWorld's
  /// products and sums, in its order, so the same values): the terms are tabulated once per
  /// index along each axis rather than multiplied out per corner.
  template<typename ForEach>
  void addGridPoints(const Point3& lo,
    const Point3& hi,
    const std::array<std::int32_t, 3>& offset,
    std::size_t count,
    ForEach&& forEach)
  {
    const GridTerms terms(*this, lo, hi, offset);
    double* xyz = this->Coordinates.extend(3 * count);
    forEach([&](const Point3& p) { xyz = terms.write(p, xyz); });
  }

  /// addGridPoints' tables: the terms of the world coordinates per index along each axis.
  class GridTerms
  {
  public:
    GridTerms(const OutputBuilder& builder,
      const Point3& lo,
      const Point3& hi,
      const std::array<std::int32_t, 3>& offset)
      : Origin(builder.Grid.origin)
      , Lo(lo)
    {
      for (int k = 0; k < 3; ++k)
      {
        const int d = builder.Axes[k];
        this->AxisOf[d] = k;
        for (std::int32_t c = lo[k]; c <= hi[k]; ++c)
        {
          const double local =
            (builder.Grid.extentMin[d] + builder.Grid.vertexShift[d] + double(c + offset[k])) *
            builder.Grid.spacing[d];
          for (int r = 0; r < 3; ++r)
            this->Term[3 * d + r].push_back(builder.Grid.direction[3 * r + d] * local);
        }
      }
    }

    /// Writes the world coordinates of grid vertex p at xyz; returns the place after them.
    double* write(const Point3& p, double* xyz) const
    {
      const std::size_t i0 =
        static_cast<std::size_t>(p[this->AxisOf[0]] - this->Lo[this->AxisOf[0]]);
      const std::size_t i1 =
        static_cast<std::size_t>(p[this->AxisOf[1]] - this->Lo[this->AxisOf[1]]);
      const std::size_t i2 =
        static_cast<std::size_t>(p[this->AxisOf[2]] - this->Lo[this->AxisOf[2]]);
      for (int r = 0; r < 3; ++r)
        *xyz++ =
          this->Origin[r] + this->Term[r][i0] + this->Term[3 + r][i1] + this->Term[6 + r][i2];
      return xyz;
    }

  private:
    const std::array<double, 3> Origin;
    const Point3 Lo;
    std::array<int, 3> AxisOf;               // the processing axis of each image axis
    std::array<std::vector<double>, 9> Term; // [3 * image axis + world axis][index - lo]
  };

  /// Appends the world position of a grid vertex given in permuted axes.
  void addPoint(const Point3& p)
  {
    std::array<std::int32_t, 3> v{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
      v[this->Axes[k]] = p[k];
    double xyz[3];
    this->Grid.vertexToWorld(v, xyz);
    for (double c : xyz)
      this->Coordinates.push_back(c);
  }

  const vbr::vtk::VoxelGrid& Grid;
  const std::array<int, 3> Axes;
  const bool Planar;  ///< a 2D image: the cells carry ParentFace and Depth
  const bool Reverse; ///< world coordinates mirror the processing axes: reverse every cell
  const vbr::KeyPacker Packer;
  vbr::GridPointIndex Index;
  MallocBuffer<double> Coordinates;
  CellStore Cells;
};

/// One cell per surfel (a unit square, or a unit segment of a 2D image), pixel on the left.
void appendSurfelCells(const vbr::vtk::Selected& object,
  const vbr::BitVolume& voxels,
  bool planar,
  OutputBuilder& builder)
{
  const std::vector<vbr::Surfel> surfels = vbr::extractSurfels(voxels, planar);
  const std::size_t n = planar ? 2 : 4;
  std::vector<Point3> corners;
  corners.reserve(n * surfels.size());
  for (const vbr::Surfel& s : surfels)
  {
    const Point3 c = s.corner(0);
    if (planar)
    {
      Point3 e = c;
      ++e[1 - s.axis()]; // the in-plane axis the pixel edge runs along
      const bool flip = s.sign() * (s.axis() == 0 ? 1 : -1) < 0;
      corners.push_back(flip ? e : c);
      corners.push_back(flip ? c : e);
      continue;
    }
    // The unit square spanned by the two other axes from its corner, normal outwards.
    const int a = (s.axis() + 1) % 3, b = (s.axis() + 2) % 3;
    Point3 p1 = c, p2 = c, p3 = c;
    ++p1[a];
    ++p2[a];
    ++p2[b];
    ++p3[b];
    corners.push_back(c);
    corners.push_back(s.sign() < 0 ? p3 : p1);
    corners.push_back(p2);
    corners.push_back(s.sign() < 0 ? p1 : p3);
  }
  const std::vector<vtkIdType> ids = builder.pointIds(corners, object.offset);
  for (std::size_t i = 0; i < surfels.size(); ++i)
  {
    builder.cells().addCell(ids.data() + n * i, n, -1, 0, object.label, -1, 0);
  }
}

/// The progress of writing one object's cells, over all the parts of its faces.
struct CellProgress
{
  vbr::ProgressPoll poll;
  std::size_t faces;         ///< of the object
  std::size_t facesDone = 0; ///< in the parts written before
  /// Counts face `f` of the current part; false when the caller asked to stop.
  bool tick(std::size_t f)
  {
    if (this->poll.due()) // not a division per face: one per poll
      this->poll.at(double(this->facesDone + f) / double(this->faces));
    return this->poll.tick();
  }
};

/// Where a face's cells go: its id, its parent face and depth (2D), its label, and the point
/// ids of its loops' corners (contiguous, in loop order).
struct FaceCellContext
{
  vtkIdType faceId;
  vtkIdType parent;
  int depth;
  vbr::vtk::LabelValue label;
  const std::int64_t* corner; ///< point ids of the face's loops' corners
};

/// The cells of the i-th face of a run (triangles or fan polygons).
void appendRunCells(const vbr::FaceCells& run,
  std::size_t i,
  const FaceCellContext& c,
  CellStore& out)
{
  const std::size_t first = run.cellBegin(i);
  out.addFaceCells(run.corners.data(),
    run.cornerBegin(first),
    run.cellEnds.data() + first,
    run.faceEnds[i] - first,
    c.corner,
    c.faceId,
    c.label,
    c.parent,
    c.depth);
}

/// One polygon (or closed polyline) per loop of the face.
void appendLoops(const vbr::BRep& brep,
  const vbr::BRepFace& face,
  const FaceCellContext& c,
  bool closePolylines,
  std::vector<vtkIdType>& ids,
  CellStore& out)
{
  const std::int64_t* first = c.corner - brep.loops[face.firstLoop].begin; // ids of all corners
  for (int l = face.firstLoop; l < face.firstLoop + face.loopCount; ++l)
  {
    const vbr::BRepLoop& loop = brep.loops[l];
    ids.assign(first + loop.begin, first + loop.end);
    if (closePolylines)
      ids.push_back(ids.front());
    out.addCell(ids.data(),
      ids.size(),
      c.faceId,
      loop.hole ? 1 : 0,
      c.label,
      loop.hole ? c.faceId : c.parent,
      loop.hole ? c.depth + 1 : c.depth);
  }
}

/// Whether an output mode's cells come from the triangulated runs of faces (cellsOfFaces):
/// triangles and fan polygons do, loops and polylines are the faces' loops themselves.
bool cellsFromRuns(int mode)
{
  return mode == vtkEVMBoundaryFilter::TRIANGLES || mode == vtkEVMBoundaryFilter::POLYGONS;
}

/// appendFaceCells for the triangles or fan polygons of a 3D object, faces [first, end): the
/// cells of each face, then the attributes of all these faces (or of those done before an
/// abort) written at once. The same cells and arrays. A 3D object's parts are triangulated on
/// one thread each (StreamedObjectCells), so `cells` is one run.
bool appendRunOfFaces(const vbr::BRep& brep,
  const std::vector<std::int64_t>& cornerIds,
  FaceRuns& cells,
  const vbr::vtk::Selected& object,
  vtkIdType faceBase,
  std::size_t first,
  std::size_t end,
  CellProgress& progress,
  CellStore& out)
{
  assert(cells.runs.size() == 1 && cells.firstFace.front() == first);
  const vbr::FaceCells& run = cells.runs.front();
  std::size_t f = first;
  bool aborted = false;
  // The point ids of every corner of the run, face by face, then the cells in one call: a
  // call per face was 200 instructions for a unit square's one cell (the checkerboard's 786,432
  // faces at 64^3), most of them the cell buffer's checks and growth, paid per face.
  std::vector<std::int64_t>& ids = cells.pointIds;
  ids.resize(run.corners.size());
  for (std::size_t j = 0; f < end; ++f)
  {
    if (!progress.tick(f))
    {
      aborted = true;
      break;
    }
    const std::int64_t* map = cornerIds.data() + brep.loops[brep.faces[f].firstLoop].begin;
    for (const std::size_t to = run.cornerBegin(run.faceEnds[f - first]); j < to; ++j)
      ids[j] = map[run.corners[j]];
  }
  const std::size_t done = f - first;
  out.addRunConnectivity(ids.data(), run.cellEnds.data(), done == 0 ? 0 : run.faceEnds[done - 1]);
  out.addRunAttributes(
    run.faceEnds, f - first, faceBase + static_cast<vtkIdType>(first), object.label);
  return !aborted; // aborted: the caller empties the output
}

/// The cells of an object's faces [first, end) (their runs `cells` in Triangles and Polygons
/// modes): its triangles, its polygons, or one cell per loop. False when aborted.
bool appendFaceCells(const vbr::BRep& brep,
  const std::vector<std::int64_t>& cornerIds,
  FaceRuns& cells,
  const vbr::vtk::Selected& object,
  int mode,
  vtkIdType faceBase,
  std::size_t first,
  std::size_t end,
  CellProgress& progress,
  CellStore& out)
{
  const bool fromRuns = cellsFromRuns(mode);
  if (fromRuns && !out.planar())
    return appendRunOfFaces(brep, cornerIds, cells, object, faceBase, first, end, progress, out);
  std::vector<vtkIdType> ids;
  std::size_t run = 0;
  for (std::size_t f = first; f < end; ++f)
  {
    if (!progress.tick(f))
      return false; // aborted: the caller empties the output
    const vbr::BRepFace& face = brep.faces[f];
    const FaceCellContext c{ faceBase + static_cast<vtkIdType>(f),
      face.parent < 0 ? -1 : faceBase + face.parent,
      face.depth,
      object.label,
      cornerIds.data() + brep.loops[face.firstLoop].begin };
    if (!fromRuns)
    {
      appendLoops(brep, face, c, mode == vtkEVMBoundaryFilter::POLYLINES, ids, out);
      continue;
    }
    while (run + 1 < cells.firstFace.size() && cells.firstFace[run + 1] <= f)
      ++run;
    appendRunCells(cells.runs[run], f - cells.firstFace[run], c, out);
  }
  return true;
}

/// Faces of an EVM by the plane sweeps (their loops without the T-junction vertices of
/// neighbouring faces yet), in parts that are written and released one after the other (in 3D,
/// one per chunk of planes). False when aborted.
bool boundaryOf(const vbr::EVM& evm,
  bool planar,
  vbr::FaceConnectivity connectivity,
  const vbr::Execution& exec,
  std::vector<vbr::BRep>& parts)
{
  vtkLogScopeF(TRACE, "EVM to B-Rep (plane sweeps)");
  if (!planar)
    return vbr::planeSweep3DParts(evm, connectivity, exec, parts);
  parts.clear();
  parts.push_back(vbr::extractBoundary2D(evm, connectivity));
  return true;
}

/// The triangles (Triangles mode) or the polygons that VTK draws right (Polygons mode) of
/// the faces [first, end), into `cells`: one run of faces, or, when `exec` runs in parallel
/// (a 2D image), up to 256 runs made side by side. Its runs are reused from call to call (their
/// cells cleared, their memory and scratch space kept): a call per part of the streamed sweep, a
/// part per plane or so, made each run's dozen vectors grow afresh (4 % of the filter's
/// instructions on the headsq bone, 1 % on porous 128^3).
void cellsOfFaces(const vbr::BRep& brep,
  int mode,
  std::size_t first,
  std::size_t end,
  const vbr::Execution& exec,
  FaceRuns& cells)
{
  const std::size_t faces = end - first;
  const std::size_t count = exec.parallelFor ? std::min<std::size_t>(faces, 256) : 1;
  cells.runs.resize(count);
  cells.firstFace.clear();
  for (std::size_t k = 0; k < count; ++k)
  {
    cells.runs[k].corners.clear();
    cells.runs[k].cellEnds.clear();
    cells.runs[k].faceEnds.clear();
    cells.firstFace.push_back(first + faces * k / count);
  }
  const auto append =
    mode == vtkEVMBoundaryFilter::TRIANGLES ? vbr::appendTriangles : vbr::appendFanPolygons;
  exec.forRange(static_cast<std::int64_t>(count),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t k = b; k < e; ++k)
      {
        const std::size_t last =
          k + 1 < static_cast<std::int64_t>(count) ? cells.firstFace[k + 1] : end;
        for (std::size_t f = cells.firstFace[k]; f < last; ++f)
          append(brep, static_cast<int>(f), cells.runs[k]);
      }
    });
}

/// How every object is processed.
struct ObjectSettings
{
  bool planar;
  vbr::FaceConnectivity connectivity;
  int outputMode;
  std::array<int, 3> axes;
  vbr::NumberedPlaneSweeper2D* planarSweeper; ///< the filter's, kept from update to update
};

/// Adds an object's extreme vertices and planes of vertices (`planes` per axis of its EVM,
/// mapped to the image's axes) to `stats`.
void addVertexCounts(const vbr::EVM& evm,
  const std::array<std::size_t, 3>& planes,
  const ObjectSettings& settings,
  Statistics& stats)
{
  stats.extremeVertices += static_cast<vtkIdType>(evm.size());
  for (int k = 0; k < 3; ++k)
    stats.planes[settings.axes[k]] += static_cast<vtkIdType>(planes[k]);
}

/// Counts a 3D object's voxels, surfels, extreme vertices and, in Surfels mode, planes of
/// vertices. Otherwise its plane sweeps count the planes (appendObjectsStreamed): their
/// sortings give them, where planesPerAxis' two passes over the vertices ran on one thread
/// (1 % of an update on porous 128^3 with two threads).
void countObject(const vbr::BitVolume& voxels,
  std::size_t count,
  const vbr::EVM& evm,
  const ObjectSettings& settings,
  Statistics& stats)
{
  stats.voxels += static_cast<vtkIdType>(count);
  stats.surfels += static_cast<vtkIdType>(vbr::countSurfels(voxels));
  const bool swept = settings.outputMode != vtkEVMBoundaryFilter::SURFELS;
  addVertexCounts(
    evm, swept ? std::array<std::size_t, 3>{ 0, 0, 0 } : vbr::planesPerAxis(evm), settings, stats);
}

/// countObject for a 2D image, from what extractEVM2D counted.
void countPlanarObject(const vbr::PlanarCounts& counts,
  const vbr::EVM& evm,
  const ObjectSettings& settings,
  Statistics& stats)
{
  stats.voxels += static_cast<vtkIdType>(counts.pixels);
  stats.surfels += static_cast<vtkIdType>(counts.edges);
  addVertexCounts(evm, counts.planes, settings, stats);
}

/// The EVM of one object (voxels -> EVM), counted in `stats`; in Surfels mode its cells
/// instead. Returns its number of voxels, 0 when it has no faces to make (no voxels, or
/// Surfels mode).
std::size_t extremeVerticesOfObject(const vbr::vtk::Selected& object,
  const ObjectSettings& settings,
  const vbr::Execution& exec,
  Statistics& stats,
  OutputBuilder& builder,
  vbr::EVM& evm,
  vbr::PointList* corners = nullptr,
  std::vector<vbr::Vertex>* planarMemory = nullptr)
{
  vbr::BitVolume voxels;
  {
    vtkLogScopeF(TRACE, "select voxels");
    voxels = object.select(exec);
  }
  std::size_t count = 0;
  if (settings.planar)
  {
    // One pass over the pixels for the vertices and the counts together (a 2D image's
    // update is short: the three passes of the 3D way were a fifth of a fax page's).
    vtkLogScopeF(TRACE, "extreme vertices and counts");
    // Its work is a few operations per word of the rows (64 pixels), not per pixel.
    vbr::PlanarCounts counts;
    const auto rowWords = static_cast<std::int64_t>(voxels.wordsPerRow()) * voxels.size(1);
    evm = vbr::extractEVM2D(voxels, exec.forWork(rowWords), &counts, planarMemory);
    count = counts.pixels;
    if (count == 0)
      return 0;
    countPlanarObject(counts, evm, settings, stats);
  }
  else
  {
    count = voxels.count();
    if (count == 0)
      return 0;
    const vbr::Execution local = exec.forWork(static_cast<std::int64_t>(count));
    {
      vtkLogScopeF(TRACE, "extreme vertices");
      evm = vbr::extractEVM(voxels, local);
    }
    countObject(voxels, count, evm, settings, stats);
  }
  if (settings.outputMode == vtkEVMBoundaryFilter::SURFELS)
  {
    vtkLogScopeF(TRACE, "surfel cells");
    appendSurfelCells(object, voxels, settings.planar, builder);
    return 0;
  }
  if (corners)
  {
    vtkLogScopeF(TRACE, "corners of the faces");
    vbr::appendFaceCorners(voxels,
      { object.offset[0], object.offset[1], object.offset[2] },
      *corners,
      exec.forWork(static_cast<std::int64_t>(count)));
  }
  return count;
}

/// Counts the faces, holes and non-manifold vertices of a part of an object's faces.
void countFaces(const vbr::BRep& brep, Statistics& stats)
{
  stats.faces += static_cast<vtkIdType>(brep.faces.size());
  stats.holes += static_cast<vtkIdType>(brep.holeCount());
  stats.nonManifoldVertices += static_cast<vtkIdType>(brep.nonManifoldVertices);
}

/// The faces of one object: voxels -> EVM -> faces (plane sweeps, paper 000) in parts,
/// counted in `stats`; in Surfels mode its cells instead (then `parts` stays empty). False
/// when aborted.
bool boundaryOfObject(const vbr::vtk::Selected& object,
  const ObjectSettings& settings,
  const vbr::Execution& exec,
  Statistics& stats,
  OutputBuilder& builder,
  std::vector<vbr::BRep>& parts)
{
  vbr::EVM evm;
  const std::size_t count = extremeVerticesOfObject(object, settings, exec, stats, builder, evm);
  if (count == 0)
    return true;
  const vbr::Execution local = exec.forWork(static_cast<std::int64_t>(count));
  if (!boundaryOf(evm, settings.planar, settings.connectivity, local, parts))
    return false;
  for (const vbr::BRep& brep : parts)
    countFaces(brep, stats);
  return true;
}

/// The output cells of an object's faces, whose loops hold their T-junction vertices, and
/// whose corners are output points `cornerIds`. The faces are triangulated slice by slice,
/// each slice's cells written before the next is made: the triangles of one slice, not of the
/// whole object, are alive next to the output. `runs` is scratch space (cellsOfFaces), kept by
/// the caller from part to part. False when aborted.
bool appendBoundaryCells(const vbr::vtk::Selected& object,
  const vbr::BRep& brep,
  const std::vector<std::int64_t>& cornerIds,
  const ObjectSettings& settings,
  const vbr::Execution& exec,
  vtkIdType& faceBase,
  CellProgress& progress,
  FaceRuns& runs,
  CellStore& out)
{
  constexpr std::size_t SliceOfFaces = std::size_t(1) << 16;
  const int mode = settings.outputMode;
  const bool fromRuns = cellsFromRuns(mode);
  vtkLogScopeF(TRACE, "triangles or fan polygons of the faces, and output cells");
  const std::size_t faces = brep.faces.size();
  for (std::size_t first = 0; first < faces; first += SliceOfFaces)
  {
    const std::size_t end = std::min(faces, first + SliceOfFaces);
    if (fromRuns)
      cellsOfFaces(brep, mode, first, end, exec, runs);
    if (!appendFaceCells(brep, cornerIds, runs, object, mode, faceBase, first, end, progress, out))
      return false;
  }
  faceBase += static_cast<vtkIdType>(faces);
  progress.facesDone += faces;
  return true;
}

/// Releases a part of the faces; returns the bytes it held.
std::size_t releaseFaces(vbr::BRep& part)
{
  const std::size_t bytes = part.faces.capacity() * sizeof(vbr::BRepFace) +
    part.loops.capacity() * sizeof(vbr::BRepLoop) + part.points.capacity() * sizeof(Point3);
  part = vbr::BRep();
  return bytes;
}

/// Once the parts of the faces released since the last time hold 32 MB or more, returns the
/// heap's free pages to the system. The parts live in the heap and the output's large arrays
/// in pages of their own, which never reuse the heap's free space: without this the parts
/// released would stay resident next to the output that replaces them. Small outputs never
/// pay for it. On the calling thread, while no worker allocates. The streamed sweep
/// (StreamedObjectCells) does not trim: it keeps each slot's part from one chunk of planes to
/// the next (trimmed between batches, each batch faulted its pages in afresh: porous 256^3,
/// 45 %, some 3,500 page faults per update), and frees no more than those parts at the end.
void trimHeap(std::size_t& releasedBytes)
{
#if defined(__GLIBC__)
  if (releasedBytes >= (std::size_t(32) << 20))
  {
    malloc_trim(0);
    releasedBytes = 0;
  }
#else
  (void)releasedBytes;
#endif
}

/// Returns the heap's free pages to the system once the streamed sweeps are done, before the
/// FaceId and LoopType counted per face (CellStore) are written in pages of their own, when
/// these take 32 MB or more. The sweeps' sortings (two alive at once) and scratch space were
/// freed into the heap, which keeps their pages: without this they stayed resident next to the
/// whole output (noise 128^3, Triangles: a peak of 261 MB, 225 with the trim). The next
/// update faults them in again: on porous 128^3, 45 % (9 MB of FaceId and LoopType in
/// Triangles mode), a trim cost 3 % of an update, hence the threshold. On the calling thread,
/// no worker running.
void trimBeforeAttributes(std::size_t attributeBytes)
{
#if defined(__GLIBC__)
  if (attributeBytes >= (std::size_t(32) << 20))
    malloc_trim(0);
#else
  (void)attributeBytes;
#endif
}

/// Releases a part of the faces, and trims the heap when enough was released (trimHeap).
void releasePart(vbr::BRep& part, std::size_t& releasedBytes)
{
  releasedBytes += releaseFaces(part);
  trimHeap(releasedBytes);
}

/// The cells of the only object of a 2D image in Polylines or Loops mode, one per loop: the
/// 2D plane sweep numbers the corners in the order of the output's points (as it meets them,
/// by column, on a large image with dense corners; sorted after the sweep otherwise) and
/// records them, from which the points are written; the loops' numbers are then written
/// straight into the output's cells, face after face. No B-Rep.
/// The same output as the B-Rep's way (appendBoundaryCells). Stops when aborted.
void appendPlanarLoops(vtkAlgorithm* self,
  const vbr::vtk::Selected& object,
  const ObjectSettings& settings,
  Statistics& stats,
  OutputBuilder& builder)
{
  const vbr::Contours2D* swept = nullptr;
  vbr::AxisOrder order;
  {
    vbr::EVM evm;
    const vbr::Execution exec = vbr::vtk::makeExecution(self, 0.1, 0.7);
    // The vertices too in the memory of the update before (NumberedPlaneSweeper2D).
    if (extremeVerticesOfObject(object,
          settings,
          exec,
          stats,
          builder,
          evm,
          nullptr,
          &settings.planarSweeper->vertexMemory()) == 0)
      return;
    vtkLogScopeF(TRACE, "EVM to contours (2D plane sweep, corners numbered)");
    order = evm.order();
    // numberedContours2D's sweep, in the filter's arrays kept from the update before.
    const vbr::CornerOrder cornerOrder =
      order[1] < order[2] ? vbr::CornerOrder::UThenV : vbr::CornerOrder::VThenU;
    const auto& v = evm.vertices();
    swept = &settings.planarSweeper->sweep(
      v.data(), v.data() + v.size(), cornerOrder, settings.connectivity);
    settings.planarSweeper->keepVertexMemory(evm.takeVertices());
  }
  const vbr::Contours2D& contours = *swept;
  const vbr::Boundary2D& b = contours.boundary;
  stats.faces += static_cast<vtkIdType>(b.faces.size());
  stats.holes += static_cast<vtkIdType>(b.holeCount());
  stats.nonManifoldVertices += static_cast<vtkIdType>(b.nonManifoldVertices);
  if (self->GetAbortExecute())
    return;
  {
    vtkLogScopeF(TRACE, "output points");
    builder.addContourCorners(contours, order, object.offset);
  }
  vtkLogScopeF(TRACE, "output cells");
  const vbr::Execution exec = vbr::vtk::makeExecution(self, 0.7, 1.0);
  CellProgress progress{ vbr::ProgressPoll(exec, 0.0, 1.0, 1024),
    std::max<std::size_t>(b.faces.size(), 1) };
  // The loops run counter-clockwise in (u, v): reversed, as the B-Rep's faces facing +A are,
  // when (A, u, v) is an odd order.
  builder.cells().setLoopCells(contours,
    vbr::axisOrderParity(order) != 1,
    settings.outputMode == vtkEVMBoundaryFilter::POLYLINES,
    object.label,
    [&](std::size_t f) { return progress.tick(f); });
}

/// The cells of the only object of a 2D image: its faces from the 2D plane sweep, which
/// numbers their corners in the order of the output's points as it meets them, so that no
/// set of corners is built nor looked up (appendObjects' way for several objects, which
/// share their corners). One object of a 2D image has no T-junction vertex (see
/// appendObjects). Stops when aborted.
void appendPlanarObject(vtkAlgorithm* self,
  const vbr::vtk::Selected& object,
  const ObjectSettings& settings,
  Statistics& stats,
  OutputBuilder& builder)
{
  if (!cellsFromRuns(settings.outputMode))
  {
    appendPlanarLoops(self, object, settings, stats, builder);
    return;
  }
  vbr::NumberedBRep faces;
  {
    vbr::EVM evm;
    const vbr::Execution exec = vbr::vtk::makeExecution(self, 0.1, 0.7);
    if (extremeVerticesOfObject(object, settings, exec, stats, builder, evm) == 0)
      return;
    vtkLogScopeF(TRACE, "EVM to B-Rep (2D plane sweep, corners numbered)");
    // Polygons and Triangles (Loops and Polylines took appendPlanarLoops): with points.
    faces = vbr::extractNumberedBoundary2D(evm, settings.connectivity, true);
  }
  countFaces(faces.brep, stats);
  if (self->GetAbortExecute())
    return;
  builder.addCornerPoints(faces.corners, object.offset);
  faces.corners = std::vector<Point3>();
  const vbr::Execution exec = vbr::vtk::makeExecution(self, 0.7, 1.0);
  CellProgress progress{ vbr::ProgressPoll(exec, 0.0, 1.0, 1024),
    std::max<std::size_t>(faces.brep.faces.size(), 1) };
  vtkIdType faceBase = 0;
  FaceRuns runs;
  appendBoundaryCells(object,
    faces.brep,
    faces.numbers,
    settings,
    exec.forWork(static_cast<std::int64_t>(faces.numbers.size())),
    faceBase,
    progress,
    runs,
    builder.cells());
}

/// The faces of every object (in Surfels mode its cells instead), in parts, object by object.
/// False when aborted.
bool facesOfObjects(vtkAlgorithm* self,
  const std::vector<vbr::vtk::Selected>& objects,
  const ObjectSettings& settings,
  Statistics& stats,
  OutputBuilder& builder,
  std::vector<std::vector<vbr::BRep>>& parts)
{
  const std::size_t n = objects.size();
  parts.assign(n, {});
  for (std::size_t o = 0; o < n && !self->GetAbortExecute(); ++o)
  {
    const double from = 0.1 + 0.6 * o / n, to = 0.1 + 0.6 * (o + 1) / n;
    if (!boundaryOfObject(
          objects[o], settings, vbr::vtk::makeExecution(self, from, to), stats, builder, parts[o]))
      return false;
  }
  return !self->GetAbortExecute();
}

/// The corners of all objects' faces in one set, numbered as the output's points: the
/// objects of a label map share their corners.
vbr::CornerSet numberCorners(const std::vector<vbr::vtk::Selected>& objects,
  const std::vector<std::vector<vbr::BRep>>& parts,
  const std::array<std::int32_t, 3>& dims)
{
  vtkLogScopeF(TRACE, "numbered corners");
  const vbr::KeyPacker packer =
    vbr::KeyPacker::forMaximum(*std::max_element(dims.begin(), dims.end()));
  std::vector<vbr::PlacedBRep> placed;
  for (std::size_t o = 0; o < objects.size(); ++o)
    for (const vbr::BRep& part : parts[o])
      placed.push_back({ &part, objects[o].offset });
  return vbr::CornerSet(placed, packer);
}

/// Where the cells of the objects are written: the corners' numbers, the ids of the faces
/// written so far and the bytes of the parts released since the heap was last trimmed; the
/// scratch space of the cells of the parts written on the calling thread (writePart).
struct CellWriter
{
  const vbr::CornerSet& corners;
  bool tJunctions;
  vtkIdType faceBase = 0;
  std::size_t releasedBytes = 0;
  FaceRuns runs;
};

/// The T-junction vertices (with `tJunctions`) and the cells of one part of an object's
/// faces, into `out`, their face ids from `faceBase` (moved past the part's faces), with the
/// scratch space `runs` (appendBoundaryCells). False when aborted.
bool partCells(const vbr::vtk::Selected& object,
  vbr::BRep& part,
  const ObjectSettings& settings,
  const vbr::Execution& exec,
  const vbr::CornerSet& corners,
  bool tJunctions,
  vtkIdType& faceBase,
  CellProgress& progress,
  FaceRuns& runs,
  CellStore& out)
{
  std::vector<std::int64_t>& numbers = runs.cornerNumbers;
  corners.numbersOf(part, object.offset, numbers);
  if (tJunctions)
  {
    vtkLogScopeF(TRACE, "T-junction vertices");
    vbr::insertTJunctionVertices(part, numbers, corners, object.offset, exec, runs.tJunctions);
  }
  return appendBoundaryCells(object, part, numbers, settings, exec, faceBase, progress, runs, out);
}

/// One part of an object's faces: its T-junction vertices (when the writer inserts them), its
/// cells, then it is released as soon as written. False when aborted.
bool writePart(const vbr::vtk::Selected& object,
  vbr::BRep& part,
  const ObjectSettings& settings,
  const vbr::Execution& objectExec,
  CellWriter& writer,
  CellProgress& progress,
  OutputBuilder& builder)
{
  const vbr::Execution exec = objectExec.forWork(static_cast<std::int64_t>(part.points.size()));
  if (!partCells(object,
        part,
        settings,
        exec,
        writer.corners,
        writer.tJunctions,
        writer.faceBase,
        progress,
        writer.runs,
        builder.cells()))
    return false;
  releasePart(part, writer.releasedBytes);
  return true;
}

/// The cells of one object, part after part: each part gets its T-junction vertices, is
/// written, then released. False when aborted.
bool appendObjectCells(const vbr::vtk::Selected& object,
  std::vector<vbr::BRep>& parts,
  const ObjectSettings& settings,
  const vbr::Execution& objectExec,
  CellWriter& writer,
  OutputBuilder& builder)
{
  std::size_t faces = 0;
  for (const vbr::BRep& part : parts)
    faces += part.faces.size();
  CellProgress progress{ vbr::ProgressPoll(objectExec, 0.0, 1.0, 1024),
    std::max<std::size_t>(faces, 1) };
  for (vbr::BRep& part : parts)
    if (!writePart(object, part, settings, objectExec, writer, progress, builder))
      return false; // aborted
  return true;
}

/// The EVM of every object of a 3D image and the corners of all their faces in one set (from
/// the voxels, before any face is made), numbered as the output's points and added to them;
/// per object, how many corners its faces have (with repeats across objects, about its faces'
/// work: a checkerboard has few extreme vertices and a corner at every grid point). False when
/// aborted or when nothing is left to do (Surfels mode: the cells are written).
bool evmsAndCorners(vtkAlgorithm* self,
  const std::vector<vbr::vtk::Selected>& objects,
  const ObjectSettings& settings,
  const std::array<std::int32_t, 3>& dims,
  Statistics& stats,
  OutputBuilder& builder,
  std::vector<vbr::EVM>& evms,
  std::vector<std::size_t>& faceCorners,
  std::unique_ptr<vbr::CornerSet>& corners)
{
  const std::size_t n = objects.size();
  evms.assign(n, vbr::EVM());
  faceCorners.assign(n, 0);
  vbr::PointList points;
  for (std::size_t o = 0; o < n; ++o)
  {
    if (self->GetAbortExecute())
      return false;
    const std::size_t before = points.size();
    const double from = 0.1 * o / n, to = 0.1 * (o + 1) / n;
    extremeVerticesOfObject(objects[o],
      settings,
      vbr::vtk::makeExecution(self, 0.1 + from, 0.1 + to),
      stats,
      builder,
      evms[o],
      &points);
    faceCorners[o] = points.size() - before;
  }
  if (settings.outputMode == vtkEVMBoundaryFilter::SURFELS || self->GetAbortExecute())
    return false;
  vtkLogScopeF(TRACE, "numbered corners");
  const vbr::KeyPacker packer =
    vbr::KeyPacker::forMaximum(*std::max_element(dims.begin(), dims.end()));
  // The corner set and the output's points: with threads when the corners are many.
  const vbr::Execution exec = vbr::vtk::makeExecution(self, 0.2, 0.2);
  corners.reset(
    new vbr::CornerSet(points, packer, exec.forWork(static_cast<std::int64_t>(points.size()))));
  points = vbr::PointList();
  builder.addCornerPoints(*corners, exec.forWork(static_cast<std::int64_t>(corners->size())));
  corners->releasePoints(); // now the output's
  return true;
}

/// Adds the counts of faces, holes and non-manifold vertices of `from` to `to`.
void addFaceCounts(const Statistics& from, Statistics& to)
{
  to.faces += from.faces;
  to.holes += from.holes;
  to.nonManifoldVertices += from.nonManifoldVertices;
}

/// The cells of one object's faces as its plane sweeps stream them (planeSweep3DStream): each
/// part's counts, T-junction vertices and cells are made by the thread that swept it (prepare)
/// into the part's slot, with face ids from 0 (the part is kept, emptied by the sweep for its
/// next chunk with its arrays' memory); the slots are then
/// appended to the output in the parts' order, one at a time, by whichever thread finds the
/// next part ready (append), their face ids shifted past the faces before. The output is the
/// one that writing the parts one after the other would give, cell for cell. Memory: the cells
/// of the parts alive at once (streamBatch(exec): two per thread, one on one thread) twice at
/// most, and each slot's scratch runs (FaceRuns), which keep until the object is done the capacity
/// of the largest part that slot triangulated (its triangles or fan polygons once more).
class StreamedObjectCells
{
public:
  StreamedObjectCells(const vbr::vtk::Selected& object,
    const ObjectSettings& settings,
    const vbr::Execution& exec,
    CellWriter& writer,
    Statistics& stats,
    OutputBuilder& builder)
    : Object(object)
    , Settings(settings)
    , Exec(exec.sequential()) // the parts are prepared side by side, one a thread
    , Writer(writer)
    , Stats(stats)
    , Builder(builder)
    , Direct(vbr::streamBatch(exec) == 1)
  {
    const std::size_t slots = vbr::streamBatch(exec);
    this->Slots.reserve(slots);
    for (std::size_t s = 0; s < slots; ++s)
      this->Slots.emplace_back(new Slot{ builder.newPartStore(), {}, 0, {} });
  }

  vbr::StreamedPartHandlers handlers()
  {
    return { [this](vbr::BRep& part, std::size_t slot) { return this->prepare(part, slot); },
      [this](vbr::BRep&, std::size_t slot) { return this->append(slot); } };
  }

private:
  /// One part's counts and cells, made on the thread that swept it.
  struct Slot
  {
    CellStore cells;
    Statistics counts;
    std::size_t faces;
    FaceRuns runs; ///< scratch space of the slot's parts' cells, kept from part to part
  };

  /// On a worker thread (concurrently with the other parts alive, each in its own slot):
  /// nothing shared is written, and only the abort is polled.
  bool prepare(vbr::BRep& part, std::size_t slot)
  {
    assert(slot < this->Slots.size()); // at most streamBatch(exec) parts are alive
    Slot& s = *this->Slots[slot];
    countFaces(part, s.counts);
    s.faces = part.faces.size();
    CellProgress progress{ vbr::ProgressPoll(this->Exec, 0.0, 1.0, 1024),
      std::max<std::size_t>(s.faces, 1) };
    vtkIdType faceBase = this->Direct ? this->Writer.faceBase : 0;
    const bool done = partCells(this->Object,
      part,
      this->Settings,
      this->Exec,
      this->Writer.corners,
      true,
      faceBase,
      progress,
      s.runs,
      this->Direct ? this->Builder.cells() : s.cells);
    // The part is not released: the sweep empties it for its next chunk of planes and keeps
    // its arrays' memory (PlaneSweep3D.cxx, emptyKeepingCapacity).
    return done;
  }

  /// Slot after slot in the parts' order, never two at once, on whichever thread finds the
  /// next part ready (planeSweep3DStream): it makes no VTK call, only copies into the cell
  /// store's own buffers and counts.
  bool append(std::size_t slot)
  {
    Slot& s = *this->Slots[slot];
    if (!this->Direct)
      this->Builder.cells().append(s.cells, this->Writer.faceBase);
    this->Writer.faceBase += static_cast<vtkIdType>(s.faces);
    addFaceCounts(s.counts, this->Stats);
    s.counts = Statistics();
    return true;
  }

  const vbr::vtk::Selected& Object;
  const ObjectSettings& Settings;
  const vbr::Execution Exec; ///< on one thread, silent: the sweep reports the progress
  CellWriter& Writer;
  Statistics& Stats;
  OutputBuilder& Builder;
  /// On one thread (one slot, each part appended as soon as it is prepared): the part's cells
  /// are written straight into the output's store, with the face ids that follow on from the
  /// parts before, rather than into the slot's and then copied (append: the same cells and
  /// arrays), a copy of every cell (2 % of the instructions on a checkerboard in Triangles mode).
  const bool Direct;
  std::vector<std::unique_ptr<Slot>> Slots;
};

/// The cells of every object of a 3D image (paper 000), streamed: the corners of all the
/// objects' faces are known from their voxels first (evmsAndCorners), so each chunk of planes
/// of each object's sweeps gets its T-junction vertices and its cells as soon as it is swept,
/// by the thread that swept it (StreamedObjectCells), and is released before the next chunks
/// are swept. Memory: the output, the corners, and the faces and cells of the chunks being
/// swept, never the faces of a whole object. The cells are those of appendObjects, in the same
/// order. Stops when aborted.
void appendObjectsStreamed(vtkAlgorithm* self,
  const std::vector<vbr::vtk::Selected>& objects,
  const ObjectSettings& settings,
  const std::array<std::int32_t, 3>& dims,
  Statistics& stats,
  OutputBuilder& builder)
{
  std::vector<vbr::EVM> evms;
  std::vector<std::size_t> faceCorners;
  std::unique_ptr<vbr::CornerSet> corners;
  if (!evmsAndCorners(self, objects, settings, dims, stats, builder, evms, faceCorners, corners))
    return; // aborted, or Surfels mode
  vtkLogScopeF(TRACE, "faces (plane sweeps), T-junction vertices and output cells");
  CellWriter writer{ *corners, true };
  const std::size_t n = objects.size();
  for (std::size_t o = 0; o < n && !self->GetAbortExecute(); ++o)
  {
    const double from = 0.2 + 0.8 * o / n, to = 0.2 + 0.8 * (o + 1) / n;
    const vbr::Execution exec = vbr::vtk::makeExecution(self, from, to);
    // The sweeps' work grows with the extreme vertices, the faces' with their corners.
    const vbr::Execution local =
      exec.forWork(static_cast<std::int64_t>(std::max(evms[o].size(), faceCorners[o])));
    const vbr::Execution quiet = local.silent(); // the sweep reports the progress
    if (evms[o].size() == 0)
      continue;
    StreamedObjectCells cells(objects[o], settings, quiet, writer, stats, builder);
    std::array<std::size_t, 3> planes{ 0, 0, 0 };
    if (!vbr::planeSweep3DStream(std::move(evms[o]), // freed once sorted
          settings.connectivity,
          local,
          cells.handlers(),
          &planes))
      return; // aborted
    evms[o] = vbr::EVM();
    for (int k = 0; k < 3; ++k) // countObject left them to the sweeps
      stats.planes[settings.axes[k]] += static_cast<vtkIdType>(planes[k]);
  }
  trimBeforeAttributes(builder.cells().pendingAttributeBytes());
}

/// The cells of every object (paper 000): first the faces of each (in Surfels mode its cells
/// instead), then, with the corners of all of them in one set, the T-junction vertices of
/// each part of each object's faces (the objects of a label map meet: two labels' loops on a
/// shared edge carry each other's vertices), then its cells, and the part is released. Memory:
/// the faces, then the cells, never both whole at once. Stops when aborted.
void appendObjects(vtkAlgorithm* self,
  const std::vector<vbr::vtk::Selected>& objects,
  const ObjectSettings& settings,
  const std::array<std::int32_t, 3>& dims,
  Statistics& stats,
  OutputBuilder& builder)
{
  const std::size_t n = objects.size();
  if (settings.planar && n == 1)
  {
    appendPlanarObject(self, objects[0], settings, stats, builder);
    return;
  }
  if (!settings.planar)
  {
    appendObjectsStreamed(self, objects, settings, dims, stats, builder);
    return;
  }
  std::vector<std::vector<vbr::BRep>> parts;
  if (!facesOfObjects(self, objects, settings, stats, builder, parts))
    return; // aborted
  vtkLogScopeF(TRACE, "T-junction vertices and output cells");
  // One object of a 2D image has no T-junction vertex: at a grid point strictly inside an
  // edge, the two pixels on either side of the edge are alike, so no loop turns there. Two
  // labels can meet there.
  const bool tJunctions = !settings.planar || n > 1;
  const vbr::CornerSet corners = numberCorners(objects, parts, dims);
  builder.addCornerPoints(corners,
    vbr::vtk::makeExecution(self, 0.7, 0.7).forWork(static_cast<std::int64_t>(corners.size())));
  CellWriter writer{ corners, tJunctions };
  for (std::size_t o = 0; o < n && !self->GetAbortExecute(); ++o)
  {
    const double from = 0.7 + 0.3 * o / n, to = 0.7 + 0.3 * (o + 1) / n;
    if (!appendObjectCells(
          objects[o], parts[o], settings, vbr::vtk::makeExecution(self, from, to), writer, builder))
      return; // aborted
    self->UpdateProgress(to);
  }
}

void writeStatistics(const Statistics& stats, vtkFieldData* fd)
{
  vbr::vtk::addFieldValues(fd,
    { { "NumberOfVoxels", stats.voxels },
      { "NumberOfExtremeVertices", stats.extremeVertices },
      { "NumberOfSurfels", stats.surfels },
      { "NumberOfFaces", stats.faces },
      { "NumberOfHoles", stats.holes },
      { "NumberOfNonManifoldVertices", stats.nonManifoldVertices } },
    1); // NumberOfPlanesOfVertices
  vtkNew<vtkIdTypeArray> planes;
  planes->SetName("NumberOfPlanesOfVertices");
  planes->SetNumberOfComponents(3);
  planes->InsertNextTypedTuple(stats.planes.data());
  fd->AddArray(planes);
}

} // namespace

/// The filter's 2D sweep (vtkEVMBoundaryFilter.h): kept between updates, released when an
/// image has much fewer vertices than the largest one swept since (NumberedPlaneSweeper2D).
class vtkEVMBoundaryFilter::vtkPlanarSweep : public vbr::NumberedPlaneSweeper2D
{
};

//------------------------------------------------------------------------------
vtkEVMBoundaryFilter::vtkEVMBoundaryFilter()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, vtkDataSetAttributes::SCALARS);
  this->SetProgressText("EVM Boundary");
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
    case LOOPS:
      return "Loops";
    default:
      return "Surfels";
  }
}

//------------------------------------------------------------------------------
int vtkEVMBoundaryFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vbr::vtk::executeGuarded(this,
    outputVector,
    "Boundary extraction",
    [&] { return this->Execute(inputVector, outputVector); });
}

//------------------------------------------------------------------------------
int vtkEVMBoundaryFilter::Execute(vtkInformationVector** inputVector,
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
  vbr::vtk::SelectionSettings settings = vbr::vtk::selectionSettingsOf(this);
  settings.flatImagesAs2D = this->FlatImagesAs2D;
  settings.maximumVoxelsPerAxis = (1 << 21) - 2;
  settings.distributed = true; // the faces of the whole image on rank 0 (N ranks = 1 rank)
  vbr::vtk::InputObjects in;
  if (!vbr::vtk::readInputObjects(this, input, scalars, association, settings, in))
    return 0;
  const vbr::vtk::VoxelGrid& grid = in.grid;
  const std::array<int, 3>& axes = in.axes;
  const std::vector<vbr::vtk::Selected>& objects = in.objects;
  if (std::int64_t(grid.dims[0]) * grid.dims[1] * grid.dims[2] == 0)
    return 1; // no voxels: an empty boundary
  const bool planar = grid.flatAxis >= 0;
  this->UpdateProgress(0.1);

  // One object (a label, or the whole selection) at a time: its voxels, EVM and faces are
  // released before the next.
  if (planar && !this->PlanarSweep)
    this->PlanarSweep = std::make_unique<vtkPlanarSweep>();
  const ObjectSettings each{ planar,
    this->MergeNonManifoldFaces ? vbr::FaceConnectivity::Vertex : vbr::FaceConnectivity::Edge,
    this->OutputMode,
    axes,
    planar ? this->PlanarSweep.get() : nullptr };
  OutputBuilder builder(grid, axes, planar);
  Statistics stats;
  appendObjects(this, objects, each, grid.dims, stats, builder);

  if (this->GetAbortExecute())
  {
    return 1; // aborted: an empty output rather than a part of the boundary
  }
  {
    vtkLogScopeF(TRACE, "hand the output to VTK");
    const bool lines = this->OutputMode == POLYLINES || (planar && this->OutputMode == SURFELS);
    builder.finish(output, lines, in.labelType);
  }
  vbr::vtk::setBoundaryColoring(output, this->GetSelectionMode() == LABELS);
  writeStatistics(stats, output->GetFieldData());
  vbr::vtk::addDistributionFields(output->GetFieldData(), in.piece);
  return 1;
}

//------------------------------------------------------------------------------
void vtkEVMBoundaryFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Selection:\n";
  this->Selection->PrintSelf(os, indent.GetNextIndent());
  os << indent << "OutputMode: " << this->GetOutputModeAsString() << "\n";
  os << indent << "MergeNonManifoldFaces: " << (this->MergeNonManifoldFaces ? "On\n" : "Off\n");
  os << indent << "FlatImagesAs2D: " << (this->FlatImagesAs2D ? "On\n" : "Off\n");
}
