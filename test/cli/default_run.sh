#!/usr/bin/env bash
# The README's main job: `gphr --output DIR` runs the default scene and writes the whole report.
set -eu
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$gphr" --output "$work/out" > "$work/stdout" 2> "$work/stderr" || { cat "$work/stderr"; exit 1; }
for f in artifacts.h5 summary.json fom_history.csv; do [ -s "$work/out/$f" ] || { echo "missing $f"; exit 1; }; done
python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['runs'][0]; assert r['status']=='ok' and r['n']==256 and r['steps']==500, r" "$work/out/summary.json"
echo ok
