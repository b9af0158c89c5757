"""BenchEVMBoundary2D.py: the contours of vtkEVMBoundaryFilter on 2D images, with their
inclusion tree, against OpenCV's findContours(RETR_TREE), in one process on the same inputs.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/BenchEVMBoundary2D.py [options]      (--help lists them)

The inputs are the benchmarks' 2D input classes (porous2d, images2d; the mazes with --large),
made by the BenchInputs program like those of BenchCUDBConnectivity.py, whose loading and
timing in turns this script shares. The filter runs with MergeNonManifoldFaces on, whose faces
are 8-connected like OpenCV's foreground: its Polylines output (one closed polyline per loop,
with FaceId, LoopType, ParentFace and Depth) is what findContours(RETR_TREE,
CHAIN_APPROX_SIMPLE) gives; its other 2D outputs (Polygons, Triangles: the filled faces) are
timed too. OpenCV reads the image padded with a one-pixel zero border (it clears the image's
own border), made once outside the timing. The ratio is OpenCV's median over the filter's
(above 1: the filter is faster). The depth histograms of both must agree (MISMATCH, exit code
1): a benchmark that compares different answers measures nothing.
"""

import argparse
import os
import sys
import time
from collections import Counter

import numpy as np
from vtkmodules.util import numpy_support as ns

import voxelbrep

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from BenchCUDBConnectivity import (  # noqa: E402
    backends_in_turn, image_of, pipeline_run, print_fixed_cost, run_benchmarks, time_in_turns)
from vtkmodules.vtkFiltersCore import vtkPassThrough  # noqa: E402

try:
    import cv2
except ImportError:  # OpenCV is the peer: without it only the filter is timed
    cv2 = None

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_DATA = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data"))
MODES = ("Polylines", "Polygons", "Triangles")


def parse_arguments():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--inputs", default="porous2d,images2d", help="2D input classes")
    p.add_argument("--sizes2d", help="edges of the procedural 2D images (porous2d)")
    p.add_argument("--seeds", help="seeds of the porous inputs")
    p.add_argument("--solid", help="solid percentages of the porous inputs")
    p.add_argument("--modes", default=",".join(MODES), help="output modes of the filter")
    p.add_argument("--repeat", type=int, default=5, help="timed rounds after the first run")
    p.add_argument("--data", default=DEFAULT_DATA, help="the shared data")
    p.add_argument("--no-data", action="store_true", help="procedural inputs only")
    p.add_argument("--quick", action="store_true",
                   help="tiny sizes, --repeat 1, small files only (the ctest smoke run)")
    p.add_argument("--large", action="store_true", help="2D sizes 1024,4096, the mazes")
    p.add_argument("--backends", help="vtkSMPTools backends (default: the one at start)")
    p.add_argument("--list", action="store_true", help="print the selected inputs and stop")
    p.add_argument("--inputs-program", help="the BenchInputs program")
    p.add_argument("--cpu-time", action="store_true",
                   help="CPU time of the process (time.process_time) instead of wall time: "
                        "on a loaded machine the waits for a core are not counted")
    p.add_argument("--no-fixed-cost", action="store_true",
                   help="no fixed-cost table (a call on a 16x16 image of zeros)")
    args = p.parse_args()
    if args.quick and "--repeat" not in sys.argv:
        args.repeat = 1
    for name in ("sizes", "radii", "labels"):  # 3D options of the shared input loader
        setattr(args, name, None)
    args.cpu = args.cpu_time  # the shared header's name for it ("CPU time" or "wall clock")
    return args


def filter_contender(image, mode, answers):
    f = voxelbrep.vtkEVMBoundaryFilter()
    f.SetInputData(image)
    f.MergeNonManifoldFacesOn()  # 8-connected faces, OpenCV's foreground connectivity
    getattr(f, "SetOutputModeTo" + mode)()

    def run():
        f.Modified()
        f.Update()

    def answer():
        out = f.GetOutput()
        depth = ns.vtk_to_numpy(out.GetCellData().GetArray("Depth"))
        answers[mode] = Counter(depth.tolist())

    return ("filter " + mode, "tool", mode, run), answer


def opencv_contender(mask, answers):
    padded = np.pad(mask[0], 1)

    def run():
        answers["found"] = cv2.findContours(padded, cv2.RETR_TREE, cv2.CHAIN_APPROX_SIMPLE)

    def answer():
        hierarchy = answers.pop("found")[-1]
        answers["OpenCV"] = Counter(contour_depths(hierarchy).tolist())

    return ("OpenCV findContours", "peer", "", run), answer


def contour_depths(hierarchy):
    """The depth of each contour in OpenCV's RETR_TREE hierarchy (parent links)."""
    if hierarchy is None:
        return np.zeros(0, int)
    parent = hierarchy[0][:, 3]
    depth = np.zeros(len(parent), int)
    for i in range(len(parent)):
        p = parent[i]
        while p >= 0:
            depth[i] += 1
            p = parent[p]
    return depth


def check_answers(name, answers):
    """The depth histograms of the filter's loops (every mode's Polylines cells) and of
    OpenCV's contours must agree."""
    if "OpenCV" not in answers or "Polylines" not in answers:
        return []
    if answers["OpenCV"] == answers["Polylines"]:
        return []
    return ["%s: depth histograms differ, OpenCV %s, filter %s" % (
        name, sorted(answers["OpenCV"].items()), sorted(answers["Polylines"].items()))]


def fixed_costs(args):
    """Fixed cost of the filter in each mode (as benchmarked: MergeNonManifoldFaces on, and
    Triangles and Polylines by default) against VTK's pipeline and OpenCV, on a 16x16 image of
    zeros."""
    mask = np.zeros((1, 16, 16), np.uint8)
    image = image_of(mask)
    contenders = [("vtkPassThrough", pipeline_run(vtkPassThrough(), image))]
    for mode in args.modes.split(","):
        for merge in (True, False):
            if not merge and mode not in ("Triangles", "Polylines"):
                continue
            f = voxelbrep.vtkEVMBoundaryFilter()
            f.SetMergeNonManifoldFaces(merge)
            getattr(f, "SetOutputModeTo" + mode)()
            contenders.append(("filter " + mode + ("" if merge else ", default faces"),
                               pipeline_run(f, image)))
    if cv2 is not None:
        padded = np.pad(mask[0], 1)
        contenders.append(("OpenCV findContours", lambda: cv2.findContours(
            padded, cv2.RETR_TREE, cv2.CHAIN_APPROX_SIMPLE)))
    print_fixed_cost("16x16 zeros", contenders, args.quick)


def print_rows(backend, rows, pixels):
    print("backend %s\n" % backend)
    print("| contender | median ms | min ms | peak MB | B/pixel | OpenCV / this |")
    print("| :-- | --: | --: | --: | --: | --: |")
    peer = [r for r in rows if r[1] == "peer"]
    for n, role, _, med, low, peak in rows:
        ratio = "%.2f" % (peer[0][3] / med) if peer and role == "tool" else "-"
        print("| %s | %.3f | %.3f | %.1f | %.1f | %s |" % (
            n, 1e3 * med, 1e3 * low, peak / 2**20, peak / pixels, ratio))
    print(flush=True)


def benchmark(name, mask, args, summary):
    print("## %s (%dx%d)\n\nselected pixels: %d\n" % (
        name, mask.shape[2], mask.shape[1], int(mask.sum())))
    image = image_of(mask)
    failures = []
    for backend in backends_in_turn(args):
        answers = {}
        made = [filter_contender(image, m, answers) for m in args.modes.split(",")]
        if cv2 is not None:
            made.append(opencv_contender(mask, answers))
        clock = time.process_time if args.cpu_time else time.perf_counter
        rows = time_in_turns(max(1, args.repeat), [m[0] for m in made], clock)
        for _, answer in made:
            answer()
        print_rows(backend, rows, mask.size)
        summary.append((backend, name, mask.shape, rows))
        failures += check_answers(name, answers)
    return failures


def print_summary(summary, modes):
    for backend in sorted(set(s[0] for s in summary)):
        print("## Summary, backend %s (median ms; ratio = OpenCV / filter)\n" % backend)
        print("| input | size | " + " | ".join(modes) + " | OpenCV | " +
              " | ".join("OpenCV/" + m for m in modes) + " |")
        print("| :-- | --: |" + " --: |" * (2 * len(modes) + 1))
        for b, name, shape, rows in summary:
            if b != backend:
                continue
            med = {r[2]: r[3] for r in rows}
            opencv = med.get("")
            cells = ["%.2f" % (1e3 * med[m]) for m in modes]
            cells.append("%.2f" % (1e3 * opencv) if opencv else "-")
            cells += ["%.2f" % (opencv / med[m]) if opencv else "-" for m in modes]
            print("| %s | %dx%d | %s |" % (name, shape[2], shape[1], " | ".join(cells)))
        print()


def main():
    args = parse_arguments()
    return run_benchmarks("BenchEVMBoundary2D.py", args, benchmark,
                          lambda summary: print_summary(summary, args.modes.split(",")),
                          accept=lambda mask: mask.shape[0] == 1,  # 3D inputs: not this one's
                          first=fixed_costs)


if __name__ == "__main__":
    sys.exit(main())
