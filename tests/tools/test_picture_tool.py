#!/usr/bin/python3
"""Tests of tools/picture.py on small synthetic Rondel files (ctest: tools.picture).

The files are written with h5py following FORMAT.md (root attributes format, format_version, kind, step,
time, config, complete; /discs, /contacts, /wall_contacts, /walls, every dataset with its checksum).
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import csv
import os
import struct
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.join(HERE, "..", "..", "tools")
TOOL = os.path.join(TOOLS, "picture.py")
sys.path.insert(0, TOOLS)
import picture  # noqa: E402
from rondel import checksum  # noqa: E402

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))


def config_text(xlo=0.0, xhi=1.0, ylo=0.0, yhi=1.0, px=False, py=False):
    return (f"[run]\nsteps = 10\n\n[domain]\nxlo = {xlo}\nxhi = {xhi}\nylo = {ylo}\nyhi = {yhi}\n"
            f"periodic_x = {'true' if px else 'false'}\nperiodic_y = {'true' if py else 'false'}\n\n"
            "[walls]\nbox = bottom\n")


def write_state(path, kind="checkpoint", step=10, config=None, discs=None, contacts=None,
                wall_contacts=None, walls=None, fmt="rondel", bonds=None):
    """A Rondel file: DISCS / CONTACTS / WALL_CONTACTS / WALLS / BONDS are dicts of dataset name -> array (a dict
    of arrays for a subgroup: history)."""
    def put(group, name, data):
        ds = group.create_dataset(name, data=data)
        ds.attrs["checksum"] = np.uint64(checksum(np.asarray(data)))

    with h5py.File(path, "w") as f:
        f.attrs["format"] = np.bytes_(fmt)
        f.attrs["format_version"] = np.int64(1)
        f.attrs["kind"] = np.bytes_(kind)
        f.attrs["step"] = np.int64(step)
        f.attrs["time"] = np.float64(step * 1e-5)
        f.attrs["dt"] = np.float64(1e-5)
        f.attrs["config"] = np.bytes_(config if config is not None else config_text())
        for gname, content in (("discs", discs), ("contacts", contacts), ("wall_contacts", wall_contacts),
                               ("walls", walls), ("bonds", bonds)):
            if content is None:
                continue
            g = f.create_group(gname)
            for name, data in content.items():
                if isinstance(data, dict):
                    sub = g.create_group(name)
                    for slot, values in data.items():
                        put(sub, slot, values)
                else:
                    put(g, name, data)
        f.attrs["complete"] = np.int64(1)


def discs_of(pos, radius, **extra):
    pos = np.asarray(pos, dtype=np.float64).reshape(-1, 2)
    n = len(pos)
    d = {"gid": np.arange(n, dtype=np.int64) * 3 + 7,  # not 0..n-1: rows must be found by gid
         "radius": np.asarray(radius, dtype=np.float64) * np.ones(n),
         "position": pos,
         "theta": np.linspace(-2.0, 3.0, n),
         "omega": np.linspace(1.0, -1.0, n),
         "flags": np.zeros(n, dtype=np.uint32)}
    d.update(extra)
    return d


def bottom_wall():
    return {"kind": np.array([0, 1], dtype=np.int32),
            "p0": np.array([[0.0, 0.0], [0.2, 0.9]]),
            "p1": np.array([[0.0, 0.0], [0.8, 0.9]]),
            "normal": np.array([[0.0, 1.0], [0.0, -1.0]])}


def run_tool(*args):
    p = subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def png_size(path):
    """(width, height) from a PNG's IHDR chunk."""
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def read_csv(path):
    with open(path) as f:
        return list(csv.reader(f))


def test_segments_minimum_image():
    dom = picture.parse_domain(config_text(0.0, 1.0, 0.0, 2.0, px=True, py=False))
    check("parse_domain periodic_x true / periodic_y false", dom["periodic_x"] and not dom["periodic_y"], dom)
    p1 = np.array([[0.05, 0.50], [0.40, 0.40]])
    p2 = np.array([[0.95, 0.52], [0.43, 0.44]])  # contact 0 wraps in x, contact 1 does not
    seg, idx = picture.contact_segments(p1, p2, dom)
    lengths = np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1)
    d_min = np.hypot(0.10, 0.02)
    check("wrapping contact gives two segments, the other one", sorted(idx.tolist()) == [0, 0, 1], idx)
    check("wrapping segments have the minimum-image length",
          np.allclose(lengths[idx == 0], d_min, rtol=0, atol=1e-12), (lengths[idx == 0], d_min))
    check("plain segment has the Euclidean length", abs(lengths[idx == 1][0] - 0.05) < 1e-12, lengths)
    s0 = seg[idx == 0]
    check("segment starts at disc 1, mirror ends at disc 2",
          len(s0) == 2 and np.allclose(s0[0, 0], p1[0]) and np.allclose(s0[1, 1], p2[0]), s0)
    check("no wrapped segment spans the box (|dx| < half box)",
          np.all(np.abs(seg[:, 1, 0] - seg[:, 0, 0]) < 0.5), seg)
    # The same pair in a box that is not periodic: one segment across.
    seg2, idx2 = picture.contact_segments(p1[:1], p2[:1], picture.parse_domain(config_text()))
    check("non-periodic: one segment of the full distance",
          len(seg2) == 1 and abs(np.linalg.norm(seg2[0, 1] - seg2[0, 0]) - np.hypot(0.9, 0.02)) < 1e-12, seg2)
    # Periodic in y too: a corner contact.
    dom_xy = picture.parse_domain(config_text(0.0, 1.0, 0.0, 1.0, px=True, py=True))
    seg3, _ = picture.contact_segments([[0.02, 0.03]], [[0.97, 0.99]], dom_xy)
    check("corner contact (x and y periodic): minimum-image length",
          np.allclose(np.linalg.norm(seg3[:, 1] - seg3[:, 0], axis=1), np.hypot(0.05, 0.04)), seg3)


def test_wall_points():
    w = bottom_wall()
    q = picture.wall_points([[0.3, 0.25], [0.1, 0.7], [0.5, 0.8]], [0, 1, 1], w["kind"], w["p0"], w["p1"],
                            w["normal"])
    check("wall point: foot on a line, clamped end and interior of a segment",
          np.allclose(q, [[0.3, 0.0], [0.2, 0.9], [0.5, 0.9]]), q)


def test_forces(tmp):
    pos = [[0.05, 0.5], [0.95, 0.5], [0.3, 0.3], [0.36, 0.3], [0.3, 0.36], [0.6, 0.05]]
    discs = discs_of(pos, 0.03)
    g = discs["gid"]
    key = np.array([[g[0], g[1]], [g[2], g[3]], [g[2], g[4]], [g[3], g[4]]], dtype=np.int64)
    Fn = np.array([1.5, 0.0, 2.25, 0.125])  # the zero row carries history only: not drawn, not listed
    path = os.path.join(tmp, "checkpoint_0000000010.h5")
    write_state(path, config=config_text(px=True), discs=discs, contacts={"key": key, "F_n": Fn},
                wall_contacts={"key": np.array([[g[5], 0]], dtype=np.int64), "F_n": np.array([3.0])},
                walls=bottom_wall())
    prefix = os.path.join(tmp, "out", "forces")
    rc, out = run_tool(path, "--kind", "forces", "--out", prefix, "--dpi", "50", "--width", "6")
    check("forces: exit 0", rc == 0, out)
    rows = read_csv(prefix + ".csv")
    want = [[str(a), str(b), repr(F)] for (a, b), F in zip(key.tolist(), Fn.tolist()) if F > 0]
    check("forces CSV: header gid1,gid2,F_n", rows[:1] == [["gid1", "gid2", "F_n"]], rows[:1])
    check("forces CSV: exactly the loaded contacts with their F_n", rows[1:] == want, (rows[1:], want))
    wrows = read_csv(prefix + "_walls.csv")
    check("forces walls CSV: the wall contact", wrows == [["gid", "wall", "F_n"], [str(g[5]), "0", "3.0"]],
          wrows)
    size = png_size(prefix + ".png")
    check("forces PNG: 6 in x 50 dpi = 300 px wide", size is not None and size[0] == 300 and size[1] > 50, size)
    # A snapshot has no contacts: a clear error.
    snap = os.path.join(tmp, "snapshot_0000000010.h5")
    write_state(snap, kind="snapshot", discs={"position": np.array(pos), "radius": np.full(6, 0.03)})
    rc, out = run_tool(snap, "--kind", "forces", "--out", os.path.join(tmp, "x"))
    check("forces on a snapshot: exit 1 naming /contacts", rc == 1 and 'Traceback' not in out and "/contacts" in out, (rc, out))


def test_bonds(tmp):
    pos = [[0.2, 0.5], [0.26, 0.5], [0.32, 0.5], [0.8, 0.5]]
    discs = discs_of(pos, 0.03)
    g = discs["gid"]
    key = np.array([[g[0], g[1]], [g[1], g[2]]], dtype=np.int64)
    history = {"Fb_n": np.array([2.5, -1.25]), "Fb_s": np.array([0.5, 0.0]), "Mb": np.array([0.0, 1e-3])}
    path = os.path.join(tmp, "checkpoint_0000000020.h5")
    write_state(path, step=20, discs=discs, walls=bottom_wall(), bonds={"key": key, "history": history})
    prefix = os.path.join(tmp, "out", "bonds")
    rc, out = run_tool(path, "--kind", "bonds", "--out", prefix, "--dpi", "60", "--width", "6")
    check("bonds: exit 0", rc == 0, out)
    rows = read_csv(prefix + ".csv")
    want = [["gid1", "gid2", "Fb_n", "Fb_s", "Mb"]] + [
        [str(a), str(b), repr(n), repr(s), repr(m)]
        for (a, b), n, s, m in zip(key.tolist(), *(history[k].tolist() for k in ("Fb_n", "Fb_s", "Mb")))]
    check("bonds CSV: every intact bond with its state, exact", rows == want, (rows, want))
    check("bonds PNG: the tension bond drawn red", red_pixels(prefix + ".png") > 20, red_pixels(prefix + ".png"))
    # A checkpoint of a run without bonds: a clear error naming [bonds].
    plain = os.path.join(tmp, "checkpoint_0000000030.h5")
    write_state(plain, step=30, discs=discs, walls=bottom_wall())
    rc, out = run_tool(plain, "--kind", "bonds", "--out", os.path.join(tmp, "y"))
    check("bonds without /bonds: exit 1 naming [bonds]", rc == 1 and "Traceback" not in out and "[bonds]" in out,
          (rc, out))


def test_ranks(tmp):
    rank = np.array([2, 0, 0, 1, 2, 0, 0, 2, 1, 0], dtype=np.int32)
    pos = np.column_stack([np.linspace(0.1, 0.9, 10), np.full(10, 0.2)])
    path = os.path.join(tmp, "snapshot_0000000020.h5")
    write_state(path, kind="snapshot", step=20,
                discs={"position": pos, "radius": np.full(10, 0.04), "rank": rank}, walls=bottom_wall())
    prefix = os.path.join(tmp, "ranks")
    rc, out = run_tool(path, "--kind", "ranks", "--out", prefix, "--dpi", "40", "--width", "5",
                       "--title", "ranks test")
    check("ranks: exit 0", rc == 0, out)
    rows = read_csv(prefix + ".csv")
    check("ranks CSV counts", rows == [["rank", "count"], ["0", "5"], ["1", "2"], ["2", "3"]], rows)
    size = png_size(prefix + ".png")
    check("ranks PNG: 5 in x 40 dpi = 200 px wide, non-empty",
          size is not None and size[0] == 200 and os.path.getsize(prefix + ".png") > 1000, size)
    rc, out = run_tool(path, "--kind", "ranks", "--out", prefix + "_pal", "--dpi", "40", "--width", "5",
                       "--palette")
    with open(prefix + "_pal.png", "rb") as f:
        head = f.read(26)
    check("--palette: an 8-bit palette PNG (IHDR colour type 3) of the same size",
          rc == 0 and head[25] == 3 and png_size(prefix + "_pal.png") == size, (rc, out, head[24:26]))
    # Without /discs/rank: non-zero exit and a message naming output.snapshot_fields.
    norank = os.path.join(tmp, "norank", "snapshot_0000000030.h5")
    os.makedirs(os.path.dirname(norank))
    write_state(norank, kind="snapshot", step=30, discs={"position": pos, "radius": np.full(10, 0.04)})
    rc, out = run_tool(os.path.dirname(norank), "--kind", "ranks", "--out", os.path.join(tmp, "nr"))
    check("ranks without /discs/rank: non-zero exit naming output.snapshot_fields",
          rc == 1 and "output.snapshot_fields" in out and "/discs/rank" in out, (rc, out))
    check("ranks without /discs/rank: no PNG written", not os.path.exists(os.path.join(tmp, "nr.png")))


def grey_pixels(png):
    import matplotlib.image as mpimg
    img = mpimg.imread(png)[..., :3]
    return int(np.sum(np.all(np.abs(img - 0.55) < 0.02, axis=-1)))


def red_pixels(png):
    import matplotlib.image as mpimg
    img = mpimg.imread(png)[..., :3]
    return int(np.sum((img[..., 0] > 0.35) & (img[..., 1] < 0.1) & (img[..., 2] < 0.2)))


def test_rotation(tmp):
    pos = [[0.3, 0.5], [0.7, 0.5]]
    for fixed in (0, 1):
        d = discs_of(pos, 0.2, theta=np.array([5.0, 5.0]), flags=np.array([fixed, 0], dtype=np.uint32))
        path = os.path.join(tmp, f"rot{fixed}.h5")
        write_state(path, discs=d, walls=bottom_wall())
        prefix = os.path.join(tmp, f"rot{fixed}")
        rc, out = run_tool(path, "--kind", "rotation", "--out", prefix, "--dpi", "60", "--width", "6",
                           "--vmax", "5")
        check(f"rotation (fixed={fixed}): exit 0", rc == 0, out)
        grey, red = grey_pixels(prefix + ".png"), red_pixels(prefix + ".png")
        if fixed:
            check("rotation: a fixed disc is drawn grey", grey > 2000, grey)
            check("rotation: the free disc with theta = +vmax is dark red", red > 2000, red)
        else:
            # a few hundred anti-aliased text pixels (the colour-bar label below a wide view) are grey too;
            # a fixed disc gives more than 2000
            check("rotation: no grey disc when no disc is fixed", grey < 600, grey)
            check("rotation: two dark red discs without fixed ones", red > 4000, red)
        check(f"rotation PNG (fixed={fixed}): 360 px wide", (png_size(prefix + ".png") or (0,))[0] == 360)
    # omega, and a snapshot without theta names the key.
    rc, out = run_tool(os.path.join(tmp, "rot0.h5"), "--kind", "rotation", "--field", "omega", "--out",
                       os.path.join(tmp, "omega"))
    check("rotation --field omega: exit 0", rc == 0 and os.path.getsize(os.path.join(tmp, "omega.png")) > 0, out)
    snap = os.path.join(tmp, "notheta.h5")
    write_state(snap, kind="snapshot", discs={"position": np.array(pos), "radius": np.full(2, 0.1)})
    rc, out = run_tool(snap, "--kind", "rotation", "--out", os.path.join(tmp, "nt"))
    check("rotation without theta: non-zero exit naming output.snapshot_fields",
          rc == 1 and "/discs/theta" in out and "output.snapshot_fields" in out, (rc, out))


def test_errors_and_directory(tmp):
    rc, out = run_tool(os.path.join(tmp, "nope.h5"), "--kind", "rotation", "--out", os.path.join(tmp, "n"))
    check("missing file: exit 1, message", rc == 1 and 'Traceback' not in out and "no such file" in out, (rc, out))
    other = os.path.join(tmp, "other.h5")
    write_state(other, fmt="something", discs=discs_of([[0.5, 0.5]], 0.1))
    rc, out = run_tool(other, "--kind", "rotation", "--out", os.path.join(tmp, "o"))
    check("format != rondel: exit 1, 'not a Rondel checkpoint'", rc == 1 and "not a Rondel checkpoint" in out,
          (rc, out))
    text = os.path.join(tmp, "text.h5")
    with open(text, "w") as f:
        f.write("not hdf5\n")
    rc, out = run_tool(text, "--kind", "rotation", "--out", os.path.join(tmp, "t"))
    check("not HDF5: exit 1, message", rc == 1 and "not an HDF5 file" in out, (rc, out))
    # A run directory: newest snapshot for rotation, newest checkpoint for forces.
    run = os.path.join(tmp, "run")
    os.makedirs(run)
    d = discs_of([[0.3, 0.5], [0.36, 0.5]], 0.03)
    c = {"key": np.array([[d["gid"][0], d["gid"][1]]], dtype=np.int64), "F_n": np.array([1.0])}
    for step in (10, 200):
        write_state(os.path.join(run, f"snapshot_{step:010d}.h5"), kind="snapshot", step=step, discs=d)
        write_state(os.path.join(run, f"checkpoint_{step:010d}.h5"), step=step, discs=d, contacts=c)
    write_state(os.path.join(run, "checkpoint_0000000030.h5"), step=30, discs=d, contacts=c)
    rc, out = run_tool(run, "--kind", "rotation", "--out", os.path.join(tmp, "dir_rot"))
    check("directory, rotation: newest snapshot", rc == 0 and "snapshot_0000000200.h5" in out, out)
    rc, out = run_tool(run, "--kind", "forces", "--out", os.path.join(tmp, "dir_f"))
    check("directory, forces: newest checkpoint", rc == 0 and "checkpoint_0000000200.h5" in out, out)
    empty = os.path.join(tmp, "empty")
    os.makedirs(empty)
    rc, out = run_tool(empty, "--kind", "forces", "--out", os.path.join(tmp, "e"))
    check("empty directory: exit 1 naming checkpoint_*.h5", rc == 1 and 'Traceback' not in out and "checkpoint_*.h5" in out,
          (rc, out))


def main():
    with tempfile.TemporaryDirectory() as tmp:
        test_segments_minimum_image()
        test_wall_points()
        test_forces(tmp)
        test_bonds(tmp)
        test_ranks(tmp)
        test_rotation(tmp)
        test_errors_and_directory(tmp)
    failed = results.count(False)
    print(f"{results.count(True)} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
