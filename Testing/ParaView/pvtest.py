"""Helpers shared by the pvbatch tests: counted, printed checks; field values; the render
view and the image comparison of the regression tests; and the numpy references of the
Python tests (Filters/Testing/Python/voxelbrep_testing.py) on the path.
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "Filters", "Testing", "Python"))

from paraview.simple import CreateView, Render  # noqa: E402

failures = []


def expect(what, got, expected):
    """Prints the check (FAILED marks a failure for ctest) and remembers failures."""
    status = "ok" if got == expected else "FAILED"
    print("%-60s %-6s got %r, expected %r" % (what, status, got, expected))
    if got != expected:
        failures.append(what)


def field(data, name):
    """A one-value field data array as an int, or None when absent."""
    array = data.GetFieldData().GetArray(name)
    return None if array is None else int(array.GetValue(0))


def finish():
    """Exits with 1 when a check failed."""
    if failures:
        print("FAILED: %d check(s): %s" % (len(failures), failures))
        sys.exit(1)


def render_view(size=(400, 400)):
    """A render view with a fixed size and light background, no orientation axes."""
    view = CreateView("RenderView")
    view.ViewSize = list(size)
    view.OrientationAxesVisibility = 0
    try:  # ParaView >= 5.10: the palette would override the background
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.Background = [0.92, 0.93, 0.95]
    return view


def compare_with_baseline(view, centre, offset, baseline, temp_dir):
    """Looks at `centre` from `centre + offset` (z up), renders, and compares with the
    baseline; raises (and so fails the test) when they differ or the baseline is missing."""
    from vtkmodules.test import Testing
    Testing.VTK_TEMP_DIR = temp_dir
    view.CameraFocalPoint = list(centre)
    view.CameraPosition = [c + o for c, o in zip(centre, offset)]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    Render(view)
    Testing.compareImage(view.GetRenderWindow(), baseline, threshold=10)
    print("image matches", baseline)
