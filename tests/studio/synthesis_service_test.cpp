// The studio's distance picture comes from the block minima the graph stores: the same PNG as
// the distance stage computed again from the graph's database and settings at the picture's
// block (the brute-force reference the studio used to run on every start). Each clip's doubts
// are info's.
#include "studio/synthesis_service.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "motiongraph/evaluation/graph_rebuild.h"
#include "motiongraph/export/matrix_png.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "studio/studio_api.h"
#include "pipeline/subject16_build.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(SynthesisService, EachClipsDoubtsAreInfosAndTheApiListsThem) {
  // Subject 16's graph with its fourth clip raised 1 m (its lowest joint off the floor): that clip
  // is doubted as info doubts it, the others not at all.
  GraphFile file = test::subject16_graph_file();
  DatabaseClip& raised = file.database.clips[3];
  for (int f = 0; f < raised.motion.frame_count; ++f) raised.motion.translations(f)[0].y() += 1.0;
  auto graph = LoadedGraph::create(std::move(file), "raised.mgraph");
  ASSERT_TRUE(graph) << graph.error().to_string();
  const auto service = studio::SynthesisService::create(std::move(*graph), "raised.mgraph");
  const MotionDatabase& db = service->file().database;
  const std::vector<std::vector<std::string>>& doubts = service->clip_doubts();
  ASSERT_EQ(doubts.size(), db.clips.size());
  for (size_t c = 0; c < db.clips.size(); ++c) {
    if (c == 3) continue;
    EXPECT_TRUE(doubts[c].empty()) << db.clips[c].name << ": " << doubts[c].front();
  }
  const Skeleton& skeleton = db.skeletons[static_cast<size_t>(db.clips[3].skeleton)];
  const std::span<const ContactMask> contacts(db.frame_contacts.data() + db.clips[3].first_frame,
                                              static_cast<size_t>(db.clips[3].frame_count));
  const std::vector<std::string> expected =
      mg::clip_doubts(world_positions(skeleton, db.clips[3].motion), skeleton.joint_count(), db.fps, contacts, {},
                      ClipClock{}, *find_foot_joints(skeleton, db.foot_names))
          .phrases();
  ASSERT_FALSE(expected.empty());
  EXPECT_NE(expected.front().find("above the floor"), std::string::npos) << expected.front();
  EXPECT_EQ(doubts[3], expected);
  // The API's clip list carries them.
  const studio::StudioApi api(*service);
  const studio::ApiResponse clips = api.handle({"GET", "/api/clips", {}, ""});
  ASSERT_EQ(clips.status, 200);
  const nlohmann::json listed = nlohmann::json::parse(clips.body);
  EXPECT_EQ(listed[3]["doubts"], nlohmann::json(expected));
  EXPECT_EQ(listed[0]["doubts"], nlohmann::json::array());
}

TEST(SynthesisService, DistancePictureIsTheStoredOneAsTheDistanceStageWouldDrawIt) {
  // Built in process: the database the distances were computed on, not one read back from a
  // file (whose motion is stored in single precision, so distances recomputed from it differ
  // in their last bits). By the exhaustive stage: every block's minimum is known.
  BuildSettings exhaustive;
  exhaustive.exhaustive = true;
  auto graph =
      LoadedGraph::create(test::build_subject16_graph(test::data_path("cmu/16"), exhaustive), "s16.mgraph");
  ASSERT_TRUE(graph) << graph.error().to_string();
  const auto owned = studio::SynthesisService::create(std::move(*graph), "s16.mgraph");
  const studio::SynthesisService& service = *owned;
  const GraphFile& file = service.file();
  const int frames = file.database.frame_count();
  const int block = service.picture_block();
  ASSERT_LE((frames + block - 1) / block, studio::SynthesisService::kPictureSide);
  ASSERT_EQ(block % file.candidates.picture_block, 0);
  auto png = service.distance_png();
  ASSERT_TRUE(png) << png.error().to_string();

  auto rebuild = prepare_graph_rebuild(file, service.graph_path());
  ASSERT_TRUE(rebuild) << rebuild.error().to_string();
  CandidateSettings settings;
  settings.picture_side = (frames + block - 1) / block;  // so that its block is `block`
  auto search = find_candidates(rebuild->features, rebuild->distance, settings);
  ASSERT_TRUE(search) << search.error().to_string();
  ASSERT_EQ(search->picture_block, block);
  std::vector<int> clip_starts;
  for (const DatabaseClip& clip : file.database.clips) clip_starts.push_back(clip.first_frame);
  MatrixPngSettings png_settings;
  png_settings.max_side_px = studio::SynthesisService::kPictureSide;
  auto reference = matrix_png(MinMatrixView{search->picture, search->picture_side, search->picture_block}, clip_starts,
                              {}, png_settings);
  ASSERT_TRUE(reference) << reference.error().to_string();
  EXPECT_EQ(*png, *reference);
}

TEST(SynthesisService, ThePrunedStagesPictureIsExactUpToItsCeiling) {
  // The pruned stage: a block whose minimum lies at or below its ceiling is the exhaustive
  // stage's, one above it +infinity (the PNG's grey).
  BuildSettings settings;
  settings.pruned_from_frames = 0;
  const GraphFile pruned = test::build_subject16_graph(test::data_path("cmu/16"), settings);
  settings.exhaustive = true;
  settings.distance_stage.distance.tile_frames = 64;  // the pruned stage's at 30 fps: the same bits
  const GraphFile exhaustive = test::build_subject16_graph(test::data_path("cmu/16"), settings);
  const CandidateSearch& p = pruned.candidates;
  const CandidateSearch& e = exhaustive.candidates;
  ASSERT_GE(p.ceiling, 0.0);
  ASSERT_LT(e.ceiling, 0.0);
  ASSERT_EQ(p.picture_side, e.picture_side);
  ASSERT_EQ(p.picture_block, e.picture_block);
  ASSERT_EQ(p.picture.size(), e.picture.size());
  int above = 0;
  for (size_t i = 0; i < p.picture.size(); ++i) {
    if (std::isnan(e.picture[i])) {
      EXPECT_TRUE(std::isnan(p.picture[i])) << i;
    } else if (e.picture[i] <= p.ceiling) {
      EXPECT_EQ(p.picture[i], e.picture[i]) << i;
    } else {
      EXPECT_EQ(p.picture[i], std::numeric_limits<float>::infinity()) << i;
      ++above;
    }
  }
  EXPECT_GT(above, 0);
}

}  // namespace
}  // namespace mg
