#!/usr/bin/env bash
# Runs the test suite under every OpenBLAS kernel this CPU can execute, with 1 and 2 BLAS threads,
# and prints one line per combination (kernel, threads, passed/failed). Debian's OpenBLAS picks its
# kernels by CPU at run time (Prescott: SSE3; Haswell and Zen: AVX2; SkylakeX: AVX-512), so the
# last bits of a BLAS result differ between machines; no test may depend on them. A test that
# passes here on every kernel passes on any x86-64 CPU that Debian supports. It builds ./build first
# (the tests run against the tree as it is). See doc/portability.md.
#
# usage: scripts/portability.sh [--kernels "K ..."] [--threads "T ..."] [-- CTEST_ARGS...]
#   --kernels  the kernels to try (default: all of Prescott Haswell Zen SkylakeX the CPU supports;
#              one it cannot execute is refused, since OpenBLAS would die of an illegal instruction)
#   --threads  OPENBLAS_NUM_THREADS values (default "1 2")
#   CTEST_ARGS passed to ctest, e.g. -R cli_ to run a subset (default: the whole suite, -j2)
# Needs a configured and built ./build (bash scripts/setup.sh). Exit 0 when every run passed.
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/openblas_kernels.sh

kernels=$(supported_kernels) threads="1 2" ctest_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --kernels) kernels=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --) shift; ctest_args=("$@"); break ;;
    *) echo "[portability] unknown option '$1' (allowed: --kernels, --threads, -- CTEST_ARGS)" >&2; exit 2 ;;
  esac
done
[ ${#ctest_args[@]} -gt 0 ] || ctest_args=(-j2)
[ -f build/CTestTestfile.cmake ] || { echo "[portability] no ./build: run bash scripts/setup.sh first" >&2; exit 2; }
for k in $kernels; do
  kernel_supported "$k" || { echo "[portability] kernel '$k' is not executable on this CPU (it can: $(supported_kernels))" >&2; exit 2; }
done
for t in $threads; do
  [[ "$t" =~ ^[1-9][0-9]*$ ]] || { echo "[portability] threads '$t': allowed, whole numbers >= 1" >&2; exit 2; }
done

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# The unit tests' thread count is a configure setting (ctest sets it per test): restore 1 at exit.
trap 'cmake -S . -B build -DGPHR_TEST_BLAS_THREADS=1 > /dev/null' EXIT
echo "[portability] CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); default kernel: $(openblas_kernel)"
summary=() failed=0
for t in $threads; do
  cmake -S . -B build -DGPHR_TEST_BLAS_THREADS="$t" > /dev/null || exit 2
  # the tree as it is: a binary built before the last commit names an older one (cli_provenance)
  cmake --build build -j2 > /dev/null || { echo "[portability] the build failed: run cmake --build build" >&2; exit 2; }
  for k in $kernels; do
    log=build/portability-$k-t$t.log
    start=$SECONDS
    OPENBLAS_CORETYPE=$k OPENBLAS_NUM_THREADS=$t ctest --test-dir build --output-on-failure "${ctest_args[@]}" > "$log" 2>&1
    rc=$?
    line=$(grep -E '^[0-9]+% tests passed' "$log" || echo "no ctest summary")
    failing=$(sed -n '/The following tests FAILED/,$p' "$log" | grep -E '^\s+[0-9]+ - ' | awk '{print $3}' | tr '\n' ' ')
    row=$(printf '%-9s threads %s  %-8s %s%s (%d s; log %s)' "$(OPENBLAS_CORETYPE=$k openblas_kernel)" "$t" \
          "$([ $rc -eq 0 ] && echo passed || echo FAILED)" "$line" "${failing:+; failed: $failing}" $((SECONDS - start)) "$log")
    echo "[portability] $row"
    summary+=("$row")
    [ $rc -eq 0 ] || failed=$((failed + 1))
  done
done
echo "[portability] summary:"
printf '  %s\n' "${summary[@]}"
echo "$(( ${#summary[@]} - failed )) passed, $failed failed"
[ $failed -eq 0 ]
