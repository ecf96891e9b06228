#!/bin/bash
# The SLURM job scripts of tools/cluster/ (README "On a cluster"): they parse (bash -n), and their chain logic
# works with a fake srun, mpirun, sbatch and rondel (no SLURM here): a run stopped after a checkpoint
# (exit 10, or mpirun's 1 with summary.json saying "stopped") submits the follow-up job, which resumes; a
# complete run submits nothing; a failed run stops the chain with its exit code even beside an old
# "stopped" summary.json; SIGUSR1 to the batch shell reaches the rank; the chain stops at RONDEL_MAX_JOBS.
# With the rondel executable as a second argument, also a real run through the real mpirun, signalled and resumed.
#   bash tests/tools/test_cluster_scripts.sh SOURCE_DIR [RONDEL]
set -u
src=${1:-$(cd "$(dirname "$0")/../.." && pwd)}
job=$src/tools/cluster/rondel.slurm
failures=0
check() {  # NAME CONDITION...
  local name=$1
  shift
  if "$@"; then echo "PASS $name"; else echo "FAIL $name"; failures=$((failures + 1)); fi
}

for f in "$src"/tools/cluster/*; do check "bash -n $(basename "$f")" bash -n "$f"; done
check "the job asks for SIGUSR1 300 s before its limit" grep -q '^#SBATCH --signal=B:USR1@300$' "$job"

work=$(mktemp -d "${TMPDIR:-/tmp}/rondel-cluster-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin"
# srun and mpirun run the command in place (exec: a signal to the launcher reaches the "rank").
printf '#!/bin/bash\nexec "$@"\n' > "$work/bin/srun"
printf '#!/bin/bash\nexec "$@"\n' > "$work/bin/mpirun"
# sbatch records the job's place in the chain and its arguments.
printf '#!/bin/bash\necho "RONDEL_JOB=$RONDEL_JOB $*" >> "$SLURM_SUBMIT_DIR/sbatch.log"\n' > "$work/bin/sbatch"
# rondel: records its arguments; FAKE_MODE says how it ends (summary.json as the real one writes it).
cat > "$work/bin/rondel" << 'FAKE'
#!/bin/bash
echo "$*" >> "$FAKE_LOG"
out=$FAKE_OUT
mkdir -p "$out"
summary() { printf '{\n  "status": "%s",\n  "steps": 10\n}\n' "$1" > "$out/summary.json"; }
stop() { touch "$out/checkpoint_0000000010.h5"; summary stopped; exit "${1:-10}"; }
case $FAKE_MODE in
  stop) stop 10 ;;
  stop-mpirun) stop 1 ;;  # the ranks exit 10, mpirun says 1
  complete) summary complete; exit 0 ;;
  fail) exit 1 ;;
  signal) trap 'stop 10' USR1; touch "$out/trap-set"; for _ in $(seq 200); do sleep 0.05; done; exit 7 ;;
  hang)  # checkpoints and says "stopped" on SIGUSR1, then never ends (the launcher fault of Open MPI)
    trap 'touch "$out/checkpoint_0000000010.h5"; summary stopped; touch "$out/stopped"' USR1
    touch "$out/trap-set"
    while :; do sleep 0.05; done ;;
esac
FAKE
chmod +x "$work/bin/"*

# Runs the job script in DIR (made if needed) with the fake rank in MODE and more environment assignments;
# the job's output in DIR/job.out (appended). Sets rc.
job_in() {
  local dir=$1 mode=$2
  shift 2
  mkdir -p "$dir"
  (cd "$dir" && exec env -u RONDEL_JOB -u RONDEL_MAX_JOBS PATH="$work/bin:$PATH" RONDEL="$work/bin/rondel" \
     RONDEL_SCRIPT="$job" FAKE_MODE="$mode" FAKE_LOG="$dir/rondel.log" FAKE_OUT="$dir/out" SLURM_SUBMIT_DIR="$dir" \
     "$@" bash "$job" in.ini out --run.steps=20 >> "$dir/job.out" 2>&1)
  rc=$?
}
run_case() {  # MODE [assignments...]: in a fresh directory
  case_dir=$work/case-$1-$RANDOM
  job_in "$case_dir" "$@"
}
sbatched() { [ -f "$case_dir/sbatch.log" ] && grep -q "$1" "$case_dir/sbatch.log"; }
no_sbatch() { [ ! -f "$case_dir/sbatch.log" ]; }
ran_with() { grep -q -- "$1" "$case_dir/rondel.log"; }
eq() { [ "$1" = "$2" ]; }

run_case stop
check "exit 10: the job ends well" eq "$rc" 0
check "exit 10: the first job ran the INI into the output" ran_with "^in.ini --run.output=out --run.steps=20$"
check "exit 10: job 2 is submitted with the same arguments" sbatched "^RONDEL_JOB=2 --export=ALL $job in.ini out --run.steps=20$"

# The follow-up job: the output holds a checkpoint now, so it resumes.
job_in "$case_dir" complete RONDEL_JOB=2
check "the follow-up job resumes" ran_with "^--resume out --run.steps=20$"
check "the follow-up job ends the chain when complete" eq "$rc" 0
check "the follow-up job submits nothing more" eq "$(wc -l < "$case_dir/sbatch.log")" 1

run_case stop-mpirun RONDEL_LAUNCH=mpirun
check "mpirun's 1 with summary.json 'stopped': resubmitted" sbatched "^RONDEL_JOB=2 "

run_case complete
check "exit 0: done" eq "$rc" 0
check "exit 0: nothing submitted" no_sbatch
check "exit 0: rondel did run" ran_with "^in.ini --run.output=out"

# A failed run beside an older summary.json that says "stopped" (from an earlier job): not resubmitted.
case_dir=$work/stale
mkdir -p "$case_dir/out"
printf '{\n  "status": "stopped"\n}\n' > "$case_dir/out/summary.json"
touch -d '2000-01-01' "$case_dir/out/summary.json"
job_in "$case_dir" fail
check "a failure stops the chain with rondel's code" eq "$rc" 1
check "a failure beside an old 'stopped' summary submits nothing" no_sbatch
check "a failure beside an old summary: rondel did run" ran_with "^in.ini --run.output=out"
check "a failure is reported" grep -q "the chain stops" "$case_dir/job.out"

# SIGUSR1 to the batch shell (what --signal=B:USR1@300 does) reaches the rank, which checkpoints and stops.
case_dir=$work/signal
mkdir -p "$case_dir"
(cd "$case_dir" && exec env -u RONDEL_JOB PATH="$work/bin:$PATH" RONDEL="$work/bin/rondel" RONDEL_SCRIPT="$job" \
   FAKE_MODE=signal FAKE_LOG="$case_dir/rondel.log" FAKE_OUT="$case_dir/out" SLURM_SUBMIT_DIR="$case_dir" \
   bash "$job" in.ini out > "$case_dir/job.out" 2>&1) &
shell=$!  # the batch shell itself (exec)
# Signal only once the fake rank has set its trap (before that, SIGUSR1 would kill it: exit 138). Polling a
# marker rather than sleeping a fixed time: on a loaded machine the rank can take longer than any guess.
for _ in $(seq 400); do [ -f "$case_dir/out/trap-set" ] && break; sleep 0.05; done
kill -USR1 "$shell"
wait "$shell"
rc=$?
check "SIGUSR1: the job ends well" eq "$rc" 0
check "SIGUSR1: forwarded to the rank" grep -q "SIGUSR1" "$case_dir/job.out"
check "SIGUSR1: the rank's exit 10 is seen" grep -q "rondel exited with 10" "$case_dir/job.out"
check "SIGUSR1: job 2 is submitted" sbatched "^RONDEL_JOB=2 "

# A launcher that never ends after SIGUSR1: killed after RONDEL_STOP_GRACE, and summary.json decides.
case_dir=$work/hang
mkdir -p "$case_dir"
(cd "$case_dir" && exec env -u RONDEL_JOB PATH="$work/bin:$PATH" RONDEL="$work/bin/rondel" RONDEL_SCRIPT="$job" \
   FAKE_MODE=hang FAKE_LOG="$case_dir/rondel.log" FAKE_OUT="$case_dir/out" SLURM_SUBMIT_DIR="$case_dir" \
   RONDEL_STOP_GRACE=1 bash "$job" in.ini out > "$case_dir/job.out" 2>&1) &
shell=$!
for _ in $(seq 400); do [ -f "$case_dir/out/trap-set" ] && break; sleep 0.05; done
kill -USR1 "$shell"
for _ in $(seq 400); do kill -0 "$shell" 2> /dev/null || break; sleep 0.05; done  # at most 20 s, not forever
kill -0 "$shell" 2> /dev/null && kill -KILL "$shell"
wait "$shell"
rc=$?
check "a launcher that hangs after SIGUSR1: the job ends well" eq "$rc" 0
check "a launcher that hangs: killed after RONDEL_STOP_GRACE" grep -q "still runs 1 s after SIGUSR1" "$case_dir/job.out"
check "a launcher that hangs: summary.json 'stopped' resubmits" sbatched "^RONDEL_JOB=2 "

run_case stop RONDEL_JOB=3 RONDEL_MAX_JOBS=3
check "at RONDEL_MAX_JOBS: exit 10" eq "$rc" 10
check "at RONDEL_MAX_JOBS: nothing submitted" no_sbatch
check "at RONDEL_MAX_JOBS: it says how to continue" grep -q "continue with: sbatch" "$case_dir/job.out"

run_case complete RONDEL_LAUNCH=aprun
check "an unknown RONDEL_LAUNCH is refused" eq "$rc" 2
check "an unknown RONDEL_LAUNCH is named" grep -q "RONDEL_LAUNCH = 'aprun'" "$case_dir/job.out"

# With the real rondel and the real mpirun (when given and installed): SIGUSR1 to the batch shell reaches
# the ranks through mpirun, they write a checkpoint and stop, the follow-up is submitted, and a follow-up job
# resumes from the checkpoint to the end.
real=${2:-}
if [ -n "$real" ] && command -v mpirun > /dev/null; then
  mkdir -p "$work/sbatch-only"
  cp "$work/bin/sbatch" "$work/sbatch-only/"
  case_dir=$work/real
  mkdir -p "$case_dir"
  cp "$src/inputs/deposition.ini" "$case_dir/in.ini"
  real_env=(env -u RONDEL_JOB PATH="$work/sbatch-only:$PATH" RONDEL="$real" RONDEL_SCRIPT="$job" RONDEL_LAUNCH=mpirun
    SLURM_SUBMIT_DIR="$case_dir" OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)
  quiet=(--run.progress=false --output.thermo_every=0)
  (cd "$case_dir" && exec "${real_env[@]}" bash "$job" in.ini out --run.steps=400000 "${quiet[@]}" >> job.out 2>&1) &
  shell=$!  # the batch shell itself (exec)
  for _ in $(seq 600); do [ -f "$case_dir/out/diagnostics.csv" ] && [ "$(wc -l < "$case_dir/out/diagnostics.csv")" -ge 3 ] && break; sleep 0.05; done
  kill -USR1 "$shell"
  wait "$shell"
  rc=$?
  check "real run: the job ends well after SIGUSR1" eq "$rc" 0
  check "real run: summary.json says stopped" grep -q '"status": "stopped"' "$case_dir/out/summary.json"
  check "real run: job 2 is submitted" sbatched "^RONDEL_JOB=2 "
  last=$(ls "$case_dir"/out/checkpoint_*.h5 2> /dev/null | tail -n 1)
  step=$(basename "$last" .h5 | sed 's/^checkpoint_0*//')
  check "real run: a checkpoint was written" test -n "$step"
  # The follow-up job gets SIGUSR1 while it reads the checkpoint (held there by RONDEL_FAULT=setup_pause): it
  # stops before writing anything, with 10, and job 3 is submitted.
  before=$(cd "$case_dir/out" && ls -l --time-style=+%s.%N | md5sum)
  (cd "$case_dir" && exec "${real_env[@]}" RONDEL_JOB=2 RONDEL_FAULT=setup_pause bash "$job" in.ini out \
     --run.steps=$((step + 100)) "${quiet[@]}" >> job.out 2>&1) &
  shell=$!
  for _ in $(seq 600); do grep -q "set-up paused" "$case_dir/job.out" && break; sleep 0.05; done
  kill -USR1 "$shell"
  wait "$shell"
  rc=$?
  check "real run: SIGUSR1 in the follow-up's set-up: the job ends well" eq "$rc" 0
  check "real run: the set-up stopped before writing" grep -q "stopped by SIGUSR1 during set-up" "$case_dir/job.out"
  check "real run: the set-up's stop exits 10" grep -q "rondel exited with 10" "$case_dir/job.out"
  check "real run: job 3 is submitted" sbatched "^RONDEL_JOB=3 "
  check "real run: the directory is as it was" eq "$before" "$(cd "$case_dir/out" && ls -l --time-style=+%s.%N | md5sum)"
  (cd "$case_dir" && exec "${real_env[@]}" RONDEL_JOB=3 bash "$job" in.ini out --run.steps=$((step + 100)) \
     "${quiet[@]}" >> job.out 2>&1)
  rc=$?
  check "real run: the follow-up job resumes and completes" eq "$rc" 0
  check "real run: the follow-up resumed at the checkpoint" grep -q "resumed at step $step" "$case_dir/out/log.txt"
  check "real run: summary.json says complete" grep -q '"status": "complete"' "$case_dir/out/summary.json"
fi

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed; the job outputs:"
  for f in "$work"/*/job.out; do echo "== $f"; cat "$f"; done
  exit 1
fi
echo "all checks passed"
