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
from vtkmodules.util import numpy_support as ns

failures = []


def expect(what, got, expected):
    status = "ok" if got == expected else "FAILED"
    print("%-60s %-6s got %r, expected %r" % (what, status, got, expected))
    if got != expected:
        failures.append(what)


def field(data, name):
    return int(data.GetFieldData().GetArray(name).GetValue(0))


def surfel_count(mask):
    p = np.pad(mask.astype(np.int8), 1)
    return sum(int(np.count_nonzero(np.diff(p, axis=a))) for a in range(3))


def check_values(phantom, dims):
    image = servermanager.Fetch(phantom)
    labels = ns.vtk_to_numpy(image.GetPointData().GetArray("Labels")).reshape(dims[::-1])
    mask = labels > 0
    poly = StandardPlanePolyhedrizer(Input=phantom)
    poly.Scalars = ["POINTS", "Labels"]
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
    poly.OutputMode = "Standard Faces"
    poly.UpdatePipeline()
    expect("one polygon per face", servermanager.Fetch(poly, idx=0).GetNumberOfCells(), faces)
    reversion = StandardPlaneReversion(Input=OutputPort(poly, 0))
    reversion.UpdatePipeline()
    voxels = servermanager.Fetch(reversion)
    back = ns.vtk_to_numpy(voxels.GetCellData().GetArray("Selection")).reshape(dims[::-1])
    expect("Standard Plane Reversion equals the selection", bool((back == mask).all()), True)
    Delete(reversion)
    Delete(poly)


def check_image(phantom, baseline, temp_dir):
    from vtkmodules.test import Testing
    Testing.VTK_TEMP_DIR = temp_dir
    poly = StandardPlanePolyhedrizer(Input=phantom)
    poly.Scalars = ["POINTS", "Labels"]
    poly.OutputMode = "Surfels"
    view = CreateView("RenderView")
    view.ViewSize = [400, 400]
    view.OrientationAxesVisibility = 0
    try:  # ParaView >= 5.10: the palette would override the background
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.Background = [0.92, 0.93, 0.95]
    display = Show(OutputPort(poly, 0), view)
    ColorBy(display, ("CELLS", "FaceId"))
    lut = GetColorTransferFunction("FaceId")
    lut.ApplyPreset("Rainbow Uniform", True)
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, False)
    view.CameraFocalPoint = [24, 24, 24]
    view.CameraPosition = [24 + 60, 24 - 95, 24 + 80]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    Render(view)
    # Raises (and so fails the test) when the images differ or the baseline is missing.
    Testing.compareImage(view.GetRenderWindow(), baseline, threshold=10)
    print("image matches", baseline)


def main():
    LoadPlugin(sys.argv[1], remote=False, ns=globals())
    dims = (48, 48, 48)
    phantom = VoxelPhantom(Dimensions=list(dims))
    check_values(phantom, dims)
    if len(sys.argv) > 3:
        check_image(phantom, sys.argv[2], sys.argv[3])
    if failures:
        print("FAILED:", failures)
        sys.exit(1)


main()
