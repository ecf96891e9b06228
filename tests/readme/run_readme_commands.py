#!/usr/bin/env python3
"""ctest readme.commands: runs the commands of README.md that CI can run, so that the README stays true.

It reads every ```sh block of README.md (continuation lines joined, comments dropped) and runs, in order and
in one scratch directory, each line that starts with `mpirun`, `build/`, `python3 tools/` or
`/usr/bin/python3 tools/`; `export` lines set the environment of the next ones. Everything else (the set-up
commands `bash tools/...`, `ctest`, `cmake`, `xvfb-run`, ...) is listed as not run. The scratch directory
holds copies of inputs/, tools/ and examples/ and a link build -> the build directory, so that the commands run as
written from a repository root and write nowhere in the checkout.

Long runs are shortened: a rondel run of an INI file without --run.steps gets --run.steps=200 (and a snapshot
every 100 steps, so that the tools find snapshots as after the whole run), rondel_bench
and rondel_bench_io get few steps, and the tools that run scenes themselves get short stages (SHORTEN).
Commands whose input a short run cannot give are skipped with the reason (SKIP); the test fails when a
command exits with a non-zero code or when fewer than MIN_RUN commands ran (the extraction broke).
  /usr/bin/python3 tests/readme/run_readme_commands.py --source DIR --build DIR --work DIR [--list]
"""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

STEPS = 200  # steps of a shortened rondel run
MIN_RUN = 5  # the README has more runnable commands than this; fewer means the extraction broke
TIMEOUT_S = 600  # per command

# Options appended to a command (when its program is `key` and the first option is not already there).
SHORTEN = {
    "build/rondel_bench": ["--steps", "100", "--warmup", "10"],
    "build/rondel_bench_io": ["--discs", "2000", "--steps", "5", "--warmup", "1", "--repeat", "1"],
    # the prepare stage runs whole (its analysis needs a confined sample; about 10 s), the shear stages short
    "tools/biaxial_sweep.py": ["--steps", "2000"],
    "examples/python/cyclic_biaxial.py": ["--quick"],
}

# (regular expression on the command, why it cannot run after shortened runs)
SKIP = [
    (r"tools/repose\.py", "needs a settled pile: the whole pile.ini run (350,000 steps)"),
    (r"tools/shear\.py", "needs snapshots in the steady window of the whole plane_shear.ini run (400,000 steps)"),
]

RUN_PREFIXES = ("mpirun", "build/", "python3 tools/", "/usr/bin/python3 tools/")


def sh_lines(readme_text):
    """The command lines of the ```sh blocks, continuation lines joined."""
    lines, in_block, pending = [], False, ""
    for raw in readme_text.splitlines():
        stripped = raw.strip()
        if stripped.startswith("```"):
            in_block = not in_block and stripped[3:].strip() in ("sh", "bash", "shell", "console")
            pending = ""
            continue
        if not in_block:
            continue
        if stripped.endswith("\\"):
            pending += stripped[:-1] + " "
            continue
        line = (pending + stripped).strip()
        pending = ""
        if line:
            lines.append(line)
    return lines


def program_of(tokens):
    """The program a command runs: past mpirun and its options, past the python interpreter."""
    i = 0
    if tokens[0] == "mpirun":
        i = 1
        while i < len(tokens) and tokens[i].startswith("-"):
            # -n N, -np N take a value; --oversubscribe and the like do not
            i += 2 if tokens[i] in ("-n", "-np", "-c", "--np", "--host", "-H", "--map-by", "--bind-to") else 1
    if i < len(tokens) and tokens[i] in ("python3", "/usr/bin/python3"):
        i += 1
    return tokens[i] if i < len(tokens) else ""


def prepared(tokens):
    """The command with its run shortened (see the module text)."""
    program = program_of(tokens)
    extra = []
    if program == "build/rondel":
        fresh = any(t.endswith(".ini") for t in tokens) and "--resume" not in tokens
        if fresh and not any(t.startswith("--run.steps=") for t in tokens):
            # snapshots within the short run, as the whole run has them (picture.py --kind ranks reads one)
            extra = [f"--run.steps={STEPS}"]
            if not any(t.startswith("--output.snapshot_every=") for t in tokens):
                extra.append(f"--output.snapshot_every={STEPS // 2}")
    elif program in SHORTEN and SHORTEN[program][0] not in tokens:
        extra = SHORTEN[program]
    return tokens + extra


def classify(line):
    """('run', tokens) | ('env', {name: value}) | ('skip', reason) | ('not run', reason)."""
    try:
        tokens = shlex.split(line, comments=True)
    except ValueError as e:
        return "not run", f"cannot split it ({e})"
    if not tokens:
        return "comment", ""
    if tokens[0] == "export":
        return "env", dict(t.split("=", 1) for t in tokens[1:] if "=" in t)
    command = shlex.join(tokens)
    if not command.startswith(RUN_PREFIXES):
        return "not run", "not a command this test runs (set-up, ctest, cmake, ...)"
    for pattern, reason in SKIP:
        if re.search(pattern, command):
            return "skip", reason
    return "run", tokens


def make_scratch(source, build, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for d in ("inputs", "tools", "examples"):
        shutil.copytree(os.path.join(source, d), os.path.join(work, d),
                        ignore=shutil.ignore_patterns("__pycache__"))
    os.symlink(os.path.abspath(build), os.path.join(work, "build"))


def run_one(tokens, work, env):
    start = time.monotonic()
    try:
        proc = subprocess.run(tokens, cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True, timeout=TIMEOUT_S)
        code, output = proc.returncode, proc.stdout
    except subprocess.TimeoutExpired as e:
        out = e.stdout or ""
        code, output = f"timeout ({TIMEOUT_S} s)", out.decode(errors="replace") if isinstance(out, bytes) else out
    except OSError as e:
        code, output = "not started", str(e)
    return code, output, time.monotonic() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, help="the repository root (README.md, inputs/, tools/)")
    ap.add_argument("--build", required=True, help="the build directory (rondel, rondel_bench)")
    ap.add_argument("--work", required=True, help="scratch directory, replaced")
    ap.add_argument("--list", action="store_true", help="print what would run, run nothing")
    args = ap.parse_args()

    readme = os.path.join(args.source, "README.md")
    try:
        with open(readme, encoding="utf-8") as f:
            lines = sh_lines(f.read())
    except OSError as e:
        print(f"readme.commands: ERROR: cannot read {readme}: {e}", file=sys.stderr)
        return 1
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", MPLBACKEND="Agg")
    if not args.list:
        make_scratch(args.source, args.build, args.work)

    ran, failed = 0, []
    for line in lines:
        kind, what = classify(line)
        if kind == "env":
            env.update(what)
            continue
        if kind == "comment":
            continue
        if kind != "run":
            print(f"{kind:8s} {line}\n         ({what})")
            continue
        tokens = prepared(what)
        print(f"run      {shlex.join(tokens)}", flush=True)
        if args.list:
            continue
        code, output, seconds = run_one(tokens, args.work, env)
        ran += 1
        print(f"         exit {code}, {seconds:.1f} s", flush=True)
        if code != 0:
            failed.append(line)
            tail = "\n".join(output.splitlines()[-30:])
            print(f"         its output (last 30 lines):\n{tail}", flush=True)

    if args.list:
        return 0
    if ran < MIN_RUN:
        print(f"readme.commands: ERROR: only {ran} command(s) found to run in {readme} (expected at least "
              f"{MIN_RUN}): are the ```sh blocks still there?", file=sys.stderr)
        return 1
    if failed:
        print(f"readme.commands: ERROR: {len(failed)} of {ran} README commands failed:", file=sys.stderr)
        for line in failed:
            print(f"  {line}", file=sys.stderr)
        return 1
    print(f"readme.commands: all {ran} README commands that CI can run exited 0")
    return 0


if __name__ == "__main__":
    sys.exit(main())
