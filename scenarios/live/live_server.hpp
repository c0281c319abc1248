#pragma once
// The live viewer's server (docs/live-and-replay.md): one page over HTTP and the run's frames
// over a WebSocket, on a thread of its own. Bounded whatever the viewers do: each viewer holds
// at most one pending frame (a newer one replaces it, counted as coalesced) and a few control
// messages; commands are small JSON texts; a viewer that stalls or misbehaves is dropped
// without the simulation ever waiting for it.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace masnet::live {

struct ServerState;  // server_state.hpp

struct ServerOptions {
  std::string bind_address = "127.0.0.1";  ///< loopback unless the user says otherwise
  std::uint16_t port = 8080;               ///< 0 picks a free port
  std::size_t max_viewers = 256;           ///< more are refused (HTTP 503)
  std::size_t max_command_bytes = 4096;    ///< a longer WebSocket message closes the viewer
  double idle_timeout_s = 120.0;           ///< a viewer silent this long (no pong) is dropped
};

/// Counters since the server started (all viewers).
struct ServerStats {
  std::size_t viewers = 0;  ///< WebSocket viewers connected now
  std::uint64_t viewers_total = 0;
  std::uint64_t frames_published = 0;   ///< frames handed to the server by the run
  std::uint64_t frames_sent = 0;        ///< frames written to a viewer
  std::uint64_t frames_coalesced = 0;   ///< frames replaced by a newer one before they were sent
  std::uint64_t controls_dropped = 0;   ///< control messages dropped from a full queue
  std::uint64_t commands = 0;           ///< commands accepted
  std::uint64_t commands_rejected = 0;  ///< malformed or unknown commands
  std::uint64_t requests_refused = 0;   ///< bad host or origin, too many viewers, bad path
};

/// The address could not be bound (port taken, address not local, bad address).
class BindError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Server {
 public:
  /// What a new viewer is sent first (the scene's header, the history so far, the latest
  /// frame, the status). Called on the server's thread.
  using Greeting = std::function<std::vector<std::string>()>;
  /// A viewer's command (a JSON object with "cmd"); returns an empty string when accepted,
  /// otherwise the reason, sent back to that viewer. Called on the server's thread.
  using CommandHandler = std::function<std::string(const nlohmann::json&)>;
  /// The number of viewers changed. Called on the server's thread.
  using ViewersHandler = std::function<void(std::size_t viewers)>;

  /// Binds and listens at once (throws BindError), so that a taken port is reported before
  /// anything is simulated. Serves nothing until `start`.
  Server(ServerOptions options, std::string page_html);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  void set_greeting(Greeting greeting);
  void set_command_handler(CommandHandler handler);
  void set_viewers_handler(ViewersHandler handler);

  /// Starts the server's thread.
  void start();
  /// Closes every connection and the listener, and joins the thread. Idempotent.
  void stop();
  /// From now on SIGINT and SIGTERM end wait_for_interrupt instead of the process; returns
  /// once the server's thread has taken them over. Call it before telling the user to press
  /// Ctrl-C: a signal that came in between would otherwise kill the process.
  void catch_interrupts();
  /// Blocks until SIGINT or SIGTERM arrives (or `stop` is called from elsewhere); catches them
  /// first if catch_interrupts was not called.
  void wait_for_interrupt();

  /// To every viewer: a frame (coalesced per viewer) or a control message (kept in order).
  /// Thread-safe and never blocks on a viewer.
  void publish_frame(std::string message);
  void publish_control(std::string message);

  std::uint16_t port() const;
  /// http://ADDRESS:PORT/ (the bound address; 127.0.0.1 for loopback).
  std::string url() const;
  ServerStats stats() const;

 private:
  std::shared_ptr<ServerState> state_;
};

}  // namespace masnet::live
