// A file's extension as the code compares it: lower case with its dot (".bvh" for "WALK.BVH"),
// so that files named on systems that keep upper-case names are read and written like any other.
#pragma once

#include <string>
#include <string_view>

namespace mg {

// "" when the last path component has no extension (also for ".hidden" files).
std::string lower_extension(std::string_view path);

}  // namespace mg
