#!/usr/bin/env bash
# Installs GPHR's Debian 12 dependencies (only what is missing), configures and builds GPHR in
# ./build (Release, Ninja, ccache). Idempotent and quick when nothing changed. Run as root.
#
# Options:
#   --docs   also install doxygen (Debian's), for the API reference (`cmake --build build --target doc`)
#            and its check, the ctest test doc_undocumented. The same as GPHR_DOCS=1 in the
#            environment. Without it nothing about doxygen changes (an installed one is kept).
#   --tests  everything the whole test suite needs (the README's test command, .ci/run): what
#            --docs installs, plus Debian's paraview and python3-paraview (pvbatch and ParaView's
#            XDMF Reader, for the ctest test cli_field_paraview; ~190 MB, ~190 packages). The same
#            as GPHR_TESTS=1 in the environment.
set -euo pipefail
cd "$(dirname "$0")/.."

docs="${GPHR_DOCS:-0}"
tests="${GPHR_TESTS:-0}"
for arg in "$@"; do
  case "$arg" in
    --docs) docs=1 ;;
    --tests) tests=1 ;;
    *) echo "[setup] unknown option '$arg' (allowed: --docs, --tests)" >&2; exit 2 ;;
  esac
done
if [ "$tests" = 1 ]; then docs=1; fi

packages=(build-essential cmake ninja-build ccache gnuplot-nox hdf5-tools python3 python3-h5py
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libgtest-dev libopenblas-dev
  libtrilinos-teuchos-dev libtrilinos-kokkos-dev libtrilinos-kokkos-kernels-dev
  libtrilinos-tpetra-dev libtrilinos-belos-dev libtrilinos-anasazi-dev libtrilinos-nox-dev
  libtrilinos-epetra-dev libtrilinos-epetraext-dev libtrilinos-triutils-dev libtrilinos-aztecoo-dev
  libtrilinos-xpetra-dev libtrilinos-thyra-dev libtrilinos-rtop-dev libtrilinos-stratimikos-dev
  libtrilinos-ifpack2-dev libtrilinos-amesos2-dev libtrilinos-shylu-dev libtrilinos-zoltan-dev
  libtrilinos-zoltan2-dev libtrilinos-teko-dev libtrilinos-ml-dev libtrilinos-ifpack-dev
  libtrilinos-amesos-dev libtrilinos-galeri-dev libtrilinos-isorropia-dev libtrilinos-trilinosss-dev
  libscotch-dev libptscotch-dev)
if [ "$docs" = 1 ]; then packages+=(doxygen); fi
if [ "$tests" = 1 ]; then packages+=(paraview python3-paraview); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[setup] installing ${#missing[@]} Debian package(s): ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
fi

# mpirun as root (CI, containers) needs these; harmless otherwise (PLATFORM.md).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
# An existing build configured before doxygen was installed: configure again to add `doc`.
if [ "$docs" = 1 ] && ! grep -qs doc_undocumented build/CTestTestfile.cmake; then
  cmake -S . -B build > /dev/null
fi
# The project's own sources build without a warning (-Wall -Wextra; Trilinos' headers are system
# includes, whatever GCC reports from inside them is theirs): a warning located in the project's
# files fails the set-up, so a fresh build (CI's) keeps them clean.
log=$(mktemp)
status=0
cmake --build build -j "$(nproc)" 2>&1 | tee "$log" || status=$?
[ "$status" -eq 0 ] || { rm -f "$log"; exit "$status"; }  # pipefail: the build's own status
if grep -E "^$(pwd)/(packages|test|bench|examples|cmake)/[^:]+:[0-9]+(:[0-9]+)?: warning:" "$log" > /dev/null; then
  grep -E "^$(pwd)/(packages|test|bench|examples|cmake)/[^:]+:[0-9]+(:[0-9]+)?: warning:" "$log" >&2
  echo "[setup] the build warned in the project's own sources (above); allowed: none" >&2
  rm -f "$log"
  exit 1
fi
rm -f "$log"
