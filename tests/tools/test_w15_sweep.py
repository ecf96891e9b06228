#!/usr/bin/python3
"""Tests of tools/w15_sweep.py on its --quick preset with the current build (ctest: tools.w15_sweep).

    /usr/bin/python3 tests/tools/test_w15_sweep.py BUILD/rondel

One 400-disc sample of the W15 set-up prepared briefly, sheared 30,000 steps with mu_r 0 and 0.5 under both
rolling models (wang = W15 model 1, alonso_marroquin = model 2). Checks: the table has one row per model
and mu_r with finite values in range; at mu_r = 0 the two models' measures.csv are the same byte for byte
(both laws give a zero couple then) and table.md says so; at mu_r = 0.5 they differ (the law was switched);
a second call reuses every run; --collect-only runs nothing; bad options exit 1 with one line; a failing
rondel run exits 2.
Prints 'N passed, N failed'.
"""
import csv
import math
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.abspath(os.path.join(HERE, "..", "..", "tools", "w15_sweep.py"))
sys.path.insert(0, HERE)
from rondel_run import Checks, run_tool  # noqa: E402

check = Checks()


def tool(*args):
    return run_tool(TOOL, *args)


def have_matplotlib():
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


def read(path):
    with open(path, "rb") as f:
        return f.read()


def main():
    if len(sys.argv) != 2:
        print("usage: test_w15_sweep.py BUILD/rondel", file=sys.stderr)
        return 2
    rondel = os.path.abspath(sys.argv[1])
    work = tempfile.mkdtemp(prefix="rondel-w15-")
    try:
        out = os.path.join(work, "sweep")
        plot = [] if have_matplotlib() else ["--no-plot"]
        rc, so, se = tool("--quick", "--out", out, "--rondel", rondel, "--jobs", 2, *plot)
        check("quick sweep exits 0", rc == 0, (rc, so[-2000:], se[-2000:]))

        rows = list(csv.DictReader(open(os.path.join(out, "table.csv")))) if rc == 0 else []
        keys = sorted((r["model"], float(r["mu_r"]), r["seed"]) for r in rows)
        want = sorted((m, mu, "2015") for m in ("wang", "alonso_marroquin") for mu in (0.0, 0.5))
        check("table.csv: one row per model and mu_r (2 x 2, seed 2015)", keys == want, keys)
        num = ["sin_peak", "sin_res", "phi_peak", "phi_res", "e0", "e_max", "e_res", "eps_end", "s3_mean_kPa"]
        finite = all(math.isfinite(float(r[k])) for r in rows for k in num)
        check("table.csv: every value finite", rows and finite, rows)
        ok = all(0 < float(r["sin_res"]) <= float(r["sin_peak"]) < 1 and 0 < float(r["e0"]) <= float(r["e_max"])
                 and 0.003 < float(r["eps_end"]) < 0.005 and int(r["rows_res"]) >= 2 for r in rows)
        check("table.csv: 0 < sin phi res <= peak < 1, e0 <= e_max, 0.4 % axial strain, a residual window",
              rows and ok, rows)
        # The prepared sample holds the lateral stress: s3 within 10 % of 160 kPa while shearing.
        check("lateral stress near 160 kPa", rows and all(abs(float(r["s3_mean_kPa"]) - 160) < 16 for r in rows),
              [r["s3_mean_kPa"] for r in rows])

        def meas(model, mu):
            return read(os.path.join(out, f"{model}_mur{mu}_s2015", "measures.csv"))
        if rc == 0:
            check("mu_r = 0: model 1 and model 2 measures.csv identical byte for byte",
                  meas("wang", 0) == meas("alonso_marroquin", 0))
            check("mu_r = 0.5: model 1 and model 2 differ", meas("wang", 0.5) != meas("alonso_marroquin", 0.5))
            md = open(os.path.join(out, "table.md")).read()
            check("table.md reports the mu_r = 0 identity", "identical byte for byte (seeds 2015)" in md, md)
            check("table.md compares the models at mu_r 0 and 0.5",
                  "| 0 | 1/1 |" in md and "| 0.5 | 1/1 |" in md, md)
            summ = list(csv.DictReader(open(os.path.join(out, "summary.csv"))))
            check("summary.csv: 4 points, n = 1 each", len(summ) == 4 and all(r["n"] == "1" for r in summ), summ)
            if plot == []:
                for f in ("friction_vs_mur.png", "void_ratio_vs_mur.png", "curves.png"):
                    check(f"figure {f} written", os.path.getsize(os.path.join(out, f)) > 10000)

            # Resume: a second call runs nothing and leaves the runs untouched.
            before = os.path.getmtime(os.path.join(out, "wang_mur0.5_s2015", "measures.csv"))
            rc2, so2, se2 = tool("--quick", "--out", out, "--rondel", rondel, "--no-plot")
            check("second call reuses every run", rc2 == 0 and "4 shear run(s) reused, 0 to run" in so2
                  and os.path.getmtime(os.path.join(out, "wang_mur0.5_s2015", "measures.csv")) == before,
                  (rc2, so2[-1000:], se2[-1000:]))

            # A run stopped by a signal (its summary says so) is run again, the others reused.
            summ_path = os.path.join(out, "alonso_marroquin_mur0.5_s2015", "summary.txt")
            text = open(summ_path).read()
            with open(summ_path, "w") as f:
                f.write(text.replace("status: complete", "status: stopped by a signal; resume with --resume X"))
            rc5, so5, se5 = tool("--quick", "--out", out, "--rondel", rondel, "--no-plot")
            check("a stopped run is run again, the others reused", rc5 == 0 and "3 shear run(s) reused, 1 to run" in so5
                  and "status: complete" in open(summ_path).read()
                  and meas("alonso_marroquin", 0.5) != meas("wang", 0.5), (rc5, so5[-1000:], se5[-1000:]))

            # --collect-only beside a run not made yet: the table of the finished runs, nothing run.
            rc4, so4, se4 = tool("--out", out, "--rondel", rondel, "--mu-r", "0,0.5,0.9", "--seeds", "2015", "--steps",
                                 "30000", "--window", "0.001", "--no-plot", "--collect-only")
            n4 = len(list(csv.DictReader(open(os.path.join(out, "table.csv")))))
            check("--collect-only: 4 of 6 runs finished, table of 4, nothing run",
                  rc4 == 0 and "4 of 6 shear runs finished; running none" in so4 and n4 == 4
                  and not os.path.exists(os.path.join(out, "wang_mur0.9_s2015")), (rc4, n4, so4[-800:], se4[-800:]))

            # A rondel run that fails (an unknown key): exit 2, the failure named.
            rc3, so3, se3 = tool("--out", out, "--rondel", rondel, "--mu-r", "0.2", "--models", "wang", "--seeds",
                                 "2015", "--steps", "100", "--no-plot", "--extra=--nosuch.key=1")
            check("a failing shear run exits 2 and is named", rc3 == 2 and "1 shear run(s) failed" in se3
                  and "wang_mur0.2_s2015" in se3, (rc3, se3))

        # Usage errors: exit 1, one line 'w15_sweep: error: ...', no traceback.
        for args in (["--mu-r", "0,x"], ["--models", "wang,none"], ["--jobs", "0"], ["--strain", "1.5"],
                     ["--rondel", os.path.join(work, "missing")]):
            rc, so, se = tool("--out", os.path.join(work, "bad"), *(["--rondel", rondel] if "--rondel" not in args
                                                                     else []), *args)
            lines = se.strip().splitlines()
            check(f"usage error {' '.join(args)}: exit 1, one line",
                  rc == 1 and "Traceback" not in se and lines and lines[-1].startswith("w15_sweep: error: "), (rc, se))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
