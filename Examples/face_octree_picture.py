"""Renders the three plates of Joan-Arinyo and Sole's figures for a CSG-like solid (a box and
a cylinder, a spherical bite): the voxels (their boundary faces), the face octree (one box per
face node, coloured by level) and the boundary (vtkFaceOctreeBoundaryFilter, Polygons: one
colour per face node, sewing triangles dark), side by side.

    xvfb-run -a /usr/bin/python3 Examples/face_octree_picture.py [out.png] [N]
"""

import sys

import numpy as np
import voxelbrep
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkRenderingCore import vtkActor, vtkDataSetMapper, vtkPolyDataMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from picture_common import add_panel, image_of, panel_window, write_png


def solid(n):
    c = (np.arange(n) + 0.5) / n - 0.5
    z, y, x = np.meshgrid(c, c, c, indexing="ij")
    box = (np.abs(x + 0.05) < 0.3) & (np.abs(y) < 0.2) & (np.abs(z) < 0.3)
    cylinder = ((x - 0.2) ** 2 + y ** 2 < 0.18 ** 2) & (np.abs(z) < 0.4)
    bite = (x + 0.15) ** 2 + y ** 2 + (z - 0.3) ** 2 < 0.2 ** 2
    return (box | cylinder) & ~bite



def shuffled_lut(count, dark_first):
    rng = np.random.default_rng(3)
    lut = vtkLookupTable()
    lut.SetNumberOfTableValues(count + 1)
    lut.SetTableValue(0, *((0.15, 0.15, 0.18, 1.0) if dark_first else (0.7, 0.7, 0.7, 1.0)))
    for i in range(1, count + 1):
        r, g, b = 0.35 + 0.65 * rng.random(3)
        lut.SetTableValue(i, r, g, b, 1.0)
    lut.SetTableRange(-1, count - 1)
    lut.Build()
    return lut


def actor_of(data, array, lut, lo, hi, edges=False):
    mapper = vtkDataSetMapper() if not hasattr(data, "GetPolys") else vtkPolyDataMapper()
    mapper.SetInputData(data)
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray(array)
    mapper.SetLookupTable(lut)
    mapper.SetScalarRange(lo, hi)
    mapper.ScalarVisibilityOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    if edges:
        actor.GetProperty().EdgeVisibilityOn()
        actor.GetProperty().SetEdgeColor(0.2, 0.2, 0.2)
    return actor


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "Documentation/face_octree.png"
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 64
    image = image_of(solid(n))
    voxels = voxelbrep.vtkEVMBoundaryFilter()
    voxels.SetInputData(image)
    voxels.SetOutputModeToSurfels()
    voxels.Update()
    f = voxelbrep.vtkFaceOctreeBoundaryFilter()
    f.SetInputData(image)
    f.Update()
    boundary = f.GetOutput()
    nodes = int(boundary.GetFieldData().GetArray("NumberOfFaceNodes").GetValue(0))
    octree = vtkGeometryFilter()
    octree.SetInputData(f.GetOutputDataObject(1))
    octree.Update()
    level = vtkLookupTable()
    level.SetHueRange(0.65, 0.0)
    level.SetTableRange(0, 5)
    level.Build()
    grey = vtkLookupTable()
    grey.SetNumberOfTableValues(1)
    grey.SetTableValue(0, 0.75, 0.75, 0.78, 1.0)
    grey.Build()
    actors = [actor_of(voxels.GetOutput(), "FaceId", grey, 0, 1, edges=True),
              actor_of(octree.GetOutput(), "NodeLevel", level, 0, 5, edges=True),
              actor_of(boundary, "FaceNodeId", shuffled_lut(nodes, True), -1, nodes - 1)]
    print("%d surfels, %d face nodes, %d cells (%d polygons, %d triangles)" % (
        voxels.GetOutput().GetNumberOfCells(), nodes, boundary.GetNumberOfCells(),
        int(boundary.GetFieldData().GetArray("NumberOfPolygons").GetValue(0)),
        int(boundary.GetFieldData().GetArray("NumberOfTriangles").GetValue(0))))
    window = panel_window(len(actors), 400)
    for i, a in enumerate(actors):
        add_panel(window, i, len(actors), [a], 30, 25, 1.3)
    write_png(window, out)


main()
