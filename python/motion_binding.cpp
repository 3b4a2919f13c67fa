// motiongraph.Motion: a clip read from a file or motion synthesized on a graph, its arrays
// numpy views of the C++ data (no copies), and load_clip().
#include <optional>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "binding.h"
#include "motiongraph/evaluation/synthesis_run.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/motion/in_place.h"
#include "motiongraph/motion/up_axis.h"

namespace mg::python {

PyMotion::PyMotion(std::string motion_name, Skeleton motion_skeleton, Motion played)
    : name(std::move(motion_name)), skeleton(std::move(motion_skeleton)), motion(std::move(played)) {
  positions = world_positions(skeleton, motion);
}

namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Quat) == 4 * sizeof(double),
              "Eigen's vectors and quaternions are stored as plain doubles");

// A frames x joints x width view of `data`, kept alive by `owner` (the Python Motion).
py::array_t<double> frames_view(const double* data, const PyMotion& m, py::ssize_t width, py::handle owner) {
  const py::ssize_t frames = m.motion.frame_count;
  const py::ssize_t joints = m.skeleton.joint_count();
  constexpr py::ssize_t d = sizeof(double);
  py::array_t<double> view({frames, joints, width}, {joints * width * d, width * d, d}, data, owner);
  // Read-only: the C++ motion behind it is what save() writes.
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

Status save_motion(const PyMotion& m, const std::string& path) {
  if (m.graph) return write_synthesized_motion(path, m.graph->context(), m.motion, m.walk, m.contacts);
  // A captured clip's JSON carries its feet's contacts, as the CLI's convert writes it.
  std::string why;
  auto contacts = clip_contacts(m.skeleton, m.motion, FootJointNames{}, why);
  if (!contacts) return contacts.error();
  if (!*contacts) return write_motion(path, m.skeleton, m.motion);
  const PositionsJsonContacts json_contacts{(*contacts)->feet, (*contacts)->masks};
  return write_motion(path, m.skeleton, m.motion, 1.0, &json_contacts);
}

PyMotion load_clip(const std::string& path, const std::optional<std::string>& asf, std::optional<double> fps,
                   std::optional<double> scale, const std::optional<std::string>& up_axis, double input_fps,
                   bool keep_rest_frames, const std::string& travel) {
  ClipLoadSettings settings;
  if (asf) settings.asf_path = *asf;
  settings.bvh_metres_per_unit = scale;
  if (up_axis) {
    settings.up_axis = parse_up_axis(*up_axis);
    if (!settings.up_axis) throw py::value_error("up_axis must be 'y' or 'z', not '" + *up_axis + "'");
  }
  settings.input_fps = input_fps;
  settings.keep_rest_frames = keep_rest_frames;
  const auto source = parse_travel_source(travel);
  if (!source) throw py::value_error("travel must be 'auto', 'root' or 'feet', not '" + travel + "'");
  settings.travel = *source;
  check(settings.validate());
  Result<LoadedClip> loaded = Error{};
  {
    py::gil_scoped_release release;
    loaded = ClipLoader(settings).load(path);
    if (loaded && fps) {
      auto resampled = resample(loaded->clip.motion, *fps);
      if (!resampled) {
        loaded = resampled.error();
      } else {
        loaded->clip.motion = std::move(*resampled);
      }
    }
  }
  LoadedClip got = take(std::move(loaded));
  return PyMotion(got.clip.name, std::move(got.clip.skeleton), std::move(got.clip.motion));
}

}  // namespace

void bind_motion(py::module_& m) {
  py::class_<PyMotion>(m, "Motion",
                       "Motion on a skeleton: a clip read from a file (load_clip) or motion synthesized on a graph "
                       "(Graph.walk, Graph.path, Controller.step). Arrays are read-only views, not copies.")
      .def_readonly("name", &PyMotion::name)
      .def_property_readonly("fps", [](const PyMotion& self) { return self.motion.fps; })
      .def_property_readonly("frame_count", [](const PyMotion& self) { return self.motion.frame_count; })
      .def("__len__", [](const PyMotion& self) { return self.motion.frame_count; })
      .def_property_readonly(
          "positions",
          [](py::object self) {
            const auto& motion = self.cast<const PyMotion&>();
            return frames_view(motion.positions.empty() ? nullptr : motion.positions.front().data(), motion, 3, self);
          },
          "World positions of every joint, metres, y up: float64 array frames x joints x 3.")
      .def_property_readonly(
          "rotations",
          [](py::object self) {
            const auto& motion = self.cast<const PyMotion&>();
            const auto& q = motion.motion.local_rotations;
            return frames_view(q.empty() ? nullptr : q.front().coeffs().data(), motion, 4, self);
          },
          "Local rotation of every joint relative to its parent, unit quaternions (x, y, z, w): float64 "
          "array frames x joints x 4.")
      .def_property_readonly("joint_names",
                             [](const PyMotion& self) {
                               std::vector<std::string> names;
                               for (const JointDef& joint : self.skeleton.joints()) names.push_back(joint.name);
                               return names;
                             })
      .def_property_readonly("parents",
                             [](const PyMotion& self) {
                               std::vector<int> parents;
                               for (const JointDef& joint : self.skeleton.joints()) parents.push_back(joint.parent);
                               return parents;
                             },
                             "Each joint's parent index (-1 for the root); parents come before children.")
      .def_property_readonly("report", [](const PyMotion& self) { return to_python(self.report); },
                             "The CLI's --report of the synthesis (a dict), None for a clip.")
      .def(
          "save",
          [](const PyMotion& self, const std::string& path) {
            Status saved = Ok{};
            {
              py::gil_scoped_release release;
              saved = save_motion(self, path);
            }
            check(saved);
          },
          py::arg("path"),
          "Writes the motion: .bvh (metres) or .json (world positions, with the feet's contacts), as the CLI "
          "does.")
      .def("__repr__", [](const PyMotion& self) {
        return fmt::format("<motiongraph.Motion '{}': {} frames at {:g} fps, {} joints>", self.name,
                           self.motion.frame_count, self.motion.fps, self.skeleton.joint_count());
      });
  m.def("load_clip", &load_clip, py::arg("path"), py::arg("asf") = py::none(), py::arg("fps") = py::none(),
        py::arg("scale") = py::none(), py::arg("up_axis") = py::none(), py::arg("input_fps") = 0.0,
        py::arg("keep_rest_frames") = false, py::arg("travel") = "auto",
        "Reads a clip (.amc with its .asf, or .bvh) as the CLI's convert does: asf the skeleton of an AMC file "
        "(default: the .asf in its folder), fps a rate to resample to, scale metres per BVH unit (default: "
        "chosen from the figure's size), up_axis 'y' or 'z' (default: whichever the figure stands along; "
        "z-up is turned y up), input_fps the capture rate overriding the file's, travel where its travel over "
        "the floor comes from: 'root' as read, 'feet' recovered from the planted feet, 'auto' (default) the "
        "feet when the clip is animated in place.");
}

}  // namespace mg::python
