#include "net/contended_medium.hpp"

#include <algorithm>
#include <cmath>

#include "net/radio.hpp"

namespace masnet::net {
namespace {
constexpr std::uint64_t kBackoffPurpose = sim::purpose("radio.backoff");
constexpr std::uint64_t kReceptionPurpose = sim::purpose("radio.reception");
}  // namespace

ContentionCounters& ContentionCounters::operator+=(const ContentionCounters& o) {
  transmissions += o.transmissions;
  delivered += o.delivered;
  collided += o.collided;
  channel_lost += o.channel_lost;
  dropped += o.dropped;
  access_failures += o.access_failures;
  queue_drops += o.queue_drops;
  retries += o.retries;
  backoffs += o.backoffs;
  acks += o.acks;
  latency_sum_s += o.latency_sum_s;
  return *this;
}

ContendedMedium::ContendedMedium(Radio& radio)
    : radio_(radio),
      params_(radio.params_.csma),
      propagation_(radio.params_.propagation),
      csma_(radio.params_.level == RadioLevel::csma),
      noise_mw_(dbm_to_mw(radio.params_.propagation.noise_floor_dbm)),
      carrier_sense_range_(radio.params_.csma.carrier_sense_range > 0
                               ? radio.params_.csma.carrier_sense_range
                               : radio.params_.max_range) {}

bool ContendedMedium::send(NodeId source, NodeId destination, double range, Payload&& payload) {
  if (deaf_until_.size() < radio_.nodes_.size()) {
    deaf_until_.resize(radio_.nodes_.size());
    locked_.resize(radio_.nodes_.size(), kNotLocked);
    receiving_.resize(radio_.nodes_.size());
  }
  while (macs_.size() < radio_.nodes_.size()) {
    Mac& fresh = macs_.emplace_back();
    fresh.random = sim::RandomStream::keyed(
        radio_.seed_, radio_.nodes_[macs_.size() - 1].random_key, kBackoffPurpose);
  }
  const std::size_t source_index = sim::index(source);
  if (radio_.guarded() && !radio_.nodes_[source_index].alive) {
    ++radio_.life_to_write(source_index).refused_count;
    radio_.mix_refusal(source);
    return false;
  }
  const MessageType type = type_of(payload);
  const auto type_index = static_cast<std::size_t>(type);
  const std::uint32_t bytes = size_bytes(payload, radio_.params_.sizes);
  Radio::TxCounter& sent = radio_.tx_[type_index * radio_.nodes_.size() + source_index];
  if (sent.count == 0) radio_.tx_written_[type_index].add(source_index);
  ++sent.count;
  sent.bytes += bytes;
  ++radio_.totals_[type_index].tx_count;
  radio_.totals_[type_index].tx_bytes += bytes;
  const std::uint64_t number = radio_.senders_[source_index].frames_sent++;
  Mac& m = mac(source);
  if (csma_ && m.queue.size() >= params_.queue_frames) {
    ++m.counters.dropped;
    ++m.counters.queue_drops;
    ++totals_[type_index].dropped;
    ++totals_[type_index].queue_drops;
    return true;  // taken, and lost: the MAC's business, as on a real node
  }
  m.queue.push_back(Outgoing{Frame{source, destination, type, bytes, range, radio_.simulator_.now(),
                                   number, std::move(payload)},
                             m.next_sequence++, 0});
  if (!m.busy) start_next(source);
  return true;
}

void ContendedMedium::start_next(NodeId node) {
  Mac& m = mac(node);
  if (m.queue.empty()) {
    m.busy = false;
    return;
  }
  m.busy = true;
  if (!csma_) {  // collision level: the frame goes out now, as soon as the last one ended
    begin_transmission(node, m.queue.front().frame, false, m.queue.front().mac_sequence);
    return;
  }
  m.backoffs_this_frame = 0;
  m.backoff_exponent = params_.min_be;
  back_off(node);
}

void ContendedMedium::back_off(NodeId node) {
  Mac& m = mac(node);
  const std::uint64_t periods = m.random.below(std::uint64_t{1} << m.backoff_exponent);
  ++m.counters.backoffs;
  ++totals_[static_cast<std::size_t>(m.queue.front().frame.type)].backoffs;
  radio_.simulator_.after(
      symbols(static_cast<std::uint32_t>(periods) * params_.unit_backoff_symbols),
      [this, node] { assess_channel(node); });
}

void ContendedMedium::assess_channel(NodeId node) {
  // The assessment takes cca_symbols and reports busy when a sensed frame is on the air at its
  // end (every frame outlasts the 8 symbols, so none starts and ends unseen inside it).
  radio_.simulator_.after(symbols(params_.cca_symbols), [this, node] {
    Mac& m = mac(node);
    if (channel_busy(node)) {
      ++m.backoffs_this_frame;
      m.backoff_exponent = std::min(m.backoff_exponent + 1, params_.max_be);
      if (m.backoffs_this_frame > params_.max_backoffs) {
        ++m.counters.access_failures;
        ++totals_[static_cast<std::size_t>(m.queue.front().frame.type)].access_failures;
        drop_head(node);
        return;
      }
      back_off(node);
      return;
    }
    // Deaf from now: the radio turns from receiving to sending.
    go_deaf(node, symbols(params_.turnaround_symbols));
    radio_.simulator_.after(symbols(params_.turnaround_symbols), [this, node] {
      const Outgoing& head = mac(node).queue.front();
      begin_transmission(node, head.frame, false, head.mac_sequence);
    });
  });
}

void ContendedMedium::go_deaf(NodeId node, sim::Duration for_at_least) {
  sim::Time& deaf_until = deaf_until_[sim::index(node)];
  deaf_until = std::max(deaf_until, radio_.simulator_.now() + for_at_least);
  // Half duplex: what it was receiving is lost (the others in progress were lost already).
  std::uint64_t& locked = locked_[sim::index(node)];
  if (locked != kNotLocked) reception(locked).locked_out = true;
  locked = kNotLocked;
}

bool ContendedMedium::channel_busy(NodeId node) const {
  const Vec2 here = radio_.position(node);
  for (const std::uint32_t index : on_air_) {
    const Transmission& tx = transmissions_[index];
    if (tx.frame.source == node) return true;
    const double distance = (tx.origin - here).norm();
    if (propagation_.model == PropagationModel::unit_disk) {
      if (distance <= carrier_sense_range_) return true;
    } else if (distance <= radio_.params_.max_range &&
               mw_to_dbm(received_power_mw(tx, node, distance * radio_.params_.meters_per_unit)) >=
                   params_.cca_threshold_dbm) {
      return true;
    }
  }
  return false;
}

double ContendedMedium::received_power_mw(const Transmission& tx, NodeId receiver,
                                          double distance_m) const {
  if (propagation_.model == PropagationModel::unit_disk) return 1.0;
  const double dbm = propagation_.tx_power_dbm - path_loss_db(propagation_, distance_m) -
                     shadowing_db(propagation_, radio_.seed_,
                                  radio_.nodes_[sim::index(tx.frame.source)].random_key,
                                  radio_.nodes_[sim::index(receiver)].random_key);
  return dbm_to_mw(dbm);
}

void ContendedMedium::begin_transmission(NodeId node, const Frame& frame, bool is_ack,
                                         std::uint32_t sequence) {
  const std::size_t node_index = sim::index(node);
  const bool battery = radio_.battery_limited();
  const double bits = 8.0 * frame.size_bytes;
  const double tx_j =
      tx_energy_j(radio_.params_.energy, bits, frame.range * radio_.params_.meters_per_unit,
                  radio_.crossover_m_);
  Mac& m = mac(node);
  if (radio_.guarded() && !radio_.afford(node, tx_j)) {
    if (!is_ack) drop_head(node);
    return;
  }
  radio_.senders_[node_index].energy_tx_j += tx_j;
  radio_.total_tx_j_.add(tx_j);
  radio_.tx_j_by_type_[static_cast<std::size_t>(frame.type)].add(tx_j);
  if (battery && radio_.params_.energy.idle_power_w > 0) radio_.schedule_depletion(node);

  const sim::Time now = radio_.simulator_.now();
  std::uint32_t slot;
  if (!free_transmissions_.empty()) {
    slot = free_transmissions_.back();
    free_transmissions_.pop_back();
  } else {
    slot = static_cast<std::uint32_t>(transmissions_.size());
    transmissions_.emplace_back();
  }
  Transmission& tx = transmissions_[slot];
  tx.frame = frame;
  tx.is_ack = is_ack;
  tx.mac_sequence = sequence;
  tx.attempt = m.attempts++;
  tx.origin = radio_.position(node);
  tx.start = now;
  tx.end = now + radio_.airtime(frame.size_bytes);
  tx.receptions.clear();
  // Deaf until the frame is out and the radio has turned back to receiving.
  go_deaf(node, (tx.end - now) + (csma_ ? symbols(params_.turnaround_symbols) : sim::Duration{}));
  if (is_ack) {
    ++m.counters.acks;
  } else {
    ++m.counters.transmissions;
    ++totals_[static_cast<std::size_t>(frame.type)].transmissions;
  }
  // Who hears it: within the frame's range on a unit disk; within max_range and above the
  // sensitivity with log-distance propagation.
  const bool unit_disk = propagation_.model == PropagationModel::unit_disk;
  // The index is asked a little wider, and the distance decides: a unicast's addressee stands
  // exactly at the frame's range, where the index's own rounding may go either way.
  const double reach = unit_disk ? frame.range : radio_.params_.max_range;
  radio_.nodes_within(tx.origin, reach * (1.0 + 1e-9), node, scratch_);
  const double rx_j = rx_energy_j(radio_.params_.energy, bits);
  const bool links = radio_.link_faults_.any();
  for (const NodeId hearer : scratch_) {
    const double distance = (radio_.position(hearer) - tx.origin).norm();
    if (distance > reach) continue;
    const double power = received_power_mw(tx, hearer, distance * radio_.params_.meters_per_unit);
    if (!unit_disk && mw_to_dbm(power) < propagation_.sensitivity_dbm) continue;
    if (links && radio_.link_faults_.cut(tx.origin, radio_.position(hearer))) continue;
    if (radio_.guarded() && !radio_.afford(hearer, rx_j)) continue;
    const std::uint32_t hot = radio_.hot_[sim::index(hearer)];
    radio_.heard_bytes_[hot] += frame.size_bytes;
    radio_.total_heard_bytes_ += frame.size_bytes;
    radio_.heard_bytes_by_type_[static_cast<std::size_t>(frame.type)] += frame.size_bytes;
    if (!frame.is_broadcast() && hearer != frame.destination) ++radio_.overheard_count_[hot];
    if (battery && radio_.params_.energy.idle_power_w > 0) radio_.schedule_depletion(hearer);
    Reception r{hearer, hot, power};
    const std::size_t h = sim::index(hearer);
    const std::uint64_t key = (std::uint64_t{slot} << 32) | tx.receptions.size();
    // A frame that ends now is over: one that starts now does not overlap it.
    std::uint64_t& locked = locked_[h];
    if (locked != kNotLocked && transmissions_[locked >> 32].end <= now) locked = kNotLocked;
    if (deaf_until_[h] > now) {
      r.locked_out = true;  // turning around or sending
    } else if (locked != kNotLocked) {
      // The receiver is synchronised on an earlier frame: this one is only interference there.
      Reception& other = reception(locked);
      other.overlapped = true;
      other.interference_mw += power;
      other.overlap_from = std::min(other.overlap_from, now);
      other.overlap_until =
          std::max(other.overlap_until, std::min(tx.end, transmissions_[locked >> 32].end));
      r.locked_out = true;
    } else {
      // It synchronises on this one, through whatever it could not synchronise on before.
      locked = key;
      for (const InProgress& other : receiving_[h]) {
        if (other.end <= now) continue;
        r.overlapped = true;
        r.interference_mw += other.power_mw;
        r.overlap_from = std::min(r.overlap_from, now);
        r.overlap_until = std::max(r.overlap_until, std::min(tx.end, other.end));
      }
    }
    r.in_progress_slot = static_cast<std::uint32_t>(receiving_[h].size());
    receiving_[h].push_back(InProgress{key, tx.end, power});
    tx.receptions.push_back(r);
  }
  if (!frame.is_broadcast() && !is_ack &&
      std::none_of(tx.receptions.begin(), tx.receptions.end(),
                   [&](const Reception& r) { return r.receiver == frame.destination; }))
    ++radio_.life_to_write(node_index).unreachable_count;
  on_air_.push_back(slot);
  sim::Fingerprint& traffic = radio_.senders_[node_index].traffic;
  traffic.mix(static_cast<std::uint64_t>(sim::to_ns(now)));
  traffic.mix((std::uint64_t{sim::index(node)} << 32) | sim::index(frame.destination));
  traffic.mix((std::uint64_t{is_ack ? 0xFFu : static_cast<std::uint8_t>(frame.type)} << 32) |
              frame.size_bytes);
  radio_.simulator_.at(tx.end, [this, slot] { end_transmission(slot); });
}

int ContendedMedium::outcome(const Transmission& tx, const Reception& r) const {
  if (r.locked_out) return 1;
  const double sinr = r.power_mw / (noise_mw_ + r.interference_mw);
  if (r.overlapped && !(std::isfinite(radio_.params_.capture_threshold_db) &&
                        propagation_.model == PropagationModel::log_distance &&
                        10.0 * std::log10(sinr) >= radio_.params_.capture_threshold_db))
    return 1;
  const std::uint64_t sender_key = radio_.nodes_[sim::index(tx.frame.source)].random_key;
  const std::uint64_t receiver_key = radio_.nodes_[sim::index(r.receiver)].random_key;
  double survive = 1.0 - radio_.params_.loss;
  if (radio_.link_faults_.any())
    survive *= 1.0 - radio_.link_faults_.loss(tx.origin, radio_.position(r.receiver));
  if (propagation_.model == PropagationModel::log_distance) {
    // The bits sent while others overlapped see the SINR, the rest the SNR.
    const double bits = 8.0 * tx.frame.size_bytes;
    const double overlapped_share =
        r.overlapped
            ? sim::to_seconds(r.overlap_until - r.overlap_from) / sim::to_seconds(tx.end - tx.start)
            : 0.0;
    survive *= oqpsk_frame_success(sinr, bits * overlapped_share) *
               oqpsk_frame_success(r.power_mw / noise_mw_, bits * (1.0 - overlapped_share));
  }
  if (survive >= 1.0) return 0;
  const double u =
      sim::keyed_uniform01(radio_.seed_, kReceptionPurpose, sender_key, receiver_key, tx.attempt);
  return u < survive ? 0 : 2;
}

void ContendedMedium::end_transmission(std::uint32_t index) {
  on_air_.erase(std::find(on_air_.begin(), on_air_.end(), index));
  // Take the frame's receptions off their receivers first: an ACK or a reply sent from a
  // handler below must not see this frame as still arriving.
  for (std::size_t k = 0; k < transmissions_[index].receptions.size(); ++k) {
    const Reception& done = transmissions_[index].receptions[k];
    const std::size_t receiver = sim::index(done.receiver);
    std::vector<InProgress>& list = receiving_[receiver];
    const std::uint64_t key = (std::uint64_t{index} << 32) | k;
    // Swap with the last and pop: the moved one learns its new place.
    const std::uint32_t at = done.in_progress_slot;
    list[at] = list.back();
    list.pop_back();
    if (at < list.size()) reception(list[at].reception).in_progress_slot = at;
    if (locked_[receiver] == key) locked_[receiver] = kNotLocked;
  }
  // Handlers may send, and so grow `transmissions_`: work on a moved-out copy.
  Transmission tx = std::move(transmissions_[index]);
  free_transmissions_.push_back(index);
  const NodeId source = tx.frame.source;
  const auto type_index = static_cast<std::size_t>(tx.frame.type);
  bool acknowledged_now = false;
  std::uint64_t received = 0, lost = 0;
  for (const Reception& r : tx.receptions) {
    const bool intended = tx.frame.is_broadcast() || r.receiver == tx.frame.destination;
    if (!intended) continue;
    const int fate = outcome(tx, r);
    if (tx.is_ack) {
      if (fate == 0) acknowledged_now = true;
      continue;
    }
    ContentionCounters& by_node = mac(source).counters;
    if (fate == 1) {
      ++by_node.collided;
      ++totals_[type_index].collided;
      ++total_collided_;
      ++lost;
    } else if (fate == 2) {
      ++by_node.channel_lost;
      ++totals_[type_index].channel_lost;
      ++radio_.life_to_write(sim::index(r.receiver)).lost_count;
      ++lost;
    } else {
      ++received;
      delivered(tx, r);
    }
  }
  radio_.senders_[sim::index(source)].traffic.mix((received << 32) ^ lost);
  if (tx.is_ack) {
    if (acknowledged_now) ack_received(tx.frame.destination, tx.mac_sequence);
    return;
  }
  Mac& m = mac(source);
  if (csma_ && !tx.frame.is_broadcast()) {
    m.awaiting_ack = true;
    m.ack_timer = radio_.simulator_.after(symbols(params_.ack_wait_symbols),
                                          [this, source] { ack_timed_out(source); });
    return;
  }
  finish_head(source);
}

void ContendedMedium::delivered(const Transmission& tx, const Reception& r) {
  const NodeId source = tx.frame.source;
  if (!tx.frame.is_broadcast() && csma_) {
    // Acknowledge after the turnaround, without carrier sense, duplicates too (their ACK
    // was lost).
    const NodeId receiver = r.receiver;
    const std::uint32_t sequence = tx.mac_sequence;
    const MessageType type = tx.frame.type;
    go_deaf(receiver, 2 * symbols(params_.turnaround_symbols) + radio_.airtime(params_.ack_bytes));
    // The ACK is the receiver's transmission: in the kernel's origin order, its own event.
    radio_.simulator_.after_as(
        sim::origin_of(receiver), symbols(params_.turnaround_symbols),
        [this, receiver, source, sequence, type] {
          const double range = (radio_.position(source) - radio_.position(receiver)).norm();
          const Frame ack{receiver,
                          source,
                          type,  // its energy counts as the acknowledged type's
                          params_.ack_bytes,
                          std::min(range, radio_.params_.max_range),
                          radio_.simulator_.now(),
                          0,
                          Payload{}};
          begin_transmission(receiver, ack, true, sequence);
        });
    const std::uint64_t link = (std::uint64_t{sim::index(r.receiver)} << 32) | sim::index(source);
    const auto [it, inserted] = last_delivered_.try_emplace(link, tx.mac_sequence);
    if (!inserted) {
      if (it->second == tx.mac_sequence) return;  // a retry of a frame already handed over
      it->second = tx.mac_sequence;
    }
  }
  const auto type_index = static_cast<std::size_t>(tx.frame.type);
  ContentionCounters& by_node = mac(source).counters;
  ++by_node.delivered;
  ++totals_[type_index].delivered;
  const std::size_t stride = radio_.heard_bytes_.size();
  if (radio_.rx_count_[type_index * stride + r.hot]++ == 0)
    radio_.rx_written_[type_index].add(r.hot);
  radio_.rx_bytes_[type_index * stride + r.hot] += tx.frame.size_bytes;
  ++radio_.totals_[type_index].rx_count;
  radio_.totals_[type_index].rx_bytes += tx.frame.size_bytes;
  const sim::Time at = tx.end + radio_.latency_;
  const double latency_s = sim::to_seconds(at - tx.frame.sent_at);
  by_node.latency_sum_s += latency_s;
  totals_[type_index].latency_sum_s += latency_s;
  record_latency(tx.frame.type, latency_s);
  const std::uint32_t type_bit = 1u << static_cast<unsigned>(tx.frame.type);
  if (!(radio_.interest_[r.hot] & type_bit)) return;
  if (radio_.latency_.count() == 0) {
    radio_.hand_over(tx.frame, r.receiver);
    return;
  }
  // The frame waits in `late_` until its receivers have it (one copy per receiver: simple, and
  // only when a latency is set).
  std::uint32_t slot;
  if (!free_late_.empty()) {
    slot = free_late_.back();
    free_late_.pop_back();
    late_[slot] = tx.frame;
  } else {
    slot = static_cast<std::uint32_t>(late_.size());
    late_.push_back(tx.frame);
  }
  radio_.simulator_.at(at, [this, slot, receiver = r.receiver] {
    radio_.hand_over(late_[slot], receiver);
    free_late_.push_back(slot);
  });
}

void ContendedMedium::ack_received(NodeId node, std::uint32_t sequence) {
  Mac& m = mac(node);
  if (!m.awaiting_ack || m.queue.empty() || m.queue.front().mac_sequence != sequence) return;
  m.awaiting_ack = false;
  radio_.simulator_.cancel(m.ack_timer);
  finish_head(node);
}

void ContendedMedium::ack_timed_out(NodeId node) {
  Mac& m = mac(node);
  m.awaiting_ack = false;
  Outgoing& head = m.queue.front();
  if (head.retries >= params_.max_frame_retries) {
    drop_head(node);
    return;
  }
  ++head.retries;
  ++m.counters.retries;
  ++totals_[static_cast<std::size_t>(head.frame.type)].retries;
  m.backoffs_this_frame = 0;
  m.backoff_exponent = params_.min_be;
  back_off(node);
}

void ContendedMedium::finish_head(NodeId node) {
  Mac& m = mac(node);
  const std::uint32_t bytes = m.queue.front().frame.size_bytes;
  m.queue.pop_front();
  if (!csma_) {
    start_next(node);
    return;
  }
  // The interframe space lets the receiver process the frame before the next one.
  const std::uint32_t ifs =
      bytes <= params_.max_sifs_frame_bytes ? params_.sifs_symbols : params_.lifs_symbols;
  radio_.simulator_.after(symbols(ifs), [this, node] { start_next(node); });
}

void ContendedMedium::drop_head(NodeId node) {
  Mac& m = mac(node);
  ++m.counters.dropped;
  ++totals_[static_cast<std::size_t>(m.queue.front().frame.type)].dropped;
  m.queue.pop_front();
  start_next(node);
}

void ContendedMedium::record_latency(MessageType type, double latency_s) {
  std::vector<std::uint64_t>& bins = latency_bins_[static_cast<std::size_t>(type)];
  if (bins.empty()) bins.assign(kLatencyBinsPerDecade * kLatencyDecades + 1, 0);
  const double position = std::log10(std::max(latency_s, kLatencyFloor_s) / kLatencyFloor_s);
  const auto bin = static_cast<std::size_t>(
      std::min(position * kLatencyBinsPerDecade, static_cast<double>(bins.size() - 1)));
  ++bins[bin];
}

double ContendedMedium::latency_quantile_s(MessageType type, double q) const {
  const std::vector<std::uint64_t>& bins = latency_bins_[static_cast<std::size_t>(type)];
  std::uint64_t total = 0;
  for (const std::uint64_t count : bins)
    total += count;
  if (total == 0) return 0.0;
  const auto wanted = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  std::uint64_t seen = 0;
  for (std::size_t bin = 0; bin < bins.size(); ++bin) {
    seen += bins[bin];
    if (seen >= std::max<std::uint64_t>(wanted, 1))
      return kLatencyFloor_s * std::pow(10.0, static_cast<double>(bin + 1) / kLatencyBinsPerDecade);
  }
  return kLatencyFloor_s * std::pow(10.0, kLatencyDecades);
}

}  // namespace masnet::net
