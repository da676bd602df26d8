#!/usr/bin/env bash
# The reduced-model pipeline (train -> reduce -> evaluate) on 1 and 2 ranks gives the same
# errors E_L2, E_fin and the same reduced Hamiltonian error: training, basis (phase-normalised)
# and ROM agree to round-off across rank counts (1e-8 relative on errors of ~1e-2 leaves room
# for the Newton tolerance 1e-10 of the default integrator).
# usage: rom_ranks.sh GPHR MPIEXEC
set -eu
gphr=$1; mpiexec=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cat > "$work/c.yaml" <<'YAML'
gphr:
  scene: {name: nls1d, n: 128}
  time: {T: 2.0, dt: 0.01}
  training: {points: [3], snapshotEvery: 2}
  reduction: {k: 6}
  pipeline: {rom: true}
  output: {plots: false}
YAML
"$gphr" run "$work/c.yaml" --output "$work/np1" > "$work/np1.json" 2> "$work/np1.err" || { cat "$work/np1.err"; exit 1; }
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$gphr" run "$work/c.yaml" --output "$work/np2" > /dev/null 2> "$work/np2.err" || { cat "$work/np2.err"; exit 1; }
python3 - "$work/np1/summary.json" "$work/np2/summary.json" <<'PY'
import json, sys
a, b = (json.load(open(f))["runs"][1] for f in sys.argv[1:])
assert a["method"] == b["method"] == "rom" and a["k"] == b["k"] == 6, (a, b)
for key in ("E_L2", "E_fin", "energy_captured"):
    assert abs(a[key] - b[key]) <= 1e-8 * abs(a[key]), (key, a[key], b[key])
assert 0 < a["E_L2"] < 0.5, a
print("ok: E_L2 =", a["E_L2"], "on 1 and 2 ranks")
PY
