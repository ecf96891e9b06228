#!/usr/bin/python3
"""Dynamic angle of repose in a rotating drum (inputs/drum.ini, docs/drum.md), and the sweep over mu_r.

  python3 tools/drum.py RUN_DIR [--from T] [--out PREFIX] [--no-plot] [--format png|pdf|svg] [--dpi N]
  python3 tools/drum.py --sweep [--out DIR] [--laws wang,constant_torque] [--mu-r 0,0.05,0.1,0.2,0.4]
                        [--jobs 2] [--ranks 1] [--steps N] [--ini inputs/drum.ini] [--rondel build/rondel]
                        [--set LAW.KEY=VALUE ...] [--rondel-arg=--SECTION.KEY=VALUE ...]

Input (RUN_DIR): the snapshots snapshot_*.h5 (/discs/position, /discs/radius; the drum from /walls: the
circle wall (kind circle), centre /walls/p0, radius /walls/radius, angular velocity /walls/omega). Snapshots at
t >= --from (default 0.4 x the time of the last snapshot: the bed has reached its steady flow by then in
inputs/drum.ini) are measured; each gives two angles, both positive when the bed leans the way the drum
turns:
  1. centre of mass: the bed's centre of mass (disc areas as weights) x_m and the drum centre c;
     angle_cm = atan2(s (x_m - c_x), c_y - y_m), s = sign(Omega). For a flat free surface the centre of mass of
     a circular segment lies on the perpendicular from c to the surface, so angle_cm is the surface's tilt.
  2. free surface: in x-bins one mean diameter wide, the highest disc top y + R (a disc counts only if it
     touches another disc or the drum: discs in flight are left out); a least-squares line through the
     points of the middle 60 % of the surface's x-range (the bed's ends at the drum are left out);
     angle_surface = atan(s slope).
The dynamic angle of the run is the mean over the measured snapshots, with their standard deviation as its
spread. Writes PREFIX.csv (one row per snapshot: time, angle_cm_deg, angle_surface_deg, surface_points,
surface_rms_m), PREFIX_angles.csv (method, mean_deg, std_deg, min_deg, max_deg, snapshots, from_s) and
PREFIX.png (the last snapshot: discs, drum, the centre-of-mass line and the fitted surface; the angles
against time). PREFIX defaults to RUN_DIR/drum.

--sweep runs inputs/drum.ini for every law of --laws and every mu_r of --mu-r (mu_r = 0 is one run with
contact.rolling = none, shared by the laws) into DIR/LAW_muMU/ (DIR/none/), --jobs runs at a time, each on
--ranks ranks; a run that finished before (its summary.txt says 'status: complete') is reused and any other
(stopped by a signal, killed, failed) runs again from its start, so a sweep stopped half way resumes where it
stopped. Each run is measured as above; the sweep writes DIR/table.csv, DIR/table.md and
DIR/angle_vs_mu_r.png. The rolling law's parameters: wang k_r = 2.857e5 N/m (inputs/drum.ini) and mu_r;
constant_torque mu_r (f_lim its default 0.08); any other law takes its parameters from --set LAW.KEY=VALUE.
Exit status: 0 done, 1 a missing or unreadable input or a bad option, 2 nothing measurable or a run failed.
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
from rondel import CheckFailed, RondelError, RondelFileError, UsageError, open_file, open_run, study  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "drum"
TOUCH = 0.05   # a disc touches another (or the drum) when the gap is below TOUCH x the mean radius
MIDDLE = 0.6   # the fraction of the surface's x-range fitted (its middle)
WANG_K_R = 2.857e5


class MeasureError(CheckFailed):
    """No snapshot could be measured (exit status 2)."""


# ------------------------------------------------------------------------------------------ measuring

def drum_of(f):
    """(centre (2,), R_c, Omega) of the file's circle wall (the first one)."""
    w = f.walls
    if "kind" not in w or "radius" not in w:
        raise RondelFileError(f.path, "has no circle wall (/walls/kind circle with /walls/radius): not a drum run")
    hits = [i for i, name in enumerate(f.wall_kinds()) if name == "circle"]
    if not len(hits):
        raise RondelFileError(f.path, "has no circle wall (/walls/kind circle): not a drum run")
    k = int(hits[0])
    omega = float(np.asarray(w["omega"]).reshape(-1)[k]) if "omega" in w else 0.0
    return np.asarray(w["p0"]).reshape(-1, 2)[k].astype(float), float(np.asarray(w["radius"]).reshape(-1)[k]), omega


def touching(pos, radius, centre, R_c, tol):
    """Discs that touch another disc or the drum (gap below tol)."""
    n = len(radius)
    ok = np.zeros(n, dtype=bool)
    d_c = np.sqrt(np.sum((pos - centre) ** 2, axis=1))
    ok |= d_c + radius > R_c - tol
    order = np.argsort(pos[:, 0])
    xs = pos[order, 0]
    r_max = float(radius.max())
    for a in range(n):
        i = order[a]
        hi = np.searchsorted(xs, xs[a] + radius[i] + r_max + tol, side="right")
        for b in range(a + 1, hi):
            j = order[b]
            gap = math.hypot(pos[i, 0] - pos[j, 0], pos[i, 1] - pos[j, 1]) - radius[i] - radius[j]
            if gap < tol:
                ok[i] = ok[j] = True
    return ok


def measure(pos, radius, centre, R_c, omega):
    """The two angles [deg] of one state, with the surface fit's points (x, y), line (slope, intercept),
    point count and RMS residual [m]."""
    pos = np.asarray(pos, dtype=float).reshape(-1, 2)
    radius = np.asarray(radius, dtype=float)
    s = 1.0 if omega >= 0.0 else -1.0
    w = radius ** 2
    cm = (pos * w[:, None]).sum(axis=0) / w.sum()
    angle_cm = math.degrees(math.atan2(s * (cm[0] - centre[0]), centre[1] - cm[1]))
    r_mean = float(radius.mean())
    keep = touching(pos, radius, centre, R_c, TOUCH * r_mean)
    p, r = pos[keep], radius[keep]
    width = 2.0 * r_mean
    bins = np.floor((p[:, 0] - centre[0]) / width).astype(int)
    top = {}
    for k, b in enumerate(bins):
        y = p[k, 1] + r[k]
        if b not in top or y > top[b][1]:
            top[b] = (p[k, 0], y)
    pts = np.array([top[b] for b in sorted(top)]) if top else np.zeros((0, 2))
    result = dict(angle_cm=angle_cm, cm=cm, points=pts, fitted=np.zeros((0, 2)), line=None, n_fit=0,
                  rms=float("nan"), angle_surface=float("nan"))
    if len(pts) >= 2:
        lo, hi = pts[:, 0].min(), pts[:, 0].max()
        mid, half = 0.5 * (lo + hi), 0.5 * MIDDLE * (hi - lo)
        sel = pts[np.abs(pts[:, 0] - mid) <= half]
        if len(sel) >= 3:
            slope, intercept = np.polyfit(sel[:, 0], sel[:, 1], 1)
            res = sel[:, 1] - (slope * sel[:, 0] + intercept)
            result.update(angle_surface=math.degrees(math.atan(s * slope)), fitted=sel, line=(slope, intercept),
                          n_fit=len(sel), rms=float(np.sqrt(np.mean(res ** 2))))
    return result


def snapshot_states(run_dir):
    """(path, time) of every snapshot in step order."""
    run = open_run(run_dir)
    paths = run.snapshot_paths()
    if not paths:
        raise RondelFileError(run_dir, "has no snapshot_*.h5 (set output.snapshot_every)")
    return paths


def measure_run(run_dir, t_from=None):
    """Rows (time, angle_cm, angle_surface, n_fit, rms) of the snapshots at t >= t_from, the summary per method,
    t_from used, and the last measured state (for the picture)."""
    paths = snapshot_states(run_dir)
    files = [open_file(p) for p in paths]
    t_last = max(float(f.time) for f in files)
    if t_from is None:
        t_from = 0.4 * t_last
    rows, last = [], None
    for f in files:
        t = float(f.time)
        if t < t_from:
            continue
        centre, R_c, omega = drum_of(f)
        pos, radius = f.disc("position"), f.disc("radius")
        m = measure(pos, radius, centre, R_c, omega)
        rows.append((t, m["angle_cm"], m["angle_surface"], m["n_fit"], m["rms"]))
        last = (f, pos, radius, centre, R_c, omega, m)
    if not rows:
        raise MeasureError(f"{run_dir}: no snapshot at t >= {t_from:g} s (the last is at {t_last:g} s)")
    summary = {}
    for k, name in ((1, "centre_of_mass"), (2, "free_surface")):
        v = np.array([r[k] for r in rows], dtype=float)
        v = v[np.isfinite(v)]
        summary[name] = dict(mean=float(v.mean()) if len(v) else float("nan"),
                             std=float(v.std(ddof=1)) if len(v) > 1 else 0.0,
                             min=float(v.min()) if len(v) else float("nan"),
                             max=float(v.max()) if len(v) else float("nan"), n=int(len(v)))
    return rows, summary, t_from, last


def write_outputs(prefix, rows, summary, t_from, last, args, title=None):
    os.makedirs(os.path.dirname(os.path.abspath(prefix)), exist_ok=True)
    with open(prefix + ".csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["time_s", "angle_cm_deg", "angle_surface_deg", "surface_points", "surface_rms_m"])
        for r in rows:
            w.writerow([f"{r[0]:.6g}", f"{r[1]:.4f}", f"{r[2]:.4f}", r[3], f"{r[4]:.4g}"])
    with open(prefix + "_angles.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["method", "mean_deg", "std_deg", "min_deg", "max_deg", "snapshots", "from_s"])
        for name, s in summary.items():
            w.writerow([name, f"{s['mean']:.3f}", f"{s['std']:.3f}", f"{s['min']:.3f}", f"{s['max']:.3f}", s["n"],
                        f"{t_from:g}"])
    out = [prefix + ".csv", prefix + "_angles.csv"]
    if not getattr(args, "no_plot", False):
        out.append(picture(prefix, rows, summary, last, args, title))
    return out


def picture(prefix, rows, summary, last, args, title):
    plt = pyplot()
    from matplotlib.collections import EllipseCollection
    from matplotlib.patches import Circle
    f, pos, radius, centre, R_c, omega, m = last
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.6), gridspec_kw=dict(width_ratios=[1, 1.25]))
    d = 2.0 * np.asarray(radius)
    ax.add_collection(EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=pos, offset_transform=ax.transData,
                                        facecolors="tan", edgecolors="0.3", linewidths=0.3))
    ax.add_patch(Circle(tuple(centre), R_c, fill=False, color="black", lw=1.5))
    ax.plot([centre[0], m["cm"][0]], [centre[1], m["cm"][1]], "b-", lw=1.2, label=f"centre of mass: {m['angle_cm']:.1f} deg")
    ax.plot(*m["cm"], "bo", ms=4)
    if m["line"] is not None:
        xs = np.array([m["fitted"][:, 0].min(), m["fitted"][:, 0].max()])
        ax.plot(xs, m["line"][0] * xs + m["line"][1], "r-", lw=1.5,
                label=f"surface fit: {m['angle_surface']:.1f} deg")
        ax.plot(m["points"][:, 0], m["points"][:, 1], "k.", ms=2)
    # The drum's sense of rotation: an arrow along the rim at the top, where the drum is empty.
    a0, a1 = (math.radians(60), math.radians(120)) if omega >= 0 else (math.radians(120), math.radians(60))
    ax.annotate("", xy=(centre[0] + 0.9 * R_c * math.cos(a1), centre[1] + 0.9 * R_c * math.sin(a1)),
                xytext=(centre[0] + 0.9 * R_c * math.cos(a0), centre[1] + 0.9 * R_c * math.sin(a0)),
                arrowprops=dict(arrowstyle="->", color="0.3",
                                connectionstyle="arc3,rad=0.25" if omega >= 0 else "arc3,rad=-0.25"))
    ax.set_xlim(centre[0] - 1.05 * R_c, centre[0] + 1.05 * R_c)
    ax.set_ylim(centre[1] - 1.05 * R_c, centre[1] + 1.05 * R_c)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"t = {float(f.time):.2f} s, Omega = {omega:g} rad/s", fontsize=9)
    ax.legend(loc="upper left", fontsize=7)
    t = np.array([r[0] for r in rows])
    bx.plot(t, [r[1] for r in rows], "b.-", label="centre of mass")
    bx.plot(t, [r[2] for r in rows], "r.-", label="free surface")
    for name, color in (("centre_of_mass", "b"), ("free_surface", "r")):
        s = summary[name]
        bx.axhline(s["mean"], color=color, ls=":", lw=1)
    bx.set_xlabel("t [s]")
    bx.set_ylabel("dynamic angle [deg]")
    bx.legend(fontsize=8)
    bx.grid(alpha=0.3)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return save_figure(fig, prefix, args)


def main_measure(args):
    if not os.path.isdir(args.run_dir):
        raise RondelFileError(args.run_dir, "is not a run directory")
    rows, summary, t_from, last = measure_run(args.run_dir, args.t_from)
    prefix = args.out or os.path.join(args.run_dir, "drum")
    files = write_outputs(prefix, rows, summary, t_from, last, args, args.title)
    for name, s in summary.items():
        print(f"{name:15s} {s['mean']:7.2f} deg  (std {s['std']:.2f}, {s['min']:.2f} .. {s['max']:.2f}, "
              f"{s['n']} snapshots from t = {t_from:g} s)")
    print("wrote " + ", ".join(files))
    return 0


# ------------------------------------------------------------------------------------------ sweep

def base_ini(ini_path, out_path):
    """The scene of ini_path without its rolling law: the contact.rolling line and the law blocks removed
    (a law's block is refused while another law is selected); the law comes on the command line."""
    try:
        text = open(ini_path).read()
    except OSError as e:
        raise RondelFileError(ini_path, f"cannot be read ({e.strerror})")
    out, section = [], ""
    blocks = {"wang", "constant_torque", "jiang", "iwashita_oda", "force_proportional", "displacement_damping"}
    for line in text.splitlines():
        m = re.match(r"\s*\[([^\]]+)\]", line)
        if m:
            section = m.group(1).strip()
        if section in blocks:
            continue
        if section == "contact" and re.match(r"\s*rolling\s*=", line):
            continue
        out.append(line)
    with open(out_path, "w") as f:
        f.write("\n".join(out) + "\n")
    return out_path


def law_args(law, mu_r, sets):
    if mu_r == 0.0:
        return ["--contact.rolling=none"]
    a = [f"--contact.rolling={law}", f"--{law}.mu_r={mu_r:g}"]
    if law in ("wang", "alonso_marroquin"):
        a.append(f"--wang.k_r={WANG_K_R:g}")
    a += [f"--{s}" for s in sets if s.startswith(law + ".")]
    return a


def run_dir_name(law, mu_r):
    return "none" if mu_r == 0.0 else f"{law}_mu{mu_r:g}"


def main_sweep(args):
    try:
        laws = [s for s in args.laws.split(",") if s]
        mus = sorted({float(s) for s in args.mu_r.split(",") if s})
    except ValueError:
        raise UsageError(f"--mu-r '{args.mu_r}' is not a comma-separated list of numbers")
    if not laws or not mus or any(m < 0 or not math.isfinite(m) for m in mus):
        raise UsageError("--laws and --mu-r need at least one law and values mu_r >= 0")
    if args.jobs < 1 or args.ranks < 1:
        raise UsageError("--jobs and --ranks must be >= 1")
    if not os.path.exists(args.rondel):
        raise RondelFileError(args.rondel, "does not exist (build it: cmake --build build --target rondel)")
    os.makedirs(args.out, exist_ok=True)
    ini = base_ini(args.ini, os.path.join(args.out, "drum_base.ini"))
    cases = {}
    for law in laws:
        for mu in mus:
            cases[run_dir_name(law, mu)] = (law, mu)
    todo = []
    for name, (law, mu) in cases.items():
        d = os.path.join(args.out, name)
        if study.complete(d):
            print(f"{name}: finished before, reused")
            continue
        cmd = ([args.mpiexec, "-n", str(args.ranks), "--oversubscribe"] if args.ranks > 1 else []) + [
            args.rondel, ini, f"--run.output={d}", "--run.overwrite=true", "--run.progress=false"]
        if args.steps:
            cmd.append(f"--run.steps={args.steps}")
        cmd += law_args(law, mu, args.set) + list(args.rondel_arg)
        todo.append([study.Job(name, cmd, d)])
    failed = study.run_chains(todo, args.jobs, ROOT) if todo else {}
    table = []
    for name, (law, mu) in cases.items():
        d = os.path.join(args.out, name)
        if not study.complete(d):
            continue
        rows, summary, t_from, last = measure_run(d, args.t_from)
        write_outputs(os.path.join(d, "drum"), rows, summary, t_from, last, args, f"{law}, mu_r = {mu:g}")
        for shown_law in (laws if mu == 0.0 else [law]):
            table.append((shown_law, mu, summary, t_from, study.wall_seconds(d)))
    if not table:
        raise MeasureError("no run of the sweep finished")
    table.sort(key=lambda r: (r[0], r[1]))
    write_table(args.out, table)
    if not args.no_plot:
        sweep_plot(args.out, table, args)
    if failed:
        raise CheckFailed(f"{len(failed)} run(s) failed: " + ", ".join(os.path.join(args.out, n) for n in failed))
    return 0


def write_table(out, table):
    with open(os.path.join(out, "table.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["law", "mu_r", "angle_cm_deg", "std_cm_deg", "angle_surface_deg", "std_surface_deg", "snapshots",
                    "from_s", "wall_s"])
        for law, mu, s, t_from, secs in table:
            c, f = s["centre_of_mass"], s["free_surface"]
            w.writerow([law, f"{mu:g}", f"{c['mean']:.2f}", f"{c['std']:.2f}", f"{f['mean']:.2f}", f"{f['std']:.2f}",
                        c["n"], f"{t_from:g}", f"{secs:.0f}"])
    with open(os.path.join(out, "table.md"), "w") as fh:
        fh.write("| law | mu_r | angle, centre of mass [deg] | angle, free surface [deg] | snapshots (from t) | "
                 "run time [s] |\n|---|---|---|---|---|---|\n")
        for law, mu, s, t_from, secs in table:
            c, f = s["centre_of_mass"], s["free_surface"]
            fh.write(f"| {law if mu else 'none'} | {mu:g} | {c['mean']:.1f} +- {c['std']:.1f} | "
                     f"{f['mean']:.1f} +- {f['std']:.1f} | {c['n']} (from {t_from:g} s) | {secs:.0f} |\n")
    print(open(os.path.join(out, "table.md")).read(), end="")


def sweep_plot(out, table, args):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    for k, law in enumerate(sorted({r[0] for r in table})):
        rows = [r for r in table if r[0] == law]
        mu = [r[1] for r in rows]
        for name, marker, ls in (("centre_of_mass", "o", "-"), ("free_surface", "s", "--")):
            ax.errorbar(mu, [r[2][name]["mean"] for r in rows], yerr=[r[2][name]["std"] for r in rows],
                        marker=marker, ls=ls, color=f"C{k}", capsize=3,
                        label=f"{law}, {'centre of mass' if name == 'centre_of_mass' else 'free surface'}")
    ax.set_xlabel("mu_r")
    ax.set_ylabel("dynamic angle of repose [deg]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return save_figure(fig, os.path.join(out, "angle_vs_mu_r"), args)


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("run_dir", nargs="?", help="a drum run directory (with snapshots)")
    ap.add_argument("--from", dest="t_from", type=float, default=None,
                    help="measure the snapshots at t >= this [s] (default 0.4 x the last snapshot's time)")
    ap.add_argument("--out", default=None, help="output prefix (measure) or directory (--sweep)")
    ap.add_argument("--title", default=None)
    ap.add_argument("--sweep", action="store_true", help="run and measure the sweep over --laws and --mu-r")
    ap.add_argument("--laws", default="wang,constant_torque")
    ap.add_argument("--mu-r", default="0,0.05,0.1,0.2,0.4")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--steps", type=int, default=0, help="run.steps of every run (default: the scene's)")
    ap.add_argument("--ini", default=os.path.join(ROOT, "inputs", "drum.ini"))
    ap.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"))
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--set", action="append", default=[], metavar="LAW.KEY=VALUE",
                    help="an extra law parameter of the sweep's runs (repeatable)")
    ap.add_argument("--rondel-arg", action="append", default=[], metavar="--SECTION.KEY=VALUE",
                    help="an extra option of every run of the sweep (repeatable), e.g. --rondel-arg=--run.dt=1e-5")
    add_figure_options(ap)
    args = ap.parse_args(argv)
    check_figure_options(ap, args)
    if args.t_from is not None and not (math.isfinite(args.t_from) and args.t_from >= 0):
        ap.error(f"--from {args.t_from:g} must be a time >= 0")
    if args.sweep:
        if args.run_dir:
            ap.error("--sweep takes no RUN_DIR (use --out DIR)")
        args.out = args.out or os.path.join("rondel-output", "drum_sweep")
        return run_tool(TOOL, main_sweep, args)
    if not args.run_dir:
        ap.error("give a RUN_DIR, or --sweep")
    return run_tool(TOOL, main_measure, args)


if __name__ == "__main__":
    sys.exit(main())
