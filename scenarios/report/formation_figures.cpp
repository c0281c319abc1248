// The figures of robot groups (docs/formations.md): each group in its leader's cell at the
// snapshot times, and the formation error and distances over time.
#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "scenarios/report/figure_parts.hpp"
#include "scenarios/report/figures.hpp"

namespace masnet::scenarios::figure_parts {

using nlohmann::json;
using plot::Axes;
using plot::Marker;
using plot::Placement;
using plot::Point;
using plot::Style;

bool has_formation(const RunData& run) {
  return run.formation.rows() > 0 && run.followers.has("group") && run.followers.has("x");
}

void draw_formation_groups(cairo_t* cr, const RunData& run, const json& snap) {
  Axes axes = map_axes(cr, run);
  axes.decorate("x (world units)", "y (world units)");
  axes.polygon(run.domain, Style{kBlack, 1.2});
  axes.clip();
  const double t = snap.value("t", 0.0);
  std::vector<Point> leaders;
  for (const json& robot : snap.value("robots", json::array())) {
    const std::size_t g = leaders.size();
    leaders.push_back(point(robot.at("position")));
    const std::vector<Point> cell = points(robot.value("cell", json::array()));
    if (cell.size() >= 3) {
      axes.filled_polygon(cell, plot::categorical(g), 0.10);
      axes.polygon(cell, Style{plot::categorical(g), 1.2});
    }
  }
  // The followers' rows nearest to the snapshot's time (their own period may differ).
  const Table& f = run.followers;
  const auto& ts = f.column("t_s");
  double nearest = std::numeric_limits<double>::infinity();
  for (double row_t : ts)
    if (std::abs(row_t - t) < std::abs(nearest - t)) nearest = row_t;
  const auto &group = f.column("group"), &x = f.column("x"), &y = f.column("y");
  const auto& slot_x = column_or_empty(f, "slot_x");
  const auto& slot_y = column_or_empty(f, "slot_y");
  for (std::size_t i = 0; i < f.rows(); ++i) {
    if (ts[i] != nearest) continue;
    const auto g = static_cast<std::size_t>(group[i]);
    const plot::Rgb colour = plot::categorical(g);
    if (g < leaders.size())  // the group's shape: a line from the leader to each follower
      axes.line({leaders[g].x, x[i]}, {leaders[g].y, y[i]}, Style{colour, 1.0});
    if (i < slot_x.size()) axes.markers({{slot_x[i], slot_y[i]}}, Marker::cross, 6, colour, colour);
    axes.markers({{x[i], y[i]}}, Marker::dot, 6, plot::Rgb{1, 1, 1}, colour);
  }
  for (std::size_t g = 0; g < leaders.size(); ++g)
    axes.markers({leaders[g]}, Marker::dot, 9, plot::categorical(g), kBlack);
  axes.unclip();
  axes.add_legend_entry("leader", Style{kBlack, 0}, Marker::dot);
  axes.add_legend_entry("follower (○) and its slot (×)", Style{plot::categorical(0), 1.0});
  axes.add_legend_entry("leader's cell", Style{plot::categorical(1), 1.2});
  axes.legend(Placement::below);
  axes.title(fmt::format("{}: groups at t = {} s", run.name, snapshot_time_label(t)));
}

void draw_formation_curves(cairo_t* cr, const RunData& run) {
  const Table& fm = run.formation;
  const auto& t = fm.column("t_s");
  const auto& mean = column_or_empty(fm, "error_mean");
  const auto& max = column_or_empty(fm, "error_max");
  Axes top = time_axes(cr, {90, 45, 640, 210}, run, {&mean, &max}, plot::Scale::linear, true);
  top.decorate("", "follower to slot (world units)");
  top.line(t, max, Style{plot::categorical(3), 1.5}, "max over followers");
  top.line(t, mean, Style{plot::categorical(0), 2.0}, "mean over followers");
  top.legend(Placement::top_right);
  top.title(run.name + ": formation error and distances");
  const auto& between = column_or_empty(fm, "min_between_groups");
  const auto& within = column_or_empty(fm, "min_within_group");
  const auto& outside = column_or_empty(fm, "outside_follower_max");
  Axes bottom = time_axes(cr, {90, 300, 640, 210}, run, {&between, &within, &outside},
                          plot::Scale::linear, true);
  bottom.decorate("t (s)", "distance (world units)");
  bottom.line(t, between, Style{plot::categorical(2), 2.0}, "nearest robots of two groups");
  bottom.line(t, within, Style{plot::categorical(4), 1.5}, "nearest robots of one group");
  bottom.line(t, outside, Style{plot::categorical(3), 1.5}, "farthest follower outside its cell");
  bottom.legend(Placement::top_right);
}

}  // namespace masnet::scenarios::figure_parts
