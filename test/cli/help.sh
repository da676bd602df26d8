#!/usr/bin/env bash
# `gphr --help` exits 0 and prints the usage and the generated key reference (with defaults).
# usage: help.sh GPHR
set -eu
gphr=$1
out=$(mktemp); trap 'rm -f "$out"' EXIT
"$gphr" --help > "$out" 2>&1 || { echo "gphr --help exited with $?"; cat "$out"; exit 1; }
for text in "usage:" "gphr run CONFIG" "gphr build CONFIG --model" "gphr query FILE.h5" "gphr validate FILE.h5" "interpolationNodes (default 7" "newtonTolerance (default 1e-10" "scene:" "reduction:"; do
  grep -qF -- "$text" "$out" || { echo "gphr --help does not print '$text'"; cat "$out"; exit 1; }
done
echo ok
