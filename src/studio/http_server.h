// The studio on the network: cpp-httplib serving the front-end (static files from a web root,
// three.js among them from its node_modules) and StudioApi under /api/. Requests are served
// by a thread pool, so several clients are answered at once; bodies are bounded; stop() ends
// run() from any thread.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "studio/studio_api.h"

namespace httplib {
class Server;
}

namespace mg::studio {

class HttpServer {
 public:
  static constexpr size_t kMaxBodyBytes = 1 << 20;

  // web_root: the folder served at / (index.html); empty: the API only.
  HttpServer(const StudioApi& api, std::string web_root);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds host:port (port 0: a free one) and returns the port bound. Fails when the web root
  // has no index.html or no three.js (web/node_modules, from npm ci). A host given by name is
  // one the server answers to (allow_hosts).
  Result<int> bind(const std::string& host, int port);
  // Names besides IP addresses and localhost that requests may be addressed to (the Host
  // header; studio/host_check.h says why others are refused), each checked by
  // check_allowed_host; before run().
  Status allow_hosts(const std::vector<std::string>& names);
  // Serves until stop(); call after bind().
  Status run();
  void stop();

 private:
  const StudioApi* api_;
  std::string web_root_;
  std::vector<std::string> allowed_hosts_;  // lower case
  std::unique_ptr<httplib::Server> server_;
};

}  // namespace mg::studio
