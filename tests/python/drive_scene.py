"""A scene stepped from Python the way the tests compare it with the executable (tests/python/test_driver.py).

    mpirun -n P python3 drive_scene.py OUT STEPS CHUNK [--resume DIR] [--steer] [--forever] [--section.key=value ...]

Steps the deposition scene (inputs/deposition.ini) to STEPS in chunks of CHUNK with run.output = OUT, then finish().
--steer: at step 600 fixes discs 0-9, gives discs 10-59 an upward velocity and a spin and discs 60-99 a body force
of twice their weight upwards; at step 1200 frees discs 0-4 and ends the body forces (the same calls on every rank). --forever: steps until a signal stops the script (rondel.Stopped, exit 10).
--self: each rank runs a simulation of its own on MPI.COMM_SELF, into OUT.rank<r>.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import rondel  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def main(argv):
    out, steps, chunk = argv[0], int(argv[1]), int(argv[2])
    rest = argv[3:]
    steer = "--steer" in rest
    forever = "--forever" in rest
    resume = None
    if "--resume" in rest:
        resume = rest[rest.index("--resume") + 1]
    overrides = [a for a in rest if a.startswith("--") and "=" in a]
    comm = None
    if "--self" in rest:
        from mpi4py import MPI
        comm, out = MPI.COMM_SELF, f"{out}.rank{MPI.COMM_WORLD.rank}"
    overrides += [f"--run.steps={steps}", f"--run.output={out}", "--run.progress=false"]
    config = None if resume else os.path.join(ROOT, "inputs", "deposition.ini")
    sim = rondel.Simulation(config, resume=resume, overrides=overrides, comm=comm)
    while forever or sim.step_count < steps:
        n = chunk if forever else min(chunk, steps - sim.step_count)
        if steer and sim.step_count == 600:
            sim.fix(range(10))
            gids = np.arange(10, 60)
            sim.set_velocity(gids, np.tile([0.0, 0.3], (len(gids), 1)))
            sim.set_omega(gids, np.full(len(gids), 5.0))
            lift = np.arange(60, 100)
            sim.set_body_force(lift, np.tile([0.0, 0.2], (len(lift), 1)))
        if steer and sim.step_count == 1200:
            sim.free(range(5))
            sim.set_body_force(np.arange(60, 100), np.zeros((40, 2)))
        if steer:
            n = min(n, 600 - sim.step_count % 600)
        sim.step(n)
    sim.finish()
    sim.close()


if __name__ == "__main__":
    main(sys.argv[1:])
