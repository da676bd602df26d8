#!/usr/bin/env python3
"""The cost model of doc/scaling.md against bench/scaling.sh's CSV (python3 standard library only).

usage: python3 bench/scaling_model.py SCALING.csv

For each case and stage: the predicted compute seconds of the busiest rank (CPU outside MPI)
beside the measured ones, at every rank count of the CSV, and their ratio; then the model
extrapolated to p = 1024 ranks and n = 1e8 state rows, with the stage whose parallel efficiency
falls below 50 % first.

Machine constants, fitted on the 1-rank runs of the CSV (the model's p-dependence is not fitted):
  F_dense   flop rate of the dense LAPACK kernels (QR, SVD) of the streaming POD: one rate for
            the basis stages of both build cases (least squares on their 1-rank compute seconds);
  g_node    seconds per state row and parameter node of the model file's interpolation (each node
            a scene instance and its O(n k) to O(n k^2) projections), per scene: the NLS's nodes
            project onto 2k = 160 columns, the SWE's onto 40, and a single value fitted on both
            predicted the NLS's 1-rank stage at 0.25x;
  g_train   seconds per state row per time step of the training's integrator, per scene (NLS AVF
            and SWE IMR do different Newton and GMRES work per row);
  g_fom     the same for the full model case (SWE IMR with a fresh Jacobian every step), plus its
            set-up per state row;
  q_step    seconds per reduced time step of a query, and the query process's fixed set-up.
Communication (only for the extrapolated wall time; not measurable on one small machine):
  ALPHA = 2e-6 s per message, BETA = 1e-10 s per byte (10 GB/s): an InfiniBand-class cluster.
The DEIM basis stage: its hierarchical POD's chunk PODs over rank groups and its root (deim_flops).
"""
import csv
import math
import sys
from collections import OrderedDict, defaultdict

ALPHA, BETA = 2e-6, 1e-10
ROWS_PER_RANK = 4096  # packages/offline: kTrainingRowsPerRank, the rank-group rule
MAX_ROWS_PER_RANK = 2 ** 18  # packages/offline: kMaxTrainingRowsPerRank


def sizes_of(text):
    out = {}
    for part in text.split(";"):
        key, value = part.split("=")
        out[key] = [float(v) for v in value.split("+")] if "+" in value else float(value)
    return out


def state_rows(s):
    """2n for the NLS, 2 nx^2 for the SWE (chi and phi on the grid)."""
    return 2 * s["n"] if "n" in s else 2 * s["nx"] ** 2


# ---- work of the busiest rank, per stage (doc/scaling.md has the derivations) -------------------

def training_group(s, p):
    """packages/offline trainingGroupSize: p / G for the group count G with the least
    ceil(P / G) / floor(p / G) among those keeping 4096 .. 2^18 rows per rank (ties: more groups)."""
    rows, P = state_rows(s), int(s["points"])
    worth, hold = math.ceil(rows / ROWS_PER_RANK), math.ceil(rows / MAX_ROWS_PER_RANK)
    most, fewest = max(1, min(P, p // hold)), math.ceil(p / worth)
    if fewest > most:
        return max(1, min(p, p // min(fewest, p)))
    best = most
    for G in range(most, fewest - 1, -1):
        if math.ceil(P / G) * (p // best) < math.ceil(P / best) * (p // G):
            best = G
    return max(1, min(p, p // best))


def training_units(s, p):
    """State rows x time steps that the busiest rank integrates: rank groups of g ranks
    (training_group), G = p // g groups, ceil(P / G) parameters per group."""
    rows = state_rows(s)
    g = training_group(s, p)
    groups = max(1, p // g)
    return math.ceil(s["points"] / groups) * s["steps"] * rows / g


def svd_flops(m, n):
    """LAPACK GESDD of an m x n matrix with its thin singular vectors, counted as 4 (max + min)
    min^2: 8 c^3 for a c x c triangle, (8 + 4 (p - 1)) c^3 for a p c x c stack (bench/pod_tree_micro.cpp's
    count: the QR of the taller matrix and its Q applied, then the c x c SVD)."""
    big, small = max(m, n), min(m, n)
    return 4.0 * (big + small) * small * small


# The streaming POD's route rule and tree levels, by the code that measured a record: its sizes
# carry `treefrom` (the rank count from which podRoute auto takes the tree) and `tplevel` (1: the
# tree's levels are the structured TPQRT of two triangles, about 3 nc^3 with its Q applied). Records
# without them (gphr 408da5c and before) took the tree from 8 ranks, its levels a dense GEQRF/ORMQR of
# the 2 nc x nc stack (22/3 nc^3). The extrapolation uses the current code's rule.
TREE_FROM, TREE_LEVEL = 2, 3.0
OLD_TREE_FROM, OLD_TREE_LEVEL = 8, 22.0 / 3.0


def pod_rule(s):
    """(tree_from, level_flops_per_nc3) of the code that measured sizes s (see TREE_FROM)."""
    if s.get("tplevel", 0) >= 1:
        return int(s.get("treefrom", TREE_FROM)), TREE_LEVEL
    return int(s.get("treefrom", OLD_TREE_FROM)), OLD_TREE_LEVEL


def pod_flops(rows, cols, carried, block, p, rule=(TREE_FROM, TREE_LEVEL)):
    """Streaming POD (packages/reduction/src/StreamingPod.cpp) of a rows x cols matrix, blocks of
    `block` columns, at most `carried` triplets kept, step by step (the first steps are narrower:
    nothing carried yet). Per step of nc = carried + new columns, on the busiest rank (rank 0):
    its own rows' GEQRF and ORMQR, 4 (rows / p) nc k with k = min(rows / p, nc) (a rank may hold
    fewer rows than columns: its R factor is k x nc); then the replicated part: the stacked route
    (p below rule[0]) a GESDD of the stack of the p R factors (min(p k, rows) x nc, on every rank);
    the tree route ceil(log2 p) levels of rule[1] nc^3 (the QR of two stacked triangles and its Q
    applied on the way down) and one GESDD of the root's nc x nc factor."""
    tree_from, level = rule
    local_rows = rows / p
    total, done, kept = 0.0, 0, 0
    while done < cols:
        new = min(block, cols - done)
        nc = kept + new
        k = min(local_rows, nc)
        total += 4.0 * local_rows * nc * k
        if p < tree_from:
            total += svd_flops(min(p * k, rows), nc)
        else:
            total += math.ceil(math.log2(p)) * level * nc ** 3 + svd_flops(min(rows, nc), nc)
        kept = min(carried, nc, rows)
        done += new
    return total


def basis_flops(s, p):
    """PSD basis: the real form [D, J^T D] of the complex data: 2n rows, 2 N_s columns, blocks of
    2 x 128 columns, 2 (2k + 32) triplets carried (packages/offline/src/BasisStage.cpp)."""
    ns = s["points"] * (s["steps"] / s["every"] + 1)
    return pod_flops(state_rows(s), 2 * ns, 2 * (2 * s["k"] + 32), 256, p, pod_rule(s))


def basis_messages(s, p):
    """Messages and bytes per rank: stacked route an all-reduce of the p nc x nc stack per step,
    tree route log2 p messages of nc x nc (up and down)."""
    ns = s["points"] * (s["steps"] / s["every"] + 1)
    steps = math.ceil(2 * ns / 256)
    nc = 2 * (2 * s["k"] + 32) + 256
    if p < pod_rule(s)[0]:
        return steps * math.ceil(math.log2(max(p, 2))), steps * 8.0 * p * nc * nc
    return steps * 2 * math.ceil(math.log2(p)), steps * 2 * math.ceil(math.log2(p)) * 8.0 * nc * nc


DEIM_ROWS_PER_RANK = 2 ** 18  # packages/offline: kDeimRowsPerRank, the DEIM stage's rank-group rule


def deim_layout(s, p):
    """The hierarchical POD of the DEIM basis (packages/hyper/src/DeimBasis.cpp, DeimChunks): N_s
    reduced-Jacobian snapshots of d x 2k (d = n / 2 rows of G), R = max(m) + 32 triplets, chunks
    of about 32 R columns (C of them, `per` snapshots each), steps of ceil(R / 2k) snapshots; the
    stage's rank groups (packages/offline/src/DeimBasisStage.cpp): min(C, p / ceil(n / 2^18))
    groups of p / G ranks, ceil(C / G) rounds."""
    # every hyper-th stored state of each parameter (hyper.snapshotEvery, default 1)
    ns = s["points"] * math.ceil((s["steps"] / s["every"] + 1) / s.get("hyper", 1))
    r = 2 * s["k"]
    ms = s["m"] if isinstance(s["m"], list) else [s["m"]]
    R = max(ms) + 32
    C = math.ceil(ns / math.ceil(32 * R / r))
    per = math.ceil(ns / C)
    smallest = max(1, math.ceil(state_rows(s) / DEIM_ROWS_PER_RANK))
    G = min(C, p // smallest) if p > 1 and C > 1 else 1
    G = max(G, 1)
    return dict(ns=ns, r=r, R=R, C=C, per=per, block=math.ceil(R / r) * r, G=G, g=p // G,
                rounds=math.ceil(C / G), d=state_rows(s) / 2)


def deim_flops(s, p):
    """The busiest rank's flops: ceil(C / G) chunk PODs on its group (pod_flops of d rows, per 2k
    columns, R carried) and, on all p ranks, the root: one step per chunk of R carried + R new
    columns (rank 0 does the tree's or the stack's replicated part)."""
    L = deim_layout(s, p)
    chunk = pod_flops(L["d"], L["per"] * L["r"], L["R"], L["block"], L["g"], pod_rule(s))
    root = pod_flops(L["d"], L["C"] * L["R"], L["R"], L["R"], p, pod_rule(s))
    return L["rounds"] * chunk + root


def deim_messages(s, p):
    """Per round the all-reduce of its statistics and one export per chunk of the chunk's modes
    from its group (d R numbers over p ranks, a rank's rows from about 2 of the group's: d G R / p
    numbers received per rank and round); per root step as a basis step of R + R columns; per
    chunk step inside a group of g > 1 ranks the stack's all-reduce."""
    L = deim_layout(s, p)
    nc = 2 * L["R"]
    msgs = L["rounds"] * (2 * L["G"] + math.ceil(math.log2(max(p, 2))))
    byts = L["rounds"] * 8.0 * L["d"] * L["G"] * L["R"] / p
    if p < pod_rule(s)[0]:
        msgs += L["C"] * math.ceil(math.log2(max(p, 2)))
        byts += L["C"] * 8.0 * p * nc * nc
    else:
        msgs += L["C"] * 2 * math.ceil(math.log2(p))
        byts += L["C"] * 2 * math.ceil(math.log2(p)) * 8.0 * nc * nc
    return msgs, byts


def training_comm(s, p):
    """Seconds of messages of the busiest rank's training: inside a group of g > 1 ranks, per
    Newton-GMRES iteration two all-reduces (log2 g messages each) and a halo exchange (2); about
    30 such iterations per step (the order gphr run reports for the SWE IMR). Groups of one rank
    send nothing."""
    rows = state_rows(s)
    g = training_group(s, p)
    if g == 1:
        return 0.0
    per_group = math.ceil(s["points"] / max(1, p // g))
    return per_group * s["steps"] * 30 * (2 * math.ceil(math.log2(g)) + 2) * ALPHA


def parameter_seconds(t1):
    """Each training parameter's seconds on one rank (bench/scaling.sh's "training parameter J"
    rows, from the progress lines), in parameter order; [] where the CSV has none."""
    per = sorted((int(k.split()[-1]), v) for k, v in t1.items() if k.startswith("training parameter "))
    return [v for _, v in per]


def training_share(s, p, seconds):
    """The busiest rank's share of the 1-rank training work: group j of the G = p / g groups
    integrates parameters j, j + G, ... (packages/offline/src/Training.cpp, trainInGroups), each
    parameter costing what it cost on one rank, split ideally over the group's g ranks. Without
    per-parameter seconds every parameter costs the mean."""
    g = training_group(s, p)
    groups = max(1, p // g)
    P = int(s["points"])
    seconds = seconds if len(seconds) == P else [1.0] * P
    busiest = max(sum(seconds[j::groups]) for j in range(groups))
    return busiest / sum(seconds) / g


def interpolation_units(s, p):
    """Parameter nodes x state rows per rank: each node instantiates the scene and projects L, f
    and the reference rows on the basis (O(n k) per node)."""
    return s["nodes"] * state_rows(s) / p


# ---- fitting ------------------------------------------------------------------------------------

def load(path):
    rows = list(csv.DictReader(open(path)))
    # per case, ranks, stage: the busiest rank's compute seconds (or the wall of a timing row)
    table = defaultdict(dict)
    sizes = {}
    for r in rows:
        key = (r["case"], int(r["ranks"]))
        sizes[r["case"]] = sizes_of(r["sizes"])
        value = float(r["compute_s"]) if r["compute_s"] else float(r["wall_s"])
        table[key][r["stage"]] = max(table[key].get(r["stage"], 0.0), value)
    return table, sizes


def is_rest(stage):
    """The small stages the model takes together as `rest`."""
    return stage in ("setup", "instance", "header", "write") or stage.startswith("gp-deim")


def fit(table, sizes):
    c = {}
    builds = [x for x in ("nls", "swe") if (x, 1) in table]
    # F_dense: least squares of compute = flops / F through the origin over the basis stages.
    num = sum(basis_flops(sizes[x], 1) ** 2 for x in builds)
    den = sum(basis_flops(sizes[x], 1) * table[(x, 1)]["basis"] for x in builds)
    c["F_dense"] = num / den if den > 0 else float("nan")
    for x in builds:
        interp = sum(v for k, v in table[(x, 1)].items() if k.startswith("interpolation"))
        c["g_node_" + x] = interp / interpolation_units(sizes[x], 1)
        deim = sum(v for k, v in table[(x, 1)].items() if k.startswith("deim basis"))
        c["F_deim_" + x] = deim_flops(sizes[x], 1) / deim if deim > 0 else float("nan")
        c["g_train_" + x] = table[(x, 1)]["training"] / training_units(sizes[x], 1)
        c["training_" + x] = table[(x, 1)]["training"]
        c["parameters_" + x] = parameter_seconds(table[(x, 1)])
        c["rest_" + x] = sum(v for k, v in table[(x, 1)].items() if is_rest(k))
    # The small stages (set-up, instance, header, gp-deim, write): a fixed part per process (the
    # Tpetra objects, the config, rank 0's header and write) plus row work that divides with the
    # ranks (the scene's assembly, the instance, the DEIM indices): rest = a + b n / p, a and b from
    # the two scenes' 1-rank runs (4096 and 131,072 state rows). A CSV with one scene cannot
    # separate them: its 1-rank rest is held fixed (b = 0).
    if len(builds) == 2:
        (n1, t1), (n2, t2) = [(state_rows(sizes[x]), c["rest_" + x]) for x in builds]
        b = (t2 - t1) / (n2 - n1)
        c["rest_a"], c["rest_b"] = t1 - b * n1, b
    elif builds:
        c["rest_a"], c["rest_b"] = c["rest_" + builds[0]], 0.0
    if ("fom", 1) in table:
        s = sizes["fom"]
        c["g_fom"] = table[("fom", 1)]["process"] / (s["steps"] * state_rows(s))
    if ("query", 1) in table:
        s = sizes["query"]
        loop = table[("query", 1)]["queries"]  # one rank: the query loop waits for nobody
        c["q_step"] = loop / (s["queries"] * s["steps"])
        c["q_setup"] = table[("query", 1)]["process"] - loop
    return c


def predict(case, stage, s, p, c):
    """Predicted compute seconds of the busiest rank, or None where the model has none."""
    if case in ("nls", "swe"):
        if stage == "training":
            return c["training_" + case] * training_share(s, p, c["parameters_" + case])
        if stage == "basis":
            return basis_flops(s, p) / c["F_dense"]
        if stage.startswith("interpolation"):
            return c["g_node_" + case] * interpolation_units(s, p)
        if stage == "rest":
            return c["rest_a"] + c["rest_b"] * state_rows(s) / p
        if stage.startswith("deim basis"):
            return deim_flops(s, p) / c["F_deim_" + case]
        return None
    if case == "fom" and stage == "process":
        return c["g_fom"] * s["steps"] * state_rows(s) / p
    if case == "query" and stage == "process":
        return c["q_setup"] + c["q_step"] * math.ceil(s["queries"] / p) * s["steps"]
    return None


def main():
    table, sizes = load(sys.argv[1])
    c = fit(table, sizes)
    print("machine constants (1-rank runs): " + ", ".join(
        f"{k} = {v:.3e}" for k, v in c.items() if not k.startswith(("rest", "training_", "parameters_"))))
    print(f"{'case':<6} {'stage':<20} {'ranks':>5} {'measured s':>11} {'predicted s':>11} {'pred/meas':>9}")
    worst = {}
    for case in OrderedDict.fromkeys(k[0] for k in table):
        ranks = sorted(p for (x, p) in table if x == case)
        stages = OrderedDict()
        for p in ranks:
            for st in table[(case, p)]:
                if case in ("nls", "swe") and is_rest(st):
                    stages["rest"] = None
                elif case in ("nls", "swe") and (st == "process" or st.startswith("training parameter")):
                    continue
                elif case in ("fom", "query") and st != "process":
                    continue
                else:
                    stages[st] = None
        for st in stages:
            for p in ranks:
                t = table[(case, p)]
                if st == "rest":
                    meas = sum(v for k, v in t.items() if is_rest(k))
                else:
                    meas = t.get(st)
                pred = predict(case, st, sizes[case], p, c)
                ratio = pred / meas if pred is not None and meas else None
                if ratio is not None and p > 1:
                    worst[(case, st)] = max(worst.get((case, st), (0.0, 1.0)), (abs(math.log(ratio)), ratio))
                print(f"{case:<6} {st:<20} {p:>5} {meas:>11.3f} "
                      f"{('-' if pred is None else f'{pred:.3f}'):>11} {('-' if ratio is None else f'{ratio:.2f}'):>9}"
                      )
    if worst:
        print("largest |pred/meas - 1| at p > 1 per stage: " + ", ".join(
            f"{c_}/{s_} {r - 1:+.0%}" for (c_, s_), (w, r) in worst.items()))
    route_rule_effect(table, sizes, c)
    extrapolate(sizes, c, None)
    extrapolate(sizes, c, 1e8)


def route_rule_effect(table, sizes, c):
    """At each build case's largest rank count in the CSV: the busiest rank's predicted compute of the
    basis and the DEIM basis under the record's POD route rule and under the current code's."""
    for case in ("nls", "swe"):
        ranks = [p for (x, p) in table if x == case]
        if case not in sizes or not ranks or "F_deim_" + case not in c:
            continue
        p, s = max(ranks), sizes[case]
        now = dict(s, treefrom=TREE_FROM, tplevel=1)
        print(f"{case} at p = {p}, predicted compute s under the record's POD route rule -> the current one: "
              f"basis {basis_flops(s, p) / c['F_dense']:.2f} -> {basis_flops(now, p) / c['F_dense']:.2f}, "
              f"deim basis {deim_flops(s, p) / c['F_deim_' + case]:.2f} -> {deim_flops(now, p) / c['F_deim_' + case]:.2f}")


def extrapolate(sizes, c, total_rows):
    """p = 1 .. 1024 at `total_rows` state rows (None: the CSV's), with each case's other sizes: per
    stage the busiest rank's compute seconds plus the communication time, and the parallel
    efficiency T(1) / (p T(p))."""
    print(f"\nextrapolated to p = 1024 at {'the CSV sizes' if total_rows is None else f'{total_rows:g} state rows'}"
          " (other sizes as in the CSV's cases), time = compute + ALPHA messages + BETA bytes (efficiency):")
    ps = [1, 8, 64, 256, 1024]
    first = None
    for case in ("nls", "swe"):
        if case not in sizes or "g_train_" + case not in c:
            continue
        s = dict(sizes[case], treefrom=TREE_FROM, tplevel=1)  # the current code's POD route rule
        if total_rows is not None and "n" in s:
            s["n"] = 0.5 * total_rows
        elif total_rows is not None:
            s["nx"] = math.sqrt(0.5 * total_rows)
        rows = state_rows(s)
        stages = {
            # training: per GMRES iteration 2 all-reduces (log2 p messages) and a halo exchange (2);
            # about 30 iterations per step (GMRES + Newton, measured order on the SWE): 130 messages.
            "training": lambda p: (c["g_train_" + case] * training_units(s, p), training_comm(s, p)),
            "basis": lambda p: (basis_flops(s, p) / c["F_dense"],
                                basis_messages(s, p)[0] * ALPHA + basis_messages(s, p)[1] * BETA),
            "deim basis": lambda p: (deim_flops(s, p) / c["F_deim_" + case],
                                     deim_messages(s, p)[0] * ALPHA + deim_messages(s, p)[1] * BETA),
            "interpolation": lambda p: (c["g_node_" + case] * interpolation_units(s, p),
                                        s["nodes"] * math.ceil(math.log2(max(p, 2))) * (ALPHA + BETA * 8 * (2 * s["k"]) ** 2)),
        }
        print(f"  {case} ({', '.join(f'{k}={v:g}' for k, v in s.items() if not isinstance(v, list))}):")
        print(f"    {'stage':<14}" + "".join(f"{'p=' + str(p):>22}" for p in ps))
        for name, f in stages.items():
            t1 = sum(f(1))
            cells, dropped = [], None
            for p in ps:
                comp, comm = f(p)
                eff = t1 / (p * (comp + comm))
                cells.append(f"{comp + comm:9.3g}s ({eff:4.0%})")
            for p in (2 ** j for j in range(1, 11)):
                if t1 / (p * sum(f(p))) < 0.5:
                    dropped = p
                    break
            print(f"    {name:<14}" + "".join(f"{x:>22}" for x in cells)
                  + (f"   efficiency < 50% from p = {dropped}" if dropped else ""))
            if dropped and (first is None or dropped < first[0]):
                first = (dropped, f"{case} {name}")
    if first:
        print(f"first to stop scaling (efficiency below 50%): {first[1]} at p = {first[0]}")
    else:
        print("no modelled stage falls below 50% efficiency up to p = 1024")


if __name__ == "__main__":
    main()
