// Execution context of the algorithm core: how to run loops in parallel and how to report
// progress, supplied by the caller so that the core stays free of any toolkit.
#ifndef vbr_Execution_h
#define vbr_Execution_h

#include <chrono>
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

  /// Work items (voxels, corners) below which a step runs on the calling thread: a parallel
  /// loop costs a thread start-up with some SMP backends (VTK's STDThread), which made a label
  /// map of many small labels 40x to 80x slower with two threads than with one.
  static constexpr std::int64_t ThreadedWorkMinimum = std::int64_t(1) << 15;

  /// The same execution on the calling thread alone.
  Execution sequential() const
  {
    Execution e = *this;
    e.parallelFor = nullptr;
    e.concurrency = 1;
    return e;
  }

  /// The same execution reporting its progress [0, 1] as [from, to] of this one's: a phase
  /// that reports its own progress, run as one part of a longer job.
  Execution within(double from, double to) const
  {
    Execution e = *this;
    if (this->progress)
      e.progress = [outer = this->progress, from, to](double f)
      { return outer(from + (to - from) * f); };
    return e;
  }

  /// The same execution without progress reports (it still polls the abort): for a phase run
  /// many times over, whose own fractions would make the reported progress jump back.
  Execution silent() const
  {
    Execution e = *this;
    e.progress = nullptr;
    return e;
  }

  /// This execution for `work` items, or the same on the calling thread alone when they are
  /// too few to pay for the threads (ThreadedWorkMinimum).
  Execution forWork(std::int64_t work) const
  {
    return work < ThreadedWorkMinimum ? this->sequential() : *this;
  }

  void forRange(std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& body) const
  {
    if (n <= 0)
      return;
    if (this->parallelFor)
      this->parallelFor(n, body);
    else
      body(0, n);
  }

  /// Reports progress; returns false when the caller asked to abort.
  bool report(double fraction) const { return !this->progress || this->progress(fraction); }

  bool stopRequested() const { return this->aborted && this->aborted(); }
};

/// Progress and abort inside one long sequential loop, on the calling thread: tick() once
/// per step of work (however uneven); every `stride` steps it asks whether to stop, and
/// every 16 of those or every 100 ms, whichever comes first, it reports the phase's
/// progress, `fraction` of the way from `from` to `to`. Once stopped, it stays stopped.
class ProgressPoll
{
public:
  ProgressPoll(const Execution& exec, double from, double to, std::uint32_t stride = 64)
    : Exec(exec)
    , From(from)
    , To(to)
    , Stride(stride)
    , Last(std::chrono::steady_clock::now())
  {
  }

  /// Where the phase is, in [0, 1] (reported at the next poll).
  void at(double fraction) { this->Fraction = fraction; }

  /// Whether the next tick polls: a caller whose fraction costs something to compute (a
  /// division per face) sets it only then, at() being read by poll() alone.
  bool due() const { return this->Count + 1 >= this->Stride; }

  /// Counts a step; returns false when the caller asked to stop.
  bool tick()
  {
    if (++this->Count < this->Stride)
      return !this->Stopped;
    return this->poll();
  }

  /// Asks now; returns false when the caller asked to stop.
  bool poll()
  {
    this->Count = 0;
    if (this->Stopped)
      return false;
    this->Stopped = this->Exec.stopRequested();
    const auto now = std::chrono::steady_clock::now();
    if (!this->Stopped &&
      (++this->Polls >= 16 || now - this->Last >= std::chrono::milliseconds(100)))
    {
      this->Last = now;
      this->Polls = 0;
      this->Stopped = !this->Exec.report(this->From + (this->To - this->From) * this->Fraction);
    }
    return !this->Stopped;
  }

  bool stopped() const { return this->Stopped; }

private:
  const Execution& Exec;
  double From, To;
  double Fraction = 0.0;
  std::uint32_t Stride;
  std::uint32_t Count = 0;
  std::uint32_t Polls = 0;
  bool Stopped = false;
  std::chrono::steady_clock::time_point Last;
};

} // namespace vbr

#endif
