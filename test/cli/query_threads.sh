#!/usr/bin/env bash
# gphr query --threads: the same per-query results on 1 thread, 3 threads and 2 ranks x 2 threads,
# bit for bit (every dataset and attribute of results.h5, and queries.csv but its timing and
# `reused` columns): 30 queries of two models and both set-up routes, some writing the lifted
# states (the HDF5 reads and writes of several threads at once). Bad --threads values exit 2
# naming the value and what is allowed.
# usage: query_threads.sh GPHR MPIEXEC   (h5py: Debian's python3-h5py, so /usr/bin/python3)
set -u
gphr=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
mpiexec=${2:-mpirun}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; [ -f err ] && { echo "--- stderr:"; tail -5 err; }; exit 1; }
cat > build.yaml <<YAML
gphr:
  scene: {name: nls1d, n: 128}
  time: {T: 1.0, dt: 0.01}
  training: {points: [3]}
  pipeline: {methods: [gp-deim], k: [6], m: [12, 16]}
  hyper: {snapshotEvery: 5}
  build: {withBasis: true}
  output: {progressSeconds: 0.0}
YAML
"$gphr" build build.yaml --model m.h5 --output art > /dev/null 2> err || fail "build"
cat > q.yaml <<YAML
queries:
  defaults: {T: 1.0, m: 12, saveEvery: 5}
  points:
    exact1: {eps: 0.93, setup: exact, states: true}
    exact2: {eps: 1.07, setup: exact, m: 16}
    states: {eps: 1.01, states: true}
  grid:
    eps: [0.9, 1.1, 27]
YAML
run() {  # run DIR RANKS THREADS
  if [ "$2" -eq 1 ]; then "$gphr" query m.h5 q.yaml --output "$1" --threads "$3" > out 2> err || fail "query $1"
  else "$mpiexec" -np "$2" "$gphr" query m.h5 q.yaml --output "$1" --threads "$3" > out 2> err || fail "query $1"; fi
  grep -q "(30 run, 0 reused, 30 ok) on $2 rank(s) x $3 thread(s)" out || fail "$1: $(cat out)"
}
run t1 1 1
run t3 1 3
run r2t2 2 2
/usr/bin/python3 - t1 t3 r2t2 <<'PY' || fail "results differ"
import csv, sys
import h5py, numpy as np
def items(path):
    out = {}
    def visit(name, obj):
        for k, v in obj.attrs.items(): out[name + "@" + k] = np.asarray(v)
        if isinstance(obj, h5py.Dataset): out[name] = obj[()]
    with h5py.File(path, "r") as f: f.visititems(visit)
    return out
def table(path):
    rows = list(csv.DictReader(open(path)))
    return [{k: v for k, v in r.items() if k not in ("setup_s", "online_s", "indicator_s", "reused")} for r in rows]
ref, ref_csv = items(sys.argv[1] + "/results.h5"), table(sys.argv[1] + "/queries.csv")
assert len(ref_csv) == 30 and sum(1 for k in ref if k.endswith("/states")) == 2, (len(ref_csv), sorted(ref)[:5])
for other in sys.argv[2:]:
    got = items(other + "/results.h5")
    assert sorted(got) == sorted(ref), other + ": other datasets or attributes"
    for k in ref:  # bit for bit: the same bytes, NaN included
        a, b = ref[k], got[k]
        same = a.tobytes() == b.tobytes() if a.dtype.kind == "f" else np.array_equal(a, b)
        assert same and a.dtype == b.dtype and a.shape == b.shape, other + ": " + k + " differs"
    assert table(other + "/queries.csv") == ref_csv, other + ": queries.csv differs"
    print(other, "=", sys.argv[1], "bit for bit:", len(ref), "datasets and attributes")
PY
for bad in 0 -2 two 1025 "" 1.5; do
  "$gphr" query m.h5 q.yaml --output bad --threads "$bad" > out 2> err
  rc=$?
  [ $rc -eq 2 ] || fail "--threads '$bad': exit $rc, expected 2"
  grep -q "threads '$bad' is not allowed (allowed: an integer from 1 to 1024)" err || fail "--threads '$bad': $(cat err)"
done
"$gphr" query m.h5 q.yaml --output bad --threads > out 2> err
[ $? -eq 2 ] && grep -q "threads '' is not allowed" err || fail "--threads without a value: $(cat err)"
echo "PASS"
