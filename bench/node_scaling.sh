#!/usr/bin/env bash
# The scaling run (bench/scaling.sh at SIZE=large) on a lent 16-core machine in one call of the `device` tool
# (../shared/device/README.md): unpacks the carried bundle (.devbundle/gphr.tar.xz, made here by
# make_bundle.sh from a Release build), runs bench/scaling.sh with the bundle's gphr and mpirun
# (CRITICAL=1: the compute critical path beside the wall seconds), and leaves under $OUT per case
# the CSVs and the printed tables (node16-CASE.csv, -mpi.csv, .txt) and runs.tar, every rank
# count's stage tables and log - also when the call is cut off (a rank count that finished is
# kept; scaling.sh writes its CSVs at the end only). Without a bundle it runs the local build (a dry run here).
# usage: OUT=DIR [CASES="swe"] [RANKS="16 1 8 4"] [SIZE=large] bash bench/node_scaling.sh
#   on the device:  run(command='OUT=$OUT CASES=swe bash bench/node_scaling.sh', carry=[".devbundle"])
set -uo pipefail
cd "$(dirname "$0")/.."
: "${OUT:?set OUT to the directory that comes back}"
CASES=${CASES:-swe}; RANKS=${RANKS:-"16 1 8 4"}; SIZE=${SIZE:-large}
mkdir -p "$OUT"
if [ -f .devbundle/gphr.tar.xz ]; then
  mkdir -p /tmp/gb && tar -C /tmp/gb -xJf .devbundle/gphr.tar.xz || { echo "cannot unpack the bundle" >&2; exit 2; }
  # shellcheck disable=SC1091
  . /tmp/gb/devroot2/env.sh /tmp/gb/devroot2  # sets G, PATH (its mpirun) and the MPI environment
else
  G=${G:-$PWD/build/packages/driver/gphr}
  echo "no .devbundle/gphr.tar.xz: running $G (a dry run)" >&2
fi
export G
# Everything a finished (or cut-off) run leaves, in one file (the device tool returns at most 8):
# per case and rank count of this call, its stage tables and log, as $OUT/runs.tar.
keep() {
  local list=()
  for c in $CASES; do
    for p in $RANKS; do
      for f in art/stages.csv art/mpi_calls.csv log; do
        [ -f "bench-out/scaling/$SIZE/${c}_np$p/$f" ] && list+=("${c}_np$p/$f")
      done
    done
  done
  [ ${#list[@]} -gt 0 ] && tar -C "bench-out/scaling/$SIZE" -cf "$OUT/runs.tar" "${list[@]}"
}
trap keep EXIT
trap 'exit 143' TERM INT
for c in $CASES; do
  CASES=$c RANKS=$RANKS SIZE=$SIZE CRITICAL=1 OUT_CSV="$OUT/node16-$c.csv" bash bench/scaling.sh 2>&1 |
    tee "$OUT/node16-$c.txt"
done
