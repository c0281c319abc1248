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
    return at(now_ + delay, std::forward<F>(action));
  }
  /// Schedules `action` at absolute time `when`. Precondition: when >= now() (asserted). In
  /// the origin order it runs as the acting origin.
  template <class F>
  EventId at(Time when, F&& action) {
    MASNET_ASSERT(when >= now_, "event scheduled before the current time");
    // Out of line: inlined at every call site, the origin order's push made the callers too
    // large to inline what they inlined before (0.6 % more instructions in a 10⁴ run).
    if (queue_.ties_by_origin()) [[unlikely]]
      return push_by_origin(when, EventAction::make(std::forward<F>(action)));
    return queue_.push(to_ns(when), EventAction::make(std::forward<F>(action)));
  }

  // --- The origin order (docs/time-and-ordering.md) ------------------------------------------
  // Ties between events of one time are broken by an EventKey that the scheduling side computes
  // alone, so that the parts of a partitioned run agree on one order without asking each other.
  // Origins are small integers: 0 is the world (code outside any node), a node is its index + 1.

  /// Switches to the origin order. Precondition: nothing has been scheduled yet (asserted).
  void order_ties_by_origin();
  bool ties_by_origin() const { return queue_.ties_by_origin(); }
  /// The origin whose handler is running: the events it schedules count as its own. The kernel
  /// sets it to each event's owner before running it; a model that hands one event to several
  /// nodes (a broadcast's receivers) sets it before each.
  void act_as(std::uint32_t origin) { origin_ = origin; }
  std::uint32_t acting_origin() const { return origin_; }
  /// The key of the event being run (of the last one run, between runs): a partition's record
  /// of what it ran merges with the others' in the one total order by (time, key).
  const EventKey& running_key() const { return running_; }
  /// The key of the next event the acting origin schedules at `when` (uses up one of its
  /// counts). For an event built here and scheduled elsewhere with `at_keyed`.
  EventKey next_key(Time when);
  /// The key `next_key(when)` would return, without using it up.
  EventKey peek_key(Time when) const {
    const std::uint32_t count = origin_ < origins_.size() ? origins_[origin_].count : 0;
    return EventKey{when == now_ ? running_.depth + 1 : 0u, origin_, count};
  }
  /// An event that does the work of several — a delivery batch, one frame after another —
  /// asks before each part whether a separate event with `key` would run next: false if an
  /// event of this instant (a cancelled one too) sorts before it. Precondition: origin order.
  bool nothing_due_before(const EventKey& key) const {
    return queue_.nothing_before(static_cast<std::uint64_t>(to_ns(now_)), key);
  }
  /// ...and then runs that part as if it were that event: what it schedules for this instant
  /// follows `key`. Precondition: origin order, key not below the running key (asserted).
  /// The parts mix themselves into the fingerprint where they belong (an event that does the
  /// work of several is scheduled for `kNoStream`).
  void continue_as(const EventKey& key) {
    MASNET_ASSERT(!(key < running_), "an event's parts continue in key order");
    running_ = key;
  }
  /// The owner of an event whose time goes into no fingerprint stream: one that does the work of
  /// several (a delivery batch), each part of which mixes itself into the stream of whoever it
  /// reaches — so that the streams do not depend on how the parts were grouped into events, nor
  /// on which part of a partitioned run delivered them. Its action must `act_as` an origin
  /// before it schedules anything.
  static constexpr std::uint32_t kNoStream = 0xFFFFFFFFu;
  /// Schedules `action` at `when` with a key made by `next_key` (here or in another partition),
  /// to run as `owner`. Precondition: the origin order, when >= now() (asserted).
  template <class F>
  EventId at_keyed(Time when, EventKey key, std::uint32_t owner, F&& action) {
    MASNET_ASSERT(when >= now_, "event scheduled before the current time");
    MASNET_ASSERT(queue_.ties_by_origin(), "a keyed event needs the origin order");
    if (owner != kNoStream) reach(owner);  // the run loop mixes into its owner's stream
    return queue_.push(to_ns(when), EventAction::make(std::forward<F>(action)),
                       OriginTag{key, owner});
  }
  /// Schedules `action` `delay` after now as `origin`'s own event — counted and run as it —
  /// then acts as before: the world starting a node's work.
  template <class F>
  EventId after_as(std::uint32_t origin, Duration delay, F&& action) {
    const std::uint32_t acting = origin_;
    origin_ = origin;
    const EventId id = after(delay, std::forward<F>(action));
    origin_ = acting;
    return id;
  }
  /// Schedules `action` at `when` to run as `owner` (e.g. a message to a node of the same
  /// part; a node's own first events are scheduled acting as the node). In scheduling order
  /// `owner` is ignored.
  template <class F>
  EventId at_for(std::uint32_t owner, Time when, F&& action) {
    if (!queue_.ties_by_origin()) return at(when, std::forward<F>(action));
    return at_keyed(when, next_key(when), owner, std::forward<F>(action));
  }
  /// Schedules `action` at `when` to run as `owner` after every other event of that time (in
  /// the scheduling order: like `at`). Its key names the owner alone — no count, no depth of a
  /// cause — so whoever schedules it, at whatever moment, gives it the same place: for an event
  /// of which an owner has at most one pending (its battery running empty), booked by the
  /// events of other nodes too. Events it schedules at its own time follow it.
  template <class F>
  EventId at_instant_end(std::uint32_t owner, Time when, F&& action) {
    if (!queue_.ties_by_origin()) return at(when, std::forward<F>(action));
    MASNET_ASSERT(when >= now_, "event scheduled before the current time");
    reach(owner);
    return queue_.push(to_ns(when), EventAction::make(std::forward<F>(action)),
                       OriginTag{EventKey{kInstantEndDepth, owner, kReservedCount}, owner});
  }
  /// The depth of `at_instant_end`'s keys: above any chain of zero-delay events (asserted).
  static constexpr std::uint32_t kInstantEndDepth = 0xFFFF0000u;
  /// The count of `at_instant_end`'s keys, which no origin's own count reaches (asserted).
  static constexpr std::uint32_t kReservedCount = 0xFFFFFFFFu;

  /// Cancels a pending event; returns false if it already ran or was cancelled.
  bool cancel(EventId id);

  /// Runs events in (time, sequence) order (or (time, EventKey)) while their time is <= `limit`,
  /// then sets the clock to `limit` (unless stopped early). Returns the number of events run.
  std::uint64_t run_until(Time limit);
  /// Runs until the queue is empty or `stop()` is called.
  std::uint64_t run();
  /// Ends the current run after the event being executed.
  void stop() { stop_requested_ = true; }

  std::uint64_t events_run() const { return events_run_; }
  /// The time of the earliest pending event (a cancelled one counts too); kTimeMax if none.
  Time next_time() const { return queue_.empty() ? kTimeMax : Time{Duration{queue_.first_time()}}; }
  /// The sequence number of the most recently scheduled event: if it is still the one a caller
  /// got from `at`, nothing was scheduled since (lets a caller extend that event instead of
  /// scheduling a new one right behind it).
  std::uint64_t last_sequence() const { return queue_.last_sequence(); }
  std::size_t pending() const { return queue_.size() - cancelled_pending_; }

  /// The fingerprint of everything executed so far. In the origin order it combines one stream
  /// per origin (`combine_origin_streams`): each event's time goes into its owner's stream and
  /// what a model mixes goes into the acting origin's, so a node's stream is the same in a part
  /// of a partitioned run that holds the node as in the whole run.
  Fingerprint fingerprint() const {
    return queue_.ties_by_origin() ? combine_origin_streams(origin_streams()) : fingerprint_;
  }
  /// The stream models mix payload digests into while handling an event (e.g. the radio mixes
  /// each delivered frame's header): the acting origin's in the origin order.
  Fingerprint& fingerprint_stream() {
    return queue_.ties_by_origin() ? origin(origin_).stream : fingerprint_;
  }
  /// A model handing one event to several nodes (a broadcast's receivers), before each: in the
  /// origin order it acts as `origin` from now on and the time goes into that origin's stream,
  /// which it returns (the event stands for one of its own there); in the scheduling order the
  /// one stream, which has the time already.
  Fingerprint& fingerprint_stream_as(std::uint32_t origin_now) {
    if (!queue_.ties_by_origin()) return fingerprint_;
    origin_ = origin_now;
    Fingerprint& stream = origin(origin_now).stream;
    stream.mix(static_cast<std::uint64_t>(to_ns(now_)));
    return stream;
  }
  /// The origin order's streams by origin (untouched ones for origins that never ran).
  std::vector<Fingerprint> origin_streams() const;

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
  template <bool kBounded, bool kByOrigin>
  std::uint64_t run_loop(std::int64_t limit_ns);
  [[gnu::noinline]] EventId push_by_origin(Time when, const EventAction& action);

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
  // The origin order: who acts now, the running event's key, each origin's count and
  // fingerprint stream (side by side: a node that acts touches both).
  struct OriginState {
    Fingerprint stream;
    std::uint32_t count = 0;
  };
  OriginState& origin(std::uint32_t o) {
    reach(o);
    return origins_[o];
  }
  void reach(std::uint32_t o) {
    if (o >= origins_.size()) [[unlikely]]
      origins_.resize(std::size_t{o} + 1);
  }
  std::uint32_t origin_ = 0;
  EventKey running_;
  std::vector<OriginState> origins_;
};

}  // namespace masnet::sim
