#include "net/radio.hpp"

#include <algorithm>
#include <cmath>

#include "sim/random.hpp"

namespace masnet::net {
namespace {
constexpr std::uint64_t kLossPurpose = sim::purpose("radio.loss");
constexpr std::uint64_t kJitterPurpose = sim::purpose("radio.jitter");
}  // namespace

Radio::Radio(sim::Simulator& simulator, const RadioParams& params, std::uint64_t seed)
    : simulator_(simulator), params_(params), seed_(seed) {
  MASNET_ASSERT(params.max_range > 0 && params.bitrate_bps > 0 && params.loss >= 0 &&
                    params.loss <= 1 && params.latency_s >= 0 && params.jitter_s >= 0,
                "radio parameters are validated by the scenario loader");
}

void Radio::add_static_node(NodeId id, const Vec2& position, std::uint64_t random_key) {
  MASNET_ASSERT(sim::index(id) == nodes_.size(), "node ids are dense from 0");
  nodes_.push_back(Node{});
  nodes_.back().position = position;
  nodes_.back().random_key = random_key;
  nodes_.back().idle_accounted_to = simulator_.now();
  counters_.resize(nodes_.size() * kMessageTypeCount);
  static_ids_.push_back(id);
  static_positions_.push_back(position);
  static_index_dirty_ = true;
  if (params_.energy.battery_j > 0 && params_.energy.idle_power_w > 0) schedule_depletion(id);
}

void Radio::add_mobile_node(NodeId id, std::uint64_t random_key) {
  MASNET_ASSERT(sim::index(id) == nodes_.size(), "node ids are dense from 0");
  nodes_.push_back(Node{});
  nodes_.back().mobile = true;
  nodes_.back().random_key = random_key;
  nodes_.back().idle_accounted_to = simulator_.now();
  counters_.resize(nodes_.size() * kMessageTypeCount);
  mobile_ids_.push_back(id);
  mobile_index_valid_ = false;
  if (params_.energy.battery_j > 0 && params_.energy.idle_power_w > 0) schedule_depletion(id);
}

void Radio::set_interest(NodeId node, std::uint32_t mask) { nodes_[sim::index(node)].interest = mask; }

Vec2 Radio::position(NodeId node) const {
  const Node& n = nodes_[sim::index(node)];
  if (!n.mobile) return n.position;
  MASNET_ASSERT(mobile_ != nullptr, "mobile nodes need a MobilePositions");
  return mobile_->position(node);
}

sim::Duration Radio::airtime(std::uint32_t bytes) const {
  return sim::seconds(static_cast<double>(bytes) * 8.0 / params_.bitrate_bps);
}

bool Radio::broadcast(NodeId source, double range, Payload payload) {
  return transmit(source, sim::kNoNode, range, std::move(payload));
}

bool Radio::unicast(NodeId source, NodeId destination, Payload payload) {
  MASNET_ASSERT(destination != source && sim::index(destination) < nodes_.size(),
                "unicast to a registered other node");
  const double distance = (position(destination) - position(source)).norm();
  return transmit(source, destination, distance, std::move(payload));
}

void Radio::prepare_static_index() {
  static_grid_.build(static_positions_, static_ids_);
  static_index_dirty_ = false;
}

void Radio::prepare_mobile_index() {
  const sim::Time now = simulator_.now();
  const double age_s = sim::to_seconds(now - mobile_index_time_);
  if (mobile_index_valid_ && margin_speed_ * age_s <= 0.5 * mobile_grid_.cell_size()) return;
  std::vector<Vec2> positions;
  positions.reserve(mobile_ids_.size());
  for (NodeId id : mobile_ids_) positions.push_back(mobile_->position(id));
  mobile_grid_.build(positions, mobile_ids_);
  mobile_index_time_ = now;
  margin_speed_ = mobile_->speed_bound();
  mobile_index_valid_ = true;
}

template <class Visit>
void Radio::for_each_node_within(NodeId source, const Vec2& center, double range, Visit&& visit) {
  if (static_index_dirty_) prepare_static_index();
  static_grid_.for_each_within(center, range, [&](NodeId id, const Vec2&, double) {
    if (id != source) visit(id);
  });
  for_each_mobile_within(center, range, [&](NodeId id) {
    if (id != source) visit(id);
  });
}

void Radio::accrue_idle(Node& node) {
  if (params_.energy.idle_power_w <= 0 || !node.stats.alive) return;
  const sim::Time now = simulator_.now();
  node.stats.energy_idle_j +=
      params_.energy.idle_power_w * sim::to_seconds(now - node.idle_accounted_to);
  node.idle_accounted_to = now;
}

const NodeRadioStats& Radio::stats(NodeId node) {
  accrue_idle(nodes_[sim::index(node)]);
  return nodes_[sim::index(node)].stats;
}

bool Radio::charge(NodeId id, double energy_j, bool is_tx) {
  Node& node = nodes_[sim::index(id)];
  NodeRadioStats& s = node.stats;
  if (params_.energy.battery_j > 0) {
    accrue_idle(node);
    const double remaining =
        params_.energy.battery_j - (s.energy_tx_j + s.energy_rx_j + s.energy_idle_j);
    if (remaining < energy_j) {  // cannot afford this frame: the battery is empty
      kill(id);
      return false;
    }
  }
  (is_tx ? s.energy_tx_j : s.energy_rx_j) += energy_j;
  (is_tx ? total_tx_j_ : total_rx_j_) += energy_j;
  if (params_.energy.battery_j > 0 && params_.energy.idle_power_w > 0) schedule_depletion(id);
  return true;
}

void Radio::schedule_depletion(NodeId id) {
  Node& node = nodes_[sim::index(id)];
  const NodeRadioStats& s = node.stats;
  const double remaining =
      params_.energy.battery_j - (s.energy_tx_j + s.energy_rx_j + s.energy_idle_j);
  simulator_.cancel(node.depletion_event);
  // The idle drain empties the battery at a known time: a scheduled event, not a poll.
  const sim::Duration left = sim::seconds(std::max(remaining, 0.0) / params_.energy.idle_power_w);
  node.depletion_event = simulator_.after(left, [this, id] {
    accrue_idle(nodes_[sim::index(id)]);
    kill(id);
  });
}

void Radio::kill(NodeId id) {
  Node& node = nodes_[sim::index(id)];
  if (!node.stats.alive) return;
  node.stats.alive = false;
  node.stats.died_at = simulator_.now();
  simulator_.cancel(node.depletion_event);
  if (listener_) listener_->on_battery_empty(id);
}

bool Radio::transmit(NodeId source, NodeId destination, double range, Payload&& payload) {
  Node& sender = nodes_[sim::index(source)];
  if (!sender.stats.alive) {
    ++sender.stats.refused_count;
    return false;
  }
  range = std::min(range, params_.max_range);
  const MessageType type = type_of(payload);
  const std::uint32_t bytes = size_bytes(payload, params_.sizes);
  const double bits = 8.0 * bytes;
  if (!charge(source, tx_energy_j(params_.energy, bits, range * params_.meters_per_unit), true)) {
    ++nodes_[sim::index(source)].stats.refused_count;
    return false;
  }
  Node& src = nodes_[sim::index(source)];
  TypeCounters& tx = counters_[sim::index(source) * kMessageTypeCount + static_cast<std::size_t>(type)];
  ++tx.tx_count;
  tx.tx_bytes += bytes;
  ++totals_[static_cast<std::size_t>(type)].tx_count;
  totals_[static_cast<std::size_t>(type)].tx_bytes += bytes;
  const std::uint64_t frame_number = src.frames_sent++;

  const sim::Time now = simulator_.now();
  const sim::Duration air = airtime(bytes);
  sim::Time start = now;
  if (params_.level == RadioLevel::airtime) {
    start = std::max(now, src.busy_until);
    src.busy_until = start + air;
  }
  const sim::Time arrival = start + air + sim::seconds(params_.latency_s);

  const double rx_j = rx_energy_j(params_.energy, bits);
  const std::uint32_t type_bit = 1u << static_cast<unsigned>(type);
  std::vector<NodeId>& receivers = scratch_receivers_;
  receivers.clear();
  auto hear = [&](NodeId id, bool addressed) {
    Node& node = nodes_[sim::index(id)];
    if (!node.stats.alive || !charge(id, rx_j, false)) return;
    if (!addressed) {  // every node in range pays for the frame, addressed or not
      ++node.stats.overheard_count;
      node.stats.overheard_bytes += bytes;
      return;
    }
    if (params_.loss > 0 &&
        sim::keyed_uniform01(seed_, kLossPurpose, src.random_key, node.random_key,
                             frame_number) < params_.loss) {
      ++node.stats.lost_count;
      return;
    }
    TypeCounters& rx =
        counters_[sim::index(id) * kMessageTypeCount + static_cast<std::size_t>(type)];
    ++rx.rx_count;
    rx.rx_bytes += bytes;
    ++totals_[static_cast<std::size_t>(type)].rx_count;
    totals_[static_cast<std::size_t>(type)].rx_bytes += bytes;
    if (node.interest & type_bit) receivers.push_back(id);
  };

  const Vec2 center = position(source);
  const bool is_broadcast = destination == sim::kNoNode;
  for_each_node_within(source, center, range, [&](NodeId id) {
    if (id != destination) hear(id, is_broadcast);
  });
  if (!is_broadcast) {
    // The addressee is decided by its distance, not by the grid's rounding at the boundary.
    if ((position(destination) - center).norm() <= range) {
      hear(destination, true);
    } else {
      ++src.stats.unreachable_count;
    }
  }
  if (receivers.empty()) return true;
  // Delivery order is by node id, whatever the grid's layout.
  std::sort(receivers.begin(), receivers.end());

  std::uint32_t flight;
  if (!free_flights_.empty()) {
    flight = free_flights_.back();
    free_flights_.pop_back();
  } else {
    flight = static_cast<std::uint32_t>(flights_.size());
    flights_.emplace_back();
  }
  InFlight& f = flights_[flight];
  f.frame.source = source;
  f.frame.destination = destination;
  f.frame.type = type;
  f.frame.size_bytes = bytes;
  f.frame.range = range;
  f.frame.sent_at = now;
  f.frame.payload = std::move(payload);
  f.receivers.assign(receivers.begin(), receivers.end());

  if (params_.jitter_s <= 0) {
    // One event delivers to every receiver in id order: the same order separate events with
    // consecutive sequence numbers would give, at a fraction of the cost.
    f.pending = 1;
    simulator_.at(arrival, [this, flight] { deliver(flight); });
  } else {
    f.pending = static_cast<std::uint32_t>(f.receivers.size());
    for (NodeId id : f.receivers) {
      const double u = sim::keyed_uniform01(seed_, kJitterPurpose, src.random_key,
                                            nodes_[sim::index(id)].random_key, frame_number);
      simulator_.at(arrival + sim::seconds(u * params_.jitter_s),
                    [this, flight, id] { deliver_one(flight, id); });
    }
  }
  return true;
}

void Radio::hand_over(const Frame& frame, NodeId receiver) {
  if (!nodes_[sim::index(receiver)].stats.alive) return;  // died while the frame was in the air
  sim::Fingerprint& fp = simulator_.fingerprint();
  fp.mix((std::uint64_t{sim::index(frame.source)} << 32) | sim::index(receiver));
  fp.mix((std::uint64_t{static_cast<std::uint8_t>(frame.type)} << 32) | frame.size_bytes);
  if (listener_) listener_->on_frame(receiver, frame);
}

void Radio::deliver(std::uint32_t flight) {
  const InFlight& f = flights_[flight];
  for (NodeId id : f.receivers) hand_over(f.frame, id);
  release(flight);
}

void Radio::deliver_one(std::uint32_t flight, NodeId id) {
  InFlight& f = flights_[flight];
  hand_over(f.frame, id);
  if (--f.pending == 0) release(flight);
}

void Radio::release(std::uint32_t flight) { free_flights_.push_back(flight); }

}  // namespace masnet::net
