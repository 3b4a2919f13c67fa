#include "motiongraph/database/travel_tags.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

namespace mg {

Status TravelTagSettings::validate() const {
  if (!(min_speed_mps >= 0.0) || !std::isfinite(min_speed_mps)) {
    return Error{"", 0, fmt::format("the speed under which walk and run are left off must be >= 0, not {}",
                                    min_speed_mps)};
  }
  if (!(window_s > 0.0) || !std::isfinite(window_s)) {
    return Error{"", 0, fmt::format("the window the travel is judged over must be positive, not {} s", window_s)};
  }
  if (!(min_gap_s >= 0.0) || !(min_run_s >= 0.0) || !std::isfinite(min_gap_s) || !std::isfinite(min_run_s)) {
    return Error{"", 0, "the shortest pause and the shortest travel must be >= 0"};
  }
  if (!(stop_lead_s >= 0.0) || !std::isfinite(stop_lead_s)) {
    return Error{"", 0,
                 fmt::format("the travel that slows into a stop must be finite and >= 0 s, not {}", stop_lead_s)};
  }
  return Ok{};
}

bool is_locomotion_tag(std::string_view tag) {
  constexpr std::array<std::string_view, 2> kLocomotion = {"walk", "run"};
  return std::find(kLocomotion.begin(), kLocomotion.end(), tag) != kLocomotion.end();
}

bool is_stop_tag(std::string_view tag) {
  constexpr std::string_view kStop = "stop";
  return std::equal(tag.begin(), tag.end(), kStop.begin(), kStop.end(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) == b;
  });
}

std::vector<FrameSpan> travelling_spans(std::span<const Vec3> roots, double fps, const TravelTagSettings& settings) {
  const int n = static_cast<int>(roots.size());
  if (n == 0) return {};
  if (settings.min_speed_mps <= 0.0) return {{0, n}};
  const int half = std::max(1, static_cast<int>(std::lround(0.5 * settings.window_s * fps)));
  std::vector<bool> travels(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - half), hi = std::min(n - 1, i + half);
    if (hi == lo) continue;  // a one-frame clip goes nowhere
    const Vec3 step = roots[static_cast<size_t>(hi)] - roots[static_cast<size_t>(lo)];
    const double metres = std::hypot(step.x(), step.z());
    travels[static_cast<size_t>(i)] = metres >= settings.min_speed_mps * (hi - lo) / fps;
  }
  std::vector<FrameSpan> spans;
  for (int i = 0; i < n;) {
    if (!travels[static_cast<size_t>(i)]) {
      ++i;
      continue;
    }
    int end = i;
    while (end < n && travels[static_cast<size_t>(end)]) ++end;
    spans.push_back({i, end - i});
    i = end;
  }
  // Pauses between two spans shorter than min_gap_s keep the tag.
  const double min_gap = settings.min_gap_s * fps, min_run = settings.min_run_s * fps;
  std::vector<FrameSpan> joined;
  for (const FrameSpan& span : spans) {
    if (!joined.empty() && span.first - (joined.back().first + joined.back().count) < min_gap) {
      joined.back().count = span.first + span.count - joined.back().first;
    } else {
      joined.push_back(span);
    }
  }
  // A clip shorter than min_run_s that travels throughout keeps its tag.
  std::erase_if(joined, [&](const FrameSpan& span) { return span.count < min_run && span.count < n; });
  return joined;
}

std::vector<FrameSpan> stopping_spans(std::span<const Vec3> roots, double fps, const TravelTagSettings& settings) {
  const int n = static_cast<int>(roots.size());
  if (n == 0) return {};
  const std::vector<FrameSpan> travel = travelling_spans(roots, fps, settings);
  if (settings.min_speed_mps <= 0.0 || (travel.size() == 1 && travel[0] == FrameSpan{0, n})) return {{0, n}};
  const int lead = static_cast<int>(std::lround(settings.stop_lead_s * fps));
  std::vector<FrameSpan> spans;
  // Halt i lies between travel i - 1 and travel i (the clip's ends around them).
  for (size_t i = 0; i <= travel.size(); ++i) {
    const int halt = i == 0 ? 0 : travel[i - 1].first + travel[i - 1].count;
    const int moves = i < travel.size() ? travel[i].first : n;
    if (moves <= halt) continue;
    const int from = i == 0 ? halt : std::max(travel[i - 1].first, halt - lead);
    spans.push_back({from, moves - from});
  }
  return spans;
}

PaceSpans pace_spans(std::span<const Vec3> roots, double fps, const TravelTagSettings& settings, double run_mps) {
  const int n = static_cast<int>(roots.size());
  const int half = std::max(1, static_cast<int>(std::lround(0.5 * settings.window_s * fps)));
  const int min_run = std::max(1, static_cast<int>(std::lround(settings.min_run_s * fps)));
  PaceSpans out;
  for (const FrameSpan& span : travelling_spans(roots, fps, settings)) {
    // Each frame's pace, fast or not; then stretches of one pace.
    std::vector<FrameSpan> stretches;
    std::vector<bool> fast;
    for (int i = span.first; i < span.first + span.count; ++i) {
      const int lo = std::max(0, i - half), hi = std::min(n - 1, i + half);
      const Vec3 step = roots[static_cast<size_t>(hi)] - roots[static_cast<size_t>(lo)];
      const bool is_fast = hi > lo && std::hypot(step.x(), step.z()) >= run_mps * (hi - lo) / fps;
      if (stretches.empty() || fast.back() != is_fast) {
        stretches.push_back({i, 0});
        fast.push_back(is_fast);
      }
      ++stretches.back().count;
    }
    // Short stretches go with the one before (or after), and neighbours of one pace join.
    std::vector<FrameSpan> kept;
    std::vector<bool> kept_fast;
    for (size_t k = 0; k < stretches.size(); ++k) {
      const bool is_short = stretches[k].count < min_run && stretches.size() > 1;
      if (is_short && !kept.empty()) {
        kept.back().count += stretches[k].count;
      } else if (is_short && k + 1 < stretches.size()) {  // at the span's start: with the next
        stretches[k + 1].first = stretches[k].first;
        stretches[k + 1].count += stretches[k].count;
      } else if (!kept.empty() && kept_fast.back() == fast[k]) {
        kept.back().count += stretches[k].count;
      } else {
        kept.push_back(stretches[k]);
        kept_fast.push_back(fast[k]);
      }
    }
    for (size_t k = 0; k < kept.size(); ++k) (kept_fast[k] ? out.running : out.walking).push_back(kept[k]);
  }
  return out;
}

double run_pace_mps(double leg_m) {
  constexpr double kFroude = 0.3, kGravity = 9.81;
  return std::sqrt(kFroude * kGravity * std::max(leg_m, 0.0));
}

}  // namespace mg
