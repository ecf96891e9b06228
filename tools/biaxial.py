#!/usr/bin/python3
"""Biaxial test post-processing for Rondel measures.csv files.

For each measures.csv (one biaxial shear stage) this writes the curves of deviator stress
q = s1 - s3 and volumetric strain against axial strain (PNG + CSV) and the friction angles from
    sin(phi) = (s1 - s3) / (s1 + s3),   s1 = wall_syy, s3 = wall_sxx (box wall stresses, compression +),
peak = the largest mobilised angle, residual = the mean mobilised angle over a window of axial strain
(default: the last 0.05 of axial strain reached, i.e. eps_axial in [eps_max - 0.05, eps_max]).
With several confining stresses the Mohr-Coulomb strength envelope t = s sin(phi) + c cos(phi)
(s = (s1 + s3)/2, t = (s1 - s3)/2 at peak) is fitted and plotted.

  python3 tools/biaxial.py RUN1/measures.csv [RUN2 ...] --out PREFIX [--window 0.05] [--format pdf] [--dpi 300]
Writes PREFIX_curves.png, PREFIX_curves.csv, PREFIX_angles.csv and, with >= 2 confining stresses,
PREFIX_envelope.png (.pdf, .svg with --format). Use --stress loveweber to take s1, s3 from the Love-Weber
sxx, syy instead, and --stress cell for a wall-free biaxial test in the periodic cell (inputs/periodic_biaxial.ini):
s1, s3 the Love-Weber syy, sxx, the strains from the cell's lengths (eps_axial = 1 - L_y / L_y0, eps_vol = 1 -
L_x L_y / (L_x0 L_y0)). A run directory may be given for its measures.csv. Files are read with tools/rondel.
"""
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import CheckFailed, RondelError, RondelFileError, open_run, read_csv, require  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "biaxial"
COLUMNS = ("eps_axial", "eps_vol", "wall_sxx", "wall_syy", "sxx", "syy")


def read_measures(path):
    """Columns of a biaxial measures.csv as a dict of float arrays (RondelFileError naming the file)."""
    if os.path.isdir(path):
        path = os.path.join(path, "measures.csv")
    t = read_csv(path)
    if len(t) == 0:
        raise RondelFileError(path, "no data rows")
    require(t, COLUMNS, "is this a biaxial run? walls.box with servo walls")
    return {h: np.asarray(t[h], dtype=float) for h in t.columns}


def scene_of(path):
    """'scene (laws)' of the run directory of PATH, for titles ('' when it has no configuration)."""
    d = path if os.path.isdir(path) else os.path.dirname(os.path.abspath(path))
    try:
        cfg = open_run(d).config
        return f"{cfg.scene_name()} ({cfg.laws()})"
    except RondelError:
        return ""


def mobilised_angle(s1, s3):
    """Mobilised friction angle [deg] from sin(phi) = (s1 - s3)/(s1 + s3); NaN where s1 + s3 <= 0."""
    s1 = np.asarray(s1, dtype=float)
    s3 = np.asarray(s3, dtype=float)
    out = np.full(s1.shape, np.nan)
    ok = (s1 + s3) > 0
    ratio = np.clip((s1[ok] - s3[ok]) / (s1[ok] + s3[ok]), -1.0, 1.0)
    out[ok] = np.degrees(np.arcsin(ratio))
    return out


def friction_angles(eps_axial, s1, s3, window=0.05):
    """Peak and residual friction angles [deg].

    peak: max of the mobilised angle (and the axial strain where it occurs);
    residual: mean of the mobilised angle over eps_axial in [eps_max - window, eps_max].
    """
    eps = np.asarray(eps_axial, dtype=float)
    phi = mobilised_angle(s1, s3)
    good = np.isfinite(phi)
    if not good.any():
        raise CheckFailed("no rows with s1 + s3 > 0: the sample carries no load")
    i_peak = int(np.nanargmax(np.where(good, phi, -np.inf)))
    eps_max = float(np.max(eps[good]))
    in_win = good & (eps >= eps_max - window)
    residual = float(np.mean(phi[in_win]))
    return {
        "phi_peak": float(phi[i_peak]),
        "eps_peak": float(eps[i_peak]),
        "q_peak": float(np.asarray(s1)[i_peak] - np.asarray(s3)[i_peak]),
        "s_peak": 0.5 * float(np.asarray(s1)[i_peak] + np.asarray(s3)[i_peak]),
        "phi_residual": residual,
        "residual_from": eps_max - window,
        "residual_to": eps_max,
        "residual_rows": int(np.count_nonzero(in_win)),
    }


def envelope(s_values, t_values):
    """Least-squares Mohr-Coulomb envelope t = s sin(phi) + c cos(phi): returns (phi [deg], c [Pa])."""
    s = np.asarray(s_values, dtype=float)
    t = np.asarray(t_values, dtype=float)
    slope, intercept = np.polyfit(s, t, 1)
    phi = math.degrees(math.asin(max(-1.0, min(1.0, slope))))
    c = intercept / math.cos(math.radians(phi))
    return phi, c


def cell_strains(m, path):
    """A wall-free test: the strains from the cell's lengths (measures.csv cell_lx, cell_ly)."""
    if "cell_ly" not in m or not (m["cell_ly"][0] > 0):
        raise RondelFileError(path, "has no cell_lx, cell_ly columns of a periodic cell (--stress cell is for "
                              "the periodic cell; a box with walls takes --stress wall or loveweber)")
    m["eps_axial"] = 1.0 - m["cell_ly"] / m["cell_ly"][0]
    m["eps_vol"] = 1.0 - m["cell_lx"] * m["cell_ly"] / (m["cell_lx"][0] * m["cell_ly"][0])
    m["wall_sxx"] = m["sxx"]  # the confining stress the servo holds


def stresses(m, which):
    if which == "wall":
        return m["wall_syy"], m["wall_sxx"]
    return m["syy"], m["sxx"]


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("measures", nargs="+", help="measures.csv files or run directories (one per biaxial run)")
    ap.add_argument("--out", default="biaxial", help="output prefix (default: biaxial)")
    ap.add_argument("--labels", default=None, help="comma-separated labels (default: the run directory names)")
    ap.add_argument("--window", type=float, default=0.05,
                    help="residual window: the last WINDOW of axial strain (default 0.05 = 5 %%)")
    ap.add_argument("--stress", choices=["wall", "loveweber", "cell"], default="wall",
                    help="s1, s3 from the box walls (default) or the Love-Weber average; cell: Love-Weber and the "
                         "strains of the periodic cell")
    ap.add_argument("--no-envelope", action="store_true",
                    help="no strength envelope (the runs differ in more than the confining stress)")
    add_figure_options(ap, dpi=150)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    if not a.window > 0:
        ap.error("--window must be > 0")
    if a.labels and len(a.labels.split(",")) != len(a.measures):
        ap.error("--labels must name every file")
    return run_tool(TOOL, analyse, a)


def analyse(a):
    labels = a.labels.split(",") if a.labels else [
        os.path.basename(os.path.normpath(p) if os.path.isdir(p) else os.path.dirname(os.path.abspath(p))) or p
        for p in a.measures]
    outdir = os.path.dirname(os.path.abspath(a.out))
    os.makedirs(outdir, exist_ok=True)

    runs = []
    for path, lab in zip(a.measures, labels):
        m = read_measures(path)
        if a.stress == "cell":
            cell_strains(m, path)
        s1, s3 = stresses(m, a.stress)
        res = friction_angles(m["eps_axial"], s1, s3, a.window)
        res.update(label=lab, path=path, confining=float(np.median(m["wall_sxx"])),
                   eps_final=float(m["eps_axial"][-1]))
        runs.append((lab, m, s1, s3, res))

    with open(a.out + "_curves.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "eps_axial", "deviator_Pa", "eps_vol", "phi_mobilised_deg", "s1_Pa", "s3_Pa"])
        for lab, m, s1, s3, _ in runs:
            phi = mobilised_angle(s1, s3)
            for k in range(len(s1)):
                w.writerow([lab, repr(m["eps_axial"][k]), repr(s1[k] - s3[k]), repr(m["eps_vol"][k]),
                            "" if not np.isfinite(phi[k]) else f"{phi[k]:.4f}", repr(s1[k]), repr(s3[k])])

    keys = ["label", "confining", "phi_peak", "eps_peak", "q_peak", "phi_residual", "residual_from",
            "residual_to", "residual_rows", "eps_final", "path"]
    with open(a.out + "_angles.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(keys)
        for *_, res in runs:
            w.writerow([res[k] for k in keys])

    print(f"{'run':<28} {'p [kPa]':>8} {'phi_peak':>9} {'at eps':>7} {'phi_res':>8}  window")
    for *_, r in runs:
        print(f"{r['label']:<28} {r['confining']/1e3:8.1f} {r['phi_peak']:9.2f} {r['eps_peak']:7.4f} "
              f"{r['phi_residual']:8.2f}  [{r['residual_from']:.4f}, {r['residual_to']:.4f}]")

    # Strength envelope over distinct confining stresses (peak states).
    ps = np.array([r["confining"] for *_, r in runs])
    env = None
    if not a.no_envelope and len(ps) >= 2 and ps.max() > 1.3 * ps.min():  # distinct confining stresses (not servo scatter)
        s = np.array([r["s_peak"] for *_, r in runs])
        t = np.array([0.5 * r["q_peak"] for *_, r in runs])
        env = envelope(s, t)
        print(f"envelope (peak, {len(runs)} runs): phi = {env[0]:.2f} deg, c = {env[1]/1e3:.2f} kPa")
        with open(a.out + "_envelope.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["label", "s_Pa", "t_Pa"])
            for (lab, *_), si, ti in zip(runs, s, t):
                w.writerow([lab, si, ti])
            w.writerow(["fit_phi_deg", env[0], ""])
            w.writerow(["fit_c_Pa", env[1], ""])

    if a.no_plot:
        return 0
    plt = pyplot()
    scenes = sorted({scene_of(p) for p in a.measures} - {""})
    scene = scenes[0] if len(scenes) == 1 else f"{len(runs)} runs"
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 8), sharex=True, layout="constrained")
    fig.suptitle(f"Biaxial test, {scene}: deviator stress and volumetric strain against axial strain", fontsize=10)
    for lab, m, s1, s3, r in runs:
        ax1.plot(100 * m["eps_axial"], (s1 - s3) / 1e3,
                 label=f"{lab}: peak {r['phi_peak']:.1f}°, res {r['phi_residual']:.1f}°")
        ax2.plot(100 * m["eps_axial"], 100 * m["eps_vol"], label=lab)
    ax1.set_ylabel("deviator s1 - s3 [kPa]")
    ax1.legend(fontsize=7)
    ax1.grid(alpha=0.3)
    ax2.set_xlabel("axial strain [%]")
    ax2.set_ylabel("volumetric strain [%] (compression +)")
    ax2.grid(alpha=0.3)
    written = [save_figure(fig, a.out + "_curves", a)]

    if env is not None:
        fig, ax = plt.subplots(figsize=(6, 5), layout="constrained")
        ax.set_title(f"Mohr-Coulomb strength envelope at peak, {scene}", fontsize=10)
        s = np.array([r["s_peak"] for *_, r in runs]) / 1e3
        t = np.array([0.5 * r["q_peak"] for *_, r in runs]) / 1e3
        ax.plot(s, t, "o")
        xs = np.linspace(0, 1.1 * s.max(), 50)
        ax.plot(xs, xs * math.sin(math.radians(env[0])) + env[1] / 1e3 * math.cos(math.radians(env[0])),
                "-", label=f"phi = {env[0]:.1f}°, c = {env[1]/1e3:.1f} kPa")
        ax.set_xlabel("s = (s1 + s3)/2 [kPa]")
        ax.set_ylabel("t = (s1 - s3)/2 [kPa]")
        ax.legend()
        ax.grid(alpha=0.3)
        written.append(save_figure(fig, a.out + "_envelope", a))
    print("wrote " + ", ".join(written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
