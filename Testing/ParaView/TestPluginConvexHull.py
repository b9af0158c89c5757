"""pvbatch test of the plugin's Convex Hull Modifier: a pac-man (a digital ball with a wedge cut
out, the paper's example) through the server manager; Separates, the reversion against the
mask (numpy), every point a voxel centre with its VoxelMark, the hull's faces fewer than the
polyhedron's, then (with a baseline) an image of the triangles coloured by Level.

Usage: pvbatch TestPluginConvexHull.py /path/to/VoxelBRep.so [BASELINE.png TEMP_DIR]
"""

import sys

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from pvtest import compare_with_baseline, expect, field, finish, render_view
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonDataModel import vtkImageData


def pac_man(r=10):
    n = 2 * r + 3
    z, y, x = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
    c = r + 1
    ball = (x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 <= r * r
    mouth = (x - c > 0) & (np.abs(y - c) < 0.6 * (x - c))
    return (ball & ~mouth).astype(np.uint8)


def source_of(mask):
    image = vtkImageData()
    nz, ny, nx = mask.shape
    image.SetDimensions(nx, ny, nz)
    array = ns.numpy_to_vtk(mask.ravel(), deep=1)
    array.SetName("mask")
    image.GetPointData().SetScalars(array)
    src = TrivialProducer()
    src.GetClientSideObject().SetOutput(image)
    return src


def modifier(src, mode):
    f = ConvexHullModifier(Input=src)
    f.Scalars = ["POINTS", "mask"]
    f.SelectionMode = "Positive"
    f.OutputMode = mode
    f.UpdatePipeline()
    return f


def check_values(src, mask):
    f = modifier(src, "Triangles")
    out = servermanager.Fetch(f, idx=0)
    expect("separates", field(out, "Separates"), 1)
    expect("a concavity", field(out, "NumberOfConcavities") >= 1, True)
    p = ns.vtk_to_numpy(out.GetPoints().GetData())
    idx = np.rint(p).astype(np.int64)
    expect("points are voxel centres", bool(np.allclose(p, idx)), True)
    marks = ns.vtk_to_numpy(out.GetPointData().GetArray("VoxelMark"))
    expect("VoxelMark", bool((marks == mask[idx[:, 2], idx[:, 1], idx[:, 0]]).all()), True)
    back = servermanager.Fetch(f, idx=1)
    sel = ns.vtk_to_numpy(back.GetPointData().GetArray("Selection")).reshape(mask.shape)
    expect("reversion equals the mask", bool((sel == mask).all()), True)
    faces = field(out, "NumberOfFaces")
    f.OutputMode = "ConvexHull"
    f.UpdatePipeline()
    hull = servermanager.Fetch(f, idx=0)
    expect("hull faces below the polyhedron's", hull.GetNumberOfCells() < faces, True)
    Delete(f)


def check_image(src, baseline, temp_dir):
    f = modifier(src, "Triangles")
    view = render_view()
    display = Show(OutputPort(f, 0), view)
    ColorBy(display, ("CELLS", "Level"))
    lut = GetColorTransferFunction("Level")
    lut.ApplyPreset("Rainbow Uniform", True)
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, False)
    compare_with_baseline(view, (11, 11, 11), (70, 45, 40), baseline, temp_dir)


def main():
    LoadPlugin(sys.argv[1], remote=False, ns=globals())
    mask = pac_man()
    src = source_of(mask)
    check_values(src, mask)
    if len(sys.argv) > 3:
        check_image(src, sys.argv[2], sys.argv[3])
    finish()


main()
