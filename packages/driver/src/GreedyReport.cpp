#include "gphr/driver/GreedyReport.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "gphr/driver/Gnuplot.hpp"
#include "gphr/driver/OutputDirectory.hpp"

namespace gphr {

namespace {

std::string greedyCsv(const GreedyResult& g, const std::vector<std::string>& names) {
  std::ostringstream csv;
  csv.precision(10);
  csv << "round,full_solves,best_model,max_estimate";
  for (const auto& n : names) csv << ",added_" << n;
  csv << "\n";
  for (size_t i = 0; i < g.rounds.size(); ++i) {
    const auto& r = g.rounds[i];
    csv << i + 1 << "," << r.fullSolves << "," << r.model << "," << r.maxEstimate;
    for (size_t p = 0; p < names.size(); ++p) csv << "," << (r.added.empty() ? std::string() : std::to_string(r.added[p]));
    csv << "\n";
  }
  return csv.str();
}

// The largest estimate per round against the full solves, the target, and each query default's
// E_L2 at the fresh points (full solves) where the rounds ended.
std::string greedyScript(const std::string& dir, const GreedyResult& g, double target) {
  // ranges with a margin around every figure drawn and the target, so that none lies on the frame
  double lo = target, hi = target;
  const auto include = [&](double v) {
    if (std::isfinite(v) && v > 0.0) lo = std::min(lo, v), hi = std::max(hi, v);
  };
  for (const auto& r : g.rounds) include(r.maxEstimate);
  for (const auto& q : g.build.data.queryDefaults) include(q.verifiedMax);
  const long first = g.rounds.front().fullSolves, last = g.rounds.back().fullSolves;
  std::ostringstream gp;
  gp << "set terminal pngcairo size 800,520 noenhanced\nset output " << gnuplotQuoted(dir + "/greedy.png")
     << "\nset xrange [" << first - 0.5 << ":" << last + 0.5 << "]\nset yrange [" << lo / 2 << ":" << hi * 2 << "]"
     << "\nset datafile separator ','\nset logscale y\nset format y '%.0e'\nset grid\nset key bottom left\n"
     << "set title " << gnuplotQuoted("Greedy training: the best model's largest estimated E_L2 over the candidates")
     << "\n"
     << "set xlabel 'full solves (training points)'\nset ylabel 'E_L2'\n"
     << "plot " << gnuplotQuoted(dir + "/greedy.csv") << " using 2:4 skip 1 with linespoints pt 7 lw 2 "
     << "title 'largest estimate', " << target << " with lines dt 2 lc rgb 'black' title 'target'";
  for (const auto& q : g.build.data.queryDefaults)
    if (std::isfinite(q.verifiedMax) && q.verifiedMax > 0.0)
      gp << ", '+' using (" << last << "):(" << q.verifiedMax << ") every ::0::0 with points pt 6 ps 2 title "
         << gnuplotQuoted(q.method + " k=" + std::to_string(q.k) + " m=" + std::to_string(q.m) +
                          ": E_L2 at fresh points");
  gp << "\n";
  return gp.str();
}

}  // namespace

std::string writeGreedyReport(const std::string& dir, const GreedyResult& g, const std::vector<std::string>& names,
                              double target) {
  if (g.rounds.empty()) return "";
  writeTextFile(dir + "/greedy.csv", greedyCsv(g, names));
  if (!haveGnuplot()) return "greedy.csv";
  const std::string script = dir + "/greedy.gp";
  writeTextFile(script, greedyScript(dir, g, target));
  if (runGnuplot(script, {dir + "/greedy.png"})) return "greedy.csv, greedy.png";
  std::fprintf(stderr, "[gphr] build: '%s/greedy.png' not drawn\n", dir.c_str());
  return "greedy.csv";
}

}  // namespace gphr
