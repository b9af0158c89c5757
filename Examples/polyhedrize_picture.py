"""Renders standard-plane faces: the paper's sphere and hexahedron, and the "Al" object of the
shared data when present, each surfel coloured by its face (vtkStandardPlanePolyhedrizer,
OutputMode Surfels), side by side.

    xvfb-run -a /usr/bin/python3 Examples/polyhedrize_picture.py [out.png] [DATA_DIR]
"""

import os
import sys

import numpy as np
import voxelbrep
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from picture_common import add_panel, image_of, panel_window, write_png

HERE = os.path.dirname(os.path.abspath(__file__))



def sphere():
    c = np.arange(-17, 18)
    z, y, x = np.meshgrid(c, c, c, indexing="ij")
    return x * x + y * y + z * z <= 240


def hexahedron():
    c = np.arange(-16, 17)
    z, y, x = np.meshgrid(c, c, c, indexing="ij")
    inside = np.ones(x.shape, bool)
    for n, h in (((2, 2, 1), 17), ((-2, 1, 2), 17), ((1, -2, 2), 29)):
        inside &= np.abs(n[0] * x + n[1] * y + n[2] * z) <= h
    return inside


def faces_actor(mask, merge):
    f = voxelbrep.vtkStandardPlanePolyhedrizer()
    f.SetInputData(image_of(mask))
    f.SetOutputModeToSurfels()
    f.SetMergeFaces(merge)
    f.Update()
    out = f.GetOutput()
    faces = int(out.GetFieldData().GetArray("NumberOfFaces").GetValue(0))
    # Neighbouring faces have close ids: a shuffled table tells them apart.
    rng = np.random.default_rng(7)
    lut = vtkLookupTable()
    lut.SetNumberOfTableValues(max(faces, 1))
    for i in range(max(faces, 1)):
        r, g, b = 0.25 + 0.75 * rng.random(3)
        lut.SetTableValue(i, r, g, b, 1.0)
    lut.SetTableRange(0, max(faces - 1, 0))
    lut.Build()
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(out)
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray("FaceId")
    mapper.SetLookupTable(lut)
    mapper.SetScalarRange(0, max(faces - 1, 0))
    mapper.ScalarVisibilityOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    print("%d surfels, %d faces" % (out.GetNumberOfCells(), faces))
    return actor


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/polyhedrizer.png"
    data = sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "..", "..", "shared", "data")
    objects = [(sphere(), False), (hexahedron(), True)]
    raw = os.path.join(data, "dgtal_al", "dgtal_al_100x100x100_uint8.raw")
    if os.path.exists(raw):
        objects.append((np.fromfile(raw, np.uint8).reshape(100, 100, 100) == 1, False))
    window = panel_window(len(objects), 400)
    for i, (mask, merge) in enumerate(objects):
        add_panel(window, i, len(objects), [faces_actor(mask, merge)], 35,
                  25 if i < 2 else -60, 1.25 if i < 2 else 1.7)
    write_png(window, out)


main()
