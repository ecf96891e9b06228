#!/usr/bin/python3
"""Tests of tools/cemented_biaxial.py (ctest: tools.cemented_biaxial; docs/cemented_biaxial.md): its --quick preset
(argv[1]: the rondel executable; the J05 specimen prepared at 200 kPa, then sheared to 1 % axial strain without bonds
and with bonds of 8e5 Pa, about 15 s): the bonded specimen's peak deviator is more than twice the unbonded one's
(the cement's strength: 737 against 201 kPa in the full study), its bonds break (some, not all, by 1 %), the
unbonded run has none, and the table and figures are written; bad options exit 1 without a traceback.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import csv
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
TOOL = os.path.join(ROOT, "tools", "cemented_biaxial.py")
PY = sys.executable or "/usr/bin/python3"
results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


def main(rondel):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "study")
        r = subprocess.run([PY, TOOL, out, "--quick", "--rondel", rondel], capture_output=True, text=True)
        check("the quick study runs", r.returncode == 0, (r.stdout + r.stderr)[-800:])
        rows = list(csv.DictReader(open(os.path.join(out, "table.csv")))) if r.returncode == 0 else []
        check("two rows", len(rows) == 2, rows)
        if len(rows) == 2:
            plain, cemented = rows
            check("the cemented peak more than twice the plain one",
                  float(cemented["q_peak"]) > 2.0 * float(plain["q_peak"]) > 0, rows)
            check("no bonds without [bonds]", int(plain["bonds"]) == 0 and int(plain["broken"]) == 0, plain)
            check("the cemented specimen's bonds: more than 1000, some broken, not all",
                  int(cemented["bonds"]) > 1000 and 0 < int(cemented["broken"]) < int(cemented["bonds"]), cemented)
        for name in ("peak.png", "curves.png"):
            path = os.path.join(out, name)
            check(f"{name} written", os.path.exists(path) and os.path.getsize(path) > 1000)
    for args, what in ((["x", "--strengths", "a,b"], "--strengths a,b"), (["x", "--rolling", "wang"], "--rolling wang"),
                       (["x", "--strain", "0.9"], "--strain 0.9")):
        r = subprocess.run([PY, TOOL] + args, capture_output=True, text=True)
        check(f"{what}: exit 1 without a traceback", r.returncode == 1 and "Traceback" not in r.stderr,
              (r.returncode, r.stderr[-300:]))
    failed = results.count(False)
    print(f"{results.count(True)} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "rondel")))
