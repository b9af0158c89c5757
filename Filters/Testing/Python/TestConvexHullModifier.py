"""vtkConvexHullModifier against independent numpy/scipy checks: the hull's faces against
scipy's Qhull (facet planes made exact here from integer cross products, merged by plane),
every output point a voxel centre with its VoxelMark, the winding number of every voxel centre
(numpy, van Oosterom-Strackee) inside the triangles only for object centres and outside only
for background ones, the closed oriented surface (every edge twice, opposite directions,
positive volume), and the reversion equal to the selection. Point and cell scalars, origin,
spacing, extent not at 0, a mirroring direction matrix, label maps. 2D images (one pixel
thick): polygons with holes in the image plane, checked from their triangles alone (boundary
edges, simple boundaries, every lattice point of the plane inside, outside or on them, the marks
and the reversion). Flat objects in volumes: prisms of genus that of their boundary, their caps
one layer off the object, checked like the volumes' H. The counts of section 4.1 (a hollow
ball's cavity, a pierced cube's tunnel), the three coplanar variants giving one H, and sets of
no volume off the axes' planes (segments, a tilted triangle) as closed solids.
"""

import math

import numpy as np
import voxelbrep
from scipy.spatial import ConvexHull
from voxelbrep_testing import Checker, cells, field_value, make_image, points
from vtkmodules.util import numpy_support as ns

check = Checker("TestConvexHullModifier")


def to_index(world, spacing, origin, index_min, cell_data, direction=None):
    rel = world - np.asarray(origin)
    if direction is not None:
        rel = rel @ np.asarray(direction, dtype=float)  # inverse of a rotation/mirror
    shift = 0.5 if cell_data else 0.0
    index = rel / np.asarray(spacing) - np.asarray(index_min) - shift
    rounded = np.rint(index)
    check.true("points are voxel centres", bool(np.allclose(index, rounded, atol=1e-6)))
    return rounded.astype(np.int64)


def exact_planes(centres, simplices):
    """Qhull's facets as exact integer planes (outward, reduced), merged by plane."""
    planes = set()
    inside = centres.sum(axis=0)  # n times the centroid
    for a, b, c in centres[simplices]:
        n = np.cross(b - a, c - a)
        g = math.gcd(math.gcd(abs(int(n[0])), abs(int(n[1]))), abs(int(n[2])))
        n = n // g
        if int(n @ inside) > int(n @ a) * len(centres):
            n = -n
        planes.add((int(n[0]), int(n[1]), int(n[2]), int(n @ a)))
    return planes


def on_surface(p, tris, q):
    """Whether each query point lies on one of the triangles (exact: integer corners)."""
    on = np.zeros(len(q), bool)
    qi = q.astype(np.int64)
    for t in tris:
        a, b, c = p[t[0]], p[t[1]], p[t[2]]
        n = np.cross(b - a, c - a)
        d = qi - a
        planar = d @ n == 0
        e1 = np.cross(b - a, qi - a) @ n >= 0
        e2 = np.cross(c - b, qi - b) @ n >= 0
        e3 = np.cross(a - c, qi - c) @ n >= 0
        on |= planar & e1 & e2 & e3
    return on


def winding_numbers(p, tris, q):
    """Winding number of the closed triangle surface around every query point."""
    w = np.zeros(len(q))
    for t in tris:
        a, b, c = p[t[0]] - q, p[t[1]] - q, p[t[2]] - q
        la, lb, lc = (np.linalg.norm(v, axis=1) for v in (a, b, c))
        num = np.einsum("ij,ij->i", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc +
               np.einsum("ij,ij->i", b, c) * la + np.einsum("ij,ij->i", c, a) * lb)
        w += 2 * np.arctan2(num, den)
    return w / (4 * np.pi)


def run(image, mode, labels=False):
    f = voxelbrep.vtkConvexHullModifier()
    f.SetInputData(image)
    if labels:
        f.SetSelectionModeToLabels()
    f.SetOutputMode(mode)
    f.Update()
    return f


def check_case(tag, mask, spacing=(1, 1, 1), origin=(0, 0, 0), index_min=(0, 0, 0),
               cell_data=False, direction=None):
    image = make_image(mask.astype(np.uint8), spacing, origin, index_min, cell_data,
                       direction=direction)
    zyx = np.argwhere(mask)
    centres = zyx[:, ::-1].astype(np.int64)
    hull = ConvexHull(centres)
    f = run(image, voxelbrep.vtkConvexHullModifier.CONVEX_HULL)
    out = f.GetOutput()
    planes = exact_planes(centres, hull.simplices)
    check.equal(tag + ": hull faces as Qhull's planes", field_value(out, "NumberOfHullFaces"),
                len(planes))
    check.equal(tag + ": one polygon per hull face", out.GetNumberOfCells(), len(planes))
    idx = to_index(points(out), spacing, origin, index_min, cell_data, direction)
    check.equal(tag + ": hull vertices", len({tuple(v) for v in idx}), len(hull.vertices))
    f = run(image, voxelbrep.vtkConvexHullModifier.TRIANGLES)
    out = f.GetOutput()
    check.equal(tag + ": separates", field_value(out, "Separates"), 1)
    p = to_index(points(out), spacing, origin, index_min, cell_data, direction)
    marks = ns.vtk_to_numpy(out.GetPointData().GetArray("VoxelMark"))
    inside_grid = mask[p[:, 2], p[:, 1], p[:, 0]]
    check.true(tag + ": VoxelMark", bool((marks == inside_grid).all()))
    tris = np.array([c for c in cells(out)])
    check.true(tag + ": triangles", tris.ndim == 2 and tris.shape[1] == 3)
    edges = {}
    for t in tris:
        for k in range(3):
            e = (t[k], t[(k + 1) % 3])
            edges[e] = edges.get(e, 0) + 1
    closed = all(n == 1 and edges.get((e[1], e[0]), 0) == 1 for e, n in edges.items())
    check.true(tag + ": closed oriented surface", closed)
    world = points(out)
    volume = sum(np.dot(world[a], np.cross(world[b], world[c])) for a, b, c in tris) / 6
    check.true(tag + ": outward (positive volume %g)" % volume, volume > 0)
    # Winding numbers of every centre of the grid, in index space.
    nz, ny, nx = mask.shape
    z, y, x = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    q = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1).astype(float)
    w = winding_numbers(p.astype(float), tris, q)
    surface = on_surface(p, tris, q)
    check.true(tag + ": winding numbers 0 or 1 off the surface",
               bool((np.abs(np.abs(w[~surface]) - np.rint(np.abs(w[~surface]))) < 1e-6).all()))
    clear = ~surface
    obj = mask.ravel() != 0
    check.equal(tag + ": object centres outside", int((obj & clear & (np.rint(w) == 0)).sum()), 0)
    check.equal(tag + ": background centres inside",
                int((~obj & clear & (np.rint(w) != 0)).sum()), 0)
    rev = f.GetOutputDataObject(1)
    attrs = rev.GetCellData() if cell_data else rev.GetPointData()
    back = ns.vtk_to_numpy(attrs.GetArray("Selection")).reshape(mask.shape)
    check.true(tag + ": reversion equals the selection", bool((back == (mask != 0)).all()))
    check.equal(tag + ": ReversionMatches", int(rev.GetFieldData().GetArray(
        "ReversionMatches").GetValue(0)), 1)
    return out


def image_2d(mask, flat, spacing, origin, index_min):
    """A point-data image one pixel thick along `flat` holding `mask` ([v, u]) in its plane."""
    u, v = (flat + 1) % 3, (flat + 2) % 3
    shape3 = [1, 1, 1]
    shape3[u], shape3[v] = mask.shape[1], mask.shape[0]
    values = np.zeros(shape3[::-1], np.uint8)  # [z, y, x]
    for (j, i) in np.argwhere(mask):
        idx = [0, 0, 0]
        idx[u], idx[v] = i, j
        values[idx[2], idx[1], idx[0]] = 1
    return values, make_image(values, spacing, origin, index_min)


def plane_points(tag, out, flat, spacing, origin, index_min):
    """Output points as lattice points (u, v) of the plane, checked to be pixel centres on it."""
    u, v = (flat + 1) % 3, (flat + 2) % 3
    rel = (points(out) - np.asarray(origin, float)) / np.asarray(spacing, float)
    index = rel - np.asarray(index_min)
    check.true(tag + ": in the image plane", bool(np.allclose(index[:, flat], 0.0, atol=1e-9)))
    check.true(tag + ": corners are pixel centres",
               bool(np.allclose(index, np.rint(index), atol=1e-6)))
    return np.rint(index).astype(np.int64)[:, [u, v]]


def boundary_edges(tag, tris, n):
    """The edges of one triangle only; every corner on them has exactly two (no pinch)."""
    edges = {}
    for t in tris:
        for k in range(3):
            e = tuple(sorted((int(t[k]), int(t[(k + 1) % 3]))))
            edges[e] = edges.get(e, 0) + 1
    boundary = [e for e, count in edges.items() if count == 1]
    check.true(tag + ": no edge in three triangles", all(c <= 2 for c in edges.values()))
    degree = np.bincount(np.array(boundary, dtype=np.int64).ravel(), minlength=n)
    check.true(tag + ": simple boundaries (two boundary edges per corner)",
               bool(((degree == 0) | (degree == 2)).all()))
    return boundary


def classify_plane(q, tris, boundary, g):
    """Exact integer tests of lattice points g: on a boundary edge, and in a closed triangle."""
    on = np.zeros(len(g), bool)
    for e0, e1 in boundary:
        p0, p1 = q[e0], q[e1]
        cr = (p1[0] - p0[0]) * (g[:, 1] - p0[1]) - (p1[1] - p0[1]) * (g[:, 0] - p0[0])
        within = ((np.minimum(p0, p1) <= g) & (g <= np.maximum(p0, p1))).all(axis=1)
        on |= (cr == 0) & within
    covered = np.zeros(len(g), bool)
    for t in tris:
        side = []
        for k in range(3):
            a, b = q[t[k]], q[t[(k + 1) % 3]]
            side.append((b[0] - a[0]) * (g[:, 1] - a[1]) - (b[1] - a[1]) * (g[:, 0] - a[0]) >= 0)
        covered |= side[0] & side[1] & side[2]
    return on, covered


def check_2d(tag, mask, flat=2, spacing=(1, 1, 1), origin=(0, 0, 0), index_min=(0, 0, 0)):
    """A 2D image (one pixel thick along `flat`; `mask` is [v, u] over its plane axes u, v with
    (u, v, flat) right-handed): polygons with holes in the image plane, checked here from the
    triangles alone against every pixel centre and a margin of two."""
    values, image = image_2d(mask, flat, spacing, origin, index_min)
    f = run(image, voxelbrep.vtkConvexHullModifier.TRIANGLES)
    out = f.GetOutput()
    check.equal(tag + ": separates", field_value(out, "Separates"), 1)
    q = plane_points(tag, out, flat, spacing, origin, index_min)
    tris = np.array([c for c in cells(out)], dtype=np.int64).reshape(-1, 3)
    a, b, c = q[tris[:, 0]], q[tris[:, 1]], q[tris[:, 2]]
    twice = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    check.true(tag + ": triangles counter-clockwise, none flat", bool((twice > 0).all()))
    boundary = boundary_edges(tag, tris, len(q))
    ny, nx = mask.shape
    in_box = (q[:, 0] >= 0) & (q[:, 1] >= 0) & (q[:, 0] < nx) & (q[:, 1] < ny)
    expected = np.zeros(len(q), bool)
    expected[in_box] = mask[q[in_box, 1], q[in_box, 0]]
    marks = ns.vtk_to_numpy(out.GetPointData().GetArray("VoxelMark"))
    check.true(tag + ": VoxelMark", bool((marks == expected).all()))
    on_surface = ns.vtk_to_numpy(out.GetFieldData().GetArray("BackgroundCentresOnSurface"))
    u, v = (flat + 1) % 3, (flat + 2) % 3
    listed = {(int(p[u]), int(p[v])) for p in on_surface.reshape(-1, 3)}  # grid indices
    gy, gx = np.mgrid[-2:ny + 2, -2:nx + 2]
    g = np.stack([gx.ravel(), gy.ravel()], axis=1)
    on, covered = classify_plane(q, tris, boundary, g)
    in_grid = (g[:, 0] >= 0) & (g[:, 1] >= 0) & (g[:, 0] < nx) & (g[:, 1] < ny)
    obj = np.zeros(len(g), bool)
    obj[in_grid] = mask[g[in_grid, 1], g[in_grid, 0]]
    check.equal(tag + ": object centres outside", int((obj & ~covered).sum()), 0)
    check.equal(tag + ": background centres inside", int((~obj & covered & ~on).sum()), 0)
    marked = np.array([(int(x), int(y)) in listed for x, y in g])
    check.true(tag + ": background marks exactly on the boundary",
               bool((marked == (on & in_grid & ~obj)).all()))
    rebuilt = in_grid & ((covered & ~on) | (on & ~marked))
    check.true(tag + ": reversion from the triangles and marks", bool((rebuilt == obj).all()))
    back = ns.vtk_to_numpy(f.GetOutputDataObject(1).GetPointData().GetArray("Selection"))
    check.true(tag + ": reversion port equals the selection",
               bool((back.reshape(values.shape) == values).all()))
    return check_2d_modes(tag, image, flat, spacing, origin, index_min, float(twice.sum()))


def check_2d_modes(tag, image, flat, spacing, origin, index_min, area):
    """Polyhedron: a polygon per face without holes, triangles for the others, the same area
    as the triangles (twice the area, shoelace); ConvexHull: one polygon."""
    poly = run(image, voxelbrep.vtkConvexHullModifier.POLYHEDRON).GetOutput()
    check.equal(tag + ": polyhedron separates", field_value(poly, "Separates"), 1)
    pq = plane_points(tag + " polyhedron", poly, flat, spacing, origin, index_min)
    shoelace = sum(float(np.dot(pq[c, 0], np.roll(pq[c, 1], -1)) -
                         np.dot(pq[c, 1], np.roll(pq[c, 0], -1))) for c in cells(poly))
    check.equal(tag + ": polyhedron covers the same area", shoelace, area)
    face_ids = ns.vtk_to_numpy(poly.GetCellData().GetArray("FaceId"))
    check.equal(tag + ": faces", field_value(poly, "NumberOfFaces"), len(set(face_ids.tolist())))
    hull = run(image, voxelbrep.vtkConvexHullModifier.CONVEX_HULL).GetOutput()
    check.equal(tag + ": one convex polygon", hull.GetNumberOfCells(), 1)
    return poly

def check_2d_labels():
    """Labels on a 2D image: each label its own polygons; a one-pixel label's triangle has
    corners outside the label's box but inside the image, background centres of that label
    that BackgroundCentresOnSurface must list (grid indices)."""
    labels = np.zeros((1, 5, 9), np.uint8)
    labels[0, 2, 2] = 3
    labels[0, 0:4, 5:9] = 7
    labels[0, 1, 6] = 0
    f = run(make_image(labels, spacing=(2, 0.5, 1), origin=(1, 1, 1)),
            voxelbrep.vtkConvexHullModifier.TRIANGLES, labels=True)
    out = f.GetOutput()
    check.equal("2D labels: separates", field_value(out, "Separates"), 1)
    lab = ns.vtk_to_numpy(out.GetCellData().GetArray("Label"))
    check.equal("2D labels: both labels", sorted(set(lab.tolist())), [3, 7])
    q = np.rint((points(out) - 1.0) / np.array([2, 0.5, 1])).astype(np.int64)
    listed = {tuple(int(x) for x in p) for p in ns.vtk_to_numpy(
        out.GetFieldData().GetArray("BackgroundCentresOnSurface")).reshape(-1, 3)}
    corners = {tuple(int(x) for x in q[i]) for c, v in zip(cells(out), lab) if v == 3 for i in c}
    in_image = {p for p in corners if 0 <= p[0] < 9 and 0 <= p[1] < 5}
    check.equal("2D labels: the pixel's triangle", len(corners), 3)
    check.true("2D labels: its background corners in the image listed",
               in_image - {(2, 2, 0)} <= listed and len(in_image) == 3)
    back = ns.vtk_to_numpy(f.GetOutputDataObject(1).GetPointData().GetArray("Selection"))
    check.true("2D labels: reversion", bool((back.reshape(labels.shape) == (labels > 0)).all()))


def check_flat_volume(tag, mask, spacing=(1, 1, 1), origin=(0, 0, 0), index_min=(0, 0, 0)):
    """An object whose centres lie in one layer of a volume: H is the prism of its polygons
    one layer off it on either side (caps beyond the grid when the layer is its first or last).
    Checked from the triangles alone: closed and oriented, the winding number of every centre
    of the grid and a margin of one, the marks (VoxelMark and BackgroundCentresOnSurface, which
    must list the caps' centres in the grid outside the object's box), the Euler characteristic
    twice the closed cubes' (well-composed masks) and the reversion."""
    image = make_image(mask.astype(np.uint8), spacing, origin, index_min)
    f = run(image, voxelbrep.vtkConvexHullModifier.TRIANGLES)
    out = f.GetOutput()
    check.equal(tag + ": separates", field_value(out, "Separates"), 1)
    p = to_index(points(out), spacing, origin, index_min, False)
    tris = np.array([c for c in cells(out)], dtype=np.int64).reshape(-1, 3)
    nz, ny, nx = mask.shape
    in_grid = lambda q: ((q >= 0) & (q < np.array([nx, ny, nz]))).all(axis=1)
    inside = in_grid(p)
    expected = np.zeros(len(p), bool)
    expected[inside] = mask[p[inside, 2], p[inside, 1], p[inside, 0]]
    marks = ns.vtk_to_numpy(out.GetPointData().GetArray("VoxelMark"))
    check.true(tag + ": VoxelMark", bool((marks == expected).all()))
    edges = {}
    for t in tris:
        for k in range(3):
            e = (t[k], t[(k + 1) % 3])
            edges[e] = edges.get(e, 0) + 1
    check.true(tag + ": closed oriented surface",
               all(n == 1 and edges.get((e[1], e[0]), 0) == 1 for e, n in edges.items()))
    check.equal(tag + ": Euler characteristic twice the closed cubes'",
                euler_of_triangles(tris), 2 * closed_cubes_euler(mask))
    z, y, x = np.meshgrid(np.arange(-1, nz + 1), np.arange(-1, ny + 1), np.arange(-1, nx + 1),
                          indexing="ij")
    q = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    w = np.rint(winding_numbers(p.astype(float), tris, q.astype(float)))
    on = on_surface(p, tris, q)
    g = in_grid(q)
    obj = np.zeros(len(q), bool)
    obj[g] = mask[q[g, 2], q[g, 1], q[g, 0]]
    check.equal(tag + ": object centres outside", int((obj & ~on & (w == 0)).sum()), 0)
    check.equal(tag + ": background centres inside", int((~obj & ~on & (w != 0)).sum()), 0)
    listed = {tuple(int(c) for c in r) for r in ns.vtk_to_numpy(
        out.GetFieldData().GetArray("BackgroundCentresOnSurface")).reshape(-1, 3)}
    marked = np.array([tuple(int(c) for c in r) in listed for r in q])
    check.true(tag + ": background centres on H listed exactly",
               bool((marked == (on & g & ~obj)).all()))
    back = ns.vtk_to_numpy(f.GetOutputDataObject(1).GetPointData().GetArray("Selection"))
    check.true(tag + ": reversion equals the selection",
               bool((back.reshape(mask.shape) == (mask != 0)).all()))
    return out


def check_flat_labels():
    """Labels on flat objects in a volume: each label's box is one layer thick, its prism's
    caps lie outside the box but inside the grid, and their centres are background centres of
    that label on H that BackgroundCentresOnSurface must list (grid indices): the list equals
    the union over the labels of their grid centres on their own triangles, not of their
    label."""
    labels = np.zeros((5, 8, 9), np.uint8)
    labels[1, 1:6, 1:6] = 3
    labels[1, 2:5, 2:5] = 0  # a ring
    labels[3, 2:7, 2:4] = 5
    labels[3, 5:7, 2:8] = 5  # an L
    f = run(make_image(labels), voxelbrep.vtkConvexHullModifier.TRIANGLES, labels=True)
    out = f.GetOutput()
    check.equal("flat labels: separates", field_value(out, "Separates"), 1)
    p = to_index(points(out), (1, 1, 1), (0, 0, 0), (0, 0, 0), False)
    lab = ns.vtk_to_numpy(out.GetCellData().GetArray("Label"))
    tris = np.array([c for c in cells(out)], dtype=np.int64).reshape(-1, 3)
    z, y, x = np.meshgrid(*(np.arange(n) for n in labels.shape), indexing="ij")
    q = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    expected = set()
    for value, euler in ((3, 0), (5, 2)):
        own = tris[lab == value]
        check.equal("flat labels: Euler characteristic of label %d" % value,
                    euler_of_triangles(own), euler)
        on = on_surface(p, own, q) & (labels.ravel() != value)
        expected |= {tuple(int(c) for c in r) for r in q[on]}
    listed = {tuple(int(c) for c in r) for r in ns.vtk_to_numpy(
        out.GetFieldData().GetArray("BackgroundCentresOnSurface")).reshape(-1, 3)}
    check.true("flat labels: the caps' background centres listed", listed == expected)
    check.true("flat labels: caps off the labels' layers",
               any(r[2] in (0, 2) for r in expected) and any(r[2] in (2, 4) for r in expected))
    back = ns.vtk_to_numpy(f.GetOutputDataObject(1).GetPointData().GetArray("Selection"))
    check.true("flat labels: reversion", bool((back.reshape(labels.shape) == (labels > 0)).all()))


def closed_cubes_euler(mask):
    """V - E + F - C of the union of the closed voxel cubes: a cell of the cubical complex
    belongs to it when one of the voxels it touches is set (the cells by their doubled
    coordinates, even along an axis where the cell spans no voxel)."""
    m = np.pad(mask.astype(bool), 1)
    chi = 0
    for spans in np.ndindex(2, 2, 2):  # per axis (z, y, x): 1 the cell spans a voxel
        touched = np.zeros(tuple(s - 1 + t for s, t in zip(m.shape, spans)), bool)
        for shift in np.ndindex(*(1 if t else 2 for t in spans)):
            sl = tuple(slice(d, d + n) for d, n in zip(shift, touched.shape))
            touched |= m[sl]
        chi += (-1) ** sum(spans) * int(touched.sum())
    return chi


def euler_of_triangles(tris):
    used = np.unique(tris)
    edges = {tuple(sorted((t[k], t[(k + 1) % 3]))) for t in tris for k in range(3)}
    return len(used) - len(edges) + len(tris)


def shape(n, inside):
    z, y, x = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
    return inside(x.astype(float), y.astype(float), z.astype(float))


def main():
    r = 8
    c = r + 1
    ball = shape(2 * r + 3, lambda x, y, z: (x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 <= r * r)
    check_case("ball", ball)
    mouth = shape(2 * r + 3, lambda x, y, z: (x - c > 0) & (np.abs(y - c) < 0.6 * (x - c)))
    out = check_case("pac-man", ball & ~mouth, spacing=(0.5, 1.0, 2.0), origin=(3, -2, 1),
                     index_min=(2, -1, 4))
    check.true("pac-man: one concavity", field_value(out, "NumberOfConcavities") >= 1)
    check_case("pac-man cells", ball & ~mouth, cell_data=True)
    check_case("pac-man mirrored", ball & ~mouth, direction=[[0, 1, 0], [1, 0, 0], [0, 0, 1]])
    ring = shape(16, lambda x, y, z: ((np.hypot(x - 7.5, y - 7.5) - 5) ** 2 +
                                      (z - 7.5) ** 2) <= 2.2 ** 2)
    out = check_case("torus", ring)
    check.true("torus: a tunnel", field_value(out, "NumberOfTunnels") >= 1)
    # A hollow ball whose 3 wide tunnel reaches the cavity: a ball with a dent (the closed
    # cubes' Euler characteristic 1), H one sphere only after a shell is joined.
    R, cb = 7, 8.0
    d2 = lambda x, y, z: (x - cb) ** 2 + (y - cb) ** 2 + (z - cb) ** 2
    hollow = shape(2 * R + 3, lambda x, y, z: (d2(x, y, z) <= R * R) & (d2(x, y, z) > 3.5 ** 2) &
                   ~((x >= cb) & (np.abs(y - cb) <= 1) & (np.abs(z - cb) <= 1)))
    out = check_case("hollow ball with a tunnel", hollow)
    tris = np.array([c for c in cells(out)])
    check.equal("hollow ball: Euler characteristic twice the closed cubes'",
                euler_of_triangles(tris), 2 * closed_cubes_euler(hollow))
    check.true("hollow ball: NumberOfJoinedShells", field_value(out, "NumberOfJoinedShells") >= 1)
    # A hollow ball (a closed cavity): one cavity, H two shells (the cavity's turned inwards),
    # Euler characteristic 4, twice the closed cubes'.
    plain = shape(2 * R + 3, lambda x, y, z: (d2(x, y, z) <= R * R) & (d2(x, y, z) > 3.5 ** 2))
    out = check_case("hollow ball", plain)
    check.equal("hollow ball: one cavity", field_value(out, "NumberOfCavities"), 1)
    check.equal("hollow ball: two shells", euler_of_triangles(np.array([c for c in cells(out)])),
                2 * closed_cubes_euler(plain))
    check.equal("hollow ball: closed cubes' Euler characteristic", closed_cubes_euler(plain), 2)
    # A cube pierced by one straight tunnel: one tunnel, no cavity, a torus.
    pierced = np.ones((9, 9, 9), bool)
    pierced[0, :, :] = pierced[-1, :, :] = pierced[:, 0, :] = pierced[:, -1, :] = False
    pierced[:, :, 0] = pierced[:, :, -1] = False
    pierced[:, 3:6, 3:6] = False
    out = check_case("pierced cube", pierced)
    check.equal("pierced cube: one tunnel", field_value(out, "NumberOfTunnels"), 1)
    check.equal("pierced cube: no cavity", field_value(out, "NumberOfCavities"), 0)
    check.equal("pierced cube: a torus", euler_of_triangles(np.array([c for c in cells(out)])), 0)
    # The three coplanar variants give the same polyhedron after merging (the pac-man).
    pac = make_image((ball & ~mouth).astype(np.uint8))
    shapes = []
    for variant in ("Extension", "Visible", "Invisible"):
        f = voxelbrep.vtkConvexHullModifier()
        f.SetInputData(pac)
        getattr(f, "SetCoplanarFacesTo" + variant)()
        f.Update()
        out = f.GetOutput()
        shapes.append((tuple(field_value(out, name) for name in (
            "NumberOfVertices", "NumberOfEdges", "NumberOfFaces", "NumberOfHullFaces")),
            sorted(map(tuple, np.rint(points(out)).astype(int).tolist()))))
    check.true("Extension, Visible and Invisible give the same H", shapes[0] == shapes[1] == shapes[2])
    # Segments and flat sets off the axes' planes: a tetrahedron, a pyramid (closed solids).
    # The segments' voxels touch nowhere and lie on the grid's corners: one tetrahedron for all
    # (one shell for several components, the documented exception), so no Euler check there.
    for tag, dims, centres in (("segment (2, 3, 4)", (3, 4, 5), [(0, 0, 0), (2, 3, 4)]),
                               ("segment (2, 3, 4) x 2", (5, 7, 9),
                                [(0, 0, 0), (2, 3, 4), (4, 6, 8)])):
        m = np.zeros(dims[::-1], np.uint8)
        for x, y, z in centres:
            m[z, y, x] = 1
        f = run(make_image(m), voxelbrep.vtkConvexHullModifier.TRIANGLES)
        out = f.GetOutput()
        check.equal(tag + ": separates", field_value(out, "Separates"), 1)
        check.equal(tag + ": four faces", field_value(out, "NumberOfFaces"), 4)
        tris = np.array([c for c in cells(out)])
        world = points(out)
        volume = sum(np.dot(world[a], np.cross(world[b], world[c])) for a, b, c in tris) / 6
        check.true(tag + ": a solid, outwards (volume %g)" % volume, volume > 0)
        check.equal(tag + ": a closed sphere", euler_of_triangles(tris), 2)
        check.equal(tag + ": ReversionMatches", int(f.GetOutputDataObject(1).GetFieldData()
                                                    .GetArray("ReversionMatches").GetValue(0)), 1)
    tilted = np.zeros((4, 4, 4), bool)
    tilted[1, 1, 1] = tilted[1, 2, 2] = tilted[2, 2, 1] = True
    out = check_flat_volume("tilted triangle", tilted)
    check.equal("tilted triangle: a pyramid of four faces", field_value(out, "NumberOfFaces"), 4)
    # A thin torus (a tube two voxels thick): the centres of its hole all lie on its hull's
    # faces, so the hull alone separates; H gets the torus's handle by a cut (Euler
    # characteristic 0, twice the closed cubes').
    thin = shape(16, lambda x, y, z: ((np.hypot(x - 7.5, y - 7.5) - 5) ** 2 +
                                      (z - 7.5) ** 2) <= 1.2 ** 2)
    out = check_case("thin torus", thin)
    check.equal("thin torus: Euler characteristic twice the closed cubes'",
                euler_of_triangles(np.array([c for c in cells(out)])), 2 * closed_cubes_euler(thin))
    check.equal("thin torus: Euler characteristic", 2 * closed_cubes_euler(thin), 0)
    check.true("thin torus: NumberOfCutHandles", field_value(out, "NumberOfCutHandles") >= 1)
    # 2D images: separating polygons with holes in the image plane.
    yy, xx = np.mgrid[0:21, 0:23]
    disc = np.hypot(xx - 11, yy - 10) < 9.5
    holes = (np.hypot(xx - 7, yy - 10) < 2) | (np.hypot(xx - 15, yy - 7) < 2.2) | \
        ((xx == 14) & (yy == 14))
    out = check_2d("2D disc with holes", disc & ~holes, spacing=(0.5, 2.0, 3.0),
                   origin=(3, -2, 1), index_min=(2, -1, 4))
    check.equal("2D disc with holes: three holes", field_value(out, "NumberOfCavities"), 3)
    check_2d("2D ring in the xz plane", (np.hypot(xx - 11, yy - 10) < 9) &
             (np.hypot(xx - 11, yy - 10) > 5), flat=1, spacing=(0.7, 1.0, 1.5),
             origin=(-1, 5, 2), index_min=(-3, 7, 1))
    rng = np.random.default_rng(7)
    for trial in range(6):
        check_2d("2D noise %d" % trial, rng.random((13, 17)) < 0.3 + 0.1 * trial,
                 spacing=(1.5, 0.25, 1.0), origin=(0.5, 0.5, -4), index_min=(1, 2, 3))
    check_2d("2D checkerboard", (xx[:6, :7] + yy[:6, :7]) % 2 == 0)
    check_2d("2D one pixel", np.array([[0, 0, 0], [0, 1, 0]], bool))
    check_2d("2D one row", np.array([[1, 1, 0, 1, 1, 1]], bool), spacing=(2, 3, 4))
    check_2d_labels()
    # Flat objects in volumes: the prism of their polygons, with the genus of their boundary.
    flat = np.zeros((3, 9, 10), bool)
    flat[1, 1:8, 1:8] = True
    flat[1, 3:6, 3:6] = False
    out = check_flat_volume("flat ring in a volume", flat, spacing=(0.5, 2.0, 1.5),
                            origin=(3, -2, 1), index_min=(2, -1, 4))
    check.equal("flat ring: a torus", 2 * closed_cubes_euler(flat), 0)
    plate = np.zeros((6, 4, 11), bool)
    plate[:, 0, :] = True
    plate[1:3, 0, 1:3] = plate[1:3, 0, 5:7] = plate[2:5, 0, 8:10] = False
    check_flat_volume("flat plate with three holes in the first layer", plate)
    thin = np.zeros((3, 5, 5), bool)
    thin[2, 1:4, 1:4] = True
    thin[2, 2, 2] = False
    out = check_flat_volume("thin flat ring in the last layer", thin)
    check.equal("thin flat ring: NumberOfCutHandles", field_value(out, "NumberOfCutHandles"), 1)
    row = np.zeros((4, 5, 6), bool)
    row[3, 2, 1:5] = True
    check_flat_volume("one row in the last layer", row)
    check_flat_labels()
    # Labels: two objects, each its own polyhedron.
    labels = np.zeros((12, 12, 24), np.uint8)
    labels[2:10, 2:10, 2:10] = 3
    labels[2:10, 2:10, 13:22] = 5
    labels[4:8, 4:8, 6:10] = 0  # a pit in the first
    f = run(make_image(labels), voxelbrep.vtkConvexHullModifier.TRIANGLES, labels=True)
    out = f.GetOutput()
    check.equal("labels: separates", field_value(out, "Separates"), 1)
    lab = ns.vtk_to_numpy(out.GetCellData().GetArray("Label"))
    check.equal("labels: both labels", sorted(set(lab.tolist())), [3, 5])
    check.finish()


main()
