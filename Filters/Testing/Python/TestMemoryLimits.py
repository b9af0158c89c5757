"""Inputs too large for the memory this process may use: each case runs in a subprocess
under an address-space limit (ulimit -v), so that a crash is one failed case, not a dead
suite. Every case must end with exit code 0, the expected error message and an empty
output; none may abort on a failed allocation.
"""

import os
import resource
import subprocess
import sys
import textwrap

MiB = 1024 * 1024
HERE = os.path.dirname(os.path.abspath(__file__))

# (name, address-space limit in MiB or None, script, text the error must contain,
#  text the standard output must contain)
CASES = [
    ("phantom of 10^15 voxels", None, """
        p = voxelbrep.vtkVoxelPhantomSource()
        p.SetDimensions(100000, 100000, 100000)
        p.Update()
        print("points", p.GetOutput().GetNumberOfPoints())
     """, "The phantom needs about", "points 0"),
    ("phantom over ulimit -v", 700, """
        p = voxelbrep.vtkVoxelPhantomSource()
        p.SetDimensions(800, 800, 800)
        p.Update()
        print("points", p.GetOutput().GetNumberOfPoints())
     """, "can be allocated", "points 0"),
    ("CUDB label image over ulimit -v", 700, """
        import numpy as np
        from voxelbrep_testing import make_image
        f = voxelbrep.vtkCUDBConnectivity()
        f.SetInputData(make_image(np.zeros((512, 512, 512), np.uint8)))
        f.Update()
        print("regions", f.GetRegionsOutput().GetNumberOfRows())
     """, "voxels needs about", "regions 0"),
] + [
    ("%s on a 128^3 checkerboard under ulimit -v" % name, 500, """
        import numpy as np
        from voxelbrep_testing import make_image
        z, y, x = np.indices((128, 128, 128), dtype=np.int16)
        f = voxelbrep.%s()
        f.SetInputData(make_image(((x + y + z) %% 2).astype(np.uint8)))
        del x, y, z
        f.Update()
        print("finished")
     """ % name, "can still be allocated|can be allocated", "finished")
    for name in ("vtkCUDBConnectivity", "vtkEVMBoundaryFilter", "vtkStandardPlanePolyhedrizer")
] + [
    ("phantom within ulimit -v", 700, """
        p = voxelbrep.vtkVoxelPhantomSource()
        p.SetDimensions(100, 100, 100)
        p.Update()
        print("points", p.GetOutput().GetNumberOfPoints())
     """, None, "points 1000000"),
]


def limit(mib):
    def apply():
        if mib is not None:
            resource.setrlimit(resource.RLIMIT_AS, (mib * MiB, mib * MiB))
    return apply


def run_case(name, mib, body, error, stdout):
    script = ("import sys\nsys.path.insert(0, %r)\nimport voxelbrep\n" % HERE
              + textwrap.dedent(body))
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                       preexec_fn=limit(mib), timeout=300, env=os.environ)
    problems = []
    if p.returncode != 0:
        problems.append("exit code %d" % p.returncode)
    if error is not None and not any(e in p.stderr for e in error.split("|")):
        problems.append("no error containing %r" % error)
    if error is None and "ERR|" in p.stderr:
        problems.append("an unexpected error")
    if stdout not in p.stdout:
        problems.append("stdout lacks %r" % stdout)
    if problems:
        print("FAIL %s: %s\n  stdout: %s\n  stderr: %s" % (
            name, ", ".join(problems), p.stdout.strip(), p.stderr.strip()[-2000:]))
        return False
    print("ok   %s" % name)
    return True


def main():
    failed = [c[0] for c in CASES if not run_case(*c)]
    print("%d of %d cases passed" % (len(CASES) - len(failed), len(CASES)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
