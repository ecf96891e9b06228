#!/usr/bin/env bash
# Sets up Rondel and builds the one program the run needs (tools/setup.sh rondel: not the test suite), then
# runs the default scene, inputs/deposition.ini, on two MPI ranks and prints where the results are.
#   bash tools/run_default.sh [OUTPUT_DIR]     (default rondel-output/deposition, replaced on a re-run)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash tools/setup.sh rondel

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
default_out=rondel-output/deposition
out=${1:-$default_out}
args=(inputs/deposition.ini "--run.output=${out}")
# Only the default directory is overwritten, so that re-running this command works; a directory you name
# must not exist yet (Rondel refuses to overwrite it).
if [ "$out" = "$default_out" ] && [ -e "$out" ]; then
  args+=(--run.overwrite=true)
fi

echo "tools/run_default.sh: mpirun -n 2 build/rondel ${args[*]}"
status=0
mpirun -n 2 --oversubscribe build/rondel "${args[@]}" || status=$?
if [ "$status" -ne 0 ]; then
  echo "tools/run_default.sh: ERROR: rondel exited with code ${status} (1 configuration or input error," \
    "3 unstable run, 4 internal error)" >&2
  exit "$status"
fi
echo
echo "tools/run_default.sh: done. Results in $(cd "$out" && pwd)/:"
echo "  summary.txt      wall time, disc-steps/s, time step, ledger residual"
echo "  diagnostics.csv  one row per diagnostics.every steps: energies, contacts, overlaps, energy ledger"
echo "  final.csv        final state per disc (hexadecimal floats; Python: float.fromhex)"
echo "  log.txt          the log, with the resolved configuration; config.ini the configuration alone"
