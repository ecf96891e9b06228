#!/usr/bin/python3
"""The Brazilian test of a bonded disc specimen (inputs/brazilian.ini, docs/brazilian.md).

  python3 tools/brazilian.py OUT_DIR [--sigma-c S1 S2 ...] [--ranks N] [--check TOL]
                             [--rondel PATH] [--format png|pdf|svg] [--dpi N]
  python3 tools/brazilian.py --specimen PATH [--specimen-radius RS] [--disc-radius R]

The specimen: discs of radius R on a hexagonal lattice, touching, whose centres lie within RS - R of the
specimen's centre (--specimen writes it as the CSV scene inputs/brazilian_disc.csv: 'id,x,y,radius', the lowest
discs on the bottom platen y = 0, the highest touching the top platen; its first line says where that is). Every touching pair is bonded
(inputs/brazilian.ini); the top platen moves down at a constant strain rate of the box height, the bottom one
stands.

The study runs the scene once per tensile strength --sigma-c (default 2e4 and 4e4 Pa; the shear strength stays
large, 1e9 Pa), each into OUT_DIR/sigma_<S> for the scene's run.steps times S over its sigma_c (the peak comes
after an approach proportional to the strength), and reads measures.csv: the platens' load F = wall_syy x width x
t (the mean of the two platens' normal force) [N] against their approach d = height0 - height [m]. The peak load
is the largest before the load first falls below 0.8 of its largest so far (the specimen has split; its halves,
pressed on, carry load again later). Writes
OUT_DIR/brazilian.csv (one row per strength: sigma_c, peak F, d at the peak, the Brazilian tensile strength
sigma_t = 2 F / (pi D t), sigma_t / sigma_c, the bonds broken by mode at the end, the peak over sigma_c's and the
ratio to the first strength's), OUT_DIR/brazilian.png (F against d) and, for each strength, the intact bonds at
the end (OUT_DIR/sigma_<S>_bonds.png, tools/picture.py --kind bonds). --check TOL: exit status 2 unless each
peak load over its sigma_c is the first's within TOL (relative): the peak is linear in the bonds' tensile strength
when the shear strength is large. Runs that finished before are not run again (rondel.study).
"""
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import CheckFailed, Config, open_run, read_csv, require, study  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "brazilian"
HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "inputs", "brazilian.ini")


def specimen(path, radius, disc):
    """Writes the specimen's CSV scene; returns the disc count."""
    centre = np.array([0.0, radius])
    rows, pitch = [], 2.0 * disc
    n = int(math.ceil(radius / pitch)) + 1
    for j in range(-2 * n, 2 * n + 1):
        y = radius + j * pitch * math.sqrt(3.0) / 2.0
        for i in range(-n - 1, n + 2):
            x = (i + 0.5 * (j % 2)) * pitch
            if np.hypot(x - centre[0], y - centre[1]) <= radius - disc + 1e-12:
                rows.append((x, y))
    low = min(y for _, y in rows) - disc  # the lowest disc on y = 0
    rows = sorted(((x, y - low) for x, y in rows), key=lambda p: (p[1], p[0]))
    top = max(y for _, y in rows) + disc
    with open(path, "w", newline="") as f:
        f.write(f"# The Brazilian specimen of inputs/brazilian.ini: {len(rows)} discs of radius {disc} m on a hexagonal "
                f"lattice within a circle of radius {radius} m, from y = 0 to {top!r} m (tools/brazilian.py "
                "--specimen)\n")
        w = csv.writer(f)
        w.writerow(["id", "x", "y", "radius"])
        for k, (x, y) in enumerate(rows):
            w.writerow([k, repr(x), repr(y), repr(disc)])
    return len(rows)


def curve(run_dir):
    """(d, F, D, t) of a run: the platens' approach [m] and load [N] at each measures.csv row, the specimen's
    diameter (the platens' first distance: they touch it) and the thickness [m]."""
    m = read_csv(os.path.join(run_dir, "measures.csv"))
    require(m, ["height", "width", "wall_syy"])
    t = open_run(run_dir).config.getfloat("material", "thickness", 1.0)
    return m["height"][0] - m["height"], m["wall_syy"] * m["width"] * t, float(m["height"][0]), t


DROP = 0.8  # the specimen has split when the load falls below this fraction of its largest value so far


def peak_row(F):
    """The row of the peak load: the largest load before it first falls below DROP of the largest so far (the
    fragments, pressed on, carry load again later); None when it never falls."""
    top = np.maximum.accumulate(F)
    fallen = np.flatnonzero(F < DROP * top)
    return int(np.argmax(F[:fallen[0]])) if len(fallen) else None


def breaks(run_dir):
    d = read_csv(os.path.join(run_dir, "diagnostics.csv"))
    require(d, ["bonds", "bond_breaks_tension", "bond_breaks_shear"])
    return int(d["bonds"][0]), int(d["bond_breaks_tension"][-1]), int(d["bond_breaks_shear"][-1])


def name_of(sigma):
    return f"sigma_{sigma:g}"


def study_runs(args):
    rondel = args.rondel or os.path.join(HERE, "..", "build", "rondel")
    mpirun = ["mpirun", "--oversubscribe", "-n", str(args.ranks)] if args.ranks > 1 else []
    # The peak comes after an approach proportional to the strength: the scene's steps scaled from its sigma_c.
    config = Config(open(SCENE).read(), SCENE)
    steps, sigma0 = config.getfloat("run", "steps"), config.getfloat("bonds", "sigma_c")
    jobs = [[study.Job(name_of(s), mpirun + [rondel, SCENE, f"--bonds.sigma_c={s!r}",
                                              f"--run.steps={int(math.ceil(steps * max(1.0, s / sigma0)))}"],
                       os.path.join(args.out, name_of(s)))] for s in args.sigma_c]
    failed = study.run_chains(jobs)
    if failed:
        raise CheckFailed("runs failed: " + ", ".join(f"{k} ({v})" for k, v in failed.items()))


def results(args):
    rows = []
    for s in args.sigma_c:
        run = os.path.join(args.out, name_of(s))
        d, F, D, t = curve(run)
        k = peak_row(F)
        if k is None:
            raise CheckFailed(f"{run}: the load never falls below {DROP:g} of its peak: the run ends before the "
                              "specimen splits")
        bonds, tension, shear = breaks(run)
        rows.append(dict(sigma_c=s, peak_F=float(F[k]), d_peak=float(d[k]), sigma_t=2.0 * F[k] / (math.pi * D * t),
                         bonds=bonds, broken_tension=tension, broken_shear=shear, curve=(d, F), run=run))
    first = rows[0]["peak_F"] / rows[0]["sigma_c"]
    for r in rows:
        r["sigma_t_over_sigma_c"] = r["sigma_t"] / r["sigma_c"]
        r["peak_per_sigma_c_ratio"] = (r["peak_F"] / r["sigma_c"]) / first
    return rows


def write(args, rows):
    table = os.path.join(args.out, "brazilian.csv")
    cols = ["sigma_c", "peak_F", "d_peak", "sigma_t", "sigma_t_over_sigma_c", "bonds", "broken_tension",
            "broken_shear", "peak_per_sigma_c_ratio"]
    with open(table, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            w.writerow([repr(r[c]) if isinstance(r[c], float) else r[c] for c in cols])
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.2), layout="constrained")
    for r in rows:
        d, F = r["curve"]
        ax.plot(d * 1e3, F, label=f"sigma_c = {r['sigma_c']:g} Pa: peak {r['peak_F']:.4g} N")
    ax.set_xlabel("platen approach d [mm]")
    ax.set_ylabel("platen load F [N per m of thickness]")
    ax.set_title("Brazilian test of a bonded disc specimen (inputs/brazilian.ini)", fontsize=10)
    ax.legend(fontsize=8)
    written = [table, save_figure(fig, os.path.join(args.out, "brazilian"), args)]
    import picture  # the crack picture of each run: its intact bonds at the end
    for r in rows:
        prefix = os.path.join(args.out, name_of(r["sigma_c"]) + "_bonds")
        picture.main([r["run"], "--kind", "bonds", "--out", prefix, "--width", "5", "--palette",
                      "--title", f"sigma_c = {r['sigma_c']:g} Pa: bonds intact at the end"])
        written.append(prefix + ".png")
    return written


def body(args):
    if args.specimen:
        n = specimen(args.specimen, args.specimen_radius, args.disc_radius)
        print(f"{TOOL}: {n} discs -> {args.specimen}")
        return 0
    study_runs(args)
    rows = results(args)
    for r in rows:
        print(f"{TOOL}: sigma_c {r['sigma_c']:g} Pa: peak F {r['peak_F']:.6g} N at d = {r['d_peak'] * 1e3:.4g} mm, "
              f"sigma_t = {r['sigma_t']:.4g} Pa = {r['sigma_t_over_sigma_c']:.4f} sigma_c; peak/sigma_c "
              f"{r['peak_per_sigma_c_ratio']:.4f} of the first's; {r['broken_tension']} + {r['broken_shear']} of "
              f"{r['bonds']} bonds broken (tension + shear)")
    print(f"{TOOL}: wrote " + ", ".join(write(args, rows)))
    if args.check is not None:
        worst = max(abs(r["peak_per_sigma_c_ratio"] - 1.0) for r in rows)
        if worst > args.check:
            raise CheckFailed(f"the peak load is not linear in sigma_c: peak/sigma_c differs by {worst:.3g} "
                              f"(relative) from the first strength's, above --check {args.check:g}")
        print(f"{TOOL}: check passed: peak/sigma_c within {worst:.3g} of the first strength's (tolerance "
              f"{args.check:g})")
    return 0


def main(argv=None):
    ap = ArgumentParser(TOOL, description="The Brazilian test of a bonded disc specimen.",
                        epilog="See the module docstring (head of tools/brazilian.py).")
    ap.add_argument("out", nargs="?", help="the study's directory (runs, table, figures)")
    ap.add_argument("--sigma-c", type=float, nargs="+", default=[2e4, 4e4], help="tensile strengths [Pa]")
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks per run (default 1)")
    ap.add_argument("--check", type=float, default=None, help="tolerance of the peak's linearity in sigma_c")
    ap.add_argument("--rondel", default=None, help="the rondel executable (default build/rondel)")
    ap.add_argument("--specimen", default=None, metavar="PATH", help="write the specimen's CSV scene and stop")
    ap.add_argument("--specimen-radius", type=float, default=0.025, help="--specimen: its radius RS [m]")
    ap.add_argument("--disc-radius", type=float, default=0.001, help="--specimen: the discs' radius R [m]")
    add_figure_options(ap, dpi=120, no_plot=False)
    args = ap.parse_args(argv)
    check_figure_options(ap, args)
    if not args.specimen and not args.out:
        ap.error("give OUT_DIR (the study) or --specimen PATH")
    if any(not (math.isfinite(s) and s > 0) for s in args.sigma_c):
        ap.error("--sigma-c: every strength a finite number > 0")
    if args.ranks < 1:
        ap.error("--ranks must be >= 1")
    if not (0 < args.disc_radius < args.specimen_radius):
        ap.error("--disc-radius must be > 0 and below --specimen-radius")
    return run_tool(TOOL, body, args)


if __name__ == "__main__":
    sys.exit(main())
