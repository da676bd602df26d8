#!/usr/bin/env bash
# Installs GPHR from the build tree into a temporary prefix, builds examples/embedding
# (GPHR::evaluation: it trains greedily to a target error, builds and writes a model file of its
# own three-parameter scene with the offline library, queries it, and measures each query's E_L2 against the full model) and examples/query
# (GPHR::online) - their link lines are printed and must name the libraries they use and none of
# the application's, gphr_driver - against the *installed* package, from projects that
# enable LANGUAGES CXX only, as a C++-only consumer would; runs the embedding on 1 and 2 ranks, and
# the query program on a model file written by the installed `gphr build`.
# usage: check_install.sh BUILD_DIR SOURCE_DIR MPIEXEC
set -euo pipefail
build=$1; src=$2; mpiexec=$3
# The consumer must stay C++-only, or this test stops catching a config that needs language C.
grep -q "^project(gphr_embedding LANGUAGES CXX)$" "$src/examples/embedding/CMakeLists.txt" \
  || { echo "FAIL: examples/embedding must declare LANGUAGES CXX only"; exit 1; }
grep -q "^project(gphr_query LANGUAGES CXX)$" "$src/examples/query/CMakeLists.txt" \
  || { echo "FAIL: examples/query must declare LANGUAGES CXX only"; exit 1; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > /dev/null
test -f "$work/prefix/lib/cmake/GPHR/GPHRConfig.cmake"
test -f "$work/prefix/include/gphr/core/HamiltonianSystem.hpp"
# consumer LABEL SOURCE BUILD TARGET LIBS...: configures and builds the project SOURCE against the
# installed package, prints TARGET's link line and fails unless it names each of LIBS and not the
# application's library gphr_driver.
consumer() {
  local label=$1 source=$2 dir=$3 target=$4; shift 4
  cmake -S "$source" -B "$dir" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/cfg.log" \
    || { cat "$work/cfg.log"; exit 1; }
  cmake --build "$dir" -v > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
  local link
  link=$(grep -E -- "-o $target( |$)" "$work/build.log" | tail -1)
  echo "$label link line: $link"
  for lib in "$@"; do [[ "$link" == *"$lib"* ]] || { echo "FAIL: $label does not link $lib"; exit 1; }; done
  [[ "$link" != *gphr_driver* ]] || { echo "FAIL: $label links the application's library gphr_driver"; exit 1; }
}
consumer examples/embedding "$src/examples/embedding" "$work/embed" fpu_lattice libgphr_evaluation.a \
  libgphr_offline.a libgphr_online.a
# The greedy training meets its target with fewer full solves than the 3 x 3 x 3 grid, and each
# of the three queries reports its E_L2 from the evaluation library and both estimates (within
# 3x), on 1 and 2 ranks.
embed() {
  (cd "$work" && "$@") | tee "$work/embed.txt"
  local solves
  solves=$(sed -n 's/.*greedy training to E_L2 <= 1e-02 over the box: \([0-9]*\) full solves .* target met; query default gp-deim k = 16, m = [0-9]*:.*/\1/p' "$work/embed.txt")
  [ -n "$solves" ] && [ "$solves" -lt 27 ] \
    || { echo "FAIL: the embedding's greedy training did not meet its target with fewer than 27 full solves"; exit 1; }
  [ "$(grep -c 'E_L2 = [0-9.e+-]* (ok), estimated [0-9.e+-]* (full residual), [0-9.e+-]* (the query.s error_estimate) -> ok' "$work/embed.txt")" -eq 3 ] \
    || { echo "FAIL: the embedding does not report 3 queries with E_L2 and status ok"; exit 1; }
}
embed "$work/embed/fpu_lattice" fpu1.h5
embed "$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$work/embed/fpu_lattice" fpu2.h5
# examples/query on a model built by the installed gphr.
consumer examples/query "$src/examples/query" "$work/query" query_model libgphr_online.a
# The umbrella GPHR::gphr: every library but the application's, whose library and headers are not
# installed (the gphr executable is).
[ ! -e "$work/prefix/include/gphr/driver" ] && ! ls "$work/prefix/lib/"libgphr_driver* > /dev/null 2>&1 \
  || { echo "FAIL: the application's library or headers are installed"; exit 1; }
mkdir -p "$work/umbrella"
cp "$src/examples/query/query_model.cpp" "$work/umbrella/"
sed 's/GPHR::online/GPHR::gphr/; s/project(gphr_query /project(gphr_umbrella /' "$src/examples/query/CMakeLists.txt" \
  > "$work/umbrella/CMakeLists.txt"
consumer GPHR::gphr "$work/umbrella" "$work/umbrella/build" query_model libgphr_offline.a libgphr_online.a
cp "$src/test/support/small_nls_model.yaml" "$work/build.yaml"
(cd "$work" && OPENBLAS_NUM_THREADS=1 "$work/prefix/bin/gphr" build build.yaml --model model.h5 --output art > /dev/null)
"$work/query/query_model" "$work/model.h5" 0.92 1.0 1.08
"$work/umbrella/build/query_model" "$work/model.h5" 1.0
