#pragma once
// A raw WebSocket viewer for the live server's tests (Beast's synchronous client), with a
// receive timeout so that a test fails instead of hanging.
#include <sys/socket.h>
#include <sys/time.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

namespace masnet::test {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = boost::asio::ip::tcp;

inline void set_receive_timeout(tcp::socket& socket, int seconds) {
  timeval timeout{seconds, 0};
  ::setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
}

struct RawViewer {
  boost::asio::io_context io;
  websocket::stream<tcp::socket> ws{io};

  /// Connects and completes the handshake (throws beast::system_error when refused).
  explicit RawViewer(std::uint16_t port, const std::string& origin = "",
                     const std::string& host = "") {
    tcp::resolver resolver(io);
    boost::asio::connect(ws.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    set_receive_timeout(ws.next_layer(), 20);
    ws.set_option(websocket::stream_base::decorator([origin](websocket::request_type& request) {
      if (!origin.empty()) request.set(beast::http::field::origin, origin);
    }));
    ws.handshake(host.empty() ? "127.0.0.1:" + std::to_string(port) : host, "/ws");
  }

  nlohmann::json read() {
    beast::flat_buffer buffer;
    ws.read(buffer);
    return nlohmann::json::parse(beast::buffers_to_string(buffer.data()));
  }
  /// Reads until a message of `type` arrives; throws when the connection fails first.
  nlohmann::json read_type(const std::string& type) {
    for (;;) {
      nlohmann::json message = read();
      if (message.value("type", "") == type) return message;
    }
  }
  void send(const std::string& text) { ws.write(boost::asio::buffer(text)); }
  /// Closes the TCP connection without a WebSocket close: an abrupt disconnect.
  void drop() {
    beast::error_code ignored;
    ws.next_layer().shutdown(tcp::socket::shutdown_both, ignored);
    ws.next_layer().close(ignored);
  }
};

/// Polls `done` every 10 ms for up to 20 s (a condition to reach, not a timing to assert).
inline bool eventually(const std::function<bool()>& done) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < until) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return done();
}

}  // namespace masnet::test
