"""The plugin's defaults on real CT data, and thresholds that follow the selected array.

Usage: pvbatch TestPluginDefaults.py /path/to/VoxelBRep.so /path/to/data_dir

1. Threshold defaults (no GUI): Lower Threshold is the middle of the selected array's range
   and Upper Threshold its maximum, for different arrays and ranges: the engine (0..255),
   a wavelet, an array chosen at creation, an array chosen after creation (then reset to the
   domain defaults, what the panel's reset button does), a component and the magnitude of a
   vector array. The ranges are computed with numpy from the fetched data.
2. Every filter with DEFAULT properties on the engine volume (256 x 256 x 128, values 0..255)
   finishes within seconds with a sensible object: the EVM boundary is closed and has far
   fewer cells than the noise that Positive selects; the components are scipy's; the
   polyhedrization reverts to the selection; the reversion gives the selected voxels back.
Skipped (77) when the engine is not in the data directory.
"""

import os
import sys
import time

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from pvtest import expect, field, finish
from voxelbrep_testing import surfel_count
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkFiltersCore import vtkFeatureEdges

plugin, data_dir = sys.argv[1], sys.argv[2]
engine_file = os.path.join(data_dir, "engine", "engine.vti")
if not os.path.exists(engine_file):
    print("no engine volume in", data_dir, "; skipped")
    sys.exit(77)
LoadPlugin(plugin, remote=False, ns=globals())
SECONDS = 30.0  # generous: the machine is shared; each run takes 0.2 to 3 s here


def point_values(source, name):
    image = servermanager.Fetch(source)
    array = image.GetPointData().GetArray(name)
    n = array.GetNumberOfComponents()
    return ns.vtk_to_numpy(array).astype(np.float64).reshape(-1, n)


def expect_defaults(tag, f, lo, hi):
    expect(tag + ": Lower Threshold = middle of the range", f.LowerThreshold, (lo + hi) / 2)
    expect(tag + ": Upper Threshold = maximum", f.UpperThreshold, hi)


def reset_thresholds(f):
    """What the panel's reset button and Apply do."""
    for name in ("LowerThreshold", "UpperThreshold"):
        f.GetProperty(name).SMProperty.ResetToDomainDefaults()
    f.UpdateVTKObjects()


def check_threshold_defaults(engine):
    values = point_values(engine, "ImageFile")
    for name in ("EVMBoundary", "CUDBConnectivity", "StandardPlanePolyhedrizer"):
        SetActiveSource(engine)
        f = globals()[name](Input=engine)
        expect(name + ": default Selection Mode", f.SelectionMode, "Range")
        expect_defaults(name + " on the engine", f, values.min(), values.max())
        Delete(f)
    wavelet = Wavelet()
    calc = Calculator(Input=wavelet, ResultArrayName="vec",
                      Function="RTData*iHat + (2*RTData - 500)*jHat + 3*kHat")
    calc.UpdatePipeline()
    other = Calculator(Input=calc, ResultArrayName="shifted", Function="RTData/4 + 1000")
    other.UpdatePipeline()
    rt = point_values(other, "RTData")[:, 0]
    shifted = point_values(other, "shifted")[:, 0]
    vec = point_values(other, "vec")
    SetActiveSource(other)
    f = EVMBoundary(Input=other, Scalars=["POINTS", "RTData"])
    expect_defaults("RTData chosen at creation", f, rt.min(), rt.max())
    SetActiveSource(other)
    g = EVMBoundary(Input=other, Scalars=["POINTS", "shifted"])
    expect_defaults("another array chosen at creation", g, shifted.min(), shifted.max())
    f.Scalars = ["POINTS", "shifted"]
    reset_thresholds(f)
    expect_defaults("after choosing another array", f, shifted.min(), shifted.max())
    f.Scalars = ["POINTS", "vec"]
    f.ArrayComponent = 1
    reset_thresholds(f)
    expect_defaults("component 1 of a vector array", f, vec[:, 1].min(), vec[:, 1].max())
    f.ArrayComponent = "Magnitude"
    reset_thresholds(f)
    norms = np.sqrt((vec ** 2).sum(axis=1))
    lower, upper = f.LowerThreshold, f.UpperThreshold
    expect("magnitude: Upper Threshold = largest norm", abs(upper - norms.max()) < 1e-6 * upper, True)
    expect("magnitude: Lower Threshold = middle of the norms' range",
           abs(lower - (norms.min() + norms.max()) / 2) < 1e-6 * upper, True)
    # The magnitude selects on the norms (ParaView's Magnitude is the number of components).
    f.UpdatePipeline()
    expect("magnitude: the selected voxels are those of the norms",
           field(servermanager.Fetch(f), "NumberOfVoxels"),
           int(((norms >= lower) & (norms <= upper)).sum()))
    for p in (g, f, other, calc, wavelet):
        Delete(p)


def timed_update(f, port=None):
    start = time.time()
    f.UpdatePipeline()
    seconds = time.time() - start
    print("  %s: %.2f s" % (f.GetXMLLabel(), seconds))
    expect(f.GetXMLLabel() + ": finishes within %g s with its defaults" % SECONDS,
           seconds < SECONDS, True)


def check_evm(engine, mask):
    SetActiveSource(engine)
    evm = EVMBoundary(Input=engine)
    timed_update(evm)
    out = servermanager.Fetch(evm)
    expect("EVM: NumberOfVoxels = numpy's value >= 127.5", field(out, "NumberOfVoxels"),
           int(mask.sum()))
    edges = vtkFeatureEdges()
    edges.SetInputData(out)
    edges.BoundaryEdgesOn()
    edges.FeatureEdgesOff()
    edges.NonManifoldEdgesOff()
    edges.ManifoldEdgesOff()
    edges.Update()
    expect("EVM: the default boundary is closed (no boundary edge)",
           edges.GetOutput().GetNumberOfCells(), 0)
    expect("EVM: a non-trivial object (> 1000 faces)", field(out, "NumberOfFaces") > 1000, True)
    SetActiveSource(engine)
    noise = EVMBoundary(Input=engine, SelectionMode="Positive")
    noise.UpdatePipeline()
    cells, noise_cells = out.GetNumberOfCells(), noise.GetDataInformation().GetNumberOfCells()
    print("  EVM cells: %d with the defaults, %d with Positive" % (cells, noise_cells))
    expect("EVM: far fewer cells than the noise Positive selects", 5 * cells < noise_cells, True)
    Delete(noise)
    Delete(evm)


def check_cudb(engine, mask):
    from scipy import ndimage
    SetActiveSource(engine)
    cudb = CUDBConnectivity(Input=engine)
    timed_update(cudb)
    labels, count = ndimage.label(mask)
    sizes = np.sort(np.bincount(labels.ravel())[1:])[::-1]
    out = servermanager.Fetch(cudb, idx=0)
    expect("CUDB: NumberOfComponents = scipy's", field(out, "NumberOfComponents"), int(count))
    table = servermanager.Fetch(cudb, idx=2)
    voxels = ns.vtk_to_numpy(table.GetColumnByName("VoxelCount"))
    expect("CUDB: region sizes = scipy's, largest first", voxels.tolist(), sizes.tolist())
    Delete(cudb)


def check_polyhedrizer(engine, mask):
    SetActiveSource(engine)
    poly = StandardPlanePolyhedrizer(Input=engine)
    timed_update(poly)
    faces = servermanager.Fetch(poly, idx=0)
    surfels = surfel_count(mask)
    expect("Polyhedrizer: NumberOfSurfels = numpy's", field(faces, "NumberOfSurfels"), surfels)
    expect("Polyhedrizer: far fewer faces than surfels",
           5 * field(faces, "NumberOfFaces") < surfels, True)
    reversion = servermanager.Fetch(poly, idx=1)
    expect("Polyhedrizer: ReversionMatches", field(reversion, "ReversionMatches"), 1)
    SetActiveSource(poly)
    back = StandardPlaneReversion(Input=poly)
    timed_update(back)
    image = servermanager.Fetch(back)
    selection = image.GetCellData().GetArray("Selection") or \
        image.GetPointData().GetArray("Selection")
    expect("Reversion: the selected voxels back", int(ns.vtk_to_numpy(selection).sum()),
           int(mask.sum()))
    Delete(back)
    Delete(poly)


engine = XMLImageDataReader(FileName=[engine_file])
engine.UpdatePipeline()
values = point_values(engine, "ImageFile")[:, 0]
dims = servermanager.Fetch(engine).GetDimensions()
mask = (values >= (values.min() + values.max()) / 2).reshape(dims[2], dims[1], dims[0])
check_threshold_defaults(engine)
check_evm(engine, mask)
check_cudb(engine, mask)
check_polyhedrizer(engine, mask)
phantom = VoxelPhantom()
timed_update(phantom)
expect("Voxel Phantom: its six values by default",
       sorted(set(point_values(phantom, "Labels")[:, 0].tolist())), [0, 1, 2, 3, 4, 5])
finish()
