#!/usr/bin/env bash
# Every config in examples/ runs, and its summary.json says what the README promises for it
# (check_summary.py: keys, finite numbers, size and steps, Newton converged, H conservation,
# ROM error). An example without expectations here fails the test.
#  - nls1d: AVF, so H and H_r within 1e-9 |H0|; ROM k = 20 with E_L2 in [0.011, 0.045] (measured
#    0.02229 on 2026-11-22, deterministic to round-off: a factor 2 either way flags a change of
#    the method; a broken ROM gives O(1)).
#  - swe2d: IMR, which conserves H only to O(dt^2) (symplectic: bounded, no drift): measured
#    5.1e-9 |H0| at dt = 0.005 over T = 2; bound 1e-7 (20x). A non-symplectic first-order
#    scheme drifts by O(dt): implicit Euler in IMR's place gives 2.9e-4 (measured).
# usage: examples.sh GPHR EXAMPLES_DIR
set -eu
gphr=$1; dir=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
for name in nls1d swe2d; do [ -s "$dir/$name.yaml" ] || { echo "examples/$name.yaml is missing"; exit 1; }; done
for cfg in "$dir"/*.yaml; do
  name=$(basename "$cfg" .yaml)
  case $name in
    nls1d) expect=(--scene nls1d --scheme avf --n 512 --steps 1000 --rom-k 20 --rom-E-L2 0.011 0.045) ;;
    swe2d) expect=(--scene swe2d --scheme imr --n 576 --steps 400 --H-rel-max 1e-7) ;;
    *) echo "$name: no expectations in examples.sh"; exit 1 ;;
  esac
  "$gphr" run "$cfg" --output "$work/$name" > /dev/null 2> "$work/$name.err" || { cat "$work/$name.err"; exit 1; }
  echo -n "$name: "
  python3 "$here/check_summary.py" check "$work/$name/summary.json" "${expect[@]}"
done
