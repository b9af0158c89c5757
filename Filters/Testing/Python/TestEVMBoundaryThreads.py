"""vtkEVMBoundaryFilter with vtkSMPTools threads (STDThread) gives the output of the
sequential backend, value for value: the same points, the same cells in the same order (and
the same 32- or 64-bit storage), the same cell and field data. In 3D the faces are streamed
from the plane sweeps and each chunk's T-junction vertices and cells are made by the thread
that swept it, then appended in order: this is what the test guards. Inputs: a porous volume
(Gaussian-filtered noise, 45 % solid), the same mirrored with anisotropic spacing (cells
reversed), a map of three labels, each with more extreme vertices than the filter's
threshold for threads (2^15, checked), and a checkerboard, whose few extreme vertices (on the
box's border) make faces with a corner at every grid point (over 2^15 of them, which take
the threads), every output mode, both face connectivities. The
face and hole counts of the threaded run are also checked against scipy (independent).
"""

import os
import sys

import numpy as np
from scipy import ndimage
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonCore import vtkSMPTools

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import voxelbrep_testing as vt  # noqa: E402

import voxelbrep  # noqa: E402

check = vt.Checker("TestEVMBoundaryThreads")

MODES = vt.evm_output_modes()
THREADED_WORK_MINIMUM = 1 << 15  # vbr::Execution::ThreadedWorkMinimum


def smooth_noise(n, seed, sigma):
    rng = np.random.default_rng(seed)
    return ndimage.gaussian_filter(rng.standard_normal((n, n, n)), sigma)


def porous(n, seed, solid):
    g = smooth_noise(n, seed, 1.5)
    return (g < np.quantile(g, solid)).astype(np.uint8)


def three_labels(n, seed):
    g = smooth_noise(n, seed, 1.5)
    return np.digitize(g, np.quantile(g, [0.25, 0.5, 0.75])).astype(np.int16)  # 0: background


def run(image, mode, merge, labels):
    f = voxelbrep.vtkEVMBoundaryFilter()
    f.SetInputData(image)
    f.SetOutputMode(MODES[mode])
    f.SetMergeNonManifoldFaces(merge)
    if labels:
        f.SetSelectionModeToLabels()
    f.Update()
    return f.GetOutput()


def arrays(out):
    """Every array of the output by name, as (class, components, numpy values)."""
    found = {"points": out.GetPoints().GetData() if out.GetPoints() else None}
    for kind, cells in (("lines", out.GetLines()), ("polys", out.GetPolys())):
        found[kind + ".offsets"] = cells.GetOffsetsArray()
        found[kind + ".connectivity"] = cells.GetConnectivityArray()
    for kind, data in (("cell", out.GetCellData()), ("field", out.GetFieldData())):
        for i in range(data.GetNumberOfArrays()):
            found[kind + "." + data.GetArrayName(i)] = data.GetAbstractArray(i)
    values = {}
    for name, a in found.items():
        if a is None:
            values[name] = None
        else:
            v = ns.vtk_to_numpy(a) if a.GetNumberOfTuples() else np.zeros(0)
            values[name] = (a.GetClassName(), a.GetNumberOfComponents(), v)
    return values


def same(what, got, expected):
    check.equal(what + ": arrays", sorted(got), sorted(expected))
    for name in expected:
        if name not in got:
            continue
        g, e = got[name], expected[name]
        if g is None or e is None:
            check.true("%s %s: present in both" % (what, name), g is None and e is None)
            continue
        check.equal("%s %s: type" % (what, name), g[:2], e[:2])
        check.true(
            "%s %s: values differ" % (what, name),
            g[2].dtype == e[2].dtype and np.array_equal(g[2], e[2]),
        )


def main():
    if not vtkSMPTools.SetBackend("STDThread"):
        print("no STDThread backend")
        return vt.SKIP_RETURN_CODE
    threads = vtkSMPTools.GetEstimatedNumberOfThreads()
    vtkSMPTools.SetBackend("Sequential")
    if threads < 2:
        # With one thread both runs take the serial path: the comparison would prove nothing.
        print("STDThread has %d thread: nothing to compare" % threads)
        return vt.SKIP_RETURN_CODE
    mask, mirrored, label_map = porous(72, 1, 0.45), porous(64, 2, 0.45), three_labels(72, 3)
    inputs = [
        ("porous", vt.make_image(mask), False, mask, [mask]),
        ("porous mirrored", vt.make_image(mirrored, spacing=(-1.0, 0.5, 2.0)), False, None,
         [mirrored]),
        ("three labels", vt.make_image(label_map), True, None,
         [label_map == k for k in (1, 2, 3)]),
        ("checkerboard", vt.make_image((np.indices((40, 40, 40)).sum(axis=0) % 2).astype(
            np.uint8)), False, None, []),
    ]
    for name, image, labels, reference, objects in inputs:
        # Each object has enough extreme vertices for its sweeps to take the threads.
        for k, o in enumerate(objects):
            evs = vt.extreme_vertices(o)
            check.true("%s object %d: %d extreme vertices, too few for the threads"
                       % (name, k, evs), evs > THREADED_WORK_MINIMUM)
        for mode in MODES:
            for merge in (False, True):
                what = "%s %s merge=%d" % (name, mode, merge)
                vtkSMPTools.SetBackend("Sequential")
                expected = run(image, mode, merge, labels)
                vtkSMPTools.SetBackend("STDThread")
                got = run(image, mode, merge, labels)
                check.true(what + ": cells", got.GetNumberOfCells() > 0)
                same(what, arrays(got), arrays(expected))
                if reference is not None and mode == "Polygons":
                    faces, holes = vt.faces_and_holes_3d(reference, merge)
                    check.equal(what + ": faces", vt.field_value(got, "NumberOfFaces"), faces)
                    check.equal(what + ": holes", vt.field_value(got, "NumberOfHoles"), holes)
    vtkSMPTools.SetBackend("Sequential")
    print("STDThread with %d threads" % threads)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
