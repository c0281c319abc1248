#pragma once
// What contention did (radio levels collision and csma), for the run's files: the summary's
// per-type and total keys, and the per-node columns of nodes.csv (docs/outputs.md). The other
// levels have no contended medium, and their files keep exactly their columns and keys.
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "net/contended_medium.hpp"

namespace masnet::scenarios {

/// Adds transmissions, delivered, collided, channel_lost, dropped, retries, backoffs,
/// latency_mean_s and latency_p99_s to each `messages.by_type.<TYPE>` and to `messages.total`
/// (the latencies are null without deliveries), and acks to `messages.total`.
void add_contention_summary(const net::ContendedMedium& medium, nlohmann::json& messages);

/// The q-quantile of the delivery latency over all message types together (0 without
/// deliveries), from the per-type histograms.
double latency_quantile_all_types_s(const net::ContendedMedium& medium, double q);

/// The extra header of nodes.csv, leading comma included.
inline constexpr std::string_view kContentionNodeColumns =
    ",transmissions,delivered,collided,channel_lost,dropped,retries,backoffs,acks";

/// Appends `node`'s values for kContentionNodeColumns (zeros for a node that never sent).
void append_contention_node(const net::ContendedMedium& medium, sim::NodeId node,
                            fmt::memory_buffer& row);

}  // namespace masnet::scenarios
