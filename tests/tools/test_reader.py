#!/usr/bin/python3
"""Tests of the Python reader tools/rondel on a run written by the current build (ctest: tools.reader).

    /usr/bin/python3 tests/tools/test_reader.py BUILD/rondel

The run (tests/tools/rondel_run.py): 50 discs on a floor, 300 steps, snapshots and checkpoints. The reader's
arrays are checked against final.csv and diagnostics.csv of the same run, the file layout of FORMAT.md
(ordering, checksums), and its errors (RondelFileError naming the file) on bad input.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import os
import shutil
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
sys.path.insert(0, HERE)
import rondel  # noqa: E402
from rondel_run import Checks, STEPS, make_run  # noqa: E402

check = Checks()


def raises(name, fn, *words):
    """FN() raises RondelFileError whose message holds every word of WORDS."""
    try:
        fn()
    except rondel.RondelFileError as e:
        check(name, all(w in str(e) for w in words), str(e))
        return
    except Exception as e:  # noqa: BLE001 - the point: nothing but RondelFileError
        check(name, False, f"{type(e).__name__}: {e}")
        return
    check(name, False, "no error raised")


def test_run_directory(d):
    run = rondel.open_run(d)
    check("config: [scene] radius", run.config.getfloat("scene", "radius") == 0.002, run.config.get("scene", "radius"))
    check("config: sections", {"run", "domain", "scene", "walls"} <= set(run.config.sections()), run.config.sections())
    s = run.summary()
    check("summary: steps and discs", s["steps"] == STEPS and s["discs"] == 50, s)
    check("summary: complete", s["complete"] is True, s)
    ts = run.time_step()
    check("time step: 0 < dt <= critical", 0 < ts["dt"] <= ts["dt_critical"] and ts["critical_mode"], ts)
    fin = run.final()
    check("final: 50 rows, gid 0..49", len(fin) == 50 and list(fin["gid"]) == list(range(50)), fin.columns)
    check("final: floats", fin["x"].dtype == np.float64 and fin["gid"].dtype == np.int64)
    diag = run.diagnostics()
    check("diagnostics: a row every 50 steps to 300", list(diag["step"]) == list(range(0, STEPS + 1, 50)),
          list(diag["step"]))
    check("diagnostics: float columns stay float", diag["ke_rot"].dtype == np.float64, diag["ke_rot"].dtype)
    return run, fin, diag


def test_checkpoint(run, fin, diag):
    steps = [rondel.step_of_name(p) for p in run.checkpoint_paths()]
    check("checkpoints in step order", steps == sorted(steps) and steps[-1] == STEPS, steps)
    c = run.checkpoint()
    check("newest checkpoint: step, kind", c.step == STEPS and c.kind == "checkpoint", (c.step, c.kind))
    check("checkpoint: complete, version 1", c.complete and c.format_version == rondel.FORMAT_VERSION)
    d = c.discs
    check("discs: every FORMAT.md dataset", {"gid", "material", "radius", "mass", "inertia", "position", "velocity",
                                            "theta", "omega", "force", "torque", "flags"} <= set(d), sorted(d))
    check("discs: position equals final.csv x, y bit for bit",
          np.array_equal(d["position"][:, 0], fin["x"]) and np.array_equal(d["position"][:, 1], fin["y"]))
    check("discs: velocity, theta, omega equal final.csv",
          np.array_equal(d["velocity"][:, 0], fin["vx"]) and np.array_equal(d["velocity"][:, 1], fin["vy"])
          and np.array_equal(d["theta"], fin["theta"]) and np.array_equal(d["omega"], fin["omega"]))
    if "radius" in fin:
        check("discs: radius equals final.csv radius", np.array_equal(d["radius"], fin["radius"]))
    ke = 0.5 * float(np.sum(d["mass"] * np.sum(d["velocity"] ** 2, axis=1)))
    last = diag.row(len(diag) - 1)
    check("kinetic energy of the discs = diagnostics ke_trans of the last row",
          abs(ke - last["ke_trans"]) <= 1e-9 * max(abs(ke), 1e-300) + 1e-15, (ke, last["ke_trans"]))
    k = c.contacts["key"]
    check("contacts: keys (M, 2), lower gid first, ascending", k.ndim == 2 and k.shape[1] == 2 and len(k) > 0
          and bool(np.all(k[:, 0] < k[:, 1])) and [tuple(r) for r in k] == sorted(tuple(r) for r in k), k[:5])
    check("contacts: history slot xi, one value per row", c.history_slots == ["xi"]
          and c.contacts["history"]["xi"].shape == (len(k),), (c.history_slots, c.contacts.get("history")))
    loaded = int(np.count_nonzero(c.contacts["F_n"] > 0))
    check("loaded contacts = diagnostics contacts", loaded == last["contacts"], (loaded, last["contacts"]))
    wl = int(np.count_nonzero(c.wall_contacts["F_n"] > 0))
    check("loaded wall contacts = diagnostics wall_contacts", wl == last["wall_contacts"], (wl, last["wall_contacts"]))
    check("wall contacts on the floor (wall 0) only", set(c.wall_contacts["key"][:, 1].tolist()) == {0})
    w = c.walls
    check("walls: bottom left right, three lines", list(w["kind"]) == [0, 0, 0]
          and np.allclose(w["normal"], [[0, 1], [1, 0], [-1, 0]]), (w.get("kind"), w.get("normal")))
    check("walls: attributes box_width0 0.3", abs(w.attrs.get("box_width0", 0) - 0.3) < 1e-12, w.attrs)
    check("walls: the file's kind table (kind_names) names every code", w.attrs.get("kind_names") == "line segment circle"
          and c.wall_kinds() == ["line", "line", "line"], (w.attrs.get("kind_names"), c.wall_kinds()))
    table, codes = dict(w.attrs), w["kind"]
    w.attrs["kind_names"] = "segment line circle"  # a file's own table decides: code 0 is what it names
    check("walls: decoded with the file's table, not a copy of it", c.wall_kinds() == ["segment"] * 3, c.wall_kinds())
    del w.attrs["kind_names"]
    check("walls: a file without the table (before it) reads line, segment, circle", c.wall_kinds() == ["line"] * 3)
    w["kind"] = np.array([0, 7, 0])
    raises("walls: a code the table lacks is an error naming it", c.wall_kinds, "kind 7", c.path)
    w["kind"] = codes
    w.attrs.clear()
    w.attrs.update(table)
    check("ledger: KE0, W_g", {"KE0", "W_g", "W_n", "scale"} <= set(c.ledger), c.ledger)
    check("run metadata: ranks 1", c.run_metadata.get("ranks") == 1, c.run_metadata)
    checked, bad = c.verify_checksums()
    check("checksums: every dataset verified", checked >= 20 and not bad, (checked, bad))
    check("config attribute parsed", c.config.get("run", "output") == run.config.get("run", "output"))
    check("laws decoded", c.laws == {"normal": "linear", "tangential": "coulomb", "rolling": "none"}, c.laws)
    return c


def test_snapshots(run, c):
    snaps = list(run.snapshots())
    steps = [s.step for s in snaps]
    check("snapshots: in step order, every 100 steps, the last at 300",
          steps == sorted(steps) and {100, 200, 300} <= set(steps) and steps[-1] == STEPS, steps)
    last = snaps[-1]
    check("snapshot: kind, no contacts", last.kind == "snapshot" and last.contacts is None)
    check("snapshot: default fields", {"position", "velocity", "omega", "radius", "rank"} <= set(last.discs),
          sorted(last.discs))
    check("snapshot at 300: position equals the checkpoint's", np.array_equal(last.discs["position"], c.discs["position"]))
    check("snapshot: rank 0 everywhere (1 rank)", not np.any(last.discs["rank"]))
    check("snapshot: checksums", not last.verify_checksums()[1])
    raises("snapshot without theta: names output.snapshot_fields", lambda: last.disc("theta"),
           "/discs/theta", "output.snapshot_fields", last.path)
    raises("snapshot: no contacts", last.need_contacts, "checkpoint", last.path)
    check("open_any of the directory: the newest snapshot", rondel.open_any(run.path).path == last.path)
    check("xdmf found", run.xdmf is not None and run.xdmf.endswith("snapshots.xdmf"))


def test_errors(tmp, run, c):
    raises("missing file", lambda: rondel.open_file(os.path.join(tmp, "nope.h5")), "nope.h5", "no such file")
    raises("not HDF5", lambda: rondel.open_file(run.file("log.txt")), "log.txt", "not an HDF5 file")
    raises("a directory as a file", lambda: rondel.open_file(run.path), "is a directory")
    cut = os.path.join(tmp, "cut.h5")
    with open(c.path, "rb") as f, open(cut, "wb") as g:
        g.write(f.read()[:4096])
    raises("truncated checkpoint", lambda: rondel.open_file(cut), "cut.h5")
    raises("missing run directory", lambda: rondel.open_run(os.path.join(tmp, "none")), "none", "no such run")
    empty = os.path.join(tmp, "empty")
    os.makedirs(empty)
    raises("empty directory", lambda: rondel.open_run(empty), "not a Rondel run directory")
    raises("no checkpoint of that step", lambda: rondel.Run(run.path).checkpoint(step=7), "step 7")
    bad = os.path.join(tmp, "bad.csv")
    with open(bad, "w") as f:
        f.write("gid,x\n0,0x1p-3\n1,abc\n")
    raises("CSV with a non-number", lambda: rondel.read_csv(bad), "bad.csv", "'x'")
    with open(bad, "w") as f:
        f.write("gid,x\n0\n")
    raises("CSV with a short row", lambda: rondel.read_csv(bad), "bad.csv", "line 2")


def test_decimal_final(tmp):
    """final.csv in decimal with a radius column (the other form a build may write) reads the same numbers."""
    p = os.path.join(tmp, "final.csv")
    with open(p, "w") as f:
        f.write("gid,x,y,vx,vy,theta,omega,radius\n0,0x1.8p-1,-0x1p-2,0,0,0,0,0x1p-9\n"
                "1,0.75,-0.25,1e-3,0,nan,0,0.001953125\n")
    t = rondel.read_csv(p)
    check("final.csv: hexadecimal and decimal rows agree", t["x"][0] == t["x"][1] == 0.75 and t["y"][1] == -0.25
          and t["radius"][0] == t["radius"][1] == 2.0 ** -9, dict(t))
    check("final.csv: nan read", np.isnan(t["theta"][1]))


def test_summary_json(tmp, run):
    """summary.json (written beside summary.txt by builds that have it) wins, with its keys normalised."""
    d = os.path.join(tmp, "json_run")
    os.makedirs(d)
    for name in ("config.ini", "log.txt", "summary.txt"):
        shutil.copy(run.file(name), d)
    with open(os.path.join(d, "summary.json"), "w") as f:
        f.write('{"status": "complete", "steps": 300, "discs": 50, "wall_seconds": 0.5, '
                '"disc_steps_per_second": 3e4, "dt": 2e-5, "critical_dt": 1e-4, "critical_mode": "normal", '
                '"critical_pair": "material 0 R=0.002 / material 0 R=0.002"}')
    r = rondel.open_run(d)
    s = r.summary()
    check("summary.json: read, keys normalised", s["complete"] is True and s["disc_steps_per_s"] == 3e4
          and s["dt_critical"] == 1e-4 and s["source"].endswith("summary.json"), s)
    check("time step from summary.json", r.time_step() == {"dt": 2e-5, "dt_critical": 1e-4, "critical_mode": "normal",
          "critical_pair": "material 0 R=0.002 / material 0 R=0.002"}, r.time_step())
    with open(os.path.join(d, "summary.json"), "w") as f:
        f.write("{not json")
    raises("summary.json not JSON", r.summary, "summary.json", "JSON")


def test_config():
    cfg = rondel.Config("[domain]\nxlo = 0\nxhi = 1\nperiodic_x = true\n[walls]\nbox = bottom top\n")
    check("config: domain", cfg.domain() == {"xlo": 0.0, "xhi": 1.0, "ylo": None, "yhi": None, "periodic_x": True,
                                             "periodic_y": False}, cfg.domain())
    raises("config: not INI", lambda: rondel.Config("xlo = 0\n", "x.ini"), "x.ini", "INI")
    raises("config: bad boolean", lambda: rondel.Config("[domain]\nperiodic_x = maybe\n").getbool("domain", "periodic_x"),
           "periodic_x", "maybe")


def main():
    if len(sys.argv) != 2 or not os.access(sys.argv[1], os.X_OK):
        print("usage: test_reader.py BUILD/rondel (an executable)", file=sys.stderr)
        return 1
    tmp = tempfile.mkdtemp(prefix="rondel-reader-")
    try:
        d = make_run(os.path.abspath(sys.argv[1]), os.path.join(tmp, "run"))
        run, fin, diag = test_run_directory(d)
        c = test_checkpoint(run, fin, diag)
        test_snapshots(run, c)
        test_errors(tmp, run, c)
        test_decimal_final(tmp)
        test_summary_json(tmp, run)
        test_config()
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return check.summary()


if __name__ == "__main__":
    sys.exit(main())
