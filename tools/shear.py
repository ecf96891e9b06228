#!/usr/bin/python3
"""Plane shear post-processing for Rondel runs (periodic in x, bottom wall and servo top wall shearing in +x).

1. Time series from RUN_DIR/measures.csv, against the shear strain gamma = shear_disp / H0 (H0 = the first
   row's height, the wall gap):
     stress ratio  mu = wall_tau / wall_syy   (shear over normal stress on the top wall; NaN where wall_syy <= 0)
     dilation      (height - H0) / H0         (and void_ratio when the column exists)
   Steady-state stress ratio = mean and (population) standard deviation of mu over gamma >= GMIN
   (default GMIN = half of the last row's gamma; --window GMIN sets it).
   Writes PREFIX_series.png (mu; dilation and void ratio), PREFIX_series.csv, PREFIX_summary.csv.

2. Profiles across the gap from snapshot_*.h5 files (FORMAT.md; needs /discs/position, velocity, omega and
   radius, i.e. output.snapshot_fields = position velocity omega radius [flags]). Snapshots used: those with
   time >= --from-time, or the last --last K; by default those inside the steady window of part 1 (time at or
   after the first measures row with gamma >= GMIN), or all of them without measures. Each snapshot's gap runs
   from the bottom wall (y_b) to the top wall (y_t), H = y_t - y_b, taken from /walls/p0 (rows: walls.lines,
   walls.segments, then walls.box in order). Discs are binned by centre on y' = (y - y_b) / H in N equal bins
   (default N = round(mean H / (2 mean diameter)), about two diameters a bin; --bins N). Per bin, pooled over
   the snapshots (every disc of every snapshot counts once):
     vx / V             mean of (vx - vx_bottom_wall) / V, V = vx_top - vx_bottom of /walls/velocity
                        (the bottom wall is fixed: V is the top wall's speed), or --velocity V
     spin               mean of omega d / V, d = the mean diameter of the discs used (counter-clockwise +);
                        a simple shear flow has omega = -0.5 dvx/dy: the CSV column spin_continuum is
                        -0.5 (d / H) d(vx/V)/dy' for comparison (-0.5 d / H for a uniform shear)
     solid fraction     simple centre binning: the area pi R^2 of the discs whose centre lies in the bin over
                        the bin area Lx H / N (Lx = xhi - xlo of [domain]), averaged over the snapshots; a disc
                        cut by a bin edge counts whole in its centre's bin, so expect scatter of a few %
                        with bins of 2 diameters. solid_fraction_all counts every disc.
   Only free discs by default: discs with flags bit 1 (value 2: glued to a rough wall) are left out when
   /discs/flags exists (--all-discs keeps them); the solid_fraction_all column counts them anyway.
   Shear band width: the local shear rate g(y') = |d(vx/V)/dy'| per bin (numpy.gradient of the bin means of
   vx/V against the bin means of y', column y_discs_over_H, so that a bin whose discs are off its centre does
   not bias it); the band is the contiguous run of bins around the largest g where g >= max(g)/2, its ends
   placed by linear interpolation of g between bins (at the wall when the run reaches the first or last bin).
   Its width is printed in mean diameters (a uniform shear gives the whole gap, H / d).
   Writes PREFIX_profiles.png (three panels against y/H) and PREFIX_profiles.csv; the band goes in the summary.

  python3 tools/shear.py RUN_DIR --out PREFIX [--window GMIN] [--bins N] [--last K | --from-time T]
  python3 tools/shear.py RUN_DIR/measures.csv snapshot_*.h5 --out PREFIX ...   (explicit files)
Without snapshots only part 1 runs (a message says so); without measures.csv in RUN_DIR the tool exits 1.
Figures: --format png|pdf|svg (PREFIX_series.<format>, PREFIX_profiles.<format>), --dpi; --no-plot for CSVs only.
Part 2 is in tools/shear_profiles.py. Files are read with tools/rondel (docs/python.md). Exit status: 0 done, 1 bad input or usage (one line on stderr).
Needs numpy, h5py (for part 2) and matplotlib: Debian's /usr/bin/python3.
"""
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import RondelError, open_run, read_csv  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501
from shear_profiles import (ToolError, plot_profiles, profiles, read_snapshot, select_snapshots,  # noqa: E402,F401
                            shear_band, write_profiles)  # shear_band: tests/tools/test_shear_tool.py

TOOL = "shear"




# ----------------------------------------------------------------------------------------------------------
# Part 1: time series


def read_measures(path):
    """Columns of a measures.csv as a dict of numpy arrays (empty fields read as NaN)."""
    if not os.path.isfile(path):
        raise ToolError(f"'{path}': no such file (a Rondel run directory holds measures.csv)")
    m = read_csv(path)
    if len(m) == 0:
        raise ToolError(f"'{path}': no data rows")
    return {h: np.asarray(m[h], dtype=float) for h in m.columns}


REQUIRED = ("time", "height", "wall_syy", "wall_tau", "shear_disp")


def series(m):
    """gamma, mu, dilation (and void ratio) of a plane shear measures table (dict of columns)."""
    missing = [c for c in REQUIRED if c not in m]
    if missing:
        raise ToolError("measures.csv lacks the column(s) " + ", ".join(missing) +
                        " (is this a plane shear run? walls.control with 'top:shear:V')")
    h0 = float(m["height"][0])
    if not h0 > 0:
        raise ToolError(f"the first height is {h0}: cannot normalise the shear displacement")
    syy = m["wall_syy"]
    mu = np.full(syy.shape, np.nan)
    ok = syy > 0
    mu[ok] = m["wall_tau"][ok] / syy[ok]
    out = {
        "step": m.get("step", np.arange(len(syy), dtype=float)),
        "time": m["time"],
        "gamma": m["shear_disp"] / h0,
        "mu": mu,
        "dilation": (m["height"] - h0) / h0,
        "height": m["height"],
        "wall_syy": syy,
        "wall_tau": m["wall_tau"],
        "void_ratio": m.get("void_ratio"),
        "H0": h0,
    }
    return out


def steady_state(gamma, mu, gmin=None):
    """Mean and std of mu over gamma >= gmin (default: half of the last gamma)."""
    gamma = np.asarray(gamma, dtype=float)
    mu = np.asarray(mu, dtype=float)
    g_last = float(gamma[-1])
    if gmin is None:
        gmin = 0.5 * g_last
    sel = (gamma >= gmin) & np.isfinite(mu)
    n = int(np.count_nonzero(sel))
    if n == 0:
        raise ToolError(f"no row with gamma >= {gmin:g} and wall_syy > 0 (last gamma {g_last:g}): "
                        "choose a smaller --window")
    return {
        "mu_mean": float(np.mean(mu[sel])),
        "mu_std": float(np.std(mu[sel])),
        "window_from": float(gmin),
        "window_to": float(np.max(gamma[sel])),
        "window_rows": n,
        "gamma_final": g_last,
    }


# ----------------------------------------------------------------------------------------------------------
# Part 2: profiles from snapshots















# ----------------------------------------------------------------------------------------------------------
# Command line


def gather_inputs(paths):
    """(measures path or None, [snapshot paths], description) from the positional arguments."""
    measures, snaps = None, []
    for p in paths:
        if os.path.isdir(p):
            mp = os.path.join(p, "measures.csv")
            if not os.path.isfile(mp):
                raise ToolError(f"'{p}': no measures.csv in this directory (not a Rondel run directory, or the "
                                "run has not written its measures yet)")
            if measures is not None:
                raise ToolError("give one run at a time (one directory or one measures.csv)")
            measures = mp
            snaps += open_run(p).snapshot_paths()
        elif p.endswith(".h5"):
            if not os.path.isfile(p):
                raise ToolError(f"'{p}': no such file")
            snaps.append(p)
        else:
            if not os.path.isfile(p):
                raise ToolError(f"'{p}': no such file or directory")
            if measures is not None:
                raise ToolError("give one run at a time (one directory or one measures.csv)")
            measures = p
    return measures, snaps




def write_series(prefix, sr):
    with open(prefix + "_series.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["step", "time", "gamma", "mu", "dilation", "void_ratio", "height_m", "wall_syy_Pa",
                    "wall_tau_Pa"])
        vr = sr["void_ratio"]
        for k in range(len(sr["gamma"])):
            w.writerow([int(sr["step"][k]), repr(float(sr["time"][k])), repr(float(sr["gamma"][k])),
                        "" if not np.isfinite(sr["mu"][k]) else repr(float(sr["mu"][k])),
                        repr(float(sr["dilation"][k])), "" if vr is None else repr(float(vr[k])),
                        repr(float(sr["height"][k])), repr(float(sr["wall_syy"][k])),
                        repr(float(sr["wall_tau"][k]))])




def write_summary(prefix, sr, st, pr, rule):
    row = {"H0_m": sr["H0"] if sr else "", "gamma_final": st["gamma_final"] if st else "",
           "window_from": st["window_from"] if st else "", "window_to": st["window_to"] if st else "",
           "window_rows": st["window_rows"] if st else "", "mu_mean": st["mu_mean"] if st else "",
           "mu_std": st["mu_std"] if st else "",
           "dilation_final": float(sr["dilation"][-1]) if sr else "",
           "void_ratio_final": float(sr["void_ratio"][-1]) if sr and sr["void_ratio"] is not None else ""}
    band = pr["band"] if pr else None
    row.update({
        "profile_snapshots": pr["snapshots"] if pr else 0,
        "profile_selection": rule if pr else "",
        "profile_bins": pr["nbins"] if pr else "",
        "V_m_per_s": pr["V"] if pr else "",
        "d_mean_m": pr["d_mean"] if pr else "",
        "H_mean_m": pr["H_mean"] if pr else "",
        "band_lo_over_H": band["lo"] if band else "",
        "band_hi_over_H": band["hi"] if band else "",
        "band_centre_over_H": band["centre"] if band else "",
        "band_width_over_H": band["width"] if band else "",
        "band_width_diameters": band["width"] * pr["H_mean"] / pr["d_mean"] if band else "",
    })
    with open(prefix + "_summary.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(list(row))
        w.writerow([row[k] for k in row])
    return row


def scene_of(measures_path):
    """'scene (laws)' of the run directory holding MEASURES_PATH, for titles ('' when it has no config)."""
    try:
        cfg = open_run(os.path.dirname(os.path.abspath(measures_path))).config
        return f"{cfg.scene_name()} ({cfg.laws()})"
    except RondelError:
        return ""


def plot_series(prefix, sr, st, a, scene=""):
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 7), sharex=True, layout="constrained")
    fig.suptitle("Plane shear: stress ratio and dilation against shear strain" + (f", {scene}" if scene else ""),
                 fontsize=10)
    ax1.plot(sr["gamma"], sr["mu"], lw=1, label="mu = tau / sigma_n")
    if st:
        ax1.axvspan(st["window_from"], st["window_to"], color="0.9", zorder=0)
        ax1.axhline(st["mu_mean"], color="C3", ls="--",
                    label=f"steady {st['mu_mean']:.3f} ± {st['mu_std']:.3f} (gamma >= {st['window_from']:.3g})")
    ax1.set_ylabel("stress ratio tau / sigma_n")
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    ax2.plot(sr["gamma"], 100 * sr["dilation"], color="C0", label="dilation (H - H0)/H0")
    ax2.set_ylabel("dilation [%]")
    ax2.set_xlabel("shear strain gamma = shear_disp / H0")
    ax2.grid(alpha=0.3)
    if sr["void_ratio"] is not None:
        ax3 = ax2.twinx()
        ax3.plot(sr["gamma"], sr["void_ratio"], color="C1", lw=1, label="void ratio")
        ax3.set_ylabel("void ratio", color="C1")
        h1, l1 = ax2.get_legend_handles_labels()
        h2, l2 = ax3.get_legend_handles_labels()
        ax2.legend(h1 + h2, l1 + l2, fontsize=8, loc="lower right")
    return save_figure(fig, prefix + "_series", a)




def run(a):
    measures, snap_paths = gather_inputs(a.inputs)
    prefix = a.out
    os.makedirs(os.path.dirname(os.path.abspath(prefix)), exist_ok=True)

    sr = st = None
    window_time = None
    scene = scene_of(measures) if measures is not None else ""
    if measures is not None:
        sr = series(read_measures(measures))
        st = steady_state(sr["gamma"], sr["mu"], a.window)
        write_series(prefix, sr)
        i = np.nonzero(sr["gamma"] >= st["window_from"])[0]
        window_time = float(sr["time"][i[0]]) if i.size else None
        print(f"series: {len(sr['gamma'])} rows, H0 = {sr['H0']:.6g} m, final gamma = {st['gamma_final']:.4g}")
        print(f"steady stress ratio mu = {st['mu_mean']:.4f} ± {st['mu_std']:.4f} over gamma in "
              f"[{st['window_from']:.4g}, {st['window_to']:.4g}] ({st['window_rows']} rows)")
        print(f"dilation at the end: {100 * sr['dilation'][-1]:.3f} %" +
              (f", void ratio {sr['void_ratio'][-1]:.4f}" if sr["void_ratio"] is not None else ""))
    else:
        print("shear: no measures.csv given: time series skipped")

    pr, rule = None, ""
    if not snap_paths:
        print("shear: no snapshot_*.h5 files: profiles skipped (set output.snapshot_every, with "
              "output.snapshot_fields = position velocity omega radius flags)")
    else:
        chosen, rule = select_snapshots(snap_paths, a.from_time, a.last, window_time)
        if not chosen:
            raise ToolError(f"no snapshot matches {rule} (of {len(snap_paths)})")
        snaps = [read_snapshot(p, a.all_discs) for p in chosen]
        if not scene:
            scene = snaps[0]["title"].split(", step")[0]
        if not all(s["periodic_x"] for s in snaps):
            print("shear: warning: the domain is not periodic in x: bin areas use the domain width xhi - xlo",
                  file=sys.stderr)
        pr = profiles(snaps, a.bins, a.velocity)
        write_profiles(prefix, pr)
        b = pr["band"]
        print(f"profiles: {pr['snapshots']} snapshot(s) ({rule}), {pr['nbins']} bins of "
              f"{pr['H_mean'] / pr['nbins'] / pr['d_mean']:.3g} mean diameters, V = {pr['V']:.6g} m/s, "
              f"d = {pr['d_mean']:.6g} m, H = {pr['H_mean']:.6g} m = {pr['H_mean'] / pr['d_mean']:.1f} d")
        if b:
            wd = b["width"] * pr["H_mean"] / pr["d_mean"]
            print(f"shear band (local shear rate >= half its maximum): width {wd:.2f} diameters = "
                  f"{b['width']:.3f} H, y/H in [{b['lo']:.3f}, {b['hi']:.3f}], peak at y/H = {b['centre']:.3f}")
        else:
            print("shear band: not estimated (fewer than 2 bins with discs)")

    write_summary(prefix, sr, st, pr, rule)
    if not a.no_plot:
        written = []
        if sr is not None:
            written.append(plot_series(prefix, sr, st, a, scene))
        if pr is not None:
            written.append(plot_profiles(prefix, pr, a, scene))
        if written:
            print("wrote " + ", ".join(written))
    return 0


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("inputs", nargs="+", help="a run directory (measures.csv, snapshot_*.h5), or a measures.csv "
                    "and/or snapshot files")
    ap.add_argument("--out", default="shear", help="output prefix (default: shear)")
    ap.add_argument("--window", type=float, default=None, metavar="GMIN",
                    help="steady window: gamma >= GMIN (default: half of the last gamma)")
    ap.add_argument("--bins", type=int, default=None, metavar="N",
                    help="bins across the gap (default: about 2 mean diameters a bin)")
    ap.add_argument("--last", type=int, default=None, metavar="K", help="profiles from the last K snapshots")
    ap.add_argument("--from-time", type=float, default=None, metavar="T",
                    help="profiles from the snapshots with time >= T [s]")
    ap.add_argument("--velocity", type=float, default=None, metavar="V",
                    help="shear velocity [m/s] (default: top minus bottom wall x velocity of each snapshot)")
    ap.add_argument("--all-discs", action="store_true", help="profiles of every disc, wall-attached ones too")
    add_figure_options(ap, dpi=120)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    if a.bins is not None and a.bins < 1:
        ap.error("--bins must be >= 1")
    if a.last is not None and a.last < 1:
        ap.error("--last must be >= 1")
    if a.velocity is not None and a.velocity == 0:
        ap.error("--velocity must be non-zero")
    return run_tool(TOOL, run, a)


if __name__ == "__main__":
    sys.exit(main())
