#pragma once
// The discrete-event kernel: a clock, a queue of small event records and a pool of inline
// actions. No globals: pass `Simulator&` explicitly.
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "sim/assert.hpp"
#include "sim/event_action.hpp"
#include "sim/event_queue.hpp"
#include "sim/fingerprint.hpp"
#include "sim/time.hpp"

namespace masnet::sim {

class Simulator {
 public:
  Simulator() = default;

  /// Current simulated time: the time of the event being run (or the last run_until limit).
  Time now() const { return now_; }

  /// Schedules `action` `delay` after now. Precondition: delay >= 0 (asserted).
  template <class F>
  EventId after(Duration delay, F&& action) {
    MASNET_ASSERT(delay.count() >= 0, "negative delay: events cannot be scheduled in the past");
    return queue_.push(to_ns(now_ + delay), EventAction::make(std::forward<F>(action)));
  }
  /// Schedules `action` at absolute time `when`. Precondition: when >= now() (asserted).
  template <class F>
  EventId at(Time when, F&& action) {
    MASNET_ASSERT(when >= now_, "event scheduled before the current time");
    return queue_.push(to_ns(when), EventAction::make(std::forward<F>(action)));
  }
  /// Cancels a pending event; returns false if it already ran or was cancelled.
  bool cancel(EventId id);

  /// Runs events in (time, sequence) order while their time is <= `limit`, then sets the
  /// clock to `limit` (unless stopped early). Returns the number of events run.
  std::uint64_t run_until(Time limit);
  /// Runs until the queue is empty or `stop()` is called.
  std::uint64_t run();
  /// Ends the current run after the event being executed.
  void stop() { stop_requested_ = true; }

  std::uint64_t events_run() const { return events_run_; }
  /// The sequence number of the most recently scheduled event: if it is still the one a caller
  /// got from `at`, nothing was scheduled since (lets a caller extend that event instead of
  /// scheduling a new one right behind it).
  std::uint64_t last_sequence() const { return queue_.last_sequence(); }
  std::size_t pending() const { return queue_.size() - cancelled_pending_; }

  /// The fingerprint of everything executed so far. Models mix payload digests into it
  /// while handling an event (e.g. the radio mixes each delivered frame's header).
  Fingerprint& fingerprint() { return fingerprint_; }
  const Fingerprint& fingerprint() const { return fingerprint_; }

  /// Calls `hook(now, events_run)` after every `every_events`-th event run (counted across
  /// run/run_until calls), e.g. to redraw a progress line while a long chunk runs. A generic
  /// "every N events" hook: the kernel reads no clock. An empty hook (or 0) removes it. The
  /// cost per event is one decrement of a counter in a register. A hook that only observes (reads a
  /// clock, draws) leaves the event stream and its fingerprint unchanged.
  void set_progress_hook(std::uint64_t every_events,
                         std::function<void(Time now, std::uint64_t events)> hook);

  /// Pre-sizes the queue for `n` simultaneously pending events.
  void reserve(std::size_t n) { queue_.reserve(n); }

 private:
  template <bool kBounded>
  std::uint64_t run_loop(std::int64_t limit_ns);

  Time now_ = kTimeZero;
  std::uint64_t events_run_ = 0;
  std::size_t cancelled_pending_ = 0;
  bool stop_requested_ = false;
  std::function<void(Time, std::uint64_t)> hook_;
  static constexpr std::uint64_t kNoHook = ~std::uint64_t{0};
  std::uint64_t hook_period_ = kNoHook;
  std::uint64_t hook_countdown_ = kNoHook;  // events until the next call
  EventQueue queue_;
  Fingerprint fingerprint_;
};

}  // namespace masnet::sim
