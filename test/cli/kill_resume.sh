#!/usr/bin/env bash
# Training killed with SIGKILL after the first of three parameters has finished, then restarted,
# gives an artifacts.h5 whose snapshots equal an uninterrupted run's bit for bit (h5diff with no
# tolerance), and the restart reuses the finished parameter. The same on 2 ranks in rank groups of
# one rank (training.groupSize: 1): killed after the first round (parameters 1 and 2, one per
# group) was stored, the restart reuses both and integrates parameter 3 only.
# usage: kill_resume.sh GPHR MPIEXEC
set -u
gphr=$1; mpiexec=$2
. "$(dirname "$0")/kill_after.sh"
work=$(mktemp -d); trap '[ $kill_pid -gt 0 ] && kill -9 $kill_pid 2>/dev/null; rm -rf "$work"' EXIT
cat > "$work/c.yaml" <<'YAML'
gphr:
  scene: {name: nls1d, n: 384}
  time: {T: 12.0, dt: 0.01}
  training: {values: [0.9, 1.0, 1.1], snapshotEvery: 4}
  reduction: {k: 8}
  pipeline: {rom: true}
  output: {plots: false, progressSeconds: 0.0}
YAML
fail() { echo "FAIL: $*"; for f in "$work"/*.err; do echo "--- $f"; cat "$f"; done; exit 1; }
# 1. Start, wait for parameter 1 to be reported complete, kill -9.
kill_after "parameter 1/3 .* done" "$work/first.err" "$gphr" run "$work/c.yaml" --output "$work/killed" \
  || fail "parameter 1 never finished"
grep -q "parameter 2/3" "$work/first.err" && fail "killed too late: parameter 2 had finished"
[ -f "$work/killed/summary.json" ] && fail "a killed run left summary.json"
# 2. Restart: parameter 1 is reused, the run completes.
"$gphr" run "$work/c.yaml" --output "$work/killed" 2> "$work/second.err" > /dev/null || fail "restart failed"
grep -q "parameter 1/3 (0.9) reused from file" "$work/second.err" || fail "restart did not reuse parameter 1"
grep -q "parameter 2/3 (1) done" "$work/second.err" || fail "restart did not compute parameter 2"
# 3. Uninterrupted run; snapshots must be identical.
"$gphr" run "$work/c.yaml" --output "$work/clean" 2> "$work/clean.err" > /dev/null || fail "clean run failed"
for p in p0 p1 p2; do
  h5diff "$work/killed/artifacts.h5" "$work/clean/artifacts.h5" /training/$p /training/$p > "$work/diff.txt" 2>&1 \
    || { cat "$work/diff.txt"; fail "snapshots /training/$p differ"; }
done
h5diff "$work/killed/artifacts.h5" "$work/clean/artifacts.h5" /basis /basis > /dev/null || fail "bases differ"
# 4. Two rank groups of one rank: killed after the first round, restarted, equal to an uninterrupted
# grouped run bit for bit (each parameter integrated on one rank, the same arithmetic every time).
sed 's/snapshotEvery: 4}/snapshotEvery: 4, groupSize: 1}/' "$work/c.yaml" > "$work/g.yaml"
np2=("$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$gphr" run "$work/g.yaml")
kill_after "parameter 2/3 .* done" "$work/g_first.err" "${np2[@]}" --output "$work/g_killed" \
  || fail "the grouped training never finished its first round"
grep -q "parameter 3/3" "$work/g_first.err" && fail "killed too late: the second round had finished"
"${np2[@]}" --output "$work/g_killed" 2> "$work/g_second.err" > /dev/null || fail "grouped restart failed"
grep -q "parameter 1/3 (0.9) reused from file" "$work/g_second.err" || fail "grouped restart did not reuse parameter 1"
grep -q "parameter 2/3 (1) reused from file" "$work/g_second.err" || fail "grouped restart did not reuse parameter 2"
grep -q "parameter 3/3 (1.1) done" "$work/g_second.err" || fail "grouped restart did not compute parameter 3"
grep -q "2 groups of 1 rank" "$work/g_second.err" || fail "the training did not run in two groups"
"${np2[@]}" --output "$work/g_clean" 2> "$work/g_clean.err" > /dev/null || fail "grouped clean run failed"
for p in p0 p1 p2; do
  h5diff "$work/g_killed/artifacts.h5" "$work/g_clean/artifacts.h5" /training/$p /training/$p > "$work/diff.txt" 2>&1 \
    || { cat "$work/diff.txt"; fail "grouped snapshots /training/$p differ"; }
done
echo "ok: killed after parameter 1 (1 rank) and after the first round of two rank groups, resumed, snapshots bit-for-bit equal"
