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

#include "BenchCommon.h"

#include "vtkAlgorithm.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#if __has_include(<vtkImageConnectivityFilter.h>)
#include <vtkImageConnectivityFilter.h>
#define VOXELBREP_HAVE_PEER 1
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{

using namespace vbrbench;

/// Every `step`-th selected voxel's centre as a seed point (the image has origin 0, spacing 1).
vtkNew<vtkPolyData> seedsOf(const Input& in, std::size_t step)
{
  vtkNew<vtkPoints> points;
  std::size_t selected = 0;
  for (std::size_t i = 0; i < in.mask.size(); ++i)
    if (in.mask[i] && selected++ % step == 0)
      points->InsertNextPoint(static_cast<double>(i % in.dims[0]),
        static_cast<double>(i / in.dims[0] % in.dims[1]),
        static_cast<double>(i / (std::size_t(in.dims[0]) * in.dims[1])));
  vtkNew<vtkPolyData> seeds;
  seeds->SetPoints(points);
  return seeds;
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

Input phantom(const std::string& kind, int n)
{
  Input in = emptyInput(kind + " " + std::to_string(n) + "^3", { n, n, n });
  const std::size_t count = in.mask.size();
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

void run(const Input& in, int repeat)
{
  const vbr::BitVolume bits = bitsOf(in);
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
  // Seeds: every 16th selected voxel (cost linear in the seeds, not seeds x boxes).
  vtkNew<vtkPolyData> seeds = seedsOf(in, 16);
  vtkNew<vtkCUDBConnectivity> seeded;
  seeded->SetInputData(image);
  seeded->GenerateBoxesOff();
  seeded->SetSeedData(seeds);
  std::vector<std::function<void()>> runs{
    [&] { update(face); }, [&] { update(vertex); }, [&] { update(seeded); }
  };
#ifdef VOXELBREP_HAVE_PEER
  vtkNew<vtkImageConnectivityFilter> peer;
  peer->SetInputData(image);
  peer->SetScalarRange(1, 1);
  peer->SetExtractionModeToAllRegions();
  peer->SetLabelModeToSizeRank();
  peer->SetLabelScalarTypeToInt(); // the default (unsigned char) caps the count at 255
  runs.push_back([&] { update(peer); });
#endif
  const long long peak = peakBytesOf([&] { update(face); }); // a first run, face connectivity
  const std::vector<double> t = interleavedMedians(repeat, runs);
  std::printf("%-18s %9zu EV %9zu OUDB %9zu CUDB %7u cc6 | EVM %7.2f  CUDB %7.2f  CCL %6.2f  "
              "write %7.2f | filter face %7.2f vertex %7.2f seeded (%lld) %7.2f ms",
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
    1e3 * t[1],
    static_cast<long long>(seeds->GetNumberOfPoints()),
    1e3 * t[2]);
  std::printf(" | peak %.1f bytes per voxel, %.0f per box",
    double(peak) / double(std::max<std::size_t>(in.mask.size(), 1)),
    double(peak) / double(std::max<std::size_t>(cudb.boxes.size(), 1)));
#ifdef VOXELBREP_HAVE_PEER
  std::printf(" | vtkImageConnectivityFilter %8.2f ms (%lld regions) ratio %.1fx",
    1e3 * t[3],
    static_cast<long long>(peer->GetNumberOfExtractedRegions()),
    t[3] / t[0]);
#endif
  std::printf("\n");
}

} // namespace

int main(int argc, char* argv[])
{
  Arguments args;
  args.list = { 128, 256 };
  args.dataDir = VOXELBREP_DEFAULT_DATA_DIR;
  if (!parseArguments(argc, argv, "sizes", args))
    return 2;
#ifndef VOXELBREP_HAVE_PEER
  std::printf(
    "(vtkImageConnectivityFilter is not in this VTK: build against stock VTK to compare)\n");
#endif
  for (int n : args.list)
    for (const char* kind : { "shells", "boxes", "blobs" })
      run(phantom(kind, n), args.repeat);
  if (!args.data)
    return 0;
  struct Real
  {
    const char* file;
    std::array<int, 3> dims;
    int lo, hi;
    const char* name;
  };
  const Real volumes[] = {
    { "/aneurism/aneurism_256x256x256_uint8.raw", { 256, 256, 256 }, 55, 255, "aneurism>=55" },
    { "/engine/engine_256x256x128_uint8.raw", { 256, 256, 128 }, 55, 255, "engine>=55" },
    { "/lobster/lobster_301x324x56_uint8.raw", { 301, 324, 56 }, 40, 255, "lobster>=40" },
    { "/berea/berea_200x200x200_uint8.raw", { 200, 200, 200 }, 0, 0, "berea pore" },
  };
  for (const Real& r : volumes)
  {
    Input in;
    if (readThresholded(args.dataDir + r.file, r.dims, r.lo, r.hi, r.name, in))
      run(in, args.repeat);
  }
  return 0;
}
