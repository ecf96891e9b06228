#!/usr/bin/env python3
"""The scaling model of docs/scaling.md: step time, parallel efficiency and checkpoint time of Rondel for
N discs on P ranks, from a few machine constants (stated below; change them for another machine).

usage: python3 tools/scaling_model.py [--c-ns 45] [--latency-us 1.5] [--bandwidth-gbs 10] [--fs-gbs 50]
Prints one table row per (N, P) with the terms of the step time and the first term to dominate."""
import argparse
import math

# Measured on the test machine (docs/scaling.md, "Measured"): ghosts per rank g = G sqrt(n) for n discs per
# rank (Hilbert ranges), 40 B per ghost and step, 280 B per disc in a checkpoint (with two contact rows).
G_GHOSTS = 7.8
GHOST_BYTES = 40
CHECKPOINT_BYTES = 280
# The step's reduction buffer: 5 slots without controlled walls; with four servo walls 4 x 208 + 5 slots.
REDUCE_BYTES = {"deposition": 48, "biaxial": 8 * (4 * 208 + 6)}
# Steps per reduction without controlled walls (measured 10 in the deposition: parallel.check_every).
STEPS_PER_REDUCTION = {"deposition": 10.0, "biaxial": 1.0}
NEIGHBOURS = 8  # partners of a rank in 2D (measured 5 to 7 on 8 ranks)


def step_terms(n, P, kind, a):
    compute = n * a.c_ns * 1e-9
    ghosts = G_GHOSTS * math.sqrt(n)
    exchange = (NEIGHBOURS * a.latency_us * 1e-6 + ghosts * GHOST_BYTES / (a.bandwidth_gbs * 1e9)) if P > 1 else 0.0
    rounds = math.ceil(math.log2(P)) if P > 1 else 0
    reduce = rounds * (a.latency_us * 1e-6 + REDUCE_BYTES[kind] / (a.bandwidth_gbs * 1e9)) / STEPS_PER_REDUCTION[kind]
    return compute, exchange, reduce


def checkpoint_time(N, P, a):
    n = N / P
    sort = P * a.latency_us * 1e-6 + n * CHECKPOINT_BYTES / (a.bandwidth_gbs * 1e9)
    write = N * CHECKPOINT_BYTES / (a.fs_gbs * 1e9)
    return sort + write


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--c-ns", type=float, default=45.0, help="ns per disc-step on one core (wang rolling)")
    ap.add_argument("--latency-us", type=float, default=1.5, help="MPI latency of a small message")
    ap.add_argument("--bandwidth-gbs", type=float, default=10.0, help="bandwidth per rank, GB/s")
    ap.add_argument("--fs-gbs", type=float, default=50.0, help="parallel file system bandwidth, GB/s")
    a = ap.parse_args()
    print("| N | P | discs per rank | compute | exchange | reduction (deposition / biaxial) | "
          "efficiency (deposition / biaxial) | checkpoint | dominant beyond compute |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for N in (1e6, 1e7, 1e8, 1e9):
        for P in (64, 1024, 16384):
            n = N / P
            c, e, r_dep = step_terms(n, P, "deposition", a)
            _, _, r_bx = step_terms(n, P, "biaxial", a)
            eff_dep = c / (c + e + r_dep)
            eff_bx = c / (c + e + r_bx)
            dominant = "reduction (biaxial)" if r_bx > e else "ghost exchange"
            print("| %.0e | %d | %.0f | %.1f us | %.1f us | %.2f / %.1f us | %.2f / %.2f | %.2f s | %s |" % (
                N, P, n, c * 1e6, e * 1e6, r_dep * 1e6, r_bx * 1e6, eff_dep, eff_bx, checkpoint_time(N, P, a),
                dominant))


if __name__ == "__main__":
    main()
