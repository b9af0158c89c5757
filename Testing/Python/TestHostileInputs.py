"""The hostile-input corpus: inputs at the limits of what the filters accept (every scalar
type, values and thresholds at the limits of 64-bit integers, NaN and infinity, empty and
degenerate grids, extents near INT_MAX, bad spacing, origin and direction, non-image and
composite inputs, missing arrays, blanking, seeds that miss).

Each case runs in its own subprocess (`TestHostileInputs.py --case NAME`), so that a crash is
one failed case and not a dead suite. Every case writes down what must happen: a valid output
checked against an independent numpy/scipy reference, or the error (or warning) it must
raise, with a text the message must contain. A case passes only when the subprocess exits
normally and the expectation holds.

  TestHostileInputs.py            runs every case (exit 1 when one fails)
  TestHostileInputs.py --list     prints the case names
  TestHostileInputs.py --case N   runs case N in this process
"""

import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "Filters", "Testing", "Python"))

CASES = {}


def case(name):
    def register(function):
        CASES[name] = function
        return function
    return register


# --------------------------------------------------------------------------------------
# Running a filter and listening to its messages
# --------------------------------------------------------------------------------------
class Messages:
    """Errors and warnings of a filter and its executive (observed, so not printed)."""

    def __init__(self, algorithm):
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.vtkConstants import VTK_STRING
        self.errors, self.warnings = [], []

        @calldata_type(VTK_STRING)
        def on_error(obj, event, text):
            self.errors.append(str(text))

        @calldata_type(VTK_STRING)
        def on_warning(obj, event, text):
            self.warnings.append(str(text))

        for target in (algorithm, algorithm.GetExecutive()):
            target.AddObserver("ErrorEvent", on_error)
            target.AddObserver("WarningEvent", on_warning)

    def error_with(self, text):
        return any(text.lower() in e.lower() for e in self.errors)

    def warning_with(self, text):
        return any(text.lower() in w.lower() for w in self.warnings)


def make_filter(kind):
    import voxelbrep
    f = {"evm": voxelbrep.vtkEVMBoundaryFilter, "cudb": voxelbrep.vtkCUDBConnectivity,
         "poly": voxelbrep.vtkStandardPlanePolyhedrizer,
         "hull": voxelbrep.vtkConvexHullModifier}[kind]()
    if kind == "poly":
        f.SetOutputModeToSurfels()  # the surfel count is checked; any mode has it
    return f


def run(kind, data, configure=None):
    """Runs filter `kind` on `data`; returns (filter, Messages)."""
    f = make_filter(kind)
    messages = Messages(f)
    f.SetInputDataObject(0, data)
    if configure:
        configure(f)
    f.Update()
    return f, messages


COUNTS = {"evm": "NumberOfExtremeVertices", "cudb": "NumberOfComponents",
          "poly": "NumberOfSurfels"}


def reverted_count(out, reversion):
    """The indices of the voxels the hull modifier rebuilds from H alone (port 1's Selection,
    on the input's grid), when its own checks passed (Separates and ReversionMatches 1); -1
    when they did not. Compared with the mask's own indices (reference), not with a count."""
    flags = [data.GetFieldData().GetArray(name) for data, name in
             ((out, "Separates"), (reversion, "ReversionMatches"))]
    if any(a is None for a in flags):
        return None
    if any(int(a.GetValue(0)) != 1 for a in flags):
        return -1
    for data in (reversion.GetPointData(), reversion.GetCellData()):
        selection = data.GetArray("Selection")
        if selection is not None:
            from vtkmodules.util import numpy_support as ns
            return tuple(np.flatnonzero(ns.vtk_to_numpy(selection)).tolist()) or 0
    return None


def count_of(kind, out, reversion=None):
    if kind == "hull":
        return reverted_count(out, reversion)
    array = out.GetFieldData().GetArray(COUNTS[kind])
    return None if array is None else int(array.GetValue(0))


def counts(kind, f):
    """What the output says of the selection: extreme vertices, components, surfels, or the
    voxels the hull modifier rebuilds from its polyhedron."""
    return count_of(kind, f.GetOutputDataObject(0), f.GetOutputDataObject(1))


def reference(kind, mask):
    """The same count from the mask alone (numpy / scipy)."""
    from voxelbrep_testing import extreme_vertices, surfel_count
    if kind == "hull":  # the selected voxels' indices, x fastest like the grid's arrays
        return tuple(np.flatnonzero(np.asarray(mask).ravel()).tolist()) or 0
    if kind == "evm":
        return extreme_vertices(mask)
    if kind == "poly":
        return surfel_count(mask)
    from scipy import ndimage
    return int(ndimage.label(mask)[1])


def expect(condition, what):
    if not condition:
        raise AssertionError(what)


def expect_selection(kind, f, messages, mask, what):
    expect(not messages.errors, "%s: unexpected errors %r" % (what, messages.errors))
    got, wanted = counts(kind, f), reference(kind, mask)
    if wanted == 0 and got is None:
        return  # an empty selection may leave the field data out
    expect(got == wanted, "%s: got %r, the reference says %r" % (what, got, wanted))


def image(values, **kwargs):
    from voxelbrep_testing import make_image
    return make_image(values, **kwargs)


def random_values(dtype, seed=1, shape=(6, 7, 8)):
    rng = np.random.default_rng(seed)
    if np.issubdtype(dtype, np.unsignedinteger):
        return rng.integers(0, 3, shape).astype(dtype)
    if np.issubdtype(dtype, np.integer):
        return rng.integers(-2, 3, shape).astype(dtype)
    return (rng.random(shape) * 4 - 2).astype(dtype)


FILTERS = ("evm", "cudb", "poly", "hull")
TYPES = (np.int8, np.uint8, np.int16, np.uint16, np.int32, np.uint32, np.int64, np.uint64,
         np.float32, np.float64)

# --------------------------------------------------------------------------------------
# Valid inputs checked against references
# --------------------------------------------------------------------------------------
for _kind in FILTERS:
    for _dtype in TYPES:
        def _scalar_type(kind=_kind, dtype=_dtype):
            values = random_values(dtype)
            f, m = run(kind, image(values))
            expect_selection(kind, f, m, values > 0, "%s on %s" % (kind, np.dtype(dtype).name))
        case("%s-type-%s" % (_kind, np.dtype(_dtype).name))(_scalar_type)

    def _int64_limits(kind=_kind):
        big = np.iinfo(np.int64).max
        values = np.array([[[big, 2**62, 2**62 - 1, 0, -big - 1, big]]], dtype=np.int64)

        def configure(f):
            f.SetSelectionModeToRange()
            f.SetLowerThreshold(float(2**62))
            f.SetUpperThreshold(float(2**63))
        f, m = run(kind, image(values), configure)
        expect_selection(kind, f, m, values >= 2**62, "int64 in [2^62, 2^63]")
    case("%s-int64-range-limits" % _kind)(_int64_limits)

    def _int64_above(kind=_kind):
        values = np.full((2, 2, 2), np.iinfo(np.int64).max, dtype=np.int64)

        def configure(f):
            f.SetSelectionModeToRange()
            f.SetLowerThreshold(float(2**63))  # above every int64: nothing is selected
        f, m = run(kind, image(values), configure)
        expect_selection(kind, f, m, np.zeros_like(values, bool), "int64 >= 2^63")
    case("%s-int64-threshold-above-type" % _kind)(_int64_above)

    def _uint64_above(kind=_kind):
        values = np.full((2, 2, 2), np.iinfo(np.uint64).max, dtype=np.uint64)

        def configure(f):
            f.SetSelectionModeToRange()
            f.SetLowerThreshold(float(2**64))
        f, m = run(kind, image(values), configure)
        expect_selection(kind, f, m, np.zeros_like(values, bool), "uint64 >= 2^64")
    case("%s-uint64-threshold-above-type" % _kind)(_uint64_above)

    def _nan_values(kind=_kind):
        values = random_values(np.float64, 3)
        values[values < -1] = np.nan
        values[0, 0, 0] = np.inf
        f, m = run(kind, image(values))
        expect_selection(kind, f, m, np.nan_to_num(values, nan=-1) > 0, "NaN and inf values")
    case("%s-nan-and-inf-values" % _kind)(_nan_values)

    def _nan_threshold(kind=_kind):
        values = random_values(np.float64, 4)

        def configure(f):
            f.SetSelectionModeToRange()
            f.SetLowerThreshold(float("nan"))
        f, m = run(kind, image(values), configure)
        expect(m.warning_with("NaN") or m.error_with("NaN"),
               "a NaN threshold must be reported; got %r %r" % (m.errors, m.warnings))
    case("%s-nan-threshold" % _kind)(_nan_threshold)

    def _degenerate(kind=_kind):
        shapes = {"one voxel": np.ones((1, 1, 1)), "full": np.ones((4, 3, 5)),
                  "row": np.ones((1, 1, 9)), "column of holes": np.tile([1, 0], (1, 1, 5)),
                  "plate": np.ones((1, 6, 7)), "empty": np.zeros((3, 3, 3))}
        edge = np.zeros((3, 3, 3)); edge[0, 0, 0] = edge[1, 1, 0] = 1
        corner = np.zeros((3, 3, 3)); corner[0, 0, 0] = corner[1, 1, 1] = 1
        shapes.update({"edge contact": edge, "corner contact": corner})
        for name, values in shapes.items():
            for cell_data in (False, True):
                def configure(f):
                    if kind == "evm":
                        f.SetFlatImagesAs2D(False)  # the references count a slab's voxels
                f, m = run(kind, image(values.astype(np.uint8), cell_data=cell_data),
                           configure)
                expect_selection(kind, f, m, values > 0, "%s (%s)" % (
                    name, "cells" if cell_data else "points"))
    case("%s-degenerate-volumes" % _kind)(_degenerate)

    def _components(kind=_kind):
        values = random_values(np.int16, 5, (5, 6, 7))
        vectors = np.stack([-values, values * 0, values], axis=-1)  # component 2 is values
        img = image(values)
        from vtkmodules.util import numpy_support as ns
        array = ns.numpy_to_vtk(vectors.reshape(-1, 3).copy(), deep=1)
        array.SetName("vectors")
        img.GetPointData().SetScalars(array)
        f, m = run(kind, img, lambda f: f.SetArrayComponent(2))
        expect_selection(kind, f, m, values > 0, "component 2 of 3")
        f, m = run(kind, img, lambda f: f.SetArrayComponent(3))  # 3 of 3: the magnitude
        expect_selection(kind, f, m, values != 0, "the magnitude of 3 components")
        f, m = run(kind, img, lambda f: f.SetArrayComponent(4))
        expect(m.error_with("component"), "component 4 of 3 must be an error: %r" % m.errors)
    case("%s-array-components" % _kind)(_components)

    def _negative_spacing(kind=_kind):
        values = random_values(np.uint8, 6)
        f, m = run(kind, image(values, spacing=(-1.0, 2.0, -0.5)))
        expect_selection(kind, f, m, values > 0, "negative spacing")
    case("%s-negative-spacing" % _kind)(_negative_spacing)

    def _bad_geometry(kind=_kind):
        values = random_values(np.uint8, 7)
        nan = float("nan")
        for what, kwargs in (("spacing", {"spacing": (1.0, nan, 1.0)}),
                             ("spacing", {"spacing": (1.0, float("inf"), 1.0)}),
                             ("origin", {"origin": (nan, 0.0, 0.0)}),
                             ("direction", {"direction": np.zeros((3, 3))})):
            f, m = run(kind, image(values, **kwargs))
            expect(m.error_with(what) or m.warning_with(what),
                   "%s %r must be reported; got %r %r" % (what, kwargs, m.errors, m.warnings))
    case("%s-nan-geometry" % _kind)(_bad_geometry)

    def _zero_spacing(kind=_kind):
        values = random_values(np.uint8, 8)
        f, m = run(kind, image(values, spacing=(1.0, 0.0, 1.0)))
        expect(m.warning_with("spacing") or m.error_with("spacing"),
               "zero spacing must be reported; got %r %r" % (m.errors, m.warnings))
    case("%s-zero-spacing" % _kind)(_zero_spacing)

    def _extent_near_int_max(kind=_kind):
        values = random_values(np.uint8, 9, (3, 3, 4))
        top = 2**31 - 1
        f, m = run(kind, image(values, index_min=(top - 3, 0, 0)))
        if m.errors:
            expect(m.error_with("extent"), "an extent error must say so: %r" % m.errors)
        else:
            expect_selection(kind, f, m, values > 0, "extent ending at INT_MAX")
    case("%s-extent-near-int-max" % _kind)(_extent_near_int_max)

    def _extent_over_int_max(kind=_kind):
        from vtkmodules.vtkCommonDataModel import vtkImageData
        from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
        img = vtkImageData()
        img.SetExtent(-2**30, 2**30, 0, 0, 0, 0)  # 2^31 + 1 points along x
        array = vtkUnsignedCharArray()
        array.SetName("s")
        array.SetNumberOfTuples(1)
        img.GetPointData().SetScalars(array)
        f, m = run(kind, img)
        expect(m.error_with("extent"), "an extent of 2^31 + 1 points must be an error: %r"
               % m.errors)
    case("%s-extent-over-int-max" % _kind)(_extent_over_int_max)

    def _empty_image(kind=_kind):
        from vtkmodules.vtkCommonDataModel import vtkImageData
        f, m = run(kind, vtkImageData())
        expect(not m.errors, "an image without points is no error: %r" % m.errors)
    case("%s-empty-image" % _kind)(_empty_image)

    def _tuples_mismatch(kind=_kind):
        from vtkmodules.vtkCommonDataModel import vtkImageData
        from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
        img = vtkImageData()
        array = vtkUnsignedCharArray()
        array.SetName("s")
        array.SetNumberOfTuples(100)
        array.Fill(1)
        img.GetPointData().SetScalars(array)
        f, m = run(kind, img)
        expect(m.error_with("tuple"), "100 tuples on no point must be an error: %r" % m.errors)
    case("%s-zero-points-100-tuples" % _kind)(_tuples_mismatch)

    def _not_an_image(kind=_kind):
        from vtkmodules.vtkFiltersSources import vtkSphereSource
        sphere = vtkSphereSource()
        sphere.Update()
        f, m = run(kind, sphere.GetOutput())
        expect(m.errors, "a vtkPolyData input must be an error")
    case("%s-polydata-input" % _kind)(_not_an_image)

    def _composite(kind=_kind):
        from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet
        values = random_values(np.uint8, 10)
        blocks = vtkMultiBlockDataSet()
        blocks.SetBlock(0, image(values))
        f, m = run(kind, blocks)
        if m.errors:
            return  # refused with a message
        out = f.GetOutputDataObject(0)
        expect(out.IsA("vtkMultiBlockDataSet") and out.GetNumberOfBlocks() == 1,
               "a composite input gives one output block per input block")
        reversion = f.GetOutputDataObject(1)
        got = count_of(kind, out.GetBlock(0),
                       reversion.GetBlock(0) if reversion is not None and
                       reversion.IsA("vtkMultiBlockDataSet") else None)
        expect(got == reference(kind, values > 0), "the block's result: %r" % (got,))
    case("%s-composite-input" % _kind)(_composite)

    def _missing_array(kind=_kind):
        img = image(random_values(np.uint8, 11))

        def configure(f):
            f.SetInputArrayToProcess(0, 0, 0, 0, "nosucharray")  # 0: point data
        f, m = run(kind, img, configure)
        expect(m.error_with("nosucharray") and m.error_with("point"),
               "the error must name the array and its association: %r" % m.errors)
    case("%s-missing-named-array" % _kind)(_missing_array)

    def _blanking(kind=_kind):
        from vtkmodules.vtkCommonDataModel import vtkUniformGrid
        values = np.ones((4, 4, 4), np.uint8)
        grid = vtkUniformGrid()
        grid.DeepCopy(image(values))
        grid.BlankPoint(1 + 4 * 1 + 16 * 1)  # an inner voxel: a cavity when honoured
        f, m = run(kind, grid)
        if kind == "cudb":
            table = f.GetOutputDataObject(2)
            column = table.GetColumnByName("VoxelCount")
            honoured = column is not None and sum(
                column.GetValue(i) for i in range(table.GetNumberOfRows())) == 63
        else:
            mask = values > 0
            mask[1, 1, 1] = False
            honoured = counts(kind, f) == reference(kind, mask)
        expect((honoured and not m.errors) or m.warning_with("blank"),
               "blanked points must be honoured or reported: %r" % m.warnings)
    case("%s-blanked-points" % _kind)(_blanking)

    def _labels(kind=_kind):
        values = np.zeros((2, 2, 4), np.int64)
        values[:, :, :2] = 2**53
        values[:, :, 2:] = 2**53 + 1
        f, m = run(kind, image(values), lambda f: f.SetSelectionModeToLabels())
        expect(not m.errors, "labels: %r" % m.errors)
        out = f.GetOutputDataObject(0)
        if kind == "cudb":
            table = f.GetOutputDataObject(2)
            column = table.GetColumnByName("Label")
            labels = {int(column.GetValue(i)) for i in range(table.GetNumberOfRows())}
        else:
            array = out.GetCellData().GetArray("Label")
            labels = {int(array.GetValue(i)) for i in range(array.GetNumberOfTuples())}
        expect(labels == {2**53, 2**53 + 1}, "labels 2^53 and 2^53+1 stay apart: %r" % labels)
    case("%s-int64-labels-above-2^53" % _kind)(_labels)


@case("cudb-seeds-that-miss")
def _seeds_miss():
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    points = vtkPoints()
    points.InsertNextPoint(-100, -100, -100)
    seeds = vtkPolyData()
    seeds.SetPoints(points)
    f, m = run("cudb", image(random_values(np.uint8, 12)), lambda f: f.SetSeedData(seeds))
    expect(m.warning_with("seed"), "seeds that all miss must warn: %r" % m.warnings)


# --------------------------------------------------------------------------------------
# The driver
# --------------------------------------------------------------------------------------
def run_in_subprocess(name):
    try:
        p = subprocess.run([sys.executable, os.path.abspath(__file__), "--case", name],
                           capture_output=True, text=True, timeout=300)
    except subprocess.TimeoutExpired:
        return "timed out after 300 s"
    if p.returncode == 0 and "CASE PASSED" in p.stdout:
        return None
    tail = (p.stdout + p.stderr).strip().splitlines()[-6:]
    return "exit code %d: %s" % (p.returncode, " | ".join(tail))


def main(argv):
    if len(argv) > 1 and argv[1] == "--list":
        print("\n".join(CASES))
        return 0
    if len(argv) > 2 and argv[1] == "--case":
        CASES[argv[2]]()
        print("CASE PASSED")
        return 0
    failed = []
    for name in CASES:
        problem = run_in_subprocess(name)
        print("%s %s%s" % ("ok  " if problem is None else "FAIL", name,
                           "" if problem is None else ": " + problem))
        sys.stdout.flush()
        if problem is not None:
            failed.append(name)
    print("%d of %d cases passed" % (len(CASES) - len(failed), len(CASES)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
