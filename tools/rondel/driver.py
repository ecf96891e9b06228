"""Driving a simulation from Python: rondel.Simulation (docs/python.md, "The driver").

    from mpi4py import MPI                  # under mpirun -n P python3 script.py
    import rondel
    sim = rondel.Simulation("inputs/deposition.ini", overrides={"run.steps": 2000})
    while sim.step_count < 2000:
        sim.step(100)
        d = sim.discs                       # this rank's discs, numpy views valid until the next step or write
        print(sim.step_count, d.velocity[:, 1].min())
    sim.finish()                            # summary, final.csv, the checkpoint at the end: the executable's files

The compiled half, rondel._driver (pybind11), drives the executable's own Simulation and Runner: the same
set-up, schedules of output, files and restart. Every call below is collective (every rank makes it, with the
same arguments) except the views and the read-only properties.
"""
import os
import signal as _signal
import sys

import numpy as np

from .errors import RondelError

# MPI as the executable has it: without MPI_THREAD_MULTIPLE, whose locks cost Open MPI's messages about 2 % of a
# 2-rank step (bench/python_overhead.py). Only when this import comes before mpi4py.MPI's; "serialized" still lets
# a script's threads make MPI calls one at a time.
if "mpi4py.MPI" not in sys.modules:
    try:
        import mpi4py
        mpi4py.rc.thread_level = "serialized"
    except ImportError:  # the reader does not need it; Simulation() says so
        pass

EXIT_STOPPED = 10  # core/ExitCodes.hpp: a run stopped by a signal after its checkpoint


class DriverMissing(RondelError):
    """The compiled driver is not built or not found: rondel reads files, but cannot run a simulation."""


class StaleViewError(RondelError):
    """A view of the discs used after step() or a write: its memory may have moved."""


class Stopped(SystemExit):
    """A stop signal (SIGTERM, SIGINT, SIGUSR1) ended the run at a step every rank agreed on, after a checkpoint;
    uncaught, it ends the script with the executable's exit code 10. `.checkpoint` is its path."""

    def __init__(self, signal_name, step, checkpoint):
        super().__init__(EXIT_STOPPED)
        self.signal_name, self.step, self.checkpoint = signal_name, step, checkpoint

    def __str__(self):
        return f"stopped by {self.signal_name} at step {self.step}; checkpoint {self.checkpoint}"


def _load_driver():
    try:
        from . import _driver
    except ImportError as e:
        raise DriverMissing(
            "rondel.Simulation needs the compiled driver rondel._driver, which was not found "
            f"({e}): build it with `bash tools/setup.sh` (Debian packages python3-pybind11, python3-dev, "
            "python3-mpi4py; it lands in build/python/rondel/, found from tools/rondel), or install Rondel and "
            "set PYTHONPATH=<prefix>/share/rondel/tools; RONDEL_DRIVER_DIR names another directory") from None
    return _driver


def _override_args(overrides):
    """A dict {"section.key": value} or a list of "--section.key=value" strings, as command-line arguments."""
    if overrides is None:
        return []
    if isinstance(overrides, dict):
        args = []
        for key, value in overrides.items():
            if not isinstance(key, str) or "." not in key:
                raise RondelError(f"override key {key!r}: 'section.key' expected (e.g. 'run.steps')")
            if isinstance(value, bool):
                value = "true" if value else "false"
            args.append(f"--{key}={value}")
        return args
    return [str(a) for a in overrides]


class DiscView(np.lib.mixins.NDArrayOperatorsMixin):
    """A read-only column of this rank's discs, valid until the next step or write; numpy takes it without a copy
    (np.asarray(view), arithmetic, ufuncs, indexing). Used later it raises StaleViewError; .copy() keeps the values.
    An array taken out of it (np.asarray, .array) is not checked: use it before the next step."""

    __slots__ = ("_array", "_sim", "_generation", "_name")

    def __init__(self, array, sim, generation, name):
        self._array, self._sim, self._generation, self._name = array, sim, generation, name

    def _checked(self):
        if self._sim._generation() != self._generation:
            raise StaleViewError(
                f"the view '{self._name}' was taken before a step or a write and its memory may have moved: "
                "take sim.discs again (or .copy() a view to keep its values)")
        return self._array

    @property
    def array(self):
        """The numpy array itself (no copy): valid until the next step or write, not checked after it."""
        return self._checked()

    def __array__(self, dtype=None, copy=None):
        a = self._checked()
        return a if dtype is None else a.astype(dtype)

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        inputs = tuple(x._checked() if isinstance(x, DiscView) else x for x in inputs)
        return getattr(ufunc, method)(*inputs, **kwargs)

    def __getitem__(self, index):
        return self._checked()[index]

    def __len__(self):
        return len(self._checked())

    def __iter__(self):
        return iter(self._checked())

    def copy(self):
        return self._checked().copy()

    @property
    def shape(self):
        return self._checked().shape

    @property
    def dtype(self):
        return self._checked().dtype

    def __repr__(self):
        return f"DiscView({self._name}, {self._checked()!r})"


class Discs:
    """This rank's discs at the present step: gid, position (n, 2), velocity (n, 2), omega, theta, radius, mass,
    material, force (n, 2), torque, flags; each a DiscView. `fixed` is a boolean copy of flags & 1."""

    COLUMNS = ("gid", "position", "velocity", "omega", "theta", "radius", "mass", "material", "force", "torque",
               "flags")

    def __init__(self, sim):
        self._views = {name: DiscView(a, sim, sim._generation(), name) for name, a in sim._d.columns().items()}

    def __getattr__(self, name):
        views = object.__getattribute__(self, "_views")
        if name in views:
            return views[name]
        raise AttributeError(f"the discs have no column '{name}' (columns: {', '.join(Discs.COLUMNS)}, fixed)")

    @property
    def fixed(self):
        return (np.asarray(self._views["flags"]) & 1).astype(bool)

    def __len__(self):
        return len(self._views["gid"])


def _table(header_and_row):
    header, row = header_and_row
    values = {}
    for name, text in zip(header.strip().split(","), row.strip().split(",")):
        try:
            values[name] = int(text)
        except ValueError:
            values[name] = float(text)
    return values


class Simulation:
    """A simulation built like `rondel FILE.ini --section.key=value ...` (or resumed like `--resume DIR`) and
    stepped from Python. Collective: every rank builds it with the same arguments.

    config     an INI file, or None with `text` (an INI text) or with overrides alone
    overrides  {"section.key": value} or ["--section.key=value", ...], as on the command line
    resume     a run directory (its newest valid checkpoint) or a checkpoint file's directory: continue from it
    comm       an mpi4py communicator (default MPI.COMM_WORLD); the simulation works on a duplicate of it
    files      False: no run directory (nothing written, run.output ignored)
    """

    def __init__(self, config=None, *, overrides=None, text=None, resume=None, comm=None, files=True):
        driver = _load_driver()
        from mpi4py import MPI  # initialises MPI (before the driver's first MPI call)
        comm = MPI.COMM_WORLD if comm is None else comm
        if config is not None and text is not None:
            raise RondelError("give an INI file or an INI text (text=), not both")
        args = [] if config is None else [os.fspath(config)]
        if resume is not None:
            args += ["--resume", os.fspath(resume)]
        args += _override_args(overrides)
        # The script's handlers of the stop signals, given back at finish() and close(): from the first step on the
        # run's own take them (a stop at an agreed step, after a checkpoint).
        self._handlers = {s: _signal.getsignal(s) for s in (_signal.SIGTERM, _signal.SIGINT, _signal.SIGUSR1)}
        self._d = driver.Driver(args, text, comm.py2f(), bool(files))
        self.rank, self.ranks = comm.Get_rank(), comm.Get_size()  # also after close()
        self._comm = comm

    def _generation(self):
        return self._d.generation

    # --- stepping -----------------------------------------------------------------------------------------------
    def step(self, n=1):
        """n steps (also past run.steps) with the run's diagnostics, snapshots and checkpoints on their schedules.
        A stop signal ends them at a step every rank agrees on, after a checkpoint: finish() runs, then Stopped."""
        signal = self._d.step(int(n))
        if signal != 0:
            summary = self.finish()
            raise Stopped(_signal.Signals(signal).name, self.step_count, summary["last_checkpoint"])

    def run(self):
        """The steps left to run.steps, then finish(): what the executable does. Returns the summary (a dict)."""
        left = self.run_steps - self.step_count
        if left > 0:
            self.step(left)
        return self.finish()

    def finish(self):
        """The end of the run: the checkpoint at the end (output.checkpoint_at_end), summary.txt, summary.json and
        final.csv, as the executable writes them. No steps after it. Returns the summary (a dict)."""
        try:
            return self._d.finish()
        finally:
            self._give_back_signals()

    def close(self):
        """Frees the simulation and its communicator (collective). finish() first if the files should be complete."""
        self._d.close()
        self._give_back_signals()

    def _give_back_signals(self):
        for s, handler in self._handlers.items():
            if handler is not None:  # None: a handler not installed from Python, which Python cannot put back
                _signal.signal(s, handler)

    def __enter__(self):
        return self

    def __exit__(self, kind, value, trace):
        if kind is None:
            self.finish()
        self.close()
        return False

    # --- state --------------------------------------------------------------------------------------------------
    time = property(lambda self: self._d.time, doc="simulated time [s]")
    step_count = property(lambda self: self._d.step_count, doc="steps since the start of the run")
    dt = property(lambda self: self._d.dt, doc="the time step [s]")
    critical_dt = property(lambda self: self._d.critical_dt, doc="the critical time step [s]")
    critical_mode = property(lambda self: self._d.critical_mode, doc="its limiting mode")
    output = property(lambda self: self._d.output, doc="the run directory")
    run_steps = property(lambda self: self._d.run_steps, doc="run.steps")

    @property
    def discs(self):
        """This rank's discs as views (Discs), valid until the next step or write."""
        return Discs(self)

    def gather(self, column, everywhere=False):
        """Collective: one column of every rank's discs, in ascending gid, as (gids, values) on rank 0 (None on the
        others) or, with everywhere=True, on every rank. A copy of the whole scene's column: for analysis and for
        decisions every rank must take alike, not for every step of a large run."""
        if column not in Discs.COLUMNS:
            raise RondelError(f"gather: no column '{column}' (columns: {', '.join(Discs.COLUMNS)})")
        d = self.discs
        mine = (np.asarray(d.gid).copy(), np.asarray(getattr(d, column)).copy())
        comm = self._comm
        parts = comm.allgather(mine) if everywhere else comm.gather(mine, root=0)
        if parts is None:
            return None
        gids = np.concatenate([p[0] for p in parts])
        values = np.concatenate([p[1] for p in parts])
        order = np.argsort(gids, kind="stable")
        return gids[order], values[order]

    # --- writes (collective: every rank passes the same gids and values) --------------------------------------
    def set_velocity(self, gids, velocity):
        """Velocities (n, 2) [m/s] of free discs by gid; the kinetic energy changed is booked as W_driver."""
        self._d.set_velocity(_gids(gids), np.asarray(velocity, dtype=float).reshape(-1, 2))

    def set_omega(self, gids, omega):
        """Spins [rad/s] of free discs by gid; booked as W_driver."""
        self._d.set_omega(_gids(gids), [float(w) for w in np.atleast_1d(omega)])

    def fix(self, gids):
        """Fixes discs (at rest, not integrated); their kinetic energy is booked as W_driver."""
        self._d.set_fixed(_gids(gids), True)

    def free(self, gids):
        """Frees fixed discs (from rest)."""
        self._d.set_fixed(_gids(gids), False)

    def set_body_force(self, gids, force):
        """Body forces (n, 2) [N] on free discs by gid beside gravity, from the next step on; a zero force removes
        one. Their work is booked as W_driver. Not in checkpoints: a resumed script sets them again."""
        self._d.set_body_force(_gids(gids), np.asarray(force, dtype=float).reshape(-1, 2))

    def cell(self):
        """The periodic cell: deforms, lo, length, tilt, rate (xx, yy, xy) [1/s], target_stress (xx, yy) [Pa, 0:
        rate-controlled]."""
        return self._d.cell()

    def set_cell_rates(self, xx=None, yy=None, xy=None):
        """A deforming cell's rates [1/s] from the next step (the components given; not the stress-controlled ones)."""
        nan = float("nan")
        self._d.set_cell_rates(*(nan if v is None else float(v) for v in (xx, yy, xy)))

    def set_cell_stress(self, xx=None, yy=None):
        """A stress-controlled cell's target stresses [Pa] from the next step (the components given)."""
        nan = float("nan")
        self._d.set_cell_stress(*(nan if v is None else float(v) for v in (xx, yy)))

    def walls(self):
        """Every wall (a list of dicts: control, velocity, target_stress, strain_rate, force, normal_force, contacts,
        p0, p1),
        with the loads of the present step. Collective."""
        return self._d.walls()

    def set_wall_velocity(self, wall, velocity):
        """A translating wall's velocity (vx, vy) [m/s] from the next step."""
        vx, vy = velocity
        self._d.set_wall_velocity(int(wall), float(vx), float(vy))

    def set_wall_stress(self, wall, stress):
        """A servo wall's target stress [Pa] from the next step."""
        self._d.set_wall_stress(int(wall), float(stress))

    def set_wall_strain_rate(self, wall, rate):
        """A strain-rate wall's rate [1/s] from the next step (> 0 compresses, < 0 unloads)."""
        self._d.set_wall_strain_rate(int(wall), float(rate))

    # --- measures (collective) ----------------------------------------------------------------------------------
    def ledger(self):
        """The run's energy ledger (every rank's share summed): {term: J per thickness}."""
        return self._d.ledger()

    def diagnostics(self):
        """The diagnostics.csv row of the present step, as a dict."""
        return _table(self._d.diagnostics())

    def measures(self):
        """The measures.csv row of the present step, as a dict."""
        return _table(self._d.measures())

    # --- output (collective) ------------------------------------------------------------------------------------
    def checkpoint(self):
        """A checkpoint of the present step in the run directory; returns its path."""
        return self._d.write_checkpoint()

    def snapshot(self):
        """A snapshot of the present step in the run directory."""
        self._d.write_snapshot()


def _gids(gids):
    a = np.atleast_1d(np.asarray(gids))
    if a.dtype.kind not in "iu":
        raise RondelError(f"gids: integers expected, got an array of {a.dtype}")
    return [int(g) for g in a]
