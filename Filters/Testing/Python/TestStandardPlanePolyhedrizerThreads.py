"""vtkStandardPlanePolyhedrizer on threads gives the sequential output cell for cell: the
boundary components are grown, their faces' surfels moved, their loops traced and their vertices
counted concurrently, and the reversion is checked beside the cells; the faces must still come
out in the sequential order with the sequential numbers. Inputs of many boundary components
(Gaussian-filtered noise, 50 % noise, a label map of noise; one of 20 labels, whose objects
are made in several batches side by side while the previous batch's cells are written), every
output mode, with and without
MergeFaces: every array of both output ports, with the STDThread backend on 2 threads, equal to
the Sequential backend's; the surfel count against numpy's.
"""

import sys

import numpy as np
from scipy import ndimage
import voxelbrep
from voxelbrep_testing import SKIP_RETURN_CODE, Checker, make_image, surfel_count
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonCore import vtkSMPTools

check = Checker("TestStandardPlanePolyhedrizerThreads")

MODES = ("SURFELS", "STANDARD_FACES", "SEMI_DISCRETE", "STANDARD_EDGES", "TRIANGULATED_FACES")


def attribute_arrays(prefix, data, out):
    for i in range(data.GetNumberOfArrays()):
        a = data.GetAbstractArray(i)
        if a.IsA("vtkDataArray"):
            out[prefix + a.GetName()] = ns.vtk_to_numpy(a).copy()
        else:
            out[prefix + a.GetName()] = [a.GetVariantValue(j).ToString()
                                         for j in range(a.GetNumberOfValues())]


def arrays_of(f):
    """Every array of both ports: points, the cells' offsets and connectivity, attributes."""
    out = {}
    poly = f.GetOutput(0)
    if poly.GetPoints() is not None:
        out["points"] = ns.vtk_to_numpy(poly.GetPoints().GetData()).copy()
    for kind, cells in (("verts", poly.GetVerts()), ("lines", poly.GetLines()),
                        ("polys", poly.GetPolys()), ("strips", poly.GetStrips())):
        out[kind + " offsets"] = ns.vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
        out[kind + " connectivity"] = ns.vtk_to_numpy(
            cells.GetConnectivityArray()).astype(np.int64)
    attribute_arrays("point ", poly.GetPointData(), out)
    attribute_arrays("cell ", poly.GetCellData(), out)
    attribute_arrays("field ", poly.GetFieldData(), out)
    reversion = f.GetOutputDataObject(1)
    attribute_arrays("reversion point ", reversion.GetPointData(), out)
    attribute_arrays("reversion cell ", reversion.GetCellData(), out)
    attribute_arrays("reversion field ", reversion.GetFieldData(), out)
    return out


def run(values, labels, mode, merge, backend):
    check.true("backend " + backend, bool(vtkSMPTools.SetBackend(backend)))
    vtkSMPTools.Initialize(2 if backend == "STDThread" else 1)
    f = voxelbrep.vtkStandardPlanePolyhedrizer()
    f.SetInputData(make_image(values))
    if labels:
        f.SetSelectionModeToLabels()
    f.SetOutputMode(getattr(f, mode))
    f.SetMergeFaces(merge)
    f.Update()
    return arrays_of(f), vtkSMPTools.GetEstimatedNumberOfThreads()


def compare(tag, values, labels):
    binary = values != 0
    for mode in MODES:
        for merge in (False, True):
            case = "%s %s%s" % (tag, mode, " merged" if merge else "")
            one, _ = run(values, labels, mode, merge, "Sequential")
            several, threads = run(values, labels, mode, merge, "STDThread")
            check.equal(case + ": threads", threads, 2)
            if mode == "SURFELS" and not labels:
                check.equal(case + ": surfels", len(one["cell FaceId"]), surfel_count(binary))
            check.equal(case + ": the same arrays", sorted(several), sorted(one))
            for name in one:
                if name in several:
                    same = np.array_equal(np.asarray(one[name]), np.asarray(several[name]))
                    check.true("%s: %s the same on threads" % (case, name), same)


if not vtkSMPTools.SetBackend("STDThread"):
    print("no STDThread backend")
    sys.exit(SKIP_RETURN_CODE)
vtkSMPTools.Initialize(2)
if vtkSMPTools.GetEstimatedNumberOfThreads() < 2:
    # One thread takes the sequential path: the comparison would prove nothing.
    print("STDThread has one thread here: nothing to compare")
    sys.exit(SKIP_RETURN_CODE)

rng = np.random.default_rng(11)
smooth = ndimage.gaussian_filter(rng.standard_normal((40, 40, 40)), 2.0)
porous = (smooth > np.quantile(smooth, 0.55)).astype(np.uint8)
noise = (rng.random((28, 28, 28)) < 0.5).astype(np.uint8)
label_map = (rng.integers(0, 4, size=(24, 24, 24))).astype(np.uint8)
many_labels = (rng.integers(0, 21, size=(20, 20, 20))).astype(np.uint8)

for tag, values in (("porous", porous), ("noise", noise)):
    # Several boundary components (else the growth stays on one thread) and enough surfels
    # for the threaded growth (4,096 or more).
    check.true(tag + ": several components", ndimage.label(values != 0)[1] > 1)
    check.true(tag + ": enough surfels", surfel_count(values != 0) >= 4096)
    compare(tag, values, False)
for k in (1, 2, 3):
    check.true("label %d: enough surfels" % k, surfel_count(label_map == k) >= 4096)
compare("labels", label_map, True)
# More objects than a batch on 2 threads (3 of the 20, objectsPerBatch): the pipeline of
# batches is crossed six times.
check.true("20 labels", len(np.unique(many_labels)) == 21)
compare("20 labels", many_labels, True)

check.finish()
