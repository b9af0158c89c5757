"""Shared helpers of the VoxelBRep Python tests: numpy <-> VTK conversion and independent
numpy/scipy reference computations (no VoxelBRep code is used to compute expectations).

Arrays are indexed [z, y, x] (numpy order); VTK images are x fastest, so `values.ravel()`
is the VTK point/cell order.
"""

import itertools
import sys

import numpy as np
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonDataModel import vtkImageData

SKIP_RETURN_CODE = 77


class Checker:
    """Collects failed expectations so that one run reports all of them."""

    def __init__(self, name):
        self.name = name
        self.failures = []
        self.count = 0

    def equal(self, what, got, expected):
        self.count += 1
        if got != expected:
            self.failures.append("%s: got %r, expected %r" % (what, got, expected))

    def close(self, what, got, expected, rtol=1e-9, atol=1e-9):
        self.count += 1
        if not np.allclose(got, expected, rtol=rtol, atol=atol):
            self.failures.append("%s: got %r, expected %r" % (what, got, expected))

    def true(self, what, condition):
        self.count += 1
        if not condition:
            self.failures.append(what)

    def finish(self):
        for f in self.failures:
            print("FAILED:", f)
        print("%s: %d checks, %d failed" % (self.name, self.count, len(self.failures)))
        sys.exit(1 if self.failures else 0)


def evm_output_modes():
    """vtkEVMBoundaryFilter's output modes by name, in the order the tests run them."""
    import voxelbrep

    f = voxelbrep.vtkEVMBoundaryFilter
    return {"Polygons": f.POLYGONS, "Triangles": f.TRIANGLES, "Polylines": f.POLYLINES,
            "Surfels": f.SURFELS, "Loops": f.LOOPS}


def make_image(values, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), index_min=(0, 0, 0),
               cell_data=False, name="scalars", direction=None):
    """A vtkImageData whose point (or cell) scalars are `values` ([z, y, x] array)."""
    if values.ndim == 2:
        values = values[np.newaxis]
    nz, ny, nx = values.shape
    extra = 1 if cell_data else 0
    i0, j0, k0 = index_min
    image = vtkImageData()
    image.SetExtent(i0, i0 + nx - 1 + extra, j0, j0 + ny - 1 + extra, k0, k0 + nz - 1 + extra)
    image.SetSpacing(*spacing)
    image.SetOrigin(*origin)
    if direction is not None:
        image.SetDirectionMatrix(*np.asarray(direction, dtype=float).ravel())
    if values.dtype == bool:
        values = values.astype(np.uint8)
    array = ns.numpy_to_vtk(np.ascontiguousarray(values).ravel(), deep=1)
    array.SetName(name)
    attributes = image.GetCellData() if cell_data else image.GetPointData()
    attributes.SetScalars(array)
    return image


def write_partitioned(values, path, pieces, name="values"):
    """`values` ([z, y, x], point data) as a .pvti of `pieces` pieces, all written by this
    process (under MPI too: a dummy controller, not the ranks')."""
    from vtkmodules.vtkIOParallelXML import vtkXMLPImageDataWriter
    from vtkmodules.vtkParallelCore import vtkDummyController
    writer = vtkXMLPImageDataWriter()
    writer.SetInputData(make_image(values, name=name))
    writer.SetFileName(path)
    writer.SetNumberOfPieces(pieces)
    writer.SetController(vtkDummyController())
    writer.SetStartPiece(0)
    writer.SetEndPiece(pieces - 1)
    writer.Write()


def field_value(polydata, name):
    array = polydata.GetFieldData().GetArray(name)
    if array is None:
        raise KeyError("no field data array " + name)
    if array.GetNumberOfComponents() > 1:
        return [int(array.GetComponent(0, c)) for c in range(array.GetNumberOfComponents())]
    return int(array.GetValue(0))


def cell_array(polydata, name):
    array = polydata.GetCellData().GetArray(name)
    if array is None:
        raise KeyError("no cell array " + name)
    return ns.vtk_to_numpy(array)


def points(polydata):
    if polydata.GetPoints() is None:
        return np.zeros((0, 3))
    return ns.vtk_to_numpy(polydata.GetPoints().GetData()).astype(float)


def cells(polydata):
    """Point ids of every cell (verts, lines, polys, strips in VTK's cell order)."""
    out = []
    for ca in (polydata.GetVerts(), polydata.GetLines(), polydata.GetPolys(),
               polydata.GetStrips()):
        if ca is None or ca.GetNumberOfCells() == 0:
            continue
        off = ns.vtk_to_numpy(ca.GetOffsetsArray())
        conn = ns.vtk_to_numpy(ca.GetConnectivityArray())
        out.extend(conn[off[i]:off[i + 1]] for i in range(len(off) - 1))
    return out


def open_loop(ids):
    """A closed polyline repeats its first point at the end: drop it."""
    if len(ids) > 1 and ids[0] == ids[-1]:
        return ids[:-1]
    return ids


def vector_area(p):
    """Newell's vector area of a closed planar loop of points p (n x 3): its length is the
    enclosed area, its direction the right-hand normal."""
    q = np.roll(p, -1, axis=0)
    return 0.5 * np.cross(p, q).sum(axis=0)


def signed_area_2d(p, a=0, b=1):
    """Shoelace area of a loop in the plane of axes a, b (counter-clockwise positive)."""
    x, y = p[:, a], p[:, b]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


# --------------------------------------------------------------------------------------
# Independent references
# --------------------------------------------------------------------------------------
def extreme_vertices(mask):
    """Grid vertices incident to an odd number of set voxels (pixels): XOR of the 2^d
    shifted copies of the zero-padded mask."""
    p = np.pad(mask.astype(bool), 1)
    acc = np.zeros(tuple(s - 1 for s in p.shape), dtype=bool)
    for corner in itertools.product((0, 1), repeat=p.ndim):
        acc ^= p[tuple(slice(c, c + s - 1) for c, s in zip(corner, p.shape))]
    return int(np.count_nonzero(acc))


def surfel_count(mask):
    """Number of boundary voxel (pixel) faces of a mask of any dimension: the 0/1
    transitions of the zero-padded mask along every axis."""
    p = np.pad(mask.astype(np.int8), 1)
    return sum(int(np.count_nonzero(np.diff(p, axis=a))) for a in range(mask.ndim))


def boundary_faces(mask):
    """Number of boundary voxel faces perpendicular to x, y and z ([z, y, x] mask): the
    0/1 transitions of the zero-padded mask along each axis."""
    p = np.pad(mask.astype(np.int8), 1)
    return [int(np.count_nonzero(np.diff(p, axis=ax))) for ax in (2, 1, 0)]


def boundary_area(mask, spacing):
    sx, sy, sz = spacing
    cx, cy, cz = boundary_faces(mask)
    return cx * sy * sz + cy * sx * sz + cz * sx * sy


def components_and_holes_2d(mask, eight_connected):
    """Faces of a 2D mask and their holes. The faces are the connected components of the
    mask: edge- (4-) connected, or vertex- (8-) connected when `eight_connected`. A hole of
    a face F is a bounded connected component of the complement of F as a closed set, that
    is, a 4-connected component of the pixels not in F that does not reach the outside (a
    face touching itself at a vertex encloses a hole there even though the enclosed pixels
    touch the outside diagonally; with 8-connected faces this is the classic 8/4 rule)."""
    from scipy import ndimage

    four = ndimage.generate_binary_structure(2, 1)
    eight = ndimage.generate_binary_structure(2, 2)
    p = np.pad(mask.astype(bool), 1)
    labels, faces = ndimage.label(p, structure=eight if eight_connected else four)
    holes = 0
    if faces == 0:
        return 0, 0
    boxes = ndimage.find_objects(labels)
    for face, box in enumerate(boxes, start=1):
        # The face's bounding box plus a one-pixel frame holds all its holes.
        sl = tuple(slice(max(b.start - 1, 0), b.stop + 1) for b in box)
        sub = labels[sl] == face
        _, n = ndimage.label(~np.pad(sub, 1), structure=four)
        holes += n - 1
    return faces, holes


def faces_and_holes_3d(mask, merge_non_manifold):
    """Faces and holes of the boundary of a 3D mask: in every plane of voxel faces, the
    faces facing +axis and those facing -axis are two 2D masks whose components are the
    faces (edge-connected, or vertex-connected when merged)."""
    p = np.pad(mask.astype(np.int8), 1)
    faces = holes = 0
    for ax in range(3):
        d = np.diff(p, axis=ax)
        for sign in (1, -1):
            m = d == sign
            for index in np.nonzero(m.any(axis=tuple(a for a in range(3) if a != ax)))[0]:
                f, h = components_and_holes_2d(np.take(m, index, axis=ax), merge_non_manifold)
                faces += f
                holes += h
    return faces, holes


def polygon_planarity(pts, cells):
    """The largest distance of a vertex of a polygon (more than three corners) from the plane
    through the polygon's centroid along its Newell normal; 0 without such polygons."""
    worst = 0.0
    for c in cells:
        if len(c) > 3:
            p = pts[c]
            n = sum(np.cross(p[i], p[(i + 1) % len(p)]) for i in range(len(p)))
            n /= np.linalg.norm(n)
            worst = max(worst, float(np.abs((p - p.mean(axis=0)) @ n).max()))
    return worst


def plugin_proxies(xml_path):
    """The proxies of the plugin XML that ParaView makes (not the bases in voxelbrep_bases),
    each as ParaView reads it: the elements of its base proxy (base_proxygroup,
    base_proxyname) first, then its own, an own property replacing the base's of that name."""
    import copy
    import xml.etree.ElementTree as ET

    root = ET.parse(xml_path).getroot()
    groups = {g.get("name"): {p.get("name"): p for p in g} for g in root.iter("ProxyGroup")}
    proxies = []
    for group_name, members in groups.items():
        if group_name == "voxelbrep_bases":
            continue
        for proxy in members.values():
            base_group = proxy.get("base_proxygroup")
            if base_group is None:
                proxies.append(proxy)
                continue
            base = groups[base_group][proxy.get("base_proxyname")]
            merged = copy.deepcopy(base)
            merged.attrib = dict(proxy.attrib)
            own = {p.get("name") for p in proxy if p.get("name")}
            for element in list(merged):
                if element.get("name") in own:
                    merged.remove(element)
            for element in proxy:
                merged.append(copy.deepcopy(element))
            proxies.append(merged)
    return proxies
