// The pruned distance stage: the ball search's pairs in bands of leaving frames, their D along
// diagonal runs, then the exhaustive stage's local-minimum test, histogram and picture.
#include "motiongraph/graph/pruned_candidates.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include "motiongraph/core/parallel_for.h"
#include "motiongraph/metric/diagonal_runs.h"

namespace mg {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A diagonal run of the band: pairs (a + m, b + m), m < length.
struct Run {
  int a = 0, b = 0, length = 0;
};

// The pairs of consecutive leaving frames the search returned and not yet tested: row i is
// leaving frame frame[i], its arrivals cols[begin[i] .. begin[i + 1]) in increasing order.
// Pairs are gathered into diagonal runs as rows come: pair j is pair offset[j] of run run[j]
// (it continues the run of (a - 1, b - 1) when the previous row holds that).
struct Band {
  std::vector<int> frame;
  std::vector<size_t> begin{0};
  std::vector<int> cols;
  std::vector<int> run, offset;
  std::vector<Run> runs;

  size_t rows() const { return frame.size(); }
  void add_row(int a, std::span<const int> arrivals) {
    const bool follows = !frame.empty() && frame.back() == a - 1;
    size_t p = follows ? begin[frame.size() - 1] : 0;
    const size_t p_end = follows ? begin[frame.size()] : 0;
    for (const int b : arrivals) {
      while (p < p_end && cols[p] < b - 1) ++p;
      if (p < p_end && cols[p] == b - 1) {
        run.push_back(run[p]);
        offset.push_back(offset[p] + 1);
        ++runs[static_cast<size_t>(run[p])].length;
      } else {
        run.push_back(static_cast<int>(runs.size()));
        offset.push_back(0);
        runs.push_back(Run{a, b, 1});
      }
    }
    frame.push_back(a);
    cols.insert(cols.end(), arrivals.begin(), arrivals.end());
    begin.push_back(cols.size());
  }
  // Drops the rows before `first_kept` (a frame); the rows kept start runs afresh. The
  // vectors keep their capacity for the next band.
  void drop_before(int first_kept) {
    size_t i = 0;
    while (i < frame.size() && frame[i] < first_kept) ++i;
    const std::vector<int> kept_frames(frame.begin() + static_cast<std::ptrdiff_t>(i), frame.end());
    const std::vector<int> kept_cols(cols.begin() + static_cast<std::ptrdiff_t>(begin[i]), cols.end());
    std::vector<size_t> kept_begin(begin.begin() + static_cast<std::ptrdiff_t>(i), begin.end());
    frame.clear();
    begin.assign(1, 0);
    cols.clear();
    run.clear();
    offset.clear();
    runs.clear();
    for (size_t r = 0; r < kept_frames.size(); ++r) {
      add_row(kept_frames[r], std::span<const int>(kept_cols)
                                  .subspan(kept_begin[r] - kept_begin[0], kept_begin[r + 1] - kept_begin[r]));
    }
  }
};

class PrunedSearch {
 public:
  PrunedSearch(const FrameFeatures& f, double ceiling, int threads, CandidateSearch& out,
               PrunedSearchStatistics& stats)
      : f_(f), runs_(f), ceiling_(ceiling), threads_(threads), out_(out), stats_(stats) {}

  // Tests the rows with leaving frames in [first_untested_, end) (rows up to `end` must be
  // complete: the test reads the next row), then keeps only what the next band needs.
  void test_rows_before(int end) {
    const auto start = std::chrono::steady_clock::now();
    compute_distances();
    find_minima(end);
    first_untested_ = end;
    band_.drop_before(end - 1);
    stats_.exact_seconds += seconds_since(start);
  }

  Band& band() { return band_; }
  int first_untested() const { return first_untested_; }
  long long binned() const { return binned_; }

 private:
  // d_[j] = D of band pair j: computed run by run into a run-major array, then gathered.
  void compute_distances() {
    const std::vector<Run>& runs = band_.runs;
    stats_.runs += static_cast<long long>(runs.size());
    run_begin_.resize(runs.size() + 1);
    run_begin_[0] = 0;
    for (size_t r = 0; r < runs.size(); ++r) run_begin_[r + 1] = run_begin_[r] + static_cast<size_t>(runs[r].length);
    by_run_.resize(run_begin_.back());
    parallel_for(static_cast<long long>(runs.size()), threads_, 256, [&](int, long long i) {
      const auto r = static_cast<size_t>(i);
      runs_.distances(runs[r].a, runs[r].b,
                      std::span<float>(by_run_).subspan(run_begin_[r], static_cast<size_t>(runs[r].length)));
    });
    d_.resize(band_.cols.size());
    for (size_t j = 0; j < d_.size(); ++j) {
      d_[j] = by_run_[run_begin_[static_cast<size_t>(band_.run[j])] + static_cast<size_t>(band_.offset[j])];
    }
  }

  // The values of (row r's frame, b - 1 .. b + 1): +infinity where row r lacks the pair (the
  // search left it out, so it lies above the ceiling). `cursor` is row r's first pair at or
  // after column b - 1: it moves forward only, as b grows along a row.
  const float* three_around(size_t r, size_t& cursor, int b) {
    const size_t end = band_.begin[r + 1];
    while (cursor < end && band_.cols[cursor] < b - 1) ++cursor;
    size_t p = cursor;
    for (int c = 0; c < 3; ++c) {
      while (p < end && band_.cols[p] < b - 1 + c) ++p;
      three_[c] = p < end && band_.cols[p] == b - 1 + c ? d_[p] : kInfinity;
    }
    return three_;
  }

  void find_minima(int end) {
    const int k = f_.window;
    const int radius = out_.continuation_radius, block = out_.picture_block, side = out_.picture_side;
    const float ceiling = static_cast<float>(ceiling_);
    for (size_t i = 0; i < band_.rows(); ++i) {
      const int a = band_.frame[i];
      if (a < first_untested_) continue;
      if (a >= end) break;
      const bool has_up = i > 0 && band_.frame[i - 1] == a - 1;
      const bool has_down = i + 1 < band_.rows() && band_.frame[i + 1] == a + 1;
      size_t up = has_up ? band_.begin[i - 1] : 0, down = has_down ? band_.begin[i + 1] : 0;
      const size_t row_begin = band_.begin[i], row_end = band_.begin[i + 1];
      for (size_t j = row_begin; j < row_end; ++j) {
        const float d = d_[j];
        if (!(d <= ceiling)) continue;  // above it (or NaN): not this stage's to tell
        const int b = band_.cols[j];
        out_.histogram.add(d);
        ++binned_;
        float& pixel = out_.picture[static_cast<size_t>(a / block) * side + b / block];
        if (!(pixel <= d)) pixel = d;
        // The exhaustive test: none of the 8 smaller; ties go to the first in row-major order.
        const float left = j > row_begin && band_.cols[j - 1] == b - 1 ? d_[j - 1] : kInfinity;
        const float right = j + 1 < row_end && band_.cols[j + 1] == b + 1 ? d_[j + 1] : kInfinity;
        if (left <= d || right < d) continue;
        bool minimum = true;
        if (has_up) {
          const float* above = three_around(i - 1, up, b);
          minimum = !(above[0] <= d) && !(above[1] <= d) && !(above[2] <= d);
        }
        if (minimum && has_down) {
          const float* below = three_around(i + 1, down, b);
          minimum = !(below[0] < d) && !(below[1] < d) && !(below[2] < d);
        }
        if (!minimum) continue;
        if (f_.clip_of_frame[b] == f_.clip_of_frame[a] && std::abs(b - (a + k - 1)) <= radius) continue;
        out_.minima.push_back(Transition{a, b, d, 0.0f, 0.0f, 0.0f});
      }
    }
  }

  const FrameFeatures& f_;
  const DiagonalRuns runs_;
  double ceiling_;
  int threads_;
  CandidateSearch& out_;
  PrunedSearchStatistics& stats_;
  Band band_;
  int first_untested_ = 0;
  long long binned_ = 0;
  std::vector<float> d_;        // per band pair, row-major
  std::vector<float> by_run_;   // per band pair, run-major
  std::vector<size_t> run_begin_;
  float three_[3] = {};
};

}  // namespace

Status PrunedSearchSettings::validate() const {
  if (auto s = embedding.validate(); !s) return s;
  if (threads < 0) return Error{"", 0, "threads must be >= 0"};
  if (band_pairs < 1) return Error{"", 0, "the pruned stage's band must hold at least one pair"};
  return Ok{};
}

Result<CandidateSearch> find_candidates_pruned(const FrameFeatures& f, double ceiling,
                                               const CandidateSettings& settings, const PrunedSearchSettings& pruned,
                                               PrunedSearchStatistics* statistics) {
  if (auto s = pruned.validate(); !s) return s.error();
  if (!(ceiling >= 0.0) || !std::isfinite(ceiling)) return Error{"", 0, "the pruned stage's ceiling must be >= 0"};
  if (settings.keep_matrix) {
    return Error{"", 0, "the pruned distance stage holds no matrix (use the exhaustive stage to export it)"};
  }
  auto empty = empty_candidate_search(f, settings);
  if (!empty) return empty.error();
  CandidateSearch search = std::move(*empty);
  search.ceiling = ceiling;
  PrunedSearchStatistics local;
  PrunedSearchStatistics& stats = statistics != nullptr ? *statistics : local;
  stats = {};
  const auto start = std::chrono::steady_clock::now();
  const int threads = worker_threads(pruned.threads);
  const long long leaving = std::count(f.can_leave.begin(), f.can_leave.end(), 1);
  const long long arriving = std::count(f.can_arrive.begin(), f.can_arrive.end(), 1);
  stats.defined_pairs = leaving * arriving;
  if (stats.defined_pairs > 0) {
    auto embedding = make_window_embedding(f, pruned.embedding);
    if (!embedding) return embedding.error();
    stats.embedding_seconds = seconds_since(start);
    PrunedSearch state(f, ceiling, threads, search, stats);
    // The bound is computed in float: a relative 1e-3 of slack keeps every pair at or below the
    // ceiling, and leaves out only pairs whose D is above it.
    const double search_ceiling = ceiling * (1.0 + 1e-3);
    const auto search_start = std::chrono::steady_clock::now();
    const BoundedPairStatistics found = for_each_bounded_pair(
        f, *embedding, search_ceiling,
        [&](int a, std::span<const int> arrivals) {
          Band& band = state.band();
          // Rows before a - 1 are complete with their next row: test them once a band is full.
          if (static_cast<long long>(band.cols.size()) >= pruned.band_pairs && a - 1 > state.first_untested()) {
            state.test_rows_before(a - 1);
          }
          band.add_row(a, arrivals);
        },
        threads);
    state.test_rows_before(std::numeric_limits<int>::max());
    stats.search_seconds = seconds_since(search_start) - stats.exact_seconds;
    stats.candidate_pairs = found.pairs;
    search.histogram.add_above(static_cast<std::uint64_t>(stats.defined_pairs - state.binned()));
  }
  // Pixels with defined pairs but none at or below the ceiling: +infinity ("above").
  const int block = search.picture_block, side = search.picture_side;
  std::vector<char> leave_block(static_cast<size_t>(side), 0), arrive_block(static_cast<size_t>(side), 0);
  for (int a = 0; a < f.frames; ++a) {
    if (f.can_leave[a]) leave_block[static_cast<size_t>(a / block)] = 1;
    if (f.can_arrive[a]) arrive_block[static_cast<size_t>(a / block)] = 1;
  }
  for (int r = 0; r < side; ++r) {
    for (int c = 0; c < side; ++c) {
      float& pixel = search.picture[static_cast<size_t>(r) * side + c];
      if (std::isnan(pixel) && leave_block[static_cast<size_t>(r)] && arrive_block[static_cast<size_t>(c)]) {
        pixel = kInfinity;
      }
    }
  }
  search.tiles.seconds = seconds_since(start);
  search.tiles.tiles = 0;
  search.tiles.pairs = stats.candidate_pairs;
  return search;
}

}  // namespace mg
