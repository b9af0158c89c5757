// Image -> EVM extraction, sortings, sections and reconstruction against brute force.
#include "BruteForce.h"
#include "EVM.h"
#include "EVMBoolean.h"
#include "PopCount.h"
#include "Selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <functional>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

std::set<vbr::Point3> worldSet(const vbr::EVM& evm)
{
  std::set<vbr::Point3> s;
  for (std::size_t i = 0; i < evm.size(); ++i)
    s.insert(evm.worldVertex(i));
  return s;
}

const char* const Orders[] = { "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX" };

} // namespace

TEST(EVM, ExtractionMatchesOddIncidence)
{
  // Row lengths around the 64-bit word boundaries, densities from sparse to dense.
  const vbr::Point3 sizes[] = { { 1, 1, 1 },
    { 63, 3, 2 },
    { 64, 2, 3 },
    { 65, 4, 4 },
    { 129, 3, 2 },
    { 7, 9, 11 },
    { 16, 16, 16 } };
  unsigned seed = 1;
  for (const auto& d : sizes)
    for (double density : { 0.05, 0.3, 0.5, 0.8, 1.0 })
    {
      const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
      const vbr::EVM evm = vbr::extractEVM(v);
      EXPECT_EQ(worldSet(evm), bf::extremeVertices(v)) << d[0] << "x" << d[1] << "x" << d[2];
      EXPECT_EQ(evm.toVoxels(v.dims()), v);
    }
}

TEST(EVM, EmptyFullAndSingleVoxel)
{
  vbr::BitVolume empty(5, 6, 7);
  EXPECT_TRUE(vbr::extractEVM(empty).empty());
  vbr::BitVolume one(5, 6, 7);
  one.set(2, 3, 4);
  EXPECT_EQ(vbr::extractEVM(one).size(), 8u);
  vbr::BitVolume full = bf::randomVolume({ 70, 5, 3 }, 1.0, 3);
  const vbr::EVM evm = vbr::extractEVM(full);
  EXPECT_EQ(evm.size(), 8u); // a box has exactly its 8 corners
  EXPECT_EQ(evm.toVoxels(full.dims()), full);
}

TEST(EVM, TwoDimensionalExtraction)
{
  unsigned seed = 100;
  for (const vbr::Point3 d : { vbr::Point3{ 1, 1, 1 },
         vbr::Point3{ 64, 5, 1 },
         vbr::Point3{ 65, 40, 1 },
         vbr::Point3{ 130, 7, 1 } })
    for (double density : { 0.1, 0.5, 0.9 })
    {
      const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
      const vbr::EVM evm = vbr::extractEVM2D(v);
      EXPECT_EQ(evm.dimension(), 2);
      EXPECT_EQ(worldSet(evm), bf::extremeVertices2D(v));
      EXPECT_EQ(evm.toVoxels(v.dims()), v);
    }
}

namespace
{

/// A 2D image of rectangles set and cleared over a set or clear background: long runs of
/// whole words all set or all clear, next to words with edges.
vbr::BitVolume blockyImage(std::int32_t nx, std::int32_t ny, unsigned seed)
{
  vbr::BitVolume v(nx, ny, 1);
  unsigned state = seed;
  const auto next = [&state](std::int32_t n)
  {
    state = state * 1103515245u + 12345u;
    return static_cast<std::int32_t>((state >> 8) % static_cast<unsigned>(n));
  };
  const bool background = seed % 2 == 0;
  for (std::int32_t y = 0; y < ny; ++y)
    for (std::int32_t x = 0; x < nx; ++x)
      v.set(x, y, 0, background);
  for (int r = 0; r < 6; ++r)
  {
    const std::int32_t x0 = next(nx), y0 = next(ny);
    const std::int32_t x1 = x0 + 1 + next(nx - x0), y1 = y0 + 1 + next(ny - y0);
    for (std::int32_t y = y0; y < y1; ++y)
      for (std::int32_t x = x0; x < x1; ++x)
        v.set(x, y, 0, r % 2 == 0 ? !background : background);
  }
  return v;
}

/// extractEVM2D's counts of `v` against pixel by pixel ones, and its vertices with the counts
/// against those without and the odd incidences.
void expectPlanarCounts(const vbr::BitVolume& v, const vbr::Execution& exec)
{
  const std::int32_t nx = v.size(0), ny = v.size(1);
  std::size_t pixels = 0, edges = 0;
  for (std::int32_t y = 0; y < ny; ++y)
    for (std::int32_t x = 0; x < nx; ++x)
    {
      if (!v.get(x, y, 0))
        continue;
      ++pixels;
      const std::int32_t steps[4][2] = { { -1, 0 }, { 1, 0 }, { 0, -1 }, { 0, 1 } };
      for (const auto& s : steps)
        edges += v.getOrBackground(x + s[0], y + s[1], 0) ? 0 : 1;
    }
  std::set<vbr::Coord> xs, ys;
  for (const vbr::Point3& p : bf::extremeVertices2D(v))
  {
    xs.insert(p[0]);
    ys.insert(p[1]);
  }
  vbr::PlanarCounts counts;
  counts.pixels = 12345; // overwritten
  const vbr::EVM evm = vbr::extractEVM2D(v, exec, &counts);
  const std::string where = std::to_string(nx) + "x" + std::to_string(ny);
  EXPECT_EQ(counts.pixels, pixels) << where;
  EXPECT_EQ(counts.edges, edges) << where;
  EXPECT_EQ(counts.planes[0], xs.size()) << where;
  EXPECT_EQ(counts.planes[1], ys.size()) << where;
  EXPECT_EQ(counts.planes[2], 0u) << where;
  EXPECT_EQ(evm, vbr::extractEVM2D(v)) << where;
  EXPECT_EQ(worldSet(evm), bf::extremeVertices2D(v)) << where;
}

} // namespace

TEST(EVM, TwoDimensionalCountsMatchPixels)
{
  vbr::Execution uneven;
  uneven.parallelFor = [](std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& f)
  {
    for (std::int64_t b = n; b > 0; b -= 5) // uneven chunks, out of order
      f(std::max<std::int64_t>(0, b - 5), b);
  };
  uneven.concurrency = 7; // blocks of lines counted apart, merged
  // Word edges of the skipped uniform words, which random images meet by chance only.
  for (const std::int32_t nx : { 128, 200 })
  {
    // Two equal rows clear up to x = 63 and set from 64 on: the word from 64 on is uniform
    // but its row starts there (the carry of the row above the line).
    vbr::BitVolume steps(nx, 2, 1);
    // Rows that differ only at x = 63, equal and uniform from 64 on: the word from 64 on has
    // a vertex at 64 (the carry of the parity), a column of its own (planes[0]).
    vbr::BitVolume notch(nx, 3, 1);
    for (std::int32_t x = 64; x < nx; ++x)
    {
      for (std::int32_t y = 0; y < 2; ++y)
        steps.set(x, y, 0);
      for (std::int32_t y = 0; y < 3; ++y)
        notch.set(x, y, 0);
    }
    notch.set(63, 1, 0);
    for (const bool portable : { false, true })
    {
      // The copy counting by the instruction and the portable one (where there are two).
      vbr::portableBitCountsForTesting() = portable;
      expectPlanarCounts(steps, {});
      expectPlanarCounts(notch, {});
      expectPlanarCounts(notch, uneven);
    }
  }
  unsigned seed = 300;
  // Widths around the word boundaries; random pixels, and blocks whose words are uniform.
  for (const std::int32_t nx : { 1, 2, 63, 64, 65, 128, 130, 200 })
    for (const std::int32_t ny : { 1, 3, 17 })
    {
      for (double density : { 0.0, 0.1, 0.5, 0.9, 1.0 })
      {
        const vbr::BitVolume v = bf::randomVolume({ nx, ny, 1 }, density, seed++);
        expectPlanarCounts(v, {});
        expectPlanarCounts(v, uneven);
        vbr::portableBitCountsForTesting() = true;
        expectPlanarCounts(v, uneven);
        vbr::portableBitCountsForTesting() = false;
      }
      for (int trial = 0; trial < 4; ++trial)
      {
        const vbr::BitVolume v = blockyImage(nx, ny, seed++);
        expectPlanarCounts(v, {});
        expectPlanarCounts(v, uneven);
        vbr::portableBitCountsForTesting() = true;
        expectPlanarCounts(v, {});
        vbr::portableBitCountsForTesting() = false;
      }
    }
}

TEST(EVM, ParallelExtractionEqualsSequential)
{
  const vbr::BitVolume v = bf::randomVolume({ 40, 30, 20 }, 0.4, 7);
  vbr::Execution exec;
  exec.parallelFor = [](std::int64_t n, const std::function<void(std::int64_t, std::int64_t)>& f)
  {
    // Uneven chunks, executed out of order.
    for (std::int64_t b = n; b > 0; b -= 3)
      f(std::max<std::int64_t>(0, b - 3), b);
  };
  EXPECT_EQ(vbr::extractEVM(v, exec), vbr::extractEVM(v));
}

TEST(EVM, AllSixSortings)
{
  const vbr::BitVolume v = bf::randomVolume({ 9, 8, 7 }, 0.4, 11);
  const vbr::EVM evm = vbr::extractEVM(v);
  const auto expected = worldSet(evm);
  std::array<std::size_t, 3> distinct{};
  for (int a = 0; a < 3; ++a)
  {
    std::set<int> c;
    for (const auto& p : expected)
      c.insert(p[a]);
    distinct[a] = c.size();
  }
  EXPECT_EQ(vbr::planesPerAxis(evm), distinct);
  for (const char* name : Orders)
  {
    const vbr::AxisOrder order = vbr::axisOrderFromName(name);
    EXPECT_EQ(vbr::axisOrderName(order), name);
    const vbr::EVM sorted = evm.sortedAs(order);
    EXPECT_TRUE(std::is_sorted(sorted.vertices().begin(), sorted.vertices().end())) << name;
    EXPECT_EQ(worldSet(sorted), expected) << name;
    EXPECT_EQ(sorted.planeCount(), distinct[order[0]]) << name;
    EXPECT_EQ(sorted.toVoxels(v.dims()), v) << name;
  }
  EXPECT_THROW(vbr::axisOrderFromName("XXY"), std::invalid_argument);
}

// The bucket passes of the sortings with threads (slabs of the vertices counted and then
// scattered side by side, from 2^15 vertices on): the vertices of std::sort, the same as one
// thread's, for 2, 3 and 16 threads and through the three sortings the sweeps make. A slab
// written one place off, or its bucket's start taken from the wrong slab, breaks the order.
TEST(EVM, ThreadedBucketSortingsEqualOneThread)
{
  for (const vbr::Point3 dims : { vbr::Point3{ 48, 40, 36 }, vbr::Point3{ 130, 20, 30 } })
  {
    const vbr::EVM evm = vbr::extractEVM(bf::randomVolume(dims, 0.5, 23));
    ASSERT_GE(evm.size(), std::size_t(vbr::Execution::ThreadedWorkMinimum));
    // The sweeps' chain: ZYX -> YZX (on B) -> XYZ (on C) -> ZXY (on C).
    const vbr::EVM first = evm.sortedAs({ 1, 2, 0 });
    const vbr::EVM zeroth = first.sortedAs({ 0, 1, 2 });
    const vbr::EVM second = zeroth.sortedAs({ 2, 0, 1 });
    for (const vbr::EVM* one : { &first, &zeroth, &second })
    {
      std::vector<vbr::Vertex> reference;
      for (std::size_t i = 0; i < evm.size(); ++i)
      {
        const auto w = evm.worldVertex(i);
        reference.push_back({ w[one->order()[0]], w[one->order()[1]], w[one->order()[2]] });
      }
      std::sort(reference.begin(), reference.end());
      EXPECT_EQ(one->vertices(), reference);
    }
    for (int threads : { 2, 3, 16 })
    {
      SCOPED_TRACE(testing::Message() << threads << " threads");
      const vbr::Execution exec = bf::threadedExecution(threads);
      const vbr::EVM t1 = evm.sortedAs({ 1, 2, 0 }, exec);
      EXPECT_EQ(t1, first);
      const vbr::EVM t0 = t1.sortedAs({ 0, 1, 2 }, exec, std::vector<vbr::Vertex>(5));
      EXPECT_EQ(t0, zeroth);
      EXPECT_EQ(t0.sortedAs({ 2, 0, 1 }, exec), second);
      EXPECT_EQ(second.sortedAs({ 0, 2, 1 }, exec), second.sortedAs({ 0, 2, 1 })); // on B
    }
  }
  // Coordinates far apart (beyond the window of buckets about the first one's, either side,
  // negative too), the first vertex's the lowest, then a middle one: the bounds found first.
  std::mt19937 random(29);
  for (const int spread : { 1000, 3000, 100000 })
  {
    std::vector<vbr::Vertex> vertices;
    for (int i = 0; i < 40000; ++i)
      vertices.push_back(
        { int(random() % 50), int(random() % spread) - spread / 3, int(random() % 7) });
    std::sort(vertices.begin(), vertices.end());
    const vbr::EVM evm(3, { 2, 1, 0 }, vertices);
    std::vector<vbr::Vertex> reference;
    for (const vbr::Vertex& v : vertices)
      reference.push_back({ v[1], v[0], v[2] });
    std::sort(reference.begin(), reference.end());
    for (int threads : { 1, 2, 3, 16 })
    {
      const vbr::EVM sorted =
        evm.sortedAs({ 1, 2, 0 }, threads == 1 ? vbr::Execution() : bf::threadedExecution(threads));
      EXPECT_EQ(sorted.vertices(), reference) << spread << " spread, " << threads << " threads";
    }
  }
}

TEST(EVM, SectionsAreXorOfPlaneProjections)
{
  // Formula (1): S_i = S_(i-1) xor plv_i; every section is the voxel slice between the planes.
  const vbr::BitVolume v = bf::randomVolume({ 10, 9, 8 }, 0.45, 21);
  for (const char* name : Orders)
  {
    const vbr::EVM evm = vbr::extractEVM(v).sortedAs(vbr::axisOrderFromName(name));
    const auto starts = evm.planeStarts();
    const auto& order = evm.order();
    std::vector<vbr::Vertex> section, previous;
    for (std::size_t p = 0; p + 1 < starts.size(); ++p)
    {
      const vbr::Vertex* b = evm.vertices().data() + starts[p];
      const vbr::Vertex* e = evm.vertices().data() + starts[p + 1];
      previous = section;
      section = vbr::xorVertices(section, vbr::project(b, e, 0));
      // Formula (2): the plane is the XOR of the two sections around it.
      EXPECT_EQ(vbr::xorVertices(previous, section), vbr::project(b, e, 0));
      // The section, as a 2D EVM, is the slice of voxels starting at this plane.
      const int a = (*b)[0];
      const int end = p + 2 < starts.size() ? evm.vertices()[starts[p + 1]][0] : a;
      const vbr::EVM s2(2, order, section);
      std::array<std::int32_t, 3> sliceDims = v.dims();
      sliceDims[order[0]] = 1;
      const vbr::BitVolume slice = s2.toVoxels(sliceDims);
      for (int c = a; c < end; ++c)
        for (int i = 0; i < v.size(order[1]); ++i)
          for (int j = 0; j < v.size(order[2]); ++j)
          {
            vbr::Point3 w{ 0, 0, 0 }, s{ 0, 0, 0 };
            w[order[0]] = c;
            w[order[1]] = s[order[1]] = i;
            w[order[2]] = s[order[2]] = j;
            ASSERT_EQ(v.get(w[0], w[1], w[2]), slice.get(s[0], s[1], s[2]));
          }
    }
    EXPECT_TRUE(section.empty());
  }
}

namespace
{

/// Reads a raw uint8 volume and selects value >= threshold; false if the file is absent.
bool readRaw(const std::string& path, const vbr::Point3& d, int threshold, vbr::BitVolume& out)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return false;
  std::vector<unsigned char> data(static_cast<std::size_t>(d[0]) * d[1] * d[2]);
  in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size()));
  if (!in)
    return false;
  out = vbr::BitVolume(d[0], d[1], d[2]);
  std::size_t i = 0;
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x)
        if (data[i++] >= threshold)
          out.set(x, y, z);
  return true;
}

} // namespace

TEST(EVM, PaperCountsOnRealVolumes)
{
  // Ayala & Vergara, Table 1: 70,260 and 85,866 extreme vertices at value >= 55.
  struct Case
  {
    const char* file;
    vbr::Point3 dims;
    std::size_t evs;
    std::array<std::size_t, 3> planes;
  } cases[] = {
    { "/aneurism/aneurism_256x256x256_uint8.raw", { 256, 256, 256 }, 70260, { 215, 216, 237 } },
    { "/engine/engine_256x256x128_uint8.raw", { 256, 256, 128 }, 85866, { 142, 199, 109 } },
  };
  int found = 0;
  for (const Case& c : cases)
  {
    vbr::BitVolume v;
    if (!readRaw(std::string(VOXELBREP_DATA_DIR) + c.file, c.dims, 55, v))
      continue;
    ++found;
    const vbr::EVM evm = vbr::extractEVM(v);
    EXPECT_EQ(evm.size(), c.evs) << c.file;
    EXPECT_EQ(vbr::planesPerAxis(evm), c.planes) << c.file;
    EXPECT_EQ(evm.toVoxels(v.dims()), v) << c.file;
  }
  if (found == 0)
    GTEST_SKIP() << "real volumes not found under " << VOXELBREP_DATA_DIR;
}

TEST(Selection, PacksFlagsAndSelectsExactly)
{
  for (unsigned f = 0; f < 256; ++f)
  {
    std::uint64_t bytes = 0;
    for (int k = 0; k < 8; ++k)
      bytes |= static_cast<std::uint64_t>((f >> k) & 1) << (8 * k);
    ASSERT_EQ(vbr::packEightFlags(bytes), f);
  }
  // A strided, offset box of a 70 x 3 x 2 grid of two-component values.
  const int nx = 70, ny = 3, nz = 2, nc = 2;
  std::vector<int> data(nx * ny * nz * nc);
  for (std::size_t i = 0; i < data.size(); ++i)
    data[i] = static_cast<int>((i * 7919) % 13);
  vbr::ScalarGrid<int> grid;
  grid.data = data.data() + 1;
  grid.dims = { nx, ny, nz };
  grid.stride = { nc, nc * nx, nc * nx * ny };
  vbr::Box box;
  box.lo = { 3, 1, 0 };
  box.hi = { 69, 3, 2 };
  const vbr::BitVolume v = vbr::selectVoxels(grid, box, [](int x) { return x > 6; }, {});
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 66; ++x)
        ASSERT_EQ(v.get(x, y, z), grid.at(x + 3, y + 1, z) > 6);
  const int background = 0;
  const auto boxes = vbr::labelBoxes(grid, &background);
  EXPECT_EQ(boxes.size(), 12u);
  // Contiguous bytes (unit strides, the loop the compiler vectorizes best), rows around whole
  // words.
  for (const int width : { 1, 15, 16, 63, 64, 65, 127, 128, 200 })
  {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(width) * 3);
    for (std::size_t i = 0; i < bytes.size(); ++i)
      bytes[i] = static_cast<std::uint8_t>((i * 2654435761u) >> 7);
    vbr::ScalarGrid<std::uint8_t> g;
    g.data = bytes.data();
    g.dims = { width, 3, 1 };
    g.stride = { 1, width, 3 * width };
    vbr::Box whole;
    whole.hi = g.dims;
    const auto selected = [](std::uint8_t x) { return x >= 40 && x <= 200; };
    const vbr::BitVolume u = vbr::selectVoxels(g, whole, selected, {});
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < width; ++x)
        ASSERT_EQ(u.get(x, y, 0), selected(g.at(x, y, 0))) << width << " " << x << " " << y;
    for (int y = 0; y < 3; ++y) // no bit set past the row's end
      ASSERT_EQ(u.row(y, 0)[u.wordsPerRow() - 1] >> 1 >> ((width - 1) % 64), 0u);
  }
}

TEST(EVM, PackSixtyFourFlagsPutsFlagKAtBitK)
{
  for (int k = 0; k < 64; ++k)
  {
    std::uint8_t flags[64] = {};
    flags[k] = 1;
    EXPECT_EQ(vbr::packSixtyFourFlags(flags), vbr::Word(1) << k) << k;
    for (int i = 0; i < 64; ++i)
      flags[i] = i == k ? 0 : 1;
    EXPECT_EQ(vbr::packSixtyFourFlags(flags), ~(vbr::Word(1) << k)) << k;
  }
}
