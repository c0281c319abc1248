#include "scenarios/run/run_tiles.hpp"

#include <algorithm>

#include "protocols/ground_truth.hpp"
#include "protocols/registry.hpp"

namespace masnet::scenarios {

std::string tiles_problem(const ScenarioDef& def, unsigned tiles) {
  if (tiles == 0) return "expected at least 1 tile";
  if (tiles == 1) return {};
  const agents::WorldDef& w = def.world;
  if (!def.ties_by_origin)
    return "tiles need `tie_order: origin`, the order each tile computes alone "
           "(docs/time-and-ordering.md)";
  if (w.radio.level != net::RadioLevel::ideal && w.radio.level != net::RadioLevel::airtime)
    return "tiles need radio.level ideal or airtime";
  if (w.radio.jitter_s > 0) return "tiles need radio.jitter 0";
  if (!(w.radio.latency_s > 0)) return "tiles need radio.latency above 0 (it is their lookahead)";
  bool batteries = w.radio.energy.battery_j > 0 || w.sensor_battery_j > 0 || w.robot_battery_j > 0;
  for (const agents::SensorDef& s : w.sensors)
    batteries = batteries || s.battery_j > 0;
  if (batteries) return "tiles do not run batteries yet";
  if (!w.faults.empty()) return "tiles do not run faults yet";
  if (w.field.kind == agents::FieldKind::diffusion) return "tiles do not run diffusion yet";
  if (w.dispenser.enabled) return "tiles do not run dispensers yet";
  if (w.formation.enabled()) return "tiles do not run robot groups yet";
  if (w.beacons.senders != agents::BeaconSenders::none) return "tiles do not run beacons yet";
  if (protocols::ground_truth_factory(w.protocol.kind) != nullptr)
    return "tiles do not run a protocol that reads the ground truth";
  if (w.sensors.size() < tiles) return "more tiles than sensors";

  return {};
}

RunTiles::RunTiles(sim::Simulator& simulator, agents::World& world, const agents::WorldDef& def,
                   unsigned tiles, unsigned threads)
    : lookahead_(sim::seconds(def.radio.latency_s)), threads_(std::clamp(threads, 1u, tiles)) {
  simulators_.push_back(&simulator);
  worlds_.push_back(&world);
  for (unsigned k = 1; k < tiles; ++k) {
    Tile tile;
    tile.simulator = std::make_unique<sim::Simulator>();
    tile.simulator->order_ties_by_origin();
    tile.world = std::make_unique<agents::World>(*tile.simulator, def);
    simulators_.push_back(tile.simulator.get());
    worlds_.push_back(tile.world.get());
    others_.push_back(std::move(tile));
  }
  // Bands of equal sensor count in the radio's slot order: rows of a sensor grid.
  const auto slots = static_cast<std::uint64_t>(world.radio().static_slots().size());
  for (unsigned k = 0; k < tiles; ++k)
    worlds_[k]->own_sensor_slots(static_cast<std::uint32_t>(slots * k / tiles),
                                 static_cast<std::uint32_t>(slots * (k + 1) / tiles));
  // The recorder samples tile 0 between windows: its radio's totals add the others' shares.
  std::vector<const net::Radio*> siblings;
  for (std::size_t k = 1; k < worlds_.size(); ++k)
    siblings.push_back(&worlds_[k]->radio());
  world.radio().set_sibling_tiles(std::move(siblings));
}

RunTiles::~RunTiles() = default;

void RunTiles::start() {
  for (std::size_t k = 1; k < worlds_.size(); ++k)
    worlds_[k]->start();
  published_.resize(worlds_.size());
  windowed_ = std::make_unique<sim::WindowedRun>(simulators_, lookahead_, threads_);
  windowed_->set_prepare([this](std::size_t tile) { take_in(tile); });
}

void RunTiles::run_until(sim::Time limit) {
  // A window must not start after a published frame's arrival: it counts as pending.
  windowed_->run_until(
      limit, [this](sim::Time) { exchange(); },
      [this](sim::Time earliest_here) { return std::min(earliest_here, published_earliest_); });
  take_in_all();
}

void RunTiles::exchange() {
  // Every tile has taken in what was published before this window: publish this window's.
  published_earliest_ = sim::kTimeMax;
  for (std::size_t k = 0; k < worlds_.size(); ++k) {
    published_[k].clear();
    std::swap(published_[k], worlds_[k]->radio().outbox());
    for (const net::FrameRecord& record : published_[k])
      published_earliest_ = std::min(published_earliest_, record.arrival);
  }
}

void RunTiles::take_in(std::size_t tile) {
  // In tile order, each tile's frames in its send order: the same on any number of threads.
  net::Radio& radio = worlds_[tile]->radio();
  for (std::size_t from = 0; from < published_.size(); ++from)
    if (from != tile)
      for (const net::FrameRecord& record : published_[from])
        radio.inject(record);
}

void RunTiles::take_in_all() {
  for (std::size_t k = 0; k < worlds_.size(); ++k)
    take_in(k);
  for (std::vector<net::FrameRecord>& frames : published_)
    frames.clear();
  published_earliest_ = sim::kTimeMax;
}

void RunTiles::absorb() {
  if (absorbed_) return;
  absorbed_ = true;
  // Origin 0 is the world, origin n + 1 node n: the world's and the robots' streams are the same
  // in every tile, a sensor's is in the tile that owns it.
  std::vector<std::vector<sim::Fingerprint>> held;
  std::size_t origins = 0;
  for (const sim::Simulator* s : simulators_) {
    held.push_back(s->origin_streams());
    origins = std::max(origins, held.back().size());
  }
  std::vector<sim::Fingerprint> streams(origins);
  for (std::size_t origin = 0; origin < origins; ++origin)
    for (std::size_t k = 0; k < worlds_.size(); ++k)
      if (origin == 0 ||
          worlds_[k]->radio().owns(sim::node_id(static_cast<std::uint32_t>(origin - 1)))) {
        if (origin < held[k].size()) streams[origin] = held[k][origin];
        break;
      }
  fingerprint_ = sim::combine_origin_streams(streams);
  for (std::size_t k = 1; k < worlds_.size(); ++k)
    worlds_[0]->absorb_tile(*worlds_[k]);
}

std::uint64_t RunTiles::events() const {
  std::uint64_t events = 0;
  for (const sim::Simulator* s : simulators_)
    events += s->events_run();
  return events;
}

}  // namespace masnet::scenarios
