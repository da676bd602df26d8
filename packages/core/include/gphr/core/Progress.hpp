#pragma once
/// @file
/// Progress on stderr without silent minutes: a phase that prints nothing of its own for a while
/// (a reduced run's timed loop, a randomized SVD, a DEIM basis) is wrapped in a ProgressPhase, and
/// while it lasts a watcher thread says "[gphr] LABEL: 12 s so far" whenever nothing was printed
/// for `seconds` (ProgressWatch::configure; the driver passes output.progressSeconds on rank 0).
/// Progress lines of their own go through progressLine(), which restarts the silence, so the
/// watcher speaks only in the gaps. Off until configured: a library caller sees nothing.
///
/// The watcher runs only while a phase is open (started by the outermost ProgressPhase, stopped
/// and joined by its end) and does nothing but format and print a line: it takes no part in the
/// phase's work, so a timed loop's results do not depend on it.
#include <atomic>
#include <cstdarg>
#include <memory>
#include <functional>
#include <string>

namespace gphr {

/// Where the watcher's lines and progressLine() go (stderr unless a test redirects them).
using ProgressSink = std::function<void(const std::string&)>;

/// The process's progress settings (one per process; thread-safe).
class ProgressWatch {
 public:
  /// seconds: the longest silence inside a phase (<= 0: the watcher is off); show: this process
  /// prints (rank 0). sink: where lines go (empty: stderr).
  static void configure(double seconds, bool show, ProgressSink sink = {});
  /// The configured longest silence (0 where off or not shown).
  static double seconds();
};

/// One progress line (printf format, a newline added) to the sink, and the silence restarts. The
/// caller decides whether it shows progress (rank 0, its own options), as for any line on stderr.
void progressLine(const char* format, ...) __attribute__((format(printf, 1, 2)));

/// While it lives, `label` is the innermost open phase (the latest opened of those still open,
/// on any thread): the watcher names it in its lines.
class ProgressPhase {
 public:
  /// total > 0: the phase counts steps (at()), and the watcher's lines say "step j/total" and an
  /// estimate of the time left.
  explicit ProgressPhase(std::string label, long total = 0);
  /// Steps done so far (one relaxed atomic store: cheap enough for a time loop).
  void at(long done);
  ~ProgressPhase();
  ProgressPhase(const ProgressPhase&) = delete;
  ProgressPhase& operator=(const ProgressPhase&) = delete;

 private:
  long id_ = 0;
  std::shared_ptr<std::atomic<long>> done_;  ///< shared with the watcher's record of the phase
};

}  // namespace gphr
