#!/usr/bin/python3
"""Pictures of one Rondel state file (checkpoint or snapshot, FORMAT.md) as PNG (+ CSV).

    python3 tools/picture.py FILE_OR_RUN_DIR --kind rotation|forces|ranks --out PREFIX
                             [--field theta|omega] [--format png|pdf|svg] [--dpi 120]
                             [--title TEXT] [--width 8]
                             [--line-width W] [--vmax V] [--palette]

Kinds (every kind draws the walls of /walls as black lines: kind 0 lines across the view, kind 1
segments from p0 to p1, kind 2 circles of /walls/radius about p0; periodic box edges are drawn dashed). The view is the discs' extent with a
margin (the domain along periodic axes): --view walls widens it to every wall segment, --view X0 X1 Y0 Y1
sets it.
  rotation  discs as circles to scale, coloured by the accumulated rotation /discs/theta [rad]
            (--field omega: the angular velocity [rad/s]) on a diverging colour map centred at 0
            (limits +-V, V = --vmax or the 99th percentile of |value|); fixed discs (/discs/flags
            bit 0) grey. Writes PREFIX.png (.pdf, .svg: --format).
  forces    the contact-force network of a checkpoint: for each /contacts row with F_n > 0 a line
            between the two disc centres, width proportional to F_n / mean F_n, over faint discs.
            Periodic boundaries: the branch vector is the minimum image, the segment is drawn from
            disc 1 to disc 1 + branch and, when it wraps, mirrored from disc 2, so no line crosses
            the box. Loaded wall contacts (/wall_contacts) are drawn from the disc centre to the
            nearest point of the wall. The width factor (--line-width, points per mean F_n) defaults
            to one that makes the 99th percentile of F_n 0.8 mean disc diameters wide. Writes
            PREFIX.png, PREFIX.csv (gid1,gid2,F_n of the drawn disc-disc contacts, file order) and,
            when there are loaded wall contacts, PREFIX_walls.csv (gid,wall,F_n).
  ranks     discs coloured by the owner rank /discs/rank (snapshots written with 'rank' in
            output.snapshot_fields), categorical colours, legend with rank and disc count.
            Writes PREFIX.png and PREFIX.csv (rank,count).
  bonds     the intact parallel bonds of a checkpoint (/bonds) as lines between the disc centres, coloured by
            their normal force (tools/picture_bonds.py). Writes PREFIX.png and PREFIX.csv (gid1,gid2,Fb_n,...).

FILE may be a run directory: its newest snapshot_*.h5 is used (forces, bonds: its newest checkpoint_*.h5;
rotation and ranks fall back to the newest checkpoint when there is no snapshot).
The figure is --width inches wide (height from the view's aspect), so the PNG is width*dpi pixels wide;
--palette writes an 8-bit palette PNG (about 3x smaller, for documentation; needs Pillow).
Vectorised: discs are one EllipseCollection (units='xy'), contacts one LineCollection, so 100k discs
take a few seconds. Exit status 1 with a one-line message naming the file on any error (missing file, not a
Rondel file, dataset missing); files are read with tools/rondel (docs/python.md).

Needs Debian's /usr/bin/python3 with python3-h5py, python3-numpy, python3-matplotlib (--palette:
python3-pil). Test: tests/tools/test_picture_tool.py (ctest tools.picture).
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import Config, RondelError, open_any  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501
from picture_bonds import picture_bonds  # noqa: E402

try:
    import numpy as np
    plt = pyplot()
    from matplotlib.collections import EllipseCollection, LineCollection
    from matplotlib.colors import ListedColormap, Normalize
    from matplotlib.patches import Circle, Patch
except ImportError as e:  # pragma: no cover - depends on the machine
    print(f"picture: error: the Python module {e.name} is missing for {sys.executable}: run the tool with "
          "Debian's /usr/bin/python3 after apt-get install python3-h5py python3-numpy python3-matplotlib",
          file=sys.stderr)
    sys.exit(1)

KINDS = ("rotation", "forces", "ranks", "bonds")
TOOL = "picture"


class PictureError(RondelError):
    """An error to report to the user as 'picture: error: MESSAGE' with exit status 1."""


# ----------------------------------------------------------------------------------------- reading


def resolve(path, kind):
    """The state file to draw: PATH itself, or the newest suitable file of the run directory PATH."""
    return open_any(path, ("checkpoint",) if kind in ("forces", "bonds") else ("snapshot", "checkpoint"))


def parse_domain(config_text):
    """[domain] of a configuration text: xlo, xhi, ylo, yhi (float or None), periodic_x, periodic_y (bool)."""
    return Config(config_text, "<config>").domain()


class State:
    """The datasets of one Rondel file that the pictures use (numpy arrays, None when absent)."""

    def __init__(self, f):
        self.file = f
        self.path, self.kind, self.step, self.time = f.path, f.kind, f.step, f.time
        self.domain = f.config.domain()
        d, c, wc, w = f.discs, f.contacts or {}, f.wall_contacts or {}, f.walls
        self.position = np.asarray(f.disc("position"), dtype=float).reshape(-1, 2)
        self.radius = np.asarray(f.disc("radius"), dtype=float)
        self.gid, self.theta, self.omega = d.get("gid"), d.get("theta"), d.get("omega")
        self.rank, self.flags = d.get("rank"), d.get("flags")
        self.contact_key, self.contact_Fn = c.get("key"), c.get("F_n")
        self.wall_key, self.wall_Fn = wc.get("key"), wc.get("F_n")
        self.wall_kind, self.wall_p0, self.wall_p1 = w.get("kind"), w.get("p0"), w.get("p1")
        self.wall_normal = w.get("normal")
        self.wall_radius = w.get("radius")

    def missing(self, dataset, field=None, extra=""):
        """Raise the error for a missing dataset, naming the key that writes it."""
        hint = ""
        if field and self.kind == "snapshot":
            hint = (f"; snapshots hold it when '{field}' is listed in output.snapshot_fields "
                    f"(e.g. --output.snapshot_fields='position radius {field}')")
        elif field == "rank":
            hint = ("; the owner rank is only in snapshots: run with output.snapshot_every > 0 and "
                    "'rank' in output.snapshot_fields")
        raise PictureError(f"'{self.path}' ({self.kind}) has no dataset {dataset}{hint}{extra}")

    def fixed(self):
        """Boolean mask of fixed discs (flags bit 0); all False without /discs/flags."""
        return self.file.fixed()

    def rows_of(self, gids):
        """Row of each gid in /discs (rows are in ascending gid)."""
        if self.gid is None:
            self.missing("/discs/gid", "gid", " (needed to place contacts)")
        return self.file.rows_of(gids)


# ------------------------------------------------------------------------------------------ geometry

def minimum_image(d, domain):
    """Branch vectors D (n, 2) reduced to the minimum image along the periodic axes of DOMAIN."""
    d = np.array(d, dtype=float, copy=True).reshape(-1, 2)
    for i, axis in enumerate(("x", "y")):
        if domain.get(f"periodic_{axis}"):
            length = domain[f"{axis}hi"] - domain[f"{axis}lo"]
            d[:, i] -= length * np.round(d[:, i] / length)
    return d


def contact_segments(p1, p2, domain):
    """Line segments of contacts between centres P1 (n, 2) and P2 (n, 2).

    The branch vector b = minimum image of p2 - p1; each contact gives the segment p1 -> p1 + b and, when
    b differs from p2 - p1 (the contact wraps a periodic boundary), also its mirror p2 - b -> p2.
    Returns (segments (m, 2, 2), contact index (m,) of each segment)."""
    p1 = np.asarray(p1, dtype=float).reshape(-1, 2)
    p2 = np.asarray(p2, dtype=float).reshape(-1, 2)
    raw = p2 - p1
    b = minimum_image(raw, domain)
    seg = np.stack([p1, p1 + b], axis=1)
    idx = np.arange(len(p1))
    wraps = np.any(np.abs(b - raw) > 0.0, axis=1)
    if wraps.any():
        mirror = np.stack([p2[wraps] - b[wraps], p2[wraps]], axis=1)
        seg = np.concatenate([seg, mirror])
        idx = np.concatenate([idx, idx[wraps]])
    return seg, idx


def wall_points(p, wall, kind, p0, p1, normal, radius=None):
    """Nearest point of wall WALL[k] to disc centre P[k]: the foot on a line (kind 0), the closest point
    of a segment (kind 1) or the point of a circle (kind 2, centre p0, RADIUS) on the ray through P[k]."""
    p = np.asarray(p, dtype=float).reshape(-1, 2)
    wall = np.asarray(wall, dtype=int)
    a, b, n = p0[wall], p1[wall], normal[wall]
    foot_line = p - n * np.sum((p - a) * n, axis=1)[:, None]
    ab = b - a
    L2 = np.sum(ab * ab, axis=1)
    t = np.clip(np.sum((p - a) * ab, axis=1) / np.where(L2 > 0, L2, 1.0), 0.0, 1.0)
    foot_seg = a + ab * t[:, None]
    k = np.asarray(kind)[wall]
    out = np.where((k == 1)[:, None], foot_seg, foot_line)
    if radius is not None and (k == 2).any():
        d = p - a
        dist = np.sqrt(np.sum(d * d, axis=1))
        rim = a + d * (np.asarray(radius)[wall] / np.where(dist > 0, dist, 1.0))[:, None]
        out = np.where((k == 2)[:, None], rim, out)
    return out


def view_limits(state, view="discs"):
    """(xmin, xmax, ymin, ymax) of the picture. VIEW 'discs': the discs' extent with a margin (a pile under
    a tall chute is drawn, not the empty chute); 'walls': also every wall segment; or (x0, x1, y0, y1) as
    given. Along periodic axes the domain, unless VIEW gives the numbers."""
    if not isinstance(view, str):
        return tuple(float(v) for v in view)
    p, r = state.position, state.radius
    if len(r):
        lo = np.min(p - r[:, None], axis=0)
        hi = np.max(p + r[:, None], axis=0)
    else:
        lo, hi = np.zeros(2), np.ones(2)
    if view == "walls" and state.wall_kind is not None and len(state.wall_kind):
        seg = np.asarray(state.wall_kind) == 1
        if seg.any():
            pts = np.concatenate([state.wall_p0[seg], state.wall_p1[seg]])
            lo, hi = np.minimum(lo, pts.min(axis=0)), np.maximum(hi, pts.max(axis=0))
        if state.wall_radius is not None:
            for w in np.flatnonzero(np.asarray(state.wall_kind) == 2):
                c, rc = np.asarray(state.wall_p0[w]), float(state.wall_radius[w])
                lo, hi = np.minimum(lo, c - rc), np.maximum(hi, c + rc)
    dom = state.domain
    for i, axis in enumerate(("x", "y")):
        if dom.get(f"periodic_{axis}"):
            lo[i], hi[i] = dom[f"{axis}lo"], dom[f"{axis}hi"]
    span = np.maximum(hi - lo, 1e-12)
    margin = 0.03 * span.max()
    return lo[0] - margin, hi[0] + margin, lo[1] - margin, hi[1] + margin


# ------------------------------------------------------------------------------------------ drawing

def new_figure(limits, width_in, extra_right=0.0, side_axes=False, extra_bottom=0.0):
    """A figure WIDTH_IN inches wide, equal-aspect axes set to LIMITS; EXTRA_RIGHT inches for a colour bar
    or legend (SIDE_AXES: returns also an empty axes of that width for a legend), EXTRA_BOTTOM inches for a
    horizontal colour bar."""
    x0, x1, y0, y1 = limits
    aspect = (y1 - y0) / (x1 - x0)
    plot_w = width_in - extra_right - 0.9
    height_in = float(np.clip(plot_w * aspect + 0.9, 2.5 - extra_bottom, 2.5 * width_in)) + extra_bottom
    fig = plt.figure(figsize=(width_in, height_in), layout="constrained")
    if side_axes:
        ax, side = fig.subplots(1, 2, gridspec_kw=dict(width_ratios=[width_in - extra_right, extra_right]))
        side.set_axis_off()
    else:
        ax, side = fig.add_subplot(), None
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    return (fig, ax, side) if side_axes else (fig, ax)


def draw_discs(ax, pos, radius, **kw):
    """All discs as one EllipseCollection in data units (to scale)."""
    d = 2.0 * np.asarray(radius, dtype=float)
    coll = EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=np.asarray(pos).reshape(-1, 2),
                             offset_transform=ax.transData, **kw)
    ax.add_collection(coll)
    return coll


def draw_walls(ax, state):
    """Walls as black lines (lines across the view, segments p0-p1) and periodic box edges dashed."""
    if state.wall_kind is not None and len(state.wall_kind):
        kind = np.asarray(state.wall_kind)
        for w in np.flatnonzero(kind == 0):
            p0, n = state.wall_p0[w], state.wall_normal[w]
            ax.axline(tuple(p0), tuple(p0 + np.array([-n[1], n[0]])), color="black", lw=1.5, zorder=5)
        seg = kind == 1
        if seg.any():
            ax.add_collection(LineCollection(np.stack([state.wall_p0[seg], state.wall_p1[seg]], axis=1),
                                             colors="black", linewidths=1.5, zorder=5))
        if state.wall_radius is not None:
            for w in np.flatnonzero(kind == 2):
                ax.add_patch(Circle(tuple(state.wall_p0[w]), float(state.wall_radius[w]), fill=False,
                                    color="black", lw=1.5, zorder=5))
    dom = state.domain
    style = dict(color="0.3", lw=0.8, ls="--", zorder=5)
    if dom.get("periodic_x"):
        ax.axvline(dom["xlo"], **style)
        ax.axvline(dom["xhi"], **style)
    if dom.get("periodic_y"):
        ax.axhline(dom["ylo"], **style)
        ax.axhline(dom["yhi"], **style)


def title_of(state, args, what):
    """What is shown, of which scene and laws, when: 'rotation theta: pile (linear/coulomb/none), step ...'."""
    if args.title:
        return args.title
    return f"{what}: {state.file.title()}"


def save(fig, prefix, args):
    """Write PREFIX.<format>; with --palette (PNG only) as an 8-bit palette PNG (about 3x smaller, needs Pillow).

    The figure uses constrained layout, which keeps labels and the colour bar inside it, so it is written
    at its full size (--width x --dpi pixels wide) rather than cropped."""
    out = save_figure(fig, prefix, args, tight=False)
    if args.palette and args.format == "png":
        try:
            from PIL import Image, features
        except ImportError:
            raise PictureError("--palette needs Pillow (Debian: python3-pil)")
        with Image.open(out) as im:
            rgb = im.convert("RGB")
        # libimagequant keeps colour-map gradients smooth; Pillow without it: fast octree.
        Q = getattr(Image, "Quantize", Image)
        method = Q.LIBIMAGEQUANT if features.check_feature("libimagequant") else Q.FASTOCTREE
        rgb.quantize(256, method=method).save(out, optimize=True)
    return out


def picture_rotation(state, args):
    field = args.field
    values = getattr(state, field)
    if values is None:
        state.missing(f"/discs/{field}", field)
    values = np.asarray(values, dtype=float)
    fixed = state.fixed()
    free = ~fixed
    if args.vmax is not None:
        vmax = float(args.vmax)
    else:
        vmax = float(np.percentile(np.abs(values[free]), 99)) if free.any() else 0.0
    if not np.isfinite(vmax) or vmax <= 0:
        vmax = float(np.max(np.abs(values[free]))) if free.any() else 0.0
    if not np.isfinite(vmax) or vmax <= 0:
        vmax = 1.0
    limits = view_limits(state, args.view)
    # A wide view (a layer, a pile) gets its colour bar below, where its label has the figure's width; a
    # vertical bar as tall as a flat view would cut the label off.
    wide = (limits[3] - limits[2]) < 0.75 * (limits[1] - limits[0])
    fig, ax = new_figure(limits, args.width, extra_right=0.0 if wide else 1.2, extra_bottom=1.0 if wide else 0.0)
    norm = Normalize(vmin=-vmax, vmax=vmax)
    coll = draw_discs(ax, state.position[free], state.radius[free], cmap="RdBu_r", norm=norm,
                      edgecolors="none")
    coll.set_array(values[free])
    if fixed.any():
        draw_discs(ax, state.position[fixed], state.radius[fixed], facecolors="0.55", edgecolors="none")
    draw_walls(ax, state)
    unit = "rad" if field == "theta" else "rad/s"
    label = "accumulated rotation theta [rad] (counter-clockwise +)" if field == "theta" \
        else "angular velocity omega [rad/s] (counter-clockwise +)"
    if wide:
        cb = fig.colorbar(coll, ax=ax, extend="both", shrink=0.7, location="bottom", aspect=40)
    else:
        cb = fig.colorbar(coll, ax=ax, extend="both", shrink=0.9)
        label = label.replace(" (counter-clockwise +)", "\n(counter-clockwise +)").replace(
            "accumulated rotation ", "rotation ")
    cb.set_label(label)
    what = "accumulated rotation theta" if field == "theta" else "angular velocity omega"
    ax.set_title(title_of(state, args, what), fontsize=10)
    note = f"colour limits +-{vmax:.3g} {unit}"
    if fixed.any():
        note += f"; {int(fixed.sum())} fixed discs grey"
    ax.text(0.01, 0.99, note, transform=ax.transAxes, va="top", ha="left", fontsize=8,
            bbox=dict(facecolor="white", alpha=0.7, edgecolor="none"))
    return [save(fig, args.out, args)]


def picture_forces(state, args):
    if state.contact_key is None or state.contact_Fn is None:
        raise PictureError(f"'{state.path}' ({state.kind}) has no /contacts/key and /contacts/F_n: the force "
                           "network needs a checkpoint (checkpoint_*.h5; output.checkpoint_at_end = true "
                           "writes one after the last step)")
    key = np.asarray(state.contact_key).reshape(-1, 2)
    Fn = np.asarray(state.contact_Fn, dtype=float)
    loaded = Fn > 0
    key, Fn = key[loaded], Fn[loaded]
    wkey = wFn = None
    if state.wall_key is not None and state.wall_Fn is not None and state.wall_kind is not None:
        wkey = np.asarray(state.wall_key).reshape(-1, 2)
        wFn = np.asarray(state.wall_Fn, dtype=float)
        wl = wFn > 0
        wkey, wFn = wkey[wl], wFn[wl]
    all_F = Fn if wFn is None else np.concatenate([Fn, wFn])
    mean_F = float(all_F.mean()) if len(all_F) else 1.0

    limits = view_limits(state, args.view)
    fig, ax = new_figure(limits, args.width, extra_right=0.0)
    draw_discs(ax, state.position, state.radius, facecolors="0.85", edgecolors="0.7", linewidths=0.2,
               zorder=1)
    # Width scale: proportional to F_n / mean F_n, the factor chosen so that the 99th percentile of F_n
    # gets a line 0.8 mean disc diameters wide (in points), unless --line-width gives the factor.
    fig.canvas.draw()
    bbox = ax.get_window_extent()
    pts_per_m = bbox.width / fig.dpi * 72.0 / (limits[1] - limits[0])
    if args.line_width is not None:
        base = args.line_width
    else:
        diam_pt = 2.0 * (state.radius.mean() if len(state.radius) else 0.0) * pts_per_m
        f99 = float(np.percentile(all_F, 99)) / mean_F if len(all_F) else 1.0
        base = float(np.clip(0.8 * diam_pt / max(f99, 1e-12), 0.05, 4.0))
    if len(Fn):
        rows = state.rows_of(key.ravel()).reshape(-1, 2)
        seg, idx = contact_segments(state.position[rows[:, 0]], state.position[rows[:, 1]], state.domain)
        ax.add_collection(LineCollection(seg, linewidths=base * Fn[idx] / mean_F, colors="firebrick",
                                         capstyle="round", zorder=3))
    if wFn is not None and len(wFn):
        wrow = state.rows_of(wkey[:, 0])
        p = state.position[wrow]
        q = wall_points(p, wkey[:, 1], state.wall_kind, state.wall_p0, state.wall_p1, state.wall_normal,
                        state.wall_radius)
        ax.add_collection(LineCollection(np.stack([p, q], axis=1), linewidths=base * wFn / mean_F,
                                         colors="navy", capstyle="round", zorder=3))
    draw_walls(ax, state)
    ax.set_title(title_of(state, args, "normal contact forces F_n"), fontsize=10)
    n_w = 0 if wFn is None else len(wFn)
    ax.text(0.01, 0.99, f"{len(Fn)} loaded disc contacts (red), {n_w} wall contacts (blue); "
            f"width = {base:.2g} pt x F_n / mean F_n, mean F_n = {mean_F:.3g} N",
            transform=ax.transAxes, va="top", ha="left", fontsize=8,
            bbox=dict(facecolor="white", alpha=0.7, edgecolor="none"))
    out = [save(fig, args.out, args), write_keyed_forces(args.out + ".csv", ["gid1", "gid2", "F_n"], key, Fn)]
    if wFn is not None and len(wFn):
        out.append(write_keyed_forces(args.out + "_walls.csv", ["gid", "wall", "F_n"], wkey, wFn))
    return out


def write_keyed_forces(path, header, key, Fn):
    """Rows (key[0], key[1], F_n) with F_n exact (repr); returns the path."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for (a, b), F in zip(key.tolist(), Fn.tolist()):
            w.writerow([a, b, repr(F)])
    return path


def rank_counts(rank):
    """(ranks, counts) of the owner ranks present, ascending rank."""
    r, c = np.unique(np.asarray(rank, dtype=np.int64), return_counts=True)
    return r, c


def picture_ranks(state, args):
    if state.rank is None:
        state.missing("/discs/rank", "rank")
    rank = np.asarray(state.rank, dtype=np.int64)
    ranks, counts = rank_counts(rank)
    base = plt.get_cmap("tab10" if len(ranks) <= 10 else "tab20")
    colours = [base(i % base.N) for i in range(len(ranks))]
    fig, ax, side = new_figure(view_limits(state, args.view), args.width, extra_right=1.7, side_axes=True)
    cat = np.searchsorted(ranks, rank)
    coll = draw_discs(ax, state.position, state.radius, cmap=ListedColormap(colours),
                      norm=Normalize(vmin=-0.5, vmax=len(ranks) - 0.5), edgecolors="none")
    coll.set_array(cat.astype(float))
    draw_walls(ax, state)
    handles = [Patch(facecolor=colours[i], label=f"rank {int(r)}: {int(c)} discs")
               for i, (r, c) in enumerate(zip(ranks, counts))]
    side.legend(handles=handles, loc="upper left", fontsize=8,
              title=f"{len(ranks)} ranks", title_fontsize=8, frameon=False)
    ax.set_title(title_of(state, args, "owner rank of each disc"), fontsize=10)
    out = [save(fig, args.out, args)]
    with open(args.out + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["rank", "count"])
        for r, c in zip(ranks.tolist(), counts.tolist()):
            w.writerow([r, c])
    out.append(args.out + ".csv")
    return out


# --------------------------------------------------------------------------------------------- main

def draw(args):
    state = State(resolve(args.file, args.kind))
    kinds = {"rotation": picture_rotation, "forces": picture_forces, "ranks": picture_ranks, "bonds": picture_bonds}
    written = kinds[args.kind](state, args)
    print(f"picture: {state.path} ({state.kind}, step {state.step}, {len(state.radius)} discs) -> "
          + ", ".join(written))


def main(argv=None):
    ap = ArgumentParser(TOOL, description="Pictures of a Rondel checkpoint or snapshot (figure + CSV).",
                        epilog="See the module docstring (head of tools/picture.py) for details.")
    ap.add_argument("file", help="a snapshot_*.h5 / checkpoint_*.h5, or a run directory (newest file)")
    ap.add_argument("--kind", required=True, choices=KINDS)
    ap.add_argument("--out", required=True, help="output prefix: writes PREFIX.<format> (and PREFIX.csv)")
    ap.add_argument("--field", default="theta", choices=("theta", "omega"),
                    help="rotation: colour by theta (accumulated rotation, default) or omega")
    add_figure_options(ap, dpi=120, no_plot=False)
    ap.add_argument("--width", type=float, default=8.0, help="figure width in inches (default 8)")
    ap.add_argument("--title", default=None, help="figure title (default: quantity, scene, laws, step, time)")
    ap.add_argument("--vmax", type=float, default=None,
                    help="rotation, bonds: colour limits +-VMAX (default: 99th percentile of |value|)")
    ap.add_argument("--line-width", type=float, default=None,
                    help="forces: line width [pt] of a contact with the mean F_n (default: from disc size)")
    ap.add_argument("--view", nargs="+", default=["discs"], metavar="discs|walls|X0 X1 Y0 Y1",
                    help="the region drawn: the discs' extent with a margin (default), also every wall segment "
                         "(walls), or the given bounds [m]")
    ap.add_argument("--palette", action="store_true",
                    help="PNG: write an 8-bit palette PNG (about 3x smaller; needs Pillow)")
    args = ap.parse_args(argv)
    check_figure_options(ap, args)
    if args.view in (["discs"], ["walls"]):
        args.view = args.view[0]
    else:
        try:
            args.view = [float(v) for v in args.view]
        except ValueError:
            args.view = None
        if args.view is None or len(args.view) != 4 or not (args.view[0] < args.view[1] and args.view[2] < args.view[3]):
            ap.error("--view takes discs, walls, or four numbers X0 X1 Y0 Y1 with X0 < X1 and Y0 < Y1")
    if args.width <= 0:
        ap.error("--width must be > 0")
    return run_tool(TOOL, draw, args)


if __name__ == "__main__":
    sys.exit(main())
