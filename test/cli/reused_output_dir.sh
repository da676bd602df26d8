#!/usr/bin/env bash
# An output directory reused for another config holds only the new run's outputs: a GP-ADEIM run,
# then a full-model-only run into the same directory, leaves no report, runs.csv,
# adeim_updates.csv, rom_history.csv or plot of the first run beside the second run's summary.json.
# A directory gphr has not completed a run in keeps every file of the user's, report.md included.
# usage: reused_output_dir.sh GPHR
set -u
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
printf 'gphr:\n  scene: {name: nls1d, n: 32}\n  time: {T: 0.2, dt: 0.01}\n  training: {points: [2]}\n  reduction: {k: 4}\n  pipeline: {rom: true, methods: [gp-adeim], m: [4]}\n' > "$work/a.yaml"
printf 'gphr:\n  scene: {name: nls1d, n: 32}\n  time: {T: 0.1, dt: 0.01}\n  pipeline: {rom: false}\n  output: {plots: false}\n' > "$work/b.yaml"
"$gphr" run "$work/a.yaml" --output "$work/out" > /dev/null 2> "$work/err" || { echo "FAIL: first run, exit $?"; cat "$work/err"; exit 1; }
for f in report.md runs.csv adeim_updates.csv rom_history.csv; do
  [ -s "$work/out/$f" ] || { echo "FAIL: the first run wrote no $f"; exit 1; }
done
"$gphr" run "$work/b.yaml" --output "$work/out" > /dev/null 2> "$work/err" || { echo "FAIL: second run, exit $?"; cat "$work/err"; exit 1; }
left=$(cd "$work/out" && ls | grep -v -x -e summary.json -e fom_history.csv -e artifacts.h5 -e config.yaml)
[ -z "$left" ] || { echo "FAIL: files of the first run left beside the second's summary: $left"; exit 1; }
grep -q '"steps": 10' "$work/out/summary.json" || { echo "FAIL: summary.json is not the second run's"; exit 1; }
grep -q 'T: 0.1' "$work/out/config.yaml" || { echo "FAIL: config.yaml is not the second run's"; exit 1; }
mkdir -p "$work/user" && echo "my notes" > "$work/user/report.md" && echo "x" > "$work/user/runs.csv"
"$gphr" run "$work/b.yaml" --output "$work/user" > /dev/null 2> "$work/err" || { echo "FAIL: run into a user directory, exit $?"; cat "$work/err"; exit 1; }
[ "$(cat "$work/user/report.md")" = "my notes" ] && [ "$(cat "$work/user/runs.csv")" = "x" ] || {
  echo "FAIL: a user's files in a directory without an earlier gphr run were removed or changed"; exit 1; }
echo "ok: only summary.json, fom_history.csv and artifacts.h5 after the full-model-only run; a user's files kept"
