#include "motiongraph/io/amc_parser.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include "motiongraph/core/text.h"

namespace mg {

int AmcLayout::values_per_frame() const {
  int total = 0;
  for (int count : dof_counts) total += count;
  return total;
}

namespace {

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::toupper(static_cast<unsigned char>(a[i])) != std::toupper(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

}  // namespace

Result<AmcDocument> parse_amc(std::string_view text, std::string file_name,
                              const AmcLayout& layout, bool default_degrees) {
  LineReader in(text, std::move(file_name));
  AmcDocument doc;
  doc.file_name = in.file_name();
  doc.angles_in_degrees = default_degrees;
  doc.values_per_frame = layout.values_per_frame();

  std::unordered_map<std::string_view, int> bone_index;
  std::vector<int> first_value;
  int required = 0;
  for (size_t b = 0; b < layout.bone_names.size(); ++b) {
    bone_index.emplace(layout.bone_names[b], static_cast<int>(b));
    first_value.push_back(b == 0 ? 0 : first_value[b - 1] + layout.dof_counts[b - 1]);
    if (layout.dof_counts[b] > 0) ++required;
  }

  std::vector<char> seen(layout.bone_names.size(), 0);
  int seen_count = 0;
  int frame_line = 0;
  long long frame_number = 0;
  bool in_header = true;
  double* frame_values = nullptr;

  auto finish_frame = [&]() -> Status {
    if (frame_line == 0 || seen_count == required) return Ok{};
    for (size_t b = 0; b < seen.size(); ++b) {
      if (!seen[b] && layout.dof_counts[b] > 0) {
        return in.error_at(frame_line, fmt::format("frame {} has no line for bone '{}'",
                                                   frame_number, layout.bone_names[b]));
      }
    }
    return Ok{};
  };

  while (auto line = in.next()) {
    auto tokens = split_tokens(*line);
    if (tokens.empty() || tokens[0].front() == '#') continue;
    if (in_header && tokens[0].front() == ':') {
      if (tokens.size() != 1) return in.error(fmt::format("unexpected text after {}", quoted(tokens[0])));
      if (iequals(tokens[0], ":FULLY-SPECIFIED")) continue;
      if (iequals(tokens[0], ":DEGREES")) { doc.angles_in_degrees = true; continue; }
      if (iequals(tokens[0], ":RADIANS")) { doc.angles_in_degrees = false; continue; }
      return in.error(fmt::format("unknown header {}", quoted(tokens[0])));
    }
    if (auto number = tokens.size() == 1 ? parse_integer(tokens[0]) : std::nullopt) {
      if (auto s = finish_frame(); !s) return s.error();
      if (in_header) {
        doc.first_frame_number = *number;
      } else if (frame_number == std::numeric_limits<long long>::max() || *number != frame_number + 1) {
        return in.error(fmt::format("frame {} follows frame {}; frame numbers must be consecutive",
                                    *number, frame_number));
      }
      in_header = false;
      frame_number = *number;
      frame_line = in.line_number();
      if (doc.frame_count == std::numeric_limits<int>::max()) return in.error("too many frames");
      ++doc.frame_count;
      doc.values.resize(doc.values.size() + doc.values_per_frame, 0.0);
      frame_values = doc.values.data() + doc.values.size() - doc.values_per_frame;
      std::fill(seen.begin(), seen.end(), 0);
      seen_count = 0;
      continue;
    }
    if (tokens.size() == 1 && tokens[0].find_first_not_of("+-0123456789") == std::string_view::npos) {
      return in.error(fmt::format("frame number {} is out of range", quoted(tokens[0])));
    }
    if (in_header) {
      return in.error(fmt::format("expected a frame number before bone line {}", quoted(tokens[0])));
    }
    auto it = bone_index.find(tokens[0]);
    if (it == bone_index.end()) {
      return in.error(fmt::format("unknown bone {} (not in the skeleton)", quoted(tokens[0])));
    }
    const int b = it->second;
    if (seen[b]) {
      return in.error(fmt::format("bone '{}' appears twice in frame {}", tokens[0], frame_number));
    }
    const int count = layout.dof_counts[b];
    if (static_cast<int>(tokens.size()) - 1 != count) {
      return in.error(fmt::format("bone '{}' has {} value{}, its skeleton gives it {}", tokens[0],
                                  tokens.size() - 1, tokens.size() == 2 ? "" : "s", count));
    }
    for (int k = 0; k < count; ++k) {
      auto value = parse_finite(tokens[1 + k]);
      if (!value) {
        return in.error(fmt::format("value {} of bone '{}' is not a finite number",
                                    quoted(tokens[1 + k]), tokens[0]));
      }
      frame_values[first_value[b] + k] = *value;
    }
    seen[b] = 1;
    if (count > 0) ++seen_count;
  }
  if (auto s = finish_frame(); !s) return s.error();
  if (doc.frame_count == 0) return Error{doc.file_name, 0, "no frames"};
  return doc;
}

}  // namespace mg
