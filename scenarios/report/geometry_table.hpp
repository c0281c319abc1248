#pragma once
// The report's table of computation per update beside the messages and the radio energy, from
// summary.json's `protocol.geometry`, `protocol.messages_per_update`, `protocol.updates` and
// `energy_j` (docs/outputs.md; the counts are defined in docs/protocols.md).
#include <string>

#include <nlohmann/json.hpp>

namespace masnet::scenarios {

/// The HTML table (id "computation-load"), or a sentence when the summary has no counts.
std::string computation_table(const nlohmann::json& summary);

}  // namespace masnet::scenarios
