#!/usr/bin/env bash
# Strong scaling of the offline phase and of the full model over a list of rank counts
# (doc/scaling.md holds the cost model, bench/scaling_model.py checks it against this CSV).
# Cases (SIZE=large, the sizes doc/scaling.md models; SIZE=small, each shrunk to seconds for a quick check):
#   nls    gphr build, NLS n = 2048, T = 10, dt = 0.01, AVF, training [5] (every 10th state kept),
#          k = 80 (2k = 160), gp-deim m = 130                       small: n = 512, T = 2, k = 20, m = 40
#   swe    gphr build, SWE 256^2, IMR (lagged Jacobian), 2 x 2 training of 80 steps (dt = 0.005),
#          k = 20 (2k = 40), gp-deim m = 40 and 80, a DEIM snapshot every 5th state  small: 64^2
#          (1-rank stage times when this case was set, DEIM basis 65.5 s of 141.5, fit every 5th state; with every
#          state the DEIM basis took 270.6 s of 363.7 on the 2-core VM)
#   fom    gphr run of the full model alone, SWE 512^2, IMR, 40 steps   small: 128^2
#   query  64 gphr query runs (--threads 1) of the nls case's model at T = 5   small: T = 2
# Per case and rank count: the wall seconds of each stage (largest over the ranks), each rank's
# compute seconds (CPU outside MPI calls: waits excluded, also when ranks outnumber the cores and
# spin in MPI) as max and mean, CPU seconds per rank, peak resident memory per rank, and the
# speed-up of wall and compute over the first rank count. The build cases' stages come from
# gphr build's DIR/stages.csv (their MPI seconds split by MPI function, DIR/mpi_calls.csv, go to
# OUT_CSV's -mpi.csv twin, and the largest rank count's leading functions are printed per stage:
# where a stage waits); every case also has a whole-process row per rank (GPHR_PROCESS_CLOCKS),
# fom a "time loop" row (summary.json t_online_s) and query a "queries" row (query_summary.json).
# Environment: RANKS (default "1 2 4 8"), SIZE (large | small), CASES (default "nls swe fom query"),
# CRITICAL=1 (each stage's compute critical path as well, GPHR_CRITICAL_PATH=1: one extra 8-byte
# allreduce per collective call; its columns "crit max" and "crit x" estimate the wall seconds with
# a core per rank where the ranks outnumber the cores, doc/scaling.md "Critical path"),
# G (the gphr binary; default build/packages/driver/gphr), OUT_CSV (default
# bench-out/scaling/scaling-SIZE.csv), MPIRUN (default mpirun), BIND (mpirun --bind-to: none, the
# default, or core). Runs with rank counts above the core count are oversubscribed
# (said in the output); OPENBLAS_NUM_THREADS=1.
# usage: [RANKS="1 2 4 8"] [SIZE=small] bash bench/scaling.sh
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
RANKS=${RANKS:-"1 2 4 8"}; SIZE=${SIZE:-large}; CASES=${CASES:-"nls swe fom query"}
G=${G:-$PWD/build/packages/driver/gphr}; MPIRUN=${MPIRUN:-mpirun}; BIND=${BIND:-none}
case $SIZE in large|small) ;; *) echo "SIZE=$SIZE; allowed: large, small" >&2; exit 2 ;; esac
[ -x "$G" ] || { echo "no gphr binary at '$G' (set G)" >&2; exit 2; }
work=bench-out/scaling/$SIZE; mkdir -p "$work"
OUT_CSV=${OUT_CSV:-bench-out/scaling/scaling-$SIZE.csv}
MPI_CSV=${OUT_CSV%.csv}-mpi.csv
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)  # GNU nproc honours both
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
case ${CRITICAL:-0} in 1) export GPHR_CRITICAL_PATH=1 ;; 0) unset GPHR_CRITICAL_PATH ;;
  *) echo "CRITICAL=$CRITICAL; allowed: 0, 1" >&2; exit 2 ;; esac

echo "machine: $(machine_line "$G"); SIZE=$SIZE, RANKS=\"$RANKS\", mpirun --bind-to $BIND"
for p in $RANKS; do
  [ "$p" -gt "$cores" ] && echo "note: $p ranks on $cores cores run oversubscribed: wall seconds include waiting for a core; compare compute seconds"
done

if [ "$SIZE" = large ]; then
  nls_n=2048 nls_T=10.0 nls_k=80 nls_m=130 swe_nx=256 fom_nx=512 q_T=5.0
else
  nls_n=512 nls_T=2.0 nls_k=20 nls_m=40 swe_nx=64 fom_nx=128 q_T=2.0
fi
# The sizes the cost model needs (bench/scaling_model.py), one column of the CSV.
# treefrom, tplevel: the streaming POD's route rule of this gphr (podRoute auto takes the tree from
# 2 ranks; its levels are TPQRT of two triangles), which the model reads per record.
pod_rule="treefrom=2;tplevel=1"
nls_sizes="n=$nls_n;steps=$(python3 -c "print(round($nls_T / 0.01))");points=5;every=10;k=$nls_k;m=$nls_m;nodes=7;$pod_rule"
swe_sizes="nx=$swe_nx;steps=80;points=4;every=1;hyper=5;k=20;m=40+80;nodes=49;$pod_rule"
fom_sizes="nx=$fom_nx;steps=40"
q_sizes="n=$nls_n;steps=$(python3 -c "print(round($q_T / 0.01))");queries=64;k=$nls_k;m=$nls_m"

cat > "$work/nls.yaml" <<YAML
gphr:
  scene: {name: nls1d, n: $nls_n}
  parameters: {eps: 1.0}
  time: {T: $nls_T, dt: 0.01}
  integrator: {scheme: avf}
  training: {points: [5], snapshotEvery: 10}
  reduction: {k: $nls_k}
  pipeline: {methods: [gp-deim], m: [$nls_m]}
  output: {progressSeconds: 0.0}
YAML
cat > "$work/swe.yaml" <<YAML
gphr:
  scene: {name: swe2d, nx: $swe_nx}
  time: {T: 0.4, dt: 0.005}
  integrator: {scheme: imr, jacobianLag: true}
  training: {points: [2, 2]}
  reduction: {k: 20}
  pipeline: {methods: [gp-deim], m: [40, 80]}
  hyper: {snapshotEvery: 5}
  output: {progressSeconds: 0.0}
YAML
cat > "$work/fom.yaml" <<YAML
gphr:
  scene: {name: swe2d, nx: $fom_nx}
  time: {T: 0.2, dt: 0.005}
  integrator: {scheme: imr}
  output: {saveEvery: 1000, plots: false, progressSeconds: 0.0}
YAML
cat > "$work/queries.yaml" <<YAML
queries:
  defaults: {T: $q_T, dt: 0.01, k: $nls_k, m: $nls_m, saveEvery: 1000, probes: false}
  grid: {eps: [0.9, 1.1, 64]}
YAML

echo "case,size,ranks,rank,stage,wall_s,cpu_s,mpi_wall_s,mpi_cpu_s,compute_s,peak_rss_mb,critical_s,sizes" > "$OUT_CSV.tmp"
echo "case,size,ranks,rank,stage,call,calls,wall_s" > "$MPI_CSV.tmp"
# rows CASE P SIZES FILE...: the CSV lines of FILE... (stages.csv format, header skipped) with the case columns.
rows() {
  local c=$1 p=$2 s=$3; shift 3
  awk -F, -v c="$c" -v z="$SIZE" -v p="$p" -v s="$s" 'FNR > 1 || $1 ~ /^[0-9]+$/ {print c "," z "," p "," $0 "," s}' "$@" >> "$OUT_CSV.tmp"
}
# mpi P DIR CMD...: runs CMD on P ranks with the whole-process clocks into DIR/process.RANK.
mpi() {
  local p=$1 dir=$2; shift 2
  rm -f "$dir"/process.*
  GPHR_PROCESS_CLOCKS="$dir/process" "$MPIRUN" --bind-to "$BIND" -np "$p" "$@"
}
model=""
for c in $CASES; do
  for p in $RANKS; do
    d=$work/${c}_np$p; rm -rf "$d"; mkdir -p "$d"
    case $c in
      nls|swe)
        mpi "$p" "$d" "$G" build "$work/$c.yaml" --model "$d/model.h5" --output "$d/art" > "$d/log" 2>&1 \
          || { tail -20 "$d/log"; exit 1; }
        sizes=nls_sizes; [ $c = swe ] && sizes=swe_sizes
        rows "$c" "$p" "${!sizes}" "$d/art/stages.csv" "$d"/process.*
        awk -v c="$c" -v z="$SIZE" -v p="$p" 'FNR > 1 {print c "," z "," p "," $0}' "$d/art/mpi_calls.csv" >> "$MPI_CSV.tmp"
        # on one rank, each training parameter's seconds from the progress lines (the cost model
        # deals them to rank groups as the training does)
        [ "$p" = 1 ] && awk -v c="$c" -v z="$SIZE" -v s="${!sizes}" \
          '/train: parameter [0-9]+\/[0-9]+ .* done, [0-9.]+ s elapsed/ {
             split($4, ij, "/"); for (i = 1; i <= NF; ++i) if ($i == "elapsed,") t = $(i - 2)
             printf "%s,%s,1,0,training parameter %d,%.3f,,,,,,,%s\n", c, z, ij[1], t - last, s; last = t }' \
          "$d/log" >> "$OUT_CSV.tmp"
        [ $c = nls ] && [ -z "$model" ] && model=$d/model.h5 ;;
      fom)
        mpi "$p" "$d" "$G" run "$work/fom.yaml" --output "$d/out" > "$d/log" 2>&1 || { tail -20 "$d/log"; exit 1; }
        rows fom "$p" "$fom_sizes" "$d"/process.*
        t=$(python3 -c "import json; print(json.load(open('$d/out/summary.json'))['runs'][0]['t_online_s'])")
        echo "fom,$SIZE,$p,,time loop,$t,,,,,,,$fom_sizes" >> "$OUT_CSV.tmp" ;;
      query)
        if [ -z "$model" ]; then  # the nls case's model, built once on one rank
          mkdir -p "$work/model"
          "$G" build "$work/nls.yaml" --model "$work/model/model.h5" --output "$work/model/art" > "$work/model/log" 2>&1 \
            || { tail -20 "$work/model/log"; exit 1; }
          model=$work/model/model.h5
        fi
        mpi "$p" "$d" "$G" query "$model" "$work/queries.yaml" --output "$d/out" --threads 1 > "$d/log" 2>&1 \
          || { tail -20 "$d/log"; exit 1; }
        rows query "$p" "$q_sizes" "$d"/process.*
        t=$(python3 -c "import json; print(json.load(open('$d/out/query_summary.json'))['wall_s'])")
        echo "query,$SIZE,$p,,queries,$t,,,,,,,$q_sizes" >> "$OUT_CSV.tmp" ;;
      *) echo "unknown case '$c'; allowed: nls, swe, fom, query" >&2; exit 2 ;;
    esac
  done
done
mv "$OUT_CSV.tmp" "$OUT_CSV"; mv "$MPI_CSV.tmp" "$MPI_CSV"

python3 - "$OUT_CSV" "$cores" "$MPI_CSV" <<'PY'
import csv, sys
from collections import OrderedDict
rows = list(csv.DictReader(open(sys.argv[1]))); cores = int(sys.argv[2])
titles = {"nls": "gphr build, NLS", "swe": "gphr build, SWE", "fom": "full model, SWE (gphr run)",
          "query": "64 gphr query runs of the NLS model"}
for case in OrderedDict.fromkeys(r["case"] for r in rows):
    mine = [r for r in rows if r["case"] == case]
    print(f"\n{titles.get(case, case)} ({mine[0]['sizes']})")
    crit = any(float(r.get("critical_s") or 0) > 0 for r in mine)  # measured (CRITICAL=1)
    print(f"{'ranks':>5} {'stage':<20} {'wall max':>9} {'comp max':>9} {'comp mean':>9} {'cpu max':>9} "
          f"{'MB max':>8} {'wall x':>7} {'comp x':>7}" + (f" {'crit max':>9} {'crit x':>7}" if crit else ""))
    ranks = list(OrderedDict.fromkeys(int(r["ranks"]) for r in mine))
    stages = list(OrderedDict.fromkeys(r["stage"] for r in mine
                                       if r["stage"] != "process" and not r["stage"].startswith("training parameter")))
    if any(r["compute_s"] for r in mine if r["stage"] != "process"):
        stages.append("stages total")
    stages.append("process")
    first = {}
    for p in ranks:
        at = [r for r in mine if int(r["ranks"]) == p]
        for st in stages:
            if st == "stages total":  # per rank, the sum of its stages
                per = {}
                for r in at:
                    if r["stage"] != "process" and r["compute_s"] and not r["stage"].startswith("training parameter"):
                        a = per.setdefault(r["rank"], [0.0] * 5)
                        a[0] += float(r["wall_s"]); a[1] += float(r["compute_s"]); a[2] += float(r["cpu_s"])
                        a[3] = max(a[3], float(r["peak_rss_mb"])); a[4] += float(r.get("critical_s") or "nan")
                vals = list(per.values())
            else:
                vals = [[float(r["wall_s"]), float(r["compute_s"] or "nan"), float(r["cpu_s"] or "nan"),
                         float(r["peak_rss_mb"] or "nan"), float(r.get("critical_s") or "nan")]
                        for r in at if r["stage"] == st]
            if not vals:
                continue
            wall = max(v[0] for v in vals); comp = max(v[1] for v in vals)
            mean = sum(v[1] for v in vals) / len(vals); cpu = max(v[2] for v in vals); mb = max(v[3] for v in vals)
            cr = max(v[4] for v in vals)
            first.setdefault(st, (wall, comp, cr))
            w0, c0, r0 = first[st]
            sw = f"{w0 / wall:.2f}" if wall > 0 else "-"
            sc = f"{c0 / comp:.2f}" if comp == comp and comp > 0 else "-"
            f = lambda x, d=3: "-" if x != x else f"{x:.{d}f}"
            sr = f"{r0 / cr:.2f}" if cr == cr and cr > 0 and r0 == r0 else "-"
            print(f"{p:>5} {st:<20} {f(wall):>9} {f(comp):>9} {f(mean):>9} {f(cpu):>9} {f(mb, 1):>8} {sw:>7} {sc:>7}"
                  + (f" {f(cr):>9} {sr:>7}" if crit else ""))
        if case == "query":
            q = [float(r["wall_s"]) for r in at if r["stage"] == "queries"]
            if q: print(f"{p:>5} {'queries/s':<20} {64 / q[0]:>9.2f}")
    over = [p for p in ranks if p > cores]
    if over: print(f"      (oversubscribed on {cores} cores: {', '.join(map(str, over))} ranks)")
    # Where the largest rank count's stages spend their MPI seconds: per stage the three MPI
    # functions with the most (mean over the ranks, and the largest rank's).
    calls = [r for r in csv.DictReader(open(sys.argv[3])) if r["case"] == case and int(r["ranks"]) == max(ranks)]
    if calls and max(ranks) > 1:
        print(f"      MPI seconds by function on {max(ranks)} ranks (mean / max over the ranks):")
        for st in OrderedDict.fromkeys(r["stage"] for r in calls):
            per = {}
            for r in calls:
                if r["stage"] == st:
                    per.setdefault(r["call"], []).append(float(r["wall_s"]))
            top = sorted(per.items(), key=lambda kv: -sum(kv[1]))[:3]
            text = ", ".join(f"{c[4:]} {sum(v) / max(ranks):.3f} / {max(v):.3f}" for c, v in top if max(v) >= 0.001)
            if text: print(f"      {st:<20} {text}")
print(f"\nCSV: {sys.argv[1]} (MPI by function: {sys.argv[3]}); wall x, comp x: speed-up over {'the first rank count'} (wall: largest over ranks; "
      "comp: the largest rank's compute seconds; crit: the compute critical path, largest over the ranks)")
PY
