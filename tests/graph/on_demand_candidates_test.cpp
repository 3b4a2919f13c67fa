// The minima above the pruned stage's ceiling, on demand: a pair's level promises every minimum
// between its cores up to it (checked against the exhaustive stage's minima), and the pruned
// stage's candidates with them give the exhaustive stage's transitions, bridges and threshold
// choice (one threshold for all motion types, or one searched for per type), bit for bit, on a
// walk and run library whose bridges lie far above the ceiling.
#include "motiongraph/graph/on_demand_candidates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/graph/threshold_choice.h"
#include "test_data.h"

namespace mg {
namespace {

constexpr int kTile = 64;

struct Library {
  MotionDatabase db;
  FrameFeatures features;
  CandidateSearch exhaustive;
  PrunedSearchSettings pruned;
};

// Subject 16's two walks and five runs, tagged (or the runs of no type): walk to run bridges lie
// near 20 cm RMS.
Library make_library(bool runs_typed) {
  Library l;
  l.db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_35.amc", "cmu/16/16_37.amc",
                               "cmu/16/16_39.amc", "cmu/16/16_41.amc", "cmu/16/16_43.amc"});
  l.db.tag_names = {"walk", "run"};
  const int runs = l.db.clips[2].first_frame;
  l.db.tag_ranges = {TagRange{0, 0, runs}};
  if (runs_typed) l.db.tag_ranges.push_back(TagRange{1, runs, l.db.frame_count() - runs});
  else l.db.tag_names.pop_back();
  DistanceSettings distance;
  distance.tile_frames = kTile;
  distance.threads = 2;
  auto layout = make_cloud_layout(l.db.skeletons[0], {});
  l.features = *make_frame_features(l.db, *layout, distance);
  l.exhaustive = *find_candidates(l.features, distance, {});
  l.pruned.tile_frames = kTile;
  l.pruned.threads = 2;
  return l;
}

const Library& library() {
  static const Library x = make_library(true);
  return x;
}

CandidateSearch pruned_search(double ceiling) {
  const Library& l = library();
  auto found = find_candidates_pruned(l.features, ceiling, {}, l.pruned);
  EXPECT_TRUE(found) << (found ? "" : found.error().to_string());
  return found ? std::move(*found) : CandidateSearch{};
}

// The same search as pruned_search, with what the stage made beyond it kept as `build` keeps it.
CandidateSearch pruned_search_keeping(double ceiling, PrunedStageWork& work) {
  const Library& l = library();
  auto plan = plan_pruned_search(l.features, ceiling, l.pruned);
  EXPECT_TRUE(plan && !plan->items.empty());
  if (!plan || plan->items.empty()) return CandidateSearch{};
  auto found = find_candidates(l.features, plan->distance, {}, {}, plan->items, plan->sides);
  EXPECT_TRUE(found);
  if (!found) return CandidateSearch{};
  work.embedding = std::move(plan->embedding);
  work.tiles = std::move(plan->tiles);
  for (const Transition& t : found->minima) {
    if (t.distance > ceiling) work.above.push_back(t);
  }
  finish_pruned_search(l.features, ceiling, *found);
  return std::move(*found);
}

void expect_same(std::span<const Transition> a, std::span<const Transition> b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].from_frame, b[i].from_frame) << what << " " << i;
    EXPECT_EQ(a[i].to_frame, b[i].to_frame) << what << " " << i;
    EXPECT_EQ(a[i].distance, b[i].distance) << what << " " << i;
    EXPECT_EQ(a[i].yaw_rad, b[i].yaw_rad) << what << " " << i;
  }
}

// Cores of walk (tag 0) and run (tag 1): every frame of its tag kept where keep(frame).
template <class Keep>
std::vector<std::vector<char>> cores_where(const std::vector<TagMask>& tags, Keep keep) {
  std::vector<std::vector<char>> cores(2, std::vector<char>(tags.size(), 0));
  for (size_t f = 0; f < tags.size(); ++f) {
    for (int t = 0; t < 2; ++t) cores[t][f] = (tags[f] >> t & 1) && keep(static_cast<int>(f));
  }
  return cores;
}

// Every minimum from a walk frame of its core to a run frame of its core, up to the level, is
// known once (in the search's minima at or below the ceiling, in `above` over it). Returns how
// many of them lie above the ceiling.
long long expect_known_up_to(const OnDemandCandidates& more, const CandidateSearch& search, double ceiling,
                        const std::vector<std::vector<char>>& cores, double level) {
  const Library& l = library();
  const std::vector<TagMask> tags = l.db.frame_tags();
  long long checked = 0;
  for (const Transition& m : l.exhaustive.minima) {
    if (!(tags[m.from_frame] & 1) || !(tags[m.to_frame] & 2) || m.distance > level) continue;
    if (!cores[0][m.from_frame] || !cores[1][m.to_frame]) continue;
    const auto& known = m.distance <= ceiling ? search.minima : more.above();
    const auto same = [&](const Transition& t) {
      return t.from_frame == m.from_frame && t.to_frame == m.to_frame && t.distance == m.distance;
    };
    EXPECT_EQ(std::count_if(known.begin(), known.end(), same), 1) << m.from_frame << " -> " << m.to_frame;
    checked += m.distance > ceiling ? 1 : 0;
  }
  return checked;
}

TEST(OnDemandCandidates, ALevelHoldsEveryMinimumOfItsRegionUpToIt) {
  const Library& l = library();
  const double ceiling = distance_of_rms_cm(3.0, l.features);
  const CandidateSearch search = pruned_search(ceiling);
  const std::vector<TagMask> tags = l.db.frame_tags();
  const TagPair walk_to_run{0, 1};
  // Cores of a few stretches first (the low thresholds' small ones): their levels rise by
  // computing fewer tiles than whole motion types need.
  OnDemandCandidates more(l.features, search, l.pruned.embedding, l.pruned.threads);
  const auto small = cores_where(tags, [](int f) { return f % 300 < 60; });
  double previous = ceiling;
  long long above_small = 0, above_whole = 0;
  for (int step = 0; step < 3; ++step) {
    ASSERT_TRUE(more.raise(std::span(&walk_to_run, 1), small));
    const double level = more.levels(small)[kBridgeTags * 0 + 1];
    EXPECT_GT(level, previous);
    previous = level;
    EXPECT_EQ(more.levels(small)[kBridgeTags * 1 + 0], ceiling) << "run to walk was not raised";
    above_small = expect_known_up_to(more, search, ceiling, small, level);
  }
  EXPECT_GT(above_small, 0) << "no minimum above the ceiling was looked at";
  const long long small_tiles = more.statistics().tiles;
  EXPECT_GT(small_tiles, 0);
  // The whole motion types: the cores grown, the level falls back where the new frames' tiles
  // are known only to the ceiling, and rises again.
  const auto whole = cores_where(tags, [](int) { return true; });
  EXPECT_EQ(more.levels(whole)[kBridgeTags * 0 + 1], ceiling);
  OnDemandCandidates fresh(l.features, search, l.pruned.embedding, l.pruned.threads);
  for (int step = 0; step < 3; ++step) {
    for (OnDemandCandidates* m : {&more, &fresh}) ASSERT_TRUE(m->raise(std::span(&walk_to_run, 1), whole));
    const double level = more.levels(whole)[kBridgeTags * 0 + 1];
    EXPECT_EQ(level, fresh.levels(whole)[kBridgeTags * 0 + 1]);
    above_whole = expect_known_up_to(more, search, ceiling, whole, level);
    EXPECT_EQ(expect_known_up_to(fresh, search, ceiling, whole, level), above_whole);
  }
  EXPECT_GT(above_whole, above_small);
  EXPECT_LT(small_tiles, fresh.statistics().tiles);
  // Everything found above the ceiling is a minimum of the exhaustive stage, above the ceiling.
  for (const Transition& t : more.above()) {
    EXPECT_GT(t.distance, ceiling);
    EXPECT_TRUE(std::binary_search(l.exhaustive.minima.begin(), l.exhaustive.minima.end(), t,
                                   [](const Transition& x, const Transition& y) {
                                     return x.from_frame != y.from_frame ? x.from_frame < y.from_frame
                                                                         : x.to_frame < y.to_frame;
                                   }));
  }
  EXPECT_TRUE(std::is_sorted(more.above().begin(), more.above().end(), [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  }));
  // Raised to the end, the level is every pair; a tag without a core has nothing to raise.
  for (int step = 0; step < 8; ++step) ASSERT_TRUE(more.raise(std::span(&walk_to_run, 1), whole));
  EXPECT_EQ(more.levels(whole)[1], std::numeric_limits<double>::infinity());
  const std::vector<std::vector<char>> coreless{whole[0], {}};
  EXPECT_EQ(fresh.levels(coreless)[1], std::numeric_limits<double>::infinity());
}

TEST(OnDemandCandidates, PrunedCandidatesGiveTheExhaustiveTransitionsAndBridges) {
  const Library& l = library();
  for (const double ceiling_cm : {6.0, 10.0}) {
    const double ceiling = distance_of_rms_cm(ceiling_cm, l.features);
    const CandidateSearch search = pruned_search(ceiling);
    OnDemandCandidates more(l.features, search, l.pruned.embedding, l.pruned.threads);
    // And given the stage's own work: its embedding, tiles and their minima above the ceiling.
    PrunedStageWork work;
    const CandidateSearch kept = pruned_search_keeping(ceiling, work);
    ASSERT_FALSE(work.above.empty());
    ASSERT_EQ(kept.minima.size(), search.minima.size());
    OnDemandCandidates reusing(l.features, kept, l.pruned.embedding, l.pruned.threads, std::move(work));
    for (const double rms : {2.0, 4.0, ceiling_cm}) {
      for (const double cap_cm : {0.0, 15.0, 22.0}) {
       for (const bool given : {false, true}) {
        GraphFromCandidatesSettings settings;
        settings.connected_tags = 0b11;
        settings.transitions.per_tag_thresholds = given;
        settings.transitions.threshold = distance_of_rms_cm(rms, l.features);
        settings.transitions.max_threshold = ceiling;
        settings.bridges.max_distance = cap_cm > 0.0 ? distance_of_rms_cm(cap_cm, l.features) : -1.0;
        if (given) {  // running's own threshold above walking's, both under the ceiling
          settings.transitions.threshold = distance_of_rms_cm(0.5 * rms, l.features);
          settings.transitions.tag_thresholds = {{0, distance_of_rms_cm(0.7 * rms, l.features)},
                                                 {1, distance_of_rms_cm(rms, l.features)}};
        }
        SCOPED_TRACE(testing::Message() << "ceiling " << ceiling_cm << " cm, threshold " << rms << " cm, cap "
                                        << cap_cm << " cm, given per-tag thresholds " << given);
        auto want = select_transitions_with_bridges(l.db, l.features, l.exhaustive, settings);
        auto got = select_transitions_with_bridges(l.db, l.features, search, settings, &more);
        auto again = select_transitions_with_bridges(l.db, l.features, kept, settings, &reusing);
        ASSERT_TRUE(want && got && again);
        expect_same(want->selection.transitions, again->selection.transitions, "transitions, reusing");
        expect_same(want->bridges, again->bridges, "bridges, reusing");
        ASSERT_EQ(want->unjoined.size(), again->unjoined.size());
        expect_same(want->selection.transitions, got->selection.transitions, "transitions");
        expect_same(want->bridges, got->bridges, "bridges");
        ASSERT_EQ(want->unjoined.size(), got->unjoined.size());
        for (size_t i = 0; i < want->unjoined.size(); ++i) {
          EXPECT_EQ(want->unjoined[i].reason, got->unjoined[i].reason);
          EXPECT_EQ(want->unjoined[i].best_distance, got->unjoined[i].best_distance);
        }
        EXPECT_EQ(want->bridge_blends, got->bridge_blends);
        ASSERT_EQ(want->selection.tag_thresholds.size(), given ? 2u : 0u);
        ASSERT_EQ(got->selection.tag_thresholds.size(), want->selection.tag_thresholds.size());
        for (size_t i = 0; i < want->selection.tag_thresholds.size(); ++i) {
          EXPECT_EQ(want->selection.tag_thresholds[i].threshold, got->selection.tag_thresholds[i].threshold);
          EXPECT_TRUE(got->selection.tag_thresholds[i].given);
        }
       }
      }
    }
    // The walk to run bridges lie far above either ceiling: they were found on demand, with
    // fewer tiles when the stage's own are known.
    EXPECT_GT(more.statistics().raises, 0);
    EXPECT_FALSE(more.above().empty());
    EXPECT_LT(reusing.statistics().tiles, more.statistics().tiles);
  }
}

// The runs of no motion type: the untagged class, bridged to the walks as a type is (bridges.h),
// gets from the pruned stage's candidates, its windows tagged for the search on demand, the
// bridges the exhaustive stage's give, far above the ceiling.
TEST(OnDemandCandidates, PrunedCandidatesBridgeTheUntaggedClassAsTheExhaustiveDo) {
  const Library l = make_library(false);
  const double ceiling = distance_of_rms_cm(6.0, l.features);
  auto search = find_candidates_pruned(l.features, ceiling, {}, l.pruned);
  ASSERT_TRUE(search) << search.error().to_string();
  OnDemandCandidates more(l.features, *search, l.pruned.embedding, l.pruned.threads);
  const int runs = l.db.clips[2].first_frame;
  for (const double rms : {4.0, 5.0}) {  // (at 2 cm the runs form no loop of their own to bridge)
    SCOPED_TRACE(testing::Message() << "threshold " << rms << " cm");
    GraphFromCandidatesSettings settings;
    settings.connected_tags = 0b1;
    settings.transitions.per_tag_thresholds = false;
    settings.transitions.threshold = distance_of_rms_cm(rms, l.features);
    settings.transitions.max_threshold = ceiling;
    auto want = select_transitions_with_bridges(l.db, l.features, l.exhaustive, settings);
    auto got = select_transitions_with_bridges(l.db, l.features, *search, settings, &more);
    ASSERT_TRUE(want) << want.error().to_string();
    ASSERT_TRUE(got) << got.error().to_string();
    expect_same(want->selection.transitions, got->selection.transitions, "transitions");
    expect_same(want->bridges, got->bridges, "bridges");
    const auto crosses = [&](const Transition& t) { return (t.from_frame < runs) != (t.to_frame < runs); };
    EXPECT_GE(std::count_if(want->bridges.begin(), want->bridges.end(), crosses), 2);
    EXPECT_TRUE(std::any_of(want->bridges.begin(), want->bridges.end(),
                            [&](const Transition& t) { return crosses(t) && t.distance > ceiling; }));
  }
  EXPECT_GT(more.statistics().raises, 0);
}

TEST(OnDemandCandidates, PrunedCandidatesGiveTheExhaustiveThresholdChoice) {
  const Library& l = library();
  ThresholdChoiceSettings choice;
  choice.max_rms_cm = 6.0;
  choice.grid = 6;
  choice.refine = 3;
  const double ceiling = distance_of_rms_cm(choice.max_rms_cm, l.features);
  const CandidateSearch search = pruned_search(ceiling);
  OnDemandCandidates more(l.features, search, l.pruned.embedding, l.pruned.threads);
  for (const bool per_type : {false, true}) {
    SCOPED_TRACE(per_type ? "a threshold per motion type" : "one threshold");
    GraphFromCandidatesSettings settings;
    settings.connected_tags = 0b11;
    settings.transitions.per_tag_thresholds = per_type;
    auto want = choose_threshold(l.db, l.features, l.exhaustive, settings, choice);
    auto got = choose_threshold(l.db, l.features, search, settings, choice, &more);
    ASSERT_TRUE(want && got);
    EXPECT_EQ(want->threshold, got->threshold);
    EXPECT_EQ(want->tag_thresholds, got->tag_thresholds);
    EXPECT_EQ(want->tag_thresholds.size(), per_type ? 2u : 0u);
    EXPECT_EQ(want->reached, got->reached);
    ASSERT_EQ(want->curve.size(), got->curve.size());
    for (size_t i = 0; i < want->curve.size(); ++i) {
      EXPECT_EQ(want->curve[i].threshold, got->curve[i].threshold);
      EXPECT_EQ(want->curve[i].tag_thresholds, got->curve[i].tag_thresholds);
      EXPECT_EQ(want->curve[i].quantile, got->curve[i].quantile);
      EXPECT_EQ(want->curve[i].tag_coverage, got->curve[i].tag_coverage);
      EXPECT_EQ(want->curve[i].transitions, got->curve[i].transitions);
    }
  }
}

TEST(OnDemandCandidates, PrunedCandidatesRefuseWhatTheyCannotKnow) {
  const Library& l = library();
  const double ceiling = distance_of_rms_cm(3.0, l.features);
  const CandidateSearch search = pruned_search(ceiling);
  GraphFromCandidatesSettings settings;
  settings.connected_tags = 0b11;
  settings.transitions.per_tag_thresholds = false;
  settings.transitions.threshold = distance_of_rms_cm(2.0, l.features);
  settings.transitions.max_threshold = ceiling;
  // Bridges without the minima above the ceiling.
  EXPECT_FALSE(select_transitions_with_bridges(l.db, l.features, search, settings));
  settings.bridges.per_tag_pair = 0;
  EXPECT_TRUE(select_transitions_with_bridges(l.db, l.features, search, settings));
  // A threshold above the ceiling, and per-tag thresholds by rank (they count every candidate
  // of a tag).
  GraphFromCandidatesSettings above = settings;
  above.transitions.threshold = 1.5 * ceiling;
  EXPECT_FALSE(select_transitions_with_bridges(l.db, l.features, search, above));
  GraphFromCandidatesSettings per_tag = settings;
  per_tag.transitions.per_tag_thresholds = true;
  EXPECT_FALSE(select_transitions_with_bridges(l.db, l.features, search, per_tag));
  EXPECT_TRUE(select_transitions_with_bridges(l.db, l.features, l.exhaustive, per_tag));
  // Given per-tag thresholds: served under the ceiling, refused above it.
  per_tag.transitions.max_threshold = -1.0;
  per_tag.transitions.tag_thresholds = {{1, 0.9 * ceiling}};
  EXPECT_TRUE(select_transitions_with_bridges(l.db, l.features, search, per_tag));
  per_tag.transitions.tag_thresholds = {{1, 1.5 * ceiling}};
  EXPECT_FALSE(select_transitions_with_bridges(l.db, l.features, search, per_tag));
}

}  // namespace
}  // namespace mg
