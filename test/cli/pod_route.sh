#!/usr/bin/env bash
# reduction.podRoute and hyper.podRoute reach the symplectic basis and the exact DEIM basis:
# 'tsqr' where a POD step has more columns than the rows per rank (n = 64: 128 state rows, 64
# rows of G; steps of 2 x 51 snapshot columns and of 3 x 2k = 60 Jacobian columns) exits 2 with one
# line naming the section, the step's columns and the rows; 'replicated' and 'stacked' run and
# report their steps, and with 'tree' give the same errors (all three routes are exact SVDs).
# usage: pod_route.sh GPHR
set -u
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
config() {  # config REDUCTION_ROUTE HYPER_ROUTE
  cat > "$work/c.yaml" <<YAML
gphr:
  scene: {name: nls1d, n: 64}
  time: {T: 0.5, dt: 0.01}
  training: {points: [3]}
  reduction: {k: 10, blockColumns: 51, podRoute: $1}
  pipeline: {rom: true, methods: [rom, gp-deim], m: [10]}
  hyper: {svd: exact, podRoute: $2}
  output: {plots: false}
YAML
}
fail() { echo "FAIL: $*"; echo "--- stderr:"; cat "$work/err"; exit 1; }
refused() {  # refused EXPECTED_TEXT...: the run exits 2 with one error line holding each text
  "$gphr" run "$work/c.yaml" --output "$work/out" > /dev/null 2> "$work/err"
  local rc=$?
  [ $rc -eq 2 ] || fail "exit code $rc, expected 2"
  [ "$(grep -c '^gphr: error' "$work/err")" -eq 1 ] || fail "not one error line"
  for text in "$@"; do grep '^gphr: error' "$work/err" | grep -qF -- "$text" || fail "error line lacks: $text"; done
}
config tsqr auto
refused "symplectic basis (psd" "podRoute 'tsqr' cannot take a step of" "+ 102 new)" "holds 128 of the 128 rows"
config replicated tsqr
refused "hyper: streaming POD: podRoute 'tsqr' cannot take a step of" "holds 64 of the 64 rows"
config replicated replicated
"$gphr" run "$work/c.yaml" --output "$work/fresh" > /dev/null 2> "$work/err" || fail "replicated routes: exit code $?"
python3 - "$work/fresh/summary.json" <<'PY' || fail "summary"
import json, sys
runs = json.load(open(sys.argv[1]))["runs"]
rom = [r for r in runs if r["method"] == "rom"][0]
# 3 training runs of 51 states: one POD step each, all replicated (a fresh directory: computed here)
assert (rom["basis_cached"], rom["pod_route"], rom["pod_steps_tsqr"], rom["pod_steps_replicated"]) == (False, "replicated", 0, 3), rom
# the DEIM basis's POD: every step on the replicated route (an ignored hyper.podRoute would take auto's route)
g = [r for r in runs if r["method"] == "gp-deim"][0]
assert not g["deim_basis_cached"] and g["deim_pod_steps_replicated"] > 0, g
assert g["deim_pod_steps_tsqr"] == g["deim_pod_steps_stacked"] == 0, g
PY
config stacked stacked
"$gphr" run "$work/c.yaml" --output "$work/stacked" > /dev/null 2> "$work/err" || fail "stacked routes: exit code $?"
config tree tree
"$gphr" run "$work/c.yaml" --output "$work/tree" > /dev/null 2> "$work/err" || fail "tree routes: exit code $?"
python3 - "$work/fresh/summary.json" "$work/stacked/summary.json" "$work/tree/summary.json" <<'PY' || fail "stacked or tree summary"
import json, sys
runs = [json.load(open(f))["runs"] for f in sys.argv[1:]]
rom = [r for r in runs[1] if r["method"] == "rom"][0]
assert (rom["pod_route"], rom["pod_steps_tsqr"], rom["pod_steps_stacked"], rom["pod_steps_replicated"]) == ("stacked", 0, 3, 0), rom
g = [r for r in runs[1] if r["method"] == "gp-deim"][0]
assert not g["deim_basis_cached"] and g["deim_pod_steps_stacked"] > 0, g
assert g["deim_pod_steps_tsqr"] == g["deim_pod_steps_replicated"] == 0, g
assert [r for r in runs[2] if r["method"] == "rom"][0]["pod_route"] == "tree"
# The same bases up to round-off, so the same errors: 1e-8 relative is far above the round-off
# carried through 50 steps and far below what a wrong basis vector does (errors change by O(1)).
for other in runs[1:]:
    assert len(runs[0]) == len(other), (len(runs[0]), len(other))
    for a, b in zip(runs[0][1:], other[1:]):
        assert a["method"] == b["method"], (a["method"], b["method"])
        assert abs(a["E_L2"] - b["E_L2"]) <= 1e-8 * abs(b["E_L2"]), (a["method"], a["E_L2"], b["E_L2"])
PY
echo ok
