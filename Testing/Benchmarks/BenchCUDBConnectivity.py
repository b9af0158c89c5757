"""Benchmark of vtkCUDBConnectivity against scipy.ndimage.label, in one process on the same
inputs (the Python companion of BenchCUDBConnectivity.cxx).

    PYTHONPATH=build/lib/python3/dist-packages VTK_SMP_BACKEND_IN_USE=STDThread \
        /usr/bin/python3 Testing/Benchmarks/BenchCUDBConnectivity.py \
        [--sizes 128,256] [--repeat 5] [--data DIR] [--no-data]

For each input (phantoms of nested shells, a row of boxes and porous blobs; the real volumes
of the shared data) it prints the median time of the filter (face and vertex connectivity,
no boxes output, uint8 0/1 input) and of scipy.ndimage.label with the 6- and 26-neighbour
structures (the same connectivities), their ratios, and checks that the component counts
agree: a benchmark that compares different answers measures nothing.
"""

import argparse
import os
import sys
import time

import numpy as np
from scipy import ndimage
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonDataModel import vtkImageData

import voxelbrep

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_DATA = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data"))


def median_seconds(repeat, run):
    run()  # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        run()
        times.append(time.perf_counter() - t0)
    return sorted(times)[len(times) // 2]


def shells(n):
    source = voxelbrep.vtkVoxelPhantomSource()
    source.SetDimensions(n, n, n)
    source.Update()
    labels = ns.vtk_to_numpy(source.GetOutput().GetPointData().GetScalars())
    return (labels.reshape(n, n, n) != 0).astype(np.uint8)


def boxes(n):
    mask = np.zeros((n, n, n), np.uint8)
    columns = (np.arange(n) // 4) % 2 == 0
    mask[n // 4 : 3 * n // 4, n // 4 : 3 * n // 4, :] = columns
    return mask


def blobs(n):
    """Thresholded union of random balls, as the C++ benchmark (not the same random draw)."""
    rng = np.random.default_rng(5)
    r = max(2, n // 20)
    mask = np.zeros((n, n, n), np.uint8)
    offsets = np.arange(-r, r)
    ball = (offsets[:, None, None] ** 2 + offsets[None, :, None] ** 2
            + offsets[None, None, :] ** 2) < r * r
    for cz, cy, cx in rng.integers(0, n, size=(n * n // 16, 3)):
        z0, y0, x0 = max(0, cz - r), max(0, cy - r), max(0, cx - r)
        z1, y1, x1 = min(n, cz + r), min(n, cy + r), min(n, cx + r)
        mask[z0:z1, y0:y1, x0:x1] |= ball[z0 - cz + r : z1 - cz + r, y0 - cy + r : y1 - cy + r,
                                          x0 - cx + r : x1 - cx + r]
    return mask


def real_volume(directory, file, dims, lo, hi):
    path = os.path.join(directory, file)
    if not os.path.exists(path):
        return None
    raw = np.fromfile(path, np.uint8).reshape(dims[2], dims[1], dims[0])
    return ((raw >= lo) & (raw <= hi)).astype(np.uint8)


def image_of(mask):
    image = vtkImageData()
    image.SetDimensions(mask.shape[2], mask.shape[1], mask.shape[0])
    scalars = ns.numpy_to_vtk(mask.ravel(), deep=1)
    scalars.SetName("mask")
    image.GetPointData().SetScalars(scalars)
    return image


def run(name, mask, repeat):
    image = image_of(mask)
    line = "%-16s" % name
    failures = []
    for connectivity, structure_rank in (("face", 1), ("vertex", 3)):
        f = voxelbrep.vtkCUDBConnectivity()
        f.SetInputData(image)
        f.GenerateBoxesOff()
        if connectivity == "vertex":
            f.SetConnectivityToVertex()

        def update():
            f.Modified()
            f.Update()

        t_filter = median_seconds(repeat, update)
        regions = int(f.GetOutput().GetFieldData().GetArray("NumberOfRegions").GetValue(0))
        structure = ndimage.generate_binary_structure(3, structure_rank)
        result = {}

        def label():
            result["count"] = ndimage.label(mask, structure)[1]

        t_scipy = median_seconds(repeat, label)
        if result["count"] != regions:
            failures.append("%s %s: %d regions, scipy %d" % (name, connectivity, regions,
                                                            result["count"]))
        line += " | %-6s %8.2f ms  scipy %8.2f ms  (%6d cc) ratio %5.1fx" % (
            connectivity, 1e3 * t_filter, 1e3 * t_scipy, regions, t_scipy / t_filter)
    print(line, flush=True)
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default="128,256")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--data", default=DEFAULT_DATA)
    parser.add_argument("--no-data", action="store_true")
    args = parser.parse_args()
    print("VTK_SMP_BACKEND_IN_USE=%s" % os.environ.get("VTK_SMP_BACKEND_IN_USE", "(default)"))
    failures = []
    for n in (int(s) for s in args.sizes.split(",") if s):
        for kind, make in (("shells", shells), ("boxes", boxes), ("blobs", blobs)):
            failures += run("%s %d^3" % (kind, n), make(n), max(1, args.repeat))
    if not args.no_data:
        for name, file, dims, lo, hi in (
            ("aneurism>=55", "aneurism/aneurism_256x256x256_uint8.raw", (256, 256, 256), 55, 255),
            ("engine>=55", "engine/engine_256x256x128_uint8.raw", (256, 256, 128), 55, 255),
            ("lobster>=40", "lobster/lobster_301x324x56_uint8.raw", (301, 324, 56), 40, 255),
            ("berea pore", "berea/berea_200x200x200_uint8.raw", (200, 200, 200), 0, 0),
        ):
            mask = real_volume(args.data, file, dims, lo, hi)
            if mask is not None:
                failures += run(name, mask, max(1, args.repeat))
    for f in failures:
        print("MISMATCH " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
