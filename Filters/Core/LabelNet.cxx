#include "LabelNet.h"

#include "UnionFind.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numeric>

namespace vbr
{
namespace
{

// ---- The star of a grid vertex: its eight voxels, twelve faces and six edges ----
//
// Corner c = dx + 2dy + 4dz is the voxel v - 1 + (dx, dy, dz) of vertex v. Face 4d + k lies
// in the plane through v perpendicular to axis d, between corner c0 (bit d clear) and
// c0 | 1 << d, with k = the bits of c0 along b = d + 1 and c = d + 2 (mod 3). Edge 2a + s
// leaves v along axis a, towards the positive side when s is 1: the voxels around it are the
// corners whose bit a is s.

int faceLow(int f)
{
  const int d = f / 4, b = (d + 1) % 3, c = (d + 2) % 3;
  return ((f & 1) << b) | (((f >> 1) & 1) << c);
}

int faceBetween(int c0, int c1)
{
  const int x = c0 ^ c1, d = x == 1 ? 0 : (x == 2 ? 1 : 2), lo = c0 & ~x;
  return 4 * d + ((lo >> ((d + 1) % 3)) & 1) + 2 * ((lo >> ((d + 2) % 3)) & 1);
}

/// The two edges of face f at the vertex: along b then along c.
std::array<int, 2> faceEdges(int f)
{
  const int d = f / 4, b = (d + 1) % 3, c = (d + 2) % 3, lo = faceLow(f);
  return { 2 * b + ((lo >> b) & 1), 2 * c + ((lo >> c) & 1) };
}

struct EdgeCopy
{
  std::array<int, 4> faces{ -1, -1, -1, -1 };
  int count = 0;
  int around = -1; ///< the voxel whose two faces this copy holds, -1 when the edge is whole
};

struct Star
{
  std::array<std::int32_t, 8> label{};
  std::array<std::array<EdgeCopy, 2>, 6> copies{};
  std::array<int, 6> copyCount{};
  std::array<int, 12> sheetOf{};       ///< per active face, -1 for the others
  std::array<int, 8> region{};         ///< per voxel: its region (a voxel number)
  std::array<std::int32_t, 12> ball{}; ///< per sheet: the ball's label, -1 when not blown up
  int sheets = 0;

  bool active(int f) const
  {
    const int c0 = faceLow(f);
    return this->label[c0] != this->label[c0 | (1 << (f / 4))];
  }
  /// The copy of edge e that holds face f.
  int copyOf(int e, int f) const
  {
    for (int i = 0; i < this->copyCount[e]; ++i)
      for (int j = 0; j < this->copies[e][i].count; ++j)
        if (this->copies[e][i].faces[j] == f)
          return i;
    return -1;
  }
};

/// The copies of edge 2a + s by the manifold rule (LabelNet.h).
void splitEdge(Star& star, int a, int s)
{
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const int cyc[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  int w[4];
  std::int32_t l[4];
  for (int i = 0; i < 4; ++i)
  {
    w[i] = (s << a) | (cyc[i][0] << b) | (cyc[i][1] << c);
    l[i] = star.label[w[i]];
  }
  bool all = true;
  for (int i = 0; i < 4; ++i)
    all = all && l[i] != l[(i + 1) % 4];
  int around = -1; // parity of the voxels the copies are formed around
  if (all && l[0] == l[2] && l[1] == l[3])
    around = l[0] < l[1] ? 0 : 1;
  else if (all && l[0] == l[2])
    around = 1;
  else if (all && l[1] == l[3])
    around = 0;
  const int e = 2 * a + s;
  if (around < 0)
  {
    EdgeCopy whole;
    for (int i = 0; i < 4; ++i)
      if (l[i] != l[(i + 1) % 4])
        whole.faces[whole.count++] = faceBetween(w[i], w[(i + 1) % 4]);
    star.copyCount[e] = whole.count > 0 ? 1 : 0;
    star.copies[e][0] = whole;
    return;
  }
  star.copyCount[e] = 2;
  for (int k = around, n = 0; k < 4; k += 2, ++n)
  {
    EdgeCopy& copy = star.copies[e][n];
    copy.faces = { faceBetween(w[(k + 3) % 4], w[k]), faceBetween(w[k], w[(k + 1) % 4]), -1, -1 };
    copy.count = 2;
    copy.around = w[k];
  }
}

/// Regions: voxels joined across faces between equal labels and across split edges (the
/// diagonal voxels of the joined label).
void findRegions(Star& star)
{
  UnionFind regions(8);
  for (int f = 0; f < 12; ++f)
    if (!star.active(f))
      regions.unite(faceLow(f), faceLow(f) | (1 << (f / 4)));
  for (int e = 0; e < 6; ++e)
    if (star.copyCount[e] == 2)
    {
      const int a = e / 2, w0 = star.copies[e][0].around, w1 = star.copies[e][1].around;
      // The joined voxels: the other diagonal of the edge's four.
      const int x = (w0 ^ w1) & ~(1 << a);
      regions.unite(w0 ^ (x & -x), w1 ^ (x & -x));
    }
  for (int c = 0; c < 8; ++c)
    star.region[c] = int(regions.find(c));
}

/// Sheets (faces linked through shared edge copies) and which of them are blown up: those
/// along which one label has two regions or more; the ball takes the largest such label.
void findSheets(Star& star)
{
  UnionFind faces(12);
  for (int e = 0; e < 6; ++e)
    for (int i = 0; i < star.copyCount[e]; ++i)
      for (int j = 1; j < star.copies[e][i].count; ++j)
        faces.unite(star.copies[e][i].faces[0], star.copies[e][i].faces[j]);
  std::array<int, 12> id;
  id.fill(-1);
  star.sheets = 0;
  for (int f = 0; f < 12; ++f)
  {
    star.sheetOf[f] = -1;
    if (!star.active(f))
      continue;
    const int r = int(faces.find(f));
    if (id[r] < 0)
      id[r] = star.sheets++;
    star.sheetOf[f] = id[r];
  }
  for (int s = 0; s < star.sheets; ++s)
  {
    star.ball[s] = -1;
    std::array<int, 8> regionLabelSeen{};
    for (int f = 0; f < 12; ++f)
      if (star.sheetOf[f] == s)
        for (int c : { faceLow(f), faceLow(f) | (1 << (f / 4)) })
          regionLabelSeen[star.region[c]] = 1;
    for (int r = 0; r < 8; ++r)
      for (int q = r + 1; q < 8; ++q)
        if (regionLabelSeen[r] && regionLabelSeen[q] && star.label[r] == star.label[q])
          star.ball[s] = std::max(star.ball[s], star.label[r]);
    // Both copies of a split edge on one sheet would meet again at this point: the ball
    // keeps them apart, with the label joined across the edge when no label is split here.
    for (int e = 0; e < 6 && star.ball[s] < 0; ++e)
      if (star.copyCount[e] == 2 && star.sheetOf[star.copies[e][0].faces[0]] == s &&
        star.sheetOf[star.copies[e][1].faces[0]] == s)
      {
        const int w = star.copies[e][0].around,
                  x = (w ^ star.copies[e][1].around) & ~(1 << (e / 2));
        star.ball[s] = star.label[w ^ (x & -x)];
      }
  }
}

Star analyseStar(const std::array<std::int32_t, 8>& label)
{
  Star star;
  star.label = label;
  for (int e = 0; e < 6; ++e)
    splitEdge(star, e / 2, e % 2);
  findRegions(star);
  findSheets(star);
  return star;
}

// ---- The net ----

/// A corner of a face seen from one of its vertices: the face's key, which corner (in the
/// face's cycle (0,0) (1,0) (1,1) (0,1) over its axes b, c), and its point, or the two points
/// that replace it at a blown-up vertex (towards the previous corner, then the next).
struct CornerRecord
{
  std::uint64_t face;
  int corner;
  std::int32_t first, second;
  bool operator<(const CornerRecord& o) const
  {
    return this->face < o.face || (this->face == o.face && this->corner < o.corner);
  }
};

/// The point of the ball around vertex v (radius 0.3 voxel) in direction dir.
Vec3 onBall(const std::array<std::int32_t, 3>& v, const Vec3& dir)
{
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  return { v[0] + 0.3 * dir[0] / len, v[1] + 0.3 * dir[1] / len, v[2] + 0.3 * dir[2] / len };
}

struct NetBuilder
{
  const LabelVolume& volume;
  const DeformedModelOptions& options;
  LabelNet& net;
  std::vector<CornerRecord> records;
  std::vector<std::uint8_t> pinned;

  std::uint64_t faceKey(const std::array<std::int32_t, 3>& u, int d) const
  {
    const auto& n = this->volume.dims;
    return ((std::uint64_t(u[2] + 1) * std::uint64_t(n[1] + 2) + std::uint64_t(u[1] + 1)) *
               std::uint64_t(n[0] + 2) +
             std::uint64_t(u[0] + 1)) *
      3 +
      std::uint64_t(d);
  }

  /// The arguments are copies: they may lie in the net's own arrays, which this grows.
  std::int32_t addPoint(std::array<std::int32_t, 3> v, Vec3 at, Vec3 lo, Vec3 hi, bool fixed);
  void addVertex(const std::array<std::int32_t, 3>& v, const Star& star);
  void addRecord(const std::array<std::int32_t, 3>& v, int f, std::int32_t p, std::int32_t q);
  void blowUp(const std::array<std::int32_t, 3>& v, const Star& star, int sheet);
  void addPatch(const Star& star,
    int sheet,
    int region,
    const std::array<std::array<std::int32_t, 2>, 6>& pointOf);
  void assembleFaces();
  void addPolygon(const std::vector<std::int32_t>& polygon,
    const LabelPair& pair,
    const Vec3* centre);
};

/// Appends a polygon; one of more than four corners becomes the fan of triangles around a
/// new point (`centre`, else the mean of the corners), its corners all fixed: a non-planar
/// polygon drawn as the fan from a corner could cross the ball's other polygons.
void NetBuilder::addPolygon(const std::vector<std::int32_t>& polygon,
  const LabelPair& pair,
  const Vec3* centre)
{
  LabelNet& net = this->net;
  DeformedModel& m = net.model;
  auto append = [&net, &pair](std::initializer_list<std::int32_t> corners)
  {
    net.corners.insert(net.corners.end(), corners.begin(), corners.end());
    net.offsets.push_back(std::int64_t(net.corners.size()));
    net.labels.push_back(pair);
  };
  if (polygon.size() == 4)
    return append({ polygon[0], polygon[1], polygon[2], polygon[3] });
  Vec3 mean{ 0, 0, 0 };
  for (std::int32_t p : polygon)
  {
    m.boxLo[p] = m.boxHi[p] = m.position[p];
    this->pinned[p] = 1;
    for (int d = 0; d < 3; ++d)
      mean[d] += m.position[p][d] / double(polygon.size());
  }
  const Vec3 at = centre ? *centre : mean;
  const std::int32_t c = this->addPoint(m.voxel[polygon[0]], at, at, at, true);
  for (std::size_t i = 0; i < polygon.size(); ++i)
    append({ c, polygon[i], polygon[(i + 1) % polygon.size()] });
}

std::int32_t NetBuilder::addPoint(std::array<std::int32_t, 3> v,
  Vec3 at,
  Vec3 lo,
  Vec3 hi,
  bool fixed)
{
  DeformedModel& m = this->net.model;
  m.voxel.push_back(v);
  m.boxLo.push_back(lo);
  m.boxHi.push_back(hi);
  m.position.push_back(at);
  m.anchor.push_back({ double(v[0]), double(v[1]), double(v[2]) });
  this->pinned.push_back(fixed);
  return std::int32_t(m.voxel.size() - 1);
}

void NetBuilder::addRecord(const std::array<std::int32_t, 3>& v,
  int f,
  std::int32_t p,
  std::int32_t q)
{
  const int d = f / 4, b = (d + 1) % 3, c = (d + 2) % 3, lo = faceLow(f);
  std::array<std::int32_t, 3> u;
  for (int x = 0; x < 3; ++x)
    u[x] = v[x] - 1 + ((lo >> x) & 1);
  // v is the face's corner (1 - bit b, 1 - bit c) of the low voxel's face.
  const int cb = 1 - ((lo >> b) & 1), cc = 1 - ((lo >> c) & 1);
  const int corner = cc == 0 ? cb : 3 - cb;
  this->records.push_back({ this->faceKey(u, d), corner, p, q });
}

/// The points of a vertex: one per sheet (relaxed when it is the only one, else fixed in the
/// middle of its faces' quarters), or a ball's points for a blown-up sheet.
void NetBuilder::addVertex(const std::array<std::int32_t, 3>& v, const Star& star)
{
  const double margin = std::clamp(this->options.margin, 0.0, 0.45);
  const Vec3 at{ double(v[0]), double(v[1]), double(v[2]) };
  for (int s = 0; s < star.sheets; ++s)
  {
    if (star.ball[s] >= 0)
    {
      this->blowUp(v, star, s);
      continue;
    }
    std::int32_t p;
    if (star.sheets == 1)
      p = this->addPoint(v,
        at,
        { at[0] - 0.5 + margin, at[1] - 0.5 + margin, at[2] - 0.5 + margin },
        { at[0] + 0.5 - margin, at[1] + 0.5 - margin, at[2] + 0.5 - margin },
        false);
    else
    {
      Vec3 mean{ 0, 0, 0 };
      int count = 0;
      for (int f = 0; f < 12; ++f)
        if (star.sheetOf[f] == s)
        {
          const int d = f / 4, lo = faceLow(f);
          for (int x = 0; x < 3; ++x)
            mean[x] += x == d ? 0.0 : ((lo >> x) & 1) - 0.5;
          ++count;
        }
      Vec3 p0;
      for (int x = 0; x < 3; ++x)
        p0[x] = at[x] + 0.5 * mean[x] / count;
      p = this->addPoint(v, p0, p0, p0, true);
    }
    for (int f = 0; f < 12; ++f)
      if (star.sheetOf[f] == s)
        this->addRecord(v, f, p, -1);
  }
}

/// A point on each edge copy of the sheet (on the ball, leaning towards the voxel a split
/// copy is formed around), the faces' corners replaced by them, and a patch for each region
/// of another label than the ball's.
void NetBuilder::blowUp(const std::array<std::int32_t, 3>& v, const Star& star, int sheet)
{
  std::array<std::array<std::int32_t, 2>, 6> pointOf;
  for (auto& p : pointOf)
    p = { -1, -1 };
  for (int e = 0; e < 6; ++e)
    for (int i = 0; i < star.copyCount[e]; ++i)
    {
      const EdgeCopy& copy = star.copies[e][i];
      if (copy.count == 0 || star.sheetOf[copy.faces[0]] != sheet)
        continue;
      Vec3 dir{ 0, 0, 0 };
      dir[e / 2] = (e % 2) ? 1.0 : -1.0;
      for (int x = 0; x < 3 && copy.around >= 0; ++x)
        if (x != e / 2)
          dir[x] = ((copy.around >> x) & 1) ? 0.5 : -0.5;
      const Vec3 at = onBall(v, dir);
      pointOf[e][i] = this->addPoint(v, at, at, at, true);
    }
  for (int f = 0; f < 12; ++f)
  {
    if (star.sheetOf[f] != sheet)
      continue;
    const auto edges = faceEdges(f);
    const std::int32_t pb = pointOf[edges[0]][star.copyOf(edges[0], f)];
    const std::int32_t pc = pointOf[edges[1]][star.copyOf(edges[1], f)];
    const int lo = faceLow(f), d = f / 4;
    const int cb = 1 - ((lo >> ((d + 1) % 3)) & 1), cc = 1 - ((lo >> ((d + 2) % 3)) & 1);
    const int corner = cc == 0 ? cb : 3 - cb;
    // Even corners have the c edge before them in the cycle, odd ones the b edge.
    if (corner % 2 == 0)
      this->addRecord(v, f, pc, pb);
    else
      this->addRecord(v, f, pb, pc);
  }
  std::array<int, 8> seen{};
  for (int f = 0; f < 12; ++f)
    if (star.sheetOf[f] == sheet)
      for (int c : { faceLow(f), faceLow(f) | (1 << (f / 4)) })
        if (!seen[star.region[c]] && star.label[c] != star.ball[sheet])
        {
          seen[star.region[c]] = 1;
          this->addPatch(star, sheet, star.region[c], pointOf);
        }
  ++this->net.blownUpVertices;
}

/// The ball's polygon facing a region: the cycle of the sheet's edge points around it,
/// oriented against the region's faces (each edge of the patch runs opposite to the face it
/// shares, both seen from the region), then from the smaller label to the larger.
void NetBuilder::addPatch(const Star& star,
  int sheet,
  int region,
  const std::array<std::array<std::int32_t, 2>, 6>& pointOf)
{
  std::vector<std::array<std::int32_t, 2>> arcs; // directed, as the patch runs
  for (int f = 0; f < 12; ++f)
  {
    if (star.sheetOf[f] != sheet)
      continue;
    const int c0 = faceLow(f), c1 = c0 | (1 << (f / 4));
    if (star.region[c0] != region && star.region[c1] != region)
      continue;
    const auto edges = faceEdges(f);
    std::int32_t prev = pointOf[edges[1]][star.copyOf(edges[1], f)];
    std::int32_t next = pointOf[edges[0]][star.copyOf(edges[0], f)];
    const int lo = faceLow(f), d = f / 4;
    const int cb = 1 - ((lo >> ((d + 1) % 3)) & 1), cc = 1 - ((lo >> ((d + 2) % 3)) & 1);
    if ((cc == 0 ? cb : 3 - cb) % 2 == 1)
      std::swap(prev, next);
    // The face's cycle (normal from c0 to c1) runs prev -> next; seen from the region it is
    // outward when the region is c0's; the patch runs the other way.
    if (star.region[c0] == region)
      arcs.push_back({ next, prev });
    else
      arcs.push_back({ prev, next });
  }
  std::vector<std::int32_t> loop{ arcs[0][0] };
  for (std::size_t step = 0; step < arcs.size(); ++step)
  {
    const auto it =
      std::find_if(arcs.begin(), arcs.end(), [&](const auto& a) { return a[0] == loop.back(); });
    if (it == arcs.end() || (*it)[1] == loop.front())
      break;
    loop.push_back((*it)[1]);
  }
  const std::int32_t mine = star.label[region], ball = star.ball[sheet];
  if (mine > ball) // stored from the smaller label to the larger: here from the ball
    std::reverse(loop.begin(), loop.end());
  // The patch's centre: the mean of its corners (inside the ball, off every corner), moved
  // a little towards the region's voxels so that the patches of a great circle differ.
  Vec3 centre{ 0, 0, 0 }, towards{ 0, 0, 0 };
  for (std::int32_t p : loop)
    for (int d = 0; d < 3; ++d)
      centre[d] += this->net.model.position[p][d] / double(loop.size());
  for (int c = 0; c < 8; ++c)
    if (star.region[c] == region)
      for (int d = 0; d < 3; ++d)
        towards[d] += ((c >> d) & 1) ? 1.0 : -1.0;
  const double len =
    std::sqrt(towards[0] * towards[0] + towards[1] * towards[1] + towards[2] * towards[2]);
  for (int d = 0; d < 3 && len > 0; ++d)
    centre[d] += 0.05 * towards[d] / len;
  this->addPolygon(loop, { std::min(mine, ball), std::max(mine, ball) }, &centre);
}

/// Each face's corners gathered from its four vertices, in its cycle, oriented from the
/// smaller label to the larger.
void NetBuilder::assembleFaces()
{
  std::sort(this->records.begin(), this->records.end());
  const auto& n = this->volume.dims;
  std::vector<std::int32_t> polygon;
  for (std::size_t r = 0; r + 3 < this->records.size(); r += 4)
  {
    polygon.clear();
    for (std::size_t i = r; i < r + 4; ++i)
    {
      polygon.push_back(this->records[i].first);
      if (this->records[i].second >= 0)
        polygon.push_back(this->records[i].second);
    }
    std::uint64_t key = this->records[r].face;
    const int d = int(key % 3);
    key /= 3;
    const std::array<std::int32_t, 3> u{ std::int32_t(key % std::uint64_t(n[0] + 2)) - 1,
      std::int32_t((key / std::uint64_t(n[0] + 2)) % std::uint64_t(n[1] + 2)) - 1,
      std::int32_t(key / (std::uint64_t(n[0] + 2) * std::uint64_t(n[1] + 2))) - 1 };
    std::array<std::int32_t, 3> w = u;
    ++w[d];
    const std::int32_t a = this->volume.at(u[0], u[1], u[2]), b = this->volume.at(w[0], w[1], w[2]);
    if (a > b)
      std::reverse(polygon.begin(), polygon.end());
    this->addPolygon(polygon, { std::min(a, b), std::max(a, b) }, nullptr);
  }
}

/// Links (each neighbour once), the points never projected (fixed, or where polygons of
/// several pairs or other than quadrilaterals meet) and the GDM normals.
void finishNet(LabelNet& net, const std::vector<std::uint8_t>& pinned)
{
  DeformedModel& m = net.model;
  const std::size_t np = m.pointCount();
  std::vector<std::vector<std::int32_t>> next(np);
  m.shared.assign(pinned.begin(), pinned.end());
  std::vector<LabelPair> pairOf(np, LabelPair{ -1, -1 });
  for (std::size_t c = 0; c < net.polygonCount(); ++c)
  {
    const std::int64_t b = net.offsets[c], e = net.offsets[c + 1], k = e - b;
    for (std::int64_t i = 0; i < k; ++i)
    {
      const std::int32_t p = net.corners[b + i], q = net.corners[b + (i + 1) % k];
      next[p].push_back(q);
      next[q].push_back(p);
      if (pairOf[p][0] >= 0 && pairOf[p] != net.labels[c])
        m.shared[p] = 1;
      pairOf[p] = net.labels[c];
      if (k != 4)
        m.shared[p] = 1; // a fan around a blown-up vertex
    }
  }
  m.linkOffsets.assign(1, 0);
  for (auto& list : next)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    m.links.insert(m.links.end(), list.begin(), list.end());
    m.linkOffsets.push_back(std::int64_t(m.links.size()));
  }
}

void computeNetNormals(LabelNet& net)
{
  DeformedModel& m = net.model;
  m.normal.assign(m.pointCount(), Vec3{ 0, 0, 0 });
  for (std::size_t c = 0; c < net.polygonCount(); ++c)
  {
    const std::int64_t b = net.offsets[c], k = net.offsets[c + 1] - b;
    for (std::int64_t i = 0; i < k; ++i)
    {
      const Vec3& p = m.position[net.corners[b + i]];
      const Vec3& q = m.position[net.corners[b + (i + 1) % k]];
      const Vec3& r = m.position[net.corners[b + (i + k - 1) % k]];
      const Vec3 u{ q[0] - p[0], q[1] - p[1], q[2] - p[2] };
      const Vec3 w{ r[0] - p[0], r[1] - p[1], r[2] - p[2] };
      Vec3& n = m.normal[net.corners[b + i]];
      n[0] += u[1] * w[2] - u[2] * w[1];
      n[1] += u[2] * w[0] - u[0] * w[2];
      n[2] += u[0] * w[1] - u[1] * w[0];
    }
  }
}

} // namespace

LabelNet buildLabelNet(const LabelVolume& volume,
  const DeformedModelOptions& options,
  const Execution& exec)
{
  LabelNet net;
  const auto& n = volume.dims;
  net.model.dims = { n[0] + 1, n[1] + 1, n[2] + 1 };
  NetBuilder builder{ volume, options, net, {}, {} };
  std::array<std::int32_t, 8> label;
  for (std::int32_t k = 0; k <= n[2]; ++k)
  {
    if (exec.stopRequested())
      return net;
    for (std::int32_t j = 0; j <= n[1]; ++j)
      for (std::int32_t i = 0; i <= n[0]; ++i)
      {
        bool uniform = true;
        for (int c = 0; c < 8; ++c)
        {
          label[c] = volume.at(i - 1 + (c & 1), j - 1 + ((c >> 1) & 1), k - 1 + (c >> 2));
          uniform = uniform && label[c] == label[0];
        }
        if (!uniform)
          builder.addVertex({ i, j, k }, analyseStar(label));
      }
  }
  builder.assembleFaces();
  builder.records = std::vector<CornerRecord>();
  finishNet(net, builder.pinned);
  relaxDeformedModel(net.model, options, exec);
  computeNetNormals(net);
  return net;
}

namespace
{

/// The quadrilaterals of one pair of labels as a model of their own, in the grid of the
/// vertices' boxes (vertex v's box is voxel v - lo there, so positions move by 0.5 - lo), and
/// the boxes no plane may cut: those of vertices that hold no corner of the pair's faces.
struct PairModel
{
  DeformedModel model;
  std::vector<std::int32_t> global; ///< per point: the net's point
  std::array<std::int32_t, 3> lo{ 0, 0, 0 };
  BitVolume far;

  Vec3 shift() const { return { 0.5 - this->lo[0], 0.5 - this->lo[1], 0.5 - this->lo[2] }; }
};

PairModel pairModel(const LabelNet& net,
  const std::vector<std::size_t>& quads,
  std::vector<std::int32_t>& localOf)
{
  PairModel pm;
  const DeformedModel& m = net.model;
  std::array<std::int32_t, 3> hi{ 0, 0, 0 };
  pm.lo = m.dims;
  for (std::size_t c : quads)
    for (std::int64_t i = net.offsets[c]; i < net.offsets[c + 1]; ++i)
    {
      const std::int32_t p = net.corners[i];
      if (localOf[p] >= 0)
        continue;
      localOf[p] = std::int32_t(pm.global.size());
      pm.global.push_back(p);
      for (int d = 0; d < 3; ++d)
      {
        pm.lo[d] = std::min(pm.lo[d], m.voxel[p][d]);
        hi[d] = std::max(hi[d], m.voxel[p][d]);
      }
    }
  DeformedModel& sub = pm.model;
  sub.dims = { hi[0] - pm.lo[0] + 1, hi[1] - pm.lo[1] + 1, hi[2] - pm.lo[2] + 1 };
  pm.far = BitVolume(sub.dims[0], sub.dims[1], sub.dims[2]);
  for (std::int32_t k = 0; k < sub.dims[2]; ++k)
    for (std::int32_t j = 0; j < sub.dims[1]; ++j)
      for (std::int32_t i = 0; i < sub.dims[0]; ++i)
        pm.far.set(i, j, k);
  const Vec3 t = pm.shift();
  auto moved = [&t](const Vec3& x) { return Vec3{ x[0] + t[0], x[1] + t[1], x[2] + t[2] }; };
  for (std::int32_t p : pm.global)
  {
    const auto& v = m.voxel[p];
    sub.voxel.push_back({ v[0] - pm.lo[0], v[1] - pm.lo[1], v[2] - pm.lo[2] });
    pm.far.set(sub.voxel.back()[0], sub.voxel.back()[1], sub.voxel.back()[2], false);
    sub.boxLo.push_back(moved(m.boxLo[p]));
    sub.boxHi.push_back(moved(m.boxHi[p]));
    sub.position.push_back(moved(m.position[p]));
    sub.anchor.push_back(moved(m.anchor[p]));
    sub.normal.push_back(m.normal[p]);
    sub.shared.push_back(m.shared[p]);
  }
  for (std::size_t c : quads)
  {
    const std::int64_t b = net.offsets[c];
    sub.quads.push_back({ localOf[net.corners[b]],
      localOf[net.corners[b + 1]],
      localOf[net.corners[b + 2]],
      localOf[net.corners[b + 3]] });
  }
  for (std::int32_t p : pm.global)
    localOf[p] = -1;
  linkQuadrilaterals(sub);
  return pm;
}

struct LabelAssembler
{
  const LabelNet& net;
  LabelBoundary& out;
  std::vector<Vec3> position;      ///< per net point: relaxed, or projected onto its node
  std::vector<std::int32_t> outId; ///< per net point, -1 until used

  void addCell(const std::vector<std::int32_t>& points, const LabelPair& pair, int node, int level)
  {
    BoundaryMesh& mesh = this->out.mesh;
    for (std::int32_t p : points)
    {
      if (this->outId[p] < 0)
      {
        this->outId[p] = std::int32_t(mesh.points.size());
        mesh.points.push_back(this->position[p]);
        mesh.pointOf.push_back(p);
      }
      mesh.connectivity.push_back(this->outId[p]);
    }
    mesh.offsets.push_back(std::int64_t(mesh.connectivity.size()));
    mesh.faceNode.push_back(node);
    mesh.nodeLevel.push_back(level);
    mesh.polygons += node >= 0;
    mesh.triangles += points.size() == 3;
    this->out.labels.push_back(pair);
  }

  /// A net polygon as it is, or as the fan from its first corner.
  void addNetPolygon(std::size_t c, bool triangles)
  {
    const std::vector<std::int32_t> corners(this->net.corners.begin() + this->net.offsets[c],
      this->net.corners.begin() + this->net.offsets[c + 1]);
    if (!triangles || corners.size() == 3)
      return this->addCell(corners, this->net.labels[c], -1, -1);
    for (std::size_t i = 1; i + 1 < corners.size(); ++i)
      this->addCell({ corners[0], corners[i], corners[i + 1] }, this->net.labels[c], -1, -1);
  }

  void addPair(const std::vector<std::size_t>& quads,
    const FaceOctreeOptions& options,
    BoundaryCells cells,
    const Execution& exec,
    std::vector<std::int32_t>& localOf);
};

/// One pair's face octree and boundary: its nodes' points take their projections, its
/// cells and nodes are appended (nodes moved back to voxel units).
void LabelAssembler::addPair(const std::vector<std::size_t>& quads,
  const FaceOctreeOptions& options,
  BoundaryCells cells,
  const Execution& exec,
  std::vector<std::int32_t>& localOf)
{
  const PairModel pm = pairModel(this->net, quads, localOf);
  // One pair of many: its own progress fractions would make the job's go back and forth.
  const FaceOctree octree = buildFaceOctreeAvoiding(pm.far, pm.model, options, exec.silent());
  const Vec3 t = pm.shift();
  for (std::size_t p = 0; p < pm.global.size(); ++p)
    if (octree.nodeOf[p] >= 0)
      for (int d = 0; d < 3; ++d)
        this->position[pm.global[p]][d] = octree.projected[p][d] - t[d];
  const LabelPair pair = this->net.labels[quads.front()];
  const std::int32_t base = std::int32_t(this->out.nodes.size());
  for (FaceNode node : octree.nodes)
  {
    node.offset -= node.normal[0] * t[0] + node.normal[1] * t[1] + node.normal[2] * t[2];
    std::array<Vec3, 2> box;
    for (int d = 0; d < 3; ++d)
    {
      box[0][d] = node.lo[d] + pm.lo[d] - 0.5;
      box[1][d] = node.hi[d] + pm.lo[d] - 0.5;
      node.lo[d] += pm.lo[d];
      node.hi[d] += pm.lo[d];
    }
    for (std::int32_t& p : node.polygon)
      p = pm.global[p];
    this->out.nodes.push_back(std::move(node));
    this->out.nodePair.push_back(pair);
    this->out.nodeBox.push_back(box);
  }
  const BoundaryMesh mesh = assembleBoundary(pm.model, octree, cells);
  std::vector<std::int32_t> points;
  for (std::size_t c = 0; c < mesh.cellCount(); ++c)
  {
    points.clear();
    for (std::int64_t i = mesh.offsets[c]; i < mesh.offsets[c + 1]; ++i)
      points.push_back(pm.global[mesh.pointOf[mesh.connectivity[i]]]);
    this->addCell(
      points, pair, mesh.faceNode[c] < 0 ? -1 : base + mesh.faceNode[c], mesh.nodeLevel[c]);
  }
}

} // namespace

LabelBoundary assembleLabelBoundary(const LabelNet& net,
  const FaceOctreeOptions& options,
  BoundaryCells cells,
  const Execution& exec)
{
  LabelBoundary out;
  LabelAssembler as{
    net, out, net.model.position, std::vector<std::int32_t>(net.model.pointCount(), -1)
  };
  const bool triangles = cells == BoundaryCells::Triangles;
  std::vector<std::size_t> order(net.polygonCount());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(),
    order.end(),
    [&net](std::size_t a, std::size_t b) { return net.labels[a] < net.labels[b]; });
  std::vector<std::int32_t> localOf(net.model.pointCount(), -1);
  std::vector<std::size_t> quads;
  for (std::size_t i = 0; i < order.size();)
  {
    std::size_t j = i;
    quads.clear();
    for (; j < order.size() && net.labels[order[j]] == net.labels[order[i]]; ++j)
    {
      const std::size_t c = order[j];
      if (cells == BoundaryCells::Quadrilaterals || net.offsets[c + 1] - net.offsets[c] != 4)
        as.addNetPolygon(c, triangles);
      else
        quads.push_back(c);
    }
    if (!quads.empty())
      as.addPair(quads, options, cells, exec, localOf);
    if (exec.stopRequested())
      break;
    i = j;
  }
  return out;
}

double maximumDistanceToLabelFaces(const LabelVolume& volume,
  const std::vector<Vec3>& points,
  const Execution& exec)
{
  return maximumDistanceToFaces(
    points,
    [&volume](std::int32_t i, std::int32_t j, std::int32_t k, int a)
    { return volume.at(i, j, k) != volume.at(i + (a == 0), j + (a == 1), k + (a == 2)); },
    exec);
}

} // namespace vbr
