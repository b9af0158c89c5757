"""vtkCUDBConnectivity's output blocks reused from one update to the next: one filter updated
on inputs of changing sizes whose outputs are over 8 MiB (checkerboards and noise, with the
boxes), keeping a shallow copy of every other output (the others are released, their blocks
reused by the following updates). After each update every kept output must be unchanged (a block still in use is never handed out again) and the new output must
equal the one a separate process computes from the same input as its first update (no block
reused there: stale values of an earlier output would differ). Last, in another process whose
address space is then limited to what it has (ulimit -v), an update that needs less than the
kept blocks of the one before must succeed: the memory check gives the kept memory back
instead of refusing the input."""

import resource
import subprocess
import sys

import numpy as np
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkTable, vtkUnstructuredGrid

import voxelbrep

failures = []


def expect(what, ok):
    if not ok:
        print("FAILED:", what)
        failures.append(what)


def mask_of(kind, n):
    """The input of a case: a checkerboard (a region per selected voxel) or noise."""
    if kind == "checkerboard":
        z, y, x = np.indices((n, n, n))
        return ((x + y + z) % 2).astype(np.uint8)
    return (np.random.default_rng(n).random((n, n, n)) < 0.5).astype(np.uint8)


def image_of(mask):
    image = vtkImageData()
    nz, ny, nx = mask.shape
    image.SetDimensions(nx, ny, nz)
    array = ns.numpy_to_vtk(mask.ravel(), deep=1)
    array.SetName("mask")
    image.GetPointData().SetScalars(array)
    return image


def arrays_of(image, boxes, table, copy):
    """Every output array by name (copies with `copy`, else views of the arrays)."""
    take = (lambda a: ns.vtk_to_numpy(a).copy()) if copy else ns.vtk_to_numpy
    out = {}
    for data, prefix in ((image.GetPointData(), "point "), (boxes.GetCellData(), "box ")):
        for i in range(data.GetNumberOfArrays()):
            out[prefix + data.GetArrayName(i)] = take(data.GetArray(i))
    if boxes.GetPoints() is not None:
        out["box points"] = take(boxes.GetPoints().GetData())
        out["box offsets"] = take(boxes.GetCells().GetOffsetsArray())
        out["box connectivity"] = take(boxes.GetCells().GetConnectivityArray())
    for c in range(table.GetNumberOfColumns()):
        out["table " + table.GetColumn(c).GetName()] = take(table.GetColumn(c))
    return out


def update(f, kind, n):
    f.SetInputData(image_of(mask_of(kind, n)))
    f.SetGenerateBoxes(True)
    f.Update()
    return f.GetOutput(), f.GetBoxesOutput(), f.GetRegionsOutput()


def reference(kind, n):
    """The outputs of a first update in a separate process."""
    run = subprocess.run(
        [sys.executable, __file__, "reference", kind, str(n)], capture_output=True, check=True)
    import io

    with np.load(io.BytesIO(run.stdout)) as data:
        return {k: data[k] for k in data.files}


def virtual_size():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmSize"):
                return int(line.split()[1]) * 1024
    return None


def limited():
    """An update on 96^3 noise after one on the 96^3 checkerboard (its outputs kept), the
    address space limited to the process's size in between; prints the outputs' points."""
    f = voxelbrep.vtkCUDBConnectivity()
    update(f, "checkerboard", 96)
    f.SetInputData(image_of(mask_of("noise", 96)))
    size = virtual_size()
    if size is None:
        print(-1)
        return
    resource.setrlimit(resource.RLIMIT_AS, (size, resource.RLIM_INFINITY))
    f.Update()
    print(f.GetBoxesOutput().GetNumberOfPoints())


def same(a, b):
    if sorted(a) != sorted(b):
        return False
    return all(a[k].dtype == b[k].dtype and np.array_equal(a[k], b[k]) for k in a)


def small_outputs_of(f):
    """Every output of a small update but the boxes: RegionIds, the table's columns (values,
    types, names) and the field data of the three ports."""
    out = {}
    data = f.GetOutput().GetPointData()
    out["RegionId"] = ns.vtk_to_numpy(data.GetArray("RegionId")).copy()
    table = f.GetRegionsOutput()
    for c in range(table.GetNumberOfColumns()):
        column = table.GetColumn(c)
        out["column %d %s" % (c, column.GetName())] = ns.vtk_to_numpy(column).copy()
    for port in (0, 1, 2):
        fd = f.GetOutputDataObject(port).GetFieldData()
        for a in range(fd.GetNumberOfArrays()):
            array = fd.GetAbstractArray(a)
            out["port %d field %s" % (port, array.GetName())] = np.array(
                [array.GetValue(i) for i in range(array.GetNumberOfValues())])
    return out


def small_case(index):
    """Small images whose RegionIds, tables and summaries a filter keeps for the next update: masks and
    label maps of three scalar types (the Label column's type follows them), 2D and 3D, of
    changing sizes and region counts, and one of no region."""
    rng = np.random.default_rng(index)
    shape = [(1, 40, 50), (12, 10, 9), (1, 40, 50), (7, 8, 30), (1, 3, 4), (9, 9, 9)][
        (index + 1) // 2 % 6]  # updates 4k + 1 and 4k + 2: the same size
    dtype = [np.uint8, np.int16, np.float32][index // 4 % 3]
    labels = index % 4 == 3
    values = rng.integers(0, 4 if labels else 2, shape) * (index % 7 != 6)
    mask = values.astype(dtype)
    options = {"SetSelectionMode": 2} if labels else {}
    if index % 5 == 2:
        options["SetMinimumRegionSize"] = 2
    return image_of(mask), options


def small_update(f, image, options, connectivity):
    f.SetInputData(image)
    f.SetGenerateBoxes(False)
    f.SetSelectionModeToPositive()
    f.SetMinimumRegionSize(1)
    if connectivity == "vertex":
        f.SetConnectivityToVertex()
    else:
        f.SetConnectivityToFace()
    for setter, value in options.items():
        getattr(f, setter)(value)
    f.Update()


def small_outputs():
    """One filter updated on small images, where it writes the RegionId image, the region
    table's columns and the summary arrays of its last update again when no one else holds
    them: each update's outputs must equal a new filter's, and the arrays of earlier updates
    that a caller still holds, or copies sharing their values, must keep their values."""
    f = voxelbrep.vtkCUDBConnectivity()
    held = []
    for index in range(36):
        image, options = small_case(index)
        connectivity = "vertex" if index % 3 == 2 else "face"
        small_update(f, image, options, connectivity)
        fresh = voxelbrep.vtkCUDBConnectivity()
        small_update(fresh, image, options, connectivity)
        got, want = small_outputs_of(f), small_outputs_of(fresh)
        expect("small update %d equal to a new filter's" % index, same(got, want))
        for what, array, values in held:
            expect("%s kept its values after small update %d" % (what, index),
                np.array_equal(ns.vtk_to_numpy(array), values))
        if index % 4 == 1:  # the next two updates have the same scalar type
            table = f.GetRegionsOutput()
            if table.GetNumberOfColumns() > 0:
                column = table.GetColumn(index % table.GetNumberOfColumns())
                held.append(("column %s of update %d" % (column.GetName(), index), column,
                             ns.vtk_to_numpy(column).copy()))
            ids = f.GetOutput().GetPointData().GetArray("RegionId")
            held.append(("RegionId of update %d" % index, ids, ns.vtk_to_numpy(ids).copy()))
            regions = f.GetOutput().GetFieldData().GetArray("NumberOfRegions")
            held.append(("NumberOfRegions of update %d" % index, regions,
                         ns.vtk_to_numpy(regions).copy()))
        if index % 4 == 3:  # copies sharing the values, not the arrays (vtkMergeArrays does)
            table = f.GetRegionsOutput()
            arrays = [("RegionId", f.GetOutput().GetPointData().GetArray("RegionId")),
                      ("NumberOfRegions", f.GetOutput().GetFieldData().GetArray("NumberOfRegions"))]
            if table.GetNumberOfColumns() > 0:
                arrays.append(("column " + table.GetColumn(0).GetName(), table.GetColumn(0)))
            for name, array in arrays:
                copy = array.NewInstance()
                copy.ShallowCopy(array)
                held.append(("a shallow copy of %s of update %d" % (name, index), copy,
                             ns.vtk_to_numpy(array).copy()))
            del arrays, array, table  # only the copies hold the values now
    return 36


def main():
    small = small_outputs()
    cases = [("checkerboard", 96), ("noise", 64), ("noise", 96), ("noise", 96),
        ("checkerboard", 64), ("checkerboard", 80), ("noise", 96), ("checkerboard", 96),
        ("checkerboard", 96), ("noise", 64)]
    f = voxelbrep.vtkCUDBConnectivity()
    kept = []
    for index, (kind, n) in enumerate(cases):
        image, boxes, table = update(f, kind, n)
        got = arrays_of(image, boxes, table, copy=True)
        big = sum(a.nbytes for a in got.values())
        expect("%s %d: outputs over 8 MiB (%d bytes)" % (kind, n, big), big > 8 << 20)
        expect("%s %d: equal to a first update's" % (kind, n), same(got, reference(kind, n)))
        for name, copies, values in kept:
            expect("%s kept unchanged after %s %d" % (name, kind, n),
                same(arrays_of(*copies, copy=False), values))
        if index % 2 == 0:
            copies = (vtkImageData(), vtkUnstructuredGrid(), vtkTable())
            for copy, output in zip(copies, (image, boxes, table)):
                copy.ShallowCopy(output)
            kept.append(("%s %d" % (kind, n), copies, got))
    run = subprocess.run([sys.executable, __file__, "limited"], capture_output=True, text=True)
    points = int(run.stdout.split()[-1]) if run.stdout.split() else None
    if points != -1:  # -1: no /proc/self/status to limit by
        expect("an update within the kept memory (%s; %s)" % (points, run.stderr[-300:]),
            points == len(reference("noise", 96)["box points"]))
    if failures:
        print(len(failures), "failures")
        return 1
    print("all passed:", len(cases), "updates and", small, "small ones")
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] == "limited":
        limited()
        sys.exit(0)
    if len(sys.argv) == 4 and sys.argv[1] == "reference":
        import io

        g = voxelbrep.vtkCUDBConnectivity()
        buffer = io.BytesIO()
        np.savez(buffer, **arrays_of(*update(g, sys.argv[2], int(sys.argv[3])), copy=True))
        sys.stdout.buffer.write(buffer.getvalue())
        sys.exit(0)
    sys.exit(main())
