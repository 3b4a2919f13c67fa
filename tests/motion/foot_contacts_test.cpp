#include "motiongraph/motion/foot_contacts.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "test_data.h"

namespace mg {
namespace {

const char* const kWalks[] = {"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_11.amc", "cmu/16/16_13.amc"};
// Straight runs (16_43's sharp turn has two contacts of one foot in a row).
const char* const kRuns[] = {"cmu/16/16_35.amc", "cmu/16/16_37.amc", "cmu/16/16_39.amc"};
const char* const kAllClips[] = {"cmu/16/16_01.amc", "cmu/16/16_05.amc", "cmu/16/16_11.amc", "cmu/16/16_13.amc",
                                 "cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_17.amc", "cmu/16/16_19.amc",
                                 "cmu/16/16_33.amc", "cmu/16/16_35.amc", "cmu/16/16_37.amc", "cmu/16/16_39.amc",
                                 "cmu/16/16_41.amc", "cmu/16/16_43.amc", "cmu/16/16_57.amc"};

FootContacts contacts_of(const Clip& clip, const FootContactSettings& settings = {}) {
  auto feet = find_foot_joints(clip.skeleton);
  EXPECT_TRUE(feet) << feet.error().to_string();
  auto contacts = detect_foot_contacts(clip.skeleton, clip.motion, *feet, settings);
  EXPECT_TRUE(contacts) << contacts.error().to_string();
  return *contacts;
}

Clip at_fps(Clip clip, double fps) {
  clip.motion = *resample(clip.motion, fps);
  return clip;
}

// Each file at its capture's 120 fps and resampled to 30 fps, with "FILE at FPS fps".
void for_each_clip_and_rate(std::span<const char* const> files,
                            const std::function<void(const Clip&, double fps, const std::string& what)>& visit) {
  for (const char* file : files) {
    const Clip clip = test::load_data_clip(file);
    for (double fps : {120.0, 30.0}) visit(at_fps(clip, fps), fps, fmt::format("{} at {} fps", file, fps));
  }
}

// Per foot (ankle or toe planted): 1 per frame.
std::vector<uint8_t> foot_track(const FootContacts& contacts, FootSide side) {
  std::vector<uint8_t> planted(static_cast<size_t>(contacts.frame_count));
  for (int f = 0; f < contacts.frame_count; ++f) planted[f] = contacts.foot_planted(side, f) ? 1 : 0;
  return planted;
}

// The contacts that start within the clip (one planted at frame 0 started before it).
std::vector<ContactInterval> started_contacts(const std::vector<uint8_t>& planted) {
  auto intervals = contact_intervals(planted);
  if (!intervals.empty() && intervals.front().first_frame == 0) intervals.erase(intervals.begin());
  return intervals;
}

// Gait cycles of one foot: from the start of a contact to the start of the next; the share
// of each cycle the foot is planted.
std::vector<double> duty_per_cycle(const std::vector<uint8_t>& planted) {
  const auto intervals = started_contacts(planted);
  std::vector<double> duties;
  for (size_t i = 0; i + 1 < intervals.size(); ++i) {
    const int cycle = intervals[i + 1].first_frame - intervals[i].first_frame;
    duties.push_back(static_cast<double>(intervals[i].frame_count) / cycle);
  }
  return duties;
}

// Contacts start left, right, left, ... (or right, left, ...): the starts of both feet's
// contacts, in order, never twice the same side in a row.
void expect_alternating(const FootContacts& contacts, const std::string& what) {
  std::vector<std::pair<int, FootSide>> starts;
  for (FootSide side : {FootSide::kLeft, FootSide::kRight}) {
    for (const ContactInterval& interval : started_contacts(foot_track(contacts, side))) {
      starts.emplace_back(interval.first_frame, side);
    }
  }
  std::sort(starts.begin(), starts.end());
  EXPECT_GE(starts.size(), 3u) << what;
  for (size_t i = 1; i < starts.size(); ++i) {
    EXPECT_NE(starts[i].second, starts[i - 1].second) << what << ": two contacts of one foot at frames "
                                                       << starts[i - 1].first << " and " << starts[i].first;
  }
}

TEST(FootContacts, WalksPlantEachFootAboutSixtyPercentOfAGaitCycleLeftAndRightInTurn) {
  for_each_clip_and_rate(kWalks, [](const Clip& clip, double, const std::string& what) {
    const FootContacts contacts = contacts_of(clip);
    ASSERT_EQ(contacts.tracks.size(), 4u) << what;  // both ankles and toes
    expect_alternating(contacts, what);
    for (FootSide side : {FootSide::kLeft, FootSide::kRight}) {
      const auto duties = duty_per_cycle(foot_track(contacts, side));
      EXPECT_GE(duties.size(), 2u) << what;
      for (double duty : duties) {
        EXPECT_GE(duty, 0.5) << what;
        EXPECT_LE(duty, 0.72) << what;
      }
    }
  });
}

TEST(FootContacts, RunsPlantEachFootLessThanWalks) {
  for_each_clip_and_rate(kRuns, [](const Clip& clip, double fps, const std::string& what) {
    const FootContacts contacts = contacts_of(clip);
    expect_alternating(contacts, what);
    int cycles = 0;
    for (FootSide side : {FootSide::kLeft, FootSide::kRight}) {
      for (double duty : duty_per_cycle(foot_track(contacts, side))) {
        EXPECT_GT(duty, 0.1) << what;
        EXPECT_LT(duty, 0.45) << what;
        ++cycles;
      }
      // Every contact is a run's short stance: under 0.3 s.
      for (const ContactInterval& interval : contact_intervals(foot_track(contacts, side))) {
        EXPECT_LT(interval.frame_count / fps, 0.3) << what;
      }
    }
    EXPECT_GE(cycles, 1) << what;
  });
}

// A synthetic clip as world positions: 4 joints (left ankle, left toe, right ankle, right toe)
// standing on a floor at floor_y, the left ankle lifted as `left_ankle_y` says.
struct Synthetic {
  std::vector<Vec3> positions;
  FootJoints feet{{0, 1}, {2, 3}};
};

Synthetic synthetic(int frames, double floor_y, const std::function<double(int)>& left_ankle_y) {
  Synthetic s;
  for (int f = 0; f < frames; ++f) {
    s.positions.push_back(Vec3(0.1, left_ankle_y(f), 0.0));
    s.positions.push_back(Vec3(0.1, floor_y - 0.05, 0.15));
    s.positions.push_back(Vec3(-0.1, floor_y, 0.0));
    s.positions.push_back(Vec3(-0.1, floor_y - 0.05, 0.15));
  }
  return s;
}

TEST(FootContacts, AJointHeldStillOnTheFloorGivesOneContactOfItsLength) {
  // At 30 fps the left ankle comes down at 0.96 m/s, stays still for `still` frames from
  // frame 10, then rises at 1.2 m/s. Central-difference speeds: 0.48 m/s on the first still
  // frame (below the entering 0.5), 0.6 on the last (below the leaving 0.8), 0.96 and 1.2
  // outside; the frame before is 3.2 cm up (above the entering 3 cm). So the contact is
  // exactly the still frames.
  const double fps = 30.0, floor_y = 0.5;
  const int first = 10;
  FootContactSettings settings;  // 3 / 5 cm, 0.5 / 0.8 m/s, 0.1 s = 3 frames at 30 fps
  ASSERT_EQ(settings.min_frames(fps), 3);
  for (int still = 1; still <= 8; ++still) {
    const int end = first + still;
    const Synthetic s = synthetic(end + 15, floor_y, [&](int f) {
      if (f < first) return floor_y + 0.96 * (first - f) / fps;
      if (f < end) return floor_y;
      return floor_y + 1.2 * (f - end + 1) / fps;
    });
    auto contacts = detect_foot_contacts(s.positions, 4, fps, s.feet, settings);
    ASSERT_TRUE(contacts) << contacts.error().to_string();
    ASSERT_EQ(contacts->tracks.size(), 4u);
    const FootContactTrack& left_ankle = contacts->tracks[0];
    EXPECT_EQ(left_ankle.joint, 0);
    EXPECT_NEAR(left_ankle.floor_height_m, floor_y, 1e-12);
    const auto intervals = contact_intervals(left_ankle.planted);
    if (still < settings.min_frames(fps)) {
      EXPECT_TRUE(intervals.empty()) << still;
      continue;
    }
    ASSERT_EQ(intervals.size(), 1u) << still;
    EXPECT_EQ(intervals[0].first_frame, first) << still;
    EXPECT_EQ(intervals[0].frame_count, still) << still;
    // The other joints stand still on the floor throughout.
    for (size_t t = 1; t < 4; ++t) {
      const auto whole = contact_intervals(contacts->tracks[t].planted);
      ASSERT_EQ(whole.size(), 1u);
      EXPECT_EQ(whole[0].frame_count, end + 15);
    }
  }
}

TEST(FootContacts, HysteresisKeepsAContactThatWouldNotStartThere) {
  // A joint planted, then hovering 4 cm up (above the entering 3 cm, within the leaving 5 cm):
  // it stays planted. The same hover after being in the air does not plant it.
  const double fps = 30.0;
  const Synthetic s = synthetic(60, 0.0, [&](int f) {
    if (f < 10) return 0.0;       // planted
    if (f < 20) return 0.04;      // hover: still planted
    if (f < 30) return 0.3;       // in the air
    return 0.04;                  // hover: not planted
  });
  FootContactSettings settings;
  settings.enter_speed_mps = settings.leave_speed_mps = std::numeric_limits<double>::infinity();
  settings.local_window_s = 0.0;  // from the clip's floor: the last hover would rest on its own
  auto contacts = detect_foot_contacts(s.positions, 4, fps, s.feet, settings);
  ASSERT_TRUE(contacts);
  const auto intervals = contact_intervals(contacts->tracks[0].planted);
  ASSERT_EQ(intervals.size(), 1u);
  EXPECT_EQ(intervals[0].first_frame, 0);
  EXPECT_EQ(intervals[0].frame_count, 20);
}

// Heights above the track's floor and speeds over +-half frames, recomputed here.
struct JointSignal {
  std::vector<double> height_m, speed_mps;
};

JointSignal signal_of(const std::vector<Vec3>& positions, int joints, int joint, double fps, double floor, int half) {
  JointSignal s;
  const int frames = static_cast<int>(positions.size()) / joints;
  for (int f = 0; f < frames; ++f) {
    s.height_m.push_back(positions[f * joints + joint].y() - floor);
    const int a = std::max(f - half, 0), b = std::min(f + half, frames - 1);
    s.speed_mps.push_back((positions[b * joints + joint] - positions[a * joints + joint]).norm() * fps / (b - a));
  }
  return s;
}

// The same for a track, heights above what its contacts were measured from: its resting height
// with the local floor, its floor otherwise.
JointSignal track_signal(const std::vector<Vec3>& positions, int joints, const FootContactTrack& track, double fps,
                         int half) {
  if (track.rest_height_m.empty()) return signal_of(positions, joints, track.joint, fps, track.floor_height_m, half);
  JointSignal s = signal_of(positions, joints, track.joint, fps, 0.0, half);
  for (size_t f = 0; f < s.height_m.size(); ++f) s.height_m[f] -= track.rest_height_m[f];
  return s;
}

TEST(FootContacts, TheSpeedSpanIsOneFifteenthOfASecondAtAnyFrameRate) {
  const FootContactSettings settings;
  EXPECT_EQ(settings.speed_half_span_frames(120.0), 4);
  EXPECT_EQ(settings.speed_half_span_frames(30.0), 1);
  EXPECT_EQ(settings.speed_half_span_frames(10.0), 1);  // at least a frame
  EXPECT_EQ(settings.max_gap_frames(120.0), 12);
  EXPECT_EQ(settings.max_gap_frames(30.0), 3);
  EXPECT_EQ(settings.min_frames(120.0), 12);
}

TEST(FootContacts, WithoutGapsFilledEveryContactStartsWithinTheEnterThresholdsAndStaysWithinTheLeaveOnes) {
  // The state machine's invariants, on every bundled clip of subject 16 at two frame rates,
  // heights measured from the clip's floor (the local floor's rules are tested below).
  FootContactSettings settings;
  settings.max_gap_s = 0.0;
  settings.local_window_s = 0.0;
  for_each_clip_and_rate(kAllClips, [&](const Clip& clip, double fps, const std::string& file) {
    const FootContacts contacts = contacts_of(clip, settings);
    const auto positions = world_positions(clip.skeleton, clip.motion);
    const int joints = clip.skeleton.joint_count();
    const int half = settings.speed_half_span_frames(fps);
    int contacts_seen = 0;
    for (const FootContactTrack& track : contacts.tracks) {
      ASSERT_TRUE(track.rest_height_m.empty());
      const JointSignal s = track_signal(positions, joints, track, fps, half);
      for (const ContactInterval& interval : contact_intervals(track.planted)) {
        ++contacts_seen;
        EXPECT_GE(interval.frame_count, settings.min_frames(fps)) << file;
        const int start = interval.first_frame, end = start + interval.frame_count;
        EXPECT_LE(s.height_m[start], settings.enter_height_m) << file << " " << start;
        EXPECT_LE(s.speed_mps[start], settings.enter_speed_mps) << file << " " << start;
        for (int f = start; f < end; ++f) {
          EXPECT_LE(s.height_m[f], settings.leave_height_m) << file << " " << f;
          EXPECT_LE(s.speed_mps[f], settings.leave_speed_mps) << file << " " << f;
        }
        if (end < contacts.frame_count) {  // it ended because a leave threshold was passed
          EXPECT_TRUE(s.height_m[end] > settings.leave_height_m || s.speed_mps[end] > settings.leave_speed_mps)
              << file << " " << end;
        }
      }
      // A frame within the enter thresholds is planted, or in a contact too short to keep
      // (then the frames from it that stay within the leave thresholds are < min_frames).
      for (int f = 0; f < contacts.frame_count; ++f) {
        if (track.planted[f] || s.height_m[f] > settings.enter_height_m || s.speed_mps[f] > settings.enter_speed_mps) {
          continue;
        }
        int end = f;
        while (end < contacts.frame_count && s.height_m[end] <= settings.leave_height_m &&
               s.speed_mps[end] <= settings.leave_speed_mps) {
          ++end;
        }
        EXPECT_LT(end - f, settings.min_frames(fps)) << file << " frame " << f;
      }
    }
    EXPECT_GT(contacts_seen, 0) << file;
  });
}

TEST(FootContacts, FillingGapsOnlyAddsAndLeavesNoShortGapOrShortContact) {
  const FootContactSettings filled;
  FootContactSettings unfilled = filled;
  unfilled.max_gap_s = 0.0;
  for_each_clip_and_rate(kAllClips, [&](const Clip& clip, double fps, const std::string& file) {
    const FootContacts with = contacts_of(clip, filled);
    const FootContacts without = contacts_of(clip, unfilled);
    for (size_t t = 0; t < with.tracks.size(); ++t) {
      for (int f = 0; f < with.frame_count; ++f) {
        EXPECT_GE(with.tracks[t].planted[f], without.tracks[t].planted[f]) << file << " frame " << f;
      }
      const auto intervals = contact_intervals(with.tracks[t].planted);
      for (size_t i = 0; i < intervals.size(); ++i) {
        EXPECT_GE(intervals[i].frame_count, filled.min_frames(fps)) << file;
        if (i == 0) continue;
        const int gap = intervals[i].first_frame - intervals[i - 1].first_frame - intervals[i - 1].frame_count;
        EXPECT_GT(gap, filled.max_gap_frames(fps)) << file;
      }
    }
  });
}

TEST(FootContacts, TheSameLabelsForAClipTurnedAndMovedOnTheFloorOrRaised) {
  const Clip clip = test::load_data_clip("cmu/16/16_17.amc");
  const FootContacts original = contacts_of(clip);
  for (const auto& [yaw, shift] : {std::pair{0.7, Vec3(3.0, 0.0, -2.0)}, std::pair{-2.4, Vec3(-10.0, 0.25, 40.0)}}) {
    Clip moved = clip;
    const Quat turn = axis_rotation(Axis::kY, yaw);
    for (int f = 0; f < moved.motion.frame_count; ++f) {
      moved.motion.rotations(f)[0] = turn * moved.motion.rotations(f)[0];
      moved.motion.translations(f)[0] = turn * moved.motion.translations(f)[0] + shift;
    }
    const FootContacts labels = contacts_of(moved);
    ASSERT_EQ(labels.tracks.size(), original.tracks.size());
    for (size_t t = 0; t < labels.tracks.size(); ++t) {
      EXPECT_EQ(labels.tracks[t].planted, original.tracks[t].planted) << yaw << " track " << t;
      EXPECT_NEAR(labels.tracks[t].floor_height_m, original.tracks[t].floor_height_m + shift.y(), 1e-9);
    }
  }
}

TEST(FootContacts, TheSameLabelsForAClipReadFromCentimetres) {
  // The clip written as BVH in centimetres and read back (its unit found from its size): the
  // thresholds are in metres, so the labels are those of the AMC.
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  BvhWriteSettings centimetres;
  centimetres.units_per_metre = 100.0;
  auto doc = parse_bvh(write_bvh(clip.skeleton, clip.motion, centimetres), "16_15_cm.bvh");
  ASSERT_TRUE(doc) << doc.error().to_string();
  auto read = clip_from_bvh(*doc, {});
  ASSERT_TRUE(read) << read.error().to_string();
  ASSERT_TRUE(read->detected_unit);
  EXPECT_EQ(read->detected_unit->unit.name, "cm");
  const FootContacts original = contacts_of(clip);
  const FootContacts labels = contacts_of(*read);
  ASSERT_EQ(labels.tracks.size(), original.tracks.size());
  for (size_t t = 0; t < labels.tracks.size(); ++t) {
    EXPECT_EQ(read->skeleton.joint(labels.tracks[t].joint).name, clip.skeleton.joint(original.tracks[t].joint).name);
    EXPECT_EQ(labels.tracks[t].planted, original.tracks[t].planted) << t;
  }
}

TEST(FootContacts, LabelsAt30FpsAgreeWithThoseAt120FpsOverMostOfTheTime) {
  // Each frame of the 30 fps clip against the 120 fps frame at the same time. They differ
  // where a contact's edge falls between frames and where the end of a clip cuts a contact
  // near its shortest length: at most 8 % of the time of any joint, 2 % on average.
  double agreement_sum = 0.0;
  int tracks = 0;
  for (const char* file : kAllClips) {
    const Clip clip = test::load_data_clip(file);
    ASSERT_EQ(clip.motion.fps, 120.0);
    const FootContacts fine = contacts_of(clip);
    const FootContacts coarse = contacts_of(at_fps(clip, 30.0));
    ASSERT_EQ(fine.tracks.size(), coarse.tracks.size());
    for (size_t t = 0; t < fine.tracks.size(); ++t) {
      int same = 0;
      for (int f = 0; f < coarse.frame_count; ++f) {
        same += coarse.tracks[t].planted[f] == fine.tracks[t].planted[std::min(4 * f, fine.frame_count - 1)] ? 1 : 0;
      }
      const double agreement = static_cast<double>(same) / coarse.frame_count;
      EXPECT_GE(agreement, 0.92) << file << " track " << t;
      agreement_sum += agreement;
      ++tracks;
    }
  }
  EXPECT_GE(agreement_sum / tracks, 0.98);
}

TEST(FootContacts, ShortGapsBetweenContactsAreFilled) {
  // Planted, lifted 30 cm for `gap` frames, planted again (height alone decides here): one
  // contact when the gap is at most 0.1 s (3 frames at 30 fps), two otherwise.
  FootContactSettings settings;
  settings.enter_speed_mps = settings.leave_speed_mps = std::numeric_limits<double>::infinity();
  for (int gap = 1; gap <= 6; ++gap) {
    const Synthetic s = synthetic(40 + gap, 0.0, [&](int f) { return f >= 20 && f < 20 + gap ? 0.3 : 0.0; });
    auto contacts = detect_foot_contacts(s.positions, 4, 30.0, s.feet, settings);
    ASSERT_TRUE(contacts);
    const auto intervals = contact_intervals(contacts->tracks[0].planted);
    ASSERT_EQ(intervals.size(), gap <= 3 ? 1u : 2u) << gap;
    EXPECT_EQ(intervals[0].first_frame, 0);
    if (gap > 3) {
      EXPECT_EQ(intervals[1].first_frame, 20 + gap);
    }
  }
}

// Two feet on ground of two heights at 30 fps: 4 joints (left ankle, left toe, right ankle, right
// toe), the toe 5 cm below its ankle and 15 cm ahead. The left foot's ground at y = 0, the
// right's at y = right_ground. Walking, in turns of `phase` frames one foot stands still on its
// ground while the other swings, 1.5 m/s forward along an arc 10 cm high; not walking, both
// stand still throughout.
std::vector<Vec3> two_grounds(int phases, int phase, double right_ground, bool walking) {
  std::vector<Vec3> positions;
  double x[2] = {0.0, 0.0};
  for (int p = 0; p < phases; ++p) {
    const int swinging = p % 2 == 0 ? 1 : 0;  // right first
    for (int i = 0; i < phase; ++i) {
      double y[2] = {0.0, right_ground};
      if (walking) {
        x[swinging] += 1.5 / 30.0;
        y[swinging] += 0.1 * std::sin(M_PI * (i + 1) / phase);
      }
      for (int side = 0; side < 2; ++side) {
        const double z = side == 0 ? 0.1 : -0.1;
        positions.push_back(Vec3(x[side], y[side], z));
        positions.push_back(Vec3(x[side] + 0.15, y[side] - 0.05, z));
      }
    }
  }
  return positions;
}

// The share of frames each track is planted.
std::vector<double> planted_shares(const FootContacts& contacts) {
  std::vector<double> shares;
  for (const FootContactTrack& track : contacts.tracks) {
    shares.push_back(static_cast<double>(std::count(track.planted.begin(), track.planted.end(), 1)) /
                     contacts.frame_count);
  }
  return shares;
}

TEST(FootContacts, TheLocalFloorPlantsStepsOnHigherGroundButNotALegHeldUp) {
  const FootJoints feet{{0, 1}, {2, 3}};
  FootContactSettings clip_floor;
  clip_floor.local_window_s = 0.0;
  const FootContactSettings local;
  for (double step : {0.1, 0.3}) {
    // Walking with the right foot on a ledge `step` higher: each foot carries the body while the
    // other swings, so both plant on their own ground, about half the time; on the clip's floor
    // the right foot never does.
    const auto walk = two_grounds(8, 20, step, true);
    auto on_ledge = detect_foot_contacts(walk, 4, 30.0, feet, local);
    ASSERT_TRUE(on_ledge) << on_ledge.error().to_string();
    for (double share : planted_shares(*on_ledge)) {
      EXPECT_GT(share, 0.4) << step;
      EXPECT_LT(share, 0.65) << step;
    }
    const auto flat_rule = planted_shares(*detect_foot_contacts(walk, 4, 30.0, feet, clip_floor));
    EXPECT_GT(flat_rule[0], 0.4) << step;
    EXPECT_EQ(flat_rule[2], 0.0) << step;
    EXPECT_EQ(flat_rule[3], 0.0) << step;
    // Each contact on the ledge is the foot's standing phase.
    for (const FootContactTrack& track : on_ledge->tracks) {
      for (int f = 0; f < on_ledge->frame_count; ++f) {
        const bool stands = (f / 20) % 2 == (track.side == FootSide::kLeft ? 0 : 1);
        if (track.planted[f]) {
          EXPECT_TRUE(stands || f % 20 < 2 || f % 20 >= 18) << step << " frame " << f;
        }
      }
    }
    // The right foot held still `step` up while the left stands: a leg held up, not planted.
    const auto held = two_grounds(8, 20, step, false);
    auto held_up = detect_foot_contacts(held, 4, 30.0, feet, local);
    ASSERT_TRUE(held_up);
    const auto shares = planted_shares(*held_up);
    EXPECT_EQ(shares[0], 1.0) << step;
    EXPECT_EQ(shares[2], 0.0) << step;
    EXPECT_EQ(shares[3], 0.0) << step;
  }
  // A foot held above max_step_m while the other swings is not carrying the body: not planted.
  FootContactSettings low_steps;
  low_steps.max_step_m = 0.2;
  const auto shares = planted_shares(*detect_foot_contacts(two_grounds(8, 20, 0.3, true), 4, 30.0, feet, low_steps));
  EXPECT_GT(shares[0], 0.4);
  EXPECT_EQ(shares[2], 0.0);
  // Both feet held still 0.6 m up for 2 s after a walk (hanging from a bar): above max_step_m,
  // never planted there, though each rests on the lowest "ground" around.
  std::vector<Vec3> hang = two_grounds(4, 20, 0.0, true);
  const std::vector<Vec3> last(hang.end() - 4, hang.end());
  for (int f = 0; f < 60; ++f) {
    for (const Vec3& joint : last) hang.push_back(joint + Vec3(0.0, 0.6, 0.0));
  }
  auto hanging = detect_foot_contacts(hang, 4, 30.0, feet, local);
  ASSERT_TRUE(hanging);
  for (const FootContactTrack& track : hanging->tracks) {
    EXPECT_GT(std::count(track.planted.begin(), track.planted.begin() + 80, 1), 20);
    EXPECT_EQ(std::count(track.planted.begin() + 80, track.planted.end(), 1), 0);
  }
  // A rig with a toe on the left foot only: the left foot held still 30 cm up while the right
  // foot stands is a leg held up (the toe's own heights are no ground); standing on both feet or
  // walking, the toe is planted as its ankle is.
  const FootJoints one_toe{{0, 1}, {2, -1}};
  for (int mode = 0; mode < 3; ++mode) {  // held up, standing, walking
    const bool walking = mode == 2;
    const auto four = two_grounds(8, 20, 0.0, walking);
    std::vector<Vec3> three;
    for (size_t f = 0; f < four.size() / 4; ++f) {
      const Vec3 lift = mode == 0 ? Vec3(0.0, 0.3, 0.0) : Vec3::Zero();
      three.push_back(four[4 * f] + lift);
      three.push_back(four[4 * f + 1] + lift);
      three.push_back(four[4 * f + 2]);
    }
    auto toe_rig = detect_foot_contacts(three, 3, 30.0, one_toe, local);
    ASSERT_TRUE(toe_rig);
    ASSERT_EQ(toe_rig->tracks.size(), 3u);
    const auto toe_rig_shares = planted_shares(*toe_rig);
    if (mode == 1) {
      for (double share : toe_rig_shares) EXPECT_EQ(share, 1.0);
    } else if (walking) {
      for (double share : toe_rig_shares) EXPECT_GT(share, 0.4);
    } else {
      EXPECT_EQ(toe_rig_shares[0], 0.0);
      EXPECT_EQ(toe_rig_shares[1], 0.0);
      EXPECT_EQ(toe_rig_shares[2], 1.0);
    }
  }
}

TEST(FootContacts, WithTheLocalFloorEveryContactStartsWithinTheEnterThresholdsOfItsRestingHeight) {
  // The state machine's invariants measured from each joint's resting height, on every bundled
  // clip of subject 16 at two frame rates (a and b only keep or give frames of stances).
  FootContactSettings settings;
  settings.max_gap_s = 0.0;
  for_each_clip_and_rate(kAllClips, [&](const Clip& clip, double fps, const std::string& file) {
    const FootContacts contacts = contacts_of(clip, settings);
    const auto positions = world_positions(clip.skeleton, clip.motion);
    const int joints = clip.skeleton.joint_count();
    const int half = settings.speed_half_span_frames(fps);
    int starts = 0;
    for (const FootContactTrack& track : contacts.tracks) {
      ASSERT_EQ(track.rest_height_m.size(), static_cast<size_t>(contacts.frame_count));
      const JointSignal s = track_signal(positions, joints, track, fps, half);
      for (const ContactInterval& interval : contact_intervals(track.planted)) {
        const int start = interval.first_frame, end = start + interval.frame_count;
        EXPECT_GE(interval.frame_count, settings.min_frames(fps)) << file;
        for (int f = start; f < end; ++f) {
          EXPECT_LE(s.height_m[f], settings.leave_height_m) << file << " " << f;
          EXPECT_LE(s.speed_mps[f], settings.leave_speed_mps) << file << " " << f;
        }
        // A contact starts where a stance does (within the enter thresholds), or where a. let a
        // stance go on (the frame before it within the leave thresholds).
        const bool entered = s.height_m[start] <= settings.enter_height_m && s.speed_mps[start] <= settings.enter_speed_mps;
        starts += entered ? 1 : 0;
        if (!entered) {
          ASSERT_GT(start, 0) << file;
          EXPECT_LE(s.height_m[start - 1], settings.leave_height_m) << file << " " << start;
          EXPECT_LE(s.speed_mps[start - 1], settings.leave_speed_mps) << file << " " << start;
        }
      }
    }
    EXPECT_GT(starts, 0) << file;
  });
}

TEST(FootContacts, TheLocalFloorKeepsTheLabelsOfAClipOnLevelGround) {
  // Subject 16 runs and walks on a level floor: measured from each joint's resting height or
  // from the clip's floor, the labels agree over most of the time. Each resting height is the
  // 5 % quantile of the joint's heights over +-0.4 s (sorted here).
  FootContactSettings clip_floor;
  clip_floor.local_window_s = 0.0;
  const FootContactSettings local;
  double agreement_sum = 0.0;
  int tracks = 0;
  for_each_clip_and_rate(kAllClips, [&](const Clip& clip, double fps, const std::string& what) {
    const FootContacts with = contacts_of(clip, local);
    const FootContacts without = contacts_of(clip, clip_floor);
    const auto positions = world_positions(clip.skeleton, clip.motion);
    const int joints = clip.skeleton.joint_count();
    const int half = local.local_window_frames(fps);
    ASSERT_EQ(half, static_cast<int>(std::lround(0.4 * fps)));
    for (size_t t = 0; t < with.tracks.size(); ++t) {
      const FootContactTrack& track = with.tracks[t];
      EXPECT_TRUE(without.tracks[t].rest_height_m.empty());
      ASSERT_EQ(track.rest_height_m.size(), static_cast<size_t>(with.frame_count));
      for (int f = 0; f < with.frame_count; f += 7) {
        std::vector<double> window;
        for (int g = std::max(0, f - half); g <= std::min(with.frame_count - 1, f + half); ++g) {
          window.push_back(positions[g * joints + track.joint].y());
        }
        std::sort(window.begin(), window.end());
        const double at = 0.05 * (window.size() - 1);
        const size_t below = static_cast<size_t>(at);
        const double expected = below + 1 < window.size()
                                    ? window[below] + (at - below) * (window[below + 1] - window[below])
                                    : window[below];
        EXPECT_NEAR(track.rest_height_m[f], expected, 1e-12) << what << " frame " << f;
      }
      int same = 0;
      for (int f = 0; f < with.frame_count; ++f) same += track.planted[f] == without.tracks[t].planted[f] ? 1 : 0;
      const double agreement = static_cast<double>(same) / with.frame_count;
      EXPECT_GE(agreement, 0.85) << what << " track " << t;
      agreement_sum += agreement;
      ++tracks;
    }
  });
  EXPECT_GE(agreement_sum / tracks, 0.96);
}

TEST(FootContacts, EachSettingsRuleGivesItsError) {
  struct Case {
    const char* rule;
    std::function<void(FootContactSettings&)> change;
    const char* message_part;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Case cases[] = {
      {"floor quantile", [](FootContactSettings& s) { s.floor_quantile = 0.6; }, "floor quantile"},
      {"floor quantile NaN", [&](FootContactSettings& s) { s.floor_quantile = nan; }, "floor quantile"},
      {"enter height", [](FootContactSettings& s) { s.enter_height_m = -0.01; }, "contact height"},
      {"leave height", [](FootContactSettings& s) { s.leave_height_m = 0.02; }, "height a contact ends above"},
      {"enter speed", [](FootContactSettings& s) { s.enter_speed_mps = 0.0; }, "contact speed"},
      {"leave speed", [](FootContactSettings& s) { s.leave_speed_mps = 0.4; }, "speed a contact ends above"},
      {"speed span", [](FootContactSettings& s) { s.speed_span_s = 0.0; }, "span speeds are measured over"},
      {"max gap", [](FootContactSettings& s) { s.max_gap_s = -0.1; }, "longest gap filled"},
      {"min duration", [](FootContactSettings& s) { s.min_duration_s = -1.0; }, "shortest contact"},
      {"local window", [](FootContactSettings& s) { s.local_window_s = -0.4; }, "local floor's window"},
      {"local window inf", [](FootContactSettings& s) { s.local_window_s = HUGE_VAL; }, "local floor's window"},
      {"local quantile", [](FootContactSettings& s) { s.local_quantile = 0.7; }, "local floor's quantile"},
      {"rest tolerance", [](FootContactSettings& s) { s.rest_tolerance_m = -0.01; }, "resting height's tolerance"},
      {"max step", [&](FootContactSettings& s) { s.max_step_m = nan; }, "highest step"},
  };
  const Synthetic s = synthetic(20, 0.0, [](int) { return 0.0; });
  for (const Case& c : cases) {
    FootContactSettings settings;
    c.change(settings);
    const Status valid = settings.validate();
    ASSERT_FALSE(valid) << c.rule;
    EXPECT_NE(valid.error().message.find(c.message_part), std::string::npos) << c.rule << ": " << valid.error().message;
    EXPECT_FALSE(detect_foot_contacts(s.positions, 4, 30.0, s.feet, settings)) << c.rule;
  }
  EXPECT_TRUE(FootContactSettings{}.validate());
  EXPECT_FALSE(detect_foot_contacts(s.positions, 4, 0.0, s.feet, {}));
}

TEST(FootContacts, ContactColumnsAreEachFootsAnkleThenToeLeftFirstAndSkipAMissingToe) {
  // Each column's bit is the one contact_mask sets for that joint's track.
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const FootJoints feet = *find_foot_joints(clip.skeleton);
  const FootContacts contacts = contacts_of(clip);
  const std::vector<ContactColumn> columns = contact_columns(feet);
  ASSERT_EQ(columns.size(), contacts.tracks.size());
  for (size_t c = 0; c < columns.size(); ++c) {
    const FootContactTrack& track = contacts.tracks[c];
    EXPECT_EQ(columns[c].joint, track.joint) << c;
    for (int f = 0; f < contacts.frame_count; ++f) {
      ASSERT_EQ((contact_mask(contacts, f) & columns[c].bit) != 0, track.planted[f] != 0) << c << " at " << f;
    }
  }
  const std::vector<int> order = {feet.left.ankle, feet.left.toe, feet.right.ankle, feet.right.toe};
  for (size_t c = 0; c < columns.size(); ++c) EXPECT_EQ(columns[c].joint, order[c]);

  FootJoints no_left_toe = feet;
  no_left_toe.left.toe = -1;
  const std::vector<ContactColumn> three = contact_columns(no_left_toe);
  ASSERT_EQ(three.size(), 3u);
  EXPECT_EQ(three[0].joint, feet.left.ankle);
  EXPECT_EQ(three[1].joint, feet.right.ankle);
  EXPECT_EQ(three[1].bit, contact_bit(FootSide::kRight, FootPart::kAnkle));
  EXPECT_EQ(three[2].bit, contact_bit(FootSide::kRight, FootPart::kToe));
}

// Gaps filled in played contacts: against a plain reference per bit, on random masks; a gap of
// at most max_gap frames between two planted frames is planted, a longer one and the unplanted
// runs at either end are not, and filling twice changes nothing.
TEST(FootContacts, FillContactGapsPlantsTheShortGapsBetweenContactsOfEachBit) {
  std::mt19937 rng(53);
  for (int trial = 0; trial < 200; ++trial) {
    const int max_gap = trial % 4;
    std::vector<ContactMask> masks(static_cast<size_t>(1 + trial % 40));
    for (ContactMask& m : masks) m = static_cast<ContactMask>(std::uniform_int_distribution<int>(0, 15)(rng));
    std::vector<ContactMask> filled = masks;
    fill_contact_gaps(filled, max_gap);
    for (int bit = 0; bit < 4; ++bit) {
      const auto mask = static_cast<ContactMask>(1 << bit);
      for (size_t f = 0; f < masks.size(); ++f) {
        bool before = false, after = false;  // planted within max_gap + 1 frames either side, gap between
        size_t gap_start = f, gap_end = f;
        while (gap_start > 0 && (masks[gap_start - 1] & mask) == 0) --gap_start;
        while (gap_end + 1 < masks.size() && (masks[gap_end + 1] & mask) == 0) ++gap_end;
        before = gap_start > 0;
        after = gap_end + 1 < masks.size();
        const bool want = (masks[f] & mask) != 0 ||
                          (before && after && static_cast<int>(gap_end - gap_start + 1) <= max_gap);
        ASSERT_EQ((filled[f] & mask) != 0, want) << "trial " << trial << " frame " << f << " bit " << bit;
      }
    }
    std::vector<ContactMask> twice = filled;
    fill_contact_gaps(twice, max_gap);
    EXPECT_EQ(twice, filled);
  }
}

}  // namespace
}  // namespace mg
