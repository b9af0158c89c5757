"""pvbatch smoke test of the VoxelBRep plugin: Voxel Phantom -> EVM Boundary through the
server manager, in Labels, Positive and Range modes and on a 2D phantom slice.

Usage: pvbatch TestPluginPipeline.py /path/to/VoxelBRep.so

The counts are checked against numpy computations on the phantom's scalars fetched from the
server (independent of the filter): NumberOfVoxels, NumberOfSurfels (0/1 transitions of the
padded mask) and NumberOfExtremeVertices (vertices with an odd number of the 8 incident
voxels selected: XOR of the 8 shifted padded masks).
"""

import sys

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from pvtest import expect, field, finish
from voxelbrep_testing import extreme_vertices, surfel_count
from vtkmodules.util import numpy_support as ns


def cell_values(data, name):
    array = data.GetCellData().GetArray(name)
    return None if array is None else ns.vtk_to_numpy(array)


def phantom_labels(source, dims):
    image = servermanager.Fetch(source)
    expect("phantom dimensions", list(image.GetDimensions()), list(dims))
    labels = ns.vtk_to_numpy(image.GetPointData().GetArray("Labels"))
    return labels.reshape(dims[2], dims[1], dims[0])


def check_output(tag, boundary, masks, planar=False):
    boundary.UpdatePipeline()
    out = servermanager.Fetch(boundary)
    expect(tag + ": has cells", out.GetNumberOfCells() > 0, True)
    expect(tag + ": NumberOfVoxels", field(out, "NumberOfVoxels"),
           sum(int(m.sum()) for m in masks.values()))
    expect(tag + ": NumberOfExtremeVertices", field(out, "NumberOfExtremeVertices"),
           sum(extreme_vertices(m) for m in masks.values()))
    if not planar:
        expect(tag + ": NumberOfSurfels", field(out, "NumberOfSurfels"),
               sum(surfel_count(m) for m in masks.values()))
    face_ids = cell_values(out, "FaceId")
    expect(tag + ": distinct FaceId = NumberOfFaces", len(set(face_ids.tolist())),
           field(out, "NumberOfFaces"))
    expect(tag + ": Label values", sorted(set(cell_values(out, "Label").tolist())),
           sorted(masks.keys()))
    expect(tag + ": ParentFace/Depth only in 2D",
           cell_values(out, "Depth") is not None, planar)
    return out


def main():
    plugin = sys.argv[1]
    LoadPlugin(plugin, remote=False, ns=globals())

    dims = (40, 36, 32)
    phantom = VoxelPhantom(Dimensions=list(dims))
    labels = phantom_labels(phantom, dims)
    present = [int(v) for v in np.unique(labels) if v != 0]
    expect("phantom holds labels 1..5", present, [1, 2, 3, 4, 5])

    boundary = EVMBoundary(Input=phantom)
    boundary.Scalars = ["POINTS", "Labels"]
    boundary.SelectionMode = "Labels"
    boundary.OutputMode = "Loops"
    out = check_output("Labels/Loops", boundary, {k: labels == k for k in present})
    expect("Labels/Loops: hole loops = NumberOfHoles",
           int(np.count_nonzero(cell_values(out, "LoopType") == 1)), field(out, "NumberOfHoles"))

    boundary.OutputMode = "Triangles"
    check_output("Labels/Triangles", boundary, {k: labels == k for k in present})

    boundary.SelectionMode = "Positive"
    check_output("Positive/Triangles", boundary, {1: labels > 0})

    boundary.SelectionMode = "Range"
    boundary.LowerThreshold = 2
    boundary.UpperThreshold = 4
    boundary.MergeNonManifoldFaces = 1
    check_output("Range [2, 4]/Triangles", boundary, {1: (labels >= 2) & (labels <= 4)})

    # A one-voxel-thick phantom is a 2D image: contours with their inclusion tree.
    flat = VoxelPhantom(Dimensions=[64, 48, 1])
    flat_labels = phantom_labels(flat, (64, 48, 1))[0]
    contours = EVMBoundary(Input=flat)
    contours.Scalars = ["POINTS", "Labels"]
    contours.SelectionMode = "Positive"
    contours.OutputMode = "Polylines"
    contours.FlatImagesAs2D = 1
    check_output("2D Positive/Polylines", contours, {1: flat_labels > 0}, planar=True)

    finish()
    print("all checks passed")


main()
