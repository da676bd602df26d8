#!/usr/bin/env bash
# Peak memory per rank of `gphr build` against the size of the training set: SWE NX x NX
# (default 128^2, 32,768 state rows), training on a 2 x 2 and a 4 x 4 grid over the same time
# window (T = 0.5, dt = 0.005, every state kept: 101 snapshots per parameter, 26 MB of them per
# parameter on one rank), and on the 2 x 2 grid over 4x the window (T = 2: 401 snapshots, 103 MB
# per parameter); k = 10, gp-deim with m = 20. Peak resident memory of the largest rank (each
# rank's own peak: getrusage of the rank's process), side by side, and the ratios to the first
# case: the training writes its snapshots to artifacts.h5 in column blocks and the stages read them
# back so, so both ratios stay near 1 (held in memory, 16 parameters would hold 4x the snapshots of
# 4, and a parameter read whole holds 4x the states over 4x the window).
# usage: bash bench/build_memory.sh [RANKS] [NX] [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
ranks=${1:-1}; nx=${2:-128}; build=${3:-build}
gphr=$PWD/$build/packages/driver/gphr
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(machine_line "$gphr")"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
# Runs its arguments and writes their peak resident memory (kB) to $1.<rank>.
cat > "$work/peak.py" <<'PY'
import os, resource, subprocess, sys
rc = subprocess.call(sys.argv[2:])
with open(sys.argv[1] + "." + os.environ.get("OMPI_COMM_WORLD_RANK", "0"), "w") as f:
    f.write(str(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss) + "\n")  # one line per rank for sort
sys.exit(rc)
PY
peak=()
for case in "2, 2|0.5" "4, 4|0.5" "2, 2|2.0"; do
  grid=${case%|*} T=${case#*|}
  cat > "$work/build.yaml" <<YAML
gphr:
  scene: {name: swe2d, nx: $nx}
  time: {T: $T, dt: 0.005}
  integrator: {scheme: imr, jacobianLag: true}
  training: {points: [$grid], snapshotEvery: 1}
  reduction: {k: 10}
  pipeline: {methods: [gp-deim], m: [20]}
  hyper: {snapshotEvery: 5}
YAML
  rm -rf "$work/art"
  start=$(date +%s.%N)
  rm -f "$work"/mem.*
  mpirun -np "$ranks" python3 "$work/peak.py" "$work/mem" \
    "$gphr" build "$work/build.yaml" --model "$work/model.h5" --output "$work/art" > /dev/null 2> "$work/err" \
    || { cat "$work/err"; exit 1; }
  seconds=$(python3 -c "import time; print(f'{time.time() - $start:.1f}')")
  kb=$(cat "$work"/mem.* | sort -n | tail -1)
  peak+=("$kb")
  printf 'training [%s], T = %s: %d parameters, peak resident memory of the largest rank %.1f MB, %s s wall\n' \
    "$grid" "$T" $(( ${grid%%,*} * ${grid##* } )) "$(python3 -c "print($kb / 1024)")" "$seconds"
done
printf 'ratio 4x4 / 2x2: %.2f, 2x2 over 4x the window / 2x2: %.2f  (%d rank(s), SWE %d^2)\n' \
  "$(python3 -c "print(${peak[1]} / ${peak[0]})")" "$(python3 -c "print(${peak[2]} / ${peak[0]})")" "$ranks" "$nx"
