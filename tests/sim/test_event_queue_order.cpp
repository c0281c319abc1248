// The queue against a plain model: at every step the event that runs is the least pending one
// by (time, sequence) — or by (time, EventKey) in the origin order — while handlers schedule at
// the current instant, nearby, far ahead and in bursts of one time, and cancel.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include "sim/random.hpp"
#include "sim/simulator.hpp"

using namespace masnet::sim;

namespace {

struct Pending {
  std::int64_t time_ns;
  std::uint64_t sequence;  // the test's own count of schedules: the scheduling order
  EventKey key;            // the origin order's key
  std::uint32_t label;
  EventId id;
};

class Model {
 public:
  Model(bool by_origin, std::uint64_t seed) : by_origin_(by_origin), rng_(seed) {
    if (by_origin_) sim_.order_ties_by_origin();
  }

  void run(std::uint32_t events) {
    for (int i = 0; i < 400; ++i)
      schedule();
    target_ = events;
    sim_.run();
  }
  std::uint32_t executed() const { return executed_; }
  std::uint32_t mismatches() const { return mismatches_; }
  std::uint32_t ties() const { return ties_; }

 private:
  bool less(const Pending& a, const Pending& b) const {
    if (by_origin_) return std::tie(a.time_ns, a.key) < std::tie(b.time_ns, b.key);
    return std::tie(a.time_ns, a.sequence) < std::tie(b.time_ns, b.sequence);
  }

  std::int64_t delay_ns() {
    switch (rng_.below(6)) {
      case 0:
        return 0;
      case 1:
        return static_cast<std::int64_t>(rng_.below(4));
      case 2:
        return static_cast<std::int64_t>(rng_.below(1000));
      case 3:
        return static_cast<std::int64_t>(rng_.below(1u << 20));
      case 4:
        return static_cast<std::int64_t>(rng_.below(std::uint64_t{1} << 34));
      default:
        return static_cast<std::int64_t>(rng_.below(50)) * 1000;  // a coarse grid: ties
    }
  }

  void schedule_at(std::int64_t time_ns) {
    const Time when = kTimeZero + Duration{time_ns};
    const std::uint32_t label = next_label_++;
    Pending p{time_ns, next_sequence_++, {}, label, {}};
    if (by_origin_) {
      sim_.act_as(static_cast<std::uint32_t>(rng_.below(8)));
      p.key = sim_.next_key(when);
      p.id = sim_.at_keyed(when, p.key, 0, [this, label] { handle(label); });
    } else {
      p.id = sim_.at(when, [this, label] { handle(label); });
    }
    pending_.push_back(p);
  }
  void schedule() { schedule_at(to_ns(sim_.now()) + delay_ns()); }

  void handle(std::uint32_t label) {
    ++executed_;
    const auto least =
        std::min_element(pending_.begin(), pending_.end(),
                         [this](const Pending& a, const Pending& b) { return less(a, b); });
    if (least == pending_.end() || least->label != label) ++mismatches_;
    if (least != pending_.end()) {
      ties_ += std::count_if(pending_.begin(), pending_.end(),
                             [&](const Pending& p) { return p.time_ns == least->time_ns; }) > 1;
      *least = pending_.back();
      pending_.pop_back();
    }
    if (executed_ >= target_) {
      sim_.stop();
      return;
    }
    // Keep about 400 pending: one or two successors, sometimes a burst at one time or a scatter
    // of nearby times first; cancels trim the rest.
    const std::uint64_t what = rng_.below(100);
    const std::int64_t now_ns = to_ns(sim_.now());
    if (what < 3) {
      const std::int64_t at = now_ns + static_cast<std::int64_t>(rng_.below(2000));
      for (int i = 0; i < 150; ++i)
        schedule_at(at);
    } else if (what < 6) {
      for (int i = 0; i < 150; ++i)
        schedule_at(now_ns + static_cast<std::int64_t>(rng_.below(5000)));
    }
    schedule();  // after a burst too: maybe for this very instant
    if (what >= 50) schedule();
    while (pending_.size() > 400) {
      const std::size_t victim = rng_.below(pending_.size());
      if (sim_.cancel(pending_[victim].id)) {
        pending_[victim] = pending_.back();
        pending_.pop_back();
      }
    }
  }

  bool by_origin_;
  Simulator sim_;
  RandomStream rng_;
  std::vector<Pending> pending_;
  std::uint64_t next_sequence_ = 0;
  std::uint32_t next_label_ = 0, executed_ = 0, target_ = 0, mismatches_ = 0, ties_ = 0;
};

}  // namespace

TEST_CASE("the queue runs the least pending event at every step, in scheduling order", "[sim]") {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    Model m(false, seed);
    m.run(60000);
    CHECK(m.executed() == 60000);
    CHECK(m.mismatches() == 0);
    CHECK(m.ties() > 1000);
  }
}

TEST_CASE("the queue runs the least pending event at every step, in the origin order", "[sim]") {
  for (std::uint64_t seed : {4u, 5u}) {
    Model m(true, seed);
    m.run(60000);
    CHECK(m.executed() == 60000);
    CHECK(m.mismatches() == 0);
    CHECK(m.ties() > 1000);
  }
}
