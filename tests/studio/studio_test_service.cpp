#include "studio/studio_test_service.h"

#include <cstdlib>
#include <memory>
#include <stdexcept>

namespace mg::test {

studio::SynthesisService& studio_service() {
  static const std::unique_ptr<studio::SynthesisService> service = [] {
    const char* path = std::getenv("MOTIONGRAPH_TEST_GRAPH");
    if (path == nullptr) throw std::runtime_error("MOTIONGRAPH_TEST_GRAPH is not set: run the tests through ctest");
    auto loaded = studio::SynthesisService::load(path);
    if (!loaded) throw std::runtime_error(loaded.error().to_string());
    return std::move(*loaded);
  }();
  return *service;
}

ApiCall call_api(const std::string& method, const std::string& path, const std::string& body,
                 const std::map<std::string, std::string>& query) {
  const studio::StudioApi api(studio_service());
  ApiCall call;
  call.response = api.handle({method, path, query, body});
  if (call.response.content_type == "application/json") call.json = nlohmann::json::parse(call.response.body);
  return call;
}

}  // namespace mg::test
