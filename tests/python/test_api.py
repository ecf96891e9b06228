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
