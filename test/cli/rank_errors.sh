#!/usr/bin/env bash
# An error on some ranks only ends the job with the error, never a hang: the ranks agree on a
# failure when they all have one (validate's full models over rank groups: the group that failed
# names its point, the other group does not wait for it), and a rank whose failure the others do
# not share prints it, naming itself, and aborts the job (main.cpp, failed()) after 10 s; a
# failure every rank shares (a gp-adeim query's full system, an overflow, a stall) is one line naming
# the query and, for an overflow or a stall at round-off, saying so.
# usage: rank_errors.sh GPHR MPIEXEC
set -u
gphr=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); mpiexec=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
np2() { timeout 60 "$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$@"; }
# one_line NAME RC PATTERN WHAT -- COMMAND...: COMMAND exits RC with one gphr line matching PATTERN
one_line() {
  local name=$1 expect=$2 pattern=$3 what=$4; shift 5
  "$@" > "$name.out" 2> "$name.err"
  local rc=$?
  [ $rc -eq "$expect" ] || fail "$what: exit code $rc, expected $expect: $(cat "$name.err")"
  [ "$(grep -c 'gphr:' "$name.err")" -eq 1 ] && grep -q "$pattern" "$name.err" || fail "$what: not one line matching '$pattern': $(cat "$name.err")"
  echo "ok: $(grep 'gphr:' "$name.err")"
}
cp "$here/../support/small_nls_model.yaml" b.yaml  # gp-deim k = 6, m = 12, the basis stored
"$gphr" build b.yaml --model m.h5 --output art > /dev/null 2> build.err || { cat build.err; fail "build"; }

# 1. validate on 2 ranks, two points in two groups of one rank; point b's full model fails
#    (eps = 1e12: Newton stalls at its round-off, ~2e-6, 2e4 times the tolerance 1e-10, on any
#    BLAS kernel) while group 0 runs point a. Exit 3 naming point b.
printf 'validate:\n  defaults: {T: 1.0, dt: 0.01}\n  points:\n    a: {eps: 1.0}\n    b: {eps: 1.0e12}\n' > v.yaml
np2 "$gphr" validate m.h5 v.yaml --output v > v.out 2> v.err
rc=$?
[ $rc -eq 3 ] || fail "validate with a failing point: exit code $rc, expected 3 (124: hung): $(cat v.err)"
grep -q "gphr: solver failure: validate: point 'b' (eps = 1e+12): the full model failed: Newton did not converge" v.err \
  || fail "validate's failure does not name point b: $(cat v.err)"
echo "ok: $(grep 'gphr:' v.err)"

# 2. query on 2 ranks where rank 1's result file cannot be written (a directory stands at its
#    path); rank 0 finishes its queries and waits at the end. Rank 1 reports and aborts: a
#    non-zero exit within the 60 s limit, the message naming rank 1 and the path.
printf 'queries:\n  defaults: {T: 1.0, dt: 0.01, k: 6, m: 12}\n  grid: {eps: [0.9, 1.1, 3]}\n' > q.yaml
mkdir -p q/queries/grid-0001.h5
np2 "$gphr" query m.h5 q.yaml --output q > q.out 2> q.err
rc=$?
[ $rc -ne 0 ] && [ $rc -ne 124 ] || fail "query with an unwritable result on rank 1: exit code $rc (124: hung): $(cat q.err)"
grep -q "gphr: error (rank 1 of 2; the other ranks did not fail with it: aborting): cannot rename 'q/queries/grid-0001.h5.partial' to 'q/queries/grid-0001.h5'" q.err \
  || fail "the query failure does not name rank 1 and the file: $(cat q.err)"
echo "ok: $(grep 'gphr:' q.err)"

# 3. The same error on both ranks stays one line from rank 0 and its exit code (no abort).
printf 'queries:\n  defaults: {T: 1.0, dt: 0.01, k: 6, m: 12}\n  points:\n    a: {eps: 5.0}\n' > bad.yaml
np2 "$gphr" query m.h5 bad.yaml --output bad > bad.out 2> bad.err
rc=$?
[ $rc -eq 2 ] || fail "a bad query on both ranks: exit code $rc, expected 2: $(cat bad.err)"
[ "$(grep -c 'gphr:' bad.err)" -eq 1 ] && ! grep -q "aborting" bad.err || fail "a shared error was not one line: $(cat bad.err)"
echo "ok: $(grep 'gphr:' bad.err)"

# 4. A gp-adeim query steps the full system on every rank together: its solver failure is every
#    rank's, one line naming the query, exit 3.
sed 's/methods: \[gp-deim\]/methods: [gp-adeim]/' b.yaml > adeim.yaml
"$gphr" build adeim.yaml --model a.h5 --output aart > /dev/null 2> adeim.err || { cat adeim.err; fail "gp-adeim build"; }
printf 'queries:\n  defaults: {T: 1.0, dt: 0.01, k: 6, m: 12, method: gp-adeim}\n  points:\n    big: {eps: 1.0e12, extrapolate: true}\n' > qa.yaml
one_line qa 3 "gphr: solver failure: query 'big' (gp-adeim k=6 m=12): the first 5 full-model steps (adeim.initialWindow): Newton did not converge" \
  "a failing gp-adeim query" -- np2 "$gphr" query a.h5 qa.yaml --output qa

# 5. An overflow is named as one: eps = 1e300 makes the full model's residual infinite at the
#    first step, which no Newton iteration can mend. Exit 3, one line saying it is not finite.
printf 'validate:\n  defaults: {T: 1.0, dt: 0.01}\n  points:\n    huge: {eps: 1.0e300}\n' > vo.yaml
one_line vo 3 "point 'huge' (eps = 1e+300): the full model failed: .*residual norm inf .*not finite: the state or its gradient left the double range" \
  "validate with eps = 1e300" -- np2 "$gphr" validate m.h5 vo.yaml --output vo

# 6. On one rank (no groups) a full model's failure is worded the same; at eps = 1e9 Newton stalls
#    at its round-off, 2.1e-9 here, 21x the tolerance 1e-10 (within the 100x the line names as a
#    stall: a margin of 21x below and 4.7x above on another BLAS kernel), which the line says
#    instead of leaving it for divergence.
printf 'validate:\n  defaults: {T: 1.0, dt: 0.01}\n  points:\n    b: {eps: 1.0e9}\n' > v9.yaml
one_line v1 3 "point 'b' (eps = 1000000000): the full model failed: Newton did not converge .*; it stalled at .*allowed: a larger integrator.newtonTolerance" \
  "validate on one rank, a stalling point" -- timeout 60 "$gphr" validate m.h5 v9.yaml --output v1

# 7. Different inputs per rank (MPMD: each rank its own arguments) are named as a disagreement
#    before any work, not found later as another error: two model files of different checksums,
#    and a model file that rank 1 cannot find (it said "cannot open ...: no such file").
sed 's/points: \[3\]/points: [2]/' b.yaml > b2.yaml
"$gphr" build b2.yaml --model m2.h5 --output art2 > /dev/null 2> build2.err || { cat build2.err; fail "second build"; }
printf 'queries:\n  points:\n    a: {eps: 1.0}\n' > q1.yaml
mpmd() { timeout 60 "$mpiexec" --allow-run-as-root --oversubscribe -np 1 "$gphr" query "$1" q1.yaml --output "$3" : \
  -np 1 "$gphr" query "$2" q1.yaml --output "$3"; }
one_line mpmd1 2 "the ranks read different contents of reduced-model file 'm.h5'" "two model files" -- mpmd m.h5 m2.h5 mp1
[ ! -e mp1 ] || fail "two model files: the output directory was made"
one_line mpmd2 2 "reduced-model file 'missing.h5': cannot open .*(on rank 1; 1 of the 2 ranks read it: the ranks do not see the same input)" \
  "a model file rank 1 lacks" -- mpmd m.h5 missing.h5 mp2
