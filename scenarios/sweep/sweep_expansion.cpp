// The runs of a sweep: the cartesian product of its axes times its seeds, each named by a
// stable id.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "scenarios/sweep/sweep.hpp"
#include "scenarios/sweep/sweep_parser.hpp"

namespace masnet::scenarios {
namespace sweep_parsing {

std::uint64_t fnv1a64(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  // splitmix64's finaliser: FNV alone leaves ids of neighbouring seeds looking alike.
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  h ^= h >> 31;
  return h;
}

std::string hex16(std::uint64_t h) {
  return fmt::format("{:016x}", h);
}

}  // namespace sweep_parsing

using nlohmann::json;
using sweep_parsing::fnv1a64;
using sweep_parsing::hex16;
using sweep_parsing::value_label;

std::vector<json> sweep_range(double from, double to, double step, int decimals, bool integers) {
  std::vector<json> values;
  if (step == 0.0 || !std::isfinite(step) || (to - from) * step < 0) return values;
  const double span = (to - from) / step;
  if (span > 1e7) return std::vector<json>(100001);  // too many: the caller says so
  // Inclusive of `to` despite rounding: 0 to 0.5 by 0.1 is six values, never five.
  const auto count = static_cast<std::int64_t>(std::floor(span + 1e-9)) + 1;
  const double scale = std::pow(10.0, std::clamp(decimals, 0, 15));
  for (std::int64_t k = 0; k < count; ++k) {
    if (integers) {
      values.emplace_back(std::llround(from) + k * std::llround(step));
    } else {
      const double v = std::round((from + static_cast<double>(k) * step) * scale) / scale;
      values.emplace_back(v == 0.0 ? 0.0 : v);  // no -0
    }
  }
  return values;
}

std::string sweep_run_id(const std::string& base_key, const std::vector<SweepOverride>& overrides,
                         std::uint64_t seed) {
  json effective = json::object();
  for (const auto& o : overrides)
    effective[o.key] = o.value;
  const json canonical = {{"base", base_key}, {"overrides", effective}, {"seed", seed}};
  return hex16(fnv1a64(canonical.dump()));
}

std::vector<RunSpec> expand_sweep(const SweepDef& sweep) {
  std::vector<RunSpec> runs;
  std::vector<std::size_t> points(sweep.axes.size(), 0);
  for (const auto& axis : sweep.axes)
    if (axis.points.empty()) return runs;
  for (;;) {
    std::vector<SweepOverride> overrides = sweep.set;
    json parameters = json::object();
    std::string label;
    for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
      const SweepAxis& axis = sweep.axes[a];
      const AxisPoint& point = axis.points[points[a]];
      if (axis.name == "variant") {
        parameters["variant"] = point.label;
        label += "variant=" + point.label + " ";
      }
      for (const auto& o : point.overrides) {
        overrides.push_back(o);
        parameters[o.key] = o.value;
        if (axis.name != "variant") label += o.key + "=" + value_label(o.value) + " ";
      }
    }
    for (std::uint64_t seed : sweep.seeds) {
      RunSpec r;
      r.index = runs.size();
      r.seed = seed;
      r.points = points;
      r.id = sweep_run_id(sweep.base_key, overrides, seed);
      for (const auto& o : overrides)
        r.overrides.push_back(o.key + "=" + o.value.dump());
      r.parameters = parameters;
      r.label = label + "seed=" + std::to_string(seed);
      runs.push_back(std::move(r));
    }
    // Odometer: the last axis turns fastest.
    std::size_t a = sweep.axes.size();
    while (a > 0) {
      --a;
      if (++points[a] < sweep.axes[a].points.size()) break;
      points[a] = 0;
      if (a == 0) return runs;
    }
    if (sweep.axes.empty()) return runs;
  }
}

}  // namespace masnet::scenarios
