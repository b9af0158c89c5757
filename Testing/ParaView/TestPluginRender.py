"""pvbatch image regression test of the VoxelBRep plugin: the EVM boundary (Labels mode,
Triangles) of a 64^3 Voxel Phantom, coloured by the cell array Label with a categorical
colour map, in a fixed camera.

Usage: pvbatch TestPluginRender.py /path/to/VoxelBRep.so BASELINE.png TEMP_DIR
Needs an X display (xvfb-run -a). When the baseline is missing, the image is written to
TEMP_DIR and the test fails (copy it to Testing/Data/Baseline/ after checking it).
"""

import sys

from paraview.simple import *  # noqa: F401,F403
from pvtest import compare_with_baseline, render_view

plugin, baseline, temp_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())

phantom = VoxelPhantom(Dimensions=[64, 64, 64])
boundary = EVMBoundary(Input=phantom)
boundary.Scalars = ["POINTS", "Labels"]
boundary.SelectionMode = "Labels"
boundary.OutputMode = "Triangles"
boundary.UpdatePipeline()

view = render_view()

display = Show(boundary, view)
ColorBy(display, ("CELLS", "Label"))
lut = GetColorTransferFunction("Label")
lut.InterpretValuesAsCategories = 1
lut.AnnotationsInitialized = 1
lut.Annotations = ["1", "shells", "2", "torus", "3", "plate", "4", "frame", "5", "boxes"]
lut.IndexedColors = [0.85, 0.37, 0.01,
                     0.46, 0.44, 0.70,
                     0.11, 0.62, 0.47,
                     0.91, 0.16, 0.54,
                     0.90, 0.67, 0.01]
display.SetScalarBarVisibility(view, False)

compare_with_baseline(view, (32, 32, 32), (80, -125, 105), baseline, temp_dir)
