"""Renders the convex hull of a voxel object next to its separating polyhedron
(vtkConvexHullModifier, OutputMode ConvexHull and Triangles): the pac-man of Schulz 2009 and a
torus, the polyhedron's triangles coloured by Level (0 hull faces, 1 pressed in, 2 pushed back
out), a grey hull beside each.

    xvfb-run -a /usr/bin/python3 Examples/convex_hull_picture.py [out.png]
"""

import sys

import numpy as np
import voxelbrep
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from picture_common import add_panel, image_of, panel_window, write_png



def grid(n):
    return np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")


def pac_man(r=11):
    z, y, x = grid(2 * r + 3)
    c = r + 1
    ball = (x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 <= r * r
    return ball & ~((x - c > 0) & (np.abs(y - c) < 0.6 * (x - c)))


def torus():
    z, y, x = grid(20)
    return (np.hypot(x - 9.5, y - 9.5) - 6) ** 2 + (z - 9.5) ** 2 <= 2.6 ** 2


def actor(mask, mode):
    f = voxelbrep.vtkConvexHullModifier()
    f.SetInputData(image_of(mask))
    f.SetOutputMode(mode)
    f.Update()
    out = f.GetOutput()
    fd = out.GetFieldData()
    print("%s: %d faces, %d vertices, Separates %d" % (
        f.GetOutputModeAsString(), out.GetNumberOfCells() if mode == f.CONVEX_HULL else
        int(fd.GetArray("NumberOfFaces").GetValue(0)), out.GetNumberOfPoints(),
        int(fd.GetArray("Separates").GetValue(0))))
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(out)
    a = vtkActor()
    a.SetMapper(mapper)
    if mode == f.CONVEX_HULL:
        mapper.ScalarVisibilityOff()
        a.GetProperty().SetColor(0.75, 0.75, 0.78)
    else:
        lut = vtkLookupTable()
        lut.SetNumberOfTableValues(3)
        for i, rgb in enumerate(((0.2, 0.45, 0.85), (0.85, 0.25, 0.3), (0.95, 0.75, 0.2))):
            lut.SetTableValue(i, *rgb, 1.0)
        lut.SetTableRange(0, 2)
        mapper.SetScalarModeToUseCellFieldData()
        mapper.SelectColorArray("Level")
        mapper.SetLookupTable(lut)
        mapper.SetScalarRange(0, 2)
        mapper.ScalarVisibilityOn()
    a.GetProperty().EdgeVisibilityOn()
    a.GetProperty().SetEdgeColor(0.15, 0.15, 0.15)
    return a


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/convexhull.png"
    panels = [(pac_man(), voxelbrep.vtkConvexHullModifier.CONVEX_HULL),
              (pac_man(), voxelbrep.vtkConvexHullModifier.TRIANGLES),
              (torus(), voxelbrep.vtkConvexHullModifier.CONVEX_HULL),
              (torus(), voxelbrep.vtkConvexHullModifier.TRIANGLES)]
    window = panel_window(len(panels), 300)
    for i, (mask, mode) in enumerate(panels):
        add_panel(window, i, len(panels), [actor(mask, mode)], 40 if i < 2 else 20,
                  25 if i < 2 else 55, 1.3)
    write_png(window, out)


main()
