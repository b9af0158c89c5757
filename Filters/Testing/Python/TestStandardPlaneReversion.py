"""The two reversions of vtkStandardPlanePolyhedrizer's faces against the input voxels as a
user reads them (numpy, layout included), and vtkStandardPlaneReversion on inputs that are
not what it expects.

- One convention: port 1 and vtkStandardPlaneReversion both have the layout of the input
  (extent, origin, spacing, association); faces without the layout fields (older files)
  give cell data on the grid of voxel corners.
- Flat images with cell scalars (a single layer of points) along x, y and z.
- GenerateReversion off after a run with it on leaves no reversion on port 1.
- Duplicated faces, arrays with the wrong number of tuples, NaN or huge dimensions, NaN or
  huge normals: clear errors and no output, never a wrong answer or a crash.
"""

import numpy as np
import voxelbrep
from voxelbrep_testing import Checker, make_image
from vtkmodules.util import numpy_support as ns
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import VTK_STRING, vtkDoubleArray, vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkPolyData

check = Checker("TestStandardPlaneReversion")


class Errors:
    """Collects the error messages of a filter."""

    def __init__(self, algorithm):
        self.messages = []
        algorithm.AddObserver("ErrorEvent", self.on_error)

    @calldata_type(VTK_STRING)
    def on_error(self, caller, event, message):
        self.messages.append(str(message))

    def text(self):
        return " | ".join(self.messages)


def selection_of(image, cell_data):
    attributes = image.GetCellData() if cell_data else image.GetPointData()
    array = attributes.GetArray("Selection")
    return None if array is None else ns.vtk_to_numpy(array)


def polyhedrize(image, **settings):
    f = voxelbrep.vtkStandardPlanePolyhedrizer()
    f.SetInputData(image)
    if settings.get("cell_data"):
        f.SetInputArrayToProcess(0, 0, 0, 1, "scalars")  # cell scalars
    f.Update()
    return f


def companion_of(faces):
    """vtkStandardPlaneReversion from a deep copy of the faces, and its errors."""
    copy = vtkPolyData()
    copy.DeepCopy(faces)
    r = voxelbrep.vtkStandardPlaneReversion()
    errors = Errors(r)
    r.SetInputData(copy)
    r.Update()
    return r.GetOutput(), errors


def check_layout(tag, image, mask, cell_data):
    """Port 1 and the companion: the input's layout and the input's voxels."""
    f = polyhedrize(image, cell_data=cell_data)
    port1 = f.GetOutputDataObject(1)
    expected = (mask != 0).ravel()
    got = selection_of(port1, cell_data)
    check.true(tag + ": port 1 has a Selection", got is not None)
    if got is not None:
        check.equal(tag + ": port 1 selected voxels", int(got.sum()), int(expected.sum()))
        check.true(tag + ": port 1 equals the input voxels", bool((got == expected).all()))
    check.equal(tag + ": ReversionMatches",
                int(port1.GetFieldData().GetArray("ReversionMatches").GetValue(0)), 1)
    back, errors = companion_of(f.GetOutput())
    check.equal(tag + ": companion without errors", errors.text(), "")
    check.equal(tag + ": companion extent", back.GetExtent(), image.GetExtent())
    check.close(tag + ": companion origin", back.GetOrigin(), image.GetOrigin())
    check.close(tag + ": companion spacing", back.GetSpacing(), image.GetSpacing())
    got = selection_of(back, cell_data)
    check.true(tag + ": companion Selection with the input's association", got is not None)
    if got is not None:
        check.true(tag + ": companion equals the input voxels", bool((got == expected).all()))
    return f


def flat_images(rng):
    # Cell scalars on a single layer of points: the extent has one point along `axis`.
    for axis, name in enumerate("xyz"):
        shape = [9, 10, 11]  # z, y, x cells
        shape[2 - axis] = 1
        mask = (rng.random(shape) < 0.5).astype(np.uint8)
        mask.flat[0] = 1
        image = make_image(mask, spacing=(0.5, 2.0, 1.5), origin=(1, -2, 3), index_min=(3, -1, 2),
                           cell_data=True)
        extent = list(image.GetExtent())
        extent[2 * axis + 1] = extent[2 * axis]  # one layer of points along the axis
        image.SetExtent(extent)
        check.equal("flat along %s: one cell per value" % name, image.GetNumberOfCells(),
                    mask.size)
        check_layout("flat along " + name, image, mask, True)


def reversion_off():
    mask = np.zeros((5, 6, 7), np.uint8)
    mask[1:4, 2:5, 1:6] = 1
    f = polyhedrize(make_image(mask))
    check.true("reversion on: a Selection", selection_of(f.GetOutputDataObject(1), False)
               is not None)
    f.GenerateReversionOff()
    f.Update()
    port1 = f.GetOutputDataObject(1)
    check.true("reversion off: no stale Selection", selection_of(port1, False) is None)
    check.equal("reversion off: empty port 1", port1.GetNumberOfPoints(), 0)


def old_faces_without_layout():
    mask = np.zeros((4, 5, 6), np.uint8)
    mask[1:3, 1:4, 2:5] = 1
    image = make_image(mask, origin=(10, 20, 30))
    faces = polyhedrize(image).GetOutput()
    for name in ("VoxelGridExtent", "VoxelGridImageOrigin", "VoxelGridAssociation"):
        faces.GetFieldData().RemoveArray(name)
    back, errors = companion_of(faces)
    check.equal("old faces: no errors", errors.text(), "")
    # The documented default: cell data on the grid of voxel corners.
    check.equal("old faces: extent of the corners", back.GetExtent(), (0, 6, 0, 5, 0, 4))
    check.close("old faces: origin at corner 0", back.GetOrigin(), (9.5, 19.5, 29.5))
    got = selection_of(back, True)
    check.true("old faces: cell Selection", got is not None and bool(
        (got == (mask != 0).ravel()).all()))


def faces_of_a_box():
    mask = np.zeros((4, 5, 6), np.uint8)
    mask[1:3, 1:4, 1:5] = 1
    mask[2, 2, 4] = 0
    return polyhedrize(make_image(mask)).GetOutput()


def expect_error(tag, faces, words):
    back, errors = companion_of(faces)
    text = errors.text()
    check.true(tag + ": an error (got %r)" % text, text != "")
    for w in words:
        check.true(tag + ": the error says %r (got %r)" % (w, text), w in text)
    check.true(tag + ": no Selection", selection_of(back, False) is None and
               selection_of(back, True) is None)


def duplicated_faces():
    faces = vtkPolyData()
    faces.DeepCopy(faces_of_a_box())
    ids = faces.GetCell(0).GetPointIds()
    faces.GetPolys().InsertNextCell(ids)
    cd = faces.GetCellData()
    for i in range(cd.GetNumberOfArrays()):
        a = cd.GetArray(i)
        a.InsertNextTuple(a.GetTuple(0))
    expect_error("duplicated face", faces, ["twice"])


def replace_cell_array(faces, name, values, components):
    array = vtkDoubleArray()
    array.SetName(name)
    array.SetNumberOfComponents(components)
    for v in values:
        array.InsertNextTuple(v)
    faces.GetCellData().RemoveArray(name)
    faces.GetCellData().AddArray(array)


def wrong_lengths():
    for name, components in (("PlaneNormal", 3), ("PlaneOffset", 1), ("Label", 1)):
        faces = vtkPolyData()
        faces.DeepCopy(faces_of_a_box())
        replace_cell_array(faces, name, [(1.0,) * components], components)
        expect_error(name + " with one tuple", faces, [name, "tuples"])


def hostile_values():
    base = faces_of_a_box()
    cells = base.GetNumberOfCells()
    for value in (float("nan"), 1e30, 3e9, -2.0):
        faces = vtkPolyData()
        faces.DeepCopy(base)
        dims = vtkIntArray() if value == -2.0 else vtkDoubleArray()
        dims.SetName("VoxelGridDimensions")
        dims.SetNumberOfComponents(3)
        dims.InsertNextTuple((6, value, 4))
        faces.GetFieldData().RemoveArray("VoxelGridDimensions")
        faces.GetFieldData().AddArray(dims)
        expect_error("dimension %r" % value, faces, ["VoxelGridDimensions"])
    for value in (float("nan"), 1e30, 0.5):
        faces = vtkPolyData()
        faces.DeepCopy(base)
        normals = ns.vtk_to_numpy(base.GetCellData().GetArray("PlaneNormal")).astype(float)
        normals[cells // 2, 1] = value
        replace_cell_array(faces, "PlaneNormal", [tuple(n) for n in normals], 3)
        expect_error("normal %r" % value, faces, ["PlaneNormal", "Face %d" % (cells // 2)])
    for name in ("VoxelGridSpacing", "VoxelGridOrigin"):
        faces = vtkPolyData()
        faces.DeepCopy(base)
        faces.GetFieldData().GetArray(name).SetComponent(0, 1, float("nan"))
        expect_error(name + " NaN", faces, [name])


def every_output_mode_of_faces(rng):
    """The reversion from TriangulatedFaces (the default: loops rebuilt from the triangles
    and their LoopEdges) and from StandardFaces, on random volumes, label maps, mirrored
    grids and porous blobs whose faces run along an edge and back (slits), against the
    mask; without LoopEdges it still works or refuses, never answers wrongly."""
    cases = []
    for seed in range(12):
        shape = tuple(int(v) for v in rng.integers(3, 11, 3))
        mask = (rng.random(shape) < rng.uniform(0.3, 0.7)).astype(np.uint8)
        spacing = (1.0, -1.0, 1.0) if seed % 3 == 0 else (1.0, 1.0, 1.0)
        cases.append(("random %d" % seed, mask, spacing))
    for tag, mask, spacing in cases:
        image = make_image(mask, spacing)
        for mode in ("TriangulatedFaces", "StandardFaces"):
            f = voxelbrep.vtkStandardPlanePolyhedrizer()
            f.SetInputData(image)
            getattr(f, "SetOutputModeTo" + mode)()
            f.Update()
            out, errors = companion_of(f.GetOutput())
            got = selection_of(out, False)
            check.equal("%s, %s: reversion without errors" % (tag, mode), errors.text(), "")
            check.true("%s, %s: the reversion is the mask" % (tag, mode),
                       got is not None and np.array_equal(got, mask.ravel()))
        f.SetOutputModeToTriangulatedFaces()
        f.Update()
        faces = vtkPolyData()
        faces.DeepCopy(f.GetOutput())
        faces.GetCellData().RemoveArray("LoopEdges")
        out, errors = companion_of(faces)
        got = selection_of(out, False)
        check.true("%s without LoopEdges: the mask or an error" % tag,
                   (errors.text() != "" and got is None)
                   or (errors.text() == "" and np.array_equal(got, mask.ravel())))


def main():
    rng = np.random.default_rng(14)
    every_output_mode_of_faces(rng)
    flat_images(rng)
    mask = (rng.random((6, 7, 8)) < 0.5).astype(np.uint8)
    check_layout("point data, shifted", make_image(mask, (1.5, 0.5, 2.0), (-1, 2, 3), (1, 2, -3)),
                 mask, False)
    check_layout("cell data, shifted",
                 make_image(mask, (1.5, 0.5, 2.0), (-1, 2, 3), (1, 2, -3), cell_data=True),
                 mask, True)
    reversion_off()
    old_faces_without_layout()
    duplicated_faces()
    wrong_lengths()
    hostile_values()
    check.finish()


main()
