"""Every filter of the plugin on N ranks (mpiexec -n N pvbatch) against numpy and scipy on
the whole image and against the 1-rank result.

Usage: mpiexec -n N pvbatch TestDistributed.py /path/to/VoxelBRep.so PACKAGE_DIR [DATA_DIR]

PACKAGE_DIR holds the built `voxelbrep` Python package: the 1-rank results come from the
filters run by plain VTK Python on the whole image in a process of their own
(single_process_reference.py). DATA_DIR holds the shared real volumes (the headsq bone is
written as a partitioned .pvti of four pieces and read back by every rank); without it that
part is skipped.

ParaView's Wavelet source hands every rank a piece of the image (neighbouring pieces share a
plane of points). With point and with cell scalars, with no ghost layer and with two ghost
layers (ParaView's Ghost Cells Generator, as Contour and other filters ask for them), the
boundary fetched from all ranks must be the one of
the whole image: the same voxels, extreme vertices, surfels, faces and holes as numpy counts
on the whole image (voxelbrep_testing, independent of the filter), its triangles covering
exactly the surfels' area once (no face twice, none cut at the pieces). The RegionIds of
CUDB Connectivity, gathered from every rank's piece, must give scipy.ndimage.label's partition
of the whole image with one id per component on all ranks, numbered largest first.
The Standard Plane Polyhedrizer, the Convex Hull Modifier and the Face Octree Boundary must give
the 1-rank counts (faces, surfels, vertices, face nodes, polygons, cells), and the reversion
gathered from every rank's piece must be the selection of the whole image. The Voxel Phantom
source must hand each rank its own piece, which together are the 1-process phantom.
"""

import atexit
import builtins
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
import scipy.ndimage
from paraview import servermanager as sm
from paraview.simple import *  # noqa: F401,F403
from pvtest import expect, field, finish
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkFiltersCore import vtkPointDataToCellData
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource

from voxelbrep_testing import extreme_vertices, faces_and_holes_3d, surfel_count
from voxelbrep_testing import write_partitioned

LoadPlugin(sys.argv[1], remote=False, ns=globals())
PACKAGE_DIR = sys.argv[2]
DATA_DIR = sys.argv[3] if len(sys.argv) > 3 else ""
HERE = os.path.dirname(os.path.abspath(__file__))
# The test's scratch folders (pieces saved by the ranks, references, the partitioned headsq)
# live in one, removed when the test ends.
SCRATCH = tempfile.mkdtemp(prefix="voxelbrep-distributed-")
atexit.register(shutil.rmtree, SCRATCH, True)
ranks = sm.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
EXTENT = [0, 36, 0, 29, 0, 25]
LOWER = 150.0


# A pac-man (a ball with a wedge cut out: one concavity) as the values of a Calculator on the
# Wavelet's grid: selected by Range [-1, PACMAN_RADIUS2], the one object the Convex Hull
# Modifier separates among these inputs (the Wavelet's blobs have touching voxels).
PACMAN = ("(coordsX-18)^2+(coordsY-15)^2+(coordsZ-12)^2"
          "+1000*((coordsX>18)*(abs(coordsY-15)<coordsX-18))")
PACMAN_RADIUS2 = 100.3  # no value of points or cells (multiples of 1/8) this close


def whole_values(cells, array="RTData"):
    """`array` (RTData or PacMan) of the whole image on this process alone, [z, y, x] (the
    reference)."""
    from vtkmodules.vtkFiltersCore import vtkArrayCalculator
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(*EXTENT)
    last = source
    if array == "PacMan":
        last = vtkArrayCalculator()
        last.SetInputConnection(source.GetOutputPort())
        for k, axis in enumerate("XYZ"):
            last.AddCoordinateScalarVariable("coords" + axis, k)
        last.SetFunction(PACMAN)
        last.SetResultArrayName("PacMan")
    last.Update()
    image = last.GetOutput()
    dims = [EXTENT[1] + 1, EXTENT[3] + 1, EXTENT[5] + 1]
    if cells:
        average = vtkPointDataToCellData()
        average.SetInputData(image)
        average.Update()
        values = average.GetOutput().GetCellData().GetArray(array)
        dims = [d - 1 for d in dims]
    else:
        values = image.GetPointData().GetArray(array)
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


def pieces_source(association, ghosts, pacman=False):
    source = Wavelet(WholeExtent=EXTENT)
    if pacman:
        source = Calculator(Input=source, ResultArrayName="PacMan", Function=PACMAN)
    if association == "CELLS":
        source = PointDatatoCellData(Input=source)
    if ghosts:
        source = GhostCellsGenerator(Input=source, BuildIfRequired=0, MinimumNumberOfGhosts=2)
    return source


# Run on every rank's piece: the values of one of its arrays and their voxel indices (ghost
# voxels left out) and the piece's extent, saved for rank 0 to read (pvbatch runs this script
# on rank 0 only, and Fetch returns rank 0's piece of an image).
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
values = ns.vtk_to_numpy(attributes.GetArray(%(array)r))
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
np.savez(%(folder)r + "/piece%%d.npz" %% rank, values=values[keep], index=index[keep],
         extent=np.array(e))
"""


def gathered_pieces(port, cells, array):
    """The values of `array` and voxel indices of the non-ghost voxels of every rank's piece
    of `port`, and the pieces' extents."""
    folder = tempfile.mkdtemp(prefix="mpi-", dir=SCRATCH)
    saver = ProgrammableFilter(Input=port, CopyArrays=1,
                               Script=SAVE_PIECE % {"cells": cells, "folder": folder,
                                                    "array": array})
    saver.UpdatePipeline()
    pieces = [np.load(f) for f in sorted(glob.glob(folder + "/piece*.npz"))]
    expect("pieces saved by every rank", len(pieces), ranks)
    Delete(saver)
    return (np.concatenate([p["values"] for p in pieces]),
            np.concatenate([p["index"] for p in pieces]),
            [tuple(p["extent"]) for p in pieces])


def gathered_region_ids(cudb, cells):
    """RegionIds and voxel indices of the non-ghost voxels of every rank's piece."""
    ids, index, _ = gathered_pieces(cudb, cells, "RegionId")
    return ids, index


def check_cudb(association, ghosts):
    tag = "CUDB, %d ranks, %s scalars, %s: " % (ranks, association.lower(),
                                                 "with ghost layers" if ghosts else "no ghosts")
    cudb = CUDBConnectivity(Input=pieces_source(association, ghosts),
                            Scalars=[association, "RTData"], SelectionMode="Range",
                            LowerThreshold=LOWER, UpperThreshold=1000.0)
    cells = association == "CELLS"
    ids, index = gathered_region_ids(cudb, cells)
    check_partition(tag, ids, index, whole_values(cells) >= LOWER)


def check_partition(tag, ids, index, mask):
    """RegionIds gathered from the ranks (non-ghost voxels at `index`) against scipy's
    face-connected components of the whole `mask`: 0 outside, one id per component on every
    rank, every component seen, numbered largest first."""
    labels, count = scipy.ndimage.label(mask)
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


def child_environment():
    """A plain Python process with the built package: none of Open MPI's variables."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_"))}
    env["PYTHONPATH"] = os.pathsep.join(
        [PACKAGE_DIR, os.path.join(HERE, "..", "..", "Filters", "Testing", "Python")])
    return env


def single_process(runs, values, cells, name="RTData"):
    """The 1-rank results of `runs` (see single_process_reference.py) on the whole image."""
    folder = tempfile.mkdtemp(prefix="reference-", dir=SCRATCH)
    np.savez(folder + "/image.npz", values=values, cells=cells, name=name)
    with open(folder + "/runs.json", "w") as f:
        json.dump(runs, f)
    subprocess.run(["/usr/bin/python3", os.path.join(HERE, "single_process_reference.py"),
                    folder + "/runs.json", folder + "/image.npz", folder + "/out.json"],
                   check=True, env=child_environment())
    with open(folder + "/out.json") as f:
        return json.load(f)


# The filters whose results must equal the 1-rank ones: their proxy and VTK class, the output
# mode as a proxy property and as VTK calls, the field values compared, the array and range
# selected, and whether port 1 is their reversion.
POLY_FIELDS = ["NumberOfSurfels", "NumberOfFaces", "NumberOfStandardVertices",
               "NumberOfBoundaryComponents"]
HULL_FIELDS = ["NumberOfVertices", "NumberOfEdges", "NumberOfFaces", "NumberOfHullFaces",
               "NumberOfConcavities", "Separates"]
OCTREE_FIELDS = ["NumberOfBoundaryVoxels", "NumberOfFaceNodes", "NumberOfPolygons",
                 "NumberOfTriangles", "NumberOfPrunedVoxels"]
WHOLE_IMAGE_FILTERS = {
    "polyhedrizer": dict(proxy="StandardPlanePolyhedrizer", cls="vtkStandardPlanePolyhedrizer",
                         properties=dict(OutputMode="StandardFaces"),
                         calls=[("SetOutputModeToStandardFaces", [])], fields=POLY_FIELDS,
                         selected=("RTData", LOWER, 1000.0), reverts=True),
    "hull": dict(proxy="ConvexHullModifier", cls="vtkConvexHullModifier",
                 properties=dict(OutputMode="Polyhedron"),
                 calls=[("SetOutputModeToPolyhedron", [])], fields=HULL_FIELDS,
                 selected=("PacMan", -1.0, PACMAN_RADIUS2), reverts=True),
    "octree": dict(proxy="FaceOctreeBoundary", cls="vtkFaceOctreeBoundaryFilter",
                   properties=dict(OutputMode="Polygons"), calls=[("SetOutputModeToPolygons", [])],
                   fields=OCTREE_FIELDS, selected=("RTData", LOWER, 1000.0), reverts=False),
}


def references(cells):
    """The 1-rank results of WHOLE_IMAGE_FILTERS, by key."""
    out = {}
    for array in ("RTData", "PacMan"):
        runs = [{"key": key, "class": f["cls"],
                 "calls": [("SetSelectionModeToRange", []),
                           ("SetLowerThreshold", [f["selected"][1]]),
                           ("SetUpperThreshold", [f["selected"][2]])] + f["calls"],
                 "fields": f["fields"]}
                for key, f in WHOLE_IMAGE_FILTERS.items() if f["selected"][0] == array]
        out.update(single_process(runs, whole_values(cells, array), cells, array))
    return out


def check_whole_image_filters(association, ghosts, reference):
    tag = "%d ranks, %s scalars, %s: " % (ranks, association.lower(),
                                           "with ghost layers" if ghosts else "no ghosts")
    cells = association == "CELLS"
    for key, f in WHOLE_IMAGE_FILTERS.items():
        array, lower, upper = f["selected"]
        proxy = globals()[f["proxy"]](Input=pieces_source(association, ghosts, array == "PacMan"),
                                      Scalars=[association, array], SelectionMode="Range",
                                      LowerThreshold=lower, UpperThreshold=upper,
                                      **f["properties"])
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy, idx=0)
        expected = reference[key]
        expect(tag + key + ": cells as on 1 rank", data.GetNumberOfCells(), expected["cells"])
        for name in f["fields"]:
            expect(tag + key + ": " + name + " as on 1 rank", field(data, name), expected[name])
        expect(tag + key + ": ranks that took part", field(data, "NumberOfRanks"),
               ranks if ranks > 1 else None)
        values = whole_values(cells, array)
        mask = (values >= lower) & (values <= upper)
        if f["reverts"]:
            check_reversion(tag + key, proxy, cells, mask)
        if key == "polyhedrizer":
            check_standard_plane_reversion(tag, proxy, cells, mask)
        Delete(proxy)


def check_standard_plane_reversion(tag, polyhedrizer, cells, mask):
    """Standard Plane Reversion of the faces on rank 0: the whole selection, by rank 0."""
    reversion = StandardPlaneReversion(Input=OutputPort(polyhedrizer, 0))
    reversion.UpdatePipeline()
    image = sm.Fetch(reversion)  # rank 0's piece: the whole image
    attributes = image.GetCellData() if cells else image.GetPointData()
    selection = attributes.GetArray("Selection")
    back = None if selection is None else ns.vtk_to_numpy(selection).reshape(mask.shape)
    expect(tag + "Standard Plane Reversion of the faces is the selection",
           back is not None and bool((back.astype(bool) == mask).all()), True)
    Delete(reversion)


def check_reversion(tag, proxy, cells, mask):
    """Port 1 of every rank: its own piece of the voxels rebuilt from the output, which
    together are the selection of the whole image."""
    selection, index, extents = gathered_pieces(OutputPort(proxy, 1), cells, "Selection")
    rebuilt = np.zeros_like(mask)
    rebuilt[index[:, 2], index[:, 1], index[:, 0]] = selection.astype(bool)
    expect(tag + ": reversion gathered from the ranks is the selection",
           bool((rebuilt == mask).all()), True)
    seen = np.zeros(mask.shape, bool)
    seen[index[:, 2], index[:, 1], index[:, 0]] = True
    expect(tag + ": the ranks' reversion pieces cover the image", bool(seen.all()), True)
    expect(tag + ": each rank's reversion is its own piece", len(set(extents)), ranks)


def check_phantom():
    """Voxel Phantom: each rank computes its own piece; the pieces are the 1-process
    phantom, and the EVM boundary of the distributed phantom is that of the whole."""
    dims = (40, 36, 30)
    phantom = VoxelPhantom(Dimensions=list(dims))
    labels, index, extents = gathered_pieces(phantom, False, "Labels")
    whole = np.full(dims[::-1], -1, np.int64)
    whole[index[:, 2], index[:, 1], index[:, 0]] = labels
    expect("phantom: each rank has a piece of its own", len(set(extents)), ranks)
    folder = tempfile.mkdtemp(prefix="phantom-", dir=SCRATCH)
    subprocess.run(["/usr/bin/python3", os.path.join(HERE, "single_process_reference.py"),
                    "--phantom"] + [str(d) for d in dims] + [folder + "/labels.npy"],
                   check=True, env=child_environment())
    single = np.load(folder + "/labels.npy").reshape(dims[::-1])
    expect("phantom: the ranks' pieces are the 1-process phantom",
           bool((whole == single).all()), True)
    boundary = EVMBoundary(Input=phantom, Scalars=["POINTS", "Labels"],
                           SelectionMode="Positive", OutputMode="Triangles")
    boundary.UpdatePipeline()
    data = sm.Fetch(boundary)
    mask = single > 0
    expect("phantom: voxels", field(data, "NumberOfVoxels"), int(mask.sum()))
    expect("phantom: extreme vertices", field(data, "NumberOfExtremeVertices"),
           extreme_vertices(mask))
    expect("phantom: surfels", field(data, "NumberOfSurfels"), surfel_count(mask))
    Delete(boundary)
    Delete(phantom)


def check_real_volume():
    """The headsq bone (v >= 1150, 64 components), from a .pvti of four pieces read by every
    rank: the EVM boundary and the CUDB components of the whole volume."""
    raw = os.path.join(DATA_DIR, "headsq", "headsq_quarter_64x64x93_int16le.raw")
    if not os.path.exists(raw):
        print("headsq not found under %r: the real-volume part is skipped" % DATA_DIR)
        return
    values = np.fromfile(raw, "<i2").reshape(93, 64, 64)
    path = os.path.join(tempfile.mkdtemp(prefix="pvti-", dir=SCRATCH), "headsq.pvti")
    write_partitioned(values, path, 4)
    reader = OpenDataFile(path)
    selection = dict(Scalars=["POINTS", "values"], SelectionMode="Range", LowerThreshold=1150.0,
                     UpperThreshold=40000.0)
    mask = values >= 1150
    boundary = EVMBoundary(Input=reader, OutputMode="Triangles", **selection)
    boundary.UpdatePipeline()
    data = sm.Fetch(boundary)
    tag = "headsq .pvti, %d ranks: " % ranks
    faces, holes = faces_and_holes_3d(mask, merge_non_manifold=False)
    expect(tag + "voxels", field(data, "NumberOfVoxels"), int(mask.sum()))
    expect(tag + "extreme vertices", field(data, "NumberOfExtremeVertices"), extreme_vertices(mask))
    expect(tag + "faces", field(data, "NumberOfFaces"), faces)
    expect(tag + "holes", field(data, "NumberOfHoles"), holes)
    cudb = CUDBConnectivity(Input=reader, **selection)
    ids, index = gathered_region_ids(cudb, False)
    check_partition(tag + "CUDB: ", ids, index, mask)
    Delete(cudb)
    Delete(boundary)


for association in ("POINTS", "CELLS"):
    reference = references(association == "CELLS")
    for ghosts in (False, True):
        check(association, ghosts)
        check_cudb(association, ghosts)
        check_whole_image_filters(association, ghosts, reference)
check_phantom()
check_real_volume()
finish()
