#!/usr/bin/env bash
# fields.xdmf of `gphr run` (swe2d on 2 ranks, nls1d) and queries/<name>.xdmf of `gphr query`
# opened by ParaView's own XDMF Reader (pvbatch, paraview_read.py): the times, the arrays, the
# grid, and every value as in the HDF5 file. `setup.sh --tests` (the README's test command, CI)
# installs Debian's paraview and python3-paraview. Without a working pvbatch the test is skipped
# (exit 77; check_xdmf.py's XML / HDF5 checks in field_output.sh stand alone), except under
# CI=true, where it fails: there a broken install step must not hide behind a skip.
# pvbatch runs headless (no DISPLAY, no X server: the reader renders nothing) and with --no-mpi:
# one serial reader needs no MPI, and without the flag each pvbatch starts MPI as a singleton,
# forking an orted of its own beside the mpirun jobs of tests ctest runs in parallel.
# usage: field_paraview.sh GPHR MPIEXEC
set -eu
gphr=$1; mpiexec=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
echo "import paraview.simple" > probe.py
if ! command -v pvbatch > /dev/null || ! pvbatch --no-mpi probe.py > probe.out 2>&1; then
  why="no ParaView pvbatch with its Python module (bash scripts/setup.sh --tests installs Debian's paraview and python3-paraview)"
  case "${CI:-}" in
    "" | 0 | false | False | FALSE) echo "skipped: $why"; exit 77 ;;
  esac
  [ ! -s probe.out ] || tail -n 20 probe.out
  echo "FAIL (CI=$CI, where ParaView is part of the test set-up): $why"
  exit 1
fi
read_back() { pvbatch --no-mpi "$here/paraview_read.py" "$@" 2> pv.err || { cat pv.err; exit 1; }; }
cat > swe.yaml <<'YAML'
gphr:
  scene: {name: swe2d, nx: 12}
  time: {T: 0.2, dt: 0.01}
  training: {points: [2, 2], snapshotEvery: 2}
  reduction: {k: 6}
  pipeline: {rom: true, methods: [rom, gp-deim], m: [24]}
  hyper: {snapshotEvery: 2}
  output: {saveEvery: 5, xdmf: true, plots: false}
YAML
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$gphr" run swe.yaml --output swe > /dev/null 2> swe.err || { cat swe.err; exit 1; }
read_back swe/fields.xdmf /fom/times -2,-2,0 0.3333333333333333,0.3333333333333333,1
cat > nls.yaml <<'YAML'
gphr:
  scene: {name: nls1d, n: 64}
  time: {T: 0.5, dt: 0.01}
  training: {points: [3]}
  pipeline: {methods: [gp-deim], k: [6], m: [12]}
  hyper: {snapshotEvery: 5}
  build: {withBasis: true}
  output: {saveEvery: 10, xdmf: true, plots: false}
YAML
"$gphr" run nls.yaml --output nls > /dev/null 2> nls.err || { cat nls.err; exit 1; }
L=$(python3 -c "import math; print(repr(math.pi / 0.11))"); dx=$(python3 -c "import math; print(repr(2 * math.pi / 0.11 / 64))")
read_back nls/fields.xdmf /fom/times "-$L,0,0" "$dx,1,1"
"$gphr" build nls.yaml --model nls.h5 --output art > /dev/null 2> build.err || { cat build.err; exit 1; }
printf 'queries:\n  defaults: {T: 0.5, dt: 0.01, k: 6, m: 12, saveEvery: 10, states: true}\n  points:\n    s: {eps: 1.04}\n' > q.yaml
"$gphr" query nls.h5 q.yaml --output q > /dev/null 2> q.err || { cat q.err; exit 1; }
read_back q/queries/s.xdmf /saved_times "-$L,0,0" "$dx,1,1"
echo ok
