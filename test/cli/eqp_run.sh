#!/usr/bin/env bash
# gp-eqp end to end: a small SWE run with rom, gp-deim, gp-eqp and gp-eqp-refit; the quadrature
# runs are in runs.csv, report.md (beside gp-deim in the term-weights table) and summary.json with
# their diagnostics (non-negative weights for gp-eqp, terms within the budget); a second run in the
# same directory reads the fits from artifacts.h5 (eqp_cached) and gives the same errors.
# usage: eqp_run.sh GPHR
set -eu
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cat > "$work/c.yaml" <<'YAML'
gphr:
  scene: {name: swe2d, nx: 12}
  time: {T: 0.5, dt: 0.01}
  integrator: {scheme: imr}
  training: {points: [2, 2], snapshotEvery: 5}
  reduction: {k: 6}
  pipeline: {rom: true, methods: [rom, gp-deim, gp-eqp, gp-eqp-refit], m: [4, 8]}
  output: {saveEvery: 10, plots: false}
YAML
for pass in 1 2; do
  "$gphr" run "$work/c.yaml" --output "$work/out" > "$work/stdout" 2> "$work/stderr" || { cat "$work/stderr"; exit 1; }
  cp "$work/out/summary.json" "$work/summary$pass.json"
done
grep -q "^gp-eqp,6,4,ok" "$work/out/runs.csv" || { echo "runs.csv lacks gp-eqp"; cat "$work/out/runs.csv"; exit 1; }
grep -q "^gp-eqp-refit,6,8," "$work/out/runs.csv" || { echo "runs.csv lacks gp-eqp-refit"; exit 1; }
grep -q "^| gp-eqp | 6 | 8 |" "$work/out/report.md" || { echo "report.md lacks gp-eqp"; exit 1; }
grep -q "Term weights: GP-DEIM and empirical quadrature" "$work/out/report.md" || { echo "no term-weights table"; exit 1; }
python3 - "$work/summary1.json" "$work/summary2.json" <<'PY'
import json, math, sys
one, two = (json.load(open(p))["runs"] for p in sys.argv[1:3])
eqp = [r for r in one if r["method"] in ("gp-eqp", "gp-eqp-refit")]
assert len(eqp) == 4, [r["method"] for r in one]
for r in eqp:
    for k in ("eqp_terms", "eqp_fit_residual", "eqp_weight_min", "eqp_weight_max", "hess_min_eig_hr", "convexity_lost",
              "t_eqp_fit_s", "t_hyper_offline_s"):
        assert k in r and r[k] is not None, (r["method"], r["m"], k)
    assert 1 <= r["eqp_terms"] <= r["m"], r
    assert 0 <= r["eqp_fit_residual"] <= 1 + 1e-12 or r["method"] == "gp-eqp-refit", r
    assert r["eqp_cached"] is False, r
    if r["method"] == "gp-eqp":
        assert r["eqp_weight_min"] > 0, r
assert all(r["eqp_cached"] is True for r in two if r["method"] in ("gp-eqp", "gp-eqp-refit"))
for a, b in zip(one, two):
    if a["method"] in ("gp-eqp", "gp-eqp-refit"):
        assert a["E_L2"] == b["E_L2"], (a["method"], a["m"], a["E_L2"], b["E_L2"])
print("eqp ok:", [(r["method"], r["m"], r["eqp_terms"], "%.3g" % r["E_L2"]) for r in eqp])
PY
echo ok
