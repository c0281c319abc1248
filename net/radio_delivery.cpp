// Delivery on the uncontended levels (ideal, airtime): frames wait in batches for their arrival
// time, or per reception with jitter, and are handed to their receivers in id order. See
// docs/radio-and-energy.md and docs/time-and-ordering.md.
#include <algorithm>
#include <cmath>

#include "net/radio.hpp"
#include "sim/free_slots.hpp"
#include "sim/random.hpp"

namespace masnet::net {
namespace {
constexpr std::uint64_t kJitterPurpose = sim::purpose("radio.jitter");
}  // namespace

void Radio::deliver(sim::Time arrival, const Outgoing& out, sim::Time sent_at, Payload&& payload,
                    const sim::EventKey* key) {
  const auto type = static_cast<MessageType>(out.type_index);
  std::vector<NodeId>& receivers = scratch_receivers_;
  // Delivery order is by node id, whatever the grid's layout.
  // (On a sensor grid the runs already come in id order: check before sorting.)
  if (receivers.size() > 1 && !std::is_sorted(receivers.begin(), receivers.end()))
    std::sort(receivers.begin(), receivers.end());

  if (params_.jitter_s <= 0) {
    // One event delivers to every receiver in id order: the same order separate events with
    // consecutive sequence numbers would give, at a fraction of the cost.
    Batch& batch = batch_for(arrival, key);
    const auto count = static_cast<std::uint32_t>(receivers.size());
    const bool one = count == 1;
    batch.deliveries.push_back(Delivery{
        Frame{out.source, out.destination, type, out.bytes, out.range, sent_at, out.frame_number,
              std::move(payload)},
        one ? sim::index(receivers[0]) : static_cast<std::uint32_t>(batch.receivers.size()),
        count});
    if (!one) batch.receivers.insert(batch.receivers.end(), receivers.begin(), receivers.end());
    return;
  }
  const std::uint32_t index = sim::reuse_or_append(free_jittered_, jittered_);
  Jittered& j = jittered_[index];
  j.frame = Frame{out.source,       out.destination,   type, out.bytes, out.range, sent_at,
                  out.frame_number, std::move(payload)};
  j.pending = static_cast<std::uint32_t>(receivers.size());
  for (NodeId id : receivers) {
    const double u =
        sim::keyed_uniform01(seed_, kJitterPurpose, nodes_[out.source_index].random_key,
                             nodes_[sim::index(id)].random_key, out.frame_number);
    // Each reception is the receiver's event: its time belongs to the receiver's fingerprint
    // stream, kept where the receiver is (in the scheduling order `at`).
    simulator_.at_for(sim::origin_of(id), arrival + sim::seconds(u * params_.jitter_s),
                      [this, index, id] { deliver_jittered(index, id); });
  }
}

void Radio::hand_over(const Frame& frame, NodeId receiver) {
  // Died while the frame was in the air (only batteries and faults kill; skip the lookup
  // otherwise).
  if (guarded() && !nodes_[sim::index(receiver)].alive) {
    sim::Fingerprint& traffic = senders_[sim::index(receiver)].traffic;
    traffic.mix((std::uint64_t{sim::index(frame.source)} << 32) | sim::index(receiver));
    traffic.mix(kUndeliveredMark ^ frame.number);
    return;
  }
  // What the receiver's handler schedules is its own (the kernel's origin order; only then:
  // a store into the simulator on every reception cost the scheduling order 2 %).
  sim::Fingerprint& fp = simulator_.fingerprint_stream_as(sim::origin_of(receiver));
  fp.mix((std::uint64_t{sim::index(frame.source)} << 32) | sim::index(receiver));
  fp.mix((std::uint64_t{static_cast<std::uint8_t>(frame.type)} << 32) | frame.size_bytes);
  if (listener_) listener_->on_frame(receiver, frame);
}

Radio::Batch& Radio::batch_for(sim::Time arrival, const sim::EventKey* key) {
  const bool open = open_batch_ != 0xFFFFFFFFu && open_batch_time_ == arrival;
  if (simulator_.ties_by_origin()) [[unlikely]]
    return batch_by_origin(arrival, open, key);
  // A separate event would have run right after the batch if nothing was scheduled since.
  if (open && simulator_.last_sequence() == open_batch_sequence_) return batches_[open_batch_];
  const std::uint32_t batch = sim::reuse_or_append(free_batches_, batches_);
  open_batch_sequence_ =
      simulator_.at(arrival, [this, batch] { run_batch<false>(batch); }).sequence;
  open_batch_ = batch;
  open_batch_time_ = arrival;
  return batches_[batch];
}

Radio::Batch& Radio::batch_by_origin(sim::Time arrival, bool open, const sim::EventKey* made) {
  // The frame takes the key its own event would have had (made by its sender's tile when it
  // crossed from another). It joins the open batch if that key comes after the batch's last: the
  // batch then hands the frames over in key order, each as its own event would have run
  // (run_batch<true> lets other events of the instant run between).
  const sim::EventKey key = made != nullptr ? *made : simulator_.next_key(arrival);
  if (open && batches_[open_batch_].keys.back() < key) {
    batches_[open_batch_].keys.push_back(key);
    return batches_[open_batch_];
  }
  const std::uint32_t batch = sim::reuse_or_append(free_batches_, batches_);
  batches_[batch].keys.push_back(key);
  // Its time goes into no stream: hand_over acts as each receiver and mixes it into theirs.
  simulator_.at_keyed(arrival, key, sim::Simulator::kNoStream,
                      [this, batch] { run_batch<true>(batch); });
  open_batch_ = batch;
  open_batch_time_ = arrival;
  return batches_[batch];
}

template <bool kByOrigin>
void Radio::run_batch(std::uint32_t batch) {
  if (open_batch_ == batch) open_batch_ = 0xFFFFFFFFu;  // closed: nothing joins it any more
  // Handlers may open new batches and so move `batches_`' elements, never this batch's buffers:
  // the pointers below stay valid.
  const Delivery* const deliveries = batches_[batch].deliveries.data();
  const NodeId* const receivers = batches_[batch].receivers.data();
  const std::size_t count = batches_[batch].deliveries.size();
  const std::size_t begin = kByOrigin ? batches_[batch].next : 0;
  for (std::size_t i = begin; i < count; ++i) {
    if constexpr (kByOrigin) {
      // Another event of this instant sorts before this frame's own: it runs first, and the
      // rest of the batch after it, keyed by this frame.
      const sim::EventKey key = batches_[batch].keys[i];
      if (i > begin && !simulator_.nothing_due_before(key)) {
        batches_[batch].next = static_cast<std::uint32_t>(i);
        simulator_.at_keyed(simulator_.now(), key, sim::Simulator::kNoStream,
                            [this, batch] { run_batch<true>(batch); });
        return;
      }
      simulator_.continue_as(key);
    }
    // The frames were written a while ago (a reply burst's round trip of other traffic): fetch
    // the next ones while this one is handled.
    if (i + kDeliveryLookahead < count) prefetch_delivery(deliveries[i + kDeliveryLookahead]);
    const Delivery& d = deliveries[i];
    if (d.count == 1) {
      hand_over(d, sim::node_id(d.first));
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
      hand_over(d, ids[k]);
    }
  }
  Batch& done = batches_[batch];
  done.deliveries.clear();
  done.receivers.clear();
  if constexpr (kByOrigin) {
    done.keys.clear();
    done.next = 0;
  }
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
