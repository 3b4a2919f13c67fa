// motiongraph.build() and load_graph(): the library's build_graph() with the CLI's options as
// keywords (pipeline/build_options.h), and motiongraph.Graph: its counts, nodes, report, save().
#include <optional>

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "binding.h"
#include "motiongraph/graph/threshold_choice.h"
#include "motiongraph/io/file.h"
#include "motiongraph/pipeline/build_graph.h"
#include "motiongraph/pipeline/build_options.h"

namespace mg::python {

namespace {

// A list of texts, or one text of comma-separated items (as --connect-tags takes).
std::vector<std::string> text_list(py::handle value) {
  if (py::isinstance<py::str>(value)) {
    std::vector<std::string> items;
    const std::string text = value.cast<std::string>();
    size_t begin = 0;
    for (size_t comma; (comma = text.find(',', begin)) != std::string::npos; begin = comma + 1) {
      items.push_back(text.substr(begin, comma - begin));
    }
    items.push_back(text.substr(begin));
    return items;
  }
  return value.cast<std::vector<std::string>>();
}

// A number as the shortest text that reads back as the same double (Python's repr).
std::string exact_text(py::handle number) {
  return py::repr(py::float_(py::reinterpret_borrow<py::object>(number))).cast<std::string>();
}

}  // namespace

OptionTable build_option_table(BuildCall& call) {
  BuildOptions& b = call.options;
  return {
      {"fps", [&b](py::handle v) { b.fps = v.cast<double>(); b.fps_given = true; }},
      {"asf", set(b.asf)},
      {"scale", [&b](py::handle v) { b.scale = v.cast<std::optional<double>>(); }},
      {"up_axis", set(b.up_axis)},
      {"travel", set(b.travel)},
      {"input_fps", set(b.input_fps)},
      {"keep_rest_frames", set(b.keep_rest_frames)},
      {"cmu_index", set(b.cmu_index)},
      {"no_cmu_tags", set(b.no_cmu_tags)},
      {"no_name_tags", set(b.no_name_tags)},
      {"whole_clip_tags", set(b.whole_clip_tags)},
      {"no_loops", set(b.no_loops)},
      {"mirror",
       [&b](py::handle v) {
         // "auto", "on" or "off"; anything else as a truth value (True, numpy.bool_): "on" or "off".
         b.mirror = py::isinstance<py::str>(v) ? v.cast<std::string>() : std::string(v.cast<bool>() ? "on" : "off");
       }},
      {"feet", set(b.feet)},
      {"ignore_tags", set(b.ignore_tags)},
      {"bridges", set(b.bridges.per_tag_pair)},
      {"max_bridge", set(b.max_bridge_cm)},
      {"bridge_blend", set(b.bridges.max_blend_factor)},
      {"connect_tags", [&b](py::handle v) { b.connect_tags = text_list(v); }},
      {"cloud", set(b.cloud)},
      {"ring_spacing", set(b.cloud_settings.ring_spacing_m)},
      {"ring_radius", set(b.cloud_settings.ring_radius_m)},
      {"ring_points", set(b.cloud_settings.points_per_ring)},
      {"joint_weight",
       [&b](py::handle v) {
         b.joint_weights.clear();
         if (py::isinstance<py::dict>(v)) {
           // {name: weight}: as NAME=WEIGHT with the weight's exact decimal form.
           for (const auto& [name, weight] : v.cast<py::dict>()) {
             b.joint_weights.push_back(name.cast<std::string>() + "=" + exact_text(weight));
           }
         } else {
           b.joint_weights = text_list(v);
         }
       }},
      {"window", set(b.distance.window_frames)},
      {"taper", set(b.taper)},
      {"threshold",
       [&b](py::handle v) {
         if (py::isinstance<py::bool_>(v)) throw py::cast_error();  // True is no distance
         b.threshold = py::isinstance<py::str>(v) ? v.cast<std::string>() : exact_text(v);
       }},
      {"threshold_quantile", set(b.quantile)},
      {"coverage", set(b.choice.coverage)},
      {"min_transition_rate", set(b.choice.min_transition_rate)},
      {"max_threshold", set(b.choice.max_rms_cm)},
      {"path_check", set(b.path_check.tolerance_m)},
      {"no_path_check", set(b.no_path_check)},
      {"no_path_check_mirror", set(b.no_path_check_mirror)},
      {"max_out", set(b.spacing.max_out)},
      {"out_window", set(b.spacing.out_window_frames)},
      {"min_piece", set(b.spacing.min_piece_frames)},
      {"no_tag_thresholds", [&b](py::handle v) { b.transitions.per_tag_thresholds = !v.cast<bool>(); }},
      {"locality", set(b.transitions.locality_radius)},
      {"continuation_radius", set(b.continuation_radius)},
      {"tile", set(b.tile_frames)},
      {"exhaustive", set(b.exhaustive)},
      {"pruned_from", set(b.pruned_from)},
      {"threads", set(b.distance.threads)},
      {"cache_dir", set(call.cache_dir)},
      {"no_cache", set(call.no_cache)},
      {"distance_matrix", set(b.exports.matrix_npy)},
      {"clouds", set(b.exports.clouds_npy)},
  };
}

namespace {

// The loaded graph of a file made or read under `name`.
std::shared_ptr<const LoadedGraph> load_file(GraphFile file, const std::string& name) {
  Result<std::unique_ptr<LoadedGraph>> loaded = Error{};
  {
    py::gil_scoped_release release;
    loaded = LoadedGraph::create(std::move(file), name);
  }
  return take(std::move(loaded));
}

PyGraph build(const std::vector<std::string>& inputs, const py::dict& options, const py::object& progress) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr())) {
    throw py::type_error("build(): progress must be callable");  // said now, not at its first line
  }
  BuildCall call;
  apply_options(options, build_option_table(call), "build");
  BuildSettings settings = take(build_settings_from(call.options));
  std::unique_ptr<DistanceCache> cache;
  if (!call.no_cache) {
    cache = std::make_unique<FileDistanceCache>(call.cache_dir.empty() ? default_distance_cache_folder()
                                                                       : call.cache_dir);
  }
  // The progress callback gets the lines the build logs and, every 2 s of reading and of the
  // distance stage, how far they got. It runs with the GIL; its first exception stops the build
  // (at its next step) and is raised. So does Ctrl-C (run_stoppable).
  std::stop_source stop;
  std::optional<py::error_already_set> callback_error;
  std::vector<std::string> warnings;
  BuildLog log;
  log.stop = stop.get_token();
  if (!progress.is_none()) {
    log.info = log.progress = [&](const std::string& line) {
      py::gil_scoped_acquire acquire;
      if (callback_error) return;
      try {
        progress(line);
      } catch (py::error_already_set& e) {
        callback_error = std::move(e);
        stop.request_stop();
      }
    };
  }
  log.warning = [&warnings](const std::string& line) { warnings.push_back(line); };
  Result<GraphBuild> built = Error{};
  run_stoppable(stop, [&] { built = build_graph(inputs, settings, cache.get(), log); });
  if (callback_error) throw std::move(*callback_error);
  for (const std::string& line : warnings) warn(line, 2);  // the caller of motiongraph.build, past its wrapper
  GraphBuild b = take(std::move(built));
  if (!b.graph_status) raise_error(b.graph_status.error(), b.report);
  PyGraph graph;
  graph.name = "graph";
  graph.report = std::move(b.report);
  graph.matrix_npy = std::move(b.matrix_npy);
  graph.clouds_npy = std::move(b.clouds_npy);
  // The graph as its file holds it (the motion as the file stores it), so that it plays what the
  // same graph saved and read back plays, and the CLI's from the file `build` writes.
  Result<GraphFile> stored = Error{};
  {
    py::gil_scoped_release release;
    const std::string bytes = serialize_graph_file(b.file);
    b.file = GraphFile{};  // (not held beside its bytes and their copy)
    stored = parse_graph_file(bytes, graph.name);
  }
  graph.loaded = load_file(take(std::move(stored)), graph.name);
  return graph;
}

PyGraph load_graph(const std::filesystem::path& file, Integer skeleton_given) {
  const int skeleton = skeleton_given.value;
  if (skeleton < -1) {
    throw py::value_error(
        fmt::format("load_graph(): skeleton must be -1 (the first clip's) or an index, not {}", skeleton));
  }
  const std::string path = file.string();
  PyGraph graph;
  graph.name = path;
  Result<std::unique_ptr<LoadedGraph>> loaded = Error{};
  {
    py::gil_scoped_release release;
    loaded = LoadedGraph::load(path, skeleton);
  }
  graph.loaded = take(std::move(loaded));
  const std::string& report = graph.loaded->file().report_json;
  if (!report.empty()) graph.report = nlohmann::json::parse(report, nullptr, false);
  if (graph.report.is_discarded()) graph.report = nullptr;  // not JSON: no report
  return graph;
}

// Graph.edges' rows: each edge of the pruned graph as a dict (see its docstring).
py::list edge_rows(const PyGraph& g) {
  const MotionGraph& graph = g.loaded->file().graph;
  // D to RMS cm as the build reports its threshold (threshold_choice.h rms_cm_of_distance): the
  // window's weight from the report's pair of them.
  auto reported = [&](const char* key) { return g.report.is_object() ? g.report.value(key, 0.0) : 0.0; };
  const double threshold = reported("threshold"), threshold_rms_cm = reported("threshold_rms_cm");
  const double window_weight =
      threshold > 0.0 && threshold_rms_cm > 0.0 ? threshold / (threshold_rms_cm * threshold_rms_cm * 1e-4) : 0.0;
  py::list rows;
  for (const GraphEdge& edge : graph.edges) {
    py::dict row;
    row["from"] = edge.from_node;
    row["to"] = edge.to_node;
    row["kind"] = !edge.transition ? "clip" : edge.bridge ? "bridge" : "transition";
    row["frames"] = edge.frame_count;
    if (edge.transition) {
      const Transition& t = graph.transitions[static_cast<size_t>(edge.transition_index)];
      row["from_frame"] = t.from_frame;
      row["to_frame"] = t.to_frame;
      row["distance"] = static_cast<double>(t.distance);
      row["rms_cm"] = window_weight > 0.0 ? py::object(py::float_(rms_cm_of_distance(t.distance, window_weight)))
                                          : py::object(py::none());
    } else {
      row["from_frame"] = graph.nodes[static_cast<size_t>(edge.from_node)].frame;
      row["to_frame"] = graph.nodes[static_cast<size_t>(edge.to_node)].frame;
      row["distance"] = py::none();
      row["rms_cm"] = py::none();
    }
    rows.append(row);
  }
  return rows;
}

}  // namespace

void bind_graph(py::module_& m, py::class_<PyGraph>& graph) {
  graph.def_property_readonly("name", [](const PyGraph& g) { return display_text(g.name); })
      .def_property_readonly("node_count", [](const PyGraph& g) { return g.loaded->file().graph.node_count(); })
      .def_property_readonly("edge_count", [](const PyGraph& g) { return g.loaded->file().graph.edge_count(); })
      .def_property_readonly("transition_count",
                             [](const PyGraph& g) {
                               int transitions = 0;
                               for (const GraphEdge& e : g.loaded->file().graph.edges) transitions += e.transition;
                               return transitions;
                             },
                             "The edges that blend one clip into another: transitions and bridges (edges' kind "
                             "'transition' or 'bridge'), as build's log counts them.")
      .def_property_readonly(
          "frame_count", [](const PyGraph& g) { return g.loaded->file().database.frame_count(); },
          "The frames of the library it was built from (the nodes' frame numbers run over them), not only those "
          "the graph plays.")
      .def_property_readonly("fps", [](const PyGraph& g) { return g.loaded->file().database.fps; },
                             "The frame rate of its library and of everything synthesized on it.")
      .def_property_readonly(
          "threshold", [](const PyGraph& g) { return g.loaded->file().threshold; },
          "The transition threshold as D, the distance (not cm: report['threshold_rms_cm'] gives it as RMS "
          "point distance over the window); per motion type, the lowest of theirs (tag_thresholds gives each).")
      .def_property_readonly("tags", [](const PyGraph& g) { return g.loaded->file().database.tag_names; },
                             "The motion types (tags) of its library.")
      .def_property_readonly(
          "nodes",
          [](const PyGraph& g) {
            // Made once (the tags of every frame are the slow part), handed out as copies.
            if (!g.nodes) {
              const GraphFile& file = g.loaded->file();
              const std::vector<TagMask> tags = file.database.frame_tags();
              py::list nodes;
              for (const GraphNode& node : file.graph.nodes) {
                const DatabaseClip& clip = file.database.clips[node.clip];
                py::dict row;
                row["frame"] = node.frame;
                row["clip"] = display_text(clip.name);
                row["clip_frame"] = node.frame - clip.first_frame;
                row["tags"] = file.database.tag_names_of(tags.empty() ? 0 : tags[node.frame]);
                nodes.append(row);
              }
              g.nodes = nodes;
            }
            py::list copy;
            for (const py::handle row : g.nodes) {
              PyObject* copied = PyDict_Copy(row.ptr());  // (py::dict(row) would be row)
              if (copied == nullptr) throw py::error_already_set();
              auto own = py::reinterpret_steal<py::dict>(copied);
              PyObject* tags = PySequence_List(py::object(own["tags"]).ptr());
              if (tags == nullptr) throw py::error_already_set();
              own["tags"] = py::reinterpret_steal<py::list>(tags);
              copy.append(own);
            }
            return copy;
          },
          "One dict per node, numbered as walk() and the CLI's 'inspect --nodes' number them: its database "
          "frame, clip, frame within the clip and tags.")
      .def_property_readonly(
          "edges",
          [](const PyGraph& g) {
            if (!g.edges) g.edges = edge_rows(g);
            py::list copy;
            for (const py::handle row : g.edges) {
              PyObject* own = PyDict_Copy(row.ptr());  // its values are numbers, text and None
              if (own == nullptr) throw py::error_already_set();
              copy.append(py::reinterpret_steal<py::dict>(own));
            }
            return copy;
          },
          "One dict per edge, numbered as the reports' 'edges' number them (per node its clip piece first, then its "
          "transitions): 'from' and 'to' (nodes), 'kind' ('clip', 'transition' or 'bridge': a blend between motion "
          "types above the threshold), 'frames' played, 'from_frame' and 'to_frame' (the database frames it leaves "
          "from and arrives at: a clip piece's nodes' frames, a transition's window pair), and 'distance' (D of a "
          "transition or bridge) and 'rms_cm' (the same as the RMS point distance over the window), None for a clip "
          "piece.")
      .def_property_readonly("report", [](const PyGraph& g) { return to_python(g.report); },
                             "The build's report (the CLI's build --report), as a dict.")
      .def("_matrix_npy", [](const PyGraph& g) { return py::bytes(g.matrix_npy); })
      .def("_clouds_npy", [](const PyGraph& g) { return py::bytes(g.clouds_npy); })
      .def(
          "save",
          [](PyGraph& g, const std::filesystem::path& file) {
            const std::string path = file.string();
            check(check_graph_output(path));
            Status saved = Ok{};
            {
              py::gil_scoped_release release;
              saved = write_file_atomic(path, serialize_graph_file(g.loaded->file()));
            }
            check(saved);
            g.name = path;  // the file it now is: messages name it
          },
          py::arg("path"), "Writes the graph file (.mgraph), as the CLI's build -o does.")
      .def("__repr__", [](const PyGraph& g) {
        return display_text("<motiongraph.Graph '" + g.name + "': " +
                            std::to_string(g.loaded->file().graph.node_count()) + " nodes, " +
                            std::to_string(g.loaded->file().graph.edge_count()) + " edges>");
      });
  m.def("_build", &build, py::arg("inputs"), py::arg("options"), py::arg("progress"));
  m.def("load_graph", &load_graph, py::arg("path"), py::arg("skeleton") = -1,
        "Reads a .mgraph file and sets up synthesis on the skeleton of index `skeleton` (-1: the first "
        "clip's).");
}

}  // namespace mg::python
