"""The small output arrays that vtkEVMBoundaryFilter and vtkCUDBConnectivity take again from
one update to the next (vbr::vtk::ArrayRecycler). One filter of each setting is updated on a
sequence of small inputs (2D and 3D, random masks and label maps, of changing sizes and label
types); after every update its outputs must equal, array for array and value for value, those
of a new filter (which has nothing to recycle) on the same input. Outputs and single arrays
kept by the caller from earlier updates must stay unchanged. The recycling must really happen:
an array nobody holds comes back as the same VTK object at the next update (else these checks
would test nothing), and an array the caller holds never does."""

import sys

import numpy as np
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData, vtkTable, vtkUnstructuredGrid

import voxelbrep
from voxelbrep_testing import make_image

failures = []


def expect(what, ok):
    if not ok:
        print("FAILED:", what)
        failures.append(what)


def inputs():
    """Small inputs of changing shapes, selections and label types."""
    rng = np.random.default_rng(11)
    out = []
    for shape in ((16, 16), (1, 9, 23), (12, 7), (6, 5, 4), (40, 33), (3, 3, 3), (16, 16)):
        out.append(("mask %s" % (shape,), (rng.random(shape) < 0.45).astype(np.uint8)))
    out.append(("zeros", np.zeros((16, 16), np.uint8)))
    out.append(("labels int16", rng.integers(0, 4, (10, 12)).astype(np.int16)))
    out.append(("labels float", rng.integers(0, 3, (5, 6, 7)).astype(np.float32)))
    out.append(("mask again", (rng.random((16, 16)) < 0.45).astype(np.uint8)))
    return out


def field_arrays(fd, prefix, out):
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        if a.IsA("vtkDataArray"):
            out[prefix + a.GetName()] = ns.vtk_to_numpy(a).copy()
        else:
            out[prefix + a.GetName()] = [a.GetValue(j) for j in range(a.GetNumberOfValues())]


def contents(obj):
    """Every array of a data object (copies), its cells, points and active attributes."""
    out = {"class": obj.GetClassName()}
    field_arrays(obj.GetFieldData(), "field ", out)
    if isinstance(obj, vtkTable):
        field_arrays(obj.GetRowData(), "row ", out)
        return out
    for data, prefix in ((obj.GetPointData(), "point "), (obj.GetCellData(), "cell ")):
        field_arrays(data, prefix, out)
        scalars = data.GetScalars()
        out[prefix + "scalars"] = scalars.GetName() if scalars else None
    if isinstance(obj, (vtkPolyData, vtkUnstructuredGrid)) and obj.GetPoints() is not None:
        out["points"] = ns.vtk_to_numpy(obj.GetPoints().GetData()).copy()
    if isinstance(obj, vtkPolyData):
        for kind in ("Verts", "Lines", "Polys", "Strips"):
            cells = getattr(obj, "Get" + kind)()
            out[kind + " offsets"] = ns.vtk_to_numpy(cells.GetOffsetsArray()).copy()
            out[kind + " ids"] = ns.vtk_to_numpy(cells.GetConnectivityArray()).copy()
    if isinstance(obj, vtkUnstructuredGrid) and obj.GetCells() is not None:
        out["cell offsets"] = ns.vtk_to_numpy(obj.GetCells().GetOffsetsArray()).copy()
        out["cell ids"] = ns.vtk_to_numpy(obj.GetCells().GetConnectivityArray()).copy()
    if isinstance(obj, vtkImageData):
        out["extent"] = obj.GetExtent()
    return out


def same(a, b):
    if a.keys() != b.keys():
        return False
    for k in a:
        x, y = a[k], b[k]
        if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
            x, y = np.asarray(x), np.asarray(y)
            if x.dtype != y.dtype or x.shape != y.shape or not np.array_equal(x, y, equal_nan=True):
                return False
        elif x != y:
            return False
    return True


def configure(f, values):
    if values.dtype != np.uint8:
        f.SetSelectionModeToLabels()
    return f


SETTINGS = [
    ("EVM Triangles", lambda: voxelbrep.vtkEVMBoundaryFilter(), None),
    ("EVM Polylines", lambda: voxelbrep.vtkEVMBoundaryFilter(), "SetOutputModeToPolylines"),
    ("EVM Polygons", lambda: voxelbrep.vtkEVMBoundaryFilter(), "SetOutputModeToPolygons"),
    ("EVM Loops", lambda: voxelbrep.vtkEVMBoundaryFilter(), "SetOutputModeToLoops"),
    ("EVM Surfels", lambda: voxelbrep.vtkEVMBoundaryFilter(), "SetOutputModeToSurfels"),
    ("CUDB", lambda: voxelbrep.vtkCUDBConnectivity(), None),
    ("CUDB vertex", lambda: voxelbrep.vtkCUDBConnectivity(), "SetConnectivityToVertex"),
    ("CUDB no boxes", lambda: voxelbrep.vtkCUDBConnectivity(), "GenerateBoxesOff"),
]


def new_filter(setting, values):
    name, make, method = setting
    f = make()
    if method:
        getattr(f, method)()
    return configure(f, values)


def outputs(f):
    return [f.GetOutputDataObject(p) for p in range(f.GetNumberOfOutputPorts())]


def check_setting(setting):
    name = setting[0]
    cases = inputs()
    f, labels = None, None
    kept_outputs = []  # (what, shallow copy, its contents then)
    kept_arrays = []   # (what, array, its values then)
    for i, (what, values) in enumerate(cases):
        image = make_image(values)
        if f is None or labels != (values.dtype != np.uint8):
            f = new_filter(setting, values)  # a filter per selection mode
            labels = values.dtype != np.uint8
        f.SetInputData(image)
        f.Update()
        fresh = new_filter(setting, values)
        fresh.SetInputData(image)
        fresh.Update()
        for p, (got, want) in enumerate(zip(outputs(f), outputs(fresh))):
            expect("%s, %s, port %d: as a new filter's" % (name, what, p),
                   same(contents(got), contents(want)))
        if i % 3 == 0:  # keep a shallow copy of every output of this update
            for p, out in enumerate(outputs(f)):
                copy = out.NewInstance()
                copy.ShallowCopy(out)
                kept_outputs.append(("%s port %d" % (what, p), copy, contents(out)))
        if i % 3 == 1:  # keep one array of port 0
            cd = f.GetOutputDataObject(0).GetFieldData()
            a = cd.GetArray(0)
            kept_arrays.append((what, a, ns.vtk_to_numpy(a).copy()))
        for kept_what, copy, then in kept_outputs:
            expect("%s: %s kept unchanged" % (name, kept_what), same(contents(copy), then))
        for kept_what, a, then in kept_arrays:
            expect("%s: %s array kept unchanged" % (name, kept_what),
                   np.array_equal(ns.vtk_to_numpy(a), then))


def address(fd, index):
    return fd.GetAbstractArray(index).GetAddressAsString("vtkAbstractArray")


def check_recycled(setting):
    """An array nobody holds is the same object at the next update; one held never is."""
    name = setting[0]
    values = (np.random.default_rng(5).random((16, 16)) < 0.5).astype(np.uint8)
    f = new_filter(setting, values)
    f.SetInputData(make_image(values))
    f.Update()
    fd = f.GetOutputDataObject(0).GetFieldData()
    before = [address(fd, i) for i in range(fd.GetNumberOfArrays())]
    f.Modified()
    f.Update()
    fd = f.GetOutputDataObject(0).GetFieldData()
    after = [address(fd, i) for i in range(fd.GetNumberOfArrays())]
    expect("%s: field arrays recycled (%d of %d)" % (
        name, sum(a == b for a, b in zip(before, after)), len(before)),
        sum(a == b for a, b in zip(before, after)) >= 5)
    held = fd.GetAbstractArray(0)
    held_address = held.GetAddressAsString("vtkAbstractArray")
    f.Modified()
    f.Update()
    fd = f.GetOutputDataObject(0).GetFieldData()
    expect("%s: a held array is not recycled" % name,
           address(fd, 0) != held_address and held.GetName() == fd.GetAbstractArray(0).GetName())


for setting in SETTINGS:
    check_setting(setting)
    check_recycled(setting)

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
print("all passed")
