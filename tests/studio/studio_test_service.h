// The studio's service on the subject-16 graph made by the library (pipeline/subject16_build.h:
// the fixture's file, or built in process), once per test process.
#pragma once

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "studio/studio_api.h"

namespace mg::test {

studio::SynthesisService& studio_service();

// A request through the API, the body parsed when it is JSON.
struct ApiCall {
  studio::ApiResponse response;
  nlohmann::json json;
};

ApiCall call_api(const std::string& method, const std::string& path, const std::string& body = "",
                 const std::multimap<std::string, std::string>& query = {});

}  // namespace mg::test
