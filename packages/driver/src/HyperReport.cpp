#include "gphr/driver/HyperReport.hpp"

#include <algorithm>
#include <functional>
#include <cmath>
#include <fstream>
#include <sstream>

#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/driver/Gnuplot.hpp"
#include "gphr/driver/ModelEvaluation.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

namespace {

// csv: the data are CSV files whose first line names the columns (the plots address them by name).
bool gnuplot(const std::string& png, const std::string& body, bool csv = true) {
  const std::string script = png + ".gp";
  std::ofstream(script) << "set terminal pngcairo size 1000,560 noenhanced\nset output " << gnuplotQuoted(png) << "\n"
                        << "set datafile separator ','\n" << (csv ? "set datafile columnheaders\n" : "") << body;
  return runGnuplot(script, {png});
}

std::string fmt(double x, const char* f = "%.3g") {
  if (!std::isfinite(x)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, f, x);
  return b;
}

// The methods with a run that satisfies `keep`, in the order report.md lists them (first seen).
std::vector<std::string> methodsWith(const RomStages& st, const std::function<bool(const ModelRun&)>& keep) {
  std::vector<std::string> out;
  for (const auto& r : st.runs)
    if (keep(r) && std::find(out.begin(), out.end(), r.method) == out.end()) out.push_back(r.method);
  return out;
}

// The models of the paper's tab:taur, whose hyper-reduction's total cost report.md compares: the
// DEIM-weighted ones, fixed (GP-DEIM) or adapted online (GP-ADEIM).
bool deimWeighted(const MethodInfo& m) { return m.fit == TermWeightFit::Deim || m.adaptive(); }

bool anyAdaptive(const RomStages& st) {
  return std::any_of(st.runs.begin(), st.runs.end(), [](const ModelRun& r) { return r.info().adaptive(); });
}

bool anyUnbounded(const RomStages& st) {
  return std::any_of(st.runs.begin(), st.runs.end(), [](const ModelRun& r) { return r.unboundedAt >= 0; });
}

// A gnuplot series of runs.csv's unbounded runs (E_L2 against column x), crosses: they ran to the end,
// so their errors exist, but they are not among the methods' curves of ok runs.
std::string unboundedPoints(const std::string& runsCsv, const std::string& x) {
  return gnuplotQuoted(runsCsv) + " using (strcol('status') eq 'unbounded' ? " + x +
         " : 1/0):(column('E_L2')) with points pt 2 ps 2 lw 2 lc rgb 'red' title 'unbounded (any method)'";
}

void writeRunsCsv(const RomStages& st, double fomOnline, const std::string& path) {
  std::ofstream os(path);
  os.precision(10);
  os << "method,k,m,status,E_L2,t_online_s,speedup_vs_fom,E_L2_rom,t_total_s\n";
  for (const auto& r : st.runs) {
    double eRom = NAN;
    for (const auto& q : st.runs)
      if (q.info().reduction == Reduction::Galerkin && q.k == r.k) eRom = q.eL2;
    os << r.method << "," << r.k << "," << r.m << "," << statusName(r.status()) << "," << r.eL2 << "," << r.tOnline << "," << (r.tOnline > 0 ? fomOnline / r.tOnline : NAN) << "," << eRom << ","
       << r.metrics.number(Metric::TTotalS) << "\n";
  }
  finishText(os, path);
}

// Hamiltonian error terms of eq:ham_cons_bound for one GP-DEIM run: |H(y^j) - H(y^0)| (full
// model), |H_hr(z^j) - H_hr(z^0)| (time integration of the hyper-reduced model), the DEIM term
// |H(A z^j) - H_hr(z^j)| and the total Delta H_j = |H(y^j) - H(A z^j)|.
void writeHamiltonianTerms(const FomResult& fom, const ModelRun& r, double dt, const std::string& csv) {
  std::ofstream os(csv);
  os.precision(10);
  os << "t,dH_fom,dH_hr_integration,dH_deim,dH_total\n";
  const double H0 = fom.hamiltonian.front(), Hhr0 = r.modelHamiltonian.front();
  for (size_t j = 0; j < r.hamiltonian.size() && j < fom.hamiltonian.size(); ++j)
    os << j * dt << "," << std::abs(fom.hamiltonian[j] - H0) << "," << std::abs(r.modelHamiltonian[j] - Hhr0) << ","
       << std::abs(r.hamiltonian[j] - r.modelHamiltonian[j]) << "," << std::abs(fom.hamiltonian[j] - r.hamiltonian[j])
       << "\n";
  finishText(os, csv);
}

// One row per GP-ADEIM adaptation: what it did (rank, m_s, residuals: fig:schro_samplingstrats,
// fig:rj_and_msj) and the terms of eq:Hambound at that time ell_{j+1} (prop:ham_cons_adapt):
//   dH_total  = |H(y^l) - H(A z^l)|            eps_fom  = |H(y^l) - H(y^0)|
//   eps_hr    = |H_hr^j(z^l) - H_hr^j(z^{l_j})| (the local model's conservation on its interval)
//   deim_end  = |H_hr^j(z^l) - H(A z^l)|        (the paper's |c^T (I - P_j) G(A z^l)|)
//   deim_start= |H(A z^l) - H_hr^{j+1}(z^l)|    (zero under the proposition's assumption
//                                                 G(A z^l) in col U_{j+1}; reported, not dropped)
//   paper_bound = eps_fom + |H(y^0) - H(A z^0)| + |H(A z^0) - H_hr^0(z^0)| + sum over the intervals
//               so far of eps_hr + deim_end: the right-hand side of eq:Hambound (the two terms at
//               z^0 are zero after the shift of sec:ham_cons). dH_total <= paper_bound holds when
//               the deim_start terms vanish, as the proposition assumes; where they do not, it may
//               fail, and
//   bound     = paper_bound + the deim_start terms of the earlier updates: the triangle inequality
//               with nothing assumed, dH_total <= bound always (a check of the bookkeeping only).
void writeAdeimUpdates(const FomResult& fom, const std::vector<ModelRun>& runs, double dt, const std::string& csv) {
  std::ofstream os(csv);
  os.precision(10);
  os << "run,k,m,update,step,t,rank,coefficient_rank,m_s,resampled,sampled_residual_before,sampled_residual_after,"
        "full_residual,window_norm,cond1_PtU,update_s,dH_total,eps_fom,eps_hr,deim_end,deim_start,bound,paper_bound,"
        "skipped,indicator\n";
  for (const auto& r : runs) {
    if (!r.info().adaptive() || r.modelHamiltonian.empty()) continue;
    const double H0 = fom.hamiltonian.front();
    double segStart = r.modelHamiltonian.front();
    double paperSum = std::abs(H0 - r.hamiltonian.front()) + std::abs(r.hamiltonian.front() - segStart), starts = 0.0;
    int j = 0;
    for (const auto& u : r.adeimUpdates) {
      const size_t l = static_cast<size_t>(u.step);
      if (l >= r.hamiltonian.size() || l >= fom.hamiltonian.size()) break;
      const double Hlift = r.hamiltonian[l], epsHr = std::abs(u.hrBefore - segStart), end = std::abs(u.hrBefore - Hlift);
      paperSum += epsHr + end;
      const double start = std::abs(Hlift - u.hrAfter), epsFom = std::abs(fom.hamiltonian[l] - H0);
      os << "\"" << r.label() << "\"," << r.k << "," << r.m << "," << ++j << "," << u.step << "," << u.step * dt << ","
         << u.rank << "," << u.coefficientRank << "," << u.numSamples << "," << (u.resampled ? 1 : 0) << ","
         << u.sampledBefore << "," << u.sampledAfter << "," << u.fullResidual << "," << u.windowNorm << "," << u.condPtU
         << "," << u.seconds << ","
         << std::abs(fom.hamiltonian[l] - Hlift) << "," << epsFom << "," << epsHr << "," << end << "," << start << ","
         << epsFom + paperSum + starts << "," << epsFom + paperSum << "," << (u.skipped ? 1 : 0) << "," << u.indicator
         << "\n";
      starts += start;
      segStart = u.hrAfter;
    }
  }
  finishText(os, csv);
}

// GP-ADEIM runs whose window has fewer columns than m (2k w < m): C_j then has rank at most 2k w,
// and at least m - 2k w directions of U are left out of each update. Harmless on small NLS runs
// (the default job has one), but the SWE at 2k = 80 diverged with m = 150, w = 1 and reached the
// ROM's error with w = 2 and every row sampled (doc/design.md, 'GP-ADEIM', window), so the report
// says so. Runs never evaluated (unavailable) are not listed.
std::string adeimWindowCaution(const RunOptions& opt, const RomStages& st) {
  std::ostringstream md;
  for (const auto& r : st.runs) {
    if (!r.info().adaptive() || !r.available) continue;
    const AdeimOptions o = adeimOptionsFor(opt.adeim, r.m);
    const int wbar = 2 * r.k * o.window;
    if (wbar >= r.m) continue;
    if (md.tellp() == 0)
      md << "\nWindow narrower than the DEIM basis (2k w < m): C_j has rank at most 2k w, so at least m - 2k w "
            "directions of U are left out of each update. If such a run drifts, raise adeim.window (and "
            "adeim.initialWindow above it) and the sampling rows adeim.numSamples.\n\n";
    const int wNeeded = (r.m + 2 * r.k - 1) / (2 * r.k);
    md << "- " << r.label() << ": 2k w = " << wbar << " < m = " << r.m << " (window >= " << wNeeded
       << ", initialWindow > " << wNeeded << ")\n";
  }
  // A run whose first update would come after its last step never adapted: say so, since its
  // status is ok and its error is then the fixed pair's (U_0, P_0).
  const long steps = opt.evaluation.time.steps;
  for (const auto& r : st.runs) {
    if (!r.info().adaptive() || !r.ok || !r.adeimUpdates.empty()) continue;
    const AdeimOptions o = adeimOptionsFor(opt.adeim, r.m);
    md << "\nNo update ran in " << r.label() << ": adeim.initialWindow = " << o.initialWindow << " exceeds the "
       << steps << " steps of the run, so it is the non-adaptive model of its initial pair (U_0, P_0).\n";
  }
  return md.str();
}

// The term-weighted models side by side (DESIGN.md "Term weights"): the weights' range, the
// smallest eigenvalue of Hess H_hr(z0) beside the reduced model's and, for the quadrature fits,
// the terms used and the fit residual (on the fitted rows and, when sketched, on the exact ones).
std::string termWeightsTable(const RomStages& st) {
  // The fit residuals exist for the quadrature fits only: their columns are shown where one ran.
  const bool fits = std::any_of(st.runs.begin(), st.runs.end(),
                                [](const ModelRun& r) { return r.available && r.info().quadratureFit(); });
  std::ostringstream md;
  for (const auto& r : st.runs) {
    const bool eqp = r.info().quadratureFit();
    if (r.info().reduction != Reduction::TermWeights || !r.available) continue;
    if (md.tellp() == 0)
      md << "\n## Term weights: GP-DEIM" << (fits ? " and empirical quadrature" : "") << "\n\n"
         << "| method | k | m | status | E_L2 | terms | weight min | weight max | "
         << (fits ? "fit residual | exact rows | " : "") << "lambda_min Hess H_hr(z0) | lambda_min rom | convexity lost |\n"
         << (fits ? "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n" : "|---|---|---|---|---|---|---|---|---|---|---|\n");
    const auto num = [&](Metric m) { return r.metrics.number(m); };
    md << "| " << r.method << " | " << r.k << " | " << r.m << " | " << r.statusText() << " | " << fmt(r.eL2) << " | "
       << (eqp ? fmt(num(Metric::EqpTerms), "%.0f") : std::to_string(r.m)) << " | "
       << fmt(num(eqp ? Metric::EqpWeightMin : Metric::DeimWeightMin)) << " | "
       << fmt(num(eqp ? Metric::EqpWeightMax : Metric::DeimWeightMax)) << " | ";
    if (fits)
      md << (eqp ? fmt(num(Metric::EqpFitResidual)) : "-") << " | "
         << (eqp ? fmt(num(Metric::EqpFitResidualExactRows)) : "-") << " | ";
    md << fmt(num(Metric::HessMinEigHr)) << " | " << fmt(num(Metric::HessMinEigRom)) << " | "
       << (r.metrics.flag(Metric::ConvexityLost) ? "yes" : "no") << " |\n";
  }
  return md.str();
}

std::string reportMd(const RunContext& ctx, const RunOptions& opt, const FomResult& fom, const RomStages& st,
                     const std::string& figures) {
  std::ostringstream md;
  const double fomOnline = fom.tOnline;
  md << "# GPHR report: " << opt.scene->name() << "\n\n";
  md << "Integrator " << opt.scheme << ", " << opt.evaluation.time.steps
     << " steps of dt = " << opt.evaluation.time.dt << ", " << ctx.comm->getSize()
     << " MPI rank(s). Times are measured in this run, side by side; errors are eq:errNR against the full model.\n\n";
  md << "Full model online: " << fmt(fomOnline, "%.3f") << " s.\n\n";
  md << "| method | k | m | status | E_L2 | E_L2 / E_L2(rom) | online s | speed-up vs rom | speed-up vs fom |\n";
  md << "|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : st.runs) {
    double eRom = NAN, tRom = NAN;
    for (const auto& q : st.runs)
      if (q.info().reduction == Reduction::Galerkin && q.k == r.k) eRom = q.eL2, tRom = q.tOnline;
    md << "| " << r.method << " | " << r.k << " | " << (r.m ? std::to_string(r.m) : "-") << " | "
       << r.statusText() << " | " << fmt(r.eL2) << " | " << fmt(r.eL2 / eRom) << " | "
       << fmt(r.tOnline, "%.3f") << " | " << fmt(tRom / r.tOnline, "%.2f") << "x | " << fmt(fomOnline / r.tOnline, "%.2f")
       << "x |\n";
  }
  for (const auto& r : st.runs)
    if (r.unboundedAt >= 0)
      md << "\n" << r.label() << " is unbounded: it ran to the end, but from step " << r.unboundedAt
         << " its lift left the full model's range (" << r.unboundedReason << "; thresholds: relative "
         << "Hamiltonian error " << kUnboundedHamiltonian << ", state norm " << kUnboundedNorm
         << " x the full model's largest).\n";
  // For each error level: the cheapest run (online time) that met it.
  md << "\n## Cheapest model per error level\n\n| E_L2 <= | cheapest | E_L2 | online s |\n|---|---|---|---|\n";
  for (double level : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4, 1e-5}) {
    const ModelRun* best = nullptr;
    for (const auto& r : st.runs)
      if (r.bounded() && r.eL2 <= level && (!best || r.tOnline < best->tOnline)) best = &r;
    // a reduced model slower than the full model is no saving: said where it is the cheapest
    const std::string slower = best && best->tOnline >= fomOnline
                                   ? " (slower than the full model's " + fmt(fomOnline, "%.3g") + " s: no saving)"
                                   : "";
    if (best) md << "| " << fmt(level, "%.0e") << " | " << best->label() << slower << " | " << fmt(best->eL2) << " | "
                 << fmt(best->tOnline, "%.3f") << " |\n";
  }
  if (anyAdaptive(st)) {
    md << "\n## GP-DEIM vs GP-ADEIM: total cost of the hyper-reduction\n\n"
          "t_total = hyper-reduction offline (DEIM basis + pair; GP-ADEIM: the first delta0 full-model steps and "
          "their POD) + online (GP-ADEIM: updates included), as the paper's tab:taur. A DEIM basis read from the cache "
          "counts the time it took to compute (stored with it).\n\n"
          "| method | k | m | status | E_L2 | offline s | online s | total s | updates | mean rank | max local H_hr drift |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : st.runs) {
      if (!deimWeighted(r.info())) continue;
      const auto num = [&](Metric m) { return r.metrics.number(m); };
      md << "| " << r.method << " | " << r.k << " | " << r.m << " | " << r.statusText() << " | "
         << fmt(r.eL2) << " | " << fmt(num(Metric::THyperOfflineS), "%.3f") << " | " << fmt(r.tOnline, "%.3f") << " | "
         << fmt(num(Metric::TTotalS), "%.3f") << " | " << (r.info().adaptive() ? fmt(num(Metric::Updates), "%.0f") : "-")
         << " | " << (r.info().adaptive() ? fmt(num(Metric::UpdateRankMean), "%.1f") : "-") << " | "
         << fmt(r.modelHamiltonianDrift) << " |\n";
    }
    md << "\nPer update (rank, m_s, residuals, the terms of eq:Hambound): adeim_updates.csv and adeim_updates.png; "
          "error vs total time: error_vs_total_time.png.\n";
    md << adeimWindowCaution(opt, st);
  }
  md << termWeightsTable(st);
  md << "\nDiagnostics of each GP-DEIM run (cond(P^T U), the smallest eigenvalue of Hess H_hr(z0) next to "
        "the reduced model's, and whether convexity was lost) are in summary.json; a (k, m) with "
        "`convexity_lost: true` can run away while H_hr is conserved.\n";
  md << figures;
  return md.str();
}


// error_vs_m.png: E_L2 against m, one curve per (method, k), the ROM's error as a line per k.
bool plotErrorVsM(const RomStages& st, const std::string& runs, const std::string& png) {
  std::ostringstream b;
  b << "set logscale y\nset format y '%.0e'\nset xlabel 'm (DEIM size)'\nset ylabel 'E_L2'\nset key outside\n"
    << "set title 'Relative error E_L2 against the number of sampled terms m'\nplot ";
  std::vector<std::pair<std::string, int>> curves;
  for (const auto& r : st.runs)
    if (r.info().reduction != Reduction::Galerkin && std::find(curves.begin(), curves.end(), std::make_pair(r.method, r.k)) == curves.end())
      curves.push_back({r.method, r.k});
  bool first = true;
  for (const auto& [m, k] : curves) {
    b << (first ? "" : ", ") << gnuplotQuoted(runs) << " using ((strcol('method') eq '" << m << "' && column('k') == " << k
      << " && strcol('status') eq 'ok') ? column('m') : 1/0):(column('E_L2')) with linespoints lw 2 title '" << m << " 2k=" << 2 * k << "'";
    first = false;
  }
  for (const auto& r : st.runs)
    if (r.info().reduction == Reduction::Galerkin)
      b << (first ? "" : ", ") << r.eL2 << " with lines dt 2 lw 2 title 'rom 2k=" << 2 * r.k << "'", first = false;
  if (anyUnbounded(st)) b << ", " << unboundedPoints(runs, "column('m')");
  b << "\n";
  return !curves.empty() && gnuplot(png, b.str());
}

// pareto.png: error against online time, every method report.md lists.
bool plotPareto(const RomStages& st, const std::string& runs, const std::string& png) {
  std::ostringstream b;
  b << "set logscale xy\nset format y '%.0e'\nset xlabel 'online time [s]'\nset ylabel 'E_L2'\nset key outside\n"
    << "set title 'Error vs online time (pick from the lower-left front)'\nplot ";
  bool first = true;
  for (const auto& m : methodsWith(st, [](const ModelRun& r) { return r.ok; })) {  // every method report.md lists
    b << (first ? "" : ", ") << gnuplotQuoted(runs) << " using ((strcol('method') eq '" << m
      << "' && strcol('status') eq 'ok') ? column('t_online_s') : 1/0):(column('E_L2')) with points pt 7 ps 1.5 title '" << m << "'";
    first = false;
  }
  if (anyUnbounded(st)) b << (first ? "" : ", ") << unboundedPoints(runs, "column('t_online_s')"), first = false;
  b << "\n";
  return !first && gnuplot(png, b.str());
}

// hamiltonian_terms.png: the Hamiltonian error of one GP-DEIM run and the terms of eq:ham_cons_bound.
bool plotHamiltonianTerms(const ModelRun& run, const std::map<std::string, std::string>& p) {
  std::ostringstream b;
  const std::string csv = p.at("hamiltonian_terms.csv");
  b << "set logscale y\nset format y '%.0e'\nset xlabel 't'\nset ylabel 'Hamiltonian error'\nset key outside\n"
    << "set title 'Hamiltonian error and the terms that bound it, " << run.label() << "'\n"
    << "plot for [term in 'dH_fom dH_hr_integration dH_deim dH_total'] " << gnuplotQuoted(csv)
    << " using (column('t')):(column(term) > 0 ? column(term) : 1e-17) with lines lw 2 title term\n";
  return gnuplot(p.at("hamiltonian_terms.png"), b.str());
}

// adeim_updates.png: per GP-ADEIM update, the residual after it and the rank and sampled rows.
bool plotAdeimUpdates(const RomStages& st, const std::map<std::string, std::string>& p) {
  const std::string csv = p.at("adeim_updates.csv");
  // Left: ||U_{j+1} C_j - F_j||_F over all rows where adeim.monitorResidual recorded it, and its
  // part at the sampling rows; right: r_j and m_s. A curve without a positive point is left out
  // (gnuplot drops the whole figure when a log-scale panel has none: m = d, monitor off).
  std::ostringstream residuals, ranks;
  bool first = true;
  for (const auto& r : st.runs) {
    if (!r.info().adaptive() || r.adeimUpdates.empty()) continue;
    const std::string sel = gnuplotQuoted(csv) + " using (strcol('run') eq '" + r.label() + "' ? ";
    const auto any = [&](auto value) {
      return std::any_of(r.adeimUpdates.begin(), r.adeimUpdates.end(), [&](const AdeimUpdateRecord& u) { return value(u) > 0.0; });
    };
    if (any([](const AdeimUpdateRecord& u) { return u.fullResidual; }))
      residuals << (residuals.tellp() > 0 ? ", " : "") << sel
                << "column('update') : 1/0):(column('full_residual') > 0 ? column('full_residual') : 1/0) "
                   "with lines lw 2 title '"
                << r.label() << "'";
    if (any([](const AdeimUpdateRecord& u) { return u.sampledAfter; }))
      residuals << (residuals.tellp() > 0 ? ", " : "") << sel
                << "column('update') : 1/0):(column('sampled_residual_after') > 0 ? "
                   "column('sampled_residual_after') : 1/0) with lines dt 2 title 'at S, "
                << r.label() << "'";
    ranks << (first ? "" : ", ") << sel << "column('update') : 1/0):(column('rank')) with lines lw 2 title 'r "
          << r.label() << "', " << sel << "column('update') : 1/0):(column('m_s')) with lines dt 2 title 'm_s "
          << r.label() << "'";
    first = false;
  }
  std::ostringstream b;
  b << "set multiplot layout 1," << (residuals.tellp() > 0 ? 2 : 1) << "\nset key below\nset xlabel 'update j'\n";
  if (residuals.tellp() > 0)
    b << "set logscale y\nset format y '%.0e'\nset title 'GP-ADEIM: residual after each update'\nplot "
      << residuals.str() << "\nunset logscale y\n";
  b << "set format y '%g'\nset title 'GP-ADEIM: rank r, sampled rows m_s'\nplot " << ranks.str()
    << "\nunset multiplot\n";
  return !first && gnuplot(p.at("adeim_updates.png"), b.str());
}

// error_vs_total_time.png: error against the hyper-reduction's offline + online time.
bool plotErrorVsTotalTime(const RomStages& st, const std::string& runs, const std::string& png) {
  std::ostringstream t;  // error vs total hyper-reduction time (doc/paper-map.md: the paper's figure)
  t << "set logscale xy\nset format y '%.0e'\nset xlabel 't_total = hyper-reduction offline + online [s]'\n"
    << "set ylabel 'E_L2'\nset key outside\nset title 'Error against total cost (offline hyper-reduction + online)'\nplot ";
  std::vector<int> ks;
  const auto totalled = methodsWith(st, [](const ModelRun& r) { return std::isfinite(r.metrics.number(Metric::TTotalS)); });
  for (const auto& r : st.runs)
    if (std::find(totalled.begin(), totalled.end(), r.method) != totalled.end() &&
        std::find(ks.begin(), ks.end(), r.k) == ks.end())
      ks.push_back(r.k);
  bool first = true;
  for (int k : ks)
    for (const auto& m : totalled) {
      t << (first ? "" : ", ") << gnuplotQuoted(runs) << " using ((strcol('method') eq '" << m << "' && column('k') == " << k
        << " && strcol('status') eq 'ok') ? column('t_total_s') : 1/0):(column('E_L2')) with linespoints lw 2 pt 7 title '" << m << " 2k=" << 2 * k << "'";
      first = false;
    }
  t << "\n";
  return gnuplot(png, t.str());
}

// The data files and report.md; the names written go to `written`.
void writeHyperData(const RunOptions& opt, const FomResult& fom, const RomStages& st, const ModelRun* terms,
                    const std::map<std::string, std::string>& p, std::vector<std::string>& written) {
  writeRunsCsv(st, fom.tOnline, p.at("runs.csv"));
  written.push_back("runs.csv");
  if (!st.deimSingularValues.empty()) {
    std::ofstream os(p.at("deim_singular_values.csv"));
    os.precision(17);
    os << "index,sigma,sigma_rel\n";
    const auto& s = st.deimSingularValues;
    for (size_t j = 0; j < s.size(); ++j) os << j + 1 << "," << s[j] << "," << s[j] / s[0] << "\n";
    finishText(os, p.at("deim_singular_values.csv"));
    written.push_back("deim_singular_values.csv");
  }
  const double dt = opt.evaluation.time.dt;
  if (terms) {
    writeHamiltonianTerms(fom, *terms, dt, p.at("hamiltonian_terms.csv"));
    written.push_back("hamiltonian_terms.csv");
  }
  if (anyAdaptive(st)) {
    writeAdeimUpdates(fom, st.runs, dt, p.at("adeim_updates.csv"));
    written.push_back("adeim_updates.csv");
  }
}

}  // namespace

void writeHyperReportMd(const RunContext& ctx, const RunOptions& opt, const FomResult& fom, const RomStages& st,
                        const std::string& path, const std::vector<std::string>& figures, const std::string& fieldNote) {
  std::string line;
  for (const auto& f : figures) line += (line.empty() ? "" : ", ") + f;
  line = line.empty() ? "\nNo figures were drawn" + std::string(opt.output.plots ? " (gnuplot missing or failed)" : " (output.plots: false)")
                      : "\nFigures: " + line;
  if (!fieldNote.empty()) line += "; " + fieldNote;
  writeTextFile(path, reportMd(ctx, opt, fom, st, line + ".\n"));
}

std::vector<std::string> writeHyperReport(const RunOptions& opt, const FomResult& fom, const RomStages& st,
                                          const std::map<std::string, std::string>& p, bool plots) {
  const ModelRun* terms = nullptr;  // the GP-DEIM run with the largest k, then m
  for (const auto& r : st.runs)
    if (r.info().fit == TermWeightFit::Deim && r.ok && (!terms || r.k > terms->k || (r.k == terms->k && r.m > terms->m))) terms = &r;
  std::vector<std::string> written;
  writeHyperData(opt, fom, st, terms, p, written);
  if (!plots || !haveGnuplot()) return written;
  const std::string runs = p.at("runs.csv");
  const auto plotted = [&](bool ok, const char* name) {
    if (ok) written.push_back(name);
  };
  plotted(plotErrorVsM(st, runs, p.at("error_vs_m.png")), "error_vs_m.png");
  plotted(plotPareto(st, runs, p.at("pareto.png")), "pareto.png");
  if (terms) plotted(plotHamiltonianTerms(*terms, p), "hamiltonian_terms.png");
  if (anyAdaptive(st)) {
    plotted(plotAdeimUpdates(st, p), "adeim_updates.png");
    plotted(plotErrorVsTotalTime(st, runs, p.at("error_vs_total_time.png")), "error_vs_total_time.png");
  }
  return written;
}

}  // namespace gphr
