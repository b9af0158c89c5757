// Test images shared by the filter tests: random voxel volumes with labels, carried by a
// vtkImageData in a chosen layout (point or cell scalars, type, extent, origin, spacing).
#ifndef vbr_TestImages_h
#define vbr_TestImages_h

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <array>
#include <cstddef>
#include <iostream>
#include <random>
#include <vector>

namespace vbrtest
{

/// Checks that failed in this test (each test runs in a process of its own).
inline int& failedChecks()
{
  static int count = 0;
  return count;
}

/// The test's exit code, after printing how many checks failed.
inline int testResult()
{
  if (failedChecks())
    std::cerr << failedChecks() << " check(s) failed" << std::endl;
  return failedChecks() == 0 ? 0 : 1;
}

/// A check that reports its line and message and lets the test go on.
#define CHECK(cond, msg)                                                                           \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __LINE__ << ": " << msg << std::endl;                                           \
      ++vbrtest::failedChecks();                                                                   \
    }                                                                                              \
  } while (false)

using Int3 = std::array<int, 3>;

/// A voxel volume with values, as the test builds it.
struct Volume
{
  Int3 dims{ 0, 0, 0 };
  std::vector<int> values;
  int at(int x, int y, int z) const
  {
    if (x < 0 || y < 0 || z < 0 || x >= dims[0] || y >= dims[1] || z >= dims[2])
      return 0;
    return values[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x];
  }
};

inline Volume randomVolume(const Int3& dims, double density, int labels, unsigned seed)
{
  Volume v;
  v.dims = dims;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  v.values.resize(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
  for (int& x : v.values)
    x = u(rng) < density ? 1 + static_cast<int>(u(rng) * labels) % labels : 0;
  return v;
}

/// How the image carries the voxels.
struct Layout
{
  bool cellData = false;
  Int3 extentMin{ 0, 0, 0 };
  std::array<double, 3> origin{ 0, 0, 0 };
  std::array<double, 3> spacing{ 1, 1, 1 };
  int scalarType = VTK_UNSIGNED_CHAR;
};

inline vtkSmartPointer<vtkImageData> makeImage(const Volume& v, const Layout& l)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  const int add = l.cellData ? 1 : 0;
  image->SetExtent(l.extentMin[0],
    l.extentMin[0] + v.dims[0] - 1 + add,
    l.extentMin[1],
    l.extentMin[1] + v.dims[1] - 1 + add,
    l.extentMin[2],
    l.extentMin[2] + v.dims[2] - 1 + add);
  image->SetOrigin(l.origin.data());
  image->SetSpacing(l.spacing.data());
  vtkSmartPointer<vtkDataArray> a;
  a.TakeReference(vtkDataArray::CreateDataArray(l.scalarType));
  a->SetName("values");
  a->SetNumberOfTuples(static_cast<vtkIdType>(v.values.size()));
  for (std::size_t i = 0; i < v.values.size(); ++i)
    a->SetTuple1(static_cast<vtkIdType>(i), v.values[i]);
  if (l.cellData)
    image->GetCellData()->SetScalars(a);
  else
    image->GetPointData()->SetScalars(a);
  return image;
}

/// Aborts the algorithm at its first progress event.
class AbortAtProgress : public vtkCommand
{
public:
  static AbortAtProgress* New() { return new AbortAtProgress; }
  void Execute(vtkObject* caller, unsigned long, void*) override
  {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    ++this->Calls;
  }
  int Calls = 0;
};

/// Counts the error events it observes.
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void*) override { ++this->Count; }
  int Count = 0;
};

/// Updates the algorithm and returns the number of errors it and its executive raised.
inline int updateCountingErrors(vtkAlgorithm* algorithm)
{
  vtkNew<ErrorCounter> errors;
  const unsigned long a = algorithm->AddObserver(vtkCommand::ErrorEvent, errors);
  const unsigned long e = algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  algorithm->Update();
  algorithm->RemoveObserver(a);
  algorithm->GetExecutive()->RemoveObserver(e);
  return errors->Count;
}

} // namespace vbrtest

#endif
