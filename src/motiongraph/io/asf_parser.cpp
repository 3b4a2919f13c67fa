#include "motiongraph/io/asf_parser.h"

#include <cctype>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "motiongraph/core/text.h"

namespace mg {

const char* acclaim_dof_name(AcclaimDof dof) {
  switch (dof) {
    case AcclaimDof::kRx: return "rx";
    case AcclaimDof::kRy: return "ry";
    case AcclaimDof::kRz: return "rz";
    case AcclaimDof::kTx: return "tx";
    case AcclaimDof::kTy: return "ty";
    case AcclaimDof::kTz: return "tz";
    case AcclaimDof::kLength: return "l";
  }
  return "?";
}

namespace {

bool is_section(const std::vector<std::string_view>& tokens) {
  return !tokens.empty() && tokens[0].front() == ':';
}

bool is_comment(const std::vector<std::string_view>& tokens) {
  return !tokens.empty() && tokens[0].front() == '#';
}

class AsfParser {
 public:
  AsfParser(std::string_view text, std::string file_name) : in_(text, std::move(file_name)) {}

  Result<AsfDocument> run() {
    doc_.file_name = in_.file_name();
    bool has_units = false;
    bool has_bonedata = false;
    bool has_hierarchy = false;
    while (true) {
      auto tokens = next();
      if (tokens.empty()) break;
      if (!is_section(tokens)) {
        return in_.error(fmt::format("expected a section such as ':bonedata', found {}",
                                     quoted(tokens[0])));
      }
      const std::string key = ascii_lower(tokens[0]);
      Status status = Ok{};
      if (key == ":units") {
        if (has_units) return in_.error("':units' appears twice");
        has_units = true;
        status = units();
      } else if (key == ":root") {
        if (doc_.has_root) return in_.error("':root' appears twice");
        doc_.has_root = true;
        doc_.root.line = in_.line_number();
        status = root();
      } else if (key == ":bonedata") {
        if (has_bonedata) return in_.error("':bonedata' appears twice");
        has_bonedata = true;
        status = bonedata();
      } else if (key == ":hierarchy") {
        if (has_hierarchy) return in_.error("':hierarchy' appears twice");
        has_hierarchy = true;
        status = hierarchy();
      } else {
        skip_section();  // :version, :name, :documentation and sections we do not use
      }
      if (!status.ok()) return status.error();
    }
    if (!doc_.has_root) return Error{doc_.file_name, 0, "no ':root' section"};
    return std::move(doc_);
  }

 private:
  // Next non-blank, non-comment line's tokens.
  std::vector<std::string_view> next() {
    while (true) {
      auto tokens = in_.next_tokens();
      if (!is_comment(tokens)) return tokens;
    }
  }
  std::vector<std::string_view> peek() {
    LineReader copy = in_;
    while (true) {
      auto tokens = copy.next_tokens();
      if (!is_comment(tokens)) return tokens;
    }
  }
  bool section_ends() {
    auto tokens = peek();
    return tokens.empty() || is_section(tokens);
  }
  void skip_section() {
    while (!section_ends()) next();
  }

  Result<double> number(std::string_view token, const char* what) {
    auto value = parse_finite(token);
    if (!value) return in_.error(fmt::format("{}: {} is not a finite number", what, quoted(token)));
    return *value;
  }

  // Expects exactly `count` numbers after the keyword.
  Result<Vec3> vec3(const std::vector<std::string_view>& tokens, size_t first, const char* what) {
    if (tokens.size() < first + 3) return in_.error(fmt::format("{} needs 3 numbers", what));
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      auto value = number(tokens[first + i], what);
      if (!value) return value.error();
      v[i] = *value;
    }
    return v;
  }

  Status expect_count(const std::vector<std::string_view>& tokens, size_t count, const char* what) {
    if (tokens.size() != count) {
      return in_.error(fmt::format("'{}' takes {} value{}, found {}", what, count - 1,
                                   count == 2 ? "" : "s", tokens.size() - 1));
    }
    return Ok{};
  }

  Result<std::array<Axis, 3>> axis_order(std::string_view token) {
    auto order = parse_axis_string(token);
    if (!order) {
      return in_.error(fmt::format("axis order {} is not a permutation of XYZ", quoted(token)));
    }
    return *order;
  }

  Result<AcclaimDof> dof(std::string_view token) {
    const std::string t = ascii_lower(token);
    if (t == "rx") return AcclaimDof::kRx;
    if (t == "ry") return AcclaimDof::kRy;
    if (t == "rz") return AcclaimDof::kRz;
    if (t == "tx") return AcclaimDof::kTx;
    if (t == "ty") return AcclaimDof::kTy;
    if (t == "tz") return AcclaimDof::kTz;
    if (t == "l") return AcclaimDof::kLength;
    return in_.error(fmt::format("unknown degree of freedom {} (expected rx ry rz tx ty tz l)",
                                 quoted(token)));
  }

  Result<std::vector<AcclaimDof>> dof_list(const std::vector<std::string_view>& tokens) {
    std::vector<AcclaimDof> dofs;
    for (size_t i = 1; i < tokens.size(); ++i) {
      auto d = dof(tokens[i]);
      if (!d) return d.error();
      for (AcclaimDof seen : dofs) {
        if (seen == *d) return in_.error(fmt::format("{} is listed twice", quoted(tokens[i])));
      }
      dofs.push_back(*d);
    }
    return dofs;
  }

  Status units() {
    while (!section_ends()) {
      auto tokens = next();
      const std::string key = ascii_lower(tokens[0]);
      if (key == "mass" || key == "length") {
        if (auto s = expect_count(tokens, 2, key.c_str()); !s) return s;
        auto value = number(tokens[1], key.c_str());
        if (!value) return value.error();
        if (*value <= 0.0) return in_.error(fmt::format("{} must be positive", key));
        (key == "mass" ? doc_.mass : doc_.length) = *value;
      } else if (key == "angle") {
        if (auto s = expect_count(tokens, 2, "angle"); !s) return s;
        const std::string unit = ascii_lower(tokens[1]);
        if (unit == "deg" || unit == "degrees") {
          doc_.angles_in_degrees = true;
        } else if (unit == "rad" || unit == "radians") {
          doc_.angles_in_degrees = false;
        } else {
          return in_.error(fmt::format("angle unit {} is neither deg nor rad", quoted(tokens[1])));
        }
      } else {
        return in_.error(fmt::format("unknown unit {} in ':units'", quoted(tokens[0])));
      }
    }
    return Ok{};
  }

  Status root() {
    bool has_order = false;
    while (!section_ends()) {
      auto tokens = next();
      const std::string key = ascii_lower(tokens[0]);
      if (key == "order") {
        auto dofs = dof_list(tokens);
        if (!dofs) return dofs.error();
        for (AcclaimDof d : *dofs) {
          if (d == AcclaimDof::kLength) return in_.error("the root cannot have an 'l' channel");
        }
        doc_.root.order = std::move(*dofs);
        has_order = true;
      } else if (key == "axis") {
        if (auto s = expect_count(tokens, 2, "axis"); !s) return s;
        auto order = axis_order(tokens[1]);
        if (!order) return order.error();
        doc_.root.axis_order = *order;
      } else if (key == "position" || key == "orientation") {
        if (auto s = expect_count(tokens, 4, key.c_str()); !s) return s;
        auto v = vec3(tokens, 1, key.c_str());
        if (!v) return v.error();
        (key == "position" ? doc_.root.position : doc_.root.orientation) = *v;
      } else {
        return in_.error(fmt::format("unknown ':root' field {}", quoted(tokens[0])));
      }
    }
    if (!has_order) return in_.error_at(doc_.root.line, "':root' has no 'order' line");
    return Ok{};
  }

  Status bonedata() {
    while (!section_ends()) {
      auto tokens = next();
      if (ascii_lower(tokens[0]) != "begin" || tokens.size() != 1) {
        return in_.error(fmt::format("expected 'begin' of a bone, found {}", quoted(tokens[0])));
      }
      AsfBone bone;
      bone.line = in_.line_number();
      if (auto s = bone_body(bone); !s) return s;
      doc_.bones.push_back(std::move(bone));
    }
    return Ok{};
  }

  Status bone_body(AsfBone& bone) {
    bool has_name = false;
    bool has_id = false;
    bool has_limits = false;
    while (true) {
      if (section_ends()) return in_.error_at(bone.line, "bone has no 'end'");
      auto tokens = next();
      const std::string key = ascii_lower(tokens[0]);
      if (key == "end") {
        if (tokens.size() != 1) return in_.error("'end' takes no value");
        break;
      }
      if (key == "id") {
        if (auto s = expect_count(tokens, 2, "id"); !s) return s;
        auto id = parse_integer(tokens[1]);
        if (!id || *id < 0 || *id > std::numeric_limits<int>::max()) {
          return in_.error(fmt::format("bone id {} is not a non-negative integer", quoted(tokens[1])));
        }
        bone.id = static_cast<int>(*id);
        has_id = true;
      } else if (key == "name") {
        if (auto s = expect_count(tokens, 2, "name"); !s) return s;
        bone.name = std::string(tokens[1]);
        has_name = true;
      } else if (key == "direction") {
        if (auto s = expect_count(tokens, 4, "direction"); !s) return s;
        auto v = vec3(tokens, 1, "direction");
        if (!v) return v.error();
        bone.direction = *v;
        bone.has_direction = true;
      } else if (key == "length") {
        if (auto s = expect_count(tokens, 2, "length"); !s) return s;
        auto value = number(tokens[1], "length");
        if (!value) return value.error();
        if (*value < 0.0) return in_.error("bone length is negative");
        bone.length = *value;
        bone.has_length = true;
      } else if (key == "axis") {
        if (auto s = expect_count(tokens, 5, "axis"); !s) return s;
        auto v = vec3(tokens, 1, "axis");
        if (!v) return v.error();
        auto order = axis_order(tokens[4]);
        if (!order) return order.error();
        bone.axis = *v;
        bone.axis_order = *order;
      } else if (key == "dof") {
        auto dofs = dof_list(tokens);
        if (!dofs) return dofs.error();
        bone.dofs = std::move(*dofs);
      } else if (key == "limits") {
        if (has_limits) return in_.error("'limits' appears twice in a bone");
        has_limits = true;
        if (auto s = limits(tokens, bone); !s) return s;
      } else if (key == "bodymass" || key == "cofmass") {
        // Optional Acclaim fields we do not use.
      } else {
        return in_.error(fmt::format("unknown bone field {}", quoted(tokens[0])));
      }
    }
    if (!has_name) return in_.error_at(bone.line, "bone has no 'name'");
    if (!has_id) bone.id = static_cast<int>(doc_.bones.size()) + 1;
    if (!bone.has_direction) return in_.error_at(bone.line, fmt::format("bone '{}' has no 'direction'", bone.name));
    if (!bone.has_length) return in_.error_at(bone.line, fmt::format("bone '{}' has no 'length'", bone.name));
    if (has_limits && bone.limits.size() != bone.dofs.size()) {
      return in_.error_at(bone.line, fmt::format("bone '{}' has {} limits for {} dofs", bone.name,
                                                 bone.limits.size(), bone.dofs.size()));
    }
    return Ok{};
  }

  // "limits (-160.0 20.0)" followed by lines "(-70.0 70.0)"; parentheses may touch the numbers
  // or stand alone; "inf" and "-inf" mean unlimited. Errors name the line of the bad pair.
  Status limits(const std::vector<std::string_view>& first_line, AsfBone& bone) {
    std::vector<std::pair<std::string, int>> numbers;  // token, line
    auto collect = [&](const std::vector<std::string_view>& tokens, size_t from) {
      std::string flat;
      for (size_t i = from; i < tokens.size(); ++i) (flat += tokens[i]) += ' ';
      for (char& c : flat) {
        if (c == '(' || c == ')') c = ' ';
      }
      for (auto t : split_tokens(flat)) numbers.emplace_back(ascii_lower(t), in_.line_number());
    };
    collect(first_line, 1);
    while (true) {
      auto ahead = peek();
      if (ahead.empty() || ahead[0].front() != '(') break;
      collect(next(), 0);
    }
    if (numbers.size() % 2 != 0) return in_.error("limits need pairs (min max)");
    for (size_t i = 0; i < numbers.size(); i += 2) {
      double pair[2];
      const int line = numbers[i + 1].second;
      for (int k = 0; k < 2; ++k) {
        const std::string& t = numbers[i + k].first;
        if (t == "inf" || t == "+inf") {
          pair[k] = std::numeric_limits<double>::infinity();
        } else if (t == "-inf") {
          pair[k] = -std::numeric_limits<double>::infinity();
        } else if (auto value = parse_finite(t)) {
          pair[k] = *value;
        } else {
          return in_.error_at(line, fmt::format("limit: {} is not a number", quoted(t)));
        }
      }
      if (pair[0] > pair[1]) return in_.error_at(line, "a limit has min > max");
      bone.limits.emplace_back(pair[0], pair[1]);
    }
    return Ok{};
  }

  Status hierarchy() {
    auto tokens = next();
    if (tokens.empty() || ascii_lower(tokens[0]) != "begin") {
      return in_.error("':hierarchy' must start with 'begin'");
    }
    while (true) {
      tokens = next();
      if (tokens.empty() || is_section(tokens)) {
        return in_.error("':hierarchy' has no 'end'");
      }
      if (ascii_lower(tokens[0]) == "end" && tokens.size() == 1) break;
      if (tokens.size() < 2) {
        return in_.error(fmt::format("hierarchy line for {} names no children", quoted(tokens[0])));
      }
      AsfHierarchyLine line;
      line.line = in_.line_number();
      line.parent = std::string(tokens[0]);
      for (size_t i = 1; i < tokens.size(); ++i) line.children.emplace_back(tokens[i]);
      doc_.hierarchy.push_back(std::move(line));
    }
    return Ok{};
  }

  LineReader in_;
  AsfDocument doc_;
};

}  // namespace

Result<AsfDocument> parse_asf(std::string_view text, std::string file_name) {
  return AsfParser(text, std::move(file_name)).run();
}

}  // namespace mg
