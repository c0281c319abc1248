// The map of the radio energy each node spent (every run with nodes.csv), and the figures of runs
// with faults or batteries (docs/outputs.md): nodes up over time, and the run beside its
// fault-free twin, with the faults' times.
#include <algorithm>
#include <cmath>
#include <utility>

#include <cairo.h>
#include <fmt/format.h>

#include "scenarios/report/figure_parts.hpp"
#include "scenarios/report/figures.hpp"

namespace masnet::scenarios::figure_parts {
namespace {

using nlohmann::json;
using plot::Axes;
using plot::Box;
using plot::Marker;
using plot::Placement;
using plot::Point;
using plot::Rgb;
using plot::Style;

constexpr Rgb kStrike{0.84, 0.15, 0.16};
constexpr Rgb kLift{0.17, 0.63, 0.17};
constexpr Rgb kRobot{0.08, 0.36, 0.90};
constexpr Rgb kWhite{1, 1, 1};
constexpr std::size_t kMaxCrosses = 2000;

// The scripted faults' strike and lift times (NaN: never lifted), from summary.json's `recovery`.
std::vector<std::pair<double, double>> fault_times(const RunData& run) {
  std::vector<std::pair<double, double>> out;
  const json recovery = run.summary.value("recovery", json::array());
  if (!recovery.is_array()) return out;
  for (const json& f : recovery) {
    const json at = f.value("at_s", json()), until = f.value("until_s", json());
    if (!at.is_number()) continue;
    out.emplace_back(at.get<double>(), until.is_number() ? until.get<double>() : kNaN);
  }
  return out;
}

// Axes over the run's time with y from `lo` to `hi`, and a vertical line at each fault's strike
// (red, dashed) and lift (green, dashed).
Axes fault_time_axes(cairo_t* cr, Box box, const RunData& run, double lo, double hi) {
  Axes axes(cr, box);
  axes.x_range(0.0, run.duration_s > 0 ? run.duration_s : 1.0).y_range(lo, hi);
  return axes;
}

void mark_faults(Axes& axes, const RunData& run, double lo, double hi) {
  bool struck = false, lifted = false;
  for (const auto& [at, until] : fault_times(run)) {
    if (at > run.duration_s) continue;
    axes.line({at, at}, {lo, hi}, Style{kStrike, 1.3, true}, struck ? "" : "fault strikes");
    struck = true;
    if (std::isfinite(until) && until <= run.duration_s) {
      axes.line({until, until}, {lo, hi}, Style{kLift, 1.3, true}, lifted ? "" : "fault lifted");
      lifted = true;
    }
  }
}

// [lo, hi] of the series padded, from zero when `from_zero`.
std::pair<double, double> fitted(const std::vector<const std::vector<double>*>& series,
                                 bool from_zero) {
  auto [lo, hi] = plot::data_range(series, 0.06);
  if (from_zero) lo = std::min(0.0, lo);
  return {lo, hi};
}

// One panel of the run's curve (solid) and its twin's (grey, dashed), faults marked.
void twin_panel(cairo_t* cr, Box box, const RunData& run, const std::string& column,
                const std::string& y_label, const std::string& what, bool bottom) {
  const Table& ts = run.timeseries;
  const auto& t = column_or_empty(ts, "t_s");
  const auto& own = column_or_empty(ts, column);
  const auto& twin = column_or_empty(ts, column + "_twin");
  const auto [lo, hi] = fitted({&own, &twin}, true);
  Axes axes = fault_time_axes(cr, box, run, lo, hi);
  axes.decorate(bottom ? "t (s)" : "", y_label);
  mark_faults(axes, run, lo, hi);
  axes.line(t, twin, Style{kGrey, 2.0, true}, what + ", fault-free twin");
  axes.line(t, own, Style{plot::categorical(0), 2.0}, what + ", with faults");
  axes.legend(Placement::top_right);
  if (!bottom) axes.title(run.name + ": the run beside its fault-free twin");
}

}  // namespace

bool has_energy_map(const RunData& run) {
  const Table& nodes = run.nodes;
  return nodes.rows() > 0 && nodes.has("x") && nodes.has("y") && nodes.has("role") &&
         nodes.has("energy_j");
}

void draw_energy_map(cairo_t* cr, const RunData& run) {
  const Table& nodes = run.nodes;
  std::vector<Point> sensors, dead_sensors, robots, dead_robots;
  std::vector<double> energy;
  if (has_energy_map(run)) {
    const auto &x = nodes.column("x"), &y = nodes.column("y"), &e = nodes.column("energy_j");
    const auto& alive = column_or_empty(nodes, "alive");
    const auto& role = nodes.text("role");
    for (std::size_t i = 0; i < nodes.rows(); ++i) {
      const bool down = i < alive.size() && alive[i] == 0;
      if (role[i] == "robot") {
        (down ? dead_robots : robots).push_back({x[i], y[i]});
      } else {
        sensors.push_back({x[i], y[i]});
        energy.push_back(e[i]);
        if (down) dead_sensors.push_back({x[i], y[i]});
      }
    }
  }
  plot::ColourScale colours;
  const auto [lo, hi] = plot::data_range({&energy}, 0.0);
  // Many sensors down: blank cells rather than a cross each (a million crosses is no figure).
  const bool blank_dead = dead_sensors.size() > kMaxCrosses;
  // Nodes go down only in runs with faults or batteries; elsewhere "down (0)" would be noise.
  const bool down_entries =
      run.summary.contains("lifetime") || !dead_sensors.empty() || !dead_robots.empty();
  if (blank_dead)
    for (std::size_t i = 0, k = 0; i < nodes.rows(); ++i)
      if (nodes.text("role")[i] != "robot") {
        if (nodes.column("alive")[i] == 0) energy[k] = kNaN;
        ++k;
      }
  colours.lo = std::min(lo, 0.0);
  colours.hi = hi > colours.lo ? hi : colours.lo + 1.0;
  Axes axes = map_axes(cr, run);
  axes.clip();
  clip_to_domain(cr, axes, run.domain);
  axes.heat_map(sensor_raster(sensors, energy, run.domain), colours);
  axes.unclip();
  axes.decorate("x (world units)", "y (world units)");
  axes.polygon(run.domain, Style{kBlack, 1.2});
  axes.clip();
  if (blank_dead)
    axes.add_legend_entry(fmt::format("sensor down at the end ({}): blank", dead_sensors.size()),
                          Style{kGrey, 1.0});
  else
    axes.markers(
        dead_sensors, Marker::cross, 6, kBlack, kBlack,
        down_entries ? fmt::format("sensor down at the end ({})", dead_sensors.size()) : "");
  axes.markers(robots, Marker::dot, 10, kRobot, kWhite, fmt::format("robot ({})", robots.size()));
  axes.markers(dead_robots, Marker::dot, 10, kGrey, kWhite, "");
  axes.markers(dead_robots, Marker::cross, 12, kStrike, kStrike,
               down_entries ? fmt::format("robot down at the end ({})", dead_robots.size()) : "");
  axes.unclip();
  axes.legend(Placement::below);
  axes.title(fmt::format("{}: radio energy per sensor at t = {} s", run.name,
                         snapshot_time_label(run.duration_s)));
  const Box f = axes.frame();
  plot::colour_bar(cr, {f.x + f.w + 22, f.y, 16, f.h}, colours, "radio energy per sensor (J)");
}

void draw_alive_nodes(cairo_t* cr, const RunData& run) {
  const Table& ts = run.timeseries;
  const auto& t = column_or_empty(ts, "t_s");
  const auto& sensors = column_or_empty(ts, "alive_sensors");
  const auto& robots = column_or_empty(ts, "alive_robots");
  const double n_sensors = run.summary["scenario"].value("sensors", 0.0);
  const double n_robots = run.summary["scenario"].value("robots", 0.0);
  auto top_of = [](const std::vector<double>& v, double n) {
    double top = n;
    for (double x : v)
      if (std::isfinite(x)) top = std::max(top, x);
    return top > 0 ? top * 1.06 : 1.0;
  };
  const double s_hi = top_of(sensors, n_sensors), r_hi = top_of(robots, n_robots);
  Axes top = fault_time_axes(cr, {90, 45, 640, 210}, run, 0.0, s_hi);
  top.decorate("", "sensors up");
  mark_faults(top, run, 0.0, s_hi);
  top.steps(t, sensors, Style{plot::categorical(0), 2.0}, "sensors up");
  top.legend(Placement::bottom_left);
  top.title(run.name + ": nodes up over time");
  Axes bottom = fault_time_axes(cr, {90, 300, 640, 210}, run, 0.0, r_hi);
  bottom.decorate("t (s)", "robots up");
  mark_faults(bottom, run, 0.0, r_hi);
  bottom.steps(t, robots, Style{plot::categorical(1), 2.0}, "robots up");
  bottom.legend(Placement::bottom_left);
}

void draw_twin_comparison(cairo_t* cr, const RunData& run) {
  twin_panel(cr, {90, 45, 640, 210}, run, "coverage_cost", "coverage cost H", "H", false);
  if (run.timeseries.has("tracking_error_mean_twin"))
    twin_panel(cr, {90, 300, 640, 210}, run, "tracking_error_mean",
               "mean distance to nearest robot", "tracking error", true);
  else
    twin_panel(cr, {90, 300, 640, 210}, run, "cell_correctness_recent",
               "correct updates since last sample", "cell correctness", true);
}

}  // namespace masnet::scenarios::figure_parts
