// Execution context of the algorithm core: how to run loops in parallel and how to report
// progress, supplied by the caller so that the core stays free of any toolkit.
#ifndef vbr_Execution_h
#define vbr_Execution_h

#include <cstdint>
#include <functional>

namespace vbr
{

/// Runs body(begin, end) over sub-ranges covering [0, n), possibly concurrently.
using ParallelFor =
  std::function<void(std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body)>;

struct Execution
{
  /// Parallel loop; empty means sequential.
  ParallelFor parallelFor;
  /// Receives the fraction done in [0, 1] between phases (on the calling thread only);
  /// returns false to abort.
  std::function<bool(double)> progress;
  /// Whether the caller asked to stop; polled from any thread inside long loops.
  std::function<bool()> aborted;
  /// How many threads parallelFor may use: splits work that parallelizes only by pieces.
  int concurrency = 1;

  void forRange(std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body) const
  {
    if (n <= 0)
    {
      return;
    }
    if (this->parallelFor)
    {
      this->parallelFor(n, body);
    }
    else
    {
      body(0, n);
    }
  }

  /// Reports progress; returns false when the caller asked to abort.
  bool report(double fraction) const { return !this->progress || this->progress(fraction); }

  bool stopRequested() const { return this->aborted && this->aborted(); }
};

} // namespace vbr

#endif
