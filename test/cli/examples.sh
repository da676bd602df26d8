#!/usr/bin/env bash
# Every config in examples/ runs and completes (the README shows them).
# usage: examples.sh GPHR EXAMPLES_DIR
set -eu
gphr=$1; dir=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
for cfg in "$dir"/*.yaml; do
  name=$(basename "$cfg" .yaml)
  "$gphr" run "$cfg" --output "$work/$name" > /dev/null 2> "$work/$name.err" || { cat "$work/$name.err"; exit 1; }
  [ -s "$work/$name/summary.json" ] || { echo "$name: no summary.json"; exit 1; }
  echo "ok: $name"
done
