#!/usr/bin/env bash
# gphr run into an output directory that cannot take its report (a full disk: the report's
# temporary file is /dev/full): exit 2 on every rank with one gphr line naming the file, no
# summary.json (the mark of a complete run), no hang; on 1 and 2 ranks.
# usage: run_write_errors.sh GPHR MPIEXEC
set -u
gphr=$1; mpiexec=$2
export OPENBLAS_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; [ -f "$work/err" ] && { echo "--- stderr:"; tail -5 "$work/err"; }; exit 1; }
printf 'gphr:\n  scene: {name: nls1d, n: 64}\n  time: {T: 0.1, dt: 0.01}\n' > "$work/c.yaml"
for ranks in 1 2; do
  out=$work/out$ranks
  mkdir -p "$out" && ln -s /dev/full "$out/summary.json.partial.tmp"
  if [ $ranks -eq 1 ]; then launch=(); else launch=("$mpiexec" -np 2); fi
  timeout -k 5 120 "${launch[@]}" "$gphr" run "$work/c.yaml" --output "$out" < /dev/null > /dev/null 2> "$work/err"
  rc=$?
  [ $rc -eq 2 ] || fail "$ranks rank(s): exit $rc, expected 2"
  [ "$(grep -c '^gphr' "$work/err")" -eq 1 ] || fail "$ranks rank(s): not one gphr line"
  grep -q "^gphr: error: gphr run: the report: cannot write '$out/summary.json.partial.tmp'" "$work/err" \
    || fail "$ranks rank(s): the message does not name the file"
  [ ! -e "$out/summary.json" ] || fail "$ranks rank(s): summary.json written"
done
echo ok
