// motiongraph.Motion: a clip read from a file or motion synthesized on a graph, its arrays
// numpy views of the C++ data (no copies), and load_clip().
#include <optional>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "binding.h"
#include "motiongraph/core/file_extension.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/motion/in_place.h"
#include "motiongraph/motion/up_axis.h"
#include "motiongraph/pipeline/clip_as_read.h"
#include "motiongraph/synthesis/facing.h"

namespace mg::python {

PyMotion::PyMotion(std::string motion_name, Skeleton motion_skeleton, Motion played)
    : name(std::move(motion_name)), skeleton(std::move(motion_skeleton)), motion(std::move(played)) {
  positions = world_positions(skeleton, motion);
}

void PyMotion::take_feet_from(const SynthesisContext& context) {
  if (!context.frame_contacts.empty() && contacts.empty() && walk.start_node >= 0) {
    contacts = context.walk_contacts(walk);
  }
  if (context.frame_contacts.empty() || static_cast<int>(contacts.size()) < motion.frame_count) {
    contacts.clear();
    feet.reset();
    return;
  }
  contacts.resize(static_cast<size_t>(motion.frame_count));
  feet = context.feet;
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

// Where the motion's skeleton faces, for a root-motion joint: where the graph's skeleton faces (a
// synthesis result) or where the clip's does, learnt from it as convert does.
Vec3 forward_axis_of(const PyMotion& m) {
  if (m.graph) return m.graph->context().tracks.forward_axis;
  FootJointNames names;
  if (m.feet) {
    const auto name = [&](int joint) { return joint >= 0 ? m.skeleton.joint(joint).name : std::string(); };
    names = {name(m.feet->left.ankle), name(m.feet->left.toe), name(m.feet->right.ankle), name(m.feet->right.toe)};
  }
  return learn_clip_forward_axis(m.skeleton, m.motion, names);
}

// The file settings save() and save_animations() take.
MotionFileSettings file_settings(bool root_motion, double root_motion_smoothing, double output_scale, bool figure) {
  MotionFileSettings settings;
  settings.units_per_metre = output_scale;
  settings.figure = figure;
  if (root_motion) {
    settings.root_motion.emplace();
    settings.root_motion->settings.smoothing_s = root_motion_smoothing;
  }
  return settings;
}

// The JSON carries the feet's contacts when they are known, as the CLI's convert and synthesis
// commands write it.
Status save_motion(const PyMotion& m, const std::string& path, MotionFileSettings settings) {
  if (settings.root_motion) settings.root_motion->forward_axis = forward_axis_of(m);
  settings.keep_root_order = !m.graph;  // a clip as it was read, as the CLI's convert writes it
  if (!m.feet) return write_motion(path, m.skeleton, m.motion, settings);
  const PositionsJsonContacts json_contacts{*m.feet, m.contacts};
  return write_motion(path, m.skeleton, m.motion, settings, &json_contacts);
}

PyMotion load_clip(const std::filesystem::path& file, const std::optional<std::filesystem::path>& asf,
                   std::optional<Real> fps_given,
                   std::optional<Real> scale, const std::optional<std::string>& up_axis, Real input_fps,
                   bool keep_rest_frames, const std::string& travel, const std::optional<std::string>& feet,
                   const std::optional<std::string>& animation) {
  const std::string path = file.string();
  ClipLoadSettings settings;
  if (asf) settings.asf_path = asf->string();
  // The least of the CLI's convert --fps: a rate that would leave a clip a frame or none is no rate.
  // A plain rate and a flag: gcc -O2 took an optional<double> copied into the GIL-free block for unset.
  const bool resample_to = fps_given.has_value();
  const double fps = resample_to ? fps_given->value : 0.0;
  if (resample_to && !(fps >= 0.01)) throw py::value_error(fmt::format("fps must be at least 0.01, not {}", fps));
  if (scale) settings.bvh_metres_per_unit = scale->value;
  if (up_axis) {
    settings.up_axis = parse_up_axis(*up_axis);
    if (!settings.up_axis) throw py::value_error("up_axis must be 'y' or 'z', not '" + *up_axis + "'");
  }
  settings.input_fps = input_fps.value;
  settings.keep_rest_frames = keep_rest_frames;
  const auto source = parse_travel_source(travel);
  if (!source) throw py::value_error("travel must be 'auto', 'root' or 'feet', not '" + travel + "'");
  settings.travel = *source;
  if (feet) {
    auto names = parse_foot_joint_names(*feet);
    if (!names) throw py::value_error("feet: " + names.error().message);
    settings.foot_names = *names;
  }
  check(settings.validate());
  Result<LoadedClip> loaded = Error{};
  double read_fps = 0.0;  // the rate the file was read at, before any resampling
  std::vector<FileGlitch> glitches;  // as info finds them in the file (kept with the rest frames)
  {
    py::gil_scoped_release release;
    loaded = ClipLoader(settings).load(path, animation);
    if (loaded) read_fps = loaded->clip.motion.fps;
    if (loaded && !keep_rest_frames) {
      glitches = in_file_frames(loaded->clip, find_capture_glitches(loaded->clip.skeleton, loaded->clip.motion));
    }
    if (loaded && resample_to) {
      auto resampled = resample(loaded->clip.motion, fps);
      if (!resampled) {
        loaded = resampled.error();
      } else {
        loaded->clip.motion = std::move(*resampled);
      }
    }
  }
  LoadedClip got = take(std::move(loaded));
  PyMotion clip(got.clip.name, std::move(got.clip.skeleton), std::move(got.clip.motion));
  clip.glitches = std::move(glitches);
  // Its feet's contacts (none when the feet are not found and none were named), and what info
  // says looks wrong with it (its unit, floor, feet or clock).
  Result<ClipAsRead> judged = Error{};
  {
    py::gil_scoped_release release;
    judged = judge_clip_as_read(clip.skeleton, clip.motion, clip.positions, read_fps, got.format, settings.foot_names);
  }
  ClipAsRead as_read = take(std::move(judged));
  if (as_read.contacts) {
    clip.feet = as_read.contacts->feet;
    clip.contacts = std::move(as_read.contacts->masks);
  }
  clip.doubts = as_read.doubts.phrases();
  return clip;
}

}  // namespace

// Motion.with_frames: a new motion on m's skeleton from numpy arrays.
PyMotion motion_with_frames(const PyMotion& m, const py::array_t<double>& rotations,
                            const std::optional<py::array_t<double>>& translations, std::optional<double> fps,
                            const std::optional<std::string>& name) {
  const int joints = m.skeleton.joint_count(), slots = m.motion.translated_count;
  auto shape_of = [](const py::array& a) {
    std::string text = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) text += (i ? ", " : "") + std::to_string(a.shape(i));
    return text + (a.ndim() == 1 ? ",)" : ")");
  };
  if (rotations.ndim() != 3 || rotations.shape(1) != joints || rotations.shape(2) != 4 || rotations.shape(0) < 1) {
    throw py::value_error(fmt::format("with_frames(): rotations must be frames x {} joints x 4, not {}", joints,
                                      shape_of(rotations)));
  }
  const int frames = static_cast<int>(rotations.shape(0));
  if (!translations && frames != m.motion.frame_count) {
    throw py::value_error(fmt::format("with_frames(): {} frames of rotations need their translations (this motion has "
                                      "{} frames)", frames, m.motion.frame_count));
  }
  if (translations && (translations->ndim() != 3 || translations->shape(0) != frames ||
                       translations->shape(1) != slots || translations->shape(2) != 3)) {
    throw py::value_error(fmt::format("with_frames(): translations must be {} frames x {} translated joints x 3, "
                                      "not {}", frames, slots, shape_of(*translations)));
  }
  const double rate = fps.value_or(m.motion.fps);
  if (!(rate > 0.0) || !std::isfinite(rate)) {
    throw py::value_error(fmt::format("with_frames(): fps must be a positive number, not {}", rate));
  }
  Motion motion(m.skeleton, frames, rate);
  const double* q = rotations.data();
  for (int f = 0; f < frames; ++f) {
    for (int j = 0; j < joints; ++j, q += 4) {
      const Quat rotation(q[3], q[0], q[1], q[2]);  // w, x, y, z
      const double norm = rotation.norm();
      if (!std::isfinite(norm) || !(norm > 1e-12)) {
        throw py::value_error(fmt::format("with_frames(): rotations[{}, {}] is not a rotation ({}, {}, {}, {})", f, j,
                                          q[0], q[1], q[2], q[3]));
      }
      motion.rotations(f)[static_cast<size_t>(j)] = rotation.normalized();
    }
  }
  if (translations) {
    const double* t = translations->data();
    for (int f = 0; f < frames; ++f) {
      for (int i = 0; i < slots; ++i, t += 3) {
        if (!std::isfinite(t[0]) || !std::isfinite(t[1]) || !std::isfinite(t[2])) {
          throw py::value_error(fmt::format("with_frames(): translations[{}, {}] is not finite", f, i));
        }
        motion.translations(f)[static_cast<size_t>(i)] = Vec3(t[0], t[1], t[2]);
      }
    }
  } else {
    motion.local_translations_m.assign(m.motion.local_translations_m.begin(), m.motion.local_translations_m.end());
  }
  // A clip of its own: no graph, report or contacts (not known for new frames).
  return PyMotion(name.value_or(m.name), m.skeleton, std::move(motion));
}

void bind_motion(py::module_& m) {
  py::class_<PyMotion>(m, "Motion",
                       "Motion on a skeleton: a clip read from a file (load_clip) or motion synthesized on a graph "
                       "(Graph.walk, Graph.path, Controller.step). Arrays are read-only views, not copies.")
      .def_property_readonly("name", [](const PyMotion& self) { return display_text(self.name); },
                             "A clip's name (its file's, as the library names it), or what made it: 'walk', "
                             "'path', 'steer'.")
      .def_property_readonly("fps", [](const PyMotion& self) { return self.motion.fps; }, "Frames a second.")
      .def_property_readonly("frame_count", [](const PyMotion& self) { return self.motion.frame_count; },
                             "Its frames, as len() gives them.")
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
      .def_property_readonly(
          "translations",
          [](py::object self) {
            const auto& motion = self.cast<const PyMotion&>();
            const py::ssize_t frames = motion.motion.frame_count, slots = motion.motion.translated_count;
            constexpr py::ssize_t d = sizeof(double);
            const auto& t = motion.motion.local_translations_m;
            py::array_t<double> view({frames, slots, py::ssize_t{3}}, {slots * 3 * d, 3 * d, d},
                                     t.empty() ? nullptr : t.front().data(), self);
            py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
            return view;
          },
          "Local translation (metres) of each joint whose translation is animated (translated_joints: the "
          "root, and any other the file animates), relative to its parent: float64 array frames x "
          "len(translated_joints) x 3. For a root with no parent, its world position.")
      .def_property_readonly(
          "translated_joints",
          [](const PyMotion& self) {
            const auto joints = self.skeleton.translated_joints();
            return std::vector<int>(joints.begin(), joints.end());
          },
          "The joints whose translation is animated (translations' columns), the root first.")
      .def(
          "with_frames",
          [](const PyMotion& self, const py::array_t<double, py::array::c_style | py::array::forcecast>& rotations,
             const std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>>& translations,
             std::optional<Real> fps, const std::optional<std::string>& name) {
            return motion_with_frames(self, rotations, translations,
                                      fps ? std::optional<double>(fps->value) : std::nullopt, name);
          },
          py::arg("rotations"), py::arg("translations") = py::none(), py::arg("fps") = py::none(),
          py::arg("name") = py::none(),
          "A new motion on this one's skeleton from arrays, as its own rotations and translations give them: "
          "rotations frames x joints x 4 (x, y, z, w; normalized), translations frames x len(translated_joints) x "
          "3 in metres (None: this motion's, when the frame counts agree), at fps (None: this one's). Edit a clip "
          "in numpy and save() it. Raises ValueError for a wrong shape, a value not finite or a zero quaternion.")
      .def_property_readonly("joint_names",
                             [](const PyMotion& self) {
                               py::list names;
                               for (const JointDef& joint : self.skeleton.joints()) {
                                 names.append(display_text(joint.name));
                               }
                               return names;
                             })
      .def_property_readonly("parents",
                             [](const PyMotion& self) {
                               std::vector<int> parents;
                               for (const JointDef& joint : self.skeleton.joints()) parents.push_back(joint.parent);
                               return parents;
                             },
                             "Each joint's parent index (-1 for the root); parents come before children.")
      .def_property_readonly(
          "foot_joints",
          [](const PyMotion& self) -> py::object {
            if (!self.feet) return py::none();
            py::list names;
            for (const ContactColumn& column : contact_columns(*self.feet)) {
              names.append(display_text(self.skeleton.joint(column.joint).name));
            }
            return names;
          },
          "The foot joints that contacts follows: left ankle, left toe, right ankle, right toe (a foot without "
          "a toe joint gives its ankle only); None when the feet are not known.")
      .def_property_readonly(
          "contacts",
          [](const PyMotion& self) -> py::object {
            if (!self.feet) return py::none();
            const std::vector<ContactColumn> columns = contact_columns(*self.feet);
            const auto frames = static_cast<py::ssize_t>(self.contacts.size());
            const auto width = static_cast<py::ssize_t>(columns.size());
            py::array_t<bool> planted({frames, width});
            auto out = planted.mutable_unchecked<2>();
            for (py::ssize_t f = 0; f < frames; ++f) {
              for (py::ssize_t c = 0; c < width; ++c) out(f, c) = (self.contacts[f] & columns[c].bit) != 0;
            }
            return planted;
          },
          "Whether each foot joint (foot_joints) rests on the floor: bool array frames x foot joints, as "
          "convert's JSON writes it; None when the feet are not known. A copy.")
      .def_property_readonly("report", [](const PyMotion& self) { return to_python(self.report); },
                             "The CLI's --report of the synthesis (a dict), None for a clip.")
      .def_readonly("doubts", &PyMotion::doubts,
                    "What looks wrong with a clip as read, as info's warning says it (a list of phrases: a figure "
                    "of no person's size, off the floor, feet that never rest, a clock that is not the capture's); "
                    "empty for a clip that looks right and for synthesized motion.")
      .def_property_readonly(
          "glitches",
          [](const PyMotion& self) {
            py::list out;
            for (const FileGlitch& g : self.glitches) {
              py::dict d;
              d["frame"] = g.frame;
              d["seconds"] = g.seconds;
              d["joint"] = g.joint;
              d["jump_m"] = g.jump_m;
              out.append(std::move(d));
            }
            return out;
          },
          "A clip's capture glitches within it, where a library cuts it (info's capture_glitches): a list of "
          "dicts with the file's frame (1-based) after which a joint jumps, the seconds from the file's start "
          "where it lands, the joint and its jump in metres; empty for a clean clip, one read with "
          "keep_rest_frames=True, and synthesized motion.")
      .def(
          "save",
          [](const PyMotion& self, const std::filesystem::path& path, bool root_motion,
             std::optional<Real> root_motion_smoothing, std::optional<Real> output_scale, bool figure,
             const std::optional<std::string>& name) {
            // What the CLI refuses (--root-motion-smoothing needs --root-motion), and options the
            // format does not take, said rather than dropped.
            if (root_motion_smoothing && !root_motion) {
              throw py::value_error("save(): root_motion_smoothing needs root_motion=True");
            }
            if (self.motion.frame_count == 0) {
              throw py::value_error("save(): the motion has no frames (a controller before its first step)");
            }
            const std::string ext = lower_extension(path.string());
            if (output_scale && output_scale->value != 1.0 && ext != ".bvh") {
              warn(fmt::format("save(): output_scale is for .bvh; {} is written in {}", ext,
                               ext == ".fbx" ? "centimetres" : "metres"));
            }
            if (!figure && !is_scene_extension(ext)) {
              warn(fmt::format("save(): figure=False is for {}; {} has no stick figure", kSceneFormats, ext));
            }
            if (name && !is_scene_extension(ext)) {
              warn(fmt::format("save(): name is for {}; {} has no animation name", kSceneFormats, ext));
            }
            if (name && name->empty()) throw py::value_error("save(): name must not be empty");
            MotionFileSettings settings =
                file_settings(root_motion, root_motion_smoothing.value_or(Real{0.5}).value,
                              output_scale.value_or(Real{1.0}).value, figure);
            settings.animation_name = name.value_or("");
            Status saved = Ok{};
            {
              py::gil_scoped_release release;
              saved = save_motion(self, path.string(), settings);
            }
            check(saved);
          },
          py::arg("path"), py::arg("root_motion") = false, py::arg("root_motion_smoothing") = py::none(),
          py::arg("output_scale") = py::none(), py::arg("figure") = true, py::arg("name") = py::none(),
          "Writes the motion: .bvh (metres times output_scale), .glb (binary glTF 2.0, metres; .gltf the same as "
          "JSON, one file), .fbx (binary FBX 7.4, centimetres; figure=False leaves their stick figure out) or .json (world positions, with the feet's contacts), as the CLI does (its "
          "--output-scale and --no-figure); root_motion adds a root-motion joint above the root (the CLI's "
          "--root-motion, averaged over root_motion_smoothing seconds, 0.5 when not given). An option the format "
          "does not take (output_scale but for .bvh, figure=False and name but for .glb, .gltf and .fbx) gives a "
          "UserWarning; name names the animation (default: the file's name, as the CLI names it; e.g. "
          "name=motion.name); a "
          "motion of no frames raises ValueError.")
      .def("__repr__", [](const PyMotion& self) {
        return display_text(fmt::format("<motiongraph.Motion '{}': {} frames at {:g} fps, {} joints>", self.name,
                                        self.motion.frame_count, self.motion.fps, self.skeleton.joint_count()));
      });
  m.def(
      "save_animations",
      [](const std::filesystem::path& path, const std::vector<const PyMotion*>& motions,
         const std::optional<std::vector<std::string>>& names, bool root_motion,
         std::optional<Real> root_motion_smoothing, bool figure) {
        if (root_motion_smoothing && !root_motion) {  // as save() says it
          throw py::value_error("save_animations(): root_motion_smoothing needs root_motion=True");
        }
        if (names && names->size() != motions.size()) {
          throw py::value_error(fmt::format("names: {} given for {} motions", names->size(), motions.size()));
        }
        std::vector<NamedMotion> set;
        for (size_t i = 0; i < motions.size(); ++i) {
          if (!motions[i]) throw py::value_error(fmt::format("motions[{}] is None", i));
          const PyMotion& motion = *motions[i];
          if (motion.motion.frame_count == 0) {  // as save() says it
            throw py::value_error(fmt::format(
                "save_animations(): motions[{}] has no frames (a controller before its first step)", i));
          }
          set.push_back({motion.name, names ? (*names)[i] : motion.name, &motion.skeleton, &motion.motion,
                         root_motion ? forward_axis_of(motion) : Vec3::UnitZ()});
        }
        const MotionFileSettings settings =
            file_settings(root_motion, root_motion_smoothing.value_or(Real{0.5}).value, 1.0, figure);
        Status saved = Ok{};
        {
          py::gil_scoped_release release;
          saved = write_animation_set(path.string(), set, settings);
        }
        check(saved);
      },
      py::arg("path"), py::arg("motions"), py::arg("names") = py::none(), py::arg("root_motion") = false,
      py::arg("root_motion_smoothing") = py::none(), py::arg("figure") = true,
      "Writes several motions of one rig (clips of one skeleton, or results of one graph) into one .glb, .gltf or .fbx, "
      "an animation each, as the CLI's convert does with several clips: names the animations' (default: each "
      "motion's name; a name repeated gets _2, _3...), root_motion, root_motion_smoothing and figure as save() "
      "takes them (smoothing 0.5 s when not given; given without root_motion, ValueError).");
  m.def("load_clip", &load_clip, py::arg("path"), py::arg("asf") = py::none(), py::arg("fps") = py::none(),
        py::arg("scale") = py::none(), py::arg("up_axis") = py::none(), py::arg("input_fps") = 0.0,
        py::arg("keep_rest_frames") = false, py::arg("travel") = "auto", py::arg("feet") = py::none(),
        py::arg("animation") = py::none(),
        "Reads a clip (.amc with its .asf, .bvh, or an animation of a .glb/.gltf/.fbx) as the CLI's convert does: asf "
        "the skeleton of an AMC file "
        "(default: the .asf in its folder), fps a rate to resample to, scale metres per BVH (or FBX number) unit (default: "
        "chosen from the figure's size), up_axis 'y' or 'z' (default: whichever the figure stands along; "
        "z-up is turned y up), input_fps the capture rate overriding the file's, travel where its travel over "
        "the floor comes from: 'root' as read, 'feet' recovered from the planted feet, 'auto' (default) the "
        "feet when the clip is animated in place; feet the foot joints as 'LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,"
        "RIGHT_TOE', any left empty to find it by name (default: found by name), for the travel and contacts; "
        "animation the glTF or FBX file's animation to read (default: its first).");
}

}  // namespace mg::python
