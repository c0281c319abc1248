#include "net/messages.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

namespace masnet::net {
namespace {

// Names live in fixed slots, so a name_of() view stays valid while later types are added.
struct MessageCatalog {
  std::array<std::string, kMaxMessageTypes> names;
  std::atomic<std::size_t> count{kBuiltinMessageTypeCount};
  MessageCatalog() {
    std::copy(kBuiltinMessageTypeNames.begin(), kBuiltinMessageTypeNames.end(), names.begin());
  }
};

MessageCatalog& catalog() {
  static MessageCatalog instance;
  return instance;
}

bool is_type_name(std::string_view name) {
  if (name.empty() || name.size() > 32) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

}  // namespace

MessageType register_message_type(std::string_view name) {
  MessageCatalog& c = catalog();
  if (!is_type_name(name))
    throw std::invalid_argument("message type name '" + std::string(name) +
                                "': use 1 to 32 upper case letters, digits and '_'");
  const std::size_t count = c.count.load();
  for (std::size_t t = 0; t < count; ++t)
    if (c.names[t] == name)
      throw std::invalid_argument("message type " + std::string(name) + " is already registered");
  if (count == kMaxMessageTypes)
    throw std::length_error("message type " + std::string(name) + ": at most " +
                            std::to_string(kMaxMessageTypes) + " message types");
  c.names[count] = std::string(name);
  c.count.store(count + 1);
  return static_cast<MessageType>(count);
}

std::size_t message_type_count() {
  return catalog().count.load(std::memory_order_relaxed);
}

std::string_view name_of(MessageType type) {
  const auto t = static_cast<std::size_t>(type);
  if (t < kBuiltinMessageTypeCount) return kBuiltinMessageTypeNames[t];
  return t < message_type_count() ? std::string_view(catalog().names[t]) : std::string_view("?");
}

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
    std::uint32_t operator()(const CustomMessage& m) const { return m.body_bytes; }
  };
  return s.header_bytes + std::visit(Sizer{s}, payload);
}

}  // namespace masnet::net
