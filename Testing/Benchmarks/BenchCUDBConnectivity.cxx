// Benchmark of vtkCUDBConnectivity against vtkImageConnectivityFilter (face connectivity; that
// filter exists only in stock VTK, so the comparison is printed in the stock-VTK build).
//
//   BenchCUDBConnectivity [--sizes 128,256] [--repeat 5] [--data DIR] [--no-data]
//
// For each input (phantoms of nested shells, a row of boxes and porous blobs; the real
// volumes of the shared data): the EVM, OUDB and CUDB sizes (the paper's Table 1), the
// median time of each phase run on the core alone (image -> EVM, EVM -> CUDB, CCL on the
// boxes, label write-back: the paper's Table 2), the whole filter (face and vertex), and the
// peer with the ratio (the three runs take turns). Run with VTK_SMP_BACKEND_IN_USE=STDThread to use
// every core.
#include "vtkCUDBConnectivity.h"

#include "CUDB.h"
#include "EVM.h"
#include "Phantom.h"

#include "vtkAlgorithm.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#if __has_include(<vtkImageConnectivityFilter.h>)
#include <vtkImageConnectivityFilter.h>
#define VOXELBREP_HAVE_PEER 1
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using Clock = std::chrono::steady_clock;

double medianSeconds(int repeat, const std::function<void()>& run)
{
  run(); // warm-up
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

/// Median time of each run, the runs taking turns in rotating order so that the machine's drift
/// (these VMs are noisy) falls on all of them alike.
std::vector<double> interleavedMedians(int repeat, const std::vector<std::function<void()>>& runs)
{
  std::vector<std::vector<double>> t(runs.size());
  for (int r = -1; r < repeat; ++r) // r = -1: warm-up
    for (std::size_t i = 0; i < runs.size(); ++i)
    {
      // Each round starts with another run: a run pays for what the one before it left
      // (freed memory, caches), and that must not always fall on the same one.
      const std::size_t k = (i + static_cast<std::size_t>(r + 1)) % runs.size();
      const auto t0 = Clock::now();
      runs[k]();
      if (r >= 0)
        t[k].push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    }
  std::vector<double> medians;
  for (std::vector<double>& times : t)
  {
    std::sort(times.begin(), times.end());
    medians.push_back(times[times.size() / 2]);
  }
  return medians;
}

void update(vtkAlgorithm* algorithm)
{
  algorithm->Modified();
  algorithm->Update();
}

struct Input
{
  std::string name;
  std::array<int, 3> dims;
  std::vector<unsigned char> mask; ///< 0/1, x fastest
};

Input phantom(const std::string& kind, int n)
{
  Input in{ kind + " " + std::to_string(n) + "^3", { n, n, n }, {} };
  const std::size_t count = std::size_t(n) * n * n;
  in.mask.assign(count, 0);
  if (kind == "shells")
  {
    const std::vector<std::uint8_t> labels = vbr::makePhantom({ n, n, n });
    for (std::size_t i = 0; i < count; ++i)
      in.mask[i] = labels[i] != 0;
  }
  else if (kind == "boxes") // a row of separate boxes
  {
    for (int z = n / 4; z < 3 * n / 4; ++z)
      for (int y = n / 4; y < 3 * n / 4; ++y)
        for (int x = 0; x < n; ++x)
          in.mask[(std::size_t(z) * n + y) * n + x] = (x / 4) % 2 == 0;
  }
  else // porous blobs: thresholded sum of random spheres
  {
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> c(0, n - 1);
    const int r = std::max(2, n / 20);
    for (int s = 0; s < n * n / 16; ++s)
    {
      const int cx = c(rng), cy = c(rng), cz = c(rng);
      for (int z = std::max(0, cz - r); z < std::min(n, cz + r); ++z)
        for (int y = std::max(0, cy - r); y < std::min(n, cy + r); ++y)
          for (int x = std::max(0, cx - r); x < std::min(n, cx + r); ++x)
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) < r * r)
              in.mask[(std::size_t(z) * n + y) * n + x] = 1;
    }
  }
  return in;
}

bool realVolume(const std::string& dir,
  const char* file,
  std::array<int, 3> dims,
  int lo,
  int hi,
  const char* name,
  Input& in)
{
  std::ifstream f(dir + file, std::ios::binary);
  if (!f)
    return false;
  std::vector<unsigned char> raw(std::size_t(dims[0]) * dims[1] * dims[2]);
  f.read(reinterpret_cast<char*>(raw.data()), raw.size());
  in = Input{ name, dims, std::vector<unsigned char>(raw.size()) };
  for (std::size_t i = 0; i < raw.size(); ++i)
    in.mask[i] = raw[i] >= lo && raw[i] <= hi;
  return static_cast<bool>(f);
}

vtkNew<vtkImageData> imageOf(const Input& in)
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

void run(const Input& in, int repeat)
{
  vbr::BitVolume bits(in.dims[0], in.dims[1], in.dims[2]);
  for (int z = 0; z < in.dims[2]; ++z)
    for (int y = 0; y < in.dims[1]; ++y)
      for (int x = 0; x < in.dims[0]; ++x)
        if (in.mask[(std::size_t(z) * in.dims[1] + y) * in.dims[0] + x])
          bits.set(x, y, z);
  vbr::EVM evm;
  vbr::CUDB cudb;
  vbr::Components comps;
  std::vector<std::int32_t> labels(in.mask.size());
  const double tEVM = medianSeconds(repeat, [&] { evm = vbr::extractEVM(bits); });
  const double tCUDB = medianSeconds(repeat, [&] { cudb = vbr::buildCUDB(evm); });
  const double tCCL =
    medianSeconds(repeat, [&] { comps = vbr::labelComponents(cudb, vbr::Connectivity::Face); });
  std::vector<std::int32_t> values(comps.boxLabel.begin(), comps.boxLabel.end());
  const double tPaint = medianSeconds(repeat,
    [&]
    {
      std::fill(labels.begin(), labels.end(), 0);
      vbr::paintBoxes(cudb.boxes, values, { 0, 0, 0 }, { 0, 1, 2 }, in.dims, labels.data());
    });

  vtkNew<vtkImageData> image = imageOf(in);
  vtkNew<vtkCUDBConnectivity> face;
  face->SetInputData(image);
  face->GenerateBoxesOff();
  vtkNew<vtkCUDBConnectivity> vertex;
  vertex->SetInputData(image);
  vertex->GenerateBoxesOff();
  vertex->SetConnectivityToVertex();
  std::vector<std::function<void()>> runs{ [&] { update(face); }, [&] { update(vertex); } };
#ifdef VOXELBREP_HAVE_PEER
  vtkNew<vtkImageConnectivityFilter> peer;
  peer->SetInputData(image);
  peer->SetScalarRange(1, 1);
  peer->SetExtractionModeToAllRegions();
  peer->SetLabelModeToSizeRank();
  peer->SetLabelScalarTypeToInt(); // the default (unsigned char) caps the count at 255
  runs.push_back([&] { update(peer); });
#endif
  const std::vector<double> t = interleavedMedians(repeat, runs);
  std::printf("%-18s %9zu EV %9zu OUDB %9zu CUDB %7u cc6 | EVM %7.2f  CUDB %7.2f  CCL %6.2f  "
              "write %7.2f | filter face %7.2f vertex %7.2f ms",
    in.name.c_str(),
    evm.size(),
    cudb.oudbBoxCount,
    cudb.boxes.size(),
    comps.count,
    1e3 * tEVM,
    1e3 * tCUDB,
    1e3 * tCCL,
    1e3 * tPaint,
    1e3 * t[0],
    1e3 * t[1]);
#ifdef VOXELBREP_HAVE_PEER
  std::printf(" | vtkImageConnectivityFilter %8.2f ms (%lld regions) ratio %.1fx",
    1e3 * t[2],
    static_cast<long long>(peer->GetNumberOfExtractedRegions()),
    t[2] / t[0]);
#endif
  std::printf("\n");
}

} // namespace

int main(int argc, char* argv[])
{
  std::vector<int> sizes{ 128, 256 };
  int repeat = 5;
  std::string dir = VOXELBREP_DEFAULT_DATA_DIR;
  bool data = true;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--sizes" && i + 1 < argc)
    {
      sizes.clear();
      std::stringstream s(argv[++i]);
      for (std::string v; std::getline(s, v, ',');)
        sizes.push_back(std::atoi(v.c_str()));
    }
    else if (a == "--repeat" && i + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--data" && i + 1 < argc)
      dir = argv[++i];
    else if (a == "--no-data")
      data = false;
    else
    {
      std::fprintf(
        stderr, "usage: %s [--sizes 128,256] [--repeat N] [--data DIR] [--no-data]\n", argv[0]);
      return 2;
    }
  }
#ifndef VOXELBREP_HAVE_PEER
  std::printf(
    "(vtkImageConnectivityFilter is not in this VTK: build against stock VTK to compare)\n");
#endif
  for (int n : sizes)
    for (const char* kind : { "shells", "boxes", "blobs" })
      run(phantom(kind, n), repeat);
  if (!data)
    return 0;
  Input in;
  if (realVolume(dir,
        "/aneurism/aneurism_256x256x256_uint8.raw",
        { 256, 256, 256 },
        55,
        255,
        "aneurism>=55",
        in))
    run(in, repeat);
  if (realVolume(
        dir, "/engine/engine_256x256x128_uint8.raw", { 256, 256, 128 }, 55, 255, "engine>=55", in))
    run(in, repeat);
  if (realVolume(
        dir, "/lobster/lobster_301x324x56_uint8.raw", { 301, 324, 56 }, 40, 255, "lobster>=40", in))
    run(in, repeat);
  if (realVolume(
        dir, "/berea/berea_200x200x200_uint8.raw", { 200, 200, 200 }, 0, 0, "berea pore", in))
    run(in, repeat);
  return 0;
}
