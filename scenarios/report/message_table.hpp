#pragma once
// The report's table of messages by type, from summary.json's `messages` section; with the
// columns of what contention did when the run has them (radio levels collision and csma).
#include <string>

#include <nlohmann/json.hpp>

namespace masnet::scenarios {

/// The HTML table (id "messages-by-type"), or a sentence when the summary has no messages.
std::string messages_table(const nlohmann::json& summary);

}  // namespace masnet::scenarios
