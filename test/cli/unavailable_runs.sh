#!/usr/bin/env bash
# A DEIM size the offline data cannot support (m = 64 on NLS n = 32: more than the DEIM basis from
# the training snapshots has vectors, and more than G's d = 32 rows, which GP-ADEIM's message
# names) is an `unavailable` run with its reason, beside the runs that can be made; gphr exits 0 and writes the
# whole report (artifacts.h5 included: an unavailable run has no trajectory to store). The report's
# caution about GP-ADEIM windows narrower than the basis (2k w < m, here 2k = 8) lists m = 9 (the
# most the offline data supports) at w = 1 (8 < 9) but not at w = 2 (16), and never the
# unavailable m = 64, which did not run; the tables call m = 64 unavailable, not diverged, with
# no error or time (nan in runs.csv, '-' in report.md). A run with adeim.initialWindow beyond its
# steps never adapts, and the report says so.
# `gphr build` of the same config stores what it can (m = 4 and 9) and names what it left out
# (m = 64) on stderr, as run marks it unavailable, instead of stopping without a file. With
# pipeline.mPerK each k gets its own m list (k = 2: m = 3; k = 4: pipeline.m) in the build and the run.
# usage: unavailable_runs.sh GPHR
set -u
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
for w in 1 2; do
  printf 'gphr:\n  scene: {name: nls1d, n: 32}\n  time: {T: 0.2, dt: 0.01}\n  training: {points: [2]}\n  reduction: {k: 4}\n  pipeline: {rom: true, methods: [gp-deim, gp-adeim], m: [4, 9, 64]}\n  adeim: {window: %d}\n  output: {plots: false}\n' $w > "$work/c$w.yaml"
  "$gphr" run "$work/c$w.yaml" --output "$work/out$w" > /dev/null 2> "$work/err" || { echo "FAIL: exit $?"; cat "$work/err"; exit 1; }
done
for w in 1 2; do [ -s "$work/out$w/report.md" ] || { echo "FAIL: no report.md at w = $w"; exit 1; }; done
grep -q -- "^- gp-adeim k=4 m=9: 2k w = 8 < m = 9" "$work/out1/report.md" || { echo "FAIL: no caution for m = 9 at w = 1"; exit 1; }
if grep -q -- "^- gp-adeim k=4 m=\(9\|64\):" "$work/out2/report.md"; then echo "FAIL: caution at w = 2 (2k w = 16)"; exit 1; fi
grep -q -- "^| gp-adeim | 4 | 64 | unavailable |" "$work/out1/report.md" || { echo "FAIL: m = 64 not shown as unavailable"; exit 1; }
if grep -q -- "^- gp-adeim k=4 m=64:" "$work/out1/report.md"; then echo "FAIL: caution for the unavailable m = 64"; exit 1; fi
# runs.csv and report.md give an unavailable run no error and no time (not 0, which would read as exact)
grep -qx -- "gp-adeim,4,64,unavailable,nan,nan,nan,[^,]*,nan" "$work/out1/runs.csv" || { echo "FAIL: runs.csv row of m = 64"; cat "$work/out1/runs.csv"; exit 1; }
grep -q -- "^| gp-adeim | 4 | 64 | unavailable | - | - | - |" "$work/out1/report.md" || { echo "FAIL: report row of m = 64"; exit 1; }
# a run whose first update would come after its last step is reported as not adapted
printf 'gphr:\n  scene: {name: nls1d, n: 32}\n  time: {T: 0.2, dt: 0.01}\n  training: {points: [2]}\n  reduction: {k: 4}\n  pipeline: {rom: true, methods: [gp-adeim], m: [4]}\n  adeim: {initialWindow: 30}\n  output: {plots: false}\n' > "$work/late.yaml"
"$gphr" run "$work/late.yaml" --output "$work/late" > /dev/null 2> "$work/err" || { echo "FAIL: exit $?"; cat "$work/err"; exit 1; }
grep -q "^No update ran in gp-adeim k=4 m=4: adeim.initialWindow = 30 exceeds the 20 steps" "$work/late/report.md" || { echo "FAIL: no 'no update ran' note"; exit 1; }
if grep -q "^No update ran" "$work/out1/report.md"; then echo "FAIL: 'no update ran' for runs that adapted"; exit 1; fi
"$gphr" build "$work/c1.yaml" --model "$work/m.h5" --output "$work/out1" > "$work/built" 2> "$work/err" ||
  { echo "FAIL: build exit $?"; cat "$work/err"; exit 1; }
grep -q "not stored: gp-deim k = 4, m = 64: the DEIM basis has [0-9]* vectors" "$work/err" ||
  { echo "FAIL: build does not name the skipped m = 64"; cat "$work/err"; exit 1; }
grep -q "gp-deim k=4 m=4, gp-deim k=4 m=9;" "$work/built" || { echo "FAIL: build did not store m = 4 and 9"; cat "$work/built"; exit 1; }
# m per k: k = 2 takes its own list [3] (the file holds gp-deim k=2 m=3 and no other m of k = 2), k = 4 pipeline.m
printf 'gphr:\n  scene: {name: nls1d, n: 32}\n  time: {T: 0.2, dt: 0.01}\n  training: {points: [2]}\n  reduction: {k: 4}\n  pipeline: {methods: [gp-deim], k: [2, 4], m: [4, 9], mPerK: {k2: [3]}}\n  output: {plots: false}\n' > "$work/perk.yaml"
"$gphr" build "$work/perk.yaml" --model "$work/perk.h5" --output "$work/perk" > "$work/built" 2> "$work/err" ||
  { echo "FAIL: build with mPerK exit $?"; cat "$work/err"; exit 1; }
grep -q "gp-deim k=2 m=3, gp-deim k=4 m=4, gp-deim k=4 m=9;" "$work/built" ||
  { echo "FAIL: build with mPerK did not store k=2 m=3 and k=4 m=4, 9 alone"; cat "$work/built"; exit 1; }
"$gphr" run "$work/perk.yaml" --output "$work/perk" > /dev/null 2> "$work/err" || { echo "FAIL: run with mPerK exit $?"; cat "$work/err"; exit 1; }
[ "$(cut -d, -f1-3 "$work/perk/runs.csv" | grep -c '^gp-deim,')" -eq 3 ] && grep -q "^gp-deim,2,3," "$work/perk/runs.csv" ||
  { echo "FAIL: run with mPerK did not evaluate k=2 m=3, k=4 m=4, 9"; cat "$work/perk/runs.csv"; exit 1; }
python3 - "$work/out1/summary.json" <<'PY'
import json, sys
runs = {(r["method"], r.get("m")): r for r in json.load(open(sys.argv[1]))["runs"]}
for method in ("gp-deim", "gp-adeim"):
    ok, big = runs[(method, 4)], runs[(method, 64)]
    assert ok["status"] == "ok" and ok["E_L2"] is not None, (method, ok)
    assert runs[(method, 9)]["status"] == "ok", (method, runs[(method, 9)])
    why = big.get("reason", "")
    # gp-deim: its DEIM basis has fewer vectors than m; gp-adeim: m exceeds G's d rows, named
    expected = "vectors" if method == "gp-deim" else "G has d = 32 rows"
    assert big["status"] == "unavailable" and expected in why, (method, big)
print("ok: m = 4 and 9 ran, m = 64 unavailable with a reason, for gp-deim and gp-adeim; window caution for m = 9 at w = 1 only; build stored m = 4 and 9 and named m = 64; mPerK gave k = 2 its own m in build and run")
PY
