// motiongraph serve GRAPH [--host H] [--port P] [--web-root DIR] [--allow-host NAME...]
// [--max-sessions N]: the web studio (src/studio/) on one graph. Prints "studio: http://HOST:PORT/"
// once it listens; SIGINT and SIGTERM stop it (exit 0): the requests being answered are finished,
// clients still connected after 2 s (or at a second signal) are not waited for.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

#include "cli/commands.h"
#include "studio/host_check.h"
#include "studio/http_server.h"
#include "studio/synthesis_service.h"

namespace mg::cli {

namespace {

struct ServeOptions {
  std::string graph;
  std::string host = "127.0.0.1";
  int port = 8080;
  std::string web_root = MOTIONGRAPH_WEB_ROOT;
  std::vector<std::string> allow_hosts;
  int max_sessions = studio::SessionLimits{}.max_sessions;
};

// Counted by SIGINT / SIGTERM, whichever thread takes them (libraries start threads of their own
// before main, so blocking the signals everywhere is not possible); a watcher polls it.
std::atomic<int> stop_signals = 0;

extern "C" void on_stop_signal(int) { stop_signals.fetch_add(1); }

// How long a stop waits for the clients still connected (an open tab's idle connection, a client
// reading slowly: the server's workers finish each one's request first) before it ends anyway;
// a second signal ends it at once.
constexpr auto kStopWait = std::chrono::seconds(2);

int run_serve(const ServeOptions& o) {
  struct sigaction action = {};
  action.sa_handler = on_stop_signal;
  action.sa_flags = SA_RESTART;  // the server's system calls go on; the watcher stops it
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);

  auto service = studio::SynthesisService::load(o.graph);
  if (!service) return fail(service.error());
  studio::SessionLimits limits;
  limits.max_sessions = o.max_sessions;
  if (Status set = (*service)->set_session_limits(limits); !set) return fail(set.error());
  const studio::StudioApi api(**service);
  studio::HttpServer server(api, o.web_root);
  auto port = server.bind(o.host, o.port);
  if (!port) return fail(port.error());
  if (Status allowed = server.allow_hosts(o.allow_hosts); !allowed) return fail(allowed.error());
  const bool every_interface = o.host == "0.0.0.0" || o.host == "::";
  char name[256] = {};
  const bool named = gethostname(name, sizeof name - 1) == 0 && name[0] != '\0';
  // Served to the network: the machine's own name (as printed below, and as .local by mDNS)
  // is one a browser opens it under.
  if (every_interface && named && studio::check_allowed_host(name)) {
    (void)server.allow_hosts({name, std::string(name) + ".local"});
  }

  std::atomic<bool> done = false;
  std::thread signal_thread([&] {
    while (!done) {
      if (stop_signals != 0) {
        std::fprintf(stderr, "motiongraph: stopping the studio\n");
        server.stop();
        const auto asked = std::chrono::steady_clock::now();
        while (!done) {
          if (stop_signals > 1 || std::chrono::steady_clock::now() - asked > kStopWait) {
            // (the studio writes no file: nothing is left half-written)
            std::fprintf(stderr, "motiongraph: stopped without waiting for the clients still connected\n");
            std::_Exit(0);
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  const std::string shown_host = o.host.find(':') != std::string::npos ? "[" + o.host + "]" : o.host;
  fmt::print("studio: http://{}:{}/\n", shown_host, *port);
  if (every_interface) {
    // Every interface: the printed address is not one a browser opens; say what to open.
    fmt::print("  listening on every network interface: open http://{}:{}/ from another machine "
               "(anyone who can reach it can use the studio)\n",
               named ? std::string(name) : std::string("THIS-MACHINE"), *port);
  }
  std::fflush(stdout);
  const Status served = server.run();
  done = true;
  signal_thread.join();
  if (!served) return fail(served.error());
  return 0;
}

}  // namespace

Command add_serve_command(CLI::App& app) {
  auto o = std::make_shared<ServeOptions>();
  CLI::App* sub = app.add_subcommand(
      "serve", "Serve the web studio on a graph: watch clips, inspect transitions, synthesize paths and steer\n"
               "the character in a browser. Prints the address once listening; Ctrl-C stops it.");
  sub->add_option("GRAPH", o->graph, "A .mgraph file written by 'motiongraph build'")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--host", o->host, "Address to listen on (loopback by default)")->capture_default_str();
  sub->add_option("--port", o->port, "Port (0: pick a free one)")->capture_default_str()->check(CLI::Range(0, 65535));
  sub->add_option("--web-root", o->web_root, "The studio's front-end folder (web/ of the source tree)")
      ->capture_default_str();
  sub->add_option("--allow-host", o->allow_hosts,
                  "A name the studio may be opened under besides IP addresses and localhost (repeatable; "
                  "'.lan' allows lan and every name under it). Requests addressed to other names are refused: a "
                  "page of another site could reach the studio under a name of its own. Served on every interface, "
                  "the machine's name (and NAME.local) is allowed too")
      ->check([](const std::string& entry) {
        const Status checked = studio::check_allowed_host(entry);
        return checked ? std::string() : checked.error().message;
      });
  sub->add_option("--max-sessions", o->max_sessions,
                  fmt::format("Steering sessions at once (browser tabs steering). A new one takes the place of the "
                              "least recently stepped once that has not been stepped for {:g} s; while all are in "
                              "use, it is refused (503)",
                              studio::SessionLimits{}.busy_s))
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  return {sub, [o] { return run_serve(*o); }};
}

}  // namespace mg::cli
