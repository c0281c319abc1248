#pragma once
// A 4-ary min-heap of small event records ordered by (time, sequence number). Four children
// per node halve the depth of a binary heap and keep siblings in one cache line; records
// are 24 bytes so sifting moves little memory. See docs/time-and-ordering.md.
#include <cstdint>
#include <vector>

namespace masnet::sim {

/// One pending event: when it runs, its position in the total order, and where its action is.
struct EventRecord {
  std::int64_t time_ns;
  std::uint64_t sequence;  ///< scheduling order; breaks ties between equal times
  std::uint32_t slot;      ///< index of the action in the simulator's slot pool
};

inline bool runs_before(const EventRecord& a, const EventRecord& b) {
  return a.time_ns < b.time_ns || (a.time_ns == b.time_ns && a.sequence < b.sequence);
}

class EventQueue {
 public:
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  const EventRecord& top() const { return heap_.front(); }
  void reserve(std::size_t n) { heap_.reserve(n); }

  void push(const EventRecord& record) {
    std::size_t hole = heap_.size();
    heap_.push_back(record);
    while (hole > 0) {
      std::size_t parent = (hole - 1) / 4;
      if (!runs_before(record, heap_[parent])) break;
      heap_[hole] = heap_[parent];
      hole = parent;
    }
    heap_[hole] = record;
  }

  void pop() {
    const EventRecord last = heap_.back();
    heap_.pop_back();
    const std::size_t n = heap_.size();
    if (n == 0) return;
    std::size_t hole = 0;
    for (;;) {
      std::size_t first = 4 * hole + 1;
      if (first >= n) break;
      std::size_t best = first;
      std::size_t end = first + 4 < n ? first + 4 : n;
      for (std::size_t c = first + 1; c < end; ++c)
        if (runs_before(heap_[c], heap_[best])) best = c;
      if (!runs_before(heap_[best], last)) break;
      heap_[hole] = heap_[best];
      hole = best;
    }
    heap_[hole] = last;
  }

 private:
  std::vector<EventRecord> heap_;
};

}  // namespace masnet::sim
