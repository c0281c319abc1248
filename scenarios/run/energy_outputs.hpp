#pragma once
// Energy in summary.json's `energy_j` (docs/outputs.md): the radio's energy by message type and
// by protocol phase, its distribution over nodes, per update, and the robots' locomotion.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "agents/world.hpp"
#include "net/radio.hpp"
#include "protocols/registry.hpp"

namespace masnet::scenarios {

/// {TYPE: {radio_tx, radio_rx}} for every message type that cost energy: sending its frames
/// (and, under csma, their acknowledgements and retries), and every node hearing them, joules.
nlohmann::json energy_by_type(const net::Radio& radio);

/// {phase: {radio_tx, radio_rx}}: energy_by_type summed over the types of each phase
/// (protocols::protocol_phase); phases that cost nothing are left out. Idle energy belongs to
/// no phase.
nlohmann::json energy_by_phase(const net::Radio& radio,
                               const protocols::ProtocolDefinition& definition);

/// The value of rank ⌈p·n⌉ (1-based, at least 1) of `sorted` (ascending, not empty).
double nearest_rank(const std::vector<double>& sorted, double p);
/// {min, p50, p90, max} of `values` by nearest rank; null when there are none.
nlohmann::json distribution_summary(std::vector<double> values);

/// Adds `by_phase`, `per_update`, `distribution` and `locomotion` to summary.json's
/// `energy_j` object `energy`.
void add_energy_details(nlohmann::json& energy, agents::World& world, std::uint64_t updates);

}  // namespace masnet::scenarios
