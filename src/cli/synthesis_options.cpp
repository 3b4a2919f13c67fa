#include "cli/synthesis_options.h"

#include <fmt/format.h>

#include <cmath>

#include "motiongraph/core/json_text.h"
#include "motiongraph/evaluation/foot_slide_report.h"
#include "motiongraph/io/file.h"

namespace mg::cli {

Result<std::unique_ptr<LoadedGraph>> load_for_synthesis(const SynthesisOptions& options) {
  if (auto s = check_motion_output(options.output); !s) return s.error();
  return LoadedGraph::load(options.graph, options.skeleton);
}

std::optional<FootCleanup> cleanup_for(const SynthesisOptions& options, const SynthesisContext& context) {
  if (options.no_cleanup) return std::nullopt;
  auto cleanup = context.foot_cleanup(FootCleanupSettings{});
  if (!cleanup) {
    fmt::print(stderr, "warning: {}: {}\n", options.graph, cleanup.error().message);
    return std::nullopt;
  }
  return std::move(*cleanup);
}

nlohmann::json cleanup_report(const SynthesisOptions& options, const SynthesisContext& context,
                              const std::optional<FootCleanup>& cleanup) {
  if (!cleanup) {
    std::string reason = "--no-cleanup";
    if (!options.no_cleanup) {
      auto made = context.foot_cleanup(FootCleanupSettings{});  // what cleanup_for warned of
      reason = made ? std::string("not made") : made.error().message;
    }
    return {{"enabled", false}, {"reason", reason}};
  }
  const FootCleanupStats& s = cleanup->stats();
  return {{"enabled", true},
          {"frames", s.frames},
          {"planted_leg_frames", s.planted_leg_frames},
          {"root_lowered_frames", s.root_lowered_frames},
          {"max_root_drop_m", s.max_root_drop_m},
          {"max_correction_m", s.max_correction_m},
          {"max_ankle_miss_m", s.max_ankle_miss_m},
          {"replants", s.replants}};
}

Status write_synthesis_outputs(const SynthesisOptions& options, const LoadedGraph& loaded, const Motion& motion,
                               const Walk& walk, nlohmann::json report, std::vector<ContactMask> contacts) {
  const SynthesisContext& context = loaded.context();
  if (contacts.empty() && walk.start_node >= 0) contacts = context.walk_contacts(walk);
  const bool with_contacts = !context.frame_contacts.empty() && static_cast<int>(contacts.size()) >= motion.frame_count;
  contacts.resize(static_cast<size_t>(motion.frame_count));
  const PositionsJsonContacts json_contacts{context.feet, contacts};
  if (auto s = write_motion(options.output, context.assembler.skeleton(), motion, 1.0,
                            with_contacts ? &json_contacts : nullptr);
      !s) {
    return s;
  }
  if (!options.report.empty()) {
    report["foot_slide"] = foot_slide_report(loaded.context(), walk, motion);
    if (auto s = write_file_atomic(options.report, json_text(report, 2) + "\n"); !s) return s;
  }
  return Ok{};
}

}  // namespace mg::cli
