#include "scenarios/run/contention_outputs.hpp"

#include <cmath>
#include <cstdint>
#include <iterator>
#include <string>

#include <fmt/compile.h>

#include "net/messages.hpp"

namespace masnet::scenarios {
namespace {

using Medium = net::ContendedMedium;

net::MessageType type_at(std::size_t t) {
  return static_cast<net::MessageType>(t);
}

// The upper edge of latency histogram bin `bin`, computed as the medium computes it.
double bin_edge_s(std::size_t bin) {
  return Medium::kLatencyFloor_s *
         std::pow(10.0, static_cast<double>(bin + 1) / Medium::kLatencyBinsPerDecade);
}

// How many deliveries of `type` fell in bins whose upper edge is at most `edge_s`. The m-th
// smallest latency lies in the bin latency_quantile_s((m − ½)/n) names, so a search over m
// reads the histogram through the medium's public quantiles.
std::uint64_t deliveries_up_to(const Medium& medium, net::MessageType type, double edge_s) {
  const std::uint64_t n = medium.totals(type).delivered;
  if (n == 0) return 0;
  const double tolerance_s = edge_s * 1e-9;  // bins are 2.3 % apart
  std::uint64_t low = 0, high = n;           // low: known to be within, high: the most there is
  while (low < high) {
    const std::uint64_t m = high - (high - low) / 2;  // low < m ≤ high
    const double q = (static_cast<double>(m) - 0.5) / static_cast<double>(n);
    if (medium.latency_quantile_s(type, q) <= edge_s + tolerance_s)
      low = m;
    else
      high = m - 1;
  }
  return low;
}

nlohmann::json counters_json(const net::ContentionCounters& c, nlohmann::json p99_s) {
  nlohmann::json mean_s = nullptr;
  if (c.delivered > 0) mean_s = c.latency_sum_s / static_cast<double>(c.delivered);
  if (c.delivered == 0) p99_s = nullptr;
  return {{"transmissions", c.transmissions}, {"delivered", c.delivered}, {"collided", c.collided},
          {"channel_lost", c.channel_lost},   {"dropped", c.dropped},     {"retries", c.retries},
          {"backoffs", c.backoffs},           {"latency_mean_s", mean_s}, {"latency_p99_s", p99_s}};
}

}  // namespace

double latency_quantile_all_types_s(const Medium& medium, double q) {
  std::uint64_t total = 0;
  for (std::size_t t = 0; t < net::message_type_count(); ++t)
    total += medium.totals(type_at(t)).delivered;
  if (total == 0) return 0.0;
  const auto wanted = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total))));
  // The first bin by which `wanted` deliveries of all types together have arrived.
  constexpr std::size_t kBins = Medium::kLatencyBinsPerDecade * Medium::kLatencyDecades + 1;
  std::size_t low = 0, high = kBins - 1;
  while (low < high) {
    const std::size_t bin = low + (high - low) / 2;
    std::uint64_t seen = 0;
    for (std::size_t t = 0; t < net::message_type_count(); ++t)
      seen += deliveries_up_to(medium, type_at(t), bin_edge_s(bin));
    if (seen >= wanted)
      high = bin;
    else
      low = bin + 1;
  }
  return bin_edge_s(low);
}

void add_contention_summary(const Medium& medium, nlohmann::json& messages) {
  net::ContentionCounters all;
  for (std::size_t t = 0; t < net::message_type_count(); ++t) {
    const net::ContentionCounters& c = medium.totals(type_at(t));
    all += c;
    const nlohmann::json keys = counters_json(c, medium.latency_quantile_s(type_at(t), 0.99));
    messages["by_type"][std::string(net::name_of(t))].update(keys);
  }
  messages["total"].update(counters_json(all, latency_quantile_all_types_s(medium, 0.99)));
  // An ACK answers a frame of any type but is booked on the node that sent it, not on a type:
  // the total is the nodes' sum.
  std::uint64_t acks = 0;
  for (std::size_t n = 0; n < medium.node_count(); ++n)
    acks += medium.node_counters(sim::node_id(static_cast<std::uint32_t>(n))).acks;
  messages["total"]["acks"] = acks;
}

void append_contention_node(const Medium& medium, sim::NodeId node, fmt::memory_buffer& row) {
  static const net::ContentionCounters kNone{};
  const net::ContentionCounters& c =
      sim::index(node) < medium.node_count() ? medium.node_counters(node) : kNone;
  fmt::format_to(std::back_inserter(row), FMT_COMPILE(",{},{},{},{},{},{},{},{}"), c.transmissions,
                 c.delivered, c.collided, c.channel_lost, c.dropped, c.retries, c.backoffs, c.acks);
}

}  // namespace masnet::scenarios
