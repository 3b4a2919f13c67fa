// Command-line options shared by the commands that read clips.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/in_place.h"
#include "motiongraph/motion/up_axis.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg::cli {

// Help of the options `build` shares with the commands that read clips (build has its own
// settings struct, but not its own meanings).
inline constexpr const char* kScaleHelp =
    "Metres per BVH length unit, 1e-6 to 1e6 (BVH carries no unit; default: m, cm, mm, inch or CMU's 1/0.45 inch per "
    "file, whichever makes the figure human-sized); for FBX, metres per unit of its numbers, instead of its own unit "
    "(which is kept unless it makes the figure no human size)";
inline constexpr const char* kInputFpsHelp =
    "Capture rate of ASF/AMC and BVH input, overriding the files' (AMC default 120, CMU's rate; a BVH Frame Time "
    "giving under 1 or over 10000 fps is refused without it); for glTF and FBX, "
    "whose keys are timed in seconds, the rate their animations are sampled at (default: their keys')";
inline constexpr const char* kKeepRestFramesHelp =
    "Keep the frames read but not played by default: leading rest or T-pose frames that a BVH converter added, "
    "first or last frames that a capture glitch cuts off (a joint jumping 0.2 m or more at 20 m/s or faster between "
    "two calm frames, or out and back within a frame), "
    "and clips whole where glitches within them would cut them into parts";

struct LoadOptions {
  std::string asf;
  std::optional<double> scale;
  std::string up_axis;
  std::string travel = "auto";
  std::string feet;  // LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE
  double input_fps = 0.0;
  bool keep_rest_frames = false;

  void add_to(CLI::App& app) {
    app.add_option("--asf", asf, "ASF skeleton of the AMC files")->check(CLI::ExistingFile);
    app.add_option("--scale", scale, kScaleHelp);
    app.add_option("--up-axis", up_axis,
                   "Up axis of a clip, y or z (default: whichever the figure stands along; a z-up file is turned "
                   "y up)")
        ->check(CLI::IsMember({"y", "z"}));
    app.add_option("--travel", travel,
                   "Where a clip's travel over the floor comes from: root (as read), feet (recovered from the planted "
                   "feet), or auto: the feet for a clip animated in place, its planted feet sliding")
        ->check(CLI::IsMember({"auto", "root", "feet"}))
        ->capture_default_str();
    app.add_option("--feet", feet,
                   "Foot joints as LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE, any left empty to find it by name "
                   "(default: found by name)")
        ->check(CLI::Validator(
            [](const std::string& text) {
              auto parsed = parse_foot_joint_names(text);
              return parsed ? std::string() : parsed.error().message;
            },
            "", "FEET"));
    app.add_option("--input-fps", input_fps, kInputFpsHelp)->check(CLI::Range(0.01, 10000.0));
    app.add_flag("--keep-rest-frames", keep_rest_frames, kKeepRestFramesHelp);
  }

  ClipLoadSettings settings() const {
    ClipLoadSettings s;
    if (!asf.empty()) s.asf_path = asf;
    s.bvh_metres_per_unit = scale;
    if (!up_axis.empty()) s.up_axis = parse_up_axis(up_axis);
    s.travel = parse_travel_source(travel).value_or(TravelSource::kAuto);
    if (auto names = parse_foot_joint_names(feet); !feet.empty() && names) s.foot_names = *names;
    s.input_fps = input_fps;
    s.keep_rest_frames = keep_rest_frames;
    return s;
  }
};

}  // namespace mg::cli
