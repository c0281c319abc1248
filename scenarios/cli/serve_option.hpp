#pragma once
// `masnet run --serve`: the live viewer around one run (docs/live-and-replay.md). The server
// binds before anything is simulated (a taken port is bad input), the run waits, paused, for
// its first viewer unless --serve-start running, and the server stays up after the run until
// interrupted, so that a late viewer still sees the finished run.
#include <cstdint>
#include <memory>
#include <string>

namespace CLI {
class App;
}

namespace masnet::scenarios {
class RunWatcher;
}

namespace masnet::cli {

struct ServeArgs {
  bool serve = false;
  std::uint16_t port = 8080;
  std::string bind = "127.0.0.1";
  std::string start = "paused";
  double speed = 1.0;
};

/// Adds --serve, --port, --bind, --serve-start and --serve-speed to `run`.
void add_serve_options(CLI::App& run, ServeArgs& args);

class LiveSession;
/// Starts serving; on failure prints why and sets `exit_code` (2 for a port that is taken or an
/// address that is not local, 1 otherwise) and returns null.
std::unique_ptr<LiveSession> start_live_session(const ServeArgs& args, int& exit_code);

/// The server and the run's controller while one run is watched.
class LiveSession {
 public:
  /// Binds the server (throws std::runtime_error with the reason), starts it and prints the URL.
  explicit LiveSession(const ServeArgs& args);
  ~LiveSession();
  scenarios::RunWatcher& watcher();
  /// After the run: says so (with the wall time the run was held, of `wall_time_s`) and serves
  /// until SIGINT or SIGTERM.
  void serve_until_interrupted(double wall_time_s);

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace masnet::cli
