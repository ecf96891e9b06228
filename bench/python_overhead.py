"""The cost of stepping from Python: the 10,000-disc benchmark packing (bench/README.md) run by the executable (A)
and by rondel.Simulation in chunks of --chunk steps (B), as interleaved pairs A B A B ... on a shared machine.
Each run's rate is its own summary.json's disc_steps_per_second (the Runner's clock, from its first step to its
end: the chunks' Python calls are inside it); the ratio B/A is taken pair by pair, and the medians reported.

    /usr/bin/python3 bench/python_overhead.py [--pairs 7] [--steps 5000] [--chunk 100] [--ranks 1]

Run from the repository root after the build (build/rondel, build/python/rondel/_driver*.so). Check `uptime` first.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
PACKING = os.path.join(ROOT, "bench", "jammed10k.csv")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
CHILD = """
import sys
sys.path.insert(0, {tools!r})
import rondel
sim = rondel.Simulation({ini!r}, overrides={overrides!r})
while sim.step_count < {steps}:
    sim.step(min({chunk}, {steps} - sim.step_count))
sim.finish()
sim.close()
"""


def packing_ini(path):
    """The benchmark's scene (src/bench_main.cpp, bench_ini: linear contacts, no rolling resistance) as an INI."""
    with open(PACKING) as f:
        f.readline()
        box = f.readline().split("[")[1].split("]")[0].split(",")
    lo, hi = float(box[0]), float(box[1])
    text = (f"[run]\ndt = 3e-4\nsteps = 0\n[domain]\nxlo = {lo!r}\nxhi = {hi!r}\nylo = {lo!r}\nyhi = {hi!r}\n"
            "periodic_x = true\nperiodic_y = true\n[material]\ndensity = 1\n[contact]\nnormal = linear\n"
            "rolling = none\n[linear]\nk_n = 1e5\nzeta = 0.3\n[coulomb]\nk_s = 28571.43\nmu = 0.5\n"
            f"[scene]\ntype = csv\nfile = {PACKING}\nmax_initial_overlap = 0.2\n")
    with open(path, "w") as f:
        f.write(text)
    return path


def rate(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["disc_steps_per_second"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pairs", type=int, default=7)
    ap.add_argument("--steps", type=int, default=5000)
    ap.add_argument("--chunk", type=int, default=100)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"))
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="rondel-pybench-")
    try:
        ini = packing_ini(os.path.join(work, "bench.ini"))
        overrides = {"run.steps": a.steps, "run.progress": False, "diagnostics.every": 1000,
                     "output.thermo_every": 0, "output.checkpoint_at_end": False, "run.overwrite": True}
        mpi = ["mpirun", "--oversubscribe", "-n", str(a.ranks)]
        pairs = []
        for k in range(a.pairs):
            ex, py = os.path.join(work, "exe"), os.path.join(work, "py")
            cmd_a = mpi + [a.rondel, ini, f"--run.output={ex}"] + [f"--{key}={v}" for key, v in overrides.items()]
            child = CHILD.format(tools=os.path.join(ROOT, "tools"), ini=ini, steps=a.steps, chunk=a.chunk,
                                 overrides=dict(overrides, **{"run.output": py}))
            cmd_b = mpi + [sys.executable, "-c", child]
            for cmd in (cmd_a, cmd_b):
                p = subprocess.run(cmd, env=ENV, capture_output=True, text=True)
                if p.returncode != 0:
                    sys.exit(f"python_overhead.py: {' '.join(cmd[:6])} ... exited {p.returncode}:\n{p.stderr[-2000:]}")
            pairs.append((rate(ex), rate(py)))
            print(f"pair {k + 1}: executable {pairs[-1][0]:.4g}, python {pairs[-1][1]:.4g} disc-steps/s, "
                  f"B/A {pairs[-1][1] / pairs[-1][0]:.4f}", flush=True)
        ratios = [b / x for x, b in pairs]
        print(f"median rate: executable {statistics.median(x for x, _ in pairs):.4g}, python (chunks of {a.chunk}) "
              f"{statistics.median(b for _, b in pairs):.4g} disc-steps/s; median B/A {statistics.median(ratios):.4f} "
              f"(min {min(ratios):.4f}, max {max(ratios):.4f}) over {a.pairs} pairs, {a.ranks} rank(s)")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
