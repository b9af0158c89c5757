// Output arrays that grow while a filter writes its cells and that VTK then takes over without
// a copy: the cells of a boundary are known one face at a time, so their arrays cannot be
// sized beforehand, and a growing std::vector copied into VTK at the end would hold them twice.
#ifndef vtkVoxelBRepBuffers_h
#define vtkVoxelBRepBuffers_h

#include "vtkAbstractArray.h"
#include "vtkCellArray.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkVoxelBRepMemory.h"

#include "Core/HugePages.h" // by its path: not every includer sees Filters/Core

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace vbr
{
namespace vtk
{

/// An append-only array that VTK takes over without a copy. Small, it is malloc'ed
/// (VTK_DATA_ARRAY_FREE) and grows by realloc; from HugePageMinimum bytes on, it is a mapping
/// of its own in huge pages (mapHugeBlock; VTK frees it by unmapHugeBlock), which grows by
/// remapping its pages rather than copying them: malloc keeps blocks up to 32 MiB in its heap,
/// where realloc copies, and each 4 KiB page would be a page fault.
template<typename T>
class MallocBuffer
{
public:
  MallocBuffer() = default;
  MallocBuffer(const MallocBuffer&) = delete;
  MallocBuffer& operator=(const MallocBuffer&) = delete;
  ~MallocBuffer() { this->release(); }

  std::size_t size() const { return this->Size; }
  const T* data() const { return this->Data; }
  void push_back(T value)
  {
    if (this->Size == this->Capacity)
      this->reserve(std::max<std::size_t>(1024, 2 * this->Capacity));
    this->Data[this->Size++] = value;
  }
  /// Grows the array by n values, left for the caller to write (room grows by doubling).
  T* extend(std::size_t n)
  {
    if (this->Size + n > this->Capacity)
      this->reserve(std::max<std::size_t>({ 1024, 2 * this->Capacity, this->Size + n }));
    this->Size += n;
    return this->Data + this->Size - n;
  }
  void reserve(std::size_t capacity)
  {
    if (capacity <= this->Capacity)
      return;
    const std::size_t bytes = capacity * sizeof(T);
    void* grown = this->Mapped ? vbr::remapHugeBlock(this->Data, bytes) : nullptr;
    if (!this->Mapped && bytes >= vbr::HugePageMinimum && (grown = vbr::mapHugeBlock(bytes)))
    {
      std::copy(this->Data, this->Data + this->Size, static_cast<T*>(grown));
      std::free(this->Data);
      this->Mapped = true;
    }
    if (!this->Mapped && !grown)
      grown = std::realloc(this->Data, bytes);
    if (!grown)
      throw std::bad_alloc();
    this->Data = static_cast<T*>(grown);
    // A mapping is whole huge pages: its slack is room too (the next doubling comes later).
    this->Capacity = this->Mapped
      ? (vbr::hugeblock::mappingLength(bytes) - vbr::hugeblock::Header) / sizeof(T)
      : capacity;
  }
  /// Empties the buffer and keeps its memory for the next values.
  void clearKeepingMemory() { this->Size = 0; }
  /// Empties the buffer and frees its memory.
  void clear()
  {
    this->release();
    this->Data = nullptr;
    this->Size = this->Capacity = 0;
    this->Mapped = false;
  }
  /// Hands the values to `array`, which frees them; the buffer is then empty.
  template<typename ArrayType>
  void handTo(ArrayType* array)
  {
    static_assert(std::is_same<typename ArrayType::ValueType, T>::value, "no conversion");
    if (this->Size == 0)
      return;
    const vtkIdType n = static_cast<vtkIdType>(this->Size);
    if (this->Mapped)
    {
      void* fitted = vbr::remapHugeBlock(this->Data, this->Size * sizeof(T)); // in place
      array->SetArray(static_cast<T*>(fitted ? fitted : this->Data),
        n,
        0,
        vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
      array->SetArrayFreeFunction(vbr::unmapHugeBlock);
    }
    else
    {
      T* data = static_cast<T*>(std::realloc(this->Data, this->Size * sizeof(T))); // the slack
      array->SetArray(data ? data : this->Data, n, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
    }
    this->Data = nullptr;
    this->Size = this->Capacity = 0;
    this->Mapped = false;
  }

private:
  void release()
  {
    if (this->Mapped)
      vbr::unmapHugeBlock(this->Data);
    else
      std::free(this->Data);
  }

  T* Data = nullptr;
  std::size_t Size = 0, Capacity = 0;
  bool Mapped = false; ///< Data is a block of mapHugeBlock, not of malloc
};

/// The offsets and connectivity of a vtkCellArray, written a cell or a face's cells at a time
/// (addCells), in 32-bit integers while every value fits (vtkCellArray's 32-bit storage, which
/// VTK's filters, writers and mappers read through the cell array's interface like the 64-bit one;
/// code that takes the connectivity array for a vtkIdTypeArray does not) and widened to 64 bits the
/// first time one does not. The ids are most of a large boundary's memory: a triangle's offset and
/// three corners take 16 bytes instead of 32. Ids are never negative.
class CellArrayBuffer
{
public:
  /// `narrowLimit`: the largest value kept in 32 bits (a smaller one lets a test widen).
  explicit CellArrayBuffer(std::int64_t narrowLimit = std::numeric_limits<std::int32_t>::max())
    : NarrowLimit(std::min<std::int64_t>(narrowLimit, std::numeric_limits<std::int32_t>::max()))
  {
    this->Narrow.Offsets.push_back(0);
  }

  bool isWide() const { return this->Wide; }
  std::size_t numberOfCells() const
  {
    return (this->Wide ? this->Large.Offsets.size() : this->Narrow.Offsets.size()) - 1;
  }
  std::size_t connectivitySize() const
  {
    return this->Wide ? this->Large.Connectivity.size() : this->Narrow.Connectivity.size();
  }

  /// Appends one cell of `n` point ids, in reverse order when `reverse`.
  template<typename Id>
  void addCell(const Id* ids, std::size_t n, bool reverse = false)
  {
    const std::int64_t end = static_cast<std::int64_t>(this->connectivitySize() + n);
    if (!this->Wide && (end > this->NarrowLimit || !this->fitNarrow(ids, n)))
      this->widen();
    if (this->Wide)
      this->Large.append(ids, n, reverse);
    else
      this->Narrow.append(ids, n, reverse);
  }

  /// Appends `count` cells whose point ids follow one another from `ids`: cell k has the ids
  /// from ends[k - 1] - first to ends[k] - first (ends[-1] = first), each cell reversed when
  /// `reverse`. The same arrays as addCell cell after cell: the 32 bits are given up for all
  /// the cells at once when one of them would give them up.
  template<typename Id, typename End>
  void addCells(const Id* ids, const End* ends, std::size_t count, std::size_t first, bool reverse)
  {
    this->addCellsAt([ids](std::size_t j) { return ids[j]; }, ends, count, first, reverse);
  }

  /// addCells with the id at j given as `map[corners[first + j]]` (a face's cells as
  /// indices into its loops' corners, `map` their point ids): the ids are read where they
  /// are, not copied to a buffer first.
  template<typename Corner, typename Id, typename End>
  void addMappedCells(const Corner* corners,
    const Id* map,
    const End* ends,
    std::size_t count,
    std::size_t first,
    bool reverse)
  {
    const Corner* from = corners + first;
    this->addCellsAt(
      [from, map](std::size_t j) { return map[from[j]]; }, ends, count, first, reverse);
  }

  /// Appends the cells of `other` after these: the same arrays (and the same 32- or 64-bit
  /// choice) as adding its cells here one after the other, as it got them.
  void append(const CellArrayBuffer& other)
  {
    const std::int64_t end =
      static_cast<std::int64_t>(this->connectivitySize() + other.connectivitySize());
    if (!this->Wide && (end > this->NarrowLimit || !other.fitsIn(this->NarrowLimit)))
      this->widen();
    if (other.Wide)
      this->appendIds(other.Large);
    else
      this->appendIds(other.Narrow);
  }

  /// Empties the buffer (back to 32 bits) and keeps its memory for the next cells.
  void clearKeepingMemory()
  {
    this->Narrow.Offsets.clearKeepingMemory();
    this->Narrow.Connectivity.clearKeepingMemory();
    this->Large.Offsets.clearKeepingMemory();
    this->Large.Connectivity.clearKeepingMemory();
    this->Narrow.Offsets.push_back(0);
    this->Wide = false;
  }

  /// Hands the cells to a new vtkCellArray (32- or 64-bit storage); the buffer is then empty.
  vtkSmartPointer<vtkCellArray> release()
  {
    auto cells = vtkSmartPointer<vtkCellArray>::New();
    if (this->Wide)
      this->Large.handTo<vtkTypeInt64Array>(cells);
    else
      this->Narrow.handTo<vtkTypeInt32Array>(cells);
    this->Narrow.Offsets.push_back(0);
    this->Wide = false;
    return cells;
  }

private:
  /// addCells with the id at j (from 0) given by at(j).
  template<typename At, typename End>
  void addCellsAt(At at, const End* ends, std::size_t count, std::size_t first, bool reverse)
  {
    if (count == 0)
      return;
    const std::size_t total = static_cast<std::size_t>(ends[count - 1]) - first;
    const std::int64_t end = static_cast<std::int64_t>(this->connectivitySize() + total);
    if (!this->Wide && (end > this->NarrowLimit || !this->fitNarrowAt(at, total)))
      this->widen();
    if (this->Wide)
      this->Large.appendCells(at, ends, count, first, reverse);
    else
      this->Narrow.appendCells(at, ends, count, first, reverse);
  }

  template<typename T>
  struct Ids
  {
    MallocBuffer<T> Offsets, Connectivity;

    template<typename Id>
    void append(const Id* ids, std::size_t n, bool reverse)
    {
      T* out = this->Connectivity.extend(n);
      for (std::size_t i = 0; i < n; ++i) // cells are small: no call to memmove
        out[i] = static_cast<T>(ids[reverse ? n - 1 - i : i]);
      this->Offsets.push_back(static_cast<T>(this->Connectivity.size()));
    }
    template<typename At, typename End>
    void appendCells(At ids, const End* ends, std::size_t count, std::size_t first, bool reverse)
    {
      const std::size_t total = static_cast<std::size_t>(ends[count - 1]) - first;
      const std::size_t base = this->Connectivity.size();
      T* out = this->Connectivity.extend(total);
      T* offsets = this->Offsets.extend(count);
      if (!reverse)
      {
        // The cells' ids follow one another as given: one loop over them all, not one per cell
        // of three or four ids (a triangle's inner loop cost more than its copy).
        for (std::size_t j = 0; j < total; ++j)
          out[j] = static_cast<T>(ids(j));
        for (std::size_t k = 0; k < count; ++k)
          offsets[k] = static_cast<T>(base + (static_cast<std::size_t>(ends[k]) - first));
        return;
      }
      std::size_t from = 0;
      for (std::size_t k = 0; k < count; ++k)
      {
        const std::size_t to = static_cast<std::size_t>(ends[k]) - first;
        const std::size_t n = to - from;
        for (std::size_t i = 0; i < n; ++i)
          out[from + i] = static_cast<T>(ids(from + (reverse ? n - 1 - i : i)));
        offsets[k] = static_cast<T>(base + to);
        from = to;
      }
    }
    /// Appends all the cells of `from`, whose offsets start at 0.
    template<typename U>
    void appendAll(const Ids<U>& from)
    {
      const std::size_t base = this->Connectivity.size();
      const std::size_t n = from.Connectivity.size(), count = from.Offsets.size() - 1;
      std::copy(
        from.Connectivity.data(), from.Connectivity.data() + n, this->Connectivity.extend(n));
      const U* offsets = from.Offsets.data() + 1;
      T* out = this->Offsets.extend(count);
      for (std::size_t k = 0; k < count; ++k)
        out[k] = static_cast<T>(base + static_cast<std::size_t>(offsets[k]));
    }
    template<typename ArrayType>
    void handTo(vtkCellArray* cells)
    {
      vtkSmartPointer<ArrayType> offsets = vtkSmartPointer<ArrayType>::New();
      vtkSmartPointer<ArrayType> connectivity = vtkSmartPointer<ArrayType>::New();
      this->Offsets.handTo(offsets.GetPointer());
      this->Connectivity.handTo(connectivity.GetPointer());
      cells->SetData(offsets, connectivity);
    }
  };

  template<typename Id>
  bool fitNarrow(const Id* ids, std::size_t n) const
  {
    return this->fitNarrowAt([ids](std::size_t j) { return ids[j]; }, n);
  }
  template<typename At>
  bool fitNarrowAt(At at, std::size_t n) const
  {
    // The largest id, with no branch per id (a loop the compiler can vectorize); the ids of
    // one call all go in, so nothing is saved by stopping at the first that does not fit.
    std::int64_t top = std::numeric_limits<std::int64_t>::min();
    for (std::size_t i = 0; i < n; ++i)
      top = std::max(top, static_cast<std::int64_t>(at(i)));
    return top <= this->NarrowLimit;
  }

  /// Whether every id of these cells is at most `limit`.
  bool fitsIn(std::int64_t limit) const
  {
    if (!this->Wide && this->NarrowLimit <= limit)
      return true; // all narrow ids are at most NarrowLimit
    const auto fit = [limit](const auto& ids)
    {
      const auto* data = ids.Connectivity.data();
      return std::all_of(
        data, data + ids.Connectivity.size(), [limit](std::int64_t id) { return id <= limit; });
    };
    return this->Wide ? fit(this->Large) : fit(this->Narrow);
  }

  template<typename U>
  void appendIds(const Ids<U>& from)
  {
    if (this->Wide)
      this->Large.appendAll(from);
    else
      this->Narrow.appendAll(from);
  }

  /// Copies the 32-bit ids into 64-bit ones, once. Both copies exist for a moment (12 bytes
  /// an id): the need is checked first, and a failure leaves the buffer as it was.
  void widen()
  {
    const double bytes =
      8.0 * static_cast<double>(this->Narrow.Offsets.size() + this->Narrow.Connectivity.size());
    const std::string refused = checkAllocation(bytes, "64-bit output cells");
    if (!refused.empty())
      throw std::runtime_error(refused);
    vtkTypeInt64 *offsets = nullptr, *connectivity = nullptr;
    try
    {
      offsets = this->Large.Offsets.extend(this->Narrow.Offsets.size());
      connectivity = this->Large.Connectivity.extend(this->Narrow.Connectivity.size());
    }
    catch (...)
    {
      this->Large.Offsets.clear();
      this->Large.Connectivity.clear();
      throw;
    }
    std::copy(this->Narrow.Offsets.data(),
      this->Narrow.Offsets.data() + this->Narrow.Offsets.size(),
      offsets);
    std::copy(this->Narrow.Connectivity.data(),
      this->Narrow.Connectivity.data() + this->Narrow.Connectivity.size(),
      connectivity);
    this->Narrow.Offsets.clear();
    this->Narrow.Connectivity.clear();
    this->Wide = true;
  }

  const std::int64_t NarrowLimit;
  bool Wide = false;
  Ids<vtkTypeInt32> Narrow;
  Ids<vtkTypeInt64> Large;
};

} // namespace vtk
} // namespace vbr

#endif
