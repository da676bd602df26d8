#!/usr/bin/env bash
# A full disk while gphr writes its HDF5 files (a 64 KiB tmpfs, nearly filled): exit 2 with one
# gphr line naming the file and the system's reason, no crash (HDF5 1.10 crashes in MPI_Finalize
# on a file it failed to close: gphr then ends without finalizing), no hang, and no partial file
# left. Skipped (77) where this machine does not let the test mount a tmpfs.
# usage: disk_full.sh GPHR MPIEXEC SMALL_MODEL_CONFIG
set -u
gphr=$1; mpiexec=$2; modelConfig=$3
export OPENBLAS_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d)
mkdir "$work/full"
mount -t tmpfs -o size=64k tmpfs "$work/full" 2> /dev/null || { rm -rf "$work"; echo "cannot mount a tmpfs here: skipped"; exit 77; }
trap 'umount "$work/full"; rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
"$gphr" build "$modelConfig" --model m.h5 --output art > /dev/null 2> build.err || fail "build: $(cat build.err)"
printf 'queries:\n  defaults: {T: 1.0, dt: 0.01, k: 6, m: 12}\n  points:\n    a: {eps: 1.0}\n' > q.yaml
# full CASE KBYTES CMD...: with KBYTES of the 64 filled, CMD exits 2 with one gphr line saying the
# disk is full, and leaves nothing but the filler.
full() {
  local name=$1 kb=$2; shift 2
  rm -rf full/* art2; head -c "${kb}k" /dev/zero > full/filler
  timeout -k 5 60 "$@" > "$name.out" 2> "$name.err"
  local rc=$?
  [ $rc -eq 2 ] || fail "$name: exit code $rc, expected 2 (124: hung, 139: crashed): $(grep -v mca_fbtl "$name.err" | tail -5)"
  [ "$(grep -c '^gphr:' "$name.err")" -eq 1 ] || fail "$name: not one gphr line: $(cat "$name.err")"
  grep -q "^gphr: error: .*No space left on device" "$name.err" || fail "$name: the reason is not named: $(cat "$name.err")"
  [ "$(cd full && find . -type f ! -name filler | wc -l)" -eq 0 ] || fail "$name: left $(cd full && find . -type f)"
  echo "ok ($name): $(grep '^gphr:' "$name.err")"
}
full query 60 "$gphr" query m.h5 q.yaml --output full/q
full build 40 "$gphr" build "$modelConfig" --model full/m.h5 --output art2
full build_np2 40 "$mpiexec" -np 2 "$gphr" build "$modelConfig" --model full/m.h5 --output art2
