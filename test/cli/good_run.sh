#!/usr/bin/env bash
# A small run of `gphr run` (optionally under mpirun): exit 0, the outputs exist and are
# complete, summary.json has the documented keys, and AVF conserved H (H_err_max_rel <= 1e-9,
# the AVF bound of the timeint tests), and the HDF5 trajectory has the expected shape.
# usage: good_run.sh GPHR [mpirun args...]
set -eu
gphr=$1; shift
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cat > "$work/c.yaml" <<'YAML'
gphr:
  scene:
    name: swe2d
    nx: 12
  time:
    T: 0.5
    dt: 0.005
  output:
    saveEvery: 20
    plots: false
YAML
"$@" "$gphr" run "$work/c.yaml" --output "$work/out" > "$work/stdout" 2> "$work/stderr" || { cat "$work/stderr"; exit 1; }
for f in artifacts.h5 summary.json fom_history.csv; do [ -s "$work/out/$f" ] || { echo "missing $f"; exit 1; }; done
ls "$work/out" | grep -q partial && { echo "temporary file left"; exit 1; }
python3 - "$work/out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
for k in ("scene", "integrator", "parameters", "runs"): assert k in s, k
r = s["runs"][0]
for k in ("method", "n", "steps", "t_online_s", "newton_iters_avg", "H_err_max", "status"): assert k in r, k
assert s["scene"] == "swe2d" and r["method"] == "fom" and r["status"] == "ok" and r["steps"] == 100, r
assert r["n"] == 144 and s["parameters"] == {"beta": 1.6435, "gamma": 0.7762}, s
assert r["H_err_max_rel"] <= 1e-9, r
print("summary ok:", r["t_online_s"], "s,", r["newton_iters_avg"], "Newton/step, H_err_rel", r["H_err_max_rel"])
PY
# 100 steps saved every 20 -> 6 states of size 2n = 288.
h5dump -H -d /fom/trajectory "$work/out/artifacts.h5" | grep -q "( 6, 288 )" || { echo "trajectory shape"; h5dump -H "$work/out/artifacts.h5"; exit 1; }
echo ok
