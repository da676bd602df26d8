#!/usr/bin/env bash
# The two long POD stages of `gphr build` resume after SIGKILL (packages/offline/PodCheckpoint.hpp):
# killed in the basis stage after its 2nd of 5 parameters, restarted and killed again in the DEIM
# basis stage after its 5th of 48 chunks, then restarted to the end. Each restart reuses what the
# progress lines before the kill said was done (and does not redo it); the basis, the DEIM basis
# and their singular values equal an uninterrupted run's bit for bit; no checkpoint is left. A
# damaged checkpoint file is said and the stage computed afresh; a leftover one beside results read
# from the cache is removed. With the default interval (output.checkpointSeconds: 60) a stage of
# seconds writes none.
# usage: offline_resume.sh GPHR
set -u
gphr=$1
. "$(dirname "$0")/kill_after.sh"
work=$(mktemp -d); trap '[ $kill_pid -gt 0 ] && kill -9 $kill_pid 2>/dev/null; rm -rf "$work"' EXIT
cat > "$work/c.yaml" <<'YAML'
gphr:
  scene: {name: nls1d, n: 1024}
  time: {T: 4.0, dt: 0.01}
  training: {values: [0.9, 0.95, 1.0, 1.05, 1.1], snapshotEvery: 1}
  reduction: {k: 20}
  pipeline: {methods: [gp-deim], m: [40]}
  hyper: {snapshotEvery: 2, chunkSnapshots: 21}
  output: {progressSeconds: 0.0, checkpointSeconds: 0.0}
YAML
# The uninterrupted run below keeps the default interval (60 s): this small build writes no checkpoint.
sed 's/, checkpointSeconds: 0.0//' "$work/c.yaml" > "$work/default.yaml"
export OPENBLAS_NUM_THREADS=1
fail() { echo "FAIL: $*"; for f in "$work"/*.err; do echo "--- $f"; tail -12 "$f"; done; exit 1; }
args=("$work/c.yaml" --model "$work/m.h5")
# 1. Killed in the basis stage.
kill_after "basis: parameter 2 of 5 POD'd, [0-9.]* s, checkpointed" "$work/first.err" "$gphr" build "${args[@]}" --output "$work/killed" || fail "the basis never reached parameter 2 of 5"
grep -q "basis: parameter 4 of 5" "$work/first.err" && fail "killed too late: the basis had gone on"
[ -f "$work/killed/artifacts.h5.ckpt_basis" ] || fail "no checkpoint file of the basis"
# 2. Restarted, killed in the DEIM basis stage.
kill_after "chunk 5 of 48 POD'd, [0-9.]* s, checkpointed" "$work/second.err" "$gphr" build "${args[@]}" --output "$work/killed" \
  || fail "the DEIM basis never reached chunk 5 of 48"
grep -q "basis: parameters 1-2 of 5 reused from file" "$work/second.err" || fail "the basis did not resume after parameter 2"
grep -q "basis: parameter [12] of 5 POD'd" "$work/second.err" && fail "the basis POD'd parameter 1 or 2 again"
grep -q "deim basis k = 20:" "$work/second.err" && fail "killed too late: the DEIM basis had finished"
[ -f "$work/killed/artifacts.h5.ckpt_basis" ] && fail "the basis's checkpoint file outlived it"
[ -f "$work/killed/artifacts.h5.ckpt_deim_k20" ] || fail "no checkpoint file of the DEIM basis"
# A damaged checkpoint file (a copy of the run, the file overwritten): said, and computed afresh.
cp -r "$work/killed" "$work/damaged"
head -c 4096 /dev/urandom > "$work/damaged/artifacts.h5.ckpt_deim_k20"
"$gphr" build "$work/c.yaml" --model "$work/d.h5" --output "$work/damaged" 2> "$work/damaged.err" > /dev/null \
  || fail "a damaged checkpoint file stopped the run"
grep -q "deim_k20' is unreadable or damaged .*: computed afresh" "$work/damaged.err" || fail "the damaged checkpoint was not said"
grep -q "chunk 1 of 48 POD'd" "$work/damaged.err" || fail "the DEIM basis did not start afresh"
# 3. Restarted to the end.
"$gphr" build "${args[@]}" --output "$work/killed" 2> "$work/third.err" > /dev/null || fail "the last restart failed"
grep -q "deim basis: chunks 1-5 of 48 reused from file" "$work/third.err" || fail "the DEIM basis did not resume after chunk 5"
grep -q "chunk [1-5] of 48 POD'd" "$work/third.err" && fail "the DEIM basis POD'd a chunk of the first five again"
ls "$work/killed" | grep -q "ckpt" && fail "checkpoint files outlived the bases"
# A leftover checkpoint file beside results read from the cache goes.
echo leftover > "$work/killed/artifacts.h5.ckpt_basis"; echo leftover > "$work/killed/artifacts.h5.ckpt_deim_k20"
"$gphr" build "${args[@]}" --output "$work/killed" 2> "$work/cached.err" > /dev/null || fail "the cached rerun failed"
ls "$work/killed" | grep -q "ckpt" && fail "leftover checkpoint files stayed beside cached results"
# 4. An uninterrupted run: the same bases and singular values, bit for bit.
"$gphr" build "$work/default.yaml" --model "$work/m.h5" --output "$work/clean" 2> "$work/clean.err" > /dev/null \
  || fail "the uninterrupted run failed"
grep -q "POD'd" "$work/clean.err" || fail "the uninterrupted run printed no progress lines"
grep -q "checkpointed" "$work/clean.err" && fail "the default interval (60 s) wrote a checkpoint of a seconds-long stage"
for d in /basis /deim/k20; do
  h5diff --exclude-attribute $d "$work/damaged/artifacts.h5" "$work/clean/artifacts.h5" $d $d > /dev/null 2>&1 \
    || fail "$d differs after a damaged checkpoint"
  h5diff --exclude-attribute $d "$work/killed/artifacts.h5" "$work/clean/artifacts.h5" $d $d > "$work/diff.txt" 2>&1 \
    || { head -20 "$work/diff.txt"; fail "$d differs"; }
  for f in killed clean; do
    h5dump -m %.17g -a $d/singularValues "$work/$f/artifacts.h5" | grep -v HDF5 > "$work/$f.sigma"
  done
  [ "$(grep -c ',' "$work/clean.sigma")" -gt 0 ] || fail "no singular values of $d read"
  cmp -s "$work/killed.sigma" "$work/clean.sigma" || { diff "$work/killed.sigma" "$work/clean.sigma" | head; fail "$d's singular values differ"; }
done
echo "ok: killed after basis parameter 2 of 5 and DEIM chunk 5 of 48, resumed both, bases bit-for-bit equal"
