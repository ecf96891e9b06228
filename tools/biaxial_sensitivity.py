#!/usr/bin/python3
"""Sensitivity of the friction angle at delta = 0 (no rolling resistance) to the set-up, J05 biaxial test
(docs/biaxial.md, "Sensitivity of the level at delta = 0"): every variant changes one factor of the baseline
(multi-layer undercompaction to e 0.25, 1008 discs in a 180 mm wide box, 200 kPa, 0.1 /s, no local damping,
frictionless walls) and is sheared on the same seeds by tools/biaxial_sweep.py; the tool collects phi_peak and
phi_res per variant (mean and sample standard deviation over the seeds) and their shift against the baseline.

  python3 tools/biaxial_sensitivity.py --out rondel-output-biaxial/sens [--samples 3] [--ucm-seed 2005]
      [--baseline-table docs/biaxial/j05_table.csv] [--factors preparation,void_ratio,rate,damping,size,walls]
      [--size-samples 3] [--jobs 1] [--collect-only]

Variants (subfolders of OUT; each one a biaxial_sweep.py output folder):
  mu01      the layer stages with mu 0.1 instead of 0.25 (target e 0.25; consolidation and shear mu 0.5)
  base      the baseline preparations (seeds --ucm-seed, +1, ...); its shear runs at 0.1 /s (baseline), 0.2 and
            0.05 /s (rate) and with run.local_damping 0.7 (damping)
  e022      undercompaction target e 0.22; the layer stages with mu 0.1 (with the default 0.25 the bottom layer,
            target 0.242, jams at 2.7 MPa and the next stage refuses its overlaps); consolidation and shear as
            the baseline (mu 0.5)
  e028      target e 0.28 (consolidation to 200 kPa ends near 0.25 to 0.27)
  e031      target e 0.31 (to end near 0.28 after the consolidation)
  e028mu05  target e 0.28 with the layer stages at mu 0.5 (the shear stage's; looser layers)
  e028c     as e028mu05, and the consolidation at mu 1 (a preparation friction only: the shear stage keeps 0.5)
  n4000     4000 discs in a 360 mm wide box (the baseline's aspect ratio, width and height x 2); --size-samples
            seeds; the shear domain widened (domain.xhi 0.45, domain.yhi 0.7)
  aspect1   1008 discs in a 231 mm wide box: height / width about 1 instead of 1.65
  wallmu    the baseline specimens (linked, not rebuilt) sheared with wall friction 0.5 (wall_contact.mu; the
            wall stiffness stays the discs' k_n, k_s)
--baseline-table FILE takes the baseline (0.1 /s) and the 0.05 /s rows from a biaxial_sweep table.csv made
with the same set-up (docs/biaxial/j05_table.csv: model none, 200 kPa, no damping) instead of running them.
--quick: the CI preset (90 discs in 3 layers, 80 mm wide, e 0.35, one sample, 0.01 axial strain; factors
void_ratio (e 0.36 and 0.40 only), rate (0.2 /s) and walls).
Writes OUT/runs.csv (one row per shear run), OUT/sensitivity.csv (one row per variant: mean, sd and shift
against the baseline of the start void ratio, the angles from the walls and from the Love-Weber stresses (_lw),
and the mean lateral stress) and OUT/sensitivity.md;
OUT/sensitivity.png unless --no-plot.
Exit status: 0 done, 1 bad input or usage, 2 a run failed.
"""
import csv
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from rondel import CheckFailed  # noqa: E402
from rondel.study import run_command  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "biaxial_sensitivity"
FACTORS = ("preparation", "void_ratio", "rate", "damping", "size", "walls")
# Per variant: mean, sd and shift against the baseline of these columns of biaxial_sweep's table.csv (angles
# from the wall stresses; _lw from the Love-Weber stresses of the discs).
QUANTITIES = ("e0", "phi_peak", "phi_res", "phi_peak_early", "phi_peak_lw", "phi_res_lw", "s3_mean_kPa")


def variants(a):
    """(factor, label, subfolder, sweep options, undercompaction.py options of a preparation run here (None: the
    sweep prepares), link the base preparations, rate, damping) of every variant, the baseline first."""
    e, W, N = a.e, a.width, a.count
    v = [("baseline", f"e {e:g}, {N} discs, {W * 1e3:g} mm wide, 0.1 /s, alpha 0, walls mu 0", "base", [],
          None, False, 0.1, 0.0)]
    if a.quick:
        v += [("void_ratio", "target e 0.36", "e036", ["--ucm-e", "0.36"], None, False, 0.1, 0.0),
              ("void_ratio", "target e 0.40", "e040", ["--ucm-e", "0.4"], None, False, 0.1, 0.0),
              ("rate", "0.2 /s", "base", ["--rate", "0.2"], None, False, 0.2, 0.0),
              ("walls", "wall friction 0.5", "wallmu", ["--extra=--wall_contact.mu=0.5"], None, True, 0.1, 0.0)]
    else:
        v += [("preparation", "layer mu 0.1 (target e 0.25)", "mu01", [], ["--mu", "0.1"], False, 0.1, 0.0),
              ("void_ratio", "target e 0.22 (layer mu 0.1)", "e022", ["--ucm-e", "0.22"], ["--mu", "0.1"], False,
               0.1, 0.0),
              ("void_ratio", "target e 0.28", "e028", ["--ucm-e", "0.28"], None, False, 0.1, 0.0),
              ("void_ratio", "target e 0.31", "e031", ["--ucm-e", "0.31"], None, False, 0.1, 0.0),
              ("void_ratio", "target e 0.28 (layer mu 0.5)", "e028mu05", ["--ucm-e", "0.28"], ["--mu", "0.5"], False,
               0.1, 0.0),
              ("void_ratio", "target e 0.28 (layer mu 0.5, consolidation mu 1)", "e028c", ["--ucm-e", "0.28"],
               ["--mu", "0.5", "--consolidate-mu", "1"], False, 0.1, 0.0),
              ("rate", "0.2 /s", "base", ["--rate", "0.2"], None, False, 0.2, 0.0),
              ("rate", "0.05 /s", "base", ["--rate", "0.05"], None, False, 0.05, 0.0),
              ("damping", "local damping 0.7", "base", ["--damping", "0.7"], None, False, 0.1, 0.7),
              ("size", f"4000 discs, {2 * W * 1e3:g} mm wide (same aspect)", "n4000",
               ["--ucm-count", "4000", "--ucm-width", repr(2 * W), "--extra=--domain.xhi=0.45",
                "--extra=--domain.yhi=0.7"], None, False, 0.1, 0.0),
              ("size", f"{N} discs, 231 mm wide (aspect about 1)", "aspect1", ["--ucm-width", "0.231"], None, False,
               0.1, 0.0),
              ("walls", "wall friction 0.5", "wallmu", ["--extra=--wall_contact.mu=0.5"], None, True, 0.1, 0.0)]
    return [x for x in v if x[0] == "baseline" or x[0] in a.factors]


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("--out", default="rondel-output-biaxial/sens")
    ap.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"),
                    help="the rondel executable (default: build/rondel of this checkout)")
    ap.add_argument("--samples", type=int, default=3, help="seeds per variant: --ucm-seed, +1, ... (default 3)")
    ap.add_argument("--size-samples", type=int, default=3, help="seeds of the 4000-disc variant (default 3)")
    ap.add_argument("--ucm-seed", type=int, default=2005)
    ap.add_argument("--factors", default=",".join(FACTORS), help="comma-separated subset of " + ", ".join(FACTORS))
    ap.add_argument("--baseline-table", default="",
                    help="take the baseline and 0.05 /s rows from this biaxial_sweep table.csv instead of running them")
    ap.add_argument("--jobs", type=int, default=1, help="runs in parallel (biaxial_sweep.py --jobs)")
    ap.add_argument("--collect-only", action="store_true", help="run nothing; tables from the runs finished so far")
    ap.add_argument("--quick", action="store_true", help="tiny CI preset (90 discs, one sample, 0.01 axial strain)")
    add_figure_options(ap, dpi=150)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    a.factors = [f for f in a.factors.split(",") if f]
    bad = [f for f in a.factors if f not in FACTORS]
    if bad:
        ap.error(f"--factors: unknown {', '.join(bad)} (choose from {', '.join(FACTORS)})")
    if a.samples < 1 or a.size_samples < 0 or a.jobs < 1:
        ap.error("--samples and --jobs must be >= 1, --size-samples >= 0")
    if a.baseline_table and not os.path.isfile(a.baseline_table):
        ap.error(f"--baseline-table: '{a.baseline_table}' does not exist")
    if not os.access(a.rondel, os.X_OK):
        ap.error(f"the rondel executable '{a.rondel}' does not exist or is not executable (pass --rondel)")
    if a.quick:
        a.count, a.layers, a.width, a.e, a.strain, a.window, a.samples = 90, 3, 0.08, 0.35, 0.01, 0.002, 1
    else:
        a.count, a.layers, a.width, a.e, a.strain, a.window = 1008, 6, 0.18, 0.25, 0.15, 0.05
    return run_tool(TOOL, study, a)


def sweep_cmd(a, sub, opts, samples):
    return [sys.executable, os.path.join(HERE, "biaxial_sweep.py"), "--rondel", a.rondel, "--out",
            os.path.join(a.out, sub), "--prep", "undercompaction", "--samples", str(samples), "--ucm-seed",
            str(a.ucm_seed), "--ucm-count", str(a.count), "--ucm-layers", str(a.layers), "--ucm-width",
            repr(a.width), "--ucm-e", f"{a.e:g}", "--deltas", "0", "--pressures", "2e5", "--rate", "0.1",
            "--strain", f"{a.strain:g}", "--window", f"{a.window:g}", "--extra=--run.max_overlap=0.2",
            "--jobs", str(a.jobs), "--no-plot"] + opts


def option(opts, key, default):
    """The value after KEY in the option list OPTS (the last one), else DEFAULT."""
    vals = [opts[k + 1] for k, o in enumerate(opts[:-1]) if o == key]
    return vals[-1] if vals else default


def prepare_direct(a, sub, opts, prep, seeds):
    """Preparations with undercompaction.py options PREP that biaxial_sweep.py does not pass (the layer and
    consolidation friction), or without the shear stage's --extra (a wider domain, which the preparation sets
    itself): run here, into the folder biaxial_sweep.py would use (it then reuses them)."""
    count, width = option(opts, "--ucm-count", str(a.count)), option(opts, "--ucm-width", repr(a.width))
    e = option(opts, "--ucm-e", f"{a.e:g}")
    for seed in seeds:
        d = os.path.join(a.out, sub, f"ucm_200kPa_s{seed}")
        if os.path.exists(os.path.join(d, "summary.txt")):
            continue
        os.makedirs(os.path.dirname(d), exist_ok=True)
        cmd = [sys.executable, os.path.join(HERE, "undercompaction.py"), "--out", d, "--rondel", a.rondel,
               "--pressure", "200000", "--layers", str(a.layers), "--e", e, "--seed", str(seed), "--count", count,
               "--width", width, "--extra=--run.max_overlap=0.2"] + prep
        rc, _ = run_command(cmd, d + ".log", ROOT)
        print(f"prepare {d}: rc {rc}", flush=True)
        if rc:
            raise CheckFailed(f"the preparation {d} failed: see {d}.log")


def read_rows(path, rate, damping, seeds):
    """Rows of a biaxial_sweep table.csv at delta 0, 200 kPa, RATE and DAMPING for SEEDS."""
    if not os.path.exists(path):
        return []
    out = []
    for r in csv.DictReader(open(path)):
        if (r["model"] == "none" and float(r["p_kPa"]) == 200.0 and math.isclose(float(r["rate"]), rate)
                and math.isclose(float(r["damping"]), damping) and r["sample"] and int(r["sample"]) in seeds):
            out.append(r)
    return out


def study(a):
    os.makedirs(a.out, exist_ok=True)
    vs = variants(a)
    failed = []
    # The variants that share the base preparations: link them (wallmu); run the base ones first.
    for factor, label, sub, opts, prep, link, rate, damping in vs:
        n = a.size_samples if sub == "n4000" else a.samples
        vseeds = [a.ucm_seed + k for k in range(n)]
        from_table = a.baseline_table and sub == "base" and rate in (0.1, 0.05) and damping == 0.0
        if a.collect_only or from_table or n == 0:
            continue
        if link:
            os.makedirs(os.path.join(a.out, sub), exist_ok=True)
            for s in vseeds:
                dst = os.path.join(a.out, sub, f"ucm_200kPa_s{s}")
                if not os.path.lexists(dst):
                    os.symlink(os.path.join("..", "base", f"ucm_200kPa_s{s}"), dst)
        if prep is not None or sub == "n4000":
            prepare_direct(a, sub, opts, prep or [], vseeds)
        log = os.path.join(a.out, f"{factor}_{sub}_{rate:g}_{damping:g}.log")
        rc, _ = run_command(sweep_cmd(a, sub, opts, n), log, ROOT)
        print(f"{factor}: {label}: rc {rc} ({log})", flush=True)
        if rc:
            failed.append(label)

    runs, rows = [], []
    for factor, label, sub, opts, prep, link, rate, damping in vs:
        n = a.size_samples if sub == "n4000" else a.samples
        vseeds = [a.ucm_seed + k for k in range(n)]
        if a.baseline_table and sub == "base" and rate in (0.1, 0.05) and damping == 0.0:
            got = read_rows(a.baseline_table, rate, damping, vseeds)
        else:
            if not a.collect_only or os.path.isdir(os.path.join(a.out, sub)):
                subprocess.call(sweep_cmd(a, sub, opts, n) + ["--collect-only"], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, cwd=ROOT)
            got = read_rows(os.path.join(a.out, sub, "table.csv"), rate, damping, vseeds)
        for r in got:
            runs.append(dict(factor=factor, variant=label, sample=r["sample"], rate=rate, damping=damping,
                             e0=float(r["e0"]), phi_peak=float(r["phi_peak"]), eps_peak=float(r["eps_peak"]),
                             phi_res=float(r["phi_res"]), phi_peak_early=float(r["phi_peak_early"]),
                             phi_peak_lw=float(r["phi_peak_lw"]), phi_res_lw=float(r["phi_res_lw"]),
                             s3_mean_kPa=float(r["s3_mean_kPa"]), source=r["dir"]))
        row = dict(factor=factor, variant=label, n=len(got))
        for q in QUANTITIES:
            v = [float(r[q]) for r in got]
            row[q + "_mean"] = float(np.mean(v)) if v else float("nan")
            row[q + "_sd"] = float(np.std(v, ddof=1)) if len(v) > 1 else float("nan")
        rows.append(row)
    base = rows[0]
    for row in rows:
        for q in QUANTITIES:
            row[q + "_shift"] = row[q + "_mean"] - base[q + "_mean"]  # NaN where either has no run
    with open(os.path.join(a.out, "runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(runs[0].keys()) if runs else ["factor"])
        w.writeheader()
        w.writerows(runs)
    with open(os.path.join(a.out, "sensitivity.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})

    def pm(m, s, fmt=".1f"):
        return "-" if math.isnan(m) else f"{m:{fmt}}" + ("" if math.isnan(s) else f" ± {s:{fmt}}")

    def shift(x):
        return "-" if math.isnan(x) else f"{x:+.1f}"
    with open(os.path.join(a.out, "sensitivity.md"), "w") as f:
        f.write("| factor | variant | n | e at the start | phi_peak [deg] | shift | phi_res [deg] | shift "
                "| LW peak / res [deg] |\n" + "|---" * 9 + "|\n")
        for r in rows:
            f.write(f"| {r['factor']} | {r['variant']} | {r['n']} | {pm(r['e0_mean'], r['e0_sd'], '.3f')} | "
                    f"{pm(r['phi_peak_mean'], r['phi_peak_sd'])} | {shift(r['phi_peak_shift'])} | "
                    f"{pm(r['phi_res_mean'], r['phi_res_sd'])} | {shift(r['phi_res_shift'])} | "
                    f"{pm(r['phi_peak_lw_mean'], float('nan'))} / {pm(r['phi_res_lw_mean'], float('nan'))} |\n")
    print(open(os.path.join(a.out, "sensitivity.md")).read(), flush=True)
    if not a.no_plot and any(r["n"] for r in rows):
        plot(a, rows)
    if failed:
        raise CheckFailed(f"{len(failed)} variant(s) had a failed run: " + "; ".join(failed))
    return 0


def plot(a, rows):
    """OUT/sensitivity.png: phi_peak and phi_res of every variant (mean, one sd), the baseline as bands."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 0.45 * len(rows) + 1.5), layout="constrained")
    y = np.arange(len(rows))[::-1]
    for q, mk, name in (("phi_peak", "o", "peak"), ("phi_res", "s", "residual")):
        m = np.array([r[q + "_mean"] for r in rows])
        s = np.nan_to_num(np.array([r[q + "_sd"] for r in rows]))
        ax.errorbar(m, y, xerr=s, fmt=mk, capsize=3, label=name)
        b, bs = rows[0][q + "_mean"], rows[0][q + "_sd"]
        if not math.isnan(b):
            ax.axvspan(b - (0 if math.isnan(bs) else bs), b + (0 if math.isnan(bs) else bs), alpha=0.12,
                       color=ax.lines[-1].get_color())
    ax.set_yticks(y, [f"{'baseline' if k == 0 else r['variant']} (n {r['n']})" for k, r in enumerate(rows)], fontsize=7)
    ax.set_xlabel("friction angle at delta = 0, 200 kPa [deg]")
    ax.grid(alpha=0.3, axis="x")
    ax.legend(fontsize=8)
    ax.set_title("J05 set-up, one factor at a time (bars: ± 1 sd; bands: baseline)", fontsize=9)
    print("wrote " + save_figure(fig, os.path.join(a.out, "sensitivity"), a))


if __name__ == "__main__":
    sys.exit(main())
