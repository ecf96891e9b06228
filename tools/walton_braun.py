#!/usr/bin/python3
"""The bounces of a disc dropped on a floor with the Walton-Braun law (inputs/walton_braun_bounce.ini).

  python3 tools/walton_braun.py RUN_DIR [--out PREFIX] [--check TOL] [--format png|pdf|svg] [--dpi N]

Input: RUN_DIR/config.ini (scene.y0, scene.radius, the material's density and thickness, gravity.y,
walton_braun.K1 and e or K2) and RUN_DIR/diagnostics.csv (time, W_gravity, D_normal_hysteresis). The disc's
height is read from the ledger, exactly: gravity's work on the one disc is m g (y0 - y), so the gap between its
bottom and the floor is h = y0 - R - W_gravity/(m g) (negative while it overlaps the floor).

Method: the apexes are the local maxima of h above --floor-gap (default 1e-4 m; below it the bounces are shorter
than a few diagnostics rows). The n-th is compared with the law's exact bounce map, gravity acting during the
impacts too: landing at v = sqrt(2 g h_(n-1)), the contact loads along K1 to u_max = (m g + sqrt((m g)^2 +
K1 m v^2))/K1, unloads along K2 and leaves at u_0 = u_max (1 - K1/K2) with m v'^2 = e^2 (K1 u_max^2 - 2 m g u_max),
so h_n = v'^2/(2 g) - u_0, and the impact took K1 (1 - e^2) u_max^2/2 (e^2 = K1/K2): the ledger's
D_normal_hysteresis at the apex against the sum. Without gravity in the impacts this is h0 e^(2n), drawn too:
gravity deepens each impact by about m g/K1, which the slower impacts feel more (2 % at the fifth apex here).
Writes PREFIX.png (h against t, the map's apexes and h0 e^(2n)) and PREFIX.csv (one row per apex); PREFIX
defaults to RUN_DIR/walton_braun. --check TOL: exit status 2 unless the first five apexes and their
dissipation lie within TOL (relative) of the map. docs/walton_braun.md.
"""
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import CheckFailed, RondelFileError, open_run, require  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "walton_braun"
CHECKED = 5  # apexes the --check holds to the map


def setting(config, section, key, default=None):
    value = config.getfloat(section, key, default)
    if value is None:
        raise RondelFileError(config.source, f"no {section}.{key}: this tool reads the scene of "
                              "inputs/walton_braun_bounce.ini")
    return value


def stiffnesses(config):
    """(K1, K2) of the run: K2 given, or K1/e^2."""
    K1 = setting(config, "walton_braun", "K1")
    e = config.getfloat("walton_braun", "e")
    return K1, (K1 / (e * e) if e is not None else setting(config, "walton_braun", "K2"))


def bounce_map(h0, m, g, K1, K2, count):
    """[(h_n, D_n)] for n = 1..count: the apex after the n-th impact and the hysteresis of the n impacts."""
    out, h, D = [], h0, 0.0
    for _ in range(count):
        v2 = 2.0 * g * h
        u_max = (m * g + math.sqrt((m * g) ** 2 + K1 * m * v2)) / K1
        D += 0.5 * K1 * (1.0 - K1 / K2) * u_max * u_max
        v_out2 = (K1 / K2) * (K1 * u_max * u_max - 2.0 * m * g * u_max) / m
        h = v_out2 / (2.0 * g) - u_max * (1.0 - K1 / K2)
        out.append((h, D))
    return out


def bounces(run_dir, floor_gap):
    """(t, h, D_hyst, apexes, h0, e, m g): the gap h(t), the ledger's hysteresis and the apex rows."""
    run = open_run(run_dir)
    c = run.config
    R, y0 = setting(c, "scene", "radius"), setting(c, "scene", "y0")
    m = setting(c, "material", "density") * math.pi * R * R * (c.getfloat("material", "thickness", 1.0) or 1.0)
    g = -setting(c, "gravity", "y", 0.0)
    if not g > 0.0:
        raise RondelFileError(run.file("config.ini"), "gravity.y is not negative: no disc falls")
    K1, K2 = stiffnesses(c)
    d = run.diagnostics()
    require(d, ["time", "W_gravity", "D_normal_hysteresis"], "diagnostics.csv of a run with walton_braun")
    t, W_g, D = (np.asarray(d[k], dtype=float) for k in ("time", "W_gravity", "D_normal_hysteresis"))
    h = y0 - R - W_g / (m * g)
    h0 = h[0]
    inner = np.flatnonzero((h[1:-1] > h[:-2]) & (h[1:-1] >= h[2:]) & (h[1:-1] > floor_gap)) + 1
    exact = bounce_map(h0, m, g, K1, K2, len(inner))
    apexes = []
    for n, (i, (h_exact, D_exact)) in enumerate(zip(inner, exact), start=1):
        apexes.append({"n": n, "t": t[i], "h": h[i], "h_map": h_exact, "h_error": h[i] / h_exact - 1.0,
                       "h_no_gravity": h0 * (K1 / K2) ** n, "D_hyst": D[i], "D_map": D_exact,
                       "D_error": D[i] / D_exact - 1.0})
    e = math.sqrt(K1 / K2)
    return t, h, D, apexes, h0, e, m * g


def main(args):
    t, h, D, apexes, h0, e, mg = bounces(args.run_dir, args.floor_gap)
    prefix = args.out or os.path.join(args.run_dir, "walton_braun")
    with open(prefix + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        keys = ("t", "h", "h_map", "h_error", "h_no_gravity", "D_hyst", "D_map", "D_error")
        w.writerow(("n",) + keys)
        for a in apexes:
            w.writerow([a["n"]] + [f"{a[k]:.10g}" for k in keys])
    print(f"e = {e:.6g}, h0 = {h0:.6g} m, m g = {mg:.6g} N; apexes (h and D_normal_hysteresis against the bounce "
          "map; h0 e^(2n) leaves gravity out of the impacts):")
    for a in apexes:
        print(f"  n {a['n']:2d}  t {a['t']:.5f} s  h {a['h']:.6e} m ({a['h_error']:+.2e}; h0 e^2n "
              f"{a['h_no_gravity'] / a['h_map'] - 1.0:+.2e})  D_hyst {a['D_hyst']:.6e} J ({a['D_error']:+.2e})")
    if not args.no_plot:
        plt = pyplot()
        fig, (ax, bx) = plt.subplots(1, 2, figsize=(10.0, 4.0), gridspec_kw={"width_ratios": [3, 2]})
        ax.plot(t, 1e3 * h, lw=0.8, label="h, from the ledger's W_gravity")
        ax.plot([a["t"] for a in apexes], [1e3 * a["h_map"] for a in apexes], "o", mfc="none", ms=8,
                label="the law's bounce map")
        ax.set_xlabel("t [s]")
        ax.set_ylabel("gap below the disc, h [mm]")
        ax.legend(loc="upper right", fontsize=8)
        n = [a["n"] for a in apexes]
        bx.semilogy(n, [a["h"] for a in apexes], "s", ms=5, label="the run")
        bx.semilogy(n, [a["h_map"] for a in apexes], "o", mfc="none", ms=9, label="the bounce map")
        bx.semilogy(n, [a["h_no_gravity"] for a in apexes], "x", ms=6,
                    label=r"$h_0 e^{2n}$ (no gravity in the impacts)")
        bx.set_xlabel("apex n")
        bx.set_ylabel("h_n [m]")
        bx.legend(loc="upper right", fontsize=8)
        fig.suptitle(r"A disc bouncing with the Walton-Braun law, $e = \sqrt{K_1/K_2}$ = " + f"{e:g}")
        print("wrote", save_figure(fig, prefix, args))
    print("wrote", prefix + ".csv")
    if args.check is not None:
        bad = [a for a in apexes[:CHECKED] if abs(a["h_error"]) > args.check or abs(a["D_error"]) > args.check]
        if len(apexes) < CHECKED or bad:
            raise CheckFailed(f"{len(apexes)} apexes found, {len(bad)} of the first {CHECKED} off the map by "
                              f"more than {args.check:g}")
        print(f"check: the first {CHECKED} apexes and their dissipation within {args.check:g} of the map")


def parse(argv):
    ap = ArgumentParser(TOOL, description=__doc__.split("\n\n")[0])
    ap.add_argument("run_dir", help="the run directory of inputs/walton_braun_bounce.ini")
    ap.add_argument("--out", help="output prefix (default RUN_DIR/walton_braun)")
    ap.add_argument("--floor-gap", type=float, default=1e-4, help="smallest apex counted [m] (default 1e-4)")
    ap.add_argument("--check", type=float, help="exit 2 unless the first apexes are within this relative error")
    add_figure_options(ap)
    args = ap.parse_args(argv)
    check_figure_options(ap, args)
    if not (args.floor_gap > 0.0 and math.isfinite(args.floor_gap)):
        ap.error(f"--floor-gap {args.floor_gap:g} is not a positive length")
    if args.check is not None and not (args.check > 0.0 and math.isfinite(args.check)):
        ap.error(f"--check {args.check:g} is not a positive tolerance")
    if not os.path.isdir(args.run_dir):
        ap.error(f"'{args.run_dir}' is not a run directory")
    return args


if __name__ == "__main__":
    sys.exit(run_tool(TOOL, main, parse(sys.argv[1:])))
