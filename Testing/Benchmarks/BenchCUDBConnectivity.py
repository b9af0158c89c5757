"""BenchCUDBConnectivity.py: vtkCUDBConnectivity against scipy.ndimage.label and OpenCV's
connectedComponents (2D images), in one process on the same inputs: the Python companion of
BenchCUDBConnectivity.cxx, on the same harness (BenchCommon.h).

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/BenchCUDBConnectivity.py [options]      (--help lists them)

The inputs are the benchmarks' input classes, made by the BenchInputs program (one definition
of the inputs for every benchmark; --inputs-program gives its path, else build/bin is
searched). The options are those of the C++ benchmarks and mean the same. Every contender
makes a first run (its peak memory, and the warm-up), then --repeat rounds in turns; the median
is the middle of the sorted times (of an even count, the mean of the middle two); the ratio is
the peer's time over the filter's with the same connectivity (above 1: the filter is faster).
The component counts of the filter and of every peer must agree (MISMATCH, exit code 1):
a benchmark that compares different answers measures nothing. So must the filter's ways of
labelling an image, on every input and, with --check (40 random images and 40 random 2D ones
with --quick, the ctest smoke run), on random images and options: every output but the boxes,
value for value, without the boxes output and with it, and every output, the boxes' cells
included, on the runs of the voxel rows (RunLabelling on, the default) and through the EVM and
the CUDB sweep (RunLabelling off); a 2D image without the boxes output on the runs of its
pixel rows (MinimumPixelRuns 0), by default and through the sweep. The filter is timed without the boxes output unless --boxes; --sweep adds
it labelled through the sweep (RunLabelling off) as a peer, in the same turns.
"""

import argparse
import os
import random
import shutil
import statistics
import subprocess
import sys
import time

import numpy as np
from scipy import ndimage
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkPassThrough

import voxelbrep

try:
    import cv2
except ImportError:  # OpenCV is optional: its rows are left out
    cv2 = None

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_DATA = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data"))
CLASSES = ("phantom,boxes,blobs,porous,checkerboard,noise,berea,volumes,labelmaps,porous2d,"
           "images2d")
INPUT_OPTIONS = ("inputs", "sizes", "sizes2d", "seeds", "solid", "radii", "labels", "data")


def parse_arguments():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--inputs", default=CLASSES, help="input classes ('all': every class)")
    p.add_argument("--sizes", help="edges of the procedural 3D volumes (default 128,256)")
    p.add_argument("--sizes2d", help="edges of the procedural 2D images (porous2d)")
    p.add_argument("--seeds", help="seeds of the porous inputs")
    p.add_argument("--solid", help="solid percentages of the porous inputs")
    p.add_argument("--radii", help="radii of the balls")
    p.add_argument("--labels", help="compact label maps of N^3 labels")
    p.add_argument("--repeat", type=int, default=5, help="timed rounds after the first run")
    p.add_argument("--data", default=DEFAULT_DATA, help="the shared data")
    p.add_argument("--no-data", action="store_true", help="procedural inputs only")
    p.add_argument("--check", type=int, default=None, metavar="N",
                   help="before the benchmark, N random images (sizes, densities, label maps, "
                        "options, seeds, cell data, extents) whose outputs must be the same "
                        "without and with the boxes output, on the runs and through the "
                        "sweep (default 40 with --quick, else 0)")
    p.add_argument("--boxes", action="store_true",
                   help="time the filter with the boxes output (GenerateBoxes on, its default)")
    p.add_argument("--sweep", action="store_true",
                   help="time the filter through the EVM and the CUDB sweep too (RunLabelling "
                        "off), as a peer ('sweep face', 'sweep vertex')")
    p.add_argument("--quick", action="store_true",
                   help="tiny sizes, --repeat 1, small files only (the ctest smoke run)")
    p.add_argument("--large", action="store_true", help="sizes 128,256,512, the mazes")
    p.add_argument("--backends", help="vtkSMPTools backends (default: the one at start)")
    p.add_argument("--list", action="store_true", help="print the selected inputs and stop")
    p.add_argument("--cpu", action="store_true",
                   help="time the process's CPU time rather than the wall clock (a loaded "
                        "machine; meaningful with one thread)")
    p.add_argument("--inputs-program", help="the BenchInputs program")
    p.add_argument("--no-fixed-cost", action="store_true",
                   help="no fixed-cost tables (a call on a tiny image of zeros)")
    args = p.parse_args()
    if args.quick and "--repeat" not in sys.argv:
        args.repeat = 1
    if args.check is None:
        args.check = 40 if args.quick else 0
    if args.sizes is None and not (args.quick or args.large):
        args.sizes = "128,256"  # the default of BenchCUDBConnectivity.cxx
    return args


def inputs_command(args):
    """The BenchInputs command line of the input options."""
    program = args.inputs_program or shutil.which("BenchInputs") or os.path.join(
        HERE, "..", "..", "build", "bin", "BenchInputs")
    command = [program]
    for name in INPUT_OPTIONS:
        value = getattr(args, name)
        if value is not None:
            command += ["--" + name, value]
    command += [flag for flag, on in (("--no-data", args.no_data), ("--quick", args.quick),
                                      ("--large", args.large)) if on]
    return command


def load_inputs(args):
    """(name, input class, 0/1 mask as a z, y, x array) of every selected input."""
    command = inputs_command(args)
    listing = subprocess.run(command + ["--list"], check=True, capture_output=True, text=True)
    for line in listing.stdout.splitlines():
        name, input_class = line.split("\t")
        out = subprocess.run(command + ["--emit", name], capture_output=True)
        if out.returncode != 0:
            print("(%s: not available, skipped)" % name)
            continue
        header, _, data = out.stdout.partition(b"\n")
        nx, ny, nz = (int(v) for v in header.split())
        yield name, input_class, np.frombuffer(data, np.uint8).reshape(nz, ny, nx)


def peak_bytes_of(run):
    """The peak memory a first run adds (the harness's peakBytesOf), or -1."""
    def status(field):
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(field + ":"):
                    return int(line.split()[1])
        return -1

    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        return -1
    before = status("VmRSS")
    run()
    return 1024 * max(0, status("VmHWM") - before)


def time_in_turns(repeat, contenders, clock=time.perf_counter):
    """(name, role, group, median s, min s, peak bytes) of each contender."""
    peaks = [peak_bytes_of(c[3]) for c in contenders]
    times = [[] for _ in contenders]
    # Each round in an order of its own (shuffled, fixed seed), so that no contender always
    # runs right after the same one: with a rotation, the one after a peer found the caches
    # cold in every round and the next one found them warm (on sub-millisecond 2D images the
    # filter's face connectivity then took twice its vertex connectivity's time).
    shuffler = random.Random(1)
    order = list(range(len(contenders)))
    for r in range(repeat):
        shuffler.shuffle(order)
        for k in order:
            t0 = clock()
            contenders[k][3]()
            times[k].append(clock() - t0)
    return [(c[0], c[1], c[2], statistics.median(t), min(t), p)
            for c, t, p in zip(contenders, times, peaks)]


def pipeline_run(algorithm, image):
    """Modified() and Update() of `algorithm` on `image`: one update through the pipeline."""
    algorithm.SetInputData(image)

    def run():
        algorithm.Modified()
        algorithm.Update()

    return run


def print_fixed_cost(title, contenders, quick):
    """The cost of one call on a tiny image, which every update pays whatever the image: each
    contender (name, run) is called many times per turn, the turns rotate, and the CPU time
    per call is the median over the turns. vtkPassThrough's row is VTK's own pipeline cost
    (the floor of any filter's update)."""
    calls, turns = (50, 3) if quick else (2000, 7)
    times = {name: [] for name, _ in contenders}
    for name, run in contenders:
        run()  # warm-up
    for t in range(turns):
        for i in range(len(contenders)):
            name, run = contenders[(i + t) % len(contenders)]
            t0 = time.process_time()
            for _ in range(calls):
                run()
            times[name].append((time.process_time() - t0) / calls)
    print("## Fixed cost per call: %s (CPU time, %d calls x %d turns)\n" % (title, calls, turns))
    print("| contender | median us | min us |")
    print("| :-- | --: | --: |")
    for name, _ in contenders:
        print("| %s | %.1f | %.1f |" % (
            name, 1e6 * statistics.median(times[name]), 1e6 * min(times[name])))
    print(flush=True)


def fixed_costs(args):
    """Fixed cost of the filter (every output, and without the boxes) against VTK's pipeline
    and the peers, on a 16x16 and a 16^3 image of zeros."""
    for shape in ((1, 16, 16), (16, 16, 16)):
        mask = np.zeros(shape, np.uint8)
        image = image_of(mask)
        data = mask[0] if shape[0] == 1 else mask
        contenders = [("vtkPassThrough", pipeline_run(vtkPassThrough(), image))]
        for boxes in (True, False):
            f = voxelbrep.vtkCUDBConnectivity()
            f.SetGenerateBoxes(boxes)
            contenders.append(("filter face" + ("" if boxes else ", no boxes"),
                               pipeline_run(f, image)))
        structure = ndimage.generate_binary_structure(data.ndim, 1)
        contenders.append(("scipy %d" % int(structure.sum() - 1),
                           lambda: ndimage.label(data, structure)))
        if shape[0] == 1 and cv2 is not None:
            contenders.append(("OpenCV 4", lambda: cv2.connectedComponents(data, connectivity=4)))
        print_fixed_cost("%dx%dx%d zeros" % shape[::-1], contenders, args.quick)


def image_of(mask):
    image = vtkImageData()
    image.SetDimensions(mask.shape[2], mask.shape[1], mask.shape[0])
    scalars = ns.numpy_to_vtk(mask.ravel(), deep=1)
    scalars.SetName("mask")
    image.GetPointData().SetScalars(scalars)
    return image


def filter_contender(image, connectivity, counts, boxes=False, sweep=False):
    """The filter timed, with or without the boxes output; `sweep`: through the EVM and the
    CUDB sweep (RunLabelling off), a peer named 'sweep <connectivity>'."""
    f = voxelbrep.vtkCUDBConnectivity()
    f.SetInputData(image)
    f.SetGenerateBoxes(boxes)
    if sweep:
        f.RunLabellingOff()
    if connectivity == "vertex":
        f.SetConnectivityToVertex()
    name = ("sweep " if sweep else "filter ") + connectivity

    def run():
        f.Modified()
        f.Update()
        regions = f.GetOutput().GetFieldData().GetArray("NumberOfRegions").GetValue(0)
        counts[name] = int(regions)

    return (name, "peer" if sweep else "tool", connectivity, run)


def boxes_of(output):
    """The boxes output (port 1) as arrays: points, cells, cell types and cell arrays."""
    out = {"boxes points": ns.vtk_to_numpy(output.GetPoints().GetData())
           if output.GetPoints() is not None else np.zeros((0, 3)),
           "boxes cell types": np.array([output.GetCellType(i)
                                         for i in range(output.GetNumberOfCells())])}
    cells = output.GetCells()
    if cells is not None:
        out["boxes offsets"] = ns.vtk_to_numpy(cells.GetOffsetsArray())
        out["boxes connectivity"] = ns.vtk_to_numpy(cells.GetConnectivityArray())
    data = output.GetCellData()
    for a in range(data.GetNumberOfArrays()):
        out["boxes cell array %s" % data.GetArrayName(a)] = ns.vtk_to_numpy(data.GetArray(a))
    return out


def has_run_labelling():
    """Whether this build's filter can be told to label through the sweep (RunLabelling)."""
    return hasattr(voxelbrep.vtkCUDBConnectivity(), "SetRunLabelling")


def outputs_of(image, connectivity, boxes, options=None, seeds=None, run_labelling=True,
               all_pixel_runs=False):
    """Every output of the filter, as arrays: the RegionId image, each column of the region
    table, the field data of ports 0 and 2, and with `boxes` the boxes output. `options`:
    setter name -> value; `run_labelling` off: through the EVM and the CUDB sweep;
    `all_pixel_runs`: a 2D image on the runs of its pixel rows however few (MinimumPixelRuns
    0)."""
    f = voxelbrep.vtkCUDBConnectivity()
    f.SetInputData(image)
    f.SetGenerateBoxes(boxes)
    if not run_labelling:
        f.RunLabellingOff()
    if all_pixel_runs:
        f.SetMinimumPixelRuns(0)
    if connectivity == "vertex":
        f.SetConnectivityToVertex()
    for setter, value in (options or {}).items():
        getattr(f, setter)(value)
    if seeds is not None:
        f.SetSeedData(seeds)
    f.Update()
    out = {}
    for data in (f.GetOutput().GetPointData(), f.GetOutput().GetCellData()):
        if data.GetArray("RegionId") is not None:
            out["RegionId"] = ns.vtk_to_numpy(data.GetArray("RegionId"))
    table = f.GetRegionsOutput()
    for c in range(table.GetNumberOfColumns()):
        column = table.GetColumn(c)
        out["column " + column.GetName()] = ns.vtk_to_numpy(column)
    for port in (0, 2):
        fd = f.GetOutputDataObject(port).GetFieldData()
        for a in range(fd.GetNumberOfArrays()):
            array = fd.GetAbstractArray(a)
            values = [array.GetValue(i) for i in range(array.GetNumberOfValues())]
            out["port %d field %s" % (port, array.GetName())] = np.array(values)
    if boxes:
        out.update(boxes_of(f.GetBoxesOutput()))
    return out


def differences(name, connectivity, a, b, what):
    return ["%s, %s: %s differs %s" % (name, connectivity, key, what)
            for key in sorted(set(a) | set(b))
            if key not in a or key not in b or not np.array_equal(a[key], b[key])]


def check_same_outputs(name, image, connectivities=("face", "vertex"), options=None,
                       seeds=None):
    """Every output but the boxes the same without and with the boxes output, and every
    output, the boxes included, the same on the runs of the voxel rows and through the sweep
    (when this build has the switch), without the boxes output too (a 2D image takes the runs
    of its pixel rows only then, and by default only with many runs: once more with
    MinimumPixelRuns 0), value for value."""
    failures = []
    for connectivity in connectivities:
        plain = outputs_of(image, connectivity, False, options, seeds)
        runs = outputs_of(image, connectivity, True, options, seeds)
        failures += differences(name, connectivity, plain,
                                {k: v for k, v in runs.items() if not k.startswith("boxes ")},
                                "without and with the boxes output")
        if has_run_labelling():
            sweep = outputs_of(image, connectivity, True, options, seeds, run_labelling=False)
            failures += differences(name, connectivity, runs, sweep,
                                    "on the runs and through the sweep")
            plain_sweep = outputs_of(image, connectivity, False, options, seeds,
                                     run_labelling=False)
            failures += differences(name, connectivity, plain, plain_sweep,
                                    "on the runs and through the sweep, without the boxes")
        if hasattr(voxelbrep.vtkCUDBConnectivity(), "SetMinimumPixelRuns"):
            pixel_runs = outputs_of(image, connectivity, False, options, seeds,
                                    all_pixel_runs=True)
            failures += differences(name, connectivity, pixel_runs, plain,
                                    "on all the pixel runs and by default, without the boxes")
    return failures


def random_image(rng, planar=False):
    """A random image for check_random_images: a mask or a label map of random size (rows of
    one to three words), density, extent, origin and spacing, as point or cell scalars;
    `planar`: a 2D image (one voxel along one axis, z most often), up to 200 pixels a side."""
    dims = rng.integers(1, 40, 3)
    if rng.random() < 0.3:
        dims[0] = rng.integers(60, 140)
    if planar:
        dims[:2] = rng.integers(1, 200, 2)
        flat = 2 if rng.random() < 0.7 else int(rng.integers(0, 2))
        dims[flat] = 1
        if flat != 2:
            dims[2] = rng.integers(2, 120)
    labels = rng.random() < 0.3
    shape = tuple(int(d) for d in dims[::-1])
    values = (rng.integers(0, 4, shape).astype(np.int16) if labels
              else (rng.random(shape) < rng.uniform(0.05, 0.95)).astype(np.uint8))
    cell = rng.random() < 0.3
    image = vtkImageData()
    start = rng.integers(-3, 3, 3)
    image.SetExtent(*[int(v) for s, d in zip(start, dims)
                      for v in (s, s + d - (0 if cell else 1))])
    image.SetOrigin(*rng.uniform(-5, 5, 3))
    image.SetSpacing(*rng.uniform(0.2, 2, 3))
    scalars = ns.numpy_to_vtk(values.ravel(), deep=1)
    scalars.SetName("values")
    (image.GetCellData() if cell else image.GetPointData()).SetScalars(scalars)
    return image, labels


def random_options(rng, labels, image):
    """Random region filters and ordering (Labels mode for a label map), and seeds or None."""
    options = {"SetSelectionMode": 2} if labels else {}
    for setter, chance, value in (("SetRegionOrdering", 0.3, 1),
                                  ("SetMinimumRegionSize", 0.3, int(rng.integers(1, 5))),
                                  ("SetLargestRegions", 0.3, int(rng.integers(1, 5)))):
        if rng.random() < chance:
            options[setter] = value
    if rng.random() >= 0.2:
        return options, None
    points = vtkPoints()
    bounds = image.GetBounds()
    for _ in range(int(rng.integers(1, 20))):
        points.InsertNextPoint(*[rng.uniform(bounds[2 * i], bounds[2 * i + 1]) for i in range(3)])
    seeds = vtkPolyData()
    seeds.SetPoints(points)
    return options, seeds


def check_random_images(trials):
    """check_same_outputs on `trials` random images and as many random 2D images (rows of 2D
    images are labelled on their runs), with random options (seeded: reproducible)."""
    failures = []
    for planar, seed in ((False, 11), (True, 12)):
        rng = np.random.default_rng(seed)
        for trial in range(trials):
            image, labels = random_image(rng, planar)
            options, seeds = random_options(rng, labels, image)
            connectivity = "vertex" if rng.random() < 0.5 else "face"
            failures += check_same_outputs("random %simage %d" % ("2D " if planar else "", trial),
                                           image, (connectivity,), options, seeds)
    print("random images checked: %d and %d 2D, %d differ\n" % (trials, trials, len(failures)),
          flush=True)
    return failures


def peer_contenders(mask, counts):
    """scipy (6/26 in 3D, 4/8 in 2D) and, in 2D, OpenCV, with the filter's connectivities."""
    flat = mask.shape[0] == 1
    data = mask[0] if flat else mask
    peers = []
    for connectivity, rank in (("face", 1), ("vertex", data.ndim)):
        structure = ndimage.generate_binary_structure(data.ndim, rank)
        name = "scipy %d" % int(structure.sum() - 1)

        def scipy_run(name=name, structure=structure):
            counts[name] = ndimage.label(data, structure)[1]

        peers.append((name, "peer", connectivity, scipy_run))
        if flat and cv2 is not None:
            n = 4 if rank == 1 else 8

            def cv_run(name="OpenCV %d" % n, n=n):
                counts[name] = cv2.connectedComponents(data, connectivity=n)[0] - 1

            peers.append(("OpenCV %d" % n, "peer", connectivity, cv_run))
    return peers


def print_rows(name, backend, rows, voxels):
    print("backend %s\n" % backend)
    print("| contender | role | median ms | min ms | peak MB | B/voxel | peer / this |")
    print("| :-- | --: | --: | --: | --: | --: | --: |")
    for n, role, group, med, low, peak in rows:
        ratios = ", ".join("%s %.2f" % (p[0], p[3] / med) for p in rows
                           if role == "tool" and p[1] == "peer" and p[2] == group)
        print("| %s | %s | %.2f | %.2f | %.1f | %.1f | %s |" % (
            n, role, 1e3 * med, 1e3 * low, peak / 2**20, peak / voxels, ratios or "-"))
    print(flush=True)


def check_counts(name, counts):
    """The connectivity's counts must agree: the filter's with every peer's."""
    failures = []
    for key, value in counts.items():
        if key.startswith("filter"):
            continue
        face = key in ("scipy 6", "scipy 4", "OpenCV 4", "sweep face")
        mine = counts["filter face" if face else "filter vertex"]
        if value != mine:
            failures.append("%s: %s finds %d regions, the filter %d" % (name, key, value, mine))
    return failures


CHECKED_VOXELS = 128 ** 3


def benchmark(name, mask, args, summary):
    print("## %s (%dx%dx%d)\n\nselected voxels: %d\n" % (
        name, mask.shape[2], mask.shape[1], mask.shape[0], int(mask.sum())))
    image = image_of(mask)
    # Both paths' outputs compared up to 128^3: with --large, a 512^3 checkerboard's boxes
    # alone would take about 13 GB each way.
    if mask.size <= CHECKED_VOXELS:
        failures = check_same_outputs(name, image)
    else:
        print("(outputs of the two paths not compared above %d voxels)\n" % CHECKED_VOXELS)
        failures = []
    for backend in backends_in_turn(args):
        counts = {}
        contenders = [filter_contender(image, c, counts, args.boxes) for c in ("face", "vertex")]
        if args.sweep:
            contenders += [filter_contender(image, c, counts, args.boxes, sweep=True)
                           for c in ("face", "vertex")]
        contenders += peer_contenders(mask, counts)
        rows = time_in_turns(max(1, args.repeat), contenders,
                             time.process_time if args.cpu else time.perf_counter)
        print_rows(name, backend, rows, mask.size)
        summary.append((backend, name, rows))
        failures += check_counts(name, counts)
    return failures


def print_summary(summary):
    for backend in sorted(set(s[0] for s in summary)):
        print("## Summary, backend %s (median ms; ratio = peer / filter, same connectivity)\n"
              % backend)
        print("| input | filter face | filter vertex | peers (ms, ratio) |")
        print("| :-- | --: | --: | :-- |")
        for b, name, rows in summary:
            if b != backend:
                continue
            tool = {r[2]: r[3] for r in rows if r[1] == "tool"}
            peers = ", ".join("%s %.2f (%.2fx)" % (r[0], 1e3 * r[3], r[3] / tool[r[2]])
                              for r in rows if r[1] == "peer")
            print("| %s | %.2f | %.2f | %s |" % (name, 1e3 * tool["face"], 1e3 * tool["vertex"],
                                                 peers))
        print()


def backends_in_turn(args):
    """The vtkSMPTools backends asked for (default: the one at start), each set in turn; one
    this VTK lacks is skipped with a warning."""
    backends = args.backends.split(",") if args.backends else [vtkSMPTools.GetBackend()]
    for backend in backends:
        if not vtkSMPTools.SetBackend(backend):
            print("WARNING: vtkSMPTools backend %s is not in this VTK; skipped" % backend)
            continue
        yield backend


def run_benchmarks(title, args, benchmark, finish, accept=lambda mask: True, first=None):
    """The driver both Python benchmarks share: --list, the header, first(args) (the fixed
    costs), benchmark(name, mask, args, summary) on every accepted input, finish(summary), and
    the mismatches, which fail the run (exit code 1)."""
    if args.list:
        return subprocess.run(inputs_command(args) + ["--list"]).returncode
    print("# %s\n\n- VTK_SMP_BACKEND_IN_USE=%s, OpenCV %s, %s\n" % (
        title, os.environ.get("VTK_SMP_BACKEND_IN_USE", "(unset)"),
        cv2.__version__ if cv2 is not None else "absent",
        "CPU time" if getattr(args, "cpu", False) else "wall clock"), flush=True)
    if first is not None and not getattr(args, "no_fixed_cost", False):
        first(args)
    failures, summary = [], []
    for name, _, mask in load_inputs(args):
        if accept(mask):
            failures += benchmark(name, mask, args, summary)
    finish(summary)
    for f in failures:
        print("MISMATCH " + f, file=sys.stderr)
    return 1 if failures else 0


def main():
    args = parse_arguments()
    failures = check_random_images(args.check) if args.check and not args.list else []
    code = run_benchmarks("BenchCUDBConnectivity.py", args, benchmark, print_summary,
                          first=fixed_costs)
    for f in failures:
        print("MISMATCH " + f, file=sys.stderr)
    return 1 if failures else code


if __name__ == "__main__":
    sys.exit(main())
