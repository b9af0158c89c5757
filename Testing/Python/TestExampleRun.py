"""Runs Examples/voxelbrep_run.py (the main job) on every input format it reads and checks its
summary line against numpy counts computed here from the same voxels.

Usage: TestExampleRun.py formats SCRIPT WORK_DIR
         writes a small phantom as .vti, .mha, .mhd, .nii, .nii.gz, .nhdr (+ .raw), .raw,
         .tif and a 2D slice as .png, then runs SCRIPT on each (Positive, Range and Labels
         selections, every output mode) and reads back the .vtp it wrote;
       TestExampleRun.py data SCRIPT DATA_DIR WORK_DIR
         runs SCRIPT on real volumes of the shared data directory and checks the MANIFEST
         numbers (foreground voxels, extreme vertices); exits 77 (skipped) without the data.

SCRIPT runs with --no-png (no display needed); the rendering path is tested by the test
that runs it with its defaults.
"""

import os
import re
import subprocess
import sys

import numpy as np

# The numpy references shared by the Python tests (Filters/Testing/Python).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "Filters", "Testing", "Python"))
from voxelbrep_testing import extreme_vertices, surfel_count  # noqa: E402

SUMMARY = re.compile(r"(\d+) voxels, (\d+) surfels, (\d+) extreme vertices, (\d+) faces, "
                     r"(\d+) holes, (\d+) (\w+) cells")
failures = []


def expect(what, got, expected):
    ok = got == expected
    print("%-70s %-6s got %r, expected %r" % (what, "ok" if ok else "FAILED", got, expected))
    if not ok:
        failures.append(what)


def run(script, work, name, args):
    """Runs the example; returns its summary numbers and the path of the .vtp."""
    out = os.path.join(work, re.sub(r"\W+", "_", name) + ".vtp")
    cmd = [sys.executable, script] + args + ["--output", out, "--no-png"]
    print("+", " ".join(cmd))
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True)
    lines = [l for l in proc.stdout.splitlines() if l.strip()]
    if proc.returncode != 0 or len(lines) != 1 or not SUMMARY.search(lines[0]):
        print(proc.stdout, proc.stderr)
        expect(name + ": exit code 0 and one summary line",
               (proc.returncode, len(lines)), (0, 1))
        return None, out
    print("  " + lines[0])
    m = SUMMARY.search(lines[0])
    values = dict(zip(("voxels", "surfels", "ev", "faces", "holes", "cells"),
                      (int(g) for g in m.groups()[:6])))
    return values, out


def check_run(script, work, name, args, masks, planar=False):
    values, out = run(script, work, name, args)
    if values is None:
        return
    expect(name + ": voxels", values["voxels"], sum(int(m.sum()) for m in masks))
    expect(name + ": extreme vertices", values["ev"], sum(extreme_vertices(m) for m in masks))
    if not planar:
        expect(name + ": surfels", values["surfels"], sum(surfel_count(m) for m in masks))
    expect(name + ": has cells", values["cells"] > 0, True)
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(out)
    reader.Update()
    written = reader.GetOutput()
    expect(name + ": .vtp cells", written.GetNumberOfCells(), values["cells"])
    ev = written.GetFieldData().GetArray("NumberOfExtremeVertices")
    expect(name + ": .vtp field data", int(ev.GetValue(0)) if ev else None, values["ev"])


def formats(script, work):
    import voxelbrep
    from vtkmodules import vtkIOImage as io
    from vtkmodules.util import numpy_support as ns
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

    os.makedirs(work, exist_ok=True)
    phantom = voxelbrep.vtkVoxelPhantomSource()
    phantom.SetDimensions(40, 36, 32)
    phantom.Update()
    image = phantom.GetOutput()
    labels = ns.vtk_to_numpy(image.GetPointData().GetArray("Labels")).reshape(32, 36, 40)

    def write(writer, name):
        path = os.path.join(work, name)
        writer.SetFileName(path)
        writer.SetInputData(image)
        writer.Write()
        return path

    vti = vtkXMLImageDataWriter()
    vti.SetDataModeToBinary()  # appended data does not parse with Debian 12's expat
    files = {
        "vti": write(vti, "phantom.vti"),
        "mha": write(io.vtkMetaImageWriter(), "phantom.mha"),
        "nii": write(io.vtkNIFTIImageWriter(), "phantom.nii"),
        "nii.gz": write(io.vtkNIFTIImageWriter(), "phantom.nii.gz"),
        "tif": write(io.vtkTIFFWriter(), "phantom.tif"),
    }
    mhd = io.vtkMetaImageWriter()
    mhd.SetRAWFileName(os.path.join(work, "phantom_mhd.raw"))
    files["mhd"] = write(mhd, "phantom.mhd")
    raw = os.path.join(work, "phantom_40x36x32.raw")
    labels.astype(np.uint8).tofile(raw)
    files["raw"] = raw
    with open(os.path.join(work, "phantom.nhdr"), "w") as f:
        f.write("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 40 36 32\nspacings: 1 1 1\n"
                "encoding: raw\ndata file: phantom_40x36x32.raw\n")
    files["nhdr"] = os.path.join(work, "phantom.nhdr")
    raw16 = os.path.join(work, "phantom_int16be.raw")
    (labels.astype(np.int16) * 100 - 50).astype(">i2").tofile(raw16)

    positive = [labels > 0]
    per_label = [labels == k for k in range(1, 6)]
    for fmt, path in sorted(files.items()):
        extra = ["--raw-dims", "40,36,32", "--raw-type", "uint8"] if fmt == "raw" else []
        check_run(script, work, "%s positive" % fmt, [path] + extra, positive)
    check_run(script, work, "nhdr labels polygons", [files["nhdr"], "--labels", "--mode",
                                                     "polygons"], per_label)
    check_run(script, work, "vti range polylines", [files["vti"], "--threshold", "2,4",
                                                    "--mode", "polylines"],
              [(labels >= 2) & (labels <= 4)])
    check_run(script, work, "raw int16 big-endian range surfels",
              [raw16, "--raw-dims", "40,36,32", "--raw-type", "int16", "--raw-big-endian",
               "--threshold", "250", "--mode", "surfels"], [labels >= 3])
    # No input: the built-in phantom.
    small = voxelbrep.vtkVoxelPhantomSource()
    small.SetDimensions(24, 20, 16)
    small.Update()
    small_labels = ns.vtk_to_numpy(small.GetOutput().GetPointData().GetArray("Labels"))
    check_run(script, work, "phantom 24x20x16 merged",
              ["--phantom-dims", "24,20,16", "--merge-non-manifold"],
              [small_labels.reshape(16, 20, 24) > 0])

    # A 2D slice as an 8-bit PNG (values label * 40): a 2D image with its contours.
    slice2d = labels[16]
    png_image = ns.numpy_to_vtk((slice2d.astype(np.uint8) * 40).ravel(), deep=1)
    from vtkmodules.vtkCommonDataModel import vtkImageData

    im = vtkImageData()
    im.SetDimensions(40, 36, 1)
    im.GetPointData().SetScalars(png_image)
    w = io.vtkPNGWriter()
    w.SetFileName(os.path.join(work, "slice.png"))
    w.SetInputData(im)
    w.Write()
    check_run(script, work, "png 2D threshold", [os.path.join(work, "slice.png"),
                                                 "--threshold", "60,255"], [slice2d >= 2],
              planar=True)


def data(script, data_dir, work):
    if not os.path.isdir(data_dir):
        print("SKIPPED: the shared data directory %s is absent" % data_dir)
        sys.exit(77)
    os.makedirs(work, exist_ok=True)
    cases = [
        # name, arguments, (foreground voxels, extreme vertices) from MANIFEST.md
        ("engine nhdr v>=55", ["engine/engine_256x256x128_uint8.nhdr", "--threshold", "55"],
         (1216197, 85866)),
        ("aneurism nhdr v>=55", ["aneurism/aneurism_256x256x256_uint8.nhdr", "--threshold",
                                 "55"], (89088, 70260)),
        ("headsq raw int16 v>=500", ["headsq/headsq_quarter_64x64x93_int16le.raw",
                                     "--raw-dims", "64,64,93", "--raw-type", "int16",
                                     "--raw-spacing", "3.2,3.2,1.5", "--threshold", "500"],
         (144968, 10462)),
        ("dgtal_al raw v==1", ["dgtal_al/dgtal_al_100x100x100_uint8.raw", "--raw-dims",
                               "100,100,100", "--threshold", "1,1"], (70413, 9934)),
        ("aal nii.gz label>0", ["mricron/aal.nii.gz"], (1479969, 74120)),
        ("page png v<=157", ["2d/skimage/page.png", "--threshold", "0,157"], (26526, 5848)),
        ("horse png grey<128", ["2d/skimage/horse.png", "--threshold", "0,127.999"],
         (43412, 1180)),
    ]
    for name, args, (fg, ev) in cases:
        path = os.path.join(data_dir, args[0])
        if not os.path.exists(path):
            print("note: %s absent, case skipped" % path)
            continue
        values, _ = run(script, work, name, [path] + args[1:])
        if values is not None:
            expect(name + ": voxels (MANIFEST)", values["voxels"], fg)
            expect(name + ": extreme vertices (MANIFEST)", values["ev"], ev)


def main():
    mode = sys.argv[1]
    if mode == "formats":
        formats(sys.argv[2], sys.argv[3])
    elif mode == "data":
        data(sys.argv[2], sys.argv[3], sys.argv[4])
    else:
        sys.exit("unknown mode " + mode)
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
