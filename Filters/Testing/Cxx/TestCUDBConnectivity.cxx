// vtkCUDBConnectivity on random and degenerate images against a flood fill written here:
// identical labels (in sweep or size order), region sizes, the region table, the boxes of
// port 1 (disjoint, covering, carrying the region of their voxels), region filters and
// seeds, for point and cell scalars, several scalar types, extents not at 0, anisotropic
// spacing, 2D images in the three planes, all sortings and both connectivities, and the
// inputs with the most regions and boxes per voxel (checkerboard, noise).
#include "vtkCUDBConnectivity.h"

#include "Core/Sanitizers.h"
#include "TestImages.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using vbrtest::AbortAtProgress;
using vbrtest::Int3;
using vbrtest::Layout;
using vbrtest::makeImage;
using vbrtest::randomVolume;
using vbrtest::Volume;

/// Which voxels are selected and which may be connected.
struct Rule
{
  int mode = vtkCUDBConnectivity::POSITIVE;
  double lower = 1, upper = 1e300;
  bool selected(int v) const
  {
    return mode == vtkCUDBConnectivity::RANGE ? v >= lower && v <= upper : v > 0;
  }
  bool joins(int a, int b) const { return mode != vtkCUDBConnectivity::LABELS || a == b; }
};

/// Flood fill: components numbered by (label in Labels mode, first voxel in x-fastest scan
/// order), which is the filter's sweep order for the ZYX sorting.
std::vector<int> floodFill(const Volume& v, const Rule& rule, bool vertex, int& count)
{
  const std::size_t n = v.values.size();
  std::vector<int> label(n, 0);
  std::vector<std::pair<int, std::size_t>> firsts; // (value, first voxel) per component
  std::vector<Int3> stack;
  auto index = [&v](int x, int y, int z)
  { return (std::size_t(z) * v.dims[1] + y) * v.dims[0] + x; };
  int provisional = 0;
  for (int z = 0; z < v.dims[2]; ++z)
    for (int y = 0; y < v.dims[1]; ++y)
      for (int x = 0; x < v.dims[0]; ++x)
      {
        const int value = v.at(x, y, z);
        if (!rule.selected(value) || label[index(x, y, z)])
          continue;
        label[index(x, y, z)] = ++provisional;
        firsts.push_back({ value, index(x, y, z) });
        stack.push_back({ x, y, z });
        while (!stack.empty())
        {
          const Int3 p = stack.back();
          stack.pop_back();
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx)
              {
                const int steps = std::abs(dx) + std::abs(dy) + std::abs(dz);
                if (steps == 0 || (!vertex && steps > 1))
                  continue;
                const int qx = p[0] + dx, qy = p[1] + dy, qz = p[2] + dz;
                if (qx < 0 || qy < 0 || qz < 0 || qx >= v.dims[0] || qy >= v.dims[1] ||
                  qz >= v.dims[2])
                  continue;
                const int q = v.at(qx, qy, qz);
                if (rule.selected(q) && rule.joins(value, q) && !label[index(qx, qy, qz)])
                {
                  label[index(qx, qy, qz)] = provisional;
                  stack.push_back({ qx, qy, qz });
                }
              }
        }
      }
  // Sweep order: by label (Labels mode only), then first voxel.
  std::vector<int> order(firsts.size());
  std::iota(order.begin(), order.end(), 0);
  if (rule.mode == vtkCUDBConnectivity::LABELS)
    std::stable_sort(
      order.begin(), order.end(), [&](int a, int b) { return firsts[a].first < firsts[b].first; });
  std::vector<int> renumber(firsts.size() + 1, 0);
  for (std::size_t k = 0; k < order.size(); ++k)
    renumber[order[k] + 1] = static_cast<int>(k + 1);
  for (int& l : label)
    l = renumber[l];
  count = static_cast<int>(firsts.size());
  return label;
}

std::vector<long long> sizesOf(const std::vector<int>& labels, int count)
{
  std::vector<long long> sizes(count + 1, 0);
  for (int l : labels)
    if (l > 0 && l <= count)
      ++sizes[l];
  return sizes;
}

/// Renumbers sweep-ordered labels by size, largest first, ties in sweep order; regions
/// failing `keep` become 0.
template<typename Keep>
std::vector<int> sizeRanked(const std::vector<int>& labels, int count, Keep keep, int largest = 0)
{
  const std::vector<long long> sizes = sizesOf(labels, count);
  std::vector<int> kept;
  for (int r = 1; r <= count; ++r)
    if (keep(r, sizes[r]))
      kept.push_back(r);
  std::stable_sort(kept.begin(), kept.end(), [&](int a, int b) { return sizes[a] > sizes[b]; });
  if (largest > 0 && static_cast<int>(kept.size()) > largest)
    kept.resize(largest);
  std::vector<int> renumber(count + 1, 0);
  for (std::size_t k = 0; k < kept.size(); ++k)
    renumber[kept[k]] = static_cast<int>(k + 1);
  std::vector<int> out(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i)
    out[i] = renumber[labels[i]];
  return out;
}

std::vector<int> regionIds(vtkCUDBConnectivity* f, const Layout& l)
{
  vtkImageData* out = f->GetOutput();
  vtkDataArray* a = l.cellData ? out->GetCellData()->GetArray("RegionId")
                               : out->GetPointData()->GetArray("RegionId");
  std::vector<int> ids;
  if (!a)
    return ids;
  ids.resize(static_cast<std::size_t>(a->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    ids[i] = static_cast<int>(a->GetTuple1(i));
  return ids;
}

vtkIdType fieldValue(vtkDataObject* out, const char* name)
{
  vtkDataArray* a = out->GetFieldData()->GetArray(name);
  return a ? static_cast<vtkIdType>(a->GetTuple1(0)) : -1;
}

/// Same partition up to a renumbering, and 0 at the same voxels.
bool samePartition(const std::vector<int>& a, const std::vector<int>& b)
{
  if (a.size() != b.size())
    return false;
  std::map<int, int> ab, ba;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    if ((a[i] == 0) != (b[i] == 0))
      return false;
    if (a[i] == 0)
      continue;
    if (ab.emplace(a[i], b[i]).first->second != b[i] ||
      ba.emplace(b[i], a[i]).first->second != a[i])
      return false;
  }
  return true;
}

/// Voxel index range [lo, hi) of a box cell, from its world bounds.
void boxIndexRange(vtkUnstructuredGrid* boxes, vtkIdType cell, const Layout& l, Int3& lo, Int3& hi)
{
  double b[6];
  boxes->GetCellBounds(cell, b);
  for (int d = 0; d < 3; ++d)
  {
    // Voxel i of point data spans vertex coordinates [i - 0.5, i + 0.5] around its point.
    const double shift = l.cellData ? 0.0 : 0.5;
    lo[d] = static_cast<int>(std::lround((b[2 * d] - l.origin[d]) / l.spacing[d] + shift)) -
      l.extentMin[d];
    hi[d] = static_cast<int>(std::lround((b[2 * d + 1] - l.origin[d]) / l.spacing[d] + shift)) -
      l.extentMin[d];
  }
}

/// Port 2 against the labels of port 0 (and NumberOfBoxes against `boxesOfRegion`, the boxes
/// of each region on port 1, when given).
void checkTable(vtkCUDBConnectivity* f,
  const Volume& v,
  const Layout& l,
  const std::vector<int>& ids,
  const std::string& what,
  const std::vector<long long>* boxesOfRegion = nullptr);

/// Port 1 (when GenerateBoxes is on; else it must be empty) and port 2 against the labels of
/// port 0.
void checkBoxesAndTable(vtkCUDBConnectivity* f,
  const Volume& v,
  const Layout& l,
  const std::vector<int>& ids,
  const std::string& what,
  bool planar)
{
  vtkUnstructuredGrid* boxes = f->GetBoxesOutput();
  if (!f->GetGenerateBoxes())
  {
    CHECK(boxes->GetNumberOfCells() == 0, what << ": no boxes without the boxes output");
    checkTable(f, v, l, ids, what);
    return;
  }
  vtkDataArray* boxRegion = boxes->GetCellData()->GetArray("RegionId");
  CHECK(boxRegion && boxes->GetCellData()->GetArray("BoxId"), what << ": box arrays");
  if (!boxRegion)
    return;
  // Each box has its own corners: cell c is points 8c..8c+7 (4c..4c+3 in 2D), in 32-bit ids.
  CHECK(!boxes->GetCells()->IsStorage64Bit(), what << ": 32-bit cell storage");
  const vtkIdType corners = planar ? 4 : 8;
  bool ownCorners = boxes->GetNumberOfPoints() == corners * boxes->GetNumberOfCells();
  vtkNew<vtkIdList> cellPoints;
  for (vtkIdType c = 0; ownCorners && c < boxes->GetNumberOfCells(); ++c)
  {
    boxes->GetCellPoints(c, cellPoints);
    ownCorners = cellPoints->GetNumberOfIds() == corners;
    for (vtkIdType k = 0; ownCorners && k < corners; ++k)
      ownCorners = cellPoints->GetId(k) == corners * c + k;
  }
  CHECK(ownCorners, what << ": every box has its own corner points, in order");
  std::vector<int> covered(ids.size(), 0);
  std::vector<long long> boxesOfRegion;
  long long selected = 0;
  for (int id : ids)
    selected += id != 0;
  bool consistent = true;
  for (vtkIdType c = 0; c < boxes->GetNumberOfCells(); ++c)
  {
    CHECK(boxes->GetCellType(c) == (planar ? VTK_PIXEL : VTK_VOXEL), what << ": cell type");
    Int3 lo, hi;
    boxIndexRange(boxes, c, l, lo, hi);
    if (planar) // the flat axis has no thickness in the output
      for (int d = 0; d < 3; ++d)
        if (v.dims[d] == 1)
        {
          lo[d] = 0;
          hi[d] = 1;
        }
    const int region = static_cast<int>(boxRegion->GetTuple1(c));
    if (region >= 0)
    {
      boxesOfRegion.resize(std::max<std::size_t>(boxesOfRegion.size(), region + 1), 0);
      ++boxesOfRegion[region];
    }
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int x = lo[0]; x < hi[0]; ++x)
        {
          if (x < 0 || y < 0 || z < 0 || x >= v.dims[0] || y >= v.dims[1] || z >= v.dims[2])
          {
            consistent = false;
            continue;
          }
          const std::size_t i = (std::size_t(z) * v.dims[1] + y) * v.dims[0] + x;
          consistent = consistent && ids[i] == region && covered[i] == 0;
          covered[i] = 1;
        }
  }
  long long coveredCount = 0;
  for (int c : covered)
    coveredCount += c;
  CHECK(consistent && coveredCount == selected,
    what << ": boxes are disjoint, carry their voxels' region and cover the " << selected
         << " labelled voxels (" << coveredCount << ")");
  checkTable(f, v, l, ids, what, &boxesOfRegion);
}

/// Calls f(id, p) for every voxel p = {x, y, z} of a grid of `dims` whose RegionId (ids, x
/// fastest) is not 0.
template<typename Dims, typename F>
void forEachLabelledVoxel(const Dims& dims, const std::vector<int>& ids, F&& f)
{
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
      {
        const int id = ids[(std::size_t(z) * dims[1] + y) * dims[0] + x];
        const int p[3] = { x, y, z };
        if (id != 0)
          f(id, p);
      }
}

/// World bounds (XMin, XMax, ...) and measure of one voxel (its volume, or its area for a 2D
/// image) of an image along the axes of the layout, from its origin and spacing: point voxels
/// span half a spacing either side of their point, cell voxels their cell; the flat axis of a
/// 2D image (one voxel along exactly that axis) has no thickness, its plane the first layer of
/// points.
struct ExpectedGeometry
{
  int flatAxis = -1;

  explicit ExpectedGeometry(const Volume& v)
  {
    if ((v.dims[0] == 1) + (v.dims[1] == 1) + (v.dims[2] == 1) == 1)
      flatAxis = v.dims[0] == 1 ? 0 : (v.dims[1] == 1 ? 1 : 2);
  }

  /// Bounds along axis d of the voxels of absolute indices [first, last].
  std::array<double, 2> world(const Layout& l, int d, int first, int last) const
  {
    if (d == this->flatAxis)
    {
      const double plane = l.origin[d] + l.extentMin[d] * l.spacing[d];
      return { plane, plane };
    }
    const double shift = l.cellData ? 0.0 : -0.5;
    const double a = l.origin[d] + (first + shift) * l.spacing[d];
    const double b = l.origin[d] + (last + 1 + shift) * l.spacing[d];
    return { std::min(a, b), std::max(a, b) };
  }

  double measure(const Layout& l) const
  {
    double m = 1;
    for (int d = 0; d < 3; ++d)
      if (d != this->flatAxis)
        m *= std::abs(l.spacing[d]);
    return m;
  }
};

bool near(double value, double expected)
{
  return std::abs(value - expected) <= 1e-9 * (1 + std::abs(expected));
}

void checkTable(vtkCUDBConnectivity* f,
  const Volume& v,
  const Layout& l,
  const std::vector<int>& ids,
  const std::string& what,
  const std::vector<long long>* boxesOfRegion)
{
  vtkTable* table = f->GetRegionsOutput();
  int count = 0;
  for (int id : ids)
    count = std::max(count, id);
  CHECK(table->GetNumberOfRows() == count, what << ": one table row per region");
  const std::vector<long long> sizes = sizesOf(ids, count);
  vtkDataArray* voxels = vtkDataArray::SafeDownCast(table->GetColumnByName("VoxelCount"));
  vtkDataArray* centroid = vtkDataArray::SafeDownCast(table->GetColumnByName("Centroid"));
  const char* const boundNames[6] = { "IMin", "IMax", "JMin", "JMax", "KMin", "KMax" };
  vtkDataArray* volume = vtkDataArray::SafeDownCast(table->GetColumnByName("Volume"));
  vtkDataArray* boxes = vtkDataArray::SafeDownCast(table->GetColumnByName("NumberOfBoxes"));
  const char* const worldNames[6] = { "XMin", "XMax", "YMin", "YMax", "ZMin", "ZMax" };
  vtkDataArray* indexBounds[6];
  vtkDataArray* worldBounds[6];
  bool haveBounds = true;
  for (int k = 0; k < 6; ++k)
  {
    indexBounds[k] = vtkDataArray::SafeDownCast(table->GetColumnByName(boundNames[k]));
    worldBounds[k] = vtkDataArray::SafeDownCast(table->GetColumnByName(worldNames[k]));
    haveBounds = haveBounds && indexBounds[k] && indexBounds[k]->GetNumberOfComponents() == 1 &&
      worldBounds[k] && worldBounds[k]->GetNumberOfComponents() == 1;
  }
  if (!voxels || !centroid || !volume || !boxes || !haveBounds || table->GetNumberOfRows() != count)
  {
    CHECK(false, what << ": table columns");
    return;
  }
  // Brute-force centroid and index bounds per region (voxel centres in world coordinates).
  std::vector<std::array<double, 3>> sum(count + 1, { 0, 0, 0 });
  std::vector<std::array<int, 6>> bounds(
    count + 1, { 1 << 30, -(1 << 30), 1 << 30, -(1 << 30), 1 << 30, -(1 << 30) });
  forEachLabelledVoxel(v.dims,
    ids,
    [&](int id, const int p[3])
    {
      for (int d = 0; d < 3; ++d)
      {
        const double index = l.extentMin[d] + p[d] + (l.cellData && v.dims[d] > 1 ? 0.5 : 0.0);
        sum[id][d] += l.origin[d] + index * l.spacing[d];
        bounds[id][2 * d] = std::min(bounds[id][2 * d], l.extentMin[d] + p[d]);
        bounds[id][2 * d + 1] = std::max(bounds[id][2 * d + 1], l.extentMin[d] + p[d]);
      }
    });
  const ExpectedGeometry geometry(v);
  const double voxelMeasure = geometry.measure(l);
  for (int r = 0; r < count; ++r)
  {
    const int id = r + 1;
    CHECK(static_cast<long long>(voxels->GetTuple1(r)) == sizes[id],
      what << ": VoxelCount of region " << id);
    CHECK(near(volume->GetTuple1(r), static_cast<double>(sizes[id]) * voxelMeasure),
      what << ": Volume of region " << id << " is " << volume->GetTuple1(r) << ", expected "
           << static_cast<double>(sizes[id]) * voxelMeasure);
    if (boxesOfRegion)
    {
      const long long expected =
        id < static_cast<int>(boxesOfRegion->size()) ? (*boxesOfRegion)[id] : 0;
      CHECK(static_cast<long long>(boxes->GetTuple1(r)) == expected,
        what << ": NumberOfBoxes of region " << id << " is " << boxes->GetTuple1(r)
             << ", port 1 has " << expected);
    }
    for (int d = 0; d < 3; ++d)
    {
      const double expected = sum[id][d] / static_cast<double>(sizes[id]);
      // 2D cell data: the plane of the pixels is the single layer of points.
      CHECK(std::abs(centroid->GetComponent(r, d) - expected) < 1e-9 * (1 + std::abs(expected)),
        what << ": centroid of region " << id << " axis " << d << " is "
             << centroid->GetComponent(r, d) << ", expected " << expected);
      CHECK(indexBounds[2 * d]->GetTuple1(r) == bounds[id][2 * d] &&
          indexBounds[2 * d + 1]->GetTuple1(r) == bounds[id][2 * d + 1],
        what << ": index bounds of region " << id);
      const std::array<double, 2> world =
        geometry.world(l, d, bounds[id][2 * d], bounds[id][2 * d + 1]);
      CHECK(near(worldBounds[2 * d]->GetTuple1(r), world[0]) &&
          near(worldBounds[2 * d + 1]->GetTuple1(r), world[1]),
        what << ": world bounds of region " << id << " axis " << d << " are ["
             << worldBounds[2 * d]->GetTuple1(r) << ", " << worldBounds[2 * d + 1]->GetTuple1(r)
             << "], expected [" << world[0] << ", " << world[1] << "]");
    }
  }
}

/// One run of the filter on a volume, checked against the flood fill. Returns whether the
/// filter kept its regions in the 32-byte records of 2D images.
bool checkRun(const Volume& v,
  const Layout& l,
  const Rule& rule,
  bool vertex,
  int sorting,
  int ordering,
  const std::string& what,
  bool detailed,
  bool runLabelling = true,
  bool generateBoxes = true)
{
  vtkNew<vtkCUDBConnectivity> f;
  f->SetRunLabelling(runLabelling);
  f->SetGenerateBoxes(generateBoxes);
  if (!generateBoxes)
    f->SetMinimumPixelRuns(0); // a 2D image: the runs of its pixel rows, however few
  f->SetInputData(makeImage(v, l));
  f->SetSelectionMode(rule.mode);
  f->SetLowerThreshold(rule.lower);
  f->SetUpperThreshold(rule.upper);
  f->SetConnectivity(vertex ? vtkCUDBConnectivity::VERTEX : vtkCUDBConnectivity::FACE);
  f->SetSortingOrder(sorting);
  f->SetRegionOrdering(ordering);
  f->Update();
  int count = 0;
  const std::vector<int> sweep = floodFill(v, rule, vertex, count);
  const std::vector<int> got = regionIds(f, l);
  const std::string label = what + (vertex ? " vertex " : " face ") + f->GetSortingOrderAsString() +
    " " + f->GetRegionOrderingAsString();
  CHECK(fieldValue(f->GetOutput(), "NumberOfRegions") == count,
    label << ": " << fieldValue(f->GetOutput(), "NumberOfRegions") << " regions, expected "
          << count);
  const bool exactOrder = sorting == vtkCUDBConnectivity::ZYX;
  if (ordering == vtkCUDBConnectivity::SWEEP_ORDER)
  {
    CHECK(exactOrder ? got == sweep : samePartition(got, sweep), label << ": labels differ");
  }
  else
  {
    const std::vector<int> ranked = sizeRanked(sweep, count, [](int, long long) { return true; });
    CHECK(exactOrder ? got == ranked : samePartition(got, ranked), label << ": labels differ");
    const std::vector<long long> sizes = sizesOf(got, count);
    CHECK(std::is_sorted(sizes.begin() + 1, sizes.end(), std::greater<long long>()),
      label << ": regions are numbered largest first");
  }
  if (detailed)
  {
    const bool planar = (v.dims[0] == 1) + (v.dims[1] == 1) + (v.dims[2] == 1) == 1;
    checkBoxesAndTable(f, v, l, got, label, planar);
  }
  return f->GetUsedPlanarRecords();
}

void checkRandomVolumes()
{
  struct Case
  {
    Int3 dims;
    double density;
    int labels;
  };
  const Case cases[] = { { { 1, 1, 1 }, 1.0, 1 },
    { { 5, 4, 3 }, 0.5, 1 },
    { { 12, 10, 8 }, 0.3, 1 },
    { { 12, 10, 8 }, 0.6, 3 },
    { { 20, 17, 13 }, 0.45, 1 },
    { { 20, 17, 13 }, 0.8, 4 },
    { { 33, 31, 29 }, 0.25, 1 },
    { { 33, 31, 29 }, 0.55, 2 },
    { { 9, 40, 3 }, 0.7, 1 } };
  const int types[] = {
    VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_FLOAT, VTK_INT, VTK_DOUBLE, VTK_UNSIGNED_SHORT
  };
  unsigned seed = 1;
  int c = 0;
  for (const Case& k : cases)
  {
    const Volume v = randomVolume(k.dims, k.density, k.labels, seed++);
    Layout l;
    l.cellData = c % 2 == 1;
    l.scalarType = types[c % 6];
    l.extentMin = { c - 3, 2 * c, -c };
    l.origin = { 0.5 * c, -1.0, 2.0 };
    l.spacing = { 1.0, 0.5 + 0.25 * c, 2.0 };
    ++c;
    std::ostringstream what;
    what << k.dims[0] << "x" << k.dims[1] << "x" << k.dims[2] << " density " << k.density
         << (l.cellData ? " cells" : " points");
    std::vector<Rule> rules(1);
    if (k.labels > 1)
    {
      rules.push_back(Rule{ vtkCUDBConnectivity::LABELS });
      rules.push_back(Rule{ vtkCUDBConnectivity::RANGE, 2, 3 });
    }
    for (const Rule& rule : rules)
      for (bool vertex : { false, true })
        for (int sorting = vtkCUDBConnectivity::XYZ; sorting <= vtkCUDBConnectivity::AUTO;
             ++sorting)
          for (int ordering : { vtkCUDBConnectivity::SIZE_RANK, vtkCUDBConnectivity::SWEEP_ORDER })
            checkRun(v,
              l,
              rule,
              vertex,
              sorting,
              ordering,
              what.str() + " mode " + std::to_string(rule.mode),
              ordering == vtkCUDBConnectivity::SIZE_RANK);
    // ZYX takes the runs of the voxel rows: once more through the sweep, which it replaces
    for (const Rule& rule : rules)
      for (bool vertex : { false, true })
        checkRun(v,
          l,
          rule,
          vertex,
          vtkCUDBConnectivity::ZYX,
          vtkCUDBConnectivity::SIZE_RANK,
          what.str() + " mode " + std::to_string(rule.mode) + " (sweep)",
          true,
          false);
  }
  // Two larger ones, fewer combinations.
  for (double density : { 0.3, 0.6 })
  {
    const Volume v = randomVolume({ 64, 64, 64 }, density, 1, seed++);
    for (bool vertex : { false, true })
      checkRun(v,
        Layout(),
        Rule(),
        vertex,
        vtkCUDBConnectivity::ZYX,
        vtkCUDBConnectivity::SWEEP_ORDER,
        "64^3",
        true);
  }
}

/// The inputs with the most regions and boxes per voxel: a 3D checkerboard (a region per
/// selected voxel with face connectivity, one region with vertex connectivity) and 50 % noise,
/// whose region tables are gathered from the most boxes; a region size filter and the largest
/// regions leave rows out of the table.
void checkHostileVolumes()
{
  Volume board;
  board.dims = { 13, 10, 9 };
  board.values.resize(13 * 10 * 9);
  for (int z = 0; z < 9; ++z)
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 13; ++x)
        board.values[(std::size_t(z) * 10 + y) * 13 + x] = (x + y + z) % 2;
  const Volume noise = randomVolume({ 24, 21, 19 }, 0.5, 1, 77);
  Layout l;
  l.extentMin = { -2, 3, 1 };
  l.spacing = { 0.5, 1.0, 2.0 };
  for (const Volume* v : std::initializer_list<const Volume*>{ &board, &noise })
    for (bool vertex : { false, true })
      for (int ordering : { vtkCUDBConnectivity::SIZE_RANK, vtkCUDBConnectivity::SWEEP_ORDER })
        checkRun(*v,
          l,
          Rule(),
          vertex,
          vtkCUDBConnectivity::ZYX,
          ordering,
          v == &board ? "checkerboard" : "noise",
          true);
  int count = 0;
  const std::vector<int> sweep = floodFill(noise, Rule(), false, count);
  vtkNew<vtkCUDBConnectivity> f;
  f->SetInputData(makeImage(noise, l));
  f->SetMinimumRegionSize(3);
  f->SetLargestRegions(5);
  f->SetSortingOrder(vtkCUDBConnectivity::ZYX);
  f->Update();
  const std::vector<int> ranked = sizeRanked(
    sweep, count, [](int, long long size) { return size >= 3; }, 5);
  const std::vector<int> got = regionIds(f, l);
  CHECK(got == ranked, "noise, 5 largest regions of 3 voxels or more: labels differ");
  checkBoxesAndTable(f, noise, l, got, "noise, 5 largest regions", false);
}

/// The size ranking's three ways, each against the stable sort of the brute force: regions
/// already largest first (the checkerboard above: none), sizes small beside their count (the
/// noise above: a counting sort), and one region far larger than the others are many (here: a
/// slab of 81,920 voxels before sparse noise, whose small regions tie often: a radix sort).
void checkSizeRankingOfALargeRegion()
{
  Volume slab = randomVolume({ 64, 64, 40 }, 0.25, 1, 79);
  for (std::size_t i = 0; i < std::size_t(64) * 64 * 22; ++i)
    slab.values[i] = i < std::size_t(64) * 64 * 20 ? 1 : 0; // the slab, then two empty planes
  for (bool vertex : { false, true })
    for (bool boxes : { false, true })
      checkRun(slab,
        Layout(),
        Rule(),
        vertex,
        vtkCUDBConnectivity::ZYX,
        vtkCUDBConnectivity::SIZE_RANK,
        "slab and sparse noise",
        true,
        true,
        boxes);
}

/// Outputs large enough (8 MiB or more) to be written into memory the filter does not clear:
/// the 64^3 checkerboard's 131,072 one-voxel regions (face connectivity) with their boxes and
/// table, every value checked (a debug build fills such memory with ones first).
void checkLargeOutputs()
{
  Volume board = randomVolume({ 64, 64, 64 }, 0.5, 1, 7);
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        board.values[(std::size_t(z) * 64 + y) * 64 + x] = (x + y + z) % 2;
  for (int ordering : { vtkCUDBConnectivity::SWEEP_ORDER, vtkCUDBConnectivity::SIZE_RANK })
    checkRun(board,
      Layout(),
      Rule(),
      false,
      vtkCUDBConnectivity::ZYX,
      ordering,
      "checkerboard 64^3",
      true);
}

void checkTwoDimensional()
{
  const Int3 shapes[] = { { 40, 30, 1 }, { 25, 1, 35 }, { 1, 33, 27 } };
  unsigned seed = 50;
  for (const Int3& dims : shapes)
    for (bool cells : { false, true })
    {
      const Volume v = randomVolume(dims, 0.55, 1, seed++);
      Layout l;
      l.cellData = cells;
      l.extentMin = { 2, -3, 4 };
      l.spacing = { 0.5, 2.0, 1.5 };
      l.origin = { 1, 2, 3 };
      for (bool vertex : { false, true })
        for (int sorting :
          { vtkCUDBConnectivity::ZYX, vtkCUDBConnectivity::XYZ, vtkCUDBConnectivity::AUTO })
          checkRun(v,
            l,
            Rule(),
            vertex,
            sorting,
            vtkCUDBConnectivity::SIZE_RANK,
            "2D " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
              std::to_string(dims[2]) + (cells ? " cells" : " points"),
            true);
    }
}

/// 2D images at the sides where the regions' compact records end (32,767 pixels: bounds of
/// 16 bits, signed) and past them (the 64-byte records), along the image's rows and
/// columns, from the boxes and from the pixel runs, numbered by size (a counting sort of every
/// region) and in sweep order, both connectivities, against the flood fill: labels, and every
/// table column; the compact records used exactly within the limit. Then the records
/// themselves: random regions of boxes and rows reaching 0 and 32,767, in a compact record and
/// in a 64-byte one, field by field, the compact bounds by their SSE2 and scalar code.
void checkPlanarRecordLimits()
{
  const Int3 shapes[] = {
    { 32767, 3, 1 }, { 32770, 3, 1 }, { 2, 1, 32767 }, { 1, 3, 32767 }, { 1, 3, 32770 }
  };
  unsigned seed = 300;
  for (const Int3& dims : shapes)
  {
    const Volume v = randomVolume(dims, 0.6, 1, seed++);
    Layout l;
    l.extentMin = { -40000, 7, 3 };
    l.spacing = { 0.25, 1.5, 2.0 };
    const bool fits = std::max({ dims[0], dims[1], dims[2] }) <= 32767;
    const std::string what = "2D " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
      std::to_string(dims[2]);
    for (bool boxes : { true, false })
      for (int ordering : { vtkCUDBConnectivity::SIZE_RANK, vtkCUDBConnectivity::SWEEP_ORDER })
        for (bool vertex : { false, true })
        {
          const bool planar = checkRun(v,
            l,
            Rule(),
            vertex,
            vtkCUDBConnectivity::ZYX,
            ordering,
            what + (boxes ? " boxes" : " runs"),
            true,
            true,
            boxes);
          CHECK(planar == fits,
            what << (boxes ? " boxes" : " runs") << ": 32-byte records " << (planar ? "" : "not ")
                 << "used");
        }
  }
  CHECK(vtkCUDBConnectivity::CheckPlanarRecords(11, 3000),
    "32-byte records agree with the 64-byte ones");
}

/// The fast numbering of every region (none removed) at its edges, against the flood fill:
/// LargestRegions equal to the count and one more, MinimumRegionSize equal to the smallest
/// region's size; and seeds in every region (the general numbering) giving the same.
void checkEveryRegionKept()
{
  const Int3 shapes[] = { { 40, 30, 1 }, { 14, 12, 10 } };
  unsigned seed = 900;
  for (const Int3& dims : shapes)
  {
    const Volume v = randomVolume(dims, 0.5, 1, seed++);
    int count = 0;
    const std::vector<int> sweep = floodFill(v, Rule(), false, count);
    const std::vector<long long> sizes = sizesOf(sweep, count);
    const long long smallest = *std::min_element(sizes.begin() + 1, sizes.end());
    const std::string what = std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
      std::to_string(dims[2]) + " (" + std::to_string(count) + " regions)";
    for (int ordering : { vtkCUDBConnectivity::SIZE_RANK, vtkCUDBConnectivity::SWEEP_ORDER })
    {
      const std::vector<int> all = ordering == vtkCUDBConnectivity::SWEEP_ORDER
        ? sweep
        : sizeRanked(sweep, count, [](int, long long) { return true; });
      const std::string how = what + (ordering == vtkCUDBConnectivity::SWEEP_ORDER ? " sweep" : "");
      vtkNew<vtkCUDBConnectivity> f;
      f->SetInputData(makeImage(v, Layout()));
      f->SetRegionOrdering(ordering);
      for (int largest : { count, count + 1 })
      {
        f->SetLargestRegions(largest);
        f->Update();
        CHECK(regionIds(f, Layout()) == all, how << ": LargestRegions " << largest << " keeps all");
      }
      f->SetLargestRegions(0);
      f->SetMinimumRegionSize(smallest);
      f->Update();
      CHECK(
        regionIds(f, Layout()) == all, how << ": MinimumRegionSize " << smallest << " keeps all");
      CHECK(f->GetRegionsOutput()->GetNumberOfRows() == count, how << ": a row per region");
      f->SetMinimumRegionSize(1);
      vtkNew<vtkPolyData> seeds;
      vtkNew<vtkPoints> points;
      for (int wanted = 1; wanted <= count; ++wanted)
      {
        const std::size_t i = std::find(sweep.begin(), sweep.end(), wanted) - sweep.begin();
        const int x = static_cast<int>(i % v.dims[0]),
                  y = static_cast<int>(i / v.dims[0] % v.dims[1]),
                  z = static_cast<int>(i / (v.dims[0] * v.dims[1]));
        points->InsertNextPoint(x + 0.2, y - 0.3, z + (dims[2] == 1 ? 0.0 : 0.4));
      }
      seeds->SetPoints(points);
      f->SetSeedData(seeds);
      f->Update();
      CHECK(regionIds(f, Layout()) == all, how << ": seeds in every region keep all");
    }
  }
}

/// The corners of every box cell of a 2D image against their world positions computed here
/// from the image's extent, spacing, origin and direction: each cell's corners, mapped back to
/// index space, must lie on voxel boundaries of its plane (the flat axis at the extent's first
/// layer), be exactly the cell type's corner order (VTK_PIXEL: lower in-plane axis first;
/// VTK_QUAD: around the square) at the positions origin + direction * (index * spacing), and
/// the boxes so found must cover the labelled pixels once each, with their region. Cases: an
/// axis-aligned image flat in z (the boxes written by the fast 2D path), the same rotated, and
/// images flat in y and in x (the general path), as points and as cells.
void checkBoxCornersInWorld()
{
  struct Case
  {
    Int3 dims;
    bool rotated;
  };
  const Case cases[] = { { { 37, 29, 1 }, false },
    { { 37, 29, 1 }, true },
    { { 31, 1, 23 }, false },
    { { 31, 1, 23 }, true },
    { { 1, 26, 33 }, false } };
  const double c = std::cos(0.3), s = std::sin(0.3);
  // A rotation about (1, 1, 1) / sqrt(3), row-major.
  const double t = 1 - c, u = 1 / std::sqrt(3.0);
  const double rotation[9] = { c + u * u * t,
    u * u * t - u * s,
    u * u * t + u * s,
    u * u * t + u * s,
    c + u * u * t,
    u * u * t - u * s,
    u * u * t - u * s,
    u * u * t + u * s,
    c + u * u * t };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  unsigned seed = 500;
  for (const Case& k : cases)
    for (bool cells : { false, true })
    {
      const Volume v = randomVolume(k.dims, 0.55, 1, seed++);
      Layout l;
      l.cellData = cells;
      l.extentMin = { 3, -5, 7 };
      l.spacing = { 0.75, 1.25, 2.5 };
      l.origin = { -4.5, 10.25, 3.125 };
      vtkSmartPointer<vtkImageData> image = makeImage(v, l);
      const double* m = k.rotated ? rotation : identity;
      image->SetDirectionMatrix(m);
      vtkNew<vtkCUDBConnectivity> f;
      f->SetInputData(image);
      f->Update();
      const std::string what = "box corners in world, " + std::to_string(k.dims[0]) + "x" +
        std::to_string(k.dims[1]) + "x" + std::to_string(k.dims[2]) +
        (k.rotated ? " rotated" : "") + (cells ? " cells" : " points");
      const int flat = k.dims[0] == 1 ? 0 : (k.dims[1] == 1 ? 1 : 2);
      const int inPlane[2] = { flat == 0 ? 1 : 0, flat == 2 ? 1 : 2 };
      const double shift = cells ? 0.0 : -0.5; // a voxel's lower vertex, from its index
      const std::vector<int> ids = regionIds(f, l);
      vtkUnstructuredGrid* boxes = f->GetBoxesOutput();
      vtkDataArray* boxRegion = boxes->GetCellData()->GetArray("RegionId");
      CHECK(boxRegion && boxes->GetNumberOfCells() > 0 && !ids.empty(), what << ": outputs");
      if (!boxRegion || ids.empty())
        continue;
      const int type = k.rotated ? VTK_QUAD : VTK_PIXEL;
      // corner k's (lower axis, higher axis) at hi
      const int pixelBits[4][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 1, 1 } };
      const int quadBits[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
      const int(*bits)[2] = k.rotated ? quadBits : pixelBits;
      std::vector<int> covered(ids.size(), 0);
      bool cornersRight = true, consistent = true;
      vtkNew<vtkIdList> points;
      for (vtkIdType cell = 0; cell < boxes->GetNumberOfCells(); ++cell)
      {
        CHECK(boxes->GetCellType(cell) == type, what << ": cell type");
        boxes->GetCellPoints(cell, points);
        if (points->GetNumberOfIds() != 4)
        {
          cornersRight = false;
          continue;
        }
        // The box's voxel vertices [lo, hi] along the in-plane axes, from its corners.
        std::array<double, 3> index[4];
        for (int q = 0; q < 4; ++q)
        {
          double p[3];
          boxes->GetPoint(points->GetId(q), p);
          for (int d = 0; d < 3; ++d) // index = direction^T (p - origin) / spacing
            index[q][d] = (m[d] * (p[0] - l.origin[0]) + m[3 + d] * (p[1] - l.origin[1]) +
                            m[6 + d] * (p[2] - l.origin[2])) /
              l.spacing[d];
        }
        Int3 lo{ 0, 0, 0 }, hi{ 0, 0, 0 };
        for (int a = 0; a < 2; ++a)
        {
          const int d = inPlane[a];
          lo[d] = static_cast<int>(std::lround(index[0][d] - shift));
          hi[d] = lo[d];
          for (int q = 1; q < 4; ++q)
          {
            const int vertex = static_cast<int>(std::lround(index[q][d] - shift));
            lo[d] = std::min(lo[d], vertex);
            hi[d] = std::max(hi[d], vertex);
          }
        }
        cornersRight =
          cornersRight && lo[inPlane[0]] < hi[inPlane[0]] && lo[inPlane[1]] < hi[inPlane[1]];
        for (int q = 0; q < 4; ++q)
        {
          double local[3];
          for (int a = 0; a < 2; ++a)
          {
            const int d = inPlane[a];
            local[d] = ((bits[q][a] ? hi[d] : lo[d]) + shift) * l.spacing[d];
          }
          local[flat] = l.extentMin[flat] * l.spacing[flat];
          double p[3];
          boxes->GetPoint(points->GetId(q), p);
          for (int w = 0; w < 3; ++w)
          {
            const double expected =
              l.origin[w] + m[3 * w] * local[0] + m[3 * w + 1] * local[1] + m[3 * w + 2] * local[2];
            cornersRight = cornersRight && near(p[w], expected);
          }
        }
        const int region = static_cast<int>(boxRegion->GetTuple1(cell));
        Int3 from = lo, to = hi;
        from[flat] = l.extentMin[flat];
        to[flat] = from[flat] + 1;
        for (int z = from[2]; z < to[2]; ++z)
          for (int y = from[1]; y < to[1]; ++y)
            for (int x = from[0]; x < to[0]; ++x)
            {
              const int i0 = x - l.extentMin[0], i1 = y - l.extentMin[1], i2 = z - l.extentMin[2];
              if (i0 < 0 || i1 < 0 || i2 < 0 || i0 >= v.dims[0] || i1 >= v.dims[1] ||
                i2 >= v.dims[2])
              {
                consistent = false;
                continue;
              }
              const std::size_t i = (std::size_t(i2) * v.dims[1] + i1) * v.dims[0] + i0;
              consistent = consistent && ids[i] == region && covered[i] == 0;
              covered[i] = 1;
            }
      }
      long long selected = 0, coveredCount = 0;
      for (std::size_t i = 0; i < ids.size(); ++i)
      {
        selected += ids[i] != 0;
        coveredCount += covered[i];
      }
      CHECK(cornersRight, what << ": every corner at its world position, in the cell's order");
      CHECK(consistent && coveredCount == selected,
        what << ": the boxes cover the labelled pixels once, with their region");
    }
}

/// Region tables from this many rows on are of 32 MiB or more (bytes of a row with 8-bit
/// labels: 125), which the filter computes in blocks of 16 rows and streams to the columns;
/// smaller tables are written row by row.
constexpr int BlockTableRows = 268436;

/// A 3D checkerboard: a one-voxel region per selected voxel with face connectivity.
Volume checkerboard(const Int3& dims)
{
  Volume v;
  v.dims = dims;
  v.values.resize(std::size_t(dims[0]) * dims[1] * dims[2]);
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
        v.values[(std::size_t(z) * dims[1] + y) * dims[0] + x] = (x + y + z) % 2;
  return v;
}

/// The world bounds and centroid of each region of a rotated image, by brute force: the
/// bounds of the eight corners of a region's index box (the box of its voxels) and the mean of
/// its voxel centres, each point mapped by origin + direction * (index * spacing).
struct RotatedRegions
{
  std::vector<std::array<double, 6>> bounds; ///< by RegionId, XMin, XMax, ...
  std::vector<std::array<double, 3>> centroids;

  RotatedRegions(const Volume& v,
    const Layout& l,
    const std::array<double, 9>& rotation,
    const std::vector<int>& ids,
    int count)
  {
    const int flatAxis = ExpectedGeometry(v).flatAxis;
    auto toWorld = [&](const std::array<double, 3>& index)
    {
      std::array<double, 3> w{};
      for (int r = 0; r < 3; ++r)
      {
        w[r] = l.origin[r];
        for (int d = 0; d < 3; ++d)
          w[r] += rotation[3 * r + d] * index[d] * l.spacing[d];
      }
      return w;
    };
    const std::array<double, 6> empty{ 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
    std::vector<std::array<double, 6>> box(count + 1, empty); // index units, voxels' extents
    std::vector<std::array<double, 3>> sum(count + 1, { 0, 0, 0 });
    std::vector<long long> voxels(count + 1, 0);
    forEachLabelledVoxel(v.dims,
      ids,
      [&](int id, const int p[3])
      {
        std::array<double, 3> centre{}, low{}, high{};
        for (int d = 0; d < 3; ++d)
        {
          const bool flat = d == flatAxis;
          const double index = l.extentMin[d] + p[d];
          centre[d] = flat ? index : index + (l.cellData ? 0.5 : 0.0);
          low[d] = flat ? index : index + (l.cellData ? 0.0 : -0.5);
          high[d] = flat ? index : low[d] + 1.0;
        }
        const std::array<double, 3> wc = toWorld(centre);
        ++voxels[id];
        for (int d = 0; d < 3; ++d)
        {
          sum[id][d] += wc[d];
          box[id][2 * d] = std::min(box[id][2 * d], low[d]);
          box[id][2 * d + 1] = std::max(box[id][2 * d + 1], high[d]);
        }
      });
    this->bounds.assign(count + 1, empty);
    this->centroids.assign(count + 1, { 0, 0, 0 });
    for (int id = 1; id <= count; ++id)
    {
      for (int corner = 0; corner < 8; ++corner)
      {
        std::array<double, 3> q{};
        for (int d = 0; d < 3; ++d)
          q[d] = box[id][2 * d + (corner >> d & 1)];
        const std::array<double, 3> w = toWorld(q);
        for (int r = 0; r < 3; ++r)
        {
          this->bounds[id][2 * r] = std::min(this->bounds[id][2 * r], w[r]);
          this->bounds[id][2 * r + 1] = std::max(this->bounds[id][2 * r + 1], w[r]);
        }
      }
      for (int d = 0; d < 3; ++d)
        this->centroids[id][d] = sum[id][d] / static_cast<double>(voxels[id]);
    }
  }
};

/// Whether the world columns (XMin ... ZMax, Centroid) of `table` are near `expected`.
void checkWorldColumns(vtkTable* table, const RotatedRegions& expected, const std::string& what)
{
  vtkDataArray* centroid = vtkDataArray::SafeDownCast(table->GetColumnByName("Centroid"));
  CHECK(centroid != nullptr, what << ": a Centroid column");
  if (!centroid)
    return;
  const vtkIdType count = table->GetNumberOfRows();
  const char* const worldNames[6] = { "XMin", "XMax", "YMin", "YMax", "ZMin", "ZMax" };
  bool same = true;
  for (int k = 0; k < 6 && same; ++k)
  {
    vtkDataArray* column = vtkDataArray::SafeDownCast(table->GetColumnByName(worldNames[k]));
    same = column != nullptr;
    CHECK(same, what << ": a " << worldNames[k] << " column");
    for (vtkIdType r = 0; r < count && same; ++r)
    {
      const double value = column->GetTuple1(r), want = expected.bounds[r + 1][k];
      same = near(value, want);
      CHECK(same,
        what << ": " << worldNames[k] << " of region " << r + 1 << " is " << value << ", expected "
             << want);
    }
  }
  for (vtkIdType r = 0; r < count && same; ++r)
    for (int d = 0; d < 3 && same; ++d)
    {
      const double value = centroid->GetComponent(r, d), want = expected.centroids[r + 1][d];
      same = near(value, want);
      CHECK(same,
        what << ": centroid of region " << r + 1 << " axis " << d << " is " << value
             << ", expected " << want);
    }
}

/// Whether the first rows of table `a` are those of `b`, every column's values bit for bit
/// (== of doubles; no NaN in a region table).
void checkSameFirstRows(vtkTable* a, vtkTable* b, const std::string& what)
{
  const vtkIdType rows = b->GetNumberOfRows();
  CHECK(a->GetNumberOfRows() >= rows && a->GetNumberOfColumns() == b->GetNumberOfColumns(),
    what << ": " << a->GetNumberOfRows() << " rows against " << rows);
  for (vtkIdType c = 0; c < b->GetNumberOfColumns(); ++c)
  {
    auto* cb = vtkDataArray::SafeDownCast(b->GetColumn(c));
    auto* ca = vtkDataArray::SafeDownCast(a->GetColumnByName(b->GetColumnName(c)));
    bool same = ca && cb && ca->GetNumberOfComponents() == cb->GetNumberOfComponents() &&
      ca->GetDataType() == cb->GetDataType() && a->GetNumberOfRows() >= rows;
    for (vtkIdType r = 0; same && r < rows; ++r)
      for (int k = 0; same && k < cb->GetNumberOfComponents(); ++k)
        same = ca->GetComponent(r, k) == cb->GetComponent(r, k);
    CHECK(same, what << ": column " << b->GetColumnName(c) << " of the first " << rows << " rows");
  }
}

/// The world columns (XMin ... ZMax, Centroid) of the region table of images with a direction
/// matrix against brute force (RotatedRegions), for point voxels (half a spacing either side
/// of their point), cell voxels (their cell), and 2D images flat along z and along y (no
/// thickness: the plane of their first layer of points). Tables of at least BlockTableRows
/// rows, computed in blocks, are also compared bit for bit, every column, with a table of the
/// same image's 200,000 largest regions (SIZE_RANK: the same regions as its first rows),
/// written row by row.
void checkTableInRotatedWorld()
{
  const double c = std::cos(0.5), s = std::sin(0.5);
  const std::array<double, 9> rotation{ c, -s, 0, 0, 0, -1, s, c, 0 }; // proper, not axis-aligned
  struct Case
  {
    Volume volume;
    bool cellData;
    std::array<double, 3> spacing;
    bool blocks; ///< whether the table has at least BlockTableRows rows
  };
  const std::array<double, 3> spacing{ 0.5, 1.25, -2.0 };
  const std::array<double, 3> negativeX{ -0.5, 1.25, 2.0 };
  const Case cases[] = { { randomVolume({ 23, 19, 17 }, 0.45, 1, 54), false, spacing, false },
    { randomVolume({ 21, 18, 15 }, 0.45, 1, 52), true, spacing, false },
    { randomVolume({ 61, 47, 1 }, 0.45, 1, 92), false, spacing, false },
    { randomVolume({ 3100, 3100, 1 }, 0.5, 1, 977), false, spacing, true },
    { checkerboard({ 82, 82, 82 }), true, negativeX, true },   // 275,684 regions
    { checkerboard({ 734, 1, 734 }), false, spacing, true } }; // 269,378 regions
  for (const Case& k : cases)
  {
    const Volume& v = k.volume;
    Layout l;
    l.cellData = k.cellData;
    l.extentMin = { -3, 5, 2 };
    l.origin = { 1.5, -2.25, 0.75 };
    l.spacing = k.spacing;
    vtkSmartPointer<vtkImageData> image = makeImage(v, l);
    image->SetDirectionMatrix(rotation.data());
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(image);
    f->GenerateBoxesOff();
    f->Update();
    std::ostringstream what;
    what << "rotated " << v.dims[0] << "x" << v.dims[1] << "x" << v.dims[2]
         << (k.cellData ? " cell" : " point") << " image";
    const std::vector<int> ids = regionIds(f, l);
    const int count = ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end());
    vtkTable* table = f->GetRegionsOutput();
    CHECK(table->GetNumberOfRows() == count && (count >= BlockTableRows) == k.blocks,
      what.str() << ": " << count << " rows, table of blocks " << k.blocks);
    if (table->GetNumberOfRows() != count)
      continue;
    checkWorldColumns(table, RotatedRegions(v, l, rotation, ids, count), what.str());
    if (!k.blocks)
      continue;
    vtkNew<vtkCUDBConnectivity> rows;
    rows->SetInputData(image);
    rows->GenerateBoxesOff();
    rows->SetLargestRegions(200000);
    rows->Update();
    checkSameFirstRows(table, rows->GetRegionsOutput(), what.str() + " blocks against rows");
  }
}

/// Whether two runs of the filter wrote the same RegionIds, region table (every column, value
/// for value) and field data (port 0).
void checkSameOutputs(vtkCUDBConnectivity* a, vtkCUDBConnectivity* b, const std::string& what)
{
  CHECK(regionIds(a, Layout()) == regionIds(b, Layout()) &&
      regionIds(a, Layout{ true }) == regionIds(b, Layout{ true }),
    what << ": RegionIds");
  vtkTable *ta = a->GetRegionsOutput(), *tb = b->GetRegionsOutput();
  CHECK(ta->GetNumberOfColumns() == tb->GetNumberOfColumns() &&
      ta->GetNumberOfRows() == tb->GetNumberOfRows(),
    what << ": table shape");
  for (vtkIdType c = 0; c < ta->GetNumberOfColumns(); ++c)
  {
    auto* ca = vtkDataArray::SafeDownCast(ta->GetColumn(c));
    auto* cb = vtkDataArray::SafeDownCast(tb->GetColumnByName(ta->GetColumnName(c)));
    bool same = ca && cb && ca->GetNumberOfValues() == cb->GetNumberOfValues() &&
      ca->GetDataType() == cb->GetDataType();
    for (vtkIdType i = 0; same && i < ca->GetNumberOfValues(); ++i)
      same = ca->GetVariantValue(i) == cb->GetVariantValue(i);
    CHECK(same, what << ": table column " << ta->GetColumnName(c));
  }
  for (const char* name : { "NumberOfRegions",
         "NumberOfComponents",
         "NumberOfBoxes",
         "NumberOfOUDBBoxes",
         "NumberOfExtremeVertices" })
    CHECK(fieldValue(a->GetOutput(), name) == fieldValue(b->GetOutput(), name),
      what << ": " << name << " " << fieldValue(a->GetOutput(), name) << " and "
           << fieldValue(b->GetOutput(), name));
  vtkAbstractArray* sa = a->GetOutput()->GetFieldData()->GetAbstractArray("SortingOrder");
  vtkAbstractArray* sb = b->GetOutput()->GetFieldData()->GetAbstractArray("SortingOrder");
  CHECK(sa && sb && sa->GetNumberOfValues() == sb->GetNumberOfValues() &&
      (sa->GetNumberOfValues() == 0 || sa->GetVariantValue(0) == sb->GetVariantValue(0)),
    what << ": SortingOrder");
}

/// One filter with Auto sorting updated on 2D images whose best sorting alternates (rows,
/// then columns, then noise), the first candidate's sweep written into the vectors of the
/// earlier update's winner: its outputs, box corners included, must equal a new filter's on
/// the same image.
void checkAutoSortingReuse2D()
{
  vtkNew<vtkCUDBConnectivity> kept;
  kept->SetSortingOrder(vtkCUDBConnectivity::AUTO);
  unsigned seed = 600;
  const Int3 shapes[] = {
    { 120, 90, 1 }, { 90, 120, 1 }, { 150, 40, 1 }, { 64, 64, 1 }, { 120, 90, 1 }
  };
  for (int n = 0; n < 10; ++n)
  {
    const Int3 dims = shapes[n % 5];
    Volume v = randomVolume(dims, 0.5, 1, seed++);
    const int pattern = n % 3; // rows, columns, noise
    for (int y = 0; pattern < 2 && y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
        if ((pattern == 0 ? y : x) % 3 == 0 && v.values[std::size_t(y) * dims[0] + x] == 0)
          v.values[std::size_t(y) * dims[0] + x] = 1; // long stripes along one axis
    vtkSmartPointer<vtkImageData> image = makeImage(v, Layout());
    kept->SetInputData(image);
    kept->Update();
    vtkNew<vtkCUDBConnectivity> fresh;
    fresh->SetSortingOrder(vtkCUDBConnectivity::AUTO);
    fresh->SetInputData(image);
    fresh->Update();
    const std::string what = "Auto sorting, update " + std::to_string(n);
    checkSameOutputs(kept, fresh, what);
    vtkPoints* pa = kept->GetBoxesOutput()->GetPoints();
    vtkPoints* pb = fresh->GetBoxesOutput()->GetPoints();
    bool same = pa && pb && pa->GetNumberOfPoints() == pb->GetNumberOfPoints() &&
      kept->GetBoxesOutput()->GetNumberOfCells() == fresh->GetBoxesOutput()->GetNumberOfCells();
    for (vtkIdType i = 0; same && i < pa->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      pa->GetPoint(i, a);
      pb->GetPoint(i, b);
      same = a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    }
    CHECK(same, what << ": box corners");
  }
}

/// 2D images without the boxes output take the runs of their pixel rows (the regions measured
/// from the runs, no boxes written): against the flood fill and brute-force table, and every
/// output the same as through the sweep's boxes (RunLabelling off) and as with the boxes
/// output, on random images of many sizes (one row, one column, rows of one to three words),
/// densities and seeds, in the three planes, masks and label maps, with region filters.
void checkTwoDimensionalRuns()
{
  const Int3 shapes[] = { { 1, 1, 1 },
    { 70, 1, 1 },
    { 1, 1, 45 },
    { 63, 17, 1 },
    { 64, 40, 1 },
    { 65, 33, 1 },
    { 130, 21, 1 },
    { 37, 1, 29 },
    { 1, 26, 31 },
    { 200, 150, 1 } };
  unsigned seed = 900;
  int c = 0;
  for (const Int3& dims : shapes)
    for (double density : { 0.15, 0.5, 0.85 })
    {
      const int labels = c % 3 == 2 ? 3 : 1;
      const Volume v = randomVolume(dims, density, labels, seed++);
      Layout l;
      // (A line of cells is a 3D image one cell thick, not a 2D one: its centroids are not
      // what checkTable expects of a flat axis.)
      const int flat = (dims[0] == 1) + (dims[1] == 1) + (dims[2] == 1);
      l.cellData = c % 2 == 1 && flat == 1;
      l.extentMin = { c % 5 - 2, 3 - c % 4, c % 3 };
      l.spacing = { 0.5, 1.25, 2.0 };
      l.origin = { -1, 0.5, 3 };
      ++c;
      std::ostringstream what;
      what << "2D runs " << dims[0] << "x" << dims[1] << "x" << dims[2] << " density " << density
           << (l.cellData ? " cells" : " points");
      std::vector<Rule> rules(1);
      if (labels > 1)
        rules.push_back(Rule{ vtkCUDBConnectivity::LABELS });
      for (const Rule& rule : rules)
        for (bool vertex : { false, true })
        {
          const std::string name = what.str() + " mode " + std::to_string(rule.mode);
          for (int ordering : { vtkCUDBConnectivity::SIZE_RANK, vtkCUDBConnectivity::SWEEP_ORDER })
            checkRun(
              v, l, rule, vertex, vtkCUDBConnectivity::ZYX, ordering, name, true, true, false);
          // The same outputs as through the sweep's boxes and as with the boxes output, with
          // the region filters too.
          for (int filters = 0; filters < 2; ++filters)
          {
            vtkNew<vtkCUDBConnectivity> runs, sweep, boxes, fewRuns;
            for (vtkCUDBConnectivity* f : { runs.Get(), sweep.Get(), boxes.Get(), fewRuns.Get() })
            {
              f->SetInputData(makeImage(v, l));
              f->SetSelectionMode(rule.mode);
              f->SetConnectivity(vertex ? vtkCUDBConnectivity::VERTEX : vtkCUDBConnectivity::FACE);
              if (filters)
              {
                f->SetMinimumRegionSize(2);
                f->SetLargestRegions(4);
                f->SetRegionOrderingToSweepOrder();
              }
            }
            runs->GenerateBoxesOff();
            runs->SetMinimumPixelRuns(0);
            fewRuns->GenerateBoxesOff(); // the default MinimumPixelRuns: from the boxes
            sweep->GenerateBoxesOff();
            sweep->RunLabellingOff();
            for (vtkCUDBConnectivity* f : { runs.Get(), sweep.Get(), boxes.Get(), fewRuns.Get() })
              f->Update();
            const std::string named =
              name + (vertex ? " vertex" : " face") + (filters ? " filtered" : "");
            checkSameOutputs(runs, sweep, named + ", runs and sweep");
            checkSameOutputs(runs, boxes, named + ", without and with boxes");
            checkSameOutputs(runs, fewRuns, named + ", runs and boxes below MinimumPixelRuns");
          }
        }
    }
  // One image of more runs than the default MinimumPixelRuns (about 2.4 million): the runs
  // against the boxes and the sweep, and the labels and table against the flood fill. Its
  // face-connected regions are a table of BlockTableRows rows or more, which the filter
  // computes and streams 16 rows a block, the last ones stored one by one.
  const Volume v = randomVolume({ 3100, 3100, 1 }, 0.5, 1, 977);
  Layout l;
  l.extentMin = { -7, 4, 2 };
  l.spacing = { 0.5, 1.25, 2.0 };
  l.origin = { -1, 0.5, 3 };
  for (bool vertex : { false, true })
  {
    vtkNew<vtkCUDBConnectivity> runs, sweep;
    for (vtkCUDBConnectivity* f : { runs.Get(), sweep.Get() })
    {
      f->SetInputData(makeImage(v, l));
      f->SetConnectivity(vertex ? vtkCUDBConnectivity::VERTEX : vtkCUDBConnectivity::FACE);
      f->SetRegionOrderingToSweepOrder();
      f->GenerateBoxesOff();
    }
    sweep->RunLabellingOff();
    runs->Update();
    sweep->Update();
    const std::string name = std::string("2D runs 3100^2") + (vertex ? " vertex" : " face");
    checkSameOutputs(runs, sweep, name + ", runs and sweep");
    int count = 0;
    const std::vector<int> ids = regionIds(runs, l);
    CHECK(ids == floodFill(v, Rule(), vertex, count), name << ": labels against the flood fill");
    CHECK(vertex || count >= BlockTableRows,
      name << ": " << count << " regions, fewer than a table of blocks' " << BlockTableRows);
    checkTable(runs, v, l, ids, name);
  }
}

void checkRegionFilters()
{
  const Volume v = randomVolume({ 20, 18, 16 }, 0.35, 1, 77);
  int count = 0;
  const std::vector<int> sweep = floodFill(v, Rule(), false, count);
  vtkNew<vtkCUDBConnectivity> f;
  f->SetInputData(makeImage(v, Layout()));
  f->SetMinimumRegionSize(4);
  f->Update();
  CHECK(regionIds(f, Layout()) == sizeRanked(sweep, count, [](int, long long s) { return s >= 4; }),
    "MinimumRegionSize 4 removes the smaller regions");
  CHECK(fieldValue(f->GetOutput(), "NumberOfComponents") == count, "all components are counted");
  f->SetMinimumRegionSize(1);
  f->SetLargestRegions(3);
  f->Update();
  CHECK(regionIds(f, Layout()) ==
      sizeRanked(
        sweep, count, [](int, long long) { return true; }, 3),
    "LargestRegions 3 keeps the three largest");
  CHECK(f->GetRegionsOutput()->GetNumberOfRows() == 3, "three table rows");

  // Seeds: the centres of the first voxel of regions 2 and 5 (sweep order), one outside.
  f->SetLargestRegions(0);
  vtkNew<vtkPolyData> seeds;
  vtkNew<vtkPoints> points;
  for (int wanted : { 2, 5 })
  {
    const std::size_t i = std::find(sweep.begin(), sweep.end(), wanted) - sweep.begin();
    const int x = static_cast<int>(i % v.dims[0]), y = static_cast<int>(i / v.dims[0] % v.dims[1]),
              z = static_cast<int>(i / (v.dims[0] * v.dims[1]));
    points->InsertNextPoint(x + 0.2, y - 0.3, z + 0.4); // within the voxel around the point
  }
  points->InsertNextPoint(-100, -100, -100);
  seeds->SetPoints(points);
  f->SetSeedData(seeds);
  f->Update();
  CHECK(regionIds(f, Layout()) ==
      sizeRanked(sweep, count, [](int r, long long) { return r == 2 || r == 5; }),
    "seeds keep the regions containing them");
}

/// Many seeds (every k-th voxel, background ones included) in Labels mode: a region is kept
/// exactly when one of the seeds lies in it; no seed on an object warns.
void checkManySeeds()
{
  for (int step : { 1, 7, 50 })
  {
    const Volume v = randomVolume({ 23, 19, 17 }, 0.45, 3, 300 + step);
    Rule rule;
    rule.mode = vtkCUDBConnectivity::LABELS;
    int count = 0;
    const std::vector<int> sweep = floodFill(v, rule, true, count);
    std::vector<bool> seeded(count + 1, false);
    vtkNew<vtkPoints> points;
    for (std::size_t i = 0; i < v.values.size(); i += step)
    {
      const int x = static_cast<int>(i % v.dims[0]),
                y = static_cast<int>(i / v.dims[0] % v.dims[1]),
                z = static_cast<int>(i / (v.dims[0] * v.dims[1]));
      points->InsertNextPoint(x, y, z);
      seeded[sweep[i]] = true;
    }
    vtkNew<vtkPolyData> seeds;
    seeds->SetPoints(points);
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(makeImage(v, Layout()));
    f->SetSelectionModeToLabels();
    f->SetConnectivityToVertex();
    f->SetSeedData(seeds);
    f->Update();
    CHECK(regionIds(f, Layout()) ==
        sizeRanked(sweep, count, [&](int r, long long) { return bool(seeded[r]); }),
      "every " << step << "th voxel as a seed keeps the regions containing one");
  }
  const Volume v = randomVolume({ 9, 9, 9 }, 0.3, 1, 5);
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(-50, 0, 0);
  vtkNew<vtkPolyData> seeds;
  seeds->SetPoints(points);
  vtkNew<vtkCUDBConnectivity> f;
  f->SetInputData(makeImage(v, Layout()));
  f->SetSeedData(seeds);
  vtkNew<vbrtest::ErrorCounter> warnings;
  f->AddObserver(vtkCommand::WarningEvent, warnings);
  f->Update();
  CHECK(warnings->Count > 0, "seeds that all miss the objects warn");
  CHECK(fieldValue(f->GetOutput(), "NumberOfRegions") == 0, "seeds that miss keep no region");
}

void checkErrorsAndDegenerateInputs()
{
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(3, 3, 3);
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(image);
    const int errorCount = vbrtest::updateCountingErrors(f);
    CHECK(errorCount > 0, "missing scalars must raise an error");
  }
  {
    const Volume v = randomVolume({ 3, 3, 3 }, 0.5, 1, 1);
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(makeImage(v, Layout()));
    f->SetArrayComponent(2); // 0, and 1 (the magnitude), are valid
    const int errorCount = vbrtest::updateCountingErrors(f);
    CHECK(errorCount > 0, "ArrayComponent out of range must raise an error");
  }
  {
    vtkNew<vtkImageData> image; // no points at all
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(image);
    const int errorCount = vbrtest::updateCountingErrors(f);
    CHECK(errorCount == 0, "an empty image is no error");
  }
  for (double density : { 0.0, 1.0 })
  {
    const Volume v = randomVolume({ 7, 6, 5 }, density, 1, 3);
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(makeImage(v, Layout()));
    f->Update();
    const int expected = density > 0 ? 1 : 0;
    CHECK(fieldValue(f->GetOutput(), "NumberOfRegions") == expected &&
        fieldValue(f->GetOutput(), "NumberOfBoxes") == expected &&
        f->GetBoxesOutput()->GetNumberOfCells() == expected,
      "empty and full selections: " << expected << " region and box");
  }
  // A direction matrix: boxes become hexahedra, labels are unchanged.
  {
    const Volume v = randomVolume({ 8, 7, 6 }, 0.5, 1, 9);
    vtkSmartPointer<vtkImageData> image = makeImage(v, Layout());
    image->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1);
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(image);
    f->SetRegionOrderingToSweepOrder();
    f->Update();
    int count = 0;
    CHECK(regionIds(f, Layout()) == floodFill(v, Rule(), false, count), "rotated image labels");
    CHECK(f->GetBoxesOutput()->GetNumberOfCells() > 0 &&
        f->GetBoxesOutput()->GetCellType(0) == VTK_HEXAHEDRON,
      "rotated boxes are hexahedra");
  }
  // Abort at the first progress event: no labels.
  {
    const Volume v = randomVolume({ 30, 30, 30 }, 0.4, 1, 5);
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(makeImage(v, Layout()));
    vtkNew<AbortAtProgress> abort;
    f->AddObserver(vtkCommand::ProgressEvent, abort);
    f->Update();
    CHECK(abort->Calls > 0, "progress is reported");
    CHECK(regionIds(f, Layout()).empty(), "an aborted run writes no labels");
  }
}

/// Records vtkCUDBConnectivity::GetCachedBlockBytes when the filter's execution starts (after
/// the pipeline has released the outputs it is about to regenerate).
class CachedBytesAtStart : public vtkCommand
{
public:
  static CachedBytesAtStart* New() { return new CachedBytesAtStart; }
  void Execute(vtkObject*, unsigned long, void*) override
  {
    this->Bytes = vtkCUDBConnectivity::GetCachedBlockBytes();
  }
  vtkIdType Bytes = -1;
};

// Whether the filter's cache keeps released blocks: not under AddressSanitizer, where it keeps
// none so that a use of a freed output stays detectable (BlockCache.cxx).
#if defined(VBR_ADDRESS_SANITIZER)
constexpr bool CacheKeepsBlocks = false;
#else
constexpr bool CacheKeepsBlocks = true;
#endif

/// The bytes of the boxes' coordinates (one output block of several MiB).
vtkIdType boxPointBytes(vtkCUDBConnectivity* f)
{
  vtkDataArray* points = f->GetBoxesOutput()->GetPoints()->GetData();
  return points->GetNumberOfValues() * points->GetDataTypeSize();
}

/// The memory of released outputs: kept for the filter's next execution when the pipeline
/// releases them just before it (that execution finds them kept), freed at once when they are
/// released at any other time (ReleaseData, a downstream ReleaseDataFlag, the filter
/// destroyed while another exists), so that idle filters keep no more than an update's
/// scratch (at most 512 MiB).
void checkReleasedOutputsMemory()
{
  const vtkIdType scratchBound = vtkIdType(512) << 20;
  const Volume v = randomVolume({ 1024, 1024, 1 }, 0.5, 1, 406);
  vtkNew<vtkImageData> image;
  image->DeepCopy(makeImage(v, Layout()));
  vtkNew<vtkCUDBConnectivity> other; // alive throughout: the cache is not cleared
  vtkCUDBConnectivity* f = vtkCUDBConnectivity::New();
  f->SetInputData(image);
  f->Update();
  const vtkIdType boxes = boxPointBytes(f);
  CHECK(boxes > (vtkIdType(8) << 20), "released outputs: the boxes' coordinates are large");
  const vtkIdType afterUpdate = vtkCUDBConnectivity::GetCachedBlockBytes();
  CHECK(afterUpdate <= scratchBound, "released outputs: idle after an update");

  vtkNew<CachedBytesAtStart> start;
  f->AddObserver(vtkCommand::StartEvent, start);
  f->Modified();
  f->Update();
  CHECK(!CacheKeepsBlocks || start->Bytes >= afterUpdate + boxes,
    "released outputs: the next execution finds the previous outputs kept");
  const vtkIdType beforeRelease = vtkCUDBConnectivity::GetCachedBlockBytes();
  CHECK(beforeRelease <= scratchBound, "released outputs: idle after a re-execution");
  f->GetBoxesOutput()->ReleaseData();
  f->GetOutput()->ReleaseData();
  CHECK(vtkCUDBConnectivity::GetCachedBlockBytes() <= beforeRelease,
    "released outputs: ReleaseData frees them");

  // The boxes as the seeds of a filter downstream, which releases its inputs after executing.
  f->SetReleaseDataFlag(1);
  const Volume small = randomVolume({ 4, 4, 1 }, 0.5, 1, 407);
  vtkNew<vtkCUDBConnectivity> downstream;
  downstream->SetInputData(makeImage(small, Layout()));
  downstream->SetSeedConnection(f->GetOutputPort(1));
  downstream->Update();
  CHECK(f->GetBoxesOutput()->GetNumberOfPoints() == 0, "ReleaseDataFlag: the boxes released");
  CHECK(vtkCUDBConnectivity::GetCachedBlockBytes() < boxes,
    "released outputs: a downstream ReleaseDataFlag frees them");
  downstream->RemoveAllInputConnections(1);

  f->SetReleaseDataFlag(0);
  f->Modified();
  f->Update();
  const vtkIdType beforeDelete = vtkCUDBConnectivity::GetCachedBlockBytes();
  f->Delete();
  CHECK(vtkCUDBConnectivity::GetCachedBlockBytes() <= beforeDelete,
    "released outputs: a filter destroyed while another exists frees them");
}

/// Records the progress events and aborts at the first one past `at`.
class AbortPastProgress : public vtkCommand
{
public:
  static AbortPastProgress* New() { return new AbortPastProgress; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    const double p = *static_cast<double*>(data);
    this->Seen.push_back(p);
    auto* algorithm = static_cast<vtkAlgorithm*>(caller);
    if (this->AbortedAt < 0 && p > this->At)
    {
      algorithm->SetAbortExecute(1);
      this->AbortedAt = p;
      this->EventsBefore = this->Seen.size();
    }
  }
  /// Whether every event after the abort is the executive's 1.0 when RequestData returns.
  bool nothingRanAfter() const
  {
    return std::all_of(this->Seen.begin() + static_cast<std::ptrdiff_t>(this->EventsBefore),
      this->Seen.end(),
      [](double p) { return p == 1.0; });
  }
  double At = 0;
  double AbortedAt = -1;
  std::size_t EventsBefore = 0;
  std::vector<double> Seen;
};

/// An abort inside one large 2D image (the direct path from the pixel rows, in either sorting
/// and both with Auto): asked for while the rows are swept, it stops the sweep there (no
/// progress event of the filter after it) and the filter writes no labels.
void checkAbortInsideA2DImage()
{
  const Volume v = randomVolume({ 4096, 2048, 1 }, 0.5, 1, 404);
  vtkNew<vtkImageData> image;
  image->DeepCopy(makeImage(v, Layout()));
  // ZYX twice: with the boxes output, and without it (the runs of the pixel rows)
  const int sortings[] = { vtkCUDBConnectivity::ZYX,
    vtkCUDBConnectivity::XYZ,
    vtkCUDBConnectivity::AUTO,
    vtkCUDBConnectivity::ZYX };
  for (int k = 0; k < 4; ++k)
  {
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(image);
    f->SetSortingOrder(sortings[k]);
    f->SetGenerateBoxes(k < 3);
    f->SetMinimumPixelRuns(0);
    vtkNew<AbortPastProgress> abort;
    abort->At = 0.3; // past the selection: inside the sweep (PASS 1 spans 0.05 to 0.7)
    f->AddObserver(vtkCommand::ProgressEvent, abort);
    f->Update();
    const std::string name = std::string("2D abort, sorting ") + f->GetSortingOrderAsString() +
      (k < 3 ? "" : " without boxes");
    CHECK(abort->AbortedAt > 0.3 && abort->AbortedAt < 0.7,
      name + ": progress is reported inside the sweep of one image");
    CHECK(abort->nothingRanAfter(), name + ": nothing runs after the abort");
    CHECK(regionIds(f, Layout()).empty(), name + ": an aborted run writes no labels");
  }
}

/// An abort while the RegionIds of one large 2D image are painted from its pixel runs (ZYX:
/// rows along x), without seeds (PASS 3, 0.7 to 0.9) and with one (the painting that finds
/// the seeds' regions, 0.7 to 0.8): the painting reports its progress and stops at the next
/// step, nothing runs after it, and the filter writes no labels.
void checkAbortWhilePainting()
{
  const Volume v = randomVolume({ 4096, 2048, 1 }, 0.5, 1, 405);
  vtkNew<vtkImageData> image;
  image->DeepCopy(makeImage(v, Layout()));
  for (bool withSeeds : { false, true })
  {
    const std::string name = withSeeds ? "painting with seeds" : "painting";
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputData(image);
    f->SetSortingOrderToZYX();
    f->SetGenerateBoxes(withSeeds); // without: the runs of the pixel rows
    f->SetMinimumPixelRuns(0);
    vtkNew<vtkPolyData> seeds;
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(100.2, 50.3, 0);
    seeds->SetPoints(points);
    if (withSeeds)
      f->SetSeedData(seeds);
    vtkNew<AbortPastProgress> abort;
    abort->At = 0.71; // PASS 1 ends at 0.7 (a little above, rounded): past it, the painting's
    f->AddObserver(vtkCommand::ProgressEvent, abort);
    f->Update();
    CHECK(abort->AbortedAt > 0.71 && abort->AbortedAt < (withSeeds ? 0.8 : 0.9),
      name + ": progress is reported while the runs are painted");
    CHECK(abort->nothingRanAfter(), name + ": nothing runs after the abort");
    CHECK(regionIds(f, Layout()).empty(), name + ": an aborted run writes no labels");
    CHECK(f->GetOutput()->GetPointData()->GetNumberOfArrays() == 0,
      name + ": an aborted run passes no arrays");
  }
}

} // namespace

int TestCUDBConnectivity(int, char*[])
{
  checkRandomVolumes();
  checkTwoDimensional();
  checkPlanarRecordLimits();
  checkEveryRegionKept();
  checkBoxCornersInWorld();
  checkTableInRotatedWorld();
  checkTwoDimensionalRuns();
  checkAutoSortingReuse2D();
  checkHostileVolumes();
  checkSizeRankingOfALargeRegion();
  checkLargeOutputs();
  checkRegionFilters();
  checkManySeeds();
  checkErrorsAndDegenerateInputs();
  checkAbortInsideA2DImage();
  checkAbortWhilePainting();
  checkReleasedOutputsMemory();
  vtkNew<vtkCUDBConnectivity> f;
  std::ostringstream print;
  f->Print(print);
  CHECK(print.str().find("Connectivity: Face") != std::string::npos, "PrintSelf");
  return vbrtest::testResult();
}
