// The oracle's per-sensor pass (Google Benchmark): assign every sensor to its robot's exact
// cell and accumulate the density-weighted centroids, for all robots. Reported per sensor.
//   masnet_bench_oracle [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <vector>

#include "agents/world.hpp"
#include "sim/random.hpp"

using namespace masnet;
using net::Vec2;

namespace {

agents::WorldDef layout(int side, int robots, agents::FieldKind field) {
  agents::WorldDef def;
  def.domain = protocols::rectangle(0, 0, 1, 1);
  const double area = 1.0 / (static_cast<double>(side) * side);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i)
      def.sensors.push_back({Vec2{(i + 0.5) / side, (j + 0.5) / side}, area});
  sim::RandomStream rng(1);
  for (int r = 0; r < robots; ++r)
    def.robots.push_back(Vec2{rng.uniform01(), rng.uniform01()});
  def.field.kind = field;
  if (field == agents::FieldKind::acoustic) {
    def.field.targets = {agents::PathDef{Vec2{0.3, 0.3}, Vec2{0, 0}, {}, 0, false},
                         agents::PathDef{Vec2{0.7, 0.6}, Vec2{0, 0}, {}, 0, false}};
    def.field.min_distance = 0.5 / side;
  }
  def.radio.max_range = 0.1;
  return def;
}

// The sensing pass alone, over cells computed beforehand.
void sensing_pass(benchmark::State& state, agents::FieldKind field) {
  const int side = static_cast<int>(state.range(0)), robots = static_cast<int>(state.range(1));
  sim::Simulator simulator;
  agents::World world(simulator, layout(side, robots, field));
  std::vector<protocols::ConvexPolygon> cells;
  for (int r = 0; r < robots; ++r)
    cells.push_back(world.oracle_cell(static_cast<std::size_t>(r)).polygon);
  double sink = 0;
  for (auto _ : state) {
    for (const auto& cell : cells) {
      protocols::CentroidAccumulator acc{protocols::DensityScaling{}};
      world.read_sensors_in(cell, acc);
      sink += acc.mass();
    }
  }
  benchmark::DoNotOptimize(sink);
  // kIsIterationInvariantRate | kInvert: seconds per sensor; shown in ns by the 1e9 factor below.
  state.counters["ns_per_sensor"] = benchmark::Counter(
      static_cast<double>(side) * side / 1e9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Cells and sensing together: what one round of oracle updates of every robot costs.
void full_oracle_round(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0)), robots = static_cast<int>(state.range(1));
  sim::Simulator simulator;
  agents::World world(simulator, layout(side, robots, agents::FieldKind::uniform));
  double sink = 0;
  for (auto _ : state) {
    for (int r = 0; r < robots; ++r) {
      const protocols::RobotCell cell = world.oracle_cell(static_cast<std::size_t>(r));
      protocols::CentroidAccumulator acc{protocols::DensityScaling{}};
      world.read_sensors_in(cell.polygon, acc);
      sink += acc.mass();
    }
  }
  benchmark::DoNotOptimize(sink);
  // kIsIterationInvariantRate | kInvert: seconds per sensor; shown in ns by the 1e9 factor below.
  state.counters["ns_per_sensor"] = benchmark::Counter(
      static_cast<double>(side) * side / 1e9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK_CAPTURE(sensing_pass, uniform, agents::FieldKind::uniform)
    ->Args({100, 100})
    ->Args({316, 1000})
    ->Args({1000, 10000})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sensing_pass, acoustic, agents::FieldKind::acoustic)
    ->Args({1000, 10000})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(full_oracle_round)->Args({100, 100})->Args({1000, 10000})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
