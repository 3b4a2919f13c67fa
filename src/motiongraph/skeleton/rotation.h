// Rotations at the I/O boundary: axes, Euler orders and their conversion to and from unit
// quaternions. Inside the library rotations are quaternions; Euler angles exist only because
// ASF/AMC and BVH store them.
//
// Order conventions (the classic trap, DESIGN.md section 7):
//  - BVH lists rotation channels in the order they are composed: "Zrotation Xrotation
//    Yrotation" is R = Rz * Rx * Ry (column vectors; intrinsic z, then x, then y).
//  - Acclaim (ASF axis strings and dof lists) lists them in the order they are applied:
//    "axis ... XYZ" and "dof rx ry rz" mean R = Rz * Ry * Rx (extrinsic x, then y, then z).
// Both are expressed here as a ComposeOrder: the axes from left to right in the product.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include <Eigen/Geometry>

namespace mg {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

enum class Axis : int { kX = 0, kY = 1, kZ = 2 };

// Axes from left to right in the matrix product R = R_a0 * R_a1 * R_a2.
using ComposeOrder = std::array<Axis, 3>;

char axis_letter(Axis axis);

// Rotation by angle_rad about one axis.
Quat axis_rotation(Axis axis, double angle_rad);

// R = R_order[0](angles[0]) * R_order[1](angles[1]) * R_order[2](angles[2]), radians.
Quat compose_euler(const ComposeOrder& order, const Vec3& angles_rad);

// Inverse of compose_euler for Tait-Bryan orders (three distinct axes): angles with the
// middle one in [-pi/2, pi/2]. When `near` is given, each angle is shifted by multiples of
// 2 pi, and at the equivalent solution (a0 + pi, pi - a1, a2 + pi) considered, to lie as
// close as possible to it, so a sequence of frames stays continuous.
Vec3 decompose_euler(const ComposeOrder& order, const Quat& rotation,
                     const std::optional<Vec3>& near = std::nullopt);

// Parses a 3-letter axis string such as "XYZ" (case-insensitive, each axis once).
std::optional<std::array<Axis, 3>> parse_axis_string(std::string_view text);

// The ComposeOrder of an Acclaim order string: "XYZ" (apply x, then y, then z) -> {Z, Y, X}.
ComposeOrder acclaim_compose_order(const std::array<Axis, 3>& applied_first_to_last);

// Makes q's sign agree with `reference` (q and -q are the same rotation).
Quat same_hemisphere(const Quat& q, const Quat& reference);

}  // namespace mg
