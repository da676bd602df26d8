#!/usr/bin/env bash
# Greedy training to a target error against the smallest tensor grid that meets it,
# measured side by side in one run, the machine printed, on one of two boxes:
#   SCENE=swe (default): the SWE box (beta in [1.1, 1.7], gamma in [0.7, 1.3]); nx = NX, IMR,
#            T = 1, dt = 0.005; gp-deim k = K, m = M (defaults 16, 10, 40);
#   SCENE=nls3: nls1d-pulse, three parameters (eps in [0.9, 1.1], the pulse's amplitude in
#            [0.8, 1.2] and velocity in [0.3, 0.7]); n = N, AVF, T = 1, dt = 0.01; gp-deim k = K,
#            m = M (defaults 128, 12, 24);
# for
#   greedy   gphr build --target-error EPS (build.greedyStart START: the corners and centre, or the
#            centre alone; then the worst of 64 candidates per round, seed 1), and
#   grids    gphr build with training.points [g, ..., g], g = 2, 3, ..., GMAX,
# the full solves, the offline seconds (gphr build's wall time, each from an empty artifacts
# cache) and the max E_L2 of the model over 64 random held-out points (seed 7, other than the
# candidates'; gphr validate). The smallest grid whose max E_L2 is <= EPS is the one to beat.
# NP ranks (default 1) run every build; IDOFS: build.indicatorDofs (default 16); PPR points per
# greedy round (build.pointsPerRound, default 1: with NP > 1 and PPR > 1 the training's rank groups
# integrate a round's points side by side).
# The greedy build's query default follows its line (the file's `query_defaults`), and each line
# gives, over the held-out points, the rank correlation of the query's error estimate with E_L2 and
# the share of points where the estimate is within 3x of it.
# usage: bash bench/greedy.sh [BUILD_DIR]   (env: START=corners|centre NP=1 PPR=1 IDOFS=16; SCENE=swe EPS=4e-5 NX=16
#                                            K=10 M=40 GMAX=5; SCENE=nls3 EPS=1e-3 N=128 K=12 M=24 GMAX=4)
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
build=${1:-build}
gphr=$PWD/$build/packages/driver/gphr
SCENE=${SCENE:-swe}; START=${START:-corners}; NP=${NP:-1}; PPR=${PPR:-1}; IDOFS=${IDOFS:-16}
case $SCENE in
  swe)  EPS=${EPS:-4e-5}; NX=${NX:-16}; K=${K:-10}; M=${M:-40}; GMAX=${GMAX:-5}
        SCENE_LINE="scene: {name: swe2d, nx: $NX}"; TIME_LINE="time: {T: 1.0, dt: 0.005}"
        INTEGRATOR="{scheme: imr, jacobianLag: true}"; BOX="beta 1.1 1.7 gamma 0.7 1.3"; DT=0.005 ;;
  nls3) EPS=${EPS:-1e-3}; N=${N:-128}; K=${K:-12}; M=${M:-24}; GMAX=${GMAX:-4}
        SCENE_LINE="scene: {name: nls1d-pulse, n: $N}"; TIME_LINE="time: {T: 1.0, dt: 0.01}"
        INTEGRATOR="{scheme: avf}"; BOX="eps 0.9 1.1 amplitude 0.8 1.2 velocity 0.3 0.7"; DT=0.01 ;;
  *) echo "SCENE=$SCENE; allowed: swe, nls3"; exit 2 ;;
esac
set -- $BOX; P=$(( $# / 3 ))
export OPENBLAS_NUM_THREADS=1
out=bench-out/greedy; rm -rf "$out"; mkdir -p "$out"; cd "$out"
config() {  # config FILE TRAINING
  cat > "$1" <<YAML
gphr:
  $SCENE_LINE
  $TIME_LINE
  integrator: $INTEGRATOR
  training: {$2snapshotEvery: 2}
  pipeline: {methods: [gp-deim], k: [$K], m: [$M]}
  hyper: {snapshotEvery: 2}
  build: {withBasis: true, greedyStart: $START, pointsPerRound: $PPR, indicatorDofs: $IDOFS}
  output: {progressSeconds: 0.0}
YAML
}
/usr/bin/python3 - "$DT" $BOX <<'PY'
import random, sys
dt, spec = sys.argv[1], sys.argv[2:]
box = [(spec[i], float(spec[i + 1]), float(spec[i + 2])) for i in range(0, len(spec), 3)]
r = random.Random(7)
lines = ["validate:", f"  defaults: {{T: 1.0, dt: {dt}, saveEvery: 10}}", "  points:"]
for i in range(64):
    lines.append(f"    h{i:02d}: {{" + ", ".join(f"{n}: {r.uniform(lo, hi):.6f}" for n, lo, hi in box) + "}")
open("held.yaml", "w").write("\n".join(lines) + "\n")
PY
# measure NAME CONFIG [BUILD ARGS...]: full solves, offline seconds, max E_L2 over the held-out points
measure() {
  local name=$1 cfg=$2; shift 2
  local t0=$(date +%s.%N)
  if [ "$NP" = 1 ]; then "$gphr" build "$cfg" --model "$name.h5" --output "art-$name" "$@" > "$name.build" 2> "$name.err"
  else mpirun --oversubscribe -np "$NP" "$gphr" build "$cfg" --model "$name.h5" --output "art-$name" "$@" \
         > "$name.build" 2> "$name.err"; fi
  local t1=$(date +%s.%N)
  "$gphr" validate "$name.h5" held.yaml --output "v-$name" > /dev/null 2>&1
  /usr/bin/python3 - "$name" "$(echo "$t1 - $t0" | bc)" "$EPS" <<'PY'
import csv, h5py, json, sys
name, seconds, eps = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
rows = [r for r in csv.DictReader(open(f"v-{name}/validation.csv")) if r["method"] == "gp-deim"]
worst = max(float(r["E_L2"]) if r["status"] == "ok" else float("inf") for r in rows)
est = max(float(r["error_estimate"]) for r in rows)
# the query estimate's quality over the held-out points, as gphr validate reports it (one model here)
quality = json.load(open(f"v-{name}/validation_summary.json"))["query_error_estimate"]
rho, within = (float("nan") if v is None else v for v in (quality["rank_correlation"], quality["within_3x"]))
with h5py.File(f"{name}.h5") as f:
    solves = int(f["greedy"][-1, 0]) if "greedy" in f else None
if solves is None:
    solves = sum(1 for line in open(f"{name}.err") if "[gphr] train: parameter" in line and "done" in line)
print(f"{name:10s} full solves {solves:3d}  offline {seconds:6.1f} s  max E_L2 {worst:.3e} ({worst / eps:.2f} EPS)  "
      f"max estimate {est:.3e}  {'meets' if worst <= eps else 'misses'} EPS  "
      f"rank corr {rho:.2f}, within 3x {100 * within:.0f} %")
with h5py.File(f"{name}.h5") as f:
    if "query_defaults" in f.attrs:  # a greedy build's choice, as gphr query takes it
        names = f.attrs["query_defaults"]
        names = (names.decode() if isinstance(names, bytes) else str(names)).split(";")
        errs = list(f.attrs["query_default_errors"])
        for i, q in enumerate(names):
            print(f"{'':10s} query default {q}: estimated max {errs[3 * i]:.3e} over the candidates, "
                  f"E_L2 max {errs[3 * i + 1]:.3e} at the build's fresh points, target {'met' if errs[3 * i + 2] else 'not met'}")
PY
}
echo "machine: $(machine_line "$gphr")"
echo "$SCENE_LINE, gp-deim k = $K, m = $M, EPS = $EPS; greedy start: $START, $PPR point(s) a round; $NP rank(s); 64 held-out points"
config greedy.yaml ""
measure greedy greedy.yaml --target-error "$EPS"
for g in $(seq 2 "$GMAX"); do
  config "grid$g.yaml" "points: [$(printf "$g, %.0s" $(seq 2 "$P"))$g], "
  measure "grid$g" "grid$g.yaml"
done
