// What the benchmark programs share: the inputs as 0/1 masks (phantoms built in the program,
// real volumes read and thresholded from the shared data), their VTK image and voxel set,
// median timing and the command line.
#ifndef vbr_BenchCommon_h
#define vbr_BenchCommon_h

#include "BitVolume.h"

#include "vtkAlgorithm.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <sstream>
#include <string>
#include <vector>

namespace vbrbench
{

using Clock = std::chrono::steady_clock;

/// Median time of `repeat` runs after one warm-up run.
inline double medianSeconds(int repeat, const std::function<void()>& run)
{
  run();
  std::vector<double> t;
  for (int r = 0; r < repeat; ++r)
  {
    const auto t0 = Clock::now();
    run();
    t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// A field of /proc/self/status in kiB (VmRSS, VmHWM), or -1.
inline long long procStatusKiB(const std::string& field)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, field.size() + 1, field + ":") == 0)
      return std::atoll(line.c_str() + field.size() + 1);
  return -1;
}

/// Peak memory a run adds to the process, in bytes: the resident-set high-water mark is reset
/// (/proc/self/clear_refs, Linux), the run made, and the new mark compared with the resident
/// size before it (freed memory given back to the system first). -1 where Linux does not tell.
/// Measure a first run (a run that replaces an earlier output counts both while the new one is
/// built).
inline long long peakBytesOf(const std::function<void()>& run)
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

/// Runs the algorithm again from scratch.
inline void update(vtkAlgorithm* algorithm)
{
  algorithm->Modified();
  algorithm->Update();
}

/// A named 0/1 voxel mask, x fastest.
struct Input
{
  std::string name;
  std::array<int, 3> dims{ 0, 0, 0 };
  std::vector<unsigned char> mask;

  unsigned char& at(int x, int y, int z)
  {
    return this->mask[(std::size_t(z) * this->dims[1] + y) * this->dims[0] + x];
  }
};

/// An empty mask of the given dimensions.
inline Input emptyInput(const std::string& name, const std::array<int, 3>& dims)
{
  return Input{ name, dims, std::vector<unsigned char>(std::size_t(dims[0]) * dims[1] * dims[2]) };
}

/// A real volume of the shared data (uint8 raw) thresholded to lo <= v <= hi; false when
/// the file is absent or short.
inline bool readThresholded(const std::string& path,
  const std::array<int, 3>& dims,
  int lo,
  int hi,
  const std::string& name,
  Input& in)
{
  std::ifstream f(path, std::ios::binary);
  if (!f)
    return false;
  in = emptyInput(name, dims);
  f.read(reinterpret_cast<char*>(in.mask.data()), static_cast<std::streamsize>(in.mask.size()));
  for (unsigned char& v : in.mask)
    v = v >= lo && v <= hi;
  return static_cast<bool>(f);
}

inline vbr::BitVolume bitsOf(const Input& in)
{
  vbr::BitVolume bits(in.dims[0], in.dims[1], in.dims[2]);
  std::size_t i = 0;
  for (int z = 0; z < in.dims[2]; ++z)
    for (int y = 0; y < in.dims[1]; ++y)
      for (int x = 0; x < in.dims[0]; ++x, ++i)
        if (in.mask[i])
          bits.set(x, y, z);
  return bits;
}

/// The mask as the point scalars ("mask", uint8) of an image with unit spacing.
inline vtkNew<vtkImageData> imageOf(const Input& in)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(in.dims.data());
  vtkNew<vtkUnsignedCharArray> a;
  a->SetName("mask");
  a->SetNumberOfTuples(static_cast<vtkIdType>(in.mask.size()));
  std::copy(in.mask.begin(), in.mask.end(), a->GetPointer(0));
  image->GetPointData()->SetScalars(a);
  return image;
}

/// The command line of the benchmarks: `--<listName> a,b,c` (sizes or radii),
/// `--repeat N`, `--data DIR`, `--no-data`.
struct Arguments
{
  std::vector<int> list;
  int repeat = 5;
  std::string dataDir;
  bool data = true;
};

/// False (after printing the usage) on an unknown argument.
inline bool parseArguments(int argc, char* argv[], const std::string& listName, Arguments& args)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--" + listName && i + 1 < argc)
    {
      args.list.clear();
      std::stringstream s(argv[++i]);
      for (std::string v; std::getline(s, v, ',');)
        args.list.push_back(std::atoi(v.c_str()));
    }
    else if (a == "--repeat" && i + 1 < argc)
      args.repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--data" && i + 1 < argc)
      args.dataDir = argv[++i];
    else if (a == "--no-data")
      args.data = false;
    else
    {
      std::fprintf(stderr,
        "usage: %s [--%s a,b,...] [--repeat N] [--data DIR] [--no-data]\n",
        argv[0],
        listName.c_str());
      return false;
    }
  }
  return true;
}

} // namespace vbrbench

#endif
