#!/usr/bin/python3
"""rondel asks for transparent huge pages (ctest: tools.huge_pages; src/app/HugePages.hpp): it runs itself again,
before MPI starts, with glibc.malloc.hugetlb=1 added to GLIBC_TUNABLES when the kernel gives huge pages on request
and glibc knows the tunable; RONDEL_HUGE_PAGES=0 keeps it from doing so, and another value is refused.

    /usr/bin/python3 tests/tools/test_huge_pages.py BUILD/rondel

A run's environment is read from /proc/PID/environ while it runs (an exec keeps the PID), then the run is stopped by
SIGTERM. (Tunables already in GLIBC_TUNABLES are kept before the new one, but glibc rewrites the variable in place
when it reads it, so what /proc shows then is not what was set: that case is not checked here.) Prints 'N passed,
N failed'.
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
TUNABLE = "glibc.malloc.hugetlb=1"
results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"), flush=True)


def offered():
    """Whether rondel should ask: THP on request ([madvise]) and glibc 2.35 or later."""
    try:
        with open("/sys/kernel/mm/transparent_hugepage/enabled") as f:
            on_request = "[madvise]" in f.read()
    except OSError:
        on_request = False
    major, minor = (int(x) for x in os.confstr("CS_GNU_LIBC_VERSION").split()[1].split(".")[:2])
    return on_request and (major, minor) >= (2, 35)


def run_environment(exe, out, env):
    """The GLIBC_TUNABLES of a running rondel (None: not set), and its exit status after SIGTERM."""
    p = subprocess.Popen([exe, os.path.join(ROOT, "inputs", "deposition.ini"), "--run.steps=100000000",
                          "--run.output=" + out, "--run.progress=false"], env=env,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    seen, deadline = None, time.time() + 60
    while time.time() < deadline and p.poll() is None:
        try:
            with open(f"/proc/{p.pid}/cmdline", "rb") as f:
                started = f.read().startswith(exe.encode())
            with open(f"/proc/{p.pid}/environ", "rb") as f:
                pairs = [kv.split(b"=", 1) for kv in f.read().split(b"\0") if b"=" in kv]
        except OSError:
            break
        tunables = dict(pairs).get(b"GLIBC_TUNABLES")
        seen = None if tunables is None else tunables.decode()
        if started and time.time() > deadline - 55:  # a few seconds in: any exec has happened
            break
        time.sleep(0.2)
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=120)
    return seen, p.returncode, err


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    exe = os.path.abspath(sys.argv[1])
    base = {k: v for k, v in os.environ.items() if k not in ("GLIBC_TUNABLES", "RONDEL_HUGE_PAGES")}
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run([exe, "--version"], env=dict(base, RONDEL_HUGE_PAGES="yes"), capture_output=True, text=True)
        check("RONDEL_HUGE_PAGES=yes refused with exit 1, naming the variable and its values",
              p.returncode == 1 and "RONDEL_HUGE_PAGES" in p.stderr and "0" in p.stderr and not p.stdout, p)
        p = subprocess.run([exe, "--help"], env=base, capture_output=True, text=True)
        check("--help names RONDEL_HUGE_PAGES and its values", "RONDEL_HUGE_PAGES = 1" in p.stdout and "or 0" in p.stdout,
              p.stdout[:600])
        p = subprocess.run([exe, "--version"], env=base, capture_output=True, text=True)
        check("run again, the arguments kept (--version answers)", p.returncode == 0 and "rondel" in p.stdout, p)
        seen, code, err = run_environment(exe, os.path.join(tmp, "a"), base)
        expected = TUNABLE if offered() else None
        check(f"by default the run's GLIBC_TUNABLES is {expected}", seen == expected, seen)
        check("stopped by SIGTERM as usual (exit 10)", code == 10, (code, err[-500:]))
        seen, _, _ = run_environment(exe, os.path.join(tmp, "b"), dict(base, RONDEL_HUGE_PAGES="0"))
        check("RONDEL_HUGE_PAGES=0: not set", seen is None, seen)
    failed = results.count(False)
    print(f"{results.count(True)} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
