// The figures that follow the run over time: coverage cost, tracking, pollution, radii, messages,
// energy, cell correctness and collisions (docs/outputs.md).
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include <cairo.h>
#include <fmt/format.h>

#include "scenarios/report/figure_parts.hpp"
#include "scenarios/report/figures.hpp"

namespace masnet::scenarios::figure_parts {
namespace {

using nlohmann::json;
using plot::Align;
using plot::Axes;
using plot::Box;
using plot::Marker;
using plot::Placement;
using plot::Point;
using plot::Rgb;
using plot::Scale;
using plot::Style;

}  // namespace

Axes time_axes(cairo_t* cr, Box box, const RunData& run,
               const std::vector<const std::vector<double>*>& series, Scale y_scale,
               bool from_zero) {
  Axes axes(cr, box);
  auto [lo, hi] =
      plot::data_range(series, y_scale == Scale::log ? 0.05 : 0.06, y_scale == Scale::log);
  if (from_zero && y_scale == Scale::linear) lo = std::min(0.0, lo + (hi - lo) * 0.06 / 1.12);
  axes.x_range(0.0, run.duration_s > 0 ? run.duration_s : 1.0).y_range(lo, hi, y_scale);
  return axes;
}

void draw_coverage(cairo_t* cr, const RunData& run) {
  const Table& ts = run.timeseries;
  const auto& t = column_or_empty(ts, "t_s");
  const auto& cost = column_or_empty(ts, "coverage_cost");
  Axes top = time_axes(cr, {90, 45, 640, 210}, run, {&cost});
  top.decorate("", "coverage cost H");
  top.line(t, cost, Style{plot::categorical(0), 2.0}, "H = Σ SK(ρ)·A·‖s − p‖²");
  top.legend(Placement::top_right);
  top.title(run.name + ": coverage cost and distance to the centroid");
  const auto& mean = column_or_empty(ts, "mean_dist_to_centroid");
  const auto& max = column_or_empty(ts, "max_dist_to_centroid");
  Axes bottom = time_axes(cr, {90, 300, 640, 210}, run, {&mean, &max}, Scale::linear, true);
  bottom.decorate("t (s)", "‖p_i − c_i‖ (world units)");
  bottom.line(t, max, Style{plot::categorical(3), 1.5}, "max over robots");
  bottom.line(t, mean, Style{plot::categorical(0), 2.0}, "mean over robots");
  bottom.legend(Placement::top_right);
}

void draw_tracking(cairo_t* cr, const RunData& run) {
  const Table& ts = run.timeseries;
  const auto& t = ts.column("t_s");
  const auto& mean = ts.column("tracking_error_mean");
  const auto& max = column_or_empty(ts, "tracking_error_max");
  Axes top = time_axes(cr, {90, 45, 640, 210}, run, {&mean, &max}, Scale::linear, true);
  top.decorate("", "distance to nearest robot (world units)");
  top.line(t, max, Style{plot::categorical(3), 1.5}, "max over targets");
  top.line(t, mean, Style{plot::categorical(0), 2.0}, "mean over targets");
  top.legend(Placement::top_right);
  top.title(run.name + ": tracking error and robots per target");
  std::vector<std::string> groups;
  for (const std::string& name : ts.names())
    if (name.rfind("robots_target_", 0) == 0) groups.push_back(name);
  std::vector<const std::vector<double>*> series;
  for (const std::string& g : groups)
    series.push_back(&ts.column(g));
  Axes bottom = time_axes(cr, {90, 300, 640, 210}, run, series, Scale::linear, true);
  bottom.decorate("t (s)", "robots in the target's group");
  for (std::size_t k = 0; k < groups.size(); ++k)
    bottom.steps(t, ts.column(groups[k]), Style{plot::categorical(k), 2.0},
                 fmt::format("target {}", k));
  bottom.legend(Placement::bottom_right);
}

void draw_pollution(cairo_t* cr, const RunData& run) {
  const Table& ts = run.timeseries;
  const auto& t = ts.column("t_s");
  const auto& with = ts.column("pollution_total");
  const auto& without = column_or_empty(ts, "pollution_total_baseline");
  Axes axes = time_axes(cr, {90, 45, 640, 400}, run, {&with, &without}, Scale::linear, true);
  {
    // Headroom for the legend above both curves.
    auto [lo, hi] = plot::data_range({&with, &without}, 0.0);
    axes.y_range(std::min(lo, 0.0), hi + 0.3 * (hi - std::min(lo, 0.0)));
  }
  axes.decorate("t (s)", "total pollution Σ u at the sensors");
  if (!without.empty())
    axes.line(t, without, Style{kGrey, 2.0, true}, "without control (baseline)");
  axes.line(t, with, Style{plot::categorical(3), 2.2}, "with control");
  // The peak and final/peak of the controlled run (paper Fig. 6: 36 %).
  std::size_t peak = 0;
  for (std::size_t i = 0; i < with.size(); ++i)
    if (std::isfinite(with[i]) && with[i] > with[peak]) peak = i;
  std::string title = run.name + ": total pollution";
  if (!with.empty() && with[peak] > 0) {
    axes.markers({{t[peak], with[peak]}}, Marker::dot, 8, plot::categorical(3), kBlack, "peak");
    title +=
        fmt::format(" (with control: final/peak = {:.0f} %)", 100.0 * with.back() / with[peak]);
  }
  axes.legend(Placement::top_right);
  axes.title(title);
}

void draw_radius(cairo_t* cr, const RunData& run) {
  const Table& tr = run.trajectories;
  std::vector<std::vector<double>> ts, rs;
  if (tr.has("radius") && tr.has("t_s"))
    for (const auto& [robot, rows] : rows_by_robot(tr)) {
      ts.emplace_back();
      rs.emplace_back();
      for (std::size_t i : rows) {
        ts.back().push_back(tr.column("t_s")[i]);
        rs.back().push_back(tr.column("radius")[i]);
      }
    }
  const auto& t = column_or_empty(run.timeseries, "t_s");
  const auto& mean = column_or_empty(run.timeseries, "mean_radius");
  std::vector<const std::vector<double>*> series{&mean};
  for (const auto& r : rs)
    series.push_back(&r);
  Axes axes = time_axes(cr, {90, 45, 640, 400}, run, series, Scale::linear, true);
  axes.decorate("t (s)", "radius R (world units)");
  for (std::size_t k = 0; k < rs.size(); ++k)
    axes.line(ts[k], rs[k], Style{plot::categorical(k), 1.0, false, 0.7},
              k == 0 ? "R_i of each robot" : "");
  axes.line(t, mean, Style{kBlack, 2.4}, "mean R");
  axes.legend(Placement::top_right);
  axes.title(run.name + ": communication radius R_i");
}

void draw_messages(cairo_t* cr, const RunData& run) {
  // Left: cumulative transmissions over time, by type from updates.csv when it exists.
  const Table& up = run.updates;
  std::vector<std::string> types;
  std::vector<std::vector<double>> cum_t, cum_n;
  if (up.rows() > 0 && up.has("t_end_s")) {
    const auto& t_end = up.column("t_end_s");
    std::vector<std::size_t> order(up.rows());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return t_end[a] < t_end[b]; });
    for (const std::string& name : up.names()) {
      if (name.size() <= 6 || name.compare(name.size() - 6, 6, "_count") != 0) continue;
      // Cumulative counts on a grid of 400 times: enough for the plot, small in the SVG.
      const auto& counts = up.column(name);
      constexpr std::size_t kPoints = 400;
      const double end = run.duration_s > 0 ? run.duration_s : 1.0;
      std::vector<double> xs, ys;
      double sum = 0;
      std::size_t next = 0;
      for (std::size_t k = 0; k <= kPoints; ++k) {
        const double t = end * static_cast<double>(k) / kPoints;
        for (; next < order.size() && !(t_end[order[next]] > t); ++next)
          if (counts[order[next]] > 0) sum += counts[order[next]];
        xs.push_back(t);
        ys.push_back(sum);
      }
      for (; next < order.size(); ++next)
        if (counts[order[next]] > 0) sum += counts[order[next]];
      ys.back() = sum;
      if (sum <= 0) continue;
      types.push_back(name.substr(0, name.size() - 6));
      cum_t.push_back(std::move(xs));
      cum_n.push_back(std::move(ys));
    }
  }
  const auto& t = column_or_empty(run.timeseries, "t_s");
  const auto& total = column_or_empty(run.timeseries, "messages");
  std::vector<const std::vector<double>*> series{&total};
  for (const auto& c : cum_n)
    series.push_back(&c);
  Axes left = time_axes(cr, {90, 70, 470, 300}, run, series, Scale::log);
  left.decorate("t (s)", "messages sent, cumulative (log scale)");
  for (std::size_t k = 0; k < types.size(); ++k)
    left.line(cum_t[k], cum_n[k], Style{plot::categorical(k), 1.6}, types[k] + " (in updates)");
  left.line(t, total, Style{kBlack, 1.6, true}, "all transmissions");
  left.legend(Placement::bottom_right);
  left.title("transmissions over time");

  // Right: totals by type from summary.json.
  std::vector<std::string> names;
  std::vector<double> counts;
  const json by_type = run.summary.contains("messages")
                           ? run.summary["messages"].value("by_type", json::object())
                           : json::object();
  for (const auto& [name, v] : by_type.items()) {
    names.push_back(name);
    counts.push_back(v.value("count", 0.0));
  }
  Axes right(cr, {660, 70, 320, 300});
  const auto [lo, hi] = plot::data_range({&counts}, 0.0, true);
  (void)lo;
  right.x_range(-0.6, static_cast<double>(std::max<std::size_t>(names.size(), 1)) - 0.4)
      .y_range(0.5, std::max(hi * 4, 10.0), Scale::log);
  right.set_categories(names);
  right.decorate("message type", "messages sent, total (log scale)");
  right.bars(counts, plot::categorical(0));
  right.title("totals by type");
  plot::text(cr, 500, 26, run.name + ": messages", 15, Align::centre, Align::end, true);
}

void draw_energy(cairo_t* cr, const RunData& run) {
  const auto& t = column_or_empty(run.timeseries, "t_s");
  const auto& energy = column_or_empty(run.timeseries, "energy_j");
  Axes left = time_axes(cr, {90, 70, 470, 300}, run, {&energy}, Scale::linear, true);
  left.decorate("t (s)", "radio energy, all nodes (J)");
  left.line(t, energy, Style{plot::categorical(3), 2.0}, "cumulative energy");
  left.legend(Placement::top_left);
  left.title("energy over time");

  // Right: histogram of the energy each node spent, sensors and robots apart.
  std::vector<double> sensors, robots;
  if (run.nodes.has("energy_j") && run.nodes.has("role")) {
    const auto& e = run.nodes.column("energy_j");
    const auto& role = run.nodes.text("role");
    for (std::size_t i = 0; i < e.size() && i < role.size(); ++i)
      (role[i] == "robot" ? robots : sensors).push_back(e[i]);
  }
  double top = 0;
  for (double v : sensors)
    top = std::max(top, v);
  for (double v : robots)
    top = std::max(top, v);
  if (!(top > 0)) top = 1;
  constexpr std::size_t kBins = 30;
  std::vector<double> edges(kBins + 1), n_sensors(kBins, 0), n_robots(kBins, 0);
  for (std::size_t i = 0; i <= kBins; ++i)
    edges[i] = top * static_cast<double>(i) / kBins;
  auto bin = [&](double v) {
    return std::min(kBins - 1, static_cast<std::size_t>(std::max(0.0, v / top * kBins)));
  };
  for (double v : sensors)
    n_sensors[bin(v)] += 1;
  for (double v : robots)
    n_robots[bin(v)] += 1;
  double most = 1;
  for (std::size_t i = 0; i < kBins; ++i)
    most = std::max({most, n_sensors[i], n_robots[i]});
  Axes right(cr, {660, 70, 320, 300});
  right.x_range(0, top * 1.02).y_range(0, most * 1.08);
  right.decorate("energy per node (J)", "nodes");
  right.histogram(edges, n_sensors, plot::categorical(0), 0.8,
                  fmt::format("sensors ({})", sensors.size()));
  right.histogram(edges, n_robots, plot::categorical(1), 0.85,
                  fmt::format("robots ({})", robots.size()));
  right.legend(Placement::top_right);
  right.title("energy per node");
  plot::text(cr, 500, 26, run.name + ": radio energy", 15, Align::centre, Align::end, true);
}

void draw_correctness(cairo_t* cr, const RunData& run) {
  const auto& t = column_or_empty(run.timeseries, "t_s");
  const auto& share = column_or_empty(run.timeseries, "cell_correctness");
  // Per sample period, from updates.csv: the share of the updates finished in it that found
  // the oracle's neighbour set.
  std::vector<double> window(t.size(), kNaN);
  if (run.updates.rows() > 0 && run.updates.has("t_end_s") && run.updates.has("correct") &&
      !t.empty()) {
    std::vector<double> n(t.size(), 0), ok(t.size(), 0);
    const auto& t_end = run.updates.column("t_end_s");
    const auto& correct = run.updates.column("correct");
    for (std::size_t i = 0; i < t_end.size(); ++i) {
      const std::size_t k = std::min<std::size_t>(
          static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), t_end[i]) - t.begin()),
          t.size() - 1);
      n[k] += 1;
      ok[k] += correct[i] > 0 ? 1 : 0;
    }
    for (std::size_t k = 0; k < t.size(); ++k)
      if (n[k] > 0) window[k] = ok[k] / n[k];
  }
  Axes axes(cr, {90, 45, 640, 400});
  axes.x_range(0, run.duration_s > 0 ? run.duration_s : 1.0).y_range(0, 1.05);
  axes.decorate("t (s)", "updates with the true neighbour set (share)");
  axes.line(t, window, Style{plot::categorical(0), 1.2, false, 0.8}, "per sample period");
  axes.line(t, share, Style{kBlack, 2.2}, "all updates so far");
  axes.legend(Placement::bottom_right);
  axes.title(run.name + ": cell correctness against the oracle");
}

void draw_collisions(cairo_t* cr, const RunData& run) {
  const auto& t = column_or_empty(run.timeseries, "t_s");
  const auto& collisions = column_or_empty(run.timeseries, "collisions");
  Axes top = time_axes(cr, {90, 45, 640, 210}, run, {&collisions}, Scale::linear, true);
  top.decorate("", "receptions lost to overlap");
  top.line(t, collisions, Style{plot::categorical(4), 2.0}, "collisions so far");
  top.legend(Placement::bottom_right);
  top.title(run.name + ": collisions over time");
  // The rate over each sample period: bursts show where the cumulative curve only bends.
  std::vector<double> rate_per_s(t.size(), kNaN);
  for (std::size_t k = 1; k < t.size() && k < collisions.size(); ++k)
    if (t[k] > t[k - 1]) rate_per_s[k] = (collisions[k] - collisions[k - 1]) / (t[k] - t[k - 1]);
  Axes bottom = time_axes(cr, {90, 300, 640, 210}, run, {&rate_per_s}, Scale::linear, true);
  bottom.decorate("t (s)", "collisions per second");
  bottom.line(t, rate_per_s, Style{plot::categorical(0), 1.5}, "per sample period");
  bottom.legend(Placement::top_right);
}

}  // namespace masnet::scenarios::figure_parts
