// Unit-disk broadcast through the real net::Radio: n static nodes uniform in the unit square,
// range calibrated for a mean degree, every node broadcasts once per period (random phase)
// for `rounds` rounds. Same layout, phases and range as the ns-3 peer
// (tests/bench/peers/bcast_ns3.cc), so deliveries and checksum must equal the peer's.
//   masnet_bench_broadcast --n=1600 --degree=20 --rounds=100
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_args.hpp"
#include "net/radio.hpp"
#include "sim/random.hpp"

using namespace masnet;
using net::Vec2;

namespace {

struct Counter : net::RadioListener {
  std::vector<std::uint64_t> count, sender_sum;
  void on_frame(sim::NodeId receiver, const net::Frame& frame) override {
    ++count[sim::index(receiver)];
    sender_sum[sim::index(receiver)] += sim::index(frame.source);
  }
};

double mean_degree(const std::vector<Vec2>& pos, double r) {
  std::vector<sim::NodeId> ids;
  for (std::uint32_t i = 0; i < pos.size(); ++i)
    ids.push_back(sim::node_id(i));
  net::SpatialGrid grid;
  grid.build(pos, ids, r);
  std::uint64_t edges = 0;
  for (const Vec2& p : pos)
    grid.for_each_within(p, r, [&](sim::NodeId, const Vec2&, double) { ++edges; });
  return static_cast<double>(edges - pos.size()) / static_cast<double>(pos.size());
}

}  // namespace

int main(int argc, char** argv) {
  bench::Args args{argc, argv};
  const auto n = static_cast<std::uint32_t>(args.number("n", 1600));
  const double degree = args.number("degree", 20);
  const auto rounds = static_cast<std::uint32_t>(args.number("rounds", 100));
  const double side_m = args.number("side", 1000);
  const std::int64_t period_ns = 1'000'000'000;

  // Layout exactly as the peer: xoshiro256** seeded 7, positions then phases.
  sim::RandomStream rng(7);
  std::vector<Vec2> pos(n);
  std::vector<std::int64_t> phase(n);
  for (auto& p : pos) {
    const double x = bench::unit_open_closed(rng.next_u64()) - 1e-12;
    const double y = bench::unit_open_closed(rng.next_u64()) - 1e-12;
    p = Vec2{x, y};
  }
  for (auto& ph : phase)
    ph = static_cast<std::int64_t>(bench::unit_open_closed(rng.next_u64()) *
                                   static_cast<double>(period_ns));
  double r = std::sqrt(degree / (M_PI * (n - 1)));
  for (int it = 0; it < 4; ++it) {
    const double m = mean_degree(pos, r);
    if (m <= 0 || std::fabs(m - degree) < 0.05) break;
    r *= std::sqrt(degree / m);
  }

  const double setup_start = bench::wall_seconds();
  sim::Simulator simulator;
  net::RadioParams params;
  params.max_range = 2.0;
  params.meters_per_unit = side_m;
  params.level = net::RadioLevel::ideal;
  net::Radio radio(simulator, params, 1);
  Counter counter;
  counter.count.assign(n, 0);
  counter.sender_sum.assign(n, 0);
  radio.set_listener(&counter);
  for (std::uint32_t i = 0; i < n; ++i)
    radio.add_static_node(sim::node_id(i), pos[i], i);

  struct Sender {
    sim::Simulator* simulator;
    net::Radio* radio;
    double range;
    std::uint32_t rounds;
    std::int64_t period_ns;
    std::uint64_t sent = 0;
    void send(std::uint32_t node, std::uint32_t round) {
      ++sent;
      radio->broadcast(sim::node_id(node), range, net::Beacon{sim::node_id(node), Vec2{0, 0}});
      if (round + 1 < rounds)
        simulator->after(sim::Duration{period_ns}, [this, node, round] { send(node, round + 1); });
    }
  } sender{&simulator, &radio, r, rounds, period_ns};
  for (std::uint32_t i = 0; i < n; ++i)
    simulator.at(sim::kTimeZero + sim::Duration{phase[i]}, [&sender, i] { sender.send(i, 0); });
  const double setup = bench::wall_seconds() - setup_start;

  const double t0 = bench::wall_seconds();
  simulator.run();
  const double sec = bench::wall_seconds() - t0;

  std::uint64_t deliveries = 0, checksum = bench::kFnvBasis;
  for (std::uint32_t i = 0; i < n; ++i) {
    deliveries += counter.count[i];
    checksum = bench::fnv_word(checksum, counter.count[i]);
    checksum = bench::fnv_word(checksum, counter.sender_sum[i]);
  }
  double energy = 0;
  for (std::uint32_t i = 0; i < n; ++i)
    energy += radio.energy_j(sim::node_id(i));
  std::printf(
      "RESULT name=bcast/masnet-radio/n=%u metric=%.0f unit=deliveries/s deliveries=%llu tx=%llu "
      "sec=%.3f mean_degree=%.2f range=%.4f setup_s=%.3f energy_j=%.6f checksum=%016llx\n",
      n, static_cast<double>(deliveries) / sec, static_cast<unsigned long long>(deliveries),
      static_cast<unsigned long long>(sender.sent), sec,
      static_cast<double>(deliveries) / n / rounds, r, setup, energy,
      static_cast<unsigned long long>(checksum));
  return 0;
}
