#include "net/messages.hpp"

namespace masnet::net {

std::uint32_t size_bytes(const Payload& payload, const MessageSizes& s) {
  struct Sizer {
    const MessageSizes& s;
    std::uint32_t operator()(const Beacon&) const { return s.id_bytes + s.position_bytes; }
    std::uint32_t operator()(const Position&) const { return s.id_bytes + s.position_bytes; }
    std::uint32_t operator()(const Report&) const {
      return s.id_bytes + s.position_bytes + s.measurement_bytes;
    }
    std::uint32_t operator()(const Discover&) const {
      return s.id_bytes + s.position_bytes + s.radius_bytes;
    }
    std::uint32_t operator()(const Neighbor&) const { return s.id_bytes + s.position_bytes; }
    std::uint32_t operator()(const Sense& m) const {
      return s.id_bytes + s.counter_bytes +
             s.vertex_bytes * static_cast<std::uint32_t>(m.cell.size());
    }
    std::uint32_t operator()(const Reading&) const {
      return s.id_bytes + s.counter_bytes + s.position_bytes + s.measurement_bytes;
    }
  };
  return s.header_bytes + std::visit(Sizer{s}, payload);
}

}  // namespace masnet::net
