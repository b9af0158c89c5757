#include "BenchInputs.h"

#include "Phantom.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTIFFReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#ifdef VOXELBREP_HAVE_LIBTIFF
#include <tiffio.h>
#endif
#include <sstream>

namespace vbrbench
{
namespace
{

//------------------------------------------------------------------------------
// Procedural inputs

Input emptyInput(const std::string& name, const std::string& cls, const std::array<int, 3>& dims)
{
  Input in;
  in.name = name;
  in.inputClass = cls;
  in.dims = dims;
  in.values.assign(in.voxelCount(), 0);
  return in;
}

std::string cube(int n)
{
  return std::to_string(n) + "^3";
}

/// SplitMix64 (Steele, Lea, Flood 2014): a counter-based generator, so that voxel i of a
/// volume has the same random value on every machine, whatever the order of evaluation.
std::uint64_t splitMix64(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

/// One pass of a normalised Gaussian (radius 3 sigma, borders clamped) along `axis`.
void blurAxis(std::vector<float>& v, const std::array<int, 3>& dims, int axis, double sigma)
{
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<float> kernel(2 * radius + 1);
  double sum = 0;
  for (int k = -radius; k <= radius; ++k)
    sum += kernel[k + radius] = static_cast<float>(std::exp(-0.5 * k * k / (sigma * sigma)));
  for (float& k : kernel)
    k = static_cast<float>(k / sum);
  const std::size_t stride = axis == 0 ? 1 : (axis == 1 ? dims[0] : std::size_t(dims[0]) * dims[1]);
  const int n = dims[axis];
  const std::size_t lines = v.size() / n;
  std::vector<float> line(n);
  for (std::size_t l = 0; l < lines; ++l)
  {
    // The first voxel of line l: lines run along `axis`, the others in storage order.
    const std::size_t start = (l / stride) * stride * n + l % stride;
    for (int i = 0; i < n; ++i)
      line[i] = v[start + i * stride];
    for (int i = 0; i < n; ++i)
    {
      float acc = 0;
      for (int k = -radius; k <= radius; ++k)
        acc += kernel[k + radius] * line[std::min(n - 1, std::max(0, i + k))];
      v[start + i * stride] = acc;
    }
  }
}

std::string porousName(const std::array<int, 3>& dims, int solidPercent, int seed)
{
  const std::string size = dims[2] == 1 ? std::to_string(dims[0]) + "^2" : cube(dims[0]);
  return "porous " + size + " " + std::to_string(solidPercent) + "% s" + std::to_string(seed);
}

/// Gaussian-filtered white noise thresholded so that `solidPercent` of the voxels are solid
/// (selected): the porous inputs. Deterministic for a seed.
Input porous(const std::array<int, 3>& dims, int solidPercent, int seed)
{
  const bool flat = dims[2] == 1;
  Input in = emptyInput(porousName(dims, solidPercent, seed), flat ? "porous2d" : "porous", dims);
  std::vector<float> v(in.voxelCount());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = static_cast<float>(splitMix64((std::uint64_t(seed) << 40) ^ i) >> 11) * 0x1p-53f;
  for (int axis = 0; axis < (flat ? 2 : 3); ++axis)
    blurAxis(v, dims, axis, 2.0);
  std::vector<float> sorted(v);
  const std::size_t solid = v.size() * solidPercent / 100;
  std::nth_element(sorted.begin(), sorted.begin() + solid, sorted.end());
  const float threshold = solid < sorted.size() ? sorted[solid] : 2.0f;
  for (std::size_t i = 0; i < v.size(); ++i)
    in.values[i] = v[i] < threshold;
  return in;
}

Input phantom(int n)
{
  Input in = emptyInput("phantom " + cube(n), "phantom", { n, n, n });
  in.values = vbr::makePhantom({ n, n, n });
  return in;
}

Input boxes(int n)
{
  Input in = emptyInput("boxes " + cube(n), "boxes", { n, n, n });
  for (int z = n / 4; z < 3 * n / 4; ++z)
    for (int y = n / 4; y < 3 * n / 4; ++y)
      for (int x = 0; x < n; ++x)
        in.at(x, y, z) = (x / 4) % 2 == 0;
  return in;
}

/// A union of random balls (radius n/20, n^2/16 of them).
Input blobs(int n)
{
  Input in = emptyInput("blobs " + cube(n), "blobs", { n, n, n });
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
            in.at(x, y, z) = 1;
  }
  return in;
}

Input ball(const std::string& name, long radiusSquared)
{
  int r = 0;
  while (long(r) * r <= radiusSquared)
    ++r;
  const int n = 2 * r + 1, c = r;
  Input in = emptyInput(name, "balls", { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        in.at(x, y, z) =
          long(x - c) * (x - c) + long(y - c) * (y - c) + long(z - c) * (z - c) <= radiusSquared;
  return in;
}

/// A hexahedron, the intersection of six half-spaces: |n_i . centre| <= h_i for the
/// orthogonal integer normals (2, 2, 1), (-2, 1, 2), (1, -2, 2) (a box turned about two
/// axes) and h = (17, 17, 29), which gives the 1,962 surfels of the polyhedrization paper's
/// hexahedron (whose exact half-spaces the paper does not give).
Input hexahedron()
{
  const int n = 33, c = 16;
  const int normals[3][3] = { { 2, 2, 1 }, { -2, 1, 2 }, { 1, -2, 2 } };
  const int half[3] = { 17, 17, 29 };
  Input in = emptyInput("hexahedron", "balls", { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        bool inside = true;
        for (int i = 0; i < 3; ++i)
          inside = inside &&
            std::abs(normals[i][0] * (x - c) + normals[i][1] * (y - c) + normals[i][2] * (z - c)) <=
              half[i];
        in.at(x, y, z) = inside;
      }
  return in;
}

/// The convex hull paper's pac-man: a ball of radius r (voxel centres within r of the centre,
/// r + 1 voxels from the border) without its mouth, the wedge |y| < 0.6 x on the positive x
/// side.
Input pacman(int r)
{
  const int n = 2 * r + 3;
  const double c = r + 1;
  Input in = emptyInput("pac-man r=" + std::to_string(r), "pacman", { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        const double dx = x - c, dy = y - c, dz = z - c;
        const bool mouth = dx > 0 && std::abs(dy) < 0.6 * dx;
        in.at(x, y, z) = dx * dx + dy * dy + dz * dz <= double(r) * r && !mouth;
      }
  return in;
}

/// A smooth solid of n^3 voxels: the voxels whose centre, in [-0.5, 0.5]^3, is inside.
Input solid(const std::string& shape, int n, const std::function<bool(double, double, double)>& f)
{
  Input in = emptyInput(shape + " " + cube(n), "solids", { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        in.at(x, y, z) = f((x + 0.5) / n - 0.5, (y + 0.5) / n - 0.5, (z + 0.5) / n - 0.5);
  return in;
}

double square(double x)
{
  return x * x;
}

/// The face octree paper's kind of solids: a ball, a torus, and a CSG solid (a box united
/// with a cylinder, less a ball).
Input smoothSolid(const std::string& shape, int n)
{
  if (shape == "ball")
    return solid(shape,
      n,
      [](double x, double y, double z)
      { return square(x) + square(y) + square(z) < square(0.38); });
  if (shape == "torus")
    return solid(shape,
      n,
      [](double x, double y, double z)
      { return square(std::sqrt(square(x) + square(y)) - 0.27) + square(z) < square(0.13); });
  return solid(shape,
    n,
    [](double x, double y, double z)
    {
      const bool box = std::abs(x + 0.05) < 0.3 && std::abs(y) < 0.2 && std::abs(z) < 0.3;
      const bool cylinder = square(x - 0.2) + square(y) < square(0.18) && std::abs(z) < 0.4;
      const bool hole = square(x + 0.15) + square(y) + square(z - 0.3) < square(0.2);
      return (box || cylinder) && !hole;
    });
}

Input checkerboard(int n)
{
  Input in = emptyInput("checkerboard " + cube(n), "checkerboard", { n, n, n });
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        in.at(x, y, z) = (x + y + z) % 2;
  return in;
}

Input noise(int n)
{
  Input in = emptyInput("noise 50% " + cube(n), "noise", { n, n, n });
  for (std::size_t i = 0; i < in.values.size(); ++i)
    in.values[i] = splitMix64(i) >> 63;
  return in;
}

/// N^3 labels 1..N^3 (in wideLabels: more than 255), each a cube of 2^3 voxels.
Input compactLabels(int n)
{
  const int side = 2 * n;
  Input in =
    emptyInput("compact labels " + std::to_string(n * n * n), "compact", { side, side, side });
  in.labels = true;
  in.values.assign(in.voxelCount(), 1);
  in.wideLabels.resize(in.voxelCount());
  std::size_t i = 0;
  for (int z = 0; z < side; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x)
        in.wideLabels[i++] = 1 + (x / 2) + n * ((y / 2) + n * (z / 2));
  return in;
}

//------------------------------------------------------------------------------
// The shared data

/// A volume or image of the shared data and its selection (the manifest's). Flags: L a label
/// map, s small (kept by --quick), x large (only with --large), i raw little-endian int16
/// selected at >= lo when read.
struct DataFile
{
  const char* cls;
  const char* name;
  const char* file;
  std::array<int, 3> dims; ///< raw files only (0: the reader tells)
  int lo, hi;
  const char* flags;
  long long selected, extremeVertices; ///< the manifest's oracle, -1 when it gives none

  bool has(char flag) const { return std::string(flags).find(flag) != std::string::npos; }
};

// clang-format off
const DataFile dataFiles[] = {
  { "berea", "berea pore", "berea/berea_200x200x200_uint8.raw", { 200, 200, 200 }, 0, 0, "", 1592109, 525674 },
  { "volumes", "aneurism>=55", "aneurism/aneurism_256x256x256_uint8.raw", { 256, 256, 256 }, 55, 255, "", 89088, 70260 },
  { "volumes", "engine>=55", "engine/engine_256x256x128_uint8.raw", { 256, 256, 128 }, 55, 255, "", 1216197, 85866 },
  { "volumes", "engine>=130", "engine/engine_256x256x128_uint8.raw", { 256, 256, 128 }, 130, 255, "", 881942, 106390 },
  { "volumes", "lobster>=40", "lobster/lobster_301x324x56_uint8.raw", { 301, 324, 56 }, 40, 255, "", 269432, 78100 },
  { "volumes", "Al (v=1)", "dgtal_al/dgtal_al_100x100x100_uint8.raw", { 100, 100, 100 }, 1, 1, "s", 70413, 9934 },
  { "volumes", "headsq>=500", "headsq/headsq_quarter_64x64x93_int16le.raw", { 64, 64, 93 }, 500, 1, "si", 144968, 10462 },
  { "volumes", "headsq bone>=1150", "headsq/headsq_quarter_64x64x93_int16le.raw", { 64, 64, 93 }, 1150, 1, "si", -1, -1 },
  { "volumes", "colin27 brain>0", "mricron/ch2bet.nii.gz", { 0, 0, 0 }, 1, 255, "", -1, -1 },
  { "labelmaps", "AAL atlas (116)", "mricron/aal.nii.gz", { 0, 0, 0 }, 1, 255, "L", 1479969, 74120 },
  { "labelmaps", "Brodmann (41)", "mricron/brodmann.nii.gz", { 0, 0, 0 }, 1, 255, "L", 1352119, 110404 },
  { "labelmaps", "JHU white matter (48)", "mricron/JHU-WhiteMatter-labels-1mm.nii.gz", { 0, 0, 0 }, 1, 255, "L", -1, -1 },
  { "labelmaps", "Harvard-Oxford (48)", "mricron/HarvardOxford-cort-maxprob-thr0-1mm.nii.gz", { 0, 0, 0 }, 1, 255, "L", -1, -1 },
  { "labelmaps", "ITK k-means (6)", "itk_kmeans/KmeansTest_T1KmeansPrelimSegmentation.nii.gz", { 0, 0, 0 }, 1, 255, "L", -1, -1 },
  { "images2d", "ccitt1", "2d/jbigkit/ccitt1.png", {}, 0, 0, "", 155591, 51476 },
  { "images2d", "ccitt4", "2d/jbigkit/ccitt4.png", {}, 0, 0, "", 509635, 204154 },
  { "images2d", "ccitt7", "2d/jbigkit/ccitt7.png", {}, 0, 0, "", 356850, 186544 },
  { "images2d", "ccitt8", "2d/jbigkit/ccitt8.png", {}, 0, 0, "", 1766467, 52296 },
  { "images2d", "test-t82", "2d/jbigkit/test-t82.png", {}, 0, 0, "", 861965, 1310306 },
  { "images2d", "feyn", "2d/leptonica/feyn.tif", {}, 0, 0, "", 1060195, 282760 },
  { "images2d", "rabi", "2d/leptonica/rabi.png", {}, 0, 0, "", 2470391, 588664 },
  { "images2d", "pageseg2", "2d/leptonica/pageseg2.tif", {}, 0, 0, "", 2388500, 555042 },
  { "images2d", "scots-frag", "2d/leptonica/scots-frag.tif", {}, 0, 0, "", 1514166, 577326 },
  { "images2d", "pollen SEM>75", "2d/pollen/misc_pollen_sem.png", {}, 76, 255, "", 394107, 65432 },
  { "images2d", "coins>107", "2d/skimage/coins.png", {}, 108, 255, "s", 45117, 5938 },
  { "images2d", "page<=157", "2d/skimage/page.png", {}, 0, 157, "s", 26526, 5848 },
  { "images2d", "text<=109", "2d/skimage/text.png", {}, 0, 109, "s", -1, -1 },
  { "images2d", "horse<128", "2d/skimage/horse.png", {}, 0, 127, "s", 43412, 1180 },
  { "images2d", "maze 4001^2", "2d/mazes/perfect4k.png", {}, 0, 0, "x", 8008000, 5741592 },
  { "images2d", "maze 6001^2", "2d/mazes/combo6k.png", {}, 0, 0, "x", 17369887, 12503994 },
};
// clang-format on

/// Raw uint8 values.
bool readRaw(const std::string& path, Input& in)
{
  std::ifstream f(path, std::ios::binary);
  if (!f)
    return false;
  in.values.resize(in.voxelCount());
  f.read(reinterpret_cast<char*>(in.values.data()), static_cast<std::streamsize>(in.voxelCount()));
  if (f.gcount() != static_cast<std::streamsize>(in.voxelCount()))
  {
    std::cout << "WARNING: " << path << " holds fewer than " << in.voxelCount() << " bytes\n";
    return false;
  }
  return true;
}

/// Raw little-endian int16 values, selected (0/1) at >= `lo` as they are read.
bool readRawInt16(const std::string& path, int lo, Input& in)
{
  std::ifstream f(path, std::ios::binary);
  if (!f)
    return false;
  in.values.resize(in.voxelCount());
  for (std::uint8_t& v : in.values)
  {
    unsigned char b[2] = { 0, 0 };
    f.read(reinterpret_cast<char*>(b), 2);
    v = static_cast<std::int16_t>(b[0] | (b[1] << 8)) >= lo;
  }
  return static_cast<bool>(f);
}

#ifdef VOXELBREP_HAVE_LIBTIFF
/// A bilevel TIFF through libtiff, black 0 and white 255, rows bottom-up as VTK's readers give
/// them. vtkTIFFReader decodes these Group 4 pages wrongly: 818,476 black pixels in feyn.tif,
/// where libtiff (and the manifest) count 1,060,195.
bool readBilevelTIFF(const std::string& path, Input& in)
{
  TIFF* tiff = TIFFOpen(path.c_str(), "r");
  if (!tiff)
    return false;
  std::uint32_t w = 0, h = 0;
  std::uint16_t bits = 1, photometric = PHOTOMETRIC_MINISWHITE;
  TIFFGetField(tiff, TIFFTAG_IMAGEWIDTH, &w);
  TIFFGetField(tiff, TIFFTAG_IMAGELENGTH, &h);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetField(tiff, TIFFTAG_PHOTOMETRIC, &photometric);
  in.dims = { static_cast<int>(w), static_cast<int>(h), 1 };
  in.values.resize(in.voxelCount());
  std::vector<std::uint8_t> line(static_cast<std::size_t>(TIFFScanlineSize(tiff)));
  bool ok = bits == 1;
  for (std::uint32_t y = 0; ok && y < h; ++y)
  {
    ok = TIFFReadScanline(tiff, line.data(), y) >= 0;
    for (std::uint32_t x = 0; x < w; ++x)
    {
      const bool set = (line[x >> 3] >> (7 - (x & 7))) & 1;
      const bool black = photometric == PHOTOMETRIC_MINISWHITE ? set : !set;
      in.values[std::size_t(h - 1 - y) * w + x] = black ? 0 : 255;
    }
  }
  TIFFClose(tiff);
  return ok;
}
#endif

/// A NIfTI, PNG or TIFF file through VTK's reader; the first component of each pixel.
bool readWithVTK(const std::string& path, Input& in)
{
  if (!std::ifstream(path))
    return false;
  vtkSmartPointer<vtkImageReader2> reader;
  const std::string ext = path.substr(path.find_last_of('.') + 1);
  if (ext == "gz" || ext == "nii")
    reader = vtkSmartPointer<vtkNIFTIImageReader>::New();
  else if (ext == "png")
    reader = vtkSmartPointer<vtkPNGReader>::New();
#ifdef VOXELBREP_HAVE_LIBTIFF
  else
    return readBilevelTIFF(path, in);
#else
  else
    reader = vtkSmartPointer<vtkTIFFReader>::New();
#endif
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars)
    return false;
  image->GetDimensions(in.dims.data());
  in.values.resize(in.voxelCount());
  for (std::size_t i = 0; i < in.values.size(); ++i)
    in.values[i] = static_cast<std::uint8_t>(
      std::min(255.0, std::max(0.0, scalars->GetComponent(static_cast<vtkIdType>(i), 0))));
  return true;
}

bool loadDataFile(const DataFile& file, const std::string& dataDir, Input& in)
{
  in.inputClass = file.cls;
  in.name = file.name;
  in.dims = file.dims;
  in.lo = file.has('i') ? 1 : file.lo; // int16 files are selected as they are read
  in.hi = file.has('i') ? 1 : file.hi;
  in.labels = file.has('L');
  in.expectedSelected = file.selected;
  in.expectedExtremeVertices = file.extremeVertices;
  const std::string path = dataDir + "/" + file.file;
  const bool raw = path.size() > 4 && path.compare(path.size() - 4, 4, ".raw") == 0;
  const bool ok = !raw ? readWithVTK(path, in)
                       : (file.has('i') ? readRawInt16(path, file.lo, in) : readRaw(path, in));
  if (!ok)
    std::cout << "(" << path << " not found: " << file.name << " skipped)\n\n";
  return ok;
}

bool wants(const InputOptions& options, const std::string& cls)
{
  return std::find(options.classes.begin(), options.classes.end(), cls) != options.classes.end() ||
    std::find(options.classes.begin(), options.classes.end(), "all") != options.classes.end();
}

/// The procedural inputs of one class.
void addProcedural(const InputOptions& o, const std::string& cls, std::vector<InputSpec>& out)
{
  auto add = [&](const std::string& name, std::function<Input()> make) {
    out.push_back({ name, cls, [make](Input& in) { return in = make(), true; } });
  };
  if (cls == "balls")
  {
    add("paper sphere r2<=240", [] { return ball("paper sphere r2<=240", 240); });
    add("hexahedron", [] { return hexahedron(); });
    for (int r : o.radii)
      add("ball r=" + std::to_string(r),
        [r] { return ball("ball r=" + std::to_string(r), long(r) * r); });
    return;
  }
  if (cls == "pacman")
  {
    add("pac-man r=11", [] { return pacman(11); });
    return;
  }
  if (cls == "solids")
  {
    for (int n : o.sizes)
      for (const char* shape : { "ball", "torus", "CSG" })
        add(std::string(shape) + " " + cube(n), [shape, n] { return smoothSolid(shape, n); });
    return;
  }
  if (cls == "compact")
  {
    for (int n : o.labels)
      add("compact labels " + std::to_string(n * n * n), [n] { return compactLabels(n); });
    return;
  }
  if (cls == "porous" || cls == "porous2d")
  {
    const bool flat = cls == "porous2d";
    for (int n : flat ? o.sizes2D : o.sizes)
      for (int p : o.solid)
        for (int s : o.seeds)
        {
          const std::array<int, 3> dims{ n, n, flat ? 1 : n };
          add(porousName(dims, p, s), [=] { return porous(dims, p, s); });
        }
    return;
  }
  const std::vector<std::string> sized{ "phantom", "boxes", "blobs", "checkerboard", "noise" };
  if (std::find(sized.begin(), sized.end(), cls) == sized.end())
    return;
  for (int n : o.sizes)
    add(cls + " " + cube(n),
      [cls, n]
      {
        return cls == "phantom" ? phantom(n)
          : cls == "boxes"      ? boxes(n)
          : cls == "blobs"      ? blobs(n)
          : cls == "noise"      ? noise(n)
                                : checkerboard(n);
      });
}

} // namespace

std::vector<std::string> splitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');)
    if (!item.empty())
      items.push_back(item);
  return items;
}

const std::vector<std::string>& inputClasses()
{
  static const std::vector<std::string> classes =
    splitList("phantom,boxes,blobs,pacman,balls,solids,"
              "porous,"
              "checkerboard,noise,compact,berea,"
              "volumes,labelmaps,porous2d,images2d");
  return classes;
}

std::vector<InputSpec> selectInputs(const InputOptions& options)
{
  std::vector<InputSpec> specs;
  for (const std::string& cls : inputClasses())
  {
    if (!wants(options, cls))
      continue;
    addProcedural(options, cls, specs);
    if (!options.data)
      continue;
    for (const DataFile& file : dataFiles)
      if (file.cls == cls && (!options.quick || file.has('s')) && (options.large || !file.has('x')))
        specs.push_back({ file.name, cls, [&file, dir = options.dataDir](Input& in) {
                           return loadDataFile(file, dir, in);
                         } });
  }
  return specs;
}

bool loadInput(const InputSpec& spec, Input& in)
{
  return spec.load(in);
}

std::size_t selectedCount(const Input& in)
{
  std::size_t n = 0;
  for (std::size_t i = 0; i < in.values.size(); ++i)
    n += in.selected(i);
  return n;
}

bool touchesBorder(const Input& in)
{
  const int nx = in.dims[0], ny = in.dims[1], nz = in.dims[2];
  std::size_t i = 0;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x, ++i)
        if ((x == 0 || x == nx - 1 || y == 0 || y == ny - 1 ||
              (nz > 1 && (z == 0 || z == nz - 1))) &&
          in.selected(i))
          return true;
  return false;
}

std::string describe(const InputSpec& spec)
{
  return spec.name + "\t" + spec.inputClass;
}

} // namespace vbrbench
