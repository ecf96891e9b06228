#!/usr/bin/python3
"""Tests of tools/biaxial_sweep.py on its --quick preset with the current build (ctest: tools.biaxial_sweep).

    /usr/bin/python3 tests/tools/test_biaxial_sweep.py BUILD/rondel

Two small specimens built by multi-layer undercompaction (90 discs, 3 layers, seeds 2005 and 2006, 200 kPa),
each sheared 20,000 steps with no rolling resistance (delta 0) and jiang_plastic delta 1.6. Checks: table.csv
has one row per sample and delta; summary.csv has one row per delta with n = 2; the peak friction angle rises
from delta 0 to 1.6 in every sample; a second call reuses every run; a run stopped by a signal (its summary.txt
says 'status: stopped ...') is run again; the strength envelope of the collection (fit over three confining
stresses) on synthetic rows of known phi and c; bad options exit 1 with one line.
Prints 'N passed, N failed'.
"""
import csv
import math
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.abspath(os.path.join(HERE, "..", "..", "tools"))
TOOL = os.path.join(TOOLS, "biaxial_sweep.py")
sys.path.insert(0, HERE)
sys.path.insert(0, TOOLS)
from rondel_run import Checks, run_tool  # noqa: E402
import biaxial_sweep  # noqa: E402

check = Checks()


def tool(*args):
    return run_tool(TOOL, *args)


def test_envelopes(work):
    """Rows at 100, 200, 400 kPa on the Mohr-Coulomb line of phi 30 deg, c 5 kPa (peak) and 25 deg, c 0
    (residual), two samples: the envelope gives them back."""
    class A:
        out = work
    rows = []
    for seed in (1, 2):
        for p in (100.0, 200.0, 400.0):
            sp = p / (1 - math.sin(math.radians(30)))  # any s works: t on the line
            sr = p * 1.3
            rows.append(dict(model="jiang_plastic", delta=0.4, sample=seed, p_kPa=p, s_peak_kPa=sp,
                             t_peak_kPa=sp * math.sin(math.radians(30)) + 5 * math.cos(math.radians(30)),
                             s_res_kPa=sr, t_res_kPa=sr * math.sin(math.radians(25))))
    by = biaxial_sweep.envelopes(A, rows)
    es = by.get(("jiang_plastic", 0.4), [])
    check("envelopes: one per sample", len(es) == 2, es)
    check("envelopes: phi 30 deg, c 5 kPa at peak; 25 deg, c 0 residual",
          es and all(abs(e["phi_peak_env"] - 30) < 1e-9 and abs(e["c_peak_kPa"] - 5) < 1e-9
                     and abs(e["phi_res_env"] - 25) < 1e-9 and abs(e["c_res_kPa"]) < 1e-9 for e in es), es)
    # A sample missing a confining stress has no envelope.
    by = biaxial_sweep.envelopes(A, rows[:-1])
    check("envelopes: a sample without every pressure is left out", len(by.get(("jiang_plastic", 0.4), [])) == 1, by)


def main():
    if len(sys.argv) != 2:
        print("usage: test_biaxial_sweep.py BUILD/rondel", file=sys.stderr)
        return 2
    rondel = os.path.abspath(sys.argv[1])
    work = tempfile.mkdtemp(prefix="rondel-biaxial-sweep-")
    try:
        test_envelopes(work)
        out = os.path.join(work, "sweep")
        rc, so, se = tool("--quick", "--out", out, "--rondel", rondel, "--jobs", 1, "--no-plot")
        check("quick sweep exits 0", rc == 0, (rc, so[-2000:], se[-2000:]))
        rows = list(csv.DictReader(open(os.path.join(out, "table.csv")))) if rc == 0 else []
        keys = sorted((r["model"], float(r["delta"]), r["sample"]) for r in rows)
        want = sorted([("none", 0.0, s) for s in ("2005", "2006")] + [("jiang_plastic", 1.6, s) for s in ("2005", "2006")])
        check("table.csv: one row per sample and delta (2 x 2)", keys == want, keys)
        finite = rows and all(math.isfinite(float(r[k])) for r in rows for k in ("phi_peak", "phi_res", "e0"))
        check("table.csv: finite angles and void ratios", finite, rows)
        by = {(r["sample"], float(r["delta"])): float(r["phi_peak"]) for r in rows}
        rises = rows and all(by[(s, 1.6)] > by[(s, 0.0)] + 1.0 for s in ("2005", "2006"))
        check("phi_peak rises from delta 0 to 1.6 (by more than 1 deg) in every sample", rises, by)
        summ = list(csv.DictReader(open(os.path.join(out, "summary.csv")))) if rc == 0 else []
        check("summary.csv: 2 points, n = 2 each", len(summ) == 2 and all(r["n"] == "2" for r in summ), summ)
        curve = list(csv.DictReader(open(os.path.join(out, "curve.csv")))) if rc == 0 else []
        check("curve.csv: 2 deltas", [float(r["delta"]) for r in curve] == [0.0, 1.6], curve)

        # --from-table: the same curve from the table alone (runs nothing).
        again = os.path.join(work, "again")
        rct, sot, set_ = tool("--from-table", os.path.join(out, "table.csv"), "--out", again, "--rondel", rondel,
                              "--no-plot")
        same = rct == 0 and open(os.path.join(again, "curve.csv")).read() == open(os.path.join(out, "curve.csv")).read()
        check("--from-table: the same curve.csv from table.csv", same, (rct, sot[-1000:], set_[-1000:]))

        # Resume: a second call runs nothing and leaves the runs untouched.
        run = os.path.join(out, "jiang_plastic_d1.6_p200kPa_r0.1_ucm_s2006")
        before = os.path.getmtime(os.path.join(run, "measures.csv")) if rc == 0 else None
        rc2, so2, se2 = tool("--quick", "--out", out, "--rondel", rondel, "--no-plot")
        check("second call reuses every run", rc2 == 0 and so2.count("2 shear run(s) reused, 0 to run") == 2
              and "prepare" not in so2 and os.path.getmtime(os.path.join(run, "measures.csv")) == before,
              (rc2, so2[-1000:], se2[-1000:]))

        # A run stopped by a signal (its summary.txt says so) is run again, the others reused.
        path = os.path.join(run, "summary.txt")
        if os.path.exists(path):
            text = open(path).read()
            with open(path, "w") as f:
                f.write(text.replace("status: complete", "status: stopped by a signal; resume with --resume X"))
        rc3, so3, se3 = tool("--quick", "--out", out, "--rondel", rondel, "--no-plot")
        check("a stopped run is run again, the others reused",
              rc3 == 0 and "sample 2005: 2 shear run(s) reused, 0 to run" in so3
              and "sample 2006: 1 shear run(s) reused, 1 to run" in so3
              and "status: complete" in open(path).read(), (rc3, so3[-1000:], se3[-1000:]))

        # Usage errors: exit 1, one line 'biaxial_sweep: error: ...', no traceback.
        for args in (["--samples", "2"], ["--samples", "0", "--prep", "undercompaction"], ["--deltas", "0,x"],
                     ["--strain", "1.5"], ["--from-table", os.path.join(work, "missing.csv")]):
            rcu, sou, seu = tool("--out", os.path.join(work, "bad"), "--rondel", rondel, *args)
            lines = seu.strip().splitlines()
            check(f"usage error {' '.join(args)}: exit 1, one line",
                  rcu == 1 and "Traceback" not in seu and lines and lines[-1].startswith("biaxial_sweep: error: "),
                  (rcu, seu))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
