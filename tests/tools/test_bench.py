#!/usr/bin/python3
"""Tests of rondel_bench's command line and report (ctest: tools.bench).

  /usr/bin/python3 tests/tools/test_bench.py BUILD/rondel_bench

  - --discs 30000 runs 3 x 1 periodic copies for a few steps and prints the existing lines (one
    "disc-steps per second" line: tools/bench_pairs.sh reads its fourth field), then the seconds per phase,
    nanoseconds per contact-step and the bytes-per-disc-step model;
  - --discs 15000 (not 10,000 times a copy count) and --discs 0 are refused with a message naming --discs;
  - with the triad (no --no-stream): the bandwidth, the bandwidth bound and the measured fraction of it;
  - the model follows the contact columns: rolling wang (a history slot and two couples more) moves more
    bytes per row than rolling none;
  - --against LAW runs a second simulation in alternating chunks: still one "disc-steps per second" line, the
    other law's rate over the same steps, and the ratio (median of the chunk pairs inside their range, and of
    the totals equal to the two printed rates' ratio); a law that does not exist, a chunk of 0 or longer than
    --steps, and --steps 0 are refused with a message naming the option.
Exits non-zero on any failure and prints 'N passed, N failed'.
"""
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))

results = []


def check(name, cond, detail=""):
    results.append(bool(cond))
    print(("PASS " if cond else "FAIL ") + name + ("" if cond else f": {detail}"), flush=True)


def bench(exe, *args):
    p = subprocess.run([exe, *args], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=120)
    return p.returncode, p.stdout, p.stderr


def number(pattern, text):
    m = re.search(pattern, text, re.M)
    return float(m.group(1)) if m else None


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    exe = os.path.abspath(sys.argv[1])

    code, out, err = bench(exe, "--discs", "30000", "--steps", "5", "--warmup", "0", "--no-stream")
    check("30000 discs: exit 0", code == 0, err)
    check("30000 discs: 3 x 1 copies", out.startswith("rondel_bench: 30000 discs (3 x 1 copies)"), out[:200])
    rates = [line.split()[3] for line in out.splitlines() if "disc-steps per second" in line]
    check("one 'disc-steps per second' line, a number in its fourth field",
          len(rates) == 1 and float(rates[0]) > 0, rates)
    for key in ("wall time", "contacts per disc", "candidate rows/disc", "neighbour builds", "memory per disc",
                "communication", "ghosts per disc", "rows computed twice"):
        check(f"existing line '{key}'", re.search(rf"^  {re.escape(key)}\s", out, re.M), out)
    phases = dict(re.findall(r"^  phase (\S+)\s+\S+ s \((\S+) %\)$", out, re.M))
    check("seconds and percent per phase",
          {"force", "neighbour", "communication", "integrate", "other"} <= set(phases)
          and 90.0 <= sum(float(v) for v in phases.values()) <= 110.0, phases)
    force_ns, total_ns = (number(r"^  ns per contact-step\s+(\S+) in the force phase", out),
                          number(r"^  ns per contact-step.*, (\S+) in all", out))
    check("ns per contact-step, force below total", force_ns and total_ns and 0 < force_ns <= total_ns, out)
    none_bytes = number(r"^  bytes per disc-step \(model\) (\S+) B", out)
    check("bytes per disc-step (model)", none_bytes and none_bytes > 0, out)
    check("no triad with --no-stream", "not measured (--no-stream)" in out and "bandwidth bound" not in out, out)

    for bad in ("15000", "0"):
        code, out, err = bench(exe, "--discs", bad, "--steps", "1", "--warmup", "0", "--no-stream")
        check(f"--discs {bad} refused naming --discs", code != 0 and "--discs" in err and bad in err, err + out)

    code, out, err = bench(exe, "--discs", "10000", "--steps", "3", "--warmup", "0", "--rolling", "wang")
    check("triad: exit 0", code == 0, err)
    bandwidth = number(r"^  stream triad\s+(\S+) GB/s", out)
    bound = number(r"^  bandwidth bound\s+(\S+) disc-steps/s", out)
    fraction = number(r"^  measured / bound\s+(\S+)$", out)
    wang_bytes = number(r"^  bytes per disc-step \(model\) (\S+) B", out)
    check("triad: bandwidth, bound and fraction printed", bandwidth and bound and fraction, out)
    if bandwidth and bound and wang_bytes:
        check("triad: bound = bandwidth / bytes per disc-step",
              abs(bound - bandwidth * 1e9 / wang_bytes) < 2e-3 * bound, (bound, bandwidth, wang_bytes))
    check("model: wang moves more bytes per row than none", wang_bytes and none_bytes and wang_bytes > none_bytes,
          (wang_bytes, none_bytes))
    check("peak RSS is the simulation's (reset after the triad)", "with the triad's arrays" not in out, out)

    code, out, err = bench(exe, "--steps", "6", "--warmup", "0", "--rolling", "wang", "--against", "none",
                           "--chunk", "2", "--no-stream")
    check("--against: exit 0", code == 0, err)
    rates = [float(line.split()[3]) for line in out.splitlines() if "disc-steps per second" in line]
    check("--against: still one 'disc-steps per second' line", len(rates) == 1 and rates[0] > 0, out)
    m = re.search(r"^  against none\s+(\S+) disc-steps/s, the same steps in 3 chunk pairs of 2 ", out, re.M)
    check("--against: the other law's rate over 3 chunk pairs of 2 steps", m and float(m.group(1)) > 0, out)
    r = re.search(r"^  rate wang / none: (\S+) median of the pairs \((\S+) to (\S+)\), (\S+) of the totals$", out, re.M)
    check("--against: the ratio line", r, out)
    if m and r and rates:
        median, lo, hi, totals = (float(g) for g in r.groups())
        check("--against: median within the pairs' range", 0 < lo <= median <= hi, r.group(0))
        # The rates are printed to 4 significant digits (each off by up to 5e-4 of itself) and the ratio to 3
        # decimals (off by up to 5e-4): a loaded machine's small ratio made a relative bound of 2e-3 fail.
        check("--against: ratio of the totals = ratio of the printed rates",
              abs(totals - rates[0] / float(m.group(1))) <= 1.01e-3 * totals + 5.01e-4, (totals, rates[0], m.group(1)))
    base = ["--warmup", "0", "--no-stream", "--steps"]
    for args, option in ((base + ["6", "--against", "sideways"], "--against"),
                         (base + ["6", "--against", "none", "--chunk", "0"], "--chunk"),
                         (base + ["6", "--against", "none", "--chunk", "7"], "--chunk"), (base + ["0"], "--steps")):
        code, out, err = bench(exe, *args)
        check(f"{' '.join(args[3:])} refused naming {option}", code != 0 and option in err and not out, err + out)
    code, out, err = bench(exe, "--steps", "6", "--warmup", "0", "--no-stream", "--against", "sideways")
    check("--against: an unknown law's message lists the laws", "wang" in err and "none" in err, err)

    failed = results.count(False)
    print(f"{results.count(True)} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
