"""pvbatch test of the plugin's Face Octree Boundary: Voxel Phantom -> Face Octree Boundary
through the server manager; its output checked against numpy on the phantom's scalars
fetched from the server (boundary voxels, closedness, one box per face node, fewer cells
than its triangulation, MaximumDistance within a voxel diagonal), then (with a
baseline) an image of the boundary coloured by face node beside its face octree.

Usage: pvbatch TestPluginFaceOctree.py /path/to/VoxelBRep.so [BASELINE.png TEMP_DIR]
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


def boundary_voxels(mask):
    padded = np.pad(mask, 1)
    inner = ndimage.binary_erosion(padded, structure=np.ones((3, 3, 3)), border_value=0)
    return int((padded & ~inner).sum())


def check_values(phantom, dims):
    image = servermanager.Fetch(phantom)
    labels = ns.vtk_to_numpy(image.GetPointData().GetArray("Labels")).reshape(dims[::-1])
    mask = labels > 0
    f = FaceOctreeBoundary(Input=phantom)
    f.Scalars = ["POINTS", "Labels"]
    f.SelectionMode = "Positive"  # the plugin's default is Range
    f.UpdatePipeline()
    out = servermanager.Fetch(f, idx=0)
    expect("NumberOfBoundaryVoxels", field(out, "NumberOfBoundaryVoxels"), boundary_voxels(mask))
    conn = ns.vtk_to_numpy(out.GetPolys().GetConnectivityArray())
    offsets = ns.vtk_to_numpy(out.GetPolys().GetOffsetsArray())
    directed = set()
    twice = False
    for c in range(len(offsets) - 1):
        ids = conn[offsets[c]:offsets[c + 1]]
        for i in range(len(ids)):
            e = (int(ids[i]), int(ids[(i + 1) % len(ids)]))
            twice = twice or e in directed
            directed.add(e)
    expect("closed and oriented",
           (not twice) and all((b, a) in directed for (a, b) in directed), True)
    octree = servermanager.Fetch(f, idx=1)
    expect("one box per face node", octree.GetNumberOfCells(), field(out, "NumberOfFaceNodes"))
    distance = out.GetFieldData().GetArray("MaximumDistance").GetValue(0)
    expect("MaximumDistance within the voxel diagonal", distance <= 3 ** 0.5, True)
    f.OutputMode = "Triangles"
    f.UpdatePipeline()
    tri = servermanager.Fetch(f, idx=0)
    expect("Triangles: NumberOfTriangles", field(tri, "NumberOfTriangles"), tri.GetNumberOfCells())
    expect("Polygons: fewer cells than Triangles",
           out.GetNumberOfCells() < tri.GetNumberOfCells(), True)
    Delete(f)


def check_image(phantom, baseline, temp_dir):
    f = FaceOctreeBoundary(Input=phantom)
    f.Scalars = ["POINTS", "Labels"]
    f.SelectionMode = "Positive"
    f.OutputMode = "Polygons"
    view = render_view()
    display = Show(OutputPort(f, 0), view)
    ColorBy(display, ("CELLS", "NodeLevel"))
    lut = GetColorTransferFunction("NodeLevel")
    lut.ApplyPreset("Rainbow Uniform", True)
    lut.RescaleTransferFunction(-1.0, 5.0)
    display.SetScalarBarVisibility(view, False)
    boxes = Show(OutputPort(f, 1), view)
    boxes.SetRepresentationType("Outline")
    ColorBy(boxes, ('CELLS', 'NodeLevel'))
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
