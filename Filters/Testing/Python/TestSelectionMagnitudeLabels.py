"""The shared selection of every filter, against numpy: Magnitude (ArrayComponent -1, or the
number of components), the type and exactness of the Label arrays (int64 labels 2^53 and
2^53 + 1, which a double cannot tell apart), and the warning before Labels mode on more than
1000 distinct labels.

Expectations are computed with numpy alone: the norms as sqrt of the sum of squares in
float64, the selected voxel counts and the label sets from the input values.
"""

import numpy as np
from vtkmodules.util import numpy_support as ns
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import VTK_STRING
from vtkmodules.vtkCommonDataModel import vtkImageData

import voxelbrep
from voxelbrep_testing import Checker

check = Checker("TestSelectionMagnitudeLabels")
rng = np.random.default_rng(8)


def vector_image(values, name="vectors"):
    """Point scalars from a [z, y, x, component] array."""
    nz, ny, nx, nc = values.shape
    image = vtkImageData()
    image.SetExtent(0, nx - 1, 0, ny - 1, 0, nz - 1)
    array = ns.numpy_to_vtk(np.ascontiguousarray(values).reshape(-1, nc), deep=1)
    array.SetName(name)
    image.GetPointData().SetScalars(array)
    return image


def run(f, image, mode, component, lower=None, upper=None):
    f.SetInputData(image)
    f.SetSelectionMode(mode)
    f.SetArrayComponent(component)
    if lower is not None:
        f.SetLowerThreshold(lower)
        f.SetUpperThreshold(upper)
    f.Update()
    return f


def selected_count(f):
    """Voxels selected, from each filter's own output (not from the selection code)."""
    if isinstance(f, voxelbrep.vtkEVMBoundaryFilter):
        return int(f.GetOutput().GetFieldData().GetArray("NumberOfVoxels").GetValue(0))
    if isinstance(f, voxelbrep.vtkCUDBConnectivity):
        ids = ns.vtk_to_numpy(f.GetOutput().GetPointData().GetArray("RegionId"))
        return int((ids > 0).sum())
    selection = f.GetOutputDataObject(1).GetCellData().GetArray("Selection")
    if selection is None:
        selection = f.GetOutputDataObject(1).GetPointData().GetArray("Selection")
    return int(ns.vtk_to_numpy(selection).sum())


FILTERS = (voxelbrep.vtkEVMBoundaryFilter, voxelbrep.vtkCUDBConnectivity,
           voxelbrep.vtkStandardPlanePolyhedrizer, voxelbrep.vtkConvexHullModifier)


def check_magnitude():
    # Integer vectors: norms exact at Pythagorean triples, so thresholds can sit on them.
    values = rng.integers(-4, 5, size=(6, 7, 8, 3)).astype(np.int16)
    values[2, 3, 4] = (3, 4, 0)   # norm exactly 5
    values[1, 1, 1] = (0, -3, 4)  # norm exactly 5
    norms = np.sqrt((values.astype(np.float64) ** 2).sum(axis=3))
    image = vector_image(values)
    for cls in FILTERS:
        name = cls.__name__
        for component in (-1, 3):
            f = run(cls(), image, cls.RANGE, component, 5.0, 5.0)
            check.equal("%s: Range [5, 5] on the magnitude (component %d)" % (name, component),
                        selected_count(f), int((norms == 5.0).sum()))
            f = run(cls(), image, cls.RANGE, component, 2.5, 6.0)
            check.equal("%s: Range [2.5, 6] on the magnitude (component %d)" % (name, component),
                        selected_count(f), int(((norms >= 2.5) & (norms <= 6.0)).sum()))
        f = run(cls(), image, cls.POSITIVE, cls.MAGNITUDE)
        check.equal(name + ": Positive on the magnitude", selected_count(f),
                    int((norms > 0).sum()))
        f = run(cls(), image, cls.RANGE, 1, 2.0, 4.0)
        check.equal(name + ": a single component still selects on its values",
                    selected_count(f),
                    int(((values[..., 1] >= 2) & (values[..., 1] <= 4)).sum()))
        f = cls()
        f.SetArrayComponent(-5)
        check.equal(name + ": ArrayComponent is clamped at MAGNITUDE", f.GetArrayComponent(), -1)
    # Labels mode on the magnitude: the labels are the distinct norms, as doubles.
    f = run(voxelbrep.vtkEVMBoundaryFilter(), image, 2, -1)
    label = f.GetOutput().GetCellData().GetArray("Label")
    check.equal("EVM: Labels on the magnitude give a double Label", label.GetDataTypeAsString(),
                "double")
    check.equal("EVM: the labels are the distinct non-zero norms",
                sorted(set(ns.vtk_to_numpy(label).tolist())),
                sorted(set(norms[norms != 0].tolist())))


def label_image(dtype, labels):
    """Two touching boxes labelled labels[0] and labels[1] in a background of 0."""
    values = np.zeros((6, 6, 8), dtype=dtype)
    values[1:5, 1:5, 1:4] = labels[0]
    values[1:5, 1:5, 4:7] = labels[1]
    return values


def check_labels(dtype, labels):
    values = label_image(dtype, labels)
    image = vector_image(values[..., np.newaxis], "labels")
    input_type = image.GetPointData().GetScalars().GetDataTypeAsString()
    expected = sorted(int(v) if np.issubdtype(dtype, np.integer) else float(v) for v in labels)
    tag = "%s labels %s" % (np.dtype(dtype).name, labels)

    def label_values(array):
        check.equal(tag + ": Label has the input's type (" + array.GetDataTypeAsString() + ")",
                    array.GetDataTypeAsString(), input_type)
        return sorted(set(ns.vtk_to_numpy(array).tolist()))

    evm = run(voxelbrep.vtkEVMBoundaryFilter(), image, 2, 0)
    check.equal(tag + ": EVM labels", label_values(evm.GetOutput().GetCellData().GetArray("Label")),
                expected)
    cudb = run(voxelbrep.vtkCUDBConnectivity(), image, 2, 0)
    check.equal(tag + ": CUDB boxes' labels",
                label_values(cudb.GetBoxesOutput().GetCellData().GetArray("Label")), expected)
    check.equal(tag + ": CUDB table labels",
                label_values(cudb.GetRegionsOutput().GetColumnByName("Label")), expected)
    poly = run(voxelbrep.vtkStandardPlanePolyhedrizer(), image, 2, 0)
    faces = poly.GetOutput()
    check.equal(tag + ": polyhedrizer labels",
                label_values(faces.GetCellData().GetArray("Label")), expected)
    reversion = voxelbrep.vtkStandardPlaneReversion()
    reversion.SetInputData(faces)
    reversion.Update()
    out = reversion.GetOutput()
    back = out.GetCellData().GetArray("Label") or out.GetPointData().GetArray("Label")
    check.equal(tag + ": reversion labels (background 0 included)", label_values(back),
                sorted(set(expected) | {0}))
    # Voxel by voxel: the reversion's labels are the input's (its cells are the voxels).
    check.equal(tag + ": reversion gives every voxel its exact label",
                ns.vtk_to_numpy(back).tolist(), values.ravel().tolist())
    # Outside Labels mode the label is 1, in the same type.
    evm = run(voxelbrep.vtkEVMBoundaryFilter(), image, 0, 0)
    check.equal(tag + ": Positive labels are 1",
                label_values(evm.GetOutput().GetCellData().GetArray("Label")), [1])


def check_label_count_warning():
    for distinct, warned in ((1000, False), (1001, True)):
        values = np.arange(distinct, dtype=np.float32) + 1.0
        values = np.concatenate([values, np.zeros(1024 - distinct, np.float32)])
        image = vector_image(values.reshape(4, 16, 16, 1), "grey")
        for cls in FILTERS:
            f = cls()
            warnings = []

            @calldata_type(VTK_STRING)
            def on_warning(obj, event, message, sink=warnings):
                sink.append(message)

            f.AddObserver("WarningEvent", on_warning)
            # Range: never warned about labels.
            run(f, image, cls.RANGE, 0, 1.0, 2.0)
            check.equal("%s: no label warning in Range mode" % cls.__name__, len(warnings), 0)
            run(f, image, cls.LABELS, 0)
            check.equal("%s: %d labels warned: %s" % (cls.__name__, distinct, warned),
                        len(warnings) > 0, warned)
            if warned and warnings:
                check.true("%s: the warning names the count and suggests Range: %s"
                           % (cls.__name__, warnings[0]),
                           "1001 distinct labels" in warnings[0] and "Range" in warnings[0])


def check_api_defaults():
    """The VTK classes keep their defaults (the plugin's Range and thresholds from the data
    are XML defaults only)."""
    for cls in FILTERS:
        f = cls()
        check.equal(cls.__name__ + ": default SelectionMode", f.GetSelectionModeAsString(),
                    "Positive")
        check.equal(cls.__name__ + ": default thresholds",
                    (f.GetLowerThreshold(), f.GetUpperThreshold()),
                    (1.0, 1e299))  # VTK_DOUBLE_MAX is 1.0e+299
        check.equal(cls.__name__ + ": default ArrayComponent", f.GetArrayComponent(), 0)


def check_selection_object():
    """One vtkVoxelSelection per filter: setting it directly (GetSelection()) re-executes the
    filter with the new values (its MTime is folded into the filter's), and the filter's own
    setters and the object agree."""
    values = np.arange(4 * 5 * 6, dtype=np.int32).reshape(4, 5, 6)  # [z, y, x]
    image = vector_image(values[..., np.newaxis], "values")
    for cls in FILTERS:
        f = run(cls(), image, cls.RANGE, 0, 10, 200)
        name = cls.__name__
        check.equal(name + ": Range [10, 200]", selected_count(f), int(((values >= 10) & (values <= 200)).sum()))
        before = f.GetMTime()
        f.GetSelection().SetLowerThreshold(50)
        check.true(name + ": the selection's MTime is the filter's", f.GetMTime() > before)
        check.equal(name + ": GetLowerThreshold follows the selection", f.GetLowerThreshold(), 50.0)
        f.Update()
        check.equal(name + ": re-executed with the selection's [50, 200]", selected_count(f),
                    int(((values >= 50) & (values <= 200)).sum()))
        f.SetSelectionModeToLabels()
        check.equal(name + ": the filter's setter reaches the selection",
                    f.GetSelection().GetModeAsString(), "Labels")


check_api_defaults()
check_selection_object()
check_magnitude()
for dtype, labels in ((np.int64, (2 ** 53, 2 ** 53 + 1)), (np.uint8, (7, 200)),
                      (np.float32, (0.5, 2.25)), (np.int64, (-(2 ** 62) - 1, 2 ** 62 + 3))):
    check_labels(dtype, labels)
check_label_count_warning()
check.finish()
