#!/usr/bin/python3
"""Prints what a Rondel checkpoint or snapshot holds (FORMAT.md).

    tools/h5info.py FILE.h5 [--config]        (or /usr/bin/python3 tools/h5info.py ...)

Kind, step, time, dt, laws, history slots, disc count, contact counts (rows, rows with history, loaded
contacts), every dataset with its type and shape, the walls, the ledger and the run metadata, and it
verifies every dataset's checksum; --config also prints the stored configuration. Exits 1 with a message
naming the file when it is not a readable Rondel file (missing, not HDF5, no format = rondel attribute,
truncated, a dataset failing its checksum), 0 otherwise; an incomplete file or another format version is
reported and exits 2. Reads the file with the reader in tools/rondel (docs/python.md).

Needs h5py and numpy (Debian: python3-h5py python3-numpy; tools/setup.sh installs them).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import (EXIT_FAILED, FORMAT_VERSION, READABLE_VERSIONS, RondelFileError, checksum, decode,  # noqa: E402,F401
                    open_file)
from rondel.cli import ArgumentParser, run_tool  # noqa: E402

text = decode  # the name older scripts import from here

TOOL = "h5info"


def describe(name, arr):
    shape = "x".join(str(n) for n in arr.shape) if arr.shape else "scalar"
    return f"    {name:<28} {str(arr.dtype):<8} ({shape})"


def count_rows(group, slots):
    """Rows, rows with a non-zero history slot, rows with F_n > 0."""
    import numpy as np
    if group is None or "key" not in group:
        return None
    rows = group["key"].shape[0]
    with_history = np.zeros(rows, dtype=bool)
    for s in slots:
        if s in group.get("history", {}):
            with_history |= group["history"][s] != 0.0
    loaded = int(np.count_nonzero(group["F_n"] > 0.0)) if "F_n" in group else 0
    return rows, int(np.count_nonzero(with_history)), loaded


def print_group(group):
    for name, v in group.items():
        if isinstance(v, dict):
            for slot, d in v.items():
                print(describe(f"{name}/{slot}", d))
        else:
            print(describe(name, v))


def print_walls(f):
    w = f.walls
    kinds = f.wall_kinds()
    nw = len(kinds)
    extra = ", ".join(f"{k} {v!r}" for k, v in w.attrs.items())
    print(f"  walls: {nw}" + (f" ({extra})" if extra else ""))
    for i in range(nw):
        kind = kinds[i]
        p0, p1, nrm, v = (w[k][i] for k in ("p0", "p1", "normal", "velocity"))
        if kind == "line":
            where = f"through ({p0[0]:.6g}, {p0[1]:.6g}), normal ({nrm[0]:.3g}, {nrm[1]:.3g})"
        elif kind == "circle":
            where = f"centre ({p0[0]:.6g}, {p0[1]:.6g}), radius {float(w['radius'][i]):.6g} m"
        else:
            where = f"({p0[0]:.6g}, {p0[1]:.6g}) - ({p1[0]:.6g}, {p1[1]:.6g})"
        if "omega" in w and float(w["omega"][i]) != 0.0:
            c = w["centre"][i]
            where += (f", rotating at {float(w['omega'][i]):.6g} rad/s about ({c[0]:.6g}, {c[1]:.6g}), "
                      f"turned {float(w['angle'][i]):.6g} rad")
        load = ""
        if "normal_force" in w:
            load = f", normal force {float(w['normal_force'][i]):.6g} N on {int(w['contacts'][i])} contacts"
        print(f"    {i}: {kind} {where}, velocity ({v[0]:.6g}, {v[1]:.6g}) m/s{load}")


def report(args):
    f = open_file(args.file, allow_incomplete=True, allow_version=True)
    print(f"{f.path}: Rondel {f.kind}, format version {f.format_version}")
    status = 0
    if f.format_version not in READABLE_VERSIONS:
        print(f"  WARNING: format version {f.format_version}; this tool knows versions "
              f"{READABLE_VERSIONS[0]} to {READABLE_VERSIONS[-1]}")
        status = EXIT_FAILED
    if not f.complete:
        print("  WARNING: incomplete (no complete = 1 attribute): the writer was interrupted; Rondel refuses it")
        status = EXIT_FAILED
    print(f"  step {f.step}, time {f.time!r} s, dt {f.dt!r} s")
    print(f"  laws: normal {f.laws['normal']}, tangential {f.laws['tangential']}, rolling {f.laws['rolling']}; "
          f"history slots: {', '.join(f.history_slots) if f.history_slots else 'none'}")
    n = len(f)
    print(f"  discs: {n}")
    if "radius" in f.discs and n > 0:
        r = f.discs["radius"]
        print(f"    radius {r.min():.6g} .. {r.max():.6g} m")
    print_group(f.discs)
    for name in ("contacts", "wall_contacts"):
        g = getattr(f, name)
        counts = count_rows(g, f.history_slots)
        if counts is None:
            print(f"  {name}: none stored" + (" (snapshot)" if f.kind == "snapshot" else ""))
            continue
        rows, hist, loaded = counts
        print(f"  {name}: {rows} rows, {hist} with non-zero history, {loaded} loaded (F_n > 0)")
        print_group(g)
    if "kind" in f.walls:
        print_walls(f)
    if f.ledger:
        print("  ledger [J]: " + ", ".join(f"{k} {v!r}" for k, v in f.ledger.items()))
    if f.run_metadata:
        print("  run metadata: " + ", ".join(f"{k} {v}" for k, v in f.run_metadata.items()))
    checked, bad = f.verify_checksums()
    if bad:
        raise RondelFileError(f.path, f"corrupted: {len(bad)} of {checked} datasets fail their checksum: "
                              + ", ".join(bad))
    print(f"  checksums: {checked} datasets verified" +
          (", and the attributes" if f.attributes_checksum is not None else ""))
    if args.config:
        print("  configuration:")
        for line in f.config.text.splitlines():
            print("    " + line)
    return status


def main(argv=None):
    ap = ArgumentParser(TOOL, description="What a Rondel checkpoint or snapshot holds (FORMAT.md).")
    ap.add_argument("file")
    ap.add_argument("--config", action="store_true", help="also print the stored configuration")
    return run_tool(TOOL, report, ap.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
