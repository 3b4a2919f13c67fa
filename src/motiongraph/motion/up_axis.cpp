#include "motiongraph/motion/up_axis.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <vector>

#include "motiongraph/motion/length_unit.h"

namespace mg {

namespace {

// z extent over y extent; 1 when the figure has no size in either.
double extent_ratio(double y_extent, double z_extent) {
  const double most = std::max(y_extent, z_extent);
  if (!(most > 0.0) || !std::isfinite(most)) return 1.0;
  // A figure flat in y (every joint at one height) says z however small its z extent is.
  return z_extent / std::max(y_extent, 1e-9 * most);
}

enum class Vote { kNone, kY, kZ };

Vote vote_of(double ratio) {
  if (ratio >= kUpAxisRatio) return Vote::kZ;
  if (ratio <= 1.0 / kUpAxisRatio) return Vote::kY;
  return Vote::kNone;
}

}  // namespace

std::string_view up_axis_name(UpAxis axis) { return axis == UpAxis::kZ ? "z" : "y"; }

std::optional<UpAxis> parse_up_axis(std::string_view text) {
  if (text.size() != 1) return std::nullopt;
  const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
  if (c == 'y') return UpAxis::kY;
  if (c == 'z') return UpAxis::kZ;
  return std::nullopt;
}

UpAxisChoice choose_up_axis(const Skeleton& skeleton, const Motion& motion) {
  UpAxisChoice choice;
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  if (joints == 0) return choice;
  if (motion.frame_count > 0) {
    std::vector<double> y_extents, z_extents;
    for (const Vec3& extent : frame_extents(skeleton, motion)) {
      y_extents.push_back(extent.y());
      z_extents.push_back(extent.z());
    }
    choice.animation_ratio = extent_ratio(median_of(std::move(y_extents)), median_of(std::move(z_extents)));
  }
  // The rest pose: every rotation zero, every joint at its rest offset.
  std::vector<Vec3> rest(joints, Vec3::Zero());
  for (size_t j = 1; j < joints; ++j) {
    rest[j] = rest[static_cast<size_t>(skeleton.parent(static_cast<int>(j)))] +
              skeleton.joint(static_cast<int>(j)).rest_offset_m;
  }
  Vec3 low = rest.front(), high = rest.front();
  for (const Vec3& p : rest) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  choice.rest_ratio = extent_ratio(high.y() - low.y(), high.z() - low.z());

  const Vote animation = vote_of(choice.animation_ratio), rest_pose = vote_of(choice.rest_ratio);
  const bool z =
      (animation == Vote::kZ && rest_pose != Vote::kY) || (animation == Vote::kNone && rest_pose == Vote::kZ);
  choice.axis = z ? UpAxis::kZ : UpAxis::kY;
  return choice;
}

bool up_axis_settled(const UpAxisChoice& choice) {
  const Vote animation = vote_of(choice.animation_ratio), rest_pose = vote_of(choice.rest_ratio);
  const Vote axis = choice.axis == UpAxis::kZ ? Vote::kZ : Vote::kY;
  if (animation == Vote::kNone && rest_pose == Vote::kNone) return false;
  return (animation == axis || animation == Vote::kNone) && (rest_pose == axis || rest_pose == Vote::kNone);
}

std::optional<UpAxis> library_up_axis(std::span<const UpAxisChoice> choices) {
  int settled_y = 0, settled_z = 0, unsettled_y = 0, unsettled_z = 0;
  for (const UpAxisChoice& choice : choices) {
    const bool z = choice.axis == UpAxis::kZ;
    if (up_axis_settled(choice)) {
      (z ? settled_z : settled_y) += 1;
    } else {
      (z ? unsettled_z : unsettled_y) += 1;
    }
  }
  if (settled_y == settled_z) return std::nullopt;
  const UpAxis axis = settled_z > settled_y ? UpAxis::kZ : UpAxis::kY;
  // The files it would turn must be fewer than those that settle it.
  const int supporters = axis == UpAxis::kZ ? settled_z : settled_y;
  const int turned = axis == UpAxis::kZ ? unsettled_y : unsettled_z;
  if (turned >= supporters) return std::nullopt;
  return axis;
}

Quat up_axis_to_y(UpAxis axis) {
  if (axis == UpAxis::kY) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(-std::numbers::pi / 2.0, Vec3::UnitX()));
}

void stand_up(Clip& clip, std::optional<UpAxis> given) {
  if (!given) {
    clip.detected_up_axis = choose_up_axis(clip.skeleton, clip.motion);
    given = clip.detected_up_axis->axis;
  }
  if (*given != UpAxis::kY) turn_clip(clip, up_axis_to_y(*given));
}

void turn_clip(Clip& clip, const Quat& rotation) {
  const Quat inverse = rotation.conjugate();
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  for (JointDef& joint : joints) joint.rest_offset_m = rotation * joint.rest_offset_m;
  std::vector<StaticAncestor> ancestors(clip.skeleton.static_ancestors().begin(),
                                        clip.skeleton.static_ancestors().end());
  for (StaticAncestor& ancestor : ancestors) {
    ancestor.translation_m = rotation * ancestor.translation_m;
    ancestor.rotation = (rotation * ancestor.rotation * inverse).normalized();
  }
  clip.skeleton = Skeleton(std::move(joints), std::move(ancestors));
  for (Vec3& t : clip.motion.local_translations_m) t = rotation * t;
  for (Quat& q : clip.motion.local_rotations) q = (rotation * q * inverse).normalized();
}

}  // namespace mg
