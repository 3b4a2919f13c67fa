// The studio over real sockets: the front-end and three.js are served, the API answers
// several clients at once, oversized and malformed requests get 4xx, and stop() ends run().
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "studio/http_server.h"
#include "studio/studio_test_service.h"

// After Eigen: <resolv.h>, which httplib includes, defines a macro _res that Eigen's headers
// use as a name.
#include <httplib.h>

namespace mg::test {
namespace {

class StudioServer : public ::testing::Test {
 protected:
  void SetUp() override {
    auto bound = server_.bind("127.0.0.1", 0);
    ASSERT_TRUE(bound) << bound.error().to_string();
    port_ = *bound;
    thread_ = std::thread([this] { served_ = static_cast<bool>(server_.run()); });
  }
  void TearDown() override {
    server_.stop();
    if (thread_.joinable()) thread_.join();
    EXPECT_TRUE(served_);
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(30, 0);
    return c;
  }

  studio::StudioApi api_{studio_service()};
  studio::HttpServer server_{api_, MOTIONGRAPH_WEB_ROOT};
  int port_ = 0;
  std::thread thread_;
  std::atomic<bool> served_ = false;
};

TEST_F(StudioServer, ServesTheFrontEndAndThreeJs) {
  auto c = client();
  auto index = c.Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_NE(index->body.find("importmap"), std::string::npos);
  auto three = c.Get("/node_modules/three/build/three.module.js");
  ASSERT_TRUE(three) << "three.js is not installed in web/node_modules: run 'npm ci' in web/";
  EXPECT_EQ(three->status, 200) << "three.js is not installed in web/node_modules: run 'npm ci' in web/";
  auto missing = c.Get("/no-such-file.js");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
}

TEST_F(StudioServer, AnswersSeveralClientsAtOnce) {
  constexpr int kClients = 6;
  std::atomic<int> ok = 0;
  std::vector<std::thread> clients;
  for (int i = 0; i < kClients; ++i) {
    clients.emplace_back([&, i] {
      auto c = client();
      auto session = c.Post("/api/steer/sessions", R"({"heading_deg": 0})", "application/json");
      if (!session || session->status != 200) return;
      const int id = nlohmann::json::parse(session->body)["session"];
      for (int s = 0; s < 5; ++s) {
        auto step = c.Post("/api/steer/sessions/" + std::to_string(id) + "/step",
                           R"({"heading_deg": )" + std::to_string(60 * i) + "}", "application/json");
        if (!step || step->status != 200) return;
      }
      auto frames = c.Get("/api/clips/" + std::to_string(i % 3) + "/frames?count=30");
      if (!frames || frames->status != 200) return;
      ++ok;
    });
  }
  for (auto& t : clients) t.join();
  EXPECT_EQ(ok, kClients);
}

TEST_F(StudioServer, BadRequestsGet4xxWithAMessage) {
  auto c = client();
  auto big = c.Post("/api/path", std::string(studio::HttpServer::kMaxBodyBytes + 10, ' '), "application/json");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  auto bad = c.Post("/api/walk", "{not json", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_TRUE(nlohmann::json::parse(bad->body).contains("error"));
  auto unknown = c.Get("/api/clips/abc/frames");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404);
  // The server still answers after all that.
  auto summary = c.Get("/api/summary");
  ASSERT_TRUE(summary);
  EXPECT_EQ(summary->status, 200);
}

TEST(StudioServerSetup, RefusesAWebRootWithoutTheStudio) {
  const studio::StudioApi api(studio_service());
  studio::HttpServer server(api, MOTIONGRAPH_DATA_DIR);
  auto bound = server.bind("127.0.0.1", 0);
  ASSERT_FALSE(bound);
  EXPECT_NE(bound.error().message.find("index.html"), std::string::npos);
}

}  // namespace
}  // namespace mg::test
