// --root-motion and --root-motion-smoothing, for the commands that write motion (convert, walk,
// path, steer): a root-motion joint above the root (motion/root_motion.h).
#pragma once

#include <optional>

#include <CLI/CLI.hpp>

#include "motiongraph/export/motion_file.h"

namespace mg::cli {

struct RootMotionOptions {
  bool enabled = false;
  RootMotionSettings settings;

  void add_to(CLI::App& app) {
    app.add_flag("--root-motion", enabled,
                 "Add a root-motion joint above the root, as game engines take root motion: on the clip's floor "
                 "under the hips, turned the way the character faces (its +z axis), carrying the travel; the hips "
                 "hang below it and no joint moves (a rig's fixed root right above the hips becomes that joint)");
    app.add_option("--root-motion-smoothing", settings.smoothing_s,
                   "Seconds over which the root-motion joint's floor position and heading are smoothed (each frame "
                   "takes the least-squares line through the frames within half of it either side), so that it "
                   "does not sway with each step (0: the hips' own)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 60.0));
  }

  // What write_motion takes, with the skeleton facing `forward_axis`; nullopt when not asked for.
  std::optional<RootMotionOutput> output(const Vec3& forward_axis) const {
    if (!enabled) return std::nullopt;
    return RootMotionOutput{settings, forward_axis};
  }
};

}  // namespace mg::cli
