#include "motiongraph/skeleton/rotation.h"

#include <cctype>
#include <cmath>
#include <numbers>

namespace mg {

char axis_letter(Axis axis) { return "XYZ"[static_cast<int>(axis)]; }

Quat axis_rotation(Axis axis, double angle_rad) {
  return Quat(Eigen::AngleAxisd(angle_rad, Vec3::Unit(static_cast<int>(axis))));
}

Quat compose_euler(const ComposeOrder& order, const Vec3& angles_rad) {
  return axis_rotation(order[0], angles_rad[0]) * axis_rotation(order[1], angles_rad[1]) *
         axis_rotation(order[2], angles_rad[2]);
}

namespace {

double wrap_near(double angle, double target) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  return angle + kTwoPi * std::round((target - angle) / kTwoPi);
}

}  // namespace

Vec3 decompose_euler(const ComposeOrder& order, const Quat& rotation,
                     const std::optional<Vec3>& near) {
  // R = R_i(a) R_j(b) R_k(c) with (i, j, k) distinct. With s = +1 for an even permutation of
  // (x, y, z) and -1 for an odd one: R[i][k] = s sin b, and a, c follow from the row k / column
  // i entries (standard Tait-Bryan extraction, e.g. Shoemake, Graphics Gems IV).
  const Eigen::Matrix3d m = rotation.normalized().toRotationMatrix();
  const int i = static_cast<int>(order[0]);
  const int j = static_cast<int>(order[1]);
  const int k = static_cast<int>(order[2]);
  const double s = ((j - i + 3) % 3 == 1) ? 1.0 : -1.0;
  const double sin_b = std::clamp(s * m(i, k), -1.0, 1.0);
  const double b = std::asin(sin_b);
  double a = 0.0;
  double c = 0.0;
  if (std::abs(sin_b) < 1.0 - 1e-12) {
    a = std::atan2(-s * m(j, k), m(k, k));
    c = std::atan2(-s * m(i, j), m(i, i));
  } else {
    // Gimbal lock: only a + c (or a - c) is determined; put it all in a.
    a = std::atan2(s * m(k, j), m(j, j));
    c = 0.0;
  }
  Vec3 result(a, b, c);
  if (near) {
    const Vec3& t = *near;
    Vec3 first(wrap_near(a, t[0]), wrap_near(b, t[1]), wrap_near(c, t[2]));
    Vec3 second(wrap_near(a + std::numbers::pi, t[0]), wrap_near(std::numbers::pi - b, t[1]),
                wrap_near(c + std::numbers::pi, t[2]));
    result = (first - t).squaredNorm() <= (second - t).squaredNorm() ? first : second;
  }
  return result;
}

std::optional<std::array<Axis, 3>> parse_axis_string(std::string_view text) {
  if (text.size() != 3) return std::nullopt;
  std::array<Axis, 3> axes{};
  bool seen[3] = {false, false, false};
  for (int n = 0; n < 3; ++n) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(text[n])));
    if (c < 'X' || c > 'Z') return std::nullopt;
    const int index = c - 'X';
    if (seen[index]) return std::nullopt;
    seen[index] = true;
    axes[n] = static_cast<Axis>(index);
  }
  return axes;
}

ComposeOrder acclaim_compose_order(const std::array<Axis, 3>& applied_first_to_last) {
  return {applied_first_to_last[2], applied_first_to_last[1], applied_first_to_last[0]};
}

Quat same_hemisphere(const Quat& q, const Quat& reference) {
  if (q.dot(reference) < 0.0) return Quat(-q.w(), -q.x(), -q.y(), -q.z());
  return q;
}

}  // namespace mg
