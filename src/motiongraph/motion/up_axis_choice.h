// The up axis chosen for a file that names none (BVH, ASF/AMC), and what it was chosen on:
// see up_axis.h.
#pragma once

namespace mg {

enum class UpAxis { kY, kZ };

struct UpAxisChoice {
  UpAxis axis = UpAxis::kY;
  double animation_ratio = 1.0;  // median z extent over median y extent over the frames
  double rest_ratio = 1.0;       // the same of the rest pose (1 when it has no size)
};

}  // namespace mg
