#!/usr/bin/env bash
# Greedy training to a target error against the smallest tensor grid that meets it (issue 54),
# measured side by side in one run, the machine printed: on the SWE box (beta in [1.1, 1.7],
# gamma in [0.7, 1.3]; nx = NX, IMR, T = 1, dt = 0.005; gp-deim k = K, m = M), for
#   greedy   gphr build --target-error EPS (corners and centre, then the worst of 64 candidates per
#            round, seed 1), and
#   grids    gphr build with training.points [g, g], g = 2, 3, ..., GMAX,
# the full solves, the offline seconds (gphr build's wall time, each from an empty artifacts
# cache) and the max E_L2 of the model over 64 random held-out points (seed 7, other than the
# candidates'; gphr validate). The smallest grid whose max E_L2 is <= EPS is the one to beat.
# usage: bash bench/greedy.sh [BUILD_DIR]   (env: EPS=4e-5 NX=16 K=10 M=40 GMAX=5)
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
build=${1:-build}
gphr=$PWD/$build/packages/driver/gphr
EPS=${EPS:-4e-5}; NX=${NX:-16}; K=${K:-10}; M=${M:-40}; GMAX=${GMAX:-5}
export OPENBLAS_NUM_THREADS=1
out=bench-out/greedy; rm -rf "$out"; mkdir -p "$out"; cd "$out"
config() {  # config FILE TRAINING
  cat > "$1" <<YAML
gphr:
  scene: {name: swe2d, nx: $NX}
  time: {T: 1.0, dt: 0.005}
  integrator: {scheme: imr, jacobianLag: true}
  training: {$2snapshotEvery: 2}
  pipeline: {methods: [gp-deim], k: [$K], m: [$M]}
  hyper: {snapshotEvery: 2}
  build: {withBasis: true}
  output: {progressSeconds: 0.0}
YAML
}
/usr/bin/python3 - <<'PY'
import random
r = random.Random(7)
lines = ["validate:", "  defaults: {T: 1.0, dt: 0.005, saveEvery: 10}", "  points:"]
for i in range(64):
    lines.append(f"    h{i:02d}: {{beta: {r.uniform(1.1, 1.7):.6f}, gamma: {r.uniform(0.7, 1.3):.6f}}}")
open("held.yaml", "w").write("\n".join(lines) + "\n")
PY
# measure NAME CONFIG [BUILD ARGS...]: full solves, offline seconds, max E_L2 over the held-out points
measure() {
  local name=$1 cfg=$2; shift 2
  local t0=$(date +%s.%N)
  "$gphr" build "$cfg" --model "$name.h5" --output "art-$name" "$@" > "$name.build" 2> "$name.err"
  local t1=$(date +%s.%N)
  "$gphr" validate "$name.h5" held.yaml --output "v-$name" > /dev/null 2>&1
  /usr/bin/python3 - "$name" "$(echo "$t1 - $t0" | bc)" "$EPS" <<'PY'
import csv, h5py, sys
name, seconds, eps = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
rows = [r for r in csv.DictReader(open(f"v-{name}/validation.csv")) if r["method"] == "gp-deim"]
worst = max(float(r["E_L2"]) if r["status"] == "ok" else float("inf") for r in rows)
est = max(float(r["error_estimate"]) for r in rows)
with h5py.File(f"{name}.h5") as f:
    solves = int(f["greedy"][-1, 0]) if "greedy" in f else None
if solves is None:
    solves = sum(1 for line in open(f"{name}.err") if "[gphr] train: parameter" in line and "done" in line)
print(f"{name:10s} full solves {solves:3d}  offline {seconds:6.1f} s  max E_L2 {worst:.3e} ({worst / eps:.2f} EPS)  "
      f"max estimate {est:.3e}  {'meets' if worst <= eps else 'misses'} EPS")
PY
}
echo "machine: $(machine_line "$gphr")"
echo "SWE nx = $NX, gp-deim k = $K, m = $M, EPS = $EPS; 64 held-out points"
config greedy.yaml ""
measure greedy greedy.yaml --target-error "$EPS"
for g in $(seq 2 "$GMAX"); do
  config "grid$g.yaml" "points: [$g, $g], "
  measure "grid$g" "grid$g.yaml"
done
