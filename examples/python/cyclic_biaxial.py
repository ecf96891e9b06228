"""A cyclic biaxial test driven from Python: load, unload and reload between two deviator stresses that the script
reads from the measured wall stresses, which no INI key can express (docs/python.md, "Examples").

    mpirun -n 2 /usr/bin/python3 examples/python/cyclic_biaxial.py [--out DIR] [--cycles N] [--quick]

Stage 1 is inputs/biaxial_wang_prepare.ini (400 discs consolidated at 160 kPa by servo walls); stage 2 is
inputs/biaxial_wang.ini, whose top wall compresses at a strain rate of 0.1 /s with servo side walls. The script
reverses the top wall's rate each time the deviator q = wall_syy - wall_sxx passes q_high (unload) or q_low
(reload), N cycles, then writes cyclic.csv and cyclic.png (q against the axial strain) into DIR.
--quick: one cycle (CI). The whole script takes about 8 s on 2 ranks here (docs/python.md has its figure).
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import rondel  # noqa: E402

TOP = 3  # walls.box = bottom left right top: the top wall is wall 3


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="rondel-output/cyclic_biaxial")
    ap.add_argument("--cycles", type=int, default=3)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    quiet = {"run.progress": False, "output.thermo_every": 0, "run.overwrite": True}
    cycles = 1 if a.quick else a.cycles
    q_high, q_low = 120e3, 20e3
    chunk = 2000  # steps between two looks at the stress (0.24 ms, about 0.002 % of axial strain)

    prep_dir = os.path.join(a.out, "prepare")
    with rondel.Simulation(os.path.join(ROOT, "inputs", "biaxial_wang_prepare.ini"),
                           overrides=dict(quiet, **{"run.output": prep_dir})) as prep:
        prep.run()

    sim = rondel.Simulation(os.path.join(ROOT, "inputs", "biaxial_wang.ini"),
                            overrides=dict(quiet, **{"run.output": os.path.join(a.out, "cyclic"),
                                                     "scene.file": prep_dir, "run.reset_history": True,
                                                     "run.steps": 10**9, "output.checkpoint_at_end": False}))
    rate = sim.walls()[TOP]["strain_rate"]
    rows, reversals, loading = [], 0, True
    while reversals < 2 * cycles:
        sim.step(chunk)
        m = sim.measures()  # collective: every rank decides alike
        q = m["wall_syy"] - m["wall_sxx"]
        rows.append((sim.time, m["eps_axial"], q, m["eps_vol"]))
        if (loading and q > q_high) or (not loading and q < q_low):
            loading = not loading
            reversals += 1
            sim.set_wall_strain_rate(TOP, rate if loading else -rate)
            if sim.rank == 0:
                print(f"step {sim.step_count}: q = {q / 1e3:.1f} kPa, {'reload' if loading else 'unload'}")
    sim.finish()
    sim.close()
    if sim.rank == 0:
        write(a.out, rows, q_low, q_high)


def write(out, rows, q_low, q_high):
    with open(os.path.join(out, "cyclic.csv"), "w") as f:
        f.write("time,eps_axial,q,eps_vol\n")
        for r in rows:
            f.write(",".join(repr(v) for v in r) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no cyclic.png")
        return
    eps = [100 * r[1] for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(eps, [r[2] / 1e3 for r in rows], "-", lw=1)
    for level in (q_low, q_high):
        ax.axhline(level / 1e3, color="grey", lw=0.5, ls="--")
    ax.set_xlabel("axial strain [%]")
    ax.set_ylabel("deviator q = syy - sxx [kPa]")
    ax.set_title("cyclic biaxial test driven from Python (400 discs, wang rolling)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "cyclic.png"), dpi=120)
    print(f"wrote {os.path.join(out, 'cyclic.csv')} and cyclic.png: {len(rows)} rows")


if __name__ == "__main__":
    main()
