#pragma once
// Warnings about a run that degenerated: the simulation finished, but its figures measure a
// broken protocol run rather than the protocol (docs/outputs.md, summary.json `warnings`).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace masnet::scenarios {

/// The warnings for a run, from its summary.json metrics (sections `protocol` and
/// `energy_j`) and the radio's loss probability. Each is one sentence with its numbers. Low
/// cell correctness warns only with loss, or when cells are wrong even for the positions the
/// robots heard (`cell_correctness_heard` below 0.9, or absent).
std::vector<std::string> run_warnings(const nlohmann::json& summary, double loss_probability);

}  // namespace masnet::scenarios
