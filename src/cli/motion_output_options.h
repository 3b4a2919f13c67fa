// How the commands that write motion (convert, walk, path, steer) write it, beyond the format the
// output's extension names: --output-scale (BVH units), --no-figure (glTF and FBX without their
// stick figure), --root-motion and --root-motion-smoothing (a root-motion joint above the root,
// motion/root_motion.h).
#pragma once

#include <CLI/CLI.hpp>

#include "motiongraph/export/motion_file.h"

namespace mg::cli {

struct MotionOutputOptions {
  double units_per_metre = 1.0;
  bool no_figure = false;
  bool root_motion = false;
  RootMotionSettings root_settings;

  void add_to(CLI::App& app) {
    app.add_option("--output-scale", units_per_metre,
                   "BVH length units per metre in the output, 1e-6 to 1e6 (100 for centimetres); glTF and JSON are "
                   "always in metres, FBX in centimetres (its UnitScaleFactor 1)")
        ->capture_default_str();
    app.add_flag("--no-figure", no_figure,
                 "glTF and FBX: write the skeleton and its animation only, without the grey stick figure skinned to it "
                 "(for retargeting onto a character of one's own)");
    CLI::Option* root_motion_flag = app.add_flag("--root-motion", root_motion,
                 "Add a root-motion joint above the root, as game engines take root motion: on the clip's floor "
                 "under the hips, turned the way the character faces (its +z axis), carrying the travel; the hips "
                 "hang below it and no joint moves (a rig's fixed root right above the hips becomes that joint)");
    app.add_option("--root-motion-smoothing", root_settings.smoothing_s,
                   "Seconds over which the root-motion joint's floor position and heading are smoothed (each frame "
                   "takes the least-squares line through the frames within half of it either side), so that it "
                   "does not sway with each step (0: the hips' own)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 60.0))
        ->needs(root_motion_flag);  // without it there is no joint to smooth: said, not ignored
  }

  // What write_motion takes, a root-motion joint (when asked for) facing `forward_axis`.
  MotionFileSettings settings(const Vec3& forward_axis = Vec3::UnitZ()) const {
    MotionFileSettings s;
    s.units_per_metre = units_per_metre;
    s.figure = !no_figure;
    if (root_motion) s.root_motion = RootMotionOutput{root_settings, forward_axis};
    return s;
  }
};

}  // namespace mg::cli
