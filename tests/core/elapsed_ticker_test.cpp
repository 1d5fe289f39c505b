// The elapsed-time progress of work that counts no units (core/elapsed_ticker.h): a heartbeat line at
// each multiple of the bar's 10 s interval while the work runs, and the last line at 100 % when the caller
// finishes the bar. A fake clock, 4 s more at each reading, so the lines do not depend on real time.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "roadbrdf/core/elapsed_ticker.h"

namespace roadbrdf {
namespace {

std::vector<std::string> lines_of(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
  std::vector<std::string> lines;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ElapsedTicker, HeartbeatsWhileTheWorkRunsThenTheEnd) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  std::atomic<int> readings{0};
  {
    ProgressBar bar(
        "lighting", f, ProgressStyle::kHeartbeat, [&readings] { return 4.0 * readings++; }, 2.0);
    {
      const ElapsedTicker ticker(bar, 0.001);
      // The work: until the ticker has read the clock at 4, 8, ..., 28 s (the start read 0 s).
      while (readings.load() < 8) std::this_thread::yield();
    }
    bar.update(1, 1);
    bar.finish();
  }
  const std::vector<std::string> lines = lines_of(f);
  std::fclose(f);
  // The first readings past 10 s and 20 s: 12 s and 20 s; the ticker may have read the clock a few more
  // times before it stopped, each line still 0 of 1.
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[0], "lighting: 0/1 0%  12.0 s");
  EXPECT_EQ(lines[1], "lighting: 0/1 0%  20.0 s");
  for (std::size_t k = 2; k + 1 < lines.size(); ++k) EXPECT_EQ(lines[k].rfind("lighting: 0/1 0%  ", 0), 0u) << lines[k];
  EXPECT_EQ(lines.back().rfind("lighting: 1/1 100%  ", 0), 0u) << lines.back();
}

TEST(ElapsedTicker, ShortWorkWritesNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressBar bar(
        "lighting", f, ProgressStyle::kHeartbeat, [] { return 1.0; }, 2.0);
    { const ElapsedTicker ticker(bar, 0.001); }
    bar.update(1, 1);
    bar.finish();
  }
  EXPECT_TRUE(lines_of(f).empty());
  std::fclose(f);
}

}  // namespace
}  // namespace roadbrdf
