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

template <bool kBounded>
std::uint64_t Simulator::run_loop(std::int64_t limit_ns) {
  const std::uint64_t before = events_run_;
  stop_requested_ = false;
  EventAction action;
  while (!queue_.empty()) {
    if (kBounded && queue_.first_time() > limit_ns) break;
    const std::int64_t time_ns = queue_.pop(action);
    if (!action) {
      --cancelled_pending_;
      continue;
    }
    MASNET_ASSERT(time_ns >= to_ns(now_), "time went backwards");
    now_ = Time{Duration{time_ns}};
    ++events_run_;
    fingerprint_.mix(static_cast<std::uint64_t>(time_ns));
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
