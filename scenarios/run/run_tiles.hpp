#pragma once
// One run cut into tiles by space (docs/decisions/0012-partitioned-runs.md): each tile is a
// world of its own — its own simulator, in the origin order — that runs a band of the sensors and
// every robot (or the first tile runs them alone: robots_in_first_tile); the tiles advance together
// in conservative windows of the radio's latency on a pool of threads, and the frames their sensors
// send cross to the other tiles between windows. At the end the other tiles are absorbed into the
// first, whose world then reads as the whole run's: every output and the fingerprint are those of
// the run in one piece. Over MPI ranks (a TileLink), each rank runs one tile and the frames and
// ledgers cross as bytes.
#include <cstddef>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "agents/world.hpp"
#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/tile_bytes.hpp"
#include "sim/fingerprint.hpp"
#include "sim/windowed_run.hpp"

namespace masnet::scenarios {

/// Why `def` cannot run in `tiles` tiles (empty: it can).
std::string tiles_problem(const ScenarioDef& def, unsigned tiles);
/// Whether the tiles of `def` leave every robot to the first tile (the others move ghosts of them
/// by the courses it publishes) rather than each running every robot: when the robots act at
/// least one window after they decide, and nothing but their protocol and the radio reads their
/// decisions (no dispensers, robot groups or oracle's cells).
bool robots_in_first_tile(const agents::WorldDef& def);

/// The processes of a run cut over MPI ranks, one tile each (the `masnet` program makes one over
/// ranks::RankExchange). Both calls are collective: every rank makes them in the same order.
class TileLink {
 public:
  virtual ~TileLink() = default;
  virtual unsigned rank() const = 0;
  virtual unsigned size() const = 0;
  /// The earliest of every rank's `earliest_here`.
  virtual sim::Time earliest(sim::Time earliest_here) = 0;
  /// Sends `outbox[r]` to rank r; returns what each rank sent here, in rank order.
  virtual const std::vector<std::vector<std::byte>>& exchange(
      const std::vector<std::vector<std::byte>>& outbox) = 0;
};

class RunTiles {
 public:
  /// A tile's own simulator and world, its band of sensors given.
  struct TileWorld {
    std::unique_ptr<sim::Simulator> simulator;
    std::unique_ptr<agents::World> world;
  };
  /// The other tiles (1 ...) as they are being built, on up to `threads` − 1 threads: building a
  /// world of a million sensors takes seconds, which the caller spends building tile 0's.
  using Building = std::vector<std::future<std::vector<std::pair<std::size_t, TileWorld>>>>;
  static Building build_others(const agents::WorldDef& def, unsigned tiles, unsigned threads);

  /// Tile 0 is the run's own `simulator` and `world`; takes the others from `building` (or makes
  /// them from `def`) and gives each tile its band of sensors. `threads`: at most one per tile and
  /// per allowed processor.
  /// With a `link`: `tiles` is its size, and this process runs tile `link->rank()` alone, in
  /// `simulator` and `world`; after absorb() the first rank's world reads as the whole run's.
  RunTiles(sim::Simulator& simulator, agents::World& world, const agents::WorldDef& def,
           unsigned tiles, unsigned threads, TileLink* link = nullptr, Building building = {});
  ~RunTiles();
  RunTiles(const RunTiles&) = delete;
  RunTiles& operator=(const RunTiles&) = delete;

  /// Starts the other tiles' worlds (the run starts tile 0's).
  void start();
  /// Advances every tile to `limit`.
  void run_until(sim::Time limit);
  /// Takes the other tiles into tile 0, once, at the end; before that, the fingerprint.
  void absorb();
  /// Each origin's stream from the tile that holds it (after absorb()).
  const sim::Fingerprint& fingerprint() const { return fingerprint_; }
  /// Every tile's kernel events (over ranks: this rank's, and after absorb() on the first rank
  /// every rank's): a cost, like the wall time — a frame that reaches two tiles is delivered by
  /// an event in each.
  std::uint64_t events() const;
  std::uint64_t windows() const { return windowed_ ? windowed_->windows() : 0; }

 private:
  /// Tile k of `tiles`, its band set.
  static TileWorld make_tile(const agents::WorldDef& def, std::size_t k, std::size_t tiles,
                             bool robots_in_first);
  static void own_band(agents::World& world, std::size_t k, std::size_t tiles,
                       bool robots_in_first);
  /// The first of `slots` in band k (k = tiles: the end).
  static std::uint32_t band_start(std::uint64_t slots, std::size_t k, std::size_t tiles,
                                  bool robots_in_first);
  void publish_courses();
  void exchange();
  /// Books and delivers into local tile `part` the frames the other tiles sent in the last window.
  void take_in(std::size_t part);
  /// Takes every published frame in (between chunks: observers see every tile's bookings), and
  /// hands tile 0 the others' shares of the totals.
  void take_in_all();
  void share_totals();
  void absorb_ranks();

  TileLink* link_ = nullptr;
  std::size_t tiles_ = 1, first_tile_ = 0;   // all tiles, and the first one this process runs
  std::vector<sim::Simulator*> simulators_;  // this process's tiles', in tile order
  std::vector<agents::World*> worlds_;
  std::vector<TileWorld> others_;  // tiles 1 ...
  std::unique_ptr<sim::WindowedRun> windowed_;
  // Each tile's frames of the last window, read by every other tile at the start of the next
  // (each on its own thread) while it sends new ones into its radio's outbox.
  std::vector<std::vector<net::FrameRecord>> published_;  // [tile]
  std::vector<std::vector<std::byte>> rank_outbox_;       // [rank], over ranks
  // Over ranks: this tile's frames of this window, written as its radio sends them, and the
  // other ranks' of the last window, as received, until taken in.
  std::vector<std::byte> frame_bytes_;
  std::optional<FrameWriter> frame_writer_;
  const std::vector<std::vector<std::byte>>* rank_inbox_ = nullptr;
  net::FrameRecord received_;  // the one being taken in (its buffers reused)
  static constexpr std::uint64_t kEndSlotsPerRound = 1 << 14;  // a ledger sent in pieces
  // Band sizes: the first band's weight when its tile runs every robot (and the others not).
  static constexpr std::uint64_t kBandWeight = 100, kFirstBandWeight = 25;
  static constexpr std::size_t kBurstBytes = 16 << 20;  // a rank's buffers kept up to this
  std::uint64_t other_ranks_events_ = 0;
  sim::Time published_earliest_ = sim::kTimeMax;  // the earliest arrival among them (or course)
  std::vector<agents::World::Course> published_courses_;  // the first tile's, of the last window
  sim::Duration lookahead_{};
  bool robots_in_first_ = false;
  unsigned threads_ = 1;
  sim::Fingerprint fingerprint_;
  bool absorbed_ = false;
};

}  // namespace masnet::scenarios
