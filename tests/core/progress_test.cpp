// The progress bar (core/progress.h): drawn only when enabled, after its delay, at most every
// min_interval, always at 100 %; the time left is elapsed * remaining / done. A fake clock, no timing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "roadbrdf/core/progress.h"

namespace roadbrdf {
namespace {

std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
  return s;
}

TEST(Progress, LineShowsShareAndTimeLeft) {
  EXPECT_EQ(ProgressBar::line("fit", 10, 40, 3.0), "fit [######..................] 10/40 25%  3.0 s, ~9.0 s left");
  EXPECT_EQ(ProgressBar::line("fit", 0, 4, 0.5), "fit [........................] 0/4 0%  0.5 s");
  EXPECT_EQ(ProgressBar::line("fit", 4, 4, 125.0), "fit [########################] 4/4 100%  2 min 05 s");
  EXPECT_EQ(ProgressBar::line("x", 1, 2, 4000.0), "x [############............] 1/2 50%  1 h 06 min, ~1 h 06 min left");
}

TEST(Progress, DrawsAfterTheDelayThrottledAndEndsTheLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  double now = 100.0;
  {
    ProgressBar bar(
        "work", f, true, [&now] { return now; }, 1.0, 0.5);
    bar.update(1, 10);  // before the delay: nothing
    EXPECT_FALSE(bar.shown());
    now = 101.0;
    bar.update(2, 10);  // drawn
    now = 101.2;
    bar.update(3, 10);  // throttled
    now = 101.6;
    bar.update(4, 10);   // drawn
    bar.update(10, 10);  // 100 %: always drawn
    EXPECT_TRUE(bar.shown());
  }
  const std::string out = contents(f);
  std::fclose(f);
  EXPECT_EQ(out,
            "\rwork [####....................] 2/10 20%  1.0 s, ~4.0 s left\x1b[K"
            "\rwork [#########...............] 4/10 40%  1.6 s, ~2.4 s left\x1b[K"
            "\rwork [########################] 10/10 100%  1.6 s\x1b[K\n");
}

TEST(Progress, DisabledOrShortWorkWritesNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  double now = 0.0;
  {
    ProgressBar off("work", f, false, [&now] { return now; });
    now = 10.0;
    off.update(5, 10);
    ProgressBar quick("work", f, true, [&now] { return now; });
    now = 10.5;
    quick.update(10, 10);  // done within the delay: never shown, no newline either
    EXPECT_FALSE(quick.shown());
  }
  EXPECT_EQ(contents(f), "");
  std::fclose(f);
  EXPECT_EQ(ProgressBar::stderr_style(true), ProgressStyle::kOff);  // --quiet: never, whatever the stream
}

// On a log (not a terminal): one plain line at the first update after each multiple of the interval
// (here 10 s of a fake clock), none before, and the final count when the work ends.
TEST(Progress, HeartbeatWritesOneLineEveryIntervalAndTheEnd) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  double now = 0.0;
  {
    ProgressBar log(
        "fit hapke", f, ProgressStyle::kHeartbeat, [&now] { return now; }, 1.0, 0.1, 10.0);
    now = 9.9;
    log.update(3, 40);  // before the first interval: nothing
    EXPECT_FALSE(log.shown());
    now = 10.0;
    log.update(4, 40);  // written
    now = 19.0;
    log.update(10, 40);  // within the second interval: nothing
    now = 35.0;
    log.update(20, 40);  // late: written once, the next at 40 s
    now = 39.0;
    log.update(30, 40);
    now = 41.0;
    log.update(40, 40);  // done: left to finish()
    now = 41.5;
  }
  const std::string out = contents(f);
  std::fclose(f);
  EXPECT_EQ(out,
            "fit hapke: 4/40 10%  10.0 s, ~1 min 30 s left\n"
            "fit hapke: 20/40 50%  35.0 s, ~35.0 s left\n"
            "fit hapke: 40/40 100%  41.5 s\n");
}

TEST(Progress, HeartbeatOfShortWorkWritesNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  double now = 0.0;
  {
    ProgressBar log(
        "mix", f, ProgressStyle::kHeartbeat, [&now] { return now; }, 1.0, 0.1, 10.0);
    now = 5.0;
    log.update(1, 2);
    now = 9.0;
    log.update(2, 2);
  }
  EXPECT_EQ(contents(f), "");
  std::fclose(f);
}

}  // namespace
}  // namespace roadbrdf

namespace roadbrdf {
namespace {

TEST(ProgressCounter, ManyThreadsReportAMonotoneCountEndingAtTheTotal) {
  std::vector<std::size_t> seen;
  std::size_t last_total = 0;
  const ProgressCallback callback = [&](std::size_t done, std::size_t total) {
    seen.push_back(done);  // never called by two threads at once (the counter's lock)
    last_total = total;
  };
  constexpr std::size_t kUnits = 4000;
  {
    ProgressCounter counter(callback, kUnits);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) {
      threads.emplace_back([&] {
        for (std::size_t k = 0; k < kUnits / 4; ++k) counter.add();
      });
    }
    for (auto& t : threads) t.join();
    counter.finish();
    counter.finish();  // once only
  }
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), kUnits);
  EXPECT_LE(std::count(seen.begin(), seen.end(), kUnits), 2);  // the last add and finish, once
  EXPECT_EQ(last_total, kUnits);
}

TEST(ProgressCounter, GrowingTotalAndEmptyCallback) {
  std::vector<std::pair<std::size_t, std::size_t>> seen;
  const ProgressCallback callback = [&](std::size_t d, std::size_t t) { seen.emplace_back(d, t); };
  ProgressCounter counter(callback, 2);
  counter.add(2);
  counter.add_total(3);
  counter.add(3);
  counter.finish();
  const std::vector<std::pair<std::size_t, std::size_t>> expected = {{2, 2}, {5, 5}, {5, 5}};
  EXPECT_EQ(seen, expected);
  const ProgressCallback none;
  ProgressCounter quiet(none, 1);
  quiet.add();
  quiet.finish();  // nothing to call: no crash
}

// An interrupt request (core/progress.h) stops work that reports progress, from every thread, with or
// without a callback, and nothing before it is requested.
TEST(ProgressCounter, AnInterruptRequestStopsEveryThreadAtItsNextReport) {
  clear_interrupt();
  const ProgressCallback none;
  ProgressCounter counter(none, 1000);
  counter.add(10);  // no request: goes on
  EXPECT_FALSE(interrupt_requested());
  request_interrupt();
  std::vector<int> stopped(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      try {
        for (int k = 0; k < 100; ++k) counter.add();
      } catch (const Interrupted&) {
        stopped[static_cast<std::size_t>(t)] = 1;
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(stopped, std::vector<int>(4, 1));
  EXPECT_THROW(throw_if_interrupted(), Interrupted);
  clear_interrupt();
  EXPECT_NO_THROW(throw_if_interrupted());
  EXPECT_NO_THROW(counter.add());
}

}  // namespace
}  // namespace roadbrdf
