// Progress bar on stderr: see progress.h.
#include "motiongraph/core/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>

#include <fmt/format.h>

namespace mg {
namespace {

constexpr std::int64_t kRedrawIntervalNs = 100'000'000;  // at most ~10 redraws a second
constexpr int kDefaultWidth = 80;
constexpr int kMinBarWidth = 10;

// Columns of the terminal on stderr, less one so the cursor never wraps to the next line.
int terminal_width() {
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1) return size.ws_col - 1;
  return kDefaultWidth - 1;
}

// What the bar and the log's sentence both say of a known total: the share done (at most all of
// it), its whole percent, the count shown, and the seconds left while under way.
struct Figures {
  double fraction = 0.0;
  int percent = 0;
  std::uint64_t done = 0;
  std::optional<double> left_s;
};

Figures figures_of(std::uint64_t done, std::uint64_t total, double elapsed_s) {
  Figures f;
  f.fraction = std::min(1.0, static_cast<double>(done) / static_cast<double>(total));
  f.percent = static_cast<int>(std::floor(f.fraction * 100.0));
  f.done = std::min(done, total);
  if (done > 0 && done < total) {
    f.left_s = std::ceil(elapsed_s * static_cast<double>(total - done) / static_cast<double>(done));
  }
  return f;
}

}  // namespace

std::string format_progress_line(std::string_view label, std::uint64_t done, std::uint64_t total,
                                 double elapsed_s, int width, bool final_line) {
  if (width <= 0) return {};
  elapsed_s = std::max(0.0, elapsed_s);
  std::string stats;
  double fraction = 0.0;
  if (total > 0) {
    const Figures f = figures_of(done, total, elapsed_s);
    fraction = f.fraction;
    stats = fmt::format("{:3d}% {}/{} {:.1f}s", f.percent, f.done, total, elapsed_s);
    if (!final_line && f.left_s) stats += fmt::format(" eta {:.0f}s", *f.left_s);
  } else {
    stats = fmt::format("{} {:.1f}s", done, elapsed_s);
  }

  std::string line(label);
  // "label [####......] stats": the bar takes the room left, when there is enough of it.
  const int bar_width = width - static_cast<int>(label.size()) - static_cast<int>(stats.size()) - 4;
  if (total > 0 && bar_width >= kMinBarWidth) {
    const int filled = static_cast<int>(std::floor(fraction * bar_width));
    line += " [";
    line.append(static_cast<size_t>(filled), '#');
    line.append(static_cast<size_t>(bar_width - filled), '.');
    line += "] ";
  } else {
    line += ' ';
  }
  line += stats;
  if (line.size() > static_cast<size_t>(width)) line.resize(static_cast<size_t>(width));
  return line;
}

std::string progress_text(std::string_view label, std::uint64_t done, std::uint64_t total, double elapsed_s) {
  elapsed_s = std::max(0.0, elapsed_s);
  if (total == 0) return fmt::format("{}: {} in {:.1f} s", label, done, elapsed_s);
  const Figures f = figures_of(done, total, elapsed_s);
  std::string text = fmt::format("{}: {} % ({} of {}) in {:.1f} s", label, f.percent, f.done, total, elapsed_s);
  if (f.left_s) text += fmt::format(", about {:.0f} s left", *f.left_s);
  return text;
}

ProgressBar::ProgressBar(std::string label, std::uint64_t total, bool quiet, ProgressLines lines)
    : label_(std::move(label)),
      total_(total),
      drawing_(!quiet && isatty(STDERR_FILENO) == 1),
      start_(Clock::now()),
      lines_(std::move(lines)),
      next_line_ns_(static_cast<std::int64_t>(kProgressLineSeconds * 1e9)) {
  if (drawing_) draw(false);
}

ProgressBar::~ProgressBar() { finish(); }

double ProgressBar::elapsed_s() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void ProgressBar::advance(std::uint64_t n) {
  done_.fetch_add(n, std::memory_order_relaxed);
  if ((!drawing_ && !lines_) || finished_.load(std::memory_order_relaxed)) return;
  const std::int64_t now_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
  if (lines_) {
    std::int64_t next_line = next_line_ns_.load(std::memory_order_relaxed);
    const auto interval = static_cast<std::int64_t>(kProgressLineSeconds * 1e9);
    if (now_ns >= next_line &&
        next_line_ns_.compare_exchange_strong(next_line, now_ns + interval, std::memory_order_relaxed)) {
      // (A line still being handed out, by a slow caller, is not joined by another.)
      if (std::unique_lock lock(lines_mutex_, std::try_to_lock); lock.owns_lock()) {
        lines_(progress_text(label_, done(), total_, elapsed_s()));
      }
    }
  }
  if (!drawing_) return;
  std::int64_t next_ns = next_draw_ns_.load(std::memory_order_relaxed);
  if (now_ns < next_ns) return;
  // One thread wins the slot; the others go back to work.
  if (!next_draw_ns_.compare_exchange_strong(next_ns, now_ns + kRedrawIntervalNs, std::memory_order_relaxed)) return;
  draw(false);
}

void ProgressBar::finish() {
  if (finished_.exchange(true)) return;
  if (drawing_) draw(true);
}

void ProgressBar::draw(bool final_line) {
  std::unique_lock lock(draw_mutex_, std::defer_lock);
  if (final_line) {
    lock.lock();
  } else if (!lock.try_lock() || finished_.load(std::memory_order_relaxed)) {
    return;  // another thread is drawing, or the final line is out
  }
  const std::string line = format_progress_line(label_, done(), total_, elapsed_s(), terminal_width(), final_line);
  // "\r" back to the line start, "\x1b[K" clears what a longer previous line left.
  const std::string text = fmt::format("\r{}\x1b[K{}", line, final_line ? "\n" : "");
  std::fwrite(text.data(), 1, text.size(), stderr);
  std::fflush(stderr);
}

}  // namespace mg
