"""VoxelBRep in ParaView's Python (pvbatch or pvpython): load the plugin, build a Voxel Phantom,
extract its EVM boundary per label, print the statistics and save the result.

  pvbatch Examples/pvbatch_example.py [--plugin path/to/VoxelBRep.so] [--output out.vtp]
                                      [--png out.png] [--dims N]

The plugin path defaults to $VOXELBREP_PLUGIN, then to the build trees next to this file
(build*/lib/paraview-5.11/plugins/VoxelBRep/VoxelBRep.so). --png renders a screenshot and
needs an X display (xvfb-run -a pvbatch ...). In the GUI the same is: Tools > Manage
Plugins > Load New, then Sources > Voxel B-Rep > Voxel Phantom and Filters > Voxel B-Rep >
EVM Boundary.
"""

import argparse
import glob
import os
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403


def find_plugin():
    env = os.environ.get("VOXELBREP_PLUGIN")
    if env:
        return env
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    found = sorted(glob.glob(os.path.join(
        root, "build*", "lib", "paraview-*", "plugins", "VoxelBRep", "VoxelBRep.so")))
    return found[0] if found else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", default=find_plugin())
    parser.add_argument("--output", default=os.path.join("out", "pvbatch_example.vtp"))
    parser.add_argument("--png", default=None)
    parser.add_argument("--dims", type=int, default=64)
    args = parser.parse_args()
    if not args.plugin or not os.path.exists(args.plugin):
        sys.exit("VoxelBRep.so not found: pass --plugin or set VOXELBREP_PLUGIN")

    # The proxies exist only once the plugin is loaded: ns=globals() defines VoxelPhantom and
    # EVMBoundary here (their XML labels without spaces).
    LoadPlugin(args.plugin, remote=False, ns=globals())

    phantom = VoxelPhantom(Dimensions=[args.dims] * 3)
    boundary = EVMBoundary(Input=phantom)
    boundary.Scalars = ["POINTS", "Labels"]  # properties are named after their XML labels
    boundary.SelectionMode = "Labels"
    boundary.OutputMode = "Triangles"
    boundary.UpdatePipeline()

    output = servermanager.Fetch(boundary)
    fd = output.GetFieldData()
    stats = {fd.GetArrayName(i): int(fd.GetArray(i).GetTuple(0)[0])
             for i in range(fd.GetNumberOfArrays())}
    print("EVM boundary of a %d^3 phantom: %s voxels, %s extreme vertices, %s faces, %s holes, "
          "%d triangles" % (args.dims, stats["NumberOfVoxels"], stats["NumberOfExtremeVertices"],
                            stats["NumberOfFaces"], stats["NumberOfHoles"],
                            output.GetNumberOfCells()))
    if output.GetNumberOfCells() == 0:
        sys.exit("empty boundary")

    if os.path.dirname(args.output):
        os.makedirs(os.path.dirname(args.output), exist_ok=True)
    # Inline binary: ParaView 5.11's readers cannot parse appended data with the expat of
    # current Debian 12 (VTK issue 19258).
    SaveData(args.output, proxy=boundary, DataMode="Binary")
    print("wrote", args.output)

    if args.png:
        view = CreateView("RenderView")
        view.ViewSize = [600, 600]
        view.OrientationAxesVisibility = 0
        display = Show(boundary, view)
        ColorBy(display, ("CELLS", "Label"))
        view.CameraPosition = [1.0, -1.6, 1.3]
        view.CameraFocalPoint = [0, 0, 0]
        view.CameraViewUp = [0, 0, 1]
        view.ResetCamera()
        Render(view)
        if os.path.dirname(args.png):
            os.makedirs(os.path.dirname(args.png), exist_ok=True)
        SaveScreenshot(args.png, view)
        print("wrote", args.png)


main()
