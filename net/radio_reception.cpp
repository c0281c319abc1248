// Reception on the uncontended levels (ideal, airtime): who hears a frame — unit disk at send
// time, static nodes through the line index or the grid, mobile ones through theirs — and the
// ledger's booking of every hearer, in bulk when no reception can fail, the bulk unicasts'
// overhearing inline or on the second thread. See docs/radio-and-energy.md, "Who hears a frame",
// and docs/decisions/0008-overhearing-thread.md.
#include <algorithm>
#include <cmath>

#include "net/radio.hpp"
#include "sim/random.hpp"

namespace masnet::net {
namespace {
constexpr std::uint64_t kLossPurpose = sim::purpose("radio.loss");
}  // namespace

template <bool kTiled>
[[gnu::always_inline]] inline std::uint64_t Radio::book_overhearing(
    const OverhearingJob& job) const {
  std::uint64_t* const heard_diff = heard_diff_.data();
  const std::uint64_t booking = job.booking;
  const Vec2 center{job.cx, job.cy};
  // Overhearing is one packed word per run end, each prefetched with the line's estimate. The
  // lambdas capture no references, so nothing is reloaded after each write.
  std::uint64_t hearers = 0;
  if constexpr (kTiled) {
    // A tile books its own slots only: each run cut to them.
    const std::uint32_t first = owned_first_, end = owned_end_;
    auto cut = [first, end](std::uint32_t& a, std::uint32_t& c) {
      a = std::max(a, first);
      c = std::min(c, end);
      return a < c;
    };
    line_index_.for_each_run_within(
        center, job.range,
        [&](std::uint32_t a, std::uint32_t c) {
          if (!cut(a, c)) return;
          heard_diff[a] += booking;
          heard_diff[c] -= booking;
          hearers += c - a;
        },
        [heard_diff, cut](std::uint32_t a, std::uint32_t c) {
          if (!cut(a, c)) return;
          __builtin_prefetch(heard_diff + a, 1);
          __builtin_prefetch(heard_diff + c, 1);
        });
  } else {
    hearers = line_index_.for_each_run_within(
        center, job.range,
        [heard_diff, booking](std::uint32_t a, std::uint32_t c) {
          heard_diff[a] += booking;
          heard_diff[c] -= booking;
        },
        [heard_diff](std::uint32_t a, std::uint32_t c) {
          __builtin_prefetch(heard_diff + a, 1);
          __builtin_prefetch(heard_diff + c, 1);
        });
  }
  // The runs included the sender (at the center: in every run of a valid range) and maybe a
  // static addressee: take them out again, as runs of one slot in the words just written.
  const auto static_count = static_cast<std::uint32_t>(static_ids_.size());
  for (const std::uint32_t hot : {job.source_hot, job.destination_hot}) {
    if (hot >= static_count || (kTiled && !owned_slot(hot)) ||
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
        const std::uint64_t heard =
            book_overhearing<false>(job) * (job.booking & (kOneOverheard - 1));
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

bool Radio::reaches_band(const Vec2& center, double range) const {
  const double slack = 1e-9 * (std::fabs(center.y()) + range + 1.0);  // rounding of y ± range
  return center.y() + range + slack >= band_y_min_ && center.y() - range - slack <= band_y_max_;
}

bool Radio::link_cut(const LinkFaults& faults, const Vec2& from, NodeId to) const {
  return faults.cut(from, position(to));
}

double Radio::link_loss(const LinkFaults& faults, const Vec2& from, NodeId to) const {
  return 1.0 - (1.0 - params_.loss) * (1.0 - faults.loss(from, position(to)));
}

template <bool kLinkFaults, bool kTiled>
Radio::Heard Radio::hear(const Outgoing& out, const FrameRecord* remote) {
  const NodeId source = out.source, destination = out.destination;
  const std::size_t source_index = out.source_index, type_index = out.type_index;
  const std::uint32_t bytes = out.bytes;
  const double range = out.range, destination_distance = out.destination_distance;
  const std::uint64_t frame_number = out.frame_number;
  const bool battery = battery_limited();
  const bool guarded_nodes = guarded();
  constexpr bool tiled = kTiled;  // runs in one piece never test for tiles
  // Partitions and degraded areas in force: each reception is asked about (rare: faults only).
  constexpr bool links = kLinkFaults;
  const auto type = static_cast<MessageType>(type_index);
  const double bits = 8.0 * bytes;
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
  sim::WrittenSpan& rx_written = rx_written_[type_index];
  std::uint64_t received = 0, lost = 0;
  const bool drains = battery && params_.energy.idle_power_w > 0;
  const std::uint32_t* const interest = interest_.data();
  // Another tile's frame was sent from where its sender stood then.
  const Vec2 center = tiled && remote != nullptr ? remote->source_position : position(source);
  // Another tile's frame is judged under the link faults in force when it was sent.
  const LinkFaults& faults =
      links && tiled && remote != nullptr ? link_history_.at(remote->link_epoch) : link_faults_;
  // Inlined: it runs for every receiver of a broadcast; the fault checks stay out of line.
  // `given_loss` >= 0: a mobile hearer of another tile's frame, judged there when it was sent.
  auto receive = [&](NodeId id, std::uint32_t hot, double given_loss = -1.0)
      __attribute__((always_inline)) {
    if (links && given_loss < 0.0 && link_cut(faults, center, id)) return;
    if (guarded_nodes && !afford(id, rx_j)) return;
    heard[hot] += bytes;
    ++hearers;
    if (drains) schedule_depletion(id);  // the idle drain now ends sooner
    const double loss = !links              ? params_.loss
                        : given_loss >= 0.0 ? given_loss
                                            : link_loss(faults, center, id);
    if (loss > 0) {
      if (sim::keyed_uniform01(seed_, kLossPurpose, nodes_[source_index].random_key,
                               nodes_[sim::index(id)].random_key, frame_number) < loss) {
        ++life_to_write(sim::index(id)).lost_count;
        ++lost;
        return;
      }
    }
    if (rx_count[hot]++ == 0) rx_written.add(hot);
    rx_bytes[hot] += bytes;
    ++received;
    if (interest[hot] & type_bit) receivers.push_back(id);
  };
  auto overhear = [&](NodeId id, std::uint32_t hot, bool judged = false) {
    if (links && !judged && link_cut(faults, center, id)) return;
    if (guarded_nodes && !afford(id, rx_j)) return;
    heard[hot] += bytes;
    ++overheard[hot];
    ++hearers;
    if (drains) schedule_depletion(id);
  };

  // Hot indices compared instead of ids: the inner loops load nothing but coordinates.
  const std::uint32_t source_hot = hot_[source_index];
  const std::uint32_t destination_hot =
      destination == sim::kNoNode ? kNoHotIndex : hot_[sim::index(destination)];
  const std::uint32_t static_count = static_cast<std::uint32_t>(static_ids_.size());
  const bool is_broadcast = destination == sim::kNoNode;
  // Booked in bulk whenever no reception can fail (no battery, no loss): energy and counters
  // go in as runs; the nodes that want the frame (interest) are collected as receivers.
  const bool bulk = use_lines_ && !guarded_nodes && !links && (!is_broadcast || params_.loss <= 0);
  const bool collect = is_broadcast && (static_interest_ & type_bit) != 0;
  const bool everyone_wants = (static_interest_common_ & type_bit) != 0;  // no per-node check
  if (tiled && !reaches_band(center, range)) {
    // No static node of this tile within reach (another tile's frame, a robot's far away).
  } else if (use_lines_) {
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
    // by type) and, when it gathers receivers, the ids of each run (on large networks each run
    // is a cache miss); a unicast's job does its own.
    auto prefetch_both = [count_diff, bytes_diff, slots, collect](std::uint32_t a,
                                                                  std::uint32_t c) {
      for (std::uint64_t* diff : {count_diff, bytes_diff}) {
        __builtin_prefetch(diff + a, 1);
        __builtin_prefetch(diff + c, 1);
      }
      if (collect) __builtin_prefetch(slots + a);
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
        hearers += book_overhearing<kTiled>(job);
      }
    } else if (bulk) {
      // A broadcast's bytes heard are its bytes received (folded into both by materialize).
      bulk_types_ |= 1u << type_index;
      line_index_.for_each_run_within(
          center, range,
          [&](std::uint32_t a, std::uint32_t c) {
            if constexpr (tiled) {  // a tile books its own slots only
              a = std::max(a, owned_first_);
              c = std::min(c, owned_end_);
              if (a >= c) return;
            }
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
        if constexpr (tiled) {
          a = std::max(a, owned_first_);
          c = std::min(c, owned_end_);
        }
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
      if (is_broadcast && source_hot < static_count && (!tiled || owned_slot(source_hot)) &&
          range >= 0.0) {
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
      if (k == source_hot || k == destination_hot || (tiled && !owned_slot(k))) return;
      if (is_broadcast)
        receive(slots[k], k);
      else
        overhear(slots[k], k);
    });
  }
  std::uint64_t static_hearers = hearers, static_received = received;
  // A static addressee is booked after the mobile hearers, but is the tile's own share.
  auto receive_destination = [&](double given_loss = -1.0) {
    const std::uint64_t hearers_before = hearers, received_before = received;
    receive(destination, destination_hot, given_loss);
    if (tiled && destination_hot < static_count) {
      static_hearers += hearers - hearers_before;
      static_received += received - received_before;
    }
  };
  if (tiled && remote != nullptr) {
    // Another tile's frame: the mobile nodes that heard it then, and its addressee if this tile
    // holds it (the sender's tile counted an unreachable one).
    for (std::size_t k = 0; k < remote->mobile_hearers.size() && mobiles_here_; ++k) {
      const NodeId id = remote->mobile_hearers[k];
      if (is_broadcast)
        receive(id, hot_[sim::index(id)], links ? remote->mobile_losses[k] : -1.0);
      else
        overhear(id, hot_[sim::index(id)], links);
    }
    if (!is_broadcast && remote->destination_reached && owns(destination)) {
      if (!links || destination_hot < static_count)
        receive_destination();
      else if (remote->destination_loss >= 0.0)  // not cut off then
        receive_destination(remote->destination_loss);
    }
    return Heard{hearers,        received,        lost,
                 static_hearers, static_received, remote->destination_reached};
  }
  // A tile's static sender names the mobile hearers in its frame's record (for the tiles that
  // run them: not needed in the record of a mobile sender's frame, shipped by the tile that runs
  // every mobile node). With link faults, also the verdicts a remote tile could not reach later
  // (the nodes move).
  const bool record = tiled && source_hot < static_count;
  if (tiled && ships_mobiles_ && !record) {
    record_mobiles_.clear();
    record_losses_.clear();
  }
  if (record) {
    record_mobiles_.clear();
    record_losses_.clear();
    record_destination_loss_ = 0.0;
  }
  // Recorded under link faults, a mobile hearer is judged once, for the record and for this
  // tile's booking alike: its loss, kCutOff, or kUnjudged (no record or no link faults).
  constexpr double kUnjudged = -1.0, kCutOff = -2.0;
  auto record_mobile = [&](NodeId id) {
    if (!record) return kUnjudged;
    if (!links) {
      record_mobiles_.push_back(id);
      return kUnjudged;
    }
    if (link_cut(faults, center, id)) return kCutOff;
    const double loss = link_loss(faults, center, id);
    record_mobiles_.push_back(id);
    record_losses_.push_back(loss);
    return loss;
  };
  bool reached = false;
  if (is_broadcast) {
    for_each_mobile_within(
        center, range,
        [&](NodeId id) {
          const double judged = record_mobile(id);
          if (judged != kCutOff && (!tiled || mobiles_here_))
            receive(id, hot_[sim::index(id)], judged);
        },
        source, sim::kNoNode);
  } else {
    for_each_mobile_within(
        center, range,
        [&](NodeId id) {
          const double judged = record_mobile(id);
          if (judged != kCutOff && (!tiled || mobiles_here_))
            overhear(id, hot_[sim::index(id)], judged >= 0.0);
        },
        source, destination, destination_distance);
    // The addressee is decided by its distance, not by the grid's rounding at the boundary.
    // The same arithmetic as unicast()'s distance, so the known value decides identically.
    const double distance = destination_distance >= 0.0 ? destination_distance
                                                        : (position(destination) - center).norm();
    reached = distance <= range;
    if (record && links && reached && destination_hot >= static_count)
      record_destination_loss_ =
          link_cut(faults, center, destination) ? -1.0 : link_loss(faults, center, destination);
    if (!reached)
      ++life_to_write(source_index).unreachable_count;
    else if (!tiled || owns(destination))
      receive_destination();
  }
  return Heard{hearers, received, lost, static_hearers, static_received, reached};
}

template Radio::Heard Radio::hear<false, false>(const Outgoing& out, const FrameRecord* remote);
template Radio::Heard Radio::hear<true, false>(const Outgoing& out, const FrameRecord* remote);
template Radio::Heard Radio::hear<false, true>(const Outgoing& out, const FrameRecord* remote);
template Radio::Heard Radio::hear<true, true>(const Outgoing& out, const FrameRecord* remote);

}  // namespace masnet::net
