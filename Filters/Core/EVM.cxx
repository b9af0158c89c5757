// Extreme vertices: extraction, sorting and the way back to voxels.
//
// Extraction (extractEVM) is one pass over the bit rows: for each row of vertices (y, z) the
// XOR of the four voxel rows around it holds, per x, the parity of the voxels on that side;
// vertex x is extreme where that parity changes (rowParityToVertexBits), i.e. where an odd
// number of the eight voxels around it is set. Two passes over the planes of vertices, in
// parallel: the first counts each plane's set bits, the second (after a prefix sum) writes
// them in order straight into the EVM's one array (writeRowVertices), with no per-plane
// vector to grow and copy: the result is ZYX-sorted without sorting (collectVertices).
//
// extractEVM2D does the same with the two pixel rows around a line of vertices, their XOR
// made word by word on the fly. Its counting pass also counts what the filter reports of a 2D
// image (PlanarCounts: pixels, boundary edges, lines and columns of vertices), so that a 2D
// image takes one pass over its pixels before the writing one, not three more. That pass skips
// a word with one test where both rows are uniform (all set or all clear) and continue the
// bits before, most words of a fax page, and counts bits by the POPCNT instruction in a copy
// compiled for it where the build does not assume it (PopCount.h).
//
// Sorting (sortedAs): when the new order is a rotation or a swap of the old one, a single
// stable bucket pass on one coordinate keeps the order of the two others (bucketedOn, with
// threads by slabs of the vertices: the same order); otherwise the coordinates are packed
// into keys and radix-sorted. toVoxels is the inverse of extraction: a parity grid of the
// vertices, XOR-prefixed along each in-plane axis.

#include "EVM.h"

#include "HugePages.h"
#include "PopCount.h"
#include "RadixSort.h"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <stdexcept>
#include <utility>

namespace vbr
{

namespace
{

const char* const AxisNames = "XYZ";

/// Writes the set bits of a row of vertex words as vertices (a, b, x) from `out` on.
void writeRowVertices(const Word* bits, std::size_t words, Coord a, Coord b, Vertex*& out)
{
  for (std::size_t w = 0; w < words; ++w)
  {
    Word e = bits[w];
    while (e)
    {
      *out++ = { a, b, static_cast<Coord>(w * 64 + countTrailingZeros(e)) };
      e &= e - 1;
    }
  }
}

/// The number of set bits of a row of vertex words.
std::size_t countRowVertices(const Word* bits, std::size_t words)
{
  std::size_t n = 0;
  for (std::size_t w = 0; w < words; ++w)
    n += static_cast<std::size_t>(popCount(bits[w]));
  return n;
}

/// Turns the XOR of the voxel rows around a row of vertices into the vertex bits: vertex x is
/// extreme when voxels x-1 and x of that XOR differ.
void rowParityToVertexBits(const Word* parity, std::size_t rowWords, Word* vertexBits)
{
  Word carry = 0;
  for (std::size_t w = 0; w < rowWords; ++w)
  {
    vertexBits[w] = transitions(parity[w], carry);
    carry = parity[w] >> 63;
  }
  vertexBits[rowWords] = carry;
}

/// The vertices of `count` runs (planes or lines of vertices) in one array, in run order:
/// countRuns(sizes) sets sizes[r] to the number of vertices of every run r (in parallel as it
/// likes), then, after a prefix sum, writeRun(r, out) writes those of run r from `out` on, in
/// parallel over the runs. With `kept`, into its memory (kept from an earlier call: see
/// extractEVM2D), grown in small pages, as memory faulted in once is.
template<typename CountRuns, typename WriteRun>
std::vector<Vertex> collectVertices(std::int64_t count,
  const Execution& exec,
  CountRuns&& countRuns,
  WriteRun&& writeRun,
  std::vector<Vertex>* kept = nullptr)
{
  std::vector<std::size_t> start(static_cast<std::size_t>(count) + 1, 0);
  countRuns(start.data() + 1);
  for (std::size_t r = 0; r + 1 < start.size(); ++r)
    start[r + 1] += start[r];
  std::vector<Vertex> vertices;
  if (kept)
  {
    // Every value is written below: the old ones are left in place (the resize below zeroes
    // only values past them), not copied into new room when it is too small.
    vertices.swap(*kept);
    if (vertices.capacity() < start.back())
      std::vector<Vertex>().swap(vertices);
    vertices.reserve(start.back());
  }
  else
    reserveHugePages(vertices, start.back());
  vertices.resize(start.back());
  exec.forRange(count,
    [&](std::int64_t rb, std::int64_t re)
    {
      for (std::int64_t r = rb; r < re; ++r)
      {
        Vertex* out = vertices.data() + start[r];
        writeRun(r, out);
      }
    });
  return vertices;
}

/// collectVertices for runs given by rows(r, visit), which calls visit(a, b, vertexBits) for
/// each row (a, b) of vertices of run r, in order (`words` words a row).
template<typename Rows>
std::vector<Vertex> collectRowVertices(std::int64_t count,
  std::size_t words,
  const Execution& exec,
  Rows&& rows)
{
  return collectVertices(
    count,
    exec,
    [&](std::size_t* sizes)
    {
      exec.forRange(count,
        [&](std::int64_t rb, std::int64_t re)
        {
          for (std::int64_t r = rb; r < re; ++r)
          {
            std::size_t n = 0;
            rows(r, [&](Coord, Coord, const Word* bits) { n += countRowVertices(bits, words); });
            sizes[r] = n;
          }
        });
    },
    [&](std::int64_t r, Vertex* out)
    {
      rows(
        r, [&](Coord a, Coord b, const Word* bits) { writeRowVertices(bits, words, a, b, out); });
    });
}

} // namespace

AxisOrder axisOrderFromName(const std::string& name)
{
  if (name.size() != 3)
    throw std::invalid_argument("axis order must have three letters: " + name);
  AxisOrder order{};
  int seen = 0;
  for (int k = 0; k < 3; ++k)
  {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(name[k])));
    if (c < 'X' || c > 'Z' || (seen & (1 << (c - 'X'))))
      throw std::invalid_argument("not an ABC sorting: " + name);
    order[k] = c - 'X';
    seen |= 1 << order[k];
  }
  return order;
}

std::string axisOrderName(const AxisOrder& order)
{
  return { AxisNames[order[0]], AxisNames[order[1]], AxisNames[order[2]] };
}

int axisOrderParity(const AxisOrder& order)
{
  return ((order[1] - order[0] + 3) % 3 == 1) ? 1 : -1;
}

EVM::EVM(int dimension, const AxisOrder& order, std::vector<Vertex> sortedVertices)
  : Dimension(dimension)
  , Order(order)
  , Vertices(std::move(sortedVertices))
{
  assert(std::is_sorted(this->Vertices.begin(), this->Vertices.end()));
}

std::array<Coord, 3> EVM::worldVertex(std::size_t i) const
{
  std::array<Coord, 3> w{ 0, 0, 0 };
  for (int k = 0; k < 3; ++k)
    w[this->Order[k]] = this->Vertices[i][k];
  return w;
}

EVM EVM::sortedAs(const AxisOrder& order, const Execution& exec) const
{
  return this->sortedAs(order, exec, std::vector<Vertex>());
}

EVM EVM::sortedAs(const AxisOrder& order, const Execution& exec, std::vector<Vertex> storage) const
{
  if (this->Dimension == 2 && order[0] != this->Order[0])
    throw std::invalid_argument("a 2D EVM keeps its plane normal as first axis");
  if (this->Dimension == 3 && !this->Vertices.empty())
  {
    // A stable bucket pass on one coordinate keeps the order of the two others: from
    // (A, B, C) it gives (C, A, B) when bucketing on C and (B, A, C) when bucketing on B.
    if (order == AxisOrder{ this->Order[2], this->Order[0], this->Order[1] })
      return this->bucketedOn(2, order, exec, std::move(storage));
    if (order == AxisOrder{ this->Order[1], this->Order[0], this->Order[2] })
      return this->bucketedOn(1, order, exec, std::move(storage));
  }
  std::vector<Vertex> v = std::move(storage);
  reserveHugePages(v, this->Vertices.size());
  v.resize(this->Vertices.size());
  bool packable = true;
  Coord maximum = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    const auto w = this->worldVertex(i);
    v[i] = { w[order[0]], w[order[1]], w[order[2]] };
    for (Coord c : v[i])
    {
      packable = packable && c >= 0 && c < PackedCoordinateLimit;
      maximum = std::max(maximum, c);
    }
  }
  if (!packable)
  {
    std::sort(v.begin(), v.end());
    return EVM(this->Dimension, order, std::move(v));
  }
  const KeyPacker packer = KeyPacker::forMaximum(maximum);
  std::vector<std::uint64_t> keys;
  reserveHugePages(keys, v.size());
  keys.resize(v.size());
  exec.forRange(static_cast<std::int64_t>(v.size()),
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t i = b; i < e; ++i)
        keys[i] = packer.pack(v[i][0], v[i][1], v[i][2]);
    });
  radixSort(keys);
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = packer.unpack(keys[i]);
  return EVM(this->Dimension, order, std::move(v));
}

namespace
{

/// Counts the vertices of each slab by their coordinate `key` into start[s * window + k] for
/// the coordinates base + k, k < window; false when some coordinate lies outside the window.
bool countBuckets(const Vertex* in,
  std::size_t n,
  int key,
  std::int64_t base,
  std::size_t window,
  const Execution& exec,
  std::int64_t slabs,
  std::vector<std::size_t>& start)
{
  start.assign(static_cast<std::size_t>(slabs) * window, 0);
  std::vector<char> outside(static_cast<std::size_t>(slabs), 0);
  exec.forRange(slabs,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t s = b; s < e; ++s)
      {
        std::size_t* count = start.data() + s * window;
        for (std::size_t i = n * s / slabs, end = n * (s + 1) / slabs; i < end; ++i)
        {
          const std::uint64_t k = std::uint64_t(std::int64_t(in[i][key]) - base);
          if (k >= window)
          {
            outside[s] = 1;
            break;
          }
          ++count[k];
        }
      }
    });
  return std::find(outside.begin(), outside.end(), 1) == outside.end();
}

} // namespace

EVM EVM::bucketedOn(int key,
  const AxisOrder& order,
  const Execution& exec,
  std::vector<Vertex> out) const
{
  // A counting sort by slabs of the vertices, each slab counted and then scattered by its
  // own thread: a bucket's vertices of slab s go after those of the slabs before, so the
  // result is the one-slab order, vertex for vertex. One slab on one thread. The buckets are
  // first those of a window about the first vertex's coordinate, wide enough for a grid of
  // 2048 along the axis, checked as they are counted: no pass over the vertices for their
  // bounds (a third of the sort's time), unless a coordinate falls outside.
  const std::size_t n = this->Vertices.size();
  const Execution run = exec.forWork(static_cast<std::int64_t>(n));
  const std::int64_t slabs = run.parallelFor
    ? std::clamp<std::int64_t>(run.concurrency, 1, static_cast<std::int64_t>(n))
    : 1;
  const Vertex* in = this->Vertices.data();
  constexpr std::size_t Window = 4096;
  std::int64_t base = std::int64_t(in[0][key]) - std::int64_t(Window / 2);
  std::size_t window = Window;
  std::vector<std::size_t> start; // start[s * window + k]: where slab s writes bucket k first
  if (!countBuckets(in, n, key, base, window, run, slabs, start))
  {
    Coord lo = in[0][key], hi = lo;
    for (const Vertex& p : this->Vertices)
    {
      lo = std::min(lo, p[key]);
      hi = std::max(hi, p[key]);
    }
    base = lo;
    window = static_cast<std::size_t>(std::int64_t(hi) - std::int64_t(lo)) + 1;
    countBuckets(in, n, key, base, window, run, slabs, start);
  }
  std::size_t placed = 0;
  for (std::size_t k = 0; k < window; ++k)
    for (std::int64_t s = 0; s < slabs; ++s)
    {
      const std::size_t count = start[s * window + k];
      start[s * window + k] = placed;
      placed += count;
    }
  const int first = 0, second = key == 2 ? 1 : 2; // the two coordinates that stay in order
  reserveHugePages(out, n);
  out.resize(n);
  Vertex* to = out.data();
  run.forRange(slabs,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t s = b; s < e; ++s)
      {
        std::size_t* next = start.data() + s * window;
        for (std::size_t i = n * s / slabs, end = n * (s + 1) / slabs; i < end; ++i)
        {
          const Vertex& p = in[i];
          to[next[std::int64_t(p[key]) - base]++] = { p[key], p[first], p[second] };
        }
      }
    });
  return EVM(this->Dimension, order, std::move(out));
}

std::vector<std::size_t> EVM::planeStarts() const
{
  // The vertices are sorted by their plane's coordinate: each plane ends where a binary search
  // says, so the cost is in the planes (a few hundred), not the vertices (a million in noise).
  const int key = this->Dimension == 3 ? 0 : 1;
  std::vector<std::size_t> starts;
  const auto begin = this->Vertices.begin(), end = this->Vertices.end();
  for (auto plane = begin; plane != end;)
  {
    starts.push_back(static_cast<std::size_t>(plane - begin));
    plane = std::upper_bound(
      plane, end, (*plane)[key], [key](std::int32_t a, const Vertex& v) { return a < v[key]; });
  }
  starts.push_back(this->Vertices.size());
  return starts;
}

std::size_t EVM::planeCount() const
{
  return this->planeStarts().size() - 1;
}

BitVolume EVM::toVoxels(const std::array<std::int32_t, 3>& dims) const
{
  BitVolume out(dims[0], dims[1], dims[2]);
  if (this->Vertices.empty())
    return out;
  // Parity grid of the vertices; the prefix XOR over all vertices <= v (in every in-plane axis)
  // is the voxel whose lowest corner is v.
  const std::size_t gx = dims[0] + 1, gy = dims[1] + 1, gz = dims[2] + 1;
  std::vector<std::uint8_t> g(gx * gy * gz, 0);
  auto at = [&](std::size_t x, std::size_t y, std::size_t z) -> std::uint8_t&
  { return g[(z * gy + y) * gx + x]; };
  for (std::size_t i = 0; i < this->Vertices.size(); ++i)
  {
    const auto w = this->worldVertex(i);
    for (int k = 0; k < 3; ++k)
      if (w[k] < 0 || w[k] > dims[k])
        throw std::out_of_range("EVM vertex outside the grid");
    at(w[0], w[1], w[2]) ^= 1;
  }
  // One prefix pass per in-plane axis (the normal of a 2D EVM has a single coordinate).
  const int flat = this->Dimension == 2 ? this->Order[0] : -1;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (axis == flat)
      continue;
    std::size_t step[3] = { 0, 0, 0 };
    step[axis] = 1;
    for (std::size_t z = step[2]; z < gz; ++z)
      for (std::size_t y = step[1]; y < gy; ++y)
        for (std::size_t x = step[0]; x < gx; ++x)
          at(x, y, z) ^= at(x - step[0], y - step[1], z - step[2]);
  }
  for (std::int32_t z = 0; z < dims[2]; ++z)
    for (std::int32_t y = 0; y < dims[1]; ++y)
      for (std::int32_t x = 0; x < dims[0]; ++x)
        if (at(x, y, z))
          out.set(x, y, z);
  return out;
}

EVM extractEVM(const BitVolume& voxels, const Execution& exec)
{
  const std::int32_t ny = voxels.size(1), nz = voxels.size(2);
  const std::size_t rowWords = voxels.wordsPerRow();
  if (voxels.size(0) == 0 || ny == 0 || nz == 0)
    return EVM(3, AxisOrder{ 2, 1, 0 }, {});
  // The rows of vertices of plane kz: the XOR of the (up to) four voxel rows around each.
  auto rowsOfPlane = [&](std::int64_t kz, auto&& visit)
  {
    std::vector<Word> parity(rowWords), bits(rowWords + 1);
    for (std::int32_t ky = 0; ky <= ny; ++ky)
    {
      std::fill(parity.begin(), parity.end(), 0);
      bool any = false;
      for (std::int32_t z = static_cast<std::int32_t>(kz) - 1; z <= kz; ++z)
        for (std::int32_t y = ky - 1; y <= ky; ++y)
        {
          if (z < 0 || z >= nz || y < 0 || y >= ny)
            continue;
          const Word* r = voxels.row(y, z);
          for (std::size_t w = 0; w < rowWords; ++w)
            parity[w] ^= r[w];
          any = true;
        }
      if (!any)
        continue;
      rowParityToVertexBits(parity.data(), rowWords, bits.data());
      visit(static_cast<Coord>(kz), ky, bits.data());
    }
  };
  return EVM(3, AxisOrder{ 2, 1, 0 }, collectRowVertices(nz + 1, rowWords + 1, exec, rowsOfPlane));
}

namespace
{

/// The lines of vertices of a 2D pixel set (nz == 1): line ky lies between pixel rows ky - 1
/// and ky, and vertex x of it is extreme where the XOR of those two rows (the parity of the
/// pixels there) changes between pixels x - 1 and x. Computed word by word from the rows
/// themselves, with no buffer per line.
class PlanarLines
{
public:
  explicit PlanarLines(const BitVolume& pixels)
    : Pixels(pixels)
    , Rows(pixels.size(1))
    , RowWords(pixels.wordsPerRow())
    , Zeros(pixels.wordsPerRow(), 0)
  {
  }

  std::size_t lineWords() const { return this->RowWords + 1; }

  /// Calls visit(w, vertexWord) for every word w of line ky (the last one, w == RowWords,
  /// holds the vertex at x = 64 RowWords only).
  template<typename Visit>
  void forEachWord(std::int64_t ky, Visit&& visit) const
  {
    const Word* below = this->rowBelow(ky);
    const Word* above = this->rowAbove(ky);
    Word carry = 0;
    for (std::size_t w = 0; w < this->RowWords; ++w)
    {
      const Word parity = below[w] ^ above[w];
      visit(w, transitions(parity, carry));
      carry = parity >> 63;
    }
    visit(this->RowWords, carry);
  }

  /// The number of vertices of line ky (bits counted as bitCount<Hardware> does). WithCounts:
  /// also adds its pixels above, boundary edges and whether it has vertices to `counts`, and
  /// ORs its vertex words into `columns` (lineWords() words). A word where both rows are all
  /// set or all clear, as are the bits just before it, holds neither a vertex nor an edge: it
  /// is skipped with one test, no bit counts (most words of a fax page, its large black or
  /// white areas).
  template<bool Hardware, bool WithCounts>
  VBR_ALWAYS_INLINE std::size_t countLine(std::int64_t ky,
    PlanarCounts& counts,
    Word* columns) const
  {
    const Word* below = this->rowBelow(ky);
    const Word* above = this->rowAbove(ky);
    std::size_t vertexCount = 0, pixels = 0, edges = 0;
    Word carry = 0, aboveCarry = 0; // the last bits of the word before: parity, above
    for (std::size_t w = 0; w < this->RowWords; ++w)
    {
      const Word a = above[w];
      const Word parity = below[w] ^ a;
      if constexpr (WithCounts)
      {
        const Word uniform = a == 0 ? 0 : ~Word(0);
        if ((parity | carry) == 0 && a == uniform && aboveCarry == (uniform & 1))
        {
          // A skipped word is all set or all clear (uniform, ~0 or 0): 64 pixels or none.
          pixels += uniform & 64;
          continue;
        }
      }
      const Word vertices = transitions(parity, carry);
      vertexCount += bitCount<Hardware>(vertices);
      carry = parity >> 63;
      if constexpr (WithCounts)
      {
        pixels += bitCount<Hardware>(a);
        // Sides along x between the pixel rows (parity), along y between the pixels of the
        // row above the line (its transitions, the row's start included).
        edges += bitCount<Hardware>(parity) + bitCount<Hardware>(transitions(a, aboveCarry));
        columns[w] |= vertices;
        aboveCarry = a >> 63;
      }
    }
    vertexCount += carry;
    if constexpr (WithCounts)
    {
      columns[this->RowWords] |= carry;
      edges += aboveCarry; // the row's end
      counts.pixels += pixels;
      counts.edges += edges;
      counts.planes[1] += vertexCount != 0 ? 1 : 0;
    }
    return vertexCount;
  }

private:
  const Word* rowBelow(std::int64_t ky) const
  {
    return ky > 0 ? this->Pixels.row(static_cast<std::int32_t>(ky - 1), 0) : this->Zeros.data();
  }
  const Word* rowAbove(std::int64_t ky) const
  {
    return ky < this->Rows ? this->Pixels.row(static_cast<std::int32_t>(ky), 0)
                           : this->Zeros.data();
  }

  const BitVolume& Pixels;
  const std::int64_t Rows;
  const std::size_t RowWords;
  const std::vector<Word> Zeros;
};

/// PlanarLines::countLine for the lines [rb, re): their vertices in sizes[r], their counts
/// added to `counts` and `columns` (WithCounts).
template<bool Hardware, bool WithCounts>
VBR_ALWAYS_INLINE void countLinesWith(const PlanarLines& lines,
  std::int64_t rb,
  std::int64_t re,
  std::size_t* sizes,
  PlanarCounts& counts,
  Word* columns)
{
  for (std::int64_t r = rb; r < re; ++r)
    sizes[r] = lines.countLine<Hardware, WithCounts>(r, counts, columns);
}

template<bool WithCounts>
void countLines(const PlanarLines& lines,
  std::int64_t rb,
  std::int64_t re,
  std::size_t* sizes,
  PlanarCounts& counts,
  Word* columns)
{
  countLinesWith<false, WithCounts>(lines, rb, re, sizes, counts, columns);
}

#if VBR_POPCNT_COPY
/// countLines compiled for processors with POPCNT.
template<bool WithCounts>
__attribute__((target("popcnt"))) void countLinesPopCount(const PlanarLines& lines,
  std::int64_t rb,
  std::int64_t re,
  std::size_t* sizes,
  PlanarCounts& counts,
  Word* columns)
{
  countLinesWith<true, WithCounts>(lines, rb, re, sizes, counts, columns);
}
#endif

using LinesCounter =
  void (*)(const PlanarLines&, std::int64_t, std::int64_t, std::size_t*, PlanarCounts&, Word*);

/// countLines, counting bits by the instruction where the processor has it and the build
/// does not assume it.
template<bool WithCounts>
LinesCounter pickCountLines()
{
#if VBR_POPCNT_COPY
  if (hasPopCountInstruction())
    return countLinesPopCount<WithCounts>;
#endif
  return countLines<WithCounts>;
}

} // namespace

EVM extractEVM2D(const BitVolume& pixels,
  const Execution& exec,
  PlanarCounts* counts,
  std::vector<Vertex>* memory)
{
  if (pixels.size(2) != 1)
    throw std::invalid_argument("extractEVM2D needs a single slice (nz == 1)");
  if (counts)
    *counts = PlanarCounts();
  const std::int32_t ny = pixels.size(1);
  if (pixels.size(0) == 0 || ny == 0)
    return EVM(2, AxisOrder{ 2, 1, 0 }, {});
  const PlanarLines lines(pixels);
  const std::size_t words = lines.lineWords();
  const std::int64_t count = static_cast<std::int64_t>(ny) + 1;
  // Counted by blocks of lines, one a thread, each with its own counts and row of columns
  // (merged after the loop), then written by collectVertices.
  const std::int64_t blocks =
    exec.parallelFor ? std::clamp<std::int64_t>(exec.concurrency, 1, count) : 1;
  std::vector<PlanarCounts> blockCounts(static_cast<std::size_t>(blocks));
  std::vector<Word> blockColumns(counts ? static_cast<std::size_t>(blocks) * words : 0, 0);
  const LinesCounter countLinesIn = counts ? pickCountLines<true>() : pickCountLines<false>();
  const auto countRuns = [&](std::size_t* sizes)
  {
    exec.forRange(blocks,
      [&](std::int64_t bb, std::int64_t be)
      {
        for (std::int64_t b = bb; b < be; ++b)
          countLinesIn(lines,
            count * b / blocks,
            count * (b + 1) / blocks,
            sizes,
            blockCounts[b],
            counts ? blockColumns.data() + b * words : nullptr);
      });
  };
  const auto writeLine = [&](std::int64_t r, Vertex* out)
  {
    const Coord y = static_cast<Coord>(r);
    lines.forEachWord(r,
      [&](std::size_t w, Word bits)
      {
        for (; bits != 0; bits &= bits - 1)
          *out++ = { 0, y, static_cast<Coord>(w * 64 + countTrailingZeros(bits)) };
      });
  };
  std::vector<Vertex> vertices = collectVertices(count, exec, countRuns, writeLine, memory);
  if (counts)
  {
    // The columns of vertices: x where any line has one.
    for (std::size_t w = 0; w < words; ++w)
    {
      Word column = 0;
      for (std::int64_t b = 0; b < blocks; ++b)
        column |= blockColumns[b * words + w];
      counts->planes[0] += popCount(column);
    }
    for (const PlanarCounts& c : blockCounts)
    {
      counts->pixels += c.pixels;
      counts->edges += c.edges;
      counts->planes[1] += c.planes[1];
    }
  }
  return EVM(2, AxisOrder{ 2, 1, 0 }, std::move(vertices));
}

std::array<std::size_t, 3> planesPerAxis(const EVM& evm)
{
  std::array<std::size_t, 3> counts{ 0, 0, 0 };
  if (evm.empty())
    return counts;
  // One pass for the bounds of every coordinate and one to mark the values met: the
  // vertices are read twice in all rather than twice per axis.
  const int first = evm.dimension() == 2 ? 1 : 0;
  Vertex lo = evm.vertices()[0], hi = lo;
  for (const Vertex& v : evm.vertices())
    for (int k = first; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  std::array<std::vector<unsigned char>, 3> seen;
  for (int k = first; k < 3; ++k)
    seen[k].assign(static_cast<std::size_t>(hi[k] - lo[k]) + 1, 0);
  for (const Vertex& v : evm.vertices())
    for (int k = first; k < 3; ++k)
      seen[k][static_cast<std::size_t>(v[k] - lo[k])] = 1;
  for (int k = first; k < 3; ++k)
    counts[evm.order()[k]] =
      static_cast<std::size_t>(std::count(seen[k].begin(), seen[k].end(), 1));
  return counts;
}

std::vector<Vertex> project(const Vertex* begin, const Vertex* end, int level)
{
  std::vector<Vertex> out(begin, end);
  for (auto& v : out)
    v[level] = 0;
  return out;
}

} // namespace vbr
