// What the tiles of a run over MPI ranks send each other (scenarios/run/tile_bytes.hpp): frames of
// every built-in message type and a tile's end (ledger, counts, streams) read back as written;
// a protocol's own message type and short bytes are refused with the reason.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include "scenarios/run/tile_bytes.hpp"

using namespace masnet;
using namespace masnet::scenarios;
using net::Vec2;

namespace {

std::vector<net::FrameRecord> read_all(std::span<const std::byte> bytes) {
  std::vector<net::FrameRecord> frames;
  net::FrameRecord record;
  for (FrameReader reader(bytes); reader.next(record);)
    frames.push_back(record);
  return frames;
}

net::FrameRecord frame(std::uint64_t number, net::Payload payload) {
  net::FrameRecord f;
  f.sent_at = sim::time_at(0.25 + static_cast<double>(number));
  f.arrival = f.sent_at + sim::seconds(0.001);
  f.key = sim::EventKey{3, static_cast<std::uint32_t>(number), 7};
  f.source = sim::node_id(static_cast<std::uint32_t>(number));
  f.destination = number % 2 ? sim::node_id(99) : sim::kNoNode;
  f.range = 12.5 + static_cast<double>(number);
  f.destination_distance = number % 2 ? 3.25 : -1.0;
  f.frame_number = 1000 + number;
  f.type_index = static_cast<std::uint32_t>(payload.index());
  f.bytes = 40 + static_cast<std::uint32_t>(number);
  f.destination_reached = number % 2 == 1;
  for (std::uint32_t h = 0; h < number; ++h) {
    f.mobile_hearers.push_back(sim::node_id(500 + h));
    if (number % 2 == 0) f.mobile_losses.push_back(0.125 * h);  // link faults in force
  }
  f.link_epoch = static_cast<std::uint32_t>(number % 3);
  f.destination_loss = number % 2 ? -1.0 : 0.375;
  f.payload = std::move(payload);
  return f;
}

}  // namespace

TEST_CASE("tile bytes: frames of every built-in message type read back as written",
          "[scenarios][tiles]") {
  const sim::NodeId a = sim::node_id(4), b = sim::node_id(9);
  std::vector<net::FrameRecord> frames = {
      frame(0, net::Beacon{a, Vec2(1.5, -2.0)}),
      frame(1, net::Position{b, Vec2(0.1, 0.2)}),
      frame(2, net::Report{a, 0.123456789012345, Vec2(3, 4)}),
      frame(3, net::Discover{b, 17.75, Vec2(-5, 6)}),
      frame(4, net::Neighbor{a, Vec2(7, 8)}),
      frame(5, net::Sense{b, 42, {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, 0.75)}}),
      frame(6, net::Reading{a, 43, 1e-300, Vec2(9, 10)})};
  frames[3].arrival = sim::time_at(0.1);  // the earliest, not the first
  std::vector<std::byte> bytes;
  append_frames(bytes, frames);
  const std::vector<net::FrameRecord> back = read_all(bytes);
  REQUIRE(back.size() == frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    INFO("frame " << k);
    const net::FrameRecord &f = frames[k], &g = back[k];
    CHECK(g.sent_at == f.sent_at);
    CHECK(g.arrival == f.arrival);
    CHECK(g.key == f.key);
    CHECK(g.source == f.source);
    CHECK(g.destination == f.destination);
    CHECK(g.range == f.range);
    CHECK(g.destination_distance == f.destination_distance);
    CHECK(g.frame_number == f.frame_number);
    CHECK(g.type_index == f.type_index);
    CHECK(g.bytes == f.bytes);
    CHECK(g.destination_reached == f.destination_reached);
    CHECK(g.mobile_hearers == f.mobile_hearers);
    CHECK(g.mobile_losses == f.mobile_losses);
    CHECK(g.link_epoch == f.link_epoch);
    CHECK(g.destination_loss == f.destination_loss);
    REQUIRE(g.payload.index() == f.payload.index());
  }
  CHECK(std::get<net::Beacon>(back[0].payload).position == Vec2(1.5, -2.0));
  CHECK(std::get<net::Report>(back[2].payload).reading == 0.123456789012345);
  CHECK(std::get<net::Discover>(back[3].payload).radius == 17.75);
  CHECK(std::get<net::Sense>(back[5].payload).cell == std::get<net::Sense>(frames[5].payload).cell);
  const auto& reading = std::get<net::Reading>(back[6].payload);
  CHECK(reading.sensor == a);
  CHECK(reading.update == 43);
  CHECK(reading.reading == 1e-300);
  CHECK(reading.position == Vec2(9, 10));

  // The head names the count and the earliest arrival; none written reads as kTimeMax.
  const FrameReader reader(bytes);
  CHECK(reader.count() == frames.size());
  sim::Time earliest = sim::kTimeMax;
  for (const net::FrameRecord& f : frames)
    earliest = std::min(earliest, f.arrival);
  CHECK(reader.earliest_arrival() == earliest);
  std::vector<std::byte> empty;
  append_frames(empty, {});
  CHECK(FrameReader(empty).count() == 0);
  CHECK(FrameReader(empty).earliest_arrival() == sim::kTimeMax);

  // Cut short: refused, not read past the end.
  bytes.pop_back();
  CHECK_THROWS_WITH(read_all(bytes), "plain records: fewer bytes than records");
}

TEST_CASE("tile bytes: a protocol's own message type cannot cross ranks", "[scenarios][tiles]") {
  net::CustomMessage custom;
  custom.body_bytes = 8;
  custom.body = std::make_shared<int>(5);
  std::vector<std::byte> bytes;
  CHECK_THROWS_WITH(append_frames(bytes, {frame(1, custom)}),
                    "a protocol's own message types cannot cross MPI ranks: run without ranks");
}

TEST_CASE("tile bytes: a tile's end reads back as written", "[scenarios][tiles]") {
  TileEnd end;
  end.counts = {11, 22, 33};
  end.events = 123456;
  end.streams = {{5, sim::Fingerprint::resumed(77)}, {9, sim::Fingerprint{}}};
  end.ledger.first_slot = 10;
  end.ledger.end_slot = 12;
  end.ledger.totals.tx_j.add(2.5);
  end.ledger.totals.heard_by_type[3] = 4;
  end.ledger.totals.counters[1].rx_bytes = 99;
  end.ledger.nodes.resize(2);
  end.ledger.nodes[1].random_key = 6;
  end.ledger.lives.resize(2);
  end.ledger.lives[0].lost_count = 7;
  end.ledger.senders.resize(2);
  end.ledger.senders[0].energy_tx_j = 0.75;
  end.ledger.heard_bytes = {1, 2};
  end.ledger.overheard_count = {3, 4};
  end.ledger.tx.resize(4);
  end.ledger.tx[3].bytes = 8;
  end.ledger.rx_count = {1, 2, 3, 4};
  end.ledger.rx_bytes = {5, 6, 7, 8};
  const net::Radio::TileLedger sent = end.ledger;
  const std::vector<std::byte> bytes = tile_end_bytes(end);
  // Written in one allocation, the ledger's parts freed as they were written.
  CHECK(bytes.capacity() == bytes.size());
  CHECK(end.ledger.nodes.capacity() == 0);
  CHECK(end.ledger.rx_bytes.capacity() == 0);
  TileEnd back = tile_end_from(bytes);
  CHECK(back.counts.readings == 11);
  CHECK(back.counts.point_in_cell_tests == 22);
  CHECK(back.counts.clamped_readings == 33);
  CHECK(back.events == 123456);
  REQUIRE(back.streams.size() == 2);
  CHECK(back.streams[0].origin == 5);
  CHECK(back.streams[0].stream.value() == 77);
  CHECK(back.streams[1].stream.untouched());
  CHECK(back.ledger.first_slot == 10);
  CHECK(back.ledger.end_slot == 12);
  CHECK(back.ledger.totals.tx_j == sent.totals.tx_j);
  CHECK(back.ledger.totals.heard_by_type[3] == 4);
  CHECK(back.ledger.totals.counters[1].rx_bytes == 99);
  REQUIRE(back.ledger.nodes.size() == 2);
  CHECK(back.ledger.nodes[1].random_key == 6);
  REQUIRE(back.ledger.lives.size() == 2);
  CHECK(back.ledger.lives[0].lost_count == 7);
  CHECK(back.ledger.lives[1].lost_count == 0);
  CHECK(back.ledger.senders[0].energy_tx_j == 0.75);
  CHECK(back.ledger.heard_bytes == sent.heard_bytes);
  CHECK(back.ledger.overheard_count == sent.overheard_count);
  CHECK(back.ledger.tx[3].bytes == 8);
  CHECK(back.ledger.rx_count == sent.rx_count);
  CHECK(back.ledger.rx_bytes == sent.rx_bytes);
}
