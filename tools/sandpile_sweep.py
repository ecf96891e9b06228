"""The sweep of tools/sandpile.py (--sweep): the fill once, then the discharge of every law from it, each run reused,
resumed, extended or run afresh as its files say, through rondel.study; then every complete discharge measured by
sandpile.py's analysis into the sweep's table. The options and the files are those of sandpile.py --help."""
import csv
import os
import sys

from rondel import CheckFailed, Config, RondelFileError, UsageError, open_run, step_of_name, study
from rondel.study import complete as done, wall_seconds
from sandpile import DISCHARGE, FILL, QUICK, ROOT, TABLE_COLUMNS, TOOL, analyse_run, fmt, write_outputs


def parse_steps(text, laws, default):
    """{law: discharge steps} from --steps: 'N' for every law and/or 'LAW=N' for one (LAW=N wins over N, in any
    order); the laws not named keep DEFAULT[law]."""
    every, one = {}, {}
    for item in (x.strip() for x in (text or "").split(",")):
        if not item:
            continue
        law, _, value = item.rpartition("=")
        try:
            n = int(value)
        except ValueError:
            raise UsageError(f"--steps '{text}': '{item}' is not N or LAW=N") from None
        if n < 1:
            raise UsageError(f"--steps '{text}': the step count {n} must be >= 1")
        if law and law not in laws:
            raise UsageError(f"--steps '{text}': '{law}' is not one of the sweep's laws ({','.join(laws)})")
        if law:
            one[law] = n
        else:
            every = {name: n for name in laws}
    return {**default, **every, **one}


def scene_steps(ini):
    """run.steps of an input file."""
    try:
        return int(Config.from_file(ini).get("run", "steps", ""))
    except ValueError:
        raise RondelFileError(ini, "has no integer run.steps") from None


def reached(d):
    """The step of the newest checkpoint in D (-1 without one)."""
    cps = open_run(d).checkpoint_paths() if os.path.isdir(d) else []
    return step_of_name(cps[-1]) if cps else -1


def finished_at(target):
    """A run's test of being finished (rondel.study.Job's DONE): complete, with its newest checkpoint at TARGET or
    beyond."""
    return lambda d: done(d) and reached(d) >= target


def stage(a, name, d, fresh_cmd, target, redo=False):
    """(study.Job or None, what): the rondel call that brings run D to TARGET steps. Reused when it is complete at
    TARGET (or beyond) and REDO is not set; resumed (rondel --resume D --run.steps=TARGET, the contact history
    kept) when it holds a checkpoint below TARGET: a run stopped by a signal, or killed, or complete at fewer
    steps (extended); otherwise run afresh into D."""
    prefix = ([a.mpiexec, "-n", str(a.ranks), "--oversubscribe"] if a.ranks > 1 else []) + [a.rondel]
    step = reached(d)
    if not redo and done(d) and step >= target:
        return None, f"{name}: complete at step {step}, reused"
    if not redo and 0 <= step < target:
        cmd = prefix + ["--resume", d, f"--run.steps={target}", "--run.progress=false",
                        f"--output.checkpoint_every={a.checkpoint_every}"] + a.rondel_arg
        return (study.Job(name, cmd, d, done=finished_at(target), output=False),  # --resume D writes into D
                f"{name}: resumed from step {step} to {target}")
    cmd = prefix + fresh_cmd + [f"--run.output={d}", "--run.overwrite=true", "--run.progress=false",
                                f"--run.steps={target}", f"--output.checkpoint_every={a.checkpoint_every}"]
    return study.Job(name, cmd, d, done=finished_at(target), again=redo), f"{name}: run afresh ({target} steps)"


def launch_all(jobs, n, failed):
    """Run JOBS (study.Job) N at a time (rondel.study); a run that exits non-zero or does not finish at its step
    is reported and its directory added to FAILED."""
    if jobs:
        bad = study.run_chains([[j] for j in jobs], n, ROOT)
        failed.extend(j.out for j in jobs if j.name in bad)


def check_preset(out, preset, write=True):
    """OUT/sweep.txt names the preset (quick or full) the sweep's runs were made with: a sweep into OUT with the
    other preset is refused (it would reuse runs of another size). WRITE: write it when there is none."""
    path = os.path.join(out, "sweep.txt")
    line = f"preset: {preset}"
    if os.path.isfile(path):
        with open(path) as f:
            old = f.readline().strip()
        if old != line:
            raise UsageError(f"{out} holds a sweep made with '{old}', not '{line}': use another --out")
    elif write:
        with open(path, "w") as f:
            f.write(line + "\n")


def sweep(a):
    laws = list(dict.fromkeys(x.strip() for x in a.laws.split(",") if x.strip()))
    bad = [x for x in laws if x not in DISCHARGE]
    if bad or not laws:
        raise UsageError(f"--laws: {','.join(bad) or 'none given'}: choose from {','.join(DISCHARGE)}")
    if a.jobs < 1 or a.ranks < 1 or a.checkpoint_every < 1:
        raise UsageError("--jobs, --ranks and --checkpoint-every must be >= 1")
    if not a.collect_only and not os.access(a.rondel, os.X_OK):
        raise UsageError(f"the rondel executable '{a.rondel}' does not exist or is not executable (build it: "
                         "bash tools/setup.sh rondel, or pass --rondel)")
    inputs = {law: os.path.join(a.inputs, DISCHARGE[law]) for law in laws}
    fill_ini = os.path.join(a.inputs, FILL)
    for ini in [fill_ini] + list(inputs.values()):
        if not os.path.isfile(ini):
            raise RondelFileError(ini, "no such input file")
    if a.quick:
        fill_steps = QUICK["fill_steps"]
        steps = parse_steps(a.steps, laws, {law: QUICK["steps"] for law in laws})
        quick = [f"--scene.count={QUICK['count']}", f"--output.snapshot_every={QUICK['snapshot_every']}"]
    else:
        fill_steps = scene_steps(fill_ini)
        steps = parse_steps(a.steps, laws, {law: scene_steps(inputs[law]) for law in laws})
        quick = []
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    check_preset(out, "quick" if a.quick else "full", write=not a.collect_only)
    fill = os.path.join(out, "fill")
    dirs = {law: os.path.join(out, law) for law in laws}
    failed = []

    # Stage 1: the fill (gate closed), once.
    job, what = stage(a, "fill", fill, [fill_ini] + quick + a.rondel_arg, fill_steps)
    new_fill = job is not None and not a.collect_only
    if a.collect_only:
        print("--collect-only: running nothing", flush=True)
    else:
        print(what, flush=True)
        launch_all([job] if job else [], 1, failed)
        if failed:
            raise CheckFailed(f"the fill stage failed: see {fill}.log")

    # Stage 2: one discharge per law from the filled hopper; after a new fill every discharge runs afresh.
    jobs = []
    for law in laws:
        cmd = [inputs[law], f"--scene.file={fill}"] + quick + a.rondel_arg
        job, what = stage(a, law, dirs[law], cmd, steps[law], redo=new_fill)
        if a.collect_only:
            print(f"{law}: {'complete' if done(dirs[law]) else 'not complete'} at step {reached(dirs[law])}",
                  flush=True)
        else:
            print(what, flush=True)
            if job:
                jobs.append(job)
    if not a.collect_only:
        launch_all(jobs, a.jobs, failed)

    # Measure every complete discharge.
    measured, errors = [], []
    for law in laws:
        if not done(dirs[law]):
            continue
        try:
            r = analyse_run(dirs[law], a, len(measured))
        except CheckFailed as e:
            errors.append(str(e))
            print(f"{TOOL}: {law}: {e}", file=sys.stderr)
            continue
        measured.append((law, r))
    if measured:
        write_outputs(os.path.join(out, "sandpile"), [r for _, r in measured], a, [law for law, _ in measured])
    with open(os.path.join(out, "table.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(TABLE_COLUMNS)
        for law, r in measured:
            s = dict(r["summary"], law=law, steps=reached(dirs[law]), wall_s=wall_seconds(dirs[law]))
            w.writerow([fmt(s[c]) for c in TABLE_COLUMNS])
    print(f"wrote {os.path.join(out, 'table.csv')} ({len(measured)} of {len(laws)} laws)", flush=True)
    if failed:
        raise CheckFailed(f"{len(failed)} run(s) failed: " + ", ".join(failed))
    if errors:
        raise CheckFailed(f"{len(errors)} run(s) could not be measured: " + "; ".join(errors))
    if not measured and not a.collect_only:
        raise CheckFailed("no discharge of the sweep is complete")
    return 0
