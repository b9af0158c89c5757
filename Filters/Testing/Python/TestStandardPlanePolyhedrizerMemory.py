"""Peak memory of vtkStandardPlanePolyhedrizer against vtkDiscreteFlyingEdges3D on the same
image, each run once in a fresh subprocess (so that neither inherits the other's freed pages):
the rise of the resident set's high-water mark (VmHWM, reset through /proc/self/clear_refs) over
the resident set just before the update, per boundary surfel (counted here with numpy). On a 3D
checkerboard every voxel is its own object face, the worst case for the faces' own storage.
Before the surfel graph lost its stored corners and hash index and the reversion its sorted list
of surfels, the filter took about 8x the memory of Flying Edges here (445 bytes per surfel on a
64^3 checkerboard); now about 3.6x (210 bytes). The bounds: 5x, and 260 bytes per surfel.
"""

import subprocess
import sys

import numpy as np

from voxelbrep_testing import Checker

check = Checker("TestStandardPlanePolyhedrizerMemory")

CHILD = r"""
import sys
import numpy as np
import voxelbrep
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersGeneral import vtkDiscreteFlyingEdges3D

def status(field):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
    return -1

n = int(sys.argv[1])
z, y, x = np.indices((n, n, n))
values = ((x + y + z) % 2).astype(np.uint8)
image = vtkImageData()
image.SetDimensions(n, n, n)
array = ns.numpy_to_vtk(values.ravel(), deep=1)
array.SetName("s")
image.GetPointData().SetScalars(array)
if sys.argv[2] == "dfe":
    f = vtkDiscreteFlyingEdges3D()
    f.SetValue(0, 1)
    f.ComputeNormalsOff()
    f.ComputeGradientsOff()
else:
    f = voxelbrep.vtkStandardPlanePolyhedrizer()
f.SetInputData(image)
try:
    with open("/proc/self/clear_refs", "w") as c:
        c.write("5")
except OSError:
    print(-1, 0)  # the high-water mark cannot be reset here
    sys.exit(0)
before = status("VmRSS")
f.Update()
print(status("VmHWM") - before, f.GetOutput().GetNumberOfCells())
"""


def peak(n, which):
    out = subprocess.run([sys.executable, "-c", CHILD, str(n), which], check=True,
                         capture_output=True, text=True).stdout.split()
    return int(out[0]), int(out[1])


def main():
    n = 48
    z, y, x = np.indices((n, n, n))
    surfels = 6 * int(((x + y + z) % 2).sum())  # every selected voxel is alone
    filter_bytes, cells = peak(n, "filter")
    dfe_bytes, _ = peak(n, "dfe")
    if filter_bytes < 0:
        print("skipped: /proc/self/clear_refs cannot be written on this system")
        check.finish()
        return
    check.true("the filter ran (%d cells)" % cells, cells > 0)
    per_surfel = filter_bytes / surfels
    print("peak bytes per surfel: filter %.0f, DiscreteFlyingEdges3D %.0f"
          % (per_surfel, dfe_bytes / surfels))
    check.true("at most 260 bytes per surfel (got %.0f)" % per_surfel, per_surfel <= 260)
    check.true("at most 5x Flying Edges' peak (got %.1fx)" % (filter_bytes / dfe_bytes),
               filter_bytes <= 5 * dfe_bytes)
    check.finish()


main()
