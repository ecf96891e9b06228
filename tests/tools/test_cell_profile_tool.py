#!/usr/bin/python3
"""Tests of tools/cell_profile.py (ctest: tools.cell_profile), with the rondel executable (argv[1]).

1. The jammed bench packing (bench/jammed10k.csv, 10,000 discs) in a cell sheared at cell.rate_xy = 0.5 /s
   from the mean flow (cell.flow_start), 100 steps: the profile of v_x across the cell has the cell's slope
   (slope / rate within 0.05 of 1) and lies on its line (largest deviation below 0.05 of gamma_dot L_y); the
   CSV is written with one row per bin.
2. The same packing in a standing periodic box: refused (exit 1, one line naming the shear rate).
3. A directory without checkpoints: exit 1 with a message.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import csv
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
TOOL = os.path.join(ROOT, "tools", "cell_profile.py")
PY = sys.executable or "/usr/bin/python3"
RESULTS = {"passed": 0, "failed": 0}


def check(ok, what):
    RESULTS["passed" if ok else "failed"] += 1
    print(("PASS " if ok else "FAIL ") + what)


def ini(rate):
    lo, hi = 2.5918674819618417, 153.93359759807294
    cell = f"[cell]\nrate_xy = {rate}\n" if rate else ""
    return (f"[run]\ndt = 3e-4\nsteps = 100\nprogress = false\n[domain]\nxlo = {lo!r}\nxhi = {hi!r}\nylo = {lo!r}\n"
            f"yhi = {hi!r}\nperiodic_x = true\nperiodic_y = true\n{cell}[material]\ndensity = 1\n[linear]\n"
            "k_n = 1e5\nzeta = 0.3\n[coulomb]\nk_s = 28571.43\nmu = 0.5\n[scene]\ntype = csv\n"
            f"file = {os.path.join(ROOT, 'bench', 'jammed10k.csv')}\nmax_initial_overlap = 0.2\n")


def run_rondel(rondel, tmp, name, rate):
    path = os.path.join(tmp, name + ".ini")
    with open(path, "w") as f:
        f.write(ini(rate))
    out = os.path.join(tmp, name)
    r = subprocess.run([rondel, path, f"--run.output={out}"], capture_output=True, text=True)
    check(r.returncode == 0, f"rondel {name}: exit 0 ({r.stderr.strip()[-200:]})")
    return out


def tool(*args):
    return subprocess.run([PY, TOOL, *args], capture_output=True, text=True)


def main():
    rondel = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        sheared = run_rondel(rondel, tmp, "sheared", 0.5)
        r = tool(sheared, "--out", os.path.join(tmp, "p"), "--no-plot")
        check(r.returncode == 0, f"profile of the sheared run: exit 0 ({r.stderr.strip()})")
        last = r.stdout.strip().splitlines()[-1] if r.stdout.strip() else ""
        ratio = dev = float("nan")
        try:
            ratio = float(last.split("slope / cell.rate_xy = ")[1].split(",")[0])
            dev = float(last.split("from the line = ")[1].split(" ")[0])
        except (IndexError, ValueError):
            pass
        check(abs(ratio - 1.0) < 0.05, f"slope / rate = {ratio} (within 0.05 of 1)")
        check(dev < 0.05, f"largest deviation {dev} of gamma_dot L_y (below 0.05)")
        with open(os.path.join(tmp, "p_profile.csv")) as f:
            rows = list(csv.DictReader(f))
        check(len(rows) >= 10 and "vx_mean" in rows[0], f"profile CSV: {len(rows)} bins")
        standing = run_rondel(rondel, tmp, "standing", 0)
        r = tool(standing, "--out", os.path.join(tmp, "q"), "--no-plot")
        check(r.returncode == 1 and "rate_xy" in r.stderr and len(r.stderr.strip().splitlines()) == 1,
              f"a standing box is refused: exit {r.returncode}, {r.stderr.strip()}")
        os.makedirs(os.path.join(tmp, "empty"))
        r = tool(os.path.join(tmp, "empty"), "--no-plot")
        check(r.returncode == 1 and "no checkpoint" in r.stderr, f"an empty directory: exit {r.returncode}")
    print(f"{RESULTS['passed']} passed, {RESULTS['failed']} failed")
    return 1 if RESULTS["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
