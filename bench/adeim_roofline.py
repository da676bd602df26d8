#!/usr/bin/env python3
"""Per-stage roofline of one GP-ADEIM update, from a `gphr run --verbose` of the NLS scene.

usage: adeim_roofline.py RUN_LOG SUMMARY_JSON CONFIG_YAML RANKS CALIBRATION_TXT

Times: the run's timer table (TimeMonitor, mean over the ranks, divided by the call count). Flops
and bytes: counted per rank from the sizes (leading-order LAPACK counts, LAWN 41; full rank r_C = m
assumed) with d = n rows of G (the NLS: each term reads q_i and p_i, t = 2 entries of the state),
d_own = d / ranks rows per rank, 2k, wbar = 2k w, m and m_s (its mean over the updates). The roofs:
this machine's DGEMM at the update's shape and its copy bandwidth, both printed by
adeim_update_micro (the calibration before the case). A stage is called
  compute: its flops at the DGEMM rate take longer than its bytes at the copy bandwidth,
  memory:  the other way round,
and latency where its time is over 4x both (collectives, small calls, waits for the other rank).
"""
import json
import re
import sys


def sizes(summary, config, ranks):
    n = int(re.search(r"scene: \{name: nls1d, n: (\d+)", config).group(1))
    w = int(re.search(r"window: (\d+)", config).group(1))
    run = next(r for r in summary["runs"] if r["method"] == "gp-adeim")
    k, m = run["k"], run["m"]
    ms = run.get("num_samples_mean") or 0.0
    return dict(d=n, dl=n / ranks, k2=2 * k, W=2 * k * w, M=m, S=ms, Sl=ms / ranks, np=ranks, t=2)


def stages(z):
    """(timer, what, flops, bytes) per rank and update."""
    d, dl, k2, W, M, S, Sl, t = z["d"], z["dl"], z["k2"], z["W"], z["M"], z["S"], z["Sl"], z["t"]
    return [
        ("window at P", "F_j at P (m x wbar), C_j = (P^T U)^-1 P^T F_j (GETRF, GETRI, GEMM)",
         2 * t * M * W + 2 * M**3 + 2 * M * M * W, 8 * (t * M * k2 + 2 * M * W + 2 * M * M)),
        ("update indicator", "S^T F_j on the own rows of S, ||S^T (U C - F)|| (adeim.updateTol)",
         2 * t * S * W + 2 * Sl * M * W, 8 * (t * S * k2 + S * W + Sl * M + M * W)),
        ("coefficient factor", "pivoted QR of C_j^T (GEQP3), T^+ (TRTRI), Q_1 (ORMQR)",
         (2 * W * M * M - 2 / 3 * M**3) + M**3 / 3 + (4 * W * M * M - 2 * M**3), 8 * (M * W + W * M + 2 * M * M)),
        ("resampling: F_j on own rows", "J_G(y) A on d/p rows",
         2 * t * dl * W, 8 * (2 * t * dl * k2 + dl * W)),  # A_S read by the lift and by the Jacobian
        ("resampling: row scores", "U T^T - F Q_1, row norms",
         2 * dl * M * M + 2 * dl * W * M + 2 * dl * M, 8 * (dl * M + dl * W + W * M + M * M + dl)),
        ("resampling: select", "m_s largest scores over the ranks",
         dl * 10, 8 * (dl + 2 * z["np"] * S)),
        ("rank-r update: dense algebra", "X = S^T U C - S^T F, X Q_1, QR, two SVDs (one per rank)",
         2 * Sl * M * W + 2 * Sl * W * M + (2 * S * M * M - 2 / 3 * M**3) + (2 * M**3 + 2 * 8 / 3 * M**3) / z["np"],
         8 * (Sl * M + Sl * W + M * W + W * M + S * M + 2 * M * M)),
        ("rank-r update|rank-r update: dense algebra", "S^T F_j and S^T U_j read, S^T U_{j+1} = S^T U_j + a b^T written",
         2 * Sl * M * M, 8 * (Sl * W + 3 * Sl * M)),
        ("orthonormalization", "SYRK, pivoted Cholesky, TRMM",
         dl * M * M + M**3 / 3 + M**3 / 3 + dl * M * M, 8 * 3 * dl * M),
        ("indices: selection", "greedy DEIM, one collective per index",
         dl * M * M - M**3 / 3, 8 * 2 * dl * M),
        ("indices: weights", "P^T U gathered, weights solved",
         2 / 3 * M**3 + 2 * M * M, 8 * 2 * M * M),
        ("indices: sample mesh of P", "rows of A at the new P gathered",
         0.0, 8 * t * M * k2),
    ]


def main():
    log, summary, config, ranks, calib = sys.argv[1:6]
    text = open(log).read()
    cal = open(calib).read()
    peak = float(re.search(r"DGEMM [^:]*: ([\d.]+) GFlop/s", cal).group(1))
    bw = float(re.search(r"memory bandwidth \(copy[^)]*\): ([\d.]+) GB/s", cal).group(1))
    z = sizes(json.load(open(summary)), open(config).read(), int(ranks))
    rows = []
    def timer_mean(name):  # (mean over the ranks, calls) of a timer, or None
        mt = re.search(r"gphr: gp-adeim %s\s+\S+ \(\d+\)\s+([\d.e+-]+) \((\d+)\)" % re.escape(name), text)
        return (float(mt.group(1)), int(mt.group(2))) if mt else None

    for timer, what, flops, nbytes in stages(z):
        parts = [timer_mean(x) for x in timer.split("|")]  # "A|B": timer A less its part B
        if any(p is None for p in parts):
            continue
        mean, calls = parts[0][0] - sum(p[0] for p in parts[1:]), parts[0][1]
        ms = 1e3 * mean / calls
        tc, tm = flops / (peak * 1e9) * 1e3, nbytes / (bw * 1e9) * 1e3
        bound = "latency" if ms > 4 * max(tc, tm) else ("compute" if tc >= tm else "memory")
        rate = flops / (ms * 1e6) if ms > 0 else 0.0
        rows.append((timer.replace("|rank-r update: dense algebra", ": rows S in, out"), ms, flops / 1e6, nbytes / 1e6, flops / nbytes if nbytes else 0.0, rate,
                     100 * rate / peak, tc, tm, bound, what))
    print("roofline per update stage (per rank; roofs from the calibration before: DGEMM %.1f GFlop/s, copy %.1f GB/s;"
          " d = %d, d/p = %d, 2k = %d, wbar = %d, m = %d, m_s = %.0f, %d rank(s)):"
          % (peak, bw, z["d"], z["dl"], z["k2"], z["W"], z["M"], z["S"], z["np"]))
    print("  %-29s %7s %7s %6s %6s %7s %6s %8s %8s  %-8s %s" % ("stage", "ms", "MFlop", "MB", "flop/B", "GFlop/s",
                                                                "%peak", "ms@peak", "ms@bw", "bound", "work"))
    for r in rows:
        print("  %-29s %7.3f %7.2f %6.2f %6.1f %7.2f %5.0f%% %8.3f %8.3f  %-8s %s" % r)
    total = sum(r[1] for r in rows)
    floor = sum(max(r[7], r[8]) for r in rows)
    print("  %-29s %7.3f %47s %8.3f  (time at the roofs, summed)" % ("all stages", total, "", floor))


if __name__ == "__main__":
    main()
