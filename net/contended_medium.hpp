#pragma once
// The `collision` and `csma` radio levels: frames that overlap in time at a receiver are lost
// (or the stronger one is captured), a node's MAC decides when it may send (queue, random
// backoff, clear-channel assessment, acknowledgements and retries), propagation decides who
// hears what at which power, and the radio's ledger books the energy. A transmission reads like
// a channel's send: begin (energy, hearers, overlaps) → end (outcomes, ACK, delivery).
// See docs/radio-and-energy.md.
#include <array>
#include <cstdint>
#include <deque>
#include <unordered_map>
#include <vector>

#include "net/csma.hpp"
#include "net/messages.hpp"
#include "net/propagation.hpp"
#include "net/vec2.hpp"
#include "sim/random.hpp"
#include "sim/simulator.hpp"

namespace masnet::net {

class Radio;

class ContendedMedium {
 public:
  /// Latency histogram bins: kLatencyBinsPerDecade per decade from kLatencyFloor_s.
  static constexpr int kLatencyBinsPerDecade = 100;
  static constexpr int kLatencyDecades = 10;
  static constexpr double kLatencyFloor_s = 1e-7;

  explicit ContendedMedium(Radio& radio);

  /// Takes a frame from the protocol (range already capped); false if the sender is dead.
  bool send(NodeId source, NodeId destination, double range, Payload&& payload);

  const ContentionCounters& totals(MessageType type) const {
    return totals_[static_cast<std::size_t>(type)];
  }
  /// Nodes with counters so far: node_counters(n) needs n below it.
  std::size_t node_count() const { return macs_.size(); }
  /// Over all message types, as sender.
  const ContentionCounters& node_counters(NodeId node) const {
    return macs_[sim::index(node)].counters;
  }
  /// The q-quantile of the delivery latency of `type` (upper edge of its histogram bin, within
  /// 2.3 %), or 0 without deliveries.
  double latency_quantile_s(MessageType type, double q) const;
  /// Overlap losses so far, all types: a collisions-over-time series samples it.
  std::uint64_t total_collided() const { return total_collided_; }

 private:
  struct Outgoing {
    Frame frame;
    std::uint32_t mac_sequence = 0;
    std::uint32_t retries = 0;
  };
  struct Mac {
    std::deque<Outgoing> queue;  // the head is the frame being sent
    bool busy = false;           // working on the head
    bool awaiting_ack = false;
    std::uint32_t backoffs_this_frame = 0;  // NB
    std::uint32_t backoff_exponent = 0;     // BE
    std::uint32_t next_sequence = 0;
    std::uint64_t attempts = 0;  // keys the per-attempt draws
    sim::EventId ack_timer;
    sim::RandomStream random{0};
    ContentionCounters counters;
  };
  struct Reception {
    NodeId receiver = sim::kNoNode;
    std::uint32_t hot = 0;
    double power_mw = 0.0;
    double interference_mw = 0.0;  // summed over every frame that overlapped it
    sim::Time overlap_from = sim::kTimeMax, overlap_until{};  // the span others overlapped
    bool overlapped = false;             // another frame arrived while this one did
    bool locked_out = false;             // the receiver was busy with another frame or sending
    std::uint32_t in_progress_slot = 0;  // where it is in its receiver's receiving_ list
  };
  struct Transmission {
    Frame frame;
    bool is_ack = false;
    std::uint32_t mac_sequence = 0;
    std::uint64_t attempt = 0;
    Vec2 origin;
    sim::Time start{}, end{};
    std::vector<Reception> receptions;  // by receiver id
  };

  Mac& mac(NodeId node) { return macs_[sim::index(node)]; }
  void start_next(NodeId node);
  void back_off(NodeId node);
  void assess_channel(NodeId node);
  bool channel_busy(NodeId node) const;
  /// Half duplex: the node hears nothing for this long, and loses what it was receiving.
  void go_deaf(NodeId node, sim::Duration for_at_least);
  void begin_transmission(NodeId node, const Frame& frame, bool is_ack, std::uint32_t sequence);
  void end_transmission(std::uint32_t index);
  /// A reception's fate: 0 survived, 1 overlapped, 2 lost to the channel.
  int outcome(const Transmission& tx, const Reception& r) const;
  void delivered(const Transmission& tx, const Reception& r);
  void ack_received(NodeId node, std::uint32_t sequence);
  void ack_timed_out(NodeId node);
  /// The head frame is done (sent, acknowledged or given up): the next one after the IFS.
  void finish_head(NodeId node);
  void drop_head(NodeId node);
  double received_power_mw(const Transmission& tx, NodeId receiver, double distance_m) const;
  void record_latency(MessageType type, double latency_s);
  sim::Duration symbols(std::uint32_t count) const {
    return sim::seconds(count * params_.symbol_s);
  }

  Radio& radio_;
  const CsmaParams& params_;
  const PropagationParams& propagation_;
  bool csma_;
  double noise_mw_;
  double carrier_sense_range_;
  std::vector<Mac> macs_;
  // What every hearer of a frame reads, dense by node id (a MAC's record is far bigger): until
  // when it is deaf (turning around or sending: frames that start meanwhile are lost), the
  // reception its radio is synchronised on (kNotLocked if none), and every reception in
  // progress. A reception is named (transmission << 32 | index in its receptions).
  struct InProgress {
    std::uint64_t reception;
    sim::Time end;
    double power_mw;
  };
  static constexpr std::uint64_t kNotLocked = ~std::uint64_t{0};
  std::vector<sim::Time> deaf_until_;
  std::vector<std::uint64_t> locked_;
  std::vector<std::vector<InProgress>> receiving_;
  Reception& reception(std::uint64_t key) {
    return transmissions_[key >> 32].receptions[key & 0xFFFFFFFFu];
  }
  std::vector<Transmission> transmissions_;
  std::vector<std::uint32_t> free_transmissions_;
  std::vector<std::uint32_t> on_air_;
  std::vector<NodeId> scratch_;
  std::deque<Frame> late_;  // frames waiting for the latency (deque: handlers add while one runs)
  std::vector<std::uint32_t> free_late_;
  // The last MAC sequence number delivered per (receiver, sender): retries after a lost ACK
  // are not handed over twice.
  std::unordered_map<std::uint64_t, std::uint32_t> last_delivered_;
  std::array<ContentionCounters, kMaxMessageTypes> totals_{};
  std::array<std::vector<std::uint64_t>, kMaxMessageTypes> latency_bins_{};
  std::uint64_t total_collided_ = 0;
};

}  // namespace masnet::net
