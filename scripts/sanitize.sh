#!/usr/bin/env bash
# Builds gphr with AddressSanitizer and UndefinedBehaviorSanitizer in ./build-asan and runs the
# hostile-input tests with it (cli_model_file_fuzz's script, the output-directory and write-error
# checks, three bad configs): any memory error or undefined behaviour ends gphr with a non-zero
# exit code, which those tests report. Leak detection is off (Open MPI's own allocations at exit).
# Cost on the 2-core development VM: about 10 minutes to build, 2 minutes to run.
# usage: scripts/sanitize.sh   (after bash scripts/setup.sh, which installs the dependencies)
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
[ -f build-asan/build.ninja ] || cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGPHR_ENABLE_TESTS=OFF -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > /dev/null
cmake --build build-asan -j "$(nproc)" --target gphr_cli
gphr=build-asan/packages/driver/gphr
mpiexec=$(command -v mpiexec)
bash test/cli/model_file_fuzz.sh "$gphr" "$mpiexec"
bash test/cli/query_output_dir.sh "$gphr"
bash test/cli/run_write_errors.sh "$gphr" "$mpiexec"
for c in negative_n malformed_yaml fom_newton; do bash test/cli/bad_input.sh "$gphr" "$c" > /dev/null; done
echo "sanitized gphr: every hostile-input check passed"
