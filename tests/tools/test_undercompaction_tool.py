#!/usr/bin/python3
"""tools/undercompaction.py on a tiny specimen (ctest: tools.undercompaction): 90 discs in 3 layers in an 8 cm
wide box, target planar void ratio 0.3 (layers of about three diameters jam before 0.25), consolidated to
200 kPa. Checks that every layer was built (its stage ran, held the discs of the layers so far, and its wall
reached the layer's target height, the lower layers' targets looser), that the grading is the J05 one, and that the consolidated specimen's planar void ratio is within 0.02 of the target.
Also: bad input exits 1 with one line.

    /usr/bin/python3 tests/tools/test_undercompaction_tool.py BUILD/rondel
"""
import csv
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.abspath(os.path.join(HERE, "..", "..", "tools"))
sys.path.insert(0, HERE)
sys.path.insert(0, TOOLS)
from rondel_run import Checks  # noqa: E402
import undercompaction  # noqa: E402

check = Checks()


def tool(*args):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([sys.executable, os.path.join(TOOLS, "undercompaction.py")] + [str(a) for a in args],
                       capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stdout, p.stderr


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    rondel = sys.argv[1]
    # The grading: exact quantiles of the J05 curve (by area d50 7.6 mm, d60/d10 1.30) from 1008 diameters.
    d = undercompaction.diameters(1008, 0.006, 0.009, 1)
    d10, d50, d60 = undercompaction.grading_of(d)
    check("1008 diameters between 6 and 9 mm", 0.006 <= min(d) and max(d) <= 0.009, (min(d), max(d)))
    check("d50 = 7.6 mm by area (to 0.05 mm)", abs(d50 - 0.0076) < 5e-5, d50)
    check("d60/d10 = 1.30 (to 0.01)", abs(d60 / d10 - 1.30) < 0.01, d60 / d10)
    check("the same diameters for every seed, shuffled", sorted(d) == sorted(undercompaction.diameters(1008, 0.006,
          0.009, 2)) and d != undercompaction.diameters(1008, 0.006, 0.009, 2))

    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "ucm")
        target = 0.3
        rc, so, se = tool("--rondel", rondel, "--out", out, "--count", 90, "--layers", 3, "--width", 0.08,
                          "--e", target, "--u1", 0.1, "--consolidate-steps", 8000, "--wall-speed", 0.5)
        print(so)
        check("the tool exits 0", rc == 0, se[-2000:])
        if rc == 0:
            layers = rows(os.path.join(out, "layers.csv"))
            check("3 layers built", len(layers) == 3, layers)
            held = 0
            for k, row in enumerate(layers, 1):
                held += int(row["discs"])
                final = rows(os.path.join(out, f"layer_{k}", "final.csv"))
                check(f"layer {k}: its stage holds the {held} discs of layers 1..{k}", len(final) == held, len(final))
                h, ht = float(row["h_reached"]), float(row["h_target"])
                check(f"layer {k}: the wall reached the target height {ht:.5f} m (to 0.05 mm)",
                      abs(h - ht) < 5e-5, h)
            e_t = [float(r["e_target"]) for r in layers]
            check("undercompaction: lower layers' targets looser, the last at the target",
                  e_t[0] > e_t[1] > e_t[2] and abs(e_t[0] - target * 1.1) < 1e-12 and abs(e_t[2] - target) < 1e-12,
                  e_t)
            summary = dict(line.split() for line in open(os.path.join(out, "summary.txt")))
            e = float(summary["void_ratio"])
            check(f"consolidated planar void ratio {e:.4f} within 0.02 of {target}", abs(e - target) < 0.02, e)
            profile = rows(os.path.join(out, "profile.csv"))
            check("a void ratio for each of 3 height bands", len(profile) == 3, profile)
            cons = rows(os.path.join(out, "consolidated", "measures.csv"))
            syy = float(cons[-1]["wall_syy"])
            check(f"consolidated: wall_syy {syy / 1e3:.0f} kPa near 200 kPa", abs(syy - 2e5) < 0.2e5, syy)

        # Bad input: one line, exit 1, nothing run.
        for args in (["--layers", 1], ["--e", "nan"], ["--u1", 0.05, "--un", 0.1], ["--damping", 1]):
            rc, so, se = tool("--rondel", rondel, "--out", os.path.join(tmp, "bad"), *args)
            lines = se.strip().splitlines()
            check(f"bad input {args} exits 1 with one line", rc == 1 and "Traceback" not in se and lines and
                  lines[-1].startswith("undercompaction: error: "), (rc, se))
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
