#include <catch2/catch.hpp>

#include <sstream>

#include <spdlog/sinks/ostream_sink.h>

#include "sim/log.hpp"
#include "sim/simulator.hpp"

using namespace masnet::sim;

TEST_CASE("log lines are prefixed with the simulated time", "[sim]") {
  std::ostringstream out;
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(out);
  auto logger = std::make_shared<spdlog::logger>("test", sink);
  logger->set_pattern("%v");
  Simulator sim;
  Log log(sim, logger);
  sim.at(time_at(1.5), [&] { log.info("robot {} moved", 3); });
  sim.run();
  CHECK(out.str() == "[t=    1.500000000 s] robot 3 moved\n");
}
