#include "motiongraph/database/manifest.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "motiongraph/core/file_extension.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/in_place.h"
#include "motiongraph/motion/length_unit_choice.h"
#include "motiongraph/motion/up_axis.h"

namespace mg {

namespace {

int line_of(const toml::node& node) { return static_cast<int>(node.source().begin.line); }
int line_of(const toml::key& key) { return static_cast<int>(key.source().begin.line); }

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

// Reads the values of one manifest table; every error carries the manifest's name and a line.
class Reader {
 public:
  explicit Reader(std::string file_name) : file_(std::move(file_name)) {}

  Error error(int line, std::string message) const { return Error{file_, line, std::move(message)}; }

  Status check_keys(const toml::table& table, std::initializer_list<std::string_view> known,
                    std::string_view where) const {
    for (auto&& [key, node] : table) {
      (void)node;
      if (std::find(known.begin(), known.end(), key.str()) == known.end()) {
        std::string list;
        for (std::string_view k : known) list += fmt::format("{}{}", list.empty() ? "" : ", ", k);
        return error(line_of(key), fmt::format("unknown key '{}' {} (known keys: {})", key.str(), where, list));
      }
    }
    return Ok{};
  }

  // An optional name from a fixed set (an up axis, a travel source): `parse` gives nullopt for a
  // name outside it, and `names` lists the set for the message ("\"y\" or \"z\""). `out` is set
  // when the key is present, left unset otherwise.
  template <typename T, typename Parse>
  Status optional_name(const toml::node* node, std::string_view key, Parse parse, std::string_view names,
                       std::optional<T>& out) const {
    if (!node) return Ok{};
    auto text = string(*node, key);
    if (!text) return text.error();
    out = parse(*text);
    if (!out) return error(line_of(*node), fmt::format("'{}' must be {}, not \"{}\"", key, names, *text));
    return Ok{};
  }
  Status optional_up_axis(const toml::node* node, std::optional<UpAxis>& out) const {
    return optional_name(node, "up_axis", parse_up_axis, "\"y\" or \"z\"", out);
  }
  Status optional_travel(const toml::node* node, std::optional<TravelSource>& out) const {
    return optional_name(node, "travel", parse_travel_source, "\"auto\", \"root\" or \"feet\"", out);
  }

  // A positive finite number written as an integer or a float.
  // An optional positive number: `out` is set when the key is present, left unset otherwise.
  Status optional_positive(const toml::node* node, std::string_view key, std::optional<double>& out) const {
    if (!node) return Ok{};
    auto value = positive_number(*node, key);
    if (!value) return value.error();
    out = *value;
    return Ok{};
  }
  // An optional boolean: `out` is set when the key is present.
  Status optional_boolean(const toml::node* node, std::string_view key, std::optional<bool>& out) const {
    if (!node) return Ok{};
    auto value = node->as_boolean();
    if (!value) return error(line_of(*node), fmt::format("'{}' must be true or false, not {}", key, type_name(*node)));
    out = value->get();
    return Ok{};
  }
  // The same, within the range of a length unit's scale (length_unit_choice.h).
  Status optional_scale(const toml::node* node, std::string_view key, std::optional<double>& out) const {
    if (auto s = optional_positive(node, key, out); !s) return s;
    if (out && !is_length_unit_scale(*out)) {
      return error(line_of(*node), fmt::format("'{}' must lie between {:g} and {:g} metres per unit, not {:g}", key,
                                               kMinLengthUnitScale, kMaxLengthUnitScale, *out));
    }
    return Ok{};
  }

  Result<double> positive_number(const toml::node& node, std::string_view key) const {
    double value = 0.0;
    if (auto i = node.as_integer()) {
      value = static_cast<double>(i->get());
    } else if (auto f = node.as_floating_point()) {
      value = f->get();
    } else {
      return error(line_of(node), fmt::format("'{}' must be a number, not {}", key, type_name(node)));
    }
    if (!std::isfinite(value) || !(value > 0.0)) {
      return error(line_of(node), fmt::format("'{}' must be a positive number, not {}", key, value));
    }
    return value;
  }

  Result<std::string> string(const toml::node& node, std::string_view key) const {
    auto s = node.as_string();
    if (!s) return error(line_of(node), fmt::format("'{}' must be a string, not {}", key, type_name(node)));
    if (s->get().empty()) return error(line_of(node), fmt::format("'{}' must not be empty", key));
    return s->get();
  }

  // A frame number of the file's numbering: an integer >= 1.
  Result<int> frame(const toml::node& node, std::string_view key) const {
    auto i = node.as_integer();
    if (!i) {
      return error(line_of(node), fmt::format("'{}' must be an integer frame number, not {}", key, type_name(node)));
    }
    const long long value = i->get();
    if (value < 1) {
      return error(line_of(node), fmt::format("'{}' is {}; frames are numbered from 1 (the file's first frame)",
                                              key, value));
    }
    if (value > std::numeric_limits<int>::max()) return error(line_of(node), fmt::format("'{}' is too large", key));
    return static_cast<int>(value);
  }

  Result<std::vector<std::string>> tags(const toml::node& node) const {
    auto array = node.as_array();
    if (!array) {
      return error(line_of(node), fmt::format("'tags' must be an array of strings, e.g. [\"walk\"], not {}",
                                              type_name(node)));
    }
    std::vector<std::string> names;
    for (const toml::node& element : *array) {
      auto s = element.as_string();
      if (!s) return error(line_of(element), fmt::format("a tag must be a string, not {}", type_name(element)));
      if (!is_valid_tag_name(s->get())) {
        return error(line_of(element), fmt::format("tag \"{}\" is not a valid name: use letters, digits, '_' and '-'",
                                                   s->get()));
      }
      if (std::find(names.begin(), names.end(), s->get()) == names.end()) names.push_back(s->get());
    }
    return names;
  }

 private:
  std::string file_;
};

Result<ManifestRange> read_range(const Reader& in, const toml::table& table, const ManifestClip& clip) {
  ManifestRange range;
  range.line = line_of(table);
  if (auto s = in.check_keys(table, {"first_frame", "last_frame", "tags"}, "in a range"); !s) return s.error();
  const toml::node* first = table.get("first_frame");
  const toml::node* last = table.get("last_frame");
  const toml::node* tags = table.get("tags");
  if (!first || !last) {
    return in.error(range.line, fmt::format("a range needs both first_frame and last_frame (missing {})",
                                            first ? "last_frame" : "first_frame"));
  }
  auto f = in.frame(*first, "first_frame");
  if (!f) return f.error();
  auto l = in.frame(*last, "last_frame");
  if (!l) return l.error();
  if (*l < *f) {
    return in.error(line_of(*last), fmt::format("range last_frame {} comes before its first_frame {}", *l, *f));
  }
  range.first_frame = *f;
  range.last_frame = *l;
  if (clip.first_frame && range.first_frame < *clip.first_frame) {
    return in.error(line_of(*first), fmt::format("range first_frame {} is before the clip's first_frame {}",
                                                 range.first_frame, *clip.first_frame));
  }
  if (clip.last_frame && range.last_frame > *clip.last_frame) {
    return in.error(line_of(*last), fmt::format("range last_frame {} is after the clip's last_frame {}",
                                                range.last_frame, *clip.last_frame));
  }
  if (!tags) return in.error(range.line, "a range needs tags, e.g. tags = [\"walk\"]");
  auto names = in.tags(*tags);
  if (!names) return names.error();
  if (names->empty()) return in.error(line_of(*tags), "a range needs at least one tag");
  range.tags = std::move(*names);
  return range;
}

Result<ManifestClip> read_clip(const Reader& in, const toml::table& table) {
  ManifestClip clip;
  clip.line = line_of(table);
  if (auto s = in.check_keys(table, {"file", "name", "skeleton", "bvh_scale", "up_axis", "travel", "input_fps",
                                     "keep_rest_frames", "first_frame", "last_frame", "tags", "ranges", "animation"},
                             "in a [[clip]]");
      !s) {
    return s.error();
  }
  const toml::node* file = table.get("file");
  if (!file) return in.error(clip.line, "a [[clip]] needs a file, e.g. file = \"16_15.amc\"");
  auto path = in.string(*file, "file");
  if (!path) return path.error();
  clip.file = std::move(*path);
  clip.file_line = line_of(*file);
  const std::string ext = lower_extension(clip.file);
  if (!is_clip_file(clip.file)) {
    return in.error(clip.file_line, fmt::format("clip file \"{}\" is not .amc, .bvh, .glb, .gltf or .fbx", clip.file));
  }
  if (const toml::node* node = table.get("animation")) {
    if (!is_scene_file(clip.file)) return in.error(line_of(*node), "'animation' applies to glTF and FBX clips only");
    auto animation = in.string(*node, "animation");
    if (!animation) return animation.error();
    clip.animation_line = line_of(*node);
    clip.animation = std::move(*animation);
  }
  if (const toml::node* node = table.get("name")) {
    auto name = in.string(*node, "name");
    if (!name) return name.error();
    clip.name = std::move(*name);
  }
  if (const toml::node* node = table.get("skeleton")) {
    if (ext != ".amc") return in.error(line_of(*node), "'skeleton' applies to AMC clips only (a BVH holds its own)");
    auto skeleton = in.string(*node, "skeleton");
    if (!skeleton) return skeleton.error();
    clip.skeleton = std::move(*skeleton);
    clip.skeleton_line = line_of(*node);
  }
  if (const toml::node* node = table.get("bvh_scale"); node && ext != ".bvh") {
    return in.error(line_of(*node), "'bvh_scale' applies to BVH clips only (ASF gives its units)");
  }
  if (auto s = in.optional_scale(table.get("bvh_scale"), "bvh_scale", clip.bvh_scale); !s) return s.error();
  if (auto s = in.optional_boolean(table.get("keep_rest_frames"), "keep_rest_frames", clip.keep_rest_frames); !s) {
    return s.error();
  }
  if (auto s = in.optional_up_axis(table.get("up_axis"), clip.up_axis); !s) return s.error();
  if (auto s = in.optional_travel(table.get("travel"), clip.travel); !s) return s.error();
  if (auto s = in.optional_positive(table.get("input_fps"), "input_fps", clip.input_fps); !s) return s.error();
  if (const toml::node* node = table.get("first_frame")) {
    auto first = in.frame(*node, "first_frame");
    if (!first) return first.error();
    clip.first_frame = *first;
    clip.frames_line = line_of(*node);
  }
  if (const toml::node* node = table.get("last_frame")) {
    auto last = in.frame(*node, "last_frame");
    if (!last) return last.error();
    if (clip.first_frame && *last < *clip.first_frame) {
      return in.error(line_of(*node), fmt::format("last_frame {} comes before first_frame {}", *last,
                                                  *clip.first_frame));
    }
    clip.last_frame = *last;
    clip.frames_line = line_of(*node);
  }
  if (const toml::node* node = table.get("tags")) {
    auto tags = in.tags(*node);
    if (!tags) return tags.error();
    clip.tags = std::move(*tags);
  }
  if (const toml::node* node = table.get("ranges")) {
    auto array = node->as_array();
    if (!array || !array->is_array_of_tables()) {
      return in.error(line_of(*node), "'ranges' must be an array of tables, e.g. "
                                      "ranges = [{ first_frame = 1, last_frame = 120, tags = [\"walk\"] }]");
    }
    for (const toml::node& element : *array) {
      auto range = read_range(in, *element.as_table(), clip);
      if (!range) return range.error();
      clip.ranges.push_back(std::move(*range));
    }
  }
  return clip;
}

Result<FootJointNames> read_feet(const Reader& in, const toml::node& node) {
  auto table = node.as_table();
  if (!table) {
    return in.error(line_of(node), fmt::format("'feet' must be a table ([feet] with left_ankle = \"...\" ...), not {}",
                                               type_name(node)));
  }
  if (auto s = in.check_keys(*table, {"left_ankle", "left_toe", "right_ankle", "right_toe"}, "in [feet]"); !s) {
    return s.error();
  }
  FootJointNames names;
  const std::pair<const char*, std::string*> keys[] = {{"left_ankle", &names.left_ankle},
                                                       {"left_toe", &names.left_toe},
                                                       {"right_ankle", &names.right_ankle},
                                                       {"right_toe", &names.right_toe}};
  for (const auto& [key, name] : keys) {
    if (const toml::node* value = table->get(key)) {
      auto text = in.string(*value, key);
      if (!text) return text.error();
      *name = std::move(*text);
    }
  }
  if (auto s = names.validate(); !s) return in.error(line_of(node), s.error().message);
  return names;
}

Result<Manifest> read_manifest(const Reader& in, const toml::table& root, std::string file_name) {
  Manifest manifest;
  manifest.file_name = std::move(file_name);
  if (auto s = in.check_keys(root,
                             {"fps", "skeleton", "bvh_scale", "up_axis", "travel", "input_fps", "keep_rest_frames",
                              "feet", "clip"},
                             "at the top level");
      !s) {
    return s.error();
  }
  if (const toml::node* node = root.get("feet")) {
    auto feet = read_feet(in, *node);
    if (!feet) return feet.error();
    manifest.feet = std::move(*feet);
    manifest.feet_line = line_of(*node);
  }
  if (auto s = in.optional_positive(root.get("fps"), "fps", manifest.fps); !s) return s.error();
  if (manifest.fps && !(*manifest.fps >= 1.0 && *manifest.fps <= 1000.0)) {  // build --fps's range
    return in.error(line_of(*root.get("fps")), fmt::format("'fps' must be 1 to 1000, not {:g}", *manifest.fps));
  }
  if (const toml::node* node = root.get("fps")) manifest.fps_line = line_of(*node);
  if (const toml::node* node = root.get("skeleton")) {
    auto skeleton = in.string(*node, "skeleton");
    if (!skeleton) return skeleton.error();
    manifest.skeleton = std::move(*skeleton);
    manifest.skeleton_line = line_of(*node);
  }
  if (auto s = in.optional_scale(root.get("bvh_scale"), "bvh_scale", manifest.bvh_scale); !s) return s.error();
  if (auto s = in.optional_boolean(root.get("keep_rest_frames"), "keep_rest_frames", manifest.keep_rest_frames); !s) {
    return s.error();
  }
  if (auto s = in.optional_up_axis(root.get("up_axis"), manifest.up_axis); !s) return s.error();
  if (auto s = in.optional_travel(root.get("travel"), manifest.travel); !s) return s.error();
  if (auto s = in.optional_positive(root.get("input_fps"), "input_fps", manifest.input_fps); !s) return s.error();
  const toml::node* clips = root.get("clip");
  if (!clips) return in.error(0, "the manifest names no clips: add a [[clip]] table with file = \"...\"");
  auto array = clips->as_array();
  if (!array || !array->is_array_of_tables()) {
    return in.error(line_of(*clips), "'clip' must be an array of tables: write each clip as [[clip]]");
  }
  for (const toml::node& element : *array) {
    auto clip = read_clip(in, *element.as_table());
    if (!clip) return clip.error();
    manifest.clips.push_back(std::move(*clip));
  }
  return manifest;
}

}  // namespace

bool is_valid_tag_name(std::string_view name) {
  if (name.empty()) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '_' || c == '-';
  });
}

Result<Manifest> parse_manifest(std::string_view toml_text, std::string file_name) {
  Reader in(file_name);
#if TOML_EXCEPTIONS
  toml::table root;
  try {
    root = toml::parse(toml_text, file_name);
  } catch (const toml::parse_error& e) {
    return in.error(static_cast<int>(e.source().begin.line), fmt::format("TOML: {}", e.description()));
  }
#else
  toml::parse_result parsed = toml::parse(toml_text, file_name);
  if (!parsed) {
    const toml::parse_error& e = parsed.error();
    return in.error(static_cast<int>(e.source().begin.line), fmt::format("TOML: {}", e.description()));
  }
  const toml::table& root = parsed.table();
#endif
  return read_manifest(in, root, std::move(file_name));
}

}  // namespace mg
