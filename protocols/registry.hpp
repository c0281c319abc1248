#pragma once
// Protocols chosen by name. A protocol definition names the protocol, declares its parameter
// keys, the message types robots and sensors hear, the extra per-update fields it reports, and
// makes its robot and sensor objects. The built-ins (none, radius_doubling, oracle,
// fixed_radius, gabriel) register through the same function as a user's protocol; a program
// registers its own before it hands its arguments to masnet's command line
// (docs/protocol-api.md).
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "net/messages.hpp"
#include "protocols/density_scaling.hpp"
#include "protocols/geometry.hpp"
#include "protocols/host.hpp"
#include "protocols/protocol.hpp"
#include "protocols/protocol_params.hpp"
#include "sim/log.hpp"
#include "sim/random.hpp"

namespace masnet::protocols {

/// What every robot's protocol knows of the deployment.
struct ProtocolContext {
  ConvexPolygon domain;
  DensityScaling scaling;
  double max_range = 1.5;  ///< the radio's cap, world units
  std::size_t robot_count = 0, sensor_count = 0;
  std::uint64_t seed = 0;  ///< the run's seed: keys draws that must not depend on event order
};

/// What a robot protocol is made from.
struct RobotSetup {
  RobotHost& host;
  std::size_t robot;  ///< this robot's number, 0..R−1
  const ProtocolContext& context;
  const ParamValues& params;  ///< the keys the definition declares, validated
  /// This robot's own random stream (keyed by the run's seed and the robot): the same draws
  /// whatever other nodes do. The built-ins draw their update phase from it first.
  sim::RandomStream& random;
  const sim::Log* log;  ///< may be null; MASNET_LOG writes through it (docs/logging.md)
};

/// What the sensors' protocol object is made from.
struct SensorSetup {
  const ProtocolContext& context;
  const ParamValues& params;
  const sim::Log* log;
};

using RobotFactory = std::function<std::unique_ptr<RobotProtocol>(const RobotSetup&)>;
using SensorFactory = std::function<std::unique_ptr<SensorProtocol>(const SensorSetup&)>;

struct ProtocolDefinition {
  std::string name;     ///< `protocol.kind` in a scenario: lower case letters, digits, '_'
  std::string summary;  ///< one line for `masnet protocols`
  /// Keys under `protocol:`. A key another protocol also declares must be declared the same
  /// way (one key, one meaning).
  std::vector<ParamSpec> params;
  /// Message types the radio hands to robots and to sensors (others are not delivered to them).
  std::vector<net::MessageType> robots_hear, sensors_hear;
  /// Names of the protocol's own per-update fields (UpdateSummary::extra): extra columns of
  /// updates.csv.
  std::vector<std::string> update_columns;
  /// The phase each of the protocol's own message types belongs to, for energy by phase
  /// (docs/outputs.md). Built-in types have theirs (protocol_phase); a type not listed here
  /// counts under "other".
  std::vector<std::pair<net::MessageType, std::string>> message_phases;
  RobotFactory make_robot;
  /// Empty: the paper's sensors (paper_sensors()).
  SensorFactory make_sensor;
};

/// The sensors of the paper: each reports to the closest robot it heard announce itself, once,
/// `reply_timeout` after the first announcement (0.002 s when the protocol declares no such
/// key), and answers a SENSE whose cell holds it with its reading; both replies `reply_jitter`
/// later at most (0 when not declared).
SensorFactory paper_sensors();

/// Registers `definition`. Throws std::invalid_argument when the name is taken or malformed, a
/// key is declared differently by another protocol, or make_robot is empty.
void register_protocol(ProtocolDefinition definition);
/// The protocol registered under `name`, or null.
const ProtocolDefinition* find_protocol(std::string_view name);
/// The protocol registered under `name`; throws std::invalid_argument if there is none.
const ProtocolDefinition& protocol_named(std::string_view name);
/// Every protocol, in registration order (the built-ins first).
std::vector<const ProtocolDefinition*> registered_protocols();

/// The keys every built-in message protocol declares, for a protocol of one's own to declare
/// the same way (a key means one thing whatever the kind): `period`, the time between a robot's
/// updates, and `reply_timeout`, how long a round waits for replies (also when the paper's
/// sensors report).
ParamSpec update_period_param();
ParamSpec reply_timeout_param();
/// `reply_jitter`: the paper's sensors delay each REPORT and READING by a uniform draw in
/// [0, J), so that a burst of replies does not start at one instant (docs/radio-and-energy.md).
ParamSpec reply_jitter_param();

/// The phase of the protocol that frames of `type` serve: POSITION and REPORT "initialisation",
/// DISCOVER and NEIGHBOR "discovery", SENSE and READING "sensing", BEACON "beacons"; a
/// protocol's own type as its definition says, else "other".
std::string protocol_phase(const ProtocolDefinition& definition, net::MessageType type);

inline constexpr std::string_view kDefaultProtocol = "radius_doubling";

/// A run's protocol: its name and the values of the keys it declares.
struct ProtocolChoice {
  std::string kind = std::string(kDefaultProtocol);
  ParamValues params = ParamValues::defaults(find_protocol(kDefaultProtocol)->params);
};
/// `kind` with every key at its default; throws std::invalid_argument if `kind` is unknown.
ProtocolChoice choose_protocol(std::string_view kind);

}  // namespace masnet::protocols
