#pragma once
// Radio energy by message type, for summary.json's `energy_j.by_type` (docs/outputs.md).
#include <nlohmann/json.hpp>

#include "net/radio.hpp"

namespace masnet::scenarios {

/// {TYPE: {radio_tx, radio_rx}} for every message type that cost energy: sending its frames
/// (and, under csma, their acknowledgements and retries), and every node hearing them, joules.
nlohmann::json energy_by_type(const net::Radio& radio);

}  // namespace masnet::scenarios
