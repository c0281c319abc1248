#pragma once
// Everything a tile of a partitioned run knows alone of its static nodes
// (docs/decisions/0012-partitioned-runs.md): their ledger, senders' records, counters and
// overhearing, by slot, and the tile's share of the totals. Plain values: the tile absorbing it
// takes it from another thread's radio or from bytes another rank sent.
#include <cstdint>
#include <vector>

#include "net/radio.hpp"

namespace masnet::net {

struct Radio::TileLedger {
  std::uint32_t first_slot = 0, end_slot = 0;  // the tile's static slots
  TileTotals totals;
  std::vector<Node> nodes;                                  // [slot - first_slot]
  std::vector<NodeLife> lives;                              // [slot - first_slot]
  std::vector<Sender> senders;                              // [slot - first_slot]
  std::vector<std::uint64_t> heard_bytes, overheard_count;  // [slot - first_slot]
  std::vector<TxCounter> tx;                                // [type][slot - first_slot]
  std::vector<std::uint64_t> rx_count, rx_bytes;            // [type][slot - first_slot]

  /// Calls `visit` on every member in one fixed order: single values, then vectors of plain
  /// records (how a ledger is written to bytes and read back).
  template <class Visit>
  void for_each_part(Visit&& visit) {
    visit(first_slot);
    visit(end_slot);
    visit(totals);
    visit(nodes);
    visit(lives);
    visit(senders);
    visit(heard_bytes);
    visit(overheard_count);
    visit(tx);
    visit(rx_count);
    visit(rx_bytes);
  }
};

}  // namespace masnet::net
