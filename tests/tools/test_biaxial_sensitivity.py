#!/usr/bin/python3
"""Tests of tools/biaxial_sensitivity.py on its --quick preset with the current build (ctest:
tools.biaxial_sensitivity).

    /usr/bin/python3 tests/tools/test_biaxial_sensitivity.py BUILD/rondel

One 90-disc specimen per preparation (baseline e 0.35, targets 0.36 and 0.40), sheared to 1 % axial strain at
delta 0; the baseline specimen also at 0.2 /s and with wall friction 0.5. Checks: one row per variant with
n = 1 and finite angles; the baseline's shift is 0; the wall-friction variant shears the baseline specimen (a
link, the same start void ratio to the bit) and so does the rate variant; a looser target gives a looser start;
the two rates are different runs; --collect-only writes the same table and runs nothing; bad options exit 1 with
one line. Prints 'N passed, N failed'.
"""
import csv
import math
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.abspath(os.path.join(HERE, "..", "..", "tools", "biaxial_sensitivity.py"))
sys.path.insert(0, HERE)
from rondel_run import Checks, run_tool  # noqa: E402

check = Checks()


def tool(*args):
    return run_tool(TOOL, *args)


def main():
    if len(sys.argv) != 2:
        print("usage: test_biaxial_sensitivity.py BUILD/rondel", file=sys.stderr)
        return 2
    rondel = os.path.abspath(sys.argv[1])
    work = tempfile.mkdtemp(prefix="rondel-biaxial-sens-")
    try:
        out = os.path.join(work, "sens")
        rc, so, se = tool("--quick", "--out", out, "--rondel", rondel, "--no-plot")
        check("quick study exits 0", rc == 0, (rc, so[-2000:], se[-2000:]))
        path = os.path.join(out, "sensitivity.csv")
        rows = list(csv.DictReader(open(path))) if os.path.exists(path) else []
        by = {r["variant"]: r for r in rows}
        want = ["target e 0.36", "target e 0.40", "0.2 /s", "wall friction 0.5"]
        check("sensitivity.csv: the baseline and the 4 variants, n = 1 each",
              len(rows) == 5 and rows[0]["factor"] == "baseline" and all(w in by for w in want)
              and all(r["n"] == "1" for r in rows), rows)
        num = lambda r, k: float(r[k])  # noqa: E731
        check("finite angles and start void ratios",
              rows and all(math.isfinite(num(r, k)) for r in rows for k in ("phi_peak_mean", "phi_res_mean", "e0_mean")),
              rows)
        check("the baseline's shift is 0", rows and num(rows[0], "phi_peak_shift") == 0.0
              and num(rows[0], "phi_res_shift") == 0.0, rows[:1])
        rpath = os.path.join(out, "runs.csv")
        runs = list(csv.DictReader(open(rpath))) if os.path.exists(rpath) else []
        e0 = {r["variant"]: r["e0"] for r in runs}
        base = rows[0]["variant"] if rows else None
        check("wall friction and 0.2 /s shear the baseline specimen (same start e to the bit)",
              base in e0 and e0.get("wall friction 0.5") == e0[base] and e0.get("0.2 /s") == e0[base], e0)
        check("the wall-friction variant links the baseline preparation",
              os.path.islink(os.path.join(out, "wallmu", "ucm_200kPa_s2005")), os.listdir(out))
        check("a looser target gives a looser start (e 0.40 above 0.36)",
              all(k in e0 for k in want[:2]) and float(e0[want[1]]) > float(e0[want[0]]) + 0.005, e0)
        srcs = {r["variant"]: r["source"] for r in runs}
        check("the two rates are two runs", base in srcs and srcs.get("0.2 /s") not in (None, srcs[base]), srcs)

        text = open(path).read() if rows else ""
        rc2, so2, se2 = tool("--quick", "--out", out, "--rondel", rondel, "--no-plot", "--collect-only")
        check("--collect-only: the same table, nothing run",
              rc2 == 0 and open(path).read() == text and "prepare" not in so2 and ": rc " not in so2,
              (rc2, so2[-1000:], se2[-1000:]))

        for args in (["--factors", "rate,colour"], ["--samples", "0"], ["--baseline-table", "no-such.csv"]):
            rcu, sou, seu = tool("--out", os.path.join(work, "bad"), "--rondel", rondel, *args)
            lines = seu.strip().splitlines()
            check(f"usage error {' '.join(args)}: exit 1, one line",
                  rcu == 1 and "Traceback" not in seu and lines and lines[-1].startswith("biaxial_sensitivity: error: "),
                  (rcu, seu))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
