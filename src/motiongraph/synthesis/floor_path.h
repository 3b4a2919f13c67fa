// A path on the floor for the character to follow (Kovar et al. 2002, section 5): a polyline
// of (x, z) points in metres, parametrised by arc length, with optional motion types along
// arc-length ranges. Coordinates are the world's: x east, z south, so "north" is -z.
//
// PATH.json:  {"points": [[x, z], ...],
//              "segments": [{"from_m": 0, "to_m": 20, "tag": "walk"}, ...]}   (segments optional)
// Built-in shapes, all starting at the origin heading north (-z) but the zigzag (north-east):
//   line:L      a straight line L metres long
//   circle:R    one turn of a circle of radius R, turning right (clockwise seen from above)
//   figure8:R   two circles of radius R, right then left, meeting at the origin
//   s-curve:L   L metres of a wave x = A (1 - cos(2 pi d / (L/2))) along d north, A = L/20:
//               S bends right and left, starting straight north
//   square:S    a square of side S, turning right at its corners (90 degrees), back at the origin
//   zigzag:L    eight legs of L metres, 45 degrees right then left of north in turn (corners of
//               90 degrees)
#pragma once

#include <algorithm>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/synthesis/facing.h"

namespace mg {

struct PathSegment {
  double from_m = 0.0;
  double to_m = 0.0;
  std::string tag;
};

class FloorPath {
 public:
  static constexpr double kMaxLengthM = 100000.0;

  FloorPath() = default;
  // Fails with fewer than two distinct points, a non-finite coordinate or a length over
  // kMaxLengthM.
  static Result<FloorPath> create(const std::vector<Vec2>& points, std::vector<PathSegment> segments = {});

  double length_m() const { return arc_.empty() ? 0.0 : arc_.back(); }
  const std::vector<Vec2>& points() const { return points_; }
  const std::vector<PathSegment>& segments() const { return segments_; }
  // The point at arc length s (clamped to the ends). Inline: searches call it for every frame
  // they try.
  Vec2 point_at(double s) const {
    s = std::clamp(s, 0.0, length_m());
    return point_on(segment_index(s), s);
  }
  // The same point, found from `segment`: the segment of an arc length at or before s (such as
  // the last call's, for the frames of a walk one after the other), or -1 for none. `segment`
  // is left at s's segment; runs of non-decreasing s then cost a step or two each, not a
  // lookup.
  Vec2 point_at(double s, int& segment) const {
    s = std::clamp(s, 0.0, length_m());
    int i = segment;
    if (i < 0 || arc_[i] > s) {
      i = segment_index(s);
    } else {
      const int last = static_cast<int>(points_.size()) - 2;
      while (i < last && arc_[i + 1] <= s) ++i;
    }
    segment = i;
    return point_on(i, s);
  }
  // The unit direction at arc length s.
  Vec2 direction_at(double s) const;
  // Distance from p to the nearest point of the path. Looks at the segments in the grid cells
  // around p, ring by ring, until no further cell can hold a nearer one: on a long path (a
  // result's deviation is measured frame by frame) a few segments, not all of them.
  double distance_to(const Vec2& p) const;
  // The arc length of the point nearest p among arc lengths [from, to] (clamped to the path):
  // from a point followed along the path, with a small range, a path that crosses itself is not
  // jumped across. Costs the segments in the range. Given `prefer` (the arc a point followed
  // along the path is expected at), where legs of the path lie on one another heading against
  // each other (out and back: points of the range whose distance to p is least along the path,
  // within 2 cm of the nearest), the one nearest `prefer`: the leg the point is on, not the one
  // beside it. Elsewhere (corners among them) the nearest, as without it.
  double nearest_arc(const Vec2& p, double from, double to,
                     double prefer = std::numeric_limits<double>::quiet_NaN()) const;
  // How far along the path each point of a track is: track[0]'s nearest point within
  // [0, window_m] (or, given the arc `from` of the point before the track, within +-window_m of
  // it), then each next point's within +-window_m of the last one's, where legs lie on one
  // another the one heading the way the point moved (nearest_arc). A motion's
  // progress: a root that sways, shuffles or steps aside does not add to it, as it adds to the
  // distance the root travels. Consecutive points must lie less than window_m apart.
  std::vector<double> followed_arcs(std::span<const Vec2> track, double window_m = 1.0, double from = -1.0) const;
  // The segment asked for at arc length s: the index of the last one given containing s
  // ([from_m, to_m)), or -1 when none; and its tag ("" when none).
  int segment_at(double s) const;
  const std::string& tag_at(double s) const;
  // Where segment_at may change, in order: 0, the path's length and every segment's ends (those
  // before 0 at 0), each with the segment it gives from there to the next (the last on past the
  // path's end).
  struct SegmentSpan {
    double from_m = 0.0;
    int segment = -1;
  };
  std::vector<SegmentSpan> segment_spans() const;

 private:
  // s is clamped to [0, length]: the segment i with arc_[i] <= s < arc_[i + 1] (the last one at
  // the end), starting from its bucket's first segment.
  int segment_index(double s) const {
    const int last = static_cast<int>(points_.size()) - 2;
    const size_t b = std::min(bucket_segment_.size() - 1, static_cast<size_t>(s / bucket_m_));
    int i = bucket_segment_[b];
    while (i > 0 && arc_[i] > s) --i;  // s / bucket_m_ rounded up into the next bucket
    while (i < last && arc_[i + 1] <= s) ++i;
    return i;
  }
  // The point at s (clamped to [0, length]) on segment i (arc_[i] <= s <= arc_[i + 1]).
  Vec2 point_on(int i, double s) const {
    const double len = arc_[i + 1] - arc_[i];
    const double u = std::clamp((s - arc_[i]) / len, 0.0, 1.0);
    return points_[i] + u * (points_[i + 1] - points_[i]);
  }
  std::vector<Vec2> points_;   // consecutive duplicates removed
  std::vector<double> arc_;    // arc length at each point
  // For arc lengths in [b * bucket_m_, (b + 1) * bucket_m_): the first segment to look at, so
  // that point_at is O(1) (searches evaluate it for every frame they try). Buckets are
  // kBucket long, or longer on paths so long that more than kMaxBuckets would be needed.
  static constexpr double kBucket = 0.05;
  static constexpr int kMaxBuckets = 1 << 20;
  double bucket_m_ = kBucket;
  std::vector<int> bucket_segment_;
  // A grid over the path's bounding box (about as many cells as segments, square, at least
  // kMinCellM): cell (i, j) lists the segments that pass through it (make_grid), as the run
  // cell_segments_[cell_start_[c] .. cell_start_[c + 1]) with c = j * cells_x_ + i.
  static constexpr double kMinCellM = 0.5;
  Vec2 grid_origin_ = Vec2::Zero();
  double cell_m_ = 1.0;
  int cells_x_ = 1, cells_z_ = 1;
  std::vector<int> cell_start_;
  std::vector<int> cell_segments_;
  void make_grid();
  std::vector<PathSegment> segments_;
};

// PATH.json as above; errors name the file (and the line for JSON syntax errors). A key that is
// none of those above is an error (a misspelt "segments" would otherwise drop every tag).
Result<FloorPath> parse_path_json(std::string_view text, const std::string& file_name);

// The same from a parsed document whose top-level keys the caller has checked (the studio's
// request body carries its own options beside "points" and "segments"); a segment's keys are
// checked here.
Result<FloorPath> parse_path_document(const nlohmann::json& doc, const std::string& file_name);

// A built-in shape "name:metres" (see above), sampled every 0.1 m or finer.
Result<FloorPath> make_shape(std::string_view spec);

// "TAG:FROM-TO", a motion type along an arc-length range in metres (e.g. run:20-40).
Result<PathSegment> parse_path_segment(const std::string& text);

// Where a path comes from (the path command's --path, --shape and --segment, the Python
// package's points, shape and segments): exactly one of a PATH.json file, a built-in shape
// or points; segments ("TAG:FROM-TO"), when given, replace the file's.
struct FloorPathSource {
  std::string file;
  std::string shape;
  std::vector<Vec2> points;
  std::vector<std::string> segments;
};
Result<FloorPath> make_floor_path(const FloorPathSource& source);

}  // namespace mg
