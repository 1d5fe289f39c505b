#include "roadbrdf/core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace roadbrdf {

namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string seconds_text(double s) {
  char buffer[32];
  if (s < 60.0) {
    std::snprintf(buffer, sizeof buffer, "%.1f s", s);
  } else if (s < 3600.0) {
    std::snprintf(buffer, sizeof buffer, "%d min %02d s", static_cast<int>(s / 60.0),
                  static_cast<int>(std::fmod(s, 60.0)));
  } else {
    std::snprintf(buffer, sizeof buffer, "%d h %02d min", static_cast<int>(s / 3600.0),
                  static_cast<int>(std::fmod(s, 3600.0) / 60.0));
  }
  return buffer;
}

// "12/40 30%  2.1 s, ~4.9 s left" (done <= total); the time left while 0 < done < total.
std::string count_and_time(std::size_t done, std::size_t total, double elapsed) {
  const double share = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  std::string text = std::to_string(done) + "/" + std::to_string(total) + " " +
                     std::to_string(static_cast<int>(std::floor(100.0 * share))) + "%  " + seconds_text(elapsed);
  if (done > 0 && done < total) {
    const double left = elapsed * static_cast<double>(total - done) / static_cast<double>(done);
    text += ", ~" + seconds_text(left) + " left";
  }
  return text;
}

// Lock-free, so that a signal handler may set it.
std::atomic<bool> interrupt_flag{false};
static_assert(std::atomic<bool>::is_always_lock_free);

}  // namespace

void request_interrupt() noexcept { interrupt_flag.store(true, std::memory_order_relaxed); }
void clear_interrupt() noexcept { interrupt_flag.store(false, std::memory_order_relaxed); }
bool interrupt_requested() noexcept { return interrupt_flag.load(std::memory_order_relaxed); }
void throw_if_interrupted() {
  if (interrupt_requested()) throw Interrupted();
}

ProgressBar::ProgressBar(std::string label, std::FILE* out, ProgressStyle style, Clock clock, double delay,
                         double min_interval, double heartbeat_interval)
    : label_(std::move(label)),
      out_(out),
      style_(out != nullptr ? style : ProgressStyle::kOff),
      clock_(clock ? std::move(clock) : Clock(steady_seconds)),
      delay_(delay),
      min_interval_(min_interval),
      heartbeat_interval_(heartbeat_interval) {
  start_ = clock_();
  next_heartbeat_ = heartbeat_interval_;
}

ProgressBar::ProgressBar(std::string label, std::FILE* out, bool enabled, Clock clock, double delay,
                         double min_interval)
    : ProgressBar(std::move(label), out, enabled ? ProgressStyle::kBar : ProgressStyle::kOff, std::move(clock), delay,
                  min_interval) {}

ProgressBar::~ProgressBar() { finish(); }

ProgressStyle ProgressBar::stderr_style(bool quiet) {
  if (quiet) return ProgressStyle::kOff;
  return isatty(fileno(stderr)) != 0 ? ProgressStyle::kBar : ProgressStyle::kHeartbeat;
}

std::string ProgressBar::line(const std::string& label, std::size_t done, std::size_t total, double elapsed) {
  constexpr std::size_t kWidth = 24;
  done = std::min(done, total);
  const double share = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const auto filled = static_cast<std::size_t>(share * static_cast<double>(kWidth));
  std::string bar(filled, '#');
  bar.resize(kWidth, '.');
  return label + " [" + bar + "] " + count_and_time(done, total, elapsed);
}

std::string ProgressBar::heartbeat_line(const std::string& label, std::size_t done, std::size_t total, double elapsed) {
  return label + ": " + count_and_time(std::min(done, total), total, elapsed);
}

void ProgressBar::update(std::size_t done, std::size_t total) {
  if (style_ == ProgressStyle::kOff || finished_) return;
  const double now = clock_();
  const double elapsed = now - start_;
  last_done_ = done;
  last_total_ = total;
  if (style_ == ProgressStyle::kHeartbeat) {
    if (done >= total || elapsed < next_heartbeat_) return;  // the end is finish()'s line
    // The next line at the next multiple of the interval, however late this update came.
    next_heartbeat_ = heartbeat_interval_ * (std::floor(elapsed / heartbeat_interval_) + 1.0);
    shown_ = true;
    std::fprintf(out_, "%s\n", heartbeat_line(label_, done, total, elapsed).c_str());
    std::fflush(out_);
    return;
  }
  if (elapsed < delay_) return;
  if (shown_ && done < total && now - last_draw_ < min_interval_) return;
  last_draw_ = now;
  shown_ = true;
  std::fprintf(out_, "\r%s\x1b[K", line(label_, done, total, elapsed).c_str());  // erase the rest of the line
  std::fflush(out_);
}

void ProgressBar::finish() {
  if (finished_) return;
  finished_ = true;
  if (!shown_) return;
  if (style_ == ProgressStyle::kHeartbeat) {
    std::fprintf(out_, "%s\n", heartbeat_line(label_, last_done_, last_total_, clock_() - start_).c_str());
  } else {
    std::fputc('\n', out_);
  }
  std::fflush(out_);
}

void ProgressCounter::add(std::size_t units) {
  throw_if_interrupted();
  done_ += units;
  if (!callback_ || !report_.try_lock()) return;
  const std::lock_guard<std::mutex> lock(report_, std::adopt_lock);
  // Read under the lock, so that the reported count never decreases.
  const std::size_t total = total_.load();
  if (!finished_) callback_(std::min(done_.load(), total), total);
}

void ProgressCounter::add_total(std::size_t units) { total_ += units; }

void ProgressCounter::finish() {
  const std::lock_guard<std::mutex> lock(report_);
  if (finished_) return;
  finished_ = true;
  if (callback_) callback_(total_.load(), total_.load());
}

}  // namespace roadbrdf
