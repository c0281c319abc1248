#include "net/radio.hpp"

#include <algorithm>
#include <cmath>

#include "net/contended_medium.hpp"
#include "sim/random.hpp"

namespace masnet::net {

Vec2 Radio::position(NodeId node) const {
  const Vec2& known = positions_[sim::index(node)];
  if (!std::isnan(known.x())) return known;
  MASNET_ASSERT(mobile_ != nullptr, "mobile nodes need a MobilePositions");
  return mobile_->position(node);
}

sim::Duration Radio::compute_airtime(std::uint32_t bytes) const {
  return sim::seconds(static_cast<double>(bytes) * 8.0 / params_.bitrate_bps);
}

sim::Duration Radio::airtime(std::uint32_t bytes) const {
  return bytes < kAirtimeTableBytes ? airtime_table_[bytes] : compute_airtime(bytes);
}

bool Radio::broadcast(NodeId source, double range, Payload payload) {
  return transmit(source, sim::kNoNode, range, std::move(payload));
}

bool Radio::unicast(NodeId source, NodeId destination, Payload payload) {
  MASNET_ASSERT(destination != source && sim::index(destination) < nodes_.size(),
                "unicast to a registered other node");
  const double distance = (position(destination) - position(source)).norm();
  return transmit(source, destination, distance, std::move(payload), distance);
}

const Radio::MobileCoordinates& Radio::mobile_positions_now() {
  const sim::Time now = simulator_.now();
  if (!mobile_cache_valid_ || mobile_cache_time_ != now ||
      mobile_cache_.xs.size() != mobile_ids_.size()) {
    mobile_cache_.xs.resize(mobile_ids_.size());
    mobile_cache_.ys.resize(mobile_ids_.size());
    for (std::size_t m = 0; m < mobile_ids_.size(); ++m) {
      const Vec2 p = mobile_->position(mobile_ids_[m]);
      mobile_cache_.xs[m] = p.x();
      mobile_cache_.ys[m] = p.y();
    }
    mobile_cache_time_ = now;
    mobile_cache_valid_ = true;
  }
  return mobile_cache_;
}

void Radio::prepare_mobile_index() {
  const sim::Time now = simulator_.now();
  const double age_s = sim::to_seconds(now - mobile_index_time_);
  if (mobile_index_valid_ && margin_speed_ * age_s <= 0.5 * mobile_grid_.cell_size()) return;
  std::vector<Vec2> positions;
  positions.reserve(mobile_ids_.size());
  for (NodeId id : mobile_ids_)
    positions.push_back(mobile_->position(id));
  mobile_grid_.build(positions, mobile_ids_);
  mobile_index_time_ = now;
  ++mobile_index_generation_;
  margin_speed_ = mobile_->speed_bound();
  mobile_index_valid_ = true;
}

const Radio::NearAddressee* Radio::near_addressee(NodeId addressee, double extent) {
  const double needed = extent * (1.0 + 1e-9);  // covers the rounding of the distances summed
  const sim::Time now = simulator_.now();
  if (!(near_.addressee == addressee && near_.at == now &&
        near_.index_generation == mobile_index_generation_)) {
    // The first frame to this addressee now: most are the only one (a NEIGHBOR), and walking
    // the grid once is cheaper than gathering the neighbourhood. Remember it, gather on the next.
    near_.addressee = addressee;
    near_.at = now;
    near_.index_generation = mobile_index_generation_;
    near_.reach = -1.0;  // nothing gathered yet
    return nullptr;
  }
  if (needed <= near_.reach) return &near_;
  // Half as much again: the next replies of the burst come from farther senders as often as not.
  near_.reach = 1.5 * needed;
  near_.xs.clear();
  near_.ys.clear();
  near_.ids.clear();
  mobile_grid_.for_each_within(position(addressee), near_.reach,
                               [&](NodeId id, const Vec2& indexed, double) {
                                 near_.xs.push_back(indexed.x());
                                 near_.ys.push_back(indexed.y());
                                 near_.ids.push_back(id);
                               });
  return &near_;
}

double Radio::idle_j(NodeId id) const {
  const EnergyParams& e = params_.energy;
  if (e.idle_power_w <= 0) return 0.0;
  const NodeLife& life = life_of(sim::index(id));
  const sim::Time until = std::min(simulator_.now(), died_at(sim::index(id)));
  double idle_s = life.earlier_lives_s + sim::to_seconds(until - life.added_at);
  if (e.model == EnergyModel::states) {
    // Idle is what is left of its life after sending and receiving.
    const std::uint32_t hot = hot_[sim::index(id)];
    const double heard_bits =
        hot == kNoHotIndex ? 0.0 : 8.0 * static_cast<double>(heard_bytes_[hot]);
    idle_s -= senders_[sim::index(id)].energy_tx_j / (e.voltage_v * e.tx_current_a) +
              heard_bits * e.seconds_per_bit;
  }
  return e.idle_power_w * std::max(idle_s, 0.0);
}

double Radio::consumed_j(NodeId id) const {
  return senders_[sim::index(id)].energy_tx_j + idle_j(id) +
         rx_energy_j(params_.energy, 8.0 * static_cast<double>(heard_bytes_[hot_[sim::index(id)]]));
}

bool Radio::afford(NodeId id, double energy_j) {
  // Only with a battery: a node that cannot pay for a frame is empty and stops.
  if (!nodes_[sim::index(id)].alive) return false;
  const double battery_j = life_of(sim::index(id)).battery_j;
  if (battery_j > 0 && battery_j - consumed_j(id) < energy_j) {
    kill(id);
    return false;
  }
  return true;
}

void Radio::schedule_depletion(NodeId id) {
  const std::size_t n = sim::index(id);
  const double battery_j = life_of(n).battery_j;
  if (battery_j <= 0 || !nodes_[n].alive) return;
  const std::uint32_t hot = hot_[n];
  const double remaining =
      battery_j - senders_[n].energy_tx_j - idle_j(id) -
      (hot == kNoHotIndex
           ? 0.0
           : rx_energy_j(params_.energy, 8.0 * static_cast<double>(heard_bytes_[hot])));
  if (depletion_events_.size() < nodes_.size()) depletion_events_.resize(nodes_.size());
  simulator_.cancel(depletion_events_[n]);
  // The idle drain empties the battery at a known time: a scheduled event, not a poll. Any
  // node's frame may move it (receptions are booked when sent), so in the origin order its key
  // names only the node (docs/decisions/0012-partitioned-runs.md).
  const sim::Duration left = sim::seconds(std::max(remaining, 0.0) / params_.energy.idle_power_w);
  depletion_events_[n] = simulator_.at_instant_end(sim::origin_of(id), simulator_.now() + left,
                                                   [this, id] { kill(id); });
}

void Radio::mix_refusal(NodeId source) {
  sim::Fingerprint& traffic = senders_[sim::index(source)].traffic;
  traffic.mix(static_cast<std::uint64_t>(sim::to_ns(simulator_.now())));
  traffic.mix(kRefusedMark | sim::index(source));
}

void Radio::kill(NodeId id) {  // the battery is empty
  Node& node = nodes_[sim::index(id)];
  if (!node.alive) return;
  node.alive = false;
  life_to_write(sim::index(id)).died_at = simulator_.now();
  cancel_depletion(sim::index(id));
  if (listener_) listener_->on_battery_empty(id);
}

void Radio::set_battery(NodeId id, double battery_j) {
  if (battery_j != life_of(sim::index(id)).battery_j)
    life_to_write(sim::index(id)).battery_j = battery_j;
  if (battery_j > 0) any_battery_ = true;
  if (battery_j > 0 && params_.energy.idle_power_w > 0)
    schedule_depletion(id);
  else
    cancel_depletion(sim::index(id));
}

void Radio::take_down(NodeId id) {
  Node& node = nodes_[sim::index(id)];
  if (!node.alive) return;
  node.alive = false;
  life_to_write(sim::index(id)).died_at = simulator_.now();
  cancel_depletion(sim::index(id));
}

bool Radio::bring_up(NodeId id) {
  Node& node = nodes_[sim::index(id)];
  if (node.alive) return false;
  NodeLife& life = life_to_write(sim::index(id));  // written when it went down
  if (life.battery_j > 0 && life.battery_j - consumed_j(id) <= 0) return false;
  life.earlier_lives_s += sim::to_seconds(life.died_at - life.added_at);
  life.added_at = simulator_.now();
  life.died_at = sim::Time{};
  node.alive = true;
  schedule_depletion(id);
  return true;
}

bool Radio::transmit(NodeId source, NodeId destination, double range, Payload&& payload,
                     double destination_distance) {
  if (index_dirty_) prepare_index();
  if (contended_)
    return contended_->send(source, destination, std::min(range, params_.max_range),
                            std::move(payload));
  // The ledger: the sender pays for the frame, or is refused (an empty battery).
  const std::size_t source_index = sim::index(source);
  const bool battery = battery_limited();
  // Only a battery or a fault takes a node down: without either every node is up, and its cold
  // record is not fetched for a frame.
  if (guarded() && !nodes_[source_index].alive) {
    ++life_to_write(source_index).refused_count;
    mix_refusal(source);
    return false;
  }
  Sender& src = senders_[source_index];
  range = std::min(range, params_.max_range);
  const MessageType type = type_of(payload);
  const std::uint32_t bytes = size_bytes(payload, params_.sizes);
  const double bits = 8.0 * bytes;
  const double tx_j =
      tx_energy_j(params_.energy, bits, range * params_.meters_per_unit, crossover_m_);
  if (guarded() && !afford(source, tx_j)) {
    ++life_to_write(source_index).refused_count;
    mix_refusal(source);
    return false;
  }
  src.energy_tx_j += tx_j;
  total_tx_j_.add(tx_j);
  tx_j_by_type_[static_cast<std::size_t>(type)].add(tx_j);
  // A tile's static senders are its own share; the mobile ones are the share of the first tile,
  // which runs them all (with every other tile, or alone: then it ships their frames).
  const bool static_sender = tiled_ && hot_[source_index] < static_ids_.size();
  const bool shipped = static_sender || ships_mobiles_;
  if (static_sender) [[unlikely]] {
    static_share_.tx_j.add(tx_j);
    static_share_.tx_j_by_type[static_cast<std::size_t>(type)].add(tx_j);
    ++static_share_.counters[static_cast<std::size_t>(type)].tx_count;
    static_share_.counters[static_cast<std::size_t>(type)].tx_bytes += bytes;
  }
  if (battery && params_.energy.idle_power_w > 0) schedule_depletion(source);
  const auto type_index = static_cast<std::size_t>(type);
  MASNET_ASSERT(type_index < type_count_, "a message type registered after the radio was built");
  // The sender's per-type counter is a cache miss on large networks: fetch it now, count the
  // frame once the receivers are booked.
  TxCounter& sent = tx_[type_index * nodes_.size() + source_index];
  __builtin_prefetch(&sent, 1);
  ++totals_[type_index].tx_count;
  totals_[type_index].tx_bytes += bytes;
  const std::uint64_t frame_number = src.frames_sent++;

  // The medium access: when the frame goes out.
  const sim::Time now = simulator_.now();
  const sim::Duration air = airtime(bytes);
  sim::Time start = now;
  if (params_.level == RadioLevel::airtime) {  // this transmitter's frames queue up
    start = std::max(now, src.busy_until);
    src.busy_until = start + air;
  }
  const sim::Time arrival = start + air + latency_;

  // Reception: who hears the frame; each hearer pays, the receivers that want its type are
  // gathered in scratch_receivers_.
  const Outgoing out{source, destination, source_index,         type_index,
                     bytes,  range,       destination_distance, frame_number};
  const bool links = link_faults_.any();
  const Heard heard = tiled_  ? (links ? hear<true, true>(out) : hear<false, true>(out))
                      : links ? hear<true, false>(out)
                              : hear<false, false>(out);
  if (sent.count == 0) tx_written_[type_index].add(source_index);
  ++sent.count;
  sent.bytes += bytes;
  book_heard(type_index, bytes, heard);
  // What this frame was, in its sender's send order. Who heard it is not here: its hearers may
  // be booked elsewhere (the second thread, other tiles); they enter the traffic fingerprint as
  // per-node sums.
  src.traffic.mix(static_cast<std::uint64_t>(sim::to_ns(now)));
  src.traffic.mix((std::uint64_t{sim::index(source)} << 32) | sim::index(destination));
  src.traffic.mix((std::uint64_t{static_cast<std::uint8_t>(type)} << 32) | bytes);
  if (shipped) [[unlikely]] {
    // The other tiles' nodes get it from the record, with the key its delivery takes here
    // (taken whether or not anyone needs it: the sender's count is the run in one piece's).
    const sim::EventKey key = simulator_.next_key(arrival);
    const Vec2 center = position(source);
    if (needed_by_other_tiles(center, destination, range, heard.destination_reached)) {
      // Field by field: the sink's one record keeps its buffers' capacity.
      FrameRecord& record = outbox_sink_ ? outgoing_ : outbox_.emplace_back();
      record.sent_at = now;
      record.arrival = arrival;
      record.key = key;
      record.source = source;
      record.source_position = center;
      record.destination = destination;
      record.range = range;
      record.destination_distance = destination_distance;
      record.frame_number = frame_number;
      record.type_index = static_cast<std::uint32_t>(type_index);
      record.bytes = bytes;
      record.destination_reached = heard.destination_reached;
      record.mobile_hearers = record_mobiles_;
      record.payload = payload;
      record.link_epoch = link_history_.epoch();
      record.mobile_losses = record_losses_;
      record.destination_loss = record_destination_loss_;
      if (outbox_sink_) outbox_sink_(record);
    }
    if (!scratch_receivers_.empty()) deliver(arrival, out, now, std::move(payload), &key);
    return true;
  }
  // Delivery: the receivers get it at its arrival.
  if (scratch_receivers_.empty()) return true;
  deliver(arrival, out, now, std::move(payload));
  return true;
}

}  // namespace masnet::net
