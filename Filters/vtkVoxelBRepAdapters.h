// Shared adaptation of VTK data to the VTK-free core: where the voxels of an image are, how
// grid vertices map to world coordinates, and vtkSMPTools as the core's parallel loop.
// Private to the module (not wrapped, not installed).
#ifndef vtkVoxelBRepAdapters_h
#define vtkVoxelBRepAdapters_h

#include "Execution.h"
#include "Selection.h"

#include "vtkVoxelSelection.h"

#include "vtkDataArray.h"
#include "vtkIndent.h"
#include "vtkIntArray.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

class vtkAlgorithm;
class vtkFieldData;
class vtkImageData;
class vtkInformation;
class vtkInformationVector;
class vtkMultiProcessController;
class vtkPolyData;
class vtkUnsignedCharArray;

namespace vbr
{
namespace vtk
{

/// vtkSMPTools as parallel loop; progress goes to the algorithm, whose abort flag stops work.
Execution makeExecution(vtkAlgorithm* algorithm, double progressFrom, double progressTo);

/// The voxel grid an image's scalars describe.
struct VoxelGrid
{
  bool cellData = false;
  std::array<std::int32_t, 3> dims{ 0, 0, 0 };  ///< voxels along each axis
  std::array<int, 3> extentMin{ 0, 0, 0 };      ///< index of the first point
  std::array<double, 3> vertexShift{ 0, 0, 0 }; ///< index of grid vertex 0 minus extentMin
  std::array<double, 3> origin{ 0, 0, 0 };
  std::array<double, 3> spacing{ 1, 1, 1 };
  std::array<double, 9> direction{ 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  int flatAxis = -1; ///< the axis with a single voxel when the image is 2D, else -1

  /// World position of grid vertex (i, j, k) (voxel i spans vertices i and i + 1).
  void vertexToWorld(const std::array<std::int32_t, 3>& v, double world[3]) const;
  /// The same for a position in continuous vertex coordinates (voxel centres at i + 0.5).
  void positionToWorld(const double v[3], double world[3]) const;
  /// The determinant of the direction matrix.
  double directionDeterminant() const;
  /// Whether index-to-world coordinates mirror space (a direction matrix of negative
  /// determinant, or an odd number of negative spacings): cells are then reversed so that
  /// normals still point out of the object.
  bool mirrorsSpace() const;
  /// The voxel whose cell of the grid contains a world position; false when outside.
  bool worldToVoxel(const double world[3], std::array<std::int32_t, 3>& voxel) const;
};

/// Describes the voxels of `image` carried by `scalars` (point or cell data). Returns an
/// empty string on success, else a message for vtkErrorMacro.
std::string describeVoxels(vtkImageData* image,
  vtkDataArray* scalars,
  bool cellData,
  bool flatImagesAs2D,
  VoxelGrid& grid);

/// Origin, spacing and direction matrix of the image into `grid`.
void readGeometry(vtkImageData* image, VoxelGrid& grid);

/// The voxels along each axis, the first point, the vertex shifts and the flat axis of an
/// extent (the rest of `grid` is kept). Returns a problem, or an empty string; an extent
/// without points gives dims 0.
std::string describeExtent(const int extent[6],
  bool cellData,
  bool flatImagesAs2D,
  VoxelGrid& grid);

/// An error message when the grid's spacing or origin is not finite or its direction matrix
/// is singular (the output would hold NaN geometry); else an empty string.
std::string geometryProblem(const VoxelGrid& grid);

/// Checks the input array of a filter and describes its voxels: point or cell data, the
/// component in range, tuples matching the image. Arrays not stored as contiguous tuples
/// (SOA, implicit arrays) are copied once into `contiguous`, and `scalars` then points to
/// the copy; for the magnitude (vtkVoxelSelection::MAGNITUDE, or the number of components) the copy
/// is the norms of the tuples and `component` becomes 0. Returns an error message, or an empty
/// string.
std::string readVoxels(vtkImageData* image,
  vtkDataArray*& scalars,
  int association,
  int& component,
  bool flatImagesAs2D,
  vtkSmartPointer<vtkDataArray>& contiguous,
  VoxelGrid& grid);

/// A vtkIntArray of n zeros. On Linux, large ones are mapped straight from the kernel, whose
/// pages are zero already (no pass over the memory), 64 bytes into a huge page and marked for
/// transparent huge pages: writing a label image is otherwise dominated by first-touch page faults
/// (one per 1024 values; about 170 ms for 256^3 labels here, 5 to 100 ms with huge pages).
vtkSmartPointer<vtkIntArray> newZeroedIntArray(vtkIdType n);

/// Sets the number of tuples of `array`, throwing when they cannot be allocated: first
/// against availableMemoryBytes() (ParaView's VTK aborts the process when an allocation
/// fails), then std::bad_alloc if VTK still came back short. executeGuarded turns the
/// exception into an error and empty outputs.
void resizeOrThrow(vtkAbstractArray* array, vtkIdType tuples);
/// The same for several arrays of `tuples` tuples each, with one memory check for all of
/// them: each check reads /proc/meminfo, which cost more than a small table of 17 columns.
void resizeOrThrow(const std::vector<vtkAbstractArray*>& arrays, vtkIdType tuples);

/// Appends a one-value field array.
void addFieldValue(vtkFieldData* fd, const char* name, vtkIdType value);

/// Makes room in `fd` for `count` more arrays at once, so that the next `count` AddArray
/// calls add to it without growing it: vtkFieldData::AddArray otherwise grows its tables (and
/// their range caches) by one array per call, reallocating them each time, which made the
/// few dozen small arrays of a small image's outputs a good part of an update's fixed cost.
/// Nothing of the field's content changes.
void reserveArrays(vtkFieldData* fd, int count);

/// A one-value field array to append (see addFieldValues).
struct FieldValue
{
  const char* name;
  vtkIdType value;
};

/// Appends one-value field arrays, in order (addFieldValue for each), after one reserveArrays
/// for them and the `following` arrays the caller appends next.
void addFieldValues(vtkFieldData* fd, std::initializer_list<FieldValue> values, int following);

/// A label exactly as the selected values' type holds it (int64 labels above 2^53 stay
/// exact, unlike through a double): the value's bytes, read back in that type. The type is
/// the data type of the Label arrays (see newLabelArray).
struct LabelValue
{
  std::uint64_t bits = 0;

  template<typename T>
  static LabelValue of(T value)
  {
    static_assert(sizeof(T) <= sizeof(std::uint64_t), "labels are at most 64 bits");
    LabelValue label;
    std::memcpy(&label.bits, &value, sizeof value);
    return label;
  }
  template<typename T>
  T as() const
  {
    T value;
    std::memcpy(&value, &this->bits, sizeof value);
    return value;
  }
  /// An order by the bits, not by value (maps of labels need one; -0.0 and 0.0 differ).
  bool operator<(const LabelValue& other) const { return this->bits < other.bits; }
  bool operator==(const LabelValue& other) const { return this->bits == other.bits; }
};

/// A `Label` array of n values of `dataType` (the selected values' type, so that every
/// label is exact), zeros.
vtkSmartPointer<vtkDataArray> newLabelArray(int dataType, vtkIdType n = 0);
/// Writes value i of a Label array (of the type the label was made in).
void setLabel(vtkDataArray* labels, vtkIdType i, const LabelValue& label);
/// Writes values [first, end) of a Label array, all `label`.
void fillLabel(vtkDataArray* labels, vtkIdType first, vtkIdType end, const LabelValue& label);
/// Appends a value to a Label array.
void appendLabel(vtkDataArray* labels, const LabelValue& label);
/// Value i of an array as a label of its type (what reading a Label array back gives).
LabelValue labelAt(vtkDataArray* labels, vtkIdType i);

/// One selected object: a label (or the whole selection) and its voxels in a box.
struct Selected
{
  LabelValue label;
  std::array<std::int32_t, 3> offset{ 0, 0, 0 }; ///< box origin, in permuted axes
  /// Builds the object's voxels in its box when it is processed, so that only one object's
  /// voxels are in memory at a time.
  std::function<BitVolume(const Execution&)> select;
};

/// Whether `v` is a value of T, exactly (no rounding, no out-of-range conversion); the value
/// in `out` then. NaN is no value of any type.
template<typename T>
bool exactlyRepresentable(double v, T& out)
{
  if constexpr (std::is_integral<T>::value)
  {
    // max + 1 is a power of two, exact in double even for 64 bits (max itself is not).
    const double aboveMax = 2.0 * static_cast<double>(std::numeric_limits<T>::max() / 2 + 1);
    if (!(v >= static_cast<double>(std::numeric_limits<T>::lowest()) && v < aboveMax) ||
      v != std::floor(v))
      return false;
    out = static_cast<T>(v);
    return true;
  }
  else
  {
    if (std::isnan(v))
      return false;
    if (!std::isinf(v) && std::abs(v) > static_cast<double>(std::numeric_limits<T>::max()))
      return false;          // beyond the largest float: the conversion would be undefined
    out = static_cast<T>(v); // infinities are values of the floating-point types
    return static_cast<double>(out) == v;
  }
}

/// The integer values of T in [lower, upper], compared exactly with the doubles (2^63 is
/// above every int64, 2^64 above every uint64); false when there is none.
template<typename T>
bool integerRange(double lower, double upper, T& first, T& last)
{
  const double lo = std::ceil(lower), hi = std::floor(upper);                   // NaN stays NaN
  const double typeMin = static_cast<double>(std::numeric_limits<T>::lowest()); // exact
  const double aboveMax = 2.0 * static_cast<double>(std::numeric_limits<T>::max() / 2 + 1);
  if (!(lo <= hi) || !(hi >= typeMin) || !(lo < aboveMax))
    return false;
  // lo < max + 1 and hi >= min, both integers: the conversions below are exact.
  first = lo <= typeMin ? std::numeric_limits<T>::lowest() : static_cast<T>(lo);
  last = hi >= aboveMax ? std::numeric_limits<T>::max() : static_cast<T>(hi);
  return true;
}

/// The objects to extract, from scalars already permuted into processing axes: one per
/// label, or a single one. The scalars must outlive the objects' `select`.
template<typename T>
std::vector<Selected> selectObjects(const ScalarGrid<T>& grid,
  int mode,
  double lower,
  double upper,
  double background)
{
  std::vector<Selected> out;
  auto add = [&out, &grid](T label, const Box& box, auto selected)
  {
    Selected s;
    s.label = LabelValue::of(label);
    s.offset = box.lo;
    s.select = [grid, box, selected](const Execution& exec)
    { return selectVoxels(grid, box, selected, exec.forWork(box.volume())); };
    out.push_back(std::move(s));
  };
  Box whole;
  whole.hi = grid.dims;
  if (mode == vtkVoxelSelection::LABELS)
  {
    // A background the type cannot hold exactly means every value is a label.
    T typedBackground{};
    const bool hasBackground = exactlyRepresentable(background, typedBackground);
    for (const auto& entry :
      labelBoxes(grid, hasBackground ? &typedBackground : static_cast<const T*>(nullptr)))
    {
      const T label = entry.first;
      add(label, entry.second, [label](T v) { return v == label; });
    }
  }
  else if (mode == vtkVoxelSelection::POSITIVE)
  {
    add(T(1), whole, [](T v) { return v > T(0); });
  }
  else if constexpr (std::is_integral<T>::value)
  {
    // Integer values: the range in the type itself (a comparison the compiler vectorizes).
    T first{}, last{};
    if (integerRange(lower, upper, first, last))
      add(T(1), whole, [first, last](T v) { return v >= first && v <= last; });
    else
      add(T(1), whole, [](T) { return false; });
  }
  else
  {
    add(T(1),
      whole,
      [lower, upper](T v)
      {
        const double d = static_cast<double>(v);
        return d >= lower && d <= upper;
      });
  }
  return out;
}

/// The axes in processing order: a 2D image is processed in its own plane, flat axis last.
inline std::array<int, 3> processingAxes(const VoxelGrid& grid)
{
  std::array<int, 3> axes{ 0, 1, 2 };
  if (grid.flatAxis >= 0)
  {
    int k = 0;
    for (int d = 0; d < 3; ++d)
      if (d != grid.flatAxis)
        axes[k++] = d;
    axes[2] = grid.flatAxis;
  }
  return axes;
}
/// A scalar grid seen in processing axes: axis k of the result is axis axes[k] of `grid`.
template<typename T>
ScalarGrid<T> permuted(const ScalarGrid<T>& grid, const std::array<int, 3>& axes)
{
  ScalarGrid<T> out = grid;
  for (int k = 0; k < 3; ++k)
  {
    out.dims[k] = grid.dims[axes[k]];
    out.stride[k] = grid.stride[axes[k]];
  }
  return out;
}

template<typename T, typename F>
void callWithGrid(void* raw, int nc, int component, const VoxelGrid& grid, F& f)
{
  ScalarGrid<T> sg;
  sg.data = static_cast<const T*>(raw) + component;
  sg.dims = grid.dims;
  sg.stride = {
    nc, std::int64_t(nc) * grid.dims[0], std::int64_t(nc) * grid.dims[0] * grid.dims[1]
  };
  f(sg);
}

/// Calls f(ScalarGrid<T>) with the typed component `component` of `scalars`; false if the
/// array type is not a plain numeric array.
template<typename F>
bool dispatchScalars(vtkDataArray* scalars, int component, const VoxelGrid& grid, F&& f)
{
  const int nc = scalars->GetNumberOfComponents();
  void* raw = scalars->GetVoidPointer(0);
  switch (scalars->GetDataType())
  {
    vtkTemplateMacro(callWithGrid<VTK_TT>(raw, nc, component, grid, f));
    default:
      return false;
  }
  return true;
}

/// Labels mode warns before the work when the selection has more distinct labels than this
/// (each label is extracted on its own: a grey-value volume in Labels mode runs for minutes).
constexpr std::size_t ManyLabels = 1000;

/// The selection properties the filters share.
struct SelectionSettings
{
  int mode = vtkVoxelSelection::POSITIVE;
  double lower = 1.0;
  double upper = VTK_DOUBLE_MAX;
  double background = 0.0;
  int component = 0;
  bool flatImagesAs2D = true;
  std::int32_t maximumVoxelsPerAxis = 0; ///< 0: no limit
  /// What the filter allocates per voxel of the image whatever its output (the selection's
  /// bit volume, a label image, ...): checked against the memory the process can allocate
  /// before any work (readInputObjects refuses an image that cannot fit).
  double bytesPerVoxel = 1.0 / 8.0;
  /// Under MPI, gather the objects of all ranks' pieces on rank 0 (see
  /// vtkVoxelBRepDistributed.h); off, each rank reads its own input alone.
  bool distributed = false;
};

/// The values of a selection.
SelectionSettings selectionSettingsOf(vtkVoxelSelection* selection);
/// The values of a filter's selection (see vtkVoxelSelectionMacro).
template<typename Filter>
SelectionSettings selectionSettingsOf(Filter* filter)
{
  return selectionSettingsOf(filter->GetSelection());
}

/// A rank's piece of a distributed image.
struct Piece
{
  vtkMultiProcessController* controller = nullptr; ///< null when not distributed
  int rank = 0;
  int ranks = 1;
  VoxelGrid whole;                              ///< the whole image's voxel grid
  int wholeExtent[6] = { 0, -1, 0, -1, 0, -1 }; ///< the whole image's extent
  VoxelGrid local;                       ///< the voxels of this rank's piece (ghosts included)
  std::array<std::int32_t, 3> offset{};  ///< whole-grid voxel of the piece's voxel 0
  std::array<std::int32_t, 3> ownedLo{}; ///< owned voxels [ownedLo, ownedHi), piece voxels
  std::array<std::int32_t, 3> ownedHi{};
  bool partitioned = true;        ///< whether the owned voxels of all ranks partition the image
  std::int64_t bytesSent = 0;     ///< by this rank, in the exchanges so far
  std::int64_t bytesReceived = 0; ///< by this rank, in the exchanges so far

  bool distributed() const { return this->controller != nullptr; }
};

/// Under MPI, on rank 0: field data NumberOfRanks and BytesExchanged (what the ranks sent
/// each other for this result). No-op otherwise.
void addDistributionFields(vtkFieldData* fd, const Piece& piece);

/// The objects of a filter's input image, ready to process.
struct InputObjects
{
  VoxelGrid grid;
  std::array<int, 3> axes{ 0, 1, 2 }; ///< processing axes (see processingAxes)
  std::vector<Selected> objects;
  /// Data type of the selected values and of the Label arrays: the input array's, or double
  /// for the magnitude.
  int labelType = VTK_DOUBLE;
  vtkSmartPointer<vtkDataArray> contiguous; ///< keeps a copied input array alive for objects
  /// The rank's piece under MPI (see vtkVoxelBRepDistributed.h): then on rank 0 `grid` and
  /// `objects` are the whole image's, and the other ranks have no objects.
  Piece piece;
};

/// Reads the objects of `image` carried by `scalars` (the filter's input array, possibly
/// null), reporting errors and warnings on `algorithm`. Returns false after an error; an
/// image without points or voxels gives no objects and true.
bool readInputObjects(vtkAlgorithm* algorithm,
  vtkImageData* image,
  vtkDataArray* scalars,
  int association,
  const SelectionSettings& settings,
  InputObjects& out);

/// The voxels of an object in the image's own axes: the selection hands the voxels over in
/// its processing axes (see processingAxes: a flat image's flat axis last), the faces and the
/// reversion are in the image's. `offset` (the object's box in the grid) is moved with them.
BitVolume inImageAxes(const BitVolume& voxels, const std::array<int, 3>& axes, Point3& offset);

/// Sets to 1 the values of `array` (one per voxel of a grid of `dims`, x fastest: the order of
/// the image's point or cell tuples) at the voxels of an object whose box starts at `offset`.
void markVoxels(const BitVolume& voxels,
  const Point3& offset,
  const std::array<std::int32_t, 3>& dims,
  unsigned char* array);

/// Port 1 of the filters that rebuild the voxels from their own output alone: `output` takes
/// the layout of `input` with the scalars `Selection` (1 at the rebuilt voxels; cell or point
/// data as the input's voxels) and the field value ReversionMatches (`matches`). `selection`
/// has one value per voxel of `in.grid`. Under MPI this is collective: rank 0 passes the
/// whole image's selection (null when it failed or was aborted), the other ranks null, and
/// every rank writes its own piece (see scatterSelection). Returns false, with `output`
/// empty, when there is nothing to write.
bool writeReversionImage(InputObjects& in,
  vtkUnsignedCharArray* selection,
  bool matches,
  vtkImageData* input,
  vtkImageData* output);

/// RequestUpdateExtent of the filters whose results (faces, components) are global: asks the
/// input for its whole extent, whatever piece the output is asked for. Under MPI, when
/// ParaView runs `algorithm` on every rank (see distributedController), the piece request
/// stays: each rank reads its own piece and the filter gathers what it needs. And every output
/// port is asked for the piece asked of the one `request` comes from (FROM_OUTPUT_PORT), so
/// that one execution serves them all: else ParaView updates port 0 for piece r of N, the
/// other ports are marked as made for piece 0 of 1, and their update executes the filter a
/// second time.
void requestWholeImage(vtkAlgorithm* algorithm,
  vtkInformation* request,
  vtkInformationVector* input,
  vtkInformationVector* outputVector);
/// Marks the data of output `ports` as having every ghost level asked of any output port, and
/// at least one: for outputs that hold a global result (whole on rank 0 under MPI, absent
/// elsewhere), so that a ghost request alone does not execute the filter again.
void markGhostLevelsComplete(vtkInformationVector* outputVector, std::initializer_list<int> ports);
/// Removes the extent, origin and spacing the executive copies from an image input to output
/// `port`, whose data is not an image.
void removeImageInformation(vtkInformationVector* outputVector, int port);

/// Runs a filter's execution. An exception (out of memory, an inconsistency the core
/// detected) becomes an error "<what> failed: ..." and empties every output: never a crash.
int executeGuarded(vtkAlgorithm* algorithm,
  vtkInformationVector* outputVector,
  const char* what,
  const std::function<int()>& execute);

/// The Euclidean norm of every tuple, sqrt(v0^2 + v1^2 + ...) in double, as a one-component
/// double array: the values Magnitude selects on.
vtkSmartPointer<vtkDataArray> tupleNorms(vtkDataArray* scalars);

/// How ParaView colours a boundary: the cell array `FaceColor`, a hash of `FaceId` spread
/// over [0, 1) (neighbouring faces get unrelated values whatever the colour map, and every
/// output has the same range, so a shared map needs no rescale), and the active cell scalars:
/// `Label` in Labels mode, else `FaceColor`. No-op without a FaceId array.
void setBoundaryColoring(vtkPolyData* output, bool labelsMode);

} // namespace vtk
} // namespace vbr

#endif
