// The path check: the probe is the shape it says; the threshold chosen is the first tried whose
// probe is followed within the tolerance (else the best tried), tried upward to the ceiling;
// the deviations it reports are what path synthesis gives on the graph of that threshold; a
// library whose root stays put is not checked.
#include "motiongraph/synthesis/path_check.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "motiongraph/graph/threshold_choice.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(PathCheck, ProbeIsStraightThenRightAndLeftHalfCircles) {
  const FloorPath probe = path_check_probe();
  constexpr double kPi = std::numbers::pi;
  EXPECT_NEAR(probe.length_m(), 4.0 + 8.0 * kPi, 0.01);
  EXPECT_NEAR((probe.point_at(0.0) - Vec2(0.0, 0.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((probe.direction_at(1.0) - Vec2(0.0, -1.0)).norm(), 0.0, 1e-6);  // north
  // After the right half circle (radius 4): 8 m east, heading south.
  const double right_end = 2.0 + 4.0 * kPi;
  EXPECT_NEAR((probe.point_at(right_end) - Vec2(8.0, -2.0)).norm(), 0.0, 0.02);
  EXPECT_NEAR((probe.direction_at(right_end - 0.05) - Vec2(0.0, 1.0)).norm(), 0.0, 0.03);
  // Its middle is east-north-east of the start: 4 m east, 6 m north.
  EXPECT_NEAR((probe.point_at(2.0 + 2.0 * kPi) - Vec2(4.0, -6.0)).norm(), 0.0, 0.02);
  // The left half circle brings it 8 m further east heading north again; then 2 m north.
  EXPECT_NEAR((probe.point_at(probe.length_m()) - Vec2(16.0, -4.0)).norm(), 0.0, 0.03);
  EXPECT_NEAR((probe.point_at(right_end + 2.0 * kPi) - Vec2(12.0, 2.0)).norm(), 0.0, 0.02);
}

TEST(PathCheck, TheMirroredProbeTurnsLeftFirst) {
  const FloorPath probe = path_check_probe();
  const FloorPath mirror = path_check_probe(true);
  ASSERT_EQ(mirror.points().size(), probe.points().size());
  EXPECT_DOUBLE_EQ(mirror.length_m(), probe.length_m());
  for (double arc = 0.0; arc <= probe.length_m(); arc += 0.7) {
    const Vec2 p = probe.point_at(arc), q = mirror.point_at(arc);
    EXPECT_NEAR(q.x(), -p.x(), 1e-9) << arc;
    EXPECT_NEAR(q.y(), p.y(), 1e-9) << arc;
  }
  EXPECT_NEAR((mirror.point_at(2.0 + 4.0 * std::numbers::pi) - Vec2(-8.0, -2.0)).norm(), 0.0, 0.02);  // west
}

TEST(PathCheck, SettingsAreValidated) {
  EXPECT_TRUE(PathCheckSettings{}.validate());
  for (auto broken : {+[](PathCheckSettings& x) { x.tolerance_m = 0.0; },
                      +[](PathCheckSettings& x) { x.steps = -1; },
                      +[](PathCheckSettings& x) { x.lost_m = 0.0; },
                      +[](PathCheckSettings& x) { x.min_travel_share = 1.5; },
                      +[](PathCheckSettings& x) { x.travel_speed_mps = 0.0; },
                      +[](PathCheckSettings& x) { x.transition_penalty_m2 = -0.1; },
                      +[](PathCheckSettings& x) { x.synthesis.commit_s = 10.0; }}) {
    PathCheckSettings x;
    broken(x);
    EXPECT_FALSE(x.validate());
  }
}

struct Fixture {
  MotionDatabase db;
  FrameFeatures features;
  CandidateSearch search;
  GraphFromCandidatesSettings settings;
  double from = 0.0, ceiling = 0.0;
};

Fixture make_fixture(bool stay_put, const std::vector<std::string>& clips = {"cmu/16/16_15.amc", "cmu/16/16_16.amc",
                                                                            "cmu/16/16_35.amc", "cmu/16/16_37.amc"}) {
  Fixture f;
  f.db = test::small_database(clips);
  if (stay_put) {
    // The same clips with the root held over its first floor position: walking on the spot.
    for (DatabaseClip& clip : f.db.clips) {
      const Vec3 first = clip.motion.translations(0)[0];
      for (int i = 0; i < clip.motion.frame_count; ++i) {
        Vec3& root = clip.motion.translations(i)[0];
        root.x() = first.x();
        root.z() = first.z();
      }
    }
  }
  DistanceSettings distance;
  distance.threads = 2;
  auto layout = make_cloud_layout(f.db.skeletons[0], {});
  f.features = *make_frame_features(f.db, *layout, distance);
  f.search = *find_candidates(f.features, distance, {});
  f.from = distance_of_rms_cm(3.0, f.features);
  f.ceiling = distance_of_rms_cm(8.0, f.features);
  f.settings.transitions.max_threshold = f.ceiling;
  return f;
}

const Fixture& walking() {
  static const Fixture x = make_fixture(false);
  return x;
}

// Walks that veer left and right besides the straight ones: graphs that follow the probe.
const Fixture& turning() {
  static const Fixture x =
      make_fixture(false, {"cmu/16/16_11.amc", "cmu/16/16_13.amc", "cmu/16/16_15.amc", "cmu/16/16_16.amc"});
  return x;
}

// The graph of the fixture at one threshold, built again as the check builds it, and its
// synthesis context (which points into it: kept on the heap).
struct GraphAt {
  GraphFromCandidates graph;
  SynthesisContext context;
};
std::unique_ptr<GraphAt> graph_at(const Fixture& x, double threshold) {
  GraphFromCandidatesSettings at = x.settings;
  at.transitions.threshold = threshold;
  auto graph = graph_from_candidates(x.db, x.features, x.search, at);
  EXPECT_TRUE(graph);
  auto out = std::make_unique<GraphAt>();
  out->graph = std::move(*graph);
  auto context = make_synthesis_context(x.db, out->graph.pruned.graph);
  EXPECT_TRUE(context);
  out->context = std::move(*context);
  return out;
}

bool passes(const PathCheckPoint& p, double tolerance) {
  return p.graph && p.reached_end && p.mean_deviation_m <= tolerance;
}

// The search the check runs on each threshold's graph: Kovar's search alone, transitions priced
// at the check's own penalty.
PathSynthesisSettings check_search(const PathCheckSettings& check) {
  PathSynthesisSettings search = check.synthesis;
  search.edit_path = false;
  search.progress_retries = 0;
  search.anchor_arc = false;
  search.transition_penalty_m2 = check.transition_penalty_m2;
  return search;
}

// The point the check makes of a graph: the probe and its mirror synthesized here with
// `search`, the worse of the two (deviation as played, or as delivered when `delivered`).
PathCheckPoint probes_here(const GraphAt& graph, const PathSynthesisSettings& search, bool delivered) {
  std::array<PathCheckPoint, 2> probe;
  for (int mirrored = 0; mirrored < 2; ++mirrored) {
    auto path = synthesize_path(graph.context, path_check_probe(mirrored == 1), search);
    EXPECT_TRUE(path);
    PathCheckPoint& one = probe[mirrored];
    one.graph = true;
    one.mean_deviation_m = delivered ? path->mean_deviation_m : path->graph_mean_deviation_m;
    one.reached_end = path->reached_end;
    one.arc_covered_m = path->arc_covered_m;
    one.transitions = path->walk.transition_count(graph.graph.pruned.graph);
  }
  PathCheckPoint worse = went_better(probe[0], probe[1]) ? probe[1] : probe[0];
  worse.probe_deviations_m = {probe[0].mean_deviation_m, probe[1].mean_deviation_m};
  return worse;
}

TEST(PathCheck, TheBestProbeHasAGraphThenReachesTheEndOrCoversMostThenDeviatesLeast) {
  auto point = [](bool graph, bool end, double arc, double deviation) {
    PathCheckPoint p;
    p.graph = graph, p.reached_end = end, p.arc_covered_m = arc, p.mean_deviation_m = deviation;
    return p;
  };
  const PathCheckPoint none = point(false, false, 0.0, 0.0), stuck = point(true, false, 5.0, 0.2),
                       further = point(true, false, 20.0, 0.8), far_off = point(true, true, 29.2, 1.5),
                       close = point(true, true, 29.3, 0.1);
  const std::vector<PathCheckPoint> worst_to_best{none, stuck, further, far_off, close};
  for (size_t i = 0; i < worst_to_best.size(); ++i) {
    EXPECT_FALSE(went_better(worst_to_best[i], worst_to_best[i])) << i;
    for (size_t j = i + 1; j < worst_to_best.size(); ++j) {
      EXPECT_TRUE(went_better(worst_to_best[j], worst_to_best[i])) << j << " over " << i;
      EXPECT_FALSE(went_better(worst_to_best[i], worst_to_best[j])) << i << " over " << j;
    }
  }
  // Past the end, how far past does not count: deviation decides.
  EXPECT_TRUE(went_better(point(true, true, 29.1, 0.1), point(true, true, 29.4, 0.2)));
  // Short of it with the same cover: deviation decides.
  EXPECT_TRUE(went_better(point(true, false, 12.0, 0.3), point(true, false, 12.0, 0.4)));
}

TEST(PathCheck, UnreachableToleranceTriesEveryStepToTheCeilingAndKeepsTheBest) {
  const Fixture& x = walking();
  PathCheckSettings s;
  s.steps = 3;
  s.tolerance_m = 1e-6;
  s.synthesis.progress_retries = 0;  // `path` searching once, for the delivered probe below
  auto check = check_path_following(x.db, x.features, x.search, x.settings, x.from, x.ceiling, s);
  ASSERT_TRUE(check) << check.error().to_string();
  EXPECT_FALSE(check->skipped);
  EXPECT_GT(check->travel_share, 0.5);  // walks and runs
  EXPECT_FALSE(check->passed);
  ASSERT_EQ(check->points.size(), 4u);
  EXPECT_EQ(check->points.front().threshold, x.from);
  EXPECT_EQ(check->points.back().threshold, x.ceiling);
  for (size_t i = 1; i < check->points.size(); ++i) {
    EXPECT_GT(check->points[i].threshold, check->points[i - 1].threshold);
  }
  const PathCheckPoint* chosen = check->chosen();
  ASSERT_NE(chosen, nullptr);
  for (const PathCheckPoint& p : check->points) {
    // None beats the chosen one: reaching the end first, else getting further along the probe,
    // then deviation; ties go to the lowest.
    const bool same_reach = p.reached_end == chosen->reached_end &&
                            (p.reached_end || p.arc_covered_m == chosen->arc_covered_m);
    const bool worse_reach = (chosen->reached_end && !p.reached_end) ||
                             (!p.reached_end && !chosen->reached_end && p.arc_covered_m < chosen->arc_covered_m);
    // A higher threshold than the first competes only when its probe was not lost.
    const bool competes = p.graph && (p.threshold == x.from || p.mean_deviation_m <= s.lost_m);
    if (p.threshold < chosen->threshold) {
      EXPECT_TRUE(!competes || worse_reach || (same_reach && p.mean_deviation_m >= chosen->mean_deviation_m));
    } else if (competes) {
      EXPECT_TRUE(worse_reach || (same_reach && p.mean_deviation_m >= chosen->mean_deviation_m));
    }
    // The way along the probe the motion got: within kEndReachedM of its length when it reached
    // the end, short of that when not.
    EXPECT_GE(p.arc_covered_m, 0.0);
    EXPECT_LE(p.arc_covered_m, check->probe_length_m + 1e-9);
    if (p.reached_end) {
      EXPECT_GE(p.arc_covered_m, check->probe_length_m - kEndReachedM);
    } else {
      EXPECT_LT(p.arc_covered_m, check->probe_length_m - kEndReachedM);
    }
  }
  // None passed, so the probe was synthesized once more at the chosen threshold as `path` does
  // (the edit bending its motion onto the path): the delivered motion's deviation, as path
  // synthesis with those settings gives it on that threshold's graph, built again here.
  ASSERT_TRUE(check->delivered.has_value());
  EXPECT_EQ(check->delivered->threshold, chosen->threshold);
  ASSERT_TRUE(s.synthesis.edit_path);
  const auto graph = graph_at(x, chosen->threshold);
  const PathCheckPoint delivered = probes_here(*graph, s.synthesis, true);
  EXPECT_DOUBLE_EQ(delivered.mean_deviation_m, check->delivered->mean_deviation_m);
  EXPECT_EQ(delivered.reached_end, check->delivered->reached_end);
  EXPECT_EQ(delivered.probe_deviations_m, check->delivered->probe_deviations_m);
  const PathCheckPoint played = probes_here(*graph, check_search(s), false);
  EXPECT_NE(delivered.probe_deviations_m, played.probe_deviations_m);  // the edit did bend them
  if (chosen->threshold != x.from) {
    EXPECT_LE(chosen->mean_deviation_m, s.lost_m);
  }

  // Every probe taken for lost: the first threshold stays, whatever the others did.
  s.lost_m = 1e-9;
  auto kept = check_path_following(x.db, x.features, x.search, x.settings, x.from, x.ceiling, s);
  ASSERT_TRUE(kept) << kept.error().to_string();
  EXPECT_FALSE(kept->passed);
  EXPECT_EQ(kept->points.size(), check->points.size());
  EXPECT_EQ(kept->threshold, x.from);
}

TEST(PathCheck, ChoosesTheFirstThresholdWithinTheToleranceAndMeasuresAsPathSynthesisDoes) {
  const Fixture& x = turning();
  PathCheckSettings s;
  s.steps = 3;
  s.tolerance_m = 1e-6;
  s.mirrored = false;  // the probe as drawn alone: the fixture's walks follow its mirror nowhere
  s.synthesis.progress_retries = 0;  // the delivered probe of the first check searches once
  auto all = check_path_following(x.db, x.features, x.search, x.settings, x.from, x.ceiling, s);
  ASSERT_TRUE(all);
  // A tolerance that the last point meets: the answer is the first point meeting it.
  const PathCheckPoint& last = all->points.back();
  ASSERT_TRUE(last.graph && last.reached_end);
  s.tolerance_m = last.mean_deviation_m;
  std::vector<std::pair<double, int>> told;  // each point as it is made (the build's progress lines)
  s.tried = [&](const PathCheckPoint& point, int tried) { told.emplace_back(point.threshold, tried); };
  auto check = check_path_following(x.db, x.features, x.search, x.settings, x.from, x.ceiling, s);
  ASSERT_TRUE(check);
  EXPECT_TRUE(check->passed);
  ASSERT_EQ(told.size(), check->points.size());
  for (size_t i = 0; i < told.size(); ++i) {
    EXPECT_EQ(told[i], std::make_pair(check->points[i].threshold, static_cast<int>(i) + 1)) << i;
  }
  size_t first = 0;
  while (!passes(all->points[first], s.tolerance_m)) ++first;
  EXPECT_EQ(check->threshold, all->points[first].threshold);
  EXPECT_EQ(check->points.size(), first + 1);  // it stops there
  EXPECT_FALSE(check->delivered.has_value());   // passed: no probe beyond the graph's own
  // The deviation reported is path synthesis's on that threshold's graph, built again here, as
  // the graph plays the walk (the check judges the graph, not the edit onto the path).
  const auto graph = graph_at(x, check->threshold);
  auto path = synthesize_path(graph->context, path_check_probe(), check_search(s));
  ASSERT_TRUE(path);
  const PathCheckPoint* chosen = check->chosen();
  EXPECT_DOUBLE_EQ(path->graph_mean_deviation_m, chosen->mean_deviation_m);
  EXPECT_EQ(path->reached_end, chosen->reached_end);
  EXPECT_EQ(path->walk.transition_count(graph->graph.pruned.graph), chosen->transitions);
  EXPECT_EQ(chosen->probe_deviations_m[0], chosen->mean_deviation_m);
  EXPECT_TRUE(std::isnan(chosen->probe_deviations_m[1]));  // no mirror followed
}

// By default each threshold's point is the worse of the probe and its mirror, each measured as
// path synthesis measures it on that threshold's graph, built again here.
TEST(PathCheck, EachPointIsTheWorseOfTheProbeAndItsMirror) {
  const Fixture& x = walking();
  PathCheckSettings s;
  ASSERT_TRUE(s.mirrored);
  s.steps = 2;
  s.tolerance_m = 1e-6;
  s.lost_m = 1e9;
  s.synthesis.progress_retries = 0;
  struct Told {
    double rms_cm;
    int probe;
    double arc_m;
  };
  std::vector<Told> told;  // while each probe is searched (the build's progress lines), for each threshold
  s.searching = [&](double rms_cm, int probe, double arc_m) { told.push_back({rms_cm, probe, arc_m}); };
  auto check = check_path_following(x.db, x.features, x.search, x.settings, x.from, x.ceiling, s);
  ASSERT_TRUE(check) << check.error().to_string();
  ASSERT_EQ(check->points.size(), 3u);
  const double probe_m = path_check_probe().length_m();
  for (const PathCheckPoint& p : check->points) {
    for (int probe : {0, 1}) {
      EXPECT_TRUE(std::any_of(told.begin(), told.end(), [&](const Told& t) {
        return t.rms_cm == p.rms_cm && t.probe == probe && t.arc_m >= 0.0 && t.arc_m <= probe_m + 1e-9;
      })) << p.rms_cm << " cm, probe " << probe;
    }
  }
  for (const PathCheckPoint& p : check->points) {
    ASSERT_TRUE(p.graph);
    const PathCheckPoint here = probes_here(*graph_at(x, p.threshold), check_search(s), false);
    EXPECT_DOUBLE_EQ(here.mean_deviation_m, p.mean_deviation_m);
    EXPECT_EQ(here.reached_end, p.reached_end);
    EXPECT_EQ(here.arc_covered_m, p.arc_covered_m);
    EXPECT_EQ(here.transitions, p.transitions);
    EXPECT_EQ(here.probe_deviations_m, p.probe_deviations_m);
  }
  // Not followed, so the chosen one was delivered as `path` does, both probes again.
  ASSERT_TRUE(check->delivered.has_value());
  const PathCheckPoint delivered = probes_here(*graph_at(x, check->threshold), s.synthesis, true);
  EXPECT_DOUBLE_EQ(delivered.mean_deviation_m, check->delivered->mean_deviation_m);
  EXPECT_EQ(delivered.probe_deviations_m, check->delivered->probe_deviations_m);
}

TEST(PathCheck, ALibraryWhoseRootStaysPutIsNotChecked) {
  const Fixture x = make_fixture(true);
  PathCheckSettings s;
  auto check = check_path_following(x.db, x.features, x.search, x.settings, x.from, x.ceiling, s);
  ASSERT_TRUE(check) << check.error().to_string();
  EXPECT_TRUE(check->skipped);
  EXPECT_LT(check->travel_share, s.min_travel_share);
  EXPECT_EQ(check->threshold, x.from);
  EXPECT_EQ(check->points.size(), 1u);
  // The walking library travels: the same measure is high there.
  const Fixture& w = walking();
  GraphFromCandidatesSettings at = w.settings;
  at.transitions.threshold = w.from;
  auto graph = graph_from_candidates(w.db, w.features, w.search, at);
  ASSERT_TRUE(graph);
  auto context = make_synthesis_context(w.db, graph->pruned.graph);
  ASSERT_TRUE(context);
  EXPECT_GT(travelling_share(*context, s.travel_speed_mps), 0.5);
  EXPECT_EQ(travelling_share(*context, 100.0), 0.0);
}

TEST(PathCheck, SettingsJsonRoundTripAndMissingKeysKeepDefaults) {
  PathCheckSettings s;
  s.tolerance_m = 0.2;
  s.steps = 3;
  s.min_travel_share = 0.3;
  s.travel_speed_mps = 0.7;
  s.lost_m = 2.5;
  s.mirrored = false;
  const nlohmann::json json = s;
  const auto back = json.get<PathCheckSettings>();
  EXPECT_EQ(nlohmann::json(back), json);
  EXPECT_EQ(back.steps, 3);
  EXPECT_EQ(back.travel_speed_mps, 0.7);
  EXPECT_EQ(back.lost_m, 2.5);
  EXPECT_FALSE(back.mirrored);
  const auto defaults = nlohmann::json{{"tolerance_m", 0.3}}.get<PathCheckSettings>();
  EXPECT_EQ(defaults.tolerance_m, 0.3);
  EXPECT_EQ(defaults.steps, PathCheckSettings{}.steps);
  EXPECT_TRUE(defaults.mirrored);
}

}  // namespace
}  // namespace mg
