#!/usr/bin/env bash
# gphr build's per-stage clocks (doc/reference.md, "stages.csv"), on 2 ranks:
#  1. DIR/stages.csv has the documented header and one row per rank and stage, the stages of a
#     gp-deim + gp-eqp build in order, and no stages.csv.tmp left behind;
#  2. compute_s = cpu_s - mpi_cpu_s, no MPI column exceeds its total (wall, cpu), and critical_s
#     is 0 (measured only with GPHR_CRITICAL_PATH=1);
#  3. the PMPI layer of the executable counts: every rank spent time inside MPI (the training's
#     and the bases' reductions), so mpi_wall_s summed over a rank's stages is > 0;
#  4. the console prints one line per stage;
#  5. DIR/mpi_calls.csv splits each rank's and stage's mpi_wall_s by MPI function: its rows add up
#     to stages.csv's column, every name is an MPI function, and the bases' tree reduction shows
#     as point-to-point calls;
#  6. artifacts.h5 is flushed to the disk (MPI_File_sync) only with output.syncArtifacts: none in
#     the offline stages by default; with it, the training flushes once per round of parameters,
#     the basis and the DEIM basis once each.
# usage: build_stages.sh GPHR MPIEXEC
set -u
gphr=$1; mpi=$2
here=$(cd "$(dirname "$0")" && pwd)
unset GPHR_CRITICAL_PATH
export OPENBLAS_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
cd "$work"
# The shared small NLS build, with gp-eqp beside gp-deim (a stage of its own: the fits).
sed 's/methods: \[gp-deim\]/methods: [gp-deim, gp-eqp]/' "$here/../support/small_nls_model.yaml" > build.yaml
grep -q "gp-eqp" build.yaml || fail "could not add gp-eqp to the shared config"
"$mpi" -np 2 "$gphr" build build.yaml --model nls.h5 --output art > build.out 2> build.err || { cat build.err; fail "build"; }
grep -q "train: 2 groups of 1 rank(s)" build.err || fail "the training did not run in 2 groups of one rank: $(cat build.err)"
[ -f art/stages.csv ] || fail "no art/stages.csv"
[ -e art/stages.csv.tmp ] && fail "stages.csv.tmp left behind"
grep -q "stages (max over 2 rank(s))" build.out || fail "no stage table on the console: $(cat build.out)"
grep -qE "^ +deim basis k=6 +[0-9.]+ +[0-9.]+ +[0-9.]+$" build.out || fail "no console line of the DEIM basis: $(cat build.out)"
python3 - art/stages.csv <<'PY' || fail "stages.csv: see above"
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head = ["rank", "stage", "wall_s", "cpu_s", "mpi_wall_s", "mpi_cpu_s", "compute_s", "peak_rss_mb", "critical_s"]
assert rows[0] == head, rows[0]
want = ["setup", "training", "instance", "basis", "header", "deim basis k=6", "gp-deim k=6", "fits k=6",
        "interpolation k=6", "calibration", "write"]
body = rows[1:]
assert len(body) == 2 * len(want), f"{len(body)} rows, want {2 * len(want)}"
for r in (0, 1):
    mine = [x for x in body if x[0] == str(r)]
    assert [x[1] for x in mine] == want, [x[1] for x in mine]
    for x in mine:
        wall, cpu, mw, mc, comp, rss, critical = map(float, x[2:])
        # The critical path is measured only with GPHR_CRITICAL_PATH=1 (test_mpi_time checks it).
        assert critical == 0, x
        # The file prints 6 decimals: compute_s is cpu_s - mpi_cpu_s up to their rounding (1.5e-6).
        assert abs(comp - (cpu - mc)) <= 2e-6, x
        # Inside MPI is part of the total, up to the two clocks' reads (a few microseconds apart).
        assert 0 <= mw <= wall + 1e-4 and 0 <= mc <= cpu + 1e-4, x
        assert wall >= 0 and rss > 0, x
    mpi = sum(float(x[4]) for x in mine)
    # Zero would mean the PMPI layer is not linked or its symbols are not exported.
    assert mpi > 0, f"rank {r}: no time inside MPI in any stage"
print("stages.csv ok")
PY
[ -f art/mpi_calls.csv ] || fail "no art/mpi_calls.csv"
python3 - art/stages.csv art/mpi_calls.csv <<'PY' || fail "mpi_calls.csv: see above"
import csv, sys
stages = {(x["rank"], x["stage"]): float(x["mpi_wall_s"]) for x in csv.DictReader(open(sys.argv[1]))}
rows = list(csv.reader(open(sys.argv[2])))
assert rows[0] == ["rank", "stage", "call", "calls", "wall_s"], rows[0]
split = {}
for rank, stage, call, calls, wall in rows[1:]:
    assert (rank, stage) in stages, f"{rank},{stage}: not a stage of stages.csv"
    assert call.startswith("MPI_") and int(calls) > 0 and float(wall) >= 0, (rank, stage, call, calls, wall)
    split.setdefault((rank, stage), []).append((call, float(wall)))
for key, mpi in stages.items():
    parts = split.get(key, [])
    # Each figure is printed with 6 decimals: the rows' sum and the column agree to half a unit
    # of the last digit per printed number.
    assert abs(sum(w for _, w in parts) - mpi) <= 5e-7 * (len(parts) + 1), (key, mpi, parts)
    assert len({c for c, _ in parts}) == len(parts), f"{key}: a function listed twice"
# The basis' streaming POD on 2 ranks takes the tree route: the R factor goes from rank 1 to rank 0.
assert any(c == "MPI_Send" for c, _ in split.get(("1", "basis"), [])), split.get(("1", "basis"))
assert any(c == "MPI_Recv" for c, _ in split.get(("0", "basis"), [])), split.get(("0", "basis"))
print("mpi_calls.csv ok")
PY
# syncs DIR TRAINING BASIS DEIM: the MPI_File_sync calls of each rank in DIR/mpi_calls.csv's
# training, basis and DEIM basis stages ([] where none) are [TRAINING], [BASIS], [DEIM].
syncs() {
  python3 - "$@" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/mpi_calls.csv")))
for r in ("0", "1"):
    for stage, want in zip(("training", "basis", "deim basis k=6"), sys.argv[2:]):
        got = [int(x["calls"]) for x in rows if (x["rank"], x["stage"], x["call"]) == (r, stage, "MPI_File_sync")]
        assert got == ([int(want)] if want != "0" else []), f"rank {r}, {stage}: MPI_File_sync calls {got}, want {want}"
PY
}
syncs art 0 0 0 || fail "the default build flushed artifacts.h5 to the disk (output.syncArtifacts is off)"
# The training's 3 parameters on 2 groups of one rank are 2 rounds, each sealed with one flush for
# all its parameters: 2 per rank, not one per parameter.
sed 's/output: {/output: {syncArtifacts: true, /' build.yaml > sync.yaml
grep -q "syncArtifacts: true" sync.yaml || fail "could not set output.syncArtifacts"
"$mpi" -np 2 "$gphr" build sync.yaml --model sync.h5 --output art2 > sync.out 2> sync.err || { cat sync.err; fail "build with syncArtifacts"; }
syncs art2 2 1 1 || fail "output.syncArtifacts: true did not flush once per round and stage"
echo PASS
