#!/usr/bin/python3
"""Biaxial specimen by multi-layer undercompaction (Jiang, Konrad & Leroueil 2003), J05 set-up: N discs built in
n layers, each generated loose above the layers below and compacted by the top wall to a target height, then
isotropic consolidation to the confining stress. The result feeds inputs/biaxial_jiang.ini.

  python3 tools/undercompaction.py --out rondel-output-biaxial/ucm [--layers 6] [--e 0.25] [--u1 0.1]
      [--pressure 2e5] [--count 1008] [--width 0.18] [--damping 0]
  build/rondel inputs/biaxial_jiang.ini --scene.file=rondel-output-biaxial/ucm/consolidated \\
      --contact.rolling=none --run.reset_history=true --run.output=...

Undercompaction rule: layer i (1 = bottom) is compacted until the average planar void ratio of layers 1..i
below the wall is e_i = e (1 + U_i), U_i = U_1 - (U_1 - U_n) (i - 1)/(n - 1): the top wall moves down to
h_i = A_1..i (1 + e_i) / W (A: the discs' area, W: the box width). U_n = 0 makes the last wall height the
specimen's at the target e. Lower layers are left looser because compacting the layers above densifies them.

Each stage is one rondel run: a layer stage starts from a CSV scene (the discs of the previous stage's final.csv,
at rest, and the new layer's discs placed at random, without overlap, at the area fraction --loose above them)
with inputs/biaxial_ucm_layer.ini, the top wall compacting at a constant true strain rate (initial speed
--wall-speed) for the steps that bring it to h_i; the consolidation continues the last layer's state
(scene.type = file, contact history kept) with inputs/biaxial_ucm_consolidate.ini (top and right walls servo to
--pressure). Friction: --mu (0.25) in the layer stages, --consolidate-mu (0.5, the shear stage's) in the
consolidation; with 0.5 throughout the bottom layer jams (1.7 MPa on the wall) before its target.
Diameters: --dmin to --dmax with the J05 grading (by area: d10 6.15 mm, d50 7.6 mm, d60 8.0 mm,
d60/d10 = 1.30, piecewise linear between), drawn stratified (the exact grading) and shuffled by --seed.

Writes OUT/layer_K.csv and OUT/layer_K/ (the layer stages), OUT/consolidated/ (its final checkpoint is the
specimen), OUT/layers.csv (targets and reached heights), OUT/profile.csv (void ratio by height band) and
OUT/summary.txt. Exit status: 0 done, 1 bad input or usage, 2 a rondel run failed.
"""
import math
import os
import random
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from rondel import CheckFailed, open_run, study  # noqa: E402
from rondel.cli import ArgumentParser, run_tool  # noqa: E402

TOOL = "undercompaction"

# The J05 grading by area (mass): cumulative fraction at each diameter [mm], linear between.
GRADING_D = (6.0, 6.15, 7.6, 8.0, 9.0)
GRADING_P = (0.0, 0.1, 0.5, 0.6, 1.0)


def diameters(count, dmin, dmax, seed):
    """COUNT diameters [m] with the grading GRADING_* stretched to [dmin, dmax]: the number distribution
    (area density / d^2) inverted at the quantiles (k + 1/2)/COUNT, shuffled by SEED."""
    s = (dmax - dmin) / (GRADING_D[-1] - GRADING_D[0])
    D = [dmin + (d - GRADING_D[0]) * s for d in GRADING_D]
    seg = []  # (a, b, c, cumulative number at a): number density c / d^2 on [a, b]
    total = 0.0
    for k in range(len(D) - 1):
        a, b = D[k], D[k + 1]
        c = (GRADING_P[k + 1] - GRADING_P[k]) / (b - a)
        seg.append((a, b, c, total))
        total += c * (1.0 / a - 1.0 / b)
    out = []
    for k in range(count):
        v = (k + 0.5) / count * total
        for a, b, c, n0 in seg:
            if v <= n0 + c * (1.0 / a - 1.0 / b) or b == D[-1]:
                out.append(1.0 / (1.0 / a - (v - n0) / c))
                break
    random.Random(seed).shuffle(out)
    return out


def grading_of(d):
    """d10, d50, d60 by area of the diameters D."""
    d = np.sort(np.asarray(d))
    cum = np.cumsum(d * d) / np.sum(d * d)
    return [float(np.interp(q, cum, d)) for q in (0.1, 0.5, 0.6)]


def place_loose(radii, width, y_base, fraction, rng, attempts=5000):
    """Random non-overlapping positions for RADII in [0, width] x [y_base, ...] at about the area FRACTION:
    (x, y, top of the region). The region grows by 10 % until every disc fits."""
    area = sum(math.pi * r * r for r in radii)
    height = area / (fraction * width)
    for _ in range(40):
        xs, ys, rs = np.empty(len(radii)), np.empty(len(radii)), np.asarray(radii)
        ok = True
        for k, r in enumerate(radii):
            for _ in range(attempts):
                x = rng.uniform(r, width - r)
                y = rng.uniform(y_base + r, y_base + height - r)
                if k == 0 or np.all((xs[:k] - x) ** 2 + (ys[:k] - y) ** 2 >= (rs[:k] + r) ** 2):
                    xs[k], ys[k] = x, y
                    break
            else:
                ok = False
                break
        if ok:
            return xs, ys, y_base + height
        height *= 1.1
    raise CheckFailed(f"could not place {len(radii)} discs loose above y = {y_base:g} m")


def band_areas(x, y, r, edges):
    """Area of the discs between consecutive heights EDGES (exact circle segments)."""
    def below(t):  # area of each disc below the line at height t
        u = np.clip(t - y, -r, r)
        return r * r * np.arcsin(u / r) + u * np.sqrt(r * r - u * u) + 0.5 * math.pi * r * r
    return np.array([np.sum(below(b) - below(a)) for a, b in zip(edges[:-1], edges[1:])])


def run(cmd, log):
    rc, _ = study.run_command(cmd, log, ROOT)
    if rc:
        tail = open(log).read().strip().splitlines()[-1:] or [""]
        raise CheckFailed(f"rondel exited with code {rc} ({log}): {tail[0]}")


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__)
    ap.add_argument("--out", default="rondel-output-biaxial/ucm")
    ap.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"),
                    help="the rondel executable (default: build/rondel of this checkout)")
    ap.add_argument("--layer-ini", default=os.path.join(ROOT, "inputs", "biaxial_ucm_layer.ini"))
    ap.add_argument("--consolidate-ini", default=os.path.join(ROOT, "inputs", "biaxial_ucm_consolidate.ini"))
    ap.add_argument("--count", type=int, default=1008, help="discs")
    ap.add_argument("--width", type=float, default=0.18, help="[m] box width")
    ap.add_argument("--layers", type=int, default=6, help="layers n, 2 to 20")
    ap.add_argument("--e", type=float, default=0.25, help="target planar void ratio of the specimen")
    ap.add_argument("--u1", type=float, default=0.1, help="undercompaction U_1 of the bottom layer (0.1 = 10 %%)")
    ap.add_argument("--un", type=float, default=0.0, help="undercompaction U_n of the top layer")
    ap.add_argument("--pressure", type=float, default=2e5, help="[Pa] confining stress of the consolidation")
    ap.add_argument("--dmin", type=float, default=0.006, help="[m] smallest diameter")
    ap.add_argument("--dmax", type=float, default=0.009, help="[m] largest diameter")
    ap.add_argument("--loose", type=float, default=0.45, help="area fraction of a layer as generated")
    ap.add_argument("--wall-speed", type=float, default=0.25, help="[m/s] initial speed of the compacting wall")
    ap.add_argument("--dt", type=float, default=3.3e-6, help="[s] time step of the stages (run.dt)")
    ap.add_argument("--consolidate-steps", type=int, default=60000)
    ap.add_argument("--damping", type=float, default=0.0, help="run.local_damping of every stage")
    ap.add_argument("--mu", type=float, default=0.25, help="coulomb.mu (disc-disc friction) of the layer stages")
    ap.add_argument("--consolidate-mu", type=float, default=0.5, help="coulomb.mu of the consolidation")
    ap.add_argument("--seed", type=int, default=2005)
    ap.add_argument("--extra", action="append", default=[], help="more --section.key=value for every run")
    a = ap.parse_args(argv)
    if not os.access(a.rondel, os.X_OK):
        ap.error(f"the rondel executable '{a.rondel}' does not exist or is not executable "
                 "(build it: make -C build rondel, or pass --rondel)")
    for ini in (a.layer_ini, a.consolidate_ini):
        if not os.path.isfile(ini):
            ap.error(f"'{ini}': no such input file")
    finite = all(math.isfinite(v) for v in (a.width, a.e, a.u1, a.un, a.pressure, a.dmin, a.dmax, a.loose,
                                            a.wall_speed, a.dt, a.damping, a.mu,
                                            a.consolidate_mu))
    if not finite:
        ap.error("every number must be finite")
    if not 2 <= a.layers <= 20:
        ap.error(f"--layers must be 2 to 20, got {a.layers}")
    if a.count < 2 * a.layers:
        ap.error(f"--count must be at least 2 discs per layer, got {a.count} for {a.layers} layers")
    if not 0.05 <= a.e <= 1.0:
        ap.error(f"--e must be in [0.05, 1] (the J05 specimens: 0.22 to 0.28), got {a.e:g}")
    if not (0.0 <= a.un <= a.u1 < 1.0):
        ap.error(f"--u1 and --un must satisfy 0 <= un <= u1 < 1, got u1 {a.u1:g}, un {a.un:g}")
    if not 0.0 < a.dmin <= a.dmax:
        ap.error(f"--dmin and --dmax must satisfy 0 < dmin <= dmax, got {a.dmin:g}, {a.dmax:g}")
    if a.width < 2 * a.dmax:
        ap.error(f"--width must hold two of the largest discs side by side (>= {2 * a.dmax:g} m), got {a.width:g}")
    if not 0.05 <= a.loose <= 0.5:
        ap.error(f"--loose must be in [0.05, 0.5], got {a.loose:g}")
    for name, v in (("--pressure", a.pressure), ("--wall-speed", a.wall_speed), ("--dt", a.dt)):
        if v <= 0:
            ap.error(f"{name} must be > 0, got {v:g}")
    if not 0.0 <= a.damping < 1.0:
        ap.error(f"--damping must be in [0, 1), got {a.damping:g}")
    if a.mu < 0 or a.consolidate_mu < 0:
        ap.error(f"--mu and --consolidate-mu must be >= 0, got {a.mu:g}, {a.consolidate_mu:g}")
    if a.consolidate_steps < 1:
        ap.error(f"--consolidate-steps must be >= 1, got {a.consolidate_steps}")
    return run_tool(TOOL, build, a)


def undercompaction(a, i):
    """U_i of layer i (1 = bottom): linear from U_1 to U_n."""
    return a.u1 - (a.u1 - a.un) * (i - 1) / (a.layers - 1)


def build(a):
    os.makedirs(a.out, exist_ok=True)
    d = diameters(a.count, a.dmin, a.dmax, a.seed)
    radii = [0.5 * x for x in d]
    d10, d50, d60 = grading_of(d)
    n = a.layers
    sizes = [a.count // n + (1 if k < a.count % n else 0) for k in range(n)]
    rng = random.Random(a.seed + 1)
    W = a.width
    common = ["--run.overwrite=true", "--run.progress=false", f"--run.dt={a.dt!r}", f"--domain.xhi={W + 0.05!r}",
              f"--run.local_damping={a.damping!r}"]
    print(f"{a.count} discs in {n} layers, width {W:g} m; diameters {min(d) * 1e3:.2f} to {max(d) * 1e3:.2f} mm, "
          f"d50 {d50 * 1e3:.2f} mm, d60/d10 {d60 / d10:.3f} (by area); target e {a.e:g}, U_1 {a.u1:g}, U_n {a.un:g}",
          flush=True)

    old = np.zeros((0, 4))  # gid, x, y, radius of the discs already in the box
    start, area_below, rows, prev = 0, 0.0, [], None
    for i in range(1, n + 1):
        r_new = radii[start:start + sizes[i - 1]]
        y_base = float(np.max(old[:, 2] + old[:, 3])) + 1e-4 if len(old) else 0.0
        xs, ys, top = place_loose(r_new, W, y_base, a.loose, rng)
        gid0 = start
        new = np.column_stack([np.arange(gid0, gid0 + len(r_new)), xs, ys, r_new])
        discs = np.vstack([old, new])
        scene = os.path.join(a.out, f"layer_{i}.csv")
        with open(scene, "w") as f:
            f.write("id,x,y,radius,vx,vy,omega\n")
            for g, x, y, r in discs:
                f.write(f"{int(g)},{x!r},{y!r},{r!r},0,0,0\n")
        area_below += float(np.sum(np.pi * np.asarray(r_new) ** 2))
        U = undercompaction(a, i)
        e_i = a.e * (1.0 + U)
        h_i = area_below * (1.0 + e_i) / W
        if h_i >= top:
            raise CheckFailed(f"layer {i}: its target height {h_i:g} m is above the loose layer's top {top:g} m "
                              "(raise --loose or lower --e)")
        rate = a.wall_speed / top
        steps = int(math.ceil(math.log(h_i / top) / math.log(1.0 - rate * a.dt)))
        out = os.path.join(a.out, f"layer_{i}")
        cmd = [a.rondel, a.layer_ini, "--scene.type=csv", f"--scene.file={scene}", f"--run.output={out}",
               f"--run.steps={steps}",
               f"--walls.box_region=0 {W!r} 0 {top!r}", f"--domain.yhi={top + 0.05!r}",
               f"--walls.control=top:strain_rate:{rate!r}", f"--coulomb.mu={a.mu!r}"] + common + a.extra
        run(cmd, out + ".log")
        m = open_run(out).measures()
        h = float(m["height"][-1])
        fin = open_run(out).final()
        old = np.column_stack([fin["gid"], fin["x"], fin["y"], fin["radius"]])
        e_reached = (W * h - area_below) / area_below
        rows.append((i, len(r_new), U, e_i, h_i, h, e_reached, steps, float(m["wall_syy"][-1])))
        print(f"layer {i}: {len(r_new)} discs from {top * 1e3:.1f} mm; U {U:.3f}: target e {e_i:.4f} at "
              f"h {h_i * 1e3:.2f} mm; reached h {h * 1e3:.2f} mm, e {e_reached:.4f}, wall stress "
              f"{m['wall_syy'][-1] / 1e3:.1f} kPa ({steps} steps)", flush=True)
        start += len(r_new)
        prev = out

    # Isotropic consolidation: the last layer's state (scene.type = file), top and right walls servo.
    out = os.path.join(a.out, "consolidated")
    p = a.pressure
    cmd = [a.rondel, a.consolidate_ini, f"--scene.file={prev}", f"--run.output={out}",
           f"--run.steps={a.consolidate_steps}", f"--walls.control=top:servo:{p:g} right:servo:{p:g}",
           f"--domain.yhi={rows[-1][5] + 0.05!r}", f"--coulomb.mu={a.consolidate_mu!r}"] + common + a.extra
    run(cmd, out + ".log")
    m = open_run(out).measures()
    fin = open_run(out).final()
    e_final, H = float(m["void_ratio"][-1]), float(m["height"][-1])
    width = float(m["width"][-1])
    x, y, r = fin["x"], fin["y"], fin["radius"]
    edges = np.linspace(0.0, H, n + 1)  # the bottom wall stays at y = 0
    a_band = band_areas(x, y, r, edges)
    e_band = (width * np.diff(edges) - a_band) / a_band
    print(f"consolidated to {p / 1e3:g} kPa: wall_sxx {m['wall_sxx'][-1] / 1e3:.1f} kPa, wall_syy "
          f"{m['wall_syy'][-1] / 1e3:.1f} kPa; {width * 1e3:.2f} x {H * 1e3:.2f} mm; planar void ratio "
          f"{e_final:.4f} (target {a.e:g})", flush=True)
    print("void ratio by height band (bottom first): " + ", ".join(f"{v:.3f}" for v in e_band), flush=True)

    with open(os.path.join(a.out, "layers.csv"), "w") as f:
        f.write("layer,discs,U,e_target,h_target,h_reached,e_reached,steps,wall_syy\n")
        for row in rows:
            f.write(",".join(repr(v) if isinstance(v, float) else str(v) for v in row) + "\n")
    with open(os.path.join(a.out, "profile.csv"), "w") as f:
        f.write("y_low,y_high,void_ratio\n")
        for lo, hi, e in zip(edges[:-1], edges[1:], e_band):
            f.write(f"{lo!r},{hi!r},{e!r}\n")
    with open(os.path.join(a.out, "summary.txt"), "w") as f:
        f.write(f"discs {a.count}\nlayers {n}\nwidth {width!r}\nheight {H!r}\nvoid_ratio {e_final!r}\n"
                f"target {a.e!r}\npressure {p!r}\nd50 {d50!r}\nd60_over_d10 {d60 / d10!r}\n"
                f"void_ratio_min_band {float(e_band.min())!r}\nvoid_ratio_max_band {float(e_band.max())!r}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
