#!/usr/bin/python3
"""Tests of tools/biaxial.py on synthetic curves with known friction angles (ctest: tools.biaxial).

Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import csv
import math
import os
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import biaxial  # noqa: E402

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


def s1_from_angle(phi_deg, s3):
    s = np.sin(np.radians(phi_deg))
    return s3 * (1 + s) / (1 - s)


def synthetic(p=2e5, peak=30.0, residual=24.0, eps_peak=0.03, eps_end=0.15, n=301):
    """phi(eps) rises to PEAK at EPS_PEAK, decays exponentially to RESIDUAL (flat over the last 5 %)."""
    eps = np.linspace(0.0, eps_end, n)
    phi = np.where(eps <= eps_peak, peak * np.sin(0.5 * np.pi * eps / eps_peak),
                   residual + (peak - residual) * np.exp(-(eps - eps_peak) / 0.01))
    phi[eps >= eps_end - 0.05] = residual  # exactly flat in the default window
    s3 = np.full(n, p)
    return eps, s1_from_angle(phi, s3), s3, phi


def test_known_angles():
    eps, s1, s3, phi = synthetic()
    r = biaxial.friction_angles(eps, s1, s3)
    check("peak angle 30 deg", abs(r["phi_peak"] - 30.0) < 1e-9, r["phi_peak"])
    check("peak strain 0.03", abs(r["eps_peak"] - 0.03) < 1e-9, r["eps_peak"])
    check("residual angle 24 deg (last 5 %)", abs(r["phi_residual"] - 24.0) < 1e-9, r["phi_residual"])
    check("residual window [0.10, 0.15]",
          abs(r["residual_from"] - 0.10) < 1e-12 and abs(r["residual_to"] - 0.15) < 1e-12,
          (r["residual_from"], r["residual_to"]))
    check("q_peak = s1 - s3 at peak",
          abs(r["q_peak"] - (s1_from_angle(30.0, 2e5) - 2e5)) < 1e-6 * 2e5, r["q_peak"])


def test_window_option():
    eps, s1, s3, phi = synthetic()
    r = biaxial.friction_angles(eps, s1, s3, window=0.10)
    sel = eps >= 0.05 - 1e-15
    check("window 0.10: mean over [0.05, 0.15]", abs(r["phi_residual"] - phi[sel].mean()) < 1e-9,
          (r["phi_residual"], phi[sel].mean()))
    check("window 0.10 differs from 24", r["phi_residual"] > 24.0 + 1e-6, r["phi_residual"])


def test_formula_and_guards():
    # sin(phi) = (s1 - s3)/(s1 + s3): s1 = 3 s3 gives sin = 0.5, phi = 30 deg exactly.
    a = biaxial.mobilised_angle([3.0, 1.0, 0.0], [1.0, 1.0, 0.0])
    check("s1 = 3 s3 -> 30 deg", abs(a[0] - 30.0) < 1e-12, a[0])
    check("isotropic -> 0 deg", abs(a[1]) < 1e-12, a[1])
    check("s1 + s3 = 0 -> NaN", math.isnan(a[2]), a[2])
    # A leading unloaded row (s1 = s3 = 0) is ignored, not taken as a peak.
    eps, s1, s3, _ = synthetic()
    s1[0] = s3[0] = 0.0
    r = biaxial.friction_angles(eps, s1, s3)
    check("zero row ignored", abs(r["phi_peak"] - 30.0) < 1e-9, r["phi_peak"])


def test_envelope():
    phi, c = 35.0, 1.0e4
    s3 = np.array([1e5, 2e5, 4e5])
    # Mohr-Coulomb at failure: s1 = s3 Np + 2 c sqrt(Np), Np = (1 + sin)/(1 - sin)
    Np = (1 + math.sin(math.radians(phi))) / (1 - math.sin(math.radians(phi)))
    s1 = s3 * Np + 2 * c * math.sqrt(Np)
    fphi, fc = biaxial.envelope(0.5 * (s1 + s3), 0.5 * (s1 - s3))
    check("envelope phi 35 deg", abs(fphi - phi) < 1e-9, fphi)
    check("envelope c 10 kPa", abs(fc - c) < 1e-6, fc)


def test_cli():
    cols = ["step", "time", "width", "height", "wall_sxx", "wall_syy", "sxx", "syy", "sxy", "s1", "s3",
            "eps_axial", "eps_lateral", "eps_vol", "void_ratio", "coordination", "rotation_mean",
            "rotation_std", "sliding_fraction", "rolling_yield_fraction"]
    with tempfile.TemporaryDirectory() as d:
        paths = []
        for p in (1e5, 2e5):
            eps, s1, s3, _ = synthetic(p=p)
            run = os.path.join(d, f"p{int(p/1e3)}")
            os.makedirs(run)
            path = os.path.join(run, "measures.csv")
            with open(path, "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(cols)
                for k in range(len(eps)):
                    row = dict.fromkeys(cols, 0.0)
                    row.update(step=k, wall_sxx=s3[k], wall_syy=s1[k], sxx=s3[k], syy=s1[k], eps_axial=eps[k],
                               eps_vol=-0.1 * eps[k])
                    w.writerow([row[c] for c in cols])
            paths.append(path)
        out = os.path.join(d, "out", "res")
        plot = []
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            plot = ["--no-plot"]
        rc = biaxial.main(paths + ["--out", out] + plot)
        check("cli exit 0", rc == 0, rc)
        with open(out + "_angles.csv") as f:
            rows = list(csv.DictReader(f))
        check("cli two runs", len(rows) == 2, len(rows))
        check("cli peak 30", all(abs(float(r["phi_peak"]) - 30.0) < 1e-6 for r in rows), rows)
        check("cli residual 24", all(abs(float(r["phi_residual"]) - 24.0) < 1e-6 for r in rows), rows)
        check("cli envelope written", os.path.exists(out + "_envelope.csv"))
        if not plot:
            check("cli png written", os.path.exists(out + "_curves.png") and os.path.exists(out + "_envelope.png"))


def test_cell():
    """--stress cell: a wall-free test's strains from the cell's lengths, s1, s3 from the Love-Weber stresses;
    a file without the cell's columns is refused naming it."""
    eps, s1, s3, _ = synthetic()
    ly = 0.3 * (1.0 - eps)  # eps_axial = 1 - L_y / L_y0 exactly
    lx = 0.2 * (1.0 + 0.7 * eps)
    cols = ["step", "wall_sxx", "wall_syy", "sxx", "syy", "eps_axial", "eps_vol", "cell_lx", "cell_ly"]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "measures.csv")
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(cols)
            for k in range(len(eps)):
                w.writerow([k, 0.0, 0.0, repr(s3[k]), repr(s1[k]), 0.0, 0.0, repr(lx[k]), repr(ly[k])])
        out = os.path.join(d, "cell")
        rc = biaxial.main([path, "--stress", "cell", "--out", out, "--no-plot", "--no-envelope"])
        check("--stress cell: exit 0", rc == 0, rc)
        rows = list(csv.DictReader(open(out + "_angles.csv"))) if rc == 0 else []
        check("--stress cell: peak 30 at eps 0.03 from the cell's height, residual 24",
              len(rows) == 1 and abs(float(rows[0]["phi_peak"]) - 30.0) < 1e-6 and
              abs(float(rows[0]["eps_peak"]) - 0.03) < 1e-9 and abs(float(rows[0]["phi_residual"]) - 24.0) < 1e-6,
              rows)
        check("--stress cell: the confining stress is the Love-Weber sxx",
              len(rows) == 1 and abs(float(rows[0]["confining"]) - 2e5) < 1e-6, rows)
        curves = list(csv.DictReader(open(out + "_curves.csv"))) if rc == 0 else []
        want = 1.0 - lx[-1] * ly[-1] / (lx[0] * ly[0])
        check("--stress cell: eps_vol = 1 - A / A0", curves and abs(float(curves[-1]["eps_vol"]) - want) < 1e-12,
              (curves[-1] if curves else None, want))
        plain = os.path.join(d, "plain.csv")
        with open(plain, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(cols[:7])
            w.writerow([0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0])
        import io
        import contextlib
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rc = biaxial.main([plain, "--stress", "cell", "--out", out, "--no-plot"])
        check("--stress cell on a walled run: exit 1 naming the columns", rc == 1 and "cell_ly" in err.getvalue(),
              (rc, err.getvalue()))


for t in (test_known_angles, test_window_option, test_formula_and_guards, test_envelope, test_cli, test_cell):
    try:
        t()
    except Exception as exc:  # a crash counts as a failure
        check(t.__name__, False, repr(exc))

n_pass = sum(results)
n_fail = len(results) - n_pass
print(f"{n_pass} passed, {n_fail} failed")
sys.exit(1 if n_fail else 0)
