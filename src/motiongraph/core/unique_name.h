// A name no one has yet: `wanted`, or with "_2", "_3"... appended while `taken(name)` says it is
// in use (a joint added to a skeleton, a node added beside a rig's joints).
#pragma once

#include <string>

#include <fmt/format.h>

namespace mg {

template <class Taken>
std::string unique_name(const std::string& wanted, Taken taken) {
  std::string name = wanted;
  for (int n = 2; taken(name); ++n) name = fmt::format("{}_{}", wanted, n);
  return name;
}

}  // namespace mg
