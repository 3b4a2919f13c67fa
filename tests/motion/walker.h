// A walker made for the tests: two ankles and eight joints of a body above them, striding along
// -z. Each ankle is planted (its contact bit set) for 60 % of a stride and swings forward along an
// arc 0.1 m high in the rest, the right one `right_phase` of a stride after the left. The body
// stands 0.9-1.6 m up, 3 cm higher when the ankles are together than when they are half a stride
// apart, as far apart as they get (a walk vaults over a stiff leg: vault 1; a run sinks into a
// bent one: vault -1). It travels at the walk's pace, surging forward and back `surge_m` twice a
// stride and swaying side to side `sway_m` once a stride. The left ankle's plant at 3 s lies
// `long_plant_m` further ahead than the others (a long step and a short one). The walker's motion
// from `slow_from_s` to `slow_to_s` of its own time plays `slowdown` times slower.
#pragma once

#include <vector>

#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/skeleton/foot_joints.h"
#include "motiongraph/skeleton/rotation.h"

namespace mg::test {

struct Walker {
  std::vector<Vec3> positions;  // frames x kWalkerJoints, frame-major
  std::vector<ContactMask> contacts;
  FootJoints feet;  // ankles 0 and 1, no toes
};

inline constexpr int kWalkerJoints = 10;

struct WalkerSettings {
  double fps = 30.0;
  double stride_m = 1.3;
  double stride_s = 1.0;
  int strides = 6;  // the walker's own seconds: strides * stride_s
  double vault = 1.0;
  double right_phase = 0.5;
  double surge_m = 0.0;
  double sway_m = 0.0;
  double long_plant_m = 0.0;
  double slow_from_s = 0.0;
  double slow_to_s = 0.0;
  double slowdown = 2.0;
};

Walker walker(const WalkerSettings& settings);

}  // namespace mg::test
