#pragma once
// The simulated radio as a *medium* (like ARGoS's range-and-bearing medium and ns-3's
// YansWifiChannel): unit-disk reception with a per-transmission range, delay = latency + airtime +
// jitter, Bernoulli loss per reception, per-node counters by message type, and the energy ledger of
// every node. It knows message formats, never protocol logic. See docs/radio-and-energy.md.
#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <thread>
#include <utility>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>  // baseline x86-64
#endif

#include <Eigen/Geometry>

#include "net/csma.hpp"
#include "net/energy.hpp"
#include "net/frame_record.hpp"
#include "net/line_index.hpp"
#include "net/link_faults.hpp"
#include "net/messages.hpp"
#include "net/propagation.hpp"
#include "net/radio_params.hpp"
#include "net/spatial_grid.hpp"
#include "net/tile_totals.hpp"
#include "net/vec2.hpp"
#include "sim/exact_sum.hpp"
#include "sim/simulator.hpp"
#include "sim/zeroed_array.hpp"

namespace masnet::net {

class ContendedMedium;

/// Receives frames and battery news for all nodes of one radio (the world implements it).
class RadioListener {
 public:
  virtual ~RadioListener() = default;
  /// `frame` reached `receiver` (the addressee of a unicast or any hearer of a broadcast).
  virtual void on_frame(NodeId receiver, const Frame& frame) = 0;
  /// `node`'s battery is empty: it will neither send nor receive again.
  virtual void on_battery_empty(NodeId /*node*/) {}
};

/// Where the mobile nodes are now (the world implements it; positions are read at send time).
class MobilePositions {
 public:
  virtual ~MobilePositions() = default;
  virtual Vec2 position(NodeId node) const = 0;
  /// An upper bound on the speed (world units / s) of every mobile node from now until the
  /// world next calls `Radio::raise_speed_bound`.
  virtual double speed_bound() const = 0;
};

/// Per node totals beyond the per-type counters.
struct NodeRadioStats {
  std::uint64_t heard_bytes = 0;        ///< everything that reached it: addressed, overheard, lost
  std::uint64_t overheard_count = 0;    ///< unicasts to others that it heard (and paid for)
  std::uint64_t lost_count = 0;         ///< receptions lost to `loss`
  std::uint64_t unreachable_count = 0;  ///< unicasts whose addressee was out of range
  std::uint64_t refused_count = 0;      ///< sends refused: battery empty
  double energy_tx_j = 0.0, energy_rx_j = 0.0, energy_idle_j = 0.0;
  bool alive = true;
  sim::Time died_at = sim::kTimeMax;
};

class Radio {
 public:
  /// Below this many mobile nodes a linear scan beats maintaining a grid.
  static constexpr std::size_t kMobileScanLimit = 32;
  /// How many receivers of a broadcast ahead delivery prefetches their records.
  static constexpr std::size_t kDeliveryLookahead = 10;
  /// A delivery batch keeps its buffers for reuse up to this many entries.
  static constexpr std::size_t kKeptBatchCapacity = 1u << 14;

  Radio(sim::Simulator& simulator, const RadioParams& params, std::uint64_t seed);
  ~Radio();
  Radio(const Radio&) = delete;
  Radio& operator=(const Radio&) = delete;
  /// Registers node ids densely from 0: a static node at `position`, or a mobile node whose
  /// position `mobile_positions` answers. `random_key` keys this node's loss and jitter draws;
  /// give a key that does not change when other nodes are added (the world: role and index).
  void add_static_node(NodeId id, const Vec2& position, std::uint64_t random_key);
  void add_mobile_node(NodeId id, std::uint64_t random_key);
  void set_listener(RadioListener* listener) { listener_ = listener; }
  void set_mobile_positions(const MobilePositions* positions) { mobile_ = positions; }
  /// Only message types in `mask` (bit = MessageType) are handed to `on_frame` at `node`;
  /// others are still heard and paid for. Saves calls, never changes results.
  void set_interest(NodeId node, std::uint32_t mask);
  /// A mobile node may now move faster than the last bound (world units / s).
  void raise_speed_bound(double speed) {
    if (speed > margin_speed_) margin_speed_ = speed;
  }
  /// A mobile node jumped (no speed bound covers it): rebuild the mobile index on next use.
  void mobile_node_jumped() {
    mobile_index_valid_ = false;
    mobile_cache_valid_ = false;
  }

  /// Broadcasts `payload` with range `range` (world units, capped at max_range). Every
  /// node within range at send time hears it and pays E_rx. Returns false if refused.
  bool broadcast(NodeId source, double range, Payload payload);
  /// Sends `payload` to `destination` with range = their distance now (capped); others
  /// within that range overhear it and pay E_rx.
  bool unicast(NodeId source, NodeId destination, Payload payload);

  Vec2 position(NodeId node) const;
  /// Calls `visit(id)` for every mobile node within `range` of `center` now (ground truth
  /// for recorders and the oracle; not a radio operation).
  template <class Visit>
  void for_each_mobile_within(const Vec2& center, double range, Visit&& visit) {
    for_each_mobile_within(center, range, std::forward<Visit>(visit), sim::kNoNode, sim::kNoNode);
  }
  /// The static nodes' index by rows, up to date (empty unless they lie on rows): the world's
  /// sensing pass reads it instead of indexing the same points again.
  const LineIndex& static_lines();
  std::size_t node_count() const { return nodes_.size(); }
  const RadioParams& params() const { return params_; }
  /// Frames of one type sent and received (as addressee) by `node`.
  TypeCounters counters(NodeId node, MessageType type) const;
  /// Frames `node` has transmitted so far, all types (cheap: no pending receptions are booked).
  std::uint64_t frames_sent(NodeId node) const;
  /// Frames by type over all nodes (tx: transmissions; rx: receptions by addressees).
  /// (With sibling tiles: their static nodes' shares added.)
  TypeCounters totals(MessageType type) const;
  /// Radio energy booked so far over all nodes (idle drain excluded), joules.
  double total_tx_energy_j() const;
  double total_rx_energy_j() const;
  /// Radio energy of the frames of one type (and, under csma, of their acknowledgements):
  /// sending them, and every node hearing them, joules.
  double type_tx_energy_j(MessageType type) const;
  double type_rx_energy_j(MessageType type) const;
  /// Per-node stats, idle energy brought up to now.
  NodeRadioStats stats(NodeId node);
  double energy_j(NodeId node) {
    const NodeRadioStats s = stats(node);
    return s.energy_tx_j + s.energy_rx_j + s.energy_idle_j;
  }
  bool alive(NodeId node) const { return nodes_[sim::index(node)].alive; }

  // ---- Faults and batteries (docs/faults-and-lifetime.md) ------------------------------------
  /// Gives `node` a battery of its own (joules; 0: unlimited), in place of `energy.battery_j`.
  void set_battery(NodeId node, double battery_j);
  /// Nodes may be taken down and brought up (scripted faults): every send, reception and
  /// delivery then asks whether its node is up, as batteries make it do.
  void enable_failures() { failures_ = true; }
  /// Takes `node` down now (it neither sends nor receives); no battery news.
  void take_down(NodeId node);
  /// Brings a node taken down back up now; false (and nothing) if its battery is empty or it
  /// is up.
  bool bring_up(NodeId node);
  /// The partitions and degraded areas in force: the world edits them at the faults' times, and
  /// then says so (a tile keeps each state for the frames of other tiles sent under it).
  LinkFaults& link_faults() { return link_faults_; }
  void link_faults_changed() {
    if (tiled_) link_history_.record(link_faults_);
  }

  /// What contention did, per message type and per sending node (levels collision and csma;
  /// null otherwise).
  const ContendedMedium* contention() const { return contended_.get(); }

  /// Airtime of a frame of `bytes`.
  sim::Duration airtime(std::uint32_t bytes) const;

  /// A hash of the radio's outcomes so far, node by node in id order: its transmissions in its
  /// send order (time, addressee, type, bytes, receptions, losses), its refusals and the frames
  /// that found it dead; then every node's counters, overhearing, energy and death.
  /// The simulator's fingerprint sees only frames handed to a listener; this one also sees
  /// what nobody handled (docs/radio-and-energy.md). The same with or without the second thread.
  sim::Fingerprint traffic_fingerprint();

  // ---- Tiles of a partitioned run (net/radio_tiles.cpp, docs/decisions/0012) -----------------
  /// Makes this radio one tile of a run cut by space: it books and delivers to the static nodes
  /// in slots [first, end) of its index and to the mobile nodes it runs (all, unless told), and
  /// puts each frame of its static senders into `outbox()` for the other tiles. Needs the
  /// origin order, level ideal or airtime, no jitter, batteries or faults.
  void own_static_slots(std::uint32_t first, std::uint32_t end);
  /// Robots in one tile: here (every mobile node, their frames shipped too) or not here (none).
  void home_mobiles(bool here);
  /// Static nodes in slot order (rows of a sensor grid): tiles own contiguous slots.
  const std::vector<NodeId>& static_slots();
  bool owns(NodeId node) const;
  std::vector<FrameRecord>& outbox() { return outbox_; }
  /// Instead of the outbox: each frame for the other tiles handed to `sink` as it is sent, in one
  /// record whose buffers are reused (over ranks the frames become bytes at once).
  void set_outbox_sink(std::function<void(const FrameRecord&)> sink) {
    outbox_sink_ = std::move(sink);
  }
  /// Another tile's frame: books and delivers it to this tile's nodes. Precondition: its
  /// arrival is not before now.
  void inject(const FrameRecord& record);
  /// This tile's static nodes (their ledger, counters and traffic) and its share of the totals
  /// (net/tile_ledger.hpp) — or its slots in [from, to) only, the share with the first — and
  /// taking another tile's over: after every other tile has been absorbed, this radio reads as
  /// the whole run's (and the sibling shares are dropped).
  struct TileLedger;
  TileLedger tile_ledger(std::uint32_t from = 0, std::uint32_t to = 0xFFFFFFFFu);
  void absorb_tile(const TileLedger& tile);
  /// Until then, the totals and energies above add the other tiles' shares, as last handed here
  /// (between windows).
  const TileTotals& tile_totals() const { return static_share_; }
  void set_sibling_shares(std::vector<TileTotals> shares) { sibling_shares_ = std::move(shares); }

 private:
  friend class ContendedMedium;
  static constexpr std::uint32_t kNoHotIndex = 0xFFFFFFFFu;
  // Set in the top bits of traffic words that are not a transmission's (never a time, id pair
  // or sequence number of a real run).
  static constexpr std::uint64_t kRefusedMark = std::uint64_t{0xA5} << 56;
  static constexpr std::uint64_t kUndeliveredMark = std::uint64_t{0x5A} << 56;

  // Cold per-node state: what only failures, batteries, loss and jitter draws and reports read.
  // What every transmission reads and writes of its sender lives apart in dense arrays by node
  // id (`senders_`, `hot_`, `positions_`): a burst of replies from neighbouring sensors walks
  // them in order, several senders to a cache line. The counters touched by every hearer of a
  // frame live in `heard_bytes_` / `overheard_count_`, indexed by a "hot index": static nodes by
  // their slot in the spatial grid (so a range query walks contiguous memory), mobile nodes after.
  struct Node {
    bool alive = true;
    std::uint32_t interest = 0xFFFFFFFFu;
    std::uint64_t random_key = 0;
  };
  // What only losses, failures, batteries and late nodes write: all zero for nearly every node of
  // a large run, so kept in `lives_`, zeroed pages resident only where written.
  struct NodeLife {
    std::uint64_t lost_count, unreachable_count, refused_count;
    sim::Time added_at;      // idle drain runs from here to min(now, died_at); zero: the start
    double earlier_lives_s;  // time up before the last restart
    double battery_j;        // 0: unlimited
    sim::Time died_at;       // read only while the node is down (up: kTimeMax)
    bool operator==(const NodeLife&) const = default;
  };
  struct Sender {
    double energy_tx_j = 0.0;
    std::uint64_t frames_sent = 0;
    sim::Time busy_until{};  // `airtime` level: when its queued frames are all sent
    // What its frames did, in its send order, its refusals, and the frames that found it dead:
    // the node's part of traffic_fingerprint(), kept by node so that where it is booked does
    // not matter (docs/decisions/0012-partitioned-runs.md).
    sim::Fingerprint traffic;
  };
  // A frame in the air. Without jitter it waits inside its delivery batch (below), written
  // and read in order; with jitter each reception is its own event and the frame waits in
  // `jittered_` until the last one.
  // The counts sit in the frame's tail padding (its payload is [[no_unique_address]]): 96 bytes
  // where a frame member and three words took 128. A READING burst of a million sensors streams
  // a million of these records through memory.
  struct Delivery : Frame {
    // count == 1: `first` is the receiver itself (unicasts: no indirection); otherwise the
    // receivers are the batch's `receivers` [first, first + count), in id order.
    std::uint32_t first = 0, count = 0;
  };
  static_assert(sizeof(Delivery) == sizeof(Frame), "delivery counts fit in the frame's padding");
  // Frames are built in place at the end of their batch: value-initialising an element and then
  // assigning it would zero the line (a string store) and read it straight back (the payload's
  // alternative), a store-forwarding stall per frame.
  struct Batch {
    std::vector<Delivery> deliveries;
    std::vector<NodeId> receivers;
    // The kernel's origin order: each frame's own event key (ascending), and the first frame
    // not handed over yet when the batch has been put back to let an event run between frames.
    std::vector<sim::EventKey> keys;
    std::uint32_t next = 0;
  };
  struct Jittered {
    Frame frame;
    std::uint32_t pending = 0;
  };

  sim::Duration compute_airtime(std::uint32_t bytes) const;
  static constexpr std::uint32_t kAirtimeTableBytes = 256;  // frames up to this size: a lookup
  std::array<sim::Duration, kAirtimeTableBytes> airtime_table_{};
  sim::Duration latency_{};
  double crossover_m_ = 0.0;

  void add_node(NodeId id, Node node, bool mobile, const Vec2& position);
  /// Every node within `range` of `center` now but `skip`, in id order (the contended levels).
  void nodes_within(const Vec2& center, double range, NodeId skip, std::vector<NodeId>& out);
  /// A unicast passes its addressee's distance (the range before the max_range cap), so the
  /// reach test need not look the addressee up again.
  bool transmit(NodeId source, NodeId destination, double range, Payload&& payload,
                double destination_distance = -1.0);
  // A transmission as its parts see it: the ledger has booked the sender (transmit), reception
  // finds and books the hearers (hear), delivery hands the frame over (deliver).
  struct Outgoing {
    NodeId source, destination;
    std::size_t source_index, type_index;
    std::uint32_t bytes;
    double range, destination_distance;
    std::uint64_t frame_number;
  };
  struct Heard {
    std::uint64_t hearers = 0, received = 0, lost = 0;
    std::uint64_t static_hearers = 0, static_received = 0;  // of `hearers`, `received`
    bool destination_reached = false;
  };
  /// Every node in range pays for the frame; the receivers that want its type are gathered in
  /// scratch_receivers_ (net/radio_reception.cpp).
  /// `kLinkFaults`: partitions or degraded areas are in force (a separate instantiation, so that
  /// runs without them never test for them per hearer).
  /// `remote`: another tile's frame, whose mobile hearers it names.
  /// `kTiled`: this radio is a tile (its own instantiation, so that runs in one piece never test).
  template <bool kLinkFaults, bool kTiled>
  Heard hear(const Outgoing& out, const FrameRecord* remote = nullptr);
  [[gnu::always_inline]] void book_heard(std::size_t type_index, std::uint32_t bytes,
                                         const Heard& heard) {
    totals_[type_index].rx_count += heard.received;
    totals_[type_index].rx_bytes += heard.received * bytes;
    total_heard_bytes_ += heard.hearers * bytes;
    heard_bytes_by_type_[type_index] += heard.hearers * bytes;
    if (tiled_) [[unlikely]] {  // the tile's own share, for the tile that absorbs it
      static_share_.heard_bytes += heard.static_hearers * bytes;
      static_share_.heard_by_type[type_index] += heard.static_hearers * bytes;
      static_share_.counters[type_index].rx_count += heard.static_received;
      static_share_.counters[type_index].rx_bytes += heard.static_received * bytes;
    }
  }
  /// A partition stands between `from` and `to` / the loss there with degraded areas (out of
  /// line: only runs with link faults in force ask).
  [[gnu::noinline]] bool link_cut(const LinkFaults& faults, const Vec2& from, NodeId to) const;
  [[gnu::noinline]] double link_loss(const LinkFaults& faults, const Vec2& from, NodeId to) const;
  /// Hands the frame to scratch_receivers_ at `arrival` (net/radio_delivery.cpp). Its parts,
  /// not a Frame: it is built in place where it waits (see Batch).
  /// `key`: the delivery's key when made already (tiles).
  void deliver(sim::Time arrival, const Outgoing& out, sim::Time sent_at, Payload&& payload,
               const sim::EventKey* key = nullptr);
  void prepare_index();
  /// Folds the bulk (run-length) bookings into the per-node counters.
  void materialize() const;
  TypeCounters written_counters(std::size_t type, std::size_t node) const;  // as folded so far
  void prepare_mobile_index();
  /// As the public one, but never visits `skip_a` or `skip_b`, and does not ask where they
  /// are (a unicast's sender and addressee: the addressee is a candidate of every query it
  /// answers, at exactly the range).
  /// `skip_b_distance` >= 0: skip_b is a unicast's addressee at that distance from `center`;
  /// the query then scans the mobile nodes near the addressee (see near_addressee).
  template <class Visit>
  void for_each_mobile_within(const Vec2& center, double range, Visit&& visit, NodeId skip_a,
                              NodeId skip_b, double skip_b_distance = -1.0);
  // The mobile index's points (positions as indexed) within `reach` of a unicast addressee, at
  // one instant. A burst of replies to one robot asks the same neighbourhood a hundred times:
  // each reply then scans these few points instead of walking the grid. Any point within r of
  // a sender at distance d from the addressee lies within r + d of the addressee, so the list
  // answers every query with r + d <= reach exactly as the grid would, in the same slot order.
  struct NearAddressee {
    NodeId addressee = sim::kNoNode;
    sim::Time at{};
    std::uint64_t index_generation = 0;
    double reach = -1.0;
    std::vector<double> xs, ys;
    std::vector<NodeId> ids;
  };
  /// The list for a frame to `addressee` from a sender at `extent` − r, or null on the first
  /// frame to it at this instant (the caller walks the grid).
  const NearAddressee* near_addressee(NodeId addressee, double extent);
  /// Positions of the (few) mobile nodes now, asked once per simulated instant: a burst of
  /// replies sent at one instant scans them many times.
  struct MobileCoordinates {
    std::vector<double> xs, ys;  // by mobile index
  };
  const MobileCoordinates& mobile_positions_now();
  /// Some node has a battery.
  bool battery_limited() const { return any_battery_; }
  /// Some node may be down: sends, receptions and deliveries ask.
  bool guarded() const { return any_battery_ || failures_; }
  double consumed_j(NodeId node) const;
  bool afford(NodeId node, double energy_j);
  /// Idle energy as a function of time, not an accumulator: the value never depends on how
  /// often someone looked at it (recorders must not change the model's numbers).
  double idle_j(NodeId node) const;
  void schedule_depletion(NodeId id);
  void kill(NodeId id);
  /// A send refused for an empty battery, into the traffic fingerprint.
  void mix_refusal(NodeId source);
  void hand_over(const Frame& frame, NodeId receiver);
  /// The batch that delivers at `arrival` (see `open_batch_`), scheduled if new.
  Batch& batch_for(sim::Time arrival, const sim::EventKey* key);
  /// The same in the kernel's origin order (out of line: the scheduling order never pays).
  [[gnu::noinline]] Batch& batch_by_origin(sim::Time arrival, bool open, const sim::EventKey* key);
  template <bool kByOrigin>
  void run_batch(std::uint32_t batch);
  static void prefetch_delivery(const Delivery& delivery);
  void deliver_jittered(std::uint32_t frame, NodeId receiver);

  sim::Simulator& simulator_;
  RadioParams params_;
  std::uint64_t seed_;
  RadioListener* listener_ = nullptr;
  const MobilePositions* mobile_ = nullptr;

  std::vector<Node> nodes_;
  sim::ZeroedArray<NodeLife> lives_;            // [node]: grown to every node at the first write
  sim::WrittenSpan lives_written_;              // the nodes life_to_write() was asked for
  std::vector<sim::EventId> depletion_events_;  // [node]: once a battery drains by idling
  const NodeLife& life_of(std::size_t node) const;
  NodeLife& life_to_write(std::size_t node);
  sim::Time died_at(std::size_t node) const {
    return nodes_[node].alive ? sim::kTimeMax : life_of(node).died_at;
  }
  void cancel_depletion(std::size_t node);
  std::vector<Sender> senders_;     // [node]
  std::vector<std::uint32_t> hot_;  // [node]: the hot index, kNoHotIndex until indexed
  std::vector<Vec2> positions_;     // [node]: static nodes' positions; NaN for mobile ones
  struct TxCounter {
    std::uint64_t count = 0, bytes = 0;  // side by side: a transmission touches one cache line
  };
  sim::ZeroedArray<TxCounter> tx_;  // [type][node]; zeroed arrays: unwritten parts cost nothing
  std::array<sim::WrittenSpan, kMaxMessageTypes> tx_written_{};  // [type]: its nodes' span
  std::array<TypeCounters, kMaxMessageTypes> totals_{};
  // Built-in and registered message types when the radio was built: the per-node counters' stride.
  std::size_t type_count_ = message_type_count();
  sim::ExactSum total_tx_j_;  // exact: the same total whatever order the frames are added in
  // Energy by message type: transmit energy, and bytes heard by every hearer (receive energy
  // is linear in them).
  std::array<sim::ExactSum, kMaxMessageTypes> tx_j_by_type_{};
  mutable std::array<std::uint64_t, kMaxMessageTypes> heard_bytes_by_type_{};
  mutable std::uint64_t total_heard_bytes_ = 0;
  // E_rx is linear in bits, so a node's receive energy is E_elec·8·(bytes it heard).
  // `mutable`: bulk bookings are kept as difference arrays over slots and folded in when read.
  mutable sim::ZeroedArray<std::uint64_t> heard_bytes_, overheard_count_;  // [hot]
  mutable sim::ZeroedArray<std::uint64_t> rx_count_, rx_bytes_;            // [type][hot]
  mutable std::array<sim::WrittenSpan, kMaxMessageTypes> rx_written_{};    // [type]: hot span
  // Bulk bookings (sensor grids, no battery): a frame heard by a run of slots [a, c) adds at a
  // and subtracts at c; unsigned wrap-around keeps the folded sums exact.
  // Heard bytes and overheard count packed in one word, so a run end is one write: bytes in the
  // low kHeardBytesBits, the count above. A slot's folded sum decodes exactly while the pending
  // bulk frames number below 2^(64 − kHeardBytesBits) and their bytes below 2^kHeardBytesBits
  // (checked per frame; past that, fold first).
  static constexpr unsigned kHeardBytesBits = 40;
  static constexpr std::uint64_t kOneOverheard = std::uint64_t{1} << kHeardBytesBits;
  mutable sim::ZeroedArray<std::uint64_t> heard_diff_;  // [hot + 1]
  mutable std::uint64_t pending_bulk_frames_ = 0, pending_bulk_bytes_ = 0;
  mutable sim::ZeroedArray<std::uint64_t> rx_count_diff_, rx_bytes_diff_;  // [type][hot + 1]
  mutable bool diffs_pending_ = false;
  mutable std::uint32_t bulk_types_ = 0;  // bit = type: the rx diffs that hold bookings

  // The overhearing of a bulk unicast: its static hearers' runs, the sender and a static
  // addressee booked out again. Done inline, or (params.overhearing_thread) by a second thread:
  // jobs gather in `jobs_filling_` and are handed over a few hundred at a time, the thread books
  // them while this one goes on, and every reader of the difference words or of
  // total_heard_bytes_ waits for it first (drain_overhearing). Only that thread writes
  // heard_diff_ while it runs. Either side waits by spinning a bounded while (none when the
  // process has a single processor), then sleeping on the other's counter
  // (docs/decisions/0008-overhearing-thread.md).
  struct OverhearingJob {
    double cx = 0.0, cy = 0.0, range = 0.0;
    std::uint64_t booking = 0;  // packed heard bytes + one overheard frame
    std::uint32_t source_hot = 0, destination_hot = 0;
    std::uint32_t type = 0;  // its message type, for the heard bytes by type
  };
  /// Books `job`; returns its static hearers.
  template <bool kTiled>
  std::uint64_t book_overhearing(const OverhearingJob& job) const;
  void start_overhearing_thread();
  /// Returns once the thread has booked all but `behind` of the hand-overs published.
  void wait_until_worker_behind_at_most(std::uint32_t behind) const;
  /// Hands the gathered jobs to the thread (waiting until it is done with the last ones).
  void hand_over_jobs() const;
  void overhearing_worker();
  static void pause_briefly() {
#if defined(__SSE2__)
    _mm_pause();
#endif
  }
  /// Hands over what is gathered, waits until the thread has booked it, adds its heard bytes.
  void drain_overhearing() const;
  static constexpr std::size_t kJobsPerHandOver = 512;
  /// Hand-overs the thread may be behind before this one waits: when the thread is off its core
  /// for a while (a busy machine, or one processor for both), this one goes on gathering.
  static constexpr std::uint32_t kHandOverSlots = 8;
  /// Pauses either side spins before it sleeps (with two processors or more).
  static constexpr std::uint32_t kSpinLimit = 2000;
  mutable std::vector<OverhearingJob> jobs_filling_;
  mutable std::array<std::vector<OverhearingJob>, kHandOverSlots>
      jobs_handed_;  // [hand-over % slots]
  // Hand-overs published by this thread and booked by the other (counts that wrap): slots
  // [booked, published) are the other thread's. Each side sleeps on the other's counter.
  alignas(64) mutable std::atomic<std::uint32_t> jobs_published_{0};
  alignas(64) mutable std::atomic<std::uint32_t> jobs_booked_{0};
  std::atomic<bool> stop_worker_{false};
  mutable std::uint64_t worker_heard_bytes_ = 0;  // the thread's, until drained
  mutable std::array<std::uint64_t, kMaxMessageTypes> worker_heard_by_type_{};
  std::uint32_t spin_limit_ = 0;
  std::thread overhearing_thread_;

  std::vector<NodeId> static_ids_, mobile_ids_;
  SpatialGrid static_grid_, mobile_grid_;
  LineIndex line_index_;  // used instead of static_grid_ when the static nodes lie on rows
  bool use_lines_ = false;
  std::uint32_t static_interest_ = 0;         // union of the static nodes' interest masks
  std::uint32_t static_interest_common_ = 0;  // their intersection: types every static node wants
  std::vector<std::uint32_t> interest_;       // [hot]: read for every receiver of a broadcast
  bool index_dirty_ = true;
  sim::Time mobile_index_time_{};
  bool mobile_index_valid_ = false;
  std::uint64_t mobile_index_generation_ = 0;  // counts rebuilds
  NearAddressee near_;
  double margin_speed_ = 0.0;       // speed bound since the mobile index was built
  MobileCoordinates mobile_cache_;  // at mobile_cache_time_
  sim::Time mobile_cache_time_{};
  bool mobile_cache_valid_ = false;

  // Delivery batches: a frame due at the same time as the last one scheduled, with no other
  // event scheduled in between, joins that event instead of getting its own. Separate events
  // would have run back to back in the same order, so nothing observable changes but the
  // event count: a burst of replies to one SENSE is one event, its frames side by side in
  // memory (written in order at send time, read in order at delivery: no scattered records).
  std::vector<Batch> batches_;
  std::vector<std::uint32_t> free_batches_;
  std::uint32_t open_batch_ = 0xFFFFFFFFu;
  sim::Time open_batch_time_{};
  std::uint64_t open_batch_sequence_ = 0;
  std::deque<Jittered> jittered_;  // deque: a frame stays put while handlers send new ones
  std::vector<std::uint32_t> free_jittered_;
  std::vector<NodeId> scratch_receivers_;
  std::unique_ptr<ContendedMedium> contended_;  // levels collision and csma
  bool any_battery_ = false, failures_ = false;
  LinkFaults link_faults_;
  // A tile: its static slots, its frames for the others, its share of the totals (the tile
  // absorbing it adds them); whether it runs the mobile nodes, and alone (then it ships theirs).
  bool tiled_ = false, mobiles_here_ = true, ships_mobiles_ = false;
  std::uint32_t owned_first_ = 0, owned_end_ = 0xFFFFFFFFu;
  bool owned_slot(std::uint32_t hot) const {
    return hot >= owned_first_ && hot < owned_end_;
  }
  double band_y_min_ = 0.0, band_y_max_ = 0.0;  // its static nodes' extent in y
  bool reaches_band(const Vec2& center, double range) const;
  // The other tiles' static nodes' extents (slots before its own, and after): a frame that
  // reaches neither and no mobile node another tile runs is no other tile's business.
  std::array<Eigen::AlignedBox2d, 2> others_extents_;
  bool needed_by_other_tiles(const Vec2& center, NodeId to, double range, bool reached) const;
  std::vector<FrameRecord> outbox_;
  std::function<void(const FrameRecord&)> outbox_sink_;
  FrameRecord outgoing_;  // the record handed to the sink
  std::vector<NodeId> record_mobiles_;
  std::vector<double> record_losses_;  // with link faults: each recorded hearer's loss then
  double record_destination_loss_ = 0.0;
  LinkFaultHistory link_history_;
  TileTotals static_share_;
  std::vector<TileTotals> sibling_shares_;
};

template <class Visit>
void Radio::for_each_mobile_within(const Vec2& center, double range, Visit&& visit, NodeId skip_a,
                                   NodeId skip_b, double skip_b_distance) {
  if (mobile_ids_.empty()) return;
  const double r2 = range * range;
  if (mobile_ids_.size() <= kMobileScanLimit) {
    // The distance tests first (disk_mask), then the few robots in range, in index order.
    static_assert(kMobileScanLimit <= 64);
    const MobileCoordinates& now = mobile_positions_now();
    std::uint64_t in_range =
        disk_mask(now.xs.data(), now.ys.data(), mobile_ids_.size(), center.x(), center.y(), r2);
    for (; in_range != 0; in_range &= in_range - 1) {
      const NodeId id = mobile_ids_[static_cast<std::size_t>(std::countr_zero(in_range))];
      if (id != skip_a && id != skip_b) visit(id);
    }
    return;
  }
  // The index may be stale: widen the search by how far any node can have moved since it
  // was built, then check each candidate at its true position now.
  prepare_mobile_index();
  const double margin = margin_speed_ * sim::to_seconds(simulator_.now() - mobile_index_time_);
  auto consider = [&](NodeId id) {
    if (id != skip_a && id != skip_b && (mobile_->position(id) - center).squaredNorm() <= r2)
      visit(id);
  };
  const double radius = range + margin;
  if (skip_b_distance >= 0.0) {
    if (const NearAddressee* near = near_addressee(skip_b, radius + skip_b_distance)) {
      // The grid's own test on the indexed positions, over the addressee's neighbourhood: up to
      // 64 points at a time (disk_mask), then the few inside, in list order.
      const double cx = center.x(), cy = center.y(), radius2 = radius * radius;
      const double* const xs = near->xs.data();
      const double* const ys = near->ys.data();
      const NodeId* const ids = near->ids.data();
      const std::size_t count = near->ids.size();
      for (std::size_t base = 0; base < count; base += 64) {
        const std::size_t end = std::min(count, base + 64);
        std::uint64_t inside = disk_mask(xs + base, ys + base, end - base, cx, cy, radius2);
        for (; inside != 0; inside &= inside - 1)
          consider(ids[base + static_cast<std::size_t>(std::countr_zero(inside))]);
      }
      return;
    }
  }
  mobile_grid_.for_each_within(center, radius,
                               [&](NodeId id, const Vec2&, double) { consider(id); });
}

}  // namespace masnet::net
