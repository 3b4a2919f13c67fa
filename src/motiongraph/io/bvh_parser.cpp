#include "motiongraph/io/bvh_parser.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <unordered_set>

#include <fmt/format.h>

#include "motiongraph/core/text.h"

namespace mg {

const char* bvh_channel_name(BvhChannel channel) {
  static const char* kNames[] = {"Xposition", "Yposition", "Zposition",
                                 "Xrotation", "Yrotation", "Zrotation"};
  return kNames[static_cast<int>(channel)];
}

bool is_rotation(BvhChannel channel) { return static_cast<int>(channel) >= 3; }

Axis channel_axis(BvhChannel channel) { return static_cast<Axis>(static_cast<int>(channel) % 3); }

namespace {

// A keyword as written in any case ("End site", "zrotation": some exporters write them so, and
// Blender reads them).
bool is_keyword(std::string_view token, std::string_view keyword) {
  return token.size() == keyword.size() && std::equal(token.begin(), token.end(), keyword.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
         });
}

// Deeper nesting than any real skeleton; bounds the parser's recursion.
constexpr int kMaxDepth = 1000;

class BvhParser {
 public:
  BvhParser(std::string_view text, std::string file_name) : in_(text, std::move(file_name)) {}

  Result<BvhDocument> run() {
    doc_.file_name = in_.file_name();
    auto first = next();
    if (first.empty() || !is_keyword(first[0], "HIERARCHY")) {
      return in_.error(first.empty() ? "empty file: expected 'HIERARCHY'"
                                     : fmt::format("expected 'HIERARCHY', found {}", quoted(first[0])));
    }
    if (first.size() != 1) return in_.error(fmt::format("unexpected {} after 'HIERARCHY'", quoted(first[1])));
    auto root = next();
    if (root.empty() || !is_keyword(root[0], "ROOT")) {
      return in_.error(root.empty() ? "no 'ROOT' joint" : fmt::format("expected 'ROOT', found {}", quoted(root[0])));
    }
    if (auto s = joint(-1, 0); !s) return s.error();
    for (auto& j : doc_.joints) {
      if (j.end_site) j.name = unique_name(doc_.joints[j.parent].name + "_end");
    }
    auto extra = next();
    if (extra.empty()) return in_.error("no 'MOTION' section");
    if (is_keyword(extra[0], "ROOT")) return in_.error("a second 'ROOT' (only one skeleton per file is supported)");
    if (!is_keyword(extra[0], "MOTION") || extra.size() != 1) {
      return in_.error(fmt::format("expected 'MOTION', found {}", quoted(extra[0])));
    }
    if (auto s = motion(); !s) return s.error();
    return std::move(doc_);
  }

 private:
  // Tokens of the next line; a line "JOINT name {" keeps its brace as the last token.
  std::vector<std::string_view> next() { return tokens_ = in_.next_tokens(); }

  // Parses a joint whose ROOT/JOINT/End line has just been read into tokens_.
  Status joint(int parent, int depth) {
    if (depth > kMaxDepth) return in_.error("joints nested too deeply");
    BvhJoint j;
    j.line = in_.line_number();
    j.parent = parent;
    const bool is_end = is_keyword(tokens_[0], "End");
    bool brace_on_line = tokens_.size() > 1 && tokens_.back() == "{";
    const size_t name_end = tokens_.size() - (brace_on_line ? 1 : 0);
    if (is_end) {
      if (name_end != 2 || !is_keyword(tokens_[1], "Site")) return in_.error("expected 'End Site'");
      j.end_site = true;  // named once all joint names are known
    } else {
      if (name_end < 2) return in_.error(fmt::format("{} has no name", tokens_[0]));
      // Names with spaces are kept whole.
      const char* begin = tokens_[1].data();
      const char* end = tokens_[name_end - 1].data() + tokens_[name_end - 1].size();
      j.name = std::string(begin, end);
      if (!names_.insert(j.name).second) {
        return in_.error(fmt::format("joint name {} is used twice", quoted(j.name)));
      }
    }
    if (!brace_on_line) {
      auto open = next();
      if (open.empty() || open[0] != "{" || open.size() != 1) {
        return in_.error(is_end ? std::string("expected '{' after End Site")
                                : fmt::format("expected '{{' after joint {}", quoted(j.name)));
      }
    }
    const int index = static_cast<int>(doc_.joints.size());
    doc_.joints.push_back(j);
    bool has_offset = false;
    bool has_channels = false;
    while (true) {
      auto tokens = next();
      if (tokens.empty()) return in_.error_at(j.line, "joint has no closing '}'");
      const auto key = tokens[0];
      if (key == "}") {
        if (tokens.size() != 1) return in_.error(fmt::format("unexpected {} after '}}'", quoted(tokens[1])));
        break;
      }
      if (is_keyword(key, "OFFSET")) {
        if (has_offset) return in_.error("OFFSET given twice");
        if (tokens.size() != 4) return in_.error(fmt::format("OFFSET needs 3 numbers, found {}", tokens.size() - 1));
        for (int i = 0; i < 3; ++i) {
          auto v = parse_finite(tokens[1 + i]);
          if (!v) return in_.error(fmt::format("OFFSET value {} is not a finite number", quoted(tokens[1 + i])));
          doc_.joints[index].offset[i] = *v;
        }
        has_offset = true;
      } else if (is_keyword(key, "CHANNELS")) {
        if (is_end) return in_.error("an End Site has no CHANNELS");
        if (has_channels) return in_.error("CHANNELS given twice");
        if (auto s = channels(tokens, doc_.joints[index]); !s) return s;
        has_channels = true;
      } else if (is_keyword(key, "JOINT") || is_keyword(key, "End")) {
        if (is_end) return in_.error("an End Site has no children");
        if (auto s = joint(index, depth + 1); !s) return s;
      } else if (is_keyword(key, "MOTION") || is_keyword(key, "ROOT")) {
        return in_.error(fmt::format("'{}' inside a joint: a '}}' is missing", key));
      } else {
        return in_.error(fmt::format("unexpected {} in a joint", quoted(key)));
      }
    }
    if (!has_offset) return in_.error_at(j.line, "joint has no OFFSET");
    return Ok{};
  }

  Status channels(const std::vector<std::string_view>& tokens, BvhJoint& j) {
    if (tokens.size() < 2) return in_.error("CHANNELS needs a count");
    auto count = parse_integer(tokens[1]);
    if (!count || *count < 0 || *count > 6) {
      return in_.error(fmt::format("channel count {} is not 0 to 6", quoted(tokens[1])));
    }
    if (static_cast<long long>(tokens.size()) - 2 != *count) {
      return in_.error(fmt::format("CHANNELS says {} but lists {}", *count, tokens.size() - 2));
    }
    j.first_channel = doc_.channel_count;
    for (size_t i = 2; i < tokens.size(); ++i) {
      int found = -1;
      for (int c = 0; c < 6; ++c) {
        if (is_keyword(tokens[i], bvh_channel_name(static_cast<BvhChannel>(c)))) found = c;
      }
      if (found < 0) return in_.error(fmt::format("unknown channel {}", quoted(tokens[i])));
      const auto channel = static_cast<BvhChannel>(found);
      if (std::find(j.channels.begin(), j.channels.end(), channel) != j.channels.end()) {
        return in_.error(fmt::format("channel {} listed twice", quoted(tokens[i])));
      }
      j.channels.push_back(channel);
    }
    doc_.channel_count += static_cast<int>(*count);
    return Ok{};
  }

  Status motion() {
    auto frames = next();
    if (frames.size() != 2 || !is_keyword(frames[0], "Frames:")) {
      return in_.error("expected 'Frames: N'");
    }
    auto count = parse_integer(frames[1]);
    if (!count || *count < 0) return in_.error(fmt::format("frame count {} is not a whole number >= 0", quoted(frames[1])));
    const int frames_line = in_.line_number();
    auto time = next();
    if (time.size() != 3 || !is_keyword(time[0], "Frame") || !is_keyword(time[1], "Time:")) {
      return in_.error("expected 'Frame Time: seconds'");
    }
    auto frame_time = parse_finite(time[2]);
    if (!frame_time || *frame_time <= 0.0) {
      return in_.error(fmt::format("Frame Time {} must be a positive number", quoted(time[2])));
    }
    doc_.frame_time_s = *frame_time;
    doc_.frame_time_line = in_.line_number();
    const size_t per_frame = static_cast<size_t>(doc_.channel_count);
    long long lines = 0;
    while (auto line = in_.next()) {
      auto tokens = split_tokens(*line);
      if (tokens.empty()) continue;
      if (lines == *count) {
        return in_.error(fmt::format("more motion lines than 'Frames: {}' (line {})", *count, frames_line));
      }
      if (tokens.size() != per_frame) {
        return in_.error(fmt::format("motion line has {} values, the hierarchy declares {} channels",
                                     tokens.size(), per_frame));
      }
      for (auto token : tokens) {
        auto v = parse_finite(token);
        if (!v) return in_.error(fmt::format("value {} is not a finite number", quoted(token)));
        doc_.values.push_back(*v);
      }
      ++lines;
    }
    if (lines != *count) {
      return in_.error_at(frames_line, fmt::format("'Frames: {}' but {} motion line{} follow{}", *count, lines,
                                                   lines == 1 ? "" : "s", lines == 1 ? "s" : ""));
    }
    if (lines > std::numeric_limits<int>::max()) return in_.error_at(frames_line, "too many frames");
    doc_.frame_count = static_cast<int>(lines);
    return Ok{};
  }

  std::string unique_name(std::string name) {
    std::string candidate = name;
    for (int n = 2; !names_.insert(candidate).second; ++n) candidate = name + std::to_string(n);
    return candidate;
  }

  LineReader in_;
  BvhDocument doc_;
  std::vector<std::string_view> tokens_;
  std::unordered_set<std::string> names_;
};

}  // namespace

Result<BvhDocument> parse_bvh(std::string_view text, std::string file_name) {
  return BvhParser(text, std::move(file_name)).run();
}

}  // namespace mg
