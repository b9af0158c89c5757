"""The 1-rank results the distributed test compares with: the project's filters run by plain
VTK Python in a process of their own (no MPI, no ParaView pipeline, the whole image at once).

Usage: python3 single_process_reference.py RUNS.json IMAGE.npz OUT.json
(with PYTHONPATH at the built `voxelbrep` package).

IMAGE.npz holds `values` ([z, y, x]), `cells` (the values are cell data) and `name` (the
array's name). RUNS.json is a list of runs, each {"key", "class", "calls": [[method, args],
...], "fields": [...]}: the filter `voxelbrep.<class>` on that image after the calls. OUT.json
maps each key to the filter's port-0 field values named in "fields", its number of cells and,
when it has a second image port with a Selection, that Selection's number of ones.
"""

import json
import sys

import numpy as np
import voxelbrep
from voxelbrep_testing import make_image
from vtkmodules.util import numpy_support as ns


def selection_count(image):
    attributes = image.GetPointData() if image.GetPointData().GetArray("Selection") \
        else image.GetCellData()
    array = attributes.GetArray("Selection")
    return None if array is None else int(ns.vtk_to_numpy(array).astype(bool).sum())


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
    if f.GetNumberOfOutputPorts() > 1 and f.GetOutputDataObject(1).IsA("vtkImageData"):
        result["selected"] = selection_count(f.GetOutputDataObject(1))
    return result


def main():
    runs = json.load(open(sys.argv[1]))
    data = np.load(sys.argv[2])
    image = make_image(data["values"], cell_data=bool(data["cells"]), name=str(data["name"]))
    json.dump({spec["key"]: run(spec, image) for spec in runs}, open(sys.argv[3], "w"))


main()
