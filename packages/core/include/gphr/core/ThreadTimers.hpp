#pragma once
/// @file
/// Teuchos::TimeMonitor's counters are process-wide and unsynchronized (a registry of named timers
/// and each timer's running state): two threads timing at once race on them. A thread that runs
/// work beside others (gphr query's worker threads) turns them off for itself; the timed code asks
/// processTimersOn() first. The main thread keeps them (`--verbose` tables).
namespace gphr {

bool processTimersOn();  ///< false on a thread inside a WithoutProcessTimers scope

/// While alive, this thread's processTimersOn() is false.
class WithoutProcessTimers {
 public:
  WithoutProcessTimers();
  ~WithoutProcessTimers();
  WithoutProcessTimers(const WithoutProcessTimers&) = delete;
  WithoutProcessTimers& operator=(const WithoutProcessTimers&) = delete;

 private:
  bool before_;
};

}  // namespace gphr
