#include "protocols/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <mutex>
#include <stdexcept>

#include "protocols/ground_truth.hpp"
#include "protocols/sensor_protocol.hpp"

namespace masnet::protocols {

void register_builtin_protocols();  // builtin_protocols.cpp

namespace {

struct Entry {
  ProtocolDefinition definition;
  TruthfulRobotFactory truthful;  // set for ground-truth protocols only
};

// A deque: entries never move, so the pointers handed out stay valid as protocols are added.
std::deque<Entry>& entries() {
  static std::deque<Entry> instance;
  return instance;
}

bool is_protocol_name(std::string_view name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

void add(ProtocolDefinition definition, TruthfulRobotFactory truthful) {
  if (!is_protocol_name(definition.name))
    throw std::invalid_argument(
        fmt::format("protocol name '{}': use lower case letters, digits and '_'", definition.name));
  if (!definition.make_robot && !truthful)
    throw std::invalid_argument(fmt::format("protocol {}: make_robot is empty", definition.name));
  for (const Entry& entry : entries()) {
    const ProtocolDefinition& other = entry.definition;
    if (other.name == definition.name)
      throw std::invalid_argument(
          fmt::format("protocol {} is already registered", definition.name));
    for (const ParamSpec& mine : definition.params)
      for (const ParamSpec& theirs : other.params)
        if (mine.key == theirs.key && !mine.same_declaration(theirs))
          throw std::invalid_argument(
              fmt::format("protocol {}: key '{}' is declared differently by protocol {} (one key, "
                          "one meaning: choose another name)",
                          definition.name, mine.key, other.name));
  }
  for (std::size_t i = 0; i < definition.params.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (definition.params[i].key == definition.params[j].key)
        throw std::invalid_argument(fmt::format("protocol {}: key '{}' is declared twice",
                                                definition.name, definition.params[i].key));
  if (!definition.make_sensor) definition.make_sensor = paper_sensors();
  entries().push_back({std::move(definition), std::move(truthful)});
}

// The built-ins come first, whoever asks first (a program registers its own protocols after).
std::deque<Entry>& ready_entries() {
  static std::once_flag once;
  std::call_once(once, [] { register_builtin_protocols(); });
  return entries();
}

}  // namespace

void register_protocol(ProtocolDefinition definition) {
  ready_entries();
  add(std::move(definition), {});
}

void register_ground_truth_protocol(ProtocolDefinition definition, TruthfulRobotFactory make) {
  ready_entries();
  add(std::move(definition), std::move(make));
}

// Called by register_builtin_protocols only (ready_entries would wait on itself).
void register_builtin(ProtocolDefinition definition, TruthfulRobotFactory truthful) {
  add(std::move(definition), std::move(truthful));
}

const ProtocolDefinition* find_protocol(std::string_view name) {
  for (const Entry& entry : ready_entries())
    if (entry.definition.name == name) return &entry.definition;
  return nullptr;
}

const TruthfulRobotFactory* ground_truth_factory(std::string_view name) {
  for (const Entry& entry : ready_entries())
    if (entry.definition.name == name) return entry.truthful ? &entry.truthful : nullptr;
  return nullptr;
}

std::vector<const ProtocolDefinition*> registered_protocols() {
  std::vector<const ProtocolDefinition*> all;
  for (const Entry& entry : ready_entries())
    all.push_back(&entry.definition);
  return all;
}

const ProtocolDefinition& protocol_named(std::string_view name) {
  const ProtocolDefinition* definition = find_protocol(name);
  if (!definition) throw std::invalid_argument(fmt::format("no protocol named '{}'", name));
  return *definition;
}

ProtocolChoice choose_protocol(std::string_view kind) {
  const ProtocolDefinition& definition = protocol_named(kind);
  ProtocolChoice choice;
  choice.kind = definition.name;
  choice.params = ParamValues::defaults(definition.params);
  return choice;
}

SensorFactory paper_sensors() {
  return [](const SensorSetup& setup) -> std::unique_ptr<SensorProtocol> {
    // Sensors listen for POSITIONs one reply timeout before they report (paper §III-B, steps
    // 2-3).
    const double report_delay_s =
        setup.params.has("reply_timeout") ? setup.params.real("reply_timeout") : 0.002;
    const double reply_jitter_s =
        setup.params.has("reply_jitter") ? setup.params.real("reply_jitter") : 0.0;
    return std::make_unique<PaperSensorProtocol>(report_delay_s, setup.context.sensor_count,
                                                 setup.log, reply_jitter_s, setup.context.seed);
  };
}

std::string protocol_phase(const ProtocolDefinition& definition, net::MessageType type) {
  switch (type) {
    case net::MessageType::position:
    case net::MessageType::report:
      return "initialisation";
    case net::MessageType::discover:
    case net::MessageType::neighbor:
      return "discovery";
    case net::MessageType::sense:
    case net::MessageType::reading:
      return "sensing";
    case net::MessageType::beacon:
      return "beacons";
    default:
      break;
  }
  for (const auto& [own, phase] : definition.message_phases)
    if (own == type) return phase;
  return "other";
}

}  // namespace masnet::protocols
