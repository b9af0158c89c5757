"""pvbatch test of the plugin's Standard Plane Polyhedrizer: Voxel Phantom -> Standard Plane
Polyhedrizer through the server manager; its outputs checked against numpy on the phantom's
scalars fetched from the server (surfel count, every surfel corner in its face's standard
plane, the reversion equal to the selection), then (with a baseline) an image of the surfels
coloured by face.

Usage: pvbatch TestPluginPolyhedrizer.py /path/to/VoxelBRep.so [BASELINE.png TEMP_DIR]
Without the baseline arguments only the values are checked (no display needed). When the
baseline is missing the image is written to TEMP_DIR and the test fails.
"""

import sys

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from pvtest import compare_with_baseline, expect, field, finish, render_view
from voxelbrep_testing import surfel_count
from vtkmodules.util import numpy_support as ns


def check_values(phantom, dims):
    image = servermanager.Fetch(phantom)
    labels = ns.vtk_to_numpy(image.GetPointData().GetArray("Labels")).reshape(dims[::-1])
    mask = labels > 0
    poly = StandardPlanePolyhedrizer(Input=phantom)
    poly.Scalars = ["POINTS", "Labels"]
    poly.SelectionMode = "Positive"  # the plugin's default is Range
    poly.OutputMode = "Surfels"
    poly.UpdatePipeline()
    out = servermanager.Fetch(poly, idx=0)
    expect("one quad per surfel", out.GetNumberOfCells(), surfel_count(mask))
    # Corners in voxel-corner index space (unit spacing, origin 0, point data).
    corners = np.rint(ns.vtk_to_numpy(out.GetPoints().GetData()) + 0.5).astype(np.int64)
    quads = ns.vtk_to_numpy(out.GetPolys().GetConnectivityArray()).reshape(-1, 4)
    normal = ns.vtk_to_numpy(out.GetCellData().GetArray("PlaneNormal")).astype(np.int64)
    mu = ns.vtk_to_numpy(out.GetCellData().GetArray("PlaneOffset")).astype(np.int64)
    value = np.einsum("cij,cj->ci", corners[quads], normal)
    omega = np.abs(normal).sum(axis=1)
    expect("every surfel corner in its standard plane",
           bool(((value >= mu[:, None]) & (value < (mu + omega)[:, None])).all()), True)
    faces = field(out, "NumberOfFaces")
    expect("fewer faces than surfels / 10", faces * 10 < out.GetNumberOfCells(), True)
    reversion = servermanager.Fetch(poly, idx=1)
    back = ns.vtk_to_numpy(reversion.GetPointData().GetArray("Selection")).reshape(dims[::-1])
    expect("reversion equals the selection", bool((back == mask).all()), True)
    poly.OutputMode = "StandardFaces"
    poly.UpdatePipeline()
    expect("one polygon per face", servermanager.Fetch(poly, idx=0).GetNumberOfCells(), faces)
    reversion = StandardPlaneReversion(Input=OutputPort(poly, 0))
    reversion.UpdatePipeline()
    voxels = servermanager.Fetch(reversion)
    # Both reversions have the layout of the input (here point data on the phantom's grid).
    back = ns.vtk_to_numpy(voxels.GetPointData().GetArray("Selection")).reshape(dims[::-1])
    expect("Standard Plane Reversion equals the selection", bool((back == mask).all()), True)
    Delete(reversion)
    Delete(poly)


def check_image(phantom, baseline, temp_dir):
    poly = StandardPlanePolyhedrizer(Input=phantom)
    poly.Scalars = ["POINTS", "Labels"]
    poly.SelectionMode = "Positive"  # the plugin's default is Range
    poly.OutputMode = "Surfels"
    view = render_view()
    display = Show(OutputPort(poly, 0), view)
    ColorBy(display, ("CELLS", "FaceId"))
    lut = GetColorTransferFunction("FaceId")
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
