#pragma once
// One WebSocket viewer: reads its commands, writes frames and control messages one at a time.
// At most one frame waits (a newer one replaces it) and at most kMaxPendingControls control
// messages, so a viewer that never reads costs a bounded amount of memory.
#include <deque>
#include <memory>

#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>

#include "scenarios/live/server_state.hpp"

namespace masnet::live {

class ViewerSession : public std::enable_shared_from_this<ViewerSession> {
 public:
  ViewerSession(boost::asio::ip::tcp::socket&& socket, ServerState& server);
  ~ViewerSession();

  /// Completes the WebSocket handshake of `request`, then greets and starts reading.
  void run(Request request);
  void send_frame(const Message& frame);
  void send_control(const Message& control);
  /// Closes the connection at once (the server stops).
  void close_now();

 private:
  void on_accept(boost::beast::error_code ec);
  void read_next();
  void on_read(boost::beast::error_code ec, std::size_t bytes);
  void write_next();
  void on_write(boost::beast::error_code ec, std::size_t bytes);

  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  ServerState& server_;
  boost::beast::flat_buffer buffer_;
  Message pending_frame_;
  std::deque<Message> pending_controls_;
  Message writing_;  // kept alive while its write is under way
  bool writing_frame_ = false;
  bool joined_ = false;
  bool closed_ = false;
};

}  // namespace masnet::live
