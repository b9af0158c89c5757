"""How ParaView colours the outputs when they are shown, with no manual step.

Usage: pvbatch TestPluginColoring.py /path/to/VoxelBRep.so   (needs an X display)

- Show() colours EVM Boundary and Standard Plane Polyhedrizer by Label in Labels mode and by
  FaceColor (the hash of FaceId) otherwise: the representation's ColorArrayName.
- FaceColor is the documented hash of FaceId (splitmix64's finaliser, top 24 bits / 2^24),
  recomputed here, so its values lie in [0, 1) for every output: the colour map shared by
  all outputs needs no rescale after a second filter with many more faces.
- Neighbouring faces (triangles or polygons sharing an edge, of different FaceId) never get
  the same FaceColor.
"""

import sys

import numpy as np
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from pvtest import expect, finish, render_view
from vtkmodules.util import numpy_support as ns

LoadPlugin(sys.argv[1], remote=False, ns=globals())
MASK = (1 << 64) - 1


def face_color(face_id):
    x = (face_id + 0x9E3779B97F4A7C15) & MASK
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & MASK
    x ^= x >> 31
    return np.float32((x >> 40) / 16777216.0)


def check_face_colors(tag, data):
    cd = data.GetCellData()
    ids = ns.vtk_to_numpy(cd.GetArray("FaceId")).astype(np.int64)
    colors = ns.vtk_to_numpy(cd.GetArray("FaceColor"))
    expected = np.array([face_color(int(i) & MASK) for i in ids], dtype=np.float32)
    expect(tag + ": FaceColor is the hash of FaceId", bool(np.array_equal(colors, expected)), True)
    expect(tag + ": FaceColor in [0, 1)", bool(colors.min() >= 0 and colors.max() < 1), True)
    # Faces across each edge: no two different neighbouring faces share a colour.
    polys = data.GetPolys()
    offsets = ns.vtk_to_numpy(polys.GetOffsetsArray())
    conn = ns.vtk_to_numpy(polys.GetConnectivityArray())
    by_edge = {}
    for c in range(len(offsets) - 1):
        loop = conn[offsets[c]:offsets[c + 1]]
        for a, b in zip(loop, np.roll(loop, -1)):
            by_edge.setdefault((min(a, b), max(a, b)), set()).add(c)
    pairs = clashes = 0
    for cells in by_edge.values():
        cells = sorted(cells)
        for i in range(len(cells)):
            for j in range(i + 1, len(cells)):
                if ids[cells[i]] != ids[cells[j]]:
                    pairs += 1
                    clashes += colors[cells[i]] == colors[cells[j]]
    expect(tag + ": neighbouring faces found", pairs > 100, True)
    expect(tag + ": neighbouring faces of the same colour", int(clashes), 0)


view = render_view()
phantom = VoxelPhantom(Dimensions=[40, 40, 40])
phantom.UpdatePipeline()
for name in ("EVMBoundary", "StandardPlanePolyhedrizer"):
    for mode, array in (("Positive", "FaceColor"), ("Range", "FaceColor"), ("Labels", "Label")):
        SetActiveSource(phantom)
        f = globals()[name](Input=phantom, SelectionMode=mode)
        display = Show(f, view)
        expect("%s %s: Show colours by" % (name, mode), list(display.ColorArrayName),
               ["CELLS", array])
        if mode == "Positive":
            check_face_colors("%s %s" % (name, mode), servermanager.Fetch(f))
        Hide(f, view)
        Delete(f)
lut = GetColorTransferFunction("FaceColor")
points = lut.RGBPoints
expect("the FaceColor map spans at most [0, 1] after every output",
       bool(points[0] >= 0.0 and points[-4] <= 1.0), True)
finish()
