#!/usr/bin/env bash
# Hostile input to gphr query and validate (a model file is a shipped artefact): damaged
# model files derived from a good one by fuzz_model_files.py (h5py), and bad queries files. Each
# run is under a timeout; the test fails on any exit code other than the expected one (2 for bad
# input, 0 for an edit that keeps the model), a hang, a crash, more than one line from gphr on
# stderr, an output directory left by a failed run, or a status other than `ok` from a file that
# loads. Every case runs on 1 rank, every eighth and the cases below on 2 ranks as well;
# validate runs on a sample.
# usage: model_file_fuzz.sh GPHR MPIEXEC
set -u
gphr=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); mpiexec=$2
export OPENBLAS_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0 runs=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
cp "$here/../support/small_nls_model.yaml" build.yaml
"$gphr" build build.yaml --model good.h5 --output art > /dev/null 2>&1 || { echo "FAIL: build"; exit 1; }
printf 'queries:\n  defaults: {T: 0.2}\n  points:\n    a: {eps: 1.0}\n    b: {eps: 1.05}\n' > q.yaml
printf 'validate:\n  defaults: {T: 0.2}\n  points:\n    a: {eps: 1.0}\n' > v.yaml
/usr/bin/python3 "$here/fuzz_model_files.py" good.h5 bad > /dev/null || { echo "FAIL: deriving the files"; exit 1; }

# run EXPECT LABEL COMMAND...: exit code, one gphr line on a failure, nothing left behind
run() {
  local expect=$1 label=$2; shift 2
  rm -rf out; runs=$((runs + 1))
  [ -z "${PREPARE:-}" ] || eval "$PREPARE"  # e.g. an output directory that cannot take the report
  timeout -k 5 60 "$@" < /dev/null > stdout.txt 2> stderr.txt
  local rc=$?
  if [ $rc -eq 124 ] || [ $rc -eq 137 ]; then fail "$label: hung (killed after 60 s)"; return; fi
  if [ $rc -ne "$expect" ]; then fail "$label: exit $rc, expected $expect: $(grep -m2 . stderr.txt | tr '\n' ' ')"; return; fi
  if [ "$expect" -ne 0 ]; then
    local n; n=$(grep -c '^gphr' stderr.txt)
    [ "$n" -eq 1 ] || fail "$label: $n lines from gphr on stderr, expected 1: $(head -c 300 stderr.txt)"
    grep -q 'malloc\|buffer overflow\|Segmentation\|internal error' stderr.txt && fail "$label: $(head -c 200 stderr.txt)"
    if [ -z "${PREPARE:-}" ] && [ -e out ] && [ -n "$(ls -A out 2> /dev/null)" ]; then
      fail "$label: left $(ls out | head -3 | tr '\n' ' ')"
    fi
  elif [ -f out/queries.csv ]; then
    grep -q ',diverged,\|,nan,' out/queries.csv && fail "$label: a loaded file gave a diverged or nan query"
  fi
}

while read -r name expect; do
  run "$expect" "query $name" "$gphr" query "bad/$name.h5" q.yaml --output out
  if [ $((runs % 8)) -eq 0 ]; then
    run "$expect" "query $name (2 ranks)" "$mpiexec" -np 2 "$gphr" query "bad/$name.h5" q.yaml --output out
  fi
done < bad/cases.txt
# a dataset behind a filter this HDF5 lacks: said as such (it said "can't open directory .../plugins")
run 2 "query lzf_weights (message)" "$gphr" query bad/lzf_weights.h5 q.yaml --output out
grep -q "through a filter -- compression or another plugin -- that this HDF5 cannot apply" stderr.txt ||
  fail "a filtered dataset: the message does not say so: $(head -c 300 stderr.txt)"
# on 2 ranks whatever the sampling above: an offset out of range, NaN in c and in w
for name in offsets_1000 nan_k6_constant_values nan_k6_gp-deim_m12_weights; do
  run 2 "query $name (2 ranks)" "$mpiexec" -np 2 "$gphr" query "bad/$name.h5" q.yaml --output out
done
for name in offsets_1000 nan_k6_constant_values flipped_k6_gp-deim_m12_basis_rows; do
  run 2 "validate $name" "$gphr" validate "bad/$name.h5" v.yaml --output out
  run 2 "validate $name (2 ranks)" "$mpiexec" -np 2 "$gphr" validate "bad/$name.h5" v.yaml --output out
done

# A damaged object header is named as one (HDF5's checksum of the 1.8 format), not as a
# missing attribute or dataset.
run 2 "query header_model (message)" "$gphr" query bad/header_model.h5 q.yaml --output out
grep -q "incorrect metadata checksum" stderr.txt || fail "header_model: the message does not name the checksum: $(cat stderr.txt)"

# The basis A is read only to lift (validate, setup: exact, states: true) and is outside the
# checksum: where it is read, a value that is not finite or a changed one (its fingerprint) is an
# error naming the dataset.
printf 'queries:\n  defaults: {T: 0.2, setup: exact}\n  points:\n    a: {eps: 1.0}\n' > qexact.yaml
/usr/bin/python3 - <<'PY' || fail "deriving the damaged bases"
import shutil
import h5py
import numpy as np
for name, index, value in (("basis_nan", 5, np.nan), ("basis_changed", 40, None)):
    shutil.copy("good.h5", f"bad/{name}.h5")
    with h5py.File(f"bad/{name}.h5", "r+") as f:
        g = sorted(k for k in f if k.startswith("k"))[0] + "/basis"
        a = f[g][()]
        a.flat[index] = value if value is not None else a.flat[index] + 0.5
        f[g][...] = a
PY
for name in basis_nan basis_changed; do
  run 2 "query (setup: exact) $name" "$gphr" query "bad/$name.h5" qexact.yaml --output out
  grep -q "/basis" stderr.txt || fail "query $name: the message does not name the basis: $(cat stderr.txt)"
  run 2 "validate $name (2 ranks)" "$mpiexec" -np 2 "$gphr" validate "bad/$name.h5" v.yaml --output out
done

# bad queries files against the good model
mkdir qdir; : > empty.yaml; head -c 200 "$gphr" > binary.yaml
printf 'queries:\n  points:\n    a: {eps: 1.0}\n    a: {eps: 1.05}\n' > duplicate.yaml
printf 'queries:\n  points:\n    %s: {eps: 1.0}\n' "$(printf 'x%.0s' $(seq 300))" > long_name.yaml
printf 'queries:\n  points:\n    "": {eps: 1.0}\n' > empty_name.yaml
printf 'queries:\n  defaults: {T: 1.0e12}\n  points:\n    a: {eps: 1.0}\n' > huge_T.yaml
printf 'queries:\n  grid: {eps: [0.9, 1.1, 1]}\n' > grid_one.yaml
printf 'queries:\n  grid: {eps: [0.9, 1.1, 1000000000]}\n' > grid_huge.yaml
# size and nesting bombs (YamlText.hpp: refused before Teuchos' quadratic reader sees them; a 2 MB
# value took > 120 s), a value over several lines, UTF-8 outside a comment
python3 -c "print('queries:\n  points:\n    a: {eps: 1.0, method: \'' + 'x' * (2 << 20) + '\'}')" > big_value.yaml
python3 -c "print('queries:\n  grid:\n    eps: [' + ', '.join(['1.0'] * 400000) + ']')" > big_list.yaml
python3 -c "print('queries:\n  points:\n' + ''.join('    p%d: {eps: 1.0}\n' % i for i in range(300000)), end='')" > big_file.yaml
python3 -c "d = 3000; print('queries:\n  defaults: ' + '{a: ' * d + '1' + '}' * d)" > deep.yaml
printf 'queries:\n  points:\n    a: {eps: 1.0, method: "gp-\n      deim"}\n' > two_lines.yaml
printf 'queries:\n  points:\n    caf\xc3\xa9: {eps: 1.0}\n' > utf8.yaml
for q in qdir empty.yaml binary.yaml duplicate.yaml long_name.yaml empty_name.yaml huge_T.yaml grid_one.yaml grid_huge.yaml missing.yaml \
         big_value.yaml big_list.yaml big_file.yaml deep.yaml two_lines.yaml utf8.yaml; do
  run 2 "queries file $q" "$gphr" query good.h5 "$q" --output out
  run 2 "queries file $q (2 ranks)" "$mpiexec" -np 2 "$gphr" query good.h5 "$q" --output out
done
for launch in "" "$mpiexec -np 2"; do
  run 2 "model file is a directory ${launch:+(2 ranks)}" $launch "$gphr" query qdir q.yaml --output out
  grep -q 'Is a directory' stderr.txt && fail "model file is a directory: MPI-IO's messages reached the user"
done

# output directories that cannot take the results: a full disk (/dev/full) and a report path taken
PREPARE='mkdir -p out && ln -s /dev/full out/queries.csv.tmp'
run 2 "query onto a full disk" "$gphr" query good.h5 q.yaml --output out
grep -q "cannot write 'out/queries.csv.tmp'" stderr.txt || fail "full disk: the message does not name the file"
run 2 "query onto a full disk (2 ranks)" "$mpiexec" -np 2 "$gphr" query good.h5 q.yaml --output out
PREPARE='mkdir -p out/validation.md'
run 2 "validate into a taken report path" "$gphr" validate good.h5 v.yaml --output out
grep -q "validation.md" stderr.txt || fail "taken report path: the message does not name it"
run 2 "validate into a taken report path (2 ranks)" "$mpiexec" -np 2 "$gphr" validate good.h5 v.yaml --output out
PREPARE=
run 0 "validate the good file" "$gphr" validate good.h5 v.yaml --output out
[ -s out/validation.md ] || fail "validate the good file: no validation.md"
# random damage besides the chosen: 12 single-bit flips anywhere in the file (seed fixed), each
# exit 0 with finite results or exit 2 with one line (scripts/flip_bits.sh: the longer sweeps)
runs=$((runs + 1))
bash "$here/../../scripts/flip_bits.sh" "$gphr" good.h5 q.yaml 12 20261127 > flips.txt 2>&1 ||
  fail "random bit flips: $(tr '\n' ' ' < flips.txt)"
echo "$runs runs: $((runs - failures)) passed, $failures failed"
[ $failures -eq 0 ]
