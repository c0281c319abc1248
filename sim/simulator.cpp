#include "sim/simulator.hpp"

#include <cstdio>

namespace masnet::sim {

std::string Fingerprint::hex() const {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(state_));
  return text;
}

Simulator::Simulator() { reserve(1024); }

void Simulator::reserve(std::size_t n) {
  queue_.reserve(n);
  slots_.reserve(n);
  free_slots_.reserve(n);
}

EventId Simulator::schedule(Time when, EventAction action) {
  std::uint32_t slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    slot = static_cast<std::uint32_t>(slots_.size());
    slots_.emplace_back();
  }
  const std::uint64_t sequence = next_sequence_++;
  slots_[slot].action = action;
  slots_[slot].sequence = sequence;
  queue_.push(EventRecord{to_ns(when), sequence, slot});
  return EventId{slot, sequence};
}

bool Simulator::cancel(EventId id) {
  if (!id.valid() || id.slot >= slots_.size()) return false;
  Slot& slot = slots_[id.slot];
  if (slot.sequence != id.sequence || !slot.action) return false;
  // Lazy deletion: the record stays in the heap and is dropped when it reaches the top.
  slot.action.clear();
  ++cancelled_pending_;
  return true;
}

template <bool kBounded>
std::uint64_t Simulator::run_loop(std::int64_t limit_ns) {
  const std::uint64_t before = events_run_;
  stop_requested_ = false;
  while (!queue_.empty()) {
    const EventRecord record = queue_.top();
    if (kBounded && record.time_ns > limit_ns) break;
    queue_.pop();
    Slot& slot = slots_[record.slot];
    EventAction action = slot.action;
    // Free the slot before running, so the events this one schedules can reuse it.
    slot.action.clear();
    free_slots_.push_back(record.slot);
    if (!action) {
      --cancelled_pending_;
      continue;
    }
    MASNET_ASSERT(record.time_ns >= to_ns(now_), "time went backwards");
    now_ = Time{Duration{record.time_ns}};
    ++events_run_;
    fingerprint_.mix(static_cast<std::uint64_t>(record.time_ns));
    action();
    if (stop_requested_) break;
  }
  return events_run_ - before;
}

std::uint64_t Simulator::run_until(Time limit) {
  MASNET_ASSERT(limit >= now_, "run_until a time in the past");
  const std::uint64_t ran = run_loop<true>(to_ns(limit));
  if (!stop_requested_) now_ = limit;
  return ran;
}

std::uint64_t Simulator::run() { return run_loop<false>(0); }

}  // namespace masnet::sim
