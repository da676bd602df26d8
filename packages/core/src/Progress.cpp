#include "gphr/core/Progress.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

namespace gphr {

namespace {
using Clock = std::chrono::steady_clock;

// The watcher's state: the open phases (innermost last), the last line's time, the thread.
struct Watch {
  std::mutex mutex;
  std::condition_variable wake;
  double seconds = 0.0;
  bool show = false;
  ProgressSink sink;
  struct Phase {
    long id;
    std::string label;
    Clock::time_point start;
    long total;
    std::shared_ptr<std::atomic<long>> done;
  };
  std::vector<Phase> phases;  // in the order opened; a phase ends wherever it stands (threads)
  long nextId = 0;
  Clock::time_point lastLine = Clock::now();
  std::thread thread;
  bool stop = false;

  void emit(const std::string& line) {  // under the mutex
    if (sink) sink(line);
    else std::fprintf(stderr, "%s\n", line.c_str());
    lastLine = Clock::now();
  }
  // Sleeps until `seconds` after the last line; then names the innermost phase if still silent.
  void run() {
    std::unique_lock<std::mutex> lock(mutex);
    const auto every = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    // The silence counts from the last line or from the innermost phase's start, the later.
    const auto since = [&] { return phases.empty() ? lastLine : std::max(lastLine, phases.back().start); };
    while (!stop) {
      if (wake.wait_until(lock, since() + every, [&] { return stop; })) break;
      if (phases.empty() || Clock::now() - since() < every) continue;
      const Phase& p = phases.back();
      const double in = std::chrono::duration<double>(Clock::now() - p.start).count();
      const long done = p.done->load(std::memory_order_relaxed);
      char tail[128];
      if (p.total > 0 && done > 0)
        std::snprintf(tail, sizeof tail, ": step %ld/%ld, %.0f s so far, ~%.0f s left", done, p.total, in,
                      in / done * (p.total - done));
      else
        std::snprintf(tail, sizeof tail, ": %.0f s so far", in);
      emit("[gphr] " + p.label + tail);
    }
  }
};

Watch& watch() {
  static Watch w;  // never destroyed while a thread runs: the outermost phase joins it
  return w;
}
}  // namespace

void ProgressWatch::configure(double seconds, bool show, ProgressSink sink) {
  Watch& w = watch();
  const std::lock_guard<std::mutex> lock(w.mutex);
  w.seconds = seconds, w.show = show, w.sink = std::move(sink);
}

double ProgressWatch::seconds() {
  Watch& w = watch();
  const std::lock_guard<std::mutex> lock(w.mutex);
  return w.show && w.seconds > 0.0 ? w.seconds : 0.0;
}

void progressLine(const char* format, ...) {
  char buffer[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  Watch& w = watch();
  const std::lock_guard<std::mutex> lock(w.mutex);
  w.emit(buffer);
}

ProgressPhase::ProgressPhase(std::string label, long total) : done_(std::make_shared<std::atomic<long>>(0)) {
  Watch& w = watch();
  const std::lock_guard<std::mutex> lock(w.mutex);
  id_ = w.nextId++;
  w.phases.push_back({id_, std::move(label), Clock::now(), total, done_});
  if (w.phases.size() == 1 && w.show && w.seconds > 0.0) {
    w.stop = false;
    w.thread = std::thread([&w] { w.run(); });
  }
}

void ProgressPhase::at(long done) { done_->store(done, std::memory_order_relaxed); }

ProgressPhase::~ProgressPhase() {
  Watch& w = watch();
  std::thread done;
  {
    const std::lock_guard<std::mutex> lock(w.mutex);
    for (auto p = w.phases.begin(); p != w.phases.end(); ++p)
      if (p->id == id_) {
        w.phases.erase(p);
        break;
      }
    if (!w.phases.empty() || !w.thread.joinable()) return;
    w.stop = true;
    done = std::move(w.thread);
  }
  w.wake.notify_all();
  done.join();
}

}  // namespace gphr
