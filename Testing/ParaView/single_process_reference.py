"""The 1-rank results the distributed test compares with: the project's filters run by plain
VTK Python in a process of their own (no MPI, no ParaView pipeline, the whole image at once).

Usage (with PYTHONPATH at the built `voxelbrep` package):
  python3 single_process_reference.py RUNS.json IMAGE.npz OUT.json
  python3 single_process_reference.py --phantom NX NY NZ OUT.npy

IMAGE.npz holds `values` ([z, y, x]), `cells` (the values are cell data) and `name` (the
array's name). RUNS.json is a list of runs, each {"key", "class", "calls": [[method, args],
...], "fields": [...]}: the filter `voxelbrep.<class>` on that image after the calls. OUT.json
maps each key to the filter's port-0 field values named in "fields" and its number of cells.
With --phantom, OUT.npy is the Labels array of vtkVoxelPhantomSource of NX x NY x NZ voxels
(x fastest).
"""

import json
import sys

import numpy as np
import voxelbrep
from voxelbrep_testing import make_image
from vtkmodules.util import numpy_support as ns


def run(spec, image):
    f = getattr(voxelbrep, spec["class"])()
    f.SetInputData(image)
    for method, args in spec["calls"]:
        getattr(f, method)(*args)
    f.Update()
    out = f.GetOutputDataObject(0)
    result = {"cells": out.GetNumberOfCells()}
    for name in spec["fields"]:
        array = out.GetFieldData().GetArray(name)
        result[name] = None if array is None else int(array.GetValue(0))
    return result


def phantom(dims, path):
    source = voxelbrep.vtkVoxelPhantomSource()
    source.SetDimensions(*dims)
    source.Update()
    np.save(path, ns.vtk_to_numpy(source.GetOutput().GetPointData().GetArray("Labels")))


def main():
    if sys.argv[1] == "--phantom":
        phantom([int(v) for v in sys.argv[2:5]], sys.argv[5])
        return
    runs = json.load(open(sys.argv[1]))
    data = np.load(sys.argv[2])
    image = make_image(data["values"], cell_data=bool(data["cells"]), name=str(data["name"]))
    json.dump({spec["key"]: run(spec, image) for spec in runs}, open(sys.argv[3], "w"))


main()
