// A transition candidate (Kovar et al. 2002, section 3): leave the database at global frame
// `from_frame` (the first frame of the window we leave, a..a+k-1) and arrive at `to_frame`
// (the last frame of the window we arrive in, b-k+1..b). The floor alignment (rotation about
// the vertical axis by yaw_rad, then translation x_m, z_m) maps the arrival window onto the
// departure window: it is the minimiser T of DESIGN.md section 3.1. In a graph, a bridge that
// blends longer than the window leaves before and lands after the window its D and alignment
// were measured on (GraphEdge::blend_lead, measured_pair in motion_graph.h).
#pragma once

namespace mg {

struct Transition {
  int from_frame = 0;
  int to_frame = 0;
  float distance = 0.0f;  // D(a, b), squared metres weighted (DESIGN.md 3.1)
  float yaw_rad = 0.0f;
  float x_m = 0.0f;
  float z_m = 0.0f;
};

}  // namespace mg
