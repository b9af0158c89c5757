// The harness every benchmark uses: one command line, one way to time the tool and its peers
// (in turns, in one process, on the same input), one median, one report.
//
// - Options (`--help` of any benchmark lists them with that benchmark's defaults): the input
//   classes and their sizes (see BenchInputs.h), --repeat, --data, --no-data, --quick,
//   --large, --backends, --list.
// - Timing: every contender (the tool's outputs, its peers, phases of the core) makes a first
//   run whose peak memory is measured (peakBytesOf; it is also the warm-up), then `repeat`
//   rounds in which each runs once, each round starting with the next contender, so that the
//   drift of a shared machine and what one run leaves to the next fall on all alike.
// - Median: the middle of the sorted times; of an even count, the mean of the middle two.
// - Report: per input a table (median and minimum ms, output cells, peak bytes per output cell
//   and per voxel, and peer time / tool time for each peer: above 1 the project is faster);
//   at the end a summary, one line per input, backend, tool and peer.
#ifndef vbr_BenchCommon_h
#define vbr_BenchCommon_h

#include "BenchInputs.h"

#include "BitVolume.h"

#include "vtkNew.h"

#include <functional>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkImageData;

#ifndef VOXELBREP_DEFAULT_DATA_DIR
#define VOXELBREP_DEFAULT_DATA_DIR "../shared/data"
#endif

namespace vbrbench
{

/// The command line of every benchmark.
struct Options
{
  InputOptions inputs;
  int repeat = 5;
  std::vector<std::string> backends; ///< vtkSMPTools backends; empty: the one at start
  bool list = false;
  /// Time each run by the CPU time of the process (all its threads) instead of the wall clock:
  /// steadier on a loaded machine, and the same as the wall clock's measure of the work with the
  /// Sequential backend; with threads it sums them, so compare threads by the wall clock.
  bool cpuTime = false;
  std::string note; ///< printed under the heading (what this build cannot compare)
};

/// Parses the command line over the benchmark's defaults. Returns -1 to go on, else the exit
/// code to stop with (0 after --help or --list, 2 after a bad argument, with the usage).
int parseOptions(int argc, char* argv[], const char* purpose, Options& options);

/// The median as defined above.
double median(std::vector<double> values);

/// Peak memory a run adds to the process, in bytes: the resident-set high-water mark is reset
/// (/proc/self/clear_refs, Linux), the run made, and the new mark compared with the resident
/// size before it (freed memory given back to the system first). -1 where Linux does not tell.
/// Measure a first run (a run that replaces an earlier output counts both while the new one is
/// built).
long long peakBytesOf(const std::function<void()>& run);

/// Runs the algorithm again from scratch.
void update(vtkAlgorithm* algorithm);

/// What a contender is: the project's filter, a peer it is compared with, or a step of the
/// core (timed, not compared).
enum class Role
{
  Tool,
  Peer,
  Phase
};

/// One timed run. Peers are compared with the tools of the same group (an empty group: with
/// every tool); `cells` gives the output cells after a run (-1: none).
struct Contender
{
  std::string name;
  Role role = Role::Tool;
  std::string group;
  std::function<void()> run;
  std::function<long long()> cells;
};

struct Measured
{
  std::string name;
  Role role = Role::Tool;
  std::string group;
  double median = 0, min = 0;
  long long cells = -1, peakBytes = -1;
};

/// The row of that name, or nullptr.
const Measured* findMeasured(const std::vector<Measured>& rows, const std::string& name);

/// The first run (peak memory), then `repeat` rounds in turns.
std::vector<Measured> timeInTurns(int repeat, const std::vector<Contender>& contenders);

/// Every requested backend in turn (vtkSMPTools::SetBackend); the backends missing from this
/// VTK are reported and skipped.
void forEachBackend(const Options& options, const std::function<void(const std::string&)>& body);

/// The report of a benchmark: prints each input's table as it is measured, the summary at
/// the end.
class Report
{
public:
  /// The heading of an input: name, dims, selected voxels, the manifest's checks.
  static void printInput(const Input& in);
  /// The table of one input under one backend, kept for the summary.
  void add(const Input& in, const std::string& backend, const std::vector<Measured>& rows);
  void printSummary() const;

private:
  struct Entry
  {
    std::string input, dims, backend;
    double voxels;
    std::vector<Measured> rows;
  };
  std::vector<Entry> Entries;
};

/// The benchmark's heading: VTK, backend, threads, load, build type, the options.
void printPreamble(const char* title, const Options& options);

/// Loads every selected input in turn and hands it to `run`.
void forEachInput(const Options& options, const std::function<void(const Input&)>& run);

/// What a benchmark measures on one input (Report::printInput, then Report::add per backend).
using Benchmark = std::function<void(const Input&, const Options&, Report&)>;

/// The whole program: parses the command line over `options` (the benchmark's defaults), prints
/// the heading, runs `benchmark` on every selected input, prints the summary; the exit code.
int runBenchmark(int argc,
  char* argv[],
  const char* title,
  const char* purpose,
  Options& options,
  const Benchmark& benchmark);

//------------------------------------------------------------------------------
// Inputs as the filters take them

/// The selection (0/1) as the point scalars ("mask", uint8) of an image with unit spacing.
vtkNew<vtkImageData> maskImageOf(const Input& in);
/// The values as the point scalars ("values", uint8).
vtkNew<vtkImageData> valueImageOf(const Input& in);
/// The labels of a label map as the point scalars ("labels"; int when above 255).
vtkNew<vtkImageData> labelImageOf(const Input& in);
/// The selection as 0/1 cell scalars of an image of (voxels + 1) points along each axis.
vtkNew<vtkImageData> cellImageOf(const Input& in);
vbr::BitVolume bitsOf(const Input& in);
/// The largest label of a label map.
int maxLabel(const Input& in);

//------------------------------------------------------------------------------
// Formatting

std::string formatMs(double seconds);
std::string formatCount(long long n);
std::string formatRatio(double r);
std::string formatFixed(double value, int digits);

/// A Markdown table with padded columns; the first column is left-aligned.
class Table
{
public:
  explicit Table(std::vector<std::string> header);
  void add(std::vector<std::string> row);
  void print() const;

private:
  std::vector<std::string> Header;
  std::vector<std::vector<std::string>> Rows;
};

} // namespace vbrbench

#endif
