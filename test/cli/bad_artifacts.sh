#!/usr/bin/env bash
# An output directory whose artifacts.h5 is truncated, belongs to another scene, holds states
# of another size, or has a damaged object header (a training entry's): exit 2 and an error line
# naming the file and the mismatch (for the damage: HDF5's checksum, and how to start afresh).
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
