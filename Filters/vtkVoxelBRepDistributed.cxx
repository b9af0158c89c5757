#include "vtkVoxelBRepDistributed.h"

#include "EVM.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>

namespace vbr
{
namespace vtk
{
namespace
{

/// The box [lo, hi] (inclusive, per axis) of the points (or cells) of an extent whose ghost
/// value has none of the bits `ghostBits`; all of them without a ghost array.
void nonGhostBox(vtkDataArray* ghosts,
  const std::array<std::int32_t, 3>& n,
  unsigned char ghostBits,
  std::array<std::int32_t, 3>& lo,
  std::array<std::int32_t, 3>& hi)
{
  lo = { 0, 0, 0 };
  hi = { n[0] - 1, n[1] - 1, n[2] - 1 };
  vtkUnsignedCharArray* g = vtkUnsignedCharArray::SafeDownCast(ghosts);
  if (!g || g->GetNumberOfValues() != vtkIdType(n[0]) * n[1] * n[2])
    return;
  lo = n;
  hi = { -1, -1, -1 };
  const unsigned char* v = g->GetPointer(0);
  for (std::int32_t k = 0; k < n[2]; ++k)
    for (std::int32_t j = 0; j < n[1]; ++j)
      for (std::int32_t i = 0; i < n[0]; ++i)
        if (!(v[(vtkIdType(k) * n[1] + j) * n[0] + i] & ghostBits))
        {
          const std::array<std::int32_t, 3> p{ i, j, k };
          for (int d = 0; d < 3; ++d)
          {
            lo[d] = std::min(lo[d], p[d]);
            hi[d] = std::max(hi[d], p[d]);
          }
        }
}

/// The owned voxels of a piece (see the ownership rule in the header).
void ownVoxels(vtkImageData* image,
  const int extent[6],
  const int whole[6],
  bool trustGhostMarks,
  Piece& piece)
{
  const bool cellData = piece.whole.cellData;
  std::array<std::int32_t, 3> n;
  for (int d = 0; d < 3; ++d)
    n[d] = extent[2 * d + 1] - extent[2 * d] + (cellData ? 0 : 1);
  for (int d = 0; d < 3; ++d)
    n[d] = std::max<std::int32_t>(n[d], 1); // cells of a single layer of points
  vtkDataArray* ghosts = cellData
    ? image->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName())
    : image->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName());
  const unsigned char bits = cellData
    ? static_cast<unsigned char>(vtkDataSetAttributes::DUPLICATECELL)
    : static_cast<unsigned char>(vtkDataSetAttributes::DUPLICATEPOINT);
  std::array<std::int32_t, 3> lo, hi;
  nonGhostBox(ghosts, n, bits, lo, hi);
  for (int d = 0; d < 3; ++d)
  {
    piece.ownedLo[d] = lo[d];
    piece.ownedHi[d] = hi[d] + 1;
    // Point scalars: the upper plane of points is the neighbour's, unless it ends the image;
    // ghost marks that already name one owner of each shared point are trusted instead.
    if (!cellData && !(ghosts && trustGhostMarks) && hi[d] >= lo[d] &&
      extent[2 * d] + hi[d] < whole[2 * d + 1])
      piece.ownedHi[d] = hi[d];
    piece.ownedHi[d] = std::max(piece.ownedHi[d], piece.ownedLo[d]);
  }
}

std::int64_t ownedVoxelCount(const Piece& piece)
{
  std::int64_t count = 1;
  for (int d = 0; d < 3; ++d)
    count *= piece.ownedHi[d] - piece.ownedLo[d];
  return count;
}

/// Sends this rank's values to rank 0, which receives every rank's (`all`, by rank).
bool gatherOnFirstRank(Piece& piece,
  std::vector<long long>& values,
  std::vector<std::vector<long long>>& all)
{
  vtkMultiProcessController* c = piece.controller;
  long long length = static_cast<long long>(values.size());
  std::vector<long long> lengths(piece.ranks, 0);
  if (!c->Gather(&length, lengths.data(), 1, 0))
    return false;
  std::vector<vtkIdType> counts(piece.ranks, 0), offsets(piece.ranks, 0);
  vtkIdType total = 0;
  for (int r = 0; r < piece.ranks; ++r)
  {
    counts[r] = static_cast<vtkIdType>(lengths[r]);
    offsets[r] = total;
    total += counts[r];
  }
  std::vector<long long> received(piece.rank == 0 ? std::max<vtkIdType>(total, 1) : 1);
  piece.bytesSent += static_cast<std::int64_t>(sizeof(long long) * (values.size() + 1));
  if (!c->GatherV(values.data(), received.data(), length, counts.data(), offsets.data(), 0))
    return false;
  if (piece.rank == 0)
  {
    piece.bytesReceived += static_cast<std::int64_t>(sizeof(long long) * (total + piece.ranks));
    all.resize(piece.ranks);
    for (int r = 0; r < piece.ranks; ++r)
      all[r].assign(received.begin() + offsets[r], received.begin() + offsets[r] + counts[r]);
  }
  return true;
}

/// The EVM of each local object, in whole-grid voxel coordinates (processing axes), as the
/// message [status, label type, object count, then per object: label bits, vertex count,
/// vertices (sorting coordinates)].
std::vector<long long> localMessage(bool ok, const Piece& piece, const InputObjects& in)
{
  std::vector<long long> m{ ok ? 1 : 0, in.labelType, 0 };
  if (!ok)
    return m;
  const bool planar = piece.whole.flatAxis >= 0;
  const Box owned = ownedBox(piece, in.axes);
  for (const Selected& object : in.objects)
  {
    const BitVolume voxels = object.select(Execution());
    const EVM evm = planar ? extractEVM2D(voxels) : extractEVM(voxels);
    if (evm.empty())
      continue;
    std::array<std::int64_t, 3> shift; // processing axes
    for (int k = 0; k < 3; ++k)
      shift[k] = object.offset[k] + owned.lo[k] + piece.offset[in.axes[k]];
    if (planar)
      shift[2] = 0; // a 2D EVM keeps its normal coordinate at 0
    long long bits;
    std::memcpy(&bits, &object.label.bits, sizeof bits);
    m.push_back(bits);
    m.push_back(static_cast<long long>(evm.size()));
    for (const Vertex& v : evm.vertices())
      for (int k = 0; k < 3; ++k)
        m.push_back(v[k] + shift[evm.order()[k]]);
    ++m[2];
  }
  return m;
}

/// The vertices that occur an odd number of times, sorted: the XOR of EVMs.
std::vector<Vertex> xorOfVertices(std::vector<Vertex> v)
{
  std::sort(v.begin(), v.end());
  std::vector<Vertex> out;
  for (std::size_t i = 0; i < v.size();)
  {
    std::size_t j = i;
    while (j < v.size() && v[j] == v[i])
      ++j;
    if ((j - i) % 2 == 1)
      out.push_back(v[i]);
    i = j;
  }
  return out;
}

/// An object of the whole image from its merged EVM: its voxels in the box of its vertices.
Selected objectOfEVM(const LabelValue& label, std::vector<Vertex> vertices, bool planar)
{
  const AxisOrder order{ 2, 1, 0 }; // what extractEVM and extractEVM2D give
  std::array<std::int32_t, 3> lo{ INT32_MAX, INT32_MAX, INT32_MAX }, hi{ 0, 0, 0 };
  for (const Vertex& v : vertices)
    for (int k = 0; k < 3; ++k)
    {
      lo[order[k]] = std::min(lo[order[k]], v[k]);
      hi[order[k]] = std::max(hi[order[k]], v[k]);
    }
  if (planar)
    lo[2] = 0, hi[2] = 1;
  for (Vertex& v : vertices)
    for (int k = 0; k < 3; ++k)
      v[k] -= lo[order[k]];
  const std::array<std::int32_t, 3> dims{ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] };
  Selected s;
  s.label = label;
  s.offset = lo;
  auto evm = std::make_shared<EVM>(planar ? 2 : 3, order, std::move(vertices));
  s.select = [evm, dims](const Execution&) { return evm->toVoxels(dims); };
  return s;
}

/// Rank 0: the labels of all ranks merged by XOR, in the order a single process lists them
/// (increasing values of the label type).
template<typename T>
std::vector<Selected> mergeMessages(const std::vector<std::vector<long long>>& all, bool planar)
{
  std::map<T, std::pair<LabelValue, std::vector<Vertex>>> byLabel;
  for (const std::vector<long long>& m : all)
  {
    std::size_t at = 3;
    for (long long o = 0; o < m[2]; ++o)
    {
      LabelValue label;
      std::memcpy(&label.bits, &m[at], sizeof label.bits);
      const std::size_t count = static_cast<std::size_t>(m[at + 1]);
      at += 2;
      auto& entry = byLabel[label.as<T>()];
      entry.first = label;
      for (std::size_t i = 0; i < count; ++i, at += 3)
        entry.second.push_back({ static_cast<Coord>(m[at]),
          static_cast<Coord>(m[at + 1]),
          static_cast<Coord>(m[at + 2]) });
    }
  }
  std::vector<Selected> out;
  for (auto& entry : byLabel)
  {
    std::vector<Vertex> merged = xorOfVertices(std::move(entry.second.second));
    if (!merged.empty())
      out.push_back(objectOfEVM(entry.second.first, std::move(merged), planar));
  }
  return out;
}

/// The voxels `selection` marks (one value per voxel of a grid of `dims`, x fastest).
BitVolume markedVoxels(const unsigned char* selection, const std::array<std::int32_t, 3>& dims)
{
  BitVolume voxels(dims[0], dims[1], dims[2]);
  for (std::int32_t z = 0; z < dims[2]; ++z)
    for (std::int32_t y = 0; y < dims[1]; ++y)
    {
      const unsigned char* row = selection + (std::size_t(z) * dims[1] + y) * dims[0];
      for (std::int32_t x = 0; x < dims[0]; ++x)
        if (row[x])
          voxels.set(x, y, z);
    }
  return voxels;
}

/// The EVM (vertices in extractEVM's order) of the voxels of the box [lo, lo + dims) of the
/// set whose EVM is `vertices`: a vertex below the box along an axis counts for every voxel of
/// the box at or above it along the others, so it moves onto the box's lower face; a vertex
/// at or past the box's upper end counts for none, so it goes.
EVM croppedEVM(const std::vector<Vertex>& vertices,
  const std::array<std::int32_t, 3>& lo,
  const std::array<std::int32_t, 3>& dims)
{
  const AxisOrder order{ 2, 1, 0 };
  std::vector<Vertex> inBox;
  inBox.reserve(vertices.size());
  for (const Vertex& v : vertices)
  {
    Vertex moved;
    bool kept = true;
    for (int k = 0; k < 3 && kept; ++k)
    {
      const std::int64_t c = std::int64_t(v[k]) - lo[order[k]];
      kept = c < dims[order[k]];
      moved[k] = static_cast<Coord>(std::max<std::int64_t>(c, 0));
    }
    if (kept)
      inBox.push_back(moved);
  }
  return EVM(3, order, xorOfVertices(std::move(inBox)));
}

/// Rank 0's message of scatterSelection: [status, vertex count, vertices (z, y, x)].
std::vector<long long> selectionMessage(const unsigned char* wholeSelection,
  int status,
  const Piece& piece)
{
  if (!wholeSelection || status == 0)
    return { 0, 0 };
  const EVM evm = extractEVM(markedVoxels(wholeSelection, piece.whole.dims));
  std::vector<long long> m{ status, static_cast<long long>(evm.size()) };
  m.reserve(2 + 3 * evm.size());
  for (const Vertex& v : evm.vertices())
    m.insert(m.end(), { v[0], v[1], v[2] });
  return m;
}

} // namespace

vtkMultiProcessController* distributedController(vtkAlgorithm* algorithm)
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  if (!c || c->GetNumberOfProcesses() < 2 || algorithm->GetNumberOfOutputPorts() == 0)
    return nullptr;
  vtkInformation* out = algorithm->GetOutputInformation(0);
  const int pieces = out->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? out->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
  return pieces == c->GetNumberOfProcesses() ? c : nullptr;
}

std::string describePiece(vtkMultiProcessController* controller,
  vtkInformation* inputInformation,
  vtkImageData* image,
  bool cellData,
  bool flatImagesAs2D,
  Piece& piece)
{
  piece = Piece();
  int whole[6], extent[6];
  if (!controller || !inputInformation ||
    !inputInformation->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    return std::string();
  inputInformation->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  image->GetExtent(extent);
  std::copy(whole, whole + 6, piece.wholeExtent);
  piece.controller = controller;
  piece.rank = controller->GetLocalProcessId();
  piece.ranks = controller->GetNumberOfProcesses();
  const std::string problem = describeExtent(whole, cellData, flatImagesAs2D, piece.whole);
  if (!problem.empty())
    return problem;
  readGeometry(image, piece.whole);
  for (int d = 0; d < 3; ++d)
    piece.offset[d] = extent[2 * d] - whole[2 * d];
  // Collective: the rule that makes the owned voxels of all ranks a partition of the image.
  const std::int64_t wholeCount =
    std::int64_t(piece.whole.dims[0]) * piece.whole.dims[1] * piece.whole.dims[2];
  for (bool trustGhostMarks : { true, false })
  {
    if (image->GetNumberOfPoints() > 0)
      ownVoxels(image, extent, whole, trustGhostMarks, piece);
    long long owned = ownedVoxelCount(piece), total = 0;
    controller->AllReduce(&owned, &total, 1, vtkCommunicator::SUM_OP);
    piece.partitioned = total == wholeCount;
    if (piece.partitioned)
      break;
  }
  return std::string();
}

Box ownedBox(const Piece& piece, const std::array<int, 3>& axes)
{
  Box box;
  for (int k = 0; k < 3; ++k)
  {
    box.lo[k] = piece.ownedLo[axes[k]];
    box.hi[k] = piece.ownedHi[axes[k]];
  }
  return box;
}

bool mergeObjectsOnFirstRank(bool ok, Piece& piece, InputObjects& in)
{
  // Pieces that do not partition the whole image (each rank given all of it) are processed
  // by rank 0 alone.
  if (!piece.partitioned && piece.rank != 0)
    in.objects.clear();
  std::vector<long long> message = localMessage(ok, piece, in);
  std::vector<std::vector<long long>> all;
  long long status = gatherOnFirstRank(piece, message, all) ? 1 : 0;
  int labelType = in.labelType;
  if (piece.rank == 0)
    for (const std::vector<long long>& m : all)
    {
      status = status && m[0];
      if (m[2] > 0)
        labelType = static_cast<int>(m[1]);
    }
  piece.controller->Broadcast(&status, 1, 0);
  in.objects.clear();
  in.contiguous = nullptr;
  piece.local = in.grid;
  if (!status)
    return false;
  if (piece.rank != 0)
    return true;
  in.grid = piece.whole;
  in.axes = processingAxes(in.grid);
  in.labelType = labelType;
  const bool planar = in.grid.flatAxis >= 0;
  switch (labelType)
  {
    vtkTemplateMacro(in.objects = mergeMessages<VTK_TT>(all, planar));
    default:
      return false;
  }
  return true;
}

bool broadcastValues(Piece& piece, std::vector<long long>& values)
{
  long long length = static_cast<long long>(values.size());
  if (!piece.controller->Broadcast(&length, 1, 0))
    return false;
  values.resize(static_cast<std::size_t>(length));
  if (piece.rank == 0)
    piece.bytesSent +=
      static_cast<std::int64_t>(sizeof(long long) * (values.size() + 1)) * (piece.ranks - 1);
  return length == 0 || piece.controller->Broadcast(values.data(), length, 0);
}

vtkSmartPointer<vtkDataSet> gatherPoints(Piece& piece, vtkDataSet* points)
{
  std::vector<long long> values;
  const vtkIdType n = points ? points->GetNumberOfPoints() : 0;
  values.reserve(static_cast<std::size_t>(3 * n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    for (double c : p)
    {
      long long bits;
      std::memcpy(&bits, &c, sizeof bits);
      values.push_back(bits);
    }
  }
  std::vector<std::vector<long long>> all;
  if (!gatherOnFirstRank(piece, values, all) || piece.rank != 0)
    return nullptr;
  vtkNew<vtkPoints> gathered;
  gathered->SetDataTypeToDouble();
  for (const std::vector<long long>& m : all)
    for (std::size_t i = 0; i + 2 < m.size(); i += 3)
    {
      double p[3];
      std::memcpy(p, &m[i], sizeof p);
      gathered->InsertNextPoint(p);
    }
  vtkSmartPointer<vtkPolyData> out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(gathered);
  return out;
}

bool scatterSelection(Piece& piece,
  vtkUnsignedCharArray* wholeSelection,
  int& status,
  vtkUnsignedCharArray* pieceSelection)
{
  std::vector<long long> message;
  if (piece.rank == 0)
    message =
      selectionMessage(wholeSelection ? wholeSelection->GetPointer(0) : nullptr, status, piece);
  status = 0;
  if (!broadcastValues(piece, message) || message.size() < 2 || message[0] == 0)
    return false;
  status = static_cast<int>(message[0]);
  std::vector<Vertex> vertices(static_cast<std::size_t>(message[1]));
  for (std::size_t i = 0; i < vertices.size(); ++i)
    for (int k = 0; k < 3; ++k)
      vertices[i][k] = static_cast<Coord>(message[2 + 3 * i + k]);
  const std::array<std::int32_t, 3>& dims = piece.local.dims;
  const BitVolume voxels = croppedEVM(vertices, piece.offset, dims).toVoxels(dims);
  resizeOrThrow(pieceSelection, vtkIdType(dims[0]) * dims[1] * dims[2]);
  unsigned char* out = pieceSelection->GetPointer(0);
  for (std::int32_t z = 0; z < dims[2]; ++z)
    for (std::int32_t y = 0; y < dims[1]; ++y)
      for (std::int32_t x = 0; x < dims[0]; ++x)
        *out++ = voxels.get(x, y, z) ? 1 : 0;
  return true;
}

} // namespace vtk
} // namespace vbr
