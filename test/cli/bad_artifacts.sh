#!/usr/bin/env bash
# An output directory whose artifacts.h5 is truncated, belongs to another scene, holds states
# of another size, or has a damaged object header (a training entry's): exit 2 and an error line
# naming the file and the mismatch (for the damage: HDF5's checksum, and how to start afresh).
# A changed value in the file's distributed data, which no HDF5 checksum covers, is caught by its
# column fingerprint: in a training snapshot (read by the basis): exit 2, naming the parameter,
# the column and the way out; in the basis or the DEIM basis: computed afresh, said on stderr,
# and the results equal the clean run's. A gp-eqp fit has no fingerprint: a term outside G's rows,
# a NaN weight or cut diagnostics are computed afresh likewise.
# usage: bad_artifacts.sh GPHR
set -u
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cfg() {  # cfg SCENE SIZEKEY SIZE
  printf 'gphr:\n  scene: {name: %s, %s: %s}\n  time: {T: 0.1, dt: 0.01}\n  training: {points: %s}\n  reduction: {k: 2}\n  pipeline: {rom: true}\n  output: {plots: false}\n' \
    "$1" "$2" "$3" "$4"
}
cfg nls1d n 32 "[2]" > "$work/nls.yaml"
cfg nls1d n 40 "[2]" > "$work/nls40.yaml"
cfg swe2d nx 6 "[2, 1]" > "$work/swe.yaml"
sed 's/pipeline: {rom: true}/pipeline: {rom: true, methods: [gp-deim], m: [6]}/' "$work/nls.yaml" > "$work/deim.yaml"
fail() { echo "FAIL ($1): $2"; cat "$work/err"; exit 1; }
expect() {  # expect NAME DIR CONFIG TEXT
  "$gphr" run "$3" --output "$2" > /dev/null 2> "$work/err"; rc=$?
  [ $rc -eq 2 ] || fail "$1" "exit code $rc, expected 2"
  grep -q "gphr: error: .*$2/artifacts.h5" "$work/err" || fail "$1" "error does not name the file"
  grep -qF -- "$4" "$work/err" || fail "$1" "error lacks: $4"
  echo "ok ($1): $(grep 'gphr: error' "$work/err")"
}
"$gphr" run "$work/nls.yaml" --output "$work/good" > /dev/null 2>&1 || { echo "setup run failed"; exit 1; }
mkdir -p "$work/trunc" && head -c 2000 "$work/good/artifacts.h5" > "$work/trunc/artifacts.h5"
expect truncated "$work/trunc" "$work/nls.yaml" "truncated"
expect other_scene "$work/good" "$work/swe.yaml" "belongs to scene 'nls1d' but the config runs 'swe2d'"
expect other_size "$work/good" "$work/nls40.yaml" "holds states of size 64 but the config gives size 80"
mkdir -p "$work/header" && cp "$work/good/artifacts.h5" "$work/header/"
/usr/bin/python3 - "$work/header/artifacts.h5" <<'PY' || { echo "damaging the header failed"; exit 1; }
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f:
    at = h5py.h5o.get_info(f["training/p0"].id).addr + 20
with open(sys.argv[1], "r+b") as g:
    g.seek(at)
    b = g.read(1)[0]
    g.seek(at)
    g.write(bytes([b ^ 0x10]))
PY
expect damaged_header "$work/header" "$work/nls.yaml" "incorrect metadata checksum"
grep -qF "the artifacts file is damaged: remove '$work/header/artifacts.h5'" "$work/err" || fail damaged_header "no way out named"

change() {  # change FILE DATASET ROW COLUMN [delete DATASET]: adds 0.5 to one entry in place (attributes kept)
  /usr/bin/python3 - "$@" <<'PY' || { echo "changing $2 failed"; exit 1; }
import sys
import h5py
with h5py.File(sys.argv[1], "r+") as f:
    d = f[sys.argv[2]]
    d[int(sys.argv[3]), int(sys.argv[4])] += 0.5
    if len(sys.argv) > 6:
        del f[sys.argv[6]]
PY
}
# a snapshot: the basis (deleted) is computed again from the snapshots and refuses the changed one
mkdir -p "$work/snap" && cp "$work/good/artifacts.h5" "$work/snap/"
change "$work/snap/artifacts.h5" training/p1 3 5 delete basis
expect changed_snapshot "$work/snap" "$work/nls.yaml" \
  "the snapshots of training parameter 2 (/training/p1): column 3 does not match its fingerprint"
grep -qF "remove '$work/snap/artifacts.h5' (or use another --output directory) to train afresh" "$work/err" ||
  fail changed_snapshot "no way out named"
# the basis and the DEIM basis: computed afresh, equal to the clean run's, and so its results
same() {  # same NAME DIR CONFIG TEXT CLEAN DATASET: exit 0, TEXT on stderr, DATASET and rom_history.csv as CLEAN's
  "$gphr" run "$3" --output "$2" > /dev/null 2> "$work/err"; rc=$?
  [ $rc -eq 0 ] || fail "$1" "exit code $rc, expected 0"
  grep -qF -- "$4" "$work/err" || fail "$1" "stderr lacks: $4"
  /usr/bin/python3 -c 'import sys, h5py, numpy
a, b = (h5py.File(f + "/artifacts.h5", "r")[sys.argv[3]][()] for f in sys.argv[1:3])
sys.exit(0 if numpy.array_equal(a, b) else 1)' "$2" "$5" "$6" || fail "$1" "$6 differs from the clean run's"
  cmp -s "$2/rom_history.csv" "$5/rom_history.csv" || fail "$1" "rom_history.csv differs from the clean run's"
  echo "ok ($1): $(grep -F -- "$4" "$work/err")"
}
mkdir -p "$work/basis" && cp "$work/good/artifacts.h5" "$work/basis/"
change "$work/basis/artifacts.h5" basis 1 7
same changed_basis "$work/basis" "$work/nls.yaml" \
  "/basis in '$work/basis/artifacts.h5' column 1 does not match its fingerprint: computed afresh" "$work/good" basis
"$gphr" run "$work/deim.yaml" --output "$work/deimgood" > /dev/null 2>&1 || { echo "gp-deim setup run failed"; exit 1; }
mkdir -p "$work/deim" && cp "$work/deimgood/artifacts.h5" "$work/deim/"
change "$work/deim/artifacts.h5" deim/k2 2 3
same changed_deim_basis "$work/deim" "$work/deim.yaml" \
  "/deim/k2 in '$work/deim/artifacts.h5' column 2 does not match its fingerprint: computed afresh" "$work/deimgood" \
  deim/k2
# a gp-eqp fit (no fingerprint: every value checked on reading): a term outside G's rows, a NaN
# weight, or diagnostics cut short are computed afresh, equal to the clean run's fit
sed 's/pipeline: {rom: true}/pipeline: {rom: true, methods: [gp-eqp], m: [6]}/' "$work/nls.yaml" > "$work/eqp.yaml"
"$gphr" run "$work/eqp.yaml" --output "$work/eqpgood" > /dev/null 2>&1 || { echo "gp-eqp setup run failed"; exit 1; }
fit=eqp/gp-eqp_k2_m6
for damage in "term:term 1 is 99999 (allowed: a row of G, 0 to 31)" "weight:weight 2 is nan (allowed: finite, >= 0)" \
              "diagnostics:holds 1 diagnostics (allowed: 5)"; do
  kind=${damage%%:*}; text=${damage#*:}
  mkdir -p "$work/eqp_$kind" && cp "$work/eqpgood/artifacts.h5" "$work/eqp_$kind/"
  /usr/bin/python3 - "$work/eqp_$kind/artifacts.h5" "$fit" "$kind" <<'PY'
import sys, h5py, numpy
with h5py.File(sys.argv[1], "r+") as f:
    d = f[sys.argv[2]]
    if sys.argv[3] == "term":
        a = d[()]; a[0, 0] = 99999; d[...] = a
    elif sys.argv[3] == "weight":
        a = d[()]; a[1, 1] = numpy.nan; d[...] = a
    else:
        d.attrs["diagnostics"] = numpy.array([1.0])
PY
  same "changed_eqp_$kind" "$work/eqp_$kind" "$work/eqp.yaml" "/$fit in '$work/eqp_$kind/artifacts.h5' $text: computed afresh" \
    "$work/eqpgood" "$fit"
done
