// The radio set up and torn down: parameters and per-frame constants, nodes registered
// (static or mobile) and their interests, the overhearing thread started and stopped. Nothing
// here runs per frame; transmission and delivery are in net/radio.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "net/contended_medium.hpp"
#include "net/radio.hpp"
#include "sim/cpus.hpp"

namespace masnet::net {
namespace {
constexpr double kMobileMark = std::numeric_limits<double>::quiet_NaN();
}  // namespace

Radio::Radio(sim::Simulator& simulator, const RadioParams& params, std::uint64_t seed)
    : simulator_(simulator), params_(params), seed_(seed) {
  MASNET_ASSERT(params.max_range > 0 && params.bitrate_bps > 0 && params.loss >= 0 &&
                    params.loss <= 1 && params.latency_s >= 0 && params.jitter_s >= 0,
                "radio parameters are validated by the scenario loader");
  // Per-frame constants, computed once (each costs a rounding call or a square root).
  crossover_m_ = params_.energy.crossover_m();
  params_.energy.seconds_per_bit = 1.0 / params_.bitrate_bps;
  if (params_.energy.model == EnergyModel::states)
    params_.energy.idle_power_w = params_.energy.voltage_v * params_.energy.idle_current_a;
  latency_ = sim::seconds(params_.latency_s);
  for (std::uint32_t bytes = 0; bytes < kAirtimeTableBytes; ++bytes)
    airtime_table_[bytes] = compute_airtime(bytes);
  any_battery_ = params_.energy.battery_j > 0;
  if (params_.contended()) contended_ = std::make_unique<ContendedMedium>(*this);
}

Radio::~Radio() {
  if (!overhearing_thread_.joinable()) return;
  drain_overhearing();
  stop_worker_.store(true, std::memory_order_release);
  jobs_published_.fetch_add(
      1, std::memory_order_release);  // an empty hand-over wakes it to see the stop
  jobs_published_.notify_one();
  overhearing_thread_.join();
}

void Radio::add_node(NodeId id, Node node, bool mobile, const Vec2& position) {
  MASNET_ASSERT(sim::index(id) == nodes_.size(), "node ids are dense from 0");
  nodes_.push_back(node);
  // A node's life record stays zero (unwritten) when it starts with the run and has no battery.
  if (simulator_.now() != sim::Time{}) life_to_write(sim::index(id)).added_at = simulator_.now();
  if (params_.energy.battery_j != 0.0)
    life_to_write(sim::index(id)).battery_j = params_.energy.battery_j;
  senders_.emplace_back();
  hot_.push_back(kNoHotIndex);  // given by the next prepare_index()
  // A mobile node's entry is NaN: the one array answers both "where" and "static or not".
  positions_.push_back(mobile ? Vec2{kMobileMark, kMobileMark} : position);
  index_dirty_ = true;
  if (battery_limited() && params_.energy.idle_power_w > 0) schedule_depletion(id);
}

void Radio::add_static_node(NodeId id, const Vec2& position, std::uint64_t random_key) {
  MASNET_ASSERT(std::isfinite(position.x()) && std::isfinite(position.y()),
                "static nodes stand somewhere");
  static_ids_.push_back(id);
  Node node;
  node.random_key = random_key;
  add_node(id, node, false, position);
}

void Radio::add_mobile_node(NodeId id, std::uint64_t random_key) {
  mobile_ids_.push_back(id);
  mobile_index_valid_ = false;
  mobile_cache_valid_ = false;
  Node node;
  node.random_key = random_key;
  add_node(id, node, true, Vec2{0, 0});
}

const Radio::NodeLife& Radio::life_of(std::size_t node) const {
  static constexpr NodeLife kNoLife{};
  return lives_written_.covers(node) ? lives_[node] : kNoLife;  // never a page nobody wrote
}

Radio::NodeLife& Radio::life_to_write(std::size_t node) {
  if (node >= lives_.size()) {
    // Rare: once the nodes are all added, then only for nodes added later. Records still zero
    // are not copied, so their pages stay unwritten.
    sim::ZeroedArray<NodeLife> grown(nodes_.size());
    for (std::size_t n = lives_written_.first; n < lives_written_.end; ++n)
      grown.fill_in(n, lives_[n]);
    lives_ = std::move(grown);
  }
  lives_written_.add(node);
  return lives_[node];
}

void Radio::cancel_depletion(std::size_t node) {
  if (node < depletion_events_.size()) simulator_.cancel(depletion_events_[node]);
}

const LineIndex& Radio::static_lines() {
  if (index_dirty_) prepare_index();
  return line_index_;
}

void Radio::nodes_within(const Vec2& center, double range, NodeId skip, std::vector<NodeId>& out) {
  if (index_dirty_) prepare_index();
  out.clear();
  if (use_lines_) {
    const NodeId* const slots = line_index_.ids().data();
    line_index_.for_each_run_within(center, range, [&](std::uint32_t a, std::uint32_t c) {
      for (std::uint32_t k = a; k < c; ++k)
        if (slots[k] != skip) out.push_back(slots[k]);
    });
  } else {
    const NodeId* const slots = static_grid_.ids().data();
    static_grid_.for_each_slot_within(center, range, [&](std::uint32_t k, double) {
      if (slots[k] != skip) out.push_back(slots[k]);
    });
  }
  // Static nodes come in slot order (id order on rows), the few mobile ones after: sort each
  // part only if it needs it, then merge.
  if (!std::is_sorted(out.begin(), out.end())) std::sort(out.begin(), out.end());
  const auto static_end = static_cast<std::ptrdiff_t>(out.size());
  for_each_mobile_within(
      center, range, [&](NodeId id) { out.push_back(id); }, skip, sim::kNoNode);
  std::sort(out.begin() + static_end, out.end());
  std::inplace_merge(out.begin(), out.begin() + static_end, out.end());
}

void Radio::set_interest(NodeId node, std::uint32_t mask) {
  nodes_[sim::index(node)].interest = mask;
  index_dirty_ = true;  // the union of static interests decides which frames may be booked in bulk
}

void Radio::start_overhearing_thread() {
  // Waiting by spinning pays only when the other thread has a processor of its own: with one,
  // every spin takes the time the other needs to make progress (a lone run pinned to one core
  // was 10-17 times slower). With one, both sides go to sleep at once.
  spin_limit_ = sim::allowed_cpu_count() >= 2 ? kSpinLimit : 0;
  overhearing_thread_ = std::thread([this] { overhearing_worker(); });
}

}  // namespace masnet::net
