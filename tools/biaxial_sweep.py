#!/usr/bin/python3
"""Biaxial friction-angle sweep (J05 set-up): prepare once per confining stress, then shear over delta
values, Jiang models and confining stresses; collect peak and residual friction angles.

  python3 tools/biaxial_sweep.py --out rondel-output-biaxial/sweep \
      --deltas 0,0.4,1.6 --models jiang_plastic,jiang_brittle --pressures 2e5 [--rate 0.1] [--jobs 2]

delta = 0 runs with contact.rolling = none (no rolling resistance; the model is then irrelevant, run once).
Preparation (--prep): servo (inputs/biaxial_prepare.ini, the default) or undercompaction (tools/undercompaction.py:
the J05 specimen built in --ucm-layers layers to the planar void ratio --ucm-e, then consolidated; its shear runs
are named ..._ucm). --damping ALPHA runs the shear stage with run.local_damping = ALPHA (names ..._aALPHA).
Writes OUT/prep_P/ (prepare runs), OUT/MODEL_dDELTA_pP_rRATE/ (shear runs), OUT/table.csv, OUT/table.md,
OUT/phi_vs_delta.png (--format pdf|svg, --dpi), plus curves from tools/biaxial.py (OUT/curves_*). Existing finished runs (summary.txt
with 'status: complete') are reused, so the sweep can be extended. Run lengths: --prep-steps, --strain
(target axial strain; steps = ln(1/(1-strain)) / (rate dt), the top wall moves at a constant true strain
rate) or --steps. Exit status: 0 done, 1 bad input or usage, 2 a rondel run failed.
"""
import concurrent.futures as cf
import csv
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import biaxial  # noqa: E402
from rondel import CheckFailed, RondelError, UsageError, open_run  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "biaxial_sweep"

DT = 3.36486e-6  # [s] the J05 set-up's step (0.2 x critical, tangential+rolling mode of the smallest discs)


def run(cmd, log):
    t0 = time.time()
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    with open(log, "w") as f:
        rc = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, env=env, cwd=ROOT)
    return rc, time.time() - t0


def wall_seconds(outdir):
    """The run's wall time from its summary (summary.json or summary.txt); NaN when it has none."""
    try:
        return float(open_run(outdir).summary()["wall_seconds"])
    except (RondelError, KeyError, TypeError, ValueError):
        return float("nan")


def probe_dt(cmd, outdir):
    """The run's time step (it depends on the laws, e.g. delta): one step into OUTDIR.probe."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(cmd + ["--run.steps=1", f"--run.output={outdir}.probe", "--run.overwrite=true",
                              "--output.checkpoint_at_end=false"], capture_output=True, text=True, env=env, cwd=ROOT)
    if p.returncode != 0:
        tail = (p.stderr.strip() or p.stdout.strip()).splitlines()[-1:] or [""]
        raise CheckFailed(f"the probe run for {outdir} exited with code {p.returncode}: {tail[0]}")
    try:  # summary.json (dt) when the build writes it, else the log's 'time step' line
        return float(open_run(f"{outdir}.probe").time_step()["dt"])
    except RondelError:
        return DT


def done(outdir):
    """The run in OUTDIR ran to its end: its summary.txt says 'status: complete'. A run stopped by a signal
    writes a summary.txt too (with 'status: stopped by a signal ...') and one that failed writes none: both
    run again."""
    try:
        with open(os.path.join(outdir, "summary.txt")) as f:
            return any(line.strip() == "status: complete" for line in f)
    except OSError:
        return False


def ucm_done(d):
    """tools/undercompaction.py finished in D: its own OUT/summary.txt (written last) and a complete
    consolidation run."""
    return os.path.exists(os.path.join(d, "summary.txt")) and done(os.path.join(d, "consolidated"))


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
    ap.add_argument("--cases", default="", help="extra cases MODEL:DELTA:P:RATE;... (e.g. a halved rate)")
    ap.add_argument("--strain", type=float, default=0.15, help="axial strain to reach")
    ap.add_argument("--steps", type=int, default=0, help="shear steps (overrides --strain)")
    ap.add_argument("--prep-steps", type=int, default=120000)
    ap.add_argument("--gain", type=float, default=0.9, help="walls.servo_gain of the shear stage")
    ap.add_argument("--window", type=float, default=0.05, help="residual window (axial strain)")
    ap.add_argument("--jobs", type=int, default=2, help="runs in parallel")
    ap.add_argument("--extra", action="append", default=[], help="more --section.key=value for every run")
    ap.add_argument("--prep", choices=("servo", "undercompaction"), default="servo",
                    help="how the samples are prepared (default servo)")
    ap.add_argument("--ucm-layers", type=int, default=6, help="undercompaction: layers")
    ap.add_argument("--ucm-e", type=float, default=0.25, help="undercompaction: target planar void ratio")
    ap.add_argument("--ucm-seed", type=int, default=2005, help="undercompaction: seed of the sizes and positions")
    ap.add_argument("--damping", type=float, default=0.0, help="run.local_damping of the shear runs, [0, 1)")
    add_figure_options(ap, dpi=150)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    if not os.access(a.rondel, os.X_OK):
        ap.error(f"the rondel executable '{a.rondel}' does not exist or is not executable "
                 "(build it: make -C build rondel, or pass --rondel)")
    for ini in (a.prepare, a.shear):
        if not os.path.isfile(ini):
            ap.error(f"'{ini}': no such input file")
    if a.jobs < 1:
        ap.error("--jobs must be >= 1")
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
        for c in filter(None, a.cases.split(";")):
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

    # Stage 1: one prepared sample per confining stress.
    preps = {}
    jobs = []
    ucm = a.prep == "undercompaction"
    for p in sorted({c[2] for c in cases}):
        if ucm:
            d = os.path.join(a.out, f"ucm_{p/1e3:g}kPa")
            preps[p] = os.path.join(d, "consolidated")
            if not ucm_done(d):
                cmd = [sys.executable, os.path.join(HERE, "undercompaction.py"), "--out", d, "--rondel", a.rondel,
                       "--pressure", f"{p:g}", "--layers", str(a.ucm_layers), "--e", f"{a.ucm_e:g}",
                       "--seed", str(a.ucm_seed)]
                cmd += [f"--extra={x}" for x in a.extra]
                jobs.append((cmd, d + ".log", d))
            continue
        d = os.path.join(a.out, f"prep_{p/1e3:g}kPa")
        preps[p] = d
        if not done(d):
            cmd = [a.rondel, a.prepare, f"--run.output={d}", "--run.overwrite=true", "--run.progress=false",
                   f"--run.steps={a.prep_steps}", f"--walls.control=top:servo:{p:g} right:servo:{p:g}"] + a.extra
            jobs.append((cmd, d + ".log", d))
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        for (cmd, log, d), (rc, t) in zip(jobs, ex.map(lambda j: run(j[0], j[1]), jobs)):
            print(f"prepare {d}: rc {rc}, {t:.1f} s", flush=True)
            if rc:
                raise CheckFailed(f"the prepare run {d} exited with code {rc}: see {log}")

    # Stage 2: the shear runs.
    runs, jobs, failed = [], [], []
    for m, dlt, p, r in cases:
        name = f"{m}_d{dlt:g}_p{p/1e3:g}kPa_r{r:g}" + ("_ucm" if ucm else "")
        name += f"_a{a.damping:g}" if a.damping else ""
        d = os.path.join(a.out, name)
        runs.append((m, dlt, p, r, d))
        if done(d):
            continue
        # Every shear run drops the prepared contact history (laws and parameters differ from the
        # prepare stage's jiang_plastic delta 0.4, mu 0.25), so all cases start alike.
        law = ["--run.reset_history=true"] + (["--contact.rolling=none"] if m == "none" else
                                               [f"--contact.rolling={m}", f"--jiang.delta={dlt:g}"])
        cmd = [a.rondel, a.shear, f"--scene.file={preps[p]}", "--run.progress=false", f"--walls.servo_gain={a.gain}",
               f"--walls.control=top:strain_rate:{r:g} left:servo:{p:g} right:servo:{p:g}"] + law + a.extra
        if a.damping:
            cmd.append(f"--run.local_damping={a.damping:g}")
        dt = probe_dt(cmd, d)
        cmd += [f"--run.output={d}", "--run.overwrite=true", f"--run.steps={shear_steps(r, dt)}"]
        jobs.append((cmd, d + ".log", d))
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        for (cmd, log, d), (rc, t) in zip(jobs, ex.map(lambda j: run(j[0], j[1]), jobs)):
            print(f"shear {d}: rc {rc}, {t:.1f} s", flush=True)
            if rc:
                failed.append(d)
                print(f"  FAILED: see {log}", flush=True)

    # Collect.
    rows = []
    for m, dlt, p, r, d in runs:
        path = os.path.join(d, "measures.csv")
        if not done(d) or not os.path.exists(path):  # a stopped run's measures end early: left out
            continue
        meas = biaxial.read_measures(path)
        res = biaxial.friction_angles(meas["eps_axial"], meas["wall_syy"], meas["wall_sxx"], a.window)
        lw = biaxial.friction_angles(meas["eps_axial"], meas["syy"], meas["sxx"], a.window)
        n = len(meas["wall_sxx"])
        late = meas["wall_sxx"][n // 10:]
        rows.append(dict(model=m, delta=dlt, p_kPa=p / 1e3, rate=r, prep=a.prep, damping=a.damping,
                         I=r * 0.0075 * math.sqrt(2650.0 / p),
                         phi_peak=res["phi_peak"], eps_peak=res["eps_peak"], phi_res=res["phi_residual"],
                         phi_peak_lw=lw["phi_peak"], phi_res_lw=lw["phi_residual"],
                         s3_mean_kPa=float(late.mean()) / 1e3, eps_end=float(meas["eps_axial"][-1]),
                         wall_s=wall_seconds(d), dir=d))
    keys = list(rows[0].keys()) if rows else []
    with open(os.path.join(a.out, "table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(a.out, "table.md"), "w") as f:
        f.write("| model | delta | p [kPa] | rate [1/s] | prep | alpha | I | phi_peak [deg] | at eps_a | phi_res [deg] "
                "| LW peak / res | mean s3 [kPa] | run time [s] |\n" + "|---" * 13 + "|\n")
        for x in rows:
            f.write(f"| {x['model']} | {x['delta']:g} | {x['p_kPa']:g} | {x['rate']:g} | {x['prep']} | "
                    f"{x['damping']:g} | {x['I']:.1e} | "
                    f"{x['phi_peak']:.1f} | {x['eps_peak']:.3f} | {x['phi_res']:.1f} | "
                    f"{x['phi_peak_lw']:.1f} / {x['phi_res_lw']:.1f} | {x['s3_mean_kPa']:.0f} | {x['wall_s']:.0f} |\n")
        f.write(f"\nResidual: mean over the last {a.window:g} of axial strain. s1 = wall_syy, s3 = wall_sxx "
                "(LW: Love-Weber syy, sxx).\n")
    print(open(os.path.join(a.out, "table.md")).read())

    # Curves of all runs, and phi against delta.
    paths = [os.path.join(x["dir"], "measures.csv") for x in rows]
    fig_opts = ["--format", a.format, "--dpi", str(a.dpi)] + (["--no-plot"] if a.no_plot else [])
    if paths:
        biaxial.main(paths + ["--out", os.path.join(a.out, "curves"), "--window", str(a.window),
                              "--labels", ",".join(os.path.basename(x["dir"]) for x in rows), "--no-envelope"] + fig_opts)
        # Strength envelope per (model, delta, rate) with several confining stresses.
        env = {}
        for x in rows:
            env.setdefault((x["model"], x["delta"], x["rate"]), []).append(x)
        for (m, dlt, r), xs in env.items():
            if len({x["p_kPa"] for x in xs}) >= 2:
                biaxial.main([os.path.join(x["dir"], "measures.csv") for x in xs] +
                             ["--out", os.path.join(a.out, f"envelope_{m}_d{dlt:g}_r{r:g}"), "--window", str(a.window)]
                             + fig_opts)
        if a.no_plot:
            return finish(failed)
        plt = pyplot()
        fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
        ax.set_title(f"Biaxial sweep: peak and residual friction angle against delta (rate {a.rate:g} 1/s)",
                     fontsize=9)
        groups = {}
        for x in rows:
            if x["rate"] != a.rate:
                continue
            for m in ([x["model"]] if x["model"] != "none" else a.models.split(",")):
                groups.setdefault((m, x["p_kPa"]), []).append(x)
        for (m, p), xs in sorted(groups.items()):
            xs.sort(key=lambda x: x["delta"])
            l, = ax.plot([x["delta"] for x in xs], [x["phi_peak"] for x in xs], "o-", label=f"{m} {p:g} kPa peak")
            ax.plot([x["delta"] for x in xs], [x["phi_res"] for x in xs], "s--", color=l.get_color(),
                    label=f"{m} {p:g} kPa residual")
        ax.set_xlabel("delta (contact width B = delta r)")
        ax.set_ylabel("friction angle [deg]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        print("wrote " + save_figure(fig, os.path.join(a.out, "phi_vs_delta"), a))
    return finish(failed)


def finish(failed):
    """Exit status 2 when a shear run failed (the table holds the others)."""
    if failed:
        raise CheckFailed(f"{len(failed)} shear run(s) failed: " + ", ".join(failed))
    return 0


if __name__ == "__main__":
    sys.exit(main())
