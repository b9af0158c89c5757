// vtkStandardPlanePolyhedrizer on long runs: an abort asked from a progress observer in the
// middle of each phase of the faces (growth, moves to larger faces, merging, loops) stops
// the filter within that phase, with empty outputs and no error, and so does an abort in the
// middle of Labels mode's objects (made in batches when threaded); a selection of millions of
// surfels raises a warning that says how large it is and what to do.
#include "vtkStandardPlanePolyhedrizer.h"

#include "TestImages.h"

#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <string>

namespace
{

using Clock = std::chrono::steady_clock;

/// Sets the abort flag at the first progress strictly inside (from, to); records the
/// highest progress seen and when the abort was asked.
class AbortInside : public vtkCommand
{
public:
  static AbortInside* New() { return new AbortInside; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    const double p = *static_cast<double*>(data);
    if (p < 1.0) // the executive reports 1 at the end of every execution
      this->Highest = std::max(this->Highest, p);
    if (!this->Asked && p > this->From && p < this->To)
    {
      this->Asked = true;
      this->When = Clock::now();
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    }
  }
  double From = 0, To = 1, Highest = 0;
  bool Asked = false;
  Clock::time_point When;
};

/// Sets the abort flag at the first warning, keeps its text and records when it came.
class AbortAtWarning : public vtkCommand
{
public:
  static AbortAtWarning* New() { return new AbortAtWarning; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    if (this->Text.empty())
      this->When = Clock::now();
    this->Text += static_cast<const char*>(data);
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  }
  std::string Text;
  Clock::time_point When;
};

/// The filter's progress of a point of the faces' phases for a single object: the object
/// spans 0.05 - 0.9, its faces the last 85 % of that; the core's phases are growth 0 - 0.6,
/// moves 0.6 - 0.7, merging 0.7 - 0.95, loops 0.95 - 1 (Polyhedrization.cxx).
double filterProgress(double phase)
{
  const double faces = 0.05 + 0.15 * 0.85;
  return faces + (0.9 - faces) * phase;
}

void checkAbortInEachPhase()
{
  const vbrtest::Volume noise = vbrtest::randomVolume({ 40, 40, 40 }, 0.5, 1, 5);
  const auto image = vbrtest::makeImage(noise, vbrtest::Layout());
  const struct
  {
    const char* name;
    double from, to;
  } phases[] = {
    { "growth", 0.0, 0.6 }, { "moves", 0.6, 0.7 }, { "merging", 0.7, 0.95 }, { "loops", 0.95, 1.0 }
  };
  for (const auto& phase : phases)
  {
    vtkNew<vtkStandardPlanePolyhedrizer> f;
    f->SetInputData(image);
    f->MergeFacesOn();
    vtkNew<AbortInside> abort;
    abort->From = filterProgress(phase.from);
    abort->To = filterProgress(phase.to);
    f->AddObserver(vtkCommand::ProgressEvent, abort);
    const int errors = vbrtest::updateCountingErrors(f);
    const std::string what = std::string("abort in ") + phase.name;
    CHECK(abort->Asked, what << ": no progress inside the phase");
    if (!abort->Asked)
      continue;
    const double seconds = std::chrono::duration<double>(Clock::now() - abort->When).count();
    CHECK(seconds < 2.0, what << ": " << seconds << " s after the abort"); // sanitizers too
    CHECK(abort->Highest < abort->To, what << ": progress went on to " << abort->Highest);
    CHECK(errors == 0, what << ": " << errors << " errors");
    CHECK(f->GetOutput()->GetNumberOfCells() == 0, what << ": faces left");
    auto* reversion = vtkImageData::SafeDownCast(f->GetOutputDataObject(1));
    CHECK(reversion && reversion->GetPointData()->GetArray("Selection") == nullptr,
      what << ": a reversion left");
  }
}

/// Labels mode on 20 labels, or 8 per thread and one more (in batches of objects on threads,
/// about eight batches, the progress moving between them; one object at a time on one
/// thread): an abort asked when a third of the objects is done stops the filter before the
/// next objects, with empty outputs and no error; not aborted, the labels have faces.
void checkAbortInLabelsMode()
{
  const int count = std::max(20, 8 * vtkSMPTools::GetEstimatedNumberOfThreads() + 1);
  const vbrtest::Volume labels = vbrtest::randomVolume({ 32, 32, 32 }, 0.9, count, 7);
  const auto image = vbrtest::makeImage(labels, vbrtest::Layout());
  vtkNew<vtkStandardPlanePolyhedrizer> whole;
  whole->SetInputData(image);
  whole->SetSelectionModeToLabels();
  CHECK(vbrtest::updateCountingErrors(whole) == 0, "labels: errors");
  CHECK(whole->GetOutput()->GetNumberOfCells() > 0, "labels: no faces");
  vtkNew<vtkStandardPlanePolyhedrizer> f;
  f->SetInputData(image);
  f->SetSelectionModeToLabels();
  vtkNew<AbortInside> abort;
  abort->From = 0.05 + 0.85 / 3.0;
  abort->To = 0.9;
  f->AddObserver(vtkCommand::ProgressEvent, abort);
  const int errors = vbrtest::updateCountingErrors(f);
  CHECK(abort->Asked, "labels: no progress inside the objects");
  CHECK(abort->Highest < abort->To, "labels: progress went on to " << abort->Highest);
  CHECK(errors == 0, "labels: " << errors << " errors after the abort");
  CHECK(f->GetOutput()->GetNumberOfCells() == 0, "labels: faces left after the abort");
  auto* reversion = vtkImageData::SafeDownCast(f->GetOutputDataObject(1));
  CHECK(reversion && reversion->GetPointData()->GetArray("Selection") == nullptr,
    "labels: a reversion left after the abort");
}

void checkWarningBeforeLargeWork()
{
  // A 96^3 checkerboard: every selected voxel alone, 6 surfels each (2.65 M in all).
  vbrtest::Volume board;
  board.dims = { 96, 96, 96 };
  board.values.resize(96 * 96 * 96);
  for (int z = 0; z < 96; ++z)
    for (int y = 0; y < 96; ++y)
      for (int x = 0; x < 96; ++x)
        board.values[(z * 96 + y) * 96 + x] = (x + y + z) % 2;
  vtkNew<vtkStandardPlanePolyhedrizer> f;
  f->SetInputData(vbrtest::makeImage(board, vbrtest::Layout()));
  vtkNew<AbortAtWarning> warning;
  f->AddObserver(vtkCommand::WarningEvent, warning);
  f->Update();
  // Timed from the warning, not from the start: on a loaded CI machine the selection and the
  // surfel count before it may take seconds; a run not aborted takes minutes.
  const double seconds = std::chrono::duration<double>(Clock::now() - warning->When).count();
  CHECK(warning->Text.find("2654208 boundary surfels") != std::string::npos,
    "large selection: warning says how large (got '" << warning->Text << "')");
  CHECK(
    warning->Text.find("Range") != std::string::npos, "large selection: warning says what to do");
  CHECK(!warning->Text.empty() && seconds < 5,
    "large selection: aborted at the warning, yet " << seconds << " s after it");
  CHECK(f->GetOutput()->GetNumberOfCells() == 0, "large selection: aborted, no faces");

  // Small inputs do not warn.
  vtkNew<vtkStandardPlanePolyhedrizer> small;
  small->SetInputData(
    vbrtest::makeImage(vbrtest::randomVolume({ 12, 12, 12 }, 0.5, 1, 3), vbrtest::Layout()));
  vtkNew<AbortAtWarning> none;
  small->AddObserver(vtkCommand::WarningEvent, none);
  small->Update();
  CHECK(none->Text.empty(), "small selection: no warning (got '" << none->Text << "')");
}

} // namespace

int TestStandardPlanePolyhedrizerLongRuns(int, char*[])
{
  checkAbortInEachPhase();
  checkAbortInLabelsMode();
  checkWarningBeforeLargeWork();
  return vbrtest::testResult();
}
