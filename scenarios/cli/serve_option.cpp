#include "scenarios/cli/serve_option.hpp"

#include <cstdio>

#include <CLI/CLI.hpp>

#include "scenarios/cli/command_output.hpp"

#include "scenarios/live/live_page.hpp"
#include "scenarios/live/live_server.hpp"
#include "scenarios/live/live_watch.hpp"

namespace masnet::cli {

void add_serve_options(CLI::App& run, ServeArgs& args) {
  CLI::Option* serve = run.add_flag(
      "--serve", args.serve, "watch the run live in a browser: serve a page and print its URL");
  run.add_option("--port", args.port, "--serve: TCP port (0 picks a free one)")
      ->check(CLI::Range(0, 65535))
      ->default_str("8080")
      ->needs(serve);
  run.add_option("--bind", args.bind,
                 "--serve: address to listen on (default loopback only; 0.0.0.0 for all)")
      ->default_str("127.0.0.1")
      ->needs(serve);
  run.add_option("--serve-start", args.start,
                 "--serve: 'paused' (wait for the first viewer) or 'running'")
      ->check(CLI::IsMember({"paused", "running"}))
      ->default_str("paused")
      ->needs(serve);
  run.add_option("--serve-speed", args.speed,
                 "--serve: initial speed, x real time (0 = as fast as possible)")
      ->check(CLI::Range(0.0, 1000.0))
      ->default_str("1")
      ->needs(serve);
}

struct LiveSession::Parts {
  live::Server server;
  live::LiveWatch watch;
  Parts(live::ServerOptions server_options, std::string page, live::WatchOptions watch_options)
      : server(std::move(server_options), std::move(page)), watch(server, watch_options) {}
};

LiveSession::LiveSession(const ServeArgs& args) {
  live::ServerOptions server_options;
  server_options.bind_address = args.bind;
  server_options.port = args.port;
  live::WatchOptions watch_options;
  watch_options.start_running = args.start == "running";
  watch_options.speed = args.speed;
  parts_ = std::make_unique<Parts>(server_options, live::live_page_html(), watch_options);
  parts_->server.start();
  std::printf("live view: %s%s\n", parts_->server.url().c_str(),
              watch_options.start_running ? "" : " (the run starts when a viewer connects)");
  std::fflush(stdout);
}

std::unique_ptr<LiveSession> start_live_session(const ServeArgs& args, int& exit_code) {
  try {
    return std::make_unique<LiveSession>(args);
  } catch (const live::BindError& e) {
    std::fprintf(stderr, "masnet run: --serve: %s\n", e.what());
    exit_code = kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "masnet run: --serve: %s\n", e.what());
    exit_code = kInternalError;
  }
  return nullptr;
}

LiveSession::~LiveSession() {
  if (parts_) parts_->server.stop();
}

scenarios::RunWatcher& LiveSession::watcher() {
  return parts_->watch;
}

void LiveSession::serve_until_interrupted(double wall_time_s) {
  // Ctrl-C must be ours before the line that asks for it is printed (a script reading that
  // line may send SIGINT at once).
  parts_->server.catch_interrupts();
  std::printf(
      "live view: the run took %.3f s of wall time, %.3f s of it held (paused, paced "
      "or waiting for a viewer)\n",
      wall_time_s, parts_->watch.held_s());
  std::printf("live view: the run has ended; still serving %s until interrupted (Ctrl-C)\n",
              parts_->server.url().c_str());
  std::fflush(stdout);
  parts_->server.wait_for_interrupt();
  const live::ServerStats stats = parts_->server.stats();
  parts_->server.stop();
  std::printf("live view: stopped (viewers %llu, frames sent %llu, coalesced %llu)\n",
              static_cast<unsigned long long>(stats.viewers_total),
              static_cast<unsigned long long>(stats.frames_sent),
              static_cast<unsigned long long>(stats.frames_coalesced));
}

}  // namespace masnet::cli
