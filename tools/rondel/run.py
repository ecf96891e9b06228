"""A run directory: config.ini, log.txt, the CSVs, summary.txt / summary.json, checkpoints, snapshots."""
import glob
import json
import os
import re

from .config import Config
from .errors import RondelFileError
from .h5 import StateFile, step_of_name
from .tables import read_csv

SUMMARY_RE = re.compile(r"summary: (\d+) steps of (\d+) discs in ([0-9.eE+-]+) s wall, ([0-9.eE+-]+) disc-steps/s")
TIME_STEP_RE = re.compile(r"time step ([0-9.eE+-]+) s = .*?critical ([0-9.eE+-]+) s, limited by the (\S+) mode"
                          r"(?: \(([^)]*)\))?")


class Run:
    """The output directory of one rondel run. Files are read when asked for; a missing one raises
    RondelFileError naming it (and the key that writes it where there is one).

        run = rondel.open_run("rondel-output/pile")
        run.config.getfloat("run", "dt"); run.diagnostics()["ke_trans"]; run.final()["x"]
        for snap in run.snapshots(): ...          # StateFile objects in step order"""

    def __init__(self, path):
        self.path = str(path)
        if not os.path.exists(self.path):
            raise RondelFileError(self.path, "no such run directory")
        if not os.path.isdir(self.path):
            raise RondelFileError(self.path, "is not a directory (a run directory holds log.txt, "
                                  "diagnostics.csv, ...; open a single .h5 file with rondel.open_file)")
        markers = ("config.ini", "log.txt", "diagnostics.csv", "measures.csv", "summary.txt", "final.csv")
        if not any(os.path.exists(self.file(m)) for m in markers) and not self.checkpoint_paths() \
                and not self.snapshot_paths():
            raise RondelFileError(self.path, "is not a Rondel run directory (none of " + ", ".join(markers) +
                                  ", checkpoint_*.h5, snapshot_*.h5)")
        self._config = None

    def file(self, name):
        return os.path.join(self.path, name)

    def _need(self, name, hint=""):
        p = self.file(name)
        if not os.path.isfile(p):
            raise RondelFileError(p, "no such file" + (f" ({hint})" if hint else ""))
        return p

    # --------------------------------------------------------------------------------------- text files

    @property
    def config(self):
        """The resolved configuration: config.ini, else the `config` attribute of the newest checkpoint."""
        if self._config is None:
            if os.path.isfile(self.file("config.ini")):
                self._config = Config.from_file(self.file("config.ini"))
            else:
                files = self.checkpoint_paths() or self.snapshot_paths()
                if not files:
                    raise RondelFileError(self.file("config.ini"), "no such file, and no checkpoint or snapshot "
                                          "to take the configuration from")
                self._config = StateFile(files[-1]).config
        return self._config

    def log(self):
        """The text of log.txt."""
        with open(self._need("log.txt")) as f:
            return f.read()

    def diagnostics(self):
        """diagnostics.csv as a Table (diagnostics.every sets its rows)."""
        return read_csv(self._need("diagnostics.csv"))

    def measures(self):
        """measures.csv as a Table (stresses, strains, wall loads; measures.every)."""
        return read_csv(self._need("measures.csv"))

    def final(self):
        """final.csv as a Table (gid, x, y, vx, vy, theta, omega and radius when written), exact floats."""
        return read_csv(self._need("final.csv", "written after the last step"))

    def summary(self):
        """The run's summary as a dict: the keys of summary.json when the run wrote one (rondel_version,
        status, steps, discs, ranks, wall_seconds, dt, critical_dt, critical_mode, critical_pair, ...), else
        what summary.txt and the log say; either way with steps, discs, wall_seconds, disc_steps_per_s,
        complete (bool), dt, dt_critical, critical_mode, critical_pair where known, and source (the file)."""
        js = self.file("summary.json")
        if os.path.isfile(js):
            try:
                with open(js) as f:
                    out = json.load(f)
            except (OSError, ValueError) as e:
                raise RondelFileError(js, f"not readable JSON ({e})") from None
            if not isinstance(out, dict):
                raise RondelFileError(js, "is not a JSON object")
            aliases = {"disc_steps_per_second": "disc_steps_per_s", "critical_dt": "dt_critical"}
            for k, alias in aliases.items():
                if k in out:
                    out.setdefault(alias, out[k])
            if "status" in out:
                out.setdefault("complete", out["status"] == "complete")
            out.setdefault("source", js)
            return out
        out = self._summary_txt()
        if os.path.isfile(self.file("log.txt")):
            try:
                out.update(self._time_step_log())
            except RondelFileError:
                pass  # a log without the line (an older build): the summary stands without it
        return out

    def _summary_txt(self):
        with open(self._need("summary.txt", "written at the end of a run")) as f:
            text = f.read()
        m = SUMMARY_RE.search(text)
        if not m:
            raise RondelFileError(self.file("summary.txt"), "has no 'summary: N steps of N discs in T s wall' line")
        return {"steps": int(m.group(1)), "discs": int(m.group(2)), "wall_seconds": float(m.group(3)),
                "disc_steps_per_s": float(m.group(4)), "complete": "status: complete" in text, "text": text,
                "source": self.file("summary.txt")}

    def time_step(self):
        """{dt, dt_critical, critical_mode, critical_pair}: from summary.json when it has them, else log.txt."""
        if os.path.isfile(self.file("summary.json")):
            s = self.summary()
            if all(k in s for k in ("dt", "dt_critical", "critical_mode")):
                return {k: s.get(k, "") for k in ("dt", "dt_critical", "critical_mode", "critical_pair")}
        return self._time_step_log()

    def _time_step_log(self):
        m = TIME_STEP_RE.search(self.log())
        if not m:
            raise RondelFileError(self.file("log.txt"), "has no 'time step ... critical ... mode' line")
        return {"dt": float(m.group(1)), "dt_critical": float(m.group(2)), "critical_mode": m.group(3),
                "critical_pair": m.group(4) or ""}

    # --------------------------------------------------------------------------------------- HDF5 files

    def _paths(self, prefix):
        return sorted(glob.glob(os.path.join(glob.escape(self.path), f"{prefix}_*.h5")), key=step_of_name)

    def checkpoint_paths(self):
        """checkpoint_*.h5 paths in step order (hidden .part files are not matched)."""
        return self._paths("checkpoint")

    def snapshot_paths(self):
        """snapshot_*.h5 paths in step order."""
        return self._paths("snapshot")

    def checkpoints(self):
        """Iterate over the checkpoints (StateFile) in step order."""
        for p in self.checkpoint_paths():
            yield StateFile(p)

    def snapshots(self):
        """Iterate over the snapshots (StateFile) in step order, one file in memory at a time."""
        for p in self.snapshot_paths():
            yield StateFile(p)

    def checkpoint(self, step=None):
        """The checkpoint at STEP, or the newest one."""
        paths = self.checkpoint_paths()
        if step is not None:
            paths = [p for p in paths if step_of_name(p) == step]
        if not paths:
            raise RondelFileError(self.path, "holds no checkpoint_*.h5" + (f" of step {step}" if step is not None
                                  else " (output.checkpoint_every, output.checkpoint_at_end = true write them)"))
        return StateFile(paths[-1])

    def newest_state(self, prefer=("snapshot", "checkpoint")):
        """The newest file of the first kind in PREFER that the directory holds."""
        for kind in prefer:
            paths = self._paths(kind)
            if paths:
                return StateFile(paths[-1])
        raise RondelFileError(self.path, "holds no " + " or ".join(f"{k}_*.h5" for k in prefer))

    @property
    def xdmf(self):
        """The path of snapshots.xdmf (None when the run wrote no snapshots)."""
        p = self.file("snapshots.xdmf")
        return p if os.path.isfile(p) else None

    def __repr__(self):
        return f"<rondel run '{self.path}'>"


def open_run(path):
    """Open a run directory (Run)."""
    return Run(path)


def open_any(path, prefer=("snapshot", "checkpoint")):
    """A StateFile: PATH itself when it is a file, else the newest file of PREFER in the run directory PATH."""
    if os.path.isdir(str(path)):
        return Run(path).newest_state(prefer)
    return StateFile(path)
