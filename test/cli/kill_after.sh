# Sourced by the kill-and-resume tests. kill_after PATTERN LOG CMD...: runs CMD with its stderr in
# LOG, waits (at most 60 s) until LOG holds PATTERN (a grep -E expression), then kills it with
# SIGKILL (its child processes too: mpirun's ranks) and reaps it; returns 1 if PATTERN never came. The EXIT trap of the caller kills a
# process left running (kill_pid).
kill_pid=0
kill_after() {
  local pattern=$1 log=$2; shift 2
  "$@" 2> "$log" > /dev/null &
  kill_pid=$!
  for _ in $(seq 1 1200); do
    grep -Eq "$pattern" "$log" 2>/dev/null && break
    sleep 0.05
  done
  # its children first (mpirun's ranks: a SIGKILLed mpirun cannot take them down), then itself
  pkill -9 -P $kill_pid 2>/dev/null
  kill -9 $kill_pid 2>/dev/null; wait $kill_pid 2>/dev/null; kill_pid=0  # reaped: the trap must not signal a reused pid
  grep -Eq "$pattern" "$log"
}
