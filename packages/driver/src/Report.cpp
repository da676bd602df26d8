#include "gphr/driver/Report.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_YamlParameterListCoreHelpers.hpp>
#include <Trilinos_version.h>
#include <unistd.h>

#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <fstream>
#include <sstream>
#include <thread>

#include "gphr/core/Error.hpp"
#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/driver/FieldOutput.hpp"
#include "gphr/driver/FieldPictures.hpp"
#include "gphr/driver/Gnuplot.hpp"
#include "gphr/driver/HyperReport.hpp"
#include "gphr/io/Hdf5File.hpp"
#include "gphr/core/Method.hpp"

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


JsonObject parametersJson(const Scene& scene, const std::vector<double>& mu) {
  JsonObject p;
  for (size_t i = 0; i < mu.size(); ++i) p.set(scene.parameterBox().names[i], mu[i]);
  return p;
}

void writeArtifacts(const RunContext& ctx, const RunOptions& opt, const FomResult& fom, const RomStages* rom, const FieldOutput* fields,
                    Hdf5File& f) {
  PhaseSpace ps(fom.trajectory->getGlobalLength() / 2, ctx.comm);
  f.setAttribute("/", "scene", opt.scene->name());
  f.setAttribute("/", "integrator", opt.scheme);
  f.setAttribute("/", "parameters", opt.mu);
  f.setAttribute("/", "config", opt.record.fullYaml);
  for (const char* g : {"/fom", "/rom", "/runs"}) f.remove(g);
  f.createGroup("/fom");
  f.writeStates("/fom/trajectory", *fom.trajectory, ps);
  f.writeArray("/fom/times", fom.savedTimes, fom.savedTimes.size(), 1);
  f.writeArray("/fom/hamiltonian", fom.hamiltonian, fom.hamiltonian.size(), 1);
  f.setAttribute("/fom/trajectory", "layout", std::string("rows are states y = (q, p) at /fom/times; "
                                                          "physical (unshifted) values"));
  if (!rom) return;
  f.createGroup("/runs");
  for (size_t i = 0; i < rom->runs.size(); ++i) {
    const ModelRun& r = rom->runs[i];
    const std::string g = "/runs/" + std::to_string(i);
    f.createGroup(g);
    f.setAttribute(g, "label", r.label());
    if (r.hamiltonian.empty()) continue;  // an unavailable run (no trajectory): its label says which
    f.writeArray(g + "/hamiltonian", r.hamiltonian, r.hamiltonian.size(), 1);
    if (!r.modelHamiltonian.empty())
      f.writeArray(g + "/model_hamiltonian", r.modelHamiltonian, r.modelHamiltonian.size(), 1);
    if (r.errors.empty()) continue;  // diverged before the first saved step after step 0
    f.writeArray(g + "/errors", r.errors, r.errors.size(), 1);
    f.setAttribute(g + "/errors", "layout", std::string("||y - (y0 + A z)|| at /fom/times"));
  }
  if (fields) writeFieldStates(f, fom, *fields);  // what fields.xdmf shows
}

void writeHistoryCsv(const std::vector<double>& H, double H0, const std::vector<double>* errors, long saveEvery,
                     double dt, const std::string& path) {
  std::ofstream os(path);
  os.precision(17);
  os << "step,t,H,H_err" << (errors ? ",state_err" : "") << "\n";
  const long steps = static_cast<long>(H.size()) - 1;
  for (long j = 0; j <= steps; ++j) {
    os << j << "," << j * dt << "," << H[j] << "," << std::abs(H[j] - H0);
    if (errors) {
      const bool saved = isSavedStep(j, steps, saveEvery);
      os << ",";
      if (saved) os << (*errors)[j / saveEvery + (j == steps && steps % saveEvery != 0)];
    }
    os << "\n";
  }
  finishText(os, path);
}

// Plot |H(y^j) - H(y^0)| with gnuplot; returns false (with the reason) when it cannot.
bool plotHamiltonian(const std::string& csv, const std::string& romCsv, const std::string& png, std::string& why) {
  if (!haveGnuplot()) {
    why = "gnuplot not found (apt-get install gnuplot-nox)";
    return false;
  }
  const std::string script = png + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 900,500 noenhanced\nset output " << gnuplotQuoted(png) << "\n"
       << "set datafile separator ','\nset datafile columnheaders\nset key top left\nset logscale y\nset format y '%.0e'\n"
       << "set xlabel 't'\nset ylabel '|H(y^j) - H(y^0)|'\nset title 'Hamiltonian error of the full model'\n"
       << "plot " << gnuplotQuoted(csv) << " using (column('t')):(column('H_err') > 0 ? column('H_err') : 1e-17) with lines lw 2 "
       << "title 'fom'";
    if (!romCsv.empty())
      gp << ", " << gnuplotQuoted(romCsv) << " using (column('t')):(column('H_err') > 0 ? column('H_err') : 1e-17) with lines lw 2 "
         << "title 'rom'";
    gp << "\n";
  }
  const bool drawn = runGnuplot(script, {png});
  if (!drawn) why = "gnuplot failed or the PNG could not be written whole";
  return drawn;
}

void writeSingularValues(const std::vector<double>& s, const std::string& csv, const std::string& png, bool plot,
                         const std::string& deimCsv) {
  {
    std::ofstream os(csv);
    os.precision(17);
    os << "index,sigma,sigma_rel\n";
    for (size_t j = 0; j < s.size(); ++j) os << j + 1 << "," << s[j] << "," << s[j] / s[0] << "\n";
    finishText(os, csv);
  }
  if (!plot || !haveGnuplot()) return;
  const std::string script = png + ".gp";
  std::ofstream(script) << "set terminal pngcairo size 900,500 noenhanced\nset output " << gnuplotQuoted(png) << "\n"
                        << "set datafile separator ','\nset datafile columnheaders\nset logscale y\nset format y '%.0e'\n"
                        << "set xlabel 'index j'\n"
                        << "set ylabel 'sigma_j / sigma_1'\nset title 'Singular values of the snapshots'\n"
                        << "plot " << gnuplotQuoted(csv) << " using (column('index')):(column('sigma_rel')) with lines lw 2 "
                        << "title 'snapshots (basis A)'"
                        << (deimCsv.empty() ? std::string()
                                            : ", " + gnuplotQuoted(deimCsv) + " using (column('index')):(column('sigma_rel')) "
                                                                "with lines lw 2 title 'reduced Jacobians (DEIM basis U)'")
                        << "\n";
  runGnuplot(script, {png});  // an optional picture: committed only where it is whole (commitReport)
}

// The first rom run: its history is rom_history.csv.
const ModelRun* firstRomRun(const RomStages* rom) {
  if (rom)
    for (const auto& r : rom->runs)
      if (r.info().reduction == Reduction::Galerkin) return &r;
  return nullptr;
}

JsonObject summaryOf(const RunContext& ctx, const RunOptions& opt, const FomResult& fom, const RomStages* rom) {
  std::vector<JsonObject> runs{fom.json()};
  if (rom)
    for (const auto& r : rom->runs) runs.push_back(r.json());
  JsonObject summary;
  summary.set("scene", opt.scene->name())
      .set("integrator", opt.scheme)
      .set("parameters", parametersJson(*opt.scene, opt.mu))
      .set("machine", machineInfo(ctx.comm))
      .set("gphr_version", gphrVersion())
      .set("provenance", opt.record.provenance)
      .set("runs", runs);
  return summary;
}

// Every file of the report under its temporary name (RenameOnCommit), committed or dropped at the end.
struct ReportFiles {
  explicit ReportFiles(const RunContext& ctx)
      : json(path(ctx, "summary.json"), ctx.comm), csv(path(ctx, "fom_history.csv"), ctx.comm),
        romCsv(path(ctx, "rom_history.csv"), ctx.comm), png(path(ctx, "hamiltonian.png"), ctx.comm),
        svCsv(path(ctx, "singular_values.csv"), ctx.comm), svPng(path(ctx, "singular_values.png"), ctx.comm),
        configFile(path(ctx, "config.yaml"), ctx.comm), xdmf(path(ctx, "fields.xdmf"), ctx.comm),
        fieldsPng(path(ctx, "fields.png"), ctx.comm), spaceTimePng(path(ctx, "spacetime.png"), ctx.comm) {
    // The speed-accuracy report (HyperReport.hpp).
    for (const char* name : {"runs.csv", "report.md", "error_vs_m.png", "pareto.png", "hamiltonian_terms.png",
                             "hamiltonian_terms.csv", "deim_singular_values.csv", "adeim_updates.csv",
                             "adeim_updates.png", "error_vs_total_time.png"}) {
      hyper[name] = std::make_unique<RenameOnCommit>(path(ctx, name), ctx.comm);
      hyperPaths[name] = hyper[name]->tempPath();
    }
  }
  static std::string path(const RunContext& ctx, const std::string& name) { return ctx.outputDir + "/" + name; }
  RenameOnCommit json, csv, romCsv, png, svCsv, svPng, configFile, xdmf, fieldsPng, spaceTimePng;
  std::map<std::string, std::unique_ptr<RenameOnCommit>> hyper;
  std::map<std::string, std::string> hyperPaths;
};

// What rank 0 wrote besides the files every run has.
struct ReportWritten {
  int plotted = 0;                       // hamiltonian.png
  int pictured = 0;                      // fields.png or spacetime.png
  std::vector<std::string> hyperFiles;   // of ReportFiles::hyper
};

// Rank 0's part: the histories, the speed-accuracy report, the plots, summary.json, config.yaml
// and the field outputs, all under their temporary names.
ReportWritten writeOnRoot(const RunContext& ctx, const RunOptions& opt, const FomResult& fom, const RomStages* rom, ReportFiles& files,
                          const std::string& summary, const FieldOutput& fields, const FieldPicture& picture,
                          bool xdmf) {
  ReportWritten w;
  const bool plots = opt.output.plots;
  const double dt = opt.evaluation.time.dt, H0 = fom.hamiltonian.front();
  const long saveEvery = opt.output.saveEvery;
  const ModelRun* firstRom = firstRomRun(rom);
  writeHistoryCsv(fom.hamiltonian, H0, nullptr, saveEvery, dt, files.csv.tempPath());
  if (firstRom) writeHistoryCsv(firstRom->hamiltonian, H0, &firstRom->errors, saveEvery, dt, files.romCsv.tempPath());
  if (rom) w.hyperFiles = writeHyperReport(opt, fom, *rom, files.hyperPaths, plots);
  const bool deimSv = std::find(w.hyperFiles.begin(), w.hyperFiles.end(), "deim_singular_values.csv") != w.hyperFiles.end();
  if (rom)
    writeSingularValues(rom->basis.singularValues, files.svCsv.tempPath(), files.svPng.tempPath(), plots,
                        deimSv ? files.hyperPaths.at("deim_singular_values.csv") : "");
  std::string why;
  if (plots) w.plotted = plotHamiltonian(files.csv.tempPath(), firstRom ? files.romCsv.tempPath() : "",
                                         files.png.tempPath(), why);
  if (!w.plotted && !why.empty()) std::fprintf(stderr, "[gphr] no plots: %s\n", why.c_str());
  writeTextFile(files.json.tempPath(), summary + "\n");
  writeTextFile(files.configFile.tempPath(), opt.record.yaml);
  for (const auto& note : fields.notes) std::fprintf(stderr, "[gphr] %s\n", note.c_str());
  if (xdmf) writeTextFile(files.xdmf.tempPath(), fieldsXdmf(fom, fields));
  if (!picture.note.empty()) std::fprintf(stderr, "[gphr] %s\n", picture.note.c_str());
  if (!picture.file.empty())
    w.pictured = drawFieldPicture(picture, (picture.file == "fields.png" ? files.fieldsPng : files.spaceTimePng).tempPath());
  if (rom) {  // last: it names the pictures drawn
    std::vector<std::string> figures;
    for (const auto& f : w.hyperFiles)
      if (f.size() > 4 && f.compare(f.size() - 4, 4, ".png") == 0) figures.push_back(f);
    if (std::filesystem::exists(files.svPng.tempPath())) figures.push_back("singular_values.png");
    if (w.plotted) figures.push_back("hamiltonian.png");
    if (w.pictured) figures.push_back(picture.file + " (the fields)");
    writeHyperReportMd(ctx, opt, fom, *rom, files.hyperPaths.at("report.md"), figures,
                       w.pictured ? "" : picture.note.empty() ? std::string("no field picture") : picture.note);
    w.hyperFiles.push_back("report.md");
  }
  return w;
}

// Commits what was written and drops the rest. In the directory of an earlier run, a report file
// this run does not write is that run's and is removed, so the directory does not mix two runs
// (RunContext::replacesEarlierRun; a directory without an earlier summary.json is left as it is).
// Collective: rank 0's verdicts are broadcast. summary.json last: its presence means the run is complete.
void commitReport(const RunContext& ctx, const RomStages* rom, ReportFiles& files, ReportWritten w,
                  const FieldPicture& picture, bool xdmf) {
  const bool root = ctx.comm->getRank() == 0;
  auto commitOrDrop = [&](RenameOnCommit& f, int written) {
    Teuchos::broadcast(*ctx.comm, 0, Teuchos::outArg(written));
    if (written) {
      f.commit();
    } else if (root && ctx.replacesEarlierRun) {
      std::error_code ec;
      std::filesystem::remove(f.finalPath(), ec);
      if (ec) std::fprintf(stderr, "[gphr] warning: cannot remove the earlier run's '%s': %s\n", f.finalPath().c_str(),
                           ec.message().c_str());
    }
  };
  files.csv.commit();
  files.configFile.commit();
  commitOrDrop(files.romCsv, firstRomRun(rom) != nullptr);
  commitOrDrop(files.svCsv, rom != nullptr);
  commitOrDrop(files.svPng, root && std::filesystem::exists(files.svPng.tempPath()));
  commitOrDrop(files.png, w.plotted);
  commitOrDrop(files.xdmf, xdmf);
  commitOrDrop(files.fieldsPng, w.pictured && picture.file == "fields.png");
  commitOrDrop(files.spaceTimePng, w.pictured && picture.file == "spacetime.png");
  for (auto& [name, file] : files.hyper)
    commitOrDrop(*file, root && std::find(w.hyperFiles.begin(), w.hyperFiles.end(), name) != w.hyperFiles.end());
  files.json.commit();
}

}  // namespace

std::string writeReport(const RunContext& ctx, const RunOptions& opt, const FomResult& fom, const RomStages* rom) {
  ReportFiles files(ctx);
  // artifacts.h5: written in place when it already holds the training cache, else written to a
  // temporary name and renamed.
  const bool inPlace = std::filesystem::exists(ctx.artifactsPath());
  const FieldOutput fields = fieldOutputOf(opt, fom, rom);
  const bool xdmf = opt.output.xdmf && fields.grid;
  ctx.comm->barrier();
  RenameOnCommit h5(ctx.artifactsPath(), ctx.comm);
  {
    Hdf5File f(inPlace ? ctx.artifactsPath() : h5.tempPath(), ctx.comm,
               inPlace ? Hdf5File::Mode::ReadWrite : Hdf5File::Mode::Create);
    writeArtifacts(ctx, opt, fom, rom, xdmf ? &fields : nullptr, f);
  }
  const std::string summary = summaryOf(ctx, opt, fom, rom).str();
  const FieldPicture picture = opt.output.plots ? fieldPicture(opt.output.fieldTimes, fom, fields)
                                                                               : FieldPicture{};
  ReportWritten written;
  // rank 0 writes the report; its failure (a full disk, say) ends every rank
  onRootAgreed(ctx.comm, "gphr run: the report",
               [&] { written = writeOnRoot(ctx, opt, fom, rom, files, summary, fields, picture, xdmf); });
  if (!inPlace) h5.commit();
  commitReport(ctx, rom, files, written, picture, xdmf);
  return summary;
}

}  // namespace gphr
