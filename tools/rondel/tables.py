"""CSV files of a run (diagnostics.csv, measures.csv, final.csv, ...) as named numpy columns."""
import csv

import numpy as np

from .errors import RondelFileError


class Table(dict):
    """Columns of a CSV file: `t["time"]` is a numpy array; `t.columns` keeps the file's order; len(t) rows.

    Integer columns are int64, the others float64 (empty cells NaN). C hexadecimal floats (final.csv:
    '0x1.4p-8') are read exactly with float.fromhex; decimal numbers as usual."""

    def __init__(self, path, columns, data):
        super().__init__(data)
        self.path = str(path)
        self.columns = list(columns)
        self.rows = len(next(iter(data.values()))) if data else 0

    def __len__(self):  # rows, not columns: a table of 3 rows has len 3
        return self.rows

    def row(self, k):
        """Row K as a dict {column: value}."""
        return {c: self[c][k].item() for c in self.columns}


def parse_number(text):
    """A number of a Rondel CSV cell: C hexadecimal float, decimal, nan/inf; '' is NaN."""
    s = text.strip()
    if not s:
        return float("nan")
    if "x" in s or "X" in s:
        return float.fromhex(s)
    return float(s)


# Columns that hold counts or ids; every other column is float64 even when its cells look like integers
# (a diagnostics column of zeros stays float).
INTEGER_COLUMNS = {"gid", "id", "step", "contacts", "wall_contacts", "migrated", "material", "rank", "flags"}


def _column(path, name, cells):
    try:
        if name in INTEGER_COLUMNS and all(c.strip().lstrip("-").isdigit() for c in cells):
            return np.array([int(c) for c in cells], dtype=np.int64)
        return np.array([parse_number(c) for c in cells], dtype=float)
    except ValueError as e:
        raise RondelFileError(path, f"column '{name}' holds a value that is not a number ({e})") from None


def read_csv(path):
    """A Rondel CSV (header line, one row per line) as a Table; RondelFileError when it cannot be read."""
    try:
        with open(path, newline="") as f:
            rows = [r for r in csv.reader(f) if r]
    except OSError as e:
        raise RondelFileError(path, f"cannot be read ({e.strerror})") from None
    if not rows:
        raise RondelFileError(path, "empty file (no header line)")
    head = [h.strip() for h in rows[0]]
    if len(set(head)) != len(head):
        raise RondelFileError(path, "the header repeats a column name")
    for i, r in enumerate(rows[1:], start=2):
        if len(r) != len(head):
            raise RondelFileError(path, f"line {i} has {len(r)} fields, the header {len(head)}")
    data = {h: _column(path, h, [r[i] for r in rows[1:]]) for i, h in enumerate(head)}
    return Table(path, head, data)


def require(table, names, hint=""):
    """Raise RondelFileError naming TABLE's file when a column of NAMES is missing."""
    missing = [n for n in names if n not in table]
    if missing:
        raise RondelFileError(table.path, "lacks the column(s) " + ", ".join(missing) + (f" ({hint})" if hint else ""))
