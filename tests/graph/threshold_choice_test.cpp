// The threshold chosen from the data: RMS centimetres mean what they say (a copy of a clip
// raised 5 cm is 5 cm away), the chosen threshold is the lowest tried that reaches each motion
// type's target, never above the ceiling; a ceiling under which no graph exists is said so;
// the lowest threshold that makes a graph makes one.
#include "motiongraph/graph/threshold_choice.h"

#include <fmt/ranges.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <stop_token>
#include <utility>
#include <vector>

#include "motiongraph/metric/reference_distance.h"
#include "motiongraph/database/database_loader.h"
#include "temp_folder.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(ThresholdChoice, RmsCentimetresAreTheAlignedPointDistance) {
  // A walk and the same walk 5 cm higher: no floor alignment removes a vertical offset, so
  // every pair (a, a) of the two is exactly 5 cm apart in RMS.
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"}, true, 0.0, Vec3(0.0, 0.05, 0.0));
  DistanceSettings distance;
  auto layout = make_cloud_layout(db.skeletons[0], {});
  ASSERT_TRUE(layout);
  auto features = make_frame_features(db, *layout, distance);
  ASSERT_TRUE(features);
  const std::vector<Vec3> clouds = database_clouds(db, *layout);
  const std::vector<double> weights(layout->weight.begin(), layout->weight.end());
  const int k = features->window;
  const int copy = db.clips[1].first_frame;
  for (int a : {0, 40, 90}) {
    const ReferenceDistance d = reference_distance(clouds, layout->point_count(), weights, features->taper, a,
                                                   copy + a + k - 1);
    EXPECT_NEAR(rms_cm_of_distance(d.distance, *features), 5.0, 1e-6) << "frame " << a;
  }
  EXPECT_DOUBLE_EQ(distance_of_rms_cm(rms_cm_of_distance(123.0, *features), *features), 123.0);
  EXPECT_EQ(rms_cm_of_distance(0.0, *features), 0.0);
}

TEST(ThresholdChoice, SettingsAreValidated) {
  ThresholdChoiceSettings s;
  EXPECT_TRUE(s.validate());
  for (auto broken : {+[](ThresholdChoiceSettings& x) { x.coverage = 0.0; },
                      +[](ThresholdChoiceSettings& x) { x.coverage = 1.5; },
                      +[](ThresholdChoiceSettings& x) { x.max_rms_cm = 0.0; },
                      +[](ThresholdChoiceSettings& x) { x.lowest_rms_cm = x.max_rms_cm; },
                      +[](ThresholdChoiceSettings& x) { x.grid = 1; },
                      +[](ThresholdChoiceSettings& x) { x.reachable_share = 0.0; },
                      +[](ThresholdChoiceSettings& x) { x.min_transition_rate = -1.0; },
                      +[](ThresholdChoiceSettings& x) { x.refine = -1; }}) {
    ThresholdChoiceSettings x;
    broken(x);
    EXPECT_FALSE(x.validate());
  }
}

struct Fixture {
  MotionDatabase db;
  FrameFeatures features;
  CandidateSearch search;
  GraphFromCandidatesSettings settings;
};

// `db`'s features and candidates, its walk and run (tags 0 and 1) connected.
Fixture fixture_of(MotionDatabase db) {
  Fixture f;
  f.db = std::move(db);
  DistanceSettings distance;
  distance.threads = 2;
  auto layout = make_cloud_layout(f.db.skeletons[0], {});
  f.features = *make_frame_features(f.db, *layout, distance);
  f.search = *find_candidates(f.features, distance, {});
  f.settings.connected_tags = 0b11;
  return f;
}

const Fixture& fixture() {
  static const Fixture x = [] {
    MotionDatabase db =
        test::small_database({"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_35.amc", "cmu/16/16_37.amc"});
    db.tag_names = {"walk", "run"};
    db.tag_ranges = {TagRange{0, 0, db.clips[2].first_frame},
                     TagRange{1, db.clips[2].first_frame, db.frame_count() - db.clips[2].first_frame}};
    return fixture_of(std::move(db));
  }();
  return x;
}

// What the fixture's tests ask: half of each motion type's frames, under a 30 cm ceiling.
ThresholdChoiceSettings half_under_30cm() {
  ThresholdChoiceSettings choice;
  choice.coverage = 0.5;
  choice.max_rms_cm = 30.0;
  return choice;
}

TEST(ThresholdChoice, ChoosesTheLowestThresholdTriedThatReachesTheTarget) {
  const Fixture& x = fixture();
  const ThresholdChoiceSettings choice = half_under_30cm();
  GraphFromCandidatesSettings settings = x.settings;
  settings.transitions.per_tag_thresholds = false;  // one threshold for all motion types
  auto chosen = choose_threshold(x.db, x.features, x.search, settings, choice);
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  EXPECT_EQ(chosen->tags, (std::vector<int>{0, 1}));
  EXPECT_TRUE(chosen->tag_thresholds.empty());
  const CoveragePoint& point = chosen->chosen();
  EXPECT_EQ(point.threshold, chosen->threshold);
  EXPECT_TRUE(point.graph);
  EXPECT_LE(chosen->rms_cm, 30.0 + 1e-9);
  EXPECT_GE(chosen->curve.size(), 2u);
  // Each type's target: the coverage asked, or 90 % of what the ceiling gives it when less.
  const CoveragePoint& top = chosen->curve.back();
  EXPECT_DOUBLE_EQ(top.rms_cm, 30.0);
  ASSERT_EQ(chosen->targets.size(), 2u);
  auto rate = [&](const CoveragePoint& p) { return p.transitions / (static_cast<double>(p.kept_frames) / x.db.fps); };
  auto reaches = [&](const CoveragePoint& p) {
    return p.graph && rate(p) >= chosen->target_rate && p.tag_coverage[0] >= chosen->targets[0] &&
           p.tag_coverage[1] >= chosen->targets[1];
  };
  EXPECT_DOUBLE_EQ(chosen->target_rate, std::min(5.0, rate(top)));
  EXPECT_TRUE(reaches(point));
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_DOUBLE_EQ(chosen->targets[i],
                     top.tag_coverage[i] < kMinServedShare ? 0.0 : std::min(0.5, 0.9 * top.tag_coverage[i]));
    EXPECT_GE(point.tag_coverage[i], chosen->targets[i]);
  }
  for (const CoveragePoint& p : chosen->curve) {
    if (p.threshold < chosen->threshold) {
      EXPECT_FALSE(reaches(p)) << "a lower one reached it";
    }
  }
  // The coverage it reports is the coverage a graph built at that threshold has.
  GraphFromCandidatesSettings capped = settings;  // the choice caps the tag thresholds at the ceiling
  capped.transitions.max_threshold = distance_of_rms_cm(choice.max_rms_cm, x.features);
  auto again = coverage_at(x.db, x.features, x.search, capped, chosen->threshold);
  ASSERT_TRUE(again);
  EXPECT_DOUBLE_EQ(again->coverage, point.coverage);
  ASSERT_EQ(point.tag_coverage.size(), 2u);
  EXPECT_DOUBLE_EQ(point.coverage, std::min(point.tag_coverage[0], point.tag_coverage[1]));
}

// Each point tried is told as it is tried (the build's progress lines), counted as it comes;
// a stop asked for from there ends the choice before the next point (Ctrl-C in Python).
TEST(ThresholdChoice, EachPointTriedIsToldAndAStopEndsTheChoice) {
  const Fixture& x = fixture();
  ThresholdChoiceSettings choice = half_under_30cm();
  std::vector<std::pair<double, int>> told;
  choice.tried = [&](const CoveragePoint& point, int tried) { told.emplace_back(point.threshold, tried); };
  auto chosen = choose_threshold(x.db, x.features, x.search, x.settings, choice);
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  // The curve's points (sorted by threshold at the end; tried the ceiling first), counted 1, 2, ...
  ASSERT_EQ(told.size(), chosen->curve.size());
  std::vector<double> told_thresholds, curve;
  for (size_t i = 0; i < told.size(); ++i) {
    EXPECT_EQ(told[i].second, static_cast<int>(i) + 1);
    told_thresholds.push_back(told[i].first);
    curve.push_back(chosen->curve[i].threshold);
  }
  std::sort(told_thresholds.begin(), told_thresholds.end());
  std::sort(curve.begin(), curve.end());
  EXPECT_EQ(told_thresholds, curve);
  ASSERT_GE(told.size(), 3u);
  std::stop_source source;
  choice.stop = source.get_token();
  int seen = 0;
  choice.tried = [&](const CoveragePoint&, int tried) {
    seen = tried;
    if (tried == 2) source.request_stop();
  };
  auto stopped = choose_threshold(x.db, x.features, x.search, x.settings, choice);
  ASSERT_FALSE(stopped);
  EXPECT_EQ(stopped.error().kind, ErrorKind::kStopped);
  EXPECT_EQ(seen, 2);
}

TEST(ThresholdChoice, EachMotionTypeGetsTheLowestThresholdTriedThatReachesItsTarget) {
  // Walking reaches its target far below running: per type, walking keeps its low threshold
  // while running's rises, and no point tried that reaches every target lies at or below the
  // chosen one in every type.
  const Fixture& x = fixture();
  const ThresholdChoiceSettings choice = half_under_30cm();
  auto chosen = choose_threshold(x.db, x.features, x.search, x.settings, choice);
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  ASSERT_EQ(chosen->tags, (std::vector<int>{0, 1}));
  ASSERT_EQ(chosen->tag_thresholds.size(), 2u);
  EXPECT_EQ(chosen->threshold, std::min(chosen->tag_thresholds[0], chosen->tag_thresholds[1]));
  EXPECT_LT(chosen->tag_thresholds[0], chosen->tag_thresholds[1]) << "walking's threshold below running's";
  const double ceiling = distance_of_rms_cm(choice.max_rms_cm, x.features);
  for (const double t : chosen->tag_thresholds) EXPECT_LE(t, ceiling * (1.0 + 1e-12));
  const CoveragePoint& point = chosen->chosen();
  EXPECT_EQ(point.tag_thresholds, chosen->tag_thresholds);
  auto rate = [&](const CoveragePoint& p) { return p.transitions / (static_cast<double>(p.kept_frames) / x.db.fps); };
  auto reaches = [&](const CoveragePoint& p) {
    return p.graph && rate(p) >= chosen->target_rate && p.tag_coverage[0] >= chosen->targets[0] &&
           p.tag_coverage[1] >= chosen->targets[1];
  };
  EXPECT_TRUE(reaches(point));
  for (const CoveragePoint& p : chosen->curve) {
    ASSERT_EQ(p.tag_thresholds.size(), 2u);
    EXPECT_EQ(p.threshold, std::min(p.tag_thresholds[0], p.tag_thresholds[1]));
    const bool no_higher = p.tag_thresholds[0] <= chosen->tag_thresholds[0] &&
                           p.tag_thresholds[1] <= chosen->tag_thresholds[1];
    if (no_higher && p.tag_thresholds != chosen->tag_thresholds) {
      EXPECT_FALSE(reaches(p)) << "a point lower in one type and no higher in the other reached the targets";
    }
  }
  // One threshold for both must rise to running's needs: the per-type choice keeps walking's
  // transitions lower.
  GraphFromCandidatesSettings one = x.settings;
  one.transitions.per_tag_thresholds = false;
  auto single = choose_threshold(x.db, x.features, x.search, one, choice);
  ASSERT_TRUE(single && single->reached);
  EXPECT_LT(chosen->tag_thresholds[0], single->threshold);
  // The coverage it reports is the coverage a graph built with those thresholds has.
  GraphFromCandidatesSettings capped = with_chosen_thresholds(x.settings, *chosen);
  capped.transitions.max_threshold = ceiling;
  EXPECT_EQ(capped.transitions.tag_thresholds,
            (std::vector<OwnThreshold>{{0, chosen->tag_thresholds[0]}, {1, chosen->tag_thresholds[1]}}));
  auto again = coverage_at(x.db, x.features, x.search, capped, chosen->threshold);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->tag_coverage, point.tag_coverage);
  EXPECT_EQ(again->transitions, point.transitions);
}

TEST(ThresholdChoice, AGraphShortOfTheTransitionRateRaisesEveryTypeOnlyAsFarAsTheRateNeeds) {
  // The defaults (70 %, 10 cm) on two walks and two runs: walking reaches its coverage low, and
  // running's rises; with running there, the graph is still short of transitions a second, so
  // every type rises, but only as far as the rate needs: walking stays well under the ceiling
  // (it went to the ceiling with running, where it keeps four times the transitions).
  const Fixture& x = fixture();
  const ThresholdChoiceSettings choice;
  auto chosen = choose_threshold(x.db, x.features, x.search, x.settings, choice);
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  ASSERT_EQ(chosen->tag_thresholds.size(), 2u);
  auto rate = [&](const CoveragePoint& p) { return p.transitions / (static_cast<double>(p.kept_frames) / x.db.fps); };
  auto covered = [&](const CoveragePoint& p) {
    return p.graph && p.tag_coverage[0] >= chosen->targets[0] && p.tag_coverage[1] >= chosen->targets[1];
  };
  auto reaches = [&](const CoveragePoint& p) { return covered(p) && rate(p) >= chosen->target_rate; };
  const CoveragePoint& point = chosen->chosen();
  EXPECT_TRUE(reaches(point));
  // What the case is: a point tried covers every type and is short of the rate alone.
  EXPECT_TRUE(std::any_of(chosen->curve.begin(), chosen->curve.end(),
                          [&](const CoveragePoint& p) { return covered(p) && !reaches(p); }));
  const double ceiling = distance_of_rms_cm(choice.max_rms_cm, x.features);
  EXPECT_LT(rms_cm_of_distance(chosen->tag_thresholds[0], x.features), 0.5 * choice.max_rms_cm) << "walking taken to the ceiling";
  for (const double t : chosen->tag_thresholds) EXPECT_LE(t, ceiling * (1.0 + 1e-12));
  for (const CoveragePoint& p : chosen->curve) {
    const bool no_higher = p.tag_thresholds[0] <= chosen->tag_thresholds[0] &&
                           p.tag_thresholds[1] <= chosen->tag_thresholds[1];
    if (no_higher && p.tag_thresholds != chosen->tag_thresholds) {
      EXPECT_FALSE(reaches(p)) << "a point lower in one type and no higher in the other reached the targets";
    }
  }
}

TEST(ThresholdChoice, FramesOfNoMotionTypeAreAClassOfTheirOwn) {
  // Only walking is tagged: the runs are frames of no motion type, measured and given a
  // threshold of their own (no lower than walking's: nothing bridges to frames of no type, so
  // they join the graph by the transitions between them and walking, at the lower of the two).
  const Fixture& x = fixture();
  MotionDatabase db = x.db;
  db.tag_ranges.resize(1);  // walk only
  GraphFromCandidatesSettings settings = x.settings;
  settings.connected_tags = 0b01;
  EXPECT_EQ(coverage_tags(db, settings), (std::vector<int>{0, kUntaggedClass}));
  EXPECT_EQ(coverage_tags(x.db, x.settings), (std::vector<int>{0, 1}));  // every clip typed
  EXPECT_EQ(motion_class_name(db, kUntaggedClass), "untagged");
  const ThresholdChoiceSettings choice = half_under_30cm();
  auto chosen = choose_threshold(db, x.features, x.search, settings, choice);
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  ASSERT_EQ(chosen->tag_thresholds.size(), 2u);
  EXPECT_LE(chosen->tag_thresholds[0], chosen->tag_thresholds[1]);
  const CoveragePoint& point = chosen->chosen();
  EXPECT_GE(point.tag_coverage[1], chosen->targets[1]);
  // Its coverage is the share of the untagged frames the graph built with those thresholds
  // plays, counted here frame by frame.
  GraphFromCandidatesSettings at = with_chosen_thresholds(settings, *chosen);
  at.transitions.max_threshold = distance_of_rms_cm(choice.max_rms_cm, x.features);
  EXPECT_EQ(at.transitions.tag_thresholds.back().tag, kUntaggedClass);
  auto graph = graph_from_candidates(db, x.features, x.search, at);
  ASSERT_TRUE(graph) << graph.error().to_string();
  const MotionGraph& g = graph->pruned.graph;
  const int runs = db.clips[2].first_frame;
  std::vector<char> played(static_cast<size_t>(db.frame_count()), 0);
  for (const GraphEdge& e : g.edges) {
    if (e.transition) continue;
    for (int f = g.nodes[e.from_node].frame; f < g.nodes[e.to_node].frame; ++f) played[f] = 1;
  }
  const long long untagged_played = std::count(played.begin() + runs, played.end(), 1);
  EXPECT_DOUBLE_EQ(point.tag_coverage[1],
                   static_cast<double>(untagged_played) / static_cast<double>(db.frame_count() - runs));
  // The selection gives the class its own threshold, over the run-run candidates.
  const auto& own = graph->transitions.selection.tag_thresholds;
  ASSERT_EQ(own.size(), 2u);
  const auto untagged =
      std::find_if(own.begin(), own.end(), [](const TagThreshold& t) { return t.tag == kUntaggedClass; });
  ASSERT_NE(untagged, own.end());
  EXPECT_GT(untagged->candidates, 0);
  EXPECT_TRUE(untagged->given);
  EXPECT_EQ(untagged->threshold, chosen->tag_thresholds[1]);
}

// The choice on a library whose every clip has a motion type, whatever frames of none they hold:
// walk and run measured, no untagged class.
void expect_typed_classes_only(const MotionDatabase& db, const Fixture& x) {
  EXPECT_EQ(coverage_tags(db, x.settings), (std::vector<int>{0, 1}));
  auto chosen = choose_threshold(db, x.features, x.search, x.settings, half_under_30cm());
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  ASSERT_EQ(chosen->tags, (std::vector<int>{0, 1}));
  ASSERT_EQ(chosen->tag_thresholds.size(), 2u);
  for (const CoveragePoint& p : chosen->curve) EXPECT_EQ(p.tag_coverage.size(), 2u);
}

TEST(ThresholdChoice, FramesOfNoTypeInATypedClipAreItsWayInAndOutNotAClass) {
  // Walk left off the first and last 15 frames of each walk (where a walk's root stands, as
  // travel_tags leaves it off): those frames are how the graph enters and leaves walking, joined
  // through windows mixed with it; measured as a class of their own, they held a library's every
  // type at the ceiling (the complete CMU subject 16, where they are 2 % of the frames). Only
  // clips of no type at all make the untagged class.
  const Fixture& x = fixture();
  MotionDatabase db = x.db;
  const int left_off = 15;
  db.tag_ranges.clear();
  for (int c = 0; c < 2; ++c) {
    db.tag_ranges.push_back({0, db.clips[c].first_frame + left_off, db.clips[c].frame_count - 2 * left_off});
  }
  for (int c = 2; c < 4; ++c) db.tag_ranges.push_back({1, db.clips[c].first_frame, db.clips[c].frame_count});
  const std::vector<char> none(static_cast<size_t>(db.frame_count()), 0);
  EXPECT_EQ(untagged_class_frames(db, x.settings.connected_tags), none);
  expect_typed_classes_only(db, x);

  // The runs untagged too: the class is their clips, every frame of them and nothing else.
  db.tag_ranges.resize(2);
  GraphFromCandidatesSettings settings = x.settings;
  settings.connected_tags = 0b01;
  std::vector<char> runs(static_cast<size_t>(db.frame_count()), 0);
  std::fill(runs.begin() + db.clips[2].first_frame, runs.end(), 1);
  EXPECT_EQ(untagged_class_frames(db, settings.connected_tags), runs);
  EXPECT_EQ(coverage_tags(db, settings), (std::vector<int>{0, kUntaggedClass}));
  const ThresholdChoiceSettings choice = half_under_30cm();
  auto chosen = choose_threshold(db, x.features, x.search, settings, choice);
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  GraphFromCandidatesSettings at = with_chosen_thresholds(settings, *chosen);
  at.transitions.max_threshold = distance_of_rms_cm(choice.max_rms_cm, x.features);
  auto graph = graph_from_candidates(db, x.features, x.search, at);
  ASSERT_TRUE(graph) << graph.error().to_string();
  // Its coverage counts those frames alone: the share of the runs' frames the graph plays,
  // counted here frame by frame.
  const MotionGraph& g = graph->pruned.graph;
  long long played = 0;
  for (const GraphEdge& e : g.edges) {
    if (e.transition) continue;
    for (int f = g.nodes[e.from_node].frame; f < g.nodes[e.to_node].frame; ++f) played += runs[f];
  }
  EXPECT_GT(played, 0);
  EXPECT_DOUBLE_EQ(chosen->chosen().tag_coverage[1],
                   static_cast<double>(played) / static_cast<double>(db.frame_count() - db.clips[2].first_frame));
  // Its threshold governs the candidates whose two windows lie in its clips, not those in the
  // walks' left-off frames.
  const int k = x.features.window;
  auto within = [&](int first) {
    return first >= 0 && first + k <= db.frame_count() &&
           std::all_of(runs.begin() + first, runs.begin() + first + k, [](char r) { return r != 0; });
  };
  auto left_off_window = [&](int first) {
    if (first < 0 || first + k > db.clips[2].first_frame) return false;
    for (int f = first; f < first + k; ++f) {
      if ((db.frame_tags()[f] & 1) != 0) return false;
    }
    return true;
  };
  long long in_class = 0, in_left_off = 0;
  for (const Transition& t : x.search.minima) {
    in_class += within(t.from_frame) && within(t.to_frame - k + 1) ? 1 : 0;
    in_left_off += left_off_window(t.from_frame) && left_off_window(t.to_frame - k + 1) ? 1 : 0;
  }
  EXPECT_GT(in_left_off, 0);  // the case is there
  const auto& own = graph->transitions.selection.tag_thresholds;
  const auto untagged =
      std::find_if(own.begin(), own.end(), [](const TagThreshold& t) { return t.tag == kUntaggedClass; });
  ASSERT_NE(untagged, own.end());
  EXPECT_EQ(untagged->candidates, in_class);
}

TEST(ThresholdChoice, ATypeTheCeilingGivesNothingTakesTheGlobalThreshold) {
  // A third type on the last 6 frames of a walk (fewer than a window: no transition leaves
  // them, so no graph plays them at any threshold) wants nothing; it follows the lowest of the
  // others' thresholds instead of holding the global one at the grid's first level.
  const Fixture& x = fixture();
  MotionDatabase db = x.db;
  db.tag_names.push_back("jump");
  const int end = db.clips[1].first_frame + db.clips[1].frame_count;
  db.tag_ranges.push_back(TagRange{2, end - 6, 6});
  GraphFromCandidatesSettings settings = x.settings;
  settings.connected_tags = 0b111;
  const ThresholdChoiceSettings choice = half_under_30cm();
  auto chosen = choose_threshold(db, x.features, x.search, settings, choice);
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  ASSERT_EQ(chosen->tags, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(chosen->targets[2], 0.0);
  EXPECT_EQ(chosen->chosen().tag_coverage[2], 0.0);
  ASSERT_EQ(chosen->tag_thresholds.size(), 3u);
  EXPECT_EQ(chosen->threshold, std::min(chosen->tag_thresholds[0], chosen->tag_thresholds[1]));
  EXPECT_EQ(chosen->tag_thresholds[2], chosen->threshold);
  EXPECT_GT(chosen->rms_cm, 1.5 * choice.lowest_rms_cm);
  for (const CoveragePoint& p : chosen->curve) {
    EXPECT_EQ(p.tag_thresholds[2], std::min(p.tag_thresholds[0], p.tag_thresholds[1]));
  }
}

TEST(ThresholdChoice, ATypeTheCeilingGivesASliverOfTakesTheGlobalThreshold) {
  // A third type on the last 6 frames of each clip (no graph plays them) and on 1 frame amid the
  // first walk (which the graph at a 10 cm ceiling plays): the ceiling serves it 1 of its 25
  // frames, under kMinServedShare, so it wants nothing rather than take the threshold to the
  // ceiling for more frames it cannot get.
  const Fixture& x = fixture();
  MotionDatabase db = x.db;
  db.tag_names.push_back("jump");
  for (const DatabaseClip& clip : db.clips) db.tag_ranges.push_back(TagRange{2, clip.first_frame + clip.frame_count - 6, 6});
  db.tag_ranges.push_back(TagRange{2, db.clips[0].first_frame + db.clips[0].frame_count / 2, 1});
  GraphFromCandidatesSettings settings = x.settings;
  settings.connected_tags = 0b111;
  ThresholdChoiceSettings choice = half_under_30cm();
  choice.max_rms_cm = 10.0;
  auto chosen = choose_threshold(db, x.features, x.search, settings, choice);
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  ASSERT_EQ(chosen->tags, (std::vector<int>{0, 1, 2}));
  const double served = chosen->curve.back().tag_coverage[2];
  ASSERT_GT(served, 0.0);
  ASSERT_LT(served, 0.1);  // the sliver kMinServedShare names
  EXPECT_DOUBLE_EQ(served, 1.0 / 25.0);
  EXPECT_EQ(chosen->targets[2], 0.0);
  ASSERT_EQ(chosen->tag_thresholds.size(), 3u);
  EXPECT_EQ(chosen->threshold, std::min(chosen->tag_thresholds[0], chosen->tag_thresholds[1]));
  EXPECT_EQ(chosen->tag_thresholds[2], chosen->threshold);
  EXPECT_LT(chosen->rms_cm, choice.max_rms_cm);
}

TEST(ThresholdChoice, FramesOfNoTypeAmidTypedClipsAreNoClass) {
  // Frames of no motion type in typed clips: the last 6 of the second walk and of the second run
  // (no graph plays them) and two in the middle of the first walk (which graphs play, one of
  // them at the ceiling). As a class they were a sliver of its 14; they are no class now.
  const Fixture& x = fixture();
  MotionDatabase db = x.db;
  const int span = 2;
  const int middle = db.clips[0].first_frame + db.clips[0].frame_count / 2 - 1;
  const int walk_end = db.clips[1].first_frame + db.clips[1].frame_count - 6;
  const int run_end = db.clips[3].first_frame + db.clips[3].frame_count - 6;
  db.tag_ranges = {TagRange{0, 0, middle}, TagRange{0, middle + span, walk_end - middle - span},
                   TagRange{1, db.clips[2].first_frame, run_end - db.clips[2].first_frame}};
  expect_typed_classes_only(db, x);
}

TEST(ThresholdChoice, CoverageIsThatOfTheGraphBuildWrites) {
  // coverage_at prunes once when there is no spacing; the graph `build` writes is pruned,
  // rebuilt from the survivors and pruned again. Their counts must agree, spaced or not.
  const Fixture& x = fixture();
  for (const int max_out : {0, 2}) {
    GraphFromCandidatesSettings settings = x.settings;
    settings.spacing.max_out = max_out;
    for (const double rms : {2.0, 3.0, 4.5, 7.0}) {
      const double threshold = distance_of_rms_cm(rms, x.features);
      auto point = coverage_at(x.db, x.features, x.search, settings, threshold);
      ASSERT_TRUE(point);
      GraphFromCandidatesSettings at = settings;
      at.transitions.threshold = threshold;
      auto graph = graph_from_candidates(x.db, x.features, x.search, at);
      ASSERT_EQ(point->graph, static_cast<bool>(graph)) << rms << " cm";
      if (!graph) continue;
      const GraphStatistics& after = graph->pruned.prune.after;
      EXPECT_EQ(point->kept_frames, after.clip_frames) << rms << " cm, max_out " << max_out;
      EXPECT_EQ(point->transitions, after.transitions) << rms << " cm, max_out " << max_out;
      for (const TagStatistics& t : after.tags) {
        EXPECT_DOUBLE_EQ(point->tag_coverage[t.tag], static_cast<double>(t.frames) / t.database_frames);
      }
    }
  }
}

TEST(ThresholdChoice, NoGraphUnderTheCeilingIsSaidSo) {
  const Fixture& x = fixture();
  ThresholdChoiceSettings choice;
  choice.lowest_rms_cm = 0.01;
  choice.max_rms_cm = 0.02;  // 0.2 mm: no transition at all
  auto chosen = choose_threshold(x.db, x.features, x.search, x.settings, choice);
  ASSERT_TRUE(chosen);
  EXPECT_FALSE(chosen->reached);
  EXPECT_FALSE(chosen->chosen().graph);
  EXPECT_EQ(chosen->curve.size(), static_cast<size_t>(choice.grid));  // no bracket, no refinement
  for (const CoveragePoint& p : chosen->curve) EXPECT_LE(p.rms_cm, 0.02 + 1e-9);
}

TEST(ThresholdChoice, LowestGraphThresholdMakesAGraph) {
  const Fixture& x = fixture();
  const double tiny = distance_of_rms_cm(0.01, x.features);
  auto none = coverage_at(x.db, x.features, x.search, x.settings, tiny);
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->graph);  // 0.1 mm: no transition at all
  auto lowest = lowest_graph_threshold(x.db, x.features, x.search, x.settings, tiny);
  ASSERT_TRUE(lowest);
  ASSERT_TRUE(lowest->has_value());
  EXPECT_TRUE((*lowest)->graph);
  EXPECT_GT((*lowest)->threshold, tiny);
  auto check = coverage_at(x.db, x.features, x.search, x.settings, (*lowest)->threshold);
  ASSERT_TRUE(check);
  EXPECT_TRUE(check->graph);
}

TEST(ThresholdChoice, SettingsJsonRoundTripAndMissingKeysKeepDefaults) {
  ThresholdChoiceSettings s;
  s.coverage = 0.55;
  s.max_rms_cm = 7.5;
  s.reachable_share = 0.8;
  s.min_transition_rate = 3.0;
  s.lowest_rms_cm = 0.25;
  s.grid = 9;
  s.refine = 2;
  const nlohmann::json json = s;
  const auto back = json.get<ThresholdChoiceSettings>();
  EXPECT_EQ(nlohmann::json(back), json);
  EXPECT_EQ(back.coverage, 0.55);
  EXPECT_EQ(back.grid, 9);
  EXPECT_EQ(json.at("coverage_target"), 0.55);  // the report's name for it
  const auto defaults = nlohmann::json::object().get<ThresholdChoiceSettings>();
  EXPECT_EQ(nlohmann::json(defaults), nlohmann::json(ThresholdChoiceSettings{}));
}

// Walks and a run, typed, and the first 25 frames of the first walk raised 6 cm, of no type: too
// short to loop, the copy has no core to bridge (bridges.h), and joins the graph only through
// windows into the walks, which pass the lower of the two classes' thresholds, about 6 cm.
// Walking rises to take it in, and as a minor share of the frames (kMinorUntaggedShare) the
// copy is said to hold the types up.
TEST(ThresholdChoice, AMinorClassOfNoTypeThatJoinsOnlyThroughRaisedTypesIsSaidToHoldThemUp) {
  MotionDatabase db = test::small_database(
      {"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_17.amc", "cmu/16/16_35.amc"}, true, 0.0,
      Vec3(0.0, 0.06, 0.0));
  DatabaseClip& raised = db.clips.back();
  raised.motion = raised.motion.slice(0, 25);
  raised.frame_count = 25;
  const int copy = raised.first_frame;
  const int runs = db.clips[3].first_frame;
  db.tag_names = {"walk", "run"};
  db.tag_ranges = {TagRange{0, 0, runs}, TagRange{1, runs, copy - runs}};
  ASSERT_LE(static_cast<double>(db.frame_count() - copy) / db.frame_count(), kMinorUntaggedShare);
  const Fixture x = fixture_of(std::move(db));
  auto chosen = choose_threshold(x.db, x.features, x.search, x.settings, ThresholdChoiceSettings{});
  ASSERT_TRUE(chosen) << chosen.error().to_string();
  ASSERT_TRUE(chosen->reached);
  ASSERT_EQ(chosen->tags, (std::vector<int>{0, 1, kUntaggedClass}));
  EXPECT_TRUE(chosen->untagged_holds);
  const CoveragePoint& point = chosen->chosen();
  EXPECT_GT(chosen->targets[2], 0.0);
  EXPECT_GE(point.tag_coverage[2], chosen->targets[2]);
  EXPECT_GE(point.tag_coverage[0], chosen->targets[0]);
  EXPECT_GT(rms_cm_of_distance(chosen->tag_thresholds[0], x.features), 4.0);
  // Whole, the copy loops: bridged to the walks, it holds nothing up, and walking stays low.
  MotionDatabase whole = test::small_database(
      {"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_17.amc", "cmu/16/16_35.amc"}, true, 0.0,
      Vec3(0.0, 0.06, 0.0));
  whole.tag_names = {"walk", "run"};
  whole.tag_ranges = {TagRange{0, 0, runs}, TagRange{1, runs, copy - runs}};
  const Fixture y = fixture_of(std::move(whole));
  auto bridged = choose_threshold(y.db, y.features, y.search, y.settings, ThresholdChoiceSettings{});
  ASSERT_TRUE(bridged) << bridged.error().to_string();
  ASSERT_TRUE(bridged->reached);
  EXPECT_FALSE(bridged->untagged_holds);
  EXPECT_GE(bridged->chosen().tag_coverage[2], bridged->targets[2]);
  EXPECT_LT(rms_cm_of_distance(bridged->tag_thresholds[0], y.features), 3.0);
}

}  // namespace
}  // namespace mg
