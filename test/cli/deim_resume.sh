#!/usr/bin/env bash
# The DEIM basis stage killed with SIGKILL mid-way (after its 5th of 51 chunks), then restarted,
# goes on from the root's last checkpoint (packages/offline/src/DeimBasisStage.cpp) instead of
# chunk 1, and gives the basis and singular values of an uninterrupted run bit for bit; the
# checkpoints are gone once the basis is written.
# usage: deim_resume.sh GPHR
set -u
gphr=$1
. "$(dirname "$0")/kill_after.sh"
work=$(mktemp -d); trap '[ $kill_pid -gt 0 ] && kill -9 $kill_pid 2>/dev/null; rm -rf "$work"' EXIT
cat > "$work/c.yaml" <<'YAML'
gphr:
  scene: {name: nls1d, n: 1024}
  time: {T: 4.0, dt: 0.01}
  training: {values: [0.9, 1.1], snapshotEvery: 1}
  reduction: {k: 20}
  pipeline: {methods: [gp-deim], m: [40]}
  hyper: {chunkSnapshots: 16}
  output: {progressSeconds: 0.0}
YAML
export OPENBLAS_NUM_THREADS=1
fail() { echo "FAIL: $*"; for f in "$work"/*.err; do echo "--- $f"; tail -20 "$f"; done; exit 1; }
# 1. Start, wait for the 5th chunk, kill -9.
kill_after "chunk 5 of 51 POD'd" "$work/first.err" "$gphr" build "$work/c.yaml" --model "$work/k.h5" \
  --output "$work/killed" || fail "the DEIM basis never reached chunk 5 of 51"
grep -q "deim basis k = 20:" "$work/first.err" && fail "killed too late: the DEIM basis had finished"
h5ls "$work/killed/artifacts.h5/deim" | grep -q "k20_root" || fail "no root checkpoint in the killed run's artifacts.h5"
# 2. Restart: the chunks of the last checkpoint are reused, chunk 1 is not POD'd again.
"$gphr" build "$work/c.yaml" --model "$work/k.h5" --output "$work/killed" 2> "$work/second.err" > /dev/null \
  || fail "restart failed"
grep -Eq "deim basis: chunks 1-[1-5] of 51 reused from file" "$work/second.err" \
  || fail "restart did not reuse the chunks before the kill"
grep -q "chunk 1 of 51 POD'd" "$work/second.err" && fail "restart POD'd chunk 1 again"
grep -q "chunk 51 of 51 POD'd" "$work/second.err" || fail "restart did not finish the chunks"
h5ls "$work/killed/artifacts.h5/deim" | grep -q "_root" && fail "the checkpoints outlived the basis"
# 3. An uninterrupted run: the same basis and singular values, bit for bit.
"$gphr" build "$work/c.yaml" --model "$work/c.h5" --output "$work/clean" 2> "$work/clean.err" > /dev/null \
  || fail "clean run failed"
h5diff --exclude-attribute /deim/k20 "$work/killed/artifacts.h5" "$work/clean/artifacts.h5" /deim/k20 /deim/k20 \
  > "$work/diff.txt" 2>&1 || { head -20 "$work/diff.txt"; fail "the DEIM bases differ"; }
for f in killed clean; do
  h5dump -m %.17g -a /deim/k20/singularValues "$work/$f/artifacts.h5" | grep -v HDF5 > "$work/$f.sigma"
done
[ "$(grep -c ',' "$work/clean.sigma")" -gt 0 ] || fail "no singular values read"
cmp -s "$work/killed.sigma" "$work/clean.sigma" || { diff "$work/killed.sigma" "$work/clean.sigma" | head; fail "singular values differ"; }
echo "ok: killed after chunk 5 of 51, $(grep -o 'chunks 1-[0-9]* of 51 reused' "$work/second.err"), basis bit-for-bit equal"
