#!/usr/bin/python3
"""Every tool's command line (ctest: tools.cli): --format pdf writes a PDF, a user error exits 1 with one line
'TOOL: error: ...' on stderr and no traceback.

    /usr/bin/python3 tests/tools/test_tools_cli.py BUILD/rondel

Inputs: a tiny run of the current build (tests/tools/rondel_run.py) for picture.py, h5info.py and
error_vs_runtime.py; small synthetic measures.csv files for shear.py and biaxial.py; a triangular heap of
touching discs (a Rondel checkpoint written with h5py) for repose.py. Prints 'N passed, N failed'.
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.abspath(os.path.join(HERE, "..", "..", "tools"))
sys.path.insert(0, HERE)
from rondel_run import Checks, make_run  # noqa: E402

check = Checks()


def tool(name, *args):
    """(exit status, stdout, stderr) of /usr/bin/python3 tools/NAME.py ARGS."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([sys.executable, os.path.join(TOOLS, name + ".py")] + [str(a) for a in args],
                       capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stdout, p.stderr


def is_pdf(path):
    try:
        with open(path, "rb") as f:
            return f.read(5) == b"%PDF-" and os.path.getsize(path) > 1000
    except OSError:
        return False


def user_error(name, *args):
    """A user error: exit 1, the last stderr line 'NAME: error: ...', no traceback."""
    rc, out, err = tool(name, *args)
    lines = err.strip().splitlines()
    ok = rc == 1 and "Traceback" not in err and lines and lines[-1].startswith(f"{name}: error: ")
    check(f"{name}: a user error ({' '.join(map(str, args))}) exits 1 with one line, no traceback", ok, (rc, err))


def write_measures(path, cols):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    names = list(cols)
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for k in range(len(cols[names[0]])):
            f.write(",".join(repr(float(cols[c][k])) for c in names) + "\n")


def shear_measures(d):
    g = np.linspace(0.0, 0.5, 60)
    write_measures(os.path.join(d, "measures.csv"), {"step": np.arange(60), "time": g, "height": 0.1 + 0.001 * g,
                   "wall_syy": np.full(60, 1e4), "wall_tau": 4e3 * (1 - np.exp(-g / 0.05)), "shear_disp": 0.1 * g})
    return d


def biaxial_measures(d):
    e = np.linspace(0.0, 0.15, 60)
    s3 = np.full(60, 1e5)
    s1 = s3 * (1 + 2 * (1 - np.exp(-e / 0.02)))
    write_measures(os.path.join(d, "measures.csv"), {"step": np.arange(60), "eps_axial": e, "eps_vol": -0.1 * e,
                   "wall_sxx": s3, "wall_syy": s1, "sxx": s3, "syy": s1})
    return d


def heap_file(path, rows=24, R=0.001):
    """A triangle of touching discs (60 degree flanks): a Rondel checkpoint with gid, radius, position."""
    import h5py
    pos = [((i + 0.5 * j) * 2 * R, R + j * math.sqrt(3) * R) for j in range(rows) for i in range(rows - j)]
    pos = np.array(pos)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with h5py.File(path, "w") as f:
        for k, v in (("format", np.bytes_("rondel")), ("kind", np.bytes_("checkpoint")), ("step", np.int64(1)),
                     ("format_version", np.int64(1)), ("complete", np.int64(1))):
            f.attrs[k] = v
        g = f.create_group("discs")
        g["gid"] = np.arange(len(pos), dtype=np.int64)
        g["radius"] = np.full(len(pos), R)
        g["position"] = pos
    return path


def main():
    if len(sys.argv) != 2 or not os.access(sys.argv[1], os.X_OK):
        print("usage: test_tools_cli.py BUILD/rondel (an executable)", file=sys.stderr)
        return 1
    rondel = os.path.abspath(sys.argv[1])
    tmp = tempfile.mkdtemp(prefix="rondel-cli-")
    try:
        run = make_run(rondel, os.path.join(tmp, "run"))
        missing = os.path.join(tmp, "no_such_input")
        cases = [
            ("picture", [run, "--kind", "rotation", "--field", "omega", "--out", f"{tmp}/pic"], f"{tmp}/pic.pdf"),
            ("picture", [run, "--kind", "forces", "--out", f"{tmp}/forces"], f"{tmp}/forces.pdf"),
            ("shear", [shear_measures(f"{tmp}/shear"), "--out", f"{tmp}/sh"], f"{tmp}/sh_series.pdf"),
            ("biaxial", [biaxial_measures(f"{tmp}/biax"), "--out", f"{tmp}/bx"], f"{tmp}/bx_curves.pdf"),
            ("repose", [heap_file(f"{tmp}/heap/checkpoint_0000000001.h5"), "--out", f"{tmp}/rp"], f"{tmp}/rp.pdf"),
            ("error_vs_runtime", ["--rondel", rondel, "--quick", "--cases", "a", "--out", f"{tmp}/evr"],
             f"{tmp}/evr/error_vs_runtime.pdf"),
        ]
        for name, args, pdf in cases:
            rc, out, err = tool(name, *args, "--format", "pdf", "--dpi", "100")
            check(f"{name} {args[2] if name == 'picture' else ''} --format pdf: exit 0, writes a PDF",
                  rc == 0 and is_pdf(pdf), (rc, err[-600:]))
        rc, out, err = tool("picture", run, "--kind", "rotation", "--field", "omega", "--out", f"{tmp}/svg",
                           "--format", "svg")
        check("picture --format svg: an SVG", rc == 0 and open(f"{tmp}/svg.svg").read(200).find("<svg") >= 0, err)
        for name in ("picture", "shear", "biaxial", "repose", "h5info"):
            extra = ["--kind", "rotation", "--out", f"{tmp}/x"] if name == "picture" else []
            user_error(name, missing, *extra)
        user_error("picture", run, "--kind", "rotation", "--out", f"{tmp}/x", "--format", "gif")
        user_error("repose", run, "--dpi", "0")
        user_error("error_vs_runtime", "--rondel", missing)
        user_error("biaxial_sweep", "--rondel", missing)
        user_error("biaxial_sensitivity", "--rondel", missing)
        user_error("h5info", os.path.join(run, "log.txt"))
        rc, out, err = tool("repose", os.path.join(run, "checkpoint_0000000300.h5"), "--out", f"{tmp}/flat", "--no-plot")
        check("repose on a flat layer: exit 2 (no heap), one line", rc == 2 and "Traceback" not in err
              and "repose: error:" in err, (rc, err))
        rc, out, err = tool("h5info", os.path.join(run, "checkpoint_0000000300.h5"))
        check("h5info on a checkpoint of this build: exit 0, checksums verified", rc == 0 and "verified" in out, err)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
