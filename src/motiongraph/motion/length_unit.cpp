#include "motiongraph/motion/length_unit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

namespace {

constexpr double kMetresPerInch = 0.0254;
constexpr std::array<LengthUnit, 5> kCandidates{{{"m", 1.0},
                                                  {"cm", 0.01},
                                                  {"mm", 0.001},
                                                  {"inch", kMetresPerInch},
                                                  {"CMU unit (1/0.45 inch)", kMetresPerInch / 0.45}}};

// One pose's extent along x, y and z over all its joints (+infinity where huge values overflow:
// inf - inf is NaN, which would break the medians' ordering).
Vec3 pose_extent(std::span<const Vec3> pose) {
  Vec3 low = pose.front();
  Vec3 high = low;
  for (const Vec3& p : pose) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  Vec3 extent = high - low;
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(extent[a])) extent[a] = std::numeric_limits<double>::infinity();
  }
  return extent;
}

}  // namespace

std::span<const LengthUnit> length_unit_candidates() { return kCandidates; }

std::vector<Vec3> frame_extents(const Skeleton& skeleton, const Motion& motion) {
  if (skeleton.joint_count() == 0) return {};
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  std::vector<Vec3> positions(joints);
  std::vector<Quat> rotations(joints);
  std::vector<Vec3> extents(static_cast<size_t>(motion.frame_count));
  for (int f = 0; f < motion.frame_count; ++f) {
    forward_kinematics(skeleton, motion, f, positions, rotations);
    extents[static_cast<size_t>(f)] = pose_extent(positions);
  }
  return extents;
}

double median_of(std::vector<double> values) {
  if (values.empty()) return 0.0;
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

double figure_size(const Skeleton& skeleton, const Motion& motion) {
  if (motion.frame_count == 0 && skeleton.joint_count() > 0) {  // a skeleton alone: its rest pose
    Motion rest(skeleton, 1, motion.fps);
    for (size_t slot = 0; slot < skeleton.translated_joints().size(); ++slot) {
      rest.local_translations_m[slot] = skeleton.joint(skeleton.translated_joints()[slot]).rest_offset_m;
    }
    return figure_size(skeleton, rest);
  }
  std::vector<double> sizes;
  for (const Vec3& extent : frame_extents(skeleton, motion)) sizes.push_back(extent.maxCoeff());
  return median_of(std::move(sizes));
}

double figure_size(std::span<const Vec3> world_positions, int joint_count) {
  if (joint_count <= 0) return 0.0;
  const size_t joints = static_cast<size_t>(joint_count);
  std::vector<double> sizes;
  for (size_t first = 0; first + joints <= world_positions.size(); first += joints) {
    sizes.push_back(pose_extent(world_positions.subspan(first, joints)).maxCoeff());
  }
  return median_of(std::move(sizes));
}

LengthUnitChoice choose_length_unit(double figure_size_units) {
  LengthUnitChoice choice;
  choice.unit = kCandidates.front();
  choice.figure_size_units = figure_size_units;
  double best = std::numeric_limits<double>::infinity(), second = best;
  if (figure_size_units > 0.0 && std::isfinite(figure_size_units)) {
    for (const LengthUnit& unit : kCandidates) {
      const double size_m = figure_size_units * unit.metres_per_unit;
      if (size_m < kPlausibleHeightMinM || size_m > kPlausibleHeightMaxM) continue;
      const double miss = std::abs(std::log(size_m / kTypicalHeightM));
      if (miss < best) {
        if (choice.plausible) {
          second = best;
          choice.also = choice.unit;
        }
        best = miss;
        choice.unit = unit;
        choice.plausible = true;
      } else if (miss < second) {
        second = miss;
        choice.also = unit;
      }
    }
  }
  if (choice.also) choice.also_figure_size_m = figure_size_units * choice.also->metres_per_unit;
  choice.figure_size_m = figure_size_units * choice.unit.metres_per_unit;
  return choice;
}

void scale_lengths(Clip& clip, double factor) {
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  for (JointDef& joint : joints) joint.rest_offset_m *= factor;
  std::vector<StaticAncestor> ancestors(clip.skeleton.static_ancestors().begin(),
                                        clip.skeleton.static_ancestors().end());
  for (StaticAncestor& ancestor : ancestors) ancestor.translation_m *= factor;
  clip.skeleton = Skeleton(std::move(joints), std::move(ancestors));
  for (Vec3& t : clip.motion.local_translations_m) t *= factor;
}

}  // namespace mg
