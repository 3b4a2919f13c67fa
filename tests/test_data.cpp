#include "test_data.h"

#include <algorithm>
#include <stdexcept>

#include <gtest/gtest.h>

#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"

namespace mg::test {

std::string data_path(const std::string& relative) { return std::string(MOTIONGRAPH_DATA_DIR) + "/" + relative; }

Clip import_bvh(const std::string& text, const BvhImportSettings& settings) {
  auto doc = parse_bvh(text, "test.bvh");
  if (!doc) throw std::runtime_error(doc.error().to_string());
  auto clip = clip_from_bvh(*doc, settings);
  if (!clip) throw std::runtime_error(clip.error().to_string());
  return *std::move(clip);
}

std::string read_data(const std::string& relative) {
  auto text = read_text_file(data_path(relative));
  if (!text) throw std::runtime_error(text.error().to_string());
  return std::move(*text);
}

namespace {

Clip load_with(const std::string& relative, const ClipLoadSettings& settings) {
  ClipLoader loader(settings);
  auto loaded = loader.load(data_path(relative));
  if (!loaded) throw std::runtime_error(loaded.error().to_string());
  return std::move(loaded->clip);
}

}  // namespace

Clip load_data_clip(const std::string& relative, std::optional<double> bvh_metres_per_unit, double input_fps) {
  ClipLoadSettings settings;
  settings.bvh_metres_per_unit = bvh_metres_per_unit;
  settings.input_fps = input_fps;
  return load_with(relative, settings);
}

Clip load_whole_data_clip(const std::string& relative) {
  ClipLoadSettings settings;
  settings.keep_rest_frames = true;
  return load_with(relative, settings);
}

std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

void expect_error_matches(const Error& error, const ErrorCase& expected) {
  EXPECT_EQ(error.line, expected.line) << expected.rule << ": " << error.to_string();
  EXPECT_NE(error.message.find(expected.message_part), std::string::npos) << expected.rule << ": " << error.to_string();
}

ScaledPair scaled_pair(double scale, int from, int window) {
  ScaledPair pair{load_data_clip("bvh/131_01.bvh", 0.056444), load_data_clip("bvh/131_01.bvh", 0.056444 * scale), {}, {}};
  MotionDatabase& db = pair.db;
  db.fps = pair.small.motion.fps;
  db.skeletons = {pair.small.skeleton, pair.large.skeleton};
  db.skeleton_names = {"small", "large"};
  const int n = pair.small.motion.frame_count;
  db.clips.push_back({"small", "", 0, 0, n, pair.small.motion});
  db.clips.push_back({"large", "", 1, n, n, pair.large.motion});
  Transition& t = pair.transition;
  t.from_frame = from;
  t.to_frame = n + from + window - 1;
  // The floor alignment of the large window onto the small one: the shift of the centroids.
  const Vec3 c_large = pair.large.motion.translations(from + window - 1)[0];
  t.x_m = static_cast<float>(c_large.x() / scale - c_large.x());
  t.z_m = static_cast<float>(c_large.z() / scale - c_large.z());
  return pair;
}

MotionDatabase small_database(const std::vector<std::string>& files, bool add_moved_copy, double yaw, Vec3 shift,
                              double fps) {
  MotionDatabase db;
  db.fps = fps;
  for (const std::string& file : files) {
    Clip clip = load_data_clip(file);
    if (db.skeletons.empty()) db.skeletons.push_back(clip.skeleton);
    DatabaseClip entry;
    entry.name = clip.name;
    entry.source = file;
    entry.first_frame = db.frame_count();
    entry.motion = *resample(clip.motion, db.fps);
    entry.frame_count = entry.motion.frame_count;
    db.clips.push_back(std::move(entry));
  }
  if (add_moved_copy) {
    DatabaseClip copy = db.clips.front();
    copy.name += "_moved";
    copy.first_frame = db.frame_count();
    const Quat turn = axis_rotation(Axis::kY, yaw);
    for (int f = 0; f < copy.motion.frame_count; ++f) {
      copy.motion.rotations(f)[0] = turn * copy.motion.rotations(f)[0];
      copy.motion.translations(f)[0] = turn * copy.motion.translations(f)[0] + shift;
    }
    db.clips.push_back(std::move(copy));
  }
  return db;
}

double max_position_error(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.size() != b.size()) throw std::runtime_error("position arrays differ in size");
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

double max_position_error_by_name(const Clip& a, const Clip& b) {
  const auto pa = world_positions(a.skeleton, a.motion);
  const auto pb = world_positions(b.skeleton, b.motion);
  EXPECT_EQ(a.motion.frame_count, b.motion.frame_count);
  const int frames = std::min(a.motion.frame_count, b.motion.frame_count);
  const size_t ja_count = static_cast<size_t>(a.skeleton.joint_count());
  const size_t jb_count = static_cast<size_t>(b.skeleton.joint_count());
  double worst = 0.0;
  for (int ja = 0; ja < a.skeleton.joint_count(); ++ja) {
    auto jb = b.skeleton.find(a.skeleton.joint(ja).name);
    if (!jb) {
      ADD_FAILURE() << "joint " << a.skeleton.joint(ja).name << " lost";
      continue;
    }
    for (int f = 0; f < frames; ++f) {
      worst = std::max(worst, (pa[f * ja_count + static_cast<size_t>(ja)] - pb[f * jb_count + static_cast<size_t>(*jb)]).norm());
    }
  }
  return worst;
}

// The clip with a three-joint finger hung from each wrist (appended after the other joints, so
// theirs keep their indices), turning a little every frame: a rig exported with fingers.
Clip with_fingers(const Clip& clip) {
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  for (const char* wrist : {"lwrist", "rwrist"}) {
    int parent = *clip.skeleton.find(wrist);
    for (int k = 0; k < 3; ++k) {
      JointDef finger;
      finger.name = std::string(wrist) + "_finger" + std::to_string(k);
      finger.parent = parent;
      finger.rest_offset_m = Vec3(0.0, -0.03, 0.0);
      parent = static_cast<int>(joints.size());
      joints.push_back(finger);
    }
  }
  Clip out = clip;
  out.skeleton = Skeleton(std::move(joints));
  out.motion = Motion(out.skeleton, clip.motion.frame_count, clip.motion.fps);
  for (int f = 0; f < clip.motion.frame_count; ++f) {
    auto rotations = out.motion.rotations(f);
    for (int j = 0; j < out.skeleton.joint_count(); ++j) {
      rotations[j] = j < clip.skeleton.joint_count() ? clip.motion.rotations(f)[j]
                                                     : Quat(Eigen::AngleAxisd(0.01 * f, Vec3::UnitZ()));
    }
    std::copy(clip.motion.translations(f).begin(), clip.motion.translations(f).end(),
              out.motion.translations(f).begin());
  }
  return out;
}

Clip held_pose(const Clip& clip, int first, int frames) {
  Clip pose = clip;
  pose.motion = clip.motion.slice(first, frames);
  for (int f = 1; f < pose.motion.frame_count; ++f) {
    for (int j = 0; j < clip.skeleton.joint_count(); ++j) pose.motion.rotations(f)[j] = pose.motion.rotations(0)[j];
    pose.motion.translations(f)[0] = pose.motion.translations(0)[0];
  }
  return pose;
}

}  // namespace mg::test
