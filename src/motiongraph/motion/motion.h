// A clip's animation on one skeleton: per frame, the local rotation of every joint (unit
// quaternions, frames x joints, frame-major) and the local translation in metres of every
// joint with animated translation (frames x skeleton.translated_joints()). Sampled at fps.
#pragma once

#include <memory_resource>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/in_place_choice.h"
#include "motiongraph/motion/length_unit_choice.h"
#include "motiongraph/motion/up_axis_choice.h"
#include "motiongraph/skeleton/skeleton.h"

namespace mg {

// The most joint poses (frames x joints) a clip, or a scene file's animations together, may hold
// as read or resampled: 1.6 GB of rotations.
inline constexpr double kMaxJointPoses = 5e7;

struct Motion {
  double fps = 30.0;
  int frame_count = 0;
  int joint_count = 0;
  int translated_count = 0;
  std::pmr::vector<Quat> local_rotations;    // frame_count x joint_count
  std::pmr::vector<Vec3> local_translations_m;  // frame_count x translated_count

  Motion() = default;
  Motion(const Skeleton& skeleton, int frames, double frames_per_second);
  // Room for `frames` frames in `memory`, their values left for the caller to write (a graph
  // file's motion, decoded into one block: core/huge_pages.h). The motion keeps `memory` when
  // moved; a copy is in ordinary memory.
  Motion(const Skeleton& skeleton, int frames, double frames_per_second, std::pmr::memory_resource* memory);

  std::span<Quat> rotations(int frame) {
    return {local_rotations.data() + static_cast<size_t>(frame) * joint_count, static_cast<size_t>(joint_count)};
  }
  std::span<const Quat> rotations(int frame) const {
    return {local_rotations.data() + static_cast<size_t>(frame) * joint_count, static_cast<size_t>(joint_count)};
  }
  std::span<Vec3> translations(int frame) {
    return {local_translations_m.data() + static_cast<size_t>(frame) * translated_count,
            static_cast<size_t>(translated_count)};
  }
  std::span<const Vec3> translations(int frame) const {
    return {local_translations_m.data() + static_cast<size_t>(frame) * translated_count,
            static_cast<size_t>(translated_count)};
  }
  double duration_s() const { return frame_count > 0 ? (frame_count - 1) / fps : 0.0; }

  // Frames [first, first + count) as a new motion.
  Motion slice(int first, int count) const;
};

// Whether `motion` can play on `skeleton`: its joint and translation counts and its arrays match
// the skeleton, and its frame rate is a positive number; an error saying which does not.
Status check_fits(const Skeleton& skeleton, const Motion& motion);

// A skeleton with one motion on it: what a file gives.
struct Clip {
  std::string name;
  Skeleton skeleton;
  Motion motion;
  int dropped_leading_frames = 0;  // frames removed at load (an added rest or T-pose)
  // Frames removed at load before a capture glitch at the start, and after one at the end
  // (glitched_ends.h), after any rest frames.
  int glitched_leading_frames = 0;
  int glitched_trailing_frames = 0;
  std::optional<LengthUnitChoice> detected_unit;  // the unit chosen for a BVH read without one
  std::optional<UpAxisChoice> detected_up_axis;   // the up axis chosen for a file read without one
  std::optional<InPlaceChoice> in_place;          // whether its travel was taken out, and recovered (in_place.h)
  // Joints that hung off the joints folded away above joint 0 (trajectory_joint.h: an engine's
  // IK targets beside the hips, under a root that travels without turning), dropped at import.
  std::vector<std::string> dropped_at_fold;
};

}  // namespace mg
