"""pvbatch image regression test of one output mode of EVM Boundary or Standard Plane
Polyhedrizer, on a crop of the engine (voxels 100..164 x 60..124 x 40..104, values 130..255)
or, for EVM Boundary in 2D, on its slice z = 64 (values 130..255), as ParaView draws it.

Everything that decides the picture is set here, by XML property name (not the panel's
defaults): the selection, the output mode, the colouring (cell array FaceId, fixed range and
preset; the EVM Surfels have no faces and are drawn in one colour), the camera and the view.

Usage: pvbatch TestPluginRenderModes.py PLUGIN FILTER MODE BASELINE.png TEMP_DIR DATA_DIR
  FILTER: EVM, EVM2D or Polyhedrizer; MODE: the OutputMode value (an integer).
Needs an X display (xvfb-run -a). Skipped (77) when the engine is absent.
"""

import os
import sys

from paraview.simple import *  # noqa: F401,F403
from pvtest import compare_with_baseline, render_view

plugin, which, mode, baseline, temp_dir, data_dir = sys.argv[1:7]
engine = os.path.join(data_dir, "engine", "engine.vti")
if not os.path.exists(engine):
    print("no engine volume in", data_dir, "; skipped")
    sys.exit(77)
LoadPlugin(plugin, remote=False, ns=globals())

reader = XMLImageDataReader(FileName=[engine])
flat = which == "EVM2D"
voi = [0, 255, 0, 255, 64, 64] if flat else [100, 164, 60, 124, 40, 104]
crop = ExtractSubset(Input=reader, VOI=voi)
if which == "Polyhedrizer":
    f = StandardPlanePolyhedrizer(Input=crop)
    f.SetPropertyWithName("GenerateReversion", 0)
else:
    f = EVMBoundary(Input=crop)
f.SetPropertyWithName("SelectInputScalars", ["POINTS", "ImageFile"])
f.SetPropertyWithName("SelectionMode", 1)  # Range
f.SetPropertyWithName("LowerThreshold", 130.0)
f.SetPropertyWithName("UpperThreshold", 255.0)
f.SetPropertyWithName("ArrayComponent", 0)
f.SetPropertyWithName("OutputMode", int(mode))
if which != "Polyhedrizer":
    f.SetPropertyWithName("MergeNonManifoldFaces", 0)
    f.SetPropertyWithName("FlatImagesAs2D", 1)
f.UpdatePipeline()
out = servermanager.Fetch(f, idx=0) if which == "Polyhedrizer" else servermanager.Fetch(f)
print("cells:", out.GetNumberOfCells())

view = render_view()
display = Show(OutputPort(f, 0), view)
display.SetRepresentationType("Surface")
display.LineWidth = 2.0
faces = out.GetCellData().GetArray("FaceId")
if faces is not None and faces.GetRange()[1] >= 0:
    ColorBy(display, ("CELLS", "FaceId"))
    lut = GetColorTransferFunction("FaceId")
    lut.ApplyPreset("Rainbow Uniform", True)
    lut.NumberOfTableValues = 64
    lut.Discretize = 1
    lut.RescaleTransferFunction(0.0, 400.0 if flat else 2000.0)
    lut.AutomaticRescaleRangeMode = "Never"
    display.SetScalarBarVisibility(view, False)
else:
    display.ColorArrayName = ["POINTS", ""]
    display.AmbientColor = display.DiffuseColor = [0.85, 0.55, 0.3]

if flat:
    compare_with_baseline(view, (128, 128, 64), (0, -1e-3, 400), baseline, temp_dir)
else:
    compare_with_baseline(view, (132, 92, 72), (70, -110, 90), baseline, temp_dir)
