#include "studio/http_server.h"

#include <filesystem>

#include <fmt/format.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"

namespace mg::studio {

namespace {

ApiRequest to_api_request(const httplib::Request& req) {
  ApiRequest r;
  r.method = req.method;
  r.path = req.path;
  for (const auto& [key, value] : req.params) r.query.emplace(key, value);
  r.body = req.body;
  return r;
}

void send(const ApiResponse& response, httplib::Response& res) {
  res.status = response.status;
  if (!response.file_name.empty()) {
    res.set_header("Content-Disposition", fmt::format("attachment; filename=\"{}\"", response.file_name));
  }
  res.set_header("Cache-Control", "no-store");
  res.set_content(response.body, response.content_type.c_str());
}

}  // namespace

HttpServer::HttpServer(const StudioApi& api, std::string web_root)
    : api_(&api), web_root_(std::move(web_root)), server_(std::make_unique<httplib::Server>()) {
  httplib::Server& s = *server_;
  s.set_payload_max_length(kMaxBodyBytes);
  s.set_read_timeout(10, 0);
  s.set_write_timeout(10, 0);
  // Wait for connections with poll() and a timeout rather than in a bare accept(), so that
  // stop() from another thread is seen within 0.1 s whatever the accept() is doing.
  s.set_idle_interval(0, 100000);
  auto api_handler = [this](const httplib::Request& req, httplib::Response& res) {
    send(api_->handle(to_api_request(req)), res);
  };
  // A request with a body method but neither Content-Length nor Transfer-Encoding has an empty
  // body (HTTP/1.1); httplib would read one until its read timeout, holding a worker 10 s.
  s.set_pre_routing_handler([api_handler](const httplib::Request& req, httplib::Response& res) {
    // A NUL byte (%00) in the path: the file opened would end there, its type read past it
    // ("index.html%00.png" served index.html as a PNG).
    if (req.path.find('\0') != std::string::npos) {
      res.status = 400;
      res.set_content(json_text(nlohmann::json({{"error", "the path holds a NUL byte (%00)"}})), "application/json");
      return httplib::Server::HandlerResponse::Handled;
    }
    const bool body_method = req.method == "POST" || req.method == "PUT" || req.method == "PATCH";
    if (!body_method || req.has_header("Content-Length") || req.has_header("Transfer-Encoding")) {
      return httplib::Server::HandlerResponse::Unhandled;
    }
    if (req.path.rfind("/api/", 0) == 0) {
      api_handler(req, res);
    } else {
      res.status = 405;
      res.set_content(json_text(nlohmann::json({{"error", fmt::format("{} {}: HTTP 405", req.method, req.path)}})),
                      "application/json");
    }
    return httplib::Server::HandlerResponse::Handled;
  });
  s.Get(R"(/api/.*)", api_handler);
  s.Post(R"(/api/.*)", api_handler);
  s.Put(R"(/api/.*)", api_handler);
  s.Patch(R"(/api/.*)", api_handler);
  s.Delete(R"(/api/.*)", api_handler);
  // Workers enough that a browser's idle keep-alive connections (each holds one for up to 5 s)
  // leave others free.
  s.new_task_queue = [] { return new httplib::ThreadPool(32); };
  s.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    const std::string message =
        res.status == 413 ? fmt::format("the request body is larger than {} bytes", kMaxBodyBytes)
                          : fmt::format("{} {}: HTTP {}", req.method, req.path, res.status);
    res.set_content(json_text(nlohmann::json({{"error", message}})), "application/json");
  });
  s.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    res.status = 500;
    res.set_content(R"({"error": "internal error"})", "application/json");
  });
  if (!web_root_.empty()) s.set_mount_point("/", web_root_);
}

HttpServer::~HttpServer() = default;

Result<int> HttpServer::bind(const std::string& host, int port) {
  if (!web_root_.empty() && !std::filesystem::is_regular_file(std::filesystem::path(web_root_) / "index.html")) {
    return Error{web_root_, 0, "no index.html here: --web-root must be the studio's web/ folder"};
  }
  if (!web_root_.empty() &&
      !std::filesystem::is_regular_file(std::filesystem::path(web_root_) / "node_modules/three/build/three.module.js")) {
    return Error{web_root_, 0, "three.js is not installed here: run 'npm ci' in this folder (scripts/install-deps.sh does)"};
  }
  if (port < 0 || port > 65535) return Error{"", 0, fmt::format("port {} is not in 0..65535", port)};
  const int bound =
      port == 0 ? server_->bind_to_any_port(host.c_str()) : (server_->bind_to_port(host.c_str(), port) ? port : -1);
  if (bound < 0) {
    return Error{"", 0, fmt::format("cannot listen on {}:{} (in use, or not an address of this machine)", host, port)};
  }
  return bound;
}

Status HttpServer::run() {
  if (!server_->listen_after_bind()) return Error{"", 0, "the server stopped listening unexpectedly"};
  return Ok{};
}

void HttpServer::stop() { server_->stop(); }

}  // namespace mg::studio
