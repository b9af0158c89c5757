// The Compact Union of Disjoint Boxes (CUDB) of an orthogonal pseudo-polyhedron, and its
// connected components (I. Cruz-Matias and D. Ayala, "CUDB: An Improved Decomposition Model
// for Orthogonal Pseudo-Polyhedra").
//
// The Ordered Union of Disjoint Boxes (OUDB) cuts the object at every plane of vertices
// perpendicular to A, then cuts each slice at every line of vertices of its section: boxes
// are split wherever any part of the object has a vertex. The CUDB merges, on the fly,
// consecutive boxes that the OUDB split needlessly: rectangles of consecutive lines with
// the same C interval (2D compaction), then boxes of consecutive slices with the same (B, C)
// rectangle (3D compaction). Each box keeps its contacts with the boxes before and after it
// along A and B, which is all that connected-component labelling needs.
//
// Boxes are in the voxel coordinates (x, y, z) of the EVM they come from, half-open
// [lo, hi); a 2D CUDB (from a 2D EVM) has boxes one voxel thick along the EVM's normal axis.
#ifndef vbr_CUDB_h
#define vbr_CUDB_h

#include "EVM.h"
#include "Execution.h"
#include "Geometry.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vbr
{

/// Two boxes that touch across a plane perpendicular to `axis` (a world axis): `backward`
/// ends where `forward` starts. `face` is set when they share a piece of face of positive
/// area; otherwise they share only an edge or a vertex (a non-manifold contact).
struct BoxContact
{
  std::uint32_t backward = 0;
  std::uint32_t forward = 0;
  std::uint8_t axis = 0;
  bool face = false;
};

/// Which contacts connect: shared faces (4 in 2D, 6 in 3D) or also edges and vertices
/// (8 in 2D, 26 in 3D).
enum class Connectivity
{
  Face,
  Vertex
};

class CUDB
{
public:
  int dimension = 3;
  AxisOrder order{ 2, 1, 0 };
  /// In creation (sweep) order: by the A coordinate where they start, then B, then C.
  std::vector<Box> boxes;
  /// Every pair of boxes that touch, each pair once, as backward/forward neighbours along
  /// the A axis (consecutive slices) or the B axis (consecutive lines within a slice).
  std::vector<BoxContact> contacts;
  /// Number of boxes the OUDB of the same EVM and sorting has.
  std::size_t oudbBoxCount = 0;

  std::int64_t volume() const;

  /// The paper's BackwardNeighbors / ForwardNeighbors arrays of one sense along one axis,
  /// for every box: neighbours of box i are entries [start[i], start[i + 1]) of `boxes`.
  struct NeighbourLists
  {
    std::vector<std::uint32_t> start;
    std::vector<std::uint32_t> boxes;
  };
  /// axisRole 0 = A, 1 = B (in 2D only B: the rectangles' neighbours across lines).
  /// Test oracle only: no filter calls it (labelComponents reads `contacts` directly); the
  /// tests check that the paper's arrays built from the contacts agree in both senses.
  NeighbourLists neighbours(int axisRole, bool forward, Connectivity connectivity) const;
};

/// EVM -> CUDB by the paper's Algorithms 1 and 2: sections of the A-slices by XOR of the
/// planes of vertices, 1D sections of the B-lines by XOR of the lines of vertices, boxes
/// compacted on the fly. Works with any sorting of the EVM. Returns false when aborted.
/// A 3D sweep is cut into `pieces` runs of planes swept concurrently and stitched (0: one
/// per thread of `exec` on large inputs); the result is the same whatever the pieces.
bool buildCUDB(const EVM& evm, const Execution& exec, CUDB& out, int pieces = 0);
CUDB buildCUDB(const EVM& evm);

/// EVM -> OUDB (Cruz-Matias & Ayala, section 2.2): the boxes without compaction, in their order.
/// Test oracle only: the tests check that the CUDB covers the same voxels with fewer boxes
/// and that oudbBoxCount counts these boxes.
std::vector<Box> buildOUDB(const EVM& evm);

/// CUDB -> EVM (Cruz-Matias & Ayala, section 3.3): the XOR of the boxes' corners (the boxes are
/// disjoint), in the CUDB's order. Test oracle only: the round trip EVM -> CUDB -> EVM.
EVM toEVM(const CUDB& cudb);

/// Connected components of the boxes by the paper's Algorithms 3 to 5: every contact of the
/// connectivity is an equivalence between its two boxes (each box its own provisional label,
/// a class represented by its first box in creation order, which is the smallest label the
/// paper's pass would give it), and a final pass numbers the classes 1..count in order of
/// first appearance along the boxes.
struct Components
{
  std::vector<std::uint32_t> boxLabel; ///< 1..count per box
  std::uint32_t count = 0;
};
Components labelComponents(const CUDB& cudb, Connectivity connectivity);

/// EVM -> CUDB and the components of its boxes in one sweep, for callers that need the boxes
/// and their labels but not the contacts: each contact of `connectivity` is an equivalence as
/// soon as the sweep finds it, so no contact list is written and read back. `out` has the
/// boxes (in the same order) and box counts of buildCUDB, and no contacts; `components` is
/// labelComponents(buildCUDB(evm), connectivity). Returns false when aborted.
bool buildCUDBComponents(const EVM& evm,
  Connectivity connectivity,
  const Execution& exec,
  CUDB& out,
  Components& components,
  int pieces = 0);

/// The runs of set pixels of the rows of a one-slice pixel set, as its 2D sweep met them: the
/// box of every run, row after row and along each row, and where each row's runs begin (the
/// sweep knows it; counting them again from the bits would read the whole image once more).
struct PixelRuns
{
  std::vector<std::uint32_t> boxes;
  /// The runs of row y are boxes[rowStarts[y]] to boxes[rowStarts[y + 1] - 1].
  std::vector<std::size_t> rowStarts;

  bool empty() const { return this->boxes.empty(); }
  void clear()
  {
    this->boxes.clear();
    this->rowStarts.clear();
  }
};

/// A one-slice pixel set (nz = 1) -> its 2D CUDB in the sorting `order`, ZYX {2, 1, 0} (lines
/// along y, rows along x) or ZXY {2, 0, 1} (lines along x, read from a transposed copy of the
/// bits), and the components of its boxes, in one pass over the pixel rows without building
/// the EVM: each row's runs of set pixels are read from its bits, a run equal to a run of the
/// row before continues that run's rectangle (the 2D compaction) and any other starts a box,
/// united at once with the runs of the row before that it meets. Same boxes (in the same
/// order), oudbBoxCount and components as buildCUDBComponents(extractEVM2D(pixels) sorted as
/// `order`, ...); `vertices` (if given) receives the number of vertices that EVM would have.
/// `runs` (if given) receives the runs of set pixels of the rows the sweep reads (the image's
/// rows in ZYX, its columns in ZXY), as paintPixelRuns reads them. Polls `exec` every 2048 words of
/// pixels or so (a few dozen rows of a wide image); returns false when aborted, with `out` empty.
/// The vectors of `out`, `components` and `runs` keep their memory (their values are replaced),
/// and the union-find is built in `memory` when given (left there, its values unspecified): a
/// caller labelling one image after another hands the same vectors back rather than having
/// new blocks faulted in and zeroed by the kernel (a maze's boxes, labels, runs and union-find
/// are 190 MB).
bool buildCUDBComponents2D(const BitVolume& pixels,
  const AxisOrder& order,
  Connectivity connectivity,
  const Execution& exec,
  CUDB& out,
  Components& components,
  std::size_t* vertices = nullptr,
  PixelRuns* runs = nullptr,
  std::vector<std::uint32_t>* memory = nullptr);
/// The same in the ZYX sorting, never aborted; returns the number of vertices of the EVM.
std::size_t buildCUDBComponents2D(const BitVolume& pixels,
  Connectivity connectivity,
  CUDB& out,
  Components& components);

/// The components of a one-slice pixel set labelled on the runs of its rows, without its boxes:
/// buildCUDBComponents2D in the ZYX sorting for callers that paint the labels and measure the
/// regions from the runs (a 2D image without the boxes output), which saves writing a box per
/// rectangle (a maze has 4.9 million). The union-find is over the CUDB's boxes all the same,
/// that is over the runs with each chain of equal runs in consecutive rows taken as one (the
/// 2D compaction: a maze's 9.2 million runs are 4.9 million such chains).
struct PixelRunComponents
{
  /// The box (chain of equal runs) of every run, numbered as the sweep starts them: in scan
  /// order of their first runs, the CUDB's box numbers. A run begins its box when its number
  /// is the next one not met yet.
  PixelRuns runs;
  Components components;        ///< labelComponents' boxLabel and count
  std::size_t oudbBoxCount = 0; ///< as CUDB::oudbBoxCount
  std::size_t extremeVertices = 0;

  std::size_t boxCount() const { return this->components.boxLabel.size(); }
};

/// Fills `out` as buildCUDBComponents2D(pixels, ZYX, connectivity, exec, cudb, components,
/// &vertices, &runs, memory) would (the same components, box numbers, counts and runs), without
/// the boxes, keeping the memory of `out`'s vectors as it does. Returns false when aborted.
bool labelPixelRuns(const BitVolume& pixels,
  Connectivity connectivity,
  const Execution& exec,
  PixelRunComponents& out,
  std::vector<std::uint32_t>* memory = nullptr);

/// The number of runs of set pixels of all rows of a one-slice pixel set (a popcount pass).
std::size_t countPixelRuns(const BitVolume& pixels);

/// The ends of the runs of set pixels of row y of a one-slice pixel set, x0 and x1 of each run
/// in turn, written from `out` on (room for pixels.wordsPerRow() * 64 + 2 values); returns the
/// end of what was written.
Coord* pixelRowRunEnds(const BitVolume& pixels, std::int32_t y, Coord* out);

/// Writes value[b] into every voxel of box b (boxes with value 0 are skipped) of `labels`, a
/// grid of `dims` voxels stored x fastest. Box coordinates are shifted by `offset` and then
/// permuted: coordinate k of a box is along axis axes[k] of the grid. Voxels outside the
/// boxes are left as they are. Parallel over slices along z (rows for a single slice). Every
/// 4096 boxes each worker asks whether to stop; false when stopped (the labels then partly
/// written).
bool paintBoxes(const std::vector<Box>& boxes,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 3>& offset,
  const std::array<int, 3>& axes,
  const std::array<Coord, 3>& dims,
  std::int32_t* labels,
  const Execution& exec = Execution());

/// Paints a one-slice pixel set into `labels`, which must hold 0 on the pixels' rectangle:
/// value[runs.boxes[i]] on the pixels of run i (the runs of buildCUDBComponents2D in ZYX).
/// Pixel (x, y) is labels[(y + offset[1]) * rowStep + x + offset[0]]; nothing outside the
/// rectangle is written. The labels of paintBoxes of the sweep's boxes into a zeroed grid, in
/// one pass along the rows: a run of up to 8 pixels is written by stores of a fixed width (8
/// values, then 8 zeros from its end over the gap they covered; the next run is written after),
/// a longer one exactly (runs of a few pixels, as a maze has, mispredicted every loop exit of
/// the boxes' painting). Parallel over rows, in up to 16 steps of at least 2^14 words of pixels
/// (a few ms of a maze), between which it reports its progress and asks whether to stop.
/// Returns false when aborted, the rows of the steps done painted. Throws
/// std::invalid_argument when `runs` is not one box per run: before anything is written when
/// the counts disagree, at the row whose runs are not its own otherwise.
bool paintPixelRuns(const BitVolume& pixels,
  const PixelRuns& runs,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 2>& offset,
  std::int64_t rowStep,
  std::int32_t* labels,
  const Execution& exec = Execution());

/// paintPixelRuns into a whole image of any content, `rows` rows of `width` pixels (row r at
/// labels + r * width), pixel (x, y) of `pixels` at row y + offset[1], column x + offset[0]:
/// every pixel of the image is written, a run's value or 0, so the image need not be zeroed
/// first (memory an earlier update used, not pages the kernel zeroes and faults in). Each row
/// is zeroed and its runs painted while it is in the cache: the image is written once. Steps
/// over the image's rows (sized by the image's width), progress, stop and checks as
/// paintPixelRuns; throws std::invalid_argument also when the pixels do not fit in the image.
bool paintPixelRunsOverwriting(const BitVolume& pixels,
  const PixelRuns& runs,
  const std::vector<std::int32_t>& value,
  const std::array<Coord, 2>& offset,
  std::int64_t width,
  std::int64_t rows,
  std::int32_t* labels,
  const Execution& exec = Execution());

} // namespace vbr

#endif
