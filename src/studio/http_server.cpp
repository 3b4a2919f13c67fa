#include "studio/http_server.h"

#include <cctype>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"
#include "motiongraph/core/text.h"
#include "studio/host_check.h"

namespace mg::studio {

namespace {

ApiRequest to_api_request(const httplib::Request& req) {
  ApiRequest r;
  r.method = req.method;
  r.path = req.path;
  r.query.insert(req.params.begin(), req.params.end());
  r.body = req.body;
  return r;
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(json_text(nlohmann::json({{"error", message}})), "application/json");
}

// A Range header is heard on a download (GET of a result that is there: 206 Partial Content, a
// download resumed) and nowhere else: httplib cut every answer to the range asked, with the
// status 200 of a whole one (a truncated JSON answer, an error's first bytes).
void send(const httplib::Request& req, const ApiResponse& response, httplib::Response& res) {
  const bool ranged = response.status == 200 && !response.file_name.empty() && req.method == "GET";
  if (!ranged) const_cast<httplib::Request&>(req).ranges.clear();  // (the server's own request object)
  if (!ranged || req.ranges.empty()) res.status = response.status;  // else httplib's 206
  if (!response.file_name.empty()) {
    res.set_header("Content-Disposition", fmt::format("attachment; filename=\"{}\"", response.file_name));
  }
  if (!response.allow.empty()) res.set_header("Allow", response.allow);
  res.set_header("Cache-Control", "no-store");
  if (response.status != 204) res.set_content(response.body, response.content_type.c_str());
}

// "host:port" of an Origin header ("http://host:port"), lower case; empty when it has no scheme.
std::string origin_authority(const std::string& origin) {
  const size_t scheme = origin.find("://");
  if (scheme == std::string::npos) return "";
  return ascii_lower(origin.substr(scheme + 3));
}

}  // namespace

HttpServer::HttpServer(const StudioApi& api, std::string web_root)
    : api_(&api), web_root_(std::move(web_root)), server_(std::make_unique<httplib::Server>()) {
  httplib::Server& s = *server_;
  s.set_payload_max_length(kMaxBodyBytes);
  s.set_read_timeout(10, 0);
  // A steering client asks about 5 times a second: a connection kept for 100 requests, not 5
  // (it reconnected every second).
  s.set_keep_alive_max_count(100);
  s.set_write_timeout(10, 0);
  // Wait for connections with poll() and a timeout rather than in a bare accept(), so that
  // stop() from another thread is seen within 0.1 s whatever the accept() is doing.
  s.set_idle_interval(0, 100000);
  auto api_handler = [this](const httplib::Request& req, httplib::Response& res) {
    send(req, api_->handle(to_api_request(req)), res);
  };
  // A request with a body method but neither Content-Length nor Transfer-Encoding has an empty
  // body (HTTP/1.1); httplib would read one until its read timeout, holding a worker 10 s.
  s.set_pre_routing_handler([this, api_handler](const httplib::Request& req, httplib::Response& res) {
    // A request addressed to a name the studio does not answer to (studio/host_check.h): a page
    // of another site that rebound its name to this machine. A client that sends no Host
    // (HTTP/1.0) is not a browser.
    if (req.has_header("Host") && !host_allowed(req.get_header_value("Host"), allowed_hosts_)) {
      const std::string header = req.get_header_value("Host");
      const std::string name = host_of_header(header);
      send_error(res, 403,
                 fmt::format("the studio answers requests addressed to an IP address or localhost{}, not to {} (a "
                             "page of another site may reach this machine under a name of its own): to open it "
                             "under that name, start it with --allow-host {}",
                             allowed_hosts_.empty() ? "" : fmt::format(" or {}", fmt::join(allowed_hosts_, ", ")),
                             mg::quoted(header.substr(0, 100)), name.empty() ? "NAME" : name));
      return httplib::Server::HandlerResponse::Handled;
    }
    // A NUL byte (%00) in the path: the file opened would end there, its type read past it
    // ("index.html%00.png" served index.html as a PNG).
    if (req.path.find('\0') != std::string::npos) {
      send_error(res, 400, "the path holds a NUL byte (%00)");
      return httplib::Server::HandlerResponse::Handled;
    }
    // A Range of several parts is answered with the whole file, as HTTP lets a server do: httplib
    // sent each part, overlapping or not, so that 300 ranges of a 2 MB script in a 1 KB request
    // made a 700 MB answer (and as much memory). Browsers ask for one range.
    if (req.ranges.size() > 1) const_cast<httplib::Request&>(req).ranges.clear();  // (the server's own)
    // A Content-Length that is not a number httplib read as 0 (a walk ran with its defaults, the
    // body ignored), and of two that differ it took the first.
    if (req.has_header("Content-Length")) {
      const std::string length = req.get_header_value("Content-Length");
      bool agreed = is_ascii_digits(length);
      for (size_t i = 1; i < req.get_header_value_count("Content-Length"); ++i) {
        agreed = agreed && req.get_header_value("Content-Length", i) == length;
      }
      if (!agreed) {
        send_error(res, 400, fmt::format("the Content-Length must be one number of bytes, not {}",
                                         mg::quoted(length)));
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    // A chunked body has no length to check before it is read (httplib read 800 MB of one whole,
    // past the limit on bodies); a client sends JSON with its length.
    if (req.has_header("Transfer-Encoding")) {
      send_error(res, 411,
                 fmt::format("send the body with a Content-Length (Transfer-Encoding '{}' is not taken; a body "
                             "holds at most {} bytes)",
                             req.get_header_value("Transfer-Encoding"), kMaxBodyBytes));
      return httplib::Server::HandlerResponse::Handled;
    }
    // A multipart form's fields are not a body httplib passes on (the API saw none, and a walk ran
    // with its defaults): the API takes JSON.
    if (req.path.rfind("/api/", 0) == 0 && req.get_header_value("Content-Type").rfind("multipart/", 0) == 0) {
      send_error(res, 415, "the API takes a JSON body (Content-Type application/json), not a multipart form");
      return httplib::Server::HandlerResponse::Handled;
    }
    // A page of another site may send the API requests a browser sends without asking (a form's
    // POST: a 200 m path, sessions that push the user's out); an Origin that is not this server's
    // own is refused. Tools that send no Origin (curl, scripts) are not concerned.
    if (req.path.rfind("/api/", 0) == 0 && req.has_header("Origin")) {
      if (origin_authority(req.get_header_value("Origin")) != ascii_lower(req.get_header_value("Host"))) {
        send_error(res, 403,
                   fmt::format("a page of another origin ({}) may not use the studio's API",
                               req.get_header_value("Origin").substr(0, 100)));
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    const bool body_method = req.method == "POST" || req.method == "PUT" || req.method == "PATCH";
    if (!body_method || req.has_header("Content-Length")) {
      return httplib::Server::HandlerResponse::Unhandled;
    }
    if (req.path.rfind("/api/", 0) == 0) {
      api_handler(req, res);
    } else {
      send_error(res, 405, fmt::format("{} {}: HTTP 405", req.method, req.path));
    }
    return httplib::Server::HandlerResponse::Handled;
  });
  s.Get(R"(/api/.*)", api_handler);
  s.Post(R"(/api/.*)", api_handler);
  s.Put(R"(/api/.*)", api_handler);
  s.Patch(R"(/api/.*)", api_handler);
  s.Delete(R"(/api/.*)", api_handler);
  s.Options(R"(/api/.*)", api_handler);
  // Workers enough that a browser's idle keep-alive connections (each holds one for up to 5 s)
  // leave others free.
  s.new_task_queue = [] { return new httplib::ThreadPool(32); };
  s.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    // A body sent as a form (curl -d, urllib without a Content-Type) is held to httplib's 8192
    // bytes for forms, whatever its length is below kMaxBodyBytes.
    const bool form = req.get_header_value("Content-Type").rfind("application/x-www-form-urlencoded", 0) == 0;
    const std::string message =
        res.status == 413 && form
            ? fmt::format("a body sent as a form (Content-Type application/x-www-form-urlencoded, which curl -d "
                          "sends) holds at most 8192 bytes: send JSON as application/json (curl -H 'Content-Type: "
                          "application/json'), up to {} bytes",
                          kMaxBodyBytes)
        : res.status == 413 ? fmt::format("the request body is larger than {} bytes", kMaxBodyBytes)
        // A request line httplib could not read leaves no method or path to name.
        : res.status == 414 ? std::string("the request line is longer than 8192 bytes: HTTP 414")
        : req.method.empty() || req.path.empty()
            ? fmt::format("the request line is not 'METHOD /path HTTP/1.1': HTTP {}", res.status)
            : fmt::format("{} {}: HTTP {}", req.method, req.path, res.status);
    res.set_content(json_text(nlohmann::json({{"error", message}})), "application/json");
  });
  s.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    res.status = 500;
    res.set_content(R"({"error": "internal error"})", "application/json");
  });
  // A page's file whose Range the pre-routing handler dropped: httplib had set 206 already.
  s.set_post_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    if (res.status == 206 && req.ranges.empty()) res.status = 200;
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
  if (!host.empty() && check_allowed_host(host) && !host_allowed(host, {})) allowed_hosts_.push_back(ascii_lower(host));
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

Status HttpServer::allow_hosts(const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    if (Status checked = check_allowed_host(name); !checked) {
      return Error{"", 0, "allowed host " + checked.error().message};
    }
    allowed_hosts_.push_back(ascii_lower(name));
  }
  return Ok{};
}

void HttpServer::stop() { server_->stop(); }

}  // namespace mg::studio
