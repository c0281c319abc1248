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

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Reserved stroke colours (see snapshot_svg_classes): nothing else is stroked with them, and
// legend samples use near neighbours so that they are not counted as cells.
constexpr Rgb kCellStroke{0.02, 0.02, 0.02};
constexpr Rgb kCellLegend{0.05, 0.05, 0.05};
constexpr Rgb kOracleStroke{0.16, 0.44, 0.88};
constexpr Rgb kOracleLegend{0.16, 0.44, 0.86};
constexpr Rgb kRobotFill{0.08, 0.36, 0.90};
constexpr Rgb kWhite{1, 1, 1};
constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGrey{0.45, 0.45, 0.45};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::optional<double> parse_number(const std::string& s) {
  if (s.empty()) return std::nullopt;
  double v = 0;
  const char* first = s.data();
  if (*first == '+') ++first;
  const auto [end, ec] = std::from_chars(first, s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read '" + path.string() + "'");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::runtime_error("'" + path.string() + "' is not valid JSON: " + e.what());
  }
}

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
  constexpr std::size_t kPixels = 160;
  r.nx = r.ny = kPixels;
  r.x0 = b.x0;
  r.y0 = b.y0;
  r.x1 = b.x1;
  r.y1 = b.y1;
  r.values.assign(kPixels * kPixels, kNaN);
  for (std::size_t j = 0; j < kPixels; ++j)
    for (std::size_t i = 0; i < kPixels; ++i) {
      const double x = b.x0 + (static_cast<double>(i) + 0.5) / kPixels * (b.x1 - b.x0);
      const double y = b.y0 + (static_cast<double>(j) + 0.5) / kPixels * (b.y1 - b.y0);
      double best = 1e300;
      for (std::size_t s = 0; s < sensors.size(); ++s) {
        const double d =
            (sensors[s].x - x) * (sensors[s].x - x) + (sensors[s].y - y) * (sensors[s].y - y);
        if (d < best) {
          best = d;
          r.values[j * kPixels + i] = values[s];
        }
      }
    }
  return r;
}

// A map of Ω: equal aspect, a small margin around the domain.
Axes map_axes(cairo_t* cr, Box box, const RunData& run) {
  const Bounds b = bounds(run.domain);
  const double mx = 0.02 * (b.x1 - b.x0), my = 0.02 * (b.y1 - b.y0);
  Axes axes(cr, box);
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

// One snapshot: the sensor readings as a heat map, cells, robots, centroids, targets.
// `field_only`: the diffusion field map (robots and sources, no cells).
void draw_snapshot(cairo_t* cr, const RunData& run, const json& snap,
                   const plot::ColourScale& colours, const FigureOptions& options,
                   bool field_only) {
  Axes axes = map_axes(cr, {70, 50, 470, 470}, run);
  const double t = snap.value("t", 0.0);
  std::vector<double> readings;
  for (const json& v : snap.value("readings", json::array()))
    readings.push_back(v.is_number() ? v.get<double>() : kNaN);

  // Field maps show the PDE grid when the snapshot has it, else (like the cell figures) what
  // the sensors read.
  const plot::Raster pde = field_only ? pde_raster(snap) : plot::Raster{};
  const bool on_grid = !pde.values.empty();
  axes.clip();
  clip_to_domain(cr, axes, run.domain);
  axes.heat_map(on_grid ? pde : sensor_raster(run.sensors, readings, run.domain), colours);
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

// Rows of trajectories.csv grouped by robot.
std::map<std::size_t, std::vector<std::size_t>> rows_by_robot(const Table& t) {
  std::map<std::size_t, std::vector<std::size_t>> out;
  if (!t.has("robot")) return out;
  const std::vector<double>& robot = t.column("robot");
  for (std::size_t i = 0; i < robot.size(); ++i)
    if (std::isfinite(robot[i])) out[static_cast<std::size_t>(robot[i])].push_back(i);
  return out;
}

void draw_trajectories(cairo_t* cr, const RunData& run) {
  Axes axes = map_axes(cr, {70, 50, 470, 470}, run);
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

// Axes over the run's time with y fitted to `series`.
Axes time_axes(cairo_t* cr, Box box, const RunData& run,
               const std::vector<const std::vector<double>*>& series, Scale y_scale = Scale::linear,
               bool from_zero = false) {
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
  bottom.decorate("t (s)", "robots nearest to the target");
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

}  // namespace

// ---------------------------------------------------------------------------------------------
// Reading a run directory

Table Table::read(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read '" + path.string() + "'");
  Table t;
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("'" + path.string() + "' is empty");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  t.names_ = split(line);
  const std::size_t n = t.names_.size();
  t.numbers_.resize(n);
  t.text_.resize(n);
  std::vector<bool> textual(n, false);
  for (std::size_t row = 2; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> cells = split(line);
    if (cells.size() != n)
      throw std::runtime_error(
          fmt::format("{}:{}: {} fields, the header has {}", path.string(), row, cells.size(), n));
    for (std::size_t c = 0; c < n; ++c) {
      const std::optional<double> v = parse_number(cells[c]);
      t.numbers_[c].push_back(v ? *v : kNaN);
      if (!v && !cells[c].empty()) textual[c] = true;
      t.text_[c].push_back(std::move(cells[c]));
    }
  }
  // Keep the text only where it says more than the numbers.
  for (std::size_t c = 0; c < n; ++c)
    if (!textual[c]) std::vector<std::string>().swap(t.text_[c]);
  return t;
}

std::size_t Table::index(std::string_view name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return i;
  return names_.size();
}

bool Table::has(std::string_view name) const {
  return index(name) < names_.size();
}

const std::vector<double>& Table::column(std::string_view name) const {
  const std::size_t i = index(name);
  if (i == names_.size()) throw std::out_of_range("no column '" + std::string(name) + "'");
  return numbers_[i];
}

const std::vector<std::string>& Table::text(std::string_view name) const {
  const std::size_t i = index(name);
  if (i == names_.size()) throw std::out_of_range("no column '" + std::string(name) + "'");
  return text_[i];
}

RunData load_run_data(const fs::path& dir) {
  RunData run;
  run.dir = dir;
  if (!fs::is_directory(dir)) throw std::runtime_error("'" + dir.string() + "' is not a directory");
  run.summary = read_json(dir / "summary.json");
  run.timeseries = Table::read(dir / "timeseries.csv");
  run.trajectories = Table::read(dir / "trajectories.csv");
  run.nodes = Table::read(dir / "nodes.csv");
  if (fs::exists(dir / "updates.csv")) run.updates = Table::read(dir / "updates.csv");
  run.snapshots =
      fs::exists(dir / "snapshots.json") ? read_json(dir / "snapshots.json") : json::array();
  if (!run.snapshots.is_array())
    throw std::runtime_error("'" + (dir / "snapshots.json").string() + "' is not a list");

  try {
    const json& scenario = run.summary.at("scenario");
    run.name = scenario.value("name", std::string("run"));
    const json& resolved = scenario.value("resolved", json::object());
    run.field_kind =
        resolved.contains("field") ? resolved["field"].value("kind", std::string()) : std::string();
    run.duration_s = run.summary.value("sim_time_s", resolved.value("duration", 0.0));
    const json domain = resolved.value("domain", json::object());
    if (domain.contains("polygon") && domain["polygon"].is_array() &&
        domain["polygon"].size() >= 3) {
      run.domain = points(domain["polygon"]);
    } else if (domain.contains("rectangle") && domain["rectangle"].size() == 4) {
      const json& r = domain["rectangle"];
      const double x0 = r[0], y0 = r[1], x1 = r[2], y1 = r[3];
      run.domain = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    } else {
      run.domain = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    }
  } catch (const json::exception& e) {
    throw std::runtime_error("'" + (dir / "summary.json").string() +
                             "': bad scenario section: " + e.what());
  }

  if (fs::exists(dir / "sensors.csv")) {
    const Table sensors = Table::read(dir / "sensors.csv");
    const auto &x = sensors.column("x"), &y = sensors.column("y");
    for (std::size_t i = 0; i < x.size(); ++i)
      run.sensors.push_back({x[i], y[i]});
  } else if (run.nodes.has("role") && run.nodes.has("index")) {
    const auto& role = run.nodes.text("role");
    const auto &index = run.nodes.column("index"), &x = run.nodes.column("x"),
               &y = run.nodes.column("y");
    std::vector<std::pair<double, Point>> rows;
    for (std::size_t i = 0; i < role.size(); ++i)
      if (role[i] == "sensor") rows.push_back({index[i], {x[i], y[i]}});
    std::stable_sort(rows.begin(), rows.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& r : rows)
      run.sensors.push_back(r.second);
  }
  return run;
}

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
        680, 600, [&](cairo_t* cr) { draw_snapshot(cr, run, snap, colours, options, false); },
        snapshot_svg_classes());
    if (is_diffusion(run))
      add({"field_t" + label, "field",
           fmt::format("The pollution field u{} with the robots and sources at t = {} s.",
                       pde_maps ? " on the PDE grid" : " at the sensors", label),
           t},
          680, 600, [&](cairo_t* cr) {
            draw_snapshot(cr, run, snap, pde_maps ? field_colours : colours, options, true);
          });
  }
  add({"trajectories", "trajectories",
       fmt::format(
           "Robot paths over the whole run and the {} paths (bold) with their direction of motion.",
           source_word(run))},
      680, 600, [&](cairo_t* cr) { draw_trajectories(cr, run); });
  add({"coverage_cost", "curve",
       "Coverage cost H and the robots' distance to their true cell centroids over time."},
      760, 560, [&](cairo_t* cr) { draw_coverage(cr, run); });
  if (run.timeseries.has("tracking_error_mean"))
    add({"tracking", "curve",
         "Tracking error (distance from each target to its nearest robot) and robots per target."},
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
  return figures;
}

}  // namespace masnet::scenarios
