#!/usr/bin/python3
"""Biaxial friction-angle sweep (J05 set-up): prepare once per sample and confining stress, then shear over delta
values, Jiang models and confining stresses; collect peak and residual friction angles, their mean and spread over
the samples and the strength envelopes.

  python3 tools/biaxial_sweep.py --out rondel-output-biaxial/sweep \
      --deltas 0,0.4,1.6 --models jiang_plastic,jiang_brittle --pressures 2e5 [--rate 0.1] [--jobs 2]
  python3 tools/biaxial_sweep.py --prep undercompaction --samples 3 ...   (the J05 curve: docs/biaxial.md)

delta = 0 runs with contact.rolling = none (no rolling resistance; the model is then irrelevant, run once).
Preparation (--prep): servo (inputs/biaxial_prepare.ini, the default; one sample) or undercompaction
(tools/undercompaction.py: the J05 specimen built in --ucm-layers layers to the planar void ratio --ucm-e, then
consolidated). --samples N (undercompaction only) prepares N independent specimens per confining stress, seeds
--ucm-seed, --ucm-seed + 1, ...: OUT/ucm_PkPa_sSEED/, shear runs OUT/MODEL_dDELTA_pP_rRATE_ucm_sSEED/.
--damping ALPHA runs the shear stage with run.local_damping = ALPHA (names ..._aALPHA). --cases adds
MODEL:DELTA:P:RATE points: at --rate for every sample, at another rate (the quasi-static check) for the first
--check-samples samples (default 1). The runs go sample after sample (a sample's points, its --cases at another
rate, then the next sample), so an interrupted sweep has whole samples first.
Resume: a run counts as finished when its summary.txt says 'status: complete' (a run stopped by a signal writes
'status: stopped ...', a failed one none: both run again); a preparation when undercompaction.py wrote its
summary.txt. Run the same command again to resume or extend a sweep; --collect-only writes the tables and
figures of the runs finished so far and runs nothing.
Writes OUT/table.csv and OUT/table.md (one row per run), OUT/summary.csv (per model, delta and confining stress:
n samples, mean and sample standard deviation of phi_peak, phi_res, eps_peak, e0 and phi_peak_early, the peak
over the first --early of axial strain), OUT/envelopes.csv (per
model, delta and sample with every confining stress: least-squares envelope t = s sin(phi) + c cos(phi) through
the peak states and through the residual states), OUT/curve.csv (per model and delta: envelope phi and c, mean
and sd over the samples, and the per-pressure means), OUT/curve.png (phi against delta with one-sd error bars;
--format pdf|svg, --dpi) and OUT/curves_* (tools/biaxial.py on the first sample's runs). Only runs at --rate
enter the summaries. Run lengths: --prep-steps (servo), --strain (target axial strain; steps =
ln(1/(1-strain)) / (rate dt), the top wall moves at a constant true strain rate) or --steps; the residual is the
mean over the last --window of axial strain.
--quick: the CI preset (90 discs in 3 layers, 2 samples, delta 0 and 1.6, 200 kPa, 20,000 shear steps).
Exit status: 0 done, 1 bad input or usage, 2 a rondel run failed (the tables hold the others).
"""
import csv
import math
import os
import re
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import biaxial  # noqa: E402
from rondel import CheckFailed, UsageError, study  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "biaxial_sweep"
# J05's own friction angles (Jiang, Yu & Harris 2005, section 5.2, from their text: the envelopes of Fig. 12 and the
# ends of Fig. 13), (model, delta, phi_peak, phi_res) in degrees; drawn beside the curve. Model 1 at delta 0.4 is
# 29.0 / 23.0 in the text on Fig. 12 and 28.8 / 22.8 a paragraph later: the first is drawn.
J05_PUBLISHED = (("none", 0.0, 24.4, 19.3), ("jiang_brittle", 0.4, 26.5, 20.7), ("jiang_plastic", 0.4, 29.0, 23.0),
                 ("jiang_plastic", 1.6, 42.3, 35.8))

# --quick: the CI preset (a few seconds of simulation): two small undercompaction samples, delta 0 and 1.6.
QUICK = dict(prep="undercompaction", samples=2, ucm_count=90, ucm_layers=3, ucm_width=0.08, ucm_e=0.35, deltas="0,1.6",
             models="jiang_plastic", pressures="2e5", steps=20000, window=0.002, cases="")
DT = 3.36486e-6  # [s] the J05 set-up's step (0.2 x critical, tangential+rolling mode of the smallest discs)


def ucm_done(d):
    """tools/undercompaction.py finished in D: its own OUT/summary.txt (written last) and a complete
    consolidation run."""
    return os.path.exists(os.path.join(d, "summary.txt")) and study.complete(os.path.join(d, "consolidated"))


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("--out", default="rondel-output-biaxial/sweep")
    ap.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"),
                    help="the rondel executable (default: build/rondel of this checkout)")
    ap.add_argument("--prepare", default=os.path.join(ROOT, "inputs", "biaxial_prepare.ini"))
    ap.add_argument("--shear", default=os.path.join(ROOT, "inputs", "biaxial_jiang.ini"))
    ap.add_argument("--deltas", default="0,0.4,1.6")
    ap.add_argument("--models", default="jiang_plastic")
    ap.add_argument("--pressures", default="2e5", help="confining stresses [Pa], comma-separated")
    ap.add_argument("--rate", type=float, default=0.1, help="top wall strain rate [1/s]")
    ap.add_argument("--cases", default="", help="extra cases MODEL:DELTA:P:RATE, separated by ; or spaces (e.g. a halved rate)")
    ap.add_argument("--strain", type=float, default=0.15, help="axial strain to reach")
    ap.add_argument("--steps", type=int, default=0, help="shear steps (overrides --strain)")
    ap.add_argument("--prep-steps", type=int, default=120000)
    ap.add_argument("--gain", type=float, default=0.9, help="walls.servo_gain of the shear stage")
    ap.add_argument("--window", type=float, default=0.05, help="residual window (axial strain)")
    ap.add_argument("--early", type=float, default=0.05,
                    help="phi_peak_early: the peak over the first EARLY of axial strain (default 0.05)")
    ap.add_argument("--jobs", type=int, default=2, help="runs in parallel")
    ap.add_argument("--extra", action="append", default=[], help="more --section.key=value for every run")
    ap.add_argument("--prep", choices=("servo", "undercompaction"), default="servo",
                    help="how the samples are prepared (default servo)")
    ap.add_argument("--ucm-layers", type=int, default=6, help="undercompaction: layers")
    ap.add_argument("--ucm-e", type=float, default=0.25, help="undercompaction: target planar void ratio")
    ap.add_argument("--ucm-seed", type=int, default=2005, help="undercompaction: seed of the sizes and positions")
    ap.add_argument("--damping", type=float, default=0.0, help="run.local_damping of the shear runs, [0, 1)")
    ap.add_argument("--samples", type=int, default=1,
                    help="undercompaction: independently prepared samples, seeds --ucm-seed, +1, ... (default 1)")
    ap.add_argument("--check-samples", type=int, default=1,
                    help="the --cases at another rate than --rate run on the first CHECK_SAMPLES samples (default 1)")
    ap.add_argument("--ucm-count", type=int, default=1008, help="undercompaction: discs (default 1008, J05)")
    ap.add_argument("--ucm-width", type=float, default=0.18, help="undercompaction: box width [m] (default 0.18)")
    ap.add_argument("--collect-only", action="store_true",
                    help="run nothing: tables and figures from the runs finished so far (e.g. beside a running sweep)")
    ap.add_argument("--from-table", metavar="CSV",
                    help="run nothing: the curve's tables and figure from a table.csv this tool wrote (e.g. "
                         "docs/biaxial/j05_table.csv, or one merged from several sweeps)")
    ap.add_argument("--quick", action="store_true",
                    help="tiny preset for CI: 90 discs in 3 layers (8 cm wide, e 0.3), 2 samples, delta 0 and 1.6, 200 kPa, "
                         "20,000 shear steps")
    add_figure_options(ap, dpi=150)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    if a.quick:
        for k, v in QUICK.items():
            setattr(a, k, v)
    if a.from_table:
        if not os.path.isfile(a.from_table):
            ap.error(f"--from-table: '{a.from_table}': no such file")
        return run_tool(TOOL, from_table, a)
    if not os.access(a.rondel, os.X_OK):
        ap.error(f"the rondel executable '{a.rondel}' does not exist or is not executable "
                 "(build it: make -C build rondel, or pass --rondel)")
    for ini in (a.prepare, a.shear):
        if not os.path.isfile(ini):
            ap.error(f"'{ini}': no such input file")
    if a.jobs < 1:
        ap.error("--jobs must be >= 1")
    if a.samples < 1 or a.check_samples < 0:
        ap.error("--samples must be >= 1 and --check-samples >= 0")
    if a.samples > 1 and a.prep != "undercompaction":
        ap.error("--samples > 1 needs --prep undercompaction (the servo preparation has one sample)")
    if not 0 < a.strain < 1 or a.steps < 0 or not a.window > 0:
        ap.error("--strain must be in (0, 1), --steps >= 0 and --window > 0")
    if not 0.0 <= a.damping < 1.0:
        ap.error(f"--damping must be in [0, 1), got {a.damping:g}")
    return run_tool(TOOL, sweep, a)


def parse_cases(a):
    """(model, delta, pressure, rate) of every run; UsageError on a malformed list."""
    try:
        cases = []
        for p in [float(x) for x in a.pressures.split(",")]:
            for d in [float(x) for x in a.deltas.split(",")]:
                for m in (a.models.split(",") if d > 0 else ["none"]):
                    cases.append((m, d, p, a.rate))
        for c in filter(None, re.split(r"[;\s]+", a.cases)):
            m, d, p, r = c.split(":")
            cases.append((m if float(d) > 0 else "none", float(d), float(p), float(r)))
    except ValueError as e:
        raise UsageError(f"--pressures, --deltas or --cases: {e} (numbers, comma-separated; cases MODEL:DELTA:P:RATE)")
    return list(dict.fromkeys(cases))


def sweep(a):
    os.makedirs(a.out, exist_ok=True)

    def shear_steps(rate, dt):
        return a.steps or int(math.ceil(math.log(1.0 / (1.0 - a.strain)) / (rate * dt)))

    cases = parse_cases(a)
    extra_cases = [c for c in cases if c[3] != a.rate]  # another rate: on the first --check-samples samples
    ucm = a.prep == "undercompaction"
    seeds = [a.ucm_seed + k for k in range(a.samples)] if ucm else [None]
    pressures = sorted({c[2] for c in cases})
    runs, failed, dts = [], [], {}

    def prepare(seed):
        """Stage 1 for one sample: one prepared specimen per confining stress; {p: scene.file}."""
        preps, jobs = {}, []
        for p in pressures:
            if ucm:
                d = os.path.join(a.out, f"ucm_{p/1e3:g}kPa_s{seed}")
                preps[p] = os.path.join(d, "consolidated")
                if not ucm_done(d):
                    cmd = [sys.executable, os.path.join(HERE, "undercompaction.py"), "--out", d, "--rondel", a.rondel,
                           "--pressure", f"{p:g}", "--layers", str(a.ucm_layers), "--e", f"{a.ucm_e:g}",
                           "--seed", str(seed), "--count", str(a.ucm_count),
                           "--width", f"{a.ucm_width!r}"]
                    cmd += [f"--extra={x}" for x in a.extra]
                    jobs.append((cmd, d + ".log", d))
                continue
            d = os.path.join(a.out, f"prep_{p/1e3:g}kPa")
            preps[p] = d
            if not study.complete(d):
                cmd = [a.rondel, a.prepare, f"--run.output={d}", "--run.overwrite=true", "--run.progress=false",
                       f"--run.steps={a.prep_steps}", f"--walls.control=top:servo:{p:g} right:servo:{p:g}"] + a.extra
                jobs.append((cmd, d + ".log", d))
        bad = study.run_chains([[study.Job(f"prepare {d}", cmd, d, log, ucm_done if ucm else study.complete,
                                           output=False)] for cmd, log, d in jobs], a.jobs, ROOT)
        if bad:
            raise CheckFailed("the prepare run(s) failed: " + "; ".join(f"{k}: see {v}" for k, v in bad.items()))
        return preps

    def shear(seed, preps, todo):
        """Stage 2 for one sample: the shear runs of TODO (model, delta, p, rate)."""
        jobs, reused = [], 0
        for m, dlt, p, r in todo:
            name = f"{m}_d{dlt:g}_p{p/1e3:g}kPa_r{r:g}" + (f"_ucm_s{seed}" if ucm else "")
            name += f"_a{a.damping:g}" if a.damping else ""
            d = os.path.join(a.out, name)
            runs.append((m, dlt, p, r, seed, d))
            if study.complete(d) or a.collect_only:
                reused += study.complete(d)
                continue
            # Every shear run drops the prepared contact history (laws and parameters differ from the
            # prepare stage's), so all cases start alike.
            law = ["--run.reset_history=true"] + (["--contact.rolling=none"] if m == "none" else
                                                   [f"--contact.rolling={m}", f"--jiang.delta={dlt:g}"])
            cmd = [a.rondel, a.shear, f"--scene.file={preps[p]}", "--run.progress=false",
                   f"--walls.servo_gain={a.gain}",
                   f"--walls.control=top:strain_rate:{r:g} left:servo:{p:g} right:servo:{p:g}"] + law + a.extra
            if a.damping:
                cmd.append(f"--run.local_damping={a.damping:g}")
            if not a.steps and (m, dlt) not in dts:  # the step depends on the laws, not on the sample or p
                dts[(m, dlt)] = study.probe_dt(cmd, d, ROOT, fallback=DT)
            cmd += [f"--run.output={d}", "--run.overwrite=true",
                    f"--run.steps={shear_steps(r, dts.get((m, dlt), DT))}"]
            jobs.append((cmd, d + ".log", d))
        print(f"sample {seed}: {reused} shear run(s) reused, {len(jobs)} to run", flush=True)
        bad = study.run_chains([[study.Job(f"shear {d}", cmd, d, log)] for cmd, log, d in jobs], a.jobs, ROOT)
        for cmd, log, d in jobs:
            if f"shear {d}" in bad:
                failed.append(d)
                print(f"  FAILED {d}: see {log}", flush=True)

    # Sample after sample (seed-major): an interrupted sweep has every point of the first sample first. The
    # --cases at another rate than --rate (the quasi-static check) run on the first --check-samples samples, right
    # after their main cases; --cases at --rate run for every sample.
    base = [c for c in cases if c not in extra_cases]
    for k, seed in enumerate(seeds):
        preps = {} if a.collect_only else prepare(seed)
        shear(seed, preps, base)
        if k < a.check_samples and extra_cases:
            shear(seed, preps, extra_cases)

    return collect(a, runs, failed)


def sd(xs):
    """Sample standard deviation (NaN for fewer than 2 values)."""
    return float(np.std(xs, ddof=1)) if len(xs) >= 2 else float("nan")


def residual_state(meas, window):
    """Mean s = (s1 + s3)/2 and t = (s1 - s3)/2 (walls) over the residual window (the last WINDOW of axial
    strain)."""
    eps, s1, s3 = meas["eps_axial"], meas["wall_syy"], meas["wall_sxx"]
    w = eps >= float(np.max(eps)) - window
    return float(np.mean(0.5 * (s1[w] + s3[w]))), float(np.mean(0.5 * (s1[w] - s3[w])))


def collect(a, runs, failed):
    rows = []
    for m, dlt, p, r, seed, d in runs:
        path = os.path.join(d, "measures.csv")
        if not study.complete(d) or not os.path.exists(path):
            continue
        meas = biaxial.read_measures(path)
        res = biaxial.friction_angles(meas["eps_axial"], meas["wall_syy"], meas["wall_sxx"], a.window)
        lw = biaxial.friction_angles(meas["eps_axial"], meas["syy"], meas["sxx"], a.window)
        s_res, t_res = residual_state(meas, a.window)
        early = meas["eps_axial"] <= a.early
        first = biaxial.friction_angles(meas["eps_axial"][early], meas["wall_syy"][early], meas["wall_sxx"][early])
        n = len(meas["wall_sxx"])
        late = meas["wall_sxx"][n // 10:]
        rows.append(dict(model=m, delta=dlt, p_kPa=p / 1e3, rate=r, prep=a.prep, sample=seed if seed is not None else "",
                         damping=a.damping, I=r * 0.0075 * math.sqrt(2650.0 / p),
                         phi_peak=res["phi_peak"], eps_peak=res["eps_peak"], phi_res=res["phi_residual"],
                         phi_peak_early=first["phi_peak"], eps_peak_early=first["eps_peak"],
                         phi_peak_lw=lw["phi_peak"], phi_res_lw=lw["phi_residual"],
                         s_peak_kPa=res["s_peak"] / 1e3, t_peak_kPa=0.5 * res["q_peak"] / 1e3,
                         s_res_kPa=s_res / 1e3, t_res_kPa=t_res / 1e3,
                         s3_mean_kPa=float(late.mean()) / 1e3, e0=float(meas["void_ratio"][0]),
                         eps_end=float(meas["eps_axial"][-1]), wall_s=study.wall_seconds(d), dir=d))
    keys = list(rows[0].keys()) if rows else []
    with open(os.path.join(a.out, "table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(a.out, "table.md"), "w") as f:
        f.write("| model | delta | p [kPa] | rate [1/s] | prep | sample | alpha | I | e0 | phi_peak [deg] | at eps_a "
                f"| peak to {a.early:g} [deg] | phi_res [deg] | LW peak / res | mean s3 [kPa] | run time [s] |\n"
                + "|---" * 16 + "|\n")
        for x in rows:
            f.write(f"| {x['model']} | {x['delta']:g} | {x['p_kPa']:g} | {x['rate']:g} | {x['prep']} | {x['sample']} | "
                    f"{x['damping']:g} | {x['I']:.1e} | {x['e0']:.3f} | "
                    f"{x['phi_peak']:.1f} | {x['eps_peak']:.3f} | {x['phi_peak_early']:.1f} | {x['phi_res']:.1f} | "
                    f"{x['phi_peak_lw']:.1f} / {x['phi_res_lw']:.1f} | {x['s3_mean_kPa']:.0f} | {x['wall_s']:.0f} |\n")
        f.write(f"\nResidual: mean over the last {a.window:g} of axial strain. s1 = wall_syy, s3 = wall_sxx "
                "(LW: Love-Weber syy, sxx).\n")
    print(open(os.path.join(a.out, "table.md")).read())
    main_rows = [x for x in rows if x["rate"] == a.rate]
    summary = summarise(a, main_rows)
    envs = envelopes(a, main_rows)
    write_curve(a, summary, envs)

    if not rows or a.no_plot:
        return finish(failed)
    fig_opts = ["--format", a.format, "--dpi", str(a.dpi)]
    first = rows[0]["sample"]
    sel = [x for x in rows if x["sample"] == first]  # the curves of one sample (all of them: too many lines)
    biaxial.main([os.path.join(x["dir"], "measures.csv") for x in sel] +
                 ["--out", os.path.join(a.out, "curves"), "--window", str(a.window),
                  "--labels", ",".join(os.path.basename(x["dir"]) for x in sel), "--no-envelope"] + fig_opts)
    plot_curve(a, summary, envs)
    return finish(failed)


def from_table(a):
    """The curve (curve.csv, curve.md, curve.png) from the rows of a table.csv, the runs at --rate."""
    os.makedirs(a.out, exist_ok=True)
    text = ("model", "prep", "dir", "sample")
    with open(a.from_table, newline="") as f:
        rows = [{k: (v if k in text else float(v)) for k, v in r.items()} for r in csv.DictReader(f)]
    if not rows:
        raise UsageError(f"--from-table: '{a.from_table}' holds no run")
    main_rows = [x for x in rows if x["rate"] == a.rate]
    summary = summarise(a, main_rows)
    envs = envelopes(a, main_rows)
    write_curve(a, summary, envs)
    if not a.no_plot:
        plot_curve(a, summary, envs)
    return 0


def summarise(a, rows):
    """Per (model, delta, p): n samples, mean and sample standard deviation of phi_peak, phi_res, e0, eps_peak.
    Writes OUT/summary.csv."""
    groups = {}
    for x in rows:
        groups.setdefault((x["model"], x["delta"], x["p_kPa"]), []).append(x)
    out = []
    for (m, dlt, p), xs in sorted(groups.items(), key=lambda kv: (kv[0][0] == "jiang_brittle", kv[0][1], kv[0][2])):
        row = dict(model=m, delta=dlt, p_kPa=p, n=len(xs))
        for q in ("phi_peak", "phi_res", "eps_peak", "e0", "phi_peak_early"):
            v = [x[q] for x in xs]
            row[q + "_mean"], row[q + "_sd"] = float(np.mean(v)), sd(v)
        out.append(row)
    with open(os.path.join(a.out, "summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(out[0].keys()) if out else ["model"])
        w.writeheader()
        w.writerows(out)
    return out


def envelopes(a, rows):
    """Per (model, delta, sample) with every confining stress: the Mohr-Coulomb envelope t = s sin(phi) +
    c cos(phi) through the peak states and through the residual states (least squares over the pressures).
    Writes OUT/envelopes.csv; returns {(model, delta): [per-sample dicts]}."""
    ps = sorted({x["p_kPa"] for x in rows})
    groups = {}
    for x in rows:
        groups.setdefault((x["model"], x["delta"], x["sample"]), []).append(x)
    out, by = [], {}
    for (m, dlt, seed), xs in sorted(groups.items(), key=lambda kv: (kv[0][0] == "jiang_brittle", kv[0][1], str(kv[0][2]))):
        if len(ps) < 2 or sorted(x["p_kPa"] for x in xs) != ps:
            continue
        phi_p, c_p = biaxial.envelope([x["s_peak_kPa"] for x in xs], [x["t_peak_kPa"] for x in xs])
        phi_r, c_r = biaxial.envelope([x["s_res_kPa"] for x in xs], [x["t_res_kPa"] for x in xs])
        e = dict(model=m, delta=dlt, sample=seed, n_pressures=len(xs), phi_peak_env=phi_p, c_peak_kPa=c_p,
                 phi_res_env=phi_r, c_res_kPa=c_r)
        out.append(e)
        by.setdefault((m, dlt), []).append(e)
    with open(os.path.join(a.out, "envelopes.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(out[0].keys()) if out else ["model"])
        w.writeheader()
        w.writerows(out)
    return by


def write_curve(a, summary, envs):
    """OUT/curve.csv: per (model, delta) the envelope angles and cohesions (mean and sd over the samples) and
    the mean and sd of phi_peak, phi_res and phi_peak_early at each confining stress; OUT/curve.md: the same as
    a Markdown table (without phi_peak_early)."""
    keys = sorted({(s["model"], s["delta"]) for s in summary}, key=lambda k: (k[0] == "jiang_brittle", k[1]))
    ps = sorted({s["p_kPa"] for s in summary})
    out = []
    for m, dlt in keys:
        row = dict(model=m, delta=dlt)
        es = envs.get((m, dlt), [])
        row["n_env"] = len(es)
        for q in ("phi_peak_env", "c_peak_kPa", "phi_res_env", "c_res_kPa"):
            v = [e[q] for e in es]
            row[q + "_mean"] = float(np.mean(v)) if v else float("nan")
            row[q + "_sd"] = sd(v)
        for p in ps:
            s = next((s for s in summary if (s["model"], s["delta"], s["p_kPa"]) == (m, dlt, p)), None)
            for q in ("phi_peak", "phi_res", "phi_peak_early"):
                row[f"{q}_{p:g}kPa_mean"] = s[q + "_mean"] if s else float("nan")
                row[f"{q}_{p:g}kPa_sd"] = s[q + "_sd"] if s else float("nan")
            row[f"n_{p:g}kPa"] = s["n"] if s else 0
        out.append(row)
    with open(os.path.join(a.out, "curve.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(out[0].keys()) if out else ["model"])
        w.writeheader()
        for r in out:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})

    def pm(mean, sdev, unit=""):
        if math.isnan(mean):
            return "-"
        return f"{mean:.1f}{unit}" + ("" if math.isnan(sdev) else f" ± {sdev:.1f}")
    with open(os.path.join(a.out, "curve.md"), "w") as f:
        f.write("| model | delta | n | " + " | ".join(f"phi_peak {p:g} kPa" for p in ps) + " | "
                + " | ".join(f"phi_res {p:g} kPa" for p in ps)
                + " | envelope phi_peak, c [kPa] | envelope phi_res, c [kPa] |\n"
                + "|---" * (5 + 2 * len(ps)) + "|\n")
        for r in out:
            ns = sorted({r[f"n_{p:g}kPa"] for p in ps})
            f.write(f"| {r['model']} | {r['delta']:g} | {'/'.join(str(n) for n in ns)} | "
                    + " | ".join(pm(r[f"phi_peak_{p:g}kPa_mean"], r[f"phi_peak_{p:g}kPa_sd"]) for p in ps) + " | "
                    + " | ".join(pm(r[f"phi_res_{p:g}kPa_mean"], r[f"phi_res_{p:g}kPa_sd"]) for p in ps) + " | "
                    + f"{pm(r['phi_peak_env_mean'], r['phi_peak_env_sd'])}, {pm(r['c_peak_kPa_mean'], r['c_peak_kPa_sd'])} | "
                    + f"{pm(r['phi_res_env_mean'], r['phi_res_env_sd'])}, {pm(r['c_res_kPa_mean'], r['c_res_kPa_sd'])} |\n")
        f.write("\nAngles in degrees, mean ± sample standard deviation over the n samples; envelope: least-squares "
                "t = s sin(phi) + c cos(phi) over the confining stresses of each sample, then mean ± sd over the "
                "samples.\n")
    return out


def plot_curve(a, summary, envs):
    """OUT/curve.png: phi_peak and phi_res against delta, per confining stress (mean, error bar one sd over
    the samples) and from the envelopes; Model 2 (jiang_brittle) as single markers."""
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True, layout="constrained")
    ps = sorted({s["p_kPa"] for s in summary})
    n = max([s["n"] for s in summary] or [0])
    for ax, q, title in ((ax1, "phi_peak", "peak"), (ax2, "phi_res", "residual")):
        for k, p in enumerate(ps):
            xs = sorted([s for s in summary if s["p_kPa"] == p and s["model"] != "jiang_brittle"],
                        key=lambda s: s["delta"])
            off = (k - 1) * 0.012
            l = ax.errorbar([s["delta"] + off for s in xs], [s[q + "_mean"] for s in xs],
                            yerr=[0 if math.isnan(s[q + "_sd"]) else s[q + "_sd"] for s in xs], fmt="o-", ms=4,
                            capsize=2, lw=1, label=f"Model 1, {p:g} kPa")
            br = [s for s in summary if s["p_kPa"] == p and s["model"] == "jiang_brittle"]
            if br:
                ax.errorbar([s["delta"] + off for s in br], [s[q + "_mean"] for s in br],
                            yerr=[0 if math.isnan(s[q + "_sd"]) else s[q + "_sd"] for s in br], fmt="v", ms=6,
                            capsize=2, color=l[0].get_color(), mfc="none", label=f"Model 2, {p:g} kPa")
        key = "phi_peak_env" if q == "phi_peak" else "phi_res_env"
        ek = sorted([k for k in envs if k[0] != "jiang_brittle"], key=lambda k: k[1])
        if ek:
            ax.errorbar([k[1] for k in ek], [np.mean([e[key] for e in envs[k]]) for k in ek],
                        yerr=[sd([e[key] for e in envs[k]]) if len(envs[k]) > 1 else 0 for k in ek], fmt="s-",
                        color="k", ms=5, capsize=3, lw=1.5, label="Model 1, envelope")
        for k in [k for k in envs if k[0] == "jiang_brittle"]:
            ax.errorbar([k[1]], [np.mean([e[key] for e in envs[k]])],
                        yerr=[sd([e[key] for e in envs[k]]) if len(envs[k]) > 1 else 0], fmt="D", color="k",
                        mfc="none", ms=7, capsize=3, label="Model 2, envelope")
        col = 2 if q == "phi_peak" else 3
        for k, (m, dlt, *angles) in enumerate(J05_PUBLISHED):
            ax.plot([dlt], [angles[col - 2]], "*", ms=11, color="tab:red", mfc="none" if m == "jiang_brittle" else
                    "tab:red", label=("J05, envelopes (their text)" if k == 0 else None))
        ax.set_title(f"{title} friction angle", fontsize=10)
        ax.set_xlabel("delta (contact width B = delta r)")
        ax.grid(alpha=0.3)
    ax1.set_ylabel("friction angle [deg]")
    ax1.legend(fontsize=7)
    fig.suptitle(f"J05 biaxial set-up, friction angle against delta: mean ± 1 sd over {n} sample(s), "
                 f"rate {a.rate:g} /s, residual over the last {a.window:g} of {a.strain:g} axial strain", fontsize=9)
    print("wrote " + save_figure(fig, os.path.join(a.out, "curve"), a))


def finish(failed):
    """Exit status 2 when a shear run failed (the table holds the others)."""
    if failed:
        raise CheckFailed(f"{len(failed)} shear run(s) failed: " + ", ".join(failed))
    return 0


if __name__ == "__main__":
    sys.exit(main())
