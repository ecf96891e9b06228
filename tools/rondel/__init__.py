"""Reading Rondel output from Python: run directories, checkpoints, snapshots, CSV files.

    import sys; sys.path.insert(0, "tools")     # or PYTHONPATH=tools
    import rondel
    run = rondel.open_run("rondel-output/pile")   # a run directory
    f = rondel.open_file("rondel-output/pile/checkpoint_0000020000.h5")
    f.discs["position"], f.contacts["F_n"], f.walls["p0"], f.ledger["W_g"], f.config.getfloat("run", "dt")

Errors are RondelFileError (naming the file) rather than h5py/KeyError tracebacks. Needs numpy and, for
the HDF5 files, h5py (Debian: python3-numpy python3-h5py, run by /usr/bin/python3). docs/python.md.

And driving a simulation: rondel.Simulation (driver.py), with the compiled rondel._driver (pybind11, built by
CMake into build/python/rondel/, or installed beside this file; RONDEL_DRIVER_DIR names another directory).
"""
import os as _os
import pkgutil as _pkgutil

# The compiled driver lives in another directory of the same package: another `rondel` directory on sys.path, the
# build tree of this checkout, or RONDEL_DRIVER_DIR.
__path__ = _pkgutil.extend_path(__path__, __name__)
for _extra in (_os.environ.get("RONDEL_DRIVER_DIR", ""),
               _os.path.join(_os.path.dirname(_os.path.dirname(_os.path.dirname(_os.path.abspath(__file__)))),
                             "build", "python", "rondel")):
    if _extra and _os.path.isdir(_extra) and _extra not in __path__:
        __path__.append(_extra)
from .config import Config
from .driver import Discs, DiscView, DriverMissing, Simulation, StaleViewError, Stopped
from .errors import EXIT_FAILED, EXIT_INPUT, EXIT_OK, CheckFailed, RondelError, RondelFileError, UsageError
from .h5 import (FLAG_FIXED, FLAG_GLUED, FORMAT_VERSION, READABLE_VERSIONS, StateFile, checksum, decode, open_file,
                 step_of_name)
from .run import Run, open_any, open_run
from .tables import Table, parse_number, read_csv, require

__all__ = ["Config", "EXIT_FAILED", "EXIT_INPUT", "EXIT_OK", "CheckFailed", "RondelError", "RondelFileError",
           "UsageError", "FLAG_FIXED", "FLAG_GLUED", "FORMAT_VERSION", "READABLE_VERSIONS", "StateFile", "checksum",
           "decode", "open_file", "step_of_name", "Run", "open_any", "open_run", "Table", "parse_number", "read_csv",
           "require", "Discs", "DiscView", "DriverMissing", "Simulation", "StaleViewError", "Stopped"]
