// Acclaim Motion Capture (AMC) parser: text in memory -> the values of every frame, in the
// channel layout of the skeleton it belongs to (built from the ASF, see
// skeleton/asf_skeleton.h). Angles stay in the file's unit; AsfRig::motion_from_amc turns
// them into rotations.
//
// Rules: optional ':FULLY-SPECIFIED'; ':DEGREES' or ':RADIANS' (otherwise the ASF's angle
// unit); '#' comment lines; frame numbers consecutive; in every frame each bone with dofs
// appears exactly once with exactly its count of finite values; unknown bones are errors.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg {

// The bones an AMC line may name and how many values each carries, in the order their values
// are stored in AmcDocument::values.
struct AmcLayout {
  std::vector<std::string> bone_names;
  std::vector<int> dof_counts;
  int values_per_frame() const;
};

struct AmcDocument {
  std::string file_name;
  bool angles_in_degrees = true;
  long long first_frame_number = 1;
  int frame_count = 0;
  int values_per_frame = 0;
  std::vector<double> values;  // frame_count x values_per_frame, layout order
};

Result<AmcDocument> parse_amc(std::string_view text, std::string file_name,
                              const AmcLayout& layout, bool default_degrees);

}  // namespace mg
