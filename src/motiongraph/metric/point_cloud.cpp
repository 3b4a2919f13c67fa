#include "motiongraph/metric/point_cloud.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

Status PointCloudSettings::validate() const {
  if (!(ring_spacing_m > 0.0) || !std::isfinite(ring_spacing_m)) return Error{"", 0, "ring spacing must be positive"};
  if (!(ring_radius_m >= 0.0) || !std::isfinite(ring_radius_m)) return Error{"", 0, "ring radius must be >= 0"};
  if (points_per_ring < 1 || points_per_ring > 64) return Error{"", 0, "points per ring must be 1 to 64"};
  for (const auto& [name, weight] : joint_weights) {
    if (!(weight >= 0.0) || !std::isfinite(weight)) {
      return Error{"", 0, fmt::format("weight of joint '{}' must be >= 0", name)};
    }
  }
  return Ok{};
}

namespace {

// A unit vector perpendicular to `axis`, chosen the same way for any bone pointing alike.
Vec3 perpendicular(const Vec3& axis) {
  const Vec3 helper = std::abs(axis.x()) < 0.9 * axis.norm() ? Vec3::UnitX() : Vec3::UnitY();
  return axis.cross(helper).normalized();
}

}  // namespace

Result<CloudLayout> make_cloud_layout(const Skeleton& reference, const PointCloudSettings& settings) {
  if (auto s = settings.validate(); !s) return s.error();
  for (const auto& [name, weight] : settings.joint_weights) {
    if (!reference.find(name)) {
      std::vector<std::string> names;
      for (int j = 0; j < reference.joint_count(); ++j) names.push_back(reference.joint(j).name);
      return Error{"", 0, fmt::format("a joint weight (--joint-weight) names '{}', which is not a joint of the skeleton (its joints: {})",
                                      name, fmt::join(names, ", "))};
    }
  }
  CloudLayout layout;
  auto weight_of = [&](int joint) {
    for (const auto& [name, weight] : settings.joint_weights) {
      if (name == reference.joint(joint).name) return static_cast<float>(weight);
    }
    return 1.0f;
  };
  auto add = [&](int parent, int end, double along, double angle, double radius) {
    layout.parent_joint.push_back(parent);
    layout.end_joint.push_back(end);
    layout.along.push_back(along);
    layout.angle_rad.push_back(angle);
    layout.radius_m.push_back(radius);
    layout.weight.push_back(weight_of(end));
  };
  if (settings.kind == PointCloudSettings::Kind::kJoints) {
    for (int j = 0; j < reference.joint_count(); ++j) add(j == 0 ? 0 : reference.parent(j), j, 1.0, 0.0, 0.0);
  } else {
    // The points counted before any is made (a ring every nanometre would be billions).
    double points = 0.0;
    for (int j = 1; j < reference.joint_count(); ++j) {
      const double length = reference.joint(j).rest_offset_m.norm();
      if (length >= 1e-6) points += std::max(1.0, std::ceil(length / settings.ring_spacing_m)) * settings.points_per_ring;
    }
    if (points > kMaxCloudPoints) {
      return Error{"", 0, fmt::format("rings every {:g} m would put {:g} points on the skeleton, more than {}: space "
                                      "them wider (--ring-spacing)",
                                      settings.ring_spacing_m, points, kMaxCloudPoints)};
    }
    for (int j = 1; j < reference.joint_count(); ++j) {
      const double length = reference.joint(j).rest_offset_m.norm();
      if (length < 1e-6) continue;  // bones of zero length (e.g. at the root) carry no ring
      const int rings = std::max(1, static_cast<int>(std::ceil(length / settings.ring_spacing_m)));
      for (int r = 0; r < rings; ++r) {
        const double along = (r + 0.5) / rings;
        for (int p = 0; p < settings.points_per_ring; ++p) {
          add(reference.parent(j), j, along, 2.0 * std::numbers::pi * p / settings.points_per_ring,
              settings.ring_radius_m);
        }
      }
    }
  }
  if (layout.point_count() == 0) return Error{"", 0, "the skeleton has no bones to put points on (every bone has length 0)"};
  return layout;
}

bool layout_fits(const CloudLayout& layout, const Skeleton& skeleton) {
  for (int p = 0; p < layout.point_count(); ++p) {
    if (layout.end_joint[p] >= skeleton.joint_count()) return false;
    const int end = layout.end_joint[p];
    if (end > 0 && skeleton.parent(end) != layout.parent_joint[p]) return false;
  }
  return true;
}

CloudEvaluator::CloudEvaluator(const Skeleton& skeleton, const CloudLayout& layout)
    : skeleton_(skeleton),
      layout_(layout),
      local_(layout.point_count()),
      positions_(skeleton.joint_count()),
      rotations_(skeleton.joint_count()) {
  for (int p = 0; p < layout.point_count(); ++p) {
    const int end = layout.end_joint[p];
    const Vec3 bone = end == 0 ? Vec3::Zero() : skeleton.joint(end).rest_offset_m;
    Vec3 offset = layout.along[p] * bone;
    if (layout.radius_m[p] > 0.0 && bone.norm() > 1e-9) {
      const Vec3 u = perpendicular(bone);
      const Vec3 v = bone.normalized().cross(u);
      offset += layout.radius_m[p] * (std::cos(layout.angle_rad[p]) * u + std::sin(layout.angle_rad[p]) * v);
    }
    local_[p] = offset;
  }
}

void CloudEvaluator::points(const Motion& motion, int frame, std::span<Vec3> out) {
  forward_kinematics(skeleton_, motion, frame, positions_, rotations_);
  for (int p = 0; p < layout_.point_count(); ++p) {
    const int parent = layout_.parent_joint[p];
    // A joint-only point on the root sits at the root; others ride on their parent's frame.
    out[p] = layout_.end_joint[p] == 0 ? positions_[0] : Vec3(positions_[parent] + rotations_[parent] * local_[p]);
  }
}

std::vector<float> compute_clouds(const Skeleton& skeleton, const Motion& motion, const CloudLayout& layout) {
  const int points = layout.point_count();
  CloudEvaluator evaluator(skeleton, layout);
  std::vector<Vec3> frame_points(points);
  std::vector<float> clouds(static_cast<size_t>(motion.frame_count) * points * 3);
  for (int f = 0; f < motion.frame_count; ++f) {
    evaluator.points(motion, f, frame_points);
    float* out = clouds.data() + static_cast<size_t>(f) * points * 3;
    for (int p = 0; p < points; ++p) {
      for (int c = 0; c < 3; ++c) out[3 * p + c] = static_cast<float>(frame_points[p][c]);
    }
  }
  return clouds;
}

}  // namespace mg
