"""A cantilever of bonded discs against the discrete chain's exact solution (docs/bonds.md, "Checks").

    mpirun -n 2 /usr/bin/python3 examples/python/bonded_cantilever.py [--out DIR] [--quick]

21 D5 discs 0.1 % apart in a row, every neighbouring pair bonded (kb_n = 1e9, kb_s = 0.5e9 Pa/m, lambda 1); the
script fixes the first disc (position and rotation), pushes the last across with P = 4 mN (a body force) and lets the
local damping bring the chain to rest. Each bond is a beam element of length l (EI = kb_n I l), the bond k from the
fixed end carrying the moment P l (n - k + 1/2) and the shear P, so disc k's rotation and deflection are exact sums:
  theta_k = (P l / (kb_n I)) sum_{m=1..k} (n - m + 1/2)
  y_k = sum_{m=1..k} [l (theta_{m-1} + theta_m) / 2 + P / (kb_s A)]
The script writes cantilever.csv (gid, x, deflection and rotation run and exact) and cantilever.png (the deflection
along the chain, with Timoshenko's continuous cantilever of E = kb_n l, G = kb_s l) into DIR.
"""
import argparse
import csv
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from mpi4py import MPI  # noqa: E402

import rondel  # noqa: E402

R, N_DISCS, P = 0.005, 21, 4e-3
SPACING = 2.0 * R * 1.001
KB_N, KB_S = 1e9, 0.5e9
SCENE = f"""[run]
progress = false
local_damping = 0.8
[domain]
xlo = -0.01
xhi = 0.23
ylo = -0.02
yhi = 0.02
[material]
density = 2650
[linear]
k_n = 1e6
[coulomb]
k_s = 7.5e5
mu = 0.5
[bonds]
kb_n = {KB_N}
kb_s = {KB_S}
sigma_c = 1e9
tau_c = 1e9
[scene]
type = lattice_square
nx = {N_DISCS}
ny = 1
radius = {R}
spacing = {SPACING!r}
"""


def exact(n):
    """(deflection, rotation) of discs 0..n of the discrete chain."""
    A, I = 2.0 * R, (2.0 * R) ** 3 / 12.0
    theta = np.zeros(n + 1)
    y = np.zeros(n + 1)
    for k in range(1, n + 1):
        theta[k] = theta[k - 1] + P * SPACING * (n - k + 0.5) / (KB_N * I)
        y[k] = y[k - 1] + SPACING * (theta[k - 1] + theta[k]) / 2.0 + P / (KB_S * A)
    return y, theta


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="rondel-output/bonded_cantilever")
    ap.add_argument("--quick", action="store_true", help="(the same run: it takes a second)")
    a = ap.parse_args()
    sim = rondel.Simulation(text=SCENE, overrides={"run.output": a.out, "run.overwrite": True, "run.steps": 10**9,
                                                   "output.thermo_every": 0, "output.checkpoint_at_end": False})
    comm = MPI.COMM_WORLD
    gids, x0 = sim.gather("position", everywhere=True)
    sim.fix([gids[0]])
    sim.set_body_force([gids[-1]], [[0.0, P]])
    before = None
    while True:  # to rest: the tip moves less than 1e-10 of its deflection in 20,000 steps
        sim.step(20000)
        _, x = sim.gather("position", everywhere=True)
        tip = x[-1, 1] - x0[-1, 1]
        if before is not None and abs(tip - before) < 1e-10 * abs(tip):
            break
        before = tip
    _, x = sim.gather("position", everywhere=True)
    _, theta = sim.gather("theta", everywhere=True)
    sim.finish()
    if comm.rank != 0:
        return
    y_run = x[:, 1] - x0[:, 1]
    y_ex, th_ex = exact(N_DISCS - 1)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "cantilever.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["gid", "x", "deflection", "deflection_exact", "rotation", "rotation_exact"])
        for k in range(N_DISCS):
            w.writerow([int(gids[k]), repr(float(x0[k, 0])), repr(float(y_run[k])), repr(float(y_ex[k])),
                        repr(float(theta[k])), repr(float(th_ex[k]))])
    worst = float(np.max(np.abs(y_run[1:] / y_ex[1:] - 1.0)))
    print(f"bonded_cantilever: tip deflection {y_run[-1]:.10g} m (exact {y_ex[-1]:.10g}), rotation {theta[-1]:.10g} "
          f"rad (exact {th_ex[-1]:.10g}); every disc's deflection within {worst:.2g} of the exact chain")
    L, A, I = (N_DISCS - 1) * SPACING, 2.0 * R, (2.0 * R) ** 3 / 12.0
    EI, s = KB_N * I * SPACING, x0[:, 0] - x0[0, 0]
    timoshenko = P * s * s * (3.0 * L - s) / (6.0 * EI) + P * s / ((5.0 / 6.0) * KB_S * SPACING * A)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 3.8), layout="constrained")
    ax.plot(s * 100, timoshenko * 1e6, "-", color="0.6", label="Timoshenko cantilever (E = kb_n l, G = kb_s l)")
    ax.plot(s * 100, y_ex * 1e6, "x", color="k", label="the discrete chain, exact")
    ax.plot(s * 100, y_run * 1e6, "o", mfc="none", color="tab:red", label="Rondel, damped to rest")
    ax.set_xlabel("distance from the fixed disc [cm]")
    ax.set_ylabel("deflection [um]")
    ax.set_title(f"21 bonded discs, P = {P * 1e3:g} mN at the tip: within {worst:.1g} of the exact chain", fontsize=10)
    ax.legend(fontsize=8)
    fig.savefig(os.path.join(a.out, "cantilever.png"), dpi=120)


if __name__ == "__main__":
    main()
