"""rondel.Simulation on one rank, in this process (docs/python.md, "The driver"): the views copy nothing, are
read-only and raise once stale; the set-up from a file, a text or a dict refuses a bad key; walls, ledger,
diagnostics, measures and the outputs on demand; `import rondel` without the compiled part still reads files and
says what is missing at a driver call.

Run by CTest (label python); the executables' bits are tests/python/test_bits.py's.
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import rondel  # noqa: E402

SCENE = os.path.join(ROOT, "inputs", "deposition.ini")


@pytest.fixture
def out():
    d = tempfile.mkdtemp(prefix="rondel-api-")
    yield os.path.join(d, "run")
    shutil.rmtree(d, ignore_errors=True)


def deposition(out, **more):
    overrides = {"run.output": out, "run.steps": 200, "run.progress": False}
    overrides.update(more)
    return rondel.Simulation(SCENE, overrides=overrides)


def test_views_copy_nothing_are_read_only_and_go_stale(out):
    sim = deposition(out)
    sim.step(10)
    a, b = sim.discs, sim.discs
    pa, pb = np.asarray(a.position), np.asarray(b.position)
    # two views of one column share the store's memory: neither is a copy
    assert pa.__array_interface__["data"][0] == pb.__array_interface__["data"][0]
    assert not pa.flags.owndata and not pa.flags.writeable
    assert pa.shape == (len(a), 2) and pa.strides == (16, 8)
    with pytest.raises(ValueError):
        pa[0, 0] = 1.0
    # the values are the discs': the ones a step moves
    y = a.position[:, 1].copy()
    assert np.all(np.isfinite(y)) and len(a.gid) == 5000
    sim.step(1)
    with pytest.raises(rondel.StaleViewError, match="position"):
        a.position[0]
    with pytest.raises(rondel.StaleViewError):
        np.asarray(b.velocity)
    fresh = sim.discs
    assert not np.array_equal(fresh.position[:, 1], y), "a step moved nothing"
    sim.set_omega([1], [2.0])  # a write makes the views stale too
    with pytest.raises(rondel.StaleViewError):
        fresh.omega + 1.0
    assert sim.discs.omega[np.asarray(sim.discs.gid) == 1][0] == 2.0
    sim.close()


def test_properties_and_tables(out):
    sim = deposition(out)
    assert sim.critical_mode == "normal" and 0 < sim.dt < sim.critical_dt
    sim.step(50)
    assert sim.step_count == 50 and sim.time == pytest.approx(50 * sim.dt, rel=1e-12)
    row = sim.diagnostics()
    assert row["step"] == 50 and "W_driver" in row and row["W_driver"] == 0.0
    ledger = sim.ledger()
    assert ledger["W_g"] == pytest.approx(row["W_gravity"], rel=1e-12) and ledger["W_g"] > 0
    m = sim.measures()
    assert m["step"] == 50 and "void_ratio" in m
    walls = sim.walls()
    assert len(walls) == 3 and walls[0]["control"] == "velocity"
    path = sim.checkpoint()
    assert os.path.isfile(path) and path.endswith("checkpoint_0000000050.h5")
    sim.snapshot()
    assert any(f.startswith("snapshot_") for f in os.listdir(out))
    with pytest.raises(ValueError, match="n = -1"):
        sim.step(-1)
    summary = sim.run()  # to run.steps = 200, then the run's files
    assert summary["steps"] == 200 and sim.step_count == 200 and summary["stop_signal"] == 0
    assert os.path.isfile(os.path.join(out, "final.csv")) and os.path.isfile(os.path.join(out, "summary.json"))
    with pytest.raises(RuntimeError, match="finished"):
        sim.step(1)
    sim.close()


def test_a_wall_velocity_set_from_python_moves_the_wall(out):
    sim = deposition(out, **{"walls.box": "bottom left right top"})
    top = [i for i, w in enumerate(sim.walls()) if w["p0"][1] > 0.05][0]
    y0 = sim.walls()[top]["p0"][1]
    sim.set_wall_velocity(top, (0.0, -0.01))
    sim.step(100)
    assert sim.walls()[top]["p0"][1] == pytest.approx(y0 - 0.01 * 100 * sim.dt, rel=1e-9)
    with pytest.raises(ValueError, match="wall velocity"):
        sim.set_wall_velocity(top, (0.0, math.inf))
    sim.close()


def test_a_body_force_that_cancels_gravity_holds_a_disc_exactly(out):
    sim = deposition(out)
    d = sim.discs
    top = np.argsort(np.asarray(d.position)[:, 1])[-10:]  # nothing is above them to fall onto them
    gids, m = np.asarray(d.gid)[top], np.asarray(d.mass)[top]
    x0 = np.asarray(d.position)[top].copy()
    sim.set_body_force(gids, np.column_stack([np.zeros(10), 9.81 * m]))  # -m g exactly: m (-9.81) + 9.81 m = 0
    sim.step(300)
    d = sim.discs
    rows = np.searchsorted(np.asarray(d.gid), gids)
    assert np.array_equal(np.asarray(d.position)[rows], x0) and not np.any(np.asarray(d.velocity)[rows])
    assert sim.ledger()["W_driver"] == 0.0
    with pytest.raises(ValueError, match="force"):
        sim.set_body_force(gids[:1], [[math.nan, 0.0]])
    sim.close()


def test_a_body_forces_work_is_booked_as_velocity_verlet_does_it(out):
    sim = deposition(out)
    d = sim.discs
    k = int(np.argmax(np.asarray(d.position)[:, 1]))
    gid, m = int(np.asarray(d.gid)[k]), float(np.asarray(d.mass)[k])
    a = 5.0  # m/s^2 sideways, gravity cancelled
    sim.set_body_force([gid], [[a * m, 9.81 * m]])
    n = 50
    sim.step(n)
    d = sim.discs
    v = np.asarray(d.velocity)[np.asarray(d.gid) == gid][0]
    assert v[1] == 0.0 and v[0] == pytest.approx(a * n * sim.dt, rel=1e-12)
    ke = 0.5 * m * v[0] ** 2
    # From the first opening kick on, a constant force: the booked work F . x is the kinetic energy
    W = sim.ledger()["W_driver"]
    assert W == pytest.approx(ke, rel=1e-9)
    sim.set_body_force([gid], [[0.0, 0.0]])  # gone from the next opening kick: the disc falls again, no more work
    sim.step(5)
    d = sim.discs
    v5 = np.asarray(d.velocity)[np.asarray(d.gid) == gid][0]
    assert v5[0] == v[0] and v5[1] == pytest.approx(-9.81 * 5 * sim.dt, rel=1e-12)
    assert sim.ledger()["W_driver"] == W
    sim.close()


def test_the_cell_from_python(out):
    overrides = {"run.output": out, "run.steps": 100, "run.progress": False, "scene.count": 300}
    sim = rondel.Simulation(os.path.join(ROOT, "inputs", "periodic_prepare.ini"), overrides=overrides)
    c = sim.cell()
    assert c["deforms"] and c["target_stress"] == (1e5, 1e5) and c["tilt"] == 0.0
    sim.set_cell_stress(yy=2e5)
    assert sim.cell()["target_stress"] == (1e5, 2e5)
    with pytest.raises(ValueError, match="stress-controlled"):
        sim.set_cell_rates(xx=0.1)
    with pytest.raises(ValueError, match="> 0"):
        sim.set_cell_stress(xx=-1.0)
    sim.set_cell_rates(xy=0.5)
    sim.step(100)
    c = sim.cell()
    assert c["rate"][2] == 0.5 and c["tilt"] > 0.0
    assert c["tilt"] == pytest.approx(0.5 * c["length"][1] * 100 * sim.dt, rel=0.05)
    sim.close()
    dep = deposition(out + "2")
    with pytest.raises(ValueError, match="does not deform"):
        dep.set_cell_rates(xy=0.1)
    with pytest.raises(ValueError, match="not stress-controlled"):
        dep.set_cell_stress(xx=1e5)
    dep.close()


def test_setup_from_text_or_dict_and_a_bad_key(out):
    text = open(SCENE).read()
    sim = rondel.Simulation(text=text, overrides={"run.output": out, "run.steps": 10, "run.progress": False})
    sim.step(10)
    assert sim.step_count == 10
    sim.close()
    with pytest.raises(ValueError, match="run.stepz"):
        rondel.Simulation(SCENE, overrides={"run.stepz": 10, "run.output": out + "2"})
    with pytest.raises(ValueError, match="run.dt"):
        rondel.Simulation(SCENE, overrides={"run.dt": "nan", "run.output": out + "3"})
    with pytest.raises(rondel.RondelError, match="section.key"):
        rondel.Simulation(SCENE, overrides={"steps": 10})


def test_import_without_the_compiled_part_reads_and_explains():
    work = tempfile.mkdtemp(prefix="rondel-nodriver-")
    try:
        pkg = os.path.join(work, "lib", "rondel")
        shutil.copytree(os.path.join(ROOT, "tools", "rondel"), pkg, ignore=shutil.ignore_patterns("__pycache__"))
        with open(os.path.join(work, "final.csv"), "w") as f:
            f.write("gid,x,y,vx,vy,theta,omega,radius\n0,0x1p-1,0x1p-2,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x1p-9\n")
        code = ("import rondel, sys\n"
                "t = rondel.read_csv(sys.argv[1])\n"
                "assert t['x'][0] == 0.5, t['x']\n"
                "try:\n    rondel.Simulation('x.ini')\n"
                "except rondel.DriverMissing as e:\n    print('MISSING:', e)\n")
        env = {k: v for k, v in os.environ.items() if k != "RONDEL_DRIVER_DIR"}
        env["PYTHONPATH"] = os.path.join(work, "lib")
        p = subprocess.run([sys.executable, "-c", code, os.path.join(work, "final.csv")], capture_output=True,
                           text=True, env=env, cwd=work)
        assert p.returncode == 0, p.stderr
        assert "MISSING:" in p.stdout and "tools/setup.sh" in p.stdout and "python3-pybind11" in p.stdout
    finally:
        shutil.rmtree(work, ignore_errors=True)


def test_the_scripts_signal_handlers_come_back_after_the_run(out):
    import signal
    sim = deposition(out)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    sim.step(1)
    sim.finish()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    with pytest.raises(KeyboardInterrupt):
        signal.raise_signal(signal.SIGINT)
    sim.close()
