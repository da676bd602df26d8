#!/usr/bin/env bash
# GP-ADEIM benchmarks at the paper's NLS settings (Sec. 5.2: n = 2048, T = 30, dt = 0.01, AVF,
# eps = 1.0932, 2k = 400, m = 100, 11 training parameters for the non-adaptive DEIM basis):
#   nls        one run: GP-DEIM (non-adaptive) and GP-ADEIM (m_s = 250, delta0 = delta = gamma = 5,
#              w = 1, r by tau_r = 1e-12, the default) side by side, with the ROM: tab:taur's first rows
#   taur       one run per tau_r in 1e-4 .. 1e-12                          (tab:taur)
#   taus       m_s chosen by tau_s (relative to the largest row score)     (tab:taus)
#   w          window w in 1, 2, 3 (delta0 = 5 > w)                        (tab:w)
#   delta      delta = delta0 in 5, 10, 20                                 (tab:delta)
#   gamma      gamma in 5, 10, 20, 50                                      (tab:gamma)
#   sampling   random / residual / projected rules, m_s in 150, 300, r = r-bar (fig:schro_samplingstrats)
#   updatetol  adeim.updateTol in 3e-6 .. 4e-5 (the indicator's 10th to 95th percentile here): updates
#              skipped while the DEIM fit's relative residual at the sampling rows stays below it
#              (its accuracy-vs-time curve; 0, the paper's rule, is the nls case)
#   ctime      E_L2 vs m and vs total time, 2k in 160, 280, 400, adaptive and not (fig:error_vs_ctime_2k400);
#              tau_r = 1e-12 as the paper sets for these figures (m_s = 250 stands in for its absolute tau_s = 1e-10)
# The residual monitor (an extra O(d) product per update) is off except for the sampling case,
# which plots it. Training, basis and the non-adaptive DEIM basis are computed once into bench-out/adeim_base_np<R>
# (reused by every run: copied into each run's directory; refreshed by a run that had to train
# again). Each run prints one line per GP-DEIM / GP-ADEIM model: E_L2, Delta H at the final time,
# t_off, t_on, t_tot (the paper's columns).
# usage: bash bench/adeim_paper.sh CASE [RANKS] [BUILD_DIR]
#   GPHR_BASE_RANKS=R2: take the cached training, basis and DEIM basis of R2 ranks (trained there
#   once) for a run on RANKS, so that only the online phase changes rank count; the outputs then go
#   to bench-out/adeim_<case>_np<RANKS>_base<R2>.
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
case=$1; np=${2:-2}; build=${3:-build}
gphr=$build/packages/driver/gphr
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(machine_line "$gphr"); ranks $np; case $case${GPHR_BASE_RANKS:+; offline artifacts of $GPHR_BASE_RANKS ranks}"
baseNp=${GPHR_BASE_RANKS:-$np}
base=bench-out/adeim_base_np$baseNp
suffix=$([ "$baseNp" = "$np" ] && echo "" || echo "_base$baseNp")
if [ -n "$suffix" ] && [ ! -s "$base/artifacts.h5" ]; then
  echo "GPHR_BASE_RANKS=$baseNp: no $base/artifacts.h5 (run a case on $baseNp ranks first)" >&2; exit 2
fi
mkdir -p "$base"

# config BODY_YAML_LINES -> stdout: the paper's NLS set-up plus the given lines (under gphr:)
config() {
  local plots=false
  case $case in ctime|sampling) plots=true ;; esac  # their figures: error_vs_total_time.png, adeim_updates.png
  sed -e "s|^  integrator:.*|  integrator: {scheme: avf, jacobianLag: true}|" -e "s|plots: false|plots: $plots|" \
    bench/configs/nls_paper.yaml
  cat <<YAML
  training: {points: [11], snapshotEvery: 10}
  reduction: {k: 200}
  hyper: {snapshotEvery: 2, svd: randomized, maxRank: 110, powerIterations: 0}
YAML
  printf '%s\n' "$@"
}

# CPU ticks (all, and stolen by the hypervisor) from /proc/stat: the steal share during a run says
# how much of the machine another guest took, which moves every time printed here.
cpu_ticks() { awk '/^cpu /{s = 0; for (i = 2; i <= 9; i++) s += $i; print s, $9}' /proc/stat; }

run() {  # run NAME YAML_LINES...: one gphr run in bench-out/adeim_<case>_np<R>/NAME, artifacts from base
  local name=$1; shift
  local out=bench-out/adeim_${case}_np$np$suffix/$name
  mkdir -p "$out"
  config "$@" > "$out.yaml"  # beside the output: gphr refuses to write over its input
  [ -s "$base/artifacts.h5" ] && cp "$base/artifacts.h5" "$out/artifacts.h5"
  local before after
  before=$(cpu_ticks)
  local rc=0
  if [ "$np" -eq 1 ]; then "$gphr" run "$out.yaml" --output "$out" --verbose > "$out/run.log" 2>&1 || rc=$?
  else mpirun --oversubscribe -np "$np" "$gphr" run "$out.yaml" --output "$out" --verbose > "$out/run.log" 2>&1 || rc=$?; fi
  if [ "$rc" -ne 0 ]; then echo "$name: gphr exited with $rc; $out/run.log ends:" >&2; grep -m3 "error" "$out/run.log" >&2; exit 1; fi
  after=$(cpu_ticks)
  # A run that had to train again (the training or integrator config differs from the cached
  # artifacts', e.g. after a new integrator default) refreshes the cache for the runs after it
  # (the cache of its own rank count only: one borrowed by GPHR_BASE_RANKS stays as it was).
  if [ -n "$suffix" ] && grep -q "training again" "$out/run.log"; then
    echo "$name: the borrowed artifacts of $baseNp ranks did not fit this config and it trained on $np ranks:" \
         "not the comparison GPHR_BASE_RANKS asks for" >&2; exit 3
  fi
  if [ -z "$suffix" ] && { [ ! -s "$base/artifacts.h5" ] || grep -q "training again" "$out/run.log"; }; then
    cp "$out/artifacts.h5" "$base/artifacts.h5"
  fi
  python3 - "$out/summary.json" "$name" "$out/adeim_updates.csv" <<'PY'
import csv, json, os, sys
s = json.load(open(sys.argv[1])); name = sys.argv[2]
fom = s["runs"][0]
for r in s["runs"][1:]:
    if r["method"] not in ("gp-deim", "gp-adeim", "rom"):
        continue
    g = lambda k: r.get(k) if r.get(k) is not None else float("nan")
    extra = ""
    if r["method"] == "gp-adeim":
        extra = " updates %d rank %.1f m_s %.0f t_upd %.2f" % (g("updates"), g("update_rank_mean"), g("num_samples_mean"), g("t_updates_s"))
        if r.get("updates_skipped"):
            extra += " skipped %d" % r["updates_skipped"]
        # adeim.updateTol's indicator where it was computed: its 5th, 50th and 95th percentiles
        ind = sorted(float(x["indicator"]) for x in csv.DictReader(open(sys.argv[3])) if float(x["indicator"]) >= 0
                     and int(x["k"]) == r["k"] and int(x["m"]) == r["m"]) if os.path.exists(sys.argv[3]) else []
        if ind:
            q = lambda f: ind[min(len(ind) - 1, int(f * len(ind)))]
            extra += " indicator p5/p50/p95 %.2e/%.2e/%.2e" % (q(0.05), q(0.5), q(0.95))
    print("%-14s %-8s 2k=%3d m=%3s %-9s E_L2 %.3e dH_T %.3e t_off %7.2f t_on %7.2f t_tot %7.2f (FOM %.2f)%s"
          % (name, r["method"], 2 * r["k"], r.get("m", "-"), r["status"], g("E_L2"), g("H_err_final"),
             g("t_hyper_offline_s"), g("t_online_s"), g("t_total_s"), fom["t_online_s"], extra))
PY
  # The per-stage roofline of the GP-ADEIM update (the NLS scene's sizes; run.log holds the timer table).
  if grep -q "gphr: gp-adeim window at P" "$out/run.log" && [ -s "$calibration.before" ]; then
    python3 bench/adeim_roofline.py "$out/run.log" "$out/summary.json" "$out.yaml" "$np" "$calibration.before"
  fi
  echo "$before $after" | awk -v n="$name" '{t = $3 - $1; if (t > 0) printf "%-14s machine: %.1f%% of the CPU time stolen by the hypervisor during this run\n", n, 100 * ($4 - $2) / t}'
}

adeim() {  # adeim "KEY: VALUE, ..." -> the adeim section: the paper's settings, the given keys instead
  local d="initialWindow: 5, updateEvery: 5, window: 1, resampleEvery: 5, numSamples: 250, rankTol: 1.0e-12, monitorResidual: false" k
  for k in $(echo "$1" | grep -o '[A-Za-z]*:' | tr -d :); do d=$(echo "$d" | sed -E "s/(^|, )$k: [^,]*//; s/^, //"); done
  echo "  adeim: {$d, $1}"
}

# The machine's speed at the update's dense algebra, before and after the case: this machine's
# speed has swung by half from hour to hour (shared host), and the adaptive runs' times with it.
# The same code printed factorCoefficients 2.35-3.18 ms and computeAdeimUpdate 3.54-3.62 ms in quiet
# hours, when the paper run took 10.9-15.3 s; 3.4 and 6.0 ms in a slow hour (doc/benchmarks.md,
# 'adeim_update_micro').
calibration=bench-out/adeim_${case}_np$np$suffix/calibration
calibrate() {
  if [ -x "$build/bench/adeim_update_micro" ]; then
    mkdir -p "$(dirname "$calibration")"
    "$build/bench/adeim_update_micro" 100 > "$calibration.$1"
    echo "calibration ($1): $(cat "$calibration.$1")"
  fi
}
calibrate before
trap 'calibrate after' EXIT

case $case in
  nls) run main "  pipeline: {rom: true, methods: [rom, gp-deim, gp-adeim], m: [100]}" "$(adeim "sampling: projected")" ;;
  taur) for t in 1.0e-4 1.0e-6 1.0e-8 1.0e-10 1.0e-12; do
          run "taur_$t" "  pipeline: {methods: [gp-adeim], m: [100]}" "$(adeim "rankTol: $t")"; done ;;
  taus) for t in 1.0e-1 1.0e-2 1.0e-3 1.0e-4; do
          run "taus_$t" "  pipeline: {methods: [gp-adeim], m: [100]}" \
            "$(adeim "numSamples: 0, sampleTol: $t, maxSamples: 2048")"; done ;;
  w) for w in 1 2 3; do run "w_$w" "  pipeline: {methods: [gp-adeim], m: [100]}" "$(adeim "window: $w")"; done ;;
  delta) for d in 5 10 20; do
           run "delta_$d" "  pipeline: {methods: [gp-adeim], m: [100]}" \
             "$(adeim "initialWindow: $d, updateEvery: $d, resampleEvery: $d")"; done ;;
  gamma) for g in 5 10 20 50; do run "gamma_$g" "  pipeline: {methods: [gp-adeim], m: [100]}" "$(adeim "resampleEvery: $g")"; done ;;
  sampling) for ms in 150 300; do for rule in random residual projected; do
              run "${rule}_$ms" "  pipeline: {methods: [gp-adeim], m: [100]}" \
                "$(adeim "numSamples: $ms, rankTol: 0.0, sampling: $rule, monitorResidual: true")"; done; done ;;
  updatetol) for t in ${UPDATE_TOLS:-3.0e-6 1.0e-5 2.0e-5 4.0e-5}; do
               run "updatetol_$t" "  pipeline: {methods: [gp-adeim], m: [100]}" "$(adeim "updateTol: $t")"; done ;;
  ctime) run ctime "  pipeline: {methods: [gp-deim, gp-adeim], k: [80, 140, 200], m: [${M_CTIME:-25, 50, 100}]}" \
           "$(adeim "sampling: projected")" ;;
  *) echo "unknown case $case"; exit 2 ;;
esac
