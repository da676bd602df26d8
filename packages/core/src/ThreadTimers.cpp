#include "gphr/core/ThreadTimers.hpp"

namespace gphr {

namespace {
thread_local bool timersOn = true;
}  // namespace

bool processTimersOn() { return timersOn; }

WithoutProcessTimers::WithoutProcessTimers() : before_(timersOn) { timersOn = false; }

WithoutProcessTimers::~WithoutProcessTimers() { timersOn = before_; }

}  // namespace gphr
