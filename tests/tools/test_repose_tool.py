#!/usr/bin/python3
"""Tests of tools/repose.py on synthetic heaps with known flank angles (ctest: tools.repose).

A heap is equal discs (R = 1.25 mm) on a triangular lattice resting on a floor at y = 0, keeping the discs
whose top lies below the flanks y = H - tan(angle) |x - x_apex|; decoys that the tool must ignore are added:
discs that rolled away on the floor, a disc in flight above the apex and one above a flank. Each case is
written as a run directory (final.csv in hexadecimal floats + checkpoint_*.h5 with /discs/gid, radius,
position, the layout of FORMAT.md) and measured with repose.main() (the missing-file case runs the command).

Asserts: the left, right and mean angles within TOL_DEG = 1 deg of the flank angles for 30/30, 20/20 and
an asymmetric 25/35 heap; the same result from an .h5 file alone; the three output files; a missing run
directory and a directory without a checkpoint give a non-zero exit with a message naming the problem.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import contextlib
import csv
import io
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "repose.py")
sys.path.insert(0, os.path.dirname(TOOL))
import repose  # noqa: E402
PY = sys.executable or "/usr/bin/python3"
TOL_DEG = 1.0
R = 1.25e-3

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


def heap(left_deg, right_deg, height=0.06, x_apex=0.01):
    """Centres (n, 2) and radii (n) of a lattice heap with the given flank angles, plus decoys."""
    tl, tr = math.tan(math.radians(left_deg)), math.tan(math.radians(right_deg))
    dy = math.sqrt(3.0) * R
    pts = []
    for row in range(int(height / dy) + 2):
        y = R + row * dy
        shift = R if row % 2 else 0.0
        for i in range(-400, 401):
            x = x_apex + shift + 2.0 * R * i
            surf = height - (tl * (x_apex - x) if x < x_apex else tr * (x - x_apex))
            if y + R <= surf:
                pts.append((x, y))
    pts = np.array(pts)
    decoys = np.array([
        (x_apex - height / tl - 0.08, R),          # rolled away, left
        (x_apex - height / tl - 0.05, R),
        (x_apex + height / tr + 0.06, R),          # rolled away, right
        (x_apex + height / tr + 0.09, R),
        (x_apex + height / tr + 0.09 + 2 * R, R),  # two touching discs on the floor
        (x_apex, height + 8 * R),                  # in flight above the apex
        (x_apex + 0.5 * height / tr, 0.5 * height + 6 * R),  # in flight above the right flank
    ])
    pos = np.vstack([pts, decoys])
    return pos, np.full(len(pos), R)


def write_run(d, pos, radius, final_csv=True, h5=True):
    os.makedirs(d, exist_ok=True)
    n = len(radius)
    if final_csv:
        with open(os.path.join(d, "final.csv"), "w") as f:
            f.write("gid,x,y,vx,vy,theta,omega\n")
            z = (0.0).hex()
            for k in range(n):
                f.write(f"{k},{float(pos[k, 0]).hex()},{float(pos[k, 1]).hex()},{z},{z},{z},{z}\n")
    if h5:
        import h5py
        with h5py.File(os.path.join(d, "checkpoint_0000001000.h5"), "w") as f:
            f.attrs["format"] = np.bytes_("rondel")
            f.attrs["kind"] = np.bytes_("checkpoint")
            f.attrs["step"] = np.int64(1000)
            f.attrs["format_version"] = np.int64(1)
            f.attrs["complete"] = np.int64(1)
            g = f.create_group("discs")
            g["gid"] = np.arange(n, dtype=np.int64)
            g["radius"] = radius.astype(np.float64)
            g["position"] = pos.astype(np.float64)


def run_tool(*args):
    """repose.main(args) in this process: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = repose.main(list(args))
    return rc, out.getvalue(), err.getvalue()


def run_command(*args):
    """The tool as a command: (exit status, stdout, stderr)."""
    p = subprocess.run([PY, TOOL, *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def read_angles(path):
    with open(path) as f:
        return {r["side"]: r for r in csv.DictReader(f)}


def case(tmp, name, left, right, plot=False, **kw):
    d = os.path.join(tmp, name)
    pos, radius = heap(left, right, **kw)
    write_run(d, pos, radius)
    rc, out, err = run_tool(d, "--out", os.path.join(tmp, name + "_rep"), *([] if plot else ["--no-plot"]))
    check(f"{name}: exit 0", rc == 0, err)
    if rc != 0:
        return None
    a = read_angles(os.path.join(tmp, name + "_rep_angles.csv"))
    got = {s: float(a[s]["angle_deg"]) for s in ("left", "right", "mean")}
    want = {"left": left, "right": right, "mean": 0.5 * (left + right)}
    for s in ("left", "right", "mean"):
        check(f"{name}: {s} angle {got[s]:.2f} within {TOL_DEG} deg of {want[s]}",
              abs(got[s] - want[s]) <= TOL_DEG, got[s])
    check(f"{name}: at least 8 points per flank",
          int(a["left"]["points"]) >= 8 and int(a["right"]["points"]) >= 8, (a["left"]["points"], a["right"]["points"]))
    check(f"{name}: residual below one radius", float(a["mean"]["rms_residual_m"]) < R, a["mean"]["rms_residual_m"])
    return d, got


def main():
    with tempfile.TemporaryDirectory() as tmp:
        r30 = case(tmp, "heap30", 30.0, 30.0, plot=True)
        case(tmp, "heap20", 20.0, 20.0, height=0.05)
        case(tmp, "heap25_35", 25.0, 35.0)

        if r30:
            d, got = r30
            for suffix in (".png", ".csv", "_angles.csv"):
                p = os.path.join(tmp, "heap30_rep" + suffix)
                check(f"output {os.path.basename(p)} written", os.path.isfile(p) and os.path.getsize(p) > 0, p)
            with open(os.path.join(tmp, "heap30_rep.csv")) as f:
                roles = [row["role"] for row in csv.DictReader(f)]
            check("profile marks one apex and both flanks",
                  roles.count("apex") == 1 and "left" in roles and "right" in roles, set(roles))
            # The same heap from the .h5 file alone (positions and radii from the checkpoint).
            rc, out, err = run_tool(os.path.join(d, "checkpoint_0000001000.h5"), "--out",
                                    os.path.join(tmp, "h5only"), "--no-plot")
            ok = rc == 0
            if ok:
                a = read_angles(os.path.join(tmp, "h5only_angles.csv"))
                ok = abs(float(a["mean"]["angle_deg"]) - got["mean"]) < 1e-3
            check(".h5 file alone gives the same mean angle", ok, err or out)

        # A missing run directory, through the command line: non-zero exit, a message naming it.
        missing = os.path.join(tmp, "no_such_run")
        rc, out, err = run_command(missing)
        check("missing directory: exit 1, no traceback", rc == 1 and "Traceback" not in err, (rc, err))
        check("missing directory: clear message", "no such run directory or file" in err and missing in err, err)

        # final.csv without any checkpoint or snapshot (no radii): non-zero exit, a message saying so.
        d = os.path.join(tmp, "no_h5")
        pos, radius = heap(30.0, 30.0)
        write_run(d, pos, radius, h5=False)
        rc, out, err = run_tool(d, "--no-plot")
        check("no checkpoint: exit 1", rc == 1, rc)
        check("no checkpoint: clear message", "checkpoint_*.h5" in err, err)

        # A flat layer (no heap): non-zero exit with a message.
        d = os.path.join(tmp, "flat")
        xs = np.arange(100) * 2 * R
        write_run(d, np.column_stack([xs, np.full(100, R)]), np.full(100, R))
        rc, out, err = run_tool(d, "--no-plot")
        check("flat layer: exit 2 (no heap to measure) and a message", rc == 2 and "no heap" in err, (rc, err))

    passed = sum(results)
    failed = len(results) - passed
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
