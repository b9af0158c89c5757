// BenchEVMBoundary: times vtkEVMBoundaryFilter against the VTK filters that give a boundary
// of the same voxels, in one process and on the same input each time.
//
// For every input (the procedural phantom at several sizes, selection label > 0, and the real
// aneurism and engine volumes when present, selection value >= 55) it times:
//  (a) image -> EVM alone, with the VTK-free core: thresholding into a BitVolume
//      (vbr::selectVoxels) and vbr::extractEVM, each on its own and together, on one thread
//      (an Execution without parallelFor) and with vtkSMPTools;
//  (b) the whole vtkEVMBoundaryFilter, Polygons and Triangles output modes (point scalars,
//      Range selection on the original values);
//  (c) vtkDiscreteFlyingEdges3D, contour value 1 of a 0/1 uint8 image of the same selection
//      (point scalars);
//  (d) vtkThreshold [1, 1] on 0/1 cell scalars of an image of (voxels + 1) points, then
//      vtkGeometryFilter: what a ParaView user does today (Threshold + Extract Surface).
// (a) to (d) run under every requested vtkSMPTools backend (vtkSMPTools::SetBackend; ParaView's
// VTK defaults to Sequential). Each measurement is one untimed warm-up run followed by
// --repeat timed runs; the tables give the median and the minimum.
//
// Usage:
//   BenchEVMBoundary [--sizes 128,256,512] [--repeat 5] [--data-dir DIR] [--quick]
//                    [--backends STDThread,Sequential] [--no-data] [--help]
// --quick drops the 512^3 phantom (sizes 128,256) unless --sizes is given; --sizes 0 skips
// the phantom. The output is Markdown tables, ready to paste into a README.
#include "BitVolume.h"
#include "EVM.h"
#include "Execution.h"
#include "Phantom.h"
#include "Selection.h"

#include "BenchCommon.h"

#include "vtkEVMBoundaryFilter.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkFieldData.h"
#include "vtkGeometryFilter.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkThreshold.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVersion.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#ifndef VOXELBREP_DEFAULT_DATA_DIR
#define VOXELBREP_DEFAULT_DATA_DIR "../shared/data"
#endif

namespace
{

using Clock = std::chrono::steady_clock;

double secondsBetween(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

/// Re-executes one algorithm and returns the seconds its update took.
double timedUpdate(vtkAlgorithm* algorithm)
{
  algorithm->Modified();
  const auto t0 = Clock::now();
  algorithm->Update();
  return secondsBetween(t0, Clock::now());
}

//------------------------------------------------------------------------------
// Options

struct Options
{
  std::vector<int> sizes{ 128, 256, 512 };
  bool sizesGiven = false;
  int repeat = 5;
  std::string dataDir = VOXELBREP_DEFAULT_DATA_DIR;
  bool quick = false;
  bool data = true;
  std::vector<std::string> backends{ "STDThread", "Sequential" };
  std::vector<int> labelEdges{ 8, 16, 24 }; ///< compact labels: edge^3 labels of 2^3 voxels
};

std::vector<std::string> splitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    if (!item.empty())
    {
      items.push_back(item);
    }
  }
  return items;
}

void printUsage(const char* program)
{
  std::cout
    << "Usage: " << program
    << " [--sizes 128,256,512] [--repeat 5] [--data-dir DIR] [--quick]\n"
       "       [--backends STDThread,Sequential] [--labels 8,16,24] [--no-data] [--help]\n"
       "  --sizes     edge lengths of the cubic phantoms (0: no phantom)\n"
       "  --repeat    timed runs per measurement, after one warm-up run (median and min)\n"
       "  --data-dir  directory holding aneurism/ and engine/ (default " VOXELBREP_DEFAULT_DATA_DIR
       ")\n"
       "  --quick     phantom sizes 128,256 only (unless --sizes is given)\n"
       "  --backends  vtkSMPTools backends to run (b), (c), (d) and the SMP part of (a) with\n"
       "  --labels    Labels mode on N^3 compact labels of 2^3 voxels, for each N (0: none)\n"
       "  --no-data   skip the real volumes\n";
}

/// Returns false (after a message) on a bad command line.
bool parseArguments(int argc, char* argv[], Options& options, bool& help)
{
  help = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto value = [&](std::string& out)
    {
      if (i + 1 >= argc)
      {
        std::cerr << "Missing value after " << arg << "\n";
        return false;
      }
      out = argv[++i];
      return true;
    };
    std::string text;
    if (arg == "--help" || arg == "-h")
    {
      help = true;
    }
    else if (arg == "--quick")
    {
      options.quick = true;
    }
    else if (arg == "--no-data")
    {
      options.data = false;
    }
    else if (arg == "--sizes")
    {
      if (!value(text))
        return false;
      options.sizes.clear();
      options.sizesGiven = true;
      for (const std::string& item : splitList(text))
      {
        const int n = std::atoi(item.c_str());
        if (n < 0 || n > 2048)
        {
          std::cerr << "Bad size " << item << "\n";
          return false;
        }
        if (n > 0)
          options.sizes.push_back(n);
      }
    }
    else if (arg == "--labels")
    {
      if (!value(text))
        return false;
      options.labelEdges.clear();
      for (const std::string& item : splitList(text))
        if (std::atoi(item.c_str()) > 0)
          options.labelEdges.push_back(std::min(std::atoi(item.c_str()), 64));
    }
    else if (arg == "--repeat")
    {
      if (!value(text))
        return false;
      options.repeat = std::atoi(text.c_str());
      if (options.repeat < 1)
      {
        std::cerr << "--repeat needs a positive count\n";
        return false;
      }
    }
    else if (arg == "--data-dir")
    {
      if (!value(options.dataDir))
        return false;
    }
    else if (arg == "--backends")
    {
      if (!value(text))
        return false;
      options.backends = splitList(text);
    }
    else
    {
      std::cerr << "Unknown argument " << arg << "\n";
      return false;
    }
  }
  if (options.quick && !options.sizesGiven)
  {
    options.sizes = { 128, 256 };
  }
  return true;
}

//------------------------------------------------------------------------------
// Inputs

struct Input
{
  std::string name;
  std::array<int, 3> dims{ 0, 0, 0 };
  std::vector<std::uint8_t> values; ///< x fastest
  int threshold = 1;                ///< selected: value >= threshold
  long long expectedExtremeVertices = -1;

  std::size_t voxelCount() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
};

bool loadRaw(const std::string& path, std::size_t size, std::vector<std::uint8_t>& values)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    return false;
  }
  values.resize(size);
  file.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(size));
  if (file.gcount() != static_cast<std::streamsize>(size))
  {
    std::cout << "WARNING: " << path << " holds fewer than " << size << " bytes; skipped\n\n";
    return false;
  }
  return true;
}

/// Whether a selected voxel lies on the border of the image (DFE leaves such surfaces open).
bool touchesBorder(const Input& input)
{
  const int nx = input.dims[0], ny = input.dims[1], nz = input.dims[2];
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
    {
      const std::uint8_t* row = &input.values[(std::size_t(z) * ny + y) * nx];
      if (z == 0 || z == nz - 1 || y == 0 || y == ny - 1)
      {
        for (int x = 0; x < nx; ++x)
          if (row[x] >= input.threshold)
            return true;
      }
      else if (row[0] >= input.threshold || row[nx - 1] >= input.threshold)
      {
        return true;
      }
    }
  return false;
}

vtkSmartPointer<vtkUnsignedCharArray> makeArray(const char* name,
  const std::vector<std::uint8_t>& values,
  int threshold,
  bool binary)
{
  auto array = vtkSmartPointer<vtkUnsignedCharArray>::New();
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::uint8_t* out = array->GetPointer(0);
  if (binary)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
      out[i] = values[i] >= threshold ? 1 : 0;
  }
  else
  {
    std::memcpy(out, values.data(), values.size());
  }
  return array;
}

/// Voxels as point scalars: one point per voxel.
vtkSmartPointer<vtkImageData> makePointImage(const Input& input, bool binary)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(input.dims[0], input.dims[1], input.dims[2]);
  image->GetPointData()->SetScalars(
    makeArray(binary ? "Selected" : "Values", input.values, input.threshold, binary));
  return image;
}

/// The 0/1 selection as cell scalars: (voxels + 1) points along each axis.
vtkSmartPointer<vtkImageData> makeBinaryCellImage(const Input& input)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(input.dims[0] + 1, input.dims[1] + 1, input.dims[2] + 1);
  image->GetCellData()->SetScalars(makeArray("Selected", input.values, input.threshold, true));
  return image;
}

//------------------------------------------------------------------------------
// Measurements

/// Output sizes; -1 means not applicable.
struct Sizes
{
  long long cells = -1, points = -1, faces = -1, extremeVertices = -1;
};

/// One run: the seconds and output sizes of each phase it times.
struct Outcome
{
  std::vector<double> seconds;
  std::vector<Sizes> sizes;
};

struct Row
{
  std::string method;
  std::string smp;
  double median = 0, min = 0;
  Sizes sizes;
  long long peakBytes = -1; ///< memory the first run added at its peak
};

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// One untimed warm-up run, then `repeat` timed runs; one row per phase.
std::vector<Row> measure(int repeat,
  const std::vector<std::string>& phases,
  const std::string& smp,
  const std::function<Outcome()>& run)
{
  // Warm-up (page faults, thread pool start, caches), and the peak memory of a first run.
  const long long peak = vbrbench::peakBytesOf([&] { run(); });
  std::vector<std::vector<double>> times(phases.size());
  Outcome last;
  for (int r = 0; r < repeat; ++r)
  {
    last = run();
    for (std::size_t p = 0; p < phases.size(); ++p)
      times[p].push_back(last.seconds[p]);
  }
  std::vector<Row> rows;
  for (std::size_t p = 0; p < phases.size(); ++p)
  {
    Row row;
    row.method = phases[p];
    row.smp = smp;
    row.median = median(times[p]);
    row.min = *std::min_element(times[p].begin(), times[p].end());
    row.sizes = last.sizes[p];
    row.peakBytes = peak;
    rows.push_back(row);
  }
  return rows;
}

long long fieldValue(vtkDataObject* data, const char* name)
{
  vtkDataArray* array = vtkDataArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(name));
  return array && array->GetNumberOfTuples() > 0 ? static_cast<long long>(array->GetTuple1(0)) : -1;
}

Sizes sizesOf(vtkDataSet* data)
{
  Sizes s;
  s.cells = data->GetNumberOfCells();
  s.points = data->GetNumberOfPoints();
  return s;
}

/// vtkSMPTools as the core's parallel loop: what vbr::vtk::makeExecution (private to the
/// module, not exported) does, without progress reporting.
vbr::Execution smpExecution()
{
  vbr::Execution exec;
  exec.parallelFor = [](std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body)
  {
    vtkSMPTools::For(
      vtkIdType(0), static_cast<vtkIdType>(n), [&body](vtkIdType b, vtkIdType e) { body(b, e); });
  };
  return exec;
}

/// (a) thresholding into a BitVolume, then the EVM.
std::vector<Row> measureConversion(const Input& input,
  const vbr::Execution& exec,
  const std::string& smp,
  int repeat)
{
  vbr::ScalarGrid<std::uint8_t> grid;
  grid.data = input.values.data();
  grid.dims = { input.dims[0], input.dims[1], input.dims[2] };
  grid.stride = { 1, input.dims[0], std::int64_t(input.dims[0]) * input.dims[1] };
  vbr::Box box;
  box.hi = grid.dims;
  const std::uint8_t threshold = static_cast<std::uint8_t>(input.threshold);
  return measure(repeat,
    { "select (BitVolume)", "extractEVM", "select + extractEVM" },
    smp,
    [&]()
    {
      const auto t0 = Clock::now();
      const vbr::BitVolume voxels = vbr::selectVoxels(
        grid, box, [threshold](std::uint8_t v) { return v >= threshold; }, exec);
      const auto t1 = Clock::now();
      const vbr::EVM evm = vbr::extractEVM(voxels, exec);
      const auto t2 = Clock::now();
      Sizes none, ev;
      ev.extremeVertices = static_cast<long long>(evm.size());
      Outcome o;
      o.seconds = { secondsBetween(t0, t1), secondsBetween(t1, t2), secondsBetween(t0, t2) };
      o.sizes = { none, ev, ev };
      return o;
    });
}

/// (b) the whole filter.
std::vector<Row> measureEVMFilter(vtkImageData* image,
  const Input& input,
  bool triangles,
  const std::string& smp,
  int repeat)
{
  vtkNew<vtkEVMBoundaryFilter> filter;
  filter->SetInputData(image);
  filter->SetSelectionModeToRange();
  filter->SetLowerThreshold(input.threshold);
  filter->SetUpperThreshold(255);
  if (triangles)
    filter->SetOutputModeToTriangles();
  else
    filter->SetOutputModeToPolygons();
  return measure(repeat,
    { triangles ? "EVM filter, Triangles" : "EVM filter, Polygons" },
    smp,
    [&]()
    {
      const double seconds = timedUpdate(filter);
      vtkPolyData* out = filter->GetOutput();
      Sizes s = sizesOf(out);
      s.faces = fieldValue(out, "NumberOfFaces");
      s.extremeVertices = fieldValue(out, "NumberOfExtremeVertices");
      return Outcome{ { seconds }, { s } };
    });
}

/// (c) discrete flying edges on the 0/1 image.
std::vector<Row> measureDFE(vtkImageData* binary, const std::string& smp, int repeat)
{
  vtkNew<vtkDiscreteFlyingEdges3D> dfe;
  dfe->SetInputData(binary);
  dfe->SetValue(0, 1.0);
  dfe->ComputeNormalsOff();
  dfe->ComputeGradientsOff();
  return measure(repeat,
    { "DiscreteFlyingEdges3D" },
    smp,
    [&]()
    {
      const double seconds = timedUpdate(dfe);
      return Outcome{ { seconds }, { sizesOf(dfe->GetOutput()) } };
    });
}

/// (d) Threshold on cell scalars, then the geometry filter.
std::vector<Row> measureThresholdGeometry(vtkImageData* cells, const std::string& smp, int repeat)
{
  vtkNew<vtkThreshold> threshold;
  threshold->SetInputData(cells);
  threshold->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, vtkDataSetAttributes::SCALARS);
  // VTK >= 9.1 API (ThresholdBetween is deprecated there).
  threshold->SetLowerThreshold(1.0);
  threshold->SetUpperThreshold(1.0);
  threshold->SetThresholdFunction(vtkThreshold::THRESHOLD_BETWEEN);
  vtkNew<vtkGeometryFilter> geometry;
  geometry->SetInputConnection(threshold->GetOutputPort());
  return measure(repeat,
    { "Threshold", "GeometryFilter", "Threshold + Geometry" },
    smp,
    [&]()
    {
      threshold->Modified();
      const auto t0 = Clock::now();
      threshold->Update();
      const auto t1 = Clock::now();
      geometry->Update();
      const auto t2 = Clock::now();
      const Sizes surface = sizesOf(geometry->GetOutput());
      return Outcome{ { secondsBetween(t0, t1), secondsBetween(t1, t2), secondsBetween(t0, t2) },
        { sizesOf(threshold->GetOutput()), surface, surface } };
    });
}

//------------------------------------------------------------------------------
// Output

std::string formatMs(double seconds)
{
  const double ms = seconds * 1e3;
  char text[32];
  std::snprintf(
    text, sizeof(text), ms < 1 ? "%.3f" : (ms < 10 ? "%.2f" : (ms < 1000 ? "%.1f" : "%.0f")), ms);
  return text;
}

std::string formatCount(long long n)
{
  if (n < 0)
    return "-";
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i)
  {
    if (i > 0 && (digits.size() - i) % 3 == 0)
      out += ',';
    out += digits[i];
  }
  return out;
}

std::string formatRatio(double r)
{
  char text[32];
  std::snprintf(text, sizeof(text), r < 10 ? "%.2f" : "%.1f", r);
  return text;
}

std::string formatFixed(double value, int digits)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", digits, value);
  return text;
}

/// A Markdown table with padded columns; the first column is left-aligned.
class Table
{
public:
  explicit Table(std::vector<std::string> header)
    : Header(std::move(header))
  {
  }
  void add(std::vector<std::string> row) { this->Rows.push_back(std::move(row)); }
  void print(std::ostream& os) const
  {
    std::vector<std::size_t> width(this->Header.size(), 3);
    for (std::size_t c = 0; c < this->Header.size(); ++c)
    {
      width[c] = std::max(width[c], this->Header[c].size());
      for (const auto& row : this->Rows)
        width[c] = std::max(width[c], row[c].size());
    }
    auto line = [&](const std::vector<std::string>& cells)
    {
      os << "|";
      for (std::size_t c = 0; c < cells.size(); ++c)
      {
        const std::string pad(width[c] - cells[c].size(), ' ');
        os << ' ' << (c == 0 ? cells[c] + pad : pad + cells[c]) << " |";
      }
      os << "\n";
    };
    line(this->Header);
    os << "|";
    for (std::size_t c = 0; c < width.size(); ++c)
      os << (c == 0 ? " :" : " ") << std::string(width[c] - 1, '-') << (c == 0 ? " |" : ": |");
    os << "\n";
    for (const auto& row : this->Rows)
      line(row);
    os << "\n";
  }

private:
  std::vector<std::string> Header;
  std::vector<std::vector<std::string>> Rows;
};

const Row* findRow(const std::vector<Row>& rows, const std::string& method, const std::string& smp)
{
  for (const Row& row : rows)
    if (row.method == method && row.smp == smp)
      return &row;
  return nullptr;
}

/// Summary of one input for the final table.
struct Summary
{
  std::string name;
  std::string dims;
  std::size_t selected = 0;
  long long extremeVertices = -1;
  std::vector<Row> rows;
};

void printRatios(const std::vector<Row>& rows, const std::vector<std::string>& backends)
{
  std::vector<std::string> header{ "ratio" };
  for (const std::string& b : backends)
    header.push_back(b);
  Table times(header);
  const std::vector<std::pair<std::string, std::string>> timeRatios{
    { "DiscreteFlyingEdges3D", "EVM filter, Polygons" },
    { "DiscreteFlyingEdges3D", "EVM filter, Triangles" },
    { "Threshold + Geometry", "EVM filter, Polygons" },
    { "Threshold + Geometry", "EVM filter, Triangles" },
    { "EVM filter, Triangles", "EVM filter, Polygons" },
  };
  for (const auto& ratio : timeRatios)
  {
    std::vector<std::string> line{ "time: " + ratio.first + " / " + ratio.second };
    for (const std::string& b : backends)
    {
      const Row* num = findRow(rows, ratio.first, b);
      const Row* den = findRow(rows, ratio.second, b);
      line.push_back(num && den && den->median > 0 ? formatRatio(num->median / den->median) : "-");
    }
    times.add(line);
  }
  times.print(std::cout);

  // Cell counts do not depend on the backend: take the first one measured.
  Table counts({ "cell-count ratio", "value" });
  const std::vector<std::pair<std::string, std::string>> cellRatios{
    { "DiscreteFlyingEdges3D", "EVM filter, Polygons" },
    { "Threshold + Geometry", "EVM filter, Polygons" },
    { "DiscreteFlyingEdges3D", "EVM filter, Triangles" },
    { "Threshold + Geometry", "EVM filter, Triangles" },
  };
  for (const auto& ratio : cellRatios)
  {
    const Row* num = backends.empty() ? nullptr : findRow(rows, ratio.first, backends[0]);
    const Row* den = backends.empty() ? nullptr : findRow(rows, ratio.second, backends[0]);
    counts.add({ "cells: " + ratio.first + " / " + ratio.second,
      num && den && den->sizes.cells > 0
        ? formatRatio(double(num->sizes.cells) / double(den->sizes.cells))
        : "-" });
  }
  counts.print(std::cout);
}

/// Runs every measurement on one input and prints its tables.
Summary benchmarkInput(const Input& input, const Options& options)
{
  Summary summary;
  summary.name = input.name;
  summary.dims = std::to_string(input.dims[0]) + "x" + std::to_string(input.dims[1]) + "x" +
    std::to_string(input.dims[2]);
  const std::size_t voxels = input.voxelCount();
  for (std::uint8_t v : input.values)
    summary.selected += v >= input.threshold;

  std::cout << "## " << input.name << " (" << summary.dims << ", value >= " << input.threshold
            << ")\n\n";
  std::cout << "selected voxels: " << formatCount(static_cast<long long>(summary.selected))
            << " of " << formatCount(static_cast<long long>(voxels)) << " ("
            << formatFixed(100.0 * summary.selected / voxels, 2) << " %)\n";
  if (touchesBorder(input))
  {
    std::cout << "note: the selection touches the image border; DiscreteFlyingEdges3D leaves "
                 "the surface open there\n";
  }
  std::cout << std::flush;

  const vtkSmartPointer<vtkImageData> values = makePointImage(input, false);
  const vtkSmartPointer<vtkImageData> binary = makePointImage(input, true);
  const vtkSmartPointer<vtkImageData> cells = makeBinaryCellImage(input);

  std::vector<Row> rows;
  auto append = [&rows](const std::vector<Row>& more)
  { rows.insert(rows.end(), more.begin(), more.end()); };

  append(measureConversion(input, vbr::Execution(), "1 thread", options.repeat));
  std::vector<std::string> backends;
  for (const std::string& backend : options.backends)
  {
    if (!vtkSMPTools::SetBackend(backend.c_str()))
    {
      continue; // reported once in main
    }
    backends.push_back(backend);
    append(measureConversion(input, smpExecution(), backend, options.repeat));
    append(measureEVMFilter(values, input, false, backend, options.repeat));
    append(measureEVMFilter(values, input, true, backend, options.repeat));
    append(measureDFE(binary, backend, options.repeat));
    append(measureThresholdGeometry(cells, backend, options.repeat));
  }

  Table table({ "method",
    "SMP",
    "median ms",
    "min ms",
    "Gvox/s",
    "cells",
    "points",
    "faces",
    "extreme vertices" });
  for (const Row& row : rows)
  {
    table.add({ row.method,
      row.smp,
      formatMs(row.median),
      formatMs(row.min),
      row.median > 0 ? formatFixed(voxels / row.median * 1e-9, 3) : "-",
      formatCount(row.sizes.cells),
      formatCount(row.sizes.points),
      formatCount(row.sizes.faces),
      formatCount(row.sizes.extremeVertices) });
  }
  table.print(std::cout);
  printRatios(rows, backends);

  // Extreme vertices: the core and the filter must agree, and with the reference counts.
  long long ev = -1;
  bool consistent = true;
  for (const Row& row : rows)
  {
    if (row.sizes.extremeVertices < 0)
      continue;
    if (ev < 0)
      ev = row.sizes.extremeVertices;
    else if (row.sizes.extremeVertices != ev)
      consistent = false;
  }
  summary.extremeVertices = ev;
  std::cout << "extreme vertices: " << formatCount(ev);
  if (input.expectedExtremeVertices >= 0)
  {
    std::cout << " (reference " << formatCount(input.expectedExtremeVertices) << ")";
  }
  std::cout << "\n";
  if (!consistent)
  {
    std::cout << "WARNING: " << input.name
              << ": the methods report different numbers of extreme vertices\n";
  }
  if (input.expectedExtremeVertices >= 0 && ev != input.expectedExtremeVertices)
  {
    std::cout << "WARNING: " << input.name << ": " << ev << " extreme vertices, expected "
              << input.expectedExtremeVertices << "\n";
  }
  std::cout << "\n" << std::flush;
  summary.rows = std::move(rows);
  return summary;
}

/// Peak memory of a first run per output cell and per voxel of the image, for the filter and
/// its peers (one backend: the memory does not depend on it).
void printMemory(const std::vector<Summary>& summaries, const std::string& backend)
{
  std::cout << "## Peak memory of a first run (backend " << backend
            << "): bytes per output cell / per voxel\n\n";
  const char* methods[] = {
    "EVM filter, Polygons", "EVM filter, Triangles", "DiscreteFlyingEdges3D", "Threshold + Geometry"
  };
  Table table({ "input", "EVM Polygons", "EVM Triangles", "DFE", "Threshold+Geometry" });
  for (const Summary& s : summaries)
  {
    std::vector<std::string> line{ s.name };
    long long voxels = 1;
    for (const std::string& d : { s.dims })
    {
      std::istringstream in(d);
      std::string part;
      while (std::getline(in, part, 'x'))
        voxels *= std::max(1LL, std::atoll(part.c_str()));
    }
    for (const char* m : methods)
    {
      const Row* r = findRow(s.rows, m, backend);
      if (!r || r->peakBytes < 0 || r->sizes.cells <= 0)
      {
        line.push_back("-");
        continue;
      }
      char text[64];
      std::snprintf(text,
        sizeof(text),
        "%.0f / %.1f",
        double(r->peakBytes) / double(r->sizes.cells),
        double(r->peakBytes) / double(voxels));
      line.push_back(text);
    }
    table.add(line);
  }
  table.print(std::cout);
}

/// Labels mode on compact labels (cubes of 2^3 voxels, one label each): the cost per label
/// must not grow with the labels before it (it was quadratic), against
/// vtkDiscreteFlyingEdges3D with one contour value per label (a pass over the image per
/// value: quadratic there).
void benchmarkLabels(int repeat, const std::vector<int>& edges)
{
  std::cout << "## Labels mode, compact labels (2^3 voxels each; current backend; median ms)\n\n";
  Table table({ "labels",
    "dims",
    "EVM Triangles",
    "us per label",
    "DFE",
    "DFE/EVM",
    "EVM cells",
    "DFE cells" });
  for (int n : edges)
  {
    const int side = 2 * n;
    vtkNew<vtkImageData> image;
    image->SetDimensions(side, side, side);
    vtkNew<vtkIntArray> labels;
    labels->SetName("Labels");
    labels->SetNumberOfValues(vtkIdType(side) * side * side);
    vtkIdType i = 0;
    for (int z = 0; z < side; ++z)
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
          labels->SetValue(i++, 1 + (x / 2) + n * ((y / 2) + n * (z / 2)));
    image->GetPointData()->SetScalars(labels);
    const int count = n * n * n;
    vtkNew<vtkEVMBoundaryFilter> evm;
    evm->SetInputData(image);
    evm->SetSelectionModeToLabels();
    evm->SetOutputModeToTriangles();
    evm->SetGlobalWarningDisplay(0); // more than 1,000 labels warns; expected here
    vtkNew<vtkDiscreteFlyingEdges3D> dfe;
    dfe->SetInputData(image);
    dfe->GenerateValues(count, 1, count);
    dfe->ComputeNormalsOff();
    dfe->ComputeGradientsOff();
    const double tEVM = vbrbench::medianSeconds(repeat, [&] { vbrbench::update(evm); });
    const double tDFE = vbrbench::medianSeconds(repeat, [&] { vbrbench::update(dfe); });
    table.add({ formatCount(count),
      std::to_string(side) + "^3",
      formatMs(tEVM),
      formatFixed(1e6 * tEVM / count, 2),
      formatMs(tDFE),
      formatRatio(tDFE / tEVM),
      formatCount(evm->GetOutput()->GetNumberOfCells()),
      formatCount(dfe->GetOutput()->GetNumberOfCells()) });
  }
  table.print(std::cout);
}

void printSummary(const std::vector<Summary>& summaries, const std::vector<std::string>& backends)
{
  if (summaries.empty())
    return;
  std::cout << "## Summary (median ms)\n\n";
  for (const std::string& backend : backends)
  {
    std::cout << "SMP backend " << backend << "\n\n";
    Table table({ "input",
      "dims",
      "EV",
      "select+EVM 1 thr",
      "select+EVM SMP",
      "EVM Polygons",
      "EVM Triangles",
      "DFE",
      "Threshold+Geometry",
      "DFE/EVM-P",
      "T+G/EVM-P",
      "EVM-P cells",
      "DFE cells",
      "T+G cells" });
    for (const Summary& s : summaries)
    {
      const Row* core1 = findRow(s.rows, "select + extractEVM", "1 thread");
      const Row* core = findRow(s.rows, "select + extractEVM", backend);
      const Row* poly = findRow(s.rows, "EVM filter, Polygons", backend);
      const Row* tri = findRow(s.rows, "EVM filter, Triangles", backend);
      const Row* dfe = findRow(s.rows, "DiscreteFlyingEdges3D", backend);
      const Row* tg = findRow(s.rows, "Threshold + Geometry", backend);
      if (!core1 || !core || !poly || !tri || !dfe || !tg)
        continue;
      table.add({ s.name,
        s.dims,
        formatCount(s.extremeVertices),
        formatMs(core1->median),
        formatMs(core->median),
        formatMs(poly->median),
        formatMs(tri->median),
        formatMs(dfe->median),
        formatMs(tg->median),
        formatRatio(dfe->median / poly->median),
        formatRatio(tg->median / poly->median),
        formatCount(poly->sizes.cells),
        formatCount(dfe->sizes.cells),
        formatCount(tg->sizes.cells) });
    }
    table.print(std::cout);
  }
  printMemory(summaries, backends.front());
}

} // namespace

//------------------------------------------------------------------------------
int main(int argc, char* argv[])
{
  Options options;
  bool help = false;
  if (!parseArguments(argc, argv, options, help))
  {
    printUsage(argv[0]);
    return 2;
  }
  if (help)
  {
    printUsage(argv[0]);
    return 0;
  }

  const char* env = std::getenv("VTK_SMP_BACKEND_IN_USE");
  std::cout << "# BenchEVMBoundary\n\n";
  std::cout << "- VTK " << vtkVersion::GetVTKVersion()
            << ", vtkSMPTools backend at start: " << vtkSMPTools::GetBackend()
            << " (VTK_SMP_BACKEND_IN_USE=" << (env ? env : "unset") << ")\n";
  std::cout << "- hardware threads: " << std::thread::hardware_concurrency();
  std::ifstream loadavg("/proc/loadavg");
  std::string load1, load5;
  if (loadavg >> load1 >> load5)
  {
    std::cout << ", load average at start: " << load1 << " (1 min), " << load5 << " (5 min)";
  }
  std::cout << "\n";
  std::vector<std::string> backends;
  for (const std::string& backend : options.backends)
  {
    if (vtkSMPTools::SetBackend(backend.c_str()))
    {
      backends.push_back(backend);
      std::cout << "- backend " << backend << ": vtkSMPTools::GetEstimatedNumberOfThreads() = "
                << vtkSMPTools::GetEstimatedNumberOfThreads() << "\n";
    }
    else
    {
      std::cout << "- WARNING: vtkSMPTools backend " << backend
                << " is not available in this VTK; skipped\n";
    }
  }
  options.backends = backends;
#ifdef NDEBUG
  std::cout << "- optimized build (NDEBUG)\n";
#else
  std::cout << "- WARNING: assertions on (not a Release build): timings are not representative\n";
#endif
  std::cout << "- " << options.repeat
            << " timed runs per measurement after one warm-up run; times in ms (wall clock)\n";
  std::cout << "- Gvox/s = voxels of the image / median time\n\n" << std::flush;

  std::vector<Summary> summaries;
  for (int n : options.sizes)
  {
    Input input;
    input.name = "phantom " + std::to_string(n) + "^3";
    input.dims = { n, n, n };
    input.values = vbr::makePhantom({ n, n, n });
    input.threshold = 1; // label > 0
    summaries.push_back(benchmarkInput(input, options));
  }

  if (options.data)
  {
    struct RealVolume
    {
      const char* name;
      const char* file;
      std::array<int, 3> dims;
      long long extremeVertices;
    };
    const RealVolume volumes[] = {
      { "aneurism", "aneurism/aneurism_256x256x256_uint8.raw", { 256, 256, 256 }, 70260 },
      { "engine", "engine/engine_256x256x128_uint8.raw", { 256, 256, 128 }, 85866 },
    };
    for (const RealVolume& volume : volumes)
    {
      Input input;
      input.name = volume.name;
      input.dims = volume.dims;
      input.threshold = 55;
      input.expectedExtremeVertices = volume.extremeVertices;
      const std::string path = options.dataDir + "/" + volume.file;
      if (!loadRaw(path, input.voxelCount(), input.values))
      {
        std::cout << "(" << path << " not found: " << volume.name << " skipped)\n\n";
        continue;
      }
      summaries.push_back(benchmarkInput(input, options));
    }
  }

  printSummary(summaries, options.backends);
  if (!options.labelEdges.empty())
    benchmarkLabels(options.repeat, options.labelEdges);
  return 0;
}
