#!/usr/bin/env bash
# Benchmarks of the build / query / validate workflow (doc/model-file.md), each measured side by
# side in one script run, with the machine printed:
#   swe         SWE 50 x 50, T = 10, IMR, 2k = 80, m = 150: one query's time loop against the same
#               model's online time inside `gphr run` (both the fastest of 5, one process), the set-up
#               time against its time loop, and the model file's size without the basis.
#   nls-queries 64 NLS queries (n = 2048, T = 30, AVF, 2k = 160, m = 130, eps over the box) on 1 and
#               2 ranks: queries per second, against the full model's solves per second on the
#               same ranks.
#   swe-scaling SWE 64^2 .. 512^2 (GRIDS), 2k = 20, m = 40, a short training run per grid (T = 0.5):
#               9 queries of 400 steps over the box; a query's time per step and per Newton iteration,
#               and the query process's peak memory, against the full model's peak memory.
#   nls-file    the model file of the paper's NLS GP-ADEIM setting without the basis (2k = 400, m = 100):
#               its size (training shared with nls-queries and nls-box).
#   nls-box     NLS over the box [0.9, 1.1]: 21 test points, the ROM and GP-DEIM (2k = 160,
#               m = 130): max and mean E_L2 over the box (gphr validate).
#   threads     64 NLS queries (n = 1024, T = 20, 2k = 40, m = 60) by one process with --threads 1 and
#               --threads 2, in five alternating pairs: queries per second (the median of each), the
#               median of the five pairs' ratios (a pair's two runs are seconds apart, so a slow spell
#               of a shared machine falls on both), and the results compared bit for bit (h5diff);
#               beside them the machine's own ceiling: two one-thread processes of 32 queries each,
#               side by side (what two cores give two independent programs).
# nls-queries and nls-box share their training, basis and model file (bench-out/model_nls).
# usage: bash bench/model_file.sh CASE [BUILD_DIR]   (CASE: swe, nls-queries, swe-scaling, nls-file, nls-box, threads)
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
case=$1; build=${2:-build}
gphr=$PWD/$build/packages/driver/gphr
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(machine_line "$gphr")"
json() { python3 -c "import json,sys; d=json.load(open('$1')); print(eval(sys.argv[1]))" "$2"; }
csvcol() { python3 -c "import csv,sys; r=list(csv.DictReader(open('$1'))); print(' '.join(x['$2'] for x in r))"; }
min() { python3 -c "import sys; print(min(float(x) for x in sys.argv[1:]))" "$@"; }

nls_config() {  # FILE K M MAXRANK [EXTRA]: the paper's NLS with 11 training parameters (shared training)
  sed -e "s|^  integrator:.*|  integrator: {scheme: avf, jacobianLag: true}|" bench/configs/nls_paper.yaml > "$1"
  cat >> "$1" <<YAML
  training: {points: [11], snapshotEvery: 10}
  reduction: {k: $2}
  pipeline: {methods: [gp-deim], m: [$3]}
  hyper: {snapshotEvery: 2, svd: randomized, maxRank: $4, powerIterations: 0}
YAML
  [ -z "${5:-}" ] || echo "  $5" >> "$1"
}

nls_model() {  # the shared NLS model file (2k = 160, m = 130, with the basis for validate)
  local out=bench-out/model_nls; mkdir -p $out
  nls_config $out/build.yaml 80 130 140 "build: {withBasis: true}"
  # Built every time: the training, bases and DEIM basis come from the artifacts cache.
  mpirun -np 2 "$gphr" build $out/build.yaml --model $out/nls.h5 --output $out/art > $out/build.log 2>&1
  cat $out/build.log | grep -E "gphr build|interpolant"
}

case $case in
  swe)
    out=bench-out/model_swe; mkdir -p $out
    sed -e "s|^  integrator:.*|  integrator: {scheme: imr, jacobianLag: true}|" bench/configs/swe_paper.yaml > $out/run.yaml
    cat >> $out/run.yaml <<YAML
  training: {points: [5, 5], snapshotEvery: 10}
  reduction: {k: 40}
  pipeline: {methods: [gp-deim], m: [150], onlineRepeats: 5, onlineRepeatSeconds: 600.0}
  hyper: {snapshotEvery: 2, svd: randomized, powerIterations: 1}
YAML
    # Offline on 2 ranks; then the in-run model and the queries each on one process, so that the
    # two time loops are the same computation on the same resources (the artifacts are reused).
    mpirun -np 2 "$gphr" build $out/run.yaml --model $out/swe.h5 --output $out/run > $out/build.log 2>&1
    "$gphr" run $out/run.yaml --output $out/run > $out/run.log 2>&1
    grep -E "gphr build|interpolant" $out/build.log
    mu=$(json $out/run/summary.json "' '.join(str(v) for v in d['parameters'].values())")
    set -- $mu
    cat > $out/q.yaml <<YAML
queries:
  defaults: {beta: $1, gamma: $2, T: 10.0, dt: 0.005, k: 40, m: 150, saveEvery: 100}
  points: {a: {}, b: {}, c: {}, d: {}, e: {}}
YAML
    rm -rf $out/q  # a fresh run: finished queries of an earlier one would be reused, with their times
    OPENBLAS_NUM_THREADS=1 "$gphr" query $out/swe.h5 $out/q.yaml --output $out/q > $out/query.log 2>&1
    inrun=$(json $out/run/summary.json "[r['t_online_s'] for r in d['runs'] if r['method'] == 'gp-deim'][0]")
    query=$(min $(csvcol $out/q/queries.csv online_s)); setup=$(min $(csvcol $out/q/queries.csv setup_s))
    size=$(stat -c %s $out/swe.h5)
    python3 - <<PY
inrun, query, setup, size = $inrun, $query, $setup, $size
print(f"SWE 50x50 T=10 IMR 2k=80 m=150: time loop in gphr run {inrun:.3f} s, in a query {query:.3f} s "
      f"(ratio {query / inrun:.2f}, target <= 1); set-up {setup * 1e3:.2f} ms = {100 * setup / query:.2f}% of the loop "
      f"(target <= 10%); model file {size / 1e6:.2f} MB (target <= 5 MB)")
PY
    ;;
  threads)
    out=bench-out/model_threads; mkdir -p $out
    printf 'gphr:\n  scene: {name: nls1d, n: 1024}\n  time: {T: 5.0, dt: 0.01}\n  training: {points: [5]}\n  pipeline: {methods: [gp-deim], k: [20], m: [60]}\n  hyper: {snapshotEvery: 5}\n' > $out/build.yaml
    "$gphr" build $out/build.yaml --model $out/nls.h5 --output $out/art > $out/build.log 2>&1
    printf 'queries:\n  defaults: {T: 20.0, dt: 0.01, saveEvery: 100}\n  grid: {eps: [0.9, 1.1, 64]}\n' > $out/q.yaml
    printf 'queries:\n  defaults: {T: 20.0, dt: 0.01, saveEvery: 100}\n  grid: {eps: [0.9, 1.1, 32]}\n' > $out/q32.yaml
    rm -f $out/qps_t1 $out/qps_t2 $out/qps_pp
    for rep in 1 2 3 4 5; do
      for t in 1 2; do
        rm -rf $out/t$t  # a fresh run: finished queries would be reused
        "$gphr" query $out/nls.h5 $out/q.yaml --output $out/t$t --threads $t > $out/t${t}_$rep.log 2>&1
        echo "$(json $out/t$t/query_summary.json "d['queries_per_s']")" >> $out/qps_t$t
      done
      h5diff $out/t1/results.h5 $out/t2/results.h5 > /dev/null || { echo "results differ between 1 and 2 threads"; exit 1; }
      # the machine's own ceiling: two one-thread processes side by side, 32 queries each
      rm -rf $out/p1 $out/p2
      "$gphr" query $out/nls.h5 $out/q32.yaml --output $out/p1 --threads 1 > $out/p1_$rep.log 2>&1 &
      "$gphr" query $out/nls.h5 $out/q32.yaml --output $out/p2 --threads 1 > $out/p2_$rep.log 2>&1
      wait
      echo "$(json $out/p1/query_summary.json "64 / max(d['wall_s'], $(json $out/p2/query_summary.json "d['wall_s']"))")" >> $out/qps_pp
    done
    python3 - $out/qps_t1 $out/qps_t2 $out/qps_pp <<PY
import statistics, sys
q1, q2, pp = ([float(x) for x in open(p).read().split()] for p in sys.argv[1:])
ratios = sorted(b / a for a, b in zip(q1, q2))
ceiling = sorted(b / a for a, b in zip(q1, pp))
print(f"64 NLS queries (n=1024, T=20, 2k=40, m=60), one process: --threads 1 {statistics.median(q1):.2f} queries/s, "
      f"--threads 2 {statistics.median(q2):.2f} queries/s (medians of {[round(x, 2) for x in q1]} and "
      f"{[round(x, 2) for x in q2]}); pair ratios {[round(x, 2) for x in ratios]}, median "
      f"{statistics.median(ratios):.2f}x; results.h5 identical (h5diff) in every pair")
print(f"the machine's ceiling, two one-thread processes of 32 queries side by side: {statistics.median(pp):.2f} "
      f"queries/s (of {[round(x, 2) for x in pp]}), against --threads 1 {statistics.median(ceiling):.2f}x "
      f"(pairs {[round(x, 2) for x in ceiling]}); --threads 2 against it "
      f"{statistics.median(q2) / statistics.median(pp):.2f}; load at the end {open('/proc/loadavg').read().split()[0]}")
PY
    rm -f $out/qps_t1 $out/qps_t2 $out/qps_pp
    ;;
  nls-queries)
    nls_model; out=bench-out/model_nls
    cat > $out/q64.yaml <<YAML
queries:
  defaults: {T: 30.0, dt: 0.01, k: 80, m: 130, saveEvery: 100, probes: false}
  grid: {eps: [0.9, 1.1, 64]}
YAML
    for np in 1 2; do
      rm -rf $out/q64_np$np
      mpirun -np $np "$gphr" query $out/nls.h5 $out/q64.yaml --output $out/q64_np$np > $out/q64_np$np.log 2>&1
      sed -e "s|^  integrator:.*|  integrator: {scheme: avf, jacobianLag: true}|" bench/configs/nls_paper.yaml > $out/fom.yaml
      mpirun -np $np "$gphr" run $out/fom.yaml --output $out/fom_np$np > $out/fom_np$np.log 2>&1
    done
    q1=$(json $out/q64_np1/query_summary.json "d['queries_per_s']"); q2=$(json $out/q64_np2/query_summary.json "d['queries_per_s']")
    f1=$(json $out/fom_np1/summary.json "d['runs'][0]['t_online_s']"); f2=$(json $out/fom_np2/summary.json "d['runs'][0]['t_online_s']")
    python3 - <<PY
q1, q2, f1, f2 = $q1, $q2, $f1, $f2
print(f"64 NLS queries (n=2048, T=30, AVF, 2k=160, m=130): 1 rank {q1:.3f} queries/s, 2 ranks {q2:.3f} queries/s "
      f"(ratio {q2 / q1:.2f}, target >= 1.8)")
print(f"full model: {1 / f1:.4f} solves/s on 1 rank ({f1:.1f} s), {1 / f2:.4f} on 2 ({f2:.1f} s); queries/s over "
      f"full solves/s: {q1 * f1:.1f} on 1 rank, {q2 * f2:.1f} on 2 (target >= 10)")
PY
    ;;
  nls-file)
    out=bench-out/model_nls; mkdir -p $out
    nls_config $out/build400.yaml 200 100 110
    mpirun -np 2 "$gphr" build $out/build400.yaml --model $out/nls400.h5 --output $out/art > $out/build400.log 2>&1
    grep -E "gphr build|interpolant" $out/build400.log
    echo "NLS 2k=400 m=100 model file without the basis: $(stat -c %s $out/nls400.h5) bytes"
    ;;
  nls-box)
    nls_model; out=bench-out/model_nls
    cat > $out/box.yaml <<YAML
validate:
  defaults: {T: 30.0, dt: 0.01, saveEvery: 100}
  grid: {eps: [0.9, 1.1, 21]}
YAML
    mpirun -np 2 "$gphr" validate $out/nls.h5 $out/box.yaml --output $out/box > $out/box.log 2>&1
    sed -n '/^| model/,/^$/p' $out/box/validation.md
    python3 - <<PY
import json
m = {x["model"]: x for x in json.load(open("$out/box/validation_summary.json"))["models"]}
rom, hr = m["rom k=80"], m["gp-deim k=80 m=130"]
print(f"NLS box [0.9, 1.1], 21 points, 2k=160: ROM max {rom['E_L2_max']:.3e} mean {rom['E_L2_mean']:.3e}; GP-DEIM m=130 "
      f"max {hr['E_L2_max']:.3e} mean {hr['E_L2_mean']:.3e}; max ratio {hr['E_L2_max'] / rom['E_L2_max']:.2f} (target <= 2)")
PY
    ;;
  swe-scaling)
    for nx in ${GRIDS:-64 128 256 512}; do
      out=bench-out/model_swe_$nx; mkdir -p $out
      cat > $out/build.yaml <<YAML
gphr:
  scene: {name: swe2d, nx: $nx}
  time: {T: 0.5, dt: 0.005}
  integrator: {scheme: imr, jacobianLag: true}
  training: {points: [2, 2], snapshotEvery: 1}
  reduction: {k: 10}
  pipeline: {methods: [gp-deim], m: [40]}
  hyper: {snapshotEvery: 1, svd: randomized, powerIterations: 0}
  output: {saveEvery: 10, plots: false, progressSeconds: 600.0}
YAML
      [ -f $out/swe.h5 ] || mpirun -np 2 "$gphr" build $out/build.yaml --model $out/swe.h5 --output $out/art > $out/build.log 2>&1
      cat > $out/q.yaml <<YAML
queries:
  defaults: {T: 2.0, dt: 0.005, k: 10, m: 40, probes: false}
  grid: {beta: [1.2, 1.6, 3], gamma: [0.8, 1.2, 3]}
YAML
      rm -rf $out/q
      /usr/bin/time -f "%M" -o $out/query.rss "$gphr" query $out/swe.h5 $out/q.yaml --output $out/q > /dev/null 2>&1
      sed -e "s|nx: $nx}|nx: $nx}\n  parameters: {beta: 1.4, gamma: 1.0}|" -e "s|^  pipeline:.*|  pipeline: {rom: false}|" \
          -e "/^  hyper:/d" -e "/^  training:/d" -e "/^  reduction:/d" $out/build.yaml > $out/fom.yaml
      /usr/bin/time -f "%M" -o $out/fom.rss "$gphr" run $out/fom.yaml --output $out/fom > /dev/null 2>&1
      # The fastest of the 9 queries, per step and per Newton iteration (a finer grid's step is a
      # harder nonlinear problem at a fixed dt: doc/benchmarks.md, hyper_scaling.sh).
      step=$(python3 -c "import csv; r=list(csv.DictReader(open('$out/q/queries.csv'))); print(min(float(x['online_s']) for x in r) / 400)")
      iter=$(python3 -c "import csv; r=list(csv.DictReader(open('$out/q/queries.csv'))); print(min(float(x['online_s']) / (400 * float(x['newton_iters_avg'])) for x in r))")
      # The same queries at a fixed CFL number (dt = 0.005 x 64 / nx, 400 steps): every grid's step
      # is then the same nonlinear problem, and the time per step compares the model's cost alone.
      dtc=$(python3 -c "print(0.005 * 64 / $nx)"); Tc=$(python3 -c "print(400 * 0.005 * 64 / $nx)")
      sed -e "s|T: 2.0, dt: 0.005|T: $Tc, dt: $dtc|" $out/q.yaml > $out/qcfl.yaml
      rm -rf $out/qcfl
      "$gphr" query $out/swe.h5 $out/qcfl.yaml --output $out/qcfl > /dev/null 2>&1
      cfl=$(python3 -c "import csv; r=list(csv.DictReader(open('$out/qcfl/queries.csv'))); print(min(float(x['online_s']) for x in r) / 400)")
      echo "nx $nx: fixed CFL (dt $dtc): query time per step $(python3 -c "print(f'{$cfl * 1e6:.1f}')") us"
      echo "nx $nx: query time per step $(python3 -c "print(f'{$step * 1e6:.1f}')") us, per Newton iteration $(python3 -c "print(f'{$iter * 1e6:.1f}')") us, query peak RSS $(cat $out/query.rss) kB, full model peak RSS $(cat $out/fom.rss) kB, file $(stat -c %s $out/swe.h5) bytes, set-up $(python3 -c "import csv; r=list(csv.DictReader(open('$out/q/queries.csv'))); print(f\"{min(float(x['setup_s']) for x in r) * 1e3:.2f}\")") ms"
    done
    ;;
  *) echo "unknown case '$case'; allowed: swe, nls-queries, nls-file, nls-box, swe-scaling"; exit 2 ;;
esac
