"""rondel.Simulation under mpirun gives the executable's bits (issue: the Python driver; docs/python.md).

- the deposition scene stepped from Python in chunks of 100 on 1, 2 and 3 ranks: final.csv, diagnostics.csv and
  measures.csv byte for byte those of the executable on as many ranks, and final.csv that of 1 rank;
- a communicator passed in (MPI.COMM_SELF on each of 2 ranks): each rank's run is the executable's on 1 rank;
- resumed from Python (on 2 ranks) from the executable's checkpoint: the uninterrupted run's final.csv;
- a script's writes (fixing, freeing, velocities and spins by gid) give the same final.csv on 1 and 3 ranks, and
  their energy is booked (W_driver), so the ledger still closes;
- a script stopped by SIGTERM exits with 10 after a checkpoint that the executable resumes bitwise on 2 ranks;
- every setter refuses bad values on 2 ranks alike (tests/python/refusals.py).

Run by CTest (label python) with RONDEL (the executable) and MPIEXEC in the environment.
"""
import csv
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
RONDEL = os.environ.get("RONDEL", os.path.join(ROOT, "build", "rondel"))
MPIEXEC = os.environ.get("MPIEXEC", "mpiexec")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
SCENE = os.path.join(ROOT, "inputs", "deposition.ini")
STEPS = 2400


def mpirun(ranks, args, timeout=600):
    p = subprocess.run([MPIEXEC, "--oversubscribe", "-n", str(ranks)] + [str(a) for a in args], env=ENV,
                       capture_output=True, text=True, timeout=timeout)
    return p


def ok(p):
    assert p.returncode == 0, f"exit {p.returncode}:\n{p.stdout[-3000:]}\n{p.stderr[-3000:]}"
    return p


def executable(ranks, out, *args):
    return ok(mpirun(ranks, [RONDEL, SCENE, f"--run.output={out}", "--run.progress=false"] + list(args)))


def script(ranks, out, steps, chunk, *args, timeout=600):
    return mpirun(ranks, [sys.executable, os.path.join(HERE, "drive_scene.py"), out, steps, chunk] + list(args),
                  timeout=timeout)


def read(path):
    with open(path, "rb") as f:
        return f.read()


@pytest.fixture(scope="module")
def tmp():
    d = tempfile.mkdtemp(prefix="rondel-driver-")
    yield d
    shutil.rmtree(d, ignore_errors=True)


@pytest.fixture(scope="module")
def one_rank(tmp):
    out = os.path.join(tmp, "exe1")
    executable(1, out, f"--run.steps={STEPS}")
    return out


@pytest.mark.parametrize("ranks", [1, 2, 3])
def test_script_gives_the_executables_bits(tmp, one_rank, ranks):
    exe = one_rank if ranks == 1 else os.path.join(tmp, f"exe{ranks}")
    if ranks > 1:
        executable(ranks, exe, f"--run.steps={STEPS}")
    py = os.path.join(tmp, f"py{ranks}")
    ok(script(ranks, py, STEPS, 100))
    for name in ("final.csv", "diagnostics.csv", "measures.csv"):
        assert read(os.path.join(py, name)) == read(os.path.join(exe, name)), f"{name} differs on {ranks} ranks"
    assert read(os.path.join(py, "final.csv")) == read(os.path.join(one_rank, "final.csv"))


def test_a_communicator_passed_in(tmp, one_rank):
    """Two ranks, each with a simulation of its own on MPI.COMM_SELF: each is the executable's run on 1 rank."""
    out = os.path.join(tmp, "self")
    ok(script(2, out, STEPS, 100, "--self"))
    for r in (0, 1):
        assert read(f"{out}.rank{r}/final.csv") == read(os.path.join(one_rank, "final.csv"))


def test_resumed_script_gives_the_uninterrupted_bits(tmp, one_rank):
    half = os.path.join(tmp, "half")
    executable(1, half, f"--run.steps={STEPS // 2}")  # its checkpoint at the end, step STEPS / 2
    resumed = os.path.join(tmp, "resumed")
    ok(script(2, resumed, STEPS, 100, "--resume", half))
    assert read(os.path.join(resumed, "final.csv")) == read(os.path.join(one_rank, "final.csv"))


def diagnostics_rows(path):
    with open(os.path.join(path, "diagnostics.csv")) as f:
        return list(csv.DictReader(f))


def test_writes_give_the_same_bits_on_any_rank_count_and_close_the_ledger(tmp):
    runs = {}
    for ranks in (1, 3):
        runs[ranks] = os.path.join(tmp, f"steer{ranks}")
        ok(script(ranks, runs[ranks], STEPS, 100, "--steer"))
    assert read(os.path.join(runs[1], "final.csv")) == read(os.path.join(runs[3], "final.csv"))
    rows = diagnostics_rows(runs[1])
    before = [r for r in rows if int(r["step"]) <= 600]
    after = [r for r in rows if int(r["step"]) > 600]
    assert all(float(r["W_driver"]) == 0.0 for r in before[:-1])
    # 50 discs of 0.001 m radius given 0.3 m/s and 5 rad/s, less the kinetic energy of the 10 fixed ones: > 0
    assert float(after[-1]["W_driver"]) > 0.0
    # The residual (the integration error, over the energy scale) stays below 1 % of the booked work over the same
    # scale: unbooked, the writes would leave a residual of W_driver / scale (about 0.02 here).
    scale = max(float(r["W_gravity"]) for r in rows)
    W_driver = float(after[-1]["W_driver"])
    assert max(float(r["ledger_residual"]) for r in rows) < 0.01 * W_driver / scale, "the writes are not in the ledger"
    # the discs fixed at step 600 and never freed (5-9) end where they were fixed: their rows in both runs agree
    # (checked by the bytes above); on 1 rank they are at rest
    final = [r for r in csv.reader(open(os.path.join(runs[1], "final.csv"))) if r and r[0].isdigit()]
    by_gid = {int(r[0]): r for r in final}
    for g in range(5, 10):
        assert float.fromhex(by_gid[g][3]) == 0.0 and float.fromhex(by_gid[g][4]) == 0.0, f"fixed disc {g} moves"


def test_sigterm_leaves_a_checkpoint_that_the_executable_resumes_bitwise(tmp):
    out = os.path.join(tmp, "killed")
    # One rank started without mpirun (a singleton), so that the signal reaches the script itself, as a batch
    # system's does; the executable resumes it on 2 ranks.
    p = subprocess.Popen([sys.executable, os.path.join(HERE, "drive_scene.py"), out, "100000", "50", "--forever",
                          "--diagnostics.every=50"], env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    diag = os.path.join(out, "diagnostics.csv")
    deadline = time.time() + 120
    while time.time() < deadline:  # stepping (rows past step 300 written), then the signal
        if os.path.exists(diag) and sum(1 for _ in open(diag)) > 8:
            break
        time.sleep(0.05)
    p.send_signal(signal.SIGTERM)
    stdout, stderr = p.communicate(timeout=120)
    assert p.returncode == 10, f"exit {p.returncode}:\n{stdout[-2000:]}\n{stderr[-2000:]}"
    checkpoints = sorted(f for f in os.listdir(out) if f.startswith("checkpoint_") and f.endswith(".h5"))
    assert checkpoints, "no checkpoint after SIGTERM"
    stopped_at = int(checkpoints[-1][len("checkpoint_"):-3])
    end = stopped_at + 300
    assert "stopped by SIGTERM" in stderr + stdout
    ok(mpirun(2, [RONDEL, "--resume", out, f"--run.steps={end}", "--run.progress=false"]))
    straight = os.path.join(tmp, "straight")
    executable(1, straight, f"--run.steps={end}", "--diagnostics.every=50")
    assert read(os.path.join(out, "final.csv")) == read(os.path.join(straight, "final.csv"))


def test_setters_refuse_bad_values_on_every_rank(tmp):
    ok(mpirun(2, [sys.executable, os.path.join(HERE, "refusals.py"), os.path.join(tmp, "refusals")]))
