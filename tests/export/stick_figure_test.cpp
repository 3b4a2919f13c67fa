#include "motiongraph/export/stick_figure.h"

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

// Every bone of 1 mm or more is 8 counter-clockwise triangles (24 vertices) bound to the parent
// joint but for the tip (bound to the child), with apexes on both joints, faces lit from outside
// and no vertex further from the bone's axis than 3 cm; shorter ones make none.
TEST(StickFigure, AnOctahedronPerBoneBoundToItsParent) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  std::vector<Vec3> rest;
  const std::vector<Vec3> first = world_positions(clip.skeleton, clip.motion.slice(0, 1));
  rest.assign(first.begin(), first.end());
  rest[5] = rest[static_cast<size_t>(clip.skeleton.parent(5))] + Vec3(0.0, 0.0005, 0.0);  // a bone of 0.5 mm
  int bones = 0;
  for (int j = 1; j < clip.skeleton.joint_count(); ++j) {
    if ((rest[static_cast<size_t>(j)] - rest[static_cast<size_t>(clip.skeleton.parent(j))]).norm() >= 1e-3) ++bones;
  }
  const StickFigure figure = stick_figure(clip.skeleton, rest);
  ASSERT_EQ(figure.positions.size(), static_cast<size_t>(24 * bones));
  ASSERT_EQ(figure.normals.size(), figure.positions.size());
  ASSERT_EQ(figure.joints.size(), figure.positions.size());
  for (size_t t = 0; t < figure.positions.size(); t += 3) {
    const Vec3 &a = figure.positions[t], &b = figure.positions[t + 1], &c = figure.positions[t + 2];
    const Vec3& n = figure.normals[t];
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    EXPECT_GT((b - a).cross(c - a).dot(n), 0.0);            // counter-clockwise seen from where the normal points
    EXPECT_EQ(figure.joints[t + 1], figure.joints[t + 2]);  // the ring's corners, the bone's joint
  }
  // Each bone's 24 vertices: its apexes are its joints; its other corners within 3 cm of its axis.
  for (size_t start = 0; start < figure.positions.size(); start += 24) {
    const int parent = figure.joints[start];
    const Vec3& head = rest[static_cast<size_t>(parent)];
    int child = -1;
    for (size_t v = start; v < start + 24; ++v) {
      for (int j = 1; j < clip.skeleton.joint_count(); ++j) {
        if (clip.skeleton.parent(j) == parent && (figure.positions[v] - rest[static_cast<size_t>(j)]).norm() < 1e-12)
          child = j;
      }
    }
    ASSERT_GE(child, 0) << "no child joint is an apex of the bone from " << clip.skeleton.joint(parent).name;
    const Vec3& tail = rest[static_cast<size_t>(child)];
    const Vec3 axis = (tail - head).normalized();
    int on_head = 0, on_tail = 0;
    for (size_t v = start; v < start + 24; ++v) {
      const Vec3& p = figure.positions[v];
      on_head += (p - head).norm() < 1e-12;
      on_tail += (p - tail).norm() < 1e-12;
      if ((p - tail).norm() < 1e-12) {  // the tip: bound to a child of the joint standing there
        const int bound = figure.joints[v];
        EXPECT_TRUE(bound > 0 && clip.skeleton.parent(bound) == parent &&
                    (rest[static_cast<size_t>(bound)] - p).norm() < 1e-12);
      } else {
        EXPECT_EQ(figure.joints[v], parent);
      }
      EXPECT_LE(((p - head) - (p - head).dot(axis) * axis).norm(), 0.03 + 1e-12);
    }
    EXPECT_EQ(on_head, 4);
    EXPECT_EQ(on_tail, 4);
  }
}

}  // namespace
}  // namespace mg
