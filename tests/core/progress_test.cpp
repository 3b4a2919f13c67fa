// Progress bar: the line it draws, the lines it hands a caller's log, counting from many threads,
// and silence off a terminal.
#include "motiongraph/core/progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace mg {
namespace {

TEST(Progress, LineHasLabelBarPercentCountsElapsedAndEta) {
  // 4 + 2 + 21 (bar) + 2 + 21 (stats) = 50 columns.
  EXPECT_EQ(format_progress_line("dist", 4, 10, 2.0, 50), "dist [########.............]  40% 4/10 2.0s eta 3s");
  // Nothing done yet: no estimate, so a longer bar.
  EXPECT_EQ(format_progress_line("dist", 0, 10, 0.0, 50), "dist [............................]   0% 0/10 0.0s");
  EXPECT_EQ(format_progress_line("dist", 10, 10, 12.34, 40), "dist [################] 100% 10/10 12.3s");
}

TEST(Progress, FinalLineHasNoEstimate) {
  EXPECT_EQ(format_progress_line("graph", 3, 4, 1.5, 40, true), "graph [#############.....]  75% 3/4 1.5s");
}

TEST(Progress, EveryLineFitsTheWidth) {
  for (int width = 0; width <= 120; ++width) {
    for (const std::uint64_t done : {0ull, 1ull, 999ull, 123456789ull}) {
      const std::string line = format_progress_line("a rather long stage label", done, 123456789, 3600.5, width);
      EXPECT_LE(line.size(), static_cast<size_t>(width));
      EXPECT_EQ(line.find('\n'), std::string::npos);
      EXPECT_EQ(line.find('\r'), std::string::npos);
    }
  }
  // Narrow: no bar, the numbers stay.
  EXPECT_EQ(format_progress_line("dist", 5, 10, 1.0, 30), "dist  50% 5/10 1.0s eta 1s");
}

TEST(Progress, UnknownTotalAndOvershoot) {
  EXPECT_EQ(format_progress_line("search", 7, 0, 1.25, 60), "search 7 1.2s");
  EXPECT_EQ(format_progress_line("x", 15, 10, 1.0, 20), "x 100% 10/10 1.0s");
}

TEST(Progress, TextForALog) {
  EXPECT_EQ(progress_text("distance", 4, 10, 2.0), "distance: 40 % (4 of 10) in 2.0 s, about 3 s left");
  EXPECT_EQ(progress_text("distance", 0, 10, 0.5), "distance: 0 % (0 of 10) in 0.5 s");
  EXPECT_EQ(progress_text("reading", 7, 0, 1.5), "reading: 7 in 1.5 s");
  EXPECT_EQ(progress_text("x", 15, 10, 1.0), "x: 100 % (10 of 10) in 1.0 s");
}

TEST(Progress, HandsItsCallerALineEveryTwoSeconds) {
  std::vector<std::string> lines;
  ProgressBar bar("stage", 10, /*quiet=*/true, [&lines](const std::string& line) { lines.push_back(line); });
  bar.advance();
  EXPECT_TRUE(lines.empty());  // not 2 s yet
  std::this_thread::sleep_for(std::chrono::milliseconds(2100));
  bar.advance();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].rfind("stage: 20 % (2 of 10) in 2.", 0), 0u) << lines[0];
  bar.advance();
  EXPECT_EQ(lines.size(), 1u);  // the next not before 2 s more
}

TEST(Progress, CountsAdvancesFromManyThreads) {
  ProgressBar bar("count", 40000, /*quiet=*/true);
  EXPECT_FALSE(bar.drawing());
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&bar] {
      for (int i = 0; i < 10000; ++i) bar.advance();
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(bar.done(), 40000u);
  EXPECT_EQ(bar.total(), 40000u);
  bar.advance(5);
  EXPECT_EQ(bar.done(), 40005u);
  bar.finish();
  bar.finish();
}

TEST(Progress, PrintsNothingWhenStderrIsNotATerminal) {
  testing::internal::CaptureStderr();  // stderr becomes a file
  {
    ProgressBar bar("silent", 10);
    EXPECT_FALSE(bar.drawing());
    for (int i = 0; i < 10; ++i) bar.advance();
    bar.finish();
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace mg
