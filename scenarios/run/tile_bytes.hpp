#pragma once
// What the tiles of a run cut over MPI ranks send each other (docs/decisions/0012-partitioned-
// runs.md), as bytes: after each window, the frames a tile's sensors sent; at the end, the tile's
// ledger, counts and its sensors' fingerprint streams for the first rank to absorb.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "agents/world.hpp"
#include "net/frame_record.hpp"
#include "net/tile_ledger.hpp"
#include "sim/fingerprint.hpp"

namespace masnet::scenarios {

/// Appends `frames`. Throws std::runtime_error for a frame of a message type a protocol
/// registered (its body is shared memory, which cannot cross ranks).
void append_frames(std::vector<std::byte>& bytes, const std::vector<net::FrameRecord>& frames);
/// Appends the frames `bytes` holds to `frames`.
void read_frames(std::span<const std::byte> bytes, std::vector<net::FrameRecord>& frames);

/// A tile at the end of the run: its sensors' counts, its radio's ledger, the fingerprint
/// streams of the origins it alone holds (its sensors), and the kernel events it ran.
struct TileEnd {
  agents::World::TileCounts counts;
  net::Radio::TileLedger ledger;
  struct Stream {
    std::uint32_t origin = 0;
    sim::Fingerprint stream;
  };
  std::vector<Stream> streams;
  std::uint64_t events = 0;
};
/// The bytes of `end`; empties its ledger's vectors on the way (they are freed as written).
std::vector<std::byte> tile_end_bytes(TileEnd& end);
TileEnd tile_end_from(std::span<const std::byte> bytes);

}  // namespace masnet::scenarios
