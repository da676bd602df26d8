#include "gphr/core/Method.hpp"
#include "gphr/driver/Console.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace gphr {

namespace {
std::string cell(double x, const char* fmt) {
  if (!std::isfinite(x)) return "-";
  char b[32];
  std::snprintf(b, sizeof b, fmt, x);
  return b;
}
}  // namespace

std::string runTable(const RunContext& ctx, const RunOptions& opt, const FomResult& fom, const RomStages* rom) {
  std::ostringstream os;
  char line[160];
  std::snprintf(line, sizeof line, "gphr run: %s, %d rank(s), T = %g, dt = %g, %s\n", opt.scene->name().c_str(),
                ctx.comm->getSize(), opt.T, opt.evaluation.time.dt,
                opt.scheme.c_str());
  os << line;
  std::snprintf(line, sizeof line, "%-9s %5s %5s  %-11s %10s %10s %9s\n", "method", "k", "m", "status", "E_L2",
                "online s", "speed-up");
  os << line;
  std::snprintf(line, sizeof line, "%-9s %5s %5s  %-11s %10s %10s %9s\n", method::kFom, "-", "-", "ok", "-",
                cell(fom.tOnline, "%.3g").c_str(), "1");
  os << line;
  if (rom)
    for (const auto& r : rom->runs) {
      std::snprintf(line, sizeof line, "%-9s %5d %5s  %-11s %10s %10s %9s\n", r.method.c_str(), r.k,
                    r.m > 0 ? std::to_string(r.m).c_str() : "-", statusName(r.status()), cell(r.eL2, "%.3e").c_str(),
                    cell(r.tOnline, "%.3g").c_str(), cell(fom.tOnline / r.tOnline, "%.3g").c_str());
      os << line;
    }
  const std::string report = ctx.outputDir + "/report.md";
  os << "report: " << (std::filesystem::exists(report) ? report : ctx.outputDir + "/summary.json") << "\n";
  return os.str();
}

}  // namespace gphr
