"""The scripts of examples/python/ on 2 ranks with --quick, and what each must show (docs/python.md, "Examples"):
the cyclic biaxial test reverses at its two deviator levels, the pour releases every disc at the rate it set (halved
while the pile splashes), the in-situ series ends at the deposition's documented coordination, every disc at rest,
and the bonded cantilever comes to rest on the discrete chain's exact solution (1e-6).

Run by CTest (label python) with MPIEXEC in the environment.
"""
import csv
import os
import shutil
import subprocess
import sys
import tempfile

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MPIEXEC = os.environ.get("MPIEXEC", "mpiexec")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


@pytest.fixture
def out():
    d = tempfile.mkdtemp(prefix="rondel-examples-")
    yield d
    shutil.rmtree(d, ignore_errors=True)


def run_example(name, out):
    p = subprocess.run([MPIEXEC, "--oversubscribe", "-n", "2", sys.executable,
                        os.path.join(ROOT, "examples", "python", name), "--quick", "--out", out],
                       env=ENV, capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, f"{name} exited {p.returncode}:\n{p.stdout[-3000:]}\n{p.stderr[-3000:]}"
    return p.stdout


def rows(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def test_cyclic_biaxial_reverses_at_its_levels(out):
    text = run_example("cyclic_biaxial.py", out)
    assert text.count("unload") == 1 and text.count("reload") == 1
    r = rows(os.path.join(out, "cyclic.csv"))
    q = [x["q"] for x in r]
    top = q.index(max(q))
    assert 120e3 < max(q) < 130e3, "unloading began at the first look above q_high"
    assert 10e3 < min(q[top:]) < 20e3, "reloading began at the first look below q_low"
    assert r[-1]["eps_axial"] < r[top]["eps_axial"], "unloading recovers strain"
    assert os.path.isfile(os.path.join(out, "cyclic.png"))


def test_scripted_pour_releases_at_the_rate_it_set(out):
    run_example("scripted_pour.py", out)
    r = rows(os.path.join(out, "pour.csv"))
    released = [x["released"] for x in r]
    assert released == sorted(released) and released[-1] == 300
    rates = {x["rate"] for x in r}
    assert 750.0 in rates and 1500.0 in rates, "the full rate and the halved one were both set"
    assert r[-1]["kinetic_energy"] < 0.1 * max(x["kinetic_energy"] for x in r), "the pile did not settle"


def test_coordination_series_ends_at_the_depositions_coordination(out):
    run_example("coordination_series.py", out)
    r = rows(os.path.join(out, "coordination.csv"))
    assert r[0]["coordination"] < 0.1 and r[0]["moving_fraction"] > 0.9
    assert 3.0 < r[-1]["coordination"] < 3.5
    assert os.path.isfile(os.path.join(out, "coordination.png"))


def test_bonded_cantilever_is_the_exact_chain(out):
    run_example("bonded_cantilever.py", out)
    r = rows(os.path.join(out, "cantilever.csv"))
    assert len(r) == 21 and r[0]["deflection"] == 0.0 and r[0]["rotation"] == 0.0, "the first disc is held"
    for x in r[1:]:
        assert abs(x["deflection"] / x["deflection_exact"] - 1.0) < 1e-6
        assert abs(x["rotation"] / x["rotation_exact"] - 1.0) < 1e-6
    assert os.path.isfile(os.path.join(out, "cantilever.png"))
