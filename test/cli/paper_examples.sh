#!/usr/bin/env bash
# examples/paper/*.yaml (the paper's settings) run at a reduced size that takes seconds — the
# size, horizon and training set scaled down, everything else as written — and every method of
# each ends ok, so that a key of those configs that the validators refuse, or a method that cannot
# run with them, fails here.
# usage: paper_examples.sh GPHR EXAMPLES_DIR
set -eu
gphr=$1; dir=$2
export OPENBLAS_NUM_THREADS=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
shrink() {
  case $(basename "$1") in
    nls.yaml) sed -e 's/n: 2048/n: 128/' -e 's/T: 30.0/T: 1.0/' -e 's/points: \[11\]/points: [3]/' \
                  -e 's/k: 200/k: 12/' -e 's/m: \[100\]/m: [12]/' -e 's/maxRank: 110/maxRank: 40/' \
                  -e 's/numSamples: 250/numSamples: 60/' -e 's/plots: true/plots: false/' "$1" ;;
    swe.yaml) sed -e 's/nx: 50/nx: 12/' -e 's/T: 10.0/T: 0.2/' -e 's/points: \[5, 5\]/points: [2, 2]/' \
                  -e 's/k: 40/k: 8/' -e 's/m: \[50, 100, 150\]/m: [10, 20]/' -e 's/plots: true/plots: false/' "$1" ;;
    *) echo "no reduced size for $1"; exit 1 ;;
  esac
}
for cfg in "$dir"/paper/*.yaml; do
  name=$(basename "$cfg" .yaml)
  shrink "$cfg" > "$work/$name.yaml"
  "$gphr" run "$work/$name.yaml" --output "$work/$name" > /dev/null 2> "$work/$name.err" || { cat "$work/$name.err"; exit 1; }
  python3 - "$work/$name.yaml" "$work/$name/summary.json" <<'PY'
import json, re, sys
methods = re.search(r"methods:\s*\[([^\]]*)\]", open(sys.argv[1]).read()).group(1).replace(" ", "").split(",")
runs = json.load(open(sys.argv[2]))["runs"]
for m in methods:
    st = [r.get("status") for r in runs if r.get("method") == m]
    assert st and all(s == "ok" for s in st), (sys.argv[1], m, st)
print(sys.argv[1].rsplit("/", 1)[-1], "at a reduced size: every run ok:", ", ".join(methods))
PY
done
