#include "motiongraph/synthesis/floor_path.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"
#include "motiongraph/io/file.h"

namespace mg {

Result<FloorPath> FloorPath::create(const std::vector<Vec2>& points, std::vector<PathSegment> segments) {
  FloorPath path;
  for (const Vec2& p : points) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return Error{"", 0, "a path point is not a finite number"};
    if (!path.points_.empty() && (p - path.points_.back()).norm() < 1e-9) continue;
    path.arc_.push_back(path.points_.empty() ? 0.0 : path.arc_.back() + (p - path.points_.back()).norm());
    path.points_.push_back(p);
  }
  if (path.points_.size() < 2) return Error{"", 0, "a path needs at least two distinct points"};
  if (!(path.length_m() <= kMaxLengthM)) {
    return Error{"", 0, fmt::format("a path may be at most {:.0f} km long", kMaxLengthM / 1000.0)};
  }
  for (const PathSegment& s : segments) {
    if (!std::isfinite(s.from_m) || !std::isfinite(s.to_m) || s.from_m < 0.0 || s.to_m <= s.from_m) {
      return Error{"", 0, fmt::format("segment '{}' must have 0 <= from_m < to_m", s.tag)};
    }
    if (s.tag.empty()) return Error{"", 0, "a segment needs a tag"};
  }
  path.segments_ = std::move(segments);
  path.bucket_m_ = std::max(kBucket, path.length_m() / (kMaxBuckets - 1));
  const int buckets = static_cast<int>(std::min<double>(kMaxBuckets - 1, path.length_m() / path.bucket_m_)) + 1;
  int segment = 0;
  for (int b = 0; b < buckets; ++b) {
    while (segment + 2 < static_cast<int>(path.points_.size()) && path.arc_[segment + 1] <= b * path.bucket_m_) {
      ++segment;
    }
    path.bucket_segment_.push_back(segment);
  }
  path.make_grid();
  return path;
}

void FloorPath::make_grid() {
  Vec2 low = points_.front(), high = points_.front();
  for (const Vec2& p : points_) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const int segments = static_cast<int>(points_.size()) - 1;
  const Vec2 size = high - low;
  cell_m_ = std::max({kMinCellM, std::sqrt(size.x() * size.y() / segments), std::max(size.x(), size.y()) / segments});
  grid_origin_ = low;
  cells_x_ = static_cast<int>(size.x() / cell_m_) + 1;
  cells_z_ = static_cast<int>(size.y() / cell_m_) + 1;
  // A segment is listed in the cells of points along it at most half a side apart (its ends
  // among them), each cell once: then any point of it lies within a quarter side of a point in
  // a cell that lists it.
  auto for_each_cell = [&](int i, auto&& visit) {
    const Vec2 a = points_[static_cast<size_t>(i)], b = points_[static_cast<size_t>(i) + 1];
    const int steps = static_cast<int>(std::ceil((b - a).norm() / (0.5 * cell_m_)));
    int last = -1;
    for (int k = 0; k <= steps; ++k) {
      const Vec2 at = (a + (b - a) * (static_cast<double>(k) / std::max(steps, 1)) - low) / cell_m_;
      const int x = std::clamp(static_cast<int>(at.x()), 0, cells_x_ - 1);
      const int z = std::clamp(static_cast<int>(at.y()), 0, cells_z_ - 1);
      const int c = z * cells_x_ + x;
      if (c != last) visit(c);  // a segment does not come back to a cell it left
      last = c;
    }
  };
  // Counting, then filling (CSR).
  cell_start_.assign(static_cast<size_t>(cells_x_) * cells_z_ + 1, 0);
  for (int i = 0; i < segments; ++i) for_each_cell(i, [&](int c) { ++cell_start_[static_cast<size_t>(c) + 1]; });
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_segments_.assign(static_cast<size_t>(cell_start_.back()), 0);
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < segments; ++i) {
    for_each_cell(i, [&](int c) { cell_segments_[static_cast<size_t>(fill[static_cast<size_t>(c)]++)] = i; });
  }
}

Vec2 FloorPath::direction_at(double s) const {
  const int i = segment_index(std::clamp(s, 0.0, length_m()));
  return (points_[i + 1] - points_[i]).normalized();
}

double FloorPath::distance_to(const Vec2& p) const {
  if (!p.allFinite()) return (p - points_.front()).norm();  // infinite or NaN, as a scan gives
  double best = std::numeric_limits<double>::infinity();
  auto look_at_cell = [&](int x, int z) {
    const size_t c = static_cast<size_t>(z) * cells_x_ + x;
    for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const size_t i = static_cast<size_t>(cell_segments_[static_cast<size_t>(k)]);
      const Vec2 d = points_[i + 1] - points_[i];
      const double u = std::clamp((p - points_[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (points_[i] + u * d - p).norm());
    }
  };
  // p's cell, or the nearest cell of the grid to p. A cell r rings out (Chebyshev) lies at
  // least (r - 1) cell sides from p, and every point of a segment within a quarter side of a
  // cell listing it, so once rings 0..r are seen, a best of at most r - 1/4 sides is final.
  const Vec2 at = (p - grid_origin_) / cell_m_;
  const int cx = std::clamp(static_cast<int>(std::floor(std::clamp(at.x(), -1.0, 1e9))), 0, cells_x_ - 1);
  const int cz = std::clamp(static_cast<int>(std::floor(std::clamp(at.y(), -1.0, 1e9))), 0, cells_z_ - 1);
  const int rings = std::max({cx, cells_x_ - 1 - cx, cz, cells_z_ - 1 - cz});
  for (int r = 0; r <= rings; ++r) {
    for (int z = cz - r; z <= cz + r; ++z) {
      if (z < 0 || z >= cells_z_) continue;
      const bool edge_row = z == cz - r || z == cz + r;
      for (int x = cx - r; x <= cx + r; x += edge_row ? 1 : 2 * r) {
        if (x >= 0 && x < cells_x_) look_at_cell(x, z);
        if (r == 0) break;
      }
    }
    if (best <= (r - 0.25) * cell_m_) break;
  }
  return best;
}

double FloorPath::nearest_arc(const Vec2& p, double from, double to, double prefer) const {
  from = std::clamp(from, 0.0, length_m());
  to = std::clamp(to, from, length_m());
  const auto distance_at = [&](double s) { return (point_at(s) - p).norm(); };
  // Each segment's nearest point in the range, visited in order.
  const auto for_each_segment = [&](auto&& visit) {
    for (int i = segment_index(from); i + 1 < static_cast<int>(points_.size()) && arc_[i] <= to; ++i) {
      const Vec2 d = points_[i + 1] - points_[i];
      const double length = arc_[i + 1] - arc_[i];
      const double s =
          std::clamp(arc_[i] + (p - points_[i]).dot(d) / length, std::max(from, arc_[i]), std::min(to, arc_[i + 1]));
      visit(i, s, (point_on(i, s) - p).norm());
    }
  };
  double best_arc = from, best = distance_at(from);
  int best_segment = segment_index(from);
  for_each_segment([&](int i, double s, double distance) {
    if (distance < best) {
      best = distance;
      best_arc = s;
      best_segment = i;
    }
  });
  if (std::isnan(prefer)) return best_arc;
  // Legs of the path that lie on one another, heading against each other (a path out and back):
  // of the points of such a leg where the distance has a minimum along the path, within 2 cm of
  // the nearest, the one nearest `prefer`, so that a point followed along the path stays on its
  // leg. Legs that meet at a corner are not such legs: there the nearest is taken, as without
  // `prefer`.
  constexpr double kNearM = 0.02, kProbeM = 1e-4;
  const Vec2 best_direction = points_[best_segment + 1] - points_[best_segment];
  double chosen = best_arc;
  for_each_segment([&](int i, double s, double distance) {
    if (distance > best + kNearM || std::abs(s - prefer) >= std::abs(chosen - prefer)) return;
    const Vec2 direction = points_[i + 1] - points_[i];
    if (direction.dot(best_direction) > -0.5 * direction.norm() * best_direction.norm()) return;  // not against
    const bool minimum = (s - kProbeM < from || distance_at(s - kProbeM) >= distance - 1e-12) &&
                         (s + kProbeM > to || distance_at(s + kProbeM) >= distance - 1e-12);
    if (minimum) chosen = s;
  });
  return chosen;
}

std::vector<double> FloorPath::followed_arcs(std::span<const Vec2> track, double window_m, double from) const {
  std::vector<double> arcs;
  arcs.reserve(track.size());
  double last = from;
  for (size_t i = 0; i < track.size(); ++i) {
    const Vec2& p = track[i];
    if (last < 0.0) {
      last = nearest_arc(p, 0.0, window_m);
    } else {
      // On legs that lie on one another (a path out and back), the leg the point moves along:
      // of the point as far ahead of the last one's arc as it moved and the one as far behind,
      // the one whose leg heads the way it moved (a point that did not move stays put).
      const Vec2 moved = i > 0 ? Vec2(p - track[i - 1]) : Vec2::Zero();
      const double step = moved.norm();
      const double ahead = nearest_arc(p, last - window_m, last + window_m, last + step);
      const double behind = step > 0.0 ? nearest_arc(p, last - window_m, last + window_m, last - step) : ahead;
      last = behind == ahead || direction_at(ahead).dot(moved) >= direction_at(behind).dot(moved) ? ahead : behind;
    }
    arcs.push_back(last);
  }
  return arcs;
}

int FloorPath::segment_at(double s) const {
  for (size_t i = segments_.size(); i-- > 0;) {
    if (s >= segments_[i].from_m && s < segments_[i].to_m) return static_cast<int>(i);
  }
  return -1;
}

std::vector<FloorPath::SegmentSpan> FloorPath::segment_spans() const {
  std::vector<double> cuts{0.0, length_m()};
  for (const PathSegment& segment : segments_) {
    cuts.push_back(std::max(0.0, segment.from_m));
    cuts.push_back(std::max(0.0, segment.to_m));
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<SegmentSpan> spans;
  for (double cut : cuts) spans.push_back({cut, segment_at(cut)});
  return spans;
}

const std::string& FloorPath::tag_at(double s) const {
  static const std::string none;
  const int i = segment_at(s);
  return i < 0 ? none : segments_[static_cast<size_t>(i)].tag;
}

Result<FloorPath> parse_path_json(std::string_view text, const std::string& file_name) {
  auto parsed = parse_json_text(text, file_name);
  if (!parsed) return parsed.error();
  if (parsed->is_object()) {
    if (const std::string key = unknown_key(*parsed, {"points", "segments"}); !key.empty()) {
      return Error{file_name, 0, fmt::format("unknown key \"{}\" (a path has \"points\" and \"segments\")", key)};
    }
  }
  return parse_path_document(*parsed, file_name);
}

Result<FloorPath> parse_path_document(const nlohmann::json& doc, const std::string& file_name) {
  auto fail = [&](const std::string& what) { return Error{file_name, 0, what}; };
  if (!doc.is_object() || !doc.contains("points") || !doc["points"].is_array()) {
    return fail("expected an object with \"points\": [[x, z], ...]");
  }
  std::vector<Vec2> points;
  for (size_t i = 0; i < doc["points"].size(); ++i) {
    const auto& p = doc["points"][i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) {
      return fail(fmt::format("points[{}] is not a pair of numbers [x, z]", i));
    }
    points.emplace_back(p[0].get<double>(), p[1].get<double>());
  }
  std::vector<PathSegment> segments;
  if (doc.contains("segments")) {
    if (!doc["segments"].is_array()) return fail("\"segments\" must be an array");
    for (size_t i = 0; i < doc["segments"].size(); ++i) {
      const auto& s = doc["segments"][i];
      if (!s.is_object() || !s.contains("from_m") || !s["from_m"].is_number() || !s.contains("to_m") ||
          !s["to_m"].is_number() || !s.contains("tag") || !s["tag"].is_string()) {
        return fail(fmt::format("segments[{}] needs \"from_m\", \"to_m\" (numbers) and \"tag\" (a string)", i));
      }
      if (const std::string key = unknown_key(s, {"from_m", "to_m", "tag"}); !key.empty()) {
        return fail(fmt::format("segments[{}]: unknown key \"{}\" (a segment has \"from_m\", \"to_m\" and \"tag\")",
                                i, key));
      }
      segments.push_back({s["from_m"].get<double>(), s["to_m"].get<double>(), s["tag"].get<std::string>()});
    }
  }
  auto path = FloorPath::create(std::move(points), std::move(segments));
  if (!path) return fail(path.error().message);
  return path;
}

Result<FloorPath> make_shape(std::string_view spec) {
  const size_t colon = spec.find(':');
  const std::string_view name = spec.substr(0, colon);
  double size = 0.0;
  if (colon == std::string_view::npos) {
    return Error{"", 0,
                 fmt::format("shape '{}' needs a size: line:20, circle:5, figure8:4, s-curve:100, square:10 or "
                             "zigzag:6",
                             spec)};
  }
  const std::string_view number = spec.substr(colon + 1);
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), size);
  if (ec != std::errc() || end != number.data() + number.size() || !(size > 0.0) || !std::isfinite(size)) {
    return Error{"", 0, fmt::format("shape '{}': the size must be a positive number of metres", spec)};
  }
  constexpr double kPi = std::numbers::pi;
  // Its length before its points are made (s-curve:1e8 would make two billion).
  const double length = name == "circle"    ? 2 * kPi * size
                        : name == "figure8" ? 4 * kPi * size
                        : name == "square"  ? 4 * size
                        : name == "zigzag"  ? 8 * size
                                            : size;
  if (length > FloorPath::kMaxLengthM) {
    return Error{"", 0, fmt::format("shape '{}' would be {:.0f} m long; a path is at most {:.0f} m", spec, length,
                                    FloorPath::kMaxLengthM)};
  }
  std::vector<Vec2> points;
  auto arc = [&](const Vec2& centre, double radius, double start_angle, double sweep) {
    const int n = std::max(8, static_cast<int>(std::ceil(std::abs(sweep) * radius / 0.1)));
    for (int i = 0; i <= n; ++i) {
      const double a = start_angle + sweep * i / n;
      points.emplace_back(centre.x() + radius * std::cos(a), centre.y() + radius * std::sin(a));
    }
  };
  if (name == "line") {
    const int n = std::max(1, static_cast<int>(std::ceil(size / 0.1)));
    for (int i = 0; i <= n; ++i) points.emplace_back(0.0, -size * i / n);
  } else if (name == "circle") {
    // Heading north (-z) at the origin and turning right (towards +x): centre at (R, 0).
    arc(Vec2(size, 0.0), size, kPi, 2 * kPi);
  } else if (name == "figure8") {
    arc(Vec2(size, 0.0), size, kPi, 2 * kPi);   // right-hand loop
    arc(Vec2(-size, 0.0), size, 0.0, -2 * kPi);  // then the left-hand loop
  } else if (name == "s-curve") {
    const double wavelength = size / 2.0, amplitude = size / 20.0;
    // Parametrised by distance along -z; arc length a little more than size: sample densely
    // and cut at `size` metres of arc.
    const int n = static_cast<int>(std::ceil(size / 0.05));
    double covered = 0.0;
    Vec2 last(0.0, 0.0);
    points.push_back(last);
    for (int i = 1; i <= 2 * n && covered < size; ++i) {
      const double t = size * i / n;
      const Vec2 p(amplitude * (1.0 - std::cos(2 * kPi * t / wavelength)), -t);
      covered += (p - last).norm();
      points.push_back(p);
      last = p;
    }
  } else if (name == "square" || name == "zigzag") {
    // Straight legs between corners, sampled every 0.1 m: a square's four sides turning right
    // (north, east, south, west: back at the origin), or a zigzag's eight legs 45 degrees right
    // and left of north in turn.
    std::vector<Vec2> corners{Vec2(0.0, 0.0)};
    if (name == "square") {
      for (const Vec2& step : {Vec2(0.0, -size), Vec2(size, 0.0), Vec2(0.0, size), Vec2(-size, 0.0)}) {
        corners.push_back(corners.back() + step);
      }
    } else {
      const double d = size / std::numbers::sqrt2;
      for (int leg = 0; leg < 8; ++leg) corners.push_back(corners.back() + Vec2(leg % 2 == 0 ? d : -d, -d));
    }
    points.push_back(corners.front());
    for (size_t c = 1; c < corners.size(); ++c) {
      const int n = std::max(1, static_cast<int>(std::ceil(size / 0.1)));
      for (int i = 1; i <= n; ++i) points.push_back(corners[c - 1] + (corners[c] - corners[c - 1]) * i / n);
    }
  } else {
    return Error{"", 0, fmt::format("unknown shape '{}': line, circle, figure8, s-curve, square or zigzag", name)};
  }
  return FloorPath::create(std::move(points));
}

Result<PathSegment> parse_path_segment(const std::string& text) {
  const size_t colon = text.rfind(':');
  const size_t dash = text.find('-', colon == std::string::npos ? 0 : colon);
  PathSegment s;
  try {
    if (colon == std::string::npos || dash == std::string::npos) throw std::invalid_argument(text);
    s.tag = text.substr(0, colon);
    size_t used = 0;
    s.from_m = std::stod(text.substr(colon + 1, dash - colon - 1), &used);
    s.to_m = std::stod(text.substr(dash + 1), &used);
    if (used != text.size() - dash - 1) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    return Error{"", 0, fmt::format("--segment '{}': expected TAG:FROM-TO in metres, e.g. run:20-40", text)};
  }
  return s;
}

Result<FloorPath> make_floor_path(const FloorPathSource& source) {
  const int given = !source.file.empty() + !source.shape.empty() + !source.points.empty();
  if (given != 1) return Error{"", 0, "give exactly one of --path and --shape"};
  std::vector<PathSegment> segments;
  for (const std::string& text : source.segments) {
    auto s = parse_path_segment(text);
    if (!s) return s.error();
    segments.push_back(*s);
  }
  if (!source.points.empty()) return FloorPath::create(source.points, segments);
  if (!source.shape.empty()) {
    auto shape = make_shape(source.shape);
    if (!shape) return shape.error();
    return FloorPath::create(shape->points(), segments);
  }
  auto text = read_text_file(source.file);
  if (!text) return text.error();
  auto path = parse_path_json(*text, source.file);
  if (!path || segments.empty()) return path;
  return FloorPath::create(path->points(), segments);
}

}  // namespace mg
