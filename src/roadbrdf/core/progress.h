// Progress of long work (fits over many wavelengths, multistart...) on a stream, in one of three
// styles (ProgressStyle): the command line picks it for standard error with stderr_style: a bar
// redrawn in place on a terminal; on a log or a pipe, where a redrawn line would be garbage, one
// plain "heartbeat" line every `heartbeat_interval` seconds (10 s), so that a script never waits in
// silence; nothing with --quiet. The clock is injectable for tests.
//
// Bar: "LABEL [########............] 12/40  30%  2.1 s, ~4.9 s left", redrawn with '\r' at most
// every `min_interval` seconds (and at 100 %), first drawn after `delay` seconds (short work shows
// no bar); finish() ends the line.
// Heartbeat: "LABEL: 12/40 30%  10.0 s, ~23.3 s left" and a newline, at the first update of unfinished
// work after each multiple of `heartbeat_interval` seconds; when at least one was written, finish()
// writes the last count and the time the same way. Work shorter than the interval writes nothing.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>

namespace roadbrdf {

// Stopping long work early. A front end that must stay responsive to Ctrl-C while the library works
// (Python: the interpreter only sees a signal between its own instructions) sets the request, e.g.
// from a signal handler: request_interrupt() only stores an atomic flag, so it is async-signal-safe.
// The long loops poll it where they report progress (ProgressCounter::add, the fit's multi-start and
// iteration loops) with throw_if_interrupted(), from any thread: Interrupted unwinds the work like
// any error (every buffer freed, no output written, TBB cancels the other tasks). The command line
// never sets it: SIGINT ends the process there, and AtomicFile removes its temporary file.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};
void request_interrupt() noexcept;
void clear_interrupt() noexcept;
bool interrupt_requested() noexcept;
// Throws Interrupted when an interrupt was requested (a relaxed atomic load otherwise).
void throw_if_interrupted();

// How the library's long loops report progress (FitOptions, MixRequest, GeneratorSettings,
// RenderSettings, AlbedoRequest): done and total units of work; `done` never decreases within one
// piece of work and ends at total. An empty callback costs nothing. The front ends connect it to a
// ProgressBar (command line) or leave it empty (Python).
using ProgressCallback = std::function<void(std::size_t done, std::size_t total)>;

// Counts units of work done by any number of threads and forwards the count to a callback from one
// thread at a time: a worker that finds the callback busy skips the report instead of waiting, so
// the callback (e.g. a ProgressBar, which is not thread-safe) never slows the work down. Every add()
// polls the interrupt request first (throw_if_interrupted), with or without a callback.
class ProgressCounter {
 public:
  ProgressCounter(const ProgressCallback& callback, std::size_t total) : callback_(callback), total_(total) {}
  ProgressCounter(const ProgressCounter&) = delete;
  ProgressCounter& operator=(const ProgressCounter&) = delete;

  void add(std::size_t units = 1);
  // Work that became known on the way (adaptive rounds): the total grows.
  void add_total(std::size_t units);
  // Reports total/total once (waiting for a report in progress).
  void finish();

 private:
  const ProgressCallback& callback_;
  std::atomic<std::size_t> done_{0}, total_;
  std::mutex report_;
  bool finished_ = false;
};

enum class ProgressStyle { kOff, kBar, kHeartbeat };

class ProgressBar {
 public:
  using Clock = std::function<double()>;  // seconds, monotonic

  ProgressBar(std::string label, std::FILE* out, ProgressStyle style, Clock clock = {}, double delay = 1.0,
              double min_interval = 0.1, double heartbeat_interval = 10.0);
  // `enabled`: ProgressStyle::kBar, else kOff.
  ProgressBar(std::string label, std::FILE* out, bool enabled, Clock clock = {}, double delay = 1.0,
              double min_interval = 0.1);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // The style for standard error: off when `quiet`, a bar on a terminal, heartbeat lines otherwise.
  static ProgressStyle stderr_style(bool quiet);

  void update(std::size_t done, std::size_t total);
  void finish();
  // update() as a ProgressCallback for the library; the bar must outlive the work.
  ProgressCallback callback() {
    return [this](std::size_t done, std::size_t total) { update(done, total); };
  }
  bool enabled() const { return style_ != ProgressStyle::kOff; }
  bool shown() const { return shown_; }

  // The bar's line for a state (no '\r'), e.g. for tests: elapsed and estimated seconds left
  // (elapsed * (total - done) / done; unknown while done = 0).
  static std::string line(const std::string& label, std::size_t done, std::size_t total, double elapsed);
  // The heartbeat's line for a state (no newline).
  static std::string heartbeat_line(const std::string& label, std::size_t done, std::size_t total, double elapsed);

 private:
  std::string label_;
  std::FILE* out_;
  ProgressStyle style_;
  Clock clock_;
  double delay_, min_interval_, heartbeat_interval_;
  double start_ = 0.0, last_draw_ = -1.0, next_heartbeat_ = 0.0;
  std::size_t last_done_ = 0, last_total_ = 0;
  bool shown_ = false, finished_ = false;
};

}  // namespace roadbrdf
