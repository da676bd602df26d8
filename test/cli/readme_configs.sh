#!/usr/bin/env bash
# Every ```yaml block of the README is a config `gphr run` accepts and runs: each block, with a
# small scene, time span and training set appended (NLS n = 128, 20 steps; the blocks set the
# methods and their sections, not these), must exit 0 with a summary.json. A block the parser
# rejects (a flow mapping over several lines, say) or a key the validators refuse fails here.
# usage: readme_configs.sh GPHR README
set -eu
gphr=$1; readme=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
awk -v dir="$work" '/^```yaml/{f=1; n++; next} /^```/{f=0} f{print > (dir "/block" n ".yaml")}' "$readme"
ls "$work"/block*.yaml > /dev/null 2>&1 || { echo "no yaml blocks in $readme"; exit 1; }
for b in "$work"/block*.yaml; do
  name=$(basename "$b" .yaml)
  grep -q '^gphr:' "$b" || { echo "$name: no top-level 'gphr:'"; cat "$b"; exit 1; }
  for line in "scene: {name: nls1d, n: 128}" "time: {T: 0.2, dt: 0.01}" "training: {points: [2]}"; do
    grep -q "^  ${line%%:*}:" "$b" || echo "  $line" >> "$b"
  done
  "$gphr" run "$b" --output "$work/$name" > "$work/$name.out" 2> "$work/$name.err" || {
    echo "$name: gphr run failed"; cat "$b"; cat "$work/$name.err"; exit 1; }
  [ -s "$work/$name/summary.json" ] || { echo "$name: no summary.json"; exit 1; }
  echo "$name: ok"
done
