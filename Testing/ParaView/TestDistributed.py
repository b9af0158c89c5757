"""EVM Boundary and CUDB Connectivity on N ranks (mpiexec -n N pvbatch) against numpy and
scipy on the whole image.

Usage: mpiexec -n N pvbatch TestDistributed.py /path/to/VoxelBRep.so

ParaView's Wavelet source hands every rank a piece of the image (neighbouring pieces share a
plane of points). With point and with cell scalars, with no ghost layer and with two ghost
layers (ParaView's Ghost Cells Generator, as Contour and other filters ask for them), the
boundary fetched from all ranks must be the one of
the whole image: the same voxels, extreme vertices, surfels, faces and holes as numpy counts
on the whole image (voxelbrep_testing, independent of the filter), its triangles covering
exactly the surfels' area once (no face twice, none cut at the pieces). The RegionIds of
CUDB Connectivity, gathered from every rank's piece, must give scipy.ndimage.label's partition
of the whole image with one id per component on all ranks, numbered largest first.
"""

import builtins
import sys

import numpy as np
import scipy.ndimage
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


def pieces_source(association, ghosts):
    source = Wavelet(WholeExtent=EXTENT)
    if association == "CELLS":
        source = PointDatatoCellData(Input=source)
    if ghosts:
        source = GhostCellsGenerator(Input=source, BuildIfRequired=0, MinimumNumberOfGhosts=2)
    return source


# Run on every rank's piece: its RegionIds and voxel indices, saved for rank 0 to read (pvbatch
# runs this script on rank 0 only, and Fetch returns rank 0's piece of an image).
SAVE_PIECE = """
import numpy as np
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkParallelCore import vtkMultiProcessController
image = self.GetInputDataObject(0, 0)
self.GetOutputDataObject(0).ShallowCopy(image)
cells = %(cells)r
attributes = image.GetCellData() if cells else image.GetPointData()
e = image.GetExtent()
dims = [e[1] - e[0] + (0 if cells else 1), e[3] - e[2] + (0 if cells else 1),
        e[5] - e[4] + (0 if cells else 1)]
k, j, i = np.meshgrid(*[np.arange(n) for n in dims[::-1]], indexing="ij")
index = np.stack([i.ravel() + e[0], j.ravel() + e[2], k.ravel() + e[4]], axis=1)
ghosts = attributes.GetArray("vtkGhostType")
keep = np.ones(len(index), bool) if ghosts is None else ns.vtk_to_numpy(ghosts) == 0
ids = ns.vtk_to_numpy(attributes.GetArray("RegionId"))
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
np.savez(%(folder)r + "/piece%%d.npz" %% rank, ids=ids[keep], index=index[keep])
"""


def gathered_region_ids(cudb, cells):
    """RegionIds and voxel indices of the non-ghost voxels of every rank's piece."""
    import glob
    import tempfile
    folder = tempfile.mkdtemp(prefix="voxelbrep-mpi-")
    saver = ProgrammableFilter(Input=cudb, CopyArrays=1,
                               Script=SAVE_PIECE % {"cells": cells, "folder": folder})
    saver.UpdatePipeline()
    pieces = [np.load(f) for f in sorted(glob.glob(folder + "/piece*.npz"))]
    expect("pieces saved by every rank", len(pieces), ranks)
    return (np.concatenate([p["ids"] for p in pieces]),
            np.concatenate([p["index"] for p in pieces]))


def check_cudb(association, ghosts):
    tag = "CUDB, %d ranks, %s scalars, %s: " % (ranks, association.lower(),
                                                 "with ghost layers" if ghosts else "no ghosts")
    cudb = CUDBConnectivity(Input=pieces_source(association, ghosts),
                            Scalars=[association, "RTData"], SelectionMode="Range",
                            LowerThreshold=LOWER, UpperThreshold=1000.0)
    ids, index = gathered_region_ids(cudb, association == "CELLS")
    cells = association == "CELLS"
    labels, count = scipy.ndimage.label(whole_values(cells) >= LOWER)
    expected = labels[index[:, 2], index[:, 1], index[:, 0]]
    pairs = set(zip(expected.tolist(), ids.tolist()))
    expect(tag + "unselected voxels have RegionId 0",
           builtins.all((e == 0) == (r == 0) for e, r in pairs), True)
    expect(tag + "one RegionId per component, on every rank",
           len({e for e, r in pairs if e}) == len({r for e, r in pairs if r}) == len(
               [1 for e, r in pairs if e]), True)
    sizes = np.bincount(labels.ravel())[1:]
    by_id = {r: sizes[e - 1] for e, r in pairs if e}
    expect(tag + "every component seen", len(by_id), count)
    expect(tag + "numbered largest first",
           [by_id[r] for r in sorted(by_id)] == sorted(sizes.tolist(), reverse=True), True)


for association in ("POINTS", "CELLS"):
    for ghosts in (False, True):
        check(association, ghosts)
        check_cudb(association, ghosts)
finish()
