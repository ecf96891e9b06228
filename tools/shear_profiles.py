"""Part 2 of tools/shear.py: the profiles across a plane shear's gap from its snapshots (the walls from /walls, the
free discs binned by height, velocity, spin and solid fraction per bin, the shear band's width) and their CSV and
figure. The method is the one tools/shear.py --help describes."""
import csv
import math

import numpy as np

from rondel import FLAG_GLUED, RondelError, open_file
from rondel.cli import pyplot, save_figure

FLAG_ATTACHED = FLAG_GLUED


class ToolError(RondelError):
    """A problem with the input, reported as 'shear: error: ...' with exit code 1."""


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
