"""vtkCUDBConnectivity from Python against scipy.ndimage.label: random 3D volumes and 2D
images (sparse to dense) in both connectivities, point and cell scalars, every sorting; the
labels must equal scipy's renumbered by size (largest first, ties in scan order), which is
what RegionOrdering SizeRank promises for the default ZYX sorting, and partition the voxels
the same way for the other sortings."""

import sys

import numpy as np
from scipy import ndimage
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonDataModel import vtkImageData

import voxelbrep

failures = []


def expect(what, ok):
    if not ok:
        print("FAILED:", what)
        failures.append(what)


def make_image(mask, cells):
    image = vtkImageData()
    nz, ny, nx = mask.shape
    add = 1 if cells else 0
    image.SetExtent(0, nx - 1 + add, 0, ny - 1 + add, 0, nz - 1 + add)
    array = ns.numpy_to_vtk(mask.astype(np.uint8).ravel(), deep=1)
    array.SetName("mask")
    (image.GetCellData() if cells else image.GetPointData()).SetScalars(array)
    return image


def size_ranked(mask, rank):
    structure = ndimage.generate_binary_structure(mask.ndim, rank)
    labels, n = ndimage.label(mask, structure)
    sizes = np.bincount(labels.ravel())[1:]
    order = np.argsort(-sizes, kind="stable")
    renumber = np.zeros(n + 1, dtype=np.int64)
    renumber[order + 1] = np.arange(1, n + 1)
    return renumber[labels], n


def same_partition(a, b):
    pairs = np.unique(np.stack([a.ravel(), b.ravel()]), axis=1)
    return len(np.unique(pairs[0])) == pairs.shape[1] == len(np.unique(pairs[1]))


def region_ids(f, cells, shape):
    out = f.GetOutput()
    data = out.GetCellData() if cells else out.GetPointData()
    return ns.vtk_to_numpy(data.GetArray("RegionId")).reshape(shape)


def check(mask, cells, tag):
    f = voxelbrep.vtkCUDBConnectivity()
    f.SetInputData(make_image(mask, cells))
    f.GenerateBoxesOff()
    flat = mask.shape[0] == 1
    for vertex in (False, True):
        f.SetConnectivity(1 if vertex else 0)
        expected, n = size_ranked(mask[0] if flat else mask,
                                  (2 if flat else 3) if vertex else 1)
        expected = expected.reshape(mask.shape)
        for sorting in range(7):
            f.SetSortingOrder(sorting)
            f.Update()
            got = region_ids(f, cells, mask.shape)
            what = "%s %s sorting %s" % (tag, "vertex" if vertex else "face",
                                         f.GetSortingOrderAsString())
            regions = f.GetOutput().GetFieldData().GetArray("NumberOfRegions").GetValue(0)
            expect(what + ": %d regions, scipy %d" % (regions, n), regions == n)
            if sorting == voxelbrep.vtkCUDBConnectivity.ZYX:
                expect(what + ": labels equal scipy's, size-ranked", (got == expected).all())
            else:
                expect(what + ": same partition as scipy", same_partition(got, expected))


def check_table(mask, tag):
    """The region table against scipy (default ZYX sorting, size ranked: the regions
    labelled on the runs of the voxel rows): voxel counts, index bounds and centroids."""
    image = make_image(mask, False)
    for vertex in (False, True):
        f = voxelbrep.vtkCUDBConnectivity()
        f.SetInputData(image)
        f.GenerateBoxesOff()
        f.SetConnectivity(1 if vertex else 0)
        f.Update()
        labels, n = size_ranked(mask, 3 if vertex else 1)
        table = f.GetRegionsOutput()
        column = lambda name: ns.vtk_to_numpy(table.GetColumn(table.GetColumnIndex(name)))
        what = "%s %s table" % (tag, "vertex" if vertex else "face")
        expect(what + ": one row per region", table.GetNumberOfRows() == n)
        if table.GetNumberOfRows() != n:
            continue
        ids = np.arange(1, n + 1)
        expect(what + ": voxel counts", (column("VoxelCount") == np.bincount(labels.ravel())[1:]).all())
        boxes = ndimage.find_objects(labels)
        for axis, (lo, hi) in zip((2, 1, 0), (("IMin", "IMax"), ("JMin", "JMax"), ("KMin", "KMax"))):
            expect(what + ": " + lo, (column(lo) == [b[axis].start for b in boxes]).all())
            expect(what + ": " + hi, (column(hi) == [b[axis].stop - 1 for b in boxes]).all())
        centres = np.array(ndimage.center_of_mass(np.ones(mask.shape), labels, ids))[:, ::-1]
        expect(what + ": centroids", np.allclose(column("Centroid"), centres))


def main():
    rng = np.random.default_rng(7)
    for shape in [(6, 5, 4), (17, 13, 11), (32, 40, 24), (1, 50, 60), (1, 7, 300)]:
        for density in (0.1, 0.35, 0.6, 0.9):
            mask = rng.random(shape) < density
            for cells in (False, True):
                check(mask, cells, "%s density %.2f %s" % (shape, density,
                                                          "cells" if cells else "points"))
    # Smooth blobs: large components spanning many slices (long boxes).
    blobs = ndimage.gaussian_filter(rng.random((48, 48, 48)), 2.5) > 0.5
    check(blobs, False, "blobs")
    # Over 2^16 runs in more than 16 planes: with threads (the STDThread run of this test) the
    # runs are labelled in pieces of planes and joined.
    porous = rng.random((70, 60, 100)) < 0.45
    check(porous, False, "porous 100x60x70")
    check_table(porous, "porous 100x60x70")
    check_table(blobs, "blobs")
    if failures:
        print(len(failures), "failure(s)")
        sys.exit(1)
    print("all checks passed")


main()
