#!/usr/bin/python3
"""Tests of tools/shear.py on a synthetic plane shear run with known answers (ctest: tools.shear).

The run directory holds a measures.csv whose stress ratio rises to a plateau mu = 0.4 (plus noise) and whose
gap dilates by 2 %, and snapshot files (FORMAT.md layout, with checksums) of discs on a square lattice between
a bottom wall and a top wall moving at V: free discs with vx = V y'/H and omega = -0.5 V/H exactly, the first
and last rows glued to the walls (flags 3: moving with their wall, omega 0, to be left out), and an early
snapshot with a plug flow that the default selection (the steady window) must leave out.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import contextlib
import csv
import io
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.join(HERE, "..", "..", "tools")
sys.path.insert(0, TOOLS)
import shear  # noqa: E402

try:
    import h5py  # noqa: F401
    import h5info  # noqa: E402  (the dataset checksum of FORMAT.md)
except ImportError:  # pragma: no cover
    print("h5py is missing for this python: run with Debian's /usr/bin/python3")
    sys.exit(1)

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


# Geometry of the synthetic run
R = 0.001           # disc radius [m]
D = 2 * R
NX, NY = 20, 24     # lattice columns and rows (rows 0 and NY-1 glued to the walls)
LX = NX * D         # periodic width [m]
H0 = NY * D         # gap [m]
V = 0.01            # shear velocity [m/s]
MU = 0.4
DIL = 0.02
PHI = math.pi * R * R / (D * D)  # solid fraction of the touching square lattice, pi/4
GAMMA_END = 2.0
T_END = GAMMA_END * H0 / V

CONFIG = f"""# resolved configuration of this run (every key, defaults included)
[run]
steps = 1000
output = synthetic

[output]
snapshot_every = 100
snapshot_fields = position velocity omega radius flags

[domain]
xlo = 0
xhi = {LX!r}
ylo = -0.01
yhi = {H0 + 0.02!r}
periodic_x = true
periodic_y = false

[walls]
box = bottom top
control = top:servo:1e5 top:shear:{V!r}
rough = bottom top
lines =
segments =
"""


def put(group, name, data):
    ds = group.create_dataset(name, data=data)
    ds.attrs["checksum"] = np.uint64(h5info.checksum(np.asarray(data)))


def write_snapshot(path, step, time, H, profile, shift=0.0, y_bottom=0.0):
    """Lattice discs between walls at y_bottom and y_bottom + H; profile(y') gives vx/V of the free discs."""
    i, j = np.meshgrid(np.arange(NX), np.arange(NY), indexing="xy")
    i, j = i.ravel(), j.ravel()
    yp = (j + 0.5) / NY
    x = np.mod((i + 0.5) * D + shift, LX)
    y = y_bottom + yp * H
    n = len(x)
    flags = np.zeros(n, dtype=np.uint32)
    flags[j == 0] = 1 | 2 | (0 << 8)
    flags[j == NY - 1] = 1 | 2 | (1 << 8)
    vx = V * profile(yp)
    omega = np.full(n, -0.5 * V / H)
    vx[j == 0], omega[j == 0] = 0.0, 0.0          # glued to the bottom wall: moves with it
    vx[j == NY - 1], omega[j == NY - 1] = V, 0.0   # glued to the top wall
    vel = np.stack([vx, np.full(n, 1e-6)], axis=1)
    with h5py.File(path, "w") as f:
        f.attrs["format"] = np.bytes_("rondel")
        f.attrs["format_version"] = np.int64(1)
        f.attrs["kind"] = np.bytes_("snapshot")
        f.attrs["step"] = np.int64(step)
        f.attrs["time"] = np.float64(time)
        f.attrs["dt"] = np.float64(1e-6)
        f.attrs["config"] = np.bytes_(CONFIG)
        f.attrs["complete"] = np.int64(1)
        g = f.create_group("discs")
        put(g, "gid", np.arange(n, dtype=np.int64))
        put(g, "position", np.stack([x, y], axis=1))
        put(g, "velocity", vel)
        put(g, "omega", omega)
        put(g, "radius", np.full(n, R))
        put(g, "flags", flags)
        w = f.create_group("walls")
        put(w, "kind", np.zeros(2, dtype=np.int32))
        put(w, "p0", np.array([[0.0, y_bottom], [V * time, y_bottom + H]]))
        put(w, "p1", np.zeros((2, 2)))
        put(w, "normal", np.array([[0.0, 1.0], [0.0, -1.0]]))
        put(w, "velocity", np.array([[0.0, 0.0], [V, -1e-6]]))
        w.attrs["box_width0"] = np.float64(LX)
        w.attrs["box_height0"] = np.float64(H0)
    return yp, flags


def write_measures(path, n=401, seed=1):
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, T_END, n)
    gamma = V * t / H0
    mu = MU * (1 - np.exp(-gamma / 0.05)) + rng.normal(0.0, 0.004, n)
    syy = 1e5 * (1 + rng.normal(0.0, 0.01, n))
    height = H0 * (1 + DIL * (1 - np.exp(-gamma / 0.1)))
    cols = ["step", "time", "width", "height", "wall_sxx", "wall_syy", "sxx", "syy", "sxy", "wall_tau",
            "shear_disp", "void_ratio", "coordination", "sliding_fraction", "rolling_yield_fraction"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for k in range(n):
            row = dict.fromkeys(cols, 0.0)
            row.update(step=100 * k, time=t[k], width=LX, height=height[k], wall_syy=syy[k], syy=syy[k],
                       wall_tau=mu[k] * syy[k], shear_disp=V * t[k], void_ratio=0.25 * height[k] / H0,
                       coordination=3.5)
            w.writerow([repr(float(row[c])) if c != "step" else row[c] for c in cols])
    return gamma, mu, height


def linear(yp):
    return yp


def plug(yp):
    return np.ones_like(yp)


def band(yp):
    return np.clip((yp - 0.4) / 0.2, 0.0, 1.0)


def run_tool(args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = shear.main(args)
    return rc, out.getvalue(), err.getvalue()


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def make_run(d, name="run", profile=linear, snapshots=True):
    run = os.path.join(d, name)
    os.makedirs(run)
    write_measures(os.path.join(run, "measures.csv"))
    Hs = []
    if snapshots:
        write_snapshot(os.path.join(run, "snapshot_0000000100.h5"), 100, 1.0, H0, plug)  # before the window
        for k, (t, h) in enumerate([(6.0, 1.004), (7.5, 0.997), (T_END, 1.0)]):
            H = H0 * h
            Hs.append(H)
            write_snapshot(os.path.join(run, f"snapshot_{1000 * (k + 1):010d}.h5"), 1000 * (k + 1), t, H, profile,
                           shift=0.37 * D * k, y_bottom=0.0)
    return run, Hs


def test_series_and_profiles(d):
    run, Hs = make_run(d)
    out = os.path.join(d, "out", "lin")
    plot = []
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        plot = ["--no-plot"]
    rc, so, se = run_tool([run, "--out", out] + plot)
    check("cli exit 0", rc == 0, (rc, so, se))
    summ = read_rows(out + "_summary.csv")[0]
    mu = float(summ["mu_mean"])
    check("steady mu 0.4 within 0.01", abs(mu - MU) < 0.01, mu)
    check("steady mu std ~ noise", 0.001 < float(summ["mu_std"]) < 0.01, summ["mu_std"])
    check("default window = half the last gamma", abs(float(summ["window_from"]) - 0.5 * GAMMA_END) < 1e-9,
          summ["window_from"])
    dil_end = DIL * (1 - math.exp(-GAMMA_END / 0.1))
    check("final dilation 2 %", abs(float(summ["dilation_final"]) - dil_end) < 1e-9, summ["dilation_final"])
    check("final void ratio", abs(float(summ["void_ratio_final"]) - 0.25 * (1 + dil_end)) < 1e-9,
          summ["void_ratio_final"])
    ser = read_rows(out + "_series.csv")
    check("series rows", len(ser) == 401, len(ser))
    g = np.array([float(r["gamma"]) for r in ser])
    check("gamma = shear_disp / H0", abs(g[-1] - GAMMA_END) < 1e-9 and g[0] == 0.0, (g[0], g[-1]))
    check("default snapshots: the 3 in the steady window", summ["profile_snapshots"] == "3", summ["profile_snapshots"])
    check("default bins: 2 diameters (12)", summ["profile_bins"] == "12", summ["profile_bins"])
    check("V from the walls", abs(float(summ["V_m_per_s"]) - V) < 1e-15, summ["V_m_per_s"])

    prof = read_rows(out + "_profiles.csv")
    check("12 profile rows", len(prof) == 12, len(prof))
    yc = np.array([float(r["y_over_H"]) for r in prof])
    vx = np.array([float(r["vx_over_V"]) for r in prof])
    # Expected: the mean y' of the free discs in each bin (rows 2k, 2k+1 minus the glued rows 0 and NY-1).
    rows = np.arange(NY)
    free = (rows > 0) & (rows < NY - 1)
    exp_v = np.array([np.mean((rows[free & (rows // 2 == k)] + 0.5) / NY) for k in range(12)])
    err = np.abs(vx - exp_v) / exp_v
    check("linear vx profile: every bin within 2 %", np.all(err < 0.02), np.round(err, 4))
    inner = slice(1, 11)
    check("linear vx profile: interior bins = y/H", np.all(np.abs(vx[inner] - yc[inner]) < 0.02 * yc[inner]),
          (vx[inner], yc[inner]))
    spin = np.array([float(r["spin"]) for r in prof])
    spin_exp = np.mean([-0.5 * D / H for H in Hs])
    check("spin omega d / V = -0.5 d / H in every bin", np.all(np.abs(spin - spin_exp) < 1e-3 * abs(spin_exp)),
          (spin, spin_exp))
    sc = np.array([float(r["spin_continuum"]) for r in prof])
    check("continuum spin -0.5 (d/H) dv/dy' matches (interior)",
          np.all(np.abs(sc[inner] - spin_exp) < 0.03 * abs(spin_exp)), (sc, spin_exp))
    phi_exp = np.mean([math.pi * R * R / (D * H / NY) for H in Hs])
    sf_all = np.array([float(r["solid_fraction_all"]) for r in prof])
    sf = np.array([float(r["solid_fraction"]) for r in prof])
    check("solid fraction (all discs) = lattice pi/4 within 3 %", np.all(np.abs(sf_all - PHI) < 0.03 * PHI),
          (sf_all, PHI))
    check("solid fraction (all discs) = exact lattice value", np.all(np.abs(sf_all - phi_exp) < 1e-9), sf_all)
    check("solid fraction (free) = lattice inside, half at the walls",
          np.all(np.abs(sf[inner] - phi_exp) < 1e-9) and abs(sf[0] - 0.5 * phi_exp) < 1e-9
          and abs(sf[-1] - 0.5 * phi_exp) < 1e-9, sf)
    bw = float(summ["band_width_diameters"])
    H_mean = float(np.mean(Hs))
    check("uniform shear: band = whole gap", abs(bw - H_mean / D) < 1e-6, (bw, H_mean / D))
    check("band printed in diameters", "shear band" in so and "diameters" in so, so)
    if not plot:
        check("PNGs written", os.path.exists(out + "_series.png") and os.path.exists(out + "_profiles.png"))

    # The glued discs are left out by default: with --all-discs the end bins move towards the wall velocity.
    rc, so, se = run_tool([run, "--out", out + "_all", "--all-discs", "--no-plot"])
    vall = np.array([float(r["vx_over_V"]) for r in read_rows(out + "_all_profiles.csv")])
    check("--all-discs includes the wall layers (bins 0 and last differ)",
          rc == 0 and abs(vall[0] - vx[0]) > 0.1 * vx[0] and abs(vall[-1] - vx[-1]) > 0.01, (vall, vx))

    # --window, --last, --from-time, --bins
    rc, so, se = run_tool([run, "--out", out + "_w", "--window", "0.02", "--last", "1", "--bins", "6",
                           "--no-plot"])
    s2 = read_rows(out + "_w_summary.csv")[0]
    check("--window 0.02: mean over gamma >= 0.02 is lower",
          rc == 0 and float(s2["window_from"]) == 0.02 and float(s2["mu_mean"]) < mu - 0.002, s2)
    check("--last 1: one snapshot", s2["profile_snapshots"] == "1", s2["profile_snapshots"])
    check("--bins 6", len(read_rows(out + "_w_profiles.csv")) == 6)
    rc, so, se = run_tool([run, "--out", out + "_t", "--from-time", "0", "--no-plot"])
    s3 = read_rows(out + "_t_summary.csv")[0]
    v3 = np.array([float(r["vx_over_V"]) for r in read_rows(out + "_t_profiles.csv")])
    check("--from-time 0: all 4 snapshots, the plug flow shows", s3["profile_snapshots"] == "4"
          and v3[5] > vx[5] + 0.05, (s3["profile_snapshots"], v3[5], vx[5]))


def test_band(d):
    run, Hs = make_run(d, "band", profile=band)
    out = os.path.join(d, "out", "band")
    rc, so, se = run_tool([run, "--out", out, "--bins", "24", "--no-plot"])
    summ = read_rows(out + "_summary.csv")[0]
    bw = float(summ["band_width_diameters"])
    exp = 0.2 * float(np.mean(Hs)) / D  # vx rises over y' in [0.4, 0.6]: 0.2 H = 4.8 d
    check("localised band: width 0.2 H within one bin", rc == 0 and abs(bw - exp) <= 1.0, (bw, exp, se))
    check("localised band: centred at mid-gap", abs(float(summ["band_centre_over_H"]) - 0.5) < 0.06,
          summ["band_centre_over_H"])
    # The function itself on an exact profile: a triangle of rate, half max crossing by interpolation.
    yc = (np.arange(20) + 0.5) / 20
    b = shear.shear_band(yc, np.cumsum(np.where(np.abs(yc - 0.5) < 0.2, 1.0, 0.0)) / 20)
    check("shear_band on a step of rate", b is not None and abs(b["width"] - 0.4) < 0.051, b and b["width"])


def test_no_snapshots_and_errors(d):
    run, _ = make_run(d, "nosnap", snapshots=False)
    out = os.path.join(d, "out", "nosnap")
    rc, so, se = run_tool([run, "--out", out, "--no-plot"])
    check("no snapshots: exit 0, series only, message", rc == 0 and os.path.exists(out + "_series.csv")
          and not os.path.exists(out + "_profiles.csv") and "no snapshot" in so, (rc, so, se))
    empty = os.path.join(d, "empty")
    os.makedirs(empty)
    p = subprocess.run([sys.executable, os.path.join(TOOLS, "shear.py"), empty, "--out", os.path.join(d, "x")],
                       capture_output=True, text=True)
    check("missing measures.csv: exit 1", p.returncode == 1, p.returncode)
    check("missing measures.csv: clear message", "measures.csv" in p.stderr and empty in p.stderr
          and "Traceback" not in p.stderr, p.stderr)
    # A measures.csv without the shear columns (a biaxial run) is refused by name.
    bi = os.path.join(d, "biax")
    os.makedirs(bi)
    with open(os.path.join(bi, "measures.csv"), "w") as f:
        f.write("step,time,width,height,wall_sxx,wall_syy\n0,0,1,1,0,0\n")
    rc, so, se = run_tool([bi, "--out", os.path.join(d, "y")])
    check("non-shear measures: exit 1 naming the columns", rc == 1 and "wall_tau" in se and "shear_disp" in se,
          (rc, se))


with tempfile.TemporaryDirectory() as tmp:
    for t in (test_series_and_profiles, test_band, test_no_snapshots_and_errors):
        try:
            t(tmp)
        except Exception as exc:  # a crash counts as a failure
            import traceback
            traceback.print_exc()
            check(t.__name__, False, repr(exc))

n_pass = sum(results)
n_fail = len(results) - n_pass
print(f"{n_pass} passed, {n_fail} failed")
sys.exit(1 if n_fail else 0)
