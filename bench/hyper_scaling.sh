#!/usr/bin/env bash
# GP-DEIM online cost against the full size (issue: GP-DEIM, "HR online time per step for SWE
# 64^2 ... 512^2 at fixed k, m within 1.2x of each other, while the ROM's grows with n"): one short
# SWE run per grid (IMR, 100 steps of dt = 0.005, training at the box centre with every state kept
# for the DEIM snapshots, 2k = 20, m = 50: with 2k = 40, m = 100 the 128^2 and 256^2 models lost
# convexity and diverged, and the DEIM basis of this one short run has few directions above the
# randomized range finder's floor (57 at 64^2 with 2k = 20, ~131 at 128^2 with 2k = 40)),
# FOM, ROM and GP-DEIM side by side in each run; each reduced online run is repeated for up to
# 3 s (at most 1000 times) and the fastest kept (pipeline.onlineRepeats / onlineRepeatSeconds): a
# GP-DEIM run is 1.3-2.5 ms here, and this VM's speed swings 2x over spells of tens of ms, so five
# repeats inside one spell gave per-grid times 1.8x apart; the ROM at 512^2 is run twice (one repeat
# starts while 0 s are spent).
# Prints the time per step of each model and, for the dense models, per Newton iteration (the
# per-step figure also moves with the iteration count).
# usage: [M_SCALING=m] [K_SCALING=k] bash bench/hyper_scaling.sh [RANKS] [BUILD_DIR] [GRIDS]
set -euo pipefail
cd "$(dirname "$0")/.."
np=${1:-2}; build=${2:-build}; grids=${3:-"64 128 256 512"}; m=${M_SCALING:-50}; k=${K_SCALING:-10}
gphr=$build/packages/driver/gphr
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; $(date -u +%F); ranks $np"
printf '%-6s %9s %12s %12s %12s %12s %12s %10s %10s %8s\n' nx fullDim fom_ms/step rom_ms/step rom_ms/iter hr_ms/step hr_ms/iter E_L2_rom E_L2_hr hr_rows
for nx in $grids; do
  out=bench-out/hyper_scaling_${nx}_np$np; mkdir -p "$out"
  cat > "$out/config.yaml" <<YAML
gphr:
  scene: {name: swe2d, nx: $nx}
  parameters: {beta: 1.6435, gamma: 0.7762}
  time: {T: 0.5, dt: 0.005}
  integrator: {scheme: imr, jacobianLag: true}
  training: {points: [1, 1], snapshotEvery: 1}
  reduction: {k: $k}
  pipeline: {rom: true, methods: [rom, gp-deim], m: [$m], onlineRepeats: 1000, onlineRepeatSeconds: 3.0}
  hyper: {snapshotEvery: 1, svd: randomized, powerIterations: 0}
  output: {saveEvery: 10, plots: false, progressSeconds: 60.0}
YAML
  if [ "$np" -eq 1 ]; then "$gphr" run "$out/config.yaml" --output "$out" > "$out/run.log" 2>&1
  else mpirun --oversubscribe -np "$np" "$gphr" run "$out/config.yaml" --output "$out" > "$out/run.log" 2>&1; fi
  python3 - "$out/summary.json" "$nx" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); f = s["runs"][0]
rom = next(r for r in s["runs"] if r["method"] == "rom"); hr = next(r for r in s["runs"] if r["method"] == "gp-deim")
ms = lambda r: 1e3 * r.get("t_online_s", float("nan")) / f["steps"]
it = lambda r: ms(r) / r["newton_iters_avg"] if r.get("newton_iters_avg") else float("nan")
num = lambda x: float("nan") if x is None else x
print(f"{sys.argv[2]:<6} {f['fullDim']:>9} {ms(f):>12.3f} {ms(rom):>12.3f} {it(rom):>12.4f} {ms(hr):>12.4f} {it(hr):>12.4f} "
      f"{num(rom['E_L2']):>10.2e} {num(hr['E_L2']):>10.2e} {hr.get('kernel_rows_per_evaluation', 0):>8} {hr['status']}")
PY
done
