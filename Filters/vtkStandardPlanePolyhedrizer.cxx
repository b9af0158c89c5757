#include "vtkStandardPlanePolyhedrizer.h"

#include "Geometry.h"
#include "PolygonTriangulator.h"
#include "Polyhedrization.h"
#include "RadixSort.h"
#include "SurfelGraph.h"
#include "vtkVoxelBRepAdapters.h"
#include "vtkVoxelBRepMemory.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkType.h"
#include "vtkUnsignedCharArray.h"

#if defined(__GLIBC__)
#include <malloc.h> // malloc_trim
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>
#include <unordered_set>
#include <vector>

vtkStandardNewMacro(vtkStandardPlanePolyhedrizer);

// Out-of-line helpers of hot inline paths (isLoopEdge, point): kept out so that the common
// answer inlines at every call.
#if defined(__GNUC__) || defined(__clang__)
#define VBR_NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define VBR_NOINLINE __declspec(noinline)
#else
#define VBR_NOINLINE
#endif

namespace
{

using Int3 = vbr::Point3; // a lattice point or voxel index

/// Faces of one selected object, with what the output needs; kept only while the object's
/// cells are written (its surfel graph is most of the filter's memory), or in Labels mode on
/// threads while its batch's cells are (buildObjectFacesInBatches).
struct ObjectFaces
{
  vbr::vtk::LabelValue label;
  Int3 offset{ 0, 0, 0 }; ///< the object's box in the grid
  vbr::SurfelGraph graph;
  vbr::Polyhedron poly;
  std::size_t surfelCount = 0;          ///< the graph's, kept when its surfels are freed
  std::vector<std::uint32_t> faceSizes; ///< surfels per face, kept when the lists are freed
};

struct Statistics
{
  vtkIdType surfels = 0, faces = 0, standardVertices = 0, components = 0;
  vtkIdType minimumFaceSize = 0, maximumFaceSize = 0;

  void add(const ObjectFaces& o)
  {
    this->surfels += static_cast<vtkIdType>(o.surfelCount);
    this->components += static_cast<vtkIdType>(o.graph.componentCount);
    for (std::uint32_t count : o.faceSizes)
    {
      const vtkIdType size = static_cast<vtkIdType>(count);
      this->minimumFaceSize = this->faces == 0 ? size : std::min(this->minimumFaceSize, size);
      this->maximumFaceSize = std::max(this->maximumFaceSize, size);
      ++this->faces;
    }
    for (std::uint8_t count : o.poly.facesAtVertex)
      this->standardVertices += count >= 3;
  }

  void write(vtkFieldData* fd) const
  {
    vbr::vtk::addFieldValue(fd, "NumberOfSurfels", this->surfels);
    vbr::vtk::addFieldValue(fd, "NumberOfFaces", this->faces);
    vbr::vtk::addFieldValue(fd, "MinimumFaceSize", this->minimumFaceSize);
    vbr::vtk::addFieldValue(fd, "MaximumFaceSize", this->maximumFaceSize);
    vbr::vtk::addFieldValue(fd, "NumberOfStandardVertices", this->standardVertices);
    vbr::vtk::addFieldValue(fd, "NumberOfBoundaryComponents", this->components);
    vtkNew<vtkDoubleArray> mean;
    mean->SetName("MeanFaceSize");
    mean->InsertNextValue(this->faces ? double(this->surfels) / double(this->faces) : 0.0);
    fd->AddArray(mean);
  }
};

/// A pointel of an object in the grid's corner index space.
vbr::Point3 inGrid(const ObjectFaces& o, const vbr::Point3& p)
{
  return vbr::add(p, o.offset);
}

/// Whether the grid's index-to-world map reverses orientation (then polygons are reversed
/// so that normals still point out of the object).
bool mirrored(const vbr::vtk::VoxelGrid& grid)
{
  return grid.mirrorsSpace();
}

/// The output points of an object's graph vertices: one per pointel (the vertices of several
/// umbrellas at one pointel share it), each made on its first use, so that points come in the
/// order in which the cells first use them. Indexed by vertex (8 bytes per vertex: the points
/// are numbered from the object's first, in 32 bits), with no hash table of the points (about
/// 56 bytes per point).
class PointIds
{
public:
  /// For the vertices of `graph`, whose points are numbered from `first` on: the first vertex
  /// at each one's pointel, found by a sort.
  void reset(const vbr::SurfelGraph& graph, vtkIdType first)
  {
    const std::size_t n = graph.vertexPointel.size();
    this->Base = first;
    this->Ids.assign(n, None);
    this->First.resize(n);
    {
      // Keys packed as narrow as the pointels' box allows, radix sorted: stable, so the
      // vertices of one pointel stay in increasing order and its first comes first.
      vbr::Point3 lo{ 0, 0, 0 };
      std::int32_t extent = 0;
      for (int d = 0; d < 3 && n > 0; ++d)
      {
        const auto [min, max] = std::minmax_element(graph.vertexPointel.begin(),
          graph.vertexPointel.end(),
          [d](const vbr::Point3& a, const vbr::Point3& b) { return a[d] < b[d]; });
        lo[d] = (*min)[d];
        extent = std::max(extent, (*max)[d] - lo[d]);
      }
      // The filter refuses more than 2^20 - 1 voxels per axis (maximumVoxelsPerAxis), so the
      // pointels span at most 2^20 and every key is its own pointel's.
      assert(extent < vbr::PackedCoordinateLimit);
      const vbr::KeyPacker packer = vbr::KeyPacker::forMaximum(extent);
      std::vector<std::pair<std::uint64_t, std::uint32_t>> byPointel(n);
      for (std::uint32_t v = 0; v < n; ++v)
      {
        const vbr::Point3& p = graph.vertexPointel[v];
        byPointel[v] = { packer.pack(p[0] - lo[0], p[1] - lo[1], p[2] - lo[2]), v };
      }
      vbr::radixSortBy(
        byPointel, [](const std::pair<std::uint64_t, std::uint32_t>& r) { return r.first; });
      for (std::size_t i = 0; i < n; ++i)
        this->First[byPointel[i].second] = i > 0 && byPointel[i].first == byPointel[i - 1].first
          ? this->First[byPointel[i - 1].second]
          : byPointel[i].second;
    }
  }

  /// The point of vertex v, made by make(first vertex at its pointel) on first use.
  template<typename Make>
  vtkIdType get(std::uint32_t v, Make make)
  {
    const std::uint32_t first = this->First[v];
    if (this->Ids[first] == None)
      this->Ids[first] = static_cast<std::uint32_t>(make(first) - this->Base);
    return this->Base + this->Ids[first];
  }

private:
  static constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();
  vtkIdType Base = 0; ///< the object's first point
  std::vector<std::uint32_t>
    Ids; ///< per vertex: its point less Base (at its pointel's first vertex)
  std::vector<std::uint32_t> First; ///< per vertex: the first vertex at its pointel
};

/// The cells of output port 0 and their arrays.
class OutputBuilder
{
public:
  OutputBuilder(const vbr::vtk::VoxelGrid& grid, int labelType)
    : Grid(grid)
    , Reverse(mirrored(grid))
    , Labels(vbr::vtk::newLabelArray(labelType))
  {
    this->FaceIds->SetName("FaceId");
    this->LoopEdges->SetName("LoopEdges");
    this->Normals->SetName("PlaneNormal");
    this->Normals->SetNumberOfComponents(3);
    this->Offsets->SetName("PlaneOffset");
    this->Sizes->SetName("SurfelCount");
    this->Polys->Use32BitStorage(); // widened by fitIds when an id does not fit
    this->Lines->Use32BitStorage();
  }

  void addObject(const ObjectFaces& o, int mode)
  {
    this->Ids.reset(o.graph, this->PointsMade);
    // The object's vertices' points may all be numbered in 32 bits; the points that
    // addSurfelTriangles makes of its own are checked cell by cell (addCell, addLine).
    this->fitIds(
      this->Polys, static_cast<std::size_t>(this->PointsMade) + o.graph.vertexPointel.size());
    this->fitIds(
      this->Lines, static_cast<std::size_t>(this->PointsMade) + o.graph.vertexPointel.size());
    if (mode == vtkStandardPlanePolyhedrizer::STANDARD_EDGES)
    {
      this->addEdges(o);
    }
    else if (mode == vtkStandardPlanePolyhedrizer::SURFELS)
    {
      this->reserveCells(o.graph.size(), 4 * o.graph.size(), false);
      std::vector<vtkIdType> ids;
      for (std::uint32_t s = 0; s < o.graph.size(); ++s)
      {
        ids.clear();
        for (int k = 0; k < 4; ++k)
          ids.push_back(this->point(o, o.graph.vertexOf(s, k)));
        this->addCell(ids, o, o.poly.faceOfSurfel[s]);
      }
    }
    else if (mode == vtkStandardPlanePolyhedrizer::STANDARD_FACES)
    {
      std::size_t corners = 0;
      for (const vbr::StandardFace& face : o.poly.faces)
        corners += face.loop.size();
      this->reserveCells(o.poly.faces.size(), corners, false);
      for (std::uint32_t f = 0; f < o.poly.faces.size(); ++f)
      {
        std::vector<vtkIdType> ids;
        for (std::uint32_t v : o.poly.faces[f].loop)
          ids.push_back(this->point(o, v));
        this->addCell(ids, o, f);
      }
    }
    else
    {
      this->addTriangulatedFaces(o, mode);
    }
    this->writeFaceValues(o);
    this->commitPoints();
    this->FaceBase += static_cast<vtkIdType>(o.poly.faces.size());
  }

  /// Before addObject, in the modes that triangulate: the faces split into chunks whose
  /// triangles may be made by another thread (help) while addObject writes the cells on this
  /// one (the triangulation is about half of their cells' time). addObject makes those of each
  /// chunk no other thread has taken, in order, and waits for those another is making: the
  /// same triangles as face by face. Ends with endPrepared, once no thread helps.
  void prepare(const ObjectFaces& o, int mode)
  {
    if (mode != vtkStandardPlanePolyhedrizer::SEMI_DISCRETE &&
      mode != vtkStandardPlanePolyhedrizer::TRIANGULATED_FACES)
      return;
    if (mode == vtkStandardPlanePolyhedrizer::SEMI_DISCRETE)
      this->Polygons = semiDiscretePolygons(o);
    const std::size_t n = o.poly.faces.size();
    const std::size_t chunks = (n + FacesPerChunk - 1) / FacesPerChunk;
    this->Made.assign(chunks, {});
    this->MadeFirst.assign(n, 0);
    this->ChunkState.reset(new std::atomic<int>[chunks]);
    for (std::size_t c = 0; c < chunks; ++c)
      this->ChunkState[c].store(Untaken, std::memory_order_relaxed);
    this->Prepared = true;
  }

  /// On another thread than addObject's, after prepare: makes the triangles of the chunks
  /// from the last one back, until it meets one addObject has taken.
  void help(const ObjectFaces& o)
  {
    if (!this->Prepared)
      return;
    Scratch scratch;
    for (std::size_t c = this->Made.size(); c-- > 0;)
      if (!this->makeChunk(o, c, scratch))
        return;
  }

  /// Frees what prepare held, once addObject and help are done.
  void endPrepared()
  {
    this->Prepared = false;
    std::vector<std::vector<std::uint32_t>>().swap(this->Polygons);
    std::vector<std::vector<vbr::Triangle>>().swap(this->Made);
    std::vector<std::size_t>().swap(this->MadeFirst);
    this->ChunkState.reset();
  }

  void finish(vtkPolyData* output)
  {
    this->commitPoints();
    output->SetPoints(this->Points);
    vtkCellData* cd = output->GetCellData();
    if (this->Lines->GetNumberOfCells() > 0 || this->OtherFaceIds->GetNumberOfTuples() > 0)
    {
      output->SetLines(this->Lines);
      cd->AddArray(this->FaceIds);
      cd->AddArray(this->OtherFaceIds);
      cd->AddArray(this->Labels);
      cd->SetActiveScalars("FaceId");
      return;
    }
    output->SetPolys(this->Polys);
    cd->AddArray(this->FaceIds);
    cd->AddArray(this->Normals);
    cd->AddArray(this->Offsets);
    cd->AddArray(this->Sizes);
    cd->AddArray(this->Labels);
    if (this->LoopEdges->GetNumberOfTuples() > 0)
      cd->AddArray(this->LoopEdges);
    cd->SetActiveScalars("FaceId");
  }

private:
  /// The standard edges of the object: each face's loop cut at its standard vertices; a
  /// piece is kept by the face of smaller number on its two sides, so each appears once.
  void addEdges(const ObjectFaces& o)
  {
    this->OtherFaceIds->SetName("OtherFaceId");
    for (std::uint32_t f = 0; f < o.poly.faces.size(); ++f)
    {
      const vbr::StandardFace& face = o.poly.faces[f];
      const vbr::IdRange across = o.poly.across(f);
      const std::size_t m = face.loop.size();
      if (across.size() != m)
        throw std::logic_error("the faces across the loops were not traced");
      std::size_t start = 0;
      while (start < m && o.poly.facesAtVertex[face.loop[start]] < 3)
        ++start;
      if (start == m)
      {
        // Two faces along a whole loop: one closed edge.
        if (f < across[0])
        {
          std::vector<vtkIdType> ids;
          for (std::uint32_t v : face.loop)
            ids.push_back(this->point(o, v));
          ids.push_back(ids.front());
          this->addLine(ids, o, f, across[0]);
        }
        continue;
      }
      std::vector<vtkIdType> ids;
      for (std::size_t step = 0; step < m; ++step)
      {
        const std::size_t i = (start + step) % m;
        if (ids.empty())
          ids.push_back(this->point(o, face.loop[i]));
        const std::uint32_t next = face.loop[(i + 1) % m];
        ids.push_back(this->point(o, next));
        if (o.poly.facesAtVertex[next] >= 3)
        {
          if (f < across[i])
            this->addLine(ids, o, f, across[i]);
          ids.clear();
        }
      }
    }
  }

  void addLine(const std::vector<vtkIdType>& ids,
    const ObjectFaces& o,
    std::uint32_t f,
    std::uint32_t other)
  {
    this->fitIds(this->Lines, this->Lines->GetNumberOfConnectivityIds() + ids.size());
    this->fitIds(this->Lines, static_cast<std::size_t>(this->PointsMade));
    this->Lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    this->FaceIds->InsertNextValue(static_cast<int>(this->FaceBase + f));
    this->OtherFaceIds->InsertNextValue(static_cast<int>(this->FaceBase + other));
    vbr::vtk::appendLabel(this->Labels, o.label);
  }

  /// The triangles of a face's polygon (graph vertices along its loop, simple in the
  /// projection along the face's normal), corners at the polygon's own pointels. A polygon
  /// that cannot be triangulated (never seen: loops project to simple polygons) is drawn
  /// by its surfels, two triangles each, rather than wrongly.
  /// With `markLoops`, each triangle's `LoopEdges` bits tell which of its edges (corner k to
  /// k + 1) run along the face's loop, in the loop's direction: what vtkStandardPlaneReversion
  /// needs to rebuild the loops from the triangles (a loop may run along an edge and back).
  void addTriangulatedFace(const ObjectFaces& o,
    std::uint32_t f,
    const vbr::IdRange& polygon,
    const vbr::Triangle* triangles,
    std::size_t count,
    bool markLoops)
  {
    const bool direct = this->trianglesFit32(count);
    bool byIndex = false;
    const vbr::StandardFace& face = o.poly.faces[f];
    if (markLoops)
    {
      byIndex = direct && count > 0 && polygon.begin() == face.loop.begin();
      if (byIndex)
        this->stampLoopPoints(o, face);
      else
        this->sortLoopEdges(o, face);
    }
    std::vector<vtkIdType>& ids = this->TriangleIds;
    ids.resize(3);
    if (direct)
      this->writeTriangles32(o, face, polygon, triangles, count, markLoops, byIndex);
    else
    {
      this->commitTriangles(); // InsertNextCell appends after the counted cells
      for (std::size_t i = 0; i < count; ++i)
      {
        for (int k = 0; k < 3; ++k)
          ids[k] = this->point(o, polygon[triangles[i][k]]);
        this->addTriangle(markLoops);
      }
    }
    this->addFaceValues(o, f, count);
    if (count == 0)
    {
      this->commitTriangles();
      this->addSurfelTriangles(o, f, markLoops);
    }
  }

  /// Whether `count` more triangles go into the 32-bit cells as addTriangle would leave them
  /// (insertCell switches to 64 bits only when an id or offset would not fit).
  bool trianglesFit32(std::size_t count) const
  {
    constexpr auto limit = static_cast<std::size_t>(std::numeric_limits<vtkTypeInt32>::max());
    return !this->Polys->IsStorage64Bit() &&
      static_cast<std::size_t>(this->Polys->GetNumberOfConnectivityIds() + 3 * this->Room.written) +
        3 * count <=
      limit &&
      static_cast<std::size_t>(this->PointsMade) + 3 * count <=
      limit; // points made for these triangles, at most 3 each
  }

  /// The triangles of a face written at once into the 32-bit connectivity and offsets (and the
  /// LoopEdges bits), the values addTriangle writes one cell at a time (InsertNextCell and
  /// InsertNextValue cost more than the triangulation's ear tests); after trianglesFit32.
  void writeTriangles32(const ObjectFaces& o,
    const vbr::StandardFace& face,
    const vbr::IdRange& polygon,
    const vbr::Triangle* triangles,
    std::size_t count,
    bool markLoops,
    bool byIndex)
  {
    if (count == 0)
      return;
    const vtkIdType cells = static_cast<vtkIdType>(count);
    TriangleRoom& room = this->Room;
    if (room.open && room.written + cells > room.room)
      this->commitTriangles();
    if (!room.open)
      this->openTriangles(markLoops);
    vtkTypeInt32* corner = nullptr;
    vtkTypeInt32* offset = nullptr;
    unsigned char* bits = nullptr;
    vtkIdType corners = 0;
    if (room.written + cells <= room.room)
    {
      // Within the reservation (always, when the polygons triangulate as they always have).
      corners = room.firstCorner + 3 * room.written;
      corner = room.corners + 3 * room.written;
      offset = room.offsets + room.written;
      bits = room.bits ? room.bits + room.written : nullptr;
      room.written += cells;
    }
    else
    {
      this->commitTriangles();
      vtkCellArray::ArrayType32* connectivity = this->Polys->GetConnectivityArray32();
      vtkCellArray::ArrayType32* offsets = this->Polys->GetOffsetsArray32();
      corners = connectivity->GetNumberOfValues();
      corner = connectivity->WritePointer(corners, 3 * cells);
      offset = offsets->WritePointer(offsets->GetNumberOfValues(), cells);
      bits = markLoops ? this->LoopEdges->WritePointer(this->LoopEdges->GetNumberOfValues(), cells)
                       : nullptr;
    }
    std::vector<vtkIdType>& ids = this->TriangleIds;
    for (std::size_t i = 0; i < count; ++i)
    {
      // By index, the polygon is the loop, whose points stampLoopPoints made and kept.
      for (int k = 0; k < 3; ++k)
        ids[k] = byIndex ? this->LoopIds[static_cast<std::size_t>(triangles[i][k])]
                         : this->point(o, polygon[triangles[i][k]]);
      if (this->Reverse)
        std::reverse(ids.begin(), ids.end());
      for (int k = 0; k < 3; ++k)
        corner[3 * i + k] = static_cast<vtkTypeInt32>(ids[k]);
      offset[i] = static_cast<vtkTypeInt32>(corners + 3 * static_cast<vtkIdType>(i + 1));
      if (bits)
        bits[i] = byIndex ? this->loopEdgeBitsByIndex(o, face, triangles[i]) : this->loopEdgeBits();
    }
  }

  /// The room reserveCells left in the 32-bit connectivity, offsets and (`markLoops`) LoopEdges
  /// arrays, written by writeTriangles32 through pointers until commitTriangles counts the
  /// cells written (three WritePointer calls a face, about 200 instructions each, cost more than
  /// the few triangles of most faces).
  void openTriangles(bool markLoops)
  {
    TriangleRoom& room = this->Room;
    room = TriangleRoom();
    if (this->Polys->IsStorage64Bit())
      return;
    vtkCellArray::ArrayType32* connectivity = this->Polys->GetConnectivityArray32();
    vtkCellArray::ArrayType32* offsets = this->Polys->GetOffsetsArray32();
    room.firstCorner = connectivity->GetNumberOfValues();
    room.firstOffset = offsets->GetNumberOfValues();
    room.room = std::min(
      (connectivity->GetSize() - room.firstCorner) / 3, offsets->GetSize() - room.firstOffset);
    room.corners = connectivity->GetPointer(0) + room.firstCorner;
    room.offsets = offsets->GetPointer(0) + room.firstOffset;
    if (markLoops)
    {
      room.firstBits = this->LoopEdges->GetNumberOfValues();
      room.room = std::min(room.room, this->LoopEdges->GetSize() - room.firstBits);
      room.bits = this->LoopEdges->GetPointer(0) + room.firstBits;
    }
    room.open = room.room > 0;
  }

  /// The cells writeTriangles32 wrote since openTriangles counted in their arrays: before any
  /// other writer of the cells and at the object's end.
  void commitTriangles()
  {
    TriangleRoom& room = this->Room;
    if (room.open && room.written > 0)
    {
      this->Polys->GetConnectivityArray32()->WritePointer(room.firstCorner, 3 * room.written);
      this->Polys->GetOffsetsArray32()->WritePointer(room.firstOffset, room.written);
      if (room.bits)
        this->LoopEdges->WritePointer(room.firstBits, room.written);
      this->Polys->Modified();
    }
    room = TriangleRoom();
  }

  /// Makes the points of face f's loop in sortLoopEdges' order (LoopIds, by index into the
  /// loop) and stamps them: LoopStamp at a point that starts one loop edge, LoopStamp + 1 at
  /// one that starts several (the loop passes it more than once). A triangle's edge of loop
  /// corners a -> b, points (P_a, P_b), is a loop edge (P_i, P_i+1) exactly when P_b ends a
  /// loop edge from P_a. When P_a starts one loop edge, that is P_b = P_a+1 (and when the
  /// points are pairwise distinct, b = a + 1): loopEdgeBitsByIndex then needs neither the
  /// sorted list of loop edges nor its binary searches, which only the edges from points the
  /// loop passes more than once still read (the loops of small faces often touch themselves).
  void stampLoopPoints(const ObjectFaces& o, const vbr::StandardFace& face)
  {
    this->LoopStamp += 2;
    if (this->LoopStamp == 0) // wrapped: forget every stamp
    {
      std::fill(this->PointStamps.begin(), this->PointStamps.end(), 0);
      this->LoopStamp = 2;
    }
    const std::size_t m = face.loop.size();
    this->LoopIds.resize(m);
    for (std::size_t i = 0; i < m; ++i)
    {
      this->point(o, face.loop[(i + 1) % m]); // made in sortLoopEdges' order
      this->LoopIds[i] = this->point(o, face.loop[i]);
    }
    this->LoopEdgesSorted = false;
    // A short loop's points are compared pairwise, and stamped only when one repeats: a
    // point's stamp lies at its id, far back in the array for the points of faces made long
    // before, and those loads were the most of this step's time on small faces.
    this->LoopDistinct = m <= PairwiseLoopPoints && pairwiseDistinct(this->LoopIds);
    if (this->LoopDistinct)
      return;
    bool distinct = true;
    for (const vtkIdType id : this->LoopIds)
    {
      const auto at = static_cast<std::size_t>(id);
      if (this->PointStamps.size() <= at)
        this->PointStamps.resize(std::max(2 * this->PointStamps.size(), at + 1), 0);
      std::uint32_t& stamp = this->PointStamps[at];
      const bool seen = stamp == this->LoopStamp || stamp == this->LoopStamp + 1;
      distinct = distinct && !seen;
      stamp = seen ? this->LoopStamp + 1 : this->LoopStamp;
    }
    this->LoopDistinct = distinct;
  }

  /// Loops of at most this many points are told distinct by comparing them pairwise.
  static constexpr std::size_t PairwiseLoopPoints = 16;

  static bool pairwiseDistinct(const std::vector<vtkIdType>& ids)
  {
    for (std::size_t i = 0; i < ids.size(); ++i)
      for (std::size_t j = i + 1; j < ids.size(); ++j)
        if (ids[i] == ids[j])
          return false;
    return true;
  }

  /// Whether the edge from loop corner a to loop corner b of face's loop runs along the loop,
  /// as loopEdgeBits finds it; after stampLoopPoints found a point the loop passes twice.
  bool isLoopEdge(const ObjectFaces& o, const vbr::StandardFace& face, int a, int b)
  {
    const std::size_t m = this->LoopIds.size();
    const std::size_t next = static_cast<std::size_t>(a) + 1 == m ? 0 : a + 1;
    const vtkIdType from = this->LoopIds[a], to = this->LoopIds[b];
    if (this->PointStamps[static_cast<std::size_t>(from)] == this->LoopStamp)
      return this->LoopIds[next] == to; // the one loop edge from P_a
    return this->isLoopEdgeFromRepeated(o, face, from, to);
  }

  /// isLoopEdge from a point the loop passes more than once: a binary search of the sorted
  /// loop edges. Not inlined, so that isLoopEdge's common answer costs no more than its test.
  VBR_NOINLINE bool isLoopEdgeFromRepeated(const ObjectFaces& o,
    const vbr::StandardFace& face,
    vtkIdType from,
    vtkIdType to)
  {
    if (!this->LoopEdgesSorted)
    {
      this->sortLoopEdges(o, face); // makes no point: stampLoopPoints made them
      this->LoopEdgesSorted = true;
    }
    return std::binary_search(
      this->FaceLoopEdges.begin(), this->FaceLoopEdges.end(), std::make_pair(from, to));
  }

  /// The LoopEdges bits of a triangle of the loop's corners (indices into face's loop, after
  /// stampLoopPoints), as loopEdgeBits finds them; on a mirrored grid the triangle is written
  /// reversed.
  unsigned char loopEdgeBitsByIndex(const ObjectFaces& o,
    const vbr::StandardFace& face,
    const vbr::Triangle& t)
  {
    bool e0, e1, e2;
    if (this->LoopDistinct)
    {
      const std::size_t m = this->LoopIds.size();
      auto follows = [m](int a, int b)
      {
        return static_cast<std::size_t>(b) ==
          (static_cast<std::size_t>(a) + 1 == m ? 0 : static_cast<std::size_t>(a) + 1);
      };
      e0 = follows(t[0], t[1]), e1 = follows(t[1], t[2]), e2 = follows(t[2], t[0]);
    }
    else
    {
      e0 = this->isLoopEdge(o, face, t[0], t[1]);
      e1 = this->isLoopEdge(o, face, t[1], t[2]);
      e2 = this->isLoopEdge(o, face, t[2], t[0]);
    }
    // Reversed, the corners are t2, t1, t0 and its edges k = 0, 1, 2 are e1, e0, e2 backwards.
    return this->Reverse ? static_cast<unsigned char>(e1 | (e0 << 1) | (e2 << 2))
                         : static_cast<unsigned char>(e0 | (e1 << 1) | (e2 << 2));
  }

  /// What one thread's triangulation of the faces reuses from face to face.
  struct Scratch
  {
    std::vector<vbr::Point2L> corners;
    vbr::PolygonTriangulator triangulator;
  };

  /// Appends the triangles of face f's polygon (indices into it), simple in the projection
  /// along the face's normal, to `triangles`; none when it does not triangulate.
  static void triangulateFace(const ObjectFaces& o,
    std::uint32_t f,
    const vbr::IdRange& polygon,
    Scratch& scratch,
    std::vector<vbr::Triangle>& triangles)
  {
    const vbr::ProjectionAlong project(o.poly.faces[f].plane.normal);
    scratch.corners.clear();
    for (std::uint32_t v : polygon)
      scratch.corners.push_back(project(o.graph.vertexPointel[v]));
    scratch.triangulator.triangulate(scratch.corners, triangles);
  }

  /// The polygon of face f that the triangulating modes draw: its semi-discrete polygon
  /// (Polygons, when made) or its loop itself (not copied).
  vbr::IdRange polygonOf(const ObjectFaces& o, std::uint32_t f) const
  {
    return this->Polygons.empty()
      ? o.poly.faces[f].loop
      : vbr::IdRange{ this->Polygons[f].data(), this->Polygons[f].size() };
  }

  /// The faces of `mode` SemiDiscrete or TriangulatedFaces, with the triangles prepare made
  /// or, without them, each face's made here; then what prepare held is freed.
  void addTriangulatedFaces(const ObjectFaces& o, int mode)
  {
    if (mode == vtkStandardPlanePolyhedrizer::SEMI_DISCRETE && !this->Prepared)
      this->Polygons = semiDiscretePolygons(o);
    const bool markLoops = mode == vtkStandardPlanePolyhedrizer::TRIANGULATED_FACES;
    std::size_t triangles = 0; // a simple polygon of m corners makes m - 2
    for (std::uint32_t f = 0; f < o.poly.faces.size(); ++f)
      triangles += std::max<std::size_t>(this->polygonOf(o, f).size(), 2) - 2;
    this->reserveCells(triangles, 3 * triangles, markLoops);
    for (std::uint32_t f = 0; f < o.poly.faces.size(); ++f)
    {
      const vbr::IdRange polygon = this->polygonOf(o, f);
      if (!this->Prepared)
      {
        std::vector<vbr::Triangle>& made = this->FaceTriangles;
        made.clear();
        triangulateFace(o, f, polygon, this->Triangulation, made);
        this->addTriangulatedFace(o, f, polygon, made.data(), made.size(), markLoops);
        continue;
      }
      const std::size_t c = f / FacesPerChunk,
                        last = std::min(o.poly.faces.size(), (c + 1) * FacesPerChunk) - 1;
      if (f == c * FacesPerChunk)
      {
        if (c > 0)
          std::vector<vbr::Triangle>().swap(this->Made[c - 1]); // written: freed
        // Made here, unless the helper has taken it: then waited for (made here if given back).
        while (this->ChunkState[c].load(std::memory_order_acquire) != Made_)
          if (!this->makeChunk(o, c, this->Triangulation))
            std::this_thread::yield();
      }
      const std::size_t first = this->MadeFirst[f];
      const std::size_t end = f < last ? this->MadeFirst[f + 1] : this->Made[c].size();
      this->addTriangulatedFace(
        o, f, polygon, this->Made[c].data() + first, end - first, markLoops);
    }
    this->commitTriangles();
    if (!this->Prepared)
      std::vector<std::vector<std::uint32_t>>().swap(this->Polygons);
  }

  /// Makes the triangles of chunk c unless another thread has taken it; false when it had.
  bool makeChunk(const ObjectFaces& o, std::size_t c, Scratch& scratch)
  {
    int untaken = Untaken;
    if (!this->ChunkState[c].compare_exchange_strong(untaken, Taken, std::memory_order_acq_rel))
      return false;
    const std::size_t end = std::min(o.poly.faces.size(), (c + 1) * FacesPerChunk);
    try
    {
      for (std::size_t f = c * FacesPerChunk; f < end; ++f)
      {
        const auto face = static_cast<std::uint32_t>(f);
        this->MadeFirst[f] = this->Made[c].size();
        triangulateFace(o, face, this->polygonOf(o, face), scratch, this->Made[c]);
      }
    }
    catch (...)
    {
      // Given back, so that addObject never waits for a chunk no thread is making.
      std::vector<vbr::Triangle>().swap(this->Made[c]);
      this->ChunkState[c].store(Untaken, std::memory_order_release);
      throw;
    }
    this->ChunkState[c].store(Made_, std::memory_order_release);
    return true;
  }

  /// The triangle of points TriangleIds, without its face's values (addFaceValues); with
  /// `markLoops`, its LoopEdges bits, from the loop edges that sortLoopEdges listed.
  void addTriangle(bool markLoops)
  {
    this->insertCell(this->TriangleIds);
    if (markLoops)
      this->LoopEdges->InsertNextValue(this->loopEdgeBits());
  }

  /// The values of face f for its next `count` cells: listed, and written with the other
  /// faces' by writeFaceValues (they are the same for every cell of the face: a value at a
  /// time cost more than the triangulation), at the object's end or once PendingRuns faces
  /// are listed (the Surfels mode lists a face per cell).
  void addFaceValues(const ObjectFaces& o, std::uint32_t f, std::size_t count)
  {
    if (count == 0)
      return;
    this->PendingValues.push_back({ f, count });
    if (this->PendingValues.size() >= PendingRuns)
      this->writeFaceValues(o);
  }

  /// The values of the faces addFaceValues listed for object o, written for all their cells
  /// at once (each array reserved and reached once for many faces rather than once a face: the
  /// calls cost more than the writing on the faces of a few triangles).
  void writeFaceValues(const ObjectFaces& o)
  {
    std::size_t total = 0;
    for (const FaceRun& run : this->PendingValues)
      total += run.count;
    if (total == 0)
      return;
    const vtkIdType cells = static_cast<vtkIdType>(total);
    const vtkIdType first = this->FaceIds->GetNumberOfTuples();
    for (vtkDataArray* a : { static_cast<vtkDataArray*>(this->FaceIds),
           static_cast<vtkDataArray*>(this->Normals),
           static_cast<vtkDataArray*>(this->Offsets),
           static_cast<vtkDataArray*>(this->Sizes) })
      reserveTuples(a, first + cells);
    int* faceIds = this->FaceIds->WritePointer(first, cells);
    int* normals = this->Normals->WritePointer(3 * first, 3 * cells);
    vtkIdType* offsets = this->Offsets->WritePointer(first, cells);
    int* sizes = this->Sizes->WritePointer(first, cells);
    for (const FaceRun& run : this->PendingValues)
    {
      const vbr::StandardFace& face = o.poly.faces[run.face];
      const auto& n = face.plane.normal;
      std::fill_n(faceIds, run.count, static_cast<int>(this->FaceBase + run.face));
      for (std::size_t i = 0; i < run.count; ++i)
        for (int k = 0; k < 3; ++k)
          normals[3 * i + k] = static_cast<int>(n[k]);
      // The plane in the grid's index space: n.(p + offset) = n.p + n.offset.
      std::fill_n(offsets,
        run.count,
        static_cast<vtkIdType>(
          face.plane.mu + n[0] * o.offset[0] + n[1] * o.offset[1] + n[2] * o.offset[2]));
      std::fill_n(sizes, run.count, static_cast<int>(o.faceSizes[run.face]));
      faceIds += run.count;
      normals += 3 * run.count;
      offsets += run.count;
      sizes += run.count;
    }
    this->PendingValues.clear();
    // Every cell of the object has its label.
    reserveTuples(this->Labels, first + cells);
    vbr::vtk::appendLabel(this->Labels, o.label); // in the array's type, whatever it is
    const int bytes = this->Labels->GetDataTypeSize() * this->Labels->GetNumberOfComponents();
    auto* labels = static_cast<unsigned char*>(
      this->Labels->WriteVoidPointer(first * this->Labels->GetNumberOfComponents(),
        cells * this->Labels->GetNumberOfComponents()));
    // The first cell's label copied in doubling blocks: a memcpy per cell cost more than all
    // the cell's other values on the faces of a few triangles.
    const auto size = static_cast<std::size_t>(bytes);
    for (std::size_t done = 1; done < total;)
    {
      const std::size_t n = std::min(done, total - done);
      std::memcpy(labels + done * size, labels, n * size);
      done += n;
    }
  }

  /// Room for `tuples` tuples in `a`: WritePointer beyond the size resizes to the exact size,
  /// which, face after face past reserveCells' reservation (faces drawn by their surfels), would
  /// copy the array once per face; doubled instead, as InsertNextValue does.
  static void reserveTuples(vtkDataArray* a, vtkIdType tuples)
  {
    if (tuples * a->GetNumberOfComponents() > a->GetSize() &&
      !a->Resize(std::max(tuples, 2 * a->GetNumberOfTuples())))
      throw std::bad_alloc();
  }

  /// The LoopEdges bits of the triangle TriangleIds (as written: reversed on a mirrored grid).
  unsigned char loopEdgeBits() const
  {
    const std::vector<vtkIdType>& ids = this->TriangleIds;
    const auto& loopEdges = this->FaceLoopEdges;
    unsigned char bits = 0;
    for (int k = 0; k < 3; ++k)
      if (std::binary_search(loopEdges.begin(),
            loopEdges.end(),
            this->Reverse ? std::make_pair(ids[(k + 1) % 3], ids[k])
                          : std::make_pair(ids[k], ids[(k + 1) % 3])))
        bits |= static_cast<unsigned char>(1 << k);
    return bits;
  }

  /// The face's loop edges as point pairs into FaceLoopEdges, sorted for a binary search (a
  /// std::set of them, a node allocated per edge, took as long as the triangulation).
  void sortLoopEdges(const ObjectFaces& o, const vbr::StandardFace& face)
  {
    std::vector<std::pair<vtkIdType, vtkIdType>>& loopEdges = this->FaceLoopEdges;
    loopEdges.clear();
    for (std::size_t i = 0; i < face.loop.size(); ++i)
    {
      // The end's point first (points are numbered as made; stampLoopPoints follows the same
      // order): the order GCC gave the two arguments of the former emplace_back(point(a),
      // point(b)), whose order C++ leaves open, now written out, so any compiler numbers alike.
      const vtkIdType next = this->point(o, face.loop[(i + 1) % face.loop.size()]);
      loopEdges.emplace_back(this->point(o, face.loop[i]), next);
    }
    std::sort(loopEdges.begin(), loopEdges.end());
  }

  /// The triangle of points TriangleIds for face f; with `markLoops`, its LoopEdges bits, from
  /// the loop edges that sortLoopEdges listed.
  void addFaceTriangle(const ObjectFaces& o, std::uint32_t f, bool markLoops)
  {
    std::vector<vtkIdType>& ids = this->TriangleIds;
    this->addCell(ids, o, f); // reverses ids on a mirrored grid, as the loop is written
    if (markLoops)
      this->LoopEdges->InsertNextValue(this->loopEdgeBits());
  }

  /// Face f drawn by its surfels, two triangles each, refilled from the face's outline (the
  /// graph's lists are freed by now): corners on the loop take the loop's points, the others
  /// points of their own.
  void addSurfelTriangles(const ObjectFaces& o, std::uint32_t f, bool markLoops)
  {
    const vbr::StandardFace& face = o.poly.faces[f];
    vbr::FaceOutline outline;
    outline.plane = face.plane;
    std::map<std::uint64_t, vtkIdType> pointOf; // pointel -> point, for this face only
    for (std::uint32_t v : face.loop)
    {
      outline.loop.push_back(o.graph.vertexPointel[v]);
      pointOf.emplace(vbr::packBiased(outline.loop.back()), this->point(o, v));
    }
    std::vector<vbr::Surfel> surfels;
    if (!vbr::surfelsOfOutline(outline, o.graph.dims, surfels).empty())
      throw std::logic_error("a face's loop neither triangulates nor bounds its surfels");
    std::vector<vtkIdType>& ids = this->TriangleIds;
    for (const vbr::Surfel& s : surfels)
      for (int half = 0; half < 2; ++half)
      {
        const int corner[3] = { 0, 1 + half, 2 + half };
        for (int k = 0; k < 3; ++k)
        {
          const vbr::Point3 p = s.corner(corner[k]);
          auto it = pointOf.find(vbr::packBiased(p));
          if (it == pointOf.end())
          {
            double world[3];
            this->Grid.vertexToWorld(inGrid(o, p), world);
            it = pointOf.emplace(vbr::packBiased(p), this->newPoint(world)).first;
          }
          ids[k] = it->second;
        }
        this->addFaceTriangle(o, f, markLoops);
      }
  }

  /// The polygons of the semi-discrete faces. Each standard edge (the piece of loop
  /// between two standard vertices, shared by the two faces beside it) is drawn as the
  /// chord between its ends, or refined: along its pointels. Refined are the edges of faces
  /// with fewer than three standard vertices, then, until none is left, those of every face
  /// whose polygon is not simple and counter-clockwise in the projection along its normal
  /// (a face refined all round is its loop, which is). Both faces beside an edge see it the
  /// same way, so the triangles of neighbouring faces meet edge to edge.
  static std::vector<std::vector<std::uint32_t>> semiDiscretePolygons(const ObjectFaces& o)
  {
    std::unordered_set<std::uint64_t> refined; // loop edges, as unordered vertex pairs
    auto edge = [](std::uint32_t a, std::uint32_t b)
    { return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a; };
    auto refineFace = [&](const vbr::StandardFace& face)
    {
      for (std::size_t i = 0; i < face.loop.size(); ++i)
        refined.insert(edge(face.loop[i], face.loop[(i + 1) % face.loop.size()]));
    };
    const auto& faces = o.poly.faces;
    for (const vbr::StandardFace& face : faces)
      if (std::count_if(face.loop.begin(),
            face.loop.end(),
            [&](std::uint32_t v) { return o.poly.facesAtVertex[v] >= 3; }) < 3)
        refineFace(face);
    std::vector<std::vector<std::uint32_t>> polygons(faces.size());
    for (bool changed = true; changed;)
    {
      changed = false;
      for (std::size_t f = 0; f < faces.size(); ++f)
      {
        const vbr::IdRange& loop = faces[f].loop;
        const std::size_t m = loop.size();
        std::vector<std::uint32_t>& polygon = polygons[f];
        polygon.clear();
        for (std::size_t i = 0; i < m; ++i)
          if (o.poly.facesAtVertex[loop[i]] >= 3 ||
            refined.count(edge(loop[(i + m - 1) % m], loop[i])) ||
            refined.count(edge(loop[i], loop[(i + 1) % m])))
            polygon.push_back(loop[i]);
        if (polygon.size() == m)
          continue; // the whole loop
        const vbr::ProjectionAlong project(faces[f].plane.normal);
        std::vector<vbr::Point2L> corners;
        for (std::uint32_t v : polygon)
          corners.push_back(project(o.graph.vertexPointel[v]));
        if (!vbr::isSimplePolygon(corners) || vbr::doubledArea(corners) <= 0)
        {
          refineFace(faces[f]);
          polygon.assign(loop.begin(), loop.end());
          changed = true;
        }
      }
    }
    return polygons;
  }

  /// Room for `cells` more polygons of `corners` corners in all, and their arrays: the object's
  /// exact need (when polygons triangulate as they always have), not the doubling of
  /// InsertNext, which left up to half of every output array unused. A second object's
  /// reservation at least doubles the room (Resize), so many objects cost no quadratic copying.
  void reserveCells(std::size_t cells, std::size_t corners, bool loopEdges)
  {
    auto reserve = [](vtkDataArray* a, std::size_t more)
    {
      const vtkIdType wanted = a->GetNumberOfTuples() + static_cast<vtkIdType>(more);
      if (wanted * a->GetNumberOfComponents() > a->GetSize() && !a->Resize(wanted))
        throw std::bad_alloc();
    };
    this->fitIds(this->Polys, this->Polys->GetNumberOfConnectivityIds() + corners);
    reserve(this->Polys->GetOffsetsArray(), cells);
    reserve(this->Polys->GetConnectivityArray(), corners);
    for (vtkDataArray* a : { static_cast<vtkDataArray*>(this->FaceIds),
           static_cast<vtkDataArray*>(this->Normals),
           static_cast<vtkDataArray*>(this->Offsets),
           static_cast<vtkDataArray*>(this->Sizes),
           this->Labels.Get() })
      reserve(a, cells);
    if (loopEdges)
      reserve(this->LoopEdges, cells);
  }

  /// The cells in 32-bit storage (half the memory of the ids, which most readers take alike)
  /// while `count` ids or offsets up to `count` fit in it; else, once, in 64-bit storage.
  /// A conversion that cannot allocate throws (an error and empty outputs), rather than leave
  /// 32-bit storage that later ids would overflow.
  static void fitIds(vtkCellArray* cells, std::size_t count)
  {
    if (cells->IsStorage64Bit() ||
      count <= static_cast<std::size_t>(std::numeric_limits<vtkTypeInt32>::max()))
      return;
    const double bytes = 8.0 *
      (static_cast<double>(cells->GetNumberOfConnectivityIds()) +
        static_cast<double>(cells->GetNumberOfOffsets()));
    const std::string refused = vbr::vtk::checkAllocation(bytes, "64-bit output cells");
    if (!refused.empty())
      throw std::runtime_error(refused);
    if (!cells->ConvertTo64BitStorage())
      throw std::bad_alloc();
  }

  /// The output point of graph vertex v of object o, made on its first use.
  vtkIdType point(const ObjectFaces& o, std::uint32_t v)
  {
    return this->Ids.get(v, [&](std::uint32_t u) { return this->makePoint(o, u); });
  }

  /// The point of graph vertex u, made. Not inlined: most calls of point find their point made
  /// already, and get's test stays small enough to be inlined at each of them.
  VBR_NOINLINE vtkIdType makePoint(const ObjectFaces& o, std::uint32_t u)
  {
    double world[3];
    this->Grid.vertexToWorld(inGrid(o, o.graph.vertexPointel[u]), world);
    return this->newPoint(world);
  }

  /// A new output point at `world`, written into the points' float array through a pointer
  /// (InsertNextPoint, a virtual call and a range check per point, cost as much as the point's
  /// place); the array's count is set once per object (commitPoints). Grown as InsertNextPoint
  /// grows it (to twice its size and one more point).
  vtkIdType newPoint(const double world[3])
  {
    if (this->PointsMade == this->PointRoom)
      this->growPoints();
    float* p = this->PointValues + 3 * this->PointsMade;
    for (int k = 0; k < 3; ++k)
      p[k] = static_cast<float>(world[k]); // InsertNextPoint's conversion
    return this->PointsMade++;
  }

  void growPoints()
  {
    this->commitPoints();
    vtkFloatArray* data = this->pointData();
    if (!data->Resize(this->PointsMade + 1))
      throw std::bad_alloc();
    this->PointRoom = data->GetSize() / 3;
    this->PointValues = data->GetPointer(0);
  }

  /// The points made since the last commit counted in the points' array.
  void commitPoints()
  {
    const vtkIdType committed = this->Points->GetNumberOfPoints();
    if (this->PointsMade == committed)
      return;
    this->pointData()->WritePointer(3 * committed, 3 * (this->PointsMade - committed));
    this->Points->Modified();
  }

  vtkFloatArray* pointData()
  {
    vtkFloatArray* data = vtkFloatArray::FastDownCast(this->Points->GetData());
    if (!data || data->GetNumberOfComponents() != 3)
      throw std::logic_error("the output points are not 3-component floats");
    return data;
  }

  /// The polygon of points `ids` (reversed first on a mirrored grid), without values.
  void insertCell(std::vector<vtkIdType>& ids)
  {
    if (this->Reverse)
      std::reverse(ids.begin(), ids.end());
    // Beyond the reservation only when a polygon is drawn by its surfels (never seen).
    this->fitIds(this->Polys, this->Polys->GetNumberOfConnectivityIds() + ids.size());
    this->fitIds(this->Polys, static_cast<std::size_t>(this->PointsMade));
    this->Polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }

  /// The polygon of points `ids` of face f, with the face's values.
  void addCell(std::vector<vtkIdType>& ids, const ObjectFaces& o, std::uint32_t f)
  {
    this->insertCell(ids);
    this->addFaceValues(o, f, 1);
  }

  const vbr::vtk::VoxelGrid& Grid;
  const bool Reverse;
  vtkIdType FaceBase = 0;
  PointIds Ids;                             ///< of the object's vertices
  Scratch Triangulation;                    ///< addTriangulatedFaces' triangulation
  std::vector<vbr::Triangle> FaceTriangles; ///< a face's triangles, in addTriangulatedFaces
  /// The object's semi-discrete polygons, while its faces are triangulated and written.
  std::vector<std::vector<std::uint32_t>> Polygons;
  /// After prepare, the triangles of each chunk of FacesPerChunk faces (each face's from
  /// MadeFirst on), and whether a thread has taken the chunk, then made it.
  bool Prepared = false;
  static constexpr std::size_t FacesPerChunk = 256;
  static constexpr int Untaken = 0, Taken = 1, Made_ = 2;
  std::vector<std::vector<vbr::Triangle>> Made;
  std::vector<std::size_t> MadeFirst;
  std::unique_ptr<std::atomic<int>[]> ChunkState;
  std::vector<std::pair<vtkIdType, vtkIdType>> FaceLoopEdges; ///< from sortLoopEdges
  std::vector<std::uint32_t> PointStamps; ///< per output point, in stampLoopPoints
  std::uint32_t LoopStamp = 0;            ///< the last face's stamp (even)
  std::vector<vtkIdType> LoopIds;         ///< the points of the last face's loop
  bool LoopDistinct = false;              ///< they are pairwise distinct
  bool LoopEdgesSorted = false;           ///< FaceLoopEdges holds the last face's
  std::vector<vtkIdType> TriangleIds;     ///< the triangle being added
  /// Where writeTriangles32 writes while open (openTriangles, commitTriangles).
  struct TriangleRoom
  {
    bool open = false;
    vtkIdType firstCorner = 0, firstOffset = 0, firstBits = 0; ///< the arrays' counts at opening
    vtkIdType room = 0;              ///< triangles the arrays have room for from there
    vtkIdType written = 0;           ///< triangles written from there
    vtkTypeInt32* corners = nullptr; ///< the connectivity from firstCorner
    vtkTypeInt32* offsets = nullptr; ///< the offsets from firstOffset
    unsigned char* bits = nullptr;   ///< LoopEdges from firstBits (TriangulatedFaces)
  };
  TriangleRoom Room;
  /// The cells of a face whose values are still to write (addFaceValues, writeFaceValues).
  struct FaceRun
  {
    std::uint32_t face;
    std::size_t count;
  };
  std::vector<FaceRun> PendingValues; ///< of the object being added, in the cells' order
  static constexpr std::size_t PendingRuns = 4096; ///< written when that many are listed
  vtkNew<vtkPoints> Points;
  vtkIdType PointsMade = 0;     ///< points made, some perhaps not yet committed
  vtkIdType PointRoom = 0;      ///< points the array holds room for
  float* PointValues = nullptr; ///< the array's values while PointRoom is its room
  vtkNew<vtkCellArray> Polys;
  vtkNew<vtkCellArray> Lines;
  vtkNew<vtkIntArray> OtherFaceIds;
  vtkNew<vtkIntArray> FaceIds;
  vtkNew<vtkIntArray> Normals;
  vtkNew<vtkIdTypeArray> Offsets;
  vtkNew<vtkIntArray> Sizes;
  vtkNew<vtkUnsignedCharArray> LoopEdges; ///< TriangulatedFaces: loop edges of each triangle
  vtkSmartPointer<vtkDataArray> Labels;   ///< of the selected values' type
};

/// The voxel grid for vtkStandardPlaneReversion: world position of corner (0, 0, 0) (axis
/// aligned grids), spacing and voxels per axis; and the input's layout (extent, origin,
/// association of the scalars), so that the reversion has the layout of the input.
void writeGrid(const vbr::vtk::VoxelGrid& grid,
  const int e[6],
  vtkImageData* input,
  vtkFieldData* fd)
{
  double corner[3];
  grid.vertexToWorld({ 0, 0, 0 }, corner);
  vtkNew<vtkDoubleArray> origin, spacing, imageOrigin;
  vtkNew<vtkIntArray> dims, extent, association;
  origin->SetName("VoxelGridOrigin");
  spacing->SetName("VoxelGridSpacing");
  dims->SetName("VoxelGridDimensions");
  extent->SetName("VoxelGridExtent");
  imageOrigin->SetName("VoxelGridImageOrigin");
  association->SetName("VoxelGridAssociation");
  origin->SetNumberOfComponents(3);
  spacing->SetNumberOfComponents(3);
  dims->SetNumberOfComponents(3);
  extent->SetNumberOfComponents(6);
  imageOrigin->SetNumberOfComponents(3);
  origin->InsertNextTuple(corner);
  spacing->InsertNextTuple(grid.spacing.data());
  dims->InsertNextTuple3(grid.dims[0], grid.dims[1], grid.dims[2]);
  extent->InsertNextTypedTuple(e);
  imageOrigin->InsertNextTuple(input->GetOrigin());
  association->InsertNextValue(grid.cellData ? vtkDataObject::FIELD_ASSOCIATION_CELLS
                                             : vtkDataObject::FIELD_ASSOCIATION_POINTS);
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(origin),
         static_cast<vtkDataArray*>(spacing),
         static_cast<vtkDataArray*>(dims),
         static_cast<vtkDataArray*>(extent),
         static_cast<vtkDataArray*>(imageOrigin),
         static_cast<vtkDataArray*>(association) })
    fd->AddArray(a);
  vtkNew<vtkDoubleArray> direction;
  direction->SetName("VoxelGridDirection");
  direction->SetNumberOfComponents(9);
  direction->InsertNextTuple(grid.direction.data());
  fd->AddArray(direction);
}

/// The self-check of the reversion, made object by object in PASS 1 while each object's faces
/// are at hand (so that neither their outlines nor the objects' voxels are kept for a pass of
/// their own): the voxels recomputed from the faces alone, one value per voxel of `in.grid`
/// (x fastest: the order of the image's tuples), and whether they are the selection: each
/// object's own voxels (in Labels mode a voxel reverted into another label's object would pass
/// the combined comparison), the array as the user reads it, and the tuple count.
class ReversionCheck
{
public:
  explicit ReversionCheck(const vbr::vtk::VoxelGrid& grid)
    : Grid(grid)
  {
  }

  /// Reverts the faces of o and compares them with its voxels `selected`; after a face that
  /// could not be reverted (problem()), does nothing.
  void add(const ObjectFaces& o, const vbr::BitVolume& selected, const vbr::Execution& exec)
  {
    if (!this->Problem.empty())
      return;
    this->allocate();
    // Face by face: an outline at a time, not a copy of every loop.
    vbr::ProgressPoll poll(exec, 0.0, 1.0);
    vbr::Reversion reversion(o.graph.dims);
    vbr::FaceOutline outline;
    for (const vbr::StandardFace& f : o.poly.faces)
    {
      if (!poll.tick())
      {
        this->Problem = "aborted";
        return;
      }
      outline.plane = f.plane;
      outline.loop.clear();
      for (std::uint32_t v : f.loop)
        outline.loop.push_back(o.graph.vertexPointel[v]);
      this->Problem = reversion.add(outline);
      if (!this->Problem.empty())
        return;
    }
    vbr::BitVolume voxels;
    this->Problem = reversion.finish(voxels);
    if (!this->Problem.empty())
      return;
    this->ObjectsMatch = this->ObjectsMatch && voxels == selected;
    this->Marked += this->mark(voxels, o.offset);
    this->Expected += static_cast<vtkIdType>(selected.count());
  }

  /// The Selection array, null when a face could not be reverted, and whether it is the
  /// input's selection (`same`).
  vtkSmartPointer<vtkUnsignedCharArray> finish(const vbr::vtk::InputObjects& in,
    vtkImageData* input,
    bool& same)
  {
    if (!this->Problem.empty())
      return nullptr;
    this->allocate();
    const vtkIdType n = this->voxelCount();
    // Under MPI rank 0's grid is the whole image's, by construction; its input is a piece.
    const vtkIdType tuples = in.piece.distributed() ? n
      : this->Grid.cellData                         ? input->GetNumberOfCells()
                                                    : input->GetNumberOfPoints();
    // Each object's voxels are its selection: then the array holds them all, once each, when
    // it counts as many (no copy of the array is marked from the selections to compare). The
    // ones in the array are the marks that found a 0 (counted by mark, not by reading the
    // whole array again).
    same = this->ObjectsMatch && tuples == n && this->Marked == this->Expected;
    return this->Selection;
  }

  const std::string& problem() const { return this->Problem; }

private:
  vtkIdType voxelCount() const
  {
    return vtkIdType(this->Grid.dims[0]) * this->Grid.dims[1] * this->Grid.dims[2];
  }

  /// Sets to 1 the values of Selection at the voxels of an object whose box starts at
  /// `offset` (what vbr::vtk::markVoxels writes); returns how many of them were 0.
  vtkIdType mark(const vbr::BitVolume& voxels, const vbr::Point3& offset)
  {
    // A word of the bit rows at a time: a large box around a thin object is mostly empty words.
    unsigned char* array = this->Selection->GetPointer(0);
    const std::array<std::int32_t, 3>& dims = this->Grid.dims;
    const std::size_t words = voxels.wordsPerRow();
    const std::int32_t nx = voxels.size(0);
    vtkIdType found = 0;
    for (std::int32_t z = 0; z < voxels.size(2); ++z)
      for (std::int32_t y = 0; y < voxels.size(1); ++y)
      {
        const vbr::Word* row = voxels.row(y, z);
        unsigned char* out =
          array + (vtkIdType(z + offset[2]) * dims[1] + y + offset[1]) * dims[0] + offset[0];
        for (std::size_t i = 0; i < words; ++i)
          for (vbr::Word w = row[i]; w; w &= w - 1)
          {
            const std::int32_t x = static_cast<std::int32_t>(64 * i) + vbr::countTrailingZeros(w);
            if (x < nx)
            {
              found += out[x] == 0;
              out[x] = 1;
            }
          }
      }
    return found;
  }

  void allocate()
  {
    if (this->Selection)
      return;
    const vtkIdType n = this->voxelCount();
    this->Selection = vtkSmartPointer<vtkUnsignedCharArray>::New();
    vbr::vtk::resizeOrThrow(this->Selection, n);
    std::fill_n(this->Selection->GetPointer(0), n, 0);
  }

  const vbr::vtk::VoxelGrid& Grid;
  vtkSmartPointer<vtkUnsignedCharArray> Selection;
  vtkIdType Expected = 0; ///< the objects' voxels
  vtkIdType Marked = 0;   ///< the ones in Selection
  bool ObjectsMatch = true;
  std::string Problem;
};

/// Output port 1: the voxels recomputed from the faces alone (planes and loops), with the
/// input's layout (each rank's piece under MPI). The self-check compares the array written
/// with the input's selection written the same way, tuple by tuple, and the tuple count with
/// the input's. Under MPI it is collective; on the ranks other than 0 `objects` is empty.
bool writeReversion(ReversionCheck& check,
  vbr::vtk::InputObjects& in,
  vtkImageData* input,
  vtkImageData* output,
  std::string& problem)
{
  const bool distributed = in.piece.distributed();
  vtkSmartPointer<vtkUnsignedCharArray> selection;
  bool same = true;
  if (!distributed || in.piece.rank == 0)
  {
    selection = check.finish(in, input, same);
    problem = check.problem();
    if (!selection && !distributed)
      return false;
  }
  if (!vbr::vtk::writeReversionImage(in, selection, same, input, output))
  {
    if (problem.empty())
      problem = "the first rank could not rebuild the voxels";
    return false;
  }
  if (!same && problem.empty())
    problem = "the reversion differs from the selection";
  return same;
}

/// Surfels below which an object's reversion check and cells are made one after the other
/// (threads cost more than they save on a small object, and Labels mode has many).
constexpr std::size_t SideBySideMinimum = 4096;

/// Surfels from which the polyhedrization takes more than a few seconds (measured: about
/// 0.3 to 1 M surfels per second, several times slower with MergeFaces).
constexpr vtkIdType LargeSurfelCount = vtkIdType(1) << 21;

/// Objects from which the memory freed before the cells are written is given back to the
/// system (tens of megabytes; the trim takes milliseconds).
constexpr std::size_t TrimFromSurfels = std::size_t(1) << 20;

/// Port 0: the cells of every object's faces in `mode`, their colouring and statistics, written
/// object by object as each object's faces are made.
class FaceWriter
{
public:
  FaceWriter(const vbr::vtk::InputObjects& in, int mode)
    : Builder(in.grid, in.labelType)
    , Mode(mode)
  {
  }

  /// Object o's cells split so that another thread may help with them (help), while add
  /// writes them; endPrepared once both are done.
  void prepare(const ObjectFaces& o) { this->Builder.prepare(o, this->Mode); }
  void help(const ObjectFaces& o) { this->Builder.help(o); }
  void endPrepared() { this->Builder.endPrepared(); }

  void add(const ObjectFaces& o)
  {
    this->Stats.add(o);
    this->Builder.addObject(o, this->Mode);
  }

  void finish(bool labelsMode, vtkPolyData* output)
  {
    this->Builder.finish(output);
    vbr::vtk::setBoundaryColoring(output, labelsMode);
    this->Stats.write(output->GetFieldData());
  }

private:
  Statistics Stats;
  OutputBuilder Builder;
  int Mode;
};

/// The options of the polyhedrization from the filter's properties.
vbr::PolyhedrizationOptions optionsOf(vtkStandardPlanePolyhedrizer* self)
{
  vbr::PolyhedrizationOptions options;
  options.maximumFaceSize = static_cast<std::size_t>(self->GetMaximumFaceSize());
  options.maximumDepth = static_cast<std::uint32_t>(self->GetMaximumDepth());
  options.moveToLargerFaces = self->GetMoveToLargerFaces();
  options.mergeFaces = self->GetMergeFaces();
  options.mergeFacesUpTo = static_cast<std::size_t>(self->GetMergeFacesUpTo());
  options.facesAcross = self->GetOutputMode() == vtkStandardPlanePolyhedrizer::STANDARD_EDGES;
  return options;
}

/// Counts the surfels of the objects and warns once, before the long work, when they are
/// so many that the polyhedrization takes long.
struct SurfelCounter
{
  vtkIdType surfels = 0;
  bool warned = false;

  void add(vtkStandardPlanePolyhedrizer* self, std::size_t count)
  {
    this->surfels += static_cast<vtkIdType>(count);
    if (this->warned || this->surfels <= LargeSurfelCount)
      return;
    this->warned = true;
    vtkWarningWithObjectMacro(self,
      << "The selection has " << this->surfels
      << " boundary surfels or more: the polyhedrization will take "
      << (self->GetMergeFaces() ? "minutes" : "tens of seconds")
      << " and much memory. To shorten it, select the object rather than "
         "the background noise (SelectionMode Range with a LowerThreshold "
         "above the noise), crop the image, or abort.");
  }
};

/// The surfel graph and standard faces of one object, each step under its own execution
/// (progress range and abort); `graphMade` is told the graph's surfels before the faces grow.
/// False when aborted; an empty object gives empty `voxels`.
template<typename GraphMade>
bool makeObjectFaces(const vbr::vtk::Selected& selected,
  const std::array<int, 3>& axes,
  const vbr::PolyhedrizationOptions& options,
  const std::array<vbr::Execution, 3>& selectGraphFaces,
  GraphMade&& graphMade,
  ObjectFaces& o,
  vbr::BitVolume& voxels)
{
  o.label = selected.label;
  o.offset = selected.offset;
  voxels = vbr::vtk::inImageAxes(selected.select(selectGraphFaces[0]), axes, o.offset);
  if (voxels.empty())
    return true;
  {
    vtkLogScopeF(TRACE, "surfel graph");
    if (!vbr::buildSurfelGraph(voxels, selectGraphFaces[1], o.graph))
      return false;
  }
  graphMade(o.graph.size());
  vtkLogScopeF(TRACE, "standard faces");
  return vbr::polyhedrize(o.graph, options, selectGraphFaces[2], o.poly);
}

/// makeObjectFaces over the progress range [from, to] (5 % selection, 10 % surfel graph, the
/// rest the faces), the counter warning before the faces grow.
bool facesOfObject(vtkStandardPlanePolyhedrizer* self,
  const vbr::vtk::Selected& selected,
  const std::array<int, 3>& axes,
  const vbr::PolyhedrizationOptions& options,
  double from,
  double to,
  SurfelCounter& counter,
  ObjectFaces& o,
  vbr::BitVolume& voxels)
{
  const double a = from + 0.05 * (to - from), b = from + 0.15 * (to - from);
  return makeObjectFaces(
    selected,
    axes,
    options,
    { vbr::vtk::makeExecution(self, from, a),
      vbr::vtk::makeExecution(self, a, b),
      vbr::vtk::makeExecution(self, b, to) },
    [&](std::size_t surfels) { counter.add(self, surfels); },
    o,
    voxels);
}

/// Frees what the cells of `mode` do not read, before they are written (the counts of surfels
/// kept): the neighbours across the surfels' edges (16 bytes per surfel); but for Surfels the
/// surfels, their vertices, the face of each surfel and the faces' lists of surfels (36 bytes
/// per surfel and a list per face). Then, for a large object, the heap's free pages go back to
/// the system: the faces' lists and the growth's small blocks lie in the heap, and the cells'
/// large arrays, in pages of their own, would never reuse them (on 50% noise they stayed
/// resident under the cells: 10 bytes per voxel of the peak).
void releaseAfterFaces(ObjectFaces& o, int mode)
{
  o.surfelCount = o.graph.size();
  o.faceSizes.reserve(o.poly.faces.size());
  for (const vbr::StandardFace& f : o.poly.faces)
    o.faceSizes.push_back(static_cast<std::uint32_t>(f.surfels.size()));
  std::vector<std::uint32_t>().swap(o.graph.neighbour);
  if (mode != vtkStandardPlanePolyhedrizer::SURFELS)
  {
    std::vector<std::uint32_t>().swap(o.poly.faceOfSurfel);
    std::vector<vbr::Surfel>().swap(o.graph.surfels);
    std::vector<std::uint32_t>().swap(o.graph.vertex);
    for (vbr::StandardFace& f : o.poly.faces)
      std::vector<std::uint32_t>().swap(f.surfels);
  }
#if defined(__GLIBC__)
  if (o.surfelCount >= TrimFromSurfels)
    malloc_trim(0);
#endif
}

/// The reversion's self-check of object o and its cells: both only read o, so with threads
/// they run side by side (the check polls the abort and reports no progress: it may run off
/// the calling thread), and the check's thread then makes the triangles of the faces, from the
/// last one back, that the cells have not reached; on one thread, or for a small object, one
/// after the other.
void checkAndWrite(vtkStandardPlanePolyhedrizer* self,
  const ObjectFaces& o,
  const vbr::BitVolume& voxels,
  FaceWriter& writer,
  ReversionCheck* check)
{
  vbr::Execution exec = vbr::vtk::makeExecution(self, 0.0, 0.0);
  exec.progress = nullptr;
  const bool threaded = o.surfelCount >= SideBySideMinimum && exec.concurrency >= 2;
  if (!threaded)
    exec = exec.sequential();
  else
    writer.prepare(o);
  exec.forRange(check || threaded ? 2 : 1,
    [&](std::int64_t b, std::int64_t e)
    {
      for (std::int64_t task = b; task < e; ++task)
        if (task == 0)
          writer.add(o);
        else
        {
          if (check)
          {
            vtkLogScopeF(TRACE, "reversion");
            check->add(o, voxels, exec);
          }
          // Then the triangles of the faces the cells have not reached, unless aborted.
          if (!exec.stopRequested())
            writer.help(o);
        }
    });
  writer.endPrepared();
}

/// Objects whose faces are made side by side, per thread, in Labels mode (each on one
/// thread), at most.
constexpr std::size_t ObjectsPerThreadInBatch = 4;

/// A batch of objects of Labels mode on several threads: their faces, then their check and
/// cells.
struct ObjectBatch
{
  std::size_t first = 0; ///< the first object's index in the input's objects
  std::vector<ObjectFaces> objects;
  std::vector<vbr::BitVolume> voxels;
  std::vector<char> done; ///< the object's faces were made (not aborted)

  ObjectBatch(std::size_t from, std::size_t count)
    : first(from)
    , objects(count)
    , voxels(count)
    , done(count, 0)
  {
  }
};

/// The faces of object k of the batch on the calling thread, without progress reports (`one`
/// polls the abort), then what its cells do not read freed at once (releaseAfterFaces), so a
/// batch holds only one object's whole surfel graph per thread.
void facesInBatch(const vbr::vtk::InputObjects& in,
  const vbr::PolyhedrizationOptions& options,
  const vbr::Execution& one,
  int mode,
  ObjectBatch& batch,
  std::size_t k)
{
  ObjectFaces& o = batch.objects[k];
  vbr::BitVolume& voxels = batch.voxels[k];
  batch.done[k] = makeObjectFaces(
    in.objects[batch.first + k],
    in.axes,
    options,
    { one, one, one },
    [](std::size_t) {},
    o,
    voxels);
  if (batch.done[k] && !voxels.empty())
    releaseAfterFaces(o, mode);
}

/// Objects per batch of buildObjectFacesInBatches: up to ObjectsPerThreadInBatch per thread,
/// but at least about eight batches when there are objects enough for a thread each, since
/// the progress moves only between batches.
std::size_t objectsPerBatch(std::size_t objects, std::size_t threads)
{
  const std::size_t eighth = (objects + 7) / 8;
  return std::min(ObjectsPerThreadInBatch * threads, std::max(threads, eighth));
}

/// PASS 1 and 2 for many objects (Labels mode) on several threads, as a pipeline of batches of
/// objects: while one task writes the cells of batch b in object order and another checks its
/// reversion in object order (both only read its faces), the other tasks make the faces of
/// batch b + 1, an object each (objects share nothing). The cells and the check see the
/// objects in the order one thread gives them, so the output is the same. False when aborted.
bool buildObjectFacesInBatches(vtkStandardPlanePolyhedrizer* self,
  const vbr::vtk::InputObjects& in,
  const vbr::PolyhedrizationOptions& options,
  const vbr::Execution& exec,
  FaceWriter& writer,
  ReversionCheck* check)
{
  SurfelCounter counter;
  const vbr::Execution one = exec.sequential().silent();
  const std::size_t n = in.objects.size();
  const std::size_t size = objectsPerBatch(n, static_cast<std::size_t>(exec.concurrency));
  std::unique_ptr<ObjectBatch> ready; // faces made, released: to be written and checked
  for (std::size_t next = 0; next < n || ready;)
  {
    std::unique_ptr<ObjectBatch> making;
    if (next < n)
      making.reset(new ObjectBatch(next, std::min(size, n - next)));
    const std::size_t writing = ready ? (check ? 2 : 1) : 0;
    const std::size_t tasks = writing + (making ? making->objects.size() : 0);
    exec.forRange(static_cast<std::int64_t>(tasks),
      [&](std::int64_t b, std::int64_t e)
      {
        for (std::int64_t task = b; task < e; ++task)
          if (std::size_t(task) >= writing)
            facesInBatch(
              in, options, one, self->GetOutputMode(), *making, std::size_t(task) - writing);
          else
            for (std::size_t k = 0; k < ready->objects.size() && !exec.stopRequested(); ++k)
              if (ready->voxels[k].empty())
                continue;
              else if (task == 0)
                writer.add(ready->objects[k]);
              else
                check->add(ready->objects[k], ready->voxels[k], one);
      });
    if (self->GetAbortExecute() ||
      (making && std::count(making->done.begin(), making->done.end(), 0) > 0))
      return false;
    if (making)
    {
      next += making->objects.size();
      for (std::size_t k = 0; k < making->objects.size(); ++k)
        if (!making->voxels[k].empty())
          counter.add(self, making->objects[k].surfelCount); // after the batch: see the header
    }
    ready = std::move(making);
    self->UpdateProgress(0.05 + 0.85 * double(next) / double(n));
  }
  return !self->GetAbortExecute();
}

/// PASS 1 of the filter: the faces of every selected object, and with the reversion their
/// self-check; PASS 2 with it, object by object, so that only one object's surfel graph is
/// held at a time: the faces as cells. False when aborted. Many objects on several threads:
/// in batches (buildObjectFacesInBatches).
bool buildObjectFaces(vtkStandardPlanePolyhedrizer* self,
  const vbr::vtk::InputObjects& in,
  const vbr::PolyhedrizationOptions& options,
  FaceWriter& writer,
  ReversionCheck* check)
{
  const std::size_t n = in.objects.size();
  const vbr::Execution exec = vbr::vtk::makeExecution(self, 0.0, 0.0);
  if (n >= 2 && exec.concurrency >= 2)
    return buildObjectFacesInBatches(self, in, options, exec, writer, check);
  SurfelCounter counter;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (self->GetAbortExecute())
      return false;
    ObjectFaces o;
    vbr::BitVolume voxels;
    const double from = 0.05 + 0.85 * i / n, to = 0.05 + 0.85 * (i + 1) / n;
    if (!facesOfObject(self, in.objects[i], in.axes, options, from, to, counter, o, voxels))
      return false;
    if (voxels.empty())
      continue;
    releaseAfterFaces(o, self->GetOutputMode()); // neither the check nor the cells need them
    checkAndWrite(self, o, voxels, writer, check);
    if (self->GetAbortExecute())
      return false;
  }
  return !self->GetAbortExecute();
}

} // namespace

//------------------------------------------------------------------------------
vtkStandardPlanePolyhedrizer::vtkStandardPlanePolyhedrizer()
{
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, vtkDataSetAttributes::SCALARS);
  this->SetProgressText("Standard Plane Polyhedrizer");
}

vtkStandardPlanePolyhedrizer::~vtkStandardPlanePolyhedrizer() = default;

//------------------------------------------------------------------------------
int vtkStandardPlanePolyhedrizer::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkStandardPlanePolyhedrizer::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkImageData");
  return 1;
}

int vtkStandardPlanePolyhedrizer::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // Port 1 keeps the image's extent, origin and spacing (copied by the executive); the
  // faces on port 0 are not structured.
  vbr::vtk::removeImageInformation(outputVector, 0);
  return 1;
}

int vtkStandardPlanePolyhedrizer::RequestUpdateExtent(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // Faces are global: the whole image is needed whatever piece is asked for.
  vbr::vtk::requestWholeImage(this, request, inputVector[0], outputVector);
  return 1;
}

const char* vtkStandardPlanePolyhedrizer::GetOutputModeAsString()
{
  switch (this->OutputMode)
  {
    case SURFELS:
      return "Surfels";
    case SEMI_DISCRETE:
      return "SemiDiscrete";
    case STANDARD_EDGES:
      return "StandardEdges";
    case TRIANGULATED_FACES:
      return "TriangulatedFaces";
    default:
      return "StandardFaces";
  }
}

//------------------------------------------------------------------------------
int vtkStandardPlanePolyhedrizer::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vbr::vtk::executeGuarded(this,
    outputVector,
    "Polyhedrization",
    [&] { return this->Execute(inputVector, outputVector); });
}

int vtkStandardPlanePolyhedrizer::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkImageData* reversion = vtkImageData::GetData(outputVector, 1);
  if (!input || !output || !reversion)
  {
    vtkErrorMacro(<< "Input must be a vtkImageData.");
    return 0;
  }
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  vbr::vtk::SelectionSettings settings = vbr::vtk::selectionSettingsOf(this);
  settings.flatImagesAs2D = false; // a flat image is a one-voxel-thick slab
  settings.maximumVoxelsPerAxis = (1 << 20) - 1;
  // Selection bits, and for the reversion its Selection array and the self-check's copy.
  settings.bytesPerVoxel = 1.0 / 8.0 + (this->GenerateReversion ? 2.0 : 0.0);
  settings.distributed = true; // the faces of the whole image on rank 0 (N ranks = 1 rank)
  vbr::vtk::InputObjects in;
  if (!vbr::vtk::readInputObjects(this, input, scalars, association, settings, in))
    return 0;
  const vbr::vtk::VoxelGrid& grid = in.grid;
  this->UpdateProgress(0.05);

  // PASS 1 and 2: the standard faces of every object (paper 003), one object at a time, and
  // the faces as cells.
  FaceWriter writer(in, this->OutputMode);
  ReversionCheck check(grid);
  if (!buildObjectFaces(
        this, in, optionsOf(this), writer, this->GenerateReversion ? &check : nullptr))
  {
    output->Initialize(); // aborted
    if (this->GenerateReversion && in.piece.distributed())
      vbr::vtk::writeReversionImage(in, nullptr, false, input, reversion); // tell the others
    reversion->Initialize();
    return 1;
  }
  writer.finish(this->GetSelectionMode() == LABELS, output);
  // Under MPI the faces are the whole image's, and every rank names its grid.
  int extent[6];
  input->GetExtent(extent);
  if (in.piece.distributed())
    std::copy_n(in.piece.wholeExtent, 6, extent);
  writeGrid(in.piece.distributed() ? in.piece.whole : grid, extent, input, output->GetFieldData());
  vbr::vtk::addDistributionFields(output->GetFieldData(), in.piece);
  this->UpdateProgress(0.95);

  // PASS 3: the voxels rebuilt from the faces alone (object by object in PASS 1), checked
  // against the input.
  reversion->Initialize(); // no stale reversion when it is off
  if (this->GenerateReversion)
  {
    vtkLogScopeF(TRACE, "reversion");
    std::string why;
    if (!writeReversion(check, in, input, reversion, why))
    {
      if (!this->GetAbortExecute())
      {
        vtkErrorMacro(<< "Reversion failed: " << why << ".");
        return 0;
      }
      output->Initialize(); // aborted
      reversion->Initialize();
      return 1;
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkStandardPlanePolyhedrizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Selection:\n";
  this->Selection->PrintSelf(os, indent.GetNextIndent());
  os << indent << "OutputMode: " << this->GetOutputModeAsString() << "\n";
  os << indent << "MaximumFaceSize: " << this->MaximumFaceSize << "\n";
  os << indent << "MaximumDepth: " << this->MaximumDepth << "\n";
  os << indent << "MoveToLargerFaces: " << (this->MoveToLargerFaces ? "On\n" : "Off\n");
  os << indent << "MergeFaces: " << (this->MergeFaces ? "On\n" : "Off\n");
  os << indent << "MergeFacesUpTo: " << this->MergeFacesUpTo << "\n";
  os << indent << "GenerateReversion: " << (this->GenerateReversion ? "On\n" : "Off\n");
}
