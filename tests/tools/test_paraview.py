#!/usr/bin/python3
"""ParaView out of the box (docs/paraview.md): a tiny run with snapshots made by the built rondel loads in
pvpython (one point and one vertex cell per disc, one line cell per wall, at every step, step 0 included),
and tools/paraview_frames.py renders a frame whose disc pixels cover the discs' true area; in a sheared periodic
cell, the cell's four edges are line cells at the corners its /cell records, and the frame tool draws them.

    test_paraview.py RONDEL_BINARY

Exit 0 pass, 1 fail, 77 skipped (no pvpython or Xvfb: ctest SKIP_RETURN_CODE; with CI=true, where
tools/setup.sh installs them, their absence fails).
"""

import os
import re
import select
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "tools", "paraview_frames.py")
SKIP = 77

# 4 x 3 discs of radius 5 mm, 12.5 mm apart (never touching), at rest without gravity in a closed box.
INI = """[run]
steps = 20
dt = 1e-5
progress = false
[diagnostics]
every = 10
[output]
snapshot_every = 10
[domain]
xlo = 0
xhi = 0.1
ylo = 0
yhi = 0.08
[material]
density = 2650
[linear]
k_n = 1e6
[coulomb]
k_s = 0.75e6
mu = 0.5
[walls]
box = bottom left right top
[scene]
type = lattice_square
nx = 4
ny = 3
radius = 0.005
spacing = 0.0125
x0 = 0.02
y0 = 0.02
"""
DISCS, WALLS, RADIUS = 12, 4, 0.005
# The same discs in a cell periodic both ways, sheared (docs/physics.md section 10): no walls; the cell's four
# edges are line cells.
CELL_INI = INI.replace("[walls]\nbox = bottom left right top\n", "[cell]\nrate_xy = 100\n").replace(
    "yhi = 0.08\n", "yhi = 0.08\nperiodic_x = true\nperiodic_y = true\n")

# Run by pvpython: counts per step with the readers ParaView offers for .xdmf.
LOAD = r"""
import sys
from paraview.simple import Xdmf3ReaderS, XDMFReader, ExtractCellsByType, servermanager
path = sys.argv[1]
for name, reader in (("Xdmf3ReaderS", Xdmf3ReaderS(FileName=path)), ("XDMFReader", XDMFReader(FileNames=[path]))):
    times = list(reader.TimestepValues)
    for t in times:
        for kind in ("Polyvertex", "Polyline"):
            e = ExtractCellsByType(Input=reader, CellTypes=[kind])
            e.UpdatePipeline(t)
            d = servermanager.Fetch(e)
            print(name, len(times), t, kind, d.GetNumberOfPoints(), d.GetNumberOfCells())
sys.stdout.flush()
import os
os._exit(0)
"""

failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + ("" if ok else ": " + str(detail)))
    if not ok:
        failures.append(what)


def run(cmd, **kw):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                       timeout=300, **kw)
    return p.returncode, p.stdout


class XServer:
    """One Xvfb for the whole test, on a display it picks itself (-displayfd: no race for a display number, as
    `xvfb-run -a` has with any other X server starting at the same moment), restarted if a client could not use it."""

    def __init__(self):
        self.proc, self.display, self.log = None, None, None

    def start(self):
        # Its messages go to a file, not a pipe nobody reads (a full pipe would stop the server).
        self.log = tempfile.TemporaryFile()
        r, w = os.pipe()
        # -noreset: an X server resets when its last client leaves, and ParaView opens and closes a display to
        # probe OpenGL before it opens its window; on a busy machine that window's connection came during the
        # reset and was refused ("bad X server connection": the CI failed so twice; here, under load, 9 refusals
        # in 3 runs without -noreset, none in 9 with it).
        self.proc = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-screen", "0", "1280x1024x24", "-noreset",
                                      "-nolisten", "tcp"], pass_fds=(w,), stdout=subprocess.DEVNULL, stderr=self.log)
        os.close(w)
        # Xvfb writes the display number once it accepts connections; EOF if it died; 60 s at most.
        number = b""
        with os.fdopen(r, "rb") as f:
            while not number.endswith(b"\n") and select.select([f], [], [], 60)[0]:
                byte = f.read(1)
                if not byte:
                    break
                number += byte
        if not number.strip().isdigit():
            why = self.messages()
            self.stop()
            raise RuntimeError("Xvfb gave no display (it ended, or 60 s passed): " + why)
        self.display = ":" + number.decode().strip()

    def messages(self):
        self.log.seek(0)
        return self.log.read().decode(errors="replace")[-500:]

    def stop(self):
        if self.proc is not None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        if self.log is not None:
            self.log.close()
        self.proc, self.display, self.log = None, None, None


X = XServer()
UNUSABLE = ("CreateAWindow", "vtkXOpenGLRenderWindow", "XSync", "cannot open display", "bad X server",
            "Could not find a decent")


def why(out):
    """The lines of a ParaView failure that are not its stack frames, without terminal colours."""
    plain = (re.sub(r"\x1b\[[0-9;]*m", "", l).strip() for l in out.splitlines())
    return [l for l in plain if l and not re.match(r"^\d+\s+0x", l)][:4]


def pvpython(args):
    # A client that finds the X server unusable (ParaView aborts creating its window) gets a new server, after a
    # pause that grows; nothing else is retried. The first lines of a failure are printed: they say why.
    rc, out = 1, "no X server"
    for attempt in range(4):
        try:
            if X.display is None:
                X.start()
            rc, out = run(["pvpython"] + args, env=dict(os.environ, DISPLAY=X.display))
        except RuntimeError as e:
            rc, out = 1, "cannot open display: " + str(e)
        if not any(s in out for s in UNUSABLE):
            break
        print("note: the X server %s was not usable (attempt %d), starting another: %s"
              % (X.display or "(none)", attempt + 1, " | ".join(why(out))[:400]))
        X.stop()
        time.sleep(2 * (attempt + 1))
    return rc, out


def cell_edges(xdmf, out, step):
    """The inline points of the step's "cell" grid equal the corners from the snapshot's /cell attributes."""
    import xml.etree.ElementTree as ET
    import h5py
    for grid in ET.parse(xdmf).getroot().iter("Grid"):
        if grid.get("Name") != "step %d" % step:
            continue
        for sub in grid.findall("Grid"):
            if sub.get("Name") == "cell":
                got = [float(v) for v in sub.find("Geometry/DataItem").text.split()]
                with h5py.File(os.path.join(out, "snapshot_%010d.h5" % step), "r") as f:
                    c = dict(f["/cell"].attrs)
                a, b = (c["xlo"], c["ylo"]), (c["xhi"], c["ylo"])
                d, e = (c["xhi"] + c["tilt"], c["yhi"]), (c["xlo"] + c["tilt"], c["yhi"])
                want = [v for p in (a, b, b, d, d, e, e, a) for v in p]
                return c["tilt"] > 0 and got == want
    return False


def red_pixels(png):
    import matplotlib.image
    img = matplotlib.image.imread(png)  # floats in [0, 1], RGB or RGBA
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return int(((r > 0.6) & (g < 0.4) & (b < 0.4)).sum()), img.shape


def main():
    if len(sys.argv) != 2:
        print("usage: test_paraview.py RONDEL_BINARY")
        return 1
    missing = [t for t in ("pvpython", "Xvfb") if shutil.which(t) is None]
    if missing and os.environ.get("CI") == "true":  # CI installs them (tools/setup.sh): missing is a failure
        print("FAIL: %s not installed although CI=true (tools/setup.sh installs paraview python3-paraview xvfb)"
              % " and ".join(missing))
        return 1
    if missing:
        print("SKIP: %s not installed (Debian: paraview python3-paraview xvfb); the ParaView test needs them"
              % " and ".join(missing))
        return SKIP
    rondel = os.path.abspath(sys.argv[1])
    tmp = tempfile.mkdtemp(prefix="rondel-paraview-")
    try:
        ini, out = os.path.join(tmp, "tiny.ini"), os.path.join(tmp, "run")
        with open(ini, "w") as f:
            f.write(INI)
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        rc, log = run([rondel, ini, "--run.output=" + out], env=env)
        check("rondel writes the tiny run", rc == 0, log[-2000:])
        if rc != 0:
            return 1
        for step in (0, 10, 20):
            name = "snapshot_%010d.h5" % step
            check("snapshot of step %d (step 0: the initial state)" % step, os.path.isfile(os.path.join(out, name)))
        xdmf = os.path.join(out, "snapshots.xdmf")
        text = open(xdmf).read()
        check("snapshots.xdmf lists the flags", 'Name="flags"' in text)
        check("snapshots.xdmf gives the vertex cells their connectivity", "/discs/index" in text)

        loader = os.path.join(tmp, "load.py")
        with open(loader, "w") as f:
            f.write(LOAD)
        rc, got = pvpython([loader, xdmf])
        rows = [l.split() for l in got.splitlines() if l.startswith(("Xdmf3ReaderS ", "XDMFReader "))]
        check("pvpython loads the series", rc == 0 and len(rows) == 2 * 3 * 2, got[-3000:])
        for r in rows:
            reader, steps, t, kind, points, cells = r[0], int(r[1]), r[2], r[3], int(r[4]), int(r[5])
            want = (DISCS, DISCS) if kind == "Polyvertex" else (2 * WALLS, WALLS)
            check("%s at t = %s: %s points and cells %s (want %s), 3 steps" % (reader, t, kind, (points, cells),
                                                                             want), steps == 3 and
                  (points, cells) == want)

        # A sheared cell: its edges at every step, as the snapshot's /cell records them, drawn by the frame tool.
        cell_ini, cell_out = os.path.join(tmp, "cell.ini"), os.path.join(tmp, "cell")
        with open(cell_ini, "w") as f:
            f.write(CELL_INI)
        rc, log = run([rondel, cell_ini, "--run.output=" + cell_out], env=env)
        check("rondel writes the tiny sheared cell", rc == 0, log[-2000:])
        if rc == 0:
            cell_xdmf = os.path.join(cell_out, "snapshots.xdmf")
            rc, got = pvpython([loader, cell_xdmf])
            lines = [l.split() for l in got.splitlines() if l.startswith("Xdmf3ReaderS ") and " Polyline " in l]
            check("the cell: 8 points and 4 line cells at each of 3 steps",
                  rc == 0 and len(lines) == 3 and all(r[4:6] == ["8", "4"] for r in lines), got[-3000:])
            check("the cell's edges at step 20 are those of its /cell", cell_edges(cell_xdmf, cell_out, 20))
            rc, got = pvpython([SCRIPT, cell_out, "--step", "20", "--out", os.path.join(tmp, "cell_frames"),
                                "--size", "300x200"])
            check("paraview_frames.py draws a cell without walls", rc == 0, got[-2000:])

        # One frame, discs pure red: their pixel count is their area in pixels (not blank, true radius).
        frames = os.path.join(tmp, "frames")
        w, h, bounds = 500, 400, ("0", "0.1", "0", "0.08")  # 5000 pixels per metre both ways
        rc, got = pvpython([SCRIPT, out, "--field", "solid", "--step", "20", "--size", "%dx%d" % (w, h),
                            "--out", frames, "--bounds"] + list(bounds))
        png = os.path.join(frames, "frame_0000000020.png")
        check("paraview_frames.py renders step 20", rc == 0 and os.path.isfile(png), got[-3000:])
        if os.path.isfile(png):
            n, shape = red_pixels(png)
            want = DISCS * 3.141592653589793 * (RADIUS * 5000.0) ** 2
            check("frame is %dx%d" % (w, h), shape[0] == h and shape[1] == w, shape)
            check("disc pixels %d within 5 %% of the discs' area %.0f px" % (n, want), abs(n - want) < 0.05 * want)
        rc, got = pvpython([SCRIPT, out, "--step", "20", "--out", frames, "--size", "300x200"])
        check("coloured by velocity (the default) renders", rc == 0, got[-2000:])

        # Bad input: exit 1 with a message naming what is wrong.
        for args, words in (([out, "--field", "nosuch"], "--field nosuch"), ([tmp + "/none"], "no such file"),
                            ([out, "--size", "big"], "--size"), ([out, "--step", "7"], "--step 7")):
            rc, got = pvpython([SCRIPT] + args + ["--out", frames])
            check("bad input %s: exit 1 naming it" % " ".join(args[1:] or args), rc == 1 and words in got, (rc, got))
    finally:
        X.stop()
        shutil.rmtree(tmp, ignore_errors=True)
    print("%d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
