#!/usr/bin/env bash
# Streaming-POD routes and the offline stages at the paper's NLS size (Sec. 5.2: n = 2048, T = 30,
# AVF, 11 training parameters, every 10th state: 3311 snapshots; 2k = 400), one `gphr run` each:
#   routes  the symplectic basis (PSD: 33 POD steps of up to 864 carried + 256 new columns on
#           4096 rows) with reduction.podRoute tsqr (Tpetra's TSQR), stacked (GEQRF per rank, one
#           SVD of the stacked R factors; what auto takes on one rank), tree (the R factors reduced
#           over a binary tree, one SVD on rank 0; what auto takes from 2 ranks) and replicated on
#           1 and 2 ranks, and on 4 ranks (oversubscribed; 1024 rows per rank < 1120 columns) tsqr,
#           which refuses, stacked and tree. Training is read from a copy of $ARTIFACTS (an artifacts.h5 holding this
#           training; never modified) or of the stages part's np2 run; the basis is recomputed in
#           every run (podRoute is in its cache key).
#           gphr also runs the FOM at the test parameter and here a ROM at k = 1: not in the table.
#   stages  FOM online, training (from scratch), basis (podRoute auto) and DEIM basis (randomized,
#           maxRank 110, m = 100, as bench/hyper_paper.sh nls) on 1 and 2 ranks.
# auto takes the stacked route on one rank and the tree route on 2 (the step counts show it), so
# with `all` the stages runs give the routes table's stacked row on 1 rank and tree row on 2.
# Before the stacked route existed auto took TSQR where it fit and the replicated route elsewhere;
# route_auto_* runs of that time are listed as auto. Times are wall seconds; the basis also in CPU seconds of rank 0 (steadier
# on a shared machine), with the 1-minute load average at the start.
# usage: bash bench/pod_routes.sh [all|routes|stages|table] [BUILD_DIR]   (all: 36 min measured on a shared 2-core machine
#        before the stacked and tsqr cases on 1 and 2 ranks were added;
#        table: print the tables of the runs already in bench-out/pod_routes;
#        routes alone: ARTIFACTS=path/to/artifacts.h5 with this training, else the stages part's np2 run;
#        CASES="route:ranks ..." runs only those route cases, e.g. CASES="stacked:1 stacked:2")
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/machine.sh
part=${1:-all}; build=${2:-build}
gphr=$build/packages/driver/gphr
out=bench-out/pod_routes; mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
echo "machine: $(machine_line "$gphr"); load $(cut -d' ' -f1-3 /proc/loadavg)"

config() {  # config BODY_LINES...: the paper's NLS set-up (the training of bench/hyper_paper.sh) plus the lines
  sed -e "s|^  integrator:.*|  integrator: {scheme: avf, jacobianLag: true}|" bench/configs/nls_paper.yaml
  echo "  training: {points: [11], snapshotEvery: 10}"
  printf '%s\n' "$@"
}
run() {  # run NAME RANKS BODY_LINES...: one gphr run in $out/NAME; exit code in NAME/rc
  local name=$1 np=$2; shift 2
  local dir=$out/$name
  rm -rf "$dir"; mkdir -p "$dir"
  config "$@" > "$dir.yaml"  # beside the output: gphr refuses to write over its input
  cut -d' ' -f1 /proc/loadavg > "$dir/load"
  if [ "$name" != "${name#route_}" ]; then cp "$artifacts" "$dir/artifacts.h5"; fi
  local rc=0
  if [ "$np" -eq 1 ]; then "$gphr" run "$dir.yaml" --output "$dir" > "$dir/run.log" 2>&1 || rc=$?
  else mpirun --oversubscribe -np "$np" "$gphr" run "$dir.yaml" --output "$dir" > "$dir/run.log" 2>&1 || rc=$?; fi
  echo "$rc" > "$dir/rc"
  echo "  $name: exit $rc, $(grep -m1 '\[gphr\] reduce\|gphr: error' "$dir/run.log" || true)" >&2
}

case $part in all|routes|stages|table) ;; *) echo "unknown part $part"; exit 2 ;; esac
if [ "$part" = all ] || [ "$part" = stages ]; then
  for np in 2 1; do
    run stages_np$np $np "  reduction: {k: 200}" "  pipeline: {methods: [gp-deim], m: [100]}" \
      "  hyper: {snapshotEvery: 2, svd: randomized, maxRank: 110, powerIterations: 0}"
  done
fi
if [ "$part" = all ] || [ "$part" = routes ]; then
  artifacts=${ARTIFACTS:-$out/stages_np2/artifacts.h5}
  [ -s "$artifacts" ] || { echo "no training to reuse: set ARTIFACTS or run the stages part first"; exit 2; }
  cases="tsqr:1 replicated:1 stacked:1 tsqr:2 replicated:2 stacked:2 tree:2 tsqr:4 stacked:4 tree:4"
  # all: the stages runs (podRoute auto) are the stacked row on 1 rank and the tree row on 2
  [ "$part" = all ] && cases="tsqr:1 replicated:1 tsqr:2 replicated:2 stacked:2 tsqr:4 stacked:4 tree:4" && rm -rf "$out/route_stacked_np1" "$out/route_tree_np2"
  cases=${CASES:-$cases}
  for c in $cases; do
    route=${c%:*}; np=${c#*:}
    run route_${route}_np$np "$np" "  reduction: {k: 200, podRoute: $route}" "  pipeline: {methods: [rom], k: [1]}"
  done
fi

python3 - "$out" <<'PY'
import json, os, sys
out = sys.argv[1]
def load(name):
    d = os.path.join(out, name)
    if not os.path.exists(os.path.join(d, "rc")):
        return None
    r = {"rc": int(open(os.path.join(d, "rc")).read()), "load": open(os.path.join(d, "load")).read().strip(), "dir": d}
    if r["rc"] == 0:
        r["summary"] = json.load(open(os.path.join(d, "summary.json")))
    else:
        r["error"] = next((l.strip() for l in open(os.path.join(d, "run.log")) if l.startswith("gphr: error")), "?")
    return r
def basis_run(s):  # the first entry carrying the basis keys (rom or gp-deim)
    return next(r for r in s["runs"] if "t_basis_s" in r)

print("\nsymplectic basis (PSD, 2k = 400, 3311 snapshots, 4096 rows) by reduction.podRoute:")
print(f"{'route':<11} {'ranks':>5} {'rows/rank':>9} {'tsqr':>5} {'stack':>5} {'tree':>5} {'repl':>5} {'basis_s':>8} {'cpu_s':>7} {'load':>5}  run")
errors = []
for route, np in [("tsqr", 1), ("replicated", 1), ("stacked", 1), ("auto", 1), ("tsqr", 2), ("replicated", 2),
                  ("stacked", 2), ("tree", 2), ("auto", 2), ("tsqr", 4), ("stacked", 4), ("tree", 4), ("auto", 4)]:
    auto_route = "stacked" if np == 1 else "tree"  # the stages runs' podRoute auto
    for name in [f"route_{route}_np{np}"] + ([f"stages_np{np}"] if route == auto_route and np < 4 else []):
        r = load(name)
        if r is None:
            continue
        if r["rc"] != 0:
            what = "refused" if "podRoute 'tsqr'" in r["error"] else "failed"
            print(f"{route:<11} {np:>5} {4096 // np:>9} {'-':>5} {'-':>5} {'-':>5} {'-':>5} {what:>8} {'-':>7} {r['load']:>5}  {name} (exit {r['rc']})")
            errors.append(r["error"])
        else:
            b = basis_run(r["summary"])
            print(f"{route:<11} {np:>5} {4096 // np:>9} {b['pod_steps_tsqr']:>5} {b.get('pod_steps_stacked', 0):>5} {b.get('pod_steps_tree', 0):>5} {b['pod_steps_replicated']:>5} "
                  f"{b['t_basis_s']:>8.1f} {b['t_basis_cpu_s']:>7.1f} {r['load']:>5}  {name}")
        break
for e in errors:
    print("  " + e)

rows = [(np, load(f"stages_np{np}")) for np in (1, 2)]
if any(r for _, r in rows):
    print("\nFOM and offline stages (NLS paper config; DEIM basis randomized, maxRank 110; GP-DEIM m = 100):")
    print(f"{'ranks':>5} {'fom_s':>7} {'train_s':>8} {'basis_s':>8} {'deim_basis_s':>12} {'gpdeim_s':>8} {'load':>5}")
    for np, r in rows:
        if r is None or r["rc"] != 0:
            continue
        s = r["summary"]; fom = s["runs"][0]; g = basis_run(s)
        print(f"{np:>5} {fom['t_online_s']:>7.1f} {g['t_training_s']:>8.1f} {g['t_basis_s']:>8.1f} "
              f"{g['t_deim_basis_s']:>12.1f} {g['t_online_s']:>8.2f} {r['load']:>5}")
PY
