#include "scenarios/run/tile_bytes.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "sim/plain_bytes.hpp"

namespace masnet::scenarios {
namespace {

using net::Vec2;

// A frame's fixed part; its mobile hearers and payload follow.
struct FrameHead {
  sim::Time sent_at{}, arrival{};
  sim::EventKey key;
  sim::NodeId source{}, destination{};
  double source_x = 0.0, source_y = 0.0;
  double range = 0.0, destination_distance = 0.0;
  std::uint64_t frame_number = 0;
  std::uint32_t type_index = 0, bytes = 0, hearers = 0, payload_index = 0;
  bool destination_reached = false;
  std::uint32_t link_epoch = 0, losses = 0;  // losses: 0, or one per mobile hearer
  double destination_loss = 0.0;
};

// The frames' head: their count and earliest arrival, written when the writer finishes.
struct FramesHead {
  std::uint64_t count = 0;
  sim::Time earliest_arrival = sim::kTimeMax;
};

// Every field of each built-in message, in one order, for writing and reading alike. A message
// that grows a field must grow here too: the sizes below say so at compile time.
static_assert(sizeof(net::Beacon) == 32 && sizeof(net::Position) == 32 &&
                  sizeof(net::Report) == 32 && sizeof(net::Discover) == 32 &&
                  sizeof(net::Neighbor) == 32 && sizeof(net::Sense) == 32 &&
                  sizeof(net::Reading) == 32,
              "a message's new field must cross ranks too");
template <class A>
void fields(A& a, net::Beacon& m) {
  a(m.sender);
  a(m.position);
}
template <class A>
void fields(A& a, net::Position& m) {
  a(m.robot);
  a(m.position);
}
template <class A>
void fields(A& a, net::Report& m) {
  a(m.sensor);
  a(m.reading);
  a(m.position);
}
template <class A>
void fields(A& a, net::Discover& m) {
  a(m.robot);
  a(m.radius);
  a(m.position);
}
template <class A>
void fields(A& a, net::Neighbor& m) {
  a(m.robot);
  a(m.position);
}
template <class A>
void fields(A& a, net::Sense& m) {
  a(m.robot);
  a(m.update);
  a(m.cell);
}
template <class A>
void fields(A& a, net::Reading& m) {
  a(m.sensor);
  a(m.update);
  a(m.reading);
  a(m.position);
}

struct Writer {
  std::vector<std::byte>& bytes;
  template <class Value>
  void operator()(const Value& value) {
    sim::append_records(bytes, &value, 1);
  }
  void operator()(const Vec2& point) {
    (*this)(point.x());
    (*this)(point.y());
  }
  void operator()(const std::vector<Vec2>& points) {
    (*this)(static_cast<std::uint64_t>(points.size()));
    for (const Vec2& p : points)
      (*this)(p);
  }
};

struct Reader {
  sim::PlainReader& in;
  template <class Value>
  void operator()(Value& value) {
    in.read(&value, 1);
  }
  void operator()(Vec2& point) {
    const auto x = in.read<double>();
    point = Vec2(x, in.read<double>());
  }
  void operator()(std::vector<Vec2>& points) {
    points.resize(in.read<std::uint64_t>());
    for (Vec2& p : points)
      (*this)(p);
  }
};

template <std::size_t... I>
net::Payload read_payload(sim::PlainReader& in, std::uint32_t index, std::index_sequence<I...>) {
  net::Payload payload;
  Reader reader{in};
  const bool known = ((index == I ? (fields(reader, payload.emplace<I>()), true) : false) || ...);
  if (!known) throw std::runtime_error("tile frames: an unknown message type");
  return payload;
}

using Builtin = std::make_index_sequence<net::kBuiltinMessageTypeCount>;

template <class Value>
void append_value(std::vector<std::byte>& bytes, const Value& value) {
  sim::append_records(bytes, &value, 1);
}

}  // namespace

FrameWriter::FrameWriter(std::vector<std::byte>& bytes) : bytes_(&bytes), head_at_(bytes.size()) {
  append_value(bytes, FramesHead{});
}

void FrameWriter::add(const net::FrameRecord& f) {
  const auto index = static_cast<std::uint32_t>(f.payload.index());
  if (index >= net::kBuiltinMessageTypeCount)
    throw std::runtime_error(
        "a protocol's own message types cannot cross MPI ranks: run without ranks");
  ++count_;
  earliest_arrival_ = std::min(earliest_arrival_, f.arrival);
  std::vector<std::byte>& bytes = *bytes_;
  const FrameHead head{f.sent_at,
                       f.arrival,
                       f.key,
                       f.source,
                       f.destination,
                       f.source_position.x(),
                       f.source_position.y(),
                       f.range,
                       f.destination_distance,
                       f.frame_number,
                       f.type_index,
                       f.bytes,
                       static_cast<std::uint32_t>(f.mobile_hearers.size()),
                       index,
                       f.destination_reached,
                       f.link_epoch,
                       static_cast<std::uint32_t>(f.mobile_losses.size()),
                       f.destination_loss};
  append_value(bytes, head);
  sim::append_records(bytes, f.mobile_hearers.data(), f.mobile_hearers.size());
  sim::append_records(bytes, f.mobile_losses.data(), f.mobile_losses.size());
  std::visit(
      [&](const auto& message) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(message)>, net::CustomMessage>) {
          auto copy = message;
          Writer writer{bytes};
          fields(writer, copy);
        }
      },
      f.payload);
}

void FrameWriter::finish() {
  const FramesHead head{count_, earliest_arrival_};
  std::memcpy(bytes_->data() + head_at_, &head, sizeof head);
}

void append_frames(std::vector<std::byte>& bytes, const std::vector<net::FrameRecord>& frames) {
  FrameWriter writer(bytes);
  for (const net::FrameRecord& f : frames)
    writer.add(f);
  writer.finish();
}

FrameReader::FrameReader(std::span<const std::byte> bytes) : in_(bytes) {
  const auto head = in_.read<FramesHead>();
  count_ = head.count;
  earliest_arrival_ = head.earliest_arrival;
}

bool FrameReader::next(net::FrameRecord& f) {
  if (read_ == count_) {
    if (!in_.done()) throw std::runtime_error("tile frames: bytes left over");
    return false;
  }
  ++read_;
  const auto head = in_.read<FrameHead>();
  f.sent_at = head.sent_at;
  f.arrival = head.arrival;
  f.key = head.key;
  f.source = head.source;
  f.destination = head.destination;
  f.source_position = net::Vec2{head.source_x, head.source_y};
  f.range = head.range;
  f.destination_distance = head.destination_distance;
  f.frame_number = head.frame_number;
  f.type_index = head.type_index;
  f.bytes = head.bytes;
  f.destination_reached = head.destination_reached;
  f.link_epoch = head.link_epoch;
  f.destination_loss = head.destination_loss;
  f.mobile_hearers.resize(head.hearers);
  in_.read(f.mobile_hearers.data(), f.mobile_hearers.size());
  f.mobile_losses.resize(head.losses);
  in_.read(f.mobile_losses.data(), f.mobile_losses.size());
  f.payload = read_payload(in_, head.payload_index, Builtin{});
  return true;
}

std::vector<std::byte> tile_end_bytes(TileEnd& end) {
  // A ledger is hundreds of megabytes on large runs: the bytes are sized once (no copies as
  // they grow) and each part of the ledger is freed as soon as it is written, so the ledger and
  // its bytes are never both held whole.
  std::size_t size = sizeof end.counts + sizeof end.events + sizeof(std::uint64_t) +
                     end.streams.size() * sizeof(TileEnd::Stream);
  end.ledger.for_each_part([&](const auto& part) {
    using Part = std::decay_t<decltype(part)>;
    if constexpr (std::is_trivially_copyable_v<Part>)
      size += sizeof part;
    else
      size += sizeof(std::uint64_t) + part.size() * sizeof(typename Part::value_type);
  });
  std::vector<std::byte> bytes;
  bytes.reserve(size);
  append_value(bytes, end.counts);
  append_value(bytes, end.events);
  append_value(bytes, static_cast<std::uint64_t>(end.streams.size()));
  sim::append_records(bytes, end.streams.data(), end.streams.size());
  end.ledger.for_each_part([&](auto& part) {
    using Part = std::decay_t<decltype(part)>;
    if constexpr (std::is_trivially_copyable_v<Part>) {
      append_value(bytes, part);
    } else {
      append_value(bytes, static_cast<std::uint64_t>(part.size()));
      sim::append_records(bytes, part.data(), part.size());
      Part().swap(part);
    }
  });
  MASNET_ASSERT(bytes.size() == size, "a tile's end is written in the size computed for it");
  return bytes;
}

TileEnd tile_end_from(std::span<const std::byte> bytes) {
  sim::PlainReader in(bytes);
  TileEnd end;
  end.counts = in.read<agents::World::TileCounts>();
  end.events = in.read<std::uint64_t>();
  end.streams.resize(in.read<std::uint64_t>());
  in.read(end.streams.data(), end.streams.size());
  end.ledger.for_each_part([&](auto& part) {
    if constexpr (std::is_trivially_copyable_v<std::decay_t<decltype(part)>>) {
      in.read(&part, 1);
    } else {
      part.resize(in.read<std::uint64_t>());
      in.read(part.data(), part.size());
    }
  });
  if (!in.done()) throw std::runtime_error("tile end: bytes left over");
  return end;
}

}  // namespace masnet::scenarios
