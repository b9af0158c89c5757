"""vtkFaceOctreeBoundaryFilter on the real volumes of the shared data (MANIFEST.md): the "Al"
object (v == 1), the engine (v >= 130), the headsq bone (v >= 1150, anisotropic spacing) and
two labels of the AAL atlas (37 and 38, the hippocampi, in Labels mode), and two labels of
it that touch (37 and 39, hippocampus and parahippocampal gyrus: one shared surface). Checked against
numpy: the boundary voxel count (26-neighbourhood erosion), closed and consistently oriented
(every directed edge once and its reverse once), planar polygons, positive enclosed volume
near the voxel volume, every vertex within one voxel diagonal of the surfels (index space),
MaximumDistance within it. Exits 77 (skipped) when the data directory is absent.

    python3 TestFaceOctreeBoundaryRealData.py DATA_DIR
"""

import gzip
import os
import sys

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import voxelbrep_testing as vt  # noqa: E402

import voxelbrep  # noqa: E402

check = vt.Checker("TestFaceOctreeBoundaryRealData")
data = sys.argv[1] if len(sys.argv) > 1 else ""
if not os.path.isdir(data):
    print("no shared data: skipped")
    sys.exit(77)


def raw(path, shape, dtype):
    return np.fromfile(os.path.join(data, path), dtype=dtype).reshape(shape)


def nifti(path):
    with gzip.open(os.path.join(data, path), "rb") as f:
        b = f.read()
    dims = np.frombuffer(b, "<i2", 8, 40)
    offset = int(np.frombuffer(b, "<f4", 1, 108)[0])
    nx, ny, nz = (int(d) for d in dims[1:4])
    return np.frombuffer(b, np.uint8, nx * ny * nz, offset).reshape(nz, ny, nx)


def boundary_count(mask):
    padded = np.pad(mask, 1)
    inner = ndimage.binary_erosion(padded, structure=np.ones((3, 3, 3)), border_value=0)
    return int((padded & ~inner).sum())


def closed_and_oriented(cells, npoints):
    a = np.concatenate([c for c in cells]).astype(np.int64)
    b = np.concatenate([np.roll(c, -1) for c in cells]).astype(np.int64)
    key = a * npoints + b
    reverse = b * npoints + a
    unique = np.unique(key)
    return len(unique) == len(key) and bool(np.isin(reverse, unique).all())


def surfel_points(mask):
    padded = np.pad(mask, 1).astype(np.int8)
    pts = []
    for axis in range(3):
        idx = np.argwhere(np.diff(padded, axis=axis) != 0).astype(float)[:, ::-1] - 1.0
        ax = 2 - axis
        others = [d for d in range(3) if d != ax]
        for du in (0.0, 0.5, 1.0):
            for dv in (0.0, 0.5, 1.0):
                p = idx.copy()
                p[:, ax] += 1.0
                p[:, others[0]] += du
                p[:, others[1]] += dv
                pts.append(p - 0.5)
    return np.concatenate(pts)


def check_volume(name, values, select, spacing=(1.0, 1.0, 1.0), mask=None, labels=False):
    image = vt.make_image(values, spacing=spacing)
    f = voxelbrep.vtkFaceOctreeBoundaryFilter()
    f.SetInputData(image)
    select(f)
    f.Update()
    out = f.GetOutput()
    pts, cells = vt.points(out), vt.cells(out)
    check.true(name + ": cells", len(cells) > 0)
    if not labels:
        check.equal(name + ": NumberOfBoundaryVoxels",
                    vt.field_value(out, "NumberOfBoundaryVoxels"), boundary_count(mask))
    check.true(name + ": closed and oriented", closed_and_oriented(cells, len(pts)))
    worst = vt.polygon_planarity(pts, cells)
    check.true(name + ": planar polygons (%g)" % worst, worst < 1e-9 * max(spacing))
    index = pts / np.asarray(spacing)
    d, _ = cKDTree(surfel_points(mask)).query(index)
    check.true(name + ": vertices within a voxel diagonal (%g)" % d.max(), d.max() <= 3 ** 0.5)
    measured = out.GetFieldData().GetArray("MaximumDistance").GetValue(0)
    check.true(name + ": MaximumDistance (%g)" % measured, measured <= 3 ** 0.5)
    print("%s: %d boundary voxels, %d face nodes, %d cells, %d pruned, distance %.3f" % (
        name, vt.field_value(out, "NumberOfBoundaryVoxels"),
        vt.field_value(out, "NumberOfFaceNodes"), len(cells),
        vt.field_value(out, "NumberOfPrunedVoxels"), measured))


def positive(f):
    f.SetSelectionModeToPositive()


def at_least(t):
    def select(f):
        f.SetSelectionModeToRange()
        f.SetLowerThreshold(t)
    return select


al = raw("dgtal_al/dgtal_al_100x100x100_uint8.raw", (100, 100, 100), np.uint8)
check_volume("Al", al, positive, mask=al == 1)
engine = raw("engine/engine_256x256x128_uint8.raw", (128, 256, 256), np.uint8)
check_volume("engine >= 130", engine, at_least(130), mask=engine >= 130)
head = raw("headsq/headsq_quarter_64x64x93_int16le.raw", (93, 64, 64), "<i2")
check_volume("headsq bone", head, at_least(1150), spacing=(3.2, 3.2, 1.5), mask=head >= 1150)
aal = nifti("mricron/aal.nii.gz")
two = np.where((aal == 37) | (aal == 38), aal, 0).astype(np.uint8)


def labels(f):
    f.SetSelectionModeToLabels()


check_volume("AAL 37 and 38", two, labels, mask=two > 0, labels=True)


def check_shared_labels(name, values, pair):
    """Labels mode with touching labels: each cell once, BoundaryLabels (smaller first, 0 the
    background) and Label (the larger), and each label's cells (those that carry it, turned
    out of it) closed and oriented, within one voxel diagonal of that label's own surfels."""
    f = voxelbrep.vtkFaceOctreeBoundaryFilter()
    f.SetInputData(vt.make_image(values))
    f.SetSelectionModeToLabels()
    f.Update()
    out = f.GetOutput()
    pts, cells = vt.points(out), vt.cells(out)
    both = vt.cell_array(out, "BoundaryLabels").reshape(-1, 2)
    label = vt.cell_array(out, "Label")
    check.true(name + ": smaller label first", bool((both[:, 0] < both[:, 1]).all()))
    check.true(name + ": Label is the larger", bool((label == both[:, 1]).all()))
    check.true(name + ": labels of the map", set(np.unique(both)) <= {0, pair[0], pair[1]})
    shared = int(((both[:, 0] == pair[0]) & (both[:, 1] == pair[1])).sum())
    check.true(name + ": a shared surface (%d cells)" % shared, shared > 0)
    keys = {tuple(sorted(c)) for c in cells}
    check.equal(name + ": each cell once", len(keys), len(cells))
    for value in pair:
        mine = [c if both[i, 0] == value else c[::-1]
                for i, c in enumerate(cells) if value in both[i]]
        check.true(name + ": label %d closed and oriented" % value,
                   closed_and_oriented(mine, len(pts)))
        used = np.unique(np.concatenate(mine))
        d, _ = cKDTree(surfel_points(values == value)).query(pts[used])
        check.true(name + ": label %d within a voxel diagonal (%g)" % (value, d.max()),
                   d.max() <= 3 ** 0.5)
    print("%s: %d cells, %d shared, %d face nodes" % (
        name, len(cells), shared, vt.field_value(out, "NumberOfFaceNodes")))


touching = np.where((aal == 37) | (aal == 39), aal, 0).astype(np.uint8)
check_shared_labels("AAL 37 and 39", touching, (37, 39))
check.finish()
