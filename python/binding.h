// What the pybind11 module's parts share: errors as Python exceptions (motiongraph.Error with
// the CLI's message, EmptyGraphError when pruning leaves nothing), JSON as Python objects,
// keyword options, and the motion object that clips and synthesis results are.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stop_token>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>  // paths as str or os.PathLike

#include "motiongraph/core/error.h"
#include "motiongraph/core/json_text.h"
#include "motiongraph/motion/capture_glitches.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/pipeline/build_options.h"
#include "motiongraph/synthesis/loaded_graph.h"
#include "motiongraph/synthesis/walk.h"

namespace mg::python {

namespace py = pybind11;

// Made once by the module (module.cpp): the exception types.
void define_exceptions(py::module_& m);
// Raises motiongraph.Error (EmptyGraphError for ErrorKind::kEmptyGraph) with error.to_string(),
// the text the CLI prints after "motiongraph: ". `report`, when not null, becomes the
// exception's .report.
[[noreturn]] void raise_error(const Error& error, const nlohmann::json& report = nullptr);

template <class T>
T take(Result<T>&& result) {
  if (!result) raise_error(result.error());
  return std::move(*result);
}
inline void check(const Status& status) {
  if (!status) raise_error(status.error());
}

// Runs `work` (which leaves Python alone but through py::gil_scoped_acquire: the GIL is not
// held) on a thread of its own while this thread waits, taking the GIL every 50 ms to run
// Python's signal handlers. When one raises (Ctrl-C's KeyboardInterrupt), `stop` is asked
// (core/stop.h: the work ends early with stopped_error()), the work awaited and the handler's
// exception raised; otherwise the work's own C++ exception, if any, propagates. A progress
// callback whose exception should stop the work asks `stop` itself.
void run_stoppable(std::stop_source& stop, const std::function<void()>& work);

// A UserWarning, `stack` frames up; raises its exception when the warning filter makes it one
// (warnings.simplefilter("error")).
inline void warn(const std::string& line, int stack = 1) {
  // As UTF-8 (a file or joint name that is not is shown with U+FFFD, as the JSON reports show it).
  if (PyErr_WarnEx(PyExc_UserWarning, valid_utf8(line).c_str(), stack) < 0) throw py::error_already_set();
}

// Text from the files (a clip's name from its file, a joint's from its rig) as a str, bytes that
// are not UTF-8 shown as U+FFFD, as the JSON reports show them.
py::str display_text(const std::string& text);

// A JSON value as the Python object json.loads makes of the same text.
py::object to_python(const nlohmann::json& value);

// A number argument of a function bound with pybind11's own arguments, which takes True and False
// as 1 and 0 (load_clip(fps=True) read a clip at 1 fps): an int or a float only, as the keyword
// options take them (set()); True or False raises TypeError, an int past C's int ValueError.
struct Real {
  double value = 0.0;
};
struct Integer {
  int value = 0;
};
// True or False, Python's or numpy's (numpy.bool_ is no subclass of bool, and casts to 1 and 0).
inline bool is_true_or_false(py::handle value) {
  if (PyBool_Check(value.ptr())) return true;
  const std::string_view type = Py_TYPE(value.ptr())->tp_name;
  return type == "numpy.bool_" || type == "numpy.bool";
}
inline void refuse_bool(py::handle value) {
  if (is_true_or_false(value)) {
    throw py::type_error(fmt::format("a number is expected, not {}", py::str(value).cast<std::string>()));
  }
}

// Keyword options: each name sets something from its value; an unknown name raises TypeError
// as Python does for a function's unexpected keyword; None leaves the keyword's default.
using OptionTable = std::map<std::string, std::function<void(py::handle)>>;
void apply_options(const py::dict& options, const OptionTable& table, const char* function);
// The table's usual entry: the value cast to the field's type (TypeError when it cannot be).
// Text from a str, or a path from an os.PathLike (pathlib.Path) or bytes, as the file system's
// bytes (os.fsencode: a name that is not UTF-8 too).
std::string text_or_path(py::handle value);
// A value of the right type that the keyword cannot take: apply_options raises ValueError,
// "f() keyword argument 'name' " followed by `what`.
struct BadKeywordValue {
  std::string what;
};
template <class T>
std::function<void(py::handle)> set(T& field) {
  return [&field](py::handle value) {
    if constexpr (std::is_same_v<T, std::string>) {
      field = text_or_path(value);
    } else if constexpr (std::is_same_v<T, std::optional<std::string>>) {
      field = text_or_path(value);
    } else if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
      // A number, as the CLI's options take one: not True or False (horizon=True was a 1 s
      // horizon), finite, and an integer within its field's range.
      if (is_true_or_false(value)) throw py::cast_error();
      if constexpr (std::is_integral_v<T>) {
        if (PyLong_Check(value.ptr())) {
          bool within = true;
          if constexpr (std::is_unsigned_v<T>) {
            const unsigned long long n = PyLong_AsUnsignedLongLong(value.ptr());  // fails below 0 or past 2^64
            if (n == static_cast<unsigned long long>(-1) && PyErr_Occurred() != nullptr) {
              PyErr_Clear();
              within = false;
            } else {
              within = n <= std::numeric_limits<T>::max();
            }
          } else {
            int overflow = 0;
            const long long n = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
            within = overflow == 0 && n >= std::numeric_limits<T>::min() && n <= std::numeric_limits<T>::max();
          }
          if (!within) {
            throw BadKeywordValue{fmt::format("must be an integer from {} to {}, not {}", std::numeric_limits<T>::min(),
                                              std::numeric_limits<T>::max(), py::str(value).cast<std::string>())};
          }
        }
      }
      field = value.cast<T>();
      if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(field)) throw BadKeywordValue{fmt::format("must be a finite number, not {}", field)};
      }
    } else {
      field = value.cast<T>();
    }
  };
}

// build()'s keywords: the CLI's build options, snake_case ('--no-tag-thresholds' is
// no_tag_thresholds), plus cache_dir, no_cache, and distance_matrix and clouds (keep those
// exports for Graph.distance_matrix(), .clouds()). graph_binding.cpp.
struct BuildCall {
  BuildOptions options;
  std::string cache_dir;
  bool no_cache = false;
};
OptionTable build_option_table(BuildCall& call);

// A motion on a skeleton with its world positions: a loaded clip, a synthesis result, or the
// frames a controller step made. Synthesis results keep their graph, so that saving them
// writes the feet's contacts as the CLI does.
struct PyMotion {
  std::string name;
  Skeleton skeleton;
  Motion motion;
  std::vector<Vec3> positions;  // frames x joints, metres
  nlohmann::json report;        // null for clips
  std::shared_ptr<const LoadedGraph> graph;
  Walk walk{-1, {}};
  std::vector<ContactMask> contacts;  // per frame, of `feet`
  std::optional<FootJoints> feet;     // the foot joints `contacts` follow; nullopt: not known
  std::vector<std::string> doubts;    // a clip's: what looks wrong with it as read (clip_doubts.h)
  std::vector<FileGlitch> glitches;   // a clip's capture glitches within it (capture_glitches.h)

  PyMotion(std::string motion_name, Skeleton motion_skeleton, Motion played);
  // A synthesis result's feet from its graph, with its contacts (the walk's own when none were
  // given); none when the graph's feet are unknown.
  void take_feet_from(const SynthesisContext& context);
};

// A graph built or read, ready for synthesis, with what its build made.
struct PyGraph {
  std::shared_ptr<const LoadedGraph> loaded;
  std::string name;             // the file it was read from or written to, else "graph"
  nlohmann::json report;        // the CLI's build --report
  std::string matrix_npy;       // when the build was asked for it
  std::string clouds_npy;
  mutable py::object nodes;     // Graph.nodes, made on first use
  mutable py::object edges;     // Graph.edges, made on first use
};

void bind_motion(py::module_& m);
void bind_graph(py::module_& m, py::class_<PyGraph>& graph_class);
void bind_synthesis(py::module_& m, py::class_<PyGraph>& graph_class);
void bind_library(py::module_& m);

}  // namespace mg::python

namespace pybind11::detail {

template <class Strict>
struct type_caster<Strict, std::enable_if_t<std::is_same_v<Strict, mg::python::Real> ||
                                            std::is_same_v<Strict, mg::python::Integer>>> {
  using Plain = decltype(Strict::value);
  PYBIND11_TYPE_CASTER(Strict, const_name<std::is_integral_v<Plain>>("int", "float"));
  bool load(handle src, bool convert) {
    mg::python::refuse_bool(src);
    if constexpr (std::is_integral_v<Plain>) {
      // An int past C's int is said as such, not answered with every signature of the function.
      if (PyLong_Check(src.ptr())) {
        int overflow = 0;
        const long long n = PyLong_AsLongLongAndOverflow(src.ptr(), &overflow);
        if (overflow != 0 || n < std::numeric_limits<Plain>::min() || n > std::numeric_limits<Plain>::max()) {
          throw value_error(fmt::format("an integer from {} to {} is expected, not {}",
                                        std::numeric_limits<Plain>::min(), std::numeric_limits<Plain>::max(),
                                        str(src).cast<std::string>()));
        }
      }
    }
    make_caster<Plain> number;
    if (!number.load(src, convert)) return false;
    value.value = cast_op<Plain>(number);
    return true;
  }
  static handle cast(Strict number, return_value_policy policy, handle parent) {
    return make_caster<Plain>::cast(number.value, policy, parent);
  }
};

}  // namespace pybind11::detail
