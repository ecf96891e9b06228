#!/usr/bin/env pvpython
"""Render a Rondel snapshot series to PNG frames with ParaView (docs/paraview.md).

Discs are drawn at their true radius (Point Gaussian representation, "Plain circle" shader, scaled by the
snapshot's `radius` dataset), coloured by a chosen field; walls and a periodic cell's edges are drawn as black lines.

    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython tools/paraview_frames.py RUN_DIR \
        [--field velocity] [--out DIR] [--size 1200x900] [--every K] [--step N] [--bounds XLO XHI YLO YHI]

RUN_DIR is a run's output directory (with snapshots.xdmf), or snapshots.xdmf itself, or one snapshot_*.h5
of it (that snapshot only). --field names a point array of the snapshots (velocity, omega, radius, flags,
rank, ...; vectors are coloured by their magnitude) or `solid` (every disc pure red, no colour bar: used by
the test that counts the disc pixels). Frames are frame_<step>.png in --out (default RUN_DIR/frames).

Exit status: 0 frames written; 1 bad input (a missing file, an unknown field, a bad option), with a message.
Tested with Debian's paraview and python3-paraview 5.11 (pvpython) under xvfb-run. -noreset keeps the X server
from resetting when ParaView closes its OpenGL probe, which on a busy machine refuses the window opened next.
"""

import argparse
import os
import sys
import xml.etree.ElementTree as ET

PROG = "paraview_frames.py"
UNITS = {"velocity": "m/s", "omega": "rad/s", "radius": "m", "theta": "rad", "force": "N", "torque": "N m",
         "mass": "kg", "inertia": "kg m^2"}  # FORMAT.md, /discs


def fail(message):
    sys.stderr.write(PROG + ": error: " + message + "\n")
    sys.exit(1)


class Parser(argparse.ArgumentParser):
    def error(self, message):  # argparse exits with 2; this tool's bad input is 1
        self.print_usage(sys.stderr)
        fail(message)


def parse_args(argv):
    p = Parser(prog=PROG, description="Render a Rondel snapshot series to PNG frames (pvpython).")
    p.add_argument("input", help="run directory, its snapshots.xdmf, or one snapshot_*.h5")
    p.add_argument("--field", default="velocity",
                   help="point array to colour by (vectors by magnitude), or 'solid' (default velocity)")
    p.add_argument("--out", help="output directory for frame_<step>.png (default RUN_DIR/frames)")
    p.add_argument("--size", default="1200x900", help="frame size WIDTHxHEIGHT in pixels (default 1200x900)")
    p.add_argument("--every", type=int, default=1, help="render every K-th snapshot (default 1: all)")
    p.add_argument("--step", type=int, help="render only the snapshot of this step")
    p.add_argument("--bounds", type=float, nargs=4, metavar=("XLO", "XHI", "YLO", "YHI"),
                   help="world region to show [m] (default: the discs and walls of the first and last frame)")
    p.add_argument("--range", type=float, nargs=2, metavar=("MIN", "MAX"),
                   help="colour range of the field (default: each frame's own range)")
    a = p.parse_args(argv)
    try:
        w, h = (int(v) for v in a.size.lower().split("x"))
        if w < 16 or h < 16 or w > 16384 or h > 16384:
            raise ValueError
    except ValueError:
        fail("--size %r: expected WIDTHxHEIGHT with 16 to 16384 pixels each, e.g. 1200x900" % a.size)
    a.width, a.height = w, h
    if a.every < 1:
        fail("--every %d: must be >= 1" % a.every)
    if a.bounds and (a.bounds[0] >= a.bounds[1] or a.bounds[2] >= a.bounds[3]):
        fail("--bounds %s: expected XLO < XHI and YLO < YHI" % " ".join("%g" % b for b in a.bounds))
    if a.range and a.range[0] >= a.range[1]:
        fail("--range %g %g: expected MIN < MAX" % tuple(a.range))
    return a


def series(path):
    """(xdmf path, [(step, time, file)], the one step asked for by a snapshot path or None)."""
    only = None
    if os.path.isdir(path):
        xdmf = os.path.join(path, "snapshots.xdmf")
    elif path.endswith(".h5"):
        xdmf, only = os.path.join(os.path.dirname(path) or ".", "snapshots.xdmf"), os.path.basename(path)
    else:
        xdmf = path
    if not os.path.isfile(xdmf):
        fail("%s: no such file (a run writes snapshots.xdmf when output.snapshot_every > 0)" % xdmf)
    try:
        root = ET.parse(xdmf).getroot()
    except ET.ParseError as e:
        fail("%s: not an XDMF file (%s)" % (xdmf, e))
    steps = []
    for grid in root.iter("Grid"):
        if grid.get("CollectionType") != "Spatial":
            continue
        time, item = grid.find("Time"), grid.find("Grid/Geometry/DataItem")
        if time is None or item is None or not grid.get("Name", "").startswith("step "):
            continue
        steps.append((int(grid.get("Name")[5:]), float(time.get("Value")), item.text.strip().split(":")[0]))
    if not steps:
        fail("%s: lists no snapshot (written by an older Rondel? rerun with this build)" % xdmf)
    if only is not None:
        steps = [s for s in steps if s[2] == only]
        if not steps:
            fail("%s is not listed in %s" % (path, xdmf))
    return os.path.abspath(xdmf), steps


def main(argv):
    a = parse_args(argv)
    xdmf, steps = series(a.input)
    if a.step is not None:
        steps = [s for s in steps if s[0] == a.step]
        if not steps:
            fail("--step %d: no snapshot of that step in %s" % (a.step, xdmf))
    steps = steps[::a.every]
    out = a.out or os.path.join(os.path.dirname(xdmf), "frames")
    try:
        os.makedirs(out, exist_ok=True)
    except OSError as e:
        fail("--out %s: cannot create the directory (%s)" % (out, e.strerror))

    try:
        import paraview.simple as pv
    except ImportError:
        fail("no ParaView Python module: run this script with pvpython (Debian: paraview, python3-paraview)")

    # The reader gives one data set per step with the discs (vertex cells) and the walls (line cells);
    # each gets its own representation.
    reader = pv.Xdmf3ReaderS(FileName=xdmf)
    discs = pv.ExtractCellsByType(Input=reader, CellTypes=["Polyvertex"])
    walls = pv.ExtractCellsByType(Input=reader, CellTypes=["Polyline"])
    discs.UpdatePipeline(steps[0][1])
    arrays = discs.PointData.keys()
    if "radius" not in arrays:
        fail("%s: the snapshots have no radius (add radius to output.snapshot_fields)" % xdmf)
    if a.field != "solid" and a.field not in arrays:
        fail("--field %s: not in the snapshots; they hold %s, or use solid (output.snapshot_fields chooses)"
             % (a.field, " ".join(sorted(arrays))))

    view = pv.CreateView("RenderView")
    view.ViewSize = [a.width, a.height]
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.CameraParallelProjection = 1

    d = pv.Show(discs, view)
    d.SetRepresentationType("Point Gaussian")
    d.ShaderPreset = "Plain circle"
    d.ScaleByArray = 1
    d.SetScaleArray = ["POINTS", "radius"]
    d.UseScaleFunction = 0  # the array's value is the radius in world units
    d.GaussianRadius = 1.0
    w = pv.Show(walls, view)
    w.ColorArrayName = ["POINTS", ""]  # solid colour (ColorBy(w, None) fails on lines without arrays: a cell alone)
    w.AmbientColor = w.DiffuseColor = [0.0, 0.0, 0.0]
    w.LineWidth = 2.0
    if a.field == "solid":
        pv.ColorBy(d, None)
        d.AmbientColor = d.DiffuseColor = [1.0, 0.0, 0.0]
    else:
        vector = discs.PointData[a.field].GetNumberOfComponents() > 1
        pv.ColorBy(d, ("POINTS", a.field, "Magnitude") if vector else ("POINTS", a.field))
        lut = pv.GetColorTransferFunction(a.field)
        bar = pv.GetScalarBar(lut, view)
        bar.Title = a.field + (" magnitude" if vector else "") + (" [%s]" % UNITS[a.field] if a.field in UNITS else "")
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
        bar.WindowLocation = "Any Location"  # right of the discs: place_camera leaves room for it
        bar.ScalarBarLength = 0.8
        bar.AutomaticLabelFormat = 0
        bar.LabelFormat = bar.RangeLabelFormat = "%-#.3g"
        d.SetScalarBarVisibility(view, True)
    label = pv.Text(Text="")
    t = pv.Show(label, view)
    t.Color = [0.0, 0.0, 0.0]
    t.WindowLocation = "Upper Left Corner"
    t.FontSize = 14

    right = place_camera(view, a, discs, walls, steps)
    if a.field != "solid":
        bar.Position = [min(right + 0.04, 0.85), 0.1]
    for step, time, _ in steps:
        view.ViewTime = time
        label.Text = "step %d, t = %.6g s" % (step, time)
        if a.field != "solid":
            lut = pv.GetColorTransferFunction(a.field)
            if a.range:
                lut.RescaleTransferFunction(a.range[0], a.range[1])
            else:
                d.RescaleTransferFunctionToDataRange(False, True)
        path = os.path.join(out, "frame_%010d.png" % step)
        pv.SaveScreenshot(path, view, ImageResolution=[a.width, a.height], TransparentBackground=0)
        print(path)
    return 0


def place_camera(view, a, discs, walls, steps):
    """A fixed 2D camera for the whole series: --bounds, or the first and last frames' discs and walls.
    Returns where the data ends on the right, as a fraction of the frame's width (the colour bar goes there)."""
    if a.bounds:
        xlo, xhi, ylo, yhi = a.bounds
    else:
        box = [float("inf"), -float("inf"), float("inf"), -float("inf")]
        for time in {steps[0][1], steps[-1][1]}:
            for src in (discs, walls):
                src.UpdatePipeline(time)
                b = src.GetDataInformation().GetBounds()
                if b[0] <= b[1]:
                    box = [min(box[0], b[0]), max(box[1], b[1]), min(box[2], b[2]), max(box[3], b[3])]
        xlo, xhi, ylo, yhi = box  # disc centres and wall ends: add the largest radius and a margin
        pad = discs.PointData["radius"].GetRange()[1] + 0.02 * max(xhi - xlo, yhi - ylo)
        xlo, xhi, ylo, yhi = xlo - pad, xhi + pad, ylo - pad, yhi + pad
    data_right = xhi
    if a.field != "solid":
        xhi += 0.25 * (xhi - xlo)  # room for the colour bar
    cx, cy = 0.5 * (xlo + xhi), 0.5 * (ylo + yhi)
    view.CameraPosition = [cx, cy, 1.0]
    view.CameraFocalPoint = [cx, cy, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    # Parallel scale: half the world height shown; the narrower of the two fits decides.
    scale = max(0.5 * (yhi - ylo), 0.5 * (xhi - xlo) * a.height / a.width)
    view.CameraParallelScale = scale
    half_width = scale * a.width / a.height
    return 0.5 + (data_right - cx) / (2.0 * half_width)  # the data's right edge, as a fraction of the width


if __name__ == "__main__":
    status = main(sys.argv[1:])
    # Skip the interpreter's teardown: under xvfb-run, ParaView 5.11's render window dies on exit with
    # "X Error ... GLXBadContext" and exit status 1 after every frame was written.
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)
