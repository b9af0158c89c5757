"""vtkConvexHullModifier against independent numpy/scipy checks: the hull's faces against
scipy's Qhull (facet planes made exact here from integer cross products, merged by plane),
every output point a voxel centre with its VoxelMark, the winding number of every voxel centre
(numpy, van Oosterom-Strackee) inside the triangles only for object centres and outside only
for background ones, the closed oriented surface (every edge twice, opposite directions,
positive volume), and the reversion equal to the selection. Point and cell scalars, origin,
spacing, extent not at 0, a mirroring direction matrix, label maps.
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
