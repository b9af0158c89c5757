"""EVM Boundary on N ranks (mpiexec -n N pvbatch) against numpy on the whole image.

Usage: mpiexec -n N pvbatch TestDistributed.py /path/to/VoxelBRep.so

ParaView's Wavelet source hands every rank a piece of the image (neighbouring pieces share a
plane of points). With point and with cell scalars, with no ghost layer and with two ghost
layers (ParaView's Ghost Cells Generator, as Contour and other filters ask for them), the
boundary fetched from all ranks must be the one of
the whole image: the same voxels, extreme vertices, surfels, faces and holes as numpy counts
on the whole image (voxelbrep_testing, independent of the filter), its triangles covering
exactly the surfels' area once (no face twice, none cut at the pieces).
"""

import sys

import numpy as np
from paraview import servermanager as sm
from paraview.simple import *  # noqa: F401,F403
from pvtest import expect, field, finish
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkFiltersCore import vtkPointDataToCellData
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource

from voxelbrep_testing import extreme_vertices, faces_and_holes_3d, surfel_count

LoadPlugin(sys.argv[1], remote=False, ns=globals())
ranks = sm.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
EXTENT = [0, 36, 0, 29, 0, 25]
LOWER = 150.0


def whole_values(cells):
    """RTData of the whole image on this process alone, [z, y, x] (the reference)."""
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(*EXTENT)
    source.Update()
    image = source.GetOutput()
    dims = [EXTENT[1] + 1, EXTENT[3] + 1, EXTENT[5] + 1]
    if cells:
        average = vtkPointDataToCellData()
        average.SetInputData(image)
        average.Update()
        values = average.GetOutput().GetCellData().GetArray("RTData")
        dims = [d - 1 for d in dims]
    else:
        values = image.GetPointData().GetArray("RTData")
    return ns.vtk_to_numpy(values).reshape(dims[2], dims[1], dims[0])


def triangle_area(polydata):
    from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter
    sizes = vtkCellSizeFilter()
    sizes.SetInputData(polydata)
    sizes.ComputeAreaOn()
    sizes.Update()
    return float(ns.vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Area")).sum())


def check(association, ghosts):
    tag = "%d ranks, %s scalars, %s: " % (ranks, association.lower(),
                                           "with a ghost layer" if ghosts else "no ghosts")
    source = Wavelet(WholeExtent=EXTENT)
    if association == "CELLS":
        source = PointDatatoCellData(Input=source)
    if ghosts:
        source = GhostCellsGenerator(Input=source, BuildIfRequired=0, MinimumNumberOfGhosts=2)
    boundary = EVMBoundary(Input=source, Scalars=[association, "RTData"], SelectionMode="Range",
                           LowerThreshold=LOWER, UpperThreshold=1000.0, OutputMode="Triangles")
    boundary.UpdatePipeline()
    data = sm.Fetch(boundary)
    if ghosts and ranks > 1:
        ghost_arrays = sm.Fetch(source).GetCellData().GetArray("vtkGhostType")
        expect(tag + "the input has ghost cells", ghost_arrays is not None, True)
    mask = whole_values(association == "CELLS") >= LOWER
    faces, holes = faces_and_holes_3d(mask, merge_non_manifold=False)
    expect(tag + "voxels", field(data, "NumberOfVoxels"), int(mask.sum()))
    expect(tag + "extreme vertices", field(data, "NumberOfExtremeVertices"), extreme_vertices(mask))
    expect(tag + "surfels", field(data, "NumberOfSurfels"), surfel_count(mask))
    expect(tag + "faces", field(data, "NumberOfFaces"), faces)
    expect(tag + "holes", field(data, "NumberOfHoles"), holes)
    expect(tag + "triangles cover the surfels once", round(triangle_area(data), 6),
           float(surfel_count(mask)))
    expect(tag + "ranks that took part", field(data, "NumberOfRanks"), ranks if ranks > 1 else None)


for association in ("POINTS", "CELLS"):
    for ghosts in (False, True):
        check(association, ghosts)
finish()
