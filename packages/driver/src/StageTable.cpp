// gphr build's stage clocks of all ranks: gathered (every rank gets them: a few numbers per
// stage), then written and printed by rank 0.
#include "gphr/driver/StageTable.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace gphr {

namespace {

constexpr int kFields = 7;  // wall, cpu, mpiWall, mpiCpu, peakRssMb, critical, and a check of the name

// A cheap fingerprint of a stage name, so that ranks that ran different stages are caught.
double nameHash(const std::string& s) {
  unsigned h = 2166136261u;  // FNV-1a, 32 bits: exact in a double
  for (unsigned char c : s) h = (h ^ c) * 16777619u;
  return static_cast<double>(h);
}

std::string format(const char* fmt, double a, double b, double c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

}  // namespace

StageTable gatherStages(const RCP<const Comm>& comm, const std::vector<StageTime>& stages) {
  const int count = static_cast<int>(stages.size());
  int lo = 0, hi = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MIN, count, Teuchos::outArg(lo));
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, count, Teuchos::outArg(hi));
  if (lo != hi)
    throw std::logic_error("gphr build: the ranks timed " + std::to_string(lo) + " to " + std::to_string(hi) +
                           " stages; every rank runs the same stages");
  std::vector<double> mine;
  for (const auto& s : stages)
    mine.insert(mine.end(), {s.wall, s.cpu, s.mpiWall, s.mpiCpu, s.peakRssMb, s.critical, nameHash(s.name)});
  StageTable t;
  t.ranks = comm->getSize();
  std::vector<double> all(mine.size() * static_cast<size_t>(t.ranks));
  if (count > 0) Teuchos::gatherAll(*comm, count * kFields, mine.data(), static_cast<int>(all.size()), all.data());
  // The per-function split of the MPI time: kMpiCallKinds wall seconds and as many call counts
  // (exact in a double) per stage.
  std::vector<double> calls, allCalls(static_cast<size_t>(count) * 2 * kMpiCallKinds * t.ranks);
  for (const auto& s : stages) {
    calls.insert(calls.end(), s.callWall.begin(), s.callWall.end());
    for (long long c : s.callCount) calls.push_back(static_cast<double>(c));
  }
  if (count > 0)
    Teuchos::gatherAll(*comm, static_cast<int>(calls.size()), calls.data(), static_cast<int>(allCalls.size()),
                       allCalls.data());
  for (const auto& s : stages) t.names.push_back(s.name);
  for (int r = 0; r < t.ranks; ++r)
    for (int i = 0; i < count; ++i) {
      const double* v = &all[(static_cast<size_t>(r) * count + i) * kFields];
      if (v[6] != nameHash(t.names[i]))
        throw std::logic_error("gphr build: rank " + std::to_string(r) + " timed other stages than rank 0 (stage " +
                               std::to_string(i) + " is '" + t.names[i] + "' on rank 0)");
      StageTime s;
      s.name = t.names[i];
      s.wall = v[0], s.cpu = v[1], s.mpiWall = v[2], s.mpiCpu = v[3], s.peakRssMb = v[4], s.critical = v[5];
      const double* c = &allCalls[(static_cast<size_t>(r) * count + i) * 2 * kMpiCallKinds];
      for (int k = 0; k < kMpiCallKinds; ++k)
        s.callWall[k] = c[k], s.callCount[k] = static_cast<long long>(c[kMpiCallKinds + k]);
      t.rows.push_back(s);
    }
  return t;
}

std::string StageTable::csv() const {
  std::string out = "rank,stage,wall_s,cpu_s,mpi_wall_s,mpi_cpu_s,compute_s,peak_rss_mb,critical_s\n";
  const size_t n = names.size();
  for (size_t j = 0; j < rows.size(); ++j) {
    const StageTime& s = rows[j];
    char buf[256];
    std::snprintf(buf, sizeof buf, "%zu,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.1f,%.6f\n", j / n, s.name.c_str(), s.wall,
                  s.cpu, s.mpiWall, s.mpiCpu, s.compute(), s.peakRssMb, s.critical);
    out += buf;
  }
  return out;
}

std::string StageTable::mpiCallsCsv() const {
  std::string out = "rank,stage,call,calls,wall_s\n";
  const size_t n = names.size();
  for (size_t j = 0; j < rows.size(); ++j) {
    const StageTime& s = rows[j];
    for (int k = 0; k < kMpiCallKinds; ++k) {
      const char* call = mpiCallName(k);
      if (!call || s.callCount[k] == 0) continue;
      char buf[256];
      std::snprintf(buf, sizeof buf, "%zu,%s,%s,%lld,%.6f\n", j / n, s.name.c_str(), call, s.callCount[k],
                    s.callWall[k]);
      out += buf;
    }
  }
  return out;
}

std::string StageTable::summary() const {
  std::string out = "  stages (max over " + std::to_string(ranks) + " rank(s)): wall s / compute s / peak MB\n";
  const size_t n = names.size();
  for (size_t i = 0; i < n; ++i) {
    double wall = 0.0, compute = 0.0, rss = 0.0;
    for (int r = 0; r < ranks; ++r) {
      const StageTime& s = rows[static_cast<size_t>(r) * n + i];
      wall = std::max(wall, s.wall), compute = std::max(compute, s.compute()), rss = std::max(rss, s.peakRssMb);
    }
    char name[64];
    std::snprintf(name, sizeof name, "    %-22s", names[i].c_str());
    out += name + format("%9.3f %9.3f %8.1f\n", wall, compute, rss);
  }
  return out;
}

}  // namespace gphr
