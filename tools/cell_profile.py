#!/usr/bin/python3
"""The mean velocity profile across a sheared periodic cell (docs/physics.md section 10).

Reads checkpoints or snapshots of a run whose cell shears (cell.rate_xy; files of format version 5, with
/cell and the discs' positions and velocities), bins the discs by height y' = (y - ylo) / L_y in N equal bins
(default: about two mean diameters a bin) pooled over the files, and compares the mean v_x per bin with the mean
flow of the cell, v_x = gamma_dot (y - ylo) (Lees-Edwards, lab frame): the least-squares slope of the bin means
against y over gamma_dot (1 for a linear profile with the cell's rate), and the largest deviation of a bin mean
from the fitted line over gamma_dot L_y. Prints one line per bin and the summary; writes PREFIX_profile.csv and
PREFIX_profile.png (unless --no-plot).

  python3 tools/cell_profile.py RUN_DIR --out PREFIX [--bins N] [--last K]
  python3 tools/cell_profile.py checkpoint_*.h5 snapshot_*.h5 --out PREFIX

RUN_DIR: its checkpoints and snapshots, the last K of them (default 1). Exit status: 0 done, 1 bad input or
usage (one line on stderr). Needs numpy, h5py, matplotlib: Debian's /usr/bin/python3.
"""
import csv
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import RondelError, open_file  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "cell_profile"


def state_files(inputs, last):
    """The files named, or the last LAST checkpoints and snapshots (by step) of each directory named."""
    out = []
    for path in inputs:
        if os.path.isdir(path):
            found = sorted(glob.glob(os.path.join(path, "checkpoint_*.h5")) +
                           glob.glob(os.path.join(path, "snapshot_*.h5")), key=lambda p: os.path.basename(p)[-13:])
            if not found:
                raise RondelError(f"'{path}': no checkpoint_*.h5 or snapshot_*.h5 in it")
            out += found[-last:]
        else:
            out.append(path)
    return out


def profile(paths, nbins=None):
    """Bin means of v_x against height, pooled over the files, and the fit against the cell's flow."""
    ys, vs, d_sum, n_sum, rate, Ly, ylo = [], [], 0.0, 0, None, None, None
    for p in paths:
        f = open_file(p)
        if not f.cell:
            raise RondelError(f"'{p}': no /cell (a file of format version 5 or later is needed)")
        for need in ("position", "velocity", "radius"):
            if need not in f.discs:
                raise RondelError(f"'{p}': no /discs/{need} (output.snapshot_fields must list it)")
        corner, _, b = f.cell_vectors()
        rate, Ly, ylo = float(f.cell["rate_xy"]), float(b[1]), float(corner[1])
        x = np.asarray(f.discs["position"], dtype=float).reshape(-1, 2)
        v = np.asarray(f.discs["velocity"], dtype=float).reshape(-1, 2)
        ys.append((x[:, 1] - ylo) / Ly)
        vs.append(v[:, 0])
        d_sum += float(np.sum(2.0 * np.asarray(f.discs["radius"], dtype=float)))
        n_sum += len(x)
    if rate == 0.0:
        raise RondelError("the cell does not shear (cell.rate_xy = 0 in the file): no profile to compare")
    y = np.concatenate(ys)
    vx = np.concatenate(vs)
    d = d_sum / n_sum
    if nbins is None:
        nbins = max(2, int(round(Ly / (2.0 * d))))
    edges = np.linspace(0.0, 1.0, nbins + 1)
    which = np.clip(np.digitize(y, edges) - 1, 0, nbins - 1)
    rows = []
    for k in range(nbins):
        sel = which == k
        if np.any(sel):
            rows.append((float(np.mean(y[sel])) * Ly, float(np.mean(vx[sel])), int(np.count_nonzero(sel))))
    h = np.array([r[0] for r in rows])
    m = np.array([r[1] for r in rows])
    slope, intercept = np.polyfit(h, m, 1)
    deviation = float(np.max(np.abs(m - (slope * h + intercept)))) / abs(rate * Ly)
    return {"rows": rows, "rate": rate, "Ly": Ly, "diameter": d, "slope_ratio": float(slope) / rate,
            "intercept": float(intercept), "deviation": deviation, "files": len(paths)}


def run(a):
    pr = profile(state_files(a.inputs, a.last), a.bins)
    with open(a.out + "_profile.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["height", "vx_mean", "vx_affine", "discs"])
        for h, m, n in pr["rows"]:
            w.writerow([f"{h:.9g}", f"{m:.9g}", f"{pr['rate'] * h:.9g}", n])
    for h, m, n in pr["rows"]:
        print(f"  y - ylo = {h:10.5g} m  v_x = {m:11.5g} m/s  (affine {pr['rate'] * h:11.5g})  {n} discs")
    print(f"{TOOL}: {pr['files']} file(s), {len(pr['rows'])} bins; slope / cell.rate_xy = {pr['slope_ratio']:.4f}, "
          f"largest deviation from the line = {pr['deviation']:.4f} of gamma_dot L_y")
    if not a.no_plot:
        plt = pyplot()
        fig, ax = plt.subplots(figsize=(4.5, 4.0))
        h = np.array([r[0] for r in pr["rows"]])
        ax.plot([r[1] for r in pr["rows"]], h / pr["Ly"], "o", label="bin mean")
        ax.plot(pr["rate"] * h, h / pr["Ly"], "-", label="cell's mean flow")
        ax.set_xlabel("v_x [m/s]")
        ax.set_ylabel("(y - ylo) / L_y")
        ax.legend()
        save_figure(fig, a.out + "_profile", a)


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__.split("\n\n")[0])
    ap.add_argument("inputs", nargs="+", help="run directories or checkpoint/snapshot files")
    ap.add_argument("--out", default="cell", help="output prefix (default: cell)")
    ap.add_argument("--bins", type=int, default=None, metavar="N", help="bins across the cell (default: 2 d each)")
    ap.add_argument("--last", type=int, default=1, metavar="K", help="the last K files of each directory")
    add_figure_options(ap)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    if a.bins is not None and a.bins < 2:
        ap.error(f"--bins must be at least 2, not {a.bins}")
    if a.last < 1:
        ap.error(f"--last must be at least 1, not {a.last}")
    return run_tool(TOOL, run, a)


if __name__ == "__main__":
    sys.exit(main())
