// The CMU motion index the project ships (data/cmu/cmu-mocap-index.tsv), built into the
// library so that clips named like CMU's ("127_03") get their tags wherever the binary runs,
// without an index beside them. Parse it with parse_cmu_index (cmu_tags.h).
#pragma once

#include <string_view>

namespace mg {

// The file's text, as it was when the library was built.
std::string_view shipped_cmu_index();

// The name errors in it are reported under.
inline constexpr std::string_view kShippedCmuIndexName = "data/cmu/cmu-mocap-index.tsv (built in)";

}  // namespace mg
