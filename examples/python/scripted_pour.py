"""A pour whose inflow rate the script controls: discs held in a reservoir above a box are released, lowest first, at a
rate that the script sets from the time and from the measured kinetic energy (docs/python.md, "Examples").

    mpirun -n 2 /usr/bin/python3 examples/python/scripted_pour.py [--out DIR] [--quick]

The scene is inputs/deposition.ini with its discs generated in a narrow reservoir high in a taller box. At the start
the script fixes every disc; then, every chunk of steps, it frees the next ones in height order at the rate
Q(t) = Q0 min(1, t / t_ramp), halved while the kinetic energy per released disc exceeds E_cap (a pile that is still
splashing). It writes pour.csv (time, released, kinetic energy, coordination) and pour.png into DIR.
"""
import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from mpi4py import MPI  # noqa: E402

import rondel  # noqa: E402

Q0 = 1500.0     # discs per second at full rate
T_RAMP = 0.05   # s
E_CAP = 0.005   # J per released disc: a fraction of what a disc gains falling from the reservoir to the floor


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="rondel-output/scripted_pour")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    count = 300 if a.quick else 700
    scene = {"run.output": a.out, "run.progress": False, "output.thermo_every": 0, "run.overwrite": True,
             "run.steps": 10**9, "scene.count": count, "scene.region": "0.12 0.18 0.12 0.36",
             "diagnostics.every": 1000, "output.checkpoint_at_end": False}
    sim = rondel.Simulation(os.path.join(ROOT, "inputs", "deposition.ini"), overrides=scene)
    comm = MPI.COMM_WORLD
    # Every rank needs the same list (the writes are collective): the reservoir's discs in height order.
    gids, position = sim.gather("position", everywhere=True)
    queue = gids[np.lexsort((gids, position[:, 1]))]
    sim.fix(queue)
    released, owed, rows, chunk = 0, 0.0, [], 200
    end = 0.8 if a.quick else 1.0
    while sim.time < end:
        row = sim.diagnostics()
        ke = row["ke_trans"] + row["ke_rot"]
        rate = Q0 * min(1.0, sim.time / T_RAMP)
        if released and ke / released > E_CAP:
            rate *= 0.5
        if released == len(queue):
            rate = 0.0
        owed += rate * chunk * sim.dt
        n = min(int(owed), len(queue) - released)
        if n > 0:
            sim.free(queue[released:released + n])
            released += n
            owed -= n
        rows.append((sim.time, released, ke, row["coordination"], rate))
        sim.step(chunk)
    sim.finish()
    sim.close()
    if comm.rank == 0:
        write(a.out, rows)


def write(out, rows):
    with open(os.path.join(out, "pour.csv"), "w") as f:
        f.write("time,released,kinetic_energy,coordination,rate\n")
        for r in rows:
            f.write(",".join(repr(v) for v in r) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no pour.png")
        return
    t = np.array([r[0] for r in rows])
    fig, ax = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
    ax[0].plot(t, [r[1] for r in rows], label="released discs")
    ax[0].plot(t, np.cumsum([r[4] for r in rows]) * (t[1] - t[0]) if len(t) > 1 else t, "--", lw=0.8,
               label="integral of the rate set")
    ax[0].set_ylabel("discs")
    ax[0].legend()
    ax[1].plot(t, [r[2] for r in rows])
    ax[1].set_ylabel("kinetic energy [J]")
    ax[1].set_xlabel("time [s]")
    fig.suptitle("a pour whose inflow the script sets")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "pour.png"), dpi=120)
    print(f"wrote {os.path.join(out, 'pour.csv')} and pour.png: {rows[-1][1]} discs released")


if __name__ == "__main__":
    main()
