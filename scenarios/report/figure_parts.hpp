#pragma once
// Shared by the figure files only (figures.cpp draws the maps, figure_curves.cpp the curves
// over time): colours, small readers of the run's data, and the curve figures.
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/report/plot/plot.hpp"
#include "scenarios/report/run_data.hpp"

namespace masnet::scenarios::figure_parts {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr plot::Rgb kBlack{0, 0, 0};
inline constexpr plot::Rgb kGrey{0.45, 0.45, 0.45};

/// A point written as [x, y].
plot::Point point(const nlohmann::json& j);
/// A list of such points (none when `j` is not an array).
std::vector<plot::Point> points(const nlohmann::json& j);
/// The column `name`, or no values when the table lacks it.
const std::vector<double>& column_or_empty(const Table& t, std::string_view name);
/// Rows of trajectories.csv grouped by robot.
std::map<std::size_t, std::vector<std::size_t>> rows_by_robot(const Table& t);

// Maps of Ω (figures.cpp).
/// Sensor values as a raster: one cell per sensor for grid layouts, else each pixel of a
/// raster of square pixels over Ω's bounding box, 160 along its long side, takes its nearest
/// sensor's value.
plot::Raster sensor_raster(const std::vector<plot::Point>& sensors,
                           const std::vector<double>& values,
                           const std::vector<plot::Point>& domain);
/// The box of a map's axes: Ω's aspect ratio with the long side 470 px (a unit square gets
/// 470 × 470), no narrower than 360 px nor lower than 160 px so that the title, legend and
/// colour bar keep their room (a longer Ω is drawn smaller inside it).
plot::Box map_box(const RunData& run);
/// Width and height of a map figure: the box, the axis labels left of it, the title above, the
/// colour bar right of it and `below_px` under it for the x label and the legend.
std::pair<double, double> map_figure_size(const RunData& run, double below_px);
/// Axes over Ω in map_box with equal aspect and a small margin.
plot::Axes map_axes(cairo_t* cr, const RunData& run);
/// Clips to Ω (inside an Axes::clip).
void clip_to_domain(cairo_t* cr, const plot::Axes& axes, const std::vector<plot::Point>& domain);

// The pollution field as a 3-D surface (surface_figures.cpp).
/// Width of the surface panel, left of the field map, in a pollution surface figure.
inline constexpr double kSurfacePanelPx = 600;
/// The least height of a pollution surface figure (a wide Ω's map is lower than that).
inline constexpr double kSurfaceMinHeightPx = 520;
/// The field `heights` (cell centres as the surface's nodes) at `t_s` as a surface in the left
/// panel, kSurfacePanelPx × `height_px`: z from 0 to this snapshot's peak, coloured by
/// `colours` (the field maps' scale); then `draw_map` translated right of it.
void draw_pollution_surface(cairo_t* cr, const RunData& run, double t_s,
                            const plot::Raster& heights, const plot::ColourScale& colours,
                            double height_px, const std::function<void(cairo_t*)>& draw_map);

// Energy, faults and lifetime (fault_figures.cpp): the energy map for every run with nodes.csv,
// the others for runs whose summary.json has `lifetime`.
/// Whether nodes.csv has the nodes' positions, roles and energy, and at least one node.
bool has_energy_map(const RunData& run);
/// Sensors coloured by their radio energy, robots marked, nodes down at the end crossed.
void draw_energy_map(cairo_t* cr, const RunData& run);
/// Sensors and robots up over time, the faults' times marked.
void draw_alive_nodes(cairo_t* cr, const RunData& run);
/// Coverage cost and tracking error (or cell correctness) beside the fault-free twin's.
void draw_twin_comparison(cairo_t* cr, const RunData& run);

// The curves over time (figure_curves.cpp).
/// Axes over the run's time with y fitted to `series` (from 0 when `from_zero`).
plot::Axes time_axes(cairo_t* cr, plot::Box box, const RunData& run,
                     const std::vector<const std::vector<double>*>& series,
                     plot::Scale y_scale = plot::Scale::linear, bool from_zero = false);
void draw_coverage(cairo_t* cr, const RunData& run);
void draw_tracking(cairo_t* cr, const RunData& run);
void draw_pollution(cairo_t* cr, const RunData& run);
void draw_radius(cairo_t* cr, const RunData& run);
void draw_messages(cairo_t* cr, const RunData& run);
void draw_energy(cairo_t* cr, const RunData& run);
void draw_correctness(cairo_t* cr, const RunData& run);
/// Runs whose timeseries.csv has a `collisions` column (radio levels collision and csma).
void draw_collisions(cairo_t* cr, const RunData& run);

// Robot groups (formation_figures.cpp), for runs with formation.csv and followers.csv.
bool has_formation(const RunData& run);
/// Leaders' cells, leaders, followers and their slots at the snapshot `snap`.
void draw_formation_groups(cairo_t* cr, const RunData& run, const nlohmann::json& snap);
/// Formation error, and the distances between and within groups, over time.
void draw_formation_curves(cairo_t* cr, const RunData& run);

}  // namespace masnet::scenarios::figure_parts
