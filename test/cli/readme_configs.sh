#!/usr/bin/env bash
# Every ```yaml block of the README is a config `gphr run` accepts and runs: each block, with a
# small scene, time span and training set appended (NLS n = 256, 200 steps, three training parameters; the blocks set the
# methods and their sections, not these), must exit 0 with a summary.json in which every method
# of the block has at least one run with status ok. A block the parser rejects (a flow mapping
# over several lines, say), a key the validators refuse, or a method that cannot run at the
# block's settings fails here.
# usage: readme_configs.sh GPHR README
set -eu
gphr=$1; readme=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
awk -v dir="$work" '/^```yaml/{f=1; n++; next} /^```/{f=0} f{print > (dir "/block" n ".yaml")}' "$readme"
ls "$work"/block*.yaml > /dev/null 2>&1 || { echo "no yaml blocks in $readme"; exit 1; }
for b in "$work"/block*.yaml; do
  name=$(basename "$b" .yaml)
  grep -q '^gphr:' "$b" || { echo "$name: no top-level 'gphr:'"; cat "$b"; exit 1; }
  for line in "scene: {name: nls1d, n: 256}" "time: {T: 2.0, dt: 0.01}" "training: {points: [3]}"; do
    grep -q "^  ${line%%:*}:" "$b" || echo "  $line" >> "$b"
  done
  "$gphr" run "$b" --output "$work/$name" > "$work/$name.out" 2> "$work/$name.err" || {
    echo "$name: gphr run failed"; cat "$b"; cat "$work/$name.err"; exit 1; }
  [ -s "$work/$name/summary.json" ] || { echo "$name: no summary.json"; exit 1; }
  python3 - "$b" "$work/$name/summary.json" <<'PY' || exit 1
import json, re, sys
methods = re.search(r"methods:\s*\[([^\]]*)\]", open(sys.argv[1]).read()).group(1).replace(" ", "").split(",")
runs = json.load(open(sys.argv[2]))["runs"]
for m in methods:
    st = [r.get("status") for r in runs if r.get("method") == m]
    if "ok" not in st:
        sys.exit("%s: no run of %s ended ok (%s)" % (sys.argv[1], m, st))
print("%s: every method ran: %s" % (sys.argv[1].rsplit("/", 1)[-1], ", ".join(methods)))
PY
done
