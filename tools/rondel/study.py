"""What a sweep of rondel runs needs: run a command into a run directory, know whether a run finished, a pool of
jobs (single runs or chains whose runs start from the one before) that skips finished runs, so that running
the same command again resumes a sweep.

    from rondel import study
    chains = [[study.Job("prep_s1", [rondel, "prep.ini", ...], out + "/prep_s1"),
               study.Job("shear_s1", [rondel, "shear.ini", "--scene.file=" + out + "/prep_s1", ...], ...)], ...]
    failed = study.run_chains(chains, workers=2)      # {job name: log path} of the runs that failed

A run counts as finished when its summary.txt says 'status: complete': a run stopped by a signal writes
'status: stopped ...' and a failed one none, and both run again. A job of a chain runs only after the one
before it finished; when one fails, the rest of its chain is skipped (and reported as failed)."""
import concurrent.futures as cf
import os
import subprocess
import time

from .errors import CheckFailed, RondelError
from .run import open_run

# Open MPI refuses root without these; the runs of a study are often started as root in a container.
MPI_ROOT_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def environment():
    return dict(os.environ, **MPI_ROOT_ENV)


def run_command(cmd, log, cwd=None):
    """Run CMD with its output into the file LOG; (exit code, wall seconds)."""
    t0 = time.time()
    with open(log, "w") as f:
        rc = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, env=environment(), cwd=cwd)
    return rc, time.time() - t0


def complete(outdir):
    """The run in OUTDIR ran to its end: its summary.txt says 'status: complete'."""
    try:
        with open(os.path.join(outdir, "summary.txt")) as f:
            return any(line.strip() == "status: complete" for line in f)
    except OSError:
        return False


def wall_seconds(outdir):
    """The run's wall time from its summary (summary.json or summary.txt); NaN when it has none."""
    try:
        return float(open_run(outdir).summary()["wall_seconds"])
    except (RondelError, KeyError, TypeError, ValueError):
        return float("nan")


def probe_dt(cmd, outdir, cwd=None, fallback=None):
    """The time step a run of CMD takes (it depends on the laws and materials): one step into OUTDIR.probe
    (CMD's own run.steps, run.output and run.overwrite are replaced). FALLBACK, when given, is returned if the
    probe's files do not say it (an older build); otherwise that raises."""
    mine = ("--run.steps=", "--run.output=", "--run.overwrite=", "--output.checkpoint_at_end=")
    cmd = [c for c in cmd if not str(c).startswith(mine)]
    p = subprocess.run(cmd + ["--run.steps=1", f"--run.output={outdir}.probe", "--run.overwrite=true",
                              "--output.checkpoint_at_end=false"], capture_output=True, text=True,
                       env=environment(), cwd=cwd)
    if p.returncode != 0:
        tail = (p.stderr.strip() or p.stdout.strip()).splitlines()[-1:] or [""]
        raise CheckFailed(f"the probe run for {outdir} exited with code {p.returncode}: {tail[0]}")
    try:
        return float(open_run(f"{outdir}.probe").time_step()["dt"])
    except RondelError:
        if fallback is None:
            raise
        return fallback


class Job:
    """One run: NAME (for the messages), CMD (the whole command line), OUT its run directory, LOG its output
    (default OUT.log). DONE(out) says whether it finished (default: complete); AGAIN runs it even so (what it
    started from has changed). With OUTPUT (default) a rondel command without --run.output gets
    --run.output=OUT --run.overwrite=true; a command of another program (a tool that runs rondel itself) passes
    OUTPUT=False."""

    def __init__(self, name, cmd, out, log=None, done=complete, output=True, again=False):
        self.name, self.out, self.log, self.done, self.again = name, out, log or out + ".log", done, again
        named = any(str(c).startswith("--run.output=") for c in cmd)
        self.cmd = cmd if named or not output else cmd + [f"--run.output={out}", "--run.overwrite=true"]


def run_chains(chains, workers=1, cwd=None, say=print):
    """Run the jobs of CHAINS (lists of Job, each job after the one before it), WORKERS chains at a time, in
    the order given; finished jobs are skipped. Says 'NAME: done (exit 0) in S s' or 'NAME: FAILED (exit N) in S s:
    see LOG' as each ends (a run that exits 0 without finishing fails too). Returns {name: log} of the jobs that
    failed or could not run because one before them in their chain failed."""
    failed = {}

    def go(chain):
        for k, job in enumerate(chain):
            if not job.again and job.done(job.out):
                continue
            os.makedirs(os.path.dirname(os.path.abspath(job.out)), exist_ok=True)
            rc, seconds = run_command([str(c) for c in job.cmd], job.log, cwd)
            ok = rc == 0 and job.done(job.out)
            say(f"{job.name}: {'done' if ok else 'FAILED'} (exit {rc}) in {seconds:.1f} s"
                + ("" if ok else f": see {job.log}"), flush=True)
            if not ok:
                failed[job.name] = job.log
                for rest in chain[k + 1:]:
                    failed[rest.name] = f"not run: {job.name} failed (see {job.log})"
                return

    chains = [c for c in chains if c]
    todo = sum(1 for c in chains for j in c if j.again or not j.done(j.out))
    say(f"{todo} run(s) to go, {sum(len(c) for c in chains) - todo} finished before", flush=True)
    with cf.ThreadPoolExecutor(max(1, workers)) as ex:
        list(ex.map(go, chains))
    return failed
