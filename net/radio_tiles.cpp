// One tile of a run cut by space (docs/decisions/0012-partitioned-runs.md): a radio that books
// and delivers to its own static nodes and to every mobile node, ships its static senders' frames
// to the other tiles, takes theirs in, and at the end absorbs the other tiles' ledgers so that
// one radio reads as the whole run's.
#include <algorithm>
#include <limits>

#include "net/radio.hpp"

namespace masnet::net {

const std::vector<NodeId>& Radio::static_slots() {
  if (index_dirty_) prepare_index();
  return use_lines_ ? line_index_.ids() : static_grid_.ids();
}

void Radio::own_static_slots(std::uint32_t first, std::uint32_t end) {
  MASNET_ASSERT(simulator_.ties_by_origin(), "tiles run in the origin order");
  MASNET_ASSERT(!contended_ && params_.jitter_s <= 0 && !guarded() && !link_faults_.any(),
                "tiles need level ideal or airtime, no jitter, batteries or faults");
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
  // Every tile would start its own: the tiles are the run's parallelism.
  params_.overhearing_thread = false;
}

bool Radio::owns(NodeId node) const {
  const std::uint32_t hot = hot_[sim::index(node)];
  return hot >= static_ids_.size() || owned_slot(hot);
}

void Radio::inject(const FrameRecord& record) {
  MASNET_ASSERT(tiled_ && record.arrival >= simulator_.now(), "a tile's frame arrives later");
  if (index_dirty_) prepare_index();
  const Outgoing out{
      record.source, record.destination, sim::index(record.source),   record.type_index,
      record.bytes,  record.range,       record.destination_distance, record.frame_number};
  const Heard heard = hear<false, true>(out, &record);
  book_heard(record.type_index, record.bytes, heard);
  if (scratch_receivers_.empty()) return;
  Payload payload = record.payload;
  deliver(record.arrival, out, record.sent_at, std::move(payload), &record.key);
}

void Radio::absorb_tile(Radio& tile) {
  MASNET_ASSERT(tiled_ && tile.tiled_ && tile.nodes_.size() == nodes_.size() &&
                    tile.static_slots() == static_slots(),
                "tiles of one run");
  materialize();
  tile.materialize();
  const std::vector<NodeId>& slots = static_slots();
  const std::size_t n_nodes = nodes_.size(), tx_stride = tx_.size() / type_count_;
  const std::size_t rx_stride = heard_bytes_.size();
  for (std::uint32_t k = tile.owned_first_; k < tile.owned_end_; ++k) {
    const std::size_t n = sim::index(slots[k]);
    nodes_[n] = tile.nodes_[n];
    senders_[n] = tile.senders_[n];
    heard_bytes_[k] = tile.heard_bytes_[k];
    overheard_count_[k] = tile.overheard_count_[k];
    for (std::size_t t = 0; t < type_count_; ++t) {
      const TxCounter sent = tile.tx_[t * tx_stride + n];
      tx_[t * tx_stride + n] = sent;
      totals_[t].tx_count += sent.count;
      totals_[t].tx_bytes += sent.bytes;
      rx_count_[t * rx_stride + k] = tile.rx_count_[t * rx_stride + k];
      rx_bytes_[t * rx_stride + k] = tile.rx_bytes_[t * rx_stride + k];
      totals_[t].rx_count += rx_count_[t * rx_stride + k];
      totals_[t].rx_bytes += rx_bytes_[t * rx_stride + k];
    }
  }
  MASNET_ASSERT(n_nodes == tx_stride, "the index covers every node");
  std::erase(siblings_, &tile);  // its share is in the totals now
  total_tx_j_.add(tile.static_tx_j_);
  total_heard_bytes_ += tile.static_heard_bytes_;
  for (std::size_t t = 0; t < kMaxMessageTypes; ++t) {
    tx_j_by_type_[t].add(tile.static_tx_j_by_type_[t]);
    heard_bytes_by_type_[t] += tile.static_heard_by_type_[t];
  }
  // This radio now holds the absorbed tile's slots too (absorbing tiles in slot order keeps
  // them one range).
  owned_first_ = std::min(owned_first_, tile.owned_first_);
  owned_end_ = std::max(owned_end_, tile.owned_end_);
}

}  // namespace masnet::net
