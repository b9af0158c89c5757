"""Distributed runs: time and bytes exchanged of EVM Boundary and CUDB Connectivity on the
ranks this pvbatch runs on, against the voxels of the volume.

Usage: mpiexec -n N pvbatch BenchDistributed.py /path/to/VoxelBRep.so [size] [repeat]

The input is ParaView's Wavelet source (each rank computes its own piece) of size^3 points,
thresholded at RTData >= 150 (a smooth field: a few large components). Prints one
line per filter: ranks, median seconds of an update, the bytes the ranks exchanged for it
(field data BytesExchanged: the extreme vertices sent to rank 0 and what rank 0 sends back),
the bytes of the selection as one byte per voxel, and their ratio. On one rank nothing is
exchanged.
"""

import statistics
import sys
import time

from paraview import servermanager as sm
from paraview.simple import *  # noqa: F401,F403

LoadPlugin(sys.argv[1], remote=False, ns=globals())
size = int(sys.argv[2]) if len(sys.argv) > 2 else 128
repeat = int(sys.argv[3]) if len(sys.argv) > 3 else 3
ranks = sm.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()

wavelet = Wavelet(WholeExtent=[0, size - 1] * 3)
selection = dict(Scalars=["POINTS", "RTData"], SelectionMode="Range", LowerThreshold=150.0,
                 UpperThreshold=1000.0)
filters = {
    "EVM Boundary (Triangles)": EVMBoundary(Input=wavelet, OutputMode="Triangles", **selection),
    "CUDB Connectivity": CUDBConnectivity(Input=wavelet, GenerateBoxes=0, **selection),
}


def bytes_exchanged(proxy):
    data = sm.Fetch(proxy) if ranks > 1 else None
    if data is None or data.GetFieldData().GetArray("BytesExchanged") is None:
        return 0
    return int(data.GetFieldData().GetArray("BytesExchanged").GetValue(0))


print("| filter | ranks | size | median s | bytes exchanged | voxel bytes | ratio |")
print("|---|---|---|---|---|---|---|")
for name, proxy in filters.items():
    proxy.UpdatePipeline()  # the first run (and the source's)
    times = []
    for k in range(repeat):
        proxy.LowerThreshold = 150.0 + 1e-9 * (k % 2 + 1)  # a new value: a real update
        start = time.perf_counter()
        proxy.UpdatePipeline()
        times.append(time.perf_counter() - start)
    exchanged = bytes_exchanged(proxy)
    voxels = size ** 3
    print("| %s | %d | %d^3 | %.3f | %d | %d | %.4f |" % (
        name, ranks, size, statistics.median(times), exchanged, voxels, exchanged / voxels))
