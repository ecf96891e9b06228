#!/usr/bin/python3
"""Tests of tools/walton_braun.py on inputs/walton_braun_bounce.ini (ctest: tools.walton_braun).

1. The scene as it is (argv[1]: the rondel executable; 140,000 steps of one disc, about a second): the tool finds
   at least eight apexes, and the first five and the ledger's D_normal_hysteresis at each lie within 1e-3 of the
   law's exact bounce map with gravity (exit 0 with --check 1e-3); h0 e^(2n), which leaves gravity out of the
   impacts, lies above the map and further from it at each apex; the CSV and the figure are written.
2. The map itself against energy: with K2 = K1 (e = 1) an impact loses nothing and the apex returns to h0.
3. Errors: a missing run directory, a bad --check, and a run without walton_braun keys give exit status 1.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import csv
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
TOOL = os.path.join(ROOT, "tools", "walton_braun.py")
sys.path.insert(0, os.path.dirname(TOOL))
import walton_braun  # noqa: E402
PY = sys.executable or "/usr/bin/python3"

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


def main(rondel):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "bounce")
        r = subprocess.run([rondel, os.path.join(ROOT, "inputs", "walton_braun_bounce.ini"), f"--run.output={out}",
                            "--run.progress=false"], capture_output=True, text=True)
        check("the scene runs", r.returncode == 0, r.stderr[-500:])
        r = subprocess.run([PY, TOOL, out, "--check", "1e-3"], capture_output=True, text=True)
        check("the first five apexes and their dissipation within 1e-3 of the map", r.returncode == 0,
              r.stdout[-1500:] + r.stderr[-500:])
        with open(os.path.join(out, "walton_braun.csv")) as f:
            rows = list(csv.DictReader(f))
        check("eight apexes or more", len(rows) >= 8, len(rows))
        gaps = [float(a["h_no_gravity"]) / float(a["h_map"]) - 1.0 for a in rows[:5]]
        check("h0 e^(2n) above the map, further at each apex", all(g > 0 for g in gaps) and
              all(b > a for a, b in zip(gaps, gaps[1:])), gaps)
        check("the figure is written", os.path.getsize(os.path.join(out, "walton_braun.png")) > 10000)

        elastic = walton_braun.bounce_map(0.1, 0.2, 9.81, 1e7, 1e7, 3)
        check("K2 = K1: no loss, the apex returns to h0",
              all(abs(h - 0.1) < 1e-12 and D == 0.0 for h, D in elastic), elastic)

        for args, what in (([os.path.join(tmp, "missing")], "a missing run directory"),
                           ([out, "--check", "nan"], "a NaN --check"),
                           ([out, "--check", "-1"], "a negative --check")):
            r = subprocess.run([PY, TOOL] + args, capture_output=True, text=True)
            check(what + " is refused with exit 1", r.returncode == 1 and "walton_braun: error:" in r.stderr,
                  (r.returncode, r.stderr))
        other = os.path.join(tmp, "linear")
        subprocess.run([rondel, os.path.join(ROOT, "inputs", "settling_disc.ini"), f"--run.output={other}",
                        "--run.steps=10", "--run.progress=false"], capture_output=True, text=True)
        r = subprocess.run([PY, TOOL, other], capture_output=True, text=True)
        check("a run without walton_braun is refused naming the key", r.returncode == 1 and
              "walton_braun.K1" in r.stderr, (r.returncode, r.stderr))
    print(f"{sum(results)} passed, {len(results) - sum(results)} failed")
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
