// The studio over real sockets: the front-end and three.js are served, the API answers
// several clients at once, oversized and malformed requests get 4xx, a POST without a length
// has an empty body, and stop() ends run().
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "studio/http_server.h"
#include "studio/studio_test_service.h"

// After Eigen: <resolv.h>, which httplib includes, defines a macro _res that Eigen's headers
// use as a name.
#include <httplib.h>

namespace mg::test {
namespace {

// A request sent as it is (the client library always sends a Content-Length) and the answer
// read until the server closes; the socket gives up after `wait_s` seconds.
std::string raw_request(int port, const std::string& request, int wait_s) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return "no socket";
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  const timeval wait{wait_s, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &wait, sizeof wait);
  std::string answer;
  if (connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0 &&
      send(fd, request.data(), request.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(request.size())) {
    char buffer[4096];
    for (ssize_t n; (n = recv(fd, buffer, sizeof buffer, 0)) > 0;) answer.append(buffer, static_cast<size_t>(n));
  }
  close(fd);
  return answer;
}

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
  // A NUL byte ends the file name opened, not the type read from it: refused (index.html was
  // served as a PNG).
  auto nul = c.Get("/index.html%00.png");
  ASSERT_TRUE(nul);
  EXPECT_EQ(nul->status, 400);
  EXPECT_EQ(nul->get_header_value("Content-Type"), "application/json");
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

// DNS rebinding: a page of another site whose name now resolves to this machine sends the
// studio requests addressed to that name. They are refused, pages and API alike, saying how to
// allow a name; addresses, localhost and the names allowed are answered (the name bound:
// cli_serve_test.sh).
TEST(StudioServerSetup, AnswersOnlyTheNamesItIsOpenedUnder) {
  const studio::StudioApi api(studio_service());
  studio::HttpServer server(api, MOTIONGRAPH_WEB_ROOT);
  ASSERT_TRUE(server.allow_hosts({"Studio.Test", ".lan"}));
  EXPECT_FALSE(server.allow_hosts({"http://studio.test/"}));
  auto bound = server.bind("127.0.0.1", 0);
  ASSERT_TRUE(bound) << bound.error().to_string();
  const int port = *bound;
  std::thread thread([&] { (void)server.run(); });
  const auto status_for = [&](const std::string& path, const std::string& host) {
    const std::string answer =
        raw_request(port, "GET " + path + " HTTP/1.1\r\nHost: " + host + "\r\nConnection: close\r\n\r\n", 8);
    return answer.substr(0, answer.find("\r\n"));
  };
  const std::string p = ":" + std::to_string(port);
  for (const std::string& host : {"127.0.0.1" + p, "localhost" + p, "[::1]" + p, "studio.test" + p, "a.lan" + p}) {
    EXPECT_EQ(status_for("/api/summary", host), "HTTP/1.1 200 OK") << host;
  }
  for (const char* path : {"/api/summary", "/", "/index.html"}) {
    EXPECT_EQ(status_for(path, "evil.example" + p), "HTTP/1.1 403 Forbidden") << path;
  }
  const std::string refused =
      raw_request(port, "GET /api/summary HTTP/1.1\r\nHost: evil.example" + p + "\r\nConnection: close\r\n\r\n", 8);
  EXPECT_NE(refused.find("start it with --allow-host evil.example"), std::string::npos) << refused;
  EXPECT_NE(refused.find("or studio.test, .lan"), std::string::npos) << refused;
  // No Host at all (HTTP/1.0): not a browser's request.
  const std::string old = raw_request(port, "GET /api/summary HTTP/1.0\r\n\r\n", 8);
  EXPECT_EQ(old.substr(0, old.find("\r\n")), "HTTP/1.1 200 OK") << old;
  server.stop();
  thread.join();
}

// A POST with neither Content-Length nor Transfer-Encoding has an empty body (HTTP/1.1): it is
// answered at once, not after the server's 10 s read timeout (the socket here gives up at 8 s);
// outside the API, 405. PATCH, which no route takes, is 405 as any wrong method.
TEST_F(StudioServer, ABodyWithoutALengthIsEmpty) {
  const std::string session =
      raw_request(port_, "POST /api/steer/sessions HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n", 8);
  EXPECT_EQ(session.rfind("HTTP/1.1 200", 0), 0u) << session;
  EXPECT_NE(session.find("\"session\""), std::string::npos) << session;
  const std::string summary =
      raw_request(port_, "POST /api/summary HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n", 8);
  EXPECT_EQ(summary.rfind("HTTP/1.1 405", 0), 0u) << summary;
  const std::string page =
      raw_request(port_, "POST /index.html HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n", 8);
  EXPECT_EQ(page.rfind("HTTP/1.1 405", 0), 0u) << page;
  auto c = client();
  auto patch = c.Patch("/api/summary", "{}", "application/json");
  ASSERT_TRUE(patch);
  EXPECT_EQ(patch->status, 405);
  EXPECT_TRUE(nlohmann::json::parse(patch->body).contains("error"));
}

// What a scripting client or a download manager sends: HEAD and OPTIONS are answered, a 405
// says which methods the path takes, a Range is heard on a download only (206 with the bytes
// asked; elsewhere the whole answer: it got 200 with a cut JSON), a chunked body is refused
// before it is read, a form body past httplib's 8192 bytes says to send JSON, and a page of
// another origin may not use the API.
TEST_F(StudioServer, AnswersHttpAsClientsUseIt) {
  auto c = client();
  auto head = c.Head("/api/summary");
  ASSERT_TRUE(head);
  EXPECT_EQ(head->status, 200);
  EXPECT_TRUE(head->body.empty());
  for (const auto& [path, allow] :
       {std::pair{"/api/summary", "GET, HEAD, OPTIONS"}, std::pair{"/api/walk", "POST, OPTIONS"}}) {
    auto options = c.Options(path);
    ASSERT_TRUE(options);
    EXPECT_EQ(options->status, 204) << path;
    EXPECT_EQ(options->get_header_value("Allow"), allow) << path;
  }
  auto patch = c.Patch("/api/summary", "{}", "application/json");
  ASSERT_TRUE(patch);
  EXPECT_EQ(patch->status, 405);
  EXPECT_EQ(patch->get_header_value("Allow"), "GET, HEAD, OPTIONS");

  // Range: the whole JSON answer (and the whole error), but a download's bytes asked.
  auto walk = c.Post("/api/walk", R"({"min_frames": 30})", "application/json");
  ASSERT_TRUE(walk);
  ASSERT_EQ(walk->status, 200) << walk->body;
  const int result = nlohmann::json::parse(walk->body)["result"].get<int>();
  const std::string download = "/api/results/" + std::to_string(result) + ".bvh";
  auto whole = c.Get(download);
  ASSERT_TRUE(whole);
  ASSERT_EQ(whole->status, 200);
  ASSERT_GT(whole->body.size(), 100u);
  const httplib::Headers range = {{"Range", "bytes=10-59"}};
  auto part = c.Get(download, range);
  ASSERT_TRUE(part);
  EXPECT_EQ(part->status, 206);
  EXPECT_EQ(part->body, whole->body.substr(10, 50));
  EXPECT_EQ(part->get_header_value("Content-Range"), "bytes 10-59/" + std::to_string(whole->body.size()));
  for (const char* path : {"/api/summary", "/api/clips/999/frames", "/api/results/77777.bvh"}) {
    auto ranged = c.Get(path, range);
    ASSERT_TRUE(ranged);
    EXPECT_NE(ranged->status, 206) << path;
    EXPECT_TRUE(nlohmann::json::accept(ranged->body)) << path << ": " << ranged->body;
  }

  // Several ranges: the whole file, once (each part was sent: 300 of them made 700 MB of a 2 MB
  // script); on a static file and on a download alike.
  std::string many = "bytes=0-99";
  for (int i = 0; i < 300; ++i) many += ",0-99";
  for (const std::string& path : {download, std::string("/js/studio.js")}) {
    auto single = c.Get(path);
    auto multi = c.Get(path, {{"Range", many}});
    ASSERT_TRUE(single && multi);
    ASSERT_EQ(single->status, 200) << path;
    EXPECT_EQ(multi->status, 200) << path;
    EXPECT_EQ(multi->body, single->body) << path;
  }
  auto static_part = c.Get("/js/studio.js", range);
  ASSERT_TRUE(static_part);
  EXPECT_EQ(static_part->status, 206);
  EXPECT_EQ(static_part->body.size(), 50u);

  // A Content-Length that is not one number, or two: 400, not a body read as empty (a walk with
  // its defaults) or cut to the first length.
  for (const std::string lengths : {"abc", "0x10", "+5", "12, 13", "2\r\nContent-Length: 19"}) {
    const std::string answer = raw_request(
        port_,
        "POST /api/walk HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: " +
            lengths + "\r\nConnection: close\r\n\r\n{\"min_frames\": 5000}",
        8);
    EXPECT_EQ(answer.rfind("HTTP/1.1 400", 0), 0u) << lengths << ": " << answer;
    EXPECT_NE(answer.find("the Content-Length must be one number of bytes"), std::string::npos) << answer;
  }
  // A request line with no version names no method or path that was never read.
  const std::string no_version = raw_request(port_, "GET /api/summary\r\nHost: 127.0.0.1\r\n\r\n", 8);
  EXPECT_EQ(no_version.rfind("HTTP/1.1 400", 0), 0u) << no_version;
  EXPECT_NE(no_version.find("the request line is not 'METHOD /path HTTP/1.1'"), std::string::npos) << no_version;

  // A chunked body: refused before it is read.
  const std::string chunked = raw_request(
      port_,
      "POST /api/walk HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\nConnection: close\r\n\r\n"
      "2\r\n{}\r\n0\r\n\r\n",
      8);
  EXPECT_EQ(chunked.rfind("HTTP/1.1 411", 0), 0u) << chunked;
  EXPECT_NE(chunked.find("send the body with a Content-Length"), std::string::npos) << chunked;
  // A form body past 8192 bytes: what to send instead, not that it passes the 1 MiB limit.
  std::string padded = R"({"min_frames": 10})";
  padded.resize(8193, ' ');
  auto form = c.Post("/api/walk", padded, "application/x-www-form-urlencoded");
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 413);
  EXPECT_NE(form->body.find("send JSON as application/json"), std::string::npos) << form->body;
  auto as_json = c.Post("/api/walk", padded, "application/json");
  ASSERT_TRUE(as_json);
  EXPECT_EQ(as_json->status, 200) << as_json->body;

  // A multipart form: the API takes JSON (its fields were dropped and a walk ran with defaults).
  auto multipart = c.Post("/api/walk", httplib::MultipartFormDataItems{{"min_frames", "10", "", ""}});
  ASSERT_TRUE(multipart);
  EXPECT_EQ(multipart->status, 415);
  EXPECT_NE(multipart->body.find("not a multipart form"), std::string::npos) << multipart->body;

  // Origin: this server's own (the studio's page) or none (curl, scripts), not another's.
  const std::string own = "http://127.0.0.1:" + std::to_string(port_);
  auto same = c.Post("/api/steer/sessions", httplib::Headers{{"Origin", own}}, "{}", "application/json");
  ASSERT_TRUE(same);
  EXPECT_EQ(same->status, 200) << same->body;
  auto other = c.Post("/api/steer/sessions", httplib::Headers{{"Origin", "http://evil.example"}}, "{}", "text/plain");
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 403);
  EXPECT_NE(other->body.find("another origin (http://evil.example)"), std::string::npos) << other->body;
}

}  // namespace
}  // namespace mg::test
