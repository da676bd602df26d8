#!/usr/bin/env bash
# Benchmark of the full model at the paper's configurations, side by side in
# one run: NLS/AVF, SWE/IMR, SWE/AVF on 1 and 2 MPI ranks, each with both Newton drivers
# (integrator.newtonSolver: nox and gphr), next to the paper's MATLAB times, plus a short
# preconditioner comparison (T shortened) that justifies the default.
# usage: bash bench/fom_paper.sh [BUILD_DIR] [all|paper|pc|reuse]   (prints tables; raw summaries in bench-out/)
#   paper: per configuration one row, NOX's wall seconds (t_online_s), CPU seconds of the whole run
#          (all ranks, incl. setup; steadier than wall time on a shared machine), Newton iterations
#          per step and GMRES iterations per Newton iteration, beside GPHR's loop's
#          (speedup: paper_s / NOX's wall_s)
#   reuse: linearSolver.preconditionerRecomputeEvery in {1, 5, 20, 100}, SWE IMR T = 0.5 and NLS AVF T = 2
#   pc:    preconditioners at the paper sizes (AVF, T = 2), then on the training run of bench/scaling.sh's
#          SWE case (256^2, IMR with the lagged Jacobian, T = 0.4; PC_NX=512 for another grid) on 1 and 2
#          ranks: the SWE's default
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
build=${1:-build}; part=${2:-all}
gphr=$build/packages/driver/gphr
out=bench-out; mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(machine_line "$gphr")"

run() {  # run NAME CONFIG RANKS [INTEGRATOR_LINE] [TIME_LINE] [SCENE_LINE]: replace those lines of CONFIG
  local name=$1 cfg=$2 np=$3 integ=${4:-} time=${5:-} scene=${6:-}
  local c=$out/$name.yaml
  cp "$cfg" "$c"
  [ -n "$scene" ] && sed -i "s|^  scene:.*|  scene: $scene|" "$c"
  [ -n "$integ" ] && sed -i "s|^  integrator:.*|  integrator: $integ|" "$c"
  [ -n "$time" ] && sed -i "s|^  time:.*|  time: $time|" "$c"
  local TIMEFORMAT='%U %S'  # CPU seconds (user, system) of the run, all ranks: $out/NAME.cpu
  if [ "$np" -eq 1 ]; then { time "$gphr" run "$c" --output "$out/$name" > "$out/$name.log" 2>&1; } 2> "$out/$name.cpu"
  else { time mpirun --oversubscribe -np "$np" "$gphr" run "$c" --output "$out/$name" > "$out/$name.log" 2>&1; } 2> "$out/$name.cpu"; fi
}
row() {  # row NAME PAPER_SECONDS
  python3 - "$out/$1/summary.json" "$1" "$2" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); r = s["runs"][0]; paper = sys.argv[3]
ratio = f"{float(paper) / r['t_online_s']:.1f}x" if paper != "-" else "-"
print(f"{sys.argv[2]:<28} {r['ranks']:>5} {r['steps']:>6} {r['t_online_s']:>9.1f} {r['newton_iters_avg']:>9.2f} "
      f"{r['linear_iters_per_newton']:>10.2f} {r['H_err_max_rel']:>10.1e} {paper:>9} {ratio:>9}")
PY
}
drivers() {  # drivers NAME CONFIG RANKS PAPER_SECONDS [SCHEME]: both Newton drivers, one row side by side
  local name=$1 cfg=$2 np=$3 paper=$4 scheme=${5:-avf} d
  for d in nox gphr; do run ${name}_$d "$cfg" "$np" "{scheme: $scheme, newtonSolver: $d}"; done
  python3 - "$out/${name}_nox" "$out/${name}_gphr" "$name" "$paper" <<'PY'
import json, sys
def load(d): return json.load(open(d + "/summary.json"))["runs"][0], sum(map(float, open(d + ".cpu").read().split()))
(a, ca), (b, cb) = load(sys.argv[1]), load(sys.argv[2]); paper = sys.argv[4]
ratio = f"{float(paper) / a['t_online_s']:.1f}x" if paper != "-" else "-"
def cols(r, c): return f"{r['t_online_s']:>7.1f} {c:>6.1f} {r['newton_iters_avg']:>6.2f} {r['linear_iters_per_newton']:>6.2f}"
print(f"{sys.argv[3]:<12} {a['ranks']:>5} {a['steps']:>5} | {cols(a, ca)} | {cols(b, cb)} | {a['H_err_max_rel']:>8.1e} "
      f"{b['H_err_max_rel']:>8.1e} {paper:>7} {ratio:>7}")
PY
}
if [ "$part" = paper ] || [ "$part" = all ]; then
  printf '%-12s %5s %5s | %-28s | %-28s | %-17s\n' "" "" "" "NOX" "GPHR's loop (default)" "H_err_rel"
  printf '%-12s %5s %5s | %7s %6s %6s %6s | %7s %6s %6s %6s | %8s %8s %7s %7s\n' run ranks steps wall_s cpu_s nwt/st \
    lin/nw wall_s cpu_s nwt/st lin/nw nox gphr paper_s speedup
  for np in 1 2; do
    drivers nls_avf_np$np bench/configs/nls_paper.yaml $np 220
    drivers swe_imr_np$np bench/configs/swe_paper.yaml $np 297.29 imr
    drivers swe_avf_np$np bench/configs/swe_paper.yaml $np 414.10
  done
  [ "$part" = paper ] && exit 0
  echo
fi
printf '%-28s %5s %6s %9s %9s %10s %10s %9s %9s\n' run ranks steps wall_s newton/st lin/newton H_err_rel paper_s speedup
if [ "$part" = reuse ]; then
  for r in 1 5 20 100; do
    run swe_reuse_$r bench/configs/swe_paper.yaml 1 "{scheme: imr, linearSolver: {preconditionerRecomputeEvery: $r}}" "{T: 0.5, dt: 0.005}"
    row swe_reuse_$r -
    run nls_reuse_$r bench/configs/nls_paper.yaml 1 "{scheme: avf, linearSolver: {preconditionerRecomputeEvery: $r}}" "{T: 2.0, dt: 0.01}"
    row nls_reuse_$r -
  done
  exit 0
fi
echo "preconditioner comparison (1 rank, T shortened to 2):"
for pc in RILUK AMESOS2 RELAXATION none; do
  run nls_pc_$pc bench/configs/nls_paper.yaml 1 "{scheme: avf, linearSolver: {preconditioner: $pc, maxIterations: 2000}}" "{T: 2.0, dt: 0.01}"
  row nls_pc_$pc -
  run swe_pc_$pc bench/configs/swe_paper.yaml 1 "{scheme: avf, linearSolver: {preconditioner: $pc, maxIterations: 2000}}" "{T: 2.0, dt: 0.005}"
  row swe_pc_$pc -
done
nx=${PC_NX:-256}
echo "preconditioner comparison on the training run of bench/scaling.sh's SWE case (${nx}^2, IMR, lagged Jacobian, T = 0.4;"
echo "RELAXATION sweeps forward Gauss-Seidel, RELAXATION-sym symmetric Gauss-Seidel):"
for pc in RILUK RELAXATION RELAXATION-sym none; do
  ls="preconditioner: ${pc%-sym}"
  [ "$pc" = RELAXATION-sym ] && ls="$ls, relaxation: Symmetric Gauss-Seidel"
  for np in 1 2; do
    run swe${nx}_pc_${pc}_np$np bench/configs/swe_paper.yaml $np \
      "{scheme: imr, jacobianLag: true, linearSolver: {$ls}}" "{T: 0.4, dt: 0.005}" "{name: swe2d, nx: $nx}"
    row swe${nx}_pc_${pc}_np$np -
  done
done
