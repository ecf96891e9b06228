"""Under mpirun (tests/python/test_bits.py): every setter of rondel.Simulation refuses bad values on every rank
alike, naming them, and changes nothing; gather() brings every rank's discs together in gid order. Exits 0 when
every check holds (an AssertionError otherwise).

    mpirun -n 2 python3 refusals.py OUT
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import rondel  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def refused(call, *words):
    try:
        call()
    except ValueError as e:
        for w in words:
            assert w in str(e), f"'{w}' not in the message: {e}"
        return
    raise AssertionError(f"not refused: {words}")


def main(out):
    sim = rondel.Simulation(os.path.join(ROOT, "inputs", "deposition.ini"),
                            overrides={"run.output": out, "run.steps": 100, "run.progress": False})
    sim.step(20)
    before = sim.ledger()
    refused(lambda: sim.set_velocity([3], [[math.nan, 0.0]]), "velocity[0]", "nan")
    refused(lambda: sim.set_velocity([3, 4], [[0.0, 0.0]]), "1 values for 2 gids")
    refused(lambda: sim.set_omega([3], [math.inf]), "omega[0]", "inf")
    refused(lambda: sim.set_velocity([10**9], [[0.0, 0.0]]), "gid 1000000000", "no rank owns it")
    refused(lambda: sim.set_omega([7, 7], [1.0, 1.0]), "gid 7 is given twice")
    refused(lambda: sim.set_wall_velocity(17, (0.0, 0.0)), "wall 17 does not exist")
    refused(lambda: sim.set_wall_velocity(0, (math.nan, 0.0)), "wall velocity")
    refused(lambda: sim.set_wall_stress(0, 1e5), "wall 0 is not a servo wall")
    refused(lambda: sim.set_body_force([3], [[0.0, math.nan]]), "force[0]")
    refused(lambda: sim.set_cell_rates(xy=0.1), "does not deform")
    # nothing changed by the refusals
    assert sim.ledger() == before
    sim.fix([5])  # it fell for 20 steps: its kinetic energy leaves as W_driver
    assert sim.ledger()["W_driver"] < 0.0
    refused(lambda: sim.set_velocity([5], [[0.0, 1.0]]), "disc 5 is fixed")
    try:
        sim.discs.position[0] = 1.0
    except (ValueError, TypeError):
        pass
    else:
        raise AssertionError("a view could be written")
    sim.step(10)
    d = sim.discs
    gids, x = sim.gather("position", everywhere=True)
    assert np.array_equal(gids, np.arange(5000)) and x.shape == (5000, 2)
    mine = np.asarray(d.gid)
    assert np.array_equal(x[mine], np.asarray(d.position)), "gather is not the views' values"
    rooted = sim.gather("omega")
    assert (rooted is None) == (sim.rank != 0)
    if rooted is not None:
        assert np.array_equal(rooted[0], gids) and rooted[1].shape == (5000,)
    try:
        sim.gather("speed")
    except rondel.RondelError as e:
        assert "no column 'speed'" in str(e)
    else:
        raise AssertionError("gather of an unknown column")
    assert d.fixed.sum() == (1 if 5 in set(np.asarray(d.gid).tolist()) else 0)
    sim.close()


if __name__ == "__main__":
    main(sys.argv[1])
