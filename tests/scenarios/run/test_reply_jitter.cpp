// protocol.reply_jitter spreads the sensors' replies: under csma fewer READINGs collide and more
// reach their robot than when every sensor answers the instant the SENSE arrives
// (docs/radio-and-energy.md, "Timeouts and jitter: advice").
#include <catch2/catch.hpp>

#include <string>

#include "agents/world.hpp"
#include "net/contended_medium.hpp"
#include "scenarios/loader/scenario.hpp"
#include "sim/simulator.hpp"

using namespace masnet;
using namespace masnet::scenarios;

namespace {

net::ContentionCounters readings(const std::string& jitter_s) {
  LoadResult loaded = load_scenario(
      std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/acoustic_tracking.yaml",
      {"duration=0.3", "output.snapshots=[]", "sensors.nx=20", "sensors.ny=20", "radio.level=csma",
       "protocol.reply_timeout=0.008", "protocol.reply_jitter=" + jitter_s});
  REQUIRE(loaded.scenario);
  sim::Simulator simulator;
  agents::World world(simulator, loaded.scenario->world);
  world.start();
  simulator.run_until(sim::Time{} + sim::seconds(loaded.scenario->duration_s));
  return world.radio().contention()->totals(net::MessageType::reading);
}

}  // namespace

TEST_CASE("reply jitter spreads a burst of replies: fewer collide, more arrive", "[scenarios]") {
  const net::ContentionCounters at_once = readings("0");
  const net::ContentionCounters spread = readings("0.004");
  INFO("collided " << at_once.collided << " -> " << spread.collided << ", delivered "
                   << at_once.delivered << " -> " << spread.delivered);
  CHECK(spread.collided * 2 < at_once.collided);
  CHECK(spread.delivered > at_once.delivered);
}
