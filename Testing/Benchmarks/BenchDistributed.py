"""Distributed runs: time and bytes exchanged of every filter on the ranks this pvbatch runs
on, against the voxels of the volume.

Usage: mpiexec -n N pvbatch BenchDistributed.py /path/to/VoxelBRep.so [options]
  --inputs wavelet,phantom,berea,pacman   the inputs (default: all four)
  --size S        the Wavelet's and the phantom's points per axis (default 256)
  --repeat R      timed updates per filter (default 3; the median is printed)
  --filters a,b   EVM,CUDB,Polyhedrizer,Hull,FaceOctree (default: all)
  --data DIR      the shared real volumes (berea/berea_200x200x200_uint8.raw)

Inputs: ParaView's Wavelet (each rank computes its own piece) thresholded at RTData >= 150 (a
smooth field: a few large components); the Voxel Phantom (each rank computes its own piece),
every label > 0; the Berea sandstone's pores (v == 0), written by rank 0 as a .pvti of one
piece per rank and read back by every rank; a pac-man (a ball of radius n/4 with a wedge cut
out, a Calculator on the Wavelet's grid, n = min(size, 96)). Prints one line per filter and input: ranks,
median seconds of an update, the bytes the ranks exchanged for it (field data
BytesExchanged: the extreme vertices sent to rank 0 and what rank 0 sends back), the
voxels, and the bytes per voxel. On one rank nothing is exchanged. The Convex Hull Modifier
runs on the pac-man only (it does not separate the Wavelet's and the phantom's touching parts
or the porous rock yet, see the README), the other filters on the other inputs.
"""

import argparse
import os
import statistics
import sys
import tempfile
import time

import numpy as np
from paraview import servermanager as sm
from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "Filters", "Testing", "Python"))
from voxelbrep_testing import write_partitioned  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("--inputs", default="wavelet,phantom,berea,pacman")
parser.add_argument("--size", type=int, default=256)
parser.add_argument("--repeat", type=int, default=3)
parser.add_argument("--filters", default="EVM,CUDB,Polyhedrizer,Hull,FaceOctree")
parser.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                   "..", "..", "..", "shared", "data"))
args = parser.parse_args()

LoadPlugin(args.plugin, remote=False, ns=globals())
ranks = sm.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()


def berea_reader():
    """The Berea volume as a .pvti of one piece per rank (written by rank 0), or None."""
    raw = os.path.join(args.data, "berea", "berea_200x200x200_uint8.raw")
    if not os.path.exists(raw):
        print("Berea not found under %s: skipped" % args.data)
        return None
    values = np.fromfile(raw, np.uint8).reshape(200, 200, 200)
    path = os.path.join(tempfile.mkdtemp(prefix="voxelbrep-bench-"), "berea.pvti")
    write_partitioned(values, path, ranks)
    return OpenDataFile(path), 200 ** 3


def make_input(name):
    """(source proxy, selection properties, voxels) of an input, or None."""
    n = args.size
    if name == "wavelet":
        return (Wavelet(WholeExtent=[0, n - 1] * 3),
                dict(Scalars=["POINTS", "RTData"], SelectionMode="Range", LowerThreshold=150.0,
                     UpperThreshold=1000.0), n ** 3)
    if name == "pacman":
        m = min(n, 96)
        c, r = (m - 1) / 2.0, m / 4.0
        function = ("(coordsX-{c})^2+(coordsY-{c})^2+(coordsZ-{c})^2"
                    "+1e9*((coordsX>{c})*(abs(coordsY-{c})<coordsX-{c}))").format(c=c)
        return (Calculator(Input=Wavelet(WholeExtent=[0, m - 1] * 3), ResultArrayName="PacMan",
                           Function=function),
                dict(Scalars=["POINTS", "PacMan"], SelectionMode="Range", LowerThreshold=-1.0,
                     UpperThreshold=r * r + 0.3), m ** 3)
    if name == "phantom":
        return (VoxelPhantom(Dimensions=[n, n, n]),
                dict(Scalars=["POINTS", "Labels"], SelectionMode="Positive"), n ** 3)
    reader = berea_reader()
    if reader is None:
        return None
    return (reader[0], dict(Scalars=["POINTS", "values"], SelectionMode="Range",
                            LowerThreshold=0.0, UpperThreshold=0.0), reader[1])


FILTERS = {
    "EVM": lambda source, sel: EVMBoundary(Input=source, OutputMode="Triangles", **sel),
    "CUDB": lambda source, sel: CUDBConnectivity(Input=source, GenerateBoxes=0, **sel),
    "Polyhedrizer": lambda source, sel: StandardPlanePolyhedrizer(Input=source, **sel),
    "Hull": lambda source, sel: ConvexHullModifier(Input=source, **sel),
    "FaceOctree": lambda source, sel: FaceOctreeBoundary(Input=source, **sel),
}


def bytes_exchanged(proxy):
    data = sm.Fetch(proxy) if ranks > 1 else None
    if data is None or data.GetFieldData().GetArray("BytesExchanged") is None:
        return 0
    return int(data.GetFieldData().GetArray("BytesExchanged").GetValue(0))


def time_updates(proxy, selection):
    """Median seconds of `args.repeat` updates, each with a new threshold (a real update)."""
    proxy.UpdatePipeline()  # the first run (and the source's)
    times = []
    for k in range(args.repeat):
        if selection["SelectionMode"] == "Range":
            proxy.UpperThreshold = selection["UpperThreshold"] + 1e-9 * (k % 2 + 1)
        else:
            proxy.BackgroundValue = -1e-9 * (k % 2 + 1)  # Positive ignores it: re-executes
        start = time.perf_counter()
        proxy.UpdatePipeline()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


print("| input | filter | ranks | median s | bytes exchanged | voxels | bytes per voxel |")
print("|---|---|---|---|---|---|---|")
for input_name in args.inputs.split(","):
    made = make_input(input_name)
    if made is None:
        continue
    source, selection, voxels = made
    for filter_name in args.filters.split(","):
        if (filter_name == "Hull") != (input_name == "pacman"):
            continue
        proxy = FILTERS[filter_name](source, selection)
        seconds = time_updates(proxy, selection)
        exchanged = bytes_exchanged(proxy)
        print("| %s | %s | %d | %.3f | %d | %d | %.4f |" % (
            input_name, filter_name, ranks, seconds, exchanged, voxels, exchanged / voxels))
        sys.stdout.flush()
        Delete(proxy)
    Delete(source)
