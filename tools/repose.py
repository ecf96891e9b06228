#!/usr/bin/python3
"""Angle of repose of a disc heap from a Rondel run (inputs/pile.ini).

  python3 tools/repose.py RUN_DIR [--out PREFIX] [--bin W] [--window 0.2 0.8] [--floor Y]
  python3 tools/repose.py FILE.h5 [...]          (a checkpoint or snapshot with position and radius)
  python3 tools/repose.py RUN_DIR/final.csv [...] (the same as RUN_DIR)

Input: RUN_DIR/final.csv (positions, ascending gid) with the radii from the newest checkpoint_*.h5 or
snapshot_*.h5 in RUN_DIR (/discs/radius, ascending gid; the gids are checked when the file has them);
without final.csv, positions and radii both come from the newest .h5 file (largest step).

Method:
  1. Resting discs: those connected to the floor through a chain of touching discs (centre distance
     < R1 + R2 + tol, disc-floor gap < tol; tol = --touch x the mean radius, default 0.05). Discs in
     flight or left in the hopper are dropped. The floor is --floor, default the lowest disc bottom.
  2. Free surface: in x-bins of width --bin (default the mean diameter), the highest disc top y + R;
     the surface point is (x of that disc's centre, y + R).
  3. Bins whose surface is less than --min-height above the floor are dropped (discs that rolled or
     bounced away from the heap; default 1.05 x the largest diameter, just above one layer of discs).
     The heap is the run of kept bins around the highest one (the apex; gaps of up to --gap empty bins
     are bridged); its height H = apex - floor. A heap lower than 10 mean diameters gets a warning.
  4. Each flank (left and right of the apex): least-squares line through the surface points whose
     height above the floor lies in [lo H, hi H] (--window, default 0.2 0.8: leaves out the toe and the
     rounded apex). Angle = atan(|slope|); residual = RMS of the vertical distances to the line.

Writes PREFIX.png (discs, surface points, fitted lines; --format pdf|svg, --dpi; cropped to the heap),
PREFIX.csv (surface profile, one row per bin), PREFIX_angles.csv (left, right, mean) and prints the
angles. PREFIX defaults to RUN_DIR/repose. Files are read with tools/rondel (docs/python.md).
Exit status: 0 done, 1 a missing or unreadable input or a bad option, 2 no heap could be measured.
"""
import csv
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import CheckFailed, RondelFileError, open_file, open_run, read_csv, require  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "repose"
InputError = RondelFileError  # a missing or unreadable input file (exit status 1)


class MeasureError(CheckFailed):
    """The discs do not form a measurable heap (exit status 2)."""


# ---------------------------------------------------------------------------------------------- input

def newest_h5(run_dir):
    """The checkpoint or snapshot with the largest step in RUN_DIR (a checkpoint wins a tie), or None."""
    run = open_run(run_dir)
    files = [(p, 1) for p in run.checkpoint_paths()] + [(p, 0) for p in run.snapshot_paths()]
    if not files:
        return None
    from rondel import step_of_name
    return max(files, key=lambda pk: (step_of_name(pk[0]), pk[1]))[0]


def read_h5(path):
    """(gid or None, positions (n, 2) or None, radii (n)) and the file's title from a Rondel .h5 file."""
    f = open_file(path)
    radius = np.asarray(f.disc("radius"), dtype=float)
    pos = np.asarray(f.discs["position"], dtype=float).reshape(-1, 2) if "position" in f.discs else None
    gid = np.asarray(f.discs["gid"], dtype=np.int64) if "gid" in f.discs else None
    return gid, pos, radius, f.title().split(", step")[0]


def read_final_csv(path):
    """(gid, positions (n, 2)) from a final.csv (hexadecimal or decimal floats; extra columns ignored)."""
    t = read_csv(path)
    require(t, ("gid", "x", "y"), "a Rondel final.csv")
    if len(t) == 0:
        raise InputError(path, "no disc rows")
    return t["gid"].astype(np.int64), np.column_stack([t["x"], t["y"]]).astype(float)


def load(path):
    """Positions (n, 2), radii (n), a description of the sources and a scene title, from a run directory or
    a .h5 file (or a final.csv: its directory)."""
    if not os.path.exists(path):
        raise InputError(path, "no such run directory or file")
    if os.path.isfile(path) and os.path.basename(path) == "final.csv":
        path = os.path.dirname(path) or "."
    if os.path.isfile(path):
        gid, pos, radius, scene = read_h5(path)
        if pos is None:
            raise InputError(path, "no /discs/position dataset")
        return pos, radius, path, scene
    final = os.path.join(path, "final.csv")
    h5 = newest_h5(path)
    if h5 is None:
        raise InputError(path, "no checkpoint_*.h5 or snapshot_*.h5 (the radii are read from one; "
                         "output.checkpoint_at_end = true writes one at the end)")
    gid_h5, pos_h5, radius, scene = read_h5(h5)
    if not os.path.isfile(final):
        if pos_h5 is None:
            raise InputError(path, f"no final.csv, and {h5} has no /discs/position")
        return pos_h5, radius, h5, scene
    gid, pos = read_final_csv(final)
    if "radius" in read_csv(final):
        radius = np.asarray(read_csv(final)["radius"], dtype=float)
    if len(gid) != len(radius):
        raise InputError(final, f"has {len(gid)} discs but {h5} has {len(radius)}")
    if gid_h5 is not None and not np.array_equal(gid, gid_h5):
        raise InputError(final, f"lists other gids than {h5}")
    return pos, radius, f"{final} + radii from {os.path.basename(h5)}", scene


# -------------------------------------------------------------------------------------------- measure

def resting_mask(pos, radius, floor, tol):
    """Discs connected to the floor through chains of touching discs (cell-list breadth-first search)."""
    n = len(radius)
    cell = 2.0 * radius.max() + tol
    ij = np.floor((pos - pos.min(axis=0)) / cell).astype(np.int64)
    cells = {}
    for k, key in enumerate(map(tuple, ij)):
        cells.setdefault(key, []).append(k)
    seen = np.zeros(n, dtype=bool)
    stack = list(np.nonzero(pos[:, 1] - radius <= floor + tol)[0])
    seen[stack] = True
    while stack:
        k = stack.pop()
        cx, cy = ij[k]
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for m in cells.get((cx + dx, cy + dy), ()):
                    if not seen[m]:
                        d = math.hypot(pos[m, 0] - pos[k, 0], pos[m, 1] - pos[k, 1])
                        if d < radius[m] + radius[k] + tol:
                            seen[m] = True
                            stack.append(m)
    return seen


def surface_profile(pos, radius, width, x0=None):
    """Per x-bin of WIDTH (starting at x0): (x_lo, x_top, y_top, index of the top disc); empty bins NaN."""
    x = pos[:, 0]
    top = pos[:, 1] + radius
    x0 = x.min() if x0 is None else x0
    b = np.floor((x - x0) / width).astype(np.int64)
    nb = int(b.max()) + 1
    y_top = np.full(nb, np.nan)
    x_top = np.full(nb, np.nan)
    who = np.full(nb, -1, dtype=np.int64)
    order = np.argsort(top)  # the last write per bin is the highest top
    y_top[b[order]] = top[order]
    x_top[b[order]] = x[order]
    who[b[order]] = order
    x_lo = x0 + width * np.arange(nb)
    return x_lo, x_top, y_top, who


def fit_line(x, y):
    """Least-squares y = a + b x: (a, b, rms of vertical residuals)."""
    A = np.column_stack([np.ones_like(x), x])
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    res = y - A @ coef
    return float(coef[0]), float(coef[1]), float(np.sqrt(np.mean(res ** 2)))


def measure(pos, radius, bin_width=None, window=(0.2, 0.8), floor=None, min_height=None, touch=0.05,
            gap=1, min_points=3):
    """Angle of repose. Returns a dict (angles in degrees, lengths in m) with the profile and the fits."""
    pos = np.asarray(pos, dtype=float)
    radius = np.asarray(radius, dtype=float)
    if pos.ndim != 2 or pos.shape[1] != 2 or len(pos) != len(radius) or len(radius) == 0:
        raise MeasureError("positions (n, 2) and radii (n) of at least one disc are needed")
    lo, hi = window
    if not 0.0 <= lo < hi <= 1.0:
        raise MeasureError(f"height window [{lo}, {hi}] must satisfy 0 <= lo < hi <= 1")
    d_mean = 2.0 * float(radius.mean())
    width = d_mean if bin_width is None else float(bin_width)
    min_h = 2.1 * float(radius.max()) if min_height is None else float(min_height)
    floor = float((pos[:, 1] - radius).min()) if floor is None else float(floor)
    tol = touch * 0.5 * d_mean

    resting = resting_mask(pos, radius, floor, tol)
    if not resting.any():
        raise MeasureError("no disc touches the floor")
    x_lo, x_top, y_top, who = surface_profile(pos[resting], radius[resting], width)
    who = np.where(who >= 0, np.nonzero(resting)[0][np.maximum(who, 0)], -1)
    height = y_top - floor
    kept = np.isfinite(height) & (height >= min_h)
    if not kept.any():
        raise MeasureError(f"no bin has its surface {min_h:.4g} m or more above the floor: no heap")

    apex = int(np.nanargmax(np.where(kept, height, -np.inf)))
    H = float(height[apex])
    # the heap: kept bins around the apex, bridging gaps of up to GAP bins
    heap = np.zeros(len(kept), dtype=bool)
    heap[apex] = True
    for step in (-1, 1):
        k, missing = apex + step, 0
        while 0 <= k < len(kept):
            if kept[k]:
                heap[k] = True
                missing = 0
            else:
                missing += 1
                if missing > gap:
                    break
            k += step

    x_apex = float(x_top[apex])
    in_window = heap & (height >= lo * H) & (height <= hi * H)
    sides = {}
    for side, sel in (("left", in_window & (np.arange(len(kept)) < apex)),
                      ("right", in_window & (np.arange(len(kept)) > apex))):
        xs, ys = x_top[sel], y_top[sel]
        if len(xs) < min_points:
            raise MeasureError(f"{side} flank: {len(xs)} surface points in the height window "
                               f"[{lo:g}, {hi:g}] x {H:.4g} m (need {min_points}); try a smaller --bin")
        a, b, rms = fit_line(xs, ys)
        sides[side] = dict(angle=math.degrees(math.atan(abs(b))), slope=b, intercept=a, rms=rms,
                           points=int(len(xs)), x_from=float(xs.min()), x_to=float(xs.max()),
                           sign_ok=(b > 0) if side == "left" else (b < 0))
    mean = 0.5 * (sides["left"]["angle"] + sides["right"]["angle"])
    role = np.full(len(kept), "", dtype=object)
    role[kept] = "kept"
    role[heap] = "heap"
    role[in_window & (np.arange(len(kept)) < apex)] = "left"
    role[in_window & (np.arange(len(kept)) > apex)] = "right"
    role[apex] = "apex"
    return dict(left=sides["left"], right=sides["right"], mean=mean, height=H, floor=floor, x_apex=x_apex,
                y_apex=float(y_top[apex]), bin=width, window=(lo, hi), min_height=min_h, resting=resting,
                profile=dict(x_lo=x_lo, x_top=x_top, y_top=y_top, height=height, role=role, disc=who),
                discs=len(radius), discs_resting=int(resting.sum()),
                discs_heap=int(np.isin(np.floor((pos[resting, 0] - x_lo[0]) / width).astype(int),
                                       np.nonzero(heap)[0]).sum()))


# ------------------------------------------------------------------------------------------- outputs

def write_profile(path, r):
    p = r["profile"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["bin", "x_lo", "x_hi", "x_top", "surface_y", "height", "role"])
        for k in range(len(p["x_lo"])):
            empty = not np.isfinite(p["y_top"][k])
            w.writerow([k, repr(float(p["x_lo"][k])), repr(float(p["x_lo"][k] + r["bin"])),
                        "" if empty else repr(float(p["x_top"][k])),
                        "" if empty else repr(float(p["y_top"][k])),
                        "" if empty else repr(float(p["height"][k])), p["role"][k] or "dropped"])


def write_angles(path, r, source):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["side", "angle_deg", "slope", "rms_residual_m", "points", "x_from", "x_to",
                    "heap_height_m", "window_lo", "window_hi", "bin_m", "source"])
        for side in ("left", "right"):
            s = r[side]
            w.writerow([side, f"{s['angle']:.4f}", repr(s["slope"]), repr(s["rms"]), s["points"],
                        repr(s["x_from"]), repr(s["x_to"]), repr(r["height"]), r["window"][0], r["window"][1],
                        repr(r["bin"]), source])
        rms = math.sqrt(0.5 * (r["left"]["rms"] ** 2 + r["right"]["rms"] ** 2))
        w.writerow(["mean", f"{r['mean']:.4f}", "", repr(rms), r["left"]["points"] + r["right"]["points"], "", "",
                    repr(r["height"]), r["window"][0], r["window"][1], repr(r["bin"]), source])


def plot(stem, pos, radius, r, title, a):
    plt = pyplot()
    from matplotlib.collections import EllipseCollection

    p = r["profile"]
    heapbins = np.isin(p["role"], ["heap", "left", "right", "apex"])
    xs = p["x_lo"][heapbins]
    x_min, x_max = xs.min() - 4 * r["bin"], xs.max() + 5 * r["bin"]
    y_max = r["y_apex"] + 0.25 * r["height"]
    aspect = (x_max - x_min) / (y_max - r["floor"])
    wfig = 12.0
    hfig = max(2.5, min(8.0, wfig / aspect + 0.8))
    fig, ax = plt.subplots(figsize=(wfig, hfig))
    show = (pos[:, 0] > x_min - 0.01) & (pos[:, 0] < x_max + 0.01) & (pos[:, 1] < y_max + 0.01)
    colours = np.where(r["resting"][show], "#9db8d2", "#e0a0a0")
    ax.add_collection(EllipseCollection(2 * radius[show], 2 * radius[show], 0, units="xy", offsets=pos[show],
                                        offset_transform=ax.transData, facecolors=colours, edgecolors="none"))
    ok = np.isfinite(p["y_top"])
    ax.plot(p["x_top"][ok & heapbins], p["y_top"][ok & heapbins], ".", color="k", ms=3, label="surface (top per bin)")
    for side, colour in (("left", "tab:red"), ("right", "tab:green")):
        s = r[side]
        sel = p["role"] == side
        ax.plot(p["x_top"][sel], p["y_top"][sel], "o", mfc="none", color=colour, ms=4)
        xx = np.array([s["x_from"], s["x_to"]])
        xx = xx + np.array([-1, 1]) * 0.15 * (s["x_to"] - s["x_from"])
        ax.plot(xx, s["intercept"] + s["slope"] * xx, "-", color=colour, lw=1.5,
                label=f"{side}: {s['angle']:.1f} deg (rms {s['rms'] * 1e3:.2f} mm, {s['points']} pts)")
    for f in r["window"]:
        ax.axhline(r["floor"] + f * r["height"], color="0.5", lw=0.6, ls=":")
    ax.axhline(r["floor"], color="k", lw=0.8)
    ax.set_xlim(x_min, x_max)
    ax.set_ylim(r["floor"] - 0.03 * r["height"], y_max)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"Angle of repose, {title}: {r['mean']:.1f} deg (mean of left and right flank), "
                 f"window {r['window'][0]:g}-{r['window'][1]:g} H, H = {r['height'] * 1e3:.1f} mm", fontsize=9)
    ax.legend(loc="upper right", fontsize=7, framealpha=0.9)
    return save_figure(fig, stem, a)  # cropped to the heap: bbox_inches='tight' drops the empty band


def analyse(a):
    pos, radius, source, scene = load(a.run)
    if a.out is None:
        a.out = os.path.join(a.run, "repose") if os.path.isdir(a.run) else re.sub(r"\.h5$", "", a.run) + "_repose"
    try:
        r = measure(pos, radius, a.bin, tuple(a.window), a.floor, a.min_height, a.touch, a.gap)
    except MeasureError as e:
        raise MeasureError(f"{a.run}: {e}") from None
    outdir = os.path.dirname(os.path.abspath(a.out))
    os.makedirs(outdir, exist_ok=True)
    write_profile(a.out + ".csv", r)
    write_angles(a.out + "_angles.csv", r, source)
    figure = None
    if not a.no_plot:
        figure = plot(a.out, pos, radius, r, a.title or scene or os.path.basename(os.path.normpath(a.run)), a)

    print(f"source: {source}")
    print(f"discs: {r['discs']} ({r['discs_resting']} resting on the floor, {r['discs_heap']} in the heap's bins); "
          f"bin {r['bin'] * 1e3:.3f} mm; floor y = {r['floor']:.6g} m")
    print(f"heap: apex x = {r['x_apex']:.4f} m, height H = {r['height'] * 1e3:.2f} mm; fit window "
          f"{r['window'][0]:g}-{r['window'][1]:g} H")
    for side in ("left", "right"):
        s = r[side]
        warn = "" if s["sign_ok"] else "  (slope has the wrong sign: not a heap flank)"
        print(f"{side:>5}: {s['angle']:6.2f} deg  ({s['points']} points, x {s['x_from']:.4f} to {s['x_to']:.4f} m, "
              f"rms residual {s['rms'] * 1e3:.3f} mm){warn}")
    print(f" mean: {r['mean']:6.2f} deg")
    if r["height"] < 20.0 * float(radius.mean()):
        print(f"warning: the heap is only {r['height'] / (2.0 * float(radius.mean())):.1f} mean diameters high: "
              "the angles are rough", file=sys.stderr)
    print(f"wrote {a.out}.csv, {a.out}_angles.csv" + (f", {figure}" if figure else ""))
    return 0


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("run", help="run directory (final.csv + a checkpoint or snapshot) or a .h5 file")
    ap.add_argument("--out", default=None, help="output prefix (default: RUN_DIR/repose, or FILE without .h5)")
    ap.add_argument("--bin", type=float, default=None, help="x-bin width [m] (default: the mean diameter)")
    ap.add_argument("--window", type=float, nargs=2, default=(0.2, 0.8), metavar=("LO", "HI"),
                    help="fit window, fractions of the heap height above the floor (default 0.2 0.8)")
    ap.add_argument("--floor", type=float, default=None, help="floor height [m] (default: lowest disc bottom)")
    ap.add_argument("--min-height", type=float, default=None,
                    help="drop bins whose surface is lower above the floor [m] (default: 1.05 x the largest "
                         "diameter)")
    ap.add_argument("--touch", type=float, default=0.05,
                    help="contact tolerance for the resting test, x mean radius (default 0.05)")
    ap.add_argument("--gap", type=int, default=1, help="empty bins bridged inside the heap (default 1)")
    ap.add_argument("--title", default=None, help="what the run is, in the title (default: scene and laws)")
    add_figure_options(ap, dpi=150)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    return run_tool(TOOL, analyse, a)


if __name__ == "__main__":
    sys.exit(main())
