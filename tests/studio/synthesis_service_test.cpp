// The studio's distance picture comes from the block minima the graph stores: the same PNG as
// the distance stage computed again from the graph's database and settings at the picture's
// block (the brute-force reference the studio used to run on every start). Each clip's doubts
// are info's.
#include "studio/synthesis_service.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "motiongraph/evaluation/graph_rebuild.h"
#include "motiongraph/export/matrix_png.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/io/bvh_parser.h"
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

// A motion of `frames` frames of one joint (the bounds count frames, not what they hold).
Motion frames_of_one_joint(int frames) {
  Motion motion;
  motion.frame_count = frames;
  motion.joint_count = 1;
  motion.translated_count = 1;
  motion.local_rotations.assign(static_cast<size_t>(frames), Quat::Identity());
  motion.local_translations_m.assign(static_cast<size_t>(frames), Vec3::Zero());
  return motion;
}

// A service of its own on subject 16's graph (the tests' shared one keeps others' results).
// A service of its own, whose sessions are taken over whenever the limit is reached (busy_s 0)
// unless `limits` says otherwise.
std::unique_ptr<studio::SynthesisService> fresh_service(studio::SessionLimits limits = {16, 0.0}) {
  auto graph = LoadedGraph::create(test::subject16_graph_file(), "s16.mgraph");
  EXPECT_TRUE(graph) << graph.error().to_string();
  auto service = studio::SynthesisService::create(std::move(*graph), "s16.mgraph");
  EXPECT_TRUE(service->set_session_limits(limits));
  return service;
}

// Results kept: the oldest go first past kMaxResults, or past kMaxKeptFrames frames in all, but
// not a live steering session's recording (it went with walks before: its download a 404 while
// the session steered on).
TEST(SynthesisService, KeepsResultsWithinItsBoundsButALiveSessionsRecording) {
  using studio::SynthesisService;
  const auto service = fresh_service();
  const SteeringControl input;
  auto started = service->create_session(input);
  ASSERT_TRUE(started) << started.error().to_string();
  const int* session = &started->id;
  ASSERT_TRUE(service->step_session(*session, input, 30));
  std::vector<int> small;
  for (int i = 0; i < SynthesisService::kMaxResults; ++i) {
    small.push_back(service->store_result(frames_of_one_joint(10)));
  }
  EXPECT_TRUE(service->has_result(*session));
  EXPECT_FALSE(service->has_result(small[0]));  // the oldest but the session's
  EXPECT_TRUE(service->has_result(small[1]));
  // Two results of more than half the frames kept (the session's counted at its most): the
  // first goes, and everything older.
  const int half = static_cast<int>((SynthesisService::kMaxKeptFrames - SynthesisService::kMaxRecordedFrames) / 2) + 1;
  const int first = service->store_result(frames_of_one_joint(half));
  EXPECT_TRUE(service->has_result(first));
  EXPECT_TRUE(service->has_result(small.back()));
  const int second = service->store_result(frames_of_one_joint(half));
  EXPECT_FALSE(service->has_result(first));
  EXPECT_FALSE(service->has_result(small.back()));
  EXPECT_TRUE(service->has_result(second));
  EXPECT_TRUE(service->has_result(*session));
  // A session gone is a result as any other.
  for (int i = 0; i < studio::SessionLimits{}.max_sessions; ++i) ASSERT_TRUE(service->create_session(input));
  for (int i = 0; i < SynthesisService::kMaxResults; ++i) service->store_result(frames_of_one_joint(10));
  EXPECT_FALSE(service->has_result(*session));
}

// At its limit of sessions, a new one takes the place of the least recently stepped only when
// that one has not been stepped for SessionLimits::busy_s: a client steering now keeps its
// session, and the new one is refused (kBusy: try again) rather than taking it.
TEST(SynthesisService, ANewSessionTakesTheLeastRecentlySteppedOnlyOnceItIsIdle) {
  const SteeringControl input;
  const auto service = fresh_service({2, 0.3});
  auto a = service->create_session(input, false);
  auto b = service->create_session(input, false);
  ASSERT_TRUE(a && b);
  auto refused = service->create_session(input, false);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::kBusy);
  EXPECT_NE(refused.error().message.find("at most 2 sessions"), std::string::npos) << refused.error().message;
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  ASSERT_TRUE(service->step_session(a->id, input, 1));  // a in use again; b idle
  auto c = service->create_session(input, false);
  ASSERT_TRUE(c) << c.error().to_string();
  EXPECT_FALSE(service->step_session(b->id, input, 1));
  EXPECT_TRUE(service->step_session(a->id, input, 1));
  EXPECT_TRUE(service->step_session(c->id, input, 1));
  // (limits checked)
  EXPECT_FALSE(service->set_session_limits({0, 1.0}));
  EXPECT_FALSE(service->set_session_limits({4, -1.0}));
  EXPECT_EQ(service->session_limits().max_sessions, 2);
}

// Sessions created at the same time with room for one: one is made and the others refused,
// and the one made is there to step (each passed the check before the work, and the last one in
// evicted one made a moment before: its first step answered 404).
TEST(SynthesisService, SessionsCreatedAtOnceNeverEvictOneInUse) {
  const SteeringControl input;
  for (int round = 0; round < 8; ++round) {
    const auto service = fresh_service({3, 60.0});
    ASSERT_TRUE(service->create_session(input, false));
    ASSERT_TRUE(service->create_session(input, false));
    std::vector<Result<studio::SteerSessionStart>> made(4, Error{});
    std::vector<std::thread> threads;
    for (size_t i = 0; i < made.size(); ++i) {
      threads.emplace_back([&, i] { made[i] = service->create_session(input, false); });
    }
    for (std::thread& t : threads) t.join();
    int ok = 0;
    for (const auto& m : made) {
      if (!m) {
        EXPECT_EQ(m.error().kind, ErrorKind::kBusy) << m.error().to_string();
        continue;
      }
      ++ok;
      EXPECT_TRUE(service->step_session(m->id, input, 1)) << "round " << round;
    }
    EXPECT_EQ(ok, 1) << "round " << round;
  }
}

// A session records its first kMaxRecordedFrames frames, one after another: a step that does
// not fit whole gives what fits (it was left out whole, and a later one that fit made a jump).
TEST(SynthesisService, ASessionRecordsItsFirstFramesWithoutAGap) {
  using studio::SynthesisService;
  const auto service = fresh_service();
  const SteeringControl input;
  auto started = service->create_session(input, /*cleanup=*/false);
  ASSERT_TRUE(started) << started.error().to_string();
  const int* session = &started->id;
  auto first = service->step_session(*session, input, SynthesisService::kMaxRecordedFrames - 20);
  ASSERT_TRUE(first) << first.error().to_string();
  ASSERT_LT(first->motion.frame_count, SynthesisService::kMaxRecordedFrames);
  auto second = service->step_session(*session, input, 60);  // does not fit whole
  ASSERT_TRUE(second) << second.error().to_string();
  ASSERT_GT(first->motion.frame_count + second->motion.frame_count, SynthesisService::kMaxRecordedFrames);
  auto third = service->step_session(*session, input, 1);
  ASSERT_TRUE(third);
  const auto bvh = service->result_file(*session);
  ASSERT_TRUE(bvh);
  auto read = parse_bvh(*bvh, "session.bvh");
  ASSERT_TRUE(read) << read.error().to_string();
  ASSERT_EQ(read->frame_count, SynthesisService::kMaxRecordedFrames);
  const BvhJoint& root = read->joints.front();
  ASSERT_GE(root.channels.size(), 3u);
  ASSERT_EQ(root.channels[0], BvhChannel::kXposition);
  ASSERT_EQ(root.channels[1], BvhChannel::kYposition);
  ASSERT_EQ(root.channels[2], BvhChannel::kZposition);
  // Frame by frame the root the steps gave, in order (the file in metres).
  for (int f = 0; f < read->frame_count; ++f) {
    const bool in_first = f < first->motion.frame_count;
    const Motion& step = in_first ? first->motion : second->motion;
    const int at = in_first ? f : f - first->motion.frame_count;
    const double* values = &read->values[static_cast<size_t>(f) * read->channel_count + root.first_channel];
    ASSERT_LT((Vec3(values[0], values[1], values[2]) - step.translations(at)[0]).norm(), 1e-5) << f;
  }
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
