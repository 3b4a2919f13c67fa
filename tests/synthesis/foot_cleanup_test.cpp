#include "motiongraph/synthesis/foot_cleanup.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "test_data.h"

namespace mg {
namespace {

// A CMU walk at 30 fps, its feet, and its contacts as masks.
struct Walked {
  Clip clip;
  FootJoints feet;
  std::vector<ContactMask> contacts;
};

Walked walked(const char* file = "cmu/16/16_15.amc") {
  Walked w{test::load_data_clip(file), {}, {}};
  w.clip.motion = *resample(w.clip.motion, 30.0);
  w.feet = *find_foot_joints(w.clip.skeleton);
  const FootContacts contacts = *detect_foot_contacts(w.clip.skeleton, w.clip.motion, w.feet, {});
  for (int f = 0; f < w.clip.motion.frame_count; ++f) w.contacts.push_back(contact_mask(contacts, f));
  return w;
}

// The motion with its root sliding sideways at `speed` m/s and swaying by `sway` m: planted
// feet slide with it, as they do where synthesis aligns and blends pieces.
Motion sliding(const Motion& motion, double speed, double sway = 0.0) {
  Motion out = motion;
  for (int f = 0; f < out.frame_count; ++f) {
    const double t = f / out.fps;
    out.translations(f)[0].x() += speed * t + sway * std::sin(2.0 * t);
    out.translations(f)[0].z() += 0.5 * sway * std::sin(3.0 * t);
  }
  return out;
}

Motion cleaned(const Walked& w, const Motion& motion, const FootCleanupSettings& settings = {},
               FootCleanupStats* stats = nullptr) {
  auto cleanup = FootCleanup::create(w.clip.skeleton, w.feet, motion.fps, settings);
  EXPECT_TRUE(cleanup) << cleanup.error().to_string();
  Motion out = motion;
  const Status s = cleanup->clean(out, 0, w.contacts);
  EXPECT_TRUE(s) << s.error().to_string();
  if (stats) *stats = cleanup->stats();
  return out;
}

double horizontal(const Vec3& a, const Vec3& b) { return std::hypot(a.x() - b.x(), a.z() - b.z()); }

// The largest per-frame step of any joint relative to the root.
double max_joint_step(const std::vector<Vec3>& p, int joints) {
  double most = 0.0;
  const int frames = static_cast<int>(p.size()) / joints;
  for (int f = 1; f < frames; ++f) {
    for (int j = 1; j < joints; ++j) {
      const Vec3 now = p[f * joints + j] - p[f * joints], before = p[(f - 1) * joints + j] - p[(f - 1) * joints];
      most = std::max(most, (now - before).norm());
    }
  }
  return most;
}

TEST(FootCleanup, PlantedFeetStayOnTheirPlantsOnTheFloor) {
  // Sliding about as fast as synthesized motion does before the clean-up (subject 16's
  // figure 8: 0.1 m/s on average, twice that at the 95th percentile).
  const Walked w = walked();
  const Motion input = sliding(w.clip.motion, 0.15, 0.03);
  FootCleanupStats stats;
  const Motion output = cleaned(w, input, {}, &stats);
  const int joints = w.clip.skeleton.joint_count();
  const std::vector<Vec3> before = world_positions(w.clip.skeleton, input);
  const std::vector<Vec3> after = world_positions(w.clip.skeleton, output);
  // Where a leg cannot reach even with the root lowered as far as it may be (3 cm), the ankle
  // falls short by a few millimetres.
  EXPECT_LT(stats.max_ankle_miss_m, 0.01);
  int checked = 0;
  double slide_before = 0.0;
  for (const auto& [foot, side] : {std::pair{w.feet.left, FootSide::kLeft}, std::pair{w.feet.right, FootSide::kRight}}) {
    for (const auto& [joint, part] : {std::pair{foot.ankle, FootPart::kAnkle}, std::pair{foot.toe, FootPart::kToe}}) {
      // An ankle holds its plant while its toe is not planted (the toe governs: a rising heel
      // pivots about it).
      std::vector<uint8_t> planted;
      for (ContactMask m : w.contacts) {
        const bool toe = (m & contact_bit(side, FootPart::kToe)) != 0;
        planted.push_back((m & contact_bit(side, part)) != 0 && (part == FootPart::kToe || !toe));
      }
      for (const ContactInterval& c : contact_intervals(planted)) {
        const Vec3 plant = after[c.first_frame * joints + joint];
        for (int f = c.first_frame; f < c.first_frame + c.frame_count; ++f) {
          // Held on the floor (heights are the motion's); a toe, turned onto its plant, may miss
          // by what its ankle does.
          EXPECT_LT(horizontal(after[f * joints + joint], plant), part == FootPart::kAnkle ? 0.003 : 0.006)
              << "joint " << joint << " frame " << f;
          slide_before = std::max(slide_before, horizontal(before[f * joints + joint], before[c.first_frame * joints + joint]));
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(slide_before, 0.1);  // the input did slide
}

TEST(FootCleanup, BoneLengthsAndEverythingButTheLegsAndTheRootsHeightAreKept) {
  const Walked w = walked();
  const Motion input = sliding(w.clip.motion, 0.3, 0.05);
  const Motion output = cleaned(w, input);
  const Skeleton& sk = w.clip.skeleton;
  const int joints = sk.joint_count();
  const std::vector<Vec3> before = world_positions(sk, input), after = world_positions(sk, output);
  const std::vector<int> legs{sk.parent(sk.parent(w.feet.left.ankle)),  sk.parent(w.feet.left.ankle),  w.feet.left.ankle,
                              sk.parent(sk.parent(w.feet.right.ankle)), sk.parent(w.feet.right.ankle), w.feet.right.ankle};
  int changed = 0;
  for (int f = 0; f < input.frame_count; ++f) {
    for (int j = 1; j < joints; ++j) {
      const double length_before = (before[f * joints + j] - before[f * joints + sk.parent(j)]).norm();
      const double length_after = (after[f * joints + j] - after[f * joints + sk.parent(j)]).norm();
      ASSERT_NEAR(length_after, length_before, 1e-9) << "frame " << f << " joint " << j;
      if (std::find(legs.begin(), legs.end(), j) == legs.end()) {
        ASSERT_EQ(output.rotations(f)[j].coeffs(), input.rotations(f)[j].coeffs()) << "frame " << f << " joint " << j;
      } else if (!output.rotations(f)[j].isApprox(input.rotations(f)[j], 1e-12)) {
        ++changed;
      }
    }
    EXPECT_EQ(output.translations(f)[0].x(), input.translations(f)[0].x());
    EXPECT_EQ(output.translations(f)[0].z(), input.translations(f)[0].z());
    EXPECT_LE(output.translations(f)[0].y(), input.translations(f)[0].y());  // only ever lowered
    EXPECT_GE(output.translations(f)[0].y(), input.translations(f)[0].y() - FootCleanupSettings{}.max_root_drop_m - 1e-12);
  }
  EXPECT_GT(changed, input.frame_count);
}

TEST(FootCleanup, AddsNoStepAndTheKneeBendsTheUsualWay) {
  for (const char* file : {"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_57.amc"}) {
    const Walked w = walked(file);
    const Motion input = sliding(w.clip.motion, 0.15, 0.03);
    const Motion output = cleaned(w, input);
    const Skeleton& sk = w.clip.skeleton;
    const int joints = sk.joint_count();
    const std::vector<Vec3> before = world_positions(sk, input), after = world_positions(sk, output);
    EXPECT_LE(max_joint_step(after, joints), 1.5 * max_joint_step(before, joints)) << file;
    // The knee's bend axis, in the hip joint's frame, where it bends by 10 degrees or more:
    // on the side the capture bends it.
    std::vector<Vec3> p(joints);
    std::vector<Quat> r_in(joints), r_out(joints);
    for (const Foot& foot : {w.feet.left, w.feet.right}) {
      const int knee = sk.parent(foot.ankle), hip = sk.parent(knee);
      Vec3 usual = Vec3::Zero();
      for (int f = 0; f < input.frame_count; ++f) {
        forward_kinematics(sk, input, f, p, r_in);
        const Vec3 bend = (p[knee] - p[hip]).cross(p[foot.ankle] - p[knee]);
        if (bend.norm() > 0.05) usual += r_in[hip].conjugate() * bend.normalized();
      }
      ASSERT_GT(usual.norm(), 1.0) << file;
      for (int f = 0; f < output.frame_count; ++f) {
        forward_kinematics(sk, output, f, p, r_out);
        const Vec3 thigh = p[knee] - p[hip], shank = p[foot.ankle] - p[knee];
        const Vec3 bend = thigh.cross(shank);
        if (bend.norm() > std::sin(10.0 * std::numbers::pi / 180.0) * thigh.norm() * shank.norm()) {
          EXPECT_GT((r_out[hip].conjugate() * bend).dot(usual), 0.0) << file << " frame " << f;
        }
      }
    }
  }
}

TEST(FootCleanup, FramesCleanedInPiecesAreTheFramesCleanedAtOnce) {
  // Without the root's drop (the only step that looks ahead), cleaning the frames as the
  // steering controller commits them gives exactly what cleaning them at once does.
  const Walked w = walked();
  const Motion input = sliding(w.clip.motion, 0.3, 0.05);
  FootCleanupSettings settings;
  settings.max_root_drop_m = 0.0;
  const Motion whole = cleaned(w, input, settings);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> piece(1, 15);
  auto cleanup = FootCleanup::create(w.clip.skeleton, w.feet, input.fps, settings);
  ASSERT_TRUE(cleanup);
  Motion pieces = input.slice(0, 0);
  for (int first = 0; first < input.frame_count;) {
    const int count = std::min(piece(rng), input.frame_count - first);
    const Motion more = input.slice(first, count);
    pieces.local_rotations.insert(pieces.local_rotations.end(), more.local_rotations.begin(), more.local_rotations.end());
    pieces.local_translations_m.insert(pieces.local_translations_m.end(), more.local_translations_m.begin(),
                                       more.local_translations_m.end());
    pieces.frame_count += count;
    ASSERT_TRUE(cleanup->clean(pieces, first, std::span(w.contacts).subspan(first, count)));
    first += count;
  }
  ASSERT_EQ(pieces.frame_count, whole.frame_count);
  for (size_t i = 0; i < whole.local_rotations.size(); ++i) {
    ASSERT_EQ(pieces.local_rotations[i].coeffs(), whole.local_rotations[i].coeffs()) << i;
  }
  EXPECT_EQ(pieces.local_translations_m, whole.local_translations_m);
  EXPECT_EQ(cleanup->frames_cleaned(), input.frame_count);
}

TEST(FootCleanup, MotionWithoutContactsIsLeftAsItIs) {
  Walked w = walked();
  std::fill(w.contacts.begin(), w.contacts.end(), ContactMask{0});
  const Motion input = sliding(w.clip.motion, 0.3);
  const Motion output = cleaned(w, input);
  EXPECT_EQ(output.local_rotations, input.local_rotations);
  EXPECT_EQ(output.local_translations_m, input.local_translations_m);
}

TEST(FootCleanup, APlantTheMotionLeavesFarBehindIsMadeAgainWhereTheFootIs) {
  // The left foot "planted" over the whole walk while the motion carries it 2 m away: a contact
  // the pieces' placement does not keep (a dance library's minute-long contacts drift so).
  Walked w = walked();
  const ContactMask left = contact_bit(FootSide::kLeft, FootPart::kAnkle) | contact_bit(FootSide::kLeft, FootPart::kToe);
  for (ContactMask& m : w.contacts) m = static_cast<ContactMask>((m & ~left) | left);
  const Motion input = sliding(w.clip.motion, 0.3);
  FootCleanupSettings held;
  held.max_hold_m = 100.0;  // never let go
  FootCleanupStats held_stats, stats;
  cleaned(w, input, held, &held_stats);
  const Motion output = cleaned(w, input, {}, &stats);
  // Held: the leg is stretched after a plant metres away and misses it by far.
  EXPECT_GT(held_stats.max_correction_m, 1.0);
  EXPECT_GT(held_stats.max_ankle_miss_m, 0.3);
  EXPECT_EQ(held_stats.replants, 0);
  // Let go beyond 25 cm: planted again, the leg never pulled much further, and missing its
  // target by far less (a walk's stride stretched by 25 cm is still out of reach now and then).
  const FootCleanupSettings defaults;
  EXPECT_GT(stats.replants, 3);
  EXPECT_LT(stats.max_correction_m, defaults.max_hold_m + 0.1);
  EXPECT_LT(stats.max_ankle_miss_m, 0.5 * held_stats.max_ankle_miss_m) << held_stats.max_ankle_miss_m;
  // And so is the toe, which is turned onto its plant: it moves with the new plants, never
  // held back where an old one was (what the measures of the targets above cannot see).
  const std::vector<Vec3> in = world_positions(w.clip.skeleton, input);
  const std::vector<Vec3> out = world_positions(w.clip.skeleton, output);
  const int toe = w.feet.left.toe;
  double furthest = 0.0;
  for (size_t f = 0; f < in.size() / w.clip.skeleton.joint_count(); ++f) {
    const size_t i = f * w.clip.skeleton.joint_count() + toe;
    furthest = std::max(furthest, horizontal(out[i], in[i]));
  }
  EXPECT_LT(furthest, defaults.max_hold_m + 0.05);  // held at the old plant: 0.45 m
  // The steps to the new plants are eased: no joint steps further than the input's do, by more
  // than the ease's share of a plant's 25 cm.
  const int joints = w.clip.skeleton.joint_count();
  const double input_step = max_joint_step(world_positions(w.clip.skeleton, input), joints);
  EXPECT_LT(max_joint_step(world_positions(w.clip.skeleton, output), joints), input_step + 0.06);
}

// The foot goes to a plant made again by a step: lifted midway (by at most step_height_m, and
// half the step's length) above where the same clean-up without the step has it, on the floor
// where the step starts and ends, so that it moves along the floor far less; with step_height_m 0
// it slides the whole way.
TEST(FootCleanup, APlantMadeAgainIsReachedByAStep) {
  Walked w = walked();
  const ContactMask left = contact_bit(FootSide::kLeft, FootPart::kAnkle) | contact_bit(FootSide::kLeft, FootPart::kToe);
  std::fill(w.contacts.begin(), w.contacts.end(), left);  // the right foot free: one foot steps
  const Motion input = sliding(w.clip.motion, 0.3);
  const int joints = w.clip.skeleton.joint_count(), ankle = w.feet.left.ankle;
  const FootCleanupSettings defaults;
  auto ankles = [&](double step_height, long long* replants) {
    FootCleanupSettings settings;
    settings.step_height_m = step_height;
    FootCleanupStats stats;
    const std::vector<Vec3> out = world_positions(w.clip.skeleton, cleaned(w, input, settings, &stats));
    *replants = stats.replants;
    // Its height from the root's (which the clean-up lowers less where a lifted foot is
    // reached more easily).
    std::vector<Vec3> track;
    for (size_t f = 0; f < out.size() / joints; ++f) {
      track.push_back(out[f * joints + ankle] - Vec3(0.0, out[f * joints].y(), 0.0));
    }
    return track;
  };
  long long slid_replants = 0, replants = 0;
  const std::vector<Vec3> slid = ankles(0.0, &slid_replants), stepped = ankles(defaults.step_height_m, &replants);
  ASSERT_GT(replants, 3);
  EXPECT_EQ(replants, slid_replants);  // the same plants, reached another way
  // The ankle's travel on the floor over the frames where the step does not lift it (by 2 cm or
  // more), against its travel without steps; the highest lift; frames lifted by 1 cm or more.
  double on_floor = 0.0, all = 0.0, highest = 0.0;
  int lifted = 0;
  for (size_t f = 1; f < stepped.size(); ++f) {
    const double rise = stepped[f].y() - slid[f].y();
    if (rise < 0.02) on_floor += horizontal(stepped[f], stepped[f - 1]);
    all += horizontal(slid[f], slid[f - 1]);
    if (rise > 0.01) ++lifted;
    highest = std::max(highest, rise);
  }
  // Each step of about 25 cm is mostly in the air.
  EXPECT_LT(on_floor, all - 0.5 * defaults.max_hold_m * static_cast<double>(replants)) << on_floor << " of " << all;
  EXPECT_GT(highest, 0.8 * defaults.step_height_m);
  // Up to 4 cm more where the leg without the lift cannot reach its plant (this walk's stride
  // and 25 cm: stretched straight, its ankle pulled down along the leg).
  EXPECT_LT(highest, defaults.step_height_m + 0.05);
  // Lifted only while stepping: at most an ease's frames a step.
  const int ease = static_cast<int>(std::lround(defaults.ease_s * input.fps));
  EXPECT_LE(lifted, ease * replants);
  EXPECT_GT(lifted, replants);
}

// The lift belongs to the steps to plants made again: where no plant is made again the frames
// are those of the clean-up without steps, whatever the contacts' switches.
TEST(FootCleanup, NoPlantMadeAgainNoLift) {
  const Walked w = walked();
  const Motion input = sliding(w.clip.motion, 0.3, 0.05);
  FootCleanupSettings held, held_flat;
  held.max_hold_m = held_flat.max_hold_m = 100.0;
  held_flat.step_height_m = 0.0;
  FootCleanupStats stats;
  const Motion a = cleaned(w, input, held, &stats);
  const Motion b = cleaned(w, input, held_flat);
  EXPECT_EQ(stats.replants, 0);
  EXPECT_EQ(stats.stepping_leg_frames, 0);
  EXPECT_EQ(a.local_rotations, b.local_rotations);
  EXPECT_EQ(a.local_translations_m, b.local_translations_m);
}

// A figure standing with both feet planted while the pieces' placement drifts (0.3 m/s): both
// plants are left 25 cm behind together, and the feet step in turn. A step cut short by its
// contact's switches (a frame without contact, the heel alone) eases its lift out: the ankle's
// height above the clean-up without steps never jumps.
TEST(FootCleanup, FeetStepInTurnAndAStepCutShortLandsSmoothly) {
  Walked w = walked();
  Motion standing = w.clip.motion;
  for (int f = 0; f < standing.frame_count; ++f) {
    std::copy(w.clip.motion.rotations(0).begin(), w.clip.motion.rotations(0).end(), standing.rotations(f).begin());
    std::copy(w.clip.motion.translations(0).begin(), w.clip.motion.translations(0).end(), standing.translations(f).begin());
  }
  const Motion input = sliding(standing, 0.3);
  const ContactMask both = contact_bit(FootSide::kLeft, FootPart::kAnkle) | contact_bit(FootSide::kLeft, FootPart::kToe) |
                           contact_bit(FootSide::kRight, FootPart::kAnkle) | contact_bit(FootSide::kRight, FootPart::kToe);
  const int joints = w.clip.skeleton.joint_count();
  FootCleanupSettings flat;
  flat.step_height_m = 0.0;
  for (bool cut : {false, true}) {
    std::fill(w.contacts.begin(), w.contacts.end(), both);
    if (cut) {
      for (size_t f = 30; f < w.contacts.size(); f += 23) w.contacts[f] = 0;  // a frame free
      for (size_t f = 40; f < w.contacts.size(); f += 31) {                    // the heels alone
        w.contacts[f] = contact_bit(FootSide::kLeft, FootPart::kAnkle) | contact_bit(FootSide::kRight, FootPart::kAnkle);
      }
    }
    FootCleanupStats stats;
    const std::vector<Vec3> stepped = world_positions(w.clip.skeleton, cleaned(w, input, {}, &stats));
    const std::vector<Vec3> slid = world_positions(w.clip.skeleton, cleaned(w, input, flat));
    ASSERT_GT(stats.replants, 4) << cut;
    EXPECT_GT(stats.stepping_leg_frames, 2 * stats.replants) << cut;
    if (!cut) {  // (a plant left twice as far while the other foot steps is let go all the same)
      EXPECT_LE(20 * stats.both_stepping_frames, stats.stepping_leg_frames) << stats.both_stepping_frames;
    }
    for (int ankle : {w.feet.left.ankle, w.feet.right.ankle}) {
      double jump = 0.0, highest = 0.0;
      auto rise = [&](size_t g) {
        return (stepped[g * joints + ankle].y() - stepped[g * joints].y()) -
               (slid[g * joints + ankle].y() - slid[g * joints].y());
      };
      for (size_t f = 1; f < stepped.size() / joints; ++f) {
        jump = std::max(jump, std::abs(rise(f) - rise(f - 1)));
        highest = std::max(highest, rise(f));
      }
      // A 5 cm step rises at most 1.8 cm a frame at 30 fps, the legs' reach moving it a little
      // more (cut short without easing: 5 cm at once).
      EXPECT_LT(jump, 0.03) << cut << " " << ankle;
      EXPECT_GT(highest, 0.04) << cut << " " << ankle;
    }
  }
}

TEST(FootCleanup, BadSettingsLegsAndCallsAreErrors) {
  const Walked w = walked();
  for (auto change : {+[](FootCleanupSettings& s) { s.ease_s = -1.0; },
                      +[](FootCleanupSettings& s) { s.max_extension = 1.0; },
                      +[](FootCleanupSettings& s) { s.max_root_drop_m = std::nan(""); },
                      +[](FootCleanupSettings& s) { s.root_speed_mps = 0.0; },
                      +[](FootCleanupSettings& s) { s.max_hold_m = 0.0; },
                      +[](FootCleanupSettings& s) { s.step_height_m = -0.01; }}) {
    FootCleanupSettings settings;
    change(settings);
    EXPECT_FALSE(settings.validate());
    EXPECT_FALSE(FootCleanup::create(w.clip.skeleton, w.feet, 30.0, settings));
  }
  // An "ankle" right below the root has no knee and hip above it.
  FootJoints no_knee = w.feet;
  no_knee.left.ankle = 1;
  auto bad = FootCleanup::create(w.clip.skeleton, no_knee, 30.0);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("knee"), std::string::npos) << bad.error().message;

  auto cleanup = FootCleanup::create(w.clip.skeleton, w.feet, 30.0);
  ASSERT_TRUE(cleanup);
  Motion motion = w.clip.motion;
  EXPECT_FALSE(cleanup->clean(motion, -1, w.contacts));                       // no such frame
  EXPECT_FALSE(cleanup->clean(motion, 0, std::span(w.contacts).subspan(1)));  // one mask short
  EXPECT_TRUE(cleanup->clean(motion, 0, w.contacts));
}

}  // namespace
}  // namespace mg
