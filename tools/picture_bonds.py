"""The kind 'bonds' of tools/picture.py: the intact parallel bonds of a checkpoint (/bonds, docs/bonds.md).

Each bond is a line between its two disc centres (the minimum image across periodic boundaries, drawn as the
force network is), coloured by its normal force Fb_n [N] on a diverging map centred at 0 (tension red, compression
blue; limits +-V, V = --vmax or the 99th percentile of |Fb_n|), over the discs in light grey, so that cracks show
as the gaps in the network. Writes PREFIX.png and PREFIX.csv (gid1,gid2,Fb_n,Fb_s,Mb of every intact bond, file
order, exact). A checkpoint of a run without bonds, or a snapshot, is refused naming what to run.
"""
import csv

import numpy as np


def picture_bonds(state, args):
    import picture as p  # the tool's helpers (this module is imported by it)
    from matplotlib.collections import LineCollection
    from matplotlib.colors import Normalize

    bonds = state.file.bonds
    if bonds is None or "key" not in bonds:
        raise p.PictureError(f"'{state.path}' ({state.kind}) has no /bonds: the bonds are in the checkpoints of a "
                             "run with [bonds] (checkpoint_*.h5; output.checkpoint_at_end = true writes one after "
                             "the last step)")
    key = np.asarray(bonds["key"]).reshape(-1, 2)
    history = bonds.get("history", {})
    Fn, Fs, Mb = (np.asarray(history.get(name, np.zeros(len(key))), dtype=float) for name in ("Fb_n", "Fb_s", "Mb"))
    vmax = args.vmax if args.vmax is not None else (float(np.percentile(np.abs(Fn), 99)) if len(Fn) else 1.0)
    vmax = vmax if vmax > 0 else 1.0
    limits = p.view_limits(state, args.view)
    wide = (limits[3] - limits[2]) < 0.75 * (limits[1] - limits[0])  # the colour bar below, as picture's rotation
    fig, ax = p.new_figure(limits, args.width, extra_right=0.0 if wide else 1.2, extra_bottom=1.0 if wide else 0.0)
    p.draw_discs(ax, state.position, state.radius, facecolors="0.88", edgecolors="0.75", linewidths=0.2, zorder=1)
    norm = Normalize(vmin=-vmax, vmax=vmax)
    lines = None
    if len(key):
        rows = state.rows_of(key.ravel()).reshape(-1, 2)
        seg, idx = p.contact_segments(state.position[rows[:, 0]], state.position[rows[:, 1]], state.domain)
        lines = LineCollection(seg, cmap="coolwarm", norm=norm, linewidths=1.2, capstyle="round", zorder=3)
        lines.set_array(Fn[idx])
        ax.add_collection(lines)
    p.draw_walls(ax, state)
    if lines is not None:
        label = "bond normal force Fb_n [N] (tension > 0)"
        if wide:
            fig.colorbar(lines, ax=ax, extend="both", shrink=0.7, location="bottom", aspect=40, label=label)
        else:
            fig.colorbar(lines, ax=ax, extend="both", shrink=0.9, label=label.replace(" (", "\n("))
    ax.set_title(p.title_of(state, args, "parallel bonds"), fontsize=10)
    ax.text(0.01, 0.99, f"{len(key)} intact bonds", transform=ax.transAxes, va="top", ha="left", fontsize=8,
            bbox=dict(facecolor="white", alpha=0.7, edgecolor="none"))
    out = [p.save(fig, args.out, args), args.out + ".csv"]
    with open(out[1], "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["gid1", "gid2", "Fb_n", "Fb_s", "Mb"])
        for (a, b), n, s, m in zip(key.tolist(), Fn.tolist(), Fs.tolist(), Mb.tolist()):
            w.writerow([a, b, repr(n), repr(s), repr(m)])
    return out
