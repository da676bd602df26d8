#!/usr/bin/env bash
# Installs GPHR from the build tree into a temporary prefix, builds examples/embedding against
# the *installed* package (find_package(GPHR) + GPHR::gphr only, from a project that enables
# LANGUAGES CXX only, as a C++-only consumer would), and runs it on 1 and 2 ranks.
# usage: check_install.sh BUILD_DIR SOURCE_DIR MPIEXEC
set -euo pipefail
build=$1; src=$2; mpiexec=$3
# The consumer must stay C++-only, or this test stops catching a config that needs language C.
grep -q "^project(gphr_embedding LANGUAGES CXX)$" "$src/examples/embedding/CMakeLists.txt" \
  || { echo "FAIL: examples/embedding must declare LANGUAGES CXX only"; exit 1; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > /dev/null
test -f "$work/prefix/lib/cmake/GPHR/GPHRConfig.cmake"
test -f "$work/prefix/include/gphr/core/HamiltonianSystem.hpp"
cmake -S "$src/examples/embedding" -B "$work/embed" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/cfg.log" \
  || { cat "$work/cfg.log"; exit 1; }
cmake --build "$work/embed" > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
"$work/embed/fpu_lattice"
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$work/embed/fpu_lattice"
