#!/usr/bin/env bash
# gp-eqp against GP-DEIM and the ROM (issue 26, targets of its section 4), measured side by side in
# one `gphr run`: SWE 20 x 20, T = 2, IMR, 3 x 3 training (every 10th state kept), 2k = 40,
# methods rom, gp-deim, gp-eqp and gp-eqp-refit (GP-DEIM's terms, least-squares weights), budgets
# m in M (default 6 10 20 40 60). The DEIM snapshots are every 2nd kept state (hyper.snapshotEvery,
# as in bench/hyper_paper.sh); the quadrature fits every kept state (eqp.snapshotEvery 1).
# Extra eqp keys can be passed as EQP='sketchRows: 4000, energyWeight: 1.0'.
# usage: bash bench/eqp_swe.sh [RANKS] [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
np=${1:-1}; build=${2:-build}
gphr=$build/packages/driver/gphr
ms=${M:-6 10 20 40 60}
out=bench-out/eqp_swe_np${np}${TAG:+_$TAG}; mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; $(date -u +%F); ranks $np"
c=$out/config.yaml
cat > "$c" <<YAML
gphr:
  scene: {name: swe2d, nx: 20}
  parameters: {beta: 1.6435, gamma: 0.7762}
  time: {T: 2.0, dt: 0.005}
  integrator: {scheme: imr, jacobianLag: true}
  training: {points: [3, 3], snapshotEvery: 10}
  reduction: {k: 20}
  pipeline: {rom: true, methods: [rom, gp-deim, gp-eqp, gp-eqp-refit], m: [$(echo $ms | tr ' ' ',')], onlineRepeats: 5}
  hyper: {snapshotEvery: 2}
  eqp: {snapshotEvery: 1${EQP:+, $EQP}}
  output: {saveEvery: 10, plots: true, progressSeconds: 0.0}
YAML
if [ "$np" -eq 1 ]; then "$gphr" run "$c" --output "$out" > "$out/run.log" 2>&1
else mpirun --oversubscribe -np "$np" "$gphr" run "$c" --output "$out" > "$out/run.log" 2>&1; fi
python3 - "$out/summary.json" <<'PY'
import json, math, sys
s = json.load(open(sys.argv[1]))
runs = s["runs"]
rom = next(r for r in runs if r["method"] == "rom")
by = {(r["method"], r.get("m", 0)): r for r in runs}
ms = sorted({r["m"] for r in runs if r["method"] == "gp-eqp"})
def e(r):
    if r is None: return "-"
    x = r.get("E_L2")
    return ("%.3e" % x if x is not None else "nan") + ("" if r["status"] == "ok" else " " + r["status"])
print(f"ROM E_L2 {rom['E_L2']:.3e}")
print(f"{'m':>4} | {'gp-deim':>20} | {'gp-eqp':>20} | {'gp-eqp-refit':>20} | {'eqp/deim':>8} | {'eqp terms':>9} | "
      f"{'eqp fit res':>11} | {'eqp w min..max':>17} | {'deim w min..max':>17} | {'lmin deim':>10} | {'lmin eqp':>10}")
for m in ms:
    d, q, f = by.get(("gp-deim", m)), by.get(("gp-eqp", m)), by.get(("gp-eqp-refit", m))
    ratio = q["E_L2"] / d["E_L2"] if d and q and d.get("E_L2") and q.get("E_L2") is not None else float("nan")
    wq = f"{q.get('eqp_weight_min', float('nan')):.3g}..{q.get('eqp_weight_max', float('nan')):.3g}"
    wd = f"{d.get('deim_weight_min', float('nan')):.3g}..{d.get('deim_weight_max', float('nan')):.3g}" if d else "-"
    print(f"{m:>4} | {e(d):>20} | {e(q):>20} | {e(f):>20} | {ratio:>8.3f} | {q.get('eqp_terms', 0):>9} | "
          f"{q.get('eqp_fit_residual', float('nan')):>11.3e} | {wq:>17} | {wd:>17} | "
          f"{(d or {}).get('hess_min_eig_hr', float('nan')):>10.3g} | {q.get('hess_min_eig_hr', float('nan')):>10.3g}")
PY
