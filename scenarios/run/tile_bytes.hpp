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
#include "sim/plain_bytes.hpp"
#include "sim/time.hpp"

namespace masnet::scenarios {

/// Appends frames to `bytes` one at a time, their count and earliest arrival first (written by
/// finish()): a tile's frames become bytes as they are sent, never held as records. add()
/// throws std::runtime_error for a frame of a message type a protocol registered (its body is
/// shared memory, which cannot cross ranks).
class FrameWriter {
 public:
  explicit FrameWriter(std::vector<std::byte>& bytes);
  void add(const net::FrameRecord& frame);
  void finish();

 private:
  std::vector<std::byte>* bytes_;
  std::size_t head_at_;
  std::uint64_t count_ = 0;
  sim::Time earliest_arrival_ = sim::kTimeMax;
};
/// Appends `frames` with a FrameWriter.
void append_frames(std::vector<std::byte>& bytes, const std::vector<net::FrameRecord>& frames);

/// The frames of bytes a FrameWriter wrote, one at a time into one record whose buffers are
/// reused: a window's frames from another rank (half a million in a burst of the 10⁶ benchmark)
/// are injected as they are read, never held as records all at once. Throws std::runtime_error
/// on bytes cut short or left over.
class FrameReader {
 public:
  explicit FrameReader(std::span<const std::byte> bytes);
  std::uint64_t count() const { return count_; }
  sim::Time earliest_arrival() const { return earliest_arrival_; }  ///< kTimeMax: none
  /// Reads the next frame into `record`; false once every frame has been read.
  bool next(net::FrameRecord& record);

 private:
  sim::PlainReader in_;
  std::uint64_t count_ = 0, read_ = 0;
  sim::Time earliest_arrival_ = sim::kTimeMax;
};

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
