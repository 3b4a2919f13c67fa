#include "motiongraph/motion/in_place.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "motion/static_root_bvh.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/trajectory_joint.h"
#include "test_data.h"

namespace mg {
namespace {

// Captures of every kind the project has: walks, turns, runs, jumps, a stop; AMC and the BVH of
// three converters (07_12, a broken conversion: its feet slide 1.5 m/s, but its root travels
// faster than that, so it is no clip in place).
const char* const kCaptures[] = {"cmu/16/16_01.amc", "cmu/16/16_05.amc", "cmu/16/16_11.amc", "cmu/16/16_17.amc",
                                 "cmu/16/16_33.amc", "cmu/16/16_35.amc", "cmu/16/16_41.amc", "cmu/16/16_57.amc",
                                 "bvh/07_01.bvh",    "bvh/07_12.bvh",    "bvh/111_36.bvh",   "bvh/131_01.bvh",
                                 "bvh/16_01.bvh"};

// The clip as an "in place" export holds it: joint 0's travel over the floor taken out, its
// height and sway about the clip's line of travel... all but x and z kept.
Clip in_place(const Clip& clip) {
  Clip out = clip;
  const int slot = out.skeleton.translation_slot(0);
  for (int f = 0; f < out.motion.frame_count; ++f) {
    Vec3& t = out.motion.translations(f)[slot];
    t.x() = 0.0;
    t.z() = 0.0;
  }
  out.in_place.reset();
  return out;
}

std::vector<Vec3> root_positions(const Clip& clip) {
  const std::vector<Vec3> world = world_positions(clip.skeleton, clip.motion);
  std::vector<Vec3> out;
  const int joints = clip.skeleton.joint_count();
  for (int f = 0; f < clip.motion.frame_count; ++f) out.push_back(world[static_cast<size_t>(f) * joints]);
  return out;
}

// The root's path over the floor, sampled every half second and at the last frame, its length.
double floor_travel(const std::vector<Vec3>& path, double fps) {
  const size_t every = static_cast<size_t>(std::lround(0.5 * fps));
  double length = 0.0;
  size_t last = 0;
  for (size_t f = every; f < path.size() + every - 1; f += every) {
    const size_t at = std::min(f, path.size() - 1);
    Vec3 d = path[at] - path[last];
    d.y() = 0.0;
    length += d.norm();
    last = at;
  }
  return length;
}

InPlaceChoice judge(const Clip& clip) {
  auto feet = find_foot_joints(clip.skeleton);
  EXPECT_TRUE(feet) << feet.error().to_string();
  return judge_in_place(world_positions(clip.skeleton, clip.motion), clip.skeleton.joint_count(), clip.motion.fps,
                        *feet);
}

TEST(InPlace, NamesParse) {
  EXPECT_EQ(parse_travel_source("auto"), TravelSource::kAuto);
  EXPECT_EQ(parse_travel_source("Root"), TravelSource::kRoot);
  EXPECT_EQ(parse_travel_source("FEET"), TravelSource::kFeet);
  for (const char* bad : {"", "yes", "foot", "roots", "none"}) EXPECT_FALSE(parse_travel_source(bad)) << bad;
  for (TravelSource s : {TravelSource::kAuto, TravelSource::kRoot, TravelSource::kFeet}) {
    EXPECT_EQ(parse_travel_source(travel_source_name(s)), s);
  }
}

TEST(InPlace, SettingsValidate) {
  EXPECT_TRUE(InPlaceSettings{}.validate());
  const auto broken = [](auto change) {
    InPlaceSettings s;
    change(s);
    return !s.validate();
  };
  EXPECT_TRUE(broken([](InPlaceSettings& s) { s.contact_height_m = 0.0; }));
  EXPECT_TRUE(broken([](InPlaceSettings& s) { s.contact_height_m = std::nan(""); }));
  EXPECT_TRUE(broken([](InPlaceSettings& s) { s.floor_quantile = 1.5; }));
  EXPECT_TRUE(broken([](InPlaceSettings& s) { s.min_slide_speed = -1.0; }));
  EXPECT_TRUE(broken([](InPlaceSettings& s) { s.root_speed_ratio = -0.5; }));
  EXPECT_TRUE(broken([](InPlaceSettings& s) { s.direction_window_s = INFINITY; }));
}

// No capture is taken for a clip in place: each keeps its root's travel, bit for bit.
TEST(InPlace, CapturesKeepTheirRootsTravel) {
  for (const char* file : kCaptures) {
    const Clip clip = test::load_data_clip(file);
    ASSERT_TRUE(clip.in_place) << file;  // every one has its feet found
    EXPECT_FALSE(clip.in_place->in_place) << file;
    EXPECT_FALSE(clip.in_place->recovered) << file;
    if (std::string(file) != "bvh/07_12.bvh") {
      EXPECT_LT(clip.in_place->slide_speed_m_s, InPlaceSettings{}.min_slide_speed) << file;
    } else {
      EXPECT_GT(clip.in_place->root_speed_m_s, clip.in_place->slide_speed_m_s) << file;
    }
    Clip as_read = clip;
    ASSERT_TRUE(recover_travel(as_read, TravelSource::kRoot));
    EXPECT_EQ(as_read.motion.local_translations_m, clip.motion.local_translations_m) << file;
  }
}

// Walks and runs with their travel taken out are judged in place; recovered, the planted foot
// stands still and the root travels about as far as it did in the capture, the same way.
TEST(InPlace, WalksAndRunsInPlaceGetTheirTravelBack) {
  struct Case {
    const char* file;
    double least_share;  // of the capture's travel
  };
  // A capture's planted foot slips: 0.05-0.1 m/s in a walk, 0.2-0.3 in a run, so a run gets
  // back less.
  const Case cases[] = {{"cmu/16/16_11.amc", 0.9}, {"cmu/16/16_15.amc", 0.9}, {"cmu/16/16_17.amc", 0.9},
                        {"cmu/16/16_19.amc", 0.9}, {"cmu/16/16_33.amc", 0.9}, {"cmu/16/16_35.amc", 0.7},
                        {"cmu/16/16_39.amc", 0.7}, {"cmu/16/16_57.amc", 0.7}};
  for (const Case& c : cases) {
    const Clip capture = test::load_data_clip(c.file);
    Clip clip = in_place(capture);
    const InPlaceChoice before = judge(clip);
    EXPECT_TRUE(before.in_place) << c.file << " slide " << before.slide_speed_m_s;
    EXPECT_LT(before.root_speed_m_s, 0.1) << c.file;

    ASSERT_TRUE(recover_travel(clip, TravelSource::kAuto)) << c.file;
    ASSERT_TRUE(clip.in_place) << c.file;
    EXPECT_TRUE(clip.in_place->in_place && clip.in_place->recovered) << c.file;
    // Each ground interval's planted joint is held where it is: the stillest low joint is still.
    const InPlaceChoice after = judge(clip);
    EXPECT_LT(after.slide_speed_m_s, 1e-9) << c.file;
    EXPECT_FALSE(after.in_place) << c.file;

    const std::vector<Vec3> truth = root_positions(capture), got = root_positions(clip);
    const double fps = clip.motion.fps;
    const double travel = floor_travel(truth, fps), recovered = floor_travel(got, fps);
    EXPECT_GE(recovered, c.least_share * travel) << c.file;
    EXPECT_LE(recovered, 1.05 * travel) << c.file;
    EXPECT_NEAR(clip.in_place->recovered_m, recovered, 0.05 * travel) << c.file;
    // The same way: the net displacement's direction within 10 degrees.
    Vec3 a = truth.back() - truth.front(), b = got.back() - got.front();
    a.y() = b.y() = 0.0;
    EXPECT_GT(a.normalized().dot(b.normalized()), std::cos(10.0 * std::numbers::pi / 180.0)) << c.file;
    // Heights, rotations and the other joints' motion relative to the root are the clip's.
    for (int f = 0; f < clip.motion.frame_count; ++f) {
      EXPECT_DOUBLE_EQ(got[f].y(), truth[f].y());
    }
    EXPECT_EQ(clip.motion.local_rotations, capture.motion.local_rotations) << c.file;
  }
}

// Recovery depends on where the figure stands and which way it faces only by that placement:
// moved and turned about the vertical, the travel recovered is moved and turned alike.
TEST(InPlace, RecoveryFollowsThePlacement) {
  const Clip walk = in_place(test::load_data_clip("cmu/16/16_17.amc"));
  Clip plain = walk;
  ASSERT_TRUE(recover_travel(plain, TravelSource::kFeet));
  const Quat turn(Eigen::AngleAxisd(2.1, Vec3::UnitY()));
  const Vec3 shift(3.0, 0.0, -7.5);
  Clip placed = walk;
  const int slot = placed.skeleton.translation_slot(0);
  for (int f = 0; f < placed.motion.frame_count; ++f) {
    Vec3& t = placed.motion.translations(f)[slot];
    t = turn * t + shift;
    Quat& q = placed.motion.rotations(f)[0];
    q = (turn * q).normalized();
  }
  ASSERT_TRUE(recover_travel(placed, TravelSource::kFeet));
  const std::vector<Vec3> a = root_positions(plain), b = root_positions(placed);
  for (size_t f = 0; f < a.size(); ++f) EXPECT_LT((turn * a[f] + shift - b[f]).norm(), 1e-6) << f;
}

// Asked for its feet, a capture that travels keeps about its travel: its planted feet's slip is
// taken out (they stand still), not its walk: a few per cent of a walk's travel, a fifth of a
// run's (its planted foot slips 0.2-0.3 m/s as captured).
TEST(InPlace, ACaptureAskedForItsFeetPlantsThem) {
  const std::pair<const char*, double> cases[] = {
      {"cmu/16/16_15.amc", 0.1}, {"cmu/16/16_19.amc", 0.1}, {"cmu/16/16_35.amc", 0.25}, {"bvh/111_36.bvh", 0.1}};
  for (const auto& [file, share] : cases) {
    const Clip capture = test::load_data_clip(file);
    Clip clip = capture;
    ASSERT_TRUE(recover_travel(clip, TravelSource::kFeet)) << file;
    EXPECT_TRUE(clip.in_place->recovered && !clip.in_place->in_place) << file;
    EXPECT_LT(judge(clip).slide_speed_m_s, 1e-9) << file;
    const double fps = clip.motion.fps;
    const double travel = floor_travel(root_positions(capture), fps);
    EXPECT_NEAR(floor_travel(root_positions(clip), fps), travel, share * travel) << file;
  }
}

// A standing clip has no travel to recover, asked or not: the feet stay planted.
TEST(InPlace, StandingStillRecoversNoTravel) {
  Clip jump = test::load_data_clip("cmu/16/16_01.amc");  // a jump on the spot: 0.09 m of travel
  const std::vector<Vec3> before = root_positions(jump);
  ASSERT_TRUE(recover_travel(jump, TravelSource::kFeet));
  EXPECT_TRUE(jump.in_place->recovered);
  EXPECT_LT(jump.in_place->recovered_m, 0.5);
  const std::vector<Vec3> after = root_positions(jump);
  EXPECT_LT((after.back() - before.back()).norm(), 0.4);
}

// The travel from the feet, when the clip has no foot joint on the floor (every frame in the
// air), is none; and a clip of two frames, or no feet at all, has none either.
TEST(InPlace, NoGroundNoTravel) {
  Clip clip = in_place(test::load_data_clip("cmu/16/16_15.amc"));
  auto feet = find_foot_joints(clip.skeleton);
  ASSERT_TRUE(feet);
  const std::vector<Vec3> world = world_positions(clip.skeleton, clip.motion);
  const int joints = clip.skeleton.joint_count();
  InPlaceSettings tiny;
  tiny.contact_height_m = 1e-9;
  tiny.floor_quantile = 0.0;  // only each joint's lowest frame is low: no interval has both ends low
  const std::vector<Vec3> none = travel_from_feet(world, joints, clip.motion.fps, *feet, true, tiny);
  ASSERT_EQ(none.size(), static_cast<size_t>(clip.motion.frame_count));
  for (const Vec3& v : none) EXPECT_EQ(v, Vec3::Zero());
  EXPECT_EQ(travel_from_feet(std::span(world).first(joints), joints, clip.motion.fps, *feet, true).size(), 1u);
  EXPECT_TRUE(travel_from_feet(world, joints, clip.motion.fps, FootJoints{}, true).back().isZero());
  EXPECT_FALSE(judge_in_place(world, joints, clip.motion.fps, FootJoints{}).in_place);
}

TEST(InPlace, FeetNotFound) {
  Clip clip = in_place(test::load_data_clip("cmu/16/16_15.amc"));
  FootJointNames names;
  names.left_ankle = "no_such_joint";
  Clip automatic = clip;
  ASSERT_TRUE(recover_travel(automatic, TravelSource::kAuto, names));  // cannot judge: left as read
  EXPECT_FALSE(automatic.in_place);
  EXPECT_EQ(automatic.motion.local_translations_m, clip.motion.local_translations_m);
  const Status asked = recover_travel(clip, TravelSource::kFeet, names);
  ASSERT_FALSE(asked);
  EXPECT_NE(asked.error().message.find("cannot recover its travel from the feet"), std::string::npos);
  EXPECT_NE(asked.error().message.find("no_such_joint"), std::string::npos) << asked.error().message;
}

TEST(InPlace, ARootWithoutTranslationCannotCarryIt) {
  const Clip walk = in_place(test::load_data_clip("cmu/16/16_15.amc"));
  // The same skeleton with joint 0's translation fixed at its rest offset.
  std::vector<JointDef> joints(walk.skeleton.joints().begin(), walk.skeleton.joints().end());
  joints[0].animated_translation = false;
  Clip fixed;
  fixed.skeleton = Skeleton(std::move(joints));
  fixed.motion = Motion(fixed.skeleton, walk.motion.frame_count, walk.motion.fps);
  fixed.motion.local_rotations = walk.motion.local_rotations;
  for (int f = 0; f < walk.motion.frame_count; ++f) {
    for (size_t i = 0; i < fixed.skeleton.translated_joints().size(); ++i) {
      const int joint = fixed.skeleton.translated_joints()[i];
      fixed.motion.translations(f)[i] = walk.motion.translations(f)[walk.skeleton.translation_slot(joint)];
    }
  }
  Clip automatic = fixed;
  ASSERT_TRUE(recover_travel(automatic, TravelSource::kAuto));
  ASSERT_TRUE(automatic.in_place);
  EXPECT_FALSE(automatic.in_place->recovered);
  const Status asked = recover_travel(fixed, TravelSource::kFeet);
  ASSERT_FALSE(asked);
  EXPECT_NE(asked.error().message.find("no translation channels"), std::string::npos) << asked.error().message;
}

// A BVH in place as a game library writes it: centimetres, a static root above the hips, the
// hips' travel taken out. Read with no options it travels as the capture did, and written back
// (the input's hierarchy, the travel in the hips' channels) it reads back to the same positions.
TEST(InPlace, AStaticRootBvhInCentimetresInPlace) {
  const Clip capture = test::load_data_clip("cmu/16/16_16.amc");
  Clip clip = test::import_bvh(test::static_root_bvh(in_place(capture), Vec3(0.5, 0.0, -1.0)));
  ASSERT_EQ(clip.skeleton.static_ancestors().size(), 1u);
  ASSERT_TRUE(recover_travel(clip, TravelSource::kAuto));
  ASSERT_TRUE(clip.in_place && clip.in_place->recovered);
  const double fps = clip.motion.fps;
  const double travel = floor_travel(root_positions(capture), fps);
  EXPECT_GE(floor_travel(root_positions(clip), fps), 0.9 * travel);
  EXPECT_LE(floor_travel(root_positions(clip), fps), 1.05 * travel);

  BvhWriteSettings write;
  write.units_per_metre = 100.0;
  const Clip unfolded = unfold_static_root(clip);
  Clip kept = test::import_bvh(write_bvh(unfolded.skeleton, unfolded.motion, write));
  ASSERT_TRUE(recover_travel(kept, TravelSource::kAuto));
  EXPECT_FALSE(kept.in_place->in_place);  // it travels now
  EXPECT_LT(test::max_position_error(world_positions(kept.skeleton, kept.motion),
                                     world_positions(clip.skeleton, clip.motion)),
            1e-4);
}

}  // namespace
}  // namespace mg
