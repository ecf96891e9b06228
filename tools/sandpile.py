#!/usr/bin/python3
"""Pile height against time and angle of repose of the 2D sandpile (inputs/sandpile_*.ini).

  python3 tools/sandpile.py RUN_DIR [RUN_DIR ...] [--out PREFIX] [--label TEXT ...] [--t0 SECONDS]
                            [--floor Y] [--chamber-top Y] [--axis X] [--window 0.2 0.8] [--tol METRES]
                            [--hline HEIGHT LABEL ...]
  python3 tools/sandpile.py --sweep [--out DIR] [--laws jiang_plastic,constant_torque] [--jobs 2] [--ranks 1]
                            [--steps N | LAW=N,...] [--quick] [--collect-only] [--rondel build/rondel]

RUN_DIR: a discharge run (inputs/sandpile_discharge.ini, inputs/sandpile_discharge_constant.ini); one
curve per run (e.g. one per rolling law). Frames: every snapshot_*.h5 (needs position and radius in
output.snapshot_fields) and the newest checkpoint when it is later than the last snapshot.

Time: the discharge stage starts at t = 0 from the filled hopper (scene.type = file), so the tool adds the
time of the state it started from: the newest checkpoint of the run's scene.file (looked up as written,
then beside RUN_DIR), i.e. the 4.5 s of filling; --t0 sets it by hand. Times are then those of the whole
experiment (the gate opens at t0).

Geometry: the floor is the lowest horizontal segment of walls.segments (--floor), the chamber the space
below the next horizontal segment above it (its ceiling, --chamber-top); the outlet axis is the middle of
the floor segment (--axis). Without segments, --floor and --chamber-top are required.

Per frame (PREFIX_height.csv):
  discs_above    discs at or above the chamber's ceiling (still in the hopper or the channel);
  discs_chamber  discs below it; discs_pile: those connected to the floor through touching discs (the
                 test of tools/repose.py, tolerance 0.05 mean radius): the pile, without discs in flight;
  height_top     highest disc top y + R of the pile above the floor: the pile height;
  height_centre  highest disc centre of the pile above the floor (the definition of the published curves
                 as the Lethe example measures them: highest particle centre + 0.57 m);
  height_axis    highest disc top of the pile within one mean diameter of the outlet axis.
Summary (PREFIX_summary.csv, printed): final heights; the settling time, the first frame time after which
height_top stays within --tol (default one mean diameter) of its final value; the height change over the
last --drift seconds (default 2; a pile still creeping shows it); the angle of repose of the final frame:
the method of tools/repose.py on the chamber's discs (surface = highest disc top per x-bin of one mean
diameter; straight lines through the surface points between 20 % and 80 % of the height, --window), left,
right and mean; the last row of diagnostics.csv (kinetic energy) when there is one.

Figures: PREFIX_height.png (height_top, solid, and height_centre, dashed, against time for every run; a
dotted line at each run's t0, where the gate opens; --hline HEIGHT LABEL adds a reference height) and
PREFIX_pile_<k>.png (the final pile of run k with its surface points and flank fits). --format pdf|svg,
--dpi, --no-plot (CSV only).

PREFIX defaults to RUN_DIR/sandpile for one run, ./sandpile for several. Files are read with tools/rondel
(docs/python.md).

--sweep runs the study (tools/sandpile_sweep.py): inputs/sandpile_fill.ini once into DIR/fill, then the discharge of every law of --laws
(jiang_plastic: inputs/sandpile_discharge.ini, constant_torque: inputs/sandpile_discharge_constant.ini) from the
filled hopper (--scene.file=DIR/fill) into DIR/LAW, --jobs at a time on --ranks ranks each, every run with a
checkpoint every --checkpoint-every steps (default 50,000 = 1 s). --steps sets the discharge's length (default
the scene's 750,000 = 15 s; e.g. --steps constant_torque=1750000 runs that law to t = 39.5 s). A run counts as
finished when its summary.txt says 'status: complete' and its newest checkpoint is at the wanted step: it is
reused. A run that is not (stopped by a signal, killed, or finished at fewer steps) is resumed from its newest
checkpoint with rondel --resume (the contact history kept); one without a checkpoint runs afresh, and so does
every discharge after the fill has run (again). Run the same command again to resume or extend a sweep;
--collect-only runs nothing and measures the discharges complete so far. Every complete discharge is measured
as above: DIR/sandpile_height.csv, DIR/sandpile_summary.csv, DIR/sandpile_height.png (all laws on one figure),
DIR/sandpile_pile_LAW.png, and DIR/table.csv (one row per law: final heights, settling, drift, angles of
repose, kinetic energy, the newest checkpoint's step and the wall time of the run's last rondel call).
DIR/sweep.txt names the preset; a sweep into DIR with the other preset is refused. rondel's output goes to
DIR/fill.log and DIR/LAW.log.
--quick: the CI preset (a few seconds per run): 300 discs, 30,000 steps (0.6 s) of filling, 50,000 steps (1 s)
of discharge, a snapshot every 2,500 steps, a checkpoint every 25,000, --drift 0.4.

Exit status: 0 done, 1 a missing or unreadable input or a bad option, 2 no pile could be measured in the final
frame of a run, or a run of the sweep failed (the table holds the others).
"""
import csv
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from rondel import CheckFailed, RondelFileError, UsageError, open_file, open_run, step_of_name  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501
import repose  # noqa: E402

TOOL = "sandpile"
LAW_BLOCK = {"jiang_plastic": "jiang", "jiang_brittle": "jiang", "alonso_marroquin": "wang"}


# ---------------------------------------------------------------------------------------------- input

def segments_of(config):
    """walls.segments of a configuration as an (n, 4) array x1 y1 x2 y2 (velocities dropped)."""
    text = config.get("walls", "segments", "") or ""
    rows = []
    for part in text.split(";"):
        part = part.strip()
        if not part:
            continue
        try:
            v = [float(x) for x in part.split()]
        except ValueError:
            raise RondelFileError(config.source, f"walls.segments entry '{part}' is not numbers") from None
        if len(v) not in (4, 6):
            raise RondelFileError(config.source, f"walls.segments entry '{part}' has {len(v)} numbers (4 or 6)")
        rows.append(v[:4])
    return np.array(rows, dtype=float).reshape(-1, 4)


def geometry(config, floor=None, chamber_top=None, axis=None):
    """(floor y, chamber ceiling y, outlet axis x) from the walls, the options overriding."""
    seg = segments_of(config)
    flat = seg[np.isclose(seg[:, 1], seg[:, 3], rtol=0.0, atol=1e-12)] if len(seg) else seg
    levels = np.unique(flat[:, 1]) if len(flat) else np.zeros(0)
    if floor is None:
        if len(levels) == 0:
            raise UsageError(f"{config.source}: no horizontal walls.segments to take the floor from: give --floor "
                             "and --chamber-top")
        floor = float(levels[0])
    if chamber_top is None:
        above = levels[levels > floor]
        if len(above) == 0:
            raise UsageError(f"{config.source}: no horizontal segment above the floor y = {floor:g} to take the "
                             "chamber's ceiling from: give --chamber-top")
        chamber_top = float(above[0])
    if axis is None:
        lowest = flat[np.isclose(flat[:, 1], floor, rtol=0.0, atol=1e-12)] if len(flat) else flat
        axis = 0.5 * (float(lowest[:, [0, 2]].min()) + float(lowest[:, [0, 2]].max())) if len(lowest) else 0.0
    if chamber_top <= floor:
        raise UsageError(f"the chamber's ceiling y = {chamber_top:g} must lie above the floor y = {floor:g}")
    return float(floor), float(chamber_top), float(axis)


def start_time(run_dir, config):
    """(t0, where it came from): the time of the state a scene.type = file stage started from, else 0."""
    if (config.get("scene", "type", "") or "") != "file":
        return 0.0, "the run starts at t = 0 (not a staged run)"
    given = config.get("scene", "file", "") or ""
    candidates = [given, os.path.join(os.path.dirname(os.path.abspath(run_dir)), os.path.basename(given.rstrip("/")))]
    for path in candidates:
        if not path or not os.path.exists(path):
            continue
        if os.path.isdir(path):
            cps = open_run(path).checkpoint_paths()
            if not cps:
                continue
            path = cps[-1]
        return float(open_file(path).time), f"time of {path}"
    print(f"{TOOL}: warning: {run_dir}: scene.file '{given}' not found: times start at 0 (give --t0)",
          file=sys.stderr)
    return 0.0, f"scene.file '{given}' not found"


def frames(run):
    """Paths of the frames in step order: every snapshot, and the newest checkpoint if it is later."""
    snaps = run.snapshot_paths()
    cps = run.checkpoint_paths()
    out = list(snaps)
    if cps and (not snaps or step_of_name(cps[-1]) > step_of_name(snaps[-1])):
        out.append(cps[-1])
    if not out:
        raise RondelFileError(run.path, "no snapshot_*.h5 or checkpoint_*.h5 (output.snapshot_every writes "
                              "snapshots)")
    return out


def label_of(config):
    """'law (key = value, ...)' of the run's rolling law, from its parameter block."""
    law = config.get("contact", "rolling", "none") or "none"
    block = LAW_BLOCK.get(law, law)
    params = config[block] if block in config else {}
    text = ", ".join(f"{k} = {short(v)}" for k, v in params.items())
    return law + (f" ({text})" if text else "")


def short(value):
    """A number as config.ini writes it (0.90000000000000002) in its shortest form (0.9); text as it is."""
    try:
        return f"{float(value):.10g}"
    except ValueError:
        return value


# -------------------------------------------------------------------------------------------- measure

def pile_mask(pos, radius, floor, chamber_top, touch=0.05):
    """(in the chamber, in the pile): discs below the ceiling; of those, the ones connected to the floor."""
    chamber = pos[:, 1] < chamber_top
    pile = np.zeros(len(radius), dtype=bool)
    if chamber.any():
        tol = touch * float(radius.mean())
        pile[np.nonzero(chamber)[0]] = repose.resting_mask(pos[chamber], radius[chamber], floor, tol)
    return chamber, pile


def heights(pos, radius, floor, chamber_top, axis):
    """The per-frame measures (dict) of one state."""
    chamber, pile = pile_mask(pos, radius, floor, chamber_top)
    d_mean = 2.0 * float(radius.mean())
    out = dict(discs_above=int((~chamber).sum()), discs_chamber=int(chamber.sum()), discs_pile=int(pile.sum()),
               height_top=math.nan, height_centre=math.nan, height_axis=math.nan)
    if pile.any():
        top = pos[pile, 1] + radius[pile]
        out["height_top"] = float(top.max()) - floor
        out["height_centre"] = float(pos[pile, 1].max()) - floor
        near = np.abs(pos[pile, 0] - axis) <= d_mean
        if near.any():
            out["height_axis"] = float(top[near].max()) - floor
    return out


def settling(times, h, tol):
    """(first time after which |h - h_final| <= tol for good, or nan)."""
    ok = np.isfinite(h) & (np.abs(h - h[-1]) <= tol)
    if not ok[-1]:
        return math.nan
    k = len(ok) - 1
    while k > 0 and ok[k - 1]:
        k -= 1
    return float(times[k])


def analyse_run(path, a, index):
    run = open_run(path)
    config = run.config
    floor, chamber_top, axis = geometry(config, a.floor, a.chamber_top, a.axis)
    if a.t0 is not None:
        t0, t0_from = a.t0, "--t0"
    else:
        t0, t0_from = start_time(path, config)
    rows = []
    last = None
    for p in frames(run):
        f = open_file(p)
        pos = np.asarray(f.disc("position"), dtype=float).reshape(-1, 2)
        radius = np.asarray(f.disc("radius"), dtype=float)
        row = dict(step=f.step, time=t0 + f.time)
        row.update(heights(pos, radius, floor, chamber_top, axis))
        rows.append(row)
        last = (pos, radius, f)
    pos, radius, f = last
    chamber = pos[:, 1] < chamber_top
    label = a.label[index] if a.label and index < len(a.label) else label_of(config)
    if not chamber.any():
        raise CheckFailed(f"{path}: no disc in the chamber (below y = {chamber_top:g}) at t = {t0 + f.time:g} s: "
                          "no pile to measure")
    try:
        rep = repose.measure(pos[chamber], radius[chamber], window=tuple(a.window), floor=floor)
    except repose.MeasureError as e:
        raise CheckFailed(f"{path}: final frame (t = {t0 + f.time:g} s): {e}") from None
    times = np.array([r["time"] for r in rows])
    h = np.array([r["height_top"] for r in rows])
    tol = 2.0 * float(radius.mean()) if a.tol is None else a.tol
    t_end = float(times[-1])
    back = np.nonzero(times <= t_end - a.drift + 1e-9)[0]
    drift = float(h[-1] - h[back[-1]]) if len(back) else math.nan
    ke = math.nan
    if os.path.isfile(run.file("diagnostics.csv")):
        d = run.diagnostics()
        if len(d) and "ke_trans" in d.columns:
            ke = float(d["ke_trans"][-1]) + (float(d["ke_rot"][-1]) if "ke_rot" in d.columns else 0.0)
    summary = dict(run=path, label=label, t0=t0, t0_from=t0_from, t_end=t_end, floor=floor, chamber_top=chamber_top,
                   axis=axis, height_top=rows[-1]["height_top"], height_centre=rows[-1]["height_centre"],
                   height_axis=rows[-1]["height_axis"], settled_at=settling(times, h, tol), tol=tol,
                   drift=drift, drift_window=a.drift, discs=len(radius), discs_above=rows[-1]["discs_above"],
                   discs_chamber=rows[-1]["discs_chamber"], discs_pile=rows[-1]["discs_pile"],
                   left=rep["left"]["angle"], right=rep["right"]["angle"], mean=rep["mean"],
                   fit_rms=math.sqrt(0.5 * (rep["left"]["rms"] ** 2 + rep["right"]["rms"] ** 2)),
                   repose_height=rep["height"], ke_end=ke)
    return dict(rows=rows, summary=summary, final=(pos[chamber], radius[chamber], rep), index=index)


# ------------------------------------------------------------------------------------------- outputs

HEIGHT_COLUMNS = ["run", "label", "step", "time", "discs_above", "discs_chamber", "discs_pile", "height_top",
                  "height_centre", "height_axis"]
SUMMARY_COLUMNS = ["run", "label", "t0", "t_end", "height_top", "height_centre", "height_axis", "settled_at", "tol",
                   "drift", "drift_window", "discs", "discs_above", "discs_chamber", "discs_pile", "left", "right",
                   "mean", "fit_rms", "repose_height", "ke_end", "floor", "chamber_top", "axis", "t0_from"]


def fmt(v):
    if isinstance(v, float):
        return "" if math.isnan(v) else repr(v)
    return v


def write_csvs(prefix, results):
    with open(prefix + "_height.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(HEIGHT_COLUMNS)
        for r in results:
            for row in r["rows"]:
                w.writerow([fmt(r["summary"]["run"]), r["summary"]["label"]] +
                           [fmt(row[c]) for c in HEIGHT_COLUMNS[2:]])
    with open(prefix + "_summary.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(SUMMARY_COLUMNS)
        for r in results:
            w.writerow([fmt(r["summary"][c]) for c in SUMMARY_COLUMNS])


def plot_heights(prefix, results, a):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8.0, 4.5))
    for r in results:
        t = np.array([row["time"] for row in r["rows"]])
        top = np.array([row["height_top"] for row in r["rows"]])
        centre = np.array([row["height_centre"] for row in r["rows"]])
        s = r["summary"]
        line, = ax.plot(t, top, "-", lw=1.5, label=f"{s['label']}: highest disc top")
        ax.plot(t, centre, "--", lw=1.0, color=line.get_color(), label=f"{s['label']}: highest disc centre")
        ax.axvline(s["t0"], color=line.get_color(), lw=0.7, ls=":")
    for k, (value, text) in enumerate(a.hline or []):
        ax.axhline(value, color=f"{0.25 + 0.2 * (k % 3):.2f}", lw=0.9, ls=(0, (1, 2 + k)), label=text)
    ax.set_xlabel("time since the start of filling [s] (dotted: the gate opens)")
    ax.set_ylabel("pile height above the floor [m]")
    tops = [row[k] for r in results for row in r["rows"] for k in ("height_top", "height_centre")]
    tops = [v for v in tops if math.isfinite(v)] + [v for v, _ in (a.hline or [])]
    ax.set_ylim(0.0, 1.12 * max(tops) if tops else 1.0)  # room above the highest curve and reference line
    ax.grid(True, lw=0.3)
    ax.set_title("2D sandpile: height of the pile in the chamber against time", fontsize=10)
    ax.legend(fontsize=7, loc="lower right")
    return save_figure(fig, prefix + "_height", a)


def print_summary(s):
    print(f"{s['run']}: {s['label']}")
    print(f"  t0 = {s['t0']:g} s ({s['t0_from']}); last frame t = {s['t_end']:g} s; floor y = {s['floor']:g} m, "
          f"chamber below y = {s['chamber_top']:g} m")
    print(f"  discs: {s['discs']} ({s['discs_above']} above the chamber, {s['discs_chamber']} in it, "
          f"{s['discs_pile']} in the pile)")
    print(f"  height: top {s['height_top']:.4f} m, centre {s['height_centre']:.4f} m, on the axis "
          f"{s['height_axis']:.4f} m; change over the last {s['drift_window']:g} s {s['drift'] * 1e3:+.1f} mm")
    if math.isfinite(s["settled_at"]) and s["settled_at"] <= s["t_end"] - s["drift_window"] + 1e-9:
        settled = f"within {s['tol'] * 1e3:.1f} mm of its final value from t = {s['settled_at']:g} s"
    elif math.isfinite(s["settled_at"]):
        settled = (f"not settled: within {s['tol'] * 1e3:.1f} mm of its final value only from t = "
                   f"{s['settled_at']:g} s, less than {s['drift_window']:g} s before the end")
    else:
        settled = "not settled"
    print(f"  settling: {settled}")
    print(f"  angle of repose: left {s['left']:.2f} deg, right {s['right']:.2f} deg, mean {s['mean']:.2f} deg "
          f"(fit rms {s['fit_rms'] * 1e3:.2f} mm)")
    if math.isfinite(s["ke_end"]):
        print(f"  kinetic energy at the end (diagnostics.csv): {s['ke_end']:.3g} J")


def write_outputs(prefix, results, a, names=None):
    """PREFIX_height.csv, PREFIX_summary.csv and the figures (PREFIX_height, PREFIX_pile_<name>, name = the run's
    index unless NAMES gives one per result); prints the summaries."""
    os.makedirs(os.path.dirname(os.path.abspath(prefix)), exist_ok=True)
    write_csvs(prefix, results)
    figures = []
    if not a.no_plot:
        figures.append(plot_heights(prefix, results, a))
        for k, r in enumerate(results):
            pos, radius, rep = r["final"]
            name = names[k] if names else r["index"]
            figures.append(repose.plot(f"{prefix}_pile_{name}", pos, radius, rep, r["summary"]["label"], a))
    for r in results:
        print_summary(r["summary"])
    print(f"wrote {prefix}_height.csv, {prefix}_summary.csv" + "".join(", " + f for f in figures))


def analyse(a):
    if a.label and len(a.label) != len(a.runs):
        raise UsageError(f"--label: {len(a.label)} labels for {len(a.runs)} runs")
    for path in a.runs:
        if not os.path.isdir(path):
            raise RondelFileError(path, "no such run directory")
    if a.out is None:
        a.out = os.path.join(a.runs[0], "sandpile") if len(a.runs) == 1 else "sandpile"
    results = [analyse_run(p, a, k) for k, p in enumerate(a.runs)]
    write_outputs(a.out, results, a)
    return 0


# --------------------------------------------------------------------------------------------- sweep

DISCHARGE = {"jiang_plastic": "sandpile_discharge.ini", "constant_torque": "sandpile_discharge_constant.ini"}
FILL = "sandpile_fill.ini"
CHECKPOINT_EVERY = 50000  # 1 s of simulated time at dt = 2e-5 s
# --quick: 300 discs (250 + 50, the scene's fractions) in the scene's region, 0.6 s of filling, 1 s of discharge,
# a snapshot every 0.05 s, a checkpoint half way through the discharge; a few seconds of computing per run.
QUICK = dict(count=300, fill_steps=30000, steps=50000, snapshot_every=2500, checkpoint_every=25000, drift=0.4)
TABLE_COLUMNS = ["law", "label", "steps", "t0", "t_end", "height_top", "height_centre", "height_axis", "settled_at",
                 "drift", "drift_window", "left", "right", "mean", "discs", "discs_above", "discs_pile", "ke_end",
                 "wall_s", "run"]


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("runs", nargs="*", metavar="RUN_DIR", help="discharge run directories (one curve each)")
    ap.add_argument("--out", default=None,
                    help="output prefix (default RUN_DIR/sandpile, or ./sandpile); with --sweep the sweep's directory "
                         "(default rondel-output/sandpile_sweep)")
    ap.add_argument("--label", nargs="+", default=None, help="one label per run (default: the rolling law)")
    ap.add_argument("--t0", type=float, default=None,
                    help="time [s] added to the run's times (default: the time of the scene.file state)")
    ap.add_argument("--floor", type=float, default=None, help="floor y [m] (default: lowest horizontal segment)")
    ap.add_argument("--chamber-top", type=float, default=None,
                    help="chamber ceiling y [m] (default: the next horizontal segment above the floor)")
    ap.add_argument("--axis", type=float, default=None, help="outlet axis x [m] (default: middle of the floor)")
    ap.add_argument("--window", type=float, nargs=2, default=(0.2, 0.8), metavar=("LO", "HI"),
                    help="flank fit window, fractions of the pile height (default 0.2 0.8)")
    ap.add_argument("--tol", type=float, default=None,
                    help="settling tolerance on the height [m] (default: the mean diameter)")
    ap.add_argument("--drift", type=float, default=None,
                    help="window [s] of the final height change (default 2; 0.4 with --quick)")
    ap.add_argument("--hline", nargs=2, action="append", metavar=("HEIGHT", "LABEL"), default=None,
                    help="a reference height [m] drawn across the height plot (repeatable), e.g. a published value")
    g = ap.add_argument_group("sweep (--sweep)")
    g.add_argument("--sweep", action="store_true", help="run the fill and the discharge of every law, then measure")
    g.add_argument("--laws", default=",".join(DISCHARGE), help="rolling laws, comma-separated (default: both)")
    g.add_argument("--jobs", type=int, default=2, help="discharge runs at a time (default 2)")
    g.add_argument("--ranks", type=int, default=1, help="MPI ranks per run (default 1)")
    g.add_argument("--steps", default="",
                   help="discharge steps: N for every law, or LAW=N,... (default: the scene's run.steps)")
    g.add_argument("--checkpoint-every", type=int, default=None,
                   help=f"output.checkpoint_every of every run (default {CHECKPOINT_EVERY}, "
                        f"{QUICK['checkpoint_every']} with --quick)")
    g.add_argument("--quick", action="store_true",
                   help="tiny preset for CI: 300 discs, 0.6 s of filling, 1 s of discharge")
    g.add_argument("--collect-only", action="store_true",
                   help="run nothing: measure the discharges complete so far (e.g. beside a running sweep)")
    g.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"),
                   help="the rondel executable (default: build/rondel of this checkout)")
    g.add_argument("--mpiexec", default="mpirun", help="MPI launcher for --ranks > 1 (default mpirun)")
    g.add_argument("--inputs", default=os.path.join(ROOT, "inputs"),
                   help=f"folder of {FILL} and the discharge scenes (default: inputs/ of this checkout)")
    g.add_argument("--rondel-arg", action="append", default=[], metavar="--SECTION.KEY=VALUE",
                   help="an extra option of every run (repeatable), e.g. --rondel-arg=--neighbour.skin=0.003")
    add_figure_options(ap, dpi=150)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    if a.drift is None:
        a.drift = QUICK["drift"] if a.quick else 2.0
    if a.checkpoint_every is None:
        a.checkpoint_every = QUICK["checkpoint_every"] if a.quick else CHECKPOINT_EVERY
    if a.drift <= 0:
        ap.error(f"--drift {a.drift:g} must be > 0")
    if a.tol is not None and a.tol <= 0:
        ap.error(f"--tol {a.tol:g} must be > 0")
    try:
        a.hline = [(float(v), text) for v, text in (a.hline or [])]
    except ValueError:
        ap.error(f"--hline: the height must be a number (got {a.hline})")
    lo, hi = a.window
    if not 0.0 <= lo < hi <= 1.0:
        ap.error(f"--window {lo:g} {hi:g}: need 0 <= LO < HI <= 1")
    if a.sweep:
        if a.runs or a.label or a.t0 is not None:
            ap.error("--sweep takes no RUN_DIR, --label or --t0 (the runs are its own: --out DIR)")
        a.out = a.out or os.path.join("rondel-output", "sandpile_sweep")
        from sandpile_sweep import sweep  # here: it imports this file's analysis
        return run_tool(TOOL, sweep, a)
    if not a.runs:
        ap.error("give a RUN_DIR, or --sweep")
    if a.quick or a.collect_only:
        ap.error("--quick and --collect-only go with --sweep")
    return run_tool(TOOL, analyse, a)


if __name__ == "__main__":
    sys.exit(main())
