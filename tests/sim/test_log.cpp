#include <catch2/catch.hpp>

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <spdlog/sinks/ostream_sink.h>

#include "sim/log.hpp"
#include "sim/simulator.hpp"

using namespace masnet::sim;

namespace {
std::shared_ptr<spdlog::logger> string_logger(std::ostringstream& out,
                                              spdlog::level::level_enum level) {
  auto logger = std::make_shared<spdlog::logger>(
      "test", std::make_shared<spdlog::sinks::ostream_sink_mt>(out));
  logger->set_pattern("%v");
  logger->set_level(level);
  return logger;
}
}  // namespace

TEST_CASE("log lines are prefixed with the simulated time and the level", "[sim]") {
  std::ostringstream out;
  Simulator sim;
  Log log(sim, string_logger(out, spdlog::level::trace));
  sim.at(time_at(1.5), [&] { log.info("robot {} moved", 3); });
  sim.at(time_at(2.25), [&] {
    log.debug("robot {} update {}: R {} -> {} (farthest sensor {})", 3, 12, 0.125, 0.25, 0.2);
  });
  sim.run();
  CHECK(out.str() ==
        "[t=    1.500000000 s] [info] robot 3 moved\n"
        "[t=    2.250000000 s] [debug] robot 3 update 12: R 0.125 -> 0.25 (farthest sensor 0.2)\n");
}

TEST_CASE("Lines below the logger's level are dropped and their arguments never evaluated",
          "[sim]") {
  std::ostringstream out;
  Simulator sim;
  Log log(sim, string_logger(out, spdlog::level::info));
  int evaluated = 0;
  const auto costly = [&] { return ++evaluated; };
  MASNET_LOG(&log, debug, "not shown {}", costly());
  MASNET_LOG(&log, trace, "not shown {}", costly());
  MASNET_LOG(static_cast<const Log*>(nullptr), error, "no log at all {}", costly());
  CHECK(evaluated == 0);
  MASNET_LOG(&log, warn, "shown {}", costly());
  MASNET_LOG(&log, error, "shown {}", costly());
  CHECK(evaluated == 2);
  CHECK(out.str() ==
        "[t=    0.000000000 s] [warn] shown 1\n[t=    0.000000000 s] [error] shown 2\n");
  CHECK_FALSE(log.enabled(spdlog::level::debug));
  CHECK(log.enabled(spdlog::level::info));
}

TEST_CASE("The log file sink appends to an existing file and reports a failed write", "[sim]") {
  const auto path =
      std::filesystem::temp_directory_path() / ("masnet-log-sink-" + std::to_string(::getpid()));
  { std::ofstream(path) << "an earlier line\n"; }
  {
    auto sink = std::make_shared<CheckedFileSink>(path.string());
    auto logger = std::make_shared<spdlog::logger>("file", sink);
    logger->set_pattern("%v");
    Simulator sim;
    Log(sim, logger).warn("robot {} lost", 1);
    CHECK(sink->error().empty());
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  CHECK(text.str() == "an earlier line\n[t=    0.000000000 s] [warn] robot 1 lost\n");
  std::filesystem::remove(path);

  CHECK_THROWS_WITH(CheckedFileSink("/nonexistent-folder/x.log"),
                    "cannot open '/nonexistent-folder/x.log': No such file or directory");
  if (std::filesystem::exists("/dev/full")) {
    auto full = std::make_shared<CheckedFileSink>("/dev/full");
    auto logger = std::make_shared<spdlog::logger>("full", full);
    logger->info("x");
    CHECK(full->error() == "cannot write '/dev/full': No space left on device");
  }
}
