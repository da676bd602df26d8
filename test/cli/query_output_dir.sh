#!/usr/bin/env bash
# Results are keyed by what produced them, and one output directory takes one command at a time:
# - a query directory written from model file A, queried again with model file B (same query
#   names, another training): every query is redone and said to be, none reused; B again: all reused;
#   B again after a finished query's file is damaged (a value, an object header): those are redone;
# - two gphr query at once into one directory: the second exits 2 naming the first (pid), the first
#   finishes; a query killed with SIGKILL leaves no stale lock (the next run takes the directory);
# - gphr validate into a directory a query holds: exit 2 as well.
# usage: query_output_dir.sh GPHR
set -u
gphr=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
export OPENBLAS_NUM_THREADS=1
work=$(mktemp -d); trap 'kill %1 %2 2> /dev/null; rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; [ -f err ] && { echo "--- stderr:"; tail -5 err; }; exit 1; }
build() {  # build NAME TRAINING_POINTS
  cat > "$1.yaml" <<YAML
gphr:
  scene: {name: nls1d, n: 128}
  time: {T: 1.0, dt: 0.01}
  training: {points: [$2]}
  pipeline: {methods: [gp-deim], k: [6], m: [12]}
  hyper: {snapshotEvery: 5}
  build: {withBasis: true}
  output: {progressSeconds: 0.0}
YAML
  "$gphr" build "$1.yaml" --model "$1.h5" --output "art-$1" > /dev/null 2>&1 || fail "build $1"
}
build a 3
build b 4
printf 'queries:\n  defaults: {T: 0.5}\n  points:\n    p1: {eps: 0.95}\n    p2: {eps: 1.05}\n' > q.yaml
"$gphr" query a.h5 q.yaml --output dir > out 2> err || fail "query a"
grep -q "(2 run, 0 reused, 2 ok)" out || fail "query a: $(cat out)"
"$gphr" query b.h5 q.yaml --output dir > out 2> err || fail "query b"
grep -q "(2 run, 0 reused, 2 ok)" out || fail "model b reused model a's results: $(cat out)"
[ "$(grep -c 'holds a result of another model file, query or gphr version: redone' err)" -eq 2 ] || fail "no 'redone' lines"
"$gphr" query b.h5 q.yaml --output dir > out 2> err || fail "query b again"
grep -q "(0 run, 2 reused, 2 ok)" out || fail "model b's own results not reused: $(cat out)"
# a finished query's file damaged in a value (its data checksum) and in an object header (HDF5's):
# each query is redone, said so, and the results equal the undamaged run's
cp dir/queries.csv clean.csv
/usr/bin/python3 - dir/queries/p1.h5 dir/queries/p2.h5 <<'PY' || fail "damaging the results"
import sys
import h5py
value, header = sys.argv[1], sys.argv[2]
with h5py.File(value, "r") as f:
    at = f["z"].id.get_offset() + 8 * 5 + 2          # a byte inside z[0, 5]: a finite value, changed
    head = h5py.h5o.get_info(f["z"].id).addr + 20     # inside z's object header
for path, offset in ((value, at), (header, head)):
    with open(path, "r+b") as g:
        g.seek(offset)
        b = g.read(1)[0]
        g.seek(offset)
        g.write(bytes([b ^ 0x10]))
PY
"$gphr" query b.h5 q.yaml --output dir > out 2> err || fail "query b after damage"
grep -q "(2 run, 0 reused, 2 ok)" out || fail "damaged results were reused: $(cat out)"
grep -q "p1.h5 is unreadable or damaged (checksum mismatch): redone" err || fail "the changed value was not said: $(cat err)"
grep -q "p2.h5 is unreadable or damaged (.*incorrect metadata checksum.*): redone" err || fail "the damaged header was not said: $(cat err)"
cut -d, -f1-12,16-17 clean.csv > a.csv; cut -d, -f1-12,16-17 dir/queries.csv > b.csv  # all but the timings and `reused`
cmp -s a.csv b.csv || fail "the redone queries differ: $(diff a.csv b.csv)"
python3 - dir/query_summary.json <<'PY' || fail "query_summary.json"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["model_file"].endswith("b.h5"), s["model_file"]
PY

# a long query (400 grid points) holds the directory while a second one tries it
printf 'queries:\n  defaults: {T: 5.0}\n  grid: {eps: [0.9, 1.1, 400]}\n' > long.yaml
"$gphr" query a.h5 long.yaml --output busy > out1 2> err1 &
first=$!
for _ in $(seq 100); do [ -f busy/.gphr.lock ] && break; sleep 0.05; done
[ -f busy/.gphr.lock ] || fail "no lock file while the first query runs"
"$gphr" query a.h5 q.yaml --output busy > out 2> err
rc=$?
[ $rc -eq 2 ] || fail "second query into a busy directory: exit $rc, expected 2"
grep -q "output directory is in use: 'busy/.gphr.lock' is held by gphr query (pid $first on host " err \
  || fail "the message does not name the first query: $(cat err)"
[ "$(wc -l < err)" -eq 1 ] || fail "$(wc -l < err) lines on stderr"
printf 'validate:\n  defaults: {T: 0.5}\n  points:\n    p1: {eps: 0.95}\n' > v.yaml
"$gphr" validate a.h5 v.yaml --output busy > out 2> err
[ $? -eq 2 ] || fail "validate into a busy directory did not exit 2"
grep -q "output directory is in use: .* held by gphr query (pid $first " err || fail "validate: $(cat err)"
[ ! -e busy/fom ] && [ ! -e busy/points ] || fail "the refused validate made its directories in busy/"
wait $first || fail "the first query failed: $(tail -2 err1)"
[ ! -e busy/.gphr.lock ] || fail "the lock file outlived its query"
grep -q "(400 run, 0 reused, 400 ok)" out1 || fail "the first query: $(cat out1)"

# SIGKILL leaves no stale lock: the kernel releases flock with the process
"$gphr" query a.h5 long.yaml --output killed > /dev/null 2>&1 &
victim=$!
for _ in $(seq 100); do [ -f killed/.gphr.lock ] && break; sleep 0.05; done
kill -9 $victim; wait $victim 2> /dev/null
"$gphr" query a.h5 long.yaml --output killed > out 2> err || fail "after kill -9 the directory stayed locked: $(cat err)"
echo ok
