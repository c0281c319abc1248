// What a valid-looking scenario implies: the periodic work of a run (a period of 1e-300 s would
// never end) and the largest density the field can reach (1e308 would overflow to inf and NaN
// in the centroids). Limits in docs/scenario-reference.md, "Limits".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scenarios/loader/scenario_parts.hpp"

namespace masnet::scenarios {
namespace {

std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

// One periodic activity: its count over the run and the key that sets its period.
struct Work {
  std::string what;
  double count;
  Section* section;
  const char* key;
};

// The smallest positive step of the diffusion solver: dt, or physical mode's substep.
double diffusion_step_s(const agents::DiffusionParams& p) {
  if (p.mode != agents::DiffusionMode::physical || p.kappa <= 0.0) return p.dt_s;
  const int cells_y = p.cells_y > 0 ? p.cells_y : p.cells;
  const double hx = (p.x1 - p.x0) / p.cells, hy = (p.y1 - p.y0) / cells_y;
  const double stable = 1.0 / (2.0 * p.kappa * (1.0 / (hx * hx) + 1.0 / (hy * hy)));
  return std::min(p.dt_s, stable);
}

void check_work(const ScenarioDef& def, std::size_t sensor_count, const NodeCaps& caps,
                LimitSections& at) {
  const double duration = def.duration_s;
  const auto robots = static_cast<double>(def.world.robots.size());
  const auto sensors = static_cast<double>(sensor_count);
  std::vector<Work> work;
  // A protocol that updates periodically declares `period` (the built-ins but `none` do).
  if (def.world.protocol.params.has("period"))
    work.push_back({"protocol updates",
                    duration / def.world.protocol.params.real("period") * robots, &at.protocol,
                    "period"});
  using agents::BeaconSenders;
  const BeaconSenders senders = def.world.beacons.senders;
  if (senders != BeaconSenders::none) {
    const double count = senders == BeaconSenders::robots    ? robots
                         : senders == BeaconSenders::sensors ? sensors
                                                             : robots + sensors;
    work.push_back(
        {"beacons", duration / def.world.beacons.period_s * count, &at.beacons, "period"});
  }
  const agents::MotionParams& motion = def.world.motion;
  if (motion.max_speed > 0.0 && !motion.jump_to_target)
    work.push_back(
        {"motion substeps", duration / motion.substep_s * robots, &at.robots, "substep"});
  work.push_back({"trajectory rows", duration / def.output.trajectory_period_s * robots, &at.output,
                  "trajectory_period"});
  if (def.output.replay)
    work.push_back({"replay frames", duration / def.output.replay_period_s * (robots + 1),
                    &at.output, "replay_period"});
  const agents::FieldDef& field = def.world.field;
  Section diffusion = at.field.peek("diffusion");
  if (field.kind == agents::FieldKind::diffusion) {
    const agents::DiffusionParams& p = field.diffusion;
    const double nodes = (p.cells + 1.0) * ((p.cells_y > 0 ? p.cells_y : p.cells) + 1.0);
    const double steps = std::ceil(duration / p.dt_s) * std::ceil(p.dt_s / diffusion_step_s(p));
    work.push_back({"diffusion node updates", steps * nodes, &diffusion, "dt"});
  }
  double total = 0.0;
  const Work* largest = nullptr;
  std::string parts;
  for (const Work& w : work) {
    total += w.count;
    if (!largest || w.count > largest->count) largest = &w;
    parts += (parts.empty() ? "" : ", ") + w.what + " " + number_text(w.count);
  }
  if (!caps.huge && largest && !(total <= kMaxPeriodicWork))
    largest->section->error_at(
        largest->key,
        "the run would take about " + number_text(total) + " periodic steps (" + parts +
            "), more than the limit of " + number_text(kMaxPeriodicWork) +
            "; use a longer period or a shorter duration, or set limits.allow_huge: true");
  const double samples = duration / def.output.sample_period_s;
  if (!caps.huge && !(samples <= kMaxSamples))
    at.output.error_at("sample_period",
                       "the run would write about " + number_text(samples) +
                           " timeseries rows, more than the limit of " + number_text(kMaxSamples) +
                           "; use a longer sample_period, or set limits.allow_huge: true");
  // Physical mode takes ⌈dt / stable step⌉ substeps per step, counted in an int.
  if (field.kind == agents::FieldKind::diffusion &&
      !(field.diffusion.dt_s / diffusion_step_s(field.diffusion) <= 1e9))
    diffusion.error_at("dt",
                       "needs more than 1e+09 substeps per step (kappa too large for the grid); "
                       "use a smaller dt, fewer cells or a smaller kappa");
}

// log10 of the largest density the field can reach, before density_scaling.
double peak_density_log10(const ScenarioDef& def, const char*& key) {
  const agents::FieldDef& f = def.world.field;
  switch (f.kind) {
    case agents::FieldKind::uniform:
      key = "value";
      return std::log10(f.uniform_value);
    case agents::FieldKind::acoustic:
      // amplitude · d^-α per target, d >= min_distance.
      key = "alpha";
      return std::log10(f.amplitude * static_cast<double>(f.targets.size())) -
             f.alpha * std::log10(f.min_distance);
    case agents::FieldKind::gaussian: {
      key = "bumps";
      double sum = 0.0;
      for (const auto& b : f.bumps)
        sum += b.amplitude;
      return std::log10(sum);
    }
    case agents::FieldKind::diffusion: {
      // At most what the sources inject over the run (rate · s), on one node.
      key = "sources";
      double sum = 0.0;
      for (const auto& s : f.sources)
        sum += s.amplitude;
      return sum > 0.0 ? std::log10(sum * std::max(def.duration_s, 1.0)) : 0.0;
    }
  }
  return 0.0;
}

void check_density(const ScenarioDef& def, LimitSections& at) {
  const char* key = "kind";
  const double peak = peak_density_log10(def, key);
  if (!(peak <= kMaxDensityLog10)) {
    at.field.error_at(
        key, "the density could reach 1e" + number_text(peak) +
                 " (amplitude over min_distance^alpha for acoustic fields), past the limit of 1e" +
                 number_text(kMaxDensityLog10) +
                 "; use a smaller amplitude or alpha, or a larger "
                 "min_distance");
    return;
  }
  const protocols::DensityScaling& sk = def.world.scaling;
  if (sk.kind == protocols::ScalingKind::power && peak > 0.0 &&
      !(peak * sk.gamma <= kMaxDensityLog10))
    at.scaling.error_at("gamma", "the scaled density could reach 1e" +
                                     number_text(peak * sk.gamma) + " (the peak density 1e" +
                                     number_text(peak) +
                                     " to the power gamma), past the limit of 1e" +
                                     number_text(kMaxDensityLog10) + "; use a smaller gamma");
}

}  // namespace

void check_limits(const ScenarioDef& def, std::size_t sensor_count, const NodeCaps& caps,
                  LimitSections& at) {
  check_work(def, sensor_count, caps, at);
  check_density(def, at);
}

}  // namespace masnet::scenarios
