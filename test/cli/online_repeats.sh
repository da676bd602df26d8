#!/usr/bin/env bash
# pipeline.onlineRepeats: every rom / gp-deim online run is timed that many times and t_online_s
# is the fastest of them (t_online_runs_s lists them all); the results come from the first run,
# so E_L2 is the same as without repeats; gp-adeim, whose model changes as it runs, runs once.
# pipeline.onlineRepeatSeconds: a repeat starts only while the repeats so far took less than
# the budget, so a budget of 1e-9 s allows exactly one repeat (the first one starts at 0 s spent).
# Fails if either option is ignored (one time listed; fifty with the budget), if t_online_s is not
# the minimum, or if the repeats changed the results.
# usage: online_repeats.sh GPHR
set -u
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
base='gphr:\n  scene: {name: nls1d, n: 32}\n  time: {T: 0.2, dt: 0.01}\n  training: {points: [2]}\n  reduction: {k: 4}\n  output: {plots: false}\n'
printf "$base"'  pipeline: {rom: true, methods: [rom, gp-deim, gp-adeim], m: [4]}\n' > "$work/one.yaml"
printf "$base"'  pipeline: {rom: true, methods: [rom, gp-deim, gp-adeim], m: [4], onlineRepeats: 3}\n' > "$work/three.yaml"
printf "$base"'  pipeline: {rom: true, methods: [rom, gp-deim], m: [4], onlineRepeats: 50, onlineRepeatSeconds: 1e-9}\n' > "$work/budget.yaml"
for c in one three budget; do
  "$gphr" run "$work/$c.yaml" --output "$work/$c" > /dev/null 2> "$work/err" || { echo "FAIL: $c exit $?"; cat "$work/err"; exit 1; }
done
python3 - "$work/one/summary.json" "$work/three/summary.json" "$work/budget/summary.json" <<'PY'
import json, sys
one, three, budget = ({r["method"]: r for r in json.load(open(p))["runs"]} for p in sys.argv[1:4])
for method in ("rom", "gp-deim"):
    assert len(budget[method]["t_online_runs_s"]) == 2, (method, budget[method]["t_online_runs_s"])
for method, n in (("rom", 3), ("gp-deim", 3), ("gp-adeim", 1)):
    r = three[method]
    times = r["t_online_runs_s"]
    assert len(times) == n, (method, times)
    assert r["t_online_s"] == min(times), (method, r["t_online_s"], times)
    assert r["E_L2"] == one[method]["E_L2"], (method, r["E_L2"], one[method]["E_L2"])
    assert len(one[method]["t_online_runs_s"]) == 1, (method, one[method]["t_online_runs_s"])
print("ok: rom and gp-deim timed 3 times (fastest reported), gp-adeim once, results unchanged; the time budget stops the repeats")
PY
