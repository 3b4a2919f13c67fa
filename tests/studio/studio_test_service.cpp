#include "studio/studio_test_service.h"

#include <memory>
#include <stdexcept>

#include "pipeline/subject16_build.h"

namespace mg::test {

studio::SynthesisService& studio_service() {
  static const std::unique_ptr<studio::SynthesisService> service = [] {
    auto graph = LoadedGraph::create(subject16_graph_file(), "subject16.mgraph");
    if (!graph) throw std::runtime_error(graph.error().to_string());
    auto created = studio::SynthesisService::create(std::move(*graph), "subject16.mgraph");
    // Shared by every test of a process, however fast they create sessions: the least recently
    // stepped always goes.
    studio::SessionLimits limits;
    limits.busy_s = 0.0;
    if (!created->set_session_limits(limits)) throw std::runtime_error("session limits");
    return created;
  }();
  return *service;
}

ApiCall call_api(const std::string& method, const std::string& path, const std::string& body,
                 const std::multimap<std::string, std::string>& query) {
  const studio::StudioApi api(studio_service());
  ApiCall call;
  call.response = api.handle({method, path, query, body});
  if (call.response.content_type == "application/json" && !call.response.body.empty()) {
    call.json = nlohmann::json::parse(call.response.body);
  }
  return call;
}

}  // namespace mg::test
