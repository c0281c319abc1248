#pragma once
// The loader's parts that live in their own files (scenario_layout.cpp, scenario_limits.cpp,
// scenario_faults.cpp, ...): the node layouts, the faults, and the checks of what a scenario's
// numbers imply. Internal to the loader.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "agents/world.hpp"
#include "scenarios/loader/reader.hpp"
#include "scenarios/loader/scenario.hpp"

namespace masnet::scenarios {

/// How many nodes a scenario may have (docs/scenario-reference.md, "Limits").
inline constexpr std::int64_t kMaxSensors = 10'000'000;
inline constexpr std::int64_t kMaxSensorsHuge = 100'000'000;
inline constexpr std::int64_t kMaxRobots = 1'000'000;
inline constexpr std::int64_t kMaxRobotsHuge = 10'000'000;
/// Periodic work over a run (protocol updates, beacons, motion substeps, trajectory rows,
/// diffusion cell updates), and timeseries rows.
inline constexpr double kMaxPeriodicWork = 1e9;
inline constexpr double kMaxSamples = 1e7;
/// Points a random layout may draw (it keeps those inside the domain).
inline constexpr double kMaxRandomDraws = 2e7;
/// The largest density a field may reach after density_scaling.
inline constexpr double kMaxDensityLog10 = 100.0;
/// How many nodes outside the domain are listed before "... and N more".
inline constexpr std::size_t kMaxListed = 10;

/// Robots per group (`robots.groups.size`), the leader included.
inline constexpr std::int64_t kMaxGroupSize = 64;

/// What the loader may build, from LoadOptions and limits.allow_huge.
struct NodeCaps {
  std::int64_t sensors = kMaxSensors;
  std::int64_t robots = kMaxRobots;
  bool huge = false;  ///< limits.allow_huge honoured and set
  bool build_sensors = true;
};

struct SensorLayout {
  std::string kind;
  double spacing = 0.0;  // h: grid spacing or sqrt(area / n)
  std::size_t count = 0;
};

/// `(1.5, 0.5)`: a point as the user would have written it, for messages.
std::string shown_point(const Vec2& p);

/// The sensors (an empty list when caps.build_sensors is off, but for file layouts);
/// `layout.count` is their number either way. Also sets the sensors' noise and battery in
/// `world`.
std::vector<agents::SensorDef> read_sensors(Section s, const protocols::ConvexPolygon& domain,
                                            std::uint64_t seed, const std::string& base_dir,
                                            ScenarioReader& reader, SensorLayout& layout,
                                            agents::WorldDef& world, const NodeCaps& caps);

/// The robots' positions; also sets their motion, battery and locomotion energy in `world`.
std::vector<Vec2> read_robots(Section s, const protocols::ConvexPolygon& domain, std::uint64_t seed,
                              agents::WorldDef& world, const NodeCaps& caps);

/// `robots.energy`: the locomotion energy (scenario_faults.cpp).
agents::LocomotionEnergy read_locomotion(Section s);
/// `robots.groups` for `leaders` leaders (scenario_groups.cpp).
agents::FormationDef read_groups(Section s, std::size_t leaders, const NodeCaps& caps);

/// How many nodes of each class a fault may name, when known (nullopt: their section had
/// errors, so ids are not checked against a count that may be wrong).
struct NodeCounts {
  std::optional<std::size_t> robots, sensors;
};

/// The top-level `faults` list, in file order (scenario_faults.cpp). `duration_s` bounds the
/// times (0: unknown, the clock's limit instead). An absent list leaves the resolved scenario
/// without `faults`.
std::vector<agents::FaultDef> read_faults(Section& top, double duration_s,
                                          const NodeCounts& counts);

/// The `protocol` section: `kind` names a registered protocol; every registered protocol's keys
/// are validated, the chosen one's are kept (scenario_protocol.cpp).
/// `level` chooses the default of `reply_timeout` (docs/radio-and-energy.md, "Timeouts").
protocols::ProtocolChoice read_protocol(Section s, net::RadioLevel level);

/// How long a round waits for replies unless the scenario says: replies queue behind each other
/// from `airtime` on and back off under `csma`.
double default_reply_timeout_s(net::RadioLevel level);

/// The `radio` section (scenario_radio.cpp).
net::RadioParams read_radio(Section s);

/// The sections a limit message points into (copies of the loader's, for their locations).
struct LimitSections {
  Section field, scaling, robots, protocol, beacons, output;
};

/// Reports work beyond the budgets and densities that would overflow, at the key to change.
void check_limits(const ScenarioDef& def, std::size_t sensor_count, const NodeCaps& caps,
                  LimitSections& at);

}  // namespace masnet::scenarios
