#!/usr/bin/python3
"""Tests of tools/mu_i.py on its --quick preset with the current build (ctest: tools.mu_i).

    /usr/bin/python3 tests/tools/test_mu_i_tool.py BUILD/rondel

One 200-disc sample prepared at 1e5 Pa, sheared to a strain of 3 at I = 0.03 then 0.1 (a chain: the second run
starts where the first ended), and at I = 0.1 from the prepared sample without and with wang rolling resistance
(mu_r 0.2). Checks: a table row per run with the steady values in range (the servo's mean pressure within 10 %
of 1e5 Pa, the measured I within 25 % of its target, mu and phi in the ranges of dense disc flows); friction
and dilation grow with I, and rolling resistance raises mu; the fit's line passes through the two points; a
second call reuses every run; bad options exit 1 with one line naming the option. Prints 'N passed, N failed'.
"""
import csv
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.abspath(os.path.join(HERE, "..", "..", "tools", "mu_i.py"))
sys.path.insert(0, HERE)
from rondel_run import Checks, run_tool  # noqa: E402

check = Checks()


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) != 2:
        print("usage: test_mu_i_tool.py BUILD/rondel", file=sys.stderr)
        return 2
    rondel = os.path.abspath(sys.argv[1])
    work = tempfile.mkdtemp(prefix="rondel-mu_i-")
    try:
        out = os.path.join(work, "sweep")
        rc, so, se = run_tool(TOOL, "--quick", "--out", out, "--rondel", rondel, "--no-plot")
        check("quick sweep exits 0", rc == 0, (rc, so[-2000:], se[-2000:]))
        table = rows(os.path.join(out, "table.csv")) if rc == 0 else []
        got = sorted((r["series"], r["law"], float(r["value"]), float(r["inertial_target"])) for r in table)
        want = sorted([("inertial", "none", 0.0, 0.03), ("inertial", "none", 0.0, 0.1), ("rolling", "none", 0.0, 0.1),
                       ("rolling", "wang", 0.2, 0.1)])
        check("one table row per run", got == want, got)
        for r in table:
            name = f"{r['series']} {r['law']} {r['value']} I {r['inertial_target']}"
            p, i, target = float(r["pressure"]), float(r["I"]), float(r["inertial_target"])
            check(f"{name}: mean pressure within 10 % of 1e5 Pa ({p:.4g})", abs(p / 1e5 - 1) < 0.1)
            check(f"{name}: I within 25 % of its target ({i:.4g})", abs(i / target - 1) < 0.25)
            check(f"{name}: mu in [0.2, 0.6] and phi in [0.72, 0.84]",
                  0.2 <= float(r["mu"]) <= 0.6 and 0.72 <= float(r["phi"]) <= 0.84, r)
            check(f"{name}: a shear strain of 3 (rate x time; tilt / height moves with the height)",
                  abs(float(r["strain"]) / 3.0 - 1) < 0.1, r["strain"])
        by = {(r["series"], r["law"], float(r["inertial_target"])): r for r in table}
        if len(by) == 4:
            lo, hi = by[("inertial", "none", 0.03)], by[("inertial", "none", 0.1)]
            check("mu grows and phi falls with I", float(hi["mu"]) > float(lo["mu"]) and
                  float(hi["phi"]) < float(lo["phi"]), (lo, hi))
            check("wang mu_r 0.2 raises mu at I = 0.1",
                  float(by[("rolling", "wang", 0.1)]["mu"]) > float(by[("rolling", "none", 0.1)]["mu"]) + 0.02)
            fit = rows(os.path.join(out, "fit.csv"))[0]
            line = float(fit["mu_s"]) + float(fit["b"]) * float(lo["I"])
            check("the fit passes through the two points", abs(line - float(lo["mu"])) < 1e-4, (fit, lo))
        rc, so, se = run_tool(TOOL, "--quick", "--out", out, "--rondel", rondel, "--no-plot")
        check("a second call reuses every run", rc == 0 and "0 run(s) to go, 4 finished before" in so, so)
        for bad, word in ((["--inertial", "0.1,abc"], "--inertial"), (["--steady", "12"], "--steady"),
                          (["--rolling", "spin:0.1"], "--rolling"), (["--pressure", "nan"], "--pressure")):
            rc, so, se = run_tool(TOOL, "--out", os.path.join(work, "bad"), "--rondel", rondel, *bad)
            check(f"{' '.join(bad)} refused with exit 1 naming {word}", rc == 1 and word in se and
                  "Traceback" not in se, (rc, se))
        check("... before any run", not os.path.exists(os.path.join(work, "bad", "prep_s11")))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
