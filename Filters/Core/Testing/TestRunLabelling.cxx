// Scan-line labelling of voxel runs against a flood fill (labels and their numbering, voxel by
// voxel), a parity count of the extreme vertices, and the CUDB of the same voxels (its boxes,
// built from the runs box for box in its order, the OUDB's count, the components of the boxes).
#include "BruteForce.h"
#include "CUDB.h"
#include "EVM.h"
#include "RunLabelling.h"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

/// The runs of v labelled, painted with their labels into a grid of v's size.
struct Labelled
{
  vbr::VoxelRuns runs;
  vbr::RunComponents components;
  std::vector<std::int32_t> grid;
};

Labelled labelAndPaint(const vbr::BitVolume& v,
  vbr::Connectivity connectivity,
  const vbr::Execution& exec = vbr::Execution(),
  vbr::ContactSearch search = vbr::ContactSearch::Adaptive)
{
  Labelled out;
  EXPECT_TRUE(vbr::extractRuns(v, exec, out.runs));
  EXPECT_TRUE(
    vbr::labelRuns(v, out.runs, connectivity, exec, out.components, true, nullptr, search));
  // Without the boxes, the same labels and counts and no boxes.
  vbr::RunComponents plain;
  EXPECT_TRUE(vbr::labelRuns(v, out.runs, connectivity, exec, plain, false, nullptr, search));
  EXPECT_EQ(plain.runLabel, out.components.runLabel);
  EXPECT_EQ(plain.boxCount, out.components.boxCount);
  EXPECT_EQ(plain.beginsBox, out.components.beginsBox);
  EXPECT_EQ(out.components.boxes.size(), out.components.boxCount);
  EXPECT_TRUE(plain.boxes.empty() && plain.boxLabel.empty());
  std::vector<std::int32_t> value(out.components.count + 1);
  for (std::size_t l = 0; l < value.size(); ++l)
    value[l] = static_cast<std::int32_t>(l);
  out.grid.assign(v.voxelCount(), 0);
  EXPECT_TRUE(vbr::paintRuns(
    out.runs, out.components.runLabel, value, { 0, 0, 0 }, v.dims(), out.grid.data(), exec));
  // The wide stores (zeros around the runs) paint the same, here and in a grid one voxel larger
  // at each end, the runs at an offset of one.
  std::vector<std::int32_t> wide(v.voxelCount(), 0);
  EXPECT_TRUE(vbr::paintRuns(
    out.runs, out.components.runLabel, value, { 0, 0, 0 }, v.dims(), wide.data(), exec, true));
  EXPECT_EQ(wide, out.grid) << "painted by wide stores";
  const std::array<std::int32_t, 3> d = v.dims(), larger{ d[0] + 2, d[1] + 2, d[2] + 2 };
  std::vector<std::int32_t> framed(std::size_t(larger[0]) * larger[1] * larger[2], 0);
  EXPECT_TRUE(vbr::paintRuns(
    out.runs, out.components.runLabel, value, { 1, 1, 1 }, larger, framed.data(), exec, true));
  std::size_t wrong = 0;
  for (std::int32_t z = 0; z < larger[2]; ++z)
    for (std::int32_t y = 0; y < larger[1]; ++y)
      for (std::int32_t x = 0; x < larger[0]; ++x)
      {
        const bool inside = x >= 1 && y >= 1 && z >= 1 && x <= d[0] && y <= d[1] && z <= d[2];
        const std::int32_t expected =
          inside ? out.grid[((z - 1) * std::size_t(d[1]) + y - 1) * d[0] + x - 1] : 0;
        wrong += framed[(z * std::size_t(larger[1]) + y) * larger[0] + x] != expected;
      }
  EXPECT_EQ(wrong, 0u) << "painted by wide stores at an offset";
  // Over a grid of any content: every voxel written, the same as painting a zeroed grid, here
  // and at an offset in the larger grid (frame, rows and planes around the runs included).
  std::vector<std::int32_t> dirty(v.voxelCount(), -1);
  EXPECT_TRUE(vbr::paintRunsOverwriting(
    out.runs, out.components.runLabel, value, { 0, 0, 0 }, v.dims(), dirty.data(), exec));
  EXPECT_EQ(dirty, out.grid) << "painted over a grid of -1";
  std::vector<std::int32_t> dirtyFramed(framed.size(), -1);
  EXPECT_TRUE(vbr::paintRunsOverwriting(
    out.runs, out.components.runLabel, value, { 1, 1, 1 }, larger, dirtyFramed.data(), exec));
  EXPECT_EQ(dirtyFramed, framed) << "painted over a grid of -1 at an offset";
  return out;
}

/// The labels, voxel by voxel and numbered alike, are the flood fill's.
void expectFloodFillLabels(const vbr::BitVolume& v, bool vertex, const Labelled& l)
{
  int count = 0;
  const std::vector<int> expected = bf::floodFillLabels(v, vertex, count);
  ASSERT_EQ(l.components.count, static_cast<std::uint32_t>(count));
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < expected.size(); ++i)
    wrong += expected[i] != l.grid[i];
  EXPECT_EQ(wrong, 0u) << "voxels labelled differently from the flood fill";
}

/// The boxes built from the runs are the CUDB's (ZYX), box for box in its order, with the labels
/// of labelComponents and of buildCUDBComponents; together they cover exactly the set voxels.
void expectSameBoxes(const vbr::BitVolume& v,
  vbr::Connectivity connectivity,
  const vbr::CUDB& cudb,
  const vbr::Components& labelled,
  const Labelled& l)
{
  ASSERT_EQ(l.components.boxes.size(), cudb.boxes.size());
  ASSERT_EQ(l.components.boxLabel.size(), cudb.boxes.size());
  std::size_t wrongBoxes = 0, wrongLabels = 0;
  for (std::size_t b = 0; b < cudb.boxes.size(); ++b)
  {
    if (!(l.components.boxes[b] == cudb.boxes[b]) && wrongBoxes++ == 0)
      ADD_FAILURE() << "first different box: " << b;
    wrongLabels += l.components.boxLabel[b] != labelled.boxLabel[b];
  }
  EXPECT_EQ(wrongBoxes, 0u) << "boxes differ from buildCUDB's";
  EXPECT_EQ(wrongLabels, 0u) << "box labels differ from labelComponents'";
  vbr::CUDB swept;
  vbr::Components sweptLabels;
  ASSERT_TRUE(vbr::buildCUDBComponents(
    vbr::extractEVM(v), connectivity, vbr::Execution(), swept, sweptLabels));
  EXPECT_EQ(sweptLabels.boxLabel, l.components.boxLabel) << "labels of buildCUDBComponents";
  // Independently of the CUDB: every set voxel in exactly one box, no empty voxel in any.
  std::vector<std::uint8_t> covered(v.voxelCount(), 0);
  for (const vbr::Box& box : l.components.boxes)
    for (std::int32_t z = box.lo[2]; z < box.hi[2]; ++z)
      for (std::int32_t y = box.lo[1]; y < box.hi[1]; ++y)
        for (std::int32_t x = box.lo[0]; x < box.hi[0]; ++x)
          ++covered[(std::size_t(z) * v.size(1) + y) * v.size(0) + x];
  std::size_t wrongVoxels = 0;
  for (std::int32_t z = 0; z < v.size(2); ++z)
    for (std::int32_t y = 0; y < v.size(1); ++y)
      for (std::int32_t x = 0; x < v.size(0); ++x)
        wrongVoxels +=
          covered[(std::size_t(z) * v.size(1) + y) * v.size(0) + x] != (v.get(x, y, z) ? 1 : 0);
  EXPECT_EQ(wrongVoxels, 0u) << "voxels not covered exactly once by the boxes";
}

/// The counts and box origins are those of the CUDB of v's EVM (ZYX), and the run beginning
/// each box has the label labelComponents gives the box.
void expectCUDBCounts(const vbr::BitVolume& v, vbr::Connectivity connectivity, const Labelled& l)
{
  const vbr::EVM evm = vbr::extractEVM(v);
  ASSERT_EQ(evm.order(), (vbr::AxisOrder{ 2, 1, 0 }));
  EXPECT_EQ(l.components.extremeVertices, evm.size());
  EXPECT_EQ(l.components.extremeVertices, bf::extremeVertices(v).size());
  const vbr::CUDB cudb = vbr::buildCUDB(evm);
  EXPECT_EQ(l.components.oudbBoxCount, cudb.oudbBoxCount);
  ASSERT_EQ(l.components.boxCount, cudb.boxes.size());
  const vbr::Components boxes = vbr::labelComponents(cudb, connectivity);
  EXPECT_EQ(boxes.count, l.components.count);
  std::size_t b = 0;
  const std::int32_t ny = v.size(1);
  for (std::int32_t z = 0; z < v.size(2); ++z)
    for (std::int32_t y = 0; y < ny; ++y)
    {
      const std::size_t row = l.runs.rowOf(y, z);
      for (std::uint32_t i = l.runs.rowStarts[row]; i < l.runs.rowStarts[row + 1]; ++i)
      {
        if (!l.components.beginsBox[i])
          continue;
        ASSERT_LT(b, cudb.boxes.size());
        const vbr::Box& box = cudb.boxes[b];
        EXPECT_EQ(box.lo, (vbr::Point3{ l.runs.runs[i].x0, y, z })) << "box " << b;
        EXPECT_EQ(box.hi[0], l.runs.runs[i].x1) << "box " << b;
        EXPECT_EQ(boxes.boxLabel[b], l.components.runLabel[i]) << "box " << b;
        ++b;
      }
    }
  expectSameBoxes(v, connectivity, cudb, boxes, l);
}

void expectAll(const vbr::BitVolume& v, const std::string& what)
{
  SCOPED_TRACE(what);
  for (bool vertex : { false, true })
  {
    SCOPED_TRACE(vertex ? "vertex" : "face");
    const vbr::Connectivity c = vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
    const Labelled l = labelAndPaint(v, c);
    expectFloodFillLabels(v, vertex, l);
    expectCUDBCounts(v, c, l);
  }
}

TEST(RunLabelling, RandomVolumesMatchFloodFillAndCUDB)
{
  const vbr::Point3 sizes[] = { { 1, 1, 1 },
    { 5, 4, 3 },
    { 17, 9, 6 },
    { 1, 12, 11 },
    { 64, 3, 5 },
    { 65, 7, 4 },
    { 130, 5, 3 },
    { 40, 9, 1 },
    { 70, 1, 6 },
    { 23, 21, 19 } };
  unsigned seed = 1;
  for (const vbr::Point3& d : sizes)
    for (double density : { 0.1, 0.3, 0.5, 0.7, 0.95 })
      for (int repeat = 0; repeat < 3; ++repeat)
      {
        const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
        expectAll(v,
          std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]) + " " +
            std::to_string(density) + " seed " + std::to_string(seed - 1));
      }
}

/// A random volume of `cells` cells of `scale` voxels each (per axis), every cell set or not:
/// equal runs in consecutive rows and equal rectangles in consecutive planes, which random
/// voxels seldom have, so boxes grow along y and z. A few voxels flipped at random break
/// some of them.
vbr::BitVolume blockyVolume(const vbr::Point3& cells,
  const vbr::Point3& scale,
  double density,
  double flips,
  unsigned seed)
{
  const vbr::BitVolume coarse = bf::randomVolume(cells, density, seed);
  const vbr::Point3 d{ cells[0] * scale[0], cells[1] * scale[1], cells[2] * scale[2] };
  const vbr::BitVolume noise = bf::randomVolume(d, flips, seed + 7777);
  vbr::BitVolume v(d[0], d[1], d[2]);
  for (std::int32_t z = 0; z < d[2]; ++z)
    for (std::int32_t y = 0; y < d[1]; ++y)
      for (std::int32_t x = 0; x < d[0]; ++x)
        v.set(x, y, z, coarse.get(x / scale[0], y / scale[1], z / scale[2]) != noise.get(x, y, z));
  return v;
}

TEST(RunLabelling, BlockyVolumesBuildTheCUDBBoxes)
{
  const vbr::Point3 cells[] = { { 4, 4, 4 }, { 9, 5, 3 }, { 3, 7, 8 }, { 30, 4, 4 } };
  const vbr::Point3 scales[] = { { 1, 2, 3 }, { 3, 3, 3 }, { 2, 1, 4 }, { 5, 4, 2 } };
  unsigned seed = 100;
  for (const vbr::Point3& c : cells)
    for (const vbr::Point3& s : scales)
      for (double density : { 0.3, 0.6, 0.9 })
        for (double flips : { 0.0, 0.02 })
        {
          const vbr::BitVolume v = blockyVolume(c, s, density, flips, seed++);
          expectAll(v, "blocky seed " + std::to_string(seed - 1));
        }
}

TEST(RunLabelling, DegenerateVolumes)
{
  expectAll(vbr::BitVolume(7, 5, 3), "empty");
  vbr::BitVolume full(66, 4, 3), one(9, 8, 7), checker(12, 11, 10), diagonal(10, 10, 10);
  vbr::BitVolume plates(70, 9, 9), edges(8, 8, 8);
  for (std::int32_t z = 0; z < 10; ++z)
    for (std::int32_t y = 0; y < 11; ++y)
      for (std::int32_t x = 0; x < 12; ++x)
        checker.set(x, y, z, (x + y + z) % 2 == 0);
  for (std::int32_t z = 0; z < 3; ++z)
    for (std::int32_t y = 0; y < 4; ++y)
      for (std::int32_t x = 0; x < 66; ++x)
        full.set(x, y, z);
  one.set(4, 3, 5);
  for (std::int32_t i = 0; i < 10; ++i)
  {
    diagonal.set(i, i, i);         // vertex contacts only
    diagonal.set(9 - i, i, 0);     // edge contacts only, in one plane
    diagonal.set(i, 9 - i, 9 - i); // vertex contacts, crossing the first diagonal
  }
  for (std::int32_t z = 0; z < 9; ++z)
    for (std::int32_t y = 0; y < 9; ++y)
    {
      plates.set(3, y, z); // a plate across x, one voxel thick
      for (std::int32_t x = 5; x < 70; ++x)
        if (z == 2 || y == 6) // plates across z and y, crossing
          plates.set(x, y, z);
    }
  for (std::int32_t k = 0; k < 7; ++k) // pairs of voxels sharing an edge along each axis
  {
    edges.set(k, 0, 0);
    edges.set(k + 1, 1, 0);
    edges.set(0, k, 3 + (k % 2));
  }
  expectAll(full, "full");
  expectAll(one, "one voxel");
  expectAll(checker, "checkerboard");
  expectAll(diagonal, "diagonal contacts");
  expectAll(plates, "thin plates");
  expectAll(edges, "edge contacts");
}

TEST(RunLabelling, CheckerboardComponents)
{
  vbr::BitVolume checker(9, 8, 7);
  for (std::int32_t z = 0; z < 7; ++z)
    for (std::int32_t y = 0; y < 8; ++y)
      for (std::int32_t x = 0; x < 9; ++x)
        checker.set(x, y, z, (x + y + z) % 2 == 1);
  EXPECT_EQ(labelAndPaint(checker, vbr::Connectivity::Face).components.count, checker.count());
  EXPECT_EQ(labelAndPaint(checker, vbr::Connectivity::Vertex).components.count, 1u);
}

/// A volume of short runs: a checkerboard (runs of one voxel, `stripes`: of one voxel along x
/// only, rows alike) with a fraction `flips` of its voxels flipped at random.
vbr::BitVolume shortRunVolume(const vbr::Point3& d, bool stripes, double flips, unsigned seed)
{
  const vbr::BitVolume noise = bf::randomVolume(d, flips, seed);
  vbr::BitVolume v(d[0], d[1], d[2]);
  for (std::int32_t z = 0; z < d[2]; ++z)
    for (std::int32_t y = 0; y < d[1]; ++y)
      for (std::int32_t x = 0; x < d[0]; ++x)
        v.set(x, y, z, ((stripes ? x : x + y + z) % 2 == 0) != noise.get(x, y, z));
  return v;
}

TEST(RunLabelling, ContactSearchesMatchFloodFill)
{
  // Every way of finding the contacts of two rows (the walk over their runs, the scan of their
  // bits, the choice between them per pair of rows) against the flood fill, on volumes and
  // images of short runs (where the choice takes the bits) and of longer ones, rows across
  // one to four 64-bit words and ending inside or at the end of a word: labels voxel by voxel,
  // and the CUDB's counts and boxes from the notes of equal runs (set where the contacts are
  // found), against the EVM's CUDB; the ways give the same runs' labels and boxes.
  const vbr::Point3 sizes[] = { { 63, 9, 7 },
    { 64, 8, 6 },
    { 65, 7, 5 },
    { 130, 6, 4 },
    { 200, 5, 3 },
    { 9, 12, 11 },
    { 150, 40, 1 },
    { 64, 64, 1 },
    { 257, 20, 1 } };
  // BitsPortable: the scan of the bits counting them without the processor's instruction,
  // the copy a build for processors without it runs.
  const vbr::ContactSearch searches[] = { vbr::ContactSearch::Runs,
    vbr::ContactSearch::Bits,
    vbr::ContactSearch::BitsPortable,
    vbr::ContactSearch::Adaptive };
  unsigned seed = 2000;
  for (const vbr::Point3& d : sizes)
    for (int kind = 0; kind < 6; ++kind)
    {
      // Random voxels at three densities, a checkerboard and stripes with flips, and runs of
      // about 8 to 16 voxels (blocks of 8 along x).
      const double densities[] = { 0.3, 0.5, 0.7 };
      vbr::BitVolume v = kind < 3 ? bf::randomVolume(d, densities[kind], seed)
        : kind < 5                ? shortRunVolume(d, kind == 4, 0.08, seed)
                                  : vbr::BitVolume(d[0], d[1], d[2]);
      if (kind == 5)
      {
        const vbr::BitVolume coarse = bf::randomVolume({ (d[0] + 7) / 8, d[1], d[2] }, 0.5, seed);
        for (std::int32_t z = 0; z < d[2]; ++z)
          for (std::int32_t y = 0; y < d[1]; ++y)
            for (std::int32_t x = 0; x < d[0]; ++x)
              v.set(x, y, z, coarse.get(x / 8, y, z));
      }
      ++seed;
      for (bool vertex : { false, true })
      {
        const vbr::Connectivity c = vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
        std::vector<Labelled> all;
        for (vbr::ContactSearch search : searches)
        {
          SCOPED_TRACE(std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
            std::to_string(d[2]) + " kind " + std::to_string(kind) + " seed " +
            std::to_string(seed - 1) + (vertex ? " vertex" : " face") + " search " +
            std::to_string(static_cast<int>(search)));
          all.push_back(labelAndPaint(v, c, vbr::Execution(), search));
          expectFloodFillLabels(v, vertex, all.back());
          expectCUDBCounts(v, c, all.back());
        }
        for (const Labelled& l : all)
        {
          EXPECT_EQ(l.components.runLabel, all[0].components.runLabel);
          EXPECT_EQ(l.components.beginsBox, all[0].components.beginsBox);
          EXPECT_EQ(l.components.boxes, all[0].components.boxes);
        }
      }
    }
}

TEST(RunLabelling, ContactsFromBitsInPiecesMatchFloodFill)
{
  // The bits' contacts with the planes labelled in pieces by threads and joined (over 2^16
  // runs), against the flood fill, with both counts of the bits.
  const vbr::BitVolume v = shortRunVolume({ 100, 60, 70 }, false, 0.1, 77);
  for (vbr::ContactSearch search : { vbr::ContactSearch::Bits, vbr::ContactSearch::BitsPortable })
    for (bool vertex : { false, true })
    {
      SCOPED_TRACE(std::string(vertex ? "vertex" : "face") + " search " +
        std::to_string(static_cast<int>(search)));
      const vbr::Connectivity c = vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
      const Labelled l = labelAndPaint(v, c, bf::threadedExecution(3), search);
      ASSERT_GE(l.runs.runs.size(), std::size_t(1) << 16);
      expectFloodFillLabels(v, vertex, l);
    }
}

TEST(RunLabelling, ThreadsChangeNothing)
{
  // Enough runs (over 2^16) and planes for the labelling to be cut into pieces of planes.
  const vbr::BitVolume v = bf::randomVolume({ 100, 60, 70 }, 0.45, 11);
  for (vbr::Connectivity c : { vbr::Connectivity::Face, vbr::Connectivity::Vertex })
  {
    const Labelled one = labelAndPaint(v, c);
    const Labelled three = labelAndPaint(v, c, bf::threadedExecution(3));
    EXPECT_EQ(one.components.runLabel, three.components.runLabel);
    EXPECT_EQ(one.components.beginsBox, three.components.beginsBox);
    EXPECT_EQ(one.components.boxCount, three.components.boxCount);
    EXPECT_EQ(one.components.boxes, three.components.boxes);
    EXPECT_EQ(one.components.boxLabel, three.components.boxLabel);
    EXPECT_EQ(one.grid, three.grid);
  }
}

TEST(RunLabelling, KeptMemoryChangesNothing)
{
  // One set of output vectors and one scratch for a sequence of volumes, each larger or smaller
  // than the one before (memory with room and the last volume's values in it, or too small),
  // threads or not: every labelling is the flood fill's, with the CUDB's counts and boxes.
  // 128x64x40 at density 0.5 has about 80,000 runs, past the 65,536 from which threads unite
  // the planes in pieces: the threaded union runs on the kept memory too (the others are
  // united sequentially). A density below 0 takes one from the seed.
  struct Case
  {
    vbr::Point3 dims;
    double density;
    bool piecesUnited = false; ///< enough runs for the threaded union
  };
  const Case cases[] = { { { 40, 30, 20 }, -1 },
    { { 128, 64, 40 }, 0.5, true },
    { { 5, 4, 3 }, -1 },
    { { 23, 21, 19 }, -1 },
    { { 1, 1, 1 }, -1 },
    { { 70, 9, 6 }, -1 },
    { { 17, 9, 6 }, -1 } };
  vbr::VoxelRuns runs;
  vbr::RunComponents components;
  vbr::RunLabellingScratch scratch;
  unsigned seed = 500;
  for (int threads : { 1, 3 })
    for (const Case& volume : cases)
      for (bool vertex : { false, true })
        for (bool withBoxes : { false, true })
        {
          const vbr::Point3& d = volume.dims;
          const double density = volume.density >= 0 ? volume.density : 0.15 + 0.2 * (seed % 4);
          const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
          SCOPED_TRACE("seed " + std::to_string(seed - 1) + (vertex ? " vertex" : " face") +
            (withBoxes ? " boxes" : "") + " threads " + std::to_string(threads));
          const vbr::Execution exec =
            threads > 1 ? bf::threadedExecution(threads) : vbr::Execution();
          const vbr::Connectivity c = vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
          ASSERT_TRUE(vbr::extractRuns(v, exec, runs));
          if (volume.piecesUnited)
            EXPECT_GE(runs.runs.size(), std::size_t(1) << 16) << "runs for the threaded union";
          ASSERT_TRUE(vbr::labelRuns(v, runs, c, exec, components, withBoxes, &scratch));
          Labelled kept{ runs, components, std::vector<std::int32_t>(v.voxelCount(), 0) };
          std::vector<std::int32_t> value(components.count + 1);
          for (std::size_t l = 0; l < value.size(); ++l)
            value[l] = static_cast<std::int32_t>(l);
          ASSERT_TRUE(vbr::paintRuns(
            runs, components.runLabel, value, { 0, 0, 0 }, v.dims(), kept.grid.data()));
          expectFloodFillLabels(v, vertex, kept);
          if (withBoxes)
          {
            expectCUDBCounts(v, c, kept);
            continue;
          }
          const vbr::EVM evm = vbr::extractEVM(v);
          const vbr::CUDB cudb = vbr::buildCUDB(evm);
          EXPECT_EQ(components.boxCount, cudb.boxes.size());
          EXPECT_EQ(components.oudbBoxCount, cudb.oudbBoxCount);
          EXPECT_EQ(components.extremeVertices, evm.size());
          EXPECT_TRUE(components.boxes.empty() && components.boxLabel.empty());
        }
}

TEST(RunLabelling, PaintsAtAnOffsetAndSkipsZero)
{
  vbr::BitVolume v(4, 3, 2);
  v.set(0, 0, 0);
  v.set(1, 0, 0);
  v.set(3, 2, 1);
  vbr::VoxelRuns runs;
  ASSERT_TRUE(vbr::extractRuns(v, vbr::Execution(), runs));
  vbr::RunComponents c;
  ASSERT_TRUE(vbr::labelRuns(v, runs, vbr::Connectivity::Face, vbr::Execution(), c));
  ASSERT_EQ(c.count, 2u);
  const std::array<std::int32_t, 3> dims{ 6, 5, 4 }, offset{ 1, 2, 1 };
  std::vector<std::int32_t> grid(6 * 5 * 4, -1);
  ASSERT_TRUE(vbr::paintRuns(runs, c.runLabel, { 0, 0, 7 }, offset, dims, grid.data()));
  for (std::int32_t z = 0; z < 4; ++z)
    for (std::int32_t y = 0; y < 5; ++y)
      for (std::int32_t x = 0; x < 6; ++x)
      {
        const bool second = x == 4 && y == 4 && z == 2;
        EXPECT_EQ(grid[(z * 5 + y) * 6 + x], second ? 7 : -1) << x << " " << y << " " << z;
      }
}

TEST(RunLabelling, Aborts)
{
  const vbr::BitVolume v = bf::randomVolume({ 40, 40, 40 }, 0.5, 3);
  vbr::Execution stop;
  stop.aborted = [] { return true; };
  vbr::VoxelRuns runs;
  EXPECT_FALSE(vbr::extractRuns(v, stop, runs));
  ASSERT_TRUE(vbr::extractRuns(v, vbr::Execution(), runs));
  vbr::RunComponents c;
  EXPECT_FALSE(vbr::labelRuns(v, runs, vbr::Connectivity::Face, stop, c));
}

TEST(RunLabelling, RunsOfAVolumeOfAnotherSizeAreRefused)
{
  // The runs' numbers in the rows' bits are counts of the bits: runs of a volume of another
  // size are refused rather than read past.
  const vbr::BitVolume v = bf::randomVolume({ 40, 30, 20 }, 0.5, 4);
  const vbr::BitVolume other = bf::randomVolume({ 40, 30, 21 }, 0.5, 4);
  vbr::VoxelRuns runs;
  ASSERT_TRUE(vbr::extractRuns(other, vbr::Execution(), runs));
  vbr::RunComponents c;
  EXPECT_THROW(
    vbr::labelRuns(v, runs, vbr::Connectivity::Face, vbr::Execution(), c), std::invalid_argument);
  // Runs of this size whose row starts do not match their runs (built by hand) too.
  ASSERT_TRUE(vbr::extractRuns(v, vbr::Execution(), runs));
  runs.runs.pop_back();
  EXPECT_THROW(
    vbr::labelRuns(v, runs, vbr::Connectivity::Face, vbr::Execution(), c), std::invalid_argument);
}

} // namespace
