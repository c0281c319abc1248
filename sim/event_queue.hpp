#pragma once
// The pending-event set. Keys (time, slot) live in a radix heap (Ahuja, Mehlhorn, Orlin &
// Tarjan 1990); the actions live in a pool of slots. Simulated time is an integer that never
// goes back — exactly what a radix heap needs: a push appends a 16-byte key to one of 65
// buckets, chosen by the highest bit in which its time differs from the last minimum, and a
// pop takes the next key of bucket 0. A small lowest bucket is not spread but sorted once, as a
// run that keys scheduled into its range join. Equal times leave in sequence (scheduling) order.
// It replaced a 4-ary heap of 24-byte records after the PHOLD benchmark showed it faster
// (docs/performance.md). No allocation per event once the vectors have grown.
// Ties can instead follow the origin order (EventKey), which a partition of a run can compute
// alone (docs/time-and-ordering.md, docs/decisions/0012-partitioned-runs.md).
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "sim/event_action.hpp"
#include "sim/free_slots.hpp"

namespace masnet::sim {

/// Handle of a pending event, for cancelling it. Stale handles are harmless.
struct EventId {
  std::uint32_t slot = 0xFFFFFFFFu;
  std::uint64_t sequence = 0;
  bool valid() const { return slot != 0xFFFFFFFFu; }
};

/// The tie-break of the origin order: events of one time run by `depth` (0, or one more than
/// that of the event which scheduled them at its own time, so that a zero-delay event follows
/// its cause), then by the `origin` that scheduled them (0: the world, outside any node), then
/// by that origin's own count. Every part is known to whoever schedules the event.
struct EventKey {
  std::uint32_t depth = 0;
  std::uint32_t origin = 0;
  std::uint32_t count = 0;
  friend constexpr auto operator<=>(const EventKey&, const EventKey&) = default;
};

/// An event's place in the origin order and the origin its handler acts as.
struct OriginTag {
  EventKey key;
  std::uint32_t owner = 0;
};

class EventQueue {
 public:
  /// Breaks ties by EventKey instead of scheduling order. Precondition: empty and never used.
  void order_ties_by_origin() { by_origin_ = true; }
  bool ties_by_origin() const { return by_origin_; }
  /// The sequence number the most recent push received (0 before any).
  std::uint64_t last_sequence() const { return next_sequence_ - 1; }
  /// Keys and slots currently held, cancelled ones included.
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void reserve(std::size_t n) {
    slots_.reserve(n);
    free_.reserve(n);
  }

  /// Adds `action` at `time_ns`. Precondition: time_ns >= the time of the last pop; ties in
  /// scheduling order.
  EventId push(std::int64_t time_ns, const EventAction& action) {
    const std::uint32_t slot = reuse_or_append(free_, slots_);
    const std::uint64_t sequence = next_sequence_++;
    slots_[slot] = Slot{action, sequence};
    enqueue(Key{static_cast<std::uint64_t>(time_ns), slot});
    ++size_;
    return EventId{slot, sequence};
  }
  /// The same in the origin order: `tag` places it among the events of its time.
  EventId push(std::int64_t time_ns, const EventAction& action, const OriginTag& tag) {
    const std::uint32_t slot = reuse_or_append(free_, slots_);
    const std::uint64_t sequence = next_sequence_++;
    slots_[slot] = Slot{action, sequence};
    if (tags_.size() <= slot) tags_.resize(slots_.size());
    tags_[slot] = tag;
    enqueue(Key{static_cast<std::uint64_t>(time_ns), slot});
    ++size_;
    return EventId{slot, sequence};
  }

  /// Marks a pending event cancelled; false if it already ran or was cancelled.
  bool cancel(EventId id) {
    if (!id.valid() || id.slot >= slots_.size()) return false;
    Slot& s = slots_[id.slot];
    if (s.sequence != id.sequence || !s.action) return false;
    s.action.clear();  // lazy deletion: the key is dropped when it comes up
    return true;
  }

  /// Origin order: false if a pending event of time `time_ns` sorts before `key`. Called while
  /// an event of that time runs, when every key of that time is in bucket 0 from its head
  /// (keys of one time always share a bucket, and bucket 0 is in run order). A cancelled event
  /// counts too.
  bool nothing_before(std::uint64_t time_ns, const EventKey& key) const {
    if (head_ == buckets_[0].size()) return true;
    const Key& first = buckets_[0][head_];
    return first.time != time_ns || !(tags_[first.slot].key < key);
  }

  /// Time of the first key; precondition !empty(). Leaves the order untouched.
  std::int64_t first_time() const {
    if (head_ == buckets_[0].size()) [[unlikely]] {
      const std::vector<Key>& bucket = buckets_[first_bucket()];
      std::uint64_t m = bucket[0].time;
      for (const Key& k : bucket)
        m = std::min(m, k.time);
      return static_cast<std::int64_t>(m);
    }
    return static_cast<std::int64_t>(buckets_[0][head_].time);
  }

  /// Removes the first event: its time and action (an empty action if it was cancelled).
  /// Precondition !empty().
  [[gnu::always_inline]] std::int64_t pop(EventAction& action) {
    if (head_ == buckets_[0].size()) [[unlikely]]
      refill();
    return take(action);
  }
  /// pop() in the origin order, also giving the event's tag.
  std::int64_t pop(EventAction& action, OriginTag& tag) {
    if (head_ == buckets_[0].size()) [[unlikely]]
      refill();
    tag = tags_[buckets_[0][head_].slot];
    return take(action);
  }

 private:
  struct Key {
    std::uint64_t time;
    std::uint32_t slot;
  };
  struct Slot {
    EventAction action;  // empty once run or cancelled
    std::uint64_t sequence = 0;
  };

  [[gnu::always_inline]] std::int64_t take(EventAction& action) {
    const Key key = buckets_[0][head_];
    Slot& slot = slots_[key.slot];
    action = slot.action;
    slot.action.clear();
    free_.push_back(key.slot);
    if (++head_ == buckets_[0].size()) {
      buckets_[0].clear();
      head_ = 0;
    }
    --size_;
    return static_cast<std::int64_t>(key.time);
  }

  // The origin order's tie-break of two keys of one time.
  bool later(const Key& a, const Key& b) const { return tags_[b.slot].key < tags_[a.slot].key; }
  // The run order of bucket 0: time, then the tie order.
  bool runs_before(const Key& a, const Key& b) const {
    if (a.time != b.time) return a.time < b.time;
    return by_origin_ ? later(b, a) : slots_[a.slot].sequence < slots_[b.slot].sequence;
  }

  std::size_t bucket_of(std::uint64_t time) const {
    return time == last_ ? 0 : 64 - static_cast<std::size_t>(std::countl_zero(time ^ last_));
  }
  void place(const Key& key) { buckets_[bucket_of(key.time)].push_back(key); }

  // A new key: into its bucket, or into the sorted run of bucket 0 if it falls in the run's
  // range (buckets below run_below_, which are empty meanwhile).
  [[gnu::always_inline]] void enqueue(const Key& key) {
    const std::size_t b = bucket_of(key.time);
    if (b >= run_below_) [[likely]] {
      buckets_[b].push_back(key);
      return;
    }
    join_run(key);
  }
  [[gnu::noinline]] void join_run(const Key& key) {
    std::vector<Key>& due = buckets_[0];
    // The usual case: not before the last key of the run (in scheduling order a new key ties
    // after every key of its time).
    if (head_ == due.size() || !runs_before(key, due.back())) {
      due.push_back(key);
      return;
    }
    if (due.size() - head_ >= kRunMax) [[unlikely]] {
      spread_run(key);
      return;
    }
    due.insert(std::upper_bound(due.begin() + static_cast<std::ptrdiff_t>(head_), due.end(), key,
                                [this](const Key& a, const Key& b) { return runs_before(a, b); }),
               key);
  }
  // A run grown too long to insert into: its keys and `key` go back to the buckets below
  // run_below_, around the same last_ (which may be the time of an event that is still
  // running: later keys must not go below it).
  [[gnu::noinline]] void spread_run(const Key& key) {
    std::vector<Key>& due = buckets_[0];
    spill_.assign(due.begin() + static_cast<std::ptrdiff_t>(head_), due.end());
    spill_.push_back(key);
    due.clear();
    head_ = 0;
    run_below_ = 1;
    for (const Key& k : spill_)
      place(k);
    sort_due();
  }
  void sort_due() {
    std::vector<Key>& due = buckets_[0];
    if (due.size() < 2) return;
    if (by_origin_)  // one test per sort, not per comparison
      sort_by_origin(due);
    else
      std::sort(due.begin(), due.end(), [this](const Key& a, const Key& b) {
        return slots_[a.slot].sequence < slots_[b.slot].sequence;
      });
  }
  std::size_t first_bucket() const {
    std::size_t i = 1;
    while (buckets_[i].empty())
      ++i;
    return i;
  }
  // Bucket 0 is used up. Take the first non-empty bucket: a small one becomes the new run of
  // bucket 0, sorted once; a large one is spread around its minimum, which becomes the new
  // last_ (every key of it lands in a lower bucket).
  [[gnu::always_inline]] void refill() {
    buckets_[0].clear();
    head_ = 0;
    const std::size_t first = first_bucket();
    std::vector<Key>& bucket = buckets_[first];
    // A small lowest bucket holds the next few events to run: fetch their slots now, so that
    // their pops do not wait for memory (with 10⁵ pending events the slots outgrow the caches).
    if (bucket.size() <= kPrefetchBelow) {
      for (const Key& k : bucket)
        __builtin_prefetch(&slots_[k.slot]);
      if (by_origin_) prefetch_tags(bucket);
    }
    std::uint64_t m = bucket[0].time;
    for (const Key& k : bucket)
      m = std::min(m, k.time);
    last_ = m;
    if (bucket.size() <= kSortBelow) {
      // Each key would move down a few more times before it runs: sort them instead. Keys
      // scheduled meanwhile into the same range join the run at their place (enqueue).
      buckets_[0].swap(bucket);
      run_below_ = first;
      sort_run();
      return;
    }
    run_below_ = 1;
    for (const Key& k : bucket)
      place(k);
    bucket.clear();
    // Keys reaching bucket 0 together may come in any order; keys pushed later at this time
    // have larger sequence numbers (or are inserted at their place, in the origin order), so
    // one sort here keeps bucket 0 in tie order.
    sort_due();
  }
  void sort_run() {
    std::vector<Key>& run = buckets_[0];
    if (run.size() < 2) return;
    std::sort(run.begin(), run.end(),
              [this](const Key& a, const Key& b) { return runs_before(a, b); });
  }
  // The origin order's parts stay out of line, and pop, take and refill are forced inline: with
  // a run loop for each order the compiler stopped inlining the queue into it, and the
  // scheduling order paid about 20 instructions per event in the kernel benchmark.
  [[gnu::noinline]] void prefetch_tags(const std::vector<Key>& bucket) const {
    for (const Key& k : bucket)
      __builtin_prefetch(&tags_[k.slot]);
  }
  [[gnu::noinline]] void sort_by_origin(std::vector<Key>& due) const {
    std::sort(due.begin(), due.end(), [this](const Key& a, const Key& b) { return later(b, a); });
  }

  static constexpr std::size_t kPrefetchBelow = 32;  // 8 gained less (docs/decisions/0005)
  static constexpr std::size_t kSortBelow = 32;      // a bucket this small becomes a sorted run
  static constexpr std::size_t kRunMax = 128;        // a run this long is spread on insertion
  std::array<std::vector<Key>, 65> buckets_;
  std::size_t head_ = 0;  // next key of bucket 0
  std::uint64_t last_ = 0;
  std::size_t run_below_ = 1;  // keys of buckets below this one go into bucket 0's sorted run
  std::vector<Key> spill_;
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> free_;
  std::vector<OriginTag> tags_;  // by slot; the origin order only
  bool by_origin_ = false;
  std::uint64_t next_sequence_ = 1;
  std::size_t size_ = 0;
};

}  // namespace masnet::sim
