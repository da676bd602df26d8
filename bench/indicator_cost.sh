#!/usr/bin/env bash
# The online error indicator's cost and quality (doc/error-estimate.md) against build.indicatorDofs,
# at two sizes n, measured side by side in one run, the machine printed: the SWE box (beta in
# [1.1, 1.7], gamma in [0.7, 1.3]), IMR, T = 1, dt = 0.005, a 3 x 3 training grid, gp-deim
# k = 10, m = 40; per nx in NXS and indicatorDofs in DOFS:
#   share   sum of indicator_s / sum of online_s of `gphr query` over 64 random points of the box
#           (seed 7), the faster of two runs (one process, one thread: gphr query's own setting);
#   corr    the rank correlation (Spearman) of the query's error_estimate with E_L2 over the same
#           points (`gphr validate`: a full solve per point), and the share within 3x.
# usage: bash bench/indicator_cost.sh [BUILD_DIR]   (env: NXS="16 32" DOFS="8 12 16")
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
build=${1:-build}
gphr=$PWD/$build/packages/driver/gphr
NXS=${NXS:-16 32}; DOFS=${DOFS:-8 12 16}
export OPENBLAS_NUM_THREADS=1
out=bench-out/indicator_cost; rm -rf "$out"; mkdir -p "$out"; cd "$out"
/usr/bin/python3 - <<'PY'
import random
r = random.Random(7)
pts = [(r.uniform(1.1, 1.7), r.uniform(0.7, 1.3)) for _ in range(64)]
common = "  defaults: {T: 1.0, dt: 0.005, saveEvery: 10%s}\n  points:\n"
body = "".join(f"    h{i:02d}: {{beta: {b:.6f}, gamma: {g:.6f}}}\n" for i, (b, g) in enumerate(pts))
open("queries.yaml", "w").write("queries:\n" + common % ", method: gp-deim, k: 10, m: 40" + body)
open("held.yaml", "w").write("validate:\n" + common % "" + body)
PY
echo "machine: $(machine_line "$gphr")"
echo "SWE, IMR, T = 1, dt = 0.005, 3 x 3 training, gp-deim k = 10, m = 40; 64 random points"
for nx in $NXS; do
  for dofs in $DOFS; do
    name=nx$nx-d$dofs
    cat > "$name.yaml" <<YAML
gphr:
  scene: {name: swe2d, nx: $nx}
  time: {T: 1.0, dt: 0.005}
  integrator: {scheme: imr, jacobianLag: true}
  training: {points: [3, 3], snapshotEvery: 2}
  pipeline: {methods: [gp-deim], k: [10], m: [40]}
  hyper: {snapshotEvery: 2}
  build: {withBasis: true, indicatorDofs: $dofs}
  output: {progressSeconds: 0.0}
YAML
    "$gphr" build "$name.yaml" --model "$name.h5" --output "art-$name" > /dev/null 2>&1
    for run in 1 2; do "$gphr" query "$name.h5" queries.yaml --output "q-$name-$run" > /dev/null 2>&1; done
    "$gphr" validate "$name.h5" held.yaml --output "v-$name" > /dev/null 2>&1
    /usr/bin/python3 - "$name" "$nx" "$dofs" <<'PY'
import csv, json, sys
name, nx, dofs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
shares = []
for run in (1, 2):
    rows = list(csv.DictReader(open(f"q-{name}-{run}/queries.csv")))
    online = sum(float(r["online_s"]) for r in rows)
    shares.append((online, sum(float(r["indicator_s"]) for r in rows) / online))
online, share = min(shares)
rows = [r for r in csv.DictReader(open(f"v-{name}/validation.csv")) if r["method"] == "gp-deim" and r["status"] == "ok"]
E = [float(r["E_L2"]) for r in rows]
# the query estimate's quality over the points, as gphr validate reports it (one model here)
quality = json.load(open(f"v-{name}/validation_summary.json"))["query_error_estimate"]
rho, within = (float("nan") if v is None else v for v in (quality["rank_correlation"], quality["within_3x"]))
print(f"nx {nx:3d} (n = {nx * nx:5d})  indicatorDofs {dofs:3d}: indicator {100 * share:5.1f} % of {online:.3f} s online; "
      f"rank corr {rho:.2f}, within 3x {100 * within:.0f} % of {len(rows)} points, E_L2 {min(E):.2e} .. {max(E):.2e}")
PY
  done
done
