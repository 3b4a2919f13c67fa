// Graph size against the threshold on bundled clips: thresholds in order, the invariants of
// every row, a row at the threshold of a graph built directly agreeing with it, and no error
// where nothing would remain.
#include "motiongraph/evaluation/threshold_sweep.h"

#include <gtest/gtest.h>

#include "motiongraph/evaluation/consistency_sweep.h"
#include "test_data.h"

namespace mg {
namespace {

struct Fixture {
  MotionDatabase db;
  FrameFeatures features;
  CandidateSearch candidates;
};

const Fixture& fixture() {
  static const Fixture x = [] {
    Fixture f;
    f.db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_17.amc"});
    DistanceSettings distance;
    distance.threads = 2;
    auto layout = make_cloud_layout(f.db.skeletons[0], {});
    f.features = *make_frame_features(f.db, *layout, distance);
    f.candidates = *find_candidates(f.features, distance, {});
    return f;
  }();
  return x;
}

TEST(ThresholdSweep, LogSpacedQuantiles) {
  const std::vector<double> q = log_spaced(0.001, 0.1, 3);
  ASSERT_EQ(q.size(), 3u);
  EXPECT_DOUBLE_EQ(q[0], 0.001);
  EXPECT_NEAR(q[1], 0.01, 1e-12);
  EXPECT_NEAR(q[2], 0.1, 1e-12);
}

TEST(ThresholdSweep, RowsAgreeWithGraphsBuiltDirectly) {
  const Fixture& x = fixture();
  const std::vector<double> quantiles = {1e-6, 0.01, 0.05, 0.2};
  GraphFromCandidatesSettings settings;
  auto rows = sweep_thresholds(x.db, x.features, x.candidates, settings, quantiles);
  ASSERT_TRUE(rows) << rows.error().to_string();
  ASSERT_EQ(rows->size(), quantiles.size());
  for (size_t i = 0; i < rows->size(); ++i) {
    const ThresholdSweepRow& r = (*rows)[i];
    EXPECT_EQ(r.quantile, quantiles[i]);
    if (i > 0) {
      EXPECT_GE(r.threshold, (*rows)[i - 1].threshold);
    }
    EXPECT_LE(r.largest_component_nodes, r.nodes);
    EXPECT_LE(r.kept_nodes, r.largest_component_nodes);
    EXPECT_LE(r.kept_transitions, r.transitions + r.bridges);
  }
  // Almost no pair below the lowest: three clips and no cycle, nothing kept (not an error).
  EXPECT_EQ((*rows)[0].kept_nodes, 0);
  EXPECT_GT((*rows)[3].kept_nodes, 0);
  settings.transitions.threshold_quantile = 0.05;
  auto direct = graph_from_candidates(x.db, x.features, x.candidates, settings);
  ASSERT_TRUE(direct);
  EXPECT_EQ((*rows)[2].kept_nodes, direct->pruned.graph.node_count());
  EXPECT_EQ((*rows)[2].kept_transitions, static_cast<int>(direct->pruned.graph.transitions.size()));
  EXPECT_EQ((*rows)[2].nodes, direct->pruned.prune.before.nodes);
}

TEST(ThresholdSweep, AGraphThatCannotBeBuiltIsAnErrorNotAnEmptyRow) {
  const Fixture& x = fixture();
  MotionDatabase broken = x.db;
  broken.clips[1].first_frame += 1;  // clips no longer back to back: no graph can be built
  int visits = 0;
  const std::vector<double> quantiles = {0.2};
  const Status s = for_each_threshold(broken, x.features, x.candidates, GraphFromCandidatesSettings{}, quantiles,
                                      [&](double, const TransitionsWithBridges&, const Result<PrunedGraph>&) -> Status {
                                        ++visits;
                                        return Ok{};
                                      });
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().kind, ErrorKind::kEmptyGraph);
  EXPECT_EQ(visits, 0);
}

TEST(ConsistencySweep, AnglesInRangeWhereTransitionsRemain) {
  const Fixture& x = fixture();
  const std::vector<double> quantiles = {1e-6, 0.05};
  auto rows = sweep_consistency(x.db, x.features, x.candidates, {}, quantiles);
  ASSERT_TRUE(rows) << rows.error().to_string();
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_EQ((*rows)[0].transitions, 0);
  EXPECT_EQ((*rows)[0].transition.frames, 0);
  ASSERT_GT((*rows)[1].transitions, 0);
  ASSERT_GT((*rows)[1].transition.frames, 0);
  EXPECT_GE((*rows)[1].transition.rms_deg(), 0.0);
  EXPECT_LE((*rows)[1].transition.rms_deg(), 180.0);
}

}  // namespace
}  // namespace mg
