#include "scenarios/live/live_server.hpp"

#include <chrono>
#include <csignal>
#include <future>

#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket/rfc6455.hpp>

#include "scenarios/live/server_state.hpp"
#include "scenarios/live/viewer_session.hpp"

namespace masnet::live {
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

namespace {

constexpr std::size_t kMaxRequestBytes = 8192;
constexpr auto kRequestTimeout = std::chrono::seconds(30);

/// The host part of a Host header ("127.0.0.1:8080" -> "127.0.0.1", "[::1]:80" -> "[::1]").
std::string host_name(std::string_view host) {
  if (!host.empty() && host.front() == '[') {
    const auto end = host.find(']');
    return std::string(host.substr(0, end == std::string_view::npos ? host.size() : end + 1));
  }
  return std::string(host.substr(0, host.find(':')));
}

/// One HTTP request, answered and closed: the page, /status, or the upgrade to a viewer.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, ServerState& server)
      : stream_(std::move(socket)), server_(server) {}

  void run() {
    parser_.emplace();
    parser_->header_limit(kMaxRequestBytes);
    parser_->body_limit(kMaxRequestBytes);
    stream_.expires_after(kRequestTimeout);
    http::async_read(stream_, buffer_, *parser_,
                     beast::bind_front_handler(&HttpSession::on_read, shared_from_this()));
  }

 private:
  void on_read(beast::error_code ec, std::size_t /*bytes*/) {
    if (ec) return;  // closed, timed out, too large or malformed: dropped
    Request request = parser_->release();
    if (!server_.request_allowed(request)) {
      ++server_.requests_refused;
      return respond(http::status::forbidden, "text/plain", "forbidden: host or origin\n");
    }
    if (beast::websocket::is_upgrade(request)) {
      if (request.target() != "/ws") {
        ++server_.requests_refused;
        return respond(http::status::not_found, "text/plain", "not found\n");
      }
      if (server_.viewer_count >= server_.options.max_viewers) {
        ++server_.requests_refused;
        return respond(http::status::service_unavailable, "text/plain", "too many viewers\n");
      }
      std::make_shared<ViewerSession>(stream_.release_socket(), server_)->run(std::move(request));
      return;
    }
    if (request.method() != http::verb::get && request.method() != http::verb::head)
      return respond(http::status::method_not_allowed, "text/plain", "GET only\n");
    if (request.target() == "/" || request.target() == "/index.html")
      return respond(http::status::ok, "text/html; charset=utf-8", server_.page);
    if (request.target() == "/status") {
      const nlohmann::json status = {{"viewers", server_.viewer_count.load()},
                                     {"viewers_total", server_.viewers_total.load()},
                                     {"frames_published", server_.frames_published.load()},
                                     {"frames_sent", server_.frames_sent.load()},
                                     {"frames_coalesced", server_.frames_coalesced.load()},
                                     {"commands_rejected", server_.commands_rejected.load()},
                                     {"requests_refused", server_.requests_refused.load()}};
      return respond(http::status::ok, "application/json", status.dump() + "\n");
    }
    respond(http::status::not_found, "text/plain", "not found\n");
  }

  void respond(http::status status, const char* type, std::string body) {
    auto response = std::make_shared<http::response<http::string_body>>(status, 11);
    response->set(http::field::server, "masnet");
    response->set(http::field::content_type, type);
    response->set(http::field::cache_control, "no-store");
    response->keep_alive(false);
    response->body() = std::move(body);
    response->prepare_payload();
    http::async_write(stream_, *response,
                      [self = shared_from_this(), response](beast::error_code, std::size_t) {
                        beast::error_code ignored;
                        self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                      });
  }

  beast::tcp_stream stream_;
  ServerState& server_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
};

}  // namespace

ServerState::ServerState(ServerOptions server_options, std::string page_html)
    : options(std::move(server_options)), page(std::move(page_html)) {}

void ServerState::accept_next() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (ec == asio::error::operation_aborted || !acceptor.is_open()) return;
    if (!ec) std::make_shared<HttpSession>(std::move(socket), *this)->run();
    accept_next();
  });
}

bool ServerState::request_allowed(const Request& request) const {
  const std::string host(request[http::field::host]);
  if (host.empty()) return false;
  const std::string name = host_name(host);
  if (loopback && name != "127.0.0.1" && name != "localhost" && name != "[::1]") return false;
  const auto origin = request.find(http::field::origin);
  // Browsers always send an Origin with a WebSocket handshake; programs may not.
  return origin == request.end() || origin->value() == "http://" + host;
}

void ServerState::viewer_joined(ViewerSession* viewer) {
  viewers.insert(viewer);
  ++viewers_total;
  viewers_changed();
}

void ServerState::viewer_left(ViewerSession* viewer) {
  viewers.erase(viewer);
  viewers_changed();
}

void ServerState::viewers_changed() {
  viewer_count = viewers.size();
  Server::ViewersHandler handler;
  {
    std::lock_guard lock(mutex);
    if (!stopped) handler = viewers_handler;
  }
  if (handler) handler(viewers.size());
}

std::string ServerState::command(const std::string& text) {
  const nlohmann::json parsed = nlohmann::json::parse(text, nullptr, false);
  std::string problem;
  if (parsed.is_discarded() || !parsed.is_object() || !parsed.contains("cmd") ||
      !parsed["cmd"].is_string()) {
    problem = "a command is a JSON object with a string \"cmd\"";
  } else {
    Server::CommandHandler handler;
    {
      std::lock_guard lock(mutex);
      handler = command_handler;
    }
    problem = handler ? handler(parsed) : "this server takes no commands";
  }
  if (problem.empty())
    ++commands;
  else
    ++commands_rejected;
  return problem;
}

std::vector<std::string> ServerState::greeting_messages() {
  Server::Greeting source;
  {
    std::lock_guard lock(mutex);
    source = greeting;
  }
  return source ? source() : std::vector<std::string>{};
}

void ServerState::schedule_drain_locked() {
  // One drain pending at most: however fast the run publishes, the io_context's queue holds
  // one handler, and the drain takes whatever is newest.
  if (drain_posted || stopped) return;
  drain_posted = true;
  asio::post(io, [this] { drain(); });
}

void ServerState::drain() {
  Message frame;
  std::deque<Message> controls;
  {
    std::lock_guard lock(mutex);
    frame = std::move(outgoing_frame);
    outgoing_frame.reset();
    controls.swap(outgoing_controls);
    drain_posted = false;
  }
  for (ViewerSession* viewer : viewers) {
    if (frame) viewer->send_frame(frame);
    for (const Message& control : controls)
      viewer->send_control(control);
  }
}

Server::Server(ServerOptions options, std::string page_html)
    : state_(std::make_shared<ServerState>(std::move(options), std::move(page_html))) {
  ServerState& s = *state_;
  beast::error_code ec;
  const asio::ip::address address = asio::ip::make_address(s.options.bind_address, ec);
  if (ec)
    throw BindError("'" + s.options.bind_address + "' is not an IP address (give one, e.g. " +
                    "127.0.0.1 or 0.0.0.0)");
  s.loopback = address.is_loopback();
  const tcp::endpoint endpoint(address, s.options.port);
  s.acceptor.open(endpoint.protocol(), ec);
  if (!ec) s.acceptor.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) s.acceptor.bind(endpoint, ec);
  if (!ec) s.acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec)
    throw BindError("cannot listen on " + s.options.bind_address + ":" +
                    std::to_string(s.options.port) + ": " + ec.message());
  s.bound_port = s.acceptor.local_endpoint().port();
}

Server::~Server() {
  stop();
}

void Server::set_greeting(Greeting greeting) {
  std::lock_guard lock(state_->mutex);
  state_->greeting = std::move(greeting);
}
void Server::set_command_handler(CommandHandler handler) {
  std::lock_guard lock(state_->mutex);
  state_->command_handler = std::move(handler);
}
void Server::set_viewers_handler(ViewersHandler handler) {
  std::lock_guard lock(state_->mutex);
  state_->viewers_handler = std::move(handler);
}

void Server::start() {
  ServerState& s = *state_;
  if (s.thread.joinable()) return;
  s.accept_next();
  s.thread = std::thread([&s] { s.io.run(); });
}

void Server::stop() {
  ServerState& s = *state_;
  {
    std::lock_guard lock(s.mutex);
    if (s.stopped) return;
    s.stopped = true;
    s.interrupted = true;
  }
  s.interrupt_cv.notify_all();
  asio::post(s.io, [&s] {
    beast::error_code ignored;
    s.acceptor.close(ignored);
    s.signals.cancel(ignored);
    for (ViewerSession* viewer : s.viewers)
      viewer->close_now();
    s.io.stop();
  });
  if (s.thread.joinable()) s.thread.join();
}

void Server::catch_interrupts() {
  ServerState& s = *state_;
  {
    std::lock_guard lock(s.mutex);
    if (s.interrupts_caught || s.stopped || !s.thread.joinable()) return;  // nobody to arm it
    s.interrupts_caught = true;
  }
  // On the server's thread, which owns the signal set; wait until it is armed.
  std::promise<void> armed;
  asio::post(s.io, [&s, &armed] {
    beast::error_code ec;
    s.signals.add(SIGINT, ec);
    s.signals.add(SIGTERM, ec);
    s.signals.async_wait([&s](beast::error_code error, int /*signal*/) {
      if (error) return;
      {
        std::lock_guard lock(s.mutex);
        s.interrupted = true;
      }
      s.interrupt_cv.notify_all();
    });
    armed.set_value();
  });
  armed.get_future().wait();
}

void Server::wait_for_interrupt() {
  ServerState& s = *state_;
  catch_interrupts();
  std::unique_lock lock(s.mutex);
  s.interrupt_cv.wait(lock, [&s] { return s.interrupted; });
}

void Server::publish_frame(std::string message) {
  ServerState& s = *state_;
  ++s.frames_published;
  std::lock_guard lock(s.mutex);
  if (s.outgoing_frame) ++s.frames_coalesced;  // the server's thread has not caught up
  s.outgoing_frame = std::make_shared<const std::string>(std::move(message));
  s.schedule_drain_locked();
}

void Server::publish_control(std::string message) {
  ServerState& s = *state_;
  std::lock_guard lock(s.mutex);
  if (s.outgoing_controls.size() >= ServerState::kMaxPendingControls) {
    s.outgoing_controls.pop_front();
    ++s.controls_dropped;
  }
  s.outgoing_controls.push_back(std::make_shared<const std::string>(std::move(message)));
  s.schedule_drain_locked();
}

std::uint16_t Server::port() const {
  return state_->bound_port;
}

std::string Server::url() const {
  const std::string& address = state_->options.bind_address;
  const std::string host = address.find(':') != std::string::npos ? "[" + address + "]" : address;
  return "http://" + host + ":" + std::to_string(port()) + "/";
}

ServerStats Server::stats() const {
  const ServerState& s = *state_;
  ServerStats out;
  out.viewers = s.viewer_count;
  out.viewers_total = s.viewers_total;
  out.frames_published = s.frames_published;
  out.frames_sent = s.frames_sent;
  out.frames_coalesced = s.frames_coalesced;
  out.controls_dropped = s.controls_dropped;
  out.commands = s.commands;
  out.commands_rejected = s.commands_rejected;
  out.requests_refused = s.requests_refused;
  return out;
}

}  // namespace masnet::live
