// What looks wrong with a clip as read: a figure that floats above the floor or sinks below it
// (y = 0), and feet that never rest on it. A converter that offsets or rescales the root's
// translation gives both (the BVH 07_12 in data/bvh: hips at -0.33..0 m, the lowest joint
// 0.57-0.90 m below the floor, feet sliding 3 m/s), and the distance metric, which compares
// heights as read, then joins such a clip to nothing. Loading reports them (one warning per
// clip) so that the user checks the file before wondering about the graph.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct ClipDoubtSettings {
  double off_floor_m = 0.25;       // the median of each frame's lowest joint height below -this, or
                                   // its 2 % quantile above this: off the floor
  double min_contactless_s = 1.0;  // a clip at least this long in which no foot joint is planted

  Status validate() const;
};

// Phrases such as "its lowest joint is 0.57-0.90 m below the floor (y = 0)"; empty when nothing
// looks wrong. world_positions_m: frames x joint_count, frame-major (world_positions()); contacts:
// one mask per frame (contact_mask()), empty when the feet are unknown (not judged then).
std::vector<std::string> clip_doubts(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                                     std::span<const ContactMask> contacts, const ClipDoubtSettings& settings = {});

// The same for a clip on its own: forward kinematics, and the contacts of the feet found by their
// usual names (skeleton/foot_joints.h; not judged when none are found).
std::vector<std::string> clip_doubts(const Skeleton& skeleton, const Motion& motion,
                                     const ClipDoubtSettings& settings = {});

// "phrase, and phrase; its root translation may be wrong": what `info` prints for a clip with
// doubts.
std::string clip_doubts_text(const std::vector<std::string>& doubts);

// "NAME: " + clip_doubts_text + " (...)": the one line loading logs for a clip with doubts.
std::string clip_doubt_line(const std::string& name, const std::vector<std::string>& doubts);

}  // namespace mg
