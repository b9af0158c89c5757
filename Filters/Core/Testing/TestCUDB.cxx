// EVM -> CUDB / OUDB conversion, CUDB -> EVM and connected-component labelling, against
// voxelwise painting, all-pairs box contacts and flood fills.
#include "BruteForce.h"
#include "CUDB.h"
#include "EVM.h"
#include "Phantom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace
{

const char* const Orders[] = { "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX" };

std::size_t indexOf(const vbr::BitVolume& v, int x, int y, int z)
{
  return (std::size_t(z) * v.size(1) + y) * v.size(0) + x;
}

/// Every set voxel lies in exactly one box and no other voxel in any.
void expectExactCover(const vbr::BitVolume& v, const std::vector<vbr::Box>& boxes)
{
  std::vector<int> hits(v.voxelCount(), 0);
  for (const vbr::Box& b : boxes)
  {
    for (int d = 0; d < 3; ++d)
    {
      ASSERT_LT(b.lo[d], b.hi[d]);
      ASSERT_GE(b.lo[d], 0);
      ASSERT_LE(b.hi[d], v.size(d));
    }
    for (int z = b.lo[2]; z < b.hi[2]; ++z)
      for (int y = b.lo[1]; y < b.hi[1]; ++y)
        for (int x = b.lo[0]; x < b.hi[0]; ++x)
          ++hits[indexOf(v, x, y, z)];
  }
  std::size_t wrong = 0;
  for (int z = 0; z < v.size(2); ++z)
    for (int y = 0; y < v.size(1); ++y)
      for (int x = 0; x < v.size(0); ++x)
        wrong += hits[indexOf(v, x, y, z)] != (v.get(x, y, z) ? 1 : 0);
  EXPECT_EQ(wrong, 0u) << "voxels covered zero or several times, or not set";
}

/// All pairs of boxes that touch, by comparing every pair: (smaller, larger) -> shares a face.
std::map<std::pair<std::uint32_t, std::uint32_t>, bool> touchingPairs(
  const std::vector<vbr::Box>& boxes)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, bool> out;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j)
    {
      int open = 0;
      bool meet = true;
      for (int d = 0; d < 3 && meet; ++d)
      {
        meet = boxes[i].lo[d] <= boxes[j].hi[d] && boxes[j].lo[d] <= boxes[i].hi[d];
        open += boxes[i].lo[d] < boxes[j].hi[d] && boxes[j].lo[d] < boxes[i].hi[d];
      }
      if (meet)
        out[{ i, j }] = open == 2; // open == 3 would be an overlap, caught by the cover
    }
  return out;
}

void expectContactsComplete(const vbr::CUDB& cudb)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, bool> recorded;
  for (const vbr::BoxContact& c : cudb.contacts)
  {
    const vbr::Box& back = cudb.boxes[c.backward];
    const vbr::Box& front = cudb.boxes[c.forward];
    EXPECT_EQ(back.hi[c.axis], front.lo[c.axis])
      << "backward box does not end where forward starts";
    EXPECT_TRUE(c.axis == cudb.order[1] || (cudb.dimension == 3 && c.axis == cudb.order[0]));
    const auto key = std::minmax(c.backward, c.forward);
    EXPECT_TRUE(recorded.emplace(key, c.face).second) << "contact listed twice";
  }
  if (cudb.boxes.size() <= 1500)
  {
    EXPECT_EQ(recorded, touchingPairs(cudb.boxes));
  }
}

/// Voxel labels from the box labels.
std::vector<int> paintedLabels(const vbr::BitVolume& v,
  const vbr::CUDB& cudb,
  const vbr::Components& components)
{
  std::vector<std::int32_t> value(components.boxLabel.begin(), components.boxLabel.end());
  std::vector<std::int32_t> labels(v.voxelCount(), 0);
  vbr::paintBoxes(cudb.boxes, value, { 0, 0, 0 }, { 0, 1, 2 }, v.dims(), labels.data());
  return std::vector<int>(labels.begin(), labels.end());
}

/// Same partition: a bijection between the labels of both, and 0 at the same voxels.
void expectSamePartition(const std::vector<int>& got, const std::vector<int>& expected)
{
  ASSERT_EQ(got.size(), expected.size());
  std::map<int, int> forward, backward;
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
  {
    if ((got[i] == 0) != (expected[i] == 0))
    {
      ++mismatches;
      continue;
    }
    if (got[i] == 0)
      continue;
    const auto f = forward.emplace(got[i], expected[i]).first;
    const auto b = backward.emplace(expected[i], got[i]).first;
    mismatches += f->second != expected[i] || b->second != got[i];
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(forward.size(), backward.size());
}

/// The sweep that labels as it goes gives the boxes of buildCUDB and the components that
/// labelComponents finds on them, for both connectivities, without contacts.
void expectLabelledSweepSame(const vbr::EVM& evm,
  const vbr::CUDB& cudb,
  const vbr::Execution& exec = vbr::Execution(),
  int pieces = 0)
{
  for (vbr::Connectivity connectivity : { vbr::Connectivity::Face, vbr::Connectivity::Vertex })
  {
    SCOPED_TRACE(
      connectivity == vbr::Connectivity::Face ? "labelled sweep, face" : "labelled sweep, vertex");
    vbr::CUDB boxes;
    vbr::Components labelled;
    ASSERT_TRUE(vbr::buildCUDBComponents(evm, connectivity, exec, boxes, labelled, pieces));
    const vbr::Components expected = vbr::labelComponents(cudb, connectivity);
    EXPECT_EQ(boxes.boxes, cudb.boxes);
    EXPECT_EQ(boxes.oudbBoxCount, cudb.oudbBoxCount);
    EXPECT_EQ(labelled.count, expected.count);
    EXPECT_EQ(labelled.boxLabel, expected.boxLabel);
  }
}

/// Everything the conversion and the labelling promise, for one voxel set and sorting.
void checkAll(const vbr::BitVolume& v, const vbr::EVM& evm, bool checkPairs = true)
{
  const vbr::CUDB cudb = vbr::buildCUDB(evm);
  SCOPED_TRACE("sorting " + vbr::axisOrderName(evm.order()));
  expectExactCover(v, cudb.boxes);
  EXPECT_EQ(cudb.volume(), static_cast<std::int64_t>(v.count()));
  EXPECT_EQ(vbr::toEVM(cudb), evm) << "CUDB -> EVM round trip";
  const std::vector<vbr::Box> oudb = vbr::buildOUDB(evm);
  EXPECT_EQ(oudb.size(), cudb.oudbBoxCount);
  EXPECT_LE(cudb.boxes.size(), oudb.size());
  expectExactCover(v, oudb);
  if (checkPairs)
    expectContactsComplete(cudb);
  for (bool vertex : { false, true })
  {
    int count = 0;
    const std::vector<int> expected = bf::floodFillLabels(v, vertex, count);
    const vbr::Components c =
      vbr::labelComponents(cudb, vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face);
    EXPECT_EQ(c.count, static_cast<std::uint32_t>(count)) << (vertex ? "vertex" : "face");
    expectSamePartition(paintedLabels(v, cudb, c), expected);
  }
  expectLabelledSweepSame(evm, cudb);
}

vbr::BitVolume fromPoints(const vbr::Point3& dims, const std::vector<vbr::Point3>& points)
{
  vbr::BitVolume v(dims[0], dims[1], dims[2]);
  for (const auto& p : points)
    v.set(p[0], p[1], p[2]);
  return v;
}

std::uint32_t componentCount(const vbr::BitVolume& v, vbr::Connectivity c)
{
  const vbr::EVM evm = v.size(2) == 1 ? vbr::extractEVM2D(v) : vbr::extractEVM(v);
  return vbr::labelComponents(vbr::buildCUDB(evm), c).count;
}

} // namespace

TEST(CUDB, RandomVolumesAllSortings)
{
  const vbr::Point3 sizes[] = {
    { 1, 1, 1 }, { 5, 4, 3 }, { 12, 9, 7 }, { 16, 16, 16 }, { 9, 17, 23 }
  };
  unsigned seed = 100;
  for (const auto& d : sizes)
    for (double density : { 0.05, 0.3, 0.5, 0.7, 0.95 })
    {
      const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
      const vbr::EVM zyx = vbr::extractEVM(v);
      for (const char* name : Orders)
        checkAll(v, zyx.sortedAs(vbr::axisOrderFromName(name)));
    }
}

TEST(CUDB, LargerRandomVolumes)
{
  unsigned seed = 200;
  for (double density : { 0.1, 0.3, 0.6, 0.9 })
  {
    const vbr::BitVolume v = bf::randomVolume({ 64, 48, 40 }, density, seed++);
    const vbr::EVM zyx = vbr::extractEVM(v);
    for (const char* name : { "ZYX", "XZY", "YXZ" })
      checkAll(v, zyx.sortedAs(vbr::axisOrderFromName(name)), false);
  }
}

namespace
{

std::vector<std::tuple<std::uint32_t, std::uint32_t, int, bool>> sortedContacts(const vbr::CUDB& c)
{
  std::vector<std::tuple<std::uint32_t, std::uint32_t, int, bool>> out;
  for (const vbr::BoxContact& k : c.contacts)
    out.emplace_back(k.backward, k.forward, k.axis, k.face);
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace

TEST(CUDB, PiecesGiveTheSequentialSweep)
{
  // The sequential sweep is checked against brute force above; a sweep cut into pieces and
  // stitched must give its boxes in the same order and the same contacts.
  const vbr::Point3 sizes[] = { { 6, 5, 4 }, { 12, 9, 20 }, { 17, 23, 31 }, { 40, 30, 64 } };
  unsigned seed = 500;
  std::size_t stitchedVolumes = 0;
  for (const auto& d : sizes)
    for (double density : { 0.1, 0.5, 0.9 })
    {
      const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
      const vbr::EVM zyx = vbr::extractEVM(v);
      for (const char* name : Orders)
      {
        const vbr::EVM evm = zyx.sortedAs(vbr::axisOrderFromName(name));
        const vbr::CUDB sequential = vbr::buildCUDB(evm);
        for (int pieces : { 2, 3, 7, 100 })
        {
          SCOPED_TRACE(std::string(name) + " in " + std::to_string(pieces) + " pieces");
          vbr::CUDB stitched;
          ASSERT_TRUE(vbr::buildCUDB(evm, bf::threadedExecution(3), stitched, pieces));
          EXPECT_EQ(stitched.boxes, sequential.boxes);
          EXPECT_EQ(sortedContacts(stitched), sortedContacts(sequential));
          EXPECT_EQ(stitched.oudbBoxCount, sequential.oudbBoxCount);
          expectLabelledSweepSame(evm, sequential, bf::threadedExecution(3), pieces);
          ++stitchedVolumes;
        }
      }
    }
  EXPECT_EQ(stitchedVolumes, 4u * 3 * 6 * 4);
  // And the automatic choice on a volume large enough to be cut.
  const vbr::BitVolume big = bf::randomVolume({ 96, 80, 64 }, 0.4, 7);
  const vbr::EVM evm = vbr::extractEVM(big);
  ASSERT_GE(evm.size(), 50000u);
  vbr::CUDB stitched;
  ASSERT_TRUE(vbr::buildCUDB(evm, bf::threadedExecution(2), stitched));
  const vbr::CUDB sequential = vbr::buildCUDB(evm);
  EXPECT_EQ(stitched.boxes, sequential.boxes);
  EXPECT_EQ(sortedContacts(stitched), sortedContacts(sequential));
  const vbr::Components c = vbr::labelComponents(stitched, vbr::Connectivity::Vertex);
  int count = 0;
  const std::vector<int> expected = bf::floodFillLabels(big, true, count);
  EXPECT_EQ(c.count, static_cast<std::uint32_t>(count));
  expectSamePartition(paintedLabels(big, stitched, c), expected);
  expectLabelledSweepSame(evm, sequential, bf::threadedExecution(2));
}

TEST(CUDB, CheckerboardAndNoiseLabelledInPieces)
{
  // The inputs with the most boxes per extreme vertex (a 3D checkerboard: a box per selected
  // voxel from a few vertices, so the room for boxes is predicted from the planes swept) and
  // per voxel (noise), labelled as the sweep goes, in one piece and in several, against a
  // flood fill, with both connectivities.
  vbr::BitVolume board(23, 19, 40);
  for (int z = 0; z < 40; ++z)
    for (int y = 0; y < 19; ++y)
      for (int x = 0; x < 23; ++x)
        if ((x + y + z) % 2 == 0)
          board.set(x, y, z);
  const vbr::BitVolume noise = bf::randomVolume({ 30, 26, 48 }, 0.5, 900);
  for (const vbr::BitVolume* v : std::initializer_list<const vbr::BitVolume*>{ &board, &noise })
  {
    const vbr::EVM zyx = vbr::extractEVM(*v);
    for (const char* name : { "ZYX", "XZY" })
    {
      const vbr::EVM evm = zyx.sortedAs(vbr::axisOrderFromName(name));
      checkAll(*v, evm, false);
      for (bool vertex : { false, true })
      {
        int count = 0;
        const std::vector<int> expected = bf::floodFillLabels(*v, vertex, count);
        for (int pieces : { 1, 3 })
        {
          SCOPED_TRACE(std::string(v == &board ? "checkerboard " : "noise ") + name + " in " +
            std::to_string(pieces) + (vertex ? " pieces, vertex" : " pieces, face"));
          vbr::CUDB boxes;
          vbr::Components c;
          ASSERT_TRUE(vbr::buildCUDBComponents(evm,
            vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face,
            bf::threadedExecution(pieces),
            boxes,
            c,
            pieces));
          EXPECT_EQ(c.count, static_cast<std::uint32_t>(count));
          expectExactCover(*v, boxes.boxes);
          expectSamePartition(paintedLabels(*v, boxes, c), expected);
        }
      }
    }
  }
  EXPECT_EQ(componentCount(board, vbr::Connectivity::Face), 23u * 19 * 40 / 2);
  EXPECT_EQ(componentCount(board, vbr::Connectivity::Vertex), 1u);
}

TEST(CUDB, TwoDimensionalImages)
{
  const vbr::Point3 sizes[] = {
    { 1, 1, 1 }, { 7, 5, 1 }, { 64, 64, 1 }, { 100, 37, 1 }, { 3, 90, 1 }
  };
  unsigned seed = 300;
  for (const auto& d : sizes)
    for (double density : { 0.1, 0.4, 0.6, 0.9 })
    {
      const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
      const vbr::EVM yx = vbr::extractEVM2D(v);
      checkAll(v, yx);
      checkAll(v, yx.sortedAs({ 2, 0, 1 })); // lines along x instead of y
    }
}

/// A random image whose rows often repeat the row before (runs continued over several rows,
/// rows equal to the one before: no line of vertices between them), with set pixels in the
/// last column too.
vbr::BitVolume imageWithRepeatedRows(vbr::Coord nx, vbr::Coord ny, double density, unsigned seed)
{
  const vbr::BitVolume noise = bf::randomVolume({ nx, ny, 1 }, density, seed);
  vbr::BitVolume v(nx, ny, 1);
  vbr::Coord source = 0;
  for (vbr::Coord y = 0; y < ny; ++y)
  {
    seed = seed * 1103515245u + 12345u;
    if ((seed >> 8) % 3 != 0)
      source = y; // else: the row before again
    for (vbr::Coord x = 0; x < nx; ++x)
      v.set(x, y, 0, noise.get(x, source, 0));
  }
  return v;
}

/// The image with x and y exchanged, pixel by pixel (the reference for the 64 x 64 block
/// transposition of the direct path's other sorting).
vbr::BitVolume transposedPixels(const vbr::BitVolume& v)
{
  vbr::BitVolume t(v.size(1), v.size(0), 1);
  for (vbr::Coord y = 0; y < v.size(1); ++y)
    for (vbr::Coord x = 0; x < v.size(0); ++x)
      t.set(y, x, 0, v.get(x, y, 0));
  return t;
}

TEST(CUDB, PixelRowsGiveTheEVMSweep2D)
{
  // The direct 2D path against the EVM's, in both sortings (ZYX: rows along x; ZXY: lines
  // along x, read from the transposed bits): the same boxes in the same order, OUDB count,
  // EVM size and labels; its boxes against the pixels, its components against a flood fill.
  // Sizes around the 64-bit words' boundaries in both axes, and a column one pixel wide.
  const vbr::Point3 sizes[] = { { 1, 1, 1 },
    { 7, 5, 1 },
    { 63, 20, 1 },
    { 64, 33, 1 },
    { 65, 17, 1 },
    { 128, 40, 1 },
    { 130, 9, 1 },
    { 20, 129, 1 },
    { 65, 64, 1 },
    { 64, 65, 1 },
    { 130, 129, 1 }, // blocks of 64 x 64 bits past the first in both axes, partial in both
    { 3, 90, 1 },
    { 1, 40, 1 } }; // one bit of one word per row
  unsigned seed = 900;
  for (const auto& d : sizes)
    for (double density : { 0.0, 0.1, 0.5, 0.9, 1.0 })
      for (int repeated : { 0, 1, 2 }) // repeated rows, repeated columns
      {
        const vbr::BitVolume v = repeated == 0 ? bf::randomVolume(d, density, seed++)
          : repeated == 1                      ? imageWithRepeatedRows(d[0], d[1], density, seed++)
                          : transposedPixels(imageWithRepeatedRows(d[1], d[0], density, seed++));
        const vbr::EVM evm = vbr::extractEVM2D(v);
        for (const vbr::AxisOrder order : { vbr::AxisOrder{ 2, 1, 0 }, vbr::AxisOrder{ 2, 0, 1 } })
        {
          const vbr::CUDB expected = vbr::buildCUDB(evm.sortedAs(order));
          for (bool vertex : { false, true })
          {
            SCOPED_TRACE(std::to_string(d[0]) + "x" + std::to_string(d[1]) + " density " +
              std::to_string(density) + " repeated " + std::to_string(repeated) + " order " +
              vbr::axisOrderName(order) + (vertex ? " vertex" : " face"));
            const vbr::Connectivity c =
              vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
            vbr::CUDB cudb;
            vbr::Components components;
            std::size_t vertices = 0;
            ASSERT_TRUE(vbr::buildCUDBComponents2D(
              v, order, c, vbr::Execution(), cudb, components, &vertices));
            EXPECT_EQ(vertices, evm.size());
            EXPECT_EQ(cudb.dimension, 2);
            EXPECT_EQ(cudb.order, order);
            EXPECT_EQ(cudb.boxes, expected.boxes);
            EXPECT_EQ(cudb.oudbBoxCount, expected.oudbBoxCount);
            EXPECT_EQ(components.boxLabel, vbr::labelComponents(expected, c).boxLabel);
            int count = 0;
            const std::vector<int> flood = bf::floodFillLabels(v, vertex, count);
            EXPECT_EQ(components.count, static_cast<std::uint32_t>(count));
            expectExactCover(v, cudb.boxes);
            expectSamePartition(paintedLabels(v, cudb, components), flood);
            if (order == vbr::AxisOrder{ 2, 1, 0 })
            {
              vbr::CUDB plain;
              vbr::Components plainComponents;
              EXPECT_EQ(vbr::buildCUDBComponents2D(v, c, plain, plainComponents), evm.size());
              EXPECT_EQ(plain.boxes, cudb.boxes);
            }
          }
        }
      }
}

TEST(CUDB, ReusedMemoryChangesNothing2D)
{
  // One set of outputs and one union-find memory handed to buildCUDBComponents2D and
  // labelPixelRuns for image after image (larger, smaller, empty, both sortings and
  // connectivities), starting from stale values: every result equals that of the EVM's CUDB.
  const vbr::Point3 sizes[] = {
    { 130, 29, 1 }, { 7, 5, 1 }, { 65, 80, 1 }, { 1, 1, 1 }, { 64, 33, 1 }, { 3, 90, 1 }
  };
  vbr::CUDB cudb;
  vbr::Components components;
  vbr::PixelRuns runs;
  std::vector<std::uint32_t> memory(1000, 7u);
  cudb.boxes.resize(50);
  components.boxLabel.assign(300, 9u);
  components.count = 4;
  runs.boxes.assign(400, 3u);
  runs.rowStarts.assign(20, 1u);
  vbr::PixelRunComponents labelled;
  labelled.components.boxLabel.assign(500, 5u);
  labelled.runs.boxes.assign(70, 2u);
  unsigned seed = 4100;
  for (int pass = 0; pass < 2; ++pass)
    for (const auto& d : sizes)
      for (double density : { 0.0, 0.3, 0.7 })
        for (const vbr::AxisOrder order : { vbr::AxisOrder{ 2, 1, 0 }, vbr::AxisOrder{ 2, 0, 1 } })
          for (bool vertex : { false, true })
          {
            SCOPED_TRACE(std::to_string(d[0]) + "x" + std::to_string(d[1]) + " density " +
              std::to_string(density) + " order " + vbr::axisOrderName(order) +
              (vertex ? " vertex" : " face"));
            const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
            const vbr::Connectivity c =
              vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
            const vbr::EVM evm = vbr::extractEVM2D(v);
            const vbr::CUDB expected = vbr::buildCUDB(evm.sortedAs(order));
            const vbr::Components expectedComponents = vbr::labelComponents(expected, c);
            std::size_t vertices = 0;
            ASSERT_TRUE(vbr::buildCUDBComponents2D(
              v, order, c, vbr::Execution(), cudb, components, &vertices, &runs, &memory));
            EXPECT_EQ(vertices, evm.size());
            EXPECT_EQ(cudb.boxes, expected.boxes);
            EXPECT_EQ(cudb.oudbBoxCount, expected.oudbBoxCount);
            EXPECT_EQ(components.boxLabel, expectedComponents.boxLabel);
            EXPECT_EQ(components.count, expectedComponents.count);
            if (order != vbr::AxisOrder{ 2, 1, 0 })
              continue;
            ASSERT_TRUE(vbr::labelPixelRuns(v, c, vbr::Execution(), labelled, &memory));
            EXPECT_EQ(labelled.components.boxLabel, expectedComponents.boxLabel);
            EXPECT_EQ(labelled.components.count, expectedComponents.count);
            EXPECT_EQ(labelled.oudbBoxCount, expected.oudbBoxCount);
            EXPECT_EQ(labelled.runs.boxes, runs.boxes);
            EXPECT_EQ(labelled.runs.rowStarts, runs.rowStarts);
            // The runs against the pixels: row y's runs, in order, are boxes of that row.
            ASSERT_EQ(runs.rowStarts.size(), std::size_t(d[1]) + 1);
            std::vector<vbr::Coord> ends(v.wordsPerRow() * 64 + 2);
            for (std::int32_t y = 0; y < d[1]; ++y)
            {
              const vbr::Coord* last = vbr::pixelRowRunEnds(v, y, ends.data());
              const std::size_t n = static_cast<std::size_t>(last - ends.data()) / 2;
              ASSERT_EQ(runs.rowStarts[y + 1] - runs.rowStarts[y], n);
              for (std::size_t i = 0; i < n; ++i)
              {
                const vbr::Box& box = expected.boxes[runs.boxes[runs.rowStarts[y] + i]];
                EXPECT_EQ(box.lo[0], ends[2 * i]);
                EXPECT_EQ(box.hi[0], ends[2 * i + 1]);
                EXPECT_LE(box.lo[1], y);
                EXPECT_GT(box.hi[1], y);
              }
            }
          }
}

TEST(CUDB, PixelRunsWithoutBoxes)
{
  // labelPixelRuns against the EVM's CUDB in the ZYX sorting: the same components of the
  // boxes, box count, OUDB count and EVM size, and for every run, found here pixel by pixel,
  // the box that holds it (same x interval, its row inside); countPixelRuns and
  // pixelRowRunEnds against the same runs.
  const vbr::Point3 sizes[] = { { 1, 1, 1 },
    { 7, 5, 1 },
    { 63, 20, 1 },
    { 64, 33, 1 },
    { 65, 17, 1 },
    { 130, 29, 1 },
    { 3, 90, 1 },
    { 1, 40, 1 } };
  unsigned seed = 1300;
  for (const auto& d : sizes)
    for (double density : { 0.0, 0.1, 0.5, 0.9, 1.0 })
      for (bool repeated : { false, true })
      {
        const vbr::BitVolume v = repeated ? imageWithRepeatedRows(d[0], d[1], density, seed++)
                                          : bf::randomVolume(d, density, seed++);
        const vbr::EVM evm = vbr::extractEVM2D(v);
        const vbr::CUDB expected = vbr::buildCUDB(evm.sortedAs(vbr::AxisOrder{ 2, 1, 0 }));
        std::vector<std::array<vbr::Coord, 3>> runs; // y, x0, x1 in scan order
        for (vbr::Coord y = 0; y < d[1]; ++y)
          for (vbr::Coord x = 0; x < d[0]; ++x)
            if (v.get(x, y, 0) && (x == 0 || !v.get(x - 1, y, 0)))
            {
              vbr::Coord end = x;
              while (end < d[0] && v.get(end, y, 0))
                ++end;
              runs.push_back({ y, x, end });
            }
        EXPECT_EQ(vbr::countPixelRuns(v), runs.size());
        std::vector<vbr::Coord> ends(v.wordsPerRow() * 64 + 2);
        std::size_t next = 0;
        for (vbr::Coord y = 0; y < d[1]; ++y)
        {
          const vbr::Coord* last = vbr::pixelRowRunEnds(v, y, ends.data());
          for (const vbr::Coord* e = ends.data(); e != last; e += 2, ++next)
            ASSERT_TRUE(
              next < runs.size() && runs[next] == (std::array<vbr::Coord, 3>{ y, e[0], e[1] }));
        }
        EXPECT_EQ(next, runs.size());
        for (bool vertex : { false, true })
        {
          SCOPED_TRACE(std::to_string(d[0]) + "x" + std::to_string(d[1]) + " density " +
            std::to_string(density) + (repeated ? " repeated" : "") +
            (vertex ? " vertex" : " face"));
          const vbr::Connectivity c = vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
          vbr::PixelRunComponents got;
          ASSERT_TRUE(vbr::labelPixelRuns(v, c, vbr::Execution(), got));
          EXPECT_EQ(got.boxCount(), expected.boxes.size());
          EXPECT_EQ(got.oudbBoxCount, expected.oudbBoxCount);
          EXPECT_EQ(got.extremeVertices, evm.size());
          EXPECT_EQ(got.components.boxLabel, vbr::labelComponents(expected, c).boxLabel);
          ASSERT_EQ(got.runs.boxes.size(), runs.size());
          for (std::size_t i = 0; i < runs.size(); ++i)
          {
            const vbr::Box& box = expected.boxes[got.runs.boxes[i]];
            EXPECT_TRUE(box.lo[0] == runs[i][1] && box.hi[0] == runs[i][2] &&
              box.lo[1] <= runs[i][0] && runs[i][0] < box.hi[1])
              << "run " << i;
          }
        }
      }
}

TEST(CUDB, PixelRunsOfShortRunsMatchFloodFill)
{
  // labelPixelRuns on images of short runs (random pixels, a checkerboard with flips) against
  // the flood fill, pixel by pixel and numbered alike: every run of a row painted with the label
  // of its box.
  const vbr::Point3 sizes[] = { { 63, 40, 1 }, { 64, 31, 1 }, { 129, 25, 1 }, { 300, 12, 1 } };
  unsigned seed = 1700;
  for (const auto& d : sizes)
    for (int kind = 0; kind < 4; ++kind)
    {
      vbr::BitVolume v = bf::randomVolume(d, 0.3 + 0.2 * kind, seed++);
      if (kind == 3)
      {
        const vbr::BitVolume flips = bf::randomVolume(d, 0.1, seed++);
        for (vbr::Coord y = 0; y < d[1]; ++y)
          for (vbr::Coord x = 0; x < d[0]; ++x)
            v.set(x, y, 0, ((x + y) % 2 == 0) != flips.get(x, y, 0));
      }
      for (bool vertex : { false, true })
      {
        SCOPED_TRACE(std::to_string(d[0]) + "x" + std::to_string(d[1]) + " kind " +
          std::to_string(kind) + (vertex ? " vertex" : " face"));
        const vbr::Connectivity c = vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face;
        vbr::PixelRunComponents got;
        ASSERT_TRUE(vbr::labelPixelRuns(v, c, vbr::Execution(), got));
        std::vector<int> painted(v.voxelCount(), 0);
        std::size_t run = 0;
        for (vbr::Coord y = 0; y < d[1]; ++y)
          for (vbr::Coord x = 0; x < d[0]; ++x)
            if (v.get(x, y, 0))
            {
              if (x == 0 || !v.get(x - 1, y, 0))
                ++run;
              ASSERT_LE(run, got.runs.boxes.size());
              painted[std::size_t(y) * d[0] + x] =
                static_cast<int>(got.components.boxLabel[got.runs.boxes[run - 1]]);
            }
        int count = 0;
        const std::vector<int> expected = bf::floodFillLabels(v, vertex, count);
        EXPECT_EQ(got.components.count, static_cast<std::uint32_t>(count));
        EXPECT_EQ(painted, expected);
      }
    }
}

TEST(CUDB, PixelRunsPaintTheBoxes)
{
  // paintPixelRuns from the runs of the ZYX sweep into a zeroed rectangle, against box-by-box
  // loops: every pixel of a run gets the value of the box that covers it, every other pixel
  // of the rectangle stays 0 (removed boxes too), nothing outside the rectangle is written. Widths
  // around the fixed stores (8 pixels) and the 64-bit words, the rectangle at an offset in a wider
  // grid, one thread and three (ranges of rows that start inside the runs).
  // paintPixelRunsOverwriting the same into the whole grid, its other pixels 0 whatever they held,
  // and refuses pixels that do not fit in the grid.
  const vbr::Point3 sizes[] = { { 1, 1, 1 },
    { 3, 7, 1 },
    { 8, 5, 1 },
    { 9, 6, 1 },
    { 16, 4, 1 },
    { 17, 30, 1 },
    { 63, 20, 1 },
    { 64, 33, 1 },
    { 65, 17, 1 },
    { 130, 41, 1 } };
  unsigned seed = 1700;
  for (const auto& d : sizes)
    for (double density : { 0.0, 0.2, 0.5, 0.8, 1.0 })
      for (bool vertex : { false, true })
      {
        SCOPED_TRACE(std::to_string(d[0]) + "x" + std::to_string(d[1]) + " density " +
          std::to_string(density) + (vertex ? " vertex" : " face"));
        const vbr::BitVolume v = bf::randomVolume(d, density, seed++);
        vbr::CUDB cudb;
        vbr::Components components;
        vbr::PixelRuns pixelRuns;
        ASSERT_TRUE(vbr::buildCUDBComponents2D(v,
          vbr::AxisOrder{ 2, 1, 0 },
          vertex ? vbr::Connectivity::Vertex : vbr::Connectivity::Face,
          vbr::Execution(),
          cudb,
          components,
          nullptr,
          &pixelRuns));
        std::size_t runs = 0;
        std::vector<std::size_t> rowStarts{ 0 };
        for (vbr::Coord y = 0; y < d[1]; ++y)
        {
          for (vbr::Coord x = 0; x < d[0]; ++x)
            runs += v.get(x, y, 0) && (x == 0 || !v.get(x - 1, y, 0));
          rowStarts.push_back(runs);
        }
        EXPECT_EQ(pixelRuns.boxes.size(), runs);
        EXPECT_EQ(pixelRuns.rowStarts, rowStarts);
        const vbr::Coord width = d[0] + 11, height = d[1] + 5, ox = 3, oy = 2;
        if (runs > 0) // a list that is not one box per run is refused before anything is written
        {
          std::vector<std::int32_t> untouched(std::size_t(width) * height, -7);
          vbr::PixelRuns shorter = pixelRuns;
          shorter.boxes.pop_back();
          const std::vector<std::int32_t> value(cudb.boxes.size(), 1);
          EXPECT_THROW(vbr::paintPixelRuns(v, shorter, value, { ox, oy }, width, untouched.data()),
            std::invalid_argument);
          EXPECT_EQ(
            std::count(untouched.begin(), untouched.end(), -7), std::ptrdiff_t(untouched.size()));
          // The right count, one run moved to the next row: refused at that row, not read past.
          const auto moved = std::find_if(pixelRuns.rowStarts.begin() + 1,
            pixelRuns.rowStarts.end() - 1,
            [](std::size_t start) { return start > 0; });
          if (moved != pixelRuns.rowStarts.end() - 1)
          {
            vbr::PixelRuns shifted = pixelRuns;
            --shifted.rowStarts[std::size_t(moved - pixelRuns.rowStarts.begin())];
            EXPECT_THROW(
              vbr::paintPixelRuns(v, shifted, value, { ox, oy }, width, untouched.data()),
              std::invalid_argument);
          }
        }
        for (int removed : { 0, 3 }) // every box kept; every third box's value 0
        {
          std::vector<std::int32_t> value(cudb.boxes.size());
          for (std::size_t b = 0; b < value.size(); ++b)
            value[b] = removed && b % removed == 0 ? 0 : static_cast<std::int32_t>(b + 1);
          std::vector<std::int32_t> expected(std::size_t(width) * height, -7);
          for (vbr::Coord y = 0; y < d[1]; ++y)
            for (vbr::Coord x = 0; x < d[0]; ++x)
              expected[std::size_t(y + oy) * width + x + ox] = 0;
          for (std::size_t b = 0; b < cudb.boxes.size(); ++b)
            for (vbr::Coord y = cudb.boxes[b].lo[1]; y < cudb.boxes[b].hi[1]; ++y)
              for (vbr::Coord x = cudb.boxes[b].lo[0]; x < cudb.boxes[b].hi[0]; ++x)
                expected[std::size_t(y + oy) * width + x + ox] = value[b];
          for (int threads : { 1, 3 })
          {
            std::vector<std::int32_t> painted(expected.size(), -7);
            for (vbr::Coord y = 0; y < d[1]; ++y)
              std::fill_n(painted.begin() + std::ptrdiff_t(y + oy) * width + ox, d[0], 0);
            EXPECT_TRUE(vbr::paintPixelRuns(v,
              pixelRuns,
              value,
              { ox, oy },
              width,
              painted.data(),
              threads == 1 ? vbr::Execution() : bf::threadedExecution(threads)));
            EXPECT_EQ(painted, expected) << threads << " threads, removed " << removed;
            // Overwriting: the whole image written, whatever it held, 0 outside the runs.
            std::vector<std::int32_t> overwritten(expected.size(), -7);
            EXPECT_TRUE(vbr::paintPixelRunsOverwriting(v,
              pixelRuns,
              value,
              { ox, oy },
              width,
              height,
              overwritten.data(),
              threads == 1 ? vbr::Execution() : bf::threadedExecution(threads)));
            std::vector<std::int32_t> whole = expected;
            std::replace(whole.begin(), whole.end(), -7, 0);
            EXPECT_EQ(overwritten, whole) << threads << " threads, removed " << removed;
          }
        }
        // Pixels that do not fit in the image are refused before anything is written.
        std::vector<std::int32_t> untouched(std::size_t(width) * height, -7);
        const std::vector<std::int32_t> ones(cudb.boxes.size(), 1);
        EXPECT_THROW(vbr::paintPixelRunsOverwriting(
                       v, pixelRuns, ones, { 12, oy }, width, height, untouched.data()),
          std::invalid_argument);
        EXPECT_THROW(vbr::paintPixelRunsOverwriting(
                       v, pixelRuns, ones, { ox, 6 }, width, height, untouched.data()),
          std::invalid_argument);
        EXPECT_EQ(
          std::count(untouched.begin(), untouched.end(), -7), std::ptrdiff_t(untouched.size()));
      }
}

TEST(CUDB, PixelRunsAbortBetweenSteps)
{
  // A stop asked for while the runs are painted: the painting stops at the first poll told to,
  // between its steps of rows (here 4 of 256 rows: 2^14 words each), returns false, and the
  // rows after the steps done stay 0; the progress reported before it increases within [0, 1).
  // Not told to stop, it polls before every step and paints what box-by-box loops paint.
  const vbr::BitVolume v = bf::randomVolume({ 4096, 1024, 1 }, 0.5, 77);
  vbr::CUDB cudb;
  vbr::Components components;
  vbr::PixelRuns runs;
  ASSERT_TRUE(vbr::buildCUDBComponents2D(v,
    vbr::AxisOrder{ 2, 1, 0 },
    vbr::Connectivity::Vertex,
    vbr::Execution(),
    cudb,
    components,
    nullptr,
    &runs));
  std::vector<std::int32_t> value(cudb.boxes.size());
  for (std::size_t b = 0; b < value.size(); ++b)
    value[b] = static_cast<std::int32_t>(b + 1);
  const std::size_t width = 4096, rows = 1024, stepRows = 256;
  std::vector<std::int32_t> expected(width * rows, 0);
  for (std::size_t b = 0; b < cudb.boxes.size(); ++b)
    for (vbr::Coord y = cudb.boxes[b].lo[1]; y < cudb.boxes[b].hi[1]; ++y)
      for (vbr::Coord x = cudb.boxes[b].lo[0]; x < cudb.boxes[b].hi[0]; ++x)
        expected[std::size_t(y) * width + std::size_t(x)] = value[b];
  for (int threads : { 1, 2 })
  {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    vbr::Execution exec = threads == 1 ? vbr::Execution() : bf::threadedExecution(threads);
    int polls = 0;
    std::vector<double> reported;
    exec.aborted = [&polls] { return ++polls > 2; };
    exec.progress = [&reported](double f)
    {
      reported.push_back(f);
      return true;
    };
    std::vector<std::int32_t> painted(expected.size(), 0);
    EXPECT_FALSE(vbr::paintPixelRuns(v, runs, value, { 0, 0 }, width, painted.data(), exec));
    EXPECT_EQ(polls, 3) << "stops at the first poll that is told to";
    const auto done = static_cast<std::ptrdiff_t>(2 * stepRows * width);
    EXPECT_TRUE(std::equal(painted.begin(), painted.begin() + done, expected.begin()))
      << "the steps before the stop are painted";
    EXPECT_EQ(
      std::count(painted.begin() + done, painted.end(), 0), std::ptrdiff_t(painted.size()) - done)
      << "nothing is painted after the stop";
    EXPECT_EQ(reported, (std::vector<double>{ 0.0, 0.25 }));

    int quiet = 0;
    reported.clear();
    exec.aborted = [&quiet] { return ++quiet < 0; };
    std::fill(painted.begin(), painted.end(), 0);
    EXPECT_TRUE(vbr::paintPixelRuns(v, runs, value, { 0, 0 }, width, painted.data(), exec));
    EXPECT_EQ(quiet, 5) << "before every step, and once done";
    EXPECT_EQ(reported, (std::vector<double>{ 0.0, 0.25, 0.5, 0.75 }));
    EXPECT_EQ(painted, expected);
    // The same into a larger image of any content, at an offset.
    std::vector<std::int32_t> overwritten((width + 5) * (rows + 3), -7);
    EXPECT_TRUE(vbr::paintPixelRunsOverwriting(
      v, runs, value, { 5, 2 }, width + 5, rows + 3, overwritten.data(), exec));
    std::vector<std::int32_t> shifted(overwritten.size(), 0);
    for (std::size_t y = 0; y < rows; ++y)
      std::copy_n(expected.begin() + std::ptrdiff_t(y * width),
        width,
        shifted.begin() + std::ptrdiff_t((y + 2) * (width + 5) + 5));
    EXPECT_EQ(overwritten, shifted);
  }
}

TEST(CUDB, PixelRowsAbortInsideTheImage)
{
  // A stop asked for while the rows are swept: the sweep stops within a poll's stride of rows
  // and returns an empty CUDB, and it reported progress (increasing, within [0, 1]) before.
  // The image is wide (its rows are many words): over 20 polls in either sorting.
  vbr::BitVolume v(8192, 1000, 1);
  std::uint64_t state = 31;
  auto next = [&state]
  {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  for (vbr::Coord y = 0; y < v.size(1); ++y) // a pixel in 16 set, filled a word at a time
    for (std::size_t w = 0; w < v.wordsPerRow(); ++w)
      v.row(y, 0)[w] = next() & next() & next() & next();
  for (const vbr::AxisOrder order : { vbr::AxisOrder{ 2, 1, 0 }, vbr::AxisOrder{ 2, 0, 1 } })
  {
    int polls = 0;
    std::vector<double> reported;
    vbr::Execution exec;
    exec.aborted = [&polls] { return ++polls > 20; };
    exec.progress = [&reported](double f)
    {
      reported.push_back(f);
      return true;
    };
    vbr::CUDB cudb;
    vbr::Components components;
    EXPECT_FALSE(
      vbr::buildCUDBComponents2D(v, order, vbr::Connectivity::Face, exec, cudb, components));
    EXPECT_EQ(polls, 21) << "stops at the first poll that is told to";
    EXPECT_TRUE(cudb.boxes.empty());
    EXPECT_EQ(components.count, 0u);
    ASSERT_FALSE(reported.empty());
    EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
    EXPECT_GE(reported.front(), 0.0);
    EXPECT_LT(reported.back(), 1.0);
    EXPECT_GT(reported.back(), 0.0) << "progress within the sweep, not only at its start";

    // Not told to stop: it polls the same way all through and finishes.
    int quiet = 0;
    exec.aborted = [&quiet] { return ++quiet < 0; };
    ASSERT_TRUE(
      vbr::buildCUDBComponents2D(v, order, vbr::Connectivity::Face, exec, cudb, components));
    EXPECT_GT(quiet, 21) << "polled all along the sweep";
    EXPECT_FALSE(cudb.boxes.empty());
  }
}

TEST(CUDB, PixelRowsNeedASingleSlice)
{
  vbr::CUDB cudb;
  vbr::Components components;
  EXPECT_THROW(
    vbr::buildCUDBComponents2D(vbr::BitVolume(4, 4, 2), vbr::Connectivity::Face, cudb, components),
    std::invalid_argument);
}

TEST(CUDB, DegenerateInputs)
{
  const vbr::BitVolume empty(6, 5, 4);
  const vbr::CUDB none = vbr::buildCUDB(vbr::extractEVM(empty));
  EXPECT_TRUE(none.boxes.empty());
  EXPECT_EQ(vbr::labelComponents(none, vbr::Connectivity::Face).count, 0u);

  const vbr::BitVolume full = bf::randomVolume({ 70, 5, 3 }, 1.0, 1);
  for (const char* name : Orders)
  {
    const vbr::CUDB one =
      vbr::buildCUDB(vbr::extractEVM(full).sortedAs(vbr::axisOrderFromName(name)));
    ASSERT_EQ(one.boxes.size(), 1u);
    EXPECT_EQ(one.oudbBoxCount, 1u);
    EXPECT_EQ(one.boxes[0].hi, (std::array<vbr::Coord, 3>{ 70, 5, 3 }));
  }
  checkAll(fromPoints({ 3, 3, 3 }, { { 1, 1, 1 } }),
    vbr::extractEVM(fromPoints({ 3, 3, 3 }, { { 1, 1, 1 } })));

  // A thin plate is one box in every sorting.
  vbr::BitVolume plate(20, 20, 3);
  for (int y = 2; y < 18; ++y)
    for (int x = 1; x < 19; ++x)
      plate.set(x, y, 1);
  for (const char* name : Orders)
    EXPECT_EQ(
      vbr::buildCUDB(vbr::extractEVM(plate).sortedAs(vbr::axisOrderFromName(name))).boxes.size(),
      1u);
}

TEST(CUDB, NonManifoldContacts)
{
  using vbr::Connectivity;
  // Edge contact, corner contact, and both along every pair of axes.
  const std::vector<std::vector<vbr::Point3>> touching = { { { 0, 0, 0 }, { 1, 1, 0 } },
    { { 0, 0, 0 }, { 0, 1, 1 } },
    { { 0, 0, 0 }, { 1, 0, 1 } },
    { { 1, 0, 0 }, { 0, 1, 0 } },
    { { 0, 0, 0 }, { 1, 1, 1 } },
    { { 1, 1, 0 }, { 0, 0, 1 } },
    { { 0, 1, 1 }, { 1, 0, 0 } } };
  for (const auto& points : touching)
  {
    const vbr::BitVolume v = fromPoints({ 2, 2, 2 }, points);
    EXPECT_EQ(componentCount(v, Connectivity::Face), 2u);
    EXPECT_EQ(componentCount(v, Connectivity::Vertex), 1u);
    const vbr::EVM zyx = vbr::extractEVM(v);
    for (const char* name : Orders)
      checkAll(v, zyx.sortedAs(vbr::axisOrderFromName(name)));
  }
  // 2D: a checkerboard is all separate pixels with 4-connectivity, one piece with 8.
  vbr::BitVolume board(9, 7, 1);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x)
      if ((x + y) % 2 == 0)
        board.set(x, y, 0);
  EXPECT_EQ(componentCount(board, Connectivity::Face), 32u);
  EXPECT_EQ(componentCount(board, Connectivity::Vertex), 1u);
}

TEST(CUDB, CompactionMergesWhatOUDBSplits)
{
  // 2D: a tall rectangle x [0, 2) y [0, 4) beside a short one x [3, 5) y [1, 2). The OUDB
  // (lines along y) splits the tall one at y = 1 and y = 2; the CUDB keeps it whole.
  vbr::BitVolume image(5, 4, 1);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 2; ++x)
      image.set(x, y, 0);
  for (int x = 3; x < 5; ++x)
    image.set(x, 1, 0);
  const vbr::CUDB flat = vbr::buildCUDB(vbr::extractEVM2D(image));
  EXPECT_EQ(flat.oudbBoxCount, 4u);
  EXPECT_EQ(flat.boxes.size(), 2u);

  // 3D: the tall rectangle extruded along z over [0, 3) and a unit cube at (6, 2, 1). ZYX:
  // the cube makes three slices along z, and in the middle one its lines y = 2 and y = 3
  // split the prism: the OUDB has 1 + 4 + 1 boxes, the CUDB the prism and the cube.
  vbr::BitVolume volume(8, 4, 3);
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 2; ++x)
        volume.set(x, y, z);
  volume.set(6, 2, 1);
  const vbr::CUDB solid = vbr::buildCUDB(vbr::extractEVM(volume)); // ZYX
  EXPECT_EQ(solid.boxes.size(), 2u);
  // OUDB: slices z [0,1), [1,2), [2,3); the middle one's lines y = 2, 3 split the prism.
  EXPECT_EQ(solid.oudbBoxCount, 1u + 4u + 1u);

  // The phantom: compaction never loses, and wins in every sorting.
  const std::vector<std::uint8_t> labels = vbr::makePhantom({ 48, 48, 48 });
  vbr::BitVolume phantom(48, 48, 48);
  for (int z = 0; z < 48; ++z)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x)
        if (labels[indexOf(phantom, x, y, z)] != 0)
          phantom.set(x, y, z);
  const vbr::EVM zyx = vbr::extractEVM(phantom);
  for (const char* name : Orders)
  {
    const vbr::CUDB c = vbr::buildCUDB(zyx.sortedAs(vbr::axisOrderFromName(name)));
    EXPECT_LT(c.boxes.size(), c.oudbBoxCount) << name;
  }
}

TEST(CUDB, NeighbourListsAreTheContacts)
{
  const vbr::BitVolume v = bf::randomVolume({ 12, 11, 10 }, 0.5, 7);
  const vbr::CUDB cudb = vbr::buildCUDB(vbr::extractEVM(v).sortedAs(vbr::axisOrderFromName("YZX")));
  for (auto connectivity : { vbr::Connectivity::Face, vbr::Connectivity::Vertex })
  {
    // Per role (A, B): pairs (backward, forward) from the backward lists, from the
    // forward lists, and from the contacts.
    std::set<std::pair<std::uint32_t, std::uint32_t>> fromBack[2], fromFront[2], fromContacts[2];
    for (int role = 0; role < 2; ++role)
    {
      const auto back = cudb.neighbours(role, false, connectivity);
      const auto front = cudb.neighbours(role, true, connectivity);
      for (std::uint32_t b = 0; b < cudb.boxes.size(); ++b)
      {
        for (std::uint32_t k = back.start[b]; k < back.start[b + 1]; ++k)
          fromBack[role].insert({ back.boxes[k], b });
        for (std::uint32_t k = front.start[b]; k < front.start[b + 1]; ++k)
          fromFront[role].insert({ b, front.boxes[k] });
      }
    }
    for (const vbr::BoxContact& c : cudb.contacts)
      if (connectivity == vbr::Connectivity::Vertex || c.face)
        fromContacts[c.axis == cudb.order[0] ? 0 : 1].insert({ c.backward, c.forward });
    EXPECT_FALSE(fromContacts[0].empty());
    EXPECT_EQ(fromBack[0], fromFront[0]);
    EXPECT_EQ(fromBack[1], fromFront[1]);
    EXPECT_EQ(fromBack[0], fromContacts[0]);
    EXPECT_EQ(fromBack[1], fromContacts[1]);
  }
}

TEST(CUDB, PaintBoxesInEveryAxisOrder)
{
  // Boxes in permuted, shifted coordinates painted by parallel slices (or rows of a single
  // slice) against one voxel at a time; later boxes overwrite earlier ones in both. The long
  // rows of the third grid reach every length class of the row writes (up to 3, 4 to 8, 9 to
  // 16, longer), with the image's own axis order and the others.
  const std::array<int, 3> permutations[] = {
    { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 }, { 2, 1, 0 }
  };
  const std::array<vbr::Coord, 3> grids[] = { { 9, 7, 5 }, { 6, 11, 1 }, { 45, 9, 4 } };
  unsigned seed = 11;
  for (const auto& axes : permutations)
    for (const auto& dims : grids)
    {
      std::array<vbr::Coord, 3> offset{ 1, 0, 2 };
      for (int k = 0; k < 3; ++k)
        offset[k] = std::min(offset[k], dims[axes[k]] - 1); // room for a voxel
      std::vector<vbr::Box> boxes;
      std::vector<std::int32_t> value;
      for (int b = 0; b < 120; ++b)
      {
        vbr::Box box;
        for (int k = 0; k < 3; ++k)
        {
          const vbr::Coord n = dims[axes[k]] - offset[k];
          seed = seed * 1103515245u + 12345u;
          box.lo[k] = static_cast<vbr::Coord>((seed >> 8) % n);
          seed = seed * 1103515245u + 12345u;
          box.hi[k] = box.lo[k] + 1 + static_cast<vbr::Coord>((seed >> 8) % (n - box.lo[k]));
        }
        boxes.push_back(box);
        value.push_back(b % 7); // 0: skipped
      }
      std::vector<std::int32_t> expected(std::size_t(dims[0]) * dims[1] * dims[2], -1);
      for (std::size_t b = 0; b < boxes.size(); ++b)
      {
        if (value[b] == 0)
          continue;
        std::array<vbr::Coord, 3> p;
        for (p[0] = boxes[b].lo[0]; p[0] < boxes[b].hi[0]; ++p[0])
          for (p[1] = boxes[b].lo[1]; p[1] < boxes[b].hi[1]; ++p[1])
            for (p[2] = boxes[b].lo[2]; p[2] < boxes[b].hi[2]; ++p[2])
            {
              std::array<std::size_t, 3> g;
              for (int k = 0; k < 3; ++k)
                g[axes[k]] = static_cast<std::size_t>(p[k] + offset[k]);
              expected[(g[2] * dims[1] + g[1]) * dims[0] + g[0]] = value[b];
            }
      }
      std::vector<std::int32_t> painted(expected.size(), -1);
      vbr::paintBoxes(boxes, value, offset, axes, dims, painted.data(), bf::threadedExecution(3));
      EXPECT_EQ(painted, expected);
    }
}

TEST(CUDB, Abort)
{
  const vbr::BitVolume v = bf::randomVolume({ 40, 40, 40 }, 0.5, 9);
  vbr::Execution exec;
  exec.aborted = [] { return true; };
  vbr::CUDB out;
  EXPECT_FALSE(vbr::buildCUDB(vbr::extractEVM(v), exec, out));
  vbr::Components components;
  EXPECT_FALSE(
    vbr::buildCUDBComponents(vbr::extractEVM(v), vbr::Connectivity::Face, exec, out, components));
}

// paintBoxes asks whether to stop every 4096 boxes in each worker: told to stop at once it
// writes nothing and says so; told after a few polls it stops partway (fewer voxels written
// than boxes hold); never told, it paints every box. A volume and a single slice (the planar
// loop), one and three threads.
TEST(CUDB, PaintBoxesStopsWhenAsked)
{
  for (const vbr::Point3 dims : { vbr::Point3{ 48, 48, 48 }, vbr::Point3{ 700, 700, 1 } })
    for (int threads : { 1, 3 })
    {
      SCOPED_TRACE(testing::Message()
        << dims[0] << "x" << dims[1] << "x" << dims[2] << ", " << threads << " threads");
      const vbr::BitVolume v = bf::randomVolume(dims, 0.5, 21);
      vbr::CUDB cudb;
      vbr::Components components;
      ASSERT_TRUE(vbr::buildCUDBComponents(
        vbr::extractEVM(v), vbr::Connectivity::Face, vbr::Execution(), cudb, components));
      ASSERT_GT(cudb.boxes.size(), 3u * 4096u); // three polls per worker at least
      const std::vector<std::int32_t> value(cudb.boxes.size(), 1);
      auto written = [&](int stopAfter, bool& finished)
      {
        vbr::Execution exec = bf::threadedExecution(threads);
        auto polls = std::make_shared<std::atomic<int>>(0);
        exec.aborted = [polls, stopAfter] { return stopAfter >= 0 && (*polls)++ >= stopAfter; };
        std::vector<std::int32_t> labels(v.voxelCount(), 0);
        finished = vbr::paintBoxes(
          cudb.boxes, value, { 0, 0, 0 }, { 0, 1, 2 }, v.dims(), labels.data(), exec);
        return std::count(labels.begin(), labels.end(), 1);
      };
      bool finished = true;
      EXPECT_EQ(written(0, finished), 0);
      EXPECT_FALSE(finished);
      const auto all = written(-1, finished);
      EXPECT_TRUE(finished);
      EXPECT_EQ(all, static_cast<long>(v.count()));
      // Told after two polls: some worker is told at its first poll and paints none of its
      // rows, so not everything is written whatever the threads' order; only one thread
      // surely paints the boxes before its third poll (with three, the first two polls may
      // go to workers whose rows the first boxes do not reach).
      const auto partway = written(2, finished);
      EXPECT_FALSE(finished);
      EXPECT_LT(partway, all);
      if (threads == 1)
        EXPECT_GT(partway, 0);
    }
}

TEST(CUDB, InvalidEVMIsRejected)
{
  // A lone vertex is no EVM: its section never closes.
  const vbr::EVM bad(3, { 2, 1, 0 }, { vbr::Vertex{ 0, 0, 0 } });
  EXPECT_THROW(vbr::buildCUDB(bad), std::invalid_argument);
}
