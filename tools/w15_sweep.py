#!/usr/bin/python3
"""Wang et al. 2015 (W15) biaxial sweep: model 1 (`wang`, their Eq. 11) against model 2 (`alonso_marroquin`,
the contact-point velocities of Alonso-Marroquin et al. 2006) over the rolling coefficient mu_r, with
several independently prepared samples per point (their Figs. 5 and 6: macroscopic friction and residual
void ratio against mu_r).

  python3 tools/w15_sweep.py --out rondel-output-w15/sweep [--mu-r 0,0.05,0.1,0.2,0.3,0.5,0.7,1.0]
      [--models wang,alonso_marroquin] [--seeds 2015,2016,2017] [--jobs 2] [--strain 0.15] [--quick]

Stage 1 prepares one sample per seed with inputs/biaxial_wang_prepare.ini (--scene.seed=SEED, isotropic
servo to --pressure, frictionless by default (--prep-mu 0) for samples as dense as W15's; OUT/prep_sSEED/);
stage 2 shears every (seed, mu_r, model) with inputs/biaxial_wang.ini (OUT/MODEL_murMU_sSEED/; the prepared
contact history dropped, --run.reset_history=true; run.max_overlap 0.2, --max-overlap, which changes nothing
but the abort test for the linear normal law). The shear runs go in the order seed, then mu_r, then model, so
an interrupted sweep has every point of the first sample first. Finished runs (summary.txt with 'status:
complete') are reused, stopped or failed ones run again: run the same command again to resume or extend it;
--collect-only writes the tables and figures of the runs finished so far and runs nothing.

Per run (s1 = wall_syy, s3 = wall_sxx, compression +): the macroscopic friction sin(phi) = (s1 - s3)/(s1 + s3)
at its peak and its mean over the residual window (the last --window of axial strain), the friction angles,
the void ratio at the start (e0) and its mean over the residual window (e_res). Writes OUT/table.csv (one row
per run), OUT/summary.csv and OUT/table.md (mean and sample standard deviation over the seeds per model and
mu_r, and model 2 against model 1), OUT/friction_vs_mur.png, OUT/void_ratio_vs_mur.png (error bars: one
standard deviation over the seeds) and OUT/curves.png (sin(phi) and void ratio against axial strain, first
seed). At mu_r = 0 both laws give a zero couple, so the two models' runs must be the same to the bit: the
tool compares their measures.csv and says so in table.md.

--quick: mu_r 0 and 0.5, one seed, a short preparation and 30,000 shear steps (0.4 % axial strain, residual
window 0.1 %; the CI test of the tool).
Exit status: 0 done, 1 bad input or usage, 2 a rondel run failed (the table holds the others).
"""
import csv
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import biaxial  # noqa: E402
from rondel import CheckFailed, UsageError, study  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "w15_sweep"
MODELS = ("wang", "alonso_marroquin")
LABEL = {"wang": "model 1 (wang, W15 Eq. 11)", "alonso_marroquin": "model 2 (alonso_marroquin)"}
QUICK = dict(mu_r="0,0.5", seeds="2015", prep_steps=120000, steps=30000, window=0.001, diag_every=1000)


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("--out", default="rondel-output-w15/sweep")
    ap.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"),
                    help="the rondel executable (default: build/rondel of this checkout)")
    ap.add_argument("--prepare", default=os.path.join(ROOT, "inputs", "biaxial_wang_prepare.ini"))
    ap.add_argument("--shear", default=os.path.join(ROOT, "inputs", "biaxial_wang.ini"))
    ap.add_argument("--mu-r", default="0,0.05,0.1,0.2,0.3,0.5,0.7,1.0", help="rolling coefficients, comma-separated")
    ap.add_argument("--models", default=",".join(MODELS), help="rolling laws, comma-separated (default: both)")
    ap.add_argument("--seeds", default="2015,2016,2017",
                    help="scene.seed of the prepared samples, one sample each (default 3 samples)")
    ap.add_argument("--pressure", type=float, default=160e3, help="lateral stress [Pa] (= N/m with thickness 1 m)")
    ap.add_argument("--rate", type=float, default=0.1, help="top wall true strain rate [1/s]")
    ap.add_argument("--strain", type=float, default=0.15, help="axial strain to reach")
    ap.add_argument("--steps", type=int, default=0, help="shear steps (overrides --strain)")
    ap.add_argument("--prep-steps", type=int, default=200000)
    ap.add_argument("--prep-mu", type=float, default=0.0,
                    help="coulomb.mu and wang.mu_r of the preparation (default 0: frictionless, the densest "
                         "samples, e0 about 0.22; the input's 0.25 and 0.1 give 0.26)")
    ap.add_argument("--max-overlap", type=float, default=0.2,
                    help="run.max_overlap of the shear runs (default 0.2: with mu_r >= 0.7, s1 reaches 5 times the "
                         "lateral stress and some contacts pass the input's 0.1)")
    ap.add_argument("--window", type=float, default=0.05, help="residual window: the last WINDOW of axial strain")
    ap.add_argument("--jobs", type=int, default=2, help="runs in parallel (1 rank each)")
    ap.add_argument("--prep-extra", action="append", default=[],
                    help="more --section.key=value for the preparation runs")
    ap.add_argument("--extra", action="append", default=[], help="more --section.key=value for the shear runs")
    ap.add_argument("--collect-only", action="store_true",
                    help="run nothing: tables and figures from the runs finished so far (e.g. beside a running sweep)")
    ap.add_argument("--quick", action="store_true",
                    help="tiny preset for CI: mu_r 0 and 0.5, one seed, 30,000 shear steps")
    add_figure_options(ap, dpi=150)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    if a.quick:
        a.mu_r, a.seeds, a.prep_steps, a.steps = QUICK["mu_r"], QUICK["seeds"], QUICK["prep_steps"], QUICK["steps"]
        a.window = QUICK["window"]
        a.extra = [f"--diagnostics.every={QUICK['diag_every']}"] + a.extra
    if not os.access(a.rondel, os.X_OK):
        ap.error(f"the rondel executable '{a.rondel}' does not exist or is not executable "
                 "(build it: bash tools/setup.sh rondel, or pass --rondel)")
    for ini in (a.prepare, a.shear):
        if not os.path.isfile(ini):
            ap.error(f"'{ini}': no such input file")
    if a.jobs < 1:
        ap.error("--jobs must be >= 1")
    if not (0 < a.strain < 1):
        ap.error("--strain must be in (0, 1)")
    if a.steps < 0 or a.prep_steps < 1:
        ap.error("--steps must be >= 0 and --prep-steps >= 1")
    if not a.window > 0:
        ap.error("--window must be > 0")
    if not 0 < a.max_overlap < 1:
        ap.error("--max-overlap must be in (0, 1)")
    if not a.prep_mu >= 0:
        ap.error("--prep-mu must be >= 0")
    if not a.pressure > 0 or not a.rate > 0:
        ap.error("--pressure and --rate must be > 0")
    return run_tool(TOOL, sweep, a)


def parse_lists(a):
    """(mu_r values, models, seeds) from the options; UsageError on a malformed list."""
    try:
        mus = list(dict.fromkeys(float(x) for x in a.mu_r.split(",")))
        seeds = list(dict.fromkeys(int(x) for x in a.seeds.split(",")))
    except ValueError as e:
        raise UsageError(f"--mu-r or --seeds: {e} (numbers, comma-separated)")
    models = list(dict.fromkeys(m.strip() for m in a.models.split(",") if m.strip()))
    bad = [m for m in models if m not in MODELS]
    if bad or not models:
        raise UsageError(f"--models: {','.join(bad) or 'none given'}: choose from {','.join(MODELS)}")
    if any(m < 0 or not math.isfinite(m) for m in mus):
        raise UsageError("--mu-r: every value must be finite and >= 0")
    return mus, models, seeds


def run_dir(out, model, mu, seed):
    return os.path.join(out, f"{model}_mur{mu:g}_s{seed}")


def run_all(jobs, n, what, failed):
    """Run JOBS [(cmd, log, dir)] N at a time in the given order (rondel.study), printing each as it ends; the
    directories of those that fail go into FAILED."""
    bad = study.run_chains([[study.Job(f"{what} {d}", cmd, d, log)] for cmd, log, d in jobs], n, ROOT)
    for cmd, log, d in jobs:
        if f"{what} {d}" in bad:
            failed.append(d)
            print(f"  FAILED {d}: see {log}", flush=True)


def sweep(a):
    mus, models, seeds = parse_lists(a)
    os.makedirs(a.out, exist_ok=True)
    p = a.pressure

    # Stage 1: one prepared sample per seed.
    preps, jobs, failed = {}, [], []
    for s in seeds:
        d = os.path.join(a.out, f"prep_s{s}")
        preps[s] = d
        if not study.complete(d) and not a.collect_only:
            cmd = [a.rondel, a.prepare, f"--run.output={d}", "--run.overwrite=true", "--run.progress=false",
                   f"--run.steps={a.prep_steps}", f"--scene.seed={s}",
                   f"--walls.control=top:servo:{p:g} right:servo:{p:g}",
                   f"--coulomb.mu={a.prep_mu:g}", f"--wang.mu_r={a.prep_mu:g}"] + a.prep_extra
            jobs.append((cmd, d + ".log", d))
    run_all(jobs, a.jobs, "prepare", failed)
    if failed:
        raise CheckFailed(f"{len(failed)} prepare run(s) failed: " + ", ".join(failed))

    # Stage 2: shear, seed-major so that the first sample's points come first.
    runs, jobs, dts = [], [], {}
    for s in seeds:
        for mu in mus:
            for m in models:
                d = run_dir(a.out, m, mu, s)
                runs.append((m, mu, s, d))
                if study.complete(d) or a.collect_only:
                    continue
                cmd = [a.rondel, a.shear, f"--scene.file={preps[s]}", "--run.progress=false",
                       "--run.reset_history=true", f"--contact.rolling={m}", f"--wang.mu_r={mu:g}",
                       f"--run.max_overlap={a.max_overlap:g}",
                       f"--walls.control=top:strain_rate:{a.rate:g} left:servo:{p:g} right:servo:{p:g}"] + a.extra
                if not a.steps and (m, mu) not in dts:  # the step depends on the laws, not on the sample
                    dts[(m, mu)] = study.probe_dt(cmd, os.path.join(a.out, f"probe_{m}_mur{mu:g}"), ROOT)
                steps = a.steps or int(math.ceil(math.log(1.0 / (1.0 - a.strain)) / (a.rate * dts[(m, mu)])))
                cmd += [f"--run.output={d}", "--run.overwrite=true", f"--run.steps={steps}"]
                jobs.append((cmd, d + ".log", d))
    if a.collect_only:
        print(f"--collect-only: {sum(study.complete(r[3]) for r in runs)} of {len(runs)} shear runs finished; running none",
              flush=True)
    else:
        print(f"{len(runs) - len(jobs)} shear run(s) reused, {len(jobs)} to run ({a.jobs} at a time)", flush=True)
    run_all(jobs, a.jobs, "shear", failed)

    rows = collect(a, runs)
    same = zero_mu_identity(a, mus, models, seeds)
    write_tables(a, rows, same)
    if rows and not a.no_plot:
        plots(a, rows)
    if failed:
        raise CheckFailed(f"{len(failed)} shear run(s) failed: " + ", ".join(failed))
    return 0


def analyse_run(meas, window):
    """Peak and residual macroscopic friction and void ratios of one shear run's measures."""
    eps = meas["eps_axial"]
    s1, s3 = meas["wall_syy"], meas["wall_sxx"]
    ang = biaxial.friction_angles(eps, s1, s3, window)
    ok = (s1 + s3) > 0
    mu_mac = np.where(ok, (s1 - s3) / np.where(ok, s1 + s3, 1.0), np.nan)
    win = ok & (eps >= ang["residual_from"])
    e = meas["void_ratio"]
    return dict(sin_peak=float(np.nanmax(mu_mac)), eps_peak=ang["eps_peak"], sin_res=float(np.mean(mu_mac[win])),
                phi_peak=ang["phi_peak"], phi_res=ang["phi_residual"], e0=float(e[0]),
                e_max=float(np.max(e)), e_res=float(np.mean(e[win])), eps_end=float(eps[-1]),
                s3_mean_kPa=float(np.mean(s3[len(s3) // 10:])) / 1e3, rows_res=int(np.count_nonzero(win)))


def collect(a, runs):
    rows = []
    for m, mu, s, d in runs:
        path = os.path.join(d, "measures.csv")
        if not study.complete(d) or not os.path.exists(path):
            continue
        r = dict(model=m, mu_r=mu, seed=s)
        r.update(analyse_run(biaxial.read_measures(path), a.window))
        r.update(wall_s=study.wall_seconds(d), dir=d)
        rows.append(r)
    keys = ["model", "mu_r", "seed", "sin_peak", "eps_peak", "sin_res", "phi_peak", "phi_res", "e0", "e_max", "e_res",
            "eps_end", "s3_mean_kPa", "rows_res", "wall_s", "dir"]
    with open(os.path.join(a.out, "table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    return rows


def zero_mu_identity(a, mus, models, seeds):
    """{seed: True/False}: the two models' measures.csv at mu_r = 0 are byte for byte the same."""
    if 0.0 not in mus or len(models) < 2:
        return {}
    out = {}
    for s in seeds:
        paths = [os.path.join(run_dir(a.out, m, 0.0, s), "measures.csv") for m in models]
        if all(study.complete(os.path.dirname(x)) and os.path.exists(x) for x in paths):
            texts = [open(x, "rb").read() for x in paths]
            out[s] = all(t == texts[0] for t in texts[1:])
    return out


QUANTITIES = ("sin_peak", "sin_res", "phi_peak", "phi_res", "e0", "e_res")


def aggregate(rows):
    """{(model, mu_r): {n, QUANTITY: (mean, std)}}; std is the sample standard deviation (NaN for n = 1)."""
    groups = {}
    for r in rows:
        groups.setdefault((r["model"], r["mu_r"]), []).append(r)
    agg = {}
    for key, rs in groups.items():
        g = {"n": len(rs)}
        for q in QUANTITIES:
            v = np.array([r[q] for r in rs], dtype=float)
            g[q] = (float(v.mean()), float(v.std(ddof=1)) if len(v) > 1 else float("nan"))
        agg[key] = g
    return agg


def pm(ms, fmt):
    m, s = ms
    return f"{m:{fmt}}" + ("" if not math.isfinite(s) else f" ± {s:{fmt}}")


def write_tables(a, rows, same):
    agg = aggregate(rows)
    with open(os.path.join(a.out, "summary.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["model", "mu_r", "n"] + [f"{q}_{k}" for q in QUANTITIES for k in ("mean", "std")])
        for (m, mu), g in sorted(agg.items(), key=lambda x: (x[0][1], x[0][0])):
            w.writerow([m, mu, g["n"]] + [repr(x) for q in QUANTITIES for x in g[q]])
    with open(os.path.join(a.out, "table.md"), "w") as f:
        f.write("| model | mu_r | n | sin phi peak | sin phi residual | phi peak [deg] | phi residual [deg] | e0 "
                "| e residual |\n|---|---|---|---|---|---|---|---|---|\n")
        for (m, mu), g in sorted(agg.items(), key=lambda x: (x[0][1], x[0][0] != "wang")):
            f.write(f"| {m} | {mu:g} | {g['n']} | {pm(g['sin_peak'], '.3f')} | {pm(g['sin_res'], '.3f')} | "
                    f"{pm(g['phi_peak'], '.1f')} | {pm(g['phi_res'], '.1f')} | {pm(g['e0'], '.4f')} | "
                    f"{pm(g['e_res'], '.4f')} |\n")
        f.write(f"\nMean ± sample standard deviation over the n samples (seeds). sin phi = (s1 - s3)/(s1 + s3), "
                f"s1 = wall_syy, s3 = wall_sxx; residual = mean over the last {a.window:g} of axial strain; "
                "e = planar void ratio (e0 at the start of shearing).\n")
        pairs = [mu for mu in sorted({mu for _, mu in agg}) if ("wang", mu) in agg and ("alonso_marroquin", mu) in agg]
        if pairs:
            f.write("\nModel 2 (alonso_marroquin) against model 1 (wang), on the means: differences 2 - 1; "
                    "dilatancy = e residual - e0.\n\n"
                    "| mu_r | n (1/2) | d sin phi peak | d sin phi residual | e residual 2/1 - 1 "
                    "| dilatancy 2/1 - 1 |\n|---|---|---|---|---|---|\n")
            for mu in pairs:
                g1, g2 = agg[("wang", mu)], agg[("alonso_marroquin", mu)]
                d1 = g1["e_res"][0] - g1["e0"][0]
                d2 = g2["e_res"][0] - g2["e0"][0]
                dil = f"{100 * (d2 / d1 - 1):+.1f} %" if abs(d1) > 1e-12 else "-"
                f.write(f"| {mu:g} | {g1['n']}/{g2['n']} | {g2['sin_peak'][0] - g1['sin_peak'][0]:+.3f} | "
                        f"{g2['sin_res'][0] - g1['sin_res'][0]:+.3f} | "
                        f"{100 * (g2['e_res'][0] / g1['e_res'][0] - 1):+.1f} % | {dil} |\n")
        if same:
            ok = [s for s, v in same.items() if v]
            bad = [s for s, v in same.items() if not v]
            f.write("\nmu_r = 0: the two models' measures.csv are " +
                    (f"identical byte for byte (seeds {', '.join(map(str, ok))})" if ok else "") +
                    ("; " if ok and bad else "") +
                    (f"DIFFERENT (seeds {', '.join(map(str, bad))})" if bad else "") + ".\n")
    print(open(os.path.join(a.out, "table.md")).read(), flush=True)


def plots(a, rows):
    plt = pyplot()
    agg = aggregate(rows)
    models = [m for m in MODELS if any(k[0] == m for k in agg)]
    styles = {"wang": dict(color="C0", marker="o"), "alonso_marroquin": dict(color="C3", marker="s")}
    shift = {"wang": -0.006, "alonso_marroquin": 0.006}  # error bars side by side

    def series(m, q):
        mus = sorted(mu for mm, mu in agg if mm == m)
        mean = np.array([agg[(m, mu)][q][0] for mu in mus])
        std = np.nan_to_num(np.array([agg[(m, mu)][q][1] for mu in mus]))
        return np.array(mus) + shift[m], mean, std

    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    ax.set_title(f"W15 biaxial set-up: macroscopic friction against mu_r (lateral stress {a.pressure/1e3:g} kN/m)",
                 fontsize=9)
    for m in models:
        x, y, e = series(m, "sin_peak")
        ax.errorbar(x, y, e, capsize=3, linestyle="-", label=f"{LABEL[m]}: peak", **styles[m])
        x, y, e = series(m, "sin_res")
        ax.errorbar(x, y, e, capsize=3, linestyle="--", mfc="none", label=f"{LABEL[m]}: residual", **styles[m])
    ax.set_xlabel("rolling coefficient mu_r")
    ax.set_ylabel("macroscopic friction sin phi = (s1 - s3)/(s1 + s3)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    written = [save_figure(fig, os.path.join(a.out, "friction_vs_mur"), a)]

    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    ax.set_title("W15 biaxial set-up: residual void ratio against mu_r", fontsize=9)
    for m in models:
        x, y, e = series(m, "e_res")
        ax.errorbar(x, y, e, capsize=3, linestyle="-", label=f"{LABEL[m]}: residual", **styles[m])
        x, y, e = series(m, "e0")
        ax.errorbar(x, y, e, capsize=3, linestyle=":", mfc="none", label=f"{LABEL[m]}: start of shear", **styles[m])
    ax.set_xlabel("rolling coefficient mu_r")
    ax.set_ylabel("planar void ratio e")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    written.append(save_figure(fig, os.path.join(a.out, "void_ratio_vs_mur"), a))

    seed = min(r["seed"] for r in rows)
    fig, axes = plt.subplots(2, len(models), figsize=(5 * len(models), 7), sharex=True, sharey="row",
                             layout="constrained", squeeze=False)
    fig.suptitle(f"W15 biaxial set-up, sample seed {seed}: sin phi and void ratio against axial strain", fontsize=10)
    cmap = plt.get_cmap("viridis")
    mus = sorted({r["mu_r"] for r in rows})
    for j, m in enumerate(models):
        for r in sorted((r for r in rows if r["model"] == m and r["seed"] == seed), key=lambda r: r["mu_r"]):
            meas = biaxial.read_measures(os.path.join(r["dir"], "measures.csv"))
            s1, s3 = meas["wall_syy"], meas["wall_sxx"]
            c = cmap(mus.index(r["mu_r"]) / max(1, len(mus) - 1))
            ok = (s1 + s3) > 0
            axes[0][j].plot(100 * meas["eps_axial"][ok], ((s1 - s3) / (s1 + s3))[ok], color=c, lw=1,
                            label=f"mu_r {r['mu_r']:g}")
            axes[1][j].plot(100 * meas["eps_axial"], meas["void_ratio"], color=c, lw=1)
        axes[0][j].set_title(LABEL[m], fontsize=9)
        axes[1][j].set_xlabel("axial strain [%]")
        for ax in axes[:, j]:
            ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("sin phi")
    axes[1][0].set_ylabel("planar void ratio e")
    axes[0][0].legend(fontsize=7)
    written.append(save_figure(fig, os.path.join(a.out, "curves"), a))
    print("wrote " + ", ".join(written), flush=True)


if __name__ == "__main__":
    sys.exit(main())
