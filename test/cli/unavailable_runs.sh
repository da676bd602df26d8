#!/usr/bin/env bash
# A DEIM size the offline data cannot support (m = d = 64 on NLS n = 32: more than the DEIM basis
# from the training snapshots, and than the first delta0 full-model steps give GP-ADEIM) is an
# `unavailable` run with its reason, beside the runs that can be made; gphr exits 0 and writes the
# whole report (artifacts.h5 included: an unavailable run has no trajectory to store).
# usage: unavailable_runs.sh GPHR
set -u
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
printf 'gphr:\n  scene: {name: nls1d, n: 32}\n  time: {T: 0.2, dt: 0.01}\n  training: {points: [2]}\n  reduction: {k: 4}\n  pipeline: {rom: true, methods: [gp-deim, gp-adeim], m: [4, 64]}\n  output: {plots: false}\n' > "$work/c.yaml"
"$gphr" run "$work/c.yaml" --output "$work/out" > /dev/null 2> "$work/err" || { echo "FAIL: exit $?"; cat "$work/err"; exit 1; }
python3 - "$work/out/summary.json" <<'PY'
import json, sys
runs = {(r["method"], r.get("m")): r for r in json.load(open(sys.argv[1]))["runs"]}
for method in ("gp-deim", "gp-adeim"):
    ok, big = runs[(method, 4)], runs[(method, 64)]
    assert ok["status"] == "ok" and ok["E_L2"] is not None, (method, ok)
    why = big.get("reason", "")
    assert big["status"] == "unavailable" and ("fewer than m = 64" in why or "vectors" in why), (method, big)
print("ok: m = 4 ran, m = 64 unavailable with a reason, for gp-deim and gp-adeim")
PY
