#include "BenchCommon.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVersion.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <thread>
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace vbrbench
{
namespace
{

using Clock = std::chrono::steady_clock;

/// Whether timeInTurns reads the process's CPU time (--cpu-time), set once by parseOptions.
bool timeOnCpu = false;

/// Seconds on the clock the runs are timed by.
double now()
{
  if (!timeOnCpu)
    return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

std::vector<int> intList(const std::string& text)
{
  std::vector<int> values;
  for (const std::string& item : splitList(text))
    if (std::atoi(item.c_str()) > 0)
      values.push_back(std::atoi(item.c_str()));
  return values;
}

std::string joinList(const std::vector<int>& values)
{
  std::string text;
  for (int v : values)
    text += (text.empty() ? "" : ",") + std::to_string(v);
  return text;
}

std::string joinList(const std::vector<std::string>& values)
{
  std::string text;
  for (const std::string& v : values)
    text += (text.empty() ? "" : ",") + v;
  return text;
}

/// The integer-list options, by name.
std::map<std::string, std::vector<int>*> listOptions(InputOptions& in)
{
  return { { "--sizes", &in.sizes },
    { "--sizes2d", &in.sizes2D },
    { "--seeds", &in.seeds },
    { "--solid", &in.solid },
    { "--radii", &in.radii },
    { "--labels", &in.labels } };
}

void printUsage(const char* program, const char* purpose, Options& o)
{
  InputOptions& in = o.inputs;
  std::printf("%s\n\nUsage: %s [options]\n"
              "  --inputs C,...   input classes (default %s; 'all': every class):\n"
              "                   %s\n"
              "  --sizes N,...    edges of the procedural 3D volumes (default %s)\n"
              "  --sizes2d N,...  edges of the procedural 2D images, porous2d (default %s)\n"
              "  --seeds S,...    seeds of the porous inputs (default %s)\n"
              "  --solid P,...    solid percentages of the porous inputs (default %s)\n"
              "  --radii R,...    radii of the balls (default %s)\n"
              "  --labels N,...   compact label maps of N^3 labels (default %s)\n"
              "  --repeat N       timed rounds after the first run (default %d)\n"
              "  --data DIR       the shared data (default %s)\n"
              "  --no-data        procedural inputs only\n"
              "  --quick          tiny sizes, one seed and fraction, --repeat 1, small files only\n"
              "                   (the smoke run of ctest); lists given explicitly are kept\n"
              "  --large          sizes 128,256,512, 2D 1024,4096, seeds 1,2,3, the mazes\n"
              "  --backends B,... vtkSMPTools backends (default %s)\n"
              "  --cpu-time       time by the process's CPU time, not the wall clock (for one\n"
              "                   thread: with threads it sums them)\n"
              "  --list           print the selected inputs and stop\n"
              "  --help           this text\n",
    purpose,
    program,
    joinList(in.classes).c_str(),
    joinList(inputClasses()).c_str(),
    joinList(in.sizes).c_str(),
    joinList(in.sizes2D).c_str(),
    joinList(in.seeds).c_str(),
    joinList(in.solid).c_str(),
    joinList(in.radii).c_str(),
    joinList(in.labels).c_str(),
    o.repeat,
    in.dataDir.c_str(),
    o.backends.empty() ? "the backend at start" : joinList(o.backends).c_str());
}

/// --quick and --large change the lists not given on the command line.
void applySizeModes(Options& o, const std::vector<std::string>& given, bool repeatGiven)
{
  InputOptions& in = o.inputs;
  auto set = [&](const char* name, std::vector<int>& list, std::vector<int> value)
  {
    if (std::find(given.begin(), given.end(), name) == given.end())
      list = std::move(value);
  };
  if (in.large)
  {
    set("--sizes", in.sizes, { 128, 256, 512 });
    set("--sizes2d", in.sizes2D, { 1024, 4096 });
    set("--seeds", in.seeds, { 1, 2, 3 });
  }
  if (in.quick)
  {
    set("--sizes", in.sizes, { 16 });
    set("--sizes2d", in.sizes2D, { 64 });
    set("--seeds", in.seeds, { 1 });
    set("--solid", in.solid, { 45 });
    set("--radii", in.radii, { 4 });
    set("--labels", in.labels, { 4 });
    if (!repeatGiven)
      o.repeat = 1;
  }
}

/// One argument at argv[i] (its value at argv[i + 1]); false when it is unknown.
bool parseOne(int argc, char* argv[], int& i, Options& o, std::vector<std::string>& given)
{
  const std::string a = argv[i];
  const bool hasValue = i + 1 < argc;
  auto lists = listOptions(o.inputs);
  if (lists.count(a) && hasValue)
    *lists[a] = intList(argv[++i]);
  else if (a == "--inputs" && hasValue)
    o.inputs.classes = splitList(argv[++i]);
  else if (a == "--backends" && hasValue)
    o.backends = splitList(argv[++i]);
  else if (a == "--repeat" && hasValue)
    o.repeat = std::max(1, std::atoi(argv[++i]));
  else if (a == "--data" && hasValue)
    o.inputs.dataDir = argv[++i];
  else if (a == "--no-data")
    o.inputs.data = false;
  else if (a == "--quick")
    o.inputs.quick = true;
  else if (a == "--large")
    o.inputs.large = true;
  else if (a == "--list")
    o.list = true;
  else if (a == "--cpu-time")
    o.cpuTime = true;
  else
    return false;
  given.push_back(a);
  return true;
}

} // namespace

int parseOptions(int argc, char* argv[], const char* purpose, Options& options)
{
  if (options.inputs.dataDir.empty())
    options.inputs.dataDir = VOXELBREP_DEFAULT_DATA_DIR;
  std::vector<std::string> given;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h")
      return printUsage(argv[0], purpose, options), 0;
    if (!parseOne(argc, argv, i, options, given))
    {
      std::fprintf(stderr, "Unknown argument or missing value: %s\n\n", a.c_str());
      return printUsage(argv[0], purpose, options), 2;
    }
  }
  applySizeModes(options, given, std::find(given.begin(), given.end(), "--repeat") != given.end());
  timeOnCpu = options.cpuTime;
  if (!options.list)
    return -1;
  for (const InputSpec& spec : selectInputs(options.inputs))
    std::printf("%s\n", describe(spec).c_str());
  return 0;
}

double median(std::vector<double> values)
{
  if (values.empty())
    return 0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

namespace
{
/// A field of /proc/self/status in kiB (VmRSS, VmHWM), or -1.
long long procStatusKiB(const std::string& field)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, field.size() + 1, field + ":") == 0)
      return std::atoll(line.c_str() + field.size() + 1);
  return -1;
}
} // namespace

long long peakBytesOf(const std::function<void()>& run)
{
#ifdef __GLIBC__
  malloc_trim(0); // give freed memory back, so that the run's pages show in the mark
#endif
  {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
  }
  const long long before = procStatusKiB("VmRSS");
  run();
  const long long peak = procStatusKiB("VmHWM");
  return before < 0 || peak < 0 ? -1 : 1024 * std::max(0LL, peak - before);
}

void update(vtkAlgorithm* algorithm)
{
  algorithm->Modified();
  algorithm->Update();
}

std::vector<Measured> timeInTurns(int repeat, const std::vector<Contender>& contenders)
{
  std::vector<Measured> out;
  for (const Contender& c : contenders)
  {
    Measured m;
    m.name = c.name;
    m.role = c.role;
    m.group = c.group;
    m.peakBytes = peakBytesOf(c.run);
    m.cells = c.cells ? c.cells() : -1;
    out.push_back(m);
  }
  std::vector<std::vector<double>> t(contenders.size());
  // Each round in an order of its own (shuffled, fixed seed), so that no contender always runs
  // right after the same one: with a rotation, the one after a peer found the caches cold in
  // every round and the next one found them warm.
  std::mt19937 shuffler(1);
  std::vector<std::size_t> order(contenders.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  for (int r = 0; r < repeat; ++r)
  {
    std::shuffle(order.begin(), order.end(), shuffler);
    for (const std::size_t k : order)
    {
      const double t0 = now();
      contenders[k].run();
      t[k].push_back(now() - t0);
    }
  }
  for (std::size_t k = 0; k < contenders.size(); ++k)
  {
    out[k].median = median(t[k]);
    out[k].min = t[k].empty() ? 0 : *std::min_element(t[k].begin(), t[k].end());
  }
  return out;
}

void forEachBackend(const Options& options, const std::function<void(const std::string&)>& body)
{
  std::vector<std::string> backends = options.backends;
  if (backends.empty())
    backends.push_back(vtkSMPTools::GetBackend());
  for (const std::string& backend : backends)
  {
    if (!vtkSMPTools::SetBackend(backend.c_str()))
    {
      std::printf(
        "WARNING: vtkSMPTools backend %s is not in this VTK; skipped\n\n", backend.c_str());
      continue;
    }
    body(backend);
  }
}

void forEachInput(const Options& options, const std::function<void(const Input&)>& run)
{
  for (const InputSpec& spec : selectInputs(options.inputs))
  {
    Input in;
    if (loadInput(spec, in))
      run(in);
    std::fflush(stdout);
  }
}

int runBenchmark(int argc,
  char* argv[],
  const char* title,
  const char* purpose,
  Options& options,
  const Benchmark& benchmark)
{
  const int stop = parseOptions(argc, argv, (std::string(title) + ": " + purpose).c_str(), options);
  if (stop >= 0)
    return stop;
  printPreamble(title, options);
  Report report;
  forEachInput(options, [&](const Input& in) { benchmark(in, options, report); });
  report.printSummary();
  return 0;
}

void printPreamble(const char* title, const Options& options)
{
  const char* env = std::getenv("VTK_SMP_BACKEND_IN_USE");
  std::printf("# %s\n\n- VTK %s, vtkSMPTools backend at start: %s (VTK_SMP_BACKEND_IN_USE=%s), "
              "%d threads estimated\n",
    title,
    vtkVersion::GetVTKVersion(),
    vtkSMPTools::GetBackend(),
    env ? env : "unset",
    vtkSMPTools::GetEstimatedNumberOfThreads());
  std::string load1 = "?", load5 = "?";
  std::ifstream("/proc/loadavg") >> load1 >> load5;
  std::printf("- hardware threads: %u, load average at start: %s (1 min), %s (5 min)\n",
    std::thread::hardware_concurrency(),
    load1.c_str(),
    load5.c_str());
#ifdef NDEBUG
  std::printf("- optimized build (NDEBUG)\n");
#else
  std::printf("- WARNING: assertions on (not a Release build): timings are not representative\n");
#endif
  std::printf("- per contender: a first run (peak memory, warm-up), then %d rounds in turns; "
              "median (mean of the middle two of an even count) and minimum, %s, ms; "
              "ratio = peer time / tool time (above 1: the project is faster)\n\n%s%s",
    options.repeat,
    options.cpuTime ? "CPU time of the process (all threads)" : "wall clock",
    options.note.c_str(),
    options.note.empty() ? "" : "\n\n");
  std::fflush(stdout);
}

//------------------------------------------------------------------------------
// Report

namespace
{
std::string dimsText(const std::array<int, 3>& d)
{
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

bool compared(const Measured& tool, const Measured& peer)
{
  return tool.role == Role::Tool && peer.role == Role::Peer &&
    (peer.group.empty() || tool.group.empty() || peer.group == tool.group);
}

std::string perUnit(long long bytes, double units)
{
  return bytes < 0 || units <= 0 ? "-" : formatFixed(double(bytes) / units, units > 1e5 ? 1 : 0);
}

std::string roleName(Role r)
{
  return r == Role::Tool ? "tool" : (r == Role::Peer ? "peer" : "phase");
}

/// "peer / this" for each peer compared with a tool row.
std::string ratiosOf(const Measured& tool, const std::vector<Measured>& rows)
{
  std::string text;
  for (const Measured& peer : rows)
    if (compared(tool, peer) && tool.median > 0)
      text += (text.empty() ? "" : ", ") + peer.name + " " + formatRatio(peer.median / tool.median);
  return text.empty() ? "-" : text;
}
} // namespace

void Report::printInput(const Input& in)
{
  const std::size_t selected = selectedCount(in);
  std::printf("## %s (%s%s%s)\n\nselected voxels: %s of %s (%.2f %%)\n",
    in.name.c_str(),
    dimsText(in.dims).c_str(),
    in.labels ? ", label map" : "",
    in.is2D() ? ", 2D" : "",
    formatCount(static_cast<long long>(selected)).c_str(),
    formatCount(static_cast<long long>(in.voxelCount())).c_str(),
    100.0 * selected / std::max<std::size_t>(1, in.voxelCount()));
  if (in.expectedSelected >= 0 && static_cast<long long>(selected) != in.expectedSelected)
    std::printf("WARNING: %s: %zu selected voxels, the manifest gives %lld\n",
      in.name.c_str(),
      selected,
      in.expectedSelected);
  if (touchesBorder(in))
    std::printf("note: the selection touches the image border (Flying Edges leaves the "
                "surface open there)\n");
  std::printf("\n");
}

void Report::add(const Input& in, const std::string& backend, const std::vector<Measured>& rows)
{
  std::printf("backend %s\n\n", backend.c_str());
  const double voxels = static_cast<double>(in.voxelCount());
  Table table({ "contender",
    "role",
    "median ms",
    "min ms",
    "cells",
    "peak MB",
    "B/cell",
    "B/voxel",
    "peer / this" });
  for (const Measured& m : rows)
    table.add({ m.name,
      roleName(m.role),
      formatMs(m.median),
      formatMs(m.min),
      formatCount(m.cells),
      m.peakBytes < 0 ? "-" : formatFixed(m.peakBytes / 1048576.0, 1),
      m.role == Role::Phase ? "-" : perUnit(m.peakBytes, double(m.cells)),
      m.role == Role::Phase ? "-" : perUnit(m.peakBytes, voxels),
      ratiosOf(m, rows) });
  table.print();
  this->Entries.push_back({ in.name, dimsText(in.dims), backend, voxels, rows });
  std::fflush(stdout);
}

const Measured* findMeasured(const std::vector<Measured>& rows, const std::string& name)
{
  for (const Measured& m : rows)
    if (m.name == name)
      return &m;
  return nullptr;
}

void Report::printSummary() const
{
  std::printf("## Summary: each tool against each of its peers (median ms; peak memory of a "
              "first run per output cell and per voxel)\n\n");
  Table table({ "input",
    "dims",
    "backend",
    "tool",
    "ms",
    "peer",
    "ms",
    "peer / tool",
    "tool B/cell",
    "peer B/cell",
    "tool B/voxel",
    "peer B/voxel" });
  for (const Entry& e : this->Entries)
    for (const Measured& tool : e.rows)
      for (const Measured& peer : e.rows)
        if (compared(tool, peer))
          table.add({ e.input,
            e.dims,
            e.backend,
            tool.name,
            formatMs(tool.median),
            peer.name,
            formatMs(peer.median),
            tool.median > 0 ? formatRatio(peer.median / tool.median) : "-",
            perUnit(tool.peakBytes, double(tool.cells)),
            perUnit(peer.peakBytes, double(peer.cells)),
            perUnit(tool.peakBytes, e.voxels),
            perUnit(peer.peakBytes, e.voxels) });
  table.print();
}

//------------------------------------------------------------------------------
// Inputs as the filters take them

namespace
{
vtkNew<vtkImageData> imageWith(const std::array<int, 3>& dims, vtkDataArray* scalars, bool cells)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(dims[0] + cells, dims[1] + cells, dims[2] + (cells && dims[2] > 1));
  if (cells)
    image->GetCellData()->SetScalars(scalars);
  else
    image->GetPointData()->SetScalars(scalars);
  return image;
}

vtkNew<vtkUnsignedCharArray> maskArray(const Input& in)
{
  vtkNew<vtkUnsignedCharArray> a;
  a->SetName("mask");
  a->SetNumberOfTuples(static_cast<vtkIdType>(in.voxelCount()));
  for (std::size_t i = 0; i < in.voxelCount(); ++i)
    a->SetValue(static_cast<vtkIdType>(i), in.selected(i));
  return a;
}
} // namespace

vtkNew<vtkImageData> maskImageOf(const Input& in)
{
  return imageWith(in.dims, maskArray(in), false);
}

vtkNew<vtkImageData> cellImageOf(const Input& in)
{
  return imageWith(in.dims, maskArray(in), true);
}

vtkNew<vtkImageData> labelImageOf(const Input& in)
{
  if (!in.wideLabels.empty())
  {
    vtkNew<vtkIntArray> a;
    a->SetName("labels");
    a->SetNumberOfTuples(static_cast<vtkIdType>(in.voxelCount()));
    std::copy(in.wideLabels.begin(), in.wideLabels.end(), a->GetPointer(0));
    return imageWith(in.dims, a, false);
  }
  return valueImageOf(in);
}

vtkNew<vtkImageData> valueImageOf(const Input& in)
{
  vtkNew<vtkUnsignedCharArray> a;
  a->SetName("values");
  a->SetNumberOfTuples(static_cast<vtkIdType>(in.voxelCount()));
  std::copy(in.values.begin(), in.values.end(), a->GetPointer(0));
  return imageWith(in.dims, a, false);
}

vbr::BitVolume bitsOf(const Input& in)
{
  vbr::BitVolume bits(in.dims[0], in.dims[1], in.dims[2]);
  std::size_t i = 0;
  for (int z = 0; z < in.dims[2]; ++z)
    for (int y = 0; y < in.dims[1]; ++y)
      for (int x = 0; x < in.dims[0]; ++x, ++i)
        if (in.selected(i))
          bits.set(x, y, z);
  return bits;
}

int maxLabel(const Input& in)
{
  if (!in.wideLabels.empty())
    return *std::max_element(in.wideLabels.begin(), in.wideLabels.end());
  return in.values.empty() ? 0 : *std::max_element(in.values.begin(), in.values.end());
}

//------------------------------------------------------------------------------
// Formatting

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
  const std::string digits = std::to_string(n);
  std::string out;
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

Table::Table(std::vector<std::string> header)
  : Header(std::move(header))
{
}

void Table::add(std::vector<std::string> row)
{
  row.resize(this->Header.size());
  this->Rows.push_back(std::move(row));
}

void Table::print() const
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
    std::string text = "|";
    for (std::size_t c = 0; c < cells.size(); ++c)
    {
      const std::string pad(width[c] - cells[c].size(), ' ');
      text += ' ' + (c == 0 ? cells[c] + pad : pad + cells[c]) + " |";
    }
    std::printf("%s\n", text.c_str());
  };
  line(this->Header);
  std::string rule = "|";
  for (std::size_t c = 0; c < width.size(); ++c)
    rule += (c == 0 ? " :" : " ") + std::string(width[c] - 1, '-') + (c == 0 ? " |" : ": |");
  std::printf("%s\n", rule.c_str());
  for (const auto& row : this->Rows)
    line(row);
  std::printf("\n");
}

} // namespace vbrbench
