#pragma once
// The server's insides, shared by live_server.cpp (listener, HTTP, publishing) and
// viewer_session.cpp (one WebSocket viewer). Private to scenarios/live/.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/beast/http.hpp>

#include "scenarios/live/live_server.hpp"

namespace masnet::live {

using Message = std::shared_ptr<const std::string>;
using Request = boost::beast::http::request<boost::beast::http::string_body>;

class ViewerSession;

struct ServerState {
  ServerState(ServerOptions server_options, std::string page_html);

  /// Called by a viewer's connection on the server's thread.
  void viewer_joined(ViewerSession* viewer);
  void viewer_left(ViewerSession* viewer);
  /// Updates the count and tells the viewers handler.
  void viewers_changed();
  /// A command from a viewer: empty when accepted, else the reason.
  std::string command(const std::string& text);
  std::vector<std::string> greeting_messages();
  /// Hands what was published since the last call to every viewer (server's thread).
  void drain();
  /// Posts a drain unless one is pending; `mutex` is held.
  void schedule_drain_locked();
  /// Whether a request may see the page or open a WebSocket: its Host names this server
  /// (loopback names when bound to loopback, against DNS rebinding) and its Origin, if any,
  /// is the page's own.
  bool request_allowed(const Request& request) const;
  void accept_next();

  // Declared before `io`: handlers that the io_context destroys still find them.
  const ServerOptions options;
  const std::string page;
  bool loopback = true;
  std::uint16_t bound_port = 0;
  std::set<ViewerSession*> viewers;  // server's thread only

  std::atomic<std::size_t> viewer_count{0};
  std::atomic<std::uint64_t> viewers_total{0}, frames_published{0}, frames_sent{0},
      frames_coalesced{0}, controls_dropped{0}, commands{0}, commands_rejected{0},
      requests_refused{0};

  std::mutex mutex;  // guards the handlers, the outgoing messages and `stopped`
  Server::Greeting greeting;
  Server::CommandHandler command_handler;
  Server::ViewersHandler viewers_handler;
  Message outgoing_frame;
  std::deque<Message> outgoing_controls;
  bool drain_posted = false;
  bool stopped = false;
  bool interrupted = false;
  bool interrupts_caught = false;  // the signal set is armed (touched by the caller's thread)
  std::condition_variable interrupt_cv;

  /// Control messages waiting for one viewer, or for all at once, beyond which the oldest go.
  static constexpr std::size_t kMaxPendingControls = 32;

  boost::asio::io_context io{1};
  boost::asio::ip::tcp::acceptor acceptor{io};
  boost::asio::signal_set signals{io};
  std::thread thread;
};

}  // namespace masnet::live
