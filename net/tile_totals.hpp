#pragma once
// Counters by message type, and a tile's share of a partitioned run's totals
// (docs/decisions/0012-partitioned-runs.md): plain values, copied between threads or sent between
// ranks, that the tile absorbing the others adds to its own.
#include <array>
#include <cstdint>

#include "net/messages.hpp"
#include "sim/exact_sum.hpp"

namespace masnet::net {

/// Per node, per message type.
struct TypeCounters {
  std::uint64_t tx_count = 0, tx_bytes = 0;
  std::uint64_t rx_count = 0, rx_bytes = 0;
};

/// What a tile's static nodes add to the run's totals: their transmissions (count, bytes,
/// energy) and receptions (what they heard and what was addressed to them). The mobile nodes'
/// share is the same in every tile, so it is never added twice.
struct TileTotals {
  sim::ExactSum tx_j;
  std::array<sim::ExactSum, kMaxMessageTypes> tx_j_by_type{};
  std::uint64_t heard_bytes = 0;
  std::array<std::uint64_t, kMaxMessageTypes> heard_by_type{};
  std::array<TypeCounters, kMaxMessageTypes> counters{};
};

}  // namespace masnet::net
