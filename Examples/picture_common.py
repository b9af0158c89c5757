"""What the README's picture scripts share: a mask as an image, panels side by side in one
window, and the window written as a PNG."""

import numpy as np
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401


def image_of(mask):
    """A [z, y, x] boolean mask as the uint8 point scalars "mask" of an image."""
    image = vtkImageData()
    image.SetDimensions(mask.shape[2], mask.shape[1], mask.shape[0])
    a = ns.numpy_to_vtk(mask.astype(np.uint8).ravel(), deep=1)
    a.SetName("mask")
    image.GetPointData().SetScalars(a)
    return image


def panel_window(count, size):
    """An offscreen window for `count` square panels of `size` pixels side by side."""
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(size * count, size)
    return window


def add_panel(window, i, count, actors, azimuth, elevation, zoom):
    """Panel i of `count`: the actors on a light background, seen from the given angles."""
    renderer = vtkRenderer()
    renderer.SetViewport(i / count, 0, (i + 1) / count, 1)
    renderer.SetBackground(0.92, 0.93, 0.95)
    for a in actors:
        renderer.AddActor(a)
    camera = renderer.GetActiveCamera()
    camera.Azimuth(azimuth)
    camera.Elevation(elevation)
    renderer.ResetCamera()
    camera.Zoom(zoom)
    window.AddRenderer(renderer)
    return renderer


def write_png(window, out):
    """Renders the window and writes it to `out`."""
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(out)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("wrote", out)
