#include "sim/simulator.hpp"

#include <cstdio>

namespace masnet::sim {

std::string Fingerprint::hex() const {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(state_));
  return text;
}

bool Simulator::cancel(EventId id) {
  if (!queue_.cancel(id)) return false;
  ++cancelled_pending_;
  return true;
}

void Simulator::set_progress_hook(std::uint64_t every_events,
                                  std::function<void(Time now, std::uint64_t events)> hook) {
  if (every_events == 0 || !hook) {
    hook_ = nullptr;
    hook_period_ = hook_countdown_ = kNoHook;
    return;
  }
  hook_ = std::move(hook);
  hook_period_ = every_events;
  hook_countdown_ = every_events;
}

void Simulator::order_ties_by_origin() {
  MASNET_ASSERT(queue_.empty() && events_run_ == 0 && queue_.last_sequence() == 0,
                "the tie order is chosen before anything is scheduled");
  queue_.order_ties_by_origin();
}

EventKey Simulator::next_key(Time when) {
  // A zero-delay event follows the event that scheduled it (and every event of its depth).
  const EventKey key = peek_key(when);
  reach(origin_);
  MASNET_ASSERT(key.count != kReservedCount, "an origin scheduled more than 2^32 events");
  MASNET_ASSERT(key.depth != kInstantEndDepth && (when != now_ || key.depth != 0),
                "a chain of zero-delay events reached the depth of the instant's end");
  ++origins_[origin_].count;
  return key;
}

std::vector<Fingerprint> Simulator::origin_streams() const {
  std::vector<Fingerprint> streams;
  streams.reserve(origins_.size());
  for (const OriginState& o : origins_)
    streams.push_back(o.stream);
  return streams;
}

EventId Simulator::push_by_origin(Time when, const EventAction& action) {
  return queue_.push(to_ns(when), action, OriginTag{next_key(when), origin_});
}

template <bool kBounded, bool kByOrigin>
std::uint64_t Simulator::run_loop(std::int64_t limit_ns) {
  const std::uint64_t before = events_run_;
  stop_requested_ = false;
  std::uint64_t countdown = hook_countdown_;  // a local: the loop keeps it in a register
  EventAction action;
  OriginTag tag;
  while (!queue_.empty()) {
    if (kBounded && queue_.first_time() > limit_ns) break;
    const std::int64_t time_ns = kByOrigin ? queue_.pop(action, tag) : queue_.pop(action);
    if (!action) {
      --cancelled_pending_;
      continue;
    }
    if constexpr (kByOrigin) {
      origin_ = tag.owner;
      running_ = tag.key;
    }
    MASNET_ASSERT(time_ns >= to_ns(now_), "time went backwards");
    now_ = Time{Duration{time_ns}};
    ++events_run_;
    // Every push in the origin order reached its owner's state (but kNoStream's, which has none):
    // no bounds check here.
    if constexpr (kByOrigin) {
      if (tag.owner != kNoStream)
        origins_[tag.owner].stream.mix(static_cast<std::uint64_t>(time_ns));
    } else {
      fingerprint_.mix(static_cast<std::uint64_t>(time_ns));
    }
    action();
    // One decrement per event, hook or not: a second copy of the loop for runs with a hook
    // made the compiler stop inlining the queue's pop (4 % more instructions in PHOLD).
    if (--countdown == 0) [[unlikely]] {
      countdown = hook_period_;
      if (hook_) hook_(now_, events_run_);  // without a hook: once in 2^64 events
    }
    if (stop_requested_) break;
  }
  hook_countdown_ = countdown;
  origin_ = 0;  // code between runs acts as the world
  return events_run_ - before;
}

std::uint64_t Simulator::run_until(Time limit) {
  MASNET_ASSERT(limit >= now_, "run_until a time in the past");
  const std::uint64_t ran = queue_.ties_by_origin() ? run_loop<true, true>(to_ns(limit))
                                                    : run_loop<true, false>(to_ns(limit));
  if (!stop_requested_ && now_ != limit) {
    now_ = limit;
    running_ = EventKey{};  // nothing ran at this time yet
  }
  return ran;
}

std::uint64_t Simulator::run() {
  return queue_.ties_by_origin() ? run_loop<false, true>(0) : run_loop<false, false>(0);
}

}  // namespace masnet::sim
