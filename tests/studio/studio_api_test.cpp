// The studio's JSON API on the subject-16 graph, without sockets: what each endpoint answers,
// and 4xx with a message for every kind of bad request.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <numbers>
#include <span>
#include <thread>
#include <vector>

#include "motiongraph/evaluation/synthesis_run.h"
#include "motiongraph/pipeline/build_graph.h"
#include "motiongraph/synthesis/loaded_graph.h"
#include "motiongraph/skeleton/foot_joints.h"
#include "pipeline/subject16_build.h"
#include "studio/studio_test_service.h"
#include "test_data.h"

namespace mg::test {
namespace {

using nlohmann::json;

void expect_error(const ApiCall& call, int status, const std::string& words) {
  EXPECT_EQ(call.response.status, status) << call.response.body;
  ASSERT_TRUE(call.json.contains("error")) << call.response.body;
  EXPECT_NE(call.json["error"].get<std::string>().find(words), std::string::npos) << call.json["error"];
}

TEST(StudioApi, SummaryDescribesTheGraphAndItsTags) {
  const ApiCall call = call_api("GET", "/api/summary");
  ASSERT_EQ(call.response.status, 200) << call.response.body;
  const auto& db = studio_service().file().database;
  EXPECT_EQ(call.json["frames"], db.frame_count());
  EXPECT_EQ(call.json["clips"], db.clips.size());
  EXPECT_EQ(call.json["statistics"]["nodes"], studio_service().file().graph.node_count());
  bool walk = false;
  for (const json& t : call.json["statistics"]["tags"]) walk |= t["name"] == "walk" && t["edges"].get<int>() > 0;
  EXPECT_TRUE(walk) << call.json["statistics"];
  EXPECT_GE(call.json["matrix"]["block"].get<int>(), 1);
}

// A library whose walk turns left, mirrored by the build: the clip list says which clip each
// mirrored one mirrors (the build report the file stores); the subject-16 graph's say none.
TEST(StudioApi, TheClipListSaysWhichClipAMirroredOneMirrors) {
  const std::vector<std::string> inputs = {data_path("cmu/16/16_15.amc"), data_path("cmu/16/16_17.amc")};
  BuildSettings settings;
  settings.path_check = false;
  auto built = build_graph(inputs, settings);
  ASSERT_TRUE(built) << built.error().to_string();
  ASSERT_TRUE(built->graph_status) << built->graph_status.error().to_string();
  auto graph = LoadedGraph::create(std::move(built->file), "mirrored.mgraph");
  ASSERT_TRUE(graph) << graph.error().to_string();
  auto service = studio::SynthesisService::create(std::move(*graph), "mirrored.mgraph");
  const studio::StudioApi api(*service);
  const studio::ApiResponse response = api.handle({"GET", "/api/clips", {}, ""});
  ASSERT_EQ(response.status, 200) << response.body;
  std::vector<std::pair<std::string, json>> clips;
  for (const json& c : json::parse(response.body)) clips.emplace_back(c["name"], c["mirror_of"]);
  const std::vector<std::pair<std::string, json>> expected = {
      {"16_15", nullptr}, {"16_17", nullptr}, {"16_15_mirrored", "16_15"}, {"16_17_mirrored", "16_17"}};
  EXPECT_EQ(clips, expected);
  for (const json& c : call_api("GET", "/api/clips").json) EXPECT_TRUE(c["mirror_of"].is_null()) << c["name"];
}

TEST(StudioApi, ClipFramesAreWorldPositionsOfEveryJoint) {
  const ApiCall clips = call_api("GET", "/api/clips");
  ASSERT_EQ(clips.response.status, 200);
  ASSERT_FALSE(clips.json.empty());
  // Each clip's frames the pruned graph plays, adding up to the graph's own count.
  const auto& file = studio_service().file();
  long long kept = 0;
  for (const json& c : clips.json) {
    // The rate its file was read at: CMU's AMC files are 120 fps, the graph's 30.
    EXPECT_EQ(c["read_fps"].get<double>(), 120.0) << c;
    EXPECT_GE(c["kept_frames"].get<int>(), 0);
    EXPECT_LE(c["kept_frames"].get<int>(), c["frames"].get<int>());
    kept += c["kept_frames"].get<int>();
  }
  EXPECT_EQ(kept, compute_graph_statistics(file.graph, file.database.frame_tags()).clip_frames);
  EXPECT_GT(kept, 0);
  const ApiCall frames = call_api("GET", "/api/clips/0/frames", "", {{"from", "5"}, {"count", "10"}});
  ASSERT_EQ(frames.response.status, 200) << frames.response.body;
  const size_t joints = frames.json["joints"].size();
  ASSERT_GT(joints, 10u);
  ASSERT_EQ(frames.json["positions"].size(), 10u);
  EXPECT_EQ(frames.json["positions"][0].size(), 3 * joints);
  // The root of a standing person is about a metre up.
  const double root_y = frames.json["positions"][0][1].get<double>();
  EXPECT_GT(root_y, 0.6);
  EXPECT_LT(root_y, 1.3);
}

// The feet's joints in the order the contacts list them (left ankle, left toe, right ankle,
// right toe; those the skeleton has) with their contact bits.
std::vector<std::pair<int, ContactMask>> foot_columns(const FootJoints& feet) {
  std::vector<std::pair<int, ContactMask>> columns;
  for (const auto& [foot, side] : {std::pair{feet.left, FootSide::kLeft}, std::pair{feet.right, FootSide::kRight}}) {
    columns.emplace_back(foot.ankle, contact_bit(side, FootPart::kAnkle));
    if (foot.toe >= 0) columns.emplace_back(foot.toe, contact_bit(side, FootPart::kToe));
  }
  return columns;
}

// An answer's "contacts" for `frames` frames of a motion on `skeleton` with `feet`, read back
// as contact masks (only the feet's bits), after checking its joints are those feet.
std::vector<ContactMask> planted_masks(const json& contacts, const Skeleton& skeleton, const FootJoints& feet,
                                       size_t frames) {
  std::vector<ContactMask> masks;
  const auto columns = foot_columns(feet);
  if (!contacts.is_object() || contacts["planted"].size() != frames) {
    ADD_FAILURE() << "expected contacts for " << frames << " frames: " << contacts.dump().substr(0, 200);
    return masks;
  }
  EXPECT_EQ(contacts["joints"].size(), columns.size());
  EXPECT_EQ(contacts["joint_indices"].size(), columns.size());
  for (size_t k = 0; k < columns.size() && k < contacts["joints"].size(); ++k) {
    EXPECT_EQ(contacts["joint_indices"][k].get<int>(), columns[k].first);
    EXPECT_EQ(contacts["joints"][k].get<std::string>(), skeleton.joint(columns[k].first).name);
  }
  for (const json& row : contacts["planted"]) {
    EXPECT_EQ(row.size(), columns.size());
    ContactMask mask = 0;
    for (size_t k = 0; k < columns.size() && k < row.size(); ++k) {
      EXPECT_TRUE(row[k] == 0 || row[k] == 1) << row;
      if (row[k] == 1) mask |= columns[k].second;
    }
    masks.push_back(mask);
  }
  return masks;
}

// The masks with only the feet's bits.
std::vector<ContactMask> feet_bits(std::span<const ContactMask> masks, const FootJoints& feet) {
  ContactMask all = 0;
  for (const auto& column : foot_columns(feet)) all |= column.second;
  std::vector<ContactMask> out;
  for (ContactMask m : masks) out.push_back(m & all);
  return out;
}

TEST(StudioApi, ClipFramesCarryTheContactsOfTheirDatabaseFrames) {
  const SynthesisContext& context = studio_service().context();
  const MotionDatabase& db = studio_service().file().database;
  ASSERT_FALSE(context.frame_contacts.empty()) << context.feet_error;
  for (int index : {0, 1}) {
    const DatabaseClip& clip = db.clips[index];
    const int from = 5;
    const int count = std::min(200, clip.frame_count - from);
    const ApiCall call = call_api("GET", "/api/clips/" + std::to_string(index) + "/frames", "",
                                  {{"from", std::to_string(from)}, {"count", std::to_string(count)}});
    ASSERT_EQ(call.response.status, 200) << call.response.body;
    ASSERT_EQ(call.json["positions"].size(), static_cast<size_t>(count));
    const FootJoints feet = *find_foot_joints(db.skeletons[clip.skeleton]);
    const std::vector<ContactMask> got =
        planted_masks(call.json["contacts"], db.skeletons[clip.skeleton], feet, static_cast<size_t>(count));
    const auto first = context.frame_contacts.begin() + clip.first_frame + from;
    const std::vector<ContactMask> expected = feet_bits({first, first + count}, feet);
    EXPECT_EQ(got, expected) << clip.name;
    // Some joint is planted on some frame and lifted on another: the marks change as it plays.
    EXPECT_NE(std::count(got.begin(), got.end(), ContactMask{0}), count) << clip.name;
    EXPECT_TRUE(std::any_of(got.begin(), got.end(), [&](ContactMask m) { return m != got.front(); })) << clip.name;
  }
  // A transition's two windows carry theirs too.
  const ApiCall poses = call_api("GET", "/api/transitions/0/poses");
  ASSERT_EQ(poses.response.status, 200) << poses.response.body;
  for (const char* side : {"from", "to"}) {
    const json& window = poses.json[side];
    const int first_frame = window["first_frame"].get<int>();
    const DatabaseClip& clip = db.clips[db.clip_of(first_frame)];
    const FootJoints feet = *find_foot_joints(db.skeletons[clip.skeleton]);
    const size_t k = window["positions"].size();
    const auto first = context.frame_contacts.begin() + first_frame;
    EXPECT_EQ(planted_masks(window["contacts"], db.skeletons[clip.skeleton], feet, k),
              feet_bits({first, first + static_cast<long>(k)}, feet))
        << side;
  }
}

TEST(StudioApi, ResultsCarryTheContactsTheirFramesPlay) {
  const SynthesisContext& context = studio_service().context();
  const Skeleton& skeleton = context.assembler.skeleton();
  // The service's walk carries walk_contacts; the API answers the same walk with them.
  studio::WalkRequest request;
  request.from = 2;
  request.to = 7;
  request.min_frames = 120;
  request.cost = WalkCost::kRandom;
  request.seed = 11;
  auto walk = studio_service().walk(request);
  ASSERT_TRUE(walk) << walk.error().to_string();
  EXPECT_EQ(walk->contacts, context.walk_contacts(walk->walk));
  ASSERT_EQ(walk->contacts.size(), static_cast<size_t>(walk->motion.frame_count));
  const ApiCall call =
      call_api("POST", "/api/walk", R"({"from": 2, "to": 7, "min_frames": 120, "cost": "random", "seed": 11})");
  ASSERT_EQ(call.response.status, 200) << call.response.body;
  ASSERT_EQ(call.json["frames"].get<int>(), walk->motion.frame_count);
  EXPECT_EQ(planted_masks(call.json["contacts"], skeleton, context.feet, call.json["positions"].size()),
            feet_bits(walk->contacts, context.feet));

  // A path's contacts are those of the frames its walk plays, cut where the path ends: the
  // same whether the motion is cleaned or not.
  const std::string path = R"({"points": [[0, 0], [0, -5], [3, -8]])";
  const ApiCall cleaned = call_api("POST", "/api/path", path + "}");
  const ApiCall raw = call_api("POST", "/api/path", path + R"(, "cleanup": false})");
  ASSERT_EQ(cleaned.response.status, 200) << cleaned.response.body;
  ASSERT_EQ(raw.response.status, 200) << raw.response.body;
  const auto path_masks =
      planted_masks(cleaned.json["contacts"], skeleton, context.feet, cleaned.json["positions"].size());
  EXPECT_EQ(path_masks, planted_masks(raw.json["contacts"], skeleton, context.feet, raw.json["positions"].size()));
  EXPECT_NE(std::count(path_masks.begin(), path_masks.end(), ContactMask{0}), static_cast<long>(path_masks.size()));

  // Each steering step carries one row per frame it appends.
  const ApiCall session = call_api("POST", "/api/steer/sessions", R"({"heading_deg": 45, "tag": "walk"})");
  ASSERT_EQ(session.response.status, 200) << session.response.body;
  const std::string step = "/api/steer/sessions/" + std::to_string(session.json["session"].get<int>()) + "/step";
  std::vector<ContactMask> steered;
  for (int i = 0; i < 4; ++i) {
    const ApiCall call_step = call_api("POST", step, R"({"heading_deg": 45, "tag": "walk", "min_frames": 30})");
    ASSERT_EQ(call_step.response.status, 200) << call_step.response.body;
    const auto masks = planted_masks(call_step.json["contacts"], skeleton, context.feet,
                                     call_step.json["frames"].get<size_t>());
    EXPECT_EQ(call_step.json["positions"].size(), masks.size());
    steered.insert(steered.end(), masks.begin(), masks.end());
  }
  EXPECT_NE(std::count(steered.begin(), steered.end(), ContactMask{0}), static_cast<long>(steered.size()));
}

TEST(StudioApi, BadIndicesAndQueriesAre4xx) {
  expect_error(call_api("GET", "/api/clips/999/frames"), 404, "no clip");
  expect_error(call_api("GET", "/api/clips/-1/frames"), 404, "no clip");
  expect_error(call_api("GET", "/api/clips/0/frames", "", {{"count", "100000"}}), 400, "count");
  expect_error(call_api("GET", "/api/clips/0/frames", "", {{"from", "1e3"}}), 400, "from");
  expect_error(call_api("GET", "/api/clips/0/frames", "", {{"from", "nan"}}), 400, "from");
  expect_error(call_api("GET", "/api/transitions/99999/poses"), 404, "no transition");
  expect_error(call_api("GET", "/api/nothing"), 404, "no such endpoint");
  expect_error(call_api("GET", "/"), 404, "no such endpoint");
  expect_error(call_api("POST", "/api/summary"), 405, "GET");
  expect_error(call_api("GET", "/api/walk"), 405, "POST");
  expect_error(call_api("GET", "/api/results/abc.bvh"), 404, "no result");
  expect_error(call_api("GET", "/api/results/123456.bvh"), 404, "no result");
}

TEST(StudioApi, TransitionsAndTheirPoses) {
  const ApiCall list = call_api("GET", "/api/transitions");
  ASSERT_EQ(list.response.status, 200);
  ASSERT_EQ(list.json.size(), studio_service().file().graph.transitions.size());
  const ApiCall poses = call_api("GET", "/api/transitions/0/poses");
  ASSERT_EQ(poses.response.status, 200) << poses.response.body;
  const int k = studio_service().file().graph.window;
  // Each transition's blend length is its edge's: the window, or longer for a bridge; and so is
  // whether it is a bridge (subject 16's graph has some).
  const MotionGraph& graph = studio_service().file().graph;
  int bridges = 0;
  for (const GraphEdge& e : graph.edges) {
    if (e.transition) {
      EXPECT_EQ(list.json[e.transition_index]["blend_frames"].get<int>(), e.frame_count + 1);
      EXPECT_GE(e.frame_count + 1, k);
      EXPECT_EQ(list.json[e.transition_index]["bridge"].get<bool>(), e.bridge);
      bridges += e.bridge ? 1 : 0;
    }
  }
  EXPECT_GT(bridges, 0);
  ASSERT_EQ(poses.json["from"]["positions"].size(), static_cast<size_t>(k));
  ASSERT_EQ(poses.json["to"]["positions"].size(), static_cast<size_t>(k));
  EXPECT_EQ(poses.json["from"]["first_frame"], list.json[0]["window_from_frame"]);
  EXPECT_EQ(poses.json["to"]["first_frame"].get<int>(), list.json[0]["window_to_frame"].get<int>() - k + 1);
  // Root-centred on the floor.
  EXPECT_EQ(poses.json["from"]["positions"][0][0], 0.0);
  EXPECT_EQ(poses.json["to"]["positions"][0][2], 0.0);
  // The windows are those D was measured on: a transition's own frames; for a bridge whose blend
  // is centred on them, inside its blend on the same pairs of frames (found again among the
  // candidate minima with the same D), and for some bridge not where its blend leaves.
  const CandidateSearch& candidates = studio_service().file().candidates;
  int moved = 0;
  for (const GraphEdge& e : graph.edges) {
    if (!e.transition) continue;
    const json& t = list.json[e.transition_index];
    const int from = t["from_frame"].get<int>(), to = t["to_frame"].get<int>();
    const int window_from = t["window_from_frame"].get<int>(), window_to = t["window_to_frame"].get<int>();
    if (!e.bridge) {
      EXPECT_EQ(window_from, from);
      EXPECT_EQ(window_to, to);
      continue;
    }
    moved += window_from != from ? 1 : 0;
    EXPECT_TRUE(std::any_of(candidates.minima.begin(), candidates.minima.end(), [&](const Transition& c) {
      return c.from_frame == window_from && c.to_frame == window_to && c.distance == t["distance"].get<float>();
    })) << from << " -> " << to;
    const ApiCall bridge_poses = call_api("GET", "/api/transitions/" + std::to_string(e.transition_index) + "/poses");
    ASSERT_EQ(bridge_poses.response.status, 200);
    EXPECT_EQ(bridge_poses.json["from"]["first_frame"].get<int>(), window_from);
    EXPECT_EQ(bridge_poses.json["to"]["first_frame"].get<int>(), window_to - k + 1);
  }
  EXPECT_GT(moved, 0);
}

TEST(StudioApi, MatrixPictureIsAPng) {
  const ApiCall call = call_api("GET", "/api/matrix.png");
  ASSERT_EQ(call.response.status, 200) << call.response.body;
  EXPECT_EQ(call.response.content_type, "image/png");
  ASSERT_GT(call.response.body.size(), 8u);
  EXPECT_EQ(call.response.body.substr(1, 3), "PNG");
}

TEST(StudioApi, WalkReturnsMotionAndABvhDownload) {
  const ApiCall walk = call_api("POST", "/api/walk", R"({"from": 0, "to": 3, "min_frames": 60, "cost": "quality"})");
  ASSERT_EQ(walk.response.status, 200) << walk.response.body;
  EXPECT_GE(walk.json["frames"].get<int>(), 60);
  const ApiCall bvh = call_api("GET", "/api/results/" + std::to_string(walk.json["result"].get<int>()) + ".bvh");
  ASSERT_EQ(bvh.response.status, 200);
  EXPECT_EQ(bvh.response.body.rfind("HIERARCHY", 0), 0u);
  EXPECT_FALSE(bvh.response.file_name.empty());
  const ApiCall glb = call_api("GET", "/api/results/" + std::to_string(walk.json["result"].get<int>()) + ".glb");
  ASSERT_EQ(glb.response.status, 200);
  EXPECT_EQ(glb.response.body.rfind("glTF", 0), 0u);
  EXPECT_EQ(glb.response.content_type, "model/gltf-binary");
  EXPECT_TRUE(glb.response.file_name.ends_with(".glb"));
  const ApiCall root_motion =
      call_api("GET", "/api/results/" + std::to_string(walk.json["result"].get<int>()) + ".bvh", "", {{"root_motion", "1"}});
  ASSERT_EQ(root_motion.response.status, 200);
  EXPECT_EQ(root_motion.response.body.rfind("HIERARCHY\nROOT root_motion", 0), 0u);
  // Named apart from the download without it (both were motiongraph-ID.bvh).
  EXPECT_EQ(root_motion.response.file_name,
            fmt::format("motiongraph-{}-root-motion.bvh", walk.json["result"].get<int>()));
  EXPECT_EQ(bvh.response.file_name, fmt::format("motiongraph-{}.bvh", walk.json["result"].get<int>()));
  const ApiCall fbx = call_api("GET", "/api/results/" + std::to_string(walk.json["result"].get<int>()) + ".fbx");
  ASSERT_EQ(fbx.response.status, 200);
  EXPECT_EQ(fbx.response.body.rfind(std::string("Kaydara FBX Binary  \0", 21), 0), 0u);
  EXPECT_TRUE(fbx.response.file_name.ends_with(".fbx"));
  // Without the stick figure: no mesh in either.
  const std::string id = std::to_string(walk.json["result"].get<int>());
  const ApiCall bare_fbx = call_api("GET", "/api/results/" + id + ".fbx", "", {{"figure", "0"}});
  const ApiCall bare_glb = call_api("GET", "/api/results/" + id + ".glb", "", {{"figure", "0"}});
  ASSERT_EQ(bare_fbx.response.status, 200);
  ASSERT_EQ(bare_glb.response.status, 200);
  EXPECT_NE(fbx.response.body.find("Geometry"), std::string::npos);
  EXPECT_EQ(bare_fbx.response.body.find("Geometry"), std::string::npos);
  EXPECT_NE(glb.response.body.find("\"meshes\""), std::string::npos);
  EXPECT_EQ(bare_glb.response.body.find("\"meshes\""), std::string::npos);
  expect_error(call_api("GET", "/api/results/" + id + ".glb", "", {{"figure", "2"}}), 400, "figure");
  expect_error(call_api("GET", "/api/results/" + std::to_string(walk.json["result"].get<int>()) + ".dae"), 404,
               "expected /api/results/ID.bvh, ID.glb, ID.gltf or ID.fbx");
  // A number past any result's is said as a result not kept, not as a name of the wrong form.
  const ApiCall far = call_api("GET", "/api/results/1073741825.bvh");
  expect_error(far, 404, "no result '1073741825' (results are kept for the latest");
  EXPECT_EQ(far.json["error"].get<std::string>().find("expected"), std::string::npos);
  // glTF as JSON: the same scene as the .glb's JSON chunk, its buffer embedded as base64.
  const ApiCall gltf = call_api("GET", "/api/results/" + id + ".gltf");
  ASSERT_EQ(gltf.response.status, 200);
  EXPECT_EQ(gltf.response.content_type, "model/gltf+json");
  EXPECT_EQ(gltf.response.file_name, "motiongraph-" + id + ".gltf");
  const nlohmann::json scene = nlohmann::json::parse(gltf.response.body);
  EXPECT_EQ(scene["asset"]["version"], "2.0");
  ASSERT_EQ(scene["animations"].size(), 1u);
  EXPECT_EQ(scene["animations"][0]["name"], "motiongraph-" + id);
  ASSERT_EQ(scene["buffers"].size(), 1u);
  EXPECT_EQ(scene["buffers"][0]["uri"].get<std::string>().rfind("data:application/octet-stream;base64,", 0), 0u);
  uint32_t json_length = 0;  // the .glb's JSON chunk: its length at byte 12, its text from byte 20
  std::memcpy(&json_length, glb.response.body.data() + 12, 4);
  nlohmann::json glb_scene = nlohmann::json::parse(glb.response.body.substr(20, json_length));
  EXPECT_EQ(glb_scene["nodes"], scene["nodes"]);
  EXPECT_EQ(glb_scene["accessors"], scene["accessors"]);
  EXPECT_EQ(call_api("GET", "/api/results/" + id + ".gltf", "", {{"figure", "0"}}).response.body.find("\"meshes\""),
            std::string::npos);
}

TEST(StudioApi, ResultsAreCleanedUnlessAskedNotToAndMeasuredAgainstTheirSource) {
  const std::string path = R"({"points": [[0, 0], [0, -6], [4, -9]])";
  const ApiCall cleaned = call_api("POST", "/api/path", path + "}");
  const ApiCall raw = call_api("POST", "/api/path", path + R"(, "cleanup": false})");
  ASSERT_EQ(cleaned.response.status, 200) << cleaned.response.body;
  ASSERT_EQ(raw.response.status, 200) << raw.response.body;
  EXPECT_TRUE(cleaned.json["cleanup"].get<bool>());
  EXPECT_FALSE(raw.json["cleanup"].get<bool>());
  const json& fc = cleaned.json["foot_slide"];
  const json& fr = raw.json["foot_slide"];
  ASSERT_FALSE(fc.contains("error")) << fc;
  EXPECT_EQ(fc["source"]["clips"], fr["source"]["clips"]);  // the same walk, played as it is or cleaned
  EXPECT_LT(fc["mean_mps"].get<double>(), 0.5 * fr["mean_mps"].get<double>()) << fc << fr;
  EXPECT_LE(fc["ratio"]["mean_mps"].get<double>(), 1.0) << fc;
  // On the frames played: the same steps of the capture, held still where played they slid.
  EXPECT_EQ(fc["same_frames"]["steps"], fr["same_frames"]["steps"]);
  EXPECT_GT(fc["same_frames"]["steps"].get<long long>(), 0) << fc;
  EXPECT_LT(fc["same_frames"]["mean_mps"].get<double>(), 0.5 * fr["same_frames"]["mean_mps"].get<double>()) << fc << fr;
  // Bent onto the path by default, as the CLI's path is; "edit_path": false plays the graph's walk.
  const ApiCall plain = call_api("POST", "/api/path", path + R"(, "edit_path": false})");
  ASSERT_EQ(plain.response.status, 200) << plain.response.body;
  EXPECT_TRUE(cleaned.json["path_edit"]["edited"].get<bool>()) << cleaned.json["path_edit"];
  EXPECT_FALSE(plain.json["path_edit"]["edited"].get<bool>()) << plain.json["path_edit"];
  EXPECT_EQ(plain.json["mean_deviation_m"], plain.json["graph_mean_deviation_m"]);
  // The graph's walk, up to where each is cut (at the frame furthest along the path: the edited
  // motion's may be another) and how the search went on near the end (it sees the edited end).
  EXPECT_NEAR(plain.json["mean_deviation_m"].get<double>(), cleaned.json["graph_mean_deviation_m"].get<double>(),
              0.005);
  EXPECT_LT(cleaned.json["mean_deviation_m"].get<double>(), cleaned.json["graph_mean_deviation_m"].get<double>());
  expect_error(call_api("POST", "/api/path", path + R"(, "edit_path": "yes"})"), 400, "edit_path");
  const ApiCall walk = call_api("POST", "/api/walk", R"({"from": 0, "to": 3, "min_frames": 90, "cleanup": false})");
  ASSERT_EQ(walk.response.status, 200) << walk.response.body;
  EXPECT_FALSE(walk.json["cleanup"].get<bool>());
  EXPECT_GT(walk.json["foot_slide"]["contact_steps"].get<int>(), 0);
  const ApiCall session = call_api("POST", "/api/steer/sessions", R"({"heading_deg": 90, "cleanup": true})");
  ASSERT_EQ(session.response.status, 200) << session.response.body;
  EXPECT_TRUE(session.json["cleanup"].get<bool>());
  // Steps report their bridges, and the session's add up (walking, then asked to run: a bridge
  // or a transition between the two may be taken).
  const std::string step = "/api/steer/sessions/" + std::to_string(session.json["session"].get<int>()) + "/step";
  int bridges = 0;
  for (int i = 0; i < 30; ++i) {
    const ApiCall s = call_api("POST", step, i < 10 ? R"({"heading_deg": 90})" : R"({"heading_deg": 90, "tag": "run"})");
    ASSERT_EQ(s.response.status, 200) << s.response.body;
    EXPECT_LE(s.json["bridges"].get<int>(), s.json["transitions"].get<int>());
    bridges += s.json["bridges"].get<int>();
    EXPECT_EQ(s.json["session_bridges"].get<int>(), bridges);
  }
  EXPECT_GE(walk.json["bridges"].get<int>(), 0);
  EXPECT_LE(walk.json["bridges"].get<int>(), walk.json["transitions"].get<int>());
  expect_error(call_api("POST", "/api/walk", R"({"cleanup": "yes"})"), 400, "cleanup");
  expect_error(call_api("POST", "/api/path", R"({"points": [[0, 0], [0, 5]], "cleanup": 1})"), 400, "cleanup");
}

TEST(StudioApi, BadWalksAre4xx) {
  expect_error(call_api("POST", "/api/walk", "{"), 400, "request body");
  expect_error(call_api("POST", "/api/walk", "[1, 2]"), 400, "object");
  expect_error(call_api("POST", "/api/walk", R"({"from": -1})"), 400, "from");
  expect_error(call_api("POST", "/api/walk", R"({"from": 1.5})"), 400, "from");
  expect_error(call_api("POST", "/api/walk", R"({"from": "0"})"), 400, "from");
  expect_error(call_api("POST", "/api/walk", R"({"min_frames": 1e9})"), 400, "min_frames");
  expect_error(call_api("POST", "/api/walk", R"({"cost": "cheap"})"), 400, "cheap");
  // A key the request does not take (a misspelling, a CLI option) is an error, not ignored.
  expect_error(call_api("POST", "/api/walk", R"({"min_frame": 10})"), 400,
               "unknown key 'min_frame' (this request takes 'from', 'to', 'min_frames', 'seed', 'cost', 'cleanup')");
  expect_error(call_api("POST", "/api/walk", R"({"max_expansions": 5000000})"), 400, "unknown key 'max_expansions'");
  // A long key or cost is shown in part (a body may be a megabyte; the answer echoed it whole).
  const std::string long_word(100000, 'k');
  for (const std::string& body : {"{\"" + long_word + "\": 1}", "{\"cost\": \"" + long_word + "\"}"}) {
    const ApiCall long_key = call_api("POST", "/api/walk", body);
    EXPECT_EQ(long_key.response.status, 400);
    EXPECT_LT(long_key.response.body.size(), 400u) << long_key.response.body.substr(0, 200);
    EXPECT_NE(long_key.response.body.find("'kkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkk"), std::string::npos);
  }
  // A budget run out says what the studio's request can change.
  const ApiCall long_walk = call_api("POST", "/api/walk", R"({"from": 0, "to": 40, "min_frames": 1800})");
  expect_error(long_walk, 422, "ask for fewer frames (min_frames) or another pair of nodes");
  EXPECT_EQ(long_walk.response.body.find("--max-expansions"), std::string::npos);
}

TEST(StudioApi, PathFollowsTheLineDrawnWithItsDeviation) {
  const ApiCall call = call_api(
      "POST", "/api/path",
      R"({"points": [[0, 0], [0, -4], [3, -7]], "segments": [{"from_m": 0, "to_m": 8.3, "tag": "walk"}]})");
  ASSERT_EQ(call.response.status, 200) << call.response.body;
  EXPECT_TRUE(call.json["reached_end"].get<bool>());
  EXPECT_LT(call.json["mean_deviation_m"].get<double>(), 0.5);
  EXPECT_GE(call.json["max_deviation_m"].get<double>(), call.json["mean_deviation_m"].get<double>());
  const json& last = call.json["positions"].back();
  EXPECT_NEAR(last[0].get<double>(), 3.0, 1.0);   // root x
  EXPECT_NEAR(last[2].get<double>(), -7.0, 1.0);  // root z
  EXPECT_EQ(call.json["frame_tags"].size(), call.json["positions"].size());
  // The one segment: its frames, all of the motion's within 8.3 m along the path, and its match,
  // the whole path's.
  ASSERT_EQ(call.json["segments"].size(), 1u);
  const json& segment = call.json["segments"][0];
  EXPECT_EQ(segment["tag"], "walk");
  EXPECT_GT(segment["frames"].get<int>(), 0);
  EXPECT_LE(segment["frames"].get<size_t>(), call.json["positions"].size());
  EXPECT_DOUBLE_EQ(segment["tag_match"].get<double>(), call.json["tag_match"].get<double>());
  // The graph plays walking (some of its clips' walking frames).
  EXPECT_GT(segment["graph_frames"].get<int>(), 0);
  EXPECT_LE(segment["graph_frames"].get<int>(), segment["clip_frames"].get<int>());
  EXPECT_EQ(call.json["shortfalls"], json::array());  // followed as asked: nothing to say
  // A circle of half a metre, which walks cannot turn: what the motion falls short of, said.
  const ApiCall tight =
      call_api("POST", "/api/path", R"({"points": [[0, 0], [0.5, -0.5], [1, 0], [0.5, 0.5], [0, 0]]})");
  ASSERT_EQ(tight.response.status, 200) << tight.response.body;
  ASSERT_TRUE(tight.json["shortfalls"].is_array());
  ASSERT_FALSE(tight.json["shortfalls"].empty());
  const char* said = tight.json["reached_end"].get<bool>() ? "off on average" : "did not reach";
  EXPECT_NE(tight.json["shortfalls"].dump().find(said), std::string::npos)
      << tight.json["shortfalls"].dump();
}

TEST(StudioApi, BadPathsAre4xx) {
  expect_error(call_api("POST", "/api/path", R"({"points": [[0, 0]]})"), 400, "two");
  expect_error(call_api("POST", "/api/path", R"({"points": [[0, 0], [0, "a"]]})"), 400, "points[1]");
  expect_error(call_api("POST", "/api/path", R"({"points": [[0, 0], [0, 1e300]]})"), 400,
               "point 1: 1e+300 m is off the floor (at most 10000 m from the origin)");
  expect_error(call_api("POST", "/api/path", R"({"points": [[1e15, 0], [1e15, 5]]})"), 400, "point 0: 1e+15 m");
  expect_error(call_api("POST", "/api/path", R"({"points": [[0, 0], [0, 500]]})"), 400,
               "the path is 500 m long, over the 200 m a path may be");
  // Just over: the length as it is, not rounded to the bound.
  expect_error(call_api("POST", "/api/path", R"({"points": [[0, 0], [0, 200.5]]})"), 400, "the path is 200.5 m long");
  // Near the floor's edge, a path as any.
  EXPECT_EQ(call_api("POST", "/api/path", R"({"points": [[9990, 0], [9990, -5]]})").response.status, 200);
  expect_error(call_api("POST", "/api/path", R"({"points": [[0, 0], [0, 5]], "segments": [{"from_m": 0, "to_m": 5, "tag": "fly"}]})"),
               400, "fly");
  expect_error(call_api("POST", "/api/path", std::string(2000, '[')), 400, "request body");
  // Each segment costs the search (15 000 fit in a body: a minute's work): at most 100.
  std::string many = R"({"points": [[0, 0], [0, -150]], "segments": [)";
  for (int i = 0; i < 101; ++i) many += fmt::format(R"({}{{"from_m": {}, "to_m": {}, "tag": "walk"}})", i ? ", " : "", i, i + 1);
  expect_error(call_api("POST", "/api/path", many + "]}"), 400, "at most 100 segments");
  expect_error(call_api("POST", "/api/path", R"({"points": [[0, 0], [0, 5]], "edit": false})"), 400,
               "unknown key 'edit'");
  // The body's own options pass; a segment's keys are checked as in a PATH.json file.
  expect_error(call_api("POST", "/api/path",
                        R"({"points": [[0, 0], [0, 5]], "segments": [{"from_m": 0, "to_m": 5, "tag": "walk", "tga": 1}]})"),
               400, "segments[0]: unknown key \"tga\"");
}

TEST(StudioApi, SteeringTurnsTheCharacterTheWayAsked) {
  const ApiCall session = call_api("POST", "/api/steer/sessions", R"({"heading_deg": 90, "tag": "walk"})");
  ASSERT_EQ(session.response.status, 200) << session.response.body;
  const std::string step = "/api/steer/sessions/" + std::to_string(session.json["session"].get<int>()) + "/step";
  json first, last;
  long long expected_first = 0;
  for (int i = 0; i < 12; ++i) {
    const ApiCall call = call_api("POST", step, R"({"heading_deg": 90, "tag": "walk", "min_frames": 15})");
    ASSERT_EQ(call.response.status, 200) << call.response.body;
    EXPECT_EQ(call.json["first_frame"].get<long long>(), expected_first);
    expected_first += call.json["frames"].get<long long>();
    if (i == 0) first = call.json["positions"].front();
    last = call.json["positions"].back();
  }
  // East is +x: after about six seconds the root has gone well east.
  EXPECT_GT(last[0].get<double>() - first[0].get<double>(), 2.0);
  const ApiCall bvh = call_api("GET", "/api/results/" + std::to_string(session.json["result"].get<int>()) + ".bvh");
  ASSERT_EQ(bvh.response.status, 200);
}

// rest: true brings the character to rest at the end of a clip that stops; the step says from when
// it stands and at which clip, and every step after holds that frame until one asks it to move: that
// step starts it off (synthesis/rest_starts.h) and says so.
TEST(StudioApi, SteeringComesToRestWhenAsked) {
  const ApiCall session = call_api("POST", "/api/steer/sessions", R"({"heading_deg": 0, "tag": "walk"})");
  ASSERT_EQ(session.response.status, 200) << session.response.body;
  EXPECT_TRUE(session.json["can_rest"].get<bool>());
  const std::string step = "/api/steer/sessions/" + std::to_string(session.json["session"].get<int>()) + "/step";
  ApiCall call = call_api("POST", step, R"({"heading_deg": 0, "tag": "walk", "min_frames": 30})");
  ASSERT_EQ(call.response.status, 200) << call.response.body;
  EXPECT_TRUE(call.json["rest_s"].is_null() && call.json["rest_clip"].is_null());
  for (int i = 0; i < 20 && call.json["rest_s"].is_null(); ++i) {
    call = call_api("POST", step, R"({"heading_deg": 0, "tag": "walk", "rest": true, "min_frames": 30})");
    ASSERT_EQ(call.response.status, 200) << call.response.body;
  }
  ASSERT_FALSE(call.json["rest_s"].is_null()) << "not at rest after 20 steps";
  const double rest_s = call.json["rest_s"].get<double>();
  EXPECT_GT(rest_s, 1.0);
  EXPECT_EQ(call.json["rest_clip"].get<std::string>().substr(0, 3), "16_");
  // The stopping clip plays on a step's worth at a time, then its last frame is held.
  for (int i = 0; i < 10 && call.json["positions"].front() != call.json["positions"].back(); ++i) {
    call = call_api("POST", step, R"({"heading_deg": 0, "tag": "walk", "rest": true, "min_frames": 30})");
    ASSERT_EQ(call.response.status, 200) << call.response.body;
  }
  // Asked to rest on, it holds its last frame.
  const json held = call.json["positions"].back();
  const ApiCall after = call_api("POST", step, R"({"heading_deg": 0, "tag": "walk", "rest": true, "min_frames": 10})");
  ASSERT_EQ(after.response.status, 200) << after.response.body;
  EXPECT_EQ(after.json["rest_s"].get<double>(), rest_s);
  EXPECT_TRUE(after.json["resting"].get<bool>());
  EXPECT_FALSE(after.json["rest_for_good"].get<bool>());  // there is a start from it
  EXPECT_EQ(after.json["starts"], json::array());
  EXPECT_TRUE(after.json["standing"].get<bool>());
  EXPECT_EQ(after.json["warnings"], json::array());
  for (const json& frame : after.json["positions"]) EXPECT_EQ(frame, held);
  // Asked to turn as it stands: not heard, said once.
  for (const char* heading : {"90", "180"}) {
    const ApiCall turn = call_api(
        "POST", step, fmt::format(R"({{"heading_deg": {}, "tag": "walk", "rest": true, "min_frames": 5}})", heading));
    ASSERT_EQ(turn.response.status, 200) << turn.response.body;
    for (const json& frame : turn.json["positions"]) EXPECT_EQ(frame, held);
    const json said = turn.json["warnings"];
    if (std::string(heading) == "90") {
      ASSERT_EQ(said.size(), 1u) << said.dump();
      EXPECT_NE(said[0].get<std::string>().find("asks to turn while the character stands at rest"), std::string::npos);
    } else {
      EXPECT_EQ(said, json::array());
    }
  }
  // Asked to walk east, it starts off: from where it stood, its start a blend (a transition).
  const ApiCall off = call_api("POST", step, R"({"heading_deg": 90, "tag": "walk", "min_frames": 10})");
  ASSERT_EQ(off.response.status, 200) << off.response.body;
  EXPECT_FALSE(off.json["resting"].get<bool>());
  ASSERT_EQ(off.json["starts"].size(), 1u) << off.json.dump();
  const json& start = off.json["starts"][0];
  EXPECT_DOUBLE_EQ(start["at_s"].get<double>(),
                   off.json["first_frame"].get<double>() / session.json["fps"].get<double>());
  EXPECT_GT(start["rms_cm"].get<double>(), 0.0);
  EXPECT_GE(off.json["transitions"].get<int>(), 1);
  // (each frame the joints' x, y, z in turn, the root's first)
  auto floor_apart = [](const json& a, const json& b) {
    return std::hypot(a[0].get<double>() - b[0].get<double>(), a[2].get<double>() - b[2].get<double>());
  };
  EXPECT_LT(floor_apart(off.json["positions"].front(), held), 0.01);
  ApiCall on = off;
  for (int i = 0; i < 6; ++i) {
    on = call_api("POST", step, R"({"heading_deg": 90, "tag": "walk", "min_frames": 30})");
    ASSERT_EQ(on.response.status, 200) << on.response.body;
    EXPECT_EQ(on.json["starts"], json::array());
  }
  EXPECT_GT(floor_apart(on.json["positions"].back(), held), 2.0);
  expect_error(call_api("POST", step, R"({"rest": 1})"), 400, "'rest' must be true or false");
}

// A path asked to end at rest says where the character stands, as the CLI's report does.
TEST(StudioApi, APathComesToRestWhenAsked) {
  const std::string points = R"("points": [[0, 0], [0, -6], [4, -6]])";
  const ApiCall plain = call_api("POST", "/api/path", "{" + points + "}");
  ASSERT_EQ(plain.response.status, 200) << plain.response.body;
  EXPECT_TRUE(plain.json["rest"].is_null());
  const ApiCall rested = call_api("POST", "/api/path", "{" + points + R"(, "rest_at_end": true})");
  ASSERT_EQ(rested.response.status, 200) << rested.response.body;
  ASSERT_TRUE(rested.json["rest"].is_object()) << rested.json.dump();
  EXPECT_EQ(rested.json["rest"]["clip"].get<std::string>().substr(0, 3), "16_");
  EXPECT_LT(rested.json["end_distance_m"].get<double>(), 0.5);
  const json& last = rested.json["positions"].back();
  const json& before = rested.json["positions"][rested.json["positions"].size() - 10];
  const double dx = last[0].get<double>() - before[0].get<double>();
  const double dz = last[2].get<double>() - before[2].get<double>();
  EXPECT_LT(std::hypot(dx, dz), 0.05);
  expect_error(call_api("POST", "/api/path", "{" + points + R"(, "rest_at_end": "yes"})"), 400,
               "'rest_at_end' must be true or false");
}

// What a control asks that the graph cannot give is said once a session, in the response of the
// call that first asked it, as the CLI's steer warns it; a path's warnings are the segments' and
// its shortfalls, as the CLI's path warns them.
TEST(StudioApi, SteeringAndPathsSayWhatTheGraphCannotGive) {
  const auto stop = unplayable_tag(studio_service().context(), "stop");
  ASSERT_TRUE(stop.has_value());
  const ApiCall session = call_api("POST", "/api/steer/sessions", R"({"heading_deg": 0, "tag": "stop"})");
  ASSERT_EQ(session.response.status, 200) << session.response.body;
  EXPECT_EQ(session.json["warnings"],
            json::array({"the control asks for " + *stop +
                         "; the character comes to rest instead, at the end of a clip that ends standing still"}));
  const std::string step = "/api/steer/sessions/" + std::to_string(session.json["session"].get<int>()) + "/step";
  for (const char* body : {R"({"tag": "stop"})", R"({"tag": "walk"})", R"({"tag": "stop", "heading_deg": 90})"}) {
    const ApiCall call = call_api("POST", step, body);
    ASSERT_EQ(call.response.status, 200) << call.response.body;
    EXPECT_EQ(call.json["warnings"], json::array()) << body;
  }
  // A session of its own says it again.
  const ApiCall other = call_api("POST", "/api/steer/sessions", R"({"tag": "walk"})");
  ASSERT_EQ(other.response.status, 200) << other.response.body;
  EXPECT_EQ(other.json["warnings"], json::array());
  const ApiCall first = call_api(
      "POST", "/api/steer/sessions/" + std::to_string(other.json["session"].get<int>()) + "/step",
      R"({"tag": "stop"})");
  ASSERT_EQ(first.response.status, 200) << first.response.body;
  EXPECT_EQ(first.json["warnings"].size(), 1u);

  const ApiCall path = call_api(
      "POST", "/api/path",
      R"({"points": [[0, 0], [0, -10]], "segments": [{"from_m": 0, "to_m": 5, "tag": "walk"},
                                                     {"from_m": 5, "to_m": 10, "tag": "stop"}]})");
  ASSERT_EQ(path.response.status, 200) << path.response.body;
  json want = json::array({"the segment 5-10 m asks for " + *stop});
  for (const json& shortfall : path.json["shortfalls"]) want.push_back(shortfall);
  EXPECT_EQ(path.json["warnings"], want);
  // A circle of half a metre, followed further off than the retries look for: its shortfalls.
  std::string circle = R"({"points": [)";
  for (int i = 0; i <= 48; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 24.0;
    circle += fmt::format("{}[{:.4f}, {:.4f}]", i ? ", " : "", 0.5 * std::sin(a), -0.5 * std::cos(a) + 0.5);
  }
  const ApiCall tight = call_api("POST", "/api/path", circle + "]}");
  ASSERT_EQ(tight.response.status, 200) << tight.response.body;
  ASSERT_GE(tight.json["shortfalls"].size(), 1u) << tight.response.body.substr(0, 300);
  EXPECT_EQ(tight.json["warnings"], tight.json["shortfalls"]);
}

// A query key a request does not take, or one given twice, is refused (a misspelt "rootmotion"
// downloaded without root motion); a path index is written as it is read back ("01", "-0" named
// clips 1 and 0).
TEST(StudioApi, QueriesAndPathIndicesAreTakenAsWritten) {
  expect_error(call_api("GET", "/api/summary", "", {{"t", "1"}}), 400,
               "unknown query parameter 't' (this request takes none)");
  expect_error(call_api("GET", "/api/clips/0/frames", "", {{"form", "10"}}), 400,
               "unknown query parameter 'form' (this request takes 'from', 'count')");
  expect_error(call_api("GET", "/api/clips/0/frames", "", {{"from", "5"}, {"from", "7"}}), 400,
               "query parameter 'from' is given twice");
  EXPECT_EQ(call_api("GET", "/api/clips/0/frames", "", {{"from", "5"}}).response.status, 200);
  for (const char* index : {"01", "-0", "+1", " 1", "1 "}) {
    expect_error(call_api("GET", std::string("/api/clips/") + index + "/frames"), 404, "no clip");
  }
  EXPECT_EQ(call_api("GET", "/api/clips/1/frames").response.status, 200);
  expect_error(call_api("GET", "/api/clips/0/frames", "", {{"from", "05"}}), 400, "'from' must be an integer");
  // OPTIONS says what a path takes; another method is 405 saying the same.
  const ApiCall options = call_api("OPTIONS", "/api/path");
  EXPECT_EQ(options.response.status, 204);
  EXPECT_EQ(options.response.allow, "POST, OPTIONS");
  const ApiCall wrong = call_api("GET", "/api/path");
  expect_error(wrong, 405, "/api/path takes POST, not GET");
  EXPECT_EQ(wrong.response.allow, "POST, OPTIONS");
  EXPECT_EQ(call_api("HEAD", "/api/summary").response.status, 200);
}

TEST(StudioApi, BadSteeringIs4xx) {
  expect_error(call_api("POST", "/api/steer/sessions", R"({"tag": "fly"})"), 400, "'fly' is not a motion tag");
  // A tag of 100 KB is named by its first 40 characters, not echoed whole.
  const ApiCall huge = call_api("POST", "/api/steer/sessions", R"({"tag": ")" + std::string(100000, 'x') + "\"}");
  expect_error(huge, 400, "'" + std::string(40, 'x') + "...' is not a motion tag");
  EXPECT_LT(huge.response.body.size(), 400u);
  expect_error(call_api("POST", "/api/steer/sessions", R"({"heading_deg": 1e9})"), 400, "heading_deg");
  expect_error(call_api("POST", "/api/steer/sessions/77777/step", "{}"), 404, "no steering session");
  expect_error(call_api("POST", "/api/steer/sessions/x/step", "{}"), 404, "no steering session");
  const ApiCall session = call_api("POST", "/api/steer/sessions", "{}");
  ASSERT_EQ(session.response.status, 200);
  const std::string step = "/api/steer/sessions/" + std::to_string(session.json["session"].get<int>()) + "/step";
  expect_error(call_api("POST", step, R"({"min_frames": 0})"), 400, "min_frames");
  expect_error(call_api("POST", step, R"({"heading_deg": "north"})"), 400, "heading_deg");
  expect_error(call_api("POST", step, R"({"heading": 90})"), 400, "unknown key 'heading'");
  expect_error(call_api("POST", "/api/steer/sessions", R"({"bogus": 1})"), 400, "unknown key 'bogus'");
}

TEST(StudioApi, SessionsAndResultsAreBounded) {
  const ApiCall first = call_api("POST", "/api/steer/sessions", "{}");
  ASSERT_EQ(first.response.status, 200);
  const std::string step = "/api/steer/sessions/" + std::to_string(first.json["session"].get<int>()) + "/step";
  ASSERT_EQ(call_api("POST", step, "{}").response.status, 200);
  for (int i = 0; i < studio::SessionLimits{}.max_sessions; ++i) {
    ASSERT_EQ(call_api("POST", "/api/steer/sessions", "{}").response.status, 200);
  }
  // The least recently used session went; so did the oldest results.
  expect_error(call_api("POST", step, "{}"), 404, "no steering session");
  for (int i = 0; i < studio::SynthesisService::kMaxResults; ++i) {
    ASSERT_EQ(call_api("POST", "/api/walk", R"({"from": 0, "to": 1, "min_frames": 0})").response.status, 200);
  }
  expect_error(call_api("GET", "/api/results/" + std::to_string(first.json["result"].get<int>()) + ".bvh"), 404,
               "no result");
}

// At its limit of sessions, all in use: a new session is refused as the server being busy (503,
// saying how to raise the limit), not as a bad request.
TEST(StudioApi, ANewSessionWhileAllAreInUseIsRefusedAsBusy) {
  auto graph = LoadedGraph::create(test::subject16_graph_file(), "s16.mgraph");
  ASSERT_TRUE(graph) << graph.error().to_string();
  const auto service = studio::SynthesisService::create(std::move(*graph), "s16.mgraph");
  ASSERT_TRUE(service->set_session_limits({1, 60.0}));
  const studio::StudioApi api(*service);
  EXPECT_EQ(api.handle({"POST", "/api/steer/sessions", {}, "{}"}).status, 200);
  const studio::ApiResponse refused = api.handle({"POST", "/api/steer/sessions", {}, "{}"});
  EXPECT_EQ(refused.status, 503);
  EXPECT_NE(refused.body.find("--max-sessions"), std::string::npos) << refused.body;
}

TEST(StudioApi, OneSessionSteppedFromSeveralThreadsHandsOutEachFrameOnce) {
  const ApiCall session = call_api("POST", "/api/steer/sessions", R"({"tag": "walk"})");
  ASSERT_EQ(session.response.status, 200);
  const std::string step = "/api/steer/sessions/" + std::to_string(session.json["session"].get<int>()) + "/step";
  std::mutex mutex;
  std::vector<std::pair<long long, long long>> ranges;  // [first, first + frames)
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 5; ++i) {
        const ApiCall call = call_api("POST", step, R"({"heading_deg": )" + std::to_string(90 * t) + "}");
        if (call.response.status != 200) continue;
        std::lock_guard lock(mutex);
        ranges.emplace_back(call.json["first_frame"].get<long long>(),
                            call.json["first_frame"].get<long long>() + call.json["frames"].get<long long>());
      }
    });
  }
  for (auto& t : threads) t.join();
  ASSERT_EQ(ranges.size(), 20u);
  std::sort(ranges.begin(), ranges.end());
  long long next = 0;
  for (const auto& [first, end] : ranges) {
    EXPECT_EQ(first, next);
    EXPECT_GT(end, first);
    next = end;
  }
}

}  // namespace
}  // namespace mg::test
