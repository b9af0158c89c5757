// The inputs of the benchmarks, by named input class, so that every benchmark runs the same
// data: procedural volumes built here (deterministic: the same bytes on every machine and
// every run) and the real volumes, label maps and 2D images of the shared data
// (VOXELBREP_DATA_DIR, see its MANIFEST.md), each with the selection the manifest gives.
//
// Classes (`--inputs`):
//  - phantom: vbr::makePhantom (nested shells, handle, pierced plate, frame, non-manifold
//    contacts), label > 0, n^3 for n in --sizes;
//  - boxes: a row of separate boxes; blobs: a union of random balls (n^3);
//  - balls: the polyhedrization paper's sphere (r^2 <= 240), its hexahedron and balls of the
//    radii in --radii;
//  - pacman: the convex hull paper's pac-man (a ball of radius 11 without its mouth);
//  - solids: a ball, a torus and a CSG solid (box and cylinder less a ball) of n^3 voxels;
//  - porous: Gaussian-filtered white noise (sigma 2 voxels) thresholded so that exactly
//    the --solid percentage of voxels is solid, n^3, one volume per seed in --seeds;
//  - checkerboard: the 3D checkerboard of single voxels (every voxel face a face); noise: 50 %
//    random voxels; porous2d: the porous construction on n^2 images (--sizes2d);
//  - compact: N^3 labels of 2^3 voxels each (a label map), N in --labels;
//  - berea, volumes, labelmaps, images2d: the shared data (skipped when absent; --quick keeps
//    only the small files, the mazes need --large).
#ifndef vbr_BenchInputs_h
#define vbr_BenchInputs_h

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vbrbench
{

/// One input: uint8 values, x fastest, with the selection lo <= v <= hi. A label map
/// (labels = true) holds its labels (0 background; the selection is every label > 0).
struct Input
{
  std::string name;
  std::string inputClass;
  std::array<int, 3> dims{ 0, 0, 0 };
  std::vector<std::uint8_t> values;
  std::vector<std::int32_t> wideLabels; ///< labels above 255 (compact), else empty: values
  int lo = 1, hi = 255;
  bool labels = false;
  long long expectedSelected = -1;        ///< the manifest's foreground count, when known
  long long expectedExtremeVertices = -1; ///< the manifest's (and papers') EV count

  std::size_t voxelCount() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
  bool is2D() const { return dims[2] == 1; }
  bool selected(std::size_t i) const { return values[i] >= lo && values[i] <= hi; }
  std::uint8_t& at(int x, int y, int z)
  {
    return this->values[(std::size_t(z) * this->dims[1] + y) * this->dims[0] + x];
  }
};

/// What selects the inputs (the input part of the benchmarks' options).
struct InputOptions
{
  std::vector<std::string> classes;
  std::vector<int> sizes{ 128 }, sizes2D{ 1024 }, seeds{ 1, 2 }, solid{ 30, 45, 60 };
  std::vector<int> radii{ 8, 16, 32, 64 }, labels{ 8, 16, 24 };
  std::string dataDir;
  bool data = true, quick = false, large = false;
};

/// An input not built yet: `load` fills it and returns false when its file is absent.
struct InputSpec
{
  std::string name;
  std::string inputClass;
  std::function<bool(Input&)> load;
};

/// The items of a comma-separated list.
std::vector<std::string> splitList(const std::string& text);

/// Every input class, in the order the benchmarks run them.
const std::vector<std::string>& inputClasses();

/// The inputs the options select, in class order (nothing is loaded yet).
std::vector<InputSpec> selectInputs(const InputOptions& options);

/// Loads one input; false (after a note on stdout) when its file is absent or short.
bool loadInput(const InputSpec& spec, Input& in);

/// Selected voxels of an input.
std::size_t selectedCount(const Input& in);

/// Whether a selected voxel lies on the border of the image (DFE leaves such surfaces open).
bool touchesBorder(const Input& in);

/// The input's `--list` line: name, class, and whether it is a label map.
std::string describe(const InputSpec& spec);

} // namespace vbrbench

#endif
