// A progress bar with an estimate of the time left, for long work (fits over many wavelengths,
// multistart...). Drawn on a stream only when enabled: the command line enables it for standard
// error when that is a terminal and --quiet is not given (terminal_enabled), so that logs and pipes
// get nothing but the usual summary. The clock is injectable for tests.
//
// Line: "LABEL [########............] 12/40  30%  2.1 s, ~4.9 s left", redrawn with '\r' at most
// every `min_interval` seconds (and at 100 %), first drawn after `delay` seconds (short work shows
// no bar); finish() ends the line.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>

namespace roadbrdf {

class ProgressBar {
 public:
  using Clock = std::function<double()>;  // seconds, monotonic

  ProgressBar(std::string label, std::FILE* out, bool enabled, Clock clock = {}, double delay = 1.0,
              double min_interval = 0.1);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Whether a bar on standard error should be drawn: it is a terminal and not `quiet`.
  static bool terminal_enabled(bool quiet);

  void update(std::size_t done, std::size_t total);
  void finish();
  bool enabled() const { return enabled_; }
  bool shown() const { return shown_; }

  // The line for a state (no '\r'), e.g. for tests: elapsed and estimated seconds left
  // (elapsed * (total - done) / done; unknown while done = 0).
  static std::string line(const std::string& label, std::size_t done, std::size_t total, double elapsed);

 private:
  std::string label_;
  std::FILE* out_;
  bool enabled_;
  Clock clock_;
  double delay_, min_interval_;
  double start_ = 0.0, last_draw_ = -1.0;
  bool shown_ = false, finished_ = false;
};

}  // namespace roadbrdf
