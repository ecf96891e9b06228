#!/usr/bin/python3
"""Tests of tools/drum.py (ctest: tools.drum).

1. Synthetic beds with a known tilt: equal discs (R = 1.25 mm) on a triangular lattice whose rows are
   parallel to a flat free surface tilted by beta, filling the part of a drum (R_c = 0.05 m) below that
   surface (about a third of the drum), plus a disc in flight above the surface. Written as snapshots
   (FORMAT.md, version 3: /walls with one circle wall, kind 2, centre p0, radius, omega). Both measures of
   the tool (the centre-of-mass line and the fitted free surface) must give beta within TOL_DEG = 1 deg, for
   beta = 30 deg with the drum turning counter-clockwise and for the mirrored bed (beta = 25 deg) with the
   drum turning clockwise (both angles positive when the bed leans the way the drum turns); only the
   snapshots at t >= --from are measured; the three output files are written.
2. With the rondel executable (argv[1]): a tiny drum run (50 discs in a drum of 0.02 m turning at 5 rad/s,
   40,000 steps = 0.64 s, snapshots every 4,000) is measured (exit 0, an angle between 0 and 60 deg: the bed
   leans the way the drum turns), and the sweep mode runs two laws and two mu_r (mu_r = 0 shared: three
   runs, two jobs at a time, 300 steps each on inputs/drum.ini), writes its table, a second call reuses
   every finished run, and a third runs again the one whose summary.txt was made to say it stopped.
3. Errors: a missing run directory and a directory without snapshots give exit status 1 with a message.
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
ROOT = os.path.join(HERE, "..", "..")
TOOL = os.path.join(ROOT, "tools", "drum.py")
sys.path.insert(0, os.path.dirname(TOOL))
import drum  # noqa: E402
PY = sys.executable or "/usr/bin/python3"
TOL_DEG = 1.0
R = 1.25e-3
R_C = 0.05

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


def bed(beta_deg, omega, depth=0.23 * R_C):
    """Disc centres (n, 2) of a bed below a flat surface tilted by beta (rising towards +x for omega > 0, -x
    for omega < 0) at the distance `depth` below the drum centre, plus one disc in flight above it."""
    b = math.radians(beta_deg) * (1.0 if omega >= 0 else -1.0)
    c, s = math.cos(b), math.sin(b)
    dy = math.sqrt(3.0) * R
    pts = []
    for row in range(int(R_C / dy) + 2):
        v = -depth - R - row * dy  # rows parallel to the surface v = -depth, in the surface's frame (u, v)
        shift = R if row % 2 else 0.0
        for i in range(-60, 61):
            u = shift + 2.0 * R * i
            if math.hypot(u, v) + R <= R_C:
                pts.append((c * u - s * v, s * u + c * v))
    flight = (c * 0.0 - s * (-depth + 6 * R), s * 0.0 + c * (-depth + 6 * R))
    return np.array(pts + [flight])


def write_snapshot(d, step, time, pos, omega):
    import h5py
    os.makedirs(d, exist_ok=True)
    n = len(pos)
    with h5py.File(os.path.join(d, f"snapshot_{step:010d}.h5"), "w") as f:
        f.attrs["format"] = np.bytes_("rondel")
        f.attrs["kind"] = np.bytes_("snapshot")
        f.attrs["step"] = np.int64(step)
        f.attrs["time"] = np.float64(time)
        f.attrs["format_version"] = np.int64(3)
        f.attrs["complete"] = np.int64(1)
        g = f.create_group("discs")
        g["position"] = np.asarray(pos, dtype=np.float64)
        g["radius"] = np.full(n, R)
        w = f.create_group("walls")
        w["kind"] = np.array([2], dtype=np.int32)
        w["p0"] = np.zeros((1, 2))
        w["p1"] = np.zeros((1, 2))
        w["normal"] = np.zeros((1, 2))
        w["radius"] = np.array([R_C])
        w["omega"] = np.array([omega])


def run_tool(*args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = drum.main(list(args))
    return rc, out.getvalue(), err.getvalue()


def read_angles(path):
    with open(path) as f:
        return {r["method"]: r for r in csv.DictReader(f)}


def synthetic(tmp):
    for name, beta, omega, plot in (("ccw30", 30.0, 1.0, True), ("cw25", 25.0, -2.0, False)):
        d = os.path.join(tmp, name)
        write_snapshot(d, 1000, 0.5, bed(5.0, omega), omega)  # before --from: must be left out
        write_snapshot(d, 2000, 1.0, bed(beta, omega), omega)
        write_snapshot(d, 3000, 1.5, bed(beta, omega), omega)
        rc, out, err = run_tool(d, "--from", "0.8", *([] if plot else ["--no-plot"]))
        check(f"{name}: exit 0", rc == 0, err)
        if rc != 0:
            continue
        a = read_angles(os.path.join(d, "drum_angles.csv"))
        for method in ("centre_of_mass", "free_surface"):
            got = float(a[method]["mean_deg"])
            check(f"{name}: {method} {got:.2f} within {TOL_DEG} deg of {beta}", abs(got - beta) <= TOL_DEG, got)
            check(f"{name}: {method} from 2 snapshots", a[method]["snapshots"] == "2", a[method]["snapshots"])
        for suffix in (".csv", "_angles.csv") + ((".png",) if plot else ()):
            p = os.path.join(d, "drum" + suffix)
            check(f"{name}: wrote drum{suffix}", os.path.isfile(p) and os.path.getsize(p) > 0, p)


def tiny_run(tmp, rondel):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    ini = os.path.join(tmp, "tiny.ini")
    with open(ini, "w") as f:
        f.write("""[run]
steps = 40000
progress = false
[output]
snapshot_every = 4000
[domain]
xlo = -0.021
xhi = 0.021
ylo = -0.021
yhi = 0.021
[gravity]
y = -9.81
[linear]
k_n = 1e6
e = 0.3
[coulomb]
k_s = 0.75e6
mu = 0.5
[contact]
rolling = wang
[wang]
k_r = 2.857e5
mu_r = 0.1
[walls]
circles = 0 0 0.02 5
[scene]
type = random
count = 50
region = -0.013 0.013 -0.013 0.013
radius_min = 0.001
radius_max = 0.0015
seed = 3
""")
    d = os.path.join(tmp, "tiny")
    p = subprocess.run([rondel, ini, f"--run.output={d}"], capture_output=True, text=True, env=env)
    check("tiny drum run: exit 0", p.returncode == 0, p.stderr[-2000:])
    if p.returncode != 0:
        return
    rc, out, err = run_tool(d, "--no-plot")
    check("tiny drum run: measured", rc == 0, err)
    if rc == 0:
        a = read_angles(os.path.join(d, "drum_angles.csv"))
        got = float(a["centre_of_mass"]["mean_deg"])
        check(f"tiny drum run: a finite angle ({got:.1f} deg), leaning the way the drum turns",
              math.isfinite(got) and 0.0 < got < 60.0, got)

    out_dir = os.path.join(tmp, "sweep")
    args = ["--sweep", "--out", out_dir, "--laws", "wang,constant_torque", "--mu-r", "0,0.2", "--steps", "300",
            "--jobs", "2", "--rondel", rondel, "--rondel-arg=--output.snapshot_every=100", "--no-plot"]
    p = subprocess.run([PY, TOOL, *args], capture_output=True, text=True, env=env)
    check("sweep: exit 0", p.returncode == 0, p.stdout[-1500:] + p.stderr[-1500:])
    for name in ("none", "wang_mu0.2", "constant_torque_mu0.2"):
        check(f"sweep: ran {name}", os.path.isfile(os.path.join(out_dir, name, "summary.txt")), name)
    table = os.path.join(out_dir, "table.csv")
    if os.path.isfile(table):
        with open(table) as f:
            rows = list(csv.DictReader(f))
        check("sweep: table has 4 rows (mu_r = 0 shown for both laws)", len(rows) == 4, rows)
    else:
        check("sweep: wrote table.csv", False, table)
    p = subprocess.run([PY, TOOL, *args], capture_output=True, text=True, env=env)
    check("sweep again: exit 0, every run reused", p.returncode == 0 and p.stdout.count("reused") == 3,
          p.stdout[-1500:] + p.stderr[-500:])
    stopped = os.path.join(out_dir, "wang_mu0.2", "summary.txt")
    if os.path.isfile(stopped):
        with open(stopped) as f:
            text = f.read()
        with open(stopped, "w") as f:
            f.write(text.replace("status: complete", "status: stopped by a signal; resume with --resume x"))
        p = subprocess.run([PY, TOOL, *args], capture_output=True, text=True, env=env)
        with open(stopped) as f:
            again = f.read()
        check("sweep with a run stopped (its summary.txt says so): that run again, the others reused",
              p.returncode == 0 and p.stdout.count("reused") == 2 and "wang_mu0.2: done" in p.stdout
              and "status: complete" in again, p.stdout[-1500:] + p.stderr[-500:])


def errors(tmp):
    p = subprocess.run([PY, TOOL, os.path.join(tmp, "missing")], capture_output=True, text=True)
    check("missing directory: exit 1 with a message", p.returncode == 1 and "drum: error" in p.stderr, p.stderr)
    empty = os.path.join(tmp, "empty")
    os.makedirs(empty)
    p = subprocess.run([PY, TOOL, empty], capture_output=True, text=True)
    check("no snapshots: exit 1 naming them", p.returncode == 1 and "snapshot" in p.stderr, p.stderr)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        synthetic(tmp)
        errors(tmp)
        if len(sys.argv) > 1:
            tiny_run(tmp, sys.argv[1])
    print(f"{sum(results)} passed, {len(results) - sum(results)} failed")
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
