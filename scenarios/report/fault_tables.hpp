#pragma once
// The report's tables of network lifetime, recovery from each scripted fault and the fault-free
// twin, from summary.json's `lifetime`, `recovery` and `twin` (runs with faults or batteries).
#include <string>

#include <nlohmann/json.hpp>

namespace masnet::scenarios {

/// Whether the summary has any of those sections.
bool has_lifetime_section(const nlohmann::json& summary);

/// The HTML tables (ids "lifetime-table", "recovery-table", "twin-table") of the sections the
/// summary has.
std::string lifetime_tables(const nlohmann::json& summary);

}  // namespace masnet::scenarios
