// Watching a run changes nothing (docs/live-and-replay.md): the fingerprint and every output
// file are the same with a live viewer connected, with the run stopped after every protocol
// update, and paused and stepped from a viewer. The command line's --serve errors.
#include <unistd.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "live_client.hpp"
#include "scenarios/live/live_server.hpp"
#include "scenarios/live/live_watch.hpp"
#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/run.hpp"
#include "text_files.hpp"

namespace fs = std::filesystem;
using namespace masnet::scenarios;
using masnet::test::eventually;
using masnet::test::RawViewer;
using masnet::test::slurp;

namespace {

ScenarioDef acoustic(double duration_s) {
  LoadResult loaded =
      load_scenario(std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/acoustic_tracking.yaml",
                    {"duration=" + std::to_string(duration_s), "output.snapshots=[0.5]"});
  REQUIRE(loaded.scenario);
  return *loaded.scenario;
}

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& tag)
      : path(fs::temp_directory_path() / fmt::format("masnet-live-{}-{}", tag, ::getpid())) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

/// Every file `run` writes, by name; summary.json without its wall time.
std::map<std::string, std::string> written_files(const Run& run, const fs::path& dir) {
  fs::create_directories(dir);
  run.write_files(dir.string());
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir))
    files[entry.path().filename().string()] = slurp(entry.path());
  nlohmann::json summary = nlohmann::json::parse(files["summary.json"]);
  summary.erase("wall_time_s");
  files["summary.json"] = summary.dump();
  return files;
}

/// Stops the run after every protocol update and counts the frames it is shown.
class StopAtEveryUpdate final : public RunWatcher {
 public:
  double frame_period_s() const override { return 0.1; }
  void on_start(const nlohmann::json& header) override { robots = header["robots"]; }
  void on_frame(const nlohmann::json& frame) override {
    CHECK(frame["t"].get<double>() >= last_t);
    last_t = frame["t"];
    ++frames;
    for (const auto& n : frame["sent"])
      sent += n.get<std::uint64_t>();
  }
  bool stop_after_update() override { return ++updates, true; }
  void on_end(const nlohmann::json& frame) override {
    ended = true;
    for (const auto& n : frame["sent"])
      sent += n.get<std::uint64_t>();
  }
  std::size_t robots = 0, frames = 0, updates = 0;
  std::uint64_t sent = 0;  // every robot transmission, counted once whatever the frames
  double last_t = 0;
  bool ended = false;
};

/// A server on a free port with a LiveWatch, started.
struct ServedRun {
  masnet::live::Server server{loopback_any_port(), "page"};
  masnet::live::LiveWatch watch;
  ServedRun(bool start_running, double speed) : watch(server, watch_options(start_running, speed)) {
    server.start();
  }
  static masnet::live::ServerOptions loopback_any_port() {
    masnet::live::ServerOptions options;
    options.port = 0;
    return options;
  }
  static masnet::live::WatchOptions watch_options(bool start_running, double speed) {
    masnet::live::WatchOptions options;
    options.start_running = start_running;
    options.speed = speed;
    return options;
  }
};

}  // namespace

TEST_CASE("live run: a connected viewer changes neither the fingerprint nor any output file") {
  TempDir temp("same");
  Run plain(acoustic(1.0));
  plain.execute();
  const auto plain_files = written_files(plain, temp.path / "plain");

  ServedRun served(false, 0.0);  // waits for the viewer below, then as fast as possible
  auto& [server, watch] = served;
  std::size_t frames = 0;
  bool ended = false;
  std::thread viewer_thread([&] {
    RawViewer viewer(server.port());
    for (;;) {
      const nlohmann::json message = viewer.read();
      if (message["type"] == "frame") ++frames;
      if (message["type"] == "end") break;
    }
    ended = true;
  });
  Run watched(acoustic(1.0));
  watched.execute({}, &watch);
  viewer_thread.join();
  CHECK(ended);
  CHECK(frames >= 1);
  CHECK(server.stats().frames_published == 51);  // t = 0, 0.02, ..., 1
  CHECK(watched.fingerprint() == plain.fingerprint());
  CHECK(watched.traffic_fingerprint() == plain.traffic_fingerprint());
  const auto watched_files = written_files(watched, temp.path / "watched");
  REQUIRE(watched_files.size() == plain_files.size());
  for (const auto& [name, bytes] : plain_files) {
    INFO(name);
    CHECK(watched_files.at(name) == bytes);
  }
}

TEST_CASE("live run: stopping after every protocol update changes nothing") {
  Run plain(acoustic(0.5));
  plain.execute();
  StopAtEveryUpdate watcher;
  Run stepped(acoustic(0.5));
  stepped.execute({}, &watcher);
  CHECK(watcher.ended);
  CHECK(watcher.robots == 9);
  const auto updates = stepped.summary()["protocol"]["updates"].get<std::size_t>();
  CHECK(watcher.updates == updates);
  CHECK(updates > 100);
  CHECK(watcher.frames == updates + 6);  // one a stop, and the checkpoints 0, 0.1, ..., 0.5
  CHECK(stepped.fingerprint() == plain.fingerprint());
  CHECK(stepped.summary()["coverage"] == plain.summary()["coverage"]);
  // The watcher's flashes and the replay's count the same transmissions, each its own way.
  TempDir temp("sent");
  stepped.write_files(temp.path.string());
  std::istringstream replay(slurp(temp.path / "replay.json"));
  const nlohmann::json parsed = nlohmann::json::parse(replay);
  std::uint64_t replay_sent = 0;
  for (const auto& frame : parsed["frames"])
    for (const auto& n : frame["sent"])
      replay_sent += n.get<std::uint64_t>();
  CHECK(watcher.sent > 0);
  CHECK(watcher.sent == replay_sent);
}

TEST_CASE("live run: a viewer pauses, steps one update and runs the rest to the end") {
  // Real time: 20 s of run leave time to pause it however loaded the machine is ("end" then
  // runs the rest as fast as possible).
  ServedRun served(false, 1.0);
  auto& [server, watch] = served;
  Run run(acoustic(20.0));
  std::thread run_thread([&] { run.execute({}, &watch); });
  RawViewer viewer(server.port());
  // A failed check below leaves the run paused: end it before the thread is destroyed.
  struct EndAndJoin {
    RawViewer& viewer;
    std::thread& thread;
    ~EndAndJoin() {
      if (!thread.joinable()) return;
      try {
        viewer.send(R"({"cmd":"end"})");
      } catch (...) {
      }
      thread.join();
    }
  } end_and_join{viewer, run_thread};
  CHECK(viewer.read_type("hello")["header"]["robots"] == 9);
  // The next status, failing (instead of waiting for ever) if the run answers otherwise.
  const auto next_status = [&viewer] {
    for (;;) {
      nlohmann::json message = viewer.read();
      const std::string type = message.value("type", "");
      if (type == "status") return message;
      INFO(message.dump());
      REQUIRE(type != "error");
      REQUIRE(type != "end");
    }
  };
  viewer.send(R"({"cmd":"pause"})");
  nlohmann::json status;
  do {
    status = next_status();
  } while (!status["paused"].get<bool>());
  const double paused_at = status["t"];
  CHECK(paused_at < 20.0);
  viewer.send(R"({"cmd":"step"})");
  // The run stops after the next update and says so; its frame is at or after the pause.
  do {
    status = next_status();
  } while (!(status["paused"].get<bool>() && status["t"].get<double>() > paused_at));
  CHECK(status["t"].get<double>() < paused_at + 0.05);  // the next update, period 0.01 s
  viewer.send(R"({"cmd":"speed","value":-1})");
  CHECK(viewer.read_type("error")["message"] ==
        "speed takes a \"value\" from 0 (as fast as possible) to 1000 (× real time)");
  viewer.send(R"({"cmd":"end"})");
  CHECK(viewer.read_type("end")["frame"]["t"] == 20.0);
  run_thread.join();
  viewer.send(R"({"cmd":"play"})");
  CHECK(viewer.read_type("error")["message"] == "the run has finished");
}

TEST_CASE("live run: a viewer that comes before the run starts still gets the run's hello") {
  // `masnet run --serve` listens before it builds the world: a page opened at once is greeted
  // without a hello, which must follow when the run starts.
  ServedRun served(false, 0.0);
  auto& [server, watch] = served;
  RawViewer viewer(server.port());
  CHECK(viewer.read_type("status")["t"] == 0.0);  // the greeting ends with a status
  Run run(acoustic(0.5));
  std::thread run_thread([&] { run.execute({}, &watch); });
  nlohmann::json message;
  do {
    message = viewer.read();
  } while (message["type"] != "hello" && message["type"] != "end");
  run_thread.join();
  REQUIRE(message["type"] == "hello");
  CHECK(message["header"]["robots"] == 9);
}

TEST_CASE("live run: a late viewer gets the whole history of the finished run") {
  ServedRun served(true, 0.0);
  auto& [server, watch] = served;
  Run run(acoustic(0.5));
  run.execute({}, &watch);
  RawViewer late(server.port());
  CHECK(late.read()["type"] == "hello");
  const nlohmann::json history = late.read();
  REQUIRE(history["type"] == "history");
  CHECK(history["points"].size() == 27);  // 26 frames and the final one
  CHECK(late.read()["frame"]["t"] == 0.5);
  CHECK(late.read()["finished"] == true);
}

TEST_CASE("live run: --serve on a port already taken exits 2 before simulating") {
  boost::asio::io_context io;
  masnet::test::tcp::acceptor taken(io, {boost::asio::ip::make_address("127.0.0.1"), 0});
  const auto port = taken.local_endpoint().port();
  TempDir temp("taken");
  const fs::path out = temp.path / "run", log = temp.path / "output.txt";
  const std::string command = fmt::format(
      "'{}/scenarios/masnet' run '{}/scenarios/paper/acoustic_tracking.yaml' --out '{}' "
      "--serve --port {} > '{}' 2>&1",
      MASNET_BINARY_DIR, MASNET_SOURCE_DIR, out.string(), port, log.string());
  const int status = std::system(command.c_str());
  CHECK(WEXITSTATUS(status) == 2);
  CHECK(slurp(log) == fmt::format("masnet run: --serve: cannot listen on 127.0.0.1:{}: Address "
                                  "already in use\n",
                                  port));
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("live run: --port without --serve is refused") {
  TempDir temp("needs");
  const fs::path log = temp.path / "output.txt";
  const std::string command = fmt::format(
      "'{}/scenarios/masnet' run '{}/scenarios/paper/acoustic_tracking.yaml' --port 0 "
      "> '{}' 2>&1",
      MASNET_BINARY_DIR, MASNET_SOURCE_DIR, log.string());
  CHECK(WEXITSTATUS(std::system(command.c_str())) == 2);
  CHECK(slurp(log).find("--port requires --serve") != std::string::npos);
}
