#!/usr/bin/env python3
"""The scaling model of docs/scaling.md: step time, parallel efficiency and checkpoint time of Rondel for
N discs on P ranks, from a few machine constants (stated below; change them for another machine).

usage: python3 tools/scaling_model.py [--c-ns 45] [--latency-us 1.5] [--bandwidth-gbs 10] [--fs-gbs 50]
                                     [--memory-gb 4]
Prints one table row per (N, P) with the terms of the step time, the peak memory of a rank and what stops the run
first: its memory before its time. The memory a set-up takes on every rank when it builds the whole scene
(scene.type = random) is shown beside it; it stops nothing, since scene.type = random_tiles places the same keys'
discs each rank its own (docs/scaling.md, "Set-up")."""
import argparse
import math

# Measured on the test machine (docs/scaling.md, "Measured"): ghosts per rank g = G sqrt(n) for n discs per
# rank (Hilbert ranges), 40 B per ghost and step, 232 B per disc in a checkpoint (with two contact rows: the file
# of the 40,000,000-disc run).
G_GHOSTS = 7.8
GHOST_BYTES = 40
CHECKPOINT_BYTES = 232
# The step's reduction buffer: 5 slots without controlled walls; with four servo walls 4 x 208 + 5 slots.
REDUCE_BYTES = {"deposition": 48, "biaxial": 8 * (4 * 208 + 6)}
# Steps per reduction without controlled walls (measured 10 in the deposition: parallel.check_every).
STEPS_PER_REDUCTION = {"deposition": 10.0, "biaxial": 1.0}
NEIGHBOURS = 8  # partners of a rank in 2D (measured 5 to 7 on 8 ranks)
# Peak bytes per disc of a rank (docs/scaling.md, "Forty million discs": 40,000,000 discs with wang rolling on 2
# ranks, set-up, steps, checkpoint and final.csv); the set-up of scene.type = random holds about 315 B per disc of
# the whole scene on every rank (every other scene is built or read in blocks, at most 270 B per disc of the rank's
# own at the set-up's peak: docs/scaling.md, "Set-up").
PEAK_BYTES = 381
WHOLE_SCENE_BYTES = 315


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
    ap.add_argument("--memory-gb", type=float, default=4.0, help="memory per rank (a core's share of a node), GB")
    a = ap.parse_args()
    print("| N | P | discs per rank | compute | exchange | reduction (deposition / biaxial) | "
          "efficiency (deposition / biaxial) | checkpoint | peak per rank (whole-scene set-up: random) | stops first |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for N in (1e6, 1e7, 1e8, 1e9, 1e10):
        for P in (64, 1024, 16384):
            n = N / P
            c, e, r_dep = step_terms(n, P, "deposition", a)
            _, _, r_bx = step_terms(n, P, "biaxial", a)
            eff_dep = c / (c + e + r_dep)
            eff_bx = c / (c + e + r_bx)
            peak, whole = n * PEAK_BYTES / 1e9, N * WHOLE_SCENE_BYTES / 1e9
            if peak > a.memory_gb:
                first = "memory of the run"
            elif eff_bx < 0.9:
                first = "reduction (biaxial)" if r_bx > e else "ghost exchange"
            else:
                first = "nothing (efficiency >= 0.9)"
            print("| %.0e | %d | %.0f | %.1f us | %.1f us | %.2f / %.1f us | %.2f / %.2f | %.2f s | %.3g GB (%.3g GB) | %s |"
                  % (N, P, n, c * 1e6, e * 1e6, r_dep * 1e6, r_bx * 1e6, eff_dep, eff_bx, checkpoint_time(N, P, a),
                     peak, whole, first))


if __name__ == "__main__":
    main()
