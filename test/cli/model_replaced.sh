#!/usr/bin/env bash
# A query never mixes two model files. `gphr query` with setup: exact reads the file's basis at
# every query; here the model file is replaced while the queries run, the way gphr build writes it
# (a new file renamed over the path), and then rewritten in place (same inode). Either the results
# equal those of the file the query opened -- every dataset of results.h5, bit for bit, keyed by
# that file's checksum -- or the run ends with exit 2 and one line naming the file. Before: 962 of
# 1,500 queries mixed the old file's data with the new file's basis, exit 0, status ok.
# usage: model_replaced.sh GPHR
set -u
gphr=$1
work=$(mktemp -d)
pid=0
trap '[ $pid -ne 0 ] && kill -9 $pid 2>/dev/null; rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
# Two models of one scene, k and m whose data differ (3 training points against 2).
for points in 3 2; do
  cat > b$points.yaml <<YAML
gphr:
  scene: {name: nls1d, n: 128}
  time: {T: 0.5, dt: 0.01}
  training: {points: [$points]}
  pipeline: {methods: [gp-deim], k: [6], m: [12]}
  hyper: {snapshotEvery: 5}
  build: {withBasis: true}
YAML
  "$gphr" build b$points.yaml --model m$points.h5 --output art$points > /dev/null 2> build.err || fail "build: $(cat build.err)"
done
python3 - <<'PY' > q.yaml
print("queries:\n  defaults: {method: gp-deim, k: 6, m: 12, setup: exact, T: 0.5, dt: 0.01}\n  grid:\n    eps: [0.9, 1.1, 400]")
PY
"$gphr" query m3.h5 q.yaml --output ref --threads 1 > /dev/null 2> ref.err || fail "reference query: $(cat ref.err)"
"$gphr" query m2.h5 q.yaml --output other --threads 1 > /dev/null 2> other.err || fail "other query: $(cat other.err)"

# same DIR A B: results.h5 of A and B hold the same datasets, bit for bit.
same() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys, h5py, numpy as np
a, b = (h5py.File(p + "/results.h5", "r") for p in sys.argv[1:3])
for name in a["queries"]:
    for ds in a["queries"][name]:
        if not np.array_equal(a["queries"][name][ds][()], b["queries"][name][ds][()]):
            sys.exit(1)
PY
}
same ref other && fail "the two model files give the same results: the test cannot tell them apart"

# replace DIR HOW: a query of model.h5 (a copy of m3.h5) into DIR, the file replaced by HOW once
# three queries are done, while the others still run.
replace() {
  local dir=$1 how=$2
  cp m3.h5 model.h5
  "$gphr" query model.h5 q.yaml --output "$dir" --threads 1 > "$dir.out" 2> "$dir.err" &
  pid=$!
  for _ in $(seq 1 1500); do [ "$(ls "$dir"/queries/*.h5 2>/dev/null | wc -l)" -ge 3 ] && break; sleep 0.02; done
  local done_before
  done_before=$(ls "$dir"/queries/*.h5 2>/dev/null | wc -l)
  [ "$done_before" -ge 3 ] || fail "$how: no query finished in 30 s"
  [ "$done_before" -lt 400 ] || fail "$how: every query had finished before the file was replaced"
  $how
  wait $pid; local rc=$?; pid=0
  if [ $rc -eq 0 ]; then
    same ref "$dir" || fail "$how: exit 0 with results that are not the opened file's"
    echo "ok ($how): results equal the opened file's ($done_before queries done at the replacement)"
  elif [ $rc -eq 2 ]; then
    [ "$(grep -c '^gphr' "$dir.err")" -eq 1 ] || fail "$how: exit 2 without one error line: $(cat "$dir.err")"
    grep -q "^gphr: error: reduced-model file 'model.h5'" "$dir.err" || fail "$how: the error does not name the file: $(cat "$dir.err")"
    echo "ok ($how): exit 2: $(grep '^gphr' "$dir.err")"
  else
    fail "$how: exit $rc: $(cat "$dir.err")"
  fi
}
renamed() { cp m2.h5 model.h5.new && mv model.h5.new model.h5; }  # as gphr build replaces a file
rewritten() { cat m2.h5 > model.h5; }                            # the same inode, new bytes
replace renamed renamed
# the opened file's results stand; a resume over them against the new file redoes every query
"$gphr" query model.h5 q.yaml --output renamed --threads 1 > resume.out 2> resume.err || fail "resume: $(cat resume.err)"
grep -q "(0 run, 400 reused" resume.out && fail "the new file reused the old file's results"
same other renamed || fail "the resumed run does not equal the new file's own results"
replace rewritten rewritten
echo "PASS"
