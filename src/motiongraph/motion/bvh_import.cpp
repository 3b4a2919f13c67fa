#include "motiongraph/motion/bvh_import.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "motiongraph/motion/length_unit.h"
#include "motiongraph/motion/rest_frame.h"
#include "motiongraph/motion/trajectory_joint.h"
#include "motiongraph/motion/up_axis.h"

namespace mg {

Status BvhImportSettings::validate() const {
  if (metres_per_unit && !is_length_unit_scale(*metres_per_unit)) {
    return Error{"", 0,
                 fmt::format("the BVH scale must lie between {:g} and {:g} metres per unit, not {:g}",
                             kMinLengthUnitScale, kMaxLengthUnitScale, *metres_per_unit)};
  }
  if (!(fps_override >= 0.0) || !std::isfinite(fps_override)) {
    return Error{"", 0, "the BVH frame rate override must be positive (or 0 for the file's)"};
  }
  return Ok{};
}

double fps_from_frame_time(double frame_time_s) {
  // Frame times are written rounded (".0083333"); a rate within 1e-4 of a whole number is
  // that number (120.0005 -> 120), while 29.97 stays 29.97; and one within 1e-6 of a number of
  // hundredths is that number (0.133333333, 7.5 fps written to 9 digits, read back as
  // 7.50000001875 fps; ".0333667" as 29.96999 fps), while 23.976 stays 23.976.
  const double fps = 1.0 / frame_time_s;
  const double whole = std::round(fps);
  if (whole > 0.0 && std::abs(fps - whole) <= 1e-4 * fps) return whole;
  const double hundredths = std::round(fps * 100.0) / 100.0;
  return hundredths > 0.0 && std::abs(fps - hundredths) <= 1e-6 * fps ? hundredths : fps;
}

Result<Clip> clip_from_bvh(const BvhDocument& bvh, const BvhImportSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  const int file_joints = static_cast<int>(bvh.joints.size());
  // New order: joints with channels or children first (file order), End Sites after.
  std::vector<int> new_index(file_joints, -1);
  std::vector<int> order;
  for (int pass = 0; pass < 2; ++pass) {
    for (int j = 0; j < file_joints; ++j) {
      if (bvh.joints[j].end_site == (pass == 1)) {
        new_index[j] = static_cast<int>(order.size());
        order.push_back(j);
      }
    }
  }
  std::vector<JointDef> joints;
  for (int j : order) {
    const BvhJoint& in = bvh.joints[j];
    JointDef out;
    out.name = in.name;
    out.parent = in.parent < 0 ? -1 : new_index[in.parent];
    out.rest_offset_m = in.offset;  // file units until the unit is known
    out.end_site = in.end_site;
    std::vector<Axis> rotation_axes;
    for (BvhChannel c : in.channels) {
      if (is_rotation(c)) {
        rotation_axes.push_back(channel_axis(c));
      } else {
        out.animated_translation = true;
      }
    }
    if (rotation_axes.size() == 3) out.euler_order = {rotation_axes[0], rotation_axes[1], rotation_axes[2]};
    joints.push_back(out);
  }
  Clip clip;
  clip.skeleton = Skeleton(std::move(joints));
  const double fps = settings.fps_override > 0.0 ? settings.fps_override : fps_from_frame_time(bvh.frame_time_s);
  if (settings.fps_override <= 0.0 && bvh.frame_count > 1 && !(fps >= kMinBvhFps && fps <= kMaxBvhFps)) {
    const double as_milliseconds = fps_from_frame_time(bvh.frame_time_s / 1000.0);
    const std::string hint = as_milliseconds >= kMinBvhFps && as_milliseconds <= kMaxBvhFps && fps < kMinBvhFps
                                 ? fmt::format(" (read as milliseconds it would be {:g} fps)", as_milliseconds)
                                 : "";
    return Error{bvh.file_name, bvh.frame_time_line,
                 fmt::format("Frame Time {:g} s is {:.3g} frames a second, no capture's rate{}: give the rate with "
                             "--input-fps",
                             bvh.frame_time_s, fps, hint)};
  }
  Motion& motion = clip.motion;
  motion = Motion(clip.skeleton, bvh.frame_count, fps);
  constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;
  for (int f = 0; f < bvh.frame_count; ++f) {
    const double* values = bvh.values.data() + static_cast<size_t>(f) * bvh.channel_count;
    auto rotations = motion.rotations(f);
    auto translations = motion.translations(f);
    for (int j = 0; j < file_joints; ++j) {
      const BvhJoint& in = bvh.joints[j];
      const int target = new_index[j];
      Quat rotation = Quat::Identity();
      Vec3 translation = in.offset;
      for (size_t c = 0; c < in.channels.size(); ++c) {
        const double v = values[in.first_channel + c];
        const BvhChannel channel = in.channels[c];
        if (is_rotation(channel)) {
          rotation = rotation * axis_rotation(channel_axis(channel), v * kRadiansPerDegree);
        } else {
          translation[static_cast<int>(channel_axis(channel))] = v;
        }
      }
      rotations[target] = rotation.normalized();
      const int slot = clip.skeleton.translation_slot(target);
      if (slot >= 0) translations[slot] = translation;
    }
  }
  // Static root, unit, metres: in file units, tolerances relative to the figure's size.
  double size = figure_size(clip.skeleton, clip.motion);
  if (settings.fold_static_root) {
    if (auto joint = find_trajectory_joint(clip.skeleton, clip.motion, kStaticRootFraction * size)) {
      clip = fold_static_root(clip, *joint);
      size = figure_size(clip.skeleton, clip.motion);
    }
  }
  // After the fold: a static root's rotation is zero in every frame, which hides the test.
  if (settings.drop_rest_frames) {
    if (const int added = leading_added_frames(motion); added > 0) {
      motion = motion.slice(added, motion.frame_count - added);
      clip.dropped_leading_frames = added;
    }
  }
  double metres_per_unit = 1.0;
  if (settings.metres_per_unit) {
    metres_per_unit = *settings.metres_per_unit;
  } else {
    clip.detected_unit = choose_length_unit(size);
    metres_per_unit = clip.detected_unit->unit.metres_per_unit;
  }
  scale_lengths(clip, metres_per_unit);
  stand_up(clip, settings.up_axis);
  return clip;
}

}  // namespace mg
