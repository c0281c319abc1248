#include "scenarios/run/run_tiles.hpp"

#include <algorithm>

#include "scenarios/run/tile_bytes.hpp"
#include "sim/buffer_capacity.hpp"
#include "sim/plain_bytes.hpp"

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
  // Faults strike every tile alike (each applies them to every node and link), as do the
  // diffusion field, the dispensers, robot groups and the world's own events: each tile runs them
  // whole. A frame that crosses tiles carries the link faults' state and its mobile hearers'
  // verdicts from when it was sent.
  if (w.sensors.size() < tiles) return "more tiles than sensors";

  return {};
}

bool robots_in_first_tile(const agents::WorldDef& def) {
  return sim::seconds(def.actuation_delay_s) >= sim::seconds(def.radio.latency_s) &&
         !def.dispenser.enabled && !def.formation.enabled() &&
         protocols::ground_truth_factory(def.protocol.kind) == nullptr;
}

std::uint32_t RunTiles::band_start(std::uint64_t slots, std::size_t k, std::size_t tiles,
                                   bool robots_in_first) {
  // Bands in the radio's slot order (rows of a sensor grid), of equal sensor count — or, when
  // the first tile runs every robot, with a smaller first band for the robots' work.
  const std::uint64_t first_weight = robots_in_first ? kFirstBandWeight : kBandWeight;
  const std::uint64_t total = first_weight + (tiles - 1) * kBandWeight;
  if (k == 0) return 0;
  if (k == tiles) return static_cast<std::uint32_t>(slots);
  return static_cast<std::uint32_t>(slots * (first_weight + (k - 1) * kBandWeight) / total);
}

void RunTiles::own_band(agents::World& world, std::size_t k, std::size_t tiles,
                        bool robots_in_first) {
  const auto slots = static_cast<std::uint64_t>(world.radio().static_slots().size());
  world.own_sensor_slots(band_start(slots, k, tiles, robots_in_first),
                         band_start(slots, k + 1, tiles, robots_in_first));
  if (robots_in_first) world.home_robots(k == 0);
}

RunTiles::TileWorld RunTiles::make_tile(const agents::WorldDef& def, std::size_t k,
                                        std::size_t tiles, bool robots_in_first) {
  TileWorld tile;
  tile.simulator = std::make_unique<sim::Simulator>();
  tile.simulator->order_ties_by_origin();
  tile.world = std::make_unique<agents::World>(*tile.simulator, def);
  // Builds the radio's index, the other half of the cost.
  own_band(*tile.world, k, tiles, robots_in_first);
  return tile;
}

RunTiles::Building RunTiles::build_others(const agents::WorldDef& def, unsigned tiles,
                                          unsigned threads) {
  Building building;
  const unsigned workers = std::min(tiles, threads) - 1;  // the caller builds tile 0
  const bool robots_in_first = robots_in_first_tile(def);
  for (unsigned w = 0; w < workers; ++w)
    building.push_back(std::async(std::launch::async, [&def, tiles, workers, w, robots_in_first] {
      std::vector<std::pair<std::size_t, TileWorld>> built;
      for (std::size_t k = 1 + w; k < tiles; k += workers)
        built.emplace_back(k, make_tile(def, k, tiles, robots_in_first));
      return built;
    }));
  return building;
}

RunTiles::RunTiles(sim::Simulator& simulator, agents::World& world, const agents::WorldDef& def,
                   unsigned tiles, unsigned threads, TileLink* link, Building building)
    : link_(link),
      tiles_(tiles),
      first_tile_(link ? link->rank() : 0),
      lookahead_(sim::seconds(def.radio.latency_s)),
      robots_in_first_(tiles > 1 && robots_in_first_tile(def)),
      threads_(link ? 1 : std::clamp(threads, 1u, tiles)) {
  MASNET_ASSERT(!link || (link->size() == tiles && link->rank() < tiles), "one tile per rank");
  MASNET_ASSERT(!link || building.empty(), "over ranks each process builds its own tile");
  simulators_.push_back(&simulator);
  worlds_.push_back(&world);
  own_band(world, first_tile_, tiles, robots_in_first_);
  if (!link) {
    others_.resize(tiles - 1);
    for (auto& worker : building)
      for (auto& [k, tile] : worker.get())
        others_[k - 1] = std::move(tile);
    for (std::size_t k = 1; k < tiles; ++k) {
      if (!others_[k - 1].world) others_[k - 1] = make_tile(def, k, tiles, robots_in_first_);
      simulators_.push_back(others_[k - 1].simulator.get());
      worlds_.push_back(others_[k - 1].world.get());
    }
  }
  published_.resize(tiles_);
  if (link_) {
    rank_outbox_.resize(tiles_);
    frame_writer_.emplace(frame_bytes_);
    world.radio().set_outbox_sink([this](const net::FrameRecord& f) { frame_writer_->add(f); });
  }
}

RunTiles::~RunTiles() {
  if (link_) worlds_[0]->radio().set_outbox_sink({});
}

void RunTiles::start() {
  for (std::size_t part = 1; part < worlds_.size(); ++part)
    worlds_[part]->start();
  windowed_ = std::make_unique<sim::WindowedRun>(simulators_, lookahead_, threads_);
  windowed_->set_prepare([this](std::size_t part) { take_in(part); });
}

void RunTiles::run_until(sim::Time limit) {
  // A window must not start after a published frame's arrival: it counts as pending.
  windowed_->run_until(
      limit, [this](sim::Time) { exchange(); },
      [this](sim::Time earliest_here) {
        const sim::Time earliest = std::min(earliest_here, published_earliest_);
        return link_ ? link_->earliest(earliest) : earliest;
      });
  take_in_all();
  share_totals();
}

void RunTiles::publish_courses() {
  // The courses the robots chose in this window, for the other tiles' ghosts of them: each
  // starts at least one window later (robots_in_first_tile).
  published_courses_.clear();
  if (first_tile_ == 0) std::swap(published_courses_, worlds_[0]->course_outbox());
  if (!link_) return;
  // Over ranks, from the first to every other, before the frames (whose inbox is read later).
  for (std::size_t r = 0; r < tiles_; ++r) {
    rank_outbox_[r].clear();
    if (first_tile_ == 0 && r != 0)
      sim::append_records(rank_outbox_[r], published_courses_.data(), published_courses_.size());
  }
  const std::vector<std::vector<std::byte>>& inbox = link_->exchange(rank_outbox_);
  if (first_tile_ != 0) published_courses_ = sim::records_from<agents::World::Course>(inbox[0]);
  for (std::vector<std::byte>& sent : rank_outbox_)
    sent.clear();
}

void RunTiles::exchange() {
  if (robots_in_first_) publish_courses();
  // Every tile has taken in what was published before this window: publish this window's.
  // The buffers keep their capacity (a window's frames are megabytes on large networks, and
  // fresh ones would be fresh pages) unless a burst left them far larger than a window needs.
  for (std::size_t part = 0; part < worlds_.size(); ++part) {
    std::vector<net::FrameRecord>& mine = published_[first_tile_ + part];
    mine.clear();
    std::swap(mine, worlds_[part]->radio().outbox());
    sim::shrink_if_oversized(mine);  // the radio gets this vector back at the next window
  }
  if (link_) {
    // This rank's frames to every other rank, written once and copied for the rest; theirs in.
    // Its radio wrote them as it sent them (a burst's records would be a hundred megabytes).
    const std::size_t first_other = first_tile_ == 0 ? 1 : 0;
    frame_writer_->finish();
    sim::shrink_if_oversized(frame_bytes_);
    std::vector<std::byte>& bytes = rank_outbox_[first_other];
    std::swap(bytes, frame_bytes_);
    for (std::size_t r = 0; r < tiles_; ++r) {
      if (r == first_tile_)
        rank_outbox_[r].clear();
      else if (r != first_other)
        rank_outbox_[r].assign(bytes.begin(), bytes.end());
    }
    // The other ranks' frames stay bytes, read one at a time as they are taken in.
    rank_inbox_ = &link_->exchange(rank_outbox_);
    std::swap(bytes, frame_bytes_);  // no one reads the bytes once sent
    frame_bytes_.clear();
    sim::shrink_if_oversized(frame_bytes_, kBurstBytes);
    frame_writer_.emplace(frame_bytes_);
    for (std::vector<std::byte>& sent : rank_outbox_) {
      sent.clear();
      sim::shrink_if_oversized(sent, kBurstBytes);
    }
  }
  published_earliest_ = sim::kTimeMax;
  for (const agents::World::Course& course : published_courses_)
    published_earliest_ = std::min(published_earliest_, course.when);
  for (const std::vector<net::FrameRecord>& frames : published_)
    for (const net::FrameRecord& record : frames)
      published_earliest_ = std::min(published_earliest_, record.arrival);
  if (rank_inbox_ != nullptr)
    for (std::size_t r = 0; r < tiles_; ++r)
      if (r != first_tile_)
        published_earliest_ =
            std::min(published_earliest_, FrameReader((*rank_inbox_)[r]).earliest_arrival());
}

void RunTiles::take_in(std::size_t part) {
  // In tile order, each tile's frames in its send order: the same on any number of threads.
  const std::size_t tile = first_tile_ + part;
  net::Radio& radio = worlds_[part]->radio();
  for (std::size_t from = 0; from < published_.size(); ++from) {
    if (from == tile) continue;
    for (const net::FrameRecord& record : published_[from])
      radio.inject(record);
    if (rank_inbox_ != nullptr)
      for (FrameReader frames((*rank_inbox_)[from]); frames.next(received_);)
        radio.inject(received_);
  }
  rank_inbox_ = nullptr;  // over ranks this process runs one tile: its frames are taken in
  if (tile != 0)
    for (const agents::World::Course& course : published_courses_)
      worlds_[part]->take_course(course);
}

void RunTiles::take_in_all() {
  for (std::size_t part = 0; part < worlds_.size(); ++part)
    take_in(part);
  for (std::vector<net::FrameRecord>& frames : published_)
    frames.clear();
  published_courses_.clear();
  published_earliest_ = sim::kTimeMax;
}

void RunTiles::share_totals() {
  // The recorder samples tile 0 between chunks: its radio's totals add the others' shares.
  std::vector<net::TileTotals> shares;
  if (!link_) {
    for (std::size_t part = 1; part < worlds_.size(); ++part)
      shares.push_back(worlds_[part]->radio().tile_totals());
  } else {
    std::vector<std::byte> mine;
    sim::append_records(mine, &worlds_[0]->radio().tile_totals(), 1);
    for (std::size_t r = 0; r < tiles_; ++r) {
      rank_outbox_[r].clear();
      if (r == 0 && first_tile_ != 0) rank_outbox_[r] = mine;
    }
    const std::vector<std::vector<std::byte>>& inbox = link_->exchange(rank_outbox_);
    for (std::size_t r = 1; r < tiles_ && first_tile_ == 0; ++r)
      shares.push_back(sim::records_from<net::TileTotals>(inbox[r]).at(0));
  }
  worlds_[0]->radio().set_sibling_shares(std::move(shares));
}

void RunTiles::absorb() {
  if (absorbed_) return;
  absorbed_ = true;
  if (link_) {
    absorb_ranks();
    return;
  }
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
    worlds_[0]->absorb_tile(worlds_[k]->tile_counts(), worlds_[k]->radio().tile_ledger());
}

void RunTiles::absorb_ranks() {
  // Every other rank sends the first its tile's end — ledger, counts and its sensors' streams —
  // in rounds of at most kEndSlotsPerRound slots: a whole ledger is hundreds of megabytes on large
  // runs, and the first rank would hold it twice (the bytes and what it reads from them). Every
  // rank knows every band, so all agree on the number of rounds.
  agents::World& world = *worlds_[0];
  std::vector<sim::Fingerprint> streams = simulators_[0]->origin_streams();
  const std::vector<sim::NodeId>& slots = world.radio().static_slots();
  const std::uint64_t slot_count = slots.size();
  std::uint64_t widest_band = 0;
  for (std::size_t k = 0; k < tiles_; ++k)
    widest_band = std::max<std::uint64_t>(widest_band,
                                          band_start(slot_count, k + 1, tiles_, robots_in_first_) -
                                              band_start(slot_count, k, tiles_, robots_in_first_));
  const std::uint64_t rounds =
      std::max<std::uint64_t>(1, (widest_band + kEndSlotsPerRound - 1) / kEndSlotsPerRound);
  const std::uint32_t band_first = band_start(slot_count, first_tile_, tiles_, robots_in_first_);
  for (std::uint64_t round = 0; round < rounds; ++round) {
    for (std::vector<std::byte>& bytes : rank_outbox_)
      std::vector<std::byte>().swap(bytes);
    if (first_tile_ != 0) {
      const std::uint64_t from = band_first + round * kEndSlotsPerRound;
      TileEnd end{round == 0 ? world.tile_counts() : agents::World::TileCounts{},
                  world.radio().tile_ledger(
                      static_cast<std::uint32_t>(std::min(from, slot_count)),
                      static_cast<std::uint32_t>(std::min(from + kEndSlotsPerRound, slot_count))),
                  {},
                  round == 0 ? simulators_[0]->events_run() : 0};
      for (std::uint32_t k = end.ledger.first_slot; k < end.ledger.end_slot; ++k) {
        // Untouched ones too: the first rank's entry for a sensor it does not own is not its own.
        const std::size_t origin = sim::index(slots[k]) + 1;
        end.streams.push_back({static_cast<std::uint32_t>(origin),
                               origin < streams.size() ? streams[origin] : sim::Fingerprint{}});
      }
      rank_outbox_[0] = tile_end_bytes(end);
    }
    const std::vector<std::vector<std::byte>>& inbox = link_->exchange(rank_outbox_);
    if (first_tile_ != 0) continue;
    for (std::size_t r = 1; r < tiles_; ++r) {
      const TileEnd end = tile_end_from(inbox[r]);
      for (const TileEnd::Stream& s : end.streams) {
        if (s.origin >= streams.size()) streams.resize(s.origin + 1);
        streams[s.origin] = s.stream;
      }
      other_ranks_events_ += end.events;
      world.absorb_tile(end.counts, end.ledger);
    }
  }
  std::vector<std::byte>().swap(rank_outbox_[0]);
  if (first_tile_ == 0) fingerprint_ = sim::combine_origin_streams(streams);
}

std::uint64_t RunTiles::events() const {
  std::uint64_t events = other_ranks_events_;
  for (const sim::Simulator* s : simulators_)
    events += s->events_run();
  return events;
}

}  // namespace masnet::scenarios
