// motiongraph.load_library(): a library read as `build` reads it (database/database_loader.h),
// its clips as Motion objects at the database's rate and its summary as `info --json` gives it
// (pipeline/library_summary.h). The package's Library class (__init__.py) wraps the two.
#include <pybind11/stl.h>

#include "binding.h"
#include "motiongraph/database/database_loader.h"
#include "motiongraph/pipeline/build_settings.h"
#include "motiongraph/pipeline/library_summary.h"

namespace mg::python {

namespace {

// The keywords of build() that say how clips are read; the others are refused, as unknown.
constexpr const char* kLoadOptions[] = {"fps",       "asf",  "scale",    "up_axis",         "travel",     "input_fps",
                                        "keep_rest_frames", "cmu_index", "feet", "no_loops", "whole_clip_tags",
                                        "no_cmu_tags", "no_name_tags", "mirror"};

// (summary, clips): the summary a dict, the clips a list of Motion with their feet's contacts.
py::tuple load_library(const std::vector<std::string>& inputs, const py::dict& options) {
  BuildCall call;
  OptionTable table = build_option_table(call);
  OptionTable load_table;
  for (const char* name : kLoadOptions) load_table.emplace(name, std::move(table.at(name)));
  apply_options(options, load_table, "load_library");
  DatabaseSettings settings = take(build_settings_from(call.options)).database;
  std::stop_source stop;  // Ctrl-C (run_stoppable)
  settings.stop = stop.get_token();

  DatabaseLoadNotes notes;
  Result<MotionDatabase> loaded = Error{};
  run_stoppable(stop, [&] { loaded = load_database(inputs, settings, &notes); });
  MotionDatabase db = take(std::move(loaded));
  const LibrarySummary summary = summarize_library(db, notes, !settings.foot_names.empty());
  py::object summary_dict = to_python(library_summary_json(inputs, db, summary));
  for (const std::string& line : summary.warnings) {
    warn(line, 2);
  }

  py::list clips;
  for (DatabaseClip& clip : db.clips) {
    const Skeleton& skeleton = db.skeletons[static_cast<size_t>(clip.skeleton)];
    std::optional<PyMotion> motion;
    {
      py::gil_scoped_release release;
      motion.emplace(clip.name, skeleton, std::move(clip.motion));
    }
    auto feet = find_foot_joints(skeleton, db.foot_names);
    if (feet && !db.frame_contacts.empty()) {
      motion->feet = *feet;
      const auto first = db.frame_contacts.begin() + clip.first_frame;
      motion->contacts.assign(first, first + clip.frame_count);
    }
    clips.append(py::cast(std::move(*motion)));
  }
  return py::make_tuple(std::move(summary_dict), std::move(clips));
}

}  // namespace

void bind_library(py::module_& m) { m.def("_load_library", &load_library, py::arg("inputs"), py::arg("options")); }

}  // namespace mg::python
