"""A tiny run of the current build for the tool tests: 50 discs of a hexagonal lattice resting on the floor of
inputs/deposition.ini (gravity, box walls bottom left right), 300 steps, snapshots every 100 steps and
checkpoints every 150, diagnostics every 50. Loaded disc-disc and wall contacts from the first step."""
import os
import subprocess

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
STEPS = 300
OVERRIDES = ["--run.steps=300", "--scene.type=lattice_hex", "--scene.nx=10", "--scene.ny=5", "--scene.spacing=0.004",
             "--scene.radius=0.002", "--scene.x0=0.01", "--scene.y0=0.002", "--output.snapshot_every=100",
             "--output.checkpoint_every=150", "--diagnostics.every=50", "--run.overwrite=true"]


def make_run(rondel, out):
    """Run RONDEL into OUT; returns OUT. Raises RuntimeError with rondel's output when it fails."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [rondel, os.path.join(ROOT, "inputs", "deposition.ini"), f"--run.output={out}"] + OVERRIDES
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} exited with {p.returncode}:\n{p.stdout}\n{p.stderr}")
    return out


def run_tool(tool, *args, timeout=600):
    """Runs the Python tool TOOL with ARGS (MPI allowed as root): (exit code, stdout, stderr)."""
    import sys
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([sys.executable, tool] + [str(x) for x in args], capture_output=True, text=True, env=env,
                       timeout=timeout)
    return p.returncode, p.stdout, p.stderr


class Checks:
    """PASS/FAIL lines, one per check, and the closing 'N passed, N failed' line with its exit status."""

    def __init__(self):
        self.results = []

    def __call__(self, name, cond, detail=""):
        self.results.append(bool(cond))
        print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))

    def summary(self):
        passed = sum(self.results)
        print(f"{passed} passed, {len(self.results) - passed} failed")
        return 0 if self.results and passed == len(self.results) else 1

