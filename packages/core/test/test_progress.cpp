// The progress watcher (core/Progress.hpp): a phase silent for longer than the configured seconds
// gets lines naming it, the innermost phase is named, a progress line of the phase's own restarts
// the silence, nothing is said once the phases end, and nothing at all where it is off.
// Tolerances: the watcher wakes `seconds` after the last line, so a phase of P seconds silent
// throughout gets about P / seconds lines; the checks ask for at least one (or none) with the
// phase at least 5x (or at most a tenth of) the interval, so a loaded machine's late wake-ups of
// a few tens of milliseconds do not decide them.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "gphr/core/Progress.hpp"

namespace gphr {
namespace {

struct Lines {
  std::mutex mutex;
  std::vector<std::string> all;
  ProgressSink sink() {
    return [this](const std::string& s) {
      const std::lock_guard<std::mutex> lock(mutex);
      all.push_back(s);
    };
  }
  int naming(const std::string& label) {
    const std::lock_guard<std::mutex> lock(mutex);
    int n = 0;
    for (const auto& s : all) n += s.rfind("[gphr] " + label + ": ", 0) == 0 && s.find(" s so far") != std::string::npos;
    return n;
  }
};

void sleepFor(double seconds) { std::this_thread::sleep_for(std::chrono::duration<double>(seconds)); }

TEST(ProgressWatch, ASilentPhaseIsNamedAndTheInnermostOneWins) {
  Lines lines;
  ProgressWatch::configure(0.1, true, lines.sink());
  {
    ProgressPhase outer("outer phase");
    sleepFor(0.6);
    {
      ProgressPhase inner("inner phase");
      sleepFor(0.6);
    }
  }
  const size_t atEnd = lines.all.size();
  sleepFor(0.3);  // no phase open: nothing more
  ProgressWatch::configure(0.0, false);
  EXPECT_GE(lines.naming("outer phase"), 1);
  EXPECT_GE(lines.naming("inner phase"), 1);
  EXPECT_EQ(lines.all.size(), atEnd);
  for (const auto& s : lines.all) EXPECT_TRUE(s.rfind("[gphr] outer phase: ", 0) == 0 || s.rfind("[gphr] inner phase: ", 0) == 0) << s;
}

TEST(ProgressWatch, ACountedPhaseSaysItsStepAndTheTimeLeft) {
  Lines lines;
  ProgressWatch::configure(0.1, true, lines.sink());
  {
    ProgressPhase phase("counted phase", 400);
    phase.at(100);  // a quarter done: the estimate left is three times the time so far
    sleepFor(0.6);
  }
  ProgressWatch::configure(0.0, false);
  ASSERT_GE(lines.naming("counted phase"), 1);
  const std::string& line = lines.all.back();
  EXPECT_EQ(line.rfind("[gphr] counted phase: step 100/400, ", 0), 0u) << line;
  double soFar = 0, left = 0;
  ASSERT_EQ(std::sscanf(line.c_str(), "[gphr] counted phase: step 100/400, %lf s so far, ~%lf s left", &soFar, &left), 2)
      << line;
  EXPECT_NEAR(left, 3.0 * soFar, 1.0);  // both printed rounded to whole seconds
}

TEST(ProgressWatch, OwnLinesRestartTheSilence) {
  Lines lines;
  ProgressWatch::configure(0.5, true, lines.sink());
  {
    ProgressPhase phase("talkative phase");
    for (int i = 0; i < 100; ++i) {  // 1 s, a line every 10 ms
      progressLine("[gphr] step %d", i);
      sleepFor(0.01);
    }
  }
  ProgressWatch::configure(0.0, false);
  EXPECT_EQ(lines.all.size() - lines.naming("talkative phase"), 100u);
  EXPECT_LE(lines.naming("talkative phase"), 1);  // a stall of 0.5 s between two 10 ms sleeps, at most once
  EXPECT_EQ(lines.all.front(), "[gphr] step 0");
}

TEST(ProgressWatch, ShortPhasesAndAWatcherOffSayNothing) {
  Lines lines;
  ProgressWatch::configure(2.0, true, lines.sink());
  { ProgressPhase phase("short phase"); sleepFor(0.05); }
  ProgressWatch::configure(0.05, false, lines.sink());  // another rank: not shown
  { ProgressPhase phase("rank 1 phase"); sleepFor(0.5); }
  ProgressWatch::configure(0.0, true, lines.sink());  // progressSeconds 0
  { ProgressPhase phase("unwatched phase"); sleepFor(0.3); }
  ProgressWatch::configure(0.0, false);
  EXPECT_TRUE(lines.all.empty()) << lines.all.front();
  EXPECT_EQ(ProgressWatch::seconds(), 0.0);
}

}  // namespace
}  // namespace gphr
