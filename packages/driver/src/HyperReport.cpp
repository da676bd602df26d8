#include "gphr/driver/HyperReport.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "gphr/driver/Config.hpp"
#include "gphr/driver/Report.hpp"

namespace gphr {

namespace {

bool haveGnuplot() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

bool gnuplot(const std::string& png, const std::string& body) {
  const std::string script = png + ".gp";
  std::ofstream(script) << "set terminal pngcairo size 1000,560 noenhanced\nset output '" << png << "'\n"
                        << "set datafile separator ','\n" << body;
  const int rc = std::system(("gnuplot '" + script + "' > /dev/null 2>&1").c_str());
  std::remove(script.c_str());
  return rc == 0;
}

std::string fmt(double x, const char* f = "%.3g") {
  if (!std::isfinite(x)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, f, x);
  return b;
}

void writeRunsCsv(const RomStages& st, double fomOnline, const std::string& path) {
  std::ofstream os(path);
  os.precision(10);
  os << "method,k,m,status,E_L2,t_online_s,speedup_vs_fom,E_L2_rom\n";
  for (const auto& r : st.runs) {
    double eRom = NAN;
    for (const auto& q : st.runs)
      if (q.method == "rom" && q.k == r.k) eRom = q.eL2;
    os << r.method << "," << r.k << "," << r.m << "," << (r.ok ? "ok" : "diverged") << "," << r.eL2 << ","
       << r.tOnline << "," << (r.tOnline > 0 ? fomOnline / r.tOnline : NAN) << "," << eRom << "\n";
  }
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
}

std::string reportMd(const RunContext& ctx, const FomResult& fom, const RomStages& st) {
  std::ostringstream md;
  const double fomOnline = fom.tOnline;
  md << "# GPHR report: " << ctx.scene->name() << "\n\n";
  md << "Integrator " << ctx.config.sublist("integrator").get<std::string>("scheme") << ", " << numSteps(ctx.config)
     << " steps of dt = " << ctx.config.sublist("time").get<double>("dt") << ", " << ctx.comm->getSize()
     << " MPI rank(s). Times are measured in this run, side by side; errors are eq:errNR against the full model.\n\n";
  md << "Full model online: " << fmt(fomOnline, "%.3f") << " s.\n\n";
  md << "| method | k | m | status | E_L2 | E_L2 / E_L2(rom) | online s | speed-up vs rom | speed-up vs fom |\n";
  md << "|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : st.runs) {
    double eRom = NAN, tRom = NAN;
    for (const auto& q : st.runs)
      if (q.method == "rom" && q.k == r.k) eRom = q.eL2, tRom = q.tOnline;
    md << "| " << r.method << " | " << r.k << " | " << (r.m ? std::to_string(r.m) : "-") << " | "
       << (r.ok ? "ok" : "**diverged**") << " | " << fmt(r.eL2) << " | " << fmt(r.eL2 / eRom) << " | "
       << fmt(r.tOnline, "%.3f") << " | " << fmt(tRom / r.tOnline, "%.2f") << "x | " << fmt(fomOnline / r.tOnline, "%.2f")
       << "x |\n";
  }
  // For each error level: the cheapest run (online time) that met it.
  md << "\n## Cheapest model per error level\n\n| E_L2 <= | cheapest | E_L2 | online s |\n|---|---|---|---|\n";
  for (double level : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4, 1e-5}) {
    const ModelRun* best = nullptr;
    for (const auto& r : st.runs)
      if (r.ok && r.eL2 <= level && (!best || r.tOnline < best->tOnline)) best = &r;
    if (best) md << "| " << fmt(level, "%.0e") << " | " << best->label() << " | " << fmt(best->eL2) << " | "
                 << fmt(best->tOnline, "%.3f") << " |\n";
  }
  md << "\nDiagnostics of each GP-DEIM run (cond(P^T U), the smallest eigenvalue of Hess H_hr(z0) next to "
        "the reduced model's, and whether convexity was lost) are in summary.json; a (k, m) with "
        "`convexity_lost: true` can run away while H_hr is conserved.\n";
  md << "\nFigures: error_vs_m.png, pareto.png, hamiltonian_terms.png, singular_values.png, spacetime.png (NLS).\n";
  return md.str();
}

}  // namespace

std::string spaceTimeData(const RunContext& ctx, const FomResult& fom, const RomStages& st) {
  if (ctx.scene->name() != "nls1d") return "";
  // |u| = sqrt(q^2 + p^2) at the saved steps, for FOM and the runs that kept their states.
  std::vector<std::pair<std::string, std::vector<RCP<const Vector>>>> fields;
  std::vector<RCP<const Vector>> f;
  for (size_t j = 0; j < fom.trajectory->getNumVectors(); ++j) f.push_back(fom.trajectory->getVector(j));
  fields.push_back({"fom", f});
  for (const auto& r : st.runs)
    if (!r.states.empty()) fields.push_back({r.label(), {r.states.begin(), r.states.end()}});
  // Gathered on rank 0 by one Import per state (offline). Blocks are separated by two blank lines,
  // as gnuplot's `index` wants; the "# name" lines are gnuplot comments naming them.
  const RCP<const Map> map = fom.trajectory->getMap();
  const GO N = static_cast<GO>(map->getGlobalNumElements()), n = N / 2;
  const auto root = rcp(new Map(N, ctx.comm->getRank() == 0 ? N : 0, 0, ctx.comm));
  const Import toRoot(map, root);
  Vector g(root);
  std::ostringstream os;
  os.precision(6);
  for (const auto& [name, states] : fields) {
    os << (os.tellp() > 0 ? "\n\n" : "") << "# " << name << "\n";
    for (const auto& state : states) {
      g.doImport(*state, toRoot, Tpetra::INSERT);
      if (ctx.comm->getRank() != 0) continue;
      auto v = g.getLocalViewHost(Tpetra::Access::ReadOnly);
      for (GO i = 0; i < n; ++i) os << (i ? "," : "") << std::sqrt(v(i, 0) * v(i, 0) + v(n + i, 0) * v(n + i, 0));
      os << "\n";
    }
  }
  return os.str();
}

std::vector<std::string> writeHyperReport(const RunContext& ctx, const FomResult& fom, const RomStages& st,
                                          const std::string& spaceTime, const std::map<std::string, std::string>& p,
                                          bool plots) {
  std::vector<std::string> written;
  writeRunsCsv(st, fom.tOnline, p.at("runs.csv"));
  written.push_back("runs.csv");
  std::ofstream(p.at("report.md")) << reportMd(ctx, fom, st);
  written.push_back("report.md");
  if (!st.deimSingularValues.empty()) {
    std::ofstream os(p.at("deim_singular_values.csv"));
    os.precision(17);
    os << "index,sigma,sigma_rel\n";
    const auto& s = st.deimSingularValues;
    for (size_t j = 0; j < s.size(); ++j) os << j + 1 << "," << s[j] << "," << s[j] / s[0] << "\n";
    written.push_back("deim_singular_values.csv");
  }
  const ModelRun* terms = nullptr;  // the GP-DEIM run with the largest k, then m
  for (const auto& r : st.runs)
    if (r.method == "gp-deim" && r.ok && (!terms || r.k > terms->k || (r.k == terms->k && r.m > terms->m))) terms = &r;
  const double dt = ctx.config.sublist("time").get<double>("dt");
  if (terms) {
    writeHamiltonianTerms(fom, *terms, dt, p.at("hamiltonian_terms.csv"));
    written.push_back("hamiltonian_terms.csv");
  }
  if (!plots || !haveGnuplot()) return written;
  const std::string runs = p.at("runs.csv");
  // error vs m, one curve per (method, k), the ROM's error as a horizontal line per k
  {
    std::ostringstream b;
    b << "set logscale y\nset format y '%.0e'\nset xlabel 'm (DEIM size)'\nset ylabel 'E_L2'\nset key outside\n"
      << "set title 'Error vs DEIM size (fig:2dsw_errors_avf_imr)'\nplot ";
    std::vector<std::pair<std::string, int>> curves;
    for (const auto& r : st.runs)
      if (r.method != "rom" && std::find(curves.begin(), curves.end(), std::make_pair(r.method, r.k)) == curves.end())
        curves.push_back({r.method, r.k});
    bool first = true;
    for (const auto& [m, k] : curves) {
      b << (first ? "" : ", ") << "'" << runs << "' every ::1 using ((strcol(1) eq '" << m << "' && $2 == " << k
        << " && strcol(4) eq 'ok') ? $3 : 1/0):5 with linespoints lw 2 title '" << m << " 2k=" << 2 * k << "'";
      first = false;
    }
    for (const auto& r : st.runs)
      if (r.method == "rom")
        b << (first ? "" : ", ") << r.eL2 << " with lines dt 2 lw 2 title 'rom 2k=" << 2 * r.k << "'", first = false;
    b << "\n";
    if (!curves.empty() && gnuplot(p.at("error_vs_m.png"), b.str())) written.push_back("error_vs_m.png");
  }
  {  // Pareto: error vs online time
    std::ostringstream b;
    b << "set logscale xy\nset format y '%.0e'\nset xlabel 'online time [s]'\nset ylabel 'E_L2'\nset key outside\n"
      << "set title 'Error vs online time (pick from the lower-left front)'\nplot ";
    bool first = true;
    for (const char* m : {"rom", "gp-deim", "deim", "sdeim"}) {
      bool any = false;
      for (const auto& r : st.runs) any |= r.method == m && r.ok;
      if (!any) continue;
      b << (first ? "" : ", ") << "'" << runs << "' every ::1 using ((strcol(1) eq '" << m
        << "' && strcol(4) eq 'ok') ? $6 : 1/0):5 with points pt 7 ps 1.5 title '" << m << "'";
      first = false;
    }
    b << "\n";
    if (!first && gnuplot(p.at("pareto.png"), b.str())) written.push_back("pareto.png");
  }
  if (terms) {
    std::ostringstream b;
    const std::string csv = p.at("hamiltonian_terms.csv");
    b << "set logscale y\nset format y '%.0e'\nset xlabel 't'\nset ylabel 'Hamiltonian error'\nset key outside\n"
      << "set title 'Hamiltonian error terms, " << terms->label() << " (fig:2dsw_hamcons)'\n"
      << "plot for [c=2:5] '" << csv << "' every ::1 using 1:(column(c) > 0 ? column(c) : 1e-17) with lines lw 2 "
      << "title columnhead(c)\n";
    if (gnuplot(p.at("hamiltonian_terms.png"), b.str())) written.push_back("hamiltonian_terms.png");
  }
  if (!spaceTime.empty()) {
    const std::string dat = p.at("spacetime.png") + ".dat";
    std::ofstream(dat) << spaceTime;
    int blocks = 0;
    for (size_t pos = 0; (pos = spaceTime.find("# ", pos)) != std::string::npos; ++pos) ++blocks;
    std::ostringstream b;
    b << "set datafile separator ','\nset multiplot layout 1," << blocks << "\nunset key\nset xlabel 'x index'\n"
      << "set ylabel 'saved step'\nset cbrange [0:*]\n";
    std::istringstream in(spaceTime);
    std::string line;
    int idx = 0;
    while (std::getline(in, line))
      if (line.rfind("# ", 0) == 0)
        b << "set title '" << line.substr(2) << "'\nplot '" << dat << "' index " << idx++ << " matrix with image\n";
    b << "unset multiplot\n";
    if (gnuplot(p.at("spacetime.png"), b.str())) written.push_back("spacetime.png");
    std::remove(dat.c_str());
  }
  return written;
}

}  // namespace gphr
