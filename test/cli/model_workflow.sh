#!/usr/bin/env bash
# The README's build / query / validate workflow, with its example files, runs and gives what the
# README says: a model file, 11 queries ok, and a validation where GP-DEIM m = 40 stays within
# 1.1x of the ROM's largest error over the box.
# usage: model_workflow.sh GPHR EXAMPLES_DIR
set -eu
gphr=$1; ex=$2
export OPENBLAS_NUM_THREADS=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$gphr" build "$ex/nls_build.yaml" --model nls.h5 > build.out 2> build.err || { cat build.err; exit 1; }
"$gphr" query nls.h5 "$ex/nls_queries.yaml" --output queries > query.out 2> query.err || { cat query.err; exit 1; }
grep -q "11 queries (11 run, 0 reused, 11 ok)" query.out || { cat query.out; exit 1; }
"$gphr" validate nls.h5 "$ex/nls_validate.yaml" --output validation > validate.out 2> validate.err || { cat validate.err; exit 1; }
python3 - <<'PY'
import json
m = {x["model"]: x for x in json.load(open("validation/validation_summary.json"))["models"]}
rom, hr = m["rom k=10"]["E_L2_max"], m["gp-deim k=10 m=40"]["E_L2_max"]
assert hr <= 1.1 * rom, (hr, rom)
print(f"ok: README workflow; max E_L2 over the box: ROM {rom:.3e}, GP-DEIM m=40 {hr:.3e}")
PY
