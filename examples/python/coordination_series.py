"""An in-situ time series while a run goes: the coordination number of the deposition scene from the run's own
diagnostics, and the fraction of discs still moving computed from this rank's views and summed over the ranks with
mpi4py, every chunk of steps, with a matplotlib figure (docs/python.md, "Examples").

    mpirun -n 2 /usr/bin/python3 examples/python/coordination_series.py [--out DIR] [--quick]

Writes coordination.csv and coordination.png into DIR.
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

MOVING = 0.01  # m/s: a disc faster than this is still moving


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="rondel-output/coordination_series")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    steps = 30000 if a.quick else 45000
    sim = rondel.Simulation(os.path.join(ROOT, "inputs", "deposition.ini"),
                            overrides={"run.output": a.out, "run.steps": steps, "run.progress": False,
                                       "output.thermo_every": 0, "run.overwrite": True})
    comm = MPI.COMM_WORLD
    rows = []
    while sim.step_count < steps:
        sim.step(250)
        d = sim.discs  # views of this rank's discs: no copy
        speed = np.hypot(d.velocity[:, 0], d.velocity[:, 1])
        moving = comm.allreduce(int(np.count_nonzero(speed > MOVING)))
        total = comm.allreduce(len(d))
        z = sim.diagnostics()["coordination"]  # collective, the run's own measure
        rows.append((sim.time, z, moving / total))
    sim.finish()
    sim.close()
    if comm.rank == 0:
        write(a.out, rows)


def write(out, rows):
    with open(os.path.join(out, "coordination.csv"), "w") as f:
        f.write("time,coordination,moving_fraction\n")
        for r in rows:
            f.write(",".join(repr(v) for v in r) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no coordination.png")
        return
    t = [r[0] for r in rows]
    fig, ax = plt.subplots(figsize=(6, 3.5))
    lines = ax.plot(t, [r[1] for r in rows], label="coordination (diagnostics)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("coordination number")
    ax2 = ax.twinx()
    lines += ax2.plot(t, [r[2] for r in rows], "C1--", label=f"fraction faster than {MOVING} m/s")
    ax2.set_ylabel("moving fraction")
    ax.legend(lines, [x.get_label() for x in lines], loc="center left", fontsize=8)
    ax.set_title("deposition of 5,000 discs, measured while it runs", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "coordination.png"), dpi=120)
    print(f"wrote {os.path.join(out, 'coordination.csv')} and coordination.png: coordination {rows[-1][1]:.2f}")


if __name__ == "__main__":
    main()
