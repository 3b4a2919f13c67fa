// The extension module motiongraph._motiongraph; the package motiongraph (motiongraph/__init__.py)
// is what users import.
#include "binding.h"

#include "motiongraph/core/json_text.h"

namespace mg::python {

namespace {

PyObject* error_type = nullptr;
PyObject* empty_graph_type = nullptr;

}  // namespace

void define_exceptions(py::module_& m) {
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<Error> empty(m, "EmptyGraphError", error.ptr());
  error.doc() = "A motiongraph error; its text is the CLI's message (FILE:LINE: what).";
  empty.doc() = "Pruning left no graph; .report is the build's report, which says why.";
  error_type = error.ptr();
  empty_graph_type = empty.ptr();
}

void raise_error(const Error& error, const nlohmann::json& report) {
  PyObject* type = error.kind == ErrorKind::kEmptyGraph ? empty_graph_type : error_type;
  // The message as text, bytes that are not UTF-8 (a Latin-1 joint or file name) as U+FFFD.
  const std::string message = error.to_string();
  const py::object text =
      py::reinterpret_steal<py::object>(PyUnicode_DecodeUTF8(message.data(), static_cast<Py_ssize_t>(message.size()), "replace"));
  py::object instance = py::reinterpret_borrow<py::object>(type)(text);
  instance.attr("report") = report.is_null() ? py::none() : to_python(report);
  PyErr_SetObject(type, instance.ptr());
  throw py::error_already_set();
}

py::object to_python(const nlohmann::json& value) {
  // Never freed: it would be released after the interpreter is gone.
  static const auto* loads = new py::object(py::module_::import("json").attr("loads"));
  return (*loads)(json_text(value));
}

std::string text_or_path(py::handle value) {
  // A path as the file system's bytes (os.fsencode): a name that is not UTF-8 too.
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || py::hasattr(value, "__fspath__")) {
    return py::module_::import("os").attr("fsencode")(value).cast<std::string>();
  }
  throw py::cast_error();  // TypeError, naming the keyword and the type given
}

py::str display_text(const std::string& text) {
  PyObject* decoded = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "replace");
  if (decoded == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(decoded);
}

void apply_options(const py::dict& options, const OptionTable& table, const char* function) {
  for (const auto& [key, value] : options) {
    const std::string name = py::str(key);
    auto it = table.find(name);
    if (it == table.end()) {
      throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" + name + "'");
    }
    if (value.is_none()) continue;  // None: the keyword's default, as if not given
    try {
      it->second(value);
    } catch (const py::cast_error&) {
      throw py::type_error(std::string(function) + "() keyword argument '" + name + "' cannot be a " +
                           py::str(py::type::of(value).attr("__name__")).cast<std::string>());
    } catch (const BadKeywordValue& bad) {
      throw py::value_error(std::string(function) + "() keyword argument '" + name + "' " + bad.what);
    }
  }
}

}  // namespace mg::python

PYBIND11_MODULE(_motiongraph, m) {
  m.doc() = "Motion graphs (Kovar, Gleicher & Pighin 2002) from motion capture: the motiongraph library.";
  mg::python::define_exceptions(m);
  mg::python::bind_motion(m);
  pybind11::class_<mg::python::PyGraph> graph(m, "Graph", "A motion graph, built or read from a .mgraph file.");
  mg::python::bind_graph(m, graph);
  mg::python::bind_synthesis(m, graph);
  mg::python::bind_library(m);
}
