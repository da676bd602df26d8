#include "gphr/core/StageClock.hpp"

#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <ctime>

namespace gphr {

namespace {

// Constant-initialised (no dynamic initialiser), so the interposer's static initializer may
// register before or after this file's static initialisation runs.
std::atomic<MpiTimeSource> g_source{nullptr};
std::atomic<const char* const*> g_callNames{nullptr};
std::atomic<bool> g_critical{false};

double seconds(const timespec& t) { return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec); }

}  // namespace

void setMpiTimeSource(MpiTimeSource source) { g_source.store(source); }

bool mpiTimeAvailable() { return g_source.load() != nullptr; }

bool criticalPathMeasured() { return g_critical.load(std::memory_order_relaxed); }

void setCriticalPathMeasured(bool on) { g_critical.store(on, std::memory_order_relaxed); }

void setMpiCallNames(const char* const* names) { g_callNames.store(names); }

const char* mpiCallName(int kind) {
  const char* const* names = g_callNames.load();
  return names && kind >= 0 && kind < kMpiCallKinds ? names[kind] : nullptr;
}

MpiTime mpiTimeNow() {
  const MpiTimeSource source = g_source.load();
  return source ? source() : MpiTime{};
}

ClockReading readClocks() {
  ClockReading r;
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  timespec t{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) == 0) r.cpu = seconds(t);
  r.mpi = mpiTimeNow();
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) == 0) r.peakRssMb = static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kB
  return r;
}

StageClocks::Scope::Scope(StageClocks& clocks, std::string name) : clocks_(clocks), phase_(name) {
  clocks_.begin(std::move(name));
}

StageClocks::Scope::~Scope() { clocks_.end(); }

void StageClocks::begin(std::string name) {
  size_t index = 0;
  while (index < stages_.size() && stages_[index].name != name) ++index;
  if (index == stages_.size()) {
    stages_.push_back(StageTime{});
    stages_.back().name = std::move(name);
  }
  open_.push_back(Open{index, ClockReading{}, StageTime{}});
  open_.back().start = readClocks();  // last: the bookkeeping above is not the stage's
}

void StageClocks::end() {
  const ClockReading now = readClocks();
  const Open o = open_.back();
  open_.pop_back();
  // The stage's inclusive figures; its parent excludes all of them.
  StageTime d;
  d.wall = now.wall - o.start.wall;
  d.cpu = now.cpu - o.start.cpu;
  d.mpiWall = now.mpi.wall - o.start.mpi.wall;
  d.mpiCpu = now.mpi.cpu - o.start.mpi.cpu;
  d.critical = now.mpi.critical - o.start.mpi.critical;
  for (int k = 0; k < kMpiCallKinds; ++k) {
    d.callWall[k] = now.mpi.callWall[k] - o.start.mpi.callWall[k];
    d.callCount[k] = now.mpi.callCount[k] - o.start.mpi.callCount[k];
  }
  StageTime& s = stages_[o.index];
  s.wall += d.wall - o.inner.wall;
  s.cpu += d.cpu - o.inner.cpu;
  s.mpiWall += d.mpiWall - o.inner.mpiWall;
  s.mpiCpu += d.mpiCpu - o.inner.mpiCpu;
  s.critical += d.critical - o.inner.critical;
  for (int k = 0; k < kMpiCallKinds; ++k) {
    s.callWall[k] += d.callWall[k] - o.inner.callWall[k];
    s.callCount[k] += d.callCount[k] - o.inner.callCount[k];
  }
  s.peakRssMb = now.peakRssMb;
  if (!open_.empty()) {
    StageTime& parent = open_.back().inner;
    parent.wall += d.wall, parent.cpu += d.cpu, parent.mpiWall += d.mpiWall, parent.mpiCpu += d.mpiCpu;
    parent.critical += d.critical;
    for (int k = 0; k < kMpiCallKinds; ++k) parent.callWall[k] += d.callWall[k], parent.callCount[k] += d.callCount[k];
  }
}

}  // namespace gphr
