#include "motiongraph/motion/acclaim_import.h"

#include <cmath>
#include <numbers>
#include <unordered_map>

#include <fmt/format.h>

namespace mg {

namespace {

constexpr double kMetresPerInch = 0.0254;

double to_radians(double angle, bool degrees) { return degrees ? angle * std::numbers::pi / 180.0 : angle; }

Quat axis_frame(const Vec3& angles, const std::array<Axis, 3>& order, bool degrees) {
  const std::array<Axis, 3> compose = acclaim_compose_order(order);
  // compose_euler takes angles in product order; the file gives them as x, y, z.
  Vec3 in_product_order;
  for (int n = 0; n < 3; ++n) in_product_order[n] = to_radians(angles[static_cast<int>(compose[n])], degrees);
  return compose_euler(compose, in_product_order);
}

bool is_translation(AcclaimDof dof) {
  return dof == AcclaimDof::kTx || dof == AcclaimDof::kTy || dof == AcclaimDof::kTz;
}

}  // namespace

Result<AcclaimRig> build_acclaim_rig(const AsfDocument& asf) {
  const std::string& file = asf.file_name;
  const int bone_count = static_cast<int>(asf.bones.size());
  std::unordered_map<std::string, int> by_name;
  for (int b = 0; b < bone_count; ++b) {
    const AsfBone& bone = asf.bones[b];
    if (bone.name == "root") return Error{file, bone.line, "a bone may not be called 'root'"};
    if (!by_name.emplace(bone.name, b).second) {
      return Error{file, bone.line, fmt::format("bone name '{}' is used twice", bone.name)};
    }
    if (bone.length > 0.0 && bone.direction.norm() < 1e-12) {
      return Error{file, bone.line, fmt::format("bone '{}' has a zero direction", bone.name)};
    }
    for (AcclaimDof dof : bone.dofs) {
      if (dof == AcclaimDof::kLength) {
        return Error{file, bone.line, fmt::format("bone '{}': dof 'l' (bone stretching) is not supported", bone.name)};
      }
    }
  }

  // Parent of each bone: -1 = root, -2 = none yet.
  std::vector<int> parent(bone_count, -2);
  std::vector<int> parent_line(bone_count, 0);
  std::vector<std::vector<int>> children(bone_count + 1);  // index bone_count = root
  for (const AsfHierarchyLine& line : asf.hierarchy) {
    int p = -1;
    if (line.parent != "root") {
      auto it = by_name.find(line.parent);
      if (it == by_name.end()) return Error{file, line.line, fmt::format("unknown bone '{}' in the hierarchy", line.parent)};
      p = it->second;
    }
    for (const std::string& child_name : line.children) {
      if (child_name == "root") return Error{file, line.line, "'root' cannot be a child"};
      auto it = by_name.find(child_name);
      if (it == by_name.end()) return Error{file, line.line, fmt::format("unknown bone '{}' in the hierarchy", child_name)};
      const int c = it->second;
      if (c == p) return Error{file, line.line, fmt::format("bone '{}' is its own parent", child_name)};
      if (parent[c] != -2) {
        return Error{file, line.line, fmt::format("bone '{}' has a second parent (first given on line {})", child_name, parent_line[c])};
      }
      parent[c] = p;
      parent_line[c] = line.line;
      children[p < 0 ? bone_count : p].push_back(c);
    }
  }
  for (int b = 0; b < bone_count; ++b) {
    // Walk up: reaching the root is fine; a bone without parent is unreachable; a walk longer
    // than the bone count is a cycle.
    int steps = 0;
    for (int a = b; a >= 0; a = parent[a]) {
      if (parent[a] == -2) {
        return Error{file, asf.bones[b].line,
                     fmt::format("bone '{}' is not reachable from the root in ':hierarchy'", asf.bones[b].name)};
      }
      if (++steps > bone_count) {
        return Error{file, parent_line[b], fmt::format("bone '{}' is in a cycle in ':hierarchy'", asf.bones[b].name)};
      }
    }
  }

  AcclaimRig rig;
  rig.metres_per_unit = kMetresPerInch / asf.length;
  rig.angles_in_degrees = asf.angles_in_degrees;
  const double scale = rig.metres_per_unit;
  auto bone_vector_m = [&](int b) -> Vec3 {
    const AsfBone& bone = asf.bones[b];
    return bone.length > 0.0 ? Vec3(bone.direction.normalized() * bone.length * scale) : Vec3::Zero();
  };

  std::vector<JointDef> joints;
  JointDef root;
  root.name = "root";
  root.rest_offset_m = asf.root.position * scale;
  root.animated_translation = true;
  joints.push_back(root);
  rig.channels.push_back({0, asf.root.order, axis_frame(asf.root.orientation, asf.root.axis_order, asf.angles_in_degrees)});
  rig.amc_layout.bone_names.push_back("root");
  rig.amc_layout.dof_counts.push_back(static_cast<int>(asf.root.order.size()));

  // Depth first from the root, children in hierarchy order (an explicit stack: no recursion).
  std::vector<int> joint_of_bone(bone_count, -1);
  std::vector<int> stack(children[bone_count].rbegin(), children[bone_count].rend());
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    const AsfBone& bone = asf.bones[b];
    JointDef joint;
    joint.name = bone.name;
    joint.parent = parent[b] < 0 ? 0 : joint_of_bone[parent[b]];
    joint.rest_offset_m = parent[b] < 0 ? Vec3::Zero() : bone_vector_m(parent[b]);
    joint_of_bone[b] = static_cast<int>(joints.size());
    bool translated = false;
    for (AcclaimDof dof : bone.dofs) translated = translated || is_translation(dof);
    joint.animated_translation = translated;
    joints.push_back(joint);
    rig.channels.push_back({joint_of_bone[b], bone.dofs, axis_frame(bone.axis, bone.axis_order, asf.angles_in_degrees)});
    rig.amc_layout.bone_names.push_back(bone.name);
    rig.amc_layout.dof_counts.push_back(static_cast<int>(bone.dofs.size()));
    for (auto it = children[b].rbegin(); it != children[b].rend(); ++it) stack.push_back(*it);
  }
  for (int b = 0; b < bone_count; ++b) {
    if (!children[b].empty()) continue;
    JointDef end;
    end.name = bone_count > 0 ? asf.bones[b].name + "_end" : "";
    while (by_name.count(end.name)) end.name += "_";
    end.parent = joint_of_bone[b];
    end.rest_offset_m = bone_vector_m(b);
    end.end_site = true;
    joints.push_back(end);
  }
  // Joints were appended depth first; end joints come after all bones, so parents precede.
  rig.skeleton = Skeleton(std::move(joints));
  return rig;
}

Motion motion_from_amc(const AcclaimRig& rig, const AmcDocument& amc, double fps) {
  const Skeleton& skeleton = rig.skeleton;
  Motion motion(skeleton, amc.frame_count, fps);
  const double scale = rig.metres_per_unit;
  for (int f = 0; f < amc.frame_count; ++f) {
    const double* values = amc.values.data() + static_cast<size_t>(f) * amc.values_per_frame;
    auto rotations = motion.rotations(f);
    auto translations = motion.translations(f);
    for (const AcclaimChannels& channels : rig.channels) {
      // M = R_last * ... * R_first: each listed rotation applies after the ones before it.
      Quat m = Quat::Identity();
      Vec3 t = Vec3::Zero();
      for (AcclaimDof dof : channels.dofs) {
        const double v = *values++;
        switch (dof) {
          case AcclaimDof::kRx: m = axis_rotation(Axis::kX, to_radians(v, amc.angles_in_degrees)) * m; break;
          case AcclaimDof::kRy: m = axis_rotation(Axis::kY, to_radians(v, amc.angles_in_degrees)) * m; break;
          case AcclaimDof::kRz: m = axis_rotation(Axis::kZ, to_radians(v, amc.angles_in_degrees)) * m; break;
          case AcclaimDof::kTx: t.x() = v; break;
          case AcclaimDof::kTy: t.y() = v; break;
          case AcclaimDof::kTz: t.z() = v; break;
          case AcclaimDof::kLength: break;  // rejected by build_acclaim_rig
        }
      }
      const int j = channels.joint;
      rotations[j] = (channels.axis * m * channels.axis.conjugate()).normalized();
      const int slot = skeleton.translation_slot(j);
      if (slot >= 0) {
        // Root: translation in the world frame. Bones: along the bone's axis frame.
        const Vec3 moved = j == 0 ? t : Vec3(channels.axis * t);
        translations[slot] = skeleton.joint(j).rest_offset_m + moved * scale;
      }
    }
  }
  return motion;
}

}  // namespace mg
