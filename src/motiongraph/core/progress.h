// A progress bar on stderr for long stages (distances, graph pruning, search):
//   "distances [#########...........]  45% 4500/10000 12.3s eta 15s"
// It draws only when stderr is a terminal and the bar is not quiet, at most ten times a
// second, on one line rewritten with '\r'; finish() ends that line with the elapsed seconds.
// Elsewhere (a pipe, a log file, CI) it prints nothing at all. Given `lines` (a caller's log: a
// notebook, a GUI), it also hands them a line of text every kProgressLineSeconds, terminal or
// not (progress_text), from the thread that advanced it, never two at once. advance() may be
// called from any number of threads: the count is an atomic, and one thread at a time redraws.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>

namespace mg {

// One line of the bar, at most `width` characters (no '\r', no '\n'): the label, a bar when
// there is room, the percentage, done/total, the elapsed seconds and, while running, an
// estimate of the time left (not on a `final_line`). total 0 means unknown: no bar, no
// percentage. done > total reads as complete.
std::string format_progress_line(std::string_view label, std::uint64_t done, std::uint64_t total,
                                 double elapsed_s, int width, bool final_line = false);

// The same as a sentence, for a log: "distance: 45 % (4500 of 10000) in 12.3 s, about 15 s left";
// total 0 means unknown: "reading: 4500 in 12.3 s".
std::string progress_text(std::string_view label, std::uint64_t done, std::uint64_t total, double elapsed_s);

using ProgressLines = std::function<void(const std::string&)>;
constexpr double kProgressLineSeconds = 2.0;

// The clock of a stage made of steps that tells its caller how far it got (a log's lines, as a
// bar's `lines`): due() is true at most once every kProgressLineSeconds, elapsed_s() counts from
// when it was made. One thread's: the caller's steps come one after another.
class ProgressLineClock {
 public:
  bool due() {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::duration<double>(kProgressLineSeconds)) return false;
    last_ = now;
    return true;
  }
  double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_ = start_;
};

class ProgressBar {
 public:
  ProgressBar(std::string label, std::uint64_t total, bool quiet = false, ProgressLines lines = {});
  ~ProgressBar();  // finish()es the line if still drawing
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Counts n more units done; redraws when drawing and the last redraw is 100 ms old.
  void advance(std::uint64_t n = 1);
  // Draws the final line with the elapsed seconds and a newline (once; later calls do nothing).
  void finish();

  std::uint64_t done() const { return done_.load(std::memory_order_relaxed); }
  std::uint64_t total() const { return total_; }
  // Whether anything is written: stderr is a terminal and the bar is not quiet.
  bool drawing() const { return drawing_; }

 private:
  using Clock = std::chrono::steady_clock;

  double elapsed_s() const;
  void draw(bool final_line);

  std::string label_;
  std::uint64_t total_ = 0;
  bool drawing_ = false;
  Clock::time_point start_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<std::int64_t> next_draw_ns_{0};  // since start_
  ProgressLines lines_;
  std::atomic<std::int64_t> next_line_ns_{0};  // since start_
  std::mutex lines_mutex_;
  std::atomic<bool> finished_{false};
  std::mutex draw_mutex_;
};

}  // namespace mg
