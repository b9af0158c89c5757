"""pvbatch test of the plugin's CUDB Connectivity: Voxel Phantom -> CUDB Connectivity through
the server manager, its three outputs checked against scipy.ndimage.label on the phantom's
scalars fetched from the server, then (with a baseline) an image of the boxes coloured by
RegionId.

Usage: pvbatch TestPluginCUDB.py /path/to/VoxelBRep.so [BASELINE.png TEMP_DIR]
Without the baseline arguments only the values are checked (no display needed). When the
baseline is missing the image is written to TEMP_DIR and the test fails.
"""

import sys

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from pvtest import compare_with_baseline, expect, field, finish, render_view
from scipy import ndimage
from vtkmodules.util import numpy_support as ns


def reference(mask, vertex):
    """scipy labels renumbered by size, largest first, ties by first voxel (scan order)."""
    labels, n = ndimage.label(mask, ndimage.generate_binary_structure(3, 3 if vertex else 1))
    sizes = np.bincount(labels.ravel())[1:]
    rank = np.argsort(-sizes, kind="stable")  # scipy numbers in scan order
    renumber = np.zeros(n + 1, dtype=np.int64)
    renumber[rank + 1] = np.arange(1, n + 1)
    return renumber[labels], n


def check_values(phantom, dims):
    image = servermanager.Fetch(phantom)
    labels = ns.vtk_to_numpy(image.GetPointData().GetArray("Labels")).reshape(dims[::-1])
    cudb = CUDBConnectivity(Input=phantom)
    cudb.Scalars = ["POINTS", "Labels"]
    cudb.SelectionMode = "Positive"  # the plugin's default is Range
    for vertex in (False, True):
        cudb.Connectivity = 1 if vertex else 0
        cudb.UpdatePipeline()
        tag = "Positive, %s" % ("vertex" if vertex else "face")
        out = servermanager.Fetch(cudb, idx=0)
        ids = ns.vtk_to_numpy(out.GetPointData().GetArray("RegionId")).reshape(dims[::-1])
        expected, n = reference(labels > 0, vertex)
        expect(tag + ": NumberOfRegions", field(out, "NumberOfRegions"), n)
        expect(tag + ": RegionId equals scipy's, size-ranked", bool((ids == expected).all()), True)
        boxes = servermanager.Fetch(cudb, idx=1)
        expect(tag + ": one cell per box", boxes.GetNumberOfCells(), field(out, "NumberOfBoxes"))
        expect(tag + ": fewer boxes than the OUDB",
               field(out, "NumberOfBoxes") <= field(out, "NumberOfOUDBBoxes"), True)
        table = servermanager.Fetch(cudb, idx=2)
        counts = ns.vtk_to_numpy(table.GetColumnByName("VoxelCount"))
        expect(tag + ": table VoxelCount", counts.tolist(),
               np.bincount(expected.ravel())[1:].tolist())
    # Labels mode: components within each label.
    cudb.SelectionMode = "Labels"
    cudb.Connectivity = 0
    cudb.RegionOrdering = 1  # sweep order
    cudb.UpdatePipeline()
    out = servermanager.Fetch(cudb, idx=0)
    total = sum(ndimage.label(labels == k)[1] for k in np.unique(labels) if k != 0)
    expect("Labels: NumberOfRegions = sum over labels", field(out, "NumberOfRegions"), total)
    Delete(cudb)


def check_image(phantom, baseline, temp_dir):
    cudb = CUDBConnectivity(Input=phantom)
    cudb.Scalars = ["POINTS", "Labels"]
    cudb.SelectionMode = "Positive"  # the plugin's default is Range
    cudb.SortingOrder = "Auto"
    view = render_view()
    display = Show(OutputPort(cudb, 1), view)
    display.SetRepresentationType("Surface With Edges")
    ColorBy(display, ("CELLS", "RegionId"))
    lut = GetColorTransferFunction("RegionId")
    lut.ApplyPreset("Rainbow Uniform", True)
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, False)
    compare_with_baseline(view, (24, 24, 24), (60, -95, 80), baseline, temp_dir)


def main():
    LoadPlugin(sys.argv[1], remote=False, ns=globals())
    dims = (48, 48, 48)
    phantom = VoxelPhantom(Dimensions=list(dims))
    check_values(phantom, dims)
    if len(sys.argv) > 3:
        check_image(phantom, sys.argv[2], sys.argv[3])
    finish()


main()
