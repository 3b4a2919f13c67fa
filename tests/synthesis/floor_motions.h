// Small synthetic motions on the floor for the edits' tests (path_edit, heading_edit): a
// two-joint figure whose root follows given floor positions, facing along its travel.
#pragma once

#include <vector>

#include "motiongraph/database/motion_database.h"
#include "motiongraph/motion/motion.h"
#include "motiongraph/synthesis/facing.h"

namespace mg::test {

constexpr double kFloorMotionFps = 30.0;

// A motion of roots.size() frames (at kFloorMotionFps) on a two-joint figure whose root is at
// roots[f] on the floor, 0.9 m high (bobbing 2 cm), facing along its travel over a second
// (north at rest: the root's -z, tilted 0.1 rad about x; a second is a stride of
// straight_walk, so its sway does not turn it), and whose second joint turns with time (values
// the edits must leave alone).
Motion motion_along(const std::vector<Vec2>& roots);

// A straight walk north from the origin at `speed`, swaying `sway` metres either side with each
// stride (1 s).
std::vector<Vec2> straight_walk(double seconds, double speed, double sway);

// A database of the motions (motion_along's), one clip each named clip0, clip1..., on their
// two-joint figure.
MotionDatabase floor_motion_database(const std::vector<Motion>& motions);

Vec2 root_of(const Motion& m, int f);

// The yaw an edit added at frame f: edited rotation times the original's inverse, about +y.
double added_yaw(const Motion& edited, const Motion& original, int f);

// What the edits may change: the root's floor position and its turn about +y; nothing else
// (gtest expectations).
void expect_only_root_moved_on_floor(const Motion& edited, const Motion& original);

}  // namespace mg::test
