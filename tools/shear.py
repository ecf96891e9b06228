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
Files are read with tools/rondel (docs/python.md). Exit status: 0 done, 1 bad input or usage (one line on stderr).
Needs numpy, h5py (for part 2) and matplotlib: Debian's /usr/bin/python3.
"""
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import FLAG_GLUED, RondelError, open_file, open_run, read_csv  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "shear"
FLAG_ATTACHED = FLAG_GLUED


class ToolError(RondelError):
    """A problem with the input, reported as 'shear: error: ...' with exit code 1."""


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



def wall_rows(cp):
    """(bottom row, top row) of /walls for the configuration, or (None, None) when unknown."""
    def count(key):
        val = cp.get("walls", key, "")
        return sum(1 for rec in val.split(";") if rec.split())
    box = cp.get("walls", "box", "").split()
    base = count("lines") + count("segments")
    bottom = base + box.index("bottom") if "bottom" in box else None
    top = base + box.index("top") if "top" in box else None
    return bottom, top


def find_walls(path, cp, normals):
    """Bottom and top wall rows: from walls.box of the config, else the lines with normal (0, +1) / (0, -1)."""
    b, t = wall_rows(cp) if cp is not None else (None, None)
    n = len(normals)
    if b is None or t is None or b >= n or t >= n:
        up = [i for i in range(n) if normals[i][1] > 0.999]
        down = [i for i in range(n) if normals[i][1] < -0.999]
        if len(up) != 1 or len(down) != 1:
            raise ToolError(f"'{path}': cannot tell the bottom and top walls (walls.box has no bottom and top, "
                            "and there is not exactly one wall facing up and one facing down)")
        b, t = up[0], down[0]
    return b, t


def read_snapshot(path, all_discs=False):
    """The data of one snapshot (or checkpoint) needed for the profiles."""
    f = open_file(path)
    need = ["position", "velocity", "omega", "radius"]
    missing = [k for k in need if k not in f.discs]
    if missing:
        raise ToolError(f"'{path}': no /discs/{', /discs/'.join(missing)}: list them in output.snapshot_fields "
                        "(position velocity omega radius flags)")
    for k in ("p0", "normal", "velocity"):
        if k not in f.walls:
            raise ToolError(f"'{path}': no /walls/{k}")
    cp = f.config
    s = {
        "path": path, "step": f.step, "time": f.time,
        "pos": np.asarray(f.discs["position"], dtype=float).reshape(-1, 2),
        "vel": np.asarray(f.discs["velocity"], dtype=float).reshape(-1, 2),
        "omega": np.asarray(f.discs["omega"], dtype=float).reshape(-1),
        "radius": np.asarray(f.discs["radius"], dtype=float).reshape(-1),
        "flags": f.discs["flags"].reshape(-1).astype(np.int64) if "flags" in f.discs else None,
        "title": f.title(),
    }
    p0 = np.asarray(f.walls["p0"], dtype=float).reshape(-1, 2)
    normal = np.asarray(f.walls["normal"], dtype=float).reshape(-1, 2)
    wvel = np.asarray(f.walls["velocity"], dtype=float).reshape(-1, 2)
    if "domain" not in cp or cp.getfloat("domain", "xhi") is None or cp.getfloat("domain", "xlo") is None:
        raise ToolError(f"'{path}': no config attribute with a [domain] section (needed for the box width)")
    b, t = find_walls(path, cp, normal)
    s["y_bottom"], s["y_top"] = float(p0[b, 1]), float(p0[t, 1])
    s["vx_bottom"], s["vx_top"] = float(wvel[b, 0]), float(wvel[t, 0])
    s["H"] = s["y_top"] - s["y_bottom"]
    if not s["H"] > 0:
        raise ToolError(f"'{path}': the top wall (y = {s['y_top']}) is not above the bottom wall (y = {s['y_bottom']})")
    s["Lx"] = cp.getfloat("domain", "xhi") - cp.getfloat("domain", "xlo")
    s["periodic_x"] = cp.getbool("domain", "periodic_x")
    keep = np.ones(len(s["radius"]), dtype=bool)
    if s["flags"] is not None and not all_discs:
        keep = (s["flags"] & FLAG_ATTACHED) == 0
    s["keep"] = keep
    return s


def snapshot_header(path):
    """(step, time) of a snapshot."""
    f = open_file(path)
    return f.step, f.time


def shear_band(yc, v):
    """Band of the local shear rate g = |dv/dy'| >= max(g)/2 around its maximum (see the docstring).

    yc: the abscissa of each bin (the mean y' of its discs); bins without discs (NaN) are skipped.
    Returns dict(lo, hi, width, centre, rate, rate_max), lengths in units of y' (fractions of the gap),
    or None with fewer than 2 bins holding discs."""
    yc = np.asarray(yc, dtype=float)
    v = np.asarray(v, dtype=float)
    ok = np.isfinite(v)
    if np.count_nonzero(ok) < 2:
        return None
    g = np.full(v.shape, np.nan)
    g[ok] = np.abs(np.gradient(v[ok], yc[ok]))
    gg = np.where(np.isfinite(g), g, -np.inf)
    k = int(np.argmax(gg))
    half = 0.5 * g[k]
    i0 = k
    while i0 > 0 and gg[i0 - 1] >= half:
        i0 -= 1
    i1 = k
    while i1 < len(g) - 1 and gg[i1 + 1] >= half:
        i1 += 1

    def cross(ia, ib):  # ia above half, ib below (or NaN): the y' where g = half, linearly
        if not (np.isfinite(g[ib]) and np.isfinite(yc[ib])):
            return yc[ia]
        return yc[ia] + (half - g[ia]) * (yc[ib] - yc[ia]) / (g[ib] - g[ia])
    lo = 0.0 if i0 == 0 else cross(i0, i0 - 1)
    hi = 1.0 if i1 == len(g) - 1 else cross(i1, i1 + 1)
    return {"lo": float(lo), "hi": float(hi), "width": float(hi - lo), "centre": float(yc[k]),
            "rate": g, "rate_max": float(g[k])}


def profiles(snaps, nbins=None, velocity=None):
    """Bin profiles pooled over the snapshots (see the docstring). Returns a dict of arrays and scalars."""
    d_all = np.concatenate([2 * s["radius"][s["keep"]] for s in snaps])
    if d_all.size == 0:
        raise ToolError("no discs to bin (every disc is attached to a wall? try --all-discs)")
    d_mean = float(np.mean(d_all))
    H_mean = float(np.mean([s["H"] for s in snaps]))
    if nbins is None:
        nbins = max(1, int(round(H_mean / (2.0 * d_mean))))
    edges = np.linspace(0.0, 1.0, nbins + 1)
    yc = 0.5 * (edges[:-1] + edges[1:])
    cnt = np.zeros(nbins)
    sum_v = np.zeros(nbins)
    sum_v2 = np.zeros(nbins)
    sum_s = np.zeros(nbins)
    sum_y = np.zeros(nbins)
    area = np.zeros(nbins)
    area_all = np.zeros(nbins)
    Vs = []
    for s in snaps:
        V = velocity if velocity is not None else s["vx_top"] - s["vx_bottom"]
        if not abs(V) > 0:
            raise ToolError(f"'{s['path']}': the top wall does not move relative to the bottom one in x "
                            "(V = 0): give the shear velocity with --velocity")
        Vs.append(V)
        yp = (s["pos"][:, 1] - s["y_bottom"]) / s["H"]
        k = np.clip(np.floor(yp * nbins).astype(np.int64), 0, nbins - 1)
        inside = (yp >= 0.0) & (yp <= 1.0)
        sel = inside & s["keep"]
        vx = (s["vel"][:, 0] - s["vx_bottom"]) / V
        spin = s["omega"] * d_mean / V
        a = math.pi * s["radius"] ** 2
        cnt += np.bincount(k[sel], minlength=nbins)
        sum_v += np.bincount(k[sel], weights=vx[sel], minlength=nbins)
        sum_v2 += np.bincount(k[sel], weights=vx[sel] ** 2, minlength=nbins)
        sum_s += np.bincount(k[sel], weights=spin[sel], minlength=nbins)
        sum_y += np.bincount(k[sel], weights=yp[sel], minlength=nbins)
        bin_area = s["Lx"] * s["H"] / nbins
        area += np.bincount(k[sel], weights=a[sel], minlength=nbins) / bin_area
        area_all += np.bincount(k[inside], weights=a[inside], minlength=nbins) / bin_area
    ns = len(snaps)
    with np.errstate(invalid="ignore", divide="ignore"):
        vmean = sum_v / cnt
        vstd = np.sqrt(np.maximum(sum_v2 / cnt - vmean ** 2, 0.0))
        smean = sum_s / cnt
        ymean = sum_y / cnt
    band = shear_band(ymean, vmean)
    rate = band["rate"] if band else np.full(nbins, np.nan)
    ok = np.isfinite(vmean)
    dv = np.full(nbins, np.nan)
    if np.count_nonzero(ok) >= 2:
        dv[ok] = np.gradient(vmean[ok], ymean[ok])
    return {
        "y": yc, "y_discs": ymean, "edges": edges, "count": cnt / ns, "vx": vmean, "vx_std": vstd, "spin": smean,
        "spin_continuum": -0.5 * (d_mean / H_mean) * dv, "rate": rate,
        "solid_fraction": area / ns, "solid_fraction_all": area_all / ns,
        "d_mean": d_mean, "H_mean": H_mean, "V": float(np.mean(Vs)), "nbins": nbins, "snapshots": ns,
        "band": band,
    }


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


def select_snapshots(paths, from_time=None, last=None, window_time=None):
    """Snapshot paths sorted by step, filtered by --from-time / --last, else by the steady window's start."""
    heads = sorted((snapshot_header(p) + (p,) for p in paths), key=lambda h: (h[0], h[2]))
    rule = "all snapshots"
    if from_time is not None:
        heads = [h for h in heads if h[1] >= from_time]
        rule = f"time >= {from_time:g} s (--from-time)"
    if last is not None:
        heads = heads[-last:]
        rule = f"the last {last}" + (f" with {rule}" if from_time is not None else "")
    if from_time is None and last is None and window_time is not None:
        sel = [h for h in heads if h[1] >= window_time]
        if sel:
            heads = sel
            rule = f"the steady window (time >= {window_time:g} s)"
        else:
            heads = heads[-1:]
            rule = "the last one (none lies in the steady window)"
    return [h[2] for h in heads], rule


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


def write_profiles(prefix, pr):
    with open(prefix + "_profiles.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["y_over_H", "y_lo", "y_hi", "y_discs_over_H", "discs_per_snapshot", "vx_over_V",
                    "vx_over_V_std", "spin", "spin_continuum", "shear_rate", "solid_fraction", "solid_fraction_all"])

        def num(x):
            return "" if not np.isfinite(x) else repr(float(x))
        for k in range(pr["nbins"]):
            w.writerow([repr(float(pr["y"][k])), repr(float(pr["edges"][k])), repr(float(pr["edges"][k + 1])),
                        num(pr["y_discs"][k]), num(pr["count"][k]), num(pr["vx"][k]), num(pr["vx_std"][k]),
                        num(pr["spin"][k]), num(pr["spin_continuum"][k]), num(pr["rate"][k]),
                        num(pr["solid_fraction"][k]),
                        num(pr["solid_fraction_all"][k])])


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


def plot_profiles(prefix, pr, a, scene=""):
    plt = pyplot()
    fig, axs = plt.subplots(1, 3, figsize=(11, 5), sharey=True, layout="constrained")
    y = pr["y"]
    yd = pr["y_discs"]
    axs[0].plot(pr["vx"], yd, "o-", ms=3, label="discs")
    axs[0].plot([0, 1], [0, 1], "k:", lw=1, label="uniform shear")
    b = pr["band"]
    if b:
        for i, ax in enumerate(axs):
            ax.axhspan(b["lo"], b["hi"], color="C2", alpha=0.08, zorder=0,
                       label="shear band (rate >= max/2)" if i == 0 else None)
    axs[0].set_xlabel("vx / V")
    axs[0].set_ylabel("y / H (0: bottom wall, 1: top wall)")
    axs[0].legend(fontsize=8)
    axs[1].plot(pr["spin"], yd, "o-", ms=3, label="omega d / V")
    axs[1].plot(pr["spin_continuum"], yd, "k:", lw=1, label="-0.5 (d/V) dvx/dy")
    axs[1].axvline(0.0, color="0.5", lw=0.5)
    axs[1].ticklabel_format(axis="x", useOffset=False)
    axs[1].set_xlabel("spin omega d / V")
    axs[1].legend(fontsize=8)
    axs[2].plot(pr["solid_fraction"], y, "o-", ms=3, label="free discs")
    axs[2].plot(pr["solid_fraction_all"], y, "--", lw=1, label="all discs")
    axs[2].set_xlabel("solid fraction (centre binning)")
    axs[2].legend(fontsize=8)
    for ax in axs:
        ax.set_ylim(0, 1)
        ax.grid(alpha=0.3)
    title = "Plane shear profiles across the gap" + (f", {scene}" if scene else "")
    title += f": {pr['snapshots']} snapshot(s), {pr['nbins']} bins of {pr['H_mean'] / pr['nbins'] / pr['d_mean']:.2g} d"
    if b:
        title += f"; shear band (rate >= max/2): {b['width'] * pr['H_mean'] / pr['d_mean']:.1f} d"
    fig.suptitle(title, fontsize=10)
    return save_figure(fig, prefix + "_profiles", a)


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
