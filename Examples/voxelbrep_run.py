#!/usr/bin/python3
"""VoxelBRep main job: the exact, compact orthogonal boundary (EVM B-Rep) of the voxels of an
image, written as .vtp and rendered to .png, with a one-line summary.

  /usr/bin/python3 Examples/voxelbrep_run.py [input] [--output out.vtp] [--png out.png]
      [--threshold LO[,HI]] [--labels] [--mode triangles|polygons|polylines|surfels|loops]
      [--raw-dims NX,NY,NZ --raw-type uint8|int16|...]

Without an input it uses a 128^3 vtkVoxelPhantomSource (voxels with label > 0). Inputs:
.vti (vtkXMLImageDataReader), .mha/.mhd (vtkMetaImageReader), .nrrd/.nhdr (vtkNrrdReader),
.nii/.nii.gz (vtkNIFTIImageReader), .png (vtkPNGReader; colour images are turned into
luminance), .tif/.tiff (vtkTIFFReader), and headerless raw volumes (vtkImageReader2, with
--raw-dims and --raw-type; x fastest).

Selection: --threshold LO[,HI] selects LO <= value <= HI (HI defaults to +infinity);
--labels gives every non-zero value its own closed boundary; otherwise value > 0.

Rendering needs an X display: run it under `xvfb-run -a` on a headless machine, or pass
--no-png. Needs PYTHONPATH=<build>/lib/python3/dist-packages (the voxelbrep package).
"""

import argparse
import colorsys
import os
import sys
import time

import numpy as np
import voxelbrep
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonCore import vtkLookupTable, vtkSMPTools
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataWriter

MODES = ("triangles", "polygons", "polylines", "surfels", "loops")
RAW_TYPES = {
    "uint8": "SetDataScalarTypeToUnsignedChar",
    "int8": "SetDataScalarTypeToSignedChar",
    "uint16": "SetDataScalarTypeToUnsignedShort",
    "int16": "SetDataScalarTypeToShort",
    "uint32": "SetDataScalarTypeToUnsignedInt",
    "int32": "SetDataScalarTypeToInt",
    "float32": "SetDataScalarTypeToFloat",
    "float64": "SetDataScalarTypeToDouble",
}


def triple(text, kind, name):
    try:
        values = [kind(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError("%s: expected numbers separated by commas" % name)
    if len(values) == 1:
        values *= 3
    if len(values) != 3:
        raise argparse.ArgumentTypeError("%s: expected 1 or 3 values" % name)
    return values


def parse_args(argv):
    p = argparse.ArgumentParser(
        description="Extract the EVM boundary of an image's voxels (VoxelBRep).",
        epilog="Example: voxelbrep_run.py engine.nhdr --threshold 55 --png engine.png")
    p.add_argument("input", nargs="?",
                   help="image file (.vti .mha .mhd .nrrd .nhdr .nii .nii.gz .png .tif, raw); "
                   "default: a built-in phantom")
    p.add_argument("--output", default=os.path.join("out", "voxelbrep.vtp"),
                   help="output polydata (.vtp), default %(default)s")
    p.add_argument("--png", default=os.path.join("out", "voxelbrep.png"),
                   help="rendered image, default %(default)s")
    p.add_argument("--no-png", action="store_true", help="do not render")
    p.add_argument("--threshold", metavar="LO[,HI]",
                   help="select LO <= value <= HI (default: value > 0)")
    p.add_argument("--labels", action="store_true",
                   help="every non-zero value is an object with its own boundary")
    p.add_argument("--mode", choices=MODES, default="triangles",
                   help="output cells, default %(default)s")
    p.add_argument("--merge-non-manifold", action="store_true",
                   help="keep faces whole at non-manifold vertices (vertex-connected faces)")
    p.add_argument("--cell-data", action="store_true",
                   help="use the input's cell scalars (default: point scalars, else cell)")
    p.add_argument("--component", type=int, default=None,
                   help="component of a multi-component array (default: luminance of "
                   "colour images, else 0)")
    p.add_argument("--color-by", choices=("auto", "label", "faceid"), default="auto",
                   help="render colouring: auto = Label with --labels, else FaceId")
    p.add_argument("--size", default="800,800", help="image size W,H, default %(default)s")
    p.add_argument("--phantom-dims", default="128",
                   help="phantom voxels N or NX,NY,NZ when no input is given, default 128")
    p.add_argument("--raw-dims", help="raw input: NX,NY,NZ (x fastest)")
    p.add_argument("--raw-type", choices=sorted(RAW_TYPES), default="uint8",
                   help="raw input: voxel type, default %(default)s")
    p.add_argument("--raw-spacing", default="1", help="raw input: SX,SY,SZ, default 1")
    p.add_argument("--raw-big-endian", action="store_true", help="raw input is big-endian")
    p.add_argument("--raw-header", type=int, default=0, help="raw input: header bytes to skip")
    p.add_argument("--backend", default=os.environ.get("VTK_SMP_BACKEND_IN_USE", "STDThread"),
                   help="vtkSMPTools backend (Sequential, STDThread), default %(default)s")
    args = p.parse_args(argv)
    if args.threshold is not None:
        try:
            parts = [float(v) for v in args.threshold.split(",")]
        except ValueError:
            p.error("--threshold: expected LO or LO,HI")
        if len(parts) not in (1, 2):
            p.error("--threshold: expected LO or LO,HI")
        args.threshold = (parts[0], parts[1] if len(parts) == 2 else float("inf"))
        if args.labels:
            p.error("--threshold and --labels exclude each other")
    try:
        args.size = triple(args.size + ",1", int, "--size")[:2]
        args.phantom_dims = triple(args.phantom_dims, int, "--phantom-dims")
        args.raw_spacing = triple(args.raw_spacing, float, "--raw-spacing")
        if args.raw_dims:
            args.raw_dims = triple(args.raw_dims, int, "--raw-dims")
    except argparse.ArgumentTypeError as e:
        p.error(str(e))
    return args


def make_reader(args):
    """A reader (algorithm) for args.input and a short description of the input."""
    path = args.input
    lower = path.lower()
    if not os.path.exists(path):
        sys.exit("voxelbrep_run: no such file: %s" % path)
    from vtkmodules import vtkIOImage as io

    if lower.endswith(".vti"):
        reader = vtkXMLImageDataReader()
    elif lower.endswith((".mha", ".mhd")):
        reader = io.vtkMetaImageReader()
    elif lower.endswith((".nrrd", ".nhdr")):
        reader = io.vtkNrrdReader()
    elif lower.endswith((".nii", ".nii.gz")):
        reader = io.vtkNIFTIImageReader()
    elif lower.endswith(".png"):
        reader = io.vtkPNGReader()
    elif lower.endswith((".tif", ".tiff")):
        reader = io.vtkTIFFReader()
    elif args.raw_dims:
        reader = io.vtkImageReader2()
        getattr(reader, RAW_TYPES[args.raw_type])()
        nx, ny, nz = args.raw_dims
        reader.SetFileDimensionality(3)
        reader.SetDataExtent(0, nx - 1, 0, ny - 1, 0, nz - 1)
        reader.SetDataSpacing(*args.raw_spacing)
        reader.SetHeaderSize(args.raw_header)
        if args.raw_big_endian:
            reader.SetDataByteOrderToBigEndian()
        else:
            reader.SetDataByteOrderToLittleEndian()
        reader.SetFileName(path)
        return reader
    else:
        sys.exit("voxelbrep_run: unknown format of %s (for a raw volume give --raw-dims "
                 "and --raw-type)" % path)
    reader.SetFileName(path)
    return reader


def load_input(args):
    """The input image (vtkImageData) and its description."""
    if args.input is None:
        phantom = voxelbrep.vtkVoxelPhantomSource()
        phantom.SetDimensions(*args.phantom_dims)
        phantom.Update()
        return phantom.GetOutput(), "phantom %dx%dx%d" % tuple(args.phantom_dims)
    reader = make_reader(args)
    reader.Update()
    image = reader.GetOutput()
    if image is None or image.GetNumberOfPoints() == 0:
        sys.exit("voxelbrep_run: could not read %s" % args.input)
    attributes = image.GetCellData() if args.cell_data else image.GetPointData()
    scalars = attributes.GetScalars()
    if scalars is None and attributes.GetNumberOfArrays() > 0:
        attributes.SetActiveScalars(attributes.GetArrayName(0))
        scalars = attributes.GetScalars()
    if scalars is None and not args.cell_data:
        cd = image.GetCellData()
        if cd.GetScalars() is None and cd.GetNumberOfArrays() > 0:
            cd.SetActiveScalars(cd.GetArrayName(0))
        scalars = cd.GetScalars()
    if scalars is None:
        sys.exit("voxelbrep_run: %s has no scalars" % args.input)
    nc = scalars.GetNumberOfComponents()
    if nc > 1 and args.component is None:
        # A colour image: select on its luminance (alpha ignored).
        rgb = ns.vtk_to_numpy(scalars).astype(np.float64)
        if nc >= 3:
            grey = 0.2125 * rgb[:, 0] + 0.7154 * rgb[:, 1] + 0.0721 * rgb[:, 2]
        else:
            grey = rgb[:, 0]
        lum = ns.numpy_to_vtk(grey, deep=1)
        lum.SetName("Luminance")
        owner = image.GetPointData() if image.GetPointData().HasArray(
            scalars.GetName() or "") else image.GetCellData()
        owner.AddArray(lum)
        owner.SetActiveScalars("Luminance")
    dims = image.GetDimensions()
    return image, "%s %dx%dx%d" % (os.path.basename(args.input), dims[0], dims[1], dims[2])


def golden_colours(count, first=0):
    lut = vtkLookupTable()
    n = max(int(count), 1)
    lut.SetNumberOfTableValues(n)
    for i in range(n):
        h = ((first + i) * 0.6180339887498949) % 1.0
        s = 0.55 + 0.35 * (((first + i) * 7) % 3) / 2.0
        v = 0.75 + 0.25 * (((first + i) * 5) % 2)
        lut.SetTableValue(i, *colorsys.hsv_to_rgb(h, s, v), 1.0)
    lut.SetTableRange(first, first + n - 1)
    lut.Build()
    return lut


def render(polydata, args, path):
    """Renders the boundary from an oblique camera (3D) or face-on (2D) into a PNG."""
    import vtkmodules.vtkInteractionStyle  # noqa: F401
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                             vtkRenderWindow, vtkWindowToImageFilter)

    color_by = args.color_by
    if color_by == "auto":
        color_by = "label" if args.labels else "faceid"
    array_name = "Label" if color_by == "label" else "FaceId"
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(polydata)
    array = polydata.GetCellData().GetArray(array_name)
    if array is not None and array.GetNumberOfTuples() > 0:
        lo, hi = array.GetRange()
        mapper.SetScalarModeToUseCellFieldData()
        mapper.SelectColorArray(array_name)
        mapper.SetLookupTable(golden_colours(hi - lo + 1, int(lo)))
        mapper.UseLookupTableScalarRangeOn()
    else:
        mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetAmbient(0.25)
    actor.GetProperty().SetDiffuse(0.8)
    if polydata.GetNumberOfLines() > 0:
        actor.GetProperty().SetLineWidth(1.5)

    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.92, 0.93, 0.95)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*args.size)
    window.AddRenderer(renderer)

    b = polydata.GetBounds()
    centre = [(b[2 * d] + b[2 * d + 1]) / 2 for d in range(3)]
    extent = [b[2 * d + 1] - b[2 * d] for d in range(3)]
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(*centre)
    flat = [d for d in range(3) if extent[d] == 0]
    if flat:  # a 2D image: look at its plane face-on
        normal = [0.0, 0.0, 0.0]
        normal[flat[0]] = 1.0
        camera.SetPosition(*[c + n for c, n in zip(centre, normal)])
        camera.SetViewUp(*([0, 1, 0] if flat[0] == 2 else [0, 0, 1]))
        camera.ParallelProjectionOn()
    else:  # 3D: an oblique view from the front right, z up
        camera.SetPosition(centre[0] + 0.8, centre[1] - 1.25, centre[2] + 1.05)
        camera.SetViewUp(0, 0, 1)
    renderer.ResetCamera()
    camera.Zoom(1.15 if flat else 1.1)
    window.Render()

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def field(polydata, name):
    array = polydata.GetFieldData().GetArray(name)
    return int(array.GetValue(0)) if array is not None else 0


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    if args.backend:
        vtkSMPTools.SetBackend(args.backend)
    image, description = load_input(args)

    boundary = voxelbrep.vtkEVMBoundaryFilter()
    boundary.SetInputData(image)
    if args.cell_data:
        from vtkmodules.vtkCommonDataModel import vtkDataObject

        name = image.GetCellData().GetScalars().GetName()
        boundary.SetInputArrayToProcess(0, 0, 0, vtkDataObject.FIELD_ASSOCIATION_CELLS, name)
    if args.component is not None:
        boundary.SetArrayComponent(args.component)
    if args.labels:
        boundary.SetSelectionModeToLabels()
    elif args.threshold is not None:
        boundary.SetSelectionModeToRange()
        boundary.SetLowerThreshold(args.threshold[0])
        boundary.SetUpperThreshold(min(args.threshold[1], 1e300))
    getattr(boundary, "SetOutputModeTo" + args.mode.capitalize())()
    boundary.SetMergeNonManifoldFaces(args.merge_non_manifold)

    start = time.perf_counter()
    boundary.Update()
    elapsed_ms = (time.perf_counter() - start) * 1000.0
    out = boundary.GetOutput()
    if boundary.GetErrorCode() or out is None:
        sys.exit("voxelbrep_run: the filter failed")

    for path in (args.output, None if args.no_png else args.png):
        if path and os.path.dirname(path):
            os.makedirs(os.path.dirname(path), exist_ok=True)
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(out)
    writer.SetFileName(args.output)
    # Inline binary, not VTK's default appended mode: VTK 9.2's XML readers cannot parse
    # appended data with the expat of current Debian 12 (reparse deferral, VTK issue 19258),
    # so appended files would not open in ParaView 5.11 on such a machine.
    writer.SetDataModeToBinary()
    writer.SetCompressorTypeToZLib()
    if not writer.Write():
        sys.exit("voxelbrep_run: could not write %s" % args.output)
    written = [args.output]
    if not args.no_png:
        render(out, args, args.png)
        written.append(args.png)

    print("voxelbrep: %s: %d voxels, %d surfels, %d extreme vertices, %d faces, %d holes, "
          "%d %s cells, %.1f ms -> %s" % (
              description, field(out, "NumberOfVoxels"), field(out, "NumberOfSurfels"),
              field(out, "NumberOfExtremeVertices"), field(out, "NumberOfFaces"),
              field(out, "NumberOfHoles"), out.GetNumberOfCells(), args.mode, elapsed_ms,
              ", ".join(written)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
