"""Runs every Python snippet of README.md as a user would paste it, each in a fresh empty
directory: the snippets must be self-contained (no variable defined elsewhere) and work from
any directory. Snippets that use paraview.simple run under pvbatch with PV_PLUGIN_PATH set
to the built plugin; the others under the Python given here with PYTHONPATH set to the built
package (both as the README's comment lines say).

Usage: TestReadmeSnippets.py README.md PVBATCH PLUGIN_DIR PYTHONPATH
"""

import os
import re
import subprocess
import sys
import tempfile

BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def run_snippet(index, code, pvbatch, plugin_dir, pythonpath):
    env = dict(os.environ)
    if "paraview.simple" in code:
        command = [pvbatch, "snippet.py"]
        env["PV_PLUGIN_PATH"] = plugin_dir
    else:
        command = [sys.executable, "snippet.py"]
        env["PYTHONPATH"] = pythonpath + os.pathsep + env.get("PYTHONPATH", "")
    with tempfile.TemporaryDirectory(prefix="readme-snippet-") as work:
        with open(os.path.join(work, "snippet.py"), "w") as f:
            f.write(code)
        p = subprocess.run(command, cwd=work, env=env, capture_output=True, text=True,
                           timeout=300)
    output = p.stdout + p.stderr
    if p.returncode != 0 or "Traceback" in output or "ERR|" in output:
        print("FAIL snippet %d (%s):\n%s\n--- output:\n%s" % (
            index, os.path.basename(command[0]), code, output[-3000:]))
        return False
    print("ok   snippet %d (%s): %s" % (index, os.path.basename(command[0]),
                                       output.strip().splitlines()[-1:] or ""))
    return True


def main(readme, pvbatch, plugin_dir, pythonpath):
    with open(readme) as f:
        snippets = BLOCK.findall(f.read())
    if not snippets:
        print("FAIL: no Python snippet found in", readme)
        return 1
    results = [run_snippet(i, code, pvbatch, plugin_dir, pythonpath)
               for i, code in enumerate(snippets)]
    print("%d of %d snippets ran" % (sum(results), len(results)))
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
