#include "gphr/driver/Report.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_YamlParameterListCoreHelpers.hpp>
#include <Trilinos_version.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "gphr/io/Hdf5File.hpp"

namespace gphr {

JsonObject machineInfo(const RCP<const Comm>& comm) {
  char host[256] = "unknown";
  gethostname(host, sizeof(host) - 1);
  JsonObject m;
  m.set("host", std::string(host))
      .set("hardware_threads", static_cast<long>(std::thread::hardware_concurrency()))
      .set("mpi_ranks", comm->getSize())
      .set("trilinos", std::string(TRILINOS_VERSION_STRING))
      .set("compiler", std::string("g++ ") + __VERSION__);
  return m;
}

namespace {

std::string yamlOf(const Teuchos::ParameterList& pl) {
  std::ostringstream os;
  Teuchos::writeParameterListToYamlOStream(pl, os);
  return os.str();
}

JsonObject parametersJson(const Scene& scene, const std::vector<double>& mu) {
  JsonObject p;
  for (size_t i = 0; i < mu.size(); ++i) p.set(scene.parameterBox().names[i], mu[i]);
  return p;
}

void writeArtifacts(const RunContext& ctx, const FomResult& fom, const std::string& path) {
  Hdf5File f(path, ctx.comm, Hdf5File::Mode::Create);
  PhaseSpace ps(fom.trajectory->getGlobalLength() / 2, ctx.comm);
  f.setAttribute("/", "scene", ctx.scene->name());
  f.setAttribute("/", "integrator", ctx.config.sublist("integrator").get<std::string>("scheme"));
  f.setAttribute("/", "parameters", ctx.mu);
  f.setAttribute("/", "config", yamlOf(ctx.config));
  f.createGroup("/fom");
  f.writeStates("/fom/trajectory", *fom.trajectory, ps);
  f.writeArray("/fom/times", fom.savedTimes, fom.savedTimes.size(), 1);
  f.writeArray("/fom/hamiltonian", fom.hamiltonian, fom.hamiltonian.size(), 1);
  f.setAttribute("/fom/trajectory", "layout", std::string("rows are states y = (q, p) at /fom/times; "
                                                          "physical (unshifted) values"));
}

void writeHistoryCsv(const FomResult& fom, double dt, const std::string& path) {
  std::ofstream os(path);
  os.precision(17);
  os << "step,t,H,H_err\n";
  const double H0 = fom.hamiltonian.front();
  for (size_t j = 0; j < fom.hamiltonian.size(); ++j)
    os << j << "," << j * dt << "," << fom.hamiltonian[j] << "," << std::abs(fom.hamiltonian[j] - H0) << "\n";
}

// Plot |H(y^j) - H(y^0)| with gnuplot; returns false (with the reason) when it cannot.
bool plotHamiltonian(const std::string& csv, const std::string& png, std::string& why) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    why = "gnuplot not found (apt-get install gnuplot-nox)";
    return false;
  }
  const std::string script = png + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 900,500 noenhanced\nset output '" << png << "'\n"
       << "set datafile separator ','\nset key top left\nset logscale y\nset format y '%.0e'\n"
       << "set xlabel 't'\nset ylabel '|H(y^j) - H(y^0)|'\nset title 'Hamiltonian error of the full model'\n"
       << "plot '" << csv << "' every ::1 using 2:($4 > 0 ? $4 : 1e-17) with lines lw 2 title 'fom'\n";
  }
  const int rc = std::system(("gnuplot '" + script + "' > /dev/null 2>&1").c_str());
  std::remove(script.c_str());
  if (rc != 0) why = "gnuplot failed";
  return rc == 0;
}

}  // namespace

std::string writeReport(const RunContext& ctx, const FomResult& fom) {
  const bool root = ctx.comm->getRank() == 0;
  const double dt = ctx.config.sublist("time").get<double>("dt");
  RenameOnCommit h5(ctx.outputDir + "/artifacts.h5", ctx.comm), json(ctx.outputDir + "/summary.json", ctx.comm),
      csv(ctx.outputDir + "/fom_history.csv", ctx.comm), png(ctx.outputDir + "/hamiltonian.png", ctx.comm);
  writeArtifacts(ctx, fom, h5.tempPath());
  JsonObject summary;
  summary.set("scene", ctx.scene->name())
      .set("integrator", ctx.config.sublist("integrator").get<std::string>("scheme"))
      .set("parameters", parametersJson(*ctx.scene, ctx.mu))
      .set("machine", machineInfo(ctx.comm))
      .set("runs", std::vector<JsonObject>{fom.run});
  bool plotted = false;
  std::string why;
  if (root) {
    writeHistoryCsv(fom, dt, csv.tempPath());
    if (ctx.config.sublist("output").get<bool>("plots"))
      plotted = plotHamiltonian(csv.tempPath(), png.tempPath(), why);
    if (!plotted && !why.empty()) std::fprintf(stderr, "[gphr] no plots: %s\n", why.c_str());
    std::ofstream(json.tempPath()) << summary.str() << "\n";
  }
  int plottedAll = plotted;
  Teuchos::broadcast(*ctx.comm, 0, Teuchos::outArg(plottedAll));
  h5.commit();
  csv.commit();
  if (plottedAll) png.commit();
  json.commit();  // last: summary.json present means the run is complete
  return summary.str();
}

}  // namespace gphr
