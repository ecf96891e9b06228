"""A run killed with SIGKILL at a random moment and resumed leaves the files of an uninterrupted run, and the
output directory is guarded (README "Resuming a run"):

- 1 rank: final.csv, diagnostics.csv and measures.csv equal the uninterrupted run's byte for byte;
- 2 ranks: final.csv and measures.csv byte for byte; diagnostics.csv byte for byte in every column except
  the three that describe the decomposition (a resume cuts the discs afresh) and the ledger's, whose rank
  shares are summed in another grouping after the new cut: those agree to 1e-9 of the ledger's scale;
- the lock file of the killed run is taken over; a lock held by a live process refuses the directory;
- --resume A --run.output=B refuses a B that holds another run; a resume whose contacts were made 100 times
  stiffer refuses the checkpoint's time step.

Usage: test_kill_resume.py RONDEL MPIEXEC [SEED]
"""
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel_run import Checks  # noqa: E402

STEPS = 6000
# 3,600 discs: about 2e7 disc-steps, long enough (seconds) for the kill to land mid-run on an idle machine.
SCENE = [os.path.join(ROOT, "inputs", "deposition.ini"), f"--run.steps={STEPS}", "--scene.type=lattice_hex",
         "--scene.nx=120", "--scene.ny=30", "--scene.spacing=0.0022", "--scene.radius=0.001", "--scene.x0=0.01",
         "--scene.y0=0.001", "--output.checkpoint_every=300", "--diagnostics.every=50", "--run.progress=false"]
# diagnostics.csv columns that depend on the decomposition, and the ledger's columns.
DECOMPOSITION = {"imbalance", "ghost_fraction", "migrated"}
LEDGER = {"W_gravity", "W_walls", "W_normal", "W_tangential", "W_rolling", "E_stored", "D_slip", "D_rolling_plastic",
          "D_rolling_dashpot", "E_rolling_break", "D_normal_hysteresis", "W_cell", "W_driver", "D_other",
          "ledger_residual"}


def command(rondel, mpiexec, ranks, args):
    return [mpiexec, "--oversubscribe", "-n", str(ranks), rondel] + args


def run(cmd, env):
    return subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)


def checkpoints(out):
    return sorted(n for n in os.listdir(out) if n.startswith("checkpoint_") and n.endswith(".h5")) \
        if os.path.isdir(out) else []


def kill_run(cmd, env, out, rng):
    """Starts cmd in its own process group and kills the group with SIGKILL once the checkpoint of a random
    step (600 to half the run) is there, after a random further delay of up to 50 ms; returns whether the run
    was still going (no summary.txt)."""
    target = rng.randrange(600, STEPS // 2 + 1, 300)
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, cwd=ROOT,
                         start_new_session=True)
    deadline = time.time() + 300
    while time.time() < deadline and p.poll() is None:
        if any(int(n[11:21]) >= target for n in checkpoints(out)):
            break
        time.sleep(0.005)
    time.sleep(rng.uniform(0.0, 0.05))
    try:
        os.killpg(p.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    p.wait()
    # The launcher may start the ranks in a session of their own: kill every process of this run, as a crash
    # of the node would, and wait until they are gone (an orphaned rank holds the directory's lock).
    deadline = time.time() + 30
    while time.time() < deadline:
        running = run_processes(out)
        if not running:
            break
        for pid in running:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        time.sleep(0.05)
    return not os.path.exists(os.path.join(out, "summary.txt"))


def run_processes(out):
    """The live (not zombie) processes whose command line names --run.output=OUT."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                args = f.read().split(b"\0")
            with open(f"/proc/{entry}/stat") as f:
                state = f.read().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if state != "Z" and f"--run.output={out}".encode() in args:
            found.append(int(entry))
    return found


def read(path):
    with open(path, "rb") as f:
        return f.read()


def diagnostics_agree(a, b):
    """Every column of every row equal as text, but the decomposition's (any value) and the ledger's (within
    1e-9 of the largest ledger magnitude); returns '' or what differs."""
    la, lb = read(a).decode().splitlines(), read(b).decode().splitlines()
    if len(la) != len(lb) or la[0] != lb[0]:
        return f"{len(la)} against {len(lb)} lines, or other headers"
    names = la[0].split(",")
    scale = max(abs(float(v)) for line in la[1:] for n, v in zip(names, line.split(",")) if n in LEDGER) or 1.0
    for line_a, line_b in zip(la[1:], lb[1:]):
        for n, x, y in zip(names, line_a.split(","), line_b.split(",")):
            if n in DECOMPOSITION or x == y:
                continue
            if n in LEDGER and abs(float(x) - float(y)) <= 1e-9 * scale:
                continue
            return f"column {n}: {x} against {y} (row of step {line_a.split(',')[0]})"
    return ""


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    rondel, mpiexec = sys.argv[1], sys.argv[2]
    rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 12)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    check = Checks()
    work = tempfile.mkdtemp(prefix="rondel_kill_")
    try:
        for ranks in (1, 2):
            whole, killed = os.path.join(work, f"whole{ranks}"), os.path.join(work, f"killed{ranks}")
            p = run(command(rondel, mpiexec, ranks, SCENE + [f"--run.output={whole}"]), env)
            check(f"{ranks} rank(s): the uninterrupted run completes", p.returncode == 0, p.stdout + p.stderr)
            was_running = kill_run(command(rondel, mpiexec, ranks, SCENE + [f"--run.output={killed}"]), env, killed,
                                   rng)
            check(f"{ranks} rank(s): killed before its end, after a checkpoint", was_running and checkpoints(killed),
                  f"running {was_running}, checkpoints {checkpoints(killed)}")
            p = run(command(rondel, mpiexec, ranks, ["--resume", killed]), env)
            check(f"{ranks} rank(s): the resume completes (the killed run's lock taken over)", p.returncode == 0,
                  p.stdout + p.stderr)
            check(f"{ranks} rank(s): no lock file left", not os.path.exists(os.path.join(killed, "rondel.lock")))
            exact = ["final.csv", "measures.csv"] + (["diagnostics.csv"] if ranks == 1 else [])
            for name in exact:
                a, b = os.path.join(whole, name), os.path.join(killed, name)
                same = os.path.exists(b) and read(a) == read(b)
                check(f"{ranks} rank(s): {name} byte for byte", same, f"{a} and {b} differ")
            if ranks == 2:
                why = diagnostics_agree(os.path.join(whole, "diagnostics.csv"), os.path.join(killed, "diagnostics.csv"))
                check("2 ranks: diagnostics.csv equal but the decomposition's columns and the ledger's last digits",
                      not why, why)
        whole = os.path.join(work, "whole1")
        # A directory locked by a live process (this one) is refused, even with run.overwrite.
        locked = os.path.join(work, "locked")
        os.makedirs(locked)
        with open(os.path.join(locked, "rondel.lock"), "w") as f:
            f.write(f"{os.getpid()} {os.uname().nodename}\n")
        p = run(command(rondel, mpiexec, 1, SCENE + [f"--run.output={locked}", "--run.overwrite=true"]), env)
        check("a directory locked by a live process is refused", p.returncode == 1 and "in use" in p.stderr,
              f"exit {p.returncode}: {p.stderr}")
        check("... and nothing is written into it", sorted(os.listdir(locked)) == ["rondel.lock"],
              str(os.listdir(locked)))
        # --resume A --run.output=B where B holds another run.
        before = sorted(os.listdir(whole))
        p = run(command(rondel, mpiexec, 1, ["--resume", os.path.join(work, "killed1"), f"--run.output={whole}",
                                             f"--run.steps={STEPS + 300}"]), env)
        check("--resume A --run.output=B refuses a B that holds another run",
              p.returncode == 1 and "not the directory of the run being resumed" in p.stderr,
              f"exit {p.returncode}: {p.stderr}")
        check("... and B is left as it was", sorted(os.listdir(whole)) == before)
        # A resume with contacts 100 times stiffer: the checkpoint's step is above the new critical step.
        p = run(command(rondel, mpiexec, 1, ["--resume", whole, f"--run.steps={STEPS + 300}", "--linear.k_n=2e8"]), env)
        check("a resume 100 times stiffer refuses the checkpoint's time step",
              p.returncode == 1 and "critical time step" in p.stderr, f"exit {p.returncode}: {p.stderr}")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
