// The radio's ledger read back: the per-node layout by hot index (prepare_index), the bulk
// bookings folded into the counters (materialize), and what reports and tests ask of it.
#include <algorithm>

#include "net/radio.hpp"

namespace masnet::net {

void Radio::prepare_index() {
  // Keep what each node has heard across a rebuild (nodes added after the first frame).
  materialize();
  const std::size_t n_nodes = nodes_.size(), types = type_count_;
  const std::size_t old_stride = heard_bytes_.size();  // 0: nothing booked yet
  const std::size_t kept = old_stride > 0 ? n_nodes : 0;
  std::vector<std::uint64_t> heard(kept, 0), overheard(kept, 0), count(kept * types, 0),
      bytes(kept * types, 0);
  for (std::size_t n = 0; n < kept; ++n) {
    const std::uint32_t hot = hot_[n];
    if (hot == kNoHotIndex) continue;
    heard[n] = heard_bytes_[hot];
    overheard[n] = overheard_count_[hot];
    for (std::size_t t = 0; t < types; ++t) {
      const TypeCounters c = written_counters(t, n);
      count[n * types + t] = c.rx_count;
      bytes[n * types + t] = c.rx_bytes;
    }
  }
  rx_written_ = {};  // the hot indices change: found again below
  // Per-type tx counters are by node id with a stride of the node count: re-lay them out. Only
  // the counts that are not zero are written, here and below: pages never written cost nothing.
  sim::ZeroedArray<TxCounter> tx(n_nodes * types);
  const std::size_t old_nodes = tx_.size() / types;
  for (std::size_t t = 0; t < types; ++t) {  // a node keeps its index: the spans stay
    const std::size_t end = std::min(old_nodes, std::size_t{tx_written_[t].end});
    for (std::size_t n = tx_written_[t].first; n < end; ++n)
      tx.fill_in(t * n_nodes + n, tx_[t * old_nodes + n]);
  }
  tx_ = std::move(tx);
  // Sensor grids lie on rows: index them as lines, so frames can be booked run by run.
  std::vector<Vec2> static_positions;
  static_positions.reserve(static_ids_.size());
  for (const NodeId id : static_ids_)
    static_positions.push_back(positions_[sim::index(id)]);
  use_lines_ = line_index_.build(static_positions, static_ids_);
  if (!use_lines_) static_grid_.build(static_positions, static_ids_);
  const std::vector<NodeId>& slots = use_lines_ ? line_index_.ids() : static_grid_.ids();
  static_interest_ = 0;
  static_interest_common_ = slots.empty() ? 0 : 0xFFFFFFFFu;
  for (std::uint32_t k = 0; k < slots.size(); ++k) {
    hot_[sim::index(slots[k])] = k;
    static_interest_ |= nodes_[sim::index(slots[k])].interest;
    static_interest_common_ &= nodes_[sim::index(slots[k])].interest;
  }
  for (std::size_t m = 0; m < mobile_ids_.size(); ++m)
    hot_[sim::index(mobile_ids_[m])] = static_cast<std::uint32_t>(slots.size() + m);
  interest_.assign(n_nodes, 0);
  for (std::size_t n = 0; n < n_nodes; ++n)
    interest_[hot_[n]] = nodes_[n].interest;
  heard_bytes_ = sim::ZeroedArray<std::uint64_t>(n_nodes);
  overheard_count_ = sim::ZeroedArray<std::uint64_t>(n_nodes);
  rx_count_ = sim::ZeroedArray<std::uint64_t>(n_nodes * types);
  rx_bytes_ = sim::ZeroedArray<std::uint64_t>(n_nodes * types);
  heard_diff_ = sim::ZeroedArray<std::uint64_t>(n_nodes + 1);
  rx_count_diff_ = sim::ZeroedArray<std::uint64_t>((n_nodes + 1) * types);
  rx_bytes_diff_ = sim::ZeroedArray<std::uint64_t>((n_nodes + 1) * types);
  for (std::size_t n = 0; n < kept; ++n) {
    const std::uint32_t hot = hot_[n];
    heard_bytes_.fill_in(hot, heard[n]);
    overheard_count_.fill_in(hot, overheard[n]);
    for (std::size_t t = 0; t < types; ++t) {
      if ((count[n * types + t] | bytes[n * types + t]) == 0) continue;
      rx_count_[t * n_nodes + hot] = count[n * types + t];
      rx_bytes_[t * n_nodes + hot] = bytes[n * types + t];
      rx_written_[t].add(hot);
    }
  }
  index_dirty_ = false;
}

void Radio::materialize() const {
  drain_overhearing();
  if (!diffs_pending_) return;
  const std::size_t n = heard_bytes_.size();
  // Bookings lie in a tile's own slots only (its runs are cut to them; a run ends one past):
  // folding there alone leaves the pages of the others' slots unwritten.
  const std::size_t first = tiled_ ? std::min<std::size_t>(owned_first_, n) : 0;
  const std::size_t end = tiled_ ? std::min<std::size_t>(owned_end_, n) : n;
  std::uint64_t packed = 0;
  for (std::size_t k = first; k < end; ++k) {
    packed += heard_diff_[k];
    heard_bytes_[k] += packed & (kOneOverheard - 1);
    overheard_count_[k] += packed >> kHeardBytesBits;
  }
  heard_diff_.zero(first, end + 1);
  pending_bulk_frames_ = pending_bulk_bytes_ = 0;
  // Only the message types some bulk broadcast booked (the others' rows stay unwritten).
  for (std::size_t t = 0; t < type_count_; ++t) {
    if (((bulk_types_ >> t) & 1u) == 0) continue;
    std::uint64_t count = 0, bytes = 0;
    for (std::size_t k = first; k < end; ++k) {
      count += rx_count_diff_[t * (n + 1) + k];
      bytes += rx_bytes_diff_[t * (n + 1) + k];
      rx_count_[t * n + k] += count;
      rx_bytes_[t * n + k] += bytes;
      heard_bytes_[k] += bytes;  // a bulk broadcast's receivers heard what they received
    }
    if (first < end) rx_written_[t].add(first, end);
    rx_count_diff_.zero(t * (n + 1) + first, t * (n + 1) + end + 1);
    rx_bytes_diff_.zero(t * (n + 1) + first, t * (n + 1) + end + 1);
  }
  bulk_types_ = 0;
  diffs_pending_ = false;
}

TypeCounters Radio::totals(MessageType type) const {
  const auto t = static_cast<std::size_t>(type);
  TypeCounters c = totals_[t];
  for (const TileTotals& tile : sibling_shares_) {
    const TypeCounters& share = tile.counters[t];
    c.tx_count += share.tx_count;
    c.tx_bytes += share.tx_bytes;
    c.rx_count += share.rx_count;
    c.rx_bytes += share.rx_bytes;
  }
  return c;
}

double Radio::total_tx_energy_j() const {
  sim::ExactSum sum = total_tx_j_;
  for (const TileTotals& tile : sibling_shares_)
    sum.add(tile.tx_j);
  return sum.value();
}

double Radio::total_rx_energy_j() const {
  drain_overhearing();
  std::uint64_t heard = total_heard_bytes_;
  for (const TileTotals& tile : sibling_shares_)
    heard += tile.heard_bytes;
  return rx_energy_j(params_.energy, 8.0 * static_cast<double>(heard));
}

double Radio::type_tx_energy_j(MessageType type) const {
  sim::ExactSum sum = tx_j_by_type_[static_cast<std::size_t>(type)];
  for (const TileTotals& tile : sibling_shares_)
    sum.add(tile.tx_j_by_type[static_cast<std::size_t>(type)]);
  return sum.value();
}

double Radio::type_rx_energy_j(MessageType type) const {
  drain_overhearing();
  std::uint64_t heard = heard_bytes_by_type_[static_cast<std::size_t>(type)];
  for (const TileTotals& tile : sibling_shares_)
    heard += tile.heard_by_type[static_cast<std::size_t>(type)];
  return net::rx_energy_j(params_.energy, 8.0 * static_cast<double>(heard));
}

TypeCounters Radio::written_counters(std::size_t type, std::size_t node) const {
  // Only where something was written (the spans): reading a never-written page costs a page.
  TypeCounters c;
  const std::size_t tx_stride = tx_.size() / type_count_;  // nodes at the last indexing
  if (node < tx_stride && tx_written_[type].covers(node)) {
    c.tx_count = tx_[type * tx_stride + node].count;
    c.tx_bytes = tx_[type * tx_stride + node].bytes;
  }
  const std::uint32_t hot = hot_[node];
  if (hot != kNoHotIndex && rx_written_[type].covers(hot)) {
    c.rx_count = rx_count_[type * heard_bytes_.size() + hot];
    c.rx_bytes = rx_bytes_[type * heard_bytes_.size() + hot];
  }
  return c;
}

std::uint64_t Radio::frames_sent(NodeId node) const {
  std::uint64_t total = 0;
  for (std::size_t t = 0; t < type_count_; ++t)
    total += written_counters(t, sim::index(node)).tx_count;
  return total;
}

TypeCounters Radio::counters(NodeId node, MessageType type) const {
  materialize();
  return written_counters(static_cast<std::size_t>(type), sim::index(node));
}

NodeRadioStats Radio::stats(NodeId node) {
  if (index_dirty_) prepare_index();
  materialize();
  const Node& n = nodes_[sim::index(node)];
  const NodeLife& life = life_of(sim::index(node));
  const std::uint32_t hot = hot_[sim::index(node)];
  NodeRadioStats s;
  s.heard_bytes = heard_bytes_[hot];
  s.overheard_count = overheard_count_[hot];
  s.lost_count = life.lost_count;
  s.unreachable_count = life.unreachable_count;
  s.refused_count = life.refused_count;
  s.energy_tx_j = senders_[sim::index(node)].energy_tx_j;
  s.energy_rx_j = rx_energy_j(params_.energy, 8.0 * static_cast<double>(s.heard_bytes));
  s.energy_idle_j = idle_j(node);
  s.alive = n.alive;
  s.died_at = died_at(sim::index(node));
  return s;
}

sim::Fingerprint Radio::traffic_fingerprint() {
  if (index_dirty_) prepare_index();
  materialize();
  // Each node's per-frame words are mixed in its send order as frames go (see transmit). The
  // overhearing of bulk unicasts, booked in any order and maybe on the second thread, enters
  // here as the folded per-node sums, in id order: the value does not depend on who booked them.
  sim::Fingerprint fp;
  const std::size_t n_nodes = nodes_.size();
  for (std::size_t n = 0; n < n_nodes; ++n) {
    const Node& node = nodes_[n];
    const std::uint32_t hot = hot_[n];
    if (!senders_[n].traffic.untouched()) {
      fp.mix(std::uint64_t{n});
      fp.mix(senders_[n].traffic.value());
    }
    fp.mix(heard_bytes_[hot]);
    fp.mix(overheard_count_[hot]);
    const NodeLife& life = life_of(n);
    fp.mix(life.lost_count);
    fp.mix((life.unreachable_count << 32) ^ life.refused_count);
    fp.mix(senders_[n].energy_tx_j);
    fp.mix(static_cast<std::uint64_t>(sim::to_ns(died_at(n))) ^ std::uint64_t{node.alive});
    for (std::size_t t = 0; t < type_count_; ++t) {
      const TypeCounters c = written_counters(t, n);
      if ((c.tx_count | c.tx_bytes | c.rx_count | c.rx_bytes) == 0)
        continue;  // most nodes use few types
      fp.mix(std::uint64_t{t} << 56 ^ n);
      fp.mix(c.tx_count);
      fp.mix(c.tx_bytes);
      fp.mix(c.rx_count);
      fp.mix(c.rx_bytes);
    }
  }
  return fp;
}

}  // namespace masnet::net
