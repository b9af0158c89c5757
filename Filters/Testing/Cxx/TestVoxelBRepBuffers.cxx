// The output cell buffer (vtkVoxelBRepBuffers.h) against cells kept in plain vectors: random
// cells read back through vtkCellArray equal the cells written, in order or reversed; 32-bit
// storage while every offset and point id fits, 64-bit storage (the same cells) once an id or
// the connectivity size passes the limit, which the test lowers so that the widening happens
// on small inputs; the same with the cells written in runs of several cells (addCells), and
// written into part buffers (reused, with the default limit or the test's) appended one after
// the other (append), as the filter's worker threads write theirs. Then
// the filter that writes through it: the EVM boundary's cells of a random volume use 32-bit
// storage and every cell refers to an existing point. Last, a MallocBuffer grown past the size
// from which its memory is a mapping of its own (HugePageMinimum; remapped as it grows, freed
// by VTK through unmapHugeBlock) holds the values pushed into a std::vector alongside, before
// and after VTK takes it over, and after VTK grows the array it took (its reallocation copies
// out of a block that malloc did not make).
#include "vtkVoxelBRepBuffers.h"

#include "TestImages.h"
#include "vtkEVMBoundaryFilter.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

namespace
{

using Cell = std::vector<vtkIdType>;

std::vector<Cell> randomCells(std::size_t count, vtkIdType maximumId, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> size(1, 8);
  std::uniform_int_distribution<vtkIdType> id(0, maximumId);
  std::vector<Cell> cells(count);
  for (Cell& c : cells)
  {
    c.resize(static_cast<std::size_t>(size(rng)));
    for (vtkIdType& v : c)
      v = id(rng);
  }
  return cells;
}

/// Whether `array` holds `expected` (each reversed when `reversed`); a message when not.
bool sameCells(vtkCellArray* array, const std::vector<Cell>& expected, bool reversed)
{
  if (array->GetNumberOfCells() != static_cast<vtkIdType>(expected.size()))
  {
    std::cerr << "cells: " << array->GetNumberOfCells() << " instead of " << expected.size()
              << "\n";
    return false;
  }
  auto it = vtk::TakeSmartPointer(array->NewIterator());
  std::size_t c = 0;
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++c)
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    Cell want = expected[c];
    if (reversed)
      want.assign(expected[c].rbegin(), expected[c].rend());
    if (Cell(ids, ids + n) != want)
    {
      std::cerr << "cell " << c << " differs\n";
      return false;
    }
  }
  return true;
}

/// Writes `cells` through the buffer in runs of one to five cells (addCells), each run's ids
/// in one array whose ends count from a run's own first index.
void addInRuns(vbr::vtk::CellArrayBuffer& buffer, const std::vector<Cell>& cells, bool reversed)
{
  std::vector<vtkIdType> ids;
  std::vector<std::uint32_t> ends;
  for (std::size_t c = 0, run = 1; c < cells.size(); c += run, run = run % 5 + 1)
  {
    const std::size_t count = std::min(run, cells.size() - c), first = 3 * c + 1;
    ids.clear();
    ends.clear();
    for (std::size_t k = c; k < c + count; ++k)
    {
      ids.insert(ids.end(), cells[k].begin(), cells[k].end());
      ends.push_back(static_cast<std::uint32_t>(first + ids.size()));
    }
    buffer.addCells(ids.data(), ends.data(), count, first, reversed);
  }
}

/// Writes `cells` through the buffer in runs of one to five cells as addInRuns does, with
/// addMappedCells: each id given as map[corner], the runs holding the corners, `map` the ids
/// in reverse order of their first use (and unused entries between).
void addInMappedRuns(vbr::vtk::CellArrayBuffer& buffer,
  const std::vector<Cell>& cells,
  bool reversed)
{
  std::vector<std::int64_t> map;
  std::vector<int> corners, ends32;
  std::vector<std::uint32_t> ends;
  for (const Cell& c : cells)
    for (vtkIdType id : c)
    {
      map.push_back(-1); // never read
      map.push_back(id);
    }
  std::reverse(map.begin(), map.end()); // the id of cell corner k at 2 * (total - 1 - k)
  const int total = static_cast<int>(map.size() / 2);
  int k = 0;
  for (std::size_t c = 0, run = 1; c < cells.size(); c += run, run = run % 5 + 1)
  {
    const std::size_t count = std::min(run, cells.size() - c), first = 2 * c + 3;
    corners.assign(first, -7); // before `first`: never read
    ends.clear();
    for (std::size_t j = c; j < c + count; ++j)
    {
      for (std::size_t i = 0; i < cells[j].size(); ++i, ++k)
        corners.push_back(2 * (total - 1 - k));
      ends.push_back(static_cast<std::uint32_t>(corners.size()));
    }
    buffer.addMappedCells(corners.data(), map.data(), ends.data(), count, first, reversed);
  }
}

/// Writes `cells` into one part buffer (limit `partLimit`) a part of 1 to 40 cells at a time,
/// each part appended to `buffer` and the part buffer emptied for the next.
void addInParts(vbr::vtk::CellArrayBuffer& buffer,
  const std::vector<Cell>& cells,
  bool reversed,
  std::int64_t partLimit)
{
  vbr::vtk::CellArrayBuffer part(partLimit);
  for (std::size_t c = 0, size = 1; c < cells.size(); c += size, size = size * 7 % 41)
  {
    for (std::size_t k = c; k < std::min(c + size, cells.size()); ++k)
      part.addCell(cells[k].data(), cells[k].size(), reversed);
    buffer.append(part);
    part.clearKeepingMemory();
  }
}

/// How a round trip writes its cells.
enum class Writing
{
  Cells,           ///< addCell, cell by cell
  Runs,            ///< addCells, in runs
  MappedRuns,      ///< addMappedCells, in runs
  PartsOf32Bits,   ///< in part buffers of the default limit, appended
  PartsOfTheLimit, ///< in part buffers of the test's limit, appended
};

/// Writes `cells` through a buffer with the given limit (cell by cell, in runs or in parts),
/// and reads them back.
bool roundTrip(const std::vector<Cell>& cells,
  std::int64_t limit,
  bool reversed,
  bool wide,
  Writing writing = Writing::Cells)
{
  vbr::vtk::CellArrayBuffer buffer(limit);
  if (writing == Writing::Runs)
    addInRuns(buffer, cells, reversed);
  else if (writing == Writing::MappedRuns)
    addInMappedRuns(buffer, cells, reversed);
  else if (writing == Writing::PartsOf32Bits)
    addInParts(buffer, cells, reversed, std::numeric_limits<std::int32_t>::max());
  else if (writing == Writing::PartsOfTheLimit)
    addInParts(buffer, cells, reversed, limit);
  else
    for (const Cell& c : cells)
      buffer.addCell(c.data(), c.size(), reversed);
  if (buffer.isWide() != wide || buffer.numberOfCells() != cells.size())
  {
    std::cerr << "limit " << limit << ": wide " << buffer.isWide() << ", expected " << wide << "\n";
    return false;
  }
  vtkSmartPointer<vtkCellArray> array = buffer.release();
  if (array->IsStorage64Bit() != wide)
  {
    std::cerr << "limit " << limit << ": the storage is not " << (wide ? 64 : 32) << "-bit\n";
    return false;
  }
  if (buffer.numberOfCells() != 0 || buffer.isWide())
  {
    std::cerr << "the buffer is not empty after release\n";
    return false;
  }
  return sameCells(array, cells, reversed);
}

bool testBuffer()
{
  bool ok = true;
  for (unsigned seed = 1; seed <= 20; ++seed)
  {
    const std::vector<Cell> cells = randomCells(200 + 37 * seed, 100, seed);
    std::size_t corners = 0;
    for (const Cell& c : cells)
      corners += c.size();
    for (bool reversed : { false, true })
      for (Writing writing : { Writing::Cells,
             Writing::Runs,
             Writing::MappedRuns,
             Writing::PartsOf32Bits,
             Writing::PartsOfTheLimit })
      {
        ok &= roundTrip(cells, 1 << 30, reversed, false, writing);
        // The connectivity size passes the limit partway: widened, nothing lost.
        ok &= roundTrip(cells, static_cast<std::int64_t>(corners / 2), reversed, true, writing);
        // A point id passes the limit: widened at the cell that holds it, partway.
        std::vector<Cell> withLargeId = cells;
        withLargeId[cells.size() / 2].push_back(200);
        ok &= roundTrip(withLargeId, 150, reversed, true, writing);
      }
  }
  // The first cell alone passes it, and an empty buffer gives an empty array.
  for (Writing writing :
    { Writing::Cells, Writing::MappedRuns, Writing::PartsOf32Bits, Writing::PartsOfTheLimit })
    ok &= roundTrip({ { 5, 6, 7 } }, 2, false, true, writing);
  ok &= roundTrip({}, 10, false, false);
  // Ids at the 32-bit maximum stay narrow; one above it widens even with the default limit.
  const vtkIdType max32 = 2147483647;
  ok &= roundTrip({ { 0, max32 } }, max32, false, false);
#ifdef VTK_USE_64BIT_IDS
  for (Writing writing : { Writing::Cells, Writing::MappedRuns, Writing::PartsOf32Bits })
    ok &= roundTrip({ { 0, max32 + 1 } }, max32, false, true, writing);
#endif
  return ok;
}

bool testFilterOutput()
{
  const vbrtest::Volume v = vbrtest::randomVolume({ 12, 11, 10 }, 0.45, 1, 7);
  auto image = vbrtest::makeImage(v, vbrtest::Layout{});
  bool ok = true;
  for (int mode : { vtkEVMBoundaryFilter::POLYGONS, vtkEVMBoundaryFilter::TRIANGLES })
  {
    vtkNew<vtkEVMBoundaryFilter> filter;
    filter->SetInputData(image);
    filter->SetOutputMode(mode);
    filter->Update();
    vtkPolyData* out = filter->GetOutput();
    vtkCellArray* polys = out->GetPolys();
    if (polys->GetNumberOfCells() == 0 || polys->IsStorage64Bit())
    {
      std::cerr << "mode " << mode << ": " << polys->GetNumberOfCells() << " cells, 64-bit storage "
                << polys->IsStorage64Bit() << "\n";
      ok = false;
      continue;
    }
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      for (vtkIdType i = 0; i < n; ++i)
        if (ids[i] < 0 || ids[i] >= out->GetNumberOfPoints())
        {
          std::cerr << "mode " << mode << ": point id " << ids[i] << " out of range\n";
          return false;
        }
    }
  }
  return ok;
}

/// Whether the first `n` values of `data` are those of `expected`.
bool sameValues(const int* data, const std::vector<int>& expected, std::size_t n)
{
  return n <= expected.size() && std::equal(expected.begin(), expected.begin() + n, data);
}

bool testLargeBuffer()
{
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> value(-1000000, 1000000);
  std::vector<int> expected;
  vbr::vtk::MallocBuffer<int> buffer;
  bool ok = true;
  // Past 4 MiB (a mapped block from there) and through several doublings (remapped).
  const std::size_t target = 6 * vbr::HugePageMinimum / sizeof(int);
  for (std::size_t round = 0; expected.size() < target; ++round)
  {
    const std::size_t n = 1 + round % 5000;
    if (round % 2 == 0)
      for (std::size_t i = 0; i < n; ++i)
      {
        expected.push_back(value(rng));
        buffer.push_back(expected.back());
      }
    else
    {
      int* out = buffer.extend(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        expected.push_back(value(rng));
        out[i] = expected.back();
      }
    }
    if (round % 997 == 0 && !sameValues(buffer.data(), expected, expected.size()))
      ok = false;
  }
  ok = ok && buffer.size() == expected.size() && sameValues(buffer.data(), expected, buffer.size());
  vtkNew<vtkIntArray> array;
  buffer.handTo(array.GetPointer());
  const std::size_t handed = expected.size();
  ok = ok && buffer.size() == 0 && static_cast<std::size_t>(array->GetNumberOfValues()) == handed &&
    sameValues(array->GetPointer(0), expected, handed);
  for (std::size_t i = 0; i < handed; ++i) // VTK grows the array it took over
  {
    expected.push_back(value(rng));
    array->InsertNextValue(expected.back());
  }
  ok = ok && static_cast<std::size_t>(array->GetNumberOfValues()) == expected.size() &&
    sameValues(array->GetPointer(0), expected, expected.size());
  if (!ok)
    std::cerr << "large MallocBuffer: values differ from the vector's\n";
  return ok;
}

/// An array VTK took over from a mapped block, emptied (vtkBuffer keeps its free function)
/// and filled again by malloc: its values are right, and the free function, handed that block
/// of malloc when the array grows again, frees it (a munmap of it would fail or unmap memory of
/// the heap).
bool emptiedAndFilledAgain(vtkIntArray* array, const char* what)
{
  array->Initialize();
  std::vector<int> expected;
  for (int i = 0; i < 100000; ++i)
  {
    expected.push_back(3 * i - 7);
    array->InsertNextValue(expected.back());
  }
  const bool ok = static_cast<std::size_t>(array->GetNumberOfValues()) == expected.size() &&
    sameValues(array->GetPointer(0), expected, expected.size()) &&
    !vbr::hugeblock::isBlock(array->GetPointer(0));
  if (!ok)
    std::cerr << what << ": refilled after Initialize, values or block differ\n";
  return ok;
}

bool testArraysEmptiedAfterTakeover()
{
  bool ok = true;
  {
    vbr::vtk::MallocBuffer<int> buffer;
    int* values = buffer.extend(3 * vbr::HugePageMinimum / sizeof(int));
    std::fill(values, values + buffer.size(), 5);
#ifdef VBR_HUGE_BLOCKS
    if (!vbr::hugeblock::isBlock(buffer.data())) // the mapped path, not malloc's
    {
      std::cerr << "a MallocBuffer of 12 MiB is not a mapped block\n";
      ok = false;
    }
#endif
    vtkNew<vtkIntArray> array;
    buffer.handTo(array.GetPointer());
    ok = emptiedAndFilledAgain(array, "mapped MallocBuffer") && ok;
  }
  std::vector<char> heap(100);
  ok = !vbr::hugeblock::isBlock(heap.data()) && ok;
  // The test itself on a page of our own: the cookie in the header's place tells a block, its
  // absence or another place in the page does not.
  void* page = std::aligned_alloc(4096, 8192);
  auto* words = static_cast<std::uint64_t*>(page);
  char* data = static_cast<char*>(page) + vbr::hugeblock::Header;
  words[0] = 8192;
  words[1] = vbr::hugeblock::Cookie;
  const bool told = vbr::hugeblock::isBlock(data) && !vbr::hugeblock::isBlock(data + 16);
  words[1] = 0;
  if (!told || vbr::hugeblock::isBlock(data))
  {
    std::cerr << "hugeblock::isBlock does not tell a block by its place and cookie\n";
    ok = false;
  }
  std::free(page);
  return ok;
}

} // namespace

int TestVoxelBRepBuffers(int, char*[])
{
  const bool ok =
    testBuffer() && testFilterOutput() && testLargeBuffer() && testArraysEmptiedAfterTakeover();
  std::cout << (ok ? "passed" : "FAILED") << "\n";
  return ok ? 0 : 1;
}
