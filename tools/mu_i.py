#!/usr/bin/python3
"""The mu(I) rheology of discs in the sheared periodic cell (docs/mu_i.md): simple shear at a constant pressure
over a range of inertial numbers, 3 samples a point, the fits mu = mu_s + b I and phi = phi_max - a I; then the
steady friction against rolling resistance at one inertial number.

  python3 tools/mu_i.py --out rondel-output-mu_i [--samples 3] [--jobs 2]
  python3 tools/mu_i.py --quick --out /tmp/mu_i      (the CI preset: 200 discs, 1 sample, 2 points, seconds)

Each sample is inputs/periodic_prepare.ini with --scene.seed SEED (SEED = --seed, --seed + 1, ...), compressed to
--pressure. The inertial points (--inertial) run as one chain per sample in increasing I, each run starting from
the state the one before ended in (the first from the prepared sample; cell.flow_start gives each the new
rate's flow over the discs' agitation): a jammed packing started at I = 0.3 overlaps its discs past
run.max_overlap, and a chain leaves each point a short transient. Each run is
inputs/periodic_shear.ini at cell.rate_xy = I sqrt(p / rho) / d (d = 2 mm, the mean diameter; rho 2650 kg/m^3)
with the servo's gain and largest rate scaled with the rate (0.163 x rate_xy: the shear scene's 5 /s at I = 0.01)
to a shear strain of --strain; its steady part is the strain past --steady. The rolling points (--rolling
LAW:V1,V2 ...; the law's parameter is wang.mu_r, jiang.delta or constant_torque.mu_r; wang.k_r = 2/7 k_n)
start from the prepared sample at --rolling-inertial each.

Steady values of a run (rows of measures.csv past --steady): mu = mean(tau) / mean(pressure), I at the mean
pressure, the means of phi, pressure and coordination. OUT/table.csv: one row per run; OUT/summary.csv: per point, the mean over the
samples and its sample standard deviation; OUT/fit.csv: the least-squares lines through the sample means with
I <= --fit-max; OUT/mu_i.png and OUT/rolling.png: the figures (--format, --dpi, --no-plot).
Resume: run the same command again; a run whose summary.txt says 'status: complete' is kept (rondel.study).
--collect-only writes the tables of the runs finished so far and runs nothing.
"""
import csv
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from rondel import CheckFailed, UsageError, open_run, study  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "mu_i"
DIAMETER, DENSITY = 0.002, 2650.0  # [m], [kg/m^3]: the scenes' mean diameter and density
SERVO_PER_RATE = 0.163  # cell.servo_gain and servo_max_rate per unit rate_xy (5 /s at 30.7 /s)
PARAMETER = {"none": None, "wang": "wang.mu_r", "jiang_plastic": "jiang.delta", "constant_torque": "constant_torque.mu_r"}
LAW_KEYS = {"wang": ["--wang.k_r=2.857e7"]}  # k_r = 2/7 k_n, as inputs/biaxial_wang.ini
ROLLING = "wang:0.05,0.1,0.2,0.3,0.5 jiang_plastic:0.2,0.4,0.8,1.2,1.6 constant_torque:0.05,0.1,0.2,0.3"
# --quick: the CI preset, a 200-disc cell (8 cm scaled to 3.6 cm at the same packing fraction), seconds of runs.
QUICK = dict(samples=1, count=200, size=0.036, inertial="0.03,0.1", strain=3.0, steady=1.0, rolling="wang:0.2",
             rolling_inertial=0.1, prep_steps=60000)
# da Cruz et al. 2005 (2D discs, interparticle friction 0.4), as this page reads their fits: for the figures.
DA_CRUZ = dict(mu_s=0.25, b=1.1, phi_max=0.81, a=0.31)


def numbers(text, what):
    try:
        vals = [float(v) for v in text.replace(" ", "").split(",") if v]
    except ValueError:
        raise UsageError(f"{what} '{text}' is not a comma-separated list of numbers") from None
    if not vals or not all(math.isfinite(v) and v > 0 for v in vals):
        raise UsageError(f"{what} '{text}' must hold positive finite numbers")
    return vals


def rolling_cases(text):
    """[(law, value)] of --rolling 'LAW:V1,V2 LAW:V ...' plus ('none', 0)."""
    cases = [("none", 0.0)]
    for item in text.split():
        law, _, vals = item.partition(":")
        if law not in PARAMETER or law == "none" or not vals:
            raise UsageError(f"--rolling item '{item}': LAW:V1,V2 with LAW one of "
                             + ", ".join(k for k in PARAMETER if k != "none"))
        cases += [(law, v) for v in numbers(vals, f"--rolling {law}")]
    return cases


def rate_of(a, inertial):
    return inertial * math.sqrt(a.pressure / DENSITY) / DIAMETER


def shear_command(a, scene, inertial, law, value, dt):
    rate = rate_of(a, inertial)
    steps = int(math.ceil(a.strain / (rate * dt)))
    servo = SERVO_PER_RATE * rate
    cmd = [a.rondel, os.path.join(ROOT, "inputs", "periodic_shear.ini"), f"--scene.file={scene}",
           f"--cell.rate_xy={rate!r}", f"--cell.stress_yy={a.pressure:g}", f"--cell.servo_gain={servo!r}",
           f"--cell.servo_max_rate={servo!r}", f"--run.steps={steps}", "--run.progress=false",
           f"--diagnostics.every={max(1, steps // 100)}", f"--contact.rolling={law}"]
    if law != "none":
        cmd += [f"--{PARAMETER[law]}={value:g}"] + LAW_KEYS.get(law, [])
    return cmd + a.extra


def mpi(a, cmd):
    return (["mpirun", "--oversubscribe", "-n", str(a.ranks)] if a.ranks > 1 else []) + cmd


def sweep(a):
    os.makedirs(a.out, exist_ok=True)
    seeds = [a.seed + k for k in range(a.samples)]
    inertials = sorted(numbers(a.inertial, "--inertial"))
    prep = {s: os.path.join(a.out, f"prep_s{s}") for s in seeds}
    runs = [dict(sample=s, inertial=i, law="none", value=0.0, out=os.path.join(a.out, f"none_i{i:g}_s{s}"))
            for s in seeds for i in inertials]
    runs += [dict(sample=s, inertial=a.rolling_inertial, law=law, value=v, rolling=True,
                  out=os.path.join(a.out, f"{law}_{v:g}_i{a.rolling_inertial:g}_s{s}"))
             for law, v in (rolling_cases(a.rolling) if a.rolling else []) for s in seeds]
    failed = {} if a.collect_only else run_all(a, seeds, prep, runs)
    return collect(a, runs, failed)


def run_all(a, seeds, prep, runs):
    """The preparations, then the chains of inertial points and the rolling points; {name: log} of failures."""
    jobs = []
    for s in seeds:
        cmd = [a.rondel, os.path.join(ROOT, "inputs", "periodic_prepare.ini"), f"--scene.seed={s}",
               f"--cell.stress_xx={a.pressure:g}", f"--cell.stress_yy={a.pressure:g}", "--run.progress=false",
               f"--run.steps={a.prep_steps}"]
        if a.count:
            cmd += [f"--scene.count={a.count}", f"--domain.xhi={a.size!r}", f"--domain.yhi={a.size!r}"]
        jobs.append([study.Job(f"prepare s{s}", mpi(a, cmd + a.extra), prep[s])])
    failed = study.run_chains(jobs, a.jobs, ROOT)
    if failed:
        raise CheckFailed("a preparation failed: " + "; ".join(f"{k}: see {v}" for k, v in failed.items()))
    dts = {}  # the step depends on the laws (a rolling law's stiffness may set it), not on the sample or rate

    def dt(law, value):
        if (law, value) not in dts:
            probe = shear_command(a, prep[seeds[0]], 0.01, law, value, 1.0)
            dts[(law, value)] = study.probe_dt(mpi(a, probe), os.path.join(a.out, f"probe_{law}_{value:g}"), ROOT)
        return dts[(law, value)]

    chains = {s: [] for s in seeds}
    rolling = []
    for r in runs:
        s = r["sample"]
        if r.get("rolling"):
            cmd = shear_command(a, prep[s], r["inertial"], r["law"], r["value"], dt(r["law"], r["value"]))
            rolling.append([study.Job(f"{r['law']} {r['value']:g} s{s}", mpi(a, cmd + ["--run.reset_history=true"]),
                                      r["out"])])
            continue
        # The first run of a chain starts from the prepared sample, each next one from the state the one before
        # ended in: its velocities apart from its flow, plus the new flow (cell.flow_start). A sheared packing's
        # overlaps reach a few per cent of a radius, more than a new scene is allowed by default.
        first = not chains[s]
        scene = prep[s] if first else chains[s][-1].out
        cmd = shear_command(a, scene, r["inertial"], "none", 0.0, dt("none", 0.0))
        cmd += ["--run.reset_history=true"] if first else ["--scene.max_initial_overlap=0.1"]
        chains[s].append(study.Job(f"I {r['inertial']:g} s{s}", mpi(a, cmd), r["out"]))
    return study.run_chains(list(chains.values()) + rolling, a.jobs, ROOT)


def steady(a, out):
    """The steady values of the run in OUT (measures.csv rows past --steady of shear strain)."""
    m = open_run(out).measures()
    strain = m["shear_strain"] - m["shear_strain"][0]
    keep = strain >= a.steady
    if keep.sum() < 3:
        raise CheckFailed(f"{out}/measures.csv has {keep.sum()} rows past the steady strain {a.steady:g} "
                          f"(it reached {strain[-1]:.3g}): lower --steady or raise --strain")
    p = m["pressure"][keep]
    # I at the mean pressure: I sqrt(p) = rate d sqrt(rho) is the same in every row (a mean of the rows' I
    # would weigh the rows of low pressure up: 25 % too high at I = 1e-3, where p fluctuates by 30 %)
    inertial = float(np.mean(m["inertial"][keep] * np.sqrt(p)) / np.sqrt(np.mean(p)))
    return dict(mu=float(np.mean(m["tau"][keep]) / np.mean(p)), I=inertial,
                phi=float(np.mean(m["phi"][keep])), pressure=float(np.mean(p)),
                coordination=float(np.mean(m["coordination"][keep])), strain=float(strain[-1]),
                wall_seconds=study.wall_seconds(out))


def mean_sd(xs):
    xs = np.asarray(xs, dtype=float)
    return float(xs.mean()), float(xs.std(ddof=1)) if len(xs) > 1 else float("nan")


def line_fit(x, y):
    """Least squares y = c0 + c1 x; (c0, c1, rms of the residuals)."""
    c1, c0 = np.polyfit(x, y, 1)
    return float(c0), float(c1), float(np.sqrt(np.mean((y - c0 - c1 * np.asarray(x)) ** 2)))


def write_csv(path, rows, columns):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow([f"{r[c]:.6g}" if isinstance(r[c], float) else r[c] for c in columns])


def collect(a, runs, failed):
    table = []
    for r in runs:
        if not study.complete(r["out"]):
            continue
        table.append(dict(series="rolling" if r.get("rolling") else "inertial", law=r["law"], value=r["value"], inertial_target=r["inertial"], sample=r["sample"],
                          **steady(a, r["out"]), run=os.path.relpath(r["out"], a.out)))
    cols = ["series", "law", "value", "inertial_target", "sample", "I", "mu", "phi", "pressure", "coordination", "strain",
            "wall_seconds", "run"]
    write_csv(os.path.join(a.out, "table.csv"), table, cols)
    points = {}
    for t in table:
        points.setdefault((t["series"], t["law"], t["value"], t["inertial_target"]), []).append(t)
    summary = []
    for (series, law, value, target), ts in sorted(points.items()):
        row = dict(series=series, law=law, value=value, inertial_target=target, n=len(ts))
        for k in ("I", "mu", "phi", "coordination"):
            row[k], row[k + "_sd"] = mean_sd([t[k] for t in ts])
        summary.append(row)
    write_csv(os.path.join(a.out, "summary.csv"), summary,
              ["series", "law", "value", "inertial_target", "n", "I", "I_sd", "mu", "mu_sd", "phi", "phi_sd", "coordination",
               "coordination_sd"])
    curve = [r for r in summary if r["series"] == "inertial" and r["I"] <= a.fit_max]
    fit = {}
    if len(curve) >= 2:
        x = [r["I"] for r in curve]
        fit["mu_s"], fit["b"], fit["mu_rms"] = line_fit(x, [r["mu"] for r in curve])
        phi0, slope, fit["phi_rms"] = line_fit(x, [r["phi"] for r in curve])
        fit["phi_max"], fit["a"] = phi0, -slope
        fit["points"] = len(curve)
        write_csv(os.path.join(a.out, "fit.csv"), [fit], ["points", "mu_s", "b", "mu_rms", "phi_max", "a", "phi_rms"])
        print(f"fit over {len(curve)} points (I <= {a.fit_max:g}): mu = {fit['mu_s']:.4f} + {fit['b']:.3f} I, "
              f"phi = {fit['phi_max']:.4f} - {fit['a']:.3f} I")
    for r in summary:
        print(f"{r['series']:>8} {r['law']:>16} {r['value']:<5g} I {r['I']:.4g}: mu {r['mu']:.4f} +- {r['mu_sd']:.4f}, "
              f"phi {r['phi']:.4f} +- {r['phi_sd']:.4f} (n {r['n']})")
    if not a.no_plot and table:
        plot(a, summary, fit, curve)
    if failed:
        for k, v in failed.items():
            print(f"FAILED {k}: {v}")
        return 2
    return 0


def spread(rows, key):
    """The error bars: the samples' sd (none from a single sample)."""
    return [0.0 if math.isnan(r[key]) else r[key] for r in rows]


def plot(a, summary, fit, curve):
    plt = pyplot()
    if curve:
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6))
        x = np.array([r["I"] for r in curve])
        xs = np.geomspace(min(x) * 0.8, max(x) * 1.25, 50)
        ax1.errorbar(x, [r["mu"] for r in curve], yerr=spread(curve, "mu_sd"), fmt="o", capsize=3,
                     label="Rondel (mean, sd of samples)")
        ax2.errorbar(x, [r["phi"] for r in curve], yerr=spread(curve, "phi_sd"), fmt="o", capsize=3,
                     label="Rondel")
        if fit:
            ax1.plot(xs, fit["mu_s"] + fit["b"] * xs, "-", label=f"fit {fit['mu_s']:.3f} + {fit['b']:.2f} I")
            ax2.plot(xs, fit["phi_max"] - fit["a"] * xs, "-", label=f"fit {fit['phi_max']:.3f} - {fit['a']:.2f} I")
        ax1.plot(xs, DA_CRUZ["mu_s"] + DA_CRUZ["b"] * xs, "k--", lw=1, label="da Cruz et al. 2005")
        ax2.plot(xs, DA_CRUZ["phi_max"] - DA_CRUZ["a"] * xs, "k--", lw=1, label="da Cruz et al. 2005")
        for ax, name in ((ax1, "mu = tau / p"), (ax2, "solid fraction phi")):
            ax.set_xscale("log")
            ax.set_xlabel("inertial number I")
            ax.set_ylabel(name)
            ax.legend(fontsize=7)
        save_figure(fig, os.path.join(a.out, "mu_i"), a)
    laws = [law for law in PARAMETER if law != "none" and any(r["law"] == law for r in summary)]
    if laws:
        base = [r for r in summary if r["series"] == "rolling" and r["law"] == "none"]
        fig, axes = plt.subplots(1, len(laws), figsize=(3.3 * len(laws), 3.2), sharey=True, squeeze=False)
        for ax, law in zip(axes[0], laws):
            rs = base + sorted((r for r in summary if r["law"] == law), key=lambda r: r["value"])
            ax.errorbar([r["value"] for r in rs], [r["mu"] for r in rs],
                        yerr=spread(rs, "mu_sd"), fmt="o-", capsize=3)
            ax.set_xlabel(PARAMETER[law])
            ax.set_title(law, fontsize=9)
        axes[0][0].set_ylabel(f"mu at I = {a.rolling_inertial:g}")
        save_figure(fig, os.path.join(a.out, "rolling"), a)


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("--out", default="rondel-output-mu_i")
    ap.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"),
                    help="the rondel executable (default: build/rondel of this checkout)")
    ap.add_argument("--samples", type=int, default=3, help="independent samples a point (default 3)")
    ap.add_argument("--seed", type=int, default=11, help="scene.seed of the first sample (default 11)")
    ap.add_argument("--pressure", type=float, default=1e5, help="the pressure held [Pa] (default 1e5)")
    ap.add_argument("--inertial", default="0.001,0.003,0.01,0.03,0.1,0.2,0.3", help="inertial numbers")
    ap.add_argument("--strain", type=float, default=10.0, help="shear strain of each run (default 10)")
    ap.add_argument("--steady", type=float, default=3.0, help="steady part: past this shear strain (default 3)")
    ap.add_argument("--fit-max", type=float, default=0.3, help="fit the points with I <= FIT_MAX (default 0.3)")
    ap.add_argument("--rolling", default=ROLLING, help="rolling points 'LAW:V1,V2 ...' ('' for none)")
    ap.add_argument("--rolling-inertial", type=float, default=0.01, help="I of the rolling points (default 0.01)")
    ap.add_argument("--prep-steps", type=int, default=120000, help="steps of each preparation (default 120,000)")
    ap.add_argument("--count", type=int, default=0, help="discs (default: the prepare scene's 1000)")
    ap.add_argument("--size", type=float, default=0.08, help="the cell's side at the start [m], with --count")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks a run (default 1)")
    ap.add_argument("--extra", action="append", default=[], help="more --section.key=value for every run")
    ap.add_argument("--collect-only", action="store_true", help="run nothing: tables and figures of the runs so far")
    ap.add_argument("--quick", action="store_true", help="the CI preset: 200 discs, 1 sample, I 0.03 and 0.1, "
                    "strain 3, wang mu_r 0.2 at I 0.1")
    add_figure_options(ap, dpi=150)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    if a.quick:
        for k, v in QUICK.items():
            setattr(a, k, v)
    if not os.access(a.rondel, os.X_OK):
        ap.error(f"the rondel executable '{a.rondel}' does not exist or is not executable "
                 "(build it: make -C build rondel, or pass --rondel)")
    if a.samples < 1 or a.jobs < 1 or a.ranks < 1 or a.prep_steps < 1 or a.count < 0:
        ap.error("--samples, --jobs, --ranks and --prep-steps must be >= 1, --count >= 0")
    for name in ("pressure", "strain", "fit_max", "rolling_inertial", "size"):
        v = getattr(a, name)
        if not (math.isfinite(v) and v > 0):
            ap.error(f"--{name.replace('_', '-')} must be a positive finite number, got {v:g}")
    if not (math.isfinite(a.steady) and 0 <= a.steady < a.strain):
        ap.error(f"--steady must lie in [0, --strain), got {a.steady:g}")
    return run_tool(TOOL, sweep, a)


if __name__ == "__main__":
    sys.exit(main())
