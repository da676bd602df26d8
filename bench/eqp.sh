#!/usr/bin/env bash
# gp-eqp against GP-DEIM and the ROM (the targets in doc/eqp.md), measured side by
# side in one `gphr run` per case:
#   swe  SWE 20 x 20, T = 2, IMR, 3 x 3 training (every 10th state kept), 2k = 40, methods rom,
#        gp-deim, gp-eqp, gp-eqp-refit (GP-DEIM's terms, least-squares weights), m in M (default
#        6 10 20 40 60); the quadrature fits every kept state, exact rows (14760).
#   nls  the paper's NLS: n = 2048, T = 30, AVF, 11 training parameters (every 10th state kept),
#        2k = 160 (K=200: 400), m in M (default 60 80 100 130); the quadrature fits every 2nd kept state, its
#        1661 x 160 = 266k rows (x 2048 terms) sketched to SKETCH rows (default 20000), the fit's
#        residual on the exact rows reported beside.
#   swe-paper  the paper's SWE (Sec. 5.1): 50 x 50, T = 10, IMR, 5 x 5 training (every 10th state
#        kept), 2k = 80 and 160, m in M (default 25 50 75 100 150 200 300); the quadrature fits every
#        2nd kept state, its rows sketched to SKETCH (default 10000).
# The DEIM snapshots are every 2nd kept state (hyper.snapshotEvery, as bench/hyper_paper.sh);
# online times are the fastest of 5 repeats. Extra eqp keys: EQP='energyWeight: 1.0, ...'.
# usage: bash bench/eqp.sh CASE [RANKS] [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
case=$1; np=${2:-1}; build=${3:-build}
gphr=$build/packages/driver/gphr
out=bench-out/eqp_${case}_np${np}${TAG:+_$TAG}; mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(machine_line "$gphr"); ranks $np"
c=$out.yaml  # beside the output: gphr refuses to write over its input
list() { echo "$1" | tr ' ' ','; }
case $case in
  swe)
    cat > "$c" <<YAML
gphr:
  scene: {name: swe2d, nx: 20}
  parameters: {beta: 1.6435, gamma: 0.7762}
  time: {T: 2.0, dt: 0.005}
  integrator: {scheme: imr, jacobianLag: true}
  training: {points: [3, 3], snapshotEvery: 10}
  reduction: {k: 20}
  pipeline: {rom: true, methods: [rom, gp-deim, gp-eqp, gp-eqp-refit], m: [$(list "${M:-6 10 20 40 60}")], onlineRepeats: 5}
  hyper: {snapshotEvery: 2}
  eqp: {snapshotEvery: 1${EQP:+, $EQP}}
  output: {saveEvery: 10, plots: true, progressSeconds: 0.0}
YAML
    ;;
  nls)
    sed -e "s|^  integrator:.*|  integrator: {scheme: avf, jacobianLag: true}|" bench/configs/nls_paper.yaml > "$c"
    cat >> "$c" <<YAML
  training: {points: [11], snapshotEvery: 10}
  reduction: {k: ${K:-80}}
  pipeline: {rom: true, methods: [rom, gp-deim, gp-eqp], m: [$(list "${M:-60 80 100 130}")], onlineRepeats: 5}
  hyper: {snapshotEvery: 2, svd: randomized, maxRank: 170, powerIterations: 0}
  eqp: {snapshotEvery: 2, sketchRows: ${SKETCH:-20000}${EQP:+, $EQP}}
YAML
    ;;
  swe-paper)
    sed -e "s|^  integrator:.*|  integrator: {scheme: imr, jacobianLag: true}|" bench/configs/swe_paper.yaml > "$c"
    cat >> "$c" <<YAML
  training: {points: [5, 5], snapshotEvery: 10}
  reduction: {k: 80}
  pipeline: {rom: true, methods: [rom, gp-deim, gp-eqp], k: [40, 80], m: [$(list "${M:-25 50 75 100 150 200 300}")], onlineRepeats: 3}
  hyper: {snapshotEvery: 2, svd: randomized, powerIterations: 1}
  eqp: {snapshotEvery: 2, sketchRows: ${SKETCH:-10000}${EQP:+, $EQP}}
YAML
    ;;
  *) echo "unknown case $case (allowed: swe, nls, swe-paper)"; exit 2 ;;
esac
if [ "$np" -eq 1 ]; then "$gphr" run "$c" --output "$out" > "$out/run.log" 2>&1
else mpirun --oversubscribe -np "$np" "$gphr" run "$c" --output "$out" > "$out/run.log" 2>&1; fi
python3 - "$out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
runs = s["runs"]
nan = float("nan")
roms = {r["k"]: r for r in runs if r["method"] == "rom"}
by = {(r["method"], r.get("k", 0), r.get("m", 0)): r for r in runs}
def err(r):
    if r is None: return "-"
    x = r.get("E_L2")
    return ("%.3e" % x if x is not None else "nan") + ("" if r["status"] == "ok" else " " + r["status"])
def g(r, k, f="%.3g"):
    x = (r or {}).get(k)
    return f % x if isinstance(x, (int, float)) else "-"
def ratio(a, b):
    return "%.3f" % (a["E_L2"] / b["E_L2"]) if a and b and a.get("E_L2") is not None and b.get("E_L2") else "-"
cols = ["2k", "m", "gp-deim", "deim/rom", "gp-eqp", "eqp/rom", "eqp/deim", "gp-eqp-refit", "terms", "fit res",
        "exact rows", "eqp w", "deim w", "lmin deim", "lmin eqp", "eqp off s", "deim off s", "eqp on s", "deim on s"]
for k, rom in sorted(roms.items()):
    print(f"2k = {2 * k}: ROM E_L2 {rom['E_L2']:.3e}")
print(" | ".join(cols))
for k, m in sorted({(r["k"], r["m"]) for r in runs if r["method"] == "gp-eqp"}):
    rom = roms.get(k)
    d, q, f = by.get(("gp-deim", k, m)), by.get(("gp-eqp", k, m)), by.get(("gp-eqp-refit", k, m))
    print(" | ".join([str(2 * k), str(m), err(d), ratio(d, rom), err(q), ratio(q, rom), ratio(q, d), err(f),
                      g(q, "eqp_terms", "%d"), g(q, "eqp_fit_residual", "%.2e"), g(q, "eqp_fit_residual_exact_rows", "%.2e"),
                      g(q, "eqp_weight_min") + ".." + g(q, "eqp_weight_max"), g(d, "deim_weight_min") + ".." + g(d, "deim_weight_max"),
                      g(d, "hess_min_eig_hr"), g(q, "hess_min_eig_hr"), g(q, "t_hyper_offline_s", "%.1f"),
                      g(d, "t_hyper_offline_s", "%.1f"), g(q, "t_online_s", "%.3f"), g(d, "t_online_s", "%.3f")]))
PY
