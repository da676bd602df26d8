#!/usr/bin/env python3
"""Content checks of a `gphr` summary.json, shared by the CLI tests.

  check_summary.py check SUMMARY --scene S --scheme imr|avf --n N --steps N
                   [--newton-tol TOL] [--H-rel-max X] [--rom-k K --rom-E-L2 LO HI]
      the documented keys are there, every number is finite, the full model ("fom") ran the
      expected size and steps with Newton converged to TOL (default 1e-10, the default
      integrator.newtonTolerance), for AVF H drifted by at most the run's H_drift_bound (plus
      round-off), with --H-rel-max by at most that fraction of |H0|, and, with --rom-k, the Galerkin
      ROM ran with 2k = reducedDim, conserved its H_r like the full model and has E_L2 in [LO, HI].
  check_summary.py adeim-updates SUMMARY CSV
      adeim_updates.csv against the summary: one row per update of every gp-adeim run, the
      documented columns, rank <= coefficient_rank <= m, the residual at S not raised by an
      update, bound - paper_bound the earlier deim_start terms, the full-row residual (when monitored) at least the one at S, and each run's
      t_total_s = t_hyper_offline_s + t_online_s.
  check_summary.py same SUMMARY_A SUMMARY_B
      the ROM of two runs (e.g. on 1 and 2 ranks) has the same E_L2, E_fin, energy_captured and
      the same (round-off level) H_err_max; see same() for the tolerances.
"""
import argparse
import json
import math
import sys

# AVF with an exact rule is a discrete gradient: per step H(y1) - H(y0) = gbar^T R for the
# accepted Newton residual R, so every run's own Hamiltonian drifts by at most H_drift_bound =
# sum_steps ||gbar|| ||R|| (summary.json) plus the round-off of evaluating H at two states, a sum
# of ~3n terms with relative error ~n eps (1e-13 at n = 256): H_ROUNDOFF (1 + |H0|) allows n to
# ~4000. Measured on the default run: drifts 2e-13 .. 1.4e-10 against bounds 4e-12 .. 1.4e-8. IMR
# (no such bound for the NLS's quartic G: H_drift_bound null) drifts O(dt^2), 3.9e-5 on that run.
H_ROUNDOFF = 1e-12


def require_avf_drift(run, drift, h0, what):
    """The run's own Hamiltonian drifted by `drift`, within its H_drift_bound plus round-off."""
    bound = run.get("H_drift_bound")
    require(bound is not None, "%s: H_drift_bound is null under AVF (its rule not exact?)" % what)
    require(drift <= bound + H_ROUNDOFF * (1 + abs(h0)),
            "%s: H drifted by %r, above its bound %r + round-off" % (what, drift, bound))

TOP_KEYS = ("scene", "integrator", "parameters", "machine", "runs")
FOM_KEYS = ("method", "n", "fullDim", "steps", "dt", "ranks", "t_online_s", "newton_iters_avg",
            "linear_iters_avg", "newton_residual_max", "H0", "H_err_max", "H_err_max_rel", "status")
ROM_KEYS = ("method", "basis", "k", "reducedDim", "energy_captured", "steps", "E_L2", "E_fin",
            "H_err_max", "H_err_max_rel", "t_online_s", "t_offline_s", "newton_iters_avg", "status",
            "pod_route", "pod_steps_tsqr", "pod_steps_stacked", "pod_steps_replicated")


def fail(msg):
    print("summary check failed:", msg)
    sys.exit(1)


def require(cond, msg):
    if not cond:
        fail(msg)


def run_of(summary, method):
    runs = [r for r in summary["runs"] if r.get("method") == method]
    require(len(runs) == 1, "expected one '%s' run, got %d: %s" % (method, len(runs), summary["runs"]))
    return runs[0]


def check_keys_and_numbers(run, keys):
    """The keys are there and not null (summary.json writes a non-finite number as null, so a NaN
    or Inf result arrives here as None), and every number present is finite."""
    for k in keys:
        require(k in run, "%s run: key '%s' missing: %s" % (run.get("method"), k, run))
        require(run[k] is not None, "%s run: %s is null (non-finite in the run)" % (run.get("method"), k))
    for k, v in run.items():
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            require(math.isfinite(v), "%s run: %s = %r is not finite" % (run["method"], k, v))
    require(run["status"] == "ok", "%s run: status %r" % (run["method"], run["status"]))


def check(a):
    s = json.load(open(a.summary))
    for k in TOP_KEYS:
        require(k in s, "key '%s' missing" % k)
    require(s["scene"] == a.scene and s["integrator"] == a.scheme, (s["scene"], s["integrator"]))
    fom = run_of(s, "fom")
    check_keys_and_numbers(fom, FOM_KEYS)
    require(fom["n"] == a.n and fom["fullDim"] == 2 * a.n and fom["steps"] == a.steps,
            "fom size/steps: n %s, fullDim %s, steps %s" % (fom["n"], fom["fullDim"], fom["steps"]))
    require(fom["newton_iters_avg"] >= 1 and 0 <= fom["newton_residual_max"] <= a.newton_tol,
            "fom Newton: %s iterations/step, max residual %s" % (fom["newton_iters_avg"], fom["newton_residual_max"]))
    require(a.scheme == "avf" or a.H_rel_max is not None, "IMR does not conserve H: give --H-rel-max")
    require(abs(fom["H0"]) > 0, "fom H0 is 0")
    if a.scheme == "avf":
        require_avf_drift(fom, fom["H_err_max"], fom["H0"], "fom")
    if a.H_rel_max is not None:
        require(fom["H_err_max_rel"] <= a.H_rel_max,
                "fom H_err_max_rel %s > %s (H0 %s)" % (fom["H_err_max_rel"], a.H_rel_max, fom["H0"]))
    if a.rom_k is None:
        require(len(s["runs"]) == 1, "unexpected runs: %s" % s["runs"])
        return "fom n=%d H_err_rel=%.2e" % (fom["n"], fom["H_err_max_rel"])
    rom = run_of(s, "rom")
    check_keys_and_numbers(rom, ROM_KEYS)
    require(rom["k"] == a.rom_k and rom["reducedDim"] == 2 * a.rom_k and rom["steps"] == a.steps,
            "rom k/reducedDim/steps: %s" % rom)
    require(0 < rom["energy_captured"] <= 1 + 1e-12, "rom energy_captured %s" % rom["energy_captured"])
    # The ROM is integrated with the same scheme: AVF conserves H_r(z) = H(y0 + A z) to its own bound.
    if a.scheme == "avf":
        require_avf_drift(rom, rom["H_err_max"], fom["H0"], "rom")
    lo, hi = a.rom_E_L2
    require(lo <= rom["E_L2"] <= hi and 0 < rom["E_fin"], "rom E_L2 %s outside [%s, %s] (E_fin %s)"
            % (rom["E_L2"], lo, hi, rom["E_fin"]))
    msg = "fom n=%d H_err_rel=%.2e; rom k=%d E_L2=%.6g E_fin=%.6g" % (
        fom["n"], fom["H_err_max_rel"], rom["k"], rom["E_L2"], rom["E_fin"])
    if a.gp_deim:
        msg += "; " + check_gp_deim(s, rom, a)
    if a.gp_adeim:
        msg += "; " + check_gp_adeim(s, rom, a)
    return msg


def check_gp_deim(s, rom, a):
    """GP-DEIM runs for every m asked: each ran (status ok, finite numbers), AVF conserved its own
    H_hr to the same bound as the full model (H_model_err_max), and at the largest m the error is
    within RATIO of the reduced model's (the 10% target is the benchmark's; here the
    default scene's measured ratio 1.0000 at m = 40 gets the same 10%)."""
    want = sorted(a.gp_deim[:-1])
    ratio = a.gp_deim[-1]
    runs = [r for r in s["runs"] if r.get("method") == "gp-deim"]
    require(sorted(r["m"] for r in runs) == want, "gp-deim runs for m = %s, expected %s" % ([r["m"] for r in runs], want))
    for r in runs:
        check_keys_and_numbers(r, ("E_L2", "E_fin", "t_online_s", "H_model_err_max", "cond_PtU", "t_offline_s"))
        if a.scheme == "avf":
            require_avf_drift(r, r["H_model_err_max"], run_of(s, "fom")["H0"], "gp-deim m=%d: H_hr" % r["m"])
    top = max(runs, key=lambda r: r["m"])
    require(top["E_L2"] <= ratio * rom["E_L2"], "gp-deim m=%d E_L2 %r > %s x rom %r" % (top["m"], top["E_L2"], ratio, rom["E_L2"]))
    return "gp-deim m=%s E_L2(m=%d)/E_L2(rom)=%.4f" % (want, top["m"], top["E_L2"] / rom["E_L2"])


def check_gp_adeim(s, rom, a):
    """GP-ADEIM runs for every m asked: each ran with its updates (one every delta steps from
    delta0 on), each local H_hr^j was conserved by AVF to the full model's bound on its interval
    (H_model_err_max is that largest local drift), and at the smallest m, where the fixed DEIM
    basis is too small, the adaptive error is within RATIO of the reduced model's and below the
    non-adaptive GP-DEIM error of the same m (measured on the default scene, m = 10: 0.0237
    against the ROM's 0.0241 and GP-DEIM's 0.654)."""
    want = sorted(int(m) for m in a.gp_adeim[:-1])
    ratio = a.gp_adeim[-1]
    runs = [r for r in s["runs"] if r.get("method") == "gp-adeim"]
    require(sorted(r["m"] for r in runs) == want, "gp-adeim runs for m = %s, expected %s" % ([r["m"] for r in runs], want))
    h0 = abs(run_of(s, "fom")["H0"])
    for r in runs:
        check_keys_and_numbers(r, ("E_L2", "E_fin", "t_online_s", "H_model_err_max", "t_total_s", "t_updates_s"))
        updates = (a.steps - r["delta0"]) // r["delta"] + 1
        ran = r["updates"] + r.get("updates_skipped", 0)  # run or skipped (adeim.updateTol)
        require(ran == updates, "gp-adeim m=%d: %r updates, expected %d" % (r["m"], ran, updates))
        if a.scheme == "avf":  # the sum over all steps bounds each update interval's
            require_avf_drift(r, r["H_model_err_max"], h0, "gp-adeim m=%d: a local H_hr" % r["m"])
    low = min(runs, key=lambda r: r["m"])
    require(low["E_L2"] <= ratio * rom["E_L2"], "gp-adeim m=%d E_L2 %r > %s x rom %r" % (low["m"], low["E_L2"], ratio, rom["E_L2"]))
    fixed = [r for r in s["runs"] if r.get("method") == "gp-deim" and r.get("m") == low["m"]]
    require(not fixed or low["E_L2"] < fixed[0]["E_L2"],
            "gp-adeim m=%d E_L2 %r is not below gp-deim's %r" % (low["m"], low["E_L2"], fixed[0]["E_L2"] if fixed else 0))
    return "gp-adeim m=%s E_L2(m=%d)/E_L2(rom)=%.4f" % (want, low["m"], low["E_L2"] / rom["E_L2"])


ADEIM_COLUMNS = ("run", "k", "m", "update", "step", "t", "rank", "coefficient_rank", "m_s", "resampled",
                 "sampled_residual_before", "sampled_residual_after", "full_residual", "window_norm", "cond1_PtU", "update_s",
                 "dH_total", "eps_fom", "eps_hr", "deim_end", "deim_start", "bound", "paper_bound", "skipped", "indicator")


def adeim_updates(a):
    """The per-update CSV of the report. The residuals: an update minimizes ||S^T (U C - F)||_F
    over rank-r corrections including zero, so it never raises it (1e-12 relative: round-off of
    a norm of ~1e3 terms); the rows S are a subset of all d rows, so ||U_{j+1} C_j - F_j||_F over
    all rows is at least the part at S (same round-off allowance). bound - paper_bound is the sum
    of the earlier updates' deim_start (the CSV prints 10 digits, so 1e-8 of bound covers the
    rounding of up to 100 terms): it fails if the columns are mis-assembled. t_total_s is
    t_hyper_offline_s + t_online_s: the summary prints 17 digits and the sums differ by one
    rounding, so 1e-12 relative."""
    import csv
    s = json.load(open(a.summary))
    rows = list(csv.DictReader(open(a.csv)))
    require(rows, "no rows in %s" % a.csv)
    require(tuple(rows[0].keys()) == ADEIM_COLUMNS, "columns %s, expected %s" % (list(rows[0].keys()), ADEIM_COLUMNS))
    runs = [r for r in s["runs"] if r.get("method") == "gp-adeim"]
    require(runs, "no gp-adeim run in the summary")
    monitored = 0
    for r in runs:
        total = r["t_hyper_offline_s"] + r["t_online_s"]
        require(abs(r["t_total_s"] - total) <= 1e-12 * total,
                "gp-adeim m=%d: t_total_s %r != t_hyper_offline_s + t_online_s = %r" % (r["m"], r["t_total_s"], total))
        mine = [x for x in rows if int(x["k"]) == r["k"] and int(x["m"]) == r["m"]]
        checks = r["updates"] + r.get("updates_skipped", 0)  # a skipped update (adeim.updateTol) has its row too
        require(len(mine) == checks, "gp-adeim m=%d: %d CSV rows for %d updates" % (r["m"], len(mine), checks))
        starts = 0.0
        for x in mine:
            f = {k: float(v) for k, v in x.items() if k != "run"}
            where = "gp-adeim m=%d update %d" % (r["m"], f["update"])
            # m_s >= m unless d - m rows are fewer (S lies outside P)
            require(0 <= f["rank"] <= f["coefficient_rank"] <= r["m"] and f["m_s"] >= 1,
                    "%s: rank %g, coefficient rank %g, m %d, m_s %g" % (where, f["rank"], f["coefficient_rank"], r["m"], f["m_s"]))
            # A skipped update (adeim.updateTol) changed nothing and had its indicator computed; -1
            # marks an indicator not computed (updateTol 0, the default, or the first update).
            require(f["skipped"] in (0, 1) and (f["indicator"] == -1 or f["indicator"] >= 0),
                    "%s: skipped %g, indicator %g" % (where, f["skipped"], f["indicator"]))
            require(not f["skipped"] or (f["rank"] == 0 and f["indicator"] >= 0),
                    "%s: skipped with rank %g, indicator %g" % (where, f["rank"], f["indicator"]))
            require(f["sampled_residual_after"] <= f["sampled_residual_before"] * (1 + 1e-12),
                    "%s: the residual at S rose from %g to %g" % (where, f["sampled_residual_before"], f["sampled_residual_after"]))
            if f["full_residual"] >= 0:
                monitored += 1
                # The rows of S are among all d rows, so the full residual is at least the one at S,
                # unless both are below what the fit resolves: directions of C_j with |R_ll| under
                # adeim.coefficientTol (1e-10) |R_11| are cut, so a window inside span(U) leaves
                # residuals of up to ~1e-10 ||F_j|| that say nothing about S (default run, m = 40 =
                # 2k w: 2.3e-10 over all rows against 3.4e-10 at S, ||F_j|| = 5.1). Compared above
                # 10x that floor.
                require(f["full_residual"] >= f["sampled_residual_after"] * (1 - 1e-12) - 1e-9 * f["window_norm"],
                        "%s: full residual %g below the one at S %g (||F_j|| %g)"
                        % (where, f["full_residual"], f["sampled_residual_after"], f["window_norm"]))
            require(abs(f["bound"] - f["paper_bound"] - starts) <= 1e-8 * f["bound"],
                    "%s: bound %g - paper_bound %g != the earlier deim_start terms %g" % (where, f["bound"], f["paper_bound"], starts))
            starts += f["deim_start"]
    if a.monitored:
        require(monitored == len(rows), "full_residual recorded at %d of %d updates" % (monitored, len(rows)))
    return "%d update rows of %d gp-adeim runs, %d with the full residual" % (len(rows), len(runs), monitored)


def same(a):
    """Same ROM results from two runs of one config (1 and 2 ranks).

    The runs differ only by summation order and by where Newton stops (the preconditioner is
    block Jacobi per rank). With the config's Newton tolerance 1e-13 (absolute; states of norm
    >= 1), each step's solution differs by <= ~1e-13 (K = I + O(dt)), so 200 steps of training and
    200 of the ROM give state differences <= ~1e-11 and |dE| <= ~1e-11 on errors E ~ 1e-2: 1e-8
    relative on E_L2, E_fin and energy_captured leaves a factor >= 10 (measured: 1e-14).
    H_err_max is round-off on both (AVF), so its relative difference is noise; both must be below
    1e-12 |H0| (round-off of H: n eps |H| ~ 3e-14 |H0| per evaluation, over 200 steps) and hence
    agree to that.
    """
    sa, sb = (json.load(open(f)) for f in (a.a, a.b))
    ra, rb = run_of(sa, "rom"), run_of(sb, "rom")
    h0 = abs(run_of(sa, "fom")["H0"])  # H_r(A^T y0) = H(y0) up to the projection error
    for k in ("k", "basis", "reducedDim", "steps"):
        require(ra[k] == rb[k], "%s: %s vs %s" % (k, ra[k], rb[k]))
    for k in ("E_L2", "E_fin", "energy_captured"):
        require(abs(ra[k] - rb[k]) <= 1e-8 * abs(ra[k]), "%s differs: %r vs %r" % (k, ra[k], rb[k]))
    for r in (ra, rb):
        require(r["H_err_max"] <= 1e-12 * h0, "H_err_max %r > 1e-12 |H0| = %r" % (r["H_err_max"], 1e-12 * h0))
    return "E_L2 %.15g vs %.15g, E_fin %.15g vs %.15g" % (ra["E_L2"], rb["E_L2"], ra["E_fin"], rb["E_fin"])


def main():
    p = argparse.ArgumentParser()
    sub = p.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("check")
    c.add_argument("summary")
    c.add_argument("--scene", required=True)
    c.add_argument("--scheme", required=True, choices=("imr", "avf"))
    c.add_argument("--n", type=int, required=True)
    c.add_argument("--steps", type=int, required=True)
    c.add_argument("--H-rel-max", type=float)
    c.add_argument("--newton-tol", type=float, default=1e-10, help="the config's integrator.newtonTolerance")
    c.add_argument("--rom-k", type=int)
    c.add_argument("--rom-E-L2", type=float, nargs=2, metavar=("LO", "HI"))
    c.add_argument("--gp-deim", type=float, nargs="+", metavar="M",
                   help="m values of the gp-deim runs, then the allowed E_L2 ratio to the rom at the largest m")
    c.add_argument("--gp-adeim", type=float, nargs="+", metavar="M",
                   help="m values of the gp-adeim runs, then the allowed E_L2 ratio to the rom at the smallest m")
    c.set_defaults(fn=check)
    u = sub.add_parser("adeim-updates")
    u.add_argument("summary")
    u.add_argument("csv")
    u.add_argument("--monitored", action="store_true", help="every update recorded the full-row residual")
    u.set_defaults(fn=adeim_updates)
    d = sub.add_parser("same")
    d.add_argument("a")
    d.add_argument("b")
    d.set_defaults(fn=same)
    a = p.parse_args()
    if a.cmd == "check" and (a.rom_k is None) != (a.rom_E_L2 is None):
        p.error("--rom-k and --rom-E-L2 go together")
    print("ok:", a.fn(a))


if __name__ == "__main__":
    main()
