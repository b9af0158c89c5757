"""Image regression test (plain VTK Python, no ParaView): the EVM boundary (Triangles) of a
48^3 vtkVoxelPhantomSource, every face in its own colour (cell array FaceId), rendered with
the faces' edges so that the maximal faces are visible.

Usage: TestEVMBoundaryRender.py BASELINE.png TEMP_DIR
Needs an X display (xvfb-run -a). When the baseline is missing, the image is written to
TEMP_DIR and the test fails (copy it to Testing/Data/Baseline/ after checking it).
"""

import colorsys
import sys

import voxelbrep
import vtkmodules.vtkInteractionStyle  # noqa: F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkmodules.test import Testing
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkFiltersCore import vtkFeatureEdges
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow)


def face_colours(count):
    """A fixed, well spread colour per face id (golden-ratio hues)."""
    lut = vtkLookupTable()
    lut.SetNumberOfTableValues(max(count, 1))
    for i in range(max(count, 1)):
        h = (i * 0.6180339887498949) % 1.0
        s = 0.55 + 0.35 * ((i * 7) % 3) / 2.0
        v = 0.75 + 0.25 * ((i * 5) % 2)
        lut.SetTableValue(i, *colorsys.hsv_to_rgb(h, s, v), 1.0)
    lut.SetTableRange(0, max(count - 1, 0))
    lut.Build()
    return lut


def main():
    baseline, temp_dir = sys.argv[1], sys.argv[2]
    Testing.VTK_TEMP_DIR = temp_dir

    phantom = voxelbrep.vtkVoxelPhantomSource()
    phantom.SetDimensions(48, 48, 48)
    boundary = voxelbrep.vtkEVMBoundaryFilter()
    boundary.SetInputConnection(phantom.GetOutputPort())
    boundary.SetOutputModeToTriangles()
    boundary.SetSelectionModeToLabels()
    boundary.Update()
    out = boundary.GetOutput()
    faces = int(out.GetFieldData().GetArray("NumberOfFaces").GetValue(0))
    print("faces:", faces, "triangles:", out.GetNumberOfCells())
    if faces <= 0:
        print("FAILED: no faces")
        return 1

    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(boundary.GetOutputPort())
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray("FaceId")
    mapper.SetLookupTable(face_colours(faces))
    mapper.UseLookupTableScalarRangeOn()
    # Push the polygons back so that the loops drawn on them stay visible.
    mapper.SetResolveCoincidentTopologyToPolygonOffset()
    mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(2, 2)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetAmbient(0.3)
    actor.GetProperty().SetDiffuse(0.8)

    # The outlines of the maximal faces: edges between faces of different FaceId only.
    outline_source = voxelbrep.vtkEVMBoundaryFilter()
    outline_source.SetInputConnection(phantom.GetOutputPort())
    outline_source.SetOutputModeToPolylines()
    outline_source.SetSelectionModeToLabels()
    outlines = vtkPolyDataMapper()
    outlines.SetInputConnection(outline_source.GetOutputPort())
    outlines.ScalarVisibilityOff()
    outline_actor = vtkActor()
    outline_actor.SetMapper(outlines)
    outline_actor.GetProperty().SetColor(0.05, 0.05, 0.05)
    outline_actor.GetProperty().SetLineWidth(1.5)

    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.AddActor(outline_actor)
    renderer.SetBackground(0.92, 0.93, 0.95)
    window = vtkRenderWindow()
    window.SetSize(400, 400)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)

    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(24, 24, 24)
    camera.SetPosition(24 + 60, 24 - 95, 24 + 80)
    camera.SetViewUp(0, 0, 1)
    renderer.ResetCamera()
    camera.Zoom(1.1)
    window.Render()

    # Raises (and so fails the test) when the images differ or the baseline is missing.
    Testing.compareImage(window, baseline, threshold=10)
    print("image matches", baseline)
    return 0


if __name__ == "__main__":
    sys.exit(main())
