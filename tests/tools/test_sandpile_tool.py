#!/usr/bin/python3
"""Tests of tools/sandpile.py on hand-built run directories (ctest: tools.sandpile).

A fill stage (a checkpoint at t = 4.5 s) and a discharge stage that starts from it (config.ini with the
walls.segments of inputs/sandpile_discharge.ini, scene.type = file) with five snapshots at t = 0..4 s: a
lattice heap of equal discs (R = 2.5 mm) on the chamber floor (y = -0.57) with 25 deg (left) and 35 deg
(right) flanks that grows (no heap, then apex heights 0.04, 0.08, 0.12, 0.12 m). Decoys the tool must leave
out of the pile: discs in the hopper above the chamber's ceiling (y > -0.22; higher than any pile disc), a
disc in flight above the apex and one beside the axis; three discs that rolled away on the floor are
connected to it, so they count as pile (and give the height of the first frame, before the heap).

Asserts: t0 = 4.5 s read from the fill's checkpoint (and --t0 overriding it); per frame the disc counts
(above the chamber, in it, in the pile) and the three heights equal to those computed from the built heap
alone; the settling time (t = 4.5 + 3 s) and the height change over the last 2 s; left, right and mean
angles within 1.5 deg of 25, 35 and 30; the label taken from the rolling law's block; the CSV and figure
files (PNG and PDF, with a --hline); a user error (missing directory, no floor to find, wrong --label
count, a --hline height that is not a number) exits 1 with one line and no traceback; a final frame
without a heap (only the rolled-away discs) exits 2.

The sweep (--sweep): its --steps parser, and its usage errors (a law it has no scene for, a RUN_DIR beside
--sweep, --quick without --sweep). With the rondel executable (argv[1]), the --quick sweep end to end (300
discs: 0.6 s of filling, the two discharges 1 s each, two jobs): exit 0, every run 'status: complete', one
table row per law with finite heights below the chamber's ceiling, t0 = 0.6 s and t_end = 1.6 s, the figures;
a second call runs nothing (every run reused, no summary.txt rewritten, the same table); a discharge whose
summary.txt says stopped and whose newest checkpoint is half way is resumed from it, one stopped without a
checkpoint runs afresh, and both end with the final.csv of the first call byte for byte; --steps LAW=N extends a
complete run (resumed, the table's steps and t_end follow); --collect-only runs nothing and tables the complete
runs only; the full preset into the quick sweep's folder is refused (exit 1, nothing run); a fill stopped half
way is resumed and then both discharges run afresh, again to the same final.csv. Exits non-zero on any failure,
prints 'N passed, N failed'.
"""
import contextlib
import csv
import io
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "sandpile.py")
sys.path.insert(0, os.path.dirname(TOOL))
import sandpile  # noqa: E402
import sandpile_sweep  # noqa: E402
PY = sys.executable or "/usr/bin/python3"
R = 2.5e-3
FLOOR, CEILING = -0.57, -0.22
TOL_DEG = 1.5
SEGMENTS = ("-0.505 1.0 -0.505 0.57; -0.505 0.57 -0.035 0.0; -0.035 0.0 -0.035 -0.22; -0.035 -0.22 -1.0 -0.22; "
            "-1.0 -0.22 -1.0 -0.57; -1.0 -0.57 1.0 -0.57; 1.0 -0.57 1.0 -0.22; 1.0 -0.22 0.035 -0.22; "
            "0.035 -0.22 0.035 0.0; 0.035 0.0 0.505 0.57; 0.505 0.57 0.505 1.0")

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


def heap(height, left_deg=25.0, right_deg=35.0, x_apex=0.0):
    """Centres (n, 2) of a triangular-lattice heap on the floor under the flanks (empty for height 0)."""
    if height <= 0.0:
        return np.zeros((0, 2))
    tl, tr = math.tan(math.radians(left_deg)), math.tan(math.radians(right_deg))
    dy = math.sqrt(3.0) * R
    pts = []
    for row in range(int(height / dy) + 2):
        y = FLOOR + R + row * dy
        shift = R if row % 2 else 0.0
        for i in range(-200, 201):
            x = x_apex + shift + 2.0 * R * i
            surf = FLOOR + height - (tl * (x_apex - x) if x < x_apex else tr * (x - x_apex))
            if y + R <= surf:
                pts.append((x, y))
    return np.array(pts)


def decoys(height):
    """(hopper discs above the ceiling, discs in the chamber that are not in the pile)."""
    hopper = np.array([(x, 0.3 + 0.01 * k) for k, x in enumerate(np.linspace(-0.2, 0.2, 12))])
    top = FLOOR + max(height, 0.0)
    loose = np.array([(0.0, top + 0.05),            # in flight above the apex
                      (0.01, -0.25),                 # in flight just below the channel
                      (-0.9, FLOOR + R), (0.93, FLOOR + R), (0.93 + 2 * R, FLOOR + R)])  # rolled away
    return hopper, loose


def write_state(path, kind, step, time, pos, config_text=""):
    import h5py
    n = len(pos)
    with h5py.File(path, "w") as f:
        f.attrs["format"] = np.bytes_("rondel")
        f.attrs["kind"] = np.bytes_(kind)
        f.attrs["step"] = np.int64(step)
        f.attrs["time"] = np.float64(time)
        f.attrs["dt"] = np.float64(2e-5)
        f.attrs["format_version"] = np.int64(1)
        f.attrs["complete"] = np.int64(1)
        f.attrs["config"] = np.bytes_(config_text)
        g = f.create_group("discs")
        g["gid"] = np.arange(n, dtype=np.int64)
        g["radius"] = np.full(n, R)
        g["position"] = np.asarray(pos, dtype=np.float64).reshape(n, 2)


def config_text(fill_dir, rolling="jiang_plastic", block="[jiang]\ndelta = 0.90000000000000002\n", segments=SEGMENTS):
    return (f"[run]\ndt = 2e-5\noutput = rondel-output/sandpile_discharge\n\n[contact]\nnormal = hertz\n"
            f"tangential = mindlin\nrolling = {rolling}\n\n{block}\n[walls]\nsegments = {segments}\n\n"
            f"[scene]\ntype = file\nfile = {fill_dir}\n")


HEIGHTS = [0.0, 0.04, 0.08, 0.12, 0.12]


def build(tmp, name="discharge", heights=HEIGHTS, **kw):
    """A fill run (checkpoint at 4.5 s) and a discharge run with one snapshot per height; the expected
    per-frame values."""
    fill = os.path.join(tmp, name + "_fill")
    os.makedirs(fill, exist_ok=True)
    write_state(os.path.join(fill, "checkpoint_0000225000.h5"), "checkpoint", 225000, 4.5, np.zeros((3, 2)) + 0.5)
    run = os.path.join(tmp, name)
    os.makedirs(run, exist_ok=True)
    text = config_text(fill, **kw)
    with open(os.path.join(run, "config.ini"), "w") as f:
        f.write(text)
    want = []
    for k, h in enumerate(heights):
        pile = heap(h)
        hopper, loose = decoys(h)
        # the discs still in the hopper shrink as the pile grows (all frames have different counts)
        hopper = hopper[: len(hopper) - 2 * k]
        pos = np.vstack([p for p in (pile, hopper, loose) if len(p)])
        write_state(os.path.join(run, f"snapshot_{50000 * k:010d}.h5"), "snapshot", 50000 * k, float(k), pos, text)
        rolled = loose[2:]  # on the floor: connected to it, so part of the pile by the tool's definition
        ground = np.vstack([p for p in (pile, rolled) if len(p)])
        w = dict(time=4.5 + k, discs_above=len(hopper), discs_chamber=len(pile) + len(loose),
                 discs_pile=len(ground), height_top=float((ground[:, 1] + R).max()) - FLOOR,
                 height_centre=float(ground[:, 1].max()) - FLOOR)
        near = np.abs(ground[:, 0]) <= 2 * R
        if near.any():
            w["height_axis"] = float((ground[near, 1] + R).max()) - FLOOR
        want.append(w)
    return run, want


def run_tool(*args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = sandpile.main([str(a) for a in args])
    return rc, out.getvalue(), err.getvalue()


def run_command(*args):
    p = subprocess.run([PY, TOOL, *map(str, args)], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def user_error(name, rc, err):
    lines = err.strip().splitlines()
    check(f"{name}: exit 1 with one line 'sandpile: error: ...', no traceback",
          rc == 1 and "Traceback" not in err and lines and lines[-1].startswith("sandpile: error: "), (rc, err))


def main():
    with tempfile.TemporaryDirectory() as tmp:
        run, want = build(tmp)
        prefix = os.path.join(tmp, "out", "sp")
        rc, out, err = run_tool(run, "--out", prefix)
        check("exit 0", rc == 0, err)
        rows = read_rows(prefix + "_height.csv") if rc == 0 else []
        check("one height row per snapshot", len(rows) == len(want), len(rows))
        for row, w in zip(rows, want):
            t = w["time"]
            check(f"t = {t:g}: time shifted by the fill's 4.5 s", abs(float(row["time"]) - t) < 1e-12, row["time"])
            for key in ("discs_above", "discs_chamber", "discs_pile"):
                check(f"t = {t:g}: {key} = {w[key]}", int(row[key]) == w[key], row[key])
            for key in ("height_top", "height_centre", "height_axis"):
                if key in w:
                    got = float(row[key])
                    check(f"t = {t:g}: {key} {got:.5f} = {w[key]:.5f}", abs(got - w[key]) < 1e-12, got)
                else:
                    check(f"t = {t:g}: {key} empty (no pile disc near the axis)", row[key] == "", row[key])
        s = read_rows(prefix + "_summary.csv")[0] if rc == 0 else {}
        if s:
            check("t0 = 4.5 s from the fill's checkpoint", abs(float(s["t0"]) - 4.5) < 1e-12, s["t0"])
            check("settled at t = 7.5 s (the frame the final height is first reached)",
                  abs(float(s["settled_at"]) - 7.5) < 1e-12, s["settled_at"])
            want_drift = want[-1]["height_top"] - want[-3]["height_top"]  # t = 8.5 against t = 6.5 s
            check(f"drift over the last 2 s {float(s['drift']):.4f} = {want_drift:.4f}",
                  abs(float(s["drift"]) - want_drift) < 1e-12, s["drift"])
            for side, angle in (("left", 25.0), ("right", 35.0), ("mean", 30.0)):
                check(f"{side} angle {float(s[side]):.2f} within {TOL_DEG} deg of {angle}",
                      abs(float(s[side]) - angle) <= TOL_DEG, s[side])
            check("label from the rolling law (config.ini's 0.90000000000000002 as 0.9)",
                  s["label"] == "jiang_plastic (delta = 0.9)", s["label"])
            check("floor and ceiling from walls.segments",
                  float(s["floor"]) == FLOOR and float(s["chamber_top"]) == CEILING, (s["floor"], s["chamber_top"]))
            check("the summary is printed", "angle of repose: left" in out and "t0 = 4.5 s" in out, out)
        for suffix in ("_height.png", "_pile_0.png"):
            p = prefix + suffix
            check(f"{os.path.basename(p)} written", os.path.isfile(p) and os.path.getsize(p) > 1000, p)

        # two runs, labels given, --t0 given, PDF figures, as a command
        run2, _ = build(tmp, "constant", rolling="constant_torque", block="[constant_torque]\nmu_r = 0.15\n")
        rc, out, err = run_command(run, run2, "--out", os.path.join(tmp, "both"), "--label", "a", "b",
                                   "--t0", "1", "--format", "pdf", "--hline", "0.1", "reference")
        check("two runs, --t0 1, PDF: exit 0", rc == 0, err)
        if rc == 0:
            s2 = read_rows(os.path.join(tmp, "both_summary.csv"))
            check("two summary rows with the given labels", [r["label"] for r in s2] == ["a", "b"], s2)
            check("--t0 overrides the fill's time", all(float(r["t0"]) == 1.0 for r in s2), [r["t0"] for r in s2])
            h = read_rows(os.path.join(tmp, "both_height.csv"))
            check("first frame at t = 1 s", float(h[0]["time"]) == 1.0, h[0]["time"])
            with open(os.path.join(tmp, "both_height.pdf"), "rb") as f:
                check("height figure is a PDF", f.read(5) == b"%PDF-")

        # a pile still growing at the end: not settled, drift = the last 2 s of growth
        run3, w3 = build(tmp, "growing", heights=[0.0, 0.03, 0.06, 0.09, 0.12])
        rc, out, err = run_tool(run3, "--out", os.path.join(tmp, "grow"), "--no-plot", "--tol", "0.001")
        s3 = read_rows(os.path.join(tmp, "grow_summary.csv"))[0] if rc == 0 else {}
        check("growing pile: exit 0", rc == 0, err)
        if s3:
            check("growing pile: settled only at the last frame", float(s3["settled_at"]) == 8.5, s3["settled_at"])
            want_drift = w3[-1]["height_top"] - w3[-3]["height_top"]
            check(f"growing pile: drift {float(s3['drift']):.4f} = {want_drift:.4f}",
                  abs(float(s3["drift"]) - want_drift) < 1e-12, s3["drift"])

        # user errors and a failed measurement
        rc, out, err = run_command(os.path.join(tmp, "missing"))
        user_error("missing run directory", rc, err)
        check("missing run directory: the message names it", "missing" in err, err)
        run4, _ = build(tmp, "nofloor", segments="-0.5 1.0 -0.5 0.0")
        rc, out, err = run_command(run4, "--no-plot")
        user_error("no horizontal segment", rc, err)
        check("no horizontal segment: the message names --floor", "--floor" in err, err)
        rc, out, err = run_command(run4, "--no-plot", "--floor", str(FLOOR), "--chamber-top", str(CEILING))
        check("--floor and --chamber-top given: exit 0", rc == 0, err)
        rc, out, err = run_command(run, run2, "--label", "only-one")
        user_error("--label count", rc, err)
        rc, out, err = run_command(run, "--hline", "high", "reference")
        user_error("--hline with a height that is not a number", rc, err)
        run5, _ = build(tmp, "empty", heights=[0.0, 0.0])
        rc, out, err = run_command(run5, "--no-plot")
        check("no heap in the chamber at the end (only discs that rolled away): exit 2, one line",
              rc == 2 and "Traceback" not in err and "sandpile: error:" in err and "no heap" in err, (rc, err))
        sweep_options()
        if len(sys.argv) > 1:
            sweep_end_to_end(sys.argv[1], tmp)
        else:
            print("no rondel executable given: the sweep end to end is not tested")
    failed = results.count(False)
    print(f"{results.count(True)} passed, {failed} failed")
    return 1 if failed else 0


LAWS = ["jiang_plastic", "constant_torque"]


def sweep_options():
    laws = LAWS
    default = {"jiang_plastic": 750000, "constant_torque": 750000}
    check("--steps '': the scenes' steps", sandpile_sweep.parse_steps("", laws, default) == default)
    got = sandpile_sweep.parse_steps("constant_torque=1750000,1000", laws, default)
    check("--steps LAW=N wins over N in any order", got == {"jiang_plastic": 1000, "constant_torque": 1750000}, got)
    for bad in ("wang=5", "x", "0", "jiang_plastic=-3"):
        try:
            sandpile_sweep.parse_steps(bad, laws, default)
            check(f"--steps '{bad}' refused", False, "accepted")
        except sandpile.UsageError:
            check(f"--steps '{bad}' refused", True)
    rc, out, err = run_command("--sweep", "--laws", "wang", "--out", "unused", "--rondel", PY)
    user_error("--sweep --laws wang (no scene for it)", rc, err)
    rc, out, err = run_command("--sweep", "some_run")
    user_error("--sweep with a RUN_DIR", rc, err)
    rc, out, err = run_command("some_run", "--quick")
    user_error("--quick without --sweep", rc, err)


def status(d):
    try:
        with open(os.path.join(d, "summary.txt")) as f:
            return [line.strip() for line in f if line.startswith("status:")]
    except OSError:
        return []


def stop(d, keep_checkpoints):
    """Make run D look stopped by a signal: its summary.txt says so, and only its KEEP_CHECKPOINTS oldest
    checkpoints stay (a signal writes one where it stops; 0: killed before its first)."""
    with open(os.path.join(d, "summary.txt")) as f:
        text = f.read()
    with open(os.path.join(d, "summary.txt"), "w") as f:
        f.write(text.replace("status: complete", f"status: stopped by a signal; resume with --resume {d}"))
    cps = sorted(x for x in os.listdir(d) if re.fullmatch(r"checkpoint_\d+\.h5", x))
    for x in cps[keep_checkpoints:]:
        os.remove(os.path.join(d, x))


def sweep_end_to_end(rondel, tmp):
    out = os.path.join(tmp, "sweep")
    runs = ["fill"] + LAWS
    base = ["--sweep", "--quick", "--out", out, "--rondel", rondel, "--jobs", "2"]

    def sweep(*extra):
        rc, so, se = run_command(*base, *extra)
        return rc, so, se, (read_rows(os.path.join(out, "table.csv"))
                            if os.path.isfile(os.path.join(out, "table.csv")) else [])

    rc, so, se, table = sweep()
    check("quick sweep: exit 0", rc == 0, so[-2000:] + se[-2000:])
    for name in runs:
        check(f"quick sweep: {name} status: complete", status(os.path.join(out, name)) == ["status: complete"],
              status(os.path.join(out, name)))
    check("quick sweep: one table row per law, in --laws order", [r["law"] for r in table] == LAWS, table)
    for r in table:
        law = r["law"]
        h = [float(r[k] or "nan") for k in ("height_top", "height_centre", "height_axis")]
        check(f"{law}: heights finite, 0 < centre < top < the chamber's 0.35 m", all(map(math.isfinite, h))
              and 0 < h[1] < h[0] < CEILING - FLOOR, h)
        check(f"{law}: most of the 300 discs in the pile", int(r["discs"]) == 300 and int(r["discs_pile"]) > 200,
              (r["discs"], r["discs_pile"]))
        check(f"{law}: t0 = 0.6 s (the quick fill), t_end = 1.6 s, 50,000 steps",
              abs(float(r["t0"]) - 0.6) < 1e-9 and abs(float(r["t_end"]) - 1.6) < 1e-9 and r["steps"] == "50000",
              (r["t0"], r["t_end"], r["steps"]))
        check(f"{law}: angles finite", all(math.isfinite(float(r[k] or "nan")) for k in ("left", "right", "mean")), r)
    for name in ["sandpile_height.png"] + [f"sandpile_pile_{law}.png" for law in LAWS]:
        p = os.path.join(out, name)
        check(f"quick sweep: {name} written", os.path.isfile(p) and os.path.getsize(p) > 1000, p)
    if rc != 0 or len(table) != 2:
        return
    finals = {law: open(os.path.join(out, law, "final.csv"), "rb").read() for law in LAWS}
    mtimes = {name: os.stat(os.path.join(out, name, "summary.txt")).st_mtime_ns for name in runs}

    rc, so, se, table2 = sweep("--no-plot")
    check("again: exit 0, all three runs reused, none run",
          rc == 0 and so.count(", reused") == 3 and "afresh" not in so and "resumed" not in so, so[-2000:] + se)
    check("again: no summary.txt rewritten", all(
        os.stat(os.path.join(out, name, "summary.txt")).st_mtime_ns == mtimes[name] for name in runs))
    check("again: the same table", table2 == table, (table, table2))

    stop(os.path.join(out, "jiang_plastic"), 1)     # stopped half way: its checkpoint at 25,000 stays
    stop(os.path.join(out, "constant_torque"), 0)   # stopped before its first checkpoint
    rc, so, se, table3 = sweep("--no-plot")
    check("stopped runs: exit 0", rc == 0, so[-2000:] + se[-2000:])
    check("stopped with a checkpoint: resumed from it", "jiang_plastic: resumed from step 25000 to 50000" in so, so)
    check("stopped without one: run afresh", "constant_torque: run afresh" in so, so)
    check("stopped runs: the fill reused", "fill: complete at step 30000, reused" in so, so)
    for law in LAWS:
        d = os.path.join(out, law)
        check(f"{law}: status: complete again", status(d) == ["status: complete"], status(d))
        check(f"{law}: the first call's final.csv byte for byte",
              open(os.path.join(d, "final.csv"), "rb").read() == finals[law])
    check("stopped runs: one table row per law again", [r["law"] for r in table3] == LAWS, table3)

    rc, so, se, table4 = sweep("--no-plot", "--steps", "jiang_plastic=60000")
    check("--steps jiang_plastic=60000: the complete run extended (resumed), the other reused",
          rc == 0 and "jiang_plastic: resumed from step 50000 to 60000" in so
          and "constant_torque: complete at step 50000, reused" in so, so[-2000:] + se[-2000:])
    rows = {r["law"]: r for r in table4}
    check("extended: steps 60000, t_end 1.8 s in the table", "jiang_plastic" in rows
          and rows["jiang_plastic"]["steps"] == "60000" and abs(float(rows["jiang_plastic"]["t_end"]) - 1.8) < 1e-9,
          rows.get("jiang_plastic"))

    os.remove(os.path.join(out, "constant_torque", "summary.txt"))
    rc, so, se, table5 = sweep("--no-plot", "--collect-only")
    check("--collect-only: exit 0, the complete run only in the table, nothing run",
          rc == 0 and [r["law"] for r in table5] == ["jiang_plastic"]
          and not os.path.exists(os.path.join(out, "constant_torque", "summary.txt")), so[-2000:] + se[-2000:])

    rc, so, se = run_command("--sweep", "--out", out, "--rondel", rondel, "--no-plot")
    user_error("the full preset into the quick sweep's folder", rc, se)
    check("the full preset refused: nothing run", "preset" in se
          and not os.path.exists(os.path.join(out, "constant_torque", "summary.txt")), se)

    fill_final = open(os.path.join(out, "fill", "final.csv"), "rb").read()
    stop(os.path.join(out, "fill"), 1)
    rc, so, se, table6 = sweep("--no-plot")
    check("a stopped fill: resumed, then both discharges run afresh",
          rc == 0 and "fill: resumed from step 25000 to 30000" in so and "jiang_plastic: run afresh" in so
          and "constant_torque: run afresh" in so, so[-2000:] + se[-2000:])
    check("the resumed fill: its final.csv byte for byte", open(os.path.join(out, "fill", "final.csv"), "rb").read()
          == fill_final)
    for law in LAWS:
        check(f"after the new fill, {law} (50,000 steps again): the first call's final.csv byte for byte",
              open(os.path.join(out, law, "final.csv"), "rb").read() == finals[law])
    check("after the new fill: one table row per law", [r["law"] for r in table6] == LAWS, table6)


if __name__ == "__main__":
    sys.exit(main())
