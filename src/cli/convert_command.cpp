// motiongraph convert IN -o OUT [-o OUT...]: AMC or BVH in, BVH or positions JSON out (metres);
// the clip is read once for all outputs.
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/load_options.h"
#include "cli/unit_report.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/export/positions_json.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/resample.h"

namespace mg::cli {

namespace {

struct ConvertOptions {
  std::string input;
  std::vector<std::string> outputs;
  LoadOptions load;
  double fps = 0.0;
  double output_units_per_metre = 1.0;
};

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
  for (const std::string& output : options.outputs) {
    if (auto s = write_motion(output, clip.skeleton, clip.motion, options.output_units_per_metre); !s) {
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
                 "({\"fps\", \"joints\": [{\"name\", \"parent\"}], \"positions\": [frame][joint][x,y,z]}).");
  sub->add_option("IN", options->input, "Input clip (.amc or .bvh)")->required()->check(CLI::ExistingFile);
  sub->add_option("-o,--output", options->outputs, "Output file, .bvh or .json; repeat for several (read once)")
      ->required();
  sub->add_option("--fps", options->fps, "Resample to this frame rate (slerp rotations, lerp translations)")
      ->check(CLI::Range(0.01, 10000.0));
  sub->add_option("--output-scale", options->output_units_per_metre,
                  "BVH length units per metre in the output (100 for centimetres)")
      ->capture_default_str();
  options->load.add_to(*sub);
  return {sub, [options] { return run_convert(*options); }};
}

}  // namespace mg::cli
