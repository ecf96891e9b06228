#!/usr/bin/env bash
# Parallel efficiency of rondel_bench on P ranks against 1 rank, as interleaved runs (1, P, 1, P, ...) in one
# go so that a shared machine loads both alike; prints each trial, the medians and the efficiency
# median(P ranks) / (P x median(1 rank)). Check that the machine is otherwise idle first (uptime, top).
#   bash tools/bench_efficiency.sh [--ranks P] [--trials N] [-- rondel_bench options]
# e.g. bash tools/bench_efficiency.sh --ranks 2 --trials 7 -- --discs 160000 --steps 1000 --warmup 200
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
ranks=2 trials=5
while [ $# -gt 0 ]; do
  case "$1" in
    --ranks) ranks=$2; shift 2 ;;
    --trials) trials=$2; shift 2 ;;
    --) shift; break ;;
    *) sed -n '2,6p' "$0" >&2; exit 1 ;;
  esac
done
bench=build/rondel_bench
[ -x "$bench" ] || { echo "tools/bench_efficiency.sh: ERROR: $bench is missing (bash tools/setup.sh)" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "tools/bench_efficiency.sh: $(uptime)"
echo "tools/bench_efficiency.sh: 1 against $ranks ranks, options: $*"
rate() { "$@" | awk '/disc-steps per second/ {print $4}'; }
r1=() rp=()
for ((t = 1; t <= trials; ++t)); do
  x=$(rate "$bench" "$@"); y=$(rate mpirun -n "$ranks" "$bench" "$@")
  [ -n "$x" ] && [ -n "$y" ] || { echo "tools/bench_efficiency.sh: ERROR: a run printed no rate" >&2; exit 1; }
  r1+=("$x") rp+=("$y")
  echo "  trial $t: 1 rank $x  $ranks ranks $y"
done
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
m1=$(median "${r1[@]}") mp=$(median "${rp[@]}")
echo "median disc-steps/s: 1 rank $m1  $ranks ranks $mp  efficiency $(awk -v x="$m1" -v y="$mp" -v p="$ranks" 'BEGIN {printf "%.3f", y / (p * x)}')"
echo "tools/bench_efficiency.sh: $(uptime)"
