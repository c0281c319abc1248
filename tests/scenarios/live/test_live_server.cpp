// The live viewer's server against misbehaving clients (docs/live-and-replay.md, "Robustness"):
// malformed and oversized messages, abrupt disconnects, a viewer that never reads, 50 viewers,
// a port already taken, foreign origins and hosts. Frames here are synthetic; test_live_run.cpp
// serves real runs.
#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "live_client.hpp"
#include "scenarios/live/live_server.hpp"

using masnet::live::Server;
using masnet::live::ServerOptions;
using masnet::test::eventually;
using masnet::test::RawViewer;

namespace {

std::unique_ptr<Server> test_server(ServerOptions options = {}) {
  options.port = 0;
  auto server = std::make_unique<Server>(options, "<!doctype html><title>test</title>");
  server->set_greeting([] { return std::vector<std::string>{R"({"type":"hello"})"}; });
  server->set_command_handler([](const nlohmann::json& command) -> std::string {
    return command["cmd"] == "pause" ? "" : "unknown command";
  });
  server->start();
  return server;
}

std::string frame_text(int i, std::size_t padding = 0) {
  return R"({"type":"frame","i":)" + std::to_string(i) + R"(,"pad":")" + std::string(padding, 'x') +
         "\"}";
}

}  // namespace

TEST_CASE("live server: a viewer is greeted and receives frames, and the count returns to zero") {
  auto server = test_server();
  {
    RawViewer viewer(server->port());
    CHECK(viewer.read().value("type", "") == "hello");
    REQUIRE(eventually([&] { return server->stats().viewers == 1; }));
    server->publish_frame(frame_text(7));
    CHECK(viewer.read_type("frame")["i"] == 7);
    viewer.ws.close(masnet::test::websocket::close_code::normal);
  }
  CHECK(eventually([&] { return server->stats().viewers == 0; }));
  CHECK(server->stats().frames_sent == 1);
}

TEST_CASE("live server: malformed commands are answered with an error and counted") {
  auto server = test_server();
  RawViewer viewer(server->port());
  viewer.read_type("hello");
  for (const std::string bad : {"not json", "[1,2]", R"({"cmd":3})", R"({"nocmd":"pause"})"}) {
    viewer.send(bad);
    CHECK(viewer.read_type("error")["message"] ==
          "a command is a JSON object with a string \"cmd\"");
  }
  viewer.send(R"({"cmd":"fly"})");
  CHECK(viewer.read_type("error")["message"] == "unknown command");
  viewer.send(R"({"cmd":"pause"})");
  server->publish_frame(frame_text(1));
  CHECK(viewer.read_type("frame")["i"] == 1);  // still served, no error for the good one
  CHECK(eventually([&] { return server->stats().commands == 1; }));
  CHECK(server->stats().commands_rejected == 5);
}

TEST_CASE("live server: an oversized message closes that viewer only") {
  ServerOptions options;
  options.max_command_bytes = 1024;
  auto server = test_server(options);
  RawViewer good(server->port());
  RawViewer bad(server->port());
  REQUIRE(eventually([&] { return server->stats().viewers == 2; }));
  bad.send(std::string(4096, 'a'));
  CHECK_THROWS_AS(bad.read_type("never"), masnet::test::beast::system_error);
  CHECK(eventually([&] { return server->stats().viewers == 1; }));
  server->publish_frame(frame_text(2));
  CHECK(good.read_type("frame")["i"] == 2);
}

TEST_CASE("live server: abrupt disconnects while frames stream leave no viewer behind") {
  auto server = test_server();
  std::atomic<bool> publishing{true};
  std::thread publisher([&] {
    for (int i = 0; publishing; ++i) {
      server->publish_frame(frame_text(i, 2000));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  for (int round = 0; round < 20; ++round) {
    RawViewer viewer(server->port());
    viewer.read_type("frame");
    viewer.drop();
  }
  CHECK(eventually([&] { return server->stats().viewers == 0; }));
  publishing = false;
  publisher.join();
  CHECK(server->stats().viewers_total == 20);
}

TEST_CASE("live server: a viewer that never reads never blocks the publisher") {
  auto server = test_server();
  RawViewer stalled(server->port());
  // A small receive window fills at once; the server then holds one frame for this viewer.
  const int small = 4096;
  ::setsockopt(stalled.ws.next_layer().native_handle(), SOL_SOCKET, SO_RCVBUF, &small,
               sizeof small);
  REQUIRE(eventually([&] { return server->stats().viewers == 1; }));
  const int frames = 3000;
  for (int i = 0; i < frames; ++i)
    server->publish_frame(frame_text(i, 64 * 1024));  // 190 MiB in all: far beyond any buffer
  const auto stats = server->stats();
  CHECK(stats.frames_published == static_cast<std::uint64_t>(frames));
  // Nearly all were coalesced: what was written is bounded by the socket buffers.
  CHECK(eventually([&] { return server->stats().frames_coalesced > frames - 200; }));
  CHECK(server->stats().frames_sent < 200);
  stalled.drop();
  CHECK(eventually([&] { return server->stats().viewers == 0; }));
}

TEST_CASE("live server: 50 viewers at once all receive the frames") {
  auto server = test_server();
  std::vector<std::unique_ptr<RawViewer>> viewers;
  for (int i = 0; i < 50; ++i)
    viewers.push_back(std::make_unique<RawViewer>(server->port()));
  REQUIRE(eventually([&] { return server->stats().viewers == 50; }));
  server->publish_frame(frame_text(42));
  for (auto& viewer : viewers)
    CHECK(viewer->read_type("frame")["i"] == 42);
  viewers.clear();  // closed without a WebSocket close
  CHECK(eventually([&] { return server->stats().viewers == 0; }));
}

TEST_CASE("live server: a port already taken is a clear error") {
  auto first = test_server();
  ServerOptions options;
  options.port = first->port();
  try {
    Server second(options, "page");
    FAIL("a second server bound the same port");
  } catch (const masnet::live::BindError& e) {
    CHECK(std::string(e.what()) == "cannot listen on 127.0.0.1:" + std::to_string(first->port()) +
                                       ": Address already in use");
  }
  options.bind_address = "localhost:80";
  CHECK_THROWS_WITH(Server(options, "page"),
                    "'localhost:80' is not an IP address (give one, e.g. 127.0.0.1 or 0.0.0.0)");
}

TEST_CASE("live server: foreign origins and host names are refused") {
  auto server = test_server();
  const std::string port = std::to_string(server->port());
  CHECK_THROWS(RawViewer(server->port(), "http://evil.example"));
  CHECK_THROWS(RawViewer(server->port(), "null"));
  CHECK_THROWS(RawViewer(server->port(), "", "evil.example:" + port));  // DNS rebinding
  CHECK(server->stats().requests_refused == 3);
  CHECK(server->stats().viewers == 0);
  RawViewer same_origin(server->port(), "http://127.0.0.1:" + port);
  RawViewer by_name(server->port(), "http://localhost:" + port, "localhost:" + port);
  CHECK(eventually([&] { return server->stats().viewers == 2; }));
}
