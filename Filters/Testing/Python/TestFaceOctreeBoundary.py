"""vtkFaceOctreeBoundaryFilter on numpy-built 3D images, against independent numpy / scipy
references:

* NumberOfBoundaryVoxels (object voxels with a background voxel among their 26 neighbours,
  by scipy's binary erosion of the padded mask) and NumberOfPrunedVoxels (boundary voxels
  none of whose 8 corners has its 8 voxels in the object);
* closed and consistently oriented (every directed edge once, its reverse once), every
  polygon planar (distance to its Newell plane);
* every output vertex within one voxel diagonal of the surfels (brute force over the surfel
  centres and corners), enclosed volume positive (outwards) and near the voxel volume, for a
  mirrored direction matrix too (cells reversed), world placement (spacing, origin, extent);
* point and cell scalars, several scalar types, Range and Labels selection, the three output
  modes, the face octree port (one box per FaceNodeId, unit normals);
* Simplify: triangles of no face node, closed and oriented, far fewer than without, within
  SimplificationDistance of the surfels both ways (surface points to the exact nearest
  surfel square; the 5 x 5 lattice of every surfel of an unpruned voxel to the surface by
  VTK's cell locator), the field distances upper bounds of these, a warning in Labels mode.
"""

import os
import sys

import numpy as np
from scipy import ndimage

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import voxelbrep_testing as vt  # noqa: E402

import voxelbrep  # noqa: E402
from vtkmodules.util import numpy_support as ns  # noqa: E402

check = vt.Checker("TestFaceOctreeBoundary")
F = voxelbrep.vtkFaceOctreeBoundaryFilter


def ball(n, r, centre=None, dtype=np.uint8):
    c = (n - 1) / 2.0 if centre is None else centre
    z, y, x = np.mgrid[0:n, 0:n, 0:n]
    return (((x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2) < r * r).astype(dtype)


def pruned_voxels(mask):
    """The object voxels none of whose 8 corners is interior (all 8 voxels about it object)."""
    padded = np.pad(mask.astype(bool), 1)
    vz, vy, vx = padded.shape
    interior = np.zeros((vz + 1, vy + 1, vx + 1), dtype=bool)
    interior[1:-1, 1:-1, 1:-1] = np.logical_and.reduce(
        [padded[dz:vz - 1 + dz, dy:vy - 1 + dy, dx:vx - 1 + dx]
         for dz in (0, 1) for dy in (0, 1) for dx in (0, 1)])
    has_corner = np.logical_or.reduce(
        [interior[dz:vz + dz, dy:vy + dy, dx:vx + dx]
         for dz in (0, 1) for dy in (0, 1) for dx in (0, 1)])
    return (padded & ~has_corner)[1:-1, 1:-1, 1:-1]


def expected_counts(mask):
    padded = np.pad(mask.astype(bool), 1)
    inner = ndimage.binary_erosion(padded, structure=np.ones((3, 3, 3)), border_value=0)
    boundary = (padded & ~inner)[1:-1, 1:-1, 1:-1]
    # A pruned voxel has no interior corner, so it is a boundary voxel (an object voxel with
    # a background voxel among its 26 neighbours) too.
    return int(boundary.sum()), int((boundary & pruned_voxels(mask)).sum())


def run(image, mode=F.POLYGONS, selection=None):
    f = F()
    f.SetInputData(image)
    f.SetOutputMode(mode)
    if selection:
        selection(f)
    f.Update()
    return f


def closed_and_oriented(cells):
    directed = {}
    for c in cells:
        for i in range(len(c)):
            e = (int(c[i]), int(c[(i + 1) % len(c)]))
            directed[e] = directed.get(e, 0) + 1
    return all(n == 1 for n in directed.values()) and all(
        (b, a) in directed for (a, b) in directed)


def volume(pts, cells):
    v = 0.0
    for c in cells:
        a = pts[c[0]]
        for i in range(1, len(c) - 1):
            v += np.dot(a, np.cross(pts[c[i]], pts[c[i + 1]])) / 6.0
    return v


def surfel_samples(mask, spacing, origin, cell_data):
    """Centres, edge midpoints and corners of every surfel, world coordinates."""
    padded = np.pad(mask.astype(bool), 1)
    out = []
    for axis in range(3):
        d = np.diff(padded.astype(np.int8), axis=axis)
        idx = np.argwhere(d != 0)  # face between index i and i + 1 along axis, padded coords
        for du in (0.0, 0.5, 1.0):
            for dv in (0.0, 0.5, 1.0):
                p = idx.astype(float)[:, ::-1]  # x, y, z of the padded voxel
                p -= 1.0  # unpadded
                ax = 2 - axis  # numpy axis 0 is z
                offs = np.zeros(3)
                offs[ax] = 1.0
                others = [a for a in range(3) if a != ax]
                offs[others[0]] = du
                offs[others[1]] = dv
                out.append(p + offs - (0.0 if cell_data else 0.5))
    pts = np.concatenate(out)
    return pts * np.asarray(spacing) + np.asarray(origin)


def max_vertex_distance(vertices, samples):
    from scipy.spatial import cKDTree
    if len(vertices) == 0:
        return 0.0
    d, _ = cKDTree(samples).query(vertices)
    return float(d.max())


def check_surface(name, mask, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0),
                  direction=None, dtype=np.uint8, cell_data=False, mode=F.POLYGONS):
    image = vt.make_image(mask.astype(dtype), spacing=spacing, origin=origin,
                          direction=direction, cell_data=cell_data)
    f = run(image, mode)
    out = f.GetOutput()
    boundary, pruned = expected_counts(mask)
    check.equal(name + " NumberOfBoundaryVoxels", vt.field_value(out, "NumberOfBoundaryVoxels"),
                boundary)
    check.equal(name + " NumberOfPrunedVoxels", vt.field_value(out, "NumberOfPrunedVoxels"),
                pruned)
    pts, cells = vt.points(out), vt.cells(out)
    check.true(name + " has cells", len(cells) > 0)
    check.true(name + " closed and oriented", closed_and_oriented(cells))
    worst = vt.polygon_planarity(pts, cells)
    if mode != F.QUADRILATERALS:  # the relaxed net's quadrilaterals are not planar
        check.true(name + " planar polygons (%g)" % worst, worst < 1e-9 * max(spacing))
    vox = float(mask.sum()) * abs(np.prod(spacing))
    v = volume(pts, cells)
    check.true(name + " outwards (volume %g of %g)" % (v, vox), 0.6 * vox < v < 1.05 * vox)
    if direction is None:
        # Vertices within a voxel diagonal of the surfels (world units, isotropic here).
        d = max_vertex_distance(pts, surfel_samples(mask, spacing, origin, cell_data))
        diag = np.linalg.norm(spacing)
        check.true(name + " vertices within a voxel diagonal (%g)" % d, d <= diag + 1e-9)
        measured = out.GetFieldData().GetArray("MaximumDistance").GetValue(0)
        check.true(name + " MaximumDistance <= sqrt(3) (%g)" % measured, measured <= 3 ** 0.5)
    return f


mask = ball(20, 7.3)
for mode, label in ((F.POLYGONS, "Polygons"), (F.TRIANGLES, "Triangles"),
                    (F.QUADRILATERALS, "Quadrilaterals")):
    f = check_surface("ball " + label, mask, mode=mode)
    out = f.GetOutput()
    if mode == F.TRIANGLES:
        check.true("Triangles only", all(len(c) == 3 for c in vt.cells(out)))
    if mode == F.QUADRILATERALS:
        check.true("Quadrilaterals only", all(len(c) == 4 for c in vt.cells(out)))
    if mode == F.POLYGONS:
        octree = f.GetOutputDataObject(1)
        nodes = vt.field_value(out, "NumberOfFaceNodes")
        check.equal("one box per face node", octree.GetNumberOfCells(), nodes)
        normals = ns.vtk_to_numpy(octree.GetCellData().GetArray("PlaneNormal"))
        check.close("unit plane normals", np.linalg.norm(normals, axis=1), np.ones(nodes))
        ids = vt.cell_array(out, "FaceNodeId")
        check.true("FaceNodeId in range", ids.min() >= -1 and ids.max() < nodes)
        check.equal("NumberOfPolygons", vt.field_value(out, "NumberOfPolygons"),
                    int((ids >= 0).sum()))
        triangles = run(vt.make_image(mask), F.TRIANGLES).GetOutput().GetNumberOfCells()
        check.true("fewer polygons than triangles", len(vt.cells(out)) < triangles)

# World placement, scalar types, cell scalars, a mirrored direction matrix.
check_surface("anisotropic float", mask, spacing=(0.5, 0.5, 0.5), origin=(3.0, -2.0, 1.0),
              dtype=np.float32)
check_surface("cell scalars int16", mask, dtype=np.int16, cell_data=True)
check_surface("mirrored", mask, direction=[[-1, 0, 0], [0, 1, 0], [0, 0, 1]])
box = np.zeros((16, 18, 20), dtype=np.uint8)
box[3:13, 4:14, 5:16] = 1
box[7:10, 6:12, 9:12] = 0  # a cavity
check_surface("box with a cavity", box)

# A one-voxel wall on a block: its voxels are pruned and counted.
wall = np.zeros((16, 16, 16), dtype=np.uint8)
wall[2:7, 2:14, 2:14] = 1
wall[7:13, 8, 2:14] = 1
f = check_surface("wall", wall)
check.true("wall voxels pruned", vt.field_value(f.GetOutput(), "NumberOfPrunedVoxels") >= 6 * 12)

# Range and Labels selection.
labels = np.zeros((20, 20, 20), dtype=np.uint16)
labels[2:9, 2:18, 2:18] = 5
labels[11:18, 2:18, 2:18] = 9
f = run(vt.make_image(labels), F.POLYGONS, lambda f: f.SetSelectionModeToLabels())
got = sorted(set(vt.cell_array(f.GetOutput(), "Label").tolist()))
check.equal("labels", got, [5, 9])
check.true("labels closed", closed_and_oriented(vt.cells(f.GetOutput())))
f = run(vt.make_image(labels), F.POLYGONS, lambda f: (f.SetSelectionModeToRange(),
                                                    f.SetLowerThreshold(6),
                                                    f.SetUpperThreshold(10)))
check.equal("range boundary voxels", vt.field_value(f.GetOutput(), "NumberOfBoundaryVoxels"),
            expected_counts(labels == 9)[0])

# An empty selection and a missing array.
f = run(vt.make_image(np.zeros((5, 5, 5), dtype=np.uint8)))
check.equal("empty selection", f.GetOutput().GetNumberOfCells(), 0)
check.true("PrintSelf", "PruneCrests" in str(F()) and "SimplificationDistance" in str(F()))


# ---- Simplify ----

def surfels_of(mask):
    """Every surfel as (lower corner x, y, z; normal axis 0-2 as x, y, z), voxel i spanning
    [i, i + 1] (point scalars: world = index - 0.5 at unit spacing)."""
    padded = np.pad(mask.astype(bool), 1)
    out = []
    for axis in range(3):
        d = np.diff(padded.astype(np.int8), axis=axis)
        idx = np.argwhere(d != 0).astype(float)[:, ::-1] - 1.0
        ax = 2 - axis
        idx[:, ax] += 1.0
        out.append(np.column_stack([idx, np.full(len(idx), ax)]))
    return np.concatenate(out)


def distance_to_surfels(points, surfels):
    """Exact distance from each point to the nearest surfel square (searched among the
    surfels whose centre is within 3)."""
    from scipy.spatial import cKDTree
    lo = surfels[:, :3]
    hi = lo + 1.0
    axis = surfels[:, 3].astype(int)
    hi[np.arange(len(hi)), axis] = lo[np.arange(len(lo)), axis]
    tree = cKDTree(0.5 * (lo + hi))
    out = np.empty(len(points))
    for i, near in enumerate(tree.query_ball_point(points, 3.0)):
        near = np.asarray(near, dtype=int)
        e = np.maximum(np.maximum(lo[near] - points[i], 0.0), points[i] - hi[near])
        out[i] = np.sqrt((e * e).sum(axis=1)).min() if len(near) else 3.0
    return out


def surface_samples(pts, cells, per_edge=8):
    """Vertices and a barycentric lattice of each triangle."""
    out = [pts]
    for c in cells:
        a, b, d = pts[c[0]], pts[c[1]], pts[c[2]]
        n = max(2, int(np.ceil(per_edge * max(np.linalg.norm(b - a), np.linalg.norm(d - a),
                                                 np.linalg.norm(d - b)))))
        u, v = np.meshgrid(np.arange(n + 1), np.arange(n + 1))
        keep = (u + v) <= n
        u, v = u[keep] / n, v[keep] / n
        out.append(a + np.outer(u, b - a) + np.outer(v, d - a))
    return np.concatenate(out)


def surfel_lattice(mask, surfels):
    """The 5 x 5 lattice of every surfel of an unpruned voxel."""
    pruned = pruned_voxels(mask)
    keep = []
    for s in surfels:
        x, y, z, a = int(s[0]), int(s[1]), int(s[2]), int(s[3])
        inner = [x, y, z]
        outer = [x, y, z]
        outer[a] -= 1  # the voxel before the face along its axis
        voxels = [v for v in (inner, outer)
                  if all(0 <= v[k] < mask.shape[2 - k] for k in range(3))
                  and mask[v[2], v[1], v[0]]]
        if voxels and not pruned[voxels[0][2], voxels[0][1], voxels[0][0]]:
            keep.append(s)
    pts = []
    for s in keep:
        a = int(s[3])
        u, w = [k for k in range(3) if k != a]
        for i in range(5):
            for j in range(5):
                p = s[:3].copy()
                p[u] += i / 4.0
                p[w] += j / 4.0
                pts.append(p)
    return np.asarray(pts)


def distance_from_surfels(samples, polydata):
    from vtkmodules.vtkCommonDataModel import vtkCellLocator, vtkGenericCell
    locator = vtkCellLocator()
    locator.SetDataSet(polydata)
    locator.BuildLocator()
    closest, cell = [0.0, 0.0, 0.0], vtkGenericCell()
    import vtkmodules.vtkCommonCore as cc
    cid, sub, d2 = cc.reference(0), cc.reference(0), cc.reference(0.0)
    worst = 0.0
    for p in samples:
        locator.FindClosestPoint(p, closest, cell, cid, sub, d2)
        worst = max(worst, float(d2) ** 0.5)
    return worst


def check_simplified(name, mask, distance=0.0):
    from vtkmodules.vtkCommonCore import vtkCommand
    f = F()
    warned = []
    f.AddObserver(vtkCommand.WarningEvent, lambda *a: warned.append(a))
    f.SetInputData(vt.make_image(mask))
    f.SimplifyOn()
    f.SetSimplificationDistance(distance)
    f.Update()
    out = f.GetOutput()
    plain = run(vt.make_image(mask), F.TRIANGLES).GetOutput()
    bound = distance if distance > 0 else 3 ** 0.5
    pts, cells = vt.points(out) + 0.5, vt.cells(out)  # voxel i spans [i, i + 1]
    check.true(name + " triangles only", len(cells) > 0 and all(len(c) == 3 for c in cells))
    check.true(name + " FaceNodeId -1", (vt.cell_array(out, "FaceNodeId") == -1).all())
    check.equal(name + " NumberOfTriangles", vt.field_value(out, "NumberOfTriangles"), len(cells))
    check.true(name + " closed and oriented", closed_and_oriented(cells))
    # Outwards, and between the unsimplified surface's volume (it runs through the boundary
    # voxels, well inside a thin torus's voxels) and a little more than the voxels' (the
    # simplification pushes the surface outwards, towards the surfels).
    v, before = volume(pts, cells), volume(vt.points(plain), vt.cells(plain))
    vox = float(mask.sum())
    check.true(name + " outwards (volume %g, unsimplified %g, voxels %g)" % (v, before, vox),
               0.9 * before < v < 1.1 * vox)
    check.true(name + " %d triangles, 5x fewer than %d" % (len(cells), plain.GetNumberOfCells()),
               5 * len(cells) <= plain.GetNumberOfCells())
    surfels = surfels_of(mask)
    there = distance_to_surfels(surface_samples(pts, cells), surfels).max()
    shifted = vtk_shifted(out)
    lattice = surfel_lattice(mask, surfels)
    back = distance_from_surfels(lattice, shifted)
    # Where the unsimplified surface is already farther than the bound, no farther than it
    # plus the half diagonal of the smallest surfel piece (1/8 voxel).
    back_bound = max(bound, distance_from_surfels(lattice, vtk_shifted(plain)) + 0.125 * 0.5 ** 0.5)
    check.true(name + " surface within %g of the surfels (%g)" % (bound, there),
               there <= bound + 1e-9)
    check.true(name + " surfels within %g of the surface (%g)" % (back_bound, back),
               back <= back_bound + 1e-6)
    fd = out.GetFieldData()
    reported = fd.GetArray("MaximumDistance").GetValue(0)
    reported_back = fd.GetArray("MaximumSurfelDistance").GetValue(0)
    check.true(name + " MaximumDistance %g bounds %g" % (reported, there),
               there <= reported + 1e-9 <= bound + 0.03)
    check.true(name + " MaximumSurfelDistance %g bounds %g" % (reported_back, back),
               back <= reported_back + 1e-6)
    # A warning exactly when the surfels' side is reported beyond the bound.
    check.equal(name + " warned (MaximumSurfelDistance %g, bound %g)" % (reported_back, bound),
                len(warned) == 1, reported_back > bound + 1e-9)
    return reported_back


def vtk_shifted(polydata):
    """The output moved by half a voxel (point scalars: voxel i spans [i, i + 1])."""
    from vtkmodules.vtkCommonTransforms import vtkTransform
    from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
    t = vtkTransform()
    t.Translate(0.5, 0.5, 0.5)
    tf = vtkTransformPolyDataFilter()
    tf.SetTransform(t)
    tf.SetInputData(polydata)
    tf.Update()
    return tf.GetOutput()



# ---- The reach rule (default) against the paper's rule (KeepPointsInVoxels) ----

def check_rule(name, mask, keep_in_voxels):
    """Closed and oriented, and within a voxel diagonal of the surfels both ways (the
    surface's samples to the surfel squares, the surfels' lattice to the surface), measured
    here from the voxels."""
    f = run(vt.make_image(mask), F.POLYGONS, lambda f: f.SetKeepPointsInVoxels(keep_in_voxels))
    out = f.GetOutput()
    pts, cells = vt.points(out) + 0.5, vt.cells(out)  # voxel i spans [i, i + 1]
    check.true(name + " closed and oriented", closed_and_oriented(cells))
    check.true(name + " planar polygons", vt.polygon_planarity(pts, cells) < 1e-9)
    fans = [[c[0], c[i], c[i + 1]] for c in cells for i in range(1, len(c) - 1)]
    surfels = surfels_of(mask)
    there = distance_to_surfels(surface_samples(pts, fans), surfels).max()
    back = distance_from_surfels(surfel_lattice(mask, surfels), vtk_shifted(out))
    check.true(name + " surface within a voxel diagonal of the surfels (%g)" % there,
               there <= 3 ** 0.5 + 1e-9)
    check.true(name + " surfels within a voxel diagonal of the surface (%g)" % back,
               back <= 3 ** 0.5 + 1e-6)
    return out.GetNumberOfCells()


check.true("KeepPointsInVoxels off by default", not F().GetKeepPointsInVoxels())
check.true("PrintSelf KeepPointsInVoxels", "KeepPointsInVoxels" in str(F()))
z, y, x = np.mgrid[0:32, 0:32, 0:32]
torus32 = ((((np.sqrt((x - 15.5) ** 2 + (y - 15.5) ** 2) - 9.0) ** 2 + (z - 15.5) ** 2) < 16.0)
           .astype(np.uint8))
for rule_name, rule_mask in (("ball", ball(32, 12.3)), ("torus", torus32)):
    reach = check_rule(rule_name + " reach rule", rule_mask, False)
    papers = check_rule(rule_name + " paper's rule", rule_mask, True)
    check.true("%s: reach rule %d cells, fewer than the paper's rule %d" % (rule_name, reach,
                                                                           papers),
               reach < papers)

check_simplified("simplified ball", ball(24, 9.3))
z, y, x = np.mgrid[0:24, 0:24, 0:24]
torus = (((np.sqrt((x - 11.5) ** 2 + (y - 11.5) ** 2) - 6.5) ** 2 + (z - 11.5) ** 2) < 9.0)
check_simplified("simplified torus", torus.astype(np.uint8))
check_simplified("simplified wall within 1.5", wall, 1.5)
# Below the unsimplified surface's own surfel distance (about 1.56) the surfels' side cannot
# hold everywhere: reported beyond the bound, with a warning.
check.true("simplified ball within 1.0: surfels farther",
           check_simplified("simplified ball within 1.0", ball(24, 9.3), 1.0) > 1.0)

# Labels mode: not simplified, with a warning.
from vtkmodules.vtkCommonCore import vtkCommand  # noqa: E402
warnings = []
f = F()
f.AddObserver(vtkCommand.WarningEvent, lambda *a: warnings.append(a))
f.SetInputData(vt.make_image(labels))
f.SetSelectionModeToLabels()
f.SimplifyOn()
f.Update()
check.true("Labels mode: a warning", len(warnings) == 1)
check.true("Labels mode: not simplified", (vt.cell_array(f.GetOutput(), "FaceNodeId") >= 0).any())

check.finish()
