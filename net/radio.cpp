#include "net/radio.hpp"

#include <algorithm>
#include <cmath>

#include "net/contended_medium.hpp"
#include "sim/free_slots.hpp"
#include "sim/random.hpp"

namespace masnet::net {
namespace {
constexpr std::uint64_t kLossPurpose = sim::purpose("radio.loss");
constexpr std::uint64_t kJitterPurpose = sim::purpose("radio.jitter");
}  // namespace

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

[[gnu::always_inline]] inline std::uint64_t Radio::book_overhearing(
    const OverhearingJob& job) const {
  std::uint64_t* const heard_diff = heard_diff_.data();
  const std::uint64_t booking = job.booking;
  const Vec2 center{job.cx, job.cy};
  // Overhearing is one packed word per run end, each prefetched with the line's estimate. The
  // lambdas capture no references, so nothing is reloaded after each write.
  std::uint64_t hearers = line_index_.for_each_run_within(
      center, job.range,
      [heard_diff, booking](std::uint32_t a, std::uint32_t c) {
        heard_diff[a] += booking;
        heard_diff[c] -= booking;
      },
      [heard_diff](std::uint32_t a, std::uint32_t c) {
        __builtin_prefetch(heard_diff + a, 1);
        __builtin_prefetch(heard_diff + c, 1);
      });
  // The runs included the sender (at the center: in every run of a valid range) and maybe a
  // static addressee: take them out again, as runs of one slot in the words just written.
  const auto static_count = static_cast<std::uint32_t>(static_ids_.size());
  for (const std::uint32_t hot : {job.source_hot, job.destination_hot}) {
    if (hot >= static_count ||
        !(hot == job.source_hot ? job.range >= 0.0 : line_index_.within(hot, center, job.range)))
      continue;
    heard_diff[hot] -= booking;
    heard_diff[hot + 1] += booking;
    --hearers;
  }
  return hearers;
}

void Radio::wait_until_worker_behind_at_most(std::uint32_t behind) const {
  const std::uint32_t published =
      jobs_published_.load(std::memory_order_relaxed);  // only this thread writes it
  std::uint32_t booked = jobs_booked_.load(std::memory_order_acquire);
  for (std::uint32_t spin = 0; published - booked > behind && spin < spin_limit_; ++spin) {
    pause_briefly();
    booked = jobs_booked_.load(std::memory_order_acquire);
  }
  while (published - booked > behind) {
    jobs_booked_.wait(booked, std::memory_order_acquire);
    booked = jobs_booked_.load(std::memory_order_acquire);
  }
}

void Radio::hand_over_jobs() const {
  if (jobs_filling_.empty()) return;
  // The thread normally keeps up: it books a hand-over in a fraction of the time this thread
  // takes to gather one.
  wait_until_worker_behind_at_most(kHandOverSlots - 1);
  const std::uint32_t published = jobs_published_.load(std::memory_order_relaxed);
  jobs_handed_[published % kHandOverSlots].swap(jobs_filling_);
  jobs_filling_.clear();
  jobs_published_.store(published + 1, std::memory_order_release);
  jobs_published_.notify_one();  // a load of the waiter count when the thread is not asleep
}

void Radio::overhearing_worker() {
  std::uint32_t booked = 0;
  for (;;) {
    // Spin a while (hand-overs come every few hundred microseconds while replies flow), then
    // sleep until the next one.
    std::uint32_t published = jobs_published_.load(std::memory_order_acquire);
    for (std::uint32_t spin = 0; published == booked && spin < spin_limit_; ++spin) {
      pause_briefly();
      published = jobs_published_.load(std::memory_order_acquire);
    }
    if (published == booked) {
      jobs_published_.wait(booked, std::memory_order_acquire);
      continue;
    }
    if (stop_worker_.load(std::memory_order_acquire)) return;
    for (; booked != published; ++booked) {
      for (const OverhearingJob& job : jobs_handed_[booked % kHandOverSlots]) {
        const std::uint64_t heard = book_overhearing(job) * (job.booking & (kOneOverheard - 1));
        worker_heard_bytes_ += heard;
        worker_heard_by_type_[job.type] += heard;
      }
      jobs_booked_.store(booked + 1, std::memory_order_release);
      jobs_booked_.notify_one();
    }
  }
}

void Radio::drain_overhearing() const {
  if (!overhearing_thread_.joinable()) return;
  hand_over_jobs();
  wait_until_worker_behind_at_most(0);
  total_heard_bytes_ += worker_heard_bytes_;
  worker_heard_bytes_ = 0;
  for (std::size_t t = 0; t < kMaxMessageTypes; ++t) {
    heard_bytes_by_type_[t] += worker_heard_by_type_[t];
    worker_heard_by_type_[t] = 0;
  }
}

const std::vector<Vec2>& Radio::mobile_positions_now() {
  const sim::Time now = simulator_.now();
  if (!mobile_cache_valid_ || mobile_cache_time_ != now ||
      mobile_cache_.size() != mobile_ids_.size()) {
    mobile_cache_.resize(mobile_ids_.size());
    for (std::size_t m = 0; m < mobile_ids_.size(); ++m)
      mobile_cache_[m] = mobile_->position(mobile_ids_[m]);
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
  const Node& node = nodes_[sim::index(id)];
  const sim::Time until = std::min(simulator_.now(), node.died_at);
  double idle_s = sim::to_seconds(until - node.added_at);
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
  Node& node = nodes_[sim::index(id)];
  if (!node.alive) return false;
  if (params_.energy.battery_j - consumed_j(id) < energy_j) {
    kill(id);
    return false;
  }
  return true;
}

void Radio::schedule_depletion(NodeId id) {
  Node& node = nodes_[sim::index(id)];
  const std::uint32_t hot = hot_[sim::index(id)];
  const double remaining =
      params_.energy.battery_j - senders_[sim::index(id)].energy_tx_j - idle_j(id) -
      (hot == kNoHotIndex
           ? 0.0
           : rx_energy_j(params_.energy, 8.0 * static_cast<double>(heard_bytes_[hot])));
  simulator_.cancel(node.depletion_event);
  // The idle drain empties the battery at a known time: a scheduled event, not a poll.
  const sim::Duration left = sim::seconds(std::max(remaining, 0.0) / params_.energy.idle_power_w);
  node.depletion_event = simulator_.after(left, [this, id] { kill(id); });
}

void Radio::mix_refusal(NodeId source) {
  traffic_.mix(static_cast<std::uint64_t>(sim::to_ns(simulator_.now())));
  traffic_.mix(kRefusedMark | sim::index(source));
}

void Radio::kill(NodeId id) {  // the battery is empty
  Node& node = nodes_[sim::index(id)];
  if (!node.alive) return;
  node.alive = false;
  node.died_at = simulator_.now();
  simulator_.cancel(node.depletion_event);
  if (listener_) listener_->on_battery_empty(id);
}

bool Radio::transmit(NodeId source, NodeId destination, double range, Payload&& payload,
                     double destination_distance) {
  if (index_dirty_) prepare_index();
  if (contended_)
    return contended_->send(source, destination, std::min(range, params_.max_range),
                            std::move(payload));
  const std::size_t source_index = sim::index(source);
  const bool battery = battery_limited();
  // Only a battery kills a node: without one every node is alive, and its cold record is not
  // fetched for a frame.
  if (battery && !nodes_[source_index].alive) {
    ++nodes_[source_index].refused_count;
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
  if (battery && !afford(source, tx_j)) {
    ++nodes_[source_index].refused_count;
    mix_refusal(source);
    return false;
  }
  src.energy_tx_j += tx_j;
  total_tx_j_ += tx_j;
  tx_j_by_type_[static_cast<std::size_t>(type)] += tx_j;
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

  const sim::Time now = simulator_.now();
  const sim::Duration air = airtime(bytes);
  sim::Time start = now;
  if (params_.level == RadioLevel::airtime) {  // this transmitter's frames queue up
    start = std::max(now, src.busy_until);
    src.busy_until = start + air;
  }
  const sim::Time arrival = start + air + latency_;

  // Who hears the frame, decided by positions now. Every node in range pays E_rx for it,
  // addressed or not; without a battery nobody can die of it, so overhearing is two
  // counter increments on contiguous memory.
  const double rx_j = rx_energy_j(params_.energy, bits);
  const std::uint32_t type_bit = 1u << static_cast<unsigned>(type);
  std::vector<NodeId>& receivers = scratch_receivers_;
  receivers.clear();
  std::uint64_t hearers = 0;
  std::uint64_t* const heard = heard_bytes_.data();
  std::uint64_t* const overheard = overheard_count_.data();
  std::uint64_t* const rx_count = rx_count_.data() + type_index * heard_bytes_.size();
  std::uint64_t* const rx_bytes = rx_bytes_.data() + type_index * heard_bytes_.size();
  std::uint64_t received = 0, lost = 0;
  const bool drains = battery && params_.energy.idle_power_w > 0;
  const std::uint32_t* const interest = interest_.data();
  auto receive = [&](NodeId id, std::uint32_t hot) {
    if (battery && !afford(id, rx_j)) return;
    heard[hot] += bytes;
    ++hearers;
    if (drains) schedule_depletion(id);  // the idle drain now ends sooner
    if (params_.loss > 0) {
      Node& node = nodes_[sim::index(id)];
      if (sim::keyed_uniform01(seed_, kLossPurpose, nodes_[source_index].random_key,
                               node.random_key, frame_number) < params_.loss) {
        ++node.lost_count;
        ++lost;
        return;
      }
    }
    ++rx_count[hot];
    rx_bytes[hot] += bytes;
    ++received;
    if (interest[hot] & type_bit) receivers.push_back(id);
  };
  auto overhear = [&](NodeId id, std::uint32_t hot) {
    if (battery && !afford(id, rx_j)) return;
    heard[hot] += bytes;
    ++overheard[hot];
    ++hearers;
    if (drains) schedule_depletion(id);
  };

  const Vec2 center = position(source);
  // Hot indices compared instead of ids: the inner loops load nothing but coordinates.
  const std::uint32_t source_hot = hot_[source_index];
  const std::uint32_t destination_hot =
      destination == sim::kNoNode ? kNoHotIndex : hot_[sim::index(destination)];
  const std::uint32_t static_count = static_cast<std::uint32_t>(static_ids_.size());
  const bool is_broadcast = destination == sim::kNoNode;
  // Booked in bulk whenever no reception can fail (no battery, no loss): energy and counters
  // go in as runs; the nodes that want the frame (interest) are collected as receivers.
  const bool bulk = use_lines_ && !battery && (!is_broadcast || params_.loss <= 0);
  const bool collect = is_broadcast && (static_interest_ & type_bit) != 0;
  const bool everyone_wants = (static_interest_common_ & type_bit) != 0;  // no per-node check
  if (use_lines_) {
    const NodeId* const slots = line_index_.ids().data();
    std::uint64_t* const count_diff =
        rx_count_diff_.data() + type_index * (static_cast<std::size_t>(heard_bytes_.size()) + 1);
    std::uint64_t* const bytes_diff =
        rx_bytes_diff_.data() + type_index * (static_cast<std::size_t>(heard_bytes_.size()) + 1);
    if (bulk) {
      if (pending_bulk_bytes_ + bytes >= kOneOverheard ||
          pending_bulk_frames_ + 1 >= (std::uint64_t{1} << (64 - kHeardBytesBits)))
        materialize();  // the packed sums would overflow
      ++pending_bulk_frames_;
      pending_bulk_bytes_ += bytes;
    }
    const std::uint64_t heard_booking = bytes + (is_broadcast ? 0 : kOneOverheard);
    // A bulk broadcast prefetches the difference-array entries it will update (its receptions
    // by type); a unicast's job does its own.
    auto prefetch_both = [count_diff, bytes_diff](std::uint32_t a, std::uint32_t c) {
      for (std::uint64_t* diff : {count_diff, bytes_diff}) {
        __builtin_prefetch(diff + a, 1);
        __builtin_prefetch(diff + c, 1);
      }
    };
    if (bulk && !is_broadcast) {
      // Unicasts, the bulk of the traffic: one job each (see OverhearingJob).
      const OverhearingJob job{center.x(),
                               center.y(),
                               range,
                               heard_booking,
                               source_hot,
                               destination_hot,
                               static_cast<std::uint32_t>(type_index)};
      if (params_.overhearing_thread && static_count >= params_.overhearing_thread_min_nodes) {
        if (!overhearing_thread_.joinable()) start_overhearing_thread();
        jobs_filling_.push_back(job);
        if (jobs_filling_.size() >= kJobsPerHandOver) hand_over_jobs();
      } else {
        hearers += book_overhearing(job);
      }
    } else if (bulk) {
      // A broadcast's bytes heard are its bytes received (folded into both by materialize).
      line_index_.for_each_run_within(
          center, range,
          [&](std::uint32_t a, std::uint32_t c) {
            hearers += c - a;
            ++count_diff[a];
            --count_diff[c];
            bytes_diff[a] += bytes;
            bytes_diff[c] -= bytes;
            received += c - a;
            if (collect)
              for (std::uint32_t k = a; k < c; ++k)
                if (k != source_hot && (everyone_wants || (interest[k] & type_bit)))
                  receivers.push_back(slots[k]);
          },
          prefetch_both);
    } else {
      line_index_.for_each_run_within(center, range, [&](std::uint32_t a, std::uint32_t c) {
        for (std::uint32_t k = a; k < c; ++k) {
          if (k == source_hot || k == destination_hot) continue;
          if (is_broadcast)
            receive(slots[k], k);
          else
            overhear(slots[k], k);
        }
      });
    }
    if (bulk) {
      diffs_pending_ = true;
      // A broadcast's runs included its sender (a unicast's job books its own out): take it out
      // again, as a run of one slot in the difference words the runs just wrote. A static
      // sender sits at the center (distance exactly 0): in every run of a valid range.
      if (is_broadcast && source_hot < static_count && range >= 0.0) {
        --hearers;
        --count_diff[source_hot];
        ++count_diff[source_hot + 1];
        bytes_diff[source_hot] -= bytes;
        bytes_diff[source_hot + 1] += bytes;
        --received;
      }
    }
  } else {
    const NodeId* const slots = static_grid_.ids().data();
    static_grid_.for_each_slot_within(center, range, [&](std::uint32_t k, double) {
      if (k == source_hot || k == destination_hot) return;
      if (is_broadcast)
        receive(slots[k], k);
      else
        overhear(slots[k], k);
    });
  }
  if (is_broadcast) {
    for_each_mobile_within(
        center, range, [&](NodeId id) { receive(id, hot_[sim::index(id)]); }, source, sim::kNoNode);
  } else {
    for_each_mobile_within(
        center, range, [&](NodeId id) { overhear(id, hot_[sim::index(id)]); }, source, destination,
        destination_distance);
    // The addressee is decided by its distance, not by the grid's rounding at the boundary.
    // The same arithmetic as unicast()'s distance, so the known value decides identically.
    const double distance = destination_distance >= 0.0 ? destination_distance
                                                        : (position(destination) - center).norm();
    if (distance <= range)
      receive(destination, destination_hot);
    else
      ++nodes_[source_index].unreachable_count;
  }
  ++sent.count;
  sent.bytes += bytes;
  totals_[type_index].rx_count += received;
  totals_[type_index].rx_bytes += received * bytes;
  total_heard_bytes_ += hearers * bytes;
  heard_bytes_by_type_[type_index] += hearers * bytes;
  // What this frame did, in send order. Its overhearers are not here: the second thread may be
  // counting them still; they enter the traffic fingerprint as per-node sums at the end.
  traffic_.mix(static_cast<std::uint64_t>(sim::to_ns(now)));
  traffic_.mix((std::uint64_t{sim::index(source)} << 32) | sim::index(destination));
  traffic_.mix((std::uint64_t{static_cast<std::uint8_t>(type)} << 32) | bytes);
  traffic_.mix((received << 32) ^ lost);
  if (receivers.empty()) return true;
  // Delivery order is by node id, whatever the grid's layout.
  // (On a sensor grid the runs already come in id order: check before sorting.)
  if (receivers.size() > 1 && !std::is_sorted(receivers.begin(), receivers.end()))
    std::sort(receivers.begin(), receivers.end());

  if (params_.jitter_s <= 0) {
    // One event delivers to every receiver in id order: the same order separate events with
    // consecutive sequence numbers would give, at a fraction of the cost.
    Batch& batch = batch_for(arrival);
    const bool one = receivers.size() == 1;
    const auto first = static_cast<std::uint32_t>(batch.receivers.size());
    batch.deliveries.push_back(Delivery{
        Frame{source, destination, type, bytes, range, now, frame_number, std::move(payload)},
        one ? receivers[0] : sim::kNoNode, first,
        one ? 0u : static_cast<std::uint32_t>(receivers.size())});
    if (!one) batch.receivers.insert(batch.receivers.end(), receivers.begin(), receivers.end());
    return true;
  }
  const std::uint32_t index = sim::reuse_or_append(free_jittered_, jittered_);
  Jittered& j = jittered_[index];
  j.frame = Frame{source, destination, type, bytes, range, now, frame_number, std::move(payload)};
  j.pending = static_cast<std::uint32_t>(receivers.size());
  for (NodeId id : receivers) {
    const double u = sim::keyed_uniform01(seed_, kJitterPurpose, nodes_[source_index].random_key,
                                          nodes_[sim::index(id)].random_key, frame_number);
    simulator_.at(arrival + sim::seconds(u * params_.jitter_s),
                  [this, index, id] { deliver_jittered(index, id); });
  }
  return true;
}

void Radio::hand_over(const Frame& frame, NodeId receiver) {
  // Died while the frame was in the air (only batteries kill; skip the lookup otherwise).
  if (battery_limited() && !nodes_[sim::index(receiver)].alive) {
    traffic_.mix((std::uint64_t{sim::index(frame.source)} << 32) | sim::index(receiver));
    traffic_.mix(kUndeliveredMark ^ frame.number);
    return;
  }
  sim::Fingerprint& fp = simulator_.fingerprint();
  fp.mix((std::uint64_t{sim::index(frame.source)} << 32) | sim::index(receiver));
  fp.mix((std::uint64_t{static_cast<std::uint8_t>(frame.type)} << 32) | frame.size_bytes);
  if (listener_) listener_->on_frame(receiver, frame);
}

Radio::Batch& Radio::batch_for(sim::Time arrival) {
  if (open_batch_ != 0xFFFFFFFFu && open_batch_time_ == arrival &&
      simulator_.last_sequence() == open_batch_sequence_)
    return batches_[open_batch_];
  const std::uint32_t batch = sim::reuse_or_append(free_batches_, batches_);
  const sim::EventId event = simulator_.at(arrival, [this, batch] { run_batch(batch); });
  open_batch_ = batch;
  open_batch_time_ = arrival;
  open_batch_sequence_ = event.sequence;
  return batches_[batch];
}

void Radio::run_batch(std::uint32_t batch) {
  if (open_batch_ == batch) open_batch_ = 0xFFFFFFFFu;  // closed: nothing joins it any more
  // Handlers may open new batches and so move `batches_`' elements, never this batch's buffers:
  // the pointers below stay valid.
  const Delivery* const deliveries = batches_[batch].deliveries.data();
  const NodeId* const receivers = batches_[batch].receivers.data();
  const std::size_t count = batches_[batch].deliveries.size();
  for (std::size_t i = 0; i < count; ++i) {
    // The frames were written a while ago (a reply burst's round trip of other traffic): fetch
    // the next ones while this one is handled.
    if (i + kDeliveryLookahead < count) prefetch_delivery(deliveries[i + kDeliveryLookahead]);
    const Delivery& d = deliveries[i];
    if (d.only != sim::kNoNode) {
      hand_over(d.frame, d.only);
      continue;
    }
    // A broadcast's receivers answer at once and their records are far apart on large
    // networks (each sensor row is a jump): fetch a few receivers ahead.
    const NodeId* const ids = receivers + d.first;
    for (std::uint32_t k = 0; k < d.count; ++k) {
      if (k % 16 == 0 && k + 32 < d.count)
        __builtin_prefetch(ids + k + 32);  // the ids, two lines ahead
      if (k + kDeliveryLookahead < d.count) {
        // What a receiver that answers reads first: its position, hot index and sender state.
        const std::size_t ahead = sim::index(ids[k + kDeliveryLookahead]);
        __builtin_prefetch(&positions_[ahead]);
        __builtin_prefetch(&hot_[ahead]);
        __builtin_prefetch(&senders_[ahead], 1);
      }
      hand_over(d.frame, ids[k]);
    }
  }
  Batch& done = batches_[batch];
  done.deliveries.clear();
  done.receivers.clear();
  // A burst of a whole network (initial reports) should not stay allocated.
  if (done.deliveries.capacity() > kKeptBatchCapacity)
    std::vector<Delivery>().swap(done.deliveries);
  if (done.receivers.capacity() > kKeptBatchCapacity) std::vector<NodeId>().swap(done.receivers);
  free_batches_.push_back(batch);
}

void Radio::prefetch_delivery(const Delivery& delivery) {
  const char* const record = reinterpret_cast<const char*>(&delivery);
  for (std::size_t offset = 0; offset < sizeof(Delivery); offset += 64)
    __builtin_prefetch(record + offset);
  __builtin_prefetch(record + sizeof(Delivery) - 1);
}

void Radio::deliver_jittered(std::uint32_t index, NodeId id) {
  Jittered& j = jittered_[index];
  hand_over(j.frame, id);
  if (--j.pending == 0) free_jittered_.push_back(index);
}

}  // namespace masnet::net
