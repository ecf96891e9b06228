#!/usr/bin/env bash
# Compares two builds of rondel_bench as interleaved pairs (A B A B ...) in one run, so that a noisy, shared
# machine loads both alike; prints each trial, the medians of disc-steps per second and the ratio B/A.
#   bash tools/bench_pairs.sh BENCH_A BENCH_B [--trials N] [-- rondel_bench options]
# e.g. bash tools/bench_pairs.sh old/rondel_bench build/rondel_bench --trials 5 -- --discs 10000 --rolling wang
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,5p' "$0" >&2; exit 1; }
a=$1 b=$2
shift 2
trials=5
if [ "${1:-}" = "--trials" ]; then trials=$2; shift 2; fi
[ "${1:-}" = "--" ] && shift
for bin in "$a" "$b"; do [ -x "$bin" ] || { echo "tools/bench_pairs.sh: ERROR: '$bin' is not an executable" >&2; exit 1; }; done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "tools/bench_pairs.sh: $(uptime)"
echo "tools/bench_pairs.sh: A = $a, B = $b, options: $*"
rate() { "$1" "${@:2}" | awk '/disc-steps per second/ {print $4}'; }
ra=() rb=()
for ((t = 1; t <= trials; ++t)); do
  x=$(rate "$a" "$@"); y=$(rate "$b" "$@")
  [ -n "$x" ] && [ -n "$y" ] || { echo "tools/bench_pairs.sh: ERROR: a run printed no rate" >&2; exit 1; }
  ra+=("$x") rb+=("$y")
  echo "  trial $t: A $x  B $y  B/A $(awk -v x="$x" -v y="$y" 'BEGIN {printf "%.3f", y / x}')"
done
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
ma=$(median "${ra[@]}") mb=$(median "${rb[@]}")
echo "median disc-steps/s: A $ma  B $mb  B/A $(awk -v x="$ma" -v y="$mb" 'BEGIN {printf "%.3f", y / x}')"
