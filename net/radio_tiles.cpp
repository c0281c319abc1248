// One tile of a run cut by space (docs/decisions/0012-partitioned-runs.md): a radio that books
// and delivers to its own static nodes and to the mobile nodes it runs, ships its static senders'
// frames (and those of the mobile nodes, if only it runs them) to the other tiles, takes theirs in,
// and at the end absorbs the other tiles' ledgers so that one radio reads as the whole run's.
#include <algorithm>
#include <limits>

#include "net/radio.hpp"
#include "net/tile_ledger.hpp"

namespace masnet::net {

const std::vector<NodeId>& Radio::static_slots() {
  if (index_dirty_) prepare_index();
  return use_lines_ ? line_index_.ids() : static_grid_.ids();
}

void Radio::own_static_slots(std::uint32_t first, std::uint32_t end) {
  MASNET_ASSERT(simulator_.ties_by_origin(), "tiles run in the origin order");
  MASNET_ASSERT(!contended_ && params_.jitter_s <= 0 && !any_battery_ && !link_faults_.any(),
                "tiles need level ideal or airtime, no jitter or batteries, and start with no "
                "link faults in force");
  const auto slots = static_cast<std::uint32_t>(static_slots().size());
  MASNET_ASSERT(first <= end && end <= slots, "a tile owns slots of the index");
  owned_first_ = first;
  owned_end_ = end;
  tiled_ = true;
  // A frame whose disk misses the band in y books nobody here: skipped before any search.
  band_y_min_ = std::numeric_limits<double>::infinity();
  band_y_max_ = -band_y_min_;
  for (std::uint32_t k = first; k < end; ++k) {
    const double y = positions_[sim::index(static_slots()[k])].y();
    band_y_min_ = std::min(band_y_min_, y);
    band_y_max_ = std::max(band_y_max_, y);
  }
  for (Eigen::AlignedBox2d& extent : others_extents_)
    extent.setEmpty();
  for (std::uint32_t k = 0; k < slots; ++k)
    if (k < first || k >= end)
      others_extents_[k < first ? 0 : 1].extend(positions_[sim::index(static_slots()[k])]);
  // Every tile would start its own: the tiles are the run's parallelism.
  params_.overhearing_thread = false;
}

void Radio::home_mobiles(bool here) {
  MASNET_ASSERT(tiled_, "a tile's robots");
  mobiles_here_ = here;
  ships_mobiles_ = here;
}

bool Radio::owns(NodeId node) const {
  const std::uint32_t hot = hot_[sim::index(node)];
  return hot >= static_ids_.size() ? mobiles_here_ : owned_slot(hot);
}

bool Radio::needed_by_other_tiles(const Vec2& center, NodeId destination, double range,
                                  bool reached) const {
  // Another tile delivers a frame to the mobile hearers and the addressee it runs, and to its own
  // static nodes within range.
  if (!ships_mobiles_) {  // another tile runs the mobile nodes
    if (!record_mobiles_.empty()) return true;
    if (destination != sim::kNoNode && reached &&
        hot_[sim::index(destination)] >= static_ids_.size())
      return true;
  }
  const double reach = range + 1e-9 * (center.cwiseAbs().maxCoeff() + range + 1.0);  // rounding
  return std::any_of(others_extents_.begin(), others_extents_.end(), [&](const auto& extent) {
    return !extent.isEmpty() && extent.squaredExteriorDistance(center) <= reach * reach;
  });
}

void Radio::inject(const FrameRecord& record) {
  MASNET_ASSERT(tiled_ && record.arrival >= simulator_.now(), "a tile's frame arrives later");
  if (index_dirty_) prepare_index();
  const Outgoing out{
      record.source, record.destination, sim::index(record.source),   record.type_index,
      record.bytes,  record.range,       record.destination_distance, record.frame_number};
  const Heard heard = link_history_.at(record.link_epoch).any() ? hear<true, true>(out, &record)
                                                                : hear<false, true>(out, &record);
  book_heard(record.type_index, record.bytes, heard);
  if (scratch_receivers_.empty()) return;
  Payload payload = record.payload;
  deliver(record.arrival, out, record.sent_at, std::move(payload), &record.key);
}

Radio::TileLedger Radio::tile_ledger(std::uint32_t from, std::uint32_t to) {
  MASNET_ASSERT(tiled_, "a tile's ledger");
  from = std::min(std::max(from, owned_first_), owned_end_);
  to = std::max(from, std::min(to, owned_end_));
  materialize();
  const std::vector<NodeId>& slots = static_slots();
  TileLedger ledger;
  ledger.first_slot = from;
  ledger.end_slot = to;
  if (from == owned_first_) ledger.totals = static_share_;  // once, with the first slots
  const std::size_t width = to - from;
  ledger.nodes.reserve(width);
  ledger.senders.reserve(width);
  ledger.heard_bytes.reserve(width);
  ledger.overheard_count.reserve(width);
  ledger.tx.resize(type_count_ * width);
  ledger.rx_count.resize(type_count_ * width);
  ledger.rx_bytes.resize(type_count_ * width);
  for (std::size_t i = 0; i < width; ++i) {
    const std::size_t k = from + i, n = sim::index(slots[k]);
    ledger.nodes.push_back(nodes_[n]);
    ledger.lives.push_back(life_of(n));
    ledger.senders.push_back(senders_[n]);
    ledger.heard_bytes.push_back(heard_bytes_[k]);
    ledger.overheard_count.push_back(overheard_count_[k]);
    for (std::size_t t = 0; t < type_count_; ++t) {
      const TypeCounters c = written_counters(t, n);  // the static node n is slot k
      ledger.tx[t * width + i] = TxCounter{c.tx_count, c.tx_bytes};
      ledger.rx_count[t * width + i] = c.rx_count;
      ledger.rx_bytes[t * width + i] = c.rx_bytes;
    }
  }
  return ledger;
}

void Radio::absorb_tile(const TileLedger& tile) {
  const std::size_t width = tile.end_slot - tile.first_slot;
  MASNET_ASSERT(tiled_ && tile.first_slot <= tile.end_slot &&
                    tile.end_slot <= static_slots().size() && tile.nodes.size() == width &&
                    tile.lives.size() == width && tile.senders.size() == width &&
                    tile.heard_bytes.size() == width && tile.overheard_count.size() == width &&
                    tile.tx.size() == type_count_ * width &&
                    tile.rx_count.size() == type_count_ * width &&
                    tile.rx_bytes.size() == type_count_ * width,
                "a ledger of another tile of this run");
  materialize();
  const std::vector<NodeId>& slots = static_slots();
  const std::size_t tx_stride = tx_.size() / type_count_, rx_stride = heard_bytes_.size();
  MASNET_ASSERT(nodes_.size() == tx_stride, "the index covers every node");
  // This radio never booked the absorbed slots: their counters are zero here (fill_in).
  for (std::size_t i = 0; i < width; ++i) {
    const std::size_t k = tile.first_slot + i, n = sim::index(slots[k]);
    nodes_[n] = tile.nodes[i];
    if (tile.lives[i] != NodeLife{}) life_to_write(n) = tile.lives[i];
    senders_[n] = tile.senders[i];
    heard_bytes_.fill_in(k, tile.heard_bytes[i]);
    overheard_count_.fill_in(k, tile.overheard_count[i]);
    for (std::size_t t = 0; t < type_count_; ++t) {
      const TxCounter& sent = tile.tx[t * width + i];
      if ((sent.count | sent.bytes) != 0) {
        tx_[t * tx_stride + n] = sent;
        tx_written_[t].add(n);
      }
      const std::uint64_t count = tile.rx_count[t * width + i],
                          bytes = tile.rx_bytes[t * width + i];
      if ((count | bytes) == 0) continue;
      rx_count_[t * rx_stride + k] = count;
      rx_bytes_[t * rx_stride + k] = bytes;
      rx_written_[t].add(k);
    }
  }
  // The tile's share of the totals, as it booked it: the sums of the counters above.
  const TileTotals& share = tile.totals;
  total_tx_j_.add(share.tx_j);
  total_heard_bytes_ += share.heard_bytes;
  for (std::size_t t = 0; t < kMaxMessageTypes; ++t) {
    tx_j_by_type_[t].add(share.tx_j_by_type[t]);
    heard_bytes_by_type_[t] += share.heard_by_type[t];
    totals_[t].tx_count += share.counters[t].tx_count;
    totals_[t].tx_bytes += share.counters[t].tx_bytes;
    totals_[t].rx_count += share.counters[t].rx_count;
    totals_[t].rx_bytes += share.counters[t].rx_bytes;
  }
  sibling_shares_.clear();  // the shares are in the totals now
  // This radio now holds the absorbed tile's slots too (absorbing tiles in slot order keeps
  // them one range).
  owned_first_ = std::min(owned_first_, tile.first_slot);
  owned_end_ = std::max(owned_end_, tile.end_slot);
}

}  // namespace masnet::net
