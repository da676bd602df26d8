#include "gphr/driver/ValidationReport.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/core/Provenance.hpp"
#include "gphr/core/Fnv1a.hpp"
#include "gphr/driver/Gnuplot.hpp"
#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/Json.hpp"
#include "gphr/online/ReducedModel.hpp"

namespace gphr {

namespace {

// A double in a data file: the fewest digits that read back as the same number (0.9, not
// 0.90000000000000002).
std::string num(double x) {
  std::ostringstream os;
  os << detail::Shortest{x};
  return os.str();
}

// Why no model of the file meets `level`: the Galerkin ROM of a k bounds what its hyper-reduced
// models reach there (they approximate its nonlinear term), so where even the best ROM misses the
// level a larger basis is needed, and where it meets it the DEIM sizes (or term budgets) are too small.
std::string whyNone(const std::vector<ModelStatistics>& stats, double level) {
  const ModelStatistics* rom = nullptr;  // the most accurate ROM
  for (const auto& s : stats)
    if (methodInfo(s.method).reduction == Reduction::Galerkin && (!rom || s.maxError < rom->maxError)) rom = &s;
  if (!rom) return "raise k or m";
  std::ostringstream os;
  os << "the best ROM (k = " << rom->k << ") reaches " << std::scientific << std::setprecision(2) << rom->maxError;
  os << (rom->maxError >= level ? "; raise k" : "; raise m at that k");
  return os.str();
}

// A figure a person reads in validation.md: printf's format, "-" for NaN.
std::string shown(double x, const char* format) {
  if (std::isnan(x)) return "-";
  char b[48];
  std::snprintf(b, sizeof b, format, x);
  return b;
}

std::string sci(double x) {
  if (std::isnan(x)) return "-";
  if (std::isinf(x)) return "inf";
  char b[32];
  std::snprintf(b, sizeof b, "%.3e", x);
  return b;
}

std::string muText(const std::vector<double>& mu) {
  std::string s;
  for (double x : mu) s += (s.empty() ? "" : ",") + num(x);
  return s;
}

// Write-then-rename of a text file (rank 0 only), InputError naming it if it cannot be written.
void writeText(const std::string& path, const std::string& text) { writeTextFile(path, text); }

// Writes the plot's data and script beside the report, draws validation_error.png and removes
// the two; a failure (a full disk, gnuplot) leaves no plot file and is said on stderr.
void drawErrorPlot(const std::string& dir, const std::string& data, const std::string& script) {
  const std::string dat = dir + "/validation_error.dat", gp = dir + "/validation_error.gp",
                    png = dir + "/validation_error.png";
  bool drawn = false;
  try {
    writeTextFile(dat, data);
    writeTextFile(gp, script);
    drawn = runGnuplot(gp, {png});
  } catch (const InputError& e) {
    std::fprintf(stderr, "[gphr] validate: %s\n", e.what());
  }
  std::remove(dat.c_str());
  std::remove(gp.c_str());
  if (!drawn) std::fprintf(stderr, "[gphr] validate: '%s' not drawn\n", png.c_str());
}

// The line colour of model i of n: twenty distinct colours (a qualitative palette: dark and light
// of ten hues), so that a file's models do not share one up to 20; beyond, the point type differs.
std::string modelColour(size_t i) {
  static const char* kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
                                   "#7f7f7f", "#bcbd22", "#17becf", "#aec7e8", "#ffbb78", "#98df8a", "#ff9896",
                                   "#c5b0d5", "#c49c94", "#f7b6d2", "#c7c7c7", "#dbdb8d", "#9edae5"};
  return kColours[i % (sizeof kColours / sizeof *kColours)];
}

// Two parameters: one map per model, each test point a square coloured by log10 E_L2 (a point that
// did not finish drawn as a cross), the training box outlined (dashed, with a margin around it so
// that no edge lies on the axes) and the training points drawn as open circles.
void plotErrorMaps(const std::string& dir, const ReducedModelData& d, const std::vector<ModelStatistics>& stats,
                   const std::vector<ValidationRecord>& records) {
  std::ostringstream dat;
  for (const auto& s : stats) {
    dat << "# " << s.label << "\n";
    for (const auto& r : records)
      if (r.label() == s.label)
        dat << num(r.mu[0]) << " " << num(r.mu[1]) << " " << (r.status == RunStatus::Ok ? num(std::log10(r.eL2)) : "NaN")
            << "\n";
    dat << "\n\n";
  }
  dat << "# training points\n";  // the last block (a placeholder NaN row where the file has none)
  for (const auto& mu : d.trainingParameters) dat << num(mu[0]) << " " << num(mu[1]) << "\n";
  if (d.trainingParameters.empty()) dat << "NaN NaN\n";
  dat << "\n\n";
  double lo = 0.0, hi = -30.0;
  for (const auto& r : records)
    if (r.status == RunStatus::Ok && r.eL2 > 0) {
      lo = std::min(lo, std::floor(std::log10(r.eL2)));
      hi = std::max(hi, std::ceil(std::log10(r.eL2)));
    }
  if (hi < lo) hi = lo + 1;
  const std::string data = gnuplotQuoted(dir + "/validation_error.dat");
  const auto range = [&](size_t p) {  // the box and every test point, 8 % beyond: no box edge on the frame
    double a = d.box[p].first, b = d.box[p].second;
    for (const auto& r : records) a = std::min(a, r.mu[p]), b = std::max(b, r.mu[p]);
    const double margin = 0.08 * std::max(b - a, 1e-12 * std::max(1.0, std::abs(b)));
    return num(a - margin) + ":" + num(b + margin);
  };
  std::ostringstream gp;
  const size_t cols = std::min<size_t>(stats.size(), 3), rows = (stats.size() + cols - 1) / cols;
  gp << "set terminal pngcairo size " << 420 * cols << "," << 380 * rows << " noenhanced\nset output "
     << gnuplotQuoted(dir + "/validation_error.png") << "\nset multiplot layout " << rows << "," << cols
     << " title 'log10 of the relative error E_L2 over the test points'\nunset key\nset xlabel "
     << gnuplotQuoted(d.parameterNames[0]) << "\nset ylabel " << gnuplotQuoted(d.parameterNames[1])
     << "\nset cblabel 'log10 E_L2'\n"
     << "set cbrange [" << lo << ":" << hi << "]\n"  // one colour scale for every model
     << "set object 1 rect from " << d.box[0].first << "," << d.box[1].first << " to " << d.box[0].second << ","
     << d.box[1].second << " fs empty border lc rgb 'black' dt 2\n"
     << "set xrange [" << range(0) << "]\nset yrange [" << range(1) << "]\n";
  for (size_t i = 0; i < stats.size(); ++i)
    gp << "set title " << gnuplotQuoted(stats[i].label + " (o: training point)") << "\nplot " << data << " index "
       << i << " using 1:2:3 with points pt 5 ps 2.5 palette, '' index " << i
       << " using 1:($3 != $3 ? $2 : 1/0) with points pt 2 ps 2 lc rgb 'red', '' index " << stats.size()
       << " using 1:2 with points pt 6 ps 2.8 lc rgb 'black'\n";
  gp << "unset multiplot\n";
  drawErrorPlot(dir, dat.str(), gp.str());
}

// One data block per model (points sorted by the parameter), then gnuplot over the blocks.
void plotErrors(const std::string& dir, const ReducedModelData& d, const std::vector<ModelStatistics>& stats,
                const std::vector<ValidationRecord>& records) {
  if (d.parameterNames.size() > 2 || !haveGnuplot()) return;
  if (d.parameterNames.size() == 2) return plotErrorMaps(dir, d, stats, records);
  std::ostringstream dat;
  for (const auto& s : stats) {
    std::vector<std::pair<double, double>> pts;
    for (const auto& r : records)
      if (r.label() == s.label && r.status == RunStatus::Ok) pts.emplace_back(r.mu[0], r.eL2);
    std::sort(pts.begin(), pts.end());
    dat << "# " << s.label << "\n";
    for (const auto& [x, e] : pts) dat << num(x) << " " << num(e) << "\n";
    dat << "\n\n";
  }
  std::ostringstream xlabel, gp;
  xlabel << d.parameterNames[0] << " (training box [" << d.box[0].first << ", " << d.box[0].second
         << "], dashed; training points: ticks at the bottom)";
  // The x range holds the box and every test point with a margin, so that the box's edges (dashed)
  // never fall on the frame.
  double xlo = d.box[0].first, xhi = d.box[0].second;
  for (const auto& r : records) xlo = std::min(xlo, r.mu[0]), xhi = std::max(xhi, r.mu[0]);
  const double margin = 0.05 * std::max(xhi - xlo, 1e-12 * std::max(1.0, std::abs(xhi)));
  gp << "set terminal pngcairo size 960,560 noenhanced\nset output " << gnuplotQuoted(dir + "/validation_error.png")
     << "\nset logscale y\nset format y '%.0e'\nset key outside right\nset grid\n"
     << "set title 'Relative error E_L2 over the parameter box'\nset xlabel "
     << gnuplotQuoted(xlabel.str())
     << "\nset ylabel 'E_L2'\nset xrange [" << xlo - margin << ":" << xhi + margin << "]\n"
     << "set arrow from " << d.box[0].first << ", graph 0 to " << d.box[0].first << ", graph 1 nohead dt 2\n"
     << "set arrow from " << d.box[0].second << ", graph 0 to " << d.box[0].second << ", graph 1 nohead dt 2\n";
  for (const auto& mu : d.trainingParameters)
    gp << "set arrow from " << mu[0] << ", graph 0 to " << mu[0] << ", graph 0.05 nohead lw 3 lc rgb 'black'\n";
  gp << "plot ";
  for (size_t i = 0; i < stats.size(); ++i)
    gp << (i ? ", " : "") << gnuplotQuoted(dir + "/validation_error.dat") << " index " << i
       << " using 1:2 with linespoints lw 1.5 pt " << (i % 13 + 1) << " lc rgb '" << modelColour(i)
       << "' title " << gnuplotQuoted(stats[i].label);
  gp << "\n";
  drawErrorPlot(dir, dat.str(), gp.str());
}

// What the break-even's offline seconds count: the build's wall time, in which a stage taken from
// the artifacts cache counts as the time to read it.
std::string offlineCounted(const ReducedModelData& d) {
  if (d.cachedStages.empty()) return "offline is the build's wall time, every stage computed by it.";
  std::string stages;
  for (const auto& s : d.cachedStages) stages += (stages.empty() ? "" : ", ") + s;
  return "offline is the build's wall time, in which the stages it took from its artifacts cache (" + stages +
         ") count only the time to read them: a build from an empty --output directory costs more and breaks even "
         "later.";
}

// The test points that are training points: their errors are the build's own fit, not held out.
// Equal to round-off of the box's width (a grid's points are computed, a test point's read).
std::string trainingAmongTests(const ReducedModelData& d, const std::vector<Query>& points) {
  const auto same = [&](const std::vector<double>& a, const std::vector<double>& b) {
    for (size_t p = 0; p < a.size(); ++p)
      if (std::abs(a[p] - b[p]) > 1e-12 * std::max(1.0, d.box[p].second - d.box[p].first)) return false;
    return a.size() == b.size();
  };
  std::string names;
  for (const auto& q : points)
    for (const auto& mu : d.trainingParameters)
      if (same(mu, q.mu)) {
        names += (names.empty() ? "" : ", ") + q.name;
        break;
      }
  if (names.empty()) return "";
  return "Test points that are training points (their errors are not held-out errors; marked in the plot): " +
         names + ".\n\n";
}

}  // namespace

std::string ValidationRecord::label() const {
  return method + " k=" + std::to_string(k) + (m > 0 ? " m=" + std::to_string(m) : "");
}

double percentile(std::vector<double> x, double p) {
  if (x.empty()) return NAN;
  std::sort(x.begin(), x.end());
  const double pos = p * (x.size() - 1);
  const size_t i = static_cast<size_t>(std::floor(pos));
  if (i + 1 >= x.size()) return x.back();
  return x[i] + (pos - i) * (x[i + 1] - x[i]);
}

std::vector<ModelStatistics> modelStatistics(const std::vector<ValidationRecord>& records) {
  std::vector<ModelStatistics> out;
  std::map<std::string, std::vector<const ValidationRecord*>> by;
  for (const auto& r : records) {
    if (!by.count(r.label())) {
      out.emplace_back();
      out.back().label = r.label(), out.back().method = r.method, out.back().k = r.k, out.back().m = r.m;
    }
    by[r.label()].push_back(&r);
  }
  for (auto& s : out) {
    std::vector<double> e, t;
    double worst = -1.0;
    for (const auto* r : by[s.label]) {
      ++s.points;
      const bool ok = r->status == RunStatus::Ok && std::isfinite(r->eL2);
      s.ok += ok;
      const double err = ok ? r->eL2 : std::numeric_limits<double>::infinity();
      e.push_back(err);
      if (ok) t.push_back(r->onlineSeconds);
      if (err > worst) worst = err, s.worstPoint = r->point;
    }
    s.maxError = *std::max_element(e.begin(), e.end());
    double sum = 0.0;
    for (double x : e) sum += x;
    s.meanError = sum / e.size();
    s.p95Error = percentile(e, 0.95);
    double ts = 0.0;
    for (double x : t) ts += x;
    s.meanOnline = t.empty() ? NAN : ts / t.size();
  }
  return out;
}

namespace {
// The last line of a point's file: FNV-1a of everything before it, so that a changed byte makes
// the point one to redo instead of a record the report would take as measured.
std::string recordsChecksum(const std::string& body) {
  Fnv1a h;
  h.text(body);
  return "checksum\t" + h.hex();
}

// One record line (writePointRecords' format); false where it does not parse whole.
bool parseRecord(const std::string& line, ValidationRecord& r) {
  std::istringstream ls(line);
  std::string status, eL2, estimate, queryEstimate, online, setup, mu;
  int extrap = 0;
  std::getline(ls, r.point, '\t'), std::getline(ls, r.method, '\t');
  ls >> r.k >> r.m >> status >> eL2 >> estimate >> queryEstimate >> online >> setup >> extrap >> mu;
  if (!ls && !ls.eof()) return false;
  try {
    r.status = statusFromName(status);
    r.eL2 = std::stod(eL2), r.onlineSeconds = std::stod(online), r.setupSeconds = std::stod(setup);
    r.errorEstimate = std::stod(estimate), r.queryEstimate = std::stod(queryEstimate);
    std::istringstream ms(mu);
    for (std::string x; std::getline(ms, x, ',');) r.mu.push_back(std::stod(x));
  } catch (const std::exception&) {  // std::stod: not a number, or out of range; an unknown status
    return false;
  }
  r.extrapolated = extrap != 0;
  return true;
}

// Rank 0's part of readPointRecords: the file's records if its key and checksum match.
bool readPointFile(const std::string& path, const std::string& key, std::vector<ValidationRecord>& recs,
                   double& fomSeconds) {
  std::ifstream in(path);
  std::ostringstream all;
  all << in.rdbuf();
  const std::string text = all.str();
  const size_t last = text.rfind('\n', text.size() >= 2 ? text.size() - 2 : 0);
  if (text.empty() || text.back() != '\n' || last == std::string::npos) return false;
  const std::string body = text.substr(0, last + 1), tail = text.substr(last + 1, text.size() - last - 2);
  if (tail != recordsChecksum(body)) {
    std::fprintf(stderr, "[gphr] validate: %s is damaged (checksum mismatch): point redone\n", path.c_str());
    return false;
  }
  std::istringstream lines(body);
  std::string line;
  if (!std::getline(lines, line) || line != "key\t" + key) return false;
  if (!std::getline(lines, line) || line.rfind("fom_s\t", 0) != 0) return false;
  try {
    fomSeconds = std::stod(line.substr(6));
  } catch (const std::exception&) {
    return false;
  }
  while (std::getline(lines, line)) {
    ValidationRecord r;
    if (!parseRecord(line, r)) return false;
    recs.push_back(r);
  }
  return true;
}
}  // namespace

void writePointRecords(const std::string& path, const std::string& key, const std::vector<ValidationRecord>& recs,
                       double fomSeconds, const RCP<const Comm>& comm) {
  if (comm->getRank() == 0) {
    std::ostringstream os;
    os << "key\t" << key << "\nfom_s\t" << num(fomSeconds) << "\n";
    for (const auto& r : recs)
      os << r.point << "\t" << r.method << "\t" << r.k << "\t" << r.m << "\t" << statusName(r.status) << "\t" << num(r.eL2) << "\t"
         << num(r.errorEstimate) << "\t" << num(r.queryEstimate) << "\t" << num(r.onlineSeconds) << "\t" << num(r.setupSeconds) << "\t" << r.extrapolated << "\t" << muText(r.mu)
         << "\n";
    writeText(path, os.str() + recordsChecksum(os.str()) + "\n");
  }
  comm->barrier();
}

bool readPointRecords(const std::string& path, const std::string& key, const RCP<const Comm>& comm,
                      std::vector<ValidationRecord>& recs, double& fomSeconds) {
  int usable = comm->getRank() == 0 && readPointFile(path, key, recs, fomSeconds);
  Teuchos::broadcast(*comm, 0, Teuchos::outArg(usable));
  if (!usable) recs.clear();
  return usable != 0;
}

namespace {

// Ranks 1..N of x, ties given their mean rank.
std::vector<double> ranks(const std::vector<double>& x) {
  std::vector<size_t> order(x.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return x[a] < x[b]; });
  std::vector<double> r(x.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && x[order[j + 1]] == x[order[i]]) ++j;
    for (size_t t = i; t <= j; ++t) r[order[t]] = 0.5 * (i + j) + 1.0;
    i = j + 1;
  }
  return r;
}

// Spearman's rank correlation: Pearson's of the ranks (NaN below 3 pairs or for a constant sample).
double rankCorrelation(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() < 3) return NAN;
  const auto ra = ranks(a), rb = ranks(b);
  const double mean = 0.5 * (a.size() + 1.0);
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (size_t i = 0; i < ra.size(); ++i)
    sab += (ra[i] - mean) * (rb[i] - mean), saa += (ra[i] - mean) * (ra[i] - mean), sbb += (rb[i] - mean) * (rb[i] - mean);
  return saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : NAN;
}

// validation.md's section on the error estimate (doc/error-estimate.md) against the error, over
// the runs where both are known: per model the median and range of estimate / E_L2 and the share
// of points within 3x; over all runs, the rank correlation (whether the estimate orders the runs
// as the error does).
std::string estimateSection(const std::vector<ValidationRecord>& records, double ValidationRecord::*estimateOf,
                            const std::string& title, const std::string& what, JsonObject& out) {
  std::vector<std::string> labels;
  std::map<std::string, std::vector<double>> ratios, modelErrors, modelEstimates;
  std::vector<double> errors, estimates;
  for (const auto& r : records) {
    const double e = r.*estimateOf;
    if (r.status != RunStatus::Ok || !(r.eL2 > 0.0) || !std::isfinite(e)) continue;
    if (!ratios.count(r.label())) labels.push_back(r.label());
    ratios[r.label()].push_back(e / r.eL2);
    modelErrors[r.label()].push_back(r.eL2), modelEstimates[r.label()].push_back(e);
    errors.push_back(r.eL2), estimates.push_back(e);
  }
  std::ostringstream md;
  md << "\n## " << title << "\n\n" << what << "; here it is set against E_L2 at every point where both are known. Over all "
     << errors.size() << " runs the rank correlation (Spearman) of estimate and error is "
     << (std::isfinite(rankCorrelation(errors, estimates)) ? shown(rankCorrelation(errors, estimates), "%.3f") : "-")
     << "; per model, over its points, in the last column.\n\n| model | points | estimate / E_L2, median | min | max | "
        "within 3x | rank correlation |\n| --- | --- | --- | --- | --- | --- | --- |\n";
  long within = 0;
  for (const auto& label : labels) {
    const auto& x = ratios[label];
    const long in3 = std::count_if(x.begin(), x.end(), [](double q) { return q <= 3.0 && q >= 1.0 / 3.0; });
    within += in3;
    md << "| " << label << " | " << x.size() << " | " << shown(percentile(x, 0.5), "%.2f") << " | "
       << shown(*std::min_element(x.begin(), x.end()), "%.2f") << " | " << shown(*std::max_element(x.begin(), x.end()), "%.2f")
       << " | " << in3 << "/" << x.size() << " | "
       << shown(rankCorrelation(modelErrors[label], modelEstimates[label]), "%.3f") << " |\n";
  }
  out.set("runs", static_cast<long>(errors.size()))
      .set("rank_correlation", rankCorrelation(errors, estimates))
      .set("within_3x", errors.empty() ? NAN : double(within) / errors.size());
  return errors.empty() ? std::string() : md.str();
}

// validation_estimate.png: both estimates against E_L2 at every finished run, log-log, with the
// lines estimate = E_L2 and a factor 3 either side. True when drawn.
bool plotEstimates(const std::string& dir, const std::vector<ValidationRecord>& records) {
  if (!haveGnuplot()) return false;
  std::ostringstream dat;
  size_t points = 0;
  for (double ValidationRecord::*field : {&ValidationRecord::errorEstimate, &ValidationRecord::queryEstimate}) {
    for (const auto& r : records)
      if (r.status == RunStatus::Ok && r.eL2 > 0.0 && std::isfinite(r.*field) && r.*field > 0.0)
        dat << num(r.eL2) << " " << num(r.*field) << "\n", ++points;
    dat << "\n\n";
  }
  if (points == 0) return false;
  const std::string base = dir + "/validation_estimate";
  std::ostringstream gp;
  gp << "set terminal pngcairo size 700,600 noenhanced\nset output " << gnuplotQuoted(base + ".png")
     << "\nset logscale xy\nset format x '%.0e'\nset format y '%.0e'\nset grid\nset key top left\n"
     << "set title 'Error estimates against the true error E_L2 (one point per run)'\n"
     << "set xlabel 'E_L2 (against the full model)'\nset ylabel 'estimate'\nset size square\n"
     << "plot x title 'estimate = E_L2' lw 2 lc 'black', 3*x title 'factor 3' dt 2 lc 'gray', x/3 notitle dt 2 lc 'gray', "
     << gnuplotQuoted(base + ".dat") << " index 0 using 1:2 with points pt 7 ps 0.8 title 'E_L2_estimate (full residual)', "
     << gnuplotQuoted(base + ".dat") << " index 1 using 1:2 with points pt 5 ps 0.8 title 'error_estimate (query)'\n";
  bool drawn = false;
  try {
    writeTextFile(base + ".dat", dat.str());
    writeTextFile(base + ".gp", gp.str());
    drawn = runGnuplot(base + ".gp", {base + ".png"});
  } catch (const InputError& e) {
    std::fprintf(stderr, "[gphr] validate: %s\n", e.what());
  }
  std::remove((base + ".dat").c_str());
  std::remove((base + ".gp").c_str());
  if (!drawn) std::fprintf(stderr, "[gphr] validate: '%s.png' not drawn\n", base.c_str());
  return drawn;
}

}  // namespace

void writeValidationReport(const std::string& dir, const ReducedModel& model, const std::vector<Query>& points,
                           const std::vector<ValidationRecord>& records, const std::vector<double>& fomSeconds) {
  const auto& d = model.data();
  std::ostringstream csv;
  csv << "point";
  for (const auto& p : d.parameterNames) csv << "," << p;
  csv << ",model,method,k,m,E_L2,E_L2_estimate,error_estimate,status,extrapolated,online_s,setup_s\n";
  for (const auto& r : records) {
    csv << r.point;
    for (double x : r.mu) csv << "," << num(x);
    // a ROM has no m: the field is left empty, not 0 (which reads as a size)
    csv << "," << r.label() << "," << r.method << "," << r.k << "," << (r.m > 0 ? std::to_string(r.m) : "") << ","
        << num(r.eL2) << "," << num(r.errorEstimate) << "," << num(r.queryEstimate) << "," << statusName(r.status)
        << "," << (r.extrapolated ? "yes" : "no") << "," << num(r.onlineSeconds) << "," << num(r.setupSeconds) << "\n";
  }
  writeText(dir + "/validation.csv", csv.str());
  const auto stats = modelStatistics(records);
  double fomMean = 0.0;
  for (double t : fomSeconds) fomMean += t / fomSeconds.size();
  std::ostringstream md;
  md << "# Validation of " << model.path() << " over " << points.size() << " test points\n\n"
     << "Scene " << d.sceneName << "; built by gphr " << d.gphrVersion << " on " << d.created << " ("
     << shown(d.offlineSeconds, "%.1f") << " s offline on " << d.buildRanks << " rank(s)). Full model: " << shown(fomMean, "%.3g")
     << " s per query on average. E_L2 is eq:errNR over the saved steps; a point whose run did not finish counts as "
        "an infinite error. The 95th percentile interpolates linearly between order statistics. Break-even: the "
        "number of queries after which the offline cost is repaid, offline / (full - model) per query; "
     << offlineCounted(d) << "\n\n"
     << trainingAmongTests(d, points)
     << "| model | points ok | max E_L2 | mean E_L2 | p95 E_L2 | worst point | online s | speed-up | "
        "break-even queries |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  std::vector<JsonObject> js;
  for (const auto& s : stats) {
    const double speedup = fomMean / s.meanOnline, breakEven = d.offlineSeconds / (fomMean - s.meanOnline);
    md << "| " << s.label << " | " << s.ok << "/" << s.points << " | " << sci(s.maxError) << " | " << sci(s.meanError)
       << " | " << sci(s.p95Error) << " | " << s.worstPoint << " | " << shown(s.meanOnline, "%.3g") << " | "
       << shown(speedup, "%.2fx") << " | " << (breakEven > 0 ? shown(std::ceil(breakEven), "%.0f") : std::string("never"))
       << " |\n";
    JsonObject j;
    j.set("model", s.label).set("k", s.k).set("m", s.m).set("points", s.points).set("ok", s.ok)
        .set("E_L2_max", s.maxError).set("E_L2_mean", s.meanError).set("E_L2_p95", s.p95Error)
        .set("worst_point", s.worstPoint).set("online_s_mean", s.meanOnline).set("speedup", speedup)
        .set("break_even_queries", breakEven > 0 ? std::ceil(breakEven) : NAN);
    js.push_back(j);
  }
  std::string outside;
  for (const auto& q : points)
    if (d.outsideBox(q.mu)) outside += (outside.empty() ? "" : ", ") + q.name;
  if (!outside.empty()) md << "\nPoints outside the training box (extrapolated, included above): " << outside << "\n";
  md << "\n## The cheapest model whose largest error over the box is below each level\n\n| level | model | max E_L2 | "
        "online s |\n| --- | --- | --- | --- |\n";
  for (double level = 1e-1; level >= 1e-8; level /= 10) {
    const ModelStatistics* best = nullptr;
    for (const auto& s : stats)
      if (s.maxError < level && (!best || s.meanOnline < best->meanOnline)) best = &s;
    const std::string slower = best && best->meanOnline >= fomMean
                                   ? " (slower than the full model's " + shown(fomMean, "%.3g") + " s: no saving)"
                                   : "";
    md << "| " << shown(level, "%.0e") << " | " << (best ? best->label + slower : "none: " + whyNone(stats, level)) << " | "
       << (best ? sci(best->maxError) : "-") << " | " << (best ? shown(best->meanOnline, "%.3g") : "-") << " |\n";
  }
  JsonObject estimate;
  md << estimateSection(records, &ValidationRecord::errorEstimate, "The error estimate against the error",
                        "E_L2_estimate (doc/error-estimate.md) needs no full-model trajectory, only the full model's "
                        "residual along the lift (n-sized work)",
                        estimate);
  JsonObject queryEstimate;
  md << estimateSection(records, &ValidationRecord::queryEstimate, "The query's error estimate against the error",
                        "error_estimate, what `gphr query` reports (doc/error-estimate.md), costs no n-sized work: the "
                        "residual on the file's indicator rows, calibrated on the build's training points",
                        queryEstimate);
  if (plotEstimates(dir, records)) md << "\n![estimates against the error](validation_estimate.png)\n";
  writeText(dir + "/validation.md", md.str());
  JsonObject summary;
  summary.set("model_file", model.path())
      .set("points", static_cast<long>(points.size()))
      .set("fom_online_s_mean", fomMean)
      .set("offline_s", d.offlineSeconds).set("gphr_version", gphrVersion()).set("models", js)
      .set("error_estimate", estimate).set("query_error_estimate", queryEstimate);
  writeText(dir + "/validation_summary.json", summary.str(2) + "\n");
  plotErrors(dir, d, stats, records);
  std::printf("%s", md.str().c_str());
}

}  // namespace gphr
