#pragma once
/// @file
/// Per-stage clocks of the offline phase (doc/scaling.md): wall seconds, CPU seconds of the
/// process, seconds inside MPI calls (wall and CPU) and the peak resident memory, on each rank.
/// Each stage's compute time per rank is wanted with waits excluded: oversubscribed ranks
/// spin inside MPI, so wall time and even CPU time count the waits. "Compute seconds" is therefore
/// the process's CPU seconds minus the CPU seconds spent inside MPI calls.
///
/// Time inside MPI is counted by a PMPI interposer that only the `gphr` executable links
/// (packages/driver/src/MpiTimeInterposer.cpp): it registers its counters with
/// setMpiTimeSource(). Libraries only read them; without the interposer mpiTimeAvailable() is false
/// and the MPI columns read 0, so no library depends on it.
#include <array>
#include <string>
#include <vector>

#include "gphr/core/Progress.hpp"

namespace gphr {

/// The most MPI functions the interposer may time one by one (it has a kind per function it wraps).
constexpr int kMpiCallKinds = 64;

/// Accumulated time inside MPI calls of this process (outermost calls only).
struct MpiTime {
  double wall = 0.0;    ///< wall seconds
  double cpu = 0.0;     ///< CPU seconds of the calling threads
  long long calls = 0;  ///< calls counted
  /// The same wall seconds and calls per MPI function (index: the function's kind, mpiCallName);
  /// they add up to `wall` and `calls`, so a stage's MPI time can be told apart (a wait in a
  /// receive, a collective write, a broadcast). Empty kinds stay 0.
  /// @{
  std::array<double, kMpiCallKinds> callWall{};
  std::array<long long, kMpiCallKinds> callCount{};
  /// @}
  /// The compute critical path so far, seconds (0 unless criticalPathMeasured()): the calling
  /// thread's CPU seconds outside MPI, raised at every collective call to the largest value among
  /// the communicator's ranks. On ranks that share cores it estimates the wall seconds the run
  /// would take with a core per rank and waits only for work (doc/scaling.md, "Critical path").
  double critical = 0.0;
};

/// Whether the interposer measures MpiTime::critical. Each collective call then makes one extra
/// MPI_Allreduce of 8 bytes, so the switch must be the same on every rank at every collective:
/// the interposer sets it before main() from GPHR_CRITICAL_PATH=1 in the environment.
bool criticalPathMeasured();

/// Switches MpiTime::critical on or off (on every rank alike, between collectives).
void setCriticalPathMeasured(bool on);

/// Reads the interposer's counters; thread-safe.
using MpiTimeSource = MpiTime (*)();

/// Registers the interposer's counters (its static initializer calls this once).
void setMpiTimeSource(MpiTimeSource source);

/// Whether an interposer registered: false means the MPI columns are not measured (0).
bool mpiTimeAvailable();

/// Registers the names of the interposer's kinds: names[kind], "MPI_Recv" etc., nullptr where unused
/// (an array of kMpiCallKinds that lives as long as the process).
void setMpiCallNames(const char* const* names);

/// The MPI function timed as `kind` (0 <= kind < kMpiCallKinds), or nullptr (no such kind, or no interposer).
const char* mpiCallName(int kind);

/// The counters now (all 0 without an interposer).
MpiTime mpiTimeNow();

/// One reading of every clock.
struct ClockReading {
  double wall = 0.0;     ///< steady clock, seconds
  double cpu = 0.0;      ///< CLOCK_PROCESS_CPUTIME_ID, seconds (all threads of the process)
  MpiTime mpi;           ///< mpiTimeNow()
  double peakRssMb = 0;  ///< getrusage ru_maxrss of the process, MB (a high-water mark)
};

/// Reads every clock.
ClockReading readClocks();

/// What one stage cost on this rank. Exclusive of the stages timed inside it.
struct StageTime {
  std::string name;        ///< the stage, e.g. "training", "deim basis k=80"
  double wall = 0.0;       ///< wall seconds
  double cpu = 0.0;        ///< CPU seconds of the process
  double mpiWall = 0.0;    ///< wall seconds inside MPI calls
  double mpiCpu = 0.0;     ///< CPU seconds inside MPI calls
  double peakRssMb = 0.0;  ///< peak resident memory of the process at the stage's end, MB
  /// mpiWall and the calls per MPI function (MpiTime::callWall, callCount)
  /// @{
  std::array<double, kMpiCallKinds> callWall{};
  std::array<long long, kMpiCallKinds> callCount{};
  /// @}
  double critical = 0.0;  ///< the stage's share of the compute critical path (MpiTime::critical), s
  /// CPU seconds outside MPI calls: the stage's own work, waits excluded.
  double compute() const { return cpu - mpiCpu; }
};

/// Named stages of one computation, in the order they were first started. A stage started inside
/// another is charged to itself only: the outer stage's figures exclude it (so the stages add up
/// to the whole), and its peak memory is read at its own end. A stage started twice under one
/// name accumulates. Single-threaded: one StageClocks per thread of work.
class StageClocks {
 public:
  /// Times a stage while alive.
  class Scope {
   public:
    /// Starts stage `name` of `clocks`; the destructor ends it. While it runs, the stage is the
    /// innermost progress phase (core/Progress.hpp).
    Scope(StageClocks& clocks, std::string name);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StageClocks& clocks_;
    ProgressPhase phase_;  ///< a stage is a progress phase too: a long one is named on stderr
  };

  /// The stages timed so far.
  const std::vector<StageTime>& stages() const { return stages_; }

 private:
  struct Open {
    size_t index;        // into stages_
    ClockReading start;  // at its start
    StageTime inner;     // what its inner stages took (subtracted at its end)
  };
  void begin(std::string name);
  void end();
  std::vector<StageTime> stages_;
  std::vector<Open> open_;
};

}  // namespace gphr
