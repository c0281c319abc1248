#pragma once
// A small network on a coarse clock for the partitioned-run tests: nodes exchange messages that
// take at least kLookahead and set themselves timers, often for the same instant, so ties are
// frequent. A Part runs some of the nodes on its own simulator in the origin order and keeps a
// record of every event it ran; messages to nodes of other parts wait in its outbox with their
// keys. Optionally one node is *watched*: every sender reads its state at send time, as the radio
// reads a robot's position — a coupling with no lookahead, which a part can only honour by running
// that node itself (`Watch::everywhere`).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <tuple>
#include <vector>

#include "sim/simulator.hpp"

namespace masnet::test {

using namespace masnet::sim;

// Every event of a node mixes what it receives into the node's state, then sends a message to a
// node of its choice (at least kLookahead later) or sets itself a timer, sometimes for the same
// instant.
constexpr std::int64_t kTick = 1000;
constexpr std::int64_t kLookahead = 5 * kTick;
constexpr std::uint32_t kNodes = 12;

inline std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  h *= 0xBF58476D1CE4E5B9ull;
  return h ^ (h >> 31);
}

struct Executed {
  std::int64_t time_ns;
  EventKey key;
  std::uint32_t node;
  std::uint64_t state;
  friend bool operator==(const Executed&, const Executed&) = default;
};

struct Message {
  std::int64_t time_ns;
  EventKey key;
  std::uint32_t to;
  std::uint64_t value;
};

// The node whose state every message carries (none: kNodes), and whether every part runs it.
struct Watch {
  std::uint32_t node = kNodes;
  bool everywhere = false;
};

// One partition: the nodes [first, last) on their own simulator (and the watched node, when every
// part runs it); messages to other nodes go to the outbox with their keys.
struct Part {
  Simulator sim;
  std::uint32_t first, last;
  Watch watch;
  std::vector<std::uint64_t> state = std::vector<std::uint64_t>(kNodes, 0);
  std::vector<std::uint64_t> draws = std::vector<std::uint64_t>(kNodes, 0);
  std::vector<Executed> log;
  std::vector<Message> outbox;
  int wrong_owner = 0;

  Part(std::uint32_t a, std::uint32_t b, Watch w = {}) : first(a), last(b), watch(w) {
    sim.order_ties_by_origin();
  }
  /// The node's home: the one part whose record of it counts.
  bool holds(std::uint32_t node) const { return node >= first && node < last; }
  /// Run by every part.
  bool everywhere(std::uint32_t node) const { return watch.everywhere && node == watch.node; }
  bool owns(std::uint32_t node) const { return holds(node) || everywhere(node); }
  static std::uint32_t origin(std::uint32_t node) { return node + 1; }

  // Each node schedules its own first events: counted as the world's, they would depend on how
  // many nodes the part sets up.
  void start() {
    for (std::uint32_t n = 0; n < kNodes; ++n) {
      if (!owns(n)) continue;
      sim.act_as(origin(n));
      for (std::int64_t k = 0; k < 3; ++k)
        sim.at(kTimeZero + Duration{k * kTick}, [this, n] { handle(n, n); });
    }
    sim.act_as(0);
  }
  void handle(std::uint32_t node, std::uint64_t value) {
    if (sim.acting_origin() != origin(node)) ++wrong_owner;
    std::uint64_t& s = state[node];
    s = mix(s, value);
    sim.fingerprint_stream().mix(s);  // into this node's stream, as a model digests a payload
    log.push_back(Executed{to_ns(sim.now()), sim.running_key(), node, s});
    // One successor per event (the population stays constant): a message, or a timer of the
    // node's own, often for the same instant.
    const std::uint64_t r = mix(node, ++draws[node]);  // the node's own random stream
    if ((r >> 16) % 3 == 0) {
      const Duration delay{static_cast<std::int64_t>((r >> 20) % 3) * kTick};
      sim.after(delay, [this, node, v = r] { handle(node, v); });
      return;
    }
    const auto to = static_cast<std::uint32_t>(r % kNodes);
    const Time arrival =
        sim.now() + Duration{kLookahead + static_cast<std::int64_t>((r >> 8) % 3) * kTick};
    // What a message carries may depend on the watched node's state now.
    const std::uint64_t carried = watch.node < kNodes ? mix(s, state[watch.node]) : s;
    // Every part that runs the sender uses up its key; the one that holds the addressee (or
    // every part, for a node run everywhere) schedules the message. A node run everywhere sends
    // from every part, so nothing of its goes out; the others ship what other parts need.
    const EventKey key = sim.next_key(arrival);
    if (owns(to))
      sim.at_keyed(arrival, key, origin(to), [this, to, carried] { handle(to, carried); });
    if (!everywhere(node) && (!owns(to) || everywhere(to)))
      outbox.push_back(Message{to_ns(arrival), key, to, carried});
  }
  void receive(const Message& m) {
    sim.at_keyed(kTimeZero + Duration{m.time_ns}, m.key, origin(m.to),
                 [this, to = m.to, v = m.value] { handle(to, v); });
  }
};

inline bool in_total_order(const Executed& a, const Executed& b) {
  return std::tie(a.time_ns, a.key) < std::tie(b.time_ns, b.key);
}

// Hands every message in the parts' outboxes to the other parts that run its addressee.
inline void exchange(const std::vector<Part*>& parts) {
  for (Part* from : parts) {
    for (const Message& m : from->outbox)
      for (Part* to : parts)
        if (to != from && to->owns(m.to)) to->receive(m);
    from->outbox.clear();
  }
}

// The network cut at `cuts` (node boundaries, first 0, last kNodes), each part started.
struct Parts {
  std::vector<std::unique_ptr<Part>> owned;
  std::vector<Part*> all;
  explicit Parts(const std::vector<std::uint32_t>& cuts, Watch watch = {}) {
    for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
      owned.push_back(std::make_unique<Part>(cuts[p], cuts[p + 1], watch));
      all.push_back(owned.back().get());
      all.back()->start();
    }
  }
  // Every part's record of the events of the nodes it holds, merged in the total order (time,
  // key).
  std::vector<Executed> merged_log() const {
    std::vector<Executed> merged;
    for (const Part* p : all)
      for (const Executed& e : p->log)
        if (p->holds(e.node)) merged.push_back(e);
    std::sort(merged.begin(), merged.end(), in_total_order);
    return merged;
  }
  // The run's fingerprint from each node's stream in the part that holds it (the world's, the
  // same in every part, from the first).
  std::uint64_t merged_fingerprint() const {
    std::vector<Fingerprint> streams(kNodes + 1);
    streams[0] = all.front()->sim.origin_streams().at(0);
    for (const Part* p : all) {
      const std::vector<Fingerprint> own = p->sim.origin_streams();
      for (std::uint32_t n = p->first; n < p->last; ++n)
        if (Part::origin(n) < own.size()) streams[Part::origin(n)] = own[Part::origin(n)];
    }
    return combine_origin_streams(streams).value();
  }
};

}  // namespace masnet::test
