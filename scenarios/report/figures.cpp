#include "scenarios/report/figures.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>

#include <cairo.h>
#include <fmt/compile.h>
#include <fmt/format.h>

#include "scenarios/output/output_file.hpp"
#include "scenarios/report/fault_tables.hpp"
#include "scenarios/report/figure_parts.hpp"
#include "scenarios/report/target_paths.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;
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
using namespace figure_parts;

namespace figure_parts {

Point point(const json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>()};
}

std::vector<Point> points(const json& j) {
  std::vector<Point> out;
  if (j.is_array())
    for (const json& p : j)
      out.push_back(point(p));
  return out;
}

const std::vector<double>& column_or_empty(const Table& t, std::string_view name) {
  static const std::vector<double> kEmpty;
  return t.has(name) ? t.column(name) : kEmpty;
}

// Rows of trajectories.csv grouped by robot.
std::map<std::size_t, std::vector<std::size_t>> rows_by_robot(const Table& t) {
  std::map<std::size_t, std::vector<std::size_t>> out;
  if (!t.has("robot")) return out;
  const std::vector<double>& robot = t.column("robot");
  for (std::size_t i = 0; i < robot.size(); ++i)
    if (std::isfinite(robot[i])) out[static_cast<std::size_t>(robot[i])].push_back(i);
  return out;
}

}  // namespace figure_parts

namespace {

// Reserved stroke colours (see snapshot_svg_classes): nothing else is stroked with them, and
// legend samples use near neighbours so that they are not counted as cells.
constexpr Rgb kCellStroke{0.02, 0.02, 0.02};
constexpr Rgb kCellLegend{0.05, 0.05, 0.05};
constexpr Rgb kOracleStroke{0.16, 0.44, 0.88};
constexpr Rgb kOracleLegend{0.16, 0.44, 0.86};
constexpr Rgb kRobotFill{0.08, 0.36, 0.90};
constexpr Rgb kWhite{1, 1, 1};

// Domain bounding box.
struct Bounds {
  double x0, y0, x1, y1;
};
Bounds bounds(const std::vector<Point>& polygon) {
  Bounds b{1e300, 1e300, -1e300, -1e300};
  for (const Point& p : polygon) {
    b.x0 = std::min(b.x0, p.x);
    b.y0 = std::min(b.y0, p.y);
    b.x1 = std::max(b.x1, p.x);
    b.y1 = std::max(b.y1, p.y);
  }
  if (!(b.x1 > b.x0) || !(b.y1 > b.y0)) return {0, 0, 1, 1};
  return b;
}

// Sorted distinct values (within a relative tolerance).
std::vector<double> distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > 1e-9 * (1.0 + std::abs(x))) out.push_back(x);
  return out;
}

std::size_t nearest_index(const std::vector<double>& sorted, double x) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), x);
  std::size_t i = static_cast<std::size_t>(it - sorted.begin());
  if (i == sorted.size()) return i - 1;
  if (i > 0 && x - sorted[i - 1] < sorted[i] - x) --i;
  return i;
}

}  // namespace

namespace figure_parts {

// Sensor values as a raster: one cell per sensor for grid layouts; otherwise each pixel of a
// 160 × 160 raster over Ω's bounding box takes its nearest sensor's value.
plot::Raster sensor_raster(const std::vector<Point>& sensors, const std::vector<double>& values,
                           const std::vector<Point>& domain) {
  plot::Raster r;
  if (sensors.empty() || sensors.size() != values.size()) return r;
  std::vector<double> xs, ys;
  for (const Point& p : sensors) {
    xs.push_back(p.x);
    ys.push_back(p.y);
  }
  const std::vector<double> ux = distinct(xs), uy = distinct(ys);
  const Bounds b = bounds(domain);
  if (ux.size() * uy.size() == sensors.size()) {
    r.nx = ux.size();
    r.ny = uy.size();
    r.values.assign(r.nx * r.ny, kNaN);
    bool full = true;
    for (std::size_t s = 0; s < sensors.size(); ++s) {
      double& cell = r.values[nearest_index(uy, ys[s]) * r.nx + nearest_index(ux, xs[s])];
      full = full && std::isnan(cell);
      cell = values[s];
    }
    if (full) {
      const double hx =
          r.nx > 1 ? (ux.back() - ux.front()) / static_cast<double>(r.nx - 1) : b.x1 - b.x0;
      const double hy =
          r.ny > 1 ? (uy.back() - uy.front()) / static_cast<double>(r.ny - 1) : b.y1 - b.y0;
      r.x0 = ux.front() - hx / 2;
      r.x1 = ux.back() + hx / 2;
      r.y0 = uy.front() - hy / 2;
      r.y1 = uy.back() + hy / 2;
      return r;
    }
  }
  constexpr double kLongPixels = 160;
  const double aspect = (b.x1 - b.x0) / (b.y1 - b.y0);
  r.nx = static_cast<std::size_t>(aspect >= 1 ? kLongPixels
                                              : std::max(1.0, std::round(kLongPixels * aspect)));
  r.ny = static_cast<std::size_t>(aspect >= 1 ? std::max(1.0, std::round(kLongPixels / aspect))
                                              : kLongPixels);
  r.x0 = b.x0;
  r.y0 = b.y0;
  r.x1 = b.x1;
  r.y1 = b.y1;
  r.values.assign(r.nx * r.ny, kNaN);
  const double nx = static_cast<double>(r.nx), ny = static_cast<double>(r.ny);
  for (std::size_t j = 0; j < r.ny; ++j)
    for (std::size_t i = 0; i < r.nx; ++i) {
      const double x = b.x0 + (static_cast<double>(i) + 0.5) / nx * (b.x1 - b.x0);
      const double y = b.y0 + (static_cast<double>(j) + 0.5) / ny * (b.y1 - b.y0);
      double best = 1e300;
      for (std::size_t s = 0; s < sensors.size(); ++s) {
        const double d =
            (sensors[s].x - x) * (sensors[s].x - x) + (sensors[s].y - y) * (sensors[s].y - y);
        if (d < best) {
          best = d;
          r.values[j * r.nx + i] = values[s];
        }
      }
    }
  return r;
}

// The margins of a map figure around its box (the unit square's figure is 680 × 600 px).
constexpr double kMapLongPx = 470, kMapLeftPx = 70, kMapTopPx = 50, kMapRightPx = 140;
constexpr double kMapMinWidthPx = 360, kMapMinHeightPx = 160;

Box map_box(const RunData& run) {
  const Bounds b = bounds(run.domain);
  const double aspect = (b.x1 - b.x0) / (b.y1 - b.y0);
  // Whole pixels, so that the PNG is exactly as large as the SVG and PDF say.
  const double w = aspect >= 1 ? kMapLongPx : std::round(kMapLongPx * aspect);
  const double h = aspect >= 1 ? std::round(kMapLongPx / aspect) : kMapLongPx;
  return {kMapLeftPx, kMapTopPx, std::max(w, kMapMinWidthPx), std::max(h, kMapMinHeightPx)};
}

std::pair<double, double> map_figure_size(const RunData& run, double below_px) {
  const Box box = map_box(run);
  return {box.x + box.w + kMapRightPx, box.y + box.h + below_px};
}

// A map of Ω: equal aspect, a small margin around the domain.
Axes map_axes(cairo_t* cr, const RunData& run) {
  const Bounds b = bounds(run.domain);
  const double mx = 0.02 * (b.x1 - b.x0), my = 0.02 * (b.y1 - b.y0);
  Axes axes(cr, map_box(run));
  axes.x_range(b.x0 - mx, b.x1 + mx).y_range(b.y0 - my, b.y1 + my).equal_aspect();
  return axes;
}

// Clips to Ω (inside an Axes::clip).
void clip_to_domain(cairo_t* cr, const Axes& axes, const std::vector<Point>& domain) {
  if (domain.size() < 3) return;
  cairo_move_to(cr, axes.px(domain[0].x), axes.py(domain[0].y));
  for (std::size_t i = 1; i < domain.size(); ++i)
    cairo_line_to(cr, axes.px(domain[i].x), axes.py(domain[i].y));
  cairo_close_path(cr);
  cairo_clip(cr);
}

}  // namespace figure_parts

namespace {

bool is_diffusion(const RunData& run) {
  return run.field_kind == "diffusion";
}
std::string source_word(const RunData& run) {
  return is_diffusion(run) ? "source" : "target";
}

// The PDE grid of a diffusion snapshot ("field": nodes (x0 + i·hx, y0 + j·hy), row-major,
// boundary nodes included) as a raster of cells centred on the nodes; empty when absent.
plot::Raster pde_raster(const json& snap) {
  plot::Raster r;
  if (!snap.contains("field") || !snap["field"].is_object()) return r;
  const json& f = snap["field"];
  try {
    const std::size_t nx = f.at("nx").get<std::size_t>(), ny = f.at("ny").get<std::size_t>();
    const json& values = f.at("values");
    if (nx < 2 || ny < 2 || values.size() != nx * ny) return r;
    const double x0 = f.at("x0"), y0 = f.at("y0"), x1 = f.at("x1"), y1 = f.at("y1");
    const double hx = (x1 - x0) / static_cast<double>(nx - 1),
                 hy = (y1 - y0) / static_cast<double>(ny - 1);
    r.nx = nx;
    r.ny = ny;
    r.x0 = x0 - hx / 2;
    r.x1 = x1 + hx / 2;
    r.y0 = y0 - hy / 2;
    r.y1 = y1 + hy / 2;
    for (const json& v : values)
      r.values.push_back(v.is_number() ? v.get<double>() : kNaN);
  } catch (const json::exception&) {
    return {};
  }
  return r;
}

// The colour scale shared by all snapshot figures of a run, so that the slider compares like
// with like: logarithmic for acoustic fields (ρ falls as a power of distance), else linear.
// `pde`: over the PDE grids of the snapshots (field maps) instead of the sensor readings.
plot::ColourScale snapshot_colours(const RunData& run, bool pde) {
  std::vector<double> all;
  for (const json& s : run.snapshots) {
    if (pde) {
      const plot::Raster r = pde_raster(s);
      all.insert(all.end(), r.values.begin(), r.values.end());
    } else if (s.contains("readings")) {
      for (const json& v : s["readings"])
        if (v.is_number()) all.push_back(v.get<double>());
    }
  }
  plot::ColourScale c;
  if (run.field_kind == "acoustic") {
    c.scale = Scale::log;
    const auto [lo, hi] = plot::data_range({&all}, 0.0, true);
    c.lo = lo;
    c.hi = hi;
  } else {
    const auto [lo, hi] = plot::data_range({&all}, 0.0, false);
    c.lo = std::min(lo, 0.0);
    c.hi = hi > c.lo ? hi : c.lo + 1.0;
    // A constant positive field (uniform density) shows a light colour, not the darkest.
    const auto [min, max] = std::minmax_element(all.begin(), all.end());
    if (!all.empty() && *max > 0 && *max - *min <= 1e-12 * *max) c.hi = 3.0 * *max;
  }
  return c;
}

std::string colour_label(const RunData& run, const plot::ColourScale& c, bool pde) {
  const std::string what = pde                 ? "pollution u on the PDE grid"
                           : is_diffusion(run) ? "pollution u at the sensors"
                                               : "density ρ at the sensors";
  return c.scale == Scale::log ? what + " (log scale)" : what;
}

// What the sensors read at a snapshot, as a raster.
plot::Raster readings_raster(const RunData& run, const json& snap) {
  std::vector<double> readings;
  for (const json& v : snap.value("readings", json::array()))
    readings.push_back(v.is_number() ? v.get<double>() : kNaN);
  return sensor_raster(run.sensors, readings, run.domain);
}

// The field of a diffusion snapshot: the PDE grid when the snapshot has it, else (like the
// cell figures) what the sensors read.
plot::Raster field_raster(const RunData& run, const json& snap) {
  plot::Raster pde = pde_raster(snap);
  return pde.values.empty() ? readings_raster(run, snap) : pde;
}

// One snapshot: the sensor readings as a heat map, cells, robots, centroids, targets.
// `field_only`: the diffusion field map (robots and sources, no cells).
void draw_snapshot(cairo_t* cr, const RunData& run, const json& snap,
                   const plot::ColourScale& colours, const FigureOptions& options,
                   bool field_only) {
  Axes axes = map_axes(cr, run);
  const double t = snap.value("t", 0.0);
  const bool on_grid = field_only && !pde_raster(snap).values.empty();
  axes.clip();
  clip_to_domain(cr, axes, run.domain);
  axes.heat_map(field_only ? field_raster(run, snap) : readings_raster(run, snap), colours);
  axes.unclip();
  axes.decorate("x (world units)", "y (world units)");
  axes.polygon(run.domain, Style{kBlack, 1.2});

  const json robots = snap.value("robots", json::array());
  axes.clip();
  if (!field_only) {
    // The oracle's cells over the robots' own: where they agree, dashes run along the line.
    for (const json& r : robots)
      axes.polygon(points(r.value("cell", json::array())), Style{kCellStroke, 1.8});
    if (options.oracle_cells)
      for (const json& r : robots)
        axes.polygon(points(r.value("oracle_cell", json::array())),
                     Style{kOracleStroke, 1.0, true});
    if (options.radius_circles)
      for (const json& r : robots)
        axes.circle(point(r.at("position")), r.value("radius", 0.0), Style{kGrey, 0.8, true, 0.8});
  }
  // Targets or sources, with an arrow along their direction of motion.
  const Bounds b = bounds(run.domain);
  const double arrow_len = 0.08 * std::max(b.x1 - b.x0, b.y1 - b.y0);
  std::vector<Point> sources;
  for (const json& s : snap.value("sources", json::array())) {
    const Point p = point(s.at("position"));
    const Point h = s.contains("heading") ? point(s["heading"]) : Point{};
    sources.push_back(p);
    if (std::hypot(h.x, h.y) > 0)
      axes.arrow(p, {p.x + h.x * arrow_len, p.y + h.y * arrow_len}, Style{kBlack, 2.2}, 10);
  }
  axes.markers(sources, Marker::diamond, 13, {0.3, 0.9, 0.4}, kBlack,
               source_word(run) + " → motion");
  std::vector<Point> robot_points, centroids;
  for (const json& r : robots) {
    robot_points.push_back(point(r.at("position")));
    if (r.contains("target")) centroids.push_back(point(r["target"]));
  }
  if (!field_only) axes.markers(centroids, Marker::cross, 9, kBlack, kBlack, "centroid");
  axes.markers(robot_points, Marker::dot, 10, kRobotFill, kWhite, "robot");
  axes.unclip();
  if (!field_only) {
    axes.add_legend_entry("cell (robot's)", Style{kCellLegend, 1.8});
    if (options.oracle_cells) axes.add_legend_entry("oracle cell", Style{kOracleLegend, 1.0, true});
    if (options.radius_circles) axes.add_legend_entry("radius R_i", Style{kGrey, 0.8, true});
  }
  axes.legend(Placement::below);
  const std::string when = snapshot_time_label(t);
  axes.title(field_only ? fmt::format("{}: pollution field at t = {} s", run.name, when)
                        : fmt::format("{}: Voronoi cells at t = {} s", run.name, when));
  const Box f = axes.frame();
  plot::colour_bar(cr, {f.x + f.w + 22, f.y, 16, f.h}, colours,
                   colour_label(run, colours, on_grid));
}

// The paths of the targets/sources over the run, sampled 200 times; from the resolved
// scenario, or else through their positions at the snapshot times.
std::vector<std::vector<Point>> source_paths(const RunData& run) {
  std::vector<std::vector<Point>> paths;
  const json& field = run.summary["scenario"]["resolved"]["field"];
  for (const char* key : {"targets", "sources", "bumps"}) {
    if (!field.contains(key) || !field[key].is_array()) continue;
    for (const json& item : field[key]) {
      const std::optional<TargetPath> def = target_path_from_json(item);
      if (!def) continue;
      std::vector<Point> path;
      constexpr int kSamples = 200;
      for (int k = 0; k <= kSamples; ++k)
        path.push_back(position_on(*def, run.duration_s * k / kSamples));
      paths.push_back(std::move(path));
    }
  }
  if (!paths.empty()) return paths;
  for (const json& s : run.snapshots) {
    const json sources = s.value("sources", json::array());
    if (paths.size() < sources.size()) paths.resize(sources.size());
    for (std::size_t k = 0; k < sources.size(); ++k)
      paths[k].push_back(point(sources[k].at("position")));
  }
  return paths;
}

void draw_trajectories(cairo_t* cr, const RunData& run) {
  Axes axes = map_axes(cr, run);
  axes.decorate("x (world units)", "y (world units)");
  axes.polygon(run.domain, Style{kBlack, 1.2});
  axes.clip();
  const Table& tr = run.trajectories;
  if (tr.has("x") && tr.has("y")) {
    const std::vector<double>&x = tr.column("x"), &y = tr.column("y");
    for (const auto& [robot, rows] : rows_by_robot(tr)) {
      std::vector<double> xs, ys;
      for (std::size_t i : rows) {
        xs.push_back(x[i]);
        ys.push_back(y[i]);
      }
      const Rgb c = plot::categorical(robot);
      axes.line(xs, ys, Style{c, 1.4});
      if (xs.empty()) continue;
      axes.markers({{xs.front(), ys.front()}}, Marker::dot, 7, kWhite, c);
      // An arrowhead at the end, along the last stretch of visible length.
      std::size_t k = xs.size() - 1;
      while (k > 0 && std::hypot(axes.px(xs.back()) - axes.px(xs[k]),
                                 axes.py(ys.back()) - axes.py(ys[k])) < 6)
        --k;
      if (k + 1 < xs.size()) axes.arrow({xs[k], ys[k]}, {xs.back(), ys.back()}, Style{c, 1.4}, 8);
      axes.markers({{xs.back(), ys.back()}}, Marker::dot, 6, c, c);
    }
  }
  for (const std::vector<Point>& path : source_paths(run)) {
    std::vector<double> xs, ys;
    for (const Point& p : path) {
      xs.push_back(p.x);
      ys.push_back(p.y);
    }
    axes.line(xs, ys, Style{kBlack, 3.5});
    if (path.size() < 2) continue;
    axes.markers({path.front()}, Marker::diamond, 11, {0.3, 0.9, 0.4}, kBlack);
    for (std::size_t at : {path.size() / 2, path.size() - 1})
      if (at > 0) axes.arrow(path[at - 1], path[at], Style{kBlack, 3.5}, 14);
  }
  axes.unclip();
  axes.add_legend_entry("robot path (○ start, ● end)", Style{plot::categorical(0), 1.4});
  axes.add_legend_entry(source_word(run) + " path (◆ start)", Style{kBlack, 3.5});
  axes.legend(Placement::below);
  axes.title(fmt::format("{}: trajectories, t = 0 to {} s", run.name,
                         snapshot_time_label(run.duration_s)));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Writing the figures

std::string snapshot_time_label(double t_s) {
  std::string s = fmt::format("{:.3f}", t_s);
  while (s.size() > 1 && s.back() == '0' && s[s.size() - 2] != '.')
    s.pop_back();
  return s == "-0.0" ? "0.0" : s;
}

const std::vector<plot::SvgClass>& snapshot_svg_classes() {
  static const std::vector<plot::SvgClass> kClasses{{kCellStroke, "cell"},
                                                    {kOracleStroke, "oracle-cell"}};
  return kClasses;
}

std::vector<FigureInfo> write_figures(const RunData& run, const fs::path& figures_dir,
                                      const FigureOptions& options) {
  fs::remove_all(figures_dir);
  fs::create_directories(figures_dir);
  std::vector<FigureInfo> figures;
  auto add = [&](FigureInfo info, double w, double h, const std::function<void(cairo_t*)>& draw,
                 const std::vector<plot::SvgClass>& classes = {}) {
    plot::write_figure(write_file, figures_dir / info.stem, w, h, draw, classes);
    figures.push_back(std::move(info));
  };

  // Maps take Ω's aspect ratio; the curves keep their sizes.
  const auto [map_w, map_h] = map_figure_size(run, 80);
  const plot::ColourScale colours = snapshot_colours(run, false);
  const bool pde_maps = std::any_of(run.snapshots.begin(), run.snapshots.end(),
                                    [](const json& s) { return !pde_raster(s).values.empty(); });
  const plot::ColourScale field_colours = pde_maps ? snapshot_colours(run, true) : colours;
  for (const json& snap : run.snapshots) {
    const double t = snap.value("t", 0.0);
    const std::string label = snapshot_time_label(t);
    add(
        {"snapshot_t" + label, "snapshot",
         fmt::format(
             "Sensor readings, the robots' Voronoi cells{}, robots, centroids and {}s at t = {} s.",
             options.oracle_cells ? " (oracle's dashed)" : "", source_word(run), label),
         t},
        map_w, map_h, [&](cairo_t* cr) { draw_snapshot(cr, run, snap, colours, options, false); },
        snapshot_svg_classes());
    if (!is_diffusion(run)) continue;
    const plot::ColourScale& map_colours = pde_maps ? field_colours : colours;
    auto draw_field = [&](cairo_t* cr) {
      draw_snapshot(cr, run, snap, map_colours, options, true);
    };
    add({"field_t" + label, "field",
         fmt::format("The pollution field u{} with the robots and sources at t = {} s.",
                     pde_maps ? " on the PDE grid" : " at the sensors", label),
         t},
        map_w, map_h, draw_field);
    add({"pollution_surface_t" + label, "surface",
         fmt::format("The pollution field u as a surface over Ω (z up to this snapshot's peak, "
                     "colours as in the field map) beside the field map at t = {} s.",
                     label),
         t},
        kSurfacePanelPx + map_w, std::max(map_h, kSurfaceMinHeightPx), [&](cairo_t* cr) {
          draw_pollution_surface(cr, run, t, field_raster(run, snap), map_colours,
                                 std::max(map_h, kSurfaceMinHeightPx), draw_field);
        });
  }
  if (has_formation(run))
    for (const json& snap : run.snapshots) {
      const double t = snap.value("t", 0.0);
      add({"groups_t" + snapshot_time_label(t), "groups",
           fmt::format("Robot groups at t = {} s: each leader's cell, the leader, its followers "
                       "and their slots.",
                       snapshot_time_label(t)),
           t},
          map_w, map_h, [&](cairo_t* cr) { draw_formation_groups(cr, run, snap); });
    }
  add({"trajectories", "trajectories",
       fmt::format(
           "Robot paths over the whole run and the {} paths (bold) with their direction of motion.",
           source_word(run))},
      map_w, map_h, [&](cairo_t* cr) { draw_trajectories(cr, run); });
  add({"coverage_cost", "curve",
       "Coverage cost H and the robots' distance to their true cell centroids over time."},
      760, 560, [&](cairo_t* cr) { draw_coverage(cr, run); });
  if (run.timeseries.has("tracking_error_mean"))
    add({"tracking", "curve",
         "Tracking error (distance from each target to its nearest robot) and robots per target "
         "(robots within the tracking radius of their nearest target)."},
        760, 560, [&](cairo_t* cr) { draw_tracking(cr, run); });
  if (run.timeseries.has("pollution_total"))
    add({"pollution", "curve",
         "Total pollution (sum of the sensor readings) with and without control."},
        760, 500, [&](cairo_t* cr) { draw_pollution(cr, run); });
  add({"radius", "curve", "The mean communication radius R and each robot's R_i over time."}, 760,
      500, [&](cairo_t* cr) { draw_radius(cr, run); });
  add({"messages", "curve",
       "Cumulative transmissions by message type over time, and totals by type."},
      1000, 450, [&](cairo_t* cr) { draw_messages(cr, run); });
  add({"energy", "curve",
       "Cumulative radio energy over time, and a histogram of the energy each node spent."},
      1000, 450, [&](cairo_t* cr) { draw_energy(cr, run); });
  add({"correctness", "curve",
       "Share of protocol updates whose neighbour set equals the oracle's, over time."},
      760, 500, [&](cairo_t* cr) { draw_correctness(cr, run); });
  if (has_formation(run))
    add({"formation", "curve",
         "Formation error (each follower to its slot around the leader) and the nearest robots "
         "of two groups and of one group over time."},
        760, 560, [&](cairo_t* cr) { draw_formation_curves(cr, run); });
  if (run.timeseries.has("collisions"))
    add({"collisions", "curve",
         "Receptions lost to overlapping frames: so far, and per second of each sample period."},
        760, 560, [&](cairo_t* cr) { draw_collisions(cr, run); });
  // Every run with nodes.csv; kind "fault" where the report has a lifetime section, which then
  // shows it with the other figures of faults and batteries.
  if (has_energy_map(run)) {
    const auto [energy_w, energy_h] = map_figure_size(run, 120);
    const bool faults = has_lifetime_section(run.summary);
    add({"energy_map", faults ? "fault" : "map",
         faults ? "Radio energy each sensor spent, the robots, and the nodes down at the end "
                  "(crossed)."
                : "Radio energy each sensor spent over the run, and the robots at the end."},
        energy_w, energy_h, [&](cairo_t* cr) { draw_energy_map(cr, run); });
  }
  // Runs with faults or batteries (kind "fault": the report shows them with the lifetime).
  if (run.timeseries.has("alive_sensors"))
    add({"alive_nodes", "fault", "Sensors and robots up over time, with the faults' times."}, 760,
        560, [&](cairo_t* cr) { draw_alive_nodes(cr, run); });
  if (run.timeseries.has("coverage_cost_twin"))
    add({"twin_comparison", "fault",
         "Coverage cost and tracking error (or cell correctness) of the run and of its fault-free "
         "twin, with the faults' times."},
        760, 560, [&](cairo_t* cr) { draw_twin_comparison(cr, run); });
  return figures;
}

}  // namespace masnet::scenarios
