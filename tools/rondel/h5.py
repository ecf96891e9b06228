"""Checkpoints and snapshots (HDF5, layout in FORMAT.md) as numpy arrays and decoded attributes."""
import os
import re

import numpy as np

from .config import Config
from .errors import RondelFileError

FORMAT_VERSION = 5
# Versions this reader takes: 2 only dropped contact datasets of 1 that the tools do not read; 3 added
# circle walls (/walls/kind 2) and wall rotation (/walls/centre, radius, omega, angle); 4 the root's
# /integrity attributes_checksum; 5 the periodic cell now (/cell: xlo, xhi, ylo, yhi, tilt, rates, flips).
READABLE_VERSIONS = (1, 2, 3, 4, 5)
# The names of the wall kind codes (/walls/kind) of files written before the attribute /walls/kind_names, which
# newer files carry (the C++ registry, src/core/WallKinds.hpp): StateFile.wall_kinds() reads that attribute.
WALL_KINDS_BEFORE_NAMES = ("line", "segment", "circle")
FLAG_FIXED = 1
FLAG_GLUED = 2
M64 = (1 << 64) - 1


def _h5py():
    try:
        import h5py
    except ImportError:
        raise RondelFileError("h5py", "the Python module h5py is missing: run the tools with Debian's "
                              "/usr/bin/python3 after apt-get install python3-h5py") from None
    return h5py


def decode(value):
    """An HDF5 attribute as Python text or number (fixed-length strings are bytes in h5py)."""
    if isinstance(value, bytes):
        return value.decode("ascii", "replace").rstrip("\0")
    if isinstance(value, np.generic):
        return value.item()
    return value


def checksum(data):
    """The dataset checksum of FORMAT.md: sum over rows r of mix(FNV-1a(row bytes) + G (r + 1)) mod 2^64."""
    n = data.shape[0] if data.ndim else 0
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


def _fnv_mix(data):
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & M64
    z = (h + 0x9e3779b97f4a7c15) & M64
    z = ((z ^ (z >> 30)) * 0xbf58476d1ce4e5b9) & M64
    z = ((z ^ (z >> 27)) * 0x94d049bb133111eb) & M64
    return z ^ (z >> 31)


def attributes_checksum(f):
    """The attributes_checksum of FORMAT.md over an open h5py File: the sum mod 2^64, over every attribute of
    every object but /integrity's attributes_checksum and the root's complete, of mix(FNV-1a(path NUL name NUL value as
    stored) + 0x9e3779b97f4a7c15)."""
    h5py = _h5py()
    objects = [("/", f)]
    f.visititems(lambda name, obj: objects.append(("/" + name, obj)))
    total = 0
    for path, obj in objects:
        for name in obj.attrs:
            if (path, name) in (("/", "complete"), ("/integrity", "attributes_checksum")):
                continue
            aid = h5py.h5a.open(obj.id, name.encode())
            raw = np.zeros((), dtype=f"V{aid.get_storage_size()}")
            aid.read(raw, mtype=aid.get_type())
            total = (total + _fnv_mix(path.encode() + b"\0" + name.encode() + b"\0" + raw.tobytes())) & M64
    return total


def step_of_name(path):
    """The step in a name like checkpoint_0000002000.h5 (-1 when there is none)."""
    m = re.search(r"_(\d+)\.h5$", os.path.basename(str(path)))
    return int(m.group(1)) if m else -1


class Group(dict):
    """Datasets of one HDF5 group as {name: numpy array}, with the group's attributes in .attrs."""

    def __init__(self, name, data=None, attrs=None):
        super().__init__(data or {})
        self.name = name
        self.attrs = dict(attrs or {})


class StateFile:
    """One Rondel checkpoint or snapshot, read whole into memory when opened.

    Attributes: path, kind ('checkpoint' or 'snapshot'), step, time, dt, format_version, complete (bool),
    laws {'normal', 'tangential', 'rolling'}, history_slots (list of names), attrs (every root attribute,
    decoded), config (Config of the `config` attribute), discs (Group: gid, radius, position (n, 2), ...),
    contacts and wall_contacts (Group with key, param, F_n, ..., history {slot: array}; None in a
    snapshot), bonds (the parallel bonds: in a checkpoint Group with key, param, history {Fb_n, Fb_s, Mb}, in a
    snapshot key, Fb_n, Fb_s, Mb, sigma, tau, points (2 per bond), index; None without bonds), breaks (the bonds'
    breaks since the last snapshot: key, position, step, mode (1 tension, 2 shear), sigma, tau; None without bonds),
    walls (Group: kind, p0, p1, normal, velocity, ...; attrs box_width0, box_height0),
    cell (dict: xlo, xhi, ylo, yhi, tilt, rate_xx, rate_xy, rate_yy, flips; {} before version 5; cell_vectors()),
    ledger (dict of float), run_metadata (dict), checksums {'/discs/gid': stored uint64}."""

    def __init__(self, path, allow_incomplete=False, allow_version=False):
        self.path = str(path)
        h5py = _h5py()
        if not os.path.exists(self.path):
            raise RondelFileError(self.path, "no such file")
        if os.path.isdir(self.path):
            raise RondelFileError(self.path, "is a directory (name a checkpoint_<step>.h5 or snapshot_<step>.h5 "
                                  "in it, or open it with rondel.open_run)")
        if not h5py.is_hdf5(self.path):
            raise RondelFileError(self.path, "not an HDF5 file (a Rondel checkpoint or snapshot is one)")
        try:
            with h5py.File(self.path, "r") as f:
                self._read(f, h5py, allow_incomplete, allow_version)
        except OSError as e:
            raise RondelFileError(self.path, f"cannot be read as HDF5, truncated or corrupt ({e})") from None
        except (KeyError, ValueError, TypeError) as e:
            raise RondelFileError(self.path, f"damaged Rondel file, cannot read its contents ({e})") from None

    def _read(self, f, h5py, allow_incomplete, allow_version):
        a = {k: decode(v) for k, v in f.attrs.items()}
        if a.get("format") != "rondel":
            raise RondelFileError(self.path, "is an HDF5 file but not a Rondel checkpoint or snapshot "
                                  "(no format = rondel attribute)")
        self.attrs = a
        self.format_version = a.get("format_version")
        if self.format_version not in READABLE_VERSIONS and not allow_version:
            raise RondelFileError(self.path, f"has format version {self.format_version}; this reader reads "
                                  f"versions {READABLE_VERSIONS[0]} to {READABLE_VERSIONS[-1]}")
        self.complete = a.get("complete") == 1
        # Version 4: the stored and the recomputed checksum of the attributes (None for older files).
        self.attributes_checksum = None
        if "integrity" in f and "attributes_checksum" in f["integrity"].attrs:
            stored = int(f["integrity"].attrs["attributes_checksum"]) & M64
            self.attributes_checksum = (stored, attributes_checksum(f))
        if not self.complete and not allow_incomplete:
            raise RondelFileError(self.path, "is incomplete (no complete = 1 attribute: the writer was cut short)")
        self.kind = a.get("kind", "?")
        self.step = int(a.get("step", -1))
        self.time = float(a.get("time", float("nan")))
        self.dt = float(a.get("dt", float("nan")))
        self.laws = {k: a.get(f"{k}_law", "") for k in ("normal", "tangential", "rolling")}
        self.history_slots = [s for s in str(a.get("history_slots", "")).split(",") if s]
        self.config = Config(a.get("config", ""), f"{self.path} (config attribute)")
        self.checksums = {}
        self.discs = self._group(f, h5py, "discs")
        if self.discs is None:
            raise RondelFileError(self.path, "has no /discs group")
        self.contacts = self._group(f, h5py, "contacts")
        self.wall_contacts = self._group(f, h5py, "wall_contacts")
        self.bonds = self._group(f, h5py, "bonds")
        self.breaks = self._group(f, h5py, "breaks")
        self.walls = self._group(f, h5py, "walls") or Group("walls")
        self.ledger = {k: float(decode(v)) for k, v in f["ledger"].attrs.items()} if "ledger" in f else {}
        self.cell = {k: decode(v) for k, v in f["cell"].attrs.items()} if "cell" in f else {}
        self.run_metadata = {k: decode(v) for k, v in f["run_metadata"].attrs.items()} if "run_metadata" in f else {}

    def _group(self, f, h5py, name):
        if name not in f:
            return None
        g = f[name]
        out = Group(name, attrs={k: decode(v) for k, v in g.attrs.items()})
        for key, obj in g.items():
            if isinstance(obj, h5py.Dataset):
                out[key] = obj[()]
                if "checksum" in obj.attrs:
                    self.checksums[f"/{name}/{key}"] = int(obj.attrs["checksum"])
            elif isinstance(obj, h5py.Group):  # /contacts/history/<slot>
                out[key] = {}
                for slot, ds in obj.items():
                    out[key][slot] = ds[()]
                    if "checksum" in ds.attrs:
                        self.checksums[f"/{name}/{key}/{slot}"] = int(ds.attrs["checksum"])
        return out

    # -------------------------------------------------------------------------------------------- access

    def cell_vectors(self):
        """The periodic cell now as (corner, a, b): numpy 2-vectors, a = (L_x, 0) and b = (tilt, L_y) (docs/physics.md
        section 10); from the configuration's box, tilt 0, for a file before version 5."""
        c = self.cell
        if not c:
            c = {k: float(self.config.get("domain", k)) for k in ("xlo", "xhi", "ylo", "yhi")}
            c["tilt"] = 0.0
        corner = np.array([float(c["xlo"]), float(c["ylo"])])
        a = np.array([float(c["xhi"]) - float(c["xlo"]), 0.0])
        b = np.array([float(c["tilt"]), float(c["yhi"]) - float(c["ylo"])])
        return corner, a, b

    def wall_kinds(self):
        """The name of each wall's kind ('line', 'segment', 'circle', ...), decoded with the file's own table
        (the attribute /walls/kind_names; older files: WALL_KINDS_BEFORE_NAMES). A code the table lacks is an
        error naming it."""
        w = self.walls
        if "kind" not in w:
            return []
        names = str(w.attrs["kind_names"]).split() if "kind_names" in w.attrs else list(WALL_KINDS_BEFORE_NAMES)
        out = []
        for i, code in enumerate(np.asarray(w["kind"]).reshape(-1)):
            if not 0 <= int(code) < len(names):
                raise RondelFileError(self.path, f"wall {i} has the kind {int(code)} (/walls/kind), which the file's "
                                      f"table {names} lacks")
            out.append(names[int(code)])
        return out

    def __len__(self):
        """The disc count."""
        first = self.discs.get("gid", next(iter(self.discs.values()), np.zeros(0)))
        return int(first.shape[0])

    def datasets(self):
        """{'/discs/radius': array, ...} of every dataset in the file."""
        out = {}
        for g in (self.discs, self.contacts, self.wall_contacts, self.bonds, self.breaks, self.walls):
            if g is None:
                continue
            for k, v in g.items():
                if isinstance(v, dict):
                    out.update({f"/{g.name}/{k}/{s}": d for s, d in v.items()})
                else:
                    out[f"/{g.name}/{k}"] = v
        return out

    def verify_checksums(self):
        """(datasets checked, [names failing or without a checksum]) following FORMAT.md."""
        bad = []
        data = self.datasets()
        for name, arr in data.items():
            if name not in self.checksums:
                bad.append(f"{name} (no checksum)")
            elif self.checksums[name] != checksum(np.asarray(arr)):
                bad.append(name)
        if self.format_version is not None and self.format_version >= 4:
            if self.attributes_checksum is None:
                bad.append("the attributes (no attributes_checksum)")
            elif self.attributes_checksum[0] != self.attributes_checksum[1]:
                bad.append("the attributes (attributes_checksum)")
        return len(data), bad

    def disc(self, name, hint=True):
        """The /discs dataset NAME; RondelFileError naming the key that writes it when it is absent."""
        if name in self.discs:
            return self.discs[name]
        why = f"({self.kind}) has no dataset /discs/{name}"
        if hint and self.kind == "snapshot":
            why += (f"; snapshots hold it when '{name}' is listed in output.snapshot_fields "
                    f"(e.g. --output.snapshot_fields='position radius {name}')")
        raise RondelFileError(self.path, why)

    def need_contacts(self):
        """The /contacts group; RondelFileError when the file has none (snapshots)."""
        if self.contacts is None or "key" not in self.contacts:
            raise RondelFileError(self.path, f"({self.kind}) has no /contacts: contacts are in checkpoints only "
                                  "(checkpoint_*.h5; output.checkpoint_at_end = true writes one after the last step)")
        return self.contacts

    def fixed(self):
        """Boolean mask of fixed discs (flags bit 0); all False without /discs/flags."""
        if "flags" not in self.discs:
            return np.zeros(len(self), dtype=bool)
        return (self.discs["flags"].astype(np.int64) & FLAG_FIXED) != 0

    def rows_of(self, gids):
        """Row of each gid in /discs (rows are in ascending gid)."""
        gid = self.disc("gid")
        gids = np.asarray(gids, dtype=gid.dtype)
        rows = np.clip(np.searchsorted(gid, gids), 0, max(len(gid) - 1, 0))
        bad = gid[rows] != gids if len(gid) else np.ones(gids.shape, dtype=bool)
        if bad.any():
            raise RondelFileError(self.path, f"gid {int(gids[bad][0])} is not in /discs/gid")
        return rows

    def title(self):
        """'scene (laws), step N, t = T s' for figure titles."""
        scene = self.config.scene_name() or os.path.basename(os.path.dirname(os.path.abspath(self.path)))
        laws = "/".join(self.laws[k] for k in ("normal", "tangential", "rolling") if self.laws[k])
        return f"{scene}" + (f" ({laws})" if laws else "") + f", step {self.step}, t = {self.time:.4g} s"

    def __repr__(self):
        return f"<rondel {self.kind} '{self.path}': step {self.step}, {len(self)} discs>"


def open_file(path, **kw):
    """Open one checkpoint or snapshot (StateFile). Refuses, with a RondelFileError naming the file, what is
    missing, not HDF5, not Rondel, incomplete or of another format version (allow_incomplete=True,
    allow_version=True accept the last two, e.g. to report on them)."""
    return StateFile(path, **kw)
