// motiongraph convert IN -o OUT [-o OUT...]: AMC or BVH in, BVH or positions JSON out (metres,
// the JSON with the feet's contacts); the clip is read once for all outputs.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/motion_output.h"
#include "cli/load_options.h"
#include "cli/unit_report.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/export/positions_json.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/motion/resample.h"

namespace mg::cli {

namespace {

struct ConvertOptions {
  std::string input;
  std::vector<std::string> outputs;
  LoadOptions load;
  double fps = 0.0;
  double output_units_per_metre = 1.0;
  std::string feet;  // LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE
};

// The clip's foot contacts for its JSON outputs; none, with a warning, when its feet are not
// found by name. Joints the user named must exist.
Result<std::optional<std::vector<ContactMask>>> clip_contacts(const ConvertOptions& options, const Clip& clip,
                                                              FootJoints& feet) {
  FootJointNames names;
  if (!options.feet.empty()) {
    auto parsed = parse_foot_joint_names(options.feet);
    if (!parsed) return Error{"", 0, "--feet: " + parsed.error().message};
    names = *parsed;
  }
  auto found = find_foot_joints(clip.skeleton, names);
  if (!found) {
    if (!names.empty()) return Error{options.input, 0, found.error().message};
    spdlog::warn("{}: no foot contacts in the JSON: {} (name the feet with --feet)", options.input,
                 found.error().message);
    return std::optional<std::vector<ContactMask>>();
  }
  feet = *found;
  auto contacts = detect_foot_contacts(clip.skeleton, clip.motion, feet, FootContactSettings{});
  if (!contacts) return Error{options.input, 0, contacts.error().message};
  std::vector<ContactMask> masks(static_cast<size_t>(clip.motion.frame_count));
  for (int f = 0; f < clip.motion.frame_count; ++f) masks[f] = contact_mask(*contacts, f);
  return std::optional<std::vector<ContactMask>>(std::move(masks));
}

int run_convert(const ConvertOptions& options) {
  for (const std::string& output : options.outputs) {
    if (auto s = check_motion_output(output); !s) return fail(s.error());
  }
  BvhWriteSettings write;
  write.units_per_metre = options.output_units_per_metre;
  if (auto s = write.validate(); !s) return fail(s.error());
  ClipLoader loader(options.load.settings());
  auto loaded = loader.load(options.input);
  if (!loaded) return fail(loaded.error());
  Clip& clip = loaded->clip;
  if (clip.detected_unit) report_unit(options.input, *clip.detected_unit);
  if (clip.dropped_leading_frames > 0) {
    spdlog::info("{}: dropped {} leading rest/T-pose frame(s) (--keep-rest-frames keeps them)", options.input,
                 clip.dropped_leading_frames);
  }
  if (options.fps > 0.0) {
    auto resampled = resample(clip.motion, options.fps);
    if (!resampled) return fail(resampled.error());
    clip.motion = std::move(*resampled);
  }
  FootJoints feet;
  std::optional<std::vector<ContactMask>> masks;
  const bool any_json = std::any_of(options.outputs.begin(), options.outputs.end(), [](const std::string& path) {
    return std::filesystem::path(path).extension() == ".json";
  });
  if (any_json || !options.feet.empty()) {
    auto contacts = clip_contacts(options, clip, feet);
    if (!contacts) return fail(contacts.error());
    masks = std::move(*contacts);
  }
  const PositionsJsonContacts json_contacts{feet, masks ? std::span<const ContactMask>(*masks) : std::span<const ContactMask>()};
  for (const std::string& output : options.outputs) {
    if (auto s = write_motion(output, clip.skeleton, clip.motion, options.output_units_per_metre,
                              masks ? &json_contacts : nullptr);
        !s) {
      return fail(s.error());
    }
  }
  return 0;
}

}  // namespace

Command add_convert_command(CLI::App& app) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* sub = app.add_subcommand(
      "convert", "Convert an AMC or BVH clip to BVH (metres) or to JSON world positions "
                 "({\"fps\", \"joints\": [{\"name\", \"parent\"}], \"positions\": [frame][joint][x,y,z], "
                 "\"contacts\": {\"joints\": [the foot joints], \"planted\": [frame][foot joint] 0 or 1}}).");
  sub->add_option("IN", options->input, "Input clip (.amc or .bvh)")->required()->check(CLI::ExistingFile);
  sub->add_option("-o,--output", options->outputs, "Output file, .bvh or .json; repeat for several (read once)")
      ->required();
  sub->add_option("--fps", options->fps, "Resample to this frame rate (slerp rotations, lerp translations)")
      ->check(CLI::Range(0.01, 10000.0));
  sub->add_option("--output-scale", options->output_units_per_metre,
                  "BVH length units per metre in the output (100 for centimetres)")
      ->capture_default_str();
  sub->add_option("--feet", options->feet,
                  "Foot joints as LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE, any left empty to find it by name "
                  "(default: found by name)");
  options->load.add_to(*sub);
  return {sub, [options] { return run_convert(*options); }};
}

}  // namespace mg::cli
