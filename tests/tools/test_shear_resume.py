"""A simple-shear run of the periodic cell to a shear strain of 20, stopped by SIGTERM half-way and resumed on
another rank count, ends in the bits of the uninterrupted run (docs/physics.md section 10):

- the sample: inputs/periodic_prepare.ini (300 discs in a 4.4 cm cell, the scene's packing fraction), then
  inputs/periodic_shear.ini at I = 0.03 with the servo holding S_yy: 170,000 steps, 20 flips of the cell;
- the uninterrupted run (1 rank) reaches the strain with its flips;
- the same run, sent SIGTERM between 30 % and 70 % of its steps, writes a checkpoint and exits 10;
- --resume on 2 ranks completes; final.csv and measures.csv equal the uninterrupted run's byte for byte.

--long: the scenes as they are (1000 discs, I = 0.01, 520,000 steps; a minute or two).

Usage: test_shear_resume.py RONDEL MPIEXEC [--long]
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel_run import Checks  # noqa: E402

PREPARE = os.path.join(ROOT, "inputs", "periodic_prepare.ini")
SHEAR = os.path.join(ROOT, "inputs", "periodic_shear.ini")
SMALL_PREPARE = ["--scene.count=300", "--domain.xhi=0.044", "--domain.yhi=0.044"]
# I = 0.03 at 1e5 Pa: rate_xy = 92.1 /s; the servo's gain and largest rate scaled with it (tools/mu_i.py).
SMALL_SHEAR = ["--cell.rate_xy=92.1", "--cell.servo_gain=15", "--cell.servo_max_rate=15", "--run.steps=170000",
               "--diagnostics.every=5000"]
LONG_STEPS = 520000


def run(cmd, env):
    return subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def last_row(path):
    lines = read(path).decode().splitlines()
    return dict(zip(lines[0].split(","), lines[-1].split(",")))


def progress_step(out):
    """The step of the newest line of OUT/log.txt's progress table (0 before the first)."""
    try:
        lines = read(os.path.join(out, "log.txt")).decode().splitlines()
    except OSError:
        return 0
    for line in reversed(lines):
        parts = line.split()
        if parts and parts[0].isdigit():
            return int(parts[0])
    return 0


def stopped_run(cmd, env, out, lo, hi):
    """Starts CMD and sends it SIGTERM once its progress passes step LO; (exit code, stdout + stderr, whether the
    signal was sent before step HI)."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env, cwd=ROOT)
    deadline, sent_at = time.time() + 600, -1
    while time.time() < deadline and p.poll() is None:
        step = progress_step(out)
        if step >= lo:
            p.send_signal(signal.SIGTERM)
            sent_at = step
            break
        time.sleep(0.01)
    text, _ = p.communicate(timeout=600)
    return p.returncode, text, 0 <= sent_at < hi


def main():
    args = [a for a in sys.argv[1:] if a != "--long"]
    if len(args) != 2:
        print(__doc__)
        return 2
    rondel, mpiexec = args
    long = "--long" in sys.argv
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    check = Checks()
    work = tempfile.mkdtemp(prefix="rondel_shear_resume_")
    try:
        prep = os.path.join(work, "prepare")
        p = run([rondel, PREPARE, f"--run.output={prep}", "--run.progress=false"] + ([] if long else SMALL_PREPARE),
                env)
        check("the sample is prepared", p.returncode == 0, p.stdout + p.stderr)
        steps = LONG_STEPS if long else 170000
        shear = [SHEAR, f"--scene.file={prep}", "--run.progress=false", "--output.thermo_every=1000"] + \
            ([] if long else SMALL_SHEAR)
        whole, stopped = os.path.join(work, "whole"), os.path.join(work, "stopped")
        p = run([rondel] + shear + [f"--run.output={whole}"], env)
        check("the uninterrupted run completes", p.returncode == 0, p.stdout + p.stderr)
        if p.returncode == 0:
            row = last_row(os.path.join(whole, "measures.csv"))
            strain, lx = float(row["shear_strain"]), float(row["cell_lx"])
            check(f"a shear strain of 20 or more ({strain:.2f}) and the tilt inside half the width",
                  strain >= 20.0 and abs(float(row["cell_tilt"])) <= 0.5 * lx, str(row))
        rc, text, in_time = stopped_run([rondel] + shear + [f"--run.output={stopped}"], env, stopped,
                                        int(0.3 * steps), int(0.7 * steps))
        check("SIGTERM half-way writes a checkpoint and exits 10", rc == 10 and in_time, f"exit {rc}: {text}")
        log = read(os.path.join(stopped, "log.txt")).decode() if os.path.exists(stopped) else ""
        check("the log says where it stopped", "stopped by SIGTERM at step" in log, log[-400:])
        p = run([mpiexec, "--oversubscribe", "-n", "2", rondel, "--resume", stopped], env)
        check("2 ranks: --resume completes", p.returncode == 0, p.stdout + p.stderr)
        for name in ("final.csv", "measures.csv"):
            a, b = os.path.join(whole, name), os.path.join(stopped, name)
            same = os.path.exists(a) and os.path.exists(b) and read(a) == read(b)
            check(f"{name} of the run resumed on 2 ranks equals the uninterrupted run's byte for byte", same, f"{a} and {b}")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
