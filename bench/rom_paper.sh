#!/usr/bin/env bash
# Benchmark of the offline training, the symplectic basis and the Galerkin reduced model at the
# paper's settings, side by side in one run per case:
#   nls      11 training parameters in [0.9, 1.1], AVF, 2k in {100, 200, 400}, test eps = 1.0932
#   swe-avf  5 x 5 training parameters, AVF, 2k in {80, 160}, test (1.6435, 0.7762)
#   swe-imr  the same with IMR
# The singular values of the NLS snapshots at eps = 1.0932 (the paper's fig:singvalues, left) are
# a separate run: gphr run bench/configs/nls_singular_values.yaml --output bench-out/nls_sv
# Each row: training / basis / ROM online / FOM online seconds, E_L2 and E_fin (eq:errNR), and the
# ROM's speed-up over the full model measured in the same run. Training is done once per case and
# reused (artifacts.h5) for the other sizes; the basis is recomputed for each k.
# usage: bash bench/rom_paper.sh CASE [RANKS] [BUILD_DIR] [SNAPSHOT_EVERY]   (KS="50" to choose the k values)
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
case=$1; np=${2:-1}; build=${3:-build}; every=${4:-10}
gphr=$build/packages/driver/gphr
out=bench-out/rom_${case}_np$np; mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(machine_line "$gphr"); ranks $np; snapshotEvery $every"
case $case in
  nls)     base=bench/configs/nls_paper.yaml; integ='{scheme: avf}'; train="{points: [11], snapshotEvery: $every}"; ks="50 100 200" ;;
  swe-avf) base=bench/configs/swe_paper.yaml; integ='{scheme: avf}'; train="{points: [5, 5], snapshotEvery: $every}"; ks="40 80" ;;
  swe-imr) base=bench/configs/swe_paper.yaml; integ='{scheme: imr}'; train="{points: [5, 5], snapshotEvery: $every}"; ks="40 80" ;;
  *) echo "unknown case $case"; exit 2 ;;
esac
ks=${KS:-$ks}
printf '%-4s %5s %10s %8s %9s %9s %8s %10s %10s %10s\n' 2k ranks train_s basis_s rom_s fom_s speedup E_L2 E_fin energy
for k in $ks; do
  c=$out/k$k.yaml
  sed -e "s|^  integrator:.*|  integrator: $integ|" "$base" > "$c"
  printf '  training: %s\n  reduction: {k: %s}\n  pipeline: {rom: true}\n' "$train" "$k" >> "$c"
  if [ "$np" -eq 1 ]; then "$gphr" run "$c" --output "$out" > "$out/k$k.log" 2>&1
  else mpirun --oversubscribe -np "$np" "$gphr" run "$c" --output "$out" > "$out/k$k.log" 2>&1; fi
  cp "$out/summary.json" "$out/summary_k$k.json"
  python3 - "$out/summary_k$k.json" "$np" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); f, r = s["runs"][0], s["runs"][1]
print(f"{r['reducedDim']:<4} {sys.argv[2]:>5} {r['t_training_s']:>10.1f} {r['t_basis_s']:>8.1f} {r['t_online_s']:>9.2f} "
      f"{f['t_online_s']:>9.2f} {f['t_online_s'] / r['t_online_s']:>7.1f}x {r['E_L2']:>10.2e} {r['E_fin']:>10.2e} {r['energy_captured']:>10.8f}")
PY
done
