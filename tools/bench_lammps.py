#!/usr/bin/python3
"""Rondel beside LAMMPS on the standard benchmark packing: the same discs, the same contact laws as far as
the two codes share them, the same time step and step counts, run as interleaved trials on one machine.

  /usr/bin/python3 tools/bench_lammps.py [--discs 10000[,160000...]] [--steps 5000] [--warmup 1000]
      [--trials 5] [--ranks 1] [--rondel build/rondel_bench] [--lmp lmp] [--workdir DIR] [--keep]
      [--packing bench/jammed10k.csv] [--no-stream] [--shear RATE]

For each disc count N (10,000 times nx x ny periodic copies of the packing, as `rondel_bench --discs N`
makes them) it writes the packing as a LAMMPS data file and two LAMMPS inputs into the work directory, then
runs, per round and in this order,
    rondel_bench --rolling wang, LAMMPS pair granular with rolling sds, rondel_bench --rolling none,
    LAMMPS pair gran/hooke/history,
for --trials rounds, with the same warm-up and timed steps for both codes (1 rank pinned to one core with
taskset, or each under `mpirun -n P --bind-to core` with --ranks P). It prints `uptime` first, every trial's disc-steps per second (LAMMPS: atoms x
steps / the timed run's "Loop time"), their medians, the ratios of the medians and the medians of the
per-round ratios, and the phase breakdown of both codes in the last round. Without LAMMPS (`lmp` not
found, or --lmp naming no program) it says so and runs Rondel alone. It stops with a message naming what
failed on a missing rondel_bench or mpirun, a LAMMPS "ERROR" line, a non-zero exit, a rate it cannot
parse, or a LAMMPS total mass that differs from Rondel's. On a shared machine the figures are only as good
as the load allows: read the `uptime` line, and compare rates within one round.

Parameter mapping (Rondel's benchmark, bench/README.md -> LAMMPS 29Sep2021):
  packing           the CSV's discs and their nx x ny copies, ids 1-based in Rondel's gid order (the copies
                    numbered in rows across the box, as rondel_bench numbers them); box nx L by ny L;
                    `dimension 2`, z = 0 in a box of z from -0.5 to 0.5, `fix enforce2d`
  mass              Rondel: pi r^2 (thickness 1, density 1). LAMMPS (this version) gives a sphere
                    4/3 pi r^3 rho, in 2D too: rho = 3/(4 r) per atom makes it pi r^2 (checked by the
                    input: mass(all) against the sum of pi r^2)
  inertia           Rondel: m r^2 / 2. `fix nve/sphere disc` (velocity Verlet, as Rondel's kick-drift-kick)
  linear k_n 1e5    hooke k_n 1e5 (granular), Kn 1e5 (gran/hooke/history)
  zeta 0.3          Rondel: c_n = 2 zeta sqrt(m_eff k_n) per pair. LAMMPS `damping mass_velocity` (and
                    gran/hooke/history) use gamma_n m_eff, so gamma_n = 2 zeta sqrt(k_n / m_eff) depends on
                    the pair: the script takes m_eff as the mean over the packing's contacts. The cost of
                    either code does not depend on the damping.
  coulomb k_s 28571.43, mu 0.5
                    granular: tangential linear_history 28571.43 0 0.5 (no tangential damping);
                    gran/hooke/history: Kt 28571.43, gamma_t 0, xmu 0.5, dampflag 0
  wang k_r 28571.43, mu_r 0.1
                    granular: rolling sds 28571.43 0 0.1 (a spring-slider on the rolling displacement
                    with the reduced radius LAMMPS computes per pair, R1 R2/(R1 + R2): wang's R*;
                    its couple is that radius times the rolling force, as wang's); twisting off.
                    gran/hooke/history has no rolling resistance: it is compared with rolling none
  dt 3e-4           timestep 3e-4
  skin              Rondel's default, a quarter of the mean radius: `neighbor SKIN bin`,
                    `neigh_modify delay 0 every 1 check yes` (both rebuild when a disc has moved half the
                    skin; both list a pair within R1 + R2 + skin)
What differs, besides the laws above: LAMMPS computes in 3D (vectors of three components, torques about
three axes) and projects onto the plane (enforce2d); both its styles cap friction (granular: and the rolling
force) at mu |F_n| with the dashpot included, and let the dashpot pull (no limit_damping), where Rondel
caps at mu F_n with F_n = max(0, k_n u_n - c_n v_n); LAMMPS holds ghost atoms for the periodic images even on
one rank (Rondel's one rank wraps the separations instead), runs with `newton on` (set in the input, its
default: a pair is computed once and the forces on ghosts are sent back to their owners) and sorts its atoms
spatially every 1,000 steps (its default); Rondel books an energy ledger every step, LAMMPS computes
energies only at its two thermo outputs (`thermo 0`). A LAMMPS `run` sets up anew (neighbour lists, forces)
outside its "Loop time"; Rondel's timed steps follow the warm-up directly. The first round's rondel_bench
runs measure the memory-bandwidth triad as well (--no-stream: none); every run's output is kept in the work
directory as *.log.
"""
import argparse
import math
import os
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile

import numpy as np

ME = "tools/bench_lammps.py"
HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_PACKING = os.path.join(HERE, "..", "bench", "jammed10k.csv")
DEFAULT_RONDEL = os.path.join("build", "rondel_bench")

# Rondel's benchmark parameters (src/bench_main.cpp, bench/README.md).
K_N = 1e5
ZETA = 0.3
K_T = 28571.43
MU = 0.5
K_R = 28571.43
MU_R = 0.1
DT = 3e-4

# The runs of a round, in order: (label, code, variant).
RUNS = [("rondel wang", "rondel", "wang"), ("lammps granular+sds", "lammps", "granular"),
        ("rondel none", "rondel", "none"), ("lammps gran/hooke/history", "lammps", "hooke")]
# The ratios reported: (numerator, denominator).
RATIOS = [("rondel wang", "lammps granular+sds"), ("rondel wang", "lammps gran/hooke/history"),
          ("rondel none", "lammps gran/hooke/history"), ("rondel wang", "rondel none")]


class BenchError(Exception):
    pass


def say(text=""):
    print(text, flush=True)


# ---------------------------------------------------------------------------------------------- packing

def read_packing(path):
    """ids, x, y, r of the CSV and its periodic interval [lo, hi] (the comment 'Periodic box x, y in [lo, hi]')."""
    lo = hi = None
    with open(path) as f:
        for line in f:
            if not line.startswith("#"):
                break
            m = re.search(r"Periodic box.*in \[([^,\]]+),\s*([^\]]+)\]", line)
            if m:
                lo, hi = float(m.group(1)), float(m.group(2))
    if lo is None:
        raise BenchError(f"'{path}' has no 'Periodic box x, y in [lo, hi]' comment line")
    rows = []
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith("#") or not (s[0].isdigit() or s[0] in "+-."):
                continue
            rows.append([float(v) for v in s.split(",")[:4]])
    if not rows:
        raise BenchError(f"'{path}' holds no disc")
    data = np.array(rows)
    return data[:, 0].astype(np.int64), data[:, 1], data[:, 2], data[:, 3], lo, hi


def copies_of(discs, base):
    """(nx, ny) for `discs` discs made of `base`-disc copies, as rondel_bench chooses them."""
    if discs <= 0 or discs % base:
        raise BenchError(f"--discs {discs}: must be {base} (the discs of the packing) times a whole number of "
                         f"periodic copies nx x ny, e.g. {base}, {3 * base} (3 x 1), {16 * base} (4 x 4)")
    k = discs // base
    ny = max(d for d in range(1, math.isqrt(k) + 1) if k % d == 0)
    return k // ny, ny


def mean_meff_of_contacts(x, y, r, L):
    """Mean effective mass m1 m2/(m1 + m2) (m = pi r^2) over the overlapping pairs of the periodic packing
    (square box of side L), and their count: a cell grid of cells at least a largest diameter wide, every
    ordered pair of discs in the same or neighbouring cells (each pair is seen twice: the mean is the same)."""
    n = len(x)
    m = math.pi * r * r
    nc = int(L // (2.0 * float(r.max())))
    if nc < 3:  # too few cells for distinct neighbours: every pair
        cells, members = np.zeros(n, dtype=np.int64), np.arange(n)[None, None, :]
        offsets, nc = [(0, 0)], 1
    else:
        cx = np.minimum((np.mod(x - x.min(), L) / (L / nc)).astype(np.int64), nc - 1)
        cy = np.minimum((np.mod(y - y.min(), L) / (L / nc)).astype(np.int64), nc - 1)
        cells = cx * nc + cy
        offsets = [(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1)]
    order = np.argsort(cells, kind="stable")
    counts = np.bincount(cells, minlength=nc * nc)
    if nc > 1:
        kmax = int(counts.max())
        members = np.full((nc * nc, kmax), -1, dtype=np.int64)
        first = np.concatenate([[0], np.cumsum(counts)[:-1]])
        slot = np.arange(n) - np.repeat(first, counts)
        members[cells[order], slot] = order
        members = members.reshape(nc, nc, kmax)
    total, count = 0.0, 0
    for ox, oy in offsets:
        other = np.roll(np.roll(members, -ox, axis=0), -oy, axis=1)
        i = members[:, :, :, None]
        j = other[:, :, None, :]
        i, j = np.broadcast_arrays(i, j)
        keep = (i >= 0) & (j >= 0) & (i != j)
        i, j = i[keep], j[keep]
        dx = x[i] - x[j]
        dy = y[i] - y[j]
        dx -= L * np.round(dx / L)
        dy -= L * np.round(dy / L)
        touch = dx * dx + dy * dy < (r[i] + r[j]) ** 2
        mi, mj = m[i[touch]], m[j[touch]]
        total += float(np.sum(mi * mj / (mi + mj)))
        count += int(np.count_nonzero(touch))
    if count == 0:
        raise BenchError("the packing has no overlapping pair")
    return total / count, count // 2


def write_data(path, ids, x, y, r, lo, L, nx, ny):
    """The LAMMPS data file (atom_style sphere: id type diameter density x y z) of nx x ny copies, in Rondel's
    gid order: the packing alone keeps its ids; copies are numbered in rows of height twice the largest radius
    across the box, by x within a row, ties in copy order (scene.replicate_x/y, src/core/SceneBuilder.cpp)."""
    cx, cy = np.meshgrid(np.arange(nx), np.arange(ny))
    cx, cy = cx.ravel(), cy.ravel()  # copy order: cy outer, cx inner
    px = np.concatenate([x + c * L for c in cx])
    py = np.concatenate([y + c * L for c in cy])
    pr = np.tile(r, nx * ny)
    if nx * ny == 1:
        order = np.argsort(ids, kind="stable")
    else:
        row = np.floor((py - lo) / (2.0 * r.max()))
        order = np.lexsort((np.arange(len(px)), px, row))
    with open(path, "w") as f:
        f.write(f"Rondel benchmark packing, {nx} x {ny} periodic copies ({ME})\n\n")
        f.write(f"{len(px)} atoms\n1 atom types\n\n")
        f.write(f"{lo!r} {lo + nx * L!r} xlo xhi\n{lo!r} {lo + ny * L!r} ylo yhi\n-0.5 0.5 zlo zhi\n\n")
        f.write("Atoms # sphere\n\n")
        diam = 2.0 * pr[order]
        dens = 3.0 / (4.0 * pr[order])  # 4/3 pi r^3 rho = pi r^2
        vals = np.column_stack([diam, dens, px[order], py[order]])
        f.writelines(f"{k + 1} 1 {d!r} {e!r} {qx!r} {qy!r} 0\n" for k, (d, e, qx, qy) in enumerate(vals.tolist()))


def shear_commands(rate, lo, height):
    """A cell sheared at RATE (Rondel: cell.rate_xy, docs/physics.md section 10): a triclinic box whose tilt
    grows at RATE x height, velocities of atoms crossing the sheared boundary shifted (remap v), flipped past
    half the width as Rondel's (flip yes); the discs start with the mean flow RATE (y - lo), as rondel_bench's
    (cell.flow_start). After the pair style: its history fix must come before fix deform, which migrates atoms
    when it flips."""
    return ("change_box all triclinic\n"
            f"velocity all ramp vx 0.0 {rate * height!r} y {lo!r} {lo + height!r} sum yes units box\n"
            f"fix shear all deform 1 xy erate {rate!r} remap v flip yes\n")


def lammps_input(kind, data, skin, gamma_n, steps, warmup, shear=""):
    if kind == "granular":
        pair = ("pair_style granular\n"
                f"pair_coeff * * hooke {K_N!r} {gamma_n!r} tangential linear_history {K_T!r} 0 {MU!r} "
                f"rolling sds {K_R!r} 0 {MU_R!r} damping mass_velocity\n")
    else:
        pair = f"pair_style gran/hooke/history {K_N!r} {K_T!r} {gamma_n!r} 0 {MU!r} 0\npair_coeff * *\n"
    warm = f"run {warmup}\n" if warmup > 0 else ""
    return (f"# Written by {ME}: Rondel's benchmark packing and parameters (see the script's header)\n"
            "units si\ndimension 2\nboundary p p p\natom_style sphere\nnewton on\ncomm_modify vel yes\n"
            f"read_data {data}\n{pair}{shear}"
            f"neighbor {skin!r} bin\nneigh_modify delay 0 every 1 check yes\n"
            "fix integrate all nve/sphere disc\nfix plane all enforce2d\n"
            f"timestep {DT!r}\nthermo 0\n"
            "variable total_mass equal mass(all)\nprint \"bench_lammps total mass ${total_mass}\"\n"
            f"{warm}run {steps}\n")


# ---------------------------------------------------------------------------------------------- runs

def run(cmd, cwd, env, log):
    with open(log, "w") as f:
        f.write("$ " + shlex.join(cmd) + "\n")
    try:
        p = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    except OSError as e:
        raise BenchError(f"cannot start {shlex.join(cmd)}: {e}")
    with open(log, "a") as f:
        f.write(p.stdout)
    return p.returncode, p.stdout


def run_rondel(args, prefix, discs, rolling, workdir, env, stream, tag):
    cmd = prefix + [args.rondel, "--discs", str(discs), "--rolling", rolling, "--steps", str(args.steps),
                    "--warmup", str(args.warmup), "--file", args.packing]
    if args.shear:
        cmd += ["--shear", repr(args.shear)]
    if not stream:
        cmd.append("--no-stream")
    code, out = run(cmd, workdir, env, os.path.join(workdir, f"rondel_{rolling}_{discs}_{tag}.log"))
    if code != 0:
        raise BenchError(f"rondel_bench exited with {code}: {shlex.join(cmd)}\n{out.strip()}")
    m = re.search(r"disc-steps per second\s+(\S+)", out)
    try:
        rate = float(m.group(1))
    except (AttributeError, ValueError):
        raise BenchError(f"cannot parse 'disc-steps per second' from rondel_bench:\n{out.strip()}")
    phases = {p: float(s) for p, s in re.findall(r"^\s+phase (\S+)\s+\S+ s \((\S+) %\)", out, re.M)}
    extra = {}
    for key, pattern in (("bytes", r"bytes per disc-step \(model\)\s+(\S+) B"),
                         ("stream", r"stream triad\s+(\S+) GB/s"), ("bound", r"bandwidth bound\s+(\S+)"),
                         ("contacts", r"contacts per disc\s+(\S+)")):
        m = re.search(pattern, out)
        if m:
            extra[key] = float(m.group(1))
    return rate, phases, extra


def run_lammps(args, prefix, lmp, infile, atoms, workdir, env, expect_mass, tag):
    cmd = prefix + [lmp, "-in", infile, "-log", "none", "-nocite"]
    code, out = run(cmd, workdir, env, os.path.join(workdir, f"{os.path.basename(infile)}_{tag}.log"))
    errors = [line for line in out.splitlines() if line.startswith("ERROR")]
    if errors:
        raise BenchError(f"LAMMPS failed ({shlex.join(cmd)}): " + "; ".join(errors))
    if code != 0:
        raise BenchError(f"LAMMPS exited with {code}: {shlex.join(cmd)}\n{out.strip()[-2000:]}")
    m = re.search(r"^bench_lammps total mass (\S+)", out, re.M)
    if not m:
        raise BenchError(f"cannot parse the total mass from LAMMPS ({infile})")
    mass = float(m.group(1))
    if abs(mass - expect_mass) > 1e-12 * expect_mass:
        raise BenchError(f"LAMMPS's total mass {mass!r} is not Rondel's sum of pi r^2 {expect_mass!r}: this LAMMPS "
                         "version computes a sphere's mass from its density otherwise (the data file's density "
                         "3/(4 r) assumes 4/3 pi r^3 rho)")
    loops = re.findall(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", out, re.M)
    if not loops:
        raise BenchError(f"cannot parse 'Loop time of ...' from LAMMPS ({infile}):\n{out.strip()[-2000:]}")
    secs, procs, steps, n = loops[-1]
    try:
        secs, steps, n = float(secs), int(steps), int(n)
    except ValueError:
        raise BenchError(f"cannot parse the timed run's 'Loop time' line of LAMMPS ({infile})")
    if steps != args.steps or n != atoms or not secs > 0:
        raise BenchError(f"LAMMPS's last run is {steps} steps with {n} atoms in {secs} s, expected {args.steps} "
                         f"steps with {atoms} atoms ({infile})")
    tail = out[out.rfind("Loop time of"):]
    phases = {name: float(pct) for name, pct in
              re.findall(r"^(Pair|Neigh|Comm|Output|Modify|Other)\s*\|.*\|\s*(\S+)\s*$", tail, re.M)}
    builds = re.search(r"Neighbor list builds = (\d+)", tail)
    extra = {"builds": int(builds.group(1)) if builds else None}
    return n * steps / secs, phases, extra


# ---------------------------------------------------------------------------------------------- report

def fmt_rate(v):
    return f"{v:.4g}"


def phase_line(phases):
    return ", ".join(f"{k} {v:.1f} %" for k, v in phases.items() if v >= 0.05) or "not printed"


def bench_size(args, discs, packing, lmp, prefix, env):
    ids, x, y, r, lo, hi = packing
    L = hi - lo
    nx, ny = copies_of(discs, len(x))
    skin = 0.25 * float(np.mean(r))
    meff, contacts = mean_meff_of_contacts(x, y, r, L)
    gamma_n = 2.0 * ZETA * math.sqrt(K_N / meff)
    total_mass = float(np.sum(math.pi * r * r)) * nx * ny
    say(f"== {discs} discs: {nx} x {ny} copies of {os.path.relpath(args.packing)}, box {nx * L:.6g} x {ny * L:.6g}, "
        f"skin {skin:.6g}, total mass {total_mass:.10g}")
    say(f"   LAMMPS gamma_n {gamma_n:.6g} 1/s = 2 zeta sqrt(k_n / m_eff), mean m_eff {meff:.6g} over the "
        f"packing's {contacts} overlapping pairs")
    # Written with or without LAMMPS here: they can be taken to a machine that has it.
    inputs = {}
    data = f"discs_{discs}.data"
    write_data(os.path.join(args.workdir, data), ids, x, y, r, lo, L, nx, ny)
    shear = shear_commands(args.shear, lo, ny * L) if args.shear else ""
    for kind in ("granular", "hooke"):
        inputs[kind] = os.path.join(args.workdir, f"in.{kind}_{discs}")
        with open(inputs[kind], "w") as f:
            f.write(lammps_input(kind, data, skin, gamma_n, args.steps, args.warmup, shear))
    say(f"   data file and inputs: {os.path.join(args.workdir, data)}, {inputs['granular']}, {inputs['hooke']}")
    runs = [run_ for run_ in RUNS if lmp or run_[1] == "rondel"]
    rates = {label: [] for label, _, _ in runs}
    last = {}
    for t in range(1, args.trials + 1):
        line = []
        for label, code, variant in runs:
            if code == "rondel":
                # the triad in the first round only: it costs about a second per run and does not change
                stream = t == 1 and not args.no_stream
                rate, phases, extra = run_rondel(args, prefix, discs, variant, args.workdir, env, stream, f"r{t}")
                if stream:
                    last[label + " model"] = extra
            else:
                rate, phases, extra = run_lammps(args, prefix, lmp, inputs[variant], discs, args.workdir, env,
                                                 total_mass, f"r{t}")
            rates[label].append(rate)
            last[label] = (phases, extra)
            line.append(f"{label} {fmt_rate(rate)}")
        say(f"   round {t}: " + ", ".join(line) + "  (disc-steps/s)")
    med = {label: statistics.median(v) for label, v in rates.items()}
    say("   medians (disc-steps/s): " + ", ".join(f"{label} {fmt_rate(v)}" for label, v in med.items()))
    pairs = [(a, b) for a, b in RATIOS if a in rates and b in rates]
    say("   ratios of the medians: " + ", ".join(f"{a} / {b} {med[a] / med[b]:.3f}" for a, b in pairs))
    say("   medians of the per-round ratios: " + ", ".join(
        f"{a} / {b} {statistics.median(x / y for x, y in zip(rates[a], rates[b])):.3f}" for a, b in pairs))
    say(f"   phases, round {args.trials} (share of the timed steps' wall time):")
    for label, _, _ in runs:
        phases, extra = last[label]
        more = f"; neighbour list builds {extra['builds']}" if extra.get("builds") is not None else ""
        say(f"     {label}: {phase_line(phases)}{more}")
    for label in ("rondel wang", "rondel none"):
        model = last.get(label + " model", {})
        if "bytes" in model:
            bound = (f", stream triad {model['stream']:.3g} GB/s, bandwidth bound {model['bound']:.4g} disc-steps/s "
                     f"(median measured / bound {med[label] / model['bound']:.3f})" if "bound" in model else "")
            say(f"   {label}: bytes per disc-step (model) {model['bytes']:.0f} B{bound}")


def main():
    ap = argparse.ArgumentParser(description="Rondel's benchmark beside LAMMPS's granular pair styles, as "
                                 "interleaved trials (see the header of this script for the parameter mapping).")
    ap.add_argument("--discs", default="10000",
                    help="disc counts, comma-separated: 10,000 times the copy count nx x ny (default 10000)")
    ap.add_argument("--steps", type=int, default=5000, help="timed steps of every run (default 5000)")
    ap.add_argument("--warmup", type=int, default=1000, help="warm-up steps before them (default 1000)")
    ap.add_argument("--trials", type=int, default=5, help="rounds of the four runs (default 5)")
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks of every run (default 1: no mpirun)")
    ap.add_argument("--pin", default="0",
                    help="the core every 1-rank run is pinned to with taskset (default 0; 'none': not pinned); "
                         "with --ranks, anything but 'none' binds the ranks to cores (mpirun --bind-to core). "
                         "An unpinned process that the scheduler moves between cores runs up to 30 %% slower "
                         "for the whole run, on the test machine")
    ap.add_argument("--rondel", default=DEFAULT_RONDEL,
                    help="rondel_bench (default build/rondel_bench of the working directory, else of this checkout)")
    ap.add_argument("--lmp", default="lmp", help="the LAMMPS binary (default lmp; missing: Rondel alone)")
    ap.add_argument("--workdir", help="where the data files, inputs and run logs go (default: a temporary "
                    "directory, removed at the end unless --keep)")
    ap.add_argument("--keep", action="store_true", help="keep the temporary work directory")
    ap.add_argument("--no-stream", action="store_true",
                    help="pass --no-stream to rondel_bench (no memory-bandwidth triad, no bandwidth bound)")
    ap.add_argument("--shear", type=float, default=0.0,
                    help="shear both codes' cells at this rate [1/s] (Rondel: rondel_bench --shear, the discs started "
                         "with the mean flow; LAMMPS: a triclinic box, fix deform xy erate RATE remap v, velocity "
                         "ramp); 0.0067 is I = 1e-3 for this packing (docs/benchmarks.md); default 0: standing")
    ap.add_argument("--packing", default=DEFAULT_PACKING,
                    help="the packing CSV (default bench/jammed10k.csv of this repository)")
    args = ap.parse_args()
    try:
        sizes = [int(v) for v in args.discs.split(",") if v.strip()]
    except ValueError:
        ap.error(f"--discs '{args.discs}': whole numbers separated by commas")
    if not math.isfinite(args.shear) or abs(args.shear) > 1.0:
        ap.error(f"--shear {args.shear!r}: a finite rate of at most 1 /s in magnitude (0.0067 is I = 1e-3)")
    if not sizes or args.steps < 1 or args.warmup < 0 or args.trials < 1 or args.ranks < 1:
        ap.error("--discs needs a value; --steps, --trials and --ranks at least 1, --warmup at least 0")

    try:
        if args.rondel == DEFAULT_RONDEL and not os.path.exists(args.rondel):
            args.rondel = os.path.join(HERE, "..", DEFAULT_RONDEL)  # the build of this checkout, from elsewhere
        rondel = shutil.which(args.rondel) if os.sep not in args.rondel else args.rondel
        if not rondel or not (os.path.isfile(rondel) and os.access(rondel, os.X_OK)):
            raise BenchError(f"rondel_bench not found at '{args.rondel}' (build it: make -C build rondel_bench; "
                             "or give --rondel PATH)")
        args.rondel = os.path.abspath(rondel)
        if not os.path.isfile(args.packing):
            raise BenchError(f"the packing '{args.packing}' does not exist (--packing PATH)")
        args.packing = os.path.abspath(args.packing)
        lmp = shutil.which(args.lmp)
        prefix = []
        env = dict(os.environ, OMP_NUM_THREADS="1")
        if args.ranks > 1:
            mpirun = shutil.which("mpirun")
            if not mpirun:
                raise BenchError("--ranks needs mpirun, which is not on the PATH")
            prefix = [mpirun, "-n", str(args.ranks)] + (["--bind-to", "core"] if args.pin != "none" else [])
            env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        elif args.pin != "none":
            taskset = shutil.which("taskset")
            if not taskset:
                raise BenchError("--pin needs taskset (Debian package util-linux); or give --pin none")
            prefix = [taskset, "-c", args.pin]
        packing = read_packing(args.packing)
        for discs in sizes:
            copies_of(discs, len(packing[1]))  # every size checked before any run
        temporary = args.workdir is None
        args.workdir = os.path.abspath(args.workdir or tempfile.mkdtemp(prefix="bench_lammps."))
        os.makedirs(args.workdir, exist_ok=True)
        say(f"{ME}: {subprocess.run(['uptime'], capture_output=True, text=True).stdout.strip()}")
        if lmp:
            version = subprocess.run([lmp, "-h"], capture_output=True, text=True, env=env).stdout
            m = re.search(r"Simulator - (.+?)\s*$", version, re.M)
            say(f"{ME}: rondel {args.rondel}; LAMMPS {lmp} ({m.group(1) if m else 'version not printed'})")
        else:
            say(f"{ME}: LAMMPS ('{args.lmp}') was not found: running Rondel alone (apt-get install lammps "
                "for the side-by-side run)")
            say(f"{ME}: rondel {args.rondel}")
        say(f"{ME}: {args.ranks} rank(s), {args.steps} timed steps after {args.warmup} warm-up, {args.trials} "
            f"round(s); work directory {args.workdir}" + (f"; both cells sheared at {args.shear!r} /s" if args.shear
                                                           else ""))
        try:
            for discs in sizes:
                bench_size(args, discs, packing, lmp, prefix, env)
        finally:
            if temporary and not args.keep:
                shutil.rmtree(args.workdir, ignore_errors=True)
            else:
                say(f"{ME}: data files, inputs and logs kept in {args.workdir}")
        say(f"{ME}: {subprocess.run(['uptime'], capture_output=True, text=True).stdout.strip()}")
    except BenchError as e:
        print(f"bench_lammps: error: {e}", file=sys.stderr, flush=True)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
