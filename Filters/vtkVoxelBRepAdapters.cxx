#include "vtkVoxelBRepAdapters.h"
#include "vtkVoxelBRepDistributed.h"
#include "vtkVoxelBRepMemory.h"

#include "HugePages.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSetGet.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUniformGrid.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <new>
#include <sstream>
#include <stdexcept>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace vbr
{
namespace vtk
{

Execution makeExecution(vtkAlgorithm* algorithm, double progressFrom, double progressTo)
{
  Execution exec;
  // An exception must not leave a vtkSMPTools worker (std::terminate): the first one is
  // kept and thrown again on the calling thread.
  exec.parallelFor = [](std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body)
  {
    std::exception_ptr failure;
    std::mutex guard;
    vtkSMPTools::For(vtkIdType(0),
      static_cast<vtkIdType>(n),
      [&](vtkIdType b, vtkIdType e)
      {
        try
        {
          body(b, e);
        }
        catch (...)
        {
          std::lock_guard<std::mutex> lock(guard);
          if (!failure)
            failure = std::current_exception();
        }
      });
    if (failure)
      std::rethrow_exception(failure);
  };
  exec.progress = [algorithm, progressFrom, progressTo](double f)
  {
    algorithm->UpdateProgress(progressFrom + f * (progressTo - progressFrom));
    return !algorithm->GetAbortExecute();
  };
  exec.aborted = [algorithm]() { return algorithm->GetAbortExecute() != 0; };
  exec.concurrency = std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
  return exec;
}

void VoxelGrid::vertexToWorld(const std::array<std::int32_t, 3>& v, double world[3]) const
{
  const double position[3] = { double(v[0]), double(v[1]), double(v[2]) }; // exact
  this->positionToWorld(position, world);
}

void VoxelGrid::positionToWorld(const double v[3], double world[3]) const
{
  double local[3];
  for (int d = 0; d < 3; ++d)
    local[d] = (this->extentMin[d] + this->vertexShift[d] + v[d]) * this->spacing[d];
  for (int r = 0; r < 3; ++r)
  {
    world[r] = this->origin[r] + this->direction[3 * r] * local[0] +
      this->direction[3 * r + 1] * local[1] + this->direction[3 * r + 2] * local[2];
  }
}

double VoxelGrid::directionDeterminant() const
{
  const auto& m = this->direction;
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
    m[2] * (m[3] * m[7] - m[4] * m[6]);
}

bool VoxelGrid::mirrorsSpace() const
{
  return this->directionDeterminant() * this->spacing[0] * this->spacing[1] * this->spacing[2] < 0;
}

bool VoxelGrid::worldToVoxel(const double world[3], std::array<std::int32_t, 3>& voxel) const
{
  // The static forms of vtkMatrix3x3 (the same arithmetic): a vtkMatrix3x3 object per call
  // cost more than the lookup itself with tens of thousands of seed points.
  double inverse[9];
  vtkMatrix3x3::Invert(this->direction.data(), inverse);
  const double p[3] = {
    world[0] - this->origin[0], world[1] - this->origin[1], world[2] - this->origin[2]
  };
  double local[3];
  vtkMatrix3x3::MultiplyPoint(inverse, p, local);
  for (int d = 0; d < 3; ++d)
  {
    if (this->spacing[d] == 0.0)
      return false;
    double index = local[d] / this->spacing[d] - this->extentMin[d] - this->vertexShift[d];
    if (d == this->flatAxis)
      index = 0.0; // a 2D image: a position anywhere above or below the plane
    const double cell = std::floor(index);
    if (!(cell >= 0.0 && cell < this->dims[d])) // also false for NaN
      return false;
    voxel[d] = static_cast<std::int32_t>(cell);
  }
  return true;
}

namespace
{

/// "the scalar array 'name' has N tuples, the image has <what>".
std::string tupleMismatch(vtkDataArray* scalars, const std::string& what)
{
  std::ostringstream msg;
  msg << "the scalar array '" << (scalars->GetName() ? scalars->GetName() : "") << "' has "
      << scalars->GetNumberOfTuples() << " tuples, the image has " << what;
  return msg.str();
}

/// The voxels along each axis from the image's extent (`flatCount`, `flat`: the axes of cell
/// data with a single layer of points). Returns a problem, or an empty string; an image
/// without points has dims 0.
std::string voxelsOfExtent(const int extent[6],
  bool cellData,
  VoxelGrid& grid,
  int& flatCount,
  int& flat)
{
  for (int d = 0; d < 3; ++d)
  {
    const std::int64_t points = std::int64_t(extent[2 * d + 1]) - extent[2 * d] + 1;
    if (points <= 0)
    {
      grid.dims = { 0, 0, 0 };
      return std::string();
    }
    if (points > std::numeric_limits<std::int32_t>::max())
    {
      std::ostringstream msg;
      msg << "the extent spans " << points << " points along axis " << d << ", more than the "
          << std::numeric_limits<std::int32_t>::max() << " the voxel coordinates hold";
      return msg.str();
    }
    grid.extentMin[d] = extent[2 * d];
    // Point scalars: voxels centred at the points. Cell scalars: the cells; a single layer of
    // points carries no thickness, and its cells are pixels of that plane.
    grid.dims[d] = cellData ? (points > 1 ? points - 1 : 1) : points;
    grid.vertexShift[d] = cellData ? 0.0 : -0.5;
    if (cellData && points == 1)
    {
      ++flatCount;
      flat = d;
    }
  }
  return std::string();
}

/// The axis a 2D image is flat along, or -1: cell data on a single layer of points is always
/// 2D, otherwise an image with one voxel along exactly one axis when flatImagesAs2D is on.
int flatAxisOf(const VoxelGrid& grid, int flatCount, int flat, bool flatImagesAs2D)
{
  if (flatCount == 1)
    return flat;
  if (!flatImagesAs2D)
    return -1;
  int singles = 0, single = -1;
  for (int d = 0; d < 3; ++d)
    if (grid.dims[d] == 1)
    {
      ++singles;
      single = d;
    }
  return singles == 1 ? single : -1;
}

} // namespace

void readGeometry(vtkImageData* image, VoxelGrid& grid)
{
  image->GetOrigin(grid.origin.data());
  image->GetSpacing(grid.spacing.data());
  if (vtkMatrix3x3* m = image->GetDirectionMatrix())
  {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        grid.direction[3 * r + c] = m->GetElement(r, c);
  }
}

std::string describeExtent(const int extent[6], bool cellData, bool flatImagesAs2D, VoxelGrid& grid)
{
  grid.cellData = cellData;
  grid.flatAxis = -1;
  int flatCount = 0, flat = -1;
  const std::string problem = voxelsOfExtent(extent, cellData, grid, flatCount, flat);
  if (!problem.empty())
    return problem;
  if (std::int64_t(grid.dims[0]) * grid.dims[1] * grid.dims[2] == 0)
    return std::string();
  if (cellData && flatCount > 1)
    return "cell scalars of an image that is flat along two axes describe no voxels";
  grid.flatAxis = flatAxisOf(grid, flatCount, flat, flatImagesAs2D);
  if (grid.flatAxis >= 0)
    grid.vertexShift[grid.flatAxis] = 0.0; // the contours lie in the image's plane
  return std::string();
}

std::string describeVoxels(vtkImageData* image,
  vtkDataArray* scalars,
  bool cellData,
  bool flatImagesAs2D,
  VoxelGrid& grid)
{
  int extent[6];
  image->GetExtent(extent);
  grid = VoxelGrid();
  const std::string problem = describeExtent(extent, cellData, flatImagesAs2D, grid);
  const vtkIdType expected = static_cast<vtkIdType>(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  if (!problem.empty() && expected == 0)
    return problem; // the extent itself is unusable
  if (expected == 0)
    return scalars->GetNumberOfTuples() == 0 ? std::string() : tupleMismatch(scalars, "no points");
  if (scalars->GetNumberOfTuples() != expected)
    return tupleMismatch(scalars, std::to_string(expected) + (cellData ? " cells" : " points"));
  if (!problem.empty())
    return problem;
  readGeometry(image, grid);
  return geometryProblem(grid);
}

std::string geometryProblem(const VoxelGrid& grid)
{
  const auto finite = [](const std::array<double, 3>& v)
  { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); };
  std::ostringstream msg;
  if (!finite(grid.spacing))
  {
    msg << "the spacing (" << grid.spacing[0] << ", " << grid.spacing[1] << ", " << grid.spacing[2]
        << ") is not finite";
    return msg.str();
  }
  if (!finite(grid.origin))
  {
    msg << "the origin (" << grid.origin[0] << ", " << grid.origin[1] << ", " << grid.origin[2]
        << ") is not finite";
    return msg.str();
  }
  const double det = grid.directionDeterminant();
  if (!(std::abs(det) > 1e-12)) // also NaN
  {
    return "the direction matrix is singular or not finite (its determinant is " +
      std::to_string(det) + ")";
  }
  return std::string();
}

} // namespace vtk
} // namespace vbr

namespace vbr
{
namespace vtk
{

namespace
{
#ifdef __linux__
constexpr std::size_t HugePage = std::size_t(2) << 20;

/// What a zeroed mapping needs to be unmapped, at the start of its first huge page, with a
/// cookie; its data start HeaderBytes later, in the same 4 KiB page.
struct MappingHeader
{
  void* base;
  std::size_t length;
  std::uint64_t cookie;
};
constexpr std::uint64_t MappingCookie = 0x5642525a65726f73ull;
constexpr std::size_t HeaderBytes = 64; // the data 64-byte aligned

/// Whether `data` is a block of mapZeroed, and then its header. VTK keeps an array's free
/// function when it empties the array and reallocates it later by malloc, then hands that
/// block to unmapZeroed. The header read lies in the page of `data`, mapped whatever it is.
#if defined(__clang__) || defined(__GNUC__)
__attribute__((no_sanitize_address))
#endif
bool
readMappingHeader(void* data, MappingHeader& header)
{
  if (reinterpret_cast<std::uintptr_t>(data) % HugePage != HeaderBytes)
    return false;
  // Plain loads, not memcpy, which a sanitizer intercepts whatever the attribute says.
  header = *reinterpret_cast<const MappingHeader*>(static_cast<char*>(data) - HeaderBytes);
  return header.cookie == MappingCookie;
}

void unmapZeroed(void* data)
{
  MappingHeader header;
  if (data && readMappingHeader(data, header))
    munmap(header.base, header.length);
  else
    std::free(data);
}

/// n zero bytes, HeaderBytes into a huge page, or nullptr.
void* mapZeroed(std::size_t bytes)
{
  const std::size_t rounded = (bytes + HeaderBytes + HugePage - 1) / HugePage * HugePage;
  const std::size_t length = rounded + HugePage; // room to align
  void* base = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (base == MAP_FAILED)
    return nullptr;
  char* page = reinterpret_cast<char*>(
    (reinterpret_cast<std::uintptr_t>(base) + HugePage - 1) / HugePage * HugePage);
  madvise(page, rounded, MADV_HUGEPAGE); // a hint: failure only costs time
  const MappingHeader header{ base, length, MappingCookie };
  std::memcpy(page, &header, sizeof header);
  return page + HeaderBytes;
}
#endif
} // namespace

vtkSmartPointer<vtkIntArray> newZeroedIntArray(vtkIdType n)
{
  auto array = vtkSmartPointer<vtkIntArray>::New();
#ifdef __linux__
  const std::size_t bytes = static_cast<std::size_t>(n) * sizeof(int);
  if (bytes >= 4 * HugePage)
  {
    if (void* memory = mapZeroed(bytes))
    {
      array->SetArray(
        static_cast<int*>(memory), n, 0, vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
      array->SetArrayFreeFunction(unmapZeroed);
      return array;
    }
  }
#endif
  resizeOrThrow(array, n);
  std::fill_n(array->GetPointer(0), n, 0);
  return array;
}

namespace
{
double bytesOf(vtkAbstractArray* array, vtkIdType tuples)
{
  return double(tuples) * array->GetNumberOfComponents() * array->GetDataTypeSize();
}

void resizeChecked(vtkAbstractArray* array, vtkIdType tuples)
{
  array->SetNumberOfTuples(tuples);
  if (array->GetNumberOfTuples() != tuples)
    throw std::bad_alloc();
}
} // namespace

void resizeOrThrow(vtkAbstractArray* array, vtkIdType tuples)
{
  // VTK aborts the process when an array cannot be allocated: refuse before asking it.
  const std::string name = array->GetName() ? array->GetName() : "";
  const std::string refused = checkAllocation(bytesOf(array, tuples),
    (name.empty() ? std::string("An output array") : "The array '" + name + "'") + " of " +
      std::to_string(tuples) + " tuples");
  if (!refused.empty())
    throw std::runtime_error(refused);
  resizeChecked(array, tuples);
}

void resizeOrThrow(const std::vector<vtkAbstractArray*>& arrays, vtkIdType tuples)
{
  double bytes = 0.0;
  for (vtkAbstractArray* array : arrays)
    bytes += bytesOf(array, tuples);
  const std::string refused = checkAllocation(bytes,
    std::to_string(arrays.size()) + " output arrays of " + std::to_string(tuples) + " tuples");
  if (!refused.empty())
    throw std::runtime_error(refused);
  for (vtkAbstractArray* array : arrays)
    resizeChecked(array, tuples);
}

void addDistributionFields(vtkFieldData* fd, const Piece& piece)
{
  if (!piece.distributed() || piece.rank != 0)
    return;
  addFieldValue(fd, "NumberOfRanks", piece.ranks);
  addFieldValue(
    fd, "BytesExchanged", static_cast<vtkIdType>(piece.bytesReceived + piece.bytesSent));
}

BitVolume inImageAxes(const BitVolume& voxels, const std::array<int, 3>& axes, Point3& offset)
{
  if (axes == std::array<int, 3>{ 0, 1, 2 })
    return voxels;
  Point3 dims, moved;
  for (int k = 0; k < 3; ++k)
  {
    dims[axes[k]] = voxels.size(k);
    moved[axes[k]] = offset[k];
  }
  offset = moved;
  BitVolume out(dims[0], dims[1], dims[2]);
  Point3 p, q;
  for (p[2] = 0; p[2] < voxels.size(2); ++p[2])
    for (p[1] = 0; p[1] < voxels.size(1); ++p[1])
      for (p[0] = 0; p[0] < voxels.size(0); ++p[0])
        if (voxels.get(p[0], p[1], p[2]))
        {
          for (int k = 0; k < 3; ++k)
            q[axes[k]] = p[k];
          out.set(q[0], q[1], q[2]);
        }
  return out;
}

void markVoxels(const BitVolume& voxels,
  const Point3& offset,
  const std::array<std::int32_t, 3>& dims,
  unsigned char* array)
{
  // A word of the bit rows at a time: a large box around a thin object is mostly empty words.
  const std::size_t words = voxels.wordsPerRow();
  const std::int32_t nx = voxels.size(0);
  for (std::int32_t z = 0; z < voxels.size(2); ++z)
    for (std::int32_t y = 0; y < voxels.size(1); ++y)
    {
      const Word* row = voxels.row(y, z);
      unsigned char* out =
        array + (vtkIdType(z + offset[2]) * dims[1] + y + offset[1]) * dims[0] + offset[0];
      for (std::size_t i = 0; i < words; ++i)
        for (Word w = row[i]; w; w &= w - 1)
        {
          const std::int32_t x = static_cast<std::int32_t>(64 * i) + countTrailingZeros(w);
          if (x < nx)
            out[x] = 1;
        }
    }
}

bool writeReversionImage(InputObjects& in,
  vtkUnsignedCharArray* selection,
  bool matches,
  vtkImageData* input,
  vtkImageData* output)
{
  output->Initialize();
  vtkSmartPointer<vtkUnsignedCharArray> values = selection;
  if (in.piece.distributed())
  {
    int status = matches ? 2 : 1; // 0: rank 0 has nothing to send
    values = vtkSmartPointer<vtkUnsignedCharArray>::New();
    if (!scatterSelection(in.piece, in.piece.rank == 0 ? selection : nullptr, status, values))
      return false;
    matches = status == 2;
  }
  if (!values)
    return false;
  values->SetName("Selection");
  output->CopyStructure(input);
  vtkDataSetAttributes* attributes = in.grid.cellData
    ? static_cast<vtkDataSetAttributes*>(output->GetCellData())
    : static_cast<vtkDataSetAttributes*>(output->GetPointData());
  attributes->SetScalars(values);
  // The piece's ghost marks stay, so that downstream filters do not count ghosts twice.
  const char* ghosts = vtkDataSetAttributes::GhostArrayName();
  if (vtkDataArray* marks = input->GetPointData()->GetArray(ghosts))
    output->GetPointData()->AddArray(marks);
  if (vtkDataArray* marks = input->GetCellData()->GetArray(ghosts))
    output->GetCellData()->AddArray(marks);
  vtkNew<vtkIntArray> flag;
  flag->SetName("ReversionMatches");
  flag->InsertNextValue(matches ? 1 : 0);
  output->GetFieldData()->AddArray(flag);
  return true;
}

void addFieldValue(vtkFieldData* fd, const char* name, vtkIdType value)
{
  vtkNew<vtkIdTypeArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

void reserveArrays(vtkFieldData* fd, int count)
{
  // Slots past the arrays are empty (AllocateArrays only unregisters arrays there).
  if (count > 0)
    fd->AllocateArrays(fd->GetNumberOfArrays() + count);
}

void addFieldValues(vtkFieldData* fd, std::initializer_list<FieldValue> values, int following)
{
  reserveArrays(fd, static_cast<int>(values.size()) + following);
  for (const FieldValue& v : values)
    addFieldValue(fd, v.name, v.value);
}

std::string readVoxels(vtkImageData* image,
  vtkDataArray*& scalars,
  int association,
  int& component,
  bool flatImagesAs2D,
  vtkSmartPointer<vtkDataArray>& contiguous,
  VoxelGrid& grid)
{
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    return "The input array must be point or cell data.";
  }
  const int components = scalars->GetNumberOfComponents();
  if (component < vtkVoxelSelection::MAGNITUDE || component > components)
  {
    std::ostringstream msg;
    msg << "ArrayComponent " << component << " is out of range: the array '"
        << (scalars->GetName() ? scalars->GetName() : "") << "' has " << components
        << " component(s) (0 to " << components - 1 << ", or " << vtkVoxelSelection::MAGNITUDE
        << " or " << components << " for the magnitude).";
    return msg.str();
  }
  if (component == vtkVoxelSelection::MAGNITUDE || component == components)
  {
    contiguous = tupleNorms(scalars);
    scalars = contiguous;
    component = 0;
  }
  else if (!scalars->HasStandardMemoryLayout())
  {
    // The kernels read raw values: other layouts (SOA, implicit arrays) are copied once.
    contiguous.TakeReference(vtkDataArray::CreateDataArray(scalars->GetDataType()));
    contiguous->DeepCopy(scalars);
    scalars = contiguous;
  }
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const std::string problem = describeVoxels(image, scalars, cellData, flatImagesAs2D, grid);
  return problem.empty() ? problem : "Cannot read the voxels: " + problem + ".";
}

namespace
{

/// What the filter asked for as its input array, and that the input lacks it.
std::string requestedArray(vtkAlgorithm* algorithm)
{
  vtkInformation* info = algorithm->GetInputArrayInformation(0);
  const int association = info && info->Has(vtkDataObject::FIELD_ASSOCIATION())
    ? info->Get(vtkDataObject::FIELD_ASSOCIATION())
    : vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS;
  const char* where = association == vtkDataObject::FIELD_ASSOCIATION_POINTS ? "point"
    : association == vtkDataObject::FIELD_ASSOCIATION_CELLS                  ? "cell"
                                                                             : "point or cell";
  std::ostringstream msg;
  if (info && info->Has(vtkDataObject::FIELD_NAME()))
    msg << "the input has no " << where << " array named '"
        << info->Get(vtkDataObject::FIELD_NAME()) << "'";
  else
    msg << "the input has no active " << where << " scalars";
  msg << " (set the input array to process)";
  return msg.str();
}

/// An error message when what the filter needs per voxel, plus the copy readVoxels makes of
/// the array (the norms for the magnitude, a contiguous copy of other layouts), cannot be
/// allocated; checked before that copy is made.
std::string refuseIfTooLarge(vtkDataArray* scalars, const SelectionSettings& settings)
{
  const double tuples = double(scalars->GetNumberOfTuples());
  const int nc = scalars->GetNumberOfComponents();
  const bool magnitude =
    settings.component == vtkVoxelSelection::MAGNITUDE || settings.component == nc;
  const double copy = magnitude          ? double(sizeof(double))
    : scalars->HasStandardMemoryLayout() ? 0.0
                                         : double(nc) * scalars->GetDataTypeSize();
  return checkAllocation(tuples * (settings.bytesPerVoxel + copy),
    "Processing " + std::to_string(static_cast<long long>(tuples)) + " voxels");
}

/// Warnings about selection settings that select nothing.
void warnAboutSettings(vtkAlgorithm* algorithm, const SelectionSettings& settings)
{
  if (settings.mode != vtkVoxelSelection::RANGE)
    return;
  if (std::isnan(settings.lower) || std::isnan(settings.upper))
    vtkWarningWithObjectMacro(algorithm,
      << "LowerThreshold (" << settings.lower << ") or UpperThreshold (" << settings.upper
      << ") is NaN: nothing is selected.");
  else if (settings.lower > settings.upper)
    vtkWarningWithObjectMacro(
      algorithm, << "LowerThreshold > UpperThreshold: nothing is selected.");
}

/// Warnings about a grid that works but is likely not what the user meant.
void warnAboutGrid(vtkAlgorithm* algorithm, vtkImageData* image, const VoxelGrid& grid)
{
  for (int d = 0; d < 3; ++d)
    if (grid.spacing[d] == 0.0 && d != grid.flatAxis)
      vtkWarningWithObjectMacro(algorithm,
        << "The spacing along axis " << d
        << " is 0: the output's geometry is flat along it (its topology is unchanged).");
  vtkUniformGrid* uniform = vtkUniformGrid::SafeDownCast(image);
  if (uniform && (uniform->HasAnyBlankPoints() || uniform->HasAnyBlankCells()))
    vtkWarningWithObjectMacro(algorithm,
      << "The input has blanked points or cells: blanking is ignored, blanked voxels are "
         "selected by their values like the others.");
}

} // namespace

namespace
{

/// A message when the grid has more voxels along an axis than `maximum` (0: no limit).
std::string axisTooLong(const VoxelGrid& grid, std::int32_t maximum)
{
  for (int d = 0; d < 3; ++d)
    if (maximum > 0 && grid.dims[d] > maximum)
    {
      std::ostringstream msg;
      msg << "The image has " << grid.dims[d] << " voxels along axis " << d << "; at most "
          << maximum << " are supported.";
      return msg.str();
    }
  return std::string();
}

/// Labels mode on a grey-value image extracts thousands of labels one by one: say so first.
void warnAboutManyLabels(vtkAlgorithm* algorithm, std::size_t labels)
{
  if (labels <= ManyLabels)
    return;
  vtkWarningWithObjectMacro(algorithm,
    << "Labels mode: the selected array has " << labels
    << " distinct labels, each extracted on its own; this can take very long. For a grey-value "
       "image use Selection Mode Range (a threshold) instead.");
}

/// The voxels of a scalar grid (in processing axes) the rank owns: all without MPI.
template<typename T>
ScalarGrid<T> owned(ScalarGrid<T> grid, const InputObjects& in)
{
  if (!in.piece.distributed())
    return grid;
  const Box box = ownedBox(in.piece, in.axes);
  for (int k = 0; k < 3; ++k)
  {
    grid.data += box.lo[k] * grid.stride[k];
    grid.dims[k] = box.hi[k] - box.lo[k];
  }
  return grid;
}

/// readInputObjects on this rank's piece alone (the whole image without MPI).
/// Reports `problem` as an error of the algorithm; true when there is none.
bool noProblem(vtkAlgorithm* algorithm, const std::string& problem)
{
  if (!problem.empty())
    vtkErrorWithObjectMacro(algorithm, << problem);
  return problem.empty();
}

bool readLocalObjects(vtkAlgorithm* algorithm,
  vtkImageData* image,
  vtkDataArray* scalars,
  int association,
  const SelectionSettings& settings,
  InputObjects& out)
{
  if (!scalars)
  {
    if (image->GetNumberOfPoints() == 0)
      return true; // an empty image has nothing to select
    return noProblem(
      algorithm, "No input scalars to select voxels from: " + requestedArray(algorithm) + ".");
  }
  warnAboutSettings(algorithm, settings);
  int component = settings.component;
  if (!noProblem(algorithm, refuseIfTooLarge(scalars, settings)) ||
    !noProblem(algorithm,
      readVoxels(
        image, scalars, association, component, settings.flatImagesAs2D, out.contiguous, out.grid)))
    return false;
  if (double(out.grid.dims[0]) * out.grid.dims[1] * out.grid.dims[2] == 0)
    return true;
  if (!noProblem(algorithm, axisTooLong(out.grid, settings.maximumVoxelsPerAxis)))
    return false;
  warnAboutGrid(algorithm, image, out.grid);
  if (out.piece.distributed())
  {
    out.grid.flatAxis = out.piece.whole.flatAxis; // a piece one voxel thick is no 2D image
    out.grid.vertexShift = out.piece.whole.vertexShift;
  }
  out.axes = processingAxes(out.grid);
  out.labelType = scalars->GetDataType();
  const bool known = dispatchScalars(scalars,
    component,
    out.grid,
    [&](auto scalarGrid)
    {
      out.objects = selectObjects(owned(permuted(scalarGrid, out.axes), out),
        settings.mode,
        settings.lower,
        settings.upper,
        settings.background);
    });
  if (!known)
    return noProblem(
      algorithm, std::string("Unsupported scalar type ") + scalars->GetDataTypeAsString() + ".");
  if (settings.mode == vtkVoxelSelection::LABELS)
    warnAboutManyLabels(algorithm, out.objects.size());
  return true;
}

} // namespace

bool readInputObjects(vtkAlgorithm* algorithm,
  vtkImageData* image,
  vtkDataArray* scalars,
  int association,
  const SelectionSettings& settings,
  InputObjects& out)
{
  out = InputObjects();
  const std::string problem =
    describePiece(settings.distributed ? distributedController(algorithm) : nullptr,
      algorithm->GetInputInformation(0, 0),
      image,
      association == vtkDataObject::FIELD_ASSOCIATION_CELLS,
      settings.flatImagesAs2D,
      out.piece);
  if (!problem.empty())
  {
    vtkErrorWithObjectMacro(algorithm, << "Cannot read the voxels: " << problem << ".");
    return false;
  }
  const bool ok = readLocalObjects(algorithm, image, scalars, association, settings, out);
  if (!out.piece.distributed())
    return ok;
  // Collective: every rank takes part, whatever its own status.
  if (!mergeObjectsOnFirstRank(ok, out.piece, out))
  {
    if (ok)
      vtkErrorWithObjectMacro(algorithm, << "Another rank could not read its piece.");
    return false;
  }
  return true;
}

int executeGuarded(vtkAlgorithm* algorithm,
  vtkInformationVector* outputVector,
  const char* what,
  const std::function<int()>& execute)
{
  try
  {
    return execute();
  }
  catch (const std::exception& e)
  {
    if (dynamic_cast<const std::bad_alloc*>(&e))
    {
      reclaimMemory(); // what is kept for reuse is wanted elsewhere now
      vtkErrorWithObjectMacro(algorithm,
        << what << " failed: out of memory (std::bad_alloc; "
        << formatBytes(double(availableMemoryBytes()))
        << " can still be allocated: available memory and ulimit -v).");
    }
    else
      vtkErrorWithObjectMacro(algorithm, << what << " failed: " << e.what());
    for (int port = 0; port < outputVector->GetNumberOfInformationObjects(); ++port)
      if (vtkDataObject* output =
            outputVector->GetInformationObject(port)->Get(vtkDataObject::DATA_OBJECT()))
        output->Initialize();
    return 0;
  }
}

namespace
{

void requestWholeExtent(vtkAlgorithm* algorithm, vtkInformationVector* input)
{
  vtkInformation* in = input->GetInformationObject(0);
  if (!in || distributedController(algorithm))
    return;
  if (in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()),
      6);
  }
}

void requestSamePieceOnEveryPort(vtkInformation* request, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  const int from = request && request->Has(vtkExecutive::FROM_OUTPUT_PORT())
    ? std::max(request->Get(vtkExecutive::FROM_OUTPUT_PORT()), 0)
    : 0;
  vtkInformation* asked = outputVector->GetInformationObject(from);
  if (!asked || !asked->Has(SDDP::UPDATE_NUMBER_OF_PIECES()))
    return;
  for (int port = 0; port < outputVector->GetNumberOfInformationObjects(); ++port)
  {
    vtkInformation* info = outputVector->GetInformationObject(port);
    if (port == from || !info)
      continue;
    info->Set(SDDP::UPDATE_PIECE_NUMBER(), asked->Get(SDDP::UPDATE_PIECE_NUMBER()));
    info->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), asked->Get(SDDP::UPDATE_NUMBER_OF_PIECES()));
    info->Set(
      SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), asked->Get(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS()));
  }
}

} // namespace

void requestWholeImage(vtkAlgorithm* algorithm,
  vtkInformation* request,
  vtkInformationVector* input,
  vtkInformationVector* outputVector)
{
  requestWholeExtent(algorithm, input);
  requestSamePieceOnEveryPort(request, outputVector);
}

void markGhostLevelsComplete(vtkInformationVector* outputVector, std::initializer_list<int> ports)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  int levels = 1;
  for (int port = 0; port < outputVector->GetNumberOfInformationObjects(); ++port)
    levels = std::max(
      levels, outputVector->GetInformationObject(port)->Get(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS()));
  for (int port : ports)
    if (vtkInformation* info = outputVector->GetInformationObject(port))
      if (vtkDataObject* data = info->Get(vtkDataObject::DATA_OBJECT()))
        data->GetInformation()->Set(vtkDataObject::DATA_NUMBER_OF_GHOST_LEVELS(), levels);
}

void removeImageInformation(vtkInformationVector* outputVector, int port)
{
  vtkInformation* info = outputVector->GetInformationObject(port);
  info->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  info->Remove(vtkDataObject::ORIGIN());
  info->Remove(vtkDataObject::SPACING());
}

SelectionSettings selectionSettingsOf(vtkVoxelSelection* selection)
{
  SelectionSettings s;
  s.mode = selection->GetMode();
  s.lower = selection->GetLowerThreshold();
  s.upper = selection->GetUpperThreshold();
  s.background = selection->GetBackgroundValue();
  s.component = selection->GetArrayComponent();
  return s;
}

namespace
{
template<typename T>
void normsOf(const T* values, int nc, vtkIdType n, double* norms)
{
  vtkSMPTools::For(vtkIdType(0),
    n,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType t = b; t < e; ++t)
      {
        double sum = 0.0;
        for (int c = 0; c < nc; ++c)
        {
          const double v = static_cast<double>(values[t * nc + c]);
          sum += v * v;
        }
        norms[t] = std::sqrt(sum);
      }
    });
}

/// splitmix64's finaliser: consecutive ids give unrelated values.
std::uint64_t mixBits(std::uint64_t x)
{
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}
} // namespace

vtkSmartPointer<vtkDataArray> tupleNorms(vtkDataArray* scalars)
{
  vtkSmartPointer<vtkDataArray> source = scalars;
  if (!scalars->HasStandardMemoryLayout())
  {
    source.TakeReference(vtkDataArray::CreateDataArray(scalars->GetDataType()));
    source->DeepCopy(scalars);
  }
  auto norms = vtkSmartPointer<vtkDoubleArray>::New();
  norms->SetName(scalars->GetName());
  const vtkIdType n = source->GetNumberOfTuples();
  resizeOrThrow(norms, n);
  const int nc = source->GetNumberOfComponents();
  void* raw = source->GetVoidPointer(0);
  switch (source->GetDataType())
  {
    vtkTemplateMacro(normsOf(static_cast<const VTK_TT*>(raw), nc, n, norms->GetPointer(0)));
    default:
      for (vtkIdType t = 0; t < n; ++t)
      {
        double sum = 0.0;
        for (int c = 0; c < nc; ++c)
          sum += source->GetComponent(t, c) * source->GetComponent(t, c);
        norms->SetValue(t, std::sqrt(sum));
      }
  }
  return norms;
}

vtkSmartPointer<vtkDataArray> newLabelArray(int dataType, vtkIdType n)
{
  vtkSmartPointer<vtkDataArray> labels;
  labels.TakeReference(vtkDataArray::CreateDataArray(dataType));
  labels->SetName("Label");
  resizeOrThrow(labels, n);
  if (n > 0)
    std::memset(
      labels->GetVoidPointer(0), 0, static_cast<std::size_t>(n) * labels->GetDataTypeSize());
  return labels;
}

void setLabel(vtkDataArray* labels, vtkIdType i, const LabelValue& label)
{
  switch (labels->GetDataType())
  {
    vtkTemplateMacro(static_cast<VTK_TT*>(labels->GetVoidPointer(0))[i] = label.as<VTK_TT>());
  }
}

void fillLabel(vtkDataArray* labels, vtkIdType first, vtkIdType end, const LabelValue& label)
{
  switch (labels->GetDataType())
  {
    vtkTemplateMacro(VTK_TT* values = static_cast<VTK_TT*>(labels->GetVoidPointer(0));
                     std::fill(values + first, values + end, label.as<VTK_TT>()));
  }
}

void appendLabel(vtkDataArray* labels, const LabelValue& label)
{
  const vtkIdType i = labels->GetNumberOfTuples();
  labels->InsertNextTuple1(0.0);
  setLabel(labels, i, label);
}

LabelValue labelAt(vtkDataArray* labels, vtkIdType i)
{
  switch (labels->GetDataType())
  {
    vtkTemplateMacro(return LabelValue::of(
      static_cast<const VTK_TT*>(labels->GetVoidPointer(0))[i * labels->GetNumberOfComponents()]));
  }
  return LabelValue::of(labels->GetComponent(i, 0));
}

void setBoundaryColoring(vtkPolyData* output, bool labelsMode)
{
  vtkCellData* cd = output->GetCellData();
  vtkDataArray* faceIds = cd->GetArray("FaceId");
  if (!faceIds)
    return;
  const vtkIdType n = faceIds->GetNumberOfTuples();
  vtkNew<vtkFloatArray> colors;
  colors->SetName("FaceColor");
  resizeOrThrow(colors, n);
  float* out = colors->GetPointer(0);
  vbr::adviseHugePages(out, static_cast<std::size_t>(n) * sizeof(float)); // written once, now
  // The filters' own ids are read in place, not through GetComponent's virtual call.
  vtkIdTypeArray* typed = vtkIdTypeArray::FastDownCast(faceIds);
  const vtkIdType* inPlace =
    typed && typed->GetNumberOfComponents() == 1 ? typed->GetPointer(0) : nullptr;
  for (vtkIdType c = 0; c < n; ++c)
  {
    // 24 bits of the hash: exact in a float, in [0, 1).
    const auto id =
      inPlace ? std::int64_t(inPlace[c]) : static_cast<std::int64_t>(faceIds->GetComponent(c, 0));
    out[c] = static_cast<float>(mixBits(static_cast<std::uint64_t>(id)) >> 40) / 16777216.0f;
  }
  cd->AddArray(colors);
  cd->SetActiveScalars(labelsMode && cd->GetArray("Label") ? "Label" : "FaceColor");
}

} // namespace vtk
} // namespace vbr
