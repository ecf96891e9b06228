#!/usr/bin/env python3
"""The set-up audit (docs/scaling.md, "Set-up"): what the set-up of a run takes on its largest rank, on 1, 2, 4 and
8 ranks (oversubscribed), for a generated scene, the same discs read from a CSV file and from a quarter of it
replicated 2 x 2, as many placed at random (random_tiles), a restart from a checkpoint and a new stage from it
(scene.type = file) (strong: 160,000 discs), and for a generated scene of 20,000 discs per rank (weak). Bytes are the
growth of the largest rank's resident set during the set-up (its peak less what it held before), seconds the slowest rank's.

    /usr/bin/python3 tests/audit/setup_audit.py --exe build/tests/rondel_scaling_audit --work /tmp/setup-audit

It prints a table and the ratio of each row's bytes to the 1-rank row's; it checks nothing (issue 31 is to make the
strong rows fall as 1/P and the weak ones stay flat). Exit 0 when every run completed.

    /usr/bin/python3 tests/audit/setup_audit.py --exe build/tests/rondel_scaling_audit --work /tmp/setup-audit \
        --speedup 3163 --pairs 5

times the set-up of a SIDE x SIDE lattice (3163: ten million discs, 0 steps) on 1 and on 2 ranks as interleaved
pairs (1 2 1 2 ...) and prints each pair's ratio, the medians and the largest rank's set-up bytes; with
--random, of as many discs placed at random (scene.type = random_tiles) in the same box. The byte tables are
counted in 4 KiB pages (RONDEL_HUGE_PAGES=0); --speedup runs as rondel does, with huge pages. On a virtual
machine whose balloon hands freed memory back to the host, a run's time depends on how long ago its memory was
freed: --memory cold or reused makes every run start alike (see prepare_memory; docs/scaling.md, "What bounds the
ratio here"), and --memory in-job times the pairs in one 2-rank job, seconds apart, on reused memory.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time

RANKS = [1, 2, 4, 8]
LATTICE = """[run]
steps = 1
[domain]
xlo = 0
xhi = {xhi}
ylo = 0
yhi = {yhi}
periodic_x = true
periodic_y = true
[material]
density = 2650
[linear]
k_n = 2e6
e = 0.5
[coulomb]
k_s = 1.5e6
mu = 0.5
[scene]
"""
GENERATED = """type = lattice_square
nx = {nx}
ny = {ny}
radius = 0.00049
spacing = 0.001
x0 = 0.0005
y0 = 0.0005
"""
# The same number of discs placed at random, tile by tile, in the lattice's box (packing fraction 0.33).
TILES = """type = random_tiles
count = {count}
radius_min = 0.0003
radius_max = 0.00035
"""
CSV = """type = csv
file = {file}
"""
# A quarter of the lattice (SIDE/2 x SIDE/2) copied 2 x 2 times: the same discs.
REPLICATED = """type = csv
file = {file}
replicate_x = 2
replicate_y = 2
"""


def prepare_memory(args, env, extra):
    """--memory: on a virtual machine whose balloon reports free pages to the host (virtio-balloon free page
    reporting, as here), memory freed more than about 2 s ago is handed back, and the next process to touch it pays
    a host fault a page: touching 2.4 GB took 0.25 s right after another process had freed as much and 3.7 to
    5.2 s otherwise. Whichever of a pair runs right after the other finds warm memory, so the pairs are only
    comparable when every run starts alike: 'cold' waits 6 s before each run, so that every run pays the host for
    all it touches; 'reused' sets the scene up twice in one process, malloc keeping what the first set-up freed
    (no mmap, no trim), and times the second, as on a machine where fresh memory costs what used memory does;
    'in-job' keeps memory so too, for the pairs of one job (in_job)."""
    if args.memory == "cold":
        time.sleep(6)
    elif args.memory in ("reused", "in-job"):
        env.update(MALLOC_MMAP_MAX_="0", MALLOC_TRIM_THRESHOLD_=str(1 << 40))
        extra.append("--setup-twice" if args.memory == "reused" else "--paired-setups=%d" % args.pairs)


def run(args, ranks, ini, out, extra=(), steps="1"):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if not args.speedup:  # the byte tables in 4 KiB pages (a huge page rounds a small rank's growth up by 2 MiB)
        env["RONDEL_HUGE_PAGES"] = "0"
    shutil.rmtree(out, ignore_errors=True)
    extra = list(extra)
    prepare_memory(args, env, extra)
    exported = [a for k in env if k.startswith("MALLOC_") for a in ("-x", k)]
    bind = ["--bind-to", args.bind_to] if args.bind_to else []
    cmd = [args.mpiexec, "-n", str(ranks), "--oversubscribe"] + bind + exported + [args.exe, ini, steps, out] + extra
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
    if p.returncode != 0:
        sys.exit("setup_audit.py: %s exited %d\n%s\n%s" % (" ".join(cmd), p.returncode, p.stdout, p.stderr))
    for line in p.stdout.splitlines():
        if line.startswith("{"):
            return json.loads(line)
    sys.exit("setup_audit.py: no result line from %s\n%s" % (" ".join(cmd), p.stdout))


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


def scene(args, name, nx, ny, body):
    return write(os.path.join(args.work, name + ".ini"), LATTICE.format(xhi=nx * 0.001, yhi=ny * 0.001) + body)


def lattice_csv(path, nx, ny):
    with open(path, "w") as f:
        f.write("id,x,y,radius\n")
        for j in range(ny):
            for i in range(nx):
                f.write("%d,%r,%r,0.00049\n" % (j * nx + i, 0.0005 + 0.001 * i, 0.0005 + 0.001 * j))
    return path


def table(title, rows):
    print(title)
    print("  %5s %9s %13s %9s %12s %10s" % ("ranks", "discs", "set-up bytes", "x 1 rank", "bytes/disc", "seconds"))
    base = rows[0]["setup_bytes"]
    for r in rows:
        print("  %5d %9d %13d %9.3f %12.1f %10.3f" % (r["ranks"], r["discs"], r["setup_bytes"], r["setup_bytes"] / base,
                                                      r["setup_bytes"] / r["discs"], r["setup_seconds"]))


def in_job(args, ini):
    """--memory in-job: the pairs from one 2-rank job (rondel_scaling_audit --paired-setups), each a set-up on rank 0
    alone (the other rank asleep) and one on both, seconds apart, alternately first, after an untimed one of each; the
    host's slow and fast minutes then fall on both of a pair."""
    r = run(args, 2, ini, os.path.join(args.work, "speedup-in-job"), ["--output.checkpoint_at_end=false"], steps="0")
    for k, (a, b) in enumerate(zip(r["one"], r["all"])):
        print("  pair %d: 1 rank %.3f s, 2 ranks %.3f s, ratio %.2f" % (k + 1, a, b, a / b))
    ratios = [a / b for a, b in zip(r["one"], r["all"])]
    print("median: 1 rank %.3f s, 2 ranks %.3f s, ratio %.2f (%.2f to %.2f)" % (
        statistics.median(r["one"]), statistics.median(r["all"]), statistics.median(ratios), min(ratios), max(ratios)))
    return 0


def speedup(args):
    """Interleaved 1-rank and 2-rank set-ups of one large lattice: pair ratios and medians."""
    n = args.speedup
    body = TILES.format(count=n * n) if args.random else GENERATED.format(nx=n, ny=n)
    ini = scene(args, "speedup", n, n, body)
    one, two = [], []
    print("uptime: %s; memory before each run: %s; binding: %s" % (
        open("/proc/loadavg").read().split()[:3], args.memory, args.bind_to or "mpirun's default"))
    print("%d discs (%s), 0 steps; set-up seconds (slowest rank), pair by pair:" %
          (n * n, "random_tiles" if args.random else "lattice_square %d x %d" % (n, n)))
    if args.memory == "in-job":
        return in_job(args, ini)
    for k in range(args.pairs):
        no_checkpoint = ["--output.checkpoint_at_end=false"]
        a = run(args, 1, ini, os.path.join(args.work, "speedup-1"), no_checkpoint, steps="0")
        b = run(args, 2, ini, os.path.join(args.work, "speedup-2"), no_checkpoint, steps="0")
        one.append(a)
        two.append(b)
        first = "" if args.memory != "reused" else " (first set-ups %.3f s and %.3f s)" % (
            a["first_setup_seconds"], b["first_setup_seconds"])
        print("  pair %d: 1 rank %.3f s, 2 ranks %.3f s, ratio %.2f%s" %
              (k + 1, a["setup_seconds"], b["setup_seconds"], a["setup_seconds"] / b["setup_seconds"], first))
    ratios = [a["setup_seconds"] / b["setup_seconds"] for a, b in zip(one, two)]
    print("median: 1 rank %.3f s (%.0f MB), 2 ranks %.3f s (%.0f MB on the largest rank), ratio %.2f" %
          (statistics.median(r["setup_seconds"] for r in one), one[0]["setup_bytes"] / 1e6,
           statistics.median(r["setup_seconds"] for r in two), two[0]["setup_bytes"] / 1e6, statistics.median(ratios)))
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--side", type=int, default=400, help="the strong lattice is SIDE x SIDE discs (default 400)")
    ap.add_argument("--speedup", type=int, default=0, metavar="SIDE",
                    help="instead: 1- and 2-rank set-up of a SIDE x SIDE lattice as interleaved pairs")
    ap.add_argument("--pairs", type=int, default=5, help="pairs of --speedup (default 5)")
    ap.add_argument("--random", action="store_true", help="--speedup of a random packing (random_tiles), not a lattice")
    ap.add_argument("--bind-to", default="", metavar="WHAT",
                    help="mpirun --bind-to WHAT (default: mpirun's own, a rank per core: on this VM rank 0 then runs on "
                         "the vCPU that takes three times the other's timer interrupts and the kernel's DAMON thread; "
                         "'none' lets the scheduler move it)")
    ap.add_argument("--memory", choices=["as-is", "cold", "reused", "in-job"], default="as-is",
                    help="--speedup: each run as it comes (as-is, the default), after a 6 s wait (cold), the second "
                         "of two set-ups in one process (reused; see prepare_memory), or every pair in one 2-rank job "
                         "on reused memory (in-job; see in_job)")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    if args.speedup:
        return speedup(args)
    n = args.side
    generated = scene(args, "generated", n, n, GENERATED.format(nx=n, ny=n))
    csv_file = lattice_csv(os.path.join(args.work, "lattice.csv"), n, n)
    from_csv = scene(args, "csv", n, n, CSV.format(file=csv_file))
    tiles = scene(args, "tiles", n, n, TILES.format(count=n * n))
    quarter = lattice_csv(os.path.join(args.work, "quarter.csv"), n // 2, n // 2)
    replicated = scene(args, "replicated", n, n, REPLICATED.format(file=quarter))
    strong, csv_rows, restart, random_rows, replicated_rows = [], [], [], [], []
    for p in RANKS:
        out = os.path.join(args.work, "generated-%d" % p)
        strong.append(run(args, p, generated, out))
        csv_rows.append(run(args, p, from_csv, os.path.join(args.work, "csv-%d" % p)))
        random_rows.append(run(args, p, tiles, os.path.join(args.work, "tiles-%d" % p)))
        replicated_rows.append(run(args, p, replicated, os.path.join(args.work, "replicated-%d" % p)))
    checkpoint_dir = os.path.join(args.work, "generated-1")  # its checkpoint at step 1
    for p in RANKS:
        restart.append(run(args, p, generated, os.path.join(args.work, "restart-%d" % p),
                           ["--resume", checkpoint_dir, "--run.steps=2"]))
    table("strong, %d discs generated (lattice_square):" % (n * n), strong)
    table("strong, the same discs read from a CSV file:", csv_rows)
    table("strong, the same discs from a quarter of them copied 2 x 2 times (replicated CSV):", replicated_rows)
    table("strong, as many discs placed at random (random_tiles):", random_rows)
    stage = [run(args, p, generated, os.path.join(args.work, "stage-%d" % p),
                 ["--scene.type=file", "--scene.file=" + checkpoint_dir]) for p in RANKS]
    table("strong, a restart from the 1-rank run's checkpoint:", restart)
    table("strong, a new stage from it (scene.type = file):", stage)
    weak = []
    sizes = {1: (200, 100), 2: (200, 200), 4: (400, 200), 8: (400, 400)}
    for p in RANKS:
        ini = scene(args, "weak%d" % p, *sizes[p], GENERATED.format(nx=sizes[p][0], ny=sizes[p][1]))
        weak.append(run(args, p, ini, os.path.join(args.work, "weak-%d" % p)))
    table("weak, 20,000 discs per rank generated:", weak)
    return 0


if __name__ == "__main__":
    sys.exit(main())
