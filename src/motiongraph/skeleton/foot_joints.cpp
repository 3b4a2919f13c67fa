// The feet of a skeleton, by name: folded names, side and part words, toes below ankles.
#include "motiongraph/skeleton/foot_joints.h"

#include <array>
#include <cctype>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "motiongraph/core/text.h"

namespace mg {

namespace {

constexpr std::array<std::string_view, 4> kRigPrefixes = {"mixamorig", "bip", "character", "def"};
constexpr std::array<std::string_view, 5> kToeWords = {"toebase", "toes", "toe", "toe0", "ball"};

struct Side {
  const char* label;  // for messages
  std::array<std::string_view, 2> words;
};
constexpr Side kLeft{"left", {"left", "l"}};
constexpr Side kRight{"right", {"right", "r"}};

// side + part or part + side, for every side word.
bool is_named(std::string_view folded, const Side& side, std::string_view part) {
  for (std::string_view word : side.words) {
    if (folded.size() != word.size() + part.size()) continue;
    if (folded.starts_with(word) && folded.ends_with(part)) return true;
    if (folded.starts_with(part) && folded.ends_with(word)) return true;
  }
  return false;
}

// The first joint (in joint order) whose folded name is side + part.
std::optional<int> find_named(const Skeleton& skeleton, const Side& side, std::string_view part) {
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    if (is_named(folded_joint_name(skeleton.joint(j).name), side, part)) return j;
  }
  return std::nullopt;
}

// Steps from `ancestor` down to `joint`; nullopt when `joint` is not below it.
std::optional<int> depth_below(const Skeleton& skeleton, int ancestor, int joint) {
  int steps = 0;
  for (int j = joint; j >= 0; j = skeleton.parent(j), ++steps) {
    if (j == ancestor) return steps;
  }
  return std::nullopt;
}

// The nearest joint below `ankle` with a toe name; else its only child; else -1.
int find_toe(const Skeleton& skeleton, int ankle, const Side& side) {
  int best = -1, best_depth = 0;
  for (int j = ankle + 1; j < skeleton.joint_count(); ++j) {
    const std::string folded = folded_joint_name(skeleton.joint(j).name);
    bool toe_named = false;
    for (std::string_view word : kToeWords) toe_named = toe_named || is_named(folded, side, word);
    if (!toe_named) continue;
    const auto depth = depth_below(skeleton, ankle, j);
    if (depth && (best < 0 || *depth < best_depth)) best = j, best_depth = *depth;
  }
  if (best >= 0) return best;
  int only_child = -1, children = 0;
  for (int j = ankle + 1; j < skeleton.joint_count(); ++j) {
    if (skeleton.parent(j) == ankle) only_child = j, ++children;
  }
  return children == 1 ? only_child : -1;
}

std::string looked_for(const Side& side) {
  std::vector<std::string> names;
  for (std::string_view part : {"ankle", "foot"}) {
    for (std::string_view word : side.words) {
      names.push_back(fmt::format("{}{}", word, part));
      names.push_back(fmt::format("{}{}", part, word));
    }
  }
  return fmt::format("{}", fmt::join(names, ", "));
}

Result<int> joint_named(const Skeleton& skeleton, const std::string& name, std::string_view role) {
  const std::string wanted = ascii_lower(name);
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    if (ascii_lower(skeleton.joint(j).name) == wanted) return j;
  }
  return Error{"", 0, fmt::format("the skeleton has no joint named '{}' (given as the {})", name, role)};
}

Result<Foot> find_foot(const Skeleton& skeleton, const Side& side, const std::string& ankle_name,
                       const std::string& toe_name) {
  Foot foot;
  if (!ankle_name.empty()) {
    auto ankle = joint_named(skeleton, ankle_name, fmt::format("{} ankle", side.label));
    if (!ankle) return ankle.error();
    foot.ankle = *ankle;
  } else {
    auto ankle = find_named(skeleton, side, "ankle");
    if (!ankle) ankle = find_named(skeleton, side, "foot");
    if (!ankle) {
      return Error{"", 0,
                   fmt::format("no {} ankle joint found: looked for a joint named {} (ignoring case, namespaces, "
                               "'_', ' ', '-', '.' and rig prefixes such as mixamorig or Bip01); name it explicitly",
                               side.label, looked_for(side))};
    }
    foot.ankle = *ankle;
  }
  if (toe_name.empty()) {
    foot.toe = find_toe(skeleton, foot.ankle, side);
    return foot;
  }
  auto toe = joint_named(skeleton, toe_name, fmt::format("{} toe", side.label));
  if (!toe) return toe.error();
  if (*toe == foot.ankle || !depth_below(skeleton, foot.ankle, *toe)) {
    return Error{"", 0, fmt::format("the {} toe '{}' is not below the {} ankle '{}'", side.label, toe_name, side.label,
                                    skeleton.joint(foot.ankle).name)};
  }
  foot.toe = *toe;
  return foot;
}

}  // namespace

std::string folded_joint_name(std::string_view name) {
  const size_t namespace_end = name.find_last_of(":|");
  if (namespace_end != std::string_view::npos) name.remove_prefix(namespace_end + 1);
  std::string folded;
  for (char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '_' || c == ' ' || c == '-' || c == '.') continue;
    folded += static_cast<char>(std::tolower(byte));
  }
  for (std::string_view prefix : kRigPrefixes) {
    if (!std::string_view(folded).starts_with(prefix)) continue;
    size_t end = prefix.size();
    while (end < folded.size() && std::isdigit(static_cast<unsigned char>(folded[end]))) ++end;
    if (end < folded.size()) folded.erase(0, end);
    break;
  }
  return folded;
}

Result<FootJointNames> parse_foot_joint_names(std::string_view text) {
  std::vector<std::string> parts(1);
  for (const char c : text) {
    if (c == ',') {
      parts.emplace_back();
    } else {
      parts.back() += c;
    }
  }
  if (parts.size() != 4) {
    return Error{"", 0, fmt::format("'{}' is not four comma-separated joint names: left ankle, left toe, right ankle, "
                                    "right toe (leave one empty to find it, e.g. 'LeftFoot,,RightFoot,')",
                                    text)};
  }
  for (std::string& part : parts) {
    const size_t first = part.find_first_not_of(' ');
    const size_t last = part.find_last_not_of(' ');
    part = first == std::string::npos ? std::string() : part.substr(first, last - first + 1);
  }
  FootJointNames names{parts[0], parts[1], parts[2], parts[3]};
  if (auto s = names.validate(); !s) return s.error();
  return names;
}

Status FootJointNames::validate() const {
  if (!left_ankle.empty() && ascii_lower(left_ankle) == ascii_lower(right_ankle)) {
    return Error{"", 0, fmt::format("the left and right ankles are both named '{}'", left_ankle)};
  }
  if (!left_toe.empty() && ascii_lower(left_toe) == ascii_lower(right_toe)) {
    return Error{"", 0, fmt::format("the left and right toes are both named '{}'", left_toe)};
  }
  if (!left_toe.empty() && ascii_lower(left_toe) == ascii_lower(left_ankle)) {
    return Error{"", 0, fmt::format("the left toe and ankle are both named '{}'", left_toe)};
  }
  if (!right_toe.empty() && ascii_lower(right_toe) == ascii_lower(right_ankle)) {
    return Error{"", 0, fmt::format("the right toe and ankle are both named '{}'", right_toe)};
  }
  return Ok{};
}

Result<FootJoints> find_foot_joints(const Skeleton& skeleton, const FootJointNames& names) {
  if (auto valid = names.validate(); !valid) return valid.error();
  auto left = find_foot(skeleton, kLeft, names.left_ankle, names.left_toe);
  if (!left) return left.error();
  auto right = find_foot(skeleton, kRight, names.right_ankle, names.right_toe);
  if (!right) return right.error();
  if (left->ankle == right->ankle) {
    return Error{"", 0, fmt::format("the left and right ankles are the same joint '{}'",
                                    skeleton.joint(left->ankle).name)};
  }
  return FootJoints{*left, *right};
}

}  // namespace mg
