#!/usr/bin/python3
"""Prints what a Rondel checkpoint or snapshot holds (FORMAT.md).

    tools/h5info.py FILE.h5 [--config]        (or /usr/bin/python3 tools/h5info.py ...)

Kind, step, time, dt, laws, history slots, disc count, contact counts (rows, rows with history, loaded
contacts), every dataset with its type and shape, the walls, the ledger and the run metadata, and it
verifies every dataset's checksum; --config also prints the stored configuration. Exits 1 with a message
naming the file when it is not a readable Rondel file (missing, not HDF5, no format = rondel attribute,
truncated, a dataset failing its checksum), 0 otherwise; an incomplete file or another format version is
reported and exits 2.

Needs h5py and numpy (Debian: python3-h5py python3-numpy; tools/setup.sh installs them).
"""
import argparse
import os
import sys

try:
    import h5py
    import numpy as np
except ImportError as e:  # pragma: no cover - depends on the machine
    sys.exit(f"h5info: the Python module {e.name} is missing for {sys.executable}: run the tool with Debian's "
             "/usr/bin/python3 after apt-get install python3-h5py python3-numpy")

FORMAT_VERSION = 1


def text(value):
    """An HDF5 attribute as Python text or number."""
    if isinstance(value, bytes):
        return value.decode("ascii", "replace")
    if isinstance(value, np.generic):
        return value.item()
    return value


def fail(path, why, code=1):
    print(f"h5info: '{path}': {why}", file=sys.stderr)
    sys.exit(code)


M64 = (1 << 64) - 1


def checksum(data):
    """The dataset checksum of FORMAT.md: sum over rows r of mix(FNV-1a(row bytes) + G (r + 1)) mod 2^64."""
    n = data.shape[0]
    if n == 0:
        return 0
    rows = np.ascontiguousarray(data).view(np.uint8).reshape(n, -1)
    with np.errstate(over="ignore"):
        h = np.full(n, 0xcbf29ce484222325, dtype=np.uint64)
        for b in range(rows.shape[1]):
            h = (h ^ rows[:, b].astype(np.uint64)) * np.uint64(0x100000001b3)
        z = h + np.uint64(0x9e3779b97f4a7c15) * np.arange(1, n + 1, dtype=np.uint64)
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xbf58476d1ce4e5b9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94d049bb133111eb)
        z = z ^ (z >> np.uint64(31))
    return int(z.sum(dtype=np.uint64)) & M64


def verify_checksums(f):
    """(datasets checked, [names failing or without a checksum])."""
    checked, bad = 0, []

    def visit(name, obj):
        nonlocal checked
        if not isinstance(obj, h5py.Dataset):
            return
        checked += 1
        if "checksum" not in obj.attrs:
            bad.append(f"/{name} (no checksum)")
        elif int(obj.attrs["checksum"]) != checksum(obj[()]):
            bad.append(f"/{name}")
    f.visititems(visit)
    return checked, bad


def describe(name, obj):
    shape = "x".join(str(n) for n in obj.shape) if obj.shape else "scalar"
    return f"    {name:<28} {str(obj.dtype):<8} ({shape})"


def count_rows(group, slots):
    """Rows, rows with a non-zero history slot, rows with F_n > 0."""
    if group is None or "key" not in group:
        return None
    rows = group["key"].shape[0]
    with_history = np.zeros(rows, dtype=bool)
    for s in slots:
        if "history" in group and s in group["history"]:
            with_history |= group["history"][s][()] != 0.0
    loaded = int(np.count_nonzero(group["F_n"][()] > 0.0)) if "F_n" in group else 0
    return rows, int(np.count_nonzero(with_history)), loaded


def main():
    ap = argparse.ArgumentParser(description="What a Rondel checkpoint or snapshot holds (FORMAT.md).")
    ap.add_argument("file")
    ap.add_argument("--config", action="store_true", help="also print the stored configuration")
    args = ap.parse_args()
    path = args.file

    if not os.path.exists(path):
        fail(path, "no such file")
    if os.path.isdir(path):
        fail(path, "is a directory (name a checkpoint_<step>.h5 or snapshot_<step>.h5 in it)")
    if not h5py.is_hdf5(path):
        fail(path, "not an HDF5 file (a Rondel checkpoint or snapshot is one)")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        fail(path, f"cannot be opened as HDF5, truncated or corrupt ({e})")

    with f:
        a = {k: text(v) for k, v in f.attrs.items()}
        if a.get("format") != "rondel":
            fail(path, "is an HDF5 file but not a Rondel checkpoint or snapshot (no format = rondel attribute)")
        version = a.get("format_version")
        print(f"{path}: Rondel {a.get('kind', '?')}, format version {version}")
        status = 0
        if version != FORMAT_VERSION:
            print(f"  WARNING: format version {version}; this tool knows version {FORMAT_VERSION}")
            status = 2
        if a.get("complete") != 1:
            print("  WARNING: incomplete (no complete = 1 attribute): the writer was interrupted; Rondel refuses it")
            status = 2
        slots = [s for s in str(a.get("history_slots", "")).split(",") if s]
        print(f"  step {a.get('step')}, time {a.get('time')!r} s, dt {a.get('dt')!r} s")
        print(f"  laws: normal {a.get('normal_law')}, tangential {a.get('tangential_law')}, "
              f"rolling {a.get('rolling_law')}; history slots: {', '.join(slots) if slots else 'none'}")

        try:
            discs = f["discs"]
            n = discs["gid"].shape[0] if "gid" in discs else next(iter(discs.values())).shape[0]
            print(f"  discs: {n}")
            if "radius" in discs and n > 0:
                r = discs["radius"][()]
                print(f"    radius {r.min():.6g} .. {r.max():.6g} m")
            for name in discs:
                print(describe(name, discs[name]))
            for group_name in ("contacts", "wall_contacts"):
                counts = count_rows(f.get(group_name), slots)
                if counts is None:
                    print(f"  {group_name}: none stored" + (" (snapshot)" if a.get("kind") == "snapshot" else ""))
                    continue
                rows, hist, loaded = counts
                print(f"  {group_name}: {rows} rows, {hist} with non-zero history, {loaded} loaded (F_n > 0)")
                g = f[group_name]

                def visit(name, obj, g=g):
                    if isinstance(obj, h5py.Dataset):
                        print(describe(name, obj))
                g.visititems(visit)
            if "walls" in f:
                w = f["walls"]
                nw = w["kind"].shape[0] if "kind" in w else 0
                wa = {k: text(v) for k, v in w.attrs.items()}
                extra = ", ".join(f"{k} {v!r}" for k, v in wa.items())
                print(f"  walls: {nw}" + (f" ({extra})" if extra else ""))
                for i in range(nw):
                    kind = "line" if int(w["kind"][i]) == 0 else "segment"
                    p0, p1, nrm, v = (w[k][i] for k in ("p0", "p1", "normal", "velocity"))
                    where = (f"through ({p0[0]:.6g}, {p0[1]:.6g}), normal ({nrm[0]:.3g}, {nrm[1]:.3g})" if kind == "line"
                             else f"({p0[0]:.6g}, {p0[1]:.6g}) - ({p1[0]:.6g}, {p1[1]:.6g})")
                    load = ""
                    if "normal_force" in w:
                        load = f", normal force {float(w['normal_force'][i]):.6g} N on {int(w['contacts'][i])} contacts"
                    print(f"    {i}: {kind} {where}, velocity ({v[0]:.6g}, {v[1]:.6g}) m/s{load}")
            if "ledger" in f:
                led = {k: text(v) for k, v in f["ledger"].attrs.items()}
                print("  ledger [J]: " + ", ".join(f"{k} {v!r}" for k, v in led.items()))
            if "run_metadata" in f:
                meta = {k: text(v) for k, v in f["run_metadata"].attrs.items()}
                print("  run metadata: " + ", ".join(f"{k} {v}" for k, v in meta.items()))
            checked, bad = verify_checksums(f)
        except (KeyError, OSError, ValueError, StopIteration) as e:
            fail(path, f"damaged Rondel file, cannot read its contents ({e})")
        if bad:
            fail(path, f"corrupted: {len(bad)} of {checked} datasets fail their checksum: {', '.join(bad)}")
        print(f"  checksums: {checked} datasets verified")
        if args.config:
            print("  configuration:")
            for line in str(a.get("config", "")).splitlines():
                print("    " + line)
        return status


if __name__ == "__main__":
    sys.exit(main())
