#include "motiongraph/motion/mirror.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include <fmt/format.h>

#include "motiongraph/core/text.h"

namespace mg {

namespace {

constexpr double kMaxTiltDeg = 10.0;      // of the plane's normal off the floor
constexpr double kMaxAsymmetryShare = 0.05;  // of the rest pose's size
constexpr double kApartM = 0.01;             // paired joints closer in the rest pose stand on one another

// `word` ("left") spelt as `as` is ("Left", "LEFT", "left").
std::string spelt_as(std::string_view word, std::string_view as) {
  std::string out(word);
  const bool all_upper = std::all_of(as.begin(), as.end(), [](char c) { return is_ascii_upper(c); });
  for (size_t i = 0; i < out.size(); ++i) {
    if (all_upper || (i == 0 && is_ascii_upper(as[0]))) {
      out[i] = static_cast<char>(std::toupper(static_cast<unsigned char>(out[i])));
    }
  }
  return out;
}

Vec3 reflected(const Vec3& v, const Vec3& n) { return v - 2.0 * n.dot(v) * n; }

}  // namespace

std::vector<std::string> mirrored_names(std::string_view name) {
  std::vector<std::string> out;
  auto add = [&](std::string candidate) {
    if (candidate != name && std::find(out.begin(), out.end(), candidate) == out.end()) {
      out.push_back(std::move(candidate));
    }
  };
  // The words, anywhere ("mixamorig:LeftArm", "lefthand", "LEFT_FOOT").
  const std::string low = ascii_lower(name);
  for (const auto& [from, to] : {std::pair{"left", "right"}, std::pair{"right", "left"}}) {
    const std::string_view f(from);
    for (size_t at = low.find(f); at != std::string::npos; at = low.find(f, at + 1)) {
      std::string candidate(name);
      candidate.replace(at, f.size(), spelt_as(to, name.substr(at, f.size())));
      add(std::move(candidate));
    }
  }
  // A side letter where a part of the name starts: at its start ("lfemur", "LHipJoint"), after a
  // mark ("Hip_L", "hip.L", "Bip01 L Thigh") or as a capital after a small letter ("ThighL").
  for (size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    const char swapped = c == 'l' ? 'r' : c == 'r' ? 'l' : c == 'L' ? 'R' : c == 'R' ? 'L' : '\0';
    if (swapped == '\0') continue;
    const bool starts = i == 0 || !is_ascii_letter(name[i - 1]) || (is_ascii_lower(name[i - 1]) && is_ascii_upper(c));
    if (!starts) continue;
    std::string candidate(name);
    candidate[i] = swapped;
    add(std::move(candidate));
  }
  return out;
}

std::string mirrored_side_words(std::string_view text) {
  const std::string low = ascii_lower(text);
  std::string out;
  for (size_t i = 0; i < text.size();) {
    bool swapped = false;
    for (const auto& [from, to] : {std::pair{"left", "right"}, std::pair{"right", "left"}}) {
      const std::string_view f(from);
      if (low.compare(i, f.size(), f) == 0) {
        out += spelt_as(to, text.substr(i, f.size()));
        i += f.size();
        swapped = true;
        break;
      }
    }
    if (!swapped) out += text[i++];
  }
  return out;
}

Result<MirrorMap> mirror_map(const Skeleton& skeleton) {
  const int n = skeleton.joint_count();
  MirrorMap map;
  map.partner.assign(static_cast<size_t>(n), -1);
  std::unordered_map<std::string, int> index;
  for (int j = 0; j < n; ++j) index.emplace(skeleton.joint(j).name, j);
  // By name: the first of the names' mirror images that is a joint.
  for (int j = 0; j < n; ++j) {
    for (const std::string& candidate : mirrored_names(skeleton.joint(j).name)) {
      if (auto it = index.find(candidate); it != index.end() && it->second != j) {
        map.partner[static_cast<size_t>(j)] = it->second;
        break;
      }
    }
  }
  for (int j = 0; j < n; ++j) {
    const int k = map.partner[static_cast<size_t>(j)];
    if (k >= 0 && map.partner[static_cast<size_t>(k)] != j) {
      return Error{"", 0,
                   fmt::format("its joints {} and {} do not pair with each other by name", skeleton.joint(j).name,
                               skeleton.joint(k).name)};
    }
  }
  // The rest by their places: a joint not paired by name, whose parent pairs with another, pairs
  // with the child of that partner in the same place among its unpaired children (end sites,
  // fingers named alike on both hands).
  for (int j = 1; j < n; ++j) {
    if (map.partner[static_cast<size_t>(j)] >= 0) continue;
    const int parent = skeleton.parent(j);
    const int other = map.partner[static_cast<size_t>(parent)];
    if (other < 0 || other == parent) continue;
    auto unpaired_children = [&](int of) {
      std::vector<int> children;
      for (int c = 1; c < n; ++c) {
        if (skeleton.parent(c) == of && map.partner[static_cast<size_t>(c)] < 0) children.push_back(c);
      }
      return children;
    };
    const std::vector<int> mine = unpaired_children(parent), theirs = unpaired_children(other);
    if (mine.size() != theirs.size()) continue;
    for (size_t i = 0; i < mine.size(); ++i) {
      map.partner[static_cast<size_t>(mine[i])] = theirs[i];
      map.partner[static_cast<size_t>(theirs[i])] = mine[i];
    }
  }
  for (int j = 0; j < n; ++j) {
    int& k = map.partner[static_cast<size_t>(j)];
    if (k < 0) k = j;
    if (k > j) ++map.pairs;
  }
  if (map.pairs == 0) return Error{"", 0, "no joint of it has a left or right partner by name"};
  if (map.partner[0] != 0) {
    return Error{"", 0, fmt::format("its root {} pairs with {} by name; a root is on the middle",
                                    skeleton.joint(0).name, skeleton.joint(map.partner[0]).name)};
  }
  for (int j = 1; j < n; ++j) {
    const int k = map.partner[static_cast<size_t>(j)];
    if (k == j) continue;
    const int parent = skeleton.parent(j);
    if (skeleton.parent(k) != map.partner[static_cast<size_t>(parent)]) {
      return Error{"", 0, fmt::format("its joints {} and {} pair, but their parents {} and {} do not",
                                      skeleton.joint(j).name, skeleton.joint(k).name, skeleton.joint(parent).name,
                                      skeleton.joint(skeleton.parent(k)).name)};
    }
    if (skeleton.joint(j).animated_translation != skeleton.joint(k).animated_translation) {
      return Error{"", 0,
                   fmt::format("of its joints {} and {}, only {} has animated translation", skeleton.joint(j).name,
                               skeleton.joint(k).name,
                               skeleton.joint(skeleton.joint(j).animated_translation ? j : k).name)};
    }
  }
  // The rest pose, and the line across it.
  std::vector<Vec3> rest(static_cast<size_t>(n), Vec3::Zero());
  for (int j = 0; j < n; ++j) {
    const Vec3 offset = skeleton.joint(j).rest_offset_m;
    rest[static_cast<size_t>(j)] = j == 0 ? offset : Vec3(rest[static_cast<size_t>(skeleton.parent(j))] + offset);
  }
  // Across the body where it first parts into paired joints that stand apart (the hips: the
  // legs' first joints set off from the root, as facing.h finds them), not across all of them: an
  // arm held higher than the other would tilt the plane, and the mirrored clips would face a little
  // off the way they go.
  std::vector<int> depth(static_cast<size_t>(n), 0);
  for (int j = 1; j < n; ++j) depth[static_cast<size_t>(j)] = depth[static_cast<size_t>(skeleton.parent(j))] + 1;
  int level = -1;
  for (int j = 0; j < n; ++j) {
    const int k = map.partner[static_cast<size_t>(j)];
    const bool apart = k > j && (rest[static_cast<size_t>(j)] - rest[static_cast<size_t>(k)]).norm() > kApartM;
    if (apart && (level < 0 || depth[static_cast<size_t>(j)] < level)) level = depth[static_cast<size_t>(j)];
  }
  if (level < 0) return Error{"", 0, "its paired joints stand on one another in the rest pose"};
  Vec3 across = Vec3::Zero(), first = Vec3::Zero();
  std::vector<std::pair<int, int>> parting;
  for (int j = 0; j < n; ++j) {
    const int k = map.partner[static_cast<size_t>(j)];
    const Vec3 d = rest[static_cast<size_t>(j)] - rest[static_cast<size_t>(k)];
    if (k <= j || depth[static_cast<size_t>(j)] != level || d.norm() <= kApartM) continue;
    if (first.squaredNorm() == 0.0) first = d;
    across += d.dot(first) >= 0.0 ? d : Vec3(-d);
    parting.emplace_back(j, k);
  }
  if (!(across.norm() > 1e-9)) return Error{"", 0, "its paired joints stand on one another in the rest pose"};
  across.normalize();
  const double tilt_deg = std::asin(std::min(1.0, std::abs(across.y()))) * 180.0 / std::numbers::pi;
  if (tilt_deg > kMaxTiltDeg) {
    return Error{"", 0,
                 fmt::format("its {} and {} lie one {:.0f} degrees above the other in the rest pose: on its side, its "
                             "mirror image would turn it over",
                             skeleton.joint(parting.front().first).name, skeleton.joint(parting.front().second).name,
                             tilt_deg)};
  }
  map.normal = Vec3(across.x(), 0.0, across.z()).normalized();
  // Its own mirror image? The plane through the middle of those joints.
  double middle = 0.0;
  for (const auto& [j, k] : parting) {
    middle += 0.5 * map.normal.dot(rest[static_cast<size_t>(j)] + rest[static_cast<size_t>(k)]);
  }
  middle /= static_cast<double>(parting.size());
  map.plane_offset_m = middle - map.normal.dot(rest[0]);
  Vec3 low = rest[0], high = rest[0];
  for (const Vec3& p : rest) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double size = (high - low).norm();
  // The joint highest up the hierarchy that is off (where the difference starts: its children
  // follow it), the furthest off of those.
  int off = -1;
  double off_m = 0.0;
  for (int j = 1; j < n; ++j) {  // the root may stand off the plane (mirror_motion sets it back)
    const Vec3& p = rest[static_cast<size_t>(j)];
    const Vec3 image = p - 2.0 * (map.normal.dot(p) - middle) * map.normal;
    const double d = (image - rest[static_cast<size_t>(map.partner[static_cast<size_t>(j)])]).norm();
    map.asymmetry_m = std::max(map.asymmetry_m, d);
    if (d <= kMaxAsymmetryShare * size) continue;
    const int at = depth[static_cast<size_t>(j)];
    if (off < 0 || at < depth[static_cast<size_t>(off)] || (at == depth[static_cast<size_t>(off)] && d > off_m)) {
      off = j;
      off_m = d;
    }
  }
  if (off >= 0) {
    const int partner = map.partner[static_cast<size_t>(off)];
    const std::string which = partner == off ? fmt::format("its {} stands", skeleton.joint(off).name)
                                             : fmt::format("its {} and {} stand", skeleton.joint(off).name,
                                                           skeleton.joint(partner).name);
    return Error{"", 0,
                 fmt::format("its rest pose is not its own mirror image: {} {:.0f} cm off each other's mirror image "
                             "(more than {:.0f} % of its {:.2f} m)",
                             which, 100.0 * off_m, 100.0 * kMaxAsymmetryShare, size)};
  }
  return map;
}

Motion mirror_motion(const Skeleton& skeleton, const MirrorMap& map, const Motion& motion) {
  Motion out(skeleton, motion.frame_count, motion.fps);
  const Vec3 n = map.normal;
  const std::span<const int> translated = skeleton.translated_joints();
  for (int f = 0; f < motion.frame_count; ++f) {
    const auto from = motion.rotations(f);
    const auto to = out.rotations(f);
    for (int j = 0; j < motion.joint_count; ++j) {
      const Quat& q = from[static_cast<size_t>(j)];
      const Vec3 v = -reflected(q.vec(), n);
      to[static_cast<size_t>(map.partner[static_cast<size_t>(j)])] = Quat(q.w(), v.x(), v.y(), v.z());
    }
    const auto moved = motion.translations(f);
    const auto moved_to = out.translations(f);
    for (size_t slot = 0; slot < translated.size(); ++slot) {
      const int joint = translated[slot], partner = map.partner[static_cast<size_t>(joint)];
      // Below the root, the partner keeps its own rest offset (what moves is mirrored); the root,
      // off the plane by d, ends as far off it on the other side.
      const Vec3 own = joint == 0 ? Vec3(-2.0 * map.plane_offset_m * (to[0] * n))
                                  : Vec3(skeleton.joint(partner).rest_offset_m -
                                         reflected(skeleton.joint(joint).rest_offset_m, n));
      moved_to[static_cast<size_t>(skeleton.translation_slot(partner))] = reflected(moved[slot], n) + own;
    }
  }
  return out;
}

}  // namespace mg
