// What `info`, `convert` and Python's load_clip say of a file's clip: its feet's contacts (the
// feet named, or found by their names) and what looks wrong with it (motion/clip_doubts.h),
// judged at the motion's own rate, its clock against the rate the file was read at.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/motion/clip_doubts.h"

namespace mg {

struct ClipAsRead {
  std::optional<ClipContacts> contacts;  // nullopt when the feet are not found (feet_missing says why)
  std::string feet_missing;
  ClipDoubts doubts;
};

// `motion` on `skeleton` as read (or resampled since); `positions` its world positions when the
// caller has them (empty: worked out here); `read_fps` the rate its file was read at; `format`
// the loader's ("gltf" and "fbx" keys are timed in seconds). An error when a foot joint named
// is not in the skeleton.
Result<ClipAsRead> judge_clip_as_read(const Skeleton& skeleton, const Motion& motion, std::span<const Vec3> positions,
                                      double read_fps, const std::string& format, const FootJointNames& feet);

}  // namespace mg
