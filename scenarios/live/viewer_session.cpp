#include "scenarios/live/viewer_session.hpp"

#include <chrono>

namespace masnet::live {
namespace beast = boost::beast;
namespace websocket = beast::websocket;

ViewerSession::ViewerSession(boost::asio::ip::tcp::socket&& socket, ServerState& server)
    : ws_(std::move(socket)), server_(server) {}

ViewerSession::~ViewerSession() {
  if (joined_) server_.viewer_left(this);
}

void ViewerSession::run(Request request) {
  // Beast's server timeouts (handshake 30 s, pings when idle) with our idle limit: a viewer
  // that neither answers pings nor sends anything is dropped.
  websocket::stream_base::timeout timeouts =
      websocket::stream_base::timeout::suggested(beast::role_type::server);
  timeouts.idle_timeout =
      std::chrono::milliseconds(static_cast<long long>(server_.options.idle_timeout_s * 1000.0));
  timeouts.keep_alive_pings = true;
  ws_.set_option(timeouts);
  ws_.read_message_max(server_.options.max_command_bytes);
  ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& response) {
    response.set(beast::http::field::server, "masnet");
  }));
  beast::get_lowest_layer(ws_).expires_never();  // the websocket timeouts take over
  ws_.async_accept(request,
                   beast::bind_front_handler(&ViewerSession::on_accept, shared_from_this()));
}

void ViewerSession::on_accept(beast::error_code ec) {
  if (ec) return;  // the connection ends with its last handler
  joined_ = true;
  server_.viewer_joined(this);
  for (std::string& message : server_.greeting_messages())
    send_control(std::make_shared<const std::string>(std::move(message)));
  read_next();
}

void ViewerSession::read_next() {
  ws_.async_read(buffer_, beast::bind_front_handler(&ViewerSession::on_read, shared_from_this()));
}

void ViewerSession::on_read(beast::error_code ec, std::size_t /*bytes*/) {
  // Closed, reset, timed out or over read_message_max (Beast then closes with 1009 "too
  // big"): the connection ends here.
  if (ec) {
    closed_ = true;
    return;
  }
  // Binary messages are not commands: read as empty text, they are refused as malformed.
  const std::string text = ws_.got_text() ? beast::buffers_to_string(buffer_.data()) : "";
  buffer_.consume(buffer_.size());
  if (std::string problem = server_.command(text); !problem.empty()) {
    nlohmann::json reply = {{"type", "error"}, {"message", problem}};
    send_control(std::make_shared<const std::string>(reply.dump()));
  }
  read_next();
}

void ViewerSession::send_frame(const Message& frame) {
  if (closed_) return;
  if (pending_frame_) ++server_.frames_coalesced;
  pending_frame_ = frame;
  write_next();
}

void ViewerSession::send_control(const Message& control) {
  if (closed_) return;
  if (pending_controls_.size() >= ServerState::kMaxPendingControls) {
    pending_controls_.pop_front();
    ++server_.controls_dropped;
  }
  pending_controls_.push_back(control);
  write_next();
}

void ViewerSession::write_next() {
  if (writing_ || closed_ || !joined_) return;
  if (!pending_controls_.empty()) {
    writing_ = std::move(pending_controls_.front());
    pending_controls_.pop_front();
    writing_frame_ = false;
  } else if (pending_frame_) {
    writing_ = std::move(pending_frame_);
    pending_frame_.reset();
    writing_frame_ = true;
  } else {
    return;
  }
  ws_.text(true);
  ws_.async_write(boost::asio::buffer(*writing_),
                  beast::bind_front_handler(&ViewerSession::on_write, shared_from_this()));
}

void ViewerSession::on_write(beast::error_code ec, std::size_t /*bytes*/) {
  if (writing_frame_ && !ec) ++server_.frames_sent;
  writing_.reset();
  if (ec) {
    closed_ = true;
    return;
  }
  write_next();
}

void ViewerSession::close_now() {
  closed_ = true;
  beast::error_code ignored;
  beast::get_lowest_layer(ws_).socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both,
                                                 ignored);
  beast::get_lowest_layer(ws_).socket().close(ignored);
}

}  // namespace masnet::live
