// Progress of work that counts no units of its own (a road-lighting calculation): while an
// ElapsedTicker lives, a thread updates a ProgressBar (core/progress.h) with 0 of 1 unit every `period`
// seconds, so that the bar shows the elapsed time: drawn after the bar's delay on a terminal, a heartbeat
// line every interval in a log. The destructor stops and joins the thread; only then may the caller use
// the bar again (update(1, 1), finish()), the bar not being thread-safe.
#pragma once

#include <condition_variable>
#include <mutex>
#include <thread>

#include "roadbrdf/core/progress.h"

namespace roadbrdf {

class ElapsedTicker {
 public:
  explicit ElapsedTicker(ProgressBar& bar, double period = 0.25);
  ~ElapsedTicker();
  ElapsedTicker(const ElapsedTicker&) = delete;
  ElapsedTicker& operator=(const ElapsedTicker&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace roadbrdf
