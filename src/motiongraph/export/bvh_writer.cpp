#include "motiongraph/export/bvh_writer.h"

#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "motiongraph/export/root_rotation_order.h"
#include "motiongraph/motion/length_unit_choice.h"
#include "motiongraph/motion/trajectory_joint.h"

namespace mg {

Status BvhWriteSettings::validate() const {
  if (!is_length_unit_scale(units_per_metre)) {
    return Error{"", 0,
                 fmt::format("BVH output scale must lie between {:g} and {:g} units per metre, not {:g}",
                             kMinLengthUnitScale, kMaxLengthUnitScale, units_per_metre)};
  }
  if (decimals < 1 || decimals > 12) return Error{"", 0, "BVH decimals must be between 1 and 12"};
  return Ok{};
}

namespace {

// Fixed decimals with trailing zeros removed ("1.250000" -> "1.25", "-0.000000" -> "0").
void append_number(std::string& out, double value, int decimals) {
  fmt::memory_buffer buffer;  // on the stack, growing for a number of hundreds of digits (1e300)
  fmt::format_to(std::back_inserter(buffer), "{:.{}f}", value, decimals);
  std::string_view s(buffer.data(), buffer.size());
  if (s.find('.') != std::string_view::npos) {
    while (s.back() == '0') s.remove_suffix(1);
    if (s.back() == '.') s.remove_suffix(1);
  }
  if (s == "-0") s = "0";
  out += s;
}

struct JointLayout {
  bool write_positions = false;   // position channels
  bool write_rotations = false;
  Vec3 offset_m = Vec3::Zero();
};

}  // namespace

std::string write_bvh(const Skeleton& folded_skeleton, const Motion& folded_motion, const BvhWriteSettings& settings) {
  // The file's static joints above joint 0 (a static root above the hips) are written back.
  Clip unfolded;
  const bool unfold = !folded_skeleton.static_ancestors().empty();
  if (unfold) {
    Clip folded;
    folded.skeleton = folded_skeleton;
    folded.motion = folded_motion;
    unfolded = unfold_static_root(folded);
  }
  const Skeleton& skeleton = unfold ? unfolded.skeleton : folded_skeleton;
  const Motion& motion = unfold ? unfolded.motion : folded_motion;
  const int joints = skeleton.joint_count();
  // Each joint's rotation order: the file's, but the heading's joint (joint 0 of the folded
  // skeleton: the hips below a static root) with the vertical outermost (root_rotation_order)
  // unless keep_root_order.
  std::vector<ComposeOrder> orders;
  for (int j = 0; j < joints; ++j) {
    const JointDef& joint = skeleton.joint(j);
    const bool heading = joint.name == folded_skeleton.joint(0).name && !joint.end_site;
    orders.push_back(heading && !settings.keep_root_order ? root_rotation_order(folded_skeleton) : joint.euler_order);
  }
  const double scale = settings.units_per_metre;
  const int decimals = settings.decimals;

  std::vector<std::vector<int>> children(joints);
  for (int j = 1; j < joints; ++j) children[skeleton.parent(j)].push_back(j);

  std::vector<JointLayout> layout(joints);
  for (int j = 0; j < joints; ++j) {
    const JointDef& joint = skeleton.joint(j);
    JointLayout& l = layout[j];
    l.offset_m = joint.rest_offset_m;
    if (joint.end_site) continue;
    l.write_rotations = true;
    const int slot = skeleton.translation_slot(j);
    if (j == 0) {
      l.write_positions = true;
      l.offset_m = Vec3::Zero();  // the position channels carry it all
    } else if (slot >= 0) {
      bool constant = true;
      const Vec3 first = motion.frame_count > 0 ? motion.translations(0)[slot] : joint.rest_offset_m;
      for (int f = 1; f < motion.frame_count && constant; ++f) {
        constant = (motion.translations(f)[slot] - first).norm() < 1e-9;
      }
      if (constant) {
        l.offset_m = first;
      } else {
        // Readers disagree on position channels: Blender and our reader take them in place of
        // OFFSET, three.js adds them to it. With a zero OFFSET both read the same.
        l.write_positions = true;
        l.offset_m = Vec3::Zero();
      }
    }
  }

  std::string out = "HIERARCHY\n";
  // Depth-first with an explicit stack of (joint, closing) entries.
  std::vector<std::pair<int, bool>> stack{{0, false}};
  std::vector<int> depth(joints, 0);
  std::vector<int> channel_joints;  // joints in the order their channels appear
  while (!stack.empty()) {
    auto [j, closing] = stack.back();
    stack.pop_back();
    const std::string indent(static_cast<size_t>(depth[j]) * 2, ' ');
    if (closing) {
      out += indent + "}\n";
      continue;
    }
    const JointDef& joint = skeleton.joint(j);
    if (joint.end_site) {
      out += indent + "End Site\n";
    } else {
      out += indent + (j == 0 ? "ROOT " : "JOINT ") + joint.name + "\n";
    }
    out += indent + "{\n";
    out += indent + "  OFFSET ";
    for (int i = 0; i < 3; ++i) {
      if (i) out += ' ';
      append_number(out, layout[j].offset_m[i] * scale, decimals);
    }
    out += '\n';
    if (!joint.end_site) {
      channel_joints.push_back(j);
      const int count = (layout[j].write_positions ? 3 : 0) + 3;
      out += fmt::format("{}  CHANNELS {}", indent, count);
      if (layout[j].write_positions) out += " Xposition Yposition Zposition";
      for (Axis axis : orders[j]) out += fmt::format(" {}rotation", axis_letter(axis));
      out += '\n';
    }
    stack.push_back({j, true});
    if (!joint.end_site && children[j].empty()) {
      out += indent + "  End Site\n" + indent + "  {\n" + indent + "    OFFSET 0 0 0\n" + indent + "  }\n";
    }
    for (auto it = children[j].rbegin(); it != children[j].rend(); ++it) {
      depth[*it] = depth[j] + 1;
      stack.push_back({*it, false});
    }
  }

  out += "MOTION\n";
  out += fmt::format("Frames: {}\n", motion.frame_count);
  out += fmt::format("Frame Time: {:.9g}\n", 1.0 / motion.fps);
  constexpr double kDegrees = 180.0 / std::numbers::pi;
  std::vector<std::optional<Vec3>> previous(joints);
  for (int f = 0; f < motion.frame_count; ++f) {
    const auto rotations = motion.rotations(f);
    const auto translations = motion.translations(f);
    bool first_value = true;
    auto put = [&](double v) {
      if (!first_value) out += ' ';
      first_value = false;
      append_number(out, v, decimals);
    };
    for (int j : channel_joints) {
      const JointDef& joint = skeleton.joint(j);
      if (layout[j].write_positions) {
        const int slot = skeleton.translation_slot(j);
        const Vec3 t = slot >= 0 ? translations[slot] : joint.rest_offset_m;
        for (int i = 0; i < 3; ++i) put(t[i] * scale);
      }
      const Vec3 angles = decompose_euler(orders[j], rotations[j], previous[j]);
      previous[j] = angles;
      for (int i = 0; i < 3; ++i) put(angles[i] * kDegrees);
    }
    out += '\n';
  }
  return out;
}

}  // namespace mg
