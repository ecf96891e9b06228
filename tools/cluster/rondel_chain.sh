# The logic of tools/cluster/rondel.slurm (sourced by it): start the ranks, pass SIGUSR1 on to them, read
# how the run ended, and submit the follow-up job when it stopped after a checkpoint. Kept apart from the
# job script so that tests/tools/test_cluster_scripts.sh can run it with a fake srun, mpirun and sbatch.

# How the run ended: rondel's exit code and the "status" of OUTPUT_DIR/summary.json ("complete" or
# "stopped"; empty when there is no summary.json written by this job). Open MPI's mpirun may return 1 rather
# than the ranks' 10 after a signal, so the status in the directory decides when the two disagree.
rondel_status() {  # OUTPUT_DIR MARKER_FILE
  local summary=$1/summary.json
  [ -f "$summary" ] && [ "$summary" -nt "$2" ] || return 0
  sed -n 's/^ *"status": *"\([a-z]*\)".*/\1/p' "$summary" | head -n 1
}

# Waits for the launcher (pid $1) and sets RONDEL_RC to its exit status (in this shell: a command
# substitution would run in a subshell, whose wait knows no such child). A trap that runs while the shell
# waits ends the wait early (status above 128), so it waits again while the launcher lives.
rondel_wait() {
  local pid=$1
  wait "$pid"
  RONDEL_RC=$?
  while [ "$RONDEL_RC" -gt 128 ] && kill -0 "$pid" 2> /dev/null; do
    wait "$pid"
    RONDEL_RC=$?
  done
  if [ "$RONDEL_RC" -gt 128 ]; then  # the launcher ended while the trap ran: its status may still be there
    wait "$pid" 2> /dev/null
    local late=$?
    [ "$late" -ne 127 ] && RONDEL_RC=$late
  fi
  return 0
}

# Starts the ranks (RONDEL_LAUNCH: srun or mpirun) in the background and waits for them; sets RONDEL_RC. A
# SIGUSR1 to this shell goes on to the launcher: srun passes it to every task, Open MPI's mpirun to every rank
# (SIGUSR1 and SIGUSR2 only: a SIGTERM or SIGINT makes mpirun end the ranks itself). The trap is set before
# the launch, so that a signal in between is not lost (the shell would die of it without one).
#
# A launcher that does not end within RONDEL_STOP_GRACE seconds (default 240, inside the 300 s of warning)
# after the signal is killed: Open MPI's mpirun was seen to hang after a signal early in the ranks' start-up
# (2 of 11 trials, the ranks long gone). The exit code and summary.json then decide as always.
rondel_launch() {  # EXECUTABLE ARGS...
  RONDEL_PID=
  RONDEL_SIGNALLED=0
  RONDEL_WATCHDOG=
  trap 'echo "rondel chain: SIGUSR1 (the time limit is near): the ranks write a checkpoint and stop"
        RONDEL_SIGNALLED=1; [ -n "$RONDEL_PID" ] && kill -USR1 "$RONDEL_PID" 2> /dev/null && rondel_watchdog' USR1
  case ${RONDEL_LAUNCH:-srun} in
    srun) srun "$@" & ;;
    mpirun) mpirun "$@" & ;;
    *)
      echo "rondel chain: RONDEL_LAUNCH = '$RONDEL_LAUNCH': use srun or mpirun" >&2
      trap - USR1
      RONDEL_RC=2
      return 0
      ;;
  esac
  RONDEL_PID=$!
  [ "$RONDEL_SIGNALLED" -eq 1 ] && kill -USR1 "$RONDEL_PID" 2> /dev/null && rondel_watchdog
  rondel_wait "$RONDEL_PID"
  trap - USR1
  if [ -n "$RONDEL_WATCHDOG" ]; then  # its sleep first (a killed subshell leaves its child running)
    pkill -P "$RONDEL_WATCHDOG" 2> /dev/null
    kill "$RONDEL_WATCHDOG" 2> /dev/null
  fi
  return 0
}

# Kills the launcher if it still runs RONDEL_STOP_GRACE seconds from now (once per launch).
rondel_watchdog() {
  [ -n "$RONDEL_WATCHDOG" ] && return 0
  local grace=${RONDEL_STOP_GRACE:-240} pid=$RONDEL_PID
  (
    sleep "$grace"
    if kill -0 "$pid" 2> /dev/null; then
      echo "rondel chain: the launcher still runs $grace s after SIGUSR1 (RONDEL_STOP_GRACE): killed; summary.json decides"
      kill -KILL "$pid" 2> /dev/null
    fi
  ) &
  RONDEL_WATCHDOG=$!
}

rondel_chain() {  # INPUT.ini OUTPUT_DIR [overrides...]
  local ini=$1 out=$2
  shift 2
  local here=${SLURM_SUBMIT_DIR:-$PWD}
  local exe=${RONDEL:-$here/build/rondel}
  local job=${RONDEL_JOB:-1} max=${RONDEL_MAX_JOBS:-20}
  local args
  if compgen -G "$out/checkpoint_*.h5" > /dev/null; then
    args=(--resume "$out" "$@")  # the configuration stored in the checkpoint, and the same overrides
  else
    args=("$ini" "--run.output=$out" "$@")
  fi
  echo "rondel chain: job $job of at most $max (${SLURM_JOB_ID:-no job id}): ${RONDEL_LAUNCH:-srun} $exe ${args[*]}"
  local marker rc status
  marker=$(mktemp "${TMPDIR:-/tmp}/rondel-chain.XXXXXX") || return 1
  rondel_launch "$exe" "${args[@]}"
  rc=$RONDEL_RC
  status=$(rondel_status "$out" "$marker")
  rm -f "$marker"
  echo "rondel chain: rondel exited with $rc${status:+, $out/summary.json says '$status'}"
  if [ "$rc" -eq 0 ] && [ "$status" != stopped ]; then
    echo "rondel chain: the run is complete; results in $out"
    return 0
  fi
  if [ "$rc" -ne 10 ] && [ "$status" != stopped ]; then
    echo "rondel chain: rondel failed (exit code $rc; README \"Exit codes\"); the chain stops. See the message above and $out/log.txt" >&2
    return "$rc"
  fi
  rondel_resubmit "$job" "$max" "$ini" "$out" "$@"
}

# The run stopped after a checkpoint: the follow-up job, unless the chain is at RONDEL_MAX_JOBS.
rondel_resubmit() {  # JOB MAX INPUT.ini OUTPUT_DIR [overrides...]
  local job=$1 max=$2
  shift 2
  if [ "$job" -ge "$max" ]; then
    echo "rondel chain: stopped after a checkpoint, but this is job $max of RONDEL_MAX_JOBS = $max: not resubmitted; continue with: sbatch $RONDEL_SCRIPT $*" >&2
    return 10
  fi
  local next=$((job + 1))
  # shellcheck disable=SC2086  # RONDEL_SBATCH_ARGS holds several options
  if RONDEL_JOB=$next sbatch --export=ALL ${RONDEL_SBATCH_ARGS:-} "$RONDEL_SCRIPT" "$@"; then
    echo "rondel chain: stopped after a checkpoint; job $next submitted to resume it"
    return 0
  fi
  echo "rondel chain: sbatch failed; continue by hand with: sbatch $RONDEL_SCRIPT $*" >&2
  return 10
}
