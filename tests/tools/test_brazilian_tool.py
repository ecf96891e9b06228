#!/usr/bin/python3
"""Tests of tools/brazilian.py on inputs/brazilian.ini (ctest: tools.brazilian; docs/validation.md section 15):

1. The study (argv[1]: the rondel executable; sigma_c = 2e4 and 4e4 Pa, shear strength 1e9 Pa, about 3 s): the
   peak platen load is linear in the bonds' tensile strength, the ratio of the peaks 2 within 5 % (exit 0 with
   --check 0.05), every bond that broke broke in tension, the load falls below 0.8 of the peak after it (the
   specimen split; its halves, pressed on, carry load again later), and
   the table, the curve and the crack pictures are written; run again, nothing runs again.
2. The specimen as shipped is what --specimen writes (inputs/brazilian_disc.csv, byte for byte).
3. The peak row: the largest load before the first fall below 0.8 of the largest so far, not the later reloading.
4. Errors: a bad --sigma-c and no OUT_DIR give exit status 1 without a traceback.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
TOOL = os.path.join(ROOT, "tools", "brazilian.py")
sys.path.insert(0, os.path.dirname(TOOL))
import brazilian  # noqa: E402
PY = sys.executable or "/usr/bin/python3"

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


def main(rondel):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "study")
        r = subprocess.run([PY, TOOL, out, "--check", "0.05", "--rondel", rondel], capture_output=True, text=True)
        check("the peak is linear in sigma_c within 5 %", r.returncode == 0, (r.stdout + r.stderr)[-800:])
        rows = list(csv.DictReader(open(os.path.join(out, "brazilian.csv")))) if r.returncode == 0 else []
        check("two strengths in the table", len(rows) == 2, rows)
        if len(rows) == 2:
            ratio = float(rows[1]["peak_F"]) / float(rows[0]["peak_F"])
            check("peak(2 sigma_c) / peak(sigma_c) = 2 +- 5 %", abs(ratio / 2.0 - 1.0) < 0.05, ratio)
            check("every break in tension (tau_c large)", all(int(x["broken_shear"]) == 0 and
                                                              int(x["broken_tension"]) > 0 for x in rows), rows)
            for x in rows:
                d, F, D, t = brazilian.curve(os.path.join(out, f"sigma_{float(x['sigma_c']):g}"))
                k = brazilian.peak_row(F)
                check(f"sigma_c {x['sigma_c']}: the load falls below 0.8 of the peak after it (the specimen split)",
                      k is not None and F[k:].min() < 0.8 * F[k], F[-5:])
        for name in ("brazilian.png", "sigma_20000_bonds.png", "sigma_40000_bonds.png"):
            check(f"{name} written", os.path.getsize(os.path.join(out, name)) > 1000 if
                  os.path.exists(os.path.join(out, name)) else False)
        r = subprocess.run([PY, TOOL, out, "--rondel", rondel], capture_output=True, text=True)
        check("run again: nothing runs again", r.returncode == 0 and "0 run(s) to go, 2 finished before" in r.stdout,
              r.stdout[-300:])
        spec = os.path.join(tmp, "specimen.csv")
        subprocess.run([PY, TOOL, "--specimen", spec], capture_output=True, text=True)
        check("the shipped specimen is --specimen's", open(spec).read() == open(
            os.path.join(ROOT, "inputs", "brazilian_disc.csv")).read())
    F = np.array([0.0, 1.0, 2.0, 3.0, 1.0, 2.5, 4.0, 5.0])
    check("peak row: before the first fall, not the later reloading", brazilian.peak_row(F) == 3, brazilian.peak_row(F))
    check("peak row: None without a fall", brazilian.peak_row(np.arange(5.0)) is None)
    for args, what in ((["x", "--sigma-c", "0"], "--sigma-c 0"), ([], "no OUT_DIR")):
        r = subprocess.run([PY, TOOL] + args, capture_output=True, text=True)
        check(f"{what}: exit 1 without a traceback", r.returncode == 1 and "Traceback" not in r.stderr,
              (r.returncode, r.stderr[-300:]))
    failed = results.count(False)
    print(f"{results.count(True)} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "rondel")))
