#include "motiongraph/synthesis/floor_path.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <span>

#include "test_data.h"

namespace mg {
namespace {

// Point at arc length s by walking the polyline from its start.
Vec2 brute_point_at(const std::vector<Vec2>& points, double s) {
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const double len = (points[i + 1] - points[i]).norm();
    if (s <= len || i + 2 == points.size()) return points[i] + std::clamp(s / len, 0.0, 1.0) * (points[i + 1] - points[i]);
    s -= len;
  }
  return points.back();
}

TEST(FloorPath, PointAtMatchesWalkingThePolyline) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> step(-1.5, 1.5);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec2> points{{0.0, 0.0}};
    for (int i = 0; i < 30; ++i) points.push_back(points.back() + Vec2(step(rng), step(rng)));
    auto path = FloorPath::create(points);
    ASSERT_TRUE(path.ok());
    std::uniform_real_distribution<double> s(-1.0, path->length_m() + 1.0);
    for (int i = 0; i < 500; ++i) {
      const double at = s(rng);
      EXPECT_LT((path->point_at(at) - brute_point_at(path->points(), std::clamp(at, 0.0, path->length_m()))).norm(), 1e-9);
    }
  }
}

// The point at arc length s by a linear scan for its segment, with point_at's arithmetic: the
// same bits are expected from the bucketed lookup and from the incremental one.
Vec2 scanned_point_at(const std::vector<Vec2>& points, double s) {
  std::vector<double> arc{0.0};
  for (size_t i = 1; i < points.size(); ++i) arc.push_back(arc.back() + (points[i] - points[i - 1]).norm());
  s = std::clamp(s, 0.0, arc.back());
  size_t i = 0;
  while (i + 2 < points.size() && arc[i + 1] <= s) ++i;
  const double u = std::clamp((s - arc[i]) / (arc[i + 1] - arc[i]), 0.0, 1.0);
  return points[i] + u * (points[i + 1] - points[i]);
}

TEST(FloorPath, IncrementalPointLookupGivesTheSameBits) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> step(-1.5, 1.5), unit(0.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Vec2> points{{0.0, 0.0}};
    const double scale = trial % 3 == 0 ? 0.03 : 1.0;  // segments shorter than the lookup's buckets too
    for (int i = 0; i < 40; ++i) points.push_back(points.back() + scale * Vec2(step(rng), step(rng)));
    auto path = FloorPath::create(points);
    ASSERT_TRUE(path.ok());
    std::vector<double> arcs{0.0};  // the vertices' arc lengths and the buckets' edges: where rounding bites
    for (size_t i = 1; i < path->points().size(); ++i) {
      arcs.push_back(arcs.back() + (path->points()[i] - path->points()[i - 1]).norm());
    }
    for (double b = 0.0; b < path->length_m(); b += 0.05) arcs.push_back(b);
    // Walks along the path: runs of non-decreasing arc lengths (steps of 0 to 0.2 m, some
    // landing exactly on a vertex or a bucket's edge), now and then a jump back, as a search
    // plays the frames of one edge after another's.
    int segment = -1;
    double s = -0.5;
    for (int i = 0; i < 3000; ++i) {
      const double r = unit(rng);
      if (r < 0.05) {
        s = unit(rng) * path->length_m();
        segment = -1;
      } else if (r < 0.1) {
        s = std::max(0.0, s - unit(rng));  // back without forgetting the segment: it is looked up again
      } else if (r < 0.2) {
        s = arcs[static_cast<size_t>(rng() % arcs.size())];
        segment = -1;
      } else if (r < 0.25) {
        // unchanged: a frame that did not move
      } else {
        s += 0.2 * unit(rng);
      }
      if (s > path->length_m() + 1.0) s = -0.5;
      const Vec2 expected = scanned_point_at(path->points(), s);
      const Vec2 bucketed = path->point_at(s);
      const Vec2 incremental = path->point_at(s, segment);
      ASSERT_EQ(bucketed.x(), expected.x()) << trial << " " << s;
      ASSERT_EQ(bucketed.y(), expected.y()) << trial << " " << s;
      ASSERT_EQ(incremental.x(), expected.x()) << trial << " " << s;
      ASSERT_EQ(incremental.y(), expected.y()) << trial << " " << s;
    }
  }
}

TEST(FloorPath, ShapesHaveTheirLengthsAndStartNorth) {
  const double pi = std::numbers::pi;
  const std::vector<std::pair<std::string, double>> shapes = {
      {"line:20", 20.0},     {"circle:5", 2 * pi * 5}, {"figure8:4", 4 * pi * 4},
      {"s-curve:100", 100.0}, {"square:10", 40.0},      {"zigzag:6", 48.0}};
  for (const auto& [spec, length] : shapes) {
    auto path = make_shape(spec);
    ASSERT_TRUE(path.ok()) << spec;
    EXPECT_NEAR(path->length_m(), length, 0.01 * length) << spec;
    EXPECT_LT(path->points().front().norm(), 1e-12) << spec;
    if (spec.starts_with("zigzag")) continue;  // its first leg: 45 degrees right of north (below)
    EXPECT_LT((path->direction_at(0.0) - Vec2(0.0, -1.0)).norm(), 0.1) << spec;
  }
  // A circle turns right (east) and comes back; a figure 8 passes the origin halfway.
  auto circle = make_shape("circle:5");
  EXPECT_GT(circle->point_at(circle->length_m() / 4).x(), 4.0);
  EXPECT_LT(circle->points().back().norm(), 1e-9);
  auto eight = make_shape("figure8:4");
  EXPECT_LT(eight->point_at(eight->length_m() / 2).norm(), 1e-9);
  EXPECT_LT(eight->point_at(3 * eight->length_m() / 4).x(), -7.0);
  // A square turns right at its corners and closes; a zigzag's legs go 45 degrees either side
  // of north, so it ends 8 L / sqrt 2 north of the origin, on its axis.
  auto square = make_shape("square:10");
  EXPECT_LT((square->point_at(10.0) - Vec2(0.0, -10.0)).norm(), 1e-9);
  EXPECT_LT((square->point_at(20.0) - Vec2(10.0, -10.0)).norm(), 1e-9);
  EXPECT_LT((square->direction_at(15.0) - Vec2(1.0, 0.0)).norm(), 1e-9);
  EXPECT_LT(square->points().back().norm(), 1e-9);
  auto zigzag = make_shape("zigzag:6");
  EXPECT_LT((zigzag->points().back() - Vec2(0.0, -48.0 / std::numbers::sqrt2)).norm(), 1e-9);
  EXPECT_LT((zigzag->direction_at(3.0) - Vec2(1.0, -1.0).normalized()).norm(), 1e-9);
  EXPECT_LT((zigzag->direction_at(9.0) - Vec2(-1.0, -1.0).normalized()).norm(), 1e-9);
}

TEST(FloorPath, DistanceAndSegments) {
  auto path = FloorPath::create({{0.0, 0.0}, {10.0, 0.0}}, {{0.0, 5.0, "walk"}, {4.0, 10.0, "run"}});
  ASSERT_TRUE(path.ok());
  EXPECT_NEAR(path->distance_to(Vec2(3.0, 2.0)), 2.0, 1e-12);
  EXPECT_NEAR(path->distance_to(Vec2(-3.0, 4.0)), 5.0, 1e-12);
  EXPECT_EQ(path->tag_at(1.0), "walk");
  EXPECT_EQ(path->tag_at(4.5), "run");  // the later segment wins where they overlap
  EXPECT_EQ(path->tag_at(10.5), "");
  // Segments are half open: [from_m, to_m).
  EXPECT_EQ(path->segment_at(0.0), 0);
  EXPECT_EQ(path->segment_at(3.999), 0);
  EXPECT_EQ(path->segment_at(4.0), 1);
  EXPECT_EQ(path->segment_at(9.999), 1);
  EXPECT_EQ(path->segment_at(10.0), -1);
  EXPECT_EQ(path->segment_at(-0.1), -1);
}

// Between the arcs segment_spans gives, segment_at gives their segment: random segments on a
// 20 m line (overlapping, some ending past its end), arcs every centimetre.
TEST(FloorPath, SegmentSpansAreWhereTheSegmentAskedForChanges) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> at(0.0, 23.0);
  for (int round = 0; round < 50; ++round) {
    std::vector<PathSegment> segments;
    for (int i = 0; i < static_cast<int>(rng() % 5); ++i) {
      const double a = at(rng), b = at(rng);
      if (a != b) segments.push_back({std::min(a, b), std::max(a, b), "walk"});
    }
    auto path = FloorPath::create({{0.0, 0.0}, {20.0, 0.0}}, segments);
    ASSERT_TRUE(path.ok());
    const auto spans = path->segment_spans();
    ASSERT_FALSE(spans.empty());
    EXPECT_EQ(spans.front().from_m, 0.0);
    for (size_t i = 1; i < spans.size(); ++i) ASSERT_LT(spans[i - 1].from_m, spans[i].from_m);
    size_t span = 0;
    for (int cm = 0; cm <= 2400; ++cm) {
      const double s = cm / 100.0;
      while (span + 1 < spans.size() && spans[span + 1].from_m <= s) ++span;
      EXPECT_EQ(spans[span].segment, path->segment_at(s)) << "round " << round << " at " << s;
    }
  }
}

// The distance to the nearest point of the path, every segment looked at.
double brute_distance(const std::vector<Vec2>& points, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const Vec2 d = points[i + 1] - points[i];
    if (d.squaredNorm() == 0.0) continue;
    const double u = std::clamp((p - points[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (points[i] + u * d - p).norm());
  }
  return best;
}

TEST(FloorPath, DistanceIsTheNearestSegmentsOverAnyPath) {
  // Shapes, long ones, random polylines (few long legs, many short ones, self-crossing), and
  // points near the path, on it and far outside its box: the grid's answer is the scan's.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<Vec2>> paths;
  for (const char* spec : {"figure8:4", "s-curve:1600", "line:10", "circle:0.3", "square:10", "zigzag:6"}) {
    auto path = make_shape(spec);
    ASSERT_TRUE(path.ok());
    paths.push_back(path->points());
  }
  for (int legs : {1, 3, 40, 2000}) {
    std::vector<Vec2> points{Vec2::Zero()};
    const double step = legs > 100 ? 0.3 : 8.0;
    for (int i = 0; i < legs; ++i) points.push_back(points.back() + step * Vec2(unit(rng) - 0.5, unit(rng) - 0.5) * 2.0);
    paths.push_back(points);
  }
  for (const std::vector<Vec2>& points : paths) {
    auto path = FloorPath::create(points);
    ASSERT_TRUE(path.ok());
    Vec2 low = points.front(), high = points.front();
    for (const Vec2& q : points) {
      low = low.cwiseMin(q);
      high = high.cwiseMax(q);
    }
    const Vec2 size = (high - low).cwiseMax(Vec2(1.0, 1.0));
    for (int trial = 0; trial < 400; ++trial) {
      Vec2 p;
      if (trial % 4 == 0) {  // on or next to the path
        p = path->point_at(unit(rng) * path->length_m()) + 0.05 * Vec2(unit(rng) - 0.5, unit(rng) - 0.5);
      } else if (trial % 4 == 1) {  // far outside the box
        p = low + Vec2(unit(rng) * 6.0 - 2.5, unit(rng) * 6.0 - 2.5).cwiseProduct(size);
      } else {
        p = low + Vec2(unit(rng) * 1.2 - 0.1, unit(rng) * 1.2 - 0.1).cwiseProduct(size);
      }
      EXPECT_NEAR(path->distance_to(p), brute_distance(path->points(), p), 1e-12) << points.size() << " points";
    }
  }
  // Points no grid cell holds: no distance, as the scan gives none.
  auto line = make_shape("line:10");
  ASSERT_TRUE(line.ok());
  EXPECT_TRUE(std::isinf(line->distance_to(Vec2(std::numeric_limits<double>::infinity(), 0.0))));
  EXPECT_TRUE(std::isnan(line->distance_to(Vec2(std::nan(""), 0.0))));
}

TEST(FloorPath, NearestArcIsTheNearestPointOfTheRange) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-6.0, 6.0), unit(0.0, 1.0);
  for (const char* spec : {"figure8:4", "s-curve:30", "line:10"}) {
    auto path = make_shape(spec);
    ASSERT_TRUE(path.ok());
    const double length = path->length_m();
    for (int trial = 0; trial < 200; ++trial) {
      const Vec2 p(coord(rng), coord(rng) - 4.0);
      // Over the whole path: the distance is distance_to's.
      const double whole = path->nearest_arc(p, -1.0, length + 1.0);
      ASSERT_GE(whole, 0.0);
      ASSERT_LE(whole, length);
      EXPECT_NEAR((path->point_at(whole) - p).norm(), path->distance_to(p), 1e-9) << spec;
      // Over a range: inside it, and no point of the range, sampled every millimetre, is nearer.
      const double from = unit(rng) * length, to = std::min(length, from + 2.0 * unit(rng));
      const double s = path->nearest_arc(p, from, to);
      ASSERT_GE(s, from);
      ASSERT_LE(s, to);
      const double found = (path->point_at(s) - p).norm();
      for (double t = from; t <= to; t += 0.001) EXPECT_GE((path->point_at(t) - p).norm(), found - 1e-9) << spec;
      // Preferring an arc changes nothing where no legs lie on one another heading against each
      // other (the figure 8's loops cross heading the same way).
      EXPECT_EQ(path->nearest_arc(p, from, to, from + (to - from) * unit(rng)), s) << spec;
    }
  }
}

TEST(FloorPath, FollowedArcsGiveProgressNotDistanceTravelled) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> sway(-0.3, 0.3);
  // A track along the figure 8 (which crosses itself at the origin, its start and its end),
  // swaying up to 0.3 m across it: each point's arc is the one it was made at, within a
  // centimetre, through the crossing and to the end; the distance the track travels is far more.
  auto path = make_shape("figure8:4");
  ASSERT_TRUE(path.ok());
  const double length = path->length_m();
  std::vector<Vec2> track;
  std::vector<double> made_at;
  double travelled = 0.0;
  for (double s = 0.0; s <= length; s += 0.03) {
    const Vec2 t = path->direction_at(s);
    // Sway along the normal, away from the crossing (where the two loops' normals would meet).
    const double across = std::min(s, length - s) < 1.0 ? 0.0 : sway(rng);
    track.push_back(path->point_at(s) + across * Vec2(-t.y(), t.x()));
    made_at.push_back(s);
    if (track.size() > 1) travelled += (track.back() - track[track.size() - 2]).norm();
  }
  track.push_back(path->point_at(length));
  made_at.push_back(length);
  const std::vector<double> arcs = path->followed_arcs(track);
  ASSERT_EQ(arcs.size(), track.size());
  for (size_t i = 0; i < arcs.size(); ++i) EXPECT_NEAR(arcs[i], made_at[i], 0.01) << i;  // the polyline's corners
  EXPECT_EQ(arcs.back(), length);
  EXPECT_GT(travelled, 2.0 * length);
  // Followed on from where an earlier part of the track left off: the same arcs.
  const size_t half = track.size() / 2;
  const std::vector<double> rest = path->followed_arcs(std::span(track).subspan(half), 1.0, arcs[half - 1]);
  EXPECT_TRUE(std::equal(rest.begin(), rest.end(), arcs.begin() + static_cast<std::ptrdiff_t>(half)));
  // Stepping sideways on the spot and back, then walking on: the steps aside add no progress.
  auto line = make_shape("line:10");
  ASSERT_TRUE(line.ok());
  const std::vector<Vec2> shuffle = {{0.0, 0.0}, {0.0, -0.5}, {0.4, -0.5}, {-0.4, -0.5}, {0.0, -0.5}, {0.0, -1.5}};
  EXPECT_EQ(line->followed_arcs(shuffle), (std::vector<double>{0.0, 0.5, 0.5, 0.5, 0.5, 1.5}));
  EXPECT_TRUE(line->followed_arcs({}).empty());
}

// A path out and back (a patrol): the legs lie on one another, or a centimetre apart. A track
// swaying across them is followed out and back, each point on its own leg, not snapped to the
// other (where the same point, or one as near, lies earlier along the path).
TEST(FloorPath, FollowedArcsStayOnTheirLegOfAPathOutAndBack) {
  for (const double apart : {0.0, 0.005, 0.01}) {
    auto path = FloorPath::create({{0.0, 0.0}, {0.0, -10.0}, {apart, 0.0}});
    ASSERT_TRUE(path.ok()) << path.error().to_string();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> sway(-0.05, 0.05);
    std::vector<Vec2> track;
    std::vector<double> made_at;
    for (double s = 0.0; s <= path->length_m(); s += 0.03) {
      const double across = std::abs(s - 10.0) < 0.3 ? 0.0 : sway(rng);
      track.push_back(path->point_at(s) + Vec2(across, 0.0));
      made_at.push_back(s);
    }
    const std::vector<double> arcs = path->followed_arcs(track);
    // (at the turn the two legs' points are one: either arc)
    for (size_t i = 0; i < arcs.size(); ++i) {
      const double tolerance = std::abs(made_at[i] - 10.0) < 0.05 ? 0.1 : 0.02;
      ASSERT_NEAR(arcs[i], made_at[i], tolerance) << apart << " m apart, point " << i;
    }
  }
  // Steps up to 0.3 m (9 m/s at 30 fps), from any point before the turn: every track ends on
  // the way back (a run at 30 fps steps 0.12 m; a walk at 10 fps as far), every point more than
  // two steps from the turn on its arc (a step straddling the turn may land on the other leg).
  auto back = FloorPath::create({{0.0, 0.0}, {0.0, -10.0}, {0.0, 0.0}});
  ASSERT_TRUE(back.ok());
  for (const double step : {0.03, 0.12, 0.2, 0.3}) {
    for (int offset = 0; offset < 50; ++offset) {
      std::vector<Vec2> track;
      std::vector<double> made_at;
      for (double s = offset * step / 50.0; s <= 20.0; s += step) {
        track.push_back(back->point_at(s));
        made_at.push_back(s);
      }
      const std::vector<double> arcs = back->followed_arcs(track);
      for (size_t i = 0; i < arcs.size(); ++i) {
        if (std::abs(made_at[i] - 10.0) >= 2.0 * step) {
          ASSERT_NEAR(arcs[i], made_at[i], 1e-9) << step << " " << offset;
        }
      }
    }
  }
  // Standing just before the turn: its arc stays; and at a corner the nearest is taken, whatever
  // is preferred (the corner cut inside, 3 cm off the way in and 4 cm off the way on).
  std::vector<Vec2> stands{back->point_at(9.8), back->point_at(9.9)};
  stands.insert(stands.end(), 5, back->point_at(9.97));
  EXPECT_NEAR(back->followed_arcs(stands, 1.0, 9.7).back(), 9.97, 1e-9);
  auto corner = FloorPath::create({{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}});
  ASSERT_TRUE(corner.ok());
  EXPECT_NEAR(corner->nearest_arc({0.96, 0.03}, 0.0, 2.0, 1.0), 0.96, 1e-9);
  EXPECT_NEAR(corner->nearest_arc({0.96, 0.05}, 0.0, 2.0, 1.0), 1.05, 1e-9);
}

TEST(FloorPath, LongPathsStayUsableAndHugeOnesAreErrors) {
  // Found by fuzzing: a point 7.8e21 m away made the bucket count overflow an int. Paths are
  // now at most 100 km long (the studio's bound) and the buckets grow with the length.
  auto huge = parse_path_json("{\"points\": [[0, 0], [3, -4], [7777777777777777777776, 0]]}", "p.json");
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.error().message.find("at most 100 km"), std::string::npos) << huge.error().message;
  EXPECT_FALSE(parse_path_json("{\"points\": [[0, 0], [1e308, 0], [-1e308, 0]]}", "p.json").ok());
  auto path = parse_path_json("{\"points\": [[0, 0], [3, -4], [99000, 0], [99000, 900]]}", "p.json");
  ASSERT_TRUE(path.ok()) << path.error().to_string();
  const std::vector<Vec2> points = {{0.0, 0.0}, {3.0, -4.0}, {99000.0, 0.0}, {99000.0, 900.0}};
  for (double s : {0.0, 2.5, 5.0, 1e3, 5e4, 0.5 * path->length_m(), path->length_m() - 450.0, path->length_m()}) {
    const Vec2 expected = brute_point_at(points, s);
    EXPECT_LE((path->point_at(s) - expected).norm(), 1e-9 * std::max(1.0, expected.norm())) << s;
  }
  EXPECT_NEAR(path->point_at(2.5).x(), 1.5, 1e-12);
  // A shape is refused by its length before its points are made (zigzag:1e7 made 8 GB of them;
  // s-curve:1e8 lost most of its to rounding and was followed for 5 cm).
  for (const char* spec : {"zigzag:1e7", "s-curve:1e8", "circle:16000", "figure8:8000", "square:25001", "line:1e5000"}) {
    auto shape = make_shape(spec);
    ASSERT_FALSE(shape.ok()) << spec;
    if (std::string(spec) != "line:1e5000") {  // not a finite number
      EXPECT_NE(shape.error().message.find("a path is at most 100000 m"), std::string::npos) << shape.error().message;
    }
  }
  EXPECT_TRUE(make_shape("square:24000").ok());
}

TEST(FloorPath, BadInputIsOneClearError) {
  const std::vector<test::ErrorCase> cases = {
      {"JSON syntax", "{\"points\": [[0, 0],\n [1, 2]\n", 3, "not valid JSON"},
      {"points missing", "{\"pts\": []}", 0, "\"points\""},
      {"point not a pair", "{\"points\": [[0, 0], [1]]}", 0, "points[1]"},
      {"one point", "{\"points\": [[0, 0], [0, 0]]}", 0, "two distinct points"},
      {"too long", "{\"points\": [[0, 0], [0, 1e300]]}", 0, "at most 100 km"},
      {"segment backwards", "{\"points\": [[0, 0], [1, 0]], \"segments\": [{\"from_m\": 2, \"to_m\": 1, \"tag\": \"run\"}]}",
       0, "from_m < to_m"},
      {"segment without tag", "{\"points\": [[0, 0], [1, 0]], \"segments\": [{\"from_m\": 0, \"to_m\": 1}]}", 0,
       "segments[0]"},
      // A misspelt key is named: "segment" would otherwise follow the path with no tags at all.
      {"misspelt segments",
       "{\"points\": [[0, 0], [1, 0]], \"segment\": [{\"from_m\": 0, \"to_m\": 1, \"tag\": \"run\"}]}", 0,
       "unknown key \"segment\""},
      {"unknown segment key",
       "{\"points\": [[0, 0], [1, 0]], \"segments\": [{\"from_m\": 0, \"to_m\": 1, \"tag\": \"run\", \"speed\": 2}]}",
       0, "segments[0]: unknown key \"speed\""},
  };
  for (const auto& c : cases) {
    auto path = parse_path_json(c.text, "p.json");
    ASSERT_FALSE(path.ok()) << c.rule;
    EXPECT_EQ(path.error().file, "p.json") << c.rule;
    test::expect_error_matches(path.error(), c);
  }
  for (const char* spec : {"line", "line:-3", "circle:abc", "spiral:4", "line:5x"}) EXPECT_FALSE(make_shape(spec).ok()) << spec;
}

}  // namespace
}  // namespace mg
