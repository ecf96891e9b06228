#!/usr/bin/python3
"""Error against run time for Rondel's validation cases with exact answers (docs/validation.md section 7).

For each case, runs dt_k = dt0 / 2^k (k = 0 .. levels-1, dt0 = 0.2 dt_crit, dt_crit read from the run's
log.txt and checked against docs/physics.md section 4 computed here) and records the step size, steps, wall time
(of the subprocess, and the figure in summary.txt), the error against the exact answer and the observed order
p_k = log2(err_k / err_{k+1}), plus a least-squares slope of log(error) against log(dt) over all levels.

Cases (the exact answers are computed here from the formulas of docs/validation.md / docs/physics.md):
  a   two-disc normal impact (two D5, set J, 1 m/s), zeta = 0: |1 - e|, worst of --phases contact-onset
      phases                                                                    (VALIDATION 4; 7 says 3)
  a2  the same with dt0 the largest step below 0.2 dt_crit that divides the contact time t_c = pi/w0
  b   the same impact with zeta = 0.3: |e - e_exact|                            (VALIDATION 4; 7 says 1)
  c   D5 rolling on a flat wall (set S, v0 = 1 m/s), constant_torque mu_r = 0.05, f_lim = 0: first-stop
      (largest) x against the rigid-plastic s = a KE0/M; also against the model's own continuum answer
      with its undamped tangential spring ("alt. error")                        (VALIDATION 2; 7 says >= 2)
  d   the same with jiang_plastic (delta = 0.3): first stop against s1 = a (KE0/M + M/(2K)) (VALIDATION 2)
  e   rolling mode of a D5 resting on a wall (jiang_plastic, K = 0.75), started along the low mode:
      frequency from the zero crossings of omega against the quartic's w_low   (VALIDATION 5; 7 says 2)
  c2  (not in the default set) case c with tangential damping zeta_t = 0.5, against the continuum stop of
      that model (the rigid s plus the static shift of the tangential spring, D/Omega^2)
final.csv is the only trajectory output of rondel, so a first stop is found by runs that end at chosen
steps (a bracketed search for the step where vx changes sign), the maximum then from the cubic Hermite
interpolant of (x, vx) at the two steps around it; the frequency of case e comes from diagnostics.csv
(ke_rot every step).

Usage (from the repository root; only numpy and matplotlib are needed; about 2 minutes on 2 cores):
  /usr/bin/python3 tools/error_vs_runtime.py [--rondel build/rondel] [--out study-output]
      [--levels 6 | --quick] [--cases a,a2,b,c,d,e] [--ranks 1] [--phases 5] [--keep-runs]
Output in --out: <case>.csv per case, combined.csv, combined.md (also printed), error_vs_runtime.png
(--format pdf|svg, --dpi). The critical step comes from the run's summary.json when present, else log.txt.
Exit status: 0 done, 1 bad executable or option, 2 a rondel run failed (e.g. more ranks than the build accepts).
The cases are in tools/error_cases.py, their runs and exact answers in tools/error_runs.py.
"""
import csv
import math
import os
import shutil
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from error_cases import CASES  # noqa: E402
from error_runs import RunError, Runner  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "error_vs_runtime"


# ---------------------------------------------------------------------------------------------------------
def orders(errors):
    p = [None]
    for e0, e1 in zip(errors[:-1], errors[1:]):
        p.append(math.log2(e0 / e1) if e0 > 0 and e1 > 0 else None)
    return p


def fitted_order(dts, errors):
    pts = [(math.log(d), math.log(e)) for d, e in zip(dts, errors) if e > 0]
    if len(pts) < 2:
        return None
    x, y = np.array(pts).T
    return float(np.polyfit(x, y, 1)[0])


def fmt(v, spec):
    return "" if v is None else format(v, spec)


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__.split("\n")[0], epilog=__doc__)
    ap.add_argument("--rondel", default="build/rondel", help="the rondel executable (default build/rondel)")
    ap.add_argument("--out", default="study-output", help="output directory (default study-output/)")
    ap.add_argument("--levels", type=int, default=6, help="number of step sizes, k = 0..levels-1 (default 6)")
    ap.add_argument("--quick", action="store_true", help="smoke check: 3 levels and 2 onset phases")
    ap.add_argument("--cases", default="a,a2,b,c,d,e", help="comma-separated cases among " + ",".join(CASES))
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks (mpirun -n N --oversubscribe "
                    "--allow-run-as-root); the errors are the same bits on any rank count")
    ap.add_argument("--launcher", choices=["auto", "mpirun", "direct"], default="auto",
                    help="auto: mpirun when --ranks > 1, else the executable directly")
    ap.add_argument("--phases", type=int, default=None, help="contact-onset phases per impact level (default 5)")
    ap.add_argument("--keep-runs", action="store_true", help="keep the run directories under OUT/runs")
    add_figure_options(ap, dpi=150)
    args = ap.parse_args(argv)
    check_figure_options(ap, args)

    levels = 3 if args.quick else args.levels
    phases = args.phases or (2 if args.quick else 5)
    if levels < 1 or phases < 1 or args.ranks < 1:
        ap.error("--levels, --phases and --ranks must be >= 1")
    keys = [c.strip() for c in args.cases.split(",") if c.strip()]
    for c in keys:
        if c not in CASES:
            ap.error(f"unknown case '{c}' (choose among {', '.join(CASES)})")
    launcher = args.launcher if args.launcher != "auto" else ("mpirun" if args.ranks > 1 else "direct")
    os.makedirs(args.out, exist_ok=True)
    if not os.access(os.path.abspath(args.rondel), os.X_OK):
        ap.error(f"the rondel executable '{args.rondel}' does not exist or is not executable "
                 "(build it: make -C build rondel, or pass --rondel)")
    return run_tool(TOOL, study, args, keys, levels, phases, launcher)


def study(args, keys, levels, phases, launcher):
    runner = Runner(args.rondel, args.ranks, args.out, launcher)

    rank_label = f"{args.ranks} rank" + ("s" if args.ranks > 1 else "")
    results = {}
    t_start = time.perf_counter()
    for key in keys:
        try:
            case = CASES[key](runner, args.out, phases)
            dt_crit = case.probe()
            dt0 = case.base_step(dt_crit)
            rows = []
            for k in range(levels):
                dt = dt0 / 2 ** k
                r = case.level(k, dt)
                r.update({"case": key, "k": k, "dt": dt, "dt_over_crit": dt / dt_crit, "ranks": args.ranks})
                rows.append(r)
                print(f"  [{key}] k={k} dt={dt:.4e} steps={r['steps']} runs={r['runs']} "
                      f"wall={r['wall_subprocess']:.3f}s ({r['wall_summary']:.4f}s in-code) "
                      f"error={r['error']:.3e}", file=sys.stderr, flush=True)
            for r, p in zip(rows, orders([r["error"] for r in rows])):
                r["order"] = p
            fit = fitted_order([r["dt"] for r in rows], [r["error"] for r in rows])
            fit_alt = None
            if all(r.get("error_alt") is not None for r in rows):
                for r, p in zip(rows, orders([r["error_alt"] for r in rows])):
                    r["order_alt"] = p
                fit_alt = fitted_order([r["dt"] for r in rows], [r["error_alt"] for r in rows])
            results[key] = {"case": case, "rows": rows, "fit": fit, "fit_alt": fit_alt, "dt_crit": dt_crit}
        except RunError as e:
            raise RunError(f"case {key}: {e}") from None
    elapsed = time.perf_counter() - t_start

    # tables
    fields = ["case", "ranks", "k", "dt", "dt_over_crit", "steps", "runs", "wall_subprocess", "wall_summary",
              "disc_steps_per_s", "measured", "exact", "error", "order", "error_alt", "order_alt", "extra"]
    all_rows = []
    for key, R in results.items():
        all_rows += R["rows"]

    def csv_rows(rows):
        return [{k: ("" if r.get(k) is None else r.get(k)) for k in fields} for r in rows]

    for key, R in results.items():
        with open(os.path.join(args.out, f"{key}.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            w.writerows(csv_rows(R["rows"]))
    with open(os.path.join(args.out, "combined.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(csv_rows(all_rows))

    md = [f"Error against run time: {rank_label}, {levels} levels dt_k = dt0/2^k (dt0 = 0.2 dt_crit; a2: the "
          f"largest step below it that divides t_c), {runner.count} rondel runs in {elapsed:.0f} s", ""]
    md.append("| case | ranks | k | dt [s] | dt/dt_crit | steps | runs | wall, subprocess [s] | wall, summary [s] "
              "| error | p | alt. error | alt. p |")
    md.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in all_rows:
        md.append(f"| {r['case']} | {r['ranks']} | {r['k']} | {r['dt']:.4e} | {r['dt_over_crit']:.5f} | {r['steps']} | "
                  f"{r['runs']} | {r['wall_subprocess']:.3f} | {r['wall_summary']:.4g} | {r['error']:.3e} | "
                  f"{fmt(r['order'], '.2f')} | {fmt(r.get('error_alt'), '.3e')} | {fmt(r.get('order_alt'), '.2f')} |")
    md += ["", "| case | error measure | exact | dt_crit [s] (log / docs/physics.md 4) | limiting mode | expected p "
           "| fitted p (all levels) | p of the last pair | alt. error: fitted p |",
           "|---|---|---|---|---|---|---|---|---|"]
    for key, R in results.items():
        c = R["case"]
        last = R["rows"][-1]["order"]
        alt = f"{c.alt_name}: {fmt(R['fit_alt'], '.2f')}" if R["fit_alt"] is not None else ""
        md.append(f"| {mdc(c.title)} | {mdc(c.error_name)} | {c.exact:.12g} | {R['dt_crit']:.6g} / "
                  f"{c.dt_crit_tool:.6g} | {c.crit_mode} | {mdc(c.expected_order)} | {fmt(R['fit'], '.2f')} | "
                  f"{fmt(last, '.2f')} | {mdc(alt)} |")
    notes = [f"- {key}: {n}" for key, R in results.items() for n in R["case"].notes]
    notes += [f"- {r['case']} k={r['k']}: {r['extra']}" for r in all_rows if r.get("extra")]
    if notes:
        md += ["", "Notes:", ""] + notes
    text = "\n".join(md) + "\n"
    with open(os.path.join(args.out, "combined.md"), "w") as f:
        f.write(text)
    print(text)

    figure = None if args.no_plot else plot(results, os.path.join(args.out, "error_vs_runtime"), rank_label, args)
    if not args.keep_runs:
        shutil.rmtree(os.path.join(args.out, "runs"), ignore_errors=True)
    print(f"error_vs_runtime: wrote {args.out}/combined.md, combined.csv, <case>.csv"
          + (f", {figure}" if figure else ""), file=sys.stderr)
    return 0


def mdc(text):
    """A markdown table cell: pipes escaped."""
    return str(text).replace("|", "\\|")


def plot(results, stem, rank_label, args):
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(15, 6.5))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, (key, R) in enumerate(results.items()):
        c = colors[i % len(colors)]
        case = R["case"]
        rows = [r for r in R["rows"] if r["error"] > 0]
        if rows:
            err = [r["error"] for r in rows]
            label = f"{case.title} [{rank_label}]: fitted p = {fmt(R['fit'], '.2f')} (expected {case.expected_order})"
            ax1.loglog([r["wall_summary"] for r in rows], err, "o-", color=c, label=label)
            ax1.loglog([r["wall_subprocess"] for r in rows], err, "s:", color=c, alpha=0.4, markersize=3)
            ax2.loglog([r["dt"] for r in rows], err, "o-", color=c, label=label)
        alt = [r for r in R["rows"] if r.get("error_alt")]
        if alt and R["fit_alt"] is not None:
            label = f"({key}) {case.alt_name} [{rank_label}]: fitted p = {fmt(R['fit_alt'], '.2f')}"
            ax1.loglog([r["wall_summary"] for r in alt], [r["error_alt"] for r in alt], "^--", color=c,
                       markerfacecolor="none", label=label)
            ax2.loglog([r["dt"] for r in alt], [r["error_alt"] for r in alt], "^--", color=c,
                       markerfacecolor="none", label=label)
    ax1.set_xlabel("wall time of one run [s]: solid = summary.txt (time loop); dotted = subprocess "
                   "(includes ~1 s of MPI start-up)", fontsize=8)
    ax1.set_ylabel("error (each case's own measure, see the legend)")
    ax1.set_title(f"Error against wall time ({rank_label})")
    ax2.set_xlabel("dt [s]")
    ax2.set_title(f"Error against step size ({rank_label})")
    # a fan of reference slopes 1, 2, 3 over one decade of dt, in the lower left corner
    (xlo, xhi), (ylo, yhi) = ax2.get_xlim(), ax2.get_ylim()
    x0, x1 = xlo * 1.3, xlo * 13
    y0 = ylo * 1.5
    for p in (1, 2, 3):
        ax2.loglog([x0, x1], [y0, y0 * (x1 / x0) ** p], color="grey", lw=0.9, ls="--")
        ax2.annotate(f"slope {p}", (x1, y0 * (x1 / x0) ** p), fontsize=7, color="grey",
                     xytext=(2, -3), textcoords="offset points")
    ax2.set_xlim(xlo, xhi)
    ax2.set_ylim(ylo, yhi)
    for ax in (ax1, ax2):
        ax.grid(True, which="both", alpha=0.25)
    handles, labels = ax2.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=7.5, frameon=False)
    fig.suptitle("Rondel validation cases with exact answers: error against run time and step size "
                 f"({rank_label})", fontsize=11)
    fig.tight_layout(rect=(0, 0.16, 1, 1))
    return save_figure(fig, stem, args)


if __name__ == "__main__":
    sys.exit(main())
