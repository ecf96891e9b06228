#!/usr/bin/python3
"""Tests of tools/bench_lammps.py, Rondel beside LAMMPS (ctest: tools.bench_lammps).

  /usr/bin/python3 tests/tools/test_bench_lammps.py BUILD/rondel_bench

Short runs (10,000 discs, 20 timed steps, 1 round):
  - without LAMMPS (--lmp /nonexistent): the script says so, runs Rondel alone, and still writes the LAMMPS
    data file and inputs: the data file holds the packing's 10,000 discs in its box, with LAMMPS's sphere
    mass 4/3 pi r^3 rho equal to Rondel's pi r^2 for every disc; the inputs carry the mapped parameters;
  - with a stand-in for LAMMPS (a script that answers as LAMMPS does, with the total mass of the data file):
    the ratios of both codes are printed; a stand-in that prints an ERROR line, one that prints no
    "Loop time" line, and one whose mass differs make the script fail with a message naming the cause;
  - a missing rondel_bench fails naming it;
  - --shear: rondel_bench shears its cell, the LAMMPS input a triclinic box by fix deform (remap v) after the
    pair style, the discs started on the flow; --shear nan refused;
  - with the real LAMMPS (`lmp` on the PATH; skipped otherwise): the whole side-by-side round, ratios included,
    standing and sheared.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
SCRIPT = os.path.join(ROOT, "tools", "bench_lammps.py")
PACKING = os.path.join(ROOT, "bench", "jammed10k.csv")
SHORT = ["--discs", "10000", "--steps", "20", "--warmup", "0", "--trials", "1"]

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"), flush=True)


def run(args):
    p = subprocess.run([sys.executable, SCRIPT] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       timeout=300)
    return p.returncode, p.stdout, p.stderr


def packing():
    lo = hi = None
    radii = {}
    with open(PACKING) as f:
        for line in f:
            m = re.search(r"Periodic box.*in \[([^,\]]+),\s*([^\]]+)\]", line)
            if m:
                lo, hi = float(m.group(1)), float(m.group(2))
            if line[:1].isdigit():
                i, _, _, r = line.split(",")
                radii[int(i)] = float(r)
    return lo, hi, radii


# A stand-in for LAMMPS: reads the input's data file, prints the total mass as LAMMPS would compute it
# (4/3 pi r^3 rho per atom) and the last run's "Loop time" and timing breakdown. MODE: ok, error, noloop, mass.
FAKE_LMP = r'''#!/usr/bin/python3
import math, re, sys
mode = "MODE"
if "-h" in sys.argv:
    print("Large-scale Atomic/Molecular Massively Parallel Simulator - stand-in for the tests")
    sys.exit(0)
text = open(sys.argv[sys.argv.index("-in") + 1]).read()
print("LAMMPS (stand-in)")
if mode == "error":
    print("ERROR: Unrecognized pair style 'granular' (src/force.cpp:277)")
    sys.exit(1)
data = re.search(r"^read_data (\S+)", text, re.M).group(1)
atoms, mass, body = 0, 0.0, False
for line in open(data):
    if line.startswith("Atoms"):
        body = True
        continue
    f = line.split()
    if body and len(f) == 7:
        r, rho = float(f[2]) / 2, float(f[3])
        mass += 4.0 / 3.0 * math.pi * r ** 3 * rho
        atoms += 1
if mode == "mass":
    mass *= 4.0 / 3.0
print("bench_lammps total mass %.15g" % mass)
runs = [int(n) for n in re.findall(r"^run (\d+)", text, re.M)]
if mode != "noloop":
    for n in runs:
        print("Loop time of %g on 1 procs for %d steps with %d atoms" % (1e-7 * atoms * max(n, 1), n, atoms))
        print("Pair    | 1 | 1 | 1 | 0.0 | 80.00")
        print("Modify  | 1 | 1 | 1 | 0.0 | 20.00")
        print("Neighbor list builds = 0")
'''


def fake_lmp(directory, mode):
    path = os.path.join(directory, f"lmp_{mode}")
    with open(path, "w") as f:
        f.write(FAKE_LMP.replace("MODE", mode))
    os.chmod(path, 0o755)
    return path


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    rondel = os.path.abspath(sys.argv[1])
    lo, hi, radii = packing()
    work = tempfile.mkdtemp(prefix="test_bench_lammps.")
    try:
        # Without LAMMPS: Rondel alone, the data file and inputs written all the same.
        out_dir = os.path.join(work, "alone")
        code, out, err = run(SHORT + ["--rondel", rondel, "--lmp", "/nonexistent", "--workdir", out_dir])
        check("alone: exit 0", code == 0, err)
        check("alone: uptime first", out.startswith("tools/bench_lammps.py:") and "load average" in out.split("\n")[0],
              out[:200])
        check("alone: says LAMMPS is missing", "was not found: running Rondel alone" in out, out)
        check("alone: Rondel's rates and ratio", re.search(r"round 1: rondel wang \S+, rondel none \S+", out) and
              "rondel wang / rondel none" in out and "lammps granular" not in out, out)
        data = os.path.join(out_dir, "discs_10000.data")
        check("alone: data file written", os.path.isfile(data), os.listdir(out_dir) if os.path.isdir(out_dir) else "")
        if os.path.isfile(data):
            text = open(data).read()
            check("data: 10000 atoms", re.search(r"^10000 atoms$", text, re.M), text[:300])
            box = re.findall(r"^(\S+) (\S+) ([xyz])lo [xyz]hi$", text, re.M)
            check("data: the packing's periodic box in x and y, z straddles 0",
                  [(float(a), float(b), c) for a, b, c in box] == [(lo, hi, "x"), (lo, hi, "y"), (-0.5, 0.5, "z")], box)
            atoms = [line.split() for line in text.split("Atoms # sphere", 1)[1].strip().splitlines()]
            ids = sorted(int(a[0]) for a in atoms)
            check("data: ids 1 to 10000, one type, z = 0",
                  ids == list(range(1, 10001)) and all(a[1] == "1" and float(a[6]) == 0.0 for a in atoms))
            worst = 0.0
            for a in atoms:
                r_csv = radii[int(a[0]) - 1]
                r, rho = float(a[2]) / 2.0, float(a[3])
                worst = max(worst, abs(r - r_csv) / r_csv,
                            abs(4.0 / 3.0 * math.pi * r ** 3 * rho - math.pi * r_csv ** 2) / (math.pi * r_csv ** 2))
            check("data: radius and LAMMPS mass 4/3 pi r^3 rho = pi r^2 for every disc", worst < 1e-14, worst)
        gran = os.path.join(out_dir, "in.granular_10000")
        hooke = os.path.join(out_dir, "in.hooke_10000")
        if os.path.isfile(gran) and os.path.isfile(hooke):
            g, h = open(gran).read(), open(hooke).read()
            skin = 0.25 * sum(radii.values()) / len(radii)
            m = re.search(r"^neighbor (\S+) bin$", g, re.M)
            check("inputs: skin a quarter of the mean radius", m and abs(float(m.group(1)) - skin) < 1e-12 * skin, m)
            check("inputs: granular hooke, linear_history, sds, mass_velocity",
                  re.search(r"^pair_coeff \* \* hooke 100000\.0 \S+ tangential linear_history 28571\.43 0 0\.5 "
                            r"rolling sds 28571\.43 0 0\.1 damping mass_velocity$", g, re.M), g)
            check("inputs: gran/hooke/history Kn Kt gamma_n 0 0.5 0",
                  re.search(r"^pair_style gran/hooke/history 100000\.0 28571\.43 \S+ 0 0\.5 0$", h, re.M), h)
            for name, t in (("granular", g), ("hooke", h)):
                check(f"inputs ({name}): 2D, disc inertia, timestep, timed run",
                      all(s in t for s in ("dimension 2", "fix integrate all nve/sphere disc", "enforce2d",
                                           "comm_modify vel yes", "timestep 0.0003", "run 20\n")), t)
        else:
            check("alone: inputs written", False, os.listdir(out_dir))

        # A stand-in LAMMPS: both codes' rates and the four ratios.
        code, out, err = run(SHORT + ["--no-stream", "--rondel", rondel, "--lmp", fake_lmp(work, "ok")])
        check("stand-in: exit 0", code == 0, err)
        check("stand-in: the ratios of both codes",
              all(s in out for s in ("rondel wang / lammps granular+sds", "rondel wang / lammps gran/hooke/history",
                                     "rondel none / lammps gran/hooke/history", "rondel wang / rondel none")), out)
        check("stand-in: rate = atoms x steps / loop time", "lammps granular+sds 1e+07" in out, out)
        check("stand-in: LAMMPS breakdown reported", "Pair 80.0 %, Modify 20.0 %" in out, out)
        check("stand-in: temporary work directory removed",
              not re.search(r"kept in", out) and not os.path.exists(
                  re.search(r"work directory (\S+)", out).group(1) if re.search(r"work directory (\S+)", out) else "x"),
              out)
        for mode, expect in (("error", "LAMMPS failed .*ERROR: Unrecognized pair style"),
                             ("noloop", "cannot parse 'Loop time of"), ("mass", "total mass .* is not Rondel's")):
            code, out, err = run(SHORT + ["--no-stream", "--rondel", rondel, "--lmp", fake_lmp(work, mode)])
            check(f"stand-in {mode}: fails naming the cause", code == 1 and re.search(expect, err), err + out[-500:])

        # A missing rondel_bench.
        code, out, err = run(SHORT + ["--rondel", os.path.join(work, "no_rondel_bench"), "--lmp", "/nonexistent"])
        check("missing rondel_bench: fails naming it", code == 1 and "rondel_bench not found" in err, err)
        code, out, err = run(["--discs", "15000", "--rondel", rondel, "--lmp", "/nonexistent"])
        check("--discs 15000: refused naming --discs", code == 1 and "--discs 15000" in err, err)

        # --shear: both cells sheared, Rondel by rondel_bench --shear, LAMMPS by a triclinic box that deforms
        # (after the pair style, whose history fix must come first) with the discs started on the flow.
        sheared = os.path.join(work, "sheared")
        code, out, err = run(SHORT + ["--rondel", rondel, "--lmp", "/nonexistent", "--workdir", sheared, "--shear",
                                      "0.0067"])
        check("--shear: exit 0, said", code == 0 and "both cells sheared at 0.0067 /s" in out, err + out)
        log = [n for n in os.listdir(sheared) if n.startswith("rondel_wang")] if os.path.isdir(sheared) else []
        check("--shear: rondel_bench ran with --shear 0.0067",
              log and "--shear 0.0067" in open(os.path.join(sheared, log[0])).readline(), log)
        text = open(os.path.join(sheared, "in.granular_10000")).read() if os.path.isdir(sheared) else ""
        height = hi - lo
        ramp = re.search(r"^velocity all ramp vx 0\.0 (\S+) y (\S+) (\S+) sum yes units box$", text, re.M)
        check("--shear: the discs start on the flow 0.0067 (y - ylo)",
              ramp and abs(float(ramp.group(1)) - 0.0067 * height) < 1e-12 * height and float(ramp.group(2)) == lo,
              text)
        check("--shear: a triclinic box deformed in xy with remap v, after the pair style",
              "change_box all triclinic" in text and
              0 < text.find("pair_style") < text.find("fix shear all deform 1 xy erate 0.0067 remap v flip yes"), text)
        code, out, err = run(SHORT + ["--rondel", rondel, "--lmp", "/nonexistent", "--shear", "nan"])
        check("--shear nan: refused naming --shear", code != 0 and "--shear" in err, err)

        # The real LAMMPS, when installed.
        if shutil.which("lmp"):
            code, out, err = run(SHORT + ["--no-stream", "--rondel", rondel])
            check("lammps: exit 0", code == 0, err + out)
            check("lammps: ratios printed", re.search(r"ratios of the medians: rondel wang / lammps granular\+sds \S+",
                                                      out), out)
            code, out, err = run(SHORT + ["--no-stream", "--rondel", rondel, "--shear", "0.0067"])
            check("lammps --shear: exit 0 (fix deform with pair granular's history)", code == 0, err + out)
        else:
            print("SKIP the real LAMMPS: lmp is not on the PATH (apt-get install lammps)")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    failed = results.count(False)
    print(f"{results.count(True)} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
